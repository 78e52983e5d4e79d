//! The packed mesh reader: valid blobs decode as the format says, and any byte string gives a
//! mesh or a typed error, never a panic or an out-of-bounds read.
//!
//! The fuzzing is proptest over arbitrary and mutated blobs. CI runs a few thousand inputs per
//! property; `MESH_FUZZ_CASES=1000000 cargo test --release -p tests --test mesh_format` runs the
//! long version (see the CHANGELOG for the last long run).

use proptest::prelude::*;
use rasterizer_core::mesh::MeshError;
use rasterizer_core::mesh::{MeshSource, NO_NEIGHBOUR};
use rasterizer_core::prelude::*;
use rasterizer_core::texture::TextureError;
use tests::packed::{encode, encode_v2, encode_v3, Tex, Vert};

fn cases(default: u32) -> u32 {
    std::env::var("MESH_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn tetra() -> (Vec<Vert>, Vec<[u32; 3]>) {
    let v = |q: [i16; 3], n: [i16; 3], c: [u8; 3]| Vert { q, n, c };
    (
        vec![
            v([32767, 32767, 32767], [18918, 18918, 18918], [255, 0, 0]),
            v(
                [-32767, -32767, 32767],
                [-18918, -18918, 18918],
                [0, 255, 0],
            ),
            v(
                [-32767, 32767, -32767],
                [-18918, 18918, -18918],
                [0, 0, 255],
            ),
            v([32767, -32767, -32767], [18918, -18918, -18918], [9, 9, 9]),
        ],
        vec![[0, 1, 3], [0, 2, 1], [0, 3, 2], [1, 2, 3]],
    )
}

/// Every accessor on every index, through the pipeline's trait too: must not panic.
fn touch_everything(m: &PackedMesh<'_>) {
    for i in 0..m.vertices() + 2 {
        let _ = m.position_bits(i);
        let _ = m.normal_bits(i);
        let _ = m.color_of(i);
        let _ = m.uv_bits(i);
        let _ = MeshSource::<Fx16>::uv(m, i);
        let _: Vec3<Fx16> = MeshSource::<Fx16>::position(m, i);
        let _: Option<Vec3<Fx16>> = MeshSource::<Fx16>::normal(m, i);
    }
    if let Some(t) = m.texture() {
        assert!(m.uv_bits(0).is_some() || m.vertices() == 0);
        let (w, h) = (t.width(), t.height());
        for (x, y) in [(0, 0), (w - 1, h - 1), (w, h), (u32::MAX, 7)] {
            let _ = t.texel(x, y);
        }
    }
    for t in 0..m.triangles() + 2 {
        if let Some(idx) = m.triangle_indices(t) {
            assert!(idx.iter().all(|&i| (i as usize) < m.vertices()));
        }
        let _ = MeshSource::<Fx16>::triangle(m, t);
        let n = MeshSource::<Fx16>::neighbours(m, t);
        assert!(n
            .iter()
            .all(|&u| u == NO_NEIGHBOUR || (u as usize) < m.triangles()));
        assert_eq!(
            m.neighbour_indices(t).is_some(),
            m.has_adjacency() && t < m.triangles()
        );
    }
}

#[test]
fn decodes_positions_normals_colours_and_indices() {
    let (v, t) = tetra();
    // Offset (0.5, -1, 2) and one quantum = 1/32767 units: the box is [-1, 1] around the offset.
    let unit = (65536u64 * 65536 / 32767) as u32;
    let blob = encode(
        &v,
        &t,
        [32768, -65536, 131072],
        [unit; 3],
        true,
        true,
        false,
    );
    let m = PackedMesh::parse(&blob).unwrap();
    assert_eq!((m.vertices(), m.triangles()), (4, 4));
    let p = m.position_bits(0).unwrap();
    // 0.5 + 1 = 1.5, -1 + 1 = 0, 2 + 1 = 3, within one 16.16 step.
    for (got, want) in p.iter().zip([98304, 0, 196608]) {
        assert!((got - want).abs() <= 1, "{got} vs {want}");
    }
    let n = m.normal_bits(1).unwrap();
    assert!(
        (n[0] + 37837).abs() <= 1 && (n[2] - 37837).abs() <= 1,
        "{n:?}"
    );
    assert_eq!(
        m.color_of(2).map(|c| (c.r(), c.g(), c.b())),
        Some((0, 0, 255))
    );
    assert_eq!(m.triangle_indices(3), Some([1, 2, 3]));
    let wide = encode(&v, &t, [0; 3], [unit; 3], false, false, true);
    let m = PackedMesh::parse(&wide).unwrap();
    assert_eq!(m.triangle_indices(1), Some([0, 2, 1]));
    assert_eq!(m.normal_bits(0), None);
    assert_eq!(m.color_of(0), None);
}

#[test]
fn typed_errors() {
    let (v, t) = tetra();
    let unit = 131076;
    let good = encode(&v, &t, [0; 3], [unit; 3], true, false, false);
    assert!(PackedMesh::parse(&good).is_ok());
    assert_eq!(
        PackedMesh::parse(&good[..10]).unwrap_err(),
        MeshError::TooShort { len: 10 }
    );
    let mut b = good.clone();
    b[0] = b'X';
    assert_eq!(PackedMesh::parse(&b).unwrap_err(), MeshError::BadMagic);
    let mut b = good.clone();
    b[4] = 4;
    assert_eq!(
        PackedMesh::parse(&b).unwrap_err(),
        MeshError::UnsupportedVersion(4)
    );
    let mut b = good.clone();
    b[6] |= 8;
    assert_eq!(
        PackedMesh::parse(&b).unwrap_err(),
        MeshError::UnknownFlags(9)
    );
    let mut b = good.clone();
    b[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(matches!(
        PackedMesh::parse(&b).unwrap_err(),
        MeshError::BadCounts { .. }
    ));
    assert!(matches!(
        PackedMesh::parse(&good[..good.len() - 4]).unwrap_err(),
        MeshError::WrongLength { .. }
    ));
    let mut long = good.clone();
    long.extend_from_slice(&[0; 4]);
    assert!(matches!(
        PackedMesh::parse(&long).unwrap_err(),
        MeshError::WrongLength { .. }
    ));
    let bad_index = encode(&v, &[[0, 1, 4]], [0; 3], [unit; 3], false, false, false);
    assert_eq!(
        PackedMesh::parse(&bad_index).unwrap_err(),
        MeshError::IndexOutOfRange {
            triangle: 0,
            index: 4
        }
    );
    let zero_scale = encode(&v, &t, [0; 3], [unit, 0, unit], false, false, false);
    assert_eq!(
        PackedMesh::parse(&zero_scale).unwrap_err(),
        MeshError::BadScale
    );
    let huge = encode(
        &v,
        &t,
        [i32::MAX - 10, 0, 0],
        [unit; 3],
        false,
        false,
        false,
    );
    assert_eq!(PackedMesh::parse(&huge).unwrap_err(), MeshError::BadScale);
    let mut q = v.clone();
    q[2].q[1] = i16::MIN;
    let quantum = encode(&q, &t, [0; 3], [unit; 3], false, false, false);
    assert_eq!(
        PackedMesh::parse(&quantum).unwrap_err(),
        MeshError::BadQuantum { vertex: 2 }
    );
    // Non-zero padding after the 3-byte-per-vertex colours (4 vertices: 12 bytes, no padding) and
    // after 4 triangles of u16 (24 bytes, none): use 1 vertex and 1 triangle to get padding.
    let one = encode(
        &v[..1],
        &[[0, 0, 0]],
        [0; 3],
        [unit; 3],
        false,
        false,
        false,
    );
    assert!(PackedMesh::parse(&one).is_ok());
    let mut bad_pad = one.clone();
    let last = bad_pad.len() - 1;
    bad_pad[last] = 1;
    assert!(matches!(
        PackedMesh::parse(&bad_pad).unwrap_err(),
        MeshError::BadPadding { .. }
    ));
    assert!(PackedMesh::parse(&[]).is_err());
    assert_eq!(
        format!("{}", MeshError::BadMagic),
        "not a packed mesh (magic is not RMSH)"
    );
}

#[test]
fn empty_mesh_is_valid() {
    let blob = encode(&[], &[], [0; 3], [1; 3], false, false, false);
    let m = PackedMesh::parse(&blob).unwrap();
    assert_eq!((m.vertices(), m.triangles()), (0, 0));
    touch_everything(&m);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases(4000)))]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..200)) {
        if let Ok(m) = PackedMesh::parse(&bytes) {
            touch_everything(&m);
        }
    }

    #[test]
    fn arbitrary_bytes_behind_a_valid_header_never_panic(
        flags in 0u16..8, nv in 0u32..6, nt in 0u32..6, body in proptest::collection::vec(any::<u8>(), 0..160),
    ) {
        // A header that passes the first checks, then anything: reaches the deeper checks.
        let mut b = b"RMSH".to_vec();
        b.extend_from_slice(&1u16.to_le_bytes());
        b.extend_from_slice(&flags.to_le_bytes());
        b.extend_from_slice(&nv.to_le_bytes());
        b.extend_from_slice(&nt.to_le_bytes());
        b.extend_from_slice(&[0; 12]);
        b.extend_from_slice(&[1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0]);
        b.extend_from_slice(&body);
        if let Ok(m) = PackedMesh::parse(&b) {
            touch_everything(&m);
        }
    }

    #[test]
    fn mutated_valid_blobs_never_panic(
        flips in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..8),
        cut in any::<usize>(), normals in any::<bool>(), colors in any::<bool>(), wide in any::<bool>(),
    ) {
        let (v, t) = tetra();
        let mut blob = encode(&v, &t, [100, -200, 300], [131076, 9, 70000], normals, colors, wide);
        for (at, byte) in flips {
            let i = at % blob.len();
            blob[i] = byte;
        }
        let keep = if cut % 3 == 0 { cut % (blob.len() + 1) } else { blob.len() };
        if let Ok(m) = PackedMesh::parse(&blob[..keep]) {
            touch_everything(&m);
        }
    }

    #[test]
    fn random_valid_meshes_round_trip(
        verts in proptest::collection::vec((any::<[i16; 3]>(), any::<[i16; 3]>(), any::<[u8; 3]>()), 1..40),
        tri_seed in proptest::collection::vec(any::<[u32; 3]>(), 0..40),
        offset in any::<[i16; 3]>(), scale in 1u32..200_000, wide in any::<bool>(),
    ) {
        let clean = |q: [i16; 3]| q.map(|x| x.max(-32767));
        let v: Vec<Vert> = verts.iter().map(|(q, n, c)| Vert { q: clean(*q), n: clean(*n), c: *c }).collect();
        let t: Vec<[u32; 3]> = tri_seed.iter().map(|s| s.map(|i| i % v.len() as u32)).collect();
        let off = offset.map(i32::from);
        let blob = encode(&v, &t, off, [scale; 3], true, true, wide);
        let m = PackedMesh::parse(&blob).unwrap();
        prop_assert_eq!(m.triangles(), t.len());
        for (i, vert) in v.iter().enumerate() {
            let p = m.position_bits(i).unwrap();
            for k in 0..3 {
                let exact = f64::from(off[k]) + f64::from(vert.q[k]) * f64::from(scale) / 65536.0;
                prop_assert!((f64::from(p[k]) - exact).abs() <= 0.5 + 1e-9);
            }
            prop_assert_eq!(m.color_of(i).map(|c| [c.r(), c.g(), c.b()]), Some(vert.c));
        }
        for (k, tri) in t.iter().enumerate() {
            prop_assert_eq!(m.triangle_indices(k), Some(*tri));
        }
    }
}

