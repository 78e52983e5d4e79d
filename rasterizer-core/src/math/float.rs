//! The comparison backend: [`Scalar`] for `f32`, with micromath's no-std functions.
//!
//! Behind the `float` feature and used only to measure what fixed point costs in accuracy and
//! time; nothing in the default build touches a float. micromath's functions are called through
//! `F32Ext::` paths so that tests, which link std, measure micromath and not std's exact versions.
//!
//! Two choices keep the comparison about the number format rather than about approximations:
//! micromath's square root is a bit-level estimate (measured: `sqrt(2) = 1.5`, `sqrt(10) = 3.25`,
//! up to 6 % off), so two Newton steps refine it to f32 precision; and sine and cosine come from the
//! same integer table as fixed point (error 5e-6) instead of micromath's polynomial (measured error
//! up to 1.1e-3, a pixel at 320 px).
#![allow(clippy::float_arithmetic, clippy::disallowed_types)]

use super::Scalar;
use micromath::F32Ext;

/// `v` rounded to the nearest integer (halves away from zero) and saturated to `[lo, hi]`; NaN
/// gives 0.
fn round_sat(v: f32, lo: i64, hi: i64) -> i64 {
    if v.is_nan() {
        return 0;
    }
    let r = F32Ext::round(v);
    if r <= lo as f32 {
        lo
    } else if r >= hi as f32 {
        hi
    } else {
        r as i64
    }
}

impl Scalar for f32 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;

    fn from_int(i: i32) -> Self {
        i as f32
    }

    fn from_ratio(num: i64, den: i64) -> Self {
        if den == 0 {
            return match num.signum() {
                1 => f32::MAX,
                -1 => f32::MIN,
                _ => 0.0,
            };
        }
        num as f32 / den as f32
    }

    fn from_q30(v: i32) -> Self {
        v as f32 / (1u32 << 30) as f32
    }

    fn sqrt(self) -> Self {
        // Zero, negative and NaN give 0; infinity stays.
        if self.is_nan() || self <= 0.0 || self.is_infinite() {
            return if self > 0.0 { self } else { 0.0 };
        }
        let mut s = F32Ext::sqrt(self);
        // Each Newton step squares the relative error: 6 % -> 0.2 % -> 2e-6 -> f32 rounding.
        for _ in 0..3 {
            s = 0.5 * (s + self / s);
        }
        s
    }

    fn abs(self) -> Self {
        F32Ext::abs(self)
    }

    fn dot4(a: [Self; 4], b: [Self; 4]) -> Self {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
    }

    fn hypot3(x: Self, y: Self, z: Self) -> Self {
        Scalar::sqrt(x * x + y * y + z * z)
    }

    fn scaled_ratio(num: Self, den: Self, scale: i64, div: i64) -> i64 {
        let d = den * div as f32;
        if d.is_nan() || d <= 0.0 {
            return 0;
        }
        round_sat(num * scale as f32 / d, i64::MIN / 2, i64::MAX / 2)
    }

    fn lerp_ratio(a: Self, b: Self, num: Self, den: Self) -> Self {
        if den == 0.0 {
            return a;
        }
        a + (b - a) * (num / den)
    }

    fn to_fx16_bits(self) -> i32 {
        self.to_scaled_int(16)
    }

    fn from_fx16_bits(bits: i32) -> Self {
        bits as f32 / 65536.0
    }

    fn to_scaled_int(self, bits: u32) -> i32 {
        let scaled = self * (1u64 << bits.min(62)) as f32;
        round_sat(scaled, i64::from(i32::MIN), i64::from(i32::MAX)) as i32
    }
}
