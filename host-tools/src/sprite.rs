//! `host-tools sprite`: a PNG converted into the sprite format `rasterizer_core::raster::sprite`
//! reads in place (`Sprite::from_bytes`, e.g. over `include_bytes!`), and the same conversion for
//! scene files.
//!
//! Colours are rounded to the nearest Rgb565 step; the alpha channel is kept at 0, 1, 4 or 8 bits
//! (`--alpha`), by default the fewest that hold it exactly (none when every pixel is opaque, one
//! bit when every pixel is fully opaque or fully transparent, else eight).

use rasterizer_core::raster::sprite::{header, AlphaBits, Sprite, SpriteError, MAX_SIDE};
use std::fmt;
use std::path::{Path, PathBuf};

/// The alpha depth asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum AlphaChoice {
    /// The fewest bits that hold the image's alpha exactly.
    #[default]
    Auto,
    /// No alpha: every pixel opaque (the PNG's alpha is dropped).
    #[value(name = "0")]
    None,
    /// One bit: opaque where the PNG's alpha is at least 128.
    #[value(name = "1")]
    One,
    /// Four bits, rounded to the nearest of 16 steps.
    #[value(name = "4")]
    Four,
    /// Eight bits, as in the PNG (16-bit PNGs rounded).
    #[value(name = "8")]
    Eight,
}

/// Options of the `sprite` command.
#[derive(Debug, clap::Args)]
pub struct SpriteArgs {
    /// The PNG to convert (any colour type and depth the PNG format has).
    pub input: PathBuf,
    /// Where to write the sprite (`.bin`, or `-` for standard output). An existing file is
    /// replaced only once the new one is complete; the input itself is refused.
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
    /// Bits of alpha to keep: auto, 0, 1, 4 or 8.
    #[arg(long, value_enum, default_value_t = AlphaChoice::Auto)]
    pub alpha: AlphaChoice,
}

/// Why a PNG did not become a sprite.
#[derive(Debug)]
pub enum SpriteConvertError {
    /// The file could not be read.
    Read(std::io::Error),
    /// The bytes are not a PNG the decoder understands.
    Decode(String),
    /// A side above the sprite format's limit.
    TooLarge {
        /// The PNG's width.
        width: u32,
        /// The PNG's height.
        height: u32,
    },
    /// The core refused the result (cannot happen for a decoded PNG within the size limit).
    Format(SpriteError),
}

