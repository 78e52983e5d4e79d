//! Reference images of the 3D pipeline: the unit cube and Suzanne under every shading model,
//! rendered at 160x120 into a `Framebuffer<Rgb888>` and compared exactly with
//! `tests/images/pipeline/<case>.png`.
//!
//! The pipeline is integer-only after the OBJ loader's rounding, so the pictures are the same on
//! every machine: any difference is a change in behaviour. When a change is intended, run
//!
//! ```text
//! UPDATE_REFERENCE=1 cargo test -p tests --test render_reference
//! ```
//!
//! look at the rewritten pictures, and commit them. Without `UPDATE_REFERENCE=1` a missing reference
//! fails the test (so CI never creates one silently). On a mismatch the test writes
//! `target/render-diff/<case>.png` (the reference dimmed to grey, differing pixels in magenta) and
//! fails with the number of differing pixels.

use fixtures::obj::LoadedMesh;
use fixtures::scenes3d::{camera, lighting, DIFFUSE, ROTATION_Y_DEGREES};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::Shading;
use std::fs::File;
use std::io::{BufReader, BufWriter};
use std::path::{Path, PathBuf};

/// Picture width.
const WIDTH: u32 = 160;
/// Picture height.
const HEIGHT: u32 = 120;
/// Pixels of one picture.
const PIXELS: usize = (WIDTH * HEIGHT) as usize;
/// The background every picture is cleared to.
const BACKGROUND: Rgb888 = Rgb888::new(14, 16, 26);

/// The repository's root.
fn root() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().unwrap_or(manifest).to_path_buf()
}

/// Loads a model of `assets/models`.
fn load(name: &str) -> LoadedMesh {
    let path = root().join("assets/models").join(name);
    LoadedMesh::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Which mesh a case renders.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Model {
    /// `unit_cube.obj`, scaled by 1.6 and turned to show three faces.
    Cube,
    /// `suzanne.obj` in the M1 benchmark scene (turned 30° about Y).
    Suzanne,
}

/// How a case is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Style {
    /// `draw_wireframe`, back faces culled.
    Wireframe,
    /// [`Unlit`].
    Unlit,
    /// [`VertexColors`].
    VertexColors,
    /// [`FlatLit`].
    Flat,
    /// [`GouraudLit`].
    Gouraud,
    /// [`PhongLit`].
    Phong,
}

impl Model {
    /// The case name's first part.
    fn name(self) -> &'static str {
        match self {
            Model::Cube => "cube",
            Model::Suzanne => "suzanne",
        }
    }
}

impl Style {
    /// The case name's second part.
    fn name(self) -> &'static str {
        match self {
            Style::Wireframe => "wireframe",
            Style::Unlit => "unlit",
            Style::VertexColors => "vertex_colors",
            Style::Flat => "flat",
            Style::Gouraud => "gouraud",
            Style::Phong => "phong",
        }
    }
}

/// The M1 camera (`fixtures::scenes3d`) at 160 x 120; the model matrix depends on the mesh.
fn transforms(model: Model) -> Transforms<Fx16> {
    let model = match model {
        Model::Cube => {
            let s = Fx16::from_ratio(8, 5);
            Mat4::scale(s, s, s)
                .then(&Mat4::rotation_y(Angle::from_degrees(35)))
                .then(&Mat4::rotation_x(Angle::from_degrees(25)))
        }
        Model::Suzanne => Mat4::rotation_y(Angle::from_degrees(ROTATION_Y_DEGREES)),
    };
    camera(model, WIDTH, HEIGHT)
}

/// Draws `mesh` filled, with a depth buffer and back faces culled, into `fb`.
fn fill<Sh: Shading<Fx16, Color = Rgb888>>(
    fb: &mut Framebuffer<'_, Rgb888>,
    xf: &Transforms<Fx16>,
    mesh: &Mesh<'_, Fx16, u32>,
    shading: Sh,
) {
    let mut zbuf = vec![u16::MAX; PIXELS];
    let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less).unwrap();
    let mut p = Pipeline::new(
        xf,
        Viewport::new(WIDTH, HEIGHT),
        CullClockwise,
        depth,
        shading,
    );
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let stats = p.draw(fb, mesh, &mut scratch).unwrap();
    assert!(stats.drawn > 0, "nothing drawn: {stats:?}");
}

/// Renders one case: RGB bytes, rows top to bottom.
fn render(model: Model, style: Style) -> Vec<u8> {
    let mut loaded = match model {
        Model::Cube => load("unit_cube.obj"),
        Model::Suzanne => load("suzanne.obj"),
    };
    // The cube file has no normals: smooth shading gets the averaged ones (rounded corners of
    // light on flat faces, as expected of Gouraud and Phong on a cube).
    if loaded.normals.is_none() {
        loaded.compute_smooth_normals();
    }
    // Vertex colours for the cube: the RGB cube, each corner's colour from its position.
    let colors: Vec<Rgb888> = loaded
        .positions
        .iter()
        .map(|p| {
            let ch = |v: Fx16| if v.to_bits() > 0 { 255 } else { 0 };
            Rgb888::new(ch(p.x), ch(p.y), ch(p.z))
        })
        .collect();
    let mut mesh = loaded.mesh();
    if style == Style::VertexColors {
        mesh.colors = Some(&colors);
    }
    let xf = transforms(model);
    let mut bytes = vec![0u8; PIXELS * 3];
    let mut fb = Framebuffer::<Rgb888>::new(&mut bytes, WIDTH, HEIGHT).unwrap();
    let Ok(()) = fb.clear(BACKGROUND);
    match style {
        Style::Wireframe => {
            let mut p = Pipeline::new(
                &xf,
                Viewport::new(WIDTH, HEIGHT),
                CullClockwise,
                NoDepth,
                Unlit {
                    color: Rgb888::WHITE,
                },
            );
            let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
            let Ok(stats) =
                p.draw_wireframe(&mut fb, &mesh, &mut scratch, Rgb888::new(120, 220, 160));
            assert!(stats.drawn > 0, "nothing drawn: {stats:?}");
        }
        Style::Unlit => {
            let color = DIFFUSE;
            fill(&mut fb, &xf, &mesh, Unlit { color });
        }
        Style::VertexColors => fill(&mut fb, &xf, &mesh, VertexColors::<Rgb888>::new()),
        Style::Flat => fill(
            &mut fb,
            &xf,
            &mesh,
            FlatLit::<_, Rgb888, 2>::new(lighting()),
        ),
        Style::Gouraud => fill(
            &mut fb,
            &xf,
            &mesh,
            GouraudLit::<_, Rgb888, 2>::new(lighting()),
        ),
        Style::Phong => fill(
            &mut fb,
            &xf,
            &mesh,
            PhongLit::<_, Rgb888, 2>::new(lighting()),
        ),
    }
    bytes
}

