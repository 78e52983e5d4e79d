//! Exact edge walking: the first pixel column at or right of an edge, row by row, with no division
//! after set-up.
//!
//! For an edge from `(xa, ya)` down to `(xb, yb)` (`dy = yb - ya > 0`, sub-pixel units, `S = 2^BITS`)
//! the sample of row `r` is `yc = r S + S/2`, and the pixel centres at or right of the edge are the
//! columns `col >= ceil(N / D)`, `N = (2 yc - 2 ya) dx + (2 xa - S) dy`, `D = 2 S dy` (doubled so that
//! the half-pixel offset stays an integer even with no sub-pixel bits). Moving down a row adds `2 S dx`
//! to `N`; the walk keeps `col` and the remainder `rem = col D - N` in `[0, D)`, like Bresenham.
//! The remainder is stored biased by `-D` so that the carry test is a sign test.
//!
//! A tall triangle's rows can take [`DdaWalk`] instead: a fixed-point accumulator whose integer
//! part stays exactly `ceil(N / D)` over as many rows as its bound allows, one add a row.

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

/// The column walk of one edge as a fixed-point accumulator, for the rows of a tall triangle: a
/// row's step is one add.
///
/// It holds `A ~ 2^40 (N + D - 1) / D`, whose integer part is the column `ceil(N / D)`: `A` is
/// set up rounded up, and so is its step `2^40 dx / dy` (both exactly, by one 64-bit division
/// each), so after `r` steps it lies above the exact value by less than `r + 1` units. The
/// fraction of `(N + D - 1) / D` is at most `(D - 1) / D`, so while that excess stays below
/// `2^40 / D` units the integer part is still exact: [`DdaWalk::new`] takes an edge only for
/// at most `2^40 / D` rows.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DdaWalk {
    acc: i64,
    step: i64,
}

impl DdaWalk {
    /// Fraction bits of the accumulator: a column of the guard band (below 2^22 in magnitude)
    /// times 2^40 fits `i64`.
    const FRAC: u32 = 40;

    /// Sets the walk up at row `row` for the edge `a -> b` (`b.y > a.y`), `s` the sub-pixel unit,
    /// to be read on `rows` rows from there (as [`EdgeWalk::new`]'s columns); `None` when its
    /// divisor `D = 2 s dy` is too large for that many rows (`rows D > 2^40`) or reaches 2^24
    /// (where the fractions would need more than one 64-bit division).
    #[inline(always)]
    pub fn new(a: (i64, i64), b: (i64, i64), s: i64, row: i64, rows: i64) -> Option<Self> {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let d = 2 * s * dy;
        let fits = dy > 0
            && d < 1 << 24
            && u64::try_from(rows).is_ok_and(|r| r * (d as u64) <= 1 << Self::FRAC);
        if !fits {
            return None;
        }
        let nz = NonZeroU64::new(d as u64)?;
        let nz_dy = NonZeroU64::new(dy as u64)?;
        let yc2 = 2 * row * s + s;
        let n = (yc2 - 2 * a.1) * dx + (2 * a.0 - s) * dy;
        // col = ceil(n / d), rem = col d - n in [0, d): (n + d - 1) / d = col + (d - 1 - rem) / d.
        let (col, rem) = ceil_div_rem(n, nz);
        let frac = ceil_fraction(d as u64 - 1 - rem, nz);
        // dx / dy = cs - rs / dy with cs = ceil(dx / dy), rs in [0, dy): its 2^40 multiple
        // rounded up takes the fraction rounded down. Inside the guard band an edge read on two
        // rows or more has |cs| < 2^22 (it crosses at most the band's width a row); a steeper
        // one is read on one row only, and its step may wrap unread.
        let (cs, rs) = ceil_div_rem(dx, nz_dy);
        let (q, _) = crate::wide::divrem_narrow(rs << Self::FRAC, nz_dy);
        Some(Self {
            acc: (col << Self::FRAC) + frac as i64,
            step: (cs << Self::FRAC).wrapping_sub(q as i64),
        })
    }

    /// The first column at or right of the edge on the current row.
    #[inline(always)]
    pub fn col(&self) -> i64 {
        self.acc >> Self::FRAC
    }

    /// Moves to the next row (wrapping past the rows it was set up for, as [`EdgeWalk::step`]).
    #[inline(always)]
    pub fn step(&mut self) {
        self.acc = self.acc.wrapping_add(self.step);
    }
}

/// `(ceil(n / d), ceil(n / d) d - n)`, the remainder in `[0, d)`.
#[inline(always)]
fn ceil_div_rem(n: i64, d: NonZeroU64) -> (i64, u64) {
    let (q, r) = crate::wide::divrem_narrow(n.unsigned_abs(), d);
    if n >= 0 && r != 0 {
        (q as i64 + 1, d.get() - r)
    } else if n >= 0 {
        (q as i64, 0)
    } else {
        (-(q as i64), r)
    }
}

/// `ceil(2^40 x / d)` for `x < d < 2^24`.
#[inline(always)]
fn ceil_fraction(x: u64, d: NonZeroU64) -> u64 {
    let (q, r) = crate::wide::divrem_narrow(x << DdaWalk::FRAC, d);
    q + u64::from(r != 0)
}

