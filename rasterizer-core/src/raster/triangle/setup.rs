//! Triangle set-up shared by the flat and Gouraud fills: sort by y, reject what cannot be drawn,
//! and walk the spans row by row.

use crate::geom::{PixelRect, SubPoint};
use crate::raster::edge::{row_at_or_below, DdaWalk, EdgeWalk};

/// A triangle sorted by y (top first), in `i64` sub-pixel units.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sorted {
    pub v: [(i64, i64); 3],
    /// The permutation: `v[i]` is the caller's vertex `order[i]`.
    pub order: [usize; 3],
    /// Twice the signed area of the sorted triangle, `(x1-x0)(y2-y0) - (x2-x0)(y1-y0)`. Negative when
    /// the middle vertex lies left of the long edge. Never zero.
    pub cross: i64,
}

impl Sorted {
    /// Sorts and checks a triangle; `None` for a zero-area triangle or a vertex outside the guard band.
    #[inline(always)]
    pub fn new<const BITS: u32>(v: &[SubPoint<BITS>; 3]) -> Option<Self> {
        #[allow(clippy::let_unit_value)]
        let () = SubPoint::<BITS>::VALID;
        if !v.iter().all(|p| p.in_guard_band()) {
            return None;
        }
        let order = row_order(v);
        let p = order.map(|i| (i64::from(v[i].x), i64::from(v[i].y)));
        // Bound: |each product| <= (2M)^2 = 2^60 inside the guard band.
        let cross = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
        (cross != 0).then_some(Self { v: p, order, cross })
    }
}

/// The order of a triangle's vertices top to bottom, left to right in a row: `(y, x)` in one
/// integer each (y above, x moved up by 2^31 below, in `0 .. 2^32`), so that integer order is the
/// pair's order and each comparison is one. Every set-up sorts this way, so that all see the
/// same edges. Any `i32` coordinates: x is moved up before it is added, so no sum leaves `i64`.
#[inline(always)]
pub(crate) fn row_order<const BITS: u32>(v: &[SubPoint<BITS>; 3]) -> [usize; 3] {
    let keys = [0, 1, 2].map(|i| (i64::from(v[i].y) << 32) + (i64::from(v[i].x) + (1 << 31)));
    let mut order = [0usize, 1, 2];
    if keys[order[1]] < keys[order[0]] {
        order.swap(0, 1);
    }
    if keys[order[2]] < keys[order[1]] {
        order.swap(1, 2);
        if keys[order[1]] < keys[order[0]] {
            order.swap(0, 1);
        }
    }
    order
}

/// How many pixel centres `k s + s/2` lie within `lo ..= hi` (sub-pixel units, `s` the unit):
/// zero or less when none does. Exact at 0 sub-pixel bits too, where [`centres`] (which
/// compares whole units) reaches one more, conservatively.
#[inline(always)]
pub(crate) fn centre_count(lo: i64, hi: i64, s: i64) -> i64 {
    // The last is `floor((2 hi - s) / 2 s)`, the first `floor((2 lo - s - 1) / 2 s) + 1`.
    let shift = (2 * s).trailing_zeros();
    ((2 * hi - s) >> shift) - ((2 * lo - s - 1) >> shift)
}

/// The pixels whose centres `c s + s / 2` lie within `lo ..= hi` (sub-pixel units), inside
/// `clip_lo .. clip_hi`: the columns (or rows) of centres a triangle's bounds reach.
#[inline(always)]
fn centres(lo: i64, hi: i64, s: i64, clip_lo: i64, clip_hi: i64) -> core::ops::Range<i64> {
    row_at_or_below(lo, s).max(clip_lo)..row_at_or_below(hi + 1, s).min(clip_hi)
}

/// Receives the spans of a triangle.
pub(crate) trait SpanSink {
    /// The target's error.
    type Error;
    /// Draws columns `x0 .. x1` (`x0 < x1`, inside the clip area) of `row`.
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), Self::Error>;
}

