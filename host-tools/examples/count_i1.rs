//! Draws one frame of workload I1 or I1id (`shared/bench/WORKLOADS.md`) for callgrind to count.
//!
//! `count_i1 RENDERER [--stats]`, RENDERER one of:
//!
//! | renderer | frame | what |
//! |---|---|---|
//! | `ours` | `frame_i1_ours` | I1: 200 sprites turned, scaled, nearest, alpha-blended |
//! | `ours-id` | `frame_i1id_ours` | I1id: the same centres, angle 0, scale 1, opaque |
//! | `eg-id` | `frame_i1id_eg` | I1id with embedded-graphics' `Image` (`ImageRaw<Rgb565>`) |
//!
//! The placements and the image (`fixtures::sprite`) are made and one warm frame drawn outside
//! the counted function; then exactly one call of the frame function draws the counted frame
//! into a 320 x 240 Rgb565 framebuffer cleared to black, and `primitives=200 checksum=..` is
//! printed. With `--stats` nothing is counted: the frame is drawn into a target that counts the
//! pixels written (blended ones included) and `pixels=N` is printed.

use embedded_graphics::image::{Image, ImageRaw};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use fixtures::scenes::{HEIGHT, PIXELS, WIDTH};
use fixtures::sprite::{i1, Placement, I1_IMAGE, I1_SIDE};
use host_tools::scenefile::Counting;
use rasterizer_core::prelude::*;
use rasterizer_core::raster::sprite::{draw_sprite, Affine, Sprite};
use rasterizer_core::texture::Filter;
use std::hint::black_box;
use std::process::ExitCode;

/// I1: each sprite under its own transform, nearest, blended by its 8-bit alpha.
#[inline(never)]
fn frame_i1_ours(fb: &mut Framebuffer<Rgb565>, sprite: &Sprite<'_>, xf: &[Affine]) {
    black_box("frame_i1_ours");
    for a in xf {
        let Ok(()) = draw_sprite(fb, sprite, a, Filter::Nearest) else {
            std::process::exit(1);
        };
    }
}

/// I1id: the same image with its alpha ignored, untransformed.
#[inline(never)]
fn frame_i1id_ours(fb: &mut Framebuffer<Rgb565>, sprite: &Sprite<'_>, xf: &[Affine]) {
    black_box("frame_i1id_ours");
    let opaque = sprite.without_alpha();
    for a in xf {
        let Ok(()) = draw_sprite(fb, &opaque, a, Filter::Nearest) else {
            std::process::exit(1);
        };
    }
}

/// I1id through embedded-graphics: `Image` of an `ImageRaw<Rgb565>` at each top-left corner.
#[inline(never)]
fn frame_i1id_eg(fb: &mut Framebuffer<Rgb565>, raw: &ImageRaw<'_, Rgb565>, at: &[Point]) {
    black_box("frame_i1id_eg");
    for &p in at {
        let Ok(()) = Image::new(raw, p).draw(fb);
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (renderer, stats) = match args.as_slice() {
        [r] => (r.as_str(), false),
        [r, s] if s == "--stats" => (r.as_str(), true),
        _ => {
            eprintln!("usage: count_i1 ours|ours-id|eg-id [--stats]");
            return ExitCode::from(2);
        }
    };
    let sprite = Sprite::from_bytes(I1_IMAGE).expect("the committed I1 image is a sprite");
    let placements: Vec<Placement> = i1();
    let turned: Vec<Affine> = placements.iter().map(Placement::transform).collect();
    let straight: Vec<Affine> = placements
        .iter()
        .map(Placement::identity_transform)
        .collect();
    // embedded-graphics' ImageRaw<Rgb565> is big-endian: the texels converted once, not counted.
    let be: Vec<u8> = sprite
        .color_bytes()
        .chunks_exact(2)
        .flat_map(|c| [c[1], c[0]])
        .collect();
    let raw = ImageRaw::<Rgb565>::new(&be, I1_SIDE);
    let half = (I1_SIDE / 2) as i32;
    let corners: Vec<Point> = placements
        .iter()
        .map(|p| Point::new(p.cx - half, p.cy - half))
        .collect();

    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let draw = |fb: &mut Framebuffer<Rgb565>| match renderer {
        "ours" => frame_i1_ours(fb, black_box(&sprite), black_box(&turned)),
        "ours-id" => frame_i1id_ours(fb, black_box(&sprite), black_box(&straight)),
        _ => frame_i1id_eg(fb, black_box(&raw), black_box(&corners)),
    };
    if !matches!(renderer, "ours" | "ours-id" | "eg-id") {
        eprintln!("count_i1: unknown renderer {renderer} (ours, ours-id, eg-id)");
        return ExitCode::from(2);
    }
    if stats {
        let mut counting = Counting::new(fb);
        let ok = match renderer {
            "ours" => turned
                .iter()
                .all(|a| draw_sprite(&mut counting, &sprite, a, Filter::Nearest).is_ok()),
            "ours-id" => straight.iter().all(|a| {
                draw_sprite(&mut counting, &sprite.without_alpha(), a, Filter::Nearest).is_ok()
            }),
            _ => corners
                .iter()
                .all(|&p| Image::new(&raw, p).draw(&mut counting).is_ok()),
        };
        if !ok {
            return ExitCode::FAILURE;
        }
        println!("pixels={}", counting.pixels);
        return ExitCode::SUCCESS;
    }
    // The warm frame, outside the counted function, then the counted one over black.
    draw(&mut fb);
    let Ok(()) = fb.clear(Rgb565::BLACK);
    draw(black_box(&mut fb));
    let checksum = fb
        .as_slice()
        .iter()
        .fold(0u32, |s, &w| s.rotate_left(5) ^ u32::from(w));
    println!(
        "i1 renderer={renderer} primitives={} checksum={checksum:08x}",
        placements.len()
    );
    ExitCode::SUCCESS
}
