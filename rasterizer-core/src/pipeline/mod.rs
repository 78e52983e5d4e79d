//! The 3D pipeline: mesh -> vertex transform -> clip -> project -> cull -> raster -> shade -> target.
//!
//! [`Pipeline`] is generic over its stages: culling ([`cull`]), the depth test
//! ([`crate::raster::interp::DepthTest`]) and the shading model ([`shading`]). A stage that is off
//! is a zero-sized type whose methods are empty, so a frame without depth, culling or lighting
//! compiles none of that code and keeps none of its state. Geometry runs in any
//! [`crate::math::Scalar`] (16.16 by default); everything after the perspective divide is integer.

pub mod cull;
pub mod shading;

use crate::clip::polygon::{
    clip_segment, clip_triangle, outcode, trivially_outside, ClipVertex, Outcode,
};
use crate::geom::SubPoint;
use crate::math::{Mat4, Scalar, Vec3, Vec4};
use crate::numerics::{reciprocal, Divide, Numerics, Standard};
use crate::raster::edge::row_at_or_below;
use crate::raster::interp::{fill_triangle_interp_with, DepthTest, ScreenVertex};
use crate::raster::line::draw_line;
use crate::target::{Band, ClipTo, Framebuffer, Storage, Surface};
use cull::Cull;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::Rgb888;
use embedded_graphics_core::prelude::RgbColor;
use embedded_graphics_core::primitives::Rectangle;
use shading::{Shading, VertexIn};

/// The sub-pixel bits of screen coordinates a [`Pipeline`] (and its [`CachedVertex`]) has unless
/// told otherwise: 6, so 26.6 (`docs/ACCURACY.md` measures the choice).
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
/// Beyond that the clip rectangle, [`Viewport::rectangle`], is clamped to 32767 x 32767 pixels and
/// to the `i32` plane (it never reaches past `i32::MAX`), so nothing is drawn outside it or the
/// target. The mapping from device coordinates still uses the fields as given, and its arithmetic
/// is sized for the documented range only.
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

/// One vertex's work, kept for the other triangles that share it ([`Pipeline::draw_cached`]).
///
/// Its size is the RAM a cached draw needs per mesh vertex: 40 bytes for 16.16 with three
/// varyings (Gouraud), so 20 KB for Suzanne's 507 vertices.
#[derive(Debug, Clone, Copy, Default)]
pub struct CachedVertex<S, V, const BITS: u32 = DEFAULT_BITS> {
    clip: Vec4<S>,
    screen: SubPoint<BITS>,
    z: u16,
    code: Outcode,
    /// 0: nothing yet; 1: transformed (and projected when inside); 2: also shaded.
    state: u8,
    var: V,
}

/// A visible triangle's place in a banded frame ([`Pipeline::draw_banded`]): 12 bytes a triangle.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BinEntry {
    triangle: u32,
    first: u32,
    last: u32,
}

impl BinEntry {
    /// An empty entry, for initialising a `static` array of bins.
    pub const ZERO: BinEntry = BinEntry {
        triangle: 0,
        first: 0,
        last: 0,
    };
}

/// How a frame is cut into bands ([`Pipeline::draw_banded`]).
#[derive(Debug, Clone, Copy)]
pub struct Banding<C> {
    /// Screen width in pixels.
    pub width: u32,
    /// Screen height in pixels.
    pub height: u32,
    /// Rows per band (the last band may have fewer).
    pub rows: u32,
    /// The colour each band starts from.
    pub background: C,
    /// The depth each band's depth buffer starts from (65535 for [`Compare::Less`]).
    ///
    /// [`Compare::Less`]: crate::raster::interp::Compare::Less
    pub clear_depth: u16,
}

/// Why a banded draw could not start.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BandError {
    /// Zero rows per band, or a zero height.
    NoRows,
    /// A screen size the framebuffer cannot have.
    BadSize {
        /// Width.
        width: u32,
        /// Height.
        height: u32,
    },
    /// The band buffer is shorter than one band.
    BandBufferTooSmall {
        /// Words one band needs.
        needed: usize,
        /// Words given.
        actual: usize,
    },
    /// More visible triangles than bins.
    TooFewBins {
        /// Visible triangles.
        needed: usize,
        /// Bins given.
        actual: usize,
    },
}

