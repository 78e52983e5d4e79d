//! Scene files with textures: `texture`, `texture_filter` and `texture_wrap` load the PNG into
//! Rgb565 beside the mesh's texture coordinates, and every problem is a message naming the file,
//! the line and the fix.

use host_tools::scenefile::load;
use rasterizer_core::texture::{Filter, Wrap};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

fn scratch(name: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "host-tools-scene-textures-{name}-{}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write_png(path: &Path, w: u32, h: u32) {
    image::RgbImage::from_fn(w, h, |x, y| image::Rgb([(x * 7) as u8, (y * 5) as u8, 200]))
        .save(path)
        .unwrap();
}

const HEAD: &str = "[output]\nwidth = 32\nheight = 24\n\n[[meshes]]\n";
const QUAD: &str = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
                    f 1/1 2/2 3/3 4/4\n";

/// A directory with the textured quad `quad.obj`, an untextured `plain.obj`, `t.png` (8 x 4) and
/// `odd.png` (6 x 4).
fn setup(name: &str) -> PathBuf {
    let dir = scratch(name);
    std::fs::write(dir.join("quad.obj"), QUAD).unwrap();
    std::fs::write(
        dir.join("plain.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    write_png(&dir.join("t.png"), 8, 4);
    write_png(&dir.join("odd.png"), 6, 4);
    dir
}

fn scene(dir: &Path, name: &str, mesh: &str) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, format!("{HEAD}{mesh}")).unwrap();
    path
}

#[test]
fn a_textured_mesh_keeps_its_texture_and_uvs() {
    let dir = setup("ok");
    let path = scene(
        &dir,
        "ok",
        "path = \"quad.obj\"\ntexture = \"t.png\"\ntexture_filter = \"bilinear\"\n\
         texture_wrap = \"clamp\"\n",
    );
    let s = load(&path).unwrap();
    let m = &s.meshes[0];
    let t = m.texture.as_ref().unwrap();
    assert_eq!((t.filter, t.wrap), (Filter::Bilinear, Wrap::Clamp));
    assert_eq!((t.image.width(), t.image.height()), (8, 4));
    assert_eq!(
        t.image.texel(7, 3),
        fixtures::texture_file::rgb565(49, 15, 200)
    );
    assert!(s.inputs().contains(&dir.join("t.png").as_path()));
    let host_tools::scenefile::MeshData::Owned(o) = &m.data else {
        panic!("an OBJ mesh is owned");
    };
    // OBJ's v counts from the bottom: the first corner (0, 0) is the texture's bottom-left.
    assert_eq!(o.uvs.as_ref().unwrap()[0], [0, 65536]);

    // Defaults: nearest, repeat; no texture, no texture.
    let path = scene(
        &dir,
        "defaults",
        "path = \"quad.obj\"\ntexture = \"t.png\"\n",
    );
    let t = load(&path).unwrap().meshes[0].texture.clone().unwrap();
    assert_eq!((t.filter, t.wrap), (Filter::Nearest, Wrap::Repeat));
    let path = scene(&dir, "none", "path = \"quad.obj\"\n");
    assert!(load(&path).unwrap().meshes[0].texture.is_none());
}

