//! Drawing a loaded scene: the meshes through the 3D pipeline, then the 2D shapes.

use super::format::{
    CullMode, DitherMode, FillRuleDef, LightDef, PixelFormat, ShadingModel, Shape,
};
use super::load::{MeshData, OwnedMesh, Scene, SceneFog, SceneMesh};
use super::reference::Real;
use super::{MAX_LIGHTS, MAX_POLYGON};
use embedded_graphics_simulator::{OutputImage, OutputSettingsBuilder, SimulatorDisplay};
use rasterizer_core::color::Channels;
use rasterizer_core::color::ShadeColor;
use rasterizer_core::cull::Cull;
use rasterizer_core::depth::DepthTest;
use rasterizer_core::numerics::{Dither, Numerics, Perspective, Standard};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::{Fog, FogCurve, FogSettings, Foggable, Shading, FOG_TABLE_LEN};
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
    /// Pixels the meshes wrote (a pixel written twice counts twice).
    pub pixels: u64,
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
    let settings = OutputSettingsBuilder::new().scale(scale).build();
    Ok(match scene.format {
        PixelFormat::Rgb565 => output(render_display::<Rgb565>(scene, pose)?, &settings),
        PixelFormat::Rgb888 => output(render_display::<Rgb888>(scene, pose)?, &settings),
        PixelFormat::Gray8 => output(render_display::<Gray8>(scene, pose)?, &settings),
        PixelFormat::Binary => output(render_display::<BinaryColor>(scene, pose)?, &settings),
    })
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
/// `Framebuffer<Rgb888>` (the shaders produce `Rgb888` and convert each pixel to the target's
/// colour in any case, so this gives the pixels a pipeline of colour `C` would), copied onto the
/// display converted to `C`; then the shapes straight onto the display through `AnyTarget`.
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
        pixels: target.pixels,
    };
    let fb = &target.inner;
    let rgb = (0..h as i32)
        .flat_map(|y| (0..w as i32).map(move |x| Point::new(x, y)))
        .map(|p| fb.pixel(p).unwrap_or(scene.background))
        .collect();
    Ok((rgb, stats))
}

/// Any mesh source behind one type, so the pipelines are compiled once for all mesh kinds.
struct DynMesh<'a, S>(&'a dyn MeshSource<S>);

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
}

/// The target every pipeline draws into.
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
struct Job<'a, S: Real> {
    mesh: &'a SceneMesh,
    transforms: Transforms<S>,
    normal_matrix: Option<Mat4<S>>,
    viewport: Viewport,
    lighting: Lighting<S, MAX_LIGHTS>,
}

/// The meshes, in order, sharing one depth buffer.
/// Returns the triangles handed to the rasterizer.
fn draw_meshes<S: Real>(scene: &Scene, target: &mut Target<'_>, pose: Pose) -> Result<u64, String> {
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
    let mut zbuf = vec![u16::MAX; w as usize * h as usize];
    let mut triangles = 0;
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
        let job = Job {
            mesh,
            transforms: Transforms {
                model,
                view,
                projection,
            },
            normal_matrix,
            viewport: Viewport::new(w, h),
            lighting,
        };
        let format = scene.format;
        let draw = |target: &mut Target<'_>, m: &DynMesh<'_, S>, zbuf: &mut [u16]| {
            if mesh.opacity < u8::MAX {
                translucent(target, m, &job, zbuf)
            } else if dithers(mesh) {
                by_format(target, m, &job, zbuf, format)
            } else if fogs(mesh) {
                fogged(target, m, &job, zbuf)
            } else {
                by_cull(target, m, &job, zbuf)
            }
        };
        match &mesh.data {
            MeshData::Packed(bytes) => {
                let packed = PackedMesh::parse(bytes).map_err(|e| e.to_string())?;
                triangles += u64::from(draw(target, &DynMesh(&packed), &mut zbuf).drawn);
            }
            MeshData::Owned(owned) => {
                let data = Converted::<S>::new(owned);
                let mesh = DynMesh(&data.mesh());
                triangles += u64::from(draw(target, &mesh, &mut zbuf).drawn);
            }
        }
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
        }
    }

    fn mesh(&self) -> Mesh<'_, S, u32> {
        Mesh {
            positions: &self.positions,
            normals: self.normals.as_deref(),
            colors: self.colors.as_deref(),
            uvs: self.uvs.as_deref(),
            triangles: &self.triangles,
        }
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
fn fogged<S: Real>(
    target: &mut Target<'_>,
    mesh: &DynMesh<'_, S>,
    job: &Job<'_, S>,
    zbuf: &mut [u16],
) -> RenderStats {
    let cull = ModeCull(job.mesh.cull);
    if !job.mesh.depth {
        return fogged_shading(target, mesh, job, cull, NoDepth);
    }
    let (w, h) = (job.viewport.width, job.viewport.height);
    match DepthBuffer::new(zbuf, w, h, Compare::Less) {
        Ok(depth) => fogged_shading(target, mesh, job, cull, depth),
        Err(_) => RenderStats::default(),
    }
}

