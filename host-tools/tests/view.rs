//! `host-tools view` in a real SDL2 window on a virtual X display (Xvfb): it opens, renders a
//! few frames and closes, and what the window showed, read back from it, is the picture `render`
//! writes. Built only with the `view` feature (which needs SDL2); skipped, saying so, where
//! `xvfb-run` is not installed. Without a display it fails with one error line of its own.
#![cfg(feature = "view")]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

#[path = "support/cli.rs"]
mod cli;
use cli::{assert_error, scratch_in, text, BIN};

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/scenes")
        .join(name)
}

fn have_xvfb() -> bool {
    let found = Command::new("xvfb-run").arg("--help").output().is_ok();
    if !found {
        eprintln!(
            "view test skipped: xvfb-run is not installed (Debian: apt-get install xvfb xauth)"
        );
    }
    found
}

/// Runs `view` for `frames` frames under Xvfb and returns the screenshot's RGB pixels.
fn view(scene: &Path, frames: u32, dir: &Path) -> (u32, u32, Vec<u8>) {
    view_with(scene, frames, dir, &[])
}

/// [`view`] with more arguments.
fn view_with(scene: &Path, frames: u32, dir: &Path, args: &[&str]) -> (u32, u32, Vec<u8>) {
    let shot = dir.join("shot.png");
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x1024x24", BIN, "view"])
        .arg(scene)
        .args(["--frames", &frames.to_string(), "--screenshot"])
        .arg(&shot)
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "view failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let img = image::open(&shot).unwrap().to_rgb8();
    (img.width(), img.height(), img.into_raw())
}

#[test]
fn the_window_shows_what_render_writes() {
    if !have_xvfb() {
        return;
    }
    let dir = scratch_in("view", "render");
    let scene = scene("suzanne_gouraud.toml");
    let (w, h, shown) = view(&scene, 3, &dir);
    // Not blank: a lit mesh has many colours.
    let colours: std::collections::BTreeSet<&[u8]> = shown.chunks_exact(3).collect();
    assert!(colours.len() > 50, "{} colours", colours.len());
    let png = dir.join("render.png");
    let out = Command::new(BIN)
        .arg("render")
        .arg(&scene)
        .arg("-o")
        .arg(&png)
        .output()
        .unwrap();
    assert!(out.status.success());
    let rendered = image::open(&png).unwrap().to_rgb8();
    assert_eq!((w, h), rendered.dimensions());
    assert!(
        shown == rendered.into_raw(),
        "the window differs from render's picture"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `view --bands` draws through the frame list and shows the same picture.
#[test]
fn the_banded_window_shows_the_same_picture() {
    if !have_xvfb() {
        return;
    }
    let dir = scratch_in("view", "bands");
    let scene = scene("translucent_mesh.toml");
    let (w, h, whole) = view(&scene, 2, &dir);
    let (bw, bh, banded) = view_with(&scene, 2, &dir, &["--bands", "7"]);
    assert_eq!((w, h), (bw, bh));
    assert!(whole == banded, "the banded window differs");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_scene_error_is_an_error_line_not_a_window() {
    let dir = scratch_in("view", "missing");
    let out = Command::new(BIN)
        .arg("view")
        .arg(dir.join("missing.toml"))
        .args(["--frames", "1"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("error:") && err.contains("missing.toml"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `view` with the display environment replaced by `env` (DISPLAY, WAYLAND_DISPLAY,
/// SDL_VIDEODRIVER and XDG_RUNTIME_DIR removed first).
fn view_without_display(scene: &Path, env: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(BIN);
    for var in [
        "DISPLAY",
        "WAYLAND_DISPLAY",
        "SDL_VIDEODRIVER",
        "XDG_RUNTIME_DIR",
    ] {
        cmd.env_remove(var);
    }
    // --frames, so that a view that runs invisibly ends (with exit 0) instead of hanging.
    cmd.arg("view").arg(scene).args(["--frames", "3"]);
    cmd.envs(env.iter().copied()).output().unwrap()
}

#[test]
fn no_display_is_one_error_line_of_ours() {
    let scene = scene("suzanne_gouraud.toml");
    for env in [
        &[][..],
        // A display that is not there; without XDG_RUNTIME_DIR SDL's Wayland driver would also
        // print its own `error:` line.
        &[("DISPLAY", ":7777")][..],
        &[("SDL_VIDEODRIVER", "offscreen")][..],
        &[("SDL_VIDEODRIVER", "nonesuch")][..],
    ] {
        let what = format!("{env:?}");
        let o = view_without_display(&scene, env);
        let line = assert_error(&o, &what);
        assert!(
            line.starts_with("error: no window could be opened: "),
            "{what}: {line}"
        );
        assert_eq!(
            text(&o.stderr).lines().count(),
            1,
            "{what}: other lines on stderr:\n{}",
            text(&o.stderr)
        );
    }
}

#[test]
fn obj_warnings_come_before_the_window() {
    let dir = scratch_in("view", "warnings");
    let cube = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/unit_cube.obj");
    let crlf = std::fs::read_to_string(cube).unwrap().replace('\n', "\r\n");
    std::fs::write(dir.join("crlf.obj"), crlf).unwrap();
    let scene = dir.join("crlf.toml");
    std::fs::write(
        &scene,
        "[output]\nwidth = 32\nheight = 24\n[[meshes]]\npath = \"crlf.obj\"\n",
    )
    .unwrap();
    let o = view_without_display(&scene, &[]);
    assert_error(&o, "view");
    let stderr = text(&o.stderr);
    assert!(
        stderr
            .lines()
            .any(|l| l.starts_with("warning: ") && l.contains("crlf.obj") && l.contains("CRLF")),
        "{stderr}"
    );
}
