//! Runs the `convert` command end to end: every shared model converts, bad input fails with the
//! file and line and writes nothing, odd input warns and converts, and what is written reads back
//! within the stated error.

use rasterizer_core::mesh::FLAG_U32_INDICES;
use rasterizer_core::prelude::*;
use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

#[path = "support/convert.rs"]
mod support;
use support::{convert, models, scratch_in, text};

fn scratch(name: &str) -> PathBuf {
    scratch_in("convert", name)
}

/// The number after `key` in the summary line.
fn figure(stdout: &str, key: &str) -> f64 {
    let rest = stdout
        .split(key)
        .nth(1)
        .unwrap_or_else(|| panic!("no `{key}` in {stdout}"));
    let word: String = rest
        .trim_start()
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '+'))
        .collect();
    word.parse()
        .unwrap_or_else(|_| panic!("`{word}` after `{key}`"))
}

/// The summary's "a -> b triangles" figures.
fn counts(stdout: &str, what: &str) -> (usize, usize) {
    let before = stdout.split(&format!(" {what}")).next().unwrap();
    let mut words = before.rsplit(' ');
    let out = words.next().unwrap().parse().unwrap();
    assert_eq!(words.next(), Some("->"));
    let inp = words.next().unwrap().parse().unwrap();
    (inp, out)
}

/// Converts `obj` (written to a temp file) expecting success; returns the blob, stdout, stderr.
fn convert_text(name: &str, obj: &[u8], extra: &[&str]) -> (Vec<u8>, String, String) {
    let dir = scratch(name);
    let input = dir.join(format!("{name}.obj"));
    std::fs::write(&input, obj).unwrap();
    let out = dir.join("out.rmsh");
    let run = convert(&input, &out, extra);
    let (stdout, stderr) = (text(&run.stdout), text(&run.stderr));
    assert_eq!(run.status.code(), Some(0), "{stdout}\n{stderr}");
    let blob = std::fs::read(&out).unwrap();
    PackedMesh::parse(&blob).unwrap();
    (blob, stdout, stderr)
}

/// Converts `obj` expecting an error at `line` mentioning `needle`, and no output at all.
fn bad(name: &str, obj: &[u8], line: usize, needle: &str) {
    bad_with(name, obj, &[], line, needle);
}

fn bad_with(name: &str, obj: &[u8], extra: &[&str], line: usize, needle: &str) {
    let dir = scratch(name);
    let input = dir.join(format!("{name}.obj"));
    std::fs::write(&input, obj).unwrap();
    let out = dir.join("out.rmsh");
    let run = convert(&input, &out, extra);
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{name}: {stderr}");
    let want = format!("error: {}:{line}: ", input.display());
    let error = stderr
        .lines()
        .find(|l| l.starts_with("error:"))
        .unwrap_or_else(|| panic!("{name}: no error line in {stderr}"));
    assert!(error.starts_with(&want), "{name}: `{error}`, want `{want}`");
    assert!(error.contains(needle), "{name}: `{error}` lacks `{needle}`");
    assert!(run.stdout.is_empty(), "{name}: {}", text(&run.stdout));
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        left.len(),
        1,
        "{name}: only the input may be left: {left:?}"
    );
}

/// The `v` lines of an OBJ text as f32 (what tobj reads), widened.
fn obj_positions(obj: &str) -> Vec<[f64; 3]> {
    obj.lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .take(3)
                .map(|w| f64::from(w.parse::<f32>().unwrap()))
                .collect();
            [v[0], v[1], v[2]]
        })
        .collect()
}

fn decoded_positions(m: &PackedMesh) -> Vec<[f64; 3]> {
    (0..m.vertices())
        .map(|i| m.position_bits(i).unwrap().map(|b| f64::from(b) / 65536.0))
        .collect()
}

fn decoded_normals(m: &PackedMesh) -> Vec<[f64; 3]> {
    (0..m.vertices())
        .map(|i| m.normal_bits(i).unwrap().map(|b| f64::from(b) / 65536.0))
        .collect()
}

fn max_diff(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max)
}

