//! Drawing a loaded scene: the meshes through the 3D pipeline, then the 2D shapes.
//!
//! The pipeline's stages are chosen here once, for both ways of drawing a frame: each mesh's
//! choice (culling, depth, shading, perspective, fog, dithering, translucency, wireframe) is
//! handed to a [`MeshSink`], which either draws it into a whole frame at once ([`Whole`]) or
//! makes a command of a frame list of it (the banded path, `super::banded`).

use super::banded::{self, SceneColor};
use super::format::{
    CullMode, DitherMode, FillRuleDef, LightDef, PixelFormat, ShadingModel, Shape,
};
use super::load::{MeshData, OwnedMesh, Scene, SceneFog, SceneMesh};
use super::reference::Real;
use super::{MAX_LIGHTS, MAX_POLYGON};
use core::fmt::Debug;
use embedded_graphics_simulator::{OutputImage, OutputSettingsBuilder, SimulatorDisplay};
use rasterizer_core::color::Channels;
use rasterizer_core::cull::Cull;
use rasterizer_core::frame;
use rasterizer_core::geom::MAX_VARYINGS;
use rasterizer_core::numerics::{Dither, Numerics, Perspective, Standard};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::{
    Fog, FogCurve, FogSettings, Foggable, Shading, VertexIn, FOG_TABLE_LEN,
};
use rasterizer_core::surface::{BlendError, ClipTo};
use rasterizer_core::{mesh::MeshSource, pipeline::RenderStats};
use std::convert::Infallible;

use super::counting::Counting;

/// Renders the whole scene (meshes in 16.16, then shapes) in its pixel format and returns the
/// simulator's RGB output image at `scale`. `turn` rotates every mesh about the world's Y axis.
///
/// # Errors
/// A message for the `error:` line (a pipeline that could not be set up).
pub fn render_image(scene: &Scene, turn: Angle, scale: u32) -> Result<OutputImage<Rgb888>, String> {
    let pose = Pose {
        yaw: turn,
        pitch: Angle(0),
    };
    Ok(render_posed(scene, pose, scale)?.0)
}

/// How the meshes are turned: about the world's Y axis, then about its X axis.
#[derive(Debug, Clone, Copy, Default)]
pub struct Pose {
    /// The turn about Y.
    pub yaw: Angle,
    /// The tilt about X, after the turn.
    pub pitch: Angle,
}

/// What drawing the meshes of a frame did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Triangles handed to the rasterizer.
    pub triangles: u64,
    /// Pixels the meshes wrote (a pixel written twice counts twice); `None` for a frame drawn
    /// in bands, whose meshes draw straight into the frame list's bands, where nothing counts.
    pub pixels: Option<u64>,
}

/// [`render_image`] with the meshes in any pose, and what drawing them did.
///
/// # Errors
/// As [`render_image`].
pub fn render_posed(
    scene: &Scene,
    pose: Pose,
    scale: u32,
) -> Result<(OutputImage<Rgb888>, FrameStats), String> {
    render_frame(scene, pose, scale, None)
}

/// [`render_posed`], drawn whole (`bands` `None`) or through a frame list in bands of `bands`
/// rows (`--bands`), which gives the same image.
///
/// # Errors
/// As [`render_image`]; also bands of 0 rows, and a scene the frame list cannot hold.
pub fn render_frame(
    scene: &Scene,
    pose: Pose,
    scale: u32,
    bands: Option<u32>,
) -> Result<(OutputImage<Rgb888>, FrameStats), String> {
    let settings = OutputSettingsBuilder::new().scale(scale).build();
    Ok(match scene.format {
        PixelFormat::Rgb565 => output(display::<Rgb565>(scene, pose, bands)?, &settings),
        PixelFormat::Rgb888 => output(display::<Rgb888>(scene, pose, bands)?, &settings),
        PixelFormat::Gray8 => output(display::<Gray8>(scene, pose, bands)?, &settings),
        PixelFormat::Binary => output(display::<BinaryColor>(scene, pose, bands)?, &settings),
    })
}

/// The scene on a display of colour `C`, drawn whole or in bands.
fn display<C: SceneColor>(
    scene: &Scene,
    pose: Pose,
    bands: Option<u32>,
) -> Result<(SimulatorDisplay<C>, FrameStats), String> {
    match bands {
        None => render_display(scene, pose),
        Some(rows) => banded::render_display(scene, pose, rows),
    }
}

/// A display's output image at `settings`, with its stats.
fn output<C>(
    (display, stats): (SimulatorDisplay<C>, FrameStats),
    settings: &embedded_graphics_simulator::OutputSettings,
) -> (OutputImage<Rgb888>, FrameStats)
where
    C: PixelColor + Into<Rgb888>,
{
    (display.to_rgb_output_image(settings), stats)
}

/// The scene drawn onto a simulator display of colour `C`: the meshes into a
/// `Framebuffer<Rgb888>` by `Rgb888` pipelines, copied onto the display converted to `C`; then
/// the shapes straight onto the display through [`ReadBack`].
fn render_display<C>(scene: &Scene, pose: Pose) -> Result<(SimulatorDisplay<C>, FrameStats), String>
where
    C: PixelColor + From<Rgb888> + Channels,
{
    let size = Size::new(scene.width, scene.height);
    let mut display = SimulatorDisplay::with_default_color(size, C::from(scene.background));
    let mut stats = FrameStats::default();
    if !scene.meshes.is_empty() {
        let rgb;
        (rgb, stats) = render_3d_pixels::<Fx16>(scene, pose)?;
        let w = scene.width as usize;
        let Ok(()) = display.draw_iter(
            rgb.into_iter()
                .enumerate()
                .map(|(i, c)| Pixel(Point::new((i % w) as i32, (i / w) as i32), C::from(c))),
        );
    }
    draw_shapes(scene, &mut display);
    Ok((display, stats))
}

/// Only the meshes, in the scalar `S`, onto an `Rgb888` display cleared to the background.
///
/// # Errors
/// A message for the `error:` line.
pub fn render_3d<S: Real>(scene: &Scene) -> Result<SimulatorDisplay<Rgb888>, String> {
    let size = Size::new(scene.width, scene.height);
    let mut display = SimulatorDisplay::with_default_color(size, scene.background);
    let (rgb, _) = render_3d_pixels::<S>(scene, Pose::default())?;
    let w = scene.width as usize;
    let Ok(()) = display.draw_iter(
        rgb.into_iter()
            .enumerate()
            .map(|(i, c)| Pixel(Point::new((i % w) as i32, (i / w) as i32), c)),
    );
    Ok(display)
}