/// The pixel rows a triangle's spans run over inside `clip`: `top..bottom`, the lower half from
/// `mid` (v1's row, kept within them); `None` when there is none.
#[inline(always)]
pub(crate) fn rows_in_clip(t: &Sorted, s: i64, clip: &PixelRect) -> Option<(i64, i64, i64)> {
    let [v0, v1, v2] = t.v;
    let top = row_at_or_below(v0.1, s).max(clip.y0);
    let mid = row_at_or_below(v1.1, s).clamp(top, clip.y1.max(top));
    let bottom = row_at_or_below(v2.1, s).min(clip.y1);
    (top < bottom).then_some((top, mid, bottom))
}

/// Hands `sink` every non-empty span of the triangle inside `clip`, top to bottom.
///
/// Rows run over `y0 <= yc < y2`; in each, columns run from the left edge's column (inclusive: a centre
/// on a left edge is inside) to the right edge's column (exclusive): the top-left rule.
#[inline(always)]
pub(crate) fn walk_spans<K: SpanSink>(
    t: &Sorted,
    s: i64,
    clip: &PixelRect,
    sink: &mut K,
) -> Result<(), K::Error> {
    let [v0, v1, v2] = t.v;
    let Some((top, mid, bottom)) = rows_in_clip(t, s, clip) else {
        return Ok(());
    };
    // Columns need clamping only when the triangle's x extent leaves the clip area: a non-empty
    // span's ends lie between the leftmost and rightmost vertex.
    let (xmin, xmax) = (v0.0.min(v1.0).min(v2.0), v0.0.max(v1.0).max(v2.0));
    let inside_x = xmin >= clip.x0 * s && xmax <= clip.x1 * s;
    let mut long = EdgeWalk::new(v0, v2, s, top);
    let short_is_left = t.cross < 0;
    if top < mid {
        let upper = EdgeWalk::new(v0, v1, s, top);
        // The walks are copied into left and right before the loop and the long one copied back
        // after it: references chosen at run time made the loop select both edges every row,
        // and a loop per side doubled the code of every fill.
        let (mut l, mut r) = if short_is_left {
            (upper, long)
        } else {
            (long, upper)
        };
        rows_of(&mut l, &mut r, top..mid.min(bottom), clip, inside_x, sink)?;
        long = if short_is_left { r } else { l };
    }
    if mid < bottom {
        let lower = EdgeWalk::new(v1, v2, s, mid);
        let (mut l, mut r) = if short_is_left {
            (lower, long)
        } else {
            (long, lower)
        };
        rows_of(&mut l, &mut r, mid..bottom, clip, inside_x, sink)?;
    }
    Ok(())
}

/// The fewest rows of a triangle that [`tall_walks`] takes for [`DdaWalk`]s: their set-up costs
/// two 64-bit divisions an edge more than [`EdgeWalk`]'s (tens of cycles each on a Cortex-M),
/// and saves a test and a conditional subtract an edge on every row.
const DDA_MIN_ROWS: i64 = 32;

/// The walks of a tall triangle's edges for [`walk_tall`]: the rows inside `clip` (as
/// [`rows_in_clip`]) and [`DdaWalk`]s for the long, upper and lower edges, when it has at least
/// [`DDA_MIN_ROWS`] rows, lies within the clip area's columns and every edge fits their bound;
/// `None` leaves it to [`walk_spans`].
#[inline(always)]
pub(crate) fn tall_walks(t: &Sorted, s: i64, clip: &PixelRect) -> Option<TallWalks> {
    let [v0, v1, v2] = t.v;
    let rows @ (top, mid, bottom) = rows_in_clip(t, s, clip)?;
    // Inside the clip area's columns its spans need no clamping (see `walk_spans`): one copy of
    // the row loop fewer, for the rare tall triangle that crosses the clip area's sides.
    let (xmin, xmax) = (v0.0.min(v1.0).min(v2.0), v0.0.max(v1.0).max(v2.0));
    if bottom - top < DDA_MIN_ROWS || xmin < clip.x0 * s || xmax > clip.x1 * s {
        return None;
    }
    let long = DdaWalk::new(v0, v2, s, top, bottom - top)?;
    // An edge with no rows to walk is never read: the long one stands in for it.
    let upper = match mid > top {
        true => DdaWalk::new(v0, v1, s, top, mid - top)?,
        false => long,
    };
    let lower = match bottom > mid {
        true => DdaWalk::new(v1, v2, s, mid, bottom - mid)?,
        false => long,
    };
    Some(TallWalks {
        rows,
        walks: [long, upper, lower],
    })
}

