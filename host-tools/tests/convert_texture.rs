//! The `convert` command with texture coordinates and textures: Spot converts with its seams
//! split and its texture resampled; every texture problem is one `error:` line naming the fix,
//! and leaves no output behind (an existing output stays as it was).

use rasterizer_core::mesh::MeshSource;
use rasterizer_core::prelude::*;
use std::path::{Path, PathBuf};

#[path = "support/convert.rs"]
mod support;
use support::{convert, models, scratch_in, text};

fn scratch(name: &str) -> PathBuf {
    scratch_in("convert-texture", name)
}

/// An 8-bit RGB PNG of `w` x `h` pixels coloured by `f`.
fn write_png(path: &Path, w: u32, h: u32, f: impl Fn(u32, u32) -> [u8; 3]) {
    image::RgbImage::from_fn(w, h, |x, y| image::Rgb(f(x, y)))
        .save(path)
        .unwrap();
}

fn rgb565(c: [f64; 3]) -> u16 {
    let q = |v: f64, max: f64| (v / 255.0 * max).round() as u16;
    (q(c[0], 31.0) << 11) | (q(c[1], 63.0) << 5) | q(c[2], 31.0)
}

const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
                    f 1/1 2/2 3/3 4/4\n";

#[test]
fn spot_with_a_resampled_texture_round_trips() {
    let dir = scratch("spot");
    let out = dir.join("spot.rmsh");
    let png = models().join("spot_texture.png");
    let obj = models().join("spot_triangulated.obj");
    let run = convert(
        &obj,
        &out,
        &[
            "--center-unit-sphere",
            "--texture",
            png.to_str().unwrap(),
            "--texture-size",
            "256",
        ],
    );
    let stdout = text(&run.stdout);
    assert_eq!(run.status.code(), Some(0), "{stdout}{}", text(&run.stderr));
    assert!(stdout.contains("a 256x256 texture"), "{stdout}");
    let blob = std::fs::read(&out).unwrap();
    assert_eq!(u16::from_le_bytes([blob[4], blob[5]]), 2, "format version");
    let mesh = PackedMesh::parse(&blob).unwrap();
    // Every position used with several texture coordinates is split: one vertex per `vt`.
    assert_eq!((mesh.vertices(), mesh.triangles()), (3225, 5856));
    let tex = mesh.texture().unwrap();
    assert_eq!((tex.width(), tex.height()), (256, 256));

    // Texels: the mean of the 4 x 4 block of the 1024 x 1024 image, rounded to Rgb565.
    let image = image::open(&png).unwrap().to_rgb8();
    assert_eq!(image.dimensions(), (1024, 1024));
    for (x, y) in [
        (0, 0),
        (255, 255),
        (17, 200),
        (128, 64),
        (200, 31),
        (90, 170),
    ] {
        let mut sum = [0f64; 3];
        for dy in 0..4 {
            for dx in 0..4 {
                let p = image.get_pixel(4 * x + dx, 4 * y + dy).0;
                for c in 0..3 {
                    sum[c] += f64::from(p[c]) / 16.0;
                }
            }
        }
        let sum = sum.map(|v| v.round());
        assert_eq!(tex.texel(x, y), rgb565(sum), "texel ({x}, {y})");
    }

    // Texture coordinates: u and 1 - v of the file, in 16.16; seams share their positions.
    let src = std::fs::read_to_string(&obj).unwrap();
    let vts: Vec<[f64; 2]> = src
        .lines()
        .filter_map(|l| l.strip_prefix("vt "))
        .map(|l| {
            let mut w = l.split_whitespace().map(|x| x.parse::<f64>().unwrap());
            [w.next().unwrap(), w.next().unwrap()]
        })
        .collect();
    let want: Vec<[i32; 2]> = vts
        .iter()
        .map(|[u, v]| {
            [
                (u * 65536.0).round() as i32,
                ((1.0 - v) * 65536.0).round() as i32,
            ]
        })
        .collect();
    let mut got: Vec<[i32; 2]> = (0..mesh.vertices())
        .map(|i| MeshSource::<Fx16>::uv(&mesh, i).unwrap())
        .collect();
    let mut want_sorted = want.clone();
    got.sort_unstable();
    want_sorted.sort_unstable();
    assert_eq!(got, want_sorted);
    // Smooth normals are per position: vertices at one position have one normal.
    let mut by_position = std::collections::HashMap::new();
    for i in 0..mesh.vertices() {
        let n = mesh.normal_bits(i).unwrap();
        let p = mesh.position_bits(i).unwrap();
        assert_eq!(*by_position.entry(p).or_insert(n), n, "vertex {i}");
    }
    assert!(by_position.len() < mesh.vertices());
}

