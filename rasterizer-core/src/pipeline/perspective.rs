//! Perspective-correct values through the fused span loop ([`crate::numerics::Perspective`]).
//!
//! The loop interpolates three planes instead of the shader's values: `1 / w` and the two
//! barycentrics of vertices 1 and 2 divided by `w`, all affine in screen space. A pixel that
//! passes the depth test divides them back into its barycentrics (two 32-bit divisions, no
//! 64-bit one) and mixes the vertices' values from them, in the fixed point the shader's
//! [`Shading::pixel_fused`] reads. Depth stays affine in screen space, as in every mode.
//!
//! Precision: the three `1 / w` are scaled together so that the largest has 14 bits; a pixel
//! divides with 15 significant bits of its interpolated `1 / w`, so its barycentrics are within `2^-13` of
//! the exact ones, where the general span engine's are exact to 16 bits (a colour channel's
//! value moves by at most a thirtieth of a step; `docs/ACCURACY.md` measures the picture).
//!
//! A triangle of three values each in `2^7 ..= 2^16 - 2^8` (every colour shader's channels)
//! whose `1 / w` lie within a factor of 2 of each other (most triangles of a mesh) takes the
//! direct planes instead ([`DirectColor`]): each value times `1 / w`, and `1 / w`, so that a
//! pixel divides once, for a reciprocal of 14 or 15 significant bits, and multiplies each value
//! back (no mix of the vertices' values): its values are within `2^-12.8` of the exact ones,
//! relative (at most 9 units of the value: under a 200th of a step of a 5-bit channel, under
//! 0.04 of a step of an 8-bit one).
//!
//! Both set-ups cost more than the default path's, so a triangle the lean path takes is first
//! tested against the depths its bounding box holds, and dropped before its set-up when it
//! lies behind all of them ([`FusedColor::HIDDEN_TEST`]): the same pixels.

use super::Shading;
use crate::geom::{Varyings, MAX_VARYINGS};
use crate::math::Scalar;
use crate::numerics::{Dither, Numerics};
use crate::raster::fused::{FusedColor, FusedVertex, Precision};
use crate::raster::interp::ScreenVertex;
use core::num::NonZeroU32;

/// Bits of the largest `1 / w` of a triangle once the three are scaled together: the planes
/// (16 fractional bits) then stay below `2^30`, so a value the planes' rounding takes a unit
/// below zero reads as negative, not as a large one.
const Q_BITS: u32 = 14;
/// Significant bits of `1 / w` a pixel divides by.
const D_BITS: u32 = 15;
/// Fractional bits of the barycentrics a pixel divides out.
const L_BITS: u32 = 16;
/// Fractional bits of the three planes in the span loop: with values of at most `2^Q_BITS` they
/// stay below `2^32`.
const PRECISION: Precision = Precision {
    frac: 16,
    offset: 0,
};

/// The colour of a pixel from its perspective planes: the shader's values rebuilt from the
/// barycentrics, then the shader's own fused colour.
pub(super) struct PerspectiveColor<'a, S: Scalar, Sh: Shading<S>, N> {
    shading: &'a Sh,
    /// Vertex 0's values in the shader's fused fixed point (`value 2^FUSED_FRAC + FUSED_OFFSET`).
    base: [i64; MAX_VARYINGS],
    /// Vertex 1's and 2's values minus vertex 0's.
    d1: [i64; MAX_VARYINGS],
    d2: [i64; MAX_VARYINGS],
    _n: core::marker::PhantomData<(S, N)>,
}

