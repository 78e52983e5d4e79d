//! Fixed-point maths for the geometry stages: the [`Scalar`] formats, vectors, 4x4 matrices and
//! integer trigonometry.
//!
//! Everything is generic over [`Scalar`] so that one pipeline runs on 16.16 (the default), other
//! fixed-point formats, or (behind a feature, for comparison only) `f32`. The fixed-point
//! implementation rounds every product once, half up, through `i64` and saturates instead of wrapping.

#[cfg(feature = "float")]
pub mod float;
pub mod fx;
pub mod mat;
pub mod trig;
pub mod vec;

pub use fx::{Fx, Fx16, Fx24, Fx8};
pub use mat::Mat4;
pub use trig::Angle;
pub use vec::{Vec3, Vec4};

use core::fmt::Debug;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// A number format the geometry pipeline can run on.
pub trait Scalar:
    Copy
    + PartialEq
    + PartialOrd
    + Default
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// An integer (saturating where the format is bounded).
    fn from_int(i: i32) -> Self;
    /// `num / den`, rounded to the format (saturating; `den = 0` saturates by `num`'s sign).
    fn from_ratio(num: i64, den: i64) -> Self;
    /// A 2.30 fixed-point value (the trigonometry tables' format).
    fn from_q30(v: i32) -> Self;
    /// Square root; 0 for negative input.
    fn sqrt(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// `a[0] b[0] + ... + a[3] b[3]`, rounded once where the format rounds.
    fn dot4(a: [Self; 4], b: [Self; 4]) -> Self;
    /// `sqrt(x² + y² + z²)`, with enough internal precision that tiny vectors keep their length.
    fn hypot3(x: Self, y: Self, z: Self) -> Self;
    /// The unit vector along `(x, y, z)`, or `None` for the zero vector; tiny vectors keep their
    /// direction.
    fn normalize3(x: Self, y: Self, z: Self) -> Option<(Self, Self, Self)> {
        let len = Self::hypot3(x, y, z);
        (len != Self::ZERO).then(|| (x / len, y / len, z / len))
    }
    /// `round(self * 2^bits)` as an integer, saturating at the `i32` range (NaN gives 0).
    fn to_scaled_int(self, bits: u32) -> i32;
    /// The raw integer of a fixed-point value (`value * 2^F`), or `None` for a floating-point
    /// format. The divide methods of [`crate::numerics`] other than exact division work on these.
    fn raw_bits(self) -> Option<i64> {
        None
    }
    /// The fractional bits of [`Scalar::raw_bits`]' integers (0 for a floating-point format).
    const RAW_FRAC: u32 = 0;
    /// The value of a raw integer, for a fixed-point format (the inverse of
    /// [`Scalar::raw_bits`], saturating); zero for a floating-point format, which has none.
    fn from_raw(_bits: i64) -> Self {
        Self::ZERO
    }
    /// `round(num * scale / (den * div))` as an integer (0 when `den * div <= 0`), the perspective
    /// divide and viewport in one step. `|scale|, |div| < 2^31`. Exact for fixed point: the only
    /// error is the final rounding, halves up.
    fn scaled_ratio(num: Self, den: Self, scale: i64, div: i64) -> i64;
    /// `a + (b - a) num / den`, rounded once (`den != 0`): the point where a clipping plane cuts
    /// an edge, without first rounding the ratio (which would move a far-away crossing point, and
    /// with it the visible edge, by the ratio's rounding times the edge's length).
    fn lerp_ratio(a: Self, b: Self, num: Self, den: Self) -> Self;
    /// The value in 16.16 bits (saturating), the format shaders interpolate positions and normals in.
    fn to_fx16_bits(self) -> i32;
    /// The value from 16.16 bits.
    fn from_fx16_bits(bits: i32) -> Self;
    /// `(sin, cos)` of an angle, from the default 256-entry table.
    fn sin_cos(a: Angle) -> (Self, Self) {
        Self::sin_cos_with::<{ trig::DEFAULT_TABLE }>(a)
    }
    /// `(sin, cos)` of an angle from an `N`-entry quarter-wave table: the table size is a
    /// compile-time choice (flash against accuracy, see [`trig`]).
    fn sin_cos_with<const N: usize>(a: Angle) -> (Self, Self) {
        let (s, c) = trig::sin_cos_table::<N>(a);
        (Self::from_q30(s), Self::from_q30(c))
    }
}

