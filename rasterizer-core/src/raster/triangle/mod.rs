//! Triangles: outlines, and fills in flat or Gouraud colour.
//!
//! Fills take vertices in sub-pixel fixed point ([`SubPoint`], 28.4 by default), sample at pixel
//! centres and follow the top-left rule: a centre exactly on an edge is drawn when the triangle lies
//! below a horizontal edge or to the right of any other edge. Two triangles that share an edge
//! therefore never leave a gap between them and never draw a pixel twice, and the coverage matches
//! OpenGL's (checked against Mesa's llvmpipe in the conformance tests). Either winding is drawn.
//!
//! Spans are found by an exact edge walk (`raster/edge.rs`): one division per edge at set-up, then two adds
//! and a compare per edge per row. Zero-area triangles draw nothing; so does a triangle with a vertex
//! outside the guard band ([`crate::geom::GUARD_BAND_PIXELS`]).

mod setup;

use crate::color::Channels;
use crate::geom::{PixelRect, SubPoint};
use crate::raster::line::{draw_line, Line};
use crate::target::Surface;
use embedded_graphics_core::geometry::Point;
use embedded_graphics_core::Pixel;
use setup::{walk_spans, Sorted};

/// Fills a triangle in one colour.
///
/// ```
/// use rasterizer_core::{geom::SubPoint, raster::triangle::fill_triangle, target::Framebuffer};
/// use embedded_graphics_core::{pixelcolor::Rgb565, prelude::*};
///
/// let mut buf = [0u16; 16 * 16];
/// let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 16, 16).unwrap();
/// let px = |x, y| SubPoint::<4>::new(x * 16, y * 16);
/// fill_triangle(&mut fb, [px(0, 0), px(16, 0), px(0, 16)], Rgb565::GREEN).unwrap();
/// assert_eq!(fb.pixel(Point::new(0, 0)), Some(Rgb565::GREEN));
/// assert_eq!(fb.pixel(Point::new(15, 15)), Some(Rgb565::BLACK));
/// ```
pub fn fill_triangle<S: Surface, const BITS: u32>(
    surface: &mut S,
    vertices: [SubPoint<BITS>; 3],
    color: S::Color,
) -> Result<(), S::Error> {
    let Some(t) = Sorted::new(&vertices) else {
        return Ok(());
    };
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    walk_spans(&t, 1 << BITS, &clip, |y, x0, x1| {
        surface.fill_span(x0, y, (x1 - x0) as u32, color)
    })
}

/// Fractional bits of the interpolated colour channels.
const FRAC: u32 = 16;

/// `round(n / d)` for `d > 0`, exact; `n` may need more than 64 bits.
#[inline]
fn div_round(n: i128, d: i64) -> i64 {
    let d = i128::from(d);
    let q = n.div_euclid(d);
    let r = n.rem_euclid(d);
    (if 2 * r >= d { q + 1 } else { q }) as i64
}

/// `round(a * b / d)` for `d > 0`, in `i64` when the product fits and in `i128` when it does not.
#[inline]
fn mul_div_round(a: i64, b: i64, d: i64) -> i64 {
    match a.checked_mul(b) {
        Some(n) => {
            let q = n.div_euclid(d);
            let r = n.rem_euclid(d);
            // r < d <= 2^62, so 2 r cannot overflow.
            if 2 * r >= d {
                q + 1
            } else {
                q
            }
        }
        None => div_round(i128::from(a) * i128::from(b), d),
    }
}