impl<'a, S: Scalar, Sh: Shading<S>, N> PerspectiveColor<'a, S, Sh, N> {
    /// The three planes' vertices and the colour source of triangle `sv` (its values already
    /// adapted by [`Shading::triangle`]).
    pub(super) fn new<const BITS: u32>(
        shading: &'a Sh,
        sv: &[ScreenVertex<Sh::Varyings, BITS>; 3],
    ) -> ([FusedVertex<[i32; 3], BITS>; 3], Self) {
        // None becomes 0.
        let q = scaled_q(sv, Q_BITS).map(|q| q.max(1) as i32);
        let planes = [[0, 0, q[0]], [q[1], 0, q[1]], [0, q[2], q[2]]];
        // Written out, as in `DirectColor::new`.
        let fv = [
            (sv[0].p, sv[0].z, planes[0]),
            (sv[1].p, sv[1].z, planes[1]),
            (sv[2].p, sv[2].z, planes[2]),
        ];
        let n = Sh::Varyings::LEN.min(MAX_VARYINGS);
        let (mut base, mut d1, mut d2) =
            ([0i64; MAX_VARYINGS], [0; MAX_VARYINGS], [0; MAX_VARYINGS]);
        let [a, b, c] = [0, 1, 2].map(|k| sv[k].var);
        let (a, b, c) = (a.as_slice(), b.as_slice(), c.as_slice());
        for k in 0..n {
            base[k] = (i64::from(a[k]) << Sh::FUSED_FRAC) + i64::from(Sh::FUSED_OFFSET);
            d1[k] = i64::from(b[k]) - i64::from(a[k]);
            d2[k] = i64::from(c[k]) - i64::from(a[k]);
        }
        let color = Self {
            shading,
            base,
            d1,
            d2,
            _n: core::marker::PhantomData,
        };
        (fv, color)
    }

    /// The shader's accumulators at a pixel whose planes are `acc[0..3]`.
    #[inline(always)]
    fn values(&self, acc: &[u32; MAX_VARYINGS]) -> [u32; MAX_VARYINGS] {
        let [l1, l2] = barycentrics(acc[0], acc[1], acc[2]);
        let (l1, l2) = (i64::from(l1), i64::from(l2));
        let mut out = [0u32; MAX_VARYINGS];
        // L_BITS >= FUSED_FRAC (at most 16): the mix loses no bit the shader reads.
        let shift = L_BITS - Sh::FUSED_FRAC.min(L_BITS);
        let half = (1i64 << shift) >> 1;
        let n = Sh::Varyings::LEN.min(MAX_VARYINGS);
        for (k, o) in out.iter_mut().enumerate().take(n) {
            // |l| <= 2^16 and |d| < 2^33: the sum fits an i64. The result is the value's own
            // fixed point, which fits 32 bits; only its low 32 bits are kept.
            let mix = l1 * self.d1[k] + l2 * self.d2[k];
            *o = self.base[k].wrapping_add((mix + half) >> shift) as u32;
        }
        out
    }
}

/// A triangle's three `1 / w` scaled together by a shift so that the largest has `bits` bits
/// (only their ratios matter). Each q is any positive multiple of `1 / w` common to the three:
/// `2^20 / w` for a clipped triangle's vertices, the product of the other two corners' `w` for
/// the others (no division). At least 1 each.
#[inline(always)]
fn scaled_q<V, const BITS: u32>(sv: &[ScreenVertex<V, BITS>; 3], bits: u32) -> [u32; 3] {
    let q = [0, 1, 2].map(|k| sv[k].q.max(1) as u64);
    // Moved up so that the largest has its top bit at 63 (no bit lost), then down to `bits`
    // bits: what shifting each by the largest's excess over `bits` gives, either way.
    let up = (q[0] | q[1] | q[2]).leading_zeros();
    q.map(|q| ((q << up) >> (64 - bits)) as u32)
}

/// Bits of the largest `1 / w` of a triangle on the direct planes ([`DirectColor`]).
const DIRECT_Q_BITS: u32 = 15;
/// The least `1 / w` of a triangle on the direct planes, once scaled: at least half the
/// largest's top bit (every triangle whose `1 / w` lie within a factor of 2 qualifies), so that
/// a pixel's `1 / w` plane has its top bit at 29 or 30 and one fixed shift cuts it to
/// [`D_BITS`] bits or one fewer.
const DIRECT_Q_MIN: u32 = 1 << (DIRECT_Q_BITS - 2);
/// The values a triangle on the direct planes may have: below `2^16` with room above for the
/// quotients' error, so that `value 2^16` cannot wrap, and at least half a step of an 8-bit
/// channel (every colour shader's value holds that half step), so that each plane stays at
/// least `2^20` and its rounding (a few units) cannot take it below zero.
const DIRECT_VALUE_MAX: i32 = (1 << 16) - (1 << 8);
/// See [`DIRECT_VALUE_MAX`].
const DIRECT_VALUE_MIN: i32 = 1 << 7;
/// Fractional bits of the `1 / w` plane of the direct planes: the largest vertex's is below
/// `2^31`, and a plane of integers steps finely enough.
const DIRECT_Q_FRAC: u32 = 16;

