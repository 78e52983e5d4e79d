//! The 3D pipeline: mesh -> vertex transform -> clip -> project -> cull -> raster -> shade -> target.
//!
//! [`Pipeline`] is generic over its stages: culling ([`cull`]), the depth test
//! ([`crate::raster::interp::DepthTest`]) and the shading model ([`shading`]). A stage that is off
//! is a zero-sized type whose methods are empty, so a frame without depth, culling or lighting
//! compiles none of that code and keeps none of its state. Geometry runs in any
//! [`crate::math::Scalar`] (16.16 by default); everything after the perspective divide is integer.
//!
//! Every draw call runs each triangle through one front end (fetch, transform once per vertex
//! into the caller's [`VertexSlot`] scratch, trivial rejection, culling); the filled, banded and
//! wireframe paths differ only in what they do with the triangles it lets through. With the
//! default numerics a visible triangle is drawn by the fused span loop of
//! [`crate::raster::interp`]'s sibling `fused` module: depth test, interpolation and colour in one
//! loop per span.

mod band;
pub mod cull;
pub mod shading;
pub mod vertex;

pub use band::{BandError, Banding, BinEntry};
pub use vertex::{Packed, Stored, VertexSlot};

use crate::clip::polygon::{
    clip_segment, clip_triangle, outcode, trivially_outside, ClipVertex, Outcode,
};
use crate::geom::{PixelRect, SubPoint};
use crate::math::{Mat4, Scalar, Vec3, Vec4};
use crate::numerics::{reciprocal, Divide, Numerics, SpanStart, Standard};
use crate::raster::fused::{fill_fused, FusedColor, FusedVertex, Precision};
use crate::raster::interp::{fill_triangle_interp_with, DepthTest, ScreenVertex};
use crate::raster::line::draw_line;
use crate::shade::MAX_VARYINGS;
use crate::target::{ClipTo, Surface};
use cull::Cull;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::Rgb888;
use embedded_graphics_core::prelude::RgbColor;
use embedded_graphics_core::primitives::Rectangle;
use shading::{Shading, VertexIn};
use vertex::{OUTSIDE, X_MIN};

/// The sub-pixel bits of screen coordinates a [`Pipeline`] has unless told otherwise: 6, so
/// 26.6 (`docs/ACCURACY.md` measures the choice).
pub const DEFAULT_BITS: u32 = 6;

/// An index into a mesh's vertex arrays.
pub trait VertexIndex: Copy {
    /// As `usize`.
    fn index(self) -> usize;
}

impl VertexIndex for u8 {
    #[inline(always)]
    fn index(self) -> usize {
        usize::from(self)
    }
}

impl VertexIndex for u16 {
    #[inline(always)]
    fn index(self) -> usize {
        usize::from(self)
    }
}

impl VertexIndex for u32 {
    #[inline(always)]
    fn index(self) -> usize {
        self as usize
    }
}

/// A triangle mesh as plain slices: nothing is copied.
#[derive(Debug, Clone, Copy)]
pub struct Mesh<'a, S, I = u16> {
    /// Vertex positions in model space.
    pub positions: &'a [Vec3<S>],
    /// Vertex normals in model space, one per position; lit shaders use the face normal when
    /// absent.
    pub normals: Option<&'a [Vec3<S>]>,
    /// Vertex colours, one per position; white when absent.
    pub colors: Option<&'a [Rgb888]>,
    /// Triangles as three vertex indices. A triangle with an index out of range is skipped and
    /// counted in [`RenderStats::invalid`].
    pub triangles: &'a [[I; 3]],
}

impl<'a, S, I> Mesh<'a, S, I> {
    /// A mesh of positions and triangles only.
    pub fn new(positions: &'a [Vec3<S>], triangles: &'a [[I; 3]]) -> Self {
        Self {
            positions,
            normals: None,
            colors: None,
            triangles,
        }
    }
}

