//! The framebuffer targets: construction errors, every pixel format, span fast paths against the
//! plain `draw_iter` path, and out-of-bounds input.

use proptest::prelude::*;
use rasterizer_core::prelude::*;
use rasterizer_core::surface::{FramebufferError, MAX_DIMENSION};

#[test]
fn wrong_length_is_a_typed_error() {
    let mut buf = [0u16; 10];
    assert_eq!(
        Framebuffer::<Rgb565>::new(&mut buf, 4, 3).unwrap_err(),
        FramebufferError::WrongLength {
            expected: 12,
            actual: 10
        }
    );
    let mut buf = [0u8; 3 * 4 * 3 + 1];
    assert_eq!(
        Framebuffer::<Rgb888>::new(&mut buf, 4, 3).unwrap_err(),
        FramebufferError::WrongLength {
            expected: 36,
            actual: 37
        }
    );
    let mut buf = [0u8; 6];
    // 9 pixels a row pack into 2 bytes; 3 rows need 6 bytes.
    assert!(Framebuffer::<BinaryColor>::new(&mut buf, 9, 3).is_ok());
    assert_eq!(
        Framebuffer::<BinaryColor>::new(&mut buf, 17, 3).unwrap_err(),
        FramebufferError::WrongLength {
            expected: 9,
            actual: 6
        }
    );
}

#[test]
fn bad_sizes_are_typed_errors() {
    let mut buf = [0u8; 0];
    assert_eq!(
        Framebuffer::<Gray8>::new(&mut buf, 0, 5).unwrap_err(),
        FramebufferError::BadSize {
            width: 0,
            height: 5
        }
    );
    assert_eq!(
        Framebuffer::<Gray8>::new(&mut buf, MAX_DIMENSION + 1, 1).unwrap_err(),
        FramebufferError::BadSize {
            width: MAX_DIMENSION + 1,
            height: 1
        }
    );
    assert_eq!(Framebuffer::<Gray8>::required_len(u32::MAX, u32::MAX), None);
    let msg = format!(
        "{}",
        FramebufferError::WrongLength {
            expected: 4,
            actual: 2
        }
    );
    assert!(msg.contains('4') && msg.contains('2'));
}

#[test]
fn rgb565_layout_is_raw_u16_row_major() {
    let mut buf = [0u16; 3 * 2];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 3, 2).unwrap();
    Pixel(Point::new(2, 1), Rgb565::RED).draw(&mut fb).unwrap();
    Pixel(Point::new(0, 0), Rgb565::BLUE).draw(&mut fb).unwrap();
    assert_eq!(buf, [0x001F, 0, 0, 0, 0, 0xF800]);
}

#[test]
fn rgb888_layout_is_three_bytes_red_first() {
    let mut buf = [0u8; 2 * 3];
    let mut fb = Framebuffer::<Rgb888>::new(&mut buf, 2, 1).unwrap();
    Pixel(Point::new(1, 0), Rgb888::new(1, 2, 3))
        .draw(&mut fb)
        .unwrap();
    assert_eq!(buf, [0, 0, 0, 1, 2, 3]);
}

#[test]
fn binary_layout_is_msb_first_rows_padded() {
    let mut buf = [0u8; 2 * 2];
    let mut fb = Framebuffer::<BinaryColor>::new(&mut buf, 10, 2).unwrap();
    Pixel(Point::new(0, 0), BinaryColor::On)
        .draw(&mut fb)
        .unwrap();
    Pixel(Point::new(9, 1), BinaryColor::On)
        .draw(&mut fb)
        .unwrap();
    Pixel(Point::new(10, 1), BinaryColor::On)
        .draw(&mut fb)
        .unwrap(); // outside: dropped
    assert_eq!(buf, [0x80, 0x00, 0x00, 0x40]);
}

