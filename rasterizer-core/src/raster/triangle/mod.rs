//! Triangles: outlines, and fills in flat or Gouraud colour.
//!
//! Fills take vertices in sub-pixel fixed point ([`SubPoint`], 28.4 by default), sample at pixel
//! centres and follow the top-left rule: a centre exactly on an edge is drawn when the triangle lies
//! below a horizontal edge or to the right of any other edge. Two triangles that share an edge
//! therefore never leave a gap between them and never draw a pixel twice, and the coverage matches
//! OpenGL's (checked against Mesa's llvmpipe in the conformance tests). Either winding is drawn.
//!
//! Spans are found by an exact edge walk (`raster/edge.rs`): divisions per edge at set-up, then an
//! add, a test and a conditional subtract per edge per row (one add for a tall flat-filled
//! triangle, whose walk costs two divisions more an edge). A small triangle inside the clip
//! area's columns (`small.rs`, most of a 2D scene's) is set up in 32-bit integers and drawn a
//! run of rows at a time. Zero-area triangles draw nothing; so does a triangle with a vertex
//! outside the guard band ([`crate::geom::GUARD_BAND_PIXELS`]).

pub(crate) mod setup;
pub(crate) mod small;

use crate::color::Channels;
use crate::geom::{PixelRect, SubPoint};
use crate::surface::{BlendError, Surface};
use crate::{geom::line::Line, raster::line::draw_line};
use core::num::NonZeroU64;
use embedded_graphics_core::geometry::Point;
use embedded_graphics_core::Pixel;
use setup::{tall_walks, walk_spans, walk_tall, Sorted, SpanSink, TallWalks};
use small::{RowSink, Small};

/// Fills a triangle in one colour.
///
/// ```
/// use rasterizer_core::{geom::SubPoint, raster::triangle::fill_triangle, surface::Framebuffer};
/// use embedded_graphics_core::{pixelcolor::Rgb565, prelude::*};
///
/// let mut buf = [0u16; 16 * 16];
/// let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 16, 16).unwrap();
/// let px = |x, y| SubPoint::new(x * 16, y * 16);
/// fill_triangle(&mut fb, [px(0, 0), px(16, 0), px(0, 16)], Rgb565::GREEN).unwrap();
/// assert_eq!(fb.pixel(Point::new(0, 0)), Some(Rgb565::GREEN));
/// assert_eq!(fb.pixel(Point::new(15, 15)), Some(Rgb565::BLACK));
/// ```
// Inlined into the caller (a loop over many triangles, mostly): the call and its register
// saves would otherwise cost a small triangle about as much as one of its spans.
#[inline]
pub fn fill_triangle<S: Surface, const BITS: u32>(
    surface: &mut S,
    vertices: [SubPoint<BITS>; 3],
    color: S::Color,
) -> Result<(), S::Error> {
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    if let Some(drawn) = fill_small(surface, &vertices, &clip, color) {
        return drawn;
    }
    fill_large(surface, vertices, color)
}

/// [`fill_triangle`] for a small triangle inside the clip area ([`Small`]); `None` for any
/// other. Out of line in an unoptimised build, so that its locals (both windings' walks) do
/// not sit on the stack under the large triangles' path.
#[cfg_attr(debug_assertions, inline(never))]
#[cfg_attr(not(debug_assertions), inline(always))]
fn fill_small<S: Surface, const BITS: u32>(
    surface: &mut S,
    vertices: &[SubPoint<BITS>; 3],
    clip: &PixelRect,
    color: S::Color,
) -> Option<Result<(), S::Error>> {
    let small = Small::new(vertices, clip)?;
    Some(small.walk::<_, BITS>(&mut FlatShort { surface, color }))
}

/// [`fill_triangle`] for a triangle the `i32` set-up does not take: out of line, so that its
/// two row loops leave the small triangles' code as it was.
#[inline(never)]
fn fill_large<S: Surface, const BITS: u32>(
    surface: &mut S,
    vertices: [SubPoint<BITS>; 3],
    color: S::Color,
) -> Result<(), S::Error> {
    // Found again rather than passed: the small triangles' path then builds none in memory.
    let clip = &PixelRect::from_rectangle(&surface.clip_area());
    if let Some(drawn) = fill_crossing(surface, &vertices, clip, color) {
        return drawn;
    }
    let Some(t) = Sorted::new(&vertices) else {
        return Ok(());
    };
    let s = 1 << BITS;
    // A tall triangle's spans are mostly long, the others' (a short triangle that crosses the
    // clip area's edge, mostly) short: each gets the fill that tests its common case first.
    match tall_walks(&t, s, clip) {
        Some(tall) => fill_tall(surface, &t, tall, color),
        None => walk_spans(&t, s, clip, &mut FlatShort { surface, color }),
    }
}

/// [`fill_large`] for a small triangle across the clip area's edge (most of those that come
/// there): the `i32` set-up, its rows and columns cut; `None` for a larger one. Out of line in
/// an unoptimised build, so that its locals do not sit on the stack under the large triangles'
/// path.
#[cfg_attr(debug_assertions, inline(never))]
#[cfg_attr(not(debug_assertions), inline(always))]
fn fill_crossing<S: Surface, const BITS: u32>(
    surface: &mut S,
    vertices: &[SubPoint<BITS>; 3],
    clip: &PixelRect,
    color: S::Color,
) -> Option<Result<(), S::Error>> {
    let small = Small::crossing(vertices, clip)?;
    Some(small.walk_clipped::<_, BITS>(clip, &mut FlatShort { surface, color }))
}