/// Where a pipeline reads a mesh from: plain slices ([`Mesh`]) or the packed format read straight
/// from flash ([`crate::mesh::PackedMesh`]).
pub trait MeshSource<S> {
    /// Number of vertices.
    fn vertex_count(&self) -> usize;
    /// Number of triangles.
    fn triangle_count(&self) -> usize;
    /// Triangle `t`'s vertex indices (`t < triangle_count()`); an index may be out of range, and
    /// the pipeline then skips the triangle.
    fn triangle(&self, t: usize) -> [usize; 3];
    /// Vertex `i`'s position (`i < vertex_count()`).
    fn position(&self, i: usize) -> Vec3<S>;
    /// True when the mesh has normals.
    fn has_normals(&self) -> bool;
    /// Vertex `i`'s normal, if the mesh has normals.
    fn normal(&self, i: usize) -> Option<Vec3<S>>;
    /// Vertex `i`'s colour, if the mesh has colours.
    fn color(&self, i: usize) -> Option<Rgb888>;
}

impl<S: Scalar, I: VertexIndex> MeshSource<S> for Mesh<'_, S, I> {
    #[inline(always)]
    fn vertex_count(&self) -> usize {
        self.positions.len()
    }
    #[inline(always)]
    fn triangle_count(&self) -> usize {
        self.triangles.len()
    }
    #[inline(always)]
    fn triangle(&self, t: usize) -> [usize; 3] {
        self.triangles
            .get(t)
            .map_or([usize::MAX; 3], |tri| tri.map(VertexIndex::index))
    }
    #[inline(always)]
    fn position(&self, i: usize) -> Vec3<S> {
        self.positions.get(i).copied().unwrap_or_default()
    }
    #[inline(always)]
    fn has_normals(&self) -> bool {
        self.normals.is_some()
    }
    #[inline(always)]
    fn normal(&self, i: usize) -> Option<Vec3<S>> {
        self.normals.and_then(|n| n.get(i).copied())
    }
    #[inline(always)]
    fn color(&self, i: usize) -> Option<Rgb888> {
        self.colors.and_then(|c| c.get(i).copied())
    }
}

/// Where normalised device coordinates land on the target: `x = -1` at the left edge of the
/// rectangle, `y = +1` at its top (the y flip), in whole pixels. The pipeline also clips to it, so
/// several viewports can share one target.
///
/// Range: any `x` and `y`; `width` and `height` at most 32767 ([`crate::target::MAX_DIMENSION`]).
/// A [`Pipeline`] clamps a larger width or height to 32767, for the mapping from device
/// coordinates as for clipping; the clip rectangle, [`Viewport::rectangle`], also stops at the
/// `i32` plane's edge (it never reaches past `i32::MAX`), so nothing is drawn outside it or the
/// target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Viewport {
    /// Left edge.
    pub x: i32,
    /// Top edge.
    pub y: i32,
    /// Width in pixels, at most 32767.
    pub width: u32,
    /// Height in pixels, at most 32767.
    pub height: u32,
}

impl Viewport {
    /// The rectangle of pixels the viewport covers: the pipeline draws nothing outside it.
    ///
    /// Exactly `(x, y)`, `width` x `height` within the documented range; a width or height above
    /// 32767 is clamped to it, and the size to what ends at `i32::MAX`, for any field values.
    pub fn rectangle(&self) -> Rectangle {
        // No pixel lies past i32::MAX.
        let max = i64::from(crate::target::MAX_DIMENSION);
        let len = |origin: i32, len: u32| {
            let room = i64::from(i32::MAX) - i64::from(origin) + 1;
            i64::from(len).min(max).min(room) as u32
        };
        Rectangle::new(
            Point::new(self.x, self.y),
            Size::new(len(self.x, self.width), len(self.y, self.height)),
        )
    }

    /// A viewport covering `width` x `height` pixels from the origin.
    pub const fn new(width: u32, height: u32) -> Self {
        Self {
            x: 0,
            y: 0,
            width,
            height,
        }
    }
}

/// What happened to the triangles of one draw call.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RenderStats {
    /// Triangles in the mesh.
    pub triangles: u32,
    /// Skipped for an index out of range.
    pub invalid: u32,
    /// Entirely outside the view volume.
    pub outside: u32,
    /// Needed clipping in homogeneous space.
    pub clipped: u32,
    /// Dropped by culling (or of zero area on screen).
    pub culled: u32,
    /// Handed to the rasterizer (as one or more triangles).
    pub drawn: u32,
}

/// The transforms of a draw call.
#[derive(Debug, Clone, Copy)]
pub struct Transforms<S> {
    /// Model to world.
    pub model: Mat4<S>,
    /// World to view (e.g. [`Mat4::look_at`]).
    pub view: Mat4<S>,
    /// View to clip space (e.g. [`Mat4::perspective`]).
    pub projection: Mat4<S>,
}