/// Picks the shading model of a fogged mesh.
fn fogged_shading<S: Real, D: DepthTest>(
    target: &mut Target<'_>,
    mesh: &DynMesh<'_, S>,
    job: &Job<'_, S>,
    cull: ModeCull,
    depth: D,
) -> RenderStats {
    fn with_fog<S: Real, D: DepthTest, Sh: Foggable<S, Color = Rgb888>>(
        target: &mut Target<'_>,
        mesh: &DynMesh<'_, S>,
        job: &Job<'_, S>,
        cull: ModeCull,
        depth: D,
        inner: Sh,
    ) -> RenderStats {
        let settings = fog_settings(job.mesh.fog.as_ref());
        let shading = Fog::new(inner, settings, &job.transforms.view);
        by_perspective(target, mesh, job, cull, depth, shading)
    }
    let lighting = job.lighting.clone();
    match job.mesh.shading {
        ShadingModel::VertexColors => with_fog(
            target,
            mesh,
            job,
            cull,
            depth,
            VertexColors::<Rgb888>::new(),
        ),
        ShadingModel::Flat => {
            let flat = FlatLit::<S, Rgb888, MAX_LIGHTS>::new(lighting);
            with_fog(target, mesh, job, cull, depth, flat)
        }
        ShadingModel::Phong => {
            let phong = PhongLit::<S, Rgb888, MAX_LIGHTS>::new(lighting);
            with_fog(target, mesh, job, cull, depth, phong)
        }
        _ => {
            let gouraud = GouraudLit::<S, Rgb888, MAX_LIGHTS>::new(lighting);
            with_fog(target, mesh, job, cull, depth, gouraud)
        }
    }
}

/// The `Rgb888` target seen as a target of the output's colour `C`, so that a dithered pipeline
/// works at the output's channel depth. Each pixel goes back to `Rgb888` exactly: the output's
/// conversion from `Rgb888` returns the same `C`.
struct AsColor<'t, 'f, C>(&'t mut Target<'f>, core::marker::PhantomData<C>);

impl<C> Dimensions for AsColor<'_, '_, C> {
    fn bounding_box(&self) -> Rectangle {
        self.0.bounding_box()
    }
}

impl<C: PixelColor + Into<Rgb888>> DrawTarget for AsColor<'_, '_, C> {
    type Color = C;
    type Error = Infallible;
    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        self.0
            .draw_iter(pixels.into_iter().map(|Pixel(p, c)| Pixel(p, c.into())))
    }
}

impl<C: PixelColor + Into<Rgb888>> Surface for AsColor<'_, '_, C> {}

/// Culling chosen at run time, so the dithered path compiles one pipeline per colour, not three.
#[derive(Debug, Clone, Copy)]
struct ModeCull(CullMode);

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
struct Dithered<const D: u8>;

impl<const D: u8> Numerics for Dithered<D> {
    const DITHER: Dither = if D == 1 {
        Dither::Bayer4
    } else {
        Dither::Bayer8
    };
}

/// A dithered mesh: picks the output's colour.
fn by_format<S: Real>(
    target: &mut Target<'_>,
    mesh: &DynMesh<'_, S>,
    job: &Job<'_, S>,
    zbuf: &mut [u16],
    format: PixelFormat,
) -> RenderStats {
    match format {
        PixelFormat::Rgb565 => dithered::<S, Rgb565>(target, mesh, job, zbuf),
        PixelFormat::Rgb888 => dithered::<S, Rgb888>(target, mesh, job, zbuf),
        PixelFormat::Gray8 => dithered::<S, Gray8>(target, mesh, job, zbuf),
        PixelFormat::Binary => dithered::<S, BinaryColor>(target, mesh, job, zbuf),
    }
}

