//! Fog: a shading model's colour mixed toward a fog colour by the depth of each vertex.
//!
//! [`Fog`] wraps a shading model with a colour to mix. A colour-interpolating one ([`GouraudLit`],
//! [`VertexColors`], [`super::MatCap`], or [`FlatLit`] once per triangle) has each vertex's colour mixed toward the
//! fog colour before the triangle interpolates it, so fogging costs a few integer operations per
//! vertex and nothing per pixel: the span loop runs the inner model's own pixel code.
//! [`PhongLit`], which makes its colour per pixel, interpolates the share of fog of its vertices
//! as one more value and mixes each pixel's lit colour by it before rounding: one interpolated
//! value and three multiply-adds per pixel. A pipeline without [`Fog`] compiles none of it.
//!
//! # The model
//! The depth `d` of a point is its distance in front of the camera along the view direction:
//! `-z` in view space (the camera of [`Mat4::look_at`] looks down `-z`), not the distance to the
//! eye, so fog is flat across the screen at a given depth, as in fixed-function fog. With
//! `t = (d - start) / (end - start)` clamped to `[0, 1]`, the share of fog is
//!
//! ```text
//! linear:       a = t
//! exponential:  a = (1 - e^(-k t)) / (1 - e^(-k))
//! ```
//!
//! and the colour is `c + (fog - c) a`. Nothing is fogged nearer than `start` and everything is
//! fog colour beyond `end`; the exponential curve of density `k` thickens fast near `start` and
//! slowly near `end` (it is fixed-function `EXP` fog of density `k / (end - start)` starting at
//! `start`, stretched to reach full fog at `end`).
//!
//! # Arithmetic
//! The depth is one dot product of the vertex's position with a plane taken from the view matrix
//! (times the model matrix when the inner model shades in model space), rounded once in the
//! geometry's [`Scalar`]; `t` is one exactly rounded ratio in 0.15 fixed point. The exponential
//! curve is a table of 33 amounts in 0.15 ([`FogCurve::exponential`], computed with integers
//! only), interpolated linearly between its entries: within `k² / (8192 (1 - e^-k))` of the
//! curve (below 0.008 for the largest density, 8), plus half a step of 0.15. The colour channels
//! are mixed at the target's depth in the inner model's own fixed point, rounded once, so a share
//! of 0 leaves them untouched and a share of 1 gives the fog colour exactly. [`PhongLit`]'s share
//! is the vertices' 0.15 shares, interpolated in 0.30 (so the interpolation adds no error beyond
//! a step of 0.30): a pixel's share lies between its vertices' as a Gouraud pixel's colour does,
//! and where the three shares are unclamped the interpolated share is the share at the pixel's
//! interpolated position, as linear fog is linear in position. Its lit sums are mixed with it
//! before their one rounding, as [`FlatLit`]'s are.
//!
//! [`Mat4::look_at`]: crate::math::Mat4::look_at

use super::model::{flat_face_sums, from_sums, phong_sums, set_flat_sums, target_channels};
use super::{FlatLit, GouraudLit, PhongLit, Shading, Stored, VertexColors, VertexIn};
use crate::color::ShadeColor;
use crate::geom::{Varyings, MAX_VARYINGS};
use crate::math::{Mat4, Scalar, Vec3};
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

/// 1.0 in the 0.15 fixed point of a fog share.
pub const FOG_ONE: u32 = 1 << 15;

/// Entries of a fog curve's table: the shares at `t = 0, 1/32, ..., 1`.
pub const FOG_TABLE_LEN: usize = 33;

/// The largest density of [`FogCurve::exponential`], in sixteenths (`k = 8`): beyond it the
/// table's linear pieces would miss the curve by more than a percent near `start`.
pub const FOG_MAX_DENSITY: u16 = 8 * 16;

/// How fog thickens from `start` to `end`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FogCurve {
    /// In proportion to depth: `a = t`, exact.
    Linear,
    /// A table of the shares at `t = i / 32` in 0.15 fixed point ([`FOG_ONE`] is all fog),
    /// interpolated linearly. [`FogCurve::exponential`] makes one; any other curve can be given
    /// (entries above [`FOG_ONE`] count as [`FOG_ONE`]).
    Table([u16; FOG_TABLE_LEN]),
}

