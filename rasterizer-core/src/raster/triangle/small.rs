//! Set-up for the common 2D case: a triangle that lies inside the clip area and is at most
//! [`SMALL_PIXELS`] pixels wide and tall. Its edge walks are set up in `i32`, in
//! coordinates relative to a pixel corner next to it (one 32-bit division per quotient, which a
//! Cortex-M has an instruction for), and its rows and columns need no clamping to the clip area.
//! It gives exactly the spans of [`super::setup::walk_spans`].

use super::setup::{row_order, SpanSink};
use crate::geom::{PixelRect, SubPoint, GUARD_BAND_PIXELS};

/// The largest width and height, in pixels, of a triangle set up in `i32`.
///
/// Bound: with `E = 64 s <= 2^14` sub-pixel units (`s <= 2^8` the unit), vertices relative to
/// the origin lie within `E + s` of it, so an edge's numerator `(yc2 - 2 ya) dx + (2 xa - s) dy`
/// stays below `4 E^2 + 5 s E < 2^30.1`, its divisor `2 s dy` below `2^23`, the doubled area
/// below `2^29`, and the spans are at most 65 pixels long.
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
    /// Twice the signed area, as `Sorted::cross`; zero for a triangle with no area.
    cross: i32,
}

/// `ceil(n / d)` for `d >= 1` (a smaller `d` is taken as 1, never met by a walked edge).
#[inline(always)]
fn ceil_div(n: i32, d: i32) -> i32 {
    let d = d.max(1);
    n / d + i32::from(n % d > 0)
}

/// The first row whose sample `r s + s/2` lies at or below `y`, for `|y|` inside the guard band.
#[inline(always)]
fn row_at_or_below<const BITS: u32>(y: i32) -> i32 {
    -(((1 << BITS) - 2 * y) >> (BITS + 1))
}

impl Small {
    /// Sorts the triangle as `Sorted::new` does; `None` unless it lies inside `clip` and the
    /// guard band and within [`SMALL_PIXELS`] each way.
    #[inline(always)]
    pub fn new<const BITS: u32>(v: &[SubPoint<BITS>; 3], clip: &PixelRect) -> Option<Self> {
        #[allow(clippy::let_unit_value)]
        let () = SubPoint::<BITS>::VALID;
        // The same order as `Sorted::new`, so both see the same edges.
        let p = row_order(v).map(|i| (v[i].x, v[i].y));
        let (xmin, xmax) = (
            i64::from(p[0].0.min(p[1].0).min(p[2].0)),
            i64::from(p[0].0.max(p[1].0).max(p[2].0)),
        );
        let (ymin, ymax) = (i64::from(p[0].1), i64::from(p[2].1));
        let s = 1i64 << BITS;
        let band = i64::from(GUARD_BAND_PIXELS) << BITS;
        // Inside the clip area, every span lies between its columns and rows (a centre inside
        // the triangle lies between its extreme vertices); inside the guard band, the generic
        // path would draw it too.
        let fits = xmin >= clip.x0 * s
            && xmax <= clip.x1 * s
            && ymin >= clip.y0 * s
            && ymax <= clip.y1 * s
            && xmin >= -band
            && xmax <= band
            && ymin >= -band
            && ymax <= band
            && xmax - xmin <= SMALL_PIXELS << BITS
            && ymax - ymin <= SMALL_PIXELS << BITS;
        if !fits {
            return None;
        }
        let (top, mid, bottom) = (
            row_at_or_below::<BITS>(p[0].1),
            row_at_or_below::<BITS>(p[1].1),
            row_at_or_below::<BITS>(p[2].1),
        );
        let cross = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
        Some(Self {
            p,
            ox: p[0].0.min(p[1].0).min(p[2].0) >> BITS,
            top,
            mid,
            bottom,
            cross,
        })
    }

