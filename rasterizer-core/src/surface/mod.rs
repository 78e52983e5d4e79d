//! Where pixels go: the [`Surface`] trait the rasterizers write through, the [`Framebuffer`] over a
//! caller's slice, and [`AnyTarget`], which lets any embedded-graphics `DrawTarget` be drawn on.
//!
//! The rasterizers clip every primitive to [`Surface::clip_area`] first and then hand the surface whole
//! horizontal spans (and, for lines, one walk along the line). The provided methods turn those into
//! `fill_solid`, `fill_contiguous` and `draw_iter` calls, so any `DrawTarget` works; [`Framebuffer`]
//! overrides them with direct slice writes, which is where the speed comes from.
//!
//! Blending (opacity, anti-aliasing) needs the colour already stored, which a plain `DrawTarget`
//! cannot give back: a surface says whether it can with [`Surface::READ_BACK`], and the blending
//! rasterizers refuse one that cannot with [`BlendError::CannotReadBack`] before writing anything.
//! [`Translucent`] wraps a surface so that whatever is drawn through it, a whole mesh included, is
//! blended with one opacity.

mod framebuffer;
mod translucent;

pub use framebuffer::{Band, Framebuffer, FramebufferError, Storage, MAX_DIMENSION};
pub use translucent::Translucent;

/// Why a blended primitive (a translucent fill, an anti-aliased line) was not drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlendError<E> {
    /// The surface cannot read back the pixels it holds ([`Surface::READ_BACK`] is false), so a
    /// blend would have to guess the colour underneath: nothing was drawn.
    CannotReadBack,
    /// The surface reported an error while drawing.
    Target(E),
}

impl<E> From<E> for BlendError<E> {
    fn from(e: E) -> Self {
        Self::Target(e)
    }
}

impl<E: core::fmt::Display> core::fmt::Display for BlendError<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::CannotReadBack => write!(f, "the target cannot read back pixels to blend into"),
            Self::Target(e) => write!(f, "the target failed: {e}"),
        }
    }
}

impl<E: core::fmt::Debug + core::fmt::Display> core::error::Error for BlendError<E> {}

use crate::geom::line::LinePoints;
use crate::geom::PixelRect;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Dimensions, Point, Size};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

/// A `DrawTarget` the rasterizers can write whole spans into.
///
/// Every method has a default built on the `DrawTarget` methods, so `impl Surface for MyDisplay {}` is
/// enough for a display type of your own; wrap a type from another crate in [`AnyTarget`].
///
/// The rasterizers call the span methods only with pixels inside [`Surface::clip_area`], `len >= 1`.
pub trait Surface: DrawTarget {
    /// The rectangle the rasterizers clip to. Defaults to the target's bounding box.
    fn clip_area(&self) -> Rectangle {
        self.bounding_box()
    }

    /// Fills `len` pixels of row `y` starting at column `x` with one colour.
    fn fill_span(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        self.fill_solid(&Rectangle::new(Point::new(x, y), Size::new(len, 1)), color)
    }

