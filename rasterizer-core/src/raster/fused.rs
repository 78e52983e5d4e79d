//! The fused span loop of the default 3D path: depth test, interpolated values and colour of each
//! pixel in one loop, in 32-bit wrapping arithmetic.
//!
//! Coverage is exactly that of [`crate::raster::triangle::fill_triangle`] (the same span walk).
//! Each interpolated value (a shader's values, and depth) is a plane over the pixel grid,
//! `K + gx px + gy py` modulo 2^32, with `K`, `gx` and `gy` fixed per triangle: a pixel's value is
//! a function of its position alone, so a band render equals the whole frame to the bit, and a
//! span starts with two multiplications per plane.
//!
//! The plane is anchored at a pixel (the pixel of the triangle's top vertex, moved into the
//! viewport when that vertex lies outside it), within one unit of the last fractional bit there,
//! and the gradients are rounded to the value's fractional bits, so a pixel `dx, dy` pixels from
//! the anchor is within `(|dx| + |dy|) / 2 + 1` units of the last fractional bit of the exact
//! plane: less than half a unit of the value itself
//! for any viewport up to 32767 pixels a side. Half a unit is added to `K`, so a pixel's value is
//! one shift away (rounded to nearest, halves up). The exact value at a covered pixel centre is a
//! mix of the three vertices' values; with the half-unit offset and that error bound it never
//! leaves `0 .. 2^32` for values and depths the vertices hold in `0 ..= 2^(32 - FRAC) - 1`, so the
//! wrapping arithmetic needs no clamp per pixel.
//!
//! With a depth test the triangle goes to the surface whole ([`DepthTriangle`]): a framebuffer
//! has it write its words directly, any other surface takes its spans one call each. In a
//! framebuffer, a small triangle inside the clip area's columns ([`Lean`]) runs a loop that keeps
//! only what a small triangle needs (32-bit walks, one index a row for both buffers, no clamp):
//! on a small core the set-up and the bookkeeping of rows and spans, not the pixels, are most of
//! a mesh's time. Every path computes the same planes and walks, so all draw the same pixels.

use crate::depth::DepthRows;
use crate::depth::{Compare, DepthTest};
use crate::geom::{PixelRect, SubPoint};
use crate::geom::{Varyings, MAX_VARYINGS};
use crate::raster::edge::{row_at_or_below, EdgeWalk};
use crate::raster::silhouette::{in_aa_range, walk_silhouette, FringeSink};
use crate::raster::triangle::setup::row_order;
use crate::raster::triangle::setup::{
    may_cover_a_centre, rows_in_clip, walk_spans_once, Sorted, SpanSink,
};
use crate::raster::triangle::small::{Edge, SMALL_PIXELS};
use crate::surface::{BlendError, DepthSpan, Surface};
use crate::surface::{DepthTriangle, Storage};
use crate::wide::Reciprocal;
use core::num::NonZeroU64;

/// One plane: the value at pixel `(px, py)` is `k + gx px + gy py`, wrapping.
#[derive(Debug, Clone, Copy, Default)]
struct Plane32 {
    k: u32,
    gx: u32,
    gy: u32,
}

impl Plane32 {
    /// The value at the pixel `(x, y)`.
    #[inline(always)]
    fn at(&self, x: i32, y: i32) -> u32 {
        self.k
            .wrapping_add(self.gx.wrapping_mul(x as u32))
            .wrapping_add(self.gy.wrapping_mul(y as u32))
    }
}

/// The triangle's shape as the planes need it: edge vectors from the top vertex, the sign and
/// size of the doubled area, and the anchor pixel with its centre's offset from the top vertex.
struct Shape {
    /// `v1 - v0` and `v2 - v0` in sub-pixel units, times the sign of the doubled area (so that
    /// every gradient divides by its magnitude).
    e1: (i64, i64),
    e2: (i64, i64),
    /// The doubled area's magnitude: the divisor of every gradient, never zero.
    cross: i64,
    /// Its reciprocal, for the narrow set-up's quotients (unused otherwise).
    recip: Reciprocal,
    /// The anchor pixel.
    anchor: (i64, i64),
    /// Its centre minus `v0`, in half sub-pixel units (a centre is half a unit off the grid
    /// when there are no sub-pixel bits).
    offset2: (i64, i64),
    /// The same for pixel `(0, 0)`: `s - 2 v0`.
    origin2: (i64, i64),
    /// The narrow set-up applies: the anchor on the top vertex's own pixel and edges of at most
    /// `2^(27 - BITS)` sub-pixels each way ([`narrow_edges`]: every gradient's numerator then
    /// stays in the reciprocal's range, see [`Shape::plane`]); otherwise the planes are set up
    /// in `i128`.
    narrow: bool,
}

/// Whether every component `e` of the edges `e1`, `e2` lies in `-2^k < e <= 2^k`, `k = 27 -
/// BITS`: small enough for the narrow set-up ([`Shape::plane`]).
#[inline(always)]
fn narrow_edges<const BITS: u32>(e1: (i64, i64), e2: (i64, i64)) -> bool {
    // Moved up by 2^k - 1, each such component lies in 0 .. 2^(k + 1) (any other below zero
    // or beyond): one test of the four's bits above covers them all.
    let k = 27 - BITS;
    let up = |e: i64| e.wrapping_add((1 << k) - 1) as u64;
    (up(e1.0) | up(e1.1) | up(e2.0) | up(e2.1)) >> (k + 1) == 0
}

/// `round(n / d)` for `d > 0`, halves up, in `i128`.
fn round_div_wide(n: i128, d: i128) -> i128 {
    crate::wide::div_floor_i128(n + (d >> 1), d)
}

/// The gradients of a plane over narrow edges from their numerators: `a 2^(BITS + frac) / cross`
/// and `b 2^(BITS + frac) / cross` rounded, halves up, to within one unit toward zero. The
/// correction step that would round them exactly (a multiply, a compare and an add) costs more than
/// the unit is worth: at most `2^-(BITS + frac)` a sub-pixel step.
#[inline(always)]
fn near_gradients<const BITS: u32>(
    recip: &Reciprocal,
    cross: i64,
    a: i64,
    b: i64,
    frac: u32,
) -> (i64, i64) {
    let half = cross >> 1;
    // (Wrapping: values outside the contract give wrong gradients, never a panic.)
    let gx = recip.near((a << (BITS + frac)).wrapping_add(half));
    let gy = recip.near((b << (BITS + frac)).wrapping_add(half));
    (gx, gy)
}

impl Shape {
    /// The plane through the values `f` at the sorted vertices, with `frac` fractional bits and
    /// `offset` (units of the last fractional bit) added: the rounding folded into the start.
    #[inline(always)]
    fn plane<const BITS: u32>(&self, f: [i64; 3], frac: u32, offset: u32) -> Plane32 {
        let (d1, d2) = (f[1] - f[0], f[2] - f[0]);
        // The value changes by a / cross per sub-pixel step in x and b / cross in y.
        let a = d1 * self.e2.1 - d2 * self.e1.1;
        let b = d2 * self.e1.0 - d1 * self.e2.0;
        if self.narrow {
            // Values that keep the shader's contract (each times `2^frac` fits an `i32`, or a
            // `u32`) differ by less than `2^(32 - frac)`, so with the narrow shape's edges of at
            // most `2^(27 - BITS)`, `|a|, |b| < 2^(60 - BITS - frac)`: shifted, they stay below
            // `2^60`. round(a 2^(BITS + frac) / cross), halves up, to within one unit of the
            // last bit, toward zero ([`Reciprocal::near`]).
            let (gx, gy) = near_gradients::<BITS>(&self.recip, self.cross, a, b, frac);
            // The anchor's centre lies within half a pixel of v0: its value from the rounded
            // gradients is within one unit of the last bit, with no division. Moved back to
            // pixel (0, 0) by whole gradients, that value is the one below: the anchor's whole
            // pixels leave the floor, and the floor's low 32 + BITS + 1 bits need only those of
            // its numerator, so the products may wrap: the gradients' size (below `2^60 + 1`,
            // slivers' too) does not matter here.
            let n = gx
                .wrapping_mul(self.origin2.0)
                .wrapping_add(gy.wrapping_mul(self.origin2.1))
                .wrapping_add(1 << BITS);
            return Plane32 {
                k: ((f[0] << frac) as u32)
                    .wrapping_add((n >> (BITS + 1)) as u32)
                    .wrapping_add(offset),
                gx: gx as u32,
                gy: gy as u32,
            };
        }
        // The anchor is the top vertex's own pixel when its centre lies within half a pixel of
        // it: `offset2` in `(-s, s]` each way.
        let s = 1i64 << BITS;
        let near = |o: i64| -s < o && o <= s;
        let own = near(self.offset2.0) && near(self.offset2.1);
        let (fa, gx, gy) = plane_wide::<BITS>(f[0], a, b, frac, self.cross, self.offset2, own);
        let (ax, ay) = (self.anchor.0 as u32, self.anchor.1 as u32);
        let (gx, gy) = (gx as u32, gy as u32);
        Plane32 {
            k: (fa as u32)
                .wrapping_add(offset)
                .wrapping_sub(gx.wrapping_mul(ax))
                .wrapping_sub(gy.wrapping_mul(ay)),
            gx,
            gy,
        }
    }
}

