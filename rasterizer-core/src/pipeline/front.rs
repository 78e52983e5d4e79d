//! The front end every draw call shares: fetch a triangle, read its vertices' slots, reject it
//! when it faces away or lies outside the view, clip what crosses the guard band, and hand what is
//! left to the rasterizer.

use super::perspective::{DirectColor, PerspectiveColor};
use super::vertex::{Projected, OUTSIDE};
use super::{DepthFrom, Pipeline, RenderStats, VertexSlot};
use crate::clip::polygon::{clip_triangle, outcode, trivially_outside, ClipVertex, Outcode};
use crate::cull::Cull;
use crate::depth::DepthTest;
use crate::geom::{SubPoint, MAX_VARYINGS};
use crate::math::{Scalar, Vec4};
use crate::mesh::MeshSource;
use crate::numerics::{Dither, Numerics, SpanStart};
use crate::raster::fused::{fill_fused, misses_every_pixel, FusedColor, FusedVertex, Precision};
use crate::raster::interp::{fill_triangle_interp_with, ScreenVertex};
use crate::raster::triangle::setup::centre_count;
use crate::shade::Shading;
use crate::surface::Surface;

/// What the front end made of a triangle.
pub(super) enum Front<S, const BITS: u32> {
    /// Nothing to draw (already counted).
    Skip,
    /// Every vertex inside the clip volume's guard band: projected, facing the right way.
    Inside {
        idx: [usize; 3],
        v: [(SubPoint<BITS>, u16); 3],
    },
    /// Needs clipping in homogeneous space.
    Clip {
        idx: [usize; 3],
        clip: [Vec4<S>; 3],
        codes: [Outcode; 3],
    },
}

/// Whether a corner lies outside the guard band ([`OUTSIDE`] in its slot).
#[inline(always)]
pub(super) fn outside(v: &[Projected; 3]) -> bool {
    v[0].0 == OUTSIDE || v[1].0 == OUTSIDE || v[2].0 == OUTSIDE
}

/// A shader as the fused span loop's colour source, dithered as `N` says.
pub(super) struct ShaderColor<'a, S, Sh, N>(
    pub(super) &'a Sh,
    pub(super) core::marker::PhantomData<(S, N)>,
);

impl<S: Scalar, Sh: Shading<S>, N: Numerics> FusedColor<Sh::Color> for ShaderColor<'_, S, Sh, N> {
    const PRECISION: Precision = Precision {
        frac: Sh::FUSED_FRAC,
        offset: Sh::FUSED_OFFSET,
    };
    const AT: bool = !matches!(N::DITHER, Dither::None);
    const PAIRED: bool = Sh::FUSED_PAIRED;
    #[inline(always)]
    fn color(&self, acc: &[u32; MAX_VARYINGS]) -> Sh::Color {
        self.0.pixel_fused(acc)
    }
    #[inline(always)]
    fn color_at(&self, acc: &[u32; MAX_VARYINGS], x: i32, y: i32) -> Sh::Color {
        self.0.pixel_fused_dithered(acc, N::DITHER.threshold(x, y))
    }
}

/// A screen vertex's position: one named function, so that every area taken over screen
/// vertices shares one copy of [`polygon_area`].
fn position<V, const BITS: u32>(v: &ScreenVertex<V, BITS>) -> SubPoint<BITS> {
    v.p
}

/// The signed doubled area of a convex polygon of screen points, saturated to `±i64::MAX` (its sign
/// and whether it is zero are exact).
pub(super) fn polygon_area<const BITS: u32>(
    points: impl Iterator<Item = SubPoint<BITS>> + Clone,
) -> i64 {
    let mut it = points.clone();
    let Some(a) = it.next() else { return 0 };
    // Projected points may lie anywhere in i32 (the projection clamps there): differences need 33
    // bits and their products 66, so the sum is taken in i128.
    let mut area = 0i128;
    let mut prev: Option<SubPoint<BITS>> = None;
    let d = |p: i32, q: i32| i128::from(p) - i128::from(q);
    for c in it {
        if let Some(b) = prev {
            area += d(b.x, a.x) * d(c.y, a.y) - d(c.x, a.x) * d(b.y, a.y);
        }
        prev = Some(c);
    }
    area.clamp(-i128::from(i64::MAX), i128::from(i64::MAX)) as i64
}

