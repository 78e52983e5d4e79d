//! Draws one M1 frame with linear fog (`shade::Fog` around the `m1` pipeline's `GouraudLit`,
//! fog from depth 2 to 4 towards grey-blue) for callgrind to count: `count3d_fog`. A binary of its
//! own, so that adding it leaves `count3d`'s code, and so its figures, as they were.
//!
//! The mesh is loaded, the pipeline built and one warm frame drawn outside the counted function
//! (`support/m1_fog.rs`, shared with the other fogged count); then exactly one call of
//! `frame_m1_fog` draws the counted frame, and the same line as `count3d m1` is printed
//! (`drawn=.. covered=.. checksum=..`).

use embedded_graphics::pixelcolor::Rgb565;
use rasterizer_core::pipeline::RenderStats;
use rasterizer_core::prelude::*;
use std::hint::black_box;
use std::process::ExitCode;

#[path = "support/m1_fog.rs"]
mod m1_fog;
use m1_fog::{Pipe, Slots};

type Lit = GouraudLit<Fx16, Rgb565, 1>;

/// M1 fogged: the `m1` pipeline with the shading wrapped in fog.
#[inline(never)]
fn frame_m1_fog(
    p: &mut Pipe<'_, Lit>,
    fb: &mut Framebuffer<'_, Rgb565>,
    mesh: &Mesh<'_, Fx16, u32>,
    scratch: &mut Slots<Lit>,
) -> RenderStats {
    black_box("frame_m1_fog");
    p.draw(fb, mesh, scratch)
        .expect("the depth buffer covers the frame")
}

fn main() -> ExitCode {
    m1_fog::run("count3d_fog", "m1_fog", GouraudLit::new, frame_m1_fog)
}
