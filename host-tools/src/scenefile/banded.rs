//! The banded path of `render`, `animate` and `view` (`--bands N`): the scene recorded into a
//! frame list ([`rasterizer_core::frame`]) and rendered band by band into a buffer of `N` rows
//! in the scene's colour format, each band copied into the display. The picture is the
//! whole-frame path's, pixel for pixel (a test renders every example scene both ways).
//!
//! How the scene maps to the list:
//! - Meshes are [`MeshCommand`]s whose pipelines are chosen by the same code as the whole
//!   frame's (`draw::dispatch`), sharing the list's depth buffer: `SharedDepth` for opaque
//!   meshes, `SharedDepthReadOnly` (and their opacity) for translucent ones, `NoDepth` without a
//!   depth test. Wireframes are a [`WireCommand`], which redoes its vertex work in every band.
//! - The whole-frame path draws every mesh into an `Rgb888` frame and converts it to the
//!   output's colour afterwards; a pipeline of the output's own colour would shade at its
//!   channel depth and blend translucent meshes there, giving other pixels. So in an `Rgb888`
//!   scene the mesh commands go into the list themselves, and in any other one they go into one
//!   [`MeshLayer`], which draws them into an `Rgb888` band of its own and converts that.
//! - Shapes are the list's [`frame::Shape`]s where one draws exactly the scene's (lines, gradient
//!   and anti-aliased lines, outlines, flat and Gouraud triangles, translucent lines and
//!   triangles), opaque polygons a [`PolygonFill`], and the rest (points, clipped shapes, other
//!   translucent ones) a [`SceneShape`] item drawing them as the whole-frame path does.

use super::draw::{
    clip_and_opacity, color, dispatch, draw_scene_shape, jobs, list_shape, pipeline, pixel, source,
    sub, wire_pipeline, DynMesh, FrameStats, Job, Knobs, MeshSink, ModeCull, Pose, Shade, Stage,
};
use super::format::{FillRuleDef, Shape};
use super::load::Scene;
use super::reference::Real;
use super::MAX_POLYGON;
use embedded_graphics_simulator::SimulatorDisplay;
use rasterizer_core::color::Channels;
use rasterizer_core::depth::{
    Compare, DepthBuffer, DepthRows, DepthTest, ListDepth, SharedDepth, SharedDepthReadOnly,
};
use rasterizer_core::frame::MeshCommand;
use rasterizer_core::frame::{
    self, Clear, Command, Fingerprint, FrameError, FrameList, Item, Layout, PolygonFill, Prepared,
    Slot,
};
use rasterizer_core::mesh::MeshSource;
use rasterizer_core::pipeline::{RenderStats, DEFAULT_BITS};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::Shading;
use rasterizer_core::surface::{Band, ClipTo, Storage};
use std::any::Any;
use std::fmt::Write as _;

/// A colour a scene can be drawn in: the frame list's band storage, and how its meshes join the
/// list.
pub trait SceneColor: Storage + PixelColor + From<Rgb888> + Into<Rgb888> + Channels {
    /// A word of band storage to start from.
    const WORD: Self::Word;

    /// Adds the meshes' commands to `list`: themselves for `Rgb888`, through a [`MeshLayer`]
    /// kept in `layer` for any other colour.
    ///
    /// # Errors
    /// The list's refusal (a mesh with too few bins).
    fn add_meshes<'c, 'a: 'c>(
        list: &mut FrameList<'c, Self>,
        meshes: &'c mut [Box<dyn SceneCommand + 'a>],
        layer: &'c mut Option<MeshLayer<'c, Self>>,
        background: Rgb888,
    ) -> Result<(), FrameError>;
}

impl SceneColor for Rgb888 {
    const WORD: u8 = 0;

    fn add_meshes<'c, 'a: 'c>(
        list: &mut FrameList<'c, Self>,
        meshes: &'c mut [Box<dyn SceneCommand + 'a>],
        _layer: &'c mut Option<MeshLayer<'c, Self>>,
        _background: Rgb888,
    ) -> Result<(), FrameError> {
        for m in meshes {
            list.command(&mut **m)?;
        }
        Ok(())
    }
}