/// `x² + y² + z²` of raw values: at most `3 · 2^62`, so it fits `u64`.
#[inline]
fn square_sum(x: i32, y: i32, z: i32) -> u64 {
    let sq = |v: i32| (v.unsigned_abs() as u64) * (v.unsigned_abs() as u64);
    sq(x) + sq(y) + sq(z)
}

impl<const F: u32> Scalar for Fx<F> {
    const ZERO: Self = Fx::ZERO;
    const ONE: Self = Fx::ONE;

    fn from_int(i: i32) -> Self {
        Fx::from_int(i)
    }

    fn from_ratio(num: i64, den: i64) -> Self {
        Fx::from_ratio(num, den)
    }

    fn from_q30(v: i32) -> Self {
        Fx::<30>::from_bits(v).convert()
    }

    fn sqrt(self) -> Self {
        Fx::sqrt(self)
    }

    fn abs(self) -> Self {
        Fx::abs(self)
    }

    #[inline]
    fn dot4(a: [Self; 4], b: [Self; 4]) -> Self {
        Fx::dot4(a, b)
    }

    fn hypot3(x: Self, y: Self, z: Self) -> Self {
        // The squares keep 2F fractional bits: a vector of length 2^-F still has a length.
        let sq = square_sum(x.to_bits(), y.to_bits(), z.to_bits());
        Fx::from_bits(fx::isqrt_u64(sq).min(i32::MAX as u64) as i32)
    }

    #[inline]
    fn normalize3(x: Self, y: Self, z: Self) -> Option<(Self, Self, Self)> {
        let (x, y, z) = (x.to_bits(), y.to_bits(), z.to_bits());
        let sq = square_sum(x, y, z);
        if sq == 0 {
            return None;
        }
        // One reciprocal square root, r ≈ 2^k / sqrt(sq) (k >= 31 >= F + 1), then a product per
        // component: v 2^F / sqrt(sq) = v r 2^(F - k), |v r| < 2^62. The root keeps 29 bits
        // however short the vector, so tiny vectors keep their direction.
        let (r, k) = fx::rsqrt_u64(sq);
        let sh = k - F;
        let unit = |v: i32| Fx::saturate((i64::from(v) * r as i64 + (1 << (sh - 1))) >> sh);
        Some((unit(x), unit(y), unit(z)))
    }

    fn scaled_ratio(num: Self, den: Self, scale: i64, div: i64) -> i64 {
        // |num bits * scale| < 2^62 and |den bits * div| < 2^62: one i64 division.
        let n = num.to_bits() as i64 * scale;
        let d = den.to_bits() as i64 * div;
        if d <= 0 {
            return 0;
        }
        // floor((n + floor(d/2)) / d) rounds halves up: an exact half needs an even d.
        crate::wide::div_floor_i64(n + (d >> 1), d)
    }

    fn lerp_ratio(a: Self, b: Self, num: Self, den: Self) -> Self {
        let d = den.to_bits() as i128;
        if d == 0 {
            return a;
        }
        // |b - a| < 2^32 and |num| < 2^31: the product fits i128; used only when clipping.
        let n = (b.to_bits() as i128 - a.to_bits() as i128) * num.to_bits() as i128;
        Fx::saturate_i128(a.to_bits() as i128 + fx::round_div_i128(n, d))
    }

    fn to_fx16_bits(self) -> i32 {
        self.convert::<16>().to_bits()
    }

    fn from_fx16_bits(bits: i32) -> Self {
        Fx::<16>::from_bits(bits).convert()
    }

    #[inline(always)]
    fn raw_bits(self) -> Option<i64> {
        Some(i64::from(self.to_bits()))
    }

    const RAW_FRAC: u32 = F;

    #[inline(always)]
    fn from_raw(bits: i64) -> Self {
        Fx::saturate(bits)
    }

    fn to_scaled_int(self, bits: u32) -> i32 {
        let v = self.to_bits() as i64;
        let r = if bits >= F {
            v << (bits - F).min(32)
        } else {
            let sh = F - bits;
            (v + (1 << (sh - 1))) >> sh
        };
        r.clamp(i32::MIN as i64, i32::MAX as i64) as i32
    }
}
