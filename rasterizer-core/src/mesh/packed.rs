//! The packed mesh format: what the host converter writes and firmware embeds with
//! `include_bytes!`, read in place with no copy and no allocation.
//!
//! Every field is little-endian. A blob is a 40-byte header followed by sections, each starting at
//! a multiple of 4 bytes from the start of the blob (zero padding between them):
//!
//! | offset | size | field |
//! |---:|---:|---|
//! | 0 | 4 | magic `RMSH` |
//! | 4 | 2 | version, `1`, `2` or `3` |
//! | 6 | 2 | flags: bit 0 normals, bit 1 colours, bit 2 32-bit indices (else 16-bit), bit 3 texture coordinates, bit 4 texture (bits 3 and 4 version 2 or 3), bit 5 adjacency (version 3 only); others 0 |
//! | 8 | 4 | vertex count `n` (at most 2^24) |
//! | 12 | 4 | triangle count `t` (at most 2^24) |
//! | 16 | 12 | offset: the box centre, x y z, 16.16 fixed point (`i32`) |
//! | 28 | 12 | scale: 16.16 units per quantum, x y z, in 16.16 fixed point (`u32`, not zero) |
//! | 40 | 6 n | positions: `i16` x y z per vertex, each in `-32767 ..= 32767` |
//! | | 6 n | normals (flag 0): `i16` x y z per vertex, unit length at 32767 |
//! | | 3 n | colours (flag 1): r g b bytes per vertex |
//! | | 8 n | texture coordinates (flag 3): `i32` u v per vertex, 16.16 ([`crate::texture`]) |
//! | | 6 t or 12 t | triangles: three `u16` (or `u32`, flag 2) vertex indices each |
//! | | 6 t or 12 t | adjacency (flag 5): three neighbour triangles each, `u16` (`0xFFFF` none) when `t` is at most 65,535, else `u32` (`0xFFFF_FFFF` none) |
//! | | 1 | texture (flag 4): the width's power of two, at most [`MAX_SIDE_LOG2`] |
//! | | 1 | the height's power of two, at most [`MAX_SIDE_LOG2`] |
//! | | 2 | zero |
//! | | 2 w h | the texels, little-endian Rgb565, row after row from the image's top row |
//!
//! A position decodes to `offset + q * scale / 2^16` (16.16, rounded half up): with `i16` quanta
//! across the mesh's bounding box, the quantisation error is at most half a quantum, 1/65534 of the
//! box's extent in each axis (1.5e-5 for a unit-sphere mesh, one 16.16 step). A normal decodes to
//! `q / 32767` in 16.16. Meshes of more than 65,535 vertices use 32-bit indices.
//!
//! Version 2 adds texture coordinates and a texture; a blob with neither is written as version 1,
//! which this reader still reads (with bits 3 and 4 unknown flags there). The texture comes last,
//! after the triangles (and adjacency), since its length depends on its own sides; it needs
//! texture coordinates (flag 4 without flag 3 is [`MeshError::TextureWithoutUvs`]), while texture
//! coordinates alone are allowed (for a texture that firmware keeps elsewhere). Texture
//! coordinates take any `i32`: values outside `0 ..= 1` repeat or clamp as the shader's
//! [`crate::texture::Wrap`] says.
//!
//! Version 3 adds edge adjacency ([`MeshSource::neighbours`]: entry `e` of a triangle is the
//! triangle across its edge from corner `e` to corner `(e + 1) % 3`), which anti-aliased
//! silhouettes read; a blob without it is written as version 1 or 2 as before, so firmware that
//! predates it still reads every blob that does not need it. The entries are as narrow as the
//! triangle count allows (6 bytes a triangle up to 65,535 triangles), and sit before the texture
//! so that the texture stays last, where its self-described length belongs.
//!
//! [`PackedMesh::parse`] checks everything once (magic, version, flags, counts, that the length is
//! exactly what the counts need, zero padding, scales, quanta, every index and every neighbour
//! entry), so any byte string gives a mesh or a [`MeshError`], and the accessors afterwards need
//! no checks that can fail. The reader decodes with `from_le_bytes`, so the blob itself needs no
//! alignment.

use super::{MeshSource, NO_NEIGHBOUR};
use crate::math::{Scalar, Vec3};
use crate::texture::{Texture, TextureError, MAX_SIDE_LOG2};
use core::fmt;
use embedded_graphics_core::pixelcolor::Rgb888;

