//! A textured, Gouraud-lit shader: the texel under each pixel times the light of its vertices.
//!
//! Per vertex the light is computed as [`super::GouraudLit`] does (the material's colours apply,
//! so a white diffuse colour gives the texture's own colours in full light) and kept with 23
//! fractional bits per 8-bit channel; texture coordinates are kept as the mesh gives them, and
//! `1 / w` is taken from the vertex's clip-space `w`.
//!
//! Perspective-correct coordinates, in integers: per triangle, the three `1 / w` are scaled
//! together to 31 bits (their ratios are all that matter) and the coordinates are made relative
//! to the whole texel before the triangle's smallest (a margin against wrapping), scaled to the
//! triangle's extent, and multiplied by them; the span loop interpolates `u / w`, `v / w` and
//! `1 / w` as 32-bit planes and each pixel divides, so the coordinates are exact up to the
//! planes' rounding, about 2^-30 of the triangle's extent in texels (`docs/ACCURACY.md` measures
//! it). The values use all 32 bits, so the span loop gives them no fractional bits of its own
//! (`FUSED_FRAC` 0). A pipeline that interpolates every value perspective-correctly
//! ([`crate::numerics::Perspective`]) gets affine values here and corrects them itself.

use super::model::{Shading, VertexIn};
use super::Lighting;
use crate::color::ShadeColor;
use crate::geom::MAX_VARYINGS;
use crate::math::{Mat4, Scalar};
use crate::texture::{Filter, Texture, Wrap};
use crate::wide;
use core::num::NonZeroU64;

/// Values per vertex: light r g b (8.23, half a step added), u, v (16.16 texture units) and
/// `1 / w`.
type Values = [i32; 6];

/// The largest `1 / w` kept per vertex, as `2^Q_BITS / w`: with `w` at least the clipper's
/// smallest (`2^-8`), it stays below `2^31`.
const Q_BITS: u32 = 22;

/// What the pixels of the current triangle need to undo its scaling.
#[derive(Debug, Clone, Copy, Default)]
struct TriangleScale {
    /// The whole texel before the triangle's smallest, in x and y (16.16 texel units shifted
    /// right by 16).
    base: [i32; 2],
    /// `u / w` was scaled down by `2^shift` texel units (16.16): the pixel shifts back.
    shift: [u32; 2],
}

/// A textured mesh lit per vertex (Gouraud) with perspective-correct texture coordinates.
#[derive(Debug, Clone)]
pub struct TexturedLit<'t, S, C, const N: usize> {
    /// The lights, material and eye.
    pub lighting: Lighting<S, N>,
    /// This frame's lighting in model space, when the model matrix allows it.
    frame: Option<Lighting<S, N>>,
    texture: Texture<'t>,
    filter: Filter,
    wrap: Wrap,
    current: TriangleScale,
    _c: core::marker::PhantomData<C>,
}

impl<'t, S: Scalar, C, const N: usize> TexturedLit<'t, S, C, N> {
    /// The shader: nearest texel, repeating.
    pub fn new(lighting: Lighting<S, N>, texture: Texture<'t>) -> Self {
        Self {
            lighting,
            frame: None,
            texture,
            filter: Filter::Nearest,
            wrap: Wrap::Repeat,
            current: TriangleScale::default(),
            _c: core::marker::PhantomData,
        }
    }

    /// The same shader with another filter.
    pub fn with_filter(self, filter: Filter) -> Self {
        Self { filter, ..self }
    }

    /// The same shader with another wrap mode.
    pub fn with_wrap(self, wrap: Wrap) -> Self {
        Self { wrap, ..self }
    }

    /// The texture.
    pub fn texture(&self) -> &Texture<'t> {
        &self.texture
    }
}

impl<S: Scalar, C: ShadeColor, const N: usize> TexturedLit<'_, S, C, N> {
    /// The colour of texel `(x, y)` (whole texels relative to nothing: wrapped or clamped here)
    /// as 5/6/5 channels.
    #[inline(always)]
    fn texel(&self, x: i32, y: i32) -> [u32; 3] {
        let t = &self.texture;
        let (x, y) = match self.wrap {
            Wrap::Repeat => (x as u32, y as u32),
            Wrap::Clamp => (
                x.clamp(0, t.width() as i32 - 1) as u32,
                y.clamp(0, t.height() as i32 - 1) as u32,
            ),
        };
        let c = u32::from(t.texel(x, y));
        [c >> 11, (c >> 5) & 63, c & 31]
    }

    /// The texel channels at texel coordinates `(u, v)` (16.16, relative to the texture), 5/6/5
    /// with 8 fractional bits.
    #[inline(always)]
    fn sample(&self, u: i64, v: i64) -> [u32; 3] {
        match self.filter {
            Filter::Nearest => self
                .texel((u >> 16) as i32, (v >> 16) as i32)
                .map(|c| c << 8),
            Filter::Bilinear => {
                // Texel centres are at half texels: weights from the point half a texel back,
                // in sixteenths.
                let (u, v) = (u - (1 << 15), v - (1 << 15));
                let (x, y) = ((u >> 16) as i32, (v >> 16) as i32);
                let (fx, fy) = (((u >> 12) & 15) as u32, ((v >> 12) & 15) as u32);
                let t = [
                    self.texel(x, y),
                    self.texel(x.wrapping_add(1), y),
                    self.texel(x, y.wrapping_add(1)),
                    self.texel(x.wrapping_add(1), y.wrapping_add(1)),
                ];
                let w = [
                    (16 - fx) * (16 - fy),
                    fx * (16 - fy),
                    (16 - fx) * fy,
                    fx * fy,
                ];
                let mut out = [0u32; 3];
                for (c, o) in out.iter_mut().enumerate() {
                    *o = t.iter().zip(&w).map(|(t, w)| t[c] * w).sum();
                }
                out
            }
        }
    }

    /// The pixel's colour from its texel coordinates relative to the triangle's base texel and
    /// its light (8-bit channels).
    #[inline(always)]
    fn shade(&self, u_rel: i64, v_rel: i64, light: [u32; 3]) -> C {
        let [bu, bv] = self.current.base;
        let u = u_rel + (i64::from(bu) << 16);
        let v = v_rel + (i64::from(bv) << 16);
        let t = self.sample(u, v);
        // The texel channel (of 31 or 63, 8 fractional bits) times light / 255, at the target's
        // depth, rounded once: at most 63 2^8 255 255 before the division, below 2^32.
        const TEXEL_MAX: [u32; 3] = [31, 63, 31];
        let mut out = [0u8; 3];
        for c in 0..3 {
            let d = TEXEL_MAX[c] * 256 * 255;
            let n = t[c] * light[c] * u32::from(C::MAX[c]);
            out[c] = ((n + d / 2) / d) as u8;
        }
        C::from_shade(out)
    }
}

