//! Whole screens in bands: a [`FrameList`] records a frame as an ordered list of commands (meshes
//! through their own pipelines, 2D shapes, embedded-graphics drawables such as text) and renders
//! it band by band into a buffer of a few rows, handing each finished band to a sink: a closure
//! ([`FrameList::render`]) or a double-buffered sender that may still be reading one buffer while
//! the next band is drawn into the other ([`FrameList::render_double`], [`DoubleBuffer`]).
//!
//! Every band holds exactly the pixels of drawing the same commands, in order, into a whole
//! framebuffer; the meshes share one depth buffer as they would in a whole frame. Each command's
//! screen bounds are computed once, when it is added (a mesh then transforms its vertices and
//! bins its triangles), so a band draws only the commands, and the triangles, that touch it.
//!
//! [`FrameList::render_region`] redraws only a rectangle (what changed since the last frame,
//! [`changed_areas`]), identical within it to the whole frame.
//!
//! The list lives for one frame: its storage ([`Slot`]s) is borrowed with the commands, so a
//! firmware loop declares the slots inside the loop and builds the list anew each frame, reusing
//! the commands (a [`MeshCommand`] takes the frame's transforms through
//! [`MeshCommand::set_pipeline`]).
//!
//! ```
//! use rasterizer_core::frame::{Clear, FrameList, Layout, Shape, Slot};
//! use rasterizer_core::prelude::*;
//!
//! let layout = Layout::new(64, 48, 8).unwrap();
//! let mut slots = [Slot::EMPTY; 4];
//! let mut list = FrameList::new(&mut slots, layout, Clear::new(Rgb565::BLACK));
//! let v = |x, y| SubPoint::<4>::new(x * 16, y * 16);
//! list.shape(Shape::Triangle { vertices: [v(4, 4), v(60, 10), v(20, 44)], color: Rgb565::RED, opacity: 255 })
//!     .unwrap();
//! list.shape(Shape::Line { a: Point::new(0, 47), b: Point::new(63, 0), color: Rgb565::WHITE }).unwrap();
//! let mut band = [0u16; 64 * 8];
//! let mut rows = 0;
//! list.render(&mut band, &mut [], |b, _area| rows += b.framebuffer().height()).unwrap();
//! assert_eq!(rows, 48);
//! ```
//!

mod mesh;
mod shape;

pub use crate::fingerprint::Fingerprint;
pub use mesh::MeshCommand;
pub use shape::{Item, PolygonFill, Shape};

use crate::depth::{Compare, DepthBuffer, DepthTest};
use crate::geom::PixelRect;
use crate::surface::{Band, ClipTo, Framebuffer, Storage, MAX_DIMENSION};
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;

/// A screen of `width` x `height` pixels cut into bands of `rows` rows (the last may have
/// fewer). One band of the screen's height renders the whole frame at once.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    width: u32,
    height: u32,
    rows: u32,
}

impl Layout {
    /// A layout; `rows` above `height` is cut to `height`.
    ///
    /// # Errors
    /// [`FrameError::BadLayout`] for a zero size, zero rows, or a side beyond
    /// [`MAX_DIMENSION`].
    pub fn new(width: u32, height: u32, rows: u32) -> Result<Self, FrameError> {
        let side = 1..=MAX_DIMENSION;
        if !side.contains(&width) || !side.contains(&height) || rows == 0 {
            return Err(FrameError::BadLayout {
                width,
                height,
                rows,
            });
        }
        Ok(Self {
            width,
            height,
            rows: rows.min(height),
        })
    }

    /// Screen width.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Screen height.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Rows per band.
    pub fn rows(&self) -> u32 {
        self.rows
    }

    /// How many bands the screen has.
    pub fn bands(&self) -> u32 {
        self.height.div_ceil(self.rows)
    }

    /// The screen.
    pub fn screen(&self) -> Rectangle {
        Rectangle::new(Point::zero(), Size::new(self.width, self.height))
    }

    /// Band `b`'s first row and row count.
    fn band(&self, b: u32) -> (u32, u32) {
        let y0 = b * self.rows;
        (y0, self.rows.min(self.height - y0))
    }
}

