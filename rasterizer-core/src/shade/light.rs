//! Phong and Blinn-Phong lighting of a surface point, per channel in integers.
//!
//! # The model
//! For each channel `c` (`0..=255`), with every product of two 8-bit colours divided by 255:
//!
//! ```text
//! out = Ma La / 255 + Σ_lights [ Md Lc / 255 · max(0, N·L) + Ms Lc / 255 · spec ]   (clamped to 255)
//! spec = max(0, R·V)^shininess      (Phong, R = reflect(-L, N) = 2 (N·L) N - L)
//!      = max(0, N·H)^shininess      (Blinn-Phong, H = normalize(L + V))
//! ```
//!
//! `N`, `L` (towards the light), `V = normalize(eye - position)` and `H` are unit vectors. A light with
//! `N·L <= 0` is behind the surface and adds neither diffuse nor specular light; `shininess = 0` makes
//! `spec = 1` wherever `N·L > 0`. Point lights are not attenuated with distance.
//!
//! # Arithmetic and rounding
//! For a fixed-point format (every [`crate::math::Fx`]) the whole computation runs on the raw
//! integers, with no rounding to the format's step on the way:
//!
//! 1. Each vector (`N`, `V`, a point light's `L`) is made a unit vector in signed 2.30 with one
//!    reciprocal square root and three products: no division. The root comes from a table of the
//!    top eight bits and two Newton steps, within `2^-29` of `1 / |v|`; a vector already of unit
//!    length within `2^-12` (a mesh normal) takes one Newton step from 1 instead, within `2^-25`.
//!    A directional light's direction is stored unit length (by [`Lighting::add_light`]) and
//!    carried into 2.30 when the lighting is set up. The cosines `N·L` (and for Phong `N·V`,
//!    `L·V`) are exact `i64` sums of products, rounded once to 2.30.
//! 2. Phong uses `R·V = 2 (N·L)(N·V) - L·V` (one product, rounded half up; no reflected vector).
//!    Blinn-Phong takes `N·H = N·h / |h|` with `h = L + V` in 2.30 and `1 / |h|` from the same
//!    reciprocal square root, so no half vector is normalised and a short `h` (light and eye on
//!    opposite sides) loses only its components' rounding. Both factors are clamped to `[0, 1]`.
//! 3. The power is taken by repeated squaring in unsigned 0.30 fixed point, each product rounded
//!    half up (error at most 2^-31, and every value stays in `[0, 1]`). A rounding error made in
//!    `x^m` reaches `x^s` multiplied by at most `s/m` (the slope of `y ↦ y^(s/m)` on `[0, 1]`);
//!    the squares have `m = 2, 4, 8, ...` and the at most 16 products into the result have slope
//!    1, so the result is within `(s + 16) · 2^-31` of the exact power of the rounded base (4e-8
//!    for `s = 64`).
//! 4. The diffuse and specular factors are rounded half up to 0.16 (error at most 2^-17) and
//!    multiplied by the colour products `Md Lc`, `Ms Lc` (at most `255²`) into one `u64` sum per
//!    channel; the ambient term `Ma La` enters exactly. The sum is clamped and divided by
//!    `255 · 2^16` (or by `255 · 2^8` for [`Lighting::shade_fine`]) once, rounding half up.
//!
//! So, in 8-bit steps, the integer stages add at most `2 · 255 · (2^-17 + 2^-30)` ≈ 0.004 per
//! light, plus the final rounding: 0.5 for [`Lighting::shade`], 1/512 for
//! [`Lighting::shade_fine`]. The rest is the error of the inputs in the format: a normal or a
//! position within half a step `q` per component moves a cosine by about `q`, and the power
//! multiplies an error in its base by at most `s`. Measured against an f64 reference over random
//! scenes (`tests/tests/lighting.rs`), [`Lighting::shade`] is within 0.57 steps in 16.16 for
//! `shininess <= 64` ([`Lighting::shade_fine`] within 0.16); 24.8 stays within 1.5 steps for
//! ambient and diffuse light and within 22 steps in highlights, as its inputs carry only 8
//! fractional bits.
//!
//! A floating-point format (the `float` feature, for comparison) takes the same formulas in its
//! own arithmetic: vectors normalised with [`Vec3::normalize`], dot products in `S`, and the same
//! integer stages from the cosines on.
//!
//! Where a light grazes the surface (`N·L = 0`) the model itself jumps: the specular term switches
//! off there (with `shininess = 0` it is 1 right up to the edge), so a cosine a few steps of `S` off
//! moves the edge.
//!
//! # Cost
//! Per call, for a fixed-point format: one reciprocal square root for `N` (a few products for a
//! unit normal), one for `V` when a specular term needs it (not for [`Specular::None`] or
//! `shininess = 0`), one per point light; then per light a dot product, and for Blinn-Phong one
//! more reciprocal square root; for the power at most 16 squarings and 16 products
//! (`u32 × u32 → u64`); six `u32 × u32 → u64` multiply-adds; and three divisions by a constant at
//! the end. No division otherwise. The colour products and a directional light's direction in
//! 2.30 are prepared when the light or the material changes. For a model whose matrix is a
//! similarity, [`Lighting::in_model_space`] moves the eye and the lights into model space once,
//! so that a mesh's positions and normals are lit as they are stored.
//!
//! The shaders ([`crate::shade::GouraudLit`], [`crate::shade::FlatLit`],
//! [`crate::shade::PhongLit`]) take a shorter road when the format is fixed point and every
//! light is directional, with Blinn-Phong or no highlight: a plan made once per draw
//! (`DirectionalPlan`) applies the normal's length to the cosines instead of normalising it,
//! takes `N·H = (N·L + N·V) / |L + V|`, uses a reciprocal square root of one Newton step from
//! a 384-entry table (within `2^-17`), and scales the colour products to the target's channels
//! once, so a channel is a multiply-add and a shift. Measured per vertex against an f64
//! reference, it stays within 0.03 of an 8-bit step (this module's path: 0.017); see
//! `tests/tests/lighting_plan.rs` and `docs/ACCURACY.md`, also for Phong's pixels, which take
//! the power from a table made per draw (`PowerTable`), renormalise their nearly unit normal
//! and view vector (scaled to unit length per triangle) from a small table and one Newton
//! step, and take `N·H` from the cosines.

use crate::math::fx::{isqrt_u64, rsqrt_fast, rsqrt_u64};
use crate::math::{Mat4, Scalar, Vec3};
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use heapless::Vec;

/// 1.0 in the unsigned 0.30 format of the specular power.
const ONE30: u32 = 1 << 30;
/// 1.0 in the 0.16 format of the diffuse and specular factors.
const ONE16: u32 = 1 << 16;
/// The largest per-channel sum that is not clamped: `255` in units of `1 / (255 · 2^16)`.
const SUM_MAX: u64 = 255 * 255 * (1 << 16);

/// A light source.
///
/// Directions point from the surface towards the light and need not be unit length: they are
/// normalised once, when the light is added to a [`Lighting`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Light<S> {
    /// A light infinitely far away (the sun), shining along `-direction` everywhere.
    Directional {
        /// From the surface towards the light; any non-zero length.
        direction: Vec3<S>,
        /// The light's colour (its intensity per channel).
        color: Rgb888,
    },
    /// A light at a point, shining in every direction, with no attenuation by distance.
    Point {
        /// Where the light is, in the same space as the shaded points and the eye.
        position: Vec3<S>,
        /// The light's colour (its intensity per channel).
        color: Rgb888,
    },
}

impl<S> Light<S> {
    /// A white directional light shining from `direction` (from the surface towards the light).
    pub const fn directional(direction: Vec3<S>) -> Self {
        Self::Directional {
            direction,
            color: Rgb888::new(255, 255, 255),
        }
    }

    /// A white point light at `position`.
    pub const fn point(position: Vec3<S>) -> Self {
        Self::Point {
            position,
            color: Rgb888::new(255, 255, 255),
        }
    }
}

/// Surface material: the colour each term reflects, and the specular exponent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Material {
    /// Reflected fraction of the ambient light, per channel (255 = all).
    pub ambient: Rgb888,
    /// Reflected fraction of the diffuse light, per channel (255 = all).
    pub diffuse: Rgb888,
    /// Reflected fraction of the specular highlight, per channel (255 = all).
    pub specular: Rgb888,
    /// Specular exponent: larger gives a smaller, sharper highlight; 0 gives a specular factor of 1
    /// wherever the light reaches the surface.
    pub shininess: u16,
}

impl Material {
    /// A material of one colour: it reflects `color` of the ambient and diffuse light, with a
    /// white highlight of exponent 16.
    pub const fn new(color: Rgb888) -> Self {
        Self {
            ambient: color,
            diffuse: color,
            specular: Rgb888::new(255, 255, 255),
            shininess: 16,
        }
    }
}

/// Which specular model [`Lighting`] uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Specular {
    /// No specular term: ambient and diffuse only (and no view vector to compute).
    None,
    /// Phong: `max(0, R·V)^shininess` with `R = reflect(-L, N)`.
    Phong,
    /// Blinn-Phong: `max(0, N·H)^shininess` with `H = normalize(L + V)`.
    BlinnPhong,
}