/// [`Shape::plane`] for large triangles, steep planes or a far anchor, in `i128`: gradients whose
/// numerators lie in the narrow set-up's range as that set-up finds them, others exactly rounded;
/// the anchor's value exactly rounded for a far anchor, or from the rounded gradients for the top
/// vertex's own pixel (`own`), as the narrow set-up finds it, so that a triangle gets the same
/// planes on either path. Only the low 32 bits of each result matter. It takes the fields it needs
/// by value, so that the shape need not be stored in memory for it.
#[inline(never)]
#[cold]
fn plane_wide<const BITS: u32>(
    f0: i64,
    a: i64,
    b: i64,
    frac: u32,
    cross: i64,
    offset2: (i64, i64),
    own: bool,
) -> (i64, i64, i64) {
    let (wa, wb, d) = (i128::from(a), i128::from(b), i128::from(cross));
    // A numerator within the narrow set-up's range gets its quotient, which that set-up
    // computes for every numerator of values within the contract (see [`Shape::plane`]). A
    // division a plane here, where the hot set-up has one a triangle: the rare path stays small.
    let reach = 60u32.saturating_sub(BITS + frac);
    let recip = NonZeroU64::new(cross.unsigned_abs())
        .filter(|_| (a.unsigned_abs() | b.unsigned_abs()) >> reach == 0)
        .map(Reciprocal::new);
    let (gx, gy) = match recip.map(|r| near_gradients::<BITS>(&r, cross, a, b, frac)) {
        Some((gx, gy)) => (i128::from(gx), i128::from(gy)),
        None => (
            round_div_wide(wa << (BITS + frac), d),
            round_div_wide(wb << (BITS + frac), d),
        ),
    };
    let moved = if own {
        // As the narrow set-up: only the low 32 + BITS + 1 bits of the sum matter, so the
        // products may wrap.
        let (gx, gy) = (gx as i64, gy as i64);
        i128::from(
            gx.wrapping_mul(offset2.0)
                .wrapping_add(gy.wrapping_mul(offset2.1))
                .wrapping_add(1 << BITS)
                >> (BITS + 1),
        )
    } else {
        let n = (crate::wide::mul_i128(a, offset2.0) + crate::wide::mul_i128(b, offset2.1)) << frac;
        round_div_wide(n, 2 * d)
    };
    let fa = (i128::from(f0) << frac) + moved;
    // Truncating keeps the low bits, all the wrapping arithmetic needs.
    (fa as i64, gx as i64, gy as i64)
}

/// What the fused loop asks of a shader: the colour of a pixel from its values, each
/// `value 2^vfrac + voffset` (see [`fill_fused`]).
pub(crate) trait FusedColor<C> {
    /// The fixed-point scale of the values this colour reads: a constant, so that the set-up's
    /// shifts and range tests are by constants.
    const PRECISION: Precision;
    /// The colour depends on the pixel's screen position too ([`FusedColor::color_at`]): the
    /// loops then track it; otherwise they compile exactly as without it.
    const AT: bool = false;
    /// The lean path first asks whether the triangle lies behind what its bounding box already
    /// holds (every stored depth there at most its nearest corner's less one, below which no
    /// pixel's depth lies) and then draws nothing, without a set-up. For the colours whose
    /// set-up costs more than the test on a mesh (the perspective-correct ones); on the default
    /// path the test cost about what it saved.
    const HIDDEN_TEST: bool = false;
    /// The values step in pairs, each pair as one 64-bit sum (value `2k` low, `2k + 1` high),
    /// for a colour whose even values are known to stay within `0 .. 2^32` at every pixel of a
    /// triangle: each half then holds its value exactly, and the span loop keeps half as many
    /// running sums and steps (registers) for the same values.
    const PAIRED: bool = false;
    /// The pixel's colour.
    fn color(&self, acc: &[u32; MAX_VARYINGS]) -> C;
    /// The colour of the pixel at `(x, y)`, when [`FusedColor::AT`] is set.
    #[inline(always)]
    fn color_at(&self, acc: &[u32; MAX_VARYINGS], x: i32, y: i32) -> C {
        let _ = (x, y);
        self.color(acc)
    }
}

/// The pixels of one span with a depth test: each pixel's depth, test and values, stepped
/// across the span. `LESS` is the usual test, known at compile time; `D` the depth stage, for
/// whether a passing pixel stores its depth ([`DepthTest::WRITE`]).
struct DepthPixels<'p, P, V, D, const LESS: bool> {
    acc: [u32; MAX_VARYINGS],
    step: [u32; MAX_VARYINGS],
    z: u32,
    dz: u32,
    compare: Compare,
    pixel: &'p P,
    _v: core::marker::PhantomData<(V, D)>,
}

impl<P, V: Varyings, D: DepthTest, const LESS: bool> DepthPixels<'_, P, V, D, LESS> {
    /// The values of pixel `i` if it passes the depth test (which then stores its depth).
    #[inline(always)]
    /// `paired`: the colour's [`FusedColor::PAIRED`].
    fn values(&mut self, i: usize, stored: &mut u16, paired: bool) -> Option<[u32; MAX_VARYINGS]> {
        // Only depth steps with every pixel; the values of a pixel that passes are computed from
        // its index (most pixels of a dense mesh fail the test).
        let nz = (self.z >> Z_FRAC) as u16;
        self.z = self.z.wrapping_add(self.dz);
        let pass = if LESS {
            nz < *stored
        } else {
            self.compare.pass(nz, *stored)
        };
        if !pass {
            return None;
        }
        if D::WRITE {
            *stored = nz;
        }
        let mut acc = self.acc;
        let n = V::LEN.min(MAX_VARYINGS);
        if paired {
            for k in (0..n).step_by(2) {
                if k + 1 >= n {
                    acc[k] = acc[k].wrapping_add(self.step[k].wrapping_mul(i as u32));
                    break;
                }
                // The pair's step as one sum: the low value's step moves the high half by
                // its sign (wrapping, as each value's own sum does).
                let base = u64::from(acc[k]) | u64::from(acc[k + 1]) << 32;
                let step = (u64::from(self.step[k + 1]) << 32)
                    .wrapping_add(self.step[k] as i32 as i64 as u64);
                let v = base.wrapping_add(step.wrapping_mul(i as u64));
                acc[k] = v as u32;
                acc[k + 1] = (v >> 32) as u32;
            }
        } else {
            for (a, step) in acc.iter_mut().zip(&self.step).take(V::LEN) {
                *a = a.wrapping_add(step.wrapping_mul(i as u32));
            }
        }
        Some(acc)
    }
}

/// [`DepthPixels`] for a colour that depends on the screen position ([`FusedColor::AT`]): a
/// type of its own, so that the usual loop carries no position.
struct DepthPixelsAt<'p, P, V, D, const LESS: bool> {
    pixels: DepthPixels<'p, P, V, D, LESS>,
    /// The span's first pixel.
    x: i32,
    y: i32,
}

impl<C, P: FusedColor<C>, V: Varyings, D: DepthTest, const LESS: bool> DepthSpan<C>
    for DepthPixelsAt<'_, P, V, D, LESS>
{
    #[inline(always)]
    fn pixel(&mut self, i: usize, stored: &mut u16) -> Option<C> {
        let acc = self.pixels.values(i, stored, P::PAIRED)?;
        let x = self.x.wrapping_add(i as i32);
        Some(self.pixels.pixel.color_at(&acc, x, self.y))
    }
}

