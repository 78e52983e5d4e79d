//! The vertex scratch changes the work, never the picture: a draw with one slot per vertex, with a
//! short scratch, with none, with a longer one or with one left over from another frame gives the
//! same pixels and the same statistics, for every shading model, lit in model space or in world
//! space, in the filled, wireframe and banded paths.

use embedded_graphics_core::pixelcolor::raw::RawU16;
use proptest::prelude::*;
use rasterizer_core::cull::Cull;
use rasterizer_core::depth::DepthTest;
use rasterizer_core::numerics::{Numerics, Perspective, Standard};
use rasterizer_core::pipeline::RenderStats;
use rasterizer_core::prelude::*;
use rasterizer_core::shade::Shading;

/// A closed, smooth mesh: an octahedron subdivided twice and pushed out to the unit sphere.
fn sphere() -> (Vec<Vec3<Fx16>>, Vec<[u16; 3]>) {
    let mut pts: Vec<[f64; 3]> = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let mut tris: Vec<[u16; 3]> = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    for _ in 0..2 {
        let mut next = Vec::new();
        let mut mid = std::collections::HashMap::new();
        let mut midpoint = |a: u16, b: u16, pts: &mut Vec<[f64; 3]>| -> u16 {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (pts[a as usize], pts[b as usize]);
                let m = [
                    (p[0] + q[0]) / 2.0,
                    (p[1] + q[1]) / 2.0,
                    (p[2] + q[2]) / 2.0,
                ];
                let l = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
                pts.push([m[0] / l, m[1] / l, m[2] / l]);
                (pts.len() - 1) as u16
            })
        };
        for t in &tris {
            let ab = midpoint(t[0], t[1], &mut pts);
            let bc = midpoint(t[1], t[2], &mut pts);
            let ca = midpoint(t[2], t[0], &mut pts);
            next.extend([[t[0], ab, ca], [ab, t[1], bc], [ca, bc, t[2]], [ab, bc, ca]]);
        }
        tris = next;
    }
    let fx = |v: f64| Fx16::from_bits((v * 65536.0).round() as i32);
    (
        pts.iter()
            .map(|p| Vec3::new(fx(p[0]), fx(p[1]), fx(p[2])))
            .collect(),
        tris,
    )
}

/// A directional and a point light with a Blinn-Phong highlight: lighting that depends on both
/// the normal and the position.
fn lighting() -> Lighting<Fx16, 2> {
    let mut l = Lighting::new(
        Material {
            ambient: Rgb888::new(30, 30, 40),
            diffuse: Rgb888::new(200, 120, 60),
            specular: Rgb888::WHITE,
            shininess: 16,
        },
        Rgb888::WHITE,
        Specular::BlinnPhong,
        Vec3::from_ints(0, 0, 3),
    );
    l.add_light(Light::Directional {
        direction: Vec3::from_ints(1, 1, 1),
        color: Rgb888::WHITE,
    })
    .unwrap();
    l.add_light(Light::Point {
        position: Vec3::from_ints(-2, 1, 2),
        color: Rgb888::new(90, 90, 140),
    })
    .unwrap();
    l
}

/// The camera at (0, 0, 3) looking at the origin, 60° field of view, for a `w` x `h` frame.
fn transforms(model: Mat4<Fx16>, w: u32, h: u32) -> Transforms<Fx16> {
    Transforms {
        model,
        view: Mat4::look_at(
            Vec3::from_ints(0, 0, 3),
            Vec3::default(),
            Vec3::from_ints(0, 1, 0),
        )
        .unwrap(),
        projection: Mat4::perspective(
            Angle::from_degrees(60),
            Fx16::from_ratio(i64::from(w), i64::from(h)),
            Fx16::from_ratio(1, 4),
            Fx16::from_int(100),
        )
        .unwrap(),
    }
}

/// How the sphere is placed: turned (so lit in model space) or stretched with its own normal
/// matrix (so lit in world space).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Placement {
    Turned,
    Stretched,
}

