//! Draws one frame of a WORKLOADS.md scene for callgrind to count (`scripts/callgrind.sh`).
//!
//! `count2d SCENE RENDERER [--pixels | --stats]`, SCENE one of L1 T1 T2 G1 P1 LIMIT, RENDERER `ours` or `eg`
//! (LIMIT ignores it). The scene is generated and one warm frame drawn outside the counted
//! function; then exactly one call of a `frame_*` function draws the counted frame:
//!
//! | scene | ours | eg |
//! |---|---|---|
//! | L1 | `frame_ours_lines` | `frame_eg_lines` |
//! | T1, T2 | `frame_ours_triangles` | `frame_eg_triangles` |
//! | G1 | `frame_ours_gouraud` | - |
//! | P1 | `frame_ours_polygons` | - |
//! | LIMIT | `frame_limit` | `frame_limit` |
//!
//! With `--pixels` nothing is counted: the scene is drawn once into a target that counts pixel writes
//! (overdraw included) and the count is printed. `--stats` does the same and prints
//! `pixels=N spans=N` (spans: the runs of one row the target was handed; see `CountingTarget`).

#[path = "../benches/support/eg.rs"]
mod eg;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use fixtures::scenes::{
    self, CountingTarget, GouraudTri, LineSeg, Poly, Tri, HEIGHT, PIXELS, WIDTH,
};
use rasterizer_core::prelude::*;
use std::hint::black_box;
use std::process::ExitCode;

#[inline(never)]
fn frame_ours_lines(fb: &mut Framebuffer<Rgb565>, l: &[LineSeg]) {
    let Ok(()) = scenes::draw_lines_ours(fb, l);
}

#[inline(never)]
fn frame_ours_triangles(fb: &mut Framebuffer<Rgb565>, t: &[Tri]) {
    let Ok(()) = scenes::draw_triangles_ours(fb, t);
}

#[inline(never)]
fn frame_ours_gouraud(fb: &mut Framebuffer<Rgb565>, t: &[GouraudTri]) {
    let Ok(()) = scenes::draw_gouraud_ours(fb, t);
}

#[inline(never)]
fn frame_ours_polygons(fb: &mut Framebuffer<Rgb565>, p: &[Poly]) {
    let Ok(()) = scenes::draw_polygons_ours(fb, p) else {
        // A P1 polygon has at most P1_MAX_VERTICES vertices: the edge table always holds it.
        std::process::exit(1);
    };
}

#[inline(never)]
fn frame_eg_lines(fb: &mut Framebuffer<Rgb565>, l: &[LineSeg]) {
    let Ok(()) = eg::draw_lines_eg(fb, l);
}

#[inline(never)]
fn frame_eg_triangles(fb: &mut Framebuffer<Rgb565>, t: &[Tri]) {
    let Ok(()) = eg::draw_triangles_eg(fb, t);
}

/// LIMIT as WORKLOADS.md defines it: the buffer's length is part of its type, so LLVM can unroll
/// the fill fully (a run-time length gives a loop with half the stores per iteration).
#[inline(never)]
fn frame_limit(buf: &mut [u16; PIXELS], value: u16) {
    buf.fill(value);
}

#[derive(Clone, Copy, PartialEq)]
enum Renderer {
    Ours,
    Eg,
}

