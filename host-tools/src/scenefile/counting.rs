//! A surface that counts the pixels written through it, for `view`'s title: it forwards every
//! call to the surface it wraps, so the pixels are exactly those of the wrapped surface alone.

use rasterizer_core::geom::line::LinePoints;
use rasterizer_core::prelude::*;
use rasterizer_core::surface::{BlendError, DepthSpan};

/// `inner`, counting the pixels written (a pixel written twice counts twice).
#[derive(Debug)]
pub struct Counting<T> {
    /// The surface drawn into.
    pub inner: T,
    /// Pixels written so far.
    pub pixels: u64,
}

impl<T> Counting<T> {
    /// Counts from zero.
    pub fn new(inner: T) -> Self {
        Self { inner, pixels: 0 }
    }
}

/// Pixels of `area` inside `bounds`.
fn pixels_in(area: &Rectangle, bounds: &Rectangle) -> u64 {
    let r = area.intersection(bounds);
    u64::from(r.size.width) * u64::from(r.size.height)
}

impl<T: Dimensions> Dimensions for Counting<T> {
    fn bounding_box(&self) -> Rectangle {
        self.inner.bounding_box()
    }
}

impl<T: DrawTarget> DrawTarget for Counting<T> {
    type Color = T::Color;
    type Error = T::Error;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        let bounds = self.inner.bounding_box();
        let count = &mut self.pixels;
        self.inner.draw_iter(pixels.into_iter().inspect(|p| {
            if bounds.contains(p.0) {
                *count += 1;
            }
        }))
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Self::Color>,
    {
        self.pixels += pixels_in(area, &self.inner.bounding_box());
        self.inner.fill_contiguous(area, colors)
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Self::Color) -> Result<(), Self::Error> {
        self.pixels += pixels_in(area, &self.inner.bounding_box());
        self.inner.fill_solid(area, color)
    }

    fn clear(&mut self, color: Self::Color) -> Result<(), Self::Error> {
        self.inner.clear(color)
    }
}

/// A depth span that counts the pixels it lets through.
struct CountingSpan<'a, F> {
    shade: F,
    pixels: &'a mut u64,
}

impl<C, F: DepthSpan<C>> DepthSpan<C> for CountingSpan<'_, F> {
    #[inline(always)]
    fn pixel(&mut self, i: usize, depth: &mut u16) -> Option<C> {
        let c = self.shade.pixel(i, depth);
        *self.pixels += u64::from(c.is_some());
        c
    }
}

impl<T: Surface> Surface for Counting<T> {
    fn clip_area(&self) -> Rectangle {
        self.inner.clip_area()
    }

    fn fill_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        self.pixels += u64::from(len);
        self.inner.fill_span_in_clip(x, y, len, color)
    }

    fn shade_span_in_clip<F: FnMut() -> Self::Color>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        shade: F,
    ) -> Result<(), Self::Error> {
        self.pixels += u64::from(len);
        self.inner.shade_span_in_clip(x, y, len, shade)
    }

    fn blend_shade_span_in_clip<F: FnMut() -> (Self::Color, u8)>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        mut shade: F,
    ) -> Result<(), BlendError<Self::Error>> {
        // A pixel of opacity 0 is left as it is: not written, so not counted.
        let pixels = &mut self.pixels;
        self.inner.blend_shade_span_in_clip(x, y, len, || {
            let (color, alpha) = shade();
            *pixels += u64::from(alpha != 0);
            (color, alpha)
        })
    }

    fn shade_span_depth_in_clip<F: DepthSpan<Self::Color>>(
        &mut self,
        x: i32,
        y: i32,
        depth: &mut [u16],
        shade: F,
    ) -> Result<(), Self::Error> {
        let span = CountingSpan {
            shade,
            pixels: &mut self.pixels,
        };
        self.inner.shade_span_depth_in_clip(x, y, depth, span)
    }

    fn draw_line_points_in_clip(
        &mut self,
        points: LinePoints,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        self.pixels += points.remaining();
        self.inner.draw_line_points_in_clip(points, color)
    }

    const READ_BACK: bool = T::READ_BACK;

    fn blend_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        color: Self::Color,
        alpha: u8,
    ) -> Result<(), BlendError<Self::Error>> {
        self.pixels += u64::from(len);
        self.inner.blend_span_in_clip(x, y, len, color, alpha)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_what_the_wrapped_surface_draws() {
        let mut bytes = vec![0u8; 16 * 8 * 3];
        let fb = Framebuffer::<Rgb888>::new(&mut bytes, 16, 8).unwrap();
        let mut c = Counting::new(fb);
        draw_line(&mut c, Point::new(-5, 0), Point::new(20, 0), Rgb888::RED).unwrap();
        assert_eq!(c.pixels, 16);
        let v = [
            SubPoint::new(0, 0),
            SubPoint::new(16 * 16, 0),
            SubPoint::new(0, 8 * 16),
        ];
        fill_triangle(&mut c, v, Rgb888::GREEN).unwrap();
        let drawn = c.pixels - 16;
        let green = (0..8)
            .flat_map(|y| (0..16).map(move |x| Point::new(x, y)))
            .filter(|&p| c.inner.pixel(p) == Some(Rgb888::GREEN))
            .count() as u64;
        assert_eq!(drawn, green);
        c.draw_iter([
            Pixel(Point::new(3, 3), Rgb888::BLUE),
            Pixel(Point::new(99, 3), Rgb888::BLUE),
        ])
        .unwrap();
        assert_eq!(c.pixels, 16 + drawn + 1);
    }

    #[test]
    fn counts_the_pixels_a_sprite_writes() {
        use rasterizer_core::raster::sprite::{draw_sprite, Affine, AlphaBits, Sprite};
        use rasterizer_core::texture::Filter;
        // A 2 x 2 image, opacities 255, 0, 128 and 0: two pixels are written, two left alone.
        let texels = [0xFFu8; 8];
        let sprite =
            Sprite::from_parts(2, 2, AlphaBits::Eight, &texels, &[255, 0, 128, 0]).unwrap();
        let mut words = [0u16; 8 * 4];
        let mut c = Counting::new(Framebuffer::<Rgb565>::new(&mut words, 8, 4).unwrap());
        draw_sprite(&mut c, &sprite, &Affine::translation(3, 1), Filter::Nearest).unwrap();
        let written = c.inner.as_slice().iter().filter(|&&w| w != 0).count() as u64;
        assert_eq!((c.pixels, written), (2, 2));
    }
}
