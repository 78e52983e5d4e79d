//! Colour-interpolated lines.
//!
//! Step `k` of `A` gets, per channel, `round((c0 (A - k) + c1 k) / A)` with halves rounded up. The
//! expression is symmetric in the two ends, so the line drawn from `b` to `a` gets the same colours,
//! and the endpoints get exactly their own colours.

use super::Line;
use crate::color::Channels;
use crate::surface::Surface;
use embedded_graphics_core::geometry::Point;
use embedded_graphics_core::Pixel;

/// Draws the line from `a` to `b` with its colour interpolated from `color_a` to `color_b`, clipped
/// to the surface's clip area. Same pixels as [`super::draw_line`].
pub fn draw_line_gradient<S>(
    surface: &mut S,
    a: Point,
    b: Point,
    color_a: S::Color,
    color_b: S::Color,
) -> Result<(), S::Error>
where
    S: Surface,
    S::Color: Channels,
{
    let line = Line::new(a, b);
    let Some((k0, k1)) = line.clipped_steps(&surface.clip_area()) else {
        return Ok(());
    };
    let (c_start, c_end) = if line.reversed {
        (color_b.to_channels(), color_a.to_channels())
    } else {
        (color_a.to_channels(), color_b.to_channels())
    };
    let span = line.a;
    let points = line.walk_from(k0, k1);
    // Each channel is `floor(N(k) / 2A)` with `N(k) = 2 c0 A + A + 2 (c1 - c0) k`, which grows by
    // a constant per step: walked as quotient and remainder from two divisions at the first step,
    // so that no pixel divides (a 64-bit division is a library call on a Cortex-M).
    let mut walks = [Channel::default(); 4];
    if span > 0 {
        let d = 2 * span;
        for (w, (&c0, &c1)) in walks.iter_mut().zip(c_start.iter().zip(&c_end)) {
            let (c0, c1) = (i64::from(c0), i64::from(c1));
            // Bound: A < 2^33 and k0 <= A, so |N(k0)| < 2 * 2^8 * 2^34 = 2^43.
            let (q, r) =
                crate::wide::divmod_floor_i64(2 * c0 * span + 2 * (c1 - c0) * k0 + span, d);
            let (dq, dr) = crate::wide::divmod_floor_i64(2 * (c1 - c0), d);
            *w = Channel { q, r, dq, dr, d };
        }
    }
    let colors = (k0..=k1).map(move |_| {
        if span == 0 {
            return S::Color::from_channels(c_start);
        }
        let mut c = [0u8; 4];
        for (c, w) in c.iter_mut().zip(walks.iter_mut()).take(S::Color::COUNT) {
            // The quotient at a step of the line lies between the two end colours.
            *c = w.q as u8;
            w.step();
        }
        S::Color::from_channels(c)
    });
    surface.draw_iter(points.zip(colors).map(|(p, c)| Pixel(p, c)))
}

/// One channel's `floor(N / d)` as quotient `q` and remainder `r` in `0..d`, `N` growing by
/// `dq d + dr` (`dr` in `0..d`) per step.
#[derive(Debug, Clone, Copy, Default)]
struct Channel {
    q: i64,
    r: i64,
    dq: i64,
    dr: i64,
    d: i64,
}

impl Channel {
    #[inline(always)]
    fn step(&mut self) {
        // Past the last step the values are not used; |q| stays below 2^9 + 2^8, no overflow.
        self.q += self.dq;
        self.r += self.dr;
        if self.r >= self.d {
            self.r -= self.d;
            self.q += 1;
        }
    }
}
