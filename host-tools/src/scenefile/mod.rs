//! Scene files and the `render`, `animate` and `compare` commands.
//!
#![doc = include_str!("../../../docs/SCENES.md")]

mod banded;
mod counting;
mod draw;
mod format;
pub mod limits;
mod load;
mod reference;
mod sprite;

pub use counting::Counting;
pub use draw::{render_3d, render_frame, render_image, render_posed, FrameStats, Pose};
pub use format::{
    Camera, Color, CullMode, FillRuleDef, LightDef, MaterialDef, MeshDef, NormalsMode, Output,
    PixelFormat, RenderOptions, ScaleDef, SceneFile, ShadingModel, Shape, SpecularModel,
    TextureFilterDef, TextureWrapDef, VertexColorMode,
};
pub use load::{load, load_with_warnings, MeshData, OwnedMesh, Scene, SceneMesh, SceneTexture};
pub use reference::{Real, F64};

use crate::output::{
    check_output as check_output_name, encode_png, goes_to_stdout, is_stdout, write_png, OutputFile,
};
use crate::progress::Progress;
use crate::sayln;
use embedded_graphics_simulator::SimulatorDisplay;
use image::codecs::gif::{GifEncoder, Repeat};
use image::{Delay, Frame, RgbImage, RgbaImage};
use rasterizer_core::prelude::*;
use std::path::{Path, PathBuf};

/// The most lights a scene may have.
pub const MAX_LIGHTS: usize = 4;
/// The most vertices a polygon shape may have.
pub const MAX_POLYGON: usize = 256;

/// Options of the `render` command.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// The scene file.
    pub scene: PathBuf,
    /// The PNG to write: a name ending in .png, a device or FIFO, or `-` for standard output
    /// (always PNG).
    #[arg(short, long, value_name = "FILE", allow_hyphen_values = true)]
    pub output: PathBuf,
    /// PNG pixels per display pixel, 1 ..= 16 (default: the scene's `output.scale`).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    pub scale: Option<u32>,
    /// Draw through a frame list (`rasterizer_core::frame`) in bands of ROWS rows (1 or more),
    /// as firmware with a buffer of a few rows does; the picture is the same as without.
    #[arg(long, value_name = "ROWS", value_parser = parse_bands)]
    pub bands: Option<u32>,
}

/// Parses `--bands`: rows per band, at least 1.
///
/// # Errors
/// A message for clap's `invalid value` line.
pub fn parse_bands(s: &str) -> std::result::Result<u32, String> {
    match s.parse::<u32>() {
        Ok(0) => Err("a band needs at least 1 row".into()),
        Ok(n) => Ok(n),
        Err(e) => Err(format!("not a number of rows: {e}")),
    }
}

/// Options of the `animate` command.
#[derive(Debug, clap::Args)]
pub struct AnimateArgs {
    /// The scene file.
    pub scene: PathBuf,
    /// The output: an animated GIF (a name ending in .gif, a device or FIFO, or `-` for
    /// standard output, always GIF), or with `--png-sequence` the name the numbered PNGs are
    /// derived from (`out.png` gives `out_000.png`, `out_001.png`, ...; .png or no extension).
    #[arg(short, long, value_name = "FILE", allow_hyphen_values = true)]
    pub output: PathBuf,
    /// Frames in one full turn, 1 ..= 720 (a progress bar counts them on stderr when it is a
    /// terminal).
    #[arg(long, value_name = "N", default_value_t = 36, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_FRAMES)))]
    pub frames: u32,
    /// Write numbered PNG files instead of a GIF.
    #[arg(long)]
    pub png_sequence: bool,
    /// PNG pixels per display pixel, 1 ..= 16 (default: the scene's `output.scale`).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    pub scale: Option<u32>,
    /// Time per GIF frame in milliseconds (default: one turn in 3 s, at least 20 ms per frame).
    #[arg(long, value_name = "MS")]
    pub delay_ms: Option<u32>,
    /// Draw through a frame list (`rasterizer_core::frame`) in bands of ROWS rows (1 or more),
    /// as firmware with a buffer of a few rows does; the picture is the same as without.
    #[arg(long, value_name = "ROWS", value_parser = parse_bands)]
    pub bands: Option<u32>,
}