/// Everything needed to light a point: up to `N` lights, the ambient light, the material, the
/// specular model and the eye position.
///
/// Positions, directions, normals and the eye must all be in the same space (world or view space).
/// See the [module documentation](self) for the formula, the rounding and the cost.
///
/// ```
/// use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
/// use rasterizer_core::math::{Fx16, Vec3};
/// use rasterizer_core::shade::{Light, Lighting, Material, Specular};
///
/// let material = Material {
///     ambient: Rgb888::new(40, 40, 40),
///     diffuse: Rgb888::new(200, 100, 50),
///     specular: Rgb888::WHITE,
///     shininess: 16,
/// };
/// let eye = Vec3::<Fx16>::from_ints(0, 0, 10);
/// let mut lighting = Lighting::<Fx16, 2>::new(material, Rgb888::WHITE, Specular::BlinnPhong, eye);
/// let sun = Light::Directional { direction: Vec3::from_ints(0, 0, 3), color: Rgb888::WHITE };
/// lighting.add_light(sun).unwrap();
///
/// // Facing both the light and the eye: ambient + full diffuse + full highlight, saturated.
/// let lit = lighting.shade(Vec3::from_ints(0, 0, 0), Vec3::from_ints(0, 0, 1));
/// assert_eq!(lit, Rgb888::WHITE);
/// // Facing away: the ambient term only.
/// let dark = lighting.shade(Vec3::from_ints(0, 0, 0), Vec3::from_ints(0, 0, -1));
/// assert_eq!(dark, Rgb888::new(40, 40, 40));
/// ```
#[derive(Debug, Clone)]
pub struct Lighting<S, const N: usize> {
    lights: Vec<Light<S>, N>,
    material: Material,
    ambient: Rgb888,
    specular: Specular,
    eye: Vec3<S>,
    /// What each light contributes independently of the point lit, kept up to date with the
    /// lights and the material.
    terms: Vec<LightTerms, N>,
    /// `Ma La` per channel, in the units of the sums.
    ambient_sum: [u64; 3],
    /// [`spec_cut`] for the material's shininess (0 for none), made when the material is set
    /// rather than with every plan, as a draw makes one or two.
    spec_cut: u64,
}

/// A light's terms that do not depend on the point lit: a directional light's unit direction in
/// 2.30, and the colour products `Md Lc` and `Ms Lc` per channel.
#[derive(Debug, Clone, Copy, Default)]
struct LightTerms {
    direction: [i64; 3],
    diffuse: [u32; 3],
    specular: [u32; 3],
}

impl<S: Scalar, const N: usize> Lighting<S, N> {
    /// Feeds the lights, material, ambient light, specular model and eye to `out`
    /// ([`Shading::fingerprint`](crate::shade::Shading::fingerprint)).
    pub fn fingerprint(&self, out: &mut crate::fingerprint::Fingerprint) {
        let rgb = |out: &mut crate::fingerprint::Fingerprint, c: Rgb888| {
            out.bytes(&[c.r(), c.g(), c.b()])
        };
        let v3 = |out: &mut crate::fingerprint::Fingerprint, v: &Vec3<S>| {
            for c in [v.x, v.y, v.z] {
                out.bytes(&c.to_fx16_bits().to_le_bytes());
            }
        };
        for l in &self.lights {
            match l {
                Light::Directional { direction, color } => {
                    out.bytes(&[0]);
                    v3(out, direction);
                    rgb(out, *color);
                }
                Light::Point { position, color } => {
                    out.bytes(&[1]);
                    v3(out, position);
                    rgb(out, *color);
                }
            }
        }
        let m = &self.material;
        for c in [m.ambient, m.diffuse, m.specular, self.ambient] {
            rgb(out, c);
        }
        out.bytes(&m.shininess.to_le_bytes());
        out.bytes(&[self.specular as u8]);
        v3(out, &self.eye);
    }
}

impl<S: Scalar, const N: usize> Lighting<S, N> {
    /// No lights yet; `ambient` is the colour of the ambient light.
    pub fn new(material: Material, ambient: Rgb888, specular: Specular, eye: Vec3<S>) -> Self {
        let mut out = Self {
            lights: Vec::new(),
            material,
            ambient,
            specular,
            eye,
            terms: Vec::new(),
            ambient_sum: [0; 3],
            spec_cut: 0,
        };
        out.prepare();
        out.spec_cut = material_cut(&material);
        out
    }

    /// The usual set-up in one call: the `N` lights given, a dim white ambient light (32 of 255
    /// per channel) and Blinn-Phong highlights, seen from `eye`.
    ///
    /// # Errors
    /// Returns the first directional light with a zero direction.
    pub fn with_lights(
        material: Material,
        lights: [Light<S>; N],
        eye: Vec3<S>,
    ) -> Result<Self, Light<S>> {
        let mut out = Self::new(material, Rgb888::new(32, 32, 32), Specular::BlinnPhong, eye);
        for light in lights {
            out.add_light(light)?;
        }
        Ok(out)
    }

    /// Recomputes the terms that do not depend on the point lit.
    fn prepare(&mut self) {
        let m = &self.material;
        let (ma, la) = (channels(m.ambient), channels(self.ambient));
        self.ambient_sum = [0, 1, 2].map(|c| u64::from(ma[c] * la[c]) << 16);
        let (md, ms) = (channels(m.diffuse), channels(m.specular));
        self.terms.clear();
        for light in &self.lights {
            let (direction, color) = match *light {
                Light::Directional { direction, color } => (
                    [direction.x, direction.y, direction.z].map(|c| i64::from(c.to_scaled_int(30))),
                    color,
                ),
                Light::Point { color, .. } => ([0; 3], color),
            };
            let lc = channels(color);
            // One entry per light, so the push cannot fail.
            let _ = self.terms.push(LightTerms {
                direction,
                diffuse: [0, 1, 2].map(|c| md[c] * lc[c]),
                specular: [0, 1, 2].map(|c| ms[c] * lc[c]),
            });
        }
    }

    /// Adds a light, normalising a directional light's direction.
    ///
    /// # Errors
    /// Returns the light unchanged when all `N` slots are taken, or when it is a directional light
    /// with a zero direction.
    pub fn add_light(&mut self, light: Light<S>) -> Result<(), Light<S>> {
        let stored = match light {
            Light::Directional { direction, color } => Light::Directional {
                direction: direction.normalize().ok_or(light)?,
                color,
            },
            Light::Point { .. } => light,
        };
        self.lights.push(stored).map_err(|_| light)?;
        self.prepare();
        Ok(())
    }

    /// The lights, directional ones with unit directions.
    pub fn lights(&self) -> &[Light<S>] {
        &self.lights
    }

    /// Moves the eye (for example once per frame).
    pub fn set_eye(&mut self, eye: Vec3<S>) {
        self.eye = eye;
    }

    /// Replaces the material (for example between objects).
    pub fn set_material(&mut self, material: Material) {
        self.material = material;
        self.prepare();
        self.spec_cut = material_cut(&material);
    }

    /// The same lighting with its lights and eye carried into the space of a model whose matrix
    /// is `model`: lighting a model-space point and normal with the result gives what lighting
    /// the world-space ones with `self` gives, up to rounding. This holds for a similarity (a
    /// rotation or reflection, a uniform scale and a translation, with `(0, 0, 0, 1)` as the last
    /// row), which keeps every angle; for any other matrix, or a scale outside `1/4 ..= 32`
    /// (where the format would carry the moved eye and lights too coarsely), `None`.
    ///
    /// The 3D pipeline lights in model space this way when it can, which saves transforming
    /// each vertex's position and normal to world space.
    pub fn in_model_space(&self, model: &Mat4<S>) -> Option<Self> {
        let m = &model.m;
        if m[3] != [S::ZERO, S::ZERO, S::ZERO, S::ONE] {
            return None;
        }
        let col = |c: usize| Vec3::new(m[0][c], m[1][c], m[2][c]);
        let (c0, c1, c2) = (col(0), col(1), col(2));
        // A similarity s R has columns of one length s, at right angles: M^T M = s^2 I.
        let g = [c0.dot(c0), c1.dot(c1), c2.dot(c2)];
        let s2 = (g[0] + g[1] + g[2]) * S::from_ratio(1, 3);
        if s2 < S::from_ratio(1, 16) || s2 > S::from_int(1024) {
            return None;
        }
        let tol = s2 * S::from_ratio(1, 4096);
        let off = [c0.dot(c1), c0.dot(c2), c1.dot(c2)];
        if g.iter().any(|&x| (x - s2).abs() > tol) || off.iter().any(|&x| x.abs() > tol) {
            return None;
        }
        // M^-1 (p - t) = M^T (p - t) / s^2; a direction needs only M^T, as it is normalised.
        let t = Vec3::new(m[0][3], m[1][3], m[2][3]);
        let c = [c0, c1, c2];
        // Out of line: per frame, for each light and the eye.
        #[inline(never)]
        fn transpose<S: Scalar>(c: &[Vec3<S>; 3], d: Vec3<S>) -> Vec3<S> {
            Vec3::new(c[0].dot(d), c[1].dot(d), c[2].dot(d))
        }
        #[inline(never)]
        fn back<S: Scalar>(p: Vec3<S>, t: Vec3<S>, c: &[Vec3<S>; 3], s2: S) -> Vec3<S> {
            let d = transpose(c, p - t);
            Vec3::new(d.x / s2, d.y / s2, d.z / s2)
        }
        // Built afresh rather than cloned: `prepare` recomputes the terms.
        let mut lights = Vec::new();
        for light in &self.lights {
            let moved = match *light {
                Light::Directional { direction, color } => Light::Directional {
                    direction: transpose(&c, direction).normalize()?,
                    color,
                },
                Light::Point { position, color } => Light::Point {
                    position: back(position, t, &c, s2),
                    color,
                },
            };
            // As many as `self` holds, so the push cannot fail.
            let _ = lights.push(moved);
        }
        let mut out = Self {
            lights,
            material: self.material,
            ambient: self.ambient,
            specular: self.specular,
            eye: back(self.eye, t, &c, s2),
            terms: Vec::new(),
            ambient_sum: [0; 3],
            spec_cut: self.spec_cut,
        };
        out.prepare();
        Some(out)
    }