    /// Hands `sink` every non-empty span of the triangle, top to bottom: those of
    /// [`super::setup::walk_spans`], with no clamping.
    #[inline(always)]
    pub fn walk<K: SpanSink, const BITS: u32>(&self, sink: &mut K) -> Result<(), K::Error> {
        if self.cross == 0 || self.top >= self.bottom {
            return Ok(());
        }
        let s = 1i32 << BITS;
        // Relative to the corner (ox, top), pixel centres sit at odd multiples of s/2.
        let (x0, y0) = (self.ox << BITS, self.top << BITS);
        let [a, b, c] = self.p.map(|(x, y)| (x - x0, y - y0));
        let ox = self.ox;
        let mut long = Edge::new(a, c, s, s, ox);
        let short_is_left = self.cross < 0;
        if self.top < self.mid {
            let upper = Edge::new(a, b, s, s, ox);
            // As in `walk_spans`: the walks copied into left and right, the long one back.
            let (mut l, mut r) = if short_is_left {
                (upper, long)
            } else {
                (long, upper)
            };
            rows(&mut l, &mut r, self.top..self.mid, sink)?;
            long = if short_is_left { r } else { l };
        }
        if self.mid < self.bottom {
            let lower = Edge::new(b, c, s, 2 * ((self.mid - self.top) << BITS) + s, ox);
            let (mut l, mut r) = if short_is_left {
                (lower, long)
            } else {
                (long, lower)
            };
            rows(&mut l, &mut r, self.mid..self.bottom, sink)?;
        }
        Ok(())
    }
}

/// The spans of `rows` between two edge walks.
#[inline(always)]
fn rows<K: SpanSink>(
    left: &mut Edge,
    right: &mut Edge,
    rows: core::ops::Range<i32>,
    sink: &mut K,
) -> Result<(), K::Error> {
    for row in rows {
        let (x0, x1) = (left.col(), right.col());
        if x0 < x1 {
            sink.span(row, x0, x1)?;
        }
        left.step();
        right.step();
    }
    Ok(())
}

/// The column walk of one edge, as `raster/edge.rs`'s `EdgeWalk` (whose notation this follows)
/// but set up in `i32` and packed as `(col + 1) 2^32 + rem`, `rem` in `[-D, 0)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Edge {
    packed: i64,
    step: i64,
    /// `2^32 + D`: one column back and one `D` off the remainder.
    carry: i64,
}

impl Edge {
    /// The walk of edge `a -> b` (local coordinates) from the row whose doubled sample is `yc2`,
    /// columns offset by `ox`.
    #[inline(always)]
    pub(crate) fn new(a: (i32, i32), b: (i32, i32), s: i32, yc2: i32, ox: i32) -> Self {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let d = 2 * s * dy;
        let n = (yc2 - 2 * a.1) * dx + (2 * a.0 - s) * dy;
        let col = ceil_div(n, d);
        let col_step = ceil_div(dx, dy);
        // col D - N - D in [-D, 0) and col_step D - 2 s dx in [0, D): below 2^24 in magnitude.
        let rem = col * d - n - d;
        let rem_step = col_step * d - 2 * s * dx;
        Self {
            packed: (i64::from(col + ox + 1) << 32) + i64::from(rem),
            step: (i64::from(col_step) << 32) + i64::from(rem_step),
            carry: (1 << 32) + i64::from(d),
        }
    }

    #[inline(always)]
    pub(crate) fn col(&self) -> i32 {
        (self.packed >> 32) as i32
    }

    #[inline(always)]
    pub(crate) fn step(&mut self) {
        self.packed = self.packed.wrapping_add(self.step);
        // The remainder's sign bit clear: it reached [0, D), so one column back.
        if self.packed & (1 << 31) == 0 {
            self.packed = self.packed.wrapping_sub(self.carry);
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::setup::{walk_spans, Sorted};
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
    /// sub-pixel setting: the small set-up either declines or gives the generic walk's spans.
    fn same_spans<const BITS: u32>(seed: u32) -> usize {
        let mut x = seed;
        let mut next = |m: u32| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x % m) as i32
        };
        let s = 1i32 << BITS;
        let mut taken = 0;
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
            let Some(small) = Small::new(&v, &clip) else {
                continue;
            };
            taken += 1;
            let (mut a, mut b) = (Spans(Vec::new()), Spans(Vec::new()));
            if let Some(t) = Sorted::new(&v) {
                let _ = walk_spans(&t, 1 << BITS, &clip, &mut a);
            }
            let _ = small.walk::<_, BITS>(&mut b);
            assert_eq!(a.0, b.0, "{v:?} {clip:?}");
        }
        taken
    }

    #[test]
    fn small_set_up_gives_the_generic_spans() {
        assert!(same_spans::<0>(0x1357_9bdf) > 5_000);
        assert!(same_spans::<4>(0x2468_ace1) > 5_000);
        assert!(same_spans::<8>(0x0bad_f00d) > 5_000);
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
            let _ = small.walk::<_, 8>(&mut b);
            assert_eq!(a.0, b.0);
        }
        // One unit too wide: the generic set-up.
        let v = [(0, 0), (64 * s + 1, 1), (1, 64 * s)].map(|(x, y)| SubPoint::<8>::raw(x, y));
        assert!(Small::new(&v, &clip).is_none());
    }
}