macro_rules! layered {
    ($($t:ty => $word:expr),*) => {$(
        impl SceneColor for $t {
            const WORD: Self::Word = $word;

            fn add_meshes<'c, 'a: 'c>(
                list: &mut FrameList<'c, Self>,
                meshes: &'c mut [Box<dyn SceneCommand + 'a>],
                layer: &'c mut Option<MeshLayer<'c, Self>>,
                background: Rgb888,
            ) -> Result<(), FrameError> {
                if meshes.is_empty() {
                    return Ok(());
                }
                list.command(layer.insert(MeshLayer::new(meshes, background)))
            }
        }
    )*};
}

layered!(Rgb565 => 0, Gray8 => 0, BinaryColor => 0);

/// A mesh's command in the list, which says how many triangles it drew.
pub trait SceneCommand: Command<Rgb888> {
    /// Triangles handed to the rasterizer this frame.
    fn drawn(&self) -> u32;
}

impl<S, Cu, D, Sh, M, N> SceneCommand for MeshCommand<'_, S, Cu, D, Sh, M, DEFAULT_BITS, N>
where
    S: Real,
    Cu: Stage,
    D: ListDepth,
    Sh: Shading<S, Color = Rgb888> + core::fmt::Debug,
    M: MeshSource<S>,
    N: Knobs,
{
    fn drawn(&self) -> u32 {
        self.stats().drawn
    }
}

/// The scene on a display of colour `C`, rendered through a frame list in bands of `rows` rows.
///
/// # Errors
/// A message for the `error:` line: bands of 0 rows, a pipeline that could not be set up, or the
/// list's refusal.
pub(super) fn render_display<C: SceneColor>(
    scene: &Scene,
    pose: Pose,
    rows: u32,
) -> Result<(SimulatorDisplay<C>, FrameStats), String> {
    if rows == 0 {
        return Err("--bands needs at least 1 row per band, got 0".into());
    }
    let (w, h) = (scene.width, scene.height);
    let layout = Layout::new(w, h, rows).map_err(|e| format!("{}: {e}", scene.path.display()))?;
    let fail = |e: FrameError| format!("{}: the frame list: {e}", scene.path.display());

    // Everything the list borrows, made before it.
    let jobs = jobs::<Fx16>(scene, pose)?;
    let data = jobs
        .iter()
        .map(|j| source::<Fx16>(j.mesh))
        .collect::<Result<Vec<_>, _>>()?;
    let meshes: Vec<DynMesh<'_, Fx16>> = data.iter().map(|d| DynMesh(&**d)).collect();
    let mut scratch: Vec<Option<Box<dyn Any>>> = jobs.iter().map(|_| None).collect();
    let mut bins: Vec<Vec<BinEntry>> = meshes
        .iter()
        .map(|m| {
            // One entry a visible triangle, and a filler for every gap of 255.
            let t = m.triangle_count();
            vec![BinEntry::ZERO; t + t / 255 + 1]
        })
        .collect();
    let mut commands: Vec<Box<dyn SceneCommand + '_>> = Vec::with_capacity(jobs.len());
    for (((job, mesh), scratch), bins) in jobs
        .iter()
        .zip(&meshes)
        .zip(scratch.iter_mut())
        .zip(bins.iter_mut())
    {
        let mut sink = ListSink {
            mesh,
            scratch: Some(scratch),
            bins: Some(bins),
            command: None,
        };
        dispatch(&mut sink, job, scene.format);
        // Every stage choice ends in one sink call; a mesh left out would draw nothing.
        let command = sink.command.ok_or_else(|| {
            format!(
                "{}: mesh {} found no frame-list command",
                scene.path.display(),
                job.mesh.name
            )
        })?;
        commands.push(command);
    }
    let plans: Vec<Plan<C>> = scene.shapes.iter().map(plan).collect();
    let fills: Vec<PolygonFill<'_, C, MAX_POLYGON>> = plans
        .iter()
        .filter_map(|p| match p {
            Plan::Fill(polygon, rule, color) => Some(PolygonFill {
                polygon,
                rule: *rule,
                color: *color,
            }),
            _ => None,
        })
        .collect();
    let mut layer = None;
    let mut slots: Vec<Slot<'_, C>> = (0..commands.len() + plans.len())
        .map(|_| Slot::EMPTY)
        .collect();

    let background = C::from(scene.background);
    let mut list = FrameList::new(&mut slots, layout, Clear::new(background));
    C::add_meshes(&mut list, &mut commands, &mut layer, scene.background).map_err(fail)?;
    let mut fills = fills.iter();
    for p in &plans {
        match p {
            Plan::Shape(s) => list.shape(*s),
            Plan::Fill(..) => match fills.next() {
                Some(f) => list.item(f, 0),
                None => Ok(()),
            },
            Plan::Item(item) => list.item(item, 0),
            Plan::Nothing => Ok(()),
        }
        .map_err(fail)?;
    }

    let rows = layout.rows();
    let words = Framebuffer::<C>::required_len(w, rows).ok_or("the band is too large")?;
    let mut band = vec![C::WORD; words];
    let mut depth = vec![u16::MAX; w as usize * rows as usize];
    let mut display = SimulatorDisplay::with_default_color(Size::new(w, h), background);
    list.render(&mut band, &mut depth, |band, area| {
        copy(band, area, &mut display)
    })
    .map_err(fail)?;

    let triangles = commands.iter().map(|c| u64::from(c.drawn())).sum();
    Ok((
        display,
        FrameStats {
            triangles,
            pixels: None,
        },
    ))
}