    /// The lit colour of the surface point `position` with normal `normal`, 8 bits per channel,
    /// saturating at 255.
    ///
    /// The normal need not be unit length; a zero normal gives the ambient term only. A point light
    /// exactly at `position` adds nothing, nor does a specular term with the eye exactly at
    /// `position` (unless `shininess = 0`).
    pub fn shade(&self, position: Vec3<S>, normal: Vec3<S>) -> Rgb888 {
        // Round half up: sum / (255 · 2^16), below 2^32 after the clamp.
        let sum = self.sum(position, normal);
        // The divisor's 2^16 first (nested floors), then a quotient of u32s.
        let ch = |c: usize| ((((sum[c] + 255 * (1 << 15)) >> 16) as u32) / 255) as u8;
        Rgb888::new(ch(0), ch(1), ch(2))
    }

    /// As [`shade`](Self::shade), but each channel with 8 fractional bits (`255 << 8` is full
    /// intensity, so every value fits a `u16`), for interpolating lit colours (Gouraud) without
    /// rounding them to 8 bits first.
    pub fn shade_fine(&self, position: Vec3<S>, normal: Vec3<S>) -> [u32; 3] {
        let sum = self.sum(position, normal);
        // As in `shade`: sum >> 8 stays below 255² 2^8 < 2^32.
        let ch = |c: usize| (((sum[c] + 255 * (1 << 7)) >> 8) as u32) / 255;
        [ch(0), ch(1), ch(2)]
    }

    /// The lit colour unrounded: channel `c` is `sums[c] / (255 · 2^16)` 8-bit steps, at most
    /// 255 ([`shade`](Self::shade) and [`shade_fine`](Self::shade_fine) round these).
    pub fn shade_sums(&self, position: Vec3<S>, normal: Vec3<S>) -> [u64; 3] {
        self.sum(position, normal)
    }

    /// Per channel, the lit colour times `255 · 2^16`, clamped to `255` times that.
    #[inline]
    fn sum(&self, position: Vec3<S>, normal: Vec3<S>) -> [u64; 3] {
        if let (Some(p), Some(n)) = (position.raw_bits(), normal.raw_bits()) {
            return self.sum_raw(p, n);
        }
        self.sum_scalar(position, normal)
    }

    /// [`Lighting::sum`] for a fixed-point format, on the raw integers: unit vectors in 2.30
    /// from one reciprocal square root each, cosines as exact `i64` sums of products.
    fn sum_raw(&self, position: [i64; 3], normal: [i64; 3]) -> [u64; 3] {
        let mut sum = self.ambient_sum;
        let Some(n) = unit30_near(normal, S::RAW_FRAC) else {
            return clamp(sum);
        };
        let shininess = self.material.shininess;
        let needs_view =
            self.specular != Specular::None && shininess != 0 && !self.lights.is_empty();
        let view = if needs_view {
            let eye = self.eye.raw_bits().unwrap_or_default();
            unit30([0, 1, 2].map(|i| eye[i] - position[i]))
        } else {
            None
        };
        let nv = match (self.specular, view) {
            (Specular::Phong, Some(v)) => dot30(n, v),
            _ => 0,
        };
        for (light, terms) in self.lights.iter().zip(&self.terms) {
            let l = match *light {
                Light::Directional { .. } => terms.direction,
                Light::Point { position: at, .. } => {
                    let at = at.raw_bits().unwrap_or_default();
                    match unit30([0, 1, 2].map(|i| at[i] - position[i])) {
                        Some(l) => l,
                        None => continue,
                    }
                }
            };
            let nl = dot30(n, l);
            if nl <= 0 {
                continue;
            }
            let diffuse = ((nl + (1 << 13)) >> 14).min(i64::from(ONE16)) as u32;
            let specular = match (self.specular, view) {
                (Specular::None, _) => 0,
                (_, _) if shininess == 0 => ONE16,
                (_, None) => 0,
                (Specular::Phong, Some(v)) => phong(nl, nv, dot30(l, v), shininess),
                (Specular::BlinnPhong, Some(v)) => {
                    // N·H = N·h / |h| with h = L + V, |h| from a reciprocal square root.
                    let h = [l[0] + v[0], l[1] + v[1], l[2] + v[2]];
                    let a = dot30(n, h);
                    let hh = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]) as u64;
                    if a <= 0 || hh == 0 {
                        0
                    } else {
                        // |a| <= 2^31 and r <= 2^31: a r / 2^k is N·H, shifted to 2.30.
                        let (r, k) = rsqrt_u64(hh);
                        let nh = ((a as u64 * r) >> (k - 30)).min(u64::from(ONE30)) as u32;
                        to_q16(pow30(nh, shininess))
                    }
                }
            };
            for (c, sum) in sum.iter_mut().enumerate() {
                *sum += u64::from(terms.diffuse[c]) * u64::from(diffuse)
                    + u64::from(terms.specular[c]) * u64::from(specular);
            }
        }
        clamp(sum)
    }

    /// [`Lighting::sum`] for a floating-point format.
    fn sum_scalar(&self, position: Vec3<S>, normal: Vec3<S>) -> [u64; 3] {
        let m = &self.material;
        let ma = channels(m.ambient);
        let la = channels(self.ambient);
        let mut sum = [0u64; 3];
        for c in 0..3 {
            sum[c] = u64::from(ma[c] * la[c]) << 16;
        }
        let Some(n) = normal.normalize() else {
            return clamp(sum);
        };
        let shininess = m.shininess;
        // The view vector, only when a specular power needs it; `None` also when the eye is at the
        // point, which leaves no specular term.
        let needs_view =
            self.specular != Specular::None && shininess != 0 && !self.lights.is_empty();
        let view = if needs_view {
            (self.eye - position).normalize()
        } else {
            None
        };
        // N·V in 2.30, for Phong.
        let nv = match (self.specular, view) {
            (Specular::Phong, Some(v)) => to_q30(n.dot(v)),
            _ => 0,
        };
        let (md, ms) = (channels(m.diffuse), channels(m.specular));
        for light in &self.lights {
            let (l, color) = match *light {
                Light::Directional { direction, color } => (direction, color),
                Light::Point {
                    position: at,
                    color,
                } => match (at - position).normalize() {
                    Some(l) => (l, color),
                    None => continue,
                },
            };
            let nl = n.dot(l);
            if nl <= S::ZERO {
                continue;
            }
            let diffuse = nl.to_scaled_int(16).clamp(0, ONE16 as i32) as u32;
            let specular = match (self.specular, view) {
                (Specular::None, _) => 0,
                (_, _) if shininess == 0 => ONE16,
                (_, None) => 0,
                (Specular::Phong, Some(v)) => phong(to_q30(nl), nv, to_q30(l.dot(v)), shininess),
                (Specular::BlinnPhong, Some(v)) => blinn(n, l + v, shininess),
            };
            let lc = channels(color);
            for c in 0..3 {
                sum[c] += u64::from(md[c] * lc[c]) * u64::from(diffuse)
                    + u64::from(ms[c] * lc[c]) * u64::from(specular);
            }
        }
        clamp(sum)
    }
}

/// A per-draw plan for the common case: a fixed-point format, directional lights only, and no
/// specular term or Blinn-Phong's. It lights a point with about a third of the work of
/// [`Lighting::shade_sums`]: the normal's length is applied to the cosines instead of to its
/// components, Blinn-Phong's `N·H` comes from the cosines as `(N·L + N·V) / sqrt(2 + 2 L·V)`
/// (no half vector is built), and the colour products are scaled once to the caller's unit so
/// that a channel is a multiply-add and a shift. A highlight that one product proves zero (its
/// `N·H` below the least argument whose power is not zero, [`spec_cut`]) takes no root or power.
///
/// Its results differ from [`Lighting::shade_sums`]' only by rounding (the cosines are rounded
/// at other points, within a few `2^-30`): see [`Lighting::directional_plan`].
#[derive(Debug, Clone)]
pub(crate) struct DirectionalPlan<const N: usize> {
    /// The eye, raw.
    eye: [i64; 3],
    /// Unit direction in 2.30 and the scaled colour products of each light.
    lights: Vec<PlanLight, N>,
    /// The ambient term per channel, in units of `2^-out_bits` of the caller's scale, plus
    /// the caller's bias.
    ambient: [u64; 3],
    /// Each channel's largest value (the caller's scale, in the same units), plus the bias.
    full: [u64; 3],
    /// A Blinn-Phong term with a positive shininess is computed.
    specular: bool,
    /// With `shininess = 0` the specular factor is 1 wherever the light reaches the surface.
    spec_one: bool,
    /// `shininess = odd · 2^twos`.
    odd: u16,
    twos: u32,
    /// A highlight whose `N·H = a / |h|` has `a² < spec_cut · (|h|² >> 30)` (both in 2.30)
    /// is zero: see [`spec_cut`].
    spec_cut: u64,
}

/// A light of a [`DirectionalPlan`].
#[derive(Debug, Clone, Copy)]
struct PlanLight {
    l: [i64; 3],
    /// `|L|²` in 2.30 (one within the rounding of the stored direction).
    ll: i64,
    /// `Md Lc` and `Ms Lc` per channel in units of `2^(16 - out_bits)` of the caller's scale
    /// over `255²`: times a 0.16 factor, in the units of the plan's sums.
    kd: [u64; 3],
    ks: [u64; 3],
}

/// `round(num / 255²)` for `num < 2^48`, once per draw for each colour product.
fn per_255_squared(num: u64) -> u64 {
    const D: u64 = 255 * 255;
    let d = core::num::NonZeroU64::new(D).unwrap_or(core::num::NonZeroU64::MIN);
    crate::wide::div_u64(num + D / 2, d)
}

