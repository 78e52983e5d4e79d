//! The 3D pictures of the `demo` command, rendered by [`rasterizer_core::pipeline::Pipeline`].
//!
//! They show both ways of getting pipeline output onto a display:
//!
//! - the Suzanne pictures render into a [`Framebuffer<Rgb565>`] (what a microcontroller sends to
//!   its panel), which is then copied pixel by pixel onto the simulator display;
//! - the cube and near-plane pictures draw straight onto the simulator display through
//!   [`AnyTarget`]; each frame of [`cube_inside`] has its own pipeline [`Viewport`], which the
//!   pipeline also clips to, so the four frames share one display.
//!
//! Every picture is [`WIDTH`] x [`HEIGHT`] display pixels and is saved at [`SCALE`]x. Scene set-up
//! (camera paths, colours) uses `f64` on the host; everything the pipeline does is integer.

use crate::demo::{hsv, Display, SceneResult, BACKGROUND};
use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::text::{Baseline, Text};
use embedded_graphics::Drawable;
use fixtures::obj::LoadedMesh;
use fixtures::scenes3d::{lighting, transforms};
use rasterizer_core::numerics::{Dither, Numerics, Standard};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::Shading;
use std::path::Path;

/// Width of every 3D picture, in display pixels.
pub const WIDTH: u32 = 320;
/// Height of every 3D picture, in display pixels.
pub const HEIGHT: u32 = 240;
/// How many PNG pixels one display pixel becomes.
pub const SCALE: u32 = 2;
/// Pixels of one picture.
const PIXELS: usize = (WIDTH * HEIGHT) as usize;

/// The meshes the scenes use, loaded once.
pub struct Models {
    /// Suzanne with the normals of its file.
    pub suzanne: LoadedMesh,
}

impl Models {
    /// Loads the models from `dir` (the repository's `assets/models`).
    ///
    /// # Errors
    /// The path of the file that failed and why.
    pub fn load(dir: &Path) -> Result<Self, (std::path::PathBuf, String)> {
        let load = |name: &str| {
            let path = dir.join(name);
            LoadedMesh::load(&path).map_err(|e| (path, e.to_string()))
        };
        let mut suzanne = load("suzanne.obj")?;
        if suzanne.normals.is_none() {
            suzanne.compute_smooth_normals();
        }
        Ok(Self { suzanne })
    }
}

/// One 3D picture: its file name and the function that draws it.
pub struct Scene3d {
    /// The PNG file name, stable across versions (README.md links to it).
    pub file: &'static str,
    /// Draws the picture onto a display cleared to the background colour.
    draw: fn(&Models, &mut Display) -> SceneResult,
}

/// Every 3D picture, in the order they are written.
pub const SCENES: [Scene3d; 10] = [
    Scene3d {
        file: "suzanne_wireframe.png",
        draw: suzanne_wireframe,
    },
    Scene3d {
        file: "suzanne_flat.png",
        draw: suzanne_flat,
    },
    Scene3d {
        file: "suzanne_gouraud.png",
        draw: suzanne_gouraud,
    },
    Scene3d {
        file: "suzanne_phong.png",
        draw: suzanne_phong,
    },
    Scene3d {
        file: "suzanne_matcap.png",
        draw: suzanne_matcap,
    },
    Scene3d {
        file: "suzanne_dither.png",
        draw: suzanne_dither,
    },
    Scene3d {
        file: "suzanne_aa.png",
        draw: suzanne_aa,
    },
    Scene3d {
        file: "suzanne_fog.png",
        draw: suzanne_fog,
    },
    Scene3d {
        file: "cube_inside.png",
        draw: cube_inside,
    },
    Scene3d {
        file: "near_plane_crossing.png",
        draw: near_plane_crossing,
    },
];

/// Draws one scene onto a fresh display with the dark background.
///
/// # Errors
/// What the scene reported (a rejected input: a bug in the scene).
pub fn render(scene: &Scene3d, models: &Models) -> Result<Display, String> {
    let mut display = Display::new(Size::new(WIDTH, HEIGHT));
    let Ok(()) = display.clear(BACKGROUND);
    (scene.draw)(models, &mut display)?;
    Ok(display)
}

