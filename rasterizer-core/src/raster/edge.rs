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
pub(crate) fn ceil_div(n: i64, d: NonZeroU64) -> i64 {
    let (q, r) = crate::wide::divrem_narrow(n.unsigned_abs(), d);
    if n >= 0 {
        (q + u64::from(r != 0)) as i64
    } else {
        -(q as i64)
    }
}

/// Bits below the column in [`EdgeWalk`]'s packed state: the remainder lies in `[-D, D)` with
/// `D <= 2^39` inside the guard band (`D = 2 S dy`, `dy <= 2^(22 + b)`, `S = 2^b`, `b <= 8`), so
/// it fits the low 40 bits as a two's-complement number, and a column of the guard band (below
/// 2^22 in magnitude) times 2^40 fits `i64`.
const REM_BITS: u32 = 40;

/// The column walk of one edge.
///
/// The column and the remainder live in one integer, `col 2^40 + rem` (the remainder biased into
/// `[-D, 0)` and 2^40 added so that the column is the integer's top bits): a row's step is one add,
/// a test of the remainder's sign bit and a conditional subtract, and the walk holds three values
/// instead of five, which the row loops keep in registers.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EdgeWalk {
    /// `(col + 1) 2^40 + rem`, `rem = col D - N - D` in `[-D, 0)`.
    packed: i64,
    /// `col_step 2^40 + rem_step`, `rem_step` in `[0, D)`.
    step: i64,
    /// `2^40 + D`: one column back and one `D` off the remainder.
    carry: i64,
}

impl EdgeWalk {
    /// Sets the walk up at row `row` for the edge `a -> b` (`b.y > a.y`), `s` the sub-pixel unit.
    ///
    /// Bound: inside the guard band `|N| <= 12 M^2 < 2^62` (see [`crate::geom::GUARD_BAND_PIXELS`]):
    /// callers only set the walk up, and read its column, at rows whose sample lies within the
    /// edge's own rows. Steps past them (the last row's, or an edge less than two rows tall) may
    /// leave a meaningless column, never read; the arithmetic wraps there rather than overflow.
    #[inline(always)]
    pub fn new(a: (i64, i64), b: (i64, i64), s: i64, row: i64) -> Self {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let d = 2 * s * dy;
        let yc2 = 2 * row * s + s;
        let n = (yc2 - 2 * a.1) * dx + (2 * a.0 - s) * dy;
        // dy > 0 for every edge a caller walks; a zero divisor would only mean a wrong span.
        let nz = NonZeroU64::new(d.unsigned_abs()).unwrap_or(NonZeroU64::MIN);
        let col = ceil_div(n, nz);
        let col_step = ceil_div(
            dx,
            NonZeroU64::new(dy.unsigned_abs()).unwrap_or(NonZeroU64::MIN),
        );
        // (col + 1) 2^40 + (col D - N - D) and col_step 2^40 + (col_step D - 2 S dx), each
        // with one product by 2^40 + D.
        let carry = (1i64 << REM_BITS) + d;
        Self {
            packed: col
                .wrapping_mul(carry)
                .wrapping_sub(n)
                .wrapping_add((1i64 << REM_BITS) - d),
            step: col_step.wrapping_mul(carry).wrapping_sub(2 * s * dx),
            carry,
        }
    }

    /// The first column at or right of the edge on the current row.
    #[inline(always)]
    pub fn col(&self) -> i64 {
        self.packed >> REM_BITS
    }

    /// Moves to the next row.
    #[inline(always)]
    pub fn step(&mut self) {
        self.packed = self.packed.wrapping_add(self.step);
        // The remainder's sign bit clear: it reached [0, D), so one column back.
        if self.packed & (1 << (REM_BITS - 1)) == 0 {
            self.packed = self.packed.wrapping_sub(self.carry);
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
