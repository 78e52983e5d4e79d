//! The `float` comparison backend: the same pipeline on `f32` (micromath) agrees with 16.16 and
//! with f64 maths within stated bounds.

use proptest::prelude::*;
use rasterizer_core::math::Scalar;
use rasterizer_core::prelude::*;

fn transforms<S: Scalar>(yaw: u16, dist: i32, fov: i32) -> Transforms<S> {
    Transforms {
        model: Mat4::rotation_y(Angle(yaw)),
        view: Mat4::look_at(
            Vec3::from_ints(0, 0, dist),
            Vec3::from_ints(0, 0, 0),
            Vec3::from_ints(0, 1, 0),
        )
        .unwrap(),
        projection: Mat4::perspective(
            Angle::from_degrees(fov),
            S::from_ratio(4, 3),
            S::from_ratio(1, 10),
            S::from_int(100),
        )
        .unwrap(),
    }
}

fn f64_of(v: Fx16) -> f64 {
    f64::from(v.to_bits()) / 65536.0
}

#[test]
fn f32_sqrt_is_refined_to_float_precision() {
    for x in [2.0f32, 25.0, 0.5, 10.0, 3.0, 1e-6, 1e6, 12345.678] {
        let got = f64::from(Scalar::sqrt(x));
        let want = f64::from(x).sqrt();
        assert!(
            (got - want).abs() <= want * 2e-7,
            "sqrt({x}) = {got}, want {want}"
        );
    }
    assert_eq!(Scalar::sqrt(-4.0f32), 0.0);
    assert_eq!(Scalar::sqrt(f32::NAN), 0.0);
    let (s, c) = <f32 as Scalar>::sin_cos(Angle::from_degrees(30));
    // 30 degrees is 5461 units of 1/65536 turn, 29.998 degrees.
    assert!((s - 0.5).abs() < 1e-4 && (c - 0.866_025_4).abs() < 1e-4);
}

proptest! {
    #[test]
    fn f32_and_fx16_project_to_nearby_pixels(
        yaw in any::<u16>(), dist in 3i32..8, fov in 40i32..80,
        x in -1.0f64..1.0, y in -1.0f64..1.0, z in -1.0f64..1.0,
    ) {
        let vp = Viewport::new(320, 240);
        let fx = Pipeline::new(&transforms(yaw, dist, fov), vp, CullClockwise, NoDepth, Unlit { color: Rgb888::WHITE }).with_bits::<4>();
        let fl = Pipeline::new(&transforms(yaw, dist, fov), vp, CullClockwise, NoDepth, Unlit { color: Rgb888::WHITE }).with_bits::<4>();
        let p = Vec3::new(Fx16::from_bits((x * 65536.0) as i32), Fx16::from_bits((y * 65536.0) as i32), Fx16::from_bits((z * 65536.0) as i32));
        let pf = Vec3::new(f64_of(p.x) as f32, f64_of(p.y) as f32, f64_of(p.z) as f32);
        let (a, _) = fx.project(&fx.mvp().transform_point(p));
        let (b, _) = fl.project(&fl.mvp().transform_point(pf));
        // Same trigonometry, so the two differ only by 16.16 rounding against f32 rounding: within
        // two sixteenths of a pixel.
        prop_assert!((a.x - b.x).abs() <= 2 && (a.y - b.y).abs() <= 2, "{:?} vs {:?}", a, b);
    }
}

#[test]
fn f32_pipeline_renders_the_same_cube_as_fixed_point() {
    let corners: Vec<Vec3<Fx16>> = (0..8)
        .map(|i| {
            Vec3::from_ints(
                if i & 1 == 0 { -1 } else { 1 },
                if i & 2 == 0 { -1 } else { 1 },
                if i & 4 == 0 { -1 } else { 1 },
            )
        })
        .collect();
    let faces: [[u16; 3]; 12] = [
        [0, 2, 1],
        [1, 2, 3],
        [4, 5, 6],
        [5, 7, 6],
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7],
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5],
    ];
    let corners_f: Vec<Vec3<f32>> = corners
        .iter()
        .map(|p| Vec3::new(f64_of(p.x) as f32, f64_of(p.y) as f32, f64_of(p.z) as f32))
        .collect();
    let vp = Viewport::new(64, 48);
    let render = |f: &mut dyn FnMut(&mut rasterizer_core::surface::Framebuffer<Rgb888>)| {
        let mut buf = vec![0u8; 64 * 48 * 3];
        let mut fb =
            rasterizer_core::surface::Framebuffer::<Rgb888>::new(&mut buf, 64, 48).unwrap();
        f(&mut fb);
        buf
    };
    let a = render(&mut |fb| {
        let mut p = Pipeline::new(
            &transforms(5000, 5, 60),
            vp,
            CullClockwise,
            NoDepth,
            Unlit {
                color: Rgb888::WHITE,
            },
        )
        .with_bits::<4>();
        p.draw(
            fb,
            &Mesh::new(&corners, &faces),
            &mut [VertexSlot::EMPTY; 8],
        )
        .unwrap();
    });
    let b = render(&mut |fb| {
        let mut p = Pipeline::new(
            &transforms(5000, 5, 60),
            vp,
            CullClockwise,
            NoDepth,
            Unlit {
                color: Rgb888::WHITE,
            },
        )
        .with_bits::<4>();
        p.draw(
            fb,
            &Mesh::new(&corners_f, &faces),
            &mut [VertexSlot::EMPTY; 8],
        )
        .unwrap();
    });
    let differing = a.chunks(3).zip(b.chunks(3)).filter(|(x, y)| x != y).count();
    let covered = a.chunks(3).filter(|x| x[0] != 0).count();
    assert!(
        covered > 300,
        "the cube should cover a good part of the frame: {covered}"
    );
    // Only silhouette pixels can differ (sub-pixel vertex differences); state it as at most 4 % of
    // the covered pixels.
    assert!(
        differing * 25 <= covered,
        "{differing} of {covered} pixels differ"
    );
}
