//! The convenience API: the prelude's constructors build exactly what the long forms build.

use rasterizer_core::depth::DepthBufferError;
use rasterizer_core::numerics::{Divide, Numerics, Perspective, SpanStart, Standard};
use rasterizer_core::pipeline::{BandError, DrawError, RenderStats};
use rasterizer_core::prelude::*;
use rasterizer_core::surface::FramebufferError;

fn p(x: i32, y: i32, z: i32) -> Vec3<Fx16> {
    Vec3::from_ints(x, y, z)
}

#[test]
fn look_at_is_the_view_and_projection_it_names() {
    let viewport = Viewport::new(160, 120);
    let fov = Angle::from_degrees(60);
    let t = Transforms::look_at(p(1, 2, 4), p(0, 0, 0), fov, viewport).unwrap();
    assert_eq!(t.model, Mat4::identity());
    assert_eq!(
        t.view,
        Mat4::look_at(p(1, 2, 4), p(0, 0, 0), p(0, 1, 0)).unwrap()
    );
    let aspect = Fx16::from_int(160) / Fx16::from_int(120);
    let near = Fx16::from_ratio(1, 8);
    let expected = Mat4::perspective(fov, aspect, near, Fx16::from_int(256)).unwrap();
    assert_eq!(t.projection, expected);
    let spun = Mat4::rotation_y(Angle::from_degrees(30));
    assert_eq!(t.with_model(spun).model, spun);
    assert_eq!(t.with_model(spun).view, t.view);
    // Looking straight down has no up direction; a zero-height viewport still has an aspect.
    assert!(Transforms::look_at(p(0, 4, 0), p(0, 0, 0), fov, viewport).is_none());
    assert!(Transforms::look_at(p(0, 0, 4), p(0, 0, 0), fov, Viewport::new(160, 0)).is_some());
}

#[test]
fn with_lights_is_new_plus_add_light() {
    let material = Material::new(Rgb888::new(200, 120, 60));
    assert_eq!(material.ambient, material.diffuse);
    let lights = [Light::directional(p(1, 1, 1)), Light::point(p(0, 3, 0))];
    let short = Lighting::with_lights(material, lights, p(0, 0, 4)).unwrap();
    let mut long = Lighting::<Fx16, 2>::new(
        material,
        Rgb888::new(32, 32, 32),
        Specular::BlinnPhong,
        p(0, 0, 4),
    );
    for l in lights {
        long.add_light(l).unwrap();
    }
    for n in [p(0, 0, 1), p(1, 1, 1), p(0, -1, 0), p(-1, 0, 2)] {
        assert_eq!(short.shade(p(0, 0, 0), n), long.shade(p(0, 0, 0), n));
    }
    // A zero direction is refused, as add_light refuses it.
    let bad = Light::directional(p(0, 0, 0));
    assert_eq!(
        Lighting::with_lights(material, [bad], p(0, 0, 4)).err(),
        Some(bad)
    );
}

#[test]
fn mesh_builders_set_their_slices() {
    let pos = [p(0, 0, 0), p(1, 0, 0), p(0, 1, 0)];
    let colors = [Rgb888::RED; 3];
    let tris = [[0u8, 1, 2]];
    let mesh = Mesh::new(&pos, &tris)
        .with_normals(&pos)
        .with_colors(&colors);
    assert_eq!(mesh.normals.map(<[_]>::len), Some(3));
    assert_eq!(mesh.colors.map(<[_]>::len), Some(3));
    const EMPTY: Mesh<'static, Fx16, u16> = Mesh::new(&[], &[]);
    assert!(EMPTY.normals.is_none() && EMPTY.triangles.is_empty());
}

/// A firmware-style owner of a pipeline, naming its type through the alias.
struct Renderer<'d> {
    pipeline: GouraudPipeline<'d>,
}