/// A dithered mesh in the output's colour `C`: picks the depth stage, shading and matrix.
fn dithered<S: Real, C: ShadeColor + Into<Rgb888>>(
    target: &mut Target<'_>,
    mesh: &DynMesh<'_, S>,
    job: &Job<'_, S>,
    zbuf: &mut [u16],
) -> RenderStats {
    let mut target = AsColor::<C>(target, core::marker::PhantomData);
    let cull = ModeCull(job.mesh.cull);
    if !job.mesh.depth {
        return dithered_shading::<S, C, _>(&mut target, mesh, job, cull, NoDepth);
    }
    let (w, h) = (job.viewport.width, job.viewport.height);
    match DepthBuffer::new(zbuf, w, h, Compare::Less) {
        Ok(depth) => dithered_shading::<S, C, _>(&mut target, mesh, job, cull, depth),
        Err(_) => RenderStats::default(),
    }
}

/// Picks the shading and the matrix of a dithered mesh.
fn dithered_shading<S: Real, C: ShadeColor + Into<Rgb888>, D: DepthTest>(
    target: &mut AsColor<'_, '_, C>,
    mesh: &DynMesh<'_, S>,
    job: &Job<'_, S>,
    cull: ModeCull,
    depth: D,
) -> RenderStats {
    fn draw<S: Real, C: ShadeColor + Into<Rgb888>, D: DepthTest, Sh, N: Numerics>(
        target: &mut AsColor<'_, '_, C>,
        mesh: &DynMesh<'_, S>,
        job: &Job<'_, S>,
        cull: ModeCull,
        depth: D,
        shading: Sh,
    ) -> RenderStats
    where
        Sh: Shading<S, Color = C>,
    {
        let mut p =
            Pipeline::new(&job.transforms, job.viewport, cull, depth, shading).with_numerics::<N>();
        if let Some(n) = job.normal_matrix {
            p.set_normal_matrix(n);
        }
        let mut scratch = vec![VertexSlot::EMPTY; mesh.vertex_count()];
        p.draw(target, mesh, &mut scratch).unwrap_or_default()
    }
    let bayer4 = job.mesh.dither == DitherMode::Bayer4;
    let fog = fog_settings(job.mesh.fog.as_ref());
    let view = &job.transforms.view;
    if job.mesh.shading == ShadingModel::VertexColors {
        let sh = Fog::new(VertexColors::<C>::new(), fog, view);
        return if bayer4 {
            draw::<S, C, D, _, Dithered<1>>(target, mesh, job, cull, depth, sh)
        } else {
            draw::<S, C, D, _, Dithered<2>>(target, mesh, job, cull, depth, sh)
        };
    }
    let sh = Fog::new(
        GouraudLit::<S, C, MAX_LIGHTS>::new(job.lighting.clone()),
        fog,
        view,
    );
    if bayer4 {
        draw::<S, C, D, _, Dithered<1>>(target, mesh, job, cull, depth, sh)
    } else {
        draw::<S, C, D, _, Dithered<2>>(target, mesh, job, cull, depth, sh)
    }
}

/// A translucent mesh (`opacity` below 255): drawn through `Translucent`, testing depth without
/// writing it; culling chosen at run time, so this compiles one pipeline per shading model.
fn translucent<S: Real>(
    target: &mut Target<'_>,
    mesh: &DynMesh<'_, S>,
    job: &Job<'_, S>,
    zbuf: &mut [u16],
) -> RenderStats {
    let mut target = Translucent::new(target, job.mesh.opacity);
    let cull = ModeCull(job.mesh.cull);
    if job.mesh.wireframe {
        let color = job.mesh.color;
        let mut p = Pipeline::new(
            &job.transforms,
            job.viewport,
            cull,
            NoDepth,
            Unlit { color },
        );
        let mut scratch = vec![VertexSlot::EMPTY; mesh.vertex_count()];
        // The framebuffer reads back, so this cannot fail.
        return p
            .draw_wireframe(&mut target, mesh, &mut scratch, color)
            .unwrap_or_default();
    }
    if !job.mesh.depth {
        return by_shading(&mut target, mesh, job, cull, NoDepth);
    }
    let (w, h) = (job.viewport.width, job.viewport.height);
    match DepthBuffer::new(zbuf, w, h, Compare::Less) {
        Ok(depth) => by_shading(&mut target, mesh, job, cull, depth.read_only()),
        Err(_) => RenderStats::default(),
    }
}

