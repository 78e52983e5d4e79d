//! Rectangles at the integer limits: `ClipTo`, `Band`, `Framebuffer` fills and the viewport's clip
//! rectangle. For any `i32` origin and `u32` size nothing panics (tests build with overflow
//! checks) and every primitive draws exactly its pixels inside the rectangle and the target, none
//! outside.

use proptest::prelude::*;
use rasterizer_core::prelude::*;
use rasterizer_core::surface::{Band, ClipTo};
use std::collections::BTreeSet;
use tests::StrictMock;

const W: u32 = 24;
const H: u32 = 16;

/// A half-open pixel rectangle in `i64`: `(x0, y0, x1, y1)`.
type Cells = (i64, i64, i64, i64);

fn cells(r: &Rectangle) -> Cells {
    let (x, y) = (i64::from(r.top_left.x), i64::from(r.top_left.y));
    (
        x,
        y,
        x + i64::from(r.size.width),
        y + i64::from(r.size.height),
    )
}

fn meet(a: Cells, b: Cells) -> Cells {
    (a.0.max(b.0), a.1.max(b.1), a.2.min(b.2), a.3.min(b.3))
}

/// The pixels of `c` (which must be small).
fn set(c: Cells) -> BTreeSet<(i32, i32)> {
    let mut out = BTreeSet::new();
    for y in c.1..c.3 {
        for x in c.0..c.2 {
            out.insert((x as i32, y as i32));
        }
    }
    out
}

/// The scenes drawn through a clipped surface, each on a fresh target.
const SCENES: usize = 10;

/// Columns every scene covers: the target's and a few more.
const COLS: core::ops::Range<i32> = -3..W as i32 + 3;

/// The rows the row-by-row scenes draw: around the target and at both ends of `i32`.
fn scene_rows() -> impl Iterator<Item = i32> {
    (-10..40)
        .chain(i32::MIN..i32::MIN + 8)
        .chain(i32::MAX - 7..=i32::MAX)
}

/// True when scene `k` covers row `y` in all of `COLS` (scenes 6 and 7 are checked otherwise).
fn covers(k: usize, y: i32) -> bool {
    match k {
        // The filled shapes reach 2^20 pixels from the origin, and cover at least half of that.
        0..=2 => y.unsigned_abs() <= 1 << 19,
        4 => true,
        _ => scene_rows().any(|r| r == y),
    }
}

/// Draws scene `k` in white: scenes 0..=5 and 8..=9 light the rows `covers` names; scene 6 is the
/// solid fill of `extra`; scene 7, a triangle outline from far outside, lights some pixels.
fn draw_scene<S>(s: &mut S, k: usize, extra: Rectangle)
where
    S: Surface<Color = Rgb565>,
    S::Error: core::fmt::Debug,
{
    let white = Rgb565::WHITE;
    let far = 1 << 20;
    let big = [
        SubPoint::new(-far * 16, -far * 16),
        SubPoint::new(far * 16, -far * 16),
        SubPoint::new(0, far * 16),
    ];
    match k {
        0 => fill_triangle(s, big, white).unwrap(),
        1 => fill_triangle_gouraud(s, big, [white; 3]).unwrap(),
        2 => {
            let quad = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
                .map(|(x, y)| SubPoint::new(x * far * 16, y * far * 16));
            Polygon::<4>::new(&quad)
                .unwrap()
                .fill(s, FillRule::NonZero, white)
                .unwrap();
        }
        3 => {
            for y in scene_rows() {
                draw_line(s, Point::new(i32::MIN, y), Point::new(i32::MAX, y), white).unwrap();
            }
        }
        4 => {
            for x in COLS {
                let (a, b) = (Point::new(x, i32::MAX), Point::new(x, i32::MIN));
                draw_line_gradient(s, a, b, white, white).unwrap();
            }
        }
        5 => {
            for y in scene_rows() {
                for x in COLS {
                    draw_point(s, Point::new(x, y), white).unwrap();
                }
            }
            for (x, y) in [(i32::MIN, 0), (i32::MAX, 0), (0, i32::MIN), (0, i32::MAX)] {
                draw_point(s, Point::new(x, y), white).unwrap();
            }
        }
        6 => s.fill_solid(&extra, white).unwrap(),
        7 => draw_triangle(
            s,
            [
                Point::new(i32::MIN, -5),
                Point::new(i32::MAX, 7),
                Point::new(3, i32::MAX),
            ],
            white,
        )
        .unwrap(),
        8 => {
            for y in scene_rows() {
                s.fill_span(i32::MIN, y, u32::MAX, white).unwrap();
            }
        }
        _ => {
            let pts = scene_rows()
                .flat_map(|y| COLS.map(move |x| (x, y)))
                .chain([(i32::MIN, 0), (i32::MAX, 0)])
                .map(|(x, y)| Pixel(Point::new(x, y), white));
            s.draw_iter(pts).unwrap();
        }
    }
}