/// What each band starts from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Clear<C> {
    /// The background colour.
    pub color: C,
    /// The depth the shared depth buffer starts from (65535 for [`Compare::Less`]).
    pub depth: u16,
    /// The shared depth buffer's comparison.
    pub compare: Compare,
}

impl<C> Clear<C> {
    /// `color`, with the usual depth test: cleared to 65535, nearer passes.
    pub fn new(color: C) -> Self {
        Self {
            color,
            depth: u16::MAX,
            compare: Compare::Less,
        }
    }
}

/// Why a frame list refused a command or could not render.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameError {
    /// A screen size or band height the list cannot have.
    BadLayout {
        /// Width.
        width: u32,
        /// Height.
        height: u32,
        /// Rows per band.
        rows: u32,
    },
    /// Every slot holds a command already.
    Full {
        /// The slots given.
        capacity: usize,
    },
    /// A mesh has more visible triangles than bins.
    TooFewBins {
        /// Bins the frame needs.
        needed: usize,
        /// Bins given.
        actual: usize,
    },
    /// A band buffer shorter than one band.
    BandBufferTooSmall {
        /// Words one band needs.
        needed: usize,
        /// Words given.
        actual: usize,
    },
    /// A depth buffer shorter than one band, while a command tests depth.
    DepthTooSmall {
        /// Entries one band needs (`width * rows`).
        needed: usize,
        /// Entries given.
        actual: usize,
    },
}

impl core::fmt::Display for FrameError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::BadLayout {
                width,
                height,
                rows,
            } => write!(f, "bad layout {width}x{height} in bands of {rows} rows"),
            Self::Full { capacity } => write!(f, "the frame list's {capacity} slots are full"),
            Self::TooFewBins { needed, actual } => {
                write!(f, "a mesh needs {needed} bins but only {actual} were given")
            }
            Self::BandBufferTooSmall { needed, actual } => {
                write!(f, "band buffer has {actual} words, a band needs {needed}")
            }
            Self::DepthTooSmall { needed, actual } => {
                write!(
                    f,
                    "depth buffer has {actual} entries, a band needs {needed}"
                )
            }
        }
    }
}

impl core::error::Error for FrameError {}

/// Why a double-buffered render stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RenderError<E> {
    /// The list could not render (nothing was sent).
    Frame(FrameError),
    /// The sender failed.
    Sink(E),
}

impl<E: core::fmt::Debug> core::fmt::Display for RenderError<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Frame(e) => write!(f, "{e}"),
            Self::Sink(e) => write!(f, "the band sender failed: {e:?}"),
        }
    }
}

impl<E: core::fmt::Debug> core::error::Error for RenderError<E> {}

/// A command's answer when it is added to a list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Prepared {
    /// The pixels it may draw (empty: none).
    pub bounds: Rectangle,
    /// It tests the shared depth buffer.
    pub depth: bool,
}

impl Prepared {
    /// Draws nothing.
    pub const NOTHING: Self = Self {
        bounds: Rectangle::zero(),
        depth: false,
    };
}

/// A command of a frame list that keeps state between bands: a mesh ([`MeshCommand`]), or
/// anything a user builds on the same terms.
///
pub trait Command<C: Storage> {
    /// Called once when the command is added to a list for `layout`: does the frame's
    /// once-only work and returns the pixels it may draw.
    ///
    /// # Errors
    /// What keeps it from drawing this frame; the list then does not take it.
    fn prepare(&mut self, layout: &Layout) -> Result<Prepared, FrameError>;
    /// Draws band `band` of the layout it was prepared for into `target`, whose clip area is
    /// the part of the band being rendered, with the frame's shared depth buffer (holding the
    /// band's rows). Bands come in increasing order within one pass over the frame.
    fn draw(
        &mut self,
        band: u32,
        target: &mut ClipTo<'_, Band<'_, C>>,
        depth: &mut DepthBuffer<'_>,
    );
    /// Feeds everything that decides its pixels to `hash` ([`changed_areas`]).
    fn fingerprint(&self, hash: &mut Fingerprint);
}

/// One command of a frame list as [`changed_areas`] compares frames: its bounds and fingerprint.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Summary {
    /// The pixels it may draw.
    pub bounds: Rectangle,
    /// What decides them ([`Command::fingerprint`]).
    pub fingerprint: u64,
}