/// Picks the culling stage.
fn by_cull<S: Real, M>(
    target: &mut Target<'_>,
    mesh: &M,
    job: &Job<'_, S>,
    zbuf: &mut [u16],
) -> RenderStats
where
    M: MeshSource<S>,
{
    match job.mesh.cull {
        CullMode::None => by_depth(target, mesh, job, zbuf, NoCull),
        CullMode::Cw => by_depth(target, mesh, job, zbuf, CullClockwise),
        CullMode::Ccw => by_depth(target, mesh, job, zbuf, CullCounterClockwise),
    }
}

/// Wireframe, or picks the depth stage.
fn by_depth<S: Real, M, C: Cull>(
    target: &mut Target<'_>,
    mesh: &M,
    job: &Job<'_, S>,
    zbuf: &mut [u16],
    cull: C,
) -> RenderStats
where
    M: MeshSource<S>,
{
    if job.mesh.wireframe {
        let color = job.mesh.color;
        let mut p = Pipeline::new(
            &job.transforms,
            job.viewport,
            cull,
            NoDepth,
            Unlit { color },
        );
        let mut scratch = vec![VertexSlot::EMPTY; mesh.vertex_count()];
        let Ok(stats) = p.draw_wireframe(target, mesh, &mut scratch, color);
        return stats;
    }
    if job.mesh.depth {
        let (w, h) = (job.viewport.width, job.viewport.height);
        // The buffer has exactly w * h entries, so this cannot fail.
        match DepthBuffer::new(zbuf, w, h, Compare::Less) {
            Ok(depth) => by_shading(target, mesh, job, cull, depth),
            Err(_) => RenderStats::default(),
        }
    } else {
        by_shading(target, mesh, job, cull, NoDepth)
    }
}

/// Picks the shading stage.
fn by_shading<S: Real, T: Surface<Color = Rgb888>, M, C: Cull, D: DepthTest>(
    target: &mut T,
    mesh: &M,
    job: &Job<'_, S>,
    cull: C,
    depth: D,
) -> RenderStats
where
    M: MeshSource<S>,
{
    let lighting = job.lighting.clone();
    // The loader allows a texture only with Gouraud shading.
    if let Some(t) = &job.mesh.texture {
        let shading = TexturedLit::<S, Rgb888, MAX_LIGHTS>::new(lighting, t.image.texture())
            .with_filter(t.filter)
            .with_wrap(t.wrap);
        return by_perspective(target, mesh, job, cull, depth, shading);
    }
    match job.mesh.shading {
        ShadingModel::None => by_perspective(
            target,
            mesh,
            job,
            cull,
            depth,
            Unlit {
                color: job.mesh.color,
            },
        ),
        ShadingModel::VertexColors => by_perspective(
            target,
            mesh,
            job,
            cull,
            depth,
            VertexColors::<Rgb888>::new(),
        ),
        ShadingModel::Flat => by_perspective(
            target,
            mesh,
            job,
            cull,
            depth,
            FlatLit::<S, Rgb888, MAX_LIGHTS>::new(lighting),
        ),
        ShadingModel::Gouraud => by_perspective(
            target,
            mesh,
            job,
            cull,
            depth,
            GouraudLit::<S, Rgb888, MAX_LIGHTS>::new(lighting),
        ),
        ShadingModel::Phong => by_perspective(
            target,
            mesh,
            job,
            cull,
            depth,
            PhongLit::<S, Rgb888, MAX_LIGHTS>::new(lighting),
        ),
    }
}

