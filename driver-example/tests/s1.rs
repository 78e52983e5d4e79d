//! Workload S1 streamed through the frame list and the double-buffered [`DisplaySender`],
//! decoded from the bytes on the SPI wire (`wire`): the first frame is the whole S1 frame drawn
//! directly, and after Suzanne turns from 30 to 35 degrees the region redraw leaves the display
//! showing the next frame, having sent only the rectangle that changed.

mod wire;

use driver_example::s1::{
    DisplaySender, S1Buffers, S1Screen, CUBE_VERTICES, S1_BAND_PIXELS, S1_COMMANDS, S1_HEIGHT,
    S1_WIDTH,
};
use driver_example::{StreamError, BAND_ROWS, SUZANNE, VERTICES};
use embedded_graphics_core::Drawable;
use embedded_hal::spi::ErrorKind;
use embedded_hal_mock::eh1::delay::NoopDelay;
use fixtures::s1;
use mipidsi::interface::{SpiError, SpiInterface};
use mipidsi::models::{ILI9341Rgb565, ST7789};
use mipidsi::options::{Orientation, Rotation};
use mipidsi::{Builder, Display};
use rasterizer_core::frame::{DoubleBuffer, Shape, Slot, Summary};
use rasterizer_core::prelude::*;
use wire::{decode, Decoded, Log, RecordingDc, RecordingSpi, Window, MADCTL};

const W: usize = S1_WIDTH as usize;
const H: usize = S1_HEIGHT as usize;

type Ili9341<'b> =
    Display<SpiInterface<'b, RecordingSpi, RecordingDc>, ILI9341Rgb565, mipidsi::NoResetPin>;

/// An ILI9341 in landscape (320 x 240) over a recording SPI device that fails from write
/// `fail_at` on.
fn ili9341<'b>(log: &Log, spi_buffer: &'b mut [u8], fail_at: Option<usize>) -> Ili9341<'b> {
    let spi = RecordingSpi {
        fail_at,
        ..RecordingSpi::new(log)
    };
    let interface = SpiInterface::new(spi, RecordingDc { log: log.clone() }, spi_buffer);
    let display = Builder::new(ILI9341Rgb565, interface)
        .orientation(Orientation::new().rotate(Rotation::Deg90))
        .init(&mut NoopDelay::new())
        .unwrap();
    assert_eq!(display.size(), Size::new(S1_WIDTH, S1_HEIGHT));
    display
}

/// Draws one of S1's shapes with the library function it stands for.
fn draw_shape(fb: &mut Framebuffer<'_, Rgb565>, shape: Shape<Rgb565>) {
    match shape {
        Shape::Triangle {
            vertices,
            color,
            opacity,
        } => fill_triangle_alpha(fb, vertices, color, opacity).unwrap(),
        Shape::LineAa { a, b, width, color } => {
            draw_line_aa_wide(fb, a, b, width, color).unwrap();
        }
        Shape::Gouraud {
            vertices,
            colors,
            opacity: 255,
        } => fill_triangle_gouraud(fb, vertices, colors).unwrap(),
        other => panic!("S1 has no {other:?}"),
    }
}

