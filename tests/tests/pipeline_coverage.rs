//! Exact coverage of the 3D pipeline's default path (the fused span loop), for every sub-pixel
//! setting: each covered pixel set must equal an independent reference, the top-left rule on
//! integer edge functions, with no tolerance; and Mesa's llvmpipe conformance cases drawn through
//! the pipeline instead of `fill_triangle`.
//!
//! The scene is set up so that the projected sub-pixel coordinates are known exactly: model and
//! view are the identity, and the projection passes x, y and z through and sets `w` to the
//! constant `2^(13 + B)` raw 16.16 units, on a viewport of `2^14` pixels a side. Then
//! `x_s = (x + w) 2^14 2^B / 2w = x + w` raw units, i.e. a mesh x of `X - w` (raw) lands on the
//! sub-pixel `X` with no rounding at all (y is flipped: `Y = w - y`). `w` stays between 1/8 and 32,
//! inside the clipper's `w >= 2^-8`. The clip volume's guard band (`|x|, |y| <= 4w`) then spans
//! `-1.5` to `2.5` viewports, 24576 pixels left of the viewport to 40960 right of it; vertices
//! beyond it, and behind the near plane (`z < -w`) or past the far plane, are clipped in
//! homogeneous space.
//!
//! The reference takes its vertices where the pipeline's coverage starts: unclipped vertices are
//! the exact sub-pixels above (checked against `Pipeline::project`); for a triangle the pipeline
//! clips, the clipped polygon is reproduced with the library's own `clip_triangle` and
//! `Pipeline::project` (the clip's rounding is not what is tested here), and the reference covers
//! the union of its fan's triangles. Only the coverage rule is computed independently.
//!
//! Each triangle is drawn span by span through a strict `DrawTarget` (which fails on a pixel
//! written twice), and with a depth buffer into framebuffers, whose words the fused loop writes
//! directly (its lean path, and its general one for other layouts and formats).

use proptest::prelude::*;
use rasterizer_core::clip::polygon::{clip_triangle, outcode, ClipVertex};
use rasterizer_core::math::Vec4;
use rasterizer_core::prelude::*;
use rasterizer_core::surface::Storage;
use std::collections::BTreeSet;
use tests::StrictMock;

/// The target: a small window somewhere inside (or across the edge of) a huge viewport.
const TW: u32 = 64;
const TH: u32 = 48;
/// The viewport's side in pixels: `2^14`, so that `w = 2^(13 + B)` maps 1:1 for every `B`.
const VP: u32 = 1 << 14;

type Pipe<const B: u32> = Pipeline<Fx16, NoCull, NoDepth, Unlit<Rgb888>, B>;

/// The constant clip-space `w` of the scene, raw 16.16.
const fn w_raw<const B: u32>() -> i64 {
    1 << (13 + B)
}

fn pipeline<const B: u32>(vx: i32, vy: i32, color: Rgb888) -> Pipe<B> {
    let (o, l) = (Fx16::ZERO, Fx16::ONE);
    let w = Fx16::from_bits(w_raw::<B>() as i32);
    let t = Transforms {
        model: Mat4::identity(),
        view: Mat4::identity(),
        projection: Mat4::from_rows([[l, o, o, o], [o, l, o, o], [o, o, l, o], [o, o, o, w]]),
    };
    let vp = Viewport {
        x: vx,
        y: vy,
        width: VP,
        height: VP,
    };
    Pipeline::new(&t, vp, NoCull, NoDepth, Unlit { color }).with_bits::<B>()
}

/// The mesh position whose projection is the screen sub-pixel `(x, y)` (viewport at `vx, vy`),
/// saturated to the 16.16 range for points far beyond the guard band.
fn position<const B: u32>(x: i64, y: i64, z: i32, vx: i32, vy: i32) -> Vec3<Fx16> {
    let raw = |v: i64| v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
    let w = w_raw::<B>();
    Vec3::new(
        Fx16::from_bits(raw(x - (i64::from(vx) << B) - w)),
        Fx16::from_bits(raw(w - (y - (i64::from(vy) << B)))),
        Fx16::from_bits(z),
    )
}

