//! Polygon fill: ASCII patterns, an independent winding-number reference, agreement with the
//! triangle fill, and hard cases (degenerate, huge, outside the guard band, too many vertices).

use embedded_graphics_core::primitives::PointsIter;
use proptest::prelude::*;
use rasterizer_core::geom::GUARD_BAND_PIXELS;
use rasterizer_core::prelude::*;
use rasterizer_core::raster::polygon::{PolygonError, PolygonFillError};
use std::collections::BTreeSet;

const RULES: [FillRule; 2] = [FillRule::EvenOdd, FillRule::NonZero];

// ---------------------------------------------------------------------------------------------
// A strict mock target
// ---------------------------------------------------------------------------------------------

/// Counts writes per pixel; panics on a second write to a pixel, on a write outside its clip
/// rectangle and on an empty fill.
struct Strict {
    /// The bounding box (may be anywhere, not only at the origin).
    area: Rectangle,
    /// The clip area it reports when used as a `Surface` directly; `area` unless set.
    clip: Rectangle,
    counts: Vec<u8>,
}

impl Strict {
    fn new(width: u32, height: u32) -> Self {
        Self::with_area(Rectangle::new(Point::zero(), Size::new(width, height)))
    }

    fn with_area(area: Rectangle) -> Self {
        Self {
            area,
            clip: area,
            counts: vec![0; (area.size.width * area.size.height) as usize],
        }
    }

    fn write(&mut self, p: Point) {
        assert!(
            self.clip.contains(p) && self.area.contains(p),
            "write at {p:?} outside clip {:?} / area {:?}",
            self.clip,
            self.area
        );
        let d = p - self.area.top_left;
        let i = (d.y as u32 * self.area.size.width + d.x as u32) as usize;
        assert_eq!(self.counts[i], 0, "pixel {p:?} written twice");
        self.counts[i] = 1;
    }

    fn pixels(&self) -> BTreeSet<(i32, i32)> {
        self.area
            .points()
            .zip(&self.counts)
            .filter(|(_, &c)| c > 0)
            .map(|(p, _)| (p.x, p.y))
            .collect()
    }

    fn pattern(&self) -> Vec<String> {
        let w = self.area.size.width as usize;
        self.counts
            .chunks(w.max(1))
            .map(|row| row.iter().map(|&c| if c > 0 { '#' } else { ' ' }).collect())
            .collect()
    }

    #[track_caller]
    fn assert_pattern(&self, expected: &[&str]) {
        let w = self.area.size.width as usize;
        let want: Vec<String> = (0..self.area.size.height as usize)
            .map(|y| format!("{:<w$}", expected.get(y).copied().unwrap_or("")))
            .collect();
        let actual = self.pattern();
        assert!(
            actual == want,
            "pattern mismatch\nexpected:\n{}\nactual:\n{}",
            frame(&want),
            frame(&actual)
        );
    }
}

fn frame(rows: &[String]) -> String {
    rows.iter()
        .map(|r| format!("|{r}|"))
        .collect::<Vec<_>>()
        .join("\n")
}

impl Dimensions for Strict {
    fn bounding_box(&self) -> Rectangle {
        self.area
    }
}

impl DrawTarget for Strict {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, _) in pixels {
            self.write(p);
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, _: Rgb565) -> Result<(), Self::Error> {
        assert!(
            area.size.width >= 1 && area.size.height >= 1,
            "empty fill {area:?}"
        );
        for p in area.points() {
            self.write(p);
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        _: I,
    ) -> Result<(), Self::Error> {
        self.fill_solid(area, Rgb565::WHITE)
    }
}

/// Used directly (not through `AnyTarget`) when a test needs a clip area smaller than the target.
impl Surface for Strict {
    fn clip_area(&self) -> Rectangle {
        self.clip
    }
}

// ---------------------------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------------------------

/// Raw sub-pixel vertices.
fn raw<const B: u32>(v: &[(i32, i32)]) -> Vec<SubPoint<B>> {
    v.iter().map(|&(x, y)| SubPoint::raw(x, y)).collect()
}

/// Whole-pixel vertices in 28.4.
fn px(v: &[(i32, i32)]) -> Vec<SubPoint<4>> {
    v.iter()
        .map(|&(x, y)| SubPoint::new(x * 16, y * 16))
        .collect()
}

/// Fills into a strict mock through `AnyTarget`.
fn fill_mock<const N: usize, const B: u32>(
    area: Rectangle,
    v: &[SubPoint<B>],
    rule: FillRule,
) -> Strict {
    let mut mock = Strict::with_area(area);
    let polygon = Polygon::<N, B>::new(v).unwrap();
    polygon
        .fill(&mut AnyTarget::new(&mut mock), rule, Rgb565::WHITE)
        .unwrap();
    mock
}

