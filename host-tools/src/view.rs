//! `view`: a scene file in a live SDL2 window, rendered again every frame.
//!
//! Each frame is the same picture `render` writes (the embedded-graphics simulator's display and
//! output settings), shown in a window of this module's own: the simulator's `Window` cannot
//! change its title, and the title carries the frame time, the triangles drawn and the pixels the
//! meshes wrote. Left and right arrows (or dragging with the mouse) turn the meshes about the
//! vertical axis, up and down tilt them; Escape or Q closes the window.
//!
//! Without a display SDL would not fail: it falls back to its invisible `offscreen` driver (and
//! would run forever without `--frames`), and its Wayland driver's library prints
//! `error: XDG_RUNTIME_DIR is invalid ...` on stderr, a line that looks like ours. So the display
//! is checked before SDL is started, SDL tries only the drivers of the displays named in the
//! environment, and an invisible driver is refused.

use crate::scenefile::{load_warning, parse_bands, render_frame, Pose};
use rasterizer_core::prelude::*;
use sdl2::event::Event;
use sdl2::keyboard::Keycode;
use sdl2::pixels::PixelFormatEnum;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// Options of the `view` command.
#[derive(Debug, clap::Args)]
pub struct ViewArgs {
    /// The scene file (format: docs/SCENES.md).
    pub scene: PathBuf,
    /// Window pixels per display pixel, 1 ..= 16 (default: the scene's `output.scale`).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    pub scale: Option<u32>,
    /// Close the window after this many frames (for scripts and tests; default: when closed).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: Option<u32>,
    /// Write what the window shows, read back from it, to this PNG when it closes.
    #[arg(long, value_name = "FILE")]
    pub screenshot: Option<PathBuf>,
    /// Draw through a frame list (`rasterizer_core::frame`) in bands of ROWS rows (1 or more),
    /// as firmware with a buffer of a few rows does; the picture is the same as without.
    #[arg(long, value_name = "ROWS", value_parser = parse_bands)]
    pub bands: Option<u32>,
}

/// The turn of one arrow key press or one pixel of mouse drag, in 1/65536 turn.
const KEY_STEP: i32 = 65536 / 72;
const DRAG_STEP: i32 = 65536 / 720;

/// Runs `view`.
///
/// # Errors
/// A message for the `error:` line: the scene, SDL2 (no display, for example), or the screenshot.
pub fn run(args: &ViewArgs) -> Result<(), Box<dyn std::error::Error>> {
    let scene = load_warning(&args.scene)?;
    let scale = args.scale.unwrap_or(scene.scale);
    let name = args.scene.file_name().map_or_else(
        || args.scene.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let sdl = sdl2::init().map_err(NoWindow)?;
    let video = open_video(&sdl)?;
    let (mut yaw, mut pitch) = (0i32, 0i32);
    let pose = |yaw: i32, pitch: i32| Pose {
        yaw: Angle(yaw.rem_euclid(65536) as u16),
        pitch: Angle(pitch.rem_euclid(65536) as u16),
    };
    // The first frame fixes the window's size (the output image's, spacing included).
    let (first, _) = render_frame(&scene, pose(0, 0), scale, args.bands)?;
    let first = first.as_image_buffer();
    let (w, h) = (first.width(), first.height());
    let window = video
        .window(&name, w, h)
        .position_centered()
        .build()
        .map_err(|e| NoWindow(e.to_string()))?;
    let mut canvas = window
        .into_canvas()
        .software()
        .build()
        .map_err(|e| e.to_string())?;
    let creator = canvas.texture_creator();
    let mut texture = creator
        .create_texture_streaming(PixelFormatEnum::RGB24, w, h)
        .map_err(|e| e.to_string())?;
    let mut events = sdl.event_pump()?;
    let mut frame = 0u32;
    let mut dragging = false;
    'frames: loop {
        for event in events.poll_iter() {
            match event {
                Event::Quit { .. }
                | Event::KeyDown {
                    keycode: Some(Keycode::Escape | Keycode::Q),
                    ..
                } => break 'frames,
                Event::KeyDown {
                    keycode: Some(key), ..
                } => match key {
                    Keycode::Left => yaw -= KEY_STEP,
                    Keycode::Right => yaw += KEY_STEP,
                    Keycode::Up => pitch -= KEY_STEP,
                    Keycode::Down => pitch += KEY_STEP,
                    _ => {}
                },
                Event::MouseButtonDown { .. } => dragging = true,
                Event::MouseButtonUp { .. } => dragging = false,
                Event::MouseMotion { xrel, yrel, .. } if dragging => {
                    yaw += xrel * DRAG_STEP;
                    pitch += yrel * DRAG_STEP;
                }
                _ => {}
            }
        }
        let start = Instant::now();
        let (image, stats) = render_frame(&scene, pose(yaw, pitch), scale, args.bands)?;
        let took = start.elapsed();
        let pixels = image.as_image_buffer();
        texture
            .update(None, pixels.as_raw(), w as usize * 3)
            .map_err(|e| e.to_string())?;
        canvas.copy(&texture, None, None)?;
        canvas.present();
        canvas.window_mut().set_title(&title(
            &name,
            took,
            stats.triangles,
            stats.pixels,
            args.bands,
        ))?;
        frame += 1;
        if args.frames.is_some_and(|n| frame >= n) {
            break;
        }
        // Rendering is the work; a short pause keeps an idle window from using a whole core.
        std::thread::sleep(Duration::from_millis(4));
    }
    if let Some(path) = &args.screenshot {
        let shot = canvas.read_pixels(None, PixelFormatEnum::RGB24)?;
        if shot.len() != w as usize * h as usize * 3 {
            return Err("the window's pixels have another size than the picture".into());
        }
        crate::output::write_png(path, &[args.scene.as_path()], w, h, &shot)?;
    }
    Ok(())
}