/// A tall triangle's rows and edge walks ([`tall_walks`]).
pub(crate) struct TallWalks {
    rows: (i64, i64, i64),
    walks: [DdaWalk; 3],
}

/// [`walk_spans`] for a triangle [`tall_walks`] took: the same spans, one add an edge a row. A
/// second copy of the row loop, so only for sinks whose spans are small code.
#[inline(always)]
pub(crate) fn walk_tall<K: SpanSink>(
    t: &Sorted,
    tall: TallWalks,
    sink: &mut K,
) -> Result<(), K::Error> {
    let (top, mid, bottom) = tall.rows;
    let [mut long, upper, lower] = tall.walks;
    let short_is_left = t.cross < 0;
    // As in `walk_spans`, with no clamping: `tall_walks` took the triangle inside the columns.
    if top < mid {
        let (mut l, mut r) = if short_is_left {
            (upper, long)
        } else {
            (long, upper)
        };
        rows_inside(&mut l, &mut r, top..mid.min(bottom), sink)?;
        long = if short_is_left { r } else { l };
    }
    if mid < bottom {
        let (mut l, mut r) = if short_is_left {
            (lower, long)
        } else {
            (long, lower)
        };
        rows_inside(&mut l, &mut r, mid..bottom, sink)?;
    }
    Ok(())
}

/// The spans of `rows` between two walks of a triangle inside the clip area's columns.
#[cfg_attr(debug_assertions, inline(never))]
#[cfg_attr(not(debug_assertions), inline(always))]
fn rows_inside<K: SpanSink>(
    left: &mut DdaWalk,
    right: &mut DdaWalk,
    rows: core::ops::Range<i64>,
    sink: &mut K,
) -> Result<(), K::Error> {
    for row in rows {
        if left.col() < right.col() {
            sink.span(row as i32, left.col() as i32, right.col() as i32)?;
        }
        left.step();
        right.step();
    }
    Ok(())
}

/// [`walk_spans`] with one copy of the row loop for both halves of the triangle, clipped or
/// not: the same spans, in a few more instructions per row, for a sink whose span is large code
/// (the 3D pipeline's fused loop), so that it is inlined once. `rows` are the triangle's rows in
/// `clip` ([`rows_in_clip`]), which the caller has found already to skip an empty triangle.
#[inline(always)]
pub(crate) fn walk_spans_once<K: SpanSink>(
    t: &Sorted,
    s: i64,
    (top, mid, bottom): (i64, i64, i64),
    clip: &PixelRect,
    sink: &mut K,
) -> Result<(), K::Error> {
    let [v0, v1, v2] = t.v;
    let mut long = EdgeWalk::new(v0, v2, s, top);
    // The upper short edge when the triangle has rows above v1, else the lower one.
    let mut short = if top < mid {
        EdgeWalk::new(v0, v1, s, top)
    } else {
        EdgeWalk::new(v1, v2, s, mid)
    };
    let short_is_left = t.cross < 0;
    // The row where the short edge changes, if the triangle has rows above it: one test a row.
    let switch = if mid > top { mid } else { i64::MIN };
    for row in top..bottom {
        if row == switch {
            short = EdgeWalk::new(v1, v2, s, mid);
        }
        let (l, r) = if short_is_left {
            (short.col(), long.col())
        } else {
            (long.col(), short.col())
        };
        let (x0, x1) = (l.max(clip.x0), r.min(clip.x1));
        if x0 < x1 {
            // The row passes through `black_box`: otherwise the optimiser turns each product of
            // the row in the sink (every plane's `gy row`, the depth and colour rows' offsets)
            // into a sum carried from row to row, which this loop then spills and reloads.
            sink.span(core::hint::black_box(row) as i32, x0 as i32, x1 as i32)?;
        }
        short.step();
        long.step();
    }
    Ok(())
}

