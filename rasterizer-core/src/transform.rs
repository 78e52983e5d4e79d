//! The vertex transform's inputs: the model, view and projection matrices ([`Transforms`]) and where
//! normalised device coordinates land on the target ([`Viewport`]).

use crate::math::{Angle, Mat4, Scalar, Vec3};
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;

/// The transforms of a draw call.
#[derive(Debug, Clone, Copy)]
pub struct Transforms<S> {
    /// Model to world.
    pub model: Mat4<S>,
    /// World to view (e.g. [`Mat4::look_at`]).
    pub view: Mat4<S>,
    /// View to clip space (e.g. [`Mat4::perspective`]).
    pub projection: Mat4<S>,
}

impl<S: Scalar> Transforms<S> {
    /// A camera at `eye` looking at `target` (y up), with a vertical field of view `fov_y` and the
    /// aspect ratio of `viewport`, seeing from 1/8 to 256 units away; the model matrix is the
    /// identity ([`Transforms::with_model`] sets it).
    ///
    /// `None` when the camera looks straight up or down, `eye` equals `target`, or the projection
    /// is not representable in `S`.
    pub fn look_at(
        eye: Vec3<S>,
        target: Vec3<S>,
        fov_y: Angle,
        viewport: Viewport,
    ) -> Option<Self> {
        let up = Vec3::new(S::ZERO, S::ONE, S::ZERO);
        let side = |v: u32| S::from_int(v.clamp(1, crate::surface::MAX_DIMENSION) as i32);
        let aspect = side(viewport.width) / side(viewport.height);
        let near = S::ONE / S::from_int(8);
        Some(Self {
            model: Mat4::identity(),
            view: Mat4::look_at(eye, target, up)?,
            projection: Mat4::perspective(fov_y, aspect, near, S::from_int(256))?,
        })
    }

    /// The same transforms with another model matrix.
    pub fn with_model(self, model: Mat4<S>) -> Self {
        Self { model, ..self }
    }
}

/// Where normalised device coordinates land on the target: `x = -1` at the left edge of the
/// rectangle, `y = +1` at its top (the y flip), in whole pixels. The pipeline also clips to it, so
/// several viewports can share one target.
///
/// Range: any `x` and `y`; `width` and `height` at most 32767 ([`crate::surface::MAX_DIMENSION`]).
/// A [`crate::pipeline::Pipeline`] clamps a larger width or height to 32767, for the mapping from device
/// coordinates as for clipping; the clip rectangle, [`Viewport::rectangle`], also stops at the
/// `i32` plane's edge (it never reaches past `i32::MAX`), so nothing is drawn outside it or the
/// target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Viewport {
    /// Left edge.
    pub x: i32,
    /// Top edge.
    pub y: i32,
    /// Width in pixels, at most 32767.
    pub width: u32,
    /// Height in pixels, at most 32767.
    pub height: u32,
}

impl Viewport {
    /// The rectangle of pixels the viewport covers: the pipeline draws nothing outside it.
    ///
    /// Exactly `(x, y)`, `width` x `height` within the documented range; a width or height above
    /// 32767 is clamped to it, and the size to what ends at `i32::MAX`, for any field values.
    pub fn rectangle(&self) -> Rectangle {
        // No pixel lies past i32::MAX.
        let max = i64::from(crate::surface::MAX_DIMENSION);
        let len = |origin: i32, len: u32| {
            let room = i64::from(i32::MAX) - i64::from(origin) + 1;
            i64::from(len).min(max).min(room) as u32
        };
        Rectangle::new(
            Point::new(self.x, self.y),
            Size::new(len(self.x, self.width), len(self.y, self.height)),
        )
    }

    /// A viewport covering `width` x `height` pixels from the origin.
    pub const fn new(width: u32, height: u32) -> Self {
        Self {
            x: 0,
            y: 0,
            width,
            height,
        }
    }
}
