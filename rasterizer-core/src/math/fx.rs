//! `Fx<F>`: signed 32-bit fixed point with `F` fractional bits.
//!
//! One const-generic type covers the formats the accuracy report compares (16.16, 24.8, 8.24) with a
//! single implementation. Rounding and overflow are explicit: products and quotients go through `i64`
//! and round half up (towards +inf) once; every operation saturates at the format's range instead of
//! wrapping, so an overflow shows as a clamped value, never as a sign flip.

use core::fmt;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// Signed fixed point: the raw `i32` `bits` stands for `bits / 2^F`.
///
/// Range: `[-2^(31-F), 2^(31-F) - 2^-F]`; for [`Fx16`] that is about ±32768 with a step of
/// 1/65536 (1.5e-5).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[repr(transparent)]
pub struct Fx<const F: u32>(i32);

/// 16.16 fixed point: the geometry format of the pipeline.
pub type Fx16 = Fx<16>;
/// 24.8 fixed point: large range, coarse step (1/256).
pub type Fx8 = Fx<8>;
/// 8.24 fixed point: fine step (6e-8), range ±128.
pub type Fx24 = Fx<24>;

impl<const F: u32> Fx<F> {
    /// Compile-time check: between 1 and 30 fractional bits.
    const VALID: () = assert!(F >= 1 && F <= 30, "Fx needs 1 to 30 fractional bits");
    /// 0.
    pub const ZERO: Self = Self(0);
    /// 1.
    pub const ONE: Self = {
        #[allow(clippy::let_unit_value)]
        let () = Self::VALID;
        Self(1 << F)
    };
    /// The largest value.
    pub const MAX: Self = Self(i32::MAX);
    /// The smallest value.
    pub const MIN: Self = Self(i32::MIN);
    /// The smallest positive value, `2^-F`.
    pub const EPSILON: Self = Self(1);

    /// From raw bits.
    pub const fn from_bits(bits: i32) -> Self {
        Self(bits)
    }

    /// The raw bits.
    pub const fn to_bits(self) -> i32 {
        self.0
    }

    /// Saturates a raw `i64` into range.
    #[inline]
    pub const fn saturate(bits: i64) -> Self {
        if bits > i32::MAX as i64 {
            Self::MAX
        } else if bits < i32::MIN as i64 {
            Self::MIN
        } else {
            Self(bits as i32)
        }
    }

    /// An integer, saturating.
    pub const fn from_int(i: i32) -> Self {
        Self::saturate((i as i64) << F)
    }

    /// `num / den` rounded to the nearest step (halves up), saturating; `den = 0` gives the largest
    /// value of `num`'s sign (0 for `0 / 0`).
    pub const fn from_ratio(num: i64, den: i64) -> Self {
        if den == 0 {
            return if num > 0 {
                Self::MAX
            } else if num < 0 {
                Self::MIN
            } else {
                Self::ZERO
            };
        }
        let n = (num as i128) << F;
        Self::saturate_i128(round_div_i128(n, den as i128))
    }

    /// Saturates a raw `i128` into range.
    pub(crate) const fn saturate_i128(v: i128) -> Self {
        if v > i32::MAX as i128 {
            Self::MAX
        } else if v < i32::MIN as i128 {
            Self::MIN
        } else {
            Self(v as i32)
        }
    }

    /// The same value in another format, rounded to the nearest step (halves up) and saturated.
    pub const fn convert<const G: u32>(self) -> Fx<G> {
        if G >= F {
            Fx::<G>::saturate((self.0 as i64) << (G - F))
        } else {
            let sh = F - G;
            Fx::<G>::saturate(((self.0 as i64) + (1 << (sh - 1))) >> sh)
        }
    }

    /// The nearest integer (halves up).
    pub const fn round_to_int(self) -> i32 {
        (((self.0 as i64) + (1 << (F - 1))) >> F) as i32
    }

    /// The largest integer not above the value.
    pub const fn floor_to_int(self) -> i32 {
        self.0 >> F
    }

    /// Absolute value, saturating (`MIN.abs() == MAX`).
    pub const fn abs(self) -> Self {
        Self(self.0.saturating_abs())
    }

