//! Triangles with a depth test and interpolated values: the rasterizer behind the 3D pipeline.
//!
//! Coverage is exactly that of [`crate::raster::triangle::fill_triangle`] (the same span walk). Depth
//! and every shader value are planes over the screen, evaluated exactly at the first pixel of each
//! span and stepped across it in 16 fractional bits; the depth test splits a span into runs of
//! passing pixels, and each run goes to the target as one `shade_span`. With [`NoDepth`] the test
//! and its buffer compile away.

use crate::geom::{PixelRect, SubPoint};
use crate::raster::triangle::setup::{walk_spans, Sorted, SpanSink};
use crate::shade::{Varyings, MAX_VARYINGS};
use crate::target::Surface;

/// How a depth buffer compares a new depth with the stored one; 0 is nearest, 65535 farthest.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Compare {
    /// Draw when nearer (the usual test; clear the buffer to 65535).
    #[default]
    Less,
    /// Draw when nearer or equal.
    LessEqual,
    /// Draw when farther.
    Greater,
    /// Draw when farther or equal.
    GreaterEqual,
    /// Draw when equal.
    Equal,
    /// Draw when different.
    NotEqual,
    /// Always draw (and store the depth).
    Always,
    /// Never draw.
    Never,
}

impl Compare {
    #[inline(always)]
    fn pass(self, new: u16, old: u16) -> bool {
        match self {
            Compare::Less => new < old,
            Compare::LessEqual => new <= old,
            Compare::Greater => new > old,
            Compare::GreaterEqual => new >= old,
            Compare::Equal => new == old,
            Compare::NotEqual => new != old,
            Compare::Always => true,
            Compare::Never => false,
        }
    }
}

/// A depth test: which pixels of a span may be drawn.
pub trait DepthTest {
    /// The test reads depths: when false the rasterizer computes none.
    const ENABLED: bool = true;
    /// Calls `run(offset, len)` for each run of pixels of row `y`, columns `x .. x + len`, that
    /// passes, storing their depths first. The depth of pixel `i` is `(z + i dz) >> 16`, clamped
    /// to `0 ..= 65535`.
    fn test_span<E, F>(
        &mut self,
        y: i32,
        x: i32,
        len: u32,
        z: i64,
        dz: i64,
        run: F,
    ) -> Result<(), E>
    where
        F: FnMut(u32, u32) -> Result<(), E>;
}

/// No depth test: every pixel passes and no depth is computed.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoDepth;

impl DepthTest for NoDepth {
    const ENABLED: bool = false;
    #[inline(always)]
    fn test_span<E, F>(
        &mut self,
        _: i32,
        _: i32,
        len: u32,
        _: i64,
        _: i64,
        mut run: F,
    ) -> Result<(), E>
    where
        F: FnMut(u32, u32) -> Result<(), E>,
    {
        run(0, len)
    }
}

/// Why a [`DepthBuffer`] could not be made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DepthBufferError {
    /// Entries the size needs.
    pub expected: usize,
    /// Entries the slice has.
    pub actual: usize,
}

/// A depth buffer over a caller-provided `&mut [u16]`, one entry per pixel, rows top to bottom.
#[derive(Debug)]
pub struct DepthBuffer<'a> {
    buf: &'a mut [u16],
    width: u32,
    height: u32,
    compare: Compare,
}

impl<'a> DepthBuffer<'a> {
    /// A depth buffer of `width` x `height` over `buf` (exactly `width * height` entries).
    ///
    /// # Errors
    /// [`DepthBufferError`] when the slice has another length.
    pub fn new(
        buf: &'a mut [u16],
        width: u32,
        height: u32,
        compare: Compare,
    ) -> Result<Self, DepthBufferError> {
        let expected = width as usize * height as usize;
        if buf.len() != expected {
            return Err(DepthBufferError {
                expected,
                actual: buf.len(),
            });
        }
        Ok(Self {
            buf,
            width,
            height,
            compare,
        })
    }

    /// Sets every entry to `depth` (65535 before a frame with [`Compare::Less`]).
    pub fn clear(&mut self, depth: u16) {
        self.buf.fill(depth);
    }

    /// The stored depths.
    pub fn as_slice(&self) -> &[u16] {
        self.buf
    }

