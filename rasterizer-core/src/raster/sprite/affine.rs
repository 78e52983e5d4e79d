//! The 2D affine transform of a sprite (16.16), and its inverse as the per-pixel steps through
//! texel space (32.32), found once per sprite with one exact division per entry.

use crate::math::{Angle, Fx16};

/// A 2D affine transform from texel space to screen pixels: texel point `(u, v)` (the image's
/// top-left corner is `(0, 0)`, texel `(i, j)` covers `[i, i + 1) x [j, j + 1)`) lands at
/// `(m[0][0] u + m[0][1] v + t[0], m[1][0] u + m[1][1] v + t[1])`, y down.
///
/// Range: every entry is [`Fx16`] (16.16 in an `i32`), so matrix entries and translations lie in
/// `[-32768, 32768)`; the constructors saturate there. A sprite whose quad reaches past the
/// guard band ([`crate::geom::GUARD_BAND_PIXELS`]) draws nothing, as a triangle would.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Affine {
    /// The linear part, row by row: `m[0]` gives x, `m[1]` gives y.
    pub m: [[Fx16; 2]; 2],
    /// The translation, in pixels: where texel point `(0, 0)` lands.
    pub t: [Fx16; 2],
}

impl Default for Affine {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Affine {
    /// Texel `(i, j)` onto pixel `(i, j)`.
    pub const IDENTITY: Self = Self {
        m: [[Fx16::ONE, Fx16::ZERO], [Fx16::ZERO, Fx16::ONE]],
        t: [Fx16::ZERO, Fx16::ZERO],
    };

    /// The identity moved so that the image's top-left corner lands on pixel `(x, y)`'s corner,
    /// saturated at the translation's range.
    pub const fn translation(x: i32, y: i32) -> Self {
        let mut a = Self::IDENTITY;
        a.t = [
            Fx16::saturate((x as i64) << 16),
            Fx16::saturate((y as i64) << 16),
        ];
        a
    }

    /// The image of `width` x `height` texels scaled by `scale`, turned by `angle` (clockwise on
    /// a y-down screen) about its centre, with that centre at `centre` (pixels, 16.16).
    ///
    /// The matrix comes from the integer sine table ([`Angle::sin_cos_q30`]), each entry rounded
    /// once; a scale or size that would leave the range saturates.
    pub fn rotate_scale(
        width: u32,
        height: u32,
        angle: Angle,
        scale: Fx16,
        centre: [Fx16; 2],
    ) -> Self {
        let (sin, cos) = angle.sin_cos_q30();
        let sc = i64::from(scale.to_bits());
        // 16.16 times 2.30, rounded back to 16.16; |product| < 2^61.
        let mul = |q30: i32| Fx16::saturate((sc * i64::from(q30) + (1 << 29)) >> 30);
        let (c, s) = (mul(cos), mul(sin));
        let m = [[c, Fx16::from_bits(s.to_bits().saturating_neg())], [s, c]];
        // t = centre - m (w/2, h/2), in 16.16 with the half folded in: m raw (2^31) times a side
        // (2^32) stays below 2^63.
        let (hw, hh) = (i64::from(width), i64::from(height));
        let off = |row: [Fx16; 2]| {
            (i64::from(row[0].to_bits()) * hw + i64::from(row[1].to_bits()) * hh) / 2
        };
        let t = [
            Fx16::saturate(i64::from(centre[0].to_bits()) - off(m[0])),
            Fx16::saturate(i64::from(centre[1].to_bits()) - off(m[1])),
        ];
        Self { m, t }
    }

    /// Where texel point `(u, v)` (whole texels) lands, in 16.16 pixels as `i64`. Exact: the
    /// products stay below `2^31 * 2^32`.
    #[inline]
    pub(crate) fn map(&self, u: i64, v: i64) -> (i64, i64) {
        let raw = |f: Fx16| i64::from(f.to_bits());
        (
            raw(self.t[0]) + raw(self.m[0][0]) * u + raw(self.m[0][1]) * v,
            raw(self.t[1]) + raw(self.m[1][0]) * u + raw(self.m[1][1]) * v,
        )
    }
}

/// Fractional bits of texel coordinates and of their steps.
pub(crate) const TEXEL_FRAC: u32 = 32;

/// The largest inverse entry accepted, in texels per pixel: `2^24`, an image squeezed to
/// `2^-24` of its size in some direction. Beyond it the sprite is treated as degenerate.
const MAX_STEP: i64 = 1 << (24 + TEXEL_FRAC);

/// The inverse of an [`Affine`]: the texel point of a pixel centre, `U(x, y) = u0 + du_dx (x - ax)
/// + du_dy (y - ay)` (and `v` alike), 32.32 in `i64`.
///
/// Evaluated with wrapping arithmetic: the terms may pass `i64` far from the sprite, but at a pixel
/// centre inside the drawn quad the exact sum is a texel point within a pixel's reach of the image
/// (`|u| < 4096 + 2^24`, far below `2^31`), so the sum modulo `2^64` is that value exactly, and
/// stepping it by `du_dx` per pixel gives the same bits as evaluating it anew: a sprite drawn in
/// bands equals the whole frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Inverse {
    pub anchor: (i64, i64),
    pub u0: i64,
    pub v0: i64,
    pub du_dx: i64,
    pub du_dy: i64,
    pub dv_dx: i64,
    pub dv_dy: i64,
}

