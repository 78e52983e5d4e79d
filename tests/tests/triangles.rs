//! Triangles: outline and fill patterns, coverage against the independent edge-function reference,
//! watertightness of fans, grids and strips, Gouraud colour, and the hard cases by name.

use proptest::prelude::*;
use rasterizer_core::geom::GUARD_BAND_PIXELS;
use rasterizer_core::prelude::*;
use rasterizer_core::raster::interp::{fill_triangle_interp, ScreenVertex};
use std::collections::BTreeSet;
use tests::{reference_triangle, StrictMock};

/// Whole-pixel corner coordinates in 28.4.
fn px(x: i32, y: i32) -> SubPoint<4> {
    SubPoint::new(x * 16, y * 16)
}

fn fill_mock<const B: u32>(w: u32, h: u32, v: [SubPoint<B>; 3]) -> StrictMock<BinaryColor> {
    let mut mock = StrictMock::new(w, h);
    fill_triangle(&mut AnyTarget::new(&mut mock), v, BinaryColor::On).unwrap();
    mock
}

fn reference_set<const B: u32>(v: [SubPoint<B>; 3], w: i32, h: i32) -> BTreeSet<(i32, i32)> {
    reference_triangle(v.map(|p| (i64::from(p.x), i64::from(p.y))), B, w, h)
        .into_iter()
        .collect()
}

#[test]
fn fill_right_triangle_top_left() {
    fill_mock(6, 6, [px(0, 0), px(6, 0), px(0, 6)])
        .assert_pattern(&["##### ", "####  ", "###   ", "##    ", "#     ", "      "]);
}

#[test]
fn fill_same_triangle_in_both_windings() {
    let cw = fill_mock(8, 8, [px(1, 1), px(7, 3), px(2, 7)]).written();
    let ccw = fill_mock(8, 8, [px(1, 1), px(2, 7), px(7, 3)]).written();
    assert_eq!(cw, ccw);
    assert!(!cw.is_empty());
}

#[test]
fn fill_flat_bottom_and_flat_top() {
    fill_mock(7, 4, [px(3, 0), px(7, 4), px(0, 4)])
        .assert_pattern(&["       ", "  ##   ", " ####  ", "###### "]);
    fill_mock(7, 4, [px(0, 0), px(7, 0), px(3, 4)])
        .assert_pattern(&["###### ", " ####  ", "  ##   ", "       "]);
}

#[test]
fn fill_all_orientations_match_reference() {
    // A triangle rotated through 8 orientations and its mirror images, each checked against the
    // reference: covers left/right middle vertices and every edge direction.
    let base = [(2, 1), (13, 5), (5, 12)];
    for k in 0..8 {
        let v = base.map(|(x, y): (i32, i32)| {
            let (x, y) = (x - 7, y - 7);
            let (x, y) = match k % 4 {
                0 => (x, y),
                1 => (-y, x),
                2 => (-x, -y),
                _ => (y, -x),
            };
            let x = if k >= 4 { -x } else { x };
            SubPoint::new((x + 8) * 16 + 5, (y + 8) * 16 + 3)
        });
        assert_eq!(
            fill_mock(16, 16, v).written(),
            reference_set(v, 16, 16),
            "orientation {k}"
        );
    }
}

#[test]
fn horizontal_and_vertical_edges_exactly_on_pixel_centres() {
    // Edges at x = 1.5 and y = 1.5 (pixel centres): left/top edges keep their centres, the right and
    // bottom ones (x = 4.5, y = 3.5) do not.
    let c = |x: i32, y: i32| SubPoint::new(x * 16 + 8, y * 16 + 8);
    let mut mock = StrictMock::<BinaryColor>::new(6, 5);
    let mut t = AnyTarget::new(&mut mock);
    fill_triangle(&mut t, [c(1, 1), c(4, 1), c(4, 3)], BinaryColor::On).unwrap();
    fill_triangle(&mut t, [c(1, 1), c(4, 3), c(1, 3)], BinaryColor::On).unwrap();
    mock.assert_pattern(&["      ", " ###  ", " ###  ", "      ", "      "]);
}

#[test]
fn zero_area_triangles_draw_nothing() {
    for v in [
        [px(1, 1), px(1, 1), px(1, 1)],
        [px(0, 0), px(3, 3), px(6, 6)],
        [px(0, 2), px(5, 2), px(3, 2)],
        [px(2, 0), px(2, 5), px(2, 3)],
        [
            SubPoint::new(17, 17),
            SubPoint::new(33, 33),
            SubPoint::new(49, 49),
        ],
    ] {
        assert!(fill_mock(8, 8, v).written().is_empty(), "{v:?}");
    }
}

#[test]
fn collinear_and_repeated_vertices_draw_nothing() {
    assert!(fill_mock(8, 8, [px(3, 3), px(3, 3), px(6, 1)])
        .written()
        .is_empty());
    assert!(fill_mock(8, 8, [px(0, 7), px(7, 0), px(7, 0)])
        .written()
        .is_empty());
}

