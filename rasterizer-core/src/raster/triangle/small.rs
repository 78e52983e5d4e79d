//! Set-up for the common 2D case: a triangle that lies inside the clip area and is at most
//! [`SMALL_PIXELS`] pixels wide and tall. Its edge walks are set up in `i32`, in coordinates
//! relative to the pixel at its top left (two unsigned 32-bit divisions an edge, which a
//! Cortex-M has an instruction for), its rows and columns need no clamping to the clip area,
//! and the surface takes its rows a half of the triangle at a time or both halves in one call
//! ([`RowSink`]), so a framebuffer steps its row offset instead of finding each span's. A
//! triangle of that size across the clip area's edge takes the same set-up with its rows and
//! columns cut ([`Small::crossing`]). It gives exactly the spans of
//! [`super::setup::walk_spans`].

use super::setup::SpanSink;
use crate::geom::{PixelRect, SubPoint, GUARD_BAND_PIXELS};
use core::num::{NonZeroU16, NonZeroU32};

/// The largest width and height, in pixels, of a triangle set up in `i32`.
///
/// Bound: with `E = 64 s <= 2^14` sub-pixel units (`s <= 2^8` the unit), a vertex lies within
/// `-s ..= 129 s` doubled units right of the centre of the triangle's leftmost pixel column,
/// an edge's `dx` within `E` and `dy` within `E`, and an edge is set up on a row whose sample
/// lies less than `2 s` doubled units below its upper end, so the numerator `y dx + x dy`
/// stays below `2^7 s^2 + 129 s E < 2^29.1`, the divisor `D = 2 s dy` is at most `2^23`, a
/// column is at most 65, and the spans are at most 65 pixels long. (The 3D pipeline's fused
/// fill sets an edge up on the first row of a clip area that may start lower, within the
/// edge's rows: less than `2 (E + s)` doubled units below its upper end, and the numerator
/// below `130 s E + 129 s E < 2^30.1`.)
pub(crate) const SMALL_PIXELS: i64 = 64;

/// A triangle sorted by y (top first) that qualifies for the `i32` set-up.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Small {
    /// The sorted vertices, in sub-pixel units.
    p: [(i32, i32); 3],
    /// The column of the pixel corner at or left of the leftmost vertex.
    ox: i32,
    /// The rows of the spans: `top..bottom`, the lower half from `mid`.
    top: i32,
    mid: i32,
    bottom: i32,
    /// How far v0 and v1 lie above the samples of rows `top` and `mid`, doubled: in `[0, 2 s)`.
    below: (i32, i32),
    /// The width and height, in sub-pixel units.
    size: (i32, i32),
    /// Twice the signed area, as `Sorted::cross`: negative when the middle vertex lies left of
    /// the long edge.
    cross: i32,
}

impl Small {
    /// Sorts the triangle by y; `None` unless it lies inside `clip` and the guard band and
    /// within [`SMALL_PIXELS`] each way.
    #[inline(always)]
    pub fn new<const BITS: u32>(v: &[SubPoint<BITS>; 3], clip: &PixelRect) -> Option<Self> {
        Self::set_up::<BITS, true>(by_y(v), clip)
    }

    /// [`Small::new`] for a triangle that may reach out of `clip`, to be walked with
    /// [`Small::walk_clipped`]: `None` unless it lies inside the guard band and within
    /// [`SMALL_PIXELS`] each way.
    #[inline(always)]
    pub fn crossing<const BITS: u32>(v: &[SubPoint<BITS>; 3], clip: &PixelRect) -> Option<Self> {
        Self::set_up::<BITS, false>(by_y(v), clip)
    }

    /// [`Small::new`] for vertices already sorted by y.
    #[inline(always)]
    pub fn sorted<const BITS: u32>(p: [(i32, i32); 3], clip: &PixelRect) -> Option<Self> {
        Self::set_up::<BITS, true>(p, clip)
    }