enum Op<'c, C: Storage> {
    Shape(Shape<C>),
    Item(&'c dyn Item<C>, u32),
    Command(&'c mut dyn Command<C>),
}

/// One command of a frame list, in storage the caller gives ([`FrameList::new`]).
pub struct Slot<'c, C: Storage>(Option<Entry<'c, C>>);

impl<C: Storage> Slot<'_, C> {
    /// An empty slot, for arrays: `[Slot::EMPTY; 32]`.
    pub const EMPTY: Self = Self(None);
}

impl<C: Storage> core::fmt::Debug for Slot<'_, C> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match &self.0 {
            None => write!(f, "Slot(empty)"),
            Some(e) => write!(f, "Slot({:?}, bands {}..={})", e.bounds(), e.first, e.last),
        }
    }
}

struct Entry<'c, C: Storage> {
    op: Op<'c, C>,
    /// Within the screen (sides below 32,768): x0, y0, x1, y1 as `i16`, to keep the slot small.
    bounds: [i16; 4],
    /// The first and last band the bounds touch.
    first: u16,
    last: u16,
}

impl<C: Storage> Entry<'_, C> {
    fn bounds(&self) -> PixelRect {
        let [x0, y0, x1, y1] = self.bounds.map(i64::from);
        PixelRect { x0, y0, x1, y1 }
    }
}

/// An ordered list of drawing commands for one frame, rendered whole, band by band or in part
/// (see the [module documentation](self)).
pub struct FrameList<'c, C: Storage> {
    slots: &'c mut [Slot<'c, C>],
    len: usize,
    layout: Layout,
    clear: Clear<C>,
    /// Some command tests depth.
    depth: bool,
}

impl<C: Storage> core::fmt::Debug for FrameList<'_, C> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("FrameList")
            .field("len", &self.len)
            .field("layout", &self.layout)
            .finish_non_exhaustive()
    }
}

