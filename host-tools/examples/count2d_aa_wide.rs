//! Draws one L1 frame with anti-aliased lines 3 pixels wide (`draw_line_aa_wide`) for callgrind
//! to count, or the same lines with embedded-graphics' stroke of width 3:
//! `count2d_aa_wide RENDERER`, RENDERER `ours` (`frame_ours_aa_w3_lines`) or `eg`
//! (`frame_eg_w3_lines`). A binary of its own, so that `count2d` and `count2d_aa`, and so their
//! figures, stay as they were.
//!
//! The lines are generated and one warm frame drawn outside the counted function; then exactly
//! one call of the frame function draws the counted frame and `primitives=N` is printed.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Line, PrimitiveStyle};
use fixtures::scenes::{self, LineSeg, HEIGHT, PIXELS, WIDTH};
use rasterizer_core::prelude::{draw_line_aa_wide, Framebuffer};
use std::hint::black_box;
use std::process::ExitCode;

/// The line width both renderers draw.
const WIDTH_PX: u32 = 3;

/// L1 anti-aliased, 3 pixels wide: each line blended over what the frame holds.
#[inline(never)]
fn frame_ours_aa_w3_lines(fb: &mut Framebuffer<Rgb565>, l: &[LineSeg]) {
    for l in l {
        // A framebuffer reads back, so this cannot fail.
        let _ = draw_line_aa_wide(fb, l.a, l.b, WIDTH_PX, l.color);
    }
}

/// L1 with embedded-graphics' stroked `Line` of width 3 (aliased).
#[inline(never)]
fn frame_eg_w3_lines(fb: &mut Framebuffer<Rgb565>, l: &[LineSeg]) {
    for l in l {
        let Ok(()) = Line::new(l.a, l.b)
            .into_styled(PrimitiveStyle::with_stroke(l.color, WIDTH_PX))
            .draw(fb);
    }
}

fn main() -> ExitCode {
    let frame: fn(&mut Framebuffer<Rgb565>, &[LineSeg]) = match std::env::args().nth(1).as_deref() {
        Some("ours") => frame_ours_aa_w3_lines,
        Some("eg") => frame_eg_w3_lines,
        _ => {
            eprintln!("usage: count2d_aa_wide ours|eg");
            return ExitCode::FAILURE;
        }
    };
    let mut buf = vec![0u16; PIXELS];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).expect("the L1 frame size");
    let l = scenes::l1();
    frame(&mut fb, &l);
    frame(&mut fb, black_box(&l));
    println!("primitives={}", l.len());
    ExitCode::SUCCESS
}