/// Whether the pixel `(px, py)` is covered by the triangle `v` (sub-pixel units, `s` to the
/// pixel): the centre strictly inside every edge, or exactly on an edge that is a top edge
/// (horizontal, triangle below it, y pointing down) or a left edge (triangle to its right), as
/// OpenGL and llvmpipe define the rule. Doubled coordinates keep the centre an integer.
fn covers(v: &[(i64, i64); 3], s: i64, px: i64, py: i64) -> bool {
    let d = v.map(|(x, y)| (2 * i128::from(x), 2 * i128::from(y)));
    let p = (i128::from(2 * px * s + s), i128::from(2 * py * s + s));
    let cross = |a: (i128, i128), b: (i128, i128), c: (i128, i128)| {
        (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
    };
    let area = cross(d[0], d[1], d[2]);
    if area == 0 {
        return false;
    }
    let sign = area.signum();
    (0..3).all(|k| {
        let (a, b) = (d[k], d[(k + 1) % 3]);
        let e = sign * cross(a, b, p);
        if e != 0 {
            return e > 0;
        }
        // The inward normal of a -> b: e = n . (p - a), n = sign (-dy, dx).
        let n = (-sign * (b.1 - a.1), sign * (b.0 - a.0));
        n.0 > 0 || (n.0 == 0 && n.1 > 0)
    })
}

/// The pixels of the target inside the viewport that the reference covers with the screen
/// triangles `tris`.
fn reference_pixels(
    tris: &[[(i64, i64); 3]],
    s: i64,
    vx: i32,
    vy: i32,
    (w, h): (u32, u32),
) -> BTreeSet<(i32, i32)> {
    let (vx, vy) = (i64::from(vx), i64::from(vy));
    let mut set = BTreeSet::new();
    for py in 0..i64::from(h) {
        for px in 0..i64::from(w) {
            let in_vp = vx <= px && px < vx + i64::from(VP) && vy <= py && py < vy + i64::from(VP);
            if in_vp && tris.iter().any(|t| covers(t, s, px, py)) {
                set.insert((px as i32, py as i32));
            }
        }
    }
    set
}

/// Twice the signed area of a screen triangle.
fn doubled_area(t: &[(i64, i64); 3]) -> i128 {
    let d = |a: (i64, i64), b: (i64, i64)| (i128::from(b.0 - a.0), i128::from(b.1 - a.1));
    let ((ax, ay), (bx, by)) = (d(t[0], t[1]), d(t[0], t[2]));
    ax * by - ay * bx
}

/// The screen triangles the pipeline rasterizes for the mesh triangle `pos`: the triangle itself
/// when no vertex is outside a clip plane, else the fan of its clipped polygon (reproduced with
/// the library's clipper and projection, as the module comment explains). `expect` holds the
/// exact sub-pixels of the vertices that should project 1:1, checked here.
fn screen_triangles<const B: u32>(
    p: &Pipe<B>,
    pos: &[Vec3<Fx16>; 3],
    expect: &[Option<(i64, i64)>; 3],
) -> Vec<[(i64, i64); 3]> {
    let clip: [Vec4<Fx16>; 3] = pos.map(|q| p.mvp().transform_point(q));
    let codes = clip.map(|c| outcode(&c));
    let screen = |c: &Vec4<Fx16>| {
        let (sp, _) = p.project(c);
        (i64::from(sp.x), i64::from(sp.y))
    };
    if codes == [0; 3] {
        let v = [0, 1, 2].map(|k| screen(&clip[k]));
        for k in 0..3 {
            if let Some(e) = expect[k] {
                assert_eq!(v[k], e, "vertex {k} does not project 1:1");
            }
        }
        return vec![v];
    }
    let tri = clip.map(|pos| ClipVertex {
        pos,
        var: [0i32; 0],
    });
    let poly: Vec<(i64, i64)> = clip_triangle(&tri, codes)
        .iter()
        .map(|v| screen(&v.pos))
        .collect();
    // The rounding of the clipped vertices can dent the convex polygon; the pipeline draws the
    // polygon left once every vertex that does not turn the polygon's way is dropped, which is
    // convex, as a fan.
    let total: i128 = doubled_area_poly(&poly);
    let mut poly = poly;
    loop {
        let n = poly.len();
        if n < 3 {
            return Vec::new();
        }
        let reflex = (0..n).find(|&k| {
            let t = [poly[(k + n - 1) % n], poly[k], poly[(k + 1) % n]];
            doubled_area(&t).signum() != total.signum()
        });
        match reflex {
            Some(k) => {
                poly.remove(k);
            }
            None => break,
        }
    }
    (1..poly.len() - 1)
        .map(|k| [poly[0], poly[k], poly[k + 1]])
        .collect()
}

/// Twice the signed area of a polygon (the shoelace sum).
fn doubled_area_poly(p: &[(i64, i64)]) -> i128 {
    (0..p.len())
        .map(|k| {
            let (a, b) = (p[k], p[(k + 1) % p.len()]);
            i128::from(a.0) * i128::from(b.1) - i128::from(b.0) * i128::from(a.1)
        })
        .sum()
}

/// Draws one triangle (sub-pixel vertices `v`, depths `z` raw) through the pipeline into a
/// strict target (which panics on a pixel written twice or out of bounds) and compares the
/// pixels with the reference.
fn check<const B: u32>(v: [(i64, i64); 3], z: [i32; 3], vx: i32, vy: i32) -> Result<(), String> {
    let p0 = pipeline::<B>(vx, vy, Rgb888::WHITE);
    let pos = [0, 1, 2].map(|k| position::<B>(v[k].0, v[k].1, z[k], vx, vy));
    // Vertices inside the guard band (not saturated) must project exactly where they were put.
    let w = w_raw::<B>();
    let expect = [0, 1, 2].map(|k| {
        let (x, y) = (v[k].0 - (i64::from(vx) << B), v[k].1 - (i64::from(vy) << B));
        let inside = (-3 * w..=5 * w).contains(&x) && (-3 * w..=5 * w).contains(&y);
        inside.then_some(v[k])
    });
    let tris = screen_triangles(&p0, &pos, &expect);
    let expected = reference_pixels(&tris, 1 << B, vx, vy, (TW, TH));
    let mesh = Mesh::new(&pos, &[[0u16, 1, 2]]);
    let mut mock = StrictMock::<Rgb888>::new(TW, TH);
    let mut scratch = [VertexSlot::<[i32; 0]>::EMPTY; 3];
    let mut p = p0;
    p.draw(&mut AnyTarget::new(&mut mock), &mesh, &mut scratch)
        .unwrap();
    let spans = mock.written();
    // The same triangle with a depth test into framebuffers, whose words the fused loop writes
    // directly: its lean path (one word a pixel, depth laid out as the colour) and its general
    // path (a depth buffer wider than the target; three words a pixel).
    let words = [
        (
            "Rgb565",
            written_through_words::<B, Rgb565>(&pos, vx, vy, TW),
        ),
        (
            "Rgb565, wider depth",
            written_through_words::<B, Rgb565>(&pos, vx, vy, TW + 5),
        ),
        (
            "Rgb888",
            written_through_words::<B, Rgb888>(&pos, vx, vy, TW),
        ),
    ];
    for (what, got) in [("spans", spans)].into_iter().chain(words) {
        if got != expected {
            let extra: Vec<_> = got.difference(&expected).take(8).collect();
            let missing: Vec<_> = expected.difference(&got).take(8).collect();
            return Err(format!(
                "{what}: B = {B}, viewport at ({vx}, {vy}), screen triangles {tris:?}: \
                 {} pixels too many {extra:?}, {} missing {missing:?}",
                got.difference(&expected).count(),
                expected.difference(&got).count()
            ));
        }
    }
    Ok(())
}

/// The pixels [`check`]'s triangle covers when drawn with a depth buffer (`depth_width` entries a
/// row, every test passing) into a `TW` x `TH` framebuffer of `C` cleared to black, in white.
fn written_through_words<const B: u32, C>(
    pos: &[Vec3<Fx16>; 3],
    vx: i32,
    vy: i32,
    depth_width: u32,
) -> BTreeSet<(i32, i32)>
where
    C: Storage + RgbColor,
    C::Word: Default,
{
    let (o, l) = (Fx16::ZERO, Fx16::ONE);
    let w = Fx16::from_bits(w_raw::<B>() as i32);
    let t = Transforms {
        model: Mat4::identity(),
        view: Mat4::identity(),
        projection: Mat4::from_rows([[l, o, o, o], [o, l, o, o], [o, o, l, o], [o, o, o, w]]),
    };
    let vp = Viewport {
        x: vx,
        y: vy,
        width: VP,
        height: VP,
    };
    let mut zbuf = vec![u16::MAX; (depth_width * TH) as usize];
    let depth = DepthBuffer::new(&mut zbuf, depth_width, TH, Compare::Always).unwrap();
    let mut p = Pipeline::new(&t, vp, NoCull, depth, Unlit { color: C::WHITE }).with_bits::<B>();
    let mut words = vec![C::Word::default(); Framebuffer::<C>::required_len(TW, TH).unwrap()];
    let mut fb = Framebuffer::<C>::new(&mut words, TW, TH).unwrap();
    let mesh = Mesh::new(pos, &[[0u16, 1, 2]]);
    let mut scratch = [VertexSlot::<[i32; 0]>::EMPTY; 3];
    p.draw(&mut fb, &mesh, &mut scratch).unwrap();
    let mut set = BTreeSet::new();
    for y in 0..TH as i32 {
        for x in 0..TW as i32 {
            if fb.pixel(Point::new(x, y)) == Some(C::WHITE) {
                set.insert((x, y));
            }
        }
    }
    set
}

/// [`check`] with the sub-pixel bits chosen at run time; vertices are given in 1/256 pixel and
/// rounded down to the `B`-bit grid.
fn check_bits(b: u32, v: [(i64, i64); 3], z: [i32; 3], vx: i32, vy: i32) -> Result<(), String> {
    let shift = 8 - b;
    let v = v.map(|(x, y)| (x >> shift, y >> shift));
    match b {
        0 => check::<0>(v, z, vx, vy),
        1 => check::<1>(v, z, vx, vy),
        2 => check::<2>(v, z, vx, vy),
        3 => check::<3>(v, z, vx, vy),
        4 => check::<4>(v, z, vx, vy),
        5 => check::<5>(v, z, vx, vy),
        6 => check::<6>(v, z, vx, vy),
        7 => check::<7>(v, z, vx, vy),
        _ => check::<8>(v, z, vx, vy),
    }
}

/// One pixel in the generators' unit (1/256 pixel).
const PX: i64 = 256;

/// A vertex anywhere in the `lo..hi` pixel square (target-relative), in 1/256 pixel.
fn anywhere(lo: i64, hi: i64) -> impl Strategy<Value = (i64, i64)> {
    (lo * PX..hi * PX, lo * PX..hi * PX)
}

/// Triangles of every shape the pipeline meets, in 1/256 pixel relative to the target.
fn triangles() -> impl Strategy<Value = [(i64, i64); 3]> {
    let small = (
        anywhere(-8, 72),
        prop::array::uniform3((-4 * PX..4 * PX, -4 * PX..4 * PX)),
    )
        .prop_map(|(c, d)| d.map(|d| (c.0 + d.0, c.1 + d.1)));
    // Within a pixel or so of a point: bounds that hold a few centres or none, which the front
    // end rejects before their values when they cover none.
    let tiny = (anywhere(-2, 66), prop::array::uniform3((-PX..PX, -PX..PX)))
        .prop_map(|(c, d)| d.map(|d| (c.0 + d.0, c.1 + d.1)));
    let medium = prop::array::uniform3(anywhere(-100, 164));
    // Nearly collinear: the third vertex close to the line through the first two.
    let sliver = (
        anywhere(-60, 124),
        anywhere(-60, 124),
        -32i64..96,
        (-64i64..64, -64i64..64),
    )
        .prop_map(|(a, b, t, d)| {
            let c = (
                a.0 + (b.0 - a.0) * t / 64 + d.0,
                a.1 + (b.1 - a.1) * t / 64 + d.1,
            );
            [a, b, c]
        });
    // Reaching over the clip volume's guard band (24576 pixels left of the viewport) or not.
    let large = prop::array::uniform3(anywhere(-40_000, 40_000));
    // Far beyond the guard band, up to the 16.16 range the mesh can hold.
    let far = prop::array::uniform3(anywhere(-(1 << 22), 1 << 22));
    let near_target = prop::array::uniform3(anywhere(-4, 68));
    let shapes = prop_oneof![
        3 => small,
        2 => tiny,
        2 => medium,
        2 => sliver,
        2 => large,
        1 => far,
        1 => near_target,
    ];
    // Snapping to whole, half and quarter pixels puts centres exactly on edges and vertices.
    let snap = prop_oneof![Just(1i64), Just(16), Just(64), Just(128), Just(256)];
    (shapes, snap).prop_map(|(v, q)| v.map(|(x, y)| (x - x.rem_euclid(q), y - y.rem_euclid(q))))
}

/// A vertex's depth, raw 16.16, in units of `w`: mostly inside, sometimes behind the near plane
/// (`z < -w`) or past the far plane (`z > w`). Scaled by `w` in [`z_raw`].
fn depths() -> impl Strategy<Value = [i32; 3]> {
    let one = prop_oneof![
        6 => Just(0i32),
        2 => -256i32..256,
        3 => -1024i32..-256,
        1 => 257i32..1024,
    ];
    prop::array::uniform3(one)
}

/// `z` (in 1/256 of `w`) as raw 16.16 for `b` sub-pixel bits (`w = 2^(13 + b)`).
fn z_raw(z: i32, b: u32) -> i32 {
    z << (5 + b)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    /// Every sub-pixel setting, both windings (NoCull), all kinds of triangles, viewports whose
    /// corner lies anywhere around the target (so that the target sees every part of it).
    #[test]
    fn fused_path_coverage_is_exactly_top_left(
        b in 0u32..=8,
        v in triangles(),
        z in depths(),
        vx in prop_oneof![-(VP as i32) + 1..40i32, -20_000i32..-(VP as i32)],
        vy in prop_oneof![-(VP as i32) + 1..30i32, -20_000i32..-(VP as i32)],
    ) {
        let z = z.map(|z| z_raw(z, b));
        if let Err(e) = check_bits(b, v, z, vx, vy) {
            return Err(TestCaseError::fail(e));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// llvmpipe's conformance cases through the pipeline.

#[path = "common/conformance_cases.rs"]
mod cases;
use cases::{color_id, id_color, load_cases, Case};

/// The mesh positions of a case's triangle at `B` bits (`B >= 4`: the cases' 1/16 grid is then
/// exact), viewport at the origin; asserts that the pipeline projects them onto the case's
/// vertices exactly.
fn case_positions<const B: u32>(p: &Pipe<B>, t: &[(i64, i64); 3]) -> [Vec3<Fx16>; 3] {
    let v = t.map(|(x, y)| (x << (B - 4), y << (B - 4)));
    let pos = v.map(|(x, y)| position::<B>(x, y, 0, 0, 0));
    for k in 0..3 {
        let (sp, _) = p.project(&p.mvp().transform_point(pos[k]));
        assert_eq!(
            (i64::from(sp.x), i64::from(sp.y)),
            v[k],
            "not projected 1:1"
        );
    }
    pos
}

/// The ids each case's pixels get through the pipeline, drawn triangle by triangle in order.
fn case_mismatches<const B: u32>(case: &Case) -> usize {
    let mut buf = vec![0u8; (case.width * case.height * 3) as usize];
    let mut fb = Framebuffer::<Rgb888>::new(&mut buf, case.width, case.height).unwrap();
    for (i, t) in case.triangles.iter().enumerate() {
        let mut p = pipeline::<B>(0, 0, id_color(i));
        let pos = case_positions(&p, t);
        let mut scratch = [VertexSlot::<[i32; 0]>::EMPTY; 3];
        p.draw(&mut fb, &Mesh::new(&pos, &[[0u16, 1, 2]]), &mut scratch)
            .unwrap();
    }
    let mut wrong = 0;
    for y in 0..case.height as i32 {
        for x in 0..case.width as i32 {
            let got = color_id(fb.pixel(Point::new(x, y)).unwrap());
            wrong += usize::from(got != case.ids[y as usize][x as usize]);
        }
    }
    wrong
}

/// Every case through the fused path, at every sub-pixel setting that holds the cases' 1/16
/// grid exactly (4 to 8). Fewer bits cannot express the vertices: they would be rounded, and the
/// expected pixels no longer apply.
#[test]
fn llvmpipe_coverage_through_the_fused_path() {
    let mut failures = Vec::new();
    for case in load_cases() {
        let counts = [
            case_mismatches::<4>(&case),
            case_mismatches::<5>(&case),
            case_mismatches::<6>(&case),
            case_mismatches::<7>(&case),
            case_mismatches::<8>(&case),
        ];
        for (b, wrong) in (4..).zip(counts) {
            if wrong > 0 {
                failures.push(format!("{} at {b} bits: {wrong} pixels differ", case.name));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The grid cases as one mesh each (shared vertices, one draw call) into a strict target: every
/// pixel written exactly once.
#[test]
fn llvmpipe_grids_tile_exactly_through_the_fused_path() {
    let mut grids = 0;
    for case in load_cases().iter().filter(|c| c.name.starts_with("grid")) {
        grids += 1;
        let mut p = pipeline::<6>(0, 0, Rgb888::WHITE);
        let pos: Vec<Vec3<Fx16>> = case
            .triangles
            .iter()
            .flat_map(|t| case_positions(&p, t))
            .collect();
        let tris: Vec<[u16; 3]> = (0..case.triangles.len() as u16)
            .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
            .collect();
        let mut mock = StrictMock::<Rgb888>::new(case.width, case.height);
        let mut scratch = vec![VertexSlot::<[i32; 0]>::EMPTY; pos.len()];
        p.draw(
            &mut AnyTarget::new(&mut mock),
            &Mesh::new(&pos, &tris),
            &mut scratch,
        )
        .unwrap();
        assert_eq!(
            mock.written().len(),
            (case.width * case.height) as usize,
            "{}: a grid must tile the screen",
            case.name
        );
    }
    assert_eq!(grids, 15);
}

/// A sliver crossing the near plane: the clipped quad's rounded vertices folded it (its two fan
/// triangles had opposite windings and overlapped), and pixel (28, 39) was drawn twice.
#[test]
fn near_clipped_sliver_no_overdraw() {
    let v = [(-58, 40), (398, 352), (14, 89)];
    let z = [0, -390, -188].map(|z| z_raw(z, 2));
    check::<2>(v, z, 0, 0).unwrap();
}

/// A triangle through the near and far planes at no sub-pixel bits (found by the proptest above):
/// its clipped polygon, rounded to whole pixels, is dented at (32, 28), and the fan of the dented
/// polygon drew a thin wedge of pixels twice.
#[test]
fn rounded_clipped_polygon_with_a_dent_draws_each_pixel_once() {
    let z = [-274, 0, 265].map(|z| z_raw(z, 0));
    check_bits(0, [(0, 8704), (9472, 6656), (8448, 7168)], z, 0, 0).unwrap();
}
