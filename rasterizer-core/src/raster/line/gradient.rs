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
    let colors = (k0..=k1).map(move |k| {
        if span == 0 {
            return S::Color::from_channels(c_start);
        }
        let mut c = [0u8; 4];
        for i in 0..S::Color::COUNT {
            let (c0, c1) = (i64::from(c_start[i]), i64::from(c_end[i]));
            // |numerator| < 2^8 * 2^34: fits i64.
            let num = 2 * c0 * span + 2 * (c1 - c0) * k + span;
            c[i] = num.div_euclid(2 * span) as u8;
        }
        S::Color::from_channels(c)
    });
    surface.draw_iter(points.zip(colors).map(|(p, c)| Pixel(p, c)))
}
