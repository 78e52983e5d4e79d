//! Band rendering gives exactly the whole-frame picture, for every band height, on meshes and on
//! random triangle soups (with and without a depth test, where draw order matters).

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics_core::prelude::*;
use proptest::prelude::*;
use rasterizer_core::math::{Angle, Fx16, Mat4, Vec3};
use rasterizer_core::numerics::{
    Custom, ExactDivide, ExactSpans, GradientSpans, NewtonDivide, Numerics, ReciprocalDivide,
    Standard,
};
use rasterizer_core::pipeline::cull::{CullClockwise, NoCull};
use rasterizer_core::pipeline::shading::{GouraudLit, Shading, VertexColors};
use rasterizer_core::pipeline::{
    BandError, Banding, BinEntry, CachedVertex, Mesh, MeshSource, Pipeline, Transforms, Viewport,
    DEFAULT_BITS,
};
use rasterizer_core::raster::interp::{Compare, DepthBuffer, DepthTest, NoDepth};
use rasterizer_core::target::Framebuffer;

fn suzanne() -> host_tools::obj::LoadedMesh {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    host_tools::obj::LoadedMesh::load(&path).unwrap()
}

fn transforms(w: u32, h: u32, yaw: i32) -> Transforms<Fx16> {
    Transforms {
        model: Mat4::rotation_y(Angle::from_degrees(yaw)),
        view: Mat4::look_at(
            Vec3::from_ints(0, 0, 3),
            Vec3::default(),
            Vec3::from_ints(0, 1, 0),
        )
        .unwrap(),
        projection: Mat4::perspective(
            Angle::from_degrees(60),
            Fx16::from_ratio(i64::from(w), i64::from(h)),
            Fx16::from_ratio(1, 10),
            Fx16::from_int(100),
        )
        .unwrap(),
    }
}

// The M1 lighting, shared with the benchmarks.
use host_tools::scenes3d::lighting;

fn whole_frame<M, C, D, Sh, N>(
    mesh: &M,
    w: u32,
    h: u32,
    mut p: Pipeline<Fx16, C, D, Sh, DEFAULT_BITS, false, N>,
) -> Vec<u16>
where
    M: MeshSource<Fx16>,
    C: rasterizer_core::pipeline::cull::Cull,
    D: DepthTest,
    Sh: Shading<Fx16, Color = Rgb565>,
    N: Numerics,
{
    let mut whole = vec![0u16; (w * h) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut whole, w, h).unwrap();
    fb.clear(Rgb565::BLACK).unwrap();
    p.draw(&mut fb, mesh).unwrap();
    whole
}

