//! The 3D pipeline: mesh -> vertex transform -> clip -> project -> cull -> raster -> shade -> target.
//!
//! [`Pipeline`] is generic over its stages: culling ([`crate::cull`]), the depth test
//! ([`crate::depth::DepthTest`]) and the shading model ([`crate::shade`]). A stage that is off
//! is a zero-sized type whose methods are empty, so a frame without depth, culling or lighting
//! compiles none of that code and keeps none of its state. Geometry runs in any
//! [`crate::math::Scalar`] (16.16 by default); everything after the perspective divide is integer.
//!
//! Every draw call runs each triangle through one front end (fetch, transform once per vertex
//! into the caller's [`VertexSlot`] scratch, trivial rejection, culling); the filled, banded and
//! wireframe paths differ only in what they do with the triangles it lets through. With the
//! default numerics a visible triangle is drawn by the raster stage's fused span loop: depth test,
//! interpolation and colour in one loop per span.
//!
//! Files: `front.rs` is the front end, `vertex.rs` the per-vertex work (transform, projection,
//! shading into the scratch), `band.rs` band rendering, `silhouette.rs` anti-aliased silhouettes.

mod band;
mod front;
mod perspective;
mod silhouette;
mod vertex;

pub use crate::raster::silhouette::AA_RANGE_PIXELS;
pub use band::{BandError, Banding, BinEntry};
pub use vertex::VertexSlot;

use crate::clip::polygon::{clip_segment, clip_triangle, ClipVertex};
use crate::cull::{Cull, CullClockwise};
use crate::depth::{DepthBuffer, DepthTest};
use crate::geom::{PixelRect, SubPoint};
use crate::math::{Fx16, Mat4, Scalar};
use crate::mesh::MeshSource;
use crate::numerics::{Numerics, Standard};
use crate::raster::line::draw_line;
use crate::shade::{GouraudLit, Shading};
use crate::surface::{ClipTo, Surface};
use crate::transform::{Transforms, Viewport};
use embedded_graphics_core::geometry::Point;
use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_graphics_core::primitives::Rectangle;
use front::{polygon_area, Front};
use vertex::{viewport_edges, RawMvp, ScreenMap};

/// The sub-pixel bits of screen coordinates a [`Pipeline`] has unless told otherwise: 6, so
/// 26.6 (`docs/ACCURACY.md` measures the choice).
pub const DEFAULT_BITS: u32 = 6;

/// The common lit pipeline, for where its type must be written (a struct field, a function's
/// return type): 16.16 geometry, back faces culled (counter-clockwise meshes), a depth buffer, and
/// Gouraud lighting with up to `LIGHTS` lights into `C` pixels.
pub type GouraudPipeline<'d, C = Rgb565, const LIGHTS: usize = 1> =
    Pipeline<Fx16, CullClockwise, DepthBuffer<'d>, GouraudLit<Fx16, C, LIGHTS>>;

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
    /// The mesh cannot be drawn with anti-aliased silhouettes ([`Pipeline::draw_antialiased`]):
    /// nothing is drawn.
    Antialias(AntialiasError),
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
            Self::Antialias(e) => write!(f, "cannot anti-alias: {e}"),
        }
    }
}

impl<E: core::fmt::Debug> core::error::Error for DrawError<E> {}

/// Why a mesh cannot be drawn with anti-aliased silhouettes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AntialiasError {
    /// The target cannot read back its pixels ([`Surface::READ_BACK`]), which blending needs.
    CannotReadBack,
    /// The mesh has no edge adjacency ([`MeshSource::has_adjacency`]): convert it with
    /// `--adjacency`, or give a [`crate::mesh::Mesh`] one with
    /// [`crate::mesh::Mesh::with_adjacency`].
    NoAdjacency,
    /// The pipeline's numerics do not take the fused span loop ([`crate::numerics::SpanStart`]
    /// other than `Wrapping`), which the silhouette fill is built on.
    Numerics,
}

impl core::fmt::Display for AntialiasError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::CannotReadBack => write!(f, "the target cannot read back pixels to blend into"),
            Self::NoAdjacency => write!(f, "the mesh has no edge adjacency"),
            Self::Numerics => write!(f, "anti-aliasing needs the fused span loop's numerics"),
        }
    }
}

/// Where a draw's depth stage comes from: the pipeline's own ([`Own`]), or one lent for the
/// call ([`Lend`]: a frame list's shared buffer), so that the pipeline need not move to take
/// another depth stage.
pub(crate) trait DepthFrom<D> {
    /// The depth stage drawn with.
    type Depth: DepthTest;
    /// It, given the pipeline's own.
    fn pick<'a>(&'a mut self, own: &'a mut D) -> &'a mut Self::Depth;
}

