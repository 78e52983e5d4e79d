//! The report's anti-aliased silhouette section: each pixel of white triangles drawn with
//! `Pipeline::draw_antialiased` (as a fraction of white) against the exact area of the pixel
//! inside them, in `f64` (`fixtures::coverage`). Deterministic and quick (no callgrind).

use fixtures::coverage::{lone_triangles, quads, CoverageError};
use std::fmt::Write as _;

/// Writes the section.
pub fn section(s: &mut String) {
    let _ = writeln!(s, "## Anti-aliased silhouettes\n");
    let _ = writeln!(
        s,
        "`draw_antialiased` blends each pixel a silhouette edge crosses by the fraction of it \
         inside the triangle: each silhouette edge's share of the pixel exactly (the trapezoid \
         of a line across a square, one reciprocal per edge), combined by inclusion and \
         exclusion where two edges cross one pixel. White triangles on black in a 64 x 64 \
         Rgb888 frame, corners on the 1/32-pixel grid (which the identity transforms map \
         exactly), against the area of each pixel inside them clipped in `f64`; random lone \
         triangles (every edge a silhouette) and convex quads of two triangles (the diagonal \
         an interior edge, drawn as without anti-aliasing). Along edges the error is the 8-bit \
         blend's rounding; at a pixel holding a corner where two silhouette edges meet the \
         overlap of the parts outside them is estimated, not clipped. The promise is 1/16 \
         along edges.\n"
    );
    let _ = writeln!(
        s,
        "| triangles | pixels along edges | max | mean | pixels at corners | max | mean | \
         interior pixels not white |"
    );
    let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---:|---:|");
    let row = |s: &mut String, what: &str, e: CoverageError| {
        let mean = |sum: f64, n: u32| sum / f64::from(n.max(1));
        let _ = writeln!(
            s,
            "| {what} | {} | {:.4} | {:.5} | {} | {:.3} | {:.4} | {} |",
            e.edge_pixels,
            e.edge_max,
            mean(e.edge_sum, e.edge_pixels),
            e.corner_pixels,
            e.corner_max,
            mean(e.corner_sum, e.corner_pixels),
            e.interior_wrong
        );
    };
    row(s, "1,000 lone triangles", lone_triangles(0x5eed_0001, 1000));
    row(s, "300 quads", quads(0x5eed_0002, 300));
    let _ = writeln!(s);
}