/// The magic number at the start of a blob.
pub const MAGIC: [u8; 4] = *b"RMSH";
/// The newest format version, the one this reader understands besides [`VERSION_1`] and
/// [`VERSION_2`]: adds adjacency.
pub const VERSION: u16 = 3;
/// The first format version: no texture coordinates and no texture.
pub const VERSION_1: u16 = 1;
/// The second format version: texture coordinates and a texture, no adjacency.
pub const VERSION_2: u16 = 2;
/// Header size in bytes.
pub const HEADER_LEN: usize = 40;
/// Flag: the mesh has normals.
pub const FLAG_NORMALS: u16 = 1;
/// Flag: the mesh has vertex colours.
pub const FLAG_COLORS: u16 = 2;
/// Flag: indices are 32-bit.
pub const FLAG_U32_INDICES: u16 = 4;
/// Flag: the mesh has texture coordinates (version 2).
pub const FLAG_UVS: u16 = 8;
/// Flag: the blob ends with a texture (version 2 or 3; needs [`FLAG_UVS`]).
pub const FLAG_TEXTURE: u16 = 16;
/// Flag: the mesh has edge adjacency, three neighbour entries per triangle (version 3).
pub const FLAG_ADJACENCY: u16 = 32;
/// The largest triangle count whose neighbour entries are `u16`; above it they are `u32`.
pub const MAX_NARROW_NEIGHBOURS: usize = 0xFFFF;
/// A `u16` neighbour entry meaning none (a `u32` entry uses [`NO_NEIGHBOUR`]).
pub const NO_NEIGHBOUR_U16: u16 = 0xFFFF;
/// Bytes before the texels in the texture section: the two sides' powers of two and two zeros.
pub const TEXTURE_HEADER_LEN: usize = 4;
/// The largest vertex or triangle count a blob may declare.
pub const MAX_COUNT: u32 = 1 << 24;
/// The largest quantum magnitude.
pub const QUANTUM_MAX: i16 = 32767;

/// Why a byte string is not a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshError {
    /// Shorter than the header.
    TooShort {
        /// Bytes given.
        len: usize,
    },
    /// The first four bytes are not `RMSH`.
    BadMagic,
    /// A version this reader does not know.
    UnsupportedVersion(u16),
    /// Flag bits this version does not define.
    UnknownFlags(u16),
    /// The texture flag without the texture coordinates flag.
    TextureWithoutUvs,
    /// The texture's sides are not a texture's ([`TextureError`]).
    Texture(TextureError),
    /// A vertex or triangle count above [`MAX_COUNT`], or triangles with no vertices.
    BadCounts {
        /// Vertices declared.
        vertices: u32,
        /// Triangles declared.
        triangles: u32,
    },
    /// The length is not what the header's counts need.
    WrongLength {
        /// Bytes the header implies.
        expected: usize,
        /// Bytes given.
        actual: usize,
    },
    /// A padding byte between sections is not zero.
    BadPadding {
        /// Its offset in the blob.
        offset: usize,
    },
    /// A scale of zero, or one so large that decoded positions leave the 16.16 range.
    BadScale,
    /// A position or normal quantum of -32768.
    BadQuantum {
        /// The vertex.
        vertex: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The index it holds.
        index: u32,
    },
    /// A neighbour entry names a triangle that does not exist (and is not the value for none).
    NeighbourOutOfRange {
        /// The triangle whose entry it is.
        triangle: usize,
        /// The entry it holds.
        entry: u32,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooShort { len } => write!(
                f,
                "{len} bytes is shorter than the {HEADER_LEN}-byte header"
            ),
            Self::BadMagic => write!(f, "not a packed mesh (magic is not RMSH)"),
            Self::UnsupportedVersion(v) => write!(
                f,
                "format version {v} is not supported (expected {VERSION_1} to {VERSION})"
            ),
            Self::UnknownFlags(x) => write!(f, "unknown flag bits {x:#06x}"),
            Self::TextureWithoutUvs => {
                write!(
                    f,
                    "a texture but no texture coordinates (flag bit 4 without bit 3)"
                )
            }
            Self::Texture(e) => write!(f, "bad texture: {e}"),
            Self::BadCounts {
                vertices,
                triangles,
            } => {
                write!(f, "bad counts: {vertices} vertices, {triangles} triangles (at most {MAX_COUNT} each)")
            }
            Self::WrongLength { expected, actual } => {
                write!(
                    f,
                    "the header needs {expected} bytes but the blob has {actual}"
                )
            }
            Self::BadPadding { offset } => write!(f, "non-zero padding byte at offset {offset}"),
            Self::BadScale => write!(f, "a scale is zero or too large for 16.16 positions"),
            Self::BadQuantum { vertex } => write!(f, "vertex {vertex} has a quantum of -32768"),
            Self::IndexOutOfRange { triangle, index } => {
                write!(
                    f,
                    "triangle {triangle} refers to vertex {index}, which does not exist"
                )
            }
            Self::NeighbourOutOfRange { triangle, entry } => {
                write!(
                    f,
                    "triangle {triangle} lists triangle {entry} as a neighbour, which does not \
                     exist"
                )
            }
        }
    }
}