/// Copies a band's `area` (screen coordinates) onto the display.
fn copy<C: SceneColor>(band: &Band<'_, C>, area: Rectangle, display: &mut SimulatorDisplay<C>) {
    let (fb, y0) = (band.framebuffer(), band.y0());
    let colors = area.points().map(|p| {
        fb.pixel(Point::new(p.x, p.y - y0))
            .unwrap_or_else(|| C::from(Rgb888::BLACK))
    });
    let Ok(()) = display.fill_contiguous(&area, colors);
}

/// Makes a mesh's pipeline, as `draw::dispatch` chooses it, a command of the list.
struct ListSink<'c, S: Real> {
    mesh: &'c DynMesh<'c, S>,
    /// The command's vertex scratch, made when its shading (and so the slot type) is known.
    scratch: Option<&'c mut Option<Box<dyn Any>>>,
    bins: Option<&'c mut Vec<BinEntry>>,
    command: Option<Box<dyn SceneCommand + 'c>>,
}

impl<'c, S: Real> ListSink<'c, S> {
    /// A [`MeshCommand`] of the mesh with depth stage `D`, blended with the mesh's opacity.
    fn record<D, Sh, N>(&mut self, job: &Job<'c, S>, depth: D, shading: Sh) -> RenderStats
    where
        D: AaDepth + core::fmt::Debug + 'static,
        Sh: Shade<S> + 'c,
        N: Knobs,
    {
        if job.mesh.antialias {
            let stage = D::Stage::default();
            let p = pipeline::<S, _, _, Sh, N>(job, ModeCull(job.mesh.cull), stage, shading);
            self.command = Some(Box::new(AaCommand {
                pipeline: p,
                mesh: self.mesh,
                scratch: vec![VertexSlot::EMPTY; self.mesh.vertex_count()],
                opacity: job.mesh.opacity,
                stats: RenderStats::default(),
            }));
            return RenderStats::default();
        }
        // One command type per stage set, not per culling: `ModeCull` keeps the same triangles.
        let p = pipeline::<S, _, D, Sh, N>(job, ModeCull(job.mesh.cull), depth, shading);
        let (Some(slot), Some(bins)) = (self.scratch.take(), self.bins.take()) else {
            return RenderStats::default();
        };
        let scratch: Vec<VertexSlot<Sh::Stored>> =
            vec![VertexSlot::EMPTY; self.mesh.vertex_count()];
        let any: &'c mut dyn Any = &mut **slot.insert(Box::new(scratch));
        let Some(scratch) = any.downcast_mut::<Vec<VertexSlot<Sh::Stored>>>() else {
            return RenderStats::default();
        };
        let command = MeshCommand::new(p, self.mesh, scratch, bins).with_opacity(job.mesh.opacity);
        self.command = Some(Box::new(command));
        RenderStats::default()
    }
}

impl<'c, S: Real> MeshSink<'c, S> for ListSink<'c, S> {
    fn opaque_with_depth<Cu: Stage, Sh: Shade<S> + 'c, N: Knobs>(
        &mut self,
        job: &Job<'c, S>,
        _cull: Cu,
        shading: Sh,
    ) -> RenderStats {
        self.record::<_, Sh, N>(job, SharedDepth, shading)
    }

    fn opaque_without_depth<Cu: Stage, Sh: Shade<S> + 'c, N: Knobs>(
        &mut self,
        job: &Job<'c, S>,
        _cull: Cu,
        shading: Sh,
    ) -> RenderStats {
        self.record::<_, Sh, N>(job, NoDepth, shading)
    }

    fn translucent_with_depth<Cu: Stage, Sh: Shade<S> + 'c, N: Knobs>(
        &mut self,
        job: &Job<'c, S>,
        _cull: Cu,
        shading: Sh,
    ) -> RenderStats {
        self.record::<_, Sh, N>(job, SharedDepthReadOnly, shading)
    }

    fn translucent_without_depth<Cu: Stage, Sh: Shade<S> + 'c, N: Knobs>(
        &mut self,
        job: &Job<'c, S>,
        _cull: Cu,
        shading: Sh,
    ) -> RenderStats {
        self.record::<_, Sh, N>(job, NoDepth, shading)
    }

    fn wireframe<Cu: Stage>(&mut self, job: &Job<'c, S>, _cull: Cu) -> RenderStats {
        self.command = Some(Box::new(WireCommand {
            pipeline: wire_pipeline(job, ModeCull(job.mesh.cull)),
            mesh: self.mesh,
            scratch: vec![VertexSlot::EMPTY; self.mesh.vertex_count()],
            color: job.mesh.color,
            opacity: job.mesh.opacity,
            stats: RenderStats::default(),
        }));
        RenderStats::default()
    }
}

