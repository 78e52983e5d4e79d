//! The 2D commands of a frame list: shapes held by value, and items drawn by reference.

use crate::color::Channels;
use crate::geom::{PixelRect, SubPoint};
use crate::raster::line::{draw_line, draw_line_aa_wide, draw_line_alpha, draw_line_gradient};
use crate::raster::polygon::{FillRule, Polygon};
use crate::raster::triangle::{
    draw_triangle, fill_triangle, fill_triangle_alpha, fill_triangle_gouraud,
};
use crate::surface::{Band, BlendError, ClipTo, Storage, Surface, Translucent};
use embedded_graphics_core::geometry::{Dimensions, Point};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Drawable;

/// A 2D shape of a frame list, drawn by the library's rasterizer of the same name. Sub-pixel
/// vertices have 4 fractional bits, as [`SubPoint`]'s default.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Shape<C> {
    /// [`draw_line`].
    Line {
        /// One end.
        a: Point,
        /// The other end.
        b: Point,
        /// Colour.
        color: C,
    },
    /// [`draw_line_gradient`].
    LineGradient {
        /// One end.
        a: Point,
        /// The other end.
        b: Point,
        /// The colours at `a` and `b`.
        colors: [C; 2],
    },
    /// [`draw_line_alpha`]: a line blended with opacity `alpha`.
    LineAlpha {
        /// One end.
        a: Point,
        /// The other end.
        b: Point,
        /// Colour.
        color: C,
        /// Opacity, 0 ..= 255.
        alpha: u8,
    },
    /// [`draw_line_aa_wide`]: an anti-aliased line `width` pixels wide (1: `draw_line_aa`).
    LineAa {
        /// One end.
        a: Point,
        /// The other end.
        b: Point,
        /// Width in pixels.
        width: u32,
        /// Colour.
        color: C,
    },
    /// [`draw_triangle`]: a triangle's outline.
    TriangleOutline {
        /// Corners.
        vertices: [Point; 3],
        /// Colour.
        color: C,
    },
    /// [`fill_triangle`], or [`fill_triangle_alpha`] when `opacity` is below 255.
    Triangle {
        /// Corners.
        vertices: [SubPoint; 3],
        /// Colour.
        color: C,
        /// Opacity, 0 ..= 255.
        opacity: u8,
    },
    /// [`fill_triangle_gouraud`], through [`Translucent`] when `opacity` is below 255.
    Gouraud {
        /// Corners.
        vertices: [SubPoint; 3],
        /// Their colours.
        colors: [C; 3],
        /// Opacity, 0 ..= 255.
        opacity: u8,
    },
}

/// The pixels a segment can touch, grown by `grow` on each side.
fn segment(a: Point, b: Point, grow: i64) -> PixelRect {
    let (ax, ay, bx, by) = (
        i64::from(a.x),
        i64::from(a.y),
        i64::from(b.x),
        i64::from(b.y),
    );
    PixelRect {
        x0: ax.min(bx) - grow,
        y0: ay.min(by) - grow,
        x1: ax.max(bx) + 1 + grow,
        y1: ay.max(by) + 1 + grow,
    }
}

/// The pixels a triangle of sub-pixel corners can cover: every pixel whose centre may lie in it.
fn corners<const BITS: u32>(v: &[SubPoint<BITS>; 3]) -> PixelRect {
    let xs = v.map(|p| i64::from(p.x));
    let ys = v.map(|p| i64::from(p.y));
    let lo = |a: [i64; 3]| a[0].min(a[1]).min(a[2]) >> BITS;
    let hi = |a: [i64; 3]| (a[0].max(a[1]).max(a[2]) >> BITS) + 1;
    PixelRect {
        x0: lo(xs),
        y0: lo(ys),
        x1: hi(xs),
        y1: hi(ys),
    }
}

impl<C: Channels> Shape<C> {
    /// The pixels the shape can draw.
    pub fn bounds(&self) -> Rectangle {
        match *self {
            Self::Line { a, b, .. }
            | Self::LineGradient { a, b, .. }
            | Self::LineAlpha { a, b, .. } => segment(a, b, 0),
            // A wide line cuts each column over w sqrt(A^2 + B^2) / A pixels
            // (`draw_line_aa_wide`), up to w sqrt 2 on a diagonal: its pixels lie within
            // w / sqrt 2 < 3w / 4 (and the anti-aliased fringe of a pixel) of the segment.
            Self::LineAa { a, b, width, .. } => segment(a, b, i64::from(width) * 3 / 4 + 2),
            Self::TriangleOutline {
                vertices: [p, q, r],
                ..
            } => segment(p, q, 0).union(&segment(q, r, 0)),
            Self::Triangle { vertices, .. } | Self::Gouraud { vertices, .. } => corners(&vertices),
        }
        .to_rectangle()
    }

