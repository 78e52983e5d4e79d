//! A pixel line as integer Bresenham walks it, in every octant, both endpoints included.
//!
//! A line is always walked from the endpoint with the smaller coordinate on its major axis (x when
//! `|dx| >= |dy|`, else y), so `line(a, b)` and `line(b, a)` light the same pixels. At each step along
//! the major axis the pixel is the one nearest the ideal line; when the ideal line passes exactly
//! half-way between two pixels, the **tie goes to the smaller minor coordinate** (the upper pixel of
//! an x-major line, the left pixel of a y-major line).
//!
//! In numbers: with `A = |major delta|`, `B = |minor delta|` and the minor axis moving by `s = ±1`,
//! step `k` (0 ..= A) lights minor offset `s * floor((2kB + A - t) / 2A)`, `t = 1` when `s = +1` and
//! `t = 0` when `s = -1`. Bresenham keeps the remainder of that division; every quantity fits `i64`
//! for any `i32` endpoints (`2A < 2^33`), and clipping's set-up uses `i128`.

use embedded_graphics_core::geometry::Point;

/// A line between two pixels, set up for walking.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Line {
    /// The endpoint with the smaller major coordinate: the walk starts here.
    pub(crate) start: Point,
    /// The other endpoint.
    pub(crate) end: Point,
    /// True when x is the major axis.
    pub(crate) major_x: bool,
    /// |major delta|.
    pub(crate) a: i64,
    /// |minor delta|.
    pub(crate) b: i64,
    /// Minor-axis direction, +1 or -1.
    pub(crate) minor_step: i32,
    /// True when the walk was reversed: `start` is the caller's second endpoint.
    pub(crate) reversed: bool,
}

impl Line {
    /// Sets up the line from `a` to `b` (any `i32` coordinates).
    pub fn new(a: Point, b: Point) -> Self {
        let dx = i64::from(b.x) - i64::from(a.x);
        let dy = i64::from(b.y) - i64::from(a.y);
        let major_x = dx.abs() >= dy.abs();
        let major_delta = if major_x { dx } else { dy };
        let reversed = major_delta < 0;
        let (start, end) = if reversed { (b, a) } else { (a, b) };
        let minor_delta = if major_x {
            i64::from(end.y) - i64::from(start.y)
        } else {
            i64::from(end.x) - i64::from(start.x)
        };
        Self {
            start,
            end,
            major_x,
            a: major_delta.abs(),
            b: minor_delta.abs(),
            minor_step: if minor_delta < 0 { -1 } else { 1 },
            reversed,
        }
    }

    /// The endpoint the walk starts from (the smaller major coordinate).
    pub fn start(&self) -> Point {
        self.start
    }

    /// The endpoint the walk ends at.
    pub fn end(&self) -> Point {
        self.end
    }

    /// Number of pixels: `max(|dx|, |dy|) + 1`.
    pub fn pixel_count(&self) -> u64 {
        self.a as u64 + 1
    }

    /// The rounding tie term `t` of the module doc.
    #[inline]
    pub(crate) fn tie(&self) -> i64 {
        i64::from(self.minor_step > 0)
    }

    /// Minor offset (unsigned) of step `k`.
    pub(crate) fn minor_offset(&self, k: i64) -> i64 {
        if self.a == 0 {
            return 0;
        }
        let num = 2 * i128::from(k) * i128::from(self.b) + i128::from(self.a - self.tie());
        (num / (2 * i128::from(self.a))) as i64
    }

    /// The pixel of step `k` (0 ..= A), in `i64` so that it cannot overflow.
    pub(crate) fn point_at(&self, k: i64) -> (i64, i64) {
        let o = self.minor_offset(k) * i64::from(self.minor_step);
        let (sx, sy) = (i64::from(self.start.x), i64::from(self.start.y));
        if self.major_x {
            (sx + k, sy + o)
        } else {
            (sx + o, sy + k)
        }
    }

    /// All pixels of the line, from [`Line::start`] to [`Line::end`].
    ///
    /// The same walk as `walk_from(0, A)`, set up without its general cases (a start inside the
    /// line, an end past the `i32` range), since every unclipped line and every line inside its clip
    /// area starts here.
    #[inline]
    pub fn points(&self) -> LinePoints {
        let (step_x, step_y) = if self.major_x {
            (1, self.minor_step)
        } else {
            (self.minor_step, 1)
        };
        LinePoints {
            x: self.start.x,
            y: self.start.y,
            remaining: self.a as u64 + 1,
            major_x: self.major_x,
            step_x,
            step_y,
            // The remainder of (A - t) / 2A, whose quotient is 0 (0 for a one-pixel line).
            err: if self.a == 0 { 0 } else { self.a - self.tie() },
            two_minor: 2 * self.b,
            two_major: 2 * self.a,
            end: Some((self.end.x, self.end.y)),
        }
    }

