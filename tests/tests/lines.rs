//! Lines, points and line clipping: ASCII patterns in every octant, properties against the
//! independent reference in `tests::reference_line`, and the i32 limits.

use proptest::prelude::*;
use rasterizer_core::geom::line::Line;
use rasterizer_core::prelude::*;
use rasterizer_core::surface::Band;
use tests::{reference_line, StrictMock};

fn line_mock(w: u32, h: u32, a: (i32, i32), b: (i32, i32)) -> StrictMock<BinaryColor> {
    let mut mock = StrictMock::new(w, h);
    draw_line(
        &mut AnyTarget::new(&mut mock),
        Point::new(a.0, a.1),
        Point::new(b.0, b.1),
        BinaryColor::On,
    )
    .unwrap();
    mock
}

#[test]
fn point_inside_and_outside() {
    let mut mock = StrictMock::<BinaryColor>::new(3, 2);
    let mut t = AnyTarget::new(&mut mock);
    draw_point(&mut t, Point::new(1, 1), BinaryColor::On).unwrap();
    draw_point(&mut t, Point::new(-1, 0), BinaryColor::On).unwrap();
    draw_point(&mut t, Point::new(3, 0), BinaryColor::On).unwrap();
    draw_point(&mut t, Point::new(i32::MIN, i32::MAX), BinaryColor::On).unwrap();
    mock.assert_pattern(&["   ", " # "]);
}

#[test]
fn line_octant_shallow_down_right() {
    line_mock(8, 4, (0, 0), (7, 3))
        .assert_pattern(&["##      ", "  ##    ", "    ##  ", "      ##"]);
}

#[test]
fn line_octant_shallow_up_right() {
    line_mock(8, 4, (0, 3), (7, 0))
        .assert_pattern(&["      ##", "    ##  ", "  ##    ", "##      "]);
}

#[test]
fn line_octant_steep_down_right() {
    line_mock(4, 8, (0, 0), (3, 7)).assert_pattern(&[
        "#   ", "#   ", " #  ", " #  ", "  # ", "  # ", "   #", "   #",
    ]);
}

#[test]
fn line_octant_steep_down_left() {
    line_mock(4, 8, (3, 0), (0, 7)).assert_pattern(&[
        "   #", "   #", "  # ", "  # ", " #  ", " #  ", "#   ", "#   ",
    ]);
}

#[test]
fn line_all_eight_octants_match_reverse_and_reference() {
    let c = (10, 10);
    for &(dx, dy) in &[
        (9, 4),
        (4, 9),
        (-4, 9),
        (-9, 4),
        (-9, -4),
        (-4, -9),
        (4, -9),
        (9, -4),
    ] {
        let end = (c.0 + dx, c.1 + dy);
        let fwd = line_mock(21, 21, c, end).written();
        let back = line_mock(21, 21, end, c).written();
        assert_eq!(fwd, back, "direction changed pixels for ({dx}, {dy})");
        let want: std::collections::BTreeSet<_> =
            reference_line(Point::new(c.0, c.1), Point::new(end.0, end.1))
                .into_iter()
                .map(|p| (p.x, p.y))
                .collect();
        assert_eq!(fwd, want, "octant ({dx}, {dy})");
    }
}

#[test]
fn line_tie_goes_to_smaller_minor_coordinate() {
    // From (0,0) to (2,1): at x = 1 the ideal y is exactly 0.5, so y = 0 is chosen, both ways.
    line_mock(3, 2, (0, 0), (2, 1)).assert_pattern(&["## ", "  #"]);
    line_mock(3, 2, (2, 1), (0, 0)).assert_pattern(&["## ", "  #"]);
    // Rising line: from (0,1) to (2,0), at x = 1 ideal y = 0.5, tie to y = 0.
    line_mock(3, 2, (0, 1), (2, 0)).assert_pattern(&[" ##", "#  "]);
    // y-major: (0,0) to (1,2), at y = 1 ideal x = 0.5, tie to x = 0.
    line_mock(2, 3, (0, 0), (1, 2)).assert_pattern(&["# ", "# ", " #"]);
}

