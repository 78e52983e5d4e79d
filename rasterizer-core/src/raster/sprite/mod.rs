//! Sprites: an Rgb565 image, with an optional alpha channel, drawn under any 2D affine transform
//! (rotation, scale, shear, translation), nearest or bilinear, in fixed point.
//!
//! Coverage is the triangles': the image rectangle's corners are mapped to sub-pixel points
//! (24.8) and the quad is filled as two triangles sharing a diagonal, with the top-left rule
//! (`raster/triangle`), so two sprites that share an edge leave no gap and draw no pixel twice.
//! Each covered pixel's centre is mapped back to texel space by the inverse transform, found once
//! per sprite ([`Affine`], 32.32 steps) and stepped per pixel with adds only; texel coordinates
//! are clamped to the image, so sampling never reads outside it.
//!
//! Degenerate transforms draw nothing, as zero-area triangles do: a singular matrix, one that
//! squeezes the image below `2^-24` of its size in some direction, a quad thinner than the
//! sub-pixel grid folds over, or a corner outside the guard band.

mod affine;
mod image;

pub use affine::Affine;
pub use image::{header, AlphaBits, Sprite, SpriteError, HEADER_LEN, MAGIC, MAX_SIDE, VERSION};

use crate::geom::{PixelRect, SubPoint};
use crate::raster::triangle::setup::{walk_spans, Sorted, SpanSink};
use crate::surface::{BlendError, Surface};
use crate::texture::Filter;
use affine::{Inverse, TEXEL_FRAC};
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::Rgb565;

/// Sub-pixel bits of the quad's corners: the finest the triangle set-up takes, so that coverage
/// follows the exact quad as closely as it can.
const QUAD_BITS: u32 = 8;

/// Draws `sprite` under `transform`, sampled `filter`, over what `surface` holds.
///
/// Without alpha every covered pixel is written; 1-bit alpha draws the texels whose bit is set (a
/// test, no blending); 4- and 8-bit alpha blend each pixel with [`crate::color::blend`]'s
/// arithmetic. Bilinear sampling weights the four nearest texels in 1/256 steps, colours by
/// their opacity (so transparent texels lend no colour), and tests a 1-bit sprite's filtered
/// opacity at one half.
///
/// ```
/// use rasterizer_core::prelude::*;
/// use rasterizer_core::raster::sprite::{draw_sprite, Affine, AlphaBits, Sprite};
/// use rasterizer_core::texture::Filter;
///
/// // 2x2 texels: red, green / blue, white.
/// let texels = [0x00, 0xF8, 0xE0, 0x07, 0x1F, 0x00, 0xFF, 0xFF];
/// let sprite = Sprite::from_parts(2, 2, AlphaBits::None, &texels, &[]).unwrap();
/// let mut buf = [0u16; 8 * 8];
/// let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 8, 8).unwrap();
/// // Twice the size, turned a quarter clockwise, its centre at (4, 4).
/// let at = [Fx16::from_int(4), Fx16::from_int(4)];
/// let turn = Affine::rotate_scale(2, 2, Angle::QUARTER, Fx16::from_int(2), at);
/// draw_sprite(&mut fb, &sprite, &turn, Filter::Nearest).unwrap();
/// assert_eq!(fb.pixel(Point::new(2, 2)), Some(Rgb565::BLUE));
/// assert_eq!(fb.pixel(Point::new(5, 2)), Some(Rgb565::RED));
/// assert_eq!(fb.pixel(Point::new(5, 5)), Some(Rgb565::GREEN));
/// assert_eq!(fb.pixel(Point::new(6, 2)), Some(Rgb565::BLACK));
/// ```
///
/// # Errors
/// [`BlendError::CannotReadBack`] (before anything is drawn) for a sprite with 4- or 8-bit alpha
/// and a surface that cannot read back its pixels; [`BlendError::Target`] for the surface's own.
pub fn draw_sprite<S: Surface<Color = Rgb565>>(
    surface: &mut S,
    sprite: &Sprite<'_>,
    transform: &Affine,
    filter: Filter,
) -> Result<(), BlendError<S::Error>> {
    let mode = match sprite.alpha_bits() {
        AlphaBits::None => Mode::Opaque,
        AlphaBits::One => Mode::Test,
        AlphaBits::Four | AlphaBits::Eight => Mode::Blend,
    };
    if mode == Mode::Blend && !S::READ_BACK {
        return Err(BlendError::CannotReadBack);
    }
    let Some(quad) = Quad::new(sprite, transform) else {
        return Ok(());
    };
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    match filter {
        Filter::Nearest => quad.draw(surface, sprite, &clip, mode, Nearest),
        Filter::Bilinear => quad.draw(surface, sprite, &clip, mode, Bilinear),
    }
}