/// The pipeline's own depth stage.
pub(crate) struct Own;

impl<D: DepthTest> DepthFrom<D> for Own {
    type Depth = D;
    #[inline(always)]
    fn pick<'a>(&'a mut self, own: &'a mut D) -> &'a mut D {
        own
    }
}

/// A depth stage lent for one call.
pub(crate) struct Lend<'x, X>(pub(crate) &'x mut X);

impl<D, X: DepthTest> DepthFrom<D> for Lend<'_, X> {
    type Depth = X;
    #[inline(always)]
    fn pick<'a>(&'a mut self, _own: &'a mut D) -> &'a mut X {
        self.0
    }
}

/// A configured pipeline: transforms, viewport and the compile-time choice of stages.
///
/// `S` is the number format of the geometry ([`crate::math::Fx16`] for 16.16), `C` the culling
/// stage ([`crate::cull`]), `D` the depth stage ([`crate::depth`]) and `Sh` the shading model
/// ([`crate::shade`]); all four are inferred from [`Pipeline::new`]'s arguments.
///
/// `BITS` is the number of sub-pixel bits of screen coordinates (0 to 8; 6 by default, 26.6, which
/// `docs/ACCURACY.md` measures against 4) and `N` the remaining accuracy knobs
/// ([`crate::numerics`]: the divide method, the precision of interpolation, perspective-correct
/// values). [`Pipeline::new`] makes a pipeline with the defaults; [`Pipeline::with_bits`] and
/// [`Pipeline::with_numerics`] change them.
#[derive(Debug, Clone)]
pub struct Pipeline<S, C, D, Sh, const BITS: u32 = DEFAULT_BITS, N = Standard> {
    mvp: Mat4<S>,
    /// The MVP's raw integers, for a fixed-point format whose entries are small enough to
    /// transform a vertex without checks ([`RawMvp`]).
    raw: Option<RawMvp>,
    model: Mat4<S>,
    normal_matrix: Mat4<S>,
    pub(crate) viewport: Viewport,
    /// The viewport's pixels, and its edges in sub-pixel units (left, top, right, bottom).
    pub(crate) area: PixelRect,
    edges: [i64; 4],
    /// The viewport's mapping for the projection's fast path.
    map: ScreenMap,
    /// The shader takes model-space positions and normals this frame.
    model_space: bool,
    /// The model-view matrix mirrors: winding on screen is the reverse of the mesh's.
    mirrored: bool,
    /// All ones when culling must negate screen areas (mirrored, not [`Cull::WINDOW_SPACE`]),
    /// else zero: a branch-free negation per triangle.
    facing: i64,
    /// The model matrix mirrors: a cross product of world-space edges points into the mesh.
    model_mirrors: bool,
    /// This frame, the shader lights in world space under a mirroring model matrix: face
    /// normals from world-space edges must be turned round.
    flip_faces: bool,
    /// This frame, every vertex lies inside the viewport (all have slots, none outside the
    /// guard band): no triangle can miss it, so the front end does not test it.
    in_viewport: bool,
    /// The culling stage.
    pub cull: C,
    /// The depth stage.
    pub depth: D,
    /// The shading stage.
    pub shading: Sh,
    _numerics: core::marker::PhantomData<N>,
}

