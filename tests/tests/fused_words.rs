//! The fused loop with a depth test draws into a framebuffer by writing its words directly
//! (`DepthTriangle::by_words`: a lean path for a triangle inside the clip area's columns on a
//! framebuffer of one word a pixel whose depth buffer shares its layout, a general one for the
//! rest), and into any other target span by span (`DepthTriangle::by_spans`). Both must give the
//! same picture and the same depth buffer, to the bit: on meshes and random triangle soups, for
//! every depth comparison, with viewports that cut triangles at their sides, depth buffers wider
//! than the framebuffer, and pixel formats of one word a pixel and of three.

use proptest::prelude::*;
use rasterizer_core::cull::Cull;
use rasterizer_core::mesh::MeshSource;
use rasterizer_core::numerics::{Dither, Numerics, Standard};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::{Shading, VertexColors};
use rasterizer_core::surface::Storage;

/// The M1 camera on a `w` x `h` screen, the model turned `yaw` degrees about y.
fn camera(w: u32, h: u32, yaw: i32) -> Transforms<Fx16> {
    fixtures::scenes3d::camera(Mat4::rotation_y(Angle::from_degrees(yaw)), w, h)
}

/// A picture and its depth buffer.
type Drawn<C> = (Vec<<C as Storage>::Word>, Vec<u16>);

/// Draws `mesh` with a fresh pipeline (`stages` gives its culling and shading) into a `w` x `h`
/// framebuffer of `C` and a depth buffer of `depth_width` entries a row, cleared to the far
/// plane: directly (`by_words`) when `any` is false, through [`AnyTarget`] (`by_spans`) when
/// it is true.
#[allow(clippy::too_many_arguments)]
fn draw<C, Cu, Sh, N>(
    xf: &Transforms<Fx16>,
    vp: Viewport,
    stages: &dyn Fn() -> (Cu, Sh),
    mesh: &impl MeshSource<Fx16>,
    (w, h): (u32, u32),
    depth_width: u32,
    compare: Compare,
    any: bool,
) -> Drawn<C>
where
    C: Storage,
    C::Word: Default,
    Cu: Cull,
    Sh: Shading<Fx16, Color = C>,
    N: Numerics,
{
    let mut z = vec![u16::MAX; (depth_width * h) as usize];
    let mut words = vec![C::Word::default(); Framebuffer::<C>::required_len(w, h).unwrap()];
    {
        let depth = DepthBuffer::new(&mut z, depth_width, h, compare).unwrap();
        let (cull, shading) = stages();
        let mut p = Pipeline::new(xf, vp, cull, depth, shading).with_numerics::<N>();
        let mut fb = Framebuffer::<C>::new(&mut words, w, h).unwrap();
        let mut scratch = vec![VertexSlot::EMPTY; mesh.vertex_count()];
        if any {
            p.draw(&mut AnyTarget::new(&mut fb), mesh, &mut scratch)
                .unwrap();
        } else {
            p.draw(&mut fb, mesh, &mut scratch).unwrap();
        }
    }
    (words, z)
}

/// Asserts that both ways of drawing give the same picture and depths (and returns how many
/// pixels were drawn, so that a caller can tell that something was).
#[allow(clippy::too_many_arguments)]
fn same<C, Cu, Sh, N>(
    xf: &Transforms<Fx16>,
    vp: Viewport,
    stages: &dyn Fn() -> (Cu, Sh),
    mesh: &impl MeshSource<Fx16>,
    size: (u32, u32),
    depth_width: u32,
    compare: Compare,
    what: &str,
) -> usize
where
    C: Storage,
    C::Word: Default + PartialEq,
    Cu: Cull,
    Sh: Shading<Fx16, Color = C>,
    N: Numerics,
{
    let words = draw::<C, Cu, Sh, N>(xf, vp, stages, mesh, size, depth_width, compare, false);
    let spans = draw::<C, Cu, Sh, N>(xf, vp, stages, mesh, size, depth_width, compare, true);
    assert!(words.0 == spans.0, "{what}: the pictures differ");
    assert!(words.1 == spans.1, "{what}: the depth buffers differ");
    words.1.iter().filter(|&&d| d != u16::MAX).count()
}

fn suzanne() -> fixtures::obj::LoadedMesh {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    fixtures::obj::LoadedMesh::load(&path).unwrap()
}

struct Bayer4;
impl Numerics for Bayer4 {
    const DITHER: Dither = Dither::Bayer4;
}

