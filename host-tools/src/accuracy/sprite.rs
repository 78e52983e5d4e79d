//! The report's sprite section: the texel `raster::sprite::draw_sprite` samples at each covered
//! pixel against an `f64` reference that inverts the same 16.16 transform exactly, over random
//! transforms (any turn, scales 0.3 to 3 per axis, shear), nearest and bilinear. Deterministic
//! and quick (no callgrind).

use fixtures::scenes::XorShift32;
use fixtures::sprite::Recorder;
use rasterizer_core::prelude::*;
use rasterizer_core::raster::sprite::{draw_sprite, Affine, AlphaBits, Sprite};
use rasterizer_core::texture::Filter;
use std::fmt::Write as _;

/// Transforms per measurement.
pub const TRANSFORMS: u32 = 1000;

fn raw(c: Rgb565) -> u16 {
    embedded_graphics_core::pixelcolor::raw::RawU16::from(c).into_inner()
}

fn bits(v: Fx16) -> f64 {
    f64::from(v.to_bits()) / 65536.0
}

/// A random transform of a `w` x `h` image centred near the middle of the recorder.
fn random_affine(r: &mut XorShift32, w: u32, h: u32) -> Affine {
    let angle = r.unit() * std::f64::consts::PI;
    let sx = 0.3 + 1.35 * (r.unit() + 1.0);
    let sy = 0.3 + 1.35 * (r.unit() + 1.0);
    let shear = r.unit() * 0.5;
    let (sin, cos) = angle.sin_cos();
    let m = [
        [cos * sx, (cos * shear - sin) * sy],
        [sin * sx, (sin * shear + cos) * sy],
    ];
    let (cx, cy) = (48.0 + 8.0 * r.unit(), 40.0 + 8.0 * r.unit());
    let t = [
        cx - (m[0][0] * f64::from(w) + m[0][1] * f64::from(h)) / 2.0,
        cy - (m[1][0] * f64::from(w) + m[1][1] * f64::from(h)) / 2.0,
    ];
    let fx = |v: f64| Fx16::from_bits((v * 65536.0).round() as i32);
    Affine {
        m: m.map(|row| row.map(fx)),
        t: t.map(fx),
    }
}

/// The texel point of pixel `(x, y)`'s centre by the transform inverted in `f64`.
fn texel_point(a: &Affine, x: i32, y: i32) -> (f64, f64) {
    let [[m00, m01], [m10, m11]] = a.m.map(|r| r.map(bits));
    let det = m00 * m11 - m01 * m10;
    let (px, py) = (
        f64::from(x) + 0.5 - bits(a.t[0]),
        f64::from(y) + 0.5 - bits(a.t[1]),
    );
    ((m11 * px - m01 * py) / det, (-m10 * px + m00 * py) / det)
}

/// How nearest sampling's texels compare with the reference's.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NearestError {
    /// Pixels drawn.
    pub pixels: u64,
    /// Pixels whose texel differs from the reference's.
    pub differ: u64,
    /// The largest difference, in texels along either axis.
    pub max: u32,
    /// The smallest distance of a reference point from a texel border, in texels: how close
    /// to a tie the cases came.
    pub closest: f64,
}

/// Nearest sampling over [`TRANSFORMS`] random transforms of images of 1 to 32 texels a side
/// whose texels name themselves (red = x, green = y).
pub fn nearest_error(transforms: u32) -> NearestError {
    let mut r = XorShift32::seeded(0x5e7e_0001);
    let mut out = NearestError {
        closest: f64::MAX,
        ..NearestError::default()
    };
    for _ in 0..transforms {
        let (w, h) = (1 + r.next_u32() % 32, 1 + r.next_u32() % 32);
        let texels: Vec<u8> = (0..h)
            .flat_map(|y| (0..w).map(move |x| raw(Rgb565::new(x as u8, y as u8, 0))))
            .flat_map(u16::to_le_bytes)
            .collect();
        let Ok(sprite) = Sprite::from_parts(w, h, AlphaBits::None, &texels, &[]) else {
            continue;
        };
        let a = random_affine(&mut r, w, h);
        let mut rec = Recorder::new(96, 80);
        if draw_sprite(&mut rec, &sprite, &a, Filter::Nearest).is_err() {
            continue; // the recorder reads back: never
        }
        for ((x, y), (c, _)) in rec.pixels {
            let (u, v) = texel_point(&a, x, y);
            let pick = |t: f64, n: u32| t.floor().clamp(0.0, f64::from(n - 1)) as u32;
            let want = (pick(u, w), pick(v, h));
            let got = (u32::from(c >> 11), u32::from((c >> 5) & 0x3F));
            out.pixels += 1;
            let d = got.0.abs_diff(want.0).max(got.1.abs_diff(want.1));
            if d > 0 {
                out.differ += 1;
                out.max = out.max.max(d);
            }
            // Only borders inside the image can flip a texel (outside, both sides clamp alike).
            let margin = |t: f64, n: u32| {
                let b = t.round();
                if b > 0.0 && b < f64::from(n) {
                    (t - b).abs()
                } else {
                    f64::MAX
                }
            };
            out.closest = out.closest.min(margin(u, w).min(margin(v, h)));
        }
    }
    out
}

/// How bilinear colours compare with the reference's, in Rgb565 steps of each channel.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BilinearError {
    /// Pixels drawn.
    pub pixels: u64,
    /// The largest channel error (opaque images).
    pub max: f64,
    /// The mean channel error (opaque images).
    pub mean: f64,
    /// The largest channel error times the opacity (8-bit alpha images, what shows over black).
    pub max_over: f64,
    /// The largest opacity error, of 255.
    pub max_alpha: f64,
}