#[test]
fn a_packed_mesh_brings_its_own_texture() {
    let dir = setup("packed");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_host-tools"))
        .arg("convert")
        .arg(dir.join("quad.obj"))
        .arg("-o")
        .arg(dir.join("quad.rmsh"))
        .arg("--texture")
        .arg(dir.join("t.png"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let path = scene(&dir, "packed", "path = \"quad.rmsh\"\n");
    let s = load(&path).unwrap();
    let t = s.meshes[0].texture.as_ref().unwrap();
    assert_eq!((t.file.as_ref(), t.image.width()), (None, 8));
    // Edited (refitted), it keeps both.
    let path = scene(
        &dir,
        "edited",
        "path = \"quad.rmsh\"\nfit_unit_sphere = true\n",
    );
    let s = load(&path).unwrap();
    assert!(s.meshes[0].texture.is_some());
    let host_tools::scenefile::MeshData::Owned(o) = &s.meshes[0].data else {
        panic!("an edited mesh is owned");
    };
    assert_eq!(o.uvs.as_ref().map(Vec::len), Some(4));
}

#[test]
fn texture_problems_name_the_file_the_line_and_the_fix() {
    let dir = setup("bad");
    for (name, mesh, needles) in [
        (
            "missing",
            "path = \"quad.obj\"\ntexture = \"gone.png\"\n",
            &["line 5", "texture", "gone.png", "cannot read"][..],
        ),
        (
            "odd",
            "path = \"quad.obj\"\ntexture = \"odd.png\"\n",
            &["line 5", "6x4", "powers of two", "--texture-size"][..],
        ),
        (
            "no_uvs",
            "path = \"plain.obj\"\ntexture = \"t.png\"\n",
            &["line 5", "plain.obj", "no texture coordinates"][..],
        ),
        (
            "filter_alone",
            "path = \"quad.obj\"\ntexture_filter = \"bilinear\"\n",
            &["line 5", "need a `texture`"][..],
        ),
        (
            "bad_filter",
            "path = \"quad.obj\"\ntexture = \"t.png\"\ntexture_filter = \"cubic\"\n",
            &["cubic", "nearest", "bilinear"][..],
        ),
        (
            "bad_wrap",
            "path = \"quad.obj\"\ntexture = \"t.png\"\ntexture_wrap = \"mirror\"\n",
            &["mirror", "repeat", "clamp"][..],
        ),
    ] {
        let path = scene(&dir, name, mesh);
        let e = load(&path).unwrap_err();
        assert!(e.starts_with(&path.display().to_string()), "{name}: {e}");
        // TOML's own errors quote the line below the message, as for every other key.
        if !e.contains("TOML parse error") {
            assert!(!e.contains('\n'), "{name}: one line: {e}");
        }
        for n in needles {
            assert!(e.contains(n), "{name}: `{n}` missing from: {e}");
        }
    }
}

#[test]
fn a_texture_needs_gouraud_shading_and_no_dither_fog_or_opacity() {
    let dir = setup("shading");
    for (name, extra, needle) in [
        ("phong", "shading = \"phong\"\n", "not \"phong\""),
        ("flat", "shading = \"flat\"\n", "not \"flat\""),
        ("dither", "dither = \"bayer4\"\n", "dither does not apply"),
        (
            "fog",
            "fog = { color = [1, 2, 3], start = 1.0, end = 2.0 }\n",
            "fog does not apply",
        ),
        (
            "opacity",
            "opacity = 128\n",
            "opacity below 255 does not apply",
        ),
    ] {
        let path = scene(
            &dir,
            name,
            &format!("path = \"quad.obj\"\ntexture = \"t.png\"\n{extra}"),
        );
        let e = load(&path).unwrap_err();
        assert!(e.contains("line 5") && e.contains(needle), "{name}: {e}");
    }
}

/// The quad facing the camera, lit by white ambient light alone (the material's ambient white):
/// each pixel is its texel. The checker's quadrants land where they are in the image, the right
/// way up.
#[test]
fn a_textured_quad_shows_its_texture_the_right_way_up() {
    let dir = setup("draw");
    let checker = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/textures/checker.png");
    std::fs::copy(&checker, dir.join("checker.png")).unwrap();
    let path = dir.join("quad.toml");
    std::fs::write(
        &path,
        "[output]\nwidth = 64\nheight = 64\n\n[camera]\neye = [0.0, 0.0, 2.0]\nfov = 60.0\n\n\
         [render]\nambient = [255, 255, 255]\nspecular = \"none\"\nperspective_correct = true\n\n\
         [[meshes]]\npath = \"quad.obj\"\ntexture = \"checker.png\"\n\
         material = { ambient = [255, 255, 255], diffuse = [0, 0, 0], specular = [0, 0, 0] }\n",
    )
    .unwrap();
    let s = load(&path).unwrap();
    let display = host_tools::scenefile::render_3d::<rasterizer_core::math::Fx16>(&s).unwrap();
    let at = |x: i32, y: i32| {
        let c = display.get_pixel(embedded_graphics::prelude::Point::new(x, y));
        [c.r(), c.g(), c.b()]
    };
    use embedded_graphics::pixelcolor::RgbColor;
    // Sample well inside each quadrant, in a check of the full colour (the checks alternate
    // every 8 texels).
    let dominant = |c: [u8; 3]| {
        let max = *c.iter().max().unwrap();
        c.map(|v| u16::from(v) * 2 > u16::from(max))
    };
    // Texel (20, 20) of 64 is in the red quadrant's full-colour check; (44, 20) green;
    // (20, 44) blue; (44, 44) yellow. The quad (2 units wide, 2 units away, 60 degrees of view)
    // covers 64 / tan(30 degrees) / 2 = 55.4 pixels about the centre.
    let px = |t: i32| (32.0 + (f64::from(t) + 0.5 - 32.0) / 64.0 * 55.4) as i32;
    assert_eq!(
        dominant(at(px(20), px(20))),
        [true, false, false],
        "red top left"
    );
    assert_eq!(
        dominant(at(px(44), px(20))),
        [false, true, false],
        "green top right"
    );
    assert_eq!(
        dominant(at(px(20), px(44))),
        [false, false, true],
        "blue bottom left"
    );
    assert_eq!(
        dominant(at(px(44), px(44))),
        [true, true, false],
        "yellow bottom right"
    );
    // The F's top bar, near the top of the red quadrant.
    assert_eq!(at(px(16), px(7)), [255, 255, 255]);
}
