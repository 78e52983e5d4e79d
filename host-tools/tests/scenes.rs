//! The scene-file commands, run as the built binary: every example scene renders; bad scene
//! files fail with an `error:` line naming the file (and the line, for TOML errors) and write
//! nothing; `compare` finds fixed and floating point close on Suzanne; `animate` writes its frames.

use image::codecs::gif::GifDecoder;
use image::AnimationDecoder;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_host-tools"))
}

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes")
}

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("host-tools-scenes-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(o: &Output) -> (String, String) {
    (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn every_example_scene_renders() {
    let out = scratch("all");
    let mut count = 0;
    for entry in std::fs::read_dir(scenes_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        count += 1;
        let png = out.join(path.file_stem().unwrap()).with_extension("png");
        let o = bin()
            .arg("render")
            .arg(&path)
            .arg("-o")
            .arg(&png)
            .output()
            .unwrap();
        let (stdout, stderr) = text(&o);
        assert!(o.status.success(), "{}: {stdout}{stderr}", path.display());
        let bytes = std::fs::read(&png).unwrap();
        assert!(
            bytes.starts_with(b"\x89PNG"),
            "{}: not a PNG",
            path.display()
        );
        // Something was drawn: the picture is not one flat colour (which compresses to < 1 KB).
        assert!(
            bytes.len() > 1500,
            "{}: PNG of {} bytes",
            path.display(),
            bytes.len()
        );
    }
    assert!(count >= 16, "only {count} example scenes");
}

/// Runs `render` on a scene written into `dir` and checks it fails properly.
fn expect_failure(dir: &Path, name: &str, scene: &str, needles: &[&str]) {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, scene).unwrap();
    let png = dir.join(format!("{name}.png"));
    let o = bin()
        .arg("render")
        .arg(&path)
        .arg("-o")
        .arg(&png)
        .output()
        .unwrap();
    let (stdout, stderr) = text(&o);
    assert!(!o.status.success(), "{name}: succeeded: {stdout}");
    let first = stderr.lines().next().unwrap_or("");
    assert!(first.starts_with("error: "), "{name}: {stderr}");
    assert!(
        first.contains(&format!("{name}.toml")),
        "{name}: file not named: {stderr}"
    );
    for n in needles {
        assert!(stderr.contains(n), "{name}: `{n}` missing from: {stderr}");
    }
    assert!(!png.exists(), "{name}: wrote an output file");
}

const OUTPUT: &str = "[output]\nwidth = 32\nheight = 24\n";

#[test]
fn bad_scenes_fail_with_file_and_line() {
    let dir = scratch("bad");
    expect_failure(
        &dir,
        "unknown_key",
        &format!("{OUTPUT}colour = 3\n"),
        &["line 4", "unknown field `colour`"],
    );
    expect_failure(
        &dir,
        "unknown_render_key",
        &format!("{OUTPUT}[render]\nshading = \"phong\"\nshadow = true\n"),
        &["line 6", "unknown field `shadow`"],
    );
    expect_failure(
        &dir,
        "bad_shading",
        &format!("{OUTPUT}[render]\nshading = \"toon\"\n"),
        &["line 5", "unknown variant `toon`"],
    );
    expect_failure(
        &dir,
        "bad_colour",
        &format!("{OUTPUT}background = [0, 300, 0]\n"),
        &["line 4", "0 ..= 255"],
    );
    expect_failure(
        &dir,
        "bad_format",
        "[output]\nwidth = 32\nheight = 24\nformat = \"rgb444\"\n",
        &["line 4", "rgb444"],
    );
    expect_failure(
        &dir,
        "negative_size",
        "[output]\nwidth = -32\nheight = 24\n",
        &["line 2"],
    );
    expect_failure(
        &dir,
        "unknown_shape_key",
        &format!("{OUTPUT}\n[[shapes]]\nkind = \"line\"\nfrom = [0, 0]\nto = [5, 5]\ncolor = [1, 2, 3]\nthickness = 2\n"),
        &["line 5", "unknown field `thickness`"],
    );
    expect_failure(
        &dir,
        "line_without_colour",
        &format!("{OUTPUT}\n[[shapes]]\nkind = \"line\"\nfrom = [0, 0]\nto = [5, 5]\n"),
        &["line 5", "exactly one of `color` and `colors`"],
    );
    expect_failure(
        &dir,
        "near_after_far",
        &format!("{OUTPUT}[camera]\nnear = 5.0\nfar = 1.0\n"),
        &["[camera]", "near"],
    );
    expect_failure(
        &dir,
        "missing_mesh",
        &format!("{OUTPUT}\n[[meshes]]\npath = \"no_such_mesh.obj\"\n"),
        &["line 5", "no_such_mesh.obj", "cannot read mesh file"],
    );
    expect_failure(
        &dir,
        "broken_packed_mesh",
        &format!("{OUTPUT}\n[[meshes]]\npath = \"broken.rmsh\"\n"),
        &["line 5", "broken.rmsh"],
    );
    // The packed mesh above: the right magic, then nothing.
    std::fs::write(dir.join("broken.rmsh"), b"RMSH\x01\x00").unwrap();
    expect_failure(
        &dir,
        "broken_packed_mesh",
        &format!("{OUTPUT}\n[[meshes]]\npath = \"broken.rmsh\"\n"),
        &["line 5", "broken.rmsh", "header"],
    );
    // A missing scene file is an error too.
    let o = bin()
        .args(["render", "no/such/scene.toml", "-o"])
        .arg(dir.join("x.png"))
        .output()
        .unwrap();
    let (_, stderr) = text(&o);
    assert!(!o.status.success());
    assert!(stderr.starts_with("error: no/such/scene.toml"), "{stderr}");
}

/// Parses `  16.16 vs f32: N differing pixels (P %), max channel difference M`.
fn figures(stdout: &str, pair: &str) -> (u64, f64, u32) {
    let line = stdout
        .lines()
        .find(|l| l.trim_start().starts_with(pair))
        .unwrap_or_else(|| panic!("no `{pair}` line in: {stdout}"));
    let rest = line.split_once(':').unwrap().1.trim();
    let pixels: u64 = rest.split_whitespace().next().unwrap().parse().unwrap();
    let percent: f64 = rest
        .split_once('(')
        .unwrap()
        .1
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let max: u32 = rest.rsplit(' ').next().unwrap().parse().unwrap();
    (pixels, percent, max)
}

/// Measured on the M1 Suzanne (Gouraud, 320x240, the pipeline's 6 sub-pixel bits): 16.16 and
/// f32 differ in 190 pixels (0.247 %), mostly single steps of lit colour plus a few silhouette
/// pixels covered by one and not the other (max channel difference 177); 16.16 and f64 in 173
/// (0.225 %, max 177); f32 and f64 in 30 pixels (0.039 %), by at most 3
/// steps (with 4 bits: 3 pixels, one step; the finer grid puts more vertices near a rounding
/// boundary, where f32 and f64 round apart and shift a triangle's gradients).
#[test]
fn compare_suzanne_fixed_and_float_are_close() {
    let dir = scratch("compare");
    let png = dir.join("diff.png");
    let o = bin()
        .arg("compare")
        .arg(scenes_dir().join("suzanne_gouraud.toml"))
        .arg("-o")
        .arg(&png)
        .output()
        .unwrap();
    let (stdout, stderr) = text(&o);
    assert!(o.status.success(), "{stdout}{stderr}");
    // Bounds about twice the measurements (in the doc comment above: 0.247 %, 0.039 %, 0.225 %).
    // The largest channel difference, 177 for both fixed-point pairs, is a silhouette pixel drawn
    // by one and background in the other; twice that would exceed 255 and bound nothing, so the
    // bound is the measurement with a little room (180).
    let (px, share, max) = figures(&stdout, "16.16 vs f32");
    assert!(px > 0, "suspiciously identical: {stdout}");
    assert!(
        share < 0.5 && max <= 180,
        "16.16 vs f32 differ in {share} % of the pixels, max {max}"
    );
    let (_, share, max) = figures(&stdout, "f32   vs f64");
    assert!(share < 0.08 && max <= 3, "f32 vs f64: {share} %, max {max}");
    let (_, share, max) = figures(&stdout, "16.16 vs f64");
    assert!(
        share < 0.45 && max <= 180,
        "16.16 vs f64 differ in {share} % of the pixels, max {max}"
    );
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
}

#[test]
fn animate_writes_the_frames() {
    let dir = scratch("animate");
    let scene = scenes_dir().join("suzanne_flat.toml");
    let gif = dir.join("turn.gif");
    let o = bin()
        .arg("animate")
        .arg(&scene)
        .args(["--frames", "4", "--scale", "1", "-o"])
        .arg(&gif)
        .output()
        .unwrap();
    let (stdout, stderr) = text(&o);
    assert!(o.status.success(), "{stdout}{stderr}");
    let bytes = std::fs::read(&gif).unwrap();
    assert!(bytes.starts_with(b"GIF89a"));
    let decoder = GifDecoder::new(std::io::Cursor::new(bytes)).unwrap();
    let frames = decoder.into_frames().collect_frames().unwrap();
    assert_eq!(frames.len(), 4, "GIF frames");
    assert_eq!(frames[0].buffer().dimensions(), (320, 240));

    let o = bin()
        .arg("animate")
        .arg(&scene)
        .args(["--frames", "5", "--png-sequence", "--scale", "1", "-o"])
        .arg(dir.join("seq.png"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{:?}", text(&o));
    let mut pngs: Vec<Vec<u8>> = (0..5)
        .map(|k| std::fs::read(dir.join(format!("seq_{k:03}.png"))).unwrap())
        .collect();
    assert!(!dir.join("seq_005.png").exists());
    // The turntable moves: consecutive frames differ.
    pngs.dedup();
    assert_eq!(pngs.len(), 5, "some frames are identical");
}

/// `view`'s frames: a pose with no tilt is `render`'s picture, a tilt turns the meshes, and the
/// stats count what the meshes drew.
#[test]
fn posed_frames_and_their_stats() {
    use host_tools::scenefile::{load, render_image, render_posed, Pose};
    use rasterizer_core::math::Angle;
    let scene = load(&scenes_dir().join("suzanne_gouraud.toml")).unwrap();
    let yaw = Angle::from_degrees(40);
    let plain = render_image(&scene, yaw, 1).unwrap();
    let pose = |pitch| Pose { yaw, pitch };
    let (same, stats) = render_posed(&scene, pose(Angle(0)), 1).unwrap();
    assert!(plain.as_image_buffer() == same.as_image_buffer());
    assert!(stats.triangles > 300 && stats.triangles < 968, "{stats:?}");
    // Every drawn triangle writes at least a pixel on average, and no more than the frame
    // holds a few times over (overdraw).
    let area = u64::from(scene.width) * u64::from(scene.height);
    let pixels = stats.pixels.expect("a whole frame counts its pixels");
    assert!(pixels > stats.triangles && pixels < 4 * area, "{stats:?}");
    let (tilted, tilted_stats) = render_posed(&scene, pose(Angle::from_degrees(30)), 1).unwrap();
    assert!(tilted.as_image_buffer() != same.as_image_buffer());
    assert!(tilted_stats.triangles > 300, "{tilted_stats:?}");
}

/// The help of the scene commands says where the format is described and the ranges allowed.
#[test]
fn scene_help_names_the_format_and_the_ranges() {
    let doc = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/SCENES.md");
    assert!(doc.is_file(), "{}", doc.display());
    for (cmd, ranges) in [
        ("render", &["1 ..= 16", "4096 x 4096"][..]),
        ("animate", &["1 ..= 16", "1 ..= 720", "4096 x 4096"][..]),
        ("compare", &["4096 x 4096"][..]),
    ] {
        let out = bin().args([cmd, "--help"]).output().unwrap();
        let (stdout, _) = text(&out);
        assert!(out.status.success(), "{cmd}");
        assert!(stdout.contains("docs/SCENES.md"), "{cmd} --help: {stdout}");
        for r in ranges {
            assert!(stdout.contains(r), "{cmd} --help lacks {r}: {stdout}");
        }
    }
}

/// `dither` under `[render]` (or per mesh) dithers Gouraud colour at the output's depth: the
/// Rgb565 picture changes, each pixel by at most one step of each channel, and a value that is
/// not a matrix is refused.
#[test]
fn dither_key_dithers_at_the_output_depth() {
    use host_tools::scenefile::{load, render_image};
    let dir = scratch("dither");
    let suzanne = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    let scene = |dither: &str| {
        format!(
            "[output]\nwidth = 160\nheight = 120\nformat = \"rgb565\"\n\n\
             [render]\ndither = \"{dither}\"\n\n\
             [[lights]]\nkind = \"directional\"\ndirection = [1.0, 1.0, 1.0]\n\n\
             [[meshes]]\npath = {suzanne:?}\n"
        )
    };
    let render = |dither: &str| {
        let path = dir.join(format!("{dither}.toml"));
        std::fs::write(&path, scene(dither)).unwrap();
        let s = load(&path).unwrap();
        let image = render_image(&s, Default::default(), 1).unwrap();
        image.as_image_buffer().into_raw().to_vec()
    };
    let (plain, dithered) = (render("none"), render("bayer4"));
    assert_eq!(plain.len(), dithered.len());
    let changed = plain.iter().zip(&dithered).filter(|(a, b)| a != b).count();
    assert!(changed > 100, "only {changed} channel values changed");
    // One Rgb565 step is at most 9 in 8 bits (5-bit channels: 255 / 31).
    assert!(plain
        .iter()
        .zip(&dithered)
        .all(|(a, b)| a.abs_diff(*b) <= 9));
    expect_failure(&dir, "bad_dither", &scene("bayer3"), &["dither"]);
}

/// Renders a scene written into a scratch file; the image's raw RGB bytes.
fn render_scene(dir: &Path, name: &str, scene: &str) -> Vec<u8> {
    use host_tools::scenefile::{load, render_image};
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, scene).unwrap();
    let s = load(&path).unwrap();
    let image = render_image(&s, Default::default(), 1).unwrap();
    image.as_image_buffer().into_raw().to_vec()
}

#[test]
fn opacity_key_blends_meshes_and_shapes() {
    let dir = scratch("opacity");
    let suzanne = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    let mesh = |opacity: &str| {
        format!(
            "[output]\nwidth = 80\nheight = 60\nbackground = [0, 0, 200]\n\n\
             [[lights]]\nkind = \"directional\"\ndirection = [1.0, 1.0, 1.0]\n\n\
             [[meshes]]\npath = {suzanne:?}\ncolor = [250, 250, 0]\n{opacity}\n"
        )
    };
    let opaque = render_scene(&dir, "opaque", &mesh(""));
    assert_eq!(render_scene(&dir, "full", &mesh("opacity = 255")), opaque);
    let none = render_scene(&dir, "none", &mesh("opacity = 0"));
    assert!(none.chunks(3).all(|p| p == [0, 0, 200]));
    let half = render_scene(&dir, "half", &mesh("opacity = 128"));
    // Exactly where the opaque mesh is drawn, the translucent one is blended: neither the
    // background nor the opaque colour.
    let mut blended = 0;
    for (o, h) in opaque.chunks(3).zip(half.chunks(3)) {
        if o == [0, 0, 200] {
            assert_eq!(h, o);
        } else if h != o && h != [0, 0, 200] {
            blended += 1;
        }
    }
    assert!(blended > 500, "{blended} pixels");
    // A 2D triangle at opacity 128 over the background: the exact blend per channel.
    let tri = |opacity: &str| {
        format!(
            "[output]\nwidth = 16\nheight = 16\nbackground = [0, 0, 200]\n\n\
             [[shapes]]\nkind = \"triangle\"\nvertices = [[0.0, 0.0], [16.0, 0.0], [0.0, 16.0]]\n\
             color = [255, 100, 0]\n{opacity}\n"
        )
    };
    let t = render_scene(&dir, "tri", &tri("opacity = 128"));
    assert_eq!(&t[3..6], &[128, 50, 100]);
    assert_eq!(&t[t.len() - 3..], &[0, 0, 200]);
}

#[test]
fn antialias_and_width_keys_draw_wide_lines() {
    let dir = scratch("antialias");
    let line = |keys: &str| {
        format!(
            "[output]\nwidth = 12\nheight = 9\n\n\
             [[shapes]]\nkind = \"line\"\nfrom = [1.5, 4.5]\nto = [10.5, 4.5]\n\
             color = [255, 255, 255]\n{keys}\n"
        )
    };
    let px = |img: &[u8], x: usize, y: usize| img[(y * 12 + x) * 3];
    let aliased = render_scene(&dir, "aliased", &line(""));
    let aa = render_scene(&dir, "aa", &line("antialias = true"));
    assert_eq!(
        aa, aliased,
        "a horizontal line through pixel centres is the same"
    );
    let wide = render_scene(&dir, "wide", &line("antialias = true\nwidth = 2"));
    assert_eq!(
        [px(&wide, 5, 3), px(&wide, 5, 4), px(&wide, 5, 5)],
        [128, 255, 128]
    );
    expect_failure(
        &dir,
        "width_without_antialias",
        &line("width = 3"),
        &["needs `antialias = true`"],
    );
    expect_failure(
        &dir,
        "antialias_gradient",
        &format!("{OUTPUT}[[shapes]]\nkind = \"line\"\nfrom = [0.0, 0.0]\nto = [5.0, 5.0]\ncolors = [[1, 2, 3], [4, 5, 6]]\nantialias = true\n"),
        &["one `color`"],
    );
    expect_failure(
        &dir,
        "opacity_too_big",
        &format!("{OUTPUT}[[shapes]]\nkind = \"point\"\nat = [1.0, 1.0]\ncolor = [1, 2, 3]\nopacity = 256\n"),
        &["opacity"],
    );
}

/// `fog` under `[render]` or per mesh: fog beyond the mesh changes nothing (dithered or not),
/// fog before it leaves only the fog colour where the mesh is, a mesh's own table replaces
/// `[render]`'s, and bad values are refused.
#[test]
fn fog_key_fogs_by_depth() {
    use host_tools::scenefile::{load, render_image};
    let dir = scratch("fog");
    let suzanne = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    let scene = |render: &str, mesh: &str| {
        format!(
            "[output]\nwidth = 160\nheight = 120\nformat = \"rgb565\"\n\n\
             [render]\n{render}\n\n\
             [[lights]]\nkind = \"directional\"\ndirection = [1.0, 1.0, 1.0]\n\n\
             [[meshes]]\npath = {suzanne:?}\n{mesh}\n"
        )
    };
    let render = |name: &str, render: &str, mesh: &str| {
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, scene(render, mesh)).unwrap();
        let s = load(&path).unwrap();
        let image = render_image(&s, Default::default(), 1).unwrap();
        image.as_image_buffer().into_raw().to_vec()
    };
    let beyond = "fog = { color = \"#ff0000\", start = 10.0, end = 20.0 }";
    let before = "fog = { color = \"#00ff00\", start = -2.0, end = 0.0, mode = \"exponential\" }";
    for shading in ["gouraud", "flat", "vertex_colors", "phong"] {
        let plain = render("plain", &format!("shading = \"{shading}\""), "");
        let far = render("far", &format!("shading = \"{shading}\"\n{beyond}"), "");
        assert!(
            plain == far,
            "{shading}: fog beyond the mesh changed the picture"
        );
        let near = render("near", &format!("shading = \"{shading}\"\n{before}"), "");
        // Black background, green where the mesh is: no red or blue anywhere.
        assert!(near.chunks(3).all(|p| p[0] == 0 && p[2] == 0), "{shading}");
        let green = near.chunks(3).filter(|p| p[1] == 255).count();
        let covered = plain.chunks(3).filter(|p| p != &[0, 0, 0]).count();
        assert_eq!(green, covered, "{shading}");
        // The mesh's table replaces [render]'s.
        let own = render("own", &format!("shading = \"{shading}\"\n{before}"), beyond);
        assert!(
            plain == own,
            "{shading}: the mesh's fog did not replace [render]'s"
        );
    }
    let dithered = render("dithered", "dither = \"bayer4\"", "");
    let dithered_far = render(
        "dithered_far",
        &format!("dither = \"bayer4\"\n{beyond}"),
        "",
    );
    assert!(
        dithered == dithered_far,
        "dithered: fog beyond the mesh changed the picture"
    );
    let dithered_near = render(
        "dithered_near",
        &format!("dither = \"bayer4\"\n{before}"),
        "",
    );
    assert!(dithered_near
        .chunks(3)
        .all(|p| p == [0, 0, 0] || p == [0, 255, 0]));
    let fog = |f: &str| scene(&format!("fog = {{ color = \"#808080\", {f} }}"), "");
    expect_failure(
        &dir,
        "bad_density",
        &fog("start = 1.0, end = 2.0, mode = \"exponential\", density = 9.0"),
        &["density"],
    );
    expect_failure(
        &dir,
        "bad_start",
        &fog("start = 1e9, end = 2.0"),
        &["fog.start"],
    );
    expect_failure(
        &dir,
        "bad_mode",
        &fog("start = 1.0, end = 2.0, mode = \"exp2\""),
        &["mode"],
    );
    expect_failure(&dir, "no_end", &fog("start = 1.0"), &["end"]);
}

/// `density` is the exponential curve's: given with linear fog (the default mode) it would be
/// ignored, so it is refused, naming where it is.
#[test]
fn fog_density_needs_exponential_mode() {
    let dir = scratch("fog_density");
    let suzanne = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    let fog = "fog = { color = \"#808080\", start = 1.0, end = 2.0, density = 2.0 }";
    let mesh = format!("[[meshes]]\npath = {suzanne:?}\n");
    expect_failure(
        &dir,
        "render_density",
        &format!("{OUTPUT}[render]\n{fog}\n\n{mesh}"),
        &[
            "[render]",
            "fog.density applies only with mode = \"exponential\"",
        ],
    );
    expect_failure(
        &dir,
        "mesh_density",
        &format!("{OUTPUT}{mesh}{fog}\n"),
        &["mesh ", "suzanne.obj", "fog.density applies only"],
    );
    let ok = dir.join("exponential.toml");
    let exponential = fog.replace("density", "mode = \"exponential\", density");
    std::fs::write(&ok, format!("{OUTPUT}{mesh}{exponential}\n")).unwrap();
    assert!(host_tools::scenefile::load(&ok).is_ok());
}

/// Keys the drawing of a mesh would ignore are refused, naming the mesh, the key and, when it
/// comes from there, `[render]`: fog and dithering with no colour to mix or dither, a material or
/// generated vertex colours its shading does not read, a depth buffer for a wireframe.
#[test]
fn keys_that_would_be_ignored_are_refused() {
    let dir = scratch("ignored_keys");
    let suzanne = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    let fog = "fog = { color = \"#808080\", start = 1.0, end = 2.0 }";
    let mesh = |extra: &str| format!("{OUTPUT}[[meshes]]\npath = {suzanne:?}\n{extra}\n");
    let cases: &[(&str, String, &[&str])] = &[
        ("fog_wire", mesh(&format!("wireframe = true\n{fog}")), &["fog does not apply to a wireframe"]),
        ("fog_unlit", mesh(&format!("shading = \"none\"\n{fog}")), &["fog does not apply to shading = \"none\""]),
        ("fog_translucent", mesh(&format!("opacity = 100\n{fog}")), &["fog does not apply to a translucent"]),
        (
            "fog_render_wire",
            format!("{OUTPUT}[render]\n{fog}\n\n[[meshes]]\npath = {suzanne:?}\nwireframe = true\n"),
            &["fog (from [render]) does not apply to a wireframe"],
        ),
        ("dither_flat", mesh("shading = \"flat\"\ndither = \"bayer4\""), &["dither does not apply to shading = \"flat\""]),
        ("dither_phong", mesh("shading = \"phong\"\ndither = \"bayer8\""), &["dither does not apply to shading = \"phong\""]),
        ("dither_wire", mesh("wireframe = true\ndither = \"bayer4\""), &["dither does not apply to a wireframe"]),
        ("dither_perspective", mesh("perspective_correct = true\ndither = \"bayer4\""), &["dither does not apply to a perspective-correct"]),
        ("dither_translucent", mesh("opacity = 100\ndither = \"bayer4\""), &["dither does not apply to a translucent"]),
        (
            "dither_render_unlit",
            format!("{OUTPUT}[render]\ndither = \"bayer4\"\n\n[[meshes]]\npath = {suzanne:?}\nshading = \"none\"\n"),
            &["dither (from [render]) does not apply"],
        ),
        ("material_unlit", mesh("shading = \"vertex_colors\"\nmaterial = { shininess = 4 }"), &["material applies only to lit shading"]),
        ("material_wire", mesh("wireframe = true\nmaterial = { shininess = 4 }"), &["material applies only to lit shading", "wireframe"]),
        ("vertex_colors_gouraud", mesh("vertex_colors = \"normal\""), &["vertex_colors applies only to shading = \"vertex_colors\""]),
        ("depth_wire", mesh("wireframe = true\ndepth = true"), &["depth = true does not apply to a wireframe"]),
    ];
    for (name, scene, needles) in cases {
        let mut all = vec!["mesh ", "suzanne.obj"];
        all.extend_from_slice(needles);
        expect_failure(&dir, name, scene, &all);
    }
}

/// A scene with an odd but usable OBJ (CRLF line endings, a missing material library): every
/// command that reads scenes says so in `warning:` lines on stderr and still does its work.
#[test]
fn obj_warnings_reach_the_user() {
    let dir = scratch("obj-warnings");
    let obj = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/unit_cube.obj"),
    )
    .unwrap();
    let odd = format!("mtllib nowhere.mtl\n{obj}").replace('\n', "\r\n");
    std::fs::write(dir.join("odd.obj"), odd).unwrap();
    let scene = dir.join("odd.toml");
    std::fs::write(
        &scene,
        "[output]\nwidth = 48\nheight = 32\n[camera]\neye = [1.5, 1.2, 2.5]\n\
         [[meshes]]\npath = \"odd.obj\"\n",
    )
    .unwrap();
    let out = |name: &str| dir.join(name);
    for (cmd, extra) in [
        ("render", vec!["-o".into(), out("r.png")]),
        (
            "animate",
            vec!["--frames".into(), "1".into(), "-o".into(), out("a.gif")],
        ),
        ("compare", vec!["-o".into(), out("c.png")]),
    ] {
        let o = bin().arg(cmd).arg(&scene).args(&extra).output().unwrap();
        let (stdout, stderr) = text(&o);
        assert!(o.status.success(), "{cmd}: {stdout}{stderr}");
        for needle in ["CRLF", "nowhere.mtl"] {
            assert!(
                stderr.lines().any(|l| l.starts_with("warning: ")
                    && l.contains("odd.obj")
                    && l.contains(needle)),
                "{cmd}: no warning about {needle}: {stderr}"
            );
        }
    }
}

