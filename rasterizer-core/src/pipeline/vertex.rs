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
use crate::numerics::{reciprocal_double, reciprocal_u32, Divide, Numerics};
use crate::shade::{Packed, Shading, VertexIn};
use crate::transform::Viewport;
use crate::wide::div_floor_i64;
use embedded_graphics_core::pixelcolor::Rgb888;
use embedded_graphics_core::prelude::RgbColor;

/// Marks a slot whose vertex lies outside the clip volume's guard band (its outcode is in `y`).
pub(crate) const OUTSIDE: i32 = i32::MIN + 1;
/// A vertex's screen position (sub-pixels) and depth, as its slot holds them.
pub(super) type Projected = (i32, i32, u16);

/// The smallest screen x a projected vertex keeps, above the mark (far outside the guard band, so
/// it never draws anyway).
pub(crate) const X_MIN: i32 = i32::MIN + 2;

/// One mesh vertex's work for the frame: its screen position and depth, and its packed shader
/// values. `St` is the shading model's [`crate::shade::Shading::Stored`]: `[u16; 3]`
/// (16 bytes a slot) for Gouraud and vertex colours, `[i32; 0]` (12 bytes) for unlit and flat
/// shading, `[i32; 5]` (32 bytes) for textures, `[i32; 6]` (36 bytes) for Phong.
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

    /// The clip-space `w` of a mesh position: only the `w` row of [`Mat4::transform_point`]
    /// (the same sum, rounded the same way), a quarter of the transform.
    #[inline(always)]
    fn clip_w(&self, p: Vec3<S>) -> S {
        S::dot4(self.mvp.m[3], p.to_point4().to_array())
    }

    /// [`Pipeline::q`] of a mesh position, from its [`Pipeline::clip_w`].
    #[inline(always)]
    pub(super) fn q_of(&self, p: Vec3<S>) -> i64 {
        if N::PERSPECTIVE {
            S::scaled_ratio(S::ONE, self.clip_w(p), 1 << 20, 1)
        } else {
            0
        }
    }

    /// The [`Pipeline::clip_w`] of a mesh position in 16.16 bits, at least one unit.
    #[inline(always)]
    pub(super) fn w_of(&self, p: Vec3<S>) -> i64 {
        // The same sum through the vertex loop's raw row, when it applies: no overflow checks,
        // and the clamp is the checked sum's saturation.
        if let (Some(raw), Some(p), 16) = (&self.raw, p.raw_bits(), S::RAW_FRAC) {
            return raw_row(raw, p, 3, 16).clamp(1, i64::from(i32::MAX));
        }
        i64::from(self.clip_w(p).to_fx16_bits().max(1))
    }

    /// A vertex's screen position and depth, or [`OUTSIDE`] with its outcode in `y`: the
    /// definition [`Pipeline::begin_raw`]'s faster loop matches. One copy, for the loop's rare
    /// vertices, for the frames without the raw fast path ([`Pipeline::begin_rare`]) and for
    /// vertices beyond the scratch.
    #[inline]
    pub(super) fn geometry(&self, p: Vec3<S>) -> Projected {
        if let (Some(raw), Some(p)) = (&self.raw, p.raw_bits()) {
            // Inside the clipper's guard band, with w and |x|, |y| below 2^29.
            let c = raw_clip(raw, p, S::RAW_FRAC);
            let small = |v: i64| v.unsigned_abs() < W_BIG as u64;
            let inside = guard_band(c, w_low(S::RAW_FRAC), W_BIG);
            let Some((n, w)) = inside.filter(|_| small(c[0]) && small(c[1])) else {
                // The outcode itself is only needed by the clipper, which computes its own.
                return (OUTSIDE, 1, 0);
            };
            let e = project_inside(&self.map, n, w, N::DIVIDE);
            let (sx, sy, z) = self.map.screen(e);
            if self.map.unclamped {
                return (sx as i32, sy as i32, z);
            }
            let clamp = |v: i64| v.clamp(i64::from(X_MIN), i64::from(i32::MAX)) as i32;
            return (clamp(sx), clamp(sy), z);
        }
        self.geometry_checked(p)
    }

    /// [`Pipeline::geometry`] through the checked transform: a matrix or a format without the
    /// raw fast path.
    #[inline(never)]
    fn geometry_checked(&self, p: Vec3<S>) -> Projected {
        let clip = self.mvp.transform_point(p);
        let code = outcode(&clip);
        if code != 0 {
            return (OUTSIDE, i32::from(code), 0);
        }
        let (s, z) = self.project(&clip);
        (s.x.max(X_MIN), s.y, z)
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

    /// [`face_values`](Self::face_values) for the clipper's rare path: one out-of-line copy of
    /// the slot read instead of three inlined ones.
    pub(super) fn face_values_rare<M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        idx: [usize; 3],
        scratch: &mut [VertexSlot<Sh::Stored>],
    ) -> [Sh::Varyings; 3] {
        if Sh::NEEDS_WORLD && !mesh.has_normals() {
            return self.face_normal_values(mesh, idx);
        }
        idx.map(|i| self.slot_values_rare(mesh, i, scratch))
    }

    /// [`slot_values`](Self::slot_values), out of line for
    /// [`face_values_rare`](Self::face_values_rare).
    #[inline(never)]
    fn slot_values_rare<M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        i: usize,
        scratch: &mut [VertexSlot<Sh::Stored>],
    ) -> Sh::Varyings {
        self.slot_values(mesh, i, scratch)
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
        let mut p = [Vec3::default(); 3];
        for (p, &i) in p.iter_mut().zip(&idx) {
            *p = space.position(mesh, i);
        }
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
    /// mesh's vertices are filled with their geometry and marked unshaded. Returns the scratch cut
    /// to the mesh's vertices, so that a corner's bounds check also validates its index
    /// ([`Pipeline::fetch`]). Out of line: the draw loops around it compile the same whatever
    /// the vertex loop holds.
    #[inline(never)]
    pub(crate) fn begin<'s, M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        scratch: &'s mut [VertexSlot<Sh::Stored>],
    ) -> &'s mut [VertexSlot<Sh::Stored>] {
        // Model-space lighting needs normals carried by the model matrix itself.
        let model = (self.normal_matrix == self.model).then_some(&self.model);
        self.model_space = self.shading.begin_frame(model);
        self.flip_faces = self.model_mirrors && !self.model_space;
        // Every vertex with a slot is transformed now, in one tight loop: the triangles then only
        // read their slots.
        let n = scratch.len().min(mesh.vertex_count());
        let scratch = &mut scratch[..n];
        let empty = <Sh::Stored as Packed>::EMPTY;
        let all = n == mesh.vertex_count();
        self.in_viewport = match (&self.raw, self.map.unclamped) {
            (Some(raw), true) => match mesh.position_slice() {
                Some(ps) => self.begin_raw(raw, scratch.iter_mut().zip(ps)),
                None => self.begin_raw(
                    raw,
                    scratch
                        .iter_mut()
                        .enumerate()
                        .map(|(i, s)| (s, Indexed(mesh, i))),
                ),
            },
            _ => {
                // A format or matrix without the raw fast path, or a viewport that needs
                // clamping: each vertex through the general path, out of line.
                let mut all_in_view = true;
                for (i, s) in scratch.iter_mut().enumerate() {
                    s.st = empty;
                    self.begin_rare(s, Indexed(mesh, i), &mut all_in_view);
                }
                all_in_view
            }
        } && all;
        scratch
    }

    /// [`Pipeline::begin`]'s loop for a raw MVP and a viewport whose results need no clamping:
    /// each slot of `slots` filled from its position, and whether every vertex lies inside the
    /// viewport. The same slots as [`Pipeline::geometry`] gives, by a shorter way for the common
    /// vertex: one in the view volume (so in the viewport, and no bounds to track), whose
    /// estimates prove themselves exact. Everything else takes [`Pipeline::begin_rare`].
    #[inline(never)]
    fn begin_raw<'a, P, I>(&self, raw: &RawMvp, slots: I) -> bool
    where
        P: PositionOf<S>,
        I: Iterator<Item = (&'a mut VertexSlot<Sh::Stored>, P)>,
        Sh::Stored: 'a,
    {
        let empty = <Sh::Stored as Packed>::EMPTY;
        // Written on the rare paths only, through memory (`begin_rare` takes its address), so
        // that it takes no register across the loop.
        let mut all_in_view = true;
        let lo = w_low(S::RAW_FRAC);
        for (s, at) in slots {
            s.st = empty;
            let p = at.position();
            let Some(p) = p.raw_bits() else {
                self.begin_rare(s, at, &mut all_in_view);
                continue;
            };
            let row = |r: usize| raw_row(raw, p, r, S::RAW_FRAC);
            let w = row(3);
            if ((w - lo) as u64) >= (W_BIG - lo) as u64 {
                // Outside the guard band, as the band's own test would find.
                (s.x, s.y, s.z) = (OUTSIDE, 1, 0);
                all_in_view = false;
                continue;
            }
            let c = [row(0), row(1), row(2), w];
            // In the view volume, so in the viewport, with estimates that prove themselves
            // exact: the common vertex, whose stores end the loop's body.
            let e = match view_volume(c) {
                Some((n, wc)) => project_estimate(&self.map.view, n, wc, N::DIVIDE),
                None if guard_band(c, lo, W_BIG).is_none() => {
                    (s.x, s.y, s.z) = (OUTSIDE, 1, 0);
                    all_in_view = false;
                    continue;
                }
                None => None,
            };
            let Some(e) = e else {
                // Rarely: an estimate to settle, or a vertex in the guard band but outside the
                // view volume.
                self.begin_rare(s, at, &mut all_in_view);
                continue;
            };
            // No clamping: the estimates hold the corner (`Axis::offset`).
            s.x = (e[0] as i64 >> 32) as i32;
            s.y = (e[1] as i64 >> 32) as i32;
            s.z = (e[2] >> 32) as u16;
        }
        all_in_view
    }

    /// A vertex of [`Pipeline::begin`] through [`Pipeline::geometry`] (every vertex without the
    /// raw fast path, the rare ones with it): `all_in_view` is cleared unless it lies in the
    /// viewport (a vertex outside the guard band has x = OUTSIDE, left of any viewport).
    #[inline(never)]
    #[cold]
    fn begin_rare<P: PositionOf<S>>(
        &self,
        s: &mut VertexSlot<Sh::Stored>,
        at: P,
        all_in_view: &mut bool,
    ) {
        let v = self.geometry(at.position());
        (s.x, s.y, s.z) = v;
        let [l, top, r, bottom] = self.edges;
        let (x, y) = (i64::from(v.0), i64::from(v.1));
        *all_in_view &= (l..=r).contains(&x) && (top..=bottom).contains(&y);
    }

    /// Projects a clip-space point (w > 0) to sub-pixel screen coordinates and depth: the divide and
    /// the viewport in one rounding per coordinate (error at most half a sub-pixel unit and half a
    /// depth step, beyond the error already in the clip-space coordinates). A fixed-point point
    /// inside the clipper's guard band (`|x|, |y| <= 4 w`, `|z| <= w`, `w` below `2^29` raw)
    /// takes one reciprocal of `w` and a multiplication per coordinate, corrected to the exactly
    /// rounded result with [`Divide::Exact`], within one unit below it with the divider-free
    /// methods ([`Divide::Reciprocal`], [`Divide::Newton`]); other points and floating-point
    /// formats divide exactly.
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
            let g = i64::from(crate::clip::polygon::GUARD);
            let n = [x + g * w, g * w - y, z + w];
            // The exact method's estimates give what the divisions below give (the clipper's
            // few vertices take those, so that the vertex loop holds the only copy of the
            // estimates); the divider-free methods keep theirs.
            if !matches!(N::DIVIDE, Divide::Exact)
                && (1..1 << 29).contains(&w)
                && n[0] as u64 <= (2 * g * w) as u64
                && n[1] as u64 <= (2 * g * w) as u64
                && n[2] as u64 <= (2 * w) as u64
            {
                let e = project_inside(&self.map, n.map(|v| v as u64), w as u64, N::DIVIDE);
                let (sx, sy, z) = self.map.screen(e);
                return (SubPoint::raw(clamp(sx), clamp(sy)), z);
            }
            // Fixed point: x_s = (x + w) W 2^BITS / 2w, y flipped, depth (z + w) 65535 / 2w, on the
            // raw integers in i64 (the sums would saturate in the format for |w| near its limit).
            // |n| < 2^33 and scale < 2^24: the product fits i64. Rounds halves up (w = d / 2); 0
            // for w <= 0.
            let (nx, ny, nz, d) = (x + w, w - y, z + w, 2 * w);
            let ratio = |n: i64, scale: i64| div_floor_i64(n * scale + w, d);
            let (sx, sy, z) = (ratio(nx, scale_x), ratio(ny, scale_y), ratio(nz, 65535));
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

/// Where [`Pipeline::begin`]'s loop reads a vertex's position: read again on the loop's rare
/// paths rather than kept in registers across the projection.
pub(super) trait PositionOf<S>: Copy {
    /// The position.
    fn position(self) -> Vec3<S>;
}

impl<S: Copy> PositionOf<S> for &Vec3<S> {
    #[inline(always)]
    fn position(self) -> Vec3<S> {
        *self
    }
}

/// Vertex `.1` of mesh `.0`.
pub(super) struct Indexed<'m, M>(&'m M, usize);