#[test]
fn line_horizontal_vertical_diagonal_and_single_pixel() {
    line_mock(4, 1, (3, 0), (0, 0)).assert_pattern(&["####"]);
    line_mock(1, 3, (0, 0), (0, 2)).assert_pattern(&["#", "#", "#"]);
    line_mock(3, 3, (2, 2), (0, 0)).assert_pattern(&["#  ", " # ", "  #"]);
    line_mock(2, 2, (1, 1), (1, 1)).assert_pattern(&["  ", " #"]);
}

#[test]
fn line_endpoint_on_clip_edge() {
    line_mock(4, 2, (-3, 0), (3, 0)).assert_pattern(&["####", "    "]);
    line_mock(4, 2, (0, 1), (4, 1)).assert_pattern(&["    ", "####"]);
}

#[test]
fn line_clipped_against_user_viewport() {
    let line = Line::new(Point::new(-5, -2), Point::new(12, 5));
    let area = Rectangle::new(Point::new(2, 0), Size::new(5, 4));
    let clipped: Vec<Point> = line.clipped(&area).unwrap().collect();
    let want: Vec<Point> = reference_line(Point::new(-5, -2), Point::new(12, 5))
        .into_iter()
        .filter(|p| area.contains(*p))
        .collect();
    assert_eq!(clipped, want);
    assert!(Line::new(Point::new(0, 10), Point::new(10, 20))
        .clipped(&area)
        .is_none());
}

#[test]
fn line_i32_limits_do_not_overflow() {
    let extremes = [i32::MIN, i32::MIN + 1, -1, 0, 1, 5, i32::MAX - 1, i32::MAX];
    for &x0 in &extremes {
        for &y0 in &extremes {
            for &(x1, y1) in &[(i32::MAX, i32::MIN), (3, 4), (i32::MIN, i32::MAX), (0, 0)] {
                let mut mock = StrictMock::<BinaryColor>::new(8, 8);
                let (a, b) = (Point::new(x0, y0), Point::new(x1, y1));
                draw_line(&mut AnyTarget::new(&mut mock), a, b, BinaryColor::On).unwrap();
                let line = Line::new(a, b);
                for (x, y) in mock.written() {
                    assert!(line.contains(Point::new(x, y)));
                }
            }
        }
    }
}

#[test]
fn line_through_screen_from_i32_extremes_matches_reference_inside() {
    // A line from far outside crossing the screen: compare the visible part with the reference
    // evaluated only at the visible major coordinates.
    let (a, b) = (
        Point::new(-1_000_000_000, -999_999_990),
        Point::new(1_000_000_000, 1_000_000_017),
    );
    let mut mock = StrictMock::<BinaryColor>::new(32, 32);
    draw_line(&mut AnyTarget::new(&mut mock), a, b, BinaryColor::On).unwrap();
    let want = tests::reference_line_on_screen(a, b, 32, 32);
    assert!(!want.is_empty());
    assert_eq!(mock.written(), want);
}

#[test]
fn line_hands_framebuffer_and_any_target_the_same_pixels() {
    let mut buf = [0u16; 40 * 30];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 40, 30).unwrap();
    let mut mock = StrictMock::<Rgb565>::new(40, 30);
    mock.allow_overdraw = true;
    let segs = [
        ((-10, 3), (50, 20)),
        ((39, 0), (0, 29)),
        ((5, -4), (7, 40)),
        ((20, 15), (20, 15)),
    ];
    for &((x0, y0), (x1, y1)) in &segs {
        let (a, b) = (Point::new(x0, y0), Point::new(x1, y1));
        draw_line(&mut fb, a, b, Rgb565::RED).unwrap();
        draw_line(&mut AnyTarget::new(&mut mock), a, b, Rgb565::RED).unwrap();
    }
    for y in 0..30 {
        for x in 0..40 {
            let p = Point::new(x, y);
            let drawn = fb.pixel(p) == Some(Rgb565::RED);
            assert_eq!(drawn, mock.get(x, y).is_some(), "at {p:?}");
        }
    }
}