impl<C, P: FusedColor<C>, V: Varyings, D: DepthTest, const LESS: bool> DepthSpan<C>
    for DepthPixels<'_, P, V, D, LESS>
{
    #[inline(always)]
    fn pixel(&mut self, i: usize, stored: &mut u16) -> Option<C> {
        let acc = self.values(i, stored, P::PAIRED)?;
        Some(self.pixel.color(&acc))
    }
}

/// Draws one span's pixels through `$draw`, with `$px` bound to the span's pixel type: the
/// usual depth test (`Less`, known at compile time) or another, and the screen position tracked
/// only for a colour that needs it ([`FusedColor::AT`]).
macro_rules! depth_pixels {
    ($less:expr, $P:ident, $V:ident, $D:ident, $acc:expr, $step:expr, $z:expr, $dz:expr,
     $compare:expr, $pixel:expr, $x:expr, $y:expr, |$px:ident| $draw:expr) => {
        if $less {
            let $px = DepthPixels::<$P, $V, $D, true> {
                acc: $acc,
                step: $step,
                z: $z,
                dz: $dz,
                compare: $compare,
                pixel: $pixel,
                _v: core::marker::PhantomData,
            };
            if $P::AT {
                let $px = DepthPixelsAt {
                    pixels: $px,
                    x: $x,
                    y: $y,
                };
                $draw
            } else {
                $draw
            }
        } else {
            let $px = DepthPixels::<$P, $V, $D, false> {
                acc: $acc,
                step: $step,
                z: $z,
                dz: $dz,
                compare: $compare,
                pixel: $pixel,
                _v: core::marker::PhantomData,
            };
            if $P::AT {
                let $px = DepthPixelsAt {
                    pixels: $px,
                    x: $x,
                    y: $y,
                };
                $draw
            } else {
                $draw
            }
        }
    };
}

/// The span sink of one triangle.
struct Fused<'a, S: Surface + ?Sized, D, V, P> {
    surface: &'a mut S,
    /// The depth buffer's entries, checked to cover the clip area (empty without depth).
    zbuf: &'a mut [u16],
    /// Entries a row, and the screen row of the first.
    zwidth: usize,
    zorigin: i32,
    pixel: P,
    values: [Plane32; MAX_VARYINGS],
    z: Plane32,
    less: bool,
    compare: Compare,
    _v: core::marker::PhantomData<(D, V)>,
}

impl<S, D, V, P> SpanSink for Fused<'_, S, D, V, P>
where
    S: Surface + ?Sized,
    D: DepthTest,
    V: Varyings,
    P: FusedColor<S::Color>,
{
    type Error = S::Error;

    #[inline(always)]
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), S::Error> {
        let n = V::LEN.min(MAX_VARYINGS);
        let mut acc = [0u32; MAX_VARYINGS];
        let mut step = [0u32; MAX_VARYINGS];
        for k in 0..n {
            acc[k] = self.values[k].at(x0, row);
            step[k] = self.values[k].gx;
        }
        let pixel = &self.pixel;
        let len = (x1 - x0) as u32;
        if !D::ENABLED {
            if n == 0 {
                return self
                    .surface
                    .fill_span_in_clip(x0, row, len, pixel.color(&acc));
            }
            if P::AT {
                let mut x = x0;
                return self.surface.shade_span_in_clip(x0, row, len, || {
                    let c = pixel.color_at(&acc, x, row);
                    x = x.wrapping_add(1);
                    for k in 0..n {
                        acc[k] = acc[k].wrapping_add(step[k]);
                    }
                    c
                });
            }
            return self.surface.shade_span_in_clip(x0, row, len, || {
                let c = pixel.color(&acc);
                for k in 0..n {
                    acc[k] = acc[k].wrapping_add(step[k]);
                }
                c
            });
        }
        // In range (the buffer covers the clip area): the check never fails.
        let start = row.wrapping_sub(self.zorigin) as u32 as usize * self.zwidth + x0 as usize;
        let Some(zrow) = self.zbuf.get_mut(start..start + len as usize) else {
            return Ok(());
        };
        let (z, dz, compare) = (self.z.at(x0, row), self.z.gx, self.compare);
        macro_rules! depth_span {
            ($less:literal) => {{
                let pixels = DepthPixels::<P, V, D, $less> {
                    acc,
                    step,
                    z,
                    dz,
                    compare,
                    pixel,
                    _v: core::marker::PhantomData,
                };
                if P::AT {
                    let pixels = DepthPixelsAt {
                        pixels,
                        x: x0,
                        y: row,
                    };
                    self.surface.shade_span_depth_in_clip(x0, row, zrow, pixels)
                } else {
                    self.surface.shade_span_depth_in_clip(x0, row, zrow, pixels)
                }
            }};
        }
        if self.less {
            depth_span!(true)
        } else {
            depth_span!(false)
        }
    }
}

/// The fixed-point scale of a fused triangle's planes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Precision {
    /// Fractional bits of the shader's values.
    pub frac: u32,
    /// Added to each value at a span's start, in units of its last fractional bit.
    pub offset: u32,
}

/// Fractional bits of depth. Always the full 16: fewer would save nothing in 32-bit planes, and
/// the bound that keeps the wrapping values in range needs them on large viewports.
const Z_FRAC: u32 = 16;

/// A screen vertex of the fused path: sub-pixel position, depth (0 nearest) and the shader's
/// values.
pub(crate) type FusedVertex<V, const BITS: u32> = (SubPoint<BITS>, u16, V);

/// Whether the screen triangle `p` (inside the guard band, its bounds holding at most four pixel
/// centres) surely covers no pixel centre of `surface`'s clip area: for a caller that can then
/// skip the values of the triangle's vertices as well as the fill ([`may_cover_a_centre`],
/// conservative: the fill decides the rest exactly). Out of line, so that the loops of its
/// callers compile as without it.
#[inline(never)]
pub(crate) fn misses_every_pixel<S: Surface, const BITS: u32>(
    surface: &S,
    p: &[SubPoint<BITS>; 3],
) -> bool {
    !may_cover_a_centre(p, &PixelRect::from_rectangle(&surface.clip_area()))
}

/// Fills a triangle with a depth test and interpolated values through the fused span loop.
///
/// The shader's values get `P::PRECISION.frac` fractional bits and `P::PRECISION.offset` added
/// (`pixel` receives each pixel's values as `value 2^frac + offset`, wrapping); depth gets 16
/// fractional bits and is rounded down to whole steps, or to the nearest when a vertex lies on
/// the near plane (depth 0), where rounding down could wrap. `area` (not empty) is the
/// rectangle the anchors are kept in: the viewport, the same for every band.
// One copy per pipeline type, called from both the inside and the clipped path: the set-up is
// per triangle, so the call costs little, and the code is not duplicated.
#[inline(never)]
pub(crate) fn fill_fused<S, D, V, P, const BITS: u32>(
    surface: &mut S,
    depth: &mut D,
    vertices: &[FusedVertex<V, BITS>; 3],
    area: &PixelRect,
    pixel: P,
) -> Result<(), S::Error>
where
    S: Surface,
    D: DepthTest,
    V: Varyings,
    P: FusedColor<S::Color>,
{
    if !D::ENABLED {
        let Some((t, Some(rows), clip, mut sink)) =
            set_up::<S, D, V, P, BITS>(surface, depth, vertices, area, pixel, true)
        else {
            return Ok(());
        };
        return walk_spans_once(&t, 1 << BITS, rows, &clip, &mut sink);
    }
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    let compare = depth.comparison();
    let Some(zrows) = depth.depth_rows() else {
        return Ok(());
    };
    surface.shade_triangle_depth_in_clip(FusedTriangle::<D, V, P, BITS> {
        vertices,
        area,
        clip,
        zrows,
        compare,
        pixel,
        _d: core::marker::PhantomData,
    })
}

/// A triangle of [`fill_fused`] with a depth buffer, handed to the surface
/// ([`Surface::shade_triangle_depth_in_clip`]).
struct FusedTriangle<'a, D, V, P, const BITS: u32> {
    vertices: &'a [FusedVertex<V, BITS>; 3],
    area: &'a PixelRect,
    clip: PixelRect,
    zrows: DepthRows<'a>,
    compare: Compare,
    pixel: P,
    _d: core::marker::PhantomData<D>,
}