/// [`fill_large`]'s tall triangles, in a function of their own: the row loops of both walks in
/// one function compiled dearer for each.
#[inline(never)]
fn fill_tall<S: Surface>(
    surface: &mut S,
    t: &Sorted,
    tall: TallWalks,
    color: S::Color,
) -> Result<(), S::Error> {
    walk_tall(t, tall, &mut FlatLong { surface, color })
}

/// A small triangle's spans in one colour: mostly a few pixels long.
struct FlatShort<'a, S: Surface> {
    surface: &'a mut S,
    color: S::Color,
}

impl<S: Surface> SpanSink for FlatShort<'_, S> {
    type Error = S::Error;
    #[inline(always)]
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), S::Error> {
        self.surface
            .fill_short_span_in_clip(x0, row, (x1 - x0) as u32, self.color)
    }
}

impl<S: Surface> RowSink for FlatShort<'_, S> {
    type Error = S::Error;
    const HALVES: bool = true;
    #[inline(always)]
    fn rows<F: FnMut() -> (i32, i32)>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        first: (i32, i32),
        next: F,
    ) -> Result<(), S::Error> {
        self.surface
            .fill_short_rows_in_clip(x, rows, self.color, first, next)
    }
    #[inline(always)]
    fn halves<F: FnMut(bool) -> (i32, i32)>(
        &mut self,
        x: i32,
        rows: (i32, i32, i32),
        first: (i32, i32),
        next: F,
    ) -> Result<(), S::Error> {
        self.surface
            .fill_short_halves_in_clip(x, rows, self.color, first, next)
    }
}

/// A tall triangle's spans in one colour: mostly dozens of pixels long.
struct FlatLong<'a, S: Surface> {
    surface: &'a mut S,
    color: S::Color,
}

impl<S: Surface> SpanSink for FlatLong<'_, S> {
    type Error = S::Error;
    #[inline(always)]
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), S::Error> {
        self.surface
            .fill_long_span_in_clip(x0, row, (x1 - x0) as u32, self.color)
    }
}

/// Blends a triangle in one colour with opacity `alpha` (0 transparent ..= 255 opaque) over what
/// the surface holds: the pixels of [`fill_triangle`], each blended once
/// ([`crate::color::blend`]), so two translucent triangles that share an edge leave no seam.
///
/// ```
/// use rasterizer_core::prelude::*;
/// use rasterizer_core::raster::triangle::fill_triangle_alpha;
///
/// let mut buf = [0u16; 16 * 16];
/// let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 16, 16).unwrap();
/// fb.clear(Rgb565::BLUE).unwrap();
/// let px = |x, y| SubPoint::<4>::new(x * 16, y * 16);
/// fill_triangle_alpha(&mut fb, [px(0, 0), px(16, 0), px(0, 16)], Rgb565::RED, 128).unwrap();
/// assert_eq!(fb.pixel(Point::new(0, 0)), Some(Rgb565::new(16, 0, 15)));
/// ```
///
/// # Errors
/// [`BlendError::CannotReadBack`] (before anything is drawn) for a surface that cannot read back
/// its pixels, such as [`crate::surface::AnyTarget`]; [`BlendError::Target`] for the surface's own.
pub fn fill_triangle_alpha<S: Surface, const BITS: u32>(
    surface: &mut S,
    vertices: [SubPoint<BITS>; 3],
    color: S::Color,
    alpha: u8,
) -> Result<(), BlendError<S::Error>> {
    if !S::READ_BACK {
        return Err(BlendError::CannotReadBack);
    }
    let Some(t) = Sorted::new(&vertices) else {
        return Ok(());
    };
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    let mut sink = Translucent {
        surface,
        color,
        alpha,
    };
    walk_spans(&t, 1 << BITS, &clip, &mut sink)
}

/// Spans blended in one colour.
struct Translucent<'a, S: Surface> {
    surface: &'a mut S,
    color: S::Color,
    alpha: u8,
}

impl<S: Surface> SpanSink for Translucent<'_, S> {
    type Error = BlendError<S::Error>;
    #[inline(always)]
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), Self::Error> {
        self.surface
            .blend_span_in_clip(x0, row, (x1 - x0) as u32, self.color, self.alpha)
    }
}

/// Fractional bits of the interpolated colour channels.
const FRAC: u32 = 16;

/// Fills a triangle with its vertex colours interpolated across it (Gouraud shading).
///
/// Each channel is interpolated at its native depth. The value at a pixel centre is the exact
/// barycentric blend rounded to the nearest step, computed exactly at the start of each span (one
/// division per channel) and stepped across it in 16.16 fixed point, so a pixel whose centre is a
/// vertex gets exactly that vertex's colour, and no pixel leaves the range of the three colours.
pub fn fill_triangle_gouraud<S, const BITS: u32>(
    surface: &mut S,
    vertices: [SubPoint<BITS>; 3],
    colors: [S::Color; 3],
) -> Result<(), S::Error>
where
    S: Surface,
    S::Color: Channels,
{
    match fill_gouraud_small(surface, &vertices, &colors) {
        Some(drawn) => drawn,
        None => fill_gouraud_large(surface, vertices, colors),
    }
}