/// Bilinear sampling over random transforms of random images, opaque and with 8-bit alpha in
/// turn; the reference weights the four texels around the exact point by distance and opacity.
pub fn bilinear_error(transforms: u32) -> BilinearError {
    let mut r = XorShift32::seeded(0x5e7e_0002);
    let mut out = BilinearError::default();
    let (mut sum, mut channels) = (0.0, 0u64);
    for k in 0..transforms {
        let (w, h) = (2 + r.next_u32() % 15, 2 + r.next_u32() % 15);
        let texels: Vec<u8> = (0..2 * w * h).map(|_| r.next_u32() as u8).collect();
        let plane: Vec<u8> = (0..w * h).map(|_| r.next_u32() as u8).collect();
        let alpha = k % 2 == 1;
        let (bits_a, plane) = if alpha {
            (AlphaBits::Eight, &plane[..])
        } else {
            (AlphaBits::None, &[][..])
        };
        let Ok(sprite) = Sprite::from_parts(w, h, bits_a, &texels, plane) else {
            continue;
        };
        let a = random_affine(&mut r, w, h);
        let mut rec = Recorder::new(96, 80);
        if draw_sprite(&mut rec, &sprite, &a, Filter::Bilinear).is_err() {
            continue; // the recorder reads back: never
        }
        for ((x, y), (c, got_alpha)) in rec.pixels {
            let (u, v) = texel_point(&a, x, y);
            let (us, vs) = (u - 0.5, v - 0.5);
            let (x0, y0) = (us.floor(), vs.floor());
            let (fx, fy) = (us - x0, vs - y0);
            let clamp = |t: f64, n: u32| t.clamp(0.0, f64::from(n - 1)) as u32;
            let (mut want, mut total) = ([0.0f64; 3], 0.0);
            for (dx, dy, wt) in [
                (0.0, 0.0, (1.0 - fx) * (1.0 - fy)),
                (1.0, 0.0, fx * (1.0 - fy)),
                (0.0, 1.0, (1.0 - fx) * fy),
                (1.0, 1.0, fx * fy),
            ] {
                let (t, ta) = sprite.texel(clamp(x0 + dx, w), clamp(y0 + dy, h));
                let wa = wt * f64::from(ta);
                total += wa;
                for (s, ch) in want.iter_mut().zip([t >> 11, (t >> 5) & 63, t & 31]) {
                    *s += wa * f64::from(ch);
                }
            }
            out.pixels += 1;
            out.max_alpha = out.max_alpha.max((f64::from(got_alpha) - total).abs());
            for (ch, s) in [c >> 11, (c >> 5) & 63, c & 31].into_iter().zip(want) {
                if alpha {
                    let e = (f64::from(ch) * f64::from(got_alpha) - s).abs() / 255.0;
                    out.max_over = out.max_over.max(e);
                } else {
                    let e = (f64::from(ch) - s / total).abs();
                    out.max = out.max.max(e);
                    sum += e;
                    channels += 1;
                }
            }
        }
    }
    out.mean = sum / channels.max(1) as f64;
    out
}

/// Appends the section.
pub fn section(s: &mut String) {
    let n = nearest_error(TRANSFORMS);
    let b = bilinear_error(TRANSFORMS);
    let _ = writeln!(s, "## Sprite texel mapping\n");
    let _ = writeln!(
        s,
        "`draw_sprite` maps each covered pixel's centre back to texel space by the inverse of \
         its 16.16 transform, found once per sprite (32.32 steps, one exact division per entry) \
         and stepped by adds across each span. Against an `f64` reference that inverts the same \
         16.16 matrix and translation exactly: {TRANSFORMS} random transforms (xorshift32; any \
         turn, scales 0.3 to 3 per axis, shear up to 0.5) of images of 1 to 32 texels a side \
         for nearest, 2 to 16 for bilinear (opaque and with 8-bit alpha in turn). Nearest: the \
         32.32 steps keep the point within about `2^-25` texel of the exact one (their rounding \
         times the pixels from the anchor), so \
         a texel can differ only for a pixel centre that close to a texel border; the closest \
         any case came is given. Bilinear: the point is rounded to 1/256 texel for the weights \
         and the result to a step, so a channel is within a step of the exact blend; with alpha \
         the colour is weighted by opacity, and its error is measured times the opacity (what \
         shows over black: a texel weighted by almost nothing may take any colour). \
         `tests/tests/sprite.rs` bounds both.\n"
    );
    let _ = writeln!(
        s,
        "| sampling | pixels | texel differs | at most (texels) | closest to a border (texels) |"
    );
    let _ = writeln!(s, "|---|---:|---:|---:|---:|");
    let _ = writeln!(
        s,
        "| nearest | {} | {:.4} % | {} | {:.1e} |\n",
        n.pixels,
        n.differ as f64 * 100.0 / n.pixels.max(1) as f64,
        n.max,
        n.closest
    );
    let _ = writeln!(
        s,
        "| bilinear | pixels | channel error, max (steps) | mean | max over black, 8-bit alpha | opacity, max (of 255) |"
    );
    let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|");
    let _ = writeln!(
        s,
        "| Rgb565 | {} | {:.3} | {:.3} | {:.3} | {:.3} |\n",
        b.pixels, b.max, b.mean, b.max_over, b.max_alpha
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/ACCURACY.md holds the section as this code writes it.
    #[test]
    fn accuracy_md_has_the_current_section() {
        let mut s = String::new();
        section(&mut s);
        crate::accuracy::assert_report_holds(&s);
    }
}
