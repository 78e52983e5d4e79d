//! A textured, Gouraud-lit shader: the texel under each pixel times the light of its vertices.
//!
//! Per vertex the light is computed as [`super::GouraudLit`] does (the material's colours apply,
//! so a white diffuse colour gives the texture's own colours in full light), through the same
//! directional-light plan when it applies, and kept already scaled to the target's channel over
//! the texel's (`LIGHT_BITS`), so that a pixel's channel is one product and a shift; texture
//! coordinates are kept as the mesh gives them, and `1 / w` is taken from the vertex's clip-space
//! `w`.
//!
//! Perspective-correct coordinates, in integers: per triangle, the three `1 / w` are scaled
//! together to 31 bits (their ratios are all that matter) and the coordinates are made relative
//! to the whole texel before the triangle's smallest (a margin against wrapping), scaled to the
//! triangle's extent, and multiplied by them; the span loop interpolates `u / w`, `v / w` and
//! `1 / w` as 32-bit planes. Each pixel takes one 32-bit reciprocal of its `1 / w` (cut to 16
//! significant bits) and multiplies both coordinates by it: no 64-bit division, which a 32-bit
//! core pays a library call for. The coordinates are then exact to about `2^-14` of the
//! triangle's extent in texels (`docs/ACCURACY.md` measures it). The values use all 32 bits, so
//! the span loop gives them no fractional bits of its own (`FUSED_FRAC` 0). A pipeline that
//! interpolates every value perspective-correctly ([`crate::numerics::Perspective`]) gets affine
//! values here and corrects them itself.

use super::light::DirectionalPlan;
use super::model::{Shading, Stored, VertexIn};
use super::Lighting;
use crate::color::ShadeColor;
use crate::geom::MAX_VARYINGS;
use crate::math::{Mat4, Scalar};
use crate::texture::{Filter, Texture, Wrap};

/// Values per vertex: light r g b (see [`LIGHT_BITS`]), u, v (16.16 texture units) and `1 / w`.
type Values = [i32; 6];

/// Fractional bits of a light value: a channel's light is `lit max / texel_max 2^LIGHT_BITS`
/// plus [`LIGHT_MARGIN`], with `lit` in `0 ..= 1` and `max / texel_max` at most `255 / 31`
/// (below `2^3.05`), so below `2^31`. `lit max / texel_max` is the factor a texel channel
/// (`0 ..= texel_max`) is multiplied by to give the target's channel.
const LIGHT_BITS: u32 = 27;

/// Added to every light value: the planes' rounding may take a value up to
/// `(|dx| + |dy|) / 2 + 1` units below the exact one (at most `2^15` over the largest viewport),
/// and none may wrap below zero. It adds at most `63 2^16 / 2^27`, a thirtieth of a step, to a
/// channel.
const LIGHT_MARGIN: u32 = 1 << 16;

/// Bits of `max / texel_max` kept in a plan's scale (which must stay below `2^16`).
const SCALE_BITS: u32 = 12;

/// Each channel's `max / texel_max 2^SCALE_BITS`, rounded down (so that full light never rounds
/// a channel past its largest value): at most `255 2^12 / 31`, below `2^16`.
fn light_scale<C: ShadeColor>() -> [u32; 3] {
    [0, 1, 2].map(|c| (u32::from(C::MAX[c]) << SCALE_BITS) / TEXEL_MAX[c])
}

/// The largest value of each texel channel (Rgb565).
const TEXEL_MAX: [u32; 3] = [31, 63, 31];

/// The largest `1 / w` kept per vertex, as `2^Q_BITS / w`: with `w` at least the clipper's
/// smallest (`2^-8`), it stays below `2^31`.
const Q_BITS: u32 = 22;

/// What the pixels of the current triangle need to undo its scaling.
#[derive(Debug, Clone, Copy, Default)]
struct TriangleScale {
    /// The whole texel before the triangle's smallest, in x and y, as 16.16 texel units.
    base: [i64; 2],
    /// `u / w` was scaled down by `2^shift` texel units (16.16): `63 - shift` per axis, the
    /// pixel's shift back once its reciprocal's exponent is taken off ([`scaled_quotient`]).
    down: [u32; 2],
}