#[test]
fn gradient_line_endpoints_exact_and_symmetric() {
    let (a, b) = (Point::new(1, 1), Point::new(14, 6));
    let (ca, cb) = (Rgb888::new(255, 0, 10), Rgb888::new(0, 128, 250));
    let mut fwd = StrictMock::<Rgb888>::new(16, 8);
    let mut back = StrictMock::<Rgb888>::new(16, 8);
    draw_line_gradient(&mut AnyTarget::new(&mut fwd), a, b, ca, cb).unwrap();
    draw_line_gradient(&mut AnyTarget::new(&mut back), b, a, cb, ca).unwrap();
    assert_eq!(fwd.get(1, 1), Some(ca));
    assert_eq!(fwd.get(14, 6), Some(cb));
    for (x, y) in fwd.written() {
        assert_eq!(fwd.get(x, y), back.get(x, y));
    }
    // Monotonic red channel from a to b, and each value within half a step of the exact blend.
    let pts = reference_line(a, b);
    let n = (pts.len() - 1) as f64;
    for (k, p) in pts.iter().enumerate() {
        let c = fwd.get(p.x, p.y).unwrap();
        let exact = 255.0 * (1.0 - k as f64 / n);
        assert!(
            (c.r() as f64 - exact).abs() <= 0.5,
            "k={k}: {} vs {exact}",
            c.r()
        );
    }
}

#[test]
fn gradient_line_clipped_keeps_colours_of_unclipped() {
    let (a, b) = (Point::new(-20, 2), Point::new(40, 9));
    let (ca, cb) = (Rgb565::new(31, 0, 0), Rgb565::new(0, 63, 31));
    let mut big = StrictMock::<Rgb565>::new(64, 16);
    let mut small = StrictMock::<Rgb565>::new(16, 16);
    draw_line_gradient(&mut AnyTarget::new(&mut small), a, b, ca, cb).unwrap();
    // The same line shifted right by 24 into a bigger target: nothing clipped on the left.
    let shift = Point::new(24, 0);
    draw_line_gradient(&mut AnyTarget::new(&mut big), a + shift, b + shift, ca, cb).unwrap();
    for (x, y) in small.written() {
        assert_eq!(small.get(x, y), big.get(x + 24, y), "at ({x}, {y})");
    }
}

#[test]
fn gradient_on_gray_and_binary() {
    let mut g = StrictMock::<Gray8>::new(5, 1);
    draw_line_gradient(
        &mut AnyTarget::new(&mut g),
        Point::new(0, 0),
        Point::new(4, 0),
        Gray8::new(0),
        Gray8::new(200),
    )
    .unwrap();
    use embedded_graphics_core::pixelcolor::GrayColor;
    let lumas: Vec<u8> = (0..5).map(|x| g.get(x, 0).unwrap().luma()).collect();
    assert_eq!(lumas, vec![0, 50, 100, 150, 200]);
    let mut b = StrictMock::<BinaryColor>::new(4, 1);
    draw_line_gradient(
        &mut AnyTarget::new(&mut b),
        Point::new(0, 0),
        Point::new(3, 0),
        BinaryColor::Off,
        BinaryColor::On,
    )
    .unwrap();
    let on: Vec<bool> = (0..4).map(|x| b.get(x, 0).unwrap().is_on()).collect();
    assert_eq!(on, vec![false, false, true, true]);
}

fn small_coord() -> impl Strategy<Value = i32> {
    -40i32..80
}

/// Mostly on and around a small screen, where a walk has many pixels, sometimes anywhere.
fn screen_coord() -> impl Strategy<Value = i32> {
    prop_oneof![6 => -8i32..30, 1 => any_coord()]
}

