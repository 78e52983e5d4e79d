//! The streamed M1 frame, decoded from the bytes on the SPI wire, equals the whole-frame render.
//!
//! The SPI device and DC pin are recorded by the `Recording*` types of `wire` (about 500 writes
//! and 115,200 pixel bytes a frame here, in one log that keeps DC changes and SPI writes in
//! order). embedded-hal-mock provides the reset pin (with the pulse it must see) and the
//! delay, and `band_on_the_wire` checks one small band's exact bytes against its SPI and pin
//! mocks, written by hand from the MIPI DCS.

mod wire;

use driver_example::{
    m1_scene, send_band, stream_m1, Ili9341Buffers, St7789Buffers, StreamError, BAND_ROWS, SUZANNE,
    VERTICES,
};
use embedded_graphics_core::pixelcolor::raw::{RawData, RawU16};
use embedded_hal::spi::ErrorKind;
use embedded_hal_mock::eh1::delay::NoopDelay;
use embedded_hal_mock::eh1::digital::{Mock as PinMock, State, Transaction as PinTransaction};
use embedded_hal_mock::eh1::spi::{Mock as SpiMock, Transaction as SpiTransaction};
use mipidsi::interface::SpiInterface;
use mipidsi::models::{ILI9341Rgb565, ST7789};
use mipidsi::options::{Orientation, Rotation};
use mipidsi::Builder;
use rasterizer_core::prelude::*;
use rasterizer_core::surface::Band;
use wire::{
    decode, Decoded, Log, RecordingDc, RecordingSpi, Window, CASET, COLMOD, MADCTL, RAMWR, RASET,
    SWRESET,
};

/// M1 drawn whole with `Pipeline::draw`: the picture the stream must reproduce.
fn whole_frame(width: u32, height: u32) -> Vec<u16> {
    let mesh = PackedMesh::parse(SUZANNE).unwrap();
    let (transforms, lighting) = m1_scene(width, height);
    let len = (width * height) as usize;
    let (mut colors, mut depths) = (vec![0u16; len], vec![u16::MAX; len]);
    let mut fb = Framebuffer::<Rgb565>::new(&mut colors, width, height).unwrap();
    fb.clear(Rgb565::BLACK).unwrap();
    let depth = DepthBuffer::new(&mut depths, width, height, Compare::Less).unwrap();
    let mut pipeline = Pipeline::new(
        &transforms,
        Viewport::new(width, height),
        CullClockwise,
        depth,
        GouraudLit::<Fx16, Rgb565, 1>::new(lighting),
    );
    let stats = pipeline
        .draw(&mut fb, &mesh, &mut [VertexSlot::EMPTY; VERTICES])
        .unwrap();
    assert!(stats.drawn > 100, "M1 draws most of Suzanne: {stats:?}");
    colors
}

/// Asserts the decoded picture is the reference, naming the first wrong pixels.
fn assert_same_picture(decoded: &Decoded, reference: &[u16]) {
    let wrong: Vec<_> = reference
        .iter()
        .zip(&decoded.pixels)
        .enumerate()
        .filter(|(_, (want, got))| Some(**want) != **got)
        .map(|(i, (want, got))| (i % decoded.width, i / decoded.width, *want, *got))
        .collect();
    assert!(
        wrong.is_empty(),
        "{} pixels differ from the whole frame; the first (x, y, want, got): {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(8)]
    );
    assert!(
        reference.iter().filter(|&&p| p != 0).count() > 1000,
        "the reference shows Suzanne"
    );
}

/// One window per band, each band's rows and full width, tiling the screen top to bottom.
fn assert_one_window_per_band(decoded: &Decoded, width: u16, height: u16) {
    let bands = height.div_ceil(BAND_ROWS as u16);
    assert_eq!(decoded.ramwr_windows.len(), usize::from(bands), "RAMWRs");
    assert_eq!(decoded.params(CASET).len(), usize::from(bands), "CASETs");
    assert_eq!(decoded.params(RASET).len(), usize::from(bands), "RASETs");
    for (b, w) in decoded.ramwr_windows.iter().enumerate() {
        let y0 = b as u16 * BAND_ROWS as u16;
        let y1 = (y0 + BAND_ROWS as u16).min(height) - 1;
        let band = Window {
            x0: 0,
            x1: width - 1,
            y0,
            y1,
        };
        assert_eq!(*w, band, "band {b}'s window");
    }
    assert_eq!(decoded.stray, 0, "pixels past a window's end or off screen");
    assert!(
        decoded.writes.iter().all(|&n| n == 1),
        "every pixel written exactly once"
    );
}