impl FogCurve {
    /// The exponential curve `(1 - e^(-k t)) / (1 - e^(-k))` of density `k = density / 16`, at
    /// most 8 ([`FOG_MAX_DENSITY`]; larger densities are taken as 8). Density 0 is
    /// [`FogCurve::Linear`], the curve's limit. Integers only, so it can be a constant:
    /// `const CURVE: FogCurve = FogCurve::exponential(48);`.
    pub const fn exponential(density: u16) -> Self {
        if density == 0 {
            return Self::Linear;
        }
        let density = if density > FOG_MAX_DENSITY {
            FOG_MAX_DENSITY
        } else {
            density
        } as u128;
        // In 1.63 fixed point: r = e^(-k / 32) by its series, whose terms term_n =
        // term_(n-1) k / (32 n) need no multiplication of fixed-point values (k / 32 <= 1/4, so
        // the terms fall below the last bit within 20 steps and the sum stays in (0, 1]).
        let one: u128 = 1 << 63;
        let mut term = one;
        let mut r = one;
        let mut n = 1;
        while term != 0 {
            term = term * density / (512 * n);
            r = if n % 2 == 1 { r - term } else { r + term };
            n += 1;
        }
        // e^(-k i / 32) = r^i, each product rounded (below 2^126, so it fits).
        let mut powers = [0u128; FOG_TABLE_LEN];
        powers[0] = one;
        let mut i = 1;
        while i < FOG_TABLE_LEN {
            powers[i] = (powers[i - 1] * r + (1 << 62)) >> 63;
            i += 1;
        }
        let full = one - powers[FOG_TABLE_LEN - 1];
        let mut table = [0u16; FOG_TABLE_LEN];
        let mut i = 0;
        while i < FOG_TABLE_LEN {
            // (1 - r^i) 2^15 / (1 - r^32), rounded: below 2^78.
            let num = (one - powers[i]) * FOG_ONE as u128;
            table[i] = ((num + full / 2) / full) as u16;
            i += 1;
        }
        Self::Table(table)
    }

    /// The share of fog at `t` (0.15, clamped to `0 ..= FOG_ONE`), in 0.15.
    #[inline]
    pub fn share(&self, t: u32) -> u32 {
        let t = t.min(FOG_ONE);
        match self {
            Self::Linear => t,
            Self::Table(table) => {
                // 32 pieces of 2^10 steps of t each.
                let i = (t >> 10) as usize;
                let f = t & 0x3FF;
                let a = u32::from(table[i.min(FOG_TABLE_LEN - 1)]);
                let b = u32::from(table[(i + 1).min(FOG_TABLE_LEN - 1)]);
                // a + (b - a) f / 2^10 rounded, as a weighted sum so a falling table works too.
                let v = (a * (0x400 - f) + b * f + 0x200) >> 10;
                v.min(FOG_ONE)
            }
        }
    }
}

/// The fog's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FogSettings<S> {
    /// The colour of the fog.
    pub color: Rgb888,
    /// The depth where fog begins (none nearer).
    pub start: S,
    /// The depth where only fog is seen. At or before `start`, fog is a step: none nearer than
    /// `start`, all of it from `start` on.
    pub end: S,
    /// How it thickens in between.
    pub curve: FogCurve,
}

/// The fog colour as a fogged shading model mixes toward it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FogColor {
    rgb: Rgb888,
    channels: [i32; 3],
    /// In the units of the lit sums: `1 / (255 · 2^16)` of an 8-bit step.
    sums: [u64; 3],
}

impl FogColor {
    /// The fog colour for shading models of colour `C`.
    pub fn new<C: ShadeColor>(rgb: Rgb888) -> Self {
        let rgb8 = [rgb.r(), rgb.g(), rgb.b()].map(u64::from);
        Self {
            rgb,
            channels: target_channels::<C>(rgb8, 1),
            sums: rgb8.map(|c| (c * 255) << 16),
        }
    }

    /// The colour.
    pub fn rgb(&self) -> Rgb888 {
        self.rgb
    }

    /// The three channels in the form [`GouraudLit`] and [`VertexColors`] interpolate: at the
    /// target's depth, with as many fractional bits as keep each below `2^16`, plus half a step.
    pub fn channels(&self) -> [i32; 3] {
        self.channels
    }
}

