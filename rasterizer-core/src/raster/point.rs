//! Single pixels.

use crate::target::Surface;
use embedded_graphics_core::geometry::Point;

/// Draws one pixel; a point outside the surface's clip area is dropped.
pub fn draw_point<S: Surface>(surface: &mut S, p: Point, color: S::Color) -> Result<(), S::Error> {
    if surface.clip_area().contains(p) {
        surface.fill_span(p.x, p.y, 1, color)?;
    }
    Ok(())
}
