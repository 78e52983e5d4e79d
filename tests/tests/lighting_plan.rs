//! The shaders' fast lighting for directional lights (what `GouraudLit` and `PhongLit` use once
//! a draw has begun) against the f64 reference of the documented formula, next to the general
//! path (`Lighting::shade_fine`, and `PhongLit` without `begin_frame`), over random scenes.
//!
//! Gouraud: one lit vertex, its channel values (8 fractional bits for Rgb888) against the
//! unrounded reference. Phong: a pixel inside a small triangle, from the vertices' values
//! interpolated as the pipeline does (integer weights), against the reference lit with the
//! exact interpolated position and the renormalised interpolated unit normal.

use fixtures::reference3d::{lit, RefLight};
use fixtures::scenes::XorShift32;
use rasterizer_core::color::ShadeColor;
use rasterizer_core::prelude::*;
use rasterizer_core::shade::{Shading, Stored, VertexIn};

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
    /// A point in the ball of radius `r`.
    fn ball(&mut self, r: f64) -> V3 {
        loop {
            let v = [self.unit(), self.unit(), self.unit()];
            if dot(v, v) <= 1.0 {
                return v.map(|x| x * r);
            }
        }
    }
    /// A unit vector.
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

/// The 16.16 value nearest `v`, and its exact value back.
fn q(v: V3) -> (Vec3<Fx16>, V3) {
    let bits = v.map(|x| (x * 65536.0).round() as i32);
    (
        Vec3::new(
            Fx16::from_bits(bits[0]),
            Fx16::from_bits(bits[1]),
            Fx16::from_bits(bits[2]),
        ),
        bits.map(|b| f64::from(b) / 65536.0),
    )
}

/// A random scene: one to three white or coloured directional lights, Blinn-Phong (or no
/// highlight), shininess up to 64, the eye 1.5 to 8 from the origin.
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
        let eye = r
            .direction()
            .map(|x| x * (1.5 + 6.5 * f64::from(r.below(1000)) / 1000.0));
        let lights = (0..1 + r.below(3))
            .map(|_| (q(r.direction()).1, r.color()))
            .collect();
        // Dim ambient light, so that the lit terms are seen rather than clamped.
        let a = (r.below(64)) as u8;
        Scene {
            material,
            ambient: Rgb888::new(a, a, a),
            model,
            eye: q(eye).1,
            lights,
        }
    }

    fn lighting(&self) -> Lighting<Fx16, 3> {
        let mut l = Lighting::new(self.material, self.ambient, self.model, q(self.eye).0);
        for &(d, color) in &self.lights {
            l.add_light(Light::Directional {
                direction: q(d).0,
                color,
            })
            .unwrap();
        }
        l
    }

    /// The reference colour, unrounded, in 8-bit steps.
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

/// Worst and mean of the worst channel's error, in 8-bit steps.
#[derive(Default)]
struct Errors {
    max: f64,
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
    fn mean(&self) -> f64 {
        self.sum / self.n as f64
    }
}

/// `(plan, general)` errors of Gouraud vertices over `count` random scenes.
fn gouraud(count: usize) -> (Errors, Errors) {
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
        // Rgb888 channels carry 8 fractional bits and half a step.
        let got = shader
            .vertex(&input(p, n))
            .map(|c| f64::from(c - 128) / 256.0);
        plan.add(got, want);
        let fine = lighting.shade_fine(p, n).map(|c| f64::from(c) / 256.0);
        general.add(fine, want);
    }
    (plan, general)
}

/// `(plan, general)` errors of Phong pixels inside random triangles of about `size` across
/// (their vertex normals up to about 25 degrees apart), over `count` pixels; with `one_light`
/// each scene keeps only its first light and a Blinn-Phong highlight.
fn phong(count: usize, size: f64, one_light: bool) -> (Errors, Errors) {
    let mut r = Rng(XorShift32::seeded(0x8765_4321));
    let (mut plan, mut general) = (Errors::default(), Errors::default());
    for _ in 0..count {
        let mut scene = Scene::random(&mut r);
        if one_light {
            scene.lights.truncate(1);
            scene.model = Specular::BlinnPhong;
        }
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
        // Integer weights summing to 2^16, as a pixel's barycentric weights.
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
        let position = [0, 1, 2].map(|k| (0..3).map(|i| bf[i] * corners[i].1[k]).sum::<f64>());
        let units: Vec<V3> = corners.iter().map(|c| unit(c.3)).collect();
        let normal = [0, 1, 2].map(|k| (0..3).map(|i| bf[i] * units[i][k]).sum::<f64>());
        let want = scene.reference(position, normal);
        let px = |c: Rgb888| [c.r(), c.g(), c.b()].map(f64::from);
        plan.add(px(fast.pixel(&mix(fast_v))), want);
        general.add(px(slow.pixel(&mix(slow_v))), want);
    }
    (plan, general)
}

// Measured (8-bit steps, worst channel, against the unrounded reference), over the cases below:
// Gouraud plan max 0.0271, mean 0.0016 (general `shade_fine`: max 0.0163, mean 0.0016); Phong
// in triangles 0.1 across, Rgb888 (whose rounding alone gives up to 0.5): plan max 0.5279, mean
// 0.3704 (general: max 0.5016, mean 0.3704).

