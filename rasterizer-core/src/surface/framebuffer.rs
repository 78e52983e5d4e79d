//! A framebuffer over a caller-provided slice, in the layouts display drivers and DMA engines expect.
//!
//! Rows are stored top to bottom with no padding between them (except the bit padding of
//! [`BinaryColor`] rows). Spans become `slice::fill` or a tight loop; line walks step a buffer index
//! instead of recomputing `y * width + x` per pixel.

use super::{BlendError, DepthSpan, DepthTriangle, Surface};
use crate::color::{blend, blend_channel, Channels};
use crate::geom::line::LinePoints;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Point, Size};
use embedded_graphics_core::pixelcolor::raw::{RawData, RawU16};
use embedded_graphics_core::pixelcolor::{BinaryColor, Gray8, GrayColor, Rgb565, Rgb888, RgbColor};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

/// The largest width or height of a [`Framebuffer`], in pixels.
///
/// It keeps every row index and span end well inside `i32`, and the triangle set-up bound of
/// [`crate::geom::GUARD_BAND_PIXELS`] assumes screens no larger than this.
pub const MAX_DIMENSION: u32 = 32_767;

/// Why a [`Framebuffer`] could not be made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FramebufferError {
    /// The slice does not have the length this size and pixel format need.
    WrongLength {
        /// Words the size needs.
        expected: usize,
        /// Words the slice has.
        actual: usize,
    },
    /// Width or height is zero or larger than [`MAX_DIMENSION`], or (on a 16-bit target) the
    /// buffer's length overflows `usize`.
    BadSize {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
}

impl core::fmt::Display for FramebufferError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::WrongLength { expected, actual } => {
                write!(
                    f,
                    "framebuffer slice has {actual} words, the size needs {expected}"
                )
            }
            Self::BadSize { width, height } => write!(
                f,
                "framebuffer size {width}x{height} is outside 1..={MAX_DIMENSION} in each axis"
            ),
        }
    }
}

impl core::error::Error for FramebufferError {}

/// How a colour type is stored in a [`Framebuffer`].
///
/// Implemented for [`Rgb565`] (one `u16` per pixel, the raw embedded-graphics value), [`Rgb888`]
/// (three bytes per pixel, red first), [`Gray8`] (one byte per pixel) and [`BinaryColor`] (one bit
/// per pixel, each row padded to whole bytes, the leftmost pixel in the most significant bit, as
/// monochrome OLED and e-paper firmware stores it).
///
/// Every stored format can be read back, so [`Channels`] is required: it is how a
/// [`Framebuffer`] blends ([`Surface::blend_span_in_clip`]).
pub trait Storage: Channels {
    /// The element type of the slice.
    type Word: Copy + core::fmt::Debug;
    /// Each pixel is one word (`row_words(w) == w`): a span's words are its pixels.
    const WORD_PER_PIXEL: bool = false;
    /// Words one row of `width` pixels takes.
    fn row_words(width: usize) -> usize;
    /// Sets pixel `x` of a row.
    fn set(row: &mut [Self::Word], x: usize, color: Self);
    /// Reads pixel `x` of a row.
    fn get(row: &[Self::Word], x: usize) -> Self;
    /// Fills pixels `x .. x + len` of a row.
    fn fill(row: &mut [Self::Word], x: usize, len: usize, color: Self) {
        for i in x..x + len {
            Self::set(row, i, color);
        }
    }
    /// Sets pixels `x .. x + len` of a row to the colours `shade` yields, left to right.
    #[inline]
    fn shade<F: FnMut() -> Self>(row: &mut [Self::Word], x: usize, len: usize, mut shade: F) {
        for i in x..x + len {
            Self::set(row, i, shade());
        }
    }
    /// Sets pixels `x ..` of a row, one for each entry of `depth`, to the colours `shade` returns
    /// for them (`None` leaves a pixel as it is), left to right.
    #[inline(always)]
    fn shade_depth<F: DepthSpan<Self>>(
        row: &mut [Self::Word],
        x: usize,
        depth: &mut [u16],
        mut shade: F,
    ) {
        for (i, d) in depth.iter_mut().enumerate() {
            if let Some(c) = shade.pixel(i, d) {
                Self::set(row, x + i, c);
            }
        }
    }
    /// [`Storage::shade_depth`] on the row that starts at word `row` of the whole buffer.
    #[inline(always)]
    fn shade_depth_at<F: DepthSpan<Self>>(
        buf: &mut [Self::Word],
        row: usize,
        x: usize,
        depth: &mut [u16],
        shade: F,
    ) {
        Self::shade_depth(&mut buf[row..], x, depth, shade);
    }
    /// Fills pixels `x .. x + len` of row `y` of the whole buffer (`stride` words per row).
    #[inline]
    fn fill_span(
        buf: &mut [Self::Word],
        stride: usize,
        x: usize,
        y: usize,
        len: usize,
        color: Self,
    ) {
        Self::fill(&mut buf[y * stride..(y + 1) * stride], x, len, color);
    }
    /// [`Storage::fill_span`] for a span that is most likely dozens of pixels long.
    #[inline(always)]
    fn fill_long_span(
        buf: &mut [Self::Word],
        stride: usize,
        x: usize,
        y: usize,
        len: usize,
        color: Self,
    ) {
        Self::fill_span(buf, stride, x, y, len, color);
    }
    /// [`Storage::fill_span`] for a span that is most likely a few pixels long.
    #[inline(always)]
    fn fill_short_span(
        buf: &mut [Self::Word],
        stride: usize,
        x: usize,
        y: usize,
        len: usize,
        color: Self,
    ) {
        Self::fill_span(buf, stride, x, y, len, color);
    }
    /// Fills one span a row on `rows` rows from row `y` down, the spans mostly a few pixels
    /// long, as [`Surface::fill_short_rows_in_clip`] (`first`, then `next` for each further
    /// row).
    #[inline(always)]
    fn fill_short_rows<F: FnMut() -> (i32, i32)>(
        buf: &mut [Self::Word],
        stride: usize,
        x: usize,
        (y, rows): (usize, usize),
        color: Self,
        (mut a, mut b): (i32, i32),
        mut next: F,
    ) {
        for i in 0..rows {
            if i > 0 {
                (a, b) = next();
            }
            if a < b {
                let (a, b) = (a as usize, b as usize);
                Self::fill_short_span(buf, stride, x + a, y + i, b - a, color);
            }
        }
    }
    /// [`Storage::fill_short_rows`] for the two halves of a small triangle, as
    /// [`Surface::fill_short_halves_in_clip`]: `rows` are the first row and the numbers of rows
    /// in the upper and the lower half.
    #[inline(always)]
    fn fill_short_halves<F: FnMut(bool) -> (i32, i32)>(
        buf: &mut [Self::Word],
        stride: usize,
        x: usize,
        (y, upper, lower): (usize, usize, usize),
        color: Self,
        first: (i32, i32),
        mut next: F,
    ) {
        if upper > 0 {
            Self::fill_short_rows(buf, stride, x, (y, upper), color, first, || next(false));
        }
        if lower > 0 {
            let first = if upper > 0 { next(true) } else { first };
            Self::fill_short_rows(buf, stride, x, (y + upper, lower), color, first, || {
                next(false)
            });
        }
    }
    /// [`Storage::fill_short_rows`] with each span's colours from a shader, as
    /// [`Surface::shade_short_rows_in_clip`].
    #[inline(always)]
    fn shade_short_rows<F, G, P>(
        buf: &mut [Self::Word],
        stride: usize,
        x: usize,
        (y, rows): (usize, usize),
        (mut a, mut b): (i32, i32),
        mut next: F,
        mut span: G,
    ) where
        F: FnMut() -> (i32, i32),
        G: FnMut(i32, i32) -> P,
        P: FnMut() -> Self,
    {
        for i in 0..rows {
            if i > 0 {
                (a, b) = next();
            }
            if a < b {
                let (row, x0) = ((y + i) as i32, (x as i32).wrapping_add(a));
                let start = (y + i) * stride;
                let (a, b) = (a as usize, b as usize);
                Self::shade(&mut buf[start..start + stride], x + a, b - a, span(row, x0));
            }
        }
    }

