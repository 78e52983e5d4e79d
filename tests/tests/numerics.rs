//! The numeric knobs of `rasterizer_core::numerics`: the reciprocal divide methods stay within one
//! unit of the exact divide, gradient span starts within one unit of the exactly rounded planes,
//! fewer fractional bits within their stated error, and every choice keeps coverage unchanged
//! (band renders equal to whole frames for every choice: `bands.rs`).

use proptest::prelude::*;
use rasterizer_core::math::{Fx, Vec4};
use rasterizer_core::numerics::{Divide, Numerics, SpanStart, Standard};
use rasterizer_core::prelude::*;
use rasterizer_core::raster::interp::{fill_triangle_interp_with, ScreenVertex};
use rasterizer_core::shade::Shading;

/// Exact division and exact span starts: what the other knobs are measured against. (`Standard`
/// starts spans with the pipeline's wrapping planes; `fill_triangle_interp_with` treats that as
/// exact, the pipeline as its fused span loop.)
/// Numerics with the given divide method, fractional bits and span starts.
macro_rules! knobs {
    ($($name:ident: $divide:ident, $frac:literal, $spans:ident;)*) => {$(
        struct $name;
        impl Numerics for $name {
            const DIVIDE: Divide = Divide::$divide;
            const FRAC: u32 = $frac;
            const SPANS: SpanStart = SpanStart::$spans;
        }
    )*};
}
knobs! {
    Exact: Exact, 16, Exact;
    Recip: Reciprocal, 16, Exact;
    Newton: Newton, 16, Exact;
    Gradient: Exact, 16, Gradient;
    Frac12: Exact, 12, Exact;
    Frac8Gradient: Exact, 8, Gradient;
    Newton4Gradient: Newton, 4, Gradient;
}

/// A pipeline of format `Fx<F>` with numerics `N`, only for its `project`.
fn projector<const F: u32, N: Numerics>(
    w: u32,
    h: u32,
) -> Pipeline<Fx<F>, CullClockwise, rasterizer_core::depth::NoDepth, Unlit<Rgb565>, 4, N> {
    let t = Transforms {
        model: Mat4::identity(),
        view: Mat4::identity(),
        projection: Mat4::identity(),
    };
    Pipeline::new(
        &t,
        Viewport::new(w, h),
        CullClockwise,
        rasterizer_core::depth::NoDepth,
        Unlit {
            color: Rgb565::WHITE,
        },
    )
    .with_bits::<4>()
    .with_numerics::<N>()
}

/// A clip-space point inside the view volume: `|x|, |y|, |z| <= w`.
fn inside<const F: u32>(w: i32, x: i32, y: i32, z: i32) -> Vec4<Fx<F>> {
    let part = |v: i32| (i64::from(v) * i64::from(w) / i64::from(i32::MAX)) as i32;
    Vec4 {
        x: Fx::from_bits(part(x)),
        y: Fx::from_bits(part(y)),
        z: Fx::from_bits(part(z)),
        w: Fx::from_bits(w),
    }
}

fn close(a: (SubPoint<4>, u16), b: (SubPoint<4>, u16)) -> bool {
    (a.0.x - b.0.x).abs() <= 1 && (a.0.y - b.0.y).abs() <= 1 && a.1.abs_diff(b.1) <= 1
}

