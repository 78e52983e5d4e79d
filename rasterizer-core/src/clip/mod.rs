//! Clipping: lines against a rectangle, pixel-exact.

pub mod line;
