//! The committed gallery is what the commands draw now: every PNG in `docs/images/` is either a
//! `demo` picture (compared in `demo.rs`) or `scene_NAME.png`, rendered by
//! `host-tools render assets/scenes/NAME.toml`, which this test renders again and compares pixel
//! for pixel, so a picture can never go stale unnoticed.

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The pixels and size of a PNG.
fn pixels(path: &Path) -> (u32, u32, Vec<u8>) {
    let image = image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8();
    (image.width(), image.height(), image.into_raw())
}

/// The demo's file names, from its help (which is made from the list the demo writes).
fn demo_files() -> Vec<String> {
    let help = Command::new(env!("CARGO_BIN_EXE_host-tools"))
        .args(["demo", "--help"])
        .output()
        .unwrap();
    String::from_utf8_lossy(&help.stdout)
        .split(|c: char| c.is_whitespace() || c == ',' || c == ':')
        .map(|w| w.trim_end_matches('.'))
        .filter(|w| w.ends_with(".png"))
        .map(String::from)
        .collect()
}

#[test]
fn committed_gallery_equals_a_fresh_render() {
    let images = repo().join("docs/images");
    let demo = demo_files();
    assert!(demo.len() >= 15, "demo --help lists {demo:?}");
    let out = std::env::temp_dir().join(format!("host-tools-gallery-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).unwrap();
    let mut scenes = 0;
    for entry in std::fs::read_dir(&images).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if !name.ends_with(".png") || demo.contains(&name) {
            continue;
        }
        let scene = name
            .strip_prefix("scene_")
            .and_then(|n| n.strip_suffix(".png"))
            .map(|n| repo().join("assets/scenes").join(format!("{n}.toml")))
            .filter(|s| s.is_file())
            .unwrap_or_else(|| {
                panic!("docs/images/{name}: neither a demo picture nor scene_NAME.png of a scene")
            });
        let fresh = out.join(&name);
        let run = Command::new(env!("CARGO_BIN_EXE_host-tools"))
            .arg("render")
            .arg(&scene)
            .arg("-o")
            .arg(&fresh)
            .output()
            .unwrap();
        assert!(
            run.status.success(),
            "{}: {}",
            scene.display(),
            String::from_utf8_lossy(&run.stderr)
        );
        assert!(
            pixels(&fresh) == pixels(&path),
            "docs/images/{name} is not what the scene draws now: run `cargo run --release -p \
             host-tools -- render assets/scenes/{} -o docs/images/{name}` from the repository root",
            scene.file_name().unwrap().to_string_lossy()
        );
        scenes += 1;
    }
    assert!(scenes >= 9, "only {scenes} scene pictures");
    std::fs::remove_dir_all(&out).unwrap();
}
