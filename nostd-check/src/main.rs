//! A `#![no_std] #![no_main]` binary that calls every public drawing entry point of
//! `rasterizer-core`. If any dependency brings in `std`, linking fails with a duplicate
//! `panic_impl` lang item; its `.text` size is the first number of the flash budget.
//!
//! The default feature `all` is that binary. Without it (`--no-default-features`), the features
//! of one effects combination build a binary with only that combination's calls, for its code
//! size (module `one`, `scripts/memory.sh`).
//!
//! It also builds for a Cortex-M4F (`--target thumbv7em-none-eabihf`), where `.text` is the
//! flash a firmware image would hold; there it links but does not run here.
#![no_std]
#![no_main]

#[cfg(feature = "all")]
mod all;
#[cfg(any(feature = "all", three_d, feature = "framelist", feature = "antialias"))]
mod m1;
#[cfg(not(feature = "all"))]
mod one;
#[cfg(all(not(feature = "all"), feature = "framelist"))]
mod s1;

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

// The prebuilt compiler_builtins (128-bit division, used by the wide set-up paths) refers to the
// unwinding personality even with panic = "abort"; nothing here unwinds, so an empty one links.
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

/// On a bare-metal target, the linker's default entry point (where a reset handler would be):
/// it calls `main`, which the host's C runtime calls elsewhere, and keeps its code linked.
#[cfg(target_os = "none")]
#[unsafe(no_mangle)]
pub extern "C" fn _start() -> ! {
    #[cfg(feature = "all")]
    core::hint::black_box(all::main());
    #[cfg(not(feature = "all"))]
    core::hint::black_box(one::main());
    loop {
        core::hint::spin_loop();
    }
}

// The host's C runtime calls `main`; on a microcontroller this would be the reset handler.
#[cfg(not(target_os = "none"))]
#[link(name = "c")]
unsafe extern "C" {
    fn write(fd: i32, buf: *const u8, count: usize) -> isize;
    fn exit(status: i32) -> !;
}