/// Why a draw call stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrawError<E> {
    /// The target reported an error.
    Target(E),
    /// The depth buffer does not cover the pixels the pipeline draws (the viewport within the
    /// target): nothing is drawn.
    DepthTooSmall {
        /// The pixels the draw needs depths for.
        needed: Rectangle,
    },
}

impl<E> From<E> for DrawError<E> {
    fn from(e: E) -> Self {
        Self::Target(e)
    }
}

impl<E: core::fmt::Debug> core::fmt::Display for DrawError<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Target(e) => write!(f, "the target failed: {e:?}"),
            Self::DepthTooSmall { needed } => write!(
                f,
                "the depth buffer does not cover the {}x{} pixels at ({}, {}) the draw needs",
                needed.size.width, needed.size.height, needed.top_left.x, needed.top_left.y
            ),
        }
    }
}

/// A configured pipeline: transforms, viewport and the compile-time choice of stages.
///
/// `BITS` is the number of sub-pixel bits of screen coordinates (6 by default: 26.6, where
/// `docs/ACCURACY.md` finds M1's vertices within 0.011 px at no measurable cost over 4 bits' 0.043
/// px; 0 to 8 allowed). With `PERSPECTIVE` the
/// shader's values are interpolated perspective-correctly (two divisions per pixel); without, they
/// are affine in screen space (depth is always exact, being affine in screen space anyway).
///
/// `N` holds the remaining accuracy knobs ([`crate::numerics`]): the divide method and the
/// precision of interpolation. [`Pipeline::new`] makes a [`Standard`] pipeline;
/// [`Pipeline::with_numerics`] changes them.
#[derive(Debug, Clone)]
pub struct Pipeline<
    S,
    C,
    D,
    Sh,
    const BITS: u32 = DEFAULT_BITS,
    const PERSPECTIVE: bool = false,
    N = Standard,
> {
    mvp: Mat4<S>,
    /// The MVP's raw integers, for a fixed-point format whose entries are small enough to
    /// transform a vertex without checks ([`RawMvp`]).
    raw: Option<RawMvp>,
    model: Mat4<S>,
    normal_matrix: Mat4<S>,
    viewport: Viewport,
    /// The viewport's pixels, and its edges in sub-pixel units (left, top, right, bottom).
    area: PixelRect,
    edges: [i64; 4],
    /// The shader takes model-space positions and normals this frame.
    model_space: bool,
    /// The culling stage.
    pub cull: C,
    /// The depth stage.
    pub depth: D,
    /// The shading stage.
    pub shading: Sh,
    _numerics: core::marker::PhantomData<N>,
}

/// A fixed-point MVP as raw integers, for the vertex transform's fast path: with every entry
/// below `2^29` in magnitude and every coordinate below `2^31`, each sum of products stays below
/// `2^62`, so a vertex is transformed without overflow checks or saturation. Results of `2^29` or
/// more take the checked path (the clipper's), so both paths agree on every vertex they share.
#[derive(Debug, Clone, Copy)]
struct RawMvp {
    m: [[i64; 4]; 4],
    /// The clipper's smallest `w`, raw.
    w_min: i64,
}

