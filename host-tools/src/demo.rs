//! The `demo` command: renders example pictures with `rasterizer-core` and saves them as PNG files.
//!
//! Every 2D picture is drawn onto an `embedded_graphics_simulator::SimulatorDisplay<Rgb888>` through
//! [`AnyTarget`], the adapter that lets the rasterizer drive any embedded-graphics `DrawTarget`. The
//! 3D pictures come from [`crate::demo3d`].

use crate::demo3d;
use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::text::{Alignment, Text};
use embedded_graphics::Drawable;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use host_tools::console::StdoutError;
use host_tools::output::write_png;
use rasterizer_core::prelude::*;
use rasterizer_core::surface::ClipTo;
use std::f64::consts::TAU;
use std::fmt;
use std::path::{Path, PathBuf};

/// Width of every demo picture, in display pixels.
pub const WIDTH: u32 = 200;
/// Height of every demo picture, in display pixels.
pub const HEIGHT: u32 = 150;
/// How many PNG pixels one display pixel becomes.
pub const SCALE: u32 = 3;

/// The display type every scene draws on.
pub type Display = SimulatorDisplay<Rgb888>;

/// The background colour: a dark blue-grey.
pub(crate) const BACKGROUND: Rgb888 = Rgb888::new(14, 16, 26);

/// Why the demo failed.
#[derive(Debug)]
pub enum DemoError {
    /// The output directory could not be created.
    CreateDir {
        /// The directory.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// A PNG file could not be written.
    Save {
        /// The file.
        path: PathBuf,
        /// What the encoder or the operating system said.
        message: String,
    },
    /// A model of the 3D pictures could not be loaded.
    Model {
        /// The model file.
        path: PathBuf,
        /// What the loader said.
        message: String,
    },
    /// Standard output could not be written.
    Stdout(host_tools::console::StdoutError),
    /// A scene was rejected by the rasterizer (a bug in the scene).
    Scene {
        /// The scene's file name.
        name: &'static str,
        /// What the rasterizer said.
        message: String,
    },
}

impl fmt::Display for DemoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::CreateDir { path, source } => {
                write!(
                    f,
                    "cannot create output directory {}: {source}",
                    path.display()
                )
            }
            Self::Save { path, message } => write!(f, "cannot write {}: {message}", path.display()),
            Self::Stdout(e) => e.fmt(f),
            Self::Model { path, message } => {
                write!(f, "cannot load model {}: {message}", path.display())
            }
            Self::Scene { name, message } => write!(f, "scene {name} failed: {message}"),
        }
    }
}

impl std::error::Error for DemoError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::CreateDir { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// A scene failure, before it is tied to a scene name.
pub(crate) type SceneResult = Result<(), String>;

/// One demo picture: its file name and the function that draws it.
pub struct Scene {
    /// The PNG file name, stable across versions (README.md links to it).
    pub file: &'static str,
    /// Draws the picture onto a cleared display.
    draw: fn(&mut Display) -> SceneResult,
}

/// Every demo picture, in the order they are written.
pub const SCENES: [Scene; 8] = [
    Scene {
        file: "lines_octants.png",
        draw: lines_octants,
    },
    Scene {
        file: "lines_gradient.png",
        draw: lines_gradient,
    },
    Scene {
        file: "triangle_outlines.png",
        draw: triangle_outlines,
    },
    Scene {
        file: "triangles_flat.png",
        draw: triangles_flat,
    },
    Scene {
        file: "triangles_gouraud.png",
        draw: triangles_gouraud,
    },
    Scene {
        file: "polygons.png",
        draw: polygons,
    },
    Scene {
        file: "clipping.png",
        draw: clipping,
    },
    Scene {
        file: "sprites.png",
        draw: sprites,
    },
];

/// Every file the demo writes, in the order it writes them: the 2D pictures, then the 3D ones.
pub fn files() -> impl Iterator<Item = &'static str> {
    SCENES
        .iter()
        .map(|s| s.file)
        .chain(demo3d::SCENES.iter().map(|s| s.file))
}

