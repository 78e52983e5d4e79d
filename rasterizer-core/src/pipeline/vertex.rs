//! The vertex scratch: each mesh vertex transformed, projected and shaded at most once a frame.
//!
//! A draw call takes a slice of [`VertexSlot`]s from the caller, one per mesh vertex. When the
//! draw begins, every slot gets its vertex's projected screen position (26.6 by default) and
//! depth; the first visible triangle that uses a vertex adds the shader's values, packed
//! ([`crate::shade::Packed`]: three `u16` channels for the colour shaders, so a Gouraud slot is 16 bytes).
//! Vertices beyond the slice's length are processed again by every triangle that uses them: a
//! short scratch is slower, never wrong.

use super::Pipeline;
use crate::clip::polygon::outcode;
use crate::cull::Cull;
use crate::depth::DepthTest;
use crate::geom::SubPoint;
use crate::math::{Mat4, Scalar, Vec3, Vec4};
use crate::mesh::MeshSource;
use crate::numerics::{reciprocal, Divide, Numerics};
use crate::shade::{Packed, Shading, VertexIn};
use crate::transform::Viewport;
use embedded_graphics_core::pixelcolor::Rgb888;
use embedded_graphics_core::prelude::RgbColor;

/// Marks a slot whose vertex lies outside the clip volume's guard band (its outcode is in `y`).
pub(crate) const OUTSIDE: i32 = i32::MIN + 1;
/// The smallest screen x a projected vertex keeps, above the mark (far outside the guard band, so
/// it never draws anyway).
pub(crate) const X_MIN: i32 = i32::MIN + 2;

/// One mesh vertex's work for the frame: its screen position and depth, and its packed shader
/// values. `St` is the shading model's [`crate::shade::Shading::Stored`]: `[u16; 3]`
/// (16 bytes a slot) for Gouraud and vertex colours, `[i32; 0]` (12 bytes) for unlit and flat
/// shading, `[i32; 6]` (36 bytes) for Phong.
///
/// Make the scratch with [`VertexSlot::EMPTY`] (`[VertexSlot::EMPTY; 507]`); a draw call fills
/// the slots it uses when it starts, so their contents before it do not matter.
#[derive(Debug, Clone, Copy)]
pub struct VertexSlot<St = [u16; 3]> {
    pub(crate) x: i32,
    pub(crate) y: i32,
    pub(crate) z: u16,
    pub(crate) st: St,
}

impl<St: Packed> VertexSlot<St> {
    /// An unused slot, all bits zero (so a `static` scratch costs no flash).
    pub const EMPTY: Self = Self {
        x: 0,
        y: 0,
        z: 0,
        st: St::ZERO,
    };
}