    /// Product rounded once, halves up, saturating.
    #[inline]
    pub const fn mul_fx(self, rhs: Self) -> Self {
        let p = (self.0 as i64) * (rhs.0 as i64);
        Self::saturate((p + (1 << (F - 1))) >> F)
    }

    /// Quotient rounded once, halves up, saturating; division by zero saturates like
    /// [`Fx::from_ratio`].
    #[inline]
    pub const fn div_fx(self, rhs: Self) -> Self {
        Self::from_ratio(self.0 as i64, rhs.0 as i64)
    }

    /// Square root, rounded down to the step; negative input gives 0.
    pub const fn sqrt(self) -> Self {
        if self.0 <= 0 {
            return Self::ZERO;
        }
        Self(isqrt_u64((self.0 as u64) << F) as i32)
    }

    /// `1 / self`, rounded, saturating.
    pub const fn recip(self) -> Self {
        Self::from_ratio(1 << F, self.0 as i64)
    }

    /// The sum of four products, rounded once: more accurate than four rounded products.
    #[inline]
    pub const fn dot4(a: [Self; 4], b: [Self; 4]) -> Self {
        // Each product is at most 2^62 in magnitude; four of them can exceed i64 only when the
        // factors are near the format's limit. The sum is taken in i64 with overflow checks (one
        // branch each, never taken for geometry) and in i128 only when one fires.
        let p = [
            (a[0].0 as i64) * (b[0].0 as i64),
            (a[1].0 as i64) * (b[1].0 as i64),
            (a[2].0 as i64) * (b[2].0 as i64),
            (a[3].0 as i64) * (b[3].0 as i64),
        ];
        if let Some(s) = p[0].checked_add(p[1]) {
            if let Some(s) = s.checked_add(p[2]) {
                if let Some(s) = s.checked_add(p[3]) {
                    if let Some(s) = s.checked_add(1 << (F - 1)) {
                        return Self::saturate(s >> F);
                    }
                }
            }
        }
        // Each product split at bit F, p = (p >> F) 2^F + low bits: the whole parts and the
        // fractions sum in i64 without overflow, and the sum rounds as the exact one would.
        let mask = (1 << F) - 1;
        let whole = (p[0] >> F) + (p[1] >> F) + (p[2] >> F) + (p[3] >> F);
        let frac = (p[0] & mask) + (p[1] & mask) + (p[2] & mask) + (p[3] & mask) + (1 << (F - 1));
        Self::saturate(whole + (frac >> F))
    }
}

/// `round(n / d)`, halves towards +inf, `d != 0`.
pub(crate) const fn round_div_i128(n: i128, d: i128) -> i128 {
    let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
    crate::wide::divmod_euclid_i128(2 * n + d, 2 * d).0
}

/// `floor(sqrt(v))`.
pub(crate) const fn isqrt_u64(v: u64) -> u64 {
    if v < 2 {
        return v;
    }
    // Start from an over-estimate within 1/64 of the root, read from a table by the top eight bits
    // (an even shift keeps the root's scale a shift too), so that Newton's method needs three or
    // four steps instead of six or seven: its divisions are the slow part of a normalisation.
    let bits = 64 - v.leading_zeros();
    let sh = if bits > 8 { (bits - 7) & !1 } else { 0 };
    // top < 2^8 and v < (top + 1) 2^sh, so sqrt(v) < sqrt(top + 1) 2^(sh/2) <= x.
    let top = (v >> sh) as usize;
    let x = ((ROOT_TABLE[top] as u64) << (sh / 2)).div_ceil(16);
    // Newton's method from an over-estimate converges monotonically down to the floor.
    let mut x = if x < 1 { 1 } else { x };
    loop {
        let y = (x + v / x) / 2;
        if y >= x {
            return x;
        }
        x = y;
    }
}