/// [`fill_triangle_gouraud`] for a small triangle inside the clip area ([`Small`]), when the
/// planes take it; `None` leaves it to [`fill_gouraud_large`]. Out of line in an unoptimised
/// build, so that its locals do not sit on the stack under the large triangles' path.
#[cfg_attr(debug_assertions, inline(never))]
#[cfg_attr(not(debug_assertions), inline(always))]
fn fill_gouraud_small<S, const BITS: u32>(
    surface: &mut S,
    vertices: &[SubPoint<BITS>; 3],
    colors: &[S::Color; 3],
) -> Option<Result<(), S::Error>>
where
    S: Surface,
    S::Color: Channels,
{
    let clip = PixelRect::from_rectangle(&surface.clip_area());
    // The planes start from v0 of `Sorted`'s order (ties broken by x), so the small set-up
    // takes that order too.
    let order = setup::row_order(vertices);
    let p = order.map(|i| (vertices[i].x, vertices[i].y));
    let small = Small::sorted::<BITS>(p, &clip)?;
    let v = small.vertices().map(|(x, y)| (i64::from(x), i64::from(y)));
    let cross = i64::from(small.cross());
    let t = Sorted { v, order, cross };
    if cross == 0 {
        return Some(Ok(()));
    }
    let s: i64 = 1 << BITS;
    // `% 3`: the order is a permutation of 0, 1, 2; the compiler then needs no bounds check.
    let c = [
        colors[order[0] % 3],
        colors[order[1] % 3],
        colors[order[2] % 3],
    ]
    .map(Channels::to_channels);
    // `fill_gouraud_large`'s extents, from the small set-up's bounds.
    let (w, h) = small.size();
    let (ex, ey) = ((2 * w + 2 * s) as u64, (2 * h + 2 * s) as u64);
    let mut planes = Planes::blank(surface, small.origin());
    if !planes.set(&t, s, &c, (ex, ey), cross.signum()) {
        return None;
    }
    Some(small.walk::<_, BITS>(&mut planes))
}

/// [`fill_triangle_gouraud`] for a triangle the small set-up does not take: out of line, so that
/// the small triangles' code stays as it is.
#[inline(never)]
fn fill_gouraud_large<S, const BITS: u32>(
    surface: &mut S,
    vertices: [SubPoint<BITS>; 3],
    colors: [S::Color; 3],
) -> Result<(), S::Error>
where
    S: Surface,
    S::Color: Channels,
{
    let Some(t) = Sorted::new(&vertices) else {
        return Ok(());
    };
    let s: i64 = 1 << BITS;
    let c = t.order.map(|i| colors[i].to_channels());
    let [v0, v1, v2] = t.v;
    // Span starts are pixel centres inside the triangle, so their doubled offsets from v0 are
    // bounded by twice the triangle's extent plus a pixel.
    let (xs, ys) = ([v0.0, v1.0, v2.0], [v0.1, v1.1, v2.1]);
    let extent = |v: [i64; 3]| {
        let (lo, hi) = (v[0].min(v[1]).min(v[2]), v[0].max(v[1]).max(v[2]));
        2 * (hi - lo).unsigned_abs() + 2 * s as u64
    };
    let (ex, ey) = (extent(xs), extent(ys));
    let mut p = Planes::blank(surface, (0, 0));
    if p.set(&t, s, &c, (ex, ey), t.cross.signum()) {
        let clip = PixelRect::from_rectangle(&p.surface.clip_area());
        return match setup::rows_in_clip(&t, s, &clip) {
            Some(rows) => setup::walk_spans_once(&t, s, rows, &clip, &mut p),
            None => Ok(()),
        };
    }
    fill_gouraud_exact(p.surface, &t, &c, s, (ex, ey))
}

