//! Anti-aliased silhouettes (`Pipeline::draw_antialiased`, `draw_banded_antialiased`): each
//! pixel a silhouette edge crosses holds the exact covered fraction of the pixel (against the
//! area of the pixel clipped to the triangle in f64), interior edges leave no seam, bands give
//! the whole frame to the bit, and a draw that cannot anti-alias says why before it writes.

use fixtures::coverage::{draw_white, lone_triangles, pixel_area, quads, SIDE};
use rasterizer_core::mesh::MeshSource;
use rasterizer_core::numerics::{Numerics, SpanStart};
use rasterizer_core::pipeline::{AntialiasError, BandError, DrawError};
use rasterizer_core::prelude::*;

#[test]
fn the_exact_mapping_holds() {
    // The coverage tests' premise: without anti-aliasing a triangle on the 1/32 grid draws
    // exactly the pixels whose centres lie inside it (none strictly outside).
    let t = [(3.25, 5.5), (40.0, 12.03125), (20.5, 50.75)];
    let plain = draw_white(&t, &[[0, 1, 2]], None, false);
    let mut drawn = 0;
    for y in 0..SIDE as i32 {
        for x in 0..SIDE as i32 {
            let v = plain[(y * SIDE as i32 + x) as usize];
            if pixel_area(&t, x, y) == 0.0 {
                assert_eq!(v, 0, "({x}, {y})");
            }
            drawn += u32::from(v == 255);
        }
    }
    // The triangle's area is 775.1 pixels; 778 centres lie inside.
    assert!((770..=786).contains(&drawn), "{drawn}");
}

#[test]
fn a_lone_triangle_covers_each_pixel_by_its_exact_area() {
    let e = lone_triangles(0x9e37_79b9, 300);
    println!("{e:?}");
    // Measured: 0.0020 along edges (the 8-bit blend's rounding; 1/16 is the promise), 0.385 at
    // pixels holding a corner where two silhouette edges meet (estimated, not clipped).
    assert!(e.edge_pixels > 10_000, "{e:?}");
    assert_eq!(e.interior_wrong, 0);
    assert!(e.edge_max <= 0.004, "{e:?}");
    assert!(e.corner_max <= 0.6, "{e:?}");
}

#[test]
fn a_quad_keeps_its_diagonal_seamless() {
    // Two triangles sharing the diagonal: every pixel wholly inside the quad stays exactly
    // white (nothing along the diagonal is blended), and the outline is anti-aliased.
    let e = quads(0x1234_5678, 100);
    println!("{e:?}");
    // Measured: 0.0020 along edges, 0.26 at the quad's corners.
    assert_eq!(e.interior_wrong, 0);
    assert!(e.edge_max <= 0.004, "{e:?}");
    assert!(e.corner_max <= 0.5, "{e:?}");
}

fn suzanne() -> fixtures::obj::LoadedMesh {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    fixtures::obj::LoadedMesh::load(&path).unwrap()
}

fn m1_pipeline(
    depth: DepthBuffer<'_>,
    w: u32,
    h: u32,
) -> Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, GouraudLit<Fx16, Rgb565, 1>> {
    let xf = fixtures::scenes3d::camera(Mat4::rotation_y(Angle::from_degrees(30)), w, h);
    Pipeline::new(
        &xf,
        Viewport::new(w, h),
        CullClockwise,
        depth,
        GouraudLit::new(fixtures::scenes3d::lighting()),
    )
}

