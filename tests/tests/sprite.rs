//! `raster::sprite`: small cases as letter patterns, coverage against the reference triangle
//! rule, edge sharing, clipping, bands, alpha, nearest and bilinear sampling against `f64`, and
//! the limits of every input.
//!
//! The references are independent of the code under test: coverage is `reference_triangle` (exact
//! `i128` edge functions) on the quad's corners rounded to 1/256 pixel, as the module documents;
//! texels come from the transform inverted in `f64`; blends from the formula in `f64`.

use embedded_graphics::image::{Image, ImageRawLE};
use embedded_graphics::Drawable;
use embedded_graphics_core::pixelcolor::raw::RawU16;
use fixtures::scenes::XorShift32;
use fixtures::sprite::Recorder;
use rasterizer_core::prelude::*;
use rasterizer_core::raster::sprite::{
    draw_sprite, header, Affine, AlphaBits, Sprite, SpriteError,
};
use rasterizer_core::surface::{Band, ClipTo};
use rasterizer_core::texture::Filter;
use std::collections::BTreeSet;
use tests::{reference_triangle, StrictMock};

/// Texels of `w` x `h` whose colour names the texel: red = x, green = y, blue = 7.
fn coordinate_texels(w: u32, h: u32) -> Vec<u8> {
    let mut out = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let c = Rgb565::new(x as u8 % 32, y as u8 % 64, 7);
            out.extend_from_slice(&RawU16::from(c).into_inner().to_le_bytes());
        }
    }
    out
}

fn random_texels(r: &mut XorShift32, n: usize) -> Vec<u8> {
    (0..2 * n).map(|_| r.next_u32() as u8).collect()
}

fn fx(v: f64) -> Fx16 {
    Fx16::from_bits((v * 65536.0).round() as i32)
}

fn f(v: Fx16) -> f64 {
    f64::from(v.to_bits()) / 65536.0
}

/// The letters of a mock's pixels: texel `(x, y)` of a coordinate image is `b"AB.."[y * w + x]`,
/// unwritten pixels are blank.
fn letters(mock: &StrictMock<Rgb565>, w: u32) -> Vec<String> {
    let size = mock.bounding_box().size;
    (0..size.height as i32)
        .map(|y| {
            let row: String = (0..size.width as i32)
                .map(|x| match mock.get(x, y) {
                    None => ' ',
                    Some(c) => (b'A' + (c.g() as u32 * w + c.r() as u32) as u8) as char,
                })
                .collect();
            row.trim_end().to_string()
        })
        .collect()
}

fn draw_mock(w: u32, h: u32, a: &Affine, size: (u32, u32)) -> StrictMock<Rgb565> {
    let texels = coordinate_texels(w, h);
    let sprite = Sprite::from_parts(w, h, AlphaBits::None, &texels, &[]).unwrap();
    let mut mock = StrictMock::new(size.0, size.1);
    draw_sprite(&mut AnyTarget::new(&mut mock), &sprite, a, Filter::Nearest).unwrap();
    mock
}

fn affine(m: [[f64; 2]; 2], t: [f64; 2]) -> Affine {
    Affine {
        m: m.map(|r| r.map(fx)),
        t: t.map(fx),
    }
}

#[test]
fn identity_pattern() {
    let mock = draw_mock(3, 2, &Affine::translation(1, 1), (6, 4));
    assert_eq!(letters(&mock, 3), ["", " ABC", " DEF", ""]);
}

#[test]
fn quarter_turn_pattern() {
    // Clockwise on a y-down screen: the top row runs down the right-hand column. The centre
    // (4, 4): columns 3..5, rows 2.5..5.5, so rows 2, 3 and 4 (a centre on the top edge is in,
    // one on the bottom edge is out).
    let turn = Affine::rotate_scale(3, 2, Angle::QUARTER, Fx16::ONE, [fx(4.0), fx(4.0)]);
    let mock = draw_mock(3, 2, &turn, (7, 7));
    assert_eq!(
        letters(&mock, 3),
        ["", "", "   DA", "   EB", "   FC", "", ""]
    );
}