impl<St: Packed> Default for VertexSlot<St> {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl<S, C, D, Sh, const BITS: u32, N> Pipeline<S, C, D, Sh, BITS, N>
where
    S: Scalar,
    C: Cull,
    D: DepthTest,
    Sh: Shading<S>,
    N: Numerics,
{
    /// `2^20 / w` for perspective-correct interpolation (not computed otherwise).
    #[inline(always)]
    pub(super) fn q(p: &Vec4<S>) -> i64 {
        if N::PERSPECTIVE {
            S::scaled_ratio(S::ONE, p.w, 1 << 20, 1)
        } else {
            0
        }
    }

    /// A vertex's screen position and depth, or [`OUTSIDE`] with its outcode in `y`.
    #[inline]
    pub(super) fn geometry(&self, p: Vec3<S>) -> (i32, i32, u16) {
        if let (Some(raw), Some(px), Some(py), Some(pz)) =
            (&self.raw, p.x.raw_bits(), p.y.raw_bits(), p.z.raw_bits())
        {
            // The same sums and rounding as `Mat4::transform_point`, without its overflow checks.
            let f = S::RAW_FRAC;
            let row = |r: &[i64; 4]| {
                (r[0] * px + r[1] * py + r[2] * pz + (r[3] << f) + ((1 << f) >> 1)) >> f
            };
            let [x, y, z, w] = [
                row(&raw.m[0]),
                row(&raw.m[1]),
                row(&raw.m[2]),
                row(&raw.m[3]),
            ];
            let g = i64::from(crate::clip::polygon::GUARD);
            let big = 1 << 29;
            let inside = x.abs() < big
                && y.abs() < big
                && z.abs() < big
                && w < big
                && w >= raw.w_min
                && z + w >= 0
                && w - z >= 0
                && x + g * w >= 0
                && g * w - x >= 0
                && y + g * w >= 0
                && g * w - y >= 0;
            if !inside {
                // The outcode itself is only needed by the clipper, which computes its own.
                return (OUTSIDE, 1, 0);
            }
            if N::DIVIDE == Divide::Exact {
                // Pipeline::project's exact divide, the same roundings, for a point known to be
                // inside: w > 0, x + w and w - y in [-3w, 5w], z + w in [0, 2w]. A numerator made
                // non-negative by whole multiples of 2w takes an unsigned division.
                let d = 2 * w;
                let vp = &self.viewport;
                let ratio = |n: i64, scale: i64| {
                    let lift = (3 * scale + 1) / 2;
                    ((n * scale + w + d * lift) as u64 / d as u64) as i64 - lift
                };
                let scale_x = i64::from(vp.width) << BITS;
                let scale_y = i64::from(vp.height) << BITS;
                let clamp = |v: i64| v.clamp(i64::from(X_MIN), i64::from(i32::MAX)) as i32;
                let sx = clamp(ratio(x + w, scale_x) + (i64::from(vp.x) << BITS));
                let sy = clamp(ratio(w - y, scale_y) + (i64::from(vp.y) << BITS));
                let z = (((z + w) * 65535 + w) as u64 / d as u64).min(65535) as u16;
                return (sx, sy, z);
            }
            let clip = Vec4::new(
                S::from_raw(x),
                S::from_raw(y),
                S::from_raw(z),
                S::from_raw(w),
            );
            let (s, z) = self.project(&clip);
            return (s.x.max(X_MIN), s.y, z);
        }
        let clip = self.mvp.transform_point(p);
        let code = outcode(&clip);
        if code != 0 {
            return (OUTSIDE, i32::from(code), 0);
        }
        let (s, z) = self.project(&clip);
        (s.x.max(X_MIN), s.y, z)
    }

    /// Vertex `i`'s [`Pipeline::geometry`], from its slot when the scratch has one (filled when
    /// the frame began).
    #[inline(always)]
    pub(super) fn slot_geometry<M: MeshSource<S>>(
        &self,
        mesh: &M,
        i: usize,
        scratch: &mut [VertexSlot<Sh::Stored>],
    ) -> (i32, i32, u16) {
        match scratch.get(i) {
            Some(s) => (s.x, s.y, s.z),
            None => self.geometry(mesh.position(i)),
        }
    }

    /// Vertex `i`'s shader values, from its slot when the scratch has one (always through their
    /// packed form, so a short scratch draws the same pixels).
    #[inline(always)]
    pub(super) fn slot_values<M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        i: usize,
        scratch: &mut [VertexSlot<Sh::Stored>],
    ) -> Sh::Varyings {
        use crate::shade::{Packed, Stored};
        match scratch.get(i) {
            Some(s) if !s.st.is_empty() => s.st.unpack(),
            _ => {
                let space = Space {
                    model: &self.model,
                    normal_matrix: &self.normal_matrix,
                    model_space: self.model_space,
                };
                let packed =
                    shade::<S, Sh, M, N>(&mut self.shading, &space, &self.mvp, mesh, i, None);
                if let Some(s) = scratch.get_mut(i) {
                    s.st = packed;
                }
                packed.unpack()
            }
        }
    }

    /// The data of a vertex the shader may read: in model space when the shader lights there this
    /// frame, in world space otherwise.
    #[inline(always)]
    pub(super) fn vertex_in<M: MeshSource<S>>(&self, mesh: &M, i: usize) -> VertexIn<S> {
        let space = Space {
            model: &self.model,
            normal_matrix: &self.normal_matrix,
            model_space: self.model_space,
        };
        space.vertex_in::<Sh, M>(mesh, i)
    }