/// A textured mesh lit per vertex (Gouraud) with perspective-correct texture coordinates.
#[derive(Debug, Clone)]
pub struct TexturedLit<'t, S, C, const N: usize> {
    /// The lights, material and eye.
    pub lighting: Lighting<S, N>,
    /// This frame's lighting in model space, when the model matrix allows it.
    frame: Option<Lighting<S, N>>,
    /// This frame's lighting as a directional plan in light values, when it applies.
    plan: Option<DirectionalPlan<N>>,
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
            plan: None,
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
    /// with [`TexturedLit::sample_frac`] fractional bits.
    #[inline(always)]
    fn sample(&self, u: i64, v: i64) -> [u32; 3] {
        match self.filter {
            Filter::Nearest => self.texel((u >> 16) as i32, (v >> 16) as i32),
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

    /// Fractional bits of [`TexturedLit::sample`]'s channels: none for the nearest texel, 8 for
    /// the bilinear weights.
    #[inline(always)]
    fn sample_frac(&self) -> u32 {
        match self.filter {
            Filter::Nearest => 0,
            Filter::Bilinear => 8,
        }
    }

    /// The pixel's colour from its texel coordinates relative to the triangle's base texel and
    /// its light values (see [`LIGHT_BITS`]).
    #[inline(always)]
    fn shade(&self, u_rel: i64, v_rel: i64, light: [u32; 3]) -> C {
        let [bu, bv] = self.current.base;
        let t = self.sample(u_rel + bu, v_rel + bv);
        // Texel channel (below 2^(6 + frac)) times light (below 2^31, cut to 2^(25 - frac)):
        // below 2^31, and the half step for rounding keeps it below 2^32. The product has
        // LIGHT_BITS - 6 fractional bits.
        let cut = 6 + self.sample_frac();
        const S: u32 = LIGHT_BITS - 6;
        let mut out = [0u8; 3];
        for c in 0..3 {
            out[c] = ((t[c] * (light[c] >> cut) + (1 << (S - 1))) >> S) as u8;
        }
        C::from_shade(out)
    }

    /// The light values of a vertex from its lit sums: the plan's when it applies, else from
    /// [`Lighting::shade_sums`] (in `1 / (255² 2^16)` of full light, at most full).
    #[inline(always)]
    fn light(&self, v: &VertexIn<S>) -> [i32; 3] {
        if let Some(plan) = &self.plan {
            if let Some(s) = plan.sums(v.position, v.normal) {
                // Sums in units of 2^-32 of the scale, rounded in the bias.
                return s.map(|s| light_value((s >> 32) as u32));
            }
        }
        let lighting = self.frame.as_ref().unwrap_or(&self.lighting);
        let sums = lighting.shade_sums(v.position, v.normal);
        let scale = light_scale::<C>();
        [0, 1, 2].map(|c| {
            // sums scale < 2^32 2^16: shifted by 16 first, a quotient of u32s by 255²
            // (rounded), lit scale.
            let n =
                (sums[c].min((255 * 255) << 16) * u64::from(scale[c]) + ((255 * 255) << 15)) >> 16;
            light_value((n as u32) / (255 * 255))
        })
    }
}

/// The largest `lit scale` [`light_value`] takes: its value then stays below `2^31`.
const LIT_MAX: u32 = (i32::MAX as u32 - LIGHT_MARGIN) >> (LIGHT_BITS - SCALE_BITS);

/// A light value from `lit scale` (at most the scale, below `2^16`): in [`LIGHT_BITS`], with
/// the margin. The slots keep only `lit scale` ([`Stored`]), so every vertex's light is rounded
/// to it here (within `2^-13` of full light).
#[inline(always)]
fn light_value(lit_scale: u32) -> i32 {
    unpacked_light(lit_scale.min(LIT_MAX))
}

/// [`light_value`] for a `lit scale` already at most [`LIT_MAX`] (a slot's, clamped when it
/// was packed): no clamp per read.
#[inline(always)]
fn unpacked_light(lit_scale: u32) -> i32 {
    // Below 2^16 2^15 + 2^16 < 2^32: no u32 overflow for any 16-bit input.
    ((lit_scale << (LIGHT_BITS - SCALE_BITS)) + LIGHT_MARGIN) as i32
}

/// A vertex's values in five words, so that a vertex slot takes 32 bytes (a shift to index)
/// rather than 36: the lights' `lit scale` (below `2^16`, red and green in one word, green high:
/// below `2^15`, so the word is never `i32::MIN`, the empty mark), then blue, u, v and `1 / w`.
impl Stored<Values> for [i32; 5] {
    #[inline(always)]
    fn pack(v: &Values) -> Self {
        let l = |c: usize| {
            ((v[c].wrapping_sub(LIGHT_MARGIN as i32) as u32) >> (LIGHT_BITS - SCALE_BITS))
                .min(LIT_MAX)
        };
        [(l(0) | (l(1) << 16)) as i32, l(2) as i32, v[3], v[4], v[5]]
    }
    #[inline(always)]
    fn unpack(&self) -> Values {
        let rg = self[0] as u32;
        [
            unpacked_light(rg & 0xffff),
            unpacked_light(rg >> 16),
            unpacked_light((self[1] as u32) & 0xffff),
            self[2],
            self[3],
            self[4],
        ]
    }
}

/// `a 2^shift / q` for the pixel's interpolated `a` (`u / w` or `v / w`) and `q` (`1 / w`, at
/// least 1), from one reciprocal of `q` ([`reciprocal`]) and `down = 63 - shift`.
#[inline(always)]
fn scaled_quotient(a: u32, (r, lz): (u32, u32), down: u32) -> i64 {
    // a r < 2^64; 1 / q = r 2^(lz - 63), so a 2^shift / q = a r 2^(lz + shift - 63) and
    // lz + shift <= 31 + 32.
    ((u64::from(a) * u64::from(r)) >> (down - lz)) as i64
}

/// One reciprocal of `q >= 1` in 32-bit integers: `(r, lz)` with `1 / q ≈ r 2^(lz - 63)`: `q`
/// cut to its 16 leading bits `d` and `r = (2^32 - 1) / d 2^15` (one division of `u32`s, `r`
/// below `2^32`), within `2^-15` of the exact value (relative).
#[inline(always)]
fn reciprocal(q: u32) -> (u32, u32) {
    let q = q.max(1);
    let lz = q.leading_zeros();
    // q << lz has its top bit set: the seed is at most 2^17.
    (crate::numerics::reciprocal_seed(q << lz) << 15, lz)
}

impl<S: Scalar, C: ShadeColor, const N: usize> Shading<S> for TexturedLit<'_, S, C, N> {
    type Color = C;
    type Varyings = Values;
    type Stored = [i32; 5];
    const NEEDS_WORLD: bool = true;
    const NEEDS_UV: bool = true;
    const NEEDS_W: bool = true;
    const NEEDS_TRIANGLE: bool = true;
    const FUSED_FRAC: u32 = 0;
    const FUSED_OFFSET: u32 = 0;
    // Lights from LIGHT_MARGIN to below 2^31, texel coordinates a texel above zero and below
    // 2^31, 1 / w from 1 to below 2^31 (`triangle`): none wraps in a triangle.
    const FUSED_PAIRED: bool = true;

    fn begin_frame(&mut self, model: Option<&Mat4<S>>) -> bool {
        self.frame = model.and_then(|m| self.lighting.in_model_space(m));
        let lighting = self.frame.as_ref().unwrap_or(&self.lighting);
        // Sums of `scale 2^32` at full light, half a unit in the bias: shifted by 32 they are
        // `lit scale` rounded.
        self.plan = lighting.directional_plan(light_scale::<C>(), 32, [1 << 31; 3]);
        self.frame.is_some()
    }

    #[inline(always)]
    fn vertex(&mut self, v: &VertexIn<S>) -> Values {
        let light = self.light(v);
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
            self.current.base[a] = base << 16;
            self.current.down[a] = 63 - shift;
        }
        for k in 0..3 {
            v[k][5] = q[k] as i32;
        }
    }

    #[inline(always)]
    fn pixel(&self, v: &Values) -> C {
        let r = reciprocal(v[5].max(1) as u32);
        let [du, dv] = self.current.down;
        let u = scaled_quotient(v[3].max(0) as u32, r, du);
        let v_ = scaled_quotient(v[4].max(0) as u32, r, dv);
        let light = [0, 1, 2].map(|c| v[c].max(0) as u32);
        self.shade(u, v_, light)
    }

    #[inline(always)]
    fn pixel_fused(&self, acc: &[u32; MAX_VARYINGS]) -> C {
        let r = reciprocal(acc[5]);
        let [du, dv] = self.current.down;
        let u = scaled_quotient(acc[3], r, du);
        let v = scaled_quotient(acc[4], r, dv);
        self.shade(u, v, [acc[0], acc[1], acc[2]])
    }
}
