//! Draws one M1 frame translucent for callgrind to count: the default configuration of
//! `count3d m1` (Gouraud, depth buffer, back faces culled, 320 x 240 Rgb565) drawn through
//! `Translucent` at opacity 128. `count3d_translucent COMBINATION`:
//!
//! | combination | depth stage | counted function |
//! |---|---|---|
//! | `m1_translucent` | `DepthBuffer` (`Less`, writing): the pixels of `m1`, each blended | `frame_m1_translucent` |
//! | `m1_translucent_readonly` | `DepthReadOnly` over a cleared buffer: every front face blended | `frame_m1_translucent_readonly` |
//!
//! A binary of its own, so that `count3d`'s code, and so its figures, stay as they were. The
//! frame is cleared to black, one warm frame drawn and the buffers cleared again outside the
//! counted function. Prints `COMBINATION scene=M1 triangles=.. drawn=.. culled=.. covered=..`.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use fixtures::scenes::{HEIGHT, PIXELS, WIDTH};
use fixtures::scenes3d::{lighting, transforms, Scene};
use rasterizer_core::depth::DepthTest;
use rasterizer_core::pipeline::RenderStats;
use rasterizer_core::prelude::*;
use std::hint::black_box;
use std::process::ExitCode;

type Gouraud = GouraudLit<Fx16, Rgb565, 1>;
type Pipe<D> = Pipeline<Fx16, CullClockwise, D, Gouraud, 6>;
type Mesh3<'a> = Mesh<'a, Fx16, u32>;
type Slots = [VertexSlot<<Gouraud as rasterizer_core::shade::Shading<Fx16>>::Stored>];

/// The opacity of the counted frames.
const OPACITY: u8 = 128;

#[inline(always)]
fn draw<D: DepthTest>(
    p: &mut Pipe<D>,
    fb: &mut Framebuffer<'_, Rgb565>,
    mesh: &Mesh3<'_>,
    scratch: &mut Slots,
) -> RenderStats {
    p.draw(&mut Translucent::new(fb, OPACITY), mesh, scratch)
        .expect("a framebuffer reads back and the depth buffer covers the frame")
}

#[inline(never)]
fn frame_m1_translucent(
    p: &mut Pipe<DepthBuffer<'_>>,
    fb: &mut Framebuffer<'_, Rgb565>,
    mesh: &Mesh3<'_>,
    scratch: &mut Slots,
) -> RenderStats {
    black_box("frame_m1_translucent");
    draw(p, fb, mesh, scratch)
}

#[inline(never)]
fn frame_m1_translucent_readonly(
    p: &mut Pipe<DepthReadOnly<'_>>,
    fb: &mut Framebuffer<'_, Rgb565>,
    mesh: &Mesh3<'_>,
    scratch: &mut Slots,
) -> RenderStats {
    black_box("frame_m1_translucent_readonly");
    draw(p, fb, mesh, scratch)
}

fn main() -> ExitCode {
    let name = std::env::args().nth(1).unwrap_or_default();
    let loaded = match Scene::M1.load() {
        Ok(m) => m,
        Err(e) => {
            eprintln!("count3d_translucent: {e}");
            return ExitCode::FAILURE;
        }
    };
    let mesh = loaded.mesh();
    let mut buf = vec![0u16; PIXELS];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let mut zbuf = vec![u16::MAX; PIXELS];
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let vp = Viewport::new(WIDTH, HEIGHT);
    let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less).expect("depth buffer");
    let gouraud = Gouraud::new(lighting());
    let stats = match name.as_str() {
        "m1_translucent" => {
            let mut p = Pipeline::new(&transforms(), vp, CullClockwise, depth, gouraud);
            let _ = draw(&mut p, &mut fb, &mesh, &mut scratch);
            let Ok(()) = fb.clear(Rgb565::BLACK);
            p.depth.clear(u16::MAX);
            frame_m1_translucent(
                &mut p,
                black_box(&mut fb),
                black_box(&mesh),
                black_box(&mut scratch),
            )
        }
        "m1_translucent_readonly" => {
            let d = depth.read_only();
            let mut p = Pipeline::new(&transforms(), vp, CullClockwise, d, gouraud);
            let _ = draw(&mut p, &mut fb, &mesh, &mut scratch);
            let Ok(()) = fb.clear(Rgb565::BLACK);
            frame_m1_translucent_readonly(
                &mut p,
                black_box(&mut fb),
                black_box(&mesh),
                black_box(&mut scratch),
            )
        }
        _ => {
            eprintln!("usage: count3d_translucent m1_translucent|m1_translucent_readonly");
            return ExitCode::FAILURE;
        }
    };
    let covered = fb.as_slice().iter().filter(|&&w| w != 0).count();
    println!(
        "{name} scene=M1 triangles={} drawn={} culled={} covered={covered}",
        stats.triangles, stats.drawn, stats.culled
    );
    ExitCode::SUCCESS
}
