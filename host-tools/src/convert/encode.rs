//! Writing the packed mesh format (specified in `rasterizer_core::mesh`): the lowest version that
//! holds the mesh, so older firmware reads every blob it can (version 1 with neither texture
//! coordinates nor a texture nor adjacency, byte for byte what it always was; version 2 with
//! either of the first two; version 3 with adjacency); and the per-axis quantisation it uses.
//!
//! The writer mirrors the reader: the same section order, 4-byte alignment and zero padding, and
//! the same decode arithmetic (`offset + (q * scale + 2^15) >> 16`), so the converter can measure
//! the error of the positions firmware will really see.

use rasterizer_core::mesh::{
    FLAG_ADJACENCY, FLAG_COLORS, FLAG_NORMALS, FLAG_TEXTURE, FLAG_U32_INDICES, FLAG_UVS,
    HEADER_LEN, MAGIC, MAX_NARROW_NEIGHBOURS, NO_NEIGHBOUR, NO_NEIGHBOUR_U16, QUANTUM_MAX, VERSION,
    VERSION_1, VERSION_2,
};

/// A mesh in the packed format's terms, ready for [`encode`].
///
/// Normals and colours, when present, hold one entry per position; every triangle index is below
/// the number of positions; no quantum is -32768. [`encode`] writes what it is given, and
/// `PackedMesh::parse` rejects a blob that breaks these rules.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct MeshData {
    /// The bounding box centre, x y z, in 16.16 fixed point.
    pub offset: [i32; 3],
    /// 16.16 units per quantum, x y z, in 16.16 fixed point (not zero).
    pub scale: [u32; 3],
    /// Position quanta, each in `-32767 ..= 32767`.
    pub positions: Vec<[i16; 3]>,
    /// Normal quanta (unit length at 32767), one per position.
    pub normals: Option<Vec<[i16; 3]>>,
    /// Vertex colours, one per position.
    pub colors: Option<Vec<[u8; 3]>>,
    /// Texture coordinates (16.16, `rasterizer_core::texture`), one pair per position.
    pub uvs: Option<Vec<[i32; 2]>>,
    /// Triangles as three vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// A texture (needs texture coordinates).
    pub texture: Option<TextureData>,
    /// Edge adjacency, one entry per triangle (`fixtures::adjacency`): each entry a triangle
    /// number below the triangle count or `NO_NEIGHBOUR`.
    pub adjacency: Option<Vec<[u32; 3]>>,
}

/// A texture in the packed format's terms: power-of-two sides and little-endian Rgb565 texels,
/// row after row from the top.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct TextureData {
    /// The width's power of two.
    pub width_log2: u8,
    /// The height's power of two.
    pub height_log2: u8,
    /// `2 << (width_log2 + height_log2)` bytes.
    pub texels: Vec<u8>,
}

impl MeshData {
    /// True when the blob needs 32-bit indices: more than 65,535 vertices.
    pub fn wide_indices(&self) -> bool {
        self.positions.len() > usize::from(u16::MAX)
    }

    /// The header's flag bits for this mesh.
    pub fn flags(&self) -> u16 {
        let mut f = 0;
        if self.normals.is_some() {
            f |= FLAG_NORMALS;
        }
        if self.colors.is_some() {
            f |= FLAG_COLORS;
        }
        if self.wide_indices() {
            f |= FLAG_U32_INDICES;
        }
        if self.uvs.is_some() {
            f |= FLAG_UVS;
        }
        if self.texture.is_some() {
            f |= FLAG_TEXTURE;
        }
        if self.adjacency.is_some() {
            f |= FLAG_ADJACENCY;
        }
        f
    }

    /// The format version the blob gets: 3 with adjacency, else 2 with texture coordinates or a
    /// texture, else 1.
    pub fn version(&self) -> u16 {
        if self.adjacency.is_some() {
            VERSION
        } else if self.uvs.is_some() || self.texture.is_some() {
            VERSION_2
        } else {
            VERSION_1
        }
    }
}