    /// Fills `len` pixels of row `y` starting at column `x`, left to right, with the colours `shade`
    /// yields, one call per pixel.
    fn shade_span<F: FnMut() -> Self::Color>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        mut shade: F,
    ) -> Result<(), Self::Error> {
        let area = Rectangle::new(Point::new(x, y), Size::new(len, 1));
        self.fill_contiguous(
            &area,
            core::iter::repeat_with(&mut shade).take(len as usize),
        )
    }

    /// [`Surface::fill_span`] for a span known to lie inside [`Surface::clip_area`]: the
    /// rasterizers' fast path, free to skip bounds checks.
    ///
    /// # Panics
    /// May panic (it never writes out of bounds) when the span is not inside the clip area;
    /// [`Framebuffer`]'s does. The default forwards to the checked [`Surface::fill_span`].
    #[inline(always)]
    fn fill_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        self.fill_span(x, y, len, color)
    }

    /// [`Surface::fill_span_in_clip`] for a span that is most likely dozens of pixels long (a tall
    /// triangle's): a target may test for long spans first. The default forwards to
    /// [`Surface::fill_span_in_clip`].
    ///
    /// # Panics
    /// As [`Surface::fill_span_in_clip`].
    #[inline(always)]
    fn fill_long_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        self.fill_span_in_clip(x, y, len, color)
    }

    /// [`Surface::fill_span_in_clip`] for a span that is most likely a few pixels long (a small
    /// triangle's): a target may test for short spans first. The default forwards to
    /// [`Surface::fill_span_in_clip`].
    ///
    /// # Panics
    /// As [`Surface::fill_span_in_clip`].
    #[inline(always)]
    fn fill_short_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        self.fill_span_in_clip(x, y, len, color)
    }

    /// Fills one span a row of one colour on the rows `rows`, top to bottom, each span mostly a
    /// few pixels long (a small triangle's): `first` is the first row's columns `x + a .. x + b`
    /// (`a` never negative, none when `a >= b`), and `next`, called once for each further row,
    /// moves on a row and gives its columns. Every span lies inside [`Surface::clip_area`]. A
    /// target may step its address from row to row, as [`Framebuffer`] does; the default fills
    /// each span through [`Surface::fill_short_span_in_clip`].
    ///
    /// # Panics
    /// As [`Surface::fill_span_in_clip`].
    #[inline(always)]
    fn fill_short_rows_in_clip<F: FnMut() -> (i32, i32)>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        color: Self::Color,
        first: (i32, i32),
        mut next: F,
    ) -> Result<(), Self::Error> {
        let (mut a, mut b) = first;
        for y in rows.clone() {
            if y > rows.start {
                (a, b) = next();
            }
            if a < b {
                self.fill_short_span_in_clip(x + a, y, (b - a) as u32, color)?;
            }
        }
        Ok(())
    }

    /// [`Surface::fill_short_rows_in_clip`] for both halves of a small triangle: the rows
    /// `top..bottom` (at least one; `top <= mid <= bottom`), `first` the columns of row `top`;
    /// `next(false)` moves on a row within a half, `next(true)` from the last row above `mid`
    /// to row `mid` (called only when both halves have rows), each giving that row's columns.
    /// A framebuffer steps its row offset from one half into the other; the default draws
    /// each half through [`Surface::fill_short_rows_in_clip`].
    ///
    /// # Panics
    /// As [`Surface::fill_span_in_clip`]. `mid` must lie within `top..=bottom`: a target that
    /// steps its rows (a [`Framebuffer`]) checks it in a debug build only, and in a release
    /// build would walk a wrapped-round count of rows (until a span leaves its buffer).
    #[inline(always)]
    fn fill_short_halves_in_clip<F: FnMut(bool) -> (i32, i32)>(
        &mut self,
        x: i32,
        (top, mid, bottom): (i32, i32, i32),
        color: Self::Color,
        first: (i32, i32),
        mut next: F,
    ) -> Result<(), Self::Error> {
        if top < mid {
            self.fill_short_rows_in_clip(x, top..mid, color, first, || next(false))?;
        }
        if mid < bottom {
            let first = if top < mid { next(true) } else { first };
            self.fill_short_rows_in_clip(x, mid..bottom, color, first, || next(false))?;
        }
        Ok(())
    }

    /// [`Surface::fill_short_rows_in_clip`] with each span's colours from a shader: `span` is
    /// called for each non-empty span with its row and first column and returns what
    /// [`Surface::shade_span_in_clip`] takes, the colours of its pixels left to right.
    ///
    /// # Panics
    /// As [`Surface::fill_span_in_clip`].
    #[inline(always)]
    fn shade_short_rows_in_clip<F, G, P>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        first: (i32, i32),
        mut next: F,
        mut span: G,
    ) -> Result<(), Self::Error>
    where
        F: FnMut() -> (i32, i32),
        G: FnMut(i32, i32) -> P,
        P: FnMut() -> Self::Color,
    {
        let (mut a, mut b) = first;
        for y in rows.clone() {
            if y > rows.start {
                (a, b) = next();
            }
            if a < b {
                let shade = span(y, x + a);
                self.shade_span_in_clip(x + a, y, (b - a) as u32, shade)?;
            }
        }
        Ok(())
    }

    /// [`Surface::shade_span`] for a span known to lie inside [`Surface::clip_area`].
    ///
    /// # Panics
    /// As [`Surface::fill_span_in_clip`].
    #[inline(always)]
    fn shade_span_in_clip<F: FnMut() -> Self::Color>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        shade: F,
    ) -> Result<(), Self::Error> {
        self.shade_span(x, y, len, shade)
    }

    /// Draws pixels of row `y` from column `x` on, one for each entry of `depth`, left to right:
    /// `shade` gets the pixel's depth entry (it runs the depth test and stores the new depth) and
    /// returns its colour, or `None` to leave the pixel as it is. The 3D pipeline's fused span
    /// loop; the span lies inside [`Surface::clip_area`].
    ///
    /// # Panics
    /// As [`Surface::fill_span_in_clip`].
    #[inline(always)]
    fn shade_span_depth_in_clip<F: DepthSpan<Self::Color>>(
        &mut self,
        x: i32,
        y: i32,
        depth: &mut [u16],
        mut shade: F,
    ) -> Result<(), Self::Error> {
        self.draw_iter(depth.iter_mut().enumerate().filter_map(|(i, d)| {
            shade
                .pixel(i, d)
                .map(|c| Pixel(Point::new(x.wrapping_add(i as i32), y), c))
        }))
    }

    /// Draws a whole triangle with a depth test (the 3D pipeline's fused loop), so that a
    /// surface that keeps its pixels in rows of words can let the triangle step through them
    /// directly ([`DepthTriangle::by_words`]). The default draws it span by span through
    /// [`Surface::shade_span_depth_in_clip`] ([`DepthTriangle::by_spans`]).
    #[inline(always)]
    fn shade_triangle_depth_in_clip<T: DepthTriangle<Self::Color>>(
        &mut self,
        triangle: T,
    ) -> Result<(), Self::Error> {
        triangle.by_spans(self)
    }

    /// [`Surface::draw_line_points`] for a walk known to lie inside [`Surface::clip_area`].
    ///
    /// # Panics
    /// As [`Surface::fill_span_in_clip`].
    #[inline(always)]
    fn draw_line_points_in_clip(
        &mut self,
        points: LinePoints,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        self.draw_line_points(points, color)
    }

    /// Draws every pixel of a line walk in one colour.
    fn draw_line_points(
        &mut self,
        points: LinePoints,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        self.draw_iter(points.map(|p| Pixel(p, color)))
    }

    /// True when the surface implements [`Surface::blend_span_in_clip`] by reading back what it
    /// holds. The blending rasterizers check it before they write anything, so a surface that
    /// cannot (the default, and [`AnyTarget`]) gets [`BlendError::CannotReadBack`], never a
    /// half-drawn picture. A constant, so the check costs nothing.
    const READ_BACK: bool = false;

    /// Blends `color` with opacity `alpha` (0 ..= 255) over `len` pixels of row `y` from column
    /// `x` on, each channel at its native depth ([`crate::color::blend`]). The span lies inside
    /// [`Surface::clip_area`]; each pixel is blended once per call.
    ///
    /// # Errors
    /// The default, for surfaces that cannot read back, returns [`BlendError::CannotReadBack`].
    ///
    /// # Panics
    /// As [`Surface::fill_span_in_clip`].
    #[inline(always)]
    fn blend_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: Self::Color,
        alpha: u8,
    ) -> Result<(), BlendError<Self::Error>> {
        let _ = (x, y, len, color, alpha);
        Err(BlendError::CannotReadBack)
    }

    /// Draws `len` pixels of row `y` from column `x` on, left to right, each with the colour and
    /// opacity `shade` returns for it (one call per pixel): opacity 255 stores the colour, 0
    /// leaves the pixel, anything between blends it as [`Surface::blend_span_in_clip`] does.
    /// Sprites with alpha draw through it. The span lies inside [`Surface::clip_area`].
    ///
    /// # Errors
    /// The default writes pixel by pixel through [`Surface::fill_span_in_clip`] and
    /// [`Surface::blend_span_in_clip`], so only a pixel that needs a blend can meet
    /// [`BlendError::CannotReadBack`]; callers with such pixels check [`Surface::READ_BACK`] first.
    ///
    /// # Panics
    /// As [`Surface::fill_span_in_clip`].
    #[inline(always)]
    fn blend_shade_span_in_clip<F: FnMut() -> (Self::Color, u8)>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        mut shade: F,
    ) -> Result<(), BlendError<Self::Error>> {
        for i in 0..len {
            let (color, alpha) = shade();
            let px = x.wrapping_add(i as i32);
            match alpha {
                255 => self.fill_span_in_clip(px, y, 1, color)?,
                0 => {}
                _ => self.blend_span_in_clip(px, y, 1, color, alpha)?,
            }
        }
        Ok(())
    }
}

