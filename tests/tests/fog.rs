//! Fog (`shade::Fog`): vertices nearer than `start` keep their colour, vertices beyond `end` take
//! the fog colour exactly, and in between the colour is the f64 mix to within the rounding of the
//! target; in model space and world space alike, and with the exponential table within its stated
//! bound of the curve.

use embedded_graphics_core::pixelcolor::raw::RawU16;
use proptest::prelude::*;
use rasterizer_core::color::ShadeColor;
use rasterizer_core::mesh::Mesh;
use rasterizer_core::numerics::{Dither, Numerics};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::{
    Fog, FogCurve, FogSettings, Lighting, Material, PhongLit, Shading, Specular, FOG_ONE,
    FOG_TABLE_LEN,
};
use tests::StrictMock;

/// Identity model, a view matrix `view` (depth is `-z` of the view space) and a projection that
/// keeps x and y (the clip square is the screen) and fits depths within ±8 into the clip volume.
fn flat_transforms(view: Mat4<Fx16>) -> Transforms<Fx16> {
    Transforms {
        model: Mat4::identity(),
        view,
        projection: Mat4::scale(Fx16::ONE, Fx16::ONE, Fx16::from_ratio(1, 8)),
    }
}

/// Vertical strips, one per entry of `depths` (view-space `-z`), side by side across a
/// `4 * depths.len()` x 4 screen, each a quad of vertex colour `color`.
fn strips(depths: &[Fx16], color: Rgb888) -> (Vec<Vec3<Fx16>>, Vec<Rgb888>, Vec<[u16; 3]>) {
    let n = depths.len() as i64;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (i, &d) in depths.iter().enumerate() {
        let x = |k: i64| Fx16::from_ratio(2 * k - n, n);
        let (x0, x1) = (x(i as i64), x(i as i64 + 1));
        let z = -d;
        let base = positions.len() as u16;
        positions.extend([
            Vec3::new(x0, -Fx16::ONE, z),
            Vec3::new(x1, -Fx16::ONE, z),
            Vec3::new(x1, Fx16::ONE, z),
            Vec3::new(x0, Fx16::ONE, z),
        ]);
        triangles.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
    }
    let colors = vec![color; positions.len()];
    (positions, colors, triangles)
}

/// The strips drawn through `shading` (fogged or not) onto a strict mock: every pixel once.
fn draw_strips<C, Sh>(depths: &[Fx16], color: Rgb888, shading: Sh) -> StrictMock<C>
where
    C: ShadeColor + core::fmt::Debug,
    Sh: Shading<Fx16, Color = C>,
{
    let (positions, colors, triangles) = strips(depths, color);
    let mesh = Mesh {
        positions: &positions,
        normals: None,
        colors: Some(&colors),
        uvs: None,
        triangles: &triangles,
        adjacency: None,
    };
    let (w, h) = (4 * depths.len() as u32, 4);
    let t = flat_transforms(Mat4::identity());
    let mut p = Pipeline::new(&t, Viewport::new(w, h), NoCull, NoDepth, shading);
    let mut mock = StrictMock::<C>::new(w, h);
    let mut scratch = vec![VertexSlot::EMPTY; positions.len()];
    p.draw(&mut AnyTarget::new(&mut mock), &mesh, &mut scratch)
        .unwrap();
    assert_eq!(mock.written().len(), (w * h) as usize, "every pixel drawn");
    mock
}

fn fx(v: f64) -> Fx16 {
    Fx16::from_ratio((v * 65536.0).round() as i64, 65536)
}

fn linear(color: Rgb888, start: f64, end: f64) -> FogSettings<Fx16> {
    FogSettings {
        color,
        start: fx(start),
        end: fx(end),
        curve: FogCurve::Linear,
    }
}