/// [`fill_triangle_gouraud`] for a triangle too large for the planes: each span's start exact.
#[inline(always)]
fn fill_gouraud_exact<S: Surface>(
    surface: &mut S,
    t: &Sorted,
    c: &[[u8; 4]; 3],
    s: i64,
    (ex, ey): (u64, u64),
) -> Result<(), S::Error>
where
    S::Color: Channels,
{
    let [v0, v1, v2] = t.v;
    // Bounds, with M = 2^(21 + BITS) <= 2^29 the guard band in raw units: vertex differences
    // <= 2M = 2^30, so den = |cross| <= 2^60 (the doubled area of a triangle inside a square of
    // side 2M) and 2 den <= 2^61.
    let den = t.cross.unsigned_abs();
    let sign = t.cross.signum();
    let mut g = Gouraud {
        surface,
        s,
        v0,
        den,
        den2: NonZeroU64::new(2 * den).unwrap_or(NonZeroU64::MIN),
        a: [0; 4],
        b: [0; 4],
        base: [0; 4],
        step: [0; 4],
        wide: false,
    };
    // One index runs over several per-channel arrays at once.
    #[allow(clippy::needless_range_loop)]
    for i in 0..S::Color::COUNT {
        let (c0, c1, c2) = (i64::from(c[0][i]), i64::from(c[1][i]), i64::from(c[2][i]));
        // The colour plane c = c0 + (a dx2 + b dy2) / (2 den) in doubled offsets from v0, the sign
        // of `cross` moved into the numerators. Bound: |a|, |b| <= 2^8 * 2 * 2M = 2^39.
        g.a[i] = sign * ((c1 - c0) * (v2.1 - v0.1) - (c2 - c0) * (v1.1 - v0.1));
        g.b[i] = sign * ((c2 - c0) * (v1.0 - v0.0) - (c1 - c0) * (v2.0 - v0.0));
        // The rounding of one pixel's step: 2s doubled units, 16 fractional bits. A step too large
        // for i32 only ever lands on spans of one pixel (two centres inside the triangle differ by
        // at most 255), so saturating it is harmless.
        let per_pixel = match g.a[i].checked_mul(s << (FRAC + 1)) {
            Some(n) if n.unsigned_abs() < 1 << 62 => {
                i128::from(crate::wide::div_floor_i64(n + den as i64, 2 * den as i64))
            }
            _ => round_div(crate::wide::mul_i128(g.a[i], s << (FRAC + 1)), den),
        };
        g.step[i] = per_pixel.clamp(i128::from(i32::MIN), i128::from(i32::MAX)) as i32;
        // c0 (2 den) folds the base colour into the numerator, which is then never negative at a
        // pixel inside the triangle. It reaches 2^8 * 2^61 = 2^69, past u64: saturated here, where
        // it only chooses `wide`; the wide path forms it in i128 from c0.
        let base = u64::from(c[0][i]).saturating_mul(g.den2.get());
        g.base[i] = base as i64;
        let bound = g.a[i]
            .unsigned_abs()
            .saturating_mul(ex)
            .saturating_add(g.b[i].unsigned_abs().saturating_mul(ey))
            .saturating_add(base);
        g.wide |= bound >= 1 << 46;
    }
    if g.wide {
        // c0 itself, so that the span set-up stays one size (a larger one costs every span).
        g.base = c[0].map(i64::from);
    }
    let clip = PixelRect::from_rectangle(&g.surface.clip_area());
    // One copy of the row loop, clipped or not, for this large span code: the path of
    // triangles of thousands of pixels, where a row's few instructions more do not count.
    match setup::rows_in_clip(t, s, &clip) {
        Some(rows) => setup::walk_spans_once(t, s, rows, &clip, &mut g),
        None => Ok(()),
    }
}

/// Gouraud spans from colour planes set up once per triangle: each channel's value at a pixel
/// centre is `c0 + (g dx2 + h dy2) / 2^32` in 32.32, with the gradients `g`, `h` per doubled
/// sub-pixel unit rounded once (one reciprocal of the doubled area for all six, its near
/// quotients: within `3/2` of a unit of the exact gradient, never larger in magnitude than the
/// exactly rounded one), so a span starts with two multiplies per channel and no division.
///
/// Taken when the triangle's extents keep both the products in `i64` and the start's error
/// (below `3 (ex + ey) 2^-33` steps from the gradients' rounding) below `3 2^-17` steps, under
/// two units of the 16.16 value: every screen-sized triangle. The start then lies that close to
/// the exact blend, which is what [`Gouraud`]'s exact start gives up to its own rounding.
struct Planes<'a, S: Surface> {
    surface: &'a mut S,
    /// The value in 32.32 at the centre of pixel `origin`, with the halves that the rounding to
    /// 16.16 and `from_fixed16` add folded in, and the gradients per pixel: each wrapping, as
    /// only a value at a pixel inside the triangle (which fits) is ever formed from them.
    base: [i64; PLANE_CHANNELS],
    gx: [i64; PLANE_CHANNELS],
    gy: [i64; PLANE_CHANNELS],
    step: [i32; 4],
    /// The steps in one word, for a colour that packs its channels ([`Channels::PACKED16`]).
    word_step: u64,
    /// The pixel whose value `base` is: pixel (0, 0) for a large triangle, the small walk's
    /// origin for a small one (whose rows then start from it with few products or none).
    origin: (i32, i32),
}

/// A span's steps a pixel: each channel's (16.16), and all of them in one word when the colour
/// packs its channels ([`pack16`]).
type Steps = ([i32; 4], u64);

/// The channels [`Planes`] interpolates: every colour of this crate has at most three (one
/// with four takes the exact path). Three keep the planes under the size a build for size
/// copies with a call to `memcpy`.
const PLANE_CHANNELS: usize = 3;

/// One value a channel of [`Planes`].
type Plane3 = [i64; PLANE_CHANNELS];

/// Channel values (16.16, each within its range or a step) in one word at the colour's
/// [`Channels::PACKED16`] shifts, wrapping (0 for a colour that does not pack them).
#[inline(always)]
fn pack16<C: Channels>(v: [i32; 4]) -> u64 {
    let Some(shift) = C::PACKED16 else {
        return 0;
    };
    // Written out rather than a loop, which a build for size keeps, with its shifts in a table.
    let field = |i: usize| {
        if i < C::COUNT {
            (i64::from(v[i]) as u64).wrapping_shl(shift[i])
        } else {
            0
        }
    };
    field(0)
        .wrapping_add(field(1))
        .wrapping_add(field(2))
        .wrapping_add(field(3))
}