impl<C, D, V, P, const BITS: u32> DepthTriangle<C> for FusedTriangle<'_, D, V, P, BITS>
where
    D: DepthTest,
    V: Varyings,
    P: FusedColor<C>,
{
    #[inline(always)]
    fn by_spans<S: Surface<Color = C> + ?Sized>(self, surface: &mut S) -> Result<(), S::Error> {
        let clip = self.clip;
        let Some((t, Some(rows), values, z)) =
            planes::<D, V, BITS>(self.vertices, self.area, &clip, P::PRECISION, true)
        else {
            return Ok(());
        };
        let Some((zbuf, zwidth, zorigin)) = depth_entries(self.zrows, &clip) else {
            return Ok(());
        };
        let mut sink = Fused::<S, D, V, P> {
            surface,
            zbuf,
            zwidth,
            zorigin,
            pixel: self.pixel,
            values,
            z,
            less: self.compare == Compare::Less,
            compare: self.compare,
            _v: core::marker::PhantomData,
        };
        walk_spans_once(&t, 1 << BITS, rows, &clip, &mut sink)
    }

    #[inline(always)]
    fn by_words(self, words: &mut [C::Word], stride: usize, y0: i32)
    where
        C: Storage,
    {
        // The lean path needs the depth entries laid out as the words (one index a pixel for
        // both): so they are for a depth buffer the size of the framebuffer or band.
        let Some(lean) = Lean::new(self.vertices, &self.clip) else {
            return;
        };
        let same_layout =
            C::WORD_PER_PIXEL && self.zrows.width as usize == stride && self.zrows.origin_y == y0;
        if same_layout && self.compare == Compare::Less && lean.is_lean(self.area, &self.clip) {
            let off0 = (lean.rows.0 as i32).wrapping_sub(y0) as u32 as usize * stride;
            return lean.draw::<C, D, V, P>(
                self.vertices,
                words,
                self.zrows.depths,
                stride,
                off0,
                &self.pixel,
            );
        }
        by_words_general::<C, D, V, P, BITS>(self, lean, words, stride, y0);
    }
}

/// [`DepthTriangle::by_words`] for the triangles the lean path does not take (columns to clamp,
/// large triangles, an anchor moved into the viewport, a depth test other than `Less`, another
/// layout), span by span: out of line, so that the lean path keeps its registers.
#[inline(never)]
fn by_words_general<C, D, V, P, const BITS: u32>(
    t: FusedTriangle<'_, D, V, P, BITS>,
    lean: Lean<BITS>,
    words: &mut [C::Word],
    stride: usize,
    y0: i32,
) where
    C: Storage,
    D: DepthTest,
    V: Varyings,
    P: FusedColor<C>,
{
    let clip = t.clip;
    let (top, mid, bottom) = lean.rows;
    let sorted = Sorted {
        v: lean.v,
        order: lean.order,
        cross: lean.cross,
    };
    let (values, z) = planes_of::<D, V, BITS, true>(&sorted, t.vertices, t.area, P::PRECISION);
    // Rows outside the depth entries find no slice below; columns beyond them would take
    // another row's, so such a buffer draws nothing (the pipeline refuses a depth buffer that
    // does not cover the viewport, so none does).
    let (zbuf, zwidth, zorigin) = (t.zrows.depths, t.zrows.width as usize, t.zrows.origin_y);
    if clip.x1 > zwidth as i64 {
        return;
    }
    // `walk_spans_once` with its walks set up out of line, the planes set up wide and each
    // pixel's values from the planes at its own position (the same values as the lean path's,
    // to the bit): these triangles are few, and their code is better small.
    let s = 1i64 << BITS;
    let [v0, v1, v2] = sorted.v;
    let mut long = edge_walk(v0, v2, s, top);
    let mut short = if top < mid {
        edge_walk(v0, v1, s, top)
    } else {
        edge_walk(v1, v2, s, mid)
    };
    let short_is_left = sorted.cross < 0;
    let (pixel, compare) = (&t.pixel, t.compare);
    for row in top..bottom {
        if row == mid && top < mid {
            short = edge_walk(v1, v2, s, mid);
        }
        let (l, r) = if short_is_left {
            (short.col(), long.col())
        } else {
            (long.col(), short.col())
        };
        let (x0, x1) = (l.max(clip.x0), r.min(clip.x1));
        // In range (the buffers cover the clip area): the checks never fail.
        let y = row as i32;
        let zstart = y.wrapping_sub(zorigin) as u32 as usize * zwidth;
        let fstart = y.wrapping_sub(y0) as u32 as usize * stride;
        if let (true, Some(zrow), Some(crow)) =
            (x0 < x1, zbuf.get_mut(zstart..), words.get_mut(fstart..))
        {
            for x in x0 as i32..x1 as i32 {
                let Some(stored) = zrow.get_mut(x as usize) else {
                    break;
                };
                let nz = (z.at(x, y) >> Z_FRAC) as u16;
                if !compare.pass(nz, *stored) {
                    continue;
                }
                if D::WRITE {
                    *stored = nz;
                }
                let mut acc = [0u32; MAX_VARYINGS];
                for k in 0..V::LEN.min(MAX_VARYINGS) {
                    acc[k] = values[k].at(x, y);
                }
                let color = if P::AT {
                    pixel.color_at(&acc, x, y)
                } else {
                    pixel.color(&acc)
                };
                C::set(crow, x as usize, color);
            }
        }
        short.step();
        long.step();
    }
}

/// [`EdgeWalk::new`] out of line, for [`by_words_general`].
#[inline(never)]
fn edge_walk(a: (i64, i64), b: (i64, i64), s: i64, row: i64) -> EdgeWalk {
    EdgeWalk::new(a, b, s, row)
}

/// A triangle the lean path of [`DepthTriangle::by_words`] takes: its columns inside the clip
/// area (no span needs clamping), at most [`SMALL_PIXELS`] pixels each way (its edge walks set
/// up in `i32`, [`Edge`], and its edges narrow) and its top vertex's pixel inside the viewport
/// ([`Shape::plane`]'s narrow set-up), with the usual depth test ([`Compare::Less`]), on a
/// framebuffer of one word a pixel whose rows the depth buffer shares. Its planes and walks come from the same formulas as the general path's, so its
/// pixels are the same to the bit.
struct Lean<const BITS: u32> {
    /// The sorted vertices and their permutation.
    v: [(i64, i64); 3],
    order: [usize; 3],
    /// The doubled area, signed (negative when the middle vertex lies left of the long edge).
    cross: i64,
    /// The edges from `v[0]`, times the area's sign.
    e1: (i64, i64),
    e2: (i64, i64),
    /// The rows: `top .. bottom`, the lower half from `mid`.
    rows: (i64, i64, i64),
}

impl<const BITS: u32> Lean<BITS> {
    /// The sorted triangle and its rows inside `clip`, or `None` when nothing is drawn: a
    /// vertex outside the guard band (as [`Sorted::new`] drops it), zero area, or no row of
    /// pixel centres.
    #[inline(always)]
    fn new<V>(vertices: &[FusedVertex<V, BITS>; 3], clip: &PixelRect) -> Option<Self> {
        let s = 1i64 << BITS;
        let p = [vertices[0].0, vertices[1].0, vertices[2].0];
        let order = row_order(&p);
        let v = order.map(|i| (i64::from(p[i].x), i64::from(p[i].y)));
        let [v0, v1, v2] = v;
        let (xmin, xmax) = (v0.0.min(v1.0).min(v2.0), v0.0.max(v1.0).max(v2.0));
        // v0 is the highest vertex, v2 the lowest.
        let band = i64::from(crate::geom::GUARD_BAND_PIXELS) << BITS;
        if xmin < -band || xmax > band || v0.1 < -band || v2.1 > band {
            return None;
        }
        let cross = (v1.0 - v0.0) * (v2.1 - v0.1) - (v2.0 - v0.0) * (v1.1 - v0.1);
        let top = row_at_or_below(v0.1, s).max(clip.y0);
        let mid = row_at_or_below(v1.1, s).clamp(top, clip.y1.max(top));
        let bottom = row_at_or_below(v2.1, s).min(clip.y1);
        if cross == 0 || top >= bottom {
            return None;
        }
        let sign = cross.signum();
        Some(Self {
            v,
            order,
            cross,
            e1: (sign * (v1.0 - v0.0), sign * (v1.1 - v0.1)),
            e2: (sign * (v2.0 - v0.0), sign * (v2.1 - v0.1)),
            rows: (top, mid, bottom),
        })
    }

