//! Angles in an integer unit and sine/cosine from a quarter-wave table, no floats anywhere.
//!
//! An [`Angle`] is a `u16` count of 1/65536 turns, so angles wrap for free. Sine comes from a table of
//! `N` entries over a quarter turn, in 2.30 fixed point, linearly interpolated. The table is built at
//! compile time by an integer Taylor series (`i128`, 60 fractional bits), so its size is a
//! compile-time choice ([`sin_cos_table`]); the default, 256 entries (1 KiB of flash), has a maximum
//! interpolation error of about 5e-6, below one 16.16 step.

/// An angle in 1/65536 of a turn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Angle(pub u16);

impl Angle {
    /// A quarter turn.
    pub const QUARTER: Angle = Angle(16384);

    /// From whole degrees, rounded to the nearest unit.
    pub const fn from_degrees(deg: i32) -> Self {
        Self::from_degrees_ratio(deg as i64, 1)
    }

    /// From `num / den` degrees, rounded to the nearest unit; `den = 0` gives zero.
    pub const fn from_degrees_ratio(num: i64, den: i64) -> Self {
        if den == 0 {
            return Angle(0);
        }
        // units = deg * 65536 / 360, reduced modulo a turn.
        let n = (num as i128) * 65536;
        let d = (den as i128) * 360;
        let units = crate::math::fx::round_div_i128(n, d);
        Angle(units.rem_euclid(65536) as u16)
    }

    /// The sum, wrapping at a full turn.
    pub const fn wrapping_add(self, other: Angle) -> Angle {
        Angle(self.0.wrapping_add(other.0))
    }

    /// `(sin, cos)` in 2.30 fixed point (1.0 = 2^30) from the default 256-entry table.
    pub fn sin_cos_q30(self) -> (i32, i32) {
        sin_cos_table::<DEFAULT_TABLE>(self)
    }
}

/// Entries of the default quarter-wave table.
pub const DEFAULT_TABLE: usize = 256;

/// 1.0 in the tables' 2.30 format.
pub const Q30_ONE: i32 = 1 << 30;

/// π in 3.60 fixed point.
const PI_Q60: i128 = 3_622_009_729_038_561_421;

/// `sin(i / n * π/2)` in 2.30 fixed point, by the Taylor series in 3.60 fixed point.
const fn sin_quarter_q30(i: usize, n: usize) -> i32 {
    let x = PI_Q60 * i as i128 / (2 * n as i128);
    let x2 = (x * x) >> 60;
    let mut term = x;
    let mut sum = x;
    let mut k = 1i128;
    // x <= π/2: the terms fall below 2^-60 after 14 rounds.
    while k < 16 {
        term = -((term * x2) >> 60) / ((2 * k) * (2 * k + 1));
        sum += term;
        k += 1;
    }
    ((sum + (1 << 29)) >> 30) as i32
}

/// A quarter-wave sine table of `N` entries: `sin(i / N * π/2)` for `i` in `0..N`.
pub struct SinTable<const N: usize>;

impl<const N: usize> SinTable<N> {
    const VALID: () = assert!(N >= 2 && N <= 16384, "table size must be 2..=16384");
    /// The entries, built at compile time.
    pub const ENTRIES: [i32; N] = {
        #[allow(clippy::let_unit_value)]
        let () = Self::VALID;
        let mut t = [0i32; N];
        let mut i = 0;
        while i < N {
            t[i] = sin_quarter_q30(i, N);
            i += 1;
        }
        t
    };
}

/// `sin` over the first quarter turn: `pos` in `0..=16384`.
#[inline]
fn quarter<const N: usize>(pos: u32) -> i32 {
    let table = &SinTable::<N>::ENTRIES;
    let scaled = pos as u64 * N as u64;
    let idx = (scaled >> 14) as usize;
    let frac = (scaled & 0x3FFF) as i64;
    let at = |i: usize| if i < N { table[i] } else { Q30_ONE };
    let (a, b) = (at(idx) as i64, at(idx + 1) as i64);
    (a + (((b - a) * frac + (1 << 13)) >> 14)) as i32
}

/// `(sin, cos)` of `angle` in 2.30 fixed point from an `N`-entry quarter-wave table.
///
/// Exact at multiples of a quarter turn; odd symmetry and `sin² + cos² ≈ 1` within the table's
/// interpolation error.
pub fn sin_cos_table<const N: usize>(angle: Angle) -> (i32, i32) {
    let a = angle.0 as u32;
    let (quadrant, pos) = (a >> 14, a & 0x3FFF);
    let s = quarter::<N>(pos);
    let c = quarter::<N>(16384 - pos);
    match quadrant {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}