#[test]
fn sliver_one_subpixel_wide_no_gap_no_overdraw() {
    // Two triangles forming a quad of one sub-pixel height along a long diagonal, plus a sliver one
    // sub-pixel wide: covered pixels equal the reference and the shared edge draws nothing twice.
    let a = SubPoint::new(0, 8 * 16);
    let b = SubPoint::new(40 * 16, 20 * 16 + 1);
    let c = SubPoint::new(40 * 16, 20 * 16);
    let d = SubPoint::new(0, 8 * 16 + 1);
    let mut mock = StrictMock::<BinaryColor>::new(40, 30);
    let mut t = AnyTarget::new(&mut mock);
    fill_triangle(&mut t, [a, b, c], BinaryColor::On).unwrap();
    fill_triangle(&mut t, [a, d, b], BinaryColor::On).unwrap();
    let mut want = reference_set([a, b, c], 40, 30);
    want.extend(reference_set([a, d, b], 40, 30));
    assert_eq!(mock.written(), want);
}

#[test]
fn sliver_triangle_no_gap() {
    // A fan of slivers around a centre must still tile its hull without gaps or overdraw.
    let centre = SubPoint::new(20 * 16 + 3, 15 * 16 + 7);
    let ring: Vec<SubPoint<4>> = (0..=64)
        .map(|i| {
            let (x, y) = match i / 16 {
                0 => (i % 16 * 40 / 16, 0),
                1 => (40, (i % 16) * 30 / 16),
                2 => (40 - (i % 16) * 40 / 16, 30),
                3 => (0, 30 - (i % 16) * 30 / 16),
                _ => (0, 0),
            };
            SubPoint::new(x * 16, y * 16)
        })
        .collect();
    let mut mock = StrictMock::<BinaryColor>::new(40, 30);
    for w in ring.windows(2) {
        fill_triangle(
            &mut AnyTarget::new(&mut mock),
            [centre, w[0], w[1]],
            BinaryColor::On,
        )
        .unwrap();
    }
    assert_eq!(mock.written().len(), 40 * 30);
}

#[test]
fn triangle_far_larger_than_screen() {
    let v = [
        SubPoint::new(-1_000_000 * 16, -1_000_000 * 16),
        SubPoint::new(1_500_000 * 16, -3),
        SubPoint::new(-7, 1_800_000 * 16),
    ];
    assert_eq!(fill_mock(32, 24, v).written(), reference_set(v, 32, 24));
    assert_eq!(fill_mock(32, 24, v).written().len(), 32 * 24);
}

#[test]
fn triangle_outside_guard_band_draws_nothing() {
    let far = (GUARD_BAND_PIXELS + 1) * 16;
    let v = [
        SubPoint::new(-far, -far),
        SubPoint::new(far, 0),
        SubPoint::new(0, far),
    ];
    assert!(fill_mock(8, 8, v).written().is_empty());
    let v = [
        SubPoint::new(i32::MIN, i32::MIN),
        SubPoint::new(i32::MAX, 0),
        SubPoint::new(0, i32::MAX),
    ];
    assert!(fill_mock(8, 8, v).written().is_empty());
}

#[test]
fn triangle_at_guard_band_edge_matches_reference() {
    let g = GUARD_BAND_PIXELS * 16;
    let v = [
        SubPoint::new(-g, -g),
        SubPoint::new(g, -g + 5),
        SubPoint::new(3, g),
    ];
    assert_eq!(fill_mock(16, 16, v).written(), reference_set(v, 16, 16));
    let g8 = GUARD_BAND_PIXELS << 8;
    let v = [
        SubPoint::<8>::raw(-g8, 17),
        SubPoint::raw(g8, -g8),
        SubPoint::raw(g8, g8),
    ];
    assert_eq!(fill_mock(16, 16, v).written(), reference_set(v, 16, 16));
}

#[test]
fn subpixel_bits_zero_and_eight() {
    let v0 = [
        SubPoint::<0>::raw(0, 0),
        SubPoint::raw(9, 2),
        SubPoint::raw(3, 8),
    ];
    assert_eq!(fill_mock(10, 10, v0).written(), reference_set(v0, 10, 10));
    let v8 = [
        SubPoint::<8>::raw(37, 300),
        SubPoint::raw(2000, 1000),
        SubPoint::raw(900, 2400),
    ];
    assert_eq!(fill_mock(10, 10, v8).written(), reference_set(v8, 10, 10));
}

#[test]
fn outline_draws_each_pixel_once() {
    let mut mock = StrictMock::<BinaryColor>::new(8, 6);
    draw_triangle(
        &mut AnyTarget::new(&mut mock),
        [Point::new(0, 0), Point::new(7, 2), Point::new(2, 5)],
        BinaryColor::On,
    )
    .unwrap();
    mock.assert_pattern(&[
        "##      ", "# ####  ", " #    ##", " #   ## ", "  ###   ", "  #     ",
    ]);
    // A thin triangle whose edges share pixels along their length.
    let mut thin = StrictMock::<BinaryColor>::new(12, 3);
    draw_triangle(
        &mut AnyTarget::new(&mut thin),
        [Point::new(0, 0), Point::new(11, 1), Point::new(11, 2)],
        BinaryColor::On,
    )
    .unwrap();
    assert!(thin.written().len() >= 12);
}