impl<M> Clone for Indexed<'_, M> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M> Copy for Indexed<'_, M> {}

impl<S, M: MeshSource<S>> PositionOf<S> for Indexed<'_, M> {
    #[inline(always)]
    fn position(self) -> Vec3<S> {
        self.0.position(self.1)
    }
}

/// The viewport's mapping for [`project_inside`], fixed per pipeline: in sub-pixel units,
/// `x_s = floor((x + w) W / 2w + 1/2) + x0` with `x + w = u - 3w` for `u = x + 4w >= 0`, so that
/// `x_s = floor((u W + h) / 2w) + base` where `h` is `w` when `3 W` is even (the lift `3 W / 2` is
/// whole and the half stays in the numerator) and 0 when it is odd (the lift's half cancels it);
/// y likewise with `u = 4w - y`, and depth `floor((z + w) 65535 / 2w + 1/2)` ([`DEPTH`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct ScreenMap {
    /// Screen x and y, and depth ([`DEPTH`]: a copy here, so that its scale is read rather than
    /// multiplied by shifts).
    axes: [Axis; 3],
    /// `base` where it is not in [`Axis::offset`] (clamped viewports), else zero.
    rest: [i64; 2],
    /// The mapping of a point in the view volume (`|x|, |y| <= w`) from the numerators
    /// `x + w` and `w - y` (`h = w`, no lift), the corner in [`Axis::offset`]: for unclamped
    /// viewports only.
    view: [Axis; 3],
    /// Every result `[0, 4 W + 1] + base` lies within `[X_MIN, i32::MAX]`: no clamping.
    pub(super) unclamped: bool,
}

