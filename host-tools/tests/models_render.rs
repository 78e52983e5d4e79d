//! Every shared model converts and renders from its packed blob (the firmware's path), and a few
//! match reference PNGs exactly (`UPDATE_REFERENCE=1` writes them).

use host_tools::convert::{convert_obj, Options};
use rasterizer_core::mesh::MeshSource;
use rasterizer_core::prelude::*;
use std::path::{Path, PathBuf};

const W: u32 = 160;
const H: u32 = 120;

fn shared_models() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/assets/models")
}

/// Converts (centred on the unit sphere) and renders with Gouraud lighting from two sides, no
/// culling (some models are open meshes); returns the Rgb888 pixels and the pixels drawn.
fn render(path: &Path) -> (Vec<u8>, usize) {
    let bytes = std::fs::read(path).unwrap();
    let opts = Options {
        center_unit_sphere: true,
        ..Options::default()
    };
    let mut warnings = Vec::new();
    let conv = convert_obj(
        &path.display().to_string(),
        &bytes,
        path.parent(),
        &opts,
        &mut warnings,
    )
    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mesh = PackedMesh::parse(&conv.blob).unwrap();
    assert!(MeshSource::<Fx16>::triangle_count(&mesh) > 0);
    let xf = Transforms {
        model: Mat4::rotation_y(Angle::from_degrees(35))
            .then(&Mat4::rotation_x(Angle::from_degrees(20))),
        view: Mat4::look_at(
            Vec3::from_ints(0, 0, 3),
            Vec3::default(),
            Vec3::from_ints(0, 1, 0),
        )
        .unwrap(),
        projection: Mat4::perspective(
            Angle::from_degrees(50),
            Fx16::from_ratio(4, 3),
            Fx16::from_ratio(1, 10),
            Fx16::from_int(10),
        )
        .unwrap(),
    };
    let mut lighting = Lighting::<Fx16, 2>::new(
        Material {
            ambient: Rgb888::new(40, 40, 50),
            diffuse: Rgb888::new(200, 170, 120),
            specular: Rgb888::new(120, 120, 120),
            shininess: 12,
        },
        Rgb888::WHITE,
        Specular::BlinnPhong,
        Vec3::from_ints(0, 0, 3),
    );
    lighting
        .add_light(Light::Directional {
            direction: Vec3::from_ints(1, 1, 1),
            color: Rgb888::WHITE,
        })
        .unwrap();
    lighting
        .add_light(Light::Directional {
            direction: Vec3::from_ints(-1, 0, -1),
            color: Rgb888::new(80, 80, 120),
        })
        .unwrap();
    let mut z = vec![u16::MAX; (W * H) as usize];
    let depth = DepthBuffer::new(&mut z, W, H, Compare::Less).unwrap();
    let mut p = Pipeline::new(
        &xf,
        Viewport::new(W, H),
        NoCull,
        depth,
        GouraudLit::<Fx16, Rgb888, 2>::new(lighting),
    );
    let mut buf = vec![0u8; (W * H * 3) as usize];
    let mut fb = Framebuffer::<Rgb888>::new(&mut buf, W, H).unwrap();
    fb.clear(Rgb888::BLACK).unwrap();
    let mut scratch = vec![VertexSlot::EMPTY; mesh.vertices()];
    let stats = p.draw(&mut fb, &mesh, &mut scratch).unwrap();
    assert!(
        stats.drawn > 0,
        "{}: nothing drawn {stats:?}",
        path.display()
    );
    let covered = buf.chunks(3).filter(|c| c != &[0, 0, 0]).count();
    (buf, covered)
}

#[test]
fn every_shared_model_converts_and_renders() {
    let mut names: Vec<PathBuf> = std::fs::read_dir(shared_models())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "obj"))
        .collect();
    names.sort();
    assert!(
        names.len() >= 15,
        "expected the shared models, found {}",
        names.len()
    );
    for path in names {
        let (_, covered) = render(&path);
        // Each model fills a visible part of the frame once centred on the unit sphere.
        assert!(covered > 200, "{}: only {covered} pixels", path.display());
    }
}

#[test]
fn reference_pictures_of_three_models() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/images/models");
    let update =
        fixtures::update_reference_requested(std::env::var_os("UPDATE_REFERENCE").as_deref())
            .unwrap_or_else(|e| panic!("{e}"));
    for name in ["teapot", "spot_triangulated", "icosphere"] {
        let (buf, _) = render(&shared_models().join(format!("{name}.obj")));
        let file = dir.join(format!("{name}.png"));
        if update {
            std::fs::create_dir_all(&dir).unwrap();
            image::save_buffer(&file, &buf, W, H, image::ExtendedColorType::Rgb8).unwrap();
            eprintln!("wrote {}", file.display());
            continue;
        }
        let want = image::open(&file)
            .unwrap_or_else(|e| {
                panic!(
                    "{}: {e} (run with UPDATE_REFERENCE=1 to create it)",
                    file.display()
                )
            })
            .to_rgb8();
        let differ = want
            .as_raw()
            .chunks(3)
            .zip(buf.chunks(3))
            .filter(|(a, b)| a != b)
            .count();
        if differ > 0 {
            let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-actual.png"));
            image::save_buffer(&out, &buf, W, H, image::ExtendedColorType::Rgb8).unwrap();
            panic!(
                "{name}: {differ} of {} pixels differ from {} (actual in {})",
                W * H,
                file.display(),
                out.display()
            );
        }
    }
}