/// `.` for the vertex colour, `#` for the fog colour, `+` for anything else.
fn pattern<C: PixelColor>(m: &StrictMock<C>, w: i32, h: i32, clear: C, fog: C) -> Vec<String> {
    (0..h)
        .map(|y| {
            (0..w)
                .map(|x| match m.get(x, y).unwrap() {
                    c if c == clear => '.',
                    c if c == fog => '#',
                    _ => '+',
                })
                .collect()
        })
        .collect()
}

/// Strips nearer than `start`, between `start` and `end`, and beyond `end`: unfogged, mixed and
/// all fog, exactly.
#[test]
fn strips_by_depth_are_clear_mixed_and_fogged() {
    let white = Rgb888::WHITE;
    let fog = Rgb888::new(64, 96, 128);
    let depths = [fx(-0.75), fx(-0.25), fx(0.0), fx(0.25), fx(0.75)];
    let settings = linear(fog, -0.5, 0.5);
    let sh = Fog::new(VertexColors::<Rgb888>::new(), settings, &Mat4::identity());
    let m = draw_strips(&depths, white, sh);
    let rows = pattern(&m, 20, 4, white, fog);
    assert_eq!(rows, vec!["....++++++++++++####"; 4]);
    // A quarter, a half and three quarters of the way to the fog: (255 - c) / 4 steps per quarter.
    let mix = |a: f64| {
        let ch = |c: u8| (255.0 + (f64::from(c) - 255.0) * a).round() as u8;
        Rgb888::new(ch(fog.r()), ch(fog.g()), ch(fog.b()))
    };
    assert_eq!(m.get(5, 0), Some(mix(0.25)));
    assert_eq!(m.get(9, 0), Some(mix(0.5)));
    assert_eq!(m.get(13, 0), Some(mix(0.75)));
    // Without fog every strip is white.
    let plain = draw_strips(&depths, white, VertexColors::<Rgb888>::new());
    assert_eq!(
        pattern(&plain, 20, 4, white, fog),
        vec!["...................."; 4]
    );
}

/// The fog colour is reached exactly at the target's depth (Rgb565), and `end` at or before
/// `start` is a step at `start`.
#[test]
fn rgb565_fog_colour_is_exact_and_a_step_when_end_is_not_after_start() {
    let fog = Rgb888::new(200, 10, 90);
    let color = Rgb888::new(20, 240, 60);
    let depths = [fx(-0.5), fx(0.0), fx(0.5)];
    let as565 = |c: Rgb888| Rgb565::from(c);
    let sh = Fog::new(
        VertexColors::<Rgb565>::new(),
        linear(fog, 0.0, 0.0),
        &Mat4::identity(),
    );
    let m = draw_strips(&depths, color, sh);
    assert_eq!(
        pattern(&m, 12, 4, as565(color), as565(fog)),
        vec!["....########"; 4]
    );
    let sh = Fog::new(
        VertexColors::<Rgb565>::new(),
        linear(fog, 0.25, -1.0),
        &Mat4::identity(),
    );
    let m = draw_strips(&depths, color, sh);
    assert_eq!(
        pattern(&m, 12, 4, as565(color), as565(fog)),
        vec!["........####"; 4]
    );
}

/// The depth follows the view matrix: a camera moved back by 2 sees the same strips 2 deeper.
#[test]
fn depth_follows_the_view_matrix() {
    let fog = Rgb888::BLACK;
    let white = Rgb888::WHITE;
    // The camera at z = 2 looking down -z: strips at z = 2.5, 2 and 1.5 are -0.5, 0 and 0.5 deep.
    let view = Mat4::translation(Vec3::new(Fx16::ZERO, Fx16::ZERO, fx(-2.0)));
    let (positions, colors, triangles) = strips(&[fx(-2.5), fx(-2.0), fx(-1.5)], white);
    let mesh = Mesh {
        positions: &positions,
        normals: None,
        colors: Some(&colors),
        uvs: None,
        triangles: &triangles,
        adjacency: None,
    };
    let t = flat_transforms(view);
    let sh = Fog::new(
        VertexColors::<Rgb888>::new(),
        linear(fog, -0.25, 0.25),
        &t.view,
    );
    let mut p = Pipeline::new(&t, Viewport::new(12, 4), NoCull, NoDepth, sh);
    let mut mock = StrictMock::<Rgb888>::new(12, 4);
    let mut scratch = vec![VertexSlot::EMPTY; positions.len()];
    p.draw(&mut AnyTarget::new(&mut mock), &mesh, &mut scratch)
        .unwrap();
    assert_eq!(pattern(&mock, 12, 4, white, fog), vec!["....++++####"; 4]);
}