    /// Blends `color` with opacity `alpha` over pixels `x .. x + len` of a row
    /// ([`crate::color::blend`]).
    #[inline]
    fn blend(row: &mut [Self::Word], x: usize, len: usize, color: Self, alpha: u8) {
        for i in x..x + len {
            let dst = Self::get(row, i);
            Self::set(row, i, blend(color, dst, alpha));
        }
    }
    /// Draws pixels `x .. x + len` of a row with the colours and opacities `shade` yields, left
    /// to right: 255 stores, 0 skips, others blend ([`crate::color::blend`]).
    #[inline(always)]
    fn blend_shade<F: FnMut() -> (Self, u8)>(
        row: &mut [Self::Word],
        x: usize,
        len: usize,
        mut shade: F,
    ) {
        for i in x..x + len {
            match shade() {
                (c, 255) => Self::set(row, i, c),
                (_, 0) => {}
                (c, a) => {
                    let dst = Self::get(row, i);
                    Self::set(row, i, blend(c, dst, a));
                }
            }
        }
    }
    /// Walks a line through the whole buffer (`stride` words per row); every point is in bounds.
    fn walk(buf: &mut [Self::Word], stride: usize, points: LinePoints, color: Self) {
        for p in points {
            let row = p.y as usize * stride;
            Self::set(&mut buf[row..row + stride], p.x as usize, color);
        }
    }
}

/// Walks a line through the whole buffer (`stride` words per row), for formats with one word per
/// pixel. Every pixel of the walk lies in the buffer.
///
/// No pixel is counted: an x-major line is drawn as one run per row, which a carry of the
/// Bresenham remainder ends (the rows are counted, and the last row's run is a plain fill); a
/// y-major line steps a strictly increasing index through the buffer cut just after its last
/// pixel, so the store's bounds check is also the loop's exit. Any inconsistent walk still ends
/// without a write outside the buffer: the rows are counted, a run stops at the buffer's end, and
/// the y-major index grows by at least one word a step.
#[inline]
fn walk_words<W: Copy>(buf: &mut [W], stride: usize, p: LinePoints, value: W) {
    let Some((ex, ey)) = p.last_pixel().filter(|_| stride > 0) else {
        return;
    };
    let (x, y, ex, ey) = (p.x as usize, p.y as usize, ex as usize, ey as usize);
    let (two_a, two_b) = (p.two_major, p.two_minor);
    // The remainder biased by -2A: the carry test becomes a sign test on the sum just computed.
    let mut err = p.err - two_a;
    let last = ey.wrapping_mul(stride).wrapping_add(ex);
    let mut idx = y.wrapping_mul(stride).wrapping_add(x);
    if p.major_x {
        let row_step = if p.step_y < 0 {
            stride.wrapping_neg()
        } else {
            stride
        };
        for _ in 0..y.abs_diff(ey) {
            // A row's run: the walk stays in the row until a carry moves it to the next one.
            loop {
                let Some(w) = buf.get_mut(idx) else {
                    return;
                };
                *w = value;
                idx += 1;
                err += two_b;
                if err >= 0 {
                    break;
                }
            }
            err -= two_a;
            idx = idx.wrapping_add(row_step);
        }
        if let Some(run) = buf.get_mut(idx..=last) {
            fill_words(run, value);
        }
    } else {
        // The index grows at each step: cut just after the last pixel, the buffer ends the walk.
        let Some(s) = buf.get_mut(..=last) else {
            return;
        };
        // In a one-word-wide buffer no pixel of the walk can move sideways; a zero minor step keeps
        // the index strictly increasing there too.
        let minor = if stride > 1 { p.step_x as isize } else { 0 };
        // Two loops, one after a step without a carry and one after a step with, so that the carry
        // is a branch between them rather than selects on every pixel.
        loop {
            let Some(w) = s.get_mut(idx) else {
                return;
            };
            *w = value;
            idx = idx.wrapping_add(stride);
            err += two_b;
            while err >= 0 {
                err -= two_a;
                idx = idx.wrapping_add_signed(minor);
                let Some(w) = s.get_mut(idx) else {
                    return;
                };
                *w = value;
                idx = idx.wrapping_add(stride);
                err += two_b;
            }
        }
    }
}

