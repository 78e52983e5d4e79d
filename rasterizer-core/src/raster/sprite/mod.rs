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
    let blends = matches!(sprite.alpha_bits(), AlphaBits::Four | AlphaBits::Eight);
    if blends && !S::READ_BACK {
        return Err(BlendError::CannotReadBack);
    }
    let Some(quad) = Quad::new(sprite, transform) else {
        return Ok(());
    };
    // One copy of the span loop per alpha depth and filter, so that neither is decided per pixel.
    match (sprite.alpha_bits(), filter) {
        (AlphaBits::None, Filter::Nearest) => quad.draw::<_, NoAlpha, Nearest>(surface, sprite),
        (AlphaBits::None, Filter::Bilinear) => quad.draw::<_, NoAlpha, Bilinear>(surface, sprite),
        (AlphaBits::One, Filter::Nearest) => quad.draw::<_, Alpha1, Nearest>(surface, sprite),
        (AlphaBits::One, Filter::Bilinear) => quad.draw::<_, Alpha1, Bilinear>(surface, sprite),
        (AlphaBits::Four, Filter::Nearest) => quad.draw::<_, Alpha4, Nearest>(surface, sprite),
        (AlphaBits::Four, Filter::Bilinear) => quad.draw::<_, Alpha4, Bilinear>(surface, sprite),
        (AlphaBits::Eight, Filter::Nearest) => quad.draw::<_, Alpha8, Nearest>(surface, sprite),
        (AlphaBits::Eight, Filter::Bilinear) => quad.draw::<_, Alpha8, Bilinear>(surface, sprite),
    }
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
        if turn(p0, p1, p2) != turn(p0, p2, p3) {
            return None;
        }
        Some(Self {
            halves: [first, second],
            inverse,
        })
    }

    fn draw<S: Surface<Color = Rgb565>, A: Alpha, F: Sample>(
        &self,
        surface: &mut S,
        sprite: &Sprite<'_>,
    ) -> Result<(), BlendError<S::Error>> {
        let clip = PixelRect::from_rectangle(&surface.clip_area());
        let mut sink = Spans::<S, A, F> {
            surface,
            texels: Texels {
                colors: sprite.color_bytes().as_chunks::<2>().0,
                alpha: sprite.alpha_bytes(),
                width: sprite.width() as usize,
                alpha_row: sprite.alpha_bits().row_bytes(sprite.width()),
                max: (
                    i64::from(sprite.width()) - 1,
                    i64::from(sprite.height()) - 1,
                ),
            },
            inverse: &self.inverse,
            _kind: core::marker::PhantomData,
        };
        for half in &self.halves {
            walk_spans(half, 1 << QUAD_BITS, &clip, &mut sink)?;
        }
        Ok(())
    }
}

/// The sign of the triangle `p q r`'s area (its turn), in `i64`: exact for any `i32` points.
fn turn(p: SubPoint<QUAD_BITS>, q: SubPoint<QUAD_BITS>, r: SubPoint<QUAD_BITS>) -> i64 {
    let d = |a: i32, b: i32| i64::from(a) - i64::from(b);
    (d(q.x, p.x) * d(r.y, p.y) - d(q.y, p.y) * d(r.x, p.x)).signum()
}

/// The texels and alpha plane of a sprite, read by index (the sampler keeps indices inside).
#[derive(Clone, Copy)]
struct Texels<'a> {
    /// Little-endian Rgb565 texels, one pair of bytes each.
    colors: &'a [[u8; 2]],
    alpha: &'a [u8],
    width: usize,
    /// Bytes of an alpha row.
    alpha_row: usize,
    /// The last texel column and row.
    max: (i64, i64),
}

impl Texels<'_> {
    /// Texel `(x, y)`, inside the image: raw colour and opacity. A slice read that could fail
    /// only gives a zero (the sprite's checks make its lengths right).
    #[inline(always)]
    fn get<A: Alpha>(&self, x: usize, y: usize) -> (u16, u8) {
        let i = y * self.width + x;
        let c = self.colors.get(i).map_or(0, |&b| u16::from_le_bytes(b));
        (c, A::read(self.alpha, y * self.alpha_row, x))
    }
}