/// The tetrahedron's texture coordinates: a corner of the texture per vertex, one outside.
const UVS: [[i32; 2]; 4] = [[0, 0], [65536, 0], [0, 65536], [-98304, 131072]];

/// A 4 x 2 texture whose texel (x, y) is `x + 16 y + 0xab00`, little-endian.
fn texels_4x2() -> Vec<u8> {
    (0..8u16)
        .flat_map(|i| (0xab00 + (i % 4) + 16 * (i / 4)).to_le_bytes())
        .collect()
}

fn textured(v: &[Vert], t: &[[u32; 3]], texels: &[u8], w: u8, h: u8) -> Vec<u8> {
    let tex = Tex {
        width_log2: w,
        height_log2: h,
        texels,
    };
    encode_v2(
        v,
        t,
        [0; 3],
        [131076; 3],
        true,
        true,
        false,
        Some(&UVS[..v.len()]),
        Some(tex),
    )
}

#[test]
fn version_2_decodes_uvs_and_texture() {
    let (v, t) = tetra();
    let texels = texels_4x2();
    let blob = textured(&v, &t, &texels, 2, 1);
    assert_eq!(blob[4], 2, "version 2");
    let m = PackedMesh::parse(&blob).unwrap();
    touch_everything(&m);
    for (i, uv) in UVS.iter().enumerate() {
        assert_eq!(m.uv_bits(i), Some(*uv));
        assert_eq!(MeshSource::<Fx16>::uv(&m, i), Some(*uv));
    }
    assert_eq!(m.uv_bits(4), None);
    let tex = m.texture().unwrap();
    assert_eq!((tex.width(), tex.height()), (4, 2));
    assert_eq!(tex.texel(3, 1), 0xab13);
    assert_eq!(tex.texel(1, 0), 0xab01);
    // Everything else reads as in version 1.
    assert_eq!(m.triangle_indices(3), Some([1, 2, 3]));
    assert_eq!(m.color_of(1).map(|c| c.g()), Some(255));
    assert!(m.normal_bits(0).is_some());

    // Texture coordinates without a texture, 1 x 1 and 1024 x 1024 textures.
    let uv_only = encode_v2(
        &v,
        &t,
        [0; 3],
        [131076; 3],
        false,
        false,
        true,
        Some(&UVS),
        None,
    );
    let m = PackedMesh::parse(&uv_only).unwrap();
    assert_eq!((m.uv_bits(3), m.texture()), (Some(UVS[3]), None));
    assert!(m.has_uvs());
    let one = textured(&v, &t, &[0x34, 0x12], 0, 0);
    let m = PackedMesh::parse(&one).unwrap();
    assert_eq!(m.texture().unwrap().texel(5, 9), 0x1234);
    let big = vec![0u8; 2 << 20];
    let big = textured(&v, &t, &big, 10, 10);
    let m = PackedMesh::parse(&big).unwrap();
    assert_eq!(m.texture().unwrap().width(), 1024);
    // Version 1 blobs have neither.
    let v1 = encode(&v, &t, [0; 3], [131076; 3], true, true, false);
    assert_eq!(v1[4], 1);
    let m = PackedMesh::parse(&v1).unwrap();
    assert_eq!((m.uv_bits(0), m.texture()), (None, None));
    assert!(!m.has_uvs());
    assert_eq!(MeshSource::<Fx16>::uv(&m, 0), None);
}

