//! Draws one M1 frame with anti-aliased silhouettes (the `m1` pipeline drawn with
//! `Pipeline::draw_antialiased`, the mesh's adjacency computed on loading, by position) for callgrind to
//! count: `count3d_aa`. A binary of its own, so that adding it leaves `count3d`'s code, and so
//! its figures, as they were.
//!
//! The mesh is loaded, the pipeline built and one warm frame drawn outside the counted function;
//! then exactly one call of `frame_m1_aa` draws the counted frame, and the same line as
//! `count3d m1` is printed (`drawn=.. covered=.. checksum=..`).

use embedded_graphics::pixelcolor::Rgb565;
use fixtures::scenes::{HEIGHT, PIXELS, WIDTH};
use fixtures::scenes3d::{lighting, transforms, Scene};
use rasterizer_core::pipeline::RenderStats;
use rasterizer_core::prelude::*;
use std::hint::black_box;
use std::process::ExitCode;

type Pipe<'z> = GouraudPipeline<'z>;

/// M1 with anti-aliased silhouettes.
#[inline(never)]
fn frame_m1_aa(
    p: &mut Pipe<'_>,
    fb: &mut Framebuffer<'_, Rgb565>,
    mesh: &Mesh<'_, Fx16, u32>,
    scratch: &mut [VertexSlot<[u16; 3]>],
) -> RenderStats {
    black_box("frame_m1_aa");
    p.draw_antialiased(fb, mesh, scratch)
        .expect("a framebuffer, a mesh with adjacency and a depth buffer covering the frame")
}

fn main() -> ExitCode {
    let loaded = match Scene::M1.load() {
        Ok(m) => m,
        Err(e) => {
            eprintln!("count3d_aa: {}: {e}", Scene::M1.path().display());
            return ExitCode::FAILURE;
        }
    };
    // By position, so that the model's normal and texture seams are not taken for edges.
    let keys: Vec<[i32; 3]> = loaded
        .positions
        .iter()
        .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
        .collect();
    let adjacency = fixtures::adjacency::adjacency_by_position(&loaded.triangles, &keys);
    let mesh = loaded.mesh().with_adjacency(&adjacency);
    let xf = transforms();
    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let mut zbuf = vec![u16::MAX; PIXELS].into_boxed_slice();
    let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less).expect("depth buffer");
    let shading = GouraudLit::<Fx16, Rgb565, 1>::new(lighting());
    let mut p = Pipeline::new(
        &xf,
        Viewport::new(WIDTH, HEIGHT),
        CullClockwise,
        depth,
        shading,
    );
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    // The warm frame, outside the counted function.
    let _ = p.draw_antialiased(&mut fb, &mesh, &mut scratch);
    let Ok(()) = fb.clear(Rgb565::BLACK);
    p.depth.clear(u16::MAX);
    let stats = frame_m1_aa(
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
        "m1_aa scene=M1 triangles={} drawn={} culled={} covered={covered} checksum={checksum:08x}",
        stats.triangles, stats.drawn, stats.culled
    );
    ExitCode::SUCCESS
}
