//! Back-face culling, chosen at compile time: [`NoCull`] compiles to nothing.
//!
//! Winding is as the viewer sees it with y up (OpenGL's convention): a triangle whose vertices go
//! counter-clockwise on screen faces the viewer in a mesh wound counter-clockwise outwards.

/// Which triangles to drop, by their winding on screen.
pub trait Cull {
    /// True to keep a triangle whose doubled signed area in screen coordinates (y down) is `area`:
    /// negative for counter-clockwise as seen with y up, positive for clockwise.
    fn keep(&self, area: i64) -> bool;
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