fn any_coord() -> impl Strategy<Value = i32> {
    prop_oneof![
        -40i32..80,
        any::<i32>(),
        Just(i32::MIN),
        Just(i32::MAX),
        -100_000i32..100_000
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn line_pixels_equal_reference(x0 in small_coord(), y0 in small_coord(), x1 in small_coord(), y1 in small_coord()) {
        let (a, b) = (Point::new(x0, y0), Point::new(x1, y1));
        let walked: Vec<Point> = Line::new(a, b).points().collect();
        let mut want = reference_line(a, b);
        let mut got = walked.clone();
        want.sort_by_key(|p| (p.x, p.y));
        got.sort_by_key(|p| (p.x, p.y));
        prop_assert_eq!(got, want);
        // Consecutive pixels are 8-connected and every pixel is distinct.
        for w in walked.windows(2) {
            prop_assert!((w[0].x - w[1].x).abs() <= 1 && (w[0].y - w[1].y).abs() <= 1);
            prop_assert!(w[0] != w[1]);
        }
    }

    #[test]
    fn line_direction_invariant(x0 in any_coord(), y0 in any_coord(), x1 in any_coord(), y1 in any_coord()) {
        let (a, b) = (Point::new(x0, y0), Point::new(x1, y1));
        let area = Rectangle::new(Point::new(-3, -3), Size::new(40, 30));
        let f: Option<Vec<Point>> = Line::new(a, b).clipped(&area).map(|p| p.collect());
        let r: Option<Vec<Point>> = Line::new(b, a).clipped(&area).map(|p| p.collect());
        prop_assert_eq!(f, r);
    }

    #[test]
    fn clipped_equals_unclipped_within_rectangle(
        x0 in small_coord(), y0 in small_coord(), x1 in small_coord(), y1 in small_coord(),
        rx in -10i32..40, ry in -10i32..40, rw in 0u32..40, rh in 0u32..40,
    ) {
        let (a, b) = (Point::new(x0, y0), Point::new(x1, y1));
        let area = Rectangle::new(Point::new(rx, ry), Size::new(rw, rh));
        let got: Vec<Point> = Line::new(a, b).clipped(&area).map(|p| p.collect()).unwrap_or_default();
        let want: Vec<Point> = Line::new(a, b).points().filter(|p| area.contains(*p)).collect();
        prop_assert_eq!(got, want);
    }

    #[test]
    fn clipped_far_lines_match_reference_on_screen(
        x0 in any_coord(), y0 in any_coord(), x1 in any_coord(), y1 in any_coord(),
    ) {
        let (a, b) = (Point::new(x0, y0), Point::new(x1, y1));
        let mut mock = StrictMock::<BinaryColor>::new(24, 16);
        draw_line(&mut AnyTarget::new(&mut mock), a, b, BinaryColor::On).unwrap();
        let want = tests::reference_line_on_screen(a, b, 24, 16);
        prop_assert_eq!(mock.written(), want);
    }

    /// The framebuffer's own line walk (one word per pixel: Rgb565 and Gray8, whole and in a band)
    /// lights exactly the reference pixels on screen, in buffers as narrow as one pixel.
    #[test]
    fn framebuffer_walk_equals_reference(
        x0 in screen_coord(), y0 in screen_coord(), x1 in screen_coord(), y1 in screen_coord(),
        w in 1u32..24, h in 1u32..20, band_y0 in -4i32..20,
    ) {
        let (a, b) = (Point::new(x0, y0), Point::new(x1, y1));
        let want = tests::reference_line_on_screen(a, b, w as i32, h as i32);
        let lit = |f: &dyn Fn(i32, i32) -> bool| -> std::collections::BTreeSet<(i32, i32)> {
            (0..h as i32).flat_map(|y| (0..w as i32).map(move |x| (x, y))).filter(|&(x, y)| f(x, y)).collect()
        };
        let mut buf = vec![0u16; (w * h) as usize];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, w, h).unwrap();
        draw_line(&mut fb, a, b, Rgb565::RED).unwrap();
        prop_assert_eq!(&lit(&|x, y| fb.pixel(Point::new(x, y)) == Some(Rgb565::RED)), &want);
        let mut gray = vec![0u8; (w * h) as usize];
        let mut fb = Framebuffer::<Gray8>::new(&mut gray, w, h).unwrap();
        draw_line(&mut fb, a, b, Gray8::WHITE).unwrap();
        prop_assert_eq!(&lit(&|x, y| fb.pixel(Point::new(x, y)) == Some(Gray8::WHITE)), &want);
        // A band of up to 5 rows stands for screen rows band_y0 ..: it lights those rows of the screen.
        let rows = h.min(5);
        let mut band_buf = vec![0u16; (w * rows) as usize];
        let mut band = Band::new(Framebuffer::<Rgb565>::new(&mut band_buf, w, rows).unwrap(), band_y0);
        draw_line(&mut band, a, b, Rgb565::RED).unwrap();
        let got = lit(&|x, y| y < rows as i32 && band.framebuffer().pixel(Point::new(x, y)) == Some(Rgb565::RED));
        // The reference of the band's rows: the line moved up by band_y0 (where that fits i32), on
        // a screen of the band's size (the reference is exact, so moving moves its pixels).
        let shift = |p: Point| p.y.checked_sub(band_y0).map(|y| Point::new(p.x, y));
        if let (Some(sa), Some(sb)) = (shift(a), shift(b)) {
            let want_band = tests::reference_line_on_screen(sa, sb, w as i32, rows as i32);
            prop_assert_eq!(got, want_band);
        }
    }

    #[test]
    fn line_translation_translates_pixels(
        x0 in small_coord(), y0 in small_coord(), x1 in small_coord(), y1 in small_coord(),
        tx in -1000i32..1000, ty in -1000i32..1000,
    ) {
        let (a, b) = (Point::new(x0, y0), Point::new(x1, y1));
        let t = Point::new(tx, ty);
        let moved: Vec<Point> = Line::new(a + t, b + t).points().collect();
        let orig: Vec<Point> = Line::new(a, b).points().map(|p| p + t).collect();
        prop_assert_eq!(moved, orig);
    }
}

