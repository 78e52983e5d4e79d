//! Shading models: what a vertex hands on to its triangle and what colour a pixel gets.
//!
//! Each model is its own type, so the pipeline compiles exactly the work it asks for: [`Unlit`]
//! interpolates nothing and computes no normals or world positions; [`FlatLit`] lights once per
//! triangle; [`GouraudLit`] once per vertex and interpolates the colour; [`PhongLit`] interpolates the
//! normal and the position and lights every pixel.

use super::light::{phong_triangle, DirectionalPlan, PowerTable};
use super::Lighting;
use crate::color::ShadeColor;
use crate::geom::{Varyings, MAX_VARYINGS};
use crate::math::{Mat4, Scalar, Vec3};
use embedded_graphics_core::pixelcolor::Rgb888;
use embedded_graphics_core::prelude::{PixelColor, RgbColor};

/// What a vertex slot ([`crate::pipeline::VertexSlot`]) keeps of a vertex's shader values, with a value meaning "not shaded
/// yet".
pub trait Packed: Copy + core::fmt::Debug {
    /// Not shaded yet.
    const EMPTY: Self;
    /// All bits zero: what a `static` scratch starts as (in `.bss`, costing no flash).
    const ZERO: Self;
    /// True for [`Packed::EMPTY`] (a value a shader may also produce is only recomputed).
    fn is_empty(&self) -> bool;
}

/// A packed form of the shader values `V`.
pub trait Stored<V>: Packed {
    /// Packs values.
    fn pack(v: &V) -> Self;
    /// The values back.
    fn unpack(&self) -> V;
}

impl<const N: usize> Packed for [i32; N] {
    const EMPTY: Self = [i32::MIN; N];
    const ZERO: Self = [0; N];
    #[inline(always)]
    fn is_empty(&self) -> bool {
        self.first() == Some(&i32::MIN)
    }
}

/// Any values, kept as they are.
impl<const N: usize> Stored<[i32; N]> for [i32; N] {
    #[inline(always)]
    fn pack(v: &[i32; N]) -> Self {
        *v
    }
    #[inline(always)]
    fn unpack(&self) -> [i32; N] {
        *self
    }
}

impl Packed for [u16; 3] {
    const EMPTY: Self = [u16::MAX; 3];
    const ZERO: Self = [0; 3];
    #[inline(always)]
    fn is_empty(&self) -> bool {
        self[0] == u16::MAX
    }
}

/// Three values in `0 ..= 65534` (the colour shaders' channels), in six bytes.
impl Stored<[i32; 3]> for [u16; 3] {
    #[inline(always)]
    fn pack(v: &[i32; 3]) -> Self {
        v.map(|c| c.clamp(0, 65534) as u16)
    }
    #[inline(always)]
    fn unpack(&self) -> [i32; 3] {
        self.map(i32::from)
    }
}

/// What the pipeline knows about a vertex when the shader sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VertexIn<S> {
    /// Position in world space (zero unless the shader asks for it).
    pub position: Vec3<S>,
    /// Normal in world space, not normalised (zero unless the shader asks for it).
    pub normal: Vec3<S>,
    /// The mesh's vertex colour, white when the mesh has none.
    pub color: Rgb888,
    /// The mesh's texture coordinates (16.16, [`crate::texture`]); zero unless the shader asks
    /// for them ([`Shading::NEEDS_UV`]) and the mesh has them.
    pub uv: [i32; 2],
}