    /// Whether the lean path takes the triangle (else the general path does): its columns
    /// inside `clip` (the clip area lies inside a framebuffer, below 2^15 pixels), at most
    /// [`SMALL_PIXELS`] pixels each way (every edge walk is then set up in `i32`, [`Edge`], and
    /// the edges are narrow: `2^(6 + BITS) <= 2^(27 - BITS)`), and its top vertex's pixel in
    /// `area`.
    #[inline(always)]
    fn is_lean(&self, area: &PixelRect, clip: &PixelRect) -> bool {
        let s = 1i64 << BITS;
        let [v0, v1, v2] = self.v;
        let (xmin, xmax) = (v0.0.min(v1.0).min(v2.0), v0.0.max(v1.0).max(v2.0));
        let small = SMALL_PIXELS << BITS;
        let own = (v0.0 >> BITS, v0.1 >> BITS);
        xmin >= clip.x0 * s
            && xmax <= clip.x1 * s
            && xmax - xmin <= small
            && v2.1 - v0.1 <= small
            && own.0 >= area.x0
            && own.0 < area.x1
            && own.1 >= area.y0
            && own.1 < area.y1
    }

    /// Draws the triangle: its planes, then its rows; `off0` is the index of its first row's
    /// first word, in `words` and in `zbuf` alike.
    #[inline(always)]
    fn draw<C, D, V, P>(
        self,
        vertices: &[FusedVertex<V, BITS>; 3],
        words: &mut [C::Word],
        zbuf: &mut [u16],
        stride: usize,
        off0: usize,
        pixel: &P,
    ) where
        C: Storage,
        D: DepthTest,
        V: Varyings,
        P: FusedColor<C>,
    {
        let s = 1i64 << BITS;
        let [v0, v1, v2] = self.v;
        if P::HIDDEN_TEST {
            let near = vertices[0]
                .1
                .min(vertices[1].1)
                .min(vertices[2].1)
                .saturating_sub(1);
            // Below the top vertex on the first row: a pixel that shows most visible triangles.
            let probe = zbuf.get(off0.wrapping_add((v0.0 >> BITS) as usize));
            if probe.is_some_and(|&z| z <= near) {
                let ox = v0.0.min(v1.0).min(v2.0) >> BITS;
                let width = ((v0.0.max(v1.0).max(v2.0) >> BITS) - ox + 1) as usize;
                let rows = (self.rows.2 - self.rows.0) as usize;
                if hidden(
                    zbuf,
                    off0.wrapping_add(ox as usize),
                    (width, rows),
                    stride,
                    near,
                ) {
                    return;
                }
            }
        }
        let cross = self.cross.abs();
        let own = (v0.0 >> BITS, v0.1 >> BITS);
        // `cross` is not zero (`Lean::new`).
        let recip = NonZeroU64::new(cross.unsigned_abs()).map_or(Reciprocal::ONE, Reciprocal::new);
        let shape = Shape {
            e1: self.e1,
            e2: self.e2,
            cross,
            recip,
            anchor: own,
            offset2: (2 * (own.0 * s - v0.0) + s, 2 * (own.1 * s - v0.1) + s),
            origin2: (s - 2 * v0.0, s - 2 * v0.1),
            narrow: true,
        };
        let Precision { frac, offset } = P::PRECISION;
        let [o0, o1, o2] = self.order;
        let n = V::LEN.min(MAX_VARYINGS);
        let mut values = [Plane32::default(); MAX_VARYINGS];
        let mut step = [0u32; MAX_VARYINGS];
        for k in 0..n {
            let f = |o: usize| i64::from(vertices[o].2.as_slice()[k]);
            values[k] = shape.plane::<BITS>([f(o0), f(o1), f(o2)], frac, offset);
            step[k] = values[k].gx;
        }
        let z = {
            let f = |o: usize| i64::from(vertices[o].1);
            // As in `planes`.
            let near = vertices.iter().any(|v| v.1 == 0);
            let zoffset = if near { 1 << (Z_FRAC - 1) } else { 0 };
            shape.plane::<BITS>([f(o0), f(o1), f(o2)], Z_FRAC, zoffset)
        };
        let (top, mid, bottom) = self.rows;
        // The walks in `i32`, columns from the leftmost vertex's pixel `ox`: each edge from its
        // upper end, in doubled units from the centre of column `ox` (at least `-s`), and the
        // first row's sample below that end (within the triangle's rows, at most `2 (64 + 1) s`
        // doubled units: the walk's bounds hold, see [`Edge::new`]).
        let ox = v0.0.min(v1.0).min(v2.0) >> BITS;
        let cx = (2 * ox + 1) << BITS;
        let end =
            |p: (i64, i64), row: i64| ((2 * p.0 - cx) as i32, (2 * row * s + s - 2 * p.1) as i32);
        let edge = |p: (i64, i64), q: (i64, i64), row: i64| {
            let (x, y) = end(p, row);
            Edge::<false>::new::<BITS>(x, y, (q.0 - p.0) as i32, (q.1 - p.1) as i32)
        };
        let mut long = edge(v0, v2, top);
        let short_is_left = self.cross < 0;
        // The walks' columns are from `ox` (not negative: inside the clip area).
        let mut off = off0.wrapping_add(ox as usize);
        let oxi = ox as i32;
        let mut row = top;
        // The upper half (when it has rows), then the lower one: one edge set-up in the code
        // for both short edges.
        let mut upper = top < mid;
        loop {
            let (p, q, from, end) = if upper {
                (v0, v1, top, mid)
            } else {
                (v1, v2, mid, bottom)
            };
            let short = edge(p, q, from);
            let (mut l, mut r) = if short_is_left {
                (short, long)
            } else {
                (long, short)
            };
            while row < end {
                let (x0, x1) = (l.col(), r.col());
                if x0 < x1 {
                    // Opaque, so that the planes' products by the row stay products rather than
                    // sums carried from row to row.
                    let y = core::hint::black_box(row) as i32;
                    // Inside the clip area, whose rows both buffers hold: the checks never fail
                    // (the pipeline refuses a depth buffer that does not cover the viewport).
                    let (a, b) = (
                        off.wrapping_add(x0 as u32 as usize),
                        off.wrapping_add(x1 as u32 as usize),
                    );
                    if let (Some(zrow), Some(crow)) = (zbuf.get_mut(a..b), words.get_mut(a..b)) {
                        let x = x0 + oxi;
                        let mut acc = [0u32; MAX_VARYINGS];
                        for k in 0..n {
                            acc[k] = values[k].at(x, y);
                        }
                        let (zx, dz) = (z.at(x, y), z.gx);
                        depth_pixels!(
                            true,
                            P,
                            V,
                            D,
                            acc,
                            step,
                            zx,
                            dz,
                            Compare::Less,
                            pixel,
                            x,
                            y,
                            |pixels| C::shade_depth(crow, 0, zrow, pixels)
                        );
                    }
                }
                off = off.wrapping_add(stride);
                l.step();
                r.step();
                row += 1;
            }
            if !upper || end == bottom {
                return;
            }
            long = if short_is_left { r } else { l };
            upper = false;
        }
    }
}

/// Whether every depth entry of `rows` rows of `width` from index `at` (a triangle's bounding
/// box, one row every `stride`) is at most `near`: every pixel of a triangle none of whose
/// pixels lies nearer than `near` then fails the usual depth test. Out of line, so that the lean
/// path's loop keeps its registers.
#[inline(never)]
fn hidden(
    zbuf: &[u16],
    mut at: usize,
    (width, rows): (usize, usize),
    stride: usize,
    near: u16,
) -> bool {
    for _ in 0..rows {
        match zbuf.get(at..at.wrapping_add(width)) {
            Some(row) if row.iter().all(|&z| z <= near) => {}
            _ => return false,
        }
        at = at.wrapping_add(stride);
    }
    true
}

/// What [`planes`] gives: the sorted triangle, its rows in the clip area ([`rows_in_clip`]), and
/// the planes of its values and of its depth.
type Planes = (
    Sorted,
    Option<(i64, i64, i64)>,
    [Plane32; MAX_VARYINGS],
    Plane32,
);

