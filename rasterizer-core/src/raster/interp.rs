//! Triangles with a depth test and interpolated values: the rasterizer behind the 3D pipeline.
//!
//! Coverage is exactly that of [`crate::raster::triangle::fill_triangle`] (the same span walk). Depth
//! and every shader value are planes over the screen, evaluated exactly at the first pixel of each
//! span and stepped across it in 16 fractional bits; the depth test splits a span into runs of
//! passing pixels, and each run goes to the target as one `shade_span`. With [`crate::depth::NoDepth`] the test
//! and its buffer compile away.

use crate::depth::DepthTest;
use crate::geom::{PixelRect, SubPoint};
use crate::geom::{Varyings, MAX_VARYINGS};
use crate::numerics::{frac, Numerics, Perspective, SpanStart, Standard};
use crate::raster::edge::row_at_or_below;
use crate::raster::triangle::setup::{misses_every_centre, walk_spans, Sorted, SpanSink};
use crate::surface::Surface;
use crate::wide;

/// A vertex in screen space: sub-pixel position, depth and the shader's values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScreenVertex<V, const BITS: u32> {
    /// Position.
    pub p: SubPoint<BITS>,
    /// Depth, 0 nearest.
    pub z: u16,
    /// The values to interpolate.
    pub var: V,
    /// `2^20 / w`, clamped to `1 ..= Q_MAX`: read only by perspective-correct interpolation.
    /// (The pipeline's fused perspective path, which reads only the ratios of a triangle's
    /// three, passes another common multiple of `1 / w` in its own triangles.)
    pub q: i64,
}

/// One linear function over the screen: `v(dx2, dy2) = v0 + (a dx2 + b dy2) / den2` in doubled
/// sub-pixel offsets from the first vertex.
#[derive(Debug, Clone, Copy, Default)]
struct Plane {
    v0: i64,
    a: i64,
    b: i64,
}

/// The number of planes a triangle can carry: the shader's values and depth (the last slot).
const PLANES: usize = MAX_VARYINGS + 1;
/// The depth plane's slot.
const Z: usize = MAX_VARYINGS;

/// `(n div d, n mod d)` of an `i128` numerator, `d > 0`, quotient saturated to `i64`.
#[inline(always)]
fn divmod(n: i128, d: i64) -> (i64, i64) {
    // 64-bit division when the numerator fits (small triangles): a 128-bit one is a library call.
    if let Ok(n) = i64::try_from(n) {
        return wide::divmod_floor_i64(n, d);
    }
    let (q, r) = wide::divmod_floor_i128(n, i128::from(d));
    (
        q.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64,
        r as i64,
    )
}

/// A plane's value at a span start, exactly: `v0 2^16 + floor(N / den2)` with
/// `N = (a dx2 + b dy2) 2^16 + den2 / 2`, kept as the quotient `q` and the remainder `r` of `N`, so
/// that moving to the next span start is additions (and a few subtractions to bring `r` back into
/// `[0, den2)`) with no rounding: every span starts from the exactly rounded value, wherever the
/// walk began (a band render and a whole-frame render agree to the bit).
#[derive(Debug, Clone, Copy, Default)]
struct Exact {
    q: i64,
    r: i64,
}

struct Interp<'a, S: Surface, D, V, F, N> {
    surface: &'a mut S,
    depth: &'a mut D,
    shade: F,
    s: i64,
    origin: (i64, i64),
    den2: i64,
    /// The values' planes (affine), or `1/w` and the two scaled barycentrics (perspective-correct),
    /// then depth in slot [`Z`].
    planes: [Plane; PLANES],
    /// Per-pixel steps in 16.16, rounded (the same for every span).
    steps: [i64; PLANES],
    /// `divmod(a 2s 2^16, den2)` and `divmod(b 2s 2^16, den2)`: the exact moves of `N` per column
    /// and per row.
    col: [Exact; PLANES],
    row: [Exact; PLANES],
    /// The previous span's start and its exact values.
    prev: Option<(i32, i32)>,
    at: [Exact; PLANES],
    /// The moves fit `i64` (`den2 < 2^46`, steps below 2^40): otherwise every span start is
    /// evaluated from scratch.
    incremental: bool,
    /// [`SpanStart::Gradient`] for this triangle: span starts from `steps` and `grad_row`.
    gradient: bool,
    /// Per-row gradients in the fractional bits (gradient span starts only).
    grad_row: [i64; PLANES],
    /// Perspective-correct only: the first vertex's values and the differences to the other two.
    base: [i64; MAX_VARYINGS],
    d1: [i64; MAX_VARYINGS],
    d2: [i64; MAX_VARYINGS],
    _v: core::marker::PhantomData<(V, N)>,
}