#[test]
fn scale_two_pattern() {
    let mock = draw_mock(2, 2, &affine([[2.0, 0.0], [0.0, 2.0]], [1.0, 0.0]), (6, 5));
    assert_eq!(letters(&mock, 2), [" AABB", " AABB", " CCDD", " CCDD", ""]);
}

#[test]
fn mirror_pattern() {
    // x mirrored: texel u lands at 4 - u, so the row reads backwards from pixel 1 to 3.
    let mock = draw_mock(3, 2, &affine([[-1.0, 0.0], [0.0, 1.0]], [4.0, 1.0]), (5, 4));
    assert_eq!(letters(&mock, 3), ["", " CBA", " FED", ""]);
    // And upside down too: a half turn by the matrix.
    let mock = draw_mock(
        3,
        2,
        &affine([[-1.0, 0.0], [0.0, -1.0]], [3.0, 2.0]),
        (4, 3),
    );
    assert_eq!(letters(&mock, 3), ["FED", "CBA", ""]);
}

#[test]
fn shear_pattern() {
    // x += v / 2: row v = 1 starts half a pixel right; centres on the slanted left edge are in.
    let mock = draw_mock(3, 2, &affine([[1.0, 0.5], [0.0, 1.0]], [0.0, 0.0]), (5, 2));
    assert_eq!(letters(&mock, 3), ["ABC", " DEF"]);
}

/// The quad's corners as the module documents them: `t + m (u, v)` in 16.16, rounded to 1/256.
fn corners(a: &Affine, w: i64, h: i64) -> [(i64, i64); 4] {
    let r = |v: Fx16| i64::from(v.to_bits());
    let map = |u: i64, v: i64| {
        let x = r(a.t[0]) + r(a.m[0][0]) * u + r(a.m[0][1]) * v;
        let y = r(a.t[1]) + r(a.m[1][0]) * u + r(a.m[1][1]) * v;
        ((x + 128) >> 8, (y + 128) >> 8)
    };
    [map(0, 0), map(w, 0), map(w, h), map(0, h)]
}

/// The pixels the quad covers: both halves by the reference triangle rule.
fn reference_cover(a: &Affine, w: u32, h: u32, size: (i32, i32)) -> BTreeSet<(i32, i32)> {
    let [p0, p1, p2, p3] = corners(a, w.into(), h.into());
    let mut set = BTreeSet::new();
    for tri in [[p0, p1, p2], [p0, p2, p3]] {
        for p in reference_triangle(tri, 8, size.0, size.1) {
            assert!(set.insert(p), "the reference halves overlap at {p:?}");
        }
    }
    set
}

/// A random transform: any angle, scales 0.3 to 3 per axis, some shear, anywhere near the screen.
fn random_affine(r: &mut XorShift32, w: u32, h: u32) -> Affine {
    let angle = r.unit() * std::f64::consts::PI;
    let (sx, sy) = (
        0.3 + 2.7 * (r.unit() + 1.0) / 2.0,
        0.3 + 2.7 * (r.unit() + 1.0) / 2.0,
    );
    let shear = r.unit() * 0.5;
    let (c, s) = (angle.cos(), angle.sin());
    let m = [
        [c * sx, (c * shear - s) * sy],
        [s * sx, (s * shear + c) * sy],
    ];
    let (cx, cy) = (30.0 + 20.0 * r.unit(), 25.0 + 20.0 * r.unit());
    let t = [
        cx - (m[0][0] * f64::from(w) + m[0][1] * f64::from(h)) / 2.0,
        cy - (m[1][0] * f64::from(w) + m[1][1] * f64::from(h)) / 2.0,
    ];
    affine(m, t)
}

#[test]
fn coverage_is_the_top_left_rule_on_both_halves() {
    let mut r = XorShift32::seeded(0x5eed_0001);
    let mut pixels = 0;
    for case in 0..400 {
        let (w, h) = (1 + r.next_u32() % 12, 1 + r.next_u32() % 12);
        let a = random_affine(&mut r, w, h);
        // The strict mock fails on a pixel written twice, the diagonal included.
        let mock = draw_mock(w, h, &a, (60, 50));
        let want = reference_cover(&a, w, h, (60, 50));
        assert_eq!(mock.written(), want, "case {case}: {a:?} {w}x{h}");
        pixels += want.len();
    }
    assert!(pixels > 10_000, "{pixels}");
}