/// The planes of [`fill_fused`]'s triangle at `precision` (depth's too when `D` is enabled);
/// `None` when nothing is drawn (with `skip_empty`, also for a triangle with no row of pixel
/// centres in `clip`).
#[inline(always)]
fn planes<D, V, const BITS: u32>(
    vertices: &[FusedVertex<V, BITS>; 3],
    area: &PixelRect,
    clip: &PixelRect,
    precision: Precision,
    skip_empty: bool,
) -> Option<Planes>
where
    D: DepthTest,
    V: Varyings,
{
    let t = Sorted::new(&[vertices[0].0, vertices[1].0, vertices[2].0])?;
    let s = 1i64 << BITS;
    // A triangle with no row of centres skips the set-up of its planes. (Testing its columns
    // and its few centres too, as the other fills do, cost more than it saved here: the pipeline
    // has already dropped most triangles that cover no centre.)
    let rows = rows_in_clip(&t, s, clip);
    if skip_empty && rows.is_none() {
        return None;
    }
    let (values, z) = planes_of::<D, V, BITS, false>(&t, vertices, area, precision);
    Some((t, rows, values, z))
}

/// The planes of a sorted triangle of [`fill_fused`] at `precision` (depth's too when `D` is
/// enabled), anchored in `area`. With `WIDE`, every plane takes the wide set-up (the same
/// planes, [`Shape::plane`]): one short copy of the code, for a caller whose triangles are rare.
#[inline(always)]
fn planes_of<D, V, const BITS: u32, const WIDE: bool>(
    t: &Sorted,
    vertices: &[FusedVertex<V, BITS>; 3],
    area: &PixelRect,
    precision: Precision,
) -> ([Plane32; MAX_VARYINGS], Plane32)
where
    D: DepthTest,
    V: Varyings,
{
    let Precision {
        frac: vfrac,
        offset: voffset,
    } = precision;
    let [v0, v1, v2] = t.v;
    let s = 1i64 << BITS;
    let sign = t.cross.signum();
    let e1 = (sign * (v1.0 - v0.0), sign * (v1.1 - v0.1));
    let e2 = (sign * (v2.0 - v0.0), sign * (v2.1 - v0.1));
    let own = (v0.0 >> BITS, v0.1 >> BITS);
    let anchor = (
        own.0.max(area.x0).min(area.x1 - 1),
        own.1.max(area.y0).min(area.y1 - 1),
    );
    let cross = t.cross.abs();
    let narrow = !WIDE && narrow_edges::<BITS>(e1, e2) && anchor == own;
    // `cross` is never zero (`Sorted` drops flat triangles); the wide set-up finds its own.
    let divisor = NonZeroU64::new(cross.unsigned_abs()).filter(|_| narrow);
    let shape = Shape {
        e1,
        e2,
        cross,
        recip: divisor.map_or(Reciprocal::ONE, Reciprocal::new),
        anchor,
        offset2: (2 * (anchor.0 * s - v0.0) + s, 2 * (anchor.1 * s - v0.1) + s),
        origin2: (s - 2 * v0.0, s - 2 * v0.1),
        narrow,
    };
    let [o0, o1, o2] = t.order;
    let n = V::LEN.min(MAX_VARYINGS);
    let mut values = [Plane32::default(); MAX_VARYINGS];
    let plane = |f: [i64; 3], frac: u32, offset: u32| shape.plane::<BITS>(f, frac, offset);
    for (k, p) in values.iter_mut().enumerate().take(n) {
        let f = |o: usize| i64::from(vertices[o].2.as_slice()[k]);
        *p = plane([f(o0), f(o1), f(o2)], vfrac, voffset);
    }
    let z = if D::ENABLED {
        let f = |o: usize| i64::from(vertices[o].1);
        // Rounded down, as the exact interpolator does; a plane that reaches depth 0 at a
        // vertex is rounded to the nearest step, so no pixel wraps below 0.
        let near = vertices.iter().any(|v| v.1 == 0);
        let offset = if near { 1 << (Z_FRAC - 1) } else { 0 };
        plane([f(o0), f(o1), f(o2)], Z_FRAC, offset)
    } else {
        Plane32::default()
    };
    (values, z)
}

/// The depth entries of the whole clip area (entries, entries a row, the first one's screen
/// row), checked here once a triangle rather than per span; `None` when they do not cover it.
/// The pipeline refuses to draw with a depth buffer that does not cover the viewport, so a
/// triangle is never dropped here in practice.
#[inline(always)]
fn depth_entries<'a>(rows: DepthRows<'a>, clip: &PixelRect) -> Option<(&'a mut [u16], usize, i32)> {
    let y0 = i64::from(rows.origin_y);
    let covered = clip.x0 >= 0
        && clip.x1 <= i64::from(rows.width)
        && clip.y0 >= y0
        && clip.y1 <= y0 + i64::from(rows.height);
    covered.then_some((rows.depths, rows.width as usize, rows.origin_y))
}

/// What [`set_up`] gives: the sorted triangle, its rows in the clip area ([`rows_in_clip`]), the
/// clip area and the span sink.
type SetUp<'a, S, D, V, P> = (
    Sorted,
    Option<(i64, i64, i64)>,
    PixelRect,
    Fused<'a, S, D, V, P>,
);

/// [`planes`] and the span sink of a triangle drawn through `surface` span by span.
#[inline(always)]
fn set_up<'a, S, D, V, P, const BITS: u32>(
    surface: &'a mut S,
    depth: &'a mut D,
    vertices: &[FusedVertex<V, BITS>; 3],
    area: &PixelRect,
    pixel: P,
    skip_empty: bool,
) -> Option<SetUp<'a, S, D, V, P>>
where
    S: Surface,
    D: DepthTest,
    V: Varyings,
    P: FusedColor<S::Color>,
{
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    let (t, rows, values, z) =
        planes::<D, V, BITS>(vertices, area, &clip, P::PRECISION, skip_empty)?;
    let compare = depth.comparison();
    let (zbuf, zwidth, zorigin) = if D::ENABLED {
        depth_entries(depth.depth_rows()?, &clip)?
    } else {
        (&mut [][..], 0, 0)
    };
    let sink = Fused::<S, D, V, P> {
        surface,
        zbuf,
        zwidth,
        zorigin,
        pixel,
        values,
        z,
        less: compare == Compare::Less,
        compare,
        _v: core::marker::PhantomData,
    };
    Some((t, rows, clip, sink))
}

/// Fills a triangle with anti-aliased silhouette edges (bit `k` of `mask`, not zero, for the
/// edge from vertex `k` to vertex `k + 1`): with `fringe` false the pixels wholly inside them,
/// with `fringe` true those they cross, blended by their coverage ([`walk_silhouette`]). The
/// triangle is as in [`fill_fused`], its vertices within [`in_aa_range`]; the surface reads
/// back ([`Surface::READ_BACK`]).
#[inline(never)]
pub(crate) fn fill_fused_silhouette<S, D, V, P, const BITS: u32>(
    surface: &mut S,
    depth: &mut D,
    vertices: &[FusedVertex<V, BITS>; 3],
    area: &PixelRect,
    pixel: P,
    mask: u8,
    fringe: bool,
) -> Result<(), S::Error>
where
    S: Surface,
    D: DepthTest,
    V: Varyings,
    P: FusedColor<S::Color>,
{
    let p = vertices.map(|v| (i64::from(v.0.x), i64::from(v.0.y)));
    if !in_aa_range::<BITS>(&p) {
        // Drawn as without anti-aliasing, in the first pass only.
        return if fringe {
            Ok(())
        } else {
            fill_fused::<S, D, V, P, BITS>(surface, depth, vertices, area, pixel)
        };
    }
    let Some((_, _, clip, sink)) =
        set_up::<S, D, V, P, BITS>(surface, depth, vertices, area, pixel, !fringe)
    else {
        return Ok(());
    };
    // Each value's range over the triangle: a crossed pixel's centre may lie outside it, where
    // the planes extrapolate (and may wrap); its values are clamped back into the range.
    let frac = P::PRECISION.frac;
    let n = V::LEN.min(MAX_VARYINGS);
    let mut lo = [0u32; MAX_VARYINGS];
    let mut hi = [0u32; MAX_VARYINGS];
    for k in 0..n {
        let f = |o: usize| vertices[o].2.as_slice()[k];
        let (a, b) = (f(0).min(f(1)).min(f(2)), f(0).max(f(1)).max(f(2)));
        lo[k] = (a as u32) << frac;
        hi[k] = ((b as u32) << frac) | ((1u32 << frac) - 1);
    }
    let zs = vertices.map(|v| u32::from(v.1));
    let mut sink = Silhouette {
        fused: sink,
        lo,
        hi,
        zlo: zs[0].min(zs[1]).min(zs[2]) << Z_FRAC,
        zhi: (zs[0].max(zs[1]).max(zs[2]) << Z_FRAC) | ((1 << Z_FRAC) - 1),
    };
    walk_silhouette::<_, BITS>(&p, mask, fringe, &clip, &mut sink)
}