#[test]
fn outline_clipped_far_outside() {
    let mut mock = StrictMock::<BinaryColor>::new(8, 8);
    draw_triangle(
        &mut AnyTarget::new(&mut mock),
        [
            Point::new(i32::MIN, 3),
            Point::new(i32::MAX, 4),
            Point::new(3, i32::MAX),
        ],
        BinaryColor::On,
    )
    .unwrap();
    assert!(!mock.written().is_empty());
}

#[test]
fn gouraud_vertex_pixels_get_vertex_colours() {
    // Vertices on pixel centres: the pixels there that are covered get exactly the vertex colour.
    let c = |x: i32, y: i32| SubPoint::new(x * 16 + 8, y * 16 + 8);
    let v = [c(1, 1), c(30, 4), c(6, 20)];
    let colors = [
        Rgb888::new(255, 0, 0),
        Rgb888::new(0, 255, 0),
        Rgb888::new(0, 0, 255),
    ];
    let mut mock = StrictMock::<Rgb888>::new(32, 24);
    fill_triangle_gouraud(&mut AnyTarget::new(&mut mock), v, colors).unwrap();
    // Which vertex pixels are covered is the top-left rule's call: the independent edge-function
    // reference decides, and every covered one must carry its vertex's colour exactly.
    let want = reference_set(v, 32, 24);
    for (p, col) in [
        ((1, 1), colors[0]),
        ((30, 4), colors[1]),
        ((6, 20), colors[2]),
    ] {
        let covered = want.contains(&p);
        assert_eq!(mock.get(p.0, p.1).is_some(), covered, "vertex pixel {p:?}");
        if covered {
            assert_eq!(mock.get(p.0, p.1), Some(col), "vertex pixel {p:?}");
        }
    }
    // A bigger triangle with a covered left vertex: the reference covers (1, 10), and it keeps
    // its vertex colour, so at least one vertex colour is really compared.
    let v = [c(10, 0), c(1, 10), c(20, 12)];
    assert!(reference_set(v, 24, 16).contains(&(1, 10)));
    let mut mock2 = StrictMock::<Rgb888>::new(24, 16);
    fill_triangle_gouraud(&mut AnyTarget::new(&mut mock2), v, colors).unwrap();
    assert_eq!(mock2.get(1, 10), Some(colors[1]));
}

#[test]
fn gouraud_same_pixels_as_flat_and_within_half_step_of_exact() {
    let v = [
        SubPoint::new(13, 21),
        SubPoint::new(600, 90),
        SubPoint::new(170, 470),
    ];
    let colors = [
        Rgb888::new(250, 10, 0),
        Rgb888::new(0, 200, 30),
        Rgb888::new(40, 40, 255),
    ];
    let mut mock = StrictMock::<Rgb888>::new(40, 32);
    fill_triangle_gouraud(&mut AnyTarget::new(&mut mock), v, colors).unwrap();
    assert_eq!(mock.written(), reference_set(v, 40, 32));
    // Exact barycentric blend at each centre, in f64.
    let f = v.map(|p| (p.x as f64 / 16.0, p.y as f64 / 16.0));
    let area = (f[1].0 - f[0].0) * (f[2].1 - f[0].1) - (f[2].0 - f[0].0) * (f[1].1 - f[0].1);
    for (x, y) in mock.written() {
        let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
        let l1 = ((cx - f[0].0) * (f[2].1 - f[0].1) - (f[2].0 - f[0].0) * (cy - f[0].1)) / area;
        let l2 = ((f[1].0 - f[0].0) * (cy - f[0].1) - (cx - f[0].0) * (f[1].1 - f[0].1)) / area;
        let l0 = 1.0 - l1 - l2;
        let got = mock.get(x, y).unwrap();
        let ch = |c: Rgb888, i: usize| [c.r(), c.g(), c.b()][i] as f64;
        for i in 0..3 {
            let exact = l0 * ch(colors[0], i) + l1 * ch(colors[1], i) + l2 * ch(colors[2], i);
            let g = [got.r(), got.g(), got.b()][i] as f64;
            assert!(
                (g - exact).abs() <= 0.5 + 1e-9,
                "({x},{y}) ch{i}: {g} vs {exact}"
            );
        }
    }
}

