//! Workload S1, a whole firmware screen (`fixtures::s1`: Suzanne and a cube sharing one depth
//! buffer, a translucent panel, twelve anti-aliased bars, two text labels, a Gouraud triangle),
//! built as a [`FrameList`] and streamed to a 320 x 240 display in [`BAND_ROWS`]-row bands,
//! double-buffered ([`FrameList::render_double`] through a [`DisplaySender`]).
//!
//! After the first frame, [`S1Screen::stream`] sends only what changed: it keeps the summaries
//! of the frame the display shows ([`FrameList::summaries`]) and redraws the rectangles
//! [`changed_areas`] finds between them and the new frame's (when Suzanne turns, the union of
//! her old and new bounds). The rest of the display keeps its pixels: nothing is sent there.
//!
//! The meshes are the ones firmware has without a file system: Suzanne's packed mesh
//! ([`crate::SUZANNE`], as the M1 stream draws her) and the cube's static slices
//! ([`fixtures::s1::cube_mesh`]).

use crate::{StreamError, BAND_ROWS, BINS, SUZANNE, VERTICES};
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::primitives::Rectangle;
use embedded_hal::digital::OutputPin;
use fixtures::s1;
use mipidsi::interface::{Interface, InterfacePixelFormat};
use mipidsi::models::Model;
use mipidsi::Display;
use rasterizer_core::depth::SharedDepth;
use rasterizer_core::frame::MeshCommand;
use rasterizer_core::frame::{
    changed_areas, Clear, DoubleBuffer, FrameList, Layout, RenderError, Slot, Summary,
};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::Shading;

/// S1's screen width.
pub const S1_WIDTH: u32 = s1::WIDTH;
/// S1's screen height.
pub const S1_HEIGHT: u32 = s1::HEIGHT;
/// Pixels of one band: 320 x 16, 10,240 bytes of Rgb565.
pub const S1_BAND_PIXELS: usize = S1_WIDTH as usize * BAND_ROWS as usize;
/// The cube's vertices: one scratch slot each.
pub const CUBE_VERTICES: usize = 8;
/// Bins for the cube's triangles (all 12 visible at worst).
pub const CUBE_BINS: usize = 12;
/// The commands of S1's list: two meshes, the panel's two triangles, twelve bars, two labels,
/// the Gouraud triangle.
pub const S1_COMMANDS: usize = 19;
/// Rectangles one frame may redraw; more changes are merged into the last
/// ([`changed_areas`]). S1's one change, Suzanne's turn, needs one.
pub const MAX_AREAS: usize = 4;

/// Suzanne's shading: Gouraud, one light.
type SuzanneShading = GouraudLit<Fx16, Rgb565, 1>;
/// The cube's shading: flat, one light.
type CubeShading = FlatLit<Fx16, Rgb565, 1>;
/// A vertex scratch slot of Suzanne's shading (16 bytes).
pub type SuzanneSlot = VertexSlot<<SuzanneShading as Shading<Fx16>>::Stored>;
/// A vertex scratch slot of the cube's shading (12 bytes: it keeps no colour per vertex).
pub type CubeSlot = VertexSlot<<CubeShading as Shading<Fx16>>::Stored>;

/// The memory an S1 frame works in, besides the meshes (in flash), the font (in flash) and the
/// list itself (on the stack, see the crate documentation's RAM table).
///
/// Put it in a `static`, as [`crate::BandBuffers`]: [`S1Buffers::new`] is `const` and all
/// zeros, so it lies in `.bss`.
#[derive(Debug)]
pub struct S1Buffers {
    /// The two band buffers [`FrameList::render_double`] alternates between: one is drawn into
    /// while the other is sent.
    pub bands: [[u16; S1_BAND_PIXELS]; 2],
    /// The depth of one band, shared by both meshes.
    pub depth: [u16; S1_BAND_PIXELS],
    /// Suzanne's bins: one entry per visible triangle.
    pub suzanne_bins: [BinEntry; BINS],
    /// Suzanne's transformed and lit vertices.
    pub suzanne_scratch: [SuzanneSlot; VERTICES],
    /// The cube's bins.
    pub cube_bins: [BinEntry; CUBE_BINS],
    /// The cube's transformed vertices.
    pub cube_scratch: [CubeSlot; CUBE_VERTICES],
}