impl core::error::Error for MeshError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Self::Texture(e) => Some(e),
            _ => None,
        }
    }
}

/// A validated packed mesh borrowing its bytes.
// In C order with the texture's fields last, so that they do not push the fields every draw
// reads (offset, scale) beyond short addressing: an untextured draw compiles as without them.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub struct PackedMesh<'a> {
    positions: &'a [u8],
    indices: &'a [u8],
    vertices: usize,
    triangles: usize,
    normals: Option<&'a [u8]>,
    colors: Option<&'a [u8]>,
    offset: [i32; 3],
    scale: [u32; 3],
    wide: bool,
    uvs: Option<&'a [u8]>,
    texture: Option<Texture<'a>>,
    // Last for the same reason as the texture: only anti-aliased draws read it.
    adjacency: Option<&'a [u8]>,
}

/// `n` rounded up to a multiple of 4.
const fn pad4(n: usize) -> usize {
    (n + 3) & !3
}

/// The first non-zero byte between the header and the first section, or between sections
/// (`(start, len)`, in order, within `bytes`). One loop, not one per section: a smaller parser.
#[inline(never)]
fn nonzero_padding(bytes: &[u8], sections: &[(usize, usize)]) -> Option<usize> {
    let mut covered = HEADER_LEN;
    for &(start, len) in sections {
        if let Some(o) = (covered..start).find(|&o| bytes.get(o).is_some_and(|&b| b != 0)) {
            return Some(o);
        }
        covered = start + len;
    }
    None
}

/// True when `t` triangles' neighbour entries are `u32` rather than `u16`.
const fn wide_neighbours(t: usize) -> bool {
    t > MAX_NARROW_NEIGHBOURS
}

/// The section layout of a blob up to the texture: `(start, len)` of positions, normals,
/// colours, texture coordinates, indices and adjacency, and the length so far (where a texture
/// starts).
fn layout(n: usize, t: usize, flags: u16) -> ([(usize, usize); 6], usize) {
    let mut at = HEADER_LEN;
    let mut section = |len: usize| {
        let s = (at, len);
        at = pad4(at + len);
        s
    };
    let pos = section(6 * n);
    let nrm = section(if flags & FLAG_NORMALS != 0 { 6 * n } else { 0 });
    let col = section(if flags & FLAG_COLORS != 0 { 3 * n } else { 0 });
    let uv = section(if flags & FLAG_UVS != 0 { 8 * n } else { 0 });
    let idx = section(if flags & FLAG_U32_INDICES != 0 {
        12 * t
    } else {
        6 * t
    });
    let adj = section(match (flags & FLAG_ADJACENCY != 0, wide_neighbours(t)) {
        (false, _) => 0,
        (true, false) => 6 * t,
        (true, true) => 12 * t,
    });
    ([pos, nrm, col, uv, idx, adj], at)
}

#[inline(always)]
fn u16_at(b: &[u8], i: usize) -> u16 {
    u16::from_le_bytes([b[i], b[i + 1]])
}

#[inline(always)]
fn u32_at(b: &[u8], i: usize) -> u32 {
    u32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]])
}

/// Record `i` of a section of `L`-byte records, or `None` past its end: one bounds check for the
/// record, and none for the fields read from it. The caller keeps `i` below its count (at most
/// `MAX_COUNT`), so `i * L` cannot overflow.
#[inline(always)]
fn record<const L: usize>(b: &[u8], i: usize) -> Option<&[u8; L]> {
    b.get(i * L..i * L + L)?.try_into().ok()
}