/// How a sampled texel's opacity is applied.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// Every pixel written: whole spans through the surface's span fast path.
    Opaque,
    /// Written when the opacity is at least one half.
    Test,
    /// Blended by the opacity.
    Blend,
}

/// A sprite's set-up: the two triangles of its quad and the inverse mapping.
struct Quad {
    halves: [Sorted; 2],
    inverse: Inverse,
}

impl Quad {
    fn new(sprite: &Sprite<'_>, a: &Affine) -> Option<Self> {
        let inverse = Inverse::new(a)?;
        let (w, h) = (i64::from(sprite.width()), i64::from(sprite.height()));
        // 16.16 corners (below 2^44 in magnitude) rounded to 24.8 and saturated to i32: a corner
        // past the guard band makes the triangle set-up refuse the quad.
        let corner = |u, v| {
            let (x, y) = a.map(u, v);
            let round =
                |c: i64| ((c + (1 << 7)) >> 8).clamp(i32::MIN.into(), i32::MAX.into()) as i32;
            SubPoint::<QUAD_BITS>::raw(round(x), round(y))
        };
        let (p0, p1, p2, p3) = (corner(0, 0), corner(w, 0), corner(w, h), corner(0, h));
        let first = Sorted::new(&[p0, p1, p2])?;
        let second = Sorted::new(&[p0, p2, p3])?;
        // The halves of a true parallelogram turn the same way; opposite turns mean the rounded
        // quad folded over (a sliver thinner than the grid), which would draw pixels twice.
        let turn = |p: SubPoint<QUAD_BITS>, q: SubPoint<QUAD_BITS>, r: SubPoint<QUAD_BITS>| {
            let (ax, ay) = (i64::from(q.x - p.x), i64::from(q.y - p.y));
            let (bx, by) = (
                i64::from(r.x) - i64::from(p.x),
                i64::from(r.y) - i64::from(p.y),
            );
            (ax * by - ay * bx).signum()
        };
        if turn(p0, p1, p2) != turn(p0, p2, p3) {
            return None;
        }
        Some(Self {
            halves: [first, second],
            inverse,
        })
    }

    fn draw<S: Surface<Color = Rgb565>, F: Sample>(
        &self,
        surface: &mut S,
        sprite: &Sprite<'_>,
        clip: &PixelRect,
        mode: Mode,
        filter: F,
    ) -> Result<(), BlendError<S::Error>> {
        let mut sink = Spans {
            surface,
            sprite,
            inverse: &self.inverse,
            mode,
            filter,
            max: (
                i64::from(sprite.width()) - 1,
                i64::from(sprite.height()) - 1,
            ),
        };
        for half in &self.halves {
            walk_spans(half, 1 << QUAD_BITS, clip, &mut sink)?;
        }
        Ok(())
    }
}

