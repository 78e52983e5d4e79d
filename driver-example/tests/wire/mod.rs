//! The wire between the driver and the display, on the host: an SPI device and a DC pin that
//! record what is written, in one log, and a decoder that replays the log as a MIPI DCS
//! controller would, into the picture in its memory. Shared by the tests of each scene.
//!
//! The SPI device and DC pin are recorded by the small `Recording*` types rather than by
//! embedded-hal-mock: its mocks check a list of expected transactions given up front (hundreds of
//! writes and over 100,000 pixel bytes a frame here, which would have to be computed from the
//! very driver under test), and its SPI and pin mocks are separate objects, so they cannot tell
//! in which order DC changes and SPI writes happened, which is what says command from data. One
//! shared log keeps that order.

// Each test file uses part of this module.
#![allow(dead_code)]

use std::cell::RefCell;
use std::rc::Rc;

use embedded_hal::digital::{ErrorType as PinErrorType, OutputPin};
use embedded_hal::spi::{ErrorKind, ErrorType as SpiErrorType, Operation, SpiDevice};

/// MIPI DCS commands the decoder understands.
pub const SWRESET: u8 = 0x01;
pub const CASET: u8 = 0x2A;
pub const RASET: u8 = 0x2B;
pub const RAMWR: u8 = 0x2C;
pub const MADCTL: u8 = 0x36;
pub const COLMOD: u8 = 0x3A;

/// What happened on the wire, in order.
#[derive(Debug, Clone, PartialEq)]
pub enum Event {
    /// The DC pin was driven: high for data, low for a command.
    Dc(bool),
    /// Bytes written in one SPI transaction.
    Write(Vec<u8>),
}

/// The wire's events, shared by the SPI device and the DC pin.
pub type Log = Rc<RefCell<Vec<Event>>>;

/// An SPI device that records every byte written; fails every write from `fail_at` on.
pub struct RecordingSpi {
    /// Where the writes go.
    pub log: Log,
    /// Writes so far.
    pub writes: usize,
    /// The first write to fail, if any.
    pub fail_at: Option<usize>,
}

impl RecordingSpi {
    /// A device writing into `log` that never fails.
    pub fn new(log: &Log) -> Self {
        Self {
            log: log.clone(),
            writes: 0,
            fail_at: None,
        }
    }
}

impl SpiErrorType for RecordingSpi {
    type Error = ErrorKind;
}

impl SpiDevice for RecordingSpi {
    fn transaction(&mut self, operations: &mut [Operation<'_, u8>]) -> Result<(), ErrorKind> {
        for op in operations {
            match op {
                Operation::Write(bytes) => {
                    if self.fail_at.is_some_and(|n| self.writes >= n) {
                        return Err(ErrorKind::Other);
                    }
                    self.writes += 1;
                    self.log.borrow_mut().push(Event::Write(bytes.to_vec()));
                }
                Operation::DelayNs(_) => {}
                // The display is write-only over this interface.
                other => panic!("unexpected SPI operation {other:?}"),
            }
        }
        Ok(())
    }
}

/// A DC pin that records its level in the same log as the SPI writes.
pub struct RecordingDc {
    /// Where the levels go.
    pub log: Log,
}

impl PinErrorType for RecordingDc {
    type Error = core::convert::Infallible;
}

impl OutputPin for RecordingDc {
    fn set_low(&mut self) -> Result<(), Self::Error> {
        self.log.borrow_mut().push(Event::Dc(false));
        Ok(())
    }
    fn set_high(&mut self) -> Result<(), Self::Error> {
        self.log.borrow_mut().push(Event::Dc(true));
        Ok(())
    }
}

/// An address window, inclusive, as CASET and RASET set it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Window {
    pub x0: u16,
    pub x1: u16,
    pub y0: u16,
    pub y1: u16,
}