impl RawMvp {
    fn new<S: Scalar>(mvp: &Mat4<S>) -> Option<Self> {
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

/// What the front end made of a triangle.
enum Front<S, const BITS: u32> {
    /// Nothing to draw (already counted).
    Skip,
    /// Every vertex inside the clip volume's guard band: projected, facing the right way.
    Inside {
        idx: [usize; 3],
        v: [(SubPoint<BITS>, u16); 3],
    },
    /// Needs clipping in homogeneous space.
    Clip {
        idx: [usize; 3],
        clip: [Vec4<S>; 3],
        codes: [Outcode; 3],
    },
}

impl<S, C, D, Sh, const BITS: u32, const PERSPECTIVE: bool> Pipeline<S, C, D, Sh, BITS, PERSPECTIVE>
where
    S: Scalar,
    C: Cull,
    D: DepthTest,
    Sh: Shading<S>,
{
    /// A pipeline. Normals are transformed by the model matrix's upper 3x3, which is right for
    /// rotations, reflections, translations and uniform scales; use [`Pipeline::set_normal_matrix`]
    /// with the inverse transpose for shear or non-uniform scale.
    pub fn new(
        transforms: &Transforms<S>,
        viewport: Viewport,
        cull: C,
        depth: D,
        shading: Sh,
    ) -> Self {
        let mvp = transforms
            .model
            .then(&transforms.view)
            .then(&transforms.projection);
        // The mapping's arithmetic is sized for the documented range.
        let max = crate::target::MAX_DIMENSION;
        let viewport = Viewport {
            width: viewport.width.min(max),
            height: viewport.height.min(max),
            ..viewport
        };
        Self {
            raw: RawMvp::new(&mvp),
            mvp,
            model: transforms.model,
            normal_matrix: transforms.model,
            viewport,
            area: PixelRect::from_rectangle(&viewport.rectangle()),
            edges: viewport_edges::<BITS>(&viewport),
            model_space: false,
            cull,
            depth,
            shading,
            _numerics: core::marker::PhantomData,
        }
    }
}

impl<S, C, D, Sh, const BITS: u32, const PERSPECTIVE: bool, N>
    Pipeline<S, C, D, Sh, BITS, PERSPECTIVE, N>
where
    S: Scalar,
    C: Cull,
    D: DepthTest,
    Sh: Shading<S>,
    N: Numerics,
{
    /// The same pipeline with other numeric knobs ([`crate::numerics`]), e.g.
    /// `Pipeline::new(..).with_numerics::<Custom<NewtonDivide, 16, GradientSpans>>()`.
    ///
    /// [`Custom<NewtonDivide, 16, GradientSpans>`]: crate::numerics::Custom
    pub fn with_numerics<M: Numerics>(self) -> Pipeline<S, C, D, Sh, BITS, PERSPECTIVE, M> {
        Pipeline {
            mvp: self.mvp,
            raw: self.raw,
            model: self.model,
            normal_matrix: self.normal_matrix,
            viewport: self.viewport,
            area: self.area,
            edges: self.edges,
            model_space: false,
            cull: self.cull,
            depth: self.depth,
            shading: self.shading,
            _numerics: core::marker::PhantomData,
        }
    }

    /// Replaces the matrix that carries normals to world space.
    pub fn set_normal_matrix(&mut self, m: Mat4<S>) {
        self.normal_matrix = m;
    }

    /// The composed model-view-projection matrix.
    pub fn mvp(&self) -> &Mat4<S> {
        &self.mvp
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
            return (SubPoint::new(clamp(sx + ox), clamp(sy + oy)), z);
        }
        // x_s = (x/w + 1) W/2 in sub-pixels, y flipped, depth = (z/w + 1)/2 * 65535.
        let sx = S::scaled_ratio(p.x + p.w, p.w, scale_x, 2);
        let sy = S::scaled_ratio(p.w - p.y, p.w, scale_y, 2);
        let z = S::scaled_ratio(p.z + p.w, p.w, 65535, 2).clamp(0, 65535) as u16;
        (SubPoint::new(clamp(sx + ox), clamp(sy + oy)), z)
    }

    /// `2^20 / w` for perspective-correct interpolation (not computed otherwise).
    #[inline(always)]
    fn q(p: &Vec4<S>) -> i64 {
        if PERSPECTIVE {
            S::scaled_ratio(S::ONE, p.w, 1 << 20, 1)
        } else {
            0
        }
    }

    /// A vertex's screen position and depth, or [`OUTSIDE`] with its outcode in `y`.
    #[inline]
    fn geometry(&self, p: Vec3<S>) -> (i32, i32, u16) {
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
    fn slot_geometry<M: MeshSource<S>>(
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
    fn slot_values<M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        i: usize,
        scratch: &mut [VertexSlot<Sh::Stored>],
    ) -> Sh::Varyings {
        use vertex::{Packed, Stored};
        match scratch.get(i) {
            Some(s) if !s.st.is_empty() => s.st.unpack(),
            _ => {
                let space = Space {
                    model: &self.model,
                    normal_matrix: &self.normal_matrix,
                    model_space: self.model_space,
                };
                let packed = shade_vertex(&mut self.shading, &space, mesh, i, None);
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
    fn vertex_in<M: MeshSource<S>>(&self, mesh: &M, i: usize) -> VertexIn<S> {
        let space = Space {
            model: &self.model,
            normal_matrix: &self.normal_matrix,
            model_space: self.model_space,
        };
        space.vertex_in::<Sh, M>(mesh, i)
    }

    /// The shader values of a triangle's three vertices. A lit shader on a mesh without normals
    /// gets the face normal (the cross product of the edges) at all three, which depends on the
    /// face, so those values are never kept in the scratch.
    #[inline(always)]
    fn face_values<M: MeshSource<S>>(
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
    fn face_normal_values<M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        idx: [usize; 3],
    ) -> [Sh::Varyings; 3] {
        use vertex::Stored;
        let space = Space {
            model: &self.model,
            normal_matrix: &self.normal_matrix,
            model_space: self.model_space,
        };
        let p = [0, 1, 2].map(|k| space.position(mesh, idx[k]));
        let normal = (p[1] - p[0]).cross(p[2] - p[0]);
        let mut out = [Sh::Varyings::default(); 3];
        for (&i, o) in idx.iter().zip(&mut out) {
            *o = shade_vertex(&mut self.shading, &space, mesh, i, Some(normal)).unpack();
        }
        out
    }

    /// Starts a frame: the shader learns the space it lights in, and the scratch's slots for the
    /// mesh's vertices are marked unused.
    fn begin<M: MeshSource<S>>(&mut self, mesh: &M, scratch: &mut [VertexSlot<Sh::Stored>]) {
        // Model-space lighting needs normals carried by the model matrix itself.
        let model = (self.normal_matrix == self.model).then_some(&self.model);
        self.model_space = self.shading.begin_frame(model);
        // Every vertex with a slot is transformed now, in one tight loop: the triangles then only
        // read their slots.
        let n = scratch.len().min(mesh.vertex_count());
        for (i, s) in scratch[..n].iter_mut().enumerate() {
            (s.x, s.y, s.z) = self.geometry(mesh.position(i));
            s.st = <Sh::Stored as vertex::Packed>::EMPTY;
        }
    }

    /// The front end shared by every draw call: fetches triangle `t`, reads its vertices (each
    /// transformed once a frame, through the scratch), rejects it when it faces away or lies
    /// outside the view, counting why in `stats`. A triangle of zero area on screen is culled, unless
    /// `keep_flat` (the wireframe draws it as a line).
    #[inline(always)]
    fn front<M: MeshSource<S>>(
        &self,
        mesh: &M,
        t: usize,
        scratch: &mut [VertexSlot<Sh::Stored>],
        stats: &mut RenderStats,
        keep_flat: bool,
    ) -> Front<S, BITS> {
        let idx = mesh.triangle(t);
        let n = mesh.vertex_count();
        if idx[0] >= n || idx[1] >= n || idx[2] >= n {
            stats.invalid += 1;
            return Front::Skip;
        }
        let a = self.slot_geometry(mesh, idx[0], scratch);
        let b = self.slot_geometry(mesh, idx[1], scratch);
        let c = self.slot_geometry(mesh, idx[2], scratch);
        if a.0 == OUTSIDE || b.0 == OUTSIDE || c.0 == OUTSIDE {
            return self.front_clip(mesh, idx, stats);
        }
        let xs = [a.0, b.0, c.0].map(i64::from);
        let ys = [a.1, b.1, c.1].map(i64::from);
        let area = (xs[1] - xs[0]) * (ys[2] - ys[0]) - (xs[2] - xs[0]) * (ys[1] - ys[0]);
        let keep = if area == 0 {
            keep_flat
        } else {
            self.cull.keep(area)
        };
        if !keep {
            stats.culled += 1;
            return Front::Skip;
        }
        // Off the viewport on one side (the screen planes are stricter than the guard band).
        let [l, top, r, bottom] = self.edges;
        let (x_lo, x_hi) = (xs[0].min(xs[1]).min(xs[2]), xs[0].max(xs[1]).max(xs[2]));
        let (y_lo, y_hi) = (ys[0].min(ys[1]).min(ys[2]), ys[0].max(ys[1]).max(ys[2]));
        if x_hi < l || x_lo > r || y_hi < top || y_lo > bottom {
            stats.outside += 1;
            return Front::Skip;
        }
        Front::Inside {
            idx,
            v: [
                (SubPoint::new(a.0, a.1), a.2),
                (SubPoint::new(b.0, b.1), b.2),
                (SubPoint::new(c.0, c.1), c.2),
            ],
        }
    }

    /// The front end's rare path, a triangle with a vertex outside the guard band: its
    /// clip-space vertices for the clipper, or nothing when it lies wholly outside one plane.
    #[inline(never)]
    fn front_clip<M: MeshSource<S>>(
        &self,
        mesh: &M,
        idx: [usize; 3],
        stats: &mut RenderStats,
    ) -> Front<S, BITS> {
        let mut clip = [Vec4::default(); 3];
        let mut codes = [0; 3];
        for k in 0..3 {
            clip[k] = self.mvp.transform_point(mesh.position(idx[k]));
            codes[k] = outcode(&clip[k]);
        }
        if trivially_outside(&clip, codes) {
            stats.outside += 1;
            return Front::Skip;
        }
        Front::Clip { idx, clip, codes }
    }

    /// The front end for a triangle that has passed it once this frame (a band's binned
    /// triangle): its vertices' slots, without the tests.
    #[inline(always)]
    fn front_again<M: MeshSource<S>>(
        &self,
        mesh: &M,
        t: usize,
        scratch: &mut [VertexSlot<Sh::Stored>],
    ) -> Front<S, BITS> {
        let idx = mesh.triangle(t);
        let a = self.slot_geometry(mesh, idx[0], scratch);
        let b = self.slot_geometry(mesh, idx[1], scratch);
        let c = self.slot_geometry(mesh, idx[2], scratch);
        if a.0 == OUTSIDE || b.0 == OUTSIDE || c.0 == OUTSIDE {
            let mut ignored = RenderStats::default();
            return self.front_clip(mesh, idx, &mut ignored);
        }
        Front::Inside {
            idx,
            v: [
                (SubPoint::new(a.0, a.1), a.2),
                (SubPoint::new(b.0, b.1), b.2),
                (SubPoint::new(c.0, c.1), c.2),
            ],
        }
    }

    /// Draws a triangle the front end let through, counting it as drawn.
    #[inline(always)]
    fn draw_front<T, M>(
        &mut self,
        target: &mut T,
        mesh: &M,
        front: Front<S, BITS>,
        scratch: &mut [VertexSlot<Sh::Stored>],
        stats: &mut RenderStats,
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        match front {
            Front::Skip => Ok(()),
            Front::Inside { idx, v } => {
                if Sh::NEEDS_FACE {
                    let vin = [0, 1, 2].map(|k| self.vertex_in(mesh, idx[k]));
                    self.shading.face(&vin);
                }
                let var = self.face_values(mesh, idx, scratch);
                stats.drawn += 1;
                if Self::FUSED {
                    let fv = [
                        (v[0].0, v[0].1, var[0]),
                        (v[1].0, v[1].1, var[1]),
                        (v[2].0, v[2].1, var[2]),
                    ];
                    return self.raster_fused(target, &fv);
                }
                let sv = [0, 1, 2].map(|k| ScreenVertex {
                    p: v[k].0,
                    z: v[k].1,
                    var: var[k],
                    q: Self::q(&self.mvp.transform_point(mesh.position(idx[k]))),
                });
                self.raster(target, &sv)
            }
            Front::Clip { idx, clip, codes } => {
                self.draw_clipped(target, mesh, idx, clip, codes, scratch, stats)
            }
        }
    }

    /// Clips a triangle in homogeneous space and draws what is left, as a fan.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn draw_clipped<T, M>(
        &mut self,
        target: &mut T,
        mesh: &M,
        idx: [usize; 3],
        clip: [Vec4<S>; 3],
        codes: [Outcode; 3],
        scratch: &mut [VertexSlot<Sh::Stored>],
        stats: &mut RenderStats,
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        stats.clipped += 1;
        let var = self.face_values(mesh, idx, scratch);
        let tri = [0, 1, 2].map(|k| ClipVertex {
            pos: clip[k],
            var: var[k],
        });
        let poly = clip_triangle(&tri, codes);
        if poly.len() < 3 {
            stats.outside += 1;
            return Ok(());
        }
        let mut screen: heapless::Vec<
            ScreenVertex<Sh::Varyings, BITS>,
            { crate::clip::polygon::MAX_CLIPPED },
        > = heapless::Vec::new();
        for v in &poly {
            let (p, z) = self.project(&v.pos);
            let _ = screen.push(ScreenVertex {
                p,
                z,
                var: v.var,
                q: Self::q(&v.pos),
            });
        }
        // The clipped polygon is convex: its total signed area decides its facing.
        let area = polygon_area(screen.iter().map(|v| v.p));
        if area == 0 || !self.cull.keep(area) {
            stats.culled += 1;
            return Ok(());
        }
        if Sh::NEEDS_FACE {
            let vin = [0, 1, 2].map(|k| self.vertex_in(mesh, idx[k]));
            self.shading.face(&vin);
        }
        for k in 1..screen.len() - 1 {
            self.raster(target, &[screen[0], screen[k], screen[k + 1]])?;
        }
        stats.drawn += 1;
        Ok(())
    }

    /// Whether visible triangles take the fused span loop ([`SpanStart::Wrapping`], affine).
    const FUSED: bool = matches!(N::SPANS, SpanStart::Wrapping) && !PERSPECTIVE;

    /// Rasterizes one screen triangle through the fused span loop.
    #[inline(always)]
    fn raster_fused<T>(
        &mut self,
        target: &mut T,
        fv: &[FusedVertex<Sh::Varyings, BITS>; 3],
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
    {
        if self.area.is_empty() {
            return Ok(());
        }
        fill_fused::<_, _, _, _, BITS>(
            target,
            &mut self.depth,
            fv,
            &self.area,
            Precision {
                frac: Sh::FUSED_FRAC,
                offset: Sh::FUSED_OFFSET,
            },
            ShaderColor::<S, Sh>(&self.shading, core::marker::PhantomData),
        )
    }

    /// Rasterizes one screen triangle with the pipeline's depth test and shading: through the
    /// fused span loop, or the exact interpolator ([`SpanStart::Exact`], [`SpanStart::Gradient`]
    /// or perspective-correct).
    #[inline(always)]
    fn raster<T>(
        &mut self,
        target: &mut T,
        sv: &[ScreenVertex<Sh::Varyings, BITS>; 3],
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
    {
        let shading = &self.shading;
        if Self::FUSED {
            let fv = sv.map(|v| (v.p, v.z, v.var));
            self.raster_fused(target, &fv)
        } else {
            fill_triangle_interp_with::<_, _, _, _, N, BITS, PERSPECTIVE>(
                target,
                &mut self.depth,
                *sv,
                |v| shading.pixel(v),
            )
        }
    }

    /// Draws a mesh filled with the pipeline's shading, depth test and culling.
    ///
    /// `scratch` holds one [`VertexSlot`] per mesh vertex (its contents on entry do not matter):
    /// each vertex is transformed and projected once when the draw begins, and shaded once, by the
    /// first visible triangle that uses it (a vertex of back faces only is never lit).
    /// A vertex beyond the scratch's length is processed again by every triangle that uses it
    /// (about six times for a closed mesh): a short scratch, even an empty one, is slower, never
    /// wrong, and draws the same pixels.
    ///
    /// # Errors
    /// [`DrawError::DepthTooSmall`] when the depth stage does not cover the viewport within the
    /// target (nothing is drawn); [`DrawError::Target`] when the target fails.
    pub fn draw<T, M>(
        &mut self,
        target: &mut T,
        mesh: &M,
        scratch: &mut [VertexSlot<Sh::Stored>],
    ) -> Result<RenderStats, DrawError<T::Error>>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        let target = &mut ClipTo::new(target, self.viewport.rectangle());
        let needed = target.clip_area();
        if needed.size.width > 0 && needed.size.height > 0 && !self.depth.covers(&needed) {
            return Err(DrawError::DepthTooSmall { needed });
        }
        self.begin(mesh, scratch);
        let mut stats = RenderStats {
            triangles: mesh.triangle_count().min(u32::MAX as usize) as u32,
            ..RenderStats::default()
        };
        for t in 0..mesh.triangle_count() {
            let front = self.front(mesh, t, scratch, &mut stats, false);
            self.draw_front(target, mesh, front, scratch, &mut stats)?;
        }
        Ok(stats)
    }

    /// Draws a mesh's edges in one colour, clipped in homogeneous space (nothing behind the camera
    /// is drawn) and then to the target. Culling applies, so a closed mesh shows only its front
    /// edges; there is no depth test. `scratch` is as in [`Pipeline::draw`].
    pub fn draw_wireframe<T, M>(
        &mut self,
        target: &mut T,
        mesh: &M,
        scratch: &mut [VertexSlot<Sh::Stored>],
        color: T::Color,
    ) -> Result<RenderStats, T::Error>
    where
        T: Surface,
        M: MeshSource<S>,
    {
        let target = &mut ClipTo::new(target, self.viewport.rectangle());
        self.begin(mesh, scratch);
        let mut stats = RenderStats {
            triangles: mesh.triangle_count().min(u32::MAX as usize) as u32,
            ..RenderStats::default()
        };
        let px = |p: SubPoint<BITS>| Point::new(p.x >> BITS, p.y >> BITS);
        for t in 0..mesh.triangle_count() {
            match self.front(mesh, t, scratch, &mut stats, true) {
                Front::Skip => {}
                Front::Inside { v, .. } => {
                    for k in 0..3 {
                        draw_line(target, px(v[k].0), px(v[(k + 1) % 3].0), color)?;
                    }
                    stats.drawn += 1;
                }
                Front::Clip { clip, codes, .. } => {
                    if codes.iter().any(|&c| c != 0) {
                        stats.clipped += 1;
                    }
                    // Facing from the clipped polygon's area, as for filled triangles.
                    let tri = clip.map(|pos| ClipVertex {
                        pos,
                        var: [0i32; 0],
                    });
                    let poly = clip_triangle(&tri, codes);
                    if poly.len() < 3 {
                        stats.outside += 1;
                        continue;
                    }
                    let area = polygon_area(poly.iter().map(|v| self.project(&v.pos).0));
                    if area != 0 && !self.cull.keep(area) {
                        stats.culled += 1;
                        continue;
                    }
                    // The visible part of each of the triangle's own edges; the pixel of a point
                    // is the one that contains it.
                    for k in 0..3 {
                        if let Some((a, b)) = clip_segment(clip[k], clip[(k + 1) % 3]) {
                            let (pa, pb) = (self.project(&a).0, self.project(&b).0);
                            draw_line(target, px(pa), px(pb), color)?;
                        }
                    }
                    stats.drawn += 1;
                }
            }
        }
        Ok(stats)
    }
}

/// The viewport's edges in sub-pixel units: left, top, right, bottom.
fn viewport_edges<const BITS: u32>(vp: &Viewport) -> [i64; 4] {
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

    /// The data of vertex `i` the shader may read.
    #[inline(always)]
    fn vertex_in<Sh: Shading<S>, M: MeshSource<S>>(&self, mesh: &M, i: usize) -> VertexIn<S> {
        let color = mesh.color(i).unwrap_or(Rgb888::WHITE);
        if !Sh::NEEDS_WORLD {
            return VertexIn {
                position: Vec3::default(),
                normal: Vec3::default(),
                color,
            };
        }
        let normal = mesh.normal(i).unwrap_or_default();
        if self.model_space {
            return VertexIn {
                position: mesh.position(i),
                normal,
                color,
            };
        }
        VertexIn {
            position: self.model.transform_point(mesh.position(i)).xyz(),
            normal: self.normal_matrix.transform_dir(normal),
            color,
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
    use vertex::Stored;
    let mut vin = space.vertex_in::<Sh, M>(mesh, i);
    if let Some(n) = normal {
        vin.normal = n;
    }
    Sh::Stored::pack(&shading.vertex(&vin))
}

/// A shader as the fused span loop's colour source.
struct ShaderColor<'a, S, Sh>(&'a Sh, core::marker::PhantomData<S>);

impl<S: Scalar, Sh: Shading<S>> FusedColor<Sh::Color> for ShaderColor<'_, S, Sh> {
    #[inline(always)]
    fn color(&self, acc: &[u32; MAX_VARYINGS]) -> Sh::Color {
        self.0.pixel_fused(acc)
    }
}

/// The signed doubled area of a convex polygon of screen points, saturated to `i64` (its sign
/// and whether it is zero are exact).
fn polygon_area<const BITS: u32>(points: impl Iterator<Item = SubPoint<BITS>> + Clone) -> i64 {
    let mut it = points.clone();
    let Some(a) = it.next() else { return 0 };
    // Projected points may lie anywhere in i32 (the projection clamps there): differences need 33
    // bits and their products 66, so the sum is taken in i128.
    let mut area = 0i128;
    let mut prev: Option<SubPoint<BITS>> = None;
    let d = |p: i32, q: i32| i128::from(p) - i128::from(q);
    for c in it {
        if let Some(b) = prev {
            area += d(b.x, a.x) * d(c.y, a.y) - d(c.x, a.x) * d(b.y, a.y);
        }
        prev = Some(c);
    }
    area.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64
}