/// The per-pixel work of a span with a depth test ([`Surface::shade_span_depth_in_clip`]): a
/// type of its own rather than a closure, so that it is always inlined into the target's loop.
pub trait DepthSpan<C> {
    /// The colour of pixel `i` of the span (called for `i = 0, 1, ...` in turn), given its
    /// stored depth (which it updates when the pixel passes), or `None` to leave the pixel as it
    /// is.
    fn pixel(&mut self, i: usize, depth: &mut u16) -> Option<C>;
}

/// A triangle with a depth test, as [`Surface::shade_triangle_depth_in_clip`] receives it: it can
/// draw itself through any surface's span methods, or straight into rows of pixel words. Made by
/// the 3D pipeline; a surface only chooses which of the two to call.
pub trait DepthTriangle<C> {
    /// Draws the triangle span by span through `surface`
    /// ([`Surface::shade_span_depth_in_clip`]).
    fn by_spans<S: Surface<Color = C> + ?Sized>(self, surface: &mut S) -> Result<(), S::Error>;
    /// Draws the triangle into `words`: `stride` words a row, the first row standing for screen
    /// row `y0`, holding every pixel of the surface's [`Surface::clip_area`].
    fn by_words(self, words: &mut [C::Word], stride: usize, y0: i32)
    where
        C: Storage;
}

