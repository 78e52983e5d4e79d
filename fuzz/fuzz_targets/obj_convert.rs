//! Any OBJ text: the converter returns a typed error, or a blob that the firmware-side reader
//! accepts with the counts the converter reported. Every option combination is exercised, chosen
//! by the first byte.
#![no_main]

use host_tools::convert::{convert_obj, NormalMode, Options};
use libfuzzer_sys::fuzz_target;
use rasterizer_core::mesh::PackedMesh;

fuzz_target!(|data: &[u8]| {
    let Some((&choice, text)) = data.split_first() else {
        return;
    };
    let normals = match choice % 5 {
        0 => None,
        1 => Some(NormalMode::None),
        2 => Some(NormalMode::Keep),
        3 => Some(NormalMode::Flat),
        _ => Some(NormalMode::Smooth),
    };
    let opts = Options {
        center_unit_sphere: choice & 8 != 0,
        normals,
        weld: choice & 16 != 0,
        no_uvs: choice & 32 != 0,
        adjacency: choice & 64 != 0,
        progress: false,
    };
    let mut warnings = Vec::new();
    if let Ok(conv) = convert_obj("fuzz.obj", text, None, &opts, &mut warnings) {
        let mesh =
            PackedMesh::parse(&conv.blob).expect("the converter wrote a blob the reader rejects");
        assert_eq!(mesh.triangles(), conv.mesh.triangles.len());
    }
});