/// The `demo` command's long help, listing [`files`] so that the help cannot leave one out.
pub fn long_help() -> String {
    let list = |files: &mut dyn Iterator<Item = &'static str>| files.collect::<Vec<_>>().join(", ");
    format!(
        "Render the demo pictures as PNG files.\n\n\
         The 2D pictures are drawn by rasterizer-core through `AnyTarget` onto an \
         embedded-graphics-simulator display ({WIDTH}x{HEIGHT} pixels) and saved at {SCALE}x \
         scale, so single pixels are easy to see: {}.\n\n\
         The 3D pictures are rendered by the 3D pipeline at {}x{} and saved at {}x scale: {}. \
         Their mesh (suzanne.obj) is read from --models.\n\n\
         The file names are fixed. The set is written all or nothing: every picture is rendered \
         into a temporary directory next to --out first and only then moved into place, so on \
         any failure the files already in --out stay as they were and nothing partial is left. \
         A progress bar is shown on stderr when it is a terminal.\n\n\
         Example: cargo run --release -p host-tools -- demo --out /tmp/pictures",
        list(&mut SCENES.iter().map(|s| s.file)),
        demo3d::WIDTH,
        demo3d::HEIGHT,
        demo3d::SCALE,
        list(&mut demo3d::SCENES.iter().map(|s| s.file)),
    )
}

/// The directory of the models when `--models` is not given: `assets/models` under the current
/// directory, else in the repository the binary was built from while it is still there, else
/// under the nearest ancestor of the executable's directory that has one (a binary cargo built
/// lies in `target/<profile>/` of the repository).
pub fn default_models() -> Option<PathBuf> {
    let rel = Path::new("assets").join("models");
    if rel.is_dir() {
        return Some(rel);
    }
    let built = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(&rel);
    if built.is_dir() {
        return Some(built);
    }
    let exe = std::env::current_exe().ok()?;
    exe.ancestors()
        .skip(1)
        .map(|dir| dir.join(&rel))
        .find(|dir| dir.is_dir())
}

/// Renders every scene into `out` (created if missing), the 2D ones first, calling `on_written`
/// after each file is in place. The 3D scenes load their meshes from `models` (the repository's
/// `assets/models`).
///
/// All or nothing: the pictures are rendered into a temporary directory beside `out` (on the same
/// file system, so moving them is a rename), and moved into `out` only when every one of them is
/// written; a file that fails to move puts the ones moved before it back. The temporary
/// directory is removed whatever happens.
///
/// # Errors
/// [`DemoError::CreateDir`] when `out` or the temporary directory cannot be created,
/// [`DemoError::Model`] when a mesh cannot be loaded, [`DemoError::Save`] when a file cannot be
/// written or moved into place, [`DemoError::Scene`] when the rasterizer rejects a scene's input.
pub fn run(
    out: &Path,
    models: &Path,
    mut on_written: impl FnMut(&Path) -> Result<(), StdoutError>,
) -> Result<(), DemoError> {
    let create = |path: &Path| {
        std::fs::create_dir_all(path).map_err(|source| DemoError::CreateDir {
            path: path.to_path_buf(),
            source,
        })
    };
    create(out)?;
    let name = out
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let staging = out.with_file_name(format!(".{name}.demo-{}", std::process::id()));
    create(&staging)?;
    let rendered = {
        let progress = host_tools::progress::Progress::new(true);
        progress.stage("demo", (SCENES.len() + demo3d::SCENES.len()) as u64);
        render_all(&staging, models, &progress).and_then(|()| install(&staging, out))
    };
    let _ = std::fs::remove_dir_all(&staging);
    for file in rendered? {
        on_written(&file).map_err(DemoError::Stdout)?;
    }
    Ok(())
}

/// Renders every picture into `dir`, one step of `progress` each.
fn render_all(
    dir: &Path,
    models: &Path,
    progress: &host_tools::progress::Progress,
) -> Result<(), DemoError> {
    let models = demo3d::Models::load(models)
        .map_err(|(path, message)| DemoError::Model { path, message })?;
    let save = |display: &Display, file: &str, scale: u32| {
        let settings = OutputSettingsBuilder::new().scale(scale).build();
        let path = dir.join(file);
        let image = display.to_rgb_output_image(&settings);
        let buf = image.as_image_buffer();
        write_png(&path, &[], buf.width(), buf.height(), &buf).map_err(|e| DemoError::Save {
            path: path.clone(),
            message: e.message,
        })
    };
    for scene in &SCENES {
        save(&render(scene)?, scene.file, SCALE)?;
        progress.inc();
    }
    for scene in &demo3d::SCENES {
        let display = demo3d::render(scene, &models).map_err(|message| DemoError::Scene {
            name: scene.file,
            message,
        })?;
        save(&display, scene.file, demo3d::SCALE)?;
        progress.inc();
    }
    Ok(())
}

