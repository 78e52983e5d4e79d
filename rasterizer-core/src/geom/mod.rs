//! Screen-space coordinate types shared by every rasterizer.
//!
//! Pixel (x, y) covers `[x, x + 1) x [y, y + 1)` with y pointing down; it is sampled at its centre
//! `(x + 0.5, y + 0.5)`. Filled primitives take vertices in sub-pixel fixed point so that meshes stay
//! watertight after projection; lines and points take whole pixels ([`mod@line`] defines which).
//! [`Varyings`] are the values a vertex carries to be interpolated across a primitive.

pub mod line;

use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;

/// The default number of sub-pixel bits: 28.4 fixed point, 1/16 of a pixel.
pub const DEFAULT_SUBPIXEL_BITS: u32 = 4;

/// The largest number of sub-pixel bits the rasterizers accept.
///
/// Eight bits keep every product in the triangle and polygon set-up inside `i64` for the whole guard
/// band (see [`GUARD_BAND_PIXELS`]).
pub const MAX_SUBPIXEL_BITS: u32 = 8;

/// Half the width of the guard band, in whole pixels.
///
/// Filled triangles and polygons whose vertices all lie within `±GUARD_BAND_PIXELS` pixels of the
/// origin are rasterized exactly, with no clipping that could move an edge. A filled primitive with a
/// vertex outside the band is dropped (nothing is drawn): the 3D pipeline clips against the band in
/// homogeneous space before it reaches the rasterizer, so only hand-made 2D input can be that large.
///
/// Bound: with `b <= 8` sub-pixel bits the largest coordinate is `M = 2^(21 + b) <= 2^29`; the
/// largest set-up products, the doubled area `|dx1 dy2| + |dx2 dy1| <= 8 M^2 = 2^61` and the edge
/// numerator `|(y - ya) dx| + |xa dy| <= 6 M^2`, fit `i64`. The Gouraud fill's colour numerators
/// (a channel times the doubled area, up to `2^72`) go to `i128` in the triangles that need it.
pub const GUARD_BAND_PIXELS: i32 = 1 << 21;

/// A point in sub-pixel fixed point with `BITS` fractional bits (28.4 by default).
///
/// The raw value `x` stands for `x / 2^BITS` pixels. Valid range: any `i32`; filled primitives draw
/// only when every vertex lies inside the guard band ([`GUARD_BAND_PIXELS`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SubPoint<const BITS: u32 = DEFAULT_SUBPIXEL_BITS> {
    /// Raw x, in `1 / 2^BITS` pixels.
    pub x: i32,
    /// Raw y, in `1 / 2^BITS` pixels.
    pub y: i32,
}

impl<const BITS: u32> SubPoint<BITS> {
    /// One pixel in raw units.
    pub const ONE: i32 = 1 << BITS;

    /// Compile-time guard: more than [`MAX_SUBPIXEL_BITS`] would overflow the set-up arithmetic.
    pub(crate) const VALID: () = assert!(BITS <= MAX_SUBPIXEL_BITS, "at most 8 sub-pixel bits");

    /// A point from raw sub-pixel values: `x` stands for `x / 2^BITS` pixels, e.g.
    /// `SubPoint::<6>::raw(64, 32)` is `(1, 0.5)`.
    pub const fn raw(x: i32, y: i32) -> Self {
        Self { x, y }
    }

    /// The top-left corner of pixel `p`, saturating at the `i32` range.
    pub const fn from_pixel(p: Point) -> Self {
        Self {
            x: p.x.saturating_mul(Self::ONE),
            y: p.y.saturating_mul(Self::ONE),
        }
    }

    /// True when both coordinates lie inside the guard band (see [`GUARD_BAND_PIXELS`]).
    pub const fn in_guard_band(self) -> bool {
        let limit = (GUARD_BAND_PIXELS as i64) << BITS;
        let (x, y) = (self.x as i64, self.y as i64);
        -limit <= x && x <= limit && -limit <= y && y <= limit
    }
}