/// The meshes rendered in `S` into a framebuffer cleared to the background, row by row.
fn render_3d_pixels<S: Real>(
    scene: &Scene,
    pose: Pose,
) -> Result<(Vec<Rgb888>, FrameStats), String> {
    let (w, h) = (scene.width, scene.height);
    let len = Framebuffer::<Rgb888>::required_len(w, h).ok_or("the output is too large")?;
    let mut bytes = vec![0u8; len];
    let fb = Framebuffer::<Rgb888>::new(&mut bytes, w, h).map_err(|e| e.to_string())?;
    let mut target = Counting::new(fb);
    let Ok(()) = target.inner.clear(scene.background);
    let triangles = draw_meshes::<S>(scene, &mut target, pose)?;
    let stats = FrameStats {
        triangles,
        pixels: Some(target.pixels),
    };
    let fb = &target.inner;
    let rgb = (0..h as i32)
        .flat_map(|y| (0..w as i32).map(move |x| Point::new(x, y)))
        .map(|p| fb.pixel(p).unwrap_or(scene.background))
        .collect();
    Ok((rgb, stats))
}

/// Any mesh source behind one type, so the pipelines are compiled once for all mesh kinds.
pub(super) struct DynMesh<'a, S>(pub(super) &'a dyn MeshSource<S>);

impl<S> MeshSource<S> for DynMesh<'_, S> {
    fn vertex_count(&self) -> usize {
        self.0.vertex_count()
    }
    fn triangle_count(&self) -> usize {
        self.0.triangle_count()
    }
    fn triangle(&self, t: usize) -> [usize; 3] {
        self.0.triangle(t)
    }
    fn position(&self, i: usize) -> Vec3<S> {
        self.0.position(i)
    }
    fn has_normals(&self) -> bool {
        self.0.has_normals()
    }
    fn normal(&self, i: usize) -> Option<Vec3<S>> {
        self.0.normal(i)
    }
    fn color(&self, i: usize) -> Option<Rgb888> {
        self.0.color(i)
    }
    fn uv(&self, i: usize) -> Option<[i32; 2]> {
        self.0.uv(i)
    }
    fn has_adjacency(&self) -> bool {
        self.0.has_adjacency()
    }
    fn neighbours(&self, t: usize) -> [u32; 3] {
        self.0.neighbours(t)
    }
}

/// The target every pipeline of [`Whole`] draws into.
type Target<'a> = Counting<Framebuffer<'a, Rgb888>>;

/// A vector of `f64`s in `S`.
fn v3<S: Real>(v: [f64; 3]) -> Vec3<S> {
    Vec3::new(S::from_f64(v[0]), S::from_f64(v[1]), S::from_f64(v[2]))
}

/// An angle in degrees, to 1/3600 degree.
fn degrees(d: f64) -> Angle {
    Angle::from_degrees_ratio((d * 3600.0).round() as i64, 3600)
}

/// A mesh's model matrix (scale, rotate x, y, z, translate, then the turntable's turn about Y)
/// and, for a non-uniform scale, the matrix for its normals.
fn model_of<S: Real>(m: &SceneMesh, pose: Pose) -> (Mat4<S>, Option<Mat4<S>>) {
    // A tilt of zero adds no matrix: the turntable's pictures stay as they were.
    let turn = |m: Mat4<S>| {
        let m = m.then(&Mat4::rotation_y(pose.yaw));
        if pose.pitch == Angle(0) {
            m
        } else {
            m.then(&Mat4::rotation_x(pose.pitch))
        }
    };
    let [sx, sy, sz] = m.scale;
    let rotation = Mat4::rotation_x(degrees(m.rotate[0]))
        .then(&Mat4::rotation_y(degrees(m.rotate[1])))
        .then(&Mat4::rotation_z(degrees(m.rotate[2])));
    let model = Mat4::scale(S::from_f64(sx), S::from_f64(sy), S::from_f64(sz))
        .then(&rotation)
        .then(&Mat4::translation(v3(m.translate)));
    let model = turn(model);
    let normal = (sx != sy || sy != sz).then(|| {
        // The inverse transpose of scale-then-rotate is the inverse scale, then the rotation.
        let normal = Mat4::scale(
            S::from_f64(1.0 / sx),
            S::from_f64(1.0 / sy),
            S::from_f64(1.0 / sz),
        )
        .then(&rotation);
        turn(normal)
    });
    (model, normal)
}

/// Everything one mesh's draw call needs besides the mesh.
pub(super) struct Job<'a, S: Real> {
    pub(super) mesh: &'a SceneMesh,
    transforms: Transforms<S>,
    normal_matrix: Option<Mat4<S>>,
    pub(super) viewport: Viewport,
    lighting: Lighting<S, MAX_LIGHTS>,
}

/// The draw call of every mesh, in order: transforms, viewport and lights.
pub(super) fn jobs<S: Real>(scene: &Scene, pose: Pose) -> Result<Vec<Job<'_, S>>, String> {
    let cam = &scene.camera;
    let (w, h) = (scene.width, scene.height);
    let view = Mat4::look_at(v3::<S>(cam.eye), v3(cam.target), v3(cam.up)).ok_or_else(|| {
        format!(
            "{}: [camera] eye, target and up give no view matrix in {}",
            scene.path.display(),
            S::NAME
        )
    })?;
    let projection = Mat4::perspective(
        degrees(cam.fov),
        S::from_ratio(i64::from(w), i64::from(h)),
        S::from_f64(cam.near),
        S::from_f64(cam.far),
    )
    .ok_or_else(|| {
        format!(
            "{}: [camera] fov, near and far give no projection in {}",
            scene.path.display(),
            S::NAME
        )
    })?;
    let mut jobs = Vec::with_capacity(scene.meshes.len());
    for mesh in &scene.meshes {
        let (model, normal_matrix) = model_of::<S>(mesh, pose);
        let mut lighting = Lighting::new(mesh.material, scene.ambient, scene.specular, v3(cam.eye));
        for light in &scene.lights {
            let light = match light {
                LightDef::Directional { direction, color } => Light::Directional {
                    direction: v3(*direction),
                    color: Rgb888::new(color.0[0], color.0[1], color.0[2]),
                },
                LightDef::Point { position, color } => Light::Point {
                    position: v3(*position),
                    color: Rgb888::new(color.0[0], color.0[1], color.0[2]),
                },
            };
            lighting.add_light(light).map_err(|_| {
                format!(
                    "{}: [[lights]] a direction is zero in {}",
                    scene.path.display(),
                    S::NAME
                )
            })?;
        }
        jobs.push(Job {
            mesh,
            transforms: Transforms {
                model,
                view,
                projection,
            },
            normal_matrix,
            viewport: Viewport::new(w, h),
            lighting,
        });
    }
    Ok(jobs)
}

