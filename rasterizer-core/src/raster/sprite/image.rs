//! The sprite image format: Rgb565 texels with an optional alpha plane of 1, 4 or 8 bits, read in
//! place from bytes (flash, `include_bytes!`), so firmware needs no copy and no allocation.

use core::fmt;

/// The largest width or height of a [`Sprite`], in texels.
///
/// It keeps texel coordinates (32.32 in `i64`, see [`super::Affine`]) far from their limits and a
/// quad of the largest image at the largest scale inside `i64` in 16.16.
pub const MAX_SIDE: u32 = 4096;

/// The four bytes a sprite file starts with.
pub const MAGIC: [u8; 4] = *b"RSPR";

/// The format version this crate reads and the host tools write.
pub const VERSION: u8 = 1;

/// Bytes of the header: magic (4), version (1), alpha bits (1), width (2, little-endian),
/// height (2, little-endian), reserved (2, zero).
pub const HEADER_LEN: usize = 12;

/// Bits of the alpha channel of a sprite.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum AlphaBits {
    /// No alpha: every texel is opaque.
    #[default]
    None,
    /// One bit a texel (the most significant bit of a byte is the leftmost texel): 1 draws the
    /// texel, 0 leaves the pixel. No blending, so any surface can take it.
    One,
    /// Four bits a texel (the high nibble is the leftmost texel), 0 ..= 15, blended.
    Four,
    /// Eight bits a texel, 0 ..= 255, blended.
    Eight,
}

impl AlphaBits {
    /// From the header's bit count (0, 1, 4 or 8).
    pub const fn from_bits(bits: u8) -> Option<Self> {
        match bits {
            0 => Some(Self::None),
            1 => Some(Self::One),
            4 => Some(Self::Four),
            8 => Some(Self::Eight),
            _ => None,
        }
    }

    /// The bit count the header stores.
    pub const fn bits(self) -> u8 {
        match self {
            Self::None => 0,
            Self::One => 1,
            Self::Four => 4,
            Self::Eight => 8,
        }
    }

    /// Bytes of one row of the alpha plane: rows are padded to whole bytes.
    pub const fn row_bytes(self, width: u32) -> usize {
        let w = width as usize;
        match self {
            Self::None => 0,
            Self::One => w.div_ceil(8),
            Self::Four => w.div_ceil(2),
            Self::Eight => w,
        }
    }
}

/// Why bytes are not a sprite.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpriteError {
    /// The bytes do not start with [`MAGIC`].
    BadMagic,
    /// A version this crate does not read.
    UnsupportedVersion(u8),
    /// An alpha bit count other than 0, 1, 4 or 8.
    UnsupportedAlphaBits(u8),
    /// A width or height of zero or above [`MAX_SIDE`].
    BadSize {
        /// The width given.
        width: u32,
        /// The height given.
        height: u32,
    },
    /// The bytes are not as long as the header, the size and the alpha bits need.
    WrongLength {
        /// Bytes the sprite needs.
        expected: usize,
        /// Bytes given.
        actual: usize,
    },
}

impl fmt::Display for SpriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BadMagic => write!(f, "not a sprite: the bytes do not start with \"RSPR\""),
            Self::UnsupportedVersion(v) => {
                write!(f, "sprite format version {v}; this reader knows {VERSION}")
            }
            Self::UnsupportedAlphaBits(b) => {
                write!(f, "{b} alpha bits; sprites have 0, 1, 4 or 8")
            }
            Self::BadSize { width, height } => write!(
                f,
                "a {width}x{height} sprite is outside 1..={MAX_SIDE} texels in each axis"
            ),
            Self::WrongLength { expected, actual } => {
                write!(f, "{actual} bytes where the sprite needs {expected}")
            }
        }
    }
}

impl core::error::Error for SpriteError {}

/// An image to draw with [`super::draw_sprite`], borrowed: Rgb565 texels (little-endian, row after
/// row, `width * height * 2` bytes) and an optional alpha plane (rows padded to whole bytes, see
/// [`AlphaBits`]).
///
/// The file format ([`Sprite::from_bytes`], written by the host tools' `sprite` command) is a
/// [`HEADER_LEN`]-byte header, then the texels, then the alpha plane. Nothing needs alignment.
///
/// ```
/// use rasterizer_core::raster::sprite::{AlphaBits, Sprite};
///
/// // A 2x1 sprite: red and blue, the blue texel transparent (1-bit alpha, 0b10 in the top bits).
/// let bytes = [b'R', b'S', b'P', b'R', 1, 1, 2, 0, 1, 0, 0, 0, 0x00, 0xF8, 0x1F, 0x00, 0b1000_0000];
/// let sprite = Sprite::from_bytes(&bytes).unwrap();
/// assert_eq!((sprite.width(), sprite.height(), sprite.alpha_bits()), (2, 1, AlphaBits::One));
/// assert_eq!(sprite.texel(1, 0), (0x001F, 0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Sprite<'a> {
    width: u32,
    height: u32,
    alpha: AlphaBits,
    colors: &'a [u8],
    alpha_plane: &'a [u8],
}