fn suzanne() -> fixtures::obj::LoadedMesh {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    fixtures::obj::LoadedMesh::load(&path).unwrap()
}

/// Suzanne (M1 camera, 160 x 120) through `shading`, with `normal_matrix` when given (which makes
/// lit shaders light in world space instead of model space).
fn draw_suzanne<Sh: Shading<Fx16, Color = Rgb565>>(
    model: Mat4<Fx16>,
    shading: impl FnOnce(&Transforms<Fx16>) -> Sh,
    normal_matrix: Option<Mat4<Fx16>>,
) -> Vec<u16> {
    let (w, h) = (160u32, 120u32);
    let loaded = suzanne();
    let mesh = loaded.mesh();
    let t = fixtures::scenes3d::camera(model, w, h);
    let mut z = vec![u16::MAX; (w * h) as usize];
    let mut p = Pipeline::new(
        &t,
        Viewport::new(w, h),
        CullClockwise,
        DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap(),
        shading(&t),
    );
    if let Some(n) = normal_matrix {
        p.set_normal_matrix(n);
    }
    let mut pixels = vec![0u16; (w * h) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut pixels, w, h).unwrap();
    let mut scratch = vec![VertexSlot::EMPTY; loaded.positions.len()];
    p.draw(&mut fb, &mesh, &mut scratch).unwrap();
    pixels
}

/// Gouraud lighting in model space (the default for a rotation) and in world space (forced by a
/// normal matrix other than the model matrix) fogs alike: the depths agree to within a few steps
/// of 16.16, and on this scene no pixel differs at all (measured). With fog beyond the whole mesh,
/// the picture is the unfogged one bit for bit; with fog before it, one flat colour.
#[test]
fn gouraud_fog_in_model_and_world_space_agree() {
    let model = Mat4::rotation_y(Angle::from_degrees(30));
    let settings = linear(Rgb888::new(128, 144, 160), 2.0, 4.0);
    let lit = || GouraudLit::<Fx16, Rgb565, 1>::new(fixtures::scenes3d::lighting::<1>());
    let fogged = |s: FogSettings<Fx16>| move |t: &Transforms<Fx16>| Fog::new(lit(), s, &t.view);
    let model_space = draw_suzanne(model, fogged(settings), None);
    // Normals twice as long light alike, but are no longer carried by the model matrix itself.
    let two = Fx16::from_int(2);
    let normals = Mat4::scale(two, two, two).then(&model);
    let world_space = draw_suzanne(model, fogged(settings), Some(normals));
    let diff: Vec<u32> = model_space
        .iter()
        .zip(&world_space)
        .filter(|(a, b)| a != b)
        .map(|(a, b)| {
            let (a, b) = (Rgb565::from(RawU16::new(*a)), Rgb565::from(RawU16::new(*b)));
            u32::from(
                a.r()
                    .abs_diff(b.r())
                    .max(a.g().abs_diff(b.g()))
                    .max(a.b().abs_diff(b.b())),
            )
        })
        .collect();
    // Measured: 0 pixels differ. The scene is fixed and the arithmetic integer-only, so that holds
    // on every machine: the bound is exact 0, not an allowance.
    assert!(diff.is_empty(), "{} pixels differ: {diff:?}", diff.len());
    let plain = draw_suzanne(model, |_| lit(), None);
    assert_ne!(plain, model_space, "fog changes the picture");
    let beyond = draw_suzanne(model, fogged(linear(Rgb888::BLACK, 10.0, 20.0)), None);
    assert!(plain == beyond, "fog beyond the mesh changes nothing");
    let fog = Rgb565::from(Rgb888::new(128, 144, 160));
    let raw = RawU16::from(fog).into_inner();
    let before = draw_suzanne(
        model,
        fogged(linear(Rgb888::new(128, 144, 160), -2.0, 0.0)),
        None,
    );
    let covered = plain.iter().filter(|&&p| p != 0).count();
    assert_eq!(before.iter().filter(|&&p| p == raw).count(), covered);
}

