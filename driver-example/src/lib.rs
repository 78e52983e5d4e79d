//! A display driver example to copy into firmware: scenes rendered in 16-row bands and streamed
//! band by band to an ST7789 (240x240) or ILI9341 (320x240) through the [`mipidsi`] driver and
//! its SPI interface.
//!
//! - The M1 scene (Suzanne, Gouraud lighting, a depth buffer, back faces culled) through
//!   [`Pipeline::draw_banded`] and one band buffer: [`stream_m1`].
//! - Workload S1, a whole firmware screen (two meshes, a translucent panel, anti-aliased bars,
//!   text, a Gouraud triangle) through the frame list ([`rasterizer_core::frame`]) and two band
//!   buffers, one drawn into while the other is sent ([`s1::DisplaySender`]); after the first
//!   frame only the rectangles that changed are sent ([`s1::S1Screen`]).
//!
//! Each finished band goes out as one address window (CASET/RASET), one memory write (RAMWR)
//! and the band's pixels in one [`Display::set_pixels`] call: never a window per pixel, which
//! would cost eleven command and parameter bytes for every two bytes of colour.
//!
//! Everything here is `no_std` without an allocator, generic over the display's interface,
//! model and reset pin, so the same code drives the SPI peripheral of any embedded-hal 1.0 HAL.
//! `tests/stream.rs` (M1) and `tests/s1.rs` (S1) drive it on the host over a recording SPI
//! device and decode the bytes back into a picture.
//!
//! # RAM
//!
//! ## M1
//!
//! Everything an M1 frame needs besides the mesh (which stays in flash) is in [`BandBuffers`];
//! at 240 pixels a row ([`St7789Buffers`]) that is [`ST7789_RAM_BYTES`] = 25,520 bytes:
//!
//! | what | size |
//! |---|---:|
//! | colour band: 240 x 16 Rgb565 (`u16`) | 7,680 B |
//! | depth band: 240 x 16 `u16` | 7,680 B |
//! | bins: [`BINS`] [`BinEntry`] of 2 bytes | 2,048 B |
//! | vertex scratch: [`VERTICES`] [`VertexSlot`] of 16 bytes | 8,112 B |
//!
//! At 320 pixels a row ([`Ili9341Buffers`]) both bands grow to 10,240 bytes:
//! [`ILI9341_RAM_BYTES`] = 30,640 bytes. On top of that come the SPI interface's byte buffer
//! (its size is the firmware's choice: [`mipidsi::interface::SpiInterface::new`] takes it; 512
//! bytes in the test), one more band buffer of 7,680 bytes (10,240 at 320 wide) for the
//! double-buffered DMA variant described at [`send_band`], and the stack of the render call
//! (measured for the banded M1 draw in the project's `docs/MEMORY.md`).
//!
//! ## S1
//!
//! An S1 frame (320 x 240) works in [`s1::S1Buffers`]: [`s1::S1_RAM_BYTES`] = 41,000 bytes.
//!
//! | what | size |
//! |---|---:|
//! | two colour bands: 2 x 320 x 16 Rgb565 | 20,480 B |
//! | depth band, shared by both meshes: 320 x 16 `u16` | 10,240 B |
//! | Suzanne's bins: [`BINS`] of 2 bytes | 2,048 B |
//! | Suzanne's vertex scratch: [`VERTICES`] of 16 bytes | 8,112 B |
//! | the cube's bins: [`s1::CUBE_BINS`] of 2 bytes | 24 B |
//! | the cube's vertex scratch: [`s1::CUBE_VERTICES`] of 12 bytes | 96 B |
//!
//! The list itself lives on the stack for the frame: [`s1::S1_COMMANDS`] slots
//! ([`rasterizer_core::frame::Slot`]), the two mesh commands (pipeline, matrices and lighting)
//! and the two labels; [`s1::S1Screen`] keeps the shown frame's summaries between frames
//! (19 x 24 bytes). Their sizes on the host are printed by `tests/s1.rs`
//! (`cargo test --test s1 -- --nocapture`); they are smaller with a microcontroller's 32-bit
//! pointers. The fonts, like the meshes, stay in flash. The unit tests check these figures
//! against `core::mem::size_of`.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

