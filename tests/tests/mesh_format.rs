//! The packed mesh reader: valid blobs decode as the format says, and any byte string gives a
//! mesh or a typed error, never a panic or an out-of-bounds read.
//!
//! The fuzzing is proptest over arbitrary and mutated blobs. CI runs a few thousand inputs per
//! property; `MESH_FUZZ_CASES=1000000 cargo test --release -p tests --test mesh_format` runs the
//! long version (see the CHANGELOG for the last long run).

use proptest::prelude::*;
use rasterizer_core::mesh::MeshError;
use rasterizer_core::mesh::MeshSource;
use rasterizer_core::prelude::*;
use tests::packed::{encode, Vert};

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
        let _: Vec3<Fx16> = MeshSource::<Fx16>::position(m, i);
        let _: Option<Vec3<Fx16>> = MeshSource::<Fx16>::normal(m, i);
    }
    for t in 0..m.triangles() + 2 {
        if let Some(idx) = m.triangle_indices(t) {
            assert!(idx.iter().all(|&i| (i as usize) < m.vertices()));
        }
        let _ = MeshSource::<Fx16>::triangle(m, t);
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
    b[4] = 2;
    assert_eq!(
        PackedMesh::parse(&b).unwrap_err(),
        MeshError::UnsupportedVersion(2)
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