impl<S: Surface, D: DepthTest, V: Varyings, F: FnMut(&V) -> S::Color, N: Numerics>
    Interp<'_, S, D, V, F, N>
{
    /// The number of values `V` holds (at most [`MAX_VARYINGS`]): a constant once inlined, so the
    /// per-pixel loops unroll.
    #[inline(always)]
    fn count() -> usize {
        V::default().as_slice().len().min(MAX_VARYINGS)
    }

    /// The planes in use besides depth: the values, or `1/w` and two barycentrics.
    #[inline(always)]
    fn used() -> usize {
        if N::PERSPECTIVE {
            3
        } else {
            Self::count()
        }
    }

    /// Moves every plane's exact value to the span starting at `(x0, row)`.
    #[inline(always)]
    fn seek(&mut self, row: i32, x0: i32) {
        if self.gradient {
            // v0 + (gx dx2 + gy dy2) / 2s, rounded: a function of the position alone.
            let dx2 = (2 * i64::from(x0) + 1) * self.s - 2 * self.origin.0;
            let dy2 = (2 * i64::from(row) + 1) * self.s - 2 * self.origin.1;
            let sh = self.s.trailing_zeros() + 1;
            for i in 0..Self::used() {
                self.at[i].q = (self.steps[i] * dx2 + self.grad_row[i] * dy2 + self.s) >> sh;
            }
            if D::ENABLED {
                self.at[Z].q = (self.steps[Z] * dx2 + self.grad_row[Z] * dy2 + self.s) >> sh;
            }
            return;
        }
        if let (true, Some((pr, px))) = (self.incremental, self.prev) {
            let (dr, dc) = (i64::from(row - pr), i64::from(x0 - px));
            for i in 0..Self::used() {
                self.advance(i, dr, dc);
            }
            if D::ENABLED {
                self.advance(Z, dr, dc);
            }
        } else {
            let dx2 = (2 * i64::from(x0) + 1) * self.s - 2 * self.origin.0;
            let dy2 = (2 * i64::from(row) + 1) * self.s - 2 * self.origin.1;
            for i in 0..Self::used() {
                self.exact(i, dx2, dy2);
            }
            if D::ENABLED {
                self.exact(Z, dx2, dy2);
            }
        }
        self.prev = Some((row, x0));
    }

    /// Plane `i` evaluated from scratch at doubled offsets `(dx2, dy2)`.
    #[inline(always)]
    fn exact(&mut self, i: usize, dx2: i64, dy2: i64) {
        let p = self.planes[i];
        let f = crate::wide::mul_i128(p.a, dx2) + crate::wide::mul_i128(p.b, dy2);
        let (q, r) = divmod((f << frac::<N>()) + i128::from(self.den2 / 2), self.den2);
        self.at[i] = Exact { q, r };
    }

    /// Plane `i` moved by `dr` rows and `dc` columns, exactly.
    #[inline(always)]
    fn advance(&mut self, i: usize, dr: i64, dc: i64) {
        let den2 = self.den2;
        let (c, r) = (self.col[i], self.row[i]);
        let e = &mut self.at[i];
        e.q += dc * c.q + dr * r.q;
        e.r += dc * c.r + dr * r.r;
        // Back into [0, den2): a step or two for neighbouring spans, a division otherwise.
        if e.r >= den2 {
            if e.r < 3 * den2 {
                e.r -= den2;
                e.q += 1;
                if e.r >= den2 {
                    e.r -= den2;
                    e.q += 1;
                }
            } else {
                let (q, r) = wide::divmod_floor_i64(e.r, den2);
                e.q += q;
                e.r = r;
            }
        } else if e.r < 0 {
            if e.r >= -2 * den2 {
                e.r += den2;
                e.q -= 1;
                if e.r < 0 {
                    e.r += den2;
                    e.q -= 1;
                }
            } else {
                let (q, r) = wide::divmod_floor_i64(e.r, den2);
                e.q += q;
                e.r = r;
            }
        }
    }

    /// Plane `i`'s value at the current span start, with `frac::<N>()` fractional bits.
    #[inline(always)]
    fn value(&self, i: usize) -> i64 {
        (self.planes[i].v0 << frac::<N>()).saturating_add(self.at[i].q)
    }
}

