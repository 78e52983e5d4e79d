//! `--bands N`: a scene drawn through the frame list, band by band, is the whole-frame picture
//! pixel for pixel: every example scene in bands of 1, 7 and 16 rows, every pixel format with
//! each kind of mesh (translucent, dithered, fogged, wireframe, with and without depth) and each
//! kind of shape (clipped, translucent), and the commands `render`, `animate` and the refusal of
//! `--bands 0`.

use host_tools::scenefile::{load, render_frame, PixelFormat, Pose, Scene};
use rasterizer_core::math::Angle;
use std::path::{Path, PathBuf};

#[path = "support/cli.rs"]
mod cli;
use cli::{assert_no_panic, assert_ok, run, s, scratch_in, text};

fn assets() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets")
}

/// The RGB pixels of a frame at scale 1, whole (`None`) or in bands.
fn pixels(scene: &Scene, pose: Pose, bands: Option<u32>) -> (u32, u32, Vec<u8>) {
    let (image, _) = render_frame(scene, pose, 1, bands)
        .unwrap_or_else(|e| panic!("{} (bands {bands:?}): {e}", scene.path.display()));
    let buf = image.as_image_buffer();
    (buf.width(), buf.height(), buf.as_raw().to_vec())
}

/// Checks that `scene` in bands of each of `rows` is the whole frame; a difference names the
/// first differing pixel and writes both pictures to a scratch directory.
fn assert_banded_same(scene: &Scene, what: &str, pose: Pose, rows: &[u32]) {
    let (w, h, whole) = pixels(scene, pose, None);
    for &r in rows {
        let (bw, bh, banded) = pixels(scene, pose, Some(r));
        assert_eq!((bw, bh), (w, h), "{what}: size in bands of {r}");
        if banded == whole {
            continue;
        }
        let differ: Vec<usize> = (0..whole.len() / 3)
            .filter(|&i| whole[3 * i..3 * i + 3] != banded[3 * i..3 * i + 3])
            .collect();
        let dir = scratch_in("banded", "diff");
        let save = |name: &str, px: &[u8]| {
            let path = dir.join(name);
            image::RgbImage::from_raw(w, h, px.to_vec())
                .unwrap()
                .save(&path)
                .unwrap();
            path
        };
        let (a, b) = (save("whole.png", &whole), save("banded.png", &banded));
        panic!(
            "{what}: bands of {r} rows differ from the whole frame in {} pixels, the first at \
             ({}, {}); see {} and {}",
            differ.len(),
            differ[0] % w as usize,
            differ[0] / w as usize,
            a.display(),
            b.display()
        );
    }
}