/// A mesh's edges as a command of the list: each band calls `Pipeline::draw_wireframe` into
/// the band, so the mesh's vertex work is done again in every band (the core bins filled
/// triangles, not edges). Its bounds are the whole screen. Good enough for the host tools; a
/// firmware would bin the edges.
struct WireCommand<'c, S: Real> {
    pipeline: Pipeline<S, ModeCull, NoDepth, Unlit<Rgb888>>,
    mesh: &'c DynMesh<'c, S>,
    scratch: Vec<VertexSlot<<Unlit<Rgb888> as Shading<S>>::Stored>>,
    color: Rgb888,
    opacity: u8,
    /// What the last band's call did (every band's does the same).
    stats: RenderStats,
}

impl<S: Real> Command<Rgb888> for WireCommand<'_, S> {
    fn prepare(&mut self, layout: &Layout) -> Result<Prepared, FrameError> {
        Ok(Prepared {
            bounds: layout.screen(),
            depth: false,
        })
    }

    fn draw(
        &mut self,
        _band: u32,
        target: &mut ClipTo<'_, Band<'_, Rgb888>>,
        _depth: &mut DepthBuffer<'_>,
    ) {
        let (p, mesh, scratch, color) =
            (&mut self.pipeline, self.mesh, &mut self.scratch, self.color);
        self.stats = if self.opacity == u8::MAX {
            let Ok(stats) = p.draw_wireframe(target, mesh, scratch, color);
            stats
        } else {
            // A band reads back, so blending cannot fail.
            let target = &mut Translucent::new(target, self.opacity);
            p.draw_wireframe(target, mesh, scratch, color)
                .unwrap_or_default()
        };
    }

    fn fingerprint(&self, hash: &mut Fingerprint) {
        let _ = write!(hash, "{:?}{}", self.pipeline, self.opacity);
    }
}

