//! Triangle coverage against Mesa's llvmpipe: every case in `tests/conformance/triangles` (copied from
//! the team's shared conformance set) must be reproduced pixel for pixel.

use rasterizer_core::prelude::*;
use tests::StrictMock;

#[path = "common/conformance_cases.rs"]
mod cases;
use cases::{color_id, id_color, load_cases};

/// A case's triangle in 28.4, the sub-pixel format of its 1/16 grid.
fn subpoints(t: &[(i64, i64); 3]) -> [SubPoint<4>; 3] {
    t.map(|(x, y)| SubPoint::new(x as i32, y as i32))
}

#[test]
fn llvmpipe_coverage_reproduced_exactly() {
    let mut failures = Vec::new();
    for case in load_cases() {
        let mut buf = vec![0u8; (case.width * case.height * 3) as usize];
        let mut fb = Framebuffer::<Rgb888>::new(&mut buf, case.width, case.height).unwrap();
        for (i, t) in case.triangles.iter().enumerate() {
            fill_triangle(&mut fb, subpoints(t), id_color(i)).unwrap();
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
            fill_triangle(&mut AnyTarget::new(&mut mock), subpoints(t), id_color(i)).unwrap();
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