fn banded<M, C, D, Sh, N>(
    mesh: &M,
    w: u32,
    h: u32,
    rows: u32,
    mut p: Pipeline<Fx16, C, D, Sh, DEFAULT_BITS, false, N>,
) -> Vec<u16>
where
    M: MeshSource<Fx16>,
    C: rasterizer_core::pipeline::cull::Cull,
    D: DepthTest,
    Sh: Shading<Fx16, Color = Rgb565>,
    N: Numerics,
{
    let mut band = vec![0u16; (w * rows.min(h)) as usize];
    let mut bins = vec![BinEntry::default(); mesh.triangle_count()];
    let mut out = vec![0u16; (w * h) as usize];
    let banding = Banding {
        width: w,
        height: h,
        rows,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    p.draw_banded(mesh, &banding, &mut band, &mut bins, &mut [], |b| {
        let y0 = b.y0() as usize * w as usize;
        let data = b.framebuffer().as_slice();
        out[y0..y0 + data.len()].copy_from_slice(data);
    })
    .unwrap();
    out
}

/// The whole frame, then the same scene in bands of each height, compared pixel for pixel.
fn compare_bands<M, C, Sh>(
    mesh: &M,
    w: u32,
    h: u32,
    make: &dyn Fn() -> (C, Sh),
    depth: Option<Compare>,
    rows_list: &[u32],
) where
    M: MeshSource<Fx16>,
    C: rasterizer_core::pipeline::cull::Cull,
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
    for &rows in rows_list {
        let out = match depth {
            Some(cmp) => {
                let r = rows.min(h);
                let mut z = vec![u16::MAX; (w * r) as usize];
                let (c, sh) = make();
                banded(
                    mesh,
                    w,
                    h,
                    rows,
                    Pipeline::new(&xf, vp, c, DepthBuffer::new(&mut z, w, r, cmp).unwrap(), sh),
                )
            }
            None => {
                let (c, sh) = make();
                banded(mesh, w, h, rows, Pipeline::new(&xf, vp, c, NoDepth, sh))
            }
        };
        let differ = whole.iter().zip(&out).filter(|(a, b)| a != b).count();
        assert_eq!(
            differ, 0,
            "{differ} pixels differ with bands of {rows} rows"
        );
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
    ) -> Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, Gouraud, DEFAULT_BITS, false, N> {
        Pipeline::new(
            &transforms(160, 120, 30),
            Viewport::new(160, 120),
            CullClockwise,
            DepthBuffer::new(depth, 160, rows, Compare::Less).unwrap(),
            GouraudLit::new(lighting()),
        )
        .with_numerics::<N>()
    }
    fn check<N: Numerics>(mesh: &Mesh<'_, Fx16, u32>) {
        let (w, h) = (160u32, 120u32);
        let mut z = vec![u16::MAX; (w * h) as usize];
        let whole = whole_frame(mesh, w, h, pipeline::<N>(&mut z, h));
        for rows in [1u32, 7, 16, 120] {
            let mut z = vec![u16::MAX; (w * rows) as usize];
            let out = banded(mesh, w, h, rows, pipeline::<N>(&mut z, rows));
            assert!(out == whole, "{rows} rows differ");
        }
    }
    let m = suzanne();
    let mesh = m.mesh();
    check::<Standard>(&mesh);
    check::<Custom<ExactDivide, 16, GradientSpans>>(&mesh);
    check::<Custom<NewtonDivide, 8, GradientSpans>>(&mesh);
    check::<Custom<ReciprocalDivide, 12, ExactSpans>>(&mesh);
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
    );
}

#[test]
fn suzanne_m1_size_common_band_heights_with_cache() {
    let m = suzanne();
    let mesh = m.mesh();
    let (w, h) = (320u32, 240u32);
    let mut whole = vec![0u16; (w * h) as usize];
    let mut z = vec![u16::MAX; (w * h) as usize];
    {
        let mut fb = Framebuffer::<Rgb565>::new(&mut whole, w, h).unwrap();
        let depth = DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap();
        let mut p = Pipeline::<_, _, _, _>::new(
            &transforms(w, h, 30),
            Viewport::new(w, h),
            CullClockwise,
            depth,
            GouraudLit::<Fx16, Rgb565, 1>::new(lighting()),
        );
        p.draw(&mut fb, &mesh).unwrap();
    }
    for rows in [8u32, 16, 32, 240] {
        let mut band = vec![0u16; (w * rows) as usize];
        let mut zb = vec![u16::MAX; (w * rows) as usize];
        let mut bins = vec![BinEntry::default(); 1000];
        let mut cache = vec![CachedVertex::default(); mesh.vertex_count()];
        let depth = DepthBuffer::new(&mut zb, w, rows, Compare::Less).unwrap();
        let mut p = Pipeline::<_, _, _, _>::new(
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
            .draw_banded(&mesh, &banding, &mut band, &mut bins, &mut cache, |b| {
                let y0 = b.y0() as usize * w as usize;
                let data = b.framebuffer().as_slice();
                out[y0..y0 + data.len()].copy_from_slice(data);
            })
            .unwrap();
        assert_eq!((stats.drawn, stats.culled), (609, 359));
        assert_eq!(whole, out, "bands of {rows} rows");
    }
}

#[test]
fn band_errors_are_typed() {
    let m = suzanne();
    let mesh = m.mesh();
    let (w, h) = (64u32, 48u32);
    let mut p = Pipeline::<_, _, _, _>::new(
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
        let mesh = Mesh { positions: &pos, normals: None, colors: Some(&col), triangles: &tris };
        let (w, h) = (80u32, 60u32);
        // Without a depth test overlapping triangles show the last one drawn, so this also checks
        // that bands keep the mesh order.
        let cmp = depth.then_some(Compare::LessEqual);
        compare_bands(&mesh, w, h, &|| (NoCull, VertexColors::<Rgb565>::new()), cmp, &[rows]);
    }
}