#[test]
fn sprites_sharing_edges_leave_no_gap_and_no_double_pixel() {
    let mut r = XorShift32::seeded(0x5eed_0002);
    let mut pixels = 0;
    for case in 0..300 {
        let (w, h) = (1 + r.next_u32() % 9, 1 + r.next_u32() % 9);
        // Entries and translation on the 1/256 grid, so that every tile corner is exact and the
        // tiles' outline is the whole image's quad (rounding could bend it).
        let mut a = random_affine(&mut r, 2 * w, 2 * h);
        let grid = |v: Fx16| Fx16::from_bits(v.to_bits() & !0xFF);
        a.m = a.m.map(|row| row.map(grid));
        a.t = a.t.map(grid);
        // Four w x h tiles of one 2w x 2h image: the tile at (i, j) moved by m (i w, j h), exact
        // in 16.16.
        let texels = coordinate_texels(w, h);
        let tile = Sprite::from_parts(w, h, AlphaBits::None, &texels, &[]).unwrap();
        let mut mock = StrictMock::new(60, 50);
        for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let mut t = a;
            let (du, dv) = (i64::from(i * w), i64::from(j * h));
            for k in 0..2 {
                let m = |c: usize| i64::from(a.m[k][c].to_bits());
                let moved = i64::from(a.t[k].to_bits()) + m(0) * du + m(1) * dv;
                t.t[k] = Fx16::from_bits(moved as i32);
            }
            draw_sprite(&mut AnyTarget::new(&mut mock), &tile, &t, Filter::Nearest).unwrap();
        }
        // No pixel twice (the mock), and no gap: the tiles cover exactly the whole image's quad.
        let whole = reference_cover(&a, 2 * w, 2 * h, (60, 50));
        assert_eq!(mock.written(), whole, "case {case}: {a:?} {w}x{h}");
        pixels += whole.len();
    }
    assert!(pixels > 10_000, "{pixels}");
}

/// The texel point of pixel `(x, y)`'s centre by the transform inverted in `f64`.
fn texel_point(a: &Affine, x: i32, y: i32) -> (f64, f64) {
    let [[m00, m01], [m10, m11]] = a.m.map(|r| r.map(f));
    let det = m00 * m11 - m01 * m10;
    let (px, py) = (
        f64::from(x) + 0.5 - f(a.t[0]),
        f64::from(y) + 0.5 - f(a.t[1]),
    );
    ((m11 * px - m01 * py) / det, (-m10 * px + m00 * py) / det)
}

#[test]
fn nearest_texels_match_the_f64_inverse() {
    // Measured (docs/ACCURACY.md, "Sprite texel mapping": 1,000 transforms, 699,344 pixels): no
    // texel differs at all, the closest point 4e-7 texel from a border. Here too none may differ
    // (the bound is exact), except within 1e-6 texel of a border, where the 32.32 rounding
    // (about 2^-25 texel) could decide.
    let mut r = XorShift32::seeded(0x5eed_0003);
    let (mut pixels, mut differ) = (0, 0);
    for _ in 0..2000 {
        let (w, h) = (1 + r.next_u32() % 24, 1 + r.next_u32() % 24);
        let a = random_affine(&mut r, w, h);
        let mock = draw_mock(w, h, &a, (60, 50));
        for (x, y) in mock.written() {
            let c = mock.get(x, y).unwrap();
            let (u, v) = texel_point(&a, x, y);
            let near_border = |t: f64| (t - t.round()).abs() < 1e-6;
            if near_border(u) || near_border(v) {
                continue;
            }
            let pick = |t: f64, n: u32| t.floor().clamp(0.0, f64::from(n - 1)) as u8;
            pixels += 1;
            if (c.r(), c.g()) != (pick(u, w), pick(v, h)) {
                differ += 1;
            }
        }
    }
    assert!(pixels > 100_000, "{pixels}");
    assert_eq!(differ, 0, "{differ} of {pixels} texels differ");
}

