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