#[test]
fn bands_give_the_whole_frame() {
    let loaded = suzanne();
    let adjacency = fixtures::adjacency::adjacency(&loaded.triangles);
    let mesh = loaded.mesh().with_adjacency(&adjacency);
    let (w, h) = (120u32, 90u32);
    let background = Rgb565::new(4, 20, 12);
    let mut whole = vec![0u16; (w * h) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut whole, w, h).unwrap();
    fb.clear(background).unwrap();
    let mut z = vec![u16::MAX; (w * h) as usize];
    let mut p = m1_pipeline(DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap(), w, h);
    let mut scratch = vec![VertexSlot::EMPTY; mesh.vertex_count()];
    let stats = p.draw_antialiased(&mut fb, &mesh, &mut scratch).unwrap();
    // The plain draw differs exactly where silhouettes are blended.
    let mut plain = vec![0u16; (w * h) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut plain, w, h).unwrap();
    fb.clear(background).unwrap();
    let mut z = vec![u16::MAX; (w * h) as usize];
    let mut p = m1_pipeline(DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap(), w, h);
    assert_eq!(p.draw(&mut fb, &mesh, &mut scratch).unwrap(), stats);
    let changed = whole.iter().zip(&plain).filter(|(a, b)| a != b).count();
    // Measured: 339 (of the 2,081 pixels the head covers).
    assert!((170..=680).contains(&changed), "{changed}");
    for rows in [1u32, 5, 16, 89, 90, 200] {
        let mut band = vec![0u16; (w * rows.min(h)) as usize];
        let mut bins = vec![BinEntry::default(); mesh.triangle_count() + 4];
        let mut out = vec![0u16; (w * h) as usize];
        let mut z = vec![u16::MAX; (w * rows.min(h)) as usize];
        let mut p = m1_pipeline(
            DepthBuffer::new(&mut z, w, rows.min(h), Compare::Less).unwrap(),
            w,
            h,
        );
        let banding = Banding {
            width: w,
            height: h,
            rows,
            background,
            clear_depth: u16::MAX,
        };
        let banded = p
            .draw_banded_antialiased(&mesh, &banding, &mut band, &mut bins, &mut scratch, |b| {
                let y0 = b.y0() as usize * w as usize;
                let data = b.framebuffer().as_slice();
                out[y0..y0 + data.len()].copy_from_slice(data);
            })
            .unwrap();
        assert_eq!(banded, stats, "{rows} rows");
        assert!(out == whole, "{rows}-row bands differ from the whole frame");
    }
}

#[test]
fn a_draw_that_cannot_antialias_says_why_before_it_writes() {
    let loaded = suzanne();
    let (w, h) = (40u32, 30u32);
    let mut scratch = vec![VertexSlot::EMPTY; loaded.positions.len()];
    let mut words = vec![0u16; (w * h) as usize];
    let mut z = vec![u16::MAX; (w * h) as usize];
    // No adjacency.
    let mut fb = Framebuffer::<Rgb565>::new(&mut words, w, h).unwrap();
    let mut p = m1_pipeline(DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap(), w, h);
    let err = p
        .draw_antialiased(&mut fb, &loaded.mesh(), &mut scratch)
        .unwrap_err();
    assert_eq!(err, DrawError::Antialias(AntialiasError::NoAdjacency));
    assert!(words.iter().all(|&w| w == 0));
    let adjacency = fixtures::adjacency::adjacency(&loaded.triangles);
    let mesh = loaded.mesh().with_adjacency(&adjacency);
    // A target that cannot read back.
    let mut mock = embedded_graphics::mock_display::MockDisplay::<Rgb565>::new();
    let mut p = m1_pipeline(DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap(), w, h);
    let err = p
        .draw_antialiased(&mut AnyTarget::new(&mut mock), &mesh, &mut scratch)
        .unwrap_err();
    assert_eq!(err, DrawError::Antialias(AntialiasError::CannotReadBack));
    // Numerics without the fused span loop.
    struct Exact;
    impl Numerics for Exact {
        const SPANS: SpanStart = SpanStart::Exact;
    }
    let mut fb = Framebuffer::<Rgb565>::new(&mut words, w, h).unwrap();
    let mut p = m1_pipeline(DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap(), w, h)
        .with_numerics::<Exact>();
    let err = p
        .draw_antialiased(&mut fb, &mesh, &mut scratch)
        .unwrap_err();
    assert_eq!(err, DrawError::Antialias(AntialiasError::Numerics));
    // Bands: no adjacency.
    let mut band = vec![0u16; (w * 8) as usize];
    let mut bins = vec![BinEntry::default(); 1000];
    let mut z = vec![u16::MAX; (w * 8) as usize];
    let mut p = m1_pipeline(DepthBuffer::new(&mut z, w, 8, Compare::Less).unwrap(), w, h);
    let banding = Banding {
        width: w,
        height: h,
        rows: 8,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    let err = p
        .draw_banded_antialiased(
            &loaded.mesh(),
            &banding,
            &mut band,
            &mut bins,
            &mut scratch,
            |_| panic!("no band is drawn"),
        )
        .unwrap_err();
    assert_eq!(err, BandError::Antialias(AntialiasError::NoAdjacency));
}