/// A mesh's vertex data as a mesh source in `S`.
pub(super) fn source<'a, S: Real>(
    mesh: &'a SceneMesh,
) -> Result<Box<dyn MeshSource<S> + 'a>, String> {
    Ok(match &mesh.data {
        MeshData::Packed(bytes) => Box::new(PackedMesh::parse(bytes).map_err(|e| e.to_string())?),
        MeshData::Owned(owned) => Box::new(Converted::<S>::new(owned)),
    })
}

/// The meshes, in order, sharing one depth buffer.
/// Returns the triangles handed to the rasterizer.
fn draw_meshes<S: Real>(scene: &Scene, target: &mut Target<'_>, pose: Pose) -> Result<u64, String> {
    let (w, h) = (scene.width, scene.height);
    let mut zbuf = vec![u16::MAX; w as usize * h as usize];
    let mut triangles = 0;
    for job in jobs::<S>(scene, pose)? {
        // One mesh converted at a time.
        let data = source::<S>(job.mesh)?;
        let mut whole = Whole {
            target: &mut *target,
            mesh: &DynMesh(&*data),
            zbuf: &mut zbuf,
        };
        triangles += u64::from(dispatch(&mut whole, &job, scene.format).drawn);
    }
    Ok(triangles)
}

/// An [`OwnedMesh`] in the scalar `S`.
struct Converted<S> {
    positions: Vec<Vec3<S>>,
    normals: Option<Vec<Vec3<S>>>,
    colors: Option<Vec<Rgb888>>,
    uvs: Option<Vec<[i32; 2]>>,
    triangles: Vec<[u32; 3]>,
    adjacency: Option<Vec<[u32; 3]>>,
}

impl<S: Real> Converted<S> {
    fn new(m: &OwnedMesh) -> Self {
        Self {
            positions: m.positions.iter().map(|&p| v3(p)).collect(),
            normals: m
                .normals
                .as_ref()
                .map(|n| n.iter().map(|&v| v3(v)).collect()),
            colors: m.colors.clone(),
            uvs: m.uvs.clone(),
            triangles: m.triangles.clone(),
            adjacency: m.adjacency.clone(),
        }
    }

    fn mesh(&self) -> Mesh<'_, S, u32> {
        Mesh {
            positions: &self.positions,
            normals: self.normals.as_deref(),
            colors: self.colors.as_deref(),
            uvs: self.uvs.as_deref(),
            triangles: &self.triangles,
            adjacency: self.adjacency.as_deref(),
        }
    }
}

impl<S: Real> MeshSource<S> for Converted<S> {
    fn vertex_count(&self) -> usize {
        self.mesh().vertex_count()
    }
    fn triangle_count(&self) -> usize {
        self.mesh().triangle_count()
    }
    fn triangle(&self, t: usize) -> [usize; 3] {
        self.mesh().triangle(t)
    }
    fn position(&self, i: usize) -> Vec3<S> {
        self.mesh().position(i)
    }
    fn has_normals(&self) -> bool {
        self.mesh().has_normals()
    }
    fn normal(&self, i: usize) -> Option<Vec3<S>> {
        self.mesh().normal(i)
    }
    fn color(&self, i: usize) -> Option<Rgb888> {
        self.mesh().color(i)
    }
    fn uv(&self, i: usize) -> Option<[i32; 2]> {
        self.mesh().uv(i)
    }
    fn has_adjacency(&self) -> bool {
        self.mesh().has_adjacency()
    }
    fn neighbours(&self, t: usize) -> [u32; 3] {
        self.mesh().neighbours(t)
    }
}

/// A culling stage a sink can keep (every one of this module's).
pub(super) trait Stage: Cull + Copy + Debug + 'static {}
impl<T: Cull + Copy + Debug + 'static> Stage for T {}

/// A shading model a sink can keep: `Rgb888` out, as every pipeline here draws (see
/// [`InRgb888`] for the dithered ones).
pub(super) trait Shade<S: Real>:
    Shading<S, Color = Rgb888, Stored: 'static> + Debug
{
}
impl<S: Real, T: Shading<S, Color = Rgb888, Stored: 'static> + Debug> Shade<S> for T {}

/// Numeric knobs a sink can keep.
pub(super) trait Knobs: Numerics + Debug + 'static {}
impl<T: Numerics + Debug + 'static> Knobs for T {}

/// What a mesh's choice of stages is handed to, one method per use of the frame's depth buffer
/// (so each compiles only its own depth stage). Opaque meshes test and write depth or ignore
/// it; translucent ones (opacity below 255, blended through `Translucent`) test it without
/// writing it, or ignore it. `'s` is how long the scene lives (a texture is borrowed from it).
/// Each returns what the draw did (nothing yet, for a sink that only records).
pub(super) trait MeshSink<'s, S: Real> {
    /// An opaque mesh, depth tested and written.
    fn opaque_with_depth<Cu: Stage, Sh: Shade<S> + 's, N: Knobs>(
        &mut self,
        job: &Job<'s, S>,
        cull: Cu,
        shading: Sh,
    ) -> RenderStats;
    /// An opaque mesh without a depth test.
    fn opaque_without_depth<Cu: Stage, Sh: Shade<S> + 's, N: Knobs>(
        &mut self,
        job: &Job<'s, S>,
        cull: Cu,
        shading: Sh,
    ) -> RenderStats;
    /// A translucent mesh, depth tested but not written.
    fn translucent_with_depth<Cu: Stage, Sh: Shade<S> + 's, N: Knobs>(
        &mut self,
        job: &Job<'s, S>,
        cull: Cu,
        shading: Sh,
    ) -> RenderStats;
    /// A translucent mesh without a depth test.
    fn translucent_without_depth<Cu: Stage, Sh: Shade<S> + 's, N: Knobs>(
        &mut self,
        job: &Job<'s, S>,
        cull: Cu,
        shading: Sh,
    ) -> RenderStats;
    /// A mesh's edges in its colour (`Pipeline::draw_wireframe`, no depth test), blended when
    /// it is translucent.
    fn wireframe<Cu: Stage>(&mut self, job: &Job<'s, S>, cull: Cu) -> RenderStats;
}

