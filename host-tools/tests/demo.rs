//! Runs the `demo` command end to end: every PNG is written and equals the README's gallery in
//! `docs/images/`, and a bad `--out` fails cleanly.

use std::path::PathBuf;
use std::process::Command;

/// The PNG files the demo promises (README.md links to them): the 2D ones, then the 3D ones.
const FILES: [&str; 18] = [
    "lines_octants.png",
    "lines_gradient.png",
    "triangle_outlines.png",
    "triangles_flat.png",
    "triangles_gouraud.png",
    "polygons.png",
    "clipping.png",
    "sprites.png",
    "suzanne_wireframe.png",
    "suzanne_flat.png",
    "suzanne_gouraud.png",
    "suzanne_phong.png",
    "suzanne_matcap.png",
    "suzanne_dither.png",
    "suzanne_aa.png",
    "suzanne_fog.png",
    "cube_inside.png",
    "near_plane_crossing.png",
];

/// A fresh directory under the system temp dir, unique to this test and process.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("host-tools-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn demo_writes_every_picture() {
    let dir = scratch("demo-ok");
    let out = dir.join("images");
    let run = Command::new(env!("CARGO_BIN_EXE_host-tools"))
        .args(["demo", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "demo failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert_eq!(
        stdout.lines().count(),
        FILES.len(),
        "one line per file:\n{stdout}"
    );
    // Progress is for terminals only: a pipe or a log sees nothing on stderr.
    assert_eq!(String::from_utf8_lossy(&run.stderr), "", "stderr of demo");
    for file in FILES {
        let path = out.join(file);
        let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(
            bytes.starts_with(b"\x89PNG\r\n\x1a\n"),
            "{file} is not a PNG"
        );
        // A blank 600x450 (or 640x480) picture compresses to well under a kilobyte; every scene has real content.
        assert!(bytes.len() > 2000, "{file} is only {} bytes", bytes.len());
        assert!(stdout.contains(file), "{file} not reported:\n{stdout}");
        // The README's gallery is this output: a change that moves a pixel renders it again.
        let shown = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../docs/images")
            .join(file);
        let committed =
            std::fs::read(&shown).unwrap_or_else(|e| panic!("{}: {e}", shown.display()));
        assert!(
            committed == bytes,
            "docs/images/{file} is not what the demo draws now: run \
             `cargo run --release -p host-tools -- demo` from the repository root"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn demo_reports_an_unwritable_output_directory() {
    let dir = scratch("demo-bad");
    let file = dir.join("not-a-directory");
    std::fs::write(&file, b"a regular file").unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_host-tools"))
        .args(["demo", "--out"])
        .arg(file.join("images"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success(), "demo should fail");
    assert_ne!(run.status.code(), Some(0));
    assert!(
        stderr.lines().any(|l| l.starts_with("error:")),
        "no `error:` line in stderr:\n{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn demo_reports_a_missing_model() {
    let dir = scratch("demo-no-models");
    let run = Command::new(env!("CARGO_BIN_EXE_host-tools"))
        .args(["demo", "--out"])
        .arg(dir.join("images"))
        .arg("--models")
        .arg(dir.join("no-such-dir"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success(), "demo should fail");
    assert!(
        stderr
            .lines()
            .any(|l| l.starts_with("error: cannot load model") && l.contains("suzanne.obj")),
        "no model error in stderr:\n{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `demo --help` names every file the demo writes (it is made from the same list), and shows no
/// path of the machine it was built on.
#[test]
fn demo_help_lists_every_picture_and_no_build_path() {
    let run = Command::new(env!("CARGO_BIN_EXE_host-tools"))
        .args(["demo", "--help"])
        .output()
        .unwrap();
    assert!(run.status.success());
    let help = String::from_utf8_lossy(&run.stdout);
    for file in FILES {
        assert!(
            help.contains(file),
            "{file} missing from demo --help:\n{help}"
        );
    }
    let listed = help.matches(".png").count();
    assert_eq!(
        listed,
        FILES.len(),
        "demo --help lists other files:\n{help}"
    );
    assert!(
        !help.contains(env!("CARGO_MANIFEST_DIR")),
        "demo --help shows a build path:\n{help}"
    );
    assert!(help.contains("assets/models"), "{help}");
}

/// A demo that fails part of the way leaves the pictures already in `--out` as they were and no
/// partial set, nor its temporary directory: here the last 3D picture's name is taken by a
/// directory, which the demo refuses to replace.
#[test]
fn demo_failure_leaves_the_old_pictures() {
    let dir = scratch("demo-all-or-nothing");
    let out = dir.join("images");
    std::fs::create_dir_all(&out).unwrap();
    let blocked = "near_plane_crossing.png";
    for file in FILES {
        if file == blocked {
            std::fs::create_dir(out.join(file)).unwrap();
        } else {
            std::fs::write(out.join(file), format!("old {file}")).unwrap();
        }
    }
    let run = Command::new(env!("CARGO_BIN_EXE_host-tools"))
        .args(["demo", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success(), "demo should fail");
    assert!(
        stderr
            .lines()
            .any(|l| l.starts_with("error: ") && l.contains(blocked)),
        "no error naming {blocked}:\n{stderr}"
    );
    for file in FILES {
        let path = out.join(file);
        if file == blocked {
            assert!(path.is_dir(), "{file} replaced");
        } else {
            let now = std::fs::read_to_string(&path).unwrap_or_default();
            assert_eq!(now, format!("old {file}"), "{file} changed");
        }
    }
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, ["images"], "left beside --out: {left:?}");
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), FILES.len());
    std::fs::remove_dir_all(&dir).unwrap();
}