/// `v` (a plane's wrapping value) as the nearest value of `lo ..= hi`: unwrapped around the
/// range's middle first, so that a value a little outside the range is not taken for one far
/// on its other side.
#[inline(always)]
fn clamp_wrapped(v: u32, lo: u32, hi: u32) -> u32 {
    if lo > hi {
        // Values beyond the documented range: nothing to clamp to.
        return v;
    }
    let mid = lo + (hi - lo) / 2;
    let exact = i64::from(mid) + i64::from(v.wrapping_sub(mid) as i32);
    exact.clamp(i64::from(lo), i64::from(hi)) as u32
}

/// The span sink of a triangle with anti-aliased silhouettes: [`Fused`] for the inner spans,
/// and the blend of each crossed pixel.
struct Silhouette<'a, S: Surface, D, V, P> {
    fused: Fused<'a, S, D, V, P>,
    /// Each value's range over the triangle, and depth's, scaled as the planes.
    lo: [u32; MAX_VARYINGS],
    hi: [u32; MAX_VARYINGS],
    zlo: u32,
    zhi: u32,
}

impl<S, D, V, P> SpanSink for Silhouette<'_, S, D, V, P>
where
    S: Surface,
    D: DepthTest,
    V: Varyings,
    P: FusedColor<S::Color>,
{
    type Error = S::Error;

    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), S::Error> {
        self.fused.span(row, x0, x1)
    }
}