/// Stores `v` in every word of `s` with wide stores: whole groups of 128 words (64, 32 or 8 for
/// shorter spans), then one group that ends exactly at the end of the span and may overlap the
/// last whole group (harmless: it stores the same value). Spans of fewer than 8 words use two
/// overlapping groups of 4, or single stores, and are tested first (most of a small triangle's).
/// Measured against `slice::fill`, whose scalar tail dominated spans of a few dozen pixels; the
/// large groups keep the compiler from unrolling a loop of small ones behind a remainder loop,
/// whose set-up cost a span of about a hundred pixels more than its stores.
#[inline(always)]
fn fill_words<W: Copy>(s: &mut [W], v: W) {
    if s.len() < 8 {
        if s.len() >= 4 {
            fill_groups::<W, 4>(s, v);
        } else if !s.is_empty() {
            fill_one_to_three(s, v);
        }
    } else if s.len() >= 128 {
        fill_groups::<W, 128>(s, v);
    } else if s.len() >= 64 {
        fill_groups::<W, 64>(s, v);
    } else if s.len() >= 32 {
        fill_groups::<W, 32>(s, v);
    } else {
        fill_groups::<W, 8>(s, v);
    }
}

/// [`fill_words`] for a span of at least `N` words: its whole groups of `N`, then the group that
/// ends at its end.
#[inline(always)]
fn fill_groups<W: Copy, const N: usize>(s: &mut [W], v: W) {
    let (groups, _) = s.as_chunks_mut::<N>();
    for g in groups {
        g.fill(v);
    }
    if let Some(last) = s.last_chunk_mut::<N>() {
        last.fill(v);
    }
}

/// [`fill_words`] with the long spans tested first: for the spans of a large triangle, mostly
/// dozens of words long.
#[inline(always)]
fn fill_long_words<W: Copy>(s: &mut [W], v: W) {
    if s.len() >= 128 {
        fill_groups::<W, 128>(s, v);
    } else if s.len() >= 64 {
        fill_groups::<W, 64>(s, v);
    } else {
        fill_words(s, v);
    }
}

/// Fills the span `at + a .. at + b` of `buf`, if any (`a`, `b` never negative), as
/// [`fill_short_words`].
#[inline(always)]
fn fill_short_at<W: Copy>(buf: &mut [W], at: u32, (a, b): (i32, i32), v: W) {
    if a < b {
        // Zero-extended, so that neither sum can wrap.
        let start = at.wrapping_add(a as u32) as usize;
        let len = b.wrapping_sub(a) as u32 as usize;
        fill_short_words(&mut buf[start..start + len], v);
    }
}

/// Fills one to three words: first, last and middle cover them all with no loop.
#[inline(always)]
fn fill_one_to_three<W: Copy>(s: &mut [W], v: W) {
    let (last, mid) = (s.len() - 1, s.len() / 2);
    s[0] = v;
    s[last] = v;
    s[mid] = v;
}

/// [`fill_words`] with spans of one to three words tested first: cheaper for a small triangle's
/// spans, dearer by two tests for long ones.
#[inline(always)]
fn fill_short_words<W: Copy>(s: &mut [W], v: W) {
    // One test for 1 ..= 3 (an empty span wraps round to a large value).
    if s.len().wrapping_sub(1) < 3 {
        fill_one_to_three(s, v);
    } else if s.len() < 8 {
        fill_ends::<W, 4>(s, v);
    } else if s.len() <= 16 {
        fill_ends::<W, 8>(s, v);
    } else {
        fill_words(s, v);
    }
}

/// Fills `N ..= 2 N` words with two groups of `N` that overlap, without the loop the compiler
/// may make of [`fill_groups`].
#[inline(always)]
fn fill_ends<W: Copy, const N: usize>(s: &mut [W], v: W) {
    if let Some(first) = s.first_chunk_mut::<N>() {
        first.fill(v);
    }
    if let Some(last) = s.last_chunk_mut::<N>() {
        last.fill(v);
    }
}