impl core::fmt::Display for BandError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NoRows => write!(f, "a band needs at least one row"),
            Self::BadSize { width, height } => write!(f, "bad screen size {width}x{height}"),
            Self::BandBufferTooSmall { needed, actual } => {
                write!(f, "band buffer has {actual} words, a band needs {needed}")
            }
            Self::TooFewBins { needed, actual } => {
                write!(f, "{needed} visible triangles but only {actual} bins")
            }
        }
    }
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
    model: Mat4<S>,
    normal_matrix: Mat4<S>,
    viewport: Viewport,
    /// The culling stage.
    pub cull: C,
    /// The depth stage.
    pub depth: D,
    /// The shading stage.
    pub shading: Sh,
    _numerics: core::marker::PhantomData<N>,
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
        Self {
            mvp,
            model: transforms.model,
            normal_matrix: transforms.model,
            viewport,
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
            model: self.model,
            normal_matrix: self.normal_matrix,
            viewport: self.viewport,
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

    /// The world-space data of a vertex the shader may read.
    #[inline(always)]
    fn vertex_in<M: MeshSource<S>>(&self, mesh: &M, i: usize) -> VertexIn<S> {
        let color = mesh.color(i).unwrap_or(Rgb888::WHITE);
        if !Sh::NEEDS_WORLD {
            return VertexIn {
                position: Vec3::default(),
                normal: Vec3::default(),
                color,
            };
        }
        let position = self.model.transform_point(mesh.position(i)).xyz();
        let normal = match mesh.normal(i) {
            Some(n) => self.normal_matrix.transform_dir(n),
            None => Vec3::default(),
        };
        VertexIn {
            position,
            normal,
            color,
        }
    }

    /// Draws a mesh filled with the pipeline's shading, depth test and culling.
    ///
    /// Each triangle transforms and shades its three vertices, so a vertex shared by six triangles
    /// is processed six times; [`Pipeline::draw_cached`] trades RAM for that work.
    pub fn draw<T, M>(&mut self, target: &mut T, mesh: &M) -> Result<RenderStats, T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        self.draw_with(
            &mut ClipTo::new(target, self.viewport.rectangle()),
            mesh,
            &mut [],
        )
    }

    /// Draws a mesh like [`Pipeline::draw`], processing each vertex at most once: `cache` holds
    /// one [`CachedVertex`] per mesh vertex (its contents on entry do not matter). Vertices beyond
    /// the cache's length are processed per triangle, so a short cache is slower, never wrong.
    pub fn draw_cached<T, M>(
        &mut self,
        target: &mut T,
        mesh: &M,
        cache: &mut [CachedVertex<S, Sh::Varyings, BITS>],
    ) -> Result<RenderStats, T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        for c in cache.iter_mut() {
            c.state = 0;
        }
        self.draw_with(
            &mut ClipTo::new(target, self.viewport.rectangle()),
            mesh,
            cache,
        )
    }

    /// A vertex's clip-space position and outcode, from the cache when it has them.
    #[inline(always)]
    fn clip_of<M: MeshSource<S>>(
        &self,
        mesh: &M,
        i: usize,
        cache: &mut [CachedVertex<S, Sh::Varyings, BITS>],
    ) -> (Vec4<S>, Outcode) {
        if let Some(c) = cache.get_mut(i) {
            if c.state == 0 {
                c.clip = self.mvp.transform_point(mesh.position(i));
                c.code = outcode(&c.clip);
                if c.code == 0 {
                    (c.screen, c.z) = self.project(&c.clip);
                }
                c.state = 1;
            }
            return (c.clip, c.code);
        }
        let clip = self.mvp.transform_point(mesh.position(i));
        (clip, outcode(&clip))
    }

    /// A vertex's shader values, from the cache when it has them.
    #[inline(always)]
    fn var_of<M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        i: usize,
        cache: &mut [CachedVertex<S, Sh::Varyings, BITS>],
    ) -> Sh::Varyings {
        if let Some(c) = cache.get_mut(i) {
            if c.state < 2 {
                let vin = self.vertex_in(mesh, i);
                c.var = self.shading.vertex(&vin);
                c.state = 2;
            }
            return c.var;
        }
        let vin = self.vertex_in(mesh, i);
        self.shading.vertex(&vin)
    }

    /// The shader values of a triangle's three vertices. A lit shader on a mesh without normals
    /// gets the face normal (the cross product of the edges in world space) at all three, which
    /// depends on the face, so those values are never cached.
    #[inline(always)]
    fn face_vars<M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        idx: [usize; 3],
        cache: &mut [CachedVertex<S, Sh::Varyings, BITS>],
    ) -> [Sh::Varyings; 3] {
        if Sh::NEEDS_WORLD && !mesh.has_normals() {
            let mut vin = idx.map(|i| self.vertex_in(mesh, i));
            let e1 = vin[1].position - vin[0].position;
            let normal = e1.cross(vin[2].position - vin[0].position);
            for v in &mut vin {
                v.normal = normal;
            }
            return vin.map(|v| self.shading.vertex(&v));
        }
        idx.map(|i| self.var_of(mesh, i, cache))
    }

    fn draw_with<T, M>(
        &mut self,
        target: &mut T,
        mesh: &M,
        cache: &mut [CachedVertex<S, Sh::Varyings, BITS>],
    ) -> Result<RenderStats, T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        let mut stats = RenderStats {
            triangles: mesh.triangle_count().min(u32::MAX as usize) as u32,
            ..RenderStats::default()
        };
        for t in 0..mesh.triangle_count() {
            self.draw_triangle(target, mesh, t, cache, &mut stats)?;
        }
        Ok(stats)
    }

    /// The signed doubled area of a convex polygon of screen points.
    fn polygon_area(points: impl Iterator<Item = SubPoint<BITS>> + Clone) -> i64 {
        let mut it = points.clone();
        let Some(a) = it.next() else { return 0 };
        let mut area = 0i64;
        let mut prev: Option<SubPoint<BITS>> = None;
        for c in it {
            if let Some(b) = prev {
                area += (i64::from(b.x) - i64::from(a.x)) * (i64::from(c.y) - i64::from(a.y))
                    - (i64::from(c.x) - i64::from(a.x)) * (i64::from(b.y) - i64::from(a.y));
            }
            prev = Some(c);
        }
        area
    }

    /// The rows triangle `t` can touch once it is clipped, or why it draws nothing (counted in
    /// `stats`). Geometry only: no shading.
    fn triangle_rows<M: MeshSource<S>>(
        &mut self,
        mesh: &M,
        t: usize,
        cache: &mut [CachedVertex<S, Sh::Varyings, BITS>],
        stats: &mut RenderStats,
    ) -> Option<(i64, i64)> {
        let idx = mesh.triangle(t);
        if idx.iter().any(|&i| i >= mesh.vertex_count()) {
            stats.invalid += 1;
            return None;
        }
        let vc = idx.map(|i| self.clip_of(mesh, i, cache));
        let clip = vc.map(|(p, _)| p);
        let codes = vc.map(|(_, c)| c);
        if trivially_outside(&clip, codes) {
            stats.outside += 1;
            return None;
        }
        let mut ys: heapless::Vec<SubPoint<BITS>, { crate::clip::polygon::MAX_CLIPPED }> =
            heapless::Vec::new();
        if codes.iter().all(|&c| c == 0) {
            for k in 0..3 {
                let p = match cache.get(idx[k]) {
                    Some(c) => c.screen,
                    None => self.project(&clip[k]).0,
                };
                let _ = ys.push(p);
            }
        } else {
            stats.clipped += 1;
            let tri = clip.map(|pos| ClipVertex {
                pos,
                var: [0i32; 0],
            });
            let poly = clip_triangle(&tri, codes);
            if poly.len() < 3 {
                stats.outside += 1;
                return None;
            }
            for v in &poly {
                let _ = ys.push(self.project(&v.pos).0);
            }
        }
        let area = Self::polygon_area(ys.iter().copied());
        if area == 0 || !self.cull.keep(area) {
            stats.culled += 1;
            return None;
        }
        stats.drawn += 1;
        let top = ys.iter().map(|p| p.y).min().unwrap_or(0);
        let bottom = ys.iter().map(|p| p.y).max().unwrap_or(0);
        let s = 1i64 << BITS;
        Some((
            row_at_or_below(i64::from(top), s),
            row_at_or_below(i64::from(bottom), s),
        ))
    }

    /// Draws triangle `t` of `mesh`, counting what happened in `stats`.
    fn draw_triangle<T, M>(
        &mut self,
        target: &mut T,
        mesh: &M,
        t: usize,
        cache: &mut [CachedVertex<S, Sh::Varyings, BITS>],
        stats: &mut RenderStats,
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        let idx = mesh.triangle(t);
        if idx.iter().any(|&i| i >= mesh.vertex_count()) {
            stats.invalid += 1;
            return Ok(());
        }
        let vc = idx.map(|i| self.clip_of(mesh, i, cache));
        let clip = vc.map(|(p, _)| p);
        let codes = vc.map(|(_, c)| c);
        if trivially_outside(&clip, codes) {
            stats.outside += 1;
            return Ok(());
        }
        if codes.iter().all(|&c| c == 0) {
            // The common case: project first, so culled triangles are never shaded.
            let projected = [0, 1, 2].map(|k| match cache.get(idx[k]) {
                Some(c) => (c.screen, c.z),
                None => self.project(&clip[k]),
            });
            let area = Self::polygon_area(projected.iter().map(|(p, _)| *p));
            if area == 0 || !self.cull.keep(area) {
                stats.culled += 1;
                return Ok(());
            }
            if Sh::NEEDS_FACE {
                let vin = idx.map(|i| self.vertex_in(mesh, i));
                self.shading.face(&vin);
            }
            let var = self.face_vars(mesh, idx, cache);
            let sv = [0, 1, 2].map(|k| ScreenVertex {
                p: projected[k].0,
                z: projected[k].1,
                var: var[k],
                q: Self::q(&clip[k]),
            });
            let shading = &self.shading;
            fill_triangle_interp_with::<_, _, _, _, N, BITS, PERSPECTIVE>(
                target,
                &mut self.depth,
                sv,
                |v| shading.pixel(v),
            )?;
            stats.drawn += 1;
            return Ok(());
        }
        stats.clipped += 1;
        let var = self.face_vars(mesh, idx, cache);
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
        let area = Self::polygon_area(screen.iter().map(|v| v.p));
        if area == 0 || !self.cull.keep(area) {
            stats.culled += 1;
            return Ok(());
        }
        if Sh::NEEDS_FACE {
            let vin = idx.map(|i| self.vertex_in(mesh, i));
            self.shading.face(&vin);
        }
        let shading = &self.shading;
        for k in 1..screen.len() - 1 {
            let t = [screen[0], screen[k], screen[k + 1]];
            fill_triangle_interp_with::<_, _, _, _, N, BITS, PERSPECTIVE>(
                target,
                &mut self.depth,
                t,
                |v| shading.pixel(v),
            )?;
        }
        stats.drawn += 1;
        Ok(())
    }

    /// Draws a mesh one horizontal band at a time, for a microcontroller that cannot hold a whole
    /// frame: each band is drawn into `band` (a buffer of `banding.rows` rows) and handed to
    /// `on_band` (where firmware starts the transfer to the display), then reused for the next.
    ///
    /// The pipeline's depth stage must hold `banding.rows` rows too (a [`DepthBuffer`] of
    /// `width` x `rows`); it is cleared to `banding.clear_depth` before each band. Triangles are
    /// binned once per frame (`bins` holds one entry per visible triangle), so each band draws
    /// only the triangles that touch it, in mesh order; finding them is one test per bin and band
    /// (about 9,000 for M1's 613 visible triangles in 15 bands, far below the drawing). `cache` is
    /// as in [`Pipeline::draw_cached`] (may be empty: vertices shared across bands are then
    /// processed again). The pixels are exactly those of a whole-frame [`Pipeline::draw`] of the same scene,
    /// for any band height.
    ///
    /// [`DepthBuffer`]: crate::raster::interp::DepthBuffer
    ///
    /// # Errors
    /// [`BandError`] for a band buffer of the wrong size, zero rows, or too few bins (nothing is
    /// drawn then).
    pub fn draw_banded<Px, M, F>(
        &mut self,
        mesh: &M,
        banding: &Banding<Px>,
        band: &mut [Px::Word],
        bins: &mut [BinEntry],
        cache: &mut [CachedVertex<S, Sh::Varyings, BITS>],
        mut on_band: F,
    ) -> Result<RenderStats, BandError>
    where
        Px: Storage,
        Sh: Shading<S, Color = Px>,
        M: MeshSource<S>,
        F: FnMut(&Band<'_, Px>),
    {
        let (width, height, rows) = (banding.width, banding.height, banding.rows);
        if rows == 0 || height == 0 {
            return Err(BandError::NoRows);
        }
        let needed = Framebuffer::<Px>::required_len(width, rows.min(height))
            .ok_or(BandError::BadSize { width, height })?;
        if band.len() < needed {
            return Err(BandError::BandBufferTooSmall {
                needed,
                actual: band.len(),
            });
        }
        for c in cache.iter_mut() {
            c.state = 0;
        }
        // Bin: each visible triangle's first and last band.
        let mut stats = RenderStats {
            triangles: mesh.triangle_count().min(u32::MAX as usize) as u32,
            ..RenderStats::default()
        };
        let mut count = 0usize;
        let mut wanted = 0usize;
        for t in 0..mesh.triangle_count() {
            let Some((top, bottom)) = self.triangle_rows(mesh, t, cache, &mut stats) else {
                continue;
            };
            let (top, bottom) = (top.max(0), bottom.min(i64::from(height)));
            if top >= bottom {
                continue;
            }
            wanted += 1;
            if let Some(slot) = bins.get_mut(count) {
                *slot = BinEntry {
                    triangle: t as u32,
                    first: (top / i64::from(rows)) as u32,
                    last: ((bottom - 1) / i64::from(rows)) as u32,
                };
                count += 1;
            }
        }
        if wanted > bins.len() {
            return Err(BandError::TooFewBins {
                needed: wanted,
                actual: bins.len(),
            });
        }
        // The bins stay in mesh order, and each band scans them for the triangles that touch it:
        // the order a whole-frame draw has, for a test per bin and band. (Keeping a window sorted
        // by first band and then by triangle cost M1 in 16-row bands 11 % of its frame.) `lo`
        // skips the leading bins that ended above the band.
        let bins = &bins[..count];
        let mut lo = 0usize;
        let mut scratch = RenderStats::default();
        let bands = height.div_ceil(rows);
        for b in 0..bands {
            while bins.get(lo).is_some_and(|e| e.last < b) {
                lo += 1;
            }
            let y0 = b * rows;
            let h = rows.min(height - y0);
            let len = Framebuffer::<Px>::required_len(width, h).unwrap_or(0);
            let Ok(mut fb) = Framebuffer::<Px>::new(&mut band[..len], width, h) else {
                return Err(BandError::BadSize { width, height });
            };
            let _ = DrawTarget::clear(&mut fb, banding.background);
            self.depth.start_band(y0 as i32, banding.clear_depth);
            let mut strip = Band::new(fb, y0 as i32);
            {
                let mut target = ClipTo::new(&mut strip, self.viewport.rectangle());
                for e in bins[lo..].iter().filter(|e| e.first <= b && b <= e.last) {
                    let Ok(()) = self.draw_triangle(
                        &mut target,
                        mesh,
                        e.triangle as usize,
                        cache,
                        &mut scratch,
                    );
                }
            }
            on_band(&strip);
        }
        Ok(stats)
    }

    /// Draws a mesh's edges in one colour, clipped in homogeneous space (nothing behind the camera
    /// is drawn) and then to the target. Culling applies, so a closed mesh shows only its front
    /// edges; there is no depth test.
    pub fn draw_wireframe<T, M>(
        &mut self,
        target: &mut T,
        mesh: &M,
        color: T::Color,
    ) -> Result<RenderStats, T::Error>
    where
        T: Surface,
        M: MeshSource<S>,
    {
        let target = &mut ClipTo::new(target, self.viewport.rectangle());
        let mut stats = RenderStats {
            triangles: mesh.triangle_count().min(u32::MAX as usize) as u32,
            ..RenderStats::default()
        };
        let n = mesh.vertex_count();
        for t in 0..mesh.triangle_count() {
            let idx = mesh.triangle(t);
            if idx.iter().any(|&i| i >= n) {
                stats.invalid += 1;
                continue;
            }
            let clip = idx.map(|i| self.mvp.transform_point(mesh.position(i)));
            let codes = clip.map(|p| outcode(&p));
            if trivially_outside(&clip, codes) {
                stats.outside += 1;
                continue;
            }
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
            let corners: heapless::Vec<SubPoint<BITS>, { crate::clip::polygon::MAX_CLIPPED }> =
                poly.iter().map(|v| self.project(&v.pos).0).collect();
            let mut area = 0i64;
            for k in 1..corners.len() - 1 {
                let (a, b, c) = (corners[0], corners[k], corners[k + 1]);
                area += (i64::from(b.x) - i64::from(a.x)) * (i64::from(c.y) - i64::from(a.y))
                    - (i64::from(c.x) - i64::from(a.x)) * (i64::from(b.y) - i64::from(a.y));
            }
            if area != 0 && !self.cull.keep(area) {
                stats.culled += 1;
                continue;
            }
            // The visible part of each of the triangle's own edges; the pixel of a point is the one
            // that contains it.
            for k in 0..3 {
                if let Some((a, b)) = clip_segment(clip[k], clip[(k + 1) % 3]) {
                    let (pa, pb) = (self.project(&a).0, self.project(&b).0);
                    let px = |p: SubPoint<BITS>| Point::new(p.x >> BITS, p.y >> BITS);
                    draw_line(target, px(pa), px(pb), color)?;
                }
            }
            stats.drawn += 1;
        }
        Ok(stats)
    }
}
