//! Band rendering: a frame drawn one horizontal strip at a time, for firmware without room for a
//! whole frame.

use super::{AntialiasError, DepthFrom, Front, MeshSource, Pipeline, RenderStats, VertexSlot};
use crate::clip::polygon::clip_triangle;
use crate::clip::polygon::ClipVertex;
use crate::cull::Cull;
use crate::depth::DepthTest;
use crate::geom::{PixelRect, SubPoint};
use crate::math::Scalar;
use crate::numerics::Numerics;
use crate::raster::edge::row_at_or_below;
use crate::shade::Shading;
use crate::surface::Surface;
use crate::surface::{Band, ClipTo, Framebuffer, Storage};
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;

/// A visible triangle's place in a banded frame ([`Pipeline::draw_banded`]): 2 bytes a triangle.
///
/// Entries are kept in mesh order, each holding the distance to the previous entry's triangle
/// (a gap beyond 255 triangles takes filler entries) and the first and last band it touches, 4
/// bits each: in groups of bands when a frame has more than 16, so that a triangle may be handed
/// to a band of its group it does not reach (where it draws nothing).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BinEntry {
    step: u8,
    /// The first band (group) in the high four bits, the last in the low four.
    bands: u8,
}

impl BinEntry {
    /// An empty entry, for initialising a `static` array of bins.
    pub const ZERO: BinEntry = BinEntry { step: 0, bands: 0 };
    /// A filler: moves the triangle index on by 255 and touches no band (first after last).
    const FILLER: BinEntry = BinEntry {
        step: u8::MAX,
        bands: 0x10,
    };

    /// The first band (group) it touches.
    #[inline(always)]
    fn first(self) -> u8 {
        self.bands >> 4
    }

    /// The last band (group) it touches.
    #[inline(always)]
    fn last(self) -> u8 {
        self.bands & 15
    }
}

/// How a frame is cut into bands ([`Pipeline::draw_banded`]).
#[derive(Debug, Clone, Copy)]
pub struct Banding<C> {
    /// Screen width in pixels.
    pub width: u32,
    /// Screen height in pixels.
    pub height: u32,
    /// Rows per band (the last band may have fewer).
    pub rows: u32,
    /// The colour each band starts from.
    pub background: C,
    /// The depth each band's depth buffer starts from (65535 for [`Compare::Less`]).
    ///
    /// [`Compare::Less`]: crate::depth::Compare::Less
    pub clear_depth: u16,
}

/// Why a banded draw could not start.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BandError {
    /// Zero rows per band, or a zero height.
    NoRows,
    /// A screen size the framebuffer cannot have.
    BadSize {
        /// Width.
        width: u32,
        /// Height.
        height: u32,
    },
    /// The band buffer is shorter than one band.
    BandBufferTooSmall {
        /// Words one band needs.
        needed: usize,
        /// Words given.
        actual: usize,
    },
    /// More visible triangles than bins.
    TooFewBins {
        /// Bins the frame needs.
        needed: usize,
        /// Bins given.
        actual: usize,
    },
    /// The depth stage does not cover a band's pixels within the viewport (a depth buffer of
    /// `width` x `rows` does).
    DepthTooSmall {
        /// The pixels of the first band the draw needs depths for.
        needed: Rectangle,
    },
    /// The mesh cannot be drawn with anti-aliased silhouettes
    /// ([`Pipeline::draw_banded_antialiased`]).
    Antialias(AntialiasError),
}

impl core::fmt::Display for BandError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NoRows => write!(f, "a band needs at least one row"),
            Self::BadSize { width, height } => write!(f, "bad screen size {width}x{height}"),
            Self::BandBufferTooSmall { needed, actual } => {
                write!(f, "band buffer has {actual} words, a band needs {needed}")
            }
            Self::TooFewBins { needed, actual } => {
                write!(
                    f,
                    "the frame needs {needed} bins but only {actual} were given"
                )
            }
            Self::DepthTooSmall { needed } => write!(
                f,
                "the depth buffer does not cover the {}x{} pixels at ({}, {}) a band needs",
                needed.size.width, needed.size.height, needed.top_left.x, needed.top_left.y
            ),
            Self::Antialias(e) => write!(f, "cannot anti-alias: {e}"),
        }
    }
}

impl core::error::Error for BandError {}