#[test]
fn gouraud_sliver_with_huge_gradient_stays_in_range() {
    // Measured: 0.5 steps, over the pixels of the long edge. Half a step is the rounding of the
    // exact blend itself, so the bound is that and no more (as for the wide triangle above).
    const SLIVER_BOUND: f64 = 0.5 + 1e-9;
    // A sliver 1/16 pixel wide at its base whose long edge runs through the pixel centres
    // (0.5 + 4k, 0.5 + 3k): blue goes from 0 to 31 across 1/16 pixel, and the top-left rule covers
    // those centres on one of the long edges, so there are pixels to check.
    let v = [
        SubPoint::new(8, 8),
        SubPoint::new(40 * 16 + 8, 30 * 16 + 8),
        SubPoint::new(40 * 16 + 9, 30 * 16 + 8),
    ];
    let colors = [
        Rgb565::new(31, 0, 0),
        Rgb565::new(0, 63, 0),
        Rgb565::new(0, 0, 31),
    ];
    let mut mock = StrictMock::<Rgb565>::new(48, 32);
    fill_triangle_gouraud(&mut AnyTarget::new(&mut mock), v, colors).unwrap();
    // Coverage from the independent edge-function reference, colour from the exact barycentric
    // blend in f64: a gradient of up to 63 steps per 1/16 pixel across the sliver must not carry
    // a pixel beyond the blend at its centre (an overflowing or unclamped gradient would).
    assert_eq!(mock.written(), reference_set(v, 48, 32));
    assert!(!mock.written().is_empty());
    let f = v.map(|p| (p.x as f64 / 16.0, p.y as f64 / 16.0));
    let area = (f[1].0 - f[0].0) * (f[2].1 - f[0].1) - (f[2].0 - f[0].0) * (f[1].1 - f[0].1);
    let mut worst = 0.0f64;
    for (x, y) in mock.written() {
        let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
        let l1 = ((cx - f[0].0) * (f[2].1 - f[0].1) - (f[2].0 - f[0].0) * (cy - f[0].1)) / area;
        let l2 = ((f[1].0 - f[0].0) * (cy - f[0].1) - (cx - f[0].0) * (f[1].1 - f[0].1)) / area;
        let l0 = 1.0 - l1 - l2;
        let got = mock.get(x, y).unwrap();
        let ch = |c: Rgb565, i: usize| [c.r(), c.g(), c.b()][i] as f64;
        for i in 0..3 {
            let exact = l0 * ch(colors[0], i) + l1 * ch(colors[1], i) + l2 * ch(colors[2], i);
            worst = worst.max((ch(got, i) - exact).abs());
        }
    }
    assert!(worst <= SLIVER_BOUND, "worst channel error {worst} steps");
}

#[test]
fn framebuffer_and_any_target_agree_on_gouraud() {
    let v = [
        SubPoint::new(-100, 40),
        SubPoint::new(700, 100),
        SubPoint::new(300, 600),
    ];
    let colors = [
        Rgb565::new(31, 0, 5),
        Rgb565::new(3, 63, 0),
        Rgb565::new(0, 20, 31),
    ];
    let mut buf = [0u16; 40 * 32];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 40, 32).unwrap();
    fill_triangle_gouraud(&mut fb, v, colors).unwrap();
    let mut mock = StrictMock::<Rgb565>::new(40, 32);
    fill_triangle_gouraud(&mut AnyTarget::new(&mut mock), v, colors).unwrap();
    for y in 0..32 {
        for x in 0..40 {
            let want = mock.get(x, y).unwrap_or(Rgb565::BLACK);
            assert_eq!(fb.pixel(Point::new(x, y)), Some(want));
        }
    }
}

fn coord() -> impl Strategy<Value = i32> {
    -80i32..(48 * 16 + 80)
}