/// Moves every picture from `staging` into `out`, keeping the files it replaces in
/// `staging/replaced` until all are in, so that a failure can put them back. Returns the paths
/// written.
fn install(staging: &Path, out: &Path) -> Result<Vec<PathBuf>, DemoError> {
    let save_error = |path: &Path, message: String| DemoError::Save {
        path: path.to_path_buf(),
        message,
    };
    // Only files are replaced: a directory (or anything else) in the way is an error before
    // anything moves.
    for file in files() {
        let dest = out.join(file);
        if let Ok(meta) = std::fs::symlink_metadata(&dest) {
            if !meta.is_file() {
                return Err(save_error(&dest, "it exists and is not a file".into()));
            }
        }
    }
    let replaced = staging.join("replaced");
    std::fs::create_dir(&replaced).map_err(|e| save_error(&replaced, e.to_string()))?;
    // (file, whether an old one was kept) for each file moved so far.
    let mut moved: Vec<(&str, bool)> = Vec::new();
    let mut result = Ok(());
    for file in files() {
        let dest = out.join(file);
        let kept = dest.exists();
        if kept {
            if let Err(e) = std::fs::rename(&dest, replaced.join(file)) {
                result = Err(save_error(
                    &dest,
                    format!("cannot move the old file aside: {e}"),
                ));
                break;
            }
        }
        if let Err(e) = std::fs::rename(staging.join(file), &dest) {
            if kept {
                let _ = std::fs::rename(replaced.join(file), &dest);
            }
            result = Err(save_error(&dest, e.to_string()));
            break;
        }
        moved.push((file, kept));
    }
    if let Err(e) = result {
        // Back as it was: the new files out, the old ones in.
        for (file, kept) in moved.into_iter().rev() {
            let dest = out.join(file);
            let _ = std::fs::remove_file(&dest);
            if kept {
                let _ = std::fs::rename(replaced.join(file), &dest);
            }
        }
        return Err(e);
    }
    Ok(files().map(|f| out.join(f)).collect())
}

/// Draws one scene onto a fresh display with the dark background.
///
/// # Errors
/// [`DemoError::Scene`] when the rasterizer rejects the scene's input.
pub fn render(scene: &Scene) -> Result<Display, DemoError> {
    let mut display = Display::new(Size::new(WIDTH, HEIGHT));
    let Ok(()) = display.clear(BACKGROUND);
    (scene.draw)(&mut display).map_err(|message| DemoError::Scene {
        name: scene.file,
        message,
    })?;
    Ok(display)
}

/// A colour from hue (turns, 0..1), saturation and value (0..1).
pub(crate) fn hsv(hue: f64, sat: f64, val: f64) -> Rgb888 {
    let h = hue.rem_euclid(1.0) * 6.0;
    let sector = h.floor();
    let f = h - sector;
    let (p, q, t) = (
        val * (1.0 - sat),
        val * (1.0 - sat * f),
        val * (1.0 - sat * (1.0 - f)),
    );
    let (r, g, b) = match sector as u32 {
        0 => (val, t, p),
        1 => (q, val, p),
        2 => (p, val, t),
        3 => (p, q, val),
        4 => (t, p, val),
        _ => (val, p, q),
    };
    let byte = |c: f64| (c * 255.0).round().clamp(0.0, 255.0) as u8;
    Rgb888::new(byte(r), byte(g), byte(b))
}

/// Scales a colour's brightness by `num / 256`.
fn dim(c: Rgb888, num: u32) -> Rgb888 {
    let s = |v: u8| (u32::from(v) * num / 256) as u8;
    Rgb888::new(s(c.r()), s(c.g()), s(c.b()))
}

/// A point at distance `r` and angle `turns` (a full circle is 1) from `c`, rounded to whole pixels.
fn polar(c: Point, r: f64, turns: f64) -> Point {
    let a = turns * TAU;
    c + Point::new((r * a.cos()).round() as i32, (r * a.sin()).round() as i32)
}