/// Flat shading fogs each triangle by its centroid: beyond `end` every triangle is the fog colour,
/// nearer than `start` the picture is the unfogged one, in between it darkens with depth.
#[test]
fn flat_fog_by_triangle() {
    let model = Mat4::rotation_y(Angle::from_degrees(30));
    let flat = || FlatLit::<Fx16, Rgb565, 1>::new(fixtures::scenes3d::lighting::<1>());
    let fogged = |s: FogSettings<Fx16>| move |t: &Transforms<Fx16>| Fog::new(flat(), s, &t.view);
    let plain = draw_suzanne(model, |_| flat(), None);
    let near = draw_suzanne(model, fogged(linear(Rgb888::BLACK, 10.0, 20.0)), None);
    assert!(plain == near);
    let far = draw_suzanne(
        model,
        fogged(linear(Rgb888::new(0, 255, 0), -2.0, 0.0)),
        None,
    );
    let green = RawU16::from(Rgb565::GREEN).into_inner();
    assert_eq!(
        far.iter().filter(|&&p| p == green).count(),
        plain.iter().filter(|&&p| p != 0).count()
    );
    // Black fog only darkens: every channel at most the unfogged one, and some strictly.
    let mid = draw_suzanne(model, fogged(linear(Rgb888::BLACK, 2.0, 4.0)), None);
    let ch = |p: u16| {
        let c = Rgb565::from(RawU16::new(p));
        [c.r(), c.g(), c.b()]
    };
    assert!(plain
        .iter()
        .zip(&mid)
        .all(|(&a, &b)| ch(a).iter().zip(ch(b)).all(|(x, y)| y <= *x)));
    assert!(plain.iter().zip(&mid).filter(|(a, b)| a != b).count() > 1000);
}

/// Dithering still applies to a fogged colour: the Bayer pattern of a flat Rgb565 colour between
/// two steps, made by fog.
#[test]
fn fog_is_dithered() {
    struct Bayer4;
    impl Numerics for Bayer4 {
        const DITHER: Dither = Dither::Bayer4;
    }
    // Black vertices half way into white fog: 15.5 steps of 5-bit red, so the half of the
    // thresholds at or above half a step go up to 16 (rounding alone gives 16 everywhere).
    let (positions, colors, triangles) = strips(&[fx(0.0)], Rgb888::BLACK);
    let mesh = Mesh {
        positions: &positions,
        normals: None,
        colors: Some(&colors),
        uvs: None,
        triangles: &triangles,
        adjacency: None,
    };
    let t = flat_transforms(Mat4::identity());
    let sh = Fog::new(
        VertexColors::<Rgb565>::new(),
        linear(Rgb888::WHITE, -1.0, 1.0),
        &t.view,
    );
    let mut p =
        Pipeline::new(&t, Viewport::new(4, 4), NoCull, NoDepth, sh).with_numerics::<Bayer4>();
    let mut mock = StrictMock::<Rgb565>::new(4, 4);
    let mut scratch = vec![VertexSlot::EMPTY; 4];
    p.draw(&mut AnyTarget::new(&mut mock), &mesh, &mut scratch)
        .unwrap();
    let reds: Vec<u8> = (0..16)
        .map(|i| mock.get(i % 4, i / 4).unwrap().r())
        .collect();
    assert!(reds.iter().all(|&r| r == 15 || r == 16), "{reds:?}");
    let up = reds.iter().filter(|&&r| r == 16).count();
    assert_eq!(up, 8, "{reds:?}");
}

