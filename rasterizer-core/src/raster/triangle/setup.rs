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

/// Calls `span(row, x0, x1)` for every non-empty span of the triangle inside `clip`, top to bottom;
/// the span covers columns `x0 .. x1`.
///
/// Rows run over `y0 <= yc < y2`; in each, columns run from the left edge's column (inclusive: a centre
/// on a left edge is inside) to the right edge's column (exclusive): the top-left rule.
#[inline(always)]
pub(crate) fn walk_spans<E, F>(t: &Sorted, s: i64, clip: &PixelRect, mut span: F) -> Result<(), E>
where
    F: FnMut(i32, i32, i32) -> Result<(), E>,
{
    let [v0, v1, v2] = t.v;
    let top = row_at_or_below(v0.1, s).max(clip.y0);
    let mid = row_at_or_below(v1.1, s).clamp(top, clip.y1.max(top));
    let bottom = row_at_or_below(v2.1, s).min(clip.y1);
    if top >= bottom {
        return Ok(());
    }
    let short_is_left = t.cross < 0;
    let mut long = EdgeWalk::new(v0, v2, s, top);
    let mut emit = |row: i64, short: &EdgeWalk, long: &EdgeWalk| {
        let (l, r) = if short_is_left {
            (short.col, long.col)
        } else {
            (long.col, short.col)
        };
        let (x0, x1) = (l.max(clip.x0), r.min(clip.x1));
        if x0 < x1 {
            span(row as i32, x0 as i32, x1 as i32)
        } else {
            Ok(())
        }
    };
    if top < mid {
        let mut upper = EdgeWalk::new(v0, v1, s, top);
        for row in top..mid.min(bottom) {
            emit(row, &upper, &long)?;
            upper.step();
            long.step();
        }
    }
    if mid < bottom {
        let mut lower = EdgeWalk::new(v1, v2, s, mid);
        for row in mid..bottom {
            emit(row, &lower, &long)?;
            lower.step();
            long.step();
        }
    }
    Ok(())
}