#[test]
fn version_2_typed_errors() {
    let (v, t) = tetra();
    let texels = texels_4x2();
    let good = textured(&v, &t, &texels, 2, 1);
    assert!(PackedMesh::parse(&good).is_ok());
    let flags_at = 6;

    // The new flags in a version 1 blob.
    for flag in [8u16, 16, 24] {
        let mut b = encode(&v, &t, [0; 3], [131076; 3], false, false, false);
        b[flags_at] |= flag as u8;
        assert_eq!(
            PackedMesh::parse(&b).unwrap_err(),
            MeshError::UnknownFlags(flag)
        );
    }
    let mut b = good.clone();
    b[flags_at] |= 32;
    assert_eq!(
        PackedMesh::parse(&b).unwrap_err(),
        MeshError::UnknownFlags(0b11_1011)
    );
    // A texture without texture coordinates.
    let mut b = good.clone();
    b[flags_at] &= !8;
    assert_eq!(
        PackedMesh::parse(&b).unwrap_err(),
        MeshError::TextureWithoutUvs
    );

    // Truncated: anywhere in the texels, in the texture header, before it.
    let header_at = good.len() - 4 - texels.len();
    for cut in [good.len() - 1, good.len() - 16, header_at + 2, header_at] {
        assert!(
            matches!(
                PackedMesh::parse(&good[..cut]).unwrap_err(),
                MeshError::WrongLength { .. }
            ),
            "cut at {cut}"
        );
    }
    assert_eq!(
        PackedMesh::parse(&good[..header_at]).unwrap_err(),
        MeshError::WrongLength {
            expected: header_at + 4,
            actual: header_at
        }
    );
    // Texels for other sides than the header's.
    for (w, h) in [(1, 1), (2, 2), (3, 1)] {
        assert_eq!(
            PackedMesh::parse(&textured(&v, &t, &texels, w, h)).unwrap_err(),
            MeshError::WrongLength {
                expected: header_at + 4 + (2 << (w + h)),
                actual: good.len()
            },
            "{w} x {h}"
        );
    }
    let mut long = good.clone();
    long.extend_from_slice(&[0; 4]);
    assert!(matches!(
        PackedMesh::parse(&long).unwrap_err(),
        MeshError::WrongLength { .. }
    ));
    // Larger than 1024 texels a side: refused before the length is looked at.
    for (w, h) in [(11, 0), (0, 11), (255, 255)] {
        assert_eq!(
            PackedMesh::parse(&textured(&v, &t, &texels, w, h)).unwrap_err(),
            MeshError::Texture(TextureError::TooLarge {
                width_log2: w,
                height_log2: h
            })
        );
    }
    // The texture header's zero bytes, and the padding after odd-length sections.
    for at in [header_at + 2, header_at + 3] {
        let mut b = good.clone();
        b[at] = 1;
        assert_eq!(
            PackedMesh::parse(&b).unwrap_err(),
            MeshError::BadPadding { offset: at }
        );
    }
    let one = textured(&v[..1], &[[0, 0, 0]], &[1, 2], 0, 0);
    assert!(PackedMesh::parse(&one).is_ok());
    let mut b = one.clone();
    let last = b.len() - 1;
    b[last] = 9;
    assert_eq!(
        PackedMesh::parse(&b).unwrap_err(),
        MeshError::BadPadding { offset: last }
    );
    // One triangle of u16 indices: 6 bytes, then 2 of padding before the texture.
    let mut b = one.clone();
    let before_texture = b.len() - 4 - 4 - 1;
    b[before_texture] = 9;
    assert_eq!(
        PackedMesh::parse(&b).unwrap_err(),
        MeshError::BadPadding {
            offset: before_texture
        }
    );
    assert_eq!(
        MeshError::Texture(TextureError::TooLarge {
            width_log2: 11,
            height_log2: 0
        })
        .to_string(),
        "bad texture: a 2048x1 texture is larger than 1024x1024 texels"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases(4000)))]

    #[test]
    fn arbitrary_bytes_behind_a_version_2_header_never_panic(
        flags in 0u16..64, nv in 0u32..6, nt in 0u32..6, sides in any::<[u8; 2]>(),
        body in proptest::collection::vec(any::<u8>(), 0..160),
    ) {
        let mut b = b"RMSH".to_vec();
        b.extend_from_slice(&2u16.to_le_bytes());
        b.extend_from_slice(&flags.to_le_bytes());
        b.extend_from_slice(&nv.to_le_bytes());
        b.extend_from_slice(&nt.to_le_bytes());
        b.extend_from_slice(&[0; 12]);
        b.extend_from_slice(&[1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0]);
        b.extend_from_slice(&body);
        // Small sides, so that a texture header falling in the body often fits.
        let at = b.len().saturating_sub(12).max(40);
        if at + 2 <= b.len() {
            b[at] = sides[0] % 3;
            b[at + 1] = sides[1] % 3;
        }
        if let Ok(m) = PackedMesh::parse(&b) {
            touch_everything(&m);
        }
    }

    #[test]
    fn mutated_textured_blobs_never_panic(
        flips in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..8),
        cut in any::<usize>(),
    ) {
        let (v, t) = tetra();
        let mut blob = textured(&v, &t, &texels_4x2(), 2, 1);
        for (at, byte) in flips {
            let i = at % blob.len();
            blob[i] = byte;
        }
        let keep = if cut % 3 == 0 { cut % (blob.len() + 1) } else { blob.len() };
        if let Ok(m) = PackedMesh::parse(&blob[..keep]) {
            touch_everything(&m);
        }
    }

    #[test]
    fn random_textured_meshes_round_trip(
        uvs in proptest::collection::vec(any::<[i32; 2]>(), 1..40),
        sides in (0u8..4, 0u8..4), texel_seed in any::<u16>(),
    ) {
        let v: Vec<Vert> = (0..uvs.len()).map(|i| Vert { q: [i as i16; 3], ..Vert::default() }).collect();
        let t: Vec<[u32; 3]> = (0..uvs.len() as u32).map(|i| [i, 0, 0]).collect();
        let n = 1usize << (sides.0 + sides.1);
        let texels: Vec<u8> = (0..n as u16).flat_map(|i| (i ^ texel_seed).to_le_bytes()).collect();
        let tex = Tex { width_log2: sides.0, height_log2: sides.1, texels: &texels };
        let blob = encode_v2(&v, &t, [0; 3], [65536; 3], false, false, false, Some(&uvs), Some(tex));
        let m = PackedMesh::parse(&blob).unwrap();
        for (i, uv) in uvs.iter().enumerate() {
            prop_assert_eq!(m.uv_bits(i), Some(*uv));
        }
        let tex = m.texture().unwrap();
        prop_assert_eq!(tex.bytes(), &texels[..]);
        let w = 1u32 << sides.0;
        for i in 0..n as u32 {
            prop_assert_eq!(tex.texel(i % w, i / w), (i as u16) ^ texel_seed);
        }
    }
}

