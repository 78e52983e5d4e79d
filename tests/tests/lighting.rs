//! Phong and Blinn-Phong lighting against an f64 reference of the same formula, and the edge cases.

use fixtures::reference3d::{lit, RefLight};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;
use rasterizer_core::math::{Fx, Fx8};
use rasterizer_core::prelude::*;

// ---------------------------------------------------------------------------------------------
// The f64 reference.

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn len(a: V3) -> f64 {
    dot(a, a).sqrt()
}

fn unit(a: V3) -> V3 {
    let l = len(a);
    [a[0] / l, a[1] / l, a[2] / l]
}

/// A scene in f64; `quantized` rounds it to a fixed-point grid so that both sides see the same
/// inputs.
#[derive(Debug, Clone)]
struct Scene {
    material: Material,
    ambient: [u8; 3],
    model: Specular,
    eye: V3,
    /// `(is_point, position or direction, colour)`.
    lights: Vec<(bool, V3, [u8; 3])>,
    position: V3,
    normal: V3,
}

fn rgb(c: [u8; 3]) -> Rgb888 {
    Rgb888::new(c[0], c[1], c[2])
}

fn chans(c: Rgb888) -> [f64; 3] {
    [c.r() as f64, c.g() as f64, c.b() as f64]
}

/// The exact lit colour per channel, unrounded, clamped to 255 (`fixtures::reference3d::lit`).
fn reference(s: &Scene) -> [f64; 3] {
    let lights: Vec<RefLight> = s.lights.iter().map(|&(p, v, c)| (p, v, rgb(c))).collect();
    lit(
        &s.material,
        rgb(s.ambient),
        s.model,
        s.eye,
        &lights,
        s.position,
        s.normal,
    )
}

// ---------------------------------------------------------------------------------------------
// The fixed-point side.

fn q<const F: u32>(v: f64) -> Fx<F> {
    Fx::from_bits((v * (1u64 << F) as f64).round() as i32)
}

fn qv<const F: u32>(v: V3) -> Vec3<Fx<F>> {
    Vec3::new(q(v[0]), q(v[1]), q(v[2]))
}

/// The scene with every coordinate rounded to the `F`-bit grid.
fn quantized<const F: u32>(s: &Scene) -> Scene {
    let r = |v: V3| v.map(|x| q::<F>(x).to_bits() as f64 / (1u64 << F) as f64);
    Scene {
        eye: r(s.eye),
        lights: s.lights.iter().map(|&(p, v, c)| (p, r(v), c)).collect(),
        position: r(s.position),
        normal: r(s.normal),
        ..s.clone()
    }
}

fn lighting<const F: u32>(s: &Scene) -> Lighting<Fx<F>, 3> {
    let mut l = Lighting::new(s.material, rgb(s.ambient), s.model, qv(s.eye));
    for &(point, v, color) in &s.lights {
        let light = if point {
            Light::Point {
                position: qv(v),
                color: rgb(color),
            }
        } else {
            Light::Directional {
                direction: qv(v),
                color: rgb(color),
            }
        };
        l.add_light(light).unwrap();
    }
    l
}

/// `(error of shade, error of shade_fine / 256)` against the reference, worst channel, in 8-bit
/// steps.
fn errors<const F: u32>(scene: &Scene) -> (f64, f64) {
    let s = quantized::<F>(scene);
    let want = reference(&s);
    let l = lighting::<F>(&s);
    let (p, n) = (qv::<F>(s.position), qv::<F>(s.normal));
    let got = chans(l.shade(p, n));
    let fine = l.shade_fine(p, n);
    let (mut e, mut ef) = (0.0f64, 0.0f64);
    for c in 0..3 {
        e = e.max((got[c] - want[c]).abs());
        ef = ef.max((fine[c] as f64 / 256.0 - want[c]).abs());
        assert!(fine[c] <= 255 << 8);
        // shade and shade_fine round the same sum, to 8 and to 16 bits.
        assert!((fine[c] as f64 / 256.0 - got[c]).abs() <= 0.5 + 1.0 / 256.0);
    }
    (e, ef)
}

// ---------------------------------------------------------------------------------------------
// Random scenes.

fn vec_in(r: f64) -> impl Strategy<Value = V3> {
    prop::array::uniform3(-r..r)
}

fn color() -> impl Strategy<Value = [u8; 3]> {
    prop::array::uniform3(any::<u8>())
}

fn model() -> impl Strategy<Value = Specular> {
    prop_oneof![
        Just(Specular::None),
        Just(Specular::Phong),
        Just(Specular::BlinnPhong)
    ]
}