/// Fills into a `Framebuffer<Rgb565>` and returns the lit pixels.
fn fill_framebuffer<const N: usize, const B: u32>(
    width: u32,
    height: u32,
    v: &[SubPoint<B>],
    rule: FillRule,
) -> BTreeSet<(i32, i32)> {
    let mut buf = vec![0u16; (width * height) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, width, height).unwrap();
    Polygon::<N, B>::new(v)
        .unwrap()
        .fill(&mut fb, rule, Rgb565::WHITE)
        .unwrap();
    let mut lit = BTreeSet::new();
    for y in 0..height as i32 {
        for x in 0..width as i32 {
            if fb.pixel(Point::new(x, y)) != Some(Rgb565::BLACK) {
                lit.insert((x, y));
            }
        }
    }
    lit
}

/// Fills with the mock and the framebuffer, checks they agree, and returns the mock.
fn fill_both<const N: usize, const B: u32>(
    width: u32,
    height: u32,
    v: &[SubPoint<B>],
    rule: FillRule,
) -> Strict {
    let area = Rectangle::new(Point::zero(), Size::new(width, height));
    let mock = fill_mock::<N, B>(area, v, rule);
    assert_eq!(
        mock.pixels(),
        fill_framebuffer::<N, B>(width, height, v, rule),
        "AnyTarget and Framebuffer disagree"
    );
    mock
}

/// Checks a pattern for both rules and both windings (they all agree for a simple polygon).
#[track_caller]
fn assert_simple_pattern(width: u32, height: u32, v: &[SubPoint<4>], expected: &[&str]) {
    let mut reversed = v.to_vec();
    reversed.reverse();
    for rule in RULES {
        fill_both::<16, 4>(width, height, v, rule).assert_pattern(expected);
        fill_both::<16, 4>(width, height, &reversed, rule).assert_pattern(expected);
    }
}

/// Upper end, lower end (doubled sub-pixel units), and +1 / -1 when the outline runs down / up.
type DirectedEdge = ((i128, i128), (i128, i128), i32);

/// The reference: for every pixel centre in `area`, the winding number of the outline, found
/// directly from each edge with an exact cross-product sign test in `i128` (no edge walking).
fn reference(v: &[(i64, i64)], bits: u32, rule: FillRule, area: Rectangle) -> BTreeSet<(i32, i32)> {
    let limit = i64::from(GUARD_BAND_PIXELS) << bits;
    let in_band = |&(x, y): &(i64, i64)| x.abs() <= limit && y.abs() <= limit;
    let mut lit = BTreeSet::new();
    if v.len() < 3 || !v.iter().all(in_band) {
        return lit;
    }
    let s = 1i128 << bits;
    // Doubled coordinates: the pixel centre is an integer even with no sub-pixel bits.
    let edges: Vec<DirectedEdge> = (0..v.len())
        .filter_map(|i| {
            let (a, b) = (v[i], v[(i + 1) % v.len()]);
            let a = (2 * i128::from(a.0), 2 * i128::from(a.1));
            let b = (2 * i128::from(b.0), 2 * i128::from(b.1));
            match a.1.cmp(&b.1) {
                std::cmp::Ordering::Less => Some((a, b, 1)),
                std::cmp::Ordering::Greater => Some((b, a, -1)),
                std::cmp::Ordering::Equal => None,
            }
        })
        .collect();
    for p in area.points() {
        let (cx, cy) = ((2 * i128::from(p.x) + 1) * s, (2 * i128::from(p.y) + 1) * s);
        let mut winding = 0;
        for &(t, b, dir) in &edges {
            if !(t.1 <= cy && cy < b.1) {
                continue;
            }
            // Edge direction (downward) cross (centre - top): <= 0 when the centre is on the edge
            // or to its right (y down).
            let cross = (b.0 - t.0) * (cy - t.1) - (b.1 - t.1) * (cx - t.0);
            if cross <= 0 {
                winding += dir;
            }
        }
        let inside = match rule {
            FillRule::EvenOdd => winding % 2 != 0,
            FillRule::NonZero => winding != 0,
        };
        if inside {
            lit.insert((p.x, p.y));
        }
    }
    lit
}

fn as_i64<const B: u32>(v: &[SubPoint<B>]) -> Vec<(i64, i64)> {
    v.iter().map(|p| (i64::from(p.x), i64::from(p.y))).collect()
}

fn cross(o: (i64, i64), a: (i64, i64), b: (i64, i64)) -> i128 {
    i128::from(a.0 - o.0) * i128::from(b.1 - o.1) - i128::from(a.1 - o.1) * i128::from(b.0 - o.0)
}

/// The strict convex hull of a point set (Andrew's monotone chain), collinear points dropped.
fn convex_hull(points: &[(i64, i64)]) -> Vec<(i64, i64)> {
    let mut p = points.to_vec();
    p.sort_unstable();
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut hull: Vec<(i64, i64)> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        for &q in &p {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
        if pass == 0 {
            p.reverse();
        }
    }
    hull
}