/// Writes an RGB picture as a PNG file, creating its directory.
fn write_png(path: &Path, rgb: &[u8]) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let file = File::create(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut encoder = png::Encoder::new(BufWriter::new(file), WIDTH, HEIGHT);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(rgb).unwrap();
    writer.finish().unwrap();
}

/// Reads an 8-bit RGB PNG file: `(width, height, bytes)`.
fn read_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let file = File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut reader = png::Decoder::new(BufReader::new(file))
        .read_info()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut buf = vec![0; reader.output_buffer_size().expect("a small picture")];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(
        (info.color_type, info.bit_depth),
        (png::ColorType::Rgb, png::BitDepth::Eight),
        "{}: not 8-bit RGB",
        path.display()
    );
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Where mismatch pictures go: `render-diff` in the workspace's target directory.
fn diff_dir() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target"));
    root().join(target).join("render-diff")
}

/// The reference picture's grey, dimmed, where `a` and `b` agree; magenta where they differ.
fn diff_image(reference: &[u8], actual: &[u8]) -> (usize, Vec<u8>) {
    let mut differing = 0;
    let mut out = Vec::with_capacity(reference.len());
    for (r, a) in reference.chunks_exact(3).zip(actual.chunks_exact(3)) {
        if r == a {
            let grey = ((u32::from(r[0]) * 3 + u32::from(r[1]) * 6 + u32::from(r[2])) / 30) as u8;
            out.extend([grey; 3]);
        } else {
            differing += 1;
            out.extend([255, 0, 255]);
        }
    }
    (differing, out)
}

/// Compares a case with its reference picture (or writes it, with `UPDATE_REFERENCE=1`).
fn check(model: Model, style: Style) {
    let case = format!("{}_{}", model.name(), style.name());
    let rgb = render(model, style);
    let path = root().join(format!("tests/images/pipeline/{case}.png"));
    let update =
        fixtures::update_reference_requested(std::env::var_os("UPDATE_REFERENCE").as_deref())
            .unwrap_or_else(|e| panic!("{e}"));
    if update {
        write_png(&path, &rgb);
        println!("UPDATE_REFERENCE=1: wrote {}", path.display());
        return;
    }
    assert!(
        path.exists(),
        "no reference picture {}: run `UPDATE_REFERENCE=1 cargo test -p tests --test \
         render_reference`, look at the picture, and commit it",
        path.display()
    );
    let (w, h, reference) = read_png(&path);
    assert_eq!((w, h), (WIDTH, HEIGHT), "{}: wrong size", path.display());
    let (differing, diff) = diff_image(&reference, &rgb);
    if differing > 0 {
        let diff_path = diff_dir().join(format!("{case}.png"));
        write_png(&diff_path, &diff);
        panic!(
            "{case}: {differing} of {PIXELS} pixels differ from {} (differences in magenta: {})",
            path.display(),
            diff_path.display()
        );
    }
}

#[test]
fn cube_wireframe() {
    check(Model::Cube, Style::Wireframe);
}

#[test]
fn cube_unlit() {
    check(Model::Cube, Style::Unlit);
}

#[test]
fn cube_vertex_colors() {
    check(Model::Cube, Style::VertexColors);
}

#[test]
fn cube_flat() {
    check(Model::Cube, Style::Flat);
}

#[test]
fn cube_gouraud() {
    check(Model::Cube, Style::Gouraud);
}

#[test]
fn cube_phong() {
    check(Model::Cube, Style::Phong);
}

#[test]
fn suzanne_wireframe() {
    check(Model::Suzanne, Style::Wireframe);
}

#[test]
fn suzanne_unlit() {
    check(Model::Suzanne, Style::Unlit);
}

#[test]
fn suzanne_flat() {
    check(Model::Suzanne, Style::Flat);
}

#[test]
fn suzanne_gouraud() {
    check(Model::Suzanne, Style::Gouraud);
}

#[test]
fn suzanne_phong() {
    check(Model::Suzanne, Style::Phong);
}

/// The diff picture marks exactly the differing pixels.
#[test]
fn diff_image_counts_and_marks_differences() {
    let reference = [10, 20, 30, 40, 50, 60, 70, 80, 90];
    let actual = [10, 20, 30, 40, 51, 60, 70, 80, 90];
    let (n, img) = diff_image(&reference, &actual);
    assert_eq!(n, 1);
    assert_eq!(&img[3..6], &[255, 0, 255]);
    assert_eq!(img[0], img[1]);
}