#[test]
fn st7789_stream_equals_whole_frame() {
    let log = Log::default();
    let spi = RecordingSpi {
        log: log.clone(),
        writes: 0,
        fail_at: None,
    };
    let dc = RecordingDc { log: log.clone() };
    let mut spi_buffer = [0u8; 512];
    let interface = SpiInterface::new(spi, dc, &mut spi_buffer);
    // The reset pin must see one low pulse and end high.
    let mut reset = PinMock::new(&[
        PinTransaction::set(State::Low),
        PinTransaction::set(State::High),
    ]);
    let mut display = Builder::new(ST7789, interface)
        .display_size(240, 240)
        .reset_pin(reset.clone())
        .init(&mut NoopDelay::new())
        .unwrap();
    reset.done();
    let init_events = log.borrow().len();

    let mut buffers = Box::new(St7789Buffers::new());
    let stats = stream_m1(&mut display, &mut buffers).unwrap();
    assert!(stats.drawn > 100, "{stats:?}");

    let decoded = decode(&log.borrow(), 240, 240);
    // The decoder maps CASET to x and RASET to y unmirrored: what MADCTL 0 means. 16-bit
    // pixels (COLMOD 0x55) are what it reads as two big-endian bytes each.
    assert_eq!(decoded.params(MADCTL), [[0x00]], "MADCTL");
    assert_eq!(decoded.params(COLMOD), [[0x55]], "COLMOD");
    assert!(
        decoded.params(SWRESET).is_empty(),
        "hardware reset, no SWRESET"
    );
    assert_one_window_per_band(&decoded, 240, 240);
    assert_same_picture(&decoded, &whole_frame(240, 240));
    // Only band traffic after init: window, RAMWR and pixels.
    let frame = decode(&log.borrow()[init_events..], 240, 240);
    let commands: Vec<u8> = frame.commands.iter().map(|(c, _)| *c).collect();
    assert_eq!(commands, [CASET, RASET].repeat(15));
}

#[test]
fn ili9341_landscape_stream_equals_whole_frame() {
    let log = Log::default();
    let spi = RecordingSpi {
        log: log.clone(),
        writes: 0,
        fail_at: None,
    };
    let mut spi_buffer = [0u8; 512];
    let interface = SpiInterface::new(spi, RecordingDc { log: log.clone() }, &mut spi_buffer);
    let mut display = Builder::new(ILI9341Rgb565, interface)
        .orientation(Orientation::new().rotate(Rotation::Deg90))
        .init(&mut NoopDelay::new())
        .unwrap();
    assert_eq!(display.size(), Size::new(320, 240));

    let mut buffers = Box::new(Ili9341Buffers::new());
    stream_m1(&mut display, &mut buffers).unwrap();

    let decoded = decode(&log.borrow(), 320, 240);
    // Landscape: MADCTL exchanges rows and columns (MV), so CASET/RASET address the picture as
    // seen, which is how the decoder reads them.
    let madctl = decoded.params(MADCTL);
    assert!(
        madctl.len() == 1 && madctl[0][0] & 0x20 != 0,
        "MADCTL {madctl:?}"
    );
    assert_one_window_per_band(&decoded, 320, 240);
    assert_same_picture(&decoded, &whole_frame(320, 240));
}

#[test]
fn buffers_narrower_than_the_display_are_refused() {
    let log = Log::default();
    let spi = RecordingSpi {
        log: log.clone(),
        writes: 0,
        fail_at: None,
    };
    let mut spi_buffer = [0u8; 64];
    let interface = SpiInterface::new(spi, RecordingDc { log: log.clone() }, &mut spi_buffer);
    let mut display = Builder::new(ILI9341Rgb565, interface)
        .orientation(Orientation::new().rotate(Rotation::Deg90))
        .init(&mut NoopDelay::new())
        .unwrap();
    let sent = log.borrow().len();
    let mut buffers = Box::new(St7789Buffers::new());
    let result = stream_m1(&mut display, &mut buffers);
    assert!(
        matches!(
            result,
            Err(StreamError::BuffersTooSmall {
                needed: 5120,
                actual: 3840,
            })
        ),
        "{result:?}"
    );
    assert_eq!(log.borrow().len(), sent, "nothing sent");
}