impl<S: Scalar, const N: usize> Lighting<S, N> {
    /// The lighting as a [`DirectionalPlan`] whose sums are each channel's lit value times
    /// `scale[c] · 2^out_bits`, clamped to full intensity (`scale[c] << out_bits`), plus
    /// `bias[c]` (a caller's rounding offset, added for free), or `None` when the plan does not
    /// apply: a floating-point format, a point light, or Phong highlights.
    /// `16 <= out_bits <= 32`, `scale[c] < 2^16` and `bias[c] < 2^48`.
    // Out of line: a frame's set-up calls it twice (target colours and sums); one copy serves.
    #[inline(never)]
    pub(crate) fn directional_plan(
        &self,
        scale: [u32; 3],
        out_bits: u32,
        bias: [u64; 3],
    ) -> Option<DirectionalPlan<N>> {
        let eye = self.eye.raw_bits()?;
        let frac = S::RAW_FRAC;
        // Up to 23 bits, the normal's range checks below stay within u64.
        if !(8..=23).contains(&frac) || self.specular == Specular::Phong {
            return None;
        }
        let m = &self.material;
        // min(s, full) + bias = min(s + bias, full + bias): the bias rides in the ambient term.
        let full = [0, 1, 2].map(|c| (u64::from(scale[c]) << out_bits) + bias[c]);
        let (ma, la) = (channels(m.ambient), channels(self.ambient));
        // The ambient term rounded as the other products are (to 2^16 units), within 2^-17 of
        // the caller's unit.
        let per = |t: u32, c: usize| {
            per_255_squared((u64::from(t) * u64::from(scale[c])) << (out_bits - 16))
        };
        let ambient = [0, 1, 2].map(|c| (per(ma[c] * la[c], c) << 16) + bias[c]);
        let mut lights = Vec::new();
        for (light, terms) in self.lights.iter().zip(&self.terms) {
            let Light::Directional { .. } = light else {
                return None;
            };
            let k = |t: [u32; 3]| [0, 1, 2].map(|c| per(t[c], c));
            let l = terms.direction;
            let _ = lights.push(PlanLight {
                l,
                ll: (l[0] * l[0] + l[1] * l[1] + l[2] * l[2] + (1 << 29)) >> 30,
                kd: k(terms.diffuse),
                ks: k(terms.specular),
            });
        }
        let shininess = m.shininess;
        let any = self.specular == Specular::BlinnPhong && !lights.is_empty();
        let twos = shininess.trailing_zeros().min(15);
        let (specular, odd) = (any && shininess != 0, shininess >> twos);
        Some(DirectionalPlan {
            eye,
            lights,
            ambient,
            full,
            specular,
            spec_one: any && shininess == 0,
            odd,
            twos,
            spec_cut: if specular { self.spec_cut } else { 0 },
        })
    }
}

impl<const N: usize> DirectionalPlan<N> {
    /// The lit sums (see [`Lighting::directional_plan`]) of the point `position` with normal
    /// `normal` (raw integers of the format), or `None` where the plan's shortcuts do not hold
    /// (a normal shorter than 2^-8 or longer than 2^8, an eye `2^30` raw units or more away
    /// along an axis): the caller then takes [`Lighting::shade_sums`].
    #[inline(always)]
    pub(crate) fn sums<S: Scalar>(&self, position: Vec3<S>, normal: Vec3<S>) -> Option<[u64; 3]> {
        let (position, normal) = (position.raw_bits()?, normal.raw_bits()?);
        // The format's, a constant: the plan is made only for it.
        let f = S::RAW_FRAC;
        let n = normal;
        // Raw components are i32s: each square below 2^62, the sum below 2^64.
        let sq = |c: i64| (c * c) as u64;
        let nn = sq(n[0]) + sq(n[1]) + sq(n[2]);
        let one = 1u64 << (2 * f);
        // 1 / |n| in 2.30: a normal of unit length within 2^-12 (a mesh's) takes one Newton
        // step from 1, within 2^-25; any other of length 2^-8 to 2^8 a reciprocal square root.
        // |nn - one| < one / 2^12, as one unsigned comparison of d + one / 2^12 - 1.
        let (d, q) = (nn.wrapping_sub(one) as i64, (one >> 12) as i64);
        let rn = if (d.wrapping_add(q - 1) as u64) < 2 * q as u64 - 1 {
            (1i64 << 30) - shr(d, 2 * f as i32 - 29)
        } else if nn >= one >> 16 && nn >> 16 < one {
            let (r, k) = rsqrt_fast(nn);
            // 2^f / sqrt(nn) in 2.30 = r 2^(f + 30 - k), below 2^39.
            shr(r as i64, k as i32 - f as i32 - 30)
        } else {
            return None;
        };
        // N·X in 2.30 for a 2.30 vector x: n·x is below 2^(f + 40) (|n| < 2^8), and n·x / 2^f
        // is |n| N·X in 2.30, so that times rn (2^30 / |n|) it stays below 2^62.
        let cos =
            |x: [i64; 3]| (((n[0] * x[0] + n[1] * x[1] + n[2] * x[2]) >> f) * rn + (1 << 29)) >> 30;
        let mut sum = self.ambient;
        let e = &self.eye;
        let w = [e[0] - position[0], e[1] - position[1], e[2] - position[2]];
        // The eye at the point (no highlight there) and an eye far away along an axis take the
        // general path.
        // Each |c| below 2^30: c + 2^30 - 1 in [0, 2^31 - 2] (unsigned), and not all zero.
        let t = |c: i64| c.wrapping_add((1 << 30) - 1) as u64;
        let far = t(w[0]).max(t(w[1])).max(t(w[2])) >= (1 << 31) - 1;
        if self.specular && (far || w[0] | w[1] | w[2] == 0) {
            return None;
        }
        // V in 2.30 and N·V, for a specular power, made when a light first reaches the point.
        let mut view: Option<([i64; 3], i64)> = None;
        // At most N lights: a bound the loop can be unrolled by.
        for light in self.lights.iter().take(N) {
            let nl = cos(light.l);
            if nl <= 0 {
                continue;
            }
            let (view, nv) = *view.get_or_insert_with(|| {
                if !self.specular {
                    return ([0; 3], 0);
                }
                // Not zero (tested above), each square below 2^60.
                let ww = sq(w[0]) + sq(w[1]) + sq(w[2]);
                // c / |w| = c r / 2^k, in 2.30: |c r| < 2^61.
                let (r, k) = rsqrt_fast(ww);
                let r = r as i64;
                let unit = |c: i64| (c * r + (1 << (k - 31))) >> (k - 30);
                let v = [unit(w[0]), unit(w[1]), unit(w[2])];
                (v, cos(v))
            });
            let diffuse = ((nl + (1 << 13)) >> 14).min(i64::from(ONE16)) as u64;
            let specular = if self.specular {
                // N·H = N·h / |h| with h = L + V: N·h = N·L + N·V, and |h|² from h's
                // components (L is unit only to the format's step, so not 2 + 2 L·V).
                let l = light.l;
                let h = [l[0] + view[0], l[1] + view[1], l[2] + view[2]];
                let a = nl + nv;
                // Components below 2^31: each square below 2^62.
                let hh = sq(h[0]) + sq(h[1]) + sq(h[2]);
                // |a| <= 2^31 (1 + 2^-15) (each cosine within (1 + 2^-16) 2^30), so a² fits
                // an i64; the cut is at most 2^30 and hh >> 30 below 2^34, their product
                // below 2^64.
                if a <= 0 || hh == 0 || sq(a) < self.spec_cut * (hh >> 30) {
                    0
                } else {
                    // 1 / |h| = 2^30 / sqrt(hh) = r 2^(30 - k); a r below 2^62.
                    let (r, k) = rsqrt_fast(hh);
                    let nh = ((a as u64 * r) >> (k - 30)).min(u64::from(ONE30)) as u32;
                    u64::from(self.power(nh))
                }
            } else if self.spec_one {
                u64::from(ONE16)
            } else {
                0
            };
            for (c, sum) in sum.iter_mut().enumerate() {
                *sum += light.kd[c] * diffuse + light.ks[c] * specular;
            }
        }
        Some([
            sum[0].min(self.full[0]),
            sum[1].min(self.full[1]),
            sum[2].min(self.full[2]),
        ])
    }
}

impl<const N: usize> DirectionalPlan<N> {
    /// What a Phong pixel interpolates under the plan: the unit normal in signed 2.30 (zero
    /// for a zero normal), then the view vector `eye - position` unnormalised, in the format's
    /// raw integers (interpolating it is interpolating the position), until
    /// [`phong_triangle`] scales it for a triangle. The view vector, not the vertices' half
    /// vectors: those would be cheaper per pixel, but their interpolation is off by the square
    /// of the angle a triangle spans from the eye (up to 20 steps in a large face's highlight,
    /// measured).
    pub(crate) fn phong_vertex<S: Scalar>(&self, position: Vec3<S>, normal: Vec3<S>) -> [i32; 6] {
        let n = normal.raw_bits().and_then(unit30).unwrap_or_default();
        let p = position.raw_bits().unwrap_or_default();
        // Unit components in 2.30 are within [-2^30, 2^30] (up to rounding); an eye and a
        // position as raw i32s are less than 2^32 apart, clamped to an i32 (an eye 2^15 units
        // away in 16.16).
        let n = n.map(|c| c.clamp(-(1 << 30), 1 << 30) as i32);
        let e = &self.eye;
        let w = [e[0] - p[0], e[1] - p[1], e[2] - p[2]];
        let w = w.map(|c| c.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32);
        [n[0], n[1], n[2], w[0], w[1], w[2]]
    }