use embedded_graphics_core::geometry::OriginDimensions;
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_hal::digital::OutputPin;
use fixtures::scenes3d;
use mipidsi::interface::{Interface, InterfacePixelFormat};
use mipidsi::models::Model;
use mipidsi::Display;
use rasterizer_core::cull::Cull;
use rasterizer_core::depth::DepthTest;
use rasterizer_core::frame::FrameError;
use rasterizer_core::math::Scalar;
use rasterizer_core::mesh::{MeshError, MeshSource};
use rasterizer_core::numerics::Numerics;
use rasterizer_core::pipeline::{BandError, RenderStats};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::Shading;
use rasterizer_core::surface::Band;

pub mod s1;

/// The converted Suzanne (`host-tools convert assets/models/suzanne.obj`), read in place from
/// flash.
pub static SUZANNE: &[u8] = include_bytes!("../../assets/meshes/suzanne.rmsh");

/// Rows per band: 16 rows of a 240-pixel display are 7,680 bytes of colour.
pub const BAND_ROWS: u32 = 16;
/// Suzanne's vertices: one scratch slot each, so that every vertex is transformed and lit once a
/// frame however many bands use it (a shorter scratch draws the same pixels, only slower).
pub const VERTICES: usize = 507;
/// Bins for the visible triangles (at most one each, Suzanne has 968; see [`BinEntry`]).
pub const BINS: usize = 1024;

/// The memory a banded frame works in, for bands of `PIXELS` pixels (`width * BAND_ROWS`).
///
/// Put it in a `static` (through `static_cell` or `cortex_m::singleton!`, so that it is not on
/// the stack): [`BandBuffers::new`] is `const`, and all of it is zeros, so it lies in `.bss`
/// and costs no flash.
#[derive(Debug)]
pub struct BandBuffers<const PIXELS: usize> {
    /// The band's colours, row-major, cleared and reused for every band.
    pub band: [u16; PIXELS],
    /// The band's depths.
    pub depth: [u16; PIXELS],
    /// One entry per visible triangle: the bands it touches.
    pub bins: [BinEntry; BINS],
    /// One transformed and lit vertex per mesh vertex.
    pub scratch: [VertexSlot; VERTICES],
}

impl<const PIXELS: usize> BandBuffers<PIXELS> {
    /// Zeroed buffers (each draw clears what it uses).
    pub const fn new() -> Self {
        Self {
            band: [0; PIXELS],
            depth: [0; PIXELS],
            bins: [BinEntry::ZERO; BINS],
            scratch: [VertexSlot::EMPTY; VERTICES],
        }
    }
}

impl<const PIXELS: usize> Default for BandBuffers<PIXELS> {
    fn default() -> Self {
        Self::new()
    }
}

/// Buffers for a 240-pixel-wide display (ST7789 240x240).
pub type St7789Buffers = BandBuffers<{ 240 * BAND_ROWS as usize }>;
/// Buffers for a 320-pixel-wide display (ILI9341 320x240 in landscape).
pub type Ili9341Buffers = BandBuffers<{ 320 * BAND_ROWS as usize }>;

/// RAM of [`St7789Buffers`], in bytes.
pub const ST7789_RAM_BYTES: usize = core::mem::size_of::<St7789Buffers>();
/// RAM of [`Ili9341Buffers`], in bytes.
pub const ILI9341_RAM_BYTES: usize = core::mem::size_of::<Ili9341Buffers>();

/// Why a streamed frame stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StreamError<E> {
    /// The embedded mesh did not parse.
    Mesh(MeshError),
    /// The band buffers hold fewer pixels than one band of the display needs.
    BuffersTooSmall {
        /// Pixels one band needs (`width * BAND_ROWS`).
        needed: usize,
        /// Pixels [`BandBuffers`] holds.
        actual: usize,
    },
    /// The banded draw could not start.
    Band(BandError),
    /// A band lies beyond the 16-bit coordinates of the display controller.
    OffScreen,
    /// The display interface failed; the bands after the failing one were rendered but not sent
    /// (M1), or the frame stopped there (S1).
    Display(E),
    /// The display's size is not the scene's.
    ScreenSize {
        /// The scene's.
        expected: Size,
        /// The display's.
        actual: Size,
    },
    /// The frame list refused a command or its buffers ([`s1::S1Screen::stream`]).
    Frame(FrameError),
}

