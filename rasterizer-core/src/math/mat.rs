//! 4x4 matrices: the transforms, the look-at camera and the projections.
//!
//! Column vectors, `p' = M p`; right-handed world, the camera looking down -z as in OpenGL; clip
//! space keeps `-w <= x, y, z <= w`. `a.then(b)` is "a, then b" (`b * a`). Every entry of a product is
//! one [`Scalar::dot4`], so fixed-point products round once per entry.

use super::trig::DEFAULT_TABLE;
use super::{Angle, Scalar, Vec3, Vec4};

/// A 4x4 matrix, row-major storage.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mat4<S> {
    /// `m[row][column]`.
    pub m: [[S; 4]; 4],
}

impl<S: Scalar> Default for Mat4<S> {
    fn default() -> Self {
        Self::identity()
    }
}

impl<S: Scalar> Mat4<S> {
    /// From rows.
    pub const fn from_rows(m: [[S; 4]; 4]) -> Self {
        Self { m }
    }

    /// The identity.
    pub fn identity() -> Self {
        Self::scale(S::ONE, S::ONE, S::ONE)
    }

    /// Column `c`.
    fn column(&self, c: usize) -> [S; 4] {
        [self.m[0][c], self.m[1][c], self.m[2][c], self.m[3][c]]
    }