/// A host `f64` rounded to 16.16.
fn fx(v: f64) -> Fx16 {
    Fx16::from_bits((v * 65536.0).round() as i32)
}

/// A vector of host `f64`s rounded to 16.16.
fn v3(x: f64, y: f64, z: f64) -> Vec3<Fx16> {
    Vec3::new(fx(x), fx(y), fx(z))
}

/// A 4:3 perspective projection with a vertical field of view of `fov` degrees.
fn perspective(fov: i32, near: Fx16, far: Fx16) -> Mat4<Fx16> {
    Mat4::perspective(Angle::from_degrees(fov), Fx16::from_ratio(4, 3), near, far)
        .expect("valid projection")
}

/// Renders into a 320x240 `Framebuffer<Rgb565>` (cleared to the background) with a depth buffer
/// cleared to the far plane, then copies the framebuffer onto `display`.
fn via_framebuffer(
    display: &mut Display,
    draw: impl FnOnce(&mut Framebuffer<'_, Rgb565>, DepthBuffer<'_>) -> SceneResult,
) -> SceneResult {
    let mut words = vec![0u16; PIXELS];
    let mut fb =
        Framebuffer::<Rgb565>::new(&mut words, WIDTH, HEIGHT).map_err(|e| e.to_string())?;
    let Ok(()) = fb.clear(Rgb565::from(BACKGROUND));
    let mut zbuf = vec![u16::MAX; PIXELS];
    let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less)
        .map_err(|e| format!("depth buffer: {e:?}"))?;
    draw(&mut fb, depth)?;
    let pixels = (0..HEIGHT as i32).flat_map(|y| (0..WIDTH as i32).map(move |x| Point::new(x, y)));
    let Ok(()) =
        display.draw_iter(pixels.filter_map(|p| fb.pixel(p).map(|c| Pixel(p, Rgb888::from(c)))));
    Ok(())
}

/// Fails unless a draw call drew something (a scene that draws nothing is a broken scene).
fn check_drawn(what: &str, drawn: u32) -> SceneResult {
    if drawn == 0 {
        Err(format!("{what}: no triangle drawn"))
    } else {
        Ok(())
    }
}

/// Suzanne's edges, back faces culled (the edges of hidden front faces still show: no depth test).
fn suzanne_wireframe(models: &Models, display: &mut Display) -> SceneResult {
    via_framebuffer(display, |fb, _depth| {
        let viewport = Viewport::new(WIDTH, HEIGHT);
        let mut p = Pipeline::new(
            &transforms(),
            viewport,
            CullClockwise,
            NoDepth,
            Unlit {
                color: Rgb565::WHITE,
            },
        );
        let color = Rgb565::from(Rgb888::new(120, 220, 160));
        let mesh = models.suzanne.mesh();
        let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
        let Ok(stats) = p.draw_wireframe(fb, &mesh, &mut scratch, color);
        check_drawn("wireframe", stats.drawn)
    })
}

/// Suzanne filled with one shading model, in the M1 scene.
fn suzanne_filled<Sh>(models: &Models, display: &mut Display, shading: Sh) -> SceneResult
where
    Sh: Shading<Fx16, Color = Rgb565>,
{
    suzanne_filled_with::<Sh, Standard>(models, display, shading)
}

/// [`suzanne_filled`] with numerics `N`.
fn suzanne_filled_with<Sh, N>(models: &Models, display: &mut Display, shading: Sh) -> SceneResult
where
    Sh: Shading<Fx16, Color = Rgb565>,
    N: Numerics,
{
    via_framebuffer(display, |fb, depth| {
        let viewport = Viewport::new(WIDTH, HEIGHT);
        let mut p = Pipeline::new(&transforms(), viewport, CullClockwise, depth, shading)
            .with_numerics::<N>();
        let mesh = models.suzanne.mesh();
        let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
        let stats = p.draw(fb, &mesh, &mut scratch).map_err(|e| e.to_string())?;
        check_drawn("suzanne", stats.drawn)
    })
}