/// Per bin unit, one past the last entry of `bins` that touches it (0 when none does), so that
/// a band's scan stops there rather than at the end of the bins; [`UNIT_END_NONE`] when that
/// index does not fit a `u16` (the scan then reads to the end). 32 bytes, on the stack of a
/// banded draw.
pub(super) fn unit_ends(bins: &[BinEntry]) -> [u16; 16] {
    let mut ends = [0u16; 16];
    for (i, e) in bins.iter().enumerate() {
        let end = u16::try_from(i + 1).unwrap_or(UNIT_END_NONE);
        let (first, last) = (usize::from(e.first()), usize::from(e.last()));
        // A filler's first unit is beyond its last: it touches none.
        if first > last {
            continue;
        }
        // Most triangles touch one or two units: their ends without a loop.
        ends[first] = end;
        ends[last] = end;
        if last > first + 1 {
            for slot in ends.iter_mut().take(last).skip(first + 1) {
                *slot = end;
            }
        }
    }
    ends
}

/// [`unit_ends`]' mark of an end too far for a `u16`.
pub(super) const UNIT_END_NONE: u16 = u16::MAX;

/// The entries of `bins` that unit `unit`'s scan reads: those up to its end ([`unit_ends`]).
#[inline(always)]
pub(super) fn unit_bins<'b>(bins: &'b [BinEntry], ends: &[u16; 16], unit: u8) -> &'b [BinEntry] {
    match ends.get(usize::from(unit)) {
        Some(&end) if end != UNIT_END_NONE => bins.get(..usize::from(end)).unwrap_or(bins),
        _ => bins,
    }
}

/// The binned triangles (`bins`, in mesh order) that touch bin unit `unit` (band `b` is in unit
/// `b / ceil(bands / 16)`). `cursor` (entry, triangle) skips the leading entries that ended
/// above the unit: start it at `(0, 0)` and pass it again for later bands, in order.
#[inline(always)]
pub(super) fn unit_triangles<'b>(
    bins: &'b [BinEntry],
    unit: u8,
    cursor: &mut (usize, usize),
) -> impl Iterator<Item = usize> + 'b {
    let (mut lo, mut lo_t) = *cursor;
    while let Some(e) = bins
        .get(lo)
        .filter(|e| e.last() < unit || e.first() > e.last())
    {
        lo_t += usize::from(e.step);
        lo += 1;
    }
    *cursor = (lo, lo_t);
    let mut t = lo_t;
    bins.get(lo..)
        .unwrap_or_default()
        .iter()
        .filter_map(move |e| {
            t += usize::from(e.step);
            (e.first() <= unit && unit <= e.last()).then_some(t)
        })
}