/// No window could be opened, and why.
#[derive(Debug)]
struct NoWindow(String);

impl std::fmt::Display for NoWindow {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "no window could be opened: {}", self.0)
    }
}

impl std::error::Error for NoWindow {}

/// SDL's drivers that draw nowhere a user can see.
const INVISIBLE_DRIVERS: [&str; 3] = ["offscreen", "dummy", "evdev"];

fn set(var: &str) -> bool {
    std::env::var_os(var).is_some_and(|v| !v.is_empty())
}

/// Starts SDL's video for a visible window, or says why there can be none.
fn open_video(sdl: &sdl2::Sdl) -> Result<sdl2::VideoSubsystem, NoWindow> {
    let chosen = set("SDL_VIDEODRIVER");
    // Without a chosen driver SDL tries them all, Wayland's noisily, and ends in `offscreen`:
    // try only those of the displays named (a console's kmsdrm can be chosen explicitly).
    if !chosen {
        let drivers =
            match (set("WAYLAND_DISPLAY"), set("DISPLAY")) {
                (true, true) => "wayland,x11",
                (true, false) => "wayland",
                (false, true) => "x11",
                (false, false) => return Err(NoWindow(
                    "no display (DISPLAY and WAYLAND_DISPLAY are not set); run it in a desktop \
                     session or under xvfb-run, or choose a driver with SDL_VIDEODRIVER"
                        .into(),
                )),
            };
        sdl2::hint::set("SDL_VIDEODRIVER", drivers);
    }
    let video = sdl.video().map_err(|e| {
        let display = std::env::var("DISPLAY").unwrap_or_default();
        NoWindow(format!(
            "SDL found no usable video driver: {e} (DISPLAY={display:?})"
        ))
    })?;
    let driver = video.current_video_driver();
    if INVISIBLE_DRIVERS.contains(&driver) {
        return Err(NoWindow(format!(
            "SDL's video driver `{driver}` shows nothing on a screen"
        )));
    }
    Ok(video)
}

/// The window title: what the frame cost and did; drawn in bands (whose meshes draw straight
/// into the frame list's bands, where nothing counts pixels), the band height instead of the
/// pixels written.
fn title(
    name: &str,
    took: Duration,
    triangles: u64,
    pixels: Option<u64>,
    bands: Option<u32>,
) -> String {
    let last = match (pixels, bands) {
        (Some(pixels), _) => format!("{pixels} pixels written"),
        (None, Some(rows)) => format!("bands of {rows} rows"),
        (None, None) => "pixels not counted".to_string(),
    };
    format!(
        "{name} | {:.1} ms | {triangles} triangles drawn | {last}",
        took.as_secs_f64() * 1000.0
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_title_names_time_triangles_and_pixels() {
        let t = title(
            "m.toml",
            Duration::from_micros(12_345),
            609,
            Some(14_773),
            None,
        );
        assert_eq!(
            t,
            "m.toml | 12.3 ms | 609 triangles drawn | 14773 pixels written"
        );
        let t = title("m.toml", Duration::from_micros(12_345), 609, None, Some(16));
        assert_eq!(
            t,
            "m.toml | 12.3 ms | 609 triangles drawn | bands of 16 rows"
        );
    }
}
