//! Mesa llvmpipe's triangle coverage cases (`tests/conformance/triangles`, a copy of the shared
//! set), read for every test that draws them: `conformance.rs` through `fill_triangle`,
//! `pipeline_coverage.rs` through the 3D pipeline.

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use serde_json::Value;
use std::path::PathBuf;

/// One case: the triangles to draw in order, and the id of the triangle llvmpipe shows at each
/// pixel (-1 where none).
pub struct Case {
    pub name: String,
    pub width: u32,
    pub height: u32,
    /// Vertices in 1/16 pixel, the cases' own grid.
    pub triangles: Vec<[(i64, i64); 3]>,
    /// `ids[y][x]`.
    pub ids: Vec<Vec<i64>>,
}

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("conformance/triangles")
}

fn sixteenths(v: &Value) -> i64 {
    let raw = v.as_f64().expect("coordinate is a number") * 16.0;
    assert_eq!(raw, raw.round(), "vertex off the 1/16 grid");
    raw as i64
}

fn json(name: &str) -> Value {
    let text = std::fs::read_to_string(dir().join(name)).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// Every case of the index, in its order.
pub fn load_cases() -> Vec<Case> {
    let index = json("INDEX.json");
    let names = index["cases"].as_array().unwrap();
    assert_eq!(names.len(), 60, "the conformance set has 60 cases");
    names
        .iter()
        .map(|n| {
            let name = n.as_str().unwrap().to_string();
            let v = json(&format!("{name}.json"));
            let triangles = v["triangles"]
                .as_array()
                .unwrap()
                .iter()
                .map(|t| {
                    let p: Vec<(i64, i64)> = t
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|xy| (sixteenths(&xy[0]), sixteenths(&xy[1])))
                        .collect();
                    [p[0], p[1], p[2]]
                })
                .collect();
            let ids = v["ids"]
                .as_array()
                .unwrap()
                .iter()
                .map(|row| {
                    let row = row.as_array().unwrap();
                    row.iter().map(|i| i.as_i64().unwrap()).collect()
                })
                .collect();
            Case {
                name,
                width: v["width"].as_u64().unwrap() as u32,
                height: v["height"].as_u64().unwrap() as u32,
                triangles,
                ids,
            }
        })
        .collect()
}

/// Triangle `i` is drawn in colour `i + 1` spread over 24 bits; 0 means uncovered.
pub fn id_color(i: usize) -> Rgb888 {
    let v = i as u32 + 1;
    Rgb888::new((v >> 16) as u8, (v >> 8) as u8, v as u8)
}

/// The triangle id of a pixel drawn with [`id_color`] (-1 for none).
pub fn color_id(c: Rgb888) -> i64 {
    i64::from(u32::from(c.r()) << 16 | u32::from(c.g()) << 8 | u32::from(c.b())) - 1
}