/// A use of the depth buffer as a type: picks the [`MeshSink`] method.
trait DepthUse {
    fn draw<'s, S, K, Cu, Sh, N>(
        sink: &mut K,
        job: &Job<'s, S>,
        cull: Cu,
        shading: Sh,
    ) -> RenderStats
    where
        S: Real,
        K: MeshSink<'s, S>,
        Cu: Stage,
        Sh: Shade<S> + 's,
        N: Knobs;
}

/// [`MeshSink::opaque_with_depth`].
struct OpaqueDepth;
/// [`MeshSink::opaque_without_depth`].
struct OpaqueNoDepth;
/// [`MeshSink::translucent_with_depth`].
struct TranslucentDepth;
/// [`MeshSink::translucent_without_depth`].
struct TranslucentNoDepth;

macro_rules! depth_use {
    ($($t:ty => $method:ident),*) => {$(
        impl DepthUse for $t {
            fn draw<'s, S, K, Cu, Sh, N>(
                sink: &mut K,
                job: &Job<'s, S>,
                cull: Cu,
                shading: Sh,
            ) -> RenderStats
            where
                S: Real,
                K: MeshSink<'s, S>,
                Cu: Stage,
                Sh: Shade<S> + 's,
                N: Knobs,
            {
                sink.$method::<Cu, Sh, N>(job, cull, shading)
            }
        }
    )*};
}

depth_use!(
    OpaqueDepth => opaque_with_depth,
    OpaqueNoDepth => opaque_without_depth,
    TranslucentDepth => translucent_with_depth,
    TranslucentNoDepth => translucent_without_depth
);

/// One mesh's pipeline, chosen from its stages and handed to `sink`.
pub(super) fn dispatch<'s, S: Real, K: MeshSink<'s, S>>(
    sink: &mut K,
    job: &Job<'s, S>,
    format: PixelFormat,
) -> RenderStats {
    let mesh = job.mesh;
    if mesh.opacity < u8::MAX {
        translucent(sink, job)
    } else if dithers(mesh) {
        by_format(sink, job, format)
    } else if fogs(mesh) {
        fogged(sink, job)
    } else {
        by_cull(sink, job)
    }
}

/// Whether a mesh takes the dithered path: it asks for dithering and has an interpolated colour
/// (filled, Gouraud or vertex colours, affine: what the core dithers).
fn dithers(m: &SceneMesh) -> bool {
    m.dither != DitherMode::None
        && m.texture.is_none()
        && !m.wireframe
        && !m.perspective_correct
        && matches!(
            m.shading,
            ShadingModel::Gouraud | ShadingModel::VertexColors
        )
}

/// Whether a mesh is fogged: it asks for fog (the loader allows it only where it applies:
/// filled, lit or vertex colours, not textured or translucent).
fn fogs(m: &SceneMesh) -> bool {
    m.fog.is_some()
}

/// A mesh's fog in `S`; without one, a curve that is zero everywhere, which leaves every colour
/// exactly as it is (so the dithered path compiles one pipeline per shading model, fogged or not).
fn fog_settings<S: Real>(fog: Option<&SceneFog>) -> FogSettings<S> {
    match fog {
        Some(f) => FogSettings {
            color: f.color,
            start: S::from_f64(f.start),
            end: S::from_f64(f.end),
            curve: f.curve,
        },
        None => FogSettings {
            color: Rgb888::BLACK,
            start: S::ZERO,
            end: S::ONE,
            curve: FogCurve::Table([0; FOG_TABLE_LEN]),
        },
    }
}

/// A fogged mesh (not dithered): culling chosen at run time and the shading model wrapped in
/// [`Fog`], so fog adds one pipeline per model, depth stage and interpolation, not per culling.
fn fogged<'s, S: Real, K: MeshSink<'s, S>>(sink: &mut K, job: &Job<'s, S>) -> RenderStats {
    if job.mesh.depth {
        fogged_shading::<S, K, OpaqueDepth>(sink, job)
    } else {
        fogged_shading::<S, K, OpaqueNoDepth>(sink, job)
    }
}

/// Picks the shading model of a fogged mesh.
fn fogged_shading<'s, S: Real, K: MeshSink<'s, S>, U: DepthUse>(
    sink: &mut K,
    job: &Job<'s, S>,
) -> RenderStats {
    fn with_fog<'s, S, K, U, Sh>(sink: &mut K, job: &Job<'s, S>, inner: Sh) -> RenderStats
    where
        S: Real,
        K: MeshSink<'s, S>,
        U: DepthUse,
        Sh: Foggable<S, Color = Rgb888> + Debug + 's,
        Fog<S, Sh>: Shade<S>,
    {
        let settings = fog_settings(job.mesh.fog.as_ref());
        let shading = Fog::new(inner, settings, &job.transforms.view);
        by_perspective::<S, K, U, _, _>(sink, job, ModeCull(job.mesh.cull), shading)
    }
    let lighting = job.lighting.clone();
    match job.mesh.shading {
        ShadingModel::VertexColors => {
            with_fog::<S, K, U, _>(sink, job, VertexColors::<Rgb888>::new())
        }
        ShadingModel::Flat => {
            let flat = FlatLit::<S, Rgb888, MAX_LIGHTS>::new(lighting);
            with_fog::<S, K, U, _>(sink, job, flat)
        }
        ShadingModel::Phong => {
            let phong = PhongLit::<S, Rgb888, MAX_LIGHTS>::new(lighting);
            with_fog::<S, K, U, _>(sink, job, phong)
        }
        ShadingModel::Matcap => with_fog::<S, K, U, _>(sink, job, matcap::<S>(job)),
        _ => {
            let gouraud = GouraudLit::<S, Rgb888, MAX_LIGHTS>::new(lighting);
            with_fog::<S, K, U, _>(sink, job, gouraud)
        }
    }
}

