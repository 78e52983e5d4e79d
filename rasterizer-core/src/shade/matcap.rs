//! MatCap shading: each vertex takes its colour from a small picture of a lit sphere, looked up by
//! the direction its normal faces on screen; the colours are interpolated as Gouraud's are.
//!
//! The picture holds the material's whole response to its lights as seen from the camera, so a
//! vertex costs a rotation of its normal, one reciprocal square root and a texel read: no lighting
//! arithmetic, and the same fused span loop as [`super::GouraudLit`].

use super::model::{channel_pixels, target_channels};
use super::{Shading, VertexIn};
use crate::color::ShadeColor;
use crate::math::{Mat4, Scalar};
use crate::texture::{Texture, TextureError};
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics_core::prelude::RgbColor;

/// The largest side of a MatCap image, as a power of two: 256 texels (128 KiB). A vertex's
/// texel is chosen to well within one texel at this size (`docs/ACCURACY.md`).
pub const MATCAP_MAX_SIDE_LOG2: u8 = 8;

/// Why a picture is not a MatCap image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MatCapError {
    /// The bytes are not a texture of the given sides ([`Texture::new`]).
    Texture(TextureError),
    /// The width and height differ: a MatCap image is square.
    NotSquare {
        /// The width's power of two.
        width_log2: u8,
        /// The height's power of two.
        height_log2: u8,
    },
    /// A side above `2^MATCAP_MAX_SIDE_LOG2` texels.
    TooLarge {
        /// The side's power of two.
        side_log2: u8,
    },
}

impl From<TextureError> for MatCapError {
    fn from(e: TextureError) -> Self {
        Self::Texture(e)
    }
}

impl core::fmt::Display for MatCapError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Texture(e) => write!(f, "not a MatCap image: {e}"),
            Self::NotSquare {
                width_log2,
                height_log2,
            } => write!(
                f,
                "a MatCap image must be square, not {}x{} texels",
                1u64 << (*width_log2).min(63),
                1u64 << (*height_log2).min(63)
            ),
            Self::TooLarge { side_log2 } => write!(
                f,
                "a {side}x{side} MatCap image is larger than {max}x{max} texels",
                side = 1u64 << (*side_log2).min(63),
                max = 1u32 << MATCAP_MAX_SIDE_LOG2
            ),
        }
    }
}

impl core::error::Error for MatCapError {}

/// Fractional bits of the unit normal's components as the lookup uses them.
const UNIT_BITS: u32 = 30;

/// The largest entry of the normal transform as [`MatCap`] keeps it, as a power of two: 20
/// significant bits, far finer than a texel, while a product with a 16.16 normal component
/// (below `2^31`, the entry at most `2^21`) and a sum of three stay below `2^54`.
const MATRIX_LEAD: u32 = 20;

/// MatCap shading per vertex: the view-space normal picks a texel of a square image of a lit
/// sphere, and the texels' colours are interpolated across each triangle.
///
/// The normal `n` (normalised here, so meshes need not carry unit normals and the model-view
/// may scale) picks texel `(round((n.x + 1) / 2 · (side - 1)), round((1 - n.y) / 2 · (side - 1)))`,
/// clamped to the image: the image's centre faces the camera, its top row looks up. A zero normal
/// (or a transform that flattens it) takes the centre texel. Normals follow the model matrix,
/// or [`crate::pipeline::Pipeline::set_normal_matrix`]'s matrix when one is set, then the view
/// matrix given here.
///
/// The image is little-endian Rgb565 ([`Texture`]), square, with a side of `2^k` texels for
/// `k <= 8` (32 or 64 are typical).
///
/// ```
/// use rasterizer_core::prelude::*;
///
/// let p = |x, y, z| Vec3::<Fx16>::from_ints(x, y, z);
/// let vp = Viewport::new(64, 48);
/// let t = Transforms::look_at(p(0, 0, 4), p(0, 0, 0), Angle::from_degrees(50), vp).unwrap();
/// // A 2x2 image: top row red and green, bottom row blue and white.
/// use embedded_graphics_core::pixelcolor::raw::RawU16;
/// let texels: Vec<u8> = [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE, Rgb565::WHITE]
///     .iter()
///     .flat_map(|c| RawU16::from(*c).into_inner().to_le_bytes())
///     .collect();
/// let shading = MatCap::<_, Rgb565>::new(1, &texels, &t.view).unwrap();
/// let mut pipeline = Pipeline::new(&t, vp, NoCull, NoDepth, shading);
/// let positions = [p(-1, -1, 0), p(1, -1, 0), p(0, 1, 0)];
/// let normals = [p(-1, -1, 1), p(1, -1, 1), p(0, 1, 1)];
/// let mesh = Mesh::new(&positions, &[[0u16, 1, 2]]).with_normals(&normals);
/// let mut pixels = [0u16; 64 * 48];
/// let mut fb = Framebuffer::<Rgb565>::new(&mut pixels, 64, 48).unwrap();
/// pipeline.draw(&mut fb, &mesh, &mut [VertexSlot::EMPTY; 3]).unwrap();
/// assert!(pixels.iter().any(|&c| c != 0));
/// ```
#[derive(Debug, Clone)]
pub struct MatCap<'a, S, C> {
    image: Texture<'a>,
    /// World to view.
    view: Mat4<S>,
    /// This frame's normal transform to view space (rows x, y, z), scaled so that its largest
    /// entry has [`MATRIX_LEAD`] bits: only the direction of its result is used.
    rows: [[i32; 3]; 3],
    _c: core::marker::PhantomData<C>,
}

