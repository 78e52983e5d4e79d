//! Exact edge walking: the first pixel column at or right of an edge, row by row, with no division
//! after set-up.
//!
//! For an edge from `(xa, ya)` down to `(xb, yb)` (`dy = yb - ya > 0`, sub-pixel units, `S = 2^BITS`)
//! the sample of row `r` is `yc = r S + S/2`, and the pixel centres at or right of the edge are the
//! columns `col >= ceil(N / D)`, `N = (2 yc - 2 ya) dx + (2 xa - S) dy`, `D = 2 S dy` (doubled so that
//! the half-pixel offset stays an integer even with no sub-pixel bits). Moving down a row adds `2 S dx`
//! to `N`; the walk keeps `col` and the remainder `rem = col D - N` in `[0, D)`, like Bresenham.
//! The remainder is stored biased by `-D` so that the carry test is a sign test.

use core::num::NonZeroU64;

/// `ceil(n / d)` for `d > 0`: unsigned, by a `NonZeroU64` (no zero or overflow checks, a
/// measurable share of a small triangle's set-up), in 32 bits when the operands fit.
#[inline(always)]
fn ceil_div(n: i64, d: NonZeroU64) -> i64 {
    let (q, r) = crate::wide::divrem_narrow(n.unsigned_abs(), d);
    if n >= 0 {
        (q + u64::from(r != 0)) as i64
    } else {
        -(q as i64)
    }
}

/// The column walk of one edge.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EdgeWalk {
    /// `ceil(N / D)` for the current row.
    pub col: i64,
    /// `col D - N - D`, in `[-D, 0)`.
    rem: i64,
    d: i64,
    col_step: i64,
    rem_step: i64,
}

impl EdgeWalk {
    /// Sets the walk up at row `row` for the edge `a -> b` (`b.y > a.y`), `s` the sub-pixel unit.
    ///
    /// Bound: inside the guard band `|N| <= 12 M^2 < 2^62` (see [`crate::geom::GUARD_BAND_PIXELS`]):
    /// callers only set the walk up at a row whose sample lies within the edge's own rows.
    #[inline(always)]
    pub fn new(a: (i64, i64), b: (i64, i64), s: i64, row: i64) -> Self {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let d = 2 * s * dy;
        let yc2 = 2 * row * s + s;
        let n = (yc2 - 2 * a.1) * dx + (2 * a.0 - s) * dy;
        // dy > 0 for every edge a caller walks; a zero divisor would only mean a wrong span.
        let nz = NonZeroU64::new(d.unsigned_abs()).unwrap_or(NonZeroU64::MIN);
        let col = ceil_div(n, nz);
        let step = 2 * s * dx;
        let col_step = ceil_div(
            dx,
            NonZeroU64::new(dy.unsigned_abs()).unwrap_or(NonZeroU64::MIN),
        );
        Self {
            col,
            rem: col * d - n - d,
            d,
            col_step,
            rem_step: col_step * d - step,
        }
    }

    /// Moves to the next row.
    #[inline(always)]
    pub fn step(&mut self) {
        self.col += self.col_step;
        self.rem += self.rem_step;
        if self.rem >= 0 {
            self.rem -= self.d;
            self.col -= 1;
        }
    }
}

/// The first row whose sample `r S + S/2` lies at or below `y` (sub-pixel units, `S` the unit).
#[inline(always)]
pub(crate) fn row_at_or_below(y: i64, s: i64) -> i64 {
    // `s` is a power of two: ceil(n / 2s) = -floor(-n / 2s), an arithmetic shift.
    let shift = (2 * s).trailing_zeros();
    -((s - 2 * y) >> shift)
}