/// A shading model of the output's colour `Sh::Color` seen as one of `Rgb888`: every colour it
/// makes converted, the rest handed through. A dithered pipeline dithers at the output's channel
/// depth, so its shading is of the output's colour; this lets it draw into the `Rgb888` frame
/// the other meshes share. Each colour comes back exactly when the frame is converted to the
/// output's colour (a test checks every one).
#[derive(Debug, Clone)]
pub(super) struct InRgb888<Sh>(Sh);

impl<S: Real, Sh: Shading<S>> Shading<S> for InRgb888<Sh>
where
    Sh::Color: Into<Rgb888>,
{
    type Color = Rgb888;
    type Varyings = Sh::Varyings;
    type Stored = Sh::Stored;
    const NEEDS_WORLD: bool = Sh::NEEDS_WORLD;
    const NEEDS_FACE: bool = Sh::NEEDS_FACE;
    const NEEDS_UV: bool = Sh::NEEDS_UV;
    const NEEDS_W: bool = Sh::NEEDS_W;
    const NEEDS_TRIANGLE: bool = Sh::NEEDS_TRIANGLE;
    const FUSED_FRAC: u32 = Sh::FUSED_FRAC;
    const FUSED_OFFSET: u32 = Sh::FUSED_OFFSET;

    fn begin_frame(&mut self, model: Option<&Mat4<S>>) -> bool {
        self.0.begin_frame(model)
    }
    #[inline(always)]
    fn vertex(&mut self, v: &VertexIn<S>) -> Self::Varyings {
        self.0.vertex(v)
    }
    #[inline(always)]
    fn project(&self, v: &mut Self::Varyings, w: S) {
        self.0.project(v, w);
    }
    #[inline(always)]
    fn triangle(&mut self, v: &mut [Self::Varyings; 3]) {
        self.0.triangle(v);
    }
    #[inline(always)]
    fn face(&mut self, vertices: &[VertexIn<S>; 3]) {
        self.0.face(vertices);
    }
    #[inline(always)]
    fn pixel(&self, v: &Self::Varyings) -> Rgb888 {
        self.0.pixel(v).into()
    }
    #[inline(always)]
    fn pixel_fused(&self, acc: &[u32; MAX_VARYINGS]) -> Rgb888 {
        self.0.pixel_fused(acc).into()
    }
    #[inline(always)]
    fn pixel_fused_dithered(&self, acc: &[u32; MAX_VARYINGS], threshold: u32) -> Rgb888 {
        self.0.pixel_fused_dithered(acc, threshold).into()
    }
}

/// Culling chosen at run time, so the fogged, dithered and translucent paths (and every mesh of
/// the banded path) compile one pipeline per stage set, not three. It keeps exactly the
/// triangles the stage it names keeps.
#[derive(Debug, Clone, Copy)]
pub(super) struct ModeCull(pub(super) CullMode);

impl Cull for ModeCull {
    fn keep(&self, area: i64) -> bool {
        match self.0 {
            CullMode::None => true,
            CullMode::Cw => CullClockwise.keep(area),
            CullMode::Ccw => CullCounterClockwise.keep(area),
        }
    }
}

/// Numerics with dithering `D` (1: Bayer 4x4, 2: Bayer 8x8).
#[derive(Debug)]
struct Dithered<const D: u8>;

impl<const D: u8> Numerics for Dithered<D> {
    const DITHER: Dither = if D == 1 {
        Dither::Bayer4
    } else {
        Dither::Bayer8
    };
}

/// A dithered mesh: picks the output's colour.
fn by_format<'s, S: Real, K: MeshSink<'s, S>>(
    sink: &mut K,
    job: &Job<'s, S>,
    format: PixelFormat,
) -> RenderStats {
    match format {
        PixelFormat::Rgb565 => dithered::<S, K, Rgb565>(sink, job),
        PixelFormat::Rgb888 => dithered::<S, K, Rgb888>(sink, job),
        PixelFormat::Gray8 => dithered::<S, K, Gray8>(sink, job),
        PixelFormat::Binary => dithered::<S, K, BinaryColor>(sink, job),
    }
}