#[test]
fn every_shared_model_converts() {
    let mut names: Vec<PathBuf> = std::fs::read_dir(models())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "obj"))
        .collect();
    names.sort();
    assert!(names.len() >= 15, "{names:?}");
    let dir = scratch("models");
    for path in &names {
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        for (k, extra) in [&[][..], &["--center-unit-sphere", "--weld"][..]]
            .iter()
            .enumerate()
        {
            let out = dir.join(format!("{stem}-{k}.rmsh"));
            let started = Instant::now();
            let run = convert(path, &out, extra);
            let took = started.elapsed();
            let (stdout, stderr) = (text(&run.stdout), text(&run.stderr));
            assert_eq!(run.status.code(), Some(0), "{stem}: {stderr}");
            assert_eq!(stdout.lines().count(), 1, "{stem}: {stdout}");
            assert!(
                stderr.lines().all(|l| l.starts_with("warning: ")),
                "{stem}: {stderr}"
            );
            let blob = std::fs::read(&out).unwrap();
            let mesh = PackedMesh::parse(&blob).unwrap();
            assert_eq!(counts(&stdout, "triangles").1, mesh.triangles(), "{stem}");
            assert_eq!(counts(&stdout, "vertices").1, mesh.vertices(), "{stem}");
            assert!(stdout.contains(&format!("{} bytes", blob.len())), "{stem}");
            if stem == "stanford-bunny" && k == 0 {
                eprintln!("stanford-bunny converted in {took:?}");
                assert!(took.as_secs() < 20, "{took:?}");
            }
        }
    }
}

#[test]
fn figures_match_the_model_notes() {
    let dir = scratch("notes");
    // (file, triangles, unused vertices) from LICENSES.md.
    for (name, tris, unused) in [
        ("suzanne.obj", 968, 0),
        ("teapot.obj", 6320, 0),
        ("spot_control_mesh.obj", 372, 0),
        ("uvsphere.obj", 960, 0),
        ("stanford-bunny-res3.obj", 3851, 2),
        ("stanford-bunny.obj", 69451, 1113),
    ] {
        let run = convert(&models().join(name), &dir.join("out"), &[]);
        let stdout = text(&run.stdout);
        assert_eq!(
            counts(&stdout, "triangles"),
            (tris, tris),
            "{name}: {stdout}"
        );
        assert_eq!(figure(&stdout, "and") as usize, unused, "{name}: {stdout}");
    }
}

#[test]
fn weld_merges_the_teapot_seams() {
    let dir = scratch("weld");
    let run = convert(&models().join("teapot.obj"), &dir.join("t"), &["--weld"]);
    let stdout = text(&run.stdout);
    assert_eq!(counts(&stdout, "vertices"), (3644, 3644 - 403), "{stdout}");
    assert!(stdout.contains("; 403 welded;"), "{stdout}");
}

#[test]
fn flat_normals_split_and_weld_rejoins() {
    let dir = scratch("flat");
    let cube = models().join("unit_cube.obj");
    let out = dir.join("c");
    let run = convert(&cube, &out, &["--normals", "flat"]);
    assert_eq!(counts(&text(&run.stdout), "vertices"), (8, 36));
    let blob = std::fs::read(&out).unwrap();
    let mesh = PackedMesh::parse(&blob).unwrap();
    let p = decoded_positions(&mesh);
    let n = decoded_normals(&mesh);
    for t in 0..mesh.triangles() {
        let [a, b, c] = mesh.triangle_indices(t).unwrap().map(|i| i as usize);
        let (e, f) = (
            [0, 1, 2].map(|k| p[b][k] - p[a][k]),
            [0, 1, 2].map(|k| p[c][k] - p[a][k]),
        );
        let x = [
            e[1] * f[2] - e[2] * f[1],
            e[2] * f[0] - e[0] * f[2],
            e[0] * f[1] - e[1] * f[0],
        ];
        // The unit cube's triangles have half unit area: the cross product is the unit normal.
        for v in [a, b, c] {
            assert!(
                max_diff(x, n[v]) < 1e-4,
                "triangle {t}: {x:?} vs {:?}",
                n[v]
            );
        }
    }
    let run = convert(&cube, &out, &["--normals", "flat", "--weld"]);
    assert_eq!(counts(&text(&run.stdout), "vertices"), (8, 24));
}

