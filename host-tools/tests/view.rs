//! `host-tools view` in a real SDL2 window on a virtual X display (Xvfb): it opens, renders a
//! few frames and closes, and what the window showed, read back from it, is the picture `render`
//! writes. Built only with the `view` feature (which needs SDL2); skipped, saying so, where
//! `xvfb-run` is not installed.
#![cfg(feature = "view")]

use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_host-tools");

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
    let shot = dir.join("shot.png");
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x1024x24", BIN, "view"])
        .arg(scene)
        .args(["--frames", &frames.to_string(), "--screenshot"])
        .arg(&shot)
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

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("host-tools-view-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn the_window_shows_what_render_writes() {
    if !have_xvfb() {
        return;
    }
    let dir = temp_dir("render");
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

#[test]
fn a_scene_error_is_an_error_line_not_a_window() {
    let dir = temp_dir("missing");
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