impl fmt::Display for SpriteConvertError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read(e) => write!(f, "cannot read: {e}"),
            Self::Decode(e) => write!(f, "not a PNG image: {e}"),
            Self::TooLarge { width, height } => write!(
                f,
                "the image is {width}x{height}; sprites are at most {MAX_SIDE}x{MAX_SIDE}"
            ),
            Self::Format(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for SpriteConvertError {}

/// A PNG's bytes as sprite bytes, and the alpha depth chosen.
///
/// # Errors
/// [`SpriteConvertError::Decode`] for bytes that are not a PNG, [`SpriteConvertError::TooLarge`]
/// for a side above [`MAX_SIDE`].
pub fn png_to_sprite(
    png: &[u8],
    alpha: AlphaChoice,
) -> Result<(Vec<u8>, AlphaBits), SpriteConvertError> {
    let img = image::load_from_memory_with_format(png, image::ImageFormat::Png)
        .map_err(|e| SpriteConvertError::Decode(e.to_string()))?
        .to_rgba8();
    let (width, height) = img.dimensions();
    if width > MAX_SIDE || height > MAX_SIDE {
        return Err(SpriteConvertError::TooLarge { width, height });
    }
    let bits = match alpha {
        AlphaChoice::Auto if img.pixels().all(|p| p[3] == 255) => AlphaBits::None,
        AlphaChoice::Auto if img.pixels().all(|p| p[3] == 0 || p[3] == 255) => AlphaBits::One,
        AlphaChoice::Auto | AlphaChoice::Eight => AlphaBits::Eight,
        AlphaChoice::None => AlphaBits::None,
        AlphaChoice::One => AlphaBits::One,
        AlphaChoice::Four => AlphaBits::Four,
    };
    let mut out = header(width, height, bits)
        .map_err(SpriteConvertError::Format)?
        .to_vec();
    for p in img.pixels() {
        out.extend_from_slice(&fixtures::texture_file::rgb565(p[0], p[1], p[2]).to_le_bytes());
    }
    let row_bytes = bits.row_bytes(width);
    for row in img.rows() {
        let mut packed = vec![0u8; row_bytes];
        for (x, p) in row.enumerate() {
            let a = p[3];
            match bits {
                AlphaBits::None => {}
                AlphaBits::One => packed[x / 8] |= u8::from(a >= 128) << (7 - x % 8),
                // Nearest of 16 steps: round(a * 15 / 255).
                AlphaBits::Four => {
                    let q = ((u32::from(a) * 15 + 127) / 255) as u8;
                    packed[x / 2] |= q << (4 * (1 - x % 2));
                }
                AlphaBits::Eight => packed[x] = a,
            }
        }
        out.extend_from_slice(&packed);
    }
    // The reader's own check, so that what is written is surely readable.
    Sprite::from_bytes(&out).map_err(SpriteConvertError::Format)?;
    Ok((out, bits))
}

/// Reads and converts a PNG file.
///
/// # Errors
/// As [`png_to_sprite`], and [`SpriteConvertError::Read`].
pub fn load_png_sprite(
    path: &Path,
    alpha: AlphaChoice,
) -> Result<(Vec<u8>, AlphaBits), SpriteConvertError> {
    let bytes = std::fs::read(path).map_err(SpriteConvertError::Read)?;
    png_to_sprite(&bytes, alpha)
}

/// Runs the command: converts, writes the output only on success, and prints a summary.
///
/// # Errors
/// A message naming the input, or the output's [`crate::output::OutputError`].
pub fn run(args: &SpriteArgs) -> Result<(), Box<dyn std::error::Error>> {
    crate::output::check_output(
        &args.output,
        &[args.input.as_path()],
        &["bin"],
        "a sprite",
        "",
    )?;
    let (bytes, bits) = load_png_sprite(&args.input, args.alpha)
        .map_err(|e| format!("{}: {e}", args.input.display()))?;
    crate::output::write_output(&args.output, &[args.input.as_path()], |w| {
        std::io::Write::write_all(w, &bytes)
    })?;
    let sprite = Sprite::from_bytes(&bytes)?;
    crate::sayln!(
        crate::output::goes_to_stdout(&args.output),
        "{} -> {}: {}x{} sprite, {} alpha bits, {} bytes",
        args.input.display(),
        args.output.display(),
        sprite.width(),
        sprite.height(),
        bits.bits(),
        bytes.len()
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(width: u32, height: u32, rgba: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        image::ImageEncoder::write_image(
            image::codecs::png::PngEncoder::new(&mut out),
            rgba,
            width,
            height,
            image::ExtendedColorType::Rgba8,
        )
        .unwrap();
        out
    }

    #[test]
    fn converts_colours_and_each_alpha_depth() {
        // Red opaque, green half, blue transparent.
        let rgba = [255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0];
        let file = png(3, 1, &rgba);
        let (bytes, bits) = png_to_sprite(&file, AlphaChoice::Auto).unwrap();
        assert_eq!(bits, AlphaBits::Eight);
        let s = Sprite::from_bytes(&bytes).unwrap();
        assert_eq!(
            [s.texel(0, 0), s.texel(1, 0), s.texel(2, 0)],
            [(0xF800, 255), (0x07E0, 128), (0x001F, 0)]
        );
        let (bytes, _) = png_to_sprite(&file, AlphaChoice::Four).unwrap();
        let s = Sprite::from_bytes(&bytes).unwrap();
        // round(128 * 15 / 255) = 8, read back as 8 * 17.
        assert_eq!([s.texel(1, 0).1, s.texel(2, 0).1], [136, 0]);
        let (bytes, _) = png_to_sprite(&file, AlphaChoice::One).unwrap();
        let s = Sprite::from_bytes(&bytes).unwrap();
        assert_eq!(
            [s.texel(0, 0).1, s.texel(1, 0).1, s.texel(2, 0).1],
            [255, 255, 0]
        );
        let (bytes, bits) = png_to_sprite(&file, AlphaChoice::None).unwrap();
        assert_eq!((bits, bytes.len()), (AlphaBits::None, 12 + 6));
        // Auto picks the fewest bits that hold the alpha exactly.
        let opaque = png(1, 1, &[1, 2, 3, 255]);
        assert_eq!(
            png_to_sprite(&opaque, AlphaChoice::Auto).unwrap().1,
            AlphaBits::None
        );
        let keyed = png(2, 1, &[1, 2, 3, 255, 4, 5, 6, 0]);
        assert_eq!(
            png_to_sprite(&keyed, AlphaChoice::Auto).unwrap().1,
            AlphaBits::One
        );
    }

    #[test]
    fn bad_pngs_are_typed_errors() {
        assert!(matches!(
            png_to_sprite(b"not a png", AlphaChoice::Auto),
            Err(SpriteConvertError::Decode(_))
        ));
        let mut file = png(2, 2, &[7; 16]);
        file.truncate(file.len() / 2);
        assert!(matches!(
            png_to_sprite(&file, AlphaChoice::Auto),
            Err(SpriteConvertError::Decode(_))
        ));
        let wide = png(MAX_SIDE + 1, 1, &vec![0; 4 * (MAX_SIDE as usize + 1)]);
        assert!(matches!(
            png_to_sprite(&wide, AlphaChoice::Auto),
            Err(SpriteConvertError::TooLarge {
                width: 4097,
                height: 1
            })
        ));
    }
}