const N: u32 = NO_NEIGHBOUR;

/// The tetrahedron's neighbours: closed, so every entry is set.
const TETRA_ADJACENCY: [[u32; 3]; 4] = [[1, 3, 2], [2, 3, 0], [0, 3, 1], [1, 2, 0]];

fn with_adjacency(v: &[Vert], t: &[[u32; 3]], adjacency: &[[u32; 3]]) -> Vec<u8> {
    encode_v3(
        v,
        t,
        [0; 3],
        [131076; 3],
        true,
        false,
        false,
        None,
        None,
        Some(adjacency),
    )
}

#[test]
fn version_3_reads_adjacency() {
    let (v, t) = tetra();
    assert_eq!(fixtures::adjacency::adjacency(&t), TETRA_ADJACENCY);
    let blob = with_adjacency(&v, &t, &TETRA_ADJACENCY);
    assert_eq!(blob[4], 3, "version 3");
    let m = PackedMesh::parse(&blob).unwrap();
    touch_everything(&m);
    assert!(m.has_adjacency());
    assert!(MeshSource::<Fx16>::has_adjacency(&m));
    for (k, n) in TETRA_ADJACENCY.iter().enumerate() {
        assert_eq!(m.neighbour_indices(k), Some(*n));
        assert_eq!(MeshSource::<Fx16>::neighbours(&m, k), *n);
    }
    assert_eq!(m.neighbour_indices(4), None);
    assert_eq!(MeshSource::<Fx16>::neighbours(&m, 4), [N; 3]);
    // Everything else reads as before.
    assert_eq!(m.triangle_indices(3), Some([1, 2, 3]));
    assert!(m.normal_bits(0).is_some());

    // Boundary edges: the u16 none reads as NO_NEIGHBOUR.
    let open = [[N, N, 1], [0, N, N]];
    let blob = with_adjacency(&v, &t[..2], &open);
    let m = PackedMesh::parse(&blob).unwrap();
    assert_eq!(m.neighbour_indices(0), Some([N, N, 1]));
    assert_eq!(m.neighbour_indices(1), Some([0, N, N]));

    // With texture coordinates and a texture: the adjacency sits before the texture.
    let texels = texels_4x2();
    let tex = Tex {
        width_log2: 2,
        height_log2: 1,
        texels: &texels,
    };
    let blob = encode_v3(
        &v,
        &t,
        [0; 3],
        [131076; 3],
        false,
        true,
        false,
        Some(&UVS),
        Some(tex),
        Some(&TETRA_ADJACENCY),
    );
    let m = PackedMesh::parse(&blob).unwrap();
    touch_everything(&m);
    assert_eq!(m.neighbour_indices(2), Some(TETRA_ADJACENCY[2]));
    assert_eq!(m.texture().unwrap().texel(3, 1), 0xab13);
    assert_eq!(m.uv_bits(3), Some(UVS[3]));

    // A version 3 blob without the flag is valid and has no adjacency; older blobs neither.
    let mut b = encode(&v, &t, [0; 3], [131076; 3], true, false, false);
    assert!(!PackedMesh::parse(&b).unwrap().has_adjacency());
    b[4] = 3;
    let m = PackedMesh::parse(&b).unwrap();
    assert!(!m.has_adjacency());
    assert_eq!(m.neighbour_indices(0), None);
    assert_eq!(MeshSource::<Fx16>::neighbours(&m, 0), [N; 3]);
}