/// A shading model.
pub trait Shading<S: Scalar> {
    /// The colour it produces.
    type Color: PixelColor;
    /// The values it interpolates across a triangle.
    type Varyings: Varyings;
    /// What the vertex scratch keeps of them ([`crate::pipeline::VertexSlot`]).
    type Stored: Stored<Self::Varyings>;
    /// The shader reads world positions and normals (the pipeline skips them otherwise).
    const NEEDS_WORLD: bool;
    /// The shader does work per triangle in [`Shading::face`] (the pipeline skips the call and
    /// the world data it needs otherwise).
    const NEEDS_FACE: bool = false;
    /// Called when a draw starts, with the model matrix when normals follow it (no
    /// [`crate::pipeline::Pipeline::set_normal_matrix`]). A shader that can light in model space (with its
    /// lights and eye moved there once) returns true; the pipeline then hands it model-space
    /// positions and normals, saving their transforms per vertex. The default returns false:
    /// world space.
    fn begin_frame(&mut self, _model: Option<&Mat4<S>>) -> bool {
        false
    }
    /// Feeds everything that decides the shader's colours to `out`, for a frame list that
    /// compares frames ([`crate::frame::changed_areas`]). The default writes the `Debug` form,
    /// which holds every field; the lit shaders write their lighting's settings, far faster.
    fn fingerprint(&self, out: &mut crate::fingerprint::Fingerprint)
    where
        Self: core::fmt::Debug,
    {
        use core::fmt::Write;
        let _ = write!(out, "{self:?}");
    }
    /// The shader reads texture coordinates ([`VertexIn::uv`]; zero otherwise).
    const NEEDS_UV: bool = false;
    /// The shader's values depend on the vertex's clip-space `w` ([`Shading::project`]).
    const NEEDS_W: bool = false;
    /// Per vertex: the values to interpolate.
    fn vertex(&mut self, v: &VertexIn<S>) -> Self::Varyings;
    /// Per vertex: the values as the vertex scratch keeps them, always
    /// `Stored::pack(&self.vertex(v))`. A shader whose values are known to lie in the packed
    /// range overrides it to skip the packing's clamps.
    #[inline(always)]
    fn vertex_stored(&mut self, v: &VertexIn<S>) -> Self::Stored {
        Self::Stored::pack(&self.vertex(v))
    }
    /// With [`Shading::NEEDS_W`], per vertex after [`Shading::vertex`] and again for every vertex
    /// the clipper makes (whose other values are interpolated in clip space): sets what depends
    /// on the vertex's clip-space `w` (`w > 0`), such as `1 / w` for perspective-correct values.
    /// Not called by pipelines that interpolate every value perspective-correctly
    /// ([`crate::numerics::Numerics::PERSPECTIVE`]).
    #[inline(always)]
    fn project(&self, v: &mut Self::Varyings, w: S) {
        let _ = (v, w);
    }
    /// The shader rescales each triangle's values in [`Shading::triangle`] (the pipeline skips
    /// the call otherwise).
    const NEEDS_TRIANGLE: bool = false;
    /// With [`Shading::NEEDS_TRIANGLE`], once per screen triangle, before its pixels: may rescale its three vertices' values (and
    /// keep what the pixels need to undo it). The values of a vertex are the same for every
    /// triangle, so this is where a shader adapts their scale to one triangle.
    #[inline(always)]
    fn triangle(&mut self, v: &mut [Self::Varyings; 3]) {
        let _ = v;
    }
    /// Once per visible triangle, before its pixels. The vertices come in the order whose edges'
    /// cross product `(v1 - v0) x (v2 - v0)` points out of the mesh's front face in the space
    /// the shader lights in, also under a mirroring model matrix (which the pipeline undoes by
    /// swapping two of them).
    fn face(&mut self, _vertices: &[VertexIn<S>; 3]) {}
    /// Per pixel: the colour from the interpolated values.
    fn pixel(&self, v: &Self::Varyings) -> Self::Color;
    /// Bounds, `lo ..= hi`, that every value of every vertex lies within (from
    /// [`Shading::vertex`], [`Shading::vertex_stored`] unpacked, and so from the clipper's mixes
    /// of them), when the shader's own arithmetic keeps them there: a pipeline need then not
    /// test them. The default claims nothing. A shader whose values leave the range it declares
    /// gets wrong colours (never a panic).
    const VALUE_RANGE: (i32, i32) = (i32::MIN, i32::MAX);
    /// Fractional bits the default path's fused span loop gives each value as it steps across a
    /// triangle (at most 16). Every value times `2^FUSED_FRAC` must fit an `i32`, or a `u32` for
    /// values that are never negative.
    const FUSED_FRAC: u32 = 16;
    /// Added to every value (in units of `2^-FUSED_FRAC`) where a span starts: half a unit by
    /// default, so that a shift by `FUSED_FRAC` rounds.
    const FUSED_OFFSET: u32 = (1 << Self::FUSED_FRAC) >> 1;
    /// Every value the fused span loop steps (times `2^FUSED_FRAC`, plus the offset) stays
    /// within `0 .. 2^32` at every pixel of a triangle, by the shader's own margins against the
    /// planes' rounding: the loop may then step the values in pairs, each pair one 64-bit sum
    /// (fewer registers on a 64-bit core, the same pixels). A shader that claims it and lets a
    /// value wrap gets a value of the pair wrong by a unit of its last bit (never a panic).
    const FUSED_PAIRED: bool = false;
    /// Per pixel in the fused span loop: `acc[i]` is value `i` times `2^FUSED_FRAC`, plus
    /// [`Shading::FUSED_OFFSET`], wrapping. By default each value is shifted back (rounded) and
    /// handed to [`Shading::pixel`].
    #[inline(always)]
    fn pixel_fused(&self, acc: &[u32; MAX_VARYINGS]) -> Self::Color {
        let mut v = Self::Varyings::default();
        for (out, a) in v.as_mut_slice().iter_mut().zip(acc) {
            *out = (*a as i32) >> Self::FUSED_FRAC;
        }
        self.pixel(&v)
    }
    /// [`Shading::pixel_fused`] for a pipeline that dithers ([`crate::numerics::Dither`]):
    /// `threshold` (below 256) is the pixel's share of one step of the target, in 256ths, to
    /// add before truncating instead of the half step that rounds. Shaders without an
    /// interpolated colour ignore it.
    #[inline(always)]
    fn pixel_fused_dithered(&self, acc: &[u32; MAX_VARYINGS], threshold: u32) -> Self::Color {
        let _ = threshold;
        self.pixel_fused(acc)
    }
}

