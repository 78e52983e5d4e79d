//! Shared test helpers: a strict mock target and reference rasterizers written independently of
//! `rasterizer-core` (exact integer or `i128` arithmetic, no Bresenham, no edge walking).

use embedded_graphics_core::prelude::PointsIter;
use rasterizer_core::prelude::*;

pub mod packed;

/// A draw target that panics on any out-of-bounds write and on any pixel written twice.
#[derive(Debug, Clone)]
pub struct StrictMock<C> {
    width: u32,
    height: u32,
    pixels: Vec<Option<C>>,
    /// Allow a pixel to be written more than once (for tests that draw several primitives over each
    /// other on purpose).
    pub allow_overdraw: bool,
    /// Number of calls of each kind the target received.
    pub calls: Calls,
}

/// What a [`StrictMock`] was asked to do.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Calls {
    /// `draw_iter` calls.
    pub draw_iter: usize,
    /// `fill_solid` calls.
    pub fill_solid: usize,
    /// `fill_contiguous` calls.
    pub fill_contiguous: usize,
    /// Pixels written.
    pub pixels: usize,
}

impl<C: PixelColor> StrictMock<C> {
    /// An empty target.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: vec![None; (width * height) as usize],
            allow_overdraw: false,
            calls: Calls::default(),
        }
    }

    /// The colour at a pixel, if written.
    pub fn get(&self, x: i32, y: i32) -> Option<C> {
        if x < 0 || y < 0 || x >= self.width as i32 || y >= self.height as i32 {
            return None;
        }
        self.pixels[(y as u32 * self.width + x as u32) as usize]
    }

    /// The set of written pixels.
    pub fn written(&self) -> std::collections::BTreeSet<(i32, i32)> {
        let mut set = std::collections::BTreeSet::new();
        for y in 0..self.height as i32 {
            for x in 0..self.width as i32 {
                if self.get(x, y).is_some() {
                    set.insert((x, y));
                }
            }
        }
        set
    }

    fn write(&mut self, p: Point, c: C) {
        assert!(
            p.x >= 0 && p.y >= 0 && p.x < self.width as i32 && p.y < self.height as i32,
            "out-of-bounds write at {p:?} on a {}x{} target",
            self.width,
            self.height
        );
        let i = (p.y as u32 * self.width + p.x as u32) as usize;
        assert!(
            self.allow_overdraw || self.pixels[i].is_none(),
            "pixel {p:?} written twice"
        );
        self.pixels[i] = Some(c);
        self.calls.pixels += 1;
    }

    /// The written pixels as rows of `#` (written) and ` ` (not written).
    pub fn pattern(&self) -> Vec<String> {
        (0..self.height as i32)
            .map(|y| {
                (0..self.width as i32)
                    .map(|x| if self.get(x, y).is_some() { '#' } else { ' ' })
                    .collect()
            })
            .collect()
    }

    /// Asserts the written pixels form `expected` (rows of `#` and ` `; short rows are padded).
    #[track_caller]
    pub fn assert_pattern(&self, expected: &[&str]) {
        let actual = self.pattern();
        let want: Vec<String> = (0..self.height as usize)
            .map(|y| {
                let row = expected.get(y).copied().unwrap_or("");
                format!("{row:<w$}", w = self.width as usize)
            })
            .collect();
        if actual != want {
            panic!(
                "pattern mismatch\nexpected:\n{}\nactual:\n{}",
                want.iter()
                    .map(|r| format!("|{r}|"))
                    .collect::<Vec<_>>()
                    .join("\n"),
                actual
                    .iter()
                    .map(|r| format!("|{r}|"))
                    .collect::<Vec<_>>()
                    .join("\n")
            );
        }
    }
}

impl<C: PixelColor> OriginDimensions for StrictMock<C> {
    fn size(&self) -> Size {
        Size::new(self.width, self.height)
    }
}

