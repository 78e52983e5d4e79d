//! Anti-aliased silhouette edges: which pixels of a triangle are drawn opaque and which are
//! blended by their coverage, row by row.
//!
//! A triangle with silhouette edges (edges whose neighbour faces away, or that have none) is
//! drawn in two passes. The first draws the pixels wholly inside every silhouette edge (and
//! inside the other edges by the usual top-left rule on pixel centres); the second, once the
//! whole mesh is drawn, blends every pixel its silhouette edges cross into what lies beneath,
//! by its coverage. Interior edges keep the pixel-centre rule, so the triangles of a surface
//! still share their pixels with no gap and no double pixel, and a pixel is only ever blended
//! over what other draws left there: its result depends on its own position alone, so bands
//! equal the whole frame.
//!
//! Geometry, in doubled sub-pixel units (`S = 2^BITS` a pixel): pixel `(col, row)` has its
//! centre at `(2 S col + S, 2 S row + S)` and spans `S` either side of it. Edge `a -> b` has the
//! inward normal `n` (the edge turned by the triangle's winding), and `E(p) = n . (p - 2a)`
//! is at least zero inside. Over a pixel, `E` ranges over the centre's value plus or minus
//! `W = S (|nx| + |ny|)`: the pixel lies wholly inside when `E >= W` at its centre, and meets
//! the inside when `E > -W`. Its covered fraction is the distribution of a sum of two uniform
//! variables, of widths `2 S max(|nx|, |ny|)` and `2 S min(|nx|, |ny|)`: a trapezoid whose
//! two quadratic ends and linear middle [`Coverage`] evaluates exactly, up to one reciprocal
//! per edge.

use crate::geom::PixelRect;
use crate::raster::triangle::setup::SpanSink;
use core::num::NonZeroU64;

/// What the blending pass asks of a triangle's pixel sink besides spans.
pub(crate) trait FringeSink: SpanSink {
    /// Blends pixel `(x, row)` (inside the clip area) by `coverage`, in `1 ..= 65536`.
    fn fringe(&mut self, row: i32, x: i32, coverage: u32) -> Result<(), Self::Error>;
}

/// The largest sub-pixel coordinate magnitude, in pixels, a triangle may have for its
/// silhouettes to be anti-aliased: the walk's products then stay far inside `i64` (normals below
/// 2^(17 + BITS), doubled distances below 2^(18 + BITS)). A triangle beyond it (only one that
/// reaches far off screen) is drawn as without anti-aliasing.
pub const AA_RANGE_PIXELS: i64 = 1 << 16;

/// Whether every vertex lies within [`AA_RANGE_PIXELS`] of the origin.
#[inline(always)]
pub(crate) fn in_aa_range<const BITS: u32>(p: &[(i64, i64); 3]) -> bool {
    let limit = AA_RANGE_PIXELS << BITS;
    p.iter()
        .all(|&(x, y)| (-limit..=limit).contains(&x) && (-limit..=limit).contains(&y))
}

/// `ceil(n / d)` for `d > 0`, through the edge walks' division (32-bit when the operands fit,
/// counted as a 64-bit one otherwise).
#[inline(always)]
fn ceil_div(n: i64, d: i64) -> i64 {
    let d = NonZeroU64::new(d.unsigned_abs()).unwrap_or(NonZeroU64::MIN);
    crate::raster::edge::ceil_div(n, d)
}

/// One column bound stepped row by row: `ceil(n / d)` as `n` moves by `delta` a row, with no
/// division after set-up (quotient and remainder, as Bresenham).
#[derive(Debug, Clone, Copy)]
struct CeilWalk {
    q: i64,
    /// `q d - n`, in `[0, d)`.
    r: i64,
    dq: i64,
    dr: i64,
    d: i64,
}

impl CeilWalk {
    fn new(n: i64, d: i64, delta: i64) -> Self {
        let q = ceil_div(n, d);
        let dq = ceil_div(delta, d);
        Self {
            q,
            r: q * d - n,
            dq,
            dr: dq * d - delta,
            d,
        }
    }

