//! Draws one L1 frame with anti-aliased lines (`draw_line_aa`, width 1) for callgrind to count,
//! against embedded-graphics' line of the same width (`count2d L1 eg`): `count2d_aa`. A binary of
//! its own, so that adding it leaves `count2d`'s code, and so its figures, as they were.
//!
//! The lines are generated and one warm frame drawn outside the counted function; then exactly
//! one call of `frame_ours_aa_lines` draws the counted frame and `primitives=N` is printed.

use embedded_graphics::pixelcolor::Rgb565;
use fixtures::scenes::{self, LineSeg, HEIGHT, PIXELS, WIDTH};
use rasterizer_core::prelude::*;
use std::hint::black_box;

/// L1 anti-aliased: each line blended over what the frame holds.
#[inline(never)]
fn frame_ours_aa_lines(fb: &mut Framebuffer<Rgb565>, l: &[LineSeg]) {
    for l in l {
        // A framebuffer reads back, so this cannot fail.
        let _ = draw_line_aa(fb, l.a, l.b, l.color);
    }
}

fn main() {
    let mut buf = vec![0u16; PIXELS];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).expect("the L1 frame size");
    let l = scenes::l1();
    frame_ours_aa_lines(&mut fb, &l);
    frame_ours_aa_lines(&mut fb, black_box(&l));
    println!("primitives={}", l.len());
}
