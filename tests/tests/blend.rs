//! Blending: translucent fills and lines, anti-aliased lines. The integer blend against its
//! exact formula and an f64 reference, patterns on a read-back mock that fails on out-of-bounds
//! and on blending a pixel twice, the typed error for targets that cannot read back, and bands.

use proptest::prelude::*;
use rasterizer_core::color::{blend, blend_channel};
use rasterizer_core::prelude::*;
use rasterizer_core::surface::{Band, BlendError, ClipTo};
use tests::StrictMock;

/// A read-back surface that records the opacity each pixel was blended with, and panics on a
/// pixel outside it or blended twice (a second blend would darken it: a visible seam).
struct BlendMock {
    width: u32,
    height: u32,
    alpha: Vec<Option<u8>>,
}

impl BlendMock {
    fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            alpha: vec![None; (width * height) as usize],
        }
    }

    /// Rows of ` ` (not blended), `#` (opacity 255) or a digit: opacity * 10 / 255.
    fn pattern(&self) -> Vec<String> {
        (0..self.height)
            .map(|y| {
                (0..self.width)
                    .map(|x| match self.alpha[(y * self.width + x) as usize] {
                        None => ' ',
                        Some(255) => '#',
                        Some(a) => char::from(b'0' + (u32::from(a) * 10 / 255) as u8),
                    })
                    .collect()
            })
            .collect()
    }

    #[track_caller]
    fn assert_pattern(&self, expected: &[&str]) {
        assert_eq!(self.pattern(), expected, "\n{}", self.pattern().join("\n"));
    }
}

impl OriginDimensions for BlendMock {
    fn size(&self) -> Size {
        Size::new(self.width, self.height)
    }
}

impl DrawTarget for BlendMock {
    type Color = Gray8;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Gray8>>>(&mut self, _: I) -> Result<(), Self::Error> {
        panic!("a blending rasterizer wrote an opaque pixel");
    }
}

impl Surface for BlendMock {
    const READ_BACK: bool = true;
    fn blend_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        _: Gray8,
        alpha: u8,
    ) -> Result<(), BlendError<Self::Error>> {
        for x in x..x + len as i32 {
            assert!(
                (0..self.width as i32).contains(&x) && (0..self.height as i32).contains(&y),
                "blend outside the target at ({x}, {y})"
            );
            let i = (y as u32 * self.width + x as u32) as usize;
            assert!(self.alpha[i].is_none(), "pixel ({x}, {y}) blended twice");
            self.alpha[i] = Some(alpha);
        }
        Ok(())
    }
}

#[test]
fn blend_channel_is_the_exact_rounded_formula() {
    for a in 0..=255u32 {
        for s in 0..=255u32 {
            for d in 0..=255u32 {
                let exact = (s * a + d * (255 - a) + 127) / 255;
                assert_eq!(
                    u32::from(blend_channel(s as u8, d as u8, a as u8)),
                    exact,
                    "{s} {d} {a}"
                );
            }
        }
    }
}

#[test]
fn rgb565_packed_blend_matches_the_channel_blend() {
    let mut buf = [0u16; 64];
    for a in [0u8, 1, 64, 127, 128, 200, 254, 255] {
        for raw in (0..=u16::MAX).step_by(61) {
            let src = Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(raw));
            for (i, w) in buf.iter_mut().enumerate() {
                *w = (i as u16).wrapping_mul(40_503).wrapping_add(raw);
            }
            let before = buf;
            let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 64, 1).unwrap();
            fb.blend_span_in_clip(0, 0, 64, src, a).unwrap();
            for (i, &d) in before.iter().enumerate() {
                let dst = Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(d));
                assert_eq!(fb.pixel(Point::new(i as i32, 0)), Some(blend(src, dst, a)));
            }
        }
    }
}

proptest! {
    #[test]
    fn blend_is_within_half_a_step_of_f64(s in 0..=255u8, d in 0..=255u8, a in 0..=255u8) {
        let f = (f64::from(s) * f64::from(a) + f64::from(d) * (255.0 - f64::from(a))) / 255.0;
        let got = f64::from(blend(Gray8::new(s), Gray8::new(d), a).luma());
        prop_assert!((got - f).abs() <= 0.5 + 1e-9, "{s} {d} {a}: {got} vs {f}");
        // At Rgb565's depths too.
        let (s5, d5) = (s >> 3, d >> 3);
        let f5 = (f64::from(s5) * f64::from(a) + f64::from(d5) * (255.0 - f64::from(a))) / 255.0;
        let got5 = blend(Rgb565::new(s5, 0, 0), Rgb565::new(d5, 0, 0), a).r();
        prop_assert!((f64::from(got5) - f5).abs() <= 0.5 + 1e-9);
    }
}

