//! Anti-aliased lines of any width, integer only: [`draw_line_aa`]'s model widened.
//!
//! [`draw_line_aa`] gives each pixel of a column (a step along the major axis) the length of its
//! minor-axis extent that lies within half a pixel of the ideal line. Here the interval is the
//! line's own cross-section on that axis: a line `w` pixels wide (measured across it) cuts a
//! column over `w sqrt(A^2 + B^2) / A` pixels, centred on the ideal line, and each pixel of the
//! column gets the part of its extent inside that interval (rounded to 255ths). That is the
//! pixel's exact area coverage wherever the line's edges do not cross the pixel's corners (and
//! within a small error where they do, measured in `docs/ACCURACY.md`); the ends are cut square to
//! the major axis at the endpoint pixels' outer edges, as [`draw_line_aa`]'s are.
//!
//! The centre is kept as a 16-bit fraction with Bresenham's quotient and remainder (exact, no
//! drift), and the half cross-section is computed once with an integer square root, so every
//! coverage is within half a 255th (plus 1/100 of one) of the model's.

use super::{draw_line_aa, Line};
use crate::geom::PixelRect;
use crate::surface::{BlendError, Surface};
use embedded_graphics_core::geometry::Point;

/// Fractional bits of the line's centre and half-width.
const FRAC: u32 = 16;
/// Half a pixel in those units.
const HALF: i64 = 1 << (FRAC - 1);

/// The widest line [`draw_line_aa_wide`] draws, in pixels: wider ones are drawn this wide.
pub const MAX_LINE_WIDTH: u32 = 65_535;

