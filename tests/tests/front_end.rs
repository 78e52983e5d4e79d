//! The front end validates a triangle's indices through its slots' bounds checks (the scratch is
//! cut to the mesh's vertex count when a draw begins): an index out of range is counted as
//! invalid and skipped, never read from a slot beyond the mesh, whatever the scratch's length
//! (none, short, exact, or longer with slots left from a frame of another mesh), in the filled,
//! wireframe and banded paths.

use rasterizer_core::pipeline::{Banding, BinEntry, RenderStats};
use rasterizer_core::prelude::*;

const W: u32 = 64;
const H: u32 = 48;

fn fx(v: f64) -> Fx16 {
    Fx16::from_bits((v * 65536.0).round() as i32)
}

fn transforms() -> Transforms<Fx16> {
    Transforms {
        model: Mat4::identity(),
        view: Mat4::look_at(
            Vec3::from_ints(0, 0, 3),
            Vec3::default(),
            Vec3::from_ints(0, 1, 0),
        )
        .unwrap(),
        projection: Mat4::perspective(
            Angle::from_degrees(60),
            Fx16::from_ratio(i64::from(W), i64::from(H)),
            Fx16::from_ratio(1, 4),
            Fx16::from_int(100),
        )
        .unwrap(),
    }
}

/// Four vertices; triangles with indices out of range mixed with valid ones (one of them
/// facing away, one degenerate).
const POSITIONS: [[f64; 3]; 4] = [
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [0.0, 1.0, 0.0],
    [1.2, 1.2, -0.5],
];
const ALL: [[u16; 3]; 8] = [
    [0, 1, 2],
    [0, 1, 4],
    [7, 0, 1],
    [1, 3, 2],
    [u16::MAX, 0, 1],
    [2, 2, 4],
    [0, 0, 0],
    [2, 1, 0],
];
const VALID: [[u16; 3]; 4] = [[0, 1, 2], [1, 3, 2], [0, 0, 0], [2, 1, 0]];

fn positions() -> Vec<Vec3<Fx16>> {
    POSITIONS
        .iter()
        .map(|p| Vec3::new(fx(p[0]), fx(p[1]), fx(p[2])))
        .collect()
}

const COLORS: [Rgb888; 4] = [Rgb888::RED, Rgb888::GREEN, Rgb888::BLUE, Rgb888::WHITE];

/// A scratch of `slots` slots, filled by a frame of another mesh (a big triangle whose slots
/// would draw a lot if an invalid index read them).
fn stale_scratch(slots: usize) -> Vec<VertexSlot> {
    let mut scratch = vec![VertexSlot::EMPTY; slots];
    let big: Vec<Vec3<Fx16>> = (0..slots)
        .map(|i| {
            let a = i as f64;
            Vec3::new(fx(4.0 * a.cos()), fx(4.0 * a.sin()), fx(0.0))
        })
        .collect();
    let tris: Vec<[u16; 3]> = (2..slots as u16).map(|i| [0, i - 1, i]).collect();
    let mut buf = vec![0u16; (W * H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
    let mut p = Pipeline::new(
        &transforms(),
        Viewport::new(W, H),
        NoCull,
        NoDepth,
        VertexColors::<Rgb565>::new(),
    );
    let _ = p.draw(&mut fb, &Mesh::new(&big, &tris), &mut scratch);
    scratch
}

fn pipeline<C: rasterizer_core::cull::Cull, D: rasterizer_core::depth::DepthTest>(
    cull: C,
    depth: D,
) -> Pipeline<Fx16, C, D, VertexColors<Rgb565>> {
    Pipeline::new(
        &transforms(),
        Viewport::new(W, H),
        cull,
        depth,
        VertexColors::<Rgb565>::new(),
    )
}

/// The filled, wireframe and banded draws of `tris` with a scratch of `slots` slots.
fn draws(tris: &[[u16; 3]], slots: usize) -> Vec<(Vec<u16>, RenderStats)> {
    let pos = positions();
    let mesh = Mesh::new(&pos, tris).with_colors(&COLORS);
    let mut out = Vec::new();

    let mut buf = vec![0u16; (W * H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
    let mut scratch = stale_scratch(slots);
    let stats = pipeline(CullClockwise, NoDepth)
        .draw(&mut fb, &mesh, &mut scratch)
        .unwrap();
    out.push((buf, stats));

    let mut buf = vec![0u16; (W * H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
    let mut scratch = stale_scratch(slots);
    let Ok(stats) = pipeline(CullClockwise, NoDepth).draw_wireframe(
        &mut fb,
        &mesh,
        &mut scratch,
        Rgb565::WHITE,
    );
    out.push((buf, stats));

    let rows = 8;
    let mut z = vec![u16::MAX; (W * rows) as usize];
    let depth = DepthBuffer::new(&mut z, W, rows, Compare::Less).unwrap();
    let mut band = vec![0u16; (W * rows) as usize];
    let mut bins = vec![BinEntry::default(); tris.len()];
    let mut buf = vec![0u16; (W * H) as usize];
    let mut scratch = stale_scratch(slots);
    let banding = Banding {
        width: W,
        height: H,
        rows,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    let stats = pipeline(NoCull, depth)
        .draw_banded(&mesh, &banding, &mut band, &mut bins, &mut scratch, |b| {
            let y0 = b.y0() as usize * W as usize;
            let data = b.framebuffer().as_slice();
            buf[y0..y0 + data.len()].copy_from_slice(data);
        })
        .unwrap();
    out.push((buf, stats));
    out
}

#[test]
fn invalid_indices_skipped_with_any_scratch() {
    let reference = draws(&VALID, 4);
    assert!(
        reference[0].0.iter().any(|&c| c != 0),
        "the valid triangles draw something"
    );
    for slots in [0, 2, 4, 5, 8, 300] {
        let all = draws(&ALL, slots);
        for (k, ((img, stats), (ref_img, ref_stats))) in all.iter().zip(&reference).enumerate() {
            let expected = RenderStats {
                triangles: ALL.len() as u32,
                invalid: 4,
                ..*ref_stats
            };
            assert_eq!(*stats, expected, "path {k}, {slots} slots");
            assert!(
                img == ref_img,
                "path {k}, {slots} slots: the picture differs"
            );
        }
    }
}