/// Lets any embedded-graphics `DrawTarget` (a display driver, `SimulatorDisplay`, `MockDisplay`) be
/// used as a [`Surface`]: spans become `fill_solid` and `fill_contiguous` calls.
///
/// ```
/// # use rasterizer_core::surface::{AnyTarget, Framebuffer};
/// # use embedded_graphics_core::{pixelcolor::Rgb565, prelude::*};
/// # let mut buf = [0u16; 8 * 8];
/// # let mut display = Framebuffer::<Rgb565>::new(&mut buf, 8, 8).unwrap();
/// use rasterizer_core::raster::line::draw_line;
/// draw_line(&mut AnyTarget::new(&mut display), Point::new(0, 0), Point::new(7, 3), Rgb565::RED)?;
/// # Ok::<(), core::convert::Infallible>(())
/// ```
#[derive(Debug)]
pub struct AnyTarget<'a, T> {
    inner: &'a mut T,
}

impl<'a, T: DrawTarget> AnyTarget<'a, T> {
    /// Wraps a target.
    pub fn new(inner: &'a mut T) -> Self {
        Self { inner }
    }

    /// The wrapped target.
    pub fn inner(&mut self) -> &mut T {
        self.inner
    }
}

impl<T: DrawTarget> Dimensions for AnyTarget<'_, T> {
    fn bounding_box(&self) -> Rectangle {
        self.inner.bounding_box()
    }
}

impl<T: DrawTarget> DrawTarget for AnyTarget<'_, T> {
    type Color = T::Color;
    type Error = T::Error;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        self.inner.draw_iter(pixels)
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Self::Color>,
    {
        self.inner.fill_contiguous(area, colors)
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Self::Color) -> Result<(), Self::Error> {
        self.inner.fill_solid(area, color)
    }

    fn clear(&mut self, color: Self::Color) -> Result<(), Self::Error> {
        self.inner.clear(color)
    }
}

impl<T: DrawTarget> Surface for AnyTarget<'_, T> {}

/// A [`Surface`] whose clip area is narrowed to a rectangle: everything drawn through it stays
/// inside both the rectangle and the wrapped surface's own clip area, for any rectangle (one that
/// ends past `i32::MAX` included). The span methods forward to the wrapped surface, so its fast
/// paths are kept.
///
/// ```
/// # use rasterizer_core::surface::{ClipTo, Framebuffer, Surface};
/// # use embedded_graphics_core::{pixelcolor::Gray8, prelude::*, primitives::Rectangle};
/// use rasterizer_core::raster::line::draw_line;
/// let mut buf = [0u8; 8 * 8];
/// let mut fb = Framebuffer::<Gray8>::new(&mut buf, 8, 8).unwrap();
/// let mut left = ClipTo::new(&mut fb, Rectangle::new(Point::zero(), Size::new(4, 8)));
/// draw_line(&mut left, Point::new(0, 0), Point::new(7, 0), Gray8::WHITE).unwrap();
/// assert_eq!(fb.pixel(Point::new(3, 0)), Some(Gray8::WHITE));
/// assert_eq!(fb.pixel(Point::new(4, 0)), Some(Gray8::BLACK));
/// ```
#[derive(Debug)]
pub struct ClipTo<'a, T> {
    inner: &'a mut T,
    /// `cells` as a rectangle (`Rectangle::zero()` when empty).
    area: Rectangle,
    cells: PixelRect,
}

