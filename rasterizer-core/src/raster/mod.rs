//! The 2D rasterizers: points, lines, triangles and polygons, drawn into any [`crate::target::Surface`].
//!
//! Every rasterizer clips to the surface's clip area before it writes, so out-of-bounds pixels never
//! reach the target, and hands the target whole spans where the primitive has them.

pub(crate) mod edge;
pub(crate) mod fused;
pub mod interp;
pub mod line;
pub mod point;
pub mod polygon;
pub mod triangle;

/// `ceil(n / d)` for `d > 0`.
#[inline]
pub(crate) fn ceil_div_i128(n: i128, d: i128) -> i128 {
    let q = n.div_euclid(d);
    if q * d == n {
        q
    } else {
        q + 1
    }
}
