//! The ranges a scene's numbers must keep for the 16.16 pipeline to draw them faithfully.
//!
//! `Fx16` holds ±32768 in steps of 1/65536 and saturates outside that, so a value beyond the
//! range does not fail: it silently becomes another value and the picture is blank or garbage.
//! The scene loader therefore checks every number against the limits below, after any rescaling
//! the scene asks for (`fit_unit_sphere`), and names the key, the value and the limit.
//!
//! The limits keep a factor of two of headroom where the pipeline forms differences: world
//! coordinates stay within ±[`MAX_COORD`] so a difference of two (a light or view vector) fits
//! within ±[`MAX_CLIP`], and the model-view-projection matrix's entries and every clip-space
//! coordinate it produces stay within ±[`MAX_CLIP`] so the clipper's edge vectors still fit 16.16.

use super::format::Camera;
use fixtures::vec64::{cross, norm, sub as sub3};
use rasterizer_core::geom::GUARD_BAND_PIXELS;
use std::fmt::Write;

/// World coordinates (camera, lights, every mesh vertex after its transform) and scale
/// factors: within ±8192.
pub const MAX_COORD: f64 = 8192.0;
/// Clip-space coordinates and model-view-projection matrix entries: within ±16384.
pub const MAX_CLIP: f64 = 16384.0;
/// The smallest magnitude of a scale factor: 2^-10 (16.16 stores it to 1/128 of itself).
pub const MIN_SCALE: f64 = 1.0 / 1024.0;
/// The smallest extent (largest axis of the bounding box) of a mesh in model space, after
/// `fit_unit_sphere`: 2^-8, so its shape spans at least 256 steps of 16.16.
pub const MIN_EXTENT: f64 = 1.0 / 256.0;
/// The largest model-space coordinate a mesh may have (the 16.16 range).
pub const MAX_MODEL_COORD: f64 = 32767.0;
/// The shortest distance between the camera's eye and target, and the shortest `up` and light
/// direction: 2^-8, so their 16.16 normalisation keeps at least 8 bits.
pub const MIN_LENGTH: f64 = 1.0 / 256.0;
/// The smallest sine of the angle between `up` and the view direction (about 0.45°).
pub const MIN_UP_SINE: f64 = 1.0 / 128.0;
/// The field of view's range, in degrees.
pub const FOV_RANGE: (f64, f64) = (1.0, 179.0);
/// The nearest near plane: 2^-13, where the 16.16 depth still orders the M1 workload (see
/// docs/ACCURACY.md, "Where each format breaks down").
pub const MIN_NEAR: f64 = 1.0 / 8192.0;
/// The farthest far plane.
pub const MAX_FAR: f64 = MAX_CLIP;
/// 2D shape coordinates: within the rasterizer's guard band, ±2^21 pixels.
pub const MAX_PIXEL: f64 = GUARD_BAND_PIXELS as f64;