impl S1Buffers {
    /// Zeroed buffers (each frame clears what it uses).
    pub const fn new() -> Self {
        Self {
            bands: [[0; S1_BAND_PIXELS]; 2],
            depth: [0; S1_BAND_PIXELS],
            suzanne_bins: [BinEntry::ZERO; BINS],
            suzanne_scratch: [VertexSlot::EMPTY; VERTICES],
            cube_bins: [BinEntry::ZERO; CUBE_BINS],
            cube_scratch: [VertexSlot::EMPTY; CUBE_VERTICES],
        }
    }
}

impl Default for S1Buffers {
    fn default() -> Self {
        Self::new()
    }
}

/// RAM of [`S1Buffers`], in bytes.
pub const S1_RAM_BYTES: usize = core::mem::size_of::<S1Buffers>();

/// Two band buffers and the display they go to: the [`DoubleBuffer`] of
/// [`FrameList::render_double`] for a display driven through [`mipidsi`].
///
/// [`DoubleBuffer::start`] sends the band's area as one address window (CASET/RASET), one RAMWR
/// and its pixels in one [`Display::set_pixels`] call, as [`crate::send_band`] does for a whole
/// band.
///
/// # Blocking, and where DMA goes
///
/// mipidsi's interfaces are blocking: `start` returns when the band's last byte is out, so
/// [`DoubleBuffer::wait`] has nothing to wait for and returns at once, and rendering waits for
/// the wire. With a DMA-capable HAL, `start` would send CASET/RASET/RAMWR (a few bytes,
/// blocking), start the DMA of buffer `k`'s pixels and return at once; `wait(k)` would wait for
/// that DMA to finish. [`FrameList::render_double`] draws into buffer `k` only after `wait(k)`,
/// so band N+1 is drawn into the other buffer while band N is on the wire, with no copy (unlike
/// the single-buffer variant described at [`crate::send_band`]). The pixels are `u16` in the
/// MCU's byte order: run the SPI in 16-bit frames, or have the display swap bytes, so that the
/// high byte goes first. A region's area (narrower than the band) is not contiguous in the
/// buffer: send it row by row, or send the band's full rows within the window's rows.
pub struct DisplaySender<'a, DI, MODEL, RST>
where
    DI: Interface,
    MODEL: Model<ColorFormat = Rgb565>,
    Rgb565: InterfacePixelFormat<DI::Word>,
    RST: OutputPin,
{
    display: &'a mut Display<DI, MODEL, RST>,
    bands: [&'a mut [u16]; 2],
    /// Transfers started, for the tests and statistics.
    sent: u32,
}

impl<DI, MODEL, RST> core::fmt::Debug for DisplaySender<'_, DI, MODEL, RST>
where
    DI: Interface,
    MODEL: Model<ColorFormat = Rgb565>,
    Rgb565: InterfacePixelFormat<DI::Word>,
    RST: OutputPin,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("DisplaySender")
            .field("band_lengths", &[self.bands[0].len(), self.bands[1].len()])
            .field("sent", &self.sent)
            .finish_non_exhaustive()
    }
}

impl<'a, DI, MODEL, RST> DisplaySender<'a, DI, MODEL, RST>
where
    DI: Interface,
    MODEL: Model<ColorFormat = Rgb565>,
    Rgb565: InterfacePixelFormat<DI::Word>,
    RST: OutputPin,
{
    /// A sender of two band buffers (each at least one band: `width * rows` pixels) to
    /// `display`.
    pub fn new(display: &'a mut Display<DI, MODEL, RST>, bands: [&'a mut [u16]; 2]) -> Self {
        Self {
            display,
            bands,
            sent: 0,
        }
    }

    /// Bands sent so far (one address window each).
    pub fn sent(&self) -> u32 {
        self.sent
    }
}