/// The f64 share of fog at `t` for a curve of density `k` (0: linear).
fn exact_share(t: f64, k: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    if k == 0.0 {
        t
    } else {
        (1.0 - (-k * t).exp()) / (1.0 - (-k).exp())
    }
}

/// The exponential table is the curve rounded to 0.15, and the linear pieces between its entries
/// stay within `k² / (8192 (1 - e^-k))` of it (the bound of a linear interpolation of a function
/// of second derivative at most `k² / (1 - e^-k)` on steps of 1/32), plus the roundings.
#[test]
fn exponential_table_matches_the_curve() {
    for density in [1u16, 8, 16, 40, 64, 100, 128] {
        let k = f64::from(density) / 16.0;
        let FogCurve::Table(table) = FogCurve::exponential(density) else {
            panic!("density {density} gives a table");
        };
        for (i, &v) in table.iter().enumerate() {
            let exact = exact_share(i as f64 / 32.0, k) * f64::from(FOG_ONE);
            assert!(
                (f64::from(v) - exact).abs() <= 0.5 + 1e-9,
                "k {k} entry {i}: {v} {exact}"
            );
        }
        assert_eq!(table[0], 0);
        assert_eq!(table[FOG_TABLE_LEN - 1] as u32, FOG_ONE);
        let curve = FogCurve::exponential(density);
        let bound = k * k / (8192.0 * (1.0 - (-k).exp())) + 1.0 / f64::from(FOG_ONE);
        for t in (0..=FOG_ONE).step_by(7) {
            let exact = exact_share(f64::from(t) / f64::from(FOG_ONE), k);
            let ours = f64::from(curve.share(t)) / f64::from(FOG_ONE);
            assert!((ours - exact).abs() <= bound, "k {k} t {t}: {ours} {exact}");
        }
    }
    assert_eq!(FogCurve::exponential(0), FogCurve::Linear);
    // Densities above the largest are the largest.
    assert_eq!(FogCurve::exponential(1000), FogCurve::exponential(128));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// A strip of one vertex colour at one depth: every pixel is the f64 fogged colour
    /// `c + (fog - c) a(t)` at the target's depth, rounded, to within the curve's error in steps
    /// (and 1/256 of a step for the mix's own rounding).
    #[test]
    fn fogged_colour_matches_f64(
        c in any::<[u8; 3]>(),
        f in any::<[u8; 3]>(),
        depth in -4.0f64..4.0,
        start in -3.0f64..3.0,
        len in 0.05f64..4.0,
        density in prop_oneof![Just(0u16), 1u16..=128],
    ) {
        let (color, fog) = (Rgb888::new(c[0], c[1], c[2]), Rgb888::new(f[0], f[1], f[2]));
        let settings = FogSettings {
            color: fog,
            start: fx(start),
            end: fx(start + len),
            curve: FogCurve::exponential(density),
        };
        let (d, s, e) = (fx(depth), settings.start, settings.end);
        let real = |v: Fx16| f64::from(v.to_bits()) / 65536.0;
        let t = (real(d) - real(s)) / (real(e) - real(s));
        let k = f64::from(density) / 16.0;
        let a = exact_share(t, k);
        let curve_error = if density == 0 {
            0.0
        } else {
            k * k / (8192.0 * (1.0 - (-k).exp()))
        };
        // t is rounded to 0.15, which moves the share by at most its slope (k / (1 - e^-k), or 1)
        // times half a step of 0.15, and the share itself is rounded to 0.15.
        let slope = if density == 0 { 1.0 } else { k / (1.0 - (-k).exp()) };
        let share_error = curve_error + (slope * 0.5 + 1.0) / f64::from(FOG_ONE);
        fn check<C: ShadeColor + core::fmt::Debug>(
            depth: Fx16,
            color: Rgb888,
            settings: FogSettings<Fx16>,
            a: f64,
            share_error: f64,
            channels: fn(C) -> [u8; 3],
        ) -> Result<(), TestCaseError> {
            let sh = Fog::new(VertexColors::<C>::new(), settings, &Mat4::identity());
            let m = draw_strips(&[depth], color, sh);
            let got = channels(m.get(1, 1).unwrap());
            let (c, f) = (
                [color.r(), color.g(), color.b()],
                [settings.color.r(), settings.color.g(), settings.color.b()],
            );
            for i in 0..3 {
                let max = f64::from(C::MAX[i]);
                let steps = |v: u8| f64::from(v) * max / 255.0;
                let exact = steps(c[i]) + (steps(f[i]) - steps(c[i])) * a;
                let bound = 0.5 + 1.0 / 256.0 + (steps(f[i]) - steps(c[i])).abs() * share_error;
                prop_assert!(
                    (f64::from(got[i]) - exact).abs() <= bound,
                    "channel {i}: got {} exact {exact} (bound {bound})", got[i]
                );
            }
            Ok(())
        }
        check::<Rgb888>(d, color, settings, a, share_error, |c| [c.r(), c.g(), c.b()])?;
        check::<Rgb565>(d, color, settings, a, share_error, |c| [c.r(), c.g(), c.b()])?;
    }
}

