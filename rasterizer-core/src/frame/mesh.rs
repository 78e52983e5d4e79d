//! A mesh as a command of a frame list ([`crate::frame`]).

use super::{Command, FrameError, Layout, Prepared};
use crate::cull::Cull;
use crate::depth::{DepthBuffer, Lent, ListDepth};
use crate::geom::PixelRect;
use crate::math::Scalar;
use crate::mesh::MeshSource;
use crate::numerics::{Numerics, Standard};
use crate::pipeline::{BandError, BinEntry, Lend, Pipeline, RenderStats, VertexSlot, DEFAULT_BITS};
use crate::shade::Shading;
use crate::surface::{Band, ClipTo, Storage, Translucent};

/// A mesh drawn through its own pipeline as one command of a [`crate::frame::FrameList`].
///
/// The pipeline's depth stage says how the mesh uses the list's one depth buffer, which all its
/// meshes share as they would share a whole frame's: [`crate::depth::SharedDepth`] (tested and
/// written), [`crate::depth::SharedDepthReadOnly`] (tested only, for translucent meshes drawn
/// after the opaque ones) or [`crate::depth::NoDepth`].
///
/// When the command is added to a list, its vertices are transformed into `scratch` and its
/// visible triangles binned into `bins` (one [`BinEntry`] a visible triangle, as for
/// [`Pipeline::draw_banded`]): once a frame. Each band then draws only the triangles that touch
/// it, each vertex shaded once a frame by the first band that needs it.
#[derive(Debug)]
pub struct MeshCommand<'m, S, C, D, Sh, M, const BITS: u32 = DEFAULT_BITS, N = Standard>
where
    S: Scalar,
    Sh: Shading<S>,
{
    pipeline: Pipeline<S, C, D, Sh, BITS, N>,
    mesh: &'m M,
    scratch: &'m mut [VertexSlot<Sh::Stored>],
    /// Slots in use this frame (the mesh's vertices, at most the scratch's length).
    slots: usize,
    bins: &'m mut [BinEntry],
    /// Entries in use this frame.
    count: usize,
    /// Bands per bin unit.
    group: u32,
    cursor: (usize, usize),
    /// The band drawn last, to restart the cursor when a new pass over the bands begins.
    last_band: Option<u32>,
    opacity: u8,
    revision: u32,
    stats: RenderStats,
}

impl<'m, S, C, D, Sh, M, const BITS: u32, N> MeshCommand<'m, S, C, D, Sh, M, BITS, N>
where
    S: Scalar,
    C: Cull,
    D: ListDepth,
    Sh: Shading<S>,
    M: MeshSource<S>,
    N: Numerics,
{
    /// A command drawing `mesh` through `pipeline`, opaque. `scratch` holds a slot per mesh
    /// vertex (as in [`Pipeline::draw`]: a shorter one is slower, never wrong) and `bins` an
    /// entry per visible triangle.
    pub fn new(
        pipeline: Pipeline<S, C, D, Sh, BITS, N>,
        mesh: &'m M,
        scratch: &'m mut [VertexSlot<Sh::Stored>],
        bins: &'m mut [BinEntry],
    ) -> Self {
        Self {
            pipeline,
            mesh,
            scratch,
            slots: 0,
            bins,
            count: 0,
            group: 1,
            cursor: (0, 0),
            last_band: None,
            opacity: 255,
            revision: 0,
            stats: RenderStats::default(),
        }
    }

    /// The mesh blended over what lies behind it with `opacity` of 255 ([`Translucent`]); 255
    /// is opaque. Usually with [`crate::depth::SharedDepthReadOnly`].
    pub fn with_opacity(mut self, opacity: u8) -> Self {
        self.opacity = opacity;
        self
    }

    /// Replaces the pipeline (new transforms or lights for the next frame).
    pub fn set_pipeline(&mut self, pipeline: Pipeline<S, C, D, Sh, BITS, N>) {
        self.pipeline = pipeline;
    }

    /// The pipeline.
    pub fn pipeline(&self) -> &Pipeline<S, C, D, Sh, BITS, N> {
        &self.pipeline
    }

    /// Marks a change that the pipeline does not show (the mesh's data changed in place), for
    /// [`crate::frame::changed_areas`].
    pub fn set_revision(&mut self, revision: u32) {
        self.revision = revision;
    }

    /// What happened to the triangles when the command was last added to a list.
    pub fn stats(&self) -> RenderStats {
        self.stats
    }
}

impl<S, C, D, Sh, M, const BITS: u32, N> Command<Sh::Color>
    for MeshCommand<'_, S, C, D, Sh, M, BITS, N>
where
    S: Scalar,
    C: Cull,
    D: ListDepth,
    Sh: Shading<S>,
    Sh::Color: Storage,
    M: MeshSource<S>,
    N: Numerics,
    C: core::fmt::Debug,
    Sh: core::fmt::Debug,
{
    fn prepare(&mut self, layout: &Layout) -> Result<Prepared, FrameError> {
        let p = &mut self.pipeline;
        self.stats = RenderStats {
            triangles: self.mesh.triangle_count().min(u32::MAX as usize) as u32,
            ..RenderStats::default()
        };
        self.slots = p.begin(self.mesh, self.scratch).len();
        let mut pixels = PixelRect::EMPTY;
        self.count = p
            .bin::<_, false, true>(
                self.mesh,
                &mut self.scratch[..self.slots],
                (layout.height(), layout.rows()),
                self.bins,
                &mut self.stats,
                &mut pixels,
            )
            .map_err(|e| match e {
                BandError::TooFewBins { needed, actual } => {
                    FrameError::TooFewBins { needed, actual }
                }
                _ => FrameError::TooFewBins {
                    needed: 0,
                    actual: 0,
                },
            })?;
        self.group = layout.bands().div_ceil(16);
        self.cursor = (0, 0);
        self.last_band = None;
        let bounds = pixels.intersection(&p.area);
        Ok(Prepared {
            bounds: bounds.to_rectangle(),
            depth: D::ENABLED,
        })
    }

    fn draw(
        &mut self,
        band: u32,
        target: &mut ClipTo<'_, Band<'_, Sh::Color>>,
        depth: &mut DepthBuffer<'_>,
    ) {
        let p = &mut self.pipeline;
        if self.last_band.is_none_or(|last| band <= last) {
            self.cursor = (0, 0);
        }
        self.last_band = Some(band);
        let unit = (band / self.group).min(15) as u8;
        // The list's buffer is lent for this band; the pipeline stays where it is.
        let mut lent = Lent::<D>::new(depth);
        let src = &mut Lend(&mut lent);
        let target = &mut ClipTo::new(target, p.viewport.rectangle());
        let scratch = &mut self.scratch[..self.slots];
        let bins = &self.bins[..self.count];
        let mut stats = RenderStats::default();
        if self.opacity == 255 {
            let Ok(()) = p.draw_unit(
                src,
                target,
                self.mesh,
                scratch,
                bins,
                unit,
                &mut self.cursor,
                &mut stats,
            );
        } else {
            // A band reads back, so blending cannot fail.
            let blended = p.draw_unit(
                src,
                &mut Translucent::new(target, self.opacity),
                self.mesh,
                scratch,
                bins,
                unit,
                &mut self.cursor,
                &mut stats,
            );
            debug_assert!(blended.is_ok());
        }
    }

    fn fingerprint(&self, hash: &mut crate::fingerprint::Fingerprint) {
        // Everything that decides the picture: transforms, stages, lights, material.
        self.pipeline.fingerprint(hash);
        hash.bytes(&[self.opacity]);
        hash.bytes(&self.revision.to_le_bytes());
    }
}
