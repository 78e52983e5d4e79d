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
    /// Where each channel's 16.16 value (as [`Channels::from_fixed16`] takes it) sits in one
    /// `u64`, when all of them fit side by side: the shift of each channel's field, in the
    /// order of [`Channels::to_channels`], each field `16 +` the channel's bits wide and up to
    /// the next one (64 bits in all at most). A Gouraud span then steps every channel with one
    /// add a pixel and colours a pixel with [`Channels::from_packed16`].
    const PACKED16: Option<[u32; 4]> = None;
    /// The colour from a [`Channels::PACKED16`] word: each channel's field within
    /// `0 ..= max << 16 | 0xFFFF`, others giving an unspecified colour, never a panic.
    #[inline]
    fn from_packed16(acc: u64) -> Self {
        Self::from_fixed16(&packed_fields::<Self>(acc))
    }
}

/// The channels of a [`Channels::PACKED16`] word, each its field: the bits from its shift up to
/// the next field's (or the word's end); zeros for a colour with no packed layout.
#[inline]
pub(crate) fn packed_fields<C: Channels>(acc: u64) -> [i32; 4] {
    let mut c = [0i32; 4];
    if let Some(shift) = C::PACKED16 {
        let used = &shift[..C::COUNT.min(4)];
        for (ch, &s) in c.iter_mut().zip(used) {
            let end = used.iter().filter(|&&t| t > s).min().map_or(64, |&t| t);
            let bits = acc.checked_shr(s).unwrap_or(0);
            let mask = 1u64.checked_shl(end - s).map_or(u64::MAX, |m| m - 1);
            *ch = (bits & mask) as i32;
        }
    }
    c
}

/// `Channels` for an RGB colour, with `{ ... }` the items that replace the trait's defaults.
macro_rules! rgb_channels {
    ($t:ty { $($extra:tt)* }) => {
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
            $($extra)*
        }
    };
    ($($t:ty),*) => {$(rgb_channels!($t {});)*};
}
rgb_channels!(Rgb555, Bgr555, Rgb666, Bgr666, Rgb888, Bgr888);
// Red in bits 43 ..= 63 of the packed word, green 21 ..= 42, blue 0 ..= 20.
rgb_channels!(Rgb565 {
    #[inline]
    fn from_fixed16(acc: &[i32; 4]) -> Self {
        fixed16_565(acc, 0, 2).into()
    }
    const PACKED16: Option<[u32; 4]> = Some([43, 21, 0, 0]);
    #[inline]
    fn from_packed16(acc: u64) -> Self {
        rgb565_from_packed16(acc).into()
    }
});
// The other way round, as in the pixel: blue highest.
rgb_channels!(Bgr565 {
    #[inline]
    fn from_fixed16(acc: &[i32; 4]) -> Self {
        fixed16_565(acc, 2, 0).into()
    }
    const PACKED16: Option<[u32; 4]> = Some([0, 21, 43, 0]);
    #[inline]
    fn from_packed16(acc: u64) -> Self {
        rgb565_from_packed16(acc).into()
    }
});

/// [`Channels::from_fixed16`] of a 5/6/5 colour whose channel `high` lies in the pixel's high
/// bits and `low` in its low ones: each channel's integer bits shifted straight to their place.
#[inline(always)]
fn fixed16_565(acc: &[i32; 4], high: usize, low: usize) -> RawU16 {
    let h = (acc[high & 3] >> 5) as u16 & 0xF800;
    let g = (acc[1] >> 11) as u16 & 0x07E0;
    let l = (acc[low & 3] >> 16) as u16 & 0x001F;
    RawU16::new(h | g | l)
}

/// [`Channels::from_packed16`] of [`Rgb565`] (and of [`Bgr565`], whose word holds the channels
/// in the pixel's order too): the upper half holds the highest field's integer bits at 27 ..= 31
/// and the middle one's at 5 ..= 10, which one 32-bit product moves to 11 ..= 15 and 21 ..= 26
/// of the product (the masked bits times `1 + 2^16`: the copies it also makes lie below bit 16
/// or above bit 31), and the lowest field's integer bits are bits 16 ..= 20 of the lower half.
#[inline(always)]
fn rgb565_from_packed16(acc: u64) -> RawU16 {
    let hi = (acc >> 32) as u32;
    // The product's third term (2^27) moves every masked bit past bit 31, where it wraps away:
    // it only keeps the compiler from making the product two shifts and an or, dearer than
    // the one multiply.
    let high_two = ((hi & 0xF800_07E0).wrapping_mul(0x0801_0001) >> 16) as u16;
    let low = ((acc as u32) >> 16) as u16 & 0x001F;
    RawU16::new(high_two | low)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Every channel value of a 5/6/5 colour with random fractions, packed at the colour's
    /// shifts: the word gives the colour of its channels' integer parts (embedded-graphics'
    /// own constructor, the reference), and `from_fixed16` of the same values agrees.
    fn packed_words_decode<C: Channels + PartialEq + core::fmt::Debug>() {
        let shift = C::PACKED16.expect("a packed layout");
        // Random fractions from a linear congruential generator (this layer has no other).
        let mut state = 0x243f_6a88_85a3_08d3u64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            state >> 32
        };
        let max = [31u32, 63, 31];
        for r in 0..=max[0] {
            for g in 0..=max[1] {
                for b in 0..=max[2] {
                    for _ in 0..4 {
                        let v = [r, g, b].map(|c| (c << 16 | (next() as u32 & 0xFFFF)) as i32);
                        let word = (0..3).fold(0u64, |w, i| w | (v[i] as u64) << shift[i]);
                        let want = C::from_channels_in_range([r as u8, g as u8, b as u8, 0]);
                        assert_eq!(C::from_packed16(word), want, "{r} {g} {b} {word:x}");
                        assert_eq!(C::from_fixed16(&[v[0], v[1], v[2], 0]), want);
                        // The trait's default decoding, for a colour that only declares a
                        // layout, gives each field back.
                        assert_eq!(packed_fields::<C>(word), [v[0], v[1], v[2], 0]);
                    }
                }
            }
        }
    }

    #[test]
    fn rgb565_packed_words_decode() {
        packed_words_decode::<Rgb565>();
    }

    #[test]
    fn bgr565_packed_words_decode() {
        packed_words_decode::<Bgr565>();
    }

    /// The packed layouts' fields are disjoint and fit the word: `16 +` each channel's bits.
    #[test]
    fn packed_fields_fit_their_words() {
        for (shift, bits) in [
            (Rgb565::PACKED16, [5u32, 6, 5]),
            (Bgr565::PACKED16, [5, 6, 5]),
        ] {
            let shift = shift.expect("a packed layout");
            let mut used = 0u128;
            for c in 0..3 {
                let field = ((1u128 << (16 + bits[c])) - 1) << shift[c];
                assert_eq!(used & field, 0, "fields overlap");
                used |= field;
            }
            assert!(used < 1 << 64);
        }
    }
}