    /// Hands the shader a visible triangle ([`Shading::face`]), its vertices in the order whose
    /// edges' cross product points out of the mesh in the space the shader lights in: swapped
    /// when a mirroring model matrix has reversed them in world space.
    #[inline(always)]
    pub(super) fn face<M: MeshSource<S>>(&mut self, mesh: &M, idx: [usize; 3]) {
        let mut vin = idx.map(|i| self.vertex_in(mesh, i));
        if self.flip_faces {
            vin.swap(1, 2);
        }
        self.shading.face(&vin);
    }

    /// The shader values of a triangle's three vertices. A lit shader on a mesh without normals
    /// gets the face normal (the cross product of the edges) at all three, which depends on the
    /// face, so those values are never kept in the scratch.
    #[inline(always)]
    pub(super) fn face_values<M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        idx: [usize; 3],
        scratch: &mut [VertexSlot<Sh::Stored>],
    ) -> [Sh::Varyings; 3] {
        if Sh::NEEDS_WORLD && !mesh.has_normals() {
            return self.face_normal_values(mesh, idx);
        }
        [
            self.slot_values(mesh, idx[0], scratch),
            self.slot_values(mesh, idx[1], scratch),
            self.slot_values(mesh, idx[2], scratch),
        ]
    }

    /// The shader values of a triangle of a mesh without normals: its face normal at all three
    /// vertices. Out of line: one copy for every caller.
    #[inline(never)]
    pub(super) fn face_normal_values<M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        idx: [usize; 3],
    ) -> [Sh::Varyings; 3] {
        use crate::shade::Stored;
        let space = Space {
            model: &self.model,
            normal_matrix: &self.normal_matrix,
            model_space: self.model_space,
        };
        let p = [0, 1, 2].map(|k| space.position(mesh, idx[k]));
        let normal = Vec3::face_normal(p[0], p[1], p[2]);
        // A mirroring model matrix turns the cross product of world-space edges inwards.
        let normal = if self.flip_faces { -normal } else { normal };
        let mut out = [Sh::Varyings::default(); 3];
        for (&i, o) in idx.iter().zip(&mut out) {
            *o = shade::<S, Sh, M, N>(&mut self.shading, &space, &self.mvp, mesh, i, Some(normal))
                .unpack();
        }
        out
    }

    /// Starts a frame: the shader learns the space it lights in, and the scratch's slots for the
    /// mesh's vertices are marked unused.
    pub(super) fn begin<M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        scratch: &mut [VertexSlot<Sh::Stored>],
    ) {
        // Model-space lighting needs normals carried by the model matrix itself.
        let model = (self.normal_matrix == self.model).then_some(&self.model);
        self.model_space = self.shading.begin_frame(model);
        self.flip_faces = self.model_mirrors && !self.model_space;
        // Every vertex with a slot is transformed now, in one tight loop: the triangles then only
        // read their slots.
        let n = scratch.len().min(mesh.vertex_count());
        for (i, s) in scratch[..n].iter_mut().enumerate() {
            (s.x, s.y, s.z) = self.geometry(mesh.position(i));
            s.st = <Sh::Stored as Packed>::EMPTY;
        }
    }

    /// Projects a clip-space point (w > 0) to sub-pixel screen coordinates and depth: the divide and
    /// the viewport in one rounding per coordinate (error at most half a sub-pixel unit and half a
    /// depth step, beyond the error already in the clip-space coordinates). With a reciprocal
    /// divide method ([`Divide::Reciprocal`], [`Divide::Newton`]) and a fixed-point format, a point
    /// inside the view volume takes one reciprocal of `w` and three multiplications instead, and
    /// may be one unit off; other points and floating-point formats divide exactly.
    #[inline]
    pub fn project(&self, p: &Vec4<S>) -> (SubPoint<BITS>, u16) {
        let vp = &self.viewport;
        let clamp = |v: i64| v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
        let (ox, oy) = (i64::from(vp.x) << BITS, i64::from(vp.y) << BITS);
        let (scale_x, scale_y) = (i64::from(vp.width) << BITS, i64::from(vp.height) << BITS);
        if let (Some(x), Some(y), Some(z), Some(w)) = (
            p.x.raw_bits(),
            p.y.raw_bits(),
            p.z.raw_bits(),
            p.w.raw_bits(),
        ) {
            // Fixed point: x_s = (x + w) W 2^BITS / 2w, y flipped, depth (z + w) 65535 / 2w, on the
            // raw integers in i64 (the sums would saturate in the format for |w| near its limit).
            let (nx, ny, nz, d) = (x + w, w - y, z + w, 2 * w);
            let (sx, sy, z) = if N::DIVIDE != Divide::Exact
                && w > 0
                && [nx, ny, nz].iter().all(|n| (0..=d).contains(n))
            {
                // One reciprocal of d (r / 2^k ≈ 1 / d, r in [2^30, 2^31], k >= 31), then per
                // coordinate t = n / d in 0.32 (n r < 2^63 as n <= d < 2^32) and
                // round(t scale / 2^32) (t <= 2^32 + 2 and scale < 2^24 keep it below 2^57).
                let (r, k) = reciprocal(d as u64, N::DIVIDE);
                let ratio = |n: i64, scale: i64| {
                    let prod = n as u64 * r;
                    let t = (if k >= 32 {
                        prod >> (k - 32)
                    } else {
                        prod << (32 - k)
                    }) as i64;
                    (t * scale + (1 << 31)) >> 32
                };
                (ratio(nx, scale_x), ratio(ny, scale_y), ratio(nz, 65535))
            } else {
                // |n| < 2^33 and scale < 2^24: the product fits i64. Rounds halves up.
                let ratio = |n: i64, scale: i64| {
                    if d <= 0 {
                        0
                    } else {
                        (n * scale + d / 2).div_euclid(d)
                    }
                };
                (ratio(nx, scale_x), ratio(ny, scale_y), ratio(nz, 65535))
            };
            let z = z.clamp(0, 65535) as u16;
            return (SubPoint::raw(clamp(sx + ox), clamp(sy + oy)), z);
        }
        // x_s = (x/w + 1) W/2 in sub-pixels, y flipped, depth = (z/w + 1)/2 * 65535.
        let sx = S::scaled_ratio(p.x + p.w, p.w, scale_x, 2);
        let sy = S::scaled_ratio(p.w - p.y, p.w, scale_y, 2);
        let z = S::scaled_ratio(p.z + p.w, p.w, 65535, 2).clamp(0, 65535) as u16;
        (SubPoint::raw(clamp(sx + ox), clamp(sy + oy)), z)
    }
}

