//! The 2D rasterizers: points, lines, triangles, polygons and sprites, drawn into any
//! [`crate::surface::Surface`].
//!
//! Every rasterizer clips to the surface's clip area before it writes, so out-of-bounds pixels never
//! reach the target, and hands the target whole spans where the primitive has them.

pub(crate) mod edge;
pub(crate) mod fused;
pub mod interp;
pub mod line;
pub mod point;
pub mod polygon;
pub(crate) mod silhouette;
pub mod sprite;
pub mod triangle;
