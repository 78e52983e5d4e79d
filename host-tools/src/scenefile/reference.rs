//! The number formats the 3D part can run in: 16.16 (what firmware runs), `f32` (the core's
//! `float` feature) and [`F64`], an `f64` reference written here.
//!
//! [`F64`] implements [`Scalar`] with plain `f64` arithmetic and exact sine and cosine of the
//! angle (the core's `f32` takes them from the same integer table as fixed point), so running the
//! same pipeline in it shows what the geometry would be with (almost) no rounding. Everything after
//! the perspective divide is integer in every format, so all three share the rasterizer, the
//! lighting's integer stages and the 16.16 interpolation of Phong's normals.

use rasterizer_core::math::Scalar;
use rasterizer_core::prelude::*;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A scalar the scene can be rendered in: [`Scalar`] plus a conversion from the scene's `f64`s.
pub trait Real: Scalar + 'static {
    /// Short name for reports.
    const NAME: &'static str;
    /// The nearest value (saturating where the format is bounded).
    fn from_f64(v: f64) -> Self;
}

impl Real for Fx16 {
    const NAME: &'static str = "16.16";
    fn from_f64(v: f64) -> Self {
        // `as` saturates (and maps NaN to 0).
        Fx16::from_bits((v * 65536.0).round() as i32)
    }
}

impl Real for f32 {
    const NAME: &'static str = "f32";
    fn from_f64(v: f64) -> Self {
        v as f32
    }
}

impl Real for F64 {
    const NAME: &'static str = "f64";
    fn from_f64(v: f64) -> Self {
        F64(v)
    }
}

/// `f64` as a pipeline scalar: the reference format of `compare`.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct F64(pub f64);

macro_rules! binop {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for F64 {
            type Output = F64;
            #[inline]
            fn $f(self, o: F64) -> F64 {
                F64(self.0 $op o.0)
            }
        }
    };
}
binop!(Add, add, +);
binop!(Sub, sub, -);
binop!(Mul, mul, *);
binop!(Div, div, /);

impl Neg for F64 {
    type Output = F64;
    fn neg(self) -> F64 {
        F64(-self.0)
    }
}

/// `v` rounded half away from zero and saturated to `[lo, hi]`; NaN gives 0.
fn round_sat(v: f64, lo: i64, hi: i64) -> i64 {
    if v.is_nan() {
        0
    } else {
        (v.round() as i64).clamp(lo, hi)
    }
}

impl Scalar for F64 {
    const ZERO: Self = F64(0.0);
    const ONE: Self = F64(1.0);

    fn from_int(i: i32) -> Self {
        F64(f64::from(i))
    }

    fn from_ratio(num: i64, den: i64) -> Self {
        if den == 0 {
            return F64(match num.signum() {
                1 => f64::MAX,
                -1 => f64::MIN,
                _ => 0.0,
            });
        }
        F64(num as f64 / den as f64)
    }

    fn from_q30(v: i32) -> Self {
        F64(f64::from(v) / f64::from(1u32 << 30))
    }

    fn sqrt(self) -> Self {
        F64(if self.0 > 0.0 { self.0.sqrt() } else { 0.0 })
    }

    fn abs(self) -> Self {
        F64(self.0.abs())
    }

    fn dot4(a: [Self; 4], b: [Self; 4]) -> Self {
        F64(a[0].0 * b[0].0 + a[1].0 * b[1].0 + a[2].0 * b[2].0 + a[3].0 * b[3].0)
    }

    fn hypot3(x: Self, y: Self, z: Self) -> Self {
        F64((x.0 * x.0 + y.0 * y.0 + z.0 * z.0).sqrt())
    }

    fn to_scaled_int(self, bits: u32) -> i32 {
        let scaled = self.0 * (1u64 << bits.min(62)) as f64;
        round_sat(scaled, i64::from(i32::MIN), i64::from(i32::MAX)) as i32
    }

    fn scaled_ratio(num: Self, den: Self, scale: i64, div: i64) -> i64 {
        let d = den.0 * div as f64;
        if d.is_nan() || d <= 0.0 {
            return 0;
        }
        round_sat(num.0 * scale as f64 / d, i64::MIN / 2, i64::MAX / 2)
    }

    fn lerp_ratio(a: Self, b: Self, num: Self, den: Self) -> Self {
        if den.0 == 0.0 {
            return a;
        }
        F64(a.0 + (b.0 - a.0) * (num.0 / den.0))
    }

    fn to_fx16_bits(self) -> i32 {
        self.to_scaled_int(16)
    }

    fn from_fx16_bits(bits: i32) -> Self {
        F64(f64::from(bits) / 65536.0)
    }

    fn sin_cos_with<const N: usize>(a: Angle) -> (Self, Self) {
        let t = f64::from(a.0) / 65536.0 * std::f64::consts::TAU;
        (F64(t.sin()), F64(t.cos()))
    }
}
