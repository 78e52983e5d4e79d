//! The depth stage: a [`DepthTest`] decides which pixels of a span may be drawn. [`DepthBuffer`]
//! keeps a 16-bit depth per pixel in a slice the caller owns (0 nearest, 65535 farthest);
//! [`NoDepth`] compiles the test, its buffer and the depth interpolation away; [`DepthReadOnly`]
//! tests against a buffer without writing it, for translucent meshes.
//!
//! Translucent meshes ([`crate::surface::Translucent`]) are usually drawn in two passes: the
//! opaque meshes first with a [`DepthBuffer`], then the translucent ones, back to front, with the
//! same buffer read-only ([`DepthBuffer::read_only`]). They are hidden behind opaque surfaces but
//! do not hide each other, so what lies behind a translucent surface still shows through it.

use crate::geom::PixelRect;
use embedded_graphics_core::primitives::Rectangle;

/// How a depth buffer compares a new depth with the stored one; 0 is nearest, 65535 farthest.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Compare {
    /// Draw when nearer (the usual test; clear the buffer to 65535).
    #[default]
    Less,
    /// Draw when nearer or equal.
    LessEqual,
    /// Draw when farther.
    Greater,
    /// Draw when farther or equal.
    GreaterEqual,
    /// Draw when equal.
    Equal,
    /// Draw when different.
    NotEqual,
    /// Always draw (and store the depth).
    Always,
    /// Never draw.
    Never,
}

impl Compare {
    /// Whether a new depth passes against the stored one.
    #[inline(always)]
    pub fn pass(self, new: u16, old: u16) -> bool {
        match self {
            Compare::Less => new < old,
            Compare::LessEqual => new <= old,
            Compare::Greater => new > old,
            Compare::GreaterEqual => new >= old,
            Compare::Equal => new == old,
            Compare::NotEqual => new != old,
            Compare::Always => true,
            Compare::Never => false,
        }
    }
}

/// A depth test: which pixels of a span may be drawn.
pub trait DepthTest {
    /// The test reads depths: when false the rasterizer computes none.
    const ENABLED: bool = true;
    /// A pixel that passes stores its depth. False for a test that only reads
    /// ([`DepthReadOnly`]); a constant, so the store is compiled in or out.
    const WRITE: bool = true;
    /// Band rendering: the buffer now holds the rows from `y0` on; every entry is reset to
    /// `clear` (a test that does not write keeps them: they come from an earlier pass). Does
    /// nothing for a test without a buffer.
    fn start_band(&mut self, _y0: i32, _clear: u16) {}
    /// Calls `run(offset, len)` for each run of pixels of row `y`, columns `x .. x + len`, that
    /// passes, storing their depths first (when [`DepthTest::WRITE`]). The depth of pixel `i` is `(z + i dz) >> 16`, clamped
    /// to `0 ..= 65535`.
    fn test_span<E, F>(
        &mut self,
        y: i32,
        x: i32,
        len: u32,
        z: i64,
        dz: i64,
        run: F,
    ) -> Result<(), E>
    where
        F: FnMut(u32, u32) -> Result<(), E>;
    /// The stored depths, for the fused span loop of the 3D pipeline, which tests and stores
    /// through them: it checks once per triangle that they cover the pixels it draws, and then
    /// indexes them directly. `None` for a test without a buffer (nothing is drawn then).
    fn depth_rows(&mut self) -> Option<DepthRows<'_>> {
        None
    }
    /// The comparison a new depth must pass against the stored one.
    fn comparison(&self) -> Compare {
        Compare::Always
    }
    /// Whether the test holds a depth for every pixel of `area` (one without a buffer does).
    fn covers(&self, _area: &Rectangle) -> bool {
        true
    }
}

/// A depth buffer's entries as [`DepthTest::depth_rows`] hands them out: `width` entries a row,
/// rows top to bottom, the first standing for screen row `origin_y`.
#[derive(Debug)]
pub struct DepthRows<'a> {
    /// The entries, at least `width * height` of them.
    pub depths: &'a mut [u16],
    /// Entries a row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// The screen row of the first row.
    pub origin_y: i32,
}