    #[inline(always)]
    fn step(&mut self) {
        self.q += self.dq;
        self.r += self.dr;
        if self.r >= self.d {
            self.r -= self.d;
            self.q -= 1;
        }
    }

    /// A bound that never binds: `q` far beyond any column, never moving.
    const fn fixed(q: i64) -> Self {
        Self {
            q,
            r: 0,
            dq: 0,
            dr: 0,
            d: 1,
        }
    }
}

/// A triangle's constraints on the columns of each row, as at most two lower and two upper
/// column walks (a triangle has at most two edges facing each way; the unused ones never
/// bind) and a range of rows (for edges along a row).
#[derive(Debug, Clone, Copy)]
struct Bounds {
    lower: [CeilWalk; 2],
    upper: [CeilWalk; 2],
    /// The rows every row-wise constraint allows.
    rows: (i64, i64),
    /// Walks set so far.
    lows: usize,
    ups: usize,
}

impl Bounds {
    /// No constraint yet, over `rows`.
    const fn new(rows: (i64, i64)) -> Self {
        Self {
            lower: [CeilWalk::fixed(i64::MIN / 4); 2],
            upper: [CeilWalk::fixed(i64::MAX / 4); 2],
            rows,
            lows: 0,
            ups: 0,
        }
    }

    /// Adds `a col + k >= t` on row `top + i`, `k` moving by `dk` a row (`k` given at `top`).
    fn add(&mut self, a: i64, k: i64, dk: i64, t: i64, top: i64) {
        if a > 0 {
            if let Some(w) = self.lower.get_mut(self.lows) {
                *w = CeilWalk::new(t - k, a, -dk);
                self.lows += 1;
            }
        } else if a < 0 {
            // col <= floor((k - t) / -a)  <=>  col < ceil((k - t + 1) / -a).
            if let Some(w) = self.upper.get_mut(self.ups) {
                *w = CeilWalk::new(k - t + 1, -a, dk);
                self.ups += 1;
            }
        } else if dk > 0 {
            // k + dk i >= t  <=>  i >= ceil((t - k) / dk).
            self.rows.0 = self.rows.0.max(top + ceil_div(t - k, dk));
        } else if dk < 0 {
            // i <= floor((k - t) / -dk)  <=>  i < ceil((k - t + 1) / -dk).
            self.rows.1 = self.rows.1.min(top + ceil_div(k - t + 1, -dk));
        } else if k < t {
            self.rows.1 = self.rows.0;
        }
    }

    /// The current row's columns, within `clip`.
    #[inline(always)]
    fn span(&self, clip: &PixelRect) -> (i64, i64) {
        (
            clip.x0.max(self.lower[0].q).max(self.lower[1].q),
            clip.x1.min(self.upper[0].q).min(self.upper[1].q),
        )
    }

    #[inline(always)]
    fn step(&mut self) {
        let [l0, l1] = &mut self.lower;
        let [u0, u1] = &mut self.upper;
        l0.step();
        l1.step();
        u0.step();
        u1.step();
    }
}

/// The covered fraction of a pixel as a function of a silhouette edge's value at its centre.
#[derive(Debug, Clone, Copy)]
struct Coverage {
    /// `E` moves by `a` a column and `dk` a row; `k` is its value at column 0 of the row.
    a: i64,
    k: i64,
    dk: i64,
    /// `W`: half the range of `E` over a pixel, and the change of `E` from a pixel's centre to
    /// its right and lower sides (`S nx`, `S ny`).
    w: i64,
    hx: i64,
    hy: i64,
    /// `t = E + W` is scaled to `u = t 2^16 / (2 S max)` by a shift and a reciprocal.
    shift: u32,
    recip: u64,
    /// The narrow width in the same scale (`2^16` at most) and `2^32 / (2 mu)`.
    mu: u64,
    recip_mu: u64,
}