/// One output of [`project_inside`]: `floor((u scale + h) / 2w)` plus an offset.
#[derive(Debug, Clone, Copy)]
struct Axis {
    /// Width or height in sub-pixel units (below `2^23`), or the depth scale 65535.
    scale: u64,
    /// All ones where the half stays in the numerator (`h = w`), else zero.
    half: u32,
    /// What [`project_inside`] adds to the estimate in 32.32: `h / 2w` (one half or zero) in the
    /// fraction and, for x and y when there is no clamping, `base` in the whole part (wrapping:
    /// the sum as `i64` is then the screen coordinate times `2^32` plus the fraction, within
    /// `i64`).
    offset: u64,
    /// The largest fraction (in 0.32) of an estimate that proves it exact: above it the estimate
    /// may be one short ([`project_inside`]).
    sure: u32,
}

/// What [`project_inside`]'s estimates of `T = u 2^32 / 2w` may fall short by, in units of
/// `2^-32`, for `u <= 8w` (so `T <= 2^34`): the reciprocal's relative shortfall below `2^-27`
/// ([`reciprocal_double`]) gives less than `2^34 2^-27`, and the floor one more.
const SHORT_XY: u64 = (1 << (34 - 27)) + 1;
/// [`SHORT_XY`] for depth, whose `u = z + w <= 2w` (so `T <= 2^32`).
const SHORT_Z: u64 = (1 << (32 - 27)) + 1;