/// An alpha depth: how a texel's opacity is read, and whether anything blends.
trait Alpha {
    /// Every texel is opaque: spans go through the surface's plain span fast path.
    const OPAQUE: bool = false;
    /// The opacity, `0 ..= 255`, of texel `x` of the alpha row starting at byte `row`.
    fn read(plane: &[u8], row: usize, x: usize) -> u8;
    /// The opacity drawn for a filtered one: a 1-bit sprite tests it at one half.
    #[inline(always)]
    fn drawn(alpha: u8) -> u8 {
        alpha
    }
}

struct NoAlpha;
struct Alpha1;
struct Alpha4;
struct Alpha8;

impl Alpha for NoAlpha {
    const OPAQUE: bool = true;
    #[inline(always)]
    fn read(_: &[u8], _: usize, _: usize) -> u8 {
        255
    }
}

impl Alpha for Alpha1 {
    #[inline(always)]
    fn read(plane: &[u8], row: usize, x: usize) -> u8 {
        let byte = plane.get(row + x / 8).copied().unwrap_or(0);
        0u8.wrapping_sub((byte >> (7 - x % 8)) & 1)
    }
    #[inline(always)]
    fn drawn(alpha: u8) -> u8 {
        if alpha >= 128 {
            255
        } else {
            0
        }
    }
}

impl Alpha for Alpha4 {
    #[inline(always)]
    fn read(plane: &[u8], row: usize, x: usize) -> u8 {
        let byte = plane.get(row + x / 2).copied().unwrap_or(0);
        ((byte >> (4 * (1 - x % 2))) & 0xF) * 17
    }
}

impl Alpha for Alpha8 {
    #[inline(always)]
    fn read(plane: &[u8], row: usize, x: usize) -> u8 {
        plane.get(row + x).copied().unwrap_or(0)
    }
}