/// Fractional bits of a channel of largest value `max` as the colour shaders interpolate it: as
/// many as keep `max + 1/2` below `2^16`.
const fn channel_frac(max: u8) -> u32 {
    8 + max.leading_zeros()
}

/// The values [`target_channels`] (and a directional plan's sums made the same way) can give:
/// from the half step of no light, `2^(frac - 1)`, to full light plus it, `max 2^frac +
/// 2^(frac - 1)`, over the three channels.
const fn channel_range(max: [u8; 3]) -> (i32, i32) {
    let (mut lo, mut hi) = (i32::MAX, 0);
    let mut c = 0;
    while c < 3 {
        let f = channel_frac(max[c]);
        let half = 1 << (f - 1);
        let full = ((max[c] as i32) << f) + half;
        if half < lo {
            lo = half;
        }
        if full > hi {
            hi = full;
        }
        c += 1;
    }
    (lo, hi)
}

/// A colour's three channels at the target's depth, each with [`channel_frac`] fractional bits
/// and half a step added (so the fused loop's shift rounds), from `num[c] / den` 8-bit steps.
///
/// `den` is 1 (8-bit colours) or `255 · 2^16` (lit sums) at every caller, and `num <= 255 den`:
/// both are then quotients of `u32`s (a single instruction, or a multiply by a constant, on a
/// 32-bit core) with the same round-half-up result as one `u64` division.
#[inline(always)]
pub(super) fn target_channels<C: ShadeColor>(num: [u64; 3], den: u64) -> [i32; 3] {
    let mut out = [0i32; 3];
    for c in 0..3 {
        let f = channel_frac(C::MAX[c]);
        // num <= 255 den, so the product stays below 2^40 den.
        let n = (num[c] * u64::from(C::MAX[c])) << f;
        let q = if den == 1 {
            // n <= 255 · max 2^f < 2^24.
            (n as u32 + 127) / 255
        } else if den == 255 << 16 {
            // floor((n + d/2) / d) with d = 255² 2^16: the low 16 bits drop first (nested floors),
            // leaving a quotient of u32s, as n < 255³ 2^16 max 2^f / 255 < 2^48.
            (((n + 255 * 255 * (1 << 15)) >> 16) as u32) / (255 * 255)
        } else {
            let d = den * 255;
            let nz = core::num::NonZeroU64::new(d).unwrap_or(core::num::NonZeroU64::MIN);
            crate::wide::div_u64(n + d / 2, nz) as u32
        };
        out[c] = q as i32 + (1 << (f - 1));
    }
    out
}

/// A lit colour from [`Lighting::shade_sums`] at the target's depth, rounded once.
#[inline(always)]
pub(super) fn from_sums<C: ShadeColor>(sums: [u64; 3]) -> C {
    // sums[c] / (255 · 2^16) 8-bit steps, times max / 255, rounded half up: the low 16 bits of
    // the divisor first (nested floors), then a quotient of u32s (sums <= 255² 2^16, so
    // sums · max < 2^48).
    let ch = |c: usize| {
        let n = sums[c] * u64::from(C::MAX[c]) + 255 * 255 * (1 << 15);
        (((n >> 16) as u32) / (255 * 255)) as u8
    };
    C::from_shade([ch(0), ch(1), ch(2)])
}