/// The spans of `rows` between two edge walks, clamped to the clip area's columns unless the
/// triangle lies inside them (`inside_x`).
// Out of line in an unoptimised build, which gives every inlined copy its own stack slots: a
// fill then holds one copy's at a time rather than all four's.
#[cfg_attr(debug_assertions, inline(never))]
#[cfg_attr(not(debug_assertions), inline(always))]
fn rows_of<K: SpanSink>(
    left: &mut EdgeWalk,
    right: &mut EdgeWalk,
    rows: core::ops::Range<i64>,
    clip: &PixelRect,
    inside_x: bool,
    sink: &mut K,
) -> Result<(), K::Error> {
    if inside_x {
        for row in rows {
            if left.col() < right.col() {
                sink.span(row as i32, left.col() as i32, right.col() as i32)?;
            }
            left.step();
            right.step();
        }
    } else {
        for row in rows {
            let (x0, x1) = (left.col().max(clip.x0), right.col().min(clip.x1));
            if x0 < x1 {
                sink.span(row as i32, x0 as i32, x1 as i32)?;
            }
            left.step();
            right.step();
        }
    }
    Ok(())
}

/// Whether the triangle surely covers no pixel centre inside `clip`, found without setting up
/// the edge walks: no row or no column of centres lies in its reach (it lies between two rows or
/// columns of centres, or outside `clip`), or at most four centres do and [`covers_a_centre`]
/// finds none. `false` decides nothing: the span walk decides coverage exactly.
#[inline(always)]
pub(crate) fn misses_every_centre(t: &Sorted, s: i64, clip: &PixelRect) -> bool {
    let [v0, v1, v2] = t.v;
    let (xmin, xmax) = (v0.0.min(v1.0).min(v2.0), v0.0.max(v1.0).max(v2.0));
    let rows = row_at_or_below(v0.1, s).max(clip.y0)..row_at_or_below(v2.1, s).min(clip.y1);
    let cols = centres(xmin, xmax, s, clip.x0, clip.x1);
    if rows.is_empty() || cols.is_empty() {
        return true;
    }
    let centres = (rows.end - rows.start).saturating_mul(cols.end - cols.start);
    centres <= 4 && !covers_a_centre(t, s, rows, cols)
}

/// Whether the triangle covers one of the pixel centres of `rows` x `cols` (pixel ranges inside
/// the clip area and the triangle's own rows): exactly what [`walk_spans`] decides for them, a
/// centre at a time with the edge functions instead of a set-up of the edge walks. For
/// triangles that reach a few centres at most (most triangles of a dense mesh seen from afar).
///
/// A centre `c` of a row lies right of (or on) an edge `a -> b` walked downwards when
/// `(c.x - a.x)(b.y - a.y) - (c.y - a.y)(b.x - a.x) >= 0`, the condition the edge walk's column
/// `ceil(N / D)` encodes; the span takes the centres at or right of its left edge and strictly
/// left of its right edge, with the short edge of the row's half of the triangle.
#[inline(never)]
pub(crate) fn covers_a_centre(
    t: &Sorted,
    s: i64,
    rows: core::ops::Range<i64>,
    cols: core::ops::Range<i64>,
) -> bool {
    let [v0, v1, v2] = t.v;
    // Doubled coordinates keep the centre (c s + s / 2) an integer with no sub-pixel bits.
    let side = |a: (i64, i64), b: (i64, i64), x2: i64, y2: i64| {
        (x2 - 2 * a.0) * (b.1 - a.1) - (y2 - 2 * a.1) * (b.0 - a.0)
    };
    for row in rows {
        let y2 = 2 * row * s + s;
        let short = if y2 < 2 * v1.1 { (v0, v1) } else { (v1, v2) };
        let (left, right) = if t.cross < 0 {
            (short, (v0, v2))
        } else {
            ((v0, v2), short)
        };
        for col in cols.clone() {
            let x2 = 2 * col * s + s;
            if side(left.0, left.1, x2, y2) >= 0 && side(right.0, right.1, x2, y2) < 0 {
                return true;
            }
        }
    }
    false
}