/// `(r, k)` with `r ≈ 2^k / sqrt(x)` for `x > 0`: `r` in `[2^30, 2^31]`, `k >= 31`, within a
/// few units of the last bit of `r`. No division: a 192-entry table of the top bits and two
/// Newton steps (`y' = y (3 - x y²) / 2`, each doubling the correct bits from about eight), so a
/// normalisation costs multiplications only.
#[inline]
pub(crate) const fn rsqrt_u64(x: u64) -> (u64, u32) {
    // m = x 2^e in [2^60, 2^62) with e even (e = -2 when x >= 2^62): sqrt(m) = sqrt(x) 2^(e/2).
    let lz = x.leading_zeros();
    let (m, half_e) = if lz >= 2 {
        let e = (lz - 2) & !1;
        (x << e, (e / 2) as i32)
    } else {
        (x >> 2, -1)
    };
    // y ≈ 2^61 / sqrt(m), in (2^30, 2^31], from the table by the top eight bits of m (64..255).
    let mut y = (RSQRT_TABLE[(m >> 54) as usize - 64] as u64) << 15;
    let mut i = 0;
    while i < 2 {
        // t = m y² / 2^122 in 2.30 (at most 2^30: Newton's steps stay below the root); then
        // y' = y (3 - t) / 2.
        let yy = (y * y) >> 30;
        let t = ((m >> 30) * yy) >> 32;
        y = (y * ((3u64 << 30) - t)) >> 31;
        i += 1;
    }
    // 2^61 / sqrt(m) = 2^(61 - e/2) / sqrt(x).
    (y, (61 - half_e) as u32)
}

/// [`rsqrt_u64`] with one Newton step from a finer table, for lighting: `r` within `2^-17` of
/// `2^k / sqrt(x)` relatively (below it, up to the truncations' few units), with `k >= 31`
/// and `r <= 2^31`; `x` must not be zero.
///
/// The table of the top nine bits gives the root within `2^-9`; Newton's step squares that
/// error (`y' = y (3 - x y²) / 2` leaves `1.5 ε²` below the root). Half the work of
/// [`rsqrt_u64`], for a cosine that a specular power of 16 turns into a colour error of about
/// `16 · 255 · 2^-17`, 0.03 of an 8-bit step.
#[inline(always)]
pub(crate) fn rsqrt_fast(x: u64) -> (u64, u32) {
    // m = x 2^e in [2^62, 2^64) with e even; X = m / 2^64 in [1/4, 1).
    let e = x.leading_zeros() & !1;
    let m = x << e;
    // y = r 2^15 ≈ 2^30 / sqrt(X) in (2^30, 2^31), r from the top nine bits of m (128 ..= 511).
    let r = u64::from(RSQRT9_TABLE[(m >> 55) as usize - 128]);
    // t = X y² in 2.30 (y² >> 32 = r² >> 2 below 2^30, times X 2^32 below 2^62); y (3 - t) / 2
    // = r (3 - t) / 2^16, r (3 - t) below 2^48.
    let t = ((m >> 32) * ((r * r) >> 2)) >> 30;
    let y = (r * ((3 << 30) - t)) >> 16;
    // 1 / sqrt(x) = 2^(e/2) / (sqrt(X) 2^32) = y 2^(e/2 - 62).
    (y, 62 - e / 2)
}

/// `2^15 / sqrt((t + 1/2) / 512)` for `128 <= t < 512` (entry `t - 128`), rounded: the
/// reciprocal root at the middle of each interval of [`rsqrt_fast`]'s top nine bits. A
/// `static`: a debug build copies a `const` array onto the stack at every inlined use.
static RSQRT9_TABLE: [u16; 384] = {
    let mut out = [0u16; 384];
    let mut t = 128;
    while t < 512 {
        // 2^15 sqrt(1024 / (2t + 1)) = 2^40 / sqrt((2t + 1) 2^40).
        let root = isqrt_u64((2 * t as u64 + 1) << 40);
        out[t - 128] = (((1u64 << 40) + root / 2) / root) as u16;
        t += 1;
    }
    out
};

/// `2^46 / sqrt((t + 1/2) 2^54)` for `64 <= t < 256` (entry `t - 64`), rounded down so that
/// Newton's steps start below the root: the reciprocal root at the middle of each interval of
/// the top eight bits, with 16 significant bits.
const RSQRT_TABLE: [u16; 192] = {
    let mut out = [0u16; 192];
    let mut t = 64;
    while t < 256 {
        // sqrt((2t + 1) 2^53) = sqrt((2t + 1) 2^53), an integer root; 2^46 / that.
        let root = isqrt_u64((2 * t as u64 + 1) << 53);
        out[t - 64] = ((1u64 << 46) / (root + 1)) as u16;
        t += 1;
    }
    out
};

