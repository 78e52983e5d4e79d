//! Divisions of 64-bit and wider operands, and products wider than 64 bits, in one place.
//!
//! A 32-bit microcontroller has no instruction for them: each division is a library call
//! (`__aeabi_ldivmod` and kin on a Cortex-M, tens of cycles), and each 64 x 64 -> 128-bit
//! product four 32-bit multiplies with their carries (library calls on a Cortex-M0+), although
//! an x86 instruction count shows one instruction. Every such division and product of the
//! triangles' vertex, set-up, span and pixel work goes through these functions, so that the
//! `count-wide` feature (for the project's counting programs only) can keep them out of line
//! and a profiler counts their calls; without the feature they inline as before. (`Fx`'s
//! `const` quotient and square root, used per draw, when clipping and off the lighting plan,
//! cannot call them and are not counted; nor are the `i128` steps of a clipped or anti-aliased
//! line's and a sprite's set-up.) [`Reciprocal`] turns many divisions by one divisor into one.

/// `a b` in full: a 64 x 64 -> 128-bit product, unsigned.
#[cfg_attr(feature = "count-wide", inline(never))]
#[cfg_attr(not(feature = "count-wide"), inline(always))]
pub(crate) fn mul_u128(a: u64, b: u64) -> u128 {
    u128::from(a) * u128::from(b)
}

/// `a b` in full: a 64 x 64 -> 128-bit product, signed.
#[cfg_attr(feature = "count-wide", inline(never))]
#[cfg_attr(not(feature = "count-wide"), inline(always))]
pub(crate) fn mul_i128(a: i64, b: i64) -> i128 {
    i128::from(a) * i128::from(b)
}

/// `n / d`, unsigned, rounded down; `d` is never zero (the callers make sure).
#[cfg_attr(feature = "count-wide", inline(never))]
#[cfg_attr(not(feature = "count-wide"), inline(always))]
pub(crate) fn div_u64(n: u64, d: core::num::NonZeroU64) -> u64 {
    n / d
}

/// `floor(n / d)` for `d > 0` (Euclidean division, which equals the floor for a positive divisor).
/// A `d <= 0` would be a caller's bug: the result is then 0 rather than a panic.
#[cfg_attr(feature = "count-wide", inline(never))]
#[cfg_attr(not(feature = "count-wide"), inline(always))]
pub(crate) fn div_floor_i64(n: i64, d: i64) -> i64 {
    if d <= 0 {
        return 0;
    }
    n.div_euclid(d)
}

/// `floor(n / d)` for `d > 0` in `i128`; 0 for `d <= 0`, as [`div_floor_i64`].
#[cfg_attr(feature = "count-wide", inline(never))]
#[cfg_attr(not(feature = "count-wide"), inline(always))]
pub(crate) fn div_floor_i128(n: i128, d: i128) -> i128 {
    if d <= 0 {
        return 0;
    }
    divmod_euclid_i128(n, d).0
}

/// `(floor(n / d), n mod d)` for `d > 0`, the remainder in `0..d`; `(0, 0)` for `d <= 0`.
#[cfg_attr(feature = "count-wide", inline(never))]
#[cfg_attr(not(feature = "count-wide"), inline(always))]
pub(crate) fn divmod_floor_i64(n: i64, d: i64) -> (i64, i64) {
    if d <= 0 {
        return (0, 0);
    }
    (n.div_euclid(d), n.rem_euclid(d))
}

/// [`divmod_floor_i64`] in `i128`.
#[cfg_attr(feature = "count-wide", inline(never))]
#[cfg_attr(not(feature = "count-wide"), inline(always))]
pub(crate) fn divmod_floor_i128(n: i128, d: i128) -> (i128, i128) {
    if d <= 0 {
        return (0, 0);
    }
    divmod_euclid_i128(n, d)
}

