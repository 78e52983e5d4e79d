//! The standard 2D benchmark scenes of `shared/bench/WORKLOADS.md` (L1, T1, T2, G1), generated once
//! with the xorshift32 generator it specifies, plus the drawing loops for our renderer and a target
//! that counts the pixels written.
//!
//! The criterion bench (`benches/scenes2d.rs`) and the instruction-counting example
//! (`examples/count2d.rs`) both use this module, so they draw exactly the same primitives.

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Point, Size};
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;
use rasterizer_core::geom::SubPoint;
use rasterizer_core::raster::line::draw_line;
use rasterizer_core::raster::triangle::{fill_triangle, fill_triangle_gouraud};
use rasterizer_core::surface::Surface;

/// Width of the benchmark framebuffer, in pixels.
pub const WIDTH: u32 = 320;
/// Height of the benchmark framebuffer, in pixels.
pub const HEIGHT: u32 = 240;
/// Pixels in the framebuffer: what one `LIMIT` frame (one `slice.fill`) writes.
pub const PIXELS: usize = (WIDTH * HEIGHT) as usize;

/// The seed every scene starts from.
pub const SEED: u32 = 0x1234_5678;

/// Lines in L1.
pub const L1_COUNT: usize = 10_000;
/// Triangles in T1 and G1.
pub const T1_COUNT: usize = 10_000;
/// Triangles in T2.
pub const T2_COUNT: usize = 100;
/// T2 keeps a triangle when its doubled area lies in this range (15,000 ..= 25,000 px^2).
pub const T2_DOUBLED_AREA: core::ops::RangeInclusive<i64> = 30_000..=50_000;

/// The xorshift32 generator of WORKLOADS.md.
#[derive(Debug, Clone)]
pub struct XorShift32(u32);

impl XorShift32 {
    /// A generator seeded with [`SEED`].
    pub fn new() -> Self {
        Self(SEED)
    }

    /// The next value: `x ^= x << 13; x ^= x >> 17; x ^= x << 5`.
    pub fn next_u32(&mut self) -> u32 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        self.0 = x;
        x
    }

    /// `r() % m` as an `i32`.
    fn below(&mut self, m: u32) -> i32 {
        (self.next_u32() % m) as i32
    }

    /// An Rgb565 colour with raw value `r() as u16`.
    fn color(&mut self) -> Rgb565 {
        Rgb565::from(RawU16::new(self.next_u32() as u16))
    }

    /// One T1 vertex around `(cx, cy)`: `(cx + r() % 17 - 8, cy + r() % 17 - 8)`.
    fn small_vertex(&mut self, cx: i32, cy: i32) -> Point {
        let x = cx + self.below(17) - 8;
        let y = cy + self.below(17) - 8;
        Point::new(x, y)
    }
}

impl Default for XorShift32 {
    fn default() -> Self {
        Self::new()
    }
}

/// One line of L1.
#[derive(Debug, Clone, Copy)]
pub struct LineSeg {
    /// First endpoint.
    pub a: Point,
    /// Second endpoint.
    pub b: Point,
    /// Colour.
    pub color: Rgb565,
}

/// One solid triangle of T1 or T2, in whole pixels and as 28.4 sub-pixel vertices (`x * 16`).
#[derive(Debug, Clone, Copy)]
pub struct Tri {
    /// Vertices in whole pixels (embedded-graphics input).
    pub px: [Point; 3],
    /// The same vertices as `SubPoint::new(x * 16, y * 16)` (our input).
    pub sub: [SubPoint<4>; 3],
    /// Colour.
    pub color: Rgb565,
}

/// One triangle of G1: a colour per vertex.
#[derive(Debug, Clone, Copy)]
pub struct GouraudTri {
    /// Vertices as `SubPoint::new(x * 16, y * 16)`.
    pub sub: [SubPoint<4>; 3],
    /// Colour of each vertex.
    pub colors: [Rgb565; 3],
}

fn to_sub(px: [Point; 3]) -> [SubPoint<4>; 3] {
    px.map(|p| SubPoint::new(p.x * 16, p.y * 16))
}

/// Twice the signed area of a triangle in whole pixels.
pub fn doubled_area(v: [Point; 3]) -> i64 {
    let [a, b, c] = v.map(|p| (i64::from(p.x), i64::from(p.y)));
    (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1)
}

/// L1: 10,000 lines, `x0, y0, x1, y1, colour` per line.
pub fn l1() -> Vec<LineSeg> {
    let mut r = XorShift32::new();
    (0..L1_COUNT)
        .map(|_| {
            let a = Point::new(r.below(WIDTH), r.below(HEIGHT));
            let b = Point::new(r.below(WIDTH), r.below(HEIGHT));
            LineSeg {
                a,
                b,
                color: r.color(),
            }
        })
        .collect()
}

/// T1: 10,000 small triangles, `cx, cy`, three vertices, colour per triangle.
pub fn t1() -> Vec<Tri> {
    let mut r = XorShift32::new();
    (0..T1_COUNT)
        .map(|_| {
            let (cx, cy) = (r.below(WIDTH), r.below(HEIGHT));
            let px = [0; 3].map(|_| r.small_vertex(cx, cy));
            Tri {
                px,
                sub: to_sub(px),
                color: r.color(),
            }
        })
        .collect()
}

