//! Any byte string gives a packed mesh whose every accessor works, or a typed error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rasterizer_core::math::{Fx16, Vec3};
use rasterizer_core::mesh::PackedMesh;
use rasterizer_core::mesh::{MeshSource, NO_NEIGHBOUR};

fuzz_target!(|data: &[u8]| {
    if let Ok(m) = PackedMesh::parse(data) {
        for i in 0..m.vertices() + 1 {
            let _ = m.position_bits(i);
            let _ = m.normal_bits(i);
            let _ = m.color_of(i);
            let _ = m.uv_bits(i);
            let _: Vec3<Fx16> = MeshSource::<Fx16>::position(&m, i);
        }
        if let Some(tex) = m.texture() {
            let _ = tex.texel(tex.width() - 1, tex.height() - 1);
            let _ = tex.texel(u32::MAX, u32::MAX);
        }
        for t in 0..m.triangles() + 1 {
            if let Some(idx) = m.triangle_indices(t) {
                assert!(idx.iter().all(|&i| (i as usize) < m.vertices()));
            }
            let n = MeshSource::<Fx16>::neighbours(&m, t);
            assert!(n
                .iter()
                .all(|&u| u == NO_NEIGHBOUR || (u as usize) < m.triangles()));
        }
    }
});