/// The three little-endian `u16`s of a 6-byte record.
#[inline(always)]
fn u16x3(r: &[u8; 6]) -> [u16; 3] {
    let [a, b, c, d, e, f] = *r;
    [
        u16::from_le_bytes([a, b]),
        u16::from_le_bytes([c, d]),
        u16::from_le_bytes([e, f]),
    ]
}

/// The three little-endian `u32`s of a 12-byte record.
#[inline(always)]
fn u32x3(r: &[u8; 12]) -> [u32; 3] {
    let [a, b, c, d, e, f, g, h, i, j, k, l] = *r;
    [
        u32::from_le_bytes([a, b, c, d]),
        u32::from_le_bytes([e, f, g, h]),
        u32::from_le_bytes([i, j, k, l]),
    ]
}

impl<'a> PackedMesh<'a> {
    /// Validates `bytes` and reads the mesh in place.
    ///
    /// # Errors
    /// A [`MeshError`] for anything that is not a well-formed version-1, -2 or -3 mesh.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, MeshError> {
        if bytes.len() < HEADER_LEN {
            return Err(MeshError::TooShort { len: bytes.len() });
        }
        if bytes[0..4] != MAGIC {
            return Err(MeshError::BadMagic);
        }
        let version = u16_at(bytes, 4);
        let known = match version {
            VERSION_1 => FLAG_NORMALS | FLAG_COLORS | FLAG_U32_INDICES,
            VERSION_2 => FLAG_NORMALS | FLAG_COLORS | FLAG_U32_INDICES | FLAG_UVS | FLAG_TEXTURE,
            VERSION => {
                FLAG_NORMALS
                    | FLAG_COLORS
                    | FLAG_U32_INDICES
                    | FLAG_UVS
                    | FLAG_TEXTURE
                    | FLAG_ADJACENCY
            }
            _ => return Err(MeshError::UnsupportedVersion(version)),
        };
        let flags = u16_at(bytes, 6);
        if flags & !known != 0 {
            return Err(MeshError::UnknownFlags(flags));
        }
        if flags & FLAG_TEXTURE != 0 && flags & FLAG_UVS == 0 {
            return Err(MeshError::TextureWithoutUvs);
        }
        let (nv, nt) = (u32_at(bytes, 8), u32_at(bytes, 12));
        if nv > MAX_COUNT || nt > MAX_COUNT || (nv == 0 && nt > 0) {
            return Err(MeshError::BadCounts {
                vertices: nv,
                triangles: nt,
            });
        }
        let (n, t) = (nv as usize, nt as usize);
        let ([pos, nrm, col, uv, idx, adj], mut total) = layout(n, t, flags);
        // The texture section: its header, then texels as many as its sides say.
        let (mut sides, mut tex, mut texture_sides) = ((total, 0), (total, 0), None);
        if flags & FLAG_TEXTURE != 0 {
            let Some(&[w, h, ..]) = bytes.get(total..total + TEXTURE_HEADER_LEN) else {
                return Err(MeshError::WrongLength {
                    expected: total + TEXTURE_HEADER_LEN,
                    actual: bytes.len(),
                });
            };
            if w > MAX_SIDE_LOG2 || h > MAX_SIDE_LOG2 {
                return Err(MeshError::Texture(TextureError::TooLarge {
                    width_log2: w,
                    height_log2: h,
                }));
            }
            // The two zero bytes after the sides are checked as padding below.
            sides = (total, 2);
            tex = (total + TEXTURE_HEADER_LEN, 2 << (w + h));
            texture_sides = Some((w, h));
            total = pad4(tex.0 + tex.1);
        }
        if bytes.len() != total {
            return Err(MeshError::WrongLength {
                expected: total,
                actual: bytes.len(),
            });
        }
        // Padding: every byte not inside the header or a section is zero.
        let sections = [pos, nrm, col, uv, idx, adj, sides, tex, (total, 0)];
        if let Some(offset) = nonzero_padding(bytes, &sections) {
            return Err(MeshError::BadPadding { offset });
        }
        let offset = [0, 1, 2].map(|k| u32_at(bytes, 16 + 4 * k) as i32);
        let scale = [0, 1, 2].map(|k| u32_at(bytes, 28 + 4 * k));
        // The decoded position offset + 32767 scale / 2^16 must stay inside i32.
        for k in 0..3 {
            let reach = (i64::from(scale[k]) * i64::from(QUANTUM_MAX)) >> 16;
            let (lo, hi) = (
                i64::from(offset[k]) - reach - 1,
                i64::from(offset[k]) + reach + 1,
            );
            if scale[k] == 0 || lo < i64::from(i32::MIN) || hi > i64::from(i32::MAX) {
                return Err(MeshError::BadScale);
            }
        }
        // Every section lies within `bytes` (the length was checked): no panic path.
        let sec = |(start, len): (usize, usize)| bytes.get(start..start + len).unwrap_or_default();
        let mesh = Self {
            vertices: n,
            triangles: t,
            offset,
            scale,
            positions: sec(pos),
            normals: (flags & FLAG_NORMALS != 0).then(|| sec(nrm)),
            colors: (flags & FLAG_COLORS != 0).then(|| sec(col)),
            uvs: (flags & FLAG_UVS != 0).then(|| sec(uv)),
            indices: sec(idx),
            wide: flags & FLAG_U32_INDICES != 0,
            // Sides and length were checked above.
            texture: texture_sides.map(|(w, h)| Texture::checked(w, h, sec(tex))),
            adjacency: (flags & FLAG_ADJACENCY != 0).then(|| sec(adj)),
        };
        for v in 0..n {
            let bad = |b: &[u8]| record(b, v).is_some_and(|r| u16x3(r).contains(&0x8000));
            if bad(mesh.positions) || mesh.normals.is_some_and(bad) {
                return Err(MeshError::BadQuantum { vertex: v });
            }
        }
        for tri in 0..t {
            for index in mesh.raw_indices(tri) {
                if index as usize >= n {
                    return Err(MeshError::IndexOutOfRange {
                        triangle: tri,
                        index,
                    });
                }
            }
            // `t` is at most 2^24, so the none value is never a triangle number.
            for entry in mesh.raw_neighbours(tri).unwrap_or_default() {
                if entry != NO_NEIGHBOUR && entry as usize >= t {
                    return Err(MeshError::NeighbourOutOfRange {
                        triangle: tri,
                        entry,
                    });
                }
            }
        }
        Ok(mesh)
    }

    /// Triangle `tri`'s neighbours (`tri` below the count), the `u16` none widened to
    /// [`NO_NEIGHBOUR`]; `None` without adjacency.
    #[inline(always)]
    fn raw_neighbours(&self, tri: usize) -> Option<[u32; 3]> {
        let b = self.adjacency?;
        if wide_neighbours(self.triangles) {
            record(b, tri).map(u32x3)
        } else {
            record(b, tri).map(|r| {
                u16x3(r).map(|e| match e {
                    NO_NEIGHBOUR_U16 => NO_NEIGHBOUR,
                    e => u32::from(e),
                })
            })
        }
    }

    /// Triangle `tri`'s vertex indices (`tri` below the count; the section holds them all, so
    /// the zeros are never returned).
    #[inline(always)]
    fn raw_indices(&self, tri: usize) -> [u32; 3] {
        let indices = if self.wide {
            record(self.indices, tri).map(u32x3)
        } else {
            record(self.indices, tri).map(|r| u16x3(r).map(u32::from))
        };
        indices.unwrap_or_default()
    }

    /// Number of vertices.
    pub fn vertices(&self) -> usize {
        self.vertices
    }

    /// Number of triangles.
    pub fn triangles(&self) -> usize {
        self.triangles
    }

    /// The box centre and the 16.16 units per quantum (16.16 fixed point), per axis.
    pub fn quantisation(&self) -> ([i32; 3], [u32; 3]) {
        (self.offset, self.scale)
    }

    /// Vertex `i`'s position in 16.16 bits, or `None` past the end.
    #[inline]
    pub fn position_bits(&self, i: usize) -> Option<[i32; 3]> {
        if i >= self.vertices {
            return None;
        }
        let r = u16x3(record(self.positions, i)?);
        Some([0, 1, 2].map(|k| {
            let q = i64::from(r[k] as i16);
            // Checked at parse time to stay inside i32.
            (i64::from(self.offset[k]) + ((q * i64::from(self.scale[k]) + (1 << 15)) >> 16)) as i32
        }))
    }

    /// Vertex `i`'s normal in 16.16 bits, or `None` without normals or past the end.
    #[inline]
    pub fn normal_bits(&self, i: usize) -> Option<[i32; 3]> {
        let b = self.normals.filter(|_| i < self.vertices)?;
        let r = u16x3(record(b, i)?);
        Some([0, 1, 2].map(|k| {
            let q = i32::from(r[k] as i16);
            // q / 32767 in 16.16, rounded half up; |q 65536 + 16383| <= 2^31 - 16385 fits i32, so
            // the division is a 32-bit one (by a constant: a multiplication).
            (q * 65536 + 16383).div_euclid(32767)
        }))
    }

    /// Vertex `i`'s colour, or `None` without colours or past the end.
    #[inline]
    pub fn color_of(&self, i: usize) -> Option<Rgb888> {
        let b = self.colors.filter(|_| i < self.vertices)?;
        let &[r, g, b] = record(b, i)?;
        Some(Rgb888::new(r, g, b))
    }

    /// Vertex `i`'s texture coordinates (16.16, [`crate::texture`]), or `None` without them or
    /// past the end.
    #[inline]
    pub fn uv_bits(&self, i: usize) -> Option<[i32; 2]> {
        let b = self.uvs.filter(|_| i < self.vertices)?;
        let r: &[u8; 8] = record(b, i)?;
        Some(
            [0, 1]
                .map(|k| i32::from_le_bytes([r[4 * k], r[4 * k + 1], r[4 * k + 2], r[4 * k + 3]])),
        )
    }

    /// True when the mesh has texture coordinates.
    #[inline]
    pub fn has_uvs(&self) -> bool {
        self.uvs.is_some()
    }

    /// The texture the blob carries, if any (read in place).
    #[inline]
    pub fn texture(&self) -> Option<Texture<'a>> {
        self.texture
    }

    /// Triangle `t`'s vertex indices, or `None` past the end.
    #[inline]
    pub fn triangle_indices(&self, t: usize) -> Option<[u32; 3]> {
        (t < self.triangles).then(|| self.raw_indices(t))
    }

    /// True when the mesh has edge adjacency (version 3, [`FLAG_ADJACENCY`]).
    #[inline]
    pub fn has_adjacency(&self) -> bool {
        self.adjacency.is_some()
    }

    /// Triangle `t`'s neighbours as [`MeshSource::neighbours`] gives them (each below
    /// [`PackedMesh::triangles`] or [`NO_NEIGHBOUR`], checked at parse time), or `None` without
    /// adjacency or past the end.
    #[inline]
    pub fn neighbour_indices(&self, t: usize) -> Option<[u32; 3]> {
        if t >= self.triangles {
            return None;
        }
        self.raw_neighbours(t)
    }
}

