//! The report's blending and anti-aliasing section: the integer blend against the f64 blend at
//! each channel depth, and the coverage of anti-aliased lines of each width against the exact
//! area the ideal line covers of each pixel. Deterministic and quick (no scenes, no callgrind).

use rasterizer_core::color::blend_channel;
use rasterizer_core::prelude::*;
use std::fmt::Write as _;

/// Max and mean of |integer blend - f64 blend| over every source, destination and opacity at a
/// channel depth with `max` as its largest value, in steps of that channel.
fn blend_error(max: u8) -> (f64, f64) {
    let (mut worst, mut sum, mut n) = (0.0f64, 0.0f64, 0u64);
    for a in 0..=255u8 {
        for s in 0..=max {
            for d in 0..=max {
                let f =
                    (f64::from(s) * f64::from(a) + f64::from(d) * (255.0 - f64::from(a))) / 255.0;
                let e = (f64::from(blend_channel(s, d, a)) - f).abs();
                worst = worst.max(e);
                sum += e;
                n += 1;
            }
        }
    }
    (worst, sum / n as f64)
}

/// The part of a convex polygon on the side `n . p <= c` of a line (Sutherland-Hodgman).
fn clip_polygon(poly: &[(f64, f64)], n: (f64, f64), c: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(poly.len() + 2);
    let side = |p: (f64, f64)| n.0 * p.0 + n.1 * p.1 - c;
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        let (sp, sq) = (side(p), side(q));
        if sp <= 0.0 {
            out.push(p);
        }
        if (sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0) {
            let t = sp / (sp - sq);
            out.push((p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1)));
        }
    }
    out
}

/// The area of a polygon (the shoelace formula).
fn area(poly: &[(f64, f64)]) -> f64 {
    let mut a = 0.0;
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        a += p.0 * q.1 - q.0 * p.1;
    }
    a.abs() / 2.0
}

/// The exact coverage of every pixel of a `w` x `h` screen by the line from `a` to `b` (pixel
/// centres) `width` pixels wide: the strip within `width / 2` of the ideal line, over the columns
/// (steps of the major axis) from `a` to `b`, as the rasterizer cuts its ends.
fn exact_coverage(w: i32, h: i32, a: Point, b: Point, width: f64) -> Vec<f64> {
    let (dx, dy) = (f64::from(b.x - a.x), f64::from(b.y - a.y));
    let len = (dx * dx + dy * dy).sqrt();
    let major_x = dx.abs() >= dy.abs();
    // The unit normal; a point p is inside when |n . (p - a)| <= width / 2.
    let n = if len == 0.0 {
        (0.0, 1.0)
    } else {
        (-dy / len, dx / len)
    };
    let c0 = n.0 * f64::from(a.x) + n.1 * f64::from(a.y);
    let (m_lo, m_hi) = if major_x {
        (a.x.min(b.x), a.x.max(b.x))
    } else {
        (a.y.min(b.y), a.y.max(b.y))
    };
    let mut out = vec![0.0; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let m = if major_x { x } else { y };
            if m < m_lo || m > m_hi {
                continue;
            }
            let (fx, fy) = (f64::from(x), f64::from(y));
            let square = [
                (fx - 0.5, fy - 0.5),
                (fx + 0.5, fy - 0.5),
                (fx + 0.5, fy + 0.5),
                (fx - 0.5, fy + 0.5),
            ];
            let p = clip_polygon(&square, n, c0 + width / 2.0);
            let p = clip_polygon(&p, (-n.0, -n.1), -(c0 - width / 2.0));
            out[(y * w + x) as usize] = area(&p);
        }
    }
    out
}