/// The format the difference image compares fixed point against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Reference {
    /// The core's `f32` backend.
    F32,
    /// The `f64` reference scalar of this tool.
    F64,
}

/// Options of the `compare` command.
#[derive(Debug, clap::Args)]
pub struct CompareArgs {
    /// The scene file.
    pub scene: PathBuf,
    /// The difference image to write (PNG): fixed point | reference | differences. A name
    /// ending in .png, a device or FIFO, or `-` for standard output (always PNG; the figures go
    /// to stderr then).
    #[arg(short, long, value_name = "FILE", allow_hyphen_values = true)]
    pub output: PathBuf,
    /// What the difference image compares 16.16 with (all pairs are printed either way).
    #[arg(long, value_enum, default_value = "f32")]
    pub reference: Reference,
    /// PNG pixels per display pixel, 1 ..= 16 (default: the scene's `output.scale`).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    pub scale: Option<u32>,
}

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// The largest scene width and height, in display pixels.
pub const MAX_SIZE: u32 = 4096;
/// The most pixels one output image may have after scaling (`render`, each `animate` frame,
/// `compare`'s three panels): 4096 x 4096. This bounds the memory and time of one image.
pub const MAX_OUTPUT_PIXELS: u64 = 1 << 24;
/// The most frames of `animate`.
pub const MAX_FRAMES: u32 = 720;
/// The widest and tallest GIF frame the format can hold.
pub const MAX_GIF_SIDE: u32 = u16::MAX as u32;

/// The limits and the memory they bound, shown by `render --help` and `animate --help`.
pub const LIMITS_HELP: &str = "Scene files: the format and every allowed value are in docs/SCENES.md; \
    examples are in assets/scenes/.\n\n\
    Limits: scenes are at most 4096 x 4096 display pixels; an output \
    image is at most 16777216 pixels (4096 x 4096) after scaling, so a 4096 x 4096 scene renders \
    at scale 1 and a 1024 x 1024 one at up to scale 4; animate makes at most 720 frames, and a GIF \
    frame is at most 65535 pixels wide and tall. A request beyond a limit is refused before \
    anything is rendered, with an error naming the limit and the value.\n\n\
    Memory: one image is rendered at a time and encoded straight into the output file (GIF \
    frames one by one, PNG sequences file by file), so the peak does not grow with the number of \
    frames: at most about 12.5 bytes per output pixel, so about 210 MB at the limit. Measured \
    peaks (maximum resident set size, release build): render of a 4096 x 4096 scene 186 MB; \
    animate of it to a GIF 203 MB, to a PNG sequence 187 MB; a GIF of a 1024 x 1024 scene at scale 4 134 MB; a GIF of a 320 x 240 scene \
    at scale 4 15 MB with 36, 144 or 720 frames.\n\n\
    Output files are written to a temporary file beside the target and renamed over it when \
    complete: a failure leaves an existing file as it was. A device or FIFO (/dev/stdout, \
    mkfifo) is written in place; `-o -` writes to standard output, and messages go to stderr \
    then. The format is the command's: a name whose extension says another one is refused.";

#[cfg(test)]
#[test]
fn the_help_states_the_limits_in_force() {
    for figure in [MAX_SIZE, MAX_FRAMES, MAX_GIF_SIDE] {
        assert!(LIMITS_HELP.contains(&figure.to_string()), "{figure}");
    }
    assert!(LIMITS_HELP.contains(&MAX_OUTPUT_PIXELS.to_string()));
}

/// [`load`] for a command: the OBJ reader's warnings are printed as `warning:` lines on stderr
/// (before an error, when the scene is refused: they often say why, e.g. a file with bare CR
/// line endings has no faces).
///
/// # Errors
/// As [`load`].
pub fn load_warning(path: &Path) -> Result<Scene> {
    let mut warnings = Vec::new();
    let scene = load_with_warnings(path, &mut warnings);
    for w in &warnings {
        crate::errln!("warning: {w}");
    }
    Ok(scene?)
}