impl<DI, MODEL, RST> DoubleBuffer<Rgb565> for DisplaySender<'_, DI, MODEL, RST>
where
    DI: Interface,
    MODEL: Model<ColorFormat = Rgb565>,
    Rgb565: InterfacePixelFormat<DI::Word>,
    RST: OutputPin,
{
    type Error = StreamError<DI::Error>;

    fn buffer(&mut self, k: usize) -> &mut [u16] {
        let [first, second] = &mut self.bands;
        if k == 0 {
            first
        } else {
            second
        }
    }

    /// Sends `area` of buffer `k` and returns when it is out (see the type's documentation).
    fn start(&mut self, k: usize, rows: Rectangle, area: Rectangle) -> Result<(), Self::Error> {
        let Some(bottom_right) = area.bottom_right() else {
            return Ok(());
        };
        // The window's last column and row are inclusive.
        let to_u16 = |v: i32| u16::try_from(v).map_err(|_| StreamError::OffScreen);
        let (sx, sy) = (to_u16(area.top_left.x)?, to_u16(area.top_left.y)?);
        let (ex, ey) = (to_u16(bottom_right.x)?, to_u16(bottom_right.y)?);
        let width = rows.size.width as usize;
        let top = rows.top_left.y;
        let band: &[u16] = if k == 0 { self.bands[0] } else { self.bands[1] };
        // Row by row within the area; every index lies in the band (`area` is within `rows`),
        // and a word that did not would be sent as black rather than panic.
        let pixels = area.rows().flat_map(move |y| {
            let row = (y - top) as usize * width;
            area.columns().map(move |x| {
                let raw = band.get(row + x as usize).copied().unwrap_or(0);
                Rgb565::from(RawU16::new(raw))
            })
        });
        self.display
            .set_pixels(sx, sy, ex, ey, pixels)
            .map_err(StreamError::Display)?;
        self.sent += 1;
        Ok(())
    }

    /// Returns at once: [`DoubleBuffer::start`] has finished the transfer.
    fn wait(&mut self, _k: usize) -> Result<(), Self::Error> {
        Ok(())
    }
}

/// The areas one streamed frame sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Redraw {
    areas: [Rectangle; MAX_AREAS],
    count: usize,
    bands: u32,
}

impl Redraw {
    /// The rectangles sent, disjoint; empty when nothing changed.
    pub fn areas(&self) -> &[Rectangle] {
        &self.areas[..self.count]
    }

    /// Pixels sent.
    pub fn pixels(&self) -> u32 {
        self.areas()
            .iter()
            .map(|a| a.size.width * a.size.height)
            .sum()
    }

    /// Address windows sent: one per band of each area.
    pub fn windows(&self) -> u32 {
        self.bands
    }
}

/// S1 on a display from frame to frame: remembers what the display shows, so that each frame
/// after the first sends only what changed.
#[derive(Debug, Clone, Default)]
pub struct S1Screen {
    /// The summaries of the frame on the display; `None` before the first frame, and after a
    /// frame that failed part-way (the display then shows a mix).
    shown: Option<[Summary; S1_COMMANDS]>,
}

impl S1Screen {
    /// A screen whose content is unknown: the first frame is sent whole.
    pub const fn new() -> Self {
        Self { shown: None }
    }

    /// Forgets what the display shows (after the display was reset, for instance): the next
    /// frame is sent whole.
    pub fn invalidate(&mut self) {
        self.shown = None;
    }