    /// The set-up of sorted vertices, inside `clip` (`INSIDE`) or anywhere in the guard band.
    #[inline(always)]
    fn set_up<const BITS: u32, const INSIDE: bool>(
        p: [(i32, i32); 3],
        clip: &PixelRect,
    ) -> Option<Self> {
        #[allow(clippy::let_unit_value)]
        let () = SubPoint::<BITS>::VALID;
        let [a, b, c] = p;
        let (xmin, xmax) = (a.0.min(b.0).min(c.0), a.0.max(b.0).max(c.0));
        let (x0, x1) = (i64::from(xmin), i64::from(xmax));
        let (y0, y1) = (i64::from(a.1), i64::from(c.1));
        let s = 1i64 << BITS;
        let band = i64::from(GUARD_BAND_PIXELS) << BITS;
        // Wrapped, as `u32` the true extents (`xmax >= xmin`, `c.1 >= a.1`).
        let size = (xmax.wrapping_sub(xmin), c.1.wrapping_sub(a.1));
        // Inside the clip area, every span lies between its columns and rows (a centre inside
        // the triangle lies between its extreme vertices); inside the guard band, the generic
        // path would draw it too. The clip area's bounds are taken within the band, which
        // folds away for a target whose size the compiler knows to lie well inside it
        // (`Framebuffer`'s).
        let inside = if INSIDE {
            x0 >= (clip.x0 * s).max(-band)
                && x1 <= (clip.x1 * s).min(band)
                && y0 >= (clip.y0 * s).max(-band)
                && y1 <= (clip.y1 * s).min(band)
        } else {
            x0 >= -band && x1 <= band && y0 >= -band && y1 <= band
        };
        let fits = inside
            && size.0 as u32 <= (SMALL_PIXELS << BITS) as u32
            && size.1 as u32 <= (SMALL_PIXELS << BITS) as u32;
        if !fits {
            return None;
        }
        // The first row whose sample `r s + s/2` lies at or below y is `ceil((2 y - s) / 2 s)`,
        // `(2 y + s - 1) >> (BITS + 1)`; with `f` the bits shifted out, the sample lies
        // `2 s - 1 - f` doubled units below y.
        let rows = |y: i32| {
            let (v, mask) = (2 * y + (1 << BITS) - 1, (2 << BITS) - 1);
            (v >> (BITS + 1), (v & mask) ^ mask)
        };
        let ((top, ya), (mid, yb), (bottom, _)) = (rows(a.1), rows(b.1), rows(c.1));
        Some(Self {
            p: [a, b, c],
            ox: xmin >> BITS,
            top,
            mid,
            bottom,
            below: (ya, yb),
            size,
            cross: (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1),
        })
    }

    /// The sorted vertices, in sub-pixel units.
    #[inline(always)]
    pub fn vertices(&self) -> [(i32, i32); 3] {
        self.p
    }

    /// The pixel of the triangle's leftmost column and top row, from which [`Small::walk`]
    /// hands a sink its columns and rows.
    #[inline(always)]
    pub fn origin(&self) -> (i32, i32) {
        (self.ox, self.top)
    }

    /// The width and height, in sub-pixel units.
    #[inline(always)]
    pub fn size(&self) -> (i64, i64) {
        (i64::from(self.size.0), i64::from(self.size.1))
    }

    /// Twice the signed area, as `Sorted::cross`.
    #[inline(always)]
    pub fn cross(&self) -> i32 {
        self.cross
    }

    /// Hands `sink` the rows of the triangle, top to bottom, with their spans: those of
    /// [`super::setup::walk_spans`], with no clamping.
    #[inline(always)]
    pub fn walk<K: RowSink, const BITS: u32>(&self, sink: &mut K) -> Result<(), K::Error> {
        // A triangle with no area but some rows (its vertices on a slanted line) needs no test:
        // its edges are one line, whose columns are the same on every row, so no span.
        if self.top >= self.bottom {
            return Ok(());
        }
        if !K::HALVES {
            return self.walk_wound::<K, BITS>(sink, self.cross < 0);
        }
        if self.cross < 0 {
            self.walk_halves::<K, BITS>(sink, true)
        } else {
            self.walk_halves::<K, BITS>(sink, false)
        }
    }

    /// [`Small::walk`] through [`RowSink::halves`], the short edges on the left
    /// (`short_left`) or on the right.
    #[inline(always)]
    fn walk_halves<K: RowSink, const BITS: u32>(
        &self,
        sink: &mut K,
        short_left: bool,
    ) -> Result<(), K::Error> {
        let (mut long, mut short, lower) = self.edges::<BITS>(self.top, self.below);
        let order = move |short: &Edge<true>, long: &Edge<true>| {
            if short_left {
                cols(short, long)
            } else {
                cols(long, short)
            }
        };
        let first = order(&short, &long);
        let rows = (self.top, self.mid, self.bottom);
        sink.halves(self.ox, rows, first, |to_lower| {
            long.step();
            if to_lower {
                short = lower();
            } else {
                short.step();
            }
            order(&short, &long)
        })
    }