/// The smallest `|N·L|` in random scenes. The model is discontinuous where a light grazes the
/// surface (`N·L = 0`): the specular term, up to `Ms Lc / 255`, switches off there (for shininess 0
/// it is 1 up to the edge). A cosine a few steps of `S` off flips it, which is no arithmetic error,
/// so random scenes keep away from that edge; 0.01 is a few times the 24.8 cosine error.
const GRAZING: f64 = 0.01;

/// Positions, the eye and point lights within ±100, normals and directions with components in ±1
/// and length at least 0.25, the eye and point lights at least one unit from the point.
fn scene(max_shininess: u16) -> impl Strategy<Value = Scene> {
    let light = (any::<bool>(), vec_in(1.0), vec_in(100.0), color())
        .prop_map(|(point, d, p, c)| (point, if point { p } else { d }, c));
    (
        (color(), color(), color(), 0..=max_shininess).prop_map(|(a, d, s, shininess)| Material {
            ambient: rgb(a),
            diffuse: rgb(d),
            specular: rgb(s),
            shininess,
        }),
        color(),
        model(),
        vec_in(100.0),
        prop::collection::vec(light, 1..=3),
        vec_in(100.0),
        vec_in(1.0),
    )
        .prop_map(
            |(material, ambient, model, eye, lights, position, normal)| Scene {
                material,
                ambient,
                model,
                eye,
                lights,
                position,
                normal,
            },
        )
        .prop_filter("degenerate vectors", |s| {
            let n = unit(s.normal);
            len(s.normal) >= 0.25
                && len(sub(s.eye, s.position)) >= 1.0
                && s.lights.iter().all(|&(point, v, _)| {
                    let l = if point { sub(v, s.position) } else { v };
                    let far = if point { len(l) >= 1.0 } else { len(l) >= 0.25 };
                    far && dot(n, unit(l)).abs() >= GRAZING
                })
        })
}

// Worst errors measured by `measure_worst_case`, 1,000,000 scenes per row, in 8-bit steps:
// |shade - exact| (|shade_fine / 256 - exact|), exact = the f64 reference, unrounded.
//
// | model, shininess   | 16.16         | 24.8            |
// |--------------------|---------------|-----------------|
// | None               | 0.505 (0.010) |  2.369 (2.193)  |
// | Phong, <= 8        | 0.524 (0.061) | 14.307 (13.916) |
// | Phong, <= 64       | 0.779 (0.397) | 75.244 (75.244) |
// | Blinn-Phong, <= 8  | 0.516 (0.151) | 28.189 (27.903) |
// | Blinn-Phong, <= 64 | 0.547 (0.141) | 31.367 (31.523) |
//
// 16.16 is limited by the final rounding (0.5) plus the cosines' error times the exponent; 24.8's
// unit vectors carry only 8 fractional bits, which is enough for diffuse light but not for
// highlights.
proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// 16.16: every channel within one 8-bit step of the exact (unrounded) value, and `shade_fine`
    /// within half a step (measured worst: 0.779 and 0.397, table above).
    #[test]
    fn fx16_matches_f64_within_one_step(s in scene(64)) {
        let (e, ef) = errors::<16>(&s);
        prop_assert!(e <= 1.0, "shade error {e}");
        prop_assert!(ef <= 0.5, "shade_fine error {ef}");
    }

    /// 24.8, ambient and diffuse only: within three steps (measured worst 2.369).
    #[test]
    fn fx8_diffuse_within_three_steps(s in scene(0)) {
        let (e, _) = errors::<8>(&s.clone_with(Specular::None));
        prop_assert!(e <= 3.0, "error {e}");
    }

    /// 24.8 with highlights of shininess up to 8: within 40 steps (measured worst 14.3 for Phong,
    /// 28.2 for Blinn-Phong); the cosines are off by about 2^-8 and the power multiplies that by the
    /// exponent.
    #[test]
    fn fx8_low_shininess_within_forty_steps(s in scene(8)) {
        let (e, _) = errors::<8>(&s);
        prop_assert!(e <= 40.0, "error {e}");
    }
}

impl Scene {
    fn clone_with(&self, model: Specular) -> Scene {
        Scene {
            model,
            ..self.clone()
        }
    }
}