impl Placement {
    fn model(self) -> Mat4<Fx16> {
        match self {
            Placement::Turned => Mat4::rotation_y(Angle::from_degrees(30))
                .then(&Mat4::rotation_x(Angle::from_degrees(-20))),
            Placement::Stretched => Mat4::scale(
                Fx16::from_ratio(3, 2),
                Fx16::from_int(1),
                Fx16::from_ratio(3, 4),
            )
            .then(&Mat4::rotation_y(Angle::from_degrees(30))),
        }
    }

    /// The inverse transpose of the model matrix for the stretched sphere.
    fn normal_matrix(self) -> Option<Mat4<Fx16>> {
        (self == Placement::Stretched).then(|| {
            Mat4::scale(
                Fx16::from_ratio(2, 3),
                Fx16::from_int(1),
                Fx16::from_ratio(4, 3),
            )
            .then(&Mat4::rotation_y(Angle::from_degrees(30)))
        })
    }
}

/// Vertex colours from positions: every vertex its own colour.
fn colors_of(pos: &[Vec3<Fx16>]) -> Vec<Rgb888> {
    let ch = |v: Fx16| ((v.to_bits() + 65536) / 520).clamp(0, 255) as u8;
    pos.iter()
        .map(|p| Rgb888::new(ch(p.x), ch(p.y), ch(p.z)))
        .collect()
}

/// Draws the sphere (with its normals or without) with `shading`, a depth buffer and back faces
/// culled, into a 96 x 72 frame, with a scratch of `slots` slots; 4 sub-pixel bits, affine, or
/// perspective-correct with `N` = `Perspective`.
fn render<Sh: Shading<Fx16, Color = Rgb565>, N: Numerics>(
    shading: Sh,
    place: Placement,
    normals: bool,
    slots: usize,
) -> (Vec<u16>, RenderStats) {
    let (w, h) = (96, 72);
    let (pos, tris) = sphere();
    let colors = colors_of(&pos);
    let mesh = Mesh {
        positions: &pos,
        normals: normals.then_some(&pos[..]),
        colors: Some(&colors),
        uvs: None,
        triangles: &tris,
        adjacency: None,
    };
    let mut z = vec![u16::MAX; (w * h) as usize];
    let depth = DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap();
    let mut p = Pipeline::new(
        &transforms(place.model(), w, h),
        Viewport::new(w, h),
        CullClockwise,
        depth,
        shading,
    )
    .with_bits::<4>()
    .with_numerics::<N>();
    if let Some(m) = place.normal_matrix() {
        p.set_normal_matrix(m);
    }
    let mut buf = vec![0u16; (w * h) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, w, h).unwrap();
    let mut scratch = vec![VertexSlot::EMPTY; slots];
    let stats = p.draw(&mut fb, &mesh, &mut scratch).unwrap();
    // From distance 3 a third of the sphere faces the camera: about 43 of 128 triangles.
    assert!(stats.drawn > 30, "{stats:?}");
    (buf, stats)
}

/// [`render`] with a full scratch, then with shorter and longer ones: all the same.
fn same_with_any_scratch<Sh: Shading<Fx16, Color = Rgb565> + Clone>(name: &str, shading: Sh) {
    let n = sphere().0.len();
    for place in [Placement::Turned, Placement::Stretched] {
        for normals in [true, false] {
            let full = render::<_, Standard>(shading.clone(), place, normals, n);
            assert!(
                full.0.iter().filter(|&&c| c != 0).count() > 1000,
                "{name}: the sphere covers a good part of the frame"
            );
            for slots in [0, 1, n / 3, n / 2, n - 1, n + 7] {
                let other = render::<_, Standard>(shading.clone(), place, normals, slots);
                assert!(
                    other == full,
                    "{name}, {place:?}, normals {normals}: {slots} of {n} slots differ"
                );
            }
            let full = render::<_, Perspective>(shading.clone(), place, normals, n);
            let none = render::<_, Perspective>(shading.clone(), place, normals, 0);
            assert!(
                none == full,
                "{name}, {place:?}, normals {normals}, perspective: no scratch differs"
            );
        }
    }
}

