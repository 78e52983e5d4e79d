//! Lighting: Phong and Blinn-Phong shading of a surface point, in integers only.
//!
//! [`Lighting`] turns a position and a normal into a lit colour, per vertex (Gouraud) or per pixel,
//! with fixed-capacity light lists and no floats, so it runs on the same cores as the rasterizer.
//! [`Fog`] mixes a shading model's colour toward a fog colour by depth. [`MatCap`] colours each
//! vertex from a picture of a lit sphere by the direction its normal faces, with no lighting maths.

pub mod fog;
pub mod light;
pub mod matcap;
pub mod model;
pub mod textured;

pub use fog::{
    Fog, FogColor, FogCurve, FogSettings, Foggable, FOG_MAX_DENSITY, FOG_ONE, FOG_TABLE_LEN,
};

pub use light::{Light, Lighting, Material, Specular};
pub use matcap::{MatCap, MatCapError, MATCAP_MAX_SIDE_LOG2};
pub use model::{
    FlatLit, GouraudLit, Packed, PhongLit, Shading, Stored, Unlit, VertexColors, VertexIn,
};
pub use textured::TexturedLit;