impl<S: Real> SceneCommand for WireCommand<'_, S> {
    fn drawn(&self) -> u32 {
        self.stats.drawn
    }
}

/// An anti-aliased mesh (`antialias = true`) as a command of the list. The core's
/// `MeshCommand` has no anti-aliased form, and `Pipeline::draw_banded_antialiased` draws one
/// mesh into bands of its own (each cleared first), so it cannot share a band with the other
/// commands. Instead each band calls `Pipeline::draw_antialiased` into the band, as
/// [`WireCommand`] does for edges: the vertex work is done again in every band, and the
/// pipeline's depth stage holds the band's rows of the list's depth buffer while it draws. A
/// blended pixel depends only on what lies beneath it, so the bands give the whole frame's
/// picture (the example scenes are checked both ways).
struct AaCommand<'c, S: Real, D, Sh: Shade<S>, N> {
    pipeline: Pipeline<S, ModeCull, D, Sh, DEFAULT_BITS, N>,
    mesh: &'c DynMesh<'c, S>,
    scratch: Vec<VertexSlot<Sh::Stored>>,
    opacity: u8,
    /// What the last band's call did (every band's counts the same triangles).
    stats: RenderStats,
}

impl<S: Real, D: BandStage, Sh: Shade<S>, N: Knobs> Command<Rgb888> for AaCommand<'_, S, D, Sh, N> {
    fn prepare(&mut self, layout: &Layout) -> Result<Prepared, FrameError> {
        Ok(Prepared {
            bounds: layout.screen(),
            depth: D::ENABLED,
        })
    }

    fn draw(
        &mut self,
        _band: u32,
        target: &mut ClipTo<'_, Band<'_, Rgb888>>,
        depth: &mut DepthBuffer<'_>,
    ) {
        let (p, mesh, scratch) = (&mut self.pipeline, self.mesh, &mut self.scratch);
        p.depth.load(depth);
        // Cannot be refused: the loader gave the mesh adjacency, a band reads back, and every
        // numerics of the scenes takes the fused span loop.
        self.stats = if self.opacity == u8::MAX {
            p.draw_antialiased(target, mesh, scratch)
                .unwrap_or_default()
        } else {
            let target = &mut Translucent::new(target, self.opacity);
            p.draw_antialiased(target, mesh, scratch)
                .unwrap_or_default()
        };
        p.depth.store(depth);
    }

    fn fingerprint(&self, hash: &mut Fingerprint) {
        let _ = write!(hash, "aa{:?}{}", self.pipeline, self.opacity);
    }
}

impl<S: Real, D: BandStage, Sh: Shade<S>, N: Knobs> SceneCommand for AaCommand<'_, S, D, Sh, N> {
    fn drawn(&self) -> u32 {
        self.stats.drawn
    }
}

/// A [`ListDepth`] as the depth stage of an [`AaCommand`].
pub(super) trait AaDepth: ListDepth {
    /// The stage that stands in for it.
    type Stage: BandStage;
}

impl AaDepth for SharedDepth {
    type Stage = BandDepth<true>;
}

impl AaDepth for SharedDepthReadOnly {
    type Stage = BandDepth<false>;
}

impl AaDepth for NoDepth {
    type Stage = NoDepth;
}

/// The depth stage of an [`AaCommand`]'s pipeline: given the list's buffer before each band's
/// draw and giving it back after.
pub(super) trait BandStage: DepthTest + Default + core::fmt::Debug + 'static {
    /// Takes the band's depths from the list's buffer.
    fn load(&mut self, _list: &mut DepthBuffer<'_>) {}
    /// Stores them back into it.
    fn store(&self, _list: &mut DepthBuffer<'_>) {}
}

impl BandStage for NoDepth {}

/// A copy of one band's rows of the list's depth buffer (the pipeline owns its depth stage, and
/// the list lends its buffer only for one call), tested and, when `WRITE`, written back.
#[derive(Default)]
pub(super) struct BandDepth<const WRITE: bool> {
    depths: Vec<u16>,
    width: u32,
    height: u32,
    origin_y: i32,
    compare: Compare,
}

impl<const WRITE: bool> core::fmt::Debug for BandDepth<WRITE> {
    // Without the depths: the fingerprint reads this, and they change every band.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "BandDepth<{WRITE}>")
    }
}