    /// The long edge and the short one on row `first` (within the triangle's rows), whose
    /// sample lies `below` doubled units below v0 and below v1 (for the lower edge if it
    /// starts there), and the lower edge from its first row.
    #[inline(always)]
    fn edges<const BITS: u32>(
        &self,
        first: i32,
        (ya, yb): (i32, i32),
    ) -> (Edge<true>, Edge<true>, impl Fn() -> Edge<true>) {
        let [a, b, c] = self.p;
        // Doubled x from the centre of column `ox`.
        let cx = (2 * self.ox + 1) << BITS;
        let (xa, xb) = (2 * a.0 - cx, 2 * b.0 - cx);
        let long = Edge::<true>::new::<BITS>(xa, ya, c.0 - a.0, c.1 - a.1);
        let lower_at = move |y| Edge::<true>::new::<BITS>(xb, y, c.0 - b.0, c.1 - b.1);
        let short = if first < self.mid {
            Edge::<true>::new::<BITS>(xa, ya, b.0 - a.0, b.1 - a.1)
        } else {
            lower_at(yb)
        };
        let y1 = self.below.1;
        (long, short, move || lower_at(y1))
    }

    /// [`Small::walk`] half by half through [`RowSink::rows`], the short edges on the left
    /// (`short_left`) or on the right.
    #[inline(always)]
    fn walk_wound<K: RowSink, const BITS: u32>(
        &self,
        sink: &mut K,
        short_left: bool,
    ) -> Result<(), K::Error> {
        let [a, b, c] = self.p;
        let ox = self.ox;
        // Doubled x from the centre of column `ox`.
        let cx = (2 * ox + 1) << BITS;
        let (xa, xb) = (2 * a.0 - cx, 2 * b.0 - cx);
        let (ya, yb) = self.below;
        let mut long = Edge::<true>::new::<BITS>(xa, ya, c.0 - a.0, c.1 - a.1);
        if self.top < self.mid {
            let upper = Edge::<true>::new::<BITS>(xa, ya, b.0 - a.0, b.1 - a.1);
            // As in `walk_spans`: the walks copied into left and right, the long one back.
            let (mut l, mut r) = if short_left {
                (upper, long)
            } else {
                (long, upper)
            };
            sink.rows(ox, self.top..self.mid, cols(&l, &r), || {
                next(&mut l, &mut r)
            })?;
            long = if short_left { r } else { l };
            // The rows' walk stops on the half's last row: on to the lower half's first.
            long.step();
        }
        if self.mid < self.bottom {
            let lower = Edge::<true>::new::<BITS>(xb, yb, c.0 - b.0, c.1 - b.1);
            let (mut l, mut r) = if short_left {
                (lower, long)
            } else {
                (long, lower)
            };
            sink.rows(ox, self.mid..self.bottom, cols(&l, &r), || {
                next(&mut l, &mut r)
            })?;
        }
        Ok(())
    }

    /// [`Small::walk`] for a triangle set up by [`Small::crossing`], span by span: its rows
    /// and columns cut to `clip`, the spans of [`super::setup::walk_spans`]. Each edge is set
    /// up on the first row it is read on, which lies within its rows (see [`SMALL_PIXELS`]).
    /// One loop for both halves: the triangles that cross the clip area's edge are few.
    #[inline(always)]
    pub fn walk_clipped<K: SpanSink, const BITS: u32>(
        &self,
        clip: &PixelRect,
        sink: &mut K,
    ) -> Result<(), K::Error> {
        let (top, mid, bottom, ox) = (self.top, self.mid, self.bottom, self.ox);
        // The rows inside the clip area, and its columns relative to `ox` within the
        // triangle's `0 ..= 65`.
        let rows = |y: i64| y.clamp(i64::from(top), i64::from(bottom)) as i32;
        let (first, end) = (rows(clip.y0), rows(clip.y1));
        let column = |x: i64| (x - i64::from(ox)).clamp(0, SMALL_PIXELS + 1) as i32;
        let (lo, hi) = (column(clip.x0), column(clip.x1));
        if first >= end || lo >= hi {
            return Ok(());
        }
        // A row is `2 s` doubled units.
        let below = (
            self.below.0 + ((first - top) << (BITS + 1)),
            self.below.1 + ((first.max(mid) - mid) << (BITS + 1)),
        );
        let (mut long, mut short, lower) = self.edges::<BITS>(first, below);
        let short_left = self.cross < 0;
        for row in first..end {
            if row > first {
                long.step();
                if row == mid {
                    short = lower();
                } else {
                    short.step();
                }
            }
            let (l, r) = if short_left {
                (&short, &long)
            } else {
                (&long, &short)
            };
            let (a, b) = (l.col().max(lo), r.col().min(hi));
            if a < b {
                sink.span(row, ox + a, ox + b)?;
            }
        }
        Ok(())
    }
}