/// Every integer key of the scene format names its allowed range when a value is outside it
/// (not "expected u8": a Rust type is no help to someone writing a scene).
#[test]
fn integer_keys_name_their_range() {
    let dir = scratch("ranges");
    let shape = |key: &str| {
        format!("{OUTPUT}[[shapes]]\nkind = \"line\"\nfrom = [1.0, 1.0]\nto = [3.0, 4.0]\ncolor = [1, 2, 3]\nantialias = true\n{key}\n")
    };
    let mesh = |key: &str| format!("{OUTPUT}[[meshes]]\npath = \"m.obj\"\n{key}\n");
    let cases = [
        (
            "width",
            "[output]\nwidth = -3\nheight = 24\n".to_string(),
            "1 ..= 4096",
        ),
        (
            "height",
            "[output]\nwidth = 3\nheight = 5000000000\n".into(),
            "1 ..= 4096",
        ),
        ("scale", format!("{OUTPUT}scale = 0\n"), "1 ..= 16"),
        (
            "background",
            format!("{OUTPUT}background = [0, 300, 0]\n"),
            "0 ..= 255",
        ),
        ("mesh_opacity", mesh("opacity = 300"), "0 ..= 255"),
        (
            "shininess",
            mesh("material = { shininess = 70000 }"),
            "0 ..= 65535",
        ),
        ("shape_opacity", shape("opacity = -1"), "`opacity`"),
        ("line_width", shape("width = 0"), "`width`"),
        (
            "clip",
            shape("clip = [0, 0, 5000000000, 1]"),
            "-2147483648 ..= 2147483647",
        ),
    ];
    for (name, scene, range) in cases {
        expect_failure(&dir, name, &scene, &[range]);
        let (stdout, stderr) = {
            let o = bin()
                .arg("render")
                .arg(dir.join(format!("{name}.toml")))
                .args(["-o", "-"])
                .output()
                .unwrap();
            text(&o)
        };
        assert!(
            !stderr.contains("expected u") && !stderr.contains("expected i"),
            "{name}: {stdout}{stderr}"
        );
    }
    // Inside [[shapes]] the key is named along with its range.
    expect_failure(
        &dir,
        "shape_opacity",
        &shape("opacity = -1"),
        &["0 ..= 255"],
    );
    expect_failure(&dir, "line_width", &shape("width = 0"), &["1 ..= 65535"]);
}

