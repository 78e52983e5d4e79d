//! 3- and 4-component vectors over a [`Scalar`].

use super::Scalar;
use core::ops::{Add, Mul, Neg, Sub};

/// A 3D vector or point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Vec3<S> {
    /// x.
    pub x: S,
    /// y.
    pub y: S,
    /// z.
    pub z: S,
}

/// A homogeneous vector (clip-space position).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Vec4<S> {
    /// x.
    pub x: S,
    /// y.
    pub y: S,
    /// z.
    pub z: S,
    /// w.
    pub w: S,
}

impl<S: Scalar> Vec3<S> {
    /// A vector from components.
    pub const fn new(x: S, y: S, z: S) -> Self {
        Self { x, y, z }
    }

    /// The raw integers of a fixed-point vector's components (`None` for `f32`).
    #[inline(always)]
    pub(crate) fn raw_bits(self) -> Option<[i64; 3]> {
        Some([self.x.raw_bits()?, self.y.raw_bits()?, self.z.raw_bits()?])
    }

    /// From integers.
    pub fn from_ints(x: i32, y: i32, z: i32) -> Self {
        Self::new(S::from_int(x), S::from_int(y), S::from_int(z))
    }

    /// Dot product, rounded once.
    pub fn dot(self, o: Self) -> S {
        S::dot4([self.x, self.y, self.z, S::ZERO], [o.x, o.y, o.z, S::ZERO])
    }

    /// Cross product, each component rounded once.
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            S::dot4(
                [self.y, -self.z, S::ZERO, S::ZERO],
                [o.z, o.y, S::ZERO, S::ZERO],
            ),
            S::dot4(
                [self.z, -self.x, S::ZERO, S::ZERO],
                [o.x, o.z, S::ZERO, S::ZERO],
            ),
            S::dot4(
                [self.x, -self.y, S::ZERO, S::ZERO],
                [o.y, o.x, S::ZERO, S::ZERO],
            ),
        )
    }

    /// A normal of the triangle `p0`, `p1`, `p2` (counter-clockwise seen from its front), of no
    /// particular length (its largest component between one and two): the cross product of its
    /// edges, without the rounding of small products.
    ///
    /// Only the direction is wanted. For a small triangle (edges of a few hundredths, as in a
    /// mesh of some thousand triangles scaled to the unit sphere) the plain product has
    /// components of a few dozen units of 2^-16 in 16.16, and rounding them turns the normal by up
    /// to a degree. A fixed-point format takes the product of the raw edges exactly (in `i64`) and
    /// keeps its leading bits; a floating-point one doubles both edges (exactly) until the larger
    /// one's largest component reaches one half.
    // Called once a face on both the flat and the face-normal paths: the hint keeps it inlined
    // in a program that has both, where the compiler had kept one copy out of line.
    #[inline]
    pub fn face_normal(p0: Self, p1: Self, p2: Self) -> Self {
        let (mut a, mut b) = (p1 - p0, p2 - p0);
        let raw = |v: S| {
            v.raw_bits()
                .filter(|r| (i64::from(i32::MIN)..=i64::from(i32::MAX)).contains(r))
        };
        if let (Some(ax), Some(ay), Some(az), Some(bx), Some(by), Some(bz)) =
            (raw(a.x), raw(a.y), raw(a.z), raw(b.x), raw(b.y), raw(b.z))
        {
            // i32 factors: each product lies in (-2^62, 2^62] and no difference of two reaches
            // 2^63, so the components are exact.
            let c = [ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx];
            let m = c.iter().map(|v| v.unsigned_abs()).max().unwrap_or(0);
            if m == 0 {
                return Self::default();
            }
            // The largest component's leading bit at 2^F: a value in [1, 2).
            let lead = i64::from(m.ilog2()) - i64::from(S::RAW_FRAC);
            let scale = |v: i64| S::from_raw(if lead >= 0 { v >> lead } else { v << -lead });
            return Self::new(scale(c[0]), scale(c[1]), scale(c[2]));
        }
        let half = S::from_ratio(1, 2);
        let bigger = |x: S, y: S| if y > x { y } else { x };
        let largest = |v: Self| bigger(bigger(v.x.abs(), v.y.abs()), v.z.abs());
        let mut m = bigger(largest(a), largest(b));
        // Components below one half, doubled: at most one, so the product's are at most two.
        // Sixteen doublings reach one half from 2^-17; a smaller (or zero) edge is left there.
        for _ in 0..16 {
            if m >= half {
                break;
            }
            a = a + a;
            b = b + b;
            m = m + m;
        }
        a.cross(b)
    }

    /// Length.
    pub fn length(self) -> S {
        S::hypot3(self.x, self.y, self.z)
    }

    /// The unit vector in the same direction, or `None` for a zero-length vector.
    pub fn normalize(self) -> Option<Self> {
        let (x, y, z) = S::normalize3(self.x, self.y, self.z)?;
        Some(Self::new(x, y, z))
    }

    /// Each component times `k`.
    pub fn scale(self, k: S) -> Self {
        Self::new(self.x * k, self.y * k, self.z * k)
    }

    /// The point with `w = 1`.
    pub fn to_point4(self) -> Vec4<S> {
        Vec4::new(self.x, self.y, self.z, S::ONE)
    }

    /// The direction with `w = 0`.
    pub fn to_dir4(self) -> Vec4<S> {
        Vec4::new(self.x, self.y, self.z, S::ZERO)
    }
}

impl<S: Scalar> Vec4<S> {
    /// A vector from components.
    pub const fn new(x: S, y: S, z: S, w: S) -> Self {
        Self { x, y, z, w }
    }

    /// The components as an array.
    pub fn to_array(self) -> [S; 4] {
        [self.x, self.y, self.z, self.w]
    }

    /// `x, y, z` without `w`.
    pub fn xyz(self) -> Vec3<S> {
        Vec3::new(self.x, self.y, self.z)
    }

    /// Linear interpolation `self + (o - self) t`.
    pub fn lerp(self, o: Self, t: S) -> Self {
        Self::new(
            self.x + (o.x - self.x) * t,
            self.y + (o.y - self.y) * t,
            self.z + (o.z - self.z) * t,
            self.w + (o.w - self.w) * t,
        )
    }
}

impl<S: Scalar> Add for Vec3<S> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<S: Scalar> Sub for Vec3<S> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<S: Scalar> Neg for Vec3<S> {
    type Output = Self;
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

impl<S: Scalar> Mul<S> for Vec3<S> {
    type Output = Self;
    fn mul(self, k: S) -> Self {
        self.scale(k)
    }
}