/// The M1 benchmark scene for a `width` x `height` screen, as the benchmarks define it
/// (`fixtures::scenes3d`): Suzanne turned 30 degrees about Y, the camera at (0, 0, 3) looking at
/// the origin, a 60 degree vertical field of view, near 0.1, far 100, one white directional light
/// from (1, 1, 1).
///
/// The aspect ratio follows the screen (1:1 on a 240x240 ST7789), as the project's host tools
/// do for other frame sizes, so that Suzanne is not stretched.
pub fn m1_scene(width: u32, height: u32) -> (Transforms<Fx16>, Lighting<Fx16, 1>) {
    let model = Mat4::rotation_y(Angle::from_degrees(scenes3d::ROTATION_Y_DEGREES));
    (scenes3d::camera(model, width, height), scenes3d::lighting())
}

/// Sends one finished band to the display: one address window covering the band's rows, one
/// RAMWR, and the band's pixels in one [`Display::set_pixels`] call (mipidsi converts them to
/// big-endian bytes and hands them to the SPI device in chunks of its interface buffer).
///
/// # DMA
///
/// This call blocks until the last byte is out, so rendering waits for the wire. With DMA,
/// keep a second band buffer (7,680 bytes at 240 wide): here, first wait until the transfer of
/// the previous band has finished, then copy `band` into the second buffer (swapping each
/// pixel's bytes into big-endian order, or leave them and run the SPI in 16-bit frames), send
/// CASET/RASET/RAMWR (`set_pixels` with an empty iterator sends just those and leaves DC high
/// for data), start the DMA of the second buffer on the same SPI bus and return at once. The
/// banded draw then renders band N+1 into `band` while band N is on the wire: that is the
/// overlap. The copy is needed because [`Pipeline::draw_banded`] reuses one band buffer; the
/// wait before it keeps the copy and the next commands from cutting into pixels still being
/// sent.
///
/// # Errors
/// The interface's error, or [`StreamError::OffScreen`] when the band's rows do not fit the
/// controller's 16-bit coordinates.
pub fn send_band<DI, MODEL, RST>(
    display: &mut Display<DI, MODEL, RST>,
    band: &Band<'_, Rgb565>,
) -> Result<(), StreamError<DI::Error>>
where
    DI: Interface,
    MODEL: Model<ColorFormat = Rgb565>,
    Rgb565: InterfacePixelFormat<DI::Word>,
    RST: OutputPin,
{
    let fb = band.framebuffer();
    let (width, rows) = (fb.width(), fb.height());
    if width == 0 || rows == 0 {
        return Ok(());
    }
    // The window's last column and row are inclusive.
    let to_u16 = |v: i64| u16::try_from(v).map_err(|_| StreamError::OffScreen);
    let y0 = i64::from(band.y0());
    let (sx, sy) = (0, to_u16(y0)?);
    let (ex, ey) = (
        to_u16(i64::from(width) - 1)?,
        to_u16(y0 + i64::from(rows) - 1)?,
    );
    let pixels = fb
        .as_slice()
        .iter()
        .map(|&raw| Rgb565::from(RawU16::new(raw)));
    display
        .set_pixels(sx, sy, ex, ey, pixels)
        .map_err(StreamError::Display)
}

/// Draws `mesh` through any pipeline whose shader yields [`Rgb565`] in bands and streams each
/// finished band with [`send_band`].
///
/// The pipeline's depth stage must hold one band (`banding.width` x `banding.rows`), as
/// [`Pipeline::draw_banded`] asks. After a display error the remaining bands are still rendered
/// (the banded draw cannot be stopped from its band callback) but nothing more is sent, and the
/// first error is returned.
///
/// # Errors
/// [`StreamError::Band`] when the draw cannot start (nothing is sent then), else the first
/// error of [`send_band`].
pub fn draw_banded_to_display<S, C, D, Sh, const BITS: u32, N, M, DI, MODEL, RST>(
    pipeline: &mut Pipeline<S, C, D, Sh, BITS, N>,
    mesh: &M,
    banding: &Banding<Rgb565>,
    band: &mut [u16],
    bins: &mut [BinEntry],
    scratch: &mut [VertexSlot<Sh::Stored>],
    display: &mut Display<DI, MODEL, RST>,
) -> Result<RenderStats, StreamError<DI::Error>>
where
    S: Scalar,
    C: Cull,
    D: DepthTest,
    Sh: Shading<S, Color = Rgb565>,
    N: Numerics,
    M: MeshSource<S>,
    DI: Interface,
    MODEL: Model<ColorFormat = Rgb565>,
    Rgb565: InterfacePixelFormat<DI::Word>,
    RST: OutputPin,
{
    let mut failed = None;
    let stats = pipeline
        .draw_banded(mesh, banding, band, bins, scratch, |b| {
            if failed.is_none() {
                // Band N goes out here, before band N+1 is rendered into the same buffer (see
                // `send_band` for the DMA variant, where the two overlap).
                failed = send_band(display, b).err();
            }
        })
        .map_err(StreamError::Band)?;
    match failed {
        Some(e) => Err(e),
        None => Ok(stats),
    }
}