impl Inverse {
    /// `None` for a singular matrix, or one whose inverse has an entry above `2^24` texels per pixel.
    pub fn new(a: &Affine) -> Option<Self> {
        let raw = |f: Fx16| i128::from(f.to_bits());
        let [[m00, m01], [m10, m11]] = a.m.map(|r| r.map(raw));
        // 32.32; below 2^63 in magnitude.
        let det = m00 * m11 - m01 * m10;
        if det == 0 {
            return None;
        }
        let (sign, det) = (det.signum(), det.abs());
        // inv = cofactor / det: in 32.32, cofactor_raw 2^16 / det_raw 2^32 = cofactor_raw 2^48 /
        // det_raw, rounded to nearest; the numerator stays below 2^80.
        let entry = |cof: i128| -> Option<i64> {
            let n = sign * cof * (1 << 48);
            let q = crate::wide::div_floor_i128(2 * n + det, 2 * det);
            (q.abs() <= i128::from(MAX_STEP)).then_some(q as i64)
        };
        let du_dx = entry(m11)?;
        let du_dy = entry(-m01)?;
        let dv_dx = entry(-m10)?;
        let dv_dy = entry(m00)?;
        // The anchor: the pixel of the translation, where the offsets stay small near the sprite.
        let anchor = (
            i64::from(a.t[0].to_bits() >> 16),
            i64::from(a.t[1].to_bits() >> 16),
        );
        // The anchor pixel's centre less the translation, in 16.16 (below 2^17 in magnitude).
        let dx = (anchor.0 << 16) + (1 << 15) - i64::from(a.t[0].to_bits());
        let dy = (anchor.1 << 16) + (1 << 15) - i64::from(a.t[1].to_bits());
        // 32.32 step times 16.16 offset, rounded back to 32.32: below 2^57 * 2^17.
        let at = |sx: i64, sy: i64| -> i64 {
            let p = i128::from(sx) * i128::from(dx) + i128::from(sy) * i128::from(dy);
            ((p + (1 << 15)) >> 16) as i64
        };
        Some(Self {
            anchor,
            u0: at(du_dx, du_dy),
            v0: at(dv_dx, dv_dy),
            du_dx,
            du_dy,
            dv_dx,
            dv_dy,
        })
    }

    /// The texel point `(u, v)` (32.32) of pixel `(x, y)`'s centre.
    #[inline(always)]
    pub fn at(&self, x: i32, y: i32) -> (i64, i64) {
        let ox = i64::from(x).wrapping_sub(self.anchor.0);
        let oy = i64::from(y).wrapping_sub(self.anchor.1);
        let u = self
            .u0
            .wrapping_add(self.du_dx.wrapping_mul(ox))
            .wrapping_add(self.du_dy.wrapping_mul(oy));
        let v = self
            .v0
            .wrapping_add(self.dv_dx.wrapping_mul(ox))
            .wrapping_add(self.dv_dy.wrapping_mul(oy));
        (u, v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identity_maps_centres_to_texel_centres() {
        let inv = Inverse::new(&Affine::translation(10, -3)).unwrap();
        assert_eq!(inv.at(10, -3), (1 << 31, 1 << 31));
        assert_eq!(
            inv.at(13, 0),
            ((3 << 32) + (1 << 31), (3 << 32) + (1 << 31))
        );
    }

    #[test]
    fn singular_and_extreme_matrices_have_no_inverse() {
        let mut a = Affine::IDENTITY;
        a.m = [[Fx16::ONE, Fx16::ONE], [Fx16::ONE, Fx16::ONE]];
        assert_eq!(Inverse::new(&a), None);
        // The smallest scale, 2^-16: 2^16 texels a pixel, inside the range.
        a.m = [[Fx16::EPSILON, Fx16::ZERO], [Fx16::ZERO, Fx16::EPSILON]];
        assert_eq!(Inverse::new(&a).map(|i| i.du_dx), Some(1 << 48));
        // Nearly singular: det = (2^30 + 1)(2^30 - 1) - 2^60 = -1 raw, 2^-32, for entries of
        // 2^14: an inverse of 2^46 texels a pixel, past the range.
        let f = Fx16::from_bits;
        a.m = [
            [f((1 << 30) + 1), f(1 << 30)],
            [f(1 << 30), f((1 << 30) - 1)],
        ];
        assert_eq!(Inverse::new(&a), None);
        // The largest entries: det = (2^31 - 1)^2 - 2^62 = 1 - 2^32 raw, an inverse of 2^15.
        a.m = [[Fx16::MAX, Fx16::MIN], [Fx16::MIN, Fx16::MAX]];
        assert!(Inverse::new(&a).is_some());
        a.m = [[Fx16::MIN, Fx16::ZERO], [Fx16::ZERO, Fx16::MAX]];
        a.t = [Fx16::MIN, Fx16::MAX];
        let inv = Inverse::new(&a).unwrap();
        let _ = inv.at(i32::MIN, i32::MAX);
    }

    #[test]
    fn rotate_scale_keeps_the_centre() {
        let c = [Fx16::from_int(100), Fx16::from_int(50)];
        let a = Affine::rotate_scale(32, 16, Angle::from_degrees(90), Fx16::from_int(2), c);
        // The image centre (16, 8) lands on the centre.
        assert_eq!(a.map(16, 8), (100 << 16, 50 << 16));
        // Clockwise on screen: +u (right) turns to +y (down).
        assert_eq!(a.m[1][0], Fx16::from_int(2));
        let a = Affine::rotate_scale(4096, 4096, Angle(12345), Fx16::MAX, c);
        let _ = Inverse::new(&a);
    }
}