/// A dithered mesh in the output's colour `C`: picks the depth stage.
fn dithered<'s, S: Real, K: MeshSink<'s, S>, C>(sink: &mut K, job: &Job<'s, S>) -> RenderStats
where
    C: rasterizer_core::color::ShadeColor + Into<Rgb888> + Debug + 'static,
{
    if job.mesh.depth {
        dithered_shading::<S, K, C, OpaqueDepth>(sink, job)
    } else {
        dithered_shading::<S, K, C, OpaqueNoDepth>(sink, job)
    }
}

/// Picks the shading and the matrix of a dithered mesh.
fn dithered_shading<'s, S: Real, K: MeshSink<'s, S>, C, U: DepthUse>(
    sink: &mut K,
    job: &Job<'s, S>,
) -> RenderStats
where
    C: rasterizer_core::color::ShadeColor + Into<Rgb888> + Debug + 'static,
{
    let cull = ModeCull(job.mesh.cull);
    let bayer4 = job.mesh.dither == DitherMode::Bayer4;
    let fog = fog_settings(job.mesh.fog.as_ref());
    let view = &job.transforms.view;
    if job.mesh.shading == ShadingModel::VertexColors {
        let sh = InRgb888(Fog::new(VertexColors::<C>::new(), fog, view));
        return if bayer4 {
            U::draw::<S, K, _, _, Dithered<1>>(sink, job, cull, sh)
        } else {
            U::draw::<S, K, _, _, Dithered<2>>(sink, job, cull, sh)
        };
    }
    let sh = InRgb888(Fog::new(
        GouraudLit::<S, C, MAX_LIGHTS>::new(job.lighting.clone()),
        fog,
        view,
    ));
    if bayer4 {
        U::draw::<S, K, _, _, Dithered<1>>(sink, job, cull, sh)
    } else {
        U::draw::<S, K, _, _, Dithered<2>>(sink, job, cull, sh)
    }
}

/// A translucent mesh (`opacity` below 255): blended, testing depth without writing it;
/// culling chosen at run time, so this compiles one pipeline per shading model.
fn translucent<'s, S: Real, K: MeshSink<'s, S>>(sink: &mut K, job: &Job<'s, S>) -> RenderStats {
    let cull = ModeCull(job.mesh.cull);
    if job.mesh.wireframe {
        return sink.wireframe(job, cull);
    }
    if job.mesh.depth {
        by_shading::<S, K, TranslucentDepth, _>(sink, job, cull)
    } else {
        by_shading::<S, K, TranslucentNoDepth, _>(sink, job, cull)
    }
}

/// Picks the culling stage.
fn by_cull<'s, S: Real, K: MeshSink<'s, S>>(sink: &mut K, job: &Job<'s, S>) -> RenderStats {
    match job.mesh.cull {
        CullMode::None => by_depth(sink, job, NoCull),
        CullMode::Cw => by_depth(sink, job, CullClockwise),
        CullMode::Ccw => by_depth(sink, job, CullCounterClockwise),
    }
}

/// Wireframe, or picks the depth stage.
fn by_depth<'s, S: Real, K: MeshSink<'s, S>, Cu: Stage>(
    sink: &mut K,
    job: &Job<'s, S>,
    cull: Cu,
) -> RenderStats {
    if job.mesh.wireframe {
        sink.wireframe(job, cull)
    } else if job.mesh.depth {
        by_shading::<S, K, OpaqueDepth, _>(sink, job, cull)
    } else {
        by_shading::<S, K, OpaqueNoDepth, _>(sink, job, cull)
    }
}

/// Picks the shading stage.
fn by_shading<'s, S: Real, K: MeshSink<'s, S>, U: DepthUse, Cu: Stage>(
    sink: &mut K,
    job: &Job<'s, S>,
    cull: Cu,
) -> RenderStats {
    let lighting = job.lighting.clone();
    // The loader allows a texture only with Gouraud shading.
    if let Some(t) = &job.mesh.texture {
        let shading = TexturedLit::<S, Rgb888, MAX_LIGHTS>::new(lighting, t.image.texture())
            .with_filter(t.filter)
            .with_wrap(t.wrap);
        return by_perspective::<S, K, U, _, _>(sink, job, cull, shading);
    }
    match job.mesh.shading {
        ShadingModel::None => {
            let color = job.mesh.color;
            by_perspective::<S, K, U, _, _>(sink, job, cull, Unlit { color })
        }
        ShadingModel::VertexColors => {
            by_perspective::<S, K, U, _, _>(sink, job, cull, VertexColors::<Rgb888>::new())
        }
        ShadingModel::Flat => {
            let flat = FlatLit::<S, Rgb888, MAX_LIGHTS>::new(lighting);
            by_perspective::<S, K, U, _, _>(sink, job, cull, flat)
        }
        ShadingModel::Gouraud => {
            let gouraud = GouraudLit::<S, Rgb888, MAX_LIGHTS>::new(lighting);
            by_perspective::<S, K, U, _, _>(sink, job, cull, gouraud)
        }
        ShadingModel::Phong => {
            let phong = PhongLit::<S, Rgb888, MAX_LIGHTS>::new(lighting);
            by_perspective::<S, K, U, _, _>(sink, job, cull, phong)
        }
        ShadingModel::Matcap => {
            let matcap = matcap::<S>(job);
            by_perspective::<S, K, U, _, _>(sink, job, cull, matcap)
        }
    }
}

/// The MatCap shader of a mesh with `shading = "matcap"` (the loader gives it an image, checked
/// square; a missing one draws the 1 x 1 black image rather than nothing).
fn matcap<'s, S: Real>(job: &Job<'s, S>) -> MatCap<'s, S, Rgb888> {
    let view = &job.transforms.view;
    job.mesh
        .matcap
        .as_ref()
        .and_then(|m| MatCap::from_texture(m.image.texture(), view).ok())
        .unwrap_or_else(|| {
            MatCap::new(0, &[0, 0], view).unwrap_or_else(|_| unreachable!("a 1 x 1 image"))
        })
}

/// Picks affine or perspective-correct interpolation.
fn by_perspective<'s, S, K, U, Cu, Sh>(
    sink: &mut K,
    job: &Job<'s, S>,
    cull: Cu,
    shading: Sh,
) -> RenderStats
where
    S: Real,
    K: MeshSink<'s, S>,
    U: DepthUse,
    Cu: Stage,
    Sh: Shade<S> + 's,
{
    if job.mesh.perspective_correct {
        U::draw::<S, K, Cu, Sh, Perspective>(sink, job, cull, shading)
    } else {
        U::draw::<S, K, Cu, Sh, Standard>(sink, job, cull, shading)
    }
}

/// The pipeline of a mesh's draw call.
pub(super) fn pipeline<S, Cu, D, Sh, N>(
    job: &Job<'_, S>,
    cull: Cu,
    depth: D,
    shading: Sh,
) -> Pipeline<S, Cu, D, Sh, { rasterizer_core::pipeline::DEFAULT_BITS }, N>
where
    S: Real,
    Cu: Cull,
    D: rasterizer_core::depth::DepthTest,
    Sh: Shading<S>,
    N: Numerics,
{
    let mut p =
        Pipeline::new(&job.transforms, job.viewport, cull, depth, shading).with_numerics::<N>();
    if let Some(n) = job.normal_matrix {
        p.set_normal_matrix(n);
    }
    p
}

/// The wireframe pipeline of a mesh: its colour, no depth test.
pub(super) fn wire_pipeline<S: Real, Cu: Cull>(
    job: &Job<'_, S>,
    cull: Cu,
) -> Pipeline<S, Cu, NoDepth, Unlit<Rgb888>> {
    let color = job.mesh.color;
    Pipeline::new(
        &job.transforms,
        job.viewport,
        cull,
        NoDepth,
        Unlit { color },
    )
}

/// Draws each mesh as it comes into one whole `Rgb888` frame, sharing one depth buffer of the
/// frame's size.
struct Whole<'t, 'f, 'm, S> {
    target: &'t mut Target<'f>,
    mesh: &'m DynMesh<'m, S>,
    zbuf: &'t mut [u16],
}

/// The draw call of one monomorphised pipeline.
fn draw_with<S, T, M, Cu, D, Sh, N>(
    target: &mut T,
    mesh: &M,
    job: &Job<'_, S>,
    cull: Cu,
    depth: D,
    shading: Sh,
) -> RenderStats
where
    S: Real,
    T: Surface<Color = Rgb888>,
    M: MeshSource<S>,
    Cu: Cull,
    D: rasterizer_core::depth::DepthTest,
    Sh: Shading<S, Color = Rgb888>,
    N: Numerics,
{
    let mut p = pipeline::<S, Cu, D, Sh, N>(job, cull, depth, shading);
    // The depth buffer is made for the target, so it always covers the viewport within it.
    let mut scratch = vec![VertexSlot::EMPTY; mesh.vertex_count()];
    if job.mesh.antialias {
        // Cannot be refused: the loader gave the mesh adjacency, every target here reads back
        // and every numerics of the scenes takes the fused span loop (a test draws each kind).
        return p
            .draw_antialiased(target, mesh, &mut scratch)
            .unwrap_or_default();
    }
    p.draw(target, mesh, &mut scratch).unwrap_or_default()
}