// ---------------------------------------------------------------------------------------------
// The whole i32 range, clip rectangles included

/// The reference line's minor coordinate at major coordinate `m` (x when `|dx| >= |dy|`), exact.
fn reference_minor(a: Point, b: Point, m: i128) -> i128 {
    let (ax, ay, bx, by) = (a.x as i128, a.y as i128, b.x as i128, b.y as i128);
    let (dx, dy) = (bx - ax, by - ay);
    if dx.abs() >= dy.abs() {
        if dx == 0 {
            ay
        } else {
            tests::nearest_tie_down(ay * dx + (m - ax) * dy, dx)
        }
    } else {
        tests::nearest_tie_down(ax * dy + (m - ay) * dx, dy)
    }
}

/// The first `m` in `lo..=hi` where `pred` holds, or `hi + 1`; `pred` false then true.
fn first_true(lo: i128, hi: i128, pred: impl Fn(i128) -> bool) -> i128 {
    let (mut lo, mut hi) = (lo, hi + 1);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if pred(mid) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    lo
}

/// A clipped walk: its first and last pixel and its length.
type Run = ((i32, i32), (i32, i32), u64);

/// The reference's first and last pixel inside `area` in walk order (smaller major coordinate
/// first) and their count, by bisection over the major axis: the reference is monotone, so the
/// pixels inside form one run. `None` when no pixel is inside.
fn reference_clipped(a: Point, b: Point, area: &Rectangle) -> Option<Run> {
    let major_x = (b.x as i128 - a.x as i128).abs() >= (b.y as i128 - a.y as i128).abs();
    let (r0, r1) = (
        (area.top_left.x as i128, area.top_left.y as i128),
        (
            area.top_left.x as i128 + area.size.width as i128,
            area.top_left.y as i128 + area.size.height as i128,
        ),
    );
    let (am, bm, (m_lo, n_lo), (m_hi, n_hi)) = if major_x {
        (a.x as i128, b.x as i128, r0, r1)
    } else {
        (a.y as i128, b.y as i128, (r0.1, r0.0), (r1.1, r1.0))
    };
    let lo = am.min(bm).max(m_lo);
    let hi = am.max(bm).min(m_hi - 1);
    if lo > hi {
        return None;
    }
    let n = |m: i128| reference_minor(a, b, m);
    // Minor rises or falls with the major coordinate: each bound of the minor range cuts the
    // major range once.
    let rising = n(hi) >= n(lo);
    let (first, end) = if rising {
        (
            first_true(lo, hi, |m| n(m) >= n_lo),
            first_true(lo, hi, |m| n(m) >= n_hi),
        )
    } else {
        (
            first_true(lo, hi, |m| n(m) < n_hi),
            first_true(lo, hi, |m| n(m) < n_lo),
        )
    };
    if first >= end {
        return None;
    }
    let px = |m: i128| {
        if major_x {
            (m as i32, n(m) as i32)
        } else {
            (n(m) as i32, m as i32)
        }
    };
    Some((px(first), px(end - 1), (end - first) as u64))
}

fn extreme_coord() -> impl Strategy<Value = i32> {
    prop_oneof![
        3 => -40i32..80,
        1 => Just(i32::MIN),
        1 => Just(i32::MAX),
        1 => (i32::MAX - 50)..=i32::MAX,
        1 => i32::MIN..=(i32::MIN + 50),
        2 => any::<i32>(),
    ]
}