/// `ceil(16 sqrt(t + 1))` for `t < 256`: [`isqrt_u64`]'s first estimate.
const ROOT_TABLE: [u16; 256] = {
    let mut t = [0u16; 256];
    let mut i = 0;
    while i < 256 {
        // The smallest r with r^2 >= 256 (i + 1).
        let target = 256 * (i as u32 + 1);
        let mut r = 0u32;
        while r * r < target {
            r += 1;
        }
        t[i] = r as u16;
        i += 1;
    }
    t
};

impl<const F: u32> Add for Fx<F> {
    type Output = Self;
    #[inline]
    fn add(self, rhs: Self) -> Self {
        Self(self.0.saturating_add(rhs.0))
    }
}

impl<const F: u32> Sub for Fx<F> {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        Self(self.0.saturating_sub(rhs.0))
    }
}

impl<const F: u32> Mul for Fx<F> {
    type Output = Self;
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        self.mul_fx(rhs)
    }
}

impl<const F: u32> Div for Fx<F> {
    type Output = Self;
    #[inline]
    fn div(self, rhs: Self) -> Self {
        self.div_fx(rhs)
    }
}

impl<const F: u32> Neg for Fx<F> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self(self.0.saturating_neg())
    }
}

impl<const F: u32> AddAssign for Fx<F> {
    fn add_assign(&mut self, rhs: Self) {
        *self = *self + rhs;
    }
}

impl<const F: u32> SubAssign for Fx<F> {
    fn sub_assign(&mut self, rhs: Self) {
        *self = *self - rhs;
    }
}

impl<const F: u32> MulAssign for Fx<F> {
    fn mul_assign(&mut self, rhs: Self) {
        *self = *self * rhs;
    }
}

impl<const F: u32> fmt::Debug for Fx<F> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

impl<const F: u32> fmt::Display for Fx<F> {
    /// Decimal with six fractional digits, exact to that many digits (truncated).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let bits = self.0 as i64;
        let sign = if bits < 0 { "-" } else { "" };
        let mag = bits.unsigned_abs();
        let int = mag >> F;
        let frac = ((mag & ((1u64 << F) - 1)) as u128 * 1_000_000) >> F;
        write!(f, "{sign}{int}.{frac:06}")
    }
}

#[cfg(test)]
mod tests {
    use super::isqrt_u64;

    /// floor(sqrt(v)) by bisection on u128 squares.
    fn reference(v: u64) -> u64 {
        let (mut lo, mut hi) = (0u128, 1u128 << 32);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if mid * mid <= u128::from(v) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo as u64
    }

    /// `Fx::<F>::dot4` against the exact sum in i128, rounded half up and saturated.
    fn dot4_matches_the_exact_sum<const F: u32>() {
        use super::Fx;
        let reference = |a: [i32; 4], b: [i32; 4]| {
            let s: i128 = (0..4).map(|k| i128::from(a[k]) * i128::from(b[k])).sum();
            ((s + (1 << (F - 1))) >> F).clamp(i32::MIN.into(), i32::MAX.into()) as i32
        };
        let extremes = [
            i32::MIN,
            i32::MIN + 1,
            -(1 << F),
            -1,
            0,
            1,
            1 << F,
            i32::MAX,
        ];
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for i in 0..100_000 {
            let mut v = [0i32; 8];
            for e in &mut v {
                let r = next();
                // Near the limits (where the i64 sum overflows), or of any size.
                *e = if i % 2 == 0 {
                    extremes[(r % 8) as usize]
                } else {
                    (r as i32) >> (r >> 59)
                };
            }
            let (mut a, mut b) = ([v[0], v[1], v[2], v[3]], [v[4], v[5], v[6], v[7]]);
            if i % 3 == 0 {
                // The first two products sum past i64 (2^62 each) and the last two take it back
                // (about -2^62 each): a result in range, rounded from the low bits the odd
                // factors of the fourth set.
                let small = |k: usize| v[k] & 0xfff;
                a = [i32::MIN, i32::MIN, i32::MIN, i32::MAX - small(0)];
                b = [
                    i32::MIN,
                    i32::MIN,
                    i32::MAX - small(1),
                    i32::MIN + 1 + small(2),
                ];
            }
            let got = Fx::<F>::dot4(a.map(Fx::from_bits), b.map(Fx::from_bits)).to_bits();
            assert_eq!(got, reference(a, b), "{a:?} . {b:?}");
        }
    }

