//! The 2D benchmark scenes of `shared/bench/WORKLOADS.md` (L1, T1, T2, G1 and LIMIT) at 320 x 240
//! Rgb565: our renderer against embedded-graphics 0.8 drawing the same primitives into the same
//! `Framebuffer`, in the same run. Throughput is in primitives per iteration (pixels for LIMIT).
//!
//! `cargo bench -p host-tools --bench scenes2d -- --warm-up-time 1 --measurement-time 3`

#[path = "support/eg.rs"]
mod eg;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use fixtures::scenes::{self, GouraudTri, LineSeg, Tri, HEIGHT, PIXELS, WIDTH};
use rasterizer_core::prelude::*;
use std::hint::black_box;

fn lines(c: &mut Criterion, fb: &mut Framebuffer<Rgb565>, l1: &[LineSeg]) {
    let mut g = c.benchmark_group("L1");
    g.throughput(Throughput::Elements(l1.len() as u64));
    g.bench_function("ours", |b| {
        b.iter(|| {
            let Ok(()) = scenes::draw_lines_ours(fb, black_box(l1));
        })
    });
    g.bench_function("embedded-graphics", |b| {
        b.iter(|| {
            let Ok(()) = eg::draw_lines_eg(fb, black_box(l1));
        })
    });
    g.finish();
}

fn triangles(c: &mut Criterion, fb: &mut Framebuffer<Rgb565>, name: &str, tris: &[Tri]) {
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(tris.len() as u64));
    g.bench_function("ours", |b| {
        b.iter(|| {
            let Ok(()) = scenes::draw_triangles_ours(fb, black_box(tris));
        })
    });
    g.bench_function("embedded-graphics", |b| {
        b.iter(|| {
            let Ok(()) = eg::draw_triangles_eg(fb, black_box(tris));
        })
    });
    g.finish();
}

fn gouraud(c: &mut Criterion, fb: &mut Framebuffer<Rgb565>, g1: &[GouraudTri]) {
    // embedded-graphics has no Gouraud fill: ours only.
    let mut g = c.benchmark_group("G1");
    g.throughput(Throughput::Elements(g1.len() as u64));
    g.bench_function("ours", |b| {
        b.iter(|| {
            let Ok(()) = scenes::draw_gouraud_ours(fb, black_box(g1));
        })
    });
    g.finish();
}

fn limit(c: &mut Criterion, fb: &mut Framebuffer<Rgb565>) {
    let mut g = c.benchmark_group("LIMIT");
    g.throughput(Throughput::Elements(PIXELS as u64));
    // The length in the type, as WORKLOADS.md defines LIMIT: LLVM unrolls the fill fully only then.
    let words: &mut [u16; PIXELS] = fb
        .as_mut_slice()
        .try_into()
        .expect("a 320 x 240 buffer holds PIXELS words");
    g.bench_function("slice.fill", |b| b.iter(|| words.fill(black_box(0xFFFF))));
    g.finish();
}

fn scenes2d(c: &mut Criterion) {
    // Generated outside the timed loops.
    let (l1, t1, t2, g1) = (scenes::l1(), scenes::t1(), scenes::t2(), scenes::g1());
    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let Ok(()) = fb.clear(Rgb565::BLACK);
    lines(c, &mut fb, &l1);
    triangles(c, &mut fb, "T1", &t1);
    triangles(c, &mut fb, "T2", &t2);
    gouraud(c, &mut fb, &g1);
    limit(c, &mut fb);
    black_box(fb.as_slice());
}

criterion_group!(benches, scenes2d);
criterion_main!(benches);