/// No depth test: every pixel passes and no depth is computed.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoDepth;

impl DepthTest for NoDepth {
    const ENABLED: bool = false;
    #[inline(always)]
    fn test_span<E, F>(
        &mut self,
        _: i32,
        _: i32,
        len: u32,
        _: i64,
        _: i64,
        mut run: F,
    ) -> Result<(), E>
    where
        F: FnMut(u32, u32) -> Result<(), E>,
    {
        run(0, len)
    }
}

/// Why a [`DepthBuffer`] could not be made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DepthBufferError {
    /// Entries the size needs.
    pub expected: usize,
    /// Entries the slice has.
    pub actual: usize,
}

impl core::fmt::Display for DepthBufferError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "depth buffer slice has {} entries, the size needs {}",
            self.actual, self.expected
        )
    }
}

impl core::error::Error for DepthBufferError {}

/// A depth buffer over a caller-provided `&mut [u16]`, one entry per pixel, rows top to bottom.
#[derive(Debug)]
pub struct DepthBuffer<'a> {
    buf: &'a mut [u16],
    width: u32,
    height: u32,
    /// The screen row the buffer's first row stands for (band rendering).
    origin_y: i32,
    compare: Compare,
}

impl<'a> DepthBuffer<'a> {
    /// A depth buffer of `width` x `height` over `buf` (exactly `width * height` entries).
    ///
    /// # Errors
    /// [`DepthBufferError`] when the slice has another length.
    pub fn new(
        buf: &'a mut [u16],
        width: u32,
        height: u32,
        compare: Compare,
    ) -> Result<Self, DepthBufferError> {
        let expected = width as usize * height as usize;
        if buf.len() != expected {
            return Err(DepthBufferError {
                expected,
                actual: buf.len(),
            });
        }
        Ok(Self {
            buf,
            width,
            height,
            origin_y: 0,
            compare,
        })
    }

    /// Sets every entry to `depth` (65535 before a frame with [`Compare::Less`]).
    pub fn clear(&mut self, depth: u16) {
        self.buf.fill(depth);
    }

    /// The stored depths.
    pub fn as_slice(&self) -> &[u16] {
        self.buf
    }

    /// The comparison in use.
    pub fn compare(&self) -> Compare {
        self.compare
    }

    /// The same buffer as a depth test that does not write: pixels are drawn where they pass
    /// against the stored depths, which stay as they are (translucent meshes; see the module
    /// documentation).
    pub fn read_only(self) -> DepthReadOnly<'a> {
        DepthReadOnly(self)
    }
}

impl DepthTest for DepthBuffer<'_> {
    fn start_band(&mut self, y0: i32, clear: u16) {
        self.origin_y = y0;
        self.buf.fill(clear);
    }

    #[inline(always)]
    fn depth_rows(&mut self) -> Option<DepthRows<'_>> {
        Some(DepthRows {
            depths: self.buf,
            width: self.width,
            height: self.height,
            origin_y: self.origin_y,
        })
    }

    #[inline(always)]
    fn comparison(&self) -> Compare {
        self.compare
    }

    fn covers(&self, area: &Rectangle) -> bool {
        let r = PixelRect::from_rectangle(area);
        let y0 = i64::from(self.origin_y);
        r.x0 >= 0
            && r.x1 <= i64::from(self.width)
            && r.y0 >= y0
            && r.y1 <= y0 + i64::from(self.height)
    }

    #[inline(always)]
    fn test_span<E, F>(
        &mut self,
        y: i32,
        x: i32,
        len: u32,
        z: i64,
        dz: i64,
        run: F,
    ) -> Result<(), E>
    where
        F: FnMut(u32, u32) -> Result<(), E>,
    {
        buffer_runs::<E, F, true>(self, y, x, len, z, dz, run)
    }
}