/// Picks affine or perspective-correct interpolation.
fn by_perspective<S, T, M, C, D, Sh>(
    target: &mut T,
    mesh: &M,
    job: &Job<'_, S>,
    cull: C,
    depth: D,
    shading: Sh,
) -> RenderStats
where
    S: Real,
    T: Surface<Color = Rgb888>,
    M: MeshSource<S>,
    C: Cull,
    D: DepthTest,
    Sh: Shading<S, Color = Rgb888>,
{
    if job.mesh.perspective_correct {
        draw_with::<S, T, M, C, D, Sh, Perspective>(target, mesh, job, cull, depth, shading)
    } else {
        draw_with::<S, T, M, C, D, Sh, Standard>(target, mesh, job, cull, depth, shading)
    }
}

/// The draw call of one monomorphised pipeline.
fn draw_with<S, T, M, C, D, Sh, N>(
    target: &mut T,
    mesh: &M,
    job: &Job<'_, S>,
    cull: C,
    depth: D,
    shading: Sh,
) -> RenderStats
where
    S: Real,
    T: Surface<Color = Rgb888>,
    M: MeshSource<S>,
    C: Cull,
    D: DepthTest,
    Sh: Shading<S, Color = Rgb888>,
    N: Numerics,
{
    let mut p =
        Pipeline::new(&job.transforms, job.viewport, cull, depth, shading).with_numerics::<N>();
    if let Some(n) = job.normal_matrix {
        p.set_normal_matrix(n);
    }
    // The depth buffer is made for the target, so it always covers the viewport within it.
    let mut scratch = vec![VertexSlot::EMPTY; mesh.vertex_count()];
    p.draw(target, mesh, &mut scratch).unwrap_or_default()
}

/// A colour of the scene file in the display's format.
fn color<C: From<Rgb888>>(c: super::format::Color) -> C {
    C::from(Rgb888::new(c.0[0], c.0[1], c.0[2]))
}

/// The pixel containing a point.
fn pixel(p: [f64; 2]) -> Point {
    // `as` saturates, so far-away points stay far away.
    Point::new(p[0].floor() as i32, p[1].floor() as i32)
}

/// A vertex in 28.4 sub-pixel fixed point, rounded to 1/16 pixel.
fn sub(p: [f64; 2]) -> SubPoint {
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
        let (clip, opacity) = match shape {
            Shape::Point { clip, opacity, .. }
            | Shape::Line { clip, opacity, .. }
            | Shape::Triangle { clip, opacity, .. }
            | Shape::Outline { clip, opacity, .. }
            | Shape::Polygon { clip, opacity, .. } => (*clip, *opacity),
        };
        let area = match clip {
            Some([x, y, w, h]) => Rectangle::new(Point::new(x, y), Size::new(w as u32, h as u32)),
            None => any.clip_area(),
        };
        let mut target = ClipTo::new(&mut any, area);
        match opacity {
            Some(a) => draw_shape(&mut Translucent::new(&mut target, a), shape),
            None => draw_shape(&mut target, shape),
        }
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
        Shape::Line {
            from,
            to,
            color: c,
            colors,
            antialias,
            width,
            ..
        } => match (c, colors) {
            (_, Some([a, b])) => {
                draw_line_gradient(t, pixel(*from), pixel(*to), color(*a), color(*b)).map_err(drop)
            }
            (Some(c), None) if *antialias => {
                let (a, b) = (pixel(*from), pixel(*to));
                draw_line_aa_wide(t, a, b, width.unwrap_or(1), color(*c)).map_err(drop)
            }
            (Some(c), None) => draw_line(t, pixel(*from), pixel(*to), color(*c)).map_err(drop),
            (None, None) => Ok(()),
        },
        Shape::Triangle {
            vertices,
            color: c,
            colors,
            ..
        } => {
            let v = vertices.map(sub);
            match (c, colors) {
                (_, Some(cs)) => fill_triangle_gouraud(t, v, cs.map(color)).map_err(drop),
                (Some(c), None) => fill_triangle(t, v, color(*c)).map_err(drop),
                (None, None) => Ok(()),
            }
        }
        Shape::Outline {
            vertices, color: c, ..
        } => draw_triangle(t, vertices.map(pixel), color(*c)).map_err(drop),
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
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`AsColor`] relies on every output colour surviving the trip through `Rgb888`.
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