/// S1 with Suzanne turned `degrees`, drawn directly into one whole framebuffer and depth buffer
/// through the library's own calls, one after the other, with the meshes the driver streams:
/// the picture the display must show.
fn whole_frame(degrees: i32) -> Vec<u16> {
    let mut px = vec![0u16; W * H];
    let mut fb = Framebuffer::<Rgb565>::new(&mut px, S1_WIDTH, S1_HEIGHT).unwrap();
    fb.clear(s1::background()).unwrap();
    let mut z = vec![u16::MAX; W * H];
    let depth = DepthBuffer::new(&mut z, S1_WIDTH, S1_HEIGHT, Compare::Less).unwrap();
    let suzanne = PackedMesh::parse(SUZANNE).unwrap();
    let mut p = Pipeline::new(
        &s1::transforms(s1::suzanne_model(degrees)),
        s1::viewport(),
        CullClockwise,
        depth,
        GouraudLit::<Fx16, Rgb565, 1>::new(s1::suzanne_lighting()),
    );
    let stats = p
        .draw(&mut fb, &suzanne, &mut [VertexSlot::EMPTY; VERTICES])
        .unwrap();
    assert!(stats.drawn > 100, "{stats:?}");
    let mut p = Pipeline::new(
        &s1::transforms(s1::cube_model()),
        s1::viewport(),
        CullClockwise,
        p.depth,
        FlatLit::<Fx16, Rgb565, 1>::new(s1::cube_lighting()),
    );
    let stats = p
        .draw(
            &mut fb,
            &s1::cube_mesh(),
            &mut [VertexSlot::EMPTY; CUBE_VERTICES],
        )
        .unwrap();
    assert!(stats.drawn >= 3, "three faces of the cube: {stats:?}");
    for shape in s1::panel().into_iter().chain(s1::bars()) {
        draw_shape(&mut fb, shape);
    }
    for label in s1::labels() {
        label.draw(&mut fb).unwrap();
    }
    draw_shape(&mut fb, s1::gouraud());
    px
}

/// A pixel that differs: x, y, the reference's raw colour, the display's.
type Wrong = (usize, usize, u16, Option<u16>);

/// The pixels of `decoded` that are not `reference`'s: how many, and the first few.
fn wrong_pixels(decoded: &Decoded, reference: &[u16]) -> (usize, Vec<Wrong>) {
    let wrong: Vec<_> = reference
        .iter()
        .zip(&decoded.pixels)
        .enumerate()
        .filter(|(_, (want, got))| Some(**want) != **got)
        .map(|(i, (want, got))| (i % W, i / W, *want, *got))
        .collect();
    (wrong.len(), wrong.into_iter().take(8).collect())
}

#[test]
fn s1_stream_equals_whole_frame() {
    let log = Log::default();
    let mut spi_buffer = [0u8; 512];
    let mut display = ili9341(&log, &mut spi_buffer, None);
    let init_events = log.borrow().len();
    let mut buffers = Box::new(S1Buffers::new());
    let mut screen = S1Screen::new();
    let redraw = screen
        .stream(&mut display, &mut buffers, s1::SUZANNE_DEGREES)
        .unwrap();
    let whole = Rectangle::new(Point::zero(), Size::new(S1_WIDTH, S1_HEIGHT));
    assert_eq!(redraw.areas(), [whole]);
    assert_eq!(redraw.pixels(), S1_WIDTH * S1_HEIGHT);

    let decoded = decode(&log.borrow(), W, H);
    // Landscape: MADCTL exchanges rows and columns, so CASET/RASET address the picture as seen.
    let madctl = decoded.params(MADCTL);
    assert!(madctl.len() == 1 && madctl[0][0] & 0x20 != 0, "{madctl:?}");
    // One full-width window per 16-row band, top to bottom, every pixel once.
    let bands = S1_HEIGHT.div_ceil(BAND_ROWS);
    assert_eq!(redraw.windows(), bands);
    let windows: Vec<Window> = (0..bands as u16)
        .map(|b| Window {
            x0: 0,
            x1: S1_WIDTH as u16 - 1,
            y0: b * BAND_ROWS as u16,
            y1: (b + 1) * BAND_ROWS as u16 - 1,
        })
        .collect();
    assert_eq!(decoded.ramwr_windows, windows);
    assert_eq!(decoded.stray, 0);
    assert!(decoded.writes.iter().all(|&n| n == 1), "each pixel once");
    let reference = whole_frame(s1::SUZANNE_DEGREES);
    assert_eq!(wrong_pixels(&decoded, &reference), (0, vec![]));
    // The picture has S1's parts: many shades (Suzanne, the cube, the blended panel).
    let shades: std::collections::HashSet<_> = reference.iter().collect();
    assert!(shades.len() > 200, "{} colours", shades.len());
    // After init, only band traffic: a window and a memory write per band.
    let frame = decode(&log.borrow()[init_events..], W, H);
    assert_eq!(frame.commands.len(), 2 * bands as usize, "CASET and RASET");
}