/// Checks scene `k`'s pixels against the clip area `clip`.
fn check_scene(
    k: usize,
    got: &BTreeSet<(i32, i32)>,
    clip: Cells,
    extra: Rectangle,
) -> Result<(), TestCaseError> {
    let inside = set(clip);
    match k {
        6 => prop_assert_eq!(got, &set(meet(clip, cells(&extra))), "fill_solid"),
        7 => prop_assert!(got.is_subset(&inside), "outline outside the clip area"),
        _ => {
            let want: BTreeSet<_> = inside.into_iter().filter(|p| covers(k, p.1)).collect();
            prop_assert_eq!(got, &want, "scene {}", k)
        }
    }
    Ok(())
}

/// Every scene through `ClipTo(r)` (and `ClipTo(r2)` inside it when given) over a strict mock and
/// over a framebuffer: exactly the pixels inside the rectangles and the target.
fn check_clip_to(
    r: Rectangle,
    r2: Option<Rectangle>,
    extra: Rectangle,
) -> Result<(), TestCaseError> {
    let screen = (0, 0, i64::from(W), i64::from(H));
    let mut clip = meet(screen, cells(&r));
    if let Some(r2) = r2 {
        clip = meet(clip, cells(&r2));
    }
    for k in 0..SCENES {
        let mut mock = StrictMock::<Rgb565>::new(W, H);
        mock.allow_overdraw = k == 7;
        let mut any = AnyTarget::new(&mut mock);
        let mut outer = ClipTo::new(&mut any, r);
        match r2 {
            Some(r2) => draw_scene(&mut ClipTo::new(&mut outer, r2), k, extra),
            None => draw_scene(&mut outer, k, extra),
        }
        check_scene(k, &mock.written(), clip, extra)?;

        let mut buf = vec![0u16; (W * H) as usize];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
        let mut outer = ClipTo::new(&mut fb, r);
        match r2 {
            Some(r2) => draw_scene(&mut ClipTo::new(&mut outer, r2), k, extra),
            None => draw_scene(&mut outer, k, extra),
        }
        let got = lit(&buf, 0);
        check_scene(k, &got, clip, extra)?;
    }
    Ok(())
}

/// The non-black pixels of a `W`-wide Rgb565 buffer whose first row stands for screen row `y0`.
fn lit(buf: &[u16], y0: i64) -> BTreeSet<(i32, i32)> {
    buf.iter()
        .enumerate()
        .filter(|(_, &w)| w != 0)
        .map(|(i, _)| ((i as u32 % W) as i32, (y0 + i64::from(i as u32 / W)) as i32))
        .collect()
}

#[test]
fn clip_to_rectangle_whose_end_overflows_i32_stays_inside() {
    // x + width past i32::MAX: embedded-graphics' own intersection overflowed (a debug panic) and
    // in release gave a rectangle reaching outside both the clip rectangle and the framebuffer.
    let extra = Rectangle::new(
        Point::new(i32::MIN, i32::MIN),
        Size::new(u32::MAX, u32::MAX),
    );
    for (x, y, w, h) in [
        (100, 0, u32::MAX, 10),
        (100, 0, u32::MAX - 50, u32::MAX),
        (10, 3, u32::MAX, u32::MAX),
        (i32::MAX, i32::MAX, u32::MAX, u32::MAX),
        (i32::MIN, i32::MIN, u32::MAX, u32::MAX),
        (i32::MAX, 0, 32767, 32767),
        (-5, -5, 1 << 31, 1 << 31),
    ] {
        let r = Rectangle::new(Point::new(x, y), Size::new(w, h));
        check_clip_to(r, None, extra).unwrap();
        check_clip_to(r, Some(r), extra).unwrap();
    }
}

fn coord() -> impl Strategy<Value = i32> {
    prop_oneof![
        4 => -6i32..(W as i32 + 6),
        1 => Just(i32::MIN),
        1 => Just(i32::MAX),
        1 => (i32::MAX - 40)..=i32::MAX,
        1 => i32::MIN..=(i32::MIN + 40),
        1 => any::<i32>(),
    ]
}