/// Draws an anti-aliased line `width` pixels wide (measured across the line) from `a` to `b`
/// (pixel centres), blending `color` over what the surface holds, clipped to its clip area.
///
/// Width 1 is [`draw_line_aa`] itself (Wu's line, exactly); width 0 draws nothing; widths above
/// [`MAX_LINE_WIDTH`] are drawn that wide. Wider lines follow the coverage model of the module
/// documentation: the ends are cut square to the major axis at the endpoints' outer pixel edges,
/// and a line from a point to itself is one column of `width` pixels. Symmetric (`b` to `a` gives
/// the same pixels); each pixel is blended once.
///
/// ```
/// use rasterizer_core::prelude::*;
/// use rasterizer_core::raster::line::draw_line_aa_wide;
///
/// let mut buf = [0u8; 8 * 5];
/// let mut fb = Framebuffer::<Gray8>::new(&mut buf, 8, 5).unwrap();
/// draw_line_aa_wide(&mut fb, Point::new(0, 2), Point::new(7, 2), 2, Gray8::WHITE).unwrap();
/// // Two pixels wide, centred on row 2: rows 1 and 3 are half covered.
/// assert_eq!(fb.pixel(Point::new(3, 1)), Some(Gray8::new(128)));
/// assert_eq!(fb.pixel(Point::new(3, 2)), Some(Gray8::WHITE));
/// assert_eq!(fb.pixel(Point::new(3, 3)), Some(Gray8::new(128)));
/// ```
///
/// # Errors
/// [`BlendError::CannotReadBack`] (before anything is drawn) for a surface that cannot read back
/// its pixels, such as [`crate::surface::AnyTarget`]; [`BlendError::Target`] for the surface's own.
pub fn draw_line_aa_wide<S: Surface>(
    surface: &mut S,
    a: Point,
    b: Point,
    width: u32,
    color: S::Color,
) -> Result<(), BlendError<S::Error>> {
    if !S::READ_BACK {
        return Err(BlendError::CannotReadBack);
    }
    match width {
        0 => return Ok(()),
        1 => return draw_line_aa(surface, a, b, color),
        _ => {}
    }
    let w = i64::from(width.min(MAX_LINE_WIDTH));
    let line = Line::new(a, b);
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    if clip.is_empty() {
        return Ok(());
    }
    let (big_a, big_b) = (line.a, line.b);
    // Half the cross-section, w sqrt(A^2 + B^2) / 2A, in 2^-FRAC pixels: the ratio
    // sqrt(1 + B^2 / A^2) (1 ..= sqrt 2) with 30 fractional bits first. (A^2 + B^2) 2^60 < 2^127.
    let half = if big_a == 0 {
        w * HALF
    } else {
        let a2 = (big_a as u128) * (big_a as u128);
        let b2 = (big_b as u128) * (big_b as u128);
        // At most 2^61: fits u64.
        let ratio = (((a2 + b2) << 60) / a2) as u64;
        let ratio = i64::try_from(ratio.isqrt()).unwrap_or(i64::MAX >> 20);
        // w ratio < 2^16 2^31: no overflow.
        (w * ratio + (1 << (30 - FRAC))) >> (31 - FRAC)
    };
    // Every pixel with coverage lies within half + 1/2 of the ideal line, which lies within 1/2
    // of Bresenham's pixel: the steps whose Bresenham pixel lies in the clip area grown by that
    // much across the line are the only ones that can draw.
    let grow = (half >> FRAC) + 2;
    let mut grown = clip;
    if line.major_x {
        (grown.y0, grown.y1) = (clip.y0 - grow, clip.y1 + grow);
    } else {
        (grown.x0, grown.x1) = (clip.x0 - grow, clip.x1 + grow);
    }
    let Some((k0, k1)) = line.clipped_steps_in(&grown) else {
        return Ok(());
    };
    let s = i64::from(line.minor_step);
    let (m0, n0, clip_m, clip_n) = if line.major_x {
        (
            i64::from(line.start.x),
            i64::from(line.start.y),
            (clip.x0, clip.x1),
            (clip.y0, clip.y1),
        )
    } else {
        (
            i64::from(line.start.y),
            i64::from(line.start.x),
            (clip.y0, clip.y1),
            (clip.x0, clip.x1),
        )
    };
    // The pixel offsets j (minor coordinate n0 + s j) inside the clip area.
    let (j_min, j_max) = if s > 0 {
        (clip_n.0 - n0, clip_n.1 - 1 - n0)
    } else {
        (n0 - (clip_n.1 - 1), n0 - clip_n.0)
    };
    // The centre's offset at step k, floor(k B 2^FRAC / A), as quotient p and remainder r of the
    // division by A. B 2^FRAC < 2^49; k0 B 2^FRAC needs i128.
    let (mut p, mut r, dp, dr) = if big_a == 0 {
        (0, 0, 0, 0)
    } else {
        let num = i128::from(k0) * i128::from(big_b << FRAC);
        let den = i128::from(big_a);
        (
            (num / den) as i64,
            (num % den) as i64,
            (big_b << FRAC) / big_a,
            (big_b << FRAC) % big_a,
        )
    };
    for k in k0..=k1 {
        let m = m0 + k;
        if (clip_m.0..clip_m.1).contains(&m) {
            let (lo, hi) = (p - half, p + half);
            // The pixels containing each end of the cross-section, then those inside the clip.
            let (first, last) = ((lo + HALF) >> FRAC, (hi + HALF) >> FRAC);
            let (from, to) = (first.max(j_min), last.min(j_max));
            // A pixel's part of the cross-section, in 255ths.
            let cover = |j: i64| {
                let inside = ((j << FRAC) + HALF).min(hi) - ((j << FRAC) - HALF).max(lo);
                (255 * inside + HALF) >> FRAC
            };
            let col = Column {
                major_x: line.major_x,
                m,
                n0,
                s,
            };
            if (from..=to).contains(&first) {
                col.blend(surface, first, first, color, cover(first))?;
            }
            // The pixels strictly between the end pixels are wholly inside: one run.
            col.blend(
                surface,
                (first + 1).max(from),
                (last - 1).min(to),
                color,
                255,
            )?;
            if last > first && (from..=to).contains(&last) {
                col.blend(surface, last, last, color, cover(last))?;
            }
        }
        p += dp;
        r += dr;
        if r >= big_a && big_a > 0 {
            r -= big_a;
            p += 1;
        }
    }
    Ok(())
}

/// One column of the line: major coordinate `m`, pixel `j` at minor coordinate `n0 + s j`.
struct Column {
    major_x: bool,
    m: i64,
    n0: i64,
    s: i64,
}

impl Column {
    /// Blends pixels `j0 ..= j1` (nothing when `j0 > j1`), all inside the clip area, with
    /// coverage `cover` (nothing when 0): one span when the minor axis is x, one pixel at a time
    /// when it is y.
    #[inline(always)]
    fn blend<S: Surface>(
        &self,
        surface: &mut S,
        j0: i64,
        j1: i64,
        color: S::Color,
        cover: i64,
    ) -> Result<(), BlendError<S::Error>> {
        if j0 > j1 || cover <= 0 {
            return Ok(());
        }
        // Inside the clip area, so every coordinate is an i32; a coverage is at most 255.
        let alpha = cover.min(255) as u8;
        if self.major_x {
            for j in j0..=j1 {
                let n = self.n0 + self.s * j;
                surface.blend_span_in_clip(self.m as i32, n as i32, 1, color, alpha)?;
            }
            Ok(())
        } else {
            let (na, nb) = (self.n0 + self.s * j0, self.n0 + self.s * j1);
            let len = (na - nb).abs() + 1;
            surface.blend_span_in_clip(na.min(nb) as i32, self.m as i32, len as u32, color, alpha)
        }
    }
}
