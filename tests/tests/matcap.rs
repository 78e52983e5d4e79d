//! `shade::MatCap` against an `f64` reference: the texel each normal picks (the view-space normal
//! and the lookup computed in `f64` from the same matrix entries and normal bits), the colour a
//! vertex gets, the clamping of zero, tiny, huge and out-of-range normals, and the image checks.

use embedded_graphics_core::pixelcolor::raw::RawU16;
use fixtures::scenes::XorShift32;
use rasterizer_core::prelude::*;
use rasterizer_core::shade::{MatCapError, Shading, VertexIn, MATCAP_MAX_SIDE_LOG2};
use rasterizer_core::texture::TextureError;

fn bits(v: Fx16) -> f64 {
    f64::from(v.to_bits()) / 65536.0
}

fn fx(v: f64) -> Fx16 {
    Fx16::from_bits((v * 65536.0).round() as i32)
}

/// The texel the reference picks: `m` (upper 3x3, in f64 from the fixed-point entries) times
/// the normal, normalised, then `round((x + 1) / 2 (side - 1))` and `round((1 - y) / 2 (side -
/// 1))`, clamped; the centre for a zero vector. Also the unrounded coordinates.
fn reference(m: &Mat4<Fx16>, n: [i32; 3], side: u32) -> ((u32, u32), (f64, f64)) {
    let n = n.map(|c| f64::from(c) / 65536.0);
    let v: Vec<f64> = (0..3)
        .map(|r| (0..3).map(|c| bits(m.m[r][c]) * n[c]).sum())
        .collect();
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let last = f64::from(side - 1);
    if len == 0.0 {
        let mid = (last / 2.0 + 0.5).floor() as u32;
        return ((mid, mid), (last / 2.0, last / 2.0));
    }
    let (x, y) = (v[0] / len, v[1] / len);
    let (u, w) = ((x + 1.0) / 2.0 * last, (1.0 - y) / 2.0 * last);
    let pick = |t: f64| (t + 0.5).floor().clamp(0.0, last) as u32;
    ((pick(u), pick(w)), (u, w))
}

/// A square image of `2^side_log2` texels whose texel `(x, y)` is its own coordinates in
/// colour (red x, green y): a colour names its texel.
fn coordinate_image(side_log2: u8) -> Vec<u8> {
    let side = 1u32 << side_log2;
    let mut out = Vec::new();
    for y in 0..side {
        for x in 0..side {
            let c = Rgb565::new(
                (x % 32) as u8,
                (y % 64) as u8,
                ((x / 32) + (y / 64) * 8) as u8,
            );
            out.extend_from_slice(&RawU16::from(c).into_inner().to_le_bytes());
        }
    }
    out
}

/// Random model rotations and uniform scales under the M1 camera, random normals of lengths
/// from 1/64 to 64: the texel chosen against the reference, for every side.
///
/// Measured (40,000 normals a side, sides 2 to 256, 320,000 in all): no texel differs. The
/// lookup's only error against this reference is its integer normalisation (a reciprocal square
/// root good to about 2^-29), far below a texel even at 256 (one texel is 2^-7 of the range): a
/// difference needs the exact coordinate within about 2^-21 of a rounding tie. The bound is
/// the measurement: none.
#[test]
fn texel_matches_f64_reference() {
    let mut rng = XorShift32::seeded(0x1234_5678);
    let camera = fixtures::scenes3d::transforms();
    for side_log2 in 1..=MATCAP_MAX_SIDE_LOG2 {
        let side = 1u32 << side_log2;
        let image = coordinate_image(side_log2);
        let mut differ = Vec::new();
        let cases = 40_000;
        let mut current = None;
        for case in 0..cases {
            if case % 1000 == 0 {
                // A new model matrix every 1000 normals.
                let a = Angle::from_degrees((rng.next_u32() % 360) as i32);
                let b = Angle::from_degrees((rng.next_u32() % 360) as i32);
                let s = [0.25, 1.0, 3.0][(rng.next_u32() % 3) as usize];
                let model = Mat4::rotation_x(a)
                    .then(&Mat4::rotation_y(b))
                    .then(&Mat4::scale(fx(s), fx(s), fx(s)));
                let mut sh = MatCap::<Fx16, Rgb565>::new(side_log2, &image, &camera.view).unwrap();
                assert!(sh.begin_frame(Some(&model)), "model-space normals");
                current = Some((model.then(&camera.view), sh));
            }
            let len = 2f64.powi((rng.next_u32() % 13) as i32 - 6);
            let d = loop {
                let d = [rng.unit(), rng.unit(), rng.unit()];
                let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                if l > 0.05 && l <= 1.0 {
                    break d.map(|c| c / l * len);
                }
            };
            let n = d.map(|c| (c * 65536.0).round() as i32);
            {
                let Some((mv, sh)) = &current else {
                    unreachable!("made at case 0")
                };
                let got = sh.texel_of(n);
                let (want, exact) = reference(mv, n, side);
                if got != want {
                    differ.push(format!("{n:?}: got {got:?}, want {want:?} ({exact:?})"));
                }
            }
        }
        assert!(
            differ.is_empty(),
            "side {side}: {} of {cases} texels differ:\n{}",
            differ.len(),
            differ.join("\n")
        );
    }
}