#[test]
fn clear_and_out_of_bounds_are_dropped() {
    let mut buf = [0u8; 4 * 4];
    let mut fb = Framebuffer::<Gray8>::new(&mut buf, 4, 4).unwrap();
    fb.clear(Gray8::new(7)).unwrap();
    fb.fill_solid(
        &Rectangle::new(Point::new(-100, 2), Size::new(1000, 1000)),
        Gray8::new(9),
    )
    .unwrap();
    fb.fill_solid(
        &Rectangle::new(
            Point::new(i32::MAX, i32::MAX),
            Size::new(u32::MAX, u32::MAX),
        ),
        Gray8::WHITE,
    )
    .unwrap();
    fb.fill_contiguous(
        &Rectangle::new(Point::new(3, -1), Size::new(2, 2)),
        [1u8, 2, 3, 4].map(Gray8::new),
    )
    .unwrap();
    Pixel(Point::new(i32::MIN, 0), Gray8::WHITE)
        .draw(&mut fb)
        .unwrap();
    let lumas: Vec<u8> = fb.as_slice().to_vec();
    assert_eq!(lumas, vec![7, 7, 7, 3, 7, 7, 7, 7, 9, 9, 9, 9, 9, 9, 9, 9]);
}

/// Runs the same drawing on two framebuffers of format `C`: one through the fast span methods and
/// one pixel by pixel through `draw_iter`, and compares every pixel.
fn spans_match_pixels<C: rasterizer_core::surface::Storage + PartialEq + core::fmt::Debug>(
    words: usize,
    w: u32,
    h: u32,
    spans: &[(i32, i32, u32)],
    color: C,
) where
    C::Word: Default + Clone + PartialEq + core::fmt::Debug,
{
    let mut a = vec![C::Word::default(); words];
    let mut b = vec![C::Word::default(); words];
    let mut c = vec![C::Word::default(); words];
    let mut d = vec![C::Word::default(); words];
    let mut fa = Framebuffer::<C>::new(&mut a, w, h).unwrap();
    let mut fb = Framebuffer::<C>::new(&mut b, w, h).unwrap();
    let mut fc = Framebuffer::<C>::new(&mut c, w, h).unwrap();
    let mut fd = Framebuffer::<C>::new(&mut d, w, h).unwrap();
    for &(x, y, len) in spans {
        fa.fill_span(x, y, len, color).unwrap();
        fb.draw_iter((x..x + len as i32).map(|x| Pixel(Point::new(x, y), color)))
            .unwrap();
        // The fills for short and for long spans test their cases in other orders.
        fc.fill_short_span_in_clip(x, y, len, color).unwrap();
        fd.fill_long_span_in_clip(x, y, len, color).unwrap();
    }
    assert_eq!(a, b);
    assert_eq!(c, b);
    assert_eq!(d, b);
}

/// Every span length a row of 300 can hold, from several starts, against pixel writes: each of
/// the fill's groups (4, 8, 32, 64 and 128 words) and its overlapping last group, with words
/// before and after the span left alone, by the fills for long and for short spans.
#[test]
fn long_spans_of_every_length_match_pixel_writes() {
    let w = 300u32;
    for x in [0i32, 1, 3, 7, 8, 13] {
        for len in 1..=(w - x as u32) {
            let spans = [(x, 1, len)];
            spans_match_pixels::<Rgb565>(w as usize * 3, w, 3, &spans, Rgb565::new(31, 0, 17));
            spans_match_pixels::<Gray8>(w as usize * 3, w, 3, &spans, Gray8::new(200));
        }
    }
}

proptest! {
    #[test]
    fn binary_spans_match_pixel_writes(spans in proptest::collection::vec((0i32..23, 0i32..5), 1..20), on in any::<bool>()) {
        // Each span from x to the end of a random length within the 23-pixel row.
        let spans: Vec<(i32, i32, u32)> = spans.into_iter().map(|(x, y)| (x, y, (23 - x) as u32 / 2 + 1)).collect();
        spans_match_pixels::<BinaryColor>(3 * 5, 23, 5, &spans, BinaryColor::from(on));
    }

    #[test]
    fn all_formats_spans_match_pixel_writes(x in 0i32..17, len in 1u32..5, y in 0i32..3, raw in any::<u32>()) {
        let len = len.min((17 - x) as u32);
        spans_match_pixels::<Rgb565>(17 * 3, 17, 3, &[(x, y, len)], Rgb565::new((raw & 31) as u8, (raw >> 5 & 63) as u8, (raw >> 11 & 31) as u8));
        spans_match_pixels::<Rgb888>(17 * 3 * 3, 17, 3, &[(x, y, len)], Rgb888::new(raw as u8, (raw >> 8) as u8, (raw >> 16) as u8));
        spans_match_pixels::<Gray8>(17 * 3, 17, 3, &[(x, y, len)], Gray8::new(raw as u8));
    }

    #[test]
    fn fill_solid_any_rectangle_stays_in_bounds(x in any::<i32>(), y in any::<i32>(), w in any::<u32>(), h in any::<u32>()) {
        let mut buf = [0u8; 2 * 7];
        let mut fb = Framebuffer::<BinaryColor>::new(&mut buf, 13, 7).unwrap();
        fb.fill_solid(&Rectangle::new(Point::new(x, y), Size::new(w, h)), BinaryColor::On).unwrap();
        // Padding bits past column 13 stay clear.
        for row in buf.chunks(2) {
            prop_assert_eq!(row[1] & 0x07, 0);
        }
    }
}