impl<'c, C: Storage> FrameList<'c, C> {
    /// An empty list over `slots` (one a command) for `layout`, each band cleared to `clear`.
    pub fn new(slots: &'c mut [Slot<'c, C>], layout: Layout, clear: Clear<C>) -> Self {
        for s in slots.iter_mut() {
            s.0 = None;
        }
        Self {
            slots,
            len: 0,
            layout,
            clear,
            depth: false,
        }
    }

    /// The layout.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// Commands in the list.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when the list holds no command.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    fn push(&mut self, op: Op<'c, C>, bounds: Rectangle) -> Result<(), FrameError> {
        let capacity = self.slots.len();
        let slot = self
            .slots
            .get_mut(self.len)
            .ok_or(FrameError::Full { capacity })?;
        let screen = PixelRect::from_rectangle(&self.layout.screen());
        let bounds = PixelRect::from_rectangle(&bounds).intersection(&screen);
        // A command outside the screen takes a slot and draws in no band (first after last).
        let rows = self.layout.rows;
        let (first, last) = if bounds.is_empty() {
            (1, 0)
        } else {
            // Within the screen: 0 <= y0 < y1 <= height, so 32-bit divisions (an instruction on
            // a Cortex-M3/M4, where a 64-bit one is a library call).
            let (y0, y1) = (bounds.y0 as u32, bounds.y1 as u32);
            ((y0 / rows) as u16, ((y1 - 1) / rows) as u16)
        };
        // Within the screen, whose sides are at most 32,767: every coordinate fits i16.
        let bounds = if bounds.is_empty() {
            [0; 4]
        } else {
            [bounds.x0, bounds.y0, bounds.x1, bounds.y1].map(|v| v as i16)
        };
        slot.0 = Some(Entry {
            op,
            bounds,
            first,
            last,
        });
        self.len += 1;
        Ok(())
    }

    /// Adds a 2D shape.
    ///
    /// # Errors
    /// [`FrameError::Full`].
    pub fn shape(&mut self, shape: Shape<C>) -> Result<(), FrameError> {
        let bounds = shape.bounds();
        self.push(Op::Shape(shape), bounds)
    }

    /// Adds an item drawn by reference: any embedded-graphics `Drawable` with `Dimensions`
    /// (text in an embedded-graphics font) or a [`PolygonFill`]. Its bounding box must hold
    /// everything it draws. `revision` stands for its content in [`FrameList::summaries`]:
    /// change it when the item draws differently within the same bounds (new text).
    ///
    /// # Errors
    /// [`FrameError::Full`].
    pub fn item(&mut self, item: &'c dyn Item<C>, revision: u32) -> Result<(), FrameError> {
        let bounds = item.bounds();
        self.push(Op::Item(item, revision), bounds)
    }

    /// Adds a command that keeps state between bands (a mesh): it is prepared now
    /// ([`Command::prepare`]).
    ///
    /// # Errors
    /// [`FrameError::Full`], or the command's own refusal ([`FrameError::TooFewBins`]); the
    /// list is unchanged then.
    pub fn command(&mut self, command: &'c mut dyn Command<C>) -> Result<(), FrameError> {
        if self.len >= self.slots.len() {
            return Err(FrameError::Full {
                capacity: self.slots.len(),
            });
        }
        let prepared = command.prepare(&self.layout)?;
        self.depth |= prepared.depth;
        self.push(Op::Command(command), prepared.bounds)
    }

    /// Each command's bounds and fingerprint, in order, into `out` (as many as fit); returns
    /// how many there are in the list.
    pub fn summaries(&self, out: &mut [Summary]) -> usize
    where
        C: core::hash::Hash,
    {
        for (entry, out) in self.entries().zip(out.iter_mut()) {
            let mut hash = Fingerprint::default();
            match &entry.op {
                Op::Shape(s) => core::hash::Hash::hash(s, &mut hash),
                Op::Item(_, revision) => {
                    hash.bytes(&revision.to_le_bytes());
                }
                Op::Command(c) => c.fingerprint(&mut hash),
            }
            *out = Summary {
                bounds: entry.bounds().to_rectangle(),
                fingerprint: hash.value(),
            };
        }
        self.len
    }

    fn entries(&self) -> impl Iterator<Item = &Entry<'c, C>> {
        self.slots[..self.len].iter().filter_map(|s| s.0.as_ref())
    }

    /// Checks the buffers and makes the depth buffer of one band.
    fn buffers<'d>(
        &self,
        band: usize,
        depth: &'d mut [u16],
    ) -> Result<DepthBuffer<'d>, FrameError> {
        let (width, rows) = (self.layout.width, self.layout.rows);
        let needed = Framebuffer::<C>::required_len(width, rows).unwrap_or(usize::MAX);
        if band < needed {
            return Err(FrameError::BandBufferTooSmall {
                needed,
                actual: band,
            });
        }
        let entries = width as usize * rows as usize;
        if !self.depth {
            // Nobody tests depth: an empty buffer that nothing reads.
            let empty: &mut [u16] = &mut depth[..0];
            return Ok(DepthBuffer::new(empty, 0, 0, self.clear.compare)
                .unwrap_or_else(|_| unreachable!("an empty buffer of 0x0 has the right length")));
        }
        if depth.len() < entries {
            return Err(FrameError::DepthTooSmall {
                needed: entries,
                actual: depth.len(),
            });
        }
        let actual = depth.len();
        DepthBuffer::new(&mut depth[..entries], width, rows, self.clear.compare).map_err(|_| {
            FrameError::DepthTooSmall {
                needed: entries,
                actual,
            }
        })
    }

    /// The bands `region` touches.
    fn bands_of(&self, region: &PixelRect) -> core::ops::Range<u32> {
        if region.is_empty() {
            return 0..0;
        }
        let rows = self.layout.rows;
        // Within the screen: 0 <= y0 < y1 <= height; 32-bit divisions, as above.
        let (y0, y1) = (region.y0 as u32, region.y1 as u32);
        y0 / rows..(y1 - 1) / rows + 1
    }

    /// Draws band `b`, within `region`, into `buf`.
    fn draw_band<'b>(
        &mut self,
        b: u32,
        region: &PixelRect,
        buf: &'b mut [C::Word],
        depth: &mut DepthBuffer<'_>,
    ) -> Result<(Band<'b, C>, Rectangle), FrameError> {
        let (width, (y0, h)) = (self.layout.width, self.layout.band(b));
        let len = Framebuffer::<C>::required_len(width, h).unwrap_or(usize::MAX);
        let actual = buf.len();
        let words = buf.get_mut(..len).ok_or(FrameError::BandBufferTooSmall {
            needed: len,
            actual,
        })?;
        let mut fb = Framebuffer::<C>::new(words, width, h).map_err(|_| FrameError::BadLayout {
            width,
            height: self.layout.height,
            rows: self.layout.rows,
        })?;
        let Ok(()) = DrawTarget::clear(&mut fb, self.clear.color);
        // Rows below 32,768: they fit i32.
        let y0 = y0 as i32;
        if self.depth {
            depth.start_band(y0, self.clear.depth);
        }
        let mut band = Band::new(fb, y0);
        let rows = PixelRect {
            x0: 0,
            y0: i64::from(y0),
            x1: i64::from(width),
            y1: i64::from(y0) + i64::from(h),
        };
        let clip = rows.intersection(region);
        {
            let mut target = ClipTo::new(&mut band, clip.to_rectangle());
            for slot in self.slots[..self.len].iter_mut() {
                let Some(e) = slot.0.as_mut() else {
                    continue;
                };
                let b16 = b as u16;
                if b16 < e.first || b16 > e.last || e.bounds().intersection(&clip).is_empty() {
                    continue;
                }
                match &mut e.op {
                    Op::Shape(s) => {
                        // A band reads back, so blending cannot fail; its own error is
                        // `Infallible`.
                        let drawn = s.draw(&mut target);
                        debug_assert!(drawn.is_ok());
                    }
                    Op::Item(item, _) => item.draw_into(&mut target),
                    Op::Command(c) => c.draw(b, &mut target, depth),
                }
            }
        }
        Ok((band, clip.to_rectangle()))
    }

    /// Renders the whole frame band by band into `band` (at least one band's words:
    /// `Framebuffer::required_len(width, rows)`), handing each finished band and its screen
    /// area to `sink` before the buffer is reused for the next. `depth` holds `width * rows`
    /// entries when a command tests depth, and may be empty otherwise.
    ///
    /// # Errors
    /// [`FrameError`] for a buffer too small (nothing is drawn).
    pub fn render<F>(
        &mut self,
        band: &mut [C::Word],
        depth: &mut [u16],
        sink: F,
    ) -> Result<(), FrameError>
    where
        F: FnMut(&Band<'_, C>, Rectangle),
    {
        let screen = self.layout.screen();
        self.render_region(&screen, band, depth, sink)
    }

    /// Renders only the pixels of `region` (cut to the screen), band by band: each band's
    /// area handed to `sink` is its rows of `region`, and holds exactly the whole frame's
    /// pixels there (the band buffer's pixels outside it are not drawn). Only the commands whose
    /// bounds meet the area are drawn.
    ///
    /// # Errors
    /// [`FrameError`] for a buffer too small (nothing is drawn).
    pub fn render_region<F>(
        &mut self,
        region: &Rectangle,
        band: &mut [C::Word],
        depth: &mut [u16],
        mut sink: F,
    ) -> Result<(), FrameError>
    where
        F: FnMut(&Band<'_, C>, Rectangle),
    {
        let mut depth = self.buffers(band.len(), depth)?;
        let region = PixelRect::from_rectangle(region)
            .intersection(&PixelRect::from_rectangle(&self.layout.screen()));
        for b in self.bands_of(&region) {
            let (strip, area) = self.draw_band(b, &region, band, &mut depth)?;
            sink(&strip, area);
        }
        Ok(())
    }

    /// Renders `region` (the whole screen for `None`) with two band buffers that `sender`
    /// owns, alternating between them: while the sender still reads one (a DMA transfer to the
    /// display), the next band is drawn into the other. A buffer is drawn into only after
    /// [`DoubleBuffer::wait`] for it has returned; the render ends by waiting for both.
    ///
    /// # Errors
    /// [`RenderError::Frame`] for a buffer too small (before anything is drawn or sent),
    /// [`RenderError::Sink`] when the sender fails (the render stops there).
    pub fn render_double<D: DoubleBuffer<C>>(
        &mut self,
        region: Option<&Rectangle>,
        depth: &mut [u16],
        sender: &mut D,
    ) -> Result<(), RenderError<D::Error>> {
        let screen = PixelRect::from_rectangle(&self.layout.screen());
        let region = region.map_or(screen, |r| {
            PixelRect::from_rectangle(r).intersection(&screen)
        });
        let shortest = sender.buffer(0).len().min(sender.buffer(1).len());
        let mut depth = self.buffers(shortest, depth).map_err(RenderError::Frame)?;
        for (i, b) in self.bands_of(&region).enumerate() {
            let k = i % 2;
            sender.wait(k).map_err(RenderError::Sink)?;
            let (strip, area) = self
                .draw_band(b, &region, sender.buffer(k), &mut depth)
                .map_err(RenderError::Frame)?;
            let rows = strip.bounding_box_rows();
            sender.start(k, rows, area).map_err(RenderError::Sink)?;
        }
        sender.wait(0).map_err(RenderError::Sink)?;
        sender.wait(1).map_err(RenderError::Sink)
    }
}

/// Two band buffers and the sender that reads them ([`FrameList::render_double`]): firmware
/// starts a DMA transfer to the display in [`DoubleBuffer::start`] and returns at once.
pub trait DoubleBuffer<C: Storage> {
    /// What a failed transfer reports.
    type Error;
    /// Buffer `k` (0 or 1), to draw the next band into: called for `k` only when no transfer
    /// reads it (after [`DoubleBuffer::wait`] for `k`), and for both once before a render to
    /// check their length.
    fn buffer(&mut self, k: usize) -> &mut [C::Word];
    /// Starts sending buffer `k`, which holds the full-width screen rows `rows` (row by row,
    /// as a [`Framebuffer`] of that size); `area` within them is the part to send (a region
    /// render's columns). The transfer may go on after this returns.
    ///
    /// # Errors
    /// The sender's.
    fn start(&mut self, k: usize, rows: Rectangle, area: Rectangle) -> Result<(), Self::Error>;
    /// Returns once no transfer reads buffer `k` (at once when none does).
    ///
    /// # Errors
    /// The sender's.
    fn wait(&mut self, k: usize) -> Result<(), Self::Error>;
}

/// The rectangles to redraw between two frames, from their [`FrameList::summaries`]: for each
/// command whose bounds or fingerprint differ (or that is in one frame only), its old and new
/// bounds together. Overlapping rectangles are merged; when `out` is full, the rest is merged
/// into its last rectangle, so the areas returned always cover every change. Returns how many
/// rectangles of `out` hold the areas.
pub fn changed_areas(old: &[Summary], new: &[Summary], out: &mut [Rectangle]) -> usize {
    let mut count = 0usize;
    let mut add = |r: PixelRect| {
        if r.is_empty() {
            return;
        }
        let mut r = r;
        // Merge with every area it meets, repeatedly, so the result holds disjoint areas.
        let mut i = 0;
        while i < count {
            let other = PixelRect::from_rectangle(&out[i]);
            if other.intersection(&r).is_empty() {
                i += 1;
            } else {
                r = r.union(&other);
                count -= 1;
                out[i] = out[count];
                i = 0;
            }
        }
        if count < out.len() {
            out[count] = r.to_rectangle();
            count += 1;
        } else if let Some(last) = out.last_mut() {
            *last = PixelRect::from_rectangle(last).union(&r).to_rectangle();
        }
    };
    for i in 0..old.len().max(new.len()) {
        let (a, b) = (old.get(i), new.get(i));
        if a == b {
            continue;
        }
        let bounds = |s: Option<&Summary>| {
            s.map_or(PixelRect::EMPTY, |s| PixelRect::from_rectangle(&s.bounds))
        };
        add(bounds(a).union(&bounds(b)));
    }
    count
}

impl<C: Storage> Band<'_, C> {
    /// The screen rows the band stands for, full width.
    fn bounding_box_rows(&self) -> Rectangle {
        let fb = self.framebuffer();
        Rectangle::new(Point::new(0, self.y0()), Size::new(fb.width(), fb.height()))
    }
}