fn usage() -> ExitCode {
    eprintln!(
        "usage: count2d SCENE RENDERER [--pixels | --stats]   SCENE: L1 T1 T2 G1 P1 LIMIT, \
         RENDERER: ours eg"
    );
    ExitCode::from(2)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (scene, renderer, count_only) = match args.as_slice() {
        [s, r] => (s.as_str(), r.as_str(), None),
        [s, r, p] if p == "--pixels" || p == "--stats" => {
            (s.as_str(), r.as_str(), Some(p.as_str()))
        }
        _ => return usage(),
    };
    let renderer = match renderer {
        "ours" => Renderer::Ours,
        "eg" => Renderer::Eg,
        _ => return usage(),
    };
    if (scene == "G1" || scene == "P1") && renderer == Renderer::Eg {
        eprintln!(
            "count2d: embedded-graphics has no Gouraud or polygon fill, {scene} is ours only"
        );
        return ExitCode::from(2);
    }
    if let Some(flag) = count_only {
        let mut count = CountingTarget::default();
        let Ok(()) = match (scene, renderer) {
            ("L1", Renderer::Ours) => scenes::draw_lines_ours(&mut count, &scenes::l1()),
            ("L1", Renderer::Eg) => eg::draw_lines_eg(&mut count, &scenes::l1()),
            ("T1", Renderer::Ours) => scenes::draw_triangles_ours(&mut count, &scenes::t1()),
            ("T1", Renderer::Eg) => eg::draw_triangles_eg(&mut count, &scenes::t1()),
            ("T2", Renderer::Ours) => scenes::draw_triangles_ours(&mut count, &scenes::t2()),
            ("T2", Renderer::Eg) => eg::draw_triangles_eg(&mut count, &scenes::t2()),
            ("G1", _) => scenes::draw_gouraud_ours(&mut count, &scenes::g1()),
            ("P1", _) => match scenes::draw_polygons_ours(&mut count, &scenes::p1()) {
                Ok(()) => Ok(()),
                Err(e) => {
                    eprintln!("count2d: P1: {e}");
                    return ExitCode::FAILURE;
                }
            },
            ("LIMIT", _) => {
                count.pixels = PIXELS as u64;
                // One contiguous fill.
                count.spans = 1;
                Ok(())
            }
            _ => return usage(),
        };
        if flag == "--stats" {
            println!("pixels={} spans={}", count.pixels, count.spans);
        } else {
            println!("{}", count.pixels);
        }
        return ExitCode::SUCCESS;
    }

    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let Ok(()) = fb.clear(Rgb565::BLACK);
    // Each arm: generate (not counted), warm frame through the same drawing code (not counted), then
    // one counted frame.
    let primitives = match (scene, renderer) {
        ("L1", r) => {
            let l = scenes::l1();
            if r == Renderer::Ours {
                let Ok(()) = scenes::draw_lines_ours(&mut fb, &l);
                frame_ours_lines(&mut fb, black_box(&l));
            } else {
                let Ok(()) = eg::draw_lines_eg(&mut fb, &l);
                frame_eg_lines(&mut fb, black_box(&l));
            }
            l.len()
        }
        ("T1" | "T2", r) => {
            let t = if scene == "T1" {
                scenes::t1()
            } else {
                scenes::t2()
            };
            if r == Renderer::Ours {
                let Ok(()) = scenes::draw_triangles_ours(&mut fb, &t);
                frame_ours_triangles(&mut fb, black_box(&t));
            } else {
                let Ok(()) = eg::draw_triangles_eg(&mut fb, &t);
                frame_eg_triangles(&mut fb, black_box(&t));
            }
            t.len()
        }
        ("G1", _) => {
            let t = scenes::g1();
            let Ok(()) = scenes::draw_gouraud_ours(&mut fb, &t);
            frame_ours_gouraud(&mut fb, black_box(&t));
            t.len()
        }
        ("P1", _) => {
            let p = scenes::p1();
            if scenes::draw_polygons_ours(&mut fb, &p).is_err() {
                return ExitCode::FAILURE;
            }
            frame_ours_polygons(&mut fb, black_box(&p));
            p.len()
        }
        ("LIMIT", _) => {
            let words: &mut [u16; PIXELS] = fb
                .as_mut_slice()
                .try_into()
                .expect("a 320 x 240 buffer holds PIXELS words");
            words.fill(black_box(0x0841));
            frame_limit(words, black_box(0xFFFF));
            1
        }
        _ => return usage(),
    };
    // Keep the frame alive and print a checksum, so that nothing can be optimised away.
    let sum = black_box(fb.as_slice())
        .iter()
        .fold(0u32, |s, &w| s.rotate_left(5) ^ u32::from(w));
    println!(
        "{scene} {} primitives={primitives} checksum={sum:08x}",
        if renderer == Renderer::Ours {
            "ours"
        } else {
            "eg"
        }
    );
    ExitCode::SUCCESS
}