/// The colour from interpolated [`target_channels`] (each shifted back by `shift` bits first).
#[inline(always)]
pub(super) fn from_target<C: ShadeColor>(v: [u32; 3], shift: u32) -> C {
    let ch = |c: usize| (v[c] >> (shift + channel_frac(C::MAX[c]))) as u8;
    C::from_shade([ch(0), ch(1), ch(2)])
}

/// [`from_target`] with `threshold` 256ths of a step in place of the half step the channels
/// carry, then truncated: ordered dithering. The channels' bound (`max + 1/2` steps below
/// `2^(16 + shift)`) keeps the sum below `2^32`, and the threshold is at least half a 256th,
/// more than the interpolation's error, so it does not wrap below zero either.
#[inline(always)]
pub(super) fn from_target_dithered<C: ShadeColor>(v: [u32; 3], shift: u32, threshold: u32) -> C {
    let ch = |c: usize| {
        let s = shift + channel_frac(C::MAX[c]);
        let t = (threshold << (s - 8)).wrapping_sub(1 << (s - 1));
        (v[c].wrapping_add(t) >> s) as u8
    };
    C::from_shade([ch(0), ch(1), ch(2)])
}

/// The pixel methods of a shader whose values are the three channels at the target's depth
/// ([`target_channels`]): one definition for every such shader (vertex colours, Gouraud,
/// MatCap). Expands inside an `impl Shading<S> for ...` whose colour is `C`.
macro_rules! channel_pixels {
    () => {
        #[inline(always)]
        fn pixel(&self, v: &[i32; 3]) -> C {
            $crate::shade::model::from_target(v.map(|x| x.max(0) as u32), 0)
        }
        #[inline(always)]
        fn pixel_fused(&self, acc: &[u32; $crate::geom::MAX_VARYINGS]) -> C {
            $crate::shade::model::from_target(
                [acc[0], acc[1], acc[2]],
                <Self as $crate::shade::Shading<S>>::FUSED_FRAC,
            )
        }
        #[inline(always)]
        fn pixel_fused_dithered(
            &self,
            acc: &[u32; $crate::geom::MAX_VARYINGS],
            threshold: u32,
        ) -> C {
            $crate::shade::model::from_target_dithered(
                [acc[0], acc[1], acc[2]],
                <Self as $crate::shade::Shading<S>>::FUSED_FRAC,
                threshold,
            )
        }
    };
}
pub(super) use channel_pixels;

/// One colour, no lighting.
#[derive(Debug, Clone, Copy)]
pub struct Unlit<C> {
    /// The colour.
    pub color: C,
}

impl<S: Scalar, C: PixelColor> Shading<S> for Unlit<C> {
    type Color = C;
    type Varyings = [i32; 0];
    type Stored = [i32; 0];
    const NEEDS_WORLD: bool = false;
    #[inline(always)]
    fn vertex(&mut self, _: &VertexIn<S>) -> [i32; 0] {
        []
    }
    #[inline(always)]
    fn pixel(&self, _: &[i32; 0]) -> C {
        self.color
    }
}

/// The mesh's vertex colours interpolated, no lighting.
#[derive(Debug, Clone, Copy, Default)]
pub struct VertexColors<C> {
    _c: core::marker::PhantomData<C>,
}

impl<C> VertexColors<C> {
    /// The shader.
    pub const fn new() -> Self {
        Self {
            _c: core::marker::PhantomData,
        }
    }
}

/// The colour shaders' values: the three channels at the target's depth, each with as many
/// fractional bits as keep it below 2^16 and half a step added, so that the fused loop rounds with
/// a shift.
impl<S: Scalar, C: ShadeColor> Shading<S> for VertexColors<C> {
    type Color = C;
    type Varyings = [i32; 3];
    type Stored = [u16; 3];
    const NEEDS_WORLD: bool = false;
    const FUSED_OFFSET: u32 = 0;
    #[inline(always)]
    fn vertex(&mut self, v: &VertexIn<S>) -> [i32; 3] {
        target_channels::<C>([v.color.r(), v.color.g(), v.color.b()].map(u64::from), 1)
    }
    channel_pixels!();
}

