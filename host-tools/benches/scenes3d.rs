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
use rasterizer_core::prelude::*;
use rasterizer_core::shade::Shading;
use std::hint::black_box;
use std::time::{Duration, Instant};

fn scene(c: &mut Criterion, scene: Scene) {
    let loaded = scene.load().expect("the scene's model");
    let mesh = loaded.mesh();
    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let euc = EucScene::new(&loaded);
    let (mut color, mut euc_depth) = EucScene::buffers();

    let mut g = c.benchmark_group(scene.name());
    g.throughput(Throughput::Elements(mesh.triangles.len() as u64));
    g.sampling_mode(SamplingMode::Flat);
    // M3 takes tens of milliseconds a frame: fewer samples keep the run short.
    g.sample_size(if scene == Scene::M3 { 10 } else { 20 });
    let gouraud = || GouraudLit::<Fx16, Rgb565, 1>::new(lighting());
    draw(&mut g, "ours", gouraud(), &mesh, &mut fb, true);
    // Every vertex transformed and shaded by each triangle that uses it: what the scratch saves.
    draw(&mut g, "ours_noscratch", gouraud(), &mesh, &mut fb, false);
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
    let unlit = Unlit {
        color: Rgb565::from(DIFFUSE),
    };
    draw(&mut g, "ours_unlit", unlit, &mesh, &mut fb, true);
    let flat = FlatLit::<Fx16, Rgb565, 1>::new(lighting());
    draw(&mut g, "ours_flat", flat, &mesh, &mut fb, true);
    let phong = PhongLit::<Fx16, Rgb565, 1>::new(lighting());
    draw(&mut g, "ours_phong", phong, &mesh, &mut fb, true);
    g.finish();
    black_box((fb.as_slice(), color.as_ref()));
}

/// Times `draw` of the scene with `shading`: a depth buffer, back faces culled, 26.6 screen
/// coordinates and affine interpolation (the pipeline of the `m1` count), with a full vertex
/// scratch or, without `scratch`, an empty one. Only the draw is timed, not the clearing.
fn draw<Sh: Shading<Fx16, Color = Rgb565>>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    shading: Sh,
    mesh: &Mesh<'_, Fx16, u32>,
    fb: &mut Framebuffer<'_, Rgb565>,
    scratch: bool,
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
    let slots = if scratch { mesh.positions.len() } else { 0 };
    let mut scratch = vec![VertexSlot::EMPTY; slots];
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
