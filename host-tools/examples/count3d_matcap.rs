//! Draws one M1 frame with MatCap shading per vertex (the `m1` pipeline with `shade::MatCap` and
//! the default image, `fixtures::matcap::GLOSSY_64`, in place of `GouraudLit`) for callgrind to
//! count: `count3d_matcap`. A binary of its own, so that adding it leaves `count3d`'s code, and
//! so its figures, as they were.
//!
//! The mesh is loaded, the pipeline built and one warm frame drawn outside the counted function;
//! then exactly one call of `frame_m1_matcap` draws the counted frame, and the same line as
//! `count3d m1` is printed (`drawn=.. covered=.. checksum=..`).

use embedded_graphics::pixelcolor::Rgb565;
use fixtures::matcap::{GLOSSY_64, GLOSSY_64_SIDE_LOG2};
use fixtures::scenes::{HEIGHT, PIXELS, WIDTH};
use fixtures::scenes3d::{transforms, Scene};
use rasterizer_core::pipeline::RenderStats;
use rasterizer_core::prelude::*;
use std::hint::black_box;
use std::process::ExitCode;

type Cap = MatCap<'static, Fx16, Rgb565>;
type Pipe<'z> = Pipeline<Fx16, CullClockwise, DepthBuffer<'z>, Cap>;

/// M1 with MatCap shading.
#[inline(never)]
fn frame_m1_matcap(
    p: &mut Pipe<'_>,
    fb: &mut Framebuffer<'_, Rgb565>,
    mesh: &Mesh<'_, Fx16, u32>,
    scratch: &mut [VertexSlot<[u16; 3]>],
) -> RenderStats {
    black_box("frame_m1_matcap");
    p.draw(fb, mesh, scratch)
        .expect("the depth buffer covers the frame")
}

fn main() -> ExitCode {
    let loaded = match Scene::M1.load() {
        Ok(m) => m,
        Err(e) => {
            eprintln!("count3d_matcap: {}: {e}", Scene::M1.path().display());
            return ExitCode::FAILURE;
        }
    };
    let mesh = loaded.mesh();
    let xf = transforms();
    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let mut zbuf = vec![u16::MAX; PIXELS].into_boxed_slice();
    let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less).expect("depth buffer");
    let shading = Cap::new(GLOSSY_64_SIDE_LOG2, GLOSSY_64, &xf.view).expect("a 64 x 64 image");
    let mut p = Pipeline::new(
        &xf,
        Viewport::new(WIDTH, HEIGHT),
        CullClockwise,
        depth,
        shading,
    );
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    // The warm frame, outside the counted function.
    let _ = p.draw(&mut fb, &mesh, &mut scratch);
    let Ok(()) = fb.clear(Rgb565::BLACK);
    p.depth.clear(u16::MAX);
    let stats = frame_m1_matcap(
        &mut p,
        black_box(&mut fb),
        black_box(&mesh),
        black_box(&mut scratch),
    );
    let px = fb.as_slice();
    let covered = px.iter().filter(|&&w| w != 0).count();
    let checksum = px
        .iter()
        .fold(0u32, |s, &w| s.rotate_left(5) ^ u32::from(w));
    println!(
        "m1_matcap scene=M1 triangles={} drawn={} culled={} covered={covered} checksum={checksum:08x}",
        stats.triangles, stats.drawn, stats.culled
    );
    ExitCode::SUCCESS
}