#[test]
fn identity_is_a_plain_copy_and_equals_embedded_graphics_image() {
    let mut r = XorShift32::seeded(0x5eed_0004);
    let (w, h) = (13, 9);
    let texels = random_texels(&mut r, (w * h) as usize);
    let sprite = Sprite::from_parts(w, h, AlphaBits::None, &texels, &[]).unwrap();
    for (x0, y0) in [(0, 0), (5, 3), (-4, -2), (30, 20), (-13, 0)] {
        let mut ours = vec![0u16; 40 * 30];
        let mut fb = Framebuffer::<Rgb565>::new(&mut ours, 40, 30).unwrap();
        let a = Affine::translation(x0, y0);
        draw_sprite(&mut fb, &sprite, &a, Filter::Nearest).unwrap();
        draw_sprite(&mut fb, &sprite, &a, Filter::Bilinear).unwrap();
        // The copy by hand.
        let mut copy = vec![0u16; 40 * 30];
        for y in 0..h as i32 {
            for x in 0..w as i32 {
                let (px, py) = (x + x0, y + y0);
                if (0..40).contains(&px) && (0..30).contains(&py) {
                    let i = 2 * (y as usize * w as usize + x as usize);
                    copy[py as usize * 40 + px as usize] =
                        u16::from_le_bytes([texels[i], texels[i + 1]]);
                }
            }
        }
        assert_eq!(ours, copy, "at ({x0}, {y0})");
        // embedded-graphics' Image of the same little-endian texels.
        let mut theirs = vec![0u16; 40 * 30];
        let mut fb = Framebuffer::<Rgb565>::new(&mut theirs, 40, 30).unwrap();
        let raw = ImageRawLE::<Rgb565>::new(&texels, w);
        Image::new(&raw, Point::new(x0, y0)).draw(&mut fb).unwrap();
        assert_eq!(ours, theirs, "at ({x0}, {y0})");
    }
}

/// `round((s a + d (255 - a)) / 255)` per channel, halves up, in f64.
fn blend_ref(src: u16, dst: u16, a: u8) -> u16 {
    let fields = [(11, 0x1F), (5, 0x3F), (0, 0x1F)];
    let mut out = 0;
    for (shift, mask) in fields {
        let (s, d) = (
            f64::from((src >> shift) & mask),
            f64::from((dst >> shift) & mask),
        );
        let a = f64::from(a);
        let v = ((s * a + d * (255.0 - a)) / 255.0 + 0.5).floor() as u16;
        out |= v << shift;
    }
    out
}

#[test]
fn alpha_of_one_four_and_eight_bits() {
    let mut r = XorShift32::seeded(0x5eed_0005);
    let (w, h) = (5u32, 3u32);
    let texels = random_texels(&mut r, 15);
    let background = 0x39E7u16;
    for bits in [AlphaBits::One, AlphaBits::Four, AlphaBits::Eight] {
        let plane: Vec<u8> = (0..bits.row_bytes(w) * h as usize)
            .map(|_| r.next_u32() as u8)
            .collect();
        let sprite = Sprite::from_parts(w, h, bits, &texels, &plane).unwrap();
        let mut buf = vec![background; 8 * 6];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 8, 6).unwrap();
        draw_sprite(
            &mut fb,
            &sprite,
            &Affine::translation(2, 1),
            Filter::Nearest,
        )
        .unwrap();
        for y in 0..h {
            for x in 0..w {
                let i = 2 * (y * w + x) as usize;
                let c = u16::from_le_bytes([texels[i], texels[i + 1]]);
                // The plane read by hand: rows padded to whole bytes, leftmost texel highest.
                let a = match bits {
                    AlphaBits::One => {
                        ((plane[y as usize + x as usize / 8] >> (7 - x % 8)) & 1) * 255
                    }
                    AlphaBits::Four => {
                        ((plane[(y * 3) as usize + x as usize / 2] >> (4 * (1 - x % 2))) & 15) * 17
                    }
                    _ => plane[(y * 5 + x) as usize],
                };
                let want = if bits == AlphaBits::One {
                    if a == 255 {
                        c
                    } else {
                        background
                    }
                } else {
                    blend_ref(c, background, a)
                };
                let got = buf[((y + 1) * 8 + x + 2) as usize];
                assert_eq!(got, want, "{bits:?} texel ({x}, {y}) alpha {a}");
            }
        }
    }
    // A 1-bit sprite needs no read-back; blending ones refuse a target that cannot.
    let plane = [0u8; 3];
    let sprite = Sprite::from_parts(5, 3, AlphaBits::Four, &texels, &[0; 9]).unwrap();
    let mut mock = StrictMock::<Rgb565>::new(8, 8);
    assert_eq!(
        draw_sprite(
            &mut AnyTarget::new(&mut mock),
            &sprite,
            &Affine::IDENTITY,
            Filter::Nearest
        ),
        Err(BlendError::CannotReadBack)
    );
    let sprite = Sprite::from_parts(5, 3, AlphaBits::One, &texels, &plane).unwrap();
    draw_sprite(
        &mut AnyTarget::new(&mut mock),
        &sprite,
        &Affine::IDENTITY,
        Filter::Nearest,
    )
    .unwrap();
    assert!(mock.written().is_empty());
}

