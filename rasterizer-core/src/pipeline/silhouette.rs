//! Anti-aliased silhouettes ([`Pipeline::draw_antialiased`]): the draws that find a mesh's
//! silhouette edges through its adjacency and hand their triangles to the raster stage's
//! two-pass silhouette fill ([`crate::raster::silhouette`]).

use super::band::{unit_bins, unit_ends, unit_triangles};
use super::front::{outside, ShaderColor};
use super::perspective::{DirectColor, PerspectiveColor};
use super::vertex::Projected;
use super::{
    AntialiasError, BandError, Banding, BinEntry, DepthFrom, DrawError, Front, MeshSource, Own,
    Pipeline, RenderStats, VertexSlot,
};
use crate::cull::Cull;
use crate::depth::DepthTest;
use crate::geom::PixelRect;
use crate::geom::SubPoint;
use crate::math::Scalar;
use crate::mesh::NO_NEIGHBOUR;
use crate::numerics::Numerics;
use crate::raster::fused::fill_fused_silhouette;
use crate::shade::Shading;
use crate::surface::{Band, Framebuffer, Storage};
use crate::surface::{ClipTo, Surface};
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;

impl<S, C, D, Sh, const BITS: u32, N> Pipeline<S, C, D, Sh, BITS, N>
where
    S: Scalar,
    C: Cull,
    D: DepthTest,
    Sh: Shading<S>,
    N: Numerics,
{
    /// Whether this pipeline's numerics can draw silhouettes anti-aliased.
    pub(super) const ANTIALIASES: bool = Self::FUSED || Self::FUSED_PERSPECTIVE;

    /// Why `mesh` cannot be drawn anti-aliased into a `T`, if it cannot.
    pub(super) fn antialias_check<T: Surface, M: MeshSource<S>>(
        mesh: &M,
    ) -> Result<(), AntialiasError> {
        if !T::READ_BACK {
            return Err(AntialiasError::CannotReadBack);
        }
        if !mesh.has_adjacency() {
            return Err(AntialiasError::NoAdjacency);
        }
        if !Self::ANTIALIASES {
            return Err(AntialiasError::Numerics);
        }
        Ok(())
    }

    /// The silhouette edges of visible triangle `t` (corners `v`, all inside the guard band):
    /// bit `k` for the edge from corner `k` to corner `k + 1` when no triangle lies across it, or
    /// the one that does faces the other way on screen (or is flat there). A neighbour with a
    /// corner outside the guard band counts as facing the same way.
    #[inline(always)]
    pub(super) fn silhouette_mask<M: MeshSource<S>>(
        &self,
        mesh: &M,
        t: usize,
        v: &[Projected; 3],
        scratch: &[VertexSlot<Sh::Stored>],
    ) -> u8 {
        let area = |v: &[Projected; 3]| {
            let xs = [v[0].0, v[1].0, v[2].0].map(i64::from);
            let ys = [v[0].1, v[1].1, v[2].1].map(i64::from);
            ((xs[1] - xs[0]) * (ys[2] - ys[0]) - (xs[2] - xs[0]) * (ys[1] - ys[0])).signum()
        };
        let own = area(v);
        let count = mesh.triangle_count();
        let mut mask = 0;
        for (k, &n) in mesh.neighbours(t).iter().enumerate() {
            let silhouette = if n == NO_NEIGHBOUR || n as usize >= count {
                true
            } else {
                match self.fetch(mesh, mesh.triangle(n as usize), scratch) {
                    None => true,
                    Some(w) if outside(&w) => false,
                    Some(w) => area(&w) != own,
                }
            };
            mask |= u8::from(silhouette) << k;
        }
        mask
    }

    /// Draws a visible triangle (as [`Pipeline::draw_visible`]) in one pass of an anti-aliased
    /// draw: the first (`fringe` false) draws what is opaque, counting the triangle as drawn;
    /// the second blends its silhouette edges' pixels.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn draw_visible_silhouette<T, M, P: DepthFrom<D>>(
        &mut self,
        src: &mut P,
        target: &mut T,
        mesh: &M,
        t: usize,
        v: [Projected; 3],
        scratch: &mut [VertexSlot<Sh::Stored>],
        stats: &mut RenderStats,
        fringe: bool,
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        let idx = mesh.triangle(t);
        let mask = self.silhouette_mask(mesh, t, &v, scratch);
        if mask == 0 {
            return if fringe {
                Ok(())
            } else {
                self.draw_visible(src, target, mesh, idx, v, scratch, stats)
            };
        }
        if !fringe {
            stats.drawn += 1;
        }
        if self.area.is_empty() {
            return Ok(());
        }
        if Sh::NEEDS_FACE {
            self.face(mesh, idx);
        }
        let p = v.map(|(x, y, _)| SubPoint::<BITS>::raw(x, y));
        let mut var = if Sh::NEEDS_WORLD && !mesh.has_normals() {
            self.face_normal_values(mesh, idx)
        } else {
            [
                self.slot_values(mesh, idx[0], scratch),
                self.slot_values(mesh, idx[1], scratch),
                self.slot_values(mesh, idx[2], scratch),
            ]
        };
        if Sh::NEEDS_TRIANGLE {
            self.shading.triangle(&mut var);
        }
        let area = self.area;
        if Self::FUSED_PERSPECTIVE {
            let sv = self.screen_vertices(mesh, idx, &v, var);
            let depth = src.pick(&mut self.depth);
            if let Some((fv, color)) = DirectColor::<S, Sh, N>::new(&self.shading, &sv) {
                return fill_fused_silhouette::<_, _, _, _, BITS>(
                    target, depth, &fv, &area, color, mask, fringe,
                );
            }
            let (fv, color) = PerspectiveColor::<S, Sh, N>::new(&self.shading, &sv);
            return fill_fused_silhouette::<_, _, _, _, BITS>(
                target, depth, &fv, &area, color, mask, fringe,
            );
        }
        let fv = [0, 1, 2].map(|k| (p[k], v[k].2, var[k]));
        let color = ShaderColor::<S, Sh, N>(&self.shading, core::marker::PhantomData);
        fill_fused_silhouette::<_, _, _, _, BITS>(
            target,
            src.pick(&mut self.depth),
            &fv,
            &area,
            color,
            mask,
            fringe,
        )
    }

    /// Draws a mesh as [`Pipeline::draw`] does, with its silhouette edges anti-aliased: each
    /// pixel a silhouette edge crosses is blended with what lies beneath by the fraction of it
    /// the mesh covers (within 1/16 of the exact area; `docs/ACCURACY.md`), after the rest of
    /// the mesh is drawn. A silhouette edge is one whose neighbouring triangle (from the mesh's
    /// adjacency) faces the other way on screen, or that has none. Edges between triangles that
    /// both face the viewer are drawn as by [`Pipeline::draw`], so no seam appears.
    ///
    /// A pixel at least half covered stores its depth; a less covered one does not, so what is
    /// drawn behind it later replaces it: draw the far objects of a scene first. Triangles
    /// that need clipping in homogeneous space, or that reach more than
    /// [`super::AA_RANGE_PIXELS`] pixels from the screen's origin, are
    /// drawn without anti-aliasing.
    ///
    /// # Errors
    /// [`DrawError::Antialias`] when the target cannot read back, the mesh has no adjacency, or
    /// the numerics do not take the fused span loop (nothing is drawn); otherwise as
    /// [`Pipeline::draw`].
    pub fn draw_antialiased<T, M>(
        &mut self,
        target: &mut T,
        mesh: &M,
        scratch: &mut [VertexSlot<Sh::Stored>],
    ) -> Result<RenderStats, DrawError<T::Error>>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        Self::antialias_check::<T, M>(mesh).map_err(DrawError::Antialias)?;
        let target = &mut ClipTo::new(target, self.viewport.rectangle());
        let needed = target.clip_area();
        if needed.size.width > 0 && needed.size.height > 0 && !self.depth.covers(&needed) {
            return Err(DrawError::DepthTooSmall { needed });
        }
        let scratch = self.begin(mesh, scratch);
        let mut stats = RenderStats {
            triangles: mesh.triangle_count().min(u32::MAX as usize) as u32,
            ..RenderStats::default()
        };
        for t in 0..mesh.triangle_count() {
            let idx = mesh.triangle(t);
            let Some(v) = self.fetch(mesh, idx, scratch) else {
                stats.invalid += 1;
                continue;
            };
            if outside(&v) {
                self.draw_outside(&mut Own, target, mesh, idx, scratch, &mut stats)?;
            } else if self.visible(&v, &mut stats, false) {
                self.draw_visible_silhouette(
                    &mut Own, target, mesh, t, v, scratch, &mut stats, false,
                )?;
            }
        }
        let mut again = RenderStats::default();
        for t in 0..mesh.triangle_count() {
            let Some(v) = self.fetch(mesh, mesh.triangle(t), scratch) else {
                continue;
            };
            if !outside(&v) && self.visible(&v, &mut again, false) {
                self.draw_visible_silhouette(
                    &mut Own, target, mesh, t, v, scratch, &mut again, true,
                )?;
            }
        }
        Ok(stats)
    }

    /// [`Pipeline::draw_banded`] with the silhouettes anti-aliased as
    /// [`Pipeline::draw_antialiased`] draws them: each band draws its triangles' opaque pixels,
    /// then blends their silhouette edges' pixels. The pixels are exactly those of a
    /// whole-frame [`Pipeline::draw_antialiased`] of the same scene on the band's background,
    /// for any band height. A triangle is binned to the bands a pixel beyond it reaches, so a
    /// frame may need a few more bins than [`Pipeline::draw_banded`].
    ///
    /// # Errors
    /// As [`Pipeline::draw_banded`], and [`BandError::Antialias`] when the mesh has no
    /// adjacency or the numerics do not take the fused span loop (nothing is drawn).
    pub fn draw_banded_antialiased<Px, M, F>(
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
        Self::antialias_check::<Framebuffer<'_, Px>, M>(mesh).map_err(BandError::Antialias)?;
        // The checks and the band loop of `draw_banded`, kept apart so that its code (and
        // its instruction counts) stay as they were.
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
        let count = self.bin::<M, true, false>(
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
                let unit = (b / group) as u8;
                let start = cursor;
                for fringe in [false, true] {
                    cursor = start;
                    let Ok(()) = self.draw_unit_silhouette(
                        &mut Own,
                        &mut target,
                        mesh,
                        scratch,
                        unit_triangles(unit_bins(bins, &ends, unit), unit, &mut cursor),
                        &mut scratch_stats,
                        fringe,
                    );
                }
            }
            on_band(&strip);
        }
        Ok(stats)
    }

    /// One pass of an anti-aliased band ([`Pipeline::draw_banded_antialiased`]): the binned
    /// triangles of bin unit `unit`, as [`Pipeline::draw_unit`] draws them.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn draw_unit_silhouette<T, M, P: DepthFrom<D>>(
        &mut self,
        src: &mut P,
        target: &mut T,
        mesh: &M,
        scratch: &mut [VertexSlot<Sh::Stored>],
        entries: impl Iterator<Item = usize>,
        stats: &mut RenderStats,
        fringe: bool,
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        for t in entries {
            match self.front_again(mesh, t, scratch) {
                Front::Skip => {}
                Front::Inside { v, .. } => {
                    let v = v.map(|(p, z)| (p.x, p.y, z));
                    self.draw_visible_silhouette(src, target, mesh, t, v, scratch, stats, fringe)?;
                }
                front @ Front::Clip { .. } => {
                    if !fringe {
                        self.draw_front(src, target, mesh, front, scratch, stats)?;
                    }
                }
            }
        }
        Ok(())
    }
}