/// Suzanne lit once per triangle.
fn suzanne_flat(models: &Models, display: &mut Display) -> SceneResult {
    suzanne_filled(
        models,
        display,
        FlatLit::<_, Rgb565, 2>::new(lighting::<2>()),
    )
}

/// Suzanne lit per vertex with the file's normals, colours interpolated.
fn suzanne_gouraud(models: &Models, display: &mut Display) -> SceneResult {
    suzanne_filled(
        models,
        display,
        GouraudLit::<_, Rgb565, 2>::new(lighting::<2>()),
    )
}

/// Suzanne coloured per vertex from the default MatCap image (a glossy clay sphere) by the
/// view-space normal, colours interpolated: no lights, the picture holds them.
fn suzanne_matcap(models: &Models, display: &mut Display) -> SceneResult {
    let side = fixtures::matcap::GLOSSY_64_SIDE_LOG2;
    let image = fixtures::matcap::GLOSSY_64;
    let matcap =
        MatCap::<_, Rgb565>::new(side, image, &transforms().view).map_err(|e| e.to_string())?;
    suzanne_filled(models, display, matcap)
}

/// Numerics with 4 x 4 ordered dithering.
struct Bayer4;

impl Numerics for Bayer4 {
    const DITHER: Dither = Dither::Bayer4;
}

/// Suzanne Gouraud-lit into Rgb565, split down the middle: on the left each pixel rounded to the
/// nearest 5- or 6-bit step (bands show across the smooth shading), on the right dithered with
/// the 4 x 4 Bayer matrix (the bands dissolve into a fine pattern of the two nearest steps).
fn suzanne_dither(models: &Models, display: &mut Display) -> SceneResult {
    let gouraud = || GouraudLit::<_, Rgb565, 2>::new(lighting::<2>());
    suzanne_filled(models, display, gouraud())?;
    let mut dithered = Display::new(Size::new(WIDTH, HEIGHT));
    let Ok(()) = dithered.clear(BACKGROUND);
    suzanne_filled_with::<_, Bayer4>(models, &mut dithered, gouraud())?;
    let half = WIDTH as i32 / 2;
    let right =
        (0..HEIGHT as i32).flat_map(|y| (half..WIDTH as i32).map(move |x| Point::new(x, y)));
    let Ok(()) = display.draw_iter(right.map(|p| Pixel(p, dithered.get_pixel(p))));
    let line = Rgb888::new(14, 16, 26);
    let Ok(()) = display.draw_iter((0..HEIGHT as i32).map(|y| Pixel(Point::new(half, y), line)));
    let style = MonoTextStyle::new(&FONT_6X10, Rgb888::WHITE);
    for (x, label) in [(3, "rounded"), (half + 4, "Bayer 4x4 dither")] {
        let text = Text::with_baseline(label, Point::new(x, 2), style, Baseline::Top);
        let Ok(_) = text.draw(display);
    }
    Ok(())
}

