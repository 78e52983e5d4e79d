//! The same scenes drawn with embedded-graphics 0.8 primitives, for comparison in the same run.
//!
//! Included with `#[path]` by `benches/scenes2d.rs` and `examples/count2d.rs` (embedded-graphics is a
//! dev-dependency, so this cannot live in the library).

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Line, PrimitiveStyle, Triangle};
use fixtures::scenes::{LineSeg, Tri};

/// Draws L1: one-pixel stroked `Line`s.
pub fn draw_lines_eg<D: DrawTarget<Color = Rgb565>>(
    d: &mut D,
    lines: &[LineSeg],
) -> Result<(), D::Error> {
    for l in lines {
        Line::new(l.a, l.b)
            .into_styled(PrimitiveStyle::with_stroke(l.color, 1))
            .draw(d)?;
    }
    Ok(())
}

/// Draws T1 or T2: filled `Triangle`s with no stroke.
pub fn draw_triangles_eg<D: DrawTarget<Color = Rgb565>>(
    d: &mut D,
    tris: &[Tri],
) -> Result<(), D::Error> {
    for t in tris {
        let [a, b, c] = t.px;
        Triangle::new(a, b, c)
            .into_styled(PrimitiveStyle::with_fill(t.color))
            .draw(d)?;
    }
    Ok(())
}