#[test]
fn version_3_typed_errors() {
    let (v, t) = tetra();
    let good = with_adjacency(&v, &t, &TETRA_ADJACENCY);
    assert!(PackedMesh::parse(&good).is_ok());

    // An entry past the triangles, also one just below the u16 none.
    for bad in [4, 5, 0xFFFE] {
        let mut a = TETRA_ADJACENCY;
        a[2][1] = bad;
        assert_eq!(
            PackedMesh::parse(&with_adjacency(&v, &t, &a)).unwrap_err(),
            MeshError::NeighbourOutOfRange {
                triangle: 2,
                entry: bad
            }
        );
    }
    assert_eq!(
        MeshError::NeighbourOutOfRange {
            triangle: 2,
            entry: 7
        }
        .to_string(),
        "triangle 2 lists triangle 7 as a neighbour, which does not exist"
    );

    // The flag on versions 1 and 2: unknown there, as before.
    for version in [1, 2] {
        let mut b = good.clone();
        b[4] = version;
        assert_eq!(
            PackedMesh::parse(&b).unwrap_err(),
            MeshError::UnknownFlags(0b10_0001),
            "version {version}"
        );
    }

    // Wrong lengths: a missing entry, a missing section, a section too many.
    let header_len = good.len() - 24;
    assert_eq!(
        PackedMesh::parse(&good[..good.len() - 4]).unwrap_err(),
        MeshError::WrongLength {
            expected: good.len(),
            actual: good.len() - 4
        }
    );
    // 18 bytes of entries and 2 of padding instead of 24.
    assert_eq!(
        PackedMesh::parse(&with_adjacency(&v, &t, &TETRA_ADJACENCY[..3])).unwrap_err(),
        MeshError::WrongLength {
            expected: good.len(),
            actual: good.len() - 4
        }
    );
    let mut b = good[..header_len].to_vec();
    assert_eq!(
        PackedMesh::parse(&b).unwrap_err(),
        MeshError::WrongLength {
            expected: good.len(),
            actual: header_len
        }
    );
    b[6] &= !32;
    assert!(PackedMesh::parse(&b).is_ok(), "the same without the flag");
    let mut long = good.clone();
    long.extend_from_slice(&[0; 4]);
    assert!(matches!(
        PackedMesh::parse(&long).unwrap_err(),
        MeshError::WrongLength { .. }
    ));

    // One triangle: 6 bytes of entries, then 2 of padding that must be zero.
    let one = with_adjacency(&v[..3], &[[0, 1, 2]], &[[N; 3]]);
    assert!(PackedMesh::parse(&one).is_ok());
    let mut b = one.clone();
    let last = b.len() - 1;
    b[last] = 1;
    assert_eq!(
        PackedMesh::parse(&b).unwrap_err(),
        MeshError::BadPadding { offset: last }
    );
}