/// `share_at` is the share of fog at a point, and `set_settings` changes it and the colour.
#[test]
fn settings_can_change_between_frames() {
    let mut sh = Fog::new(
        VertexColors::<Rgb888>::new(),
        linear(Rgb888::BLACK, -1.0, 1.0),
        &Mat4::identity(),
    );
    let at = |z: f64| Vec3::new(Fx16::ZERO, Fx16::ZERO, fx(z));
    assert_eq!(sh.share_at(at(0.0)), FOG_ONE / 2);
    assert_eq!(sh.share_at(at(-2.0)), FOG_ONE);
    assert_eq!(sh.share_at(at(2.0)), 0);
    let red = Rgb888::RED;
    sh.set_settings(linear(red, -2.0, -1.0));
    assert_eq!(sh.share_at(at(0.0)), FOG_ONE);
    assert_eq!(sh.settings().color, red);
    let m = draw_strips(&[fx(0.0)], Rgb888::WHITE, sh);
    assert_eq!(m.get(2, 2), Some(red));
}

/// Ambient light only, `Ma` of colour `color` under white ambient light and no lights: every
/// pixel of a Phong-lit surface is exactly `color`, so what fog does to it is all there is to see.
fn ambient_phong<C: ShadeColor>(color: Rgb888) -> PhongLit<Fx16, C, 1> {
    let material = Material {
        ambient: color,
        diffuse: Rgb888::BLACK,
        specular: Rgb888::BLACK,
        shininess: 0,
    };
    let eye = Vec3::from_ints(0, 0, 8);
    PhongLit::new(Lighting::new(material, Rgb888::WHITE, Specular::None, eye))
}

/// Each drawn pixel `(x, y)` with the f64 weights of the three vertices at its centre.
type Weights = Vec<(i32, i32, [f64; 3])>;