fn length() -> impl Strategy<Value = u32> {
    prop_oneof![
        4 => 0u32..(W + 12),
        1 => Just(u32::MAX),
        1 => (u32::MAX - 40)..=u32::MAX,
        1 => (1u32 << 31) - 20..(1u32 << 31) + 20,
        1 => any::<u32>(),
    ]
}

/// The first row of a band: near the target, or at either end of `i32`.
fn band_row() -> impl Strategy<Value = i32> {
    prop_oneof![
        2 => -8i32..40,
        1 => i32::MIN..=(i32::MIN + 12),
        1 => (i32::MAX - 12)..=i32::MAX,
    ]
}

fn rect() -> impl Strategy<Value = Rectangle> {
    (coord(), coord(), length(), length())
        .prop_map(|(x, y, w, h)| Rectangle::new(Point::new(x, y), Size::new(w, h)))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn clip_to_any_rectangles_draws_exactly_inside(r in rect(), r2 in proptest::option::of(rect()), extra in rect()) {
        check_clip_to(r, r2, extra)?;
    }

    /// The clip area a `ClipTo` reports is the intersection.
    #[test]
    fn clip_to_area_is_the_intersection(r in rect(), r2 in rect()) {
        let mut mock = StrictMock::<Rgb565>::new(W, H);
        let mut any = AnyTarget::new(&mut mock);
        let mut outer = ClipTo::new(&mut any, r);
        let inner = ClipTo::new(&mut outer, r2);
        let area = inner.clip_area();
        let want = meet(meet((0, 0, i64::from(W), i64::from(H)), cells(&r)), cells(&r2));
        if want.0 < want.2 && want.1 < want.3 {
            prop_assert_eq!(cells(&area), want);
        } else {
            prop_assert!(area.is_zero_sized());
        }
        prop_assert_eq!(inner.bounding_box(), area);
    }

    /// A band anywhere in `i32`, even one whose rows run past `i32::MAX`: each scene lights exactly
    /// the band's rows of the clip area, and the checked methods drop what lies outside.
    #[test]
    fn band_at_any_row_draws_exactly_its_rows(y0 in band_row(), r in rect(), extra in rect()) {
        let rows = 4u32;
        let band = (0, i64::from(y0), i64::from(W), i64::from(y0) + i64::from(rows));
        // Rows past i32::MAX stand for no screen row.
        let band = meet(band, (i64::MIN, i64::MIN, i64::MAX, i64::from(i32::MAX) + 1));
        let clip = meet(band, cells(&r));
        for k in 0..SCENES {
            let mut buf = vec![0u16; (W * rows) as usize];
            let fb = Framebuffer::<Rgb565>::new(&mut buf, W, rows).unwrap();
            let mut strip = Band::new(fb, y0);
            draw_scene(&mut ClipTo::new(&mut strip, r), k, extra);
            check_scene(k, &lit(&buf, i64::from(y0)), clip, extra)?;
        }
        // Straight into the band: spans and pixels at any row land only on the band's own rows.
        let mut buf = vec![0u16; (W * rows) as usize];
        let fb = Framebuffer::<Rgb565>::new(&mut buf, W, rows).unwrap();
        let mut strip = Band::new(fb, y0);
        let white = Rgb565::WHITE;
        for y in [i32::MIN, i32::MIN + 1, -1, 0, i32::MAX - 1, i32::MAX, y0 ^ i32::MIN] {
            if !(band.1..band.3).contains(&i64::from(y)) {
                strip.fill_span(0, y, W, white).unwrap();
                strip.shade_span(0, y, W, || white).unwrap();
                strip.draw_iter([Pixel(Point::new(1, y), white)]).unwrap();
                strip.fill_solid(&Rectangle::new(Point::new(0, y), Size::new(W, 1)), white).unwrap();
            }
        }
        prop_assert!(buf.iter().all(|&w| w == 0), "a row outside the band was drawn");
    }

    /// Framebuffer fills with any rectangle, span or pixel: only the covered pixels inside.
    #[test]
    fn framebuffer_fills_any_rectangle_exactly(r in rect(), x in coord(), y in coord(), len in length()) {
        let screen = (0, 0, i64::from(W), i64::from(H));
        let mut buf = vec![0u16; (W * H) as usize];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
        fb.fill_solid(&r, Rgb565::WHITE).unwrap();
        prop_assert_eq!(lit(&buf, 0), set(meet(screen, cells(&r))));

        let mut buf = vec![0u16; (W * H) as usize];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
        fb.fill_span(x, y, len, Rgb565::WHITE).unwrap();
        let span = (i64::from(x), i64::from(y), i64::from(x) + i64::from(len), i64::from(y) + 1);
        prop_assert_eq!(lit(&buf, 0), set(meet(screen, span)));

        // A colour iterator as long as the area's first rows, at most: it ends in bounded time.
        let mut buf = vec![0u16; (W * H) as usize];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
        let n = (u64::from(r.size.width) * 3).min(4096) as usize;
        fb.fill_contiguous(&r, core::iter::repeat_n(Rgb565::WHITE, n)).unwrap();
        prop_assert!(lit(&buf, 0).is_subset(&set(meet(screen, cells(&r)))));
    }
}