    /// The lit sums of a Phong pixel from its interpolated [`DirectionalPlan::phong_vertex`]
    /// values (the view vector scaled by [`phong_triangle`]), the power from `power` (made for
    /// the plan's shininess): the normal's and the view vector's lengths from [`inv_len`], and
    /// `N·H = (N·L + N·V) / |L + V|` from the cosines, with `|L + V|² = |L|² + 1 + 2 L·V`, so
    /// that no vector is normalised component by component. A highlight below the table's
    /// start is known to be zero before its root is taken.
    #[inline(always)]
    pub(crate) fn phong_pixel(&self, v: &[i32; 6], power: &PowerTable) -> [u64; 3] {
        let sum = self.phong_pixel_unclamped(v, power);
        [
            sum[0].min(self.full[0]),
            sum[1].min(self.full[1]),
            sum[2].min(self.full[2]),
        ]
    }

    /// [`DirectionalPlan::phong_pixel`] before the clamp to full intensity, for a caller that
    /// clamps what it keeps of the sums (below `2^49` per light and term, so the sum of a few
    /// lights cannot wrap).
    #[inline(always)]
    pub(crate) fn phong_pixel_unclamped(&self, v: &[i32; 6], power: &PowerTable) -> [u64; 3] {
        let mut sum = [0u64; 3];
        let n = [v[0], v[1], v[2]].map(i64::from);
        let w = [v[3], v[4], v[5]].map(i64::from);
        // Values interpolated from `phong_triangle`'s (components within 2^30) keep every
        // product and sum below in range, as the comments say; the wrapping operations only
        // keep values from elsewhere from panicking (they give a wrong colour instead).
        let sq = |c: i64| c.wrapping_mul(c) as u64;
        let nn = sq(n[0]).wrapping_add(sq(n[1])).wrapping_add(sq(n[2]));
        // 0 for a zero normal: then no light reaches the pixel.
        let rn = inv_len(nn);
        // a·b / 2^30 for 2.30 vectors, below 2^33 in magnitude for components within 2^31.
        let dot = |a: [i64; 3], b: [i64; 3]| {
            (a[0].wrapping_mul(b[0]))
                .wrapping_add(a[1].wrapping_mul(b[1]))
                .wrapping_add(a[2].wrapping_mul(b[2]))
                >> 30
        };
        // 1 / |w| in 2.30 and N·V, made when a light first reaches the pixel (`rv` stays 0
        // without a highlight, and with the eye at the point).
        let (mut rv, mut nv, mut view_made) = (0i64, 0i64, false);
        // At most N lights: a bound the loop can be unrolled by.
        for light in self.lights.iter().take(N) {
            let l = light.l;
            // N·L = (n·l) / |n|: below 2^33 times rn (below 2^31 for normals longer than 1/2).
            let nl = dot(n, l).wrapping_mul(rn) >> 30;
            if nl <= 0 {
                continue;
            }
            let diffuse = (nl.wrapping_add(1 << 13) >> 14).min(i64::from(ONE16)) as u64;
            if self.specular && !view_made {
                view_made = true;
                let ww = sq(w[0]).wrapping_add(sq(w[1])).wrapping_add(sq(w[2]));
                // 0 with the eye at the point, and then nv = 0 too.
                rv = inv_len(ww);
                // (n·w / |n|) / |w|, each step below 2^62.
                nv = (dot(n, w).wrapping_mul(rn) >> 30).wrapping_mul(rv) >> 30;
            }
            let specular = if rv != 0 {
                let a = nl.wrapping_add(nv);
                // L·V = (l·w) / |w|; |L + V|² in 2.30, V unit within 2^-17.
                let lv = dot(l, w).wrapping_mul(rv) >> 30;
                let hh = light.ll.wrapping_add(1 << 30).wrapping_add(2 * lv);
                // N·H below the table's start (a² < start² |h|², a start rounded down) has a
                // power of zero: no root to take. a and hh below 2^32 here.
                if a <= 0 || hh <= 0 || sq(a) < power.start2.wrapping_mul(hh as u64) {
                    0
                } else {
                    let nh = (a.wrapping_mul(inv_len4(hh)) >> 30).min(i64::from(ONE30)) as u32;
                    u64::from(power.power(nh))
                }
            } else if self.spec_one {
                u64::from(ONE16)
            } else {
                0
            };
            // Most pixels lie outside the highlight.
            if specular == 0 {
                for (c, sum) in sum.iter_mut().enumerate() {
                    *sum += light.kd[c] * diffuse;
                }
            } else {
                for (c, sum) in sum.iter_mut().enumerate() {
                    *sum += light.kd[c] * diffuse + light.ks[c] * specular;
                }
            }
        }
        [0, 1, 2].map(|c| sum[c] + self.ambient[c])
    }

    /// The shininess a [`PowerTable`] for this plan's pixels is made for (0: none is used).
    pub(crate) fn table_shininess(&self) -> u16 {
        if self.specular {
            self.odd << self.twos
        } else {
            0
        }
    }

    /// `x^shininess` in 0.16 from `x` in 0.30.
    #[inline(always)]
    fn power(&self, x: u32) -> u32 {
        plan_power(x, self.odd, self.twos)
    }
}

/// `x^(odd 2^twos)` in 0.16 from `x` in 0.30 (at most 1), as a [`DirectionalPlan`] takes it:
/// the odd power, then `twos` squarings, each rounded half up in 0.30.
#[inline(always)]
fn plan_power(x: u32, odd: u16, twos: u32) -> u32 {
    // mul30 in u64: p <= 2^30, so p² + 2^29 fits and the square stays at most 2^30.
    let mut p = u64::from(if odd == 1 { x } else { pow30(x, odd) });
    let mut t = twos;
    while t != 0 {
        p = (p * p + (1 << 29)) >> 30;
        t -= 1;
    }
    to_q16(p as u32)
}

/// [`spec_cut`] of a material's shininess (`odd 2^twos` as [`Lighting::directional_plan`]
/// splits it).
fn material_cut(material: &Material) -> u64 {
    let s = material.shininess;
    let twos = s.trailing_zeros().min(15);
    spec_cut(s >> twos, twos)
}

/// The cut of a [`DirectionalPlan`]'s zero test of the highlight: with `t` the least `x` whose
/// [`plan_power`] is not zero, at most `t² (1 - 2^-24) / 2^30`.
///
/// Why a highlight that passes the test is zero: `a² < cut (hh >> 30) <= t² (1 - 2^-24) hh /
/// 2^60`, so `a 2^30 / sqrt(hh) < t (1 - 2^-25)`. [`rsqrt_fast`]'s `r` exceeds the root
/// `R = 2^k / sqrt(hh)` (in `(2^30, 2^31]`) by at most 6 units (its Newton step from the table
/// lands at or below the root, and its three truncations of `t` lower `t` by at most 6 units of
/// `2^-30`, which lifts the step by at most `6 y / 2^31 <= 6`), a factor of at most
/// `1 + 6 · 2^-30`. So `N·H = (a r) >> (k - 30) <= a 2^30 (1 + 6 · 2^-30) / sqrt(hh) < t`, and
/// the power, monotonic in `x` (every rounded product is), is zero. (For `shininess = 1` the
/// cut is 0, no test: `t = 2^-17` squared is below the cut's unit.)
fn spec_cut(odd: u16, twos: u32) -> u64 {
    // A caller's exponent is positive; 0 would have no zero highlights to find.
    if odd == 0 {
        return 0;
    }
    // power(0) = 0 and power(1) = 1 for a positive exponent: bisect for the least x.
    let (mut lo, mut hi) = (0u32, ONE30);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if plan_power(mid, odd, twos) != 0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    // floor(t²/2^30) - floor(t²/2^54) - 1 <= t² (1 - 2^-24) / 2^30 (t² below 2^61).
    let t2 = u64::from(hi) * u64::from(hi);
    (t2 >> 30).saturating_sub((t2 >> 54) + 1)
}

/// `2^30 / |v|` (1 / |v| in 2.30) for a 2.30 vector `v` with `|v|² = x` (4.60).
///
/// An interpolated unit vector is somewhat shorter than 1: for `1/2 <= |v| < sqrt(2)` the
/// reciprocal root comes from [`INV_LEN_TABLE`] by the top bits of `x` and one Newton step
/// (`y' = y (3 - x y²) / 2`), within `2^-17` for `|v| >= 0.7` (`2^-15` down to 1/2), with no
/// shift by the length; others take [`rsqrt_fast`] (within `2^-17`). 0 for `x = 0`.
#[inline(always)]
fn inv_len(x: u64) -> i64 {
    // x in [2^58, 2^61): its interval of 2^52 is the table's index, 64 to 511.
    let i = x >> 52;
    if i.wrapping_sub(64) < 512 - 64 {
        // y0 = e 2^15 in 2.30 within 2^-8 of the root (below 2^31), e the table's entry.
        let e = u64::from(INV_LEN_TABLE[i as usize & 511]);
        // x y0² in 2.30, about 2^30: y0² >> 30 = e² (below 2^32) times x >> 30 (below 2^31)
        // stays near 2^60; y0 (3 - t) / 2 = e (3 - t) / 2^16, e (3 - t) below 2^48.
        let t = ((e * e) * (x >> 30)) >> 30;
        ((e * ((3 << 30) - t)) >> 16) as i64
    } else {
        inv_len_far(x)
    }
}

/// [`inv_len`] away from unit length: kept out of line, so that the per-pixel code does not
/// prepare its normalising shift on the way to the table.
#[cold]
#[inline(never)]
fn inv_len_far(x: u64) -> i64 {
    if x == 0 {
        return 0;
    }
    // 2^30 / sqrt(x / 2^60) = r 2^(60 - k) (k is below 60 only for vectors shorter than 1/2,
    // whose inverse lengths stay below 2^61 in 2.30 down to 2^-30 long).
    let (r, k) = rsqrt_fast(x);
    shr(r as i64, k as i32 - 60)
}