/// `antialias = true` on a mesh: every kind of filled mesh the scene format has (each shading
/// model, dithered, perspective-correct, fogged, translucent, without depth, unculled, textured)
/// is drawn with its silhouettes blended, so each picture differs from the same mesh without the
/// key in a few of the mesh's pixels; wireframes refuse the key, naming where it came from.
#[test]
fn antialias_key_blends_silhouettes() {
    let dir = scratch("antialias");
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models");
    let suzanne = models.join("suzanne.obj");
    let cube = models.join("cube_textured.obj");
    let checker = models.join("../textures/checker.png");
    const HEAD: &str = "[output]\nwidth = 64\nheight = 48\nbackground = [10, 20, 30]\n\n\
                        [[lights]]\nkind = \"directional\"\ndirection = [1.0, 1.0, 1.0]\n\n";
    let mesh = |path: &Path, extra: &str| format!("{HEAD}[[meshes]]\npath = {path:?}\n{extra}\n");
    let textured = format!("texture = {checker:?}\nrotate = [30.0, 40.0, 0.0]");
    let cases: &[(&str, &Path, &str)] = &[
        ("gouraud", &suzanne, ""),
        ("none", &suzanne, "shading = \"none\""),
        (
            "vertex_colors",
            &suzanne,
            "shading = \"vertex_colors\"\nvertex_colors = \"normal\"",
        ),
        ("flat", &suzanne, "shading = \"flat\""),
        ("phong", &suzanne, "shading = \"phong\""),
        ("matcap", &suzanne, "shading = \"matcap\""),
        ("dither", &suzanne, "dither = \"bayer4\""),
        ("perspective", &suzanne, "perspective_correct = true"),
        (
            "fog",
            &suzanne,
            "fog = { color = [10, 20, 30], start = 2.0, end = 5.0 }",
        ),
        ("translucent", &suzanne, "opacity = 128"),
        ("no_depth", &suzanne, "depth = false"),
        ("no_cull", &suzanne, "cull = \"none\""),
        ("textured", &cube, &textured),
    ];
    for (name, path, extra) in cases {
        let plain = render_scene(&dir, name, &mesh(path, extra));
        let aa_name = format!("{name}_aa");
        let aa = render_scene(
            &dir,
            &aa_name,
            &mesh(path, &format!("{extra}\nantialias = true")),
        );
        assert_eq!(plain.len(), aa.len(), "{name}");
        let changed: Vec<usize> = (0..plain.len() / 3)
            .filter(|&i| plain[3 * i..3 * i + 3] != aa[3 * i..3 * i + 3])
            .collect();
        assert!(!changed.is_empty(), "{name}: antialias changed nothing");
        // Only the pixels visible silhouette edges cross change: a few of the mesh's.
        let drawn = (0..plain.len() / 3)
            .filter(|&i| plain[3 * i..3 * i + 3] != [10, 20, 30])
            .count();
        // Without a depth write the blending pass also shows the silhouettes the mesh hides
        // from itself (drawn after the whole mesh, nothing hides them): more pixels change.
        let hides = !matches!(*name, "translucent" | "no_depth");
        assert!(
            changed.len() * 2 < drawn || !hides,
            "{name}: {} of {drawn} pixels changed",
            changed.len()
        );
    }
    let wire = |render: &str, extra: &str| {
        format!("{OUTPUT}{render}[[meshes]]\npath = {suzanne:?}\n{extra}\nantialias = true\n")
    };
    let failures: &[(&str, String, &[&str])] = &[
        (
            "antialias_wire",
            wire("", "wireframe = true"),
            &[
                "mesh ",
                "suzanne.obj",
                "antialias = true does not apply to a wireframe",
            ],
        ),
        (
            "antialias_render_wire",
            wire("[render]\nwireframe = true\n\n", ""),
            &[
                "antialias = true does not apply to a wireframe",
                "from [render]",
            ],
        ),
        (
            "antialias_not_bool",
            format!("{OUTPUT}[[meshes]]\npath = {suzanne:?}\nantialias = \"yes\"\n"),
            &["line 6", "antialias", "bool"],
        ),
        (
            "antialias_misspelt",
            format!("{OUTPUT}[[meshes]]\npath = {suzanne:?}\nanti_alias = true\n"),
            &["anti_alias", "antialias"],
        ),
    ];
    for (name, scene, needles) in failures {
        expect_failure(&dir, name, scene, needles);
    }
}