impl Storage for Rgb565 {
    type Word = u16;
    const WORD_PER_PIXEL: bool = true;
    fn row_words(width: usize) -> usize {
        width
    }
    #[inline]
    fn set(row: &mut [u16], x: usize, color: Self) {
        row[x] = RawU16::from(color).into_inner();
    }
    #[inline]
    fn get(row: &[u16], x: usize) -> Self {
        RawU16::new(row[x]).into()
    }
    #[inline]
    fn fill(row: &mut [u16], x: usize, len: usize, color: Self) {
        fill_words(&mut row[x..x + len], RawU16::from(color).into_inner());
    }
    #[inline(always)]
    fn fill_span(buf: &mut [u16], stride: usize, x: usize, y: usize, len: usize, color: Self) {
        let start = y * stride + x;
        fill_words(
            &mut buf[start..start + len],
            RawU16::from(color).into_inner(),
        );
    }
    #[inline(always)]
    fn fill_long_span(buf: &mut [u16], stride: usize, x: usize, y: usize, len: usize, color: Self) {
        let start = y * stride + x;
        fill_long_words(
            &mut buf[start..start + len],
            RawU16::from(color).into_inner(),
        );
    }
    #[inline(always)]
    fn fill_short_span(
        buf: &mut [u16],
        stride: usize,
        x: usize,
        y: usize,
        len: usize,
        color: Self,
    ) {
        let start = y * stride + x;
        fill_short_words(
            &mut buf[start..start + len],
            RawU16::from(color).into_inner(),
        );
    }
    #[inline(always)]
    fn fill_short_rows<F: FnMut() -> (i32, i32)>(
        buf: &mut [u16],
        stride: usize,
        x: usize,
        (y, rows): (usize, usize),
        color: Self,
        first: (i32, i32),
        mut next: F,
    ) {
        Self::fill_short_halves(buf, stride, x, (y, rows, 0), color, first, |_| next());
    }
    #[inline(always)]
    fn fill_short_halves<F: FnMut(bool) -> (i32, i32)>(
        buf: &mut [u16],
        stride: usize,
        x: usize,
        (y, upper, lower): (usize, usize, usize),
        color: Self,
        (mut a, mut b): (i32, i32),
        mut next: F,
    ) {
        let v = RawU16::from(color).into_inner();
        // The offset of column `x` of each row, stepped by the stride from one half into the
        // other: no product a span. A buffer holds fewer than 2^32 words (`MAX_DIMENSION`), so
        // the offsets are `u32`, and a span's start and length zero-extended cannot wrap: one
        // range check a span.
        let mut at = (y as u32)
            .wrapping_mul(stride as u32)
            .wrapping_add(x as u32);
        if upper > 0 {
            let mut left = upper;
            loop {
                fill_short_at(buf, at, (a, b), v);
                at = at.wrapping_add(stride as u32);
                left -= 1;
                if left == 0 {
                    break;
                }
                (a, b) = next(false);
            }
            if lower == 0 {
                return;
            }
            (a, b) = next(true);
        }
        let mut left = lower;
        loop {
            fill_short_at(buf, at, (a, b), v);
            left -= 1;
            if left == 0 {
                break;
            }
            at = at.wrapping_add(stride as u32);
            (a, b) = next(false);
        }
    }
    #[inline(always)]
    fn shade_short_rows<F, G, P>(
        buf: &mut [u16],
        stride: usize,
        x: usize,
        (y, rows): (usize, usize),
        (mut a, mut b): (i32, i32),
        mut next: F,
        mut span: G,
    ) where
        F: FnMut() -> (i32, i32),
        G: FnMut(i32, i32) -> P,
        P: FnMut() -> Self,
    {
        // As `fill_short_rows`.
        let mut at = (y as u32)
            .wrapping_mul(stride as u32)
            .wrapping_add(x as u32);
        let mut row = y as i32;
        let mut left = rows;
        // The pixel loop steps by a one the compiler cannot see: it would otherwise vectorise
        // it, and the vector loop's constants, set up before the rows, cost a short span's
        // triangle more than the vector loop saves.
        let one = core::hint::black_box(1usize);
        loop {
            if a < b {
                let start = at.wrapping_add(a as u32) as usize;
                let len = b.wrapping_sub(a) as u32 as usize;
                let mut shade = span(row, (x as i32).wrapping_add(a));
                let span = &mut buf[start..start + len];
                let mut i = 0;
                while i < span.len() {
                    span[i] = RawU16::from(shade()).into_inner();
                    i += one;
                }
            }
            left -= 1;
            if left == 0 {
                break;
            }
            at = at.wrapping_add(stride as u32);
            row = row.wrapping_add(1);
            (a, b) = next();
        }
    }

    #[inline(always)]
    fn shade<F: FnMut() -> Self>(row: &mut [u16], x: usize, len: usize, mut shade: F) {
        for w in &mut row[x..x + len] {
            *w = RawU16::from(shade()).into_inner();
        }
    }
    #[inline(always)]
    fn shade_depth_at<F: DepthSpan<Self>>(
        buf: &mut [u16],
        row: usize,
        x: usize,
        depth: &mut [u16],
        shade: F,
    ) {
        // The span's own words (one a pixel), cut with one range check.
        let start = row + x;
        if let Some(span) = buf.get_mut(start..start + depth.len()) {
            Self::shade_depth(span, 0, depth, shade);
        }
    }
    #[inline(always)]
    fn shade_depth<F: DepthSpan<Self>>(row: &mut [u16], x: usize, depth: &mut [u16], mut shade: F) {
        // One loop over both rows: the zip needs no bounds check per pixel.
        let end = x + depth.len();
        for (i, (w, d)) in row[x..end].iter_mut().zip(depth).enumerate() {
            if let Some(c) = shade.pixel(i, d) {
                *w = RawU16::from(c).into_inner();
            }
        }
    }
    #[inline]
    fn walk(buf: &mut [u16], stride: usize, points: LinePoints, color: Self) {
        walk_words(buf, stride, points, RawU16::from(color).into_inner());
    }
    #[inline]
    fn blend(row: &mut [u16], x: usize, len: usize, color: Self, alpha: u8) {
        // On the packed word: each field shifted out, blended and shifted back, with the same
        // arithmetic as `blend` (a test checks they agree for every pair of fields).
        let (r, g, b) = (color.r(), color.g(), color.b());
        for w in &mut row[x..x + len] {
            let d = *w;
            let dr = blend_channel(r, (d >> 11) as u8, alpha);
            let dg = blend_channel(g, ((d >> 5) & 0x3F) as u8, alpha);
            let db = blend_channel(b, (d & 0x1F) as u8, alpha);
            *w = (u16::from(dr) << 11) | (u16::from(dg) << 5) | u16::from(db);
        }
    }
    #[inline(always)]
    fn blend_shade<F: FnMut() -> (Self, u8)>(row: &mut [u16], x: usize, len: usize, mut shade: F) {
        for w in &mut row[x..x + len] {
            let (c, a) = shade();
            match a {
                255 => *w = RawU16::from(c).into_inner(),
                0 => {}
                _ => {
                    // As `blend` above, on the packed word.
                    let d = *w;
                    let dr = blend_channel(c.r(), (d >> 11) as u8, a);
                    let dg = blend_channel(c.g(), ((d >> 5) & 0x3F) as u8, a);
                    let db = blend_channel(c.b(), (d & 0x1F) as u8, a);
                    *w = (u16::from(dr) << 11) | (u16::from(dg) << 5) | u16::from(db);
                }
            }
        }
    }
}