impl<const WRITE: bool> BandStage for BandDepth<WRITE> {
    fn load(&mut self, list: &mut DepthBuffer<'_>) {
        self.compare = list.compare();
        let Some(rows) = list.depth_rows() else {
            return;
        };
        self.depths.clear();
        self.depths.extend_from_slice(rows.depths);
        (self.width, self.height, self.origin_y) = (rows.width, rows.height, rows.origin_y);
    }

    fn store(&self, list: &mut DepthBuffer<'_>) {
        if let (true, Some(rows)) = (WRITE, list.depth_rows()) {
            if rows.depths.len() == self.depths.len() {
                rows.depths.copy_from_slice(&self.depths);
            }
        }
    }
}

impl<const WRITE: bool> DepthTest for BandDepth<WRITE> {
    const WRITE: bool = WRITE;

    fn test_span<E, F>(
        &mut self,
        y: i32,
        x: i32,
        len: u32,
        z: i64,
        dz: i64,
        run: F,
    ) -> Result<(), E>
    where
        F: FnMut(u32, u32) -> Result<(), E>,
    {
        // A buffer of the band's rows from row 0: the same entries, the row moved by the origin.
        let (w, h) = (self.width, self.height);
        let Ok(buffer) = DepthBuffer::new(&mut self.depths, w, h, self.compare) else {
            return Ok(());
        };
        let y = y.wrapping_sub(self.origin_y);
        if WRITE {
            let mut buffer = buffer;
            buffer.test_span(y, x, len, z, dz, run)
        } else {
            buffer.read_only().test_span(y, x, len, z, dz, run)
        }
    }

    fn depth_rows(&mut self) -> Option<DepthRows<'_>> {
        Some(DepthRows {
            depths: &mut self.depths,
            width: self.width,
            height: self.height,
            origin_y: self.origin_y,
        })
    }

    fn comparison(&self) -> Compare {
        self.compare
    }

    fn covers(&self, area: &Rectangle) -> bool {
        let y0 = i64::from(self.origin_y);
        let (x, y) = (i64::from(area.top_left.x), i64::from(area.top_left.y));
        x >= 0
            && x + i64::from(area.size.width) <= i64::from(self.width)
            && y >= y0
            && y + i64::from(area.size.height) <= y0 + i64::from(self.height)
    }
}

/// The meshes of a scene in another colour than `Rgb888`, as one command of the list: each band
/// draws them, in order, into an `Rgb888` band of its own cleared to the background (sharing
/// the list's depth buffer), and converts that into the list's band, as the whole-frame path
/// converts its `Rgb888` frame. It comes first in the list, so it covers nothing but the
/// background.
pub struct MeshLayer<'c, C> {
    meshes: Vec<Layered<'c>>,
    background: Rgb888,
    /// One `Rgb888` band.
    buffer: Vec<u8>,
    layout: Option<Layout>,
    _color: core::marker::PhantomData<C>,
}

/// A mesh of a [`MeshLayer`] and the rows it may draw.
struct Layered<'c> {
    command: &'c mut (dyn SceneCommand + 'c),
    rows: core::ops::Range<i64>,
}

impl<'c, C> MeshLayer<'c, C> {
    fn new<'a: 'c>(meshes: &'c mut [Box<dyn SceneCommand + 'a>], background: Rgb888) -> Self {
        Self {
            meshes: meshes
                .iter_mut()
                .map(|m| Layered {
                    command: &mut **m,
                    rows: 0..0,
                })
                .collect(),
            background,
            buffer: Vec::new(),
            layout: None,
            _color: core::marker::PhantomData,
        }
    }
}