/// A shading model [`Fog`] can fog: it mixes its colour toward the fog colour, per vertex (in
/// its interpolated values), per triangle, or per pixel by an interpolated share.
pub trait Foggable<S: Scalar>: Shading<S> {
    /// The model's colour is one per triangle, made in [`Shading::face`]: [`Fog`] fogs it by
    /// the triangle's centroid with [`Foggable::fog_face`] instead of per vertex.
    const FOG_PER_FACE: bool = false;
    /// The values the fogged model interpolates: its own when it mixes per vertex or per
    /// triangle, its own and the share of fog when it mixes per pixel.
    type Fogged: Varyings;
    /// What the vertex scratch keeps of them.
    type FoggedStored: Stored<Self::Fogged>;
    /// A vertex's values `share` of the way (0.15, at most [`FOG_ONE`]) toward `fog` (`share`
    /// is 0 for models with [`Foggable::FOG_PER_FACE`]).
    fn fog_vertex(values: Self::Varyings, fog: &FogColor, share: u32) -> Self::Fogged;
    /// [`Shading::project`] of the fogged values.
    fn fog_project(&self, v: &mut Self::Fogged, w: S);
    /// [`Shading::triangle`] of the fogged values.
    fn fog_triangle(&mut self, v: &mut [Self::Fogged; 3]);
    /// [`Shading::pixel`] of the fogged values.
    fn fog_pixel(&self, v: &Self::Fogged, fog: &FogColor) -> Self::Color;
    /// [`Shading::pixel_fused`] of the fogged values.
    fn fog_pixel_fused(&self, acc: &[u32; MAX_VARYINGS], fog: &FogColor) -> Self::Color;
    /// [`Shading::pixel_fused_dithered`] of the fogged values.
    fn fog_pixel_fused_dithered(
        &self,
        acc: &[u32; MAX_VARYINGS],
        threshold: u32,
        fog: &FogColor,
    ) -> Self::Color;
    /// [`Shading::face`] with the triangle's colour mixed `share` of the way toward `fog`: for
    /// models with [`Foggable::FOG_PER_FACE`] (the default ignores the fog).
    fn fog_face(&mut self, vertices: &[VertexIn<S>; 3], fog: &FogColor, share: u32) {
        let _ = (fog, share);
        self.face(vertices);
    }
}

/// The [`Foggable`] items of a model that fogs its own values (per vertex or per triangle): it
/// interpolates and colours them as it does unfogged, so its pixels cost what they did.
macro_rules! fogs_own_values {
    ($s:ty) => {
        type Fogged = <Self as Shading<$s>>::Varyings;
        type FoggedStored = <Self as Shading<$s>>::Stored;
        #[inline(always)]
        fn fog_project(&self, v: &mut Self::Fogged, w: $s) {
            <Self as Shading<$s>>::project(self, v, w);
        }
        #[inline(always)]
        fn fog_triangle(&mut self, v: &mut [Self::Fogged; 3]) {
            <Self as Shading<$s>>::triangle(self, v);
        }
        #[inline(always)]
        fn fog_pixel(&self, v: &Self::Fogged, _: &FogColor) -> Self::Color {
            <Self as Shading<$s>>::pixel(self, v)
        }
        #[inline(always)]
        fn fog_pixel_fused(&self, acc: &[u32; MAX_VARYINGS], _: &FogColor) -> Self::Color {
            <Self as Shading<$s>>::pixel_fused(self, acc)
        }
        #[inline(always)]
        fn fog_pixel_fused_dithered(
            &self,
            acc: &[u32; MAX_VARYINGS],
            threshold: u32,
            _: &FogColor,
        ) -> Self::Color {
            <Self as Shading<$s>>::pixel_fused_dithered(self, acc, threshold)
        }
    };
}

/// Three interpolated channels mixed `share` (0.15) of the way toward the fog's: rounded once,
/// between the two (both carry the same half step, which the mix keeps).
#[inline(always)]
fn mix_channels(mut values: [i32; 3], fog: &FogColor, share: u32) -> [i32; 3] {
    for (v, f) in values.iter_mut().zip(fog.channels) {
        // |f - v| < 2^16 and share <= 2^15: the product fits an i64 with room to spare.
        let d = i64::from(f) - i64::from(*v);
        *v += ((d * i64::from(share) + (1 << 14)) >> 15) as i32;
    }
    values
}

