//! Polygons, concave or self-intersecting, filled by a scanline with an edge table and an active
//! edge table. Edges are stepped by the triangle fill's exact edge walk under its top-left rule, so
//! a polygon lights exactly the pixels of any triangulation of it; neighbours never overlap or gap.

use crate::geom::{PixelRect, SubPoint, DEFAULT_SUBPIXEL_BITS};
use crate::raster::edge::{row_at_or_below, EdgeWalk};
use crate::surface::Surface;
use core::cmp::Ordering;
use core::fmt;
use embedded_graphics_core::primitives::Rectangle;
use heapless::Vec;

/// How overlapping parts of a polygon are filled.
///
/// Both count the edges that cross a pixel's row at or left of its centre: an edge the outline runs
/// down counts +1, one it runs up counts -1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FillRule {
    /// Filled where the count of crossings is odd: overlapping parts cancel, so a pentagram has a
    /// hollow centre.
    EvenOdd,
    /// Filled where the winding number (the signed count) is not zero: everything the outline
    /// encloses is filled, so a pentagram is solid.
    NonZero,
}

impl FillRule {
    #[inline(always)]
    fn is_inside(self, winding: i32) -> bool {
        match self {
            // The signed sum has the parity of the plain crossing count.
            Self::EvenOdd => winding & 1 != 0,
            Self::NonZero => winding != 0,
        }
    }
}

/// Why a polygon could not be built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PolygonError {
    /// More vertices than the polygon's capacity `N`.
    TooManyVertices {
        /// The capacity `N`.
        capacity: usize,
        /// The number of vertices given.
        given: usize,
    },
}

impl fmt::Display for PolygonError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooManyVertices { capacity, given } => {
                write!(
                    f,
                    "polygon has {given} vertices, more than its capacity of {capacity}"
                )
            }
        }
    }
}

impl core::error::Error for PolygonError {}

/// Why [`fill_polygon`] failed: the polygon could not be built, or the target reported an error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PolygonFillError<E> {
    /// The vertices did not make a polygon; nothing was drawn.
    Polygon(PolygonError),
    /// The target failed part way; the rows before the failing span were drawn.
    Target(E),
}

impl<E> From<PolygonError> for PolygonFillError<E> {
    fn from(e: PolygonError) -> Self {
        Self::Polygon(e)
    }
}

impl<E: fmt::Display> fmt::Display for PolygonFillError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Polygon(e) => e.fmt(f),
            Self::Target(e) => write!(f, "draw target error: {e}"),
        }
    }
}

impl<E: core::error::Error + 'static> core::error::Error for PolygonFillError<E> {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Self::Polygon(e) => Some(e),
            Self::Target(e) => Some(e),
        }
    }
}

/// One entry of the edge table: a non-horizontal edge that crosses at least one row's sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Edge {
    /// The upper end, raw sub-pixel units.
    top: (i32, i32),
    /// The lower end, raw sub-pixel units.
    bottom: (i32, i32),
    /// The first row whose sample lies on the edge (`y_top <= yc`).
    first_row: i32,
    /// The first row below the edge (`yc >= y_bottom`): the edge is half-open so that the two edges
    /// meeting at a vertex are never both counted on the same row.
    end_row: i32,
    /// +1 when the outline runs down this edge, -1 when it runs up.
    winding: i8,
}

/// One entry of the active edge table.
#[derive(Debug, Clone, Copy)]
struct Active {
    walk: EdgeWalk,
    end_row: i32,
    winding: i8,
}