/// A shortfall below `short scale` units of `2^-32` (below `2^30` for scales below `2^23`) can
/// carry an estimate below a whole number only from a fraction above `2^32 - short scale`.
const fn sure(short: u64, scale: u64) -> u32 {
    ((1 << 32) - short * scale) as u32
}

/// Depth: `floor((z + w) 65535 / 2w + 1/2)`.
const DEPTH: Axis = Axis {
    scale: 65535,
    half: u32::MAX,
    offset: 1 << 31,
    sure: sure(SHORT_Z, 65535),
};

impl ScreenMap {
    pub(super) fn new<const BITS: u32>(vp: &Viewport) -> Self {
        let g = crate::clip::polygon::GUARD as u32;
        let mut base = [0i64; 2];
        let mut map = Self {
            axes: [DEPTH; 3],
            rest: [0; 2],
            view: [DEPTH; 3],
            unclamped: true,
        };
        for (k, (size, corner)) in [(vp.width, vp.x), (vp.height, vp.y)]
            .into_iter()
            .enumerate()
        {
            // The viewport is at most 32767 pixels and BITS at most 8.
            let scale = size.min(crate::surface::MAX_DIMENSION) << BITS;
            let lift = u64::from(g - 1) * u64::from(scale);
            let half = if lift % 2 == 0 { u32::MAX } else { 0 };
            map.axes[k] = Axis {
                scale: u64::from(scale),
                half,
                offset: u64::from(half & 1 << 31),
                sure: sure(SHORT_XY, u64::from(scale)),
            };
            // x + w <= 2w: the estimate of T = (x + w) 2^32 / 2w <= 2^32 falls short as depth's
            // does.
            map.view[k] = Axis {
                scale: u64::from(scale),
                half: u32::MAX,
                offset: (1u64 << 31).wrapping_add((i64::from(corner) << BITS << 32) as u64),
                sure: sure(SHORT_Z, u64::from(scale)),
            };
            base[k] = (i64::from(corner) << BITS) - (lift / 2) as i64;
            let hi = base[k] + i64::from(g) * i64::from(scale) + 1;
            map.unclamped &= base[k] >= i64::from(X_MIN) && hi <= i64::from(i32::MAX);
        }
        for (axis, (base, rest)) in map.axes.iter_mut().zip(base.iter().zip(&mut map.rest)) {
            if map.unclamped {
                axis.offset = axis.offset.wrapping_add((*base as u64) << 32);
            } else {
                *rest = *base;
            }
        }
        map
    }

    /// Screen x and y in sub-pixels (not yet clamped to `i32`) and depth from
    /// [`project_inside`]'s estimates.
    #[inline(always)]
    fn screen(&self, e: [u64; 3]) -> (i64, i64, u16) {
        (
            (e[0] as i64 >> 32) + self.rest[0],
            (e[1] as i64 >> 32) + self.rest[1],
            (e[2] >> 32) as u16,
        )
    }
}

/// The raw clipper's smallest `w` for `frac` fractional bits: `2^-8` rounded to the format, as
/// `Scalar::from_fx16_bits` rounds it (halves up).
const fn w_min(frac: u32) -> i64 {
    let one = 1i64 << (16 - crate::clip::polygon::W_MIN_SHIFT);
    if frac >= 16 {
        one << (frac - 16)
    } else {
        (one + (1 << (15 - frac))) >> (16 - frac)
    }
}

/// The raw fast path's smallest `w`: the clipper's ([`w_min`]), and at least 1 (the projection
/// divides by `2w`; only formats of fewer than 7 fractional bits round the clipper's to 0, and
/// their `w = 0` takes the checked path, as the clipper's own projection does).
const fn w_low(frac: u32) -> i64 {
    let min = w_min(frac);
    if min < 1 {
        1
    } else {
        min
    }
}