/// Every vertex of M1 (Suzanne's file normals, M1's model and camera) takes the colour of the
/// texel the reference picks, in Rgb565 exactly: the texel's own colour is what the pipeline
/// interpolates from.
#[test]
fn m1_vertex_colours_are_the_reference_texels() {
    let loaded = fixtures::scenes3d::Scene::M1.load().unwrap();
    let mesh = loaded.mesh();
    let xf = fixtures::scenes3d::transforms();
    let image = coordinate_image(6);
    let mut sh = MatCap::<Fx16, Rgb565>::new(6, &image, &xf.view).unwrap();
    let normals = mesh.normals.unwrap();
    // Normals that follow the model matrix: model space, as the pipeline hands them over.
    assert!(sh.begin_frame(Some(&xf.model)));
    let mv = xf.model.then(&xf.view);
    let mut differ = 0;
    for n in normals {
        let bits = [n.x, n.y, n.z].map(|c| c.to_bits());
        let (want, _) = reference(&mv, bits, 64);
        let v = VertexIn {
            position: Vec3::default(),
            normal: *n,
            color: Rgb888::WHITE,
            uv: [0; 2],
        };
        let values = sh.vertex(&v);
        let got = sh.pixel(&values);
        let texel = |(x, y): (u32, u32)| {
            let i = 2 * (y * 64 + x) as usize;
            Rgb565::from(RawU16::new(u16::from_le_bytes([image[i], image[i + 1]])))
        };
        if got != texel(want) {
            differ += 1;
        }
    }
    // Measured: 0 of 507.
    assert_eq!(differ, 0, "{differ} of {} vertices", normals.len());
}