/// The vertices sorted by y, top first. Vertices on one row may come in either order: the
/// spans between the edges are the same (a flat top or bottom has no half above or below it),
/// so the sort needs no tie-break.
#[inline(always)]
fn by_y<const BITS: u32>(v: &[SubPoint<BITS>; 3]) -> [(i32, i32); 3] {
    let [mut a, mut b, mut c] = v.map(|q| (q.x, q.y));
    if b.1 < a.1 {
        core::mem::swap(&mut a, &mut b);
    }
    if c.1 < b.1 {
        core::mem::swap(&mut b, &mut c);
        if b.1 < a.1 {
            core::mem::swap(&mut a, &mut b);
        }
    }
    [a, b, c]
}

/// The columns between two edge walks on the current row.
#[inline(always)]
fn cols(left: &Edge<true>, right: &Edge<true>) -> (i32, i32) {
    (left.col(), right.col())
}

/// [`cols`] on the next row.
#[inline(always)]
fn next(left: &mut Edge<true>, right: &mut Edge<true>) -> (i32, i32) {
    left.step();
    right.step();
    cols(left, right)
}

/// Receives a small triangle's rows.
pub(crate) trait RowSink {
    /// The target's error.
    type Error;
    /// Whether [`Small::walk`] hands both halves to [`RowSink::halves`] in one call, with code
    /// of its own for each winding (short edges left or right), so that the walks stay in
    /// their registers: worth it where the rows are cheap (one colour), dearer where they need
    /// many registers (the Gouraud planes).
    const HALVES: bool = false;
    /// Draws the rows `top..bottom` of both halves (at least one row), as
    /// [`crate::surface::Surface::fill_short_halves_in_clip`] takes them; used where
    /// [`RowSink::HALVES`] is set.
    #[inline(always)]
    fn halves<F: FnMut(bool) -> (i32, i32)>(
        &mut self,
        x: i32,
        (top, mid, bottom): (i32, i32, i32),
        first: (i32, i32),
        mut next: F,
    ) -> Result<(), Self::Error> {
        if top < mid {
            self.rows(x, top..mid, first, || next(false))?;
        }
        if mid < bottom {
            let first = if top < mid { next(true) } else { first };
            self.rows(x, mid..bottom, first, || next(false))?;
        }
        Ok(())
    }
    /// Draws `rows` (at least one), top to bottom: `first` is the first row's columns
    /// `x + a .. x + b` (relative columns `a`, `b` never negative, none when `a >= b`), and
    /// `next` moves on a row and gives its columns.
    fn rows<F: FnMut() -> (i32, i32)>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        first: (i32, i32),
        next: F,
    ) -> Result<(), Self::Error>;
}

/// A [`RowSink`] that hands each non-empty span to a [`SpanSink`].
#[cfg(test)]
pub(crate) struct EachSpan<'a, K>(pub &'a mut K);

#[cfg(test)]
impl<K: SpanSink> RowSink for EachSpan<'_, K> {
    type Error = K::Error;
    #[inline(always)]
    fn rows<F: FnMut() -> (i32, i32)>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        first: (i32, i32),
        mut next: F,
    ) -> Result<(), K::Error> {
        let (mut a, mut b) = first;
        for row in rows.clone() {
            if row > rows.start {
                (a, b) = next();
            }
            if a < b {
                self.0.span(row, x + a, x + b)?;
            }
        }
        Ok(())
    }
}

/// [`EachSpan`] with both halves in one call ([`RowSink::HALVES`]).
#[cfg(test)]
pub(crate) struct EachSpanHalves<'a, K>(pub &'a mut K);