/// A raw fixed-point vertex `p` (`frac` fractional bits) through the raw MVP: `[x, -y, z, w]`
/// (`y` negated: the projection takes `w - y`), with the same sums and rounding as
/// `Mat4::transform_point` (the rounding half and the translation are in `bias`), without its
/// overflow checks.
#[inline(always)]
fn raw_clip(raw: &RawMvp, p: [i64; 3], frac: u32) -> [i64; 4] {
    [
        raw_row(raw, p, 0, frac),
        raw_row(raw, p, 1, frac),
        raw_row(raw, p, 2, frac),
        raw_row(raw, p, 3, frac),
    ]
}

/// Row `r` of [`raw_clip`]: `floor(sum / 2^frac)` of the row's sum and bias, which for row 1
/// (negated, its bias `2^frac - 1 - b` for `y`'s `b`) is `floor((2^frac - 1 - Y) / 2^frac) =
/// -floor(Y / 2^frac)`.
#[inline(always)]
fn raw_row(raw: &RawMvp, [px, py, pz]: [i64; 3], r: usize, frac: u32) -> i64 {
    let m = &raw.m[r];
    (i64::from(m[0]) * px + i64::from(m[1]) * py + i64::from(m[2]) * pz + raw.bias[r]) >> frac
}

/// The raw fast path's largest `w` (exclusive): larger `w` take the checked path, the
/// clipper's, so both agree on every vertex they share.
const W_BIG: i64 = 1 << 29;

/// [`project_inside`]'s numerators `[x + 4w, 4w - y, z + w]` and `w` of a clip-space point with
/// `w` in `[lo, hi)` (`hi <= 2^29`) and inside the clipper's guard band (`|z| <= w`,
/// `|x|, |y| <= GUARD w`), else `None`; each test is one unsigned compare.
#[inline(always)]
fn guard_band([x, ny, z, w]: [i64; 4], lo: i64, hi: i64) -> Option<([u64; 3], u64)> {
    let g = i64::from(crate::clip::polygon::GUARD);
    let n = [x + g * w, g * w + ny, z + w];
    let inside = ((w - lo) as u64) < (hi - lo) as u64
        && n[2] as u64 <= (2 * w) as u64
        && n[0] as u64 <= (2 * g * w) as u64
        && n[1] as u64 <= (2 * g * w) as u64;
    inside.then_some((n.map(|v| v as u64), w as u64))
}

/// [`project_estimate`]'s numerators `[x + w, w - y, z + w]` for [`ScreenMap::view`] and `w`
/// of a clip-space point with `w` in `[w_min, 2^29)` when it lies in the view volume
/// (`|x|, |y|, |z| <= w`), else `None`. Such a point lies in the guard band with `|x|, |y|`
/// below `2^29`, and projects into the viewport: `floor((x + w) W / 2w + 1/2)` lies in
/// `[0, W]`.
#[inline(always)]
fn view_volume([x, ny, z, w]: [i64; 4]) -> Option<([u64; 3], u64)> {
    let n = [x + w, w + ny, z + w];
    let d = (2 * w) as u64;
    let inside = n[2] as u64 <= d && n[0] as u64 <= d && n[1] as u64 <= d;
    inside.then_some((n.map(|v| v as u64), w as u64))
}

/// The perspective divide and viewport of a raw fixed-point point inside the guard band
/// (`1 <= w < 2^29`, `|x|, |y| <= 4 w`, `|z| <= w`), given as the numerators
/// `n = [x + 4w, 4w - y, z + w]`, with one reciprocal of `2w` instead of three divisions: each
/// quotient in 32.32 with [`Axis::offset`] added ([`ScreenMap::screen`] takes the screen
/// position and depth from them).
///
/// The reciprocal `r <= 2^(32 + sh) / 2w` is at most `2^-27` below it ([`reciprocal_double`]), so
/// each quotient `floor((u scale + h) / 2w)` (`u <= 8w < 2^32`, `scale < 2^23`) is estimated as
/// `floor((floor(u r / 2^sh) scale + h 2^32 / 2w) / 2^32)` from below by less than
/// `short scale / 2^32` ([`SHORT_XY`], [`SHORT_Z`]; below `1/4`): the estimate is the quotient
/// or one less, and one less only when its fraction lies within that shortfall of one
/// ([`Axis::sure`]). [`Divide::Exact`] settles those few with the remainder, in wrapping
/// 32-bit arithmetic (the remainder lies in `[0, 4w)`, below `2^31`); the divider-free methods
/// keep the estimate.
#[inline(always)]
fn project_inside(map: &ScreenMap, n: [u64; 3], w: u64, divide: Divide) -> [u64; 3] {
    let d = (2 * w) as u32;
    let (r, sh) = reciprocal_u32(d, divide);
    let quotient = |u: u64, a: &Axis| {
        let e = estimate(u, r, sh, a);
        // Every estimate settled, without the test that proves most exact: this serves the
        // rare paths, where fewer instructions of code count more than a few more executed.
        if divide != Divide::Exact {
            return e;
        }
        let q = ((e >> 32) as u32).wrapping_sub((a.offset >> 32) as u32);
        // `half` is all ones when h = w, zero when h = 0.
        let rem = (u as u32)
            .wrapping_mul(a.scale as u32)
            .wrapping_add(a.half & w as u32)
            .wrapping_sub(q.wrapping_mul(d));
        e.wrapping_add(u64::from(rem >= d) << 32)
    };
    [
        quotient(n[0], &map.axes[0]),
        quotient(n[1], &map.axes[1]),
        quotient(n[2], &map.axes[2]),
    ]
}