fn any_sub() -> impl Strategy<Value = i32> {
    prop_oneof![
        coord(),
        any::<i32>(),
        Just(i32::MIN),
        Just(i32::MAX),
        -(1 << 26)..(1 << 26)
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn coverage_equals_reference(x0 in coord(), y0 in coord(), x1 in coord(), y1 in coord(), x2 in coord(), y2 in coord()) {
        let v = [SubPoint::new(x0, y0), SubPoint::new(x1, y1), SubPoint::new(x2, y2)];
        prop_assert_eq!(fill_mock(48, 40, v).written(), reference_set(v, 48, 40));
    }

    #[test]
    fn coverage_equals_reference_other_bits(x0 in 0i32..2000, y0 in 0i32..2000, x1 in 0i32..2000, y1 in 0i32..2000, x2 in 0i32..2000, y2 in 0i32..2000) {
        let v6 = [SubPoint::<6>::raw(x0, y0), SubPoint::raw(x1, y1), SubPoint::raw(x2, y2)];
        prop_assert_eq!(fill_mock(32, 32, v6).written(), reference_set(v6, 32, 32));
        let v2 = [SubPoint::<2>::raw(x0 / 16, y0 / 16), SubPoint::raw(x1 / 16, y1 / 16), SubPoint::raw(x2 / 16, y2 / 16)];
        prop_assert_eq!(fill_mock(32, 32, v2).written(), reference_set(v2, 32, 32));
    }

    #[test]
    fn fan_is_watertight(cx in 100i32..600, cy in 100i32..500, n in 3usize..24, seed in any::<u64>()) {
        // A closed fan around a centre: a star-shaped polygon of n spokes at sorted angles. Every pixel
        // of the union is drawn once (the mock panics otherwise), and the union equals the union of
        // the reference coverages.
        let mut rng = seed;
        let mut next = || { rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17; rng };
        let ring: Vec<SubPoint<4>> = (0..n).map(|i| {
            let ang = (i as f64 + (next() % 1000) as f64 / 3000.0) / n as f64 * std::f64::consts::TAU;
            let r = 60.0 + (next() % 300) as f64;
            SubPoint::new(cx + (r * ang.cos()) as i32, cy + (r * ang.sin()) as i32)
        }).collect();
        let centre = SubPoint::new(cx, cy);
        let mut mock = StrictMock::<BinaryColor>::new(48, 40);
        let mut want = BTreeSet::new();
        for i in 0..n {
            let t = [centre, ring[i], ring[(i + 1) % n]];
            fill_triangle(&mut AnyTarget::new(&mut mock), t, BinaryColor::On).unwrap();
            want.extend(reference_set(t, 48, 40));
        }
        prop_assert_eq!(mock.written(), want);
    }

    #[test]
    fn jittered_grid_tiles_screen_exactly_once(seed in any::<u64>(), cols in 1usize..7, rows in 1usize..6) {
        let (w, h) = (48i32, 40i32);
        let mut rng = seed | 1;
        let mut next = || { rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17; rng };
        // Grid corners in 28.4; inner ones jittered; the border stays on the screen edge.
        let mut pts = vec![vec![SubPoint::<4>::default(); cols + 1]; rows + 1];
        for (j, row) in pts.iter_mut().enumerate() {
            for (i, p) in row.iter_mut().enumerate() {
                let mut x = i as i32 * w * 16 / cols as i32;
                let mut y = j as i32 * h * 16 / rows as i32;
                if i > 0 && i < cols { x += (next() % 61) as i32 - 30; }
                if j > 0 && j < rows { y += (next() % 61) as i32 - 30; }
                *p = SubPoint::new(x, y);
            }
        }
        let mut mock = StrictMock::<BinaryColor>::new(w as u32, h as u32);
        for j in 0..rows {
            for i in 0..cols {
                let (a, b, c, d) = (pts[j][i], pts[j][i + 1], pts[j + 1][i + 1], pts[j + 1][i]);
                let flip = next() % 2 == 0;
                let (t1, t2) = if flip { ([a, b, c], [a, c, d]) } else { ([a, b, d], [b, c, d]) };
                fill_triangle(&mut AnyTarget::new(&mut mock), t1, BinaryColor::On).unwrap();
                fill_triangle(&mut AnyTarget::new(&mut mock), t2, BinaryColor::On).unwrap();
            }
        }
        prop_assert_eq!(mock.written().len(), (w * h) as usize);
    }

    #[test]
    fn strip_is_watertight(seed in any::<u64>(), n in 3usize..20) {
        let mut rng = seed | 1;
        let mut next = || { rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17; rng };
        let pts: Vec<SubPoint<4>> = (0..n + 2).map(|i| {
            let x = (i as i32) * 48 * 16 / (n as i32 + 1) + (next() % 21) as i32 - 10;
            let y = if i % 2 == 0 { 100 + (next() % 100) as i32 } else { 500 + (next() % 100) as i32 };
            SubPoint::new(x, y)
        }).collect();
        let mut mock = StrictMock::<BinaryColor>::new(48, 40);
        let mut want = BTreeSet::new();
        for w in pts.windows(3) {
            let t = [w[0], w[1], w[2]];
            fill_triangle(&mut AnyTarget::new(&mut mock), t, BinaryColor::On).unwrap();
            want.extend(reference_set(t, 48, 40));
        }
        prop_assert_eq!(mock.written(), want);
    }

    #[test]
    fn whole_pixel_translation_translates_pixels(x0 in coord(), y0 in coord(), x1 in coord(), y1 in coord(), x2 in coord(), y2 in coord(), tx in -20i32..20, ty in -20i32..20) {
        let v = [SubPoint::new(x0, y0), SubPoint::new(x1, y1), SubPoint::new(x2, y2)];
        let moved = v.map(|p| SubPoint::new(p.x + tx * 16, p.y + ty * 16));
        // Large target so nothing is clipped away in either.
        let a: BTreeSet<_> = fill_mock(160, 150, v.map(|p| SubPoint::new(p.x + 40 * 16, p.y + 40 * 16))).written();
        let b: BTreeSet<_> = fill_mock(160, 150, moved.map(|p| SubPoint::new(p.x + 40 * 16, p.y + 40 * 16))).written();
        let shifted: BTreeSet<_> = a.iter().map(|&(x, y)| (x + tx, y + ty)).collect();
        prop_assert_eq!(shifted, b);
    }

    #[test]
    fn any_i32_input_never_panics_or_writes_out_of_bounds(x0 in any_sub(), y0 in any_sub(), x1 in any_sub(), y1 in any_sub(), x2 in any_sub(), y2 in any_sub()) {
        let v = [SubPoint::new(x0, y0), SubPoint::new(x1, y1), SubPoint::new(x2, y2)];
        let colors = [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE];
        let mut mock = StrictMock::<Rgb565>::new(20, 16);
        fill_triangle_gouraud(&mut AnyTarget::new(&mut mock), v, colors).unwrap();
        let inside = v.iter().all(|p| p.in_guard_band());
        if inside {
            prop_assert_eq!(mock.written(), reference_set(v, 20, 16));
        } else {
            prop_assert!(mock.written().is_empty());
        }
        let mut buf = [0u16; 20 * 16];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 20, 16).unwrap();
        fill_triangle(&mut fb, v, Rgb565::WHITE).unwrap();
        let pts = [Point::new(x0, y0), Point::new(x1, y1), Point::new(x2, y2)];
        let mut outline = StrictMock::<Rgb565>::new(20, 16);
        draw_triangle(&mut AnyTarget::new(&mut outline), pts, Rgb565::WHITE).unwrap();
    }
}