#[test]
fn pixel_read_back() {
    let mut buf = [0u8; 3];
    let mut fb = Framebuffer::<BinaryColor>::new(&mut buf, 3, 3).unwrap();
    Pixel(Point::new(1, 2), BinaryColor::On)
        .draw(&mut fb)
        .unwrap();
    assert_eq!(fb.pixel(Point::new(1, 2)), Some(BinaryColor::On));
    assert_eq!(fb.pixel(Point::new(0, 2)), Some(BinaryColor::Off));
    assert_eq!(fb.pixel(Point::new(3, 0)), None);
    let _ = Gray8::new(1).luma();
    let _ = Rgb888::RED.r();
}

#[test]
fn surface_methods_called_directly_clip_instead_of_panicking() {
    use rasterizer_core::geom::line::Line;
    let mut buf = [0u16; 8 * 4];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 8, 4).unwrap();
    // An unclipped line walk from far outside (drawn first: the spans below go over it).
    let far = Line::new(Point::new(-100, -50), Point::new(100, 52)).points();
    fb.draw_line_points(far, Rgb565::BLUE).unwrap();
    assert!((0..8).any(|x| fb.pixel(Point::new(x, 1)) == Some(Rgb565::BLUE)));
    // Spans partly or wholly outside, and lengths that overflow.
    fb.fill_span(-3, 1, 5, Rgb565::RED).unwrap();
    fb.fill_span(6, 2, u32::MAX, Rgb565::RED).unwrap();
    fb.fill_span(0, 9, 4, Rgb565::RED).unwrap();
    fb.fill_span(i32::MIN, i32::MAX, 3, Rgb565::RED).unwrap();
    let mut n = 0;
    fb.shade_span(-2, 3, 4, || {
        n += 1;
        Rgb565::GREEN
    })
    .unwrap();
    assert_eq!(n, 4, "every colour is taken, in order");
    let extreme = Line::new(Point::new(i32::MIN, 0), Point::new(i32::MAX, 3)).points();
    assert!(extreme.last_pixel().is_some());
    let red: Vec<(i32, i32)> = (0..4)
        .flat_map(|y| (0..8).map(move |x| (x, y)))
        .filter(|&(x, y)| fb.pixel(Point::new(x, y)) == Some(Rgb565::RED))
        .collect();
    assert_eq!(red, vec![(0, 1), (1, 1), (6, 2), (7, 2)]);
    assert_eq!(fb.pixel(Point::new(0, 3)), Some(Rgb565::GREEN));
    assert_eq!(fb.pixel(Point::new(1, 3)), Some(Rgb565::GREEN));
}

#[test]
fn fill_contiguous_with_a_huge_area_and_endless_colours_ends() {
    let mut buf = [0u8; 4 * 4];
    let mut fb = Framebuffer::<Gray8>::new(&mut buf, 4, 4).unwrap();
    let area = Rectangle::new(Point::new(0, 0), Size::new(4, u32::MAX));
    fb.fill_contiguous(&area, core::iter::repeat(Gray8::WHITE))
        .unwrap();
    assert!(fb.as_slice().iter().all(|&v| v == 255));
}