const ONE: u64 = 1 << 16;

impl Coverage {
    fn new(nx: i64, ny: i64, k: i64, dk: i64, s: i64) -> Self {
        let (ax, ay) = (nx.unsigned_abs(), ny.unsigned_abs());
        let (big, small) = (ax.max(ay) * s as u64, ax.min(ay) * s as u64);
        let w1 = 2 * big;
        let shift = (64 - w1.leading_zeros()).saturating_sub(16);
        // 2 <= w1 >> shift < 2^16 (an edge has a non-zero normal and S >= 1).
        let w1s = (w1 >> shift).max(1) as u32;
        let recip = u64::from(u32::MAX / w1s);
        let mu = ((((2 * small) >> shift) * recip) >> 16).min(ONE);
        let recip_mu = if mu == 0 {
            0
        } else {
            u64::from(u32::MAX / (2 * mu) as u32)
        };
        Self {
            a: 2 * s * nx,
            k,
            dk,
            w: (big + small) as i64,
            hx: s * nx,
            hy: s * ny,
            shift,
            recip,
            mu,
            recip_mu,
        }
    }

    /// The corners of column `x`'s pixel (of the current row) outside the edge, one bit each.
    fn corners(&self, x: i64) -> u8 {
        let e = self.a * x + self.k;
        let mut bits = 0;
        for (i, (sx, sy)) in [(-1, -1), (1, -1), (-1, 1), (1, 1)].into_iter().enumerate() {
            bits |= u8::from(e + sx * self.hx + sy * self.hy < 0) << i;
        }
        bits
    }

    /// The covered fraction of column `x` of the current row, in `0 ..= 2^16`.
    #[inline(always)]
    fn at(&self, x: i64) -> u64 {
        let t = self.a * x + self.k + self.w;
        if t <= 0 {
            return 0;
        }
        if t >= 2 * self.w {
            return ONE;
        }
        let u = (((t as u64) >> self.shift) * self.recip) >> 16;
        let c = if u < self.mu {
            (u * u * self.recip_mu) >> 32
        } else if u <= ONE {
            u - self.mu / 2
        } else if u < ONE + self.mu {
            let v = ONE + self.mu - u;
            ONE.saturating_sub((v * v * self.recip_mu) >> 32)
        } else {
            ONE
        };
        c.min(ONE)
    }
}

/// The covered fraction of column `x`'s pixel (current row) inside every edge of `cover`, in
/// `0 ..= 2^16`: one minus the part outside some edge, by inclusion and exclusion over the parts
/// outside each (no point lies outside all three edges of a triangle). Within a pixel that
/// no two edges cross inside, the parts outside two edges are nested (they share the corners
/// of the smaller) or meet only as far as their sizes force; a pixel that holds a corner of
/// the triangle is estimated the same way.
#[inline(always)]
fn covered(cover: &[Coverage], x: i64) -> u64 {
    let mut out = [0u64; 3];
    let mut partial = 0;
    for (o, c) in out.iter_mut().zip(cover) {
        *o = ONE - c.at(x);
        partial += usize::from(*o > 0);
    }
    let union = if partial < 2 {
        out.iter().sum()
    } else {
        let corners = [0, 1, 2].map(|i| cover.get(i).map_or(0, |c| c.corners(x)));
        let mut u: u64 = out.iter().sum();
        for i in 0..cover.len() {
            for j in i + 1..cover.len() {
                let (a, b) = (corners[i], corners[j]);
                u = u.saturating_sub(if a & b == a || a & b == b {
                    out[i].min(out[j])
                } else {
                    (out[i] + out[j]).saturating_sub(ONE)
                });
            }
        }
        u
    };
    ONE.saturating_sub(union)
}