/// [`DepthBuffer::test_span`], storing the depths that pass when `WRITE`.
#[inline(always)]
fn buffer_runs<E, F, const WRITE: bool>(
    buffer: &mut DepthBuffer<'_>,
    y: i32,
    x: i32,
    len: u32,
    z: i64,
    dz: i64,
    run: F,
) -> Result<(), E>
where
    F: FnMut(u32, u32) -> Result<(), E>,
{
    // Pixels outside the buffer are never drawn (a buffer smaller than the target clips).
    let y = y.wrapping_sub(buffer.origin_y);
    if y < 0 || y as u32 >= buffer.height || x < 0 {
        return Ok(());
    }
    let len = len.min(buffer.width.saturating_sub(x as u32));
    let start = y as usize * buffer.width as usize + x as usize;
    let Some(row) = buffer.buf.get_mut(start..start + len as usize) else {
        return Ok(());
    };
    // The usual test gets its own loop, with the comparison known at compile time; the others
    // share one (a copy per comparison would multiply the shading code inlined into each).
    if buffer.compare == Compare::Less {
        passing_runs::<E, _, F, WRITE>(row, z, dz, |new, old| new < old, run)
    } else {
        let compare = buffer.compare;
        passing_runs::<E, _, F, WRITE>(row, z, dz, |new, old| compare.pass(new, old), run)
    }
}

/// A [`DepthBuffer`] that tests but does not write ([`DepthBuffer::read_only`]): pixels behind the
/// stored depths are not drawn, and the stored depths stay as they are. Band rendering moves it
/// to each band without clearing it ([`DepthTest::start_band`]).
#[derive(Debug)]
pub struct DepthReadOnly<'a>(DepthBuffer<'a>);

impl<'a> DepthReadOnly<'a> {
    /// The buffer, writing again.
    pub fn into_inner(self) -> DepthBuffer<'a> {
        self.0
    }

    /// The stored depths.
    pub fn as_slice(&self) -> &[u16] {
        self.0.buf
    }
}

impl DepthTest for DepthReadOnly<'_> {
    const WRITE: bool = false;

    fn start_band(&mut self, y0: i32, _clear: u16) {
        self.0.origin_y = y0;
    }

    #[inline(always)]
    fn depth_rows(&mut self) -> Option<DepthRows<'_>> {
        self.0.depth_rows()
    }

    #[inline(always)]
    fn comparison(&self) -> Compare {
        self.0.compare
    }

    fn covers(&self, area: &Rectangle) -> bool {
        self.0.covers(area)
    }

    #[inline(always)]
    fn test_span<E, F>(
        &mut self,
        y: i32,
        x: i32,
        len: u32,
        z: i64,
        dz: i64,
        run: F,
    ) -> Result<(), E>
    where
        F: FnMut(u32, u32) -> Result<(), E>,
    {
        buffer_runs::<E, F, false>(&mut self.0, y, x, len, z, dz, run)
    }
}

/// Calls `run(offset, len)` for each run of pixels of `row` whose depth `(z + i dz) >> 16`
/// (clamped to `0 ..= 65535`) passes `pass(new, stored)`, storing those depths first when
/// `WRITE`.
#[inline(always)]
fn passing_runs<E, P, F, const WRITE: bool>(
    row: &mut [u16],
    z: i64,
    dz: i64,
    pass: P,
    mut run: F,
) -> Result<(), E>
where
    P: Fn(u16, u16) -> bool,
    F: FnMut(u32, u32) -> Result<(), E>,
{
    let mut z = z;
    let mut i = 0usize;
    while i < row.len() {
        let begin = i;
        while i < row.len() {
            let d = (z >> 16).clamp(0, 65535) as u16;
            if !pass(d, row[i]) {
                break;
            }
            if WRITE {
                row[i] = d;
            }
            i += 1;
            z += dz;
        }
        if i > begin {
            run(begin as u32, (i - begin) as u32)?;
        }
        // Skip the failing pixel(s).
        while i < row.len() {
            let d = (z >> 16).clamp(0, 65535) as u16;
            if pass(d, row[i]) {
                break;
            }
            i += 1;
            z += dz;
        }
    }
    Ok(())
}

