//! Back-face culling, chosen at compile time: [`NoCull`] compiles to nothing.
//!
//! Winding is as the viewer sees it with y up (OpenGL's convention): a triangle whose vertices go
//! counter-clockwise on screen faces the viewer in a mesh wound counter-clockwise outwards.
//!
//! A mirroring model or view matrix (a reflection, a negative scale on one or three axes:
//! [`Mat4::mirrors`]) reverses every winding on screen. The pipeline notices once per frame and
//! judges each triangle by the winding it has in the mesh, so [`CullClockwise`] drops a mirrored
//! mesh's back faces too (as Three.js does). OpenGL instead applies the rule to the winding on
//! screen as it is and leaves the flip to the caller (`glFrontFace`); [`WindowSpace`] keeps that
//! rule for those who want it.
//!
//! [`Mat4::mirrors`]: crate::math::Mat4::mirrors

/// Which triangles to drop, by their winding on screen.
pub trait Cull {
    /// True to keep a triangle whose doubled signed area in screen coordinates (y down) is `area`:
    /// negative for counter-clockwise as seen with y up, positive for clockwise. Under a mirroring
    /// transform the pipeline hands over the area the triangle would have unmirrored (the negated
    /// one), unless [`Cull::WINDOW_SPACE`].
    fn keep(&self, area: i64) -> bool;

    /// Whether the rule applies to the winding on screen as it is, even under a mirroring
    /// transform, where it then drops the mesh's front faces (OpenGL's rule). False by default.
    const WINDOW_SPACE: bool = false;
}

/// Keep everything.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoCull;

/// Drop triangles that appear clockwise (the back faces of a counter-clockwise mesh).
#[derive(Debug, Clone, Copy, Default)]
pub struct CullClockwise;

/// Drop triangles that appear counter-clockwise.
#[derive(Debug, Clone, Copy, Default)]
pub struct CullCounterClockwise;

/// A culling rule applied to the winding on screen as it is, as OpenGL applies `glFrontFace`:
/// under a mirroring model or view matrix it drops the mesh's front faces instead of its back
/// faces. `WindowSpace(CullClockwise)` is OpenGL's default culling.
#[derive(Debug, Clone, Copy, Default)]
pub struct WindowSpace<C>(pub C);

impl Cull for NoCull {
    #[inline(always)]
    fn keep(&self, _: i64) -> bool {
        true
    }
}

impl Cull for CullClockwise {
    #[inline(always)]
    fn keep(&self, area: i64) -> bool {
        area < 0
    }
}

impl Cull for CullCounterClockwise {
    #[inline(always)]
    fn keep(&self, area: i64) -> bool {
        area > 0
    }
}

impl<C: Cull> Cull for WindowSpace<C> {
    #[inline(always)]
    fn keep(&self, area: i64) -> bool {
        self.0.keep(area)
    }
    const WINDOW_SPACE: bool = true;
}