impl<'a, S: Surface> Planes<'a, S>
where
    S::Color: Channels,
{
    /// Planes for `surface` anchored at pixel `origin`, not yet set up ([`Planes::set`]).
    #[inline(always)]
    fn blank(surface: &'a mut S, origin: (i32, i32)) -> Self {
        Self {
            surface,
            base: [0; PLANE_CHANNELS],
            gx: [0; PLANE_CHANNELS],
            gy: [0; PLANE_CHANNELS],
            step: [0; 4],
            word_step: 0,
            origin,
        }
    }

    /// Sets up the planes of triangle `t` with colours `c` (the same order) and doubled extents
    /// `ex`, `ey`; false when they do not take it (then the exact path does). In place, so
    /// that a build for size does not copy the planes with a call to `memcpy`.
    #[inline(always)]
    fn set(
        &mut self,
        t: &Sorted,
        s: i64,
        c: &[[u8; 4]; 3],
        (ex, ey): (u64, u64),
        sign: i64,
    ) -> bool {
        // Within 2^16 doubled units the start's error stays below 3 2^-17 steps.
        if ex + ey > 1 << 16 || S::Color::COUNT > PLANE_CHANNELS {
            return false;
        }
        let den = t.cross.unsigned_abs();
        let Some(den2) = NonZeroU64::new(2 * den) else {
            return false;
        };
        let recip = crate::wide::Reciprocal::new(den2);
        let half = (den2.get() / 2) as i64;
        let fat = reach_bounded(ex, ey, den);
        let [v0, v1, v2] = t.v;
        let origin = self.origin;
        let p = self;
        // The origin pixel's centre in doubled units from v0: pixel (x, y)'s is this plus
        // 2s (x, y) from the origin.
        let (ox, oy) = (
            s - 2 * v0.0 + 2 * s * i64::from(origin.0),
            s - 2 * v0.1 + 2 * s * i64::from(origin.1),
        );
        // One index runs over several per-channel arrays at once.
        #[allow(clippy::needless_range_loop)]
        for i in 0..S::Color::COUNT.min(PLANE_CHANNELS) {
            let (c0, c1, c2) = (i64::from(c[0][i]), i64::from(c[1][i]), i64::from(c[2][i]));
            // The plane's numerators, as for `Gouraud`; |a|, |b| <= 2^8 (ex + ey) <= 2^24 here.
            let a = sign * ((c1 - c0) * (v2.1 - v0.1) - (c2 - c0) * (v1.1 - v0.1));
            let b = sign * ((c2 - c0) * (v1.0 - v0.0) - (c1 - c0) * (v2.0 - v0.0));
            // round(a 2^32 / 2 den) to within one toward zero (`Reciprocal::near`), below 2^57
            // in magnitude.
            let g = recip.near((a << 32) + half);
            let h = recip.near((b << 32) + half);
            // The products at a pixel inside the triangle must fit i64 with the base (up to
            // 2^40): a sliver's gradients can be as large as its colour range over 1/2^BITS.
            if !fat {
                let reach = g
                    .unsigned_abs()
                    .checked_mul(ex)
                    .zip(h.unsigned_abs().checked_mul(ey))
                    .and_then(|(x, y)| x.checked_add(y));
                if reach.is_none_or(|r| r >= 1 << 61) {
                    return false;
                }
            }
            // The value at pixel (x, y) from the origin is (c0 << 32) + g (ox + 2s x) +
            // h (oy + 2s y), which fits i64 inside the triangle; its terms apart may not, hence
            // the wrapping.
            p.base[i] = (c0 << 32)
                .wrapping_add(g.wrapping_mul(ox))
                .wrapping_add(h.wrapping_mul(oy))
                .wrapping_add((1 << 15) + (1 << (FRAC - 1 + 16)));
            p.gx[i] = g.wrapping_mul(2 * s);
            p.gy[i] = h.wrapping_mul(2 * s);
            // A pixel is 2s doubled units: its step in 16.16, saturated as `Gouraud`'s is (a step
            // beyond i32 only lands on one-pixel spans).
            p.step[i] = step16(p.gx[i]);
        }
        p.word_step = pack16::<S::Color>(p.step);
        true
    }
}

/// Whether every channel of a triangle whose doubled extents are `ex`, `ey` (`ex + ey <= 2^16`)
/// and doubled area `den` passes [`Planes::new`]'s reach test, from the triangle alone: a
/// channel's numerators are at most `|a| <= 2^8 ey`, `|b| <= 2^8 ex`, so its gradients at most
/// `|g| <= 2^39 ey / den + 2`, `|h| <= 2^39 ex / den + 2`, and the reach `|g| ex + |h| ey` below
/// `2^40 ex ey / den + 2^17`, under `2^61` when `ex ey < 2^20 den`. No overflow: `ex ey <= 2^32`
/// and `den <= ex ey / 2`.
#[inline(always)]
fn reach_bounded(ex: u64, ey: u64, den: u64) -> bool {
    ex * ey < den << 20
}

