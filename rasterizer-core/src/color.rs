//! Colour channels for interpolation.
//!
//! Gouraud triangles and colour-interpolated lines work on each channel at its native depth (5 bits
//! for red in Rgb565, 8 in Rgb888), so a vertex colour comes back unchanged at its own pixel.

use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, BinaryColor, Gray2, Gray4, Gray8, GrayColor, Rgb555, Rgb565,
    Rgb666, Rgb888, RgbColor,
};
use embedded_graphics_core::prelude::PixelColor;

/// A colour that can be split into up to four integer channels and put back together.
pub trait Channels: PixelColor {
    /// How many of the four channel slots are used.
    const COUNT: usize;
    /// The channels at their native depth; unused slots are zero.
    fn to_channels(self) -> [u8; 4];
    /// The colour from channels at native depth. Values above a channel's maximum are clamped.
    fn from_channels(c: [u8; 4]) -> Self;
    /// The colour from channels already known to be within range (interpolation between valid
    /// colours). An out-of-range value gives an unspecified colour, never a panic.
    #[inline]
    fn from_channels_in_range(c: [u8; 4]) -> Self {
        Self::from_channels(c)
    }
    /// The colour from fixed-point channels with 16 fractional bits, truncated: the inner loop of
    /// interpolation. Each value must lie in `0 ..= max << 16 | 0xFFFF`; others give an unspecified
    /// colour, never a panic.
    #[inline]
    fn from_fixed16(acc: &[i32; 4]) -> Self {
        let mut c = [0u8; 4];
        for (ch, a) in c.iter_mut().zip(acc).take(Self::COUNT) {
            *ch = (a >> 16) as u8;
        }
        Self::from_channels_in_range(c)
    }
}

macro_rules! rgb_channels {
    ($($t:ty),*) => {$(
        impl Channels for $t {
            const COUNT: usize = 3;
            #[inline]
            fn to_channels(self) -> [u8; 4] {
                [self.r(), self.g(), self.b(), 0]
            }
            #[inline]
            fn from_channels(c: [u8; 4]) -> Self {
                <$t>::new(
                    c[0].min(<$t>::MAX_R),
                    c[1].min(<$t>::MAX_G),
                    c[2].min(<$t>::MAX_B),
                )
            }
            #[inline]
            fn from_channels_in_range(c: [u8; 4]) -> Self {
                // `new` masks each channel to its width, so this cannot panic.
                <$t>::new(c[0], c[1], c[2])
            }
        }
    )*};
}
rgb_channels!(Rgb555, Bgr555, Bgr565, Rgb666, Bgr666, Rgb888, Bgr888);

impl Channels for Rgb565 {
    const COUNT: usize = 3;
    #[inline]
    fn to_channels(self) -> [u8; 4] {
        [self.r(), self.g(), self.b(), 0]
    }
    #[inline]
    fn from_channels(c: [u8; 4]) -> Self {
        Rgb565::new(c[0].min(31), c[1].min(63), c[2].min(31))
    }
    #[inline]
    fn from_channels_in_range(c: [u8; 4]) -> Self {
        Rgb565::new(c[0], c[1], c[2])
    }
    #[inline]
    fn from_fixed16(acc: &[i32; 4]) -> Self {
        // Shift each channel's integer bits straight to their place in the 16-bit word.
        let r = (acc[0] >> 5) as u16 & 0xF800;
        let g = (acc[1] >> 11) as u16 & 0x07E0;
        let b = (acc[2] >> 16) as u16 & 0x001F;
        RawU16::new(r | g | b).into()
    }
}

macro_rules! gray_channels {
    ($($t:ty, $max:expr);*) => {$(
        impl Channels for $t {
            const COUNT: usize = 1;
            #[inline]
            fn to_channels(self) -> [u8; 4] {
                [self.luma(), 0, 0, 0]
            }
            #[inline]
            fn from_channels(c: [u8; 4]) -> Self {
                <$t>::new(c[0].min($max))
            }
        }
    )*};
}
gray_channels!(Gray2, 3; Gray4, 15; Gray8, 255);