/// Coverage errors of anti-aliased lines `width` wide against the exact area: max and mean
/// |ours - exact| over the pixels either side covers, in 255ths, and the total ink's relative
/// error (the sum of the coverages against the exact area), over a fixed set of random lines.
fn aa_error(width: u32) -> (f64, f64, f64) {
    let (w, h) = (96i32, 72i32);
    let mut seed = 0x1234_5678u32;
    let mut next = |n: i32| {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        (seed % n as u32) as i32
    };
    let (mut worst, mut sum, mut n, mut ink, mut exact_ink) = (0.0f64, 0.0, 0u64, 0.0, 0.0);
    for _ in 0..200 {
        // Endpoints well inside, so no part of the line is clipped.
        let a = Point::new(12 + next(w - 24), 12 + next(h - 24));
        let b = Point::new(12 + next(w - 24), 12 + next(h - 24));
        let mut buf = vec![0u8; (w * h) as usize];
        let mut fb = Framebuffer::<Gray8>::new(&mut buf, w as u32, h as u32).expect("a valid size");
        // White over black blends to the coverage itself.
        let Ok(()) = draw_line_aa_wide(&mut fb, a, b, width, Gray8::WHITE) else {
            continue;
        };
        let want = exact_coverage(w, h, a, b, f64::from(width));
        for (&got, &f) in buf.iter().zip(&want) {
            if got == 0 && f == 0.0 {
                continue;
            }
            let e = (f64::from(got) - 255.0 * f).abs();
            worst = worst.max(e);
            sum += e;
            n += 1;
            ink += f64::from(got) / 255.0;
            exact_ink += f;
        }
    }
    (worst, sum / n as f64, 100.0 * (ink - exact_ink) / exact_ink)
}

/// Writes the section.
pub fn section(s: &mut String) {
    let _ = writeln!(s, "## Blending and anti-aliased lines\n");
    let _ = writeln!(
        s,
        "Translucent drawing (`Translucent`, `fill_triangle_alpha`, `draw_line_alpha`) blends \
         each channel at its own depth with `color::blend`, in integers: the error against the \
         f64 blend `(src a + dst (255 - a)) / 255`, over every source, destination and opacity, \
         in steps of the channel.\n"
    );
    let _ = writeln!(s, "| channel depth | formats | max error | mean error |");
    let _ = writeln!(s, "|---|---|---:|---:|");
    for (bits, max, formats) in [
        (5, 31u8, "Rgb565 red and blue, Rgb555"),
        (6, 63, "Rgb565 green, Rgb666"),
        (8, 255, "Rgb888, Gray8"),
    ] {
        let (worst, mean) = blend_error(max);
        let _ = writeln!(s, "| {bits} bits | {formats} | {worst:.4} | {mean:.4} |");
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "Anti-aliased lines (`draw_line_aa`, width 1; `draw_line_aa_wide`) against the exact \
         area of each pixel inside the ideal line (the strip `width` pixels across, its ends cut \
         square to the major axis at the endpoint pixels' outer edges, as drawn), over 200 random \
         lines on a 96x72 screen (xorshift32 seeded 0x12345678): per pixel in 255ths, and the \
         error of the total coverage. Width 1 is Wu's line, whose column of one pixel is narrower \
         than the line across diagonals; wider lines take the line's own cross-section and err \
         only where its edges cross a pixel's corners.\n"
    );
    let _ = writeln!(
        s,
        "| width | max error (255ths) | mean error (255ths) | total coverage error |"
    );
    let _ = writeln!(s, "|---:|---:|---:|---:|");
    for width in [1u32, 2, 3, 5] {
        let (worst, mean, ink) = aa_error(width);
        let _ = writeln!(s, "| {width} | {worst:.1} | {mean:.2} | {ink:+.2} % |");
    }
    let _ = writeln!(s);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_coverage_of_an_axis_aligned_line_is_its_rows() {
        let c = exact_coverage(5, 5, Point::new(0, 2), Point::new(4, 2), 2.0);
        for x in 0..5 {
            assert_eq!(c[(5 + x) as usize], 0.5);
            assert_eq!(c[(10 + x) as usize], 1.0);
            assert_eq!(c[(15 + x) as usize], 0.5);
            assert_eq!(c[x as usize], 0.0);
        }
    }

    /// docs/ACCURACY.md holds the section as this code writes it.
    #[test]
    fn accuracy_md_has_the_current_section() {
        let mut s = String::new();
        section(&mut s);
        crate::accuracy::assert_report_holds(&s);
    }
}