#[test]
fn opacity_255_is_opaque_and_0_leaves_the_target() {
    let v = |x, y| SubPoint::<4>::new(x * 16, y * 16);
    let tri = [v(1, 1), v(30, 4), v(9, 20)];
    let (mut a, mut b) = ([7u16; 32 * 24], [7u16; 32 * 24]);
    let mut fa = Framebuffer::<Rgb565>::new(&mut a, 32, 24).unwrap();
    let mut fbb = Framebuffer::<Rgb565>::new(&mut b, 32, 24).unwrap();
    fill_triangle(&mut fa, tri, Rgb565::CSS_ORANGE).unwrap();
    draw_line(&mut fa, Point::new(0, 23), Point::new(31, 0), Rgb565::GREEN).unwrap();
    fill_triangle_alpha(&mut fbb, tri, Rgb565::CSS_ORANGE, 255).unwrap();
    draw_line_alpha(
        &mut fbb,
        Point::new(0, 23),
        Point::new(31, 0),
        Rgb565::GREEN,
        255,
    )
    .unwrap();
    assert_eq!(a, b);
    let mut fbb = Framebuffer::<Rgb565>::new(&mut b, 32, 24).unwrap();
    fill_triangle_alpha(&mut fbb, tri, Rgb565::BLUE, 0).unwrap();
    draw_line_alpha(
        &mut fbb,
        Point::new(0, 0),
        Point::new(31, 23),
        Rgb565::BLUE,
        0,
    )
    .unwrap();
    assert_eq!(a, b);
}

#[test]
fn target_without_read_back_gets_a_typed_error_and_no_pixels() {
    let mut mock = StrictMock::<Rgb565>::new(8, 8);
    let mut t = AnyTarget::new(&mut mock);
    let v = |x, y| SubPoint::<4>::new(x * 16, y * 16);
    assert_eq!(
        fill_triangle_alpha(&mut t, [v(0, 0), v(8, 0), v(0, 8)], Rgb565::RED, 100),
        Err(BlendError::CannotReadBack)
    );
    let (a, b) = (Point::new(0, 0), Point::new(7, 3));
    assert_eq!(
        draw_line_alpha(&mut t, a, b, Rgb565::RED, 100),
        Err(BlendError::CannotReadBack)
    );
    assert_eq!(
        draw_line_aa(&mut t, a, b, Rgb565::RED),
        Err(BlendError::CannotReadBack)
    );
    // Even when nothing would be visible: the answer does not depend on the geometry.
    assert_eq!(
        draw_line_aa(&mut t, Point::new(-9, -9), Point::new(-20, -3), Rgb565::RED),
        Err(BlendError::CannotReadBack)
    );
    assert_eq!(mock.calls.pixels, 0);
}

#[test]
fn translucent_fill_and_line_blend_the_opaque_pixels_once() {
    let v = |x, y| SubPoint::<4>::new(x, y);
    let tri = [v(8, 8), v(150, 40), v(40, 120)];
    let mut strict = StrictMock::<Gray8>::new(10, 8);
    fill_triangle(&mut AnyTarget::new(&mut strict), tri, Gray8::WHITE).unwrap();
    let mut mock = BlendMock::new(10, 8);
    fill_triangle_alpha(&mut mock, tri, Gray8::WHITE, 255).unwrap();
    let want: Vec<String> = strict.pattern();
    assert_eq!(mock.pattern(), want);

    let mut mock = BlendMock::new(8, 4);
    draw_line_alpha(
        &mut mock,
        Point::new(-3, 0),
        Point::new(12, 3),
        Gray8::WHITE,
        128,
    )
    .unwrap();
    mock.assert_pattern(&["        ", "55555   ", "     555", "        "]);
}