/// A fixed-point MVP as raw integers, for the vertex transform's fast path: with every entry
/// below `2^29` in magnitude and every coordinate below `2^31`, each sum of products stays below
/// `2^62`, so a vertex is transformed without overflow checks or saturation. Results of `2^29` or
/// more take the checked path (the clipper's), so both paths agree on every vertex they share.
#[derive(Debug, Clone, Copy)]
pub(super) struct RawMvp {
    m: [[i64; 4]; 4],
    /// The clipper's smallest `w`, raw.
    w_min: i64,
}

impl RawMvp {
    pub(super) fn new<S: Scalar>(mvp: &Mat4<S>) -> Option<Self> {
        let mut m = [[0i64; 4]; 4];
        for (row, out) in mvp.m.iter().zip(&mut m) {
            for (v, o) in row.iter().zip(out.iter_mut()) {
                *o = v.raw_bits().filter(|b| b.unsigned_abs() < 1 << 29)?;
            }
        }
        let w_min = S::from_fx16_bits(1 << (16 - crate::clip::polygon::W_MIN_SHIFT)).raw_bits()?;
        Some(Self { m, w_min })
    }
}

/// The viewport's edges in sub-pixel units: left, top, right, bottom.
pub(super) fn viewport_edges<const BITS: u32>(vp: &Viewport) -> [i64; 4] {
    let (x, y) = (i64::from(vp.x) << BITS, i64::from(vp.y) << BITS);
    [
        x,
        y,
        x + (i64::from(vp.width) << BITS),
        y + (i64::from(vp.height) << BITS),
    ]
}

/// Where a shader's vertices are taken from: the model and normal matrices, and whether the
/// shader lights in model space this frame.
struct Space<'a, S> {
    model: &'a Mat4<S>,
    normal_matrix: &'a Mat4<S>,
    model_space: bool,
}