/// The colour of a pixel from the direct planes: the values times `1 / w` (`acc[0..3]`), and
/// `1 / w` (`acc[3]`, with [`DIRECT_Q_FRAC`] fractional bits), all as integers.
pub(super) struct DirectColor<'a, S: Scalar, Sh: Shading<S>, N> {
    shading: &'a Sh,
    _n: core::marker::PhantomData<(S, N)>,
}

impl<'a, S: Scalar, Sh: Shading<S>, N> DirectColor<'a, S, Sh, N> {
    /// The direct planes' vertices of triangle `sv` (its values already adapted by
    /// [`Shading::triangle`]), or `None` when the triangle does not qualify: not three values,
    /// a value outside `DIRECT_VALUE_MIN ..= DIRECT_VALUE_MAX`, or its `1 / w` too far apart.
    #[inline(always)]
    pub(super) fn new<const BITS: u32>(
        shading: &'a Sh,
        sv: &[ScreenVertex<Sh::Varyings, BITS>; 3],
    ) -> Option<([FusedVertex<[i32; 4], BITS>; 3], Self)> {
        if Sh::Varyings::LEN != 3 {
            return None;
        }
        let q = scaled_q(sv, DIRECT_Q_BITS);
        if q[0].min(q[1]).min(q[2]) < DIRECT_Q_MIN {
            return None;
        }
        // A shader whose values are known to lie in the range needs no test of each.
        let (lo, hi) = Sh::VALUE_RANGE;
        let known = DIRECT_VALUE_MIN <= lo && hi <= DIRECT_VALUE_MAX;
        let mut planes = [[0i32; 4]; 3];
        for (k, plane) in planes.iter_mut().enumerate() {
            let v = sv[k].var.as_slice();
            for c in 0..3 {
                if !known && !(DIRECT_VALUE_MIN..=DIRECT_VALUE_MAX).contains(&v[c]) {
                    return None;
                }
                // Below 2^16 times below 2^15: an i32 (wrapping only for a shader whose values
                // leave the range it declares: wrong colours, not a panic).
                plane[c] = v[c].wrapping_mul(q[k] as i32);
            }
            plane[3] = (q[k] << DIRECT_Q_FRAC) as i32;
        }
        // Written out: mapped over an index, the closure stayed out of line with its bounds
        // checks.
        let fv = [
            (sv[0].p, sv[0].z, planes[0]),
            (sv[1].p, sv[1].z, planes[1]),
            (sv[2].p, sv[2].z, planes[2]),
        ];
        let color = Self {
            shading,
            _n: core::marker::PhantomData,
        };
        Some((fv, color))
    }

    /// The shader's accumulators at a pixel whose direct planes are `acc[0..4]`.
    #[inline(always)]
    fn values(&self, acc: &[u32; MAX_VARYINGS]) -> [u32; MAX_VARYINGS] {
        let mut out = [0u32; MAX_VARYINGS];
        let [a0, a1, a2] = direct_values([acc[0], acc[1], acc[2]], acc[3], Sh::FUSED_FRAC.min(16));
        out[0] = a0.wrapping_add(Sh::FUSED_OFFSET);
        out[1] = a1.wrapping_add(Sh::FUSED_OFFSET);
        out[2] = a2.wrapping_add(Sh::FUSED_OFFSET);
        out
    }
}

/// `value 2^frac` of each of `p` (a value times `1 / w`) from `q` (`1 / w` with
/// [`DIRECT_Q_FRAC`] fractional bits, from `2^29` up to `2^31` in a triangle): one 32-bit
/// division for a reciprocal of `q >> 16` (14 or 15 significant bits), then a 32 x 32 -> 64-bit
/// product each. The cut divisor lifts the result by up to `2^-13` of it, the truncated
/// reciprocal and shift lower it by up to `2^-16` and a unit: it lies within `9 2^-16` of the
/// exact quotient, plus a unit.
#[inline(always)]
fn direct_values(p: [u32; 3], q: u32, frac: u32) -> [u32; 3] {
    // Inside the triangle q is at least DIRECT_Q_MIN 2^16 = 2^29 (below 2^31) up to the
    // planes' rounding: d from 2^13 to 2^15. The floor of 1 only keeps a value from elsewhere
    // (no pixel of the triangle has one) from dividing by zero.
    let d = NonZeroU32::new(q >> 16).unwrap_or(NonZeroU32::MIN);
    // 2^31 / d > 2^16 for d below 2^15: 1 / q = r 2^-47, within 2^-13 + 2^-16.
    let r = u64::from((1u32 << 31) / d);
    // value 2^frac = p 2^DIRECT_Q_FRAC / q 2^frac = p r 2^(DIRECT_Q_FRAC + frac - 47). p < 2^32
    // and r <= 2^31: the product fits a u64.
    let down = 47 - DIRECT_Q_FRAC - frac;
    p.map(|p| ((u64::from(p) * r) >> down) as u32)
}

