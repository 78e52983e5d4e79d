//! Scene files' sprites: the image loaded (a PNG converted as `host-tools sprite` does, or a sprite
//! file), the placement turned into the core's 16.16 transform with its range checked, and an
//! adapter that lets the Rgb565 sprite draw into a target of any of the scene formats.

use super::format::{Shape, SpriteScaleDef, TextureFilterDef};
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::Dimensions;
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;
use rasterizer_core::math::Fx16;
use rasterizer_core::raster::sprite::{draw_sprite, Affine, Sprite};
use rasterizer_core::surface::{BlendError, Surface};
use rasterizer_core::texture::Filter;
use std::path::Path;

/// Reads a sprite shape's image into its `data` (and `file`).
///
/// # Errors
/// A message naming the image.
pub(super) fn load(dir: &Path, shape: &mut Shape) -> Result<(), String> {
    let Shape::Sprite {
        image, file, data, ..
    } = shape
    else {
        return Ok(());
    };
    *file = dir.join(&*image);
    let is_png = file
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    *data = if is_png {
        crate::sprite::load_png_sprite(file, crate::sprite::AlphaChoice::Auto)
            .map_err(|e| format!("sprite image {}: {e}", file.display()))?
            .0
    } else {
        let bytes =
            std::fs::read(&*file).map_err(|e| format!("sprite image {}: {e}", file.display()))?;
        Sprite::from_bytes(&bytes).map_err(|e| format!("sprite image {}: {e}", file.display()))?;
        bytes
    };
    Ok(())
}

/// The sprite of a loaded shape.
pub(super) fn sprite(shape: &Shape) -> Option<Sprite<'_>> {
    match shape {
        Shape::Sprite { data, .. } => Sprite::from_bytes(data).ok(),
        _ => None,
    }
}

/// The shape's transform: scale and shear along the image's axes, then the turn, with the
/// image's centre on `at`; in 16.16.
///
/// # Errors
/// A message when an entry or the translation leaves 16.16's range (±32767), or the matrix is
/// singular.
pub(super) fn transform(shape: &Shape) -> Result<Affine, String> {
    let Shape::Sprite {
        at,
        angle,
        scale,
        shear,
        ..
    } = shape
    else {
        return Err("not a sprite".into());
    };
    let s = sprite(shape).ok_or("the image is not loaded")?;
    let (sx, sy) = match *scale {
        SpriteScaleDef::Uniform(k) => (k, k),
        SpriteScaleDef::Axes([x, y]) => (x, y),
    };
    let (sin, cos) = angle.to_radians().sin_cos();
    // R * [[1, shear], [0, 1]] * diag(sx, sy).
    let m = [
        [cos * sx, (cos * shear - sin) * sy],
        [sin * sx, (sin * shear + cos) * sy],
    ];
    let (hw, hh) = (f64::from(s.width()) / 2.0, f64::from(s.height()) / 2.0);
    let t = [
        at[0] - m[0][0] * hw - m[0][1] * hh,
        at[1] - m[1][0] * hw - m[1][1] * hh,
    ];
    let fx = |v: f64, what: &str| -> Result<Fx16, String> {
        if !v.is_finite() || v.abs() >= 32767.0 {
            return Err(format!(
                "{what} {v} is outside the 16.16 range of a sprite's transform (±32767)"
            ));
        }
        Ok(Fx16::from_bits((v * 65536.0).round() as i32))
    };
    let a = Affine {
        m: [
            [
                fx(m[0][0], "the matrix entry")?,
                fx(m[0][1], "the matrix entry")?,
            ],
            [
                fx(m[1][0], "the matrix entry")?,
                fx(m[1][1], "the matrix entry")?,
            ],
        ],
        t: [fx(t[0], "the translation")?, fx(t[1], "the translation")?],
    };
    if a.m[0][0].to_bits() as i64 * a.m[1][1].to_bits() as i64
        == a.m[0][1].to_bits() as i64 * a.m[1][0].to_bits() as i64
    {
        return Err("the scale or shear flattens the image (a singular transform)".into());
    }
    Ok(a)
}

