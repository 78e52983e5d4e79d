//! The M1 scene that both builds draw: Suzanne's packed mesh and its camera.

use core::hint::black_box;
use rasterizer_core::math::{Angle, Fx16, Mat4, Vec3};
use rasterizer_core::transform::Transforms;

/// The mesh, converted on the host.
pub static MESH: &[u8] = include_bytes!("../../assets/meshes/suzanne.rmsh");

/// Suzanne turned 30 degrees, seen from (0, 0, 3) through a 60-degree 4:3 lens (near 0.1, far
/// 100).
pub fn transforms() -> Transforms<Fx16> {
    let p = |x, y, z| Vec3::<Fx16>::from_ints(x, y, z);
    Transforms {
        model: Mat4::rotation_y(black_box(Angle::from_degrees(30))),
        view: Mat4::look_at(p(0, 0, 3), p(0, 0, 0), p(0, 1, 0)).unwrap_or_default(),
        projection: Mat4::perspective(
            Angle::from_degrees(60),
            Fx16::from_ratio(4, 3),
            Fx16::from_ratio(1, 10),
            Fx16::from_int(100),
        )
        .unwrap_or_default(),
    }
}