impl<'s, S: Real> MeshSink<'s, S> for Whole<'_, '_, '_, S> {
    fn opaque_with_depth<Cu: Stage, Sh: Shade<S> + 's, N: Knobs>(
        &mut self,
        job: &Job<'s, S>,
        cull: Cu,
        shading: Sh,
    ) -> RenderStats {
        let (w, h) = (job.viewport.width, job.viewport.height);
        // The buffer has exactly w * h entries, so this cannot fail.
        let Ok(depth) = DepthBuffer::new(self.zbuf, w, h, Compare::Less) else {
            return RenderStats::default();
        };
        draw_with::<S, _, _, Cu, _, Sh, N>(self.target, self.mesh, job, cull, depth, shading)
    }

    fn opaque_without_depth<Cu: Stage, Sh: Shade<S> + 's, N: Knobs>(
        &mut self,
        job: &Job<'s, S>,
        cull: Cu,
        shading: Sh,
    ) -> RenderStats {
        draw_with::<S, _, _, Cu, _, Sh, N>(self.target, self.mesh, job, cull, NoDepth, shading)
    }

    fn translucent_with_depth<Cu: Stage, Sh: Shade<S> + 's, N: Knobs>(
        &mut self,
        job: &Job<'s, S>,
        cull: Cu,
        shading: Sh,
    ) -> RenderStats {
        let mesh = self.mesh;
        let (w, h) = (job.viewport.width, job.viewport.height);
        let Ok(depth) = DepthBuffer::new(self.zbuf, w, h, Compare::Less) else {
            return RenderStats::default();
        };
        let target = &mut Translucent::new(&mut *self.target, job.mesh.opacity);
        draw_with::<S, _, _, Cu, _, Sh, N>(target, mesh, job, cull, depth.read_only(), shading)
    }

    fn translucent_without_depth<Cu: Stage, Sh: Shade<S> + 's, N: Knobs>(
        &mut self,
        job: &Job<'s, S>,
        cull: Cu,
        shading: Sh,
    ) -> RenderStats {
        let target = &mut Translucent::new(&mut *self.target, job.mesh.opacity);
        draw_with::<S, _, _, Cu, _, Sh, N>(target, self.mesh, job, cull, NoDepth, shading)
    }

    fn wireframe<Cu: Stage>(&mut self, job: &Job<'s, S>, cull: Cu) -> RenderStats {
        let mut p = wire_pipeline(job, cull);
        let color = job.mesh.color;
        let mut scratch = vec![VertexSlot::EMPTY; self.mesh.vertex_count()];
        if job.mesh.opacity == u8::MAX {
            let Ok(stats) = p.draw_wireframe(self.target, self.mesh, &mut scratch, color);
            return stats;
        }
        let target = &mut Translucent::new(&mut *self.target, job.mesh.opacity);
        // The framebuffer reads back, so this cannot fail.
        p.draw_wireframe(target, self.mesh, &mut scratch, color)
            .unwrap_or_default()
    }
}

/// A colour of the scene file in the display's format.
pub(super) fn color<C: From<Rgb888>>(c: super::format::Color) -> C {
    C::from(Rgb888::new(c.0[0], c.0[1], c.0[2]))
}

/// The pixel containing a point.
pub(super) fn pixel(p: [f64; 2]) -> Point {
    // `as` saturates, so far-away points stay far away.
    Point::new(p[0].floor() as i32, p[1].floor() as i32)
}

/// A vertex in 28.4 sub-pixel fixed point, rounded to 1/16 pixel.
pub(super) fn sub(p: [f64; 2]) -> SubPoint {
    let one = f64::from(SubPoint::<4>::ONE);
    SubPoint::new((p[0] * one).round() as i32, (p[1] * one).round() as i32)
}

/// The simulator display as a surface that reads back, so that translucent and anti-aliased
/// shapes can blend into it; everything else goes through the `DrawTarget` methods, as through
/// `AnyTarget`.
struct ReadBack<'a, C: PixelColor>(&'a mut SimulatorDisplay<C>);

impl<C: PixelColor> Dimensions for ReadBack<'_, C> {
    fn bounding_box(&self) -> Rectangle {
        self.0.bounding_box()
    }
}

impl<C: PixelColor> DrawTarget for ReadBack<'_, C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        self.0.draw_iter(pixels)
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = C>,
    {
        self.0.fill_contiguous(area, colors)
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Infallible> {
        self.0.fill_solid(area, color)
    }
}

impl<C: PixelColor + Channels> Surface for ReadBack<'_, C> {
    const READ_BACK: bool = true;

    fn blend_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: C,
        alpha: u8,
    ) -> Result<(), BlendError<Infallible>> {
        for x in x..x.saturating_add(len as i32) {
            let p = Point::new(x, y);
            let under = self.0.get_pixel(p);
            let Ok(()) = self
                .0
                .draw_iter([Pixel(p, rasterizer_core::color::blend(color, under, alpha))]);
        }
        Ok(())
    }
}

/// The 2D shapes, in order, straight onto the display (through [`ReadBack`]).
fn draw_shapes<C>(scene: &Scene, display: &mut SimulatorDisplay<C>)
where
    C: PixelColor + From<Rgb888> + Channels,
{
    let mut any = ReadBack(display);
    for shape in &scene.shapes {
        draw_scene_shape(&mut any, shape);
    }
}

/// A shape's clip rectangle and opacity.
pub(super) fn clip_and_opacity(shape: &Shape) -> (Option<Rectangle>, Option<u8>) {
    let (clip, opacity) = match shape {
        Shape::Point { clip, opacity, .. }
        | Shape::Line { clip, opacity, .. }
        | Shape::Triangle { clip, opacity, .. }
        | Shape::Outline { clip, opacity, .. }
        | Shape::Polygon { clip, opacity, .. }
        | Shape::Sprite { clip, opacity, .. } => (*clip, *opacity),
    };
    // The loader checked that width and height are not negative.
    let clip = clip.map(|[x, y, w, h]| {
        Rectangle::new(
            Point::new(x, y),
            Size::new(w.max(0) as u32, h.max(0) as u32),
        )
    });
    (clip, opacity)
}