/// Lit once per triangle with the face normal (the cross product of its edges in world space).
#[derive(Debug, Clone)]
pub struct FlatLit<S, C, const N: usize> {
    /// The lights, material and eye.
    pub lighting: Lighting<S, N>,
    /// This frame's lighting in model space, when the model matrix allows it.
    frame: Option<Lighting<S, N>>,
    /// This frame's lighting as a directional plan in `shade_sums`' units, when it applies.
    plan: Option<DirectionalPlan<N>>,
    color: C,
}

impl<S: Scalar, C: ShadeColor, const N: usize> FlatLit<S, C, N> {
    /// The shader.
    pub fn new(lighting: Lighting<S, N>) -> Self {
        Self {
            lighting,
            frame: None,
            plan: None,
            color: C::from_shade([0; 3]),
        }
    }
}

impl<S: Scalar, C: ShadeColor, const N: usize> Shading<S> for FlatLit<S, C, N> {
    fn fingerprint(&self, out: &mut crate::fingerprint::Fingerprint)
    where
        Self: core::fmt::Debug,
    {
        self.lighting.fingerprint(out);
    }
    type Color = C;
    type Varyings = [i32; 0];
    type Stored = [i32; 0];
    const NEEDS_WORLD: bool = true;
    const NEEDS_FACE: bool = true;
    #[inline(always)]
    fn vertex(&mut self, _: &VertexIn<S>) -> [i32; 0] {
        []
    }
    fn face(&mut self, v: &[VertexIn<S>; 3]) {
        self.color = from_sums(flat_face_sums(self, v));
    }
    fn begin_frame(&mut self, model: Option<&Mat4<S>>) -> bool {
        self.frame = model.and_then(|m| self.lighting.in_model_space(m));
        let lighting = self.frame.as_ref().unwrap_or(&self.lighting);
        // 255² 2^16 is full intensity in `shade_sums`' units: the products are then exact.
        self.plan = lighting.directional_plan([255 * 255; 3], 16, [0; 3]);
        self.frame.is_some()
    }
    #[inline(always)]
    fn pixel(&self, _: &[i32; 0]) -> C {
        self.color
    }
}

/// A triangle's lit sums ([`Lighting::shade_sums`]) as [`FlatLit`] lights it: with the face
/// normal, at the centroid.
#[inline(always)]
pub(super) fn flat_face_sums<S: Scalar, C, const N: usize>(
    flat: &FlatLit<S, C, N>,
    v: &[VertexIn<S>; 3],
) -> [u64; 3] {
    let normal = Vec3::face_normal(v[0].position, v[1].position, v[2].position);
    // The centroid, for point lights and the specular term.
    let third = S::from_ratio(1, 3);
    let centre = (v[0].position + v[1].position + v[2].position).scale(third);
    if let Some(sums) = flat.plan.as_ref().and_then(|p| p.sums(centre, normal)) {
        return sums;
    }
    let lighting = flat.frame.as_ref().unwrap_or(&flat.lighting);
    lighting.shade_sums(centre, normal)
}

/// Sets a [`FlatLit`]'s colour for the triangle from lit sums, rounded once.
#[inline(always)]
pub(super) fn set_flat_sums<S, C: ShadeColor, const N: usize>(
    flat: &mut FlatLit<S, C, N>,
    sums: [u64; 3],
) {
    flat.color = from_sums(sums);
}

/// Lit per vertex with the mesh's normals; the lit colour is interpolated (Gouraud shading).
#[derive(Debug, Clone)]
pub struct GouraudLit<S, C, const N: usize> {
    /// The lights, material and eye.
    pub lighting: Lighting<S, N>,
    /// This frame's lighting in model space, when the model matrix allows it.
    frame: Option<Lighting<S, N>>,
    /// This frame's lighting as a directional plan in the target's channel units, when it
    /// applies.
    plan: Option<DirectionalPlan<N>>,
    _c: core::marker::PhantomData<C>,
}

impl<S: Scalar, C, const N: usize> GouraudLit<S, C, N> {
    /// The shader.
    pub fn new(lighting: Lighting<S, N>) -> Self {
        Self {
            lighting,
            frame: None,
            plan: None,
            _c: core::marker::PhantomData,
        }
    }
}