impl Storage for Gray8 {
    type Word = u8;
    const WORD_PER_PIXEL: bool = true;
    fn row_words(width: usize) -> usize {
        width
    }
    #[inline]
    fn set(row: &mut [u8], x: usize, color: Self) {
        row[x] = color.luma();
    }
    #[inline]
    fn get(row: &[u8], x: usize) -> Self {
        Gray8::new(row[x])
    }
    #[inline]
    fn fill(row: &mut [u8], x: usize, len: usize, color: Self) {
        fill_words(&mut row[x..x + len], color.luma());
    }
    #[inline(always)]
    fn fill_span(buf: &mut [u8], stride: usize, x: usize, y: usize, len: usize, color: Self) {
        let start = y * stride + x;
        fill_words(&mut buf[start..start + len], color.luma());
    }
    #[inline(always)]
    fn fill_long_span(buf: &mut [u8], stride: usize, x: usize, y: usize, len: usize, color: Self) {
        let start = y * stride + x;
        fill_long_words(&mut buf[start..start + len], color.luma());
    }
    #[inline]
    fn walk(buf: &mut [u8], stride: usize, points: LinePoints, color: Self) {
        walk_words(buf, stride, points, color.luma());
    }
}

impl Storage for Rgb888 {
    type Word = u8;
    fn row_words(width: usize) -> usize {
        // Saturating: no slice is usize::MAX bytes long, so a 16-bit target rejects such a width.
        width.saturating_mul(3)
    }
    #[inline]
    fn set(row: &mut [u8], x: usize, color: Self) {
        row[3 * x..3 * x + 3].copy_from_slice(&[color.r(), color.g(), color.b()]);
    }
    #[inline]
    fn get(row: &[u8], x: usize) -> Self {
        Rgb888::new(row[3 * x], row[3 * x + 1], row[3 * x + 2])
    }
    #[inline]
    fn fill(row: &mut [u8], x: usize, len: usize, color: Self) {
        let rgb = [color.r(), color.g(), color.b()];
        for px in row[3 * x..3 * (x + len)].chunks_exact_mut(3) {
            px.copy_from_slice(&rgb);
        }
    }
}

impl Storage for BinaryColor {
    type Word = u8;
    fn row_words(width: usize) -> usize {
        width.div_ceil(8)
    }
    #[inline]
    fn set(row: &mut [u8], x: usize, color: Self) {
        let mask = 0x80u8 >> (x % 8);
        if color.is_on() {
            row[x / 8] |= mask;
        } else {
            row[x / 8] &= !mask;
        }
    }
    #[inline]
    fn get(row: &[u8], x: usize) -> Self {
        BinaryColor::from(row[x / 8] & (0x80u8 >> (x % 8)) != 0)
    }
    fn fill(row: &mut [u8], x: usize, len: usize, color: Self) {
        let end = x + len;
        let value = if color.is_on() { 0xFF } else { 0x00 };
        // Partial bytes at either end keep their other bits; whole bytes in between are stored.
        let (first, last) = (x / 8, (end - 1) / 8);
        let head = 0xFFu8 >> (x % 8);
        let tail = 0xFFu8 << (7 - (end - 1) % 8);
        if first == last {
            let mask = head & tail;
            row[first] = (row[first] & !mask) | (value & mask);
            return;
        }
        row[first] = (row[first] & !head) | (value & head);
        row[first + 1..last].fill(value);
        row[last] = (row[last] & !tail) | (value & tail);
    }
}

/// A framebuffer over a caller-provided slice: no allocation, rows top to bottom.
///
/// ```
/// use rasterizer_core::surface::Framebuffer;
/// use embedded_graphics_core::{pixelcolor::Rgb565, prelude::*};
///
/// let mut buf = [0u16; 320 * 240];
/// let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 320, 240).unwrap();
/// fb.clear(Rgb565::BLUE).unwrap();
/// assert_eq!(fb.pixel(Point::new(10, 10)), Some(Rgb565::BLUE));
/// ```
#[derive(Debug)]
pub struct Framebuffer<'a, C: Storage> {
    buf: &'a mut [C::Word],
    /// At most [`MAX_DIMENSION`], so `u16`: a rasterizer inlined with the framebuffer then knows
    /// that its clip area lies far inside the guard band, and drops those tests.
    width: u16,
    height: u16,
    stride: usize,
}

impl<'a, C: Storage> Framebuffer<'a, C> {
    /// Words a `width` x `height` framebuffer of this format needs, or `None` if the size is out of
    /// range (zero, or above [`MAX_DIMENSION`]) or its length overflows `usize` (16-bit targets).
    pub fn required_len(width: u32, height: u32) -> Option<usize> {
        let valid = (1..=MAX_DIMENSION).contains(&width) && (1..=MAX_DIMENSION).contains(&height);
        // At most 98,301 x 32,767 words: below 2^32, so checked only for 16-bit targets.
        valid
            .then(|| C::row_words(width as usize).checked_mul(height as usize))
            .flatten()
    }

