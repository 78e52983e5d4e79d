//! The M1 scene that both builds draw: Suzanne's packed mesh and the benchmarks' camera
//! (`fixtures::scenes3d`).

use core::hint::black_box;
use fixtures::scenes3d::{camera, ROTATION_Y_DEGREES};
use rasterizer_core::math::{Angle, Fx16, Mat4};
use rasterizer_core::transform::Transforms;

/// The mesh, converted on the host. (The `textured` and `antialias` configurations draw
/// others.)
#[cfg_attr(any(feature = "textured", feature = "antialias"), allow(dead_code))]
pub static MESH: &[u8] = include_bytes!("../../assets/meshes/suzanne.rmsh");

/// Suzanne turned as in M1, seen through M1's camera on a 4:3 frame. The angle is opaque so that
/// the matrices are computed, as from a firmware's input, not folded into constants. (The
/// `framelist` build takes only the mesh: S1 has its own camera.)
#[cfg_attr(not(any(feature = "all", three_d)), allow(dead_code))]
pub fn transforms() -> Transforms<Fx16> {
    let model = Mat4::rotation_y(black_box(Angle::from_degrees(ROTATION_Y_DEGREES)));
    camera(model, 320, 240)
}
