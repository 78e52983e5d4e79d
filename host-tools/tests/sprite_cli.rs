//! `host-tools sprite`, run as the built binary: a PNG becomes a sprite the core reads; a bad PNG,
//! a wrong extension and the input named as the output fail with an `error:` line and leave
//! every file as it was.

use rasterizer_core::raster::sprite::{AlphaBits, Sprite};
use std::path::PathBuf;
use std::process::Command;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("host-tools-sprite-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(args: &[&std::ffi::OsStr]) -> (bool, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_host-tools"))
        .arg("sprite")
        .args(args)
        .output()
        .unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn converts_and_refuses_cleanly() {
    let dir = scratch("cli");
    let png = dir.join("in.png");
    let mut img = image::RgbaImage::new(3, 2);
    img.put_pixel(1, 0, image::Rgba([255, 0, 0, 255]));
    img.save(&png).unwrap();
    let out = dir.join("out.bin");
    let (ok, err) = run(&[png.as_os_str(), "-o".as_ref(), out.as_os_str()]);
    assert!(ok, "{err}");
    let bytes = std::fs::read(&out).unwrap();
    let s = Sprite::from_bytes(&bytes).unwrap();
    assert_eq!(
        (s.width(), s.height(), s.alpha_bits()),
        (3, 2, AlphaBits::One)
    );
    assert_eq!(s.texel(1, 0), (0xF800, 255));
    assert_eq!(s.texel(0, 0).1, 0);

    // A bad PNG: an error, and the existing output untouched.
    let junk = dir.join("junk.png");
    std::fs::write(&junk, b"not a png at all").unwrap();
    let (ok, err) = run(&[junk.as_os_str(), "-o".as_ref(), out.as_os_str()]);
    assert!(
        !ok && err.starts_with("error:") && err.contains("not a PNG"),
        "{err}"
    );
    assert_eq!(std::fs::read(&out).unwrap(), bytes);
    // The input as the output, and a wrong extension: refused before anything is written.
    let (ok, err) = run(&[out.as_os_str(), "-o".as_ref(), out.as_os_str()]);
    assert!(!ok && err.contains("input"), "{err}");
    assert_eq!(std::fs::read(&out).unwrap(), bytes);
    let wrong = dir.join("out.png");
    let (ok, err) = run(&[png.as_os_str(), "-o".as_ref(), wrong.as_os_str()]);
    assert!(!ok && err.contains(".bin"), "{err}");
    assert!(!wrong.exists());
    let _ = std::fs::remove_dir_all(&dir);
}