/// Suzanne Gouraud-lit, split down the middle: on the left `Pipeline::draw` (a pixel is hers or
/// not by its centre, so her outline steps), on the right `Pipeline::draw_antialiased` (each
/// pixel her silhouette crosses blended with the background by the share she covers), with the
/// adjacency found by position as the scene loader finds it.
fn suzanne_aa(models: &Models, display: &mut Display) -> SceneResult {
    let gouraud = || GouraudLit::<_, Rgb565, 2>::new(lighting::<2>());
    suzanne_filled(models, display, gouraud())?;
    let mut smooth = Display::new(Size::new(WIDTH, HEIGHT));
    let Ok(()) = smooth.clear(BACKGROUND);
    let suzanne = &models.suzanne;
    let keys: Vec<[i32; 3]> = suzanne
        .positions
        .iter()
        .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
        .collect();
    let adjacency = fixtures::adjacency::adjacency_by_position(&suzanne.triangles, &keys);
    via_framebuffer(&mut smooth, |fb, depth| {
        let viewport = Viewport::new(WIDTH, HEIGHT);
        let mut p = Pipeline::new(&transforms(), viewport, CullClockwise, depth, gouraud());
        let mesh = suzanne.mesh().with_adjacency(&adjacency);
        let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
        let stats = p
            .draw_antialiased(fb, &mesh, &mut scratch)
            .map_err(|e| e.to_string())?;
        check_drawn("anti-aliased suzanne", stats.drawn)
    })?;
    let half = WIDTH as i32 / 2;
    let right =
        (0..HEIGHT as i32).flat_map(|y| (half..WIDTH as i32).map(move |x| Point::new(x, y)));
    let Ok(()) = display.draw_iter(right.map(|p| Pixel(p, smooth.get_pixel(p))));
    let line = Rgb888::new(60, 64, 80);
    let Ok(()) = display.draw_iter((0..HEIGHT as i32).map(|y| Pixel(Point::new(half, y), line)));
    let style = MonoTextStyle::new(&FONT_6X10, Rgb888::WHITE);
    for (x, label) in [(3, "draw"), (half + 4, "draw_antialiased")] {
        let text = Text::with_baseline(label, Point::new(x, 2), style, Baseline::Top);
        let Ok(_) = text.draw(display);
    }
    Ok(())
}

/// Six Suzannes receding from 3.6 to 15 units (about 1.33 times further each, spaced evenly
/// across the screen), Gouraud-lit into Rgb565 and fogged per vertex (`shade::Fog`, linear from
/// depth 4 to 16) toward the colour the frame is cleared to, so the far ones fade into it.
fn suzanne_fog(models: &Models, display: &mut Display) -> SceneResult {
    use rasterizer_core::shade::{Fog, FogCurve, FogSettings};
    // Where each one stands and its turn towards the camera, in degrees.
    const PLACES: [(f64, f64, f64, i32); 6] = [
        (-2.0, -0.3, -0.6, 29),
        (-1.45, -0.25, -1.8, 20),
        (-0.35, -0.1, -3.4, 5),
        (1.65, 0.15, -5.45, -17),
        (5.05, 0.6, -8.25, -31),
        (10.45, 1.3, -12.0, -35),
    ];
    let fog = Rgb888::new(150, 166, 186);
    let eye = v3(0.0, 0.0, 3.0);
    let view = Mat4::look_at(eye, v3(0.0, 0.0, 0.0), v3(0.0, 1.0, 0.0)).ok_or("view")?;
    let projection = perspective(60, Fx16::from_ratio(1, 10), Fx16::from_int(100));
    let settings = FogSettings {
        color: fog,
        start: Fx16::from_int(4),
        end: Fx16::from_int(16),
        curve: FogCurve::Linear,
    };
    let mut words = vec![0u16; PIXELS];
    let mut fb =
        Framebuffer::<Rgb565>::new(&mut words, WIDTH, HEIGHT).map_err(|e| e.to_string())?;
    let Ok(()) = fb.clear(Rgb565::from(fog));
    let mut zbuf = vec![u16::MAX; PIXELS];
    let mesh = models.suzanne.mesh();
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    for (x, y, z, turn) in PLACES {
        let model =
            Mat4::rotation_y(Angle::from_degrees(turn)).then(&Mat4::translation(v3(x, y, z)));
        let t = Transforms {
            model,
            view,
            projection,
        };
        let mut lighting = Lighting::new(
            fixtures::scenes3d::material(),
            Rgb888::WHITE,
            Specular::BlinnPhong,
            eye,
        );
        lighting
            .add_light(Light::directional(v3(1.0, 1.0, 1.0)))
            .map_err(|_| "light")?;
        let shading = Fog::new(GouraudLit::<_, Rgb565, 1>::new(lighting), settings, &view);
        let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less)
            .map_err(|e| format!("depth buffer: {e:?}"))?;
        let viewport = Viewport::new(WIDTH, HEIGHT);
        let mut p = Pipeline::new(&t, viewport, CullClockwise, depth, shading);
        let stats = p
            .draw(&mut fb, &mesh, &mut scratch)
            .map_err(|e| e.to_string())?;
        check_drawn("fogged suzanne", stats.drawn)?;
    }
    let pixels = (0..HEIGHT as i32).flat_map(|y| (0..WIDTH as i32).map(move |x| Point::new(x, y)));
    let Ok(()) =
        display.draw_iter(pixels.filter_map(|p| fb.pixel(p).map(|c| Pixel(p, Rgb888::from(c)))));
    Ok(())
}