/// A filter: the colour and opacity at a texel point (32.32).
trait Sample {
    /// Whether the point samples only texels inside the image without clamping, so that a
    /// span whose two ends do (and so, the texel map being linear, every pixel between) skips
    /// the clamps.
    fn inside(t: &Texels<'_>, u: i64, v: i64) -> bool;
    /// The sample; `CLAMP` false only where [`Sample::inside`] holds.
    fn sample<A: Alpha, const CLAMP: bool>(t: &Texels<'_>, u: i64, v: i64) -> (u16, u8);
}

/// The texel the point falls in.
struct Nearest;

impl Sample for Nearest {
    #[inline(always)]
    fn inside(t: &Texels<'_>, u: i64, v: i64) -> bool {
        let (x, y) = (u >> TEXEL_FRAC, v >> TEXEL_FRAC);
        0 <= x && x <= t.max.0 && 0 <= y && y <= t.max.1
    }

    #[inline(always)]
    fn sample<A: Alpha, const CLAMP: bool>(t: &Texels<'_>, u: i64, v: i64) -> (u16, u8) {
        let (mut x, mut y) = (u >> TEXEL_FRAC, v >> TEXEL_FRAC);
        if CLAMP {
            x = x.clamp(0, t.max.0);
            y = y.clamp(0, t.max.1);
        }
        t.get::<A>(x as usize, y as usize)
    }
}

/// The four texels around the point, weighted in 1/256 steps, colours by opacity.
struct Bilinear;

impl Bilinear {
    /// The point moved so that texel centres are whole numbers and rounded to the nearest 1/256
    /// (half a weight step off at most): its whole part and the weight of the next texel.
    #[inline(always)]
    fn split(t: i64) -> (i64, u32) {
        let off = (1 << (TEXEL_FRAC - 1)) - (1 << (TEXEL_FRAC - 9));
        let s = t.wrapping_sub(off);
        (s >> TEXEL_FRAC, ((s >> (TEXEL_FRAC - 8)) & 0xFF) as u32)
    }
}

impl Sample for Bilinear {
    #[inline(always)]
    fn inside(t: &Texels<'_>, u: i64, v: i64) -> bool {
        let ((x, _), (y, _)) = (Self::split(u), Self::split(v));
        0 <= x && x < t.max.0 && 0 <= y && y < t.max.1
    }

    #[inline(always)]
    fn sample<A: Alpha, const CLAMP: bool>(t: &Texels<'_>, u: i64, v: i64) -> (u16, u8) {
        let ((x0, fx), (y0, fy)) = (Self::split(u), Self::split(v));
        let (mut xa, mut xb, mut ya, mut yb) = (x0, x0.wrapping_add(1), y0, y0.wrapping_add(1));
        if CLAMP {
            xa = xa.clamp(0, t.max.0);
            xb = xb.clamp(0, t.max.0);
            ya = ya.clamp(0, t.max.1);
            yb = yb.clamp(0, t.max.1);
        }
        let (xa, xb, ya, yb) = (xa as usize, xb as usize, ya as usize, yb as usize);
        let texels = [
            t.get::<A>(xa, ya),
            t.get::<A>(xb, ya),
            t.get::<A>(xa, yb),
            t.get::<A>(xb, yb),
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
        if A::OPAQUE || texels.iter().all(|x| x.1 == texels[0].1) {
            // One opacity: the plain weighted mean, rounded.
            for (tex, wt) in texels.iter().zip(w) {
                for (o, c) in out.iter_mut().zip(channels(tex.0)) {
                    *o += wt * c;
                }
            }
            out = out.map(|o| (o + (1 << 15)) >> 16);
            alpha = texels[0].1;
        } else {
            // Opacity-weighted: sum(w a c) / sum(w a), below 2^30 and 2^24. Only where the
            // opacities differ (a sprite's rim), so the division is rare.
            let mut total = 0u32;
            for (tex, wt) in texels.iter().zip(w) {
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
        ((out[0] << 11 | out[1] << 5 | out[2]) as u16, alpha)
    }
}

/// The spans of a sprite's quad, sampled and written.
struct Spans<'a, S, A, F> {
    surface: &'a mut S,
    texels: Texels<'a>,
    inverse: &'a Inverse,
    _kind: core::marker::PhantomData<(A, F)>,
}

impl<S: Surface<Color = Rgb565>, A: Alpha, F: Sample> Spans<'_, S, A, F> {
    #[inline(always)]
    fn run<const CLAMP: bool>(
        &mut self,
        row: i32,
        x0: i32,
        len: u32,
        (mut u, mut v): (i64, i64),
    ) -> Result<(), BlendError<S::Error>> {
        let (t, du, dv) = (self.texels, self.inverse.du_dx, self.inverse.dv_dx);
        let mut next = || {
            let s = F::sample::<A, CLAMP>(&t, u, v);
            u = u.wrapping_add(du);
            v = v.wrapping_add(dv);
            s
        };
        if A::OPAQUE {
            self.surface
                .shade_span_in_clip(x0, row, len, || Rgb565::from(RawU16::new(next().0)))?;
        } else {
            self.surface.blend_shade_span_in_clip(x0, row, len, || {
                let (c, a) = next();
                (Rgb565::from(RawU16::new(c)), A::drawn(a))
            })?;
        }
        Ok(())
    }
}

impl<S: Surface<Color = Rgb565>, A: Alpha, F: Sample> SpanSink for Spans<'_, S, A, F> {
    type Error = BlendError<S::Error>;

    #[inline(always)]
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), Self::Error> {
        let inv = self.inverse;
        let start = inv.at(x0, row);
        let len = (x1 - x0) as u32;
        // The last pixel's point, exact as every pixel's is (wrapping, see `Inverse`).
        let n = i64::from(len - 1);
        let end = (
            start.0.wrapping_add(inv.du_dx.wrapping_mul(n)),
            start.1.wrapping_add(inv.dv_dx.wrapping_mul(n)),
        );
        if F::inside(&self.texels, start.0, start.1) && F::inside(&self.texels, end.0, end.1) {
            self.run::<false>(row, x0, len, start)
        } else {
            self.run::<true>(row, x0, len, start)
        }
    }
}
