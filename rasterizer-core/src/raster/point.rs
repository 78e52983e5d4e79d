//! Single pixels.

use crate::geom::PixelRect;
use crate::surface::Surface;
use embedded_graphics_core::geometry::Point;

/// Draws one pixel; a point outside the surface's clip area is dropped.
pub fn draw_point<S: Surface>(surface: &mut S, p: Point, color: S::Color) -> Result<(), S::Error> {
    // In i64: embedded-graphics' `Rectangle::contains` overflows for a clip area that ends past
    // i32::MAX.
    if PixelRect::from_rectangle(&surface.clip_area()).contains(p) {
        surface.fill_span(p.x, p.y, 1, color)?;
    }
    Ok(())
}