impl SubPoint {
    /// A point at the default precision, 28.4, from raw values: 16 units to the pixel, so
    /// `SubPoint::new(160 * 16, 8)` is `(160, 0.5)`. Other precisions: [`SubPoint::raw`].
    pub const fn new(x: i32, y: i32) -> Self {
        Self { x, y }
    }
}

/// A rectangle of whole pixels, `x0 <= x < x1`, `y0 <= y < y1`, in `i64` so that its arithmetic
/// cannot overflow for any `i32` input. Empty when `x0 >= x1` or `y0 >= y1`.
///
/// An embedded-graphics `Rectangle` may end past `i32::MAX` (`top_left + size` is up to
/// `2^31 - 1 + 2^32 - 1`), and its own `intersection`, `contains` and `bottom_right` overflow there;
/// everything here stays below `2^33` in magnitude.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct PixelRect {
    pub x0: i64,
    pub y0: i64,
    pub x1: i64,
    pub y1: i64,
}

impl PixelRect {
    /// The pixels of an embedded-graphics rectangle.
    pub fn from_rectangle(r: &Rectangle) -> Self {
        let x0 = i64::from(r.top_left.x);
        let y0 = i64::from(r.top_left.y);
        Self {
            x0,
            y0,
            x1: x0 + i64::from(r.size.width),
            y1: y0 + i64::from(r.size.height),
        }
    }

    /// No pixels.
    pub const EMPTY: Self = Self {
        x0: 0,
        y0: 0,
        x1: 0,
        y1: 0,
    };

    pub fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }

    /// The smallest rectangle holding both (the other one when either is empty).
    pub fn union(&self, other: &Self) -> Self {
        if self.is_empty() {
            return *other;
        }
        if other.is_empty() {
            return *self;
        }
        Self {
            x0: self.x0.min(other.x0),
            y0: self.y0.min(other.y0),
            x1: self.x1.max(other.x1),
            y1: self.y1.max(other.y1),
        }
    }

    /// The pixels in both.
    #[inline]
    pub fn intersection(&self, other: &Self) -> Self {
        Self {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        }
    }

    #[inline]
    pub fn contains(&self, p: Point) -> bool {
        let (x, y) = (i64::from(p.x), i64::from(p.y));
        self.x0 <= x && x < self.x1 && self.y0 <= y && y < self.y1
    }

    /// The same pixels as an embedded-graphics rectangle; `Rectangle::zero()` when empty.
    ///
    /// Exact for the intersection of rectangles made by [`PixelRect::from_rectangle`]: its corner is
    /// one of theirs and its size at most one of theirs. Anything else is clamped to what a
    /// `Rectangle` can hold.
    pub fn to_rectangle(self) -> Rectangle {
        if self.is_empty() {
            return Rectangle::zero();
        }
        let clamp = |v: i64| v.clamp(i64::from(i32::MIN), i64::from(i32::MAX));
        let len = |lo: i64, hi: i64| (hi - clamp(lo)).clamp(0, i64::from(u32::MAX)) as u32;
        Rectangle::new(
            Point::new(clamp(self.x0) as i32, clamp(self.y0) as i32),
            Size::new(len(self.x0, self.x1), len(self.y0, self.y1)),
        )
    }
}

/// Values a shader interpolates across a triangle: `[i32; N]` for `N` values, at most
/// [`MAX_VARYINGS`]. Their meaning and fixed-point scale are the shader's own.
pub trait Varyings: Copy + Default + core::fmt::Debug {
    /// How many values there are.
    const LEN: usize;
    /// The values.
    fn as_slice(&self) -> &[i32];
    /// The values, mutably.
    fn as_mut_slice(&mut self) -> &mut [i32];
}

/// The most values a triangle interpolates; a longer [`Varyings`] has only its first
/// `MAX_VARYINGS` values interpolated (the rest keep the first vertex's values).
pub const MAX_VARYINGS: usize = 8;

impl<const N: usize> Varyings for [i32; N]
where
    [i32; N]: Default,
{
    const LEN: usize = N;
    #[inline]
    fn as_slice(&self) -> &[i32] {
        self
    }
    #[inline]
    fn as_mut_slice(&mut self) -> &mut [i32] {
        self
    }
}