#[test]
fn positions_and_normals_round_trip() {
    for (name, extra) in [
        ("suzanne.obj", &[][..]),
        ("suzanne.obj", &["--center-unit-sphere"][..]),
        ("spot_control_mesh.obj", &["--center-unit-sphere"][..]),
        ("cube_textured.obj", &[][..]),
        ("stanford-bunny-res3.obj", &["--normals", "none"][..]),
    ] {
        let src = std::fs::read_to_string(models().join(name)).unwrap();
        let (blob, stdout, _) = convert_text("roundtrip", src.as_bytes(), extra);
        let mesh = PackedMesh::parse(&blob).unwrap();
        let stated = figure(&stdout, "max quantisation error");
        let mut want = obj_positions(&src);
        if extra.contains(&"--center-unit-sphere") {
            // The test's own centring: box centre, then the farthest vertex at distance 1.
            let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
            for p in &want {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            let c = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
            let r = want
                .iter()
                .map(|p| (0..3).map(|k| (p[k] - c[k]).powi(2)).sum::<f64>().sqrt())
                .fold(0.0, f64::max);
            for p in &mut want {
                *p = [0, 1, 2].map(|k| (p[k] - c[k]) / r);
            }
        }
        // Every written vertex is within the stated error of a vertex of the file.
        let got = decoded_positions(&mesh);
        let mut worst = 0f64;
        for g in &got {
            let d = want
                .iter()
                .map(|w| max_diff(*g, *w))
                .fold(f64::MAX, f64::min);
            worst = worst.max(d);
        }
        assert!(worst <= stated * 1.001 + 1e-9, "{name}: {worst} > {stated}");
        // The bound of the format: half a quantum plus a 16.16 rounding, per axis.
        assert!(stated <= 2e-5 * want.iter().flatten().fold(1.0, |m: f64, c| m.max(c.abs())));
        // Every vertex of these (fully used) files is written (Suzanne has two at one position).
        if name != "stanford-bunny-res3.obj" {
            for (i, w) in want.iter().enumerate() {
                let d = got
                    .iter()
                    .map(|g| max_diff(*g, *w))
                    .fold(f64::MAX, f64::min);
                assert!(
                    d <= stated * 1.001 + 1e-9,
                    "{name}: vertex {i} went missing"
                );
            }
        }
        assert_eq!(counts(&stdout, "triangles").1, mesh.triangles());
        // The cube's kept normals are its face normals, within the stated error, and each
        // vertex lies on the face its normal belongs to.
        if extra.is_empty() && name == "cube_textured.obj" {
            let stated_n = figure(&stdout, ", normals");
            assert!(stated_n <= 0.5 / 32767.0 + 0.5 / 65536.0, "{stated_n}");
            for (p, n) in got.iter().zip(decoded_normals(&mesh)) {
                let k = (0..3).find(|&k| n[k].abs() > 0.5).unwrap();
                let mut face = [0.0; 3];
                face[k] = n[k].signum();
                assert!(max_diff(n, face) <= stated_n, "{n:?}");
                assert_eq!(p[k], face[k], "{p:?} is not on the face of {n:?}");
            }
        }
    }
}

#[test]
fn kept_normals_match_the_file() {
    let src = std::fs::read_to_string(models().join("suzanne.obj")).unwrap();
    let file: Vec<[f64; 3]> = src
        .lines()
        .filter_map(|l| l.strip_prefix("vn "))
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
            let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            [v[0] / len, v[1] / len, v[2] / len]
        })
        .collect();
    let (blob, stdout, _) = convert_text("keep", src.as_bytes(), &["--normals", "keep"]);
    let stated = figure(&stdout, ", normals");
    // Half a quantum of 1/32767 plus a 16.16 rounding, and f32 parsing.
    assert!(stated <= 0.5 / 32767.0 + 0.5 / 65536.0 + 1e-6, "{stated}");
    let mesh = PackedMesh::parse(&blob).unwrap();
    for n in decoded_normals(&mesh) {
        let best = file
            .iter()
            .map(|f| max_diff(n, *f))
            .fold(f64::MAX, f64::min);
        assert!(best <= stated + 1e-6, "{n:?}: {best}");
    }
}

