//! Everything a typical program names, in one `use`:
//!
//! ```
//! use rasterizer_core::prelude::*;
//! ```
//!
//! It brings the drawing functions, the framebuffer, the 3D pipeline and its stages, the number
//! types, and embedded-graphics' colours and geometry (`Rgb565`, `Point`, `RgbColor`, ...).
//! Knobs for accuracy studies ([`crate::numerics`]) and lower-level pieces stay in their modules.

pub use embedded_graphics_core::pixelcolor::{BinaryColor, Gray8, Rgb565, Rgb888};
pub use embedded_graphics_core::prelude::*;
pub use embedded_graphics_core::primitives::Rectangle;

pub use crate::cull::{CullClockwise, CullCounterClockwise, NoCull, WindowSpace};
pub use crate::depth::{Compare, DepthBuffer, DepthReadOnly, NoDepth};
pub use crate::geom::SubPoint;
pub use crate::math::{Angle, Fx16, Mat4, Vec3};
pub use crate::mesh::{Mesh, PackedMesh};
pub use crate::pipeline::{Banding, BinEntry, GouraudPipeline, Pipeline, VertexSlot};
pub use crate::raster::line::{
    draw_line, draw_line_aa, draw_line_aa_wide, draw_line_alpha, draw_line_gradient,
};
pub use crate::raster::point::draw_point;
pub use crate::raster::polygon::{fill_polygon, FillRule, Polygon};
pub use crate::raster::sprite::{draw_sprite, Affine, Sprite};
pub use crate::raster::triangle::{
    draw_triangle, fill_triangle, fill_triangle_alpha, fill_triangle_gouraud,
};
pub use crate::shade::{
    FlatLit, GouraudLit, Light, Lighting, MatCap, Material, PhongLit, Specular, TexturedLit, Unlit,
    VertexColors,
};
pub use crate::surface::{AnyTarget, BlendError, Framebuffer, Surface, Translucent};
pub use crate::texture::{Filter, Texture, Wrap};
pub use crate::transform::{Transforms, Viewport};