impl<S: Scalar> MeshSource<S> for PackedMesh<'_> {
    #[inline(always)]
    fn vertex_count(&self) -> usize {
        self.vertices
    }
    #[inline(always)]
    fn triangle_count(&self) -> usize {
        self.triangles
    }
    #[inline(always)]
    fn triangle(&self, t: usize) -> [usize; 3] {
        self.triangle_indices(t)
            .map_or([usize::MAX; 3], |i| i.map(|v| v as usize))
    }
    #[inline(always)]
    fn position(&self, i: usize) -> Vec3<S> {
        let p = self
            .position_bits(i)
            .unwrap_or_default()
            .map(S::from_fx16_bits);
        Vec3::new(p[0], p[1], p[2])
    }
    #[inline(always)]
    fn has_normals(&self) -> bool {
        self.normals.is_some()
    }
    #[inline(always)]
    fn normal(&self, i: usize) -> Option<Vec3<S>> {
        let n = self.normal_bits(i)?.map(S::from_fx16_bits);
        Some(Vec3::new(n[0], n[1], n[2]))
    }
    #[inline(always)]
    fn color(&self, i: usize) -> Option<Rgb888> {
        self.color_of(i)
    }
    #[inline(always)]
    fn uv(&self, i: usize) -> Option<[i32; 2]> {
        self.uv_bits(i)
    }
    #[inline(always)]
    fn has_adjacency(&self) -> bool {
        self.adjacency.is_some()
    }
    #[inline(always)]
    fn neighbours(&self, t: usize) -> [u32; 3] {
        self.neighbour_indices(t).unwrap_or([NO_NEIGHBOUR; 3])
    }
}