#[test]
fn full_short_and_empty_scratch_draw_the_same() {
    same_with_any_scratch("Gouraud", GouraudLit::<_, Rgb565, 2>::new(lighting()));
    same_with_any_scratch("flat", FlatLit::<_, Rgb565, 2>::new(lighting()));
    same_with_any_scratch("Phong", PhongLit::<_, Rgb565, 2>::new(lighting()));
    same_with_any_scratch("vertex colours", VertexColors::<Rgb565>::new());
    same_with_any_scratch(
        "unlit",
        Unlit {
            color: Rgb565::CSS_ORANGE,
        },
    );
}

#[test]
fn scratch_left_from_another_frame_does_not_matter() {
    // One scratch through frames of another mesh (same vertex count, other positions), another
    // camera and the wireframe: the frame drawn after them equals a fresh scratch's.
    let (w, h) = (96u32, 72u32);
    let (pos, tris) = sphere();
    let small: Vec<Vec3<Fx16>> = pos
        .iter()
        .map(|p| {
            let half = |v: Fx16| Fx16::from_bits(v.to_bits() / 2);
            Vec3::new(half(p.x) + Fx16::from_ratio(1, 4), half(p.y), half(p.z))
        })
        .collect();
    let draw = |positions: &[Vec3<Fx16>],
                yaw: i32,
                scratch: &mut [VertexSlot<[u16; 3]>],
                wireframe: bool| {
        let mesh = Mesh {
            positions,
            normals: Some(positions),
            colors: None,
            uvs: None,
            triangles: &tris,
            adjacency: None,
        };
        let mut z = vec![u16::MAX; (w * h) as usize];
        let depth = DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap();
        let mut p = Pipeline::new(
            &transforms(Mat4::rotation_y(Angle::from_degrees(yaw)), w, h),
            Viewport::new(w, h),
            CullClockwise,
            depth,
            GouraudLit::<_, Rgb565, 2>::new(lighting()),
        );
        let mut buf = vec![0u16; (w * h) as usize];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, w, h).unwrap();
        let stats = if wireframe {
            p.draw_wireframe(&mut fb, &mesh, scratch, Rgb565::WHITE)
                .unwrap()
        } else {
            p.draw(&mut fb, &mesh, scratch).unwrap()
        };
        (buf, stats)
    };
    let fresh = draw(&pos, 30, &mut vec![VertexSlot::EMPTY; pos.len()], false);
    let mut used = vec![VertexSlot::EMPTY; pos.len() + 5];
    draw(&small, 30, &mut used, false);
    draw(&pos, 75, &mut used, false);
    draw(&pos, 10, &mut used, true);
    assert!(draw(&pos, 30, &mut used, false) == fresh);
    // The same after a frame of the other mesh drawn with this very camera.
    draw(&small, 30, &mut used, false);
    assert!(draw(&pos, 30, &mut used, false) == fresh);
}

#[test]
fn vertex_slot_sizes_are_as_documented() {
    type Slot<Sh> = VertexSlot<<Sh as Shading<Fx16>>::Stored>;
    // `pipeline::vertex`: 16 bytes a slot for Gouraud and vertex colours, 12 for unlit and flat,
    // 36 for Phong.
    assert_eq!(size_of::<Slot<GouraudLit<Fx16, Rgb565, 1>>>(), 16);
    assert_eq!(size_of::<Slot<VertexColors<Rgb565>>>(), 16);
    assert_eq!(size_of::<Slot<Unlit<Rgb565>>>(), 12);
    assert_eq!(size_of::<Slot<FlatLit<Fx16, Rgb565, 1>>>(), 12);
    assert_eq!(size_of::<Slot<PhongLit<Fx16, Rgb565, 1>>>(), 36);
    // `BinEntry`: 2 bytes a visible triangle.
    assert_eq!(size_of::<BinEntry>(), 2);
}