/// One shape, within its clip rectangle and blended with its opacity, into `target` (the
/// display, or a band of the frame list).
pub(super) fn draw_scene_shape<T>(target: &mut T, shape: &Shape)
where
    T: Surface,
    T::Color: From<Rgb888> + Channels,
{
    let (clip, opacity) = clip_and_opacity(shape);
    let area = clip.unwrap_or_else(|| target.clip_area());
    let mut target = ClipTo::new(target, area);
    match opacity {
        Some(a) => draw_shape(&mut Translucent::new(&mut target, a), shape),
        None => draw_shape(&mut target, shape),
    }
}

/// The frame list's shape of a scene shape's geometry and colours, opaque and unclipped (the
/// caller applies the scene's clip and opacity): what both the whole-frame path and the bands
/// draw. `None` for points and polygons, which have no list shape, and for a shape without
/// colours.
pub(super) fn list_shape<C: From<Rgb888>>(shape: &Shape) -> Option<frame::Shape<C>> {
    match shape {
        Shape::Line {
            from,
            to,
            color: c,
            colors,
            antialias,
            width,
            ..
        } => {
            let (a, b) = (pixel(*from), pixel(*to));
            match (c, colors) {
                (_, Some([ca, cb])) => Some(frame::Shape::LineGradient {
                    a,
                    b,
                    colors: [color(*ca), color(*cb)],
                }),
                (Some(c), None) if *antialias => Some(frame::Shape::LineAa {
                    a,
                    b,
                    width: width.unwrap_or(1),
                    color: color(*c),
                }),
                (Some(c), None) => Some(frame::Shape::Line {
                    a,
                    b,
                    color: color(*c),
                }),
                (None, None) => None,
            }
        }
        Shape::Triangle {
            vertices,
            color: c,
            colors,
            ..
        } => {
            let vertices = vertices.map(sub);
            match (c, colors) {
                (_, Some(cs)) => Some(frame::Shape::Gouraud {
                    vertices,
                    colors: cs.map(color),
                    opacity: u8::MAX,
                }),
                (Some(c), None) => Some(frame::Shape::Triangle {
                    vertices,
                    color: color(*c),
                    opacity: u8::MAX,
                }),
                (None, None) => None,
            }
        }
        Shape::Outline {
            vertices, color: c, ..
        } => Some(frame::Shape::TriangleOutline {
            vertices: vertices.map(pixel),
            color: color(*c),
        }),
        Shape::Point { .. } | Shape::Polygon { .. } | Shape::Sprite { .. } => None,
    }
}

/// One shape (already checked by the loader). The target reads back, so no draw fails.
fn draw_shape<T>(t: &mut T, shape: &Shape)
where
    T: Surface,
    T::Color: From<Rgb888> + Channels,
{
    let _ = match shape {
        Shape::Point { at, color: c, .. } => draw_point(t, pixel(*at), color(*c)).map_err(drop),
        Shape::Polygon {
            vertices,
            fill_rule,
            color: c,
            ..
        } => {
            let pts: Vec<SubPoint> = vertices.iter().map(|&p| sub(p)).collect();
            let rule = match fill_rule {
                FillRuleDef::EvenOdd => FillRule::EvenOdd,
                FillRuleDef::NonZero => FillRule::NonZero,
            };
            match Polygon::<MAX_POLYGON, 4>::new(&pts) {
                Ok(poly) => poly.fill(t, rule, color(*c)).map_err(drop),
                // The loader checked the vertex count.
                Err(_) => Ok(()),
            }
        }
        Shape::Sprite { .. } => {
            super::sprite::draw(t, shape);
            Ok(())
        }
        _ => list_shape(shape).map_or(Ok(()), |s| s.draw(t).map_err(drop)),
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use rasterizer_core::mesh::NO_NEIGHBOUR;

    /// Both mesh sources of a scene, and the one type behind which they are drawn, answer with
    /// the adjacency their mesh carries.
    #[test]
    fn mesh_sources_expose_adjacency() {
        const N: u32 = NO_NEIGHBOUR;
        let quad = OwnedMesh {
            positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..OwnedMesh::default()
        };
        let plain = Converted::<Fx16>::new(&quad);
        assert!(!plain.has_adjacency() && !DynMesh(&plain).has_adjacency());
        assert_eq!(DynMesh(&plain).neighbours(0), [N; 3]);
        let quad = quad.with_adjacency();
        let c = Converted::<Fx16>::new(&quad);
        for m in [&c as &dyn MeshSource<Fx16>, &DynMesh(&c)] {
            assert!(m.has_adjacency());
            assert_eq!(m.neighbours(0), [N, N, 1]);
            assert_eq!(m.neighbours(1), [0, N, N]);
            assert_eq!(m.neighbours(2), [N; 3], "past the end");
        }
        let opts = crate::convert::Options {
            adjacency: true,
            ..Default::default()
        };
        let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
        let conv =
            crate::convert::convert_obj("q.obj", obj.as_bytes(), None, &opts, &mut Vec::new())
                .unwrap();
        let packed = PackedMesh::parse(&conv.blob).unwrap();
        let dynamic = DynMesh::<Fx16>(&packed);
        assert!(dynamic.has_adjacency());
        let (a, b) = (dynamic.neighbours(0), dynamic.neighbours(1));
        assert_eq!(a.iter().filter(|&&u| u == 1).count(), 1, "{a:?}");
        assert_eq!(b.iter().filter(|&&u| u == 0).count(), 1, "{b:?}");
    }

    /// [`InRgb888`] and the banded path's mesh layer rely on every output colour surviving the
    /// trip through `Rgb888`.
    #[test]
    fn output_colours_round_trip_through_rgb888() {
        for raw in 0..=u16::MAX {
            let c = Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(raw));
            assert_eq!(Rgb565::from(Rgb888::from(c)), c);
        }
        for v in 0..=255 {
            assert_eq!(Gray8::from(Rgb888::from(Gray8::new(v))), Gray8::new(v));
        }
        for b in [BinaryColor::Off, BinaryColor::On] {
            assert_eq!(BinaryColor::from(Rgb888::from(b)), b);
        }
    }
}