impl<S: Scalar, Sh: Shading<S>, N: Numerics> FusedColor<Sh::Color> for DirectColor<'_, S, Sh, N> {
    const PRECISION: Precision = Precision { frac: 0, offset: 0 };
    const AT: bool = !matches!(N::DITHER, Dither::None);
    const HIDDEN_TEST: bool = true;
    // Within a triangle each value times `1 / w` is at least `2^20` and below `2^31`.
    const PAIRED: bool = true;
    #[inline(always)]
    fn color(&self, acc: &[u32; MAX_VARYINGS]) -> Sh::Color {
        self.shading.pixel_fused(&self.values(acc))
    }
    #[inline(always)]
    fn color_at(&self, acc: &[u32; MAX_VARYINGS], x: i32, y: i32) -> Sh::Color {
        self.shading
            .pixel_fused_dithered(&self.values(acc), N::DITHER.threshold(x, y))
    }
}

/// The barycentrics `(b1 / q, b2 / q)` in `L_BITS` fixed point, from the planes' values at a
/// pixel (each `value 2^16`, below `2^30`; the planes' rounding may take a zero a unit below,
/// which wraps). Each division is of 32-bit operands: `q` is cut to `D_BITS` significant bits
/// and `b1`, `b2` by the same shift.
#[inline(always)]
fn barycentrics(b1: u32, b2: u32, q: u32) -> [u32; 2] {
    let q = (q as i32).max(1) as u32;
    let shift = (32 - q.leading_zeros()).saturating_sub(D_BITS);
    let d = (q >> shift).max(1);
    // Within the triangle 0 <= b <= q up to the planes' rounding; beyond it (a rounding away)
    // the barycentric is clamped to 0 ..= 1, so the shifted numerator stays below 2^32.
    let l = |b: u32| {
        let b = ((b as i32).max(0) as u32 >> shift).min(d);
        (b << L_BITS) / d
    };
    [l(b1), l(b2)]
}