/// Suzanne lit per pixel with interpolated normals.
fn suzanne_phong(models: &Models, display: &mut Display) -> SceneResult {
    suzanne_filled(
        models,
        display,
        PhongLit::<_, Rgb565, 2>::new(lighting::<2>()),
    )
}

/// Triangles with their own vertices (no sharing), so each can have its own colours.
#[derive(Debug, Default)]
pub struct ColoredMesh {
    /// Positions.
    pub positions: Vec<Vec3<Fx16>>,
    /// One colour per position.
    pub colors: Vec<Rgb888>,
    /// Triangles.
    pub triangles: Vec<[u32; 3]>,
}

impl ColoredMesh {
    /// Adds the quad `a b c d` (counter-clockwise seen from its front) in one colour.
    fn quad(&mut self, corners: [Vec3<Fx16>; 4], color: Rgb888) {
        let base = self.positions.len() as u32;
        self.positions.extend(corners);
        self.colors.extend([color; 4]);
        self.triangles.push([base, base + 1, base + 2]);
        self.triangles.push([base, base + 2, base + 3]);
    }

    /// The pipeline's view of it.
    pub fn mesh(&self) -> Mesh<'_, Fx16, u32> {
        Mesh {
            positions: &self.positions,
            normals: None,
            colors: Some(&self.colors),
            uvs: None,
            triangles: &self.triangles,
            adjacency: None,
        }
    }
}

/// The unit cube (side 1, centred at the origin, faces counter-clockwise seen from outside, as
/// `assets/models/unit_cube.obj`), each face an `n` x `n` checkerboard in two tones of its own
/// colour: +X red, -X cyan, +Y white, -Y brown, +Z green, -Z blue.
pub fn checker_cube(n: u32) -> ColoredMesh {
    let colors = [
        (hsv(0.0, 0.75, 0.95), hsv(0.0, 0.75, 0.7)),
        (hsv(0.5, 0.7, 0.9), hsv(0.5, 0.7, 0.65)),
        (Rgb888::new(235, 235, 235), Rgb888::new(175, 175, 185)),
        (hsv(0.08, 0.6, 0.6), hsv(0.08, 0.6, 0.42)),
        (hsv(0.33, 0.7, 0.85), hsv(0.33, 0.7, 0.6)),
        (hsv(0.62, 0.7, 0.95), hsv(0.62, 0.7, 0.7)),
    ];
    let mut out = ColoredMesh::default();
    let step = 1.0 / f64::from(n);
    for (face, (light, dark)) in colors.into_iter().enumerate() {
        let axis = face / 2;
        let sign = if face % 2 == 0 { 1.0 } else { -1.0 };
        // Tangents with u x v = the outward normal, so (u, v)-counter-clockwise is outward-facing.
        let (u, v) = if sign > 0.0 {
            ((axis + 1) % 3, (axis + 2) % 3)
        } else {
            ((axis + 2) % 3, (axis + 1) % 3)
        };
        let point = |a: f64, b: f64| {
            let mut c = [0.0; 3];
            c[axis] = 0.5 * sign;
            c[u] = a - 0.5;
            c[v] = b - 0.5;
            v3(c[0], c[1], c[2])
        };
        for i in 0..n {
            for j in 0..n {
                let (a0, b0) = (f64::from(i) * step, f64::from(j) * step);
                let (a1, b1) = (a0 + step, b0 + step);
                let color = if (i + j) % 2 == 0 { light } else { dark };
                out.quad(
                    [point(a0, b0), point(a1, b0), point(a1, b1), point(a0, b1)],
                    color,
                );
            }
        }
    }
    out
}

