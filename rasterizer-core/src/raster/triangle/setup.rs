//! Triangle set-up shared by the flat and Gouraud fills: sort by y, reject what cannot be drawn,
//! and walk the spans row by row.

use crate::geom::{PixelRect, SubPoint};
use crate::raster::edge::{row_at_or_below, EdgeWalk};

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
        let key = |i: usize| (v[i].y, v[i].x);
        let mut order = [0usize, 1, 2];
        if key(order[1]) < key(order[0]) {
            order.swap(0, 1);
        }
        if key(order[2]) < key(order[1]) {
            order.swap(1, 2);
            if key(order[1]) < key(order[0]) {
                order.swap(0, 1);
            }
        }
        let p = order.map(|i| (i64::from(v[i].x), i64::from(v[i].y)));
        // Bound: |each product| <= (2M)^2 = 2^60 inside the guard band.
        let cross = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
        (cross != 0).then_some(Self { v: p, order, cross })
    }
}

/// Receives the spans of a triangle.
pub(crate) trait SpanSink {
    /// The target's error.
    type Error;
    /// Draws columns `x0 .. x1` (`x0 < x1`, inside the clip area) of `row`.
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), Self::Error>;
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
    let top = row_at_or_below(v0.1, s).max(clip.y0);
    let mid = row_at_or_below(v1.1, s).clamp(top, clip.y1.max(top));
    let bottom = row_at_or_below(v2.1, s).min(clip.y1);
    if top >= bottom {
        return Ok(());
    }
    // Columns need clamping only when the triangle's x extent leaves the clip area: a non-empty
    // span's ends lie between the leftmost and rightmost vertex.
    let (xmin, xmax) = (v0.0.min(v1.0).min(v2.0), v0.0.max(v1.0).max(v2.0));
    let inside_x = xmin >= clip.x0 * s && xmax <= clip.x1 * s;
    let mut long = EdgeWalk::new(v0, v2, s, top);
    let short_is_left = t.cross < 0;
    if top < mid {
        let mut upper = EdgeWalk::new(v0, v1, s, top);
        let (l, r) = if short_is_left {
            (&mut upper, &mut long)
        } else {
            (&mut long, &mut upper)
        };
        rows_of(l, r, top..mid.min(bottom), clip, inside_x, sink)?;
    }
    if mid < bottom {
        let mut lower = EdgeWalk::new(v1, v2, s, mid);
        let (l, r) = if short_is_left {
            (&mut lower, &mut long)
        } else {
            (&mut long, &mut lower)
        };
        rows_of(l, r, mid..bottom, clip, inside_x, sink)?;
    }
    Ok(())
}

/// The spans of `rows` between two edge walks, clamped to the clip area's columns unless the
/// triangle lies inside them (`inside_x`).
#[inline(always)]
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
            if left.col < right.col {
                sink.span(row as i32, left.col as i32, right.col as i32)?;
            }
            left.step();
            right.step();
        }
    } else {
        for row in rows {
            let (x0, x1) = (left.col.max(clip.x0), right.col.min(clip.x1));
            if x0 < x1 {
                sink.span(row as i32, x0 as i32, x1 as i32)?;
            }
            left.step();
            right.step();
        }
    }
    Ok(())
}