#[test]
fn aa_line_patterns() {
    let aa = |w, h, a: (i32, i32), b: (i32, i32)| {
        let mut mock = BlendMock::new(w, h);
        draw_line_aa(
            &mut mock,
            Point::new(a.0, a.1),
            Point::new(b.0, b.1),
            Gray8::WHITE,
        )
        .unwrap();
        mock
    };
    // Axis-aligned and diagonal lines pass through pixel centres: full coverage only.
    aa(6, 3, (0, 1), (5, 1)).assert_pattern(&["      ", "######", "      "]);
    aa(4, 4, (0, 0), (3, 3)).assert_pattern(&["#   ", " #  ", "  # ", "   #"]);
    // Slope 1/4: coverage 3/4 + 1/4, 2/4 + 2/4 (127 + 128: the far pixel takes the half), 1/4 +
    // 3/4 between the full endpoints.
    aa(5, 2, (0, 0), (4, 1)).assert_pattern(&["#742 ", " 257#"]);
    // The same, steep and drawn backwards.
    aa(2, 5, (1, 4), (0, 0)).assert_pattern(&["# ", "72", "45", "27", " #"]);
    // Up and to the right.
    aa(5, 2, (0, 1), (4, 0)).assert_pattern(&[" 257#", "#742 "]);
    // Clipped at every edge of a small target, never outside it.
    aa(4, 3, (-5, -2), (9, 5)).assert_pattern(&["4   ", "5#4 ", "  5#"]);
}

/// The f64 model of the anti-aliased line: the ideal line through the endpoint centres, and per
/// major step the two pixels straddling it with coverage 1 - distance.
fn aa_reference(w: i32, h: i32, a: (i32, i32), b: (i32, i32)) -> Vec<f64> {
    let mut out = vec![0.0; (w * h) as usize];
    let (dx, dy) = (f64::from(b.0 - a.0), f64::from(b.1 - a.1));
    let major_x = dx.abs() >= dy.abs();
    let (m0, m1) = if major_x { (a.0, b.0) } else { (a.1, b.1) };
    for m in m0.min(m1)..=m0.max(m1) {
        let t = if m0 == m1 {
            0.0
        } else {
            f64::from(m - m0) / f64::from(m1 - m0)
        };
        let n = if major_x {
            f64::from(a.1) + t * dy
        } else {
            f64::from(a.0) + t * dx
        };
        let lo = n.floor();
        for (p, cover) in [(lo, 1.0 - (n - lo)), (lo + 1.0, n - lo)] {
            let (x, y) = if major_x {
                (m, p as i32)
            } else {
                (p as i32, m)
            };
            if (0..w).contains(&x) && (0..h).contains(&y) {
                out[(y * w + x) as usize] += cover;
            }
        }
    }
    out
}

proptest! {
    #[test]
    fn aa_line_coverage_is_within_half_a_step_of_f64(
        ax in -20..60i32, ay in -20..50i32, bx in -20..60i32, by in -20..50i32,
    ) {
        let (w, h) = (40, 30);
        let mut buf = vec![0u8; (w * h) as usize];
        let mut fb = Framebuffer::<Gray8>::new(&mut buf, w as u32, h as u32).unwrap();
        draw_line_aa(&mut fb, Point::new(ax, ay), Point::new(bx, by), Gray8::WHITE).unwrap();
        let want = aa_reference(w, h, (ax, ay), (bx, by));
        for (i, (&got, &f)) in buf.iter().zip(&want).enumerate() {
            prop_assert!((f64::from(got) - 255.0 * f).abs() <= 0.5 + 1e-6,
                "pixel {} {}: {} vs {}", i as i32 % w, i as i32 / w, got, 255.0 * f);
        }
        // Symmetric.
        let mut rev = vec![0u8; (w * h) as usize];
        let mut fb = Framebuffer::<Gray8>::new(&mut rev, w as u32, h as u32).unwrap();
        draw_line_aa(&mut fb, Point::new(bx, by), Point::new(ax, ay), Gray8::WHITE).unwrap();
        prop_assert_eq!(rev, buf);
    }

    #[test]
    fn aa_line_clips_exactly(
        ax in -30..70i32, ay in -30..60i32, bx in -30..70i32, by in -30..60i32,
        cx in 0..40i32, cy in 0..30i32, cw in 0..40u32, ch in 0..30u32,
    ) {
        let (w, h) = (40u32, 30u32);
        let (a, b) = (Point::new(ax, ay), Point::new(bx, by));
        let mut whole = vec![0u8; (w * h) as usize];
        let mut fb = Framebuffer::<Gray8>::new(&mut whole, w, h).unwrap();
        draw_line_aa(&mut fb, a, b, Gray8::WHITE).unwrap();
        let mut part = vec![0u8; (w * h) as usize];
        let mut fb = Framebuffer::<Gray8>::new(&mut part, w, h).unwrap();
        let area = Rectangle::new(Point::new(cx, cy), Size::new(cw, ch));
        draw_line_aa(&mut ClipTo::new(&mut fb, area), a, b, Gray8::WHITE).unwrap();
        for y in 0..h as i32 {
            for x in 0..w as i32 {
                let i = (y * w as i32 + x) as usize;
                let inside = (cx..cx + cw as i32).contains(&x) && (cy..cy + ch as i32).contains(&y);
                prop_assert_eq!(part[i], if inside { whole[i] } else { 0 });
            }
        }
    }

    #[test]
    fn aa_line_at_the_i32_limits_stays_inside(
        ax in any::<i32>(), ay in any::<i32>(), bx in any::<i32>(), by in any::<i32>(),
        near in any::<bool>(),
    ) {
        // Half the cases aim one end into the target so that the line crosses it.
        let a = if near { Point::new(ax.rem_euclid(16), ay.rem_euclid(12)) } else { Point::new(ax, ay) };
        let mut mock = BlendMock::new(16, 12);
        draw_line_aa(&mut mock, a, Point::new(bx, by), Gray8::WHITE).unwrap();
    }
}