#[cfg(test)]
impl<K: SpanSink> RowSink for EachSpanHalves<'_, K> {
    type Error = K::Error;
    const HALVES: bool = true;
    fn rows<F: FnMut() -> (i32, i32)>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        first: (i32, i32),
        next: F,
    ) -> Result<(), K::Error> {
        EachSpan(&mut *self.0).rows(x, rows, first, next)
    }
    // Both halves in one loop, `next(true)` on the first row of the lower half, as a
    // framebuffer takes them.
    fn halves<F: FnMut(bool) -> (i32, i32)>(
        &mut self,
        x: i32,
        (top, mid, bottom): (i32, i32, i32),
        (mut a, mut b): (i32, i32),
        mut next: F,
    ) -> Result<(), K::Error> {
        for row in top..bottom {
            if row > top {
                (a, b) = next(row == mid);
            }
            if a < b {
                self.0.span(row, x + a, x + b)?;
            }
        }
        Ok(())
    }
}

/// The column walk of one edge, as `raster/edge.rs`'s `EdgeWalk` (whose notation this follows)
/// but set up in `i32`, columns relative to the triangle's leftmost pixel, packed as
/// `rem 2^32 + col` with `rem` in `[-D, 0)`: the column is the low half, read with no shift, and
/// the remainder's carry is the sign of the whole. On every row a walk is read on, the column
/// lies in `0 ..= 65`, so the sum of two packed values is the sum of their halves (no carry or
/// borrow crosses from the column into the remainder, the step's column moved up by one before
/// a carry included); past those rows the values wrap unread.
///
/// `BACK` chooses the form of a step that carries: the stepped value less `D 2^32 + 1`, or the
/// current value plus `step - D 2^32 - 1` (one register fewer where the rows keep both; the
/// small walks take it, the 3D pipeline's fused fill compiles the other smaller). The same
/// values either way.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Edge<const BACK: bool> {
    packed: i64,
    /// `rem_step 2^32 + col_step`, `rem_step` in `[0, D)`.
    step: i64,
    /// `carry = D 2^32 + 1`, one `D` off the remainder and one column back; with `BACK`,
    /// `step - carry`.
    fix: i64,
}

impl<const BACK: bool> Edge<BACK> {
    /// The walk of an edge with extent `(dx, dy)` (`dy > 0`, sub-pixel units) from a row whose
    /// sample lies `y` (doubled units, `0 <= y < 2 s`, or within the edge's rows: below
    /// `2 (dy + s)`, see [`SMALL_PIXELS`]) below the edge's upper end, which lies `x` doubled
    /// units right of the centre of column 0 (`x >= -s`, as every vertex).
    #[inline(always)]
    pub(crate) fn new<const BITS: u32>(x: i32, y: i32, dx: i32, dy: i32) -> Self {
        // `dy <= 64 s <= 2^14`: as a non-zero `u16` (a walked edge is never flat), both divisors
        // below are known to be non-zero without a test each.
        let dy16 = NonZeroU16::new(dy as u16).unwrap_or(NonZeroU16::MIN);
        let dy = NonZeroU32::from(dy16);
        let d = NonZeroU32::new(dy.get() << (BITS + 1)).unwrap_or(NonZeroU32::MIN);
        // The edge crosses the row `X = N / dy` doubled units right of the centre, at least
        // `-s` (no vertex lies left of column 0), so `N > -D` and `N + D - 1 >= 0`: the column
        // `ceil(N / D) = floor((N + D - 1) / D)` by an unsigned division, whose remainder `r`
        // gives `col D - N - D = -1 - r`. Below `66 D <= 2^30`.
        let n = y * dx + x * dy.get() as i32;
        let m = (n + d.get() as i32 - 1) as u32;
        let (col, r) = (m / d, m % d);
        // ceil(dx / dy) the same way, moved up by `2^(BITS + 7) dy` (`dx >= -64 s`): below 2^30.
        let lift = 1 << (BITS + 7);
        let m = (dx - 1 + (dy.get() << (BITS + 7)) as i32) as u32;
        let (q, rs) = (m / dy, m % dy);
        let col_step = q as i32 - lift + 1;
        // col_step D - 2 s dx = 2 s (col_step dy - dx) = 2 s (dy - 1 - rs), in [0, D).
        let rem_step = (dy.get() - 1 - rs) << (BITS + 1);
        let step = (i64::from(rem_step) << 32) + i64::from(col_step);
        let carry = (i64::from(d.get()) << 32) + 1;
        Self {
            packed: (i64::from(-1 - r as i32) << 32) + i64::from(col),
            step,
            fix: if BACK { step - carry } else { carry },
        }
    }

