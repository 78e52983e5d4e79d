//! The 3D benchmark scenes of `shared/bench/WORKLOADS.md` (M1 Suzanne, M2 the Stanford bunny res3,
//! M3 the full Stanford bunny) at 320 x 240: our pipeline (Gouraud, 16-bit depth buffer, back faces
//! culled; `draw` with a vertex scratch of one slot per vertex and with none (`ours_noscratch`);
//! and `draw` with the unlit, flat and Phong shading models)
//! against euc 0.5.3 (`f32`, Gouraud, `f32` depth buffer, back
//! faces culled; `benches/support/euc3d.rs`) drawing the same scene, in the same run. The scenes
//! come from `fixtures::scenes3d`, as in `examples/count3d.rs`.
//!
//! Each timed iteration is one frame's drawing only: the colour and depth buffers are cleared
//! before it, outside the timed part (`iter_custom`), as in the instruction counts. Throughput is
//! in mesh triangles per frame.
//!
//! `cargo bench -p host-tools --bench scenes3d -- --warm-up-time 1 --measurement-time 3`
//! (about 40 s once built).

// `stats` and `triangles` are for `examples/count3d.rs`.
#[allow(dead_code)]
#[path = "support/euc3d.rs"]
mod euc3d;

use criterion::measurement::WallTime;
use criterion::{
    criterion_group, criterion_main, BenchmarkGroup, Criterion, SamplingMode, Throughput,
};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use euc3d::EucScene;
use fixtures::scenes::{HEIGHT, PIXELS, WIDTH};
use fixtures::scenes3d::{lighting, transforms, Scene, DIFFUSE};
use rasterizer_core::math::Fx16;
use rasterizer_core::pipeline::cull::CullClockwise;
use rasterizer_core::pipeline::shading::{FlatLit, GouraudLit, PhongLit, Shading, Unlit};
use rasterizer_core::pipeline::{Mesh, Pipeline, VertexSlot, Viewport};
use rasterizer_core::raster::interp::{Compare, DepthBuffer};
use rasterizer_core::target::Framebuffer;
use std::hint::black_box;
use std::time::{Duration, Instant};

fn scene(c: &mut Criterion, scene: Scene) {
    let loaded = scene.load().expect("the scene's model");
    let mesh = loaded.mesh();
    let xf = transforms();
    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let mut zbuf = vec![u16::MAX; PIXELS].into_boxed_slice();
    let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less).expect("depth buffer");
    // 26.6 screen coordinates, affine interpolation: the pipeline of the `m1` count.
    let mut p: Pipeline<Fx16, _, _, _, 6> = Pipeline::new(
        &xf,
        Viewport::new(WIDTH, HEIGHT),
        CullClockwise,
        depth,
        GouraudLit::<Fx16, Rgb565, 1>::new(lighting()),
    );
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let euc = EucScene::new(&loaded);
    let (mut color, mut euc_depth) = EucScene::buffers();

    let mut g = c.benchmark_group(scene.name());
    g.throughput(Throughput::Elements(mesh.triangles.len() as u64));
    g.sampling_mode(SamplingMode::Flat);
    // M3 takes tens of milliseconds a frame: fewer samples keep the run short.
    g.sample_size(if scene == Scene::M3 { 10 } else { 20 });
    g.bench_function("ours", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                let Ok(()) = fb.clear(Rgb565::BLACK);
                p.depth.clear(u16::MAX);
                let t = Instant::now();
                let stats = p.draw(&mut fb, black_box(&mesh), &mut scratch);
                total += t.elapsed();
                black_box(stats.expect("the depth buffer covers the frame"));
            }
            total
        })
    });
    // Every vertex transformed and shaded by each triangle that uses it: what the scratch saves.
    g.bench_function("ours_noscratch", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                let Ok(()) = fb.clear(Rgb565::BLACK);
                p.depth.clear(u16::MAX);
                let t = Instant::now();
                let stats = p.draw(&mut fb, black_box(&mesh), &mut []);
                total += t.elapsed();
                black_box(stats.expect("the depth buffer covers the frame"));
            }
            total
        })
    });
    g.bench_function("euc", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                EucScene::clear(&mut color, &mut euc_depth);
                let t = Instant::now();
                black_box(&euc).render(&mut color, &mut euc_depth);
                total += t.elapsed();
            }
            total
        })
    });
    // The other shading models, ours only (euc is compared on Gouraud).
    drop(p);
    let unlit = Unlit {
        color: Rgb565::from(DIFFUSE),
    };
    other_shading(&mut g, "ours_unlit", unlit, &mesh, &mut fb);
    other_shading(
        &mut g,
        "ours_flat",
        FlatLit::new(lighting::<1>()),
        &mesh,
        &mut fb,
    );
    other_shading(
        &mut g,
        "ours_phong",
        PhongLit::new(lighting::<1>()),
        &mesh,
        &mut fb,
    );
    g.finish();
    black_box((fb.as_slice(), color.as_ref()));
}

/// Times `draw` of the scene with another shading model (depth buffer, back faces culled, 26.6, a
/// full vertex scratch).
fn other_shading<Sh: Shading<Fx16, Color = Rgb565>>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    shading: Sh,
    mesh: &Mesh<'_, Fx16, u32>,
    fb: &mut Framebuffer<'_, Rgb565>,
) {
    let mut zbuf = vec![u16::MAX; PIXELS].into_boxed_slice();
    let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less).expect("depth buffer");
    let mut p: Pipeline<Fx16, _, _, _, 6> = Pipeline::new(
        &transforms(),
        Viewport::new(WIDTH, HEIGHT),
        CullClockwise,
        depth,
        shading,
    );
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    g.bench_function(name, |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                let Ok(()) = fb.clear(Rgb565::BLACK);
                p.depth.clear(u16::MAX);
                let t = Instant::now();
                let stats = p.draw(fb, black_box(mesh), &mut scratch);
                total += t.elapsed();
                black_box(stats.expect("the depth buffer covers the frame"));
            }
            total
        })
    });
}

fn scenes3d(c: &mut Criterion) {
    for s in Scene::ALL {
        scene(c, s);
    }
}

criterion_group!(benches, scenes3d);
criterion_main!(benches);
