//! Divisions of 64-bit and wider operands, in one place.
//!
//! A 32-bit microcontroller has no instruction for them: each is a library call
//! (`__aeabi_ldivmod` and kin on a Cortex-M, tens of cycles), although an x86 instruction count
//! shows one instruction. Every such division of the crate goes through these functions, so
//! that the `count-wide` feature (for the project's counting programs only) can keep them out of
//! line and a profiler counts their calls. Without the feature they inline as before.

/// `n / d`, unsigned, rounded down; `d` is never zero (the callers make sure).
// Kept for the stages that still need it; the vertex projection no longer does.
#[allow(dead_code)]
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
#[allow(dead_code)]
#[cfg_attr(feature = "count-wide", inline(never))]
#[cfg_attr(not(feature = "count-wide"), inline(always))]
pub(crate) fn div_floor_i128(n: i128, d: i128) -> i128 {
    if d <= 0 {
        return 0;
    }
    n.div_euclid(d)
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
    }
}