/// The pixels the shape can touch: the bounding box of its quad, a pixel wider on each side.
pub(super) fn bounds(shape: &Shape) -> Rectangle {
    let (Ok(a), Some(s)) = (transform(shape), sprite(shape)) else {
        return Rectangle::zero();
    };
    let f = |v: Fx16| f64::from(v.to_bits()) / 65536.0;
    let (w, h) = (f64::from(s.width()), f64::from(s.height()));
    let corners = [(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)].map(|(u, v)| {
        (
            f(a.t[0]) + f(a.m[0][0]) * u + f(a.m[0][1]) * v,
            f(a.t[1]) + f(a.m[1][0]) * u + f(a.m[1][1]) * v,
        )
    });
    let x0 = corners.iter().map(|c| c.0).fold(f64::MAX, f64::min).floor() as i32 - 1;
    let y0 = corners.iter().map(|c| c.1).fold(f64::MAX, f64::min).floor() as i32 - 1;
    let x1 = corners.iter().map(|c| c.0).fold(f64::MIN, f64::max).ceil() as i32 + 1;
    let y1 = corners.iter().map(|c| c.1).fold(f64::MIN, f64::max).ceil() as i32 + 1;
    Rectangle::new(
        embedded_graphics_core::geometry::Point::new(x0, y0),
        embedded_graphics_core::geometry::Size::new((x1 - x0) as u32, (y1 - y0) as u32),
    )
}

/// Draws a loaded sprite shape into `target`.
pub(super) fn draw<T>(target: &mut T, shape: &Shape)
where
    T: Surface,
    T::Color: From<Rgb888>,
{
    let (Some(s), Ok(a), Shape::Sprite { filter, .. }) = (sprite(shape), transform(shape), shape)
    else {
        return;
    };
    let filter = match filter {
        TextureFilterDef::Nearest => Filter::Nearest,
        TextureFilterDef::Bilinear => Filter::Bilinear,
    };
    // The scene targets read back, so no draw fails.
    let _ = draw_sprite(&mut AsRgb565(target), &s, &a, filter);
}

/// A surface of any colour seen as an Rgb565 one: each colour converted through Rgb888 (exact
/// for Rgb565 itself), spans and blends forwarded.
struct AsRgb565<'a, T>(&'a mut T);

fn convert<C: From<Rgb888>>(c: Rgb565) -> C {
    C::from(Rgb888::from(c))
}

impl<T: Surface> Dimensions for AsRgb565<'_, T> {
    fn bounding_box(&self) -> Rectangle {
        self.0.bounding_box()
    }
}

impl<T: Surface> DrawTarget for AsRgb565<'_, T>
where
    T::Color: From<Rgb888>,
{
    type Color = Rgb565;
    type Error = T::Error;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, it: I) -> Result<(), T::Error> {
        self.0
            .draw_iter(it.into_iter().map(|Pixel(p, c)| Pixel(p, convert(c))))
    }
}

impl<T: Surface> Surface for AsRgb565<'_, T>
where
    T::Color: From<Rgb888>,
{
    fn clip_area(&self) -> Rectangle {
        self.0.clip_area()
    }

    fn fill_span_in_clip(&mut self, x: i32, y: i32, len: u32, c: Rgb565) -> Result<(), T::Error> {
        self.0.fill_span_in_clip(x, y, len, convert(c))
    }

    fn shade_span_in_clip<F: FnMut() -> Rgb565>(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        mut shade: F,
    ) -> Result<(), T::Error> {
        self.0.shade_span_in_clip(x, y, len, || convert(shade()))
    }

    const READ_BACK: bool = T::READ_BACK;

    fn blend_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        c: Rgb565,
        alpha: u8,
    ) -> Result<(), BlendError<T::Error>> {
        self.0.blend_span_in_clip(x, y, len, convert(c), alpha)
    }
}