impl<'a> Sprite<'a> {
    /// Reads a sprite file in place.
    ///
    /// # Errors
    /// [`SpriteError`] for bytes that are not a sprite of this version, of a supported size and
    /// alpha, with exactly the length those need.
    pub fn from_bytes(bytes: &'a [u8]) -> Result<Self, SpriteError> {
        let Some((head, body)) = bytes.split_first_chunk::<HEADER_LEN>() else {
            if bytes.len() >= 4 && bytes[..4] != MAGIC {
                return Err(SpriteError::BadMagic);
            }
            return Err(SpriteError::WrongLength {
                expected: HEADER_LEN,
                actual: bytes.len(),
            });
        };
        if head[..4] != MAGIC {
            return Err(SpriteError::BadMagic);
        }
        if head[4] != VERSION {
            return Err(SpriteError::UnsupportedVersion(head[4]));
        }
        let alpha =
            AlphaBits::from_bits(head[5]).ok_or(SpriteError::UnsupportedAlphaBits(head[5]))?;
        let width = u32::from(u16::from_le_bytes([head[6], head[7]]));
        let height = u32::from(u16::from_le_bytes([head[8], head[9]]));
        check_size(width, height)?;
        let colors = width as usize * height as usize * 2;
        let expected = colors + alpha.row_bytes(width) * height as usize;
        if body.len() != expected {
            return Err(SpriteError::WrongLength {
                expected: HEADER_LEN + expected,
                actual: bytes.len(),
            });
        }
        let (colors, alpha_plane) = body.split_at(colors);
        Ok(Self {
            width,
            height,
            alpha,
            colors,
            alpha_plane,
        })
    }

    /// A sprite from its parts: `colors` the Rgb565 texels (`width * height * 2` bytes,
    /// little-endian), `alpha_plane` the alpha rows (empty for [`AlphaBits::None`]).
    ///
    /// # Errors
    /// [`SpriteError::BadSize`] for a side of zero or above [`MAX_SIDE`],
    /// [`SpriteError::WrongLength`] (counting the two slices together) for slices of other lengths.
    pub fn from_parts(
        width: u32,
        height: u32,
        alpha: AlphaBits,
        colors: &'a [u8],
        alpha_plane: &'a [u8],
    ) -> Result<Self, SpriteError> {
        check_size(width, height)?;
        let need_colors = width as usize * height as usize * 2;
        let need_alpha = alpha.row_bytes(width) * height as usize;
        if colors.len() != need_colors || alpha_plane.len() != need_alpha {
            return Err(SpriteError::WrongLength {
                expected: need_colors + need_alpha,
                actual: colors.len() + alpha_plane.len(),
            });
        }
        Ok(Self {
            width,
            height,
            alpha,
            colors,
            alpha_plane,
        })
    }

    /// The same texels with the alpha channel ignored: every texel opaque.
    pub const fn without_alpha(self) -> Self {
        Self {
            alpha: AlphaBits::None,
            alpha_plane: &[],
            ..self
        }
    }

    /// Width in texels, `1 ..= MAX_SIDE`.
    pub const fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels, `1 ..= MAX_SIDE`.
    pub const fn height(&self) -> u32 {
        self.height
    }

    /// The alpha channel's bits.
    pub const fn alpha_bits(&self) -> AlphaBits {
        self.alpha
    }

    /// The texel bytes (little-endian Rgb565, row after row).
    pub const fn color_bytes(&self) -> &'a [u8] {
        self.colors
    }

    /// The alpha plane's bytes (empty without alpha).
    pub const fn alpha_bytes(&self) -> &'a [u8] {
        self.alpha_plane
    }

    /// Texel `(x, y)`: its raw Rgb565 value and its opacity scaled to `0 ..= 255` (255 without
    /// alpha; a 4-bit value `a` becomes `17 a`, a 1-bit one 0 or 255). Coordinates outside the
    /// image read as `(0, 0)`, never out of bounds.
    #[inline(always)]
    pub fn texel(&self, x: u32, y: u32) -> (u16, u8) {
        if x >= self.width || y >= self.height {
            return (0, 0);
        }
        let i = (y * self.width + x) as usize * 2;
        let c = match self.colors.get(i..i + 2) {
            Some(&[lo, hi]) => u16::from_le_bytes([lo, hi]),
            _ => 0,
        };
        (c, self.alpha_at(x, y))
    }

    /// The opacity of texel `(x, y)` (inside the image), `0 ..= 255`.
    #[inline(always)]
    fn alpha_at(&self, x: u32, y: u32) -> u8 {
        let row = y as usize * self.alpha.row_bytes(self.width);
        let byte = |i: usize| self.alpha_plane.get(row + i).copied().unwrap_or(0);
        match self.alpha {
            AlphaBits::None => 255,
            AlphaBits::One => {
                let bit = byte(x as usize / 8) >> (7 - x % 8) & 1;
                0u8.wrapping_sub(bit)
            }
            AlphaBits::Four => {
                let nibble = byte(x as usize / 2) >> (4 * (1 - x % 2)) & 0xF;
                nibble * 17
            }
            AlphaBits::Eight => byte(x as usize),
        }
    }
}