/// [`project_inside`] without the settling: `None` when [`Divide::Exact`] would settle one of
/// the estimates (rarely: [`Axis::sure`]).
#[inline(always)]
fn project_estimate(axes: &[Axis; 3], n: [u64; 3], w: u64, divide: Divide) -> Option<[u64; 3]> {
    let (r, sh) = reciprocal_double(w as u32, divide);
    let e = [
        estimate(n[0], r, sh, &axes[0]),
        estimate(n[1], r, sh, &axes[1]),
        estimate(n[2], r, sh, &axes[2]),
    ];
    let sure =
        e[0] as u32 <= axes[0].sure && e[1] as u32 <= axes[1].sure && e[2] as u32 <= axes[2].sure;
    (divide != Divide::Exact || sure).then_some(e)
}

/// The estimate of `floor((u scale + h) / 2w)` in 32.32 from the reciprocal, plus the axis's
/// offset (the fraction is the same with it: its whole part has no fraction).
#[inline(always)]
fn estimate(u: u64, r: u64, sh: u32, a: &Axis) -> u64 {
    (((u * r) >> sh) * a.scale).wrapping_add(a.offset)
}

/// A fixed-point MVP as raw integers, for the vertex transform's fast path: with every entry
/// below `2^29` in magnitude and every coordinate below `2^31`, each sum of products stays below
/// `2^62`, so a vertex is transformed without overflow checks or saturation. The entries fit
/// `i32`, so each product is one 32 x 32 -> 64-bit multiply (one instruction on a Cortex-M3/M4,
/// `SMLAL` with the sum). Results of `2^29` or more take the checked path (the clipper's), so
/// both paths agree on every vertex they share.
#[derive(Debug, Clone, Copy)]
pub(super) struct RawMvp {
    /// The linear part, row by row, row 1 negated ([`raw_row`]).
    m: [[i32; 3]; 4],
    /// Per row, the translation shifted to the products' fractional bits plus the rounding half
    /// (row 1 as [`raw_row`] says).
    bias: [i64; 4],
}