impl<C: PixelColor> DrawTarget for StrictMock<C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        self.calls.draw_iter += 1;
        for Pixel(p, c) in pixels {
            self.write(p, c);
        }
        Ok(())
    }

    fn fill_solid(
        &mut self,
        area: &embedded_graphics_core::primitives::Rectangle,
        color: C,
    ) -> Result<(), Self::Error> {
        self.calls.fill_solid += 1;
        for p in area.points() {
            self.write(p, color);
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = C>>(
        &mut self,
        area: &embedded_graphics_core::primitives::Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        self.calls.fill_contiguous += 1;
        for (p, c) in area.points().zip(colors) {
            self.write(p, c);
        }
        Ok(())
    }
}

/// Reference line: for each major-axis coordinate, the minor coordinate nearest the ideal line,
/// ties to the smaller minor coordinate. Computed directly from the rational slope in `i128`.
pub fn reference_line(a: Point, b: Point) -> Vec<Point> {
    let (ax, ay, bx, by) = (a.x as i128, a.y as i128, b.x as i128, b.y as i128);
    let (dx, dy) = (bx - ax, by - ay);
    let mut out = Vec::new();
    if dx.abs() >= dy.abs() {
        if dx == 0 {
            return vec![a];
        }
        let (lo, hi) = (ax.min(bx), ax.max(bx));
        for x in lo..=hi {
            // ideal y = ay + (x - ax) dy / dx; nearest integer, ties to the smaller y.
            let y = nearest_tie_down(ay * dx + (x - ax) * dy, dx);
            out.push(Point::new(x as i32, y as i32));
        }
    } else {
        let (lo, hi) = (ay.min(by), ay.max(by));
        for y in lo..=hi {
            let x = nearest_tie_down(ax * dy + (y - ay) * dx, dy);
            out.push(Point::new(x as i32, y as i32));
        }
    }
    out
}

/// The integer nearest `n / d` (`d != 0`), a tie going to the smaller integer.
pub fn nearest_tie_down(n: i128, d: i128) -> i128 {
    let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
    // smallest k with k >= n/d - 1/2  <=>  2kd >= 2n - d
    let num = 2 * n - d;
    let den = 2 * d;
    num.div_euclid(den) + i128::from(num.rem_euclid(den) != 0)
}

/// Reference triangle coverage: the pixels whose centres pass all three edge-function tests, with the
/// top-left rule for centres on an edge. `i128` throughout; `bits` sub-pixel bits.
pub fn reference_triangle(
    v: [(i64, i64); 3],
    bits: u32,
    width: i32,
    height: i32,
) -> Vec<(i32, i32)> {
    let v = v.map(|(x, y)| (x as i128, y as i128));
    let area = (v[1].0 - v[0].0) * (v[2].1 - v[0].1) - (v[2].0 - v[0].0) * (v[1].1 - v[0].1);
    if area == 0 {
        return Vec::new();
    }
    // Make the winding such that inside means all edge functions >= 0 (clockwise on screen, y down).
    let v = if area < 0 { [v[0], v[2], v[1]] } else { v };
    let s = 1i128 << bits;
    let mut out = Vec::new();
    for py in 0..height {
        for px in 0..width {
            // Doubled coordinates so the centre is an integer even with zero sub-pixel bits.
            let (cx, cy) = ((2 * px as i128 + 1) * s, (2 * py as i128 + 1) * s);
            let inside = (0..3).all(|i| {
                let (a, b) = (v[i], v[(i + 1) % 3]);
                let (ax, ay, bx, by) = (2 * a.0, 2 * a.1, 2 * b.0, 2 * b.1);
                let e = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
                if e != 0 {
                    return e > 0;
                }
                // On the edge: keep it on a top edge (horizontal, triangle below) or a left edge
                // (triangle to the right). With this winding, going a->b: top edge runs +x with dy=0,
                // left edge runs upward (dy < 0).
                let (ex, ey) = (bx - ax, by - ay);
                (ey == 0 && ex > 0) || ey < 0
            });
            if inside {
                out.push((px, py));
            }
        }
    }
    out
}

/// A sub-pixel point from raw coordinates.
pub fn sp<const B: u32>(x: i32, y: i32) -> SubPoint<B> {
    SubPoint::raw(x, y)
}

/// The reference line's pixels inside `[0, w) x [0, h)`, for any `i32` endpoints: evaluated only at
/// the major coordinates on screen, so it stays cheap for lines billions of pixels long.
pub fn reference_line_on_screen(
    a: Point,
    b: Point,
    w: i32,
    h: i32,
) -> std::collections::BTreeSet<(i32, i32)> {
    let (ax, ay, bx, by) = (a.x as i128, a.y as i128, b.x as i128, b.y as i128);
    let (dx, dy) = (bx - ax, by - ay);
    let mut want = std::collections::BTreeSet::new();
    if dx.abs() >= dy.abs() {
        for x in 0..w as i128 {
            if x < ax.min(bx) || x > ax.max(bx) {
                continue;
            }
            let y = if dx == 0 {
                ay
            } else {
                nearest_tie_down(ay * dx + (x - ax) * dy, dx)
            };
            if (0..h as i128).contains(&y) {
                want.insert((x as i32, y as i32));
            }
        }
    } else {
        for y in 0..h as i128 {
            if y < ay.min(by) || y > ay.max(by) {
                continue;
            }
            let x = nearest_tie_down(ax * dy + (y - ay) * dx, dy);
            if (0..w as i128).contains(&x) {
                want.insert((x as i32, y as i32));
            }
        }
    }
    want
}

/// Draws `mesh` through `pipeline` in bands of `rows` (Rgb565, a black background, depth cleared
/// to the far value) into one `width` x `height` frame, checking that every band comes once, top
/// to bottom. The scratch has a slot per vertex and the bins are as many as any mesh needs.
pub fn draw_banded_rgb565<S, C, D, Sh, const BITS: u32, N, M>(
    pipeline: &mut Pipeline<S, C, D, Sh, BITS, N>,
    mesh: &M,
    width: u32,
    height: u32,
    rows: u32,
) -> (Vec<u16>, rasterizer_core::pipeline::RenderStats)
where
    S: rasterizer_core::math::Scalar,
    C: rasterizer_core::cull::Cull,
    D: rasterizer_core::depth::DepthTest,
    Sh: rasterizer_core::shade::Shading<S, Color = Rgb565>,
    N: rasterizer_core::numerics::Numerics,
    M: rasterizer_core::mesh::MeshSource<S>,
{
    let mut band = vec![0u16; (width * rows.min(height)) as usize];
    // A bin per triangle, and a filler for each gap of 255 (at most one per 255 triangles).
    let triangles = mesh.triangle_count();
    let mut bins = vec![BinEntry::default(); triangles + triangles / 255];
    let mut scratch = vec![VertexSlot::EMPTY; mesh.vertex_count()];
    let mut frame = vec![0u16; (width * height) as usize];
    let banding = Banding {
        width,
        height,
        rows,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    let mut next_row = 0;
    let stats = pipeline
        .draw_banded(mesh, &banding, &mut band, &mut bins, &mut scratch, |b| {
            assert_eq!(b.y0(), next_row, "bands come top to bottom");
            let y0 = b.y0() as usize * width as usize;
            let data = b.framebuffer().as_slice();
            frame[y0..y0 + data.len()].copy_from_slice(data);
            next_row += rows as i32;
        })
        .unwrap();
    assert_eq!(
        next_row as u32,
        height.div_ceil(rows) * rows,
        "every band handed on once"
    );
    (frame, stats)
}