/// Walks a triangle's anti-aliased pixels: with `fringe` false, hands `sink` the spans of pixels
/// wholly inside its silhouette edges (bit `k` of `mask` for the edge from corner `k` to corner
/// `k + 1`); with `fringe` true, the pixels its silhouette edges cross, each with its coverage.
/// `p` holds the corners in the mesh's order, in sub-pixel units, within [`in_aa_range`], and
/// makes a triangle of non-zero area.
pub(crate) fn walk_silhouette<K: FringeSink, const BITS: u32>(
    p: &[(i64, i64); 3],
    mask: u8,
    fringe: bool,
    clip: &PixelRect,
    sink: &mut K,
) -> Result<(), K::Error> {
    let s = 1i64 << BITS;
    let cross = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
    let sign = cross.signum();
    if sign == 0 {
        return Ok(());
    }
    let (ymin, ymax) = (
        p[0].1.min(p[1].1).min(p[2].1),
        p[0].1.max(p[1].1).max(p[2].1),
    );
    // The rows whose pixels reach inside the triangle's vertical extent.
    let top = (ymin >> BITS).max(clip.y0);
    let bottom = ((ymax + s - 1) >> BITS).min(clip.y1);
    if top >= bottom {
        return Ok(());
    }
    // Inner bounds (every edge), outer bounds (silhouette edges only, the others are shared),
    // and each silhouette edge's coverage.
    let mut inner = Bounds::new((top, bottom));
    let mut outer = Bounds::new((top, bottom));
    let mut cover = [Coverage::new(1, 0, 0, 0, s); 3];
    let mut silhouettes = 0;
    for k in 0..3 {
        let (a, b) = (p[k], p[(k + 1) % 3]);
        let (nx, ny) = (-sign * (b.1 - a.1), sign * (b.0 - a.0));
        let a_col = 2 * s * nx;
        let dk = 2 * s * ny;
        let k0 = nx * (s - 2 * a.0) + ny * (s - 2 * a.1) + dk * top;
        if mask & (1 << k) == 0 {
            // The top-left rule: a centre on a left edge, or on a top edge, is inside.
            let t = i64::from(!(nx > 0 || (nx == 0 && ny > 0)));
            inner.add(a_col, k0, dk, t, top);
            if fringe {
                outer.add(a_col, k0, dk, t, top);
            }
        } else {
            let w = s * (nx.abs() + ny.abs());
            inner.add(a_col, k0, dk, w, top);
            if fringe {
                outer.add(a_col, k0, dk, 1 - w, top);
                cover[silhouettes] = Coverage::new(nx, ny, k0, dk, s);
                silhouettes += 1;
            }
        }
    }
    let cover = &mut cover[..silhouettes];
    if !fringe {
        for row in top..inner.rows.1 {
            if row >= inner.rows.0 {
                let (i0, i1) = inner.span(clip);
                if i0 < i1 {
                    sink.span(row as i32, i0 as i32, i1 as i32)?;
                }
            }
            inner.step();
        }
        return Ok(());
    }
    for row in top..outer.rows.1 {
        if row >= outer.rows.0 {
            let (o0, o1) = outer.span(clip);
            let (mut i0, mut i1) = inner.span(clip);
            if row < inner.rows.0 || row >= inner.rows.1 || i0 >= i1 {
                (i0, i1) = (o1, o1);
            }
            // The crossed pixels: the outer span less the inner one (which it holds).
            for range in [o0..i0.min(o1), i1.max(o0)..o1] {
                for x in range {
                    let c = covered(cover, x);
                    if c > 0 {
                        sink.fringe(row as i32, x as i32, c as u32)?;
                    }
                }
            }
        }
        for c in cover.iter_mut() {
            c.k += c.dk;
        }
        outer.step();
        inner.step();
    }
    Ok(())
}

// The reference areas are f64: test code only, never in a build of the crate.
#[cfg(test)]
#[allow(clippy::disallowed_types, clippy::float_arithmetic)]
mod tests {
    extern crate std;
    use super::*;
    use crate::geom::SubPoint;
    use crate::raster::triangle::setup::tests::{numbers, Spans};
    use crate::raster::triangle::setup::{walk_spans, Sorted};
    use std::collections::BTreeMap;
    use std::vec::Vec;