/// Pads `out` with zeros to a multiple of 4 bytes.
fn pad(out: &mut Vec<u8>) {
    while !out.len().is_multiple_of(4) {
        out.push(0);
    }
}

/// Writes `mesh` in the packed mesh format ([`MeshData::version`]): 16-bit indices up to 65,535
/// vertices, 32-bit beyond.
pub fn encode(mesh: &MeshData) -> Vec<u8> {
    let n = mesh.positions.len();
    let t = mesh.triangles.len();
    let wide = mesh.wide_indices();
    let mut out = Vec::with_capacity(HEADER_LEN + 15 * n + 12 * t + 12);
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&mesh.version().to_le_bytes());
    out.extend_from_slice(&mesh.flags().to_le_bytes());
    out.extend_from_slice(&(n as u32).to_le_bytes());
    out.extend_from_slice(&(t as u32).to_le_bytes());
    for o in mesh.offset {
        out.extend_from_slice(&o.to_le_bytes());
    }
    for s in mesh.scale {
        out.extend_from_slice(&s.to_le_bytes());
    }
    for p in &mesh.positions {
        for c in p {
            out.extend_from_slice(&c.to_le_bytes());
        }
    }
    pad(&mut out);
    if let Some(normals) = &mesh.normals {
        for v in normals {
            for c in v {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        pad(&mut out);
    }
    if let Some(colors) = &mesh.colors {
        for c in colors {
            out.extend_from_slice(c);
        }
        pad(&mut out);
    }
    if let Some(uvs) = &mesh.uvs {
        for uv in uvs {
            for c in uv {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        pad(&mut out);
    }
    for tri in &mesh.triangles {
        for &i in tri {
            if wide {
                out.extend_from_slice(&i.to_le_bytes());
            } else {
                // In range: there are at most 65,535 vertices.
                out.extend_from_slice(&(i as u16).to_le_bytes());
            }
        }
    }
    pad(&mut out);
    if let Some(adjacency) = &mesh.adjacency {
        let narrow = t <= MAX_NARROW_NEIGHBOURS;
        for entry in adjacency.iter().flatten() {
            if narrow {
                // Below 65,535 when not none: there are at most 65,535 triangles.
                let e = if *entry == NO_NEIGHBOUR {
                    NO_NEIGHBOUR_U16
                } else {
                    *entry as u16
                };
                out.extend_from_slice(&e.to_le_bytes());
            } else {
                out.extend_from_slice(&entry.to_le_bytes());
            }
        }
        pad(&mut out);
    }
    if let Some(t) = &mesh.texture {
        out.extend_from_slice(&[t.width_log2, t.height_log2, 0, 0]);
        out.extend_from_slice(&t.texels);
        pad(&mut out);
    }
    out
}

/// 2^16 and 2^32 as `f64`.
const F16: f64 = 65536.0;
const F32: f64 = 4_294_967_296.0;

/// The per-axis quantisation of one mesh: box centre and step, as the header stores them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Quantiser {
    /// The box centre in 16.16.
    pub offset: [i32; 3],
    /// 16.16 units per quantum in 16.16.
    pub scale: [u32; 3],
}

impl Quantiser {
    /// The quantisation for positions inside the box `lo ..= hi` (model units): the centre
    /// rounded to 16.16, and the smallest step that reaches both ends of the box with 32767
    /// quanta. An axis of no extent gets a step of one 16.16 unit. `None` when the box leaves the
    /// 16.16 range (or is not finite).
    pub fn for_box(lo: [f64; 3], hi: [f64; 3]) -> Option<Self> {
        let mut offset = [0i32; 3];
        let mut scale = [0u32; 3];
        for k in 0..3 {
            if !(lo[k].is_finite() && hi[k].is_finite() && lo[k] <= hi[k]) {
                return None;
            }
            let o = ((lo[k] + hi[k]) / 2.0 * F16).round();
            if o.abs() >= 2_147_483_647.0 {
                return None;
            }
            let c = o / F16;
            let h = (hi[k] - c).max(c - lo[k]).max(0.0);
            let s = if h == 0.0 {
                F16
            } else {
                (h * F32 / f64::from(QUANTUM_MAX)).ceil().max(1.0)
            };
            if s > f64::from(u32::MAX) {
                return None;
            }
            offset[k] = o as i32;
            scale[k] = s as u32;
            // The reader's own range check (PackedMesh::parse, BadScale).
            let reach = (i64::from(scale[k]) * i64::from(QUANTUM_MAX)) >> 16;
            let o = i64::from(offset[k]);
            if o - reach - 1 < i64::from(i32::MIN) || o + reach + 1 > i64::from(i32::MAX) {
                return None;
            }
        }
        Some(Self { offset, scale })
    }

    /// Decodes one quantum on axis `k` to 16.16 bits, exactly as the reader does.
    pub fn decode_bits(&self, k: usize, q: i16) -> i32 {
        let q = i64::from(q);
        (i64::from(self.offset[k]) + ((q * i64::from(self.scale[k]) + (1 << 15)) >> 16)) as i32
    }

    /// Decodes one quantum on axis `k` to model units.
    pub fn decode(&self, k: usize, q: i16) -> f64 {
        f64::from(self.decode_bits(k, q)) / F16
    }

    /// The quanta whose decoded position is nearest to `p` (model units), clamped to the box.
    pub fn quantise(&self, p: [f64; 3]) -> [i16; 3] {
        [0, 1, 2].map(|k| {
            let t = (p[k] - f64::from(self.offset[k]) / F16) * F32 / f64::from(self.scale[k]);
            let max = f64::from(QUANTUM_MAX);
            let q0 = if t.is_finite() {
                t.round().clamp(-max, max) as i16
            } else {
                0
            };
            // Rounding the decoded value to 16.16 can make a neighbour slightly closer.
            let mut best = q0;
            let limit = i32::from(QUANTUM_MAX);
            for q in [i32::from(q0) - 1, i32::from(q0) + 1] {
                if q.abs() > limit {
                    continue;
                }
                let q = q as i16;
                if (self.decode(k, q) - p[k]).abs() < (self.decode(k, best) - p[k]).abs() {
                    best = q;
                }
            }
            best
        })
    }
}

/// Quantises a unit normal: each component times 32767, rounded. A zero vector stays zero.
pub fn quantise_normal(n: [f64; 3]) -> [i16; 3] {
    let max = f64::from(QUANTUM_MAX);
    n.map(|c| {
        if c.is_finite() {
            (c * max).round().clamp(-max, max) as i16
        } else {
            0
        }
    })
}

/// Decodes a normal quantum to model units exactly as the reader does (16.16, rounded).
pub fn decode_normal(q: i16) -> f64 {
    let bits = (i64::from(q) * 65536 + 16383).div_euclid(i64::from(QUANTUM_MAX));
    bits as f64 / F16
}

#[cfg(test)]
mod tests {
    use super::*;
    use rasterizer_core::mesh::PackedMesh;

    fn sample(n: usize, normals: bool, colors: bool) -> MeshData {
        MeshData {
            offset: [65536, -65536, 0],
            scale: [131072, 65536, 1],
            positions: (0..n)
                .map(|i| [(i % 1000) as i16, -((i % 999) as i16), 7])
                .collect(),
            normals: normals.then(|| vec![[0, 0, 32767]; n]),
            colors: colors.then(|| (0..n).map(|i| [i as u8, 1, 2]).collect()),
            uvs: None,
            triangles: (0..n.saturating_sub(2))
                .map(|i| [i as u32, i as u32 + 1, i as u32 + 2])
                .collect(),
            texture: None,
            adjacency: None,
        }
    }

    #[test]
    fn every_layout_parses_and_reads_back() {
        for n in [0, 3, 4, 5, 7] {
            for (normals, colors) in [(false, false), (true, false), (false, true), (true, true)] {
                let m = sample(n, normals, colors);
                let blob = encode(&m);
                let p = PackedMesh::parse(&blob).unwrap_or_else(|e| panic!("{n} {m:?}: {e}"));
                assert_eq!(p.vertices(), n);
                assert_eq!(p.triangles(), n.saturating_sub(2));
                assert_eq!(p.quantisation(), (m.offset, m.scale));
                for (i, t) in m.triangles.iter().enumerate() {
                    assert_eq!(p.triangle_indices(i), Some(*t));
                }
                if colors && n > 0 {
                    let c = p.color_of(n - 1).unwrap();
                    assert_eq!(c.r(), (n - 1) as u8);
                }
                assert_eq!(p.normal_bits(0).is_some(), normals && n > 0);
            }
        }
    }

    use embedded_graphics_core::pixelcolor::RgbColor;

    #[test]
    fn version_1_without_uvs_version_2_with() {
        let mut m = sample(5, true, true);
        let v1 = encode(&m);
        assert_eq!(u16::from_le_bytes([v1[4], v1[5]]), VERSION_1);
        m.uvs = Some((0..5).map(|i| [i * 65536, -i]).collect());
        let with_uvs = encode(&m);
        assert_eq!(u16::from_le_bytes([with_uvs[4], with_uvs[5]]), VERSION_2);
        // The uvs go between the colours and the triangles: everything before is unchanged.
        let before_uvs = v1.len() - 3 * 6;
        assert_eq!(with_uvs[8..before_uvs], v1[8..before_uvs]);
        let p = PackedMesh::parse(&with_uvs).unwrap();
        assert_eq!(p.uv_bits(4), Some([4 * 65536, -4]));
        assert!(p.texture().is_none());
        m.texture = Some(TextureData {
            width_log2: 1,
            height_log2: 0,
            texels: vec![0x1f, 0, 0, 0xf8],
        });
        let blob = encode(&m);
        let p = PackedMesh::parse(&blob).unwrap();
        let t = p.texture().unwrap();
        assert_eq!((t.width(), t.height()), (2, 1));
        assert_eq!((t.texel(0, 0), t.texel(1, 0)), (0x001f, 0xf800));
        assert_eq!(p.triangle_indices(2), Some([2, 3, 4]));
    }

    #[test]
    fn wide_indices_above_65535_vertices() {
        let mut m = sample(65_535, false, false);
        assert!(!m.wide_indices());
        assert_eq!(PackedMesh::parse(&encode(&m)).unwrap().vertices(), 65_535);
        m.positions.push([0; 3]);
        m.triangles.push([65_535, 0, 1]);
        assert!(m.wide_indices());
        let blob = encode(&m);
        assert_eq!(blob[6] & FLAG_U32_INDICES as u8, FLAG_U32_INDICES as u8);
        let p = PackedMesh::parse(&blob).unwrap();
        assert_eq!(
            p.triangle_indices(m.triangles.len() - 1),
            Some([65_535, 0, 1])
        );
    }

    #[test]
    fn adjacency_is_version_3_and_reads_back() {
        use rasterizer_core::math::Fx16;
        use rasterizer_core::mesh::MeshSource;
        let mut m = sample(7, true, false);
        let plain = encode(&m);
        // Triangles of the strip share their middle edges: i with i + 1.
        let n = m.triangles.len() as u32;
        m.adjacency = Some(
            (0..n)
                .map(|i| {
                    [
                        NO_NEIGHBOUR,
                        i.checked_sub(1).unwrap_or(NO_NEIGHBOUR),
                        i + 1,
                    ]
                })
                .map(|mut e| {
                    if e[2] == n {
                        e[2] = NO_NEIGHBOUR;
                    }
                    e
                })
                .collect(),
        );
        let blob = encode(&m);
        assert_eq!(u16::from_le_bytes([blob[4], blob[5]]), VERSION);
        assert_eq!(blob[6] & FLAG_ADJACENCY as u8, FLAG_ADJACENCY as u8);
        // 5 triangles: 30 bytes of u16 entries and 2 of padding, after the triangles.
        assert_eq!(blob.len(), plain.len() + 32);
        assert_eq!(blob[8..plain.len()], plain[8..]);
        let p = PackedMesh::parse(&blob).unwrap();
        assert!(p.has_adjacency());
        for (t, e) in m.adjacency.as_ref().unwrap().iter().enumerate() {
            assert_eq!(p.neighbour_indices(t), Some(*e));
            assert_eq!(MeshSource::<Fx16>::neighbours(&p, t), *e);
        }
        // With texture coordinates and a texture the adjacency comes before the texture.
        m.uvs = Some(vec![[0, 0]; 7]);
        m.texture = Some(TextureData {
            width_log2: 0,
            height_log2: 0,
            texels: vec![0x34, 0x12],
        });
        let p_blob = encode(&m);
        let p = PackedMesh::parse(&p_blob).unwrap();
        assert_eq!(p.neighbour_indices(2), Some([NO_NEIGHBOUR, 1, 3]));
        assert_eq!(p.texture().unwrap().texel(0, 0), 0x1234);
        m.adjacency = None;
        assert_eq!(encode(&m)[4], VERSION_2 as u8, "no adjacency: version 2");
    }

    #[test]
    fn neighbour_entries_widen_above_65535_triangles() {
        // 65,535 triangles on 3 vertices take u16 entries; one more takes u32.
        for (t, width) in [(65_535usize, 2), (65_536, 4)] {
            let mut m = sample(3, false, false);
            m.triangles = vec![[0, 1, 2]; t];
            let last = t as u32 - 1;
            let mut adjacency = vec![[NO_NEIGHBOUR; 3]; t];
            adjacency[0] = [last, NO_NEIGHBOUR, 1];
            adjacency[t - 1] = [0, last, NO_NEIGHBOUR];
            m.adjacency = Some(adjacency);
            let blob = encode(&m);
            let without = encode(&MeshData {
                adjacency: None,
                ..m.clone()
            });
            assert_eq!(blob.len() - without.len(), (3 * width * t + 3) & !3, "{t}");
            let p = PackedMesh::parse(&blob).unwrap();
            assert_eq!(p.neighbour_indices(0), Some([last, NO_NEIGHBOUR, 1]));
            assert_eq!(p.neighbour_indices(t - 1), Some([0, last, NO_NEIGHBOUR]));
            assert_eq!(p.neighbour_indices(t), None);
        }
    }

    #[test]
    fn quantiser_error_is_half_a_step_plus_rounding() {
        let lo = [-1.0, -0.25, 3.0];
        let hi = [1.0, 0.5, 3.0];
        let q = Quantiser::for_box(lo, hi).unwrap();
        assert_eq!(q.scale[2], 65536, "flat axis");
        let mut worst = [0f64; 3];
        for i in 0..=1000 {
            let f = i as f64 / 1000.0;
            let p = [0, 1, 2].map(|k| lo[k] + (hi[k] - lo[k]) * f);
            let qq = q.quantise(p);
            for k in 0..3 {
                worst[k] = worst[k].max((q.decode(k, qq[k]) - p[k]).abs());
            }
        }
        for (k, (&w, &s)) in worst.iter().zip(&q.scale).take(2).enumerate() {
            let step = f64::from(s) / F32;
            assert!(w <= step / 2.0 + 0.5 / F16, "axis {k}: {w}");
        }
        assert_eq!(worst[2], 0.0);
        assert!(Quantiser::for_box([-40000.0; 3], [0.0; 3]).is_none());
        assert!(Quantiser::for_box([-32766.9; 3], [32766.9; 3]).is_some());
    }

    #[test]
    fn normals_round_trip() {
        for c in [-1.0, -0.5, 0.0, 0.3, 1.0] {
            let q = quantise_normal([c, 0.0, 0.0])[0];
            assert!((decode_normal(q) - c).abs() <= 0.5 / 32767.0 + 0.5 / F16);
        }
    }
}