/// The depth stage of a mesh drawn through a frame list ([`crate::frame`]): the list's one depth
/// buffer, shared by all its meshes as one buffer is in a whole frame, tested and written.
///
/// The buffer belongs to the list and is lent to the mesh only while it draws, so a pipeline with
/// this stage draws nothing on its own: [`crate::pipeline::Pipeline::draw`] returns
/// `DepthTooSmall`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SharedDepth;

/// Like [`SharedDepth`], tested but not written ([`DepthReadOnly`]): for translucent meshes,
/// hidden behind the opaque ones drawn before them without hiding what lies behind them.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SharedDepthReadOnly;

impl DepthTest for SharedDepth {
    fn covers(&self, _area: &Rectangle) -> bool {
        false
    }

    fn test_span<E, F>(&mut self, _: i32, _: i32, _: u32, _: i64, _: i64, _: F) -> Result<(), E>
    where
        F: FnMut(u32, u32) -> Result<(), E>,
    {
        Ok(())
    }
}

impl DepthTest for SharedDepthReadOnly {
    const WRITE: bool = false;

    fn covers(&self, _area: &Rectangle) -> bool {
        false
    }

    fn test_span<E, F>(&mut self, _: i32, _: i32, _: u32, _: i64, _: i64, _: F) -> Result<(), E>
    where
        F: FnMut(u32, u32) -> Result<(), E>,
    {
        Ok(())
    }
}

/// How a mesh of a frame list uses the list's depth buffer: [`NoDepth`], [`SharedDepth`] or
/// [`SharedDepthReadOnly`] (sealed: no other type is one).
pub trait ListDepth: DepthTest + Copy + sealed::Sealed {}

impl ListDepth for NoDepth {}
impl ListDepth for SharedDepth {}
impl ListDepth for SharedDepthReadOnly {}

mod sealed {
    pub trait Sealed {}
    impl Sealed for crate::depth::NoDepth {}
    impl Sealed for crate::depth::SharedDepth {}
    impl Sealed for crate::depth::SharedDepthReadOnly {}
}

/// The list's depth buffer lent to one mesh for one band, used as its [`ListDepth`] `L` says.
#[derive(Debug)]
pub(crate) struct Lent<'a, 'b, L>(&'a mut DepthBuffer<'b>, core::marker::PhantomData<L>);

impl<'a, 'b, L> Lent<'a, 'b, L> {
    pub(crate) fn new(buffer: &'a mut DepthBuffer<'b>) -> Self {
        Self(buffer, core::marker::PhantomData)
    }
}

impl<L: ListDepth> DepthTest for Lent<'_, '_, L> {
    const ENABLED: bool = L::ENABLED;
    const WRITE: bool = L::WRITE;

    #[inline(always)]
    fn depth_rows(&mut self) -> Option<DepthRows<'_>> {
        self.0.depth_rows()
    }

    #[inline(always)]
    fn comparison(&self) -> Compare {
        self.0.compare
    }

    fn covers(&self, area: &Rectangle) -> bool {
        !L::ENABLED || self.0.covers(area)
    }

    #[inline(always)]
    fn test_span<E, F>(
        &mut self,
        y: i32,
        x: i32,
        len: u32,
        z: i64,
        dz: i64,
        mut run: F,
    ) -> Result<(), E>
    where
        F: FnMut(u32, u32) -> Result<(), E>,
    {
        if !L::ENABLED {
            run(0, len)
        } else if L::WRITE {
            buffer_runs::<E, F, true>(self.0, y, x, len, z, dz, run)
        } else {
            buffer_runs::<E, F, false>(self.0, y, x, len, z, dz, run)
        }
    }
}