/// `shading = "matcap"`: the built-in sphere by default, a PNG by the `matcap` key (a flat red
/// image paints every pixel of the mesh red), and the key's errors name the mesh and the cause.
#[test]
fn matcap_key_picks_the_image() {
    let dir = scratch("matcap");
    let suzanne = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    let png = |name: &str, w: u32, h: u32, rgb: [u8; 3]| {
        let path = dir.join(name);
        image::RgbImage::from_pixel(w, h, image::Rgb(rgb))
            .save(&path)
            .unwrap();
        path
    };
    let red = png("red.png", 8, 8, [255, 0, 0]);
    let wide = png("wide.png", 8, 4, [0, 255, 0]);
    let big = png("big.png", 512, 512, [0, 0, 255]);
    let mesh = |extra: &str| {
        format!("{OUTPUT}[[meshes]]\npath = {suzanne:?}\nshading = \"matcap\"\n{extra}\n")
    };
    let builtin = render_scene(&dir, "builtin", &mesh(""));
    let colours: std::collections::HashSet<&[u8]> = builtin.chunks(3).collect();
    assert!(
        colours.len() > 20,
        "the sphere shades: {} colours",
        colours.len()
    );
    let flat = render_scene(&dir, "red", &mesh(&format!("matcap = {:?}", red)));
    let drawn: Vec<&[u8]> = flat.chunks(3).filter(|p| *p != [0, 0, 0]).collect();
    assert!(!drawn.is_empty());
    assert!(drawn.iter().all(|p| *p == [255, 0, 0]), "{:?}", &drawn[..4]);
    // Fog mixes the MatCap colours as it does Gouraud's; opacity blends them.
    let fogged = render_scene(
        &dir,
        "fogged",
        &mesh("fog = { color = \"#8090a0\", start = 2.0, end = 4.0 }"),
    );
    assert_ne!(fogged, builtin);
    let translucent = render_scene(&dir, "translucent", &mesh("opacity = 128"));
    assert_ne!(translucent, builtin);
    let cases: &[(&str, String, &[&str])] = &[
        (
            "matcap_gouraud",
            format!("{OUTPUT}[[meshes]]\npath = {suzanne:?}\nmatcap = {red:?}\n"),
            &["matcap applies only to shading = \"matcap\""],
        ),
        (
            "matcap_missing",
            mesh("matcap = \"no/such.png\""),
            &["matcap", "no/such.png"],
        ),
        (
            "matcap_wide",
            mesh(&format!("matcap = {wide:?}")),
            &["must be square", "8x4"],
        ),
        (
            "matcap_big",
            mesh(&format!("matcap = {big:?}")),
            &["larger than 256x256"],
        ),
        (
            "matcap_dither",
            mesh("dither = \"bayer4\""),
            &["dither does not apply to shading = \"matcap\""],
        ),
        (
            "matcap_material",
            mesh("material = { shininess = 4 }"),
            &["material applies only to lit shading"],
        ),
    ];
    for (name, scene, needles) in cases {
        let mut all = vec!["suzanne.obj"];
        all.extend_from_slice(needles);
        expect_failure(&dir, name, scene, &all);
    }
    let unknown = format!("{OUTPUT}[[meshes]]\npath = {suzanne:?}\nshading = \"matcapp\"\n");
    expect_failure(
        &dir,
        "matcap_unknown",
        &unknown,
        &["line 6", "matcapp", "matcap"],
    );
}

