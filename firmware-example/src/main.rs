//! What firmware does with rasterizer-core, on the host so that CI can build and run it: a mesh
//! converted on the PC (`host-tools convert suzanne.obj -o suzanne.rmsh`) is embedded with
//! `include_bytes!`, read in place, and rendered into a static 320x240 Rgb565 framebuffer with
//! Gouraud lighting, a depth buffer and back-face culling (the M1 benchmark scene). A second frame
//! is rendered in 16-row bands through a 10 KB buffer, as a board without 150 KB of RAM would,
//! and must match the first. Both draws share one vertex scratch (16 bytes per mesh vertex), so
//! each vertex is transformed and lit once a frame however many bands use it.
//!
//! On a microcontroller, `main` would be the reset handler and the band callback would start the
//! display's DMA; here the C runtime calls `main` and the process exit code reports the result.
#![no_std]
#![no_main]

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics_core::prelude::*;
use rasterizer_core::cull::CullClockwise;
use rasterizer_core::depth::{Compare, DepthBuffer};
use rasterizer_core::math::{Angle, Fx16, Mat4, Vec3};
use rasterizer_core::mesh::PackedMesh;
use rasterizer_core::shade::GouraudLit;
use rasterizer_core::shade::{Light, Lighting, Material, Specular};
use rasterizer_core::surface::Framebuffer;
use rasterizer_core::{
    pipeline::Banding, pipeline::BinEntry, pipeline::Pipeline, pipeline::VertexSlot,
    transform::Transforms, transform::Viewport,
};

/// The converted mesh, in flash.
static SUZANNE: &[u8] = include_bytes!("../../assets/meshes/suzanne.rmsh");

const W: u32 = 320;
const H: u32 = 240;
const BAND_ROWS: u32 = 16;
/// Suzanne's vertices: one scratch slot each (a mesh with more only draws slower).
const VERTICES: usize = 507;

// Frame memory, as a linker would place it in RAM.
static mut FRAME: [u16; (W * H) as usize] = [0; (W * H) as usize];
static mut DEPTH: [u16; (W * H) as usize] = [0; (W * H) as usize];
static mut BAND: [u16; (W * BAND_ROWS) as usize] = [0; (W * BAND_ROWS) as usize];
static mut BAND_DEPTH: [u16; (W * BAND_ROWS) as usize] = [0; (W * BAND_ROWS) as usize];
static mut BINS: [BinEntry; 1024] = [BinEntry::ZERO; 1024];
// `VertexSlot::EMPTY` is not all zeros, so this one lies in .data: its 8 KB image costs flash too.
static mut SCRATCH: [VertexSlot; VERTICES] = [VertexSlot::EMPTY; VERTICES];

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

// compiler_builtins' 128-bit division refers to the unwinding personality even with
// panic = "abort"; nothing here unwinds.
#[unsafe(no_mangle)]
pub extern "C" fn rust_eh_personality() {}

#[link(name = "c")]
unsafe extern "C" {}

fn scene() -> (Transforms<Fx16>, Lighting<Fx16, 1>) {
    let p = |x, y, z| Vec3::<Fx16>::from_ints(x, y, z);
    let transforms = Transforms {
        model: Mat4::rotation_y(Angle::from_degrees(30)),
        view: Mat4::look_at(p(0, 0, 3), p(0, 0, 0), p(0, 1, 0)).unwrap_or_default(),
        projection: Mat4::perspective(
            Angle::from_degrees(60),
            Fx16::from_ratio(4, 3),
            Fx16::from_ratio(1, 10),
            Fx16::from_int(100),
        )
        .unwrap_or_default(),
    };
    let material = Material {
        ambient: Rgb888::new(40, 30, 30),
        diffuse: Rgb888::new(220, 140, 80),
        specular: Rgb888::WHITE,
        shininess: 16,
    };
    let mut lighting = Lighting::new(material, Rgb888::WHITE, Specular::BlinnPhong, p(0, 0, 3));
    let _ = lighting.add_light(Light::Directional {
        direction: p(1, 1, 1),
        color: Rgb888::WHITE,
    });
    (transforms, lighting)
}

/// Renders the frame whole, then in bands; 0 when both agree and something was drawn.
#[unsafe(no_mangle)]
pub extern "C" fn main() -> i32 {
    let Ok(mesh) = PackedMesh::parse(SUZANNE) else {
        return 1;
    };
    let (transforms, lighting) = scene();
    let viewport = Viewport::new(W, H);
    // SAFETY: single-threaded, and each static is borrowed once here.
    #[allow(static_mut_refs)]
    let (frame, depth, band, band_depth, bins, scratch) = unsafe {
        (
            &mut FRAME,
            &mut DEPTH,
            &mut BAND,
            &mut BAND_DEPTH,
            &mut BINS,
            &mut SCRATCH,
        )
    };

    // The whole frame: 150 KB of colour and 150 KB of depth.
    depth.fill(u16::MAX);
    let Ok(depth_buffer) = DepthBuffer::new(depth, W, H, Compare::Less) else {
        return 2;
    };
    let mut pipeline = Pipeline::new(
        &transforms,
        viewport,
        CullClockwise,
        depth_buffer,
        GouraudLit::<Fx16, Rgb565, 1>::new(lighting.clone()),
    );
    let Ok(mut fb) = Framebuffer::<Rgb565>::new(frame, W, H) else {
        return 3;
    };
    let _ = fb.clear(Rgb565::BLACK);
    let Ok(stats) = pipeline.draw(&mut fb, &mesh, scratch) else {
        return 8;
    };
    if stats.drawn == 0 {
        return 4;
    }

    // The same frame in bands: 10 KB of colour and 10 KB of depth.
    let Ok(band_depth_buffer) = DepthBuffer::new(band_depth, W, BAND_ROWS, Compare::Less) else {
        return 5;
    };
    let mut banded = Pipeline::new(
        &transforms,
        viewport,
        CullClockwise,
        band_depth_buffer,
        GouraudLit::<Fx16, Rgb565, 1>::new(lighting),
    );
    let banding = Banding {
        width: W,
        height: H,
        rows: BAND_ROWS,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    let whole = fb.as_slice();
    let mut mismatched = false;
    let result = banded.draw_banded(&mesh, &banding, band, bins, scratch, |b| {
        // Firmware would start the DMA transfer of this band to the display here.
        let y0 = b.y0() as usize * W as usize;
        let rows = b.framebuffer().as_slice();
        mismatched |= whole.get(y0..y0 + rows.len()) != Some(rows);
    });
    match result {
        Ok(_) if !mismatched => 0,
        Ok(_) => 6,
        Err(_) => 7,
    }
}