#[test]
fn fill_contiguous_with_zero_width_over_every_row_ends() {
    // An area of no columns over 2^32 rows (most of them above the buffer) used to walk each
    // row, which takes minutes. It must return at once, taking no colours.
    let (done, finished) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut buf = [0u8; 4 * 4];
        let mut fb = Framebuffer::<Gray8>::new(&mut buf, 4, 4).unwrap();
        let mut taken = 0;
        let colors = core::iter::repeat_with(|| {
            taken += 1;
            Gray8::WHITE
        });
        let area = Rectangle::new(Point::new(0, i32::MIN), Size::new(0, u32::MAX));
        fb.fill_contiguous(&area, colors).unwrap();
        let _ = done.send((taken, buf));
    });
    let (taken, buf) = finished
        .recv_timeout(std::time::Duration::from_secs(5))
        .expect("fill_contiguous of an empty area did not return");
    assert_eq!(taken, 0);
    assert_eq!(buf, [0; 16]);
}

/// The default pipeline of scene M1 for colour format `C`, over the depth buffer `z`.
fn m1_pipeline<C: rasterizer_core::color::ShadeColor>(
    z: &mut [u16],
) -> Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, GouraudLit<Fx16, C, 1>> {
    use fixtures::scenes::{HEIGHT, WIDTH};
    use fixtures::scenes3d::{lighting, transforms};
    let depth = DepthBuffer::new(z, WIDTH, HEIGHT, Compare::Less).unwrap();
    Pipeline::new(
        &transforms(),
        Viewport::new(WIDTH, HEIGHT),
        CullClockwise,
        depth,
        GouraudLit::new(lighting()),
    )
}

/// The M1 scene (Suzanne, Gouraud, depth buffer, back faces culled) drawn into a framebuffer of
/// format `C` (`words` long), and the same draw through the plain `DrawTarget` path
/// ([`AnyTarget`] over a mock): every pixel the same.
fn mesh_matches_the_plain_path<C>(words: usize)
where
    C: rasterizer_core::surface::Storage + rasterizer_core::color::ShadeColor + PartialEq,
    C::Word: Default,
{
    use fixtures::scenes::{HEIGHT, WIDTH};
    let loaded = fixtures::scenes3d::Scene::M1.load().expect("M1 loads");
    let mesh = loaded.mesh();
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let mut z = vec![u16::MAX; (WIDTH * HEIGHT) as usize];
    let mut buf = vec![C::Word::default(); words];
    let mut fb = Framebuffer::<C>::new(&mut buf, WIDTH, HEIGHT).unwrap();
    let stats = m1_pipeline::<C>(&mut z)
        .draw(&mut fb, &mesh, &mut scratch)
        .unwrap();
    assert!(stats.drawn > 500, "{stats:?}");
    let mut mock = tests::StrictMock::<C>::new(WIDTH, HEIGHT);
    mock.allow_overdraw = true;
    z.fill(u16::MAX);
    m1_pipeline::<C>(&mut z)
        .draw(&mut AnyTarget::new(&mut mock), &mesh, &mut scratch)
        .unwrap();
    let mut drawn = 0;
    for y in 0..HEIGHT as i32 {
        for x in 0..WIDTH as i32 {
            let ours = fb.pixel(Point::new(x, y));
            match mock.get(x, y) {
                Some(c) => {
                    drawn += 1;
                    assert!(ours == Some(c), "pixel ({x}, {y})");
                }
                None => assert!(ours == Some(C::from_shade([0, 0, 0])), "pixel ({x}, {y})"),
            }
        }
    }
    // Suzanne covers 14,773 pixels of the frame.
    assert!(drawn > 14_000, "{drawn} pixels");
}

#[test]
fn mesh_into_every_format_matches_the_plain_path() {
    use fixtures::scenes::{HEIGHT, WIDTH};
    let n = (WIDTH * HEIGHT) as usize;
    mesh_matches_the_plain_path::<Rgb565>(n);
    mesh_matches_the_plain_path::<Rgb888>(3 * n);
    mesh_matches_the_plain_path::<Gray8>(n);
    mesh_matches_the_plain_path::<BinaryColor>(WIDTH.div_ceil(8) as usize * HEIGHT as usize);
}
