//! Ordered dithering (`Numerics::DITHER`): a flat colour between two steps of the target gives
//! the Bayer pattern, and the mean of every tile is the exact (f64) colour to within a fraction
//! of a step.

use proptest::prelude::*;
use rasterizer_core::color::ShadeColor;
use rasterizer_core::mesh::Mesh;
use rasterizer_core::numerics::{Dither, Numerics, Standard};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::VertexColors;
use tests::StrictMock;

struct Bayer4;
impl Numerics for Bayer4 {
    const DITHER: Dither = Dither::Bayer4;
}
struct Bayer8;
impl Numerics for Bayer8 {
    const DITHER: Dither = Dither::Bayer8;
}

/// A `w x h` screen filled with one vertex colour: a quad over the whole clip square, with
/// identity transforms, through numerics `N`. Every pixel written once (the mock checks it).
fn flat<C, N>(color: Rgb888, w: u32, h: u32) -> StrictMock<C>
where
    C: ShadeColor + Default + core::fmt::Debug,
    N: Numerics,
{
    let one = Fx16::ONE;
    let v = |x: Fx16, y: Fx16| Vec3::new(x, y, Fx16::ZERO);
    let positions = [v(-one, -one), v(one, -one), v(one, one), v(-one, one)];
    let colors = [color; 4];
    let triangles: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];
    let mesh = Mesh {
        positions: &positions,
        normals: None,
        colors: Some(&colors),
        uvs: None,
        triangles: &triangles,
        adjacency: None,
    };
    let t = Transforms {
        model: Mat4::identity(),
        view: Mat4::identity(),
        projection: Mat4::identity(),
    };
    let mut p = Pipeline::new(
        &t,
        Viewport::new(w, h),
        NoCull,
        NoDepth,
        VertexColors::<C>::new(),
    )
    .with_numerics::<N>();
    let mut mock = StrictMock::<C>::new(w, h);
    let mut scratch = vec![VertexSlot::EMPTY; 4];
    p.draw(&mut AnyTarget::new(&mut mock), &mesh, &mut scratch)
        .unwrap();
    assert_eq!(mock.written().len(), (w * h) as usize, "every pixel drawn");
    mock
}

/// `#` where `upper` holds, for each pixel.
fn pattern<C: PixelColor>(
    m: &StrictMock<C>,
    w: i32,
    h: i32,
    upper: impl Fn(C) -> bool,
) -> Vec<String> {
    (0..h)
        .map(|y| {
            (0..w)
                .map(|x| {
                    if upper(m.get(x, y).unwrap()) {
                        '#'
                    } else {
                        '.'
                    }
                })
                .collect()
        })
        .collect()
}

/// Red 76 of 255 is 9.239 steps of Rgb565's 5-bit red: a quarter of each 4 x 4 tile (the four
/// largest thresholds of the Bayer matrix) goes up to 10, the rest down to 9.
#[test]
fn flat_rgb565_between_two_steps_gives_the_bayer_pattern() {
    let color = Rgb888::new(76, 0, 0);
    let m = flat::<Rgb565, Bayer4>(color, 8, 8);
    let quarter = ["........", "#.#.#.#.", "........", "#.#.#.#."];
    let want: Vec<String> = quarter
        .iter()
        .chain(&quarter)
        .map(|r| r.to_string())
        .collect();
    assert!((0..8).all(|y| (0..8).all(|x| [9, 10].contains(&m.get(x, y).unwrap().r()))));
    assert_eq!(pattern(&m, 8, 8, |c: Rgb565| c.r() == 10), want);
    // Without dithering, every pixel rounds to the nearest step.
    let m = flat::<Rgb565, Standard>(color, 8, 8);
    assert!(pattern(&m, 8, 8, |c: Rgb565| c.r() == 9)
        .iter()
        .all(|r| r == "########"));
}

/// The classic case: a grey a quarter of the way to white on a one-bit display lights a quarter
/// of the pixels, spread evenly; the 8 x 8 matrix does the same over its larger tile.
#[test]
fn flat_grey_on_binary_color_gives_the_bayer_pattern() {
    let grey = Rgb888::new(64, 64, 64);
    let m = flat::<BinaryColor, Bayer4>(grey, 8, 4);
    assert_eq!(
        pattern(&m, 8, 4, |c: BinaryColor| c.is_on()),
        ["........", "#.#.#.#.", "........", "#.#.#.#."]
    );
    let m = flat::<BinaryColor, Bayer8>(grey, 8, 8);
    assert_eq!(
        pattern(&m, 8, 8, |c: BinaryColor| c.is_on()),
        [
            "........", "#.#.#.#.", "........", "#.#.#.#.", "........", "#.#.#.#.", "........",
            "#.#.#.#.",
        ]
    );
    // Without dithering, a quarter grey is off everywhere.
    let m = flat::<BinaryColor, Standard>(grey, 8, 4);
    assert!(pattern(&m, 8, 4, |c: BinaryColor| c.is_on())
        .iter()
        .all(|r| r == "........"));
}

