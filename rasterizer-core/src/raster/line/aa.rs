//! Anti-aliased lines (Xiaolin Wu's algorithm), exact in integers.
//!
//! At each step along the major axis the ideal line (through the endpoint pixels' centres) passes
//! between two pixel centres on the minor axis, at distance `f` from the nearer one; that pixel
//! gets coverage `1 - f` and the other `f`: the far one `round(255 f)` out of 255 (halves up),
//! the near one the rest, so each step's two coverages add up to exactly 255. Each is then
//! blended over the surface. The fraction is kept as Bresenham's remainder and the coverage as a second
//! quotient-and-remainder pair, so every step is adds and compares with no division and no drift:
//! each coverage is the exact rounding, whatever the line's length.

use super::Line;
use crate::geom::PixelRect;
use crate::surface::{BlendError, Surface};
use embedded_graphics_core::geometry::Point;

/// Draws an anti-aliased line from `a` to `b` (pixel centres), both endpoints included and drawn
/// at full coverage, blending `color` over what the surface holds, clipped to its clip area.
///
/// Any `i32` endpoints are accepted. The line is symmetric: drawn from `b` to `a` it gives the
/// same pixels. Each pixel is blended once.
///
/// ```
/// use rasterizer_core::prelude::*;
/// use rasterizer_core::raster::line::draw_line_aa;
///
/// let mut buf = [0u8; 8 * 4];
/// let mut fb = Framebuffer::<Gray8>::new(&mut buf, 8, 4).unwrap();
/// draw_line_aa(&mut fb, Point::new(0, 0), Point::new(4, 2), Gray8::WHITE).unwrap();
/// // At column 1 the line is half-way between rows 0 and 1: the half goes to the far pixel.
/// assert_eq!(fb.pixel(Point::new(1, 0)), Some(Gray8::new(127)));
/// assert_eq!(fb.pixel(Point::new(1, 1)), Some(Gray8::new(128)));
/// assert_eq!(fb.pixel(Point::new(2, 1)), Some(Gray8::WHITE));
/// ```
///
/// # Errors
/// [`BlendError::CannotReadBack`] (before anything is drawn) for a surface that cannot read back
/// its pixels, such as [`crate::surface::AnyTarget`]; [`BlendError::Target`] for the surface's own.
pub fn draw_line_aa<S: Surface>(
    surface: &mut S,
    a: Point,
    b: Point,
    color: S::Color,
) -> Result<(), BlendError<S::Error>> {
    if !S::READ_BACK {
        return Err(BlendError::CannotReadBack);
    }
    let line = Line::new(a, b);
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    // A step's two pixels lie within one pixel of Bresenham's (which rounds where they floor and
    // floor + 1), so clipping Bresenham's line to the clip area grown by one pixel across the line
    // finds every step with a pixel inside; the pixels themselves are checked one by one.
    let mut grown = clip;
    if line.major_x {
        (grown.y0, grown.y1) = (clip.y0 - 1, clip.y1 + 1);
    } else {
        (grown.x0, grown.x1) = (clip.x0 - 1, clip.x1 + 1);
    }
    if clip.is_empty() {
        return Ok(());
    }
    let Some((k0, k1)) = line.clipped_steps_in(&grown) else {
        return Ok(());
    };
    let (big_a, big_b) = (line.a, line.b);
    let s = i64::from(line.minor_step);
    let (m0, n0) = if line.major_x {
        (i64::from(line.start.x), i64::from(line.start.y))
    } else {
        (i64::from(line.start.y), i64::from(line.start.x))
    };
    // The minor offset at step k is (q + r / A) with q, r the quotient and remainder of k B / A;
    // the far pixel's coverage is c = round(255 r / A) = (510 r + A) div 2A, kept as c and its
    // remainder u. Bounds: A, B < 2^33 and r < A, so 510 r + A < 2^42 (k0 B needs i128).
    let (mut q, mut r, mut c, mut u) = (0i64, 0i64, 0i64, 0i64);
    let (dc, du) = if big_a == 0 {
        (0, 0)
    } else {
        let kb = i128::from(k0) * i128::from(big_b);
        q = (kb / i128::from(big_a)) as i64;
        r = (kb % i128::from(big_a)) as i64;
        let t = 510 * r + big_a;
        (c, u) = (t / (2 * big_a), t % (2 * big_a));
        (510 * big_b / (2 * big_a), 510 * big_b % (2 * big_a))
    };
    for k in k0..=k1 {
        let near = n0 + s * q;
        for (n, cover) in [(near, 255 - c), (near + s, c)] {
            let (x, y) = if line.major_x {
                (m0 + k, n)
            } else {
                (n, m0 + k)
            };
            let inside = (clip.x0..clip.x1).contains(&x) && (clip.y0..clip.y1).contains(&y);
            if cover > 0 && inside {
                // Inside the clip area, so both coordinates are i32.
                surface.blend_span_in_clip(x as i32, y as i32, 1, color, cover as u8)?;
            }
        }
        // One step: r += B (carrying into q), the coverage numerator by 510 B; a carry takes
        // 510 A = 255 * 2A off it, that is 255 off c with u unchanged.
        r += big_b;
        c += dc;
        u += du;
        if u >= 2 * big_a {
            u -= 2 * big_a;
            c += 1;
        }
        if r >= big_a {
            r -= big_a;
            q += 1;
            c -= 255;
        }
    }
    Ok(())
}
