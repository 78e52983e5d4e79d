//! A `no_std`, allocation-free, integer-only rasterizer for microcontroller displays.
//!
//! Draw points, lines, triangles and polygons into a [`surface::Framebuffer`] over a slice you own,
//! or into any embedded-graphics `DrawTarget` through [`surface::AnyTarget`]; draw lit meshes
//! through [`pipeline::Pipeline`]. One `use` of the [`prelude`] brings what a typical program names:
//!
//! ```
//! use rasterizer_core::prelude::*;
//!
//! let mut buf = [0u16; 320 * 240];
//! let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 320, 240).unwrap();
//! draw_line(&mut fb, Point::new(0, 0), Point::new(319, 239), Rgb565::WHITE).unwrap();
//! // Vertices in 28.4 fixed point: 16 units to the pixel.
//! let v = [SubPoint::new(160 * 16, 8), SubPoint::new(300 * 16, 230 * 16), SubPoint::new(20 * 16, 200 * 16)];
//! fill_triangle_gouraud(&mut fb, v, [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE]).unwrap();
//! assert_eq!(fb.pixel(Point::new(0, 0)), Some(Rgb565::WHITE));
//! ```
//!
//! # Layout
//! The modules are layered: each uses only those above it in this list (`tests/layers.rs` checks
//! it), and the stages appear in the order data flows through them.
//! - Foundations: [`math`] (fixed point, vectors, matrices, angles), [`numerics`] (accuracy
//!   knobs), [`color`] (colour channels), [`geom`] (sub-pixel points, pixel lines, varyings).
//! - [`surface`]: where pixels go (framebuffers, bands, any `DrawTarget`).
//! - The 3D stages: [`mesh`] -> [`transform`] -> [`clip`] -> [`cull`] -> [`depth`] and
//!   [`raster`] -> [`shade`], and [`pipeline`], which runs them.
//! - [`prelude`]: one `use` for a typical program.
//!
//! # Conventions
//! - Pixel `(x, y)` covers `[x, x + 1) x [y, y + 1)`, y down; filled primitives sample its centre.
//! - Filled primitives follow the top-left rule, so shared edges are drawn exactly once.
//! - Lines include both endpoints and light the same pixels in either direction; ties go to the
//!   smaller minor coordinate ([`raster::line`]).
//! - Everything is clipped to the target before it is written: any `i32` input is safe.
//!
//! # Numeric formats
//! - [`geom::SubPoint`]: sub-pixel vertices, `i32` raw with `BITS` fractional bits (default 4 for
//!   the 2D rasterizers, 6 for the 3D pipeline's screen coordinates; at most 8). Fills are exact
//!   inside the guard band of ±[`geom::GUARD_BAND_PIXELS`] pixels.
//! - Interpolated colour: each channel at its native depth, 16 fractional bits.
//!
//! # Features
//! - `float` (off by default): [`math::Scalar`] for `f32` with micromath, so the same pipeline can
//!   run in floating point for accuracy comparisons. The default build contains no float code.
//!
//! The crate needs no allocator and no `std`.
#![no_std]
#![deny(unsafe_code)]
#![deny(missing_docs)]
#![deny(clippy::float_arithmetic, clippy::disallowed_types)]

// The crate documentation lists the modules by layer and in the order data flows through them.
pub mod clip;
pub mod color;
pub mod cull;
pub mod depth;
pub mod geom;
pub mod math;
pub mod mesh;
pub mod numerics;
pub mod pipeline;
pub mod prelude;
pub mod raster;
pub mod shade;
pub mod surface;
pub mod transform;

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
struct ReadmeExamples;
