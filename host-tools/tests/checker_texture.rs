//! The generated texture `assets/textures/checker.png` (for `cube_textured.obj`): four coloured
//! quadrants of 8 x 8 checks with a white `F` in the top-left one, so that a flipped or turned
//! texture shows at a glance. This test draws it and checks the committed file is that picture;
//! `REGENERATE_TEXTURES=1 cargo test -p host-tools --test checker_texture` writes it again.

use std::path::Path;

const SIDE: u32 = 64;

/// The texel at `(x, y)`, row 0 the top.
fn checker(x: u32, y: u32) -> [u8; 3] {
    let half = SIDE / 2;
    // Top left red, top right green, bottom left blue, bottom right yellow.
    let base: [u8; 3] = match (x < half, y < half) {
        (true, true) => [220, 50, 40],
        (false, true) => [50, 180, 60],
        (true, false) => [40, 80, 220],
        (false, false) => [230, 200, 40],
    };
    // The F: a stem and two bars, in the top-left quadrant.
    let (fx, fy) = (x as i32 - 8, y as i32 - 6);
    let stem = (0..4).contains(&fx) && (0..20).contains(&fy);
    let top = (0..16).contains(&fx) && (0..4).contains(&fy);
    let middle = (0..11).contains(&fx) && (8..12).contains(&fy);
    if stem || top || middle {
        return [255, 255, 255];
    }
    if (x / 8 + y / 8).is_multiple_of(2) {
        base
    } else {
        base.map(|c| c / 2)
    }
}

#[test]
fn checker_png_is_the_generated_picture() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/textures/checker.png");
    let want = image::RgbImage::from_fn(SIDE, SIDE, |x, y| image::Rgb(checker(x, y)));
    if std::env::var_os("REGENERATE_TEXTURES").is_some() {
        want.save(&path).unwrap();
    }
    let got = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8();
    assert!(
        got == want,
        "{} differs from the generated picture",
        path.display()
    );
    // The corners tell the orientation: red top left, yellow bottom right, the F's top bar white.
    assert_eq!(checker(0, 0), [220, 50, 40]);
    assert_eq!(checker(SIDE - 1, SIDE - 1), [230, 200, 40]);
    assert_eq!(checker(20, 7), [255, 255, 255]);
    assert_ne!(checker(20, SIDE - 7), [255, 255, 255]);
}