/// `2^30 / sqrt(h)` for `h` in 2.30 (`0 < h <= 4`, the squared length of `L + V`): [`inv_len`]
/// of `h / 4`, halved, above 2, so that the table serves lengths from 1/2 to 2.
#[inline(always)]
fn inv_len4(h: i64) -> i64 {
    let x = (h as u64) << 30;
    if x >= 1 << 61 {
        inv_len(x >> 2) >> 1
    } else {
        inv_len(x)
    }
}

/// Scales a triangle's three view vectors (the last three of [`DirectionalPlan::phong_vertex`]'s
/// values) by one factor, so that the longest is of unit length in 2.30. A common factor keeps
/// the direction of every interpolated vector, which is all a pixel uses, and leaves the
/// pixels' vectors near unit length (shorter by at most the ratio of the triangle's distances
/// from the eye), where [`inv_len`] takes its table.
pub(crate) fn phong_triangle(v: &mut [[i32; 6]; 3]) {
    // i32 components: each square at most 2^62, the sum below 2^64.
    let sq = |c: i32| (i64::from(c) * i64::from(c)) as u64;
    let len = v.map(|x| sq(x[3]) + sq(x[4]) + sq(x[5]));
    let big = len[0].max(len[1]).max(len[2]);
    if big == 0 {
        return;
    }
    // c 2^30 / sqrt(big) = c r 2^(30 - k) (k >= 31): |c| r is at most 2^k (1 + 2^-29).
    let (r, k) = rsqrt_fast(big);
    for x in v.iter_mut() {
        for c in &mut x[3..] {
            *c = ((i64::from(*c) * r as i64) >> (k - 30)) as i32;
        }
    }
}

/// `2^15 / sqrt((i + 1/2) / 256)` for `64 <= i < 512` (entry `i`, the first 64 never read; a
/// `static`, as a debug build copies a `const` array onto the stack at every use):
/// [`inv_len`]'s first estimate, `2^30 / |v|` in units of `2^15` at the middle of each
/// interval of `2^52` of `|v|²` in 4.60 from 1/4 to 2.
static INV_LEN_TABLE: [u16; 512] = {
    let mut out = [0u16; 512];
    let mut i = 64;
    while i < 512 {
        // 2^15 sqrt(512 / (2i + 1)) = 2^19 sqrt(2) / sqrt(2i + 1) = 2^40 / sqrt((2i + 1) 2^41).
        let root = isqrt_u64((2 * i as u64 + 1) << 41);
        let q = ((1u64 << 40) + root / 2) / root;
        // At most 2^15 sqrt(512 / 129) = 65,280: fits.
        out[i] = q as u16;
        i += 1;
    }
    out
};

/// Intervals of a [`PowerTable`].
const POWER_STEPS: usize = 128;
/// Fractional bits of a position between two entries of a [`PowerTable`].
const POWER_FRAC: u32 = 16;
/// A [`PowerTable`] starts where `x^s` reaches `2^-POWER_CUT`, taking the power below as
/// zero: at most `255 · 2^-13`, 0.03 of an 8-bit step, lost.
const POWER_CUT: u32 = 13;

/// `x^s` for a Phong pixel's `N·H` by table, made once per draw: `POWER_STEPS + 1` values
/// from where the power reaches `2^-POWER_CUT` up to 1, evenly spaced, interpolated linearly
/// (a multiply-add instead of a squaring per factor of two of the exponent).
///
/// The interpolation's error is at most `s (s - 1) d² / 8` for spacing `d`; the span from
/// the start to 1 is about `ln(2^13) / s`, so it stays below `9² / (8 · 128²)`, 6e-4, for
/// every `s` (0.15 of an 8-bit step at most, where the highlight bends most).
#[derive(Debug, Clone)]
pub(crate) struct PowerTable {
    /// The exponent it is made for (0: not made).
    shininess: u16,
    /// The first argument, in 0.30.
    start: u32,
    /// `(start / 2^15)²` rounded down: the start squared in 0.30, at most its square.
    start2: u64,
    /// `(x - start) scale >> 32` is `x`'s position in units of `2^-POWER_FRAC` entries.
    scale: u64,
    /// `x^s` in 0.16 at each of the points (1 saturated to `u16::MAX`).
    entries: [u16; POWER_STEPS + 1],
}

impl PowerTable {
    /// No table (the power of a plan without highlights is never taken).
    pub(crate) const fn none() -> Self {
        Self {
            shininess: 0,
            start: ONE30,
            start2: 1 << 30,
            scale: 0,
            entries: [0; POWER_STEPS + 1],
        }
    }