    /// Every pixel a walk hands over: opaque (coverage 2^16) or crossed, by position.
    #[derive(Default)]
    struct Record(BTreeMap<(i32, i32), (u32, bool)>, usize);

    impl SpanSink for Record {
        type Error = ();
        fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), ()> {
            for x in x0..x1 {
                if self.0.insert((x, row), (1 << 16, true)).is_some() {
                    self.1 += 1;
                }
            }
            Ok(())
        }
    }

    impl FringeSink for Record {
        fn fringe(&mut self, row: i32, x: i32, coverage: u32) -> Result<(), ()> {
            if self.0.insert((x, row), (coverage, false)).is_some() {
                self.1 += 1;
            }
            Ok(())
        }
    }

    /// Both passes of a triangle.
    fn record<const BITS: u32>(p: &[(i64, i64); 3], mask: u8, clip: &PixelRect) -> Record {
        let mut r = Record::default();
        walk_silhouette::<_, BITS>(p, mask, false, clip, &mut r).unwrap();
        if mask != 0 {
            walk_silhouette::<_, BITS>(p, mask, true, clip, &mut r).unwrap();
        }
        r
    }

    /// The area of the pixel `(x, y)` (the unit square from `(x, y)`) inside the triangle `t`
    /// (pixel units), in f64: the square clipped by each edge's half-plane in turn.
    fn exact_coverage(t: &[(f64, f64); 3], x: i32, y: i32) -> f64 {
        let (x, y) = (f64::from(x), f64::from(y));
        let mut poly = std::vec![(x, y), (x + 1.0, y), (x + 1.0, y + 1.0), (x, y + 1.0)];
        let cross = (t[1].0 - t[0].0) * (t[2].1 - t[0].1) - (t[2].0 - t[0].0) * (t[1].1 - t[0].1);
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let side = |p: (f64, f64)| {
                cross.signum() * ((b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0))
            };
            let mut out = Vec::new();
            for i in 0..poly.len() {
                let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
                let (sp, sq) = (side(p), side(q));
                if sp >= 0.0 {
                    out.push(p);
                }
                if (sp >= 0.0) != (sq >= 0.0) {
                    let f = sp / (sp - sq);
                    out.push((p.0 + f * (q.0 - p.0), p.1 + f * (q.1 - p.1)));
                }
            }
            poly = out;
            if poly.is_empty() {
                return 0.0;
            }
        }
        let mut area = 0.0;
        for i in 0..poly.len() {
            let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
            area += p.0 * q.1 - q.0 * p.1;
        }
        area.abs() / 2.0
    }

    const CLIP: PixelRect = PixelRect {
        x0: -3,
        y0: -2,
        x1: 60,
        y1: 50,
    };

    /// A random triangle of sub-pixel corners within the clip area and a little beyond.
    fn triangle(next: &mut impl FnMut(u32) -> i32, s: i32, size: u32) -> [(i64, i64); 3] {
        let (cx, cy) = (next(50 * s as u32), next(40 * s as u32));
        // Whole or half pixels now and then, so that corners and edges meet centres and rows.
        let snap = match next(4) {
            0 => s,
            1 => (s / 2).max(1),
            _ => 1,
        };
        [0, 1, 2].map(|_| {
            let d =
                |n: &mut dyn FnMut(u32) -> i32| n(size * s as u32) - (size * s as u32 / 2) as i32;
            let (x, y) = (cx + d(next), cy + d(next));
            (i64::from(x / snap * snap), i64::from(y / snap * snap))
        })
    }

    #[test]
    fn without_silhouettes_the_walk_is_the_span_walk() {
        // Every shared edge of a mesh follows the same top-left rule as every other fill.
        let mut next = numbers(0x2468_ace1);
        for _ in 0..60_000 {
            let size = [2, 8, 40][next(3) as usize] as u32;
            let p = triangle(&mut next, 16, size);
            let mut spans = Spans(Vec::new());
            let v = p.map(|(x, y)| SubPoint::<4>::raw(x as i32, y as i32));
            if let Some(t) = Sorted::new(&v) {
                walk_spans(&t, 16, &CLIP, &mut spans).unwrap();
            }
            let mut expected = BTreeMap::new();
            for (row, x0, x1) in spans.0 {
                for x in x0..x1 {
                    expected.insert((x, row), (1u32 << 16, true));
                }
            }
            let got = record::<4>(&p, 0, &CLIP);
            assert_eq!(got.0, expected, "{p:?}");
        }
    }

    /// The worst coverage errors of random triangles with every edge a silhouette: at pixels
    /// no corner is within a pixel of, and at all.
    fn worst_errors<const BITS: u32>(seed: u32, count: usize) -> (f64, f64) {
        let s = 1i32 << BITS;
        let mut next = numbers(seed);
        let (mut edge, mut all) = (0f64, 0f64);
        for _ in 0..count {
            let size = [1, 3, 10, 40][next(4) as usize] as u32;
            let p = triangle(&mut next, s, size);
            let cross =
                (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
            if cross == 0 {
                continue;
            }
            let got = record::<BITS>(&p, 7, &CLIP);
            assert_eq!(got.1, 0, "a pixel handed over twice: {p:?}");
            let t = p.map(|(x, y)| (x as f64 / f64::from(s), y as f64 / f64::from(s)));
            let (x_lo, x_hi) = (
                t.iter().map(|v| v.0).fold(f64::MAX, f64::min),
                t.iter().map(|v| v.0).fold(f64::MIN, f64::max),
            );
            let (y_lo, y_hi) = (
                t.iter().map(|v| v.1).fold(f64::MAX, f64::min),
                t.iter().map(|v| v.1).fold(f64::MIN, f64::max),
            );
            for y in (y_lo.floor() as i32 - 1).max(CLIP.y0 as i32)
                ..(y_hi.ceil() as i32 + 1).min(CLIP.y1 as i32)
            {
                for x in (x_lo.floor() as i32 - 1).max(CLIP.x0 as i32)
                    ..(x_hi.ceil() as i32 + 1).min(CLIP.x1 as i32)
                {
                    let exact = exact_coverage(&t, x, y);
                    let (c, opaque) = got
                        .0
                        .get(&(x, y))
                        .map_or((0.0, false), |&(c, o)| (f64::from(c) / 65536.0, o));
                    if opaque {
                        // Opaque only where the pixel is wholly inside.
                        assert!(exact > 1.0 - 1e-9, "{p:?} ({x}, {y}) {exact}");
                    }
                    let err = (c - exact).abs();
                    all = all.max(err);
                    let near = t.iter().any(|v| {
                        v.0 > f64::from(x) - 1.0
                            && v.0 < f64::from(x) + 2.0
                            && v.1 > f64::from(y) - 1.0
                            && v.1 < f64::from(y) + 2.0
                    });
                    if !near {
                        edge = edge.max(err);
                    }
                }
            }
        }
        (edge, all)
    }

    #[test]
    fn coverage_is_the_exact_area_along_edges() {
        for (bits, (edge, all)) in [
            (4, worst_errors::<4>(0x0bad_cafe, 20_000)),
            (6, worst_errors::<6>(0x1234_5678, 20_000)),
            (0, worst_errors::<0>(0x0f0f_0f0f, 20_000)),
        ] {
            std::println!("BITS {bits}: worst error along edges {edge:.5}, anywhere {all:.5}");
            // Measured 0.00006 along edges (the reciprocals' rounding) and 0.475 at pixels
            // holding a corner where two silhouette edges meet (estimated, not clipped).
            assert!(edge <= 1.2e-4, "{bits}: {edge}");
            assert!(all <= 0.5, "{bits}: {all}");
        }
    }
}