impl<'a, T: Surface> ClipTo<'a, T> {
    /// Narrows `inner`'s clip area to `area`. An empty intersection draws nothing.
    pub fn new(inner: &'a mut T, area: Rectangle) -> Self {
        // Not embedded-graphics' `Rectangle::intersection`: it overflows for a rectangle that ends
        // past i32::MAX.
        let cells = PixelRect::from_rectangle(&inner.clip_area())
            .intersection(&PixelRect::from_rectangle(&area));
        Self {
            inner,
            area: cells.to_rectangle(),
            cells,
        }
    }
}

impl<T: Surface> Dimensions for ClipTo<'_, T> {
    fn bounding_box(&self) -> Rectangle {
        self.area
    }
}

impl<T: Surface> DrawTarget for ClipTo<'_, T> {
    type Color = T::Color;
    type Error = T::Error;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        let cells = self.cells;
        self.inner
            .draw_iter(pixels.into_iter().filter(|p| cells.contains(p.0)))
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Self::Color) -> Result<(), Self::Error> {
        let r = PixelRect::from_rectangle(area).intersection(&self.cells);
        if r.is_empty() {
            return Ok(());
        }
        self.inner.fill_solid(&r.to_rectangle(), color)
    }
}

/// The checked methods clip to the narrowed area through the `DrawTarget` methods; the in-clip
/// ones, which the rasterizers call only inside that area, forward to the wrapped surface's fast
/// paths.
impl<T: Surface> Surface for ClipTo<'_, T> {
    #[inline(always)]
    fn fill_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        self.inner.fill_span_in_clip(x, y, len, color)
    }

    #[inline(always)]
    fn fill_short_rows_in_clip<F: FnMut() -> (i32, i32)>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        color: Self::Color,
        first: (i32, i32),
        next: F,
    ) -> Result<(), Self::Error> {
        self.inner
            .fill_short_rows_in_clip(x, rows, color, first, next)
    }

    #[inline(always)]
    fn fill_short_halves_in_clip<F: FnMut(bool) -> (i32, i32)>(
        &mut self,
        x: i32,
        rows: (i32, i32, i32),
        color: Self::Color,
        first: (i32, i32),
        next: F,
    ) -> Result<(), Self::Error> {
        self.inner
            .fill_short_halves_in_clip(x, rows, color, first, next)
    }

    #[inline(always)]
    fn shade_short_rows_in_clip<F, G, P>(
        &mut self,
        x: i32,
        rows: core::ops::Range<i32>,
        first: (i32, i32),
        next: F,
        span: G,
    ) -> Result<(), Self::Error>
    where
        F: FnMut() -> (i32, i32),
        G: FnMut(i32, i32) -> P,
        P: FnMut() -> Self::Color,
    {
        self.inner
            .shade_short_rows_in_clip(x, rows, first, next, span)
    }

    #[inline(always)]
    fn shade_span_in_clip<F: FnMut() -> Self::Color>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        shade: F,
    ) -> Result<(), Self::Error> {
        self.inner.shade_span_in_clip(x, y, len, shade)
    }

    #[inline(always)]
    fn shade_span_depth_in_clip<F: DepthSpan<Self::Color>>(
        &mut self,
        x: i32,
        y: i32,
        depth: &mut [u16],
        shade: F,
    ) -> Result<(), Self::Error> {
        self.inner.shade_span_depth_in_clip(x, y, depth, shade)
    }

    #[inline(always)]
    fn shade_triangle_depth_in_clip<R: DepthTriangle<Self::Color>>(
        &mut self,
        triangle: R,
    ) -> Result<(), Self::Error> {
        self.inner.shade_triangle_depth_in_clip(triangle)
    }

    #[inline(always)]
    fn draw_line_points_in_clip(
        &mut self,
        points: LinePoints,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        self.inner.draw_line_points_in_clip(points, color)
    }

    const READ_BACK: bool = T::READ_BACK;

    #[inline(always)]
    fn blend_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: Self::Color,
        alpha: u8,
    ) -> Result<(), BlendError<Self::Error>> {
        self.inner.blend_span_in_clip(x, y, len, color, alpha)
    }

    #[inline(always)]
    fn blend_shade_span_in_clip<F: FnMut() -> (Self::Color, u8)>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        shade: F,
    ) -> Result<(), BlendError<Self::Error>> {
        self.inner.blend_shade_span_in_clip(x, y, len, shade)
    }
}