/// The cube of [`cube_inside`] is scaled by this: its walls are 2 units from its centre.
const ROOM_SCALE: i32 = 4;
/// The near plane of [`cube_inside`]: large, so the cut is easy to see.
const ROOM_NEAR: f64 = 0.3;

/// The four camera positions of [`cube_inside`]: walking towards the red +X wall (at x = 2),
/// looking 40° to the right of -Z and slightly down. Each is `(eye, distance to the wall)`.
pub fn room_cameras() -> [([f64; 3], f64); 4] {
    [0.4, 1.3, 1.75, 1.92].map(|x| ([x, 0.4, 1.2], 2.0 - x))
}

/// The camera of [`cube_inside`] at `eye`.
fn room_view(eye: [f64; 3]) -> Mat4<Fx16> {
    let yaw = 40f64.to_radians();
    let pitch = -15f64.to_radians();
    let dir = [
        yaw.sin() * pitch.cos(),
        pitch.sin(),
        -yaw.cos() * pitch.cos(),
    ];
    let at = [eye[0] + dir[0], eye[1] + dir[1], eye[2] + dir[2]];
    Mat4::look_at(
        v3(eye[0], eye[1], eye[2]),
        v3(at[0], at[1], at[2]),
        Vec3::from_ints(0, 1, 0),
    )
    .expect("not looking straight up")
}

/// The viewport of frame `k` (0..4) of [`cube_inside`]: a 2x2 grid of 160x120 frames.
pub fn room_frame(k: usize) -> Viewport {
    let (w, h) = (WIDTH / 2, HEIGHT / 2);
    Viewport {
        x: (k % 2) as i32 * w as i32,
        y: (k / 2) as i32 * h as i32,
        width: w,
        height: h,
    }
}

/// Frame `k` of [`cube_inside`], drawn into its quarter of `display` (the pipeline clips to its
/// viewport), with its own region of the depth buffer (which covers the display).
pub fn draw_room_frame(
    room: &ColoredMesh,
    k: usize,
    display: &mut Display,
    zbuf: &mut [u16],
) -> SceneResult {
    let (eye, _) = room_cameras()[k];
    let s = Fx16::from_int(ROOM_SCALE);
    let xf = Transforms {
        model: Mat4::scale(s, s, s),
        view: room_view(eye),
        projection: perspective(70, fx(ROOM_NEAR), fx(20.0)),
    };
    let depth = DepthBuffer::new(zbuf, WIDTH, HEIGHT, Compare::Less)
        .map_err(|e| format!("depth buffer: {e:?}"))?;
    // Seen from inside, the outward-facing walls appear clockwise: cull the other way round.
    let frame = room_frame(k);
    let mut p = Pipeline::new(
        &xf,
        frame,
        CullCounterClockwise,
        depth,
        VertexColors::<Rgb888>::new(),
    );
    let mesh = room.mesh();
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let stats = p
        .draw(&mut AnyTarget::new(display), &mesh, &mut scratch)
        .map_err(|e| e.to_string())?;
    check_drawn("room", stats.drawn)
}