    /// True when `p` is one of the line's pixels.
    pub fn contains(&self, p: Point) -> bool {
        let (major, minor, m0, n0) = if self.major_x {
            (p.x, p.y, self.start.x, self.start.y)
        } else {
            (p.y, p.x, self.start.y, self.start.x)
        };
        let k = i64::from(major) - i64::from(m0);
        if !(0..=self.a).contains(&k) {
            return false;
        }
        let o = self.minor_offset(k) * i64::from(self.minor_step);
        i64::from(n0) + o == i64::from(minor)
    }

    /// A walk over steps `k0 ..= k1` (both within 0 ..= A, `k0 <= k1`).
    pub(crate) fn walk_from(&self, k0: i64, k1: i64) -> LinePoints {
        let two_major = 2 * self.a;
        // Remainder of (2 k0 B + A - t) / 2A; its quotient is already in point_at. At k0 = 0 (every
        // unclipped start) the quotient is 0 and the remainder A - t, with no 128-bit division.
        let ((x, y), err) = if self.a == 0 {
            (self.point_at(k0), 0)
        } else if k0 == 0 {
            let start = (i64::from(self.start.x), i64::from(self.start.y));
            (start, self.a - self.tie())
        } else {
            let num = 2 * i128::from(k0) * i128::from(self.b) + i128::from(self.a - self.tie());
            (self.point_at(k0), (num % i128::from(two_major)) as i64)
        };
        let (step_x, step_y) = if self.major_x {
            (1, self.minor_step)
        } else {
            (self.minor_step, 1)
        };
        // The last pixel: the endpoint itself unless the walk was clipped short.
        let end = if k1 == self.a {
            Some((self.end.x, self.end.y))
        } else {
            let (ex, ey) = self.point_at(k1);
            i32::try_from(ex).ok().zip(i32::try_from(ey).ok())
        };
        LinePoints {
            end,
            x: x as i32,
            y: y as i32,
            remaining: (k1 - k0 + 1) as u64,
            major_x: self.major_x,
            step_x,
            step_y,
            err,
            two_minor: 2 * self.b,
            two_major,
        }
    }
}

/// The pixels of a line walk, in order: an iterator of [`Point`]s.
///
/// Made by [`Line::points`] and [`Line::clipped`]; surfaces with a fast path read its state directly.
#[derive(Debug, Clone)]
pub struct LinePoints {
    pub(crate) x: i32,
    pub(crate) y: i32,
    pub(crate) remaining: u64,
    pub(crate) major_x: bool,
    pub(crate) step_x: i32,
    pub(crate) step_y: i32,
    /// Bresenham remainder, `0 <= err < two_major`.
    pub(crate) err: i64,
    pub(crate) two_minor: i64,
    pub(crate) two_major: i64,
    /// The last pixel, when it is in the `i32` range.
    pub(crate) end: Option<(i32, i32)>,
}

impl LinePoints {
    /// Pixels left to yield.
    pub fn remaining(&self) -> u64 {
        self.remaining
    }

    /// The last pixel the walk will yield, or `None` when it is empty (or ends beyond the `i32`
    /// range, which an unclipped walk between extreme endpoints can).
    pub fn last_pixel(&self) -> Option<(i32, i32)> {
        (self.remaining > 0).then_some(self.end)?
    }
}

impl Iterator for LinePoints {
    type Item = Point;

    #[inline]
    fn next(&mut self) -> Option<Point> {
        if self.remaining == 0 {
            return None;
        }
        self.remaining -= 1;
        let p = Point::new(self.x, self.y);
        // The step after the last pixel may leave the i32 range; it is never yielded.
        self.err += self.two_minor;
        let carry = self.err >= self.two_major;
        if carry {
            self.err -= self.two_major;
        }
        if self.major_x {
            self.x = self.x.wrapping_add(self.step_x);
            if carry {
                self.y = self.y.wrapping_add(self.step_y);
            }
        } else {
            self.y = self.y.wrapping_add(self.step_y);
            if carry {
                self.x = self.x.wrapping_add(self.step_x);
            }
        }
        Some(p)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = usize::try_from(self.remaining).unwrap_or(usize::MAX);
        (n, usize::try_from(self.remaining).ok())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use std::format;

    #[test]
    fn points_is_the_general_walk_from_the_start() {
        let coords = [
            i32::MIN,
            i32::MIN + 1,
            -70_000,
            -3,
            -1,
            0,
            1,
            2,
            5,
            9,
            70_001,
            i32::MAX,
        ];
        for &x0 in &coords {
            for &y0 in &coords {
                for &(x1, y1) in &[
                    (0, 0),
                    (7, -2),
                    (-5, 11),
                    (i32::MAX, 3),
                    (4, i32::MIN),
                    (x0, y0),
                ] {
                    let line = Line::new(Point::new(x0, y0), Point::new(x1, y1));
                    // Every field of the walk, through its Debug form.
                    assert_eq!(
                        format!("{:?}", line.points()),
                        format!("{:?}", line.walk_from(0, line.a)),
                        "{x0},{y0} -> {x1},{y1}"
                    );
                }
            }
        }
    }
}