/// Checks the size of one output image, `width x height` PNG pixels, before anything is drawn.
fn check_output(scene: &Scene, scale: u32, width: u64, height: u64) -> Result<()> {
    let pixels = width * height;
    if pixels > MAX_OUTPUT_PIXELS {
        return Err(format!(
            "{}: the output would be {width} x {height} = {pixels} pixels ({} x {} display \
             pixels at scale {scale}); the limit is {MAX_OUTPUT_PIXELS} pixels (4096 x 4096): \
             lower the scale or the scene's size",
            scene.path.display(),
            scene.width,
            scene.height
        )
        .into());
    }
    Ok(())
}

/// Runs `render`: draws the scene through embedded-graphics-simulator and saves the PNG.
///
/// # Errors
/// Any failure, as a message for the `error:` line; an existing output is left as it was then.
pub fn render(args: &RenderArgs) -> Result<()> {
    let to_stdout = goes_to_stdout(&args.output);
    let scene = load_warning(&args.scene)?;
    check_output_name(&args.output, &scene.inputs(), &["png"], "a PNG", "")?;
    let scale = args.scale.unwrap_or(scene.scale);
    check_output(
        &scene,
        scale,
        u64::from(scene.width) * u64::from(scale),
        u64::from(scene.height) * u64::from(scale),
    )?;
    let image = turned(&scene, Angle(0), scale, args.bands)?;
    let buf = image.as_image_buffer();
    write_png(
        &args.output,
        &scene.inputs(),
        buf.width(),
        buf.height(),
        &buf,
    )?;
    sayln!(to_stdout, "wrote {}", args.output.display())?;
    Ok(())
}

/// [`render_image`], drawn whole or (`bands`) through a frame list in bands of that many rows.
fn turned(
    scene: &Scene,
    turn: Angle,
    scale: u32,
    bands: Option<u32>,
) -> std::result::Result<embedded_graphics_simulator::OutputImage<Rgb888>, String> {
    let pose = Pose {
        yaw: turn,
        pitch: Angle(0),
    };
    Ok(render_frame(scene, pose, scale, bands)?.0)
}

/// Why a frame of `animate` failed: the scene, or the output.
enum FrameError {
    Scene(String),
    Encode(image::ImageError),
}