    /// The table for `x^shininess` (kept when it is already made for it).
    pub(crate) fn make(&mut self, shininess: u16) {
        if shininess == self.shininess {
            return;
        }
        if shininess == 0 {
            *self = Self::none();
            return;
        }
        // The last x (0.30) whose power is below the cut, by bisection: pow30 is monotonic.
        let cut = ONE30 >> POWER_CUT;
        let (mut lo, mut hi) = (0u32, ONE30);
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            if pow30(mid, shininess) >= cut {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let start = lo;
        // scale = POWER_STEPS 2^(POWER_FRAC + 32) / span (below 2^55): x - start is at most
        // span, so the product stays below 2^55 too.
        let span = ONE30 - start;
        let scale = ((POWER_STEPS as u64) << (POWER_FRAC + 32)) / u64::from(span);
        let mut entries = [0u16; POWER_STEPS + 1];
        for (i, e) in entries.iter_mut().enumerate() {
            // i span / POWER_STEPS below 2^30 + 2^7 span: within u64.
            let x = start + ((i as u64 * u64::from(span)) / POWER_STEPS as u64) as u32;
            *e = to_q16(pow30(x, shininess)).min(u32::from(u16::MAX)) as u16;
        }
        *self = Self {
            shininess,
            start,
            start2: u64::from(start >> 15).pow(2),
            scale,
            entries,
        };
    }

    /// `x^s` in 0.16 for `x` in 0.30 (at most 1).
    #[inline(always)]
    fn power(&self, x: u32) -> u32 {
        let Some(d) = x.checked_sub(self.start) else {
            return 0;
        };
        // The last position below the end, so that an entry follows.
        let last = ((POWER_STEPS as u64) << POWER_FRAC) - 1;
        let pos = ((u64::from(d) * self.scale) >> 32).min(last) as u32;
        let i = (pos >> POWER_FRAC) as usize;
        let f = pos & ((1 << POWER_FRAC) - 1);
        let (a, b) = (u32::from(self.entries[i]), u32::from(self.entries[i + 1]));
        // The entries do not decrease (the rounded power is monotonic in x), so b - a does not
        // wrap; both factors below 2^16.
        a + (((b - a) * f) >> POWER_FRAC)
    }
}

/// `x / 2^sh` rounded down for `sh >= 0`, `x 2^-sh` for `sh < 0` (a signed shift count).
#[inline(always)]
fn shr(x: i64, sh: i32) -> i64 {
    if sh >= 0 {
        x >> sh
    } else {
        x << -sh
    }
}

/// The unit vector along `v` in 2.30 (`2^30` is one), or `None` for the zero vector: one
/// reciprocal square root and three products.
// Out of line: the view vector, point lights and the slow normal each called a copy.
#[inline(never)]
fn unit30(v: [i64; 3]) -> Option<[i64; 3]> {
    let big = v[0].unsigned_abs() | v[1].unsigned_abs() | v[2].unsigned_abs();
    if big == 0 {
        return None;
    }
    // Components below 2^31 keep the sum of the squares within u64; only the direction counts.
    let shift = (64 - big.leading_zeros()).saturating_sub(31);
    let v = v.map(|c| c >> shift);
    let sq = v
        .iter()
        .map(|&c| c.unsigned_abs() * c.unsigned_abs())
        .sum::<u64>();
    if sq == 0 {
        return None;
    }
    // c / |v| = c r / 2^k, in 2.30: c r >> (k - 30), |c r| < 2^62.
    let (r, k) = rsqrt_u64(sq);
    let r = r as i64;
    Some(v.map(|c| (c * r + (1 << (k - 31))) >> (k - 30)))
}

/// [`unit30`] for a vector whose components have `frac` fractional bits, taking a shortcut
/// when it is already of unit length within `2^-12` (a mesh normal): one Newton step of the
/// reciprocal square root from 1, `(3 - |v|²) / 2`, then within `2^-25` of the exact root.
#[inline(always)]
fn unit30_near(v: [i64; 3], frac: u32) -> Option<[i64; 3]> {
    if frac <= 24 {
        let one = 1i64 << (2 * frac);
        // |v|² - 1 in units of 2^-2frac; components of a near-unit vector are below 2^25.
        let small = v.iter().all(|c| c.unsigned_abs() < 1 << (frac + 1));
        if small {
            let d = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - one;
            if d.unsigned_abs() < (one >> 12) as u64 {
                // r = (3 - |v|²) / 2 = 1 - d / 2, in 2.30 (d / 2 in units of 2^-2frac).
                let half = if 2 * frac >= 29 {
                    d >> (2 * frac - 29)
                } else {
                    d << (29 - 2 * frac)
                };
                let r = (1i64 << 30) - half;
                let sh = frac;
                return Some(v.map(|c| (c * r + (1 << (sh - 1))) >> sh));
            }
        }
    }
    unit30(v)
}

/// The dot product of two 2.30 vectors, in 2.30.
#[inline(always)]
fn dot30(a: [i64; 3], b: [i64; 3]) -> i64 {
    (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + (1 << 29)) >> 30
}

/// The three channels as `u32`.
fn channels(c: Rgb888) -> [u32; 3] {
    [c.r().into(), c.g().into(), c.b().into()]
}

/// Each sum clamped to full intensity.
fn clamp(sum: [u64; 3]) -> [u64; 3] {
    sum.map(|s| s.min(SUM_MAX))
}

/// A cosine as a signed 2.30 integer.
fn to_q30<S: Scalar>(x: S) -> i64 {
    i64::from(x.to_scaled_int(30))
}

/// A 2.30 value clamped to `[0, 1]`, as unsigned 0.30.
fn unit_q30(x: i64) -> u32 {
    x.clamp(0, i64::from(ONE30)) as u32
}

/// `a · b` in 0.30, rounded half up; both at most 1.
fn mul30(a: u32, b: u32) -> u32 {
    ((u64::from(a) * u64::from(b) + (1 << 29)) >> 30) as u32
}

/// `base^exp` in 0.30 by repeated squaring, `base` at most 1; `0^0 = 1`.
fn pow30(mut base: u32, mut exp: u16) -> u32 {
    let mut acc = ONE30;
    while exp != 0 {
        if exp & 1 != 0 {
            acc = mul30(acc, base);
        }
        exp >>= 1;
        if exp != 0 {
            base = mul30(base, base);
        }
    }
    acc
}

/// A 0.30 factor rounded half up to 0.16.
fn to_q16(x: u32) -> u32 {
    (x + (1 << 13)) >> 14
}

/// Phong's `max(0, R·V)^s` in 0.16 from the cosines `N·L`, `N·V`, `L·V` in 2.30.
fn phong(nl: i64, nv: i64, lv: i64, s: u16) -> u32 {
    // R·V = (2 (N·L) N - L)·V = 2 (N·L)(N·V) - L·V.
    let rv = ((2 * nl * nv + (1 << 29)) >> 30) - lv;
    to_q16(pow30(unit_q30(rv), s))
}

/// Blinn-Phong's `max(0, N·H)^s` in 0.16 from the unit normal `n` and `h = L + V`.
fn blinn<S: Scalar>(n: Vec3<S>, h: Vec3<S>, s: u16) -> u32 {
    // N·H = N·h / |h|. Both come exactly from the components in 4.28 (|n| <= 1, |h| <= 2), so that a
    // short h (light and eye on opposite sides) loses no more than its components' rounding.
    let c = |x: S| i64::from(x.to_scaled_int(28));
    let (hx, hy, hz) = (c(h.x), c(h.y), c(h.z));
    // N·h in 0.56, about 2^57 at most; h·h in 0.56, about 2^58 at most.
    let a = c(n.x) * hx + c(n.y) * hy + c(n.z) * hz;
    let hh = (hx * hx + hy * hy + hz * hz) as u64;
    if a <= 0 || hh == 0 {
        return 0;
    }
    // N·h in 0.28 (below 2^30) times r / 2^k ≈ 1 / sqrt(h·h) in units of 2^-28: N·H in 0.30
    // is (N·h) r / 2^(k - 30), the product below 2^61.
    let a = ((a + (1 << 27)) >> 28) as u64;
    let (r, k) = rsqrt_u64(hh);
    let nh = ((a * r) >> (k - 30)).min(u64::from(ONE30)) as u32;
    to_q16(pow30(nh, s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Fx16;

    fn lighting() -> Lighting<Fx16, 2> {
        let material = Material {
            ambient: Rgb888::new(40, 30, 30),
            diffuse: Rgb888::new(220, 140, 80),
            specular: Rgb888::WHITE,
            shininess: 16,
        };
        let eye = Vec3::from_ints(0, 0, 3);
        let mut l = Lighting::new(material, Rgb888::WHITE, Specular::BlinnPhong, eye);
        l.add_light(Light::directional(Vec3::from_ints(1, 1, 1)))
            .unwrap();
        l.add_light(Light::directional(Vec3::from_ints(-1, 0, 2)))
            .unwrap();
        l
    }

    /// The plan's `sums` as first written (before its shortcuts), the reference its results
    /// must match bit for bit.
    fn reference_sums<S: Scalar, const N: usize>(
        plan: &DirectionalPlan<N>,
        position: Vec3<S>,
        normal: Vec3<S>,
    ) -> Option<[u64; 3]> {
        let (position, normal) = (position.raw_bits()?, normal.raw_bits()?);
        // The format's, a constant: the plan is made only for it.
        let f = S::RAW_FRAC;
        let n = normal;
        // Raw components are i32s: each square below 2^62, the sum below 2^64.
        let sq = |c: i64| (c * c) as u64;
        let nn = sq(n[0]) + sq(n[1]) + sq(n[2]);
        let one = 1u64 << (2 * f);
        // 1 / |n| in 2.30: a normal of unit length within 2^-12 (a mesh's) takes one Newton
        // step from 1, within 2^-25; any other of length 2^-8 to 2^8 a reciprocal square root.
        let rn = if nn.abs_diff(one) < one >> 12 {
            (1i64 << 30) - shr(nn as i64 - one as i64, 2 * f as i32 - 29)
        } else if nn >= one >> 16 && nn >> 16 < one {
            let (r, k) = rsqrt_fast(nn);
            // 2^f / sqrt(nn) in 2.30 = r 2^(f + 30 - k), below 2^39.
            shr(r as i64, k as i32 - f as i32 - 30)
        } else {
            return None;
        };
        // N·X in 2.30 for a 2.30 vector x: n·x is below 2^(f + 40) (|n| < 2^8), and n·x / 2^f
        // is |n| N·X in 2.30, so that times rn (2^30 / |n|) it stays below 2^62.
        let cos =
            |x: [i64; 3]| (((n[0] * x[0] + n[1] * x[1] + n[2] * x[2]) >> f) * rn + (1 << 29)) >> 30;
        let mut sum = plan.ambient;
        let e = &plan.eye;
        let w = [e[0] - position[0], e[1] - position[1], e[2] - position[2]];
        // The eye at the point (no highlight there) and an eye far away along an axis take the
        // general path.
        let big = w[0].unsigned_abs() | w[1].unsigned_abs() | w[2].unsigned_abs();
        if plan.specular && big.wrapping_sub(1) >= (1 << 30) - 1 {
            return None;
        }
        // V in 2.30 and N·V, for a specular power, made when a light first reaches the point.
        let mut view: Option<([i64; 3], i64)> = None;
        for light in &plan.lights {
            let nl = cos(light.l);
            if nl <= 0 {
                continue;
            }
            let (view, nv) = *view.get_or_insert_with(|| {
                if !plan.specular {
                    return ([0; 3], 0);
                }
                // Not zero (tested above), each square below 2^60.
                let ww = sq(w[0]) + sq(w[1]) + sq(w[2]);
                // c / |w| = c r / 2^k, in 2.30: |c r| < 2^61.
                let (r, k) = rsqrt_fast(ww);
                let r = r as i64;
                let unit = |c: i64| (c * r + (1 << (k - 31))) >> (k - 30);
                let v = [unit(w[0]), unit(w[1]), unit(w[2])];
                (v, cos(v))
            });
            let diffuse = ((nl + (1 << 13)) >> 14).min(i64::from(ONE16)) as u64;
            let specular = if plan.specular {
                // N·H = N·h / |h| with h = L + V: N·h = N·L + N·V, and |h|² from h's
                // components (L is unit only to the format's step, so not 2 + 2 L·V).
                let l = light.l;
                let h = [l[0] + view[0], l[1] + view[1], l[2] + view[2]];
                let a = nl + nv;
                // Components below 2^31: each square below 2^62.
                let hh = sq(h[0]) + sq(h[1]) + sq(h[2]);
                if a <= 0 || hh == 0 {
                    0
                } else {
                    // 1 / |h| = 2^30 / sqrt(hh) = r 2^(30 - k); a r below 2^62.
                    let (r, k) = rsqrt_fast(hh);
                    let nh = ((a as u64 * r) >> (k - 30)).min(u64::from(ONE30)) as u32;
                    u64::from(reference_power(plan, nh))
                }
            } else if plan.spec_one {
                u64::from(ONE16)
            } else {
                0
            };
            for (c, sum) in sum.iter_mut().enumerate() {
                *sum += light.kd[c] * diffuse + light.ks[c] * specular;
            }
        }
        Some([
            sum[0].min(plan.full[0]),
            sum[1].min(plan.full[1]),
            sum[2].min(plan.full[2]),
        ])
    }

    fn reference_power<const N: usize>(plan: &DirectionalPlan<N>, x: u32) -> u32 {
        let mut p = if plan.odd == 1 { x } else { pow30(x, plan.odd) };
        for _ in 0..plan.twos {
            p = mul30(p, p);
        }
        to_q16(p)
    }

    /// xorshift64.
    fn next(x: &mut u64) -> u64 {
        *x ^= *x << 13;
        *x ^= *x >> 7;
        *x ^= *x << 17;
        *x
    }

    fn plans_for_test<S: Scalar>(seed: &mut u64) -> Vec<DirectionalPlan<2>, 64> {
        let mut out = Vec::new();
        let shininess = [
            16u16, 0, 1, 2, 3, 5, 8, 12, 16, 24, 33, 64, 100, 128, 255, 1000,
        ];
        for (i, &s) in shininess.iter().enumerate() {
            for spec in [Specular::BlinnPhong, Specular::None] {
                let r = |x: &mut u64| (next(x) % 256) as u8;
                let material = Material {
                    ambient: Rgb888::new(r(seed), r(seed), r(seed)),
                    diffuse: Rgb888::new(r(seed), r(seed), r(seed)),
                    specular: Rgb888::new(r(seed), r(seed), r(seed)),
                    shininess: s,
                };
                let c = |x: &mut u64| S::from_ratio((next(x) % 2001) as i64 - 1000, 256);
                let eye = Vec3::new(c(seed), c(seed), c(seed));
                let ambient = Rgb888::new(r(seed), r(seed), r(seed));
                let mut l = Lighting::<S, 2>::new(material, ambient, spec, eye);
                let lights = 1 + i % 2;
                for _ in 0..lights {
                    let d = Vec3::new(c(seed), c(seed), c(seed));
                    let color = Rgb888::new(r(seed), r(seed), r(seed));
                    let _ = l.add_light(Light::Directional {
                        direction: d,
                        color,
                    });
                }
                if i == 0 {
                    // The M1 scene's settings.
                    l = Lighting::new(
                        Material {
                            ambient: Rgb888::new(40, 30, 30),
                            diffuse: Rgb888::new(220, 140, 80),
                            specular: Rgb888::WHITE,
                            shininess: 16,
                        },
                        Rgb888::WHITE,
                        spec,
                        Vec3::from_ints(0, 0, 3),
                    );
                    l.add_light(Light::directional(Vec3::from_ints(1, 1, 1)))
                        .unwrap();
                }
                let scale = [255 * 255, 31 << 11, 63 << 10];
                let bias = [0, (1 << 31) + (1 << 42), (1 << 31) + (1 << 41)];
                for (sc, b, bits) in [([255 * 255; 3], [0; 3], 16), (scale, bias, 32)] {
                    if let Some(p) = l.directional_plan(sc, bits, b) {
                        let _ = out.push(p);
                    }
                }
            }
        }
        out
    }

    /// A normal as a mesh stores it: unit length rounded to the format, or to four decimals
    /// first (an OBJ file's), or not unit length at all.
    fn normal_for_test<S: Scalar>(x: &mut u64) -> Vec3<S> {
        let kind = next(x) % 8;
        let c = |x: &mut u64| (next(x) % 20_001) as i64 - 10_000;
        let (a, b, c) = (c(x), c(x), c(x));
        let len2 = (a * a + b * b + c * c).max(1) as u64;
        let len = isqrt_u64(len2 << 32);
        // Components of a unit vector in 0.32 (rounded down), then to four decimals or the
        // format.
        let unit = |v: i64| (v << 48) / len.max(1) as i64;
        let f = S::RAW_FRAC;
        let to_raw = |v: i64| -> i32 {
            match kind {
                0..=3 => ((v * 10_000 + (1 << 31)) >> 32) as i32 * (1 << f) / 10_000,
                4 | 5 => ((v + (1 << (31 - f))) >> (32 - f)) as i32,
                6 => (next(&mut v.unsigned_abs()) % (1 << (f + 2))) as i32 - (1 << (f + 1)),
                _ => (v >> (32 - f - 3)) as i32,
            }
        };
        let r = |v: i64| S::from_raw(i64::from(to_raw(v)));
        Vec3::new(r(unit(a)), r(unit(b)), r(unit(c)))
    }

    fn plan_matches_reference<S: Scalar>() {
        let mut seed = 0x2545_f491_4f6c_dd1d;
        let plans = plans_for_test::<S>(&mut seed);
        assert!(plans.len() > 20);
        let mut checked = 0u32;
        for plan in &plans {
            for _ in 0..4000 {
                let n = normal_for_test::<S>(&mut seed);
                let c = |x: &mut u64| S::from_ratio((next(x) % 4001) as i64 - 2000, 1000);
                let p = Vec3::new(c(&mut seed), c(&mut seed), c(&mut seed));
                let want = reference_sums(plan, p, n);
                assert_eq!(plan.sums(p, n), want, "{p:?} {n:?}");
                checked += u32::from(want.is_some());
            }
        }
        assert!(checked > 100_000, "{checked}");
    }

    /// [`spec_cut`]'s test passes only highlights whose power is zero: at the largest `a` it
    /// passes for a given `|h|²`, over `|h|²` from tiny to the largest the plan forms, the
    /// power of `N·H` as the plan computes it is zero; and a few percent above, it is not.
    #[test]
    fn spec_cut_passes_only_zero_highlights() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for shininess in [1u16, 2, 3, 5, 7, 8, 16, 17, 24, 64, 100, 255, 1024, 40_000] {
            let twos = shininess.trailing_zeros().min(15);
            let odd = shininess >> twos;
            let cut = spec_cut(odd, twos);
            // x^1 is zero only below 2^-17, whose square the cut's 2.30 does not hold: no test.
            if cut == 0 {
                assert_eq!(shininess, 1);
                continue;
            }
            let mut above = 0;
            for i in 0..20_000u64 {
                // |h|² in 4.60: at most (2 (1 + 2^-15))² 2^60, and tiny where L and V nearly
                // cancel.
                let hh = match i {
                    0..64 => (1 << 62) + (1 << 49) - i,
                    64..1000 => next(&mut x) >> (2 + next(&mut x) % 60),
                    _ => (1 << 56) + next(&mut x) % ((1 << 62) - (1 << 56)),
                }
                .max(1);
                let bound = cut * (hh >> 30);
                if bound == 0 {
                    continue;
                }
                // The largest a with a² < bound.
                let a = isqrt_u64(bound - 1);
                assert!(a * a < bound);
                let (r, k) = rsqrt_fast(hh);
                let nh = |a: u64| ((a * r) >> (k - 30)).min(u64::from(ONE30)) as u32;
                assert_eq!(plan_power(nh(a), odd, twos), 0, "{shininess} {hh} {a}");
                above += u32::from(plan_power(nh(a + (a >> 5) + 1), odd, twos) != 0);
            }
            // The test is tight: 3 % more than its largest a makes a highlight almost always.
            assert!(above > 18_000, "{shininess}: {above}");
        }
    }

    /// `inv_len` is one Newton step from its table in the table's range, exactly as its
    /// comments define it (`y0` the entry times 2^15, truncating each product), taken here in
    /// `u128`; 0 for 0; and `rsqrt_fast`'s root outside the range.
    #[test]
    fn inv_len_is_its_newton_step() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for i in 0..400_000u64 {
            let v = match i {
                0..64 => 1 << i,
                64..128 => (1 << 58) + (i - 64) - 32,
                128..192 => (1 << 61) + (i - 128) - 32,
                _ => {
                    x ^= x << 13;
                    x ^= x >> 7;
                    x ^= x << 17;
                    if i % 4 == 0 {
                        x >> (x % 64)
                    } else {
                        (1 << 58) + x % ((1 << 61) - (1 << 58))
                    }
                }
            };
            let want = if (1 << 58..1 << 61).contains(&v) {
                let y0 = u128::from(INV_LEN_TABLE[(v >> 52) as usize]) << 15;
                let t = (((y0 * y0) >> 30) * u128::from(v >> 30)) >> 30;
                ((y0 * ((3 << 30) - t)) >> 31) as i64
            } else if v == 0 {
                0
            } else {
                let (r, k) = rsqrt_fast(v);
                shr(r as i64, k as i32 - 60)
            };
            assert_eq!(inv_len(v), want, "{v}");
        }
    }

    /// A [`PowerTable`]'s entries never decrease (its interpolation subtracts neighbours
    /// without a saturating step), and its power stays within its entries' range.
    #[test]
    fn power_table_entries_never_decrease() {
        let mut table = PowerTable::none();
        for shininess in [1u16, 2, 3, 7, 16, 33, 64, 128, 1000, u16::MAX] {
            table.make(shininess);
            assert!(
                table.entries.windows(2).all(|e| e[0] <= e[1]),
                "{shininess}"
            );
            for x in (0..=ONE30).step_by(4099) {
                assert!(table.power(x) <= u32::from(u16::MAX));
            }
        }
    }

    /// The plan's shortcuts change no bit of its sums: against the reference over random
    /// plans, normals and positions.
    #[test]
    fn plan_sums_match_the_reference() {
        plan_matches_reference::<Fx16>();
        plan_matches_reference::<crate::math::Fx8>();
    }

    /// The plan's results over the extremes of its inputs: no overflow (the tests run with
    /// overflow checks), sums within full intensity, and the general path wherever the plan
    /// declines.
    #[test]
    fn plan_never_overflows() {
        let l = lighting();
        let plan = l.directional_plan([255 * 255; 3], 16, [0; 3]).unwrap();
        let mut power = PowerTable::none();
        power.make(plan.table_shininess());
        let full = (255 * 255) << 16;
        let edges = [i32::MIN, -(1 << 30), -1, 0, 1, 1 << 16, 1 << 30, i32::MAX];
        for a in edges {
            for b in edges {
                for c in edges {
                    let v = [a, b, c, c, a, b];
                    assert!(plan.phong_pixel(&v, &power).iter().all(|&s| s <= full));
                    let p = Vec3::new(Fx16::from_bits(a), Fx16::from_bits(b), Fx16::from_bits(c));
                    let n = Vec3::new(Fx16::from_bits(c), Fx16::from_bits(a), Fx16::from_bits(b));
                    if let Some(s) = plan.sums(p, n) {
                        assert!(s.iter().all(|&s| s <= full));
                    }
                    let _ = plan.phong_vertex(p, n);
                }
            }
        }
    }

    /// A point light or Phong highlights take the general path; so does a float format.
    #[test]
    fn plan_only_for_directional_blinn_phong() {
        let mut l = lighting();
        assert!(l.directional_plan([1; 3], 32, [0; 3]).is_some());
        l.specular = Specular::Phong;
        assert!(l.directional_plan([1; 3], 32, [0; 3]).is_none());
        let mut p = lighting();
        p.lights.clear();
        p.add_light(Light::point(Vec3::from_ints(0, 2, 0))).unwrap();
        assert!(p.directional_plan([1; 3], 32, [0; 3]).is_none());
    }
}
