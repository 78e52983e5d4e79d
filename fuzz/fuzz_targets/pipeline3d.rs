//! The 3D pipeline with arbitrary (NaN-free) fixed-point matrices and vertices: no panic, a short
//! vertex scratch draws what a full one draws, and the banded render equals the whole-frame render
//! for an arbitrary band height and scratch length.
#![no_main]

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics_core::prelude::*;
use libfuzzer_sys::fuzz_target;
use rasterizer_core::cull::NoCull;
use rasterizer_core::depth::{Compare, DepthBuffer};
use rasterizer_core::math::{Fx16, Mat4, Vec3};
use rasterizer_core::shade::VertexColors;
use rasterizer_core::surface::Framebuffer;
use rasterizer_core::{
    mesh::Mesh, pipeline::Banding, pipeline::BinEntry, pipeline::Pipeline, pipeline::VertexSlot,
    transform::Transforms, transform::Viewport,
};

const W: u32 = 32;
const H: u32 = 24;

fuzz_target!(|data: &[u8]| {
    let mut words: Vec<i32> = data
        .chunks_exact(4)
        .map(|b| i32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    if words.len() < 17 {
        return;
    }
    let rows = (words[16] as u32 % H) + 1;
    // Scratch lengths for the short whole-frame draw and the banded one.
    let (short, band_slots) = (
        (words[16] >> 8) as u8 as usize,
        (words[16] >> 16) as u8 as usize,
    );
    let mut m = [[Fx16::ZERO; 4]; 4];
    for (k, w) in words.drain(..16).enumerate() {
        m[k / 4][k % 4] = Fx16::from_bits(w);
    }
    words.remove(0);
    let n = (words.len() / 3).min(30);
    let pos: Vec<Vec3<Fx16>> = (0..n)
        .map(|i| {
            Vec3::new(
                Fx16::from_bits(words[3 * i]),
                Fx16::from_bits(words[3 * i + 1]),
                Fx16::from_bits(words[3 * i + 2]),
            )
        })
        .collect();
    let colors: Vec<Rgb888> = (0..n)
        .map(|i| Rgb888::new((i as u8).wrapping_mul(40), 255 - i as u8 * 7, 128))
        .collect();
    // A strip: each vertex shared by up to three triangles, as the scratch expects.
    let tris: Vec<[u16; 3]> = (0..n.saturating_sub(2))
        .map(|t| [t as u16, t as u16 + 1, t as u16 + 2])
        .collect();
    let mesh = Mesh {
        positions: &pos,
        normals: None,
        colors: Some(&colors),
        uvs: None,
        triangles: &tris,
        adjacency: None,
    };
    let xf = Transforms {
        model: Mat4::identity(),
        view: Mat4::identity(),
        projection: Mat4::from_rows(m),
    };
    let vp = Viewport::new(W, H);

    let mut whole = vec![0u16; (W * H) as usize];
    {
        let mut z = vec![u16::MAX; (W * H) as usize];
        let depth = DepthBuffer::new(&mut z, W, H, Compare::LessEqual).unwrap();
        let mut p = Pipeline::new(&xf, vp, NoCull, depth, VertexColors::<Rgb565>::new());
        let mut fb = Framebuffer::<Rgb565>::new(&mut whole, W, H).unwrap();
        let mut scratch = vec![VertexSlot::EMPTY; n];
        let _ = p.draw(&mut fb, &mesh, &mut scratch);
        let _ = p.draw_wireframe(&mut fb, &mesh, &mut scratch, Rgb565::WHITE);
        let _ = fb.pixel(Point::zero());
    }
    // Wireframe was drawn on top above; redraw the fill alone for the comparison, with a full
    // scratch and with a short one.
    let fill_with = |slots: usize| {
        let mut fill = vec![0u16; (W * H) as usize];
        let mut z = vec![u16::MAX; (W * H) as usize];
        let depth = DepthBuffer::new(&mut z, W, H, Compare::LessEqual).unwrap();
        let mut p = Pipeline::new(&xf, vp, NoCull, depth, VertexColors::<Rgb565>::new());
        let mut fb = Framebuffer::<Rgb565>::new(&mut fill, W, H).unwrap();
        let stats = p.draw(&mut fb, &mesh, &mut vec![VertexSlot::EMPTY; slots]);
        (fill, stats)
    };
    let (fill, stats) = fill_with(n);
    assert!(
        fill_with(short) == (fill.clone(), stats),
        "a scratch of {short} of {n} slots differs from a full one"
    );
    let mut banded = vec![0u16; (W * H) as usize];
    {
        let mut z = vec![u16::MAX; (W * rows) as usize];
        let depth = DepthBuffer::new(&mut z, W, rows, Compare::LessEqual).unwrap();
        let mut p = Pipeline::new(&xf, vp, NoCull, depth, VertexColors::<Rgb565>::new());
        let mut band = vec![0u16; (W * rows) as usize];
        let mut bins = vec![BinEntry::default(); tris.len()];
        let banding = Banding {
            width: W,
            height: H,
            rows,
            background: Rgb565::BLACK,
            clear_depth: u16::MAX,
        };
        let mut scratch = vec![VertexSlot::EMPTY; band_slots];
        let _ = p.draw_banded(&mesh, &banding, &mut band, &mut bins, &mut scratch, |b| {
            let y0 = b.y0() as usize * W as usize;
            let d = b.framebuffer().as_slice();
            banded[y0..y0 + d.len()].copy_from_slice(d);
        });
    }
    assert_eq!(
        fill, banded,
        "bands of {rows} rows ({band_slots} scratch slots) differ from the whole frame"
    );
});