/// Suzanne lit per vertex (the default configuration), dithered, and with every depth
/// comparison, on the whole screen, on viewports that cut her at every side, and with a depth
/// buffer wider than the screen.
#[test]
fn suzanne_through_words_and_spans() {
    let m = suzanne();
    let mesh = m.mesh();
    let (w, h) = (160u32, 120u32);
    let lit = || {
        (
            CullClockwise,
            GouraudLit::<Fx16, Rgb565, 1>::new(fixtures::scenes3d::lighting()),
        )
    };
    let viewports = [
        Viewport::new(w, h),
        // Her left and right sides cut: those triangles' spans are clamped.
        Viewport {
            x: 20,
            y: 10,
            width: 100,
            height: 90,
        },
        Viewport {
            x: -40,
            y: -30,
            width: 160,
            height: 120,
        },
        Viewport {
            x: 70,
            y: 0,
            width: 160,
            height: 120,
        },
    ];
    for yaw in [0, 30, 75, 160, 250] {
        let xf = camera(w, h, yaw);
        for (i, vp) in viewports.iter().enumerate() {
            for depth_width in [w, w + 7] {
                let what = format!("yaw {yaw}, viewport {i}, depth width {depth_width}");
                let drawn = same::<Rgb565, _, _, Standard>(
                    &xf,
                    *vp,
                    &lit,
                    &mesh,
                    (w, h),
                    depth_width,
                    Compare::Less,
                    &what,
                );
                assert!(drawn > 1000, "{what}: {drawn} pixels");
                same::<Rgb565, _, _, Bayer4>(
                    &xf,
                    *vp,
                    &lit,
                    &mesh,
                    (w, h),
                    depth_width,
                    Compare::Less,
                    &what,
                );
            }
        }
    }
    // The other comparisons, on a buffer cleared to the far plane (some draw nothing).
    let xf = camera(w, h, 30);
    for compare in [
        Compare::LessEqual,
        Compare::Greater,
        Compare::GreaterEqual,
        Compare::Equal,
        Compare::NotEqual,
        Compare::Always,
        Compare::Never,
    ] {
        let what = format!("{compare:?}");
        same::<Rgb565, _, _, Standard>(&xf, viewports[0], &lit, &mesh, (w, h), w, compare, &what);
        same::<Rgb565, _, _, Standard>(&xf, viewports[1], &lit, &mesh, (w, h), w, compare, &what);
    }
}

/// Random triangle soups with random vertex colours, some of them large (wide planes), some
/// crossing the near plane (clipped), on random viewports, in all three word layouts.
fn soup() -> impl Strategy<Value = (Vec<Vec3<Fx16>>, Vec<Rgb888>)> {
    // Mostly within a unit or two of the origin (in front of the camera at z = 3), now and
    // then far out or behind the near plane.
    let coord = prop_oneof![
        8 => -2 * 65536i32..2 * 65536,
        1 => -40 * 65536i32..40 * 65536,
    ];
    let z = prop_oneof![
        8 => -2 * 65536i32..2 * 65536,
        1 => 2 * 65536i32..5 * 65536,
    ];
    let vertex = (coord.clone(), coord, z).prop_map(|(x, y, z)| {
        Vec3::new(Fx16::from_bits(x), Fx16::from_bits(y), Fx16::from_bits(z))
    });
    let color = any::<[u8; 3]>().prop_map(|c| Rgb888::new(c[0], c[1], c[2]));
    (1usize..12).prop_flat_map(move |n| {
        (
            prop::collection::vec(vertex.clone(), 3 * n),
            prop::collection::vec(color.clone(), 3 * n),
        )
    })
}

fn compare_mode() -> impl Strategy<Value = Compare> {
    prop_oneof![
        4 => Just(Compare::Less),
        1 => Just(Compare::LessEqual),
        1 => Just(Compare::Greater),
        1 => Just(Compare::GreaterEqual),
        1 => Just(Compare::Equal),
        1 => Just(Compare::NotEqual),
        1 => Just(Compare::Always),
    ]
}

fn viewport() -> impl Strategy<Value = Viewport> {
    prop_oneof![
        2 => Just(Viewport::new(64, 48)),
        1 => (-30i32..50, -20i32..40, 8u32..90, 8u32..70).prop_map(|(x, y, width, height)| {
            Viewport { x, y, width, height }
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn soups_through_words_and_spans(
        (positions, colors) in soup(),
        compare in compare_mode(),
        vp in viewport(),
        wider in prop_oneof![3 => Just(0u32), 1 => 1u32..9],
        format in 0u32..3,
    ) {
        let triangles: Vec<[u16; 3]> =
            (0..positions.len() as u16 / 3).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
        let mesh = Mesh::new(&positions, &triangles).with_colors(&colors);
        let (w, h) = (64u32, 48u32);
        let xf = camera(w, h, 0);
        let what = format!("{vp:?}, depth {wider} wider, {compare:?}, format {format}");
        match format {
            0 => {
                let stages = || (NoCull, VertexColors::<Rgb565>::new());
                same::<Rgb565, _, _, Standard>(&xf, vp, &stages, &mesh, (w, h), w + wider, compare, &what);
            }
            1 => {
                let stages = || (NoCull, VertexColors::<Gray8>::new());
                same::<Gray8, _, _, Standard>(&xf, vp, &stages, &mesh, (w, h), w + wider, compare, &what);
            }
            _ => {
                let stages = || (NoCull, VertexColors::<Rgb888>::new());
                same::<Rgb888, _, _, Standard>(&xf, vp, &stages, &mesh, (w, h), w + wider, compare, &what);
            }
        }
    }
}