#[test]
fn bands_blend_exactly_as_the_whole_frame() {
    let (w, h) = (64u32, 48u32);
    let mut whole = vec![0u16; (w * h) as usize];
    {
        let mut fb = Framebuffer::<Rgb565>::new(&mut whole, w, h).unwrap();
        fb.clear(Rgb565::new(3, 20, 9)).unwrap();
        draw_scene(&mut fb);
    }
    for rows in [1u32, 5, 16] {
        let mut band_buf = vec![0u16; (w * rows) as usize];
        let mut y0 = 0;
        while y0 < h as i32 {
            let n = rows.min(h - y0 as u32);
            let fb = Framebuffer::<Rgb565>::new(&mut band_buf[..(w * n) as usize], w, n).unwrap();
            let mut band = Band::new(fb, y0);
            band.clear(Rgb565::new(3, 20, 9)).unwrap();
            draw_scene(&mut band);
            let start = (y0 as u32 * w) as usize;
            assert_eq!(
                band.framebuffer().as_slice(),
                &whole[start..start + (w * n) as usize],
                "{rows}-row band at {y0}"
            );
            y0 += n as i32;
        }
    }
}

fn draw_scene<S: Surface<Color = Rgb565, Error = core::convert::Infallible>>(s: &mut S) {
    let v = |x, y| SubPoint::<4>::new(x, y);
    fill_triangle_alpha(s, [v(-40, 10), v(900, 200), v(300, 760)], Rgb565::RED, 150).unwrap();
    fill_triangle_alpha(s, [v(500, -30), v(1000, 700), v(30, 400)], Rgb565::CYAN, 90).unwrap();
    draw_line_alpha(
        s,
        Point::new(-5, 3),
        Point::new(70, 44),
        Rgb565::YELLOW,
        200,
    )
    .unwrap();
    for i in 0..12 {
        let (a, b) = (Point::new(2 + i * 5, -3), Point::new(60 - i * 3, 50));
        draw_line_aa(s, a, b, Rgb565::WHITE).unwrap();
        draw_line_aa(
            s,
            Point::new(-4, i * 4),
            Point::new(70, 47 - i * 3),
            Rgb565::GREEN,
        )
        .unwrap();
    }
}

fn aa_wide(w: u32, h: u32, a: (i32, i32), b: (i32, i32), width: u32) -> BlendMock {
    let mut mock = BlendMock::new(w, h);
    draw_line_aa_wide(
        &mut mock,
        Point::new(a.0, a.1),
        Point::new(b.0, b.1),
        width,
        Gray8::WHITE,
    )
    .unwrap();
    mock
}