fn to_sub<const B: u32>(v: &[(i64, i64)]) -> Vec<SubPoint<B>> {
    v.iter()
        .map(|&(x, y)| SubPoint::raw(x as i32, y as i32))
        .collect()
}

/// Draws triangles into one strict mock (which panics on overdraw) and returns the lit pixels.
fn fill_triangles(area: Rectangle, triangles: &[[(i64, i64); 3]]) -> BTreeSet<(i32, i32)> {
    let mut mock = Strict::with_area(area);
    for t in triangles {
        let v = t.map(|(x, y)| SubPoint::new(x as i32, y as i32));
        fill_triangle(&mut AnyTarget::new(&mut mock), v, Rgb565::WHITE).unwrap();
    }
    mock.pixels()
}

// ---------------------------------------------------------------------------------------------
// Patterns
// ---------------------------------------------------------------------------------------------

#[test]
fn convex_diamond_pattern() {
    // Corners on pixel corners: the row at yc spans [4 - w, 4 + w), left edge in, right edge out.
    let v = px(&[(4, 0), (8, 4), (4, 8), (0, 4)]);
    assert_simple_pattern(
        8,
        8,
        &v,
        &[
            "   #    ", "  ###   ", " #####  ", "####### ", "####### ", " #####  ", "  ###   ",
            "   #    ",
        ],
    );
}

#[test]
fn concave_l_shape_pattern() {
    let v = px(&[(2, 2), (6, 2), (6, 10), (12, 10), (12, 14), (2, 14)]);
    let mut expected = vec!["", ""];
    expected.extend(std::iter::repeat_n("  ####", 8));
    expected.extend(std::iter::repeat_n("  ##########", 4));
    assert_simple_pattern(14, 16, &v, &expected);
}

#[test]
fn concave_arrowhead_pattern() {
    // A chevron pointing right with its notch at (3, 4).
    let v = px(&[(0, 0), (8, 4), (0, 8), (3, 4)]);
    assert_simple_pattern(
        9,
        8,
        &v,
        &[
            "#        ",
            " ##      ",
            "  ###    ",
            "   ####  ",
            "   ####  ",
            "  ###    ",
            " ##      ",
            "#        ",
        ],
    );
}

/// A regular pentagram (centre (12, 12), radius 11), drawn point to point (0, 2, 4, 1, 3).
const PENTAGRAM: [(i32, i32); 5] = [(192, 16), (295, 334), (25, 138), (359, 138), (89, 334)];

#[test]
fn pentagram_even_odd_has_hollow_centre() {
    let expected = [
        "",
        "",
        "",
        "           ##",
        "           ##",
        "           ##",
        "          ####",
        "          ####",
        "          ####",
        "   ######      ######",
        "    #####      #####",
        "      ###      ###",
        "       #        #",
        "",
        "        ##    ##",
        "       ####  ####",
        "       ##########",
        "       ###    ###",
        "      ###      ###",
        "      #          #",
    ];
    let v = raw::<4>(&PENTAGRAM);
    fill_both::<5, 4>(24, 23, &v, FillRule::EvenOdd).assert_pattern(&expected);
    let mut reversed = v.clone();
    reversed.reverse();
    fill_both::<5, 4>(24, 23, &reversed, FillRule::EvenOdd).assert_pattern(&expected);
}

#[test]
fn pentagram_non_zero_is_solid() {
    let expected = [
        "",
        "",
        "",
        "           ##",
        "           ##",
        "           ##",
        "          ####",
        "          ####",
        "          ####",
        "   ##################",
        "    ################",
        "      ############",
        "       ##########",
        "        ########",
        "        ########",
        "       ##########",
        "       ##########",
        "       ###    ###",
        "      ###      ###",
        "      #          #",
    ];
    let v = raw::<4>(&PENTAGRAM);
    fill_both::<5, 4>(24, 23, &v, FillRule::NonZero).assert_pattern(&expected);
    let mut reversed = v.clone();
    reversed.reverse();
    fill_both::<5, 4>(24, 23, &reversed, FillRule::NonZero).assert_pattern(&expected);
}

#[test]
fn horizontal_edges_on_pixel_centres() {
    // A rectangle whose edges all pass through pixel centres: the top and left rows/columns are
    // in, the bottom and right ones out.
    let half = |v: &[(i32, i32)]| -> Vec<SubPoint<4>> {
        v.iter()
            .map(|&(x, y)| SubPoint::new(x * 8, y * 8))
            .collect()
    };
    let rect = half(&[(3, 3), (13, 3), (13, 11), (3, 11)]);
    assert_simple_pattern(9, 7, &rect, &["", " #####", " #####", " #####", " #####"]);
    // A house: a roof meeting walls at the centre row 3.5, a floor on the centre row 6.5.
    let house = half(&[(3, 7), (9, 1), (15, 7), (15, 13), (3, 13)]);
    assert_simple_pattern(
        9,
        7,
        &house,
        &["", "   ##", "  ####", " ######", " ######", " ######"],
    );
}