impl RawMvp {
    pub(super) fn new<S: Scalar>(mvp: &Mat4<S>) -> Option<Self> {
        let mut m = [[0i32; 3]; 4];
        let mut bias = [0i64; 4];
        let half = (1i64 << S::RAW_FRAC) >> 1;
        for (r, row) in mvp.m.iter().enumerate() {
            let mut raw = [0i64; 4];
            for (v, o) in row.iter().zip(raw.iter_mut()) {
                *o = v.raw_bits().filter(|b| b.unsigned_abs() < 1 << 29)?;
            }
            m[r] = [raw[0] as i32, raw[1] as i32, raw[2] as i32];
            bias[r] = (raw[3] << S::RAW_FRAC) + half;
        }
        // Row 1 gives -y ([`raw_row`]).
        m[1] = m[1].map(|v| -v);
        bias[1] = (1 << S::RAW_FRAC) - 1 - bias[1];
        Some(Self { m, bias })
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
        // Read once, before the branch: one copy of the mesh's decoding, not two.
        let p = mesh.position(i);
        if self.model_space {
            p
        } else {
            self.model.transform_point(p).xyz()
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
        let position = mesh.position(i);
        if self.model_space {
            return VertexIn {
                position,
                normal,
                color,
                uv,
            };
        }
        VertexIn {
            position: self.model.transform_point(position).xyz(),
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
    shading.vertex_stored(&space.vertex_in_with::<Sh, M>(mesh, i, normal))
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
    // Only the w row of `Mat4::transform_point` (the same sum, rounded the same way): the other
    // three rows cost three times as much and the projection has them already.
    let w = S::dot4(mvp.m[3], mesh.position(i).to_point4().to_array());
    shading.project(&mut values, w);
    Sh::Stored::pack(&values)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exactly rounded projection, `floor((n scale + w) / 2w)` in i128: the reference.
    fn reference(vp: &Viewport, bits: u32, [x, y, z, w]: [i64; 4]) -> (i64, i64, i64) {
        let ratio = |n: i64, scale: i64| {
            (i128::from(n) * i128::from(scale) + i128::from(w)).div_euclid(i128::from(2 * w)) as i64
        };
        let (sx, sy) = (i64::from(vp.width) << bits, i64::from(vp.height) << bits);
        (
            ratio(x + w, sx) + (i64::from(vp.x) << bits),
            ratio(w - y, sy) + (i64::from(vp.y) << bits),
            ratio(z + w, 65535),
        )
    }

    /// A point of the guard band (`g = 4`) or the view volume (`g = 1`): `1 <= w < 2^29`,
    /// `|x|, |y| <= g w`, `|z| <= w`, from random bits (half of them at the edges).
    fn point(bits: [u32; 4], g: i64) -> [i64; 4] {
        let w = 1 + i64::from(bits[0] >> (bits[0] & 31).min(3)) % ((1 << 29) - 1);
        let w = w >> (bits[1] % 29);
        let w = w.max(1);
        let pick = |b: u32, lim: i64| match b % 8 {
            0 => lim,
            1 => -lim,
            2 => lim - 1,
            3 => -lim + 1,
            _ => i64::from(b as i32) % (lim + 1),
        };
        [
            pick(bits[1], g * w),
            pick(bits[2], g * w),
            pick(bits[3], w),
            w,
        ]
    }

    /// Every slot `begin` fills holds what the vertex stage defines for its vertex, from an
    /// i128 reference: the MVP's exact sums rounded once, inside the clipper's guard band (with w
    /// and |x|, |y| below 2^29) the exactly rounded projection, else the outside mark; and the
    /// frame is in the viewport exactly when every vertex is.
    #[test]
    fn begin_fills_every_slot_as_defined() {
        use crate::cull::NoCull;
        use crate::depth::NoDepth;
        use crate::math::{Fx16, Mat4};
        use crate::mesh::Mesh;
        use crate::shade::Unlit;
        use crate::transform::Transforms;
        use embedded_graphics_core::pixelcolor::Rgb565;
        let mut s = 0x1234_5678u32;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            s
        };
        let vp = Viewport::new(320, 240);
        // In the view volume, in the band only, outside, w of 2^27 or more, frames in view.
        let mut seen = [0; 5];
        for _ in 0..400 {
            // Each row at its own scale, w's translation large or small.
            let mut m = [[Fx16::ZERO; 4]; 4];
            for row in m.iter_mut() {
                let k = next() % 29;
                for v in row.iter_mut() {
                    *v = Fx16::from_bits((next() as i32) >> (31 - k).max(3));
                }
            }
            let k = 8 + next() % 21;
            m[3][3] = Fx16::from_bits(((next() >> 1) >> (31 - k)) as i32);
            let transforms = Transforms {
                model: Mat4::from_rows(m),
                view: Mat4::identity(),
                projection: Mat4::identity(),
            };
            let mut p = Pipeline::new(
                &transforms,
                vp,
                NoCull,
                NoDepth,
                Unlit { color: Rgb565::RED },
            );
            assert!(p.raw.is_some());
            let shift = next() % 19;
            let positions: [Vec3<Fx16>; 48] = core::array::from_fn(|_| {
                let mut c = || Fx16::from_bits((next() as i32) >> (12 + shift));
                Vec3::new(c(), c(), c())
            });
            // The perspective path's `w` from the raw row is the checked definition's, also at
            // the format's limits.
            let far = [i32::MIN, i32::MAX].map(Fx16::from_bits);
            for q in positions.iter().chain(&[
                Vec3::new(far[0], far[1], far[0]),
                Vec3::new(far[1], far[1], far[1]),
            ]) {
                assert_eq!(
                    p.w_of(*q),
                    i64::from(p.clip_w(*q).to_fx16_bits().max(1)),
                    "{q:?}"
                );
            }
            let mesh = Mesh::<Fx16, u16>::new(&positions, &[]);
            let mut scratch = [VertexSlot::<[i32; 0]>::EMPTY; 48];
            p.begin(&mesh, &mut scratch);
            let mvp = p.mvp.m.map(|row| row.map(|v| i128::from(v.to_bits())));
            let mut in_view = true;
            for (slot, q) in scratch.iter().zip(&positions) {
                let q = [q.x, q.y, q.z].map(|v| i128::from(v.to_bits()));
                let c = mvp.map(|row| {
                    let sum = row[0] * q[0] + row[1] * q[1] + row[2] * q[2] + (row[3] << 16);
                    (sum + (1 << 15)) >> 16
                });
                let [x, y, z, w] = c;
                let band = (256..1 << 29).contains(&w)
                    && z.abs() <= w
                    && x.abs() <= 4 * w
                    && y.abs() <= 4 * w
                    && x.abs() < 1 << 29
                    && y.abs() < 1 << 29;
                let expected = if band {
                    let (sx, sy, sz) = reference(&vp, 6, c.map(|v| v as i64));
                    (sx as i32, sy as i32, sz as u16)
                } else {
                    (OUTSIDE, 1, 0)
                };
                assert_eq!((slot.x, slot.y, slot.z), expected, "{c:?}");
                let view = band && x.abs() <= w && y.abs() <= w;
                seen[0] += usize::from(view);
                seen[1] += usize::from(band && !view);
                seen[2] += usize::from(!band);
                seen[3] += usize::from(w >= 1 << 27);
                let (sx, sy) = (i64::from(expected.0), i64::from(expected.1));
                in_view &= (0..=320 << 6).contains(&sx) && (0..=240 << 6).contains(&sy);
            }
            assert_eq!(p.in_viewport, in_view);
            seen[4] += usize::from(in_view);
        }
        assert!(seen.iter().all(|&n| n > 0), "{seen:?}");
    }

    /// `w_min` is the clipper's smallest `w` in each fixed-point format.
    #[test]
    fn w_min_is_the_clippers() {
        use crate::math::Fx;
        fn clipper<S: Scalar>() -> i64 {
            let min = 1 << (16 - crate::clip::polygon::W_MIN_SHIFT);
            S::from_fx16_bits(min).raw_bits().unwrap()
        }
        assert_eq!(w_min(4), clipper::<Fx<4>>());
        assert_eq!(w_min(7), clipper::<Fx<7>>());
        assert_eq!(w_min(8), clipper::<Fx<8>>());
        assert_eq!(w_min(12), clipper::<Fx<12>>());
        assert_eq!(w_min(16), clipper::<Fx<16>>());
        assert_eq!(w_min(24), clipper::<Fx<24>>());
    }

    #[test]
    fn fast_projection_is_exact() {
        let viewports = [
            (Viewport::new(320, 240), 6),
            (Viewport::new(32767, 32767), 8),
            (Viewport::new(1, 3), 0),
            (Viewport::new(33, 17), 3),
            (
                Viewport {
                    x: -1000,
                    y: 77,
                    width: 641,
                    height: 479,
                },
                4,
            ),
            // Results beyond i32: the corner is added after the quotient (`ScreenMap::rest`).
            (
                Viewport {
                    x: i32::MAX - 100,
                    y: i32::MIN + 7,
                    width: 32767,
                    height: 200,
                },
                8,
            ),
        ];
        let mut s = 0x9e37_79b9u32;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            s
        };
        for (k, (vp, bits)) in viewports.into_iter().enumerate() {
            let map = match bits {
                0 => ScreenMap::new::<0>(&vp),
                3 => ScreenMap::new::<3>(&vp),
                4 => ScreenMap::new::<4>(&vp),
                6 => ScreenMap::new::<6>(&vp),
                _ => ScreenMap::new::<8>(&vp),
            };
            assert_eq!(map.unclamped, k < 5, "{vp:?}");
            let mut settled = 0;
            for _ in 0..100_000 {
                let p = point([next(), next(), next(), next()], 4);
                let (rx, ry, rz) = reference(&vp, bits, p);
                let [x, y, z, w] = p;
                let n = [x + 4 * w, 4 * w - y, z + w].map(|v| v as u64);
                let w = w as u64;
                let exact = map.screen(project_inside(&map, n, w, Divide::Exact));
                assert_eq!(exact, (rx, ry, rz as u16), "{vp:?} {bits} {p:?}");
                // The estimates are taken only where their fractions prove them exact.
                match project_estimate(&map.axes, n, w, Divide::Exact) {
                    Some(e) => assert_eq!(map.screen(e), exact, "{vp:?} {bits} {p:?}"),
                    None => settled += 1,
                }
                for method in [Divide::Reciprocal, Divide::Newton] {
                    let e = project_inside(&map, n, w, method);
                    assert_eq!(Some(e), project_estimate(&map.axes, n, w, method));
                    let (sx, sy, sz) = map.screen(e);
                    // One unit below at most, never above.
                    assert!((rx - 1..=rx).contains(&sx), "{method:?} {p:?}");
                    assert!((ry - 1..=ry).contains(&sy), "{method:?} {p:?}");
                    assert!((rz - 1..=rz).contains(&i64::from(sz)), "{method:?} {p:?}");
                }
            }
            // Settling takes the points whose quotient is whole or nearly (a band's or the view
            // volume's edge: half of these points) and, for the widest scales, any quotient
            // within a quarter of a unit below a whole one. Measured per 100,000 points, in the
            // order of `viewports`: 6,212, 34,234, 33,583, 6,937, 6,477, 21,917.
            let bound = [12_500, 70_000, 70_000, 14_000, 13_000, 44_000][k];
            assert!(settled <= bound, "{vp:?}: {settled}");
            if !map.unclamped {
                continue;
            }
            // The view volume's mapping (`ScreenMap::view`), from `x + w` and `w - y`.
            let mut settled = 0;
            for _ in 0..100_000 {
                let p = point([next(), next(), next(), next()], 1);
                let (rx, ry, rz) = reference(&vp, bits, p);
                let [x, y, z, w] = p;
                let n = [x + w, w - y, z + w].map(|v| v as u64);
                let w = w as u64;
                let screen = |e: [u64; 3]| ((e[0] as i64) >> 32, (e[1] as i64) >> 32, e[2] >> 32);
                match project_estimate(&map.view, n, w, Divide::Exact) {
                    Some(e) => assert_eq!(screen(e), (rx, ry, rz as u64), "{vp:?} {p:?}"),
                    None => settled += 1,
                }
                for method in [Divide::Reciprocal, Divide::Newton] {
                    let (sx, sy, sz) = screen(project_estimate(&map.view, n, w, method).unwrap());
                    assert!((rx - 1..=rx).contains(&sx), "{method:?} {p:?}");
                    assert!((ry - 1..=ry).contains(&sy), "{method:?} {p:?}");
                    assert!((rz - 1..=rz).contains(&(sz as i64)), "{method:?} {p:?}");
                }
            }
            // Measured, in the order of `viewports`: 6,339, 13,608, 10,656, 6,759, 6,489.
            let bound = [12_500, 27_000, 21_000, 13_500, 13_000][k];
            assert!(settled <= bound, "view {vp:?}: {settled}");
        }
    }
}