/// A sub-pixel vertex (28.4 fixed point) from pixel coordinates, rounded to 1/16 pixel.
fn sub(x: f64, y: f64) -> SubPoint {
    let one = f64::from(SubPoint::<4>::ONE);
    SubPoint::new((x * one).round() as i32, (y * one).round() as i32)
}

/// A small deterministic pseudo-random generator (xorshift64*), so the pictures never change.
struct Rng(u64);

impl Rng {
    /// The next 64 random bits.
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A uniform value in `[0, 1)`.
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A uniform value in `[lo, hi)`.
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// 32 spokes from the centre, covering all eight octants, alternately long and short.
fn lines_octants(display: &mut Display) -> SceneResult {
    let mut t = AnyTarget::new(display);
    let centre = Point::new(100, 75);
    let n = 32u32;
    for i in 0..n {
        let turns = f64::from(i) / f64::from(n);
        let r = if i.is_multiple_of(2) { 70.0 } else { 54.0 };
        let Ok(()) = draw_line(
            &mut t,
            centre,
            polar(centre, r, turns),
            hsv(turns, 0.7, 1.0),
        );
    }
    let Ok(()) = draw_point(&mut t, centre, Rgb888::WHITE);
    Ok(())
}

/// A fan of colour-interpolated lines (warm at the hub, cool at the tips) under horizontal ramps.
fn lines_gradient(display: &mut Display) -> SceneResult {
    let mut t = AnyTarget::new(display);
    let hub = Point::new(100, 144);
    let n = 31;
    for i in 0..n {
        let f = f64::from(i) / f64::from(n - 1);
        let tip = polar(hub, 118.0, 0.6 + 0.3 * f);
        let warm = hsv(0.0 + 0.12 * f, 0.85, 1.0);
        let cool = hsv(0.66 - 0.16 * f, 0.8, 1.0);
        let Ok(()) = draw_line_gradient(&mut t, hub, tip, warm, cool);
    }
    let ramps = [
        (Rgb888::new(255, 40, 40), Rgb888::new(40, 80, 255)),
        (Rgb888::BLACK, Rgb888::WHITE),
    ];
    for (k, (a, b)) in ramps.into_iter().enumerate() {
        for dy in 0..3 {
            let y = 4 + 5 * k as i32 + dy;
            let Ok(()) = draw_line_gradient(&mut t, Point::new(8, y), Point::new(191, y), a, b);
        }
    }
    Ok(())
}

/// Triangle outlines: large, right-angled, small, tiny, thin slivers and a collinear one.
fn triangle_outlines(display: &mut Display) -> SceneResult {
    let mut t = AnyTarget::new(display);
    let p = Point::new;
    let outlines = [
        ([p(8, 140), p(50, 12), p(92, 120)], hsv(0.08, 0.8, 1.0)),
        ([p(38, 92), p(62, 98), p(47, 114)], hsv(0.92, 0.6, 1.0)),
        ([p(48, 58), p(53, 58), p(50, 62)], Rgb888::WHITE),
        ([p(108, 8), p(192, 8), p(192, 62)], hsv(0.5, 0.8, 1.0)),
        ([p(104, 72), p(195, 84), p(104, 77)], hsv(0.33, 0.7, 1.0)),
        ([p(108, 144), p(194, 94), p(115, 144)], hsv(0.15, 0.8, 1.0)),
        ([p(140, 146), p(165, 134), p(190, 122)], hsv(0.75, 0.6, 1.0)),
        ([p(110, 28), p(136, 34), p(116, 58)], hsv(0.58, 0.5, 1.0)),
    ];
    for (vertices, color) in outlines {
        let Ok(()) = draw_triangle(&mut t, vertices, color);
    }
    Ok(())
}

/// The pixel rectangle the flat-triangle mesh covers exactly: `x0..x1`, `y0..y1`.
pub const MESH_AREA: (i32, i32, i32, i32) = (102, 14, 194, 136);

/// A 5x6 grid mesh over [`MESH_AREA`]: boundary vertices on whole pixels, interior vertices moved
/// by pseudo-random sub-pixel amounts, every cell split into two triangles sharing the diagonal.
pub fn mesh_triangles() -> Vec<([SubPoint; 3], Rgb888)> {
    let (x0, y0, x1, y1) = MESH_AREA;
    let (cols, rows) = (5usize, 6usize);
    let mut rng = Rng(0x005E_ED0F_F1A7);
    let mut grid = vec![vec![(0.0, 0.0); cols + 1]; rows + 1];
    for (r, row) in grid.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            let x = f64::from(x0) + f64::from(x1 - x0) * c as f64 / cols as f64;
            let y = f64::from(y0) + f64::from(y1 - y0) * r as f64 / rows as f64;
            let inner = c > 0 && c < cols && r > 0 && r < rows;
            *v = if inner {
                (x + rng.range(-6.0, 6.0), y + rng.range(-6.0, 6.0))
            } else {
                (x, y)
            };
        }
    }
    let v = |r: usize, c: usize| sub(grid[r][c].0, grid[r][c].1);
    let mut out = Vec::new();
    for r in 0..rows {
        for c in 0..cols {
            let hue = (r * cols + c) as f64 / (rows * cols) as f64;
            let (a, b) = (hsv(hue, 0.65, 0.95), hsv(hue + 0.04, 0.75, 0.65));
            let (tl, tr, bl, br) = (v(r, c), v(r, c + 1), v(r + 1, c), v(r + 1, c + 1));
            if (r + c).is_multiple_of(2) {
                out.push(([tl, tr, br], a));
                out.push(([tl, br, bl], b));
            } else {
                out.push(([tl, tr, bl], a));
                out.push(([tr, br, bl], b));
            }
        }
    }
    out
}

