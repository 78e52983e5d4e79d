//! Lines with integer Bresenham, in every octant, both endpoints included: [`crate::geom::line`]
//! defines which pixels a line lights, [`crate::clip::line`] which of them a clip area keeps, and
//! this module draws them: opaque, translucent ([`draw_line_alpha`]) or anti-aliased
//! ([`draw_line_aa`], and any width with [`draw_line_aa_wide`]).

mod aa;
mod alpha;
mod gradient;
mod wide;

pub use aa::draw_line_aa;
pub use alpha::draw_line_alpha;
pub use gradient::draw_line_gradient;
pub use wide::{draw_line_aa_wide, MAX_LINE_WIDTH};

use crate::geom::line::Line;
use crate::geom::PixelRect;
use crate::surface::Surface;
use embedded_graphics_core::geometry::Point;

/// Draws the line from `a` to `b`, both endpoints included, clipped to the surface's clip area.
///
/// Any `i32` endpoints are accepted; the pixels drawn are exactly the line's pixels that lie inside
/// the clip area.
// Inlined into the caller (a loop over many lines, mostly): the call and its register saves
// would otherwise cost a short line about as much as a few of its pixels.
#[inline]
pub fn draw_line<S: Surface>(
    surface: &mut S,
    a: Point,
    b: Point,
    color: S::Color,
) -> Result<(), S::Error> {
    let area = surface.clip_area();
    let inside = PixelRect::from_rectangle(&area);
    // Most lines lie inside the clip area: they skip the clipping and its general walk set-up.
    if inside.contains(a) && inside.contains(b) {
        return surface.draw_line_points_in_clip(Line::new(a, b).points(), color);
    }
    match Line::new(a, b).clipped(&area) {
        Some(points) => surface.draw_line_points_in_clip(points, color),
        None => Ok(()),
    }
}