#[test]
fn s1_region_redraw_shows_the_next_frame() {
    let log = Log::default();
    let mut spi_buffer = [0u8; 512];
    let mut display = ili9341(&log, &mut spi_buffer, None);
    let mut buffers = Box::new(S1Buffers::new());
    let mut screen = S1Screen::new();
    screen
        .stream(&mut display, &mut buffers, s1::SUZANNE_DEGREES)
        .unwrap();
    let first_frame = log.borrow().len();

    // Suzanne turns 30 -> 35 degrees; everything else is as it was.
    let redraw = screen
        .stream(&mut display, &mut buffers, s1::SUZANNE_DEGREES_NEXT)
        .unwrap();
    let [region] = redraw.areas() else {
        panic!("one rectangle: {:?}", redraw.areas());
    };
    let (before, after) = (
        whole_frame(s1::SUZANNE_DEGREES),
        whole_frame(s1::SUZANNE_DEGREES_NEXT),
    );
    // The region holds every pixel that changed, and is far smaller than the screen.
    for (i, _) in before
        .iter()
        .zip(&after)
        .enumerate()
        .filter(|(_, (a, b))| a != b)
    {
        let p = Point::new((i % W) as i32, (i / W) as i32);
        assert!(region.contains(p), "{p} changed outside {region:?}");
    }
    assert_ne!(before, after);
    let pixels = region.size.width * region.size.height;
    assert_eq!(redraw.pixels(), pixels);
    assert!(
        pixels > 10_000 && pixels < S1_WIDTH * S1_HEIGHT / 2,
        "{region:?}"
    );

    // The display, all bytes since init replayed, shows the next frame.
    let shown = decode(&log.borrow(), W, H);
    assert_eq!(wrong_pixels(&shown, &after), (0, vec![]));
    // The second frame sent the region's pixels once each, nothing outside it, one window for
    // each band the region crosses.
    let second = decode(&log.borrow()[first_frame..], W, H);
    assert_eq!(second.stray, 0);
    for (i, &n) in second.writes.iter().enumerate() {
        let p = Point::new((i % W) as i32, (i / W) as i32);
        assert_eq!(n, u32::from(region.contains(p)), "{p} written {n} times");
    }
    let (top, bottom) = (
        region.top_left.y as u32,
        region.bottom_right().unwrap().y as u32,
    );
    let bands = bottom / BAND_ROWS - top / BAND_ROWS + 1;
    assert_eq!(second.ramwr_windows.len(), bands as usize);
    assert_eq!(redraw.windows(), bands);
    assert!(second.ramwr_windows.iter().all(|w| {
        (i32::from(w.x0), i32::from(w.x1)) == (region.top_left.x, region.bottom_right().unwrap().x)
    }));

    // Nothing changed: nothing sent.
    let sent = log.borrow().len();
    let redraw = screen
        .stream(&mut display, &mut buffers, s1::SUZANNE_DEGREES_NEXT)
        .unwrap();
    assert!(redraw.areas().is_empty() && redraw.windows() == 0);
    assert_eq!(log.borrow().len(), sent);
}

#[test]
fn after_a_display_error_the_next_frame_is_sent_whole() {
    let log = Log::default();
    let mut spi_buffer = [0u8; 512];
    // Fail within the first band's pixels: init takes 16 writes, the band's CASET, RASET and
    // RAMWR 6 more, and its 10,240 pixel bytes go in 20 chunks of 512: fail at the 19th.
    let mut failing = ili9341(&log, &mut spi_buffer, Some(40));
    let mut buffers = Box::new(S1Buffers::new());
    let mut screen = S1Screen::new();
    let result = screen.stream(&mut failing, &mut buffers, s1::SUZANNE_DEGREES);
    assert!(
        matches!(
            result,
            Err(StreamError::Display(SpiError::Spi(ErrorKind::Other)))
        ),
        "{result:?}"
    );
    assert_eq!(decode(&log.borrow(), W, H).ramwr_windows.len(), 1);
    // The display shows part of the frame: the next one is sent whole, though only Suzanne
    // turned.
    let log = Log::default();
    let mut spi_buffer = [0u8; 512];
    let mut display = ili9341(&log, &mut spi_buffer, None);
    let redraw = screen
        .stream(&mut display, &mut buffers, s1::SUZANNE_DEGREES_NEXT)
        .unwrap();
    assert_eq!(redraw.pixels(), S1_WIDTH * S1_HEIGHT);
    let decoded = decode(&log.borrow(), W, H);
    let after = whole_frame(s1::SUZANNE_DEGREES_NEXT);
    assert_eq!(wrong_pixels(&decoded, &after), (0, vec![]));
}

