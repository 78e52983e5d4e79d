//! What firmware does with rasterizer-core, on the host so that CI can build and run it: a mesh
//! converted on the PC (`host-tools convert suzanne.obj -o suzanne.rmsh`) is embedded with
//! `include_bytes!`, read in place, and rendered into a static 320x240 Rgb565 framebuffer with
//! Gouraud lighting, a depth buffer and back-face culling: the M1 benchmark scene, its camera and
//! lighting taken from the benchmarks' own definition (`fixtures` without its `std` feature). A
//! second frame is rendered in 16-row bands through a 10 KB buffer, as a board without 150 KB of
//! RAM would, and must match the first. Both draws share one vertex scratch (16 bytes per mesh vertex), so
//! each vertex is transformed and lit once a frame however many bands use it.
//!
//! On a microcontroller, `main` would be the reset handler and the band callback would start the
//! display's DMA; here the C runtime calls `main` and the process exit code reports the result.
//! Built for a Cortex-M4F (`--target thumbv7em-none-eabihf`), it links with its own entry point,
//! for the flash it needs (CI prints it); it does not run here.
#![no_std]
#![no_main]

use fixtures::scenes3d;
use rasterizer_core::prelude::*;

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

// A panic ends the process with status 101 (as a std program's would) so that CI sees a failure;
// looping forever, as firmware might, would hang CI instead. The message is a fixed string: printing
// the `PanicInfo` would link `core::fmt` into every build and blur the code sizes measured here.
#[cfg(not(target_os = "none"))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    const MSG: &[u8] = b"panicked\n";
    // SAFETY: `write` reads MSG.len() bytes of a static; `exit` does not return.
    unsafe {
        write(2, MSG.as_ptr(), MSG.len());
        exit(101)
    }
}

// compiler_builtins' 128-bit division refers to the unwinding personality even with
// panic = "abort"; nothing here unwinds.
#[unsafe(no_mangle)]
pub extern "C" fn rust_eh_personality() {}

// On a bare-metal target nothing can report a panic: the core stops, as firmware's would.
#[cfg(target_os = "none")]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {
        core::hint::spin_loop();
    }
}

/// On a bare-metal target, the linker's default entry point (where the reset handler would be):
/// it calls `main` and keeps its code linked.
#[cfg(target_os = "none")]
#[unsafe(no_mangle)]
pub extern "C" fn _start() -> ! {
    core::hint::black_box(main());
    loop {
        core::hint::spin_loop();
    }
}

#[cfg(not(target_os = "none"))]
#[link(name = "c")]
unsafe extern "C" {
    fn write(fd: i32, buf: *const u8, count: usize) -> isize;
    fn exit(status: i32) -> !;
}

/// Renders the frame whole, then in bands; 0 when both agree and something was drawn.
#[unsafe(no_mangle)]
pub extern "C" fn main() -> i32 {
    let Ok(mesh) = PackedMesh::parse(SUZANNE) else {
        return 1;
    };
    let (transforms, lighting) = (scenes3d::transforms(), scenes3d::lighting::<1>());
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
