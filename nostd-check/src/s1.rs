//! Workload S1, the firmware screen (`fixtures::s1`), built as a frame list and rendered in
//! 16-row bands (`--features framelist`): the code a firmware screen of two meshes, 2D shapes and
//! text links, for its size (`.text`, WORKLOADS.md's `text_bytes` of `ours-band16`).
//!
//! One band buffer through [`FrameList::render`] by default; with `double` as well, two band
//! buffers through [`FrameList::render_double`] and a sender that stands for a DMA transfer
//! (`ours-band16x2`). Suzanne is the packed M1 mesh, the cube `fixtures::s1::cube_mesh`. The
//! buffers are `static`s, as in `one`, so `.bss` is the frame's RAM.

use core::hint::black_box;
use embedded_graphics_core::pixelcolor::Rgb565;
use fixtures::s1;
use rasterizer_core::cull::CullClockwise;
use rasterizer_core::depth::SharedDepth;
use rasterizer_core::frame::MeshCommand;
use rasterizer_core::frame::{Clear, FrameList, Layout, Slot};
use rasterizer_core::math::Fx16;
use rasterizer_core::mesh::PackedMesh;
use rasterizer_core::pipeline::{BinEntry, Pipeline, VertexSlot};
use rasterizer_core::shade::{FlatLit, GouraudLit, Shading};

/// The screen: 320 x 240.
const W: u32 = s1::WIDTH;
const H: u32 = s1::HEIGHT;
/// Rows per band.
const ROWS: u32 = s1::BAND_ROWS;
/// Words of one band.
const BAND: usize = (W * ROWS) as usize;
/// Suzanne's vertices and triangles; bins for every triangle and the filler entries of the
/// longest gaps between visible ones (one per 255 triangles).
const SUZANNE_VERTICES: usize = 507;
const SUZANNE_BINS: usize = 968 + 968 / 255;
/// The cube's.
const CUBE_VERTICES: usize = 8;
const CUBE_BINS: usize = 12;
/// Commands: two meshes, the panel's two triangles, twelve bars, two labels, the Gouraud
/// triangle.
const COMMANDS: usize = 19;

type Suzanne = GouraudLit<Fx16, Rgb565, 1>;
type Cube = FlatLit<Fx16, Rgb565, 1>;

/// Band buffers: one, or two with `double`.
#[cfg(not(feature = "double"))]
const BUFFERS: usize = 1;
#[cfg(feature = "double")]
const BUFFERS: usize = 2;

// All zeros (`VertexSlot::EMPTY`, `BinEntry::ZERO`): in .bss, no flash.
static mut BANDS: [[u16; BAND]; BUFFERS] = [[0; BAND]; BUFFERS];
static mut DEPTH: [u16; BAND] = [0; BAND];
static mut SUZANNE_SCRATCH: [VertexSlot<<Suzanne as Shading<Fx16>>::Stored>; SUZANNE_VERTICES] =
    [VertexSlot::EMPTY; SUZANNE_VERTICES];
static mut SUZANNE_BIN: [BinEntry; SUZANNE_BINS] = [BinEntry::ZERO; SUZANNE_BINS];
static mut CUBE_SCRATCH: [VertexSlot<<Cube as Shading<Fx16>>::Stored>; CUBE_VERTICES] =
    [VertexSlot::EMPTY; CUBE_VERTICES];
static mut CUBE_BIN: [BinEntry; CUBE_BINS] = [BinEntry::ZERO; CUBE_BINS];

/// Two band buffers and a transfer that firmware would start on the display's DMA.
#[cfg(feature = "double")]
struct Dma<'b> {
    bands: [&'b mut [u16]; 2],
}

#[cfg(feature = "double")]
impl rasterizer_core::frame::DoubleBuffer<Rgb565> for Dma<'_> {
    type Error = ();

    fn buffer(&mut self, k: usize) -> &mut [u16] {
        let [first, second] = &mut self.bands;
        if k == 0 {
            first
        } else {
            second
        }
    }

    fn start(
        &mut self,
        k: usize,
        rows: embedded_graphics_core::primitives::Rectangle,
        area: embedded_graphics_core::primitives::Rectangle,
    ) -> Result<(), ()> {
        // Where firmware would start the DMA of buffer k.
        black_box((&self.bands[k & 1][..], rows, area));
        Ok(())
    }

    fn wait(&mut self, k: usize) -> Result<(), ()> {
        black_box(k);
        Ok(())
    }
}

/// The S1 frame; returns the number of triangles drawn (0 when the list could not render).
pub fn draw() -> u32 {
    let Ok(suzanne) = PackedMesh::parse(black_box(crate::m1::MESH)) else {
        return 0;
    };
    let cube = s1::cube_mesh();
    // SAFETY: the only references to these statics, made once.
    #[allow(static_mut_refs)]
    let (bands, depth, suzanne_scratch, suzanne_bins, cube_scratch, cube_bins) = unsafe {
        (
            &mut BANDS,
            &mut DEPTH,
            &mut SUZANNE_SCRATCH,
            &mut SUZANNE_BIN,
            &mut CUBE_SCRATCH,
            &mut CUBE_BIN,
        )
    };
    // The angle is opaque, so that the matrices are computed, as from a firmware's input.
    let degrees = black_box(s1::SUZANNE_DEGREES);
    let mut suzanne_command = MeshCommand::new(
        Pipeline::new(
            &s1::transforms(s1::suzanne_model(degrees)),
            s1::viewport(),
            CullClockwise,
            SharedDepth,
            Suzanne::new(s1::suzanne_lighting()),
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
            Cube::new(s1::cube_lighting()),
        ),
        &cube,
        cube_scratch,
        cube_bins,
    );
    let labels = s1::labels();
    let rendered = {
        let Ok(layout) = Layout::new(W, H, ROWS) else {
            return 0;
        };
        let mut slots = [Slot::EMPTY; COMMANDS];
        let mut list = FrameList::new(&mut slots, layout, Clear::new(s1::background()));
        let mut added = list.command(&mut suzanne_command).is_ok();
        added &= list.command(&mut cube_command).is_ok();
        for shape in s1::panel().into_iter().chain(s1::bars()) {
            added &= list.shape(shape).is_ok();
        }
        for label in &labels {
            added &= list.item(label, 0).is_ok();
        }
        added &= list.shape(s1::gouraud()).is_ok();
        #[cfg(not(feature = "double"))]
        let rendered = list
            .render(&mut bands[0], depth, |band, area| {
                // Where firmware would send the band to the display.
                black_box((band.framebuffer().as_slice(), area));
            })
            .is_ok();
        #[cfg(feature = "double")]
        let rendered = {
            let [first, second] = bands;
            let mut dma = Dma {
                bands: [first, second],
            };
            list.render_double(None, depth, &mut dma).is_ok()
        };
        added && rendered
    };
    if !rendered {
        return 0;
    }
    suzanne_command.stats().drawn + cube_command.stats().drawn
}