/// A gradient per pixel `v` in 32.32 rounded to 16.16 (halves up) and saturated to `i32`.
/// [`Planes::new`]'s `gx` is the exact product `g 2s`: its reach test keeps `|g| ex` below
/// `2^61`, and a doubled extent `ex` is at least `2s`.
#[inline(always)]
fn step16(v: i64) -> i32 {
    // round(v / 2^16): bit 15 is the half, with no add that could overflow.
    ((v >> 16) + ((v >> 15) & 1)).clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// The colours of a span of [`Planes`], over the colour alone (the planes' surface plays no
/// part).
struct PlaneSpan<C>(core::marker::PhantomData<C>);

impl<C: Channels> PlaneSpan<C> {
    /// The colours of the span from pixel `(x, y)` (from the origin) on, left to right.
    ///
    /// The first and third channels share one `i64`, `c0 2^32 + c2`: one add a pixel for both,
    /// exactly, as the third stays in `0 .. 2^32` over a span (in the colour range but for the
    /// stepping error, under half a step, plus the half `from_fixed16` rounds by), and its
    /// step, saturated only where a span has one pixel, is added after that pixel. It also
    /// keeps the compiler from pairing the channels in a vector register, whose 64-bit products
    /// cost more than scalar ones. A channel the colour lacks is zero and its work is dropped.
    /// A colour whose channels all fit one `u64` ([`Channels::PACKED16`], Rgb565 and Bgr565)
    /// steps them all with one add, for the same reason and as exactly.
    #[inline(always)]
    fn pixels(
        (base, gx, gy, step): (&Plane3, &Plane3, &Plane3, Steps),
        y: i64,
        x: i64,
    ) -> impl FnMut() -> C {
        let at = core::array::from_fn(|i| base[i].wrapping_add(gy[i].wrapping_mul(y)));
        Self::pixels_from(&at, gx, step, x)
    }

    /// [`PlaneSpan::pixels`] from the values `at` of a row at the origin's column (in 32.32,
    /// wrapping), the span starting `x` columns right of it.
    #[inline(always)]
    fn pixels_from(
        at: &Plane3,
        gx: &Plane3,
        (step, word_step): Steps,
        x: i64,
    ) -> impl FnMut() -> C {
        // The value in 32.32, rounded to 16.16, plus the half that `from_fixed16` rounds by;
        // inside the triangle it lies within the vertex colours' range (up to 3 2^-17), far
        // inside that half.
        let start = |i: usize| (at[i].wrapping_add(gx[i].wrapping_mul(x)) >> 16) as i32;
        let pair = |hi: i32, lo: i32| (i64::from(hi) << 32).wrapping_add(i64::from(lo));
        let packed = C::PACKED16;
        // All the channels in one word, where they fit: the fields' sum is the word's, as each
        // stays within its field over the span (the first and third's pair below likewise).
        let mut word = pack16::<C>([start(0), start(1), start(2), 0]);
        let step02 = pair(step[0], step[2]);
        let mut a02 = pair(start(0), start(2));
        let mut a1 = start(1);
        move || {
            if packed.is_some() {
                let color = C::from_packed16(word);
                word = word.wrapping_add(word_step);
                return color;
            }
            let acc = [(a02 >> 32) as i32, a1, a02 as i32, 0];
            a02 = a02.wrapping_add(step02);
            a1 = a1.wrapping_add(step[1]);
            C::from_fixed16(&acc)
        }
    }
}

impl<S: Surface> SpanSink for Planes<'_, S>
where
    S::Color: Channels,
{
    type Error = S::Error;

    #[inline(always)]
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), S::Error> {
        let steps = (self.step, self.word_step);
        // From the origin (in i64: a row and column of the clip area lie within i32 of it).
        let (x, y) = (
            i64::from(x0) - i64::from(self.origin.0),
            i64::from(row) - i64::from(self.origin.1),
        );
        let shade = PlaneSpan::pixels((&self.base, &self.gx, &self.gy, steps), y, x);
        self.surface
            .shade_span_in_clip(x0, row, (x1 - x0) as u32, shade)
    }
}

impl<S: Surface> RowSink for Planes<'_, S>
where
    S::Color: Channels,
{
    type Error = S::Error;

    #[inline(always)]
    fn rows<F: FnMut() -> (i32, i32)>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        first: (i32, i32),
        next: F,
    ) -> Result<(), S::Error> {
        // The planes borrowed field by field beside the surface, not copied.
        let Planes {
            surface,
            base,
            gx,
            gy,
            step,
            word_step,
            origin,
        } = self;
        let step = (*step, *word_step);
        // Each channel's value at column `x` of the current row, stepped by a row as the walk
        // moves on: a span's start then takes one product a channel, not two.
        // From the origin: for the small walk, whose origin is its first half's first row and
        // the column of every half, no product at all on that half.
        let (x0, y0) = (
            i64::from(x) - i64::from(origin.0),
            i64::from(rows.start) - i64::from(origin.1),
        );
        let at = core::cell::Cell::new(core::array::from_fn::<i64, PLANE_CHANNELS, _>(|i| {
            base[i]
                .wrapping_add(gx[i].wrapping_mul(x0))
                .wrapping_add(gy[i].wrapping_mul(y0))
        }));
        let mut next = next;
        surface.shade_short_rows_in_clip(
            x,
            rows,
            first,
            || {
                let v = at.get();
                at.set(core::array::from_fn(|i| v[i].wrapping_add(gy[i])));
                next()
            },
            |_, a| PlaneSpan::pixels_from(&at.get(), gx, step, i64::from(a.wrapping_sub(x))),
        )
    }
}

/// The pixels of a Gouraud span: the channels `acc` (16.16, half a step added) packed per pixel
/// and stepped by `step`, for both the plane and the exact span starts.
#[inline(always)]
fn shade_stepped<S: Surface>(
    surface: &mut S,
    row: i32,
    x0: i32,
    x1: i32,
    mut acc: [i32; 4],
    step: [i32; 4],
) -> Result<(), S::Error>
where
    S::Color: Channels,
{
    surface.shade_span_in_clip(x0, row, (x1 - x0) as u32, || {
        let color = S::Color::from_fixed16(&acc);
        for (a, st) in acc.iter_mut().zip(step).take(S::Color::COUNT) {
            *a = a.wrapping_add(st);
        }
        color
    })
}