#[test]
fn display_error_stops_the_stream() {
    let log = Log::default();
    let spi = RecordingSpi {
        log: log.clone(),
        writes: 0,
        // Init takes 14 writes (7 commands, each a command byte and a parameter write), the
        // first band's CASET, RASET and RAMWR 6 more: fail at its fourth chunk of pixels.
        fail_at: Some(14 + 6 + 3),
    };
    let mut spi_buffer = [0u8; 512];
    let interface = SpiInterface::new(spi, RecordingDc { log: log.clone() }, &mut spi_buffer);
    let mut display = Builder::new(ST7789, interface)
        .display_size(240, 240)
        .init(&mut NoopDelay::new())
        .unwrap();
    let mut buffers = Box::new(St7789Buffers::new());
    let result = stream_m1(&mut display, &mut buffers);
    assert!(
        matches!(
            result,
            Err(StreamError::Display(mipidsi::interface::SpiError::Spi(
                ErrorKind::Other
            )))
        ),
        "{result:?}"
    );
    let decoded = decode(&log.borrow(), 240, 240);
    assert_eq!(
        decoded.ramwr_windows.len(),
        1,
        "no band after the failing one"
    );
}

/// One 3x2 band at row 16, checked byte by byte against the MIPI DCS with embedded-hal-mock's
/// SPI and pin mocks (each checks its own order; the recording test checks them together).
#[test]
fn band_on_the_wire() {
    let command = |c: u8, params: &[u8]| {
        [
            SpiTransaction::transaction_start(),
            SpiTransaction::write_vec(vec![c]),
            SpiTransaction::transaction_end(),
            SpiTransaction::transaction_start(),
            SpiTransaction::write_vec(params.to_vec()),
            SpiTransaction::transaction_end(),
        ]
    };
    let dc_per_command = [
        PinTransaction::set(State::Low),
        PinTransaction::set(State::High),
    ];
    // ST7789 init after a software reset, as mipidsi 0.10 sends it.
    let init: [(u8, &[u8]); 7] = [
        (SWRESET, &[]),
        (0x11, &[]),       // SLPOUT
        (MADCTL, &[0x00]), // default orientation, RGB order
        (0x20, &[]),       // INVOFF
        (COLMOD, &[0x55]), // 16 bits a pixel
        (0x13, &[]),       // NORON
        (0x29, &[]),       // DISPON
    ];
    let pixels = [
        Rgb565::RED,
        Rgb565::GREEN,
        Rgb565::BLUE,
        Rgb565::WHITE,
        Rgb565::new(1, 2, 3),
        Rgb565::BLACK,
    ];
    // x 0..=2, y 16..=17, then each pixel's two bytes, high first.
    let band_commands: [(u8, &[u8]); 3] = [
        (CASET, &[0, 0, 0, 2]),
        (RASET, &[0, 16, 0, 17]),
        (RAMWR, &[]),
    ];
    let mut wire: Vec<u8> = Vec::new();
    for p in pixels {
        wire.extend(RawU16::from(p).into_inner().to_be_bytes());
    }
    assert_eq!(&wire[..4], [0xF8, 0x00, 0x07, 0xE0], "red, green");

    let mut spi_expected = Vec::new();
    let mut dc_expected = Vec::new();
    for (c, params) in init.iter().chain(&band_commands) {
        spi_expected.extend(command(*c, params));
        dc_expected.extend(dc_per_command.clone());
    }
    spi_expected.extend([
        SpiTransaction::transaction_start(),
        SpiTransaction::write_vec(wire),
        SpiTransaction::transaction_end(),
    ]);
    let mut spi = SpiMock::new(&spi_expected);
    let mut dc = PinMock::new(&dc_expected);

    let mut spi_buffer = [0u8; 64];
    let interface = SpiInterface::new(spi.clone(), dc.clone(), &mut spi_buffer);
    let mut display = Builder::new(ST7789, interface)
        .display_size(240, 240)
        .init(&mut NoopDelay::new())
        .unwrap();
    let mut words = pixels.map(|p| RawU16::from(p).into_inner());
    let band = Band::new(Framebuffer::<Rgb565>::new(&mut words, 3, 2).unwrap(), 16);
    send_band(&mut display, &band).unwrap();
    spi.done();
    dc.done();
}