impl<'a, S: Scalar, C> MatCap<'a, S, C> {
    /// The shader: an image of `2^side_log2` texels a side from its little-endian Rgb565 bytes
    /// (row 0 at the top), seen through `view` (the view matrix of the pipeline's
    /// [`crate::transform::Transforms`]).
    ///
    /// # Errors
    /// [`MatCapError::TooLarge`] for a side above `2^MATCAP_MAX_SIDE_LOG2`, and
    /// [`MatCapError::Texture`] when the bytes are not `2 · 4^side_log2`.
    pub fn new(side_log2: u8, texels: &'a [u8], view: &Mat4<S>) -> Result<Self, MatCapError> {
        if side_log2 > MATCAP_MAX_SIDE_LOG2 {
            return Err(MatCapError::TooLarge { side_log2 });
        }
        Self::from_texture(Texture::new(side_log2, side_log2, texels)?, view)
    }

    /// The shader from a texture, which must be square with a side of at most
    /// `2^MATCAP_MAX_SIDE_LOG2`.
    ///
    /// # Errors
    /// [`MatCapError::NotSquare`] and [`MatCapError::TooLarge`].
    pub fn from_texture(image: Texture<'a>, view: &Mat4<S>) -> Result<Self, MatCapError> {
        let (width_log2, height_log2) = (image.width_log2(), image.height_log2());
        if width_log2 != height_log2 {
            return Err(MatCapError::NotSquare {
                width_log2,
                height_log2,
            });
        }
        if width_log2 > MATCAP_MAX_SIDE_LOG2 {
            return Err(MatCapError::TooLarge {
                side_log2: width_log2,
            });
        }
        let mut out = Self {
            image,
            view: *view,
            rows: [[0; 3]; 3],
            _c: core::marker::PhantomData,
        };
        out.rows = scaled_rows(view);
        Ok(out)
    }

    /// The image.
    pub fn image(&self) -> &Texture<'a> {
        &self.image
    }

    /// The texel `(column, row)` a normal in the space the shader currently takes normals in
    /// (world space, or model space during a draw that lets it) picks: 16.16 bits of its
    /// components, any length. This is the lookup [`Shading::vertex`] makes.
    pub fn texel_of(&self, normal: [i32; 3]) -> (u32, u32) {
        texel_of(&self.rows, normal, self.image.width_log2())
    }
}