/// Each channel's value of full intensity at the target's depth with [`channel_frac`]
/// fractional bits: the scale of [`target_channels`], for a [`DirectionalPlan`].
fn target_scale<C: ShadeColor>() -> [u32; 3] {
    [0, 1, 2].map(|c| u32::from(C::MAX[c]) << channel_frac(C::MAX[c]))
}

/// Fractional bits of a [`DirectionalPlan`]'s sums below the unit of its scale.
const PLAN_BITS: u32 = 32;

impl<S: Scalar, C: ShadeColor, const N: usize> Shading<S> for GouraudLit<S, C, N> {
    fn fingerprint(&self, out: &mut crate::fingerprint::Fingerprint)
    where
        Self: core::fmt::Debug,
    {
        self.lighting.fingerprint(out);
    }
    type Color = C;
    type Varyings = [i32; 3];
    type Stored = [u16; 3];
    const NEEDS_WORLD: bool = true;
    const FUSED_OFFSET: u32 = 0;
    const VALUE_RANGE: (i32, i32) = channel_range(C::MAX);
    fn begin_frame(&mut self, model: Option<&Mat4<S>>) -> bool {
        self.frame = model.and_then(|m| self.lighting.in_model_space(m));
        let lighting = self.frame.as_ref().unwrap_or(&self.lighting);
        // Rounding half up and the fused loop's half step, both in the plan's bias: a channel
        // is then its sum shifted.
        let bias = [0, 1, 2]
            .map(|c| (1 << (PLAN_BITS - 1)) + (1u64 << (channel_frac(C::MAX[c]) - 1 + PLAN_BITS)));
        self.plan = lighting.directional_plan(target_scale::<C>(), PLAN_BITS, bias);
        self.frame.is_some()
    }
    #[inline(always)]
    fn vertex(&mut self, v: &VertexIn<S>) -> [i32; 3] {
        if let Some(plan) = &self.plan {
            if let Some(s) = plan.sums(v.position, v.normal) {
                return s.map(|s| (s >> PLAN_BITS) as i32);
            }
        }
        self.vertex_general(v)
    }
    #[inline(always)]
    fn vertex_stored(&mut self, v: &VertexIn<S>) -> [u16; 3] {
        if let Some(plan) = &self.plan {
            if let Some(s) = plan.sums(v.position, v.normal) {
                // A sum is at most its full value, `max 2^frac` plus the bias (below
                // `2^(frac - 1)` after the shift), which `channel_frac` keeps below 65,408:
                // within the packed range, so the packing's clamps would change nothing.
                return s.map(|s| (s >> PLAN_BITS) as u16);
            }
        }
        <[u16; 3] as Stored<[i32; 3]>>::pack(&self.vertex_general(v))
    }
    channel_pixels!();
}

impl<S: Scalar, C: ShadeColor, const N: usize> GouraudLit<S, C, N> {
    /// A vertex's values where the directional plan does not apply.
    #[inline(always)]
    fn vertex_general(&self, v: &VertexIn<S>) -> [i32; 3] {
        let lighting = self.frame.as_ref().unwrap_or(&self.lighting);
        target_channels::<C>(lighting.shade_sums(v.position, v.normal), 255 << 16)
    }
}

/// Lit per pixel: the normal and the world position are interpolated (in 16.16) and lit at every
/// pixel (Phong shading).
///
/// For a fixed-point format whose lights are all directional (Blinn-Phong or no highlight), a
/// draw interpolates the unit normal in 2.30 instead, and the view vector `eye - position`
/// scaled per triangle so that it is about unit length. Each pixel takes both lengths from a
/// small table and one Newton step, `N·H = (N·L + N·V) / |L + V|` from the cosines with one
/// reciprocal square root (none where the highlight is known to be zero) and the specular
/// power from a table made per draw, with no division (its error against `f64` is in
/// `docs/ACCURACY.md` and `tests/tests/lighting_plan.rs`).
#[derive(Debug, Clone)]
pub struct PhongLit<S, C, const N: usize> {
    /// The lights, material and eye.
    pub lighting: Lighting<S, N>,
    /// This frame's lighting in model space, when the model matrix allows it.
    frame: Option<Lighting<S, N>>,
    /// This frame's lighting as a directional plan: `target` in the target's channel steps,
    /// `sums` in the units of [`Lighting::shade_sums`] (for fog), when it applies.
    target: Option<DirectionalPlan<N>>,
    sums: Option<DirectionalPlan<N>>,
    /// The plans' specular power by table.
    power: PowerTable,
    _c: core::marker::PhantomData<C>,
}