/// Runs `animate`: a turntable of the scene's meshes about the world's Y axis, one full turn in
/// `--frames` frames, as an animated GIF or numbered PNGs. Each frame is encoded into its file as
/// soon as it is rendered, so memory does not grow with the number of frames.
///
/// # Errors
/// Any failure, as a message for the `error:` line; existing outputs are left as they were
/// unless every frame rendered and was written.
pub fn animate(args: &AnimateArgs) -> Result<()> {
    if args.png_sequence && is_stdout(&args.output) {
        return Err(
            "--png-sequence writes numbered files, which standard output cannot hold; \
                    name them with -o NAME.png"
                .into(),
        );
    }
    let to_stdout = goes_to_stdout(&args.output);
    let scene = load_warning(&args.scene)?;
    if args.png_sequence {
        let format = "PNG files (--png-sequence)";
        check_output_name(&args.output, &scene.inputs(), &["png"], format, "")?;
    } else {
        check_output_name(
            &args.output,
            &scene.inputs(),
            &["gif"],
            "an animated GIF",
            " (--png-sequence writes numbered PNG files)",
        )?;
    }
    let scale = args.scale.unwrap_or(scene.scale);
    let n = args.frames;
    if !(1..=MAX_FRAMES).contains(&n) {
        return Err(format!("--frames must be 1 ..= {MAX_FRAMES}, got {n}").into());
    }
    let (width, height) = (
        u64::from(scene.width) * u64::from(scale),
        u64::from(scene.height) * u64::from(scale),
    );
    check_output(&scene, scale, width, height)?;
    let turn = |k: u32| Angle((u64::from(k) * 65536 / u64::from(n)) as u16);
    let inputs = scene.inputs();
    let progress = Progress::new(true);
    progress.stage("frames", u64::from(n));
    if args.png_sequence {
        let stem = args
            .output
            .file_stem()
            .ok_or("the output needs a file name")?
            .to_string_lossy()
            .into_owned();
        let dir = args.output.parent().unwrap_or(Path::new(""));
        // All frames or none: each is finished into a temporary file, and they are renamed into
        // place together at the end.
        let mut pending = Vec::with_capacity(n as usize);
        for k in 0..n {
            let path = dir.join(format!("{stem}_{k:03}.png"));
            let image = turned(&scene, turn(k), scale, args.bands)?;
            let buf = image.as_image_buffer();
            let mut out = OutputFile::create(&path, &inputs)?;
            if let Err(e) = encode_png(&mut out, buf.width(), buf.height(), &buf) {
                return Err(out.error(e).into());
            }
            pending.push(out.finish()?);
            progress.inc();
        }
        progress.finish();
        for p in pending {
            p.commit()?;
        }
        crate::outln!(
            "wrote {n} frames to {}",
            dir.join(format!("{stem}_NNN.png")).display()
        )?;
        return Ok(());
    }
    if width > u64::from(MAX_GIF_SIDE) || height > u64::from(MAX_GIF_SIDE) {
        return Err(format!(
            "{}: a GIF frame is at most {MAX_GIF_SIDE} pixels wide and tall; this one would be \
             {width} x {height} ({} x {} at scale {scale}); lower the scale or use --png-sequence",
            scene.path.display(),
            scene.width,
            scene.height
        )
        .into());
    }
    let delay = args.delay_ms.unwrap_or((3000 / n).max(20));
    let mut out = OutputFile::create(&args.output, &inputs)?;
    let result = (|| {
        let mut encoder = GifEncoder::new_with_speed(&mut out, 10);
        encoder
            .set_repeat(Repeat::Infinite)
            .map_err(FrameError::Encode)?;
        for k in 0..n {
            let rgba = {
                let image =
                    turned(&scene, turn(k), scale, args.bands).map_err(FrameError::Scene)?;
                let buf = image.as_image_buffer();
                RgbaImage::from_fn(buf.width(), buf.height(), |x, y| {
                    let [r, g, b] = buf.get_pixel(x, y).0;
                    image::Rgba([r, g, b, 255])
                })
            };
            let frame = Frame::from_parts(rgba, 0, 0, Delay::from_numer_denom_ms(delay, 1));
            encoder.encode_frame(frame).map_err(FrameError::Encode)?;
            progress.inc();
        }
        Ok(())
    })();
    progress.finish();
    match result {
        Ok(()) => out.commit()?,
        Err(FrameError::Scene(e)) => return Err(e.into()),
        Err(FrameError::Encode(e)) => return Err(out.error(e).into()),
    }
    sayln!(to_stdout, "wrote {} ({n} frames)", args.output.display())?;
    Ok(())
}

/// How two renders differ.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Difference {
    /// Pixels whose colours differ.
    pub pixels: u64,
    /// All pixels.
    pub total: u64,
    /// The largest difference of one channel, in 8-bit steps.
    pub max_channel: u8,
}

impl Difference {
    /// The share of differing pixels, in percent.
    pub fn percent(&self) -> f64 {
        100.0 * self.pixels as f64 / self.total.max(1) as f64
    }
}

/// The largest channel difference of two colours.
fn channel_diff(a: Rgb888, b: Rgb888) -> u8 {
    a.r()
        .abs_diff(b.r())
        .max(a.g().abs_diff(b.g()))
        .max(a.b().abs_diff(b.b()))
}

/// Compares two displays of the same size pixel by pixel.
pub fn difference(
    a: &SimulatorDisplay<Rgb888>,
    b: &SimulatorDisplay<Rgb888>,
    w: u32,
    h: u32,
) -> Difference {
    let mut d = Difference {
        pixels: 0,
        total: u64::from(w) * u64::from(h),
        max_channel: 0,
    };
    for y in 0..h as i32 {
        for x in 0..w as i32 {
            let p = Point::new(x, y);
            let c = channel_diff(a.get_pixel(p), b.get_pixel(p));
            if c > 0 {
                d.pixels += 1;
                d.max_channel = d.max_channel.max(c);
            }
        }
    }
    d
}

