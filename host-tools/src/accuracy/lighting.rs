//! The report's lighting section: the shaders' directional-light plan (what `GouraudLit`,
//! `PhongLit` and `FlatLit` use once a draw has begun, for fixed-point formats and directional
//! lights) against the `f64` formula, next to the general path, over random scenes.
//! Deterministic and quick (no scenes loaded, no callgrind).

use fixtures::reference3d::{lit, RefLight};
use fixtures::scenes::XorShift32;
use rasterizer_core::prelude::*;
use rasterizer_core::shade::{Shading, VertexIn};
use std::fmt::Write as _;

type V3 = [f64; 3];

/// WORKLOADS.md's xorshift32 (`fixtures::scenes::XorShift32`) with the draws these scenes need.
struct Rng(XorShift32);

impl Rng {
    fn next(&mut self) -> u32 {
        self.0.next_u32()
    }
    fn unit(&mut self) -> f64 {
        self.0.unit()
    }
    fn below(&mut self, n: u32) -> u32 {
        self.next() % n
    }
    fn color(&mut self) -> Rgb888 {
        let c = self.next().to_le_bytes();
        Rgb888::new(c[0], c[1], c[2])
    }
    fn ball(&mut self, r: f64) -> V3 {
        loop {
            let v = [self.unit(), self.unit(), self.unit()];
            if dot(v, v) <= 1.0 {
                return v.map(|x| x * r);
            }
        }
    }
    fn direction(&mut self) -> V3 {
        loop {
            let v = self.ball(1.0);
            if dot(v, v) > 0.01 {
                return unit(v);
            }
        }
    }
}

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(a: V3) -> V3 {
    let l = dot(a, a).sqrt();
    a.map(|x| x / l)
}

/// The 16.16 vector nearest `v` and its exact value.
fn q(v: V3) -> (Vec3<Fx16>, V3) {
    let bits = v.map(|x| (x * 65536.0).round() as i32);
    let fx = |i: usize| Fx16::from_bits(bits[i]);
    (
        Vec3::new(fx(0), fx(1), fx(2)),
        bits.map(|b| f64::from(b) / 65536.0),
    )
}

/// One to three coloured directional lights, Blinn-Phong (one scene in five without a
/// highlight), shininess 0 to 64, a dim grey ambient light, the eye 1.5 to 8 from the origin.
struct Scene {
    material: Material,
    ambient: Rgb888,
    model: Specular,
    eye: V3,
    lights: Vec<(V3, Rgb888)>,
}

impl Scene {
    fn random(r: &mut Rng) -> Scene {
        let material = Material {
            ambient: r.color(),
            diffuse: r.color(),
            specular: r.color(),
            shininess: r.below(65) as u16,
        };
        let model = if r.below(5) == 0 {
            Specular::None
        } else {
            Specular::BlinnPhong
        };
        let d = 1.5 + 6.5 * f64::from(r.below(1000)) / 1000.0;
        let eye = q(r.direction().map(|x| x * d)).1;
        let lights = (0..1 + r.below(3))
            .map(|_| (q(r.direction()).1, r.color()))
            .collect();
        let a = r.below(64) as u8;
        Scene {
            material,
            ambient: Rgb888::new(a, a, a),
            model,
            eye,
            lights,
        }
    }

    fn lighting(&self) -> Lighting<Fx16, 3> {
        let mut l = Lighting::new(self.material, self.ambient, self.model, q(self.eye).0);
        for &(d, color) in &self.lights {
            let direction = q(d).0;
            // Unit directions of a 16.16 grid are never zero.
            let _ = l.add_light(Light::Directional { direction, color });
        }
        l
    }

    fn reference(&self, position: V3, normal: V3) -> [f64; 3] {
        let lights: Vec<RefLight> = self.lights.iter().map(|&(d, c)| (false, d, c)).collect();
        lit(
            &self.material,
            self.ambient,
            self.model,
            self.eye,
            &lights,
            position,
            normal,
        )
    }
}