impl<S: Scalar> Space<'_, S> {
    /// Vertex `i`'s position where the shader lights.
    #[inline(always)]
    fn position<M: MeshSource<S>>(&self, mesh: &M, i: usize) -> Vec3<S> {
        if self.model_space {
            mesh.position(i)
        } else {
            self.model.transform_point(mesh.position(i)).xyz()
        }
    }

    /// [`Space::vertex_in`] with `normal` instead of the vertex's own when there is one (a face
    /// normal).
    #[inline(always)]
    fn vertex_in_with<Sh: Shading<S>, M: MeshSource<S>>(
        &self,
        mesh: &M,
        i: usize,
        normal: Option<Vec3<S>>,
    ) -> VertexIn<S> {
        let mut vin = self.vertex_in::<Sh, M>(mesh, i);
        if let Some(n) = normal {
            vin.normal = n;
        }
        vin
    }

    /// The data of vertex `i` the shader may read.
    #[inline(always)]
    fn vertex_in<Sh: Shading<S>, M: MeshSource<S>>(&self, mesh: &M, i: usize) -> VertexIn<S> {
        let color = mesh.color(i).unwrap_or(Rgb888::WHITE);
        let uv = if Sh::NEEDS_UV {
            mesh.uv(i).unwrap_or_default()
        } else {
            [0; 2]
        };
        if !Sh::NEEDS_WORLD {
            return VertexIn {
                position: Vec3::default(),
                normal: Vec3::default(),
                color,
                uv,
            };
        }
        let normal = mesh.normal(i).unwrap_or_default();
        if self.model_space {
            return VertexIn {
                position: mesh.position(i),
                normal,
                color,
                uv,
            };
        }
        VertexIn {
            position: self.model.transform_point(mesh.position(i)).xyz(),
            normal: self.normal_matrix.transform_dir(normal),
            color,
            uv,
        }
    }
}

/// Shades vertex `i` into its packed values, with the given normal instead of its own when there
/// is one (a face normal). Out of line, once per vertex and frame, with one copy of the vertex
/// shading for every caller; it takes only the shader and the matrices, so a caller's other state
/// stays in registers across the call. A hint, not a rule: a build for size keeps it out of line,
/// a build for speed may inline it.
#[inline]
fn shade_vertex<S: Scalar, Sh: Shading<S>, M: MeshSource<S>>(
    shading: &mut Sh,
    space: &Space<'_, S>,
    mesh: &M,
    i: usize,
    normal: Option<Vec3<S>>,
) -> Sh::Stored {
    use crate::shade::Stored;
    Sh::Stored::pack(&shading.vertex(&space.vertex_in_with::<Sh, M>(mesh, i, normal)))
}

/// [`shade_vertex`], or for a shader whose values depend on the vertex's clip-space `w`
/// ([`Shading::NEEDS_W`]), [`shade_vertex_w`].
#[inline(always)]
fn shade<S: Scalar, Sh: Shading<S>, M: MeshSource<S>, N: Numerics>(
    shading: &mut Sh,
    space: &Space<'_, S>,
    mvp: &Mat4<S>,
    mesh: &M,
    i: usize,
    normal: Option<Vec3<S>>,
) -> Sh::Stored {
    if Sh::NEEDS_W && !N::PERSPECTIVE {
        shade_vertex_w(shading, space, mvp, mesh, i, normal)
    } else {
        shade_vertex(shading, space, mesh, i, normal)
    }
}

/// [`shade_vertex`] followed by [`Shading::project`] with the vertex's clip-space `w` (from
/// `mvp`).
#[inline]
fn shade_vertex_w<S: Scalar, Sh: Shading<S>, M: MeshSource<S>>(
    shading: &mut Sh,
    space: &Space<'_, S>,
    mvp: &Mat4<S>,
    mesh: &M,
    i: usize,
    normal: Option<Vec3<S>>,
) -> Sh::Stored {
    use crate::shade::Stored;
    let mut values = shading.vertex(&space.vertex_in_with::<Sh, M>(mesh, i, normal));
    let w = mvp.transform_point(mesh.position(i)).w;
    shading.project(&mut values, w);
    Sh::Stored::pack(&values)
}