    /// A framebuffer over `buf`, which must hold exactly [`Self::required_len`] words.
    ///
    /// # Errors
    /// [`FramebufferError::BadSize`] for a zero or too large size, [`FramebufferError::WrongLength`]
    /// when the slice is shorter or longer than the size needs.
    pub fn new(buf: &'a mut [C::Word], width: u32, height: u32) -> Result<Self, FramebufferError> {
        let expected =
            Self::required_len(width, height).ok_or(FramebufferError::BadSize { width, height })?;
        if buf.len() != expected {
            return Err(FramebufferError::WrongLength {
                expected,
                actual: buf.len(),
            });
        }
        Ok(Self {
            buf,
            // Both checked against MAX_DIMENSION above.
            width: width as u16,
            height: height as u16,
            stride: C::row_words(width as usize),
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        u32::from(self.width)
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        u32::from(self.height)
    }

    /// The underlying words, rows top to bottom.
    pub fn as_slice(&self) -> &[C::Word] {
        self.buf
    }

    /// The underlying words, for a DMA transfer or a direct edit.
    pub fn as_mut_slice(&mut self) -> &mut [C::Word] {
        self.buf
    }

    /// The colour of a pixel, or `None` outside the buffer.
    pub fn pixel(&self, p: Point) -> Option<C> {
        let (x, y) = self.index(p.x, p.y)?;
        Some(C::get(&self.buf[y * self.stride..(y + 1) * self.stride], x))
    }

    #[inline]
    fn index(&self, x: i32, y: i32) -> Option<(usize, usize)> {
        let inside = (x as u32) < u32::from(self.width) && (y as u32) < u32::from(self.height);
        inside.then_some((x as usize, y as usize))
    }

    #[inline]
    fn row_mut(&mut self, y: usize) -> &mut [C::Word] {
        &mut self.buf[y * self.stride..(y + 1) * self.stride]
    }
}

impl<C: Storage> OriginDimensions for Framebuffer<'_, C> {
    fn size(&self) -> Size {
        Size::new(u32::from(self.width), u32::from(self.height))
    }
}

impl<C: Storage> DrawTarget for Framebuffer<'_, C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        for Pixel(p, color) in pixels {
            if let Some((x, y)) = self.index(p.x, p.y) {
                C::set(self.row_mut(y), x, color);
            }
        }
        Ok(())
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = C>,
    {
        let area_px = crate::geom::PixelRect::from_rectangle(area);
        // An empty area takes no colours; without this, zero columns over 2^32 rows would loop.
        if area_px.is_empty() {
            return Ok(());
        }
        let mut colors = colors.into_iter();
        // Rows below the buffer can hold no visible pixel: stop there, so a huge area with an
        // endless colour iterator still ends. Above the buffer, every step takes a colour.
        for y in area_px.y0..area_px.y1.min(i64::from(self.height)) {
            for x in area_px.x0..area_px.x1 {
                let Some(color) = colors.next() else {
                    return Ok(());
                };
                if (0..i64::from(self.width)).contains(&x)
                    && (0..i64::from(self.height)).contains(&y)
                {
                    C::set(self.row_mut(y as usize), x as usize, color);
                }
            }
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Self::Error> {
        let r = crate::geom::PixelRect::from_rectangle(area);
        let (x0, x1) = (r.x0.max(0), r.x1.min(i64::from(self.width)));
        let (y0, y1) = (r.y0.max(0), r.y1.min(i64::from(self.height)));
        if x0 >= x1 || y0 >= y1 {
            return Ok(());
        }
        for y in y0..y1 {
            C::fill(
                self.row_mut(y as usize),
                x0 as usize,
                (x1 - x0) as usize,
                color,
            );
        }
        Ok(())
    }

    fn clear(&mut self, color: C) -> Result<(), Self::Error> {
        let (w, h) = (usize::from(self.width), usize::from(self.height));
        for y in 0..h {
            C::fill(self.row_mut(y), 0, w, color);
        }
        Ok(())
    }
}

impl<C: Storage> Framebuffer<'_, C> {
    /// True when the span lies inside the buffer (one unsigned compare each).
    #[inline(always)]
    fn span_inside(&self, x: i32, y: i32, len: u32) -> bool {
        (y as u32) < u32::from(self.height)
            && (x as u32) <= u32::from(self.width)
            && len <= u32::from(self.width) - x as u32
    }

    /// A span that is not wholly inside: clipped. Kept out of line so the fast path stays small.
    #[cold]
    #[inline(never)]
    fn fill_span_clipped(&mut self, x: i32, y: i32, len: u32, color: C) {
        let area = Rectangle::new(Point::new(x, y), Size::new(len, 1));
        let Ok(()) = self.fill_solid(&area, color);
    }

    /// A line walk that is not wholly inside: pixel by pixel with the bounds check.
    #[cold]
    #[inline(never)]
    fn walk_clipped(&mut self, points: LinePoints, color: C) {
        let Ok(()) = self.draw_iter(points.map(|p| Pixel(p, color)));
    }
}

