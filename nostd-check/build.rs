//! Names the feature groups of `src/one.rs`, `cfg(three_d)` (a shading feature is on) and
//! `cfg(two_d)` (a 2D one is), and refuses the combinations that make no binary.

fn on(feature: &str) -> bool {
    std::env::var_os(format!("CARGO_FEATURE_{}", feature.to_uppercase())).is_some()
}

fn main() {
    println!("cargo::rustc-check-cfg=cfg(three_d)");
    println!("cargo::rustc-check-cfg=cfg(two_d)");
    let shading = ["unlit", "flat", "gouraud", "phong", "textured", "matcap"];
    let stages = [
        "depth",
        "cull",
        "banded",
        "noscratch",
        "dither",
        "translucent",
        "fog",
    ];
    if on("translucent") && on("banded") {
        panic!("translucent draws a whole frame: not with banded");
    }
    match shading.into_iter().filter(|f| on(f)).count() {
        0 if stages.into_iter().any(on) => {
            panic!("{stages:?} need a shading feature: {shading:?}")
        }
        0 => {}
        1 => println!("cargo::rustc-cfg=three_d"),
        _ => panic!("choose at most one shading feature: {shading:?}"),
    }
    // Fog mixes a shaded colour (per vertex, triangle or pixel), which unlit shading does not have,
    // and the textured model does not take it.
    if on("fog") && !(on("flat") || on("gouraud") || on("phong") || on("matcap")) {
        panic!("fog needs flat, gouraud, phong or matcap shading");
    }
    if on("double") && !on("framelist") {
        panic!("double renders the frame list double-buffered: with framelist");
    }
    if [
        "line2d",
        "triangle2d",
        "gouraud2d",
        "polygon2d",
        "aa2d",
        "sprite",
    ]
    .into_iter()
    .any(on)
    {
        println!("cargo::rustc-cfg=two_d");
    }
}