#[test]
fn smooth_normals_of_a_sphere_point_outwards() {
    let src = std::fs::read_to_string(models().join("icosphere.obj")).unwrap();
    let (blob, _, _) = convert_text("smooth", src.as_bytes(), &["--normals", "smooth"]);
    let mesh = PackedMesh::parse(&blob).unwrap();
    let p = decoded_positions(&mesh);
    for (i, n) in decoded_normals(&mesh).into_iter().enumerate() {
        let len = (0..3).map(|k| p[i][k] * p[i][k]).sum::<f64>().sqrt();
        let d = max_diff(n, p[i].map(|c| c / len));
        assert!(d < 0.02, "vertex {i}: {n:?} vs {:?}", p[i]);
    }
}

/// Twice the signed area of 2D triangle `a b c`.
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Even-odd point-in-polygon.
fn inside(poly: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut inside = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
        {
            inside = !inside;
        }
    }
    inside
}

#[test]
fn concave_polygons_are_triangulated_inside() {
    for (name, area, tris) in [
        ("concave_polygon.obj", 3.0, 4),
        ("concave_quad.obj", 1.3, 2),
    ] {
        let src = std::fs::read_to_string(models().join(name)).unwrap();
        let poly: Vec<[f64; 2]> = obj_positions(&src).iter().map(|p| [p[0], p[1]]).collect();
        let (blob, stdout, _) = convert_text("concave", src.as_bytes(), &[]);
        let stated = figure(&stdout, "max quantisation error");
        let mesh = PackedMesh::parse(&blob).unwrap();
        assert_eq!(mesh.triangles(), tris, "{name}");
        let p: Vec<[f64; 2]> = decoded_positions(&mesh)
            .iter()
            .map(|p| [p[0], p[1]])
            .collect();
        let mut total = 0.0;
        for t in 0..mesh.triangles() {
            let [a, b, c] = mesh.triangle_indices(t).unwrap().map(|i| p[i as usize]);
            let twice = orient(a, b, c);
            assert!(twice > 0.0, "{name}: triangle {t} is not counter-clockwise");
            total += twice / 2.0;
            // Its centroid and edge midpoints (nudged towards the centroid) lie in the polygon.
            let g = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
            assert!(inside(&poly, g), "{name}: triangle {t} is outside");
            for (u, v) in [(a, b), (b, c), (c, a)] {
                let m = [
                    (u[0] + v[0]) / 2.0 * 0.99 + g[0] * 0.01,
                    (u[1] + v[1]) / 2.0 * 0.99 + g[1] * 0.01,
                ];
                assert!(
                    inside(&poly, m),
                    "{name}: triangle {t} crosses the boundary"
                );
            }
        }
        assert!(
            (total - area).abs() < 8.0 * stated + 1e-9,
            "{name}: area {total}"
        );
    }
}

#[test]
fn rust_output_holds_the_same_bytes() {
    let dir = scratch("rust");
    let input = models().join("suzanne.obj");
    let bin = dir.join("suzanne.rmsh");
    let rs = dir.join("suzanne_mesh.rs");
    assert_eq!(convert(&input, &bin, &[]).status.code(), Some(0));
    assert_eq!(convert(&input, &rs, &["--rust"]).status.code(), Some(0));
    let src = std::fs::read_to_string(&rs).unwrap();
    assert!(
        src.contains("pub static SUZANNE_MESH: [u8; "),
        "{}",
        &src[..400]
    );
    assert!(src.contains("\n/// Packed mesh"));
    let bytes = host_tools::convert::bytes_from_rust_source(&src).unwrap();
    assert_eq!(bytes, std::fs::read(&bin).unwrap());
    let named = dir.join("named.rs");
    assert_eq!(
        convert(&input, &named, &["--rust", "--name", "MONKEY"])
            .status
            .code(),
        Some(0)
    );
    assert!(std::fs::read_to_string(&named)
        .unwrap()
        .contains("pub static MONKEY: [u8; "));
}