#[test]
fn s1_on_a_display_of_another_size_is_refused() {
    let log = Log::default();
    let mut spi_buffer = [0u8; 64];
    let interface = SpiInterface::new(
        RecordingSpi::new(&log),
        RecordingDc { log: log.clone() },
        &mut spi_buffer,
    );
    let mut display = Builder::new(ST7789, interface)
        .display_size(240, 240)
        .init(&mut NoopDelay::new())
        .unwrap();
    let sent = log.borrow().len();
    let mut buffers = Box::new(S1Buffers::new());
    let result = S1Screen::new().stream(&mut display, &mut buffers, 30);
    assert!(
        matches!(
            result,
            Err(StreamError::ScreenSize { expected, actual })
                if expected == Size::new(320, 240) && actual == Size::new(240, 240)
        ),
        "{result:?}"
    );
    assert_eq!(log.borrow().len(), sent, "nothing sent");
}

#[test]
fn sender_sends_only_the_area_of_its_buffer() {
    // A band of rows 16..32 whose buffer 1 holds its row index in every pixel; the area is
    // columns 5..8 of rows 20..22: three pixels a row, from the right rows.
    let log = Log::default();
    let mut spi_buffer = [0u8; 64];
    let mut display = ili9341(&log, &mut spi_buffer, None);
    let sent = log.borrow().len();
    let (mut a, mut b) = (vec![0u16; S1_BAND_PIXELS], vec![0u16; S1_BAND_PIXELS]);
    let mut sender = DisplaySender::new(&mut display, [&mut a, &mut b]);
    for (i, p) in sender.buffer(1).iter_mut().enumerate() {
        *p = (i / W) as u16 + 1;
    }
    let rows = Rectangle::new(Point::new(0, 16), Size::new(S1_WIDTH, BAND_ROWS));
    let area = Rectangle::new(Point::new(5, 20), Size::new(3, 2));
    sender.start(1, rows, area).unwrap();
    sender.wait(1).unwrap();
    assert_eq!(sender.sent(), 1);
    let decoded = decode(&log.borrow()[sent..], W, H);
    assert_eq!(
        decoded.ramwr_windows,
        [Window {
            x0: 5,
            x1: 7,
            y0: 20,
            y1: 21
        }]
    );
    for (i, p) in decoded.pixels.iter().enumerate() {
        let (x, y) = (i % W, i / W);
        let inside = (5..8).contains(&x) && (20..22).contains(&y);
        // Screen row y is the band's row y - 16, which holds y - 16 + 1.
        assert_eq!(*p, inside.then(|| (y - 15) as u16), "({x}, {y})");
    }
    // An empty area sends nothing.
    let before = log.borrow().len();
    sender.start(0, rows, Rectangle::zero()).unwrap();
    assert_eq!(log.borrow().len(), before);
}

/// What a frame keeps on the stack and between frames, on this host (64-bit pointers), for
/// the crate documentation's RAM section: `cargo test --test s1 -- --nocapture`.
#[test]
fn s1_list_memory() {
    let slot = std::mem::size_of::<Slot<'static, Rgb565>>();
    let labels = std::mem::size_of_val(&s1::labels());
    let screen = std::mem::size_of::<S1Screen>();
    assert_eq!(std::mem::size_of::<Summary>(), 24);
    assert!(screen <= S1_COMMANDS * 24 + 8, "{screen}");
    println!(
        "S1 list on the stack: {S1_COMMANDS} slots of {slot} B = {} B, labels {labels} B; \
         S1Screen {screen} B between frames",
        S1_COMMANDS * slot
    );
}