#[test]
fn gouraud_plan_matches_f64() {
    let (plan, general) = gouraud(20_000);
    eprintln!(
        "Gouraud plan: max {:.4} mean {:.4}; general: max {:.4} mean {:.4}",
        plan.max,
        plan.mean(),
        general.max,
        general.mean()
    );
    assert!(plan.max <= 0.06, "{}", plan.max);
    assert!(plan.mean() <= 0.004, "{}", plan.mean());
}

#[test]
fn phong_plan_matches_f64() {
    let (plan, general) = phong(20_000, 0.1, false);
    eprintln!(
        "Phong plan: max {:.4} mean {:.4}; general: max {:.4} mean {:.4}",
        plan.max,
        plan.mean(),
        general.max,
        general.mean()
    );
    // The rounding to 8 bits dominates: bounds a little above it rather than twice.
    assert!(plan.max <= 0.75, "{}", plan.max);
    assert!(plan.mean() <= 0.45, "{}", plan.mean());
}

// Measured (as above) with one light and a highlight, in triangles 0.1 and 0.5 across: the plan
// max 0.5195 and 0.5183, mean 0.3719 and 0.3723 (the general path: max 0.5013 and 0.5063, mean
// 0.3718 and 0.3723). Bounds: a little above the rounding's, as above.
#[test]
fn phong_one_light_matches_f64() {
    for (size, max, mean) in [(0.1, 0.75, 0.45), (0.5, 0.75, 0.45)] {
        let (plan, general) = phong(20_000, size, true);
        eprintln!(
            "Phong one light, size {size}: plan max {:.4} mean {:.4}; general: max {:.4} mean {:.4}",
            plan.max,
            plan.mean(),
            general.max,
            general.mean()
        );
        assert!(plan.max <= max, "{size}: {}", plan.max);
        assert!(plan.mean() <= mean, "{size}: {}", plan.mean());
    }
}

/// `GouraudLit`'s values, from the vertex and from its packed slot, on the directional plan
/// (directional lights) and off it (a point light too), over random scenes bright and dim: the
/// lowest and highest seen.
fn gouraud_extremes<C: ShadeColor>(count: usize) -> (i32, i32) {
    let mut r = Rng(XorShift32::seeded(0x5ca1_ab1e));
    let (mut lo, mut hi) = (i32::MAX, i32::MIN);
    for i in 0..count {
        let mut scene = Scene::random(&mut r);
        if i % 3 == 0 {
            // Ambient light past what the lights add, so that channels saturate.
            let a = 128 + r.below(128) as u8;
            scene.ambient = Rgb888::new(a, a, a);
            scene.material.ambient = Rgb888::WHITE;
        }
        let mut lighting =
            Lighting::<Fx16, 4>::new(scene.material, scene.ambient, scene.model, q(scene.eye).0);
        for &(d, color) in &scene.lights {
            lighting
                .add_light(Light::Directional {
                    direction: q(d).0,
                    color,
                })
                .unwrap();
        }
        if i % 2 == 1 {
            // Off the plan.
            lighting
                .add_light(Light::Point {
                    position: q(r.ball(4.0)).0,
                    color: r.color(),
                })
                .unwrap();
        }
        let mut shader = GouraudLit::<Fx16, C, 4>::new(lighting);
        shader.begin_frame(None);
        let v = input(q(r.ball(1.0)).0, q(r.direction()).0);
        let stored = <[u16; 3] as Stored<[i32; 3]>>::unpack(&shader.vertex_stored(&v));
        for c in shader.vertex(&v).into_iter().chain(stored) {
            lo = lo.min(c);
            hi = hi.max(c);
        }
    }
    (lo, hi)
}

/// The range `GouraudLit` declares (`Shading::VALUE_RANGE`, which lets the perspective-correct
/// path skip testing each value) is the half step of no light to full light plus it, per
/// channel depth (Rgb565: 5 bits with 11 fractional bits, 6 with 10; Rgb888: 8 with 8), and no
/// value leaves it, also where the light saturates.
#[test]
fn gouraud_values_stay_in_their_declared_range() {
    assert_eq!(
        <GouraudLit<Fx16, Rgb565, 4> as Shading<Fx16>>::VALUE_RANGE,
        (1 << 9, (63 << 10) + (1 << 9))
    );
    assert_eq!(
        <GouraudLit<Fx16, Rgb888, 4> as Shading<Fx16>>::VALUE_RANGE,
        (1 << 7, (255 << 8) + (1 << 7))
    );
    let (lo, hi) = gouraud_extremes::<Rgb565>(20_000);
    let (range_lo, range_hi) = <GouraudLit<Fx16, Rgb565, 4> as Shading<Fx16>>::VALUE_RANGE;
    assert!(range_lo <= lo && hi <= range_hi, "{lo} {hi}");
    // Both ends are reached: no light and full light on green, the deepest channel.
    assert_eq!((lo, hi), (range_lo, range_hi));
    let (lo, hi) = gouraud_extremes::<Rgb888>(20_000);
    let (range_lo, range_hi) = <GouraudLit<Fx16, Rgb888, 4> as Shading<Fx16>>::VALUE_RANGE;
    assert_eq!((lo, hi), (range_lo, range_hi));
}