#[test]
fn both_windings_and_start_vertices_agree() {
    let v = px(&[(1, 1), (9, 2), (6, 5), (10, 9), (2, 8), (4, 5)]);
    let base = fill_both::<8, 4>(12, 11, &v, FillRule::NonZero).pixels();
    assert!(!base.is_empty());
    for start in 0..v.len() {
        let mut rotated = v.clone();
        rotated.rotate_left(start);
        let mut reversed = rotated.clone();
        reversed.reverse();
        for rule in RULES {
            assert_eq!(fill_both::<8, 4>(12, 11, &rotated, rule).pixels(), base);
            assert_eq!(fill_both::<8, 4>(12, 11, &reversed, rule).pixels(), base);
        }
    }
}

#[test]
fn adjacent_polygons_share_an_edge_exactly() {
    // A quad cut by a slanted line into two quads: drawn on one strict target (no overdraw) they
    // light exactly their union (the cut points are not quite on the quad's edges, so the union is
    // a hexagon).
    let a = [(3, 5), (90, 9), (70, 120), (10, 100)];
    let cut = [(47, 7), (40, 110)];
    let left = raw::<4>(&[a[0], cut[0], cut[1], a[3]]);
    let right = raw::<4>(&[cut[0], a[1], a[2], cut[1]]);
    let area = Rectangle::new(Point::zero(), Size::new(8, 9));
    let mut mock = Strict::with_area(area);
    for part in [&left, &right] {
        Polygon::<4>::new(part)
            .unwrap()
            .fill(
                &mut AnyTarget::new(&mut mock),
                FillRule::NonZero,
                Rgb565::RED,
            )
            .unwrap();
    }
    let union = [a[0], cut[0], a[1], a[2], cut[1], a[3]];
    let whole = fill_mock::<6, 4>(area, &raw::<4>(&union), FillRule::NonZero);
    assert!(whole.pixels().len() > 30);
    assert_eq!(mock.pixels(), whole.pixels());
}

#[test]
fn clip_area_smaller_than_target() {
    let v = px(&[(-3, -2), (20, 1), (14, 18), (1, 13)]);
    let full = fill_mock::<4, 4>(
        Rectangle::new(Point::zero(), Size::new(16, 16)),
        &v,
        FillRule::EvenOdd,
    )
    .pixels();
    let clip = Rectangle::new(Point::new(3, 4), Size::new(7, 5));
    let mut mock = Strict::new(16, 16);
    mock.clip = clip;
    Polygon::<4>::new(&v)
        .unwrap()
        .fill(&mut mock, FillRule::EvenOdd, Rgb565::RED)
        .unwrap();
    let want: BTreeSet<_> = full
        .into_iter()
        .filter(|&(x, y)| clip.contains(Point::new(x, y)))
        .collect();
    assert_eq!(mock.pixels(), want);
}

#[test]
fn fill_polygon_builds_and_fills() {
    let v = px(&[(1, 1), (7, 1), (7, 5), (1, 5)]);
    let mut mock = Strict::new(8, 8);
    fill_polygon::<_, 4, _>(
        &mut AnyTarget::new(&mut mock),
        &v,
        FillRule::NonZero,
        Rgb565::RED,
    )
    .unwrap();
    assert_eq!(mock.pixels().len(), 24);
    let err = fill_polygon::<_, 3, _>(
        &mut AnyTarget::new(&mut mock),
        &v,
        FillRule::NonZero,
        Rgb565::RED,
    );
    let expected = PolygonError::TooManyVertices {
        capacity: 3,
        given: 4,
    };
    assert_eq!(err, Err(PolygonFillError::Polygon(expected)));
    assert_eq!(
        expected.to_string(),
        "polygon has 4 vertices, more than its capacity of 3"
    );
}

/// A target that fails on its third span.
struct Failing {
    spans: usize,
}

impl Dimensions for Failing {
    fn bounding_box(&self) -> Rectangle {
        Rectangle::new(Point::zero(), Size::new(16, 16))
    }
}

impl DrawTarget for Failing {
    type Color = Rgb565;
    type Error = &'static str;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        _: I,
    ) -> Result<(), Self::Error> {
        Err("draw_iter not expected")
    }

    fn fill_solid(&mut self, _: &Rectangle, _: Rgb565) -> Result<(), Self::Error> {
        self.spans += 1;
        if self.spans == 3 {
            Err("bus error")
        } else {
            Ok(())
        }
    }
}