    /// The comparison in use.
    pub fn compare(&self) -> Compare {
        self.compare
    }
}

impl DepthTest for DepthBuffer<'_> {
    #[inline(always)]
    fn test_span<E, F>(
        &mut self,
        y: i32,
        x: i32,
        len: u32,
        z: i64,
        dz: i64,
        mut run: F,
    ) -> Result<(), E>
    where
        F: FnMut(u32, u32) -> Result<(), E>,
    {
        // Pixels outside the buffer are never drawn (a buffer smaller than the target clips).
        if y < 0 || y as u32 >= self.height || x < 0 {
            return Ok(());
        }
        let len = len.min(self.width.saturating_sub(x as u32));
        let start = y as usize * self.width as usize + x as usize;
        let Some(row) = self.buf.get_mut(start..start + len as usize) else {
            return Ok(());
        };
        let compare = self.compare;
        let mut z = z;
        let mut i = 0usize;
        while i < row.len() {
            let begin = i;
            while i < row.len() {
                let d = (z >> 16).clamp(0, 65535) as u16;
                if !compare.pass(d, row[i]) {
                    break;
                }
                row[i] = d;
                i += 1;
                z += dz;
            }
            if i > begin {
                run(begin as u32, (i - begin) as u32)?;
            }
            // Skip the failing pixel(s).
            while i < row.len() {
                let d = (z >> 16).clamp(0, 65535) as u16;
                if compare.pass(d, row[i]) {
                    break;
                }
                i += 1;
                z += dz;
            }
        }
        Ok(())
    }
}

/// A vertex in screen space: sub-pixel position, depth and the shader's values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScreenVertex<V, const BITS: u32 = 4> {
    /// Position.
    pub p: SubPoint<BITS>,
    /// Depth, 0 nearest.
    pub z: u16,
    /// The values to interpolate.
    pub var: V,
    /// `2^20 / w`, clamped to `1 ..= Q_MAX`: read only by perspective-correct interpolation.
    pub q: i64,
}

/// Fractional bits of interpolated values.
const FRAC: u32 = 16;

/// One linear function over the screen: `v(dx2, dy2) = v0 + (a dx2 + b dy2) / den2` in doubled
/// sub-pixel offsets from the first vertex.
#[derive(Debug, Clone, Copy, Default)]
struct Plane {
    v0: i64,
    a: i64,
    b: i64,
}

/// `round(f 2^16 / den2)`, halves up, for `den2 > 0`, without overflow: quotient and remainder are
/// scaled separately (`den2 < 2^46` on the fast path; larger divisors go through `i128`).
#[inline(always)]
fn scaled_div(f: i128, den2: i64) -> i64 {
    if den2 < 1 << 46 {
        if let Ok(f) = i64::try_from(f) {
            let (q, r) = (f.div_euclid(den2), f.rem_euclid(den2));
            return (q << FRAC) + (((r << FRAC) + den2 / 2) / den2);
        }
    }
    (((f << FRAC) + i128::from(den2 / 2)).div_euclid(i128::from(den2))) as i64
}

struct Interp<'a, S: Surface, D, V, F, const P: bool> {
    surface: &'a mut S,
    depth: &'a mut D,
    shade: F,
    s: i64,
    origin: (i64, i64),
    den2: i64,
    z: Plane,
    /// The depth plane's step per pixel (16.16).
    dz: i64,
    /// Affine: the values' planes. Perspective-correct: `1/w` and the two scaled barycentrics.
    planes: [Plane; MAX_VARYINGS],
    /// The planes' steps per pixel (16.16), the same for every span.
    steps: [i64; MAX_VARYINGS],
    /// The planes' steps per row (16.16), and the depth plane's.
    row_steps: [i64; MAX_VARYINGS],
    dz_row: i64,
    /// The previous span's first pixel and its values, which the next span starts from: two
    /// multiplications per plane instead of an exact evaluation (two divisions). Each step adds at
    /// most half a unit of 2^-16, so after `r` rows and `c` columns of travel a value is within
    /// `(r + c) 2^-17` units of exact (2e-3 units on a 240-row screen). Off (`None` forever) when
    /// a step is too large for the products to fit `i64`.
    prev: Option<(i32, i32)>,
    prev_z: i64,
    prev_vals: [i64; MAX_VARYINGS],
    incremental: bool,
    count: usize,
    /// Perspective-correct only: the first vertex's values and the differences to the other two.
    base: [i64; MAX_VARYINGS],
    d1: [i64; MAX_VARYINGS],
    d2: [i64; MAX_VARYINGS],
    _v: core::marker::PhantomData<V>,
}