fn example_scenes() -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(assets().join("scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    paths
}

/// Every example scene, in bands of one row, of 7 (which divides none of their heights) and of
/// 16 rows. Measured: about 4 s for all 24 in a debug build on 2 cores, 1-row bands included,
/// so every scene gets all three.
#[test]
fn every_example_scene_is_the_same_in_bands() {
    let scenes = example_scenes();
    assert!(scenes.len() >= 24, "only {} example scenes", scenes.len());
    for path in scenes {
        let scene = load(&path).unwrap();
        assert!(
            !scene.height.is_multiple_of(7),
            "{}: 7 divides the height",
            path.display()
        );
        let what = path.file_name().unwrap().to_string_lossy().into_owned();
        assert_banded_same(&scene, &what, Pose::default(), &[1, 7, 16]);
    }
}

/// A turned and tilted pose (`animate`, `view`) is the same in bands too.
#[test]
fn posed_meshes_are_the_same_in_bands() {
    for name in [
        "teapot.toml",
        "translucent_mesh.toml",
        "suzanne_wireframe.toml",
    ] {
        let scene = load(&assets().join("scenes").join(name)).unwrap();
        let pose = Pose {
            yaw: Angle::from_degrees(130),
            pitch: Angle::from_degrees(-25),
        };
        assert_banded_same(&scene, name, pose, &[9]);
    }
}

const FORMATS: [PixelFormat; 4] = [
    PixelFormat::Rgb565,
    PixelFormat::Rgb888,
    PixelFormat::Gray8,
    PixelFormat::Binary,
];

/// A scene of every kind of mesh, overlapping, in this order: opaque with depth, flat without
/// depth, dithered (at the output's depth, before a translucent mesh blends over it), fogged,
/// Phong with perspective-correct interpolation, translucent with and without depth, and
/// wireframes opaque and translucent.
fn mesh_scene(format: &str) -> String {
    let suzanne = assets().join("models/suzanne.obj");
    let mesh = |extra: &str, at: [f64; 3]| {
        format!(
            "[[meshes]]\npath = {:?}\ntranslate = [{}, {}, {}]\nscale = 0.6\n{extra}\n",
            suzanne.display(),
            at[0],
            at[1],
            at[2]
        )
    };
    [
        format!(
            "[output]\nwidth = 150\nheight = 100\nformat = \"{format}\"\nbackground = [30, 40, 60]\n\n\
             [camera]\neye = [0.0, 0.0, 4.0]\nfov = 55.0\n\n\
             [[lights]]\nkind = \"directional\"\ndirection = [1.0, 1.0, 1.0]\n"
        ),
        mesh("shading = \"gouraud\"", [-1.2, 0.5, 0.0]),
        mesh("shading = \"flat\"\ndepth = false\ncull = \"none\"", [-0.6, 0.4, -0.5]),
        mesh(
            "shading = \"gouraud\"\ndither = \"bayer8\"\ncolor = [200, 90, 40]",
            [0.0, 0.5, 0.0],
        ),
        mesh(
            "shading = \"gouraud\"\ndither = \"bayer4\"\nfog = { color = [30, 40, 60], start = 3.0, end = 6.0 }",
            [1.2, 0.5, -1.0],
        ),
        mesh(
            "shading = \"phong\"\nperspective_correct = true\nfog = { color = [30, 40, 60], start = 3.0, end = 7.0 }",
            [0.6, 0.4, -0.3],
        ),
        mesh("shading = \"gouraud\"\nopacity = 140", [-0.2, 0.3, 0.6]),
        mesh(
            "shading = \"none\"\ncolor = [250, 250, 120]\nopacity = 90\ndepth = false",
            [0.5, 0.2, 0.5],
        ),
        mesh("wireframe = true\ncolor = [255, 60, 60]", [-1.0, -0.7, 0.0]),
        mesh(
            "wireframe = true\ncolor = [60, 255, 120]\nopacity = 100\ncull = \"ccw\"",
            [0.9, -0.7, 0.0],
        ),
    ]
    .concat()
}

/// The pixel formats differ in how meshes reach them (`Rgb888` scenes take the mesh commands
/// straight into the list, the others through a layer that converts an `Rgb888` band), so
/// every kind of mesh is checked in every format.
#[test]
fn every_kind_of_mesh_in_every_format_is_the_same_in_bands() {
    let dir = scratch_in("banded", "meshes");
    for format in ["rgb565", "rgb888", "gray8", "binary"] {
        let path = dir.join(format!("meshes_{format}.toml"));
        std::fs::write(&path, mesh_scene(format)).unwrap();
        let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_banded_same(
            &scene,
            &format!("meshes in {format}"),
            Pose::default(),
            &[1, 7],
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// [`mesh_scene`] with every filled mesh anti-aliased (`antialias = true`): each band draws
/// them through `Pipeline::draw_antialiased`, sharing the list's depth buffer, in every format.
#[test]
fn antialiased_meshes_in_every_format_are_the_same_in_bands() {
    let dir = scratch_in("banded", "antialiased");
    for format in ["rgb565", "rgb888", "gray8", "binary"] {
        // Wireframes refuse the key: they keep their edges plain.
        let scene = mesh_scene(format)
            .split("[[meshes]]")
            .map(|m| {
                if m.contains("path") && !m.contains("wireframe") {
                    format!("{m}antialias = true\n")
                } else {
                    m.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("[[meshes]]");
        let path = dir.join(format!("antialiased_{format}.toml"));
        std::fs::write(&path, &scene).unwrap();
        let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
        let aa = scene.meshes.iter().filter(|m| m.antialias).count();
        assert_eq!(aa, 7, "{format}");
        assert_banded_same(
            &scene,
            &format!("anti-aliased meshes in {format}"),
            Pose::default(),
            &[1, 7],
        );
    }
    // A textured mesh, turned so that its silhouette crosses bands.
    let mut text = std::fs::read_to_string(assets().join("scenes/cube_textured.toml")).unwrap();
    text = text.replace("../", &format!("{}/", assets().display()));
    text.push_str("antialias = true\n");
    let path = dir.join("cube_textured_aa.toml");
    std::fs::write(&path, text).unwrap();
    let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.meshes[0].antialias);
    assert_banded_same(&scene, "anti-aliased textured cube", Pose::default(), &[7]);
    std::fs::remove_dir_all(&dir).ok();
}

/// The textured scenes in every format (they are Rgb565 files).
#[test]
fn textured_meshes_in_every_format_are_the_same_in_bands() {
    for name in ["cube_textured.toml", "spot_textured.toml"] {
        let mut scene = load(&assets().join("scenes").join(name)).unwrap();
        for format in FORMATS {
            scene.format = format;
            assert_banded_same(
                &scene,
                &format!("{name} in {format:?}"),
                Pose::default(),
                &[7],
            );
        }
    }
}

/// Every kind of shape four times: plain, translucent, clipped, and both; over a mesh, so the
/// blending reads the meshes' pixels.
fn shape_scene(format: &str) -> String {
    let suzanne = assets().join("models/suzanne.obj");
    let mut out = format!(
        "[output]\nwidth = 160\nheight = 130\nformat = \"{format}\"\nbackground = [20, 20, 30]\n\n\
         [[lights]]\nkind = \"directional\"\ndirection = [1.0, 1.0, 1.0]\n\n\
         [[meshes]]\npath = {:?}\nshading = \"gouraud\"\n\n",
        suzanne.display()
    );
    let kinds: [&dyn Fn(f64, f64) -> String; 9] = [
        &|x, y| {
            format!(
                "kind = \"point\"\nat = [{}, {}]\ncolor = [255, 255, 0]",
                x + 8.5,
                y + 4.5
            )
        },
        &|x, y| {
            format!(
                "kind = \"line\"\nfrom = [{x}, {y}]\nto = [{}, {}]\ncolor = [250, 120, 40]",
                x + 30.0,
                y + 11.0
            )
        },
        &|x, y| {
            format!(
                "kind = \"line\"\nfrom = [{x}, {}]\nto = [{}, {y}]\ncolors = [[255, 0, 0], [0, 90, 255]]",
                y + 12.0,
                x + 25.0
            )
        },
        &|x, y| {
            format!(
                "kind = \"line\"\nfrom = [{}, {}]\nto = [{}, {}]\ncolor = [120, 255, 200]\nantialias = true",
                x + 0.5,
                y + 0.5,
                x + 28.5,
                y + 9.5
            )
        },
        &|x, y| {
            format!(
                "kind = \"line\"\nfrom = [{}, {}]\nto = [{}, {}]\ncolor = [255, 200, 255]\nantialias = true\nwidth = 4",
                x + 2.5,
                y + 12.5,
                x + 26.5,
                y + 2.5
            )
        },
        &|x, y| {
            format!(
                "kind = \"outline\"\nvertices = [[{x}, {y}], [{}, {}], [{}, {}]]\ncolor = [255, 255, 255]",
                x + 28.0,
                y + 4.0,
                x + 9.0,
                y + 13.0
            )
        },
        &|x, y| {
            format!(
                "kind = \"triangle\"\nvertices = [[{}, {y}], [{}, {}], [{}, {}]]\ncolor = [60, 200, 90]",
                x + 0.3,
                x + 29.7,
                y + 2.2,
                x + 12.1,
                y + 13.9
            )
        },
        &|x, y| {
            format!(
                "kind = \"triangle\"\nvertices = [[{x}, {}], [{}, {y}], [{}, {}]]\ncolors = [[255, 0, 0], [0, 255, 0], [0, 0, 255]]",
                y + 13.0,
                x + 15.5,
                x + 29.0,
                y + 12.5
            )
        },
        &|x, y| {
            format!(
                "kind = \"polygon\"\nvertices = [[{x}, {y}], [{}, {}], [{}, {y}], [{}, {}], [{}, {}]]\nfill_rule = \"non_zero\"\ncolor = [90, 140, 255]",
                x + 29.0,
                y + 13.0,
                x + 29.0,
                x + 2.0,
                y + 13.0,
                x + 15.0,
                y - 3.0
            )
        },
    ];
    // A wide diagonal line reaches w / sqrt 2 beyond its segment in y (rasterizer-core's
    // `wide_diagonal_aa_line_within_bounds`).
    out += "[[shapes]]\nkind = \"line\"\nfrom = [125.5, 60.5]\nto = [145.5, 80.5]\n\
            color = [255, 255, 255]\nantialias = true\nwidth = 24\nopacity = 200\n\n\
            [[shapes]]\nkind = \"line\"\nfrom = [20.5, 80.5]\nto = [40.5, 60.5]\n\
            color = [255, 128, 0]\nantialias = true\nwidth = 30\n";
    for (k, kind) in kinds.iter().enumerate() {
        for variant in 0..4 {
            let (x, y) = (2.0 + 40.0 * variant as f64, 2.0 + 14.0 * k as f64);
            out += "[[shapes]]\n";
            out += &kind(x, y);
            out += "\n";
            if variant % 2 == 1 {
                out += "opacity = 150\n";
            }
            if variant >= 2 {
                // Cuts every shape across the middle, in both directions.
                out += &format!("clip = [{}, {}, 17, 9]\n", x as i32 + 5, y as i32 + 2);
            }
        }
    }
    out
}

#[test]
fn every_kind_of_shape_in_every_format_is_the_same_in_bands() {
    let dir = scratch_in("banded", "shapes");
    for format in ["rgb565", "rgb888", "gray8", "binary"] {
        let path = dir.join(format!("shapes_{format}.toml"));
        std::fs::write(&path, shape_scene(format)).unwrap();
        let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_banded_same(
            &scene,
            &format!("shapes in {format}"),
            Pose::default(),
            &[1, 5, 16],
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `render --bands` writes the same PNG, byte for byte; a band taller than the scene is one
/// band; `--bands 0` is refused before anything is written.
#[test]
fn render_with_bands_writes_the_same_png() {
    let dir = scratch_in("banded", "render");
    let scene = assets().join("scenes/suzanne_dither_binary.toml");
    let whole = dir.join("whole.png");
    assert_ok(&run(&["render", s(&scene), "-o", s(&whole)]), "render");
    let want = std::fs::read(&whole).unwrap();
    for rows in ["7", "100000"] {
        let png = dir.join(format!("bands_{rows}.png"));
        let o = run(&["render", s(&scene), "-o", s(&png), "--bands", rows]);
        assert_ok(&o, "render --bands");
        assert!(std::fs::read(&png).unwrap() == want, "--bands {rows}");
    }
    for bad in ["0", "-3", "seven", ""] {
        let png = dir.join("bad.png");
        let o = run(&[
            "render",
            s(&scene),
            "-o",
            s(&png),
            &format!("--bands={bad}"),
        ]);
        assert_no_panic(&o, &format!("--bands={bad}"));
        assert!(!o.status.success(), "--bands {bad} was accepted");
        let stderr = text(&o.stderr);
        assert!(
            stderr.starts_with("error:") && stderr.contains("--bands"),
            "--bands {bad}: {stderr}"
        );
        assert!(!png.exists(), "--bands {bad} wrote a file");
    }
    let o = run(&[
        "render",
        s(&scene),
        "-o",
        s(&dir.join("z.png")),
        "--bands",
        "0",
    ]);
    assert!(
        text(&o.stderr).contains("at least 1 row"),
        "{}",
        text(&o.stderr)
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `animate --bands` writes the same frames.
#[test]
fn animate_with_bands_writes_the_same_frames() {
    let dir = scratch_in("banded", "animate");
    let scene = assets().join("scenes/translucent_mesh.toml");
    let args = |out: &Path| {
        vec![
            "animate".to_string(),
            s(&scene).to_string(),
            "-o".to_string(),
            s(out).to_string(),
            "--frames".to_string(),
            "3".to_string(),
            "--png-sequence".to_string(),
            "--scale".to_string(),
            "1".to_string(),
        ]
    };
    let whole = args(&dir.join("whole.png"));
    let whole: Vec<&str> = whole.iter().map(String::as_str).collect();
    assert_ok(&run(&whole), "animate");
    let mut banded = args(&dir.join("banded.png"));
    banded.extend(["--bands".to_string(), "11".to_string()]);
    let banded: Vec<&str> = banded.iter().map(String::as_str).collect();
    assert_ok(&run(&banded), "animate --bands");
    for k in 0..3 {
        let a = std::fs::read(dir.join(format!("whole_{k:03}.png"))).unwrap();
        let b = std::fs::read(dir.join(format!("banded_{k:03}.png"))).unwrap();
        assert!(a == b, "frame {k} differs");
    }
    std::fs::remove_dir_all(&dir).ok();
}