/// `(floor(n / d), n mod d)` for `d > 0`. Operands that fit in 64 bits (nearly all) take one
/// 64-bit division; wider ones the compiler's 128-bit division on a 64-bit target (a library
/// routine with a hardware step), and [`divrem_long`] on a 32-bit one, which has no such
/// routine: there the compiler would expand each division inline into more than a kilobyte of
/// code. `const`, for [`crate::math::Fx`]'s constant conversions.
pub(crate) const fn divmod_euclid_i128(n: i128, d: i128) -> (i128, i128) {
    // A negative n is folded onto u = !n = -n - 1 >= 0: with u = q d + r, n = (-q - 1) d + (d
    // - 1 - r), whose remainder lies in 0..d as well.
    let neg = n < 0;
    let u = (if neg { !n } else { n }) as u128;
    let d = d as u128;
    let (q, r) = if (u | d) >> 64 == 0 {
        let (u, d) = (u as u64, d as u64);
        ((u / d) as u128, (u % d) as u128)
    } else {
        divrem_wide(u, d)
    };
    if neg {
        (!(q as i128), (d - 1 - r) as i128)
    } else {
        (q as i128, r as i128)
    }
}

/// `(u / d, u % d)` for `0 < d`, `u < 2^127`, as [`divmod_euclid_i128`] takes it on this target.
#[cfg(target_pointer_width = "64")]
const fn divrem_wide(u: u128, d: u128) -> (u128, u128) {
    let q = u / d;
    (q, u - q * d)
}

/// `(u / d, u % d)` for `0 < d`, `u < 2^127`, as [`divmod_euclid_i128`] takes it on this target.
#[cfg(not(target_pointer_width = "64"))]
const fn divrem_wide(u: u128, d: u128) -> (u128, u128) {
    divrem_long(u, d)
}

/// `(u / d, u % d)` for `0 < d`, `u < 2^127`, by shifting and subtracting one quotient bit at
/// a time from the divisor aligned under `u`'s top bit: small code, with only constant shifts
/// in the loop. (Built on every target, so that the host's tests check it.)
#[cfg_attr(target_pointer_width = "64", allow(dead_code))]
const fn divrem_long(mut u: u128, d: u128) -> (u128, u128) {
    if u < d {
        return (0, u);
    }
    let shift = d.leading_zeros() - u.leading_zeros();
    let mut step = d << shift;
    let mut q = 0u128;
    let mut k = 0;
    while k <= shift {
        q <<= 1;
        if u >= step {
            u -= step;
            q |= 1;
        }
        step >>= 1;
        k += 1;
    }
    (q, u)
}

/// `(n / d, n % d)` for `d > 0`: a 32-bit division when both operands fit in 32 bits (a
/// Cortex-M3/M4 has an instruction for it), else [`div_u64`]. The edge walks' operands fit for
/// every triangle narrower than a few thousand pixels.
#[inline(always)]
pub(crate) fn divrem_narrow(n: u64, d: core::num::NonZeroU64) -> (u64, u64) {
    if (n | d.get()) >> 32 == 0 {
        let (n, d) = (n as u32, d.get() as u32);
        // `d` is the non-zero divisor narrowed: never zero.
        let d = core::num::NonZeroU32::new(d).unwrap_or(core::num::NonZeroU32::MIN);
        (u64::from(n / d), u64::from(n % d))
    } else {
        let q = div_u64(n, d);
        (q, n - q * d.get())
    }
}

/// Quotients by one divisor for the price of one 64-bit division: `m = floor((2^64 - 1) / d)`
/// once, then each quotient is the high half of an unsigned 64 x 64-bit product
/// ([`Reciprocal::near`]), within one of `floor(n / d)`.
///
/// A negative `n` is folded onto `u = !n = -n - 1 >= 0`, whose quotient gives the floor back as
/// `!floor(u / d)`. Why within one: `u < 2^63` and `m > 2^64 / d - 1`, so `u m / 2^64` lies below
/// `u / d` by less than `u / 2^64 + u / (d 2^64) < 1`: its floor is the quotient or one less.
/// The remainder `u - q d` (in `0 .. 2 d`) would tell which, for a multiply, a compare and an add
/// a quotient that no caller needs: each uses the near quotient wherever it computes that
/// quantity, so that its paths agree to the bit.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Reciprocal {
    m: u64,
}