impl<S, D, V, P> FringeSink for Silhouette<'_, S, D, V, P>
where
    S: Surface,
    D: DepthTest,
    V: Varyings,
    P: FusedColor<S::Color>,
{
    fn fringe(&mut self, row: i32, x: i32, coverage: u32) -> Result<(), S::Error> {
        let f = &mut self.fused;
        if D::ENABLED {
            let z = clamp_wrapped(f.z.at(x, row), self.zlo, self.zhi);
            let nz = (z >> Z_FRAC) as u16;
            let i = row.wrapping_sub(f.zorigin) as u32 as usize * f.zwidth + x as usize;
            let Some(stored) = f.zbuf.get_mut(i) else {
                return Ok(());
            };
            if !f.compare.pass(nz, *stored) {
                return Ok(());
            }
            // A pixel at least half covered stands in the depth buffer for the surface, as its
            // centre would without anti-aliasing; a less covered one lets what is drawn later
            // behind it replace it.
            if D::WRITE && coverage >= 1 << 15 {
                *stored = nz;
            }
        }
        let mut acc = [0u32; MAX_VARYINGS];
        for (k, a) in acc.iter_mut().enumerate().take(V::LEN.min(MAX_VARYINGS)) {
            *a = clamp_wrapped(f.values[k].at(x, row), self.lo[k], self.hi[k]);
        }
        let color = if P::AT {
            f.pixel.color_at(&acc, x, row)
        } else {
            f.pixel.color(&acc)
        };
        let alpha = ((coverage * 255 + (1 << 15)) >> 16) as u8;
        match alpha {
            0 => Ok(()),
            255 => f.surface.fill_span_in_clip(x, row, 1, color),
            _ => match f.surface.blend_span_in_clip(x, row, 1, color, alpha) {
                Ok(()) => Ok(()),
                Err(BlendError::Target(e)) => Err(e),
                // The pipeline refuses a surface that cannot read back before it draws.
                Err(BlendError::CannotReadBack) => Ok(()),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{FusedColor, Precision, Shape};
    use crate::raster::triangle::setup::tests::numbers;
    use crate::wide::Reciprocal;
    use core::num::NonZeroU64;

    /// A colour from the pixel's first value, with or without the lean path's hidden-triangle
    /// test.
    struct Red<const HIDDEN: bool>;
    impl<const HIDDEN: bool> FusedColor<embedded_graphics_core::pixelcolor::Rgb565> for Red<HIDDEN> {
        const PRECISION: Precision = Precision {
            frac: 16,
            offset: 1 << 15,
        };
        const HIDDEN_TEST: bool = HIDDEN;
        fn color(
            &self,
            acc: &[u32; crate::geom::MAX_VARYINGS],
        ) -> embedded_graphics_core::pixelcolor::Rgb565 {
            embedded_graphics_core::pixelcolor::Rgb565::new((acc[0] >> 16) as u8 & 31, 0, 0)
        }
    }

    /// The values of a span's pixels stepped in pairs are those stepped one by one while each
    /// pair's low value stays within `0 .. 2^32` (random values, steps of either sign, even and
    /// odd counts of values), and the depth test and stored depths are the same.
    #[test]
    fn paired_values_step_as_single_ones() {
        use super::DepthPixels;
        use crate::depth::{Compare, NoDepth};
        use crate::geom::{Varyings, MAX_VARYINGS};
        fn check<V: Varyings>(next: &mut impl FnMut() -> u32) {
            const LEN: usize = 64;
            let mut acc = [0u32; MAX_VARYINGS];
            let mut step = [0u32; MAX_VARYINGS];
            for k in 0..V::LEN {
                // Low values from 2^24 to 2^32 - 2^24, steps below 2^17 either way: in range
                // over the span. High values anything.
                acc[k] = if k % 2 == 0 {
                    (1 << 24) + next() % (u32::MAX - (1 << 25))
                } else {
                    next()
                };
                step[k] = ((next() % (1 << 18)) as i32 - (1 << 17)) as u32;
            }
            let (z, dz) = (next(), next() % (1 << 20));
            let depths = [0u16; LEN].map(|_| next() as u16);
            let mut stored = [depths; 2];
            let mut pixels = [true, false].map(|_| DepthPixels::<Red<false>, V, NoDepth, true> {
                acc,
                step,
                z,
                dz,
                compare: Compare::Less,
                pixel: &Red::<false>,
                _v: core::marker::PhantomData,
            });
            for i in 0..LEN {
                let [a, b] = &mut stored;
                let [p, q] = &mut pixels;
                let paired = p.values(i, &mut a[i], true);
                let single = q.values(i, &mut b[i], false);
                assert_eq!(paired, single, "{i} {acc:?} {step:?}");
            }
            assert_eq!(stored[0], stored[1]);
        }
        let mut x = 0x2468_ace1u32;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x
        };
        for _ in 0..2_000 {
            check::<[i32; 4]>(&mut next);
            check::<[i32; 3]>(&mut next);
            check::<[i32; 1]>(&mut next);
        }
    }

    /// Random small triangles, many behind others, drawn with and without the hidden-triangle
    /// test: the same colours and depths, while the data holds triangles that draw nothing but
    /// have rows (those the test may drop).
    #[test]
    fn hidden_triangles_are_dropped_without_a_pixel_changing() {
        extern crate std;
        use crate::depth::{Compare, DepthBuffer};
        use crate::geom::{PixelRect, SubPoint};
        use crate::surface::Framebuffer;
        use embedded_graphics_core::pixelcolor::Rgb565;
        use std::vec;
        const BITS: u32 = 6;
        const W: u32 = 64;
        const H: u32 = 48;
        let n = (W * H) as usize;
        let (mut c0, mut c1) = (vec![0u16; n], vec![0u16; n]);
        let (mut z0, mut z1) = (vec![u16::MAX; n], vec![u16::MAX; n]);
        let area = PixelRect {
            x0: 0,
            y0: 0,
            x1: i64::from(W),
            y1: i64::from(H),
        };
        let mut next = numbers(0x41dd_e115);
        let mut silent = 0;
        for t in 0..4000 {
            // Corners within a few pixels of a centre, depths near one another (so that later
            // triangles land on the same depths, a unit nearer or farther, as often as not).
            let (cx, cy) = (next(W) << BITS, next(H) << BITS);
            let base = 30_000 + next(64) as u16;
            let mut corner = || {
                let mut at = |c: i32, size: u32| {
                    (c + next(12 << BITS) - (6 << BITS)).clamp(0, (size << BITS) as i32 - 1)
                };
                let p = SubPoint::<BITS>::raw(at(cx, W), at(cy, H));
                let z = if t % 7 == 0 { 0 } else { base + next(3) as u16 };
                (p, z, [next(1 << 16), 0, 0])
            };
            let v = [corner(), corner(), corner()];
            let before = (c0.clone(), z0.clone());
            {
                let mut fb = Framebuffer::<Rgb565>::new(&mut c0, W, H).unwrap();
                let mut zb = DepthBuffer::new(&mut z0, W, H, Compare::Less).unwrap();
                super::fill_fused::<_, _, _, _, BITS>(&mut fb, &mut zb, &v, &area, Red::<false>)
                    .unwrap();
            }
            {
                let mut fb = Framebuffer::<Rgb565>::new(&mut c1, W, H).unwrap();
                let mut zb = DepthBuffer::new(&mut z1, W, H, Compare::Less).unwrap();
                super::fill_fused::<_, _, _, _, BITS>(&mut fb, &mut zb, &v, &area, Red::<true>)
                    .unwrap();
            }
            assert!(c0 == c1 && z0 == z1, "triangle {t}: {v:?}");
            // What the test relies on: no pixel nearer than the nearest corner less one.
            let near = v.iter().map(|v| v.1).min().unwrap().saturating_sub(1);
            for (new, old) in z0.iter().zip(&before.1) {
                assert!(
                    new == old || *new >= near,
                    "triangle {t}: {v:?}: depth {new}"
                );
            }
            if (c0.clone(), z0.clone()) == before {
                silent += 1;
            }
        }
        // Measured: 2,469 of the 4,000 draw nothing.
        assert!(silent > 1200, "{silent}");
    }

    /// `narrow_edges` is its definition, `|e| <= 2^(27 - BITS)` for every component (and not
    /// `-2^(27 - BITS)`), at its limits and anywhere in the guard band.
    #[test]
    fn narrow_edges_are_the_small_ones() {
        const BITS: u32 = 6;
        let limit = 1i64 << (27 - BITS);
        let def = |e: i64| -limit < e && e <= limit;
        let mut next = numbers(0x5eed_ed9e);
        let near = [
            -limit - 1,
            -limit,
            -limit + 1,
            -1,
            0,
            1,
            limit - 1,
            limit,
            limit + 1,
        ];
        let (mut taken, mut refused) = (0, 0);
        for _ in 0..100_000 {
            let mut pick = || match next(3) {
                0 => near[next(near.len() as u32) as usize],
                1 => i64::from(next(1 << 31)) - (1 << 30),
                _ => i64::from(next(4 * limit as u32)) - 2 * limit,
            };
            let (e1, e2) = ((pick(), pick()), (pick(), pick()));
            let want = def(e1.0) && def(e1.1) && def(e2.0) && def(e2.1);
            assert_eq!(super::narrow_edges::<BITS>(e1, e2), want, "{e1:?} {e2:?}");
            if want {
                taken += 1;
            } else {
                refused += 1;
            }
        }
        assert!(taken > 1000 && refused > 1000, "{taken} {refused}");
    }

    /// The narrow plane's gradients lie within one unit of the exactly rounded ones, toward zero,
    /// within the bound its products rely on, and its value at pixel (0, 0) equals the anchor's
    /// value moved back by whole gradients, to the bit, for any top vertex, anchor on its pixel and
    /// narrow shape.
    #[test]
    fn narrow_plane_start_is_the_anchors_value_moved_back() {
        const BITS: u32 = 6;
        let s = 1i64 << BITS;
        let mut next = numbers(0x0bad_5eed);
        let (mut slivers, mut tried, mut corrected) = (0, 0, 0);
        while tried < 20_000 {
            // Top vertices anywhere in the guard band's reach, edges of every size (small ones
            // for steep gradients).
            let v0 = (
                i64::from(next(1 << 24)) - (1 << 23),
                i64::from(next(1 << 24)) - (1 << 23),
            );
            // (The largest narrow edges too: up to 2^(27 - BITS) either way.)
            let span = [1 << 15, 1 << 8, 8, 1 << (27 - BITS)][next(4) as usize];
            let mut edge = || i64::from(next(2 * span + 1)) - i64::from(span);
            let (e1, e2) = ((edge(), edge()), (edge(), edge()));
            let cross = e1.0 * e2.1 - e2.0 * e1.1;
            if cross <= 0 {
                continue;
            }
            // Slivers (doubled area below 2^BITS) have gradients up to 2^60: the start must
            // still be exact.
            if cross < s {
                slivers += 1;
            }
            tried += 1;
            let anchor = (v0.0 >> BITS, v0.1 >> BITS);
            let shape = Shape {
                e1,
                e2,
                cross,
                recip: Reciprocal::new(NonZeroU64::new(cross as u64).unwrap()),
                anchor,
                offset2: (2 * (anchor.0 * s - v0.0) + s, 2 * (anchor.1 * s - v0.1) + s),
                origin2: (s - 2 * v0.0, s - 2 * v0.1),
                narrow: true,
            };
            // Values anywhere in the contract's range (below 2^(32 - frac)), its ends now and
            // then; 16 fractional bits as the colours and depth, none as the full-word values.
            let (frac, offset) = [(16, 1 << 15), (0, 0)][next(2) as usize];
            let top = 1i64 << (32 - frac);
            let f = [0, 1, 2].map(|_| match next(4) {
                0 => 0,
                1 => top - 1,
                _ => (i64::from(next(1 << 16)) << 16 | i64::from(next(1 << 16))) % top,
            });
            let p = shape.plane::<BITS>(f, frac, offset);
            // The gradients, rounded exactly in i128.
            let (d1, d2) = (f[1] - f[0], f[2] - f[0]);
            let a = d1 * e2.1 - d2 * e1.1;
            let b = d2 * e1.0 - d1 * e2.0;
            let round = |n: i64| {
                ((i128::from(n) << (BITS + frac)) + i128::from(cross / 2))
                    .div_euclid(i128::from(cross)) as i64
            };
            // The plane's gradient is the exactly rounded one or its neighbour toward zero: take
            // that one (its low 32 bits are the plane's) as the reference for the start below.
            let mut near = |exact: i64, got: u32| {
                let toward_zero = exact - exact.signum();
                let g = [exact, toward_zero]
                    .into_iter()
                    .find(|&g| g as u32 == got)
                    .unwrap_or_else(|| panic!("{got} is not {exact} or {toward_zero}"));
                if g != exact {
                    corrected += 1;
                }
                g
            };
            let (gx, gy) = (near(round(a), p.gx), near(round(b), p.gy));
            // |a|, |b| < 2^(60 - BITS - frac), so the rounded quotients stay within 2^60.
            let h = (1i64 << 60) + 1;
            assert!((-h..h).contains(&gx) && (-h..h).contains(&gy));
            let n = i128::from(gx) * i128::from(shape.offset2.0)
                + i128::from(gy) * i128::from(shape.offset2.1);
            let fa = (i128::from(f[0] << frac) + ((n + (1 << BITS)) >> (BITS + 1))) as i64;
            let k = (fa as u32)
                .wrapping_add(offset)
                .wrapping_sub((gx as u32).wrapping_mul(anchor.0 as u32))
                .wrapping_sub((gy as u32).wrapping_mul(anchor.1 as u32));
            assert_eq!(p.k, k, "{v0:?} {e1:?} {e2:?} {f:?}");
            // The wide set-up of the same shape (the general path's) gives the same plane, so
            // that a triangle drawn by either path has the same pixels.
            let wide = Shape {
                narrow: false,
                ..shape
            };
            let q = wide.plane::<BITS>(f, frac, offset);
            assert_eq!(
                (q.k, q.gx, q.gy),
                (p.k, p.gx, p.gy),
                "{v0:?} {e1:?} {e2:?} {f:?}"
            );
        }
        // Both kinds are drawn often, and the gradient one below the exact one too.
        assert!(
            slivers > 100 && tried - slivers > 100,
            "{slivers} slivers of {tried}"
        );
        // (Measured: 666 of the 40,000 gradients one off the exact ones.)
        assert!(corrected > 300, "{corrected} near gradients");
    }
}