#[test]
fn adjacency_flag_writes_version_3_in_both_outputs() {
    let dir = scratch("adjacency");
    // Per-face texture coordinates and normals: every corner a vertex of its own, and still a
    // closed surface.
    let input = models().join("cube_textured.obj");
    let plain = dir.join("plain.rmsh");
    let bin = dir.join("cube.rmsh");
    let rs = dir.join("cube.rs");
    assert_eq!(convert(&input, &plain, &[]).status.code(), Some(0));
    let run = convert(&input, &bin, &["--adjacency"]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    assert!(
        text(&run.stdout).contains("adjacency (0 edges without a neighbour)"),
        "{}",
        text(&run.stdout)
    );
    let blob = std::fs::read(&bin).unwrap();
    let without = std::fs::read(&plain).unwrap();
    assert_eq!((without[4], blob[4]), (2, 3), "versions");
    let mesh = PackedMesh::parse(&blob).unwrap();
    assert!(mesh.has_adjacency() && !PackedMesh::parse(&without).unwrap().has_adjacency());
    for t in 0..mesh.triangles() {
        let n = mesh.neighbour_indices(t).unwrap();
        assert!(
            n.iter().all(|&u| (u as usize) < mesh.triangles()),
            "{t}: {n:?}"
        );
    }
    assert_eq!(
        convert(&input, &rs, &["--rust", "--adjacency"])
            .status
            .code(),
        Some(0)
    );
    let src = std::fs::read_to_string(&rs).unwrap();
    assert!(
        src.contains("(format v3)") && src.contains("adjacency, "),
        "{src}"
    );
    assert_eq!(
        host_tools::convert::bytes_from_rust_source(&src).unwrap(),
        blob
    );
}

#[test]
fn many_vertices_use_32_bit_indices() {
    // A 265 x 265 grid: 70,225 vertices.
    let n = 265;
    let mut obj = String::new();
    for y in 0..n {
        for x in 0..n {
            obj += &format!("v {x} {y} 0\n");
        }
    }
    for y in 0..n - 1 {
        for x in 0..n - 1 {
            let i = y * n + x + 1;
            obj += &format!("f {} {} {} {}\n", i, i + 1, i + n + 1, i + n);
        }
    }
    let (blob, stdout, _) = convert_text("wide", obj.as_bytes(), &["--normals", "none"]);
    let mesh = PackedMesh::parse(&blob).unwrap();
    assert_eq!(mesh.vertices(), n * n);
    assert_eq!(mesh.triangles(), 2 * (n - 1) * (n - 1));
    assert_ne!(u16::from_le_bytes([blob[6], blob[7]]) & FLAG_U32_INDICES, 0);
    assert_eq!(counts(&stdout, "triangles").1, mesh.triangles());
}

#[test]
fn usage_errors_exit_2() {
    let bin = env!("CARGO_BIN_EXE_host-tools");
    let model = models().join("single_triangle.obj");
    let dir = scratch("usage");
    let out = dir.join("o");
    for args in [
        vec!["convert".to_owned(), model.display().to_string()],
        vec![
            "convert".into(),
            model.display().to_string(),
            "-o".into(),
            out.display().to_string(),
            "--normals".into(),
            "sideways".into(),
        ],
        vec![
            "convert".into(),
            model.display().to_string(),
            "-o".into(),
            out.display().to_string(),
            "--rust".into(),
            "--name".into(),
            "not an ident".into(),
        ],
    ] {
        let run = Command::new(bin).args(&args).output().unwrap();
        assert_eq!(run.status.code(), Some(2), "{args:?}");
        assert!(!out.exists());
    }
}

#[test]
fn missing_input_is_a_conversion_error() {
    let dir = scratch("missing");
    let input = dir.join("nothing.obj");
    let run = convert(&input, &dir.join("out"), &[]);
    assert_eq!(run.status.code(), Some(1));
    assert!(text(&run.stderr).starts_with(&format!("error: {}: ", input.display())));
    assert!(!dir.join("out").exists());
}

const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

#[test]
fn bad_nan_coordinate() {
    bad(
        "nan",
        b"v 0 0 0\nv 1 0 0\nv nan 0 0\nf 1 2 3\n",
        3,
        "not finite",
    );
}

#[test]
fn bad_infinite_coordinate() {
    bad(
        "inf",
        b"v 0 0 0\n# c\nv 1 -inf 0\nv 0 1 0\nf 1 2 3\n",
        3,
        "not finite",
    );
    bad(
        "overflow",
        b"v 0 0 0\nv 1 0 1e39\nv 0 1 0\nf 1 2 3\n",
        2,
        "absurdly large",
    );
}

#[test]
fn bad_absurdly_large_coordinate() {
    let obj = b"v 0 0 0\nv 2e6 0 0\nv 0 1 0\nf 1 2 3\n";
    bad_with(
        "absurd",
        obj,
        &["--center-unit-sphere"],
        2,
        "absurdly large",
    );
}

#[test]
fn bad_coordinate_beyond_16_16() {
    bad(
        "fx16",
        b"v 0 0 0\nv 1 0 0\nv 0 40000 0\nf 1 2 3\n",
        3,
        "16.16",
    );
    // Rescaled, the same file is fine.
    convert_text(
        "fx16-ok",
        b"v 0 0 0\nv 1 0 0\nv 0 40000 0\nf 1 2 3\n",
        &["--center-unit-sphere"],
    );
}

#[test]
fn bad_index_zero() {
    bad("zero", format!("{TRI}f 1 0 2\n").as_bytes(), 4, "index 0");
    bad(
        "zero-vn",
        format!("{TRI}vn 0 0 1\nf 1//1 2//0 3//1\n").as_bytes(),
        5,
        "index 0",
    );
}

#[test]
fn bad_index_out_of_range() {
    bad(
        "range",
        format!("{TRI}\nf 1 2 3\nf 1 2 4\n").as_bytes(),
        6,
        "vertex 4",
    );
    bad("relative", format!("{TRI}f -1 -2 -4\n").as_bytes(), 4, "-4");
    bad(
        "vn-range",
        format!("{TRI}vn 0 0 1\nf 1//1 2//2 3//1\n").as_bytes(),
        5,
        "normal 2",
    );
    bad(
        "vt-range",
        format!("{TRI}vt 0 0\nf 1/1 2/3 3/1\n").as_bytes(),
        5,
        "texture",
    );
}

#[test]
fn bad_face_tokens() {
    for (i, f) in [
        "f 1 2 x",
        "f 1/2/3/4 2 3",
        "f 1 2 3/",
        "f 1 2 1.5",
        "f /1 2 3",
    ]
    .iter()
    .enumerate()
    {
        bad(
            &format!("token{i}"),
            format!("{TRI}{f}\n").as_bytes(),
            4,
            "malformed",
        );
    }
    bad("short", format!("{TRI}f 1 2\n").as_bytes(), 4, "at least 3");
    bad(
        "vertex",
        b"v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n",
        2,
        "malformed vertex",
    );
    bad("w", b"v 0 0 0\nv 1 0 0 0\nv 0 1 0\nf 1 2 3\n", 2, "w = 0");
}

#[test]
fn bad_empty_file() {
    bad("empty", b"", 1, "empty file");
    bad("blank", b"\n  \n\t\n", 1, "empty file");
}

#[test]
fn bad_no_faces() {
    bad("nofaces", TRI.as_bytes(), 3, "no faces");
    bad("comments", b"# nothing\n# here\n", 2, "no faces");
}

#[test]
fn bad_not_utf8() {
    bad(
        "latin1",
        b"v 0 0 0\nv 1 0 0\n# caf\xe9\nv 0 1 0\nf 1 2 3\n",
        3,
        "UTF-8",
    );
}

#[test]
fn bad_only_degenerate_triangles() {
    let dir = scratch("degenerate");
    let input = dir.join("d.obj");
    std::fs::write(&input, "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n").unwrap();
    let run = convert(&input, &dir.join("out"), &[]);
    assert_eq!(run.status.code(), Some(1));
    assert!(text(&run.stderr).contains("degenerate"));
    assert!(!dir.join("out").exists());
}

fn warned(stderr: &str, line: usize, needle: &str) {
    assert!(
        stderr.lines().any(|l| l.starts_with("warning: ")
            && l.contains(&format!(".obj:{line}: "))
            && l.contains(needle)),
        "no warning at line {line} with `{needle}` in:\n{stderr}"
    );
}

#[test]
fn bare_cr_line_endings_are_read() {
    let (blob, _, stderr) = convert_text(
        "cr",
        b"v 0 0 0\rv 1 0 0\rv 0 1 0\rv 1 1 0\rf 1 2 4 3\r",
        &[],
    );
    warned(&stderr, 1, "bare CR");
    let mesh = PackedMesh::parse(&blob).unwrap();
    assert_eq!((mesh.vertices(), mesh.triangles()), (4, 2));
}

#[test]
fn crlf_warns_and_converts() {
    let (blob, _, stderr) =
        convert_text("crlf", b"v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n", &[]);
    warned(&stderr, 1, "CRLF");
    assert_eq!(PackedMesh::parse(&blob).unwrap().triangles(), 1);
}

#[test]
fn byte_order_mark_keeps_the_first_vertex() {
    let (blob, stdout, stderr) = convert_text(
        "bom",
        b"\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        &[],
    );
    warned(&stderr, 1, "byte-order mark");
    let mesh = PackedMesh::parse(&blob).unwrap();
    assert_eq!((mesh.vertices(), mesh.triangles()), (3, 1));
    assert_eq!(counts(&stdout, "vertices"), (3, 3));
    let mut p = decoded_positions(&mesh);
    p.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(p, vec![[0.0; 3], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]);
}

#[test]
fn unknown_keyword_warns() {
    let (blob, _, stderr) = convert_text(
        "unknown",
        format!("{TRI}frobnicate 1 2\nf 1 2 3\n").as_bytes(),
        &[],
    );
    warned(&stderr, 4, "unknown keyword `frobnicate`");
    assert_eq!(PackedMesh::parse(&blob).unwrap().triangles(), 1);
}

#[test]
fn missing_material_library_warns() {
    let obj = format!("mtllib nowhere.mtl\n{TRI}usemtl red\nf 1 2 3\n");
    let (blob, _, stderr) = convert_text("mtl", obj.as_bytes(), &[]);
    warned(&stderr, 1, "nowhere.mtl");
    assert_eq!(PackedMesh::parse(&blob).unwrap().triangles(), 1);
}

#[test]
fn polylines_are_ignored_with_a_warning() {
    let obj = format!("{TRI}v 1 1 0\nl 1 2 4 3\nf 1 2 3\n");
    let (blob, stdout, stderr) = convert_text("lines", obj.as_bytes(), &[]);
    warned(&stderr, 5, "`l` polyline ignored");
    let mesh = PackedMesh::parse(&blob).unwrap();
    assert_eq!(
        mesh.triangles(),
        1,
        "the polyline must not become a filled quad"
    );
    assert_eq!(counts(&stdout, "vertices"), (4, 3));
}

#[test]
fn mixed_texcoord_faces_warn_and_convert() {
    let obj = format!("{TRI}v 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n");
    let (blob, _, stderr) = convert_text("mixed", obj.as_bytes(), &[]);
    warned(&stderr, 7, "texture coordinates");
    assert_eq!(PackedMesh::parse(&blob).unwrap().triangles(), 2);
}

#[test]
fn mixed_normal_faces_fall_back_to_smooth() {
    let obj = format!("{TRI}v 1 1 0\nvn 0 0 -1\nf 1//1 2//1 3//1\nf 2 4 3\n");
    let (blob, stdout, stderr) = convert_text("mixedn", obj.as_bytes(), &[]);
    warned(&stderr, 7, "normals");
    assert!(stdout.contains("smooth normals"), "{stdout}");
    let mesh = PackedMesh::parse(&blob).unwrap();
    for n in decoded_normals(&mesh) {
        assert_eq!(n, [0.0, 0.0, 1.0]);
    }
}

#[test]
fn clean_models_print_nothing_on_stderr() {
    let dir = scratch("clean");
    let run = convert(&models().join("suzanne.obj"), &dir.join("s"), &[]);
    assert_eq!(run.status.code(), Some(0));
    assert!(run.stderr.is_empty(), "{}", text(&run.stderr));
}