impl<S: Surface, D: DepthTest, V: Varyings, F: FnMut(&V) -> S::Color, N: Numerics> SpanSink
    for Interp<'_, S, D, V, F, N>
{
    type Error = S::Error;

    #[inline(always)]
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), S::Error> {
        self.seek(row, x0);
        // The depth test takes 16 fractional bits.
        let z0 = if D::ENABLED {
            self.value(Z) << (16 - frac::<N>())
        } else {
            0
        };
        let dz = self.steps[Z] << (16 - frac::<N>());
        let planes = Self::used();
        let mut start = [0i64; MAX_VARYINGS];
        for (i, s) in start.iter_mut().enumerate().take(planes) {
            *s = self.value(i);
        }
        let mut step = [0i64; MAX_VARYINGS];
        step[..planes].copy_from_slice(&self.steps[..planes]);
        let count = Self::count();
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
            surface.shade_span_in_clip(x0 + offset as i32, row, len, || {
                let mut v = V::default();
                if N::PERSPECTIVE {
                    // The barycentrics divided by w, over 1/w: one division each per pixel.
                    let q = acc[0].max(1);
                    let l1 = wide::div_floor_i64(acc[1].max(0) << frac::<N>(), q);
                    let l2 = wide::div_floor_i64(acc[2].max(0) << frac::<N>(), q);
                    for (i, out) in v.as_mut_slice().iter_mut().enumerate().take(count) {
                        let mix = l1 * d1[i] + l2 * d2[i];
                        *out = (base[i] + ((mix + (1 << (frac::<N>() - 1))) >> frac::<N>())) as i32;
                    }
                } else {
                    for (out, a) in v.as_mut_slice().iter_mut().zip(&acc) {
                        // Rounded to the nearest unit of the value.
                        *out = ((a + (1 << (frac::<N>() - 1))) >> frac::<N>()) as i32;
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
/// Every span starts from the exactly rounded value of each plane (kept as a quotient and a
/// remainder, so moving between spans needs no division), and steps across the span in 16.16. The
/// pixels therefore do not depend on which rows are drawn: rendering the screen in bands gives the
/// whole-frame picture to the bit.
///
/// With `PERSPECTIVE` the values are interpolated perspective-correctly from the vertices' `q`
/// (`1/w`, see [`ScreenVertex::q`]): the barycentrics divided by `w` are planes over the screen and
/// each pixel divides them by `1/w` (two divisions per pixel). Without it they are affine in screen
/// space, which is exact for depth and close for small triangles.
///
/// This is [`fill_triangle_interp_with`] with the [`Standard`] numeric knobs (or [`Perspective`]).
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
    if PERSPECTIVE {
        fill_triangle_interp_with::<S, D, V, F, Perspective, BITS>(surface, depth, vertices, shade)
    } else {
        fill_triangle_interp_with::<S, D, V, F, Standard, BITS>(surface, depth, vertices, shade)
    }
}

/// [`fill_triangle_interp`] with chosen numeric knobs `N` ([`crate::numerics`]): the fractional
/// bits of the interpolation, the span-start method and perspective correction. With [`SpanStart::Gradient`] the pixels
/// still depend only on their position (bands match the whole frame), but values may differ from
/// the exactly rounded plane by the gradients' rounding times the distance from the first vertex.
pub fn fill_triangle_interp_with<S, D, V, F, N, const BITS: u32>(
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
    N: Numerics,
{
    let Some(t) = Sorted::new(&vertices.map(|v| v.p)) else {
        return Ok(());
    };
    let [v0, v1, v2] = t.v;
    let s = 1i64 << BITS;
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    // A triangle that surely covers no pixel (most triangles of a dense mesh far away) skips
    // the set-up of its planes.
    if misses_every_centre(&t, s, &clip) {
        return Ok(());
    }
    let [o0, o1, o2] = t.order;
    let sign = t.cross.signum();
    let den2 = 2 * t.cross.abs();
    // The plane through three values, in doubled offsets from v0, the sign moved into a and b.
    let plane = |f0: i64, f1: i64, f2: i64| Plane {
        v0: f0,
        a: sign * ((f1 - f0) * (v2.1 - v0.1) - (f2 - f0) * (v1.1 - v0.1)),
        b: sign * ((f2 - f0) * (v1.0 - v0.0) - (f1 - f0) * (v2.0 - v0.0)),
    };
    let mut planes = [Plane::default(); PLANES];
    let values = [vertices[o0].var, vertices[o1].var, vertices[o2].var];
    let count = values[0].as_slice().len().min(MAX_VARYINGS);
    let value = |k: usize, i: usize| i64::from(values[k].as_slice()[i]);
    let (mut base, mut d1, mut d2) = (
        [0i64; MAX_VARYINGS],
        [0i64; MAX_VARYINGS],
        [0i64; MAX_VARYINGS],
    );
    let used = if N::PERSPECTIVE {
        let q = [vertices[o0].q, vertices[o1].q, vertices[o2].q].map(|q| q.clamp(1, Q_MAX));
        planes[0] = plane(q[0], q[1], q[2]);
        planes[1] = plane(0, q[1], 0);
        planes[2] = plane(0, 0, q[2]);
        for i in 0..count {
            base[i] = value(0, i);
            d1[i] = value(1, i) - value(0, i);
            d2[i] = value(2, i) - value(0, i);
        }
        3
    } else {
        for (i, p) in planes.iter_mut().enumerate().take(count) {
            *p = plane(value(0, i), value(1, i), value(2, i));
        }
        count
    };
    let zs = [vertices[o0].z, vertices[o1].z, vertices[o2].z].map(i64::from);
    planes[Z] = plane(zs[0], zs[1], zs[2]);
    let mut steps = [0i64; PLANES];
    let mut col = [Exact::default(); PLANES];
    let mut row = [Exact::default(); PLANES];
    let mut incremental = den2 < 1 << 46;
    let mut grad_row = [0i64; PLANES];
    // Gradient span starts when every plane's a 2s 2^F and b 2s 2^F fit i64 and the gradients stay
    // below 2^30 (then gx dx2 + gy dy2 < 2^62 for offsets within the guard band).
    let limit = 1i64 << (61 - BITS - frac::<N>());
    let fits = |i: usize| planes[i].a.abs() < limit && planes[i].b.abs() < limit;
    let mut gradient =
        N::SPANS == SpanStart::Gradient && (0..used).all(fits) && (!D::ENABLED || fits(Z));
    if gradient {
        let round = |n: i64| wide::div_floor_i64(n + den2 / 2, den2);
        let mut grad = |i: usize| {
            let p = planes[i];
            steps[i] = round((p.a * 2 * s) << frac::<N>());
            grad_row[i] = round((p.b * 2 * s) << frac::<N>());
            steps[i].abs() < 1 << 30 && grad_row[i].abs() < 1 << 30
        };
        for i in 0..used {
            gradient &= grad(i);
        }
        if D::ENABLED {
            gradient &= grad(Z);
        }
    }
    // A triangle on one row of pixel centres has one span: it never moves down a row.
    let one_row =
        row_at_or_below(v2.1, s).min(clip.y1) - row_at_or_below(v0.1, s).max(clip.y0) == 1;
    let mut setup = |i: usize| {
        let p = planes[i];
        let (cq, cr) = divmod(crate::wide::mul_i128(p.a, 2 * s) << frac::<N>(), den2);
        let (rq, rr) = if one_row {
            (0, 0)
        } else {
            divmod(crate::wide::mul_i128(p.b, 2 * s) << frac::<N>(), den2)
        };
        // The per-pixel step is the column move rounded: round(a 2s 2^16 / den2).
        steps[i] = cq + i64::from(2 * cr >= den2);
        col[i] = Exact { q: cq, r: cr };
        row[i] = Exact { q: rq, r: rr };
        // Travel between span starts is at most 2^16 rows or columns: moves below 2^40 keep
        // the products below 2^56.
        incremental &= cq.unsigned_abs() < 1 << 40 && rq.unsigned_abs() < 1 << 40;
    };
    if !gradient {
        for i in 0..used {
            setup(i);
        }
        if D::ENABLED {
            setup(Z);
        }
    }
    let mut sink = Interp::<S, D, V, F, N> {
        surface,
        depth,
        shade,
        s,
        origin: v0,
        den2,
        planes,
        steps,
        col,
        row,
        prev: None,
        at: [Exact::default(); PLANES],
        incremental,
        gradient,
        grad_row,
        base,
        d1,
        d2,
        _v: core::marker::PhantomData,
    };
    walk_spans(&t, s, &clip, &mut sink)
}

/// The largest `q` a vertex may carry: `1/w` for `w = 2^-8` in the scale of [`ScreenVertex::q`].
pub const Q_MAX: i64 = 1 << 28;
