//! A `no_std`, allocation-free, integer-only rasterizer for microcontroller displays.
//!
//! Draw points, lines, triangles, polygons and sprites into a [`surface::Framebuffer`] over a
//! slice you own, or into any embedded-graphics `DrawTarget` through [`surface::AnyTarget`]; draw
//! lit meshes through [`pipeline::Pipeline`], whole or in bands. One `use` of the [`prelude`]
//! brings what a typical program names. Each task below is a doc test.
//!
//! # A line
//! ```
//! use rasterizer_core::prelude::*;
//!
//! let mut buf = [0u16; 320 * 240];
//! let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 320, 240).unwrap();
//! draw_line(&mut fb, Point::new(0, 0), Point::new(319, 239), Rgb565::WHITE).unwrap();
//! assert_eq!(fb.pixel(Point::new(160, 120)), Some(Rgb565::WHITE));
//! ```
//!
//! # A Gouraud-shaded triangle
//! Vertices are in sub-pixel fixed point, 28.4 by default (16 units to the pixel); the colours
//! are interpolated per channel at the target's depth.
//! ```
//! use rasterizer_core::prelude::*;
//!
//! let mut buf = [0u16; 320 * 240];
//! let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 320, 240).unwrap();
//! let v = [SubPoint::new(160 * 16, 8), SubPoint::new(300 * 16, 230 * 16), SubPoint::new(20 * 16, 200 * 16)];
//! fill_triangle_gouraud(&mut fb, v, [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE]).unwrap();
//! assert_ne!(fb.pixel(Point::new(160, 150)), Some(Rgb565::BLACK));
//! ```
//!
//! # A sprite
//! An image in the sprite format, read in place (firmware uses `include_bytes!` on a file that
//! `host-tools sprite` made from a PNG), turned 30 degrees and doubled about its centre.
//! ```
//! use rasterizer_core::prelude::*;
//! use rasterizer_core::texture::Filter;
//!
//! // A 1x1 white sprite without alpha: the 12-byte header, then one little-endian texel.
//! let bytes = [b'R', b'S', b'P', b'R', 1, 0, 1, 0, 1, 0, 0, 0, 0xFF, 0xFF];
//! let sprite = Sprite::from_bytes(&bytes).unwrap();
//! let mut buf = [0u16; 32 * 32];
//! let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 32, 32).unwrap();
//! let at = [Fx16::from_int(16), Fx16::from_int(16)];
//! let turn = Affine::rotate_scale(1, 1, Angle::from_degrees(30), Fx16::from_int(2), at);
//! draw_sprite(&mut fb, &sprite, &turn, Filter::Nearest).unwrap();
//! assert_eq!(fb.pixel(Point::new(16, 16)), Some(Rgb565::WHITE));
//! ```
//!
//! # A lit mesh
//! The stages are chosen at compile time: here back faces culled, a depth buffer and Gouraud
//! lighting (`NoCull`, `NoDepth` and `Unlit` are the zero-cost "off" forms).
//! ```
//! use rasterizer_core::prelude::*;
//!
//! let p = |x, y, z| Vec3::<Fx16>::from_ints(x, y, z);
//! let corners = [p(1, 1, 1), p(-1, -1, 1), p(-1, 1, -1), p(1, -1, -1)]; // a tetrahedron
//! let triangles = [[0u16, 1, 3], [0, 2, 1], [0, 3, 2], [1, 2, 3]];
//! let mesh = Mesh::new(&corners, &triangles).with_normals(&corners);
//! let viewport = Viewport::new(160, 120);
//! let camera = Transforms::look_at(p(0, 0, 4), p(0, 0, 0), Angle::from_degrees(60), viewport).unwrap();
//! let material = Material::new(Rgb888::new(200, 120, 60));
//! let lighting = Lighting::with_lights(material, [Light::directional(p(1, 1, 1))], p(0, 0, 4)).unwrap();
//! let (mut colors, mut depths) = ([0u16; 160 * 120], [u16::MAX; 160 * 120]);
//! let mut fb = Framebuffer::<Rgb565>::new(&mut colors, 160, 120).unwrap();
//! let depth = DepthBuffer::new(&mut depths, 160, 120, Compare::Less).unwrap();
//! let mut pipeline = Pipeline::new(&camera, viewport, CullClockwise, depth, GouraudLit::new(lighting));
//! // One slot per vertex: each vertex is transformed and lit once a frame.
//! let stats = pipeline.draw(&mut fb, &mesh, &mut [VertexSlot::EMPTY; 4]).unwrap();
//! assert_eq!(stats.drawn + stats.culled, 4);
//! ```
//!
//! # A translucent mesh over an opaque one
//! Draw the opaque meshes first with the depth buffer, then the translucent ones (back to front)
//! through [`surface::Translucent`] with the buffer read-only, so that they are hidden behind
//! opaque surfaces but hide nothing. The blend is integer, per channel; a target that cannot read
//! back its pixels gets [`surface::BlendError::CannotReadBack`] instead of a wrong picture.
//! ```
//! use rasterizer_core::prelude::*;
//! # let p = |x, y, z| Vec3::<Fx16>::from_ints(x, y, z);
//! # let corners = [p(1, 1, 1), p(-1, -1, 1), p(-1, 1, -1), p(1, -1, -1)];
//! # let triangles = [[0u16, 1, 3], [0, 2, 1], [0, 3, 2], [1, 2, 3]];
//! # let mesh = Mesh::new(&corners, &triangles).with_normals(&corners);
//! # let viewport = Viewport::new(160, 120);
//! # let camera = Transforms::look_at(p(0, 0, 4), p(0, 0, 0), Angle::from_degrees(60), viewport).unwrap();
//! # let lighting = Lighting::with_lights(Material::new(Rgb888::new(200, 120, 60)), [Light::directional(p(1, 1, 1))], p(0, 0, 4)).unwrap();
//! let (mut colors, mut depths) = ([0u16; 160 * 120], [u16::MAX; 160 * 120]);
//! let mut fb = Framebuffer::<Rgb565>::new(&mut colors, 160, 120).unwrap();
//! let depth = DepthBuffer::new(&mut depths, 160, 120, Compare::Less).unwrap();
//! let mut opaque = Pipeline::new(&camera, viewport, CullClockwise, depth, GouraudLit::new(lighting.clone()));
//! opaque.draw(&mut fb, &mesh, &mut [VertexSlot::EMPTY; 4]).unwrap();
//! // The same depths, tested but not written; the mesh blended at opacity 128 of 255.
//! let mut glass = Pipeline::new(&camera, viewport, CullClockwise, opaque.depth.read_only(), GouraudLit::new(lighting));
//! glass.draw(&mut Translucent::new(&mut fb, 128), &mesh, &mut [VertexSlot::EMPTY; 4]).unwrap();
//! ```
//!
//! # A frame in bands, to a display
//! For a display whose frame does not fit in RAM: each band is drawn into a small buffer and handed
//! to a callback, where firmware sends it to the display (one address window, one burst of pixels;
//! with DMA, the transfer of one band overlaps drawing the next into a second buffer). The pixels
//! equal the whole-frame draw.
//! ```
//! use rasterizer_core::prelude::*;
//! # let p = |x, y, z| Vec3::<Fx16>::from_ints(x, y, z);
//! # let corners = [p(1, 1, 1), p(-1, -1, 1), p(-1, 1, -1), p(1, -1, -1)];
//! # let triangles = [[0u16, 1, 3], [0, 2, 1], [0, 3, 2], [1, 2, 3]];
//! # let mesh = Mesh::new(&corners, &triangles).with_normals(&corners);
//! # let camera = Transforms::look_at(p(0, 0, 4), p(0, 0, 0), Angle::from_degrees(60), Viewport::new(240, 240)).unwrap();
//! # let lighting = Lighting::with_lights(Material::new(Rgb888::new(200, 120, 60)), [Light::directional(p(1, 1, 1))], p(0, 0, 4)).unwrap();
//! // The display: anything that takes a rectangle of pixels (here a buffer standing for it).
//! let mut display = vec![0u16; 240 * 240];
//! let mut send = |area: Rectangle, pixels: &[u16]| {
//!     let start = area.top_left.y as usize * 240;
//!     display[start..start + pixels.len()].copy_from_slice(pixels);
//! };
//!
//! const ROWS: u32 = 16;
//! let mut depths = [u16::MAX; 240 * ROWS as usize]; // one band of depths
//! let depth = DepthBuffer::new(&mut depths, 240, ROWS, Compare::Less).unwrap();
//! let mut pipeline = Pipeline::new(&camera, Viewport::new(240, 240), CullClockwise, depth, GouraudLit::new(lighting));
//! let banding = Banding { width: 240, height: 240, rows: ROWS, background: Rgb565::BLACK, clear_depth: u16::MAX };
//! let mut band = [0u16; 240 * ROWS as usize];
//! let mut bins = [BinEntry::ZERO; 8]; // one per visible triangle (and per 255 invisible ones)
//! pipeline.draw_banded(&mesh, &banding, &mut band, &mut bins, &mut [VertexSlot::EMPTY; 4], |b| {
//!     let rows = b.framebuffer().size().height;
//!     send(Rectangle::new(Point::new(0, b.y0()), Size::new(240, rows)), b.framebuffer().as_slice());
//! }).unwrap();
//! # let mut whole = vec![0u16; 240 * 240];
//! # let mut fb = Framebuffer::<Rgb565>::new(&mut whole, 240, 240).unwrap();
//! # let mut depths = vec![u16::MAX; 240 * 240];
//! # pipeline.depth = DepthBuffer::new(&mut depths, 240, 240, Compare::Less).unwrap();
//! # pipeline.draw(&mut fb, &mesh, &mut [VertexSlot::EMPTY; 4]).unwrap();
//! # assert!(display.iter().any(|&c| c != 0));
//! # assert_eq!(display, whole);
//! ```
//!
//! # Layout
//! The modules are layered: each uses only those above it in this list (`tests/layers.rs` checks
//! it), and the stages appear in the order data flows through them.
//! - Foundations: [`math`] (fixed point, vectors, matrices, angles), [`numerics`] (accuracy
//!   knobs, dithering), [`color`] (colour channels), [`geom`] (sub-pixel points, pixel lines, varyings).
//! - [`surface`]: where pixels go (framebuffers, bands, any `DrawTarget`).
//! - The 3D stages: [`mesh`] -> [`transform`] -> [`clip`] -> [`cull`] -> [`depth`] and
//!   [`raster`] -> [`shade`] (lighting, MatCap, fog), and [`pipeline`], which runs them.
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
pub mod fingerprint;
pub mod frame;
pub mod geom;
pub mod math;
pub mod mesh;
pub mod numerics;
pub mod pipeline;
pub mod prelude;
pub mod raster;
pub mod shade;
pub mod surface;
pub mod texture;
pub mod transform;
mod wide;

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
struct ReadmeExamples;

/// The crate README's example, compiled and run as a doc test.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct CrateReadmeExamples;
