//! A `no_std`, allocation-free, integer-only rasterizer for microcontroller displays.
//!
//! Draw points, lines, triangles and polygons into a [`target::Framebuffer`] over a slice you own, or
//! into any embedded-graphics `DrawTarget` through [`target::AnyTarget`]:
//!
//! ```
//! use embedded_graphics_core::{pixelcolor::Rgb565, prelude::*};
//! use rasterizer_core::geom::SubPoint;
//! use rasterizer_core::raster::{line::draw_line, triangle::fill_triangle_gouraud};
//! use rasterizer_core::surface::Framebuffer;
//!
//! let mut buf = [0u16; 320 * 240];
//! let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 320, 240).unwrap();
//! draw_line(&mut fb, Point::new(0, 0), Point::new(319, 239), Rgb565::WHITE).unwrap();
//! // Vertices in 28.4 fixed point: 16 units to the pixel.
//! let v = [SubPoint::<4>::new(160 * 16, 8), SubPoint::new(300 * 16, 230 * 16), SubPoint::new(20 * 16, 200 * 16)];
//! fill_triangle_gouraud(&mut fb, v, [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE]).unwrap();
//! assert_eq!(fb.pixel(Point::new(0, 0)), Some(Rgb565::WHITE));
//! ```
//!
//! # Conventions
//! - Pixel `(x, y)` covers `[x, x + 1) x [y, y + 1)`, y down; filled primitives sample its centre.
//! - Filled primitives follow the top-left rule, so shared edges are drawn exactly once.
//! - Lines include both endpoints and light the same pixels in either direction; ties go to the
//!   smaller minor coordinate ([`raster::line`]).
//! - Everything is clipped to the target before it is written: any `i32` input is safe.
//!
//! # Numeric formats
//! - [`geom::SubPoint`]: sub-pixel vertices, `i32` raw with `BITS` fractional bits (default 4, at
//!   most 8). Fills are exact inside the guard band of ±[`geom::GUARD_BAND_PIXELS`] pixels.
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

// Foundations.
pub mod color;
pub mod geom;
pub mod math;
pub mod numerics;
// Where pixels go.
pub mod surface;
// The stages, in the order data flows through them.
pub mod clip;
pub mod cull;
pub mod depth;
pub mod mesh;
pub mod pipeline;
pub mod raster;
pub mod shade;
pub mod transform;

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
struct ReadmeExamples;