fn check_divide<const F: u32>(w: i32, x: i32, y: i32, z: i32, width: u32, height: u32) {
    let p = inside::<F>(w, x, y, z);
    let exact = projector::<F, Standard>(width, height).project(&p);
    let recip = projector::<F, Recip>(width, height).project(&p);
    let newton = projector::<F, Newton>(width, height).project(&p);
    assert!(
        close(exact, recip),
        "{p:?}: exact {exact:?}, reciprocal {recip:?}"
    );
    assert!(
        close(exact, newton),
        "{p:?}: exact {exact:?}, newton {newton:?}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// One reciprocal (by division or by Newton-Raphson) and three multiplications land within
    /// one sub-pixel unit and one depth step of the exact divide, for every fixed-point format
    /// and any `w` the format holds.
    #[test]
    fn reciprocal_divides_within_one_unit(
        w in 1i32..=i32::MAX,
        x in -i32::MAX..=i32::MAX,
        y in -i32::MAX..=i32::MAX,
        z in -i32::MAX..=i32::MAX,
        width in 1u32..=32767,
        height in 1u32..=32767,
    ) {
        check_divide::<16>(w, x, y, z, width, height);
        check_divide::<8>(w, x, y, z, width, height);
        check_divide::<24>(w, x, y, z, width, height);
    }

    /// Points outside the view volume (and w <= 0) take the exact path in every method.
    #[test]
    fn outside_points_divide_exactly(
        w in i32::MIN..=i32::MAX,
        x in i32::MIN..=i32::MAX,
        y in i32::MIN..=i32::MAX,
        z in i32::MIN..=i32::MAX,
    ) {
        let p = Vec4 { x: Fx16::from_bits(x), y: Fx16::from_bits(y), z: Fx16::from_bits(z), w: Fx16::from_bits(w) };
        let exact = projector::<16, Standard>(320, 240).project(&p);
        let newton = projector::<16, Newton>(320, 240).project(&p);
        prop_assert!(close(exact, newton), "{:?}: {:?} {:?}", p, exact, newton);
    }
}

/// Draws one triangle with Gouraud colours and depth through numerics `N`: the colours and the
/// depth buffer.
fn draw_one<N: Numerics>(v: [ScreenVertex<[i32; 3], 4>; 3]) -> (Vec<Rgb888>, Vec<u16>) {
    let (w, h) = (96u32, 96u32);
    let mut color = vec![0u8; (w * h * 3) as usize];
    let mut depth = vec![u16::MAX; (w * h) as usize];
    {
        let mut fb = Framebuffer::<Rgb888>::new(&mut color, w, h).unwrap();
        let mut db = DepthBuffer::new(&mut depth, w, h, Compare::Always).unwrap();
        let shade = |c: &[i32; 3]| {
            let ch = |x: i32| ((x + 128) >> 8).clamp(0, 255) as u8;
            Rgb888::new(ch(c[0]), ch(c[1]), ch(c[2]))
        };
        let Ok(()) = fill_triangle_interp_with::<_, _, _, _, N, 4>(&mut fb, &mut db, v, shade);
    }
    let pixels = color
        .chunks(3)
        .map(|c| Rgb888::new(c[0], c[1], c[2]))
        .collect();
    (pixels, depth)
}

fn vertex() -> impl Strategy<Value = ScreenVertex<[i32; 3], 4>> {
    (
        -200i32..1736,
        -200i32..1736,
        any::<u16>(),
        prop::array::uniform3(0i32..=255 << 8),
    )
        .prop_map(|(x, y, z, var)| ScreenVertex {
            p: SubPoint::new(x, y),
            z,
            var,
            q: 0,
        })
}

/// The largest channel and depth differences between two draws.
fn compare(a: &(Vec<Rgb888>, Vec<u16>), b: &(Vec<Rgb888>, Vec<u16>)) -> (u8, u16) {
    let mut color = 0u8;
    let mut depth = 0u16;
    for i in 0..a.1.len() {
        let (p, q) = (a.0[i], b.0[i]);
        color = color
            .max(p.r().abs_diff(q.r()))
            .max(p.g().abs_diff(q.g()))
            .max(p.b().abs_diff(q.b()));
        depth = depth.max(a.1[i].abs_diff(b.1[i]));
    }
    (color, depth)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Gradient span starts stay within one 8-bit colour step and one depth step of the exactly
    /// rounded planes (at 16 fractional bits and spans of at most 96 pixels).
    #[test]
    fn gradient_spans_within_one_step(v in prop::array::uniform3(vertex())) {
        let exact = draw_one::<Exact>(v);
        let gradient = draw_one::<Gradient>(v);
        let (color, depth) = compare(&exact, &gradient);
        prop_assert!(color <= 1 && depth <= 1, "colour {} depth {}", color, depth);
    }

    /// Fewer fractional bits: the per-pixel steps are rounded to 2^-FRAC, so across a span of at
    /// most 96 pixels the error grows by at most 96 / 2^(FRAC + 1) units, plus one for rounding.
    #[test]
    fn fewer_fraction_bits_within_their_bound(v in prop::array::uniform3(vertex())) {
        let exact = draw_one::<Exact>(v);
        let f12 = draw_one::<Frac12>(v);
        let f8 = draw_one::<Frac8Gradient>(v);
        // Depth is in whole units: 96 / 2^13 < 1, 96 / 2^9 < 1.
        let (c12, d12) = compare(&exact, &f12);
        prop_assert!(c12 <= 1 && d12 <= 2, "12 bits: colour {} depth {}", c12, d12);
        let (c8, d8) = compare(&exact, &f8);
        prop_assert!(c8 <= 1 && d8 <= 2, "8 bits: colour {} depth {}", c8, d8);
    }
}

/// Coverage never depends on the numeric knobs: the same pixels for every choice.
#[test]
fn coverage_is_independent_of_numerics() {
    let mut x = 0x1234_5678u32;
    let mut r = || {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        x
    };
    for _ in 0..500 {
        // Green is 255 at every vertex, so any covered pixel is green whatever the numerics' error
        // (a few units of 65,280), and the background stays black: coverage is read from the
        // colour, not from the depth (where 65,535 is a real depth too).
        let v: [ScreenVertex<[i32; 3], 4>; 3] = core::array::from_fn(|_| ScreenVertex {
            p: SubPoint::new((r() % 1600) as i32 - 32, (r() % 1600) as i32 - 32),
            z: r() as u16,
            var: [(r() % 65536) as i32, 255 << 8, 0],
            q: 0,
        });
        let covered =
            |d: (Vec<Rgb888>, Vec<u16>)| -> Vec<bool> { d.0.iter().map(|c| c.g() != 0).collect() };
        let base = covered(draw_one::<Exact>(v));
        for (name, other) in [
            ("Standard", covered(draw_one::<Standard>(v))),
            ("Recip", covered(draw_one::<Recip>(v))),
            ("Newton", covered(draw_one::<Newton>(v))),
            ("Gradient", covered(draw_one::<Gradient>(v))),
            ("Frac12", covered(draw_one::<Frac12>(v))),
            ("Frac8Gradient", covered(draw_one::<Frac8Gradient>(v))),
            ("Newton4Gradient", covered(draw_one::<Newton4Gradient>(v))),
        ] {
            // Equal sets: no pixel gained or lost.
            if let Some(i) = (0..base.len()).find(|&i| base[i] != other[i]) {
                panic!(
                    "{name}: pixel {i} covered {} but {} exactly",
                    other[i], base[i]
                );
            }
        }
    }
}

/// A point with `w` near the top of 16.16 projects from the exact sums: `w - y` and `z + w` no
/// longer saturate in the format before the divide (they moved the point by up to a few units).
#[test]
fn projection_near_the_format_limit_is_exact() {
    let (w, y, z) = (1_690_739_965i64, -456_765_291i64, 688_000_000i64);
    let p = Vec4 {
        x: Fx16::from_bits(0),
        y: Fx16::from_bits(y as i32),
        z: Fx16::from_bits(z as i32),
        w: Fx16::from_bits(w as i32),
    };
    let (width, height) = (320u32, 23_846u32);
    for got in [
        projector::<16, Standard>(width, height).project(&p),
        projector::<16, Newton>(width, height).project(&p),
    ] {
        let round = |n: i64, scale: i64| {
            let (n, d) = (i128::from(n) * i128::from(scale), i128::from(2 * w));
            ((2 * n + d).div_euclid(2 * d)) as i64
        };
        let sy = round(w - y, i64::from(height) << 4);
        let depth = round(z + w, 65535);
        assert!(
            (i64::from(got.0.y) - sy).abs() <= 1,
            "{got:?} against y {sy}"
        );
        assert!(
            (i64::from(got.1) - depth).abs() <= 1,
            "{got:?} against depth {depth}"
        );
    }
    // The exact divide is exact.
    let exact = projector::<16, Standard>(width, height).project(&p);
    let n = i128::from(w - y) * (i128::from(height) << 4);
    let d = i128::from(2 * w);
    assert_eq!(i128::from(exact.0.y), (2 * n + d).div_euclid(2 * d));
}

/// Suzanne (M1 scene, 160 x 120, depth buffer, back faces culled) drawn with `shading` through
/// numerics `N`: the colours and the depth buffer.
fn suzanne_with<C, Sh, N>(shading: Sh) -> (Vec<C>, Vec<u16>)
where
    C: PixelColor + Default,
    Sh: Shading<Fx16, Color = C>,
    N: Numerics,
{
    let (w, h) = (160u32, 120u32);
    let loaded = fixtures::obj::LoadedMesh::load(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj"),
    )
    .unwrap();
    let colors: Vec<Rgb888> = loaded
        .positions
        .iter()
        .map(|p| {
            let ch = |v: Fx16| (v.to_bits().clamp(-65536, 65535) + 65536) as u32 * 255 / 131_071;
            Rgb888::new(ch(p.x) as u8, ch(p.y) as u8, ch(p.z) as u8)
        })
        .collect();
    let mut mesh = loaded.mesh();
    mesh.colors = Some(&colors);
    let mut pixels = vec![C::default(); (w * h) as usize];
    let mut depth = vec![u16::MAX; (w * h) as usize];
    let db = DepthBuffer::new(&mut depth, w, h, Compare::Less).unwrap();
    let mut p = Pipeline::new(
        &fixtures::scenes3d::transforms(),
        Viewport::new(w, h),
        CullClockwise,
        db,
        shading,
    )
    .with_numerics::<N>();
    let mut target = tests::StrictMock::<C>::new(w, h);
    target.allow_overdraw = true;
    let mut scratch = vec![VertexSlot::EMPTY; loaded.positions.len()];
    p.draw(&mut AnyTarget::new(&mut target), &mesh, &mut scratch)
        .unwrap();
    for (i, px) in pixels.iter_mut().enumerate() {
        if let Some(c) = target.get(i as i32 % w as i32, i as i32 / w as i32) {
            *px = c;
        }
    }
    (pixels, depth)
}

/// The default numerics' fused span loop (`SpanStart::Wrapping`) against exact span starts, for
/// one shading model: the same pixels covered, depths within one step, and colours within one
/// step of each channel except where the nearest triangle changed (its depth differs).
fn wrapping_against_exact<C, Sh>(name: &str, shading: Sh, max_step: [u8; 3])
where
    C: PixelColor + Default + RgbColor + core::fmt::Debug,
    Sh: Shading<Fx16, Color = C> + Clone,
{
    let (wc, wd) = suzanne_with::<C, Sh, Standard>(shading.clone());
    let (ec, ed) = suzanne_with::<C, Sh, Exact>(shading);
    let covered = |d: &[u16]| d.iter().filter(|&&z| z != u16::MAX).count();
    assert!(covered(&ed) > 3000, "{name}: {} pixels", covered(&ed));
    let mut worst = 0;
    let mut differ = 0;
    for i in 0..wd.len() {
        assert_eq!(
            wd[i] == u16::MAX,
            ed[i] == u16::MAX,
            "{name}: pixel {i} covered by one only"
        );
        let dz = wd[i].abs_diff(ed[i]);
        assert!(
            dz <= 1,
            "{name}: pixel {i}: depth {} against {}",
            wd[i],
            ed[i]
        );
        let (a, b) = (wc[i], ec[i]);
        let step = [
            a.r().abs_diff(b.r()),
            a.g().abs_diff(b.g()),
            a.b().abs_diff(b.b()),
        ];
        if step != [0; 3] {
            differ += 1;
        }
        if dz == 0 {
            for c in 0..3 {
                worst = worst.max(step[c]);
                assert!(
                    step[c] <= max_step[c],
                    "{name}: pixel {i}: {a:?} against {b:?}"
                );
            }
        }
    }
    println!("{name}: {differ} pixels differ, at most {worst} steps where depths agree");
}

/// A regression test for the Phong shader in the fused span loop: its 16.16 normals and positions
/// times `2^FUSED_FRAC` overflowed the loop's 32 bits, so whole faces were lit wrongly.
#[test]
fn wrapping_spans_match_exact_spans_for_every_shading_model() {
    use fixtures::scenes3d::lighting;
    use rasterizer_core::shade::{FlatLit, GouraudLit, PhongLit, VertexColors};
    let one = [1; 3];
    wrapping_against_exact::<Rgb565, _>(
        "unlit 565",
        Unlit {
            color: Rgb565::CYAN,
        },
        [0; 3],
    );
    wrapping_against_exact::<Rgb565, _>("flat 565", FlatLit::new(lighting::<1>()), [0; 3]);
    wrapping_against_exact::<Rgb565, _>("vertex colours 565", VertexColors::new(), one);
    wrapping_against_exact::<Rgb888, _>("vertex colours 888", VertexColors::new(), one);
    wrapping_against_exact::<Rgb565, _>("Gouraud 565", GouraudLit::new(lighting::<1>()), one);
    wrapping_against_exact::<Rgb888, _>("Gouraud 888", GouraudLit::new(lighting::<1>()), one);
    wrapping_against_exact::<Rgb565, _>("Phong 565", PhongLit::new(lighting::<1>()), one);
    wrapping_against_exact::<Rgb888, _>("Phong 888", PhongLit::new(lighting::<1>()), one);
}
