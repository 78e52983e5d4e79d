//! Shading models: what a vertex hands on to its triangle and what colour a pixel gets.
//!
//! Each model is its own type, so the pipeline compiles exactly the work it asks for: [`Unlit`]
//! interpolates nothing and computes no normals or world positions; [`FlatLit`] lights once per
//! triangle; [`GouraudLit`] once per vertex and interpolates the colour; [`PhongLit`] interpolates the
//! normal and the position and lights every pixel.

use crate::math::{Scalar, Vec3};
use crate::shade::{Lighting, Varyings};
use embedded_graphics_core::pixelcolor::Rgb888;
use embedded_graphics_core::prelude::{PixelColor, RgbColor};

/// What the pipeline knows about a vertex when the shader sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VertexIn<S> {
    /// Position in world space (zero unless the shader asks for it).
    pub position: Vec3<S>,
    /// Normal in world space, not normalised (zero unless the shader asks for it).
    pub normal: Vec3<S>,
    /// The mesh's vertex colour, white when the mesh has none.
    pub color: Rgb888,
}

/// A shading model.
pub trait Shading<S: Scalar> {
    /// The colour it produces.
    type Color: PixelColor;
    /// The values it interpolates across a triangle.
    type Varyings: Varyings;
    /// The shader reads world positions and normals (the pipeline skips them otherwise).
    const NEEDS_WORLD: bool;
    /// The shader does work per triangle in [`Shading::face`] (the pipeline skips the call and
    /// the world data it needs otherwise).
    const NEEDS_FACE: bool = false;
    /// Per vertex: the values to interpolate.
    fn vertex(&mut self, v: &VertexIn<S>) -> Self::Varyings;
    /// Once per visible triangle, before its pixels.
    fn face(&mut self, _vertices: &[VertexIn<S>; 3]) {}
    /// Per pixel: the colour from the interpolated values.
    fn pixel(&self, v: &Self::Varyings) -> Self::Color;
}

/// One colour, no lighting.
#[derive(Debug, Clone, Copy)]
pub struct Unlit<C> {
    /// The colour.
    pub color: C,
}

impl<S: Scalar, C: PixelColor> Shading<S> for Unlit<C> {
    type Color = C;
    type Varyings = [i32; 0];
    const NEEDS_WORLD: bool = false;
    #[inline(always)]
    fn vertex(&mut self, _: &VertexIn<S>) -> [i32; 0] {
        []
    }
    #[inline(always)]
    fn pixel(&self, _: &[i32; 0]) -> C {
        self.color
    }
}

/// The mesh's vertex colours interpolated, no lighting.
#[derive(Debug, Clone, Copy, Default)]
pub struct VertexColors<C> {
    _c: core::marker::PhantomData<C>,
}

impl<C> VertexColors<C> {
    /// The shader.
    pub fn new() -> Self {
        Self {
            _c: core::marker::PhantomData,
        }
    }
}

/// Channels in 8.8 fixed point, as interpolated.
#[inline(always)]
fn rgb_fine(c: [u32; 3]) -> [i32; 3] {
    c.map(|v| v as i32)
}

/// An 8.8 channel triple back to a colour, rounded and clamped.
#[inline(always)]
fn from_fine<C: From<Rgb888>>(v: &[i32; 3]) -> C {
    let ch = |x: i32| ((x + 128) >> 8).clamp(0, 255) as u8;
    C::from(Rgb888::new(ch(v[0]), ch(v[1]), ch(v[2])))
}

impl<S: Scalar, C: PixelColor + From<Rgb888>> Shading<S> for VertexColors<C> {
    type Color = C;
    type Varyings = [i32; 3];
    const NEEDS_WORLD: bool = false;
    #[inline(always)]
    fn vertex(&mut self, v: &VertexIn<S>) -> [i32; 3] {
        rgb_fine([v.color.r(), v.color.g(), v.color.b()].map(|c| u32::from(c) << 8))
    }
    #[inline(always)]
    fn pixel(&self, v: &[i32; 3]) -> C {
        from_fine(v)
    }
}