impl<S, C, D, Sh, const BITS: u32, N> Pipeline<S, C, D, Sh, BITS, N>
where
    S: Scalar,
    C: Cull,
    D: DepthTest,
    Sh: Shading<S>,
    N: Numerics,
{
    /// The sub-pixel extent (left, top, right, bottom) of triangle `idx` once it is clipped (a
    /// corner outside the guard band, the rare path), or `None` when it draws nothing (counted
    /// in `stats`). Geometry only: no shading.
    #[inline(never)]
    fn clipped_extent<M: MeshSource<S>>(
        &self,
        mesh: &M,
        idx: [usize; 3],
        stats: &mut RenderStats,
    ) -> Option<[i32; 4]> {
        let Front::Clip { clip, codes, .. } = self.front_clip(mesh, idx, stats) else {
            return None;
        };
        stats.clipped += 1;
        let tri = clip.map(|pos| ClipVertex {
            pos,
            var: [0i32; 0],
        });
        let poly = clip_triangle(&tri, codes);
        if poly.len() < 3 {
            stats.outside += 1;
            return None;
        }
        let mut ps: heapless::Vec<_, { crate::clip::polygon::MAX_CLIPPED }> = heapless::Vec::new();
        for v in &poly {
            let _ = ps.push(self.project(&v.pos).0);
        }
        let area = super::front::polygon_area(ps.iter().copied());
        if area == 0 || !self.keeps(area) {
            stats.culled += 1;
            return None;
        }
        stats.drawn += 1;
        Some(ps.iter().fold(
            [i32::MAX, i32::MAX, i32::MIN, i32::MIN],
            |e, p: &SubPoint<BITS>| [e[0].min(p.x), e[1].min(p.y), e[2].max(p.x), e[3].max(p.y)],
        ))
    }

    /// Bins the frame's triangles for bands of `rows` rows on a screen of `height` rows (see
    /// [`BinEntry`]), after [`Pipeline::begin`]: writes the entries to `bins` and returns how
    /// many there are, and with `WIDEN` widens `pixels` to hold every pixel the triangles can
    /// touch (a banded draw that does not need them skips the columns). With `MARGIN`
    /// (anti-aliased silhouettes) each triangle reaches a pixel further each way, as a pixel it
    /// only partly covers can.
    ///
    /// # Errors
    /// [`BandError::TooFewBins`] when `bins` cannot hold them all.
    pub(crate) fn bin<M: MeshSource<S>, const MARGIN: bool, const WIDEN: bool>(
        &self,
        mesh: &M,
        scratch: &mut [VertexSlot<Sh::Stored>],
        (height, rows): (u32, u32),
        bins: &mut [BinEntry],
        stats: &mut RenderStats,
        pixels: &mut PixelRect,
    ) -> Result<usize, BandError> {
        let bands = height.div_ceil(rows.max(1));
        // Bands per unit of an entry's first and last, so that four bits hold any band.
        let group = bands.div_ceil(16);
        // Rows per unit, for 32-bit divisions (rows are below 2^32; a unit beyond them all
        // gives the same quotients, zero).
        let band_rows = u32::try_from(u64::from(rows) * u64::from(group)).unwrap_or(u32::MAX);
        let band_rows = core::num::NonZeroU32::new(band_rows).unwrap_or(core::num::NonZeroU32::MIN);
        let s = 1i64 << BITS;
        let mut count = 0usize;
        let mut wanted = 0usize;
        let mut prev = 0usize;
        let mut push = |entry: BinEntry| {
            wanted += 1;
            if let Some(slot) = bins.get_mut(count) {
                *slot = entry;
                count += 1;
            }
        };
        for t in 0..mesh.triangle_count() {
            let idx = mesh.triangle(t);
            let Some(v) = self.fetch(mesh, idx, scratch) else {
                stats.invalid += 1;
                continue;
            };
            let extent = if super::front::outside(&v) {
                match self.clipped_extent(mesh, idx, stats) {
                    Some(e) => e,
                    None => continue,
                }
            } else {
                if !self.visible(&v, stats, false) {
                    continue;
                }
                stats.drawn += 1;
                let (xs, ys) = ([v[0].0, v[1].0, v[2].0], [v[0].1, v[1].1, v[2].1]);
                [
                    xs[0].min(xs[1]).min(xs[2]),
                    ys[0].min(ys[1]).min(ys[2]),
                    xs[0].max(xs[1]).max(xs[2]),
                    ys[0].max(ys[1]).max(ys[2]),
                ]
            };
            let [left, top, right, bottom] = if MARGIN {
                let m = 1 << BITS;
                let [l, t, r, b] = extent;
                [
                    l.saturating_sub(m),
                    t.saturating_sub(m),
                    r.saturating_add(m),
                    b.saturating_add(m),
                ]
            } else {
                extent
            };
            // The rows whose sample lines the triangle can cross; columns to the whole pixel.
            let top = row_at_or_below(i64::from(top), s).max(0);
            let bottom = row_at_or_below(i64::from(bottom), s).min(i64::from(height));
            if top >= bottom {
                continue;
            }
            if WIDEN {
                *pixels = pixels.union(&PixelRect {
                    x0: i64::from(left) >> BITS,
                    y0: top,
                    x1: (i64::from(right) >> BITS) + 1,
                    y1: bottom,
                });
            }
            while t - prev > usize::from(u8::MAX) {
                push(BinEntry::FILLER);
                prev += usize::from(u8::MAX);
            }
            // 0 <= top < bottom <= height.
            let (top, bottom) = (top as u32, bottom as u32);
            let (first, last) = ((top / band_rows) as u8, ((bottom - 1) / band_rows) as u8);
            push(BinEntry {
                step: (t - prev) as u8,
                bands: first << 4 | last,
            });
            prev = t;
        }
        if wanted > bins.len() {
            return Err(BandError::TooFewBins {
                needed: wanted,
                actual: bins.len(),
            });
        }
        Ok(count)
    }

    /// Draws the binned triangles (`bins`, in mesh order) that touch bin unit `unit` (band `b`
    /// is in unit `b / ceil(bands / 16)`). `cursor` (entry, triangle) skips the leading entries
    /// that ended above the unit: start it at `(0, 0)` and pass it again for later bands, in
    /// order.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn draw_unit<T, M, P: DepthFrom<D>>(
        &mut self,
        src: &mut P,
        target: &mut T,
        mesh: &M,
        scratch: &mut [VertexSlot<Sh::Stored>],
        bins: &[BinEntry],
        unit: u8,
        cursor: &mut (usize, usize),
        stats: &mut RenderStats,
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        let (mut lo, mut lo_t) = *cursor;
        while let Some(e) = bins
            .get(lo)
            .filter(|e| e.last() < unit || e.first() > e.last())
        {
            lo_t += usize::from(e.step);
            lo += 1;
        }
        *cursor = (lo, lo_t);
        let mut t = lo_t;
        // `first <= unit <= last` as two compares of the packed byte (a filler, first after
        // last, fails one of them).
        let below = (u16::from(unit) + 1) << 4;
        for e in bins.get(lo..).unwrap_or_default() {
            t += usize::from(e.step);
            if u16::from(e.bands) < below && e.last() >= unit {
                // The front end's tests passed when the triangle was binned.
                let idx = mesh.triangle(t);
                let Some(v) = self.fetch(mesh, idx, scratch) else {
                    continue;
                };
                if super::front::outside(&v) {
                    self.draw_outside(src, target, mesh, idx, scratch, stats)?;
                } else {
                    self.draw_visible(src, target, mesh, idx, v, scratch, stats)?;
                }
            }
        }
        Ok(())
    }

    /// Draws a mesh one horizontal band at a time, for a microcontroller that cannot hold a whole
    /// frame: each band is drawn into `band` (a buffer of `banding.rows` rows) and handed to
    /// `on_band` (where firmware starts the transfer to the display), then reused for the next.
    ///
    /// The pipeline's depth stage must hold `banding.rows` rows too (a [`DepthBuffer`] of
    /// `width` x `rows`); it is cleared to `banding.clear_depth` before each band. Triangles are
    /// binned once per frame (`bins` holds one [`BinEntry`] per visible triangle, plus a filler
    /// for every gap of 255 triangles without one), so each band draws only the triangles that
    /// touch it, in mesh order. `scratch` is as in [`Pipeline::draw`]: with a slot per vertex,
    /// each vertex is transformed and shaded once a frame, however many bands use it. The pixels
    /// are exactly those of a whole-frame [`Pipeline::draw`] of the same scene, for any band
    /// height.
    ///
    /// [`DepthBuffer`]: crate::depth::DepthBuffer
    ///
    /// # Errors
    /// [`BandError`] for a band buffer or depth stage too small for a band, zero rows, or too
    /// few bins (nothing is drawn then).
    pub fn draw_banded<Px, M, F>(
        &mut self,
        mesh: &M,
        banding: &Banding<Px>,
        band: &mut [Px::Word],
        bins: &mut [BinEntry],
        scratch: &mut [VertexSlot<Sh::Stored>],
        mut on_band: F,
    ) -> Result<RenderStats, BandError>
    where
        Px: Storage,
        Sh: Shading<S, Color = Px>,
        M: MeshSource<S>,
        F: FnMut(&Band<'_, Px>),
    {
        let (width, height, rows) = (banding.width, banding.height, banding.rows);
        if rows == 0 || height == 0 {
            return Err(BandError::NoRows);
        }
        let needed = Framebuffer::<Px>::required_len(width, rows.min(height))
            .ok_or(BandError::BadSize { width, height })?;
        if band.len() < needed {
            return Err(BandError::BandBufferTooSmall {
                needed,
                actual: band.len(),
            });
        }
        // Every band's depth entries: checked on the first (the others have the same rows).
        self.depth.start_band(0, banding.clear_depth);
        let first = Rectangle::new(Point::zero(), Size::new(width, rows.min(height)))
            .intersection(&self.viewport.rectangle());
        if first.size.width > 0 && first.size.height > 0 && !self.depth.covers(&first) {
            return Err(BandError::DepthTooSmall { needed: first });
        }
        let scratch = self.begin(mesh, scratch);
        let mut stats = RenderStats {
            triangles: mesh.triangle_count().min(u32::MAX as usize) as u32,
            ..RenderStats::default()
        };
        let mut pixels = PixelRect::EMPTY;
        let count = self.bin::<M, false, false>(
            mesh,
            scratch,
            (height, rows),
            bins,
            &mut stats,
            &mut pixels,
        )?;
        let bins = &bins[..count];
        let bands = height.div_ceil(rows);
        let group = bands.div_ceil(16);
        let ends = unit_ends(bins);
        let mut cursor = (0, 0);
        let mut scratch_stats = RenderStats::default();
        for b in 0..bands {
            let y0 = b * rows;
            let h = rows.min(height - y0);
            let len = Framebuffer::<Px>::required_len(width, h).unwrap_or(0);
            let Ok(mut fb) = Framebuffer::<Px>::new(&mut band[..len], width, h) else {
                return Err(BandError::BadSize { width, height });
            };
            let _ = DrawTarget::clear(&mut fb, banding.background);
            self.depth.start_band(y0 as i32, banding.clear_depth);
            let mut strip = Band::new(fb, y0 as i32);
            {
                let mut target = ClipTo::new(&mut strip, self.viewport.rectangle());
                let Ok(()) = self.draw_unit(
                    &mut super::Own,
                    &mut target,
                    mesh,
                    scratch,
                    unit_bins(bins, &ends, (b / group) as u8),
                    (b / group) as u8,
                    &mut cursor,
                    &mut scratch_stats,
                );
            }
            on_band(&strip);
        }
        Ok(stats)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::vec::Vec;

    fn entry(first: u8, last: u8) -> BinEntry {
        BinEntry {
            step: 1,
            bands: first << 4 | last,
        }
    }

    /// Per unit, one past the last entry touching it, by definition.
    fn naive_ends(bins: &[BinEntry]) -> [usize; 16] {
        let mut ends = [0; 16];
        for (u, end) in ends.iter_mut().enumerate() {
            let touches = |e: &BinEntry| usize::from(e.first()) <= u && u <= usize::from(e.last());
            *end = bins.iter().rposition(touches).map_or(0, |i| i + 1);
        }
        ends
    }

    #[test]
    fn unit_ends_are_one_past_each_units_last_entry() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = |n: u64| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % n) as u8
        };
        for _ in 0..500 {
            let len = usize::from(next(60));
            let bins: Vec<BinEntry> = (0..len)
                .map(|_| match next(8) {
                    0 => BinEntry::FILLER,
                    // Most span one or two units, some up to all sixteen.
                    1 => {
                        let first = next(16);
                        entry(first, first + next(16 - u64::from(first)))
                    }
                    _ => {
                        let first = next(15);
                        entry(first, first + next(2))
                    }
                })
                .collect();
            let ends = unit_ends(&bins);
            let want = naive_ends(&bins);
            for u in 0..16 {
                assert_eq!(usize::from(ends[u]), want[u], "unit {u} of {bins:?}");
                // The scan of the cut bins meets every entry of its unit.
                let cut = unit_bins(&bins, &ends, u as u8);
                let count = |b: &[BinEntry]| {
                    b.iter()
                        .filter(|e| e.first() <= u as u8 && u as u8 <= e.last())
                        .count()
                };
                assert_eq!(count(cut), count(&bins));
            }
        }
    }

    #[test]
    fn unit_ends_beyond_a_u16_read_to_the_end() {
        let mut bins = std::vec![BinEntry::FILLER; 70_000];
        bins[100] = entry(5, 5);
        bins[65_533] = entry(2, 3);
        bins[65_534] = entry(3, 4);
        bins[69_999] = entry(4, 4);
        let ends = unit_ends(&bins);
        assert_eq!(ends[5], 101);
        assert_eq!(ends[2], 65_534);
        assert_eq!(ends[3], UNIT_END_NONE);
        assert_eq!(ends[4], UNIT_END_NONE);
        assert_eq!(ends[0], 0);
        assert_eq!(unit_bins(&bins, &ends, 5).len(), 101);
        assert_eq!(unit_bins(&bins, &ends, 2).len(), 65_534);
        assert_eq!(unit_bins(&bins, &ends, 4).len(), 70_000);
        assert_eq!(unit_bins(&bins, &ends, 3).len(), 70_000);
        assert!(unit_bins(&bins, &ends, 0).is_empty());
    }
}