/// The bilinear colour in f64 at texel point `(u, v)`: the four texels around it, weighted by
/// distance and by opacity, and the weighted opacity.
fn bilinear_ref(sprite: &Sprite<'_>, u: f64, v: f64) -> ([f64; 3], f64) {
    let (us, vs) = (u - 0.5, v - 0.5);
    let (x0, y0) = (us.floor(), vs.floor());
    let (fx, fy) = (us - x0, vs - y0);
    let clamp = |t: f64, n: u32| t.clamp(0.0, f64::from(n - 1)) as u32;
    let mut sum = [0.0; 3];
    let mut total = 0.0;
    for (dx, dy, wt) in [
        (0.0, 0.0, (1.0 - fx) * (1.0 - fy)),
        (1.0, 0.0, fx * (1.0 - fy)),
        (0.0, 1.0, (1.0 - fx) * fy),
        (1.0, 1.0, fx * fy),
    ] {
        let (c, a) = sprite.texel(
            clamp(x0 + dx, sprite.width()),
            clamp(y0 + dy, sprite.height()),
        );
        let wa = wt * f64::from(a);
        total += wa;
        for (s, ch) in sum.iter_mut().zip([c >> 11, (c >> 5) & 63, c & 31]) {
            *s += wa * f64::from(ch);
        }
    }
    (
        sum.map(|s| if total > 0.0 { s / total } else { 0.0 }),
        total,
    )
}

#[test]
fn bilinear_colours_match_the_f64_reference() {
    // Measured (600 transforms, opaque and 8-bit alpha alternately; docs/ACCURACY.md's
    // "Sprite texel mapping" has 0.634, 0.610 and 1.080 over 1,000): the largest channel error
    // 0.63 steps opaque and 0.59 over black (colour times opacity: a texel weighted by almost
    // nothing may take any colour), the opacity's 1.05 of 255 (the point rounded to 1/256 texel
    // for the weights, then the result to a step). Bounded at about twice that.
    let mut r = XorShift32::seeded(0x5eed_0006);
    let (mut worst, mut worst_over, mut worst_alpha, mut pixels) = (0.0f64, 0.0f64, 0.0f64, 0);
    for case in 0..600 {
        let (w, h) = (2 + r.next_u32() % 12, 2 + r.next_u32() % 12);
        let texels = random_texels(&mut r, (w * h) as usize);
        let plane: Vec<u8> = (0..w * h).map(|_| r.next_u32() as u8).collect();
        let bits = if case % 2 == 0 {
            AlphaBits::None
        } else {
            AlphaBits::Eight
        };
        let plane = if bits == AlphaBits::None {
            &[][..]
        } else {
            &plane[..]
        };
        let sprite = Sprite::from_parts(w, h, bits, &texels, plane).unwrap();
        let a = random_affine(&mut r, w, h);
        // Each pixel's colour and opacity as the sprite hands them to the target.
        let mut rec = Recorder::new(60, 50);
        draw_sprite(&mut rec, &sprite, &a, Filter::Bilinear).unwrap();
        for ((x, y), (c, alpha)) in rec.pixels {
            let (u, v) = texel_point(&a, x, y);
            let (want, total) = bilinear_ref(&sprite, u, v);
            pixels += 1;
            for (ch, wv) in [c >> 11, (c >> 5) & 63, c & 31].into_iter().zip(want) {
                // Over black: the colour times its opacity, what the picture shows (a texel
                // weighted by almost nothing may take any colour).
                let e = (f64::from(ch) * f64::from(alpha) - wv * total).abs() / 255.0;
                if bits == AlphaBits::None {
                    worst = worst.max(e);
                } else {
                    worst_over = worst_over.max(e);
                }
            }
            worst_alpha = worst_alpha.max((f64::from(alpha) - total).abs());
        }
    }
    assert!(pixels > 50_000, "{pixels}");
    assert!(worst <= 1.3, "channel error {worst}");
    assert!(worst_over <= 1.2, "channel error over black {worst_over}");
    assert!(worst_alpha <= 2.1, "opacity error {worst_alpha}");
}