/// Fills a triangle with its vertex colours interpolated across it (Gouraud shading).
///
/// Each channel is interpolated at its native depth. The value at a pixel centre is the exact
/// barycentric blend rounded to the nearest step, computed exactly at the start of each span and
/// stepped across it in 16.16 fixed point, so a pixel whose centre is a vertex gets exactly that
/// vertex's colour, and no pixel leaves the range of the three colours.
pub fn fill_triangle_gouraud<S, const BITS: u32>(
    surface: &mut S,
    vertices: [SubPoint<BITS>; 3],
    colors: [S::Color; 3],
) -> Result<(), S::Error>
where
    S: Surface,
    S::Color: Channels,
{
    let Some(t) = Sorted::new(&vertices) else {
        return Ok(());
    };
    let s: i64 = 1 << BITS;
    let c = t.order.map(|i| colors[i].to_channels());
    let [v0, v1, v2] = t.v;
    // The colour plane c(x, y) = c0 + (a (x - x0) + b (y - y0)) / cross, per channel, with the sign of
    // `cross` moved into the numerators so the divisor is positive. Bound: |a|, |b| <= 2^9 * 2M = 2^39.
    let sign = t.cross.signum();
    let den = t.cross.abs();
    let mut a = [0i64; 4];
    let mut b = [0i64; 4];
    let mut lo = [0i32; 4];
    let mut hi = [0i32; 4];
    let mut step = [0i32; 4];
    for i in 0..S::Color::COUNT {
        let (c0, c1, c2) = (i64::from(c[0][i]), i64::from(c[1][i]), i64::from(c[2][i]));
        a[i] = sign * ((c1 - c0) * (v2.1 - v0.1) - (c2 - c0) * (v1.1 - v0.1));
        b[i] = sign * ((c2 - c0) * (v1.0 - v0.0) - (c1 - c0) * (v2.0 - v0.0));
        lo[i] = (c0.min(c1).min(c2) << FRAC) as i32;
        hi[i] = (c0.max(c1).max(c2) << FRAC) as i32;
        // One pixel is `s` sub-pixel units. A step too large for i32 only ever lands on spans of one
        // pixel (two centres inside the triangle differ by at most 255), so saturating it is harmless.
        let per_pixel = mul_div_round(a[i], s << FRAC, den);
        step[i] = per_pixel.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
    }
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    walk_spans(&t, s, &clip, |y, x0, x1| {
        // Doubled pixel-centre offsets from v0: exact integers even with no sub-pixel bits.
        let dx2 = (2 * i64::from(x0) + 1) * s - 2 * v0.0;
        let dy2 = (2 * i64::from(y) + 1) * s - 2 * v0.1;
        let mut acc = [0i32; 4];
        for i in 0..S::Color::COUNT {
            let f = i128::from(a[i]) * i128::from(dx2) + i128::from(b[i]) * i128::from(dy2);
            let start = match i64::try_from(f).ok().and_then(|f| f.checked_mul(1 << FRAC)) {
                Some(n) => mul_div_round(n, 1, 2 * den),
                None => div_round(f << FRAC, 2 * den),
            };
            let base = i64::from(c[0][i]) << FRAC;
            let v = (base + start).clamp(i64::from(lo[i]), i64::from(hi[i])) as i32;
            acc[i] = v + (1 << (FRAC - 1));
        }
        surface.shade_span(x0, y, (x1 - x0) as u32, || {
            let mut ch = [0u8; 4];
            for i in 0..S::Color::COUNT {
                ch[i] = (acc[i].max(0) >> FRAC) as u8;
                acc[i] = acc[i].wrapping_add(step[i]);
            }
            S::Color::from_channels(ch)
        })
    })
}

/// Draws the outline of a triangle: its three edges as [`crate::raster::line`] lines, each pixel once.
///
/// Pixels shared by two edges (the corners, and more in a thin triangle) are drawn by the first edge
/// only, so a target that counts writes sees every outline pixel exactly once.
pub fn draw_triangle<S: Surface>(
    surface: &mut S,
    vertices: [Point; 3],
    color: S::Color,
) -> Result<(), S::Error> {
    let [p0, p1, p2] = vertices;
    let (l0, l1, l2) = (Line::new(p0, p1), Line::new(p1, p2), Line::new(p2, p0));
    draw_line(surface, p0, p1, color)?;
    let area = surface.clip_area();
    if let Some(points) = l1.clipped(&area) {
        surface.draw_iter(points.filter(|p| !l0.contains(*p)).map(|p| Pixel(p, color)))?;
    }
    if let Some(points) = l2.clipped(&area) {
        let fresh = points.filter(|p| !l0.contains(*p) && !l1.contains(*p));
        surface.draw_iter(fresh.map(|p| Pixel(p, color)))?;
    }
    Ok(())
}