/// `round(n / (2 den))`, halves up, for `den > 0`.
#[inline]
fn round_div(n: i128, den: u64) -> i128 {
    crate::wide::div_floor_i128(n + i128::from(den), 2 * i128::from(den))
}

/// Gouraud spans: the colour plane evaluated exactly at each span's first pixel, then stepped.
struct Gouraud<'a, S: Surface> {
    surface: &'a mut S,
    s: i64,
    v0: (i64, i64),
    /// |cross|: the plane's divisor is `2 den` in doubled units.
    den: u64,
    /// `2 den`, never zero (the triangle has area).
    den2: NonZeroU64,
    a: [i64; 4],
    b: [i64; 4],
    /// `c0 * 2 den`, or when `wide` only `c0` (the product may pass i64).
    base: [i64; 4],
    step: [i32; 4],
    /// The plane numerators need `i128` (a triangle of millions of pixels).
    wide: bool,
}

impl<S: Surface> SpanSink for Gouraud<'_, S>
where
    S::Color: Channels,
{
    type Error = S::Error;

    #[inline(always)]
    fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), S::Error> {
        // Doubled pixel-centre offsets from v0: exact integers even with no sub-pixel bits.
        let dx2 = (2 * i64::from(x0) + 1) * self.s - 2 * self.v0.0;
        let dy2 = (2 * i64::from(row) + 1) * self.s - 2 * self.v0.1;
        let mut acc = [0i32; 4];
        #[allow(clippy::needless_range_loop)]
        for i in 0..S::Color::COUNT {
            // The exact value at an inside pixel lies in the vertex colours' range, so its 16.16
            // rounding does too: no clamping. Unless `wide`, the numerator is below 2^62 and not
            // negative, and the division is unsigned (no sign or overflow fix-ups). Wide: |dx2|,
            // |dy2| <= 2^31 + 2s at a centre inside the triangle, |a|, |b| < 2^39 and the base
            // below 2^69, so |f| < 2^72 and f 2^16 < 2^88.
            let v = if self.wide {
                // 2 den <= 2^61 (above): an i64.
                let base = crate::wide::mul_i128(self.base[i], self.den2.get() as i64);
                let f = base
                    + crate::wide::mul_i128(self.a[i], dx2)
                    + crate::wide::mul_i128(self.b[i], dy2);
                round_div(f << FRAC, self.den).clamp(0, 255 << FRAC) as i32
            } else {
                let f = self.base[i] + self.a[i] * dx2 + self.b[i] * dy2;
                let n = ((f.max(0) as u64) << FRAC) + self.den;
                crate::wide::div_u64(n, self.den2) as i32
            };
            acc[i] = v + (1 << (FRAC - 1));
        }
        // Within a span the value stays inside the triangle's colour range up to the stepping error
        // (at most 2^-17 per pixel, under 1/2 for any span), so no clamping is needed per pixel.
        shade_stepped(self.surface, row, x0, x1, acc, self.step)
    }
}