#[test]
fn lit_shading_without_normals_uses_face_normals() {
    // The sphere with no normals: Gouraud lighting falls back to each face's normal, so every
    // triangle is evenly lit (no specular term here) and the picture equals flat shading's.
    let (pos, tris) = sphere();
    let mesh = Mesh::new(&pos, &tris);
    let mut plain = Lighting::new(
        Material {
            ambient: Rgb888::new(30, 30, 40),
            diffuse: Rgb888::new(200, 120, 60),
            specular: Rgb888::BLACK,
            shininess: 0,
        },
        Rgb888::WHITE,
        Specular::BlinnPhong,
        Vec3::from_ints(0, 0, 3),
    );
    plain
        .add_light(Light::Directional {
            direction: Vec3::from_ints(1, 1, 1),
            color: Rgb888::WHITE,
        })
        .unwrap();
    let draw = |gouraud: bool| {
        let xf = transforms(Mat4::identity(), 64, 64);
        let mut buf = vec![0u16; 64 * 64];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 64, 64).unwrap();
        let mut z = vec![u16::MAX; 64 * 64];
        let depth = DepthBuffer::new(&mut z, 64, 64, Compare::Less).unwrap();
        let vp = Viewport::new(64, 64);
        let n = pos.len();
        if gouraud {
            let shading = GouraudLit::<_, Rgb565, 1>::new(plain.clone());
            let mut p = Pipeline::new(&xf, vp, CullClockwise, depth, shading).with_bits::<4>();
            p.draw(&mut fb, &mesh, &mut vec![VertexSlot::EMPTY; n])
                .unwrap();
        } else {
            let shading = FlatLit::<_, Rgb565, 1>::new(plain.clone());
            let mut p = Pipeline::new(&xf, vp, CullClockwise, depth, shading).with_bits::<4>();
            p.draw(&mut fb, &mesh, &mut vec![VertexSlot::EMPTY; n])
                .unwrap();
        }
        buf
    };
    let (g, f) = (draw(true), draw(false));
    let distinct: std::collections::BTreeSet<u16> = g.iter().copied().filter(|&c| c != 0).collect();
    assert!(
        distinct.len() > 10,
        "faces should be lit differently: {} colours",
        distinct.len()
    );
    // Flat shading lights the centroid and Gouraud each corner with the same normal; with no
    // specular term and a directional light the colour does not depend on the position, so they
    // agree up to rounding: flat shading rounds the lit colour to 8 bits and then to Rgb565,
    // Gouraud interpolates it at Rgb565's depth and rounds once. At most one step of a channel.
    let close = g.iter().zip(&f).all(|(&a, &b)| {
        let (ca, cb) = (Rgb565::from(RawU16::new(a)), Rgb565::from(RawU16::new(b)));
        (i16::from(ca.r()) - i16::from(cb.r())).abs() <= 1
            && (i16::from(ca.g()) - i16::from(cb.g())).abs() <= 1
            && (i16::from(ca.b()) - i16::from(cb.b())).abs() <= 1
    });
    assert!(close);
}

// ---------------------------------------------------------------------------------------------
// Random meshes.

const W: u32 = 48;
const H: u32 = 36;

/// A random mesh whose vertices are shared between triangles (so the scratch is reused), some of
/// them behind the near plane or off screen, a few indices out of range, normals (some zero) or
/// none, and the camera that looks at it.
#[derive(Debug)]
struct RandomScene {
    positions: Vec<Vec3<Fx16>>,
    normals: Option<Vec<Vec3<Fx16>>>,
    colors: Vec<Rgb888>,
    triangles: Vec<[u16; 3]>,
    transforms: Transforms<Fx16>,
    /// The model matrix is a similarity (lit in model space) or stretched (world space).
    similar: bool,
    /// Rows per band.
    rows: u32,
}

/// Xorshift: scenes reproduce from their seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Within 2.5 units of the origin: the camera at z = 3 with its near plane at 0.25 has some
    /// vertices behind it.
    fn coord(&mut self) -> Fx16 {
        Fx16::from_bits((self.next() % 327_681) as i32 - 163_840)
    }

    fn point(&mut self) -> Vec3<Fx16> {
        Vec3::new(self.coord(), self.coord(), self.coord())
    }
}