#[test]
fn clipped_drawing_is_the_unclipped_drawing_cut() {
    let mut r = XorShift32::seeded(0x5eed_0007);
    // Pixels drawn inside the clip rectangle and cut off at the frame's border, over all cases:
    // both must occur for the comparison to mean something.
    let (mut in_rect, mut cut) = (0, 0);
    for case in 0..300 {
        let (w, h) = (1 + r.next_u32() % 20, 1 + r.next_u32() % 20);
        let texels = random_texels(&mut r, (w * h) as usize);
        let sprite = Sprite::from_parts(w, h, AlphaBits::None, &texels, &[]).unwrap();
        let a = random_affine(&mut r, w, h);
        let filter = if case % 2 == 0 {
            Filter::Nearest
        } else {
            Filter::Bilinear
        };
        // The unclipped picture: a frame 40 pixels larger on every side, the sprite moved in.
        let mut big = vec![0u16; 140 * 130];
        let mut fb = Framebuffer::<Rgb565>::new(&mut big, 140, 130).unwrap();
        let mut moved = a;
        moved.t = [fx(f(a.t[0]) + 40.0), fx(f(a.t[1]) + 40.0)];
        draw_sprite(&mut fb, &sprite, &moved, filter).unwrap();
        // At the frame's border (the sprites lie across it).
        let mut small = vec![0u16; 60 * 50];
        let mut fb = Framebuffer::<Rgb565>::new(&mut small, 60, 50).unwrap();
        draw_sprite(&mut fb, &sprite, &a, filter).unwrap();
        // In a clip rectangle.
        let rect = Rectangle::new(Point::new(20, 15), Size::new(17, 13));
        let mut clipped = vec![0u16; 60 * 50];
        let mut fb = Framebuffer::<Rgb565>::new(&mut clipped, 60, 50).unwrap();
        draw_sprite(&mut ClipTo::new(&mut fb, rect), &sprite, &a, filter).unwrap();
        for y in 0..50 {
            for x in 0..60 {
                let want = big[(y + 40) * 140 + x + 40];
                assert_eq!(small[y * 60 + x], want, "case {case} frame ({x}, {y})");
                let inside = rect.contains(Point::new(x as i32, y as i32));
                in_rect += usize::from(inside && want != 0);
                let want = if inside { want } else { 0 };
                assert_eq!(clipped[y * 60 + x], want, "case {case} clip ({x}, {y})");
            }
        }
        let shown: usize = small.iter().filter(|&&p| p != 0).count();
        let whole: usize = big.iter().filter(|&&p| p != 0).count();
        cut += whole - shown;
    }
    assert!(
        in_rect > 1000 && cut > 1000,
        "{in_rect} pixels in the rectangle, {cut} cut off"
    );
}