fn check_size(width: u32, height: u32) -> Result<(), SpriteError> {
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        return Err(SpriteError::BadSize { width, height });
    }
    Ok(())
}

/// Writes the header of a sprite file into `out` (for tools and tests that build sprite bytes).
///
/// # Errors
/// As [`Sprite::from_parts`] for the size.
pub fn header(width: u32, height: u32, alpha: AlphaBits) -> Result<[u8; HEADER_LEN], SpriteError> {
    check_size(width, height)?;
    let (w, h) = ((width as u16).to_le_bytes(), (height as u16).to_le_bytes());
    Ok([
        MAGIC[0],
        MAGIC[1],
        MAGIC[2],
        MAGIC[3],
        VERSION,
        alpha.bits(),
        w[0],
        w[1],
        h[0],
        h[1],
        0,
        0,
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_what_is_not_a_sprite() {
        let good = header(2, 1, AlphaBits::Four).unwrap();
        let mut bytes = [0u8; HEADER_LEN + 5];
        bytes[..HEADER_LEN].copy_from_slice(&good);
        assert!(Sprite::from_bytes(&bytes).is_ok());
        assert_eq!(
            Sprite::from_bytes(&bytes[..HEADER_LEN + 4]),
            Err(SpriteError::WrongLength {
                expected: HEADER_LEN + 5,
                actual: HEADER_LEN + 4
            })
        );
        assert_eq!(
            Sprite::from_bytes(b"RSP"),
            Err(SpriteError::WrongLength {
                expected: HEADER_LEN,
                actual: 3
            })
        );
        assert_eq!(Sprite::from_bytes(b"PNG\x0d"), Err(SpriteError::BadMagic));
        let mut b = bytes;
        b[0] = b'X';
        assert_eq!(Sprite::from_bytes(&b), Err(SpriteError::BadMagic));
        let mut b = bytes;
        b[4] = 2;
        assert_eq!(
            Sprite::from_bytes(&b),
            Err(SpriteError::UnsupportedVersion(2))
        );
        let mut b = bytes;
        b[5] = 2;
        assert_eq!(
            Sprite::from_bytes(&b),
            Err(SpriteError::UnsupportedAlphaBits(2))
        );
        let mut b = bytes;
        b[6] = 0;
        assert_eq!(
            Sprite::from_bytes(&b),
            Err(SpriteError::BadSize {
                width: 0,
                height: 1
            })
        );
        let mut b = bytes;
        b[6..8].copy_from_slice(&4097u16.to_le_bytes());
        assert_eq!(
            Sprite::from_bytes(&b),
            Err(SpriteError::BadSize {
                width: 4097,
                height: 1
            })
        );
        assert!(header(0, 5, AlphaBits::None).is_err());
    }

    #[test]
    fn alpha_planes_unpack_per_bit_depth() {
        let colors = [0u8; 3 * 2 * 2];
        // Rows padded to whole bytes: row 1 starts a new byte in each depth.
        let one = [0b1010_0000, 0b0110_0000];
        let s = Sprite::from_parts(3, 2, AlphaBits::One, &colors, &one).unwrap();
        let got: [u8; 6] = core::array::from_fn(|i| s.texel(i as u32 % 3, i as u32 / 3).1);
        assert_eq!(got, [255, 0, 255, 0, 255, 255]);
        let four = [0x0F, 0x70, 0x12, 0x30];
        let s = Sprite::from_parts(3, 2, AlphaBits::Four, &colors, &four).unwrap();
        let got: [u8; 6] = core::array::from_fn(|i| s.texel(i as u32 % 3, i as u32 / 3).1);
        assert_eq!(got, [0, 255, 7 * 17, 17, 2 * 17, 3 * 17]);
        let eight = [1, 2, 3, 4, 5, 6];
        let s = Sprite::from_parts(3, 2, AlphaBits::Eight, &colors, &eight).unwrap();
        let got: [u8; 6] = core::array::from_fn(|i| s.texel(i as u32 % 3, i as u32 / 3).1);
        assert_eq!(got, [1, 2, 3, 4, 5, 6]);
        assert_eq!(s.texel(3, 0), (0, 0));
        assert_eq!(s.without_alpha().texel(1, 1).1, 255);
    }
}