impl Channels for BinaryColor {
    const COUNT: usize = 1;
    #[inline]
    fn to_channels(self) -> [u8; 4] {
        [u8::from(self.is_on()), 0, 0, 0]
    }
    #[inline]
    fn from_channels(c: [u8; 4]) -> Self {
        BinaryColor::from(c[0] != 0)
    }
}

/// A colour the lit shaders of the 3D pipeline produce: the depth of each of its three colour
/// channels, so that lit colours are interpolated at the target's own depth and each pixel is
/// rounded once (not to 8 bits first and then again to the target's depth).
///
/// Implemented for the RGB colours of embedded-graphics (at their channel depths) and for the
/// grey colours (8-bit RGB, turned into grey by their `From<Rgb888>`).
pub trait ShadeColor: PixelColor {
    /// The largest value of each of the three interpolated channels: `[31, 63, 31]` for
    /// [`Rgb565`].
    const MAX: [u8; 3];
    /// The colour from the three channels, each at most its [`ShadeColor::MAX`].
    fn from_shade(c: [u8; 3]) -> Self;
}

macro_rules! rgb_shade {
    ($($t:ty),*) => {$(
        impl ShadeColor for $t {
            const MAX: [u8; 3] = [<$t>::MAX_R, <$t>::MAX_G, <$t>::MAX_B];
            #[inline(always)]
            fn from_shade(c: [u8; 3]) -> Self {
                // `new` masks each channel to its width.
                <$t>::new(c[0], c[1], c[2])
            }
        }
    )*};
}
rgb_shade!(Rgb555, Bgr555, Rgb565, Bgr565, Rgb666, Bgr666, Rgb888, Bgr888);

macro_rules! mono_shade {
    ($($t:ty),*) => {$(
        impl ShadeColor for $t {
            const MAX: [u8; 3] = [255; 3];
            #[inline(always)]
            fn from_shade(c: [u8; 3]) -> Self {
                <$t>::from(Rgb888::new(c[0], c[1], c[2]))
            }
        }
    )*};
}
mono_shade!(Gray2, Gray4, Gray8);

/// One channel blended over another: `round((src a + dst (255 - a)) / 255)` with halves rounded
/// up, exactly, for channels of any depth up to 8 bits and opacity `alpha` out of 255.
///
/// Integer only and division-free: the sum `x` is below 65,280, where `(x + 1 + (x >> 8)) >> 8`
/// equals `x / 255` (checked for every `x` by a test), so each pixel costs two multiplies and
/// shifts even on a core without a divider. Opacity 255 gives `src` and 0 gives `dst` exactly.
#[inline(always)]
pub fn blend_channel(src: u8, dst: u8, alpha: u8) -> u8 {
    let a = u32::from(alpha);
    let x = u32::from(src) * a + u32::from(dst) * (255 - a) + 127;
    ((x + 1 + (x >> 8)) >> 8) as u8
}

/// `src` over `dst` with opacity `alpha` (0 transparent ..= 255 opaque), each channel at its
/// native depth with [`blend_channel`]: no conversion to 8 bits and back, so blending a colour
/// over itself gives it back unchanged.
#[inline]
pub fn blend<C: Channels>(src: C, dst: C, alpha: u8) -> C {
    let (s, d) = (src.to_channels(), dst.to_channels());
    let mut c = [0u8; 4];
    for ((c, s), d) in c.iter_mut().zip(s).zip(d).take(C::COUNT) {
        *c = blend_channel(s, d, alpha);
    }
    // A blend of two in-range values lies between them.
    C::from_channels_in_range(c)
}

/// One bit: each channel is interpolated between 0 and 1 and the pixel is on where
/// embedded-graphics' conversion from RGB says so (its luma at least one half), so a grey
/// material gives the classic black-and-white dithering.
impl ShadeColor for BinaryColor {
    const MAX: [u8; 3] = [1; 3];
    #[inline(always)]
    fn from_shade(c: [u8; 3]) -> Self {
        let full = |v: u8| if v != 0 { 255 } else { 0 };
        BinaryColor::from(Rgb888::new(full(c[0]), full(c[1]), full(c[2])))
    }
}
