//! Textures: Rgb565 texels read in place from a byte slice (flash), power-of-two sides.
//!
//! Texture coordinates are 16.16 fixed point in units of the whole texture: `(0, 0)` is the
//! top-left corner of the first texel (row 0 is the image's top row), `(1.0, 1.0)` = `(65536,
//! 65536)` the bottom-right corner of the last. (OBJ files count `v` from the bottom; the converter
//! flips it.) Values outside `0 ..= 1` repeat the texture or clamp to its edge ([`Wrap`]).
//!
//! Texels are little-endian Rgb565, row after row, `width * height * 2` bytes; the reader decodes
//! with `from_le_bytes`, so the slice needs no alignment.

use core::fmt;

/// The largest side, as a power of two: 1024 texels (2 MiB at 2 bytes a texel).
pub const MAX_SIDE_LOG2: u8 = 10;

/// Why bytes are not a texture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureError {
    /// A side above `2^MAX_SIDE_LOG2` texels.
    TooLarge {
        /// The width's power of two.
        width_log2: u8,
        /// The height's power of two.
        height_log2: u8,
    },
    /// The slice is not `width * height * 2` bytes.
    WrongLength {
        /// Bytes the sides need.
        expected: usize,
        /// Bytes given.
        actual: usize,
    },
}

impl fmt::Display for TextureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooLarge {
                width_log2,
                height_log2,
            } => write!(
                f,
                "a {}x{} texture is larger than {max}x{max} texels",
                1u64 << (*width_log2).min(63),
                1u64 << (*height_log2).min(63),
                max = 1u32 << MAX_SIDE_LOG2
            ),
            Self::WrongLength { expected, actual } => write!(
                f,
                "{actual} bytes of texels where the sides need {expected} (2 bytes a texel)"
            ),
        }
    }
}

impl core::error::Error for TextureError {}

/// How coordinates outside `0 ..= 1` address the texture.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Wrap {
    /// The texture repeats (tiles).
    #[default]
    Repeat,
    /// The edge texels continue outwards.
    Clamp,
}

/// How a texel is picked at a point between texel centres.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Filter {
    /// The texel the point falls in.
    #[default]
    Nearest,
    /// The four nearest texels, weighted by distance (in 1/16 texel steps).
    Bilinear,
}

/// An Rgb565 texture with power-of-two sides, borrowed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Texture<'a> {
    texels: &'a [u8],
    width_log2: u8,
    height_log2: u8,
}

impl<'a> Texture<'a> {
    /// A texture of `2^width_log2 x 2^height_log2` texels from their little-endian Rgb565 bytes.
    pub const fn new(
        width_log2: u8,
        height_log2: u8,
        texels: &'a [u8],
    ) -> Result<Self, TextureError> {
        if width_log2 > MAX_SIDE_LOG2 || height_log2 > MAX_SIDE_LOG2 {
            return Err(TextureError::TooLarge {
                width_log2,
                height_log2,
            });
        }
        let expected = 2 << (width_log2 + height_log2);
        if texels.len() != expected {
            return Err(TextureError::WrongLength {
                expected,
                actual: texels.len(),
            });
        }
        Ok(Self {
            texels,
            width_log2,
            height_log2,
        })
    }

    /// A texture whose sides and length the caller has checked ([`crate::mesh::PackedMesh`]'s
    /// parser): no second check in the code. Wrong ones read texels as 0, never out of bounds.
    pub(crate) const fn checked(width_log2: u8, height_log2: u8, texels: &'a [u8]) -> Self {
        Self {
            texels,
            width_log2,
            height_log2,
        }
    }

    /// The width's power of two.
    pub const fn width_log2(&self) -> u8 {
        self.width_log2
    }

    /// The height's power of two.
    pub const fn height_log2(&self) -> u8 {
        self.height_log2
    }

    /// Width in texels.
    pub const fn width(&self) -> u32 {
        1 << self.width_log2
    }

    /// Height in texels.
    pub const fn height(&self) -> u32 {
        1 << self.height_log2
    }

    /// The texel bytes.
    pub const fn bytes(&self) -> &'a [u8] {
        self.texels
    }

    /// The raw Rgb565 texel at `(x, y)`, both taken modulo the sides.
    #[inline(always)]
    pub fn texel(&self, x: u32, y: u32) -> u16 {
        let x = x & ((1 << self.width_log2) - 1);
        let y = y & ((1 << self.height_log2) - 1);
        let i = 2 * ((y << self.width_log2) | x) as usize;
        match self.texels.get(i..i + 2) {
            Some(&[lo, hi]) => u16::from_le_bytes([lo, hi]),
            // The length was checked when the texture was made.
            _ => 0,
        }
    }
}