/// The first row whose sample `r S + S/2` lies at or below `y` (sub-pixel units, `S` the unit).
#[inline(always)]
pub(crate) fn row_at_or_below(y: i64, s: i64) -> i64 {
    // `s` is a power of two: ceil(n / 2s) = -floor(-n / 2s), an arithmetic shift.
    let shift = (2 * s).trailing_zeros();
    -((s - 2 * y) >> shift)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// `ceil(N / D)` of row `r` straight from the definition, in `i128`.
    fn exact_col(a: (i64, i64), b: (i64, i64), s: i64, r: i64) -> i64 {
        let (dx, dy) = (i128::from(b.0 - a.0), i128::from(b.1 - a.1));
        let (s, r) = (i128::from(s), i128::from(r));
        let n = (2 * r * s + s - 2 * i128::from(a.1)) * dx + (2 * i128::from(a.0) - s) * dy;
        let d = 2 * s * dy;
        (-(-n).div_euclid(d)) as i64
    }

    /// Xorshift numbers, for the tests of the raster modules.
    pub(crate) fn xorshift(mut x: u64) -> impl FnMut() -> u64 {
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        }
    }

    /// Every row an edge is read on, up to the walk's bound, against the definition: random
    /// edges at every sub-pixel setting, with divisors up to just below 2^24 and slopes from
    /// vertical to nearly flat, and the walk set up at the edge's first row.
    #[test]
    fn dda_walk_gives_the_exact_columns_up_to_its_bound() {
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
        let mut rows_checked = 0u64;
        for case in 0..3000 {
            let bits = case % 9;
            let s = 1i64 << bits;
            // Heights up to the largest divisor taken, 2 s dy < 2^24.
            let max_dy = ((1i64 << 23) / s - 1).min(1 << (21 + bits));
            let dy = match case % 3 {
                0 => max_dy - (next() % 64) as i64,
                1 => 1 + (next() % max_dy as u64) as i64,
                _ => 1 + (next() % 4096) as i64,
            }
            .max(1);
            // Both ends inside the guard band, 2^21 pixels each way.
            let band = 1i64 << (21 + bits);
            let mut coord = || (next() % (2 * band as u64 + 1)) as i64 - band;
            let (xa, xb) = (coord(), coord());
            let xb = if case % 5 == 0 { xa + (xb % 7) } else { xb };
            let ya = coord().min(band - dy);
            let (a, b) = ((xa, ya), (xb, ya + dy));
            let top = row_at_or_below(a.1, s);
            // The edge's own rows, capped by the bound (and for the test's time).
            let own = row_at_or_below(b.1, s) - top;
            let d = 2 * s * dy;
            let bound = (1i64 << 40) / d;
            let rows = own.min(bound).min(70_000);
            if rows <= 0 {
                continue;
            }
            let mut w = DdaWalk::new(a, b, s, top, rows).expect("inside the bound");
            for r in 0..rows {
                assert_eq!(
                    w.col(),
                    exact_col(a, b, s, top + r),
                    "edge {a:?} -> {b:?}, {bits} bits, row {r} of {rows}"
                );
                w.step();
            }
            rows_checked += rows as u64;
        }
        // The cases reach the bound's long walks, not only short edges (74,653,710 rows).
        assert!(rows_checked > 37_000_000, "{rows_checked}");
    }

    #[test]
    fn dda_walk_refuses_edges_past_its_bound() {
        let s = 16;
        // D = 2 s dy reaches 2^24.
        assert!(DdaWalk::new((0, 0), (5, 1 << 19), s, 0, 1).is_none());
        assert!(DdaWalk::new((0, 0), (5, (1 << 19) - 1), s, 0, 1).is_some());
        // rows D passes 2^40.
        let d = 2 * s * 1000;
        let most = (1i64 << 40) / d;
        assert!(DdaWalk::new((0, 0), (7, 1000), s, 0, most).is_some());
        assert!(DdaWalk::new((0, 0), (7, 1000), s, 0, most + 1).is_none());
        // No walk for an edge with no height.
        assert!(DdaWalk::new((0, 0), (7, 0), s, 0, 1).is_none());
    }

    /// An edge one sub-pixel unit tall that crosses the whole guard band is read on its one row:
    /// its step, far beyond `i64` at 2^40, wraps unread and nothing overflows (debug builds
    /// check), at every sub-pixel setting.
    #[test]
    fn dda_walk_of_a_flat_edge_across_the_band() {
        for bits in 0..=8 {
            let s = 1i64 << bits;
            let m = 1i64 << (21 + bits);
            for (a, b) in [((-m, 0), (m, 1)), ((m, 0), (-m, 1))] {
                // Sample of row 0 at s / 2: only the 8-bit edge from y = 0 to 1 holds none.
                let (a, b) = ((a.0, a.1 + s / 2 - 1), (b.0, b.1 + s / 2 - 1));
                let w = DdaWalk::new(a, b, s, 0, 1).expect("one row");
                assert_eq!(w.col(), exact_col(a, b, s, 0), "{bits} bits");
            }
        }
        // Three units tall (one row from 2 bits up), its slope's ceiling 2^23: 2^40 times it is
        // i64::MIN once wrapped, and the step's fraction is still to come off it.
        for bits in 2..=8 {
            let s = 1i64 << bits;
            let (a, b) = ((0, s / 2 - 1), (3 * (1 << 23) - 1, s / 2 + 2));
            let w = DdaWalk::new(a, b, s, 0, 1).expect("one row");
            assert_eq!(w.col(), exact_col(a, b, s, 0), "{bits} bits");
        }
    }
}