/// The triangle (-1, -1), (1, -1), (-1, 1) at view-space depths `depths`, filling the lower left
/// half of a 16 x 16 screen, through `shading`: the mock and, for each vertex, its weight at each
/// pixel centre in f64 (the projection keeps x and y, so screen and space weights agree).
fn draw_slanted<C, Sh>(depths: [Fx16; 3], shading: Sh) -> (StrictMock<C>, Weights)
where
    C: ShadeColor + core::fmt::Debug,
    Sh: Shading<Fx16, Color = C>,
{
    let corners = [(-1, -1), (1, -1), (-1, 1)];
    let positions: Vec<Vec3<Fx16>> = corners
        .iter()
        .zip(depths)
        .map(|(&(x, y), d)| Vec3::new(Fx16::from_int(x), Fx16::from_int(y), -d))
        .collect();
    let mesh = Mesh {
        positions: &positions,
        normals: None,
        colors: None,
        uvs: None,
        triangles: &[[0u16, 1, 2]],
        adjacency: None,
    };
    let t = flat_transforms(Mat4::identity());
    let mut p = Pipeline::new(&t, Viewport::new(16, 16), NoCull, NoDepth, shading);
    let mut mock = StrictMock::<C>::new(16, 16);
    p.draw(
        &mut AnyTarget::new(&mut mock),
        &mesh,
        &mut [VertexSlot::EMPTY; 3],
    )
    .unwrap();
    let mut weights = Vec::new();
    for py in 0..16 {
        for px in 0..16 {
            if mock.get(px, py).is_none() {
                continue;
            }
            // Pixel centres in the clip square, y up; the weights of (-1, -1), (1, -1), (-1, 1).
            let x = (f64::from(px) + 0.5) / 8.0 - 1.0;
            let y = 1.0 - (f64::from(py) + 0.5) / 8.0;
            let (b1, b2) = ((x + 1.0) / 2.0, (y + 1.0) / 2.0);
            weights.push((px, py, [1.0 - b1 - b2, b1, b2]));
        }
    }
    (mock, weights)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]

    /// Phong fogs each pixel by the share of fog of its vertices (each the f64 curve at the
    /// vertex's depth), weighted by the pixel's position in the triangle: within the curve's
    /// error of the f64 colour `c + (fog - c) a`, rounded, as a Gouraud vertex is. Where no
    /// vertex is clamped in linear fog that share is the share of the pixel's own depth.
    #[test]
    fn phong_fog_matches_f64_per_pixel(
        c in any::<[u8; 3]>(),
        f in any::<[u8; 3]>(),
        depths in [-6.0f64..6.0, -6.0f64..6.0, -6.0f64..6.0],
        start in -4.0f64..4.0,
        len in 0.05f64..6.0,
        density in prop_oneof![Just(0u16), 1u16..=128],
    ) {
        let (color, fog) = (Rgb888::new(c[0], c[1], c[2]), Rgb888::new(f[0], f[1], f[2]));
        let settings = FogSettings {
            color: fog,
            start: fx(start),
            end: fx(start + len),
            curve: FogCurve::exponential(density),
        };
        let real = |v: Fx16| f64::from(v.to_bits()) / 65536.0;
        let (s, e) = (real(settings.start), real(settings.end));
        let k = f64::from(density) / 16.0;
        let depths = depths.map(fx);
        let vertex_share = depths.map(|d| exact_share((real(d) - s) / (e - s), k));
        let curve_error = if density == 0 {
            0.0
        } else {
            k * k / (8192.0 * (1.0 - (-k).exp()))
        };
        let slope = if density == 0 { 1.0 } else { k / (1.0 - (-k).exp()) };
        // As for a vertex, and the interpolation in 0.30 within a few units of its last bit.
        let share_error = curve_error + (slope * 0.5 + 1.0) / f64::from(FOG_ONE) + 1e-8;
        fn check<C: ShadeColor + core::fmt::Debug>(
            depths: [Fx16; 3],
            color: Rgb888,
            settings: FogSettings<Fx16>,
            vertex_share: [f64; 3],
            share_error: f64,
            channels: fn(C) -> [u8; 3],
        ) -> Result<(), TestCaseError> {
            let sh = Fog::new(ambient_phong::<C>(color), settings, &Mat4::identity());
            let (m, weights) = draw_slanted(depths, sh);
            prop_assert!(weights.len() > 100, "{} pixels drawn", weights.len());
            let (c, f) = (
                [color.r(), color.g(), color.b()],
                [settings.color.r(), settings.color.g(), settings.color.b()],
            );
            for (x, y, w) in weights {
                prop_assert!(w.iter().all(|&l| l > 0.0), "({x}, {y}) outside: {w:?}");
                let a: f64 = w.iter().zip(vertex_share).map(|(l, a)| l * a).sum();
                let got = channels(m.get(x, y).unwrap());
                for i in 0..3 {
                    let max = f64::from(C::MAX[i]);
                    let steps = |v: u8| f64::from(v) * max / 255.0;
                    let exact = steps(c[i]) + (steps(f[i]) - steps(c[i])) * a;
                    let bound =
                        0.5 + 1.0 / 256.0 + (steps(f[i]) - steps(c[i])).abs() * share_error;
                    prop_assert!(
                        (f64::from(got[i]) - exact).abs() <= bound,
                        "({x}, {y}) channel {i}: got {} exact {exact} (bound {bound})", got[i]
                    );
                }
            }
            Ok(())
        }
        check::<Rgb888>(depths, color, settings, vertex_share, share_error, |c| {
            [c.r(), c.g(), c.b()]
        })?;
        check::<Rgb565>(depths, color, settings, vertex_share, share_error, |c| {
            [c.r(), c.g(), c.b()]
        })?;
    }
}