/// The rows of a rectangle, in `i64`.
fn rows_of(r: &Rectangle) -> core::ops::Range<i64> {
    let y = i64::from(r.top_left.y);
    y..y + i64::from(r.size.height)
}

impl<C: SceneColor> Command<C> for MeshLayer<'_, C> {
    fn prepare(&mut self, layout: &Layout) -> Result<Prepared, FrameError> {
        let mut depth = false;
        let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
        for m in &mut self.meshes {
            let p = m.command.prepare(layout)?;
            depth |= p.depth;
            let b = p.bounds;
            m.rows = rows_of(&b);
            if b.size.width > 0 && b.size.height > 0 {
                x0 = x0.min(i64::from(b.top_left.x));
                x1 = x1.max(i64::from(b.top_left.x) + i64::from(b.size.width));
                y0 = y0.min(m.rows.start);
                y1 = y1.max(m.rows.end);
            }
        }
        let len = Framebuffer::<Rgb888>::required_len(layout.width(), layout.rows()).ok_or(
            FrameError::BandBufferTooSmall {
                needed: usize::MAX,
                actual: 0,
            },
        )?;
        self.buffer.resize(len, 0);
        self.layout = Some(*layout);
        let bounds = if x0 < x1 && y0 < y1 {
            // Within the screen, so within i32 and u32.
            Rectangle::new(
                Point::new(x0 as i32, y0 as i32),
                Size::new((x1 - x0) as u32, (y1 - y0) as u32),
            )
        } else {
            Rectangle::zero()
        };
        Ok(Prepared { bounds, depth })
    }

    fn draw(
        &mut self,
        band: u32,
        target: &mut ClipTo<'_, Band<'_, C>>,
        depth: &mut DepthBuffer<'_>,
    ) {
        let Some(layout) = self.layout else {
            return;
        };
        let y0 = band.saturating_mul(layout.rows());
        if y0 >= layout.height() {
            return;
        }
        let (width, height) = (layout.width(), layout.rows().min(layout.height() - y0));
        let Some(words) = Framebuffer::<Rgb888>::required_len(width, height)
            .and_then(|len| self.buffer.get_mut(..len))
        else {
            return;
        };
        let Ok(fb) = Framebuffer::<Rgb888>::new(words, width, height) else {
            return;
        };
        // Rows are below 32,768 (the list's layout): they fit i32.
        let mut strip = Band::new(fb, y0 as i32);
        let Ok(()) = strip.clear(self.background);
        let area = target.clip_area();
        let rows = rows_of(&area);
        {
            let mut t = ClipTo::new(&mut strip, area);
            for m in &mut self.meshes {
                if m.rows.start < rows.end && rows.start < m.rows.end {
                    m.command.draw(band, &mut t, depth);
                }
            }
        }
        let fb = strip.framebuffer();
        let background = C::from(self.background);
        let colors = area.points().map(|p| {
            fb.pixel(Point::new(p.x, p.y - y0 as i32))
                .map_or(background, C::from)
        });
        let Ok(()) = target.fill_contiguous(&area, colors);
    }

    fn fingerprint(&self, hash: &mut Fingerprint) {
        for m in &self.meshes {
            m.command.fingerprint(hash);
        }
    }
}

/// How one shape of the scene joins the list.
enum Plan<'s, C> {
    /// A shape of the list that draws exactly it.
    Shape(frame::Shape<C>),
    /// An opaque polygon, by the list's [`PolygonFill`].
    Fill(Box<Polygon<MAX_POLYGON>>, FillRule, C),
    /// Drawn as the whole-frame path draws it.
    Item(SceneShape<'s>),
    /// Draws nothing.
    Nothing,
}

/// A scene shape drawn into each band it touches as the whole-frame path draws it (its clip
/// rectangle, its opacity through `Translucent`).
struct SceneShape<'s> {
    shape: &'s Shape,
    bounds: Rectangle,
}

impl<C: SceneColor> Item<C> for SceneShape<'_> {
    fn bounds(&self) -> Rectangle {
        self.bounds
    }

    fn draw_into(&self, target: &mut ClipTo<'_, Band<'_, C>>) {
        draw_scene_shape(target, self.shape);
    }
}