#[test]
fn target_error_stops_the_fill() {
    let mut target = Failing { spans: 0 };
    let v = px(&[(1, 1), (7, 1), (7, 9), (1, 9)]);
    let result = Polygon::<4>::new(&v).unwrap().fill(
        &mut AnyTarget::new(&mut target),
        FillRule::EvenOdd,
        Rgb565::RED,
    );
    assert_eq!(result, Err("bus error"));
    assert_eq!(target.spans, 3);
    let mut target = Failing { spans: 0 };
    let result = fill_polygon::<_, 4, _>(
        &mut AnyTarget::new(&mut target),
        &v,
        FillRule::EvenOdd,
        Rgb565::RED,
    );
    assert_eq!(result, Err(PolygonFillError::Target("bus error")));
}

// ---------------------------------------------------------------------------------------------
// Hard cases
// ---------------------------------------------------------------------------------------------

#[test]
fn polygon_all_vertices_collinear_draws_nothing() {
    let cases: [&[(i32, i32)]; 4] = [
        &[(0, 0), (40, 24), (80, 48), (20, 12)],
        &[(16, 8), (16, 100), (16, 50)],
        &[(0, 40), (100, 40), (50, 40)],
        &[(-300, -100), (700, 233), (2000, 666), (-300, -100)],
    ];
    for v in cases {
        for rule in RULES {
            let mock = fill_both::<4, 4>(16, 16, &raw::<4>(v), rule);
            assert!(mock.pixels().is_empty(), "{v:?} {rule:?}");
        }
    }
}

#[test]
fn polygon_repeated_vertices() {
    let square = [(16, 16), (96, 16), (96, 80), (16, 80)];
    let base = fill_both::<4, 4>(8, 8, &raw::<4>(&square), FillRule::NonZero).pixels();
    assert_eq!(base.len(), 20);
    // Each vertex twice, and the first vertex repeated at the end.
    let doubled: Vec<_> = square.iter().flat_map(|&p| [p, p]).collect();
    let closed: Vec<_> = square.iter().chain(&square[..1]).copied().collect();
    for v in [&doubled[..], &closed[..]] {
        for rule in RULES {
            assert_eq!(fill_both::<8, 4>(8, 8, &raw::<4>(v), rule).pixels(), base);
        }
    }
    // Every vertex the same point, and a polygon that runs out and back along itself.
    let point = [(40, 40); 6];
    let there_and_back = [(16, 16), (96, 80), (16, 16), (96, 80)];
    for v in [&point[..], &there_and_back[..]] {
        for rule in RULES {
            assert!(fill_both::<8, 4>(8, 8, &raw::<4>(v), rule)
                .pixels()
                .is_empty());
        }
    }
    // Fewer than three vertices.
    for v in [&[][..], &[(3, 3)][..], &[(0, 0), (100, 100)][..]] {
        assert!(fill_both::<8, 4>(8, 8, &raw::<4>(v), FillRule::NonZero)
            .pixels()
            .is_empty());
    }
}

#[test]
fn polygon_far_larger_than_screen() {
    let g = GUARD_BAND_PIXELS << 4;
    // Covers the whole screen: every pixel exactly once.
    let huge = raw::<4>(&[(-g, -g), (g, -g + 7), (g - 3, g), (-g, g)]);
    for rule in RULES {
        let mock = fill_both::<4, 4>(20, 12, &huge, rule);
        assert_eq!(mock.pixels().len(), 20 * 12);
    }
    // Long edges across the screen, and a notch the screen sits in: against the reference.
    let screen = Rectangle::new(Point::new(-5, -3), Size::new(20, 12));
    let shapes: [&[(i32, i32)]; 3] = [
        &[(-g, -g), (g, 3 * 16 + 5), (-g, g)],
        &[(-g, -g), (g, -g), (3 * 16, 16), (g, g), (-g, g)],
        &[
            (-g, 0),
            (0, -g),
            (g, g - 1),
            (5 * 16 + 3, -g + 9),
            (-g / 2, g),
        ],
    ];
    for v in shapes {
        for rule in RULES {
            let mock = fill_mock::<5, 4>(screen, &raw::<4>(v), rule);
            assert_eq!(
                mock.pixels(),
                reference(&as_i64(&raw::<4>(v)), 4, rule, screen)
            );
        }
    }
}

#[test]
fn polygon_too_many_vertices_is_error() {
    let v = px(&[(0, 0), (4, 0), (4, 4), (0, 4)]);
    assert_eq!(
        Polygon::<3>::new(&v).unwrap_err(),
        PolygonError::TooManyVertices {
            capacity: 3,
            given: 4
        }
    );
    assert!(Polygon::<4>::new(&v).is_ok());
    assert_eq!(
        Polygon::<0>::new(&v[..1]).unwrap_err(),
        PolygonError::TooManyVertices {
            capacity: 0,
            given: 1
        }
    );
    assert!(Polygon::<0>::new(&[]).is_ok());
}

