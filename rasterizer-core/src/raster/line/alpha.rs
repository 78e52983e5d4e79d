//! Translucent lines: the pixels of [`super::draw_line`], each blended once with one opacity.

use super::Line;
use crate::surface::{BlendError, Surface};
use embedded_graphics_core::geometry::Point;

/// Blends the line from `a` to `b` over what the surface holds, with opacity `alpha`
/// (0 transparent ..= 255 opaque), clipped to the surface's clip area. Same pixels as
/// [`super::draw_line`]; each is blended once ([`crate::color::blend`]).
///
/// ```
/// use rasterizer_core::prelude::*;
/// use rasterizer_core::raster::line::draw_line_alpha;
///
/// let mut buf = [0u8; 8 * 4];
/// let mut fb = Framebuffer::<Gray8>::new(&mut buf, 8, 4).unwrap();
/// draw_line_alpha(&mut fb, Point::new(0, 1), Point::new(7, 1), Gray8::WHITE, 128).unwrap();
/// assert_eq!(fb.pixel(Point::new(3, 1)), Some(Gray8::new(128)));
/// ```
///
/// # Errors
/// [`BlendError::CannotReadBack`] (before anything is drawn) for a surface that cannot read back
/// its pixels, such as [`crate::surface::AnyTarget`]; [`BlendError::Target`] for the surface's own.
pub fn draw_line_alpha<S: Surface>(
    surface: &mut S,
    a: Point,
    b: Point,
    color: S::Color,
    alpha: u8,
) -> Result<(), BlendError<S::Error>> {
    if !S::READ_BACK {
        return Err(BlendError::CannotReadBack);
    }
    let Some(points) = Line::new(a, b).clipped(&surface.clip_area()) else {
        return Ok(());
    };
    for p in points {
        surface.blend_span_in_clip(p.x, p.y, 1, color, alpha)?;
    }
    Ok(())
}