/// Prints the worst errors over many random scenes, per specular model and exponent range. Run
/// with `cargo test -p tests --test lighting --release -- --ignored --nocapture` (set
/// `LIGHTING_CASES` for another count per row).
#[test]
#[ignore]
fn measure_worst_case() {
    let cases: usize = std::env::var("LIGHTING_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    println!("{cases} scenes per row; worst |shade - exact| (|shade_fine / 256 - exact|) in steps");
    for model in [Specular::None, Specular::Phong, Specular::BlinnPhong] {
        for max_shininess in [8u16, 64] {
            if model == Specular::None && max_shininess > 8 {
                continue;
            }
            let strategy = scene(max_shininess).prop_map(move |s| Scene { model, ..s });
            let mut runner = TestRunner::deterministic();
            let mut worst = [(0.0f64, 0.0f64); 2];
            let mut worst_scene = None;
            for _ in 0..cases {
                let s = strategy.new_tree(&mut runner).unwrap().current();
                let e16 = errors::<16>(&s);
                let e8 = errors::<8>(&s);
                if e16.0 > worst[0].0 {
                    worst_scene = Some(s);
                }
                for (w, e) in worst.iter_mut().zip([e16, e8]) {
                    *w = (w.0.max(e.0), w.1.max(e.1));
                }
            }
            println!(
                "{model:?}, shininess <= {max_shininess}: 16.16 {:.3} ({:.3}), 24.8 {:.3} ({:.3})",
                worst[0].0, worst[0].1, worst[1].0, worst[1].1
            );
            println!("  worst 16.16 scene: {worst_scene:?}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Named cases.

fn material(shininess: u16) -> Material {
    Material {
        ambient: Rgb888::new(100, 50, 200),
        diffuse: Rgb888::new(200, 100, 50),
        specular: Rgb888::new(120, 120, 120),
        shininess,
    }
}

const GREY: Rgb888 = Rgb888::new(51, 51, 51);
/// 100, 50, 200 times 51 / 255.
const AMBIENT_ONLY: Rgb888 = Rgb888::new(20, 10, 40);

#[test]
fn light_behind_surface_gives_ambient_only() {
    for model in [Specular::None, Specular::Phong, Specular::BlinnPhong] {
        for shininess in [0, 1, 16] {
            // The eye looks straight at the light through the surface: a full Phong highlight
            // (R·V = 1) if the light were not behind it.
            let eye = Vec3::<Fx16>::from_ints(0, 0, 5);
            let mut l = Lighting::<Fx16, 2>::new(material(shininess), GREY, model, eye);
            let down = Vec3::from_ints(0, 0, -1);
            l.add_light(Light::Directional {
                direction: down,
                color: Rgb888::WHITE,
            })
            .unwrap();
            l.add_light(Light::Point {
                position: Vec3::from_ints(3, 1, -10),
                color: Rgb888::WHITE,
            })
            .unwrap();
            let (p, n) = (Vec3::from_ints(0, 0, 0), Vec3::from_ints(0, 0, 1));
            assert_eq!(l.shade(p, n), AMBIENT_ONLY, "{model:?} {shininess}");
            // Grazing (N·L = 0) counts as behind.
            let mut g = Lighting::<Fx16, 1>::new(material(shininess), GREY, model, eye);
            g.add_light(Light::Directional {
                direction: Vec3::from_ints(1, 0, 0),
                color: Rgb888::WHITE,
            })
            .unwrap();
            assert_eq!(g.shade(p, n), AMBIENT_ONLY, "{model:?} {shininess}");
        }
    }
}

#[test]
fn zero_normal_gives_ambient_only() {
    let eye = Vec3::<Fx16>::from_ints(0, 0, 5);
    let mut l = Lighting::<Fx16, 1>::new(material(0), GREY, Specular::Phong, eye);
    l.add_light(Light::Directional {
        direction: Vec3::from_ints(0, 0, 1),
        color: Rgb888::WHITE,
    })
    .unwrap();
    let p = Vec3::from_ints(0, 0, 0);
    assert_eq!(l.shade(p, Vec3::default()), AMBIENT_ONLY);
    assert_eq!(l.shade_fine(p, Vec3::default()), [5120, 2560, 10240]);
}

#[test]
fn saturates_at_255() {
    let white = Material {
        ambient: Rgb888::WHITE,
        diffuse: Rgb888::WHITE,
        specular: Rgb888::WHITE,
        shininess: 8,
    };
    for model in [Specular::None, Specular::Phong, Specular::BlinnPhong] {
        let eye = Vec3::<Fx16>::from_ints(0, 0, 50);
        let mut l = Lighting::<Fx16, 3>::new(white, Rgb888::WHITE, model, eye);
        for x in [-1, 0, 1] {
            l.add_light(Light::Directional {
                direction: Vec3::from_ints(x, 0, 4),
                color: Rgb888::WHITE,
            })
            .unwrap();
        }
        let (p, n) = (Vec3::from_ints(0, 0, 0), Vec3::from_ints(0, 0, 1));
        assert_eq!(l.shade(p, n), Rgb888::WHITE);
        assert_eq!(l.shade_fine(p, n), [255 << 8; 3]);
    }
    // Ambient alone at full intensity is exactly 255, not above.
    let l = Lighting::<Fx16, 1>::new(white, Rgb888::WHITE, Specular::Phong, Vec3::default());
    let (p, n) = (Vec3::from_ints(0, 0, 0), Vec3::from_ints(0, 0, 1));
    assert_eq!(l.shade(p, n), Rgb888::WHITE);
    assert_eq!(l.shade_fine(p, n), [255 << 8; 3]);
}

#[test]
fn shininess_zero() {
    // N·L = 0.8; the eye is below the surface, where R·V and N·H are negative: with shininess 0
    // the specular factor is 1 anyway, since the light reaches the surface.
    let mat = Material {
        ambient: Rgb888::BLACK,
        diffuse: Rgb888::new(100, 200, 0),
        specular: Rgb888::new(50, 50, 255),
        shininess: 0,
    };
    let (p, n) = (Vec3::from_ints(0, 0, 0), Vec3::from_ints(0, 0, 7));
    for (model, want) in [
        (Specular::None, Rgb888::new(80, 160, 0)),
        (Specular::Phong, Rgb888::new(130, 210, 255)),
        (Specular::BlinnPhong, Rgb888::new(130, 210, 255)),
    ] {
        for eye in [Vec3::<Fx16>::from_ints(0, -3, 4), Vec3::from_ints(0, 3, -4)] {
            let mut l = Lighting::<Fx16, 1>::new(mat, Rgb888::BLACK, model, eye);
            l.add_light(Light::Directional {
                direction: Vec3::from_ints(0, 3, 4),
                color: Rgb888::WHITE,
            })
            .unwrap();
            assert_eq!(l.shade(p, n), want, "{model:?}");
            // Also with the eye exactly at the point: no view vector is needed.
            l.set_eye(p);
            assert_eq!(l.shade(p, n), want, "{model:?}");
        }
    }
}

#[test]
fn too_many_lights_is_rejected() {
    let mut l =
        Lighting::<Fx16, 2>::new(material(4), GREY, Specular::Phong, Vec3::from_ints(0, 0, 5));
    let light = |i: i32| Light::Point {
        position: Vec3::from_ints(i, 2, 3),
        color: Rgb888::WHITE,
    };
    assert_eq!(l.add_light(light(1)), Ok(()));
    assert_eq!(l.add_light(light(2)), Ok(()));
    assert_eq!(l.add_light(light(3)), Err(light(3)));
    assert_eq!(l.lights(), &[light(1), light(2)]);
    let sun = Light::Directional {
        direction: Vec3::from_ints(0, 0, 1),
        color: Rgb888::WHITE,
    };
    assert_eq!(l.add_light(sun), Err(sun));
    // A zero-capacity list takes nothing.
    let mut none = Lighting::<Fx16, 0>::new(material(4), GREY, Specular::Phong, Vec3::default());
    assert_eq!(none.add_light(light(1)), Err(light(1)));
}

#[test]
fn zero_direction_light_rejected() {
    let mut l =
        Lighting::<Fx16, 2>::new(material(4), GREY, Specular::Phong, Vec3::from_ints(0, 0, 5));
    let zero = Light::Directional {
        direction: Vec3::default(),
        color: Rgb888::WHITE,
    };
    assert_eq!(l.add_light(zero), Err(zero));
    assert!(l.lights().is_empty());
    // A directional light is stored normalised.
    l.add_light(Light::Directional {
        direction: Vec3::from_ints(0, 0, 9),
        color: Rgb888::WHITE,
    })
    .unwrap();
    assert_eq!(
        l.lights(),
        &[Light::Directional {
            direction: Vec3::from_ints(0, 0, 1),
            color: Rgb888::WHITE
        }]
    );
}

#[test]
fn point_light_at_the_point_adds_nothing() {
    let mut l =
        Lighting::<Fx16, 1>::new(material(4), GREY, Specular::Phong, Vec3::from_ints(0, 0, 5));
    let p = Vec3::from_ints(1, 2, 3);
    l.add_light(Light::Point {
        position: p,
        color: Rgb888::WHITE,
    })
    .unwrap();
    assert_eq!(l.shade(p, Vec3::from_ints(0, 0, 1)), AMBIENT_ONLY);
}

#[test]
fn blinn_and_phong_agree_when_light_equals_eye_direction() {
    // N = L = V = (1, 2, 2) / 3: R·V = N·H = 1, a full highlight for any exponent.
    let d = Vec3::<Fx16>::from_ints(1, 2, 2);
    let p = Vec3::from_ints(-4, 7, 1);
    let mat = Material {
        ambient: Rgb888::BLACK,
        diffuse: Rgb888::new(100, 20, 0),
        specular: Rgb888::new(40, 60, 255),
        shininess: 0,
    };
    for shininess in [0, 1, 2, 7, 64, 1000, u16::MAX] {
        let mut got = [Rgb888::BLACK; 2];
        for (i, model) in [Specular::Phong, Specular::BlinnPhong]
            .into_iter()
            .enumerate()
        {
            let mat = Material { shininess, ..mat };
            // The eye along the normal, the light from the same direction (point and directional).
            let eye = p + d.scale(Fx16::from_int(10));
            let mut l = Lighting::<Fx16, 1>::new(mat, Rgb888::BLACK, model, eye);
            l.add_light(Light::Directional {
                direction: d,
                color: Rgb888::WHITE,
            })
            .unwrap();
            got[i] = l.shade(p, d.scale(Fx16::from_int(3)));
            let mut pl = Lighting::<Fx16, 1>::new(mat, Rgb888::BLACK, model, eye);
            pl.add_light(Light::Point {
                position: p + d.scale(Fx16::from_int(20)),
                color: Rgb888::WHITE,
            })
            .unwrap();
            assert_eq!(pl.shade(p, d), got[i], "{model:?} {shininess}");
        }
        assert_eq!(got[0], got[1], "{shininess}");
        assert_eq!(got[0], Rgb888::new(140, 80, 255), "{shininess}");
    }
}

#[test]
fn fx8_named_highlight() {
    // 24.8 still finds the centre of the highlight.
    let d = Vec3::<Fx8>::from_ints(0, 0, 1);
    let mat = Material {
        ambient: Rgb888::BLACK,
        diffuse: Rgb888::new(100, 20, 0),
        specular: Rgb888::new(40, 60, 255),
        shininess: 32,
    };
    for model in [Specular::Phong, Specular::BlinnPhong] {
        let mut l = Lighting::<Fx8, 1>::new(mat, Rgb888::BLACK, model, Vec3::from_ints(0, 0, 9));
        l.add_light(Light::Directional {
            direction: d,
            color: Rgb888::WHITE,
        })
        .unwrap();
        assert_eq!(
            l.shade(Vec3::default(), d),
            Rgb888::new(140, 80, 255),
            "{model:?}"
        );
    }
}

/// Regression: `FlatLit` lit each face with the plain 16.16 cross product of its edges. For a
/// small triangle (M2's edges are about 0.03 long) its components are a few dozen units of 2^-16,
/// and their rounding turned the normal by up to a degree: highlights were 14 steps off
/// (`colors_f64.rs`). `Vec3::face_normal` takes the product of the raw edges exactly.
#[test]
fn small_triangle_face_normal_keeps_direction() {
    let p = |x: f64, y: f64, z: f64| Vec3::new(q::<16>(x), q::<16>(y), q::<16>(z));
    let (a, b, c) = (
        p(0.31, -0.12, 0.4),
        p(0.331, -0.117, 0.392),
        p(0.317, -0.101, 0.409),
    );
    let f = |v: Vec3<Fx16>| [v.x, v.y, v.z].map(|s| f64::from(s.to_bits()) / 65536.0);
    let (fa, fb, fc) = (f(a), f(b), f(c));
    let (u, v) = (sub(fb, fa), sub(fc, fa));
    let exact = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let degrees = |n: Vec3<Fx16>| {
        let cos = dot(unit(f(n)), unit(exact)).min(1.0);
        cos.acos().to_degrees()
    };
    let plain = degrees((b - a).cross(c - a));
    let face = degrees(Vec3::face_normal(a, b, c));
    eprintln!("plain cross {plain:.4} degrees off, face_normal {face:.6}");
    // Measured: the plain cross product 0.4764 degrees off, face_normal 0.000363 (the rounding
    // of its result to 16.16).
    assert!(
        plain > 0.1,
        "the case no longer shows the rounding ({plain} degrees)"
    );
    assert!(face < 0.0008, "face normal {face} degrees off");
}