fn extreme_len() -> impl Strategy<Value = u32> {
    prop_oneof![
        3 => 0u32..60,
        1 => Just(u32::MAX),
        1 => (u32::MAX - 50)..=u32::MAX,
        1 => (1u32 << 31) - 50..(1u32 << 31) + 50,
        2 => any::<u32>(),
    ]
}

/// Endpoints anywhere in `i32`; half of the time mirrored through a pixel of a 24 x 16 screen
/// (clamped to `i32`), so that long lines from far outside cross it.
fn endpoints() -> impl Strategy<Value = (Point, Point)> {
    let any = (
        extreme_coord(),
        extreme_coord(),
        extreme_coord(),
        extreme_coord(),
    )
        .prop_map(|(x0, y0, x1, y1)| (Point::new(x0, y0), Point::new(x1, y1)));
    let through =
        (extreme_coord(), extreme_coord(), 0i64..24, 0i64..16).prop_map(|(x, y, cx, cy)| {
            let mirror = |v: i32, c: i64| {
                (2 * c - i64::from(v)).clamp(i32::MIN.into(), i32::MAX.into()) as i32
            };
            (Point::new(x, y), Point::new(mirror(x, cx), mirror(y, cy)))
        });
    prop_oneof![any, through]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// Any endpoints and any clip rectangle, up to the i32/u32 extremes: the clipped walk starts,
    /// ends and counts exactly as the reference's pixels inside the rectangle.
    #[test]
    fn clipped_walk_exact_for_any_endpoints_and_rectangle(
        (a, b) in endpoints(),
        rx in extreme_coord(), ry in extreme_coord(), rw in extreme_len(), rh in extreme_len(),
    ) {
        let area = Rectangle::new(Point::new(rx, ry), Size::new(rw, rh));
        let got = Line::new(a, b).clipped(&area).map(|mut walk| {
            let (count, last) = (walk.remaining(), walk.last_pixel().unwrap());
            let first = walk.next().unwrap();
            ((first.x, first.y), last, count)
        });
        prop_assert_eq!(got, reference_clipped(a, b, &area));
        let back = Line::new(b, a).clipped(&area).map(|w| w.remaining());
        prop_assert_eq!(back, got.map(|g| g.2));
    }

    /// Gradient lines between any endpoints: the reference's pixels on screen, each with
    /// `round((c_a (A - k) + c_b k) / A)` per channel, `k` its major distance from `a`.
    #[test]
    fn gradient_line_any_endpoints_exact_colours(
        (a, b) in endpoints(),
        ca in any::<[u8; 3]>(), cb in any::<[u8; 3]>(),
    ) {
        let (x0, y0, x1, y1) = (a.x, a.y, b.x, b.y);
        let (col_a, col_b) = (Rgb888::new(ca[0], ca[1], ca[2]), Rgb888::new(cb[0], cb[1], cb[2]));
        let mut mock = StrictMock::<Rgb888>::new(24, 16);
        draw_line_gradient(&mut AnyTarget::new(&mut mock), a, b, col_a, col_b).unwrap();
        let mut buf = vec![0u8; 24 * 16 * 3];
        let mut fb = Framebuffer::<Rgb888>::new(&mut buf, 24, 16).unwrap();
        draw_line_gradient(&mut fb, a, b, col_a, col_b).unwrap();
        prop_assert_eq!(mock.written(), tests::reference_line_on_screen(a, b, 24, 16));
        let (dx, dy) = (x1 as i128 - x0 as i128, y1 as i128 - y0 as i128);
        let span = dx.abs().max(dy.abs());
        for (x, y) in mock.written() {
            let k = if dx.abs() >= dy.abs() { (x as i128 - x0 as i128).abs() } else { (y as i128 - y0 as i128).abs() };
            let want: Vec<u8> = (0..3).map(|i| {
                if span == 0 {
                    return ca[i];
                }
                let num = 2 * (ca[i] as i128 * (span - k) + cb[i] as i128 * k) + span;
                (num / (2 * span)) as u8
            }).collect();
            let got = mock.get(x, y).unwrap();
            prop_assert_eq!(vec![got.r(), got.g(), got.b()], want, "pixel ({}, {})", x, y);
            prop_assert_eq!(fb.pixel(Point::new(x, y)), Some(got));
        }
    }
}