impl<S: Scalar, C: ShadeColor, const N: usize> Foggable<S> for GouraudLit<S, C, N> {
    fogs_own_values!(S);
    #[inline(always)]
    fn fog_vertex(values: [i32; 3], fog: &FogColor, share: u32) -> [i32; 3] {
        mix_channels(values, fog, share)
    }
}

impl<S: Scalar, C: ShadeColor> Foggable<S> for super::MatCap<'_, S, C> {
    fogs_own_values!(S);
    #[inline(always)]
    fn fog_vertex(values: [i32; 3], fog: &FogColor, share: u32) -> [i32; 3] {
        mix_channels(values, fog, share)
    }
}

impl<S: Scalar, C: ShadeColor> Foggable<S> for VertexColors<C> {
    fogs_own_values!(S);
    #[inline(always)]
    fn fog_vertex(values: [i32; 3], fog: &FogColor, share: u32) -> [i32; 3] {
        mix_channels(values, fog, share)
    }
}

impl<S: Scalar, C: ShadeColor, const N: usize> Foggable<S> for FlatLit<S, C, N> {
    const FOG_PER_FACE: bool = true;
    fogs_own_values!(S);
    #[inline(always)]
    fn fog_vertex(_: [i32; 0], _: &FogColor, _: u32) -> [i32; 0] {
        []
    }
    fn fog_face(&mut self, vertices: &[VertexIn<S>; 3], fog: &FogColor, share: u32) {
        // The lit sums (units of 1 / (255 · 2^16) of an 8-bit step, at most 255 steps) mixed
        // before their one rounding to the target.
        let sums = flat_face_sums(self, vertices);
        let rgb = fog.rgb();
        let unit = 255u64 << 16;
        let fogs = [rgb.r(), rgb.g(), rgb.b()].map(|c| u64::from(c) * unit);
        let share = u64::from(share);
        let mut mixed = [0u64; 3];
        for c in 0..3 {
            // Both below 2^40; the weighted sum below 2^56.
            mixed[c] = (sums[c] * (u64::from(FOG_ONE) - share) + fogs[c] * share + (1 << 14)) >> 15;
        }
        set_flat_sums(self, mixed);
    }
}

/// Fractional bits of the share of fog [`PhongLit`] interpolates: 0.15 shifted up by 15, so
/// that the interpolation adds no error of its own and the share stays below `2^31` (the
/// clipper interpolates it as an `i32`).
const PHONG_SHARE_BITS: u32 = 30;

/// Phong fogs per pixel: the share of fog at each vertex is interpolated as a seventh value and
/// the lit sums are mixed toward the fog colour before their one rounding, so a pixel costs one
/// more interpolated value and three multiply-adds.
impl<S: Scalar, C: ShadeColor, const N: usize> Foggable<S> for PhongLit<S, C, N> {
    type Fogged = [i32; 7];
    type FoggedStored = [i32; 7];
    #[inline(always)]
    fn fog_vertex(v: [i32; 6], _: &FogColor, share: u32) -> [i32; 7] {
        // share <= 2^15, so the shifted share is at most 2^30.
        let share = (share << (PHONG_SHARE_BITS - 15)) as i32;
        [v[0], v[1], v[2], v[3], v[4], v[5], share]
    }
    // PhongLit does not project its values; it rescales their view vectors per triangle.
    #[inline(always)]
    fn fog_project(&self, _: &mut [i32; 7], _: S) {}
    #[inline(always)]
    fn fog_triangle(&mut self, v: &mut [[i32; 7]; 3]) {
        let mut lit = v.map(|x| [x[0], x[1], x[2], x[3], x[4], x[5]]);
        <Self as Shading<S>>::triangle(self, &mut lit);
        for (x, lit) in v.iter_mut().zip(lit) {
            x[..6].copy_from_slice(&lit);
        }
    }
    #[inline(always)]
    fn fog_pixel(&self, v: &[i32; 7], fog: &FogColor) -> C {
        let [a, b, c, d, e, f, share] = *v;
        let sums = phong_sums(self, &[a, b, c, d, e, f]);
        let one = 1u64 << PHONG_SHARE_BITS;
        // The interpolated share lies between the vertices' up to the interpolation's last
        // unit; clamped so that rounding cannot push it out of [0, 1].
        let share = u64::from(share.max(0) as u32).min(one);
        let mut mixed = [0u64; 3];
        for ch in 0..3 {
            // Sums at most 255 · 255 · 2^16 < 2^32, times at most 2^30: the weighted sum stays
            // below 2^63.
            mixed[ch] =
                (sums[ch] * (one - share) + fog.sums[ch] * share + (one >> 1)) >> PHONG_SHARE_BITS;
        }
        from_sums(mixed)
    }
    #[inline(always)]
    fn fog_pixel_fused(&self, acc: &[u32; MAX_VARYINGS], fog: &FogColor) -> C {
        // PhongLit's FUSED_FRAC is 0: each accumulator is its value.
        let v = [0, 1, 2, 3, 4, 5, 6].map(|i| acc[i] as i32);
        self.fog_pixel(&v, fog)
    }
    #[inline(always)]
    fn fog_pixel_fused_dithered(&self, acc: &[u32; MAX_VARYINGS], _: u32, fog: &FogColor) -> C {
        // No interpolated colour to dither, as unfogged.
        self.fog_pixel_fused(acc, fog)
    }
}