fn input(position: Vec3<Fx16>, normal: Vec3<Fx16>) -> VertexIn<Fx16> {
    VertexIn {
        position,
        normal,
        color: Rgb888::WHITE,
        uv: [0, 0],
    }
}

/// Worst and mean error of the worst channel, in 8-bit steps.
#[derive(Default)]
pub struct Errors {
    /// The largest.
    pub max: f64,
    sum: f64,
    n: usize,
}

impl Errors {
    fn add(&mut self, got: [f64; 3], want: [f64; 3]) {
        let e = (0..3).map(|c| (got[c] - want[c]).abs()).fold(0.0, f64::max);
        self.max = self.max.max(e);
        self.sum += e;
        self.n += 1;
    }
    /// The mean.
    pub fn mean(&self) -> f64 {
        self.sum / self.n.max(1) as f64
    }
}

/// Gouraud vertices: `(plan, general)`, channels with 8 fractional bits (Rgb888), unrounded.
pub fn gouraud(count: usize) -> (Errors, Errors) {
    let mut r = Rng(XorShift32::seeded(0x1234_5678));
    let (mut plan, mut general) = (Errors::default(), Errors::default());
    for _ in 0..count {
        let scene = Scene::random(&mut r);
        let lighting = scene.lighting();
        let mut shader = GouraudLit::<Fx16, Rgb888, 3>::new(lighting.clone());
        shader.begin_frame(None);
        let (p, pf) = q(r.ball(1.0));
        let (n, nf) = q(r.direction());
        let want = scene.reference(pf, nf);
        let got = shader
            .vertex(&input(p, n))
            .map(|c| f64::from(c - 128) / 256.0);
        plan.add(got, want);
        let fine = lighting.shade_fine(p, n).map(|c| f64::from(c) / 256.0);
        general.add(fine, want);
    }
    (plan, general)
}

/// Phong pixels inside triangles about `size` across whose vertex normals lie up to about 25
/// degrees apart: `(plan, general, share of pixels where the two differ)`, Rgb888 pixels.
pub fn phong(count: usize, size: f64) -> (Errors, Errors, f64) {
    let mut r = Rng(XorShift32::seeded(0x8765_4321));
    let (mut plan, mut general, mut differ) = (Errors::default(), Errors::default(), 0usize);
    for _ in 0..count {
        let scene = Scene::random(&mut r);
        let lighting = scene.lighting();
        let mut fast = PhongLit::<Fx16, Rgb888, 3>::new(lighting.clone());
        fast.begin_frame(None);
        let mut slow = PhongLit::<Fx16, Rgb888, 3>::new(lighting);
        let centre = r.ball(1.0);
        let base = r.direction();
        let corners: Vec<(Vec3<Fx16>, V3, Vec3<Fx16>, V3)> = (0..3)
            .map(|_| {
                let off = r.ball(size / 2.0);
                let (p, pf) = q([0, 1, 2].map(|i| centre[i] + off[i]));
                let bend = r.ball(0.45);
                let (n, nf) = q(unit([0, 1, 2].map(|i| base[i] + bend[i])));
                (p, pf, n, nf)
            })
            .collect();
        let (a, b) = (r.below(1 << 16), r.below(1 << 16));
        let (a, b) = (a.min(b), a.max(b));
        let w = [a, b - a, (1 << 16) - b].map(i64::from);
        let mix = |v: [[i32; 6]; 3]| {
            [0, 1, 2, 3, 4, 5].map(|k| {
                let s: i64 = (0..3).map(|i| w[i] * i64::from(v[i][k])).sum();
                ((s + (1 << 15)) >> 16) as i32
            })
        };
        let mut fast_v = [0, 1, 2].map(|i| fast.vertex(&input(corners[i].0, corners[i].2)));
        let mut slow_v = [0, 1, 2].map(|i| slow.vertex(&input(corners[i].0, corners[i].2)));
        // As the pipeline does once per triangle, before its pixels.
        fast.triangle(&mut fast_v);
        slow.triangle(&mut slow_v);
        let bf = w.map(|x| x as f64 / 65536.0);
        let mixf = |f: &dyn Fn(usize) -> V3| {
            [0, 1, 2].map(|k| (0..3).map(|i| bf[i] * f(i)[k]).sum::<f64>())
        };
        let position = mixf(&|i| corners[i].1);
        let normal = mixf(&|i| unit(corners[i].3));
        let want = scene.reference(position, normal);
        let px = |c: Rgb888| [c.r(), c.g(), c.b()].map(f64::from);
        let (got_fast, got_slow) = (fast.pixel(&mix(fast_v)), slow.pixel(&mix(slow_v)));
        differ += usize::from(got_fast != got_slow);
        plan.add(px(got_fast), want);
        general.add(px(got_slow), want);
    }
    (plan, general, differ as f64 / count.max(1) as f64)
}