impl RandomScene {
    fn new(seed: u64, vertices: usize, triangles: usize, normals: bool, similar: bool) -> Self {
        let mut rng = Rng(seed | 1);
        let positions: Vec<Vec3<Fx16>> = (0..vertices).map(|_| rng.point()).collect();
        let normals = normals.then(|| {
            (0..vertices)
                .map(|k| {
                    if k % 7 == 3 {
                        Vec3::default()
                    } else {
                        rng.point()
                    }
                })
                .collect()
        });
        let mut r = || rng.next();
        let colors = (0..vertices)
            .map(|_| Rgb888::new(r() as u8, r() as u8, r() as u8))
            .collect();
        // About one triangle in twelve has an index up to two beyond the last vertex.
        let n = vertices as u64;
        let triangles = (0..triangles)
            .map(|_| {
                let mut t = [0; 3].map(|_: u16| (r() % n) as u16);
                if r() % 12 == 0 {
                    t[(r() % 3) as usize] = (n + r() % 3) as u16;
                }
                t
            })
            .collect();
        let yaw = Angle((r() % 65536) as u16);
        let model = if similar {
            let s = Fx16::from_ratio(3 + (r() % 4) as i64, 4);
            Mat4::scale(s, s, s).then(&Mat4::rotation_y(yaw))
        } else {
            Mat4::scale(Fx16::from_ratio(5, 4), Fx16::ONE, Fx16::from_ratio(2, 3))
                .then(&Mat4::rotation_y(yaw))
        };
        let rows = 1 + (r() % u64::from(H)) as u32;
        RandomScene {
            positions,
            normals,
            colors,
            triangles,
            transforms: transforms(model, W, H),
            similar,
            rows,
        }
    }

    fn mesh(&self) -> Mesh<'_, Fx16, u16> {
        Mesh {
            positions: &self.positions,
            normals: self.normals.as_deref(),
            colors: Some(&self.colors),
            uvs: None,
            triangles: &self.triangles,
            adjacency: None,
        }
    }
}

/// The pixels and statistics of a filled frame, a wireframe and a banded frame.
type Frames = [(Vec<u16>, RenderStats); 3];

/// Draws the scene filled, as a wireframe and in bands, all three through one scratch of `slots`
/// slots (so each draw also starts from the slots the previous one left).
fn frames<C: Cull + Copy, Sh: Shading<Fx16, Color = Rgb565> + Clone>(
    scene: &RandomScene,
    cull: C,
    shading: &Sh,
    depth: Option<Compare>,
    slots: usize,
) -> Frames {
    let vp = Viewport::new(W, H);
    let xf = &scene.transforms;
    match depth {
        Some(cmp) => {
            let mut z = vec![u16::MAX; (W * H) as usize];
            let mut zb = vec![u16::MAX; (W * scene.rows) as usize];
            let d = DepthBuffer::new(&mut z, W, H, cmp).unwrap();
            let db = DepthBuffer::new(&mut zb, W, scene.rows, cmp).unwrap();
            let p = Pipeline::new(xf, vp, cull, d, shading.clone());
            let pb = Pipeline::new(xf, vp, cull, db, shading.clone());
            run(scene, p, pb, slots)
        }
        None => {
            let p = Pipeline::new(xf, vp, cull, NoDepth, shading.clone());
            let pb = Pipeline::new(xf, vp, cull, NoDepth, shading.clone());
            run(scene, p, pb, slots)
        }
    }
}