impl<S: Surface, D: DepthTest, V: Varyings, F: FnMut(&V) -> S::Color, const P: bool>
    Interp<'_, S, D, V, F, P>
{
    /// The plane's value at an offset, in 16.16.
    #[inline(always)]
    fn at(&self, p: &Plane, dx2: i64, dy2: i64) -> i64 {
        let f = i128::from(p.a) * i128::from(dx2) + i128::from(p.b) * i128::from(dy2);
        (p.v0 << FRAC) + scaled_div(f, self.den2)
    }
}

impl<S: Surface, D: DepthTest, V: Varyings, F: FnMut(&V) -> S::Color, const P: bool> SpanSink
    for Interp<'_, S, D, V, F, P>
{
    type Error = S::Error;

    #[inline(always)]
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), S::Error> {
        let dx2 = (2 * i64::from(x0) + 1) * self.s - 2 * self.origin.0;
        let dy2 = (2 * i64::from(row) + 1) * self.s - 2 * self.origin.1;
        let dz = self.dz;
        let planes = if P { 3 } else { self.count };
        let mut start = [0i64; MAX_VARYINGS];
        let z0;
        if let Some((pr, px)) = self.prev {
            let (dr, dc) = (i64::from(row - pr), i64::from(x0 - px));
            z0 = if D::ENABLED {
                self.prev_z + dr * self.dz_row + dc * dz
            } else {
                0
            };
            for (i, s) in start.iter_mut().enumerate().take(planes) {
                *s = self.prev_vals[i] + dr * self.row_steps[i] + dc * self.steps[i];
            }
        } else {
            z0 = if D::ENABLED {
                self.at(&self.z, dx2, dy2)
            } else {
                0
            };
            for (i, s) in start.iter_mut().enumerate().take(planes) {
                *s = self.at(&self.planes[i], dx2, dy2);
            }
        }
        if self.incremental {
            self.prev = Some((row, x0));
            self.prev_z = z0;
            self.prev_vals = start;
        }
        let step = self.steps;
        let count = self.count;
        let Self {
            surface,
            depth,
            shade,
            base,
            d1,
            d2,
            ..
        } = self;
        depth.test_span(row, x0, (x1 - x0) as u32, z0, dz, |offset, len| {
            let mut acc = start;
            for i in 0..planes {
                acc[i] += step[i] * i64::from(offset);
            }
            surface.shade_span(x0 + offset as i32, row, len, || {
                let mut v = V::default();
                if P {
                    // The barycentrics divided by w, over 1/w: one division each per pixel.
                    let q = acc[0].max(1);
                    let l1 = (acc[1].max(0) << FRAC) / q;
                    let l2 = (acc[2].max(0) << FRAC) / q;
                    for (i, out) in v.as_mut_slice().iter_mut().enumerate().take(count) {
                        let mix = l1 * d1[i] + l2 * d2[i];
                        *out = (base[i] + ((mix + (1 << (FRAC - 1))) >> FRAC)) as i32;
                    }
                } else {
                    for (out, a) in v.as_mut_slice().iter_mut().zip(&acc) {
                        // Rounded to the nearest unit of the value.
                        *out = ((a + (1 << (FRAC - 1))) >> FRAC) as i32;
                    }
                }
                for i in 0..planes {
                    acc[i] += step[i];
                }
                shade(&v)
            })
        })
    }
}

