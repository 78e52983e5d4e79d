//! Colour channels for interpolation.
//!
//! Gouraud triangles and colour-interpolated lines work on each channel at its native depth (5 bits
//! for red in Rgb565, 8 in Rgb888), so a vertex colour comes back unchanged at its own pixel.

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
rgb_channels!(Rgb555, Bgr555, Rgb565, Bgr565, Rgb666, Bgr666, Rgb888, Bgr888);

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