/// `kind = "sprite"`: a PNG or a sprite file placed by its centre (an untransformed 2x2 red image
/// covers exactly its four pixels), and the key's errors name the item and the cause.
#[test]
fn sprite_shapes_place_images() {
    let dir = scratch("sprite");
    let red = dir.join("red.png");
    image::RgbImage::from_pixel(2, 2, image::Rgb([255, 0, 0]))
        .save(&red)
        .unwrap();
    let shape = |extra: &str| {
        format!(
            "{OUTPUT}[[shapes]]\nkind = \"sprite\"\nimage = {red:?}\nat = [5.0, 7.0]\n{extra}\n"
        )
    };
    let pixels = render_scene(&dir, "plain", &shape(""));
    let drawn: Vec<usize> = pixels
        .chunks(3)
        .enumerate()
        .filter(|(_, p)| *p != [0, 0, 0])
        .map(|(i, p)| {
            assert_eq!(p, [255, 0, 0]);
            i
        })
        .collect();
    assert_eq!(drawn, [6 * 32 + 4, 6 * 32 + 5, 7 * 32 + 4, 7 * 32 + 5]);
    // Turned, scaled, translucent and bilinear all draw, and differently.
    let turned = render_scene(&dir, "turned", &shape("angle = 30.0\nscale = [3.0, 2.0]"));
    let faint = render_scene(&dir, "faint", &shape("scale = 3.0\nopacity = 100"));
    assert_ne!(turned, pixels);
    assert!(faint.chunks(3).any(|p| p[0] > 0 && p[0] < 255));
    let i1 = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/sprites/i1.bin");
    let from_bin = render_scene(
        &dir,
        "bin",
        &format!("{OUTPUT}[[shapes]]\nkind = \"sprite\"\nimage = {i1:?}\nat = [16.0, 12.0]\nfilter = \"bilinear\"\n"),
    );
    assert!(from_bin.chunks(3).filter(|p| *p != [0, 0, 0]).count() > 300);
    let junk = dir.join("junk.bin");
    std::fs::write(&junk, b"RSPR junk").unwrap();
    let cases: &[(&str, String, &[&str])] = &[
        (
            "missing",
            shape("").replace("red.png", "none.png"),
            &["[[shapes]]", "sprite image", "none.png"],
        ),
        (
            "junk",
            shape("").replace(&*red.to_string_lossy(), &junk.to_string_lossy()),
            &["[[shapes]]", "junk.bin", "bytes where the sprite needs"],
        ),
        (
            "flat",
            shape("scale = [1.0, 0.0]"),
            &["[[shapes]]", "sprite", "singular"],
        ),
        (
            "huge",
            shape("scale = 40000.0"),
            &["[[shapes]]", "sprite", "16.16"],
        ),
        (
            "far",
            shape("").replace("at = [5.0, 7.0]", "at = [1e9, 7.0]"),
            &["[[shapes]]", "sprite"],
        ),
        ("bad_filter", shape("filter = \"cubic\""), &["cubic"]),
    ];
    for (name, scene, needles) in cases {
        expect_failure(&dir, name, scene, needles);
    }
}
