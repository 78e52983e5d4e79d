//! Clipping: lines against a rectangle, pixel-exact; triangles in homogeneous clip space.

pub mod line;
pub mod polygon;