#[test]
fn wide_aa_line_patterns() {
    // Horizontal, width 3: three full rows; width 2: one full row and two halves (5 = 128/255).
    aa_wide(6, 5, (0, 2), (5, 2), 3)
        .assert_pattern(&["      ", "######", "######", "######", "      "]);
    aa_wide(6, 5, (0, 2), (5, 2), 2)
        .assert_pattern(&["      ", "555555", "######", "555555", "      "]);
    // Width 4: two full rows each side of the centre row's middle, halves beyond.
    aa_wide(3, 7, (0, 3), (2, 3), 4)
        .assert_pattern(&["   ", "555", "###", "###", "###", "555", "   "]);
    // Vertical, drawn backwards.
    aa_wide(5, 3, (2, 2), (2, 0), 3).assert_pattern(&[" ### ", " ### ", " ### "]);
    // Diagonal, width 2: the cross-section is 2 sqrt 2 = 2.83 pixels of each column, centred on
    // the diagonal: the centre pixel full and 0.91 of each neighbour.
    aa_wide(6, 6, (0, 0), (5, 5), 2)
        .assert_pattern(&["#9    ", "9#9   ", " 9#9  ", "  9#9 ", "   9#9", "    9#"]);
    // Slope 1/2, width 3: a cross-section of 3.35 pixels (1.68 each side of the centre) moving
    // half a pixel per column: 0.18 and 0.68 at its ends.
    aa_wide(5, 6, (0, 1), (4, 3), 3)
        .assert_pattern(&["#61  ", "###61", "#####", "16###", "  16#", "    1"]);
    // Clipped at every edge, never outside.
    aa_wide(4, 3, (-5, -2), (9, 5), 3).assert_pattern(&["##61", "####", "6###"]);
    // Width 0 draws nothing.
    aa_wide(4, 3, (0, 1), (3, 1), 0).assert_pattern(&["    ", "    ", "    "]);
}

#[test]
fn wide_aa_line_of_width_1_is_the_wu_line() {
    for (a, b) in [
        ((0, 0), (9, 3)),
        ((1, 7), (4, -2)),
        ((8, 8), (-3, 2)),
        ((2, 2), (2, 2)),
    ] {
        let mut wu = BlendMock::new(10, 8);
        draw_line_aa(
            &mut wu,
            Point::new(a.0, a.1),
            Point::new(b.0, b.1),
            Gray8::WHITE,
        )
        .unwrap();
        assert_eq!(aa_wide(10, 8, a, b, 1).alpha, wu.alpha, "{a:?} {b:?}");
    }
}

/// The f64 model of the wide line: per column (a step along the major axis) the ideal line's
/// cross-section on the minor axis, `width sqrt(A^2 + B^2) / A` long and centred on the line, and
/// each pixel's share of it.
fn aa_wide_reference(w: i32, h: i32, a: (i32, i32), b: (i32, i32), width: f64) -> Vec<f64> {
    let mut out = vec![0.0; (w * h) as usize];
    let (dx, dy) = (f64::from(b.0 - a.0), f64::from(b.1 - a.1));
    let major_x = dx.abs() >= dy.abs();
    let (m0, m1, n0, dm, dn) = if major_x {
        (a.0, b.0, f64::from(a.1), dx, dy)
    } else {
        (a.1, b.1, f64::from(a.0), dy, dx)
    };
    let half = if dm == 0.0 {
        width / 2.0
    } else {
        width * (dm * dm + dn * dn).sqrt() / (2.0 * dm.abs())
    };
    for m in m0.min(m1)..=m0.max(m1) {
        let c = if dm == 0.0 {
            n0
        } else {
            n0 + f64::from(m - m0) / dm * dn
        };
        for n in (c - half - 1.0).floor() as i32..=(c + half + 1.0).ceil() as i32 {
            let cover = ((f64::from(n) + 0.5).min(c + half) - (f64::from(n) - 0.5).max(c - half))
                .clamp(0.0, 1.0);
            let (x, y) = if major_x { (m, n) } else { (n, m) };
            if (0..w).contains(&x) && (0..h).contains(&y) {
                out[(y * w + x) as usize] += cover;
            }
        }
    }
    out
}

