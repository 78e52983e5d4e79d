//! The 2D primitives with arbitrary i32 coordinates, at 0, 4 and 8 sub-pixel bits, drawn through a
//! `ClipTo` with an arbitrary rectangle: no panic, no out-of-bounds write (a write outside the
//! slice would panic in safe code), the same pixels through the framebuffer's fast paths and
//! through a plain `DrawTarget`. Run it with `-a` for overflow checks.
#![no_main]

use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_graphics_core::prelude::*;
use embedded_graphics_core::primitives::Rectangle;
use libfuzzer_sys::fuzz_target;
use rasterizer_core::geom::SubPoint;
use rasterizer_core::raster::line::{draw_line, draw_line_gradient};
use rasterizer_core::raster::polygon::{FillRule, Polygon};
use rasterizer_core::raster::triangle::{draw_triangle, fill_triangle, fill_triangle_gouraud};
use rasterizer_core::surface::{AnyTarget, ClipTo, Framebuffer, Surface};

const W: u32 = 40;
const H: u32 = 30;

/// A target that records writes and panics outside its bounds.
struct Strict(Vec<u16>);

impl OriginDimensions for Strict {
    fn size(&self) -> Size {
        Size::new(W, H)
    }
}

impl DrawTarget for Strict {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        it: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in it {
            assert!(
                p.x >= 0 && p.y >= 0 && p.x < W as i32 && p.y < H as i32,
                "out of bounds {p:?}"
            );
            self.0[(p.y as u32 * W + p.x as u32) as usize] = c.into_storage();
        }
        Ok(())
    }
}

fn draw_all<S: Surface<Color = Rgb565>>(s: &mut S, v: &[i32]) {
    let area = Rectangle::new(
        Point::new(v[10], v[11]),
        Size::new(v[12] as u32, v[13] as u32),
    );
    let s = &mut ClipTo::new(s, area);
    draw_bits::<_, 4>(s, v);
    draw_bits::<_, 0>(s, v);
    draw_bits::<_, 8>(s, v);
}

fn draw_bits<S: Surface<Color = Rgb565>, const B: u32>(s: &mut S, v: &[i32]) {
    let p = |i: usize| Point::new(v[i], v[i + 1]);
    let sp = |i: usize| SubPoint::<B>::raw(v[i], v[i + 1]);
    let c = |i: usize| {
        Rgb565::new(
            v[i] as u8 & 31,
            (v[i] >> 5) as u8 & 63,
            (v[i] >> 11) as u8 & 31,
        )
    };
    let _ = draw_line(s, p(0), p(2), c(4));
    let _ = draw_line_gradient(s, p(2), p(4), c(0), c(1));
    let _ = draw_triangle(s, [p(0), p(2), p(4)], c(3));
    let _ = fill_triangle(s, [sp(0), sp(2), sp(4)], c(5));
    let _ = fill_triangle_gouraud(s, [sp(6), sp(2), sp(8)], [c(0), c(1), c(2)]);
    let pts: Vec<SubPoint<B>> = (0..5).map(|i| sp(2 * i)).collect();
    if let Ok(poly) = Polygon::<8, B>::new(&pts) {
        let _ = poly.fill(s, FillRule::NonZero, c(7));
        let _ = poly.fill(s, FillRule::EvenOdd, c(8));
    }
}

fuzz_target!(|data: &[u8]| {
    let mut v: Vec<i32> = data
        .chunks_exact(4)
        .map(|b| i32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    // Five points, then the clip rectangle; a short input clips to the whole target.
    v.resize(14, 0);
    if data.len() < 56 {
        v[12] = -1;
        v[13] = -1;
    }
    let mut buf = vec![0u16; (W * H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
    draw_all(&mut fb, &v);
    let mut strict = Strict(vec![0; (W * H) as usize]);
    draw_all(&mut AnyTarget::new(&mut strict), &v);
    assert_eq!(
        buf, strict.0,
        "framebuffer fast paths and DrawTarget disagree"
    );
});