/// A closed polygon ready to fill, with room for `N` vertices (= edges), fixed at compile time.
///
/// The last vertex connects back to the first. The polygon may be concave or self-intersecting; the
/// [`FillRule`] decides what is inside. Building it sorts the edges once, so a shape drawn every
/// frame (a gauge needle, a map outline) pays only for the row walk. Fills are exact, integer only.
///
/// - Fewer than 3 vertices, or no interior (all vertices collinear): nothing is drawn, no error.
/// - A vertex outside the guard band ([`crate::geom::GUARD_BAND_PIXELS`]): nothing is drawn, as
///   for a triangle.
/// - More than `N` vertices: [`PolygonError::TooManyVertices`].
///
/// Memory: the polygon holds up to `N` edges of 28 bytes; [`Polygon::fill`] keeps an active edge
/// table of `N` entries (48 bytes each) on the stack.
///
/// ```
/// use rasterizer_core::geom::SubPoint;
/// use rasterizer_core::raster::polygon::{FillRule, Polygon};
/// use rasterizer_core::surface::Framebuffer;
/// use embedded_graphics_core::{pixelcolor::Rgb565, prelude::*};
///
/// let mut buf = [0u16; 16 * 16];
/// let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 16, 16).unwrap();
/// // An L shape, in whole pixels converted to 28.4 fixed point.
/// let px = |x: i32, y: i32| SubPoint::new(x * 16, y * 16);
/// let outline = [px(2, 2), px(6, 2), px(6, 10), px(12, 10), px(12, 14), px(2, 14)];
/// let shape = Polygon::<8>::new(&outline).unwrap();
/// shape.fill(&mut fb, FillRule::NonZero, Rgb565::CYAN).unwrap();
///
/// assert_eq!(fb.pixel(Point::new(2, 2)), Some(Rgb565::CYAN)); // top-left corner is inside
/// assert_eq!(fb.pixel(Point::new(6, 2)), Some(Rgb565::BLACK)); // right edge is not
/// assert_eq!(fb.pixel(Point::new(11, 13)), Some(Rgb565::CYAN));
/// assert_eq!(fb.pixel(Point::new(8, 8)), Some(Rgb565::BLACK)); // the notch of the L
/// ```
#[derive(Debug, Clone)]
pub struct Polygon<const N: usize, const BITS: u32 = DEFAULT_SUBPIXEL_BITS> {
    /// The edge table: the edges that cross a row's sample, sorted by first row.
    edges: Vec<Edge, N>,
    /// The largest `end_row` of the edges.
    end_row: i32,
}

impl<const N: usize, const BITS: u32> Polygon<N, BITS> {
    /// Builds the edge table of the closed polygon through `vertices`, in order.
    ///
    /// # Errors
    /// [`PolygonError::TooManyVertices`] when there are more than `N` vertices.
    pub fn new(vertices: &[SubPoint<BITS>]) -> Result<Self, PolygonError> {
        #[allow(clippy::let_unit_value)]
        let () = SubPoint::<BITS>::VALID;
        if vertices.len() > N {
            return Err(PolygonError::TooManyVertices {
                capacity: N,
                given: vertices.len(),
            });
        }
        let mut polygon = Self {
            edges: Vec::new(),
            end_row: i32::MIN,
        };
        if vertices.len() < 3 || !vertices.iter().all(|p| p.in_guard_band()) {
            return Ok(polygon);
        }
        let s = 1i64 << BITS;
        let next = vertices.iter().cycle().skip(1);
        for (&a, &b) in vertices.iter().zip(next) {
            let (top, bottom, winding) = match a.y.cmp(&b.y) {
                Ordering::Less => (a, b, 1),
                Ordering::Greater => (b, a, -1),
                // A horizontal edge never crosses a row's sample line.
                Ordering::Equal => continue,
            };
            let first_row = row_at_or_below(i64::from(top.y), s);
            let end_row = row_at_or_below(i64::from(bottom.y), s);
            if first_row >= end_row {
                // Lies between two samples: it crosses no row.
                continue;
            }
            // Rows of i32 coordinates fit i32. The push cannot fail: one edge per vertex.
            let _ = polygon.edges.push(Edge {
                top: (top.x, top.y),
                bottom: (bottom.x, bottom.y),
                first_row: first_row as i32,
                end_row: end_row as i32,
                winding,
            });
            polygon.end_row = polygon.end_row.max(end_row as i32);
        }
        polygon.edges.sort_unstable_by_key(|e| e.first_row);
        Ok(polygon)
    }

    /// The pixels the fill can touch (every pixel whose centre may lie inside);
    /// `Rectangle::zero()` for a polygon that fills nothing.
    pub fn pixel_bounds(&self) -> Rectangle {
        let mut r = PixelRect::EMPTY;
        for e in &self.edges {
            let xs = (i64::from(e.top.0), i64::from(e.bottom.0));
            r = r.union(&PixelRect {
                x0: xs.0.min(xs.1) >> BITS,
                y0: i64::from(e.first_row),
                x1: (xs.0.max(xs.1) >> BITS) + 1,
                y1: i64::from(e.end_row),
            });
        }
        r.to_rectangle()
    }