#[test]
fn map_kd_gives_the_texture_and_no_texture_drops_it() {
    let dir = scratch("mtl");
    std::fs::create_dir(dir.join("maps")).unwrap();
    write_png(&dir.join("maps/t.png"), 4, 2, |x, y| {
        [(x * 60) as u8, (y * 200) as u8, 9]
    });
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl plain\nKd 1 1 1\nnewmtl tex\nmap_Kd -s 1 1 1 maps/t.png\n",
    )
    .unwrap();
    let obj = dir.join("q.obj");
    std::fs::write(&obj, format!("mtllib m.mtl\nusemtl tex\n{QUAD}")).unwrap();
    let out = dir.join("q.rmsh");
    let run = convert(&obj, &out, &[]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    let blob = std::fs::read(&out).unwrap();
    let mesh = PackedMesh::parse(&blob).unwrap();
    let tex = mesh.texture().unwrap();
    assert_eq!((tex.width(), tex.height()), (4, 2));
    assert_eq!(tex.texel(3, 1), rgb565([180.0, 200.0, 9.0]));
    // The quad's corner (0, 0) is the texture's bottom-left: v = 1 from the top.
    assert_eq!(mesh.uv_bits(0), Some([0, 65536]));
    assert_eq!(mesh.uv_bits(2), Some([65536, 0]));

    let run = convert(&obj, &out, &["--no-texture"]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    let blob = std::fs::read(&out).unwrap();
    let mesh = PackedMesh::parse(&blob).unwrap();
    assert!(mesh.texture().is_none() && mesh.uv_bits(0).is_some());
    let run = convert(&obj, &out, &["--no-uvs"]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    let blob = std::fs::read(&out).unwrap();
    assert_eq!(blob[4], 1, "neither: version 1");
    // Without the material the faces use, no texture.
    std::fs::write(&obj, format!("mtllib m.mtl\nusemtl plain\n{QUAD}")).unwrap();
    let run = convert(&obj, &out, &[]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    let blob = std::fs::read(&out).unwrap();
    assert!(PackedMesh::parse(&blob).unwrap().texture().is_none());
}

/// Converts expecting exit code 1 and one `error: FILE: ...` line containing `needle`; the
/// existing output must be untouched and nothing else left in the directory.
fn fails(dir: &Path, obj: &Path, extra: &[&str], file: &Path, needle: &str) {
    let out = dir.join("out.rmsh");
    std::fs::write(&out, b"old").unwrap();
    let before: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    let run = convert(obj, &out, extra);
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{extra:?}: {stderr}");
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "{stderr}");
    let want = format!("error: {}: ", file.display());
    assert!(
        errors[0].starts_with(&want),
        "`{}`, want `{want}`",
        errors[0]
    );
    assert!(
        errors[0].contains(needle),
        "`{}` lacks `{needle}`",
        errors[0]
    );
    assert_eq!(std::fs::read(&out).unwrap(), b"old");
    let after: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(before.len(), after.len(), "{after:?}");
}

#[test]
fn texture_errors_name_the_fix_and_write_nothing() {
    let dir = scratch("errors");
    let obj = dir.join("q.obj");
    std::fs::write(&obj, QUAD).unwrap();
    let arg = |p: &Path| p.to_str().unwrap().to_owned();

    let missing = dir.join("missing.png");
    fails(
        &dir,
        &obj,
        &["--texture", &arg(&missing)],
        &missing,
        "texture file not found",
    );

    let odd = dir.join("odd.png");
    write_png(&odd, 6, 4, |_, _| [1, 2, 3]);
    fails(
        &dir,
        &obj,
        &["--texture", &arg(&odd)],
        &odd,
        "6x4: texture sides must be powers of two; --texture-size N",
    );
    let wide = dir.join("wide.png");
    write_png(&wide, 2048, 1, |_, _| [1, 2, 3]);
    fails(
        &dir,
        &obj,
        &["--texture", &arg(&wide)],
        &wide,
        "at most 1024; --texture-size N",
    );
    for bad in ["100", "0", "2048"] {
        fails(
            &dir,
            &obj,
            &["--texture", &arg(&odd), "--texture-size", bad],
            &odd,
            "--texture-size: texture size",
        );
    }
    let not_png = dir.join("not.png");
    std::fs::write(&not_png, b"GIF89a").unwrap();
    fails(
        &dir,
        &obj,
        &["--texture", &arg(&not_png)],
        &not_png,
        "not a readable PNG",
    );

    // A texture for a mesh without texture coordinates, or with them dropped.
    let plain = dir.join("plain.obj");
    std::fs::write(&plain, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let good = dir.join("good.png");
    write_png(&good, 2, 2, |_, _| [1, 2, 3]);
    fails(
        &dir,
        &plain,
        &["--texture", &arg(&good)],
        &plain,
        "has none",
    );
    fails(&dir, &plain, &["--texture-size", "4"], &plain, "no texture");

    // The material's texture missing.
    std::fs::write(dir.join("m.mtl"), "newmtl a\nmap_Kd gone.png\n").unwrap();
    let with_mtl = dir.join("mtl.obj");
    std::fs::write(&with_mtl, format!("mtllib m.mtl\nusemtl a\n{QUAD}")).unwrap();
    fails(
        &dir,
        &with_mtl,
        &[],
        &dir.join("gone.png"),
        "texture file not found (named by `map_Kd`",
    );

    // Resampled, the odd and the wide images convert.
    for png in [&odd, &wide] {
        let out = dir.join("ok.rmsh");
        let run = convert(&obj, &out, &["--texture", &arg(png), "--texture-size", "8"]);
        assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
        let blob = std::fs::read(&out).unwrap();
        let tex = PackedMesh::parse(&blob).unwrap().texture().unwrap();
        assert_eq!(
            (tex.width(), tex.height(), tex.texel(7, 7)),
            (8, 8, rgb565([1.0, 2.0, 3.0]))
        );
    }
}