impl<S: Scalar, C, const N: usize> PhongLit<S, C, N> {
    /// The shader.
    pub fn new(lighting: Lighting<S, N>) -> Self {
        Self {
            lighting,
            frame: None,
            target: None,
            sums: None,
            power: PowerTable::none(),
            _c: core::marker::PhantomData,
        }
    }
}

impl<S: Scalar, C: ShadeColor, const N: usize> Shading<S> for PhongLit<S, C, N> {
    fn fingerprint(&self, out: &mut crate::fingerprint::Fingerprint)
    where
        Self: core::fmt::Debug,
    {
        self.lighting.fingerprint(out);
    }
    type Color = C;
    type Varyings = [i32; 6];
    type Stored = [i32; 6];
    const NEEDS_WORLD: bool = true;
    // 16.16 normals and positions use all 32 bits: no room for more fractional bits.
    const FUSED_FRAC: u32 = 0;
    // Under a plan, each triangle's view vectors are scaled to unit length.
    const NEEDS_TRIANGLE: bool = true;
    #[inline(always)]
    fn triangle(&mut self, v: &mut [[i32; 6]; 3]) {
        if self.target.is_some() {
            phong_triangle(v);
        }
    }
    fn begin_frame(&mut self, model: Option<&Mat4<S>>) -> bool {
        self.frame = model.and_then(|m| self.lighting.in_model_space(m));
        let lighting = self.frame.as_ref().unwrap_or(&self.lighting);
        // Rounded half up by the bias.
        let half = [1 << (PLAN_BITS - 1); 3];
        self.target = lighting.directional_plan(C::MAX.map(u32::from), PLAN_BITS, half);
        // 255² 2^16 is full intensity in `shade_sums`' units: the products are then exact.
        self.sums = lighting.directional_plan([255 * 255; 3], 16, [0; 3]);
        // Both or neither: they decide what the vertices' values are.
        if self.target.is_none() || self.sums.is_none() {
            (self.target, self.sums) = (None, None);
        }
        if let Some(plan) = &self.target {
            self.power.make(plan.table_shininess());
        }
        self.frame.is_some()
    }
    #[inline(always)]
    fn vertex(&mut self, v: &VertexIn<S>) -> [i32; 6] {
        if let Some(plan) = &self.target {
            return plan.phong_vertex(v.position, v.normal);
        }
        // Unit normals keep the interpolated normal's scale even across a long triangle.
        let n = v.normal.normalize().unwrap_or_default();
        let p = v.position;
        [n.x, n.y, n.z, p.x, p.y, p.z].map(S::to_fx16_bits)
    }
    #[inline(always)]
    fn pixel(&self, v: &[i32; 6]) -> C {
        if let Some(plan) = &self.target {
            let s = plan.phong_pixel_unclamped(v, &self.power);
            // The plan's full intensity is `MAX << PLAN_BITS` plus a bias below `2^PLAN_BITS`,
            // so clamping after the shift (which keeps the order) clamps to `MAX`: the same.
            let ch = |c: usize| ((s[c] >> PLAN_BITS) as u32).min(u32::from(C::MAX[c])) as u8;
            return C::from_shade([ch(0), ch(1), ch(2)]);
        }
        from_sums(phong_sums(self, v))
    }
}

/// The lit sums ([`Lighting::shade_sums`]) of a pixel of [`PhongLit`] from its interpolated
/// normal and position.
#[inline(always)]
pub(super) fn phong_sums<S: Scalar, C, const N: usize>(
    phong: &PhongLit<S, C, N>,
    v: &[i32; 6],
) -> [u64; 3] {
    if let Some(plan) = &phong.sums {
        return plan.phong_pixel(v, &phong.power);
    }
    let f = |i: usize| S::from_fx16_bits(v[i]);
    let normal = Vec3::new(f(0), f(1), f(2));
    let position = Vec3::new(f(3), f(4), f(5));
    let lighting = phong.frame.as_ref().unwrap_or(&phong.lighting);
    lighting.shade_sums(position, normal)
}