/// The part of `a` inside `b`, in `i64` (embedded-graphics' own intersection overflows for
/// rectangles that end past `i32::MAX`).
fn meet(a: &Rectangle, b: &Rectangle) -> Rectangle {
    let span = |r: &Rectangle| {
        let (x, y) = (i64::from(r.top_left.x), i64::from(r.top_left.y));
        (
            x,
            y,
            x + i64::from(r.size.width),
            y + i64::from(r.size.height),
        )
    };
    let (ax0, ay0, ax1, ay1) = span(a);
    let (bx0, by0, bx1, by1) = span(b);
    let (x0, y0, x1, y1) = (ax0.max(bx0), ay0.max(by0), ax1.min(bx1), ay1.min(by1));
    if x0 >= x1 || y0 >= y1 {
        return Rectangle::zero();
    }
    // Both start within i32, and the sizes are at most a u32's.
    Rectangle::new(
        Point::new(x0 as i32, y0 as i32),
        Size::new((x1 - x0) as u32, (y1 - y0) as u32),
    )
}

/// How a shape joins the list.
fn plan<C: SceneColor>(shape: &Shape) -> Plan<'_, C> {
    let (clip, opacity) = clip_and_opacity(shape);
    match shape {
        Shape::Point { at, .. } => {
            let bounds = Rectangle::new(pixel(*at), Size::new(1, 1));
            return item(shape, bounds, clip);
        }
        Shape::Sprite { .. } => return item(shape, super::sprite::bounds(shape), clip),
        Shape::Polygon {
            vertices,
            fill_rule,
            color: c,
            ..
        } => {
            let pts: Vec<SubPoint> = vertices.iter().map(|&p| sub(p)).collect();
            // The loader checked the vertex count.
            let Ok(polygon) = Polygon::<MAX_POLYGON>::new(&pts) else {
                return Plan::Nothing;
            };
            if clip.is_some() || opacity.is_some() {
                return item(shape, polygon.pixel_bounds(), clip);
            }
            let rule = match fill_rule {
                FillRuleDef::EvenOdd => FillRule::EvenOdd,
                FillRuleDef::NonZero => FillRule::NonZero,
            };
            return Plan::Fill(Box::new(polygon), rule, color(*c));
        }
        _ => {}
    }
    // The list's shape of the same geometry and colours: its bounds hold the shape's pixels,
    // and with no clip and no opacity it draws exactly them.
    let Some(geometry) = list_shape::<C>(shape) else {
        return Plan::Nothing;
    };
    // With an opacity, a flat or Gouraud triangle blends each pixel once and a plain line is
    // `draw_line_alpha`: exactly what `Translucent` makes of them. Other shapes with an opacity
    // are drawn as the whole frame draws them.
    let listed = match (geometry, opacity) {
        (s, None) => Some(s),
        (
            frame::Shape::Triangle {
                vertices, color, ..
            },
            Some(opacity),
        ) => Some(frame::Shape::Triangle {
            vertices,
            color,
            opacity,
        }),
        (
            frame::Shape::Gouraud {
                vertices, colors, ..
            },
            Some(opacity),
        ) => Some(frame::Shape::Gouraud {
            vertices,
            colors,
            opacity,
        }),
        (frame::Shape::Line { a, b, color }, Some(alpha)) => {
            Some(frame::Shape::LineAlpha { a, b, color, alpha })
        }
        (_, Some(_)) => None,
    };
    match (listed, clip) {
        (Some(s), None) => Plan::Shape(s),
        _ => item(shape, geometry.bounds(), clip),
    }
}

/// A [`SceneShape`] within `bounds`, cut to its clip rectangle.
fn item<C>(shape: &Shape, bounds: Rectangle, clip: Option<Rectangle>) -> Plan<'_, C> {
    let bounds = clip.map_or(bounds, |c| meet(&bounds, &c));
    Plan::Item(SceneShape { shape, bounds })
}