fn run<C: Cull, D: DepthTest, Sh: Shading<Fx16, Color = Rgb565>>(
    scene: &RandomScene,
    mut p: Pipeline<Fx16, C, D, Sh>,
    mut pb: Pipeline<Fx16, C, D, Sh>,
    slots: usize,
) -> Frames {
    if !scene.similar {
        // The inverse transpose is not needed for the comparison: any other matrix moves the
        // lighting to world space.
        p.set_normal_matrix(Mat4::rotation_x(Angle::from_degrees(10)));
        pb.set_normal_matrix(Mat4::rotation_x(Angle::from_degrees(10)));
    }
    let mesh = scene.mesh();
    let mut scratch = vec![VertexSlot::EMPTY; slots];
    let mut filled = vec![0u16; (W * H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut filled, W, H).unwrap();
    let filled_stats = p.draw(&mut fb, &mesh, &mut scratch).unwrap();
    let mut wire = vec![0u16; (W * H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut wire, W, H).unwrap();
    let wire_stats = p
        .draw_wireframe(&mut fb, &mesh, &mut scratch, Rgb565::WHITE)
        .unwrap();
    let mut banded = vec![0u16; (W * H) as usize];
    let mut band = vec![0u16; (W * scene.rows) as usize];
    let mut bins = vec![BinEntry::ZERO; scene.triangles.len()];
    let banding = Banding {
        width: W,
        height: H,
        rows: scene.rows,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    let banded_stats = pb
        .draw_banded(&mesh, &banding, &mut band, &mut bins, &mut scratch, |b| {
            let at = b.y0() as usize * W as usize;
            let data = b.framebuffer().as_slice();
            banded[at..at + data.len()].copy_from_slice(data);
        })
        .unwrap();
    [
        (filled, filled_stats),
        (wire, wire_stats),
        (banded, banded_stats),
    ]
}

/// Every scratch size gives the full scratch's frames, and the banded frame is the filled one.
fn check_scene<C: Cull + Copy, Sh: Shading<Fx16, Color = Rgb565> + Clone>(
    scene: &RandomScene,
    cull: C,
    shading: Sh,
    depth: Option<Compare>,
    short: usize,
) -> Result<(), TestCaseError> {
    let n = scene.positions.len();
    let full = frames(scene, cull, &shading, depth, n);
    prop_assert!(full[2] == full[0], "bands differ from the whole frame");
    for slots in [0, short % n, n + 3] {
        let other = frames(scene, cull, &shading, depth, slots);
        for (k, what) in ["filled", "wireframe", "banded"].iter().enumerate() {
            prop_assert!(
                other[k] == full[k],
                "{what}: a scratch of {slots} of {n} slots differs"
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_meshes_draw_the_same_with_any_scratch(
        seed in any::<u64>(),
        vertices in 3usize..24,
        triangles in 1usize..40,
        normals in any::<bool>(),
        similar in any::<bool>(),
        shading in 0u8..5,
        depth in any::<bool>(),
        cull in any::<bool>(),
        short in any::<usize>(),
    ) {
        let scene = RandomScene::new(seed, vertices, triangles, normals, similar);
        let depth = depth.then_some(Compare::Less);
        let check = |c| -> Result<(), TestCaseError> {
            match (shading, c) {
                (0, true) => check_scene(&scene, CullClockwise, GouraudLit::<_, Rgb565, 2>::new(lighting()), depth, short),
                (0, false) => check_scene(&scene, NoCull, GouraudLit::<_, Rgb565, 2>::new(lighting()), depth, short),
                (1, true) => check_scene(&scene, CullClockwise, PhongLit::<_, Rgb565, 2>::new(lighting()), depth, short),
                (1, false) => check_scene(&scene, NoCull, PhongLit::<_, Rgb565, 2>::new(lighting()), depth, short),
                (2, true) => check_scene(&scene, CullClockwise, FlatLit::<_, Rgb565, 2>::new(lighting()), depth, short),
                (2, false) => check_scene(&scene, NoCull, FlatLit::<_, Rgb565, 2>::new(lighting()), depth, short),
                (3, true) => check_scene(&scene, CullClockwise, VertexColors::<Rgb565>::new(), depth, short),
                (3, false) => check_scene(&scene, NoCull, VertexColors::<Rgb565>::new(), depth, short),
                (_, true) => check_scene(&scene, CullClockwise, Unlit { color: Rgb565::CSS_TEAL }, depth, short),
                (_, false) => check_scene(&scene, NoCull, Unlit { color: Rgb565::CSS_TEAL }, depth, short),
            }
        };
        check(cull)?;
    }
}