proptest! {
    #[test]
    fn wide_aa_line_coverage_is_within_half_a_step_of_f64(
        ax in -20..60i32, ay in -20..50i32, bx in -20..60i32, by in -20..50i32, width in 2..9u32,
    ) {
        let (w, h) = (40, 30);
        let mut buf = vec![0u8; (w * h) as usize];
        let mut fb = Framebuffer::<Gray8>::new(&mut buf, w as u32, h as u32).unwrap();
        let (a, b) = (Point::new(ax, ay), Point::new(bx, by));
        draw_line_aa_wide(&mut fb, a, b, width, Gray8::WHITE).unwrap();
        let want = aa_wide_reference(w, h, (ax, ay), (bx, by), f64::from(width));
        for (i, (&got, &f)) in buf.iter().zip(&want).enumerate() {
            // Half a step of rounding, and the 16-bit fractions of the centre and half-width.
            prop_assert!((f64::from(got) - 255.0 * f).abs() <= 0.52,
                "pixel {} {}: {} vs {}", i as i32 % w, i as i32 / w, got, 255.0 * f);
        }
        // Symmetric.
        let mut rev = vec![0u8; (w * h) as usize];
        let mut fb = Framebuffer::<Gray8>::new(&mut rev, w as u32, h as u32).unwrap();
        draw_line_aa_wide(&mut fb, b, a, width, Gray8::WHITE).unwrap();
        prop_assert_eq!(rev, buf);
    }

    #[test]
    fn wide_aa_line_clips_exactly(
        ax in -30..70i32, ay in -30..60i32, bx in -30..70i32, by in -30..60i32, width in 2..12u32,
        cx in 0..40i32, cy in 0..30i32, cw in 0..40u32, ch in 0..30u32,
    ) {
        let (w, h) = (40u32, 30u32);
        let (a, b) = (Point::new(ax, ay), Point::new(bx, by));
        let mut whole = vec![0u8; (w * h) as usize];
        let mut fb = Framebuffer::<Gray8>::new(&mut whole, w, h).unwrap();
        draw_line_aa_wide(&mut fb, a, b, width, Gray8::WHITE).unwrap();
        let mut part = vec![0u8; (w * h) as usize];
        let mut fb = Framebuffer::<Gray8>::new(&mut part, w, h).unwrap();
        let area = Rectangle::new(Point::new(cx, cy), Size::new(cw, ch));
        draw_line_aa_wide(&mut ClipTo::new(&mut fb, area), a, b, width, Gray8::WHITE).unwrap();
        for y in 0..h as i32 {
            for x in 0..w as i32 {
                let i = (y * w as i32 + x) as usize;
                let inside = (cx..cx + cw as i32).contains(&x) && (cy..cy + ch as i32).contains(&y);
                prop_assert_eq!(part[i], if inside { whole[i] } else { 0 });
            }
        }
    }

    #[test]
    fn wide_aa_line_at_the_limits_stays_inside(
        ax in any::<i32>(), ay in any::<i32>(), bx in any::<i32>(), by in any::<i32>(),
        near in any::<bool>(), width in prop_oneof![2..40u32, any::<u32>()],
    ) {
        let a = if near { Point::new(ax.rem_euclid(16), ay.rem_euclid(12)) } else { Point::new(ax, ay) };
        let mut mock = BlendMock::new(16, 12);
        draw_line_aa_wide(&mut mock, a, Point::new(bx, by), width, Gray8::WHITE).unwrap();
    }
}

#[test]
fn wide_aa_line_without_read_back_is_refused() {
    let mut mock = StrictMock::<Rgb565>::new(8, 8);
    let mut t = AnyTarget::new(&mut mock);
    for width in [0, 1, 3] {
        assert_eq!(
            draw_line_aa_wide(
                &mut t,
                Point::new(0, 0),
                Point::new(7, 3),
                width,
                Rgb565::RED
            ),
            Err(BlendError::CannotReadBack)
        );
    }
    assert_eq!(mock.calls.pixels, 0);
}

#[test]
fn wide_aa_line_bands_equal_the_whole_frame() {
    let (w, h) = (64u32, 48u32);
    let scene = |s: &mut dyn FnMut(Point, Point, u32)| {
        for i in 0..10 {
            s(
                Point::new(2 + i * 6, -3),
                Point::new(60 - i * 4, 50),
                2 + i as u32 % 4,
            );
            s(
                Point::new(-4, i * 5),
                Point::new(70, 47 - i * 3),
                3 + i as u32 % 3,
            );
        }
    };
    let mut whole = vec![0u16; (w * h) as usize];
    {
        let mut fb = Framebuffer::<Rgb565>::new(&mut whole, w, h).unwrap();
        scene(&mut |a, b, width| draw_line_aa_wide(&mut fb, a, b, width, Rgb565::GREEN).unwrap());
    }
    for rows in [1u32, 5, 16] {
        let mut band_buf = vec![0u16; (w * rows) as usize];
        let mut y0 = 0;
        while y0 < h as i32 {
            let n = rows.min(h - y0 as u32);
            let fb = Framebuffer::<Rgb565>::new(&mut band_buf[..(w * n) as usize], w, n).unwrap();
            let mut band = Band::new(fb, y0);
            band.clear(Rgb565::BLACK).unwrap();
            scene(&mut |a, b, width| {
                draw_line_aa_wide(&mut band, a, b, width, Rgb565::GREEN).unwrap()
            });
            let start = (y0 as u32 * w) as usize;
            assert_eq!(
                band.framebuffer().as_slice(),
                &whole[start..start + (w * n) as usize],
                "{rows}-row band at {y0}"
            );
            y0 += n as i32;
        }
    }
}