/// Linear fog across a slanted triangle whose vertices all lie between `start` and `end`: each
/// pixel's share is that of its own depth, so Phong's fog is exact per pixel there, not a mix of
/// per-vertex colours (Suzanne-sized check of the claim in the module documentation).
#[test]
fn phong_linear_fog_follows_each_pixels_depth() {
    let depths = [fx(1.25), fx(2.75), fx(2.0)];
    let (start, end) = (1.0, 3.0);
    let settings = linear(Rgb888::WHITE, start, end);
    let sh = Fog::new(
        ambient_phong::<Rgb888>(Rgb888::BLACK),
        settings,
        &Mat4::identity(),
    );
    let (m, weights) = draw_slanted(depths, sh);
    for (x, y, w) in weights {
        let d: f64 = w.iter().zip([1.25, 2.75, 2.0]).map(|(l, d)| l * d).sum();
        let exact = 255.0 * (d - start) / (end - start);
        let got = f64::from(m.get(x, y).unwrap().r());
        assert!((got - exact).abs() <= 0.51, "({x}, {y}): {got} {exact}");
    }
}

/// Phong on Suzanne: fog beyond the mesh leaves the picture bit for bit, fog before it makes it
/// one flat colour, and in between black fog only darkens it.
#[test]
fn phong_fog_on_suzanne() {
    let model = Mat4::rotation_y(Angle::from_degrees(30));
    let phong = || PhongLit::<Fx16, Rgb565, 1>::new(fixtures::scenes3d::lighting::<1>());
    let fogged = |s: FogSettings<Fx16>| move |t: &Transforms<Fx16>| Fog::new(phong(), s, &t.view);
    let plain = draw_suzanne(model, |_| phong(), None);
    let beyond = draw_suzanne(model, fogged(linear(Rgb888::BLACK, 10.0, 20.0)), None);
    assert!(plain == beyond, "fog beyond the mesh changes nothing");
    let grey = Rgb888::new(128, 144, 160);
    let before = draw_suzanne(model, fogged(linear(grey, -2.0, 0.0)), None);
    let raw = RawU16::from(Rgb565::from(grey)).into_inner();
    let covered = plain.iter().filter(|&&p| p != 0).count();
    assert_eq!(before.iter().filter(|&&p| p == raw).count(), covered);
    let mid = draw_suzanne(model, fogged(linear(Rgb888::BLACK, 2.0, 4.0)), None);
    let ch = |p: u16| {
        let c = Rgb565::from(RawU16::new(p));
        [c.r(), c.g(), c.b()]
    };
    assert!(plain
        .iter()
        .zip(&mid)
        .all(|(&a, &b)| ch(a).iter().zip(ch(b)).all(|(x, y)| y <= *x)));
    assert!(plain.iter().zip(&mid).filter(|(a, b)| a != b).count() > 1000);
}