/// Lit once per triangle with the face normal (the cross product of its edges in world space).
#[derive(Debug, Clone)]
pub struct FlatLit<S, C, const N: usize> {
    /// The lights, material and eye.
    pub lighting: Lighting<S, N>,
    color: C,
}

impl<S: Scalar, C: PixelColor + From<Rgb888>, const N: usize> FlatLit<S, C, N> {
    /// The shader.
    pub fn new(lighting: Lighting<S, N>) -> Self {
        Self {
            lighting,
            color: C::from(Rgb888::BLACK),
        }
    }
}

impl<S: Scalar, C: PixelColor + From<Rgb888>, const N: usize> Shading<S> for FlatLit<S, C, N> {
    type Color = C;
    type Varyings = [i32; 0];
    const NEEDS_WORLD: bool = true;
    const NEEDS_FACE: bool = true;
    #[inline(always)]
    fn vertex(&mut self, _: &VertexIn<S>) -> [i32; 0] {
        []
    }
    fn face(&mut self, v: &[VertexIn<S>; 3]) {
        let normal = (v[1].position - v[0].position).cross(v[2].position - v[0].position);
        // The centroid, for point lights and the specular term.
        let third = S::from_ratio(1, 3);
        let centre = (v[0].position + v[1].position + v[2].position).scale(third);
        self.color = C::from(self.lighting.shade(centre, normal));
    }
    #[inline(always)]
    fn pixel(&self, _: &[i32; 0]) -> C {
        self.color
    }
}

/// Lit per vertex with the mesh's normals; the lit colour is interpolated (Gouraud shading).
#[derive(Debug, Clone)]
pub struct GouraudLit<S, C, const N: usize> {
    /// The lights, material and eye.
    pub lighting: Lighting<S, N>,
    _c: core::marker::PhantomData<C>,
}

impl<S: Scalar, C, const N: usize> GouraudLit<S, C, N> {
    /// The shader.
    pub fn new(lighting: Lighting<S, N>) -> Self {
        Self {
            lighting,
            _c: core::marker::PhantomData,
        }
    }
}

impl<S: Scalar, C: PixelColor + From<Rgb888>, const N: usize> Shading<S> for GouraudLit<S, C, N> {
    type Color = C;
    type Varyings = [i32; 3];
    const NEEDS_WORLD: bool = true;
    #[inline(always)]
    fn vertex(&mut self, v: &VertexIn<S>) -> [i32; 3] {
        rgb_fine(self.lighting.shade_fine(v.position, v.normal))
    }
    #[inline(always)]
    fn pixel(&self, v: &[i32; 3]) -> C {
        from_fine(v)
    }
}

/// Lit per pixel: the normal and the world position are interpolated (in 16.16) and lit at every
/// pixel (Phong shading).
#[derive(Debug, Clone)]
pub struct PhongLit<S, C, const N: usize> {
    /// The lights, material and eye.
    pub lighting: Lighting<S, N>,
    _c: core::marker::PhantomData<C>,
}

impl<S: Scalar, C, const N: usize> PhongLit<S, C, N> {
    /// The shader.
    pub fn new(lighting: Lighting<S, N>) -> Self {
        Self {
            lighting,
            _c: core::marker::PhantomData,
        }
    }
}

impl<S: Scalar, C: PixelColor + From<Rgb888>, const N: usize> Shading<S> for PhongLit<S, C, N> {
    type Color = C;
    type Varyings = [i32; 6];
    const NEEDS_WORLD: bool = true;
    #[inline(always)]
    fn vertex(&mut self, v: &VertexIn<S>) -> [i32; 6] {
        // Unit normals keep the interpolated normal's scale even across a long triangle.
        let n = v.normal.normalize().unwrap_or_default();
        let p = v.position;
        [n.x, n.y, n.z, p.x, p.y, p.z].map(S::to_fx16_bits)
    }
    #[inline(always)]
    fn pixel(&self, v: &[i32; 6]) -> C {
        let f = |i: usize| S::from_fx16_bits(v[i]);
        let normal = Vec3::new(f(0), f(1), f(2));
        let position = Vec3::new(f(3), f(4), f(5));
        C::from(self.lighting.shade(position, normal))
    }
}