/// A display controller's view of the log: commands with their parameters, and the pixels
/// RAMWR put into memory (in the address space CASET/RASET name, before MADCTL's mapping to the
/// glass).
pub struct Decoded {
    /// Pixels a row.
    pub width: usize,
    /// Raw Rgb565 per pixel, row-major, `None` where nothing was written.
    pub pixels: Vec<Option<u16>>,
    /// How many times each pixel was written.
    pub writes: Vec<u32>,
    /// Every command but RAMWR with its parameters, in order.
    pub commands: Vec<(u8, Vec<u8>)>,
    /// The window of each RAMWR.
    pub ramwr_windows: Vec<Window>,
    /// Pixels sent past the end of their window, or outside the screen.
    pub stray: usize,
}

impl Decoded {
    /// The parameters of each `command` sent, in order.
    pub fn params(&self, command: u8) -> Vec<&[u8]> {
        let found = self.commands.iter().filter(|(c, _)| *c == command);
        found.map(|(_, p)| p.as_slice()).collect()
    }
}

/// A command still taking its parameters.
enum Current {
    None,
    Params(u8, Vec<u8>),
    /// RAMWR: the next pixel's place, and the high byte of a pixel split across writes.
    Memory {
        x: u16,
        y: u16,
        high: Option<u8>,
    },
}

/// Replays `log` on a `width` x `height` controller.
pub fn decode(log: &[Event], width: usize, height: usize) -> Decoded {
    let mut d = Decoded {
        width,
        pixels: vec![None; width * height],
        writes: vec![0; width * height],
        commands: Vec::new(),
        ramwr_windows: Vec::new(),
        stray: 0,
    };
    let mut dc = None;
    let mut window = Window {
        x0: 0,
        x1: 0,
        y0: 0,
        y1: 0,
    };
    let mut current = Current::None;
    // A command's parameters end where the next command starts (or the log ends).
    let finish = |current: &mut Current, window: &mut Window, d: &mut Decoded| {
        if let Current::Params(command, params) = std::mem::replace(current, Current::None) {
            let pair = |p: &[u8]| {
                assert_eq!(p.len(), 4, "CASET/RASET take 4 bytes");
                (
                    u16::from_be_bytes([p[0], p[1]]),
                    u16::from_be_bytes([p[2], p[3]]),
                )
            };
            match command {
                CASET => (window.x0, window.x1) = pair(&params),
                RASET => (window.y0, window.y1) = pair(&params),
                _ => {}
            }
            d.commands.push((command, params));
        }
    };
    for event in log {
        match event {
            Event::Dc(level) => dc = Some(*level),
            Event::Write(bytes) => match dc {
                None => panic!("SPI write before DC was driven"),
                Some(false) => {
                    for &command in bytes {
                        finish(&mut current, &mut window, &mut d);
                        current = if command == RAMWR {
                            d.ramwr_windows.push(window);
                            Current::Memory {
                                x: window.x0,
                                y: window.y0,
                                high: None,
                            }
                        } else {
                            Current::Params(command, Vec::new())
                        };
                    }
                }
                Some(true) => {
                    for &byte in bytes {
                        match &mut current {
                            Current::None => panic!("data byte {byte:#04x} with no command"),
                            Current::Params(_, params) => params.push(byte),
                            Current::Memory {
                                high: high @ None, ..
                            } => *high = Some(byte),
                            Current::Memory { x, y, high } => {
                                let raw = u16::from_be_bytes([high.take().unwrap_or(0), byte]);
                                let (px, py) = (usize::from(*x), usize::from(*y));
                                if *y > window.y1 || px >= width || py >= height {
                                    d.stray += 1;
                                } else {
                                    d.pixels[py * width + px] = Some(raw);
                                    d.writes[py * width + px] += 1;
                                }
                                // Row-major within the window, as the controller fills it.
                                if *x >= window.x1 {
                                    *x = window.x0;
                                    *y += 1;
                                } else {
                                    *x += 1;
                                }
                            }
                        }
                    }
                }
            },
        }
    }
    finish(&mut current, &mut window, &mut d);
    d
}