impl<S: Scalar, C: ShadeColor, const N: usize> Shading<S> for TexturedLit<'_, S, C, N> {
    type Color = C;
    type Varyings = Values;
    type Stored = Values;
    const NEEDS_WORLD: bool = true;
    const NEEDS_UV: bool = true;
    const NEEDS_W: bool = true;
    const NEEDS_TRIANGLE: bool = true;
    const FUSED_FRAC: u32 = 0;
    const FUSED_OFFSET: u32 = 0;

    fn begin_frame(&mut self, model: Option<&Mat4<S>>) -> bool {
        self.frame = model.and_then(|m| self.lighting.in_model_space(m));
        self.frame.is_some()
    }

    #[inline(always)]
    fn vertex(&mut self, v: &VertexIn<S>) -> Values {
        let lighting = self.frame.as_ref().unwrap_or(&self.lighting);
        // sums / (255 2^16) 8-bit steps (at most 255, `shade_sums` clamps), in 8.23 with half a
        // step added (the pixel truncates): below 2^31.
        let light = lighting
            .shade_sums(v.position, v.normal)
            .map(|s| ((s * 128 + 127) / 255) as i32 + (1 << 22));
        // Affine until `project` sets 1 / w: every vertex the same.
        [light[0], light[1], light[2], v.uv[0], v.uv[1], 1 << 16]
    }

    #[inline(always)]
    fn project(&self, v: &mut Values, w: S) {
        v[5] = S::scaled_ratio(S::ONE, w, 1 << Q_BITS, 1).clamp(1, i64::from(i32::MAX)) as i32;
    }

    fn triangle(&mut self, v: &mut [Values; 3]) {
        // 1 / w of the three (each in 1 ..= 2^31 - 1), scaled together so the largest has 31
        // bits.
        let q_max = v[0][5].max(v[1][5]).max(v[2][5]).max(1) as u32;
        let up = q_max.leading_zeros() - 1;
        let q = [0, 1, 2].map(|k| i64::from((v[k][5].max(1) as u32) << up));
        let (wl, hl) = (
            u32::from(self.texture.width_log2()),
            u32::from(self.texture.height_log2()),
        );
        for (axis, log2) in [(3usize, wl), (4, hl)] {
            // Texel units (16.16) relative to the whole texel before the triangle's smallest: a
            // texel of margin, so that the planes' rounding (a few units of 2^-31) cannot take
            // a pixel's value below zero, where it would wrap.
            // An i32 coordinate times at most 2^10 texels: below 2^41, so `base` fits an i32.
            let t = [0, 1, 2].map(|k| i64::from(v[k][axis]) << log2);
            let base = (t[0].min(t[1]).min(t[2]) >> 16) - 1;
            // Beyond 2^16 texels across one triangle the coordinates are clamped (the pixels'
            // shifts stay within 64 bits).
            let rel = t.map(|x| (x - (base << 16)).min(u32::MAX.into()));
            let extent = rel[0].max(rel[1]).max(rel[2]) as u64;
            // rel q / 2^shift stays below 2^31 (q below 2^31, rel below 2^shift); the product
            // below 2^63. The margin makes `extent` at least a texel, so `shift` is at least 17.
            let shift = 64 - extent.leading_zeros();
            for k in 0..3 {
                v[k][axis] = ((rel[k] * q[k]) >> shift) as i32;
            }
            let a = axis - 3;
            self.current.base[a] = base as i32;
            self.current.shift[a] = shift;
        }
        for k in 0..3 {
            v[k][5] = q[k] as i32;
        }
    }

    #[inline(always)]
    fn pixel(&self, v: &Values) -> C {
        let q = v[5].max(1) as i64;
        let tu = wide::div_floor_i64(i64::from(v[3].max(0)) << self.current.shift[0], q);
        let tv = wide::div_floor_i64(i64::from(v[4].max(0)) << self.current.shift[1], q);
        let light = [0, 1, 2].map(|c| (v[c].max(0) as u32) >> 23);
        self.shade(tu, tv, light)
    }

    #[inline(always)]
    fn pixel_fused(&self, acc: &[u32; MAX_VARYINGS]) -> C {
        let q = NonZeroU64::new(u64::from(acc[5])).unwrap_or(NonZeroU64::MIN);
        let [su, sv] = self.current.shift;
        let u = wide::div_u64(u64::from(acc[3]) << su, q) as i64;
        let v = wide::div_u64(u64::from(acc[4]) << sv, q) as i64;
        self.shade(u, v, [acc[0] >> 23, acc[1] >> 23, acc[2] >> 23])
    }
}
