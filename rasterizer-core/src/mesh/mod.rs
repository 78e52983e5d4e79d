//! Meshes as the pipeline reads them: plain slices ([`Mesh`]) or the packed format firmware embeds
//! ([`PackedMesh`], read in place), both behind [`MeshSource`].

mod packed;

pub use packed::*;

use crate::math::{Scalar, Vec3};
use embedded_graphics_core::pixelcolor::Rgb888;

/// An index into a mesh's vertex arrays.
pub trait VertexIndex: Copy {
    /// As `usize`.
    fn index(self) -> usize;
}

impl VertexIndex for u8 {
    #[inline(always)]
    fn index(self) -> usize {
        usize::from(self)
    }
}

impl VertexIndex for u16 {
    #[inline(always)]
    fn index(self) -> usize {
        usize::from(self)
    }
}

impl VertexIndex for u32 {
    #[inline(always)]
    fn index(self) -> usize {
        self as usize
    }
}

/// A triangle mesh as plain slices: nothing is copied.
#[derive(Debug, Clone, Copy)]
pub struct Mesh<'a, S, I = u16> {
    /// Vertex positions in model space.
    pub positions: &'a [Vec3<S>],
    /// Vertex normals in model space, one per position; lit shaders use the face normal when
    /// absent.
    pub normals: Option<&'a [Vec3<S>]>,
    /// Vertex colours, one per position; white when absent.
    pub colors: Option<&'a [Rgb888]>,
    /// Texture coordinates, one pair per position, 16.16 in units of the whole texture
    /// ([`crate::texture`]); `(0, 0)` when absent.
    pub uvs: Option<&'a [[i32; 2]]>,
    /// Triangles as three vertex indices. A triangle with an index out of range is skipped and
    /// counted in [`crate::pipeline::RenderStats::invalid`].
    pub triangles: &'a [[I; 3]],
    /// Edge adjacency, one entry per triangle ([`MeshSource::neighbours`]): what anti-aliased
    /// silhouettes need ([`crate::pipeline::Pipeline::draw_antialiased`]).
    pub adjacency: Option<&'a [[u32; 3]]>,
}

impl<'a, S, I> Mesh<'a, S, I> {
    /// A mesh of positions and triangles only.
    pub const fn new(positions: &'a [Vec3<S>], triangles: &'a [[I; 3]]) -> Self {
        Self {
            positions,
            normals: None,
            colors: None,
            uvs: None,
            triangles,
            adjacency: None,
        }
    }

    /// The mesh with edge adjacency, one entry per triangle ([`MeshSource::neighbours`]).
    pub const fn with_adjacency(self, adjacency: &'a [[u32; 3]]) -> Self {
        Self {
            adjacency: Some(adjacency),
            ..self
        }
    }

    /// The mesh with vertex normals, one per position.
    pub const fn with_normals(self, normals: &'a [Vec3<S>]) -> Self {
        Self {
            normals: Some(normals),
            ..self
        }
    }

    /// The mesh with texture coordinates, one pair per position (16.16, [`crate::texture`]).
    pub const fn with_uvs(self, uvs: &'a [[i32; 2]]) -> Self {
        Self {
            uvs: Some(uvs),
            ..self
        }
    }

    /// The mesh with vertex colours, one per position.
    pub const fn with_colors(self, colors: &'a [Rgb888]) -> Self {
        Self {
            colors: Some(colors),
            ..self
        }
    }
}

/// The neighbour entry of an edge no other triangle shares (a boundary edge, or one shared by more
/// than two triangles): [`MeshSource::neighbours`].
pub const NO_NEIGHBOUR: u32 = u32::MAX;

/// Where a pipeline reads a mesh from: plain slices ([`Mesh`]) or the packed format read straight
/// from flash ([`PackedMesh`]).
pub trait MeshSource<S> {
    /// Number of vertices.
    fn vertex_count(&self) -> usize;
    /// Number of triangles.
    fn triangle_count(&self) -> usize;
    /// Triangle `t`'s vertex indices (`t < triangle_count()`); an index may be out of range, and
    /// the pipeline then skips the triangle.
    fn triangle(&self, t: usize) -> [usize; 3];
    /// Vertex `i`'s position (`i < vertex_count()`).
    fn position(&self, i: usize) -> Vec3<S>;
    /// All positions as one slice, when the mesh keeps them so (`vertex_count()` long): a loop
    /// over every vertex then reads them without an index check each.
    #[inline(always)]
    fn position_slice(&self) -> Option<&[Vec3<S>]> {
        None
    }
    /// True when the mesh has normals.
    fn has_normals(&self) -> bool;
    /// Vertex `i`'s normal, if the mesh has normals.
    fn normal(&self, i: usize) -> Option<Vec3<S>>;
    /// Vertex `i`'s colour, if the mesh has colours.
    fn color(&self, i: usize) -> Option<Rgb888>;
    /// Vertex `i`'s texture coordinates (16.16, [`crate::texture`]), if the mesh has them.
    #[inline(always)]
    fn uv(&self, i: usize) -> Option<[i32; 2]> {
        let _ = i;
        None
    }
    /// True when the mesh has edge adjacency ([`MeshSource::neighbours`]).
    #[inline(always)]
    fn has_adjacency(&self) -> bool {
        false
    }
    /// Triangle `t`'s neighbours (`t < triangle_count()`), when the mesh has adjacency: entry `e`
    /// is the triangle across the edge from corner `e` to corner `(e + 1) % 3`, or
    /// [`NO_NEIGHBOUR`]. A neighbour out of range is treated as none.
    #[inline(always)]
    fn neighbours(&self, t: usize) -> [u32; 3] {
        let _ = t;
        [NO_NEIGHBOUR; 3]
    }
}

impl<S: Scalar, I: VertexIndex> MeshSource<S> for Mesh<'_, S, I> {
    #[inline(always)]
    fn vertex_count(&self) -> usize {
        self.positions.len()
    }
    #[inline(always)]
    fn triangle_count(&self) -> usize {
        self.triangles.len()
    }
    #[inline(always)]
    fn triangle(&self, t: usize) -> [usize; 3] {
        self.triangles
            .get(t)
            .map_or([usize::MAX; 3], |tri| tri.map(VertexIndex::index))
    }
    #[inline(always)]
    fn position(&self, i: usize) -> Vec3<S> {
        self.positions.get(i).copied().unwrap_or_default()
    }
    #[inline(always)]
    fn position_slice(&self) -> Option<&[Vec3<S>]> {
        Some(self.positions)
    }
    #[inline(always)]
    fn has_normals(&self) -> bool {
        self.normals.is_some()
    }
    #[inline(always)]
    fn normal(&self, i: usize) -> Option<Vec3<S>> {
        self.normals.and_then(|n| n.get(i).copied())
    }
    #[inline(always)]
    fn color(&self, i: usize) -> Option<Rgb888> {
        self.colors.and_then(|c| c.get(i).copied())
    }
    #[inline(always)]
    fn uv(&self, i: usize) -> Option<[i32; 2]> {
        self.uvs.and_then(|c| c.get(i).copied())
    }
    #[inline(always)]
    fn has_adjacency(&self) -> bool {
        self.adjacency.is_some()
    }
    #[inline(always)]
    fn neighbours(&self, t: usize) -> [u32; 3] {
        self.adjacency
            .and_then(|a| a.get(t).copied())
            .unwrap_or([NO_NEIGHBOUR; 3])
    }
}