/// Runs `compare`: renders the scene's meshes (not its shapes) in 16.16, `f32` and `f64` into
/// `Rgb888` displays, prints how each pair differs, and writes fixed point, the reference and
/// the differing pixels side by side.
///
/// # Errors
/// Any failure, as a message for the `error:` line.
pub fn compare(args: &CompareArgs) -> Result<()> {
    let to_stdout = goes_to_stdout(&args.output);
    let scene = load_warning(&args.scene)?;
    check_output_name(&args.output, &scene.inputs(), &["png"], "a PNG", "")?;
    if scene.meshes.is_empty() {
        return Err(format!(
            "{}: the scene has no meshes to compare",
            scene.path.display()
        )
        .into());
    }
    let (w, h) = (scene.width, scene.height);
    let scale = args.scale.unwrap_or(scene.scale);
    check_output(
        &scene,
        scale,
        u64::from(3 * w + 2 * DIFF_GAP) * u64::from(scale),
        u64::from(h) * u64::from(scale),
    )?;
    let fixed = render_3d::<Fx16>(&scene)?;
    let single = render_3d::<f32>(&scene)?;
    let double = render_3d::<F64>(&scene)?;
    sayln!(
        to_stdout,
        "{}: 3D part, {w}x{h} = {} pixels, compared in Rgb888",
        scene.path.display(),
        u64::from(w) * u64::from(h)
    )?;
    for (name, a, b) in [
        ("16.16 vs f32", &fixed, &single),
        ("16.16 vs f64", &fixed, &double),
        ("f32   vs f64", &single, &double),
    ] {
        let d = difference(a, b, w, h);
        sayln!(
            to_stdout,
            "  {name}: {} differing pixels ({:.3} %), max channel difference {}",
            d.pixels,
            d.percent(),
            d.max_channel
        )?;
    }
    let reference = match args.reference {
        Reference::F32 => &single,
        Reference::F64 => &double,
    };
    let image = diff_image(&fixed, reference, w, h, scale);
    write_png(
        &args.output,
        &scene.inputs(),
        image.width(),
        image.height(),
        &image,
    )?;
    sayln!(
        to_stdout,
        "wrote {} (16.16 | {} | differences: yellow 1 step .. red 8 or more)",
        args.output.display(),
        match args.reference {
            Reference::F32 => "f32",
            Reference::F64 => "f64",
        }
    )?;
    Ok(())
}

/// The white gap between the panels of the difference image, in display pixels.
const DIFF_GAP: u32 = 4;

/// Three panels: `a`, `b`, and `a` in dim grey with the differing pixels coloured by how much
/// they differ (yellow: one step, red: eight or more).
fn diff_image(
    a: &SimulatorDisplay<Rgb888>,
    b: &SimulatorDisplay<Rgb888>,
    w: u32,
    h: u32,
    scale: u32,
) -> RgbImage {
    const GAP: u32 = DIFF_GAP;
    let panel = |x: u32, y: u32, k: u32| -> [u8; 3] {
        let p = Point::new(x as i32, y as i32);
        let (ca, cb) = (a.get_pixel(p), b.get_pixel(p));
        match k {
            0 => [ca.r(), ca.g(), ca.b()],
            1 => [cb.r(), cb.g(), cb.b()],
            _ => {
                let d = channel_diff(ca, cb);
                if d == 0 {
                    let luma =
                        (u32::from(ca.r()) * 3 + u32::from(ca.g()) * 6 + u32::from(ca.b())) / 10;
                    let g = (20 + luma / 4) as u8;
                    [g, g, g]
                } else {
                    [255, (230 - 230 * u32::from(d.min(8)) / 8) as u8, 0]
                }
            }
        }
    };
    let width = (3 * w + 2 * GAP) * scale;
    RgbImage::from_fn(width, h * scale, |px, py| {
        let (x, y) = (px / scale, py / scale);
        let k = x / (w + GAP);
        let xi = x % (w + GAP);
        if xi >= w {
            image::Rgb([255, 255, 255])
        } else {
            image::Rgb(panel(xi, y, k))
        }
    })
}