/// Draws the outline of a triangle: its three edges as [`crate::raster::line`] lines, each pixel once.
///
/// Pixels shared by two edges (the corners, and more in a thin triangle) are drawn by the first edge
/// only, so a target that counts writes sees every outline pixel exactly once.
pub fn draw_triangle<S: Surface>(
    surface: &mut S,
    vertices: [Point; 3],
    color: S::Color,
) -> Result<(), S::Error> {
    let [p0, p1, p2] = vertices;
    let (l0, l1, l2) = (Line::new(p0, p1), Line::new(p1, p2), Line::new(p2, p0));
    draw_line(surface, p0, p1, color)?;
    let area = surface.clip_area();
    if let Some(points) = l1.clipped(&area) {
        surface.draw_iter(points.filter(|p| !l0.contains(*p)).map(|p| Pixel(p, color)))?;
    }
    if let Some(points) = l2.clipped(&area) {
        let fresh = points.filter(|p| !l0.contains(*p) && !l1.contains(*p));
        surface.draw_iter(fresh.map(|p| Pixel(p, color)))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::raster::edge::tests::xorshift as rng;

    #[test]
    fn step16_is_the_rounded_saturated_product() {
        let mut next = rng(0x9e37_79b9_7f4a_7c15);
        let reference = |g: i64, two_s: i64| {
            let v = (i128::from(g) * i128::from(two_s) + (1 << 15)) >> 16;
            v.clamp(i128::from(i32::MIN), i128::from(i32::MAX)) as i32
        };
        for two_s in [2i64, 32, 512] {
            // The largest gradients the bound allows, |g| two_s < 2^63.
            let top = (i64::MAX / two_s) as u64 + 1;
            let edges = [
                0,
                1,
                -1,
                1 << 15,
                -(1 << 15),
                1 << 47,
                top as i64 - 1,
                1 - top as i64,
            ];
            for &g in &edges {
                assert_eq!(step16(g * two_s), reference(g, two_s), "{g} {two_s}");
            }
            for _ in 0..100_000 {
                let g = (next() % top) as i64 >> (next() % 64);
                let g = if next() & 1 == 0 { g } else { -g };
                assert_eq!(step16(g * two_s), reference(g, two_s), "{g} {two_s}");
            }
        }
    }

    /// Spans of every length up to 65 pixels with random starts and steps that keep each
    /// channel within its range over the span (as inside a triangle): the pixels a packed word
    /// steps (Rgb565, Bgr565) are those of each channel stepped on its own in `i32` and cut to
    /// its integer part, the reference.
    fn packed_spans_match_channels<C: Channels + PartialEq + core::fmt::Debug>() {
        let mut next = rng(0x1319_8a2e_0370_7344);
        let max = [31i64, 63, 31];
        for _ in 0..50_000 {
            let len = 1 + (next() % 65) as i64;
            let mut start = [0i32; 4];
            let mut step = [0i32; 4];
            for c in 0..3 {
                let top = (max[c] + 1) << 16;
                // Two values in range, the span's first and last: the step between them,
                // rounded down, keeps every pixel between them.
                let (a, b) = ((next() % top as u64) as i64, (next() % top as u64) as i64);
                let d = if len > 1 {
                    (b - a).div_euclid(len - 1)
                } else {
                    0
                };
                start[c] = a as i32;
                step[c] = d as i32;
            }
            let at = [0, 1, 2].map(|c| i64::from(start[c]) << 16);
            let steps = (step, pack16::<C>(step));
            let mut shade = PlaneSpan::<C>::pixels_from(&at, &[0; 3], steps, 0);
            for k in 0..len as i32 {
                let v = [0, 1, 2].map(|c| (start[c] + k * step[c]) >> 16);
                let want = C::from_channels_in_range([v[0] as u8, v[1] as u8, v[2] as u8, 0]);
                assert_eq!(shade(), want, "{start:?} {step:?} pixel {k}");
            }
        }
    }

    #[test]
    fn packed_spans_match_channels_rgb565() {
        packed_spans_match_channels::<embedded_graphics_core::pixelcolor::Rgb565>();
    }

    #[test]
    fn packed_spans_match_channels_bgr565() {
        packed_spans_match_channels::<embedded_graphics_core::pixelcolor::Bgr565>();
    }

    /// Random triangles inside the planes' extent limit (many of them slivers) and colours:
    /// whenever `reach_bounded` holds, every channel's reach, formed as `Planes::new` forms it
    /// from exactly rounded gradients (in i128 here), is below 2^61: the near quotients it uses
    /// are never larger in magnitude, see `wide`'s `reciprocal_quotients_lie_next_to_the_floor`.
    #[test]
    fn reach_bounded_implies_every_channel_in_reach() {
        let mut next = rng(0x2545_f491_4f6c_dd1d);
        let (mut held, mut failed) = (0, 0);
        for _ in 0..200_000 {
            let bits = [0, 4, 8][(next() % 3) as usize];
            let s = 1i64 << bits;
            let side = 1 + (next() % (1 << 14)) as i64;
            let mut v = [(0i64, 0i64); 3]
                .map(|_| ((next() % side as u64) as i64, (next() % side as u64) as i64));
            match next() % 3 {
                // A sliver: the third vertex on or next to the line through the first two.
                0 => {
                    let t = (next() % 64) as i64;
                    v[2] = (
                        v[0].0 + (v[1].0 - v[0].0) * t / 63,
                        v[0].1 + (v[1].1 - v[0].1) * t / 63,
                    );
                    v[2].0 += (next() % 3) as i64 - 1;
                }
                // The thinnest: (k, k + 1) and (k + 1, k + 2) from v0 span a doubled area of 1.
                1 => {
                    let k = (next() % (side as u64 / 2 + 1)) as i64;
                    v[1] = (v[0].0 + k, v[0].1 + k + 1);
                    v[2] = (v[0].0 + k + 1, v[0].1 + k + 2);
                }
                _ => {}
            }
            v.sort_by_key(|p| (p.1, p.0));
            let [v0, v1, v2] = v;
            let cross = (v1.0 - v0.0) * (v2.1 - v0.1) - (v2.0 - v0.0) * (v1.1 - v0.1);
            let extent = |a: i64, b: i64, c: i64| {
                2 * (a.max(b).max(c) - a.min(b).min(c)).unsigned_abs() + 2 * s as u64
            };
            let (ex, ey) = (extent(v0.0, v1.0, v2.0), extent(v0.1, v1.1, v2.1));
            if cross == 0 || ex + ey > 1 << 16 {
                continue;
            }
            let den = cross.unsigned_abs();
            if !reach_bounded(ex, ey, den) {
                failed += 1;
                continue;
            }
            held += 1;
            let c = [0; 3].map(|_| (next() % 256) as i64);
            let sign = cross.signum();
            let a = sign * ((c[1] - c[0]) * (v2.1 - v0.1) - (c[2] - c[0]) * (v1.1 - v0.1));
            let b = sign * ((c[2] - c[0]) * (v1.0 - v0.0) - (c[1] - c[0]) * (v2.0 - v0.0));
            let round = |n: i64| {
                (i128::from(n) * (1 << 32) + i128::from(den)).div_euclid(2 * i128::from(den))
            };
            let reach = round(a).abs() * i128::from(ex) + round(b).abs() * i128::from(ey);
            assert!(reach < 1 << 61, "{v:?} {c:?}");
        }
        // Both ways taken often (measured: 145,307 and 53,692).
        assert!(held > 70_000 && failed > 25_000, "{held} {failed}");
    }
}