impl<S: Scalar, Sh: Shading<S>, N: Numerics> FusedColor<Sh::Color>
    for PerspectiveColor<'_, S, Sh, N>
{
    const PRECISION: Precision = PRECISION;
    const AT: bool = !matches!(N::DITHER, Dither::None);
    const HIDDEN_TEST: bool = true;
    #[inline(always)]
    fn color(&self, acc: &[u32; MAX_VARYINGS]) -> Sh::Color {
        self.shading.pixel_fused(&self.values(acc))
    }
    #[inline(always)]
    fn color_at(&self, acc: &[u32; MAX_VARYINGS], x: i32, y: i32) -> Sh::Color {
        self.shading
            .pixel_fused_dithered(&self.values(acc), N::DITHER.threshold(x, y))
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// A xorshift32 stream from `seed` (not zero).
    fn xorshift(mut x: u32) -> impl FnMut() -> u32 {
        move || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x
        }
    }

    #[test]
    fn direct_values_are_within_their_bound() {
        // Against the exact quotient p 2^(16 + frac) / q over random planes as a triangle's
        // pixels see them (q from DIRECT_Q_MIN 2^16 up to 2^31, values up to DIRECT_VALUE_MAX):
        // within 2^-13 + 2^-16 = 9 2^-16 of it plus a unit, as the theory says (measured: 7.95 2^-16
        // beyond the unit).
        let mut next = xorshift(0x1357_9bdf);
        // The worst excess over a unit, in 2^-16 of the exact value: (excess, exact).
        let mut worst = (0u64, 1u64);
        for i in 0..200_000u32 {
            let frac = [16, 11, 8, 0][(i % 4) as usize];
            let q = (next() >> 1).max(DIRECT_Q_MIN << DIRECT_Q_FRAC);
            let value = u64::from(
                DIRECT_VALUE_MIN as u32
                    + next() % ((DIRECT_VALUE_MAX - DIRECT_VALUE_MIN) as u32 + 1),
            );
            // p = value q / 2^16 (a value times 1 / w), as the planes interpolate it.
            let p = ((value * u64::from(q)) >> DIRECT_Q_FRAC) as u32;
            let [got, _, _] = direct_values([p, 0, 0], q, frac);
            let exact = (u128::from(p) << (DIRECT_Q_FRAC + frac)) / u128::from(q);
            let exact = u64::try_from(exact).unwrap();
            let excess = exact.abs_diff(u64::from(got)).saturating_sub(1) << 16;
            let exact = exact.max(1);
            if u128::from(excess) * u128::from(worst.1) > u128::from(worst.0) * u128::from(exact) {
                worst = (excess, exact);
            }
        }
        assert!(worst.0 <= 9 * worst.1, "{worst:?}");
        // Values no pixel of a triangle has (a plane read outside it) give some value, with
        // no overflow or division by zero (the tests run with overflow checks).
        for q in [0, 1, 2, 1 << 14, (1 << 15) - 1, 1 << 31, u32::MAX] {
            for frac in [0, 16] {
                let _ = direct_values([0, 1, u32::MAX], q, frac);
            }
        }
    }

    #[test]
    fn scaled_q_keeps_the_ratios_of_one_over_w() {
        // A triangle's `1 / w` as the products of the other corners' `w` (the fused path's,
        // below 2^62) against the exact ratios: the largest gets exactly the bits asked for, and
        // each is within WORST thousandths of a unit of its exact share of it, `top w_min / w`
        // (one truncation each after the common shift; measured: 998).
        const WORST: u128 = 2_000;
        let mut next = xorshift(0x0bad_cafe);
        let mut worst = 0u128;
        for i in 0..100_000u32 {
            let bits = [DIRECT_Q_BITS, Q_BITS][(i % 2) as usize];
            // Any w from 1 to 2^31 - 1, or three within a factor of 2 (most of a mesh's).
            let w = if i % 3 == 0 {
                [0, 1, 2].map(|_| i64::from((next() >> 1).max(1)))
            } else {
                let base = i64::from(next() >> 2).max(1);
                [0, 1, 2].map(|_| base + i64::from(next()) % base)
            };
            let sv = [w[1] * w[2], w[0] * w[2], w[0] * w[1]].map(|q| ScreenVertex::<[i32; 0], 4> {
                p: crate::geom::SubPoint::raw(0, 0),
                z: 0,
                var: [],
                q,
            });
            let got = scaled_q(&sv, bits);
            let top = got[0].max(got[1]).max(got[2]);
            assert_eq!(32 - top.leading_zeros(), bits, "{w:?}");
            let wmin = w[0].min(w[1]).min(w[2]) as u128;
            for k in 0..3 {
                // |got - top wmin / w| in thousandths: |got w - top wmin| 1000 / w.
                let wk = w[k] as u128;
                let diff = (u128::from(got[k]) * wk).abs_diff(u128::from(top) * wmin);
                worst = worst.max(diff * 1000 / wk);
            }
        }
        assert!(worst <= WORST, "{worst}");
    }

    #[test]
    fn barycentrics_are_within_their_bound() {
        // Against the exact quotient over random planes, in units of 2^-32: both operands are
        // cut to 15 significant bits, so the error stays below 2^-13 (measured: at most 7.5e-5,
        // 2^-13.7).
        let mut next = xorshift(0x2468_ace1);
        let mut worst = 0u64;
        for _ in 0..200_000 {
            let q = (next() >> (2 + next() % 16)).max(1 << 16);
            let b1 = ((u64::from(next()) * u64::from(q)) >> 32) as u32;
            let b2 = ((u64::from(next()) * u64::from(q - b1)) >> 32) as u32;
            let [l1, l2] = barycentrics(b1, b2, q);
            for (l, b) in [(l1, b1), (l2, b2)] {
                assert!(l <= 1 << L_BITS);
                // |l / 2^16 - b / q| 2^32 = |l q - b 2^16| 2^16 / q.
                let diff = (i64::from(l) * i64::from(q) - (i64::from(b) << 16)).unsigned_abs();
                worst = worst.max((diff << 16) / u64::from(q));
            }
        }
        assert!(worst < 1 << 19, "{worst}");
    }
}