impl Reciprocal {
    /// The reciprocal of 1, which costs no division.
    pub(crate) const ONE: Self = Self { m: u64::MAX };

    /// The reciprocal of `d`.
    #[inline(always)]
    pub(crate) fn new(d: core::num::NonZeroU64) -> Self {
        Self {
            m: div_u64(u64::MAX, d),
        }
    }

    /// `floor(n / d)` or the integer next to it toward zero (see the type): for `n >= 0` the
    /// floor or one less, for `n < 0` the floor or one more. For every `n`, never a panic.
    #[inline(always)]
    pub(crate) fn near(&self, n: i64) -> i64 {
        // All ones for a negative n: u = !n then, n itself otherwise.
        let sign = n >> 63;
        let u = (n ^ sign) as u64;
        ((mul_u128(u, self.m) >> 64) as u64) as i64 ^ sign
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floors_and_never_panics() {
        let nz = |d| core::num::NonZeroU64::new(d).unwrap();
        assert_eq!(div_u64(u64::MAX, nz(1)), u64::MAX);
        assert_eq!(div_u64(7, nz(2)), 3);
        assert_eq!(div_floor_i64(-7, 2), -4);
        assert_eq!(div_floor_i64(7, 2), 3);
        assert_eq!(div_floor_i64(i64::MIN, 1), i64::MIN);
        assert_eq!(div_floor_i64(5, 0), 0);
        assert_eq!(div_floor_i64(5, -1), 0);
        assert_eq!(div_floor_i128(-7, 2), -4);
        assert_eq!(div_floor_i128(i128::MIN, 3), i128::MIN.div_euclid(3));
        assert_eq!(div_floor_i128(1, 0), 0);
        assert_eq!(divmod_floor_i64(-7, 2), (-4, 1));
        assert_eq!(divmod_floor_i64(7, 0), (0, 0));
        assert_eq!(divmod_floor_i128(-7, 3), (-3, 2));
        assert_eq!(divmod_floor_i128(7, -3), (0, 0));
    }

    #[test]
    fn wide_products_are_exact_at_the_extremes() {
        assert_eq!(mul_u128(u64::MAX, u64::MAX), u128::from(u64::MAX).pow(2));
        assert_eq!(mul_u128(1 << 63, 2), 1 << 64);
        assert_eq!(mul_i128(i64::MIN, i64::MIN), 1 << 126);
        assert_eq!(
            mul_i128(i64::MIN, i64::MAX),
            -(1i128 << 63) * i128::from(i64::MAX)
        );
        assert_eq!(mul_i128(-3, 5), -15);
    }

    /// Whether `q` is `n / d`'s near quotient: the floor, or its neighbour toward zero (a
    /// non-negative n's quotient may be one below its floor, a negative one's one above), and
    /// never larger in magnitude than the floor (a gradient's reach bound holds for it too).
    fn near_floor(q: i64, n: i64, d: u64) -> bool {
        let floor = i128::from(n).div_euclid(i128::from(d));
        let q = i128::from(q);
        let next = floor - i128::from(n >= 0) + i128::from(n < 0);
        (q == floor || q == next) && q.abs() <= floor.abs()
    }

    #[test]
    fn reciprocal_quotients_lie_next_to_the_floor() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let edge = [
            1,
            2,
            3,
            7,
            (1 << 32) - 1,
            1 << 32,
            1 << 61,
            (1 << 63) - 1,
            1 << 63,
            u64::MAX,
        ];
        let numerators = [0, 1, -1, i64::MAX, i64::MIN, i64::MAX - 5, i64::MIN + 5];
        let (mut off, mut tried) = (0, 0);
        for _ in 0..20_000 {
            // Divisors and numerators of every size, as the planes of tiny and huge triangles.
            let d = (next() >> (next() % 64)).max(1);
            let n = (next() as i64) >> (next() % 64);
            let r = Reciprocal::new(core::num::NonZeroU64::new(d).unwrap());
            for n in numerators.iter().copied().chain([n]) {
                let q = r.near(n);
                assert!(near_floor(q, n, d), "{n} / {d}: {q}");
                tried += 1;
                off += usize::from(i128::from(q) != i128::from(n).div_euclid(i128::from(d)));
            }
        }
        // The correction step would matter now and then (measured: 43,491 of 160,000).
        assert!(off > 20_000 && off < 90_000, "{off} of {tried}");
        for d in edge {
            let r = Reciprocal::new(core::num::NonZeroU64::new(d).unwrap());
            for n in numerators {
                assert!(near_floor(r.near(n), n, d), "{n} / {d}");
            }
        }
    }