    /// `self * rhs`: apply `rhs` first, then `self`.
    pub fn mul_mat(&self, rhs: &Self) -> Self {
        let mut out = [[S::ZERO; 4]; 4];
        for (r, row) in out.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = S::dot4(self.m[r], rhs.column(c));
            }
        }
        Self { m: out }
    }

    /// This transform followed by `next`: `next * self`.
    pub fn then(&self, next: &Self) -> Self {
        next.mul_mat(self)
    }

    /// `self * v`.
    #[inline]
    pub fn transform(&self, v: Vec4<S>) -> Vec4<S> {
        let a = v.to_array();
        Vec4::new(
            S::dot4(self.m[0], a),
            S::dot4(self.m[1], a),
            S::dot4(self.m[2], a),
            S::dot4(self.m[3], a),
        )
    }

    /// Transforms a point (`w = 1`).
    #[inline]
    pub fn transform_point(&self, p: Vec3<S>) -> Vec4<S> {
        self.transform(p.to_point4())
    }

    /// Transforms a direction (`w = 0`), ignoring translation.
    pub fn transform_dir(&self, d: Vec3<S>) -> Vec3<S> {
        self.transform(d.to_dir4()).xyz()
    }

    /// The transpose.
    pub fn transpose(&self) -> Self {
        let mut out = self.m;
        for (r, row) in out.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = self.m[c][r];
            }
        }
        Self { m: out }
    }

    /// Whether the transform mirrors: its upper 3x3 (the linear part of an affine transform) has
    /// a negative determinant, as a reflection ([`Mat4::reflect_xy`] and friends) or a negative
    /// scale on one or three axes has. Mirroring reverses the winding of every triangle it
    /// carries. Exact for the fixed-point formats (the determinant of the raw integers); a
    /// transform that flattens (determinant zero) does not mirror.
    pub fn mirrors(&self) -> bool {
        let m = &self.m;
        let raw = |r: usize, c: usize| {
            m[r][c]
                .raw_bits()
                .filter(|b| (i64::from(i32::MIN)..=i64::from(i32::MAX)).contains(b))
        };
        let mut e = [[0i64; 3]; 3];
        let mut exact = true;
        for (r, row) in e.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                match raw(r, c) {
                    Some(b) => *v = b,
                    None => exact = false,
                }
            }
        }
        if exact {
            // i32 entries: each 2x2 minor is exact in i64 (no difference of two products reaches
            // 2^63), and each entry times its minor in i128.
            let minor = |a: usize, b: usize| e[1][a] * e[2][b] - e[1][b] * e[2][a];
            let term = |c: usize, minor: i64| i128::from(e[0][c]) * i128::from(minor);
            return term(0, minor(1, 2)) - term(1, minor(0, 2)) + term(2, minor(0, 1)) < 0;
        }
        // A floating-point format: its own arithmetic (NaN mirrors nothing).
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        det < S::ZERO
    }

    /// The same transform with its upper 3x3 made orthonormal again (Gram-Schmidt on the rows, the
    /// third row rebuilt as a cross product), translation kept. Long chains of composed rotations
    /// drift from orthonormal by rounding; calling this every few hundred compositions holds the
    /// drift at the rounding of one step. `None` if the rows have collapsed.
    pub fn renormalized(&self) -> Option<Self> {
        let row = |r: usize| Vec3::new(self.m[r][0], self.m[r][1], self.m[r][2]);
        let r0 = row(0).normalize()?;
        let r1 = row(1);
        let r1 = (r1 - r0.scale(r1.dot(r0))).normalize()?;
        let r2 = r0.cross(r1);
        let mut m = self.m;
        for (r, v) in [r0, r1, r2].iter().enumerate() {
            m[r][0] = v.x;
            m[r][1] = v.y;
            m[r][2] = v.z;
        }
        Some(Self { m })
    }

    /// Scale along the axes.
    pub fn scale(x: S, y: S, z: S) -> Self {
        let (o, l) = (S::ZERO, S::ONE);
        Self::from_rows([[x, o, o, o], [o, y, o, o], [o, o, z, o], [o, o, o, l]])
    }

    /// Translation by `t`.
    pub fn translation(t: Vec3<S>) -> Self {
        let (o, l) = (S::ZERO, S::ONE);
        Self::from_rows([[l, o, o, t.x], [o, l, o, t.y], [o, o, l, t.z], [o, o, o, l]])
    }

    /// Rotation about x by `a` (counter-clockwise looking from +x towards the origin).
    pub fn rotation_x(a: Angle) -> Self {
        Self::rotation_x_with::<DEFAULT_TABLE>(a)
    }

    /// [`Mat4::rotation_x`] with sine and cosine from an `N`-entry table.
    pub fn rotation_x_with<const N: usize>(a: Angle) -> Self {
        let (s, c) = S::sin_cos_with::<N>(a);
        let (o, l) = (S::ZERO, S::ONE);
        Self::from_rows([[l, o, o, o], [o, c, -s, o], [o, s, c, o], [o, o, o, l]])
    }

    /// Rotation about y by `a`.
    pub fn rotation_y(a: Angle) -> Self {
        Self::rotation_y_with::<DEFAULT_TABLE>(a)
    }

    /// [`Mat4::rotation_y`] with sine and cosine from an `N`-entry table.
    pub fn rotation_y_with<const N: usize>(a: Angle) -> Self {
        let (s, c) = S::sin_cos_with::<N>(a);
        let (o, l) = (S::ZERO, S::ONE);
        Self::from_rows([[c, o, s, o], [o, l, o, o], [-s, o, c, o], [o, o, o, l]])
    }

    /// Rotation about z by `a`.
    pub fn rotation_z(a: Angle) -> Self {
        Self::rotation_z_with::<DEFAULT_TABLE>(a)
    }

    /// [`Mat4::rotation_z`] with sine and cosine from an `N`-entry table.
    pub fn rotation_z_with<const N: usize>(a: Angle) -> Self {
        let (s, c) = S::sin_cos_with::<N>(a);
        let (o, l) = (S::ZERO, S::ONE);
        Self::from_rows([[c, -s, o, o], [s, c, o, o], [o, o, l, o], [o, o, o, l]])
    }

    /// Shear: `x += xy y + xz z`, `y += yx x + yz z`, `z += zx x + zy z`.
    pub fn shear(xy: S, xz: S, yx: S, yz: S, zx: S, zy: S) -> Self {
        let (o, l) = (S::ZERO, S::ONE);
        Self::from_rows([[l, xy, xz, o], [yx, l, yz, o], [zx, zy, l, o], [o, o, o, l]])
    }

    /// Reflection in the xy plane (z negated).
    pub fn reflect_xy() -> Self {
        Self::scale(S::ONE, S::ONE, -S::ONE)
    }

    /// Reflection in the yz plane (x negated).
    pub fn reflect_yz() -> Self {
        Self::scale(-S::ONE, S::ONE, S::ONE)
    }

    /// Reflection in the xz plane (y negated).
    pub fn reflect_xz() -> Self {
        Self::scale(S::ONE, -S::ONE, S::ONE)
    }

    /// The view matrix of a camera at `eye` looking at `target` with `up` roughly up; `None` when
    /// `eye == target` or `up` is parallel to the view direction.
    pub fn look_at(eye: Vec3<S>, target: Vec3<S>, up: Vec3<S>) -> Option<Self> {
        let f = (target - eye).normalize()?;
        let s = f.cross(up).normalize()?;
        let u = s.cross(f);
        let o = S::ZERO;
        Some(Self::from_rows([
            [s.x, s.y, s.z, -s.dot(eye)],
            [u.x, u.y, u.z, -u.dot(eye)],
            [-f.x, -f.y, -f.z, f.dot(eye)],
            [o, o, o, S::ONE],
        ]))
    }

    /// OpenGL's perspective projection: vertical field of view `fov_y`, `aspect` = width / height,
    /// clip planes at `near` and `far` (`0 < near < far`). `None` for a degenerate field of view or
    /// planes.
    pub fn perspective(fov_y: Angle, aspect: S, near: S, far: S) -> Option<Self> {
        Self::perspective_with::<DEFAULT_TABLE>(fov_y, aspect, near, far)
    }

    /// [`Mat4::perspective`] with sine and cosine from an `N`-entry table.
    pub fn perspective_with<const N: usize>(
        fov_y: Angle,
        aspect: S,
        near: S,
        far: S,
    ) -> Option<Self> {
        // cot(fov / 2) = (1 + cos fov) / sin fov: the whole angle, so an odd number of angle units
        // is not rounded down by halving it first.
        let (s, c) = S::sin_cos_with::<N>(fov_y);
        if s <= S::ZERO || aspect <= S::ZERO || near <= S::ZERO || far <= near {
            return None;
        }
        let f = (S::ONE + c) / s;
        let o = S::ZERO;
        let depth = near - far;
        Some(Self::from_rows([
            [f / aspect, o, o, o],
            [o, f, o, o],
            [
                o,
                o,
                (far + near) / depth,
                // 2 far near / (near - far) without forming far * near, which saturates (and
                // silently gives a wrong matrix) once it passes the format's range.
                (near + near) * (far / depth),
            ],
            [o, o, -S::ONE, o],
        ]))
    }

    /// The simple focal-distance projection of course pipelines: the viewer on the +z axis at distance
    /// `d` from the `z = 0` plane, looking towards -z, with `w = 1 - z / d`. After the divide, points in
    /// the `z = 0` plane keep their size and nearer points grow. `None` when `d <= 0`.
    pub fn focal(d: S) -> Option<Self> {
        if d <= S::ZERO {
            return None;
        }
        let (o, l) = (S::ZERO, S::ONE);
        Some(Self::from_rows([
            [l, o, o, o],
            [o, l, o, o],
            [o, o, l, o],
            [o, o, -(l / d), l],
        ]))
    }
}
