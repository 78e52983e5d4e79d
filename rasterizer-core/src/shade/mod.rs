//! Lighting: Phong and Blinn-Phong shading of a surface point, in integers only.
//!
//! [`Lighting`] turns a position and a normal into a lit colour, per vertex (Gouraud) or per pixel,
//! with fixed-capacity light lists and no floats, so it runs on the same cores as the rasterizer.

pub mod light;

pub use light::{Light, Lighting, Material, Specular};

/// Values a shader interpolates across a triangle: `[i32; N]` for `N` values, at most
/// [`MAX_VARYINGS`]. Their meaning and fixed-point scale are the shader's own.
pub trait Varyings: Copy + Default + core::fmt::Debug {
    /// How many values there are.
    const LEN: usize;
    /// The values.
    fn as_slice(&self) -> &[i32];
    /// The values, mutably.
    fn as_mut_slice(&mut self) -> &mut [i32];
}

/// The most values a triangle interpolates; a longer [`Varyings`] has only its first
/// `MAX_VARYINGS` values interpolated (the rest keep the first vertex's values).
pub const MAX_VARYINGS: usize = 8;

impl<const N: usize> Varyings for [i32; N]
where
    [i32; N]: Default,
{
    const LEN: usize = N;
    #[inline]
    fn as_slice(&self) -> &[i32] {
        self
    }
    #[inline]
    fn as_mut_slice(&mut self) -> &mut [i32] {
        self
    }
}