/// A texel lookup at a texel point (32.32), giving the raw Rgb565 colour and the opacity.
trait Sample: Copy {
    fn sample(self, sprite: &Sprite<'_>, max: (i64, i64), u: i64, v: i64) -> (u16, u8);
}

/// The texel the point falls in, its coordinates clamped to the image.
#[derive(Clone, Copy)]
struct Nearest;

impl Sample for Nearest {
    #[inline(always)]
    fn sample(self, sprite: &Sprite<'_>, max: (i64, i64), u: i64, v: i64) -> (u16, u8) {
        let x = (u >> TEXEL_FRAC).clamp(0, max.0) as u32;
        let y = (v >> TEXEL_FRAC).clamp(0, max.1) as u32;
        sprite.texel(x, y)
    }
}

/// The four texels around the point, weighted in 1/256 steps, colours by opacity.
#[derive(Clone, Copy)]
struct Bilinear;

impl Sample for Bilinear {
    #[inline(always)]
    fn sample(self, sprite: &Sprite<'_>, max: (i64, i64), u: i64, v: i64) -> (u16, u8) {
        // Texel centres sit at half-texels: offset by one half, round to the nearest 1/256
        // (half a weight step off at most, not a whole one), then split whole and fraction.
        let off = (1 << (TEXEL_FRAC - 1)) - (1 << (TEXEL_FRAC - 9));
        let (us, vs) = (u.wrapping_sub(off), v.wrapping_sub(off));
        let (x0, y0) = (us >> TEXEL_FRAC, vs >> TEXEL_FRAC);
        let fx = ((us >> (TEXEL_FRAC - 8)) & 0xFF) as u32;
        let fy = ((vs >> (TEXEL_FRAC - 8)) & 0xFF) as u32;
        let cx = |x: i64| x.clamp(0, max.0) as u32;
        let cy = |y: i64| y.clamp(0, max.1) as u32;
        let (xa, xb, ya, yb) = (
            cx(x0),
            cx(x0.saturating_add(1)),
            cy(y0),
            cy(y0.saturating_add(1)),
        );
        let t = [
            sprite.texel(xa, ya),
            sprite.texel(xb, ya),
            sprite.texel(xa, yb),
            sprite.texel(xb, yb),
        ];
        // Weights summing to 2^16.
        let w = [
            (256 - fx) * (256 - fy),
            fx * (256 - fy),
            (256 - fx) * fy,
            fx * fy,
        ];
        let channels = |c: u16| {
            [
                u32::from(c >> 11),
                u32::from((c >> 5) & 0x3F),
                u32::from(c & 0x1F),
            ]
        };
        let mut out = [0u32; 3];
        let alpha;
        if t.iter().all(|x| x.1 == t[0].1) {
            // One opacity (always, without alpha): the plain weighted mean, rounded.
            for (tex, wt) in t.iter().zip(w) {
                for (o, c) in out.iter_mut().zip(channels(tex.0)) {
                    *o += wt * c;
                }
            }
            out = out.map(|o| (o + (1 << 15)) >> 16);
            alpha = t[0].1;
        } else {
            // Opacity-weighted: sum(w a c) / sum(w a), below 2^24 and 2^30. Only where the
            // opacities differ (a sprite's rim), so the division is rare.
            let mut total = 0u32;
            for (tex, wt) in t.iter().zip(w) {
                let wa = wt * u32::from(tex.1);
                total += wa;
                for (o, c) in out.iter_mut().zip(channels(tex.0)) {
                    *o += wa * c;
                }
            }
            if total == 0 {
                return (0, 0);
            }
            out = out.map(|o| (o + total / 2) / total);
            alpha = ((total + (1 << 15)) >> 16) as u8;
        }
        let raw = (out[0] << 11 | out[1] << 5 | out[2]) as u16;
        (raw, alpha)
    }
}

/// The spans of a sprite's quad, sampled and written.
struct Spans<'a, S, F> {
    surface: &'a mut S,
    sprite: &'a Sprite<'a>,
    inverse: &'a Inverse,
    mode: Mode,
    filter: F,
    /// The last texel column and row.
    max: (i64, i64),
}

impl<S: Surface<Color = Rgb565>, F: Sample> SpanSink for Spans<'_, S, F> {
    type Error = BlendError<S::Error>;

    #[inline(always)]
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), Self::Error> {
        let inv = self.inverse;
        let (mut u, mut v) = inv.at(x0, row);
        let (sprite, max, filter) = (self.sprite, self.max, self.filter);
        let mut next = || {
            let t = filter.sample(sprite, max, u, v);
            u = u.wrapping_add(inv.du_dx);
            v = v.wrapping_add(inv.dv_dx);
            t
        };
        match self.mode {
            Mode::Opaque => {
                let len = (x1 - x0) as u32;
                self.surface
                    .shade_span_in_clip(x0, row, len, || Rgb565::from(RawU16::new(next().0)))?;
            }
            Mode::Test => {
                for x in x0..x1 {
                    let (c, a) = next();
                    if a >= 128 {
                        let c = Rgb565::from(RawU16::new(c));
                        self.surface.fill_span_in_clip(x, row, 1, c)?;
                    }
                }
            }
            Mode::Blend => {
                for x in x0..x1 {
                    let (c, a) = next();
                    let c = Rgb565::from(RawU16::new(c));
                    if a == 255 {
                        self.surface.fill_span_in_clip(x, row, 1, c)?;
                    } else if a != 0 {
                        self.surface.blend_span_in_clip(x, row, 1, c, a)?;
                    }
                }
            }
        }
        Ok(())
    }
}