/// Zero normals take the centre texel; the axes take the edges' middles; huge, tiny and
/// saturated components stay in the image; a matrix without a linear part (a model scaled to
/// zero) gives the centre; the pipeline draws such a mesh without panicking.
#[test]
fn extreme_normals_clamp_to_the_image() {
    let view = Mat4::<Fx16>::identity();
    let image = coordinate_image(6);
    let sh = MatCap::<Fx16, Rgb565>::new(6, &image, &view).unwrap();
    let one = 1 << 16;
    assert_eq!(sh.texel_of([0, 0, 0]), (32, 32));
    assert_eq!(sh.texel_of([0, 0, one]), (32, 32));
    assert_eq!(sh.texel_of([0, 0, -one]), (32, 32));
    assert_eq!(sh.texel_of([one, 0, 0]), (63, 32));
    assert_eq!(sh.texel_of([-one, 0, 0]), (0, 32));
    assert_eq!(sh.texel_of([0, one, 0]), (32, 0));
    assert_eq!(sh.texel_of([0, -one, 0]), (32, 63));
    assert_eq!(sh.texel_of([i32::MAX, i32::MAX, 0]), (54, 9));
    assert_eq!(sh.texel_of([i32::MIN, 0, 0]), (0, 32));
    assert_eq!(sh.texel_of([i32::MIN, i32::MIN, i32::MIN]), (13, 50));
    assert_eq!(sh.texel_of([1, 0, 0]), (63, 32));
    assert_eq!(sh.texel_of([0, -1, 0]), (32, 63));
    let mut rng = XorShift32::seeded(99);
    for _ in 0..100_000 {
        let n = [
            rng.next_u32() as i32,
            rng.next_u32() as i32,
            rng.next_u32() as i32,
        ];
        let (x, y) = sh.texel_of(n);
        assert!(x < 64 && y < 64, "{n:?}");
    }
    // One texel and a side of 1: every normal picks it.
    let single = [0x1f, 0xf8];
    let sh1 = MatCap::<Fx16, Rgb565>::new(0, &single, &view).unwrap();
    assert_eq!(sh1.texel_of([one, -one, 0]), (0, 0));
    assert_eq!(sh1.texel_of([0, 0, 0]), (0, 0));
    // A model scaled to nothing: no direction, the centre.
    let mut flat = sh.clone();
    let zero = Mat4::scale(Fx16::ZERO, Fx16::ZERO, Fx16::ZERO);
    flat.begin_frame(Some(&zero));
    assert_eq!(flat.texel_of([one, 0, 0]), (32, 32));
    // A huge uniform scale picks the same texels as none.
    let mut big = sh.clone();
    big.begin_frame(Some(&Mat4::scale(fx(30000.0), fx(30000.0), fx(30000.0))));
    for n in [[one, 0, 0], [3000, -7000, 100], [-one, one, one]] {
        assert_eq!(big.texel_of(n), sh.texel_of(n), "{n:?}");
    }
    // A mesh of zero, tiny and saturated normals draws.
    let p = |x, y, z| Vec3::<Fx16>::from_ints(x, y, z);
    let positions = [p(-1, -1, 0), p(1, -1, 0), p(0, 1, 0), p(1, 1, 0)];
    let normals = [
        Vec3::default(),
        Vec3::new(Fx16::from_bits(1), Fx16::ZERO, Fx16::ZERO),
        Vec3::new(Fx16::MAX, Fx16::MIN, Fx16::MAX),
        Vec3::new(Fx16::MIN, Fx16::MIN, Fx16::MIN),
    ];
    let mesh = Mesh::new(&positions, &[[0u16, 1, 2], [1, 3, 2]]).with_normals(&normals);
    let xf = Transforms::look_at(
        p(0, 0, 4),
        p(0, 0, 0),
        Angle::from_degrees(50),
        Viewport::new(64, 48),
    )
    .unwrap();
    let mut pl = Pipeline::new(&xf, Viewport::new(64, 48), NoCull, NoDepth, sh);
    let mut px = [0u16; 64 * 48];
    let mut fb = Framebuffer::<Rgb565>::new(&mut px, 64, 48).unwrap();
    let stats = pl
        .draw(&mut fb, &mesh, &mut [VertexSlot::EMPTY; 4])
        .unwrap();
    assert_eq!(stats.drawn, 2);
}

/// The image is checked when the shader is made: the length, the side's limit, squareness.
#[test]
fn image_errors_are_typed() {
    let view = Mat4::<Fx16>::identity();
    let image = coordinate_image(5);
    assert_eq!(
        MatCap::<Fx16, Rgb565>::new(5, &image[..image.len() - 2], &view).err(),
        Some(MatCapError::Texture(TextureError::WrongLength {
            expected: 2048,
            actual: 2046
        }))
    );
    assert_eq!(
        MatCap::<Fx16, Rgb565>::new(9, &[], &view).err(),
        Some(MatCapError::TooLarge { side_log2: 9 })
    );
    assert_eq!(
        MatCap::<Fx16, Rgb565>::new(200, &[], &view).err(),
        Some(MatCapError::TooLarge { side_log2: 200 })
    );
    let wide = Texture::new(5, 4, &image[..1024]).unwrap();
    let err = MatCap::<Fx16, Rgb565>::from_texture(wide, &view).err();
    assert_eq!(
        err,
        Some(MatCapError::NotSquare {
            width_log2: 5,
            height_log2: 4
        })
    );
    assert_eq!(
        err.unwrap().to_string(),
        "a MatCap image must be square, not 32x16 texels"
    );
    let big = vec![0u8; 2 << 18];
    let tex = Texture::new(9, 9, &big).unwrap();
    assert_eq!(
        MatCap::<Fx16, Rgb565>::from_texture(tex, &view).err(),
        Some(MatCapError::TooLarge { side_log2: 9 })
    );
    assert_eq!(
        MatCapError::TooLarge { side_log2: 9 }.to_string(),
        "a 512x512 MatCap image is larger than 256x256 texels"
    );
    assert!(MatCap::<Fx16, Rgb565>::new(5, &image, &view).is_ok());
}