impl<S, C, D, Sh> Pipeline<S, C, D, Sh>
where
    S: Scalar,
    C: Cull,
    D: DepthTest,
    Sh: Shading<S>,
{
    /// A pipeline. Normals are transformed by the model matrix's upper 3x3, which is right for
    /// rotations, reflections, translations and uniform scales; use [`Pipeline::set_normal_matrix`]
    /// with the inverse transpose for shear or non-uniform scale.
    ///
    /// The pipeline has the default sub-pixel bits ([`DEFAULT_BITS`]) and numeric knobs
    /// ([`Standard`]); [`Pipeline::with_bits`] and [`Pipeline::with_numerics`] change them.
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
        let max = crate::surface::MAX_DIMENSION;
        let viewport = Viewport {
            width: viewport.width.min(max),
            height: viewport.height.min(max),
            ..viewport
        };
        let model_mirrors = transforms.model.mirrors();
        let mirrored = model_mirrors != transforms.view.mirrors();
        Self {
            raw: RawMvp::new(&mvp),
            mvp,
            model: transforms.model,
            normal_matrix: transforms.model,
            mirrored,
            facing: -i64::from(mirrored && !C::WINDOW_SPACE),
            model_mirrors,
            flip_faces: false,
            in_viewport: false,
            viewport,
            area: PixelRect::from_rectangle(&viewport.rectangle()),
            edges: viewport_edges::<DEFAULT_BITS>(&viewport),
            map: ScreenMap::new::<DEFAULT_BITS>(&viewport),
            model_space: false,
            cull,
            depth,
            shading,
            _numerics: core::marker::PhantomData,
        }
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
    /// The same pipeline with other numeric knobs ([`crate::numerics`]), e.g.
    /// `Pipeline::new(..).with_numerics::<Perspective>()`.
    ///
    /// [`Perspective`]: crate::numerics::Perspective
    pub fn with_numerics<M: Numerics>(self) -> Pipeline<S, C, D, Sh, BITS, M> {
        self.with::<BITS, M>()
    }

    /// The same pipeline with `B` sub-pixel bits of screen coordinates (0 to 8), e.g.
    /// `Pipeline::new(..).with_bits::<4>()`.
    pub fn with_bits<const B: u32>(self) -> Pipeline<S, C, D, Sh, B, N> {
        self.with::<B, N>()
    }

    fn with<const B: u32, M: Numerics>(self) -> Pipeline<S, C, D, Sh, B, M> {
        Pipeline {
            mvp: self.mvp,
            raw: self.raw,
            model: self.model,
            normal_matrix: self.normal_matrix,
            mirrored: self.mirrored,
            facing: self.facing,
            model_mirrors: self.model_mirrors,
            flip_faces: false,
            in_viewport: false,
            viewport: self.viewport,
            area: self.area,
            edges: viewport_edges::<B>(&self.viewport),
            map: ScreenMap::new::<B>(&self.viewport),
            model_space: false,
            cull: self.cull,
            depth: self.depth,
            shading: self.shading,
            _numerics: core::marker::PhantomData,
        }
    }

    /// Feeds everything that decides the pipeline's picture of a given mesh to `out`: its
    /// matrices, viewport, culling stage and shading ([`Shading::fingerprint`]).
    pub fn fingerprint(&self, out: &mut crate::fingerprint::Fingerprint)
    where
        C: core::fmt::Debug,
        Sh: core::fmt::Debug,
    {
        use core::fmt::Write;
        for m in [&self.mvp, &self.model, &self.normal_matrix] {
            for v in m.m.iter().flatten() {
                out.bytes(&v.to_fx16_bits().to_le_bytes());
            }
        }
        let vp = &self.viewport;
        for v in [vp.x, vp.y, vp.width as i32, vp.height as i32] {
            out.bytes(&v.to_le_bytes());
        }
        let _ = write!(out, "{:?}", self.cull);
        self.shading.fingerprint(out);
    }

    /// Replaces the matrix that carries normals to world space.
    pub fn set_normal_matrix(&mut self, m: Mat4<S>) {
        self.normal_matrix = m;
    }

    /// The composed model-view-projection matrix.
    pub fn mvp(&self) -> &Mat4<S> {
        &self.mvp
    }

    /// Whether the model and view matrices together mirror ([`Mat4::mirrors`]), so that every
    /// triangle appears on screen with the reverse of its winding in the mesh. Culling then
    /// judges triangles by their winding in the mesh (unless [`Cull::WINDOW_SPACE`]).
    pub fn mirrored(&self) -> bool {
        self.mirrored
    }

    /// The culling stage's verdict on a triangle of doubled signed screen area `area`, judged by
    /// its winding in the mesh when the transforms mirror.
    #[inline(always)]
    pub(super) fn keeps(&self, area: i64) -> bool {
        // Areas stay within ±i64::MAX, so the negation cannot overflow.
        let m = self.facing;
        self.cull.keep((area ^ m).wrapping_sub(m))
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
        let scratch = self.begin(mesh, scratch);
        let mut stats = RenderStats {
            triangles: mesh.triangle_count().min(u32::MAX as usize) as u32,
            ..RenderStats::default()
        };
        let n = mesh.triangle_count();
        let mut t = 0;
        loop {
            // The back faces (half a closed mesh) leave in a loop of their own, which keeps its
            // registers for them.
            let (idx, v) = loop {
                if t == n {
                    return Ok(stats);
                }
                let idx = mesh.triangle(t);
                t += 1;
                match self.fetch(mesh, idx, scratch) {
                    None => stats.invalid += 1,
                    Some(v) if front::outside(&v) || self.faces(&v, false) => break (idx, v),
                    Some(_) => stats.culled += 1,
                }
            };
            if front::outside(&v) {
                self.draw_outside(&mut Own, target, mesh, idx, scratch, &mut stats)?;
            } else if self.reaches_viewport(&v, &mut stats) {
                self.draw_visible(&mut Own, target, mesh, idx, v, scratch, &mut stats)?;
            }
        }
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
        let scratch = self.begin(mesh, scratch);
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
                    if area != 0 && !self.keeps(area) {
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