/// Whether the triangle `p` (vertices inside the guard band, in any order) may cover a pixel
/// centre of `clip`, for a triangle whose bounds hold at most four centres: `false` only when
/// [`walk_spans`] would give it no span there. Conservative and cheap, with no sort and no edge
/// walk: each centre of the bounds inside `clip` is tested against the three edges, a centre
/// on an edge counting as covered (the walk's top-left rule takes some of those and not
/// others). A flat triangle covers nothing.
#[inline(always)]
pub(crate) fn may_cover_a_centre<const BITS: u32>(
    p: &[SubPoint<BITS>; 3],
    clip: &PixelRect,
) -> bool {
    let s = 1i64 << BITS;
    let [a, b, c] = p.map(|q| (i64::from(q.x), i64::from(q.y)));
    let (xmin, xmax) = (a.0.min(b.0).min(c.0), a.0.max(b.0).max(c.0));
    let (ymin, ymax) = (a.1.min(b.1).min(c.1), a.1.max(b.1).max(c.1));
    // A larger triangle gets no quick answer (the fill decides): below 8 pixels a side (both
    // extents below 2^(BITS + 3), so their bits too), what follows fits `i32`.
    if ((xmax - xmin) | (ymax - ymin)) >= 8 << BITS {
        return true;
    }
    let cols = centres(xmin, xmax, s, clip.x0, clip.x1);
    let rows = centres(ymin, ymax, s, clip.y0, clip.y1);
    if cols.is_empty() || rows.is_empty() {
        return false;
    }
    // Doubled coordinates (a centre is then an integer with no sub-pixel bits), relative to
    // `a`'s: each within `2^(BITS + 4)`, as are the centres inside the bounds.
    let narrow = |v: i64| v as i32;
    let rel = |q: (i64, i64)| (narrow(2 * (q.0 - a.0)), narrow(2 * (q.1 - a.1)));
    let (a2, b2, c2) = ((0, 0), rel(b), rel(c));
    let area = b2.0 * c2.1 - c2.0 * b2.1;
    if area == 0 {
        return false;
    }
    // A clockwise triangle is walked the other way round (b and c swapped), so that every edge
    // function below is non-negative on the triangle's side, with no sign to multiply by.
    let (b2, c2) = if area < 0 { (c2, b2) } else { (b2, c2) };
    // Each edge `u -> v` as `f = dx (Y - u.y) - dy (X - u.x)` at the doubled centre `(X, Y)`,
    // `dx, dy` the edge (doubled too): each product below `2^(2 BITS + 9)`, `f` below `2^26`
    // (and a step beyond the last centre below `2^27`).
    let edge = |u: (i32, i32), v: (i32, i32)| (v.0 - u.0, v.1 - u.1, u.0, u.1);
    let (ea, eb, ec) = (edge(a2, b2), edge(b2, c2), edge(c2, a2));
    let (x2, y2) = (
        narrow(2 * cols.start * s + s - 2 * a.0),
        narrow(2 * rows.start * s + s - 2 * a.1),
    );
    let at = |e: (i32, i32, i32, i32)| e.0 * (y2 - e.3) - e.1 * (x2 - e.2);
    // Each edge's value at a row's first centre; a column on adds `-2 s dy`, a row `2 s dx` (a
    // centre is `2 s` doubled units from the next).
    let (mut fa, mut fb, mut fc) = (at(ea), at(eb), at(ec));
    let si = 2 * s as i32;
    let width = cols.end - cols.start;
    let mut left = (rows.end - rows.start) * width;
    let (mut ga, mut gb, mut gc) = (fa, fb, fc);
    let mut col = 0;
    // A centre a step: a loop with no count the compiler would unroll for the four centres
    // it ever sees.
    while left > 0 {
        if (ga | gb | gc) >= 0 {
            return true;
        }
        left -= 1;
        col += 1;
        if col == width {
            col = 0;
            (fa, fb, fc) = (fa + si * ea.0, fb + si * eb.0, fc + si * ec.0);
            (ga, gb, gc) = (fa, fb, fc);
        } else {
            (ga, gb, gc) = (ga - si * ea.1, gb - si * eb.1, gc - si * ec.1);
        }
    }
    false
}

#[cfg(test)]
pub(crate) mod tests {
    extern crate std;
    use super::*;
    use crate::geom::SubPoint;

    /// The first span of the walk, as the probe the centre test replaces.
    fn walk_covers(t: &Sorted, s: i64, clip: &PixelRect) -> bool {
        struct Probe(bool);
        impl SpanSink for Probe {
            type Error = ();
            fn span(&mut self, _: i32, _: i32, _: i32) -> Result<(), ()> {
                self.0 = true;
                Err(())
            }
        }
        let mut probe = Probe(false);
        let _ = walk_spans(t, s, clip, &mut probe);
        probe.0
    }