#[test]
fn polygon_outside_guard_band_draws_nothing() {
    let g = GUARD_BAND_PIXELS;
    // One vertex one sub-pixel step outside the band: nothing, although the polygon covers the
    // screen.
    let limit = g << 4;
    let outside = raw::<4>(&[(-limit, -limit), (limit + 1, 0), (0, limit)]);
    for rule in RULES {
        assert!(fill_both::<3, 4>(16, 16, &outside, rule)
            .pixels()
            .is_empty());
    }
    // Exactly on the band's edge is still drawn.
    let on_edge = raw::<4>(&[(-limit, -limit), (limit, 0), (0, limit)]);
    assert!(!fill_both::<3, 4>(16, 16, &on_edge, FillRule::NonZero)
        .pixels()
        .is_empty());
    // Far outside, in every direction, at the extremes of i32.
    for far in [
        (i32::MAX, 0),
        (0, i32::MIN),
        (i32::MIN, i32::MIN),
        (g * 16 + 16, 5),
    ] {
        let v = raw::<4>(&[(0, 0), (160, 0), far, (0, 160)]);
        for rule in RULES {
            assert!(fill_both::<4, 4>(16, 16, &v, rule).pixels().is_empty());
        }
    }
    // With no sub-pixel bits the band is in raw units directly.
    let v = raw::<0>(&[(0, 0), (g + 1, 0), (0, 10)]);
    assert!(fill_both::<3, 0>(16, 16, &v, FillRule::NonZero)
        .pixels()
        .is_empty());
}

// ---------------------------------------------------------------------------------------------
// Properties
// ---------------------------------------------------------------------------------------------

/// Vertices in raw units in `lo..hi` for both axes.
fn vertices(lo: i32, hi: i32, max: usize) -> impl Strategy<Value = Vec<(i32, i32)>> {
    prop::collection::vec((lo..hi, lo..hi), 0..=max)
}

/// A target rectangle somewhere around the origin.
fn area() -> impl Strategy<Value = Rectangle> {
    (-12i32..12, -12i32..12, 1u32..40, 1u32..32)
        .prop_map(|(x, y, w, h)| Rectangle::new(Point::new(x, y), Size::new(w, h)))
}

/// Extreme coordinates: small, near the guard band, and anywhere in `i32`.
fn extreme() -> impl Strategy<Value = i32> {
    let g = GUARD_BAND_PIXELS;
    prop_oneof![
        8 => -800i32..800,
        1 => (g - 40)..=(g + 40),
        1 => -(g + 40)..=-(g - 40),
        1 => (g * 16 - 40)..=(g * 16 + 40),
        1 => -(g * 16 + 40)..=-(g * 16 - 40),
        1 => Just(i32::MIN),
        1 => Just(i32::MAX),
        1 => any::<i32>(),
    ]
}

/// 28.4 coordinates inside the guard band, often near its edge.
fn in_band_4() -> impl Strategy<Value = i32> {
    let limit = GUARD_BAND_PIXELS << 4;
    prop_oneof![
        3 => -64 * 16..64 * 16,
        2 => -limit..=limit,
        1 => Just(limit),
        1 => Just(-limit),
        1 => (limit - 64)..=limit,
    ]
}

/// The top-left corner of a target: usually near the origin, sometimes at the ends of `i32`.
fn corner() -> impl Strategy<Value = i32> {
    prop_oneof![
        6 => -40i32..40,
        1 => Just(i32::MIN),
        1 => Just(i32::MAX - 40),
        1 => any::<i32>(),
    ]
}

