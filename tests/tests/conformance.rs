//! Triangle coverage against Mesa's llvmpipe: every case in `tests/conformance/triangles` (copied from
//! the team's shared conformance set) must be reproduced pixel for pixel.

use rasterizer_core::prelude::*;
use serde_json::Value;
use std::path::PathBuf;
use tests::StrictMock;

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("conformance/triangles")
}

struct Case {
    name: String,
    width: u32,
    height: u32,
    triangles: Vec<[SubPoint<4>; 3]>,
    ids: Vec<Vec<i64>>,
}

fn to_subpixel(v: &Value) -> i32 {
    let f = v.as_f64().expect("coordinate is a number");
    let raw = f * 16.0;
    assert_eq!(raw, raw.round(), "vertex off the 1/16 grid");
    raw as i32
}

fn load_cases() -> Vec<Case> {
    let index: Value =
        serde_json::from_str(&std::fs::read_to_string(dir().join("INDEX.json")).unwrap()).unwrap();
    let names = index["cases"].as_array().unwrap();
    assert_eq!(names.len(), 60, "the conformance set has 60 cases");
    names
        .iter()
        .map(|n| {
            let name = n.as_str().unwrap().to_string();
            let text = std::fs::read_to_string(dir().join(format!("{name}.json"))).unwrap();
            let v: Value = serde_json::from_str(&text).unwrap();
            let triangles = v["triangles"]
                .as_array()
                .unwrap()
                .iter()
                .map(|t| {
                    let p: Vec<SubPoint<4>> = t
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|xy| SubPoint::new(to_subpixel(&xy[0]), to_subpixel(&xy[1])))
                        .collect();
                    [p[0], p[1], p[2]]
                })
                .collect();
            let ids = v["ids"]
                .as_array()
                .unwrap()
                .iter()
                .map(|row| {
                    row.as_array()
                        .unwrap()
                        .iter()
                        .map(|i| i.as_i64().unwrap())
                        .collect()
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
fn id_color(i: usize) -> Rgb888 {
    let v = i as u32 + 1;
    Rgb888::new((v >> 16) as u8, (v >> 8) as u8, v as u8)
}

fn color_id(c: Rgb888) -> i64 {
    ((u32::from(c.r()) << 16 | u32::from(c.g()) << 8 | u32::from(c.b())) as i64) - 1
}

#[test]
fn llvmpipe_coverage_reproduced_exactly() {
    let mut failures = Vec::new();
    for case in load_cases() {
        let mut buf = vec![0u8; (case.width * case.height * 3) as usize];
        let mut fb = Framebuffer::<Rgb888>::new(&mut buf, case.width, case.height).unwrap();
        for (i, t) in case.triangles.iter().enumerate() {
            fill_triangle(&mut fb, *t, id_color(i)).unwrap();
        }
        let mut wrong = 0;
        for y in 0..case.height as i32 {
            for x in 0..case.width as i32 {
                let got = color_id(fb.pixel(Point::new(x, y)).unwrap());
                if got != case.ids[y as usize][x as usize] {
                    wrong += 1;
                }
            }
        }
        if wrong > 0 {
            failures.push(format!("{}: {wrong} pixels differ", case.name));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn llvmpipe_grids_cover_every_pixel_exactly_once() {
    let mut grids = 0;
    for case in load_cases()
        .into_iter()
        .filter(|c| c.name.starts_with("grid"))
    {
        grids += 1;
        // StrictMock panics on a second write to any pixel.
        let mut mock = StrictMock::<Rgb888>::new(case.width, case.height);
        for (i, t) in case.triangles.iter().enumerate() {
            fill_triangle(&mut AnyTarget::new(&mut mock), *t, id_color(i)).unwrap();
        }
        assert_eq!(
            mock.written().len(),
            (case.width * case.height) as usize,
            "{}: a grid must tile the screen",
            case.name
        );
    }
    assert_eq!(grids, 15);
}