/// A number as a person would write it in the scene file: `1e30`, `-2.5`, `0.001`.
pub fn num(v: f64) -> String {
    if v != 0.0 && !(1e-4..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// A vector as `[a, b, c]`.
pub fn vector(v: &[f64]) -> String {
    let mut s = String::from("[");
    for (i, x) in v.iter().enumerate() {
        let _ = write!(s, "{}{}", if i > 0 { ", " } else { "" }, num(*x));
    }
    s + "]"
}

/// `key = value` is finite with every component within ±`limit`.
pub fn within(key: &str, v: &[f64], limit: f64) -> Result<(), String> {
    if v.iter().all(|x| x.is_finite() && x.abs() <= limit) {
        Ok(())
    } else {
        let shown = if v.len() == 1 { num(v[0]) } else { vector(v) };
        Err(format!(
            "{key} = {shown} is out of range: each component must be finite and within ±{}",
            num(limit)
        ))
    }
}

/// The `[camera]` table, on its own.
pub fn check_camera(c: &Camera) -> Result<(), String> {
    within("eye", &c.eye, MAX_COORD)?;
    within("target", &c.target, MAX_COORD)?;
    within("up", &c.up, MAX_COORD)?;
    let (lo, hi) = FOV_RANGE;
    if !(lo..=hi).contains(&c.fov) {
        return Err(format!(
            "fov = {} is out of range: it must be {} ..= {} degrees",
            num(c.fov),
            num(lo),
            num(hi)
        ));
    }
    if !(c.near >= MIN_NEAR && c.near < c.far && c.far <= MAX_FAR) {
        return Err(format!(
            "near = {}, far = {}: need {} <= near < far <= {}",
            num(c.near),
            num(c.far),
            num(MIN_NEAR),
            num(MAX_FAR)
        ));
    }
    let f = sub3(c.target, c.eye);
    if norm(f) < MIN_LENGTH {
        return Err(format!(
            "eye = {} and target = {} are {} apart: the camera needs them at least {} apart to \
             have a view direction",
            vector(&c.eye),
            vector(&c.target),
            num(norm(f)),
            num(MIN_LENGTH)
        ));
    }
    if norm(c.up) < MIN_LENGTH {
        return Err(format!(
            "up = {} is too short: its length must be at least {}",
            vector(&c.up),
            num(MIN_LENGTH)
        ));
    }
    if norm(cross(f, c.up)) < MIN_UP_SINE * norm(f) * norm(c.up) {
        return Err(format!(
            "up = {} is parallel to the view direction from eye = {} to target = {}: choose an \
             up that is not",
            vector(&c.up),
            vector(&c.eye),
            vector(&c.target)
        ));
    }
    Ok(())
}

/// The largest absolute row sum of the projection matrix and its largest translation, for an
/// aspect ratio of `width / height`.
fn projection_bounds(c: &Camera, width: u32, height: u32) -> (f64, f64) {
    let f = 1.0 / (c.fov.to_radians() / 2.0).tan();
    let aspect = f64::from(width) / f64::from(height);
    let depth = (c.far + c.near) / (c.far - c.near);
    let shift = 2.0 * c.far * c.near / (c.far - c.near);
    ((f / aspect).max(f).max(depth).max(1.0), shift)
}

/// One mesh's numbers: its scale and translation, its model-space positions (after
/// `fit_unit_sphere`), and the clip-space coordinates it can reach with this camera at any turn
/// of `animate`'s turntable.
pub fn check_mesh(
    positions: &[[f64; 3]],
    scale: [f64; 3],
    translate: [f64; 3],
    camera: &Camera,
    width: u32,
    height: u32,
) -> Result<(), String> {
    let shown_scale = if scale[0] == scale[1] && scale[1] == scale[2] {
        num(scale[0])
    } else {
        vector(&scale)
    };
    if !scale
        .iter()
        .all(|s| s.is_finite() && (MIN_SCALE..=MAX_COORD).contains(&s.abs()))
    {
        return Err(format!(
            "scale = {shown_scale} is out of range: each factor's magnitude must be {} ..= {} \
             (fit_unit_sphere = true rescales a model to the unit sphere first)",
            num(MIN_SCALE),
            num(MAX_COORD)
        ));
    }
    within("translate", &translate, MAX_COORD)?;
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let mut reach = 0f64;
    for (i, p) in positions.iter().enumerate() {
        if !p.iter().all(|v| v.abs() <= MAX_MODEL_COORD) {
            return Err(format!(
                "vertex {i} at {} is outside 16.16's range ±{}; fit_unit_sphere = true rescales \
                 the model first (it is applied before this check)",
                vector(p),
                num(MAX_MODEL_COORD)
            ));
        }
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
        reach = reach.max(norm([0, 1, 2].map(|k| p[k] * scale[k])));
    }
    let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    if extent < MIN_EXTENT {
        return Err(format!(
            "the model's extent is {} (its bounding box's largest side): 16.16 needs at least {} \
             to resolve its shape; fit_unit_sphere = true rescales it",
            num(extent),
            num(MIN_EXTENT)
        ));
    }
    // Rotation keeps lengths: the transformed mesh lies within reach + |translate| of the
    // origin, whatever the rotation and the turntable's turn.
    let world = reach + norm(translate);
    if world > MAX_COORD {
        return Err(format!(
            "with scale = {shown_scale} and translate = {} the mesh reaches {} from the origin; \
             world coordinates must stay within {}",
            vector(&translate),
            num(world),
            num(MAX_COORD)
        ));
    }
    let (rows, shift) = projection_bounds(camera, width, height);
    let view = world.max(norm(translate)) + norm(camera.eye);
    let clip = rows * view + shift;
    let entries = rows * scale.iter().fold(0.0, |m: f64, s| m.max(s.abs()));
    if clip.max(entries) > MAX_CLIP {
        return Err(format!(
            "with the camera's eye = {} and fov = {} the mesh's clip-space coordinates reach {}; \
             the 16.16 pipeline needs them within ±{}: bring the mesh and the camera closer to \
             the origin, scale the mesh down or widen the field of view",
            vector(&camera.eye),
            num(camera.fov),
            num(clip.max(entries)),
            num(MAX_CLIP)
        ));
    }
    Ok(())
}

/// A 2D shape's coordinates: `filled` shapes (triangles, polygons) within the guard band,
/// the others (whole pixels: points, lines, outlines) within `i32`, which they handle exactly.
pub fn check_pixels(points: &[[f64; 2]], filled: bool) -> Result<(), String> {
    let (lo, hi, why) = if filled {
        (
            -MAX_PIXEL,
            MAX_PIXEL,
            "the rasterizer's guard band for filled shapes",
        )
    } else {
        (f64::from(i32::MIN), f64::from(i32::MAX), "whole i32 pixels")
    };
    for (i, p) in points.iter().enumerate() {
        if !p
            .iter()
            .all(|v| v.is_finite() && (lo..=hi).contains(&v.floor()))
        {
            return Err(format!(
                "point {} = {} is out of range: coordinates must be finite and within {} ..= {} \
                 pixels ({why})",
                i + 1,
                vector(p),
                lo,
                hi
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_like_the_scene_file() {
        assert_eq!(num(1e30), "1e30");
        assert_eq!(num(-1e9), "-1e9");
        assert_eq!(num(3e6), "3e6");
        assert_eq!(num(1e-30), "1e-30");
        assert_eq!(num(0.5), "0.5");
        assert_eq!(num(0.0), "0");
        assert_eq!(vector(&[0.0, 0.0, 1e6]), "[0, 0, 1e6]");
    }

    #[test]
    fn the_default_camera_and_a_unit_mesh_pass() {
        let cam = Camera::default();
        check_camera(&cam).unwrap();
        let cube = [[-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]];
        check_mesh(&cube, [1.0; 3], [0.0; 3], &cam, 320, 240).unwrap();
        // The largest world the limits allow still passes with a camera at the origin.
        let far = Camera {
            eye: [0.0, 0.0, 0.0],
            target: [0.0, 0.0, -1.0],
            far: MAX_FAR,
            ..Camera::default()
        };
        check_mesh(&cube, [1000.0; 3], [0.0, 0.0, -6000.0], &far, 320, 240).unwrap();
        assert!(check_mesh(&cube, [1e30; 3], [0.0; 3], &cam, 320, 240).is_err());
        assert!(check_mesh(&cube, [1e-30; 3], [0.0; 3], &cam, 320, 240).is_err());
    }
}