/// Cases per row: enough for the worst case to settle, quick in a debug build.
const CASES: usize = 4_000;

/// The triangle sizes of the Phong rows (M1's triangles are about 0.05 to 0.1 across, seen
/// from 3).
const SIZES: [f64; 4] = [0.05, 0.1, 0.2, 0.4];

/// Appends the section.
pub fn section(s: &mut String) {
    let _ = writeln!(s, "## Lighting: the directional-light plan\n");
    let _ = writeln!(
        s,
        "For a fixed-point format with directional lights only (Blinn-Phong or no highlight), \
         `GouraudLit`, `FlatLit` and `PhongLit` light through a plan made once per draw: the \
         normal's length applied to the cosines (one Newton step from 1 for a mesh's unit \
         normals, else a reciprocal square root from a 384-entry table and one Newton step, \
         within 2^-17), `N·H = (N·L + N·V) / |L + V|`, and the colour products scaled to the \
         target's channels, so that a channel is a multiply-add and a shift (no 64-bit \
         division). `PhongLit` then interpolates the unit normal (in 2.30) and the view vector \
         (scaled once per triangle so that the longest of its three is of unit length), \
         renormalises both per pixel from a 512-entry table and one Newton step, takes `N·H` \
         from the cosines with `|L + V|² = |L|² + 1 + 2 L·V` and the same table (no root where \
         the highlight is known to be zero), and the power from a 129-entry table made per \
         draw. Random scenes (xorshift32): 1 to 3 \
         coloured lights, \
         shininess 0 to 64, points in the unit ball, the eye 1.5 to 8 away; errors of the worst \
         channel against the `f64` formula in 8-bit steps, {CASES} cases a row. Gouraud: the \
         vertex's channels (8 fractional bits), unrounded. Phong: an Rgb888 pixel (its rounding \
         alone gives up to 0.5) inside a triangle of the given size, its vertex normals up to \
         about 25 degrees apart, against the exact position and the renormalised interpolated \
         normal; the general path is `PhongLit` without a plan (interpolating positions).\n"
    );
    let _ = writeln!(
        s,
        "| shading | triangle size | general: max | general: mean | plan: max | plan: mean | pixels that differ |"
    );
    let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---:|");
    let (plan, general) = gouraud(CASES);
    let _ = writeln!(
        s,
        "| Gouraud (per vertex) | - | {:.4} | {:.4} | {:.4} | {:.4} | - |",
        general.max,
        general.mean(),
        plan.max,
        plan.mean()
    );
    for size in SIZES {
        let (plan, general, differ) = phong(CASES, size);
        let _ = writeln!(
            s,
            "| Phong (per pixel) | {size} | {:.4} | {:.4} | {:.4} | {:.4} | {:.2} % |",
            general.max,
            general.mean(),
            plan.max,
            plan.mean(),
            100.0 * differ
        );
    }
    let _ = writeln!(s);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/ACCURACY.md holds the section as this code writes it.
    #[test]
    fn accuracy_md_has_the_current_section() {
        let mut s = String::new();
        section(&mut s);
        crate::accuracy::assert_report_holds(&s);
    }
}