/// A camera walking up to a wall inside the (scaled-up) unit cube, in four frames. As the wall
/// comes nearer than the near plane, the part of it in front of the near plane is clipped away and
/// the background shows through.
fn cube_inside(_: &Models, display: &mut Display) -> SceneResult {
    let room = checker_cube(8);
    let mut zbuf = vec![u16::MAX; PIXELS];
    for k in 0..4 {
        draw_room_frame(&room, k, display, &mut zbuf)?;
    }
    let style = MonoTextStyle::new(&FONT_6X10, Rgb888::WHITE);
    for (k, (_, dist)) in room_cameras().into_iter().enumerate() {
        let f = room_frame(k);
        let label = format!("wall {dist:.2}, near {ROOM_NEAR:.1}");
        let text = Text::with_baseline(&label, Point::new(f.x + 3, f.y + 2), style, Baseline::Top);
        let Ok(_) = text.draw(display);
    }
    // One-pixel dividers between the frames, drawn over the frames' own pixels.
    let line = Rgb888::new(14, 16, 26);
    let Ok(()) = display.draw_iter(
        (0..HEIGHT as i32)
            .map(|y| Pixel(Point::new(WIDTH as i32 / 2, y), line))
            .chain((0..WIDTH as i32).map(|x| Pixel(Point::new(x, HEIGHT as i32 / 2), line))),
    );
    Ok(())
}

/// A checkerboard ground in the plane y = 0, facing up: `2 n + 1` x `2 n + 1` square cells of side
/// `size`, the middle one centred on the origin (so the origin is not on a grid line).
pub fn ground(n: i32, size: i32) -> ColoredMesh {
    let mut out = ColoredMesh::default();
    let (a, b) = (Rgb888::new(70, 110, 70), Rgb888::new(150, 170, 120));
    let half = f64::from(size) / 2.0;
    let p = |i: i32, j: i32| v3(f64::from(i * size) - half, 0.0, f64::from(j * size) - half);
    for i in -n..=n {
        for j in -n..=n {
            // Counter-clockwise seen from above (+y): +x, then -z.
            let corners = [p(i, j + 1), p(i + 1, j + 1), p(i + 1, j), p(i, j)];
            out.quad(corners, if (i + j) % 2 == 0 { a } else { b });
        }
    }
    out
}

/// The near plane of [`near_plane_crossing`].
const NEAR_PLANE: f64 = 0.4;

/// Where the camera of [`near_plane_crossing`] stands: low, in the middle of a ground cell.
const GROUND_EYE: [f64; 3] = [0.0, 0.55, 0.0];

/// The camera of [`near_plane_crossing`].
fn ground_view() -> Mat4<Fx16> {
    let [x, y, z] = GROUND_EYE;
    Mat4::look_at(v3(x, y, z), v3(0.0, 0.25, -4.0), Vec3::from_ints(0, 1, 0))
        .expect("not looking straight up")
}