/// Flat-filled triangles: a pinwheel around a sub-pixel centre and a jittered mesh.
fn triangles_flat(display: &mut Display) -> SceneResult {
    let mut t = AnyTarget::new(display);
    // Pinwheel: 14 triangles sharing a centre at a sub-pixel position, with sub-pixel rim vertices.
    let (cx, cy) = (50.3125, 75.6875);
    let n = 14;
    let rim = |i: u32| {
        let a = f64::from(i % n) / f64::from(n) * TAU;
        let r = if i.is_multiple_of(2) { 44.0 } else { 34.0 };
        sub(cx + r * a.cos(), cy + r * a.sin())
    };
    for i in 0..n {
        let color = hsv(
            f64::from(i) / f64::from(n),
            0.7,
            if i.is_multiple_of(2) { 1.0 } else { 0.7 },
        );
        let Ok(()) = fill_triangle(&mut t, [sub(cx, cy), rim(i), rim(i + 1)], color);
    }
    for (vertices, color) in mesh_triangles() {
        let Ok(()) = fill_triangle(&mut t, vertices, color);
    }
    Ok(())
}

/// Gouraud-shaded triangles: an RGB triangle, a CMY one with a white corner, and a strip.
fn triangles_gouraud(display: &mut Display) -> SceneResult {
    let mut t = AnyTarget::new(display);
    let rgb = [Rgb888::RED, Rgb888::GREEN, Rgb888::BLUE];
    let Ok(()) = fill_triangle_gouraud(
        &mut t,
        [sub(10.0, 72.0), sub(52.5, 4.25), sub(95.0, 72.0)],
        rgb,
    );
    let cmy = [Rgb888::CYAN, Rgb888::MAGENTA, Rgb888::YELLOW];
    let Ok(()) = fill_triangle_gouraud(
        &mut t,
        [sub(105.0, 4.0), sub(190.0, 4.0), sub(147.5, 72.0)],
        cmy,
    );
    // A strip of 15 triangles over a zigzag of vertices. Each vertex has one colour, so the shading
    // runs on across every shared edge.
    let top = |i: u32| {
        let x = 8.0 + 23.0 * f64::from(i);
        (sub(x, 84.0), hsv(f64::from(i) / 8.0, 0.85, 1.0))
    };
    let bottom = |i: u32| {
        let x = 19.5 + 23.0 * f64::from(i);
        (sub(x, 143.5), hsv((f64::from(i) + 0.5) / 8.0, 0.9, 0.6))
    };
    for i in 0..8 {
        let ((a, ca), (b, cb)) = (top(i), top(i + 1));
        let (c, cc) = bottom(i);
        let Ok(()) = fill_triangle_gouraud(&mut t, [a, b, c], [ca, cb, cc]);
        if i < 7 {
            let (d, cd) = bottom(i + 1);
            let Ok(()) = fill_triangle_gouraud(&mut t, [b, d, c], [cb, cd, cc]);
        }
    }
    Ok(())
}