    /// Every span of a walk.
    pub(crate) struct Spans(pub(crate) std::vec::Vec<(i32, i32, i32)>);
    impl SpanSink for Spans {
        type Error = ();
        fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), ()> {
            self.0.push((row, x0, x1));
            Ok(())
        }
    }

    /// Xorshift numbers in `0 .. m`, from `seed`.
    pub(crate) fn numbers(mut x: u32) -> impl FnMut(u32) -> i32 {
        move |m| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x % m) as i32
        }
    }

    /// The clip area of the few-centres tests: its edges cross the triangles' region.
    const CLIP: PixelRect = PixelRect {
        x0: -3,
        y0: -2,
        x1: 40,
        y1: 30,
    };

    #[test]
    fn one_loop_walk_gives_the_same_spans() {
        let mut next = numbers(0x1357_9bdf);
        for _ in 0..50_000 {
            let clip = PixelRect {
                x0: i64::from(next(20)) - 5,
                y0: i64::from(next(20)) - 5,
                x1: i64::from(next(40)) + 10,
                y1: i64::from(next(40)) + 10,
            };
            // Whole pixels now and then, so that vertices fall on rows and edges.
            let w = if next(4) == 0 { 16 } else { 1 };
            let v = [0, 1, 2]
                .map(|_| SubPoint::new((next(60 * 16) - 80) / w * w, (next(50 * 16) - 80) / w * w));
            let Some(t) = Sorted::new(&v) else { continue };
            let (mut a, mut b) = (Spans(std::vec::Vec::new()), Spans(std::vec::Vec::new()));
            let _ = walk_spans(&t, 16, &clip, &mut a);
            if let Some(rows) = rows_in_clip(&t, 16, &clip) {
                let _ = walk_spans_once(&t, 16, rows, &clip, &mut b);
            }
            assert_eq!(a.0, b.0, "{v:?} {clip:?}");
        }
    }

    /// The columns of centres within `lo ..= hi` against a count of every centre, at 0, 1, 4 and
    /// 8 sub-pixel bits: none beyond `hi` (a bound between two centres reaches none, so a
    /// triangle there is rejected before its edges are set up) and none missed at either end.
    #[test]
    fn centres_are_exactly_those_within_the_bounds() {
        for bits in [0, 1, 4, 8] {
            let s = 1i64 << bits;
            for lo in -3 * s..3 * s {
                for hi in lo..lo + 3 * s {
                    let want: std::vec::Vec<i64> = (-10..10)
                        .filter(|c| (lo..=hi).contains(&(c * s + s / 2)))
                        .collect();
                    let got: std::vec::Vec<i64> = centres(lo, hi, s, -10, 10).collect();
                    assert_eq!(got, want, "{lo} ..= {hi}, {bits} bits");
                    // Exactly the centres within the bounds, at 0 bits too (in doubled units,
                    // where a centre is an integer).
                    let all = (-10..10).filter(|c| (2 * lo..=2 * hi).contains(&(2 * c * s + s)));
                    assert_eq!(centre_count(lo, hi, s), all.count() as i64, "{lo} ..= {hi}");
                }
            }
        }
    }

    #[test]
    fn unsorted_centre_test_never_misses_a_span() {
        let mut next = numbers(0x7f4a_7c15);
        let clip = CLIP;
        let s = 1i64 << 4;
        let (mut missed, mut tested) = (0, 0);
        for _ in 0..200_000 {
            // Vertices within a couple of pixels of each other, in any order; now and then on a
            // grid of half and whole pixels, so that centres fall on edges.
            let (cx, cy) = (next(48 * 16) - 64, next(40 * 16) - 64);
            let grid = [1, 1, 8, 16][next(4) as usize];
            let mut near = |c: i32| (c + next(48) - 24) / grid * grid;
            let p = [0, 1, 2].map(|_| SubPoint::<4>::new(near(cx), near(cy)));
            let may = may_cover_a_centre(&p, &clip);
            let Some(t) = Sorted::new(&p) else {
                assert!(!may, "a flat triangle {p:?}");
                continue;
            };
            let covers = walk_covers(&t, s, &clip);
            assert!(may || !covers, "{p:?} covers a centre");
            tested += 1;
            missed += usize::from(!may);
        }
        // Most of these triangles reach no centre: the test must say so for them.
        assert!(missed * 3 > tested, "{missed} of {tested}");
    }

    /// The unsorted test at its size limit (just below 8 pixels a side, where its `i32` sums are
    /// largest) and beyond it, at 0 and 8 sub-pixel bits, anywhere in the guard band: it never
    /// misses a span, and it still rejects triangles of the size the pipeline hands it.
    fn never_misses_up_to_its_limit<const BITS: u32>(seed: u32, share: usize) {
        let mut next = numbers(seed);
        let s = 1i64 << BITS;
        let limit = 8 << BITS;
        let band = crate::geom::GUARD_BAND_PIXELS << BITS;
        let (mut missed, mut tested) = (0, 0);
        for _ in 0..100_000 {
            // Around a point anywhere in the band, or in the clip area; extents up to the limit,
            // one unit below it, at it and a little beyond.
            let far = next(4) == 0;
            let (cx, cy) = if far {
                (
                    next(2 * (band as u32) - 2 * limit as u32) - band + limit,
                    next(2 * (band as u32) - 2 * limit as u32) - band + limit,
                )
            } else {
                (
                    next(48 << BITS) - (4 << BITS),
                    next(40 << BITS) - (4 << BITS),
                )
            };
            let reach = [limit - 1, limit, limit + 3, 2 << BITS][next(4) as usize] as u32;
            let mut near = |c: i32| c + next(reach + 1) - (reach / 2) as i32;
            let p = [0, 1, 2].map(|_| SubPoint::<BITS>::raw(near(cx), near(cy)));
            let clip = if far {
                PixelRect {
                    x0: i64::from(cx) / s - 6,
                    y0: i64::from(cy) / s - 6,
                    x1: i64::from(cx) / s + 6,
                    y1: i64::from(cy) / s + 6,
                }
            } else {
                CLIP
            };
            let may = may_cover_a_centre(&p, &clip);
            let Some(t) = Sorted::new(&p) else {
                continue;
            };
            assert!(may || !walk_covers(&t, s, &clip), "{p:?} covers a centre");
            tested += 1;
            missed += usize::from(!may);
        }
        // Small ones reach no centre now and then: measured 11,522 of 85,926 rejected at 0 bits,
        // 38,899 of 99,998 at 8; the bounds are about half of that.
        assert!(missed * share > tested, "{missed} of {tested}");
    }

    #[test]
    fn unsorted_centre_test_at_its_limit() {
        never_misses_up_to_its_limit::<0>(0x51ed_270b, 15);
        never_misses_up_to_its_limit::<8>(0x2f6b_9c1d, 5);
    }

    #[test]
    fn centre_test_matches_the_walk_on_small_triangles() {
        let mut next = numbers(0x2545_f491);
        let clip = CLIP;
        let s = 1i64 << 4;
        for _ in 0..200_000 {
            // Vertices within a few pixels of each other; now and then on a grid of half
            // pixels, so that they fall on pixel centres, share rows (flat tops and bottoms)
            // and put centres exactly on edges.
            let (cx, cy) = (next(48 * 16) - 64, next(40 * 16) - 64);
            let grid = [1, 1, 8, 16][next(4) as usize];
            let mut near = |c: i32| (c + next(80) - 40) / grid * grid;
            let v = [0, 1, 2].map(|_| SubPoint::new(near(cx), near(cy)));
            let Some(t) = Sorted::new(&v) else { continue };
            let [v0, v1, v2] = t.v;
            let (xmin, xmax) = (v0.0.min(v1.0).min(v2.0), v0.0.max(v1.0).max(v2.0));
            let rows = row_at_or_below(v0.1, s).max(clip.y0)..row_at_or_below(v2.1, s).min(clip.y1);
            let cols = centres(xmin, xmax, s, clip.x0, clip.x1);
            let expected = walk_covers(&t, s, &clip);
            assert_eq!(covers_a_centre(&t, s, rows, cols), expected, "{v:?}");
        }
    }
}