/// The upper 3x3 of `m`, scaled by a power of two (only the direction of what it transforms
/// matters) so that its largest entry has [`MATRIX_LEAD`] significant bits; all zero for a
/// matrix without a linear part.
fn scaled_rows<S: Scalar>(m: &Mat4<S>) -> [[i32; 3]; 3] {
    let at = |bits: u32| {
        let mut r = [[0i32; 3]; 3];
        for (row, src) in r.iter_mut().zip(&m.m) {
            for (v, s) in row.iter_mut().zip(src) {
                *v = s.to_scaled_int(bits);
            }
        }
        r
    };
    let largest = |r: &[[i32; 3]; 3]| {
        r.iter()
            .flatten()
            .map(|v| v.unsigned_abs())
            .max()
            .unwrap_or(0)
    };
    // 16 fractional bits find the scale (a lead of at most 31); the entries are then taken again
    // at it, so that a floating-point format keeps its precision for small entries. The clamp
    // only bites where a floating-point entry saturated the first look (beyond 2^15).
    let lead = match largest(&at(16)) {
        0 => return [[0; 3]; 3],
        m => m.ilog2(),
    };
    let limit = 1i32 << (MATRIX_LEAD + 1);
    at(16 + MATRIX_LEAD - lead).map(|row| row.map(|v| v.clamp(-limit, limit)))
}

/// The texel a normal (16.16 bits) picks through `rows` ([`scaled_rows`]) in an image of
/// `2^side_log2` texels a side.
#[inline(always)]
fn texel_of(rows: &[[i32; 3]; 3], n: [i32; 3], side_log2: u8) -> (u32, u32) {
    // Each product at most 2^(MATRIX_LEAD + 32), a sum of three below 2^54.
    let dot = |r: &[i32; 3]| {
        i64::from(r[0]) * i64::from(n[0])
            + i64::from(r[1]) * i64::from(n[1])
            + i64::from(r[2]) * i64::from(n[2])
    };
    let v = [dot(&rows[0]), dot(&rows[1]), dot(&rows[2])];
    let largest = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
    let last = (1u32 << side_log2) - 1;
    if largest == 0 {
        // No direction: the texel facing the camera, round(last / 2).
        let mid = (1u32 << side_log2) >> 1;
        return (mid, mid);
    }
    // Below 2^30 a component, so that the squares' sum (below 2^62) fits a u64.
    let shift = largest.ilog2().saturating_sub(29);
    let [x, y, z] = v.map(|c| c >> shift);
    let sq = [x, y, z].map(|c| c.unsigned_abs() * c.unsigned_abs());
    let (r, k) = crate::math::fx::rsqrt_u64(sq[0] + sq[1] + sq[2]);
    // Unit components in 2.30: |c| r < 2^61, and k >= 31 > UNIT_BITS.
    let unit = |c: i64| (c * r as i64) >> (k - UNIT_BITS);
    // round((u + 1) / 2 · last) = floor(((u + 1) last + 1) / 2) in units of 2^-30: below 2^41.
    let texel = |u: i64| {
        let one = 1i64 << UNIT_BITS;
        let t = ((u + one) * i64::from(last) + one) >> (UNIT_BITS + 1);
        t.clamp(0, i64::from(last)) as u32
    };
    (texel(unit(x)), texel(-unit(y)))
}

impl<S: Scalar, C: ShadeColor> Shading<S> for MatCap<'_, S, C> {
    type Color = C;
    type Varyings = [i32; 3];
    type Stored = [u16; 3];
    const NEEDS_WORLD: bool = true;
    const FUSED_OFFSET: u32 = 0;

    fn fingerprint(&self, out: &mut crate::fingerprint::Fingerprint)
    where
        Self: core::fmt::Debug,
    {
        use core::fmt::Write;
        out.bytes(&[self.image.width_log2()]);
        out.bytes(self.image.bytes());
        let _ = write!(out, "{:?}", self.view);
    }

    fn begin_frame(&mut self, model: Option<&Mat4<S>>) -> bool {
        // With normals that follow the model matrix, model and view in one transform: the
        // pipeline then hands over the mesh's own normals, untransformed.
        self.rows = match model {
            Some(m) => scaled_rows(&m.then(&self.view)),
            None => scaled_rows(&self.view),
        };
        model.is_some()
    }

    #[inline(always)]
    fn vertex(&mut self, v: &VertexIn<S>) -> [i32; 3] {
        let n = [v.normal.x, v.normal.y, v.normal.z].map(S::to_fx16_bits);
        let (x, y) = texel_of(&self.rows, n, self.image.width_log2());
        let rgb = Rgb888::from(Rgb565::from(RawU16::new(self.image.texel(x, y))));
        target_channels::<C>([rgb.r(), rgb.g(), rgb.b()].map(u64::from), 1)
    }

    channel_pixels!();
}