    /// Fills the polygon in one colour, clipped to the surface's clip area.
    ///
    /// A pixel is filled when its centre is inside by `rule`; a centre exactly on an edge follows
    /// the top-left rule, so a pixel on an edge two polygons share is drawn by exactly one of them.
    /// Every pixel is written at most once. Only the rows inside the clip area are walked.
    ///
    /// # Errors
    /// The first error the surface returns; the spans before it have been drawn.
    pub fn fill<S: Surface>(
        &self,
        surface: &mut S,
        rule: FillRule,
        color: S::Color,
    ) -> Result<(), S::Error> {
        let Some(first) = self.edges.first() else {
            return Ok(());
        };
        let clip = PixelRect::from_rectangle(&surface.clip_area());
        if clip.is_empty() {
            return Ok(());
        }
        let s = 1i64 << BITS;
        let end = i64::from(self.end_row).min(clip.y1);
        let mut row = i64::from(first.first_row).max(clip.y0);
        let mut aet: Vec<Active, N> = Vec::new();
        // The first edge-table entry not yet moved to the active table.
        let mut next = 0;
        while row < end {
            aet.retain(|a| i64::from(a.end_row) > row);
            while let Some(e) = self.edges.get(next) {
                if i64::from(e.first_row) > row {
                    break;
                }
                next += 1;
                // Edges that ended above the first visible row are skipped, and the rest set up
                // directly at this row, so nothing above the clip area is walked.
                if i64::from(e.end_row) > row {
                    let top = (i64::from(e.top.0), i64::from(e.top.1));
                    let bottom = (i64::from(e.bottom.0), i64::from(e.bottom.1));
                    // Cannot fail: the active table holds a subset of the N edges.
                    let _ = aet.push(Active {
                        walk: EdgeWalk::new(top, bottom, s, row),
                        end_row: e.end_row,
                        winding: e.winding,
                    });
                }
            }
            if aet.is_empty() {
                match self.edges.get(next) {
                    Some(e) => {
                        row = i64::from(e.first_row);
                        continue;
                    }
                    None => break,
                }
            }
            sort_by_column(&mut aet);
            emit_row(surface, &aet, row, &clip, rule, color)?;
            for a in aet.iter_mut() {
                a.walk.step();
            }
            row += 1;
        }
        Ok(())
    }
}

/// Insertion sort by crossing column: from one row to the next edges swap places only where they
/// cross, so the table is nearly sorted and this is close to one pass.
#[inline(always)]
fn sort_by_column(aet: &mut [Active]) {
    for i in 1..aet.len() {
        let mut j = i;
        while j > 0 && aet[j - 1].walk.col() > aet[j].walk.col() {
            aet.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// Draws one row: between consecutive crossings the winding number is constant, so the row is a run
/// of half-open spans `[c_i, c_i+1)`. Touching spans are merged into one call.
#[inline(always)]
fn emit_row<S: Surface>(
    surface: &mut S,
    aet: &[Active],
    row: i64,
    clip: &PixelRect,
    rule: FillRule,
    color: S::Color,
) -> Result<(), S::Error> {
    // Inside the clip area and the guard band, so every value below fits i32.
    let mut emit = |x0: i64, x1: i64| {
        surface.fill_span_in_clip(x0 as i32, row as i32, (x1 - x0) as u32, color)
    };
    let mut winding = 0i32;
    let mut pending: Option<(i64, i64)> = None;
    for pair in aet.windows(2) {
        winding += i32::from(pair[0].winding);
        if !rule.is_inside(winding) {
            continue;
        }
        let x0 = pair[0].walk.col().max(clip.x0);
        let x1 = pair[1].walk.col().min(clip.x1);
        if x0 >= x1 {
            continue;
        }
        pending = match pending {
            Some((start, end)) if end == x0 => Some((start, x1)),
            Some((start, end)) => {
                emit(start, end)?;
                Some((x0, x1))
            }
            None => Some((x0, x1)),
        };
    }
    match pending {
        Some((start, end)) => emit(start, end),
        None => Ok(()),
    }
}

/// Builds a polygon of capacity `N` and fills it in one call.
///
/// Give the capacity explicitly, e.g. `fill_polygon::<_, 16, _>(...)`. Use [`Polygon`] to fill the
/// same shape more than once without rebuilding its edge table.
///
/// # Errors
/// [`PolygonFillError::Polygon`] when there are more than `N` vertices (nothing is drawn);
/// [`PolygonFillError::Target`] with the first error the surface returns.
pub fn fill_polygon<S: Surface, const N: usize, const BITS: u32>(
    surface: &mut S,
    vertices: &[SubPoint<BITS>],
    rule: FillRule,
    color: S::Color,
) -> Result<(), PolygonFillError<S::Error>> {
    Polygon::<N, BITS>::new(vertices)?
        .fill(surface, rule, color)
        .map_err(PolygonFillError::Target)
}