// ---------------------------------------------------------------------------------------------
// The viewport

fn quad_pipeline(vp: Viewport) -> Pipeline<Fx16, NoCull, NoDepth, Unlit<Rgb888>> {
    let t = Transforms {
        model: Mat4::identity(),
        view: Mat4::identity(),
        projection: Mat4::identity(),
    };
    Pipeline::new(
        &t,
        vp,
        NoCull,
        NoDepth,
        Unlit {
            color: Rgb888::WHITE,
        },
    )
}

/// Draws a quad over most of normalised device space into a 64 x 48 framebuffer and returns the
/// lit pixels.
fn draw_quad(vp: Viewport) -> BTreeSet<(i32, i32)> {
    let h = Fx16::from_ratio(9, 10);
    let positions = [
        Vec3::new(-h, -h, Fx16::ZERO),
        Vec3::new(h, -h, Fx16::ZERO),
        Vec3::new(h, h, Fx16::ZERO),
        Vec3::new(-h, h, Fx16::ZERO),
    ];
    let triangles: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];
    let mut buf = vec![0u8; 64 * 48 * 3];
    let mut fb = Framebuffer::<Rgb888>::new(&mut buf, 64, 48).unwrap();
    quad_pipeline(vp)
        .draw(
            &mut fb,
            &Mesh::new(&positions, &triangles),
            &mut [VertexSlot::EMPTY; 4],
        )
        .unwrap();
    let lit: BTreeSet<(i32, i32)> = buf
        .chunks(3)
        .enumerate()
        .filter(|(_, px)| px.iter().any(|&c| c != 0))
        .map(|(i, _)| ((i % 64) as i32, (i / 64) as i32))
        .collect();
    lit
}

#[test]
fn viewport_at_the_integer_limits_draws_without_panicking() {
    // The clip rectangle of these viewports overflowed in embedded-graphics' intersection.
    let off_screen = Viewport {
        x: i32::MAX,
        y: i32::MAX,
        width: 32767,
        height: 32767,
    };
    assert!(draw_quad(off_screen).is_empty());
    let huge = draw_quad(Viewport::new(u32::MAX, u32::MAX));
    assert!(huge
        .iter()
        .all(|&(x, y)| (0..64).contains(&x) && (0..48).contains(&y)));
    // A viewport within the limits keeps its exact clip rectangle.
    let normal = Viewport {
        x: -10,
        y: 5,
        width: 50,
        height: 30,
    };
    assert_eq!(
        normal.rectangle(),
        Rectangle::new(Point::new(-10, 5), Size::new(50, 30))
    );
    let lit = draw_quad(normal);
    assert!(!lit.is_empty());
    assert!(lit
        .iter()
        .all(|&(x, y)| (0..40).contains(&x) && (5..35).contains(&y)));
}

proptest! {
    /// Any field values: `rectangle` does not panic, stays within the documented 32767 x 32767 and
    /// the `i32` plane, and is exact inside the limits.
    #[test]
    fn viewport_rectangle_any_fields(x in coord(), y in coord(), width in length(), height in length()) {
        let vp = Viewport { x, y, width, height };
        let r = vp.rectangle();
        prop_assert_eq!(r.top_left, Point::new(x, y));
        prop_assert!(r.size.width <= 32767 && r.size.height <= 32767);
        prop_assert!(i64::from(x) + i64::from(r.size.width) <= i64::from(i32::MAX) + 1);
        prop_assert!(i64::from(y) + i64::from(r.size.height) <= i64::from(i32::MAX) + 1);
        let fits = |o: i32, len: u32| len <= 32767 && i64::from(o) + i64::from(len) <= i64::from(i32::MAX) + 1;
        if fits(x, width) && fits(y, height) {
            prop_assert_eq!(r.size, Size::new(width, height));
        }
    }
}