/// A shading model fogged per vertex (per triangle for [`FlatLit`], per pixel for
/// [`PhongLit`]): see the [module documentation](self).
///
/// ```
/// use rasterizer_core::prelude::*;
/// use rasterizer_core::shade::{Fog, FogCurve, FogSettings};
///
/// let (w, h) = (64, 48);
/// let eye = Vec3::<Fx16>::from_ints(0, 1, 4);
/// let vp = Viewport::new(w, h);
/// let t = Transforms::look_at(eye, Vec3::default(), Angle::from_degrees(50), vp).unwrap();
/// let sun = Light::directional(Vec3::from_ints(1, 1, 1));
/// let lighting = Lighting::with_lights(Material::new(Rgb888::new(200, 120, 80)), [sun], eye);
/// // Grey-blue fog from 3 to 6 units in front of the camera.
/// let fog = FogSettings {
///     color: Rgb888::new(128, 144, 160),
///     start: Fx16::from_int(3),
///     end: Fx16::from_int(6),
///     curve: FogCurve::Linear,
/// };
/// let shading = Fog::new(GouraudLit::<_, Rgb565, 1>::new(lighting.unwrap()), fog, &t.view);
/// let mut p = Pipeline::new(&t, vp, CullClockwise, NoDepth, shading);
///
/// // A triangle about 5 units away, two thirds into the fog.
/// let positions = [(-1, 0, -1), (1, 0, -1), (0, 2, -1)].map(|(x, y, z)| Vec3::from_ints(x, y, z));
/// let mesh = Mesh {
///     positions: &positions,
///     normals: None,
///     colors: None,
///     uvs: None,
///     triangles: &[[0u16, 1, 2]],
///     adjacency: None,
/// };
/// let mut pixels = [0u16; 64 * 48];
/// let mut fb = Framebuffer::<Rgb565>::new(&mut pixels, w, h).unwrap();
/// p.draw(&mut fb, &mesh, &mut [VertexSlot::EMPTY; 3]).unwrap();
/// ```
#[derive(Debug, Clone)]
pub struct Fog<S, Sh> {
    /// The shading model fogged.
    pub inner: Sh,
    settings: FogSettings<S>,
    color: FogColor,
    /// `-(row 2)` of the view matrix: the depth of a world-space point `p` is
    /// `plane · (p, 1)`.
    view_plane: [S; 4],
    /// This frame's plane, in the space the positions come in.
    plane: [S; 4],
}