/// Renders the M1 scene at the display's size in [`BAND_ROWS`]-row bands and streams it to
/// `display`, one address window and one `set_pixels` call per band.
///
/// `display` must be initialised ([`mipidsi::Builder::init`]) with its size set to the screen
/// (`.display_size(240, 240)` for a 240x240 ST7789, whose controller holds 240x320).
///
/// # Errors
/// [`StreamError`]: buffers narrower than a band of the display, a mesh or banding error, or
/// the display's first error.
pub fn stream_m1<DI, MODEL, RST, const PIXELS: usize>(
    display: &mut Display<DI, MODEL, RST>,
    buffers: &mut BandBuffers<PIXELS>,
) -> Result<RenderStats, StreamError<DI::Error>>
where
    DI: Interface,
    MODEL: Model<ColorFormat = Rgb565>,
    Rgb565: InterfacePixelFormat<DI::Word>,
    RST: OutputPin,
{
    let mesh = PackedMesh::parse(SUZANNE).map_err(StreamError::Mesh)?;
    let Size { width, height } = display.size();
    let needed = width as usize * BAND_ROWS as usize;
    let too_small = || StreamError::BuffersTooSmall {
        needed,
        actual: PIXELS,
    };
    // The depth buffer must be exactly one band; the colour band may be longer.
    let depth_band = buffers.depth.get_mut(..needed).ok_or_else(too_small)?;
    let depth =
        DepthBuffer::new(depth_band, width, BAND_ROWS, Compare::Less).map_err(|_| too_small())?;
    let (transforms, lighting) = m1_scene(width, height);
    let mut pipeline = Pipeline::new(
        &transforms,
        Viewport::new(width, height),
        CullClockwise,
        depth,
        GouraudLit::<Fx16, Rgb565, 1>::new(lighting),
    );
    let banding = Banding {
        width,
        height,
        rows: BAND_ROWS,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    draw_banded_to_display(
        &mut pipeline,
        &mesh,
        &banding,
        &mut buffers.band,
        &mut buffers.bins,
        &mut buffers.scratch,
        display,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::mem::size_of;

    /// The figures of the crate documentation's RAM table.
    #[test]
    fn ram_figures_hold() {
        assert_eq!(size_of::<BinEntry>(), 2);
        assert_eq!(size_of::<VertexSlot>(), 16);
        let band = 240 * BAND_ROWS as usize * size_of::<u16>();
        assert_eq!(band, 7_680);
        assert_eq!(BINS * size_of::<BinEntry>(), 2_048);
        assert_eq!(VERTICES * size_of::<VertexSlot>(), 8_112);
        assert_eq!(ST7789_RAM_BYTES, 2 * band + 2_048 + 8_112);
        assert_eq!(ST7789_RAM_BYTES, 25_520);
        assert_eq!(ILI9341_RAM_BYTES, 2 * 10_240 + 2_048 + 8_112);
        assert_eq!(ILI9341_RAM_BYTES, 30_640);
    }

    /// The scratch and bins are sized for the embedded mesh.
    #[test]
    fn buffers_fit_the_mesh() {
        let mesh = PackedMesh::parse(SUZANNE).unwrap();
        assert_eq!(MeshSource::<Fx16>::vertex_count(&mesh), VERTICES);
        assert!(MeshSource::<Fx16>::triangle_count(&mesh) <= BINS);
    }
}