    /// Renders S1 with Suzanne turned `suzanne_degrees` about y, and sends it to `display`
    /// (320 x 240, initialised, [`mipidsi::Builder::init`]) double-buffered: the whole screen
    /// the first time, afterwards only the rectangles that changed since the last frame sent
    /// (none when nothing did).
    ///
    /// # Errors
    /// [`StreamError::ScreenSize`] for a display of another size, [`StreamError::Mesh`] or
    /// [`StreamError::Frame`] when the list cannot be built or rendered (nothing is sent then),
    /// or the display's first error (the stream stops there, and the next frame is sent
    /// whole).
    pub fn stream<DI, MODEL, RST>(
        &mut self,
        display: &mut Display<DI, MODEL, RST>,
        buffers: &mut S1Buffers,
        suzanne_degrees: i32,
    ) -> Result<Redraw, StreamError<DI::Error>>
    where
        DI: Interface,
        MODEL: Model<ColorFormat = Rgb565>,
        Rgb565: InterfacePixelFormat<DI::Word>,
        RST: OutputPin,
    {
        let expected = Size::new(S1_WIDTH, S1_HEIGHT);
        let actual = display.size();
        if actual != expected {
            return Err(StreamError::ScreenSize { expected, actual });
        }
        let S1Buffers {
            bands,
            depth,
            suzanne_bins,
            suzanne_scratch,
            cube_bins,
            cube_scratch,
        } = buffers;

        // The list and everything it borrows live in this frame only.
        let suzanne = PackedMesh::parse(SUZANNE).map_err(StreamError::Mesh)?;
        let cube = s1::cube_mesh();
        let mut suzanne_command = MeshCommand::new(
            Pipeline::new(
                &s1::transforms(s1::suzanne_model(suzanne_degrees)),
                s1::viewport(),
                CullClockwise,
                SharedDepth,
                SuzanneShading::new(s1::suzanne_lighting()),
            ),
            &suzanne,
            suzanne_scratch,
            suzanne_bins,
        );
        let mut cube_command = MeshCommand::new(
            Pipeline::new(
                &s1::transforms(s1::cube_model()),
                s1::viewport(),
                CullClockwise,
                SharedDepth,
                CubeShading::new(s1::cube_lighting()),
            ),
            &cube,
            cube_scratch,
            cube_bins,
        );
        let labels = s1::labels();
        let layout = Layout::new(S1_WIDTH, S1_HEIGHT, BAND_ROWS).map_err(StreamError::Frame)?;
        let mut slots = [Slot::EMPTY; S1_COMMANDS];
        let mut list = FrameList::new(&mut slots, layout, Clear::new(s1::background()));
        // WORKLOADS.md's order: the meshes, the panel over them, the bars, the text, the
        // Gouraud triangle.
        list.command(&mut suzanne_command)
            .map_err(StreamError::Frame)?;
        list.command(&mut cube_command)
            .map_err(StreamError::Frame)?;
        s1::add_2d(&mut list, &labels).map_err(StreamError::Frame)?;

        let mut now = [Summary::default(); S1_COMMANDS];
        list.summaries(&mut now);
        let mut redraw = Redraw {
            areas: [Rectangle::zero(); MAX_AREAS],
            count: 0,
            bands: 0,
        };
        match &self.shown {
            None => {
                redraw.areas[0] = layout.screen();
                redraw.count = 1;
            }
            Some(shown) => redraw.count = changed_areas(shown, &now, &mut redraw.areas),
        }

        // Until every area is out the display shows a mix of two frames.
        self.shown = None;
        let [first, second] = bands;
        let mut sender = DisplaySender::new(display, [first, second]);
        for area in redraw.areas() {
            list.render_double(Some(area), depth, &mut sender)
                .map_err(|e| match e {
                    RenderError::Frame(e) => StreamError::Frame(e),
                    RenderError::Sink(e) => e,
                })?;
        }
        redraw.bands = sender.sent();
        self.shown = Some(now);
        Ok(redraw)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::mem::size_of;

    /// The figures of the crate documentation's S1 RAM table.
    #[test]
    fn s1_ram_figures_hold() {
        assert_eq!(S1_BAND_PIXELS * size_of::<u16>(), 10_240);
        assert_eq!(size_of::<SuzanneSlot>(), 16);
        assert_eq!(size_of::<CubeSlot>(), 12);
        assert_eq!(VERTICES * size_of::<SuzanneSlot>(), 8_112);
        assert_eq!(CUBE_VERTICES * size_of::<CubeSlot>(), 96);
        assert_eq!(CUBE_BINS * size_of::<BinEntry>(), 24);
        assert_eq!(S1_RAM_BYTES, 3 * 10_240 + 2_048 + 8_112 + 24 + 96);
        assert_eq!(S1_RAM_BYTES, 41_000);
    }

    /// The scratch and bins hold the meshes: every vertex a slot, every triangle (and the filler
    /// entries of long gaps between visible ones: one per 255 triangles) a bin.
    #[test]
    fn s1_buffers_fit_the_meshes() {
        use rasterizer_core::mesh::MeshSource;
        let suzanne = PackedMesh::parse(SUZANNE).unwrap();
        let triangles = MeshSource::<Fx16>::triangle_count(&suzanne);
        assert!(triangles + triangles / 255 <= BINS);
        let cube = s1::cube_mesh();
        assert_eq!(MeshSource::<Fx16>::vertex_count(&cube), CUBE_VERTICES);
        assert_eq!(MeshSource::<Fx16>::triangle_count(&cube), CUBE_BINS);
    }
}