fn check_reference<const B: u32>(v: &[(i32, i32)], area: Rectangle) -> Result<(), TestCaseError> {
    let sub = raw::<B>(v);
    for rule in RULES {
        let mock = fill_mock::<16, B>(area, &sub, rule);
        prop_assert_eq!(
            mock.pixels(),
            reference(&as_i64(&sub), B, rule, area),
            "{:?}",
            rule
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn matches_reference_4_bits(v in vertices(-20 * 16, 56 * 16, 16), area in area()) {
        check_reference::<4>(&v, area)?;
    }

    #[test]
    fn matches_reference_0_bits(v in vertices(-20, 56, 16), area in area()) {
        check_reference::<0>(&v, area)?;
    }

    #[test]
    fn matches_reference_8_bits(v in vertices(-20 * 256, 56 * 256, 16), area in area()) {
        check_reference::<8>(&v, area)?;
    }

    /// Coarse coordinates: many vertices share rows, columns and pixel centres.
    #[test]
    fn matches_reference_on_pixel_centre_grid(v in vertices(-2, 20, 16), area in area()) {
        let v: Vec<_> = v.into_iter().map(|(x, y)| (x * 8, y * 8)).collect();
        check_reference::<4>(&v, area)?;
    }

    #[test]
    fn framebuffer_matches_any_target(v in vertices(-10 * 16, 50 * 16, 12)) {
        let sub = raw::<4>(&v);
        for rule in RULES {
            fill_both::<12, 4>(40, 30, &sub, rule);
        }
    }

    #[test]
    fn convex_polygon_equals_fan_triangulation(
        points in prop::collection::vec((-8 * 16..48 * 16i64, -8 * 16..40 * 16i64), 3..24),
        area in area(),
    ) {
        let hull = convex_hull(&points);
        prop_assume!(hull.len() >= 3);
        let triangles: Vec<_> =
            (1..hull.len() - 1).map(|i| [hull[0], hull[i], hull[i + 1]]).collect();
        let want = fill_triangles(area, &triangles);
        let mut v = to_sub::<4>(&hull);
        for rule in RULES {
            prop_assert_eq!(&fill_mock::<24, 4>(area, &v, rule).pixels(), &want);
        }
        v.reverse();
        prop_assert_eq!(&fill_mock::<24, 4>(area, &v, FillRule::NonZero).pixels(), &want);
    }

    /// A random star-shaped (so simple) polygon, cut into the fan of triangles around its centre.
    #[test]
    fn simple_polygon_equals_its_triangles(
        centre in (0i64..32 * 16, 0i64..24 * 16),
        offsets in prop::collection::vec((-20 * 16..20 * 16i64, -20 * 16..20 * 16i64), 3..16),
        area in area(),
    ) {
        let mut rays: Vec<(i64, i64)> = offsets.into_iter().filter(|&o| o != (0, 0)).collect();
        // Sort by angle, integer only: upper half-plane first, then by cross product.
        let half = |(x, y): (i64, i64)| y < 0 || (y == 0 && x < 0);
        rays.sort_by(|&a, &b| {
            half(a).cmp(&half(b)).then_with(|| 0.cmp(&cross((0, 0), a, b)))
        });
        let n = rays.len();
        prop_assume!(n >= 3);
        // Every turn around the centre strictly less than half a turn: a star around `centre`.
        prop_assume!((0..n).all(|i| cross((0, 0), rays[i], rays[(i + 1) % n]) > 0));
        let v: Vec<(i64, i64)> = rays.iter().map(|&(x, y)| (centre.0 + x, centre.1 + y)).collect();
        let triangles: Vec<_> = (0..n).map(|i| [centre, v[i], v[(i + 1) % n]]).collect();
        let want = fill_triangles(area, &triangles);
        for rule in RULES {
            prop_assert_eq!(&fill_mock::<16, 4>(area, &to_sub::<4>(&v), rule).pixels(), &want);
        }
    }

    /// A convex polygon cut along a chord: the two halves share the chord, and together light
    /// exactly the whole, each pixel once.
    #[test]
    fn polygons_sharing_an_edge_partition(
        points in prop::collection::vec((-8 * 16..48 * 16i64, -8 * 16..40 * 16i64), 4..20),
        cut in 2usize..20,
        area in area(),
    ) {
        let hull = convex_hull(&points);
        prop_assume!(hull.len() >= 4);
        let k = 2 + cut % (hull.len() - 3);
        let a = to_sub::<4>(&hull[..=k]);
        let b = to_sub::<4>(&[&hull[k..], &hull[..1]].concat());
        let mut mock = Strict::with_area(area);
        for part in [&a, &b] {
            Polygon::<20>::new(part)
                .unwrap()
                .fill(&mut AnyTarget::new(&mut mock), FillRule::EvenOdd, Rgb565::RED)
                .unwrap();
        }
        let whole = fill_mock::<20, 4>(area, &to_sub::<4>(&hull), FillRule::EvenOdd);
        prop_assert_eq!(mock.pixels(), whole.pixels());
    }

    #[test]
    fn whole_pixel_translation_translates_pixels(
        v in vertices(0, 24 * 16, 12),
        dx in -8i32..24,
        dy in -8i32..24,
    ) {
        let area = Rectangle::new(Point::new(-8, -8), Size::new(56, 56));
        let moved: Vec<_> = v.iter().map(|&(x, y)| (x + dx * 16, y + dy * 16)).collect();
        for rule in RULES {
            let before = fill_mock::<12, 4>(area, &raw::<4>(&v), rule).pixels();
            let after = fill_mock::<12, 4>(area, &raw::<4>(&moved), rule).pixels();
            let shifted: BTreeSet<_> = before.iter().map(|&(x, y)| (x + dx, y + dy)).collect();
            prop_assert_eq!(after, shifted);
        }
    }

    /// Any `i32` input: no panic, no write outside the target, no overdraw (the mock checks), and
    /// exactly the reference's pixels (none when a vertex is outside the guard band).
    #[test]
    fn extreme_coordinates_are_safe_and_exact(
        v in prop::collection::vec((extreme(), extreme()), 0..10),
        x in corner(),
        y in corner(),
        w in 1u32..40,
        h in 1u32..40,
    ) {
        // Keep the target's own pixels representable.
        let x = x.min(i32::MAX - w as i32);
        let y = y.min(i32::MAX - h as i32);
        let area = Rectangle::new(Point::new(x, y), Size::new(w, h));
        for rule in RULES {
            let b4 = raw::<4>(&v);
            let want = reference(&as_i64(&b4), 4, rule, area);
            prop_assert_eq!(fill_mock::<10, 4>(area, &b4, rule).pixels(), want);
            let b0 = raw::<0>(&v);
            let want = reference(&as_i64(&b0), 0, rule, area);
            prop_assert_eq!(fill_mock::<10, 0>(area, &b0, rule).pixels(), want);
            let b8 = raw::<8>(&v);
            let want = reference(&as_i64(&b8), 8, rule, area);
            prop_assert_eq!(fill_mock::<10, 8>(area, &b8, rule).pixels(), want);
        }
    }

    /// Huge polygons inside the guard band, mixed with small vertices so that long edges cross the
    /// target: exactly the reference's pixels.
    #[test]
    fn huge_polygons_inside_the_guard_band_match_reference(
        v in prop::collection::vec((in_band_4(), in_band_4()), 3..10),
        area in area(),
    ) {
        let sub = raw::<4>(&v);
        for rule in RULES {
            let want = reference(&as_i64(&sub), 4, rule, area);
            prop_assert_eq!(fill_mock::<10, 4>(area, &sub, rule).pixels(), want);
        }
    }

    #[test]
    fn too_many_vertices_is_typed_error(v in vertices(-100, 100, 20)) {
        let result = Polygon::<8>::new(&raw::<4>(&v));
        if v.len() > 8 {
            let want = PolygonError::TooManyVertices { capacity: 8, given: v.len() };
            prop_assert_eq!(result.unwrap_err(), want);
        } else {
            prop_assert!(result.is_ok());
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Every sub-pixel setting, over the whole guard band
// ---------------------------------------------------------------------------------------------

/// A coordinate drawn without knowing the sub-pixel bits: near the targets of `area()`, anywhere
/// in the guard band, at or next to its limits, or beyond them.
#[derive(Debug, Clone, Copy)]
enum Place {
    /// Raw 1/256-pixel units.
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
            Place::Limit { negative, inset } => (limit - inset) * if negative { -1 } else { 1 },
            Place::Beyond(k) => [limit + 1, -limit - 1, i32::MAX, i32::MIN][usize::from(k % 4)],
        }
    }
}

fn place() -> impl Strategy<Value = Place> {
    prop_oneof![
        5 => (-16 * 256..56 * 256).prop_map(Place::Screen),
        3 => any::<u32>().prop_map(Place::Band),
        2 => (any::<bool>(), prop_oneof![Just(0), Just(1), 0..300])
            .prop_map(|(negative, inset)| Place::Limit { negative, inset }),
        1 => any::<u8>().prop_map(Place::Beyond),
    ]
}

fn check_reference_at(
    bits: u32,
    v: &[(Place, Place)],
    area: Rectangle,
) -> Result<(), TestCaseError> {
    let v: Vec<(i32, i32)> = v.iter().map(|(x, y)| (x.raw(bits), y.raw(bits))).collect();
    match bits {
        0 => check_reference::<0>(&v, area),
        1 => check_reference::<1>(&v, area),
        2 => check_reference::<2>(&v, area),
        3 => check_reference::<3>(&v, area),
        4 => check_reference::<4>(&v, area),
        5 => check_reference::<5>(&v, area),
        6 => check_reference::<6>(&v, area),
        7 => check_reference::<7>(&v, area),
        _ => check_reference::<8>(&v, area),
    }
}

#[test]
fn polygon_at_the_guard_band_corners_every_bits() {
    let limit = |negative| Place::Limit { negative, inset: 0 };
    let (lo, hi) = (limit(true), limit(false));
    // The band's square, a bow tie across it, and a sliver from a corner to the target.
    let shapes: [&[(Place, Place)]; 3] = [
        &[(lo, lo), (hi, lo), (hi, hi), (lo, hi)],
        &[(lo, lo), (hi, hi), (hi, lo), (lo, hi)],
        &[
            (lo, lo),
            (Place::Screen(5 * 256), Place::Screen(3 * 256)),
            (Place::Screen(9 * 256), Place::Screen(3 * 256)),
        ],
    ];
    let area = Rectangle::new(Point::new(-3, -2), Size::new(20, 12));
    for bits in 0..=8 {
        for v in shapes {
            check_reference_at(bits, v, area).unwrap();
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// Both rules at every sub-pixel setting 0..=8, vertices anywhere in the guard band, at its
    /// exact limits and beyond: exactly the reference's pixels (none with a vertex outside).
    #[test]
    fn matches_reference_across_the_guard_band_at_every_bits(
        bits in 0u32..=8,
        v in prop::collection::vec((place(), place()), 0..10),
        area in area(),
    ) {
        check_reference_at(bits, &v, area)?;
    }
}
