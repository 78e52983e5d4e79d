//! Cohen-Sutherland clipping of a pixel line against a rectangle, exact to the pixel.
//!
//! The classic algorithm moves an endpoint to where the ideal line meets a clip edge, which lights
//! different pixels from the unclipped line once the new endpoint is rounded. Here the outcodes pick
//! the trivial accept and reject cases and the edges to clip against, as in Cohen-Sutherland, but each
//! edge narrows the range of Bresenham *steps* instead: on the major axis by subtraction, on the minor
//! axis by solving `floor((2kB + A - t) / 2A) = q` for `k` exactly in `i128`. The clipped walk then
//! lights exactly the unclipped line's pixels that lie inside the rectangle, for any `i32` endpoints.

use crate::geom::line::{Line, LinePoints};
use crate::geom::PixelRect;
use crate::wide;
use embedded_graphics_core::geometry::Point;
use embedded_graphics_core::primitives::Rectangle;

const LEFT: u8 = 1;
const RIGHT: u8 = 2;
const TOP: u8 = 4;
const BOTTOM: u8 = 8;

/// Cohen-Sutherland outcode of `p` against `r`.
#[inline]
fn outcode(p: Point, r: &PixelRect) -> u8 {
    let (x, y) = (i64::from(p.x), i64::from(p.y));
    let mut code = 0;
    if x < r.x0 {
        code |= LEFT;
    } else if x >= r.x1 {
        code |= RIGHT;
    }
    if y < r.y0 {
        code |= TOP;
    } else if y >= r.y1 {
        code |= BOTTOM;
    }
    code
}

/// The first and last step of `line` whose pixel lies inside `area`, or `None` when none does.
#[inline]
pub(crate) fn clip_steps(line: &Line, area: &Rectangle) -> Option<(i64, i64)> {
    clip_steps_in(line, PixelRect::from_rectangle(area))
}

/// [`clip_steps`] for a pixel rectangle, which may reach past the `i32` range (an area grown
/// around a clip area at the limits). Always inlined so that `draw_line`'s clipping compiles as
/// one function, as it did before this was split out.
#[inline(always)]
pub(crate) fn clip_steps_in(line: &Line, r: PixelRect) -> Option<(i64, i64)> {
    if r.is_empty() {
        return None;
    }
    let (c0, c1) = (outcode(line.start, &r), outcode(line.end, &r));
    if c0 | c1 == 0 {
        return Some((0, line.a));
    }
    if c0 & c1 != 0 {
        return None;
    }
    let (mut k0, mut k1) = (0i64, line.a);
    // Major axis: the walk moves by +1 each step, so each bound is a subtraction.
    let (m_lo, m_hi, m_start) = if line.major_x {
        (r.x0, r.x1 - 1, i64::from(line.start.x))
    } else {
        (r.y0, r.y1 - 1, i64::from(line.start.y))
    };
    k0 = k0.max(m_lo - m_start);
    k1 = k1.min(m_hi - m_start);
    // Minor axis: the unsigned offset o(k) must stay within [o_lo, o_hi].
    let (n_lo, n_hi, n_start) = if line.major_x {
        (r.y0, r.y1 - 1, i64::from(line.start.y))
    } else {
        (r.x0, r.x1 - 1, i64::from(line.start.x))
    };
    let (o_lo, o_hi) = if line.minor_step > 0 {
        (n_lo - n_start, n_hi - n_start)
    } else {
        (n_start - n_hi, n_start - n_lo)
    };
    if o_hi < 0 {
        return None;
    }
    if o_lo > 0 {
        k0 = k0.max(first_step_reaching(line, o_lo)?);
    }
    if let Some(k) = last_step_within(line, o_hi) {
        k1 = k1.min(k);
    }
    (k0 <= k1).then_some((k0, k1))
}

/// The smallest step `k` with `o(k) >= q` (`q >= 1`), or `None` if the line never gets there.
fn first_step_reaching(line: &Line, q: i64) -> Option<i64> {
    if line.b == 0 {
        return None;
    }
    let (a, b, t) = (
        i128::from(line.a),
        i128::from(line.b),
        i128::from(line.tie()),
    );
    let k = ceil_div_i128(2 * a * i128::from(q) - a + t, 2 * b);
    (k <= a).then_some(k as i64)
}

/// The largest step `k` with `o(k) <= q` (`q >= 0`), or `None` when every step qualifies.
fn last_step_within(line: &Line, q: i64) -> Option<i64> {
    if line.b == 0 {
        return None;
    }
    let (a, b, t) = (
        i128::from(line.a),
        i128::from(line.b),
        i128::from(line.tie()),
    );
    let k = ceil_div_i128(2 * a * i128::from(q) + a + t, 2 * b) - 1;
    (k < a).then_some(k as i64)
}

impl Line {
    /// The pixels of the line that lie inside `area`, in walk order, found by Cohen-Sutherland
    /// clipping ([`crate::clip::line`]); `None` when no pixel is inside.
    #[inline]
    pub fn clipped(&self, area: &Rectangle) -> Option<LinePoints> {
        let (k0, k1) = clip_steps(self, area)?;
        Some(if k0 == 0 && k1 == self.a {
            self.points()
        } else {
            self.walk_from(k0, k1)
        })
    }

    /// The step range of the clipped walk: the first and last step inside `area`.
    pub(crate) fn clipped_steps(&self, area: &Rectangle) -> Option<(i64, i64)> {
        clip_steps(self, area)
    }

    /// [`Line::clipped_steps`] for a pixel rectangle, which may reach past the `i32` range.
    pub(crate) fn clipped_steps_in(&self, area: &PixelRect) -> Option<(i64, i64)> {
        clip_steps_in(self, *area)
    }
}

/// `ceil(n / d)` for `d > 0`.
#[inline]
fn ceil_div_i128(n: i128, d: i128) -> i128 {
    let q = wide::div_floor_i128(n, d);
    if q * d == n {
        q
    } else {
        q + 1
    }
}