/// T2: 100 large triangles; three vertices are drawn again until the area is 15,000 ..= 25,000 px^2,
/// then the colour.
pub fn t2() -> Vec<Tri> {
    let mut r = XorShift32::new();
    (0..T2_COUNT)
        .map(|_| {
            let px = loop {
                let px = [0; 3].map(|_| Point::new(r.below(WIDTH), r.below(HEIGHT)));
                if T2_DOUBLED_AREA.contains(&doubled_area(px).abs()) {
                    break px;
                }
            };
            Tri {
                px,
                sub: to_sub(px),
                color: r.color(),
            }
        })
        .collect()
}

/// G1: T1's geometry draws (`cx, cy`, three vertices) followed by three vertex colours.
pub fn g1() -> Vec<GouraudTri> {
    let mut r = XorShift32::new();
    (0..T1_COUNT)
        .map(|_| {
            let (cx, cy) = (r.below(WIDTH), r.below(HEIGHT));
            let px = [0; 3].map(|_| r.small_vertex(cx, cy));
            GouraudTri {
                sub: to_sub(px),
                colors: [0; 3].map(|_| r.color()),
            }
        })
        .collect()
}

/// Draws L1 with our renderer.
pub fn draw_lines_ours<S: Surface<Color = Rgb565>>(
    s: &mut S,
    lines: &[LineSeg],
) -> Result<(), S::Error> {
    for l in lines {
        draw_line(s, l.a, l.b, l.color)?;
    }
    Ok(())
}

/// Draws T1 or T2 with our renderer.
pub fn draw_triangles_ours<S: Surface<Color = Rgb565>>(
    s: &mut S,
    tris: &[Tri],
) -> Result<(), S::Error> {
    for t in tris {
        fill_triangle(s, t.sub, t.color)?;
    }
    Ok(())
}

/// Draws G1 with our renderer.
pub fn draw_gouraud_ours<S: Surface<Color = Rgb565>>(
    s: &mut S,
    tris: &[GouraudTri],
) -> Result<(), S::Error> {
    for t in tris {
        fill_triangle_gouraud(s, t.sub, t.colors)?;
    }
    Ok(())
}

/// A 320 x 240 target that stores nothing and counts the pixel writes it receives (overdraw
/// included), whichever `DrawTarget` or [`Surface`] method they come through.
#[derive(Debug, Default)]
pub struct CountingTarget {
    /// Pixels written so far.
    pub pixels: u64,
    /// Runs of pixels on one row handed over so far: one per span call, one per row of a
    /// rectangle, one per pixel of `draw_iter`. `pixels / spans` is the average span.
    pub spans: u64,
}

impl CountingTarget {
    fn visible(area: &Rectangle) -> Size {
        area.intersection(&Rectangle::new(Point::zero(), Size::new(WIDTH, HEIGHT)))
            .size
    }

    fn add_rectangle(&mut self, area: &Rectangle) {
        let Size { width, height } = Self::visible(area);
        self.pixels += u64::from(width) * u64::from(height);
        if width > 0 {
            self.spans += u64::from(height);
        }
    }

    fn add_span(&mut self, len: u32) {
        self.pixels += u64::from(len);
        self.spans += u64::from(len > 0);
    }
}

impl OriginDimensions for CountingTarget {
    fn size(&self) -> Size {
        Size::new(WIDTH, HEIGHT)
    }
}

impl DrawTarget for CountingTarget {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Rgb565>>,
    {
        let inside = |p: &Point| (p.x as u32) < WIDTH && (p.y as u32) < HEIGHT;
        let n = pixels.into_iter().filter(|Pixel(p, _)| inside(p)).count() as u64;
        self.pixels += n;
        self.spans += n;
        Ok(())
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, _colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Rgb565>,
    {
        self.add_rectangle(area);
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, _color: Rgb565) -> Result<(), Self::Error> {
        self.add_rectangle(area);
        Ok(())
    }
}

impl Surface for CountingTarget {
    fn fill_span(&mut self, _x: i32, _y: i32, len: u32, _color: Rgb565) -> Result<(), Self::Error> {
        self.add_span(len);
        Ok(())
    }

    fn shade_span<F: FnMut() -> Rgb565>(
        &mut self,
        _x: i32,
        _y: i32,
        len: u32,
        _shade: F,
    ) -> Result<(), Self::Error> {
        self.add_span(len);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn xorshift_matches_the_reference_steps() {
        let mut r = XorShift32::new();
        let mut x: u32 = 0x1234_5678;
        for _ in 0..100 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            assert_eq!(r.next_u32(), x);
        }
    }

    #[test]
    fn scenes_have_the_documented_sizes() {
        assert_eq!(l1().len(), L1_COUNT);
        assert_eq!(t1().len(), T1_COUNT);
        assert_eq!(g1().len(), T1_COUNT);
        let t2 = t2();
        assert_eq!(t2.len(), T2_COUNT);
        assert!(t2
            .iter()
            .all(|t| T2_DOUBLED_AREA.contains(&doubled_area(t.px).abs())));
    }

    #[test]
    fn t1_and_g1_start_with_the_same_triangle() {
        // Same generator, same first four draws (cx, cy, first vertex); T1 then draws a colour where
        // G1 draws three, so only the first triangle is identical.
        assert_eq!(t1()[0].sub, g1()[0].sub);
    }
}