    /// Draws the shape into `surface`, as the rasterizer it names would.
    ///
    /// # Errors
    /// The surface's, or [`BlendError::CannotReadBack`] for a blended shape on a surface that
    /// cannot read back.
    pub fn draw<S: Surface<Color = C>>(&self, surface: &mut S) -> Result<(), BlendError<S::Error>> {
        match *self {
            Self::Line { a, b, color } => draw_line(surface, a, b, color)?,
            Self::LineGradient { a, b, colors } => {
                draw_line_gradient(surface, a, b, colors[0], colors[1])?
            }
            Self::LineAlpha { a, b, color, alpha } => draw_line_alpha(surface, a, b, color, alpha)?,
            Self::LineAa { a, b, width, color } => draw_line_aa_wide(surface, a, b, width, color)?,
            Self::TriangleOutline { vertices, color } => draw_triangle(surface, vertices, color)?,
            Self::Triangle {
                vertices,
                color,
                opacity: 255,
            } => fill_triangle(surface, vertices, color)?,
            Self::Triangle {
                vertices,
                color,
                opacity,
            } => fill_triangle_alpha(surface, vertices, color, opacity)?,
            Self::Gouraud {
                vertices,
                colors,
                opacity: 255,
            } => fill_triangle_gouraud(surface, vertices, colors)?,
            Self::Gouraud {
                vertices,
                colors,
                opacity,
            } => fill_triangle_gouraud(&mut Translucent::new(surface, opacity), vertices, colors)?,
        }
        Ok(())
    }
}

/// Something a frame list draws by reference ([`super::FrameList::item`]): every
/// embedded-graphics `Drawable` with `Dimensions` (text, images, embedded-graphics' own
/// primitives) is one, and so is a [`PolygonFill`].
pub trait Item<C: Storage> {
    /// The pixels it can draw.
    fn bounds(&self) -> Rectangle;
    /// Draws it into a band.
    fn draw_into(&self, target: &mut ClipTo<'_, Band<'_, C>>);
}

impl<C: Storage, T: Drawable<Color = C> + Dimensions> Item<C> for T {
    fn bounds(&self) -> Rectangle {
        self.bounding_box()
    }

    fn draw_into(&self, target: &mut ClipTo<'_, Band<'_, C>>) {
        // A band cannot fail.
        let Ok(_) = self.draw(target);
    }
}

/// A polygon filled by the scanline rasterizer ([`Polygon::fill`]) as a frame-list item.
#[derive(Debug, Clone)]
pub struct PolygonFill<
    'p,
    C,
    const N: usize,
    const BITS: u32 = { crate::geom::DEFAULT_SUBPIXEL_BITS },
> {
    /// The polygon.
    pub polygon: &'p Polygon<N, BITS>,
    /// Which parts are inside.
    pub rule: FillRule,
    /// Colour.
    pub color: C,
}

impl<C: Storage, const N: usize, const BITS: u32> Item<C> for PolygonFill<'_, C, N, BITS> {
    fn bounds(&self) -> Rectangle {
        self.polygon.pixel_bounds()
    }

    fn draw_into(&self, target: &mut ClipTo<'_, Band<'_, C>>) {
        let Ok(()) = self.polygon.fill(target, self.rule, self.color);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::Framebuffer;
    use embedded_graphics_core::draw_target::DrawTarget;
    use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};

    /// A wide anti-aliased line cuts each column over `w sqrt(A^2 + B^2) / A` pixels, up to
    /// `w sqrt 2` on a diagonal: its bounds held only `w / 2` on each side, so a frame list
    /// skipped the bands of a diagonal line's outer rows (a 60-pixel line at 45 degrees lost
    /// them in every band height).
    #[test]
    fn wide_diagonal_aa_line_within_bounds() {
        let mut buf = [0u8; 160 * 160];
        let ends = [
            (20, 20),
            (20, -20),
            (-20, 20),
            (30, 10),
            (10, 30),
            (-30, -29),
            (29, -30),
            (1, 1),
            (1, 0),
            (0, 0),
            (25, 0),
            (0, -25),
        ];
        for width in 1..=60 {
            for (dx, dy) in ends {
                let mut fb = Framebuffer::<Gray8>::new(&mut buf, 160, 160).unwrap();
                fb.clear(Gray8::BLACK).unwrap();
                let (a, b) = (Point::new(80, 80), Point::new(80 + dx, 80 + dy));
                let line = Shape::LineAa {
                    a,
                    b,
                    width,
                    color: Gray8::WHITE,
                };
                line.draw(&mut fb).unwrap();
                let bounds = line.bounds();
                for y in 0..160 {
                    for x in 0..160 {
                        let p = Point::new(x, y);
                        if fb.pixel(p) != Some(Gray8::BLACK) {
                            assert!(
                                bounds.contains(p),
                                "width {width} to ({dx}, {dy}): {p:?} outside {bounds:?}"
                            );
                        }
                    }
                }
            }
        }
    }
}
