//! Band rendering gives exactly the whole-frame picture (and the same statistics), for every band
//! height, with a full vertex scratch, a short one and none, on meshes and on random triangle soups
//! (with and without a depth test, where draw order matters); bins stay 2 bytes for any mesh size
//! and any number of bands.

use embedded_graphics_core::pixelcolor::raw::RawU16;
use proptest::prelude::*;
use rasterizer_core::depth::DepthTest;
use rasterizer_core::numerics::{Dither, Divide, Numerics, Perspective, SpanStart, Standard};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::Shading;
use rasterizer_core::{
    mesh::MeshSource, pipeline::BandError, pipeline::RenderStats, pipeline::DEFAULT_BITS,
};

fn suzanne() -> fixtures::obj::LoadedMesh {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    fixtures::obj::LoadedMesh::load(&path).unwrap()
}

/// The M1 camera with the model turned `yaw` degrees about y.
fn transforms(w: u32, h: u32, yaw: i32) -> Transforms<Fx16> {
    fixtures::scenes3d::camera(Mat4::rotation_y(Angle::from_degrees(yaw)), w, h)
}

// The M1 lighting, shared with the benchmarks.
use fixtures::scenes3d::lighting;

/// How much vertex scratch a draw gets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Scratch {
    /// One slot per mesh vertex.
    Full,
    /// Slots for the first half of the vertices.
    Half,
    /// None.
    Empty,
}

impl Scratch {
    const ALL: [Scratch; 3] = [Scratch::Full, Scratch::Half, Scratch::Empty];

    /// A scratch of this size for `mesh`.
    fn slots<St: rasterizer_core::shade::Packed>(
        self,
        mesh: &impl MeshSource<Fx16>,
    ) -> Vec<VertexSlot<St>> {
        let n = match self {
            Scratch::Full => mesh.vertex_count(),
            Scratch::Half => mesh.vertex_count() / 2,
            Scratch::Empty => 0,
        };
        vec![VertexSlot::EMPTY; n]
    }
}

/// A whole-frame draw with a full scratch: the picture every banded draw must give.
fn whole_frame<M, C, D, Sh, N>(
    mesh: &M,
    w: u32,
    h: u32,
    mut p: Pipeline<Fx16, C, D, Sh, DEFAULT_BITS, N>,
) -> (Vec<u16>, RenderStats)
where
    M: MeshSource<Fx16>,
    C: rasterizer_core::cull::Cull,
    D: DepthTest,
    Sh: Shading<Fx16, Color = Rgb565>,
    N: Numerics,
{
    let mut whole = vec![0u16; (w * h) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut whole, w, h).unwrap();
    fb.clear(Rgb565::BLACK).unwrap();
    let stats = p
        .draw(&mut fb, mesh, &mut Scratch::Full.slots(mesh))
        .unwrap();
    (whole, stats)
}