impl<S: Scalar, Sh: Foggable<S>> Fog<S, Sh>
where
    Sh::Color: ShadeColor,
{
    /// `inner` fogged with `settings`, seen through `view` (the view matrix of the pipeline's
    /// [`crate::transform::Transforms`]: depth is taken along its `-z`).
    pub fn new(inner: Sh, settings: FogSettings<S>, view: &Mat4<S>) -> Self {
        let r = view.m[2];
        let view_plane = [-r[0], -r[1], -r[2], -r[3]];
        Self {
            inner,
            settings,
            color: FogColor::new::<Sh::Color>(settings.color),
            view_plane,
            plane: view_plane,
        }
    }

    /// The settings.
    pub fn settings(&self) -> &FogSettings<S> {
        &self.settings
    }

    /// Changes the settings (between frames: a draw call already under way keeps the values it
    /// has shaded).
    pub fn set_settings(&mut self, settings: FogSettings<S>) {
        self.settings = settings;
        self.color = FogColor::new::<Sh::Color>(settings.color);
    }

    /// The share of fog (0.15) at a point of this frame's space.
    #[inline]
    pub fn share_at(&self, p: Vec3<S>) -> u32 {
        let d = S::dot4(self.plane, [p.x, p.y, p.z, S::ONE]);
        let FogSettings { start, end, .. } = self.settings;
        let t = if end > start {
            let t = S::scaled_ratio(d - start, end - start, i64::from(FOG_ONE), 1);
            t.clamp(0, i64::from(FOG_ONE)) as u32
        } else if d >= start {
            FOG_ONE
        } else {
            0
        };
        self.settings.curve.share(t)
    }
}

impl<S: Scalar, Sh: Foggable<S>> Shading<S> for Fog<S, Sh>
where
    Sh::Color: ShadeColor,
{
    type Color = Sh::Color;
    type Varyings = Sh::Fogged;
    type Stored = Sh::FoggedStored;
    const NEEDS_WORLD: bool = true;
    const NEEDS_FACE: bool = Sh::NEEDS_FACE;
    const FUSED_FRAC: u32 = Sh::FUSED_FRAC;
    const FUSED_OFFSET: u32 = Sh::FUSED_OFFSET;
    const NEEDS_UV: bool = Sh::NEEDS_UV;
    const NEEDS_W: bool = Sh::NEEDS_W;
    const NEEDS_TRIANGLE: bool = Sh::NEEDS_TRIANGLE;

    #[inline(always)]
    fn project(&self, v: &mut Self::Varyings, w: S) {
        self.inner.fog_project(v, w);
    }

    #[inline(always)]
    fn triangle(&mut self, v: &mut [Self::Varyings; 3]) {
        self.inner.fog_triangle(v);
    }

    fn begin_frame(&mut self, model: Option<&Mat4<S>>) -> bool {
        // A model that reads no positions of its own takes them in model space too: fewer
        // transforms per vertex.
        let model_space = self.inner.begin_frame(model) || (!Sh::NEEDS_WORLD && model.is_some());
        self.plane = match model {
            Some(m) if model_space => {
                // The view plane carried back through the model matrix:
                // plane · (M p) = (plane M) · p.
                let col = |j: usize| [m.m[0][j], m.m[1][j], m.m[2][j], m.m[3][j]];
                [0, 1, 2, 3].map(|j| S::dot4(self.view_plane, col(j)))
            }
            _ => self.view_plane,
        };
        model_space
    }

    #[inline(always)]
    fn vertex(&mut self, v: &VertexIn<S>) -> Self::Varyings {
        let values = self.inner.vertex(v);
        let share = if Sh::FOG_PER_FACE {
            0
        } else {
            self.share_at(v.position)
        };
        Sh::fog_vertex(values, &self.color, share)
    }

    fn face(&mut self, v: &[VertexIn<S>; 3]) {
        if Sh::FOG_PER_FACE {
            let third = S::from_ratio(1, 3);
            let centre = (v[0].position + v[1].position + v[2].position).scale(third);
            let share = self.share_at(centre);
            self.inner.fog_face(v, &self.color, share);
        } else {
            self.inner.face(v);
        }
    }

    #[inline(always)]
    fn pixel(&self, v: &Self::Varyings) -> Self::Color {
        self.inner.fog_pixel(v, &self.color)
    }

    #[inline(always)]
    fn pixel_fused(&self, acc: &[u32; MAX_VARYINGS]) -> Self::Color {
        self.inner.fog_pixel_fused(acc, &self.color)
    }

    #[inline(always)]
    fn pixel_fused_dithered(&self, acc: &[u32; MAX_VARYINGS], threshold: u32) -> Self::Color {
        self.inner
            .fog_pixel_fused_dithered(acc, threshold, &self.color)
    }
}