    /// The first column at or right of the edge on the current row, relative to the
    /// triangle's leftmost pixel.
    #[inline(always)]
    pub(crate) fn col(&self) -> i32 {
        self.packed as i32
    }

    /// Moves to the next row.
    #[inline(always)]
    pub(crate) fn step(&mut self) {
        let t = self.packed.wrapping_add(self.step);
        // The remainder reached [0, D): one column back.
        self.packed = if t < 0 {
            t
        } else if BACK {
            self.packed.wrapping_add(self.fix)
        } else {
            t.wrapping_sub(self.fix)
        };
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::setup::{row_order, walk_spans, Sorted};
    use super::*;
    use std::vec::Vec;

    /// Every span of a walk.
    struct Spans(Vec<(i32, i32, i32)>);
    impl SpanSink for Spans {
        type Error = ();
        fn span(&mut self, row: i32, x0: i32, x1: i32) -> Result<(), ()> {
            self.0.push((row, x0, x1));
            Ok(())
        }
    }

    /// Random triangles up to a little past the size limit, on and off a clip area, at every
    /// sub-pixel setting: the small set-up either declines or gives the generic walk's spans,
    /// and the clipped one takes every triangle within the size limit and gives them too. The
    /// triangles the small set-up took, and those only the clipped one took that have spans.
    fn same_spans<const BITS: u32>(seed: u32) -> (usize, usize) {
        let mut x = seed;
        let mut next = |m: u32| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x % m) as i32
        };
        let s = 1i32 << BITS;
        let (mut taken, mut crossed) = (0, 0);
        for _ in 0..40_000 {
            let clip = PixelRect {
                x0: i64::from(next(20)) - 10,
                y0: i64::from(next(20)) - 10,
                x1: i64::from(next(100)) + 20,
                y1: i64::from(next(100)) + 20,
            };
            // Whole pixels now and then, so that vertices fall on rows, columns and centres.
            let w = if next(4) == 0 { s } else { 1 };
            let reach = [4, 16, 70][next(3) as usize] * s;
            let (cx, cy) = (next(100 * s as u32) - 10 * s, next(100 * s as u32) - 10 * s);
            let v = [0, 1, 2].map(|_| {
                SubPoint::<BITS>::raw(
                    (cx + next(reach as u32) - reach / 2) / w * w,
                    (cy + next(reach as u32) - reach / 2) / w * w,
                )
            });
            let mut a = Spans(Vec::new());
            if let Some(t) = Sorted::new(&v) {
                let _ = walk_spans(&t, 1 << BITS, &clip, &mut a);
            }
            // Across the clip area's edges or not: the clipped walk gives the same spans.
            let crossing = Small::crossing(&v, &clip);
            let size = (v.map(|p| p.x), v.map(|p| p.y));
            let extent = |c: [i32; 3]| c.iter().max().unwrap() - c.iter().min().unwrap();
            assert_eq!(
                crossing.is_some(),
                extent(size.0) <= 64 * s && extent(size.1) <= 64 * s,
                "{v:?}"
            );
            if let Some(small) = crossing {
                let mut d = Spans(Vec::new());
                let _ = small.walk_clipped::<_, BITS>(&clip, &mut d);
                assert_eq!(a.0, d.0, "{v:?} {clip:?}");
                crossed += usize::from(Small::new(&v, &clip).is_none() && !a.0.is_empty());
            }
            let Some(small) = Small::new(&v, &clip) else {
                continue;
            };
            taken += 1;
            let (mut b, mut h) = (Spans(Vec::new()), Spans(Vec::new()));
            let _ = small.walk::<_, BITS>(&mut EachSpan(&mut b));
            assert_eq!(a.0, b.0, "{v:?} {clip:?}");
            let _ = small.walk::<_, BITS>(&mut EachSpanHalves(&mut h));
            assert_eq!(a.0, h.0, "{v:?} {clip:?}");
            // Sorted with ties broken by x, as the Gouraud fill sorts: the same spans.
            let keyed = row_order(&v).map(|i| (v[i].x, v[i].y));
            let mut c = Spans(Vec::new());
            let _ = Small::sorted::<BITS>(keyed, &clip)
                .expect("the same bounds")
                .walk::<_, BITS>(&mut EachSpan(&mut c));
            assert_eq!(a.0, c.0, "{v:?} {clip:?}");
        }
        (taken, crossed)
    }

    /// Every triangle with its vertices on a grid of quarter pixels over three by three
    /// pixels, at 2 sub-pixel bits (flat tops and bottoms, vertices on centres and on pixel
    /// edges, centres on edges, every winding), and the same moved by a sub-pixel unit: the
    /// small set-up's spans are the generic walk's.
    #[test]
    fn small_set_up_on_a_grid_gives_the_generic_spans() {
        let clip = PixelRect {
            x0: -2,
            y0: -2,
            x1: 8,
            y1: 8,
        };
        let cut = PixelRect {
            x0: 1,
            y0: 1,
            x1: 2,
            y1: 3,
        };
        let grid: Vec<(i32, i32)> = (0..13 * 13).map(|i| (i % 13, i / 13)).collect();
        let (mut walked, mut cut_walked) = (0usize, 0usize);
        for shift in [0, 1] {
            for &p in &grid {
                for &q in &grid {
                    for &r in &grid {
                        let v = [p, q, r].map(|(x, y)| SubPoint::<2>::raw(x + shift, y));
                        let small = Small::new(&v, &clip).expect("inside");
                        let (mut a, mut b) = (Spans(Vec::new()), Spans(Vec::new()));
                        if let Some(t) = Sorted::new(&v) {
                            let _ = walk_spans(&t, 4, &clip, &mut a);
                        }
                        let _ = small.walk::<_, 2>(&mut EachSpan(&mut b));
                        assert_eq!(a.0, b.0, "{v:?}");
                        let mut h = Spans(Vec::new());
                        let _ = small.walk::<_, 2>(&mut EachSpanHalves(&mut h));
                        assert_eq!(a.0, h.0, "{v:?}");
                        // Cut to the middle pixel column's two lower pixels.
                        let (mut e, mut d) = (Spans(Vec::new()), Spans(Vec::new()));
                        if let Some(t) = Sorted::new(&v) {
                            let _ = walk_spans(&t, 4, &cut, &mut e);
                        }
                        let crossing = Small::crossing(&v, &cut).expect("small");
                        let _ = crossing.walk_clipped::<_, 2>(&cut, &mut d);
                        assert_eq!(e.0, d.0, "{v:?}");
                        cut_walked += usize::from(!e.0.is_empty());
                        walked += usize::from(!a.0.is_empty());
                    }
                }
            }
        }
        // More than half of them cover a centre (measured: 5,288,658 of 9,653,618).
        assert!(walked > 2_700_000, "{walked}");
        // Cut, 2,982,300 still have spans.
        assert!(cut_walked > 1_500_000, "{cut_walked}");
    }

    #[test]
    fn small_set_up_gives_the_generic_spans() {
        for (taken, crossed) in [
            same_spans::<0>(0x1357_9bdf),
            same_spans::<4>(0x2468_ace1),
            same_spans::<8>(0x0bad_f00d),
        ] {
            // Measured: 12,005 / 8,182, 11,839 / 8,381, 11,896 / 8,395.
            assert!(taken > 6_000 && crossed > 4_000, "{taken} {crossed}");
        }
    }

    #[test]
    fn small_set_up_at_its_limits() {
        // 64 pixels wide and tall at 8 sub-pixel bits, with the long edge's numerator at its largest.
        let s = 1 << 8;
        let clip = PixelRect {
            x0: 0,
            y0: 0,
            x1: 100,
            y1: 100,
        };
        for v in [
            [(0, 0), (64 * s, 1), (1, 64 * s)],
            [(64 * s, 0), (0, 64 * s), (64 * s, 64 * s)],
            [(0, 64 * s), (64 * s, 0), (1, 1)],
        ] {
            let v = v.map(|(x, y)| SubPoint::<8>::raw(x + 30 * s, y + 30 * s));
            let small = Small::new(&v, &clip).expect("fits");
            let (mut a, mut b) = (Spans(Vec::new()), Spans(Vec::new()));
            let _ = walk_spans(&Sorted::new(&v).unwrap(), s.into(), &clip, &mut a);
            let _ = small.walk::<_, 8>(&mut EachSpan(&mut b));
            assert_eq!(a.0, b.0);
        }
        // One unit too wide: the generic set-up.
        let v = [(0, 0), (64 * s + 1, 1), (1, 64 * s)].map(|(x, y)| SubPoint::<8>::raw(x, y));
        assert!(Small::new(&v, &clip).is_none());
    }
}