    #[test]
    fn dot4_rounds_the_exact_sum_once() {
        dot4_matches_the_exact_sum::<16>();
        dot4_matches_the_exact_sum::<1>();
        dot4_matches_the_exact_sum::<30>();
    }

    #[test]
    fn rsqrt_fast_is_close() {
        // r below 2^k / sqrt(v) by at most 2^-17 of it: r² v within 2^-16 below 2^2k (and
        // above it by truncation only, 1e-9 at most here).
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut worst = 0u128;
        for i in 0..300_000u64 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = if i < 200 {
                i + 1
            } else {
                (x >> (x % 64)).max(1)
            };
            let (r, k) = super::rsqrt_fast(v);
            assert!(r <= 1 << 31 && k >= 31, "{v}: {r} {k}");
            let product = u128::from(r) * u128::from(r) * u128::from(v);
            let exact = 1u128 << (2 * k);
            // Newton's step lands below the root; its truncations may lift it by a few units.
            assert!(product <= exact + (exact >> 28), "{v}: {r} {k}");
            assert!(exact.saturating_sub(product) <= exact >> 16, "{v}: {r} {k}");
            worst = worst.max(exact.saturating_sub(product) >> (2 * k - 40));
        }
        // Below the root somewhere by more than 2^-40: the Newton step is doing the work.
        assert!(worst > 0);
    }

    /// `rsqrt_fast` is one Newton step, exactly as its comments define it (`y0` the table's
    /// entry times 2^15, truncating each product), taken here in `u128`.
    #[test]
    fn rsqrt_fast_is_its_newton_step() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        for i in 0..300_000u64 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = match i {
                0..64 => 1 << i,
                64..128 => u64::MAX >> (i - 64),
                _ => (x >> (x % 64)).max(1),
            };
            let e = v.leading_zeros() & !1;
            let m = u128::from(v << e);
            let y0 = u128::from(super::RSQRT9_TABLE[(m >> 55) as usize - 128]) << 15;
            let t = ((m >> 32) * ((y0 * y0) >> 32)) >> 30;
            let y1 = (y0 * ((3 << 30) - t)) >> 31;
            assert_eq!(super::rsqrt_fast(v), (y1 as u64, 62 - e / 2), "{v}");
        }
    }

    #[test]
    fn rsqrt_is_close() {
        // r ≈ 2^k / sqrt(v) within a few units of r's last bit: r² v within 8 parts in 2^30 of
        // 2^2k (an error of one unit in r moves r² v by two parts in 2^30 at most).
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for i in 0..300_000u64 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = if i < 200 {
                i + 1
            } else {
                (x >> (x % 64)).max(1)
            };
            let (r, k) = super::rsqrt_u64(v);
            assert!((1 << 30..=1 << 31).contains(&r), "{v}: {r}");
            let product = u128::from(r) * u128::from(r) * u128::from(v);
            let exact = 1u128 << (2 * k);
            assert!(product.abs_diff(exact) <= (exact >> 30) * 8, "{v}: {r} {k}");
        }
    }

    #[test]
    fn isqrt_is_the_floor_of_the_root() {
        for v in 0..70_000u64 {
            assert_eq!(isqrt_u64(v), reference(v), "{v}");
        }
        for k in 0..64 {
            for d in [0u64, 1, 2, 3] {
                let v = (1u64 << k).wrapping_add(d).wrapping_sub(2);
                assert_eq!(isqrt_u64(v), reference(v), "{v}");
            }
        }
        for r in [u64::from(u32::MAX), 1 << 31, (1 << 31) - 1, 3_037_000_499] {
            for v in [r * r - 1, r * r, r * r + 1, r * r + 2 * r] {
                assert_eq!(isqrt_u64(v), reference(v), "{v}");
            }
        }
        let mut x = 0x1234_5678_9abc_def0u64;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = x >> (x % 64);
            assert_eq!(isqrt_u64(v), reference(v), "{v}");
        }
        assert_eq!(isqrt_u64(u64::MAX), reference(u64::MAX));
    }
}