/// A checkerboard ground of 2-unit cells that runs far behind the camera (the camera stands in the
/// middle of a cell, so the triangles around it cross the near plane and the plane w = 0), a Suzanne whose face pokes through the
/// near plane (cut open: her inside is drawn in a dark flat colour) and a Phong-lit Suzanne sunk
/// into the ground.
fn near_plane_crossing(models: &Models, display: &mut Display) -> SceneResult {
    let projection = perspective(60, fx(NEAR_PLANE), fx(40.0));
    let mut zbuf = vec![u16::MAX; PIXELS];
    let viewport = Viewport::new(WIDTH, HEIGHT);
    let floor = ground(12, 2);
    let mut target = AnyTarget::new(display);
    {
        let xf = Transforms {
            model: Mat4::identity(),
            view: ground_view(),
            projection,
        };
        let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less)
            .map_err(|e| format!("depth buffer: {e:?}"))?;
        let mut p = Pipeline::new(
            &xf,
            viewport,
            CullClockwise,
            depth,
            VertexColors::<Rgb888>::new(),
        );
        let mesh = floor.mesh();
        let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
        let stats = p
            .draw(&mut target, &mesh, &mut scratch)
            .map_err(|e| e.to_string())?;
        check_drawn("ground", stats.drawn)?;
        if stats.clipped == 0 {
            return Err("the ground should cross the near plane".into());
        }
    }
    let suzanne = models.suzanne.mesh();
    let mut lighting = lighting::<2>();
    let [x, y, z] = GROUND_EYE;
    lighting.set_eye(v3(x, y, z));
    // Near: close to the camera, turned towards it, her nose through the near plane.
    let near_model = Mat4::scale(fx(0.3), fx(0.3), fx(0.3))
        .then(&Mat4::rotation_y(Angle::from_degrees(25)))
        .then(&Mat4::translation(v3(-0.28, 0.45, -0.62)));
    // Far: life size, sunk into the ground up to her chin.
    let far_model =
        Mat4::rotation_y(Angle::from_degrees(-25)).then(&Mat4::translation(v3(1.3, 0.3, -4.5)));
    for (model, lit) in [(near_model, false), (far_model, true)] {
        let xf = Transforms {
            model,
            view: ground_view(),
            projection,
        };
        let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less)
            .map_err(|e| format!("depth buffer: {e:?}"))?;
        if lit {
            let mut p = Pipeline::new(
                &xf,
                viewport,
                CullClockwise,
                depth,
                PhongLit::<_, Rgb888, 2>::new(lighting.clone()),
            );
            let stats = p
                .draw(
                    &mut target,
                    &suzanne,
                    &mut vec![VertexSlot::EMPTY; suzanne.positions.len()],
                )
                .map_err(|e| e.to_string())?;
            check_drawn("far suzanne", stats.drawn)?;
            continue;
        }
        // Outside: Gouraud-lit front faces.
        let mut p = Pipeline::new(
            &xf,
            viewport,
            CullClockwise,
            depth,
            GouraudLit::<_, Rgb888, 2>::new(lighting.clone()),
        );
        let stats = p
            .draw(
                &mut target,
                &suzanne,
                &mut vec![VertexSlot::EMPTY; suzanne.positions.len()],
            )
            .map_err(|e| e.to_string())?;
        check_drawn("near suzanne", stats.drawn)?;
        if stats.clipped == 0 {
            return Err("the near Suzanne should cross the near plane".into());
        }
        // Inside: the back faces, flat dark red, visible only where the near plane cut her open.
        let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less)
            .map_err(|e| format!("depth buffer: {e:?}"))?;
        let mut p = Pipeline::new(
            &xf,
            viewport,
            CullCounterClockwise,
            depth,
            Unlit {
                color: Rgb888::new(90, 20, 30),
            },
        );
        let stats = p
            .draw(
                &mut target,
                &suzanne,
                &mut vec![VertexSlot::EMPTY; suzanne.positions.len()],
            )
            .map_err(|e| e.to_string())?;
        check_drawn("inside of near suzanne", stats.drawn)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The models of the repository.
    fn models() -> Models {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models");
        Models::load(&dir).unwrap()
    }

    #[test]
    fn every_3d_scene_renders() {
        let models = models();
        for scene in &SCENES {
            render(scene, &models).unwrap_or_else(|e| panic!("{}: {e}", scene.file));
        }
    }

    /// Each frame of the cube strip stays inside its own viewport, even where the near plane cuts.
    #[test]
    fn room_frames_stay_in_their_viewports() {
        let room = checker_cube(8);
        for k in 0..4 {
            let mut display = Display::new(Size::new(WIDTH, HEIGHT));
            let Ok(()) = display.clear(BACKGROUND);
            let mut zbuf = vec![u16::MAX; PIXELS];
            draw_room_frame(&room, k, &mut display, &mut zbuf).unwrap();
            let f = room_frame(k);
            let mut inside_background = 0;
            for y in 0..HEIGHT as i32 {
                for x in 0..WIDTH as i32 {
                    let c = display.get_pixel(Point::new(x, y));
                    let inside = (f.x..f.x + f.width as i32).contains(&x)
                        && (f.y..f.y + f.height as i32).contains(&y);
                    if !inside {
                        assert_eq!(
                            c, BACKGROUND,
                            "frame {k} drew ({x}, {y}) outside its viewport"
                        );
                    } else if c == BACKGROUND {
                        inside_background += 1;
                    }
                }
            }
            // Far from the wall the room fills the frame; at the wall the cut shows background.
            if k == 0 {
                assert_eq!(inside_background, 0, "frame 0 has holes");
            }
            if k == 3 {
                assert!(inside_background > 0, "frame 3 shows no near-plane cut");
            }
        }
    }
}