/// Fills `points` as one polygon.
fn fill_polygon(
    t: &mut AnyTarget<'_, Display>,
    points: &[SubPoint],
    rule: FillRule,
    color: Rgb888,
) -> SceneResult {
    let polygon = Polygon::<16, 4>::new(points).map_err(|e| e.to_string())?;
    let Ok(()) = polygon.fill(t, rule, color);
    Ok(())
}

/// A star polygon `{n/k}`: `n` points on a circle, joined every `k`-th, as one self-intersecting path.
fn star(cx: f64, cy: f64, r: f64, n: u32, k: u32) -> Vec<SubPoint> {
    (0..n)
        .map(|i| {
            let a = (f64::from(i * k % n) / f64::from(n) - 0.25) * TAU;
            sub(cx + r * a.cos(), cy + r * a.sin())
        })
        .collect()
}

/// Polygons: two concave shapes, and two self-intersecting stars under each fill rule.
fn polygons(display: &mut Display) -> SceneResult {
    let mut t = AnyTarget::new(display);
    let shift = |pts: &[(f64, f64)], dx: f64, dy: f64| -> Vec<SubPoint> {
        pts.iter().map(|&(x, y)| sub(x + dx, y + dy)).collect()
    };
    let arrow = [
        (-28.0, -9.0),
        (3.0, -9.0),
        (3.0, -24.0),
        (30.0, 0.0),
        (3.0, 24.0),
        (3.0, 9.0),
        (-28.0, 9.0),
        (-17.5, 0.0),
    ];
    fill_polygon(
        &mut t,
        &shift(&arrow, 33.0, 40.0),
        FillRule::EvenOdd,
        hsv(0.08, 0.8, 1.0),
    )?;
    let comb = [
        (-28.0, -26.0),
        (28.0, -26.0),
        (28.0, 26.0),
        (16.5, 26.0),
        (16.5, -10.0),
        (5.5, -10.0),
        (5.5, 26.0),
        (-5.5, 26.0),
        (-5.5, -10.0),
        (-16.5, -10.0),
        (-16.5, 26.0),
        (-28.0, 26.0),
    ];
    fill_polygon(
        &mut t,
        &shift(&comb, 33.0, 108.0),
        FillRule::NonZero,
        hsv(0.33, 0.6, 0.9),
    )?;
    for (cx, rule, hue) in [
        (100.0, FillRule::EvenOdd, 0.55),
        (166.0, FillRule::NonZero, 0.85),
    ] {
        fill_polygon(
            &mut t,
            &star(cx, 41.0, 31.0, 5, 2),
            rule,
            hsv(hue, 0.7, 1.0),
        )?;
        fill_polygon(
            &mut t,
            &star(cx, 109.0, 29.0, 7, 3),
            rule,
            hsv(hue + 0.1, 0.6, 0.95),
        )?;
    }
    let style = MonoTextStyle::new(&FONT_6X10, Rgb888::new(200, 204, 220));
    for (x, label) in [(33, "concave"), (100, "EvenOdd"), (166, "NonZero")] {
        let text = Text::with_alignment(label, Point::new(x, 147), style, Alignment::Center);
        let Ok(_) = text.draw(t.inner());
    }
    Ok(())
}