    #[test]
    fn reciprocal_quotients_hold_at_the_extremes() {
        for d in [1u64, 2, 3, 1 << 40, (1 << 63) - 1, 1 << 63, u64::MAX] {
            let r = Reciprocal::new(core::num::NonZeroU64::new(d).unwrap());
            for n in [
                i64::MIN,
                i64::MAX,
                i64::MIN + 1,
                i64::MAX - 1,
                1 << 62,
                -(1 << 62),
                0,
                -1,
            ] {
                assert!(near_floor(r.near(n), n, d), "{n} / {d}");
            }
        }
    }

    #[test]
    fn wide_division_matches_the_compilers() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let wide = |hi: u64, lo: u64| (u128::from(hi) << 64 | u128::from(lo)) as i128;
        let edge = [
            0,
            1,
            -1,
            2,
            -2,
            i128::from(i64::MAX),
            i128::from(i64::MIN),
            i128::from(u64::MAX),
            1 << 64,
            -(1 << 64),
            i128::MAX,
            i128::MIN,
            i128::MIN + 1,
            i128::MAX - 1,
        ];
        let check = |n: i128, d: i128| {
            let want = (n.div_euclid(d), n.rem_euclid(d));
            assert_eq!(divmod_euclid_i128(n, d), want, "{n} / {d}");
        };
        for _ in 0..20_000 {
            // Operands of every width: both below 2^64, one above, both above.
            let n = wide(next(), next()) >> (next() % 128);
            let d = ((wide(next(), next()) >> (next() % 128)) as u128 >> 1).max(1) as i128;
            check(n, d);
            for e in edge {
                check(e, d);
                if e > 0 {
                    check(n, e);
                }
            }
        }
        for n in edge {
            for d in edge.into_iter().filter(|&d| d > 0) {
                check(n, d);
            }
        }
        // The long division itself, which the host's path above only takes on 32-bit targets.
        for _ in 0..20_000 {
            let u = (wide(next(), next()) >> (next() % 128)) as u128 >> 1;
            let d = ((wide(next(), next()) >> (next() % 128)) as u128 >> 1).max(1);
            for (u, d) in [
                (u, d),
                (u, 1),
                (u128::MAX >> 1, d),
                (u, u.max(1)),
                (d - 1, d),
            ] {
                assert_eq!(divrem_long(u, d), (u / d, u % d), "{u} / {d}");
            }
        }
    }

    #[test]
    fn narrow_division_matches_u64() {
        let nz = |d| core::num::NonZeroU64::new(d).unwrap();
        for (n, d) in [
            (0, 1),
            (7, 2),
            (u32::MAX as u64, 1),
            (1 << 32, 3),
            (5, 1 << 32),
            (u64::MAX, 7),
        ] {
            assert_eq!(divrem_narrow(n, nz(d)), (n / d, n % d), "{n} / {d}");
        }
    }
}