impl<S, C, D, Sh, const BITS: u32, N> Pipeline<S, C, D, Sh, BITS, N>
where
    S: Scalar,
    C: Cull,
    D: DepthTest,
    Sh: Shading<S>,
    N: Numerics,
{
    /// The front end shared by every draw call: fetches triangle `t`, reads its vertices (each
    /// transformed once a frame, through the scratch), rejects it when it faces away or lies
    /// outside the view, counting why in `stats`. A triangle of zero area on screen is culled, unless
    /// `keep_flat` (the wireframe draws it as a line).
    #[inline(always)]
    pub(super) fn front<M: MeshSource<S>>(
        &self,
        mesh: &M,
        t: usize,
        scratch: &mut [VertexSlot<Sh::Stored>],
        stats: &mut RenderStats,
        keep_flat: bool,
    ) -> Front<S, BITS> {
        let idx = mesh.triangle(t);
        let Some(v) = self.fetch(mesh, idx, scratch) else {
            stats.invalid += 1;
            return Front::Skip;
        };
        if outside(&v) {
            return self.front_clip(mesh, idx, stats);
        }
        if !self.visible(&v, stats, keep_flat) {
            return Front::Skip;
        }
        Front::Inside {
            idx,
            v: v.map(|(x, y, z)| (SubPoint::raw(x, y), z)),
        }
    }

    /// The projected corners of a triangle, from their slots: one bounds check per corner, which
    /// also validates its index when the scratch has a slot for every vertex (`scratch` is cut to
    /// the mesh's vertex count). `None` for an index out of range.
    #[inline(always)]
    pub(super) fn fetch<M: MeshSource<S>>(
        &self,
        mesh: &M,
        idx: [usize; 3],
        scratch: &[VertexSlot<Sh::Stored>],
    ) -> Option<[Projected; 3]> {
        match (
            scratch.get(idx[0]),
            scratch.get(idx[1]),
            scratch.get(idx[2]),
        ) {
            (Some(a), Some(b), Some(c)) => {
                Some([(a.x, a.y, a.z), (b.x, b.y, b.z), (c.x, c.y, c.z)])
            }
            _ => self.fetch_unslotted(mesh, idx, scratch),
        }
    }

    /// [`Pipeline::fetch`] for a triangle with a corner beyond the scratch (a short scratch, or
    /// an index out of range): the rare path, out of line.
    #[inline(never)]
    fn fetch_unslotted<M: MeshSource<S>>(
        &self,
        mesh: &M,
        idx: [usize; 3],
        scratch: &[VertexSlot<Sh::Stored>],
    ) -> Option<[Projected; 3]> {
        let n = mesh.vertex_count();
        if idx[0] >= n || idx[1] >= n || idx[2] >= n {
            return None;
        }
        Some(idx.map(|i| match scratch.get(i) {
            Some(s) => (s.x, s.y, s.z),
            None => self.geometry(mesh.position(i)),
        }))
    }

    /// The front end's tests on a triangle whose corners are all inside the guard band: it faces
    /// the right way (a zero area only with `keep_flat`) and reaches the viewport. Counts why
    /// not in `stats`.
    #[inline(always)]
    pub(super) fn visible(
        &self,
        v: &[Projected; 3],
        stats: &mut RenderStats,
        keep_flat: bool,
    ) -> bool {
        if !self.faces(v, keep_flat) {
            stats.culled += 1;
            return false;
        }
        self.reaches_viewport(v, stats)
    }

    /// Whether a triangle inside the guard band faces the right way (a zero area only with
    /// `keep_flat`).
    #[inline(always)]
    pub(super) fn faces(&self, v: &[Projected; 3], keep_flat: bool) -> bool {
        let xs = [v[0].0, v[1].0, v[2].0].map(i64::from);
        let ys = [v[0].1, v[1].1, v[2].1].map(i64::from);
        let area = (xs[1] - xs[0]) * (ys[2] - ys[0]) - (xs[2] - xs[0]) * (ys[1] - ys[0]);
        if area == 0 {
            keep_flat
        } else {
            self.keeps(area)
        }
    }

    /// Whether a triangle inside the guard band reaches the viewport; counts it in `stats` when
    /// not.
    #[inline(always)]
    pub(super) fn reaches_viewport(&self, v: &[Projected; 3], stats: &mut RenderStats) -> bool {
        if self.in_viewport {
            return true;
        }
        let xs = [v[0].0, v[1].0, v[2].0].map(i64::from);
        let ys = [v[0].1, v[1].1, v[2].1].map(i64::from);
        // Off the viewport on one side (the screen planes are stricter than the guard band).
        let [l, top, r, bottom] = self.edges;
        let (x_lo, x_hi) = (xs[0].min(xs[1]).min(xs[2]), xs[0].max(xs[1]).max(xs[2]));
        let (y_lo, y_hi) = (ys[0].min(ys[1]).min(ys[2]), ys[0].max(ys[1]).max(ys[2]));
        if x_hi < l || x_lo > r || y_hi < top || y_lo > bottom {
            stats.outside += 1;
            return false;
        }
        true
    }

    /// The front end's rare path, a triangle with a vertex outside the guard band: its
    /// clip-space vertices for the clipper, or nothing when it lies wholly outside one plane.
    #[inline(never)]
    pub(super) fn front_clip<M: MeshSource<S>>(
        &self,
        mesh: &M,
        idx: [usize; 3],
        stats: &mut RenderStats,
    ) -> Front<S, BITS> {
        let mut clip = [Vec4::default(); 3];
        let mut codes = [0; 3];
        for k in 0..3 {
            clip[k] = self.mvp.transform_point(mesh.position(idx[k]));
            codes[k] = outcode(&clip[k]);
        }
        if trivially_outside(&clip, codes) {
            stats.outside += 1;
            return Front::Skip;
        }
        Front::Clip { idx, clip, codes }
    }

    /// The front end for a triangle that has passed it once this frame (a band's binned
    /// triangle): its vertices' slots, without the tests.
    #[inline(always)]
    pub(super) fn front_again<M: MeshSource<S>>(
        &self,
        mesh: &M,
        t: usize,
        scratch: &mut [VertexSlot<Sh::Stored>],
    ) -> Front<S, BITS> {
        let idx = mesh.triangle(t);
        let Some(v) = self.fetch(mesh, idx, scratch) else {
            return Front::Skip;
        };
        if outside(&v) {
            let mut ignored = RenderStats::default();
            return self.front_clip(mesh, idx, &mut ignored);
        }
        Front::Inside {
            idx,
            v: v.map(|(x, y, z)| (SubPoint::raw(x, y), z)),
        }
    }

    /// Draws a triangle the front end let through, counting it as drawn.
    #[inline(always)]
    pub(super) fn draw_front<T, M, P: DepthFrom<D>>(
        &mut self,
        src: &mut P,
        target: &mut T,
        mesh: &M,
        front: Front<S, BITS>,
        scratch: &mut [VertexSlot<Sh::Stored>],
        stats: &mut RenderStats,
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        match front {
            Front::Skip => Ok(()),
            Front::Inside { idx, v } => {
                let v = v.map(|(p, z)| (p.x, p.y, z));
                self.draw_visible(src, target, mesh, idx, v, scratch, stats)
            }
            Front::Clip { idx, clip, codes } => {
                self.draw_clipped(src, target, mesh, idx, clip, codes, scratch, stats)
            }
        }
    }

    /// Draws a triangle that passed the front end's tests, counting it as drawn: its shader
    /// values (from the slots, shading a vertex the first time a visible triangle uses it) and
    /// the raster stage.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn draw_visible<T, M, P: DepthFrom<D>>(
        &mut self,
        src: &mut P,
        target: &mut T,
        mesh: &M,
        idx: [usize; 3],
        v: [Projected; 3],
        scratch: &mut [VertexSlot<Sh::Stored>],
        stats: &mut RenderStats,
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        if Sh::NEEDS_FACE {
            self.face(mesh, idx);
        }
        stats.drawn += 1;
        let p = v.map(|(x, y, _)| SubPoint::raw(x, y));
        if Self::FUSED {
            // A triangle whose bounds hold at most four pixel centres and that covers none of
            // them (most of a dense mesh's far triangles) stops here, before its vertices are
            // shaded. The fill repeats the test for those that pass.
            let bounds = |c: [i32; 3]| (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]));
            let (x, y) = (
                bounds([v[0].0, v[1].0, v[2].0]),
                bounds([v[0].1, v[1].1, v[2].1]),
            );
            // Less than eight pixels each way first, a test large triangles leave at once (in
            // `i32`: corners inside the guard band are less than 2^31 apart).
            if (x.1.wrapping_sub(x.0) | y.1.wrapping_sub(y.0)) < 8 << BITS {
                let s = 1i64 << BITS;
                let count = |(lo, hi): (i32, i32)| centre_count(i64::from(lo), i64::from(hi), s);
                let (nx, ny) = (count(x), count(y));
                if nx <= 0 || ny <= 0 || (nx * ny <= 4 && misses_every_pixel(target, &p)) {
                    return Ok(());
                }
            }
            let fv = if Sh::NEEDS_WORLD && !mesh.has_normals() {
                let var = self.face_normal_values(mesh, idx);
                [0, 1, 2].map(|k| (p[k], v[k].2, var[k]))
            } else {
                [
                    (p[0], v[0].2, self.slot_values(mesh, idx[0], scratch)),
                    (p[1], v[1].2, self.slot_values(mesh, idx[1], scratch)),
                    (p[2], v[2].2, self.slot_values(mesh, idx[2], scratch)),
                ]
            };
            return self.raster_fused(src, target, &fv);
        }
        let var = self.face_values(mesh, idx, scratch);
        let sv = self.screen_vertices(mesh, idx, &v, var);
        self.raster(src, target, &sv)
    }

    /// A triangle's screen vertices for the span engines that take them: its corners, depths
    /// and values, and each corner's `1 / w` from its mesh position. Written out rather than
    /// mapped over an index, whose closure the compiler kept out of line.
    #[inline(always)]
    pub(super) fn screen_vertices<M: MeshSource<S>>(
        &self,
        mesh: &M,
        idx: [usize; 3],
        v: &[Projected; 3],
        var: [Sh::Varyings; 3],
    ) -> [ScreenVertex<Sh::Varyings, BITS>; 3] {
        let q = if Self::FUSED_PERSPECTIVE {
            // The fused loop reads only the ratios of a triangle's three `1 / w`
            // (`perspective::scaled_q`): `1 / w_k` is proportional to the product of the other
            // two `w`, which takes no division (each below 2^31, the product below 2^62).
            let w = [
                self.w_of(mesh.position(idx[0])),
                self.w_of(mesh.position(idx[1])),
                self.w_of(mesh.position(idx[2])),
            ];
            [w[1] * w[2], w[0] * w[2], w[0] * w[1]]
        } else {
            [
                self.q_of(mesh.position(idx[0])),
                self.q_of(mesh.position(idx[1])),
                self.q_of(mesh.position(idx[2])),
            ]
        };
        let vertex = |k: usize| ScreenVertex {
            p: SubPoint::raw(v[k].0, v[k].1),
            z: v[k].2,
            var: var[k],
            q: q[k],
        };
        [vertex(0), vertex(1), vertex(2)]
    }

    /// Draws a triangle with a corner outside the guard band (the front end's rare path): clipped,
    /// or counted as outside.
    #[inline(never)]
    pub(super) fn draw_outside<T, M, P: DepthFrom<D>>(
        &mut self,
        src: &mut P,
        target: &mut T,
        mesh: &M,
        idx: [usize; 3],
        scratch: &mut [VertexSlot<Sh::Stored>],
        stats: &mut RenderStats,
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        match self.front_clip(mesh, idx, stats) {
            Front::Clip { idx, clip, codes } => {
                self.draw_clipped(src, target, mesh, idx, clip, codes, scratch, stats)
            }
            _ => Ok(()),
        }
    }

    /// Clips a triangle in homogeneous space and draws what is left, as a fan.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    pub(super) fn draw_clipped<T, M, P: DepthFrom<D>>(
        &mut self,
        src: &mut P,
        target: &mut T,
        mesh: &M,
        idx: [usize; 3],
        clip: [Vec4<S>; 3],
        codes: [Outcode; 3],
        scratch: &mut [VertexSlot<Sh::Stored>],
        stats: &mut RenderStats,
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
        M: MeshSource<S>,
    {
        stats.clipped += 1;
        let var = self.face_values_rare(mesh, idx, scratch);
        let tri = [0, 1, 2].map(|k| ClipVertex {
            pos: clip[k],
            var: var[k],
        });
        let poly = clip_triangle(&tri, codes);
        if poly.len() < 3 {
            stats.outside += 1;
            return Ok(());
        }
        let mut screen: heapless::Vec<
            ScreenVertex<Sh::Varyings, BITS>,
            { crate::clip::polygon::MAX_CLIPPED },
        > = heapless::Vec::new();
        for v in &poly {
            let (p, z) = self.project(&v.pos);
            let mut var = v.var;
            if Sh::NEEDS_W && !N::PERSPECTIVE {
                self.shading.project(&mut var, v.pos.w);
            }
            let _ = screen.push(ScreenVertex {
                p,
                z,
                var,
                q: Self::q(&v.pos),
            });
        }
        // The clipped polygon is convex: its total signed area decides its facing.
        let area = polygon_area(screen.iter().map(position));
        if area == 0 || !self.keeps(area) {
            stats.culled += 1;
            return Ok(());
        }
        if Sh::NEEDS_FACE {
            self.face(mesh, idx);
        }
        // The clipped vertices are rounded, which can dent the convex polygon: at a reflex
        // vertex the fan's triangles overlap (or fold), and their common pixels would be drawn
        // twice. Dropping every vertex that does not turn the polygon's way leaves a convex
        // polygon (the dents were thinner than the rounding), whose fan tiles it exactly.
        let sign = area.signum();
        let turns = |s: &[ScreenVertex<Sh::Varyings, BITS>], k: usize| {
            let n = s.len();
            let corner = [s[(k + n - 1) % n], s[k], s[(k + 1) % n]];
            polygon_area(corner.iter().map(position)).signum() == sign
        };
        while screen.len() >= 3 {
            match (0..screen.len()).find(|&k| !turns(&screen, k)) {
                Some(k) => {
                    // By hand: `Vec::remove` would link `memmove`, 1.5 KB of a Cortex-M's flash.
                    let n = screen.len();
                    for j in k..n - 1 {
                        screen[j] = screen[j + 1];
                    }
                    screen.truncate(n - 1);
                }
                None => break,
            }
        }
        for k in 1..screen.len().saturating_sub(1) {
            self.raster(src, target, &[screen[0], screen[k], screen[k + 1]])?;
        }
        stats.drawn += 1;
        Ok(())
    }

    /// Rasterizes one screen triangle through the fused span loop.
    #[inline(always)]
    pub(super) fn raster_fused<T, P: DepthFrom<D>>(
        &mut self,
        src: &mut P,
        target: &mut T,
        fv: &[FusedVertex<Sh::Varyings, BITS>; 3],
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
    {
        if self.area.is_empty() {
            return Ok(());
        }
        let rescaled;
        let fv = if Sh::NEEDS_TRIANGLE {
            let mut values = [fv[0].2, fv[1].2, fv[2].2];
            self.shading.triangle(&mut values);
            rescaled = [
                (fv[0].0, fv[0].1, values[0]),
                (fv[1].0, fv[1].1, values[1]),
                (fv[2].0, fv[2].1, values[2]),
            ];
            &rescaled
        } else {
            fv
        };
        fill_fused::<_, _, _, _, BITS>(
            target,
            src.pick(&mut self.depth),
            fv,
            &self.area,
            ShaderColor::<S, Sh, N>(&self.shading, core::marker::PhantomData),
        )
    }

    /// Rasterizes one screen triangle with the pipeline's depth test and shading: through the
    /// fused span loop, or the exact interpolator ([`SpanStart::Exact`], [`SpanStart::Gradient`]
    /// or perspective-correct).
    #[inline(always)]
    pub(super) fn raster<T, P: DepthFrom<D>>(
        &mut self,
        src: &mut P,
        target: &mut T,
        sv: &[ScreenVertex<Sh::Varyings, BITS>; 3],
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
    {
        if Self::FUSED {
            let fv = sv.map(|v| (v.p, v.z, v.var));
            self.raster_fused(src, target, &fv)
        } else if Self::FUSED_PERSPECTIVE {
            self.raster_perspective(src, target, sv)
        } else {
            let mut sv = *sv;
            if Sh::NEEDS_TRIANGLE {
                let mut values = [sv[0].var, sv[1].var, sv[2].var];
                self.shading.triangle(&mut values);
                for (v, values) in sv.iter_mut().zip(values) {
                    v.var = values;
                }
            }
            let shading = &self.shading;
            fill_triangle_interp_with::<_, _, _, _, N, BITS>(
                target,
                src.pick(&mut self.depth),
                sv,
                |v| shading.pixel(v),
            )
        }
    }

    /// Whether visible triangles take the fused span loop ([`SpanStart::Wrapping`], affine).
    pub(super) const FUSED: bool = matches!(N::SPANS, SpanStart::Wrapping) && !N::PERSPECTIVE;
    /// Whether they take it perspective-correctly ([`SpanStart::Wrapping`] with
    /// [`Numerics::PERSPECTIVE`]): see [`super::perspective`].
    pub(super) const FUSED_PERSPECTIVE: bool =
        matches!(N::SPANS, SpanStart::Wrapping) && N::PERSPECTIVE;

    /// Rasterizes one screen triangle through the fused span loop with perspective-correct
    /// values.
    #[inline(always)]
    fn raster_perspective<T, P: DepthFrom<D>>(
        &mut self,
        src: &mut P,
        target: &mut T,
        sv: &[ScreenVertex<Sh::Varyings, BITS>; 3],
    ) -> Result<(), T::Error>
    where
        T: Surface<Color = Sh::Color>,
    {
        if self.area.is_empty() {
            return Ok(());
        }
        let mut sv = *sv;
        if Sh::NEEDS_TRIANGLE {
            let mut values = [sv[0].var, sv[1].var, sv[2].var];
            self.shading.triangle(&mut values);
            for (v, values) in sv.iter_mut().zip(values) {
                v.var = values;
            }
        }
        let depth = src.pick(&mut self.depth);
        if let Some((fv, color)) = DirectColor::<S, Sh, N>::new(&self.shading, &sv) {
            return fill_fused::<_, _, _, _, BITS>(target, depth, &fv, &self.area, color);
        }
        let (fv, color) = PerspectiveColor::<S, Sh, N>::new(&self.shading, &sv);
        fill_fused::<_, _, _, _, BITS>(target, depth, &fv, &self.area, color)
    }
}