fn render(settings: impl FnOnce(GouraudPipeline<'_>) -> Vec<u16>, depths: &mut [u16]) -> Vec<u16> {
    let viewport = Viewport::new(64, 48);
    let camera = Transforms::look_at(p(0, 0, 4), p(0, 0, 0), Angle::from_degrees(60), viewport)
        .unwrap()
        .with_model(Mat4::rotation_y(Angle::from_degrees(30)));
    let material = Material::new(Rgb888::new(200, 120, 60));
    let lighting = Lighting::with_lights(material, [Light::directional(p(1, 1, 1))], p(0, 0, 4));
    let depth = DepthBuffer::new(depths, 64, 48, Compare::Less).unwrap();
    let renderer = Renderer {
        pipeline: Pipeline::new(
            &camera,
            viewport,
            CullClockwise,
            depth,
            GouraudLit::new(lighting.unwrap()),
        ),
    };
    settings(renderer.pipeline)
}

fn draw<const B: u32, N: Numerics>(
    mut p: Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, GouraudLit<Fx16, Rgb565, 1>, B, N>,
) -> Vec<u16> {
    let c = [
        Vec3::from_ints(1, 1, 1),
        Vec3::from_ints(-1, -1, 1),
        Vec3::from_ints(-1, 1, -1),
        Vec3::from_ints(1, -1, -1),
    ];
    let mesh = Mesh::new(&c, &[[0u16, 1, 3], [0, 2, 1], [0, 3, 2], [1, 2, 3]]).with_normals(&c);
    let mut buf = vec![0u16; 64 * 48];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 64, 48).unwrap();
    let stats = p.draw(&mut fb, &mesh, &mut [VertexSlot::EMPTY; 4]).unwrap();
    assert!(stats.drawn >= 2, "{stats:?}");
    buf
}

#[test]
fn settings_change_only_what_they_name() {
    let mut d = vec![u16::MAX; 64 * 48];
    let default = render(draw::<6, Standard>, &mut d);
    // The defaults of the settings trait are the library's defaults.
    struct Restated;
    impl Numerics for Restated {
        const DIVIDE: Divide = Divide::Exact;
        const FRAC: u32 = 16;
        const SPANS: SpanStart = SpanStart::Wrapping;
        const PERSPECTIVE: bool = false;
    }
    d.fill(u16::MAX);
    let restated = render(|p| draw(p.with_numerics::<Restated>()), &mut d);
    assert_eq!(default, restated);
    // Other sub-pixel bits and perspective correction give other pictures of the same object.
    d.fill(u16::MAX);
    let bits4 = render(|p| draw(p.with_bits::<4>()), &mut d);
    d.fill(u16::MAX);
    let persp = render(|p| draw(p.with_numerics::<Perspective>()), &mut d);
    let lit = |b: &[u16]| b.iter().filter(|&&c| c != 0).count();
    for other in [&bits4, &persp] {
        assert_ne!(*other, default);
        assert!(lit(other).abs_diff(lit(&default)) < lit(&default) / 20);
    }
    // Switching back restores the default exactly.
    d.fill(u16::MAX);
    let back = render(
        |p| {
            draw(
                p.with_bits::<2>()
                    .with_numerics::<Perspective>()
                    .with_bits::<6>()
                    .with_numerics::<Standard>(),
            )
        },
        &mut d,
    );
    assert_eq!(back, default);
}

#[test]
fn every_error_is_a_core_error_with_a_message() {
    fn message(e: &dyn core::error::Error) -> String {
        e.to_string()
    }
    let depth = DepthBufferError {
        expected: 12,
        actual: 11,
    };
    assert!(message(&depth).contains("11") && message(&depth).contains("12"));
    let fb = Framebuffer::<Rgb565>::new(&mut [0u16; 3], 2, 2).unwrap_err();
    assert!(matches!(fb, FramebufferError::WrongLength { .. }));
    assert!(message(&fb).contains('3'));
    assert!(!message(&BandError::NoRows).is_empty());
    let draw: DrawError<core::convert::Infallible> = DrawError::DepthTooSmall {
        needed: Rectangle::new(Point::new(1, 2), Size::new(3, 4)),
    };
    assert!(message(&draw).contains("3x4"));
    let _ = RenderStats::default();
}