/// Target of the tall-triangle property: taller than the 32 rows from which a flat fill walks its
/// edges with fixed-point accumulators.
const TALL_W: u32 = 24;
const TALL_H: u32 = 300;

/// One tall-triangle case at `B` sub-pixel bits: the pixels of a framebuffer fill and of a
/// fill through `AnyTarget` equal the reference's.
fn check_tall<const B: u32>(corners: [(i32, i32); 3]) -> Result<(), TestCaseError> {
    let v = corners.map(|(x, y)| SubPoint::<B>::raw(x >> (8 - B), y >> (8 - B)));
    let want = reference_set(v, TALL_W as i32, TALL_H as i32);
    prop_assert_eq!(&fill_mock(TALL_W, TALL_H, v).written(), &want);
    let mut buf = vec![0u16; (TALL_W * TALL_H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, TALL_W, TALL_H).unwrap();
    fill_triangle(&mut fb, v, Rgb565::WHITE).unwrap();
    let lit: BTreeSet<(i32, i32)> = (0..TALL_H as i32)
        .flat_map(|y| (0..TALL_W as i32).map(move |x| (x, y)))
        .filter(|&(x, y)| fb.pixel(Point::new(x, y)) == Some(Rgb565::WHITE))
        .collect();
    prop_assert_eq!(&lit, &want);
    Ok(())
}

/// A corner in 1/256 pixels: mostly within the tall target's columns (where the fixed-point
/// walks are taken), sometimes beside them or far above, below or beside the target (long edges,
/// large divisors, clipped rows and columns: the exact walk).
fn tall_corner() -> impl Strategy<Value = (i32, i32)> {
    prop_oneof![
        6 => (0..(TALL_W as i32) * 256, -60 * 256..360 * 256),
        2 => (-40 * 256..64 * 256, -60 * 256..360 * 256),
        1 => (-4000 * 256..4000 * 256, -40_000 * 256..40_000 * 256),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Tall triangles, whose rows the flat fill walks with fixed-point accumulators when they lie
    /// within the clip area's columns and their edges' divisors allow (edges up to 127 pixels
    /// tall at 8 sub-pixel bits, 32,767 at 4) and with the exact remainder walk otherwise: the
    /// same pixels as the reference either way.
    #[test]
    fn tall_triangles_equal_reference(corners in [tall_corner(), tall_corner(), tall_corner()]) {
        check_tall::<0>(corners)?;
        check_tall::<4>(corners)?;
        check_tall::<8>(corners)?;
    }
}

/// The pixels the interpolating (3D) fill writes for `v`, with no depth buffer.
fn interp_mock<const B: u32>(w: u32, h: u32, v: [SubPoint<B>; 3]) -> StrictMock<BinaryColor> {
    let mut mock = StrictMock::new(w, h);
    let vertices = v.map(|p| ScreenVertex {
        p,
        z: 0,
        var: [0i32],
        q: 1,
    });
    fill_triangle_interp::<_, _, _, _, B, false>(
        &mut AnyTarget::new(&mut mock),
        &mut NoDepth,
        vertices,
        |_| BinaryColor::On,
    )
    .unwrap();
    mock
}

/// A vertex within a few pixels of `(16, 16)`: most such triangles reach at most four pixel
/// centres, where the fill asks the span walk for coverage before setting up its planes.
fn tiny() -> impl Strategy<Value = i32> {
    (16 * 64 - 160)..(16 * 64 + 160)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn interp_coverage_of_tiny_triangles_equals_reference(x0 in tiny(), y0 in tiny(), x1 in tiny(), y1 in tiny(), x2 in tiny(), y2 in tiny()) {
        let v = [SubPoint::<6>::raw(x0, y0), SubPoint::raw(x1, y1), SubPoint::raw(x2, y2)];
        prop_assert_eq!(interp_mock(32, 32, v).written(), reference_set(v, 32, 32));
    }

    #[test]
    fn interp_coverage_equals_reference(x0 in coord(), y0 in coord(), x1 in coord(), y1 in coord(), x2 in coord(), y2 in coord()) {
        let v = [SubPoint::new(x0, y0), SubPoint::new(x1, y1), SubPoint::new(x2, y2)];
        prop_assert_eq!(interp_mock(48, 40, v).written(), reference_set(v, 48, 40));
    }
}

// ---------------------------------------------------------------------------------------------
// The whole guard band at every sub-pixel setting
// ---------------------------------------------------------------------------------------------

/// True when `got` is within half a step, plus the span stepping's error (below 2^-10 on targets
/// at most 64 pixels wide), of the exact barycentric blend of `colors` at the centre of pixel `p`.
/// Exact rational arithmetic in `i128`, from edge functions (not the fill's colour planes).
fn gouraud_close(
    v: [(i64, i64); 3],
    bits: u32,
    colors: [[u8; 3]; 3],
    p: (i32, i32),
    got: [u8; 3],
) -> bool {
    let s = 1i128 << bits;
    let (cx, cy) = ((2 * i128::from(p.0) + 1) * s, (2 * i128::from(p.1) + 1) * s);
    let d = v.map(|(x, y)| (2 * i128::from(x), 2 * i128::from(y)));
    let edge =
        |a: (i128, i128), b: (i128, i128)| (b.0 - a.0) * (cy - a.1) - (b.1 - a.1) * (cx - a.0);
    let w = [edge(d[1], d[2]), edge(d[2], d[0]), edge(d[0], d[1])];
    let total: i128 = w.iter().sum();
    (0..3).all(|ch| {
        let num: i128 = (0..3).map(|k| i128::from(colors[k][ch]) * w[k]).sum();
        // |got - num / total| <= 1/2 + 2^-10
        1024 * (i128::from(got[ch]) * total - num).abs() <= 513 * total.abs()
    })
}

/// A coordinate drawn without knowing the sub-pixel bits: placed on the target, anywhere in the
/// guard band, at or next to its limits, or just beyond them.
#[derive(Debug, Clone, Copy)]
enum Place {
    /// Raw 1/256-pixel units from two pixels left of the target to two beyond it.
    Screen(i32),
    /// A fraction (of 2^32) of the way from `-limit` to `+limit`.
    Band(u32),
    /// `±limit`, less a few units inwards.
    Limit { negative: bool, inset: i32 },
    /// Outside the band: `±(limit + 1)`, or the ends of `i32`.
    Beyond(u8),
}

impl Place {
    fn raw(self, bits: u32) -> i32 {
        let limit = GUARD_BAND_PIXELS << bits;
        match self {
            Place::Screen(t) => t >> (8 - bits),
            Place::Band(f) => {
                (-i64::from(limit) + (((2 * i64::from(limit) + 1) * i64::from(f)) >> 32)) as i32
            }
            Place::Limit { negative, inset } => {
                let m = limit - inset;
                if negative {
                    -m
                } else {
                    m
                }
            }
            Place::Beyond(k) => [limit + 1, -limit - 1, i32::MAX, i32::MIN][usize::from(k % 4)],
        }
    }
}

/// Target size of the guard-band properties.
const GB_W: u32 = 16;
const GB_H: u32 = 12;

fn place() -> impl Strategy<Value = Place> {
    prop_oneof![
        4 => (-2 * 256..(GB_W as i32 + 2) * 256).prop_map(Place::Screen),
        3 => any::<u32>().prop_map(Place::Band),
        2 => (any::<bool>(), prop_oneof![Just(0), Just(1), 0..300]).prop_map(|(negative, inset)| Place::Limit { negative, inset }),
        1 => any::<u8>().prop_map(Place::Beyond),
    ]
}

/// Flat and Gouraud fills of one triangle: the reference's pixels (none with a vertex outside the
/// guard band), the same on a framebuffer and through `AnyTarget`, colours within half a step of
/// exact. The dev profile checks every intermediate for overflow.
fn check_fills<const B: u32>(
    places: [(Place, Place); 3],
    colors: [Rgb888; 3],
) -> Result<(), TestCaseError> {
    let v = places.map(|(x, y)| SubPoint::<B>::raw(x.raw(B), y.raw(B)));
    let want = if v.iter().all(|p| p.in_guard_band()) {
        reference_set(v, GB_W as i32, GB_H as i32)
    } else {
        BTreeSet::new()
    };
    prop_assert_eq!(&fill_mock(GB_W, GB_H, v).written(), &want);
    let mut mock = StrictMock::<Rgb888>::new(GB_W, GB_H);
    fill_triangle_gouraud(&mut AnyTarget::new(&mut mock), v, colors).unwrap();
    prop_assert_eq!(&mock.written(), &want);
    let mut buf = vec![0u8; (GB_W * GB_H * 3) as usize];
    let mut fb = Framebuffer::<Rgb888>::new(&mut buf, GB_W, GB_H).unwrap();
    fill_triangle(&mut fb, v, Rgb888::WHITE).unwrap();
    let lit: BTreeSet<(i32, i32)> = (0..GB_H as i32)
        .flat_map(|y| (0..GB_W as i32).map(move |x| (x, y)))
        .filter(|&(x, y)| fb.pixel(Point::new(x, y)) == Some(Rgb888::WHITE))
        .collect();
    prop_assert_eq!(&lit, &want);
    fill_triangle_gouraud(&mut fb, v, colors).unwrap();
    let rgb = |c: Rgb888| [c.r(), c.g(), c.b()];
    let raw = v.map(|p| (i64::from(p.x), i64::from(p.y)));
    for &(x, y) in &want {
        let got = mock.get(x, y).unwrap();
        prop_assert_eq!(fb.pixel(Point::new(x, y)), Some(got));
        prop_assert!(
            gouraud_close(raw, B, colors.map(rgb), (x, y), rgb(got)),
            "pixel ({}, {}) = {:?}, vertices {:?}",
            x,
            y,
            got,
            v
        );
    }
    Ok(())
}

fn check_fills_at(
    bits: u32,
    places: [(Place, Place); 3],
    colors: [Rgb888; 3],
) -> Result<(), TestCaseError> {
    match bits {
        0 => check_fills::<0>(places, colors),
        1 => check_fills::<1>(places, colors),
        2 => check_fills::<2>(places, colors),
        3 => check_fills::<3>(places, colors),
        4 => check_fills::<4>(places, colors),
        5 => check_fills::<5>(places, colors),
        6 => check_fills::<6>(places, colors),
        7 => check_fills::<7>(places, colors),
        _ => check_fills::<8>(places, colors),
    }
}

#[test]
fn gouraud_at_guard_band_limits_keeps_base_colour() {
    // c0 * 2 * |doubled area| overflowed u64 for a triangle this large at 8 sub-pixel bits: debug
    // panicked, release lost the red channel.
    let m = (1 << 29) - 1;
    let v = [
        SubPoint::<8>::raw(-m, -m),
        SubPoint::raw(m, -m),
        SubPoint::raw(0, m),
    ];
    let colors = [
        Rgb565::new(8, 16, 16),
        Rgb565::new(8, 16, 16),
        Rgb565::new(8, 16, 16),
    ];
    let mut buf = [0u16; 8 * 8];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 8, 8).unwrap();
    fill_triangle_gouraud(&mut fb, v, colors).unwrap();
    assert!(buf.iter().all(|&w| w == 0x4210), "{buf:04x?}");
    // Every corner of the band and every sub-pixel setting, with distinct colours.
    let colors = [
        Rgb888::new(255, 0, 7),
        Rgb888::new(0, 255, 128),
        Rgb888::new(9, 40, 255),
    ];
    let limit = |negative| Place::Limit { negative, inset: 0 };
    let screen = Place::Screen(3 * 256);
    let corners = [
        [
            (limit(true), limit(true)),
            (limit(false), limit(true)),
            (limit(true), limit(false)),
        ],
        [
            (limit(false), limit(false)),
            (limit(true), limit(false)),
            (limit(false), limit(true)),
        ],
        [
            (limit(true), limit(true)),
            (limit(false), screen),
            (limit(true), limit(false)),
        ],
        [
            (screen, limit(true)),
            (limit(false), limit(false)),
            (limit(true), limit(false)),
        ],
    ];
    for bits in 0..=8 {
        for places in corners {
            check_fills_at(bits, places, colors).unwrap();
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn fills_exact_across_the_guard_band_at_every_bits(
        bits in 0u32..=8,
        places in [(place(), place()), (place(), place()), (place(), place())],
        colors in [any::<[u8; 3]>(), any::<[u8; 3]>(), any::<[u8; 3]>()],
    ) {
        check_fills_at(bits, places, colors.map(|c| Rgb888::new(c[0], c[1], c[2])))?;
    }
}

/// An outline corner anywhere in `i32`: near the target, at the ends, or anywhere.
fn outline_coord() -> impl Strategy<Value = i32> {
    prop_oneof![
        3 => -30i32..50,
        1 => Just(i32::MIN),
        1 => Just(i32::MAX),
        2 => any::<i32>(),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// Outlines with corners anywhere in `i32`: exactly the union of the three edges' reference
    /// pixels on the target, each written once (the mock fails on overdraw), the same on a
    /// framebuffer.
    #[test]
    fn outline_any_i32_corners_is_the_union_of_its_edges(
        x0 in outline_coord(), y0 in outline_coord(), x1 in outline_coord(), y1 in outline_coord(),
        x2 in outline_coord(), y2 in outline_coord(),
    ) {
        let p = [Point::new(x0, y0), Point::new(x1, y1), Point::new(x2, y2)];
        let mut mock = StrictMock::<BinaryColor>::new(20, 16);
        draw_triangle(&mut AnyTarget::new(&mut mock), p, BinaryColor::On).unwrap();
        let mut want = BTreeSet::new();
        for i in 0..3 {
            want.extend(tests::reference_line_on_screen(p[i], p[(i + 1) % 3], 20, 16));
        }
        prop_assert_eq!(mock.written(), want.clone());
        let mut buf = [0u16; 20 * 16];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 20, 16).unwrap();
        draw_triangle(&mut fb, p, Rgb565::WHITE).unwrap();
        let lit: BTreeSet<(i32, i32)> = (0..16)
            .flat_map(|y| (0..20).map(move |x| (x, y)))
            .filter(|&(x, y)| fb.pixel(Point::new(x, y)) == Some(Rgb565::WHITE))
            .collect();
        prop_assert_eq!(lit, want);
    }
}