/// The checked methods clip what lies outside (pixels outside are dropped, as the `DrawTarget`
/// contract says); the rasterizers call the in-clip ones, which skip the checks.
impl<C: Storage> Surface for Framebuffer<'_, C> {
    #[inline(always)]
    fn fill_span(&mut self, x: i32, y: i32, len: u32, color: C) -> Result<(), Self::Error> {
        if self.span_inside(x, y, len) {
            C::fill_span(
                self.buf,
                self.stride,
                x as usize,
                y as usize,
                len as usize,
                color,
            );
        } else {
            self.fill_span_clipped(x, y, len, color);
        }
        Ok(())
    }

    #[inline]
    fn shade_span<F: FnMut() -> C>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        mut shade: F,
    ) -> Result<(), Self::Error> {
        if self.span_inside(x, y, len) {
            C::shade(self.row_mut(y as usize), x as usize, len as usize, shade);
            Ok(())
        } else {
            // Every colour is still taken, in order; only the pixels inside are stored.
            let area = Rectangle::new(Point::new(x, y), Size::new(len, 1));
            self.fill_contiguous(
                &area,
                core::iter::repeat_with(&mut shade).take(len as usize),
            )
        }
    }

    #[inline(always)]
    fn fill_span_in_clip(&mut self, x: i32, y: i32, len: u32, color: C) -> Result<(), Self::Error> {
        C::fill_span(
            self.buf,
            self.stride,
            x as usize,
            y as usize,
            len as usize,
            color,
        );
        Ok(())
    }

    #[inline(always)]
    fn fill_long_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: C,
    ) -> Result<(), Self::Error> {
        C::fill_long_span(
            self.buf,
            self.stride,
            x as usize,
            y as usize,
            len as usize,
            color,
        );
        Ok(())
    }

    #[inline(always)]
    fn fill_short_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: C,
    ) -> Result<(), Self::Error> {
        C::fill_short_span(
            self.buf,
            self.stride,
            x as usize,
            y as usize,
            len as usize,
            color,
        );
        Ok(())
    }

    #[inline(always)]
    fn fill_short_halves_in_clip<F: FnMut(bool) -> (i32, i32)>(
        &mut self,
        x: i32,
        (top, mid, bottom): (i32, i32, i32),
        color: C,
        first: (i32, i32),
        next: F,
    ) -> Result<(), Self::Error> {
        if top >= bottom {
            return Ok(());
        }
        // `top <= mid <= bottom`, as documented (else a count wraps round); checked in debug
        // builds only: a test here spoils the small triangles' row loops.
        debug_assert!(top <= mid && mid <= bottom, "rows {top}, {mid}, {bottom}");
        let (upper, lower) = (
            mid.wrapping_sub(top) as u32 as usize,
            bottom.wrapping_sub(mid) as u32 as usize,
        );
        C::fill_short_halves(
            self.buf,
            self.stride,
            x as usize,
            (top as usize, upper, lower),
            color,
            first,
            next,
        );
        Ok(())
    }

    #[inline(always)]
    fn fill_short_rows_in_clip<F: FnMut() -> (i32, i32)>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        color: C,
        first: (i32, i32),
        next: F,
    ) -> Result<(), Self::Error> {
        if rows.is_empty() {
            return Ok(());
        }
        let n = rows.end.wrapping_sub(rows.start) as u32 as usize;
        C::fill_short_rows(
            self.buf,
            self.stride,
            x as usize,
            (rows.start as usize, n),
            color,
            first,
            next,
        );
        Ok(())
    }

    #[inline(always)]
    fn shade_short_rows_in_clip<F, G, P>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        first: (i32, i32),
        next: F,
        span: G,
    ) -> Result<(), Self::Error>
    where
        F: FnMut() -> (i32, i32),
        G: FnMut(i32, i32) -> P,
        P: FnMut() -> C,
    {
        if rows.is_empty() {
            return Ok(());
        }
        let n = rows.end.wrapping_sub(rows.start) as u32 as usize;
        C::shade_short_rows(
            self.buf,
            self.stride,
            x as usize,
            (rows.start as usize, n),
            first,
            next,
            span,
        );
        Ok(())
    }

    #[inline(always)]
    fn shade_span_in_clip<F: FnMut() -> C>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        shade: F,
    ) -> Result<(), Self::Error> {
        C::shade(self.row_mut(y as usize), x as usize, len as usize, shade);
        Ok(())
    }

    #[inline(always)]
    fn shade_span_depth_in_clip<F: DepthSpan<C>>(
        &mut self,
        x: i32,
        y: i32,
        depth: &mut [u16],
        shade: F,
    ) -> Result<(), Self::Error> {
        C::shade_depth_at(self.buf, y as usize * self.stride, x as usize, depth, shade);
        Ok(())
    }

    #[inline(always)]
    fn shade_triangle_depth_in_clip<T: DepthTriangle<C>>(
        &mut self,
        triangle: T,
    ) -> Result<(), Self::Error> {
        triangle.by_words(self.buf, self.stride, 0);
        Ok(())
    }

    #[inline(always)]
    fn draw_line_points_in_clip(
        &mut self,
        points: LinePoints,
        color: C,
    ) -> Result<(), Self::Error> {
        C::walk(self.buf, self.stride, points, color);
        Ok(())
    }

    #[inline]
    fn draw_line_points(&mut self, points: LinePoints, color: C) -> Result<(), Self::Error> {
        // A line's pixels lie between its first and last, so checking those two is enough.
        let first = (points.x, points.y);
        let last = points.last_pixel();
        let (w, h) = (u32::from(self.width), u32::from(self.height));
        let inside = |p: (i32, i32)| (p.0 as u32) < w && (p.1 as u32) < h;
        if points.remaining() == 0 || (inside(first) && last.is_some_and(inside)) {
            C::walk(self.buf, self.stride, points, color);
        } else {
            self.walk_clipped(points, color);
        }
        Ok(())
    }
    const READ_BACK: bool = true;

    #[inline(always)]
    fn blend_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: C,
        alpha: u8,
    ) -> Result<(), BlendError<Self::Error>> {
        C::blend(
            self.row_mut(y as usize),
            x as usize,
            len as usize,
            color,
            alpha,
        );
        Ok(())
    }

    #[inline(always)]
    fn blend_shade_span_in_clip<F: FnMut() -> (C, u8)>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        shade: F,
    ) -> Result<(), BlendError<Self::Error>> {
        C::blend_shade(self.row_mut(y as usize), x as usize, len as usize, shade);
        Ok(())
    }
}

/// One horizontal strip of a screen rendered into a small buffer: a [`Framebuffer`] of `rows`
/// rows that stands for screen rows `y0 .. y0 + rows`. Drawing uses screen coordinates; the clip
/// area is the strip, so everything outside it is dropped. Any `y0` is accepted; rows that would
/// lie past `i32::MAX` stand for no screen row and are never drawn.
#[derive(Debug)]
pub struct Band<'a, C: Storage> {
    fb: Framebuffer<'a, C>,
    y0: i32,
}

impl<'a, C: Storage> Band<'a, C> {
    /// A band over `fb` standing for the screen rows from `y0` on.
    pub fn new(fb: Framebuffer<'a, C>, y0: i32) -> Self {
        Self { fb, y0 }
    }

    /// The first screen row of the band.
    pub fn y0(&self) -> i32 {
        self.y0
    }