#[test]
fn neighbour_entries_are_u32_above_65535_triangles() {
    let (v, _) = tetra();
    let t = vec![[0u32, 1, 2]; 65_536];
    let mut a = vec![[N; 3]; t.len()];
    // 0xFFFF is a triangle here, not none, and 65,535 is the last one.
    a[0] = [0xFFFF, N, 1];
    a[0xFFFF] = [0, 0xFFFE, N];
    let blob = with_adjacency(&v, &t, &a);
    let m = PackedMesh::parse(&blob).unwrap();
    assert_eq!(m.neighbour_indices(0), Some([0xFFFF, N, 1]));
    assert_eq!(m.neighbour_indices(0xFFFF), Some([0, 0xFFFE, N]));
    assert_eq!(m.neighbour_indices(1), Some([N; 3]));
    // One triangle fewer: u16 entries, half the section, and 0xFFFF is none again.
    let narrow = with_adjacency(&v, &t[1..], &a[1..]);
    assert_eq!(blob.len() - narrow.len(), 6 + 6 * 65_536 + 2);
    let m = PackedMesh::parse(&narrow).unwrap();
    assert_eq!(m.neighbour_indices(0xFFFE), Some([0, 0xFFFE, N]));
    // (The blob is too large to print, so errors are compared with `.err()`.)
    a[7][2] = 65_536;
    assert_eq!(
        PackedMesh::parse(&with_adjacency(&v, &t, &a)).err(),
        Some(MeshError::NeighbourOutOfRange {
            triangle: 7,
            entry: 65_536
        })
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases(4000)))]

    #[test]
    fn mutated_adjacency_blobs_never_panic(
        flips in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..8),
        cut in any::<usize>(), version in 1u8..5,
    ) {
        let (v, t) = tetra();
        let mut blob = with_adjacency(&v, &t, &TETRA_ADJACENCY);
        blob[4] = version;
        for (at, byte) in flips {
            let i = at % blob.len();
            blob[i] = byte;
        }
        let keep = if cut % 3 == 0 { cut % (blob.len() + 1) } else { blob.len() };
        if let Ok(m) = PackedMesh::parse(&blob[..keep]) {
            touch_everything(&m);
        }
    }

    #[test]
    fn random_adjacency_round_trips(
        tri_seed in proptest::collection::vec(any::<[u8; 3]>(), 0..60),
    ) {
        let v: Vec<Vert> = (0..6).map(|i| Vert { q: [i; 3], ..Vert::default() }).collect();
        let t: Vec<[u32; 3]> = tri_seed.iter().map(|s| s.map(|i| u32::from(i % 6))).collect();
        let a = fixtures::adjacency::adjacency(&t);
        let blob = with_adjacency(&v, &t, &a);
        let m = PackedMesh::parse(&blob).unwrap();
        for (k, n) in a.iter().enumerate() {
            prop_assert_eq!(m.neighbour_indices(k), Some(*n));
        }
    }
}