/// A channel of a colour.
type Channel = fn(Rgb565) -> u8;

/// The mean of each `n x n` tile of channel `ch` of `m`, against `exact` steps.
fn worst_tile_error<C: PixelColor>(
    m: &StrictMock<C>,
    (w, h, n): (i32, i32, i32),
    ch: impl Fn(C) -> u8,
    exact: f64,
) -> f64 {
    let mut worst = 0f64;
    for ty in (0..h).step_by(n as usize) {
        for tx in (0..w).step_by(n as usize) {
            let sum: u32 = (0..n)
                .flat_map(|y| (0..n).map(move |x| (tx + x, ty + y)))
                .map(|(x, y)| u32::from(ch(m.get(x, y).unwrap())))
                .sum();
            worst = worst.max((f64::from(sum) / f64::from(n * n) - exact).abs());
        }
    }
    worst
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Any flat colour: the mean of every 4 x 4 (8 x 8) tile of each Rgb565 channel is the f64
    /// colour `c max / 255` within 1/16 (1/64) of a step; rounding alone is off by up to 1/2.
    #[test]
    fn tile_means_match_the_exact_colour(r in 0u8..=255, g in 0u8..=255, b in 0u8..=255) {
        let exact = |v: u8, max: u8| f64::from(v) * f64::from(max) / 255.0;
        let m4 = flat::<Rgb565, Bayer4>(Rgb888::new(r, g, b), 16, 8);
        let m8 = flat::<Rgb565, Bayer8>(Rgb888::new(r, g, b), 16, 8);
        let channels: [(Channel, u8, u8); 3] =
            [(|c| c.r(), r, 31), (|c| c.g(), g, 63), (|c| c.b(), b, 31)];
        for (ch, v, max) in channels {
            let e4 = worst_tile_error(&m4, (16, 8, 4), ch, exact(v, max));
            prop_assert!(e4 <= 1.0 / 16.0, "Bayer4 {v} of {max}: {e4}");
            let e8 = worst_tile_error(&m8, (16, 8, 8), ch, exact(v, max));
            prop_assert!(e8 <= 1.0 / 64.0, "Bayer8 {v} of {max}: {e8}");
        }
    }

    /// Any grey on a one-bit display: the share of pixels lit in each tile is the grey level
    /// within 1/16 (1/64).
    #[test]
    fn binary_tile_means_match_the_grey_level(v in 0u8..=255) {
        let grey = Rgb888::new(v, v, v);
        let on = |c: BinaryColor| u8::from(c.is_on());
        let exact = f64::from(v) / 255.0;
        let e4 = worst_tile_error(&flat::<BinaryColor, Bayer4>(grey, 8, 8), (8, 8, 4), on, exact);
        prop_assert!(e4 <= 1.0 / 16.0, "Bayer4 grey {v}: {e4}");
        let e8 = worst_tile_error(&flat::<BinaryColor, Bayer8>(grey, 8, 8), (8, 8, 8), on, exact);
        prop_assert!(e8 <= 1.0 / 64.0, "Bayer8 grey {v}: {e8}");
    }
}

/// Gray8 gets fractions from lighting: Suzanne Gouraud-lit (M1 scene, 160 x 120) dithered stays
/// within one step of the rounded picture everywhere, changes some pixels, and keeps the mean.
#[test]
fn gray8_gouraud_dithers_within_one_step() {
    fn draw<N: Numerics>() -> Vec<u8> {
        let (w, h) = (160u32, 120u32);
        let loaded = fixtures::obj::LoadedMesh::load(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj"),
        )
        .unwrap();
        let mesh = loaded.mesh();
        let mut z = vec![u16::MAX; (w * h) as usize];
        let mut p = Pipeline::new(
            &fixtures::scenes3d::camera(Mat4::rotation_y(Angle::from_degrees(30)), w, h),
            Viewport::new(w, h),
            CullClockwise,
            DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap(),
            GouraudLit::<Fx16, Gray8, 1>::new(fixtures::scenes3d::lighting::<1>()),
        )
        .with_numerics::<N>();
        let mut pixels = vec![0u8; (w * h) as usize];
        let mut fb = Framebuffer::<Gray8>::new(&mut pixels, w, h).unwrap();
        let mut scratch = vec![VertexSlot::EMPTY; loaded.positions.len()];
        p.draw(&mut fb, &mesh, &mut scratch).unwrap();
        pixels
    }
    let (rounded, dithered) = (draw::<Standard>(), draw::<Bayer4>());
    assert!(rounded
        .iter()
        .zip(&dithered)
        .all(|(a, b)| a.abs_diff(*b) <= 1));
    let changed = rounded
        .iter()
        .zip(&dithered)
        .filter(|(a, b)| a != b)
        .count();
    assert!(changed > 100, "only {changed} pixels dithered");
    let sum = |v: &[u8]| v.iter().map(|&x| i64::from(x)).sum::<i64>();
    // Rounding and dithering both keep the mean within half a step per pixel.
    assert!((sum(&rounded) - sum(&dithered)).abs() < rounded.len() as i64 / 2);
}