/// Fills a triangle with a depth test and interpolated values: `shade` turns the values at each
/// pixel into its colour. Coverage follows the top-left rule exactly as
/// [`crate::raster::triangle::fill_triangle`]; a zero-area triangle or one outside the guard band
/// draws nothing.
///
/// With `PERSPECTIVE` the values are interpolated perspective-correctly from the vertices' `q`
/// (`1/w`, see [`ScreenVertex::q`]): the barycentrics divided by `w` are planes over the screen and
/// each pixel divides them by `1/w` (two divisions per pixel). Without it they are affine in screen
/// space, which is exact for depth and close for small triangles.
pub fn fill_triangle_interp<S, D, V, F, const BITS: u32, const PERSPECTIVE: bool>(
    surface: &mut S,
    depth: &mut D,
    vertices: [ScreenVertex<V, BITS>; 3],
    shade: F,
) -> Result<(), S::Error>
where
    S: Surface,
    D: DepthTest,
    V: Varyings,
    F: FnMut(&V) -> S::Color,
{
    let Some(t) = Sorted::new(&vertices.map(|v| v.p)) else {
        return Ok(());
    };
    let [v0, v1, v2] = t.v;
    let [o0, o1, o2] = t.order;
    let sign = t.cross.signum();
    let den2 = 2 * t.cross.abs();
    // The plane through three values, in doubled offsets from v0, the sign moved into a and b.
    let plane = |f0: i64, f1: i64, f2: i64| Plane {
        v0: f0,
        a: sign * ((f1 - f0) * (v2.1 - v0.1) - (f2 - f0) * (v1.1 - v0.1)),
        b: sign * ((f2 - f0) * (v1.0 - v0.0) - (f1 - f0) * (v2.0 - v0.0)),
    };
    let zs = [vertices[o0].z, vertices[o1].z, vertices[o2].z].map(i64::from);
    let mut planes = [Plane::default(); MAX_VARYINGS];
    let values = [vertices[o0].var, vertices[o1].var, vertices[o2].var];
    let count = values[0].as_slice().len().min(MAX_VARYINGS);
    let value = |k: usize, i: usize| i64::from(values[k].as_slice()[i]);
    let (mut base, mut d1, mut d2) = (
        [0i64; MAX_VARYINGS],
        [0i64; MAX_VARYINGS],
        [0i64; MAX_VARYINGS],
    );
    if PERSPECTIVE {
        let q = [vertices[o0].q, vertices[o1].q, vertices[o2].q].map(|q| q.clamp(1, Q_MAX));
        planes[0] = plane(q[0], q[1], q[2]);
        planes[1] = plane(0, q[1], 0);
        planes[2] = plane(0, 0, q[2]);
        for i in 0..count {
            base[i] = value(0, i);
            d1[i] = value(1, i) - value(0, i);
            d2[i] = value(2, i) - value(0, i);
        }
    } else {
        for (i, p) in planes.iter_mut().enumerate().take(count) {
            *p = plane(value(0, i), value(1, i), value(2, i));
        }
    }
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    let s = 1i64 << BITS;
    let step = |p: &Plane| scaled_div(i128::from(p.a) * i128::from(2 * s), den2);
    let row_step = |p: &Plane| scaled_div(i128::from(p.b) * i128::from(2 * s), den2);
    let z = plane(zs[0], zs[1], zs[2]);
    let (dz, dz_row) = if D::ENABLED {
        (step(&z), row_step(&z))
    } else {
        (0, 0)
    };
    let mut steps = [0i64; MAX_VARYINGS];
    let mut row_steps = [0i64; MAX_VARYINGS];
    let used = if PERSPECTIVE { 3 } else { count };
    for ((st, rs), p) in steps
        .iter_mut()
        .zip(row_steps.iter_mut())
        .zip(&planes)
        .take(used)
    {
        *st = step(p);
        *rs = row_step(p);
    }
    // Travel between span starts is at most 2^16 rows or columns: steps below 2^40 keep the
    // products below 2^56.
    let small = |v: &i64| v.unsigned_abs() < 1 << 40;
    let incremental = [dz, dz_row].iter().all(small)
        && steps[..used].iter().all(small)
        && row_steps[..used].iter().all(small);
    let mut sink = Interp::<S, D, V, F, PERSPECTIVE> {
        surface,
        depth,
        shade,
        s,
        origin: v0,
        den2,
        z,
        dz,
        planes,
        steps,
        row_steps,
        dz_row,
        prev: None,
        prev_z: 0,
        prev_vals: [0; MAX_VARYINGS],
        incremental,
        count,
        base,
        d1,
        d2,
        _v: core::marker::PhantomData,
    };
    walk_spans(&t, 1 << BITS, &clip, &mut sink)
}

/// The largest `q` a vertex may carry: `1/w` for `w = 2^-8` in the scale of [`ScreenVertex::q`].
pub const Q_MAX: i64 = 1 << 28;