fn banded<M, C, D, Sh, N>(
    mesh: &M,
    w: u32,
    h: u32,
    rows: u32,
    scratch: Scratch,
    mut p: Pipeline<Fx16, C, D, Sh, DEFAULT_BITS, N>,
) -> (Vec<u16>, RenderStats)
where
    M: MeshSource<Fx16>,
    C: rasterizer_core::cull::Cull,
    D: DepthTest,
    Sh: Shading<Fx16, Color = Rgb565>,
    N: Numerics,
{
    let mut band = vec![0u16; (w * rows.min(h)) as usize];
    // A bin per triangle, and a filler for each gap of 255 (at most one per 255 triangles).
    let mut bins = vec![BinEntry::default(); mesh.triangle_count() + mesh.triangle_count() / 255];
    let mut out = vec![0u16; (w * h) as usize];
    let banding = Banding {
        width: w,
        height: h,
        rows,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    let mut slots = scratch.slots(mesh);
    let mut next_row = 0;
    let stats = p
        .draw_banded(mesh, &banding, &mut band, &mut bins, &mut slots, |b| {
            // Bands come top to bottom, each `rows` high but the last.
            assert_eq!(b.y0(), next_row);
            let y0 = b.y0() as usize * w as usize;
            let data = b.framebuffer().as_slice();
            out[y0..y0 + data.len()].copy_from_slice(data);
            next_row += rows as i32;
        })
        .unwrap();
    assert_eq!(
        next_row as u32,
        h.div_ceil(rows) * rows,
        "every band handed on once"
    );
    (out, stats)
}

/// The whole frame, then the same scene in bands of each height, compared pixel for pixel and
/// statistic for statistic: with the scratch sizes `scratch` gives for a band height.
fn compare_bands<M, C, Sh>(
    mesh: &M,
    w: u32,
    h: u32,
    make: &dyn Fn() -> (C, Sh),
    depth: Option<Compare>,
    rows_list: &[u32],
    scratch: &dyn Fn(u32) -> Vec<Scratch>,
) where
    M: MeshSource<Fx16>,
    C: rasterizer_core::cull::Cull,
    Sh: Shading<Fx16, Color = Rgb565>,
{
    let xf = transforms(w, h, 23);
    let vp = Viewport::new(w, h);
    let whole = match depth {
        Some(cmp) => {
            let mut z = vec![u16::MAX; (w * h) as usize];
            let (c, sh) = make();
            whole_frame(
                mesh,
                w,
                h,
                Pipeline::new(&xf, vp, c, DepthBuffer::new(&mut z, w, h, cmp).unwrap(), sh),
            )
        }
        None => {
            let (c, sh) = make();
            whole_frame(mesh, w, h, Pipeline::new(&xf, vp, c, NoDepth, sh))
        }
    };
    let (whole, whole_stats) = whole;
    for &rows in rows_list {
        for s in scratch(rows) {
            let (out, stats) = match depth {
                Some(cmp) => {
                    let r = rows.min(h);
                    let mut z = vec![u16::MAX; (w * r) as usize];
                    let (c, sh) = make();
                    let d = DepthBuffer::new(&mut z, w, r, cmp).unwrap();
                    banded(mesh, w, h, rows, s, Pipeline::new(&xf, vp, c, d, sh))
                }
                None => {
                    let (c, sh) = make();
                    banded(mesh, w, h, rows, s, Pipeline::new(&xf, vp, c, NoDepth, sh))
                }
            };
            let differ = whole.iter().zip(&out).filter(|(a, b)| a != b).count();
            assert_eq!(
                differ, 0,
                "{differ} pixels differ with bands of {rows} rows ({s:?} scratch)"
            );
            assert_eq!(stats, whole_stats, "bands of {rows} rows ({s:?} scratch)");
        }
    }
}

/// Band renders equal the whole frame for every numeric knob (`rasterizer_core::numerics`): with
/// reciprocal divides, fewer interpolation bits and gradient span starts too, the values of a pixel
/// depend on its position alone.
#[test]
fn suzanne_bands_for_every_numerics() {
    type Gouraud = GouraudLit<Fx16, Rgb565, 1>;
    fn pipeline<N: Numerics>(
        depth: &mut [u16],
        rows: u32,
    ) -> Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, Gouraud, DEFAULT_BITS, N> {
        Pipeline::new(
            &transforms(160, 120, 30),
            Viewport::new(160, 120),
            CullClockwise,
            DepthBuffer::new(depth, 160, rows, Compare::Less).unwrap(),
            GouraudLit::new(lighting::<1>()),
        )
        .with_numerics::<N>()
    }
    fn check<N: Numerics>(mesh: &Mesh<'_, Fx16, u32>) {
        let (w, h) = (160u32, 120u32);
        let mut z = vec![u16::MAX; (w * h) as usize];
        let (whole, _) = whole_frame(mesh, w, h, pipeline::<N>(&mut z, h));
        for (rows, scratch) in [
            (1u32, Scratch::Full),
            (7, Scratch::Empty),
            (16, Scratch::Half),
            (120, Scratch::Full),
        ] {
            let mut z = vec![u16::MAX; (w * rows) as usize];
            let (out, _) = banded(mesh, w, h, rows, scratch, pipeline::<N>(&mut z, rows));
            assert!(out == whole, "{rows} rows differ ({scratch:?} scratch)");
        }
    }
    let m = suzanne();
    let mesh = m.mesh();
    check::<Standard>(&mesh);
    struct Gradient16;
    impl Numerics for Gradient16 {
        const SPANS: SpanStart = SpanStart::Gradient;
    }
    struct NewtonGradient8;
    impl Numerics for NewtonGradient8 {
        const DIVIDE: Divide = Divide::Newton;
        const FRAC: u32 = 8;
        const SPANS: SpanStart = SpanStart::Gradient;
    }
    struct ReciprocalExact12;
    impl Numerics for ReciprocalExact12 {
        const DIVIDE: Divide = Divide::Reciprocal;
        const FRAC: u32 = 12;
        const SPANS: SpanStart = SpanStart::Exact;
    }
    check::<Gradient16>(&mesh);
    check::<NewtonGradient8>(&mesh);
    check::<ReciprocalExact12>(&mesh);
    // Perspective-correct colours too, whose hidden-triangle test reads each band's depths.
    check::<Perspective>(&mesh);
}

/// Dithering takes its threshold from the screen position, not the band's: bands of heights
/// that are no multiple of the matrix's size match the whole frame, with and without a depth test.
#[test]
fn dithered_bands_match_the_whole_frame() {
    struct Bayer4;
    impl Numerics for Bayer4 {
        const DITHER: Dither = Dither::Bayer4;
    }
    struct Bayer8;
    impl Numerics for Bayer8 {
        const DITHER: Dither = Dither::Bayer8;
    }
    fn check<N: Numerics>(mesh: &Mesh<'_, Fx16, u32>) {
        let (w, h) = (160u32, 120u32);
        let xf = transforms(w, h, 30);
        let vp = Viewport::new(w, h);
        let shading = || GouraudLit::<Fx16, Rgb565, 1>::new(lighting::<1>());
        let mut z = vec![u16::MAX; (w * h) as usize];
        let db = DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap();
        let p = Pipeline::new(&xf, vp, CullClockwise, db, shading()).with_numerics::<N>();
        let (whole, _) = whole_frame(mesh, w, h, p);
        let (flat, _) = whole_frame(
            mesh,
            w,
            h,
            Pipeline::new(&xf, vp, CullClockwise, NoDepth, shading()).with_numerics::<N>(),
        );
        for rows in [1u32, 3, 5, 6, 7, 13, 30] {
            let mut z = vec![u16::MAX; (w * rows) as usize];
            let db = DepthBuffer::new(&mut z, w, rows, Compare::Less).unwrap();
            let p = Pipeline::new(&xf, vp, CullClockwise, db, shading()).with_numerics::<N>();
            let (out, _) = banded(mesh, w, h, rows, Scratch::Full, p);
            assert!(out == whole, "{rows} rows differ (depth buffer)");
            let p = Pipeline::new(&xf, vp, CullClockwise, NoDepth, shading()).with_numerics::<N>();
            let (out, _) = banded(mesh, w, h, rows, Scratch::Half, p);
            assert!(out == flat, "{rows} rows differ (no depth)");
        }
    }
    let m = suzanne();
    let mesh = m.mesh();
    check::<Bayer4>(&mesh);
    check::<Bayer8>(&mesh);
}

#[test]
fn suzanne_every_band_height() {
    let m = suzanne();
    let mesh = m.mesh();
    let (w, h) = (160u32, 120u32);
    let rows: Vec<u32> = (1..=h).collect();
    compare_bands(
        &mesh,
        w,
        h,
        &|| {
            (
                CullClockwise,
                GouraudLit::<Fx16, Rgb565, 1>::new(lighting()),
            )
        },
        Some(Compare::Less),
        &rows,
        // Each scratch size in turn: a third of the heights each.
        &|rows| vec![Scratch::ALL[rows as usize % 3]],
    );
}

/// Fog is per vertex (per triangle for flat shading), so bands match the whole frame: Gouraud,
/// flat and vertex colours, linear and exponential, with and without a depth test, and dithered.
#[test]
fn fogged_bands_match_the_whole_frame() {
    use rasterizer_core::shade::{Fog, FogCurve, FogSettings};
    let m = suzanne();
    let mesh = m.mesh();
    let (w, h) = (160u32, 120u32);
    // compare_bands' camera: the view is the same for any turn of the model.
    let view = transforms(w, h, 23).view;
    let fog = |curve| FogSettings {
        color: Rgb888::new(128, 144, 160),
        start: Fx16::from_ratio(5, 2),
        end: Fx16::from_int(4),
        curve,
    };
    let rows = [1u32, 5, 16, 33, 120];
    let scratch = |rows: u32| vec![Scratch::ALL[rows as usize % 3]];
    for curve in [FogCurve::Linear, FogCurve::exponential(48)] {
        for depth in [Some(Compare::Less), None] {
            compare_bands(
                &mesh,
                w,
                h,
                &|| {
                    let lit = GouraudLit::<Fx16, Rgb565, 1>::new(lighting());
                    (CullClockwise, Fog::new(lit, fog(curve), &view))
                },
                depth,
                &rows,
                &scratch,
            );
        }
        compare_bands(
            &mesh,
            w,
            h,
            &|| {
                let flat = FlatLit::<Fx16, Rgb565, 1>::new(lighting());
                (CullClockwise, Fog::new(flat, fog(curve), &view))
            },
            Some(Compare::Less),
            &rows,
            &scratch,
        );
        compare_bands(
            &mesh,
            w,
            h,
            &|| {
                let colors = VertexColors::<Rgb565>::new();
                (CullClockwise, Fog::new(colors, fog(curve), &view))
            },
            Some(Compare::Less),
            &rows,
            &scratch,
        );
    }
    struct Bayer4;
    impl Numerics for Bayer4 {
        const DITHER: Dither = Dither::Bayer4;
    }
    let xf = transforms(w, h, 30);
    let vp = Viewport::new(w, h);
    let shading = || {
        let lit = GouraudLit::<Fx16, Rgb565, 1>::new(lighting());
        Fog::new(lit, fog(FogCurve::Linear), &xf.view)
    };
    let (whole, _) = whole_frame(
        &mesh,
        w,
        h,
        Pipeline::new(&xf, vp, CullClockwise, NoDepth, shading()).with_numerics::<Bayer4>(),
    );
    for rows in [3u32, 7, 16] {
        let p = Pipeline::new(&xf, vp, CullClockwise, NoDepth, shading()).with_numerics::<Bayer4>();
        let (out, _) = banded(&mesh, w, h, rows, Scratch::Half, p);
        assert!(out == whole, "{rows} rows differ (dithered fog)");
    }
}

/// MatCap colours are per vertex, so bands match the whole frame: with and without a depth
/// test, fogged, and with a short scratch and none.
#[test]
fn matcap_bands_match_the_whole_frame() {
    use fixtures::matcap::{GLOSSY_64, GLOSSY_64_SIDE_LOG2};
    use rasterizer_core::shade::{Fog, FogCurve, FogSettings};
    let m = suzanne();
    let mesh = m.mesh();
    let (w, h) = (160u32, 120u32);
    // compare_bands' camera: the view is the same for any turn of the model.
    let view = transforms(w, h, 23).view;
    let matcap = || MatCap::<Fx16, Rgb565>::new(GLOSSY_64_SIDE_LOG2, GLOSSY_64, &view).unwrap();
    let rows = [1u32, 5, 16, 33, 120];
    let scratch = |rows: u32| vec![Scratch::ALL[rows as usize % 3]];
    for depth in [Some(Compare::Less), None] {
        compare_bands(
            &mesh,
            w,
            h,
            &|| (CullClockwise, matcap()),
            depth,
            &rows,
            &scratch,
        );
    }
    let fog = FogSettings {
        color: Rgb888::new(128, 144, 160),
        start: Fx16::from_ratio(5, 2),
        end: Fx16::from_int(4),
        curve: FogCurve::Linear,
    };
    compare_bands(
        &mesh,
        w,
        h,
        &|| (CullClockwise, Fog::new(matcap(), fog, &view)),
        Some(Compare::Less),
        &rows,
        &scratch,
    );
}

#[test]
fn suzanne_m1_size_common_band_heights_with_and_without_scratch() {
    let m = suzanne();
    let mesh = m.mesh();
    let (w, h) = (320u32, 240u32);
    let mut whole = vec![0u16; (w * h) as usize];
    let mut z = vec![u16::MAX; (w * h) as usize];
    {
        let mut fb = Framebuffer::<Rgb565>::new(&mut whole, w, h).unwrap();
        let depth = DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap();
        let mut p = Pipeline::new(
            &transforms(w, h, 30),
            Viewport::new(w, h),
            CullClockwise,
            depth,
            GouraudLit::<Fx16, Rgb565, 1>::new(lighting()),
        );
        let mut scratch = vec![VertexSlot::EMPTY; mesh.vertex_count()];
        let stats = p.draw(&mut fb, &mesh, &mut scratch).unwrap();
        assert_eq!((stats.drawn, stats.culled), (609, 359));
    }
    for (rows, scratch) in [
        (8u32, Scratch::Full),
        (16, Scratch::Full),
        (16, Scratch::Empty),
        (32, Scratch::Half),
        (240, Scratch::Full),
    ] {
        let mut band = vec![0u16; (w * rows) as usize];
        let mut zb = vec![u16::MAX; (w * rows) as usize];
        let mut bins = vec![BinEntry::default(); 1000];
        let mut slots = scratch.slots(&mesh);
        let depth = DepthBuffer::new(&mut zb, w, rows, Compare::Less).unwrap();
        let mut p = Pipeline::new(
            &transforms(w, h, 30),
            Viewport::new(w, h),
            CullClockwise,
            depth,
            GouraudLit::<Fx16, Rgb565, 1>::new(lighting()),
        );
        let mut out = vec![0u16; (w * h) as usize];
        let banding = Banding {
            width: w,
            height: h,
            rows,
            background: Rgb565::BLACK,
            clear_depth: u16::MAX,
        };
        let stats = p
            .draw_banded(&mesh, &banding, &mut band, &mut bins, &mut slots, |b| {
                let y0 = b.y0() as usize * w as usize;
                let data = b.framebuffer().as_slice();
                out[y0..y0 + data.len()].copy_from_slice(data);
            })
            .unwrap();
        assert_eq!((stats.drawn, stats.culled), (609, 359));
        assert_eq!(whole, out, "bands of {rows} rows ({scratch:?} scratch)");
    }
}

#[test]
fn band_errors_are_typed() {
    let m = suzanne();
    let mesh = m.mesh();
    let (w, h) = (64u32, 48u32);
    let mut p = Pipeline::new(
        &transforms(w, h, 0),
        Viewport::new(w, h),
        CullClockwise,
        NoDepth,
        GouraudLit::<Fx16, Rgb565, 1>::new(lighting()),
    );
    let banding = |rows| Banding {
        width: w,
        height: h,
        rows,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    let mut band = vec![0u16; (w * 8) as usize];
    let mut bins = vec![BinEntry::default(); 4];
    assert_eq!(
        p.draw_banded(&mesh, &banding(0), &mut band, &mut bins, &mut [], |_| {})
            .unwrap_err(),
        BandError::NoRows
    );
    assert!(matches!(
        p.draw_banded(&mesh, &banding(16), &mut band, &mut bins, &mut [], |_| {})
            .unwrap_err(),
        BandError::BandBufferTooSmall { .. }
    ));
    let mut called = false;
    let err = p
        .draw_banded(&mesh, &banding(8), &mut band, &mut bins, &mut [], |_| {
            called = true
        })
        .unwrap_err();
    assert!(
        matches!(err, BandError::TooFewBins { actual: 4, .. }),
        "{err:?}"
    );
    assert!(!called, "nothing is drawn when the bins are too few");
    // The count it asks for is enough, and one fewer is not.
    let Err(BandError::TooFewBins { needed, .. }) =
        p.draw_banded(&mesh, &banding(8), &mut band, &mut [], &mut [], |_| {})
    else {
        panic!("no bins must be too few");
    };
    assert!(needed > 100, "{needed} bins for Suzanne");
    let mut bins = vec![BinEntry::default(); needed];
    assert_eq!(
        p.draw_banded(
            &mesh,
            &banding(8),
            &mut band,
            &mut bins[..needed - 1],
            &mut [],
            |_| {}
        )
        .unwrap_err(),
        BandError::TooFewBins {
            needed,
            actual: needed - 1
        }
    );
    let mut bands = 0;
    p.draw_banded(&mesh, &banding(8), &mut band, &mut bins, &mut [], |_| {
        bands += 1
    })
    .unwrap();
    assert_eq!(bands, 6);
}

#[test]
fn band_depth_buffer_too_small_is_an_error() {
    let m = suzanne();
    let mesh = m.mesh();
    let (w, h, rows) = (64u32, 48u32, 8u32);
    let banding = Banding {
        width: w,
        height: h,
        rows,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    let draw = |viewport: Viewport, zw: u32, zh: u32| {
        let mut z = vec![u16::MAX; (zw * zh) as usize];
        let depth = DepthBuffer::new(&mut z, zw, zh, Compare::Less).unwrap();
        let mut p = Pipeline::new(
            &transforms(w, h, 0),
            viewport,
            CullClockwise,
            depth,
            GouraudLit::<Fx16, Rgb565, 1>::new(lighting()),
        );
        let mut band = vec![0u16; (w * rows) as usize];
        let mut bins = vec![BinEntry::default(); mesh.triangle_count()];
        let mut scratch = vec![VertexSlot::EMPTY; mesh.vertex_count()];
        let mut called = false;
        let result = p.draw_banded(&mesh, &banding, &mut band, &mut bins, &mut scratch, |_| {
            called = true
        });
        assert_eq!(
            called,
            result.is_ok(),
            "bands drawn although the draw failed"
        );
        result
    };
    let band_rect = |x, wd, ht| Rectangle::new(Point::new(x, 0), Size::new(wd, ht));
    // One row short, one column short.
    let full = Viewport::new(w, h);
    assert_eq!(
        draw(full, w, rows - 1).unwrap_err(),
        BandError::DepthTooSmall {
            needed: band_rect(0, w, rows)
        }
    );
    assert_eq!(
        draw(full, w - 1, rows).unwrap_err(),
        BandError::DepthTooSmall {
            needed: band_rect(0, w, rows)
        }
    );
    assert!(draw(full, w, rows).is_ok());
    // A buffer of a whole frame holds every band too.
    assert!(draw(full, w, h).is_ok());
    // Only the band within the viewport needs depths: a viewport of the left half needs half a
    // band, one that starts further right needs the columns up to its right edge.
    let left = Viewport::new(w / 2, h);
    assert!(draw(left, w / 2, rows).is_ok());
    let right = Viewport {
        x: 8,
        y: 0,
        width: w / 2,
        height: h,
    };
    assert_eq!(
        draw(right, w / 2, rows).unwrap_err(),
        BandError::DepthTooSmall {
            needed: band_rect(8, w / 2, rows)
        }
    );
    assert!(draw(right, w / 2 + 8, rows).is_ok());
}

/// A mesh of `count` triangles of which only those in `visible` lie in front of the camera: the
/// others alternate between a degenerate triangle (zero area, culled) and one behind the camera
/// (outside). The visible ones overlap, each in its own colour, so that a frame drawn without a
/// depth test shows their order.
fn sparse_mesh(visible: &[usize], count: usize) -> (Vec<Vec3<Fx16>>, Vec<Rgb888>, Vec<[u16; 3]>) {
    let v = |x: i32, y: i32, z: i32| {
        Vec3::new(
            Fx16::from_ratio(i64::from(x), 8),
            Fx16::from_ratio(i64::from(y), 8),
            Fx16::from_ratio(i64::from(z), 8),
        )
    };
    let mut positions = vec![
        // Behind the camera at z = 3.
        v(-8, -8, 40),
        v(8, -8, 40),
        v(0, 8, 40),
        // In front of it.
        v(0, 0, 0),
    ];
    let mut colors = vec![Rgb888::WHITE; positions.len()];
    let mut tris: Vec<[u16; 3]> = (0..count)
        .map(|t| if t % 2 == 0 { [3, 3, 3] } else { [0, 1, 2] })
        .collect();
    // Each visible triangle its own, shifted a little to the right and down from the last, all
    // overlapping (counter-clockwise, as seen from the camera).
    for (k, &t) in visible.iter().enumerate() {
        let d = 2 * k as i32;
        let base = positions.len() as u16;
        positions.extend([v(-8 + d, -6 - d, 0), v(8 + d, -6 - d, 0), v(d, 8 - d, 0)]);
        let c = [Rgb888::RED, Rgb888::GREEN, Rgb888::BLUE][k % 3];
        colors.extend([c; 3]);
        tris[t] = [base, base + 1, base + 2];
    }
    (positions, colors, tris)
}

/// The bins a frame needs: one per visible triangle, plus a filler per 255 triangles of a gap
/// beyond the 8-bit step to it.
fn bins_needed(visible: &[usize]) -> usize {
    let mut prev = 0;
    let mut n = 0;
    for &t in visible {
        n += 1 + (t - prev).saturating_sub(1) / 255;
        prev = t;
    }
    n
}

#[test]
fn bins_span_gaps_beyond_255_triangles() {
    let (w, h) = (64u32, 48u32);
    // (visible triangles, mesh size, bins the frame needs).
    let cases: [(&[usize], usize, usize); 7] = [
        (&[0, 255], 256, 2),
        (&[0, 256], 257, 3),
        (&[0, 510], 511, 3),
        (&[0, 511], 512, 4),
        (&[0, 70_000], 70_001, bins_needed(&[0, 70_000])),
        (&[70_000], 70_001, bins_needed(&[70_000])),
        (
            &[3, 140_003, 140_004],
            140_010,
            bins_needed(&[3, 140_003, 140_004]),
        ),
    ];
    for (visible, count, needed) in cases {
        let (pos, colors, tris) = sparse_mesh(visible, count);
        let mesh = Mesh {
            positions: &pos,
            normals: None,
            colors: Some(&colors),
            uvs: None,
            triangles: &tris,
            adjacency: None,
        };
        let make = || {
            Pipeline::new(
                &transforms(w, h, 0),
                Viewport::new(w, h),
                NoCull,
                NoDepth,
                VertexColors::<Rgb565>::new(),
            )
        };
        let (whole, whole_stats) = whole_frame(&mesh, w, h, make());
        let hidden = (0..count as u32).filter(|t| !visible.contains(&(*t as usize)));
        let culled = hidden.clone().filter(|t| t % 2 == 0).count() as u32;
        assert_eq!(
            whole_stats,
            RenderStats {
                triangles: count as u32,
                invalid: 0,
                outside: hidden.count() as u32 - culled,
                clipped: 0,
                culled,
                drawn: visible.len() as u32,
            },
            "{visible:?}"
        );
        // Every visible triangle shows: the last one drawn on top, the others around it.
        for k in 0..visible.len() {
            let c = RawU16::from(Rgb565::from(
                [Rgb888::RED, Rgb888::GREEN, Rgb888::BLUE][k % 3],
            ))
            .into_inner();
            let n = whole.iter().filter(|&&p| p == c).count();
            assert!(n > 20, "{visible:?}: triangle {k} shows at {n} pixels");
        }
        let banding = Banding {
            width: w,
            height: h,
            rows: 8,
            background: Rgb565::BLACK,
            clear_depth: u16::MAX,
        };
        let mut band = vec![0u16; (w * 8) as usize];
        let mut scratch = vec![VertexSlot::EMPTY; pos.len()];
        let mut bins = vec![BinEntry::ZERO; needed];
        assert_eq!(
            make()
                .draw_banded(
                    &mesh,
                    &banding,
                    &mut band,
                    &mut bins[..needed - 1],
                    &mut scratch,
                    |_| {}
                )
                .unwrap_err(),
            BandError::TooFewBins {
                needed,
                actual: needed - 1
            },
            "{visible:?}"
        );
        for rows in [1u32, 8, 48] {
            for s in Scratch::ALL {
                let (out, stats) = banded(&mesh, w, h, rows, s, make());
                assert!(
                    out == whole,
                    "{visible:?}: bands of {rows} rows ({s:?} scratch)"
                );
                assert_eq!(stats, whole_stats, "{visible:?}");
            }
        }
        let mut out = vec![0u16; (w * h) as usize];
        make()
            .draw_banded(&mesh, &banding, &mut band, &mut bins, &mut scratch, |b| {
                let y0 = b.y0() as usize * w as usize;
                let data = b.framebuffer().as_slice();
                out[y0..y0 + data.len()].copy_from_slice(data);
            })
            .unwrap();
        assert!(out == whole, "{visible:?}: exactly {needed} bins");
    }
}

#[test]
fn more_than_16_bands_match_the_whole_frame() {
    // Band numbers beyond four bits: an entry's first and last band count groups of bands then.
    let m = suzanne();
    let mesh = m.mesh();
    for (w, h, rows) in [(40u32, 600u32, 2u32), (40, 600, 1), (24, 1000, 3)] {
        compare_bands(
            &mesh,
            w,
            h,
            &|| {
                (
                    CullClockwise,
                    GouraudLit::<Fx16, Rgb565, 1>::new(lighting()),
                )
            },
            Some(Compare::Less),
            &[rows],
            &|_| Scratch::ALL.to_vec(),
        );
    }
}

/// A random triangle soup with per-vertex colours, in a box in front of the camera.
fn soup(seed: u64, n: usize) -> (Vec<Vec3<Fx16>>, Vec<Rgb888>, Vec<[u16; 3]>) {
    let mut x = seed | 1;
    let mut r = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    let mut pos = Vec::new();
    let mut col = Vec::new();
    let mut tris = Vec::new();
    for t in 0..n {
        for _ in 0..3 {
            let c = |v: u64| Fx16::from_bits((v % 160_000) as i32 - 80_000);
            pos.push(Vec3::new(c(r()), c(r()), c(r())));
            col.push(Rgb888::new(r() as u8, r() as u8, r() as u8));
        }
        tris.push([3 * t as u16, 3 * t as u16 + 1, 3 * t as u16 + 2]);
    }
    (pos, col, tris)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn random_soups_match_in_any_band_height(seed in any::<u64>(), n in 1usize..60, rows in 1u32..50, depth in any::<bool>()) {
        let (pos, col, tris) = soup(seed, n);
        let mesh = Mesh { positions: &pos, normals: None, colors: Some(&col), uvs: None, triangles: &tris, adjacency: None };
        let (w, h) = (80u32, 60u32);
        // Without a depth test overlapping triangles show the last one drawn, so this also checks
        // that bands keep the mesh order.
        let cmp = depth.then_some(Compare::LessEqual);
        compare_bands(
            &mesh,
            w,
            h,
            &|| (NoCull, VertexColors::<Rgb565>::new()),
            cmp,
            &[rows],
            &|_| Scratch::ALL.to_vec(),
        );
    }
}