/// Sprites: workload I1's image (8-bit alpha) turned and scaled, nearest and bilinear; a mosaic of
/// opaque tiles sharing their edges under one turn; and a ring of small blended sprites.
///
/// Drawn into an Rgb565 framebuffer (blending reads the pixels back, which the simulator's
/// display cannot through `AnyTarget`), then copied onto the display where it changed.
fn sprites(display: &mut Display) -> SceneResult {
    use rasterizer_core::raster::sprite::{draw_sprite, Affine, Sprite};
    use rasterizer_core::texture::Filter;
    let sprite = Sprite::from_bytes(fixtures::sprite::I1_IMAGE).map_err(|e| e.to_string())?;
    let background = Rgb565::from(BACKGROUND);
    let mut buf = vec![0u16; (WIDTH * HEIGHT) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).map_err(|e| e.to_string())?;
    let Ok(()) = fb.clear(background);
    let fx = |v: f64| Fx16::from_bits((v * 65536.0).round() as i32);
    let place = |cx: f64, cy: f64, deg: f64, scale: f64| {
        let (sin, cos) = deg.to_radians().sin_cos();
        let m = [[cos * scale, -sin * scale], [sin * scale, cos * scale]];
        Affine {
            m: m.map(|r| r.map(fx)),
            t: [
                cx - (m[0][0] + m[0][1]) * 16.0,
                cy - (m[1][0] + m[1][1]) * 16.0,
            ]
            .map(fx),
        }
    };
    let draw = |fb: &mut Framebuffer<Rgb565>, s: &Sprite, a: &Affine, f: Filter| {
        draw_sprite(fb, s, a, f).map_err(|e| format!("{e:?}"))
    };
    draw(
        &mut fb,
        &sprite,
        &place(36.0, 44.0, 25.0, 1.9),
        Filter::Nearest,
    )?;
    draw(
        &mut fb,
        &sprite,
        &place(100.0, 44.0, 25.0, 1.9),
        Filter::Bilinear,
    )?;
    // Nine opaque tiles of the image, one turn: tile (i, j) moved by m (32 i, 32 j), exact in
    // 16.16, so that neighbours share their edges.
    let tile = sprite.without_alpha();
    let grid = place(166.0, 40.0, -20.0, 0.42);
    for j in -1..2 {
        for i in -1..2 {
            let mut a = grid;
            for k in 0..2 {
                let m = |c: usize| i64::from(a.m[k][c].to_bits());
                let t = i64::from(grid.t[k].to_bits()) + m(0) * 32 * i + m(1) * 32 * j;
                a.t[k] = Fx16::from_bits(t as i32);
            }
            draw(&mut fb, &tile, &a, Filter::Nearest)?;
        }
    }
    // A ring of small sprites, each turned to face the centre.
    for k in 0..12 {
        let turn = f64::from(k) / 12.0;
        let (cx, cy) = (
            100.0 + 34.0 * (turn * TAU).cos(),
            112.0 + 22.0 * (turn * TAU).sin(),
        );
        draw(
            &mut fb,
            &sprite,
            &place(cx, cy, turn * 360.0, 0.3 + 0.25 * turn),
            Filter::Nearest,
        )?;
    }
    let changed = fb.bounding_box().points().filter_map(|p| {
        let c = fb.pixel(p)?;
        (c != background).then(|| Pixel(p, Rgb888::from(c)))
    });
    let Ok(()) = display.draw_iter(changed);
    let style = MonoTextStyle::new(&FONT_6X10, Rgb888::new(200, 204, 220));
    for (x, label) in [(36, "nearest"), (100, "bilinear"), (166, "tiles")] {
        let text = Text::with_alignment(label, Point::new(x, 84), style, Alignment::Center);
        let Ok(_) = text.draw(display);
    }
    Ok(())
}

/// Brightness of the unclipped lines under the clipped ones, in 256ths.
const DIM: u32 = 80;

/// The viewport of the clipping scene.
pub const CLIP_VIEWPORT: Rectangle = Rectangle::new(Point::new(45, 30), Size::new(110, 90));

/// The lines of the clipping scene: endpoints far outside the display, some extremely far.
pub fn clipping_lines() -> Vec<(Point, Point, Rgb888)> {
    let mut rng = Rng(0xC11F_2024);
    let mut out = Vec::new();
    for i in 0..36u32 {
        // A line through a random point of the display, in a random direction, with both ends
        // hundreds of pixels off screen (every sixth one, tens of thousands).
        let (px, py) = (rng.range(10.0, 190.0), rng.range(10.0, 140.0));
        let turns = rng.unit();
        let (dx, dy) = ((turns * TAU).cos(), (turns * TAU).sin());
        let far = if i.is_multiple_of(6) { 40_000.0 } else { 300.0 };
        let (r0, r1) = (far + rng.range(0.0, 300.0), far + rng.range(0.0, 300.0));
        let end = |r: f64| Point::new((px + r * dx).round() as i32, (py + r * dy).round() as i32);
        out.push((end(r0), end(-r1), hsv(f64::from(i) / 36.0, 0.7, 1.0)));
    }
    // Extreme coordinates: the clipper must stay exact far from the screen.
    out.push((
        Point::new(-1_000_000, -740_000),
        Point::new(1_000_000, 760_000),
        Rgb888::new(255, 230, 120),
    ));
    out.push((
        Point::new(i32::MIN, 90),
        Point::new(i32::MAX, 100),
        Rgb888::new(255, 230, 120),
    ));
    out
}