#[test]
fn bands_equal_the_whole_frame() {
    let sprite = Sprite::from_bytes(fixtures::sprite::I1_IMAGE).unwrap();
    let placements = fixtures::sprite::i1();
    for filter in [Filter::Nearest, Filter::Bilinear] {
        let mut whole = vec![0u16; 320 * 240];
        let mut fb = Framebuffer::<Rgb565>::new(&mut whole, 320, 240).unwrap();
        for p in &placements {
            draw_sprite(&mut fb, &sprite, &p.transform(), filter).unwrap();
        }
        let drawn = whole.iter().filter(|&&p| p != 0).count();
        assert!(drawn > 50_000, "{filter:?}: only {drawn} pixels drawn");
        for rows in [1u32, 7, 16] {
            let mut frame = vec![0u16; 320 * 240];
            for y0 in (0..240).step_by(rows as usize) {
                let n = rows.min(240 - y0);
                let mut buf = vec![0u16; (320 * n) as usize];
                let fb = Framebuffer::<Rgb565>::new(&mut buf, 320, n).unwrap();
                let mut band = Band::new(fb, y0 as i32);
                for p in &placements {
                    draw_sprite(&mut band, &sprite, &p.transform(), filter).unwrap();
                }
                let start = (y0 * 320) as usize;
                frame[start..start + buf.len()].copy_from_slice(&buf);
            }
            assert!(frame == whole, "{filter:?} in bands of {rows}");
        }
    }
}

#[test]
fn limits_never_panic() {
    // Image checks: typed errors, never a panic.
    assert_eq!(
        Sprite::from_parts(0, 4, AlphaBits::None, &[], &[]),
        Err(SpriteError::BadSize {
            width: 0,
            height: 4
        })
    );
    assert_eq!(
        Sprite::from_parts(2, 2, AlphaBits::None, &[0; 7], &[]),
        Err(SpriteError::WrongLength {
            expected: 8,
            actual: 7
        })
    );
    assert!(header(4097, 1, AlphaBits::None).is_err());
    // The largest side at every extreme of the transform (overflow checks are on in tests).
    let texels = vec![0xA5u8; 2 * 4096];
    let plane = vec![0x5Au8; 4096];
    let wide = Sprite::from_parts(4096, 1, AlphaBits::Eight, &texels, &plane).unwrap();
    let tall = Sprite::from_parts(1, 4096, AlphaBits::Eight, &texels, &plane).unwrap();
    let e = Fx16::from_bits;
    let extremes = [i32::MIN, i32::MIN + 1, -1, 0, 1, 1 << 16, i32::MAX];
    let mut buf = vec![0u16; 64 * 48];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 64, 48).unwrap();
    let mut r = XorShift32::seeded(0x5eed_0008);
    for _ in 0..3000 {
        let mut pick = || extremes[(r.next_u32() % extremes.len() as u32) as usize];
        let a = Affine {
            m: [[e(pick()), e(pick())], [e(pick()), e(pick())]],
            t: [e(pick()), e(pick())],
        };
        for s in [&wide, &tall] {
            for filter in [Filter::Nearest, Filter::Bilinear] {
                draw_sprite(&mut fb, s, &a, filter).unwrap();
            }
        }
    }
    // Translations at the i32 limits saturate; huge and tiny scales; a singular matrix.
    for (x, y) in [
        (i32::MIN, i32::MIN),
        (i32::MAX, i32::MAX),
        (i32::MIN, 0),
        (0, i32::MAX),
    ] {
        draw_sprite(&mut fb, &wide, &Affine::translation(x, y), Filter::Nearest).unwrap();
    }
    for scale in [Fx16::MAX, Fx16::MIN, Fx16::EPSILON, Fx16::ZERO] {
        for angle in [0, 1, 45, 90, 359] {
            let a = Affine::rotate_scale(4096, 1, Angle::from_degrees(angle), scale, [fx(3.0); 2]);
            draw_sprite(&mut fb, &wide, &a, Filter::Bilinear).unwrap();
        }
    }
    let mut before = vec![0u16; 64 * 48];
    before.copy_from_slice(fb.as_slice());
    let singular = affine([[1.0, 2.0], [2.0, 4.0]], [10.0, 10.0]);
    draw_sprite(&mut fb, &wide, &singular, Filter::Nearest).unwrap();
    assert_eq!(
        fb.as_slice(),
        &before[..],
        "a singular transform draws nothing"
    );
}