    /// The band's pixels.
    pub fn framebuffer(&self) -> &Framebuffer<'a, C> {
        &self.fb
    }
}

impl<C: Storage> embedded_graphics_core::geometry::Dimensions for Band<'_, C> {
    fn bounding_box(&self) -> Rectangle {
        // Rows past i32::MAX stand for no screen row: the strip stops there.
        let room = i64::from(i32::MAX) - i64::from(self.y0) + 1;
        let rows = i64::from(self.fb.height).min(room) as u32;
        Rectangle::new(
            Point::new(0, self.y0),
            Size::new(u32::from(self.fb.width), rows),
        )
    }
}

impl<C: Storage> DrawTarget for Band<'_, C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        // A row too far from the band for the difference to fit i32 is certainly outside it.
        let y0 = self.y0;
        self.fb.draw_iter(
            pixels
                .into_iter()
                .filter_map(|Pixel(p, c)| Some(Pixel(Point::new(p.x, p.y.checked_sub(y0)?), c))),
        )
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Self::Error> {
        // Shifted in i64: the area's rows may lie anywhere relative to the band.
        let mut r = crate::geom::PixelRect::from_rectangle(area);
        r.y0 -= i64::from(self.y0);
        r.y1 -= i64::from(self.y0);
        let rows = crate::geom::PixelRect {
            x0: 0,
            y0: 0,
            x1: i64::from(self.fb.width),
            y1: i64::from(self.fb.height),
        };
        let r = r.intersection(&rows);
        if r.is_empty() {
            return Ok(());
        }
        self.fb.fill_solid(&r.to_rectangle(), color)
    }

    fn clear(&mut self, color: C) -> Result<(), Self::Error> {
        self.fb.clear(color)
    }
}

impl<C: Storage> Surface for Band<'_, C> {
    #[inline(always)]
    fn fill_span(&mut self, x: i32, y: i32, len: u32, color: C) -> Result<(), Self::Error> {
        // Not wrapping: a row 2^32 away would land inside the band.
        match y.checked_sub(self.y0) {
            Some(y) => self.fb.fill_span(x, y, len, color),
            None => Ok(()),
        }
    }

    #[inline(always)]
    fn fill_span_in_clip(&mut self, x: i32, y: i32, len: u32, color: C) -> Result<(), Self::Error> {
        self.fb.fill_span_in_clip(x, y - self.y0, len, color)
    }

    #[inline(always)]
    fn fill_long_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: C,
    ) -> Result<(), Self::Error> {
        self.fb.fill_long_span_in_clip(x, y - self.y0, len, color)
    }

    #[inline(always)]
    fn fill_short_rows_in_clip<F: FnMut() -> (i32, i32)>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        color: C,
        first: (i32, i32),
        next: F,
    ) -> Result<(), Self::Error> {
        let rows = rows.start - self.y0..rows.end - self.y0;
        self.fb.fill_short_rows_in_clip(x, rows, color, first, next)
    }

    #[inline(always)]
    fn fill_short_halves_in_clip<F: FnMut(bool) -> (i32, i32)>(
        &mut self,
        x: i32,
        (top, mid, bottom): (i32, i32, i32),
        color: C,
        first: (i32, i32),
        next: F,
    ) -> Result<(), Self::Error> {
        let rows = (top - self.y0, mid - self.y0, bottom - self.y0);
        self.fb
            .fill_short_halves_in_clip(x, rows, color, first, next)
    }

    #[inline(always)]
    fn shade_short_rows_in_clip<F, G, P>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        first: (i32, i32),
        next: F,
        mut span: G,
    ) -> Result<(), Self::Error>
    where
        F: FnMut() -> (i32, i32),
        G: FnMut(i32, i32) -> P,
        P: FnMut() -> C,
    {
        // The shader sees screen rows, the band's buffer its own.
        let y0 = self.y0;
        let band = rows.start - y0..rows.end - y0;
        self.fb
            .shade_short_rows_in_clip(x, band, first, next, |y, x0| span(y + y0, x0))
    }

    #[inline(always)]
    fn shade_span_in_clip<F: FnMut() -> C>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        shade: F,
    ) -> Result<(), Self::Error> {
        self.fb.shade_span_in_clip(x, y - self.y0, len, shade)
    }

    #[inline(always)]
    fn shade_span_depth_in_clip<F: DepthSpan<C>>(
        &mut self,
        x: i32,
        y: i32,
        depth: &mut [u16],
        shade: F,
    ) -> Result<(), Self::Error> {
        self.fb
            .shade_span_depth_in_clip(x, y - self.y0, depth, shade)
    }

    #[inline(always)]
    fn shade_triangle_depth_in_clip<T: DepthTriangle<C>>(
        &mut self,
        triangle: T,
    ) -> Result<(), Self::Error> {
        triangle.by_words(self.fb.buf, self.fb.stride, self.y0);
        Ok(())
    }

    #[inline(always)]
    fn shade_span<F: FnMut() -> C>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        shade: F,
    ) -> Result<(), Self::Error> {
        match y.checked_sub(self.y0) {
            Some(y) => self.fb.shade_span(x, y, len, shade),
            None => Ok(()),
        }
    }

    fn draw_line_points(&mut self, points: LinePoints, color: C) -> Result<(), Self::Error> {
        // A line walk carries screen rows; shift each point (lines are not the band fast path).
        self.draw_iter(points.map(|p| Pixel(p, color)))
    }
    const READ_BACK: bool = true;

    #[inline(always)]
    fn blend_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: C,
        alpha: u8,
    ) -> Result<(), BlendError<Self::Error>> {
        self.fb
            .blend_span_in_clip(x, y - self.y0, len, color, alpha)
    }

    #[inline(always)]
    fn blend_shade_span_in_clip<F: FnMut() -> (C, u8)>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        shade: F,
    ) -> Result<(), BlendError<Self::Error>> {
        self.fb.blend_shade_span_in_clip(x, y - self.y0, len, shade)
    }
}