/// Clipping: the full lines dimmed, the same lines bright but clipped to a viewport, and its outline.
fn clipping(display: &mut Display) -> SceneResult {
    let lines = clipping_lines();
    {
        let mut t = AnyTarget::new(&mut *display);
        for &(a, b, color) in &lines {
            let Ok(()) = draw_line(&mut t, a, b, dim(color, DIM));
        }
    }
    {
        // rasterizer-core's ClipTo narrows the display's clip area to the viewport.
        let mut any = AnyTarget::new(&mut *display);
        let mut v = ClipTo::new(&mut any, CLIP_VIEWPORT);
        for &(a, b, color) in &lines {
            let Ok(()) = draw_line(&mut v, a, b, color);
        }
    }
    // The outline lies one pixel outside the viewport, so it never hides a clipped pixel.
    let mut t = AnyTarget::new(display);
    let r = CLIP_VIEWPORT;
    let (x0, y0) = (r.top_left.x - 1, r.top_left.y - 1);
    let (x1, y1) = (
        r.top_left.x + r.size.width as i32,
        r.top_left.y + r.size.height as i32,
    );
    let frame = Rgb888::new(235, 235, 245);
    let corners = [
        Point::new(x0, y0),
        Point::new(x1, y0),
        Point::new(x1, y1),
        Point::new(x0, y1),
    ];
    for i in 0..4 {
        let Ok(()) = draw_line(&mut t, corners[i], corners[(i + 1) % 4], frame);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics_core::geometry::OriginDimensions;
    use embedded_graphics_core::primitives::PointsIter;
    use embedded_graphics_core::Pixel;
    use std::convert::Infallible;

    /// Counts how often each pixel is written.
    struct Counter {
        counts: Vec<u32>,
    }

    impl OriginDimensions for Counter {
        fn size(&self) -> Size {
            Size::new(WIDTH, HEIGHT)
        }
    }

    impl DrawTarget for Counter {
        type Color = Rgb888;
        type Error = Infallible;
        fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(
            &mut self,
            pixels: I,
        ) -> Result<(), Infallible> {
            for Pixel(p, _) in pixels {
                if (0..WIDTH as i32).contains(&p.x) && (0..HEIGHT as i32).contains(&p.y) {
                    self.counts[(p.y * WIDTH as i32 + p.x) as usize] += 1;
                }
            }
            Ok(())
        }
    }

    #[test]
    fn mesh_covers_its_rectangle_exactly_once() {
        let mut counter = Counter {
            counts: vec![0; (WIDTH * HEIGHT) as usize],
        };
        let mut t = AnyTarget::new(&mut counter);
        for (vertices, color) in mesh_triangles() {
            let Ok(()) = fill_triangle(&mut t, vertices, color);
        }
        let (x0, y0, x1, y1) = MESH_AREA;
        for y in 0..HEIGHT as i32 {
            for x in 0..WIDTH as i32 {
                let inside = (x0..x1).contains(&x) && (y0..y1).contains(&y);
                let n = counter.counts[(y * WIDTH as i32 + x) as usize];
                assert_eq!(n, u32::from(inside), "pixel ({x}, {y}) written {n} times");
            }
        }
    }

    #[test]
    fn clipped_lines_cover_every_dim_pixel_inside_the_viewport() {
        let display = render(&SCENES[6]).unwrap();
        let dimmed: Vec<Rgb888> = clipping_lines().iter().map(|l| dim(l.2, DIM)).collect();
        for p in CLIP_VIEWPORT.points() {
            let c = display.get_pixel(p);
            assert!(
                !dimmed.contains(&c) || c == BACKGROUND,
                "unclipped pixel left at {p:?}"
            );
        }
    }

    #[test]
    fn every_scene_renders() {
        for scene in &SCENES {
            render(scene).unwrap();
        }
    }
}
