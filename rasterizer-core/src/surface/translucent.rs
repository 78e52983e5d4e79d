//! [`Translucent`]: a surface wrapper that blends everything drawn through it over what the
//! wrapped surface holds, with one opacity. Any rasterizer, the 3D pipeline included, draws
//! translucent through it unchanged: the wrapper turns its spans into
//! [`Surface::blend_span_in_clip`] calls.

use super::{BlendError, DepthSpan, Surface};
use crate::color::blend_channel;
use crate::geom::line::LinePoints;
use crate::geom::PixelRect;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::Dimensions;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

/// Draws through to a surface with opacity `opacity` (0 transparent ..= 255 opaque): every pixel
/// drawn is blended once over the colour the surface holds ([`crate::color::blend`]), in integer
/// arithmetic at the colour's own channel depth.
///
/// The wrapped surface must read back ([`Surface::READ_BACK`], as [`super::Framebuffer`] and
/// [`super::Band`] do). One that cannot gets [`BlendError::CannotReadBack`] from the first
/// drawing call that would touch a pixel, before anything is written; the error type of every
/// drawing call is [`BlendError`] of the wrapped surface's.
///
/// A translucent mesh is drawn by handing the wrapper to [`crate::pipeline::Pipeline::draw`]; its
/// depth stage is usually [`crate::depth::DepthReadOnly`], after the opaque meshes (see
/// [`crate::depth`] for the recipe). Opacity 255 gives exactly the opaque picture and 0 leaves
/// the surface as it was.
///
/// ```
/// use rasterizer_core::prelude::*;
/// use rasterizer_core::surface::Translucent;
///
/// let mut buf = [0u8; 8 * 8];
/// let mut fb = Framebuffer::<Gray8>::new(&mut buf, 8, 8).unwrap();
/// fb.clear(Gray8::new(100)).unwrap();
/// let v = |x, y| SubPoint::<4>::new(x * 16, y * 16);
/// fill_triangle(&mut Translucent::new(&mut fb, 128), [v(0, 0), v(8, 0), v(0, 8)], Gray8::WHITE)
///     .unwrap();
/// // round((255 * 128 + 100 * 127) / 255) = 178.
/// assert_eq!(fb.pixel(Point::new(1, 1)), Some(Gray8::new(178)));
/// assert_eq!(fb.pixel(Point::new(7, 7)), Some(Gray8::new(100)));
/// ```
#[derive(Debug)]
pub struct Translucent<'s, S> {
    inner: &'s mut S,
    opacity: u8,
}

impl<'s, S: Surface> Translucent<'s, S> {
    /// Draws into `inner` with `opacity` (0 ..= 255).
    pub fn new(inner: &'s mut S, opacity: u8) -> Self {
        Self { inner, opacity }
    }

    /// The opacity.
    pub fn opacity(&self) -> u8 {
        self.opacity
    }

    /// The wrapped surface.
    pub fn inner(&mut self) -> &mut S {
        self.inner
    }

    /// Blends one pixel known to lie inside the clip area.
    #[inline(always)]
    fn blend_pixel(&mut self, x: i32, y: i32, color: S::Color) -> Result<(), BlendError<S::Error>> {
        self.inner.blend_span_in_clip(x, y, 1, color, self.opacity)
    }
}

/// The refusal of a surface that cannot read back, before anything is drawn.
#[inline(always)]
fn check<S: Surface>() -> Result<(), BlendError<S::Error>> {
    if S::READ_BACK {
        Ok(())
    } else {
        Err(BlendError::CannotReadBack)
    }
}

impl<S: Surface> Dimensions for Translucent<'_, S> {
    fn bounding_box(&self) -> Rectangle {
        self.inner.bounding_box()
    }
}

/// The `DrawTarget` methods blend too, so embedded-graphics primitives drawn through the wrapper
/// are translucent; pixels outside the wrapped surface's clip area are dropped.
impl<S: Surface> DrawTarget for Translucent<'_, S> {
    type Color = S::Color;
    type Error = BlendError<S::Error>;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        check::<S>()?;
        let clip = PixelRect::from_rectangle(&self.inner.clip_area());
        for Pixel(p, c) in pixels {
            if clip.contains(p) {
                self.blend_pixel(p.x, p.y, c)?;
            }
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Self::Color) -> Result<(), Self::Error> {
        check::<S>()?;
        let clip = PixelRect::from_rectangle(&self.inner.clip_area());
        let r = PixelRect::from_rectangle(area).intersection(&clip);
        if r.is_empty() {
            return Ok(());
        }
        // Inside the clip area, so every coordinate and the width fit their types.
        for y in r.y0..r.y1 {
            self.inner.blend_span_in_clip(
                r.x0 as i32,
                y as i32,
                (r.x1 - r.x0) as u32,
                color,
                self.opacity,
            )?;
        }
        Ok(())
    }
}

/// The in-clip span methods blend into the wrapped surface; the checked ones go through the
/// `DrawTarget` methods above.
impl<S: Surface> Surface for Translucent<'_, S> {
    fn clip_area(&self) -> Rectangle {
        self.inner.clip_area()
    }

    #[inline(always)]
    fn fill_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        self.inner
            .blend_span_in_clip(x, y, len, color, self.opacity)
    }

    #[inline(always)]
    fn shade_span_in_clip<F: FnMut() -> Self::Color>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        mut shade: F,
    ) -> Result<(), Self::Error> {
        check::<S>()?;
        for i in 0..len {
            let c = shade();
            self.blend_pixel(x.wrapping_add(i as i32), y, c)?;
        }
        Ok(())
    }

    #[inline(always)]
    fn shade_span_depth_in_clip<F: DepthSpan<Self::Color>>(
        &mut self,
        x: i32,
        y: i32,
        depth: &mut [u16],
        mut shade: F,
    ) -> Result<(), Self::Error> {
        check::<S>()?;
        for (i, d) in depth.iter_mut().enumerate() {
            if let Some(c) = shade.pixel(i, d) {
                self.blend_pixel(x.wrapping_add(i as i32), y, c)?;
            }
        }
        Ok(())
    }

    #[inline(always)]
    fn draw_line_points_in_clip(
        &mut self,
        points: LinePoints,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        check::<S>()?;
        for p in points {
            self.blend_pixel(p.x, p.y, color)?;
        }
        Ok(())
    }

    const READ_BACK: bool = S::READ_BACK;

    /// Blends with the product of the two opacities (`alpha` times the wrapper's, rounded), so
    /// that an anti-aliased or translucent line drawn through the wrapper is fainter still.
    #[inline(always)]
    fn blend_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: Self::Color,
        alpha: u8,
    ) -> Result<(), BlendError<Self::Error>> {
        let alpha = blend_channel(alpha, 0, self.opacity);
        self.inner
            .blend_span_in_clip(x, y, len, color, alpha)
            .map_err(|e| match e {
                BlendError::CannotReadBack => BlendError::CannotReadBack,
                e => BlendError::Target(e),
            })
    }
}
