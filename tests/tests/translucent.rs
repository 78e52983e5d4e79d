//! Translucent meshes: the 3D pipeline drawing through `Translucent` with a read-only depth test
//! (`DepthReadOnly`). Opacity 255 is the opaque picture and 0 leaves the target; each pixel of a
//! convex mesh is blended once, exactly as `color::blend` and within half a step of f64; the
//! stored depths never change; bands give the whole frame; a target without read-back gets the
//! typed error and no pixel.

use proptest::prelude::*;
use rasterizer_core::color::blend;
use rasterizer_core::depth::DepthTest;
use rasterizer_core::numerics::{Numerics, Perspective, Standard};
use rasterizer_core::pipeline::{DrawError, DEFAULT_BITS};
use rasterizer_core::prelude::*;
use rasterizer_core::surface::{Band, BlendError};
use tests::StrictMock;

type Gouraud = GouraudLit<Fx16, Rgb565, 1>;

fn suzanne() -> fixtures::obj::LoadedMesh {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models/suzanne.obj");
    fixtures::obj::LoadedMesh::load(&path).unwrap()
}

/// The M1 camera with the model turned `yaw` degrees about y and moved by `x` (16.16).
fn transforms(w: u32, h: u32, yaw: i32, x: i32) -> Transforms<Fx16> {
    let model = Mat4::rotation_y(Angle::from_degrees(yaw)).then(&Mat4::translation(Vec3::new(
        Fx16::from_bits(x),
        Fx16::ZERO,
        Fx16::ZERO,
    )));
    fixtures::scenes3d::camera(model, w, h)
}

fn gouraud() -> Gouraud {
    GouraudLit::new(fixtures::scenes3d::lighting())
}

/// A lit pipeline with the given depth stage and numerics.
fn pipeline<D: DepthTest, N: Numerics>(
    w: u32,
    h: u32,
    yaw: i32,
    x: i32,
    depth: D,
) -> Pipeline<Fx16, CullClockwise, D, Gouraud, DEFAULT_BITS, N> {
    Pipeline::new(
        &transforms(w, h, yaw, x),
        Viewport::new(w, h),
        CullClockwise,
        depth,
        gouraud(),
    )
    .with_numerics::<N>()
}

const BG: Rgb565 = Rgb565::new(4, 20, 12);

/// Opaque Suzanne (turned 20°, moved left) with a writing depth buffer, then Suzanne turned -35°
/// and moved right through `Translucent` at `opacity` with the buffer read-only, into `fb`.
fn two_pass<S, N>(fb: &mut S, z: &mut [u16], w: u32, h: u32, opacity: u8)
where
    S: Surface<Color = Rgb565, Error = core::convert::Infallible>,
    N: Numerics,
{
    let mesh = suzanne();
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let d = DepthBuffer::new(z, w, h, Compare::Less).unwrap();
    let mut p = pipeline::<_, N>(w, h, 20, -20_000, d);
    p.draw(fb, &mesh.mesh(), &mut scratch).unwrap();
    let d = p.depth.read_only();
    let mut p = pipeline::<_, N>(w, h, -35, 22_000, d);
    p.draw(
        &mut Translucent::new(fb, opacity),
        &mesh.mesh(),
        &mut scratch,
    )
    .unwrap();
}

fn fb_pixels(buf: &[u16]) -> Vec<Rgb565> {
    buf.iter()
        .map(|&w| embedded_graphics_core::pixelcolor::raw::RawU16::new(w).into())
        .collect()
}

#[test]
fn opacity_255_draws_the_opaque_mesh_and_0_leaves_the_target() {
    let (w, h) = (96u32, 72u32);
    let mesh = suzanne();
    let scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let draw = |opacity: Option<u8>| {
        let mut buf = vec![0u16; (w * h) as usize];
        let mut z = vec![u16::MAX; (w * h) as usize];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, w, h).unwrap();
        fb.clear(BG).unwrap();
        let d = DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap();
        let mut p = pipeline::<_, Standard>(w, h, 30, 0, d);
        let mut scratch = scratch.clone();
        match opacity {
            None => p.draw(&mut fb, &mesh.mesh(), &mut scratch).map(|_| ()),
            Some(a) => p
                .draw(
                    &mut Translucent::new(&mut fb, a),
                    &mesh.mesh(),
                    &mut scratch,
                )
                .map(|_| ())
                .map_err(|_| unreachable!()),
        }
        .unwrap();
        (buf, z)
    };
    let (opaque, opaque_z) = draw(None);
    assert!(opaque.iter().any(|&p| p != opaque[0]), "the mesh is drawn");
    // Writing depth through the wrapper: the same picture and the same depths at opacity 255.
    assert_eq!(draw(Some(255)), (opaque.clone(), opaque_z.clone()));
    let (clear, _) = draw(Some(0));
    assert!(fb_pixels(&clear).iter().all(|&c| c == BG));
}

#[test]
fn read_only_depth_hides_the_translucent_mesh_and_keeps_the_depths() {
    let (w, h) = (96u32, 72u32);
    fn check<N: Numerics>(w: u32, h: u32) {
        // The opaque pass alone, and its depths.
        let mesh = suzanne();
        let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
        let mut alone = vec![0u16; (w * h) as usize];
        let mut z_alone = vec![u16::MAX; (w * h) as usize];
        {
            let mut fb = Framebuffer::<Rgb565>::new(&mut alone, w, h).unwrap();
            fb.clear(BG).unwrap();
            let d = DepthBuffer::new(&mut z_alone, w, h, Compare::Less).unwrap();
            let mut p = pipeline::<_, N>(w, h, 20, -20_000, d);
            p.draw(&mut fb, &mesh.mesh(), &mut scratch).unwrap();
        }
        // The translucent mesh alone over the background at full opacity, with its own depths:
        // where it is nearer than the opaque one, it shows.
        let mut front = vec![0u16; (w * h) as usize];
        let mut z_front = vec![u16::MAX; (w * h) as usize];
        {
            let mut fb = Framebuffer::<Rgb565>::new(&mut front, w, h).unwrap();
            fb.clear(BG).unwrap();
            let d = DepthBuffer::new(&mut z_front, w, h, Compare::Less).unwrap();
            let mut p = pipeline::<_, N>(w, h, -35, 22_000, d);
            p.draw(&mut fb, &mesh.mesh(), &mut scratch).unwrap();
        }
        let mut both = vec![0u16; (w * h) as usize];
        let mut z = vec![u16::MAX; (w * h) as usize];
        {
            let mut fb = Framebuffer::<Rgb565>::new(&mut both, w, h).unwrap();
            fb.clear(BG).unwrap();
            two_pass::<_, N>(&mut fb, &mut z, w, h, 160);
        }
        assert_eq!(z, z_alone, "a read-only depth stage writes nothing");
        let (mut hidden, mut shown) = (0, 0);
        for i in 0..(w * h) as usize {
            if z_front[i] == u16::MAX {
                assert_eq!(both[i], alone[i], "pixel {i}: no translucent mesh here");
            } else if z_front[i] > z_alone[i] {
                // Wholly behind the opaque surface here (the translucent depth at this pixel is
                // the nearest of its own, so no part of it passes).
                assert_eq!(both[i], alone[i], "pixel {i}: hidden");
                hidden += 1;
            } else if z_front[i] < z_alone[i] && z_alone[i] == u16::MAX {
                // Over the background only: at least one blend happened.
                assert_ne!(both[i], alone[i], "pixel {i}: shown");
                shown += 1;
            }
        }
        assert!(hidden > 50 && shown > 200, "{hidden} hidden, {shown} shown");
    }
    check::<Standard>(w, h);
    check::<Perspective>(w, h);
}

/// A cube of 12 triangles (counter-clockwise from outside), each face its own vertices and
/// colour: with back faces culled, each pixel is covered by exactly one triangle.
struct Cube {
    positions: Vec<Vec3<Fx16>>,
    colors: Vec<Rgb888>,
    triangles: Vec<[u8; 3]>,
}

fn cube() -> Cube {
    let f = |v: i32| Fx16::from_bits(v * 56_000);
    // Each face: its normal, two axes along it, its colour.
    type Face = ([i32; 3], [i32; 3], [i32; 3], Rgb888);
    let faces: [Face; 6] = [
        ([1, 0, 0], [0, 1, 0], [0, 0, 1], Rgb888::new(230, 60, 40)),
        ([-1, 0, 0], [0, 0, 1], [0, 1, 0], Rgb888::new(40, 200, 90)),
        ([0, 1, 0], [0, 0, 1], [1, 0, 0], Rgb888::new(60, 90, 240)),
        ([0, -1, 0], [1, 0, 0], [0, 0, 1], Rgb888::new(240, 220, 60)),
        ([0, 0, 1], [1, 0, 0], [0, 1, 0], Rgb888::new(200, 70, 220)),
        ([0, 0, -1], [0, 1, 0], [1, 0, 0], Rgb888::new(250, 250, 250)),
    ];
    let mut c = Cube {
        positions: vec![],
        colors: vec![],
        triangles: vec![],
    };
    for (n, u, v, color) in faces {
        let base = c.positions.len() as u8;
        for (su, sv) in [(-1, -1), (1, -1), (1, 1), (-1, 1)] {
            let p: [i32; 3] = core::array::from_fn(|k| n[k] + su * u[k] + sv * v[k]);
            c.positions.push(Vec3::new(f(p[0]), f(p[1]), f(p[2])));
            c.colors.push(color);
        }
        c.triangles.push([base, base + 1, base + 2]);
        c.triangles.push([base, base + 2, base + 3]);
    }
    c
}

/// The cube turned `yaw` and `pitch` degrees, drawn with vertex colours into `target`.
fn draw_cube<T: Surface<Color = Rgb565>>(
    target: &mut T,
    z: &mut [u16],
    w: u32,
    h: u32,
    yaw: i32,
    pitch: i32,
) -> Result<(), DrawError<T::Error>> {
    let c = cube();
    let mesh = Mesh {
        positions: &c.positions,
        normals: None,
        colors: Some(&c.colors),
        uvs: None,
        triangles: &c.triangles,
        adjacency: None,
    };
    let model = Mat4::rotation_y(Angle::from_degrees(yaw))
        .then(&Mat4::rotation_x(Angle::from_degrees(pitch)));
    let t = fixtures::scenes3d::camera(model, w, h);
    let d = DepthBuffer::new(z, w, h, Compare::Less).unwrap();
    let mut p = Pipeline::new(
        &t,
        Viewport::new(w, h),
        CullClockwise,
        d.read_only(),
        VertexColors::<Rgb565>::new(),
    );
    let mut scratch = vec![VertexSlot::EMPTY; c.positions.len()];
    p.draw(target, &mesh, &mut scratch).map(|_| ())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Each pixel of a convex mesh is blended once: exactly `blend(opaque, background, a)`, and
    /// within half a step of the f64 blend in each channel at its own depth.
    #[test]
    fn translucent_cube_blends_each_pixel_once_within_half_a_step_of_f64(
        opacity in 0..=255u8, r in 0..32u8, g in 0..64u8, b in 0..32u8,
        yaw in -180..180i32, pitch in -90..90i32,
    ) {
        let (w, h) = (64u32, 48u32);
        let bg = Rgb565::new(r, g, b);
        let mut opaque = vec![0u16; (w * h) as usize];
        let mut fb = Framebuffer::<Rgb565>::new(&mut opaque, w, h).unwrap();
        fb.clear(bg).unwrap();
        let mut z = vec![u16::MAX; (w * h) as usize];
        draw_cube(&mut fb, &mut z, w, h, yaw, pitch).unwrap();
        let mut over = vec![0u16; (w * h) as usize];
        let mut fb = Framebuffer::<Rgb565>::new(&mut over, w, h).unwrap();
        fb.clear(bg).unwrap();
        draw_cube(&mut Translucent::new(&mut fb, opacity), &mut z, w, h, yaw, pitch).unwrap();
        prop_assert!(z.iter().all(|&d| d == u16::MAX));
        let a = f64::from(opacity);
        for (i, (&src, &got)) in fb_pixels(&opaque).iter().zip(&fb_pixels(&over)).enumerate() {
            prop_assert_eq!(got, blend(src, bg, opacity), "pixel {}", i);
            for (s, d, o) in [(src.r(), bg.r(), got.r()), (src.g(), bg.g(), got.g()),
                              (src.b(), bg.b(), got.b())] {
                let f = (f64::from(s) * a + f64::from(d) * (255.0 - a)) / 255.0;
                prop_assert!((f64::from(o) - f).abs() <= 0.5 + 1e-9, "pixel {}: {} vs {}", i, o, f);
            }
        }
    }
}

/// A read-back mock recording the opacity each pixel was blended with, panicking on a pixel
/// blended twice or outside it.
struct AlphaMock {
    width: u32,
    alpha: Vec<Option<u8>>,
}

impl OriginDimensions for AlphaMock {
    fn size(&self) -> Size {
        Size::new(self.width, self.alpha.len() as u32 / self.width)
    }
}

impl DrawTarget for AlphaMock {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        _: I,
    ) -> Result<(), Self::Error> {
        panic!("a translucent draw wrote an opaque pixel");
    }
}

impl Surface for AlphaMock {
    const READ_BACK: bool = true;
    fn blend_span_in_clip(
        &mut self,
        x: i32,
        y: i32,
        len: u32,
        _: Rgb565,
        alpha: u8,
    ) -> Result<(), BlendError<Self::Error>> {
        for x in x..x + len as i32 {
            let i = (y * self.width as i32 + x) as usize;
            assert!(self.alpha[i].is_none(), "({x}, {y}) blended twice");
            self.alpha[i] = Some(alpha);
        }
        Ok(())
    }
}

#[test]
fn translucent_cube_pattern_is_the_opaque_coverage() {
    let (w, h) = (16u32, 12u32);
    let mut strict = StrictMock::<Rgb565>::new(w, h);
    let mut z = vec![u16::MAX; (w * h) as usize];
    draw_cube(&mut AnyTarget::new(&mut strict), &mut z, w, h, 30, 20).unwrap();
    let mut mock = AlphaMock {
        width: w,
        alpha: vec![None; (w * h) as usize],
    };
    draw_cube(&mut Translucent::new(&mut mock, 100), &mut z, w, h, 30, 20).unwrap();
    let pattern: Vec<String> = mock
        .alpha
        .chunks(w as usize)
        .map(|row| {
            row.iter()
                .map(|a| match a {
                    None => ' ',
                    Some(100) => '#',
                    Some(_) => '?',
                })
                .collect()
        })
        .collect();
    assert_eq!(pattern, strict.pattern(), "\n{}", pattern.join("\n"));
    assert_eq!(
        pattern,
        [
            "                ",
            "                ",
            "                ",
            "    #########   ",
            "    #########   ",
            "    #########   ",
            "    ########    ",
            "     #######    ",
            "     #######    ",
            "     ######     ",
            "      ###       ",
            "      #         ",
        ]
    );
}

#[test]
fn target_without_read_back_gets_a_typed_error_and_no_pixels() {
    let (w, h) = (32u32, 24u32);
    let mut mock = StrictMock::<Rgb565>::new(w, h);
    let mut target = AnyTarget::new(&mut mock);
    let mut z = vec![u16::MAX; (w * h) as usize];
    let mesh = suzanne();
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let d = DepthBuffer::new(&mut z, w, h, Compare::Less).unwrap();
    let mut p = pipeline::<_, Standard>(w, h, 30, 0, d);
    let result = p.draw(
        &mut Translucent::new(&mut target, 128),
        &mesh.mesh(),
        &mut scratch,
    );
    assert_eq!(
        result.map(|_| ()),
        Err(DrawError::Target(BlendError::CannotReadBack))
    );
    drop(p);
    assert_eq!(mock.calls.pixels, 0);
    assert!(z.iter().all(|&d| d == u16::MAX), "no depth written either");
    // 2D drawing through the wrapper too.
    let mut target = AnyTarget::new(&mut mock);
    let v = |x, y| SubPoint::<4>::new(x * 16, y * 16);
    assert_eq!(
        fill_triangle(
            &mut Translucent::new(&mut target, 9),
            [v(0, 0), v(9, 0), v(0, 9)],
            Rgb565::RED
        ),
        Err(BlendError::CannotReadBack)
    );
    assert_eq!(mock.calls.pixels, 0);
}

/// The two-pass frame in bands of `rows` rows, by hand: each band cleared, the opaque pass with
/// the band's depth buffer, the translucent pass with it read-only.
fn two_pass_banded(w: u32, h: u32, rows: u32, opacity: u8) -> Vec<u16> {
    let mesh = suzanne();
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let mut out = vec![0u16; (w * h) as usize];
    let mut band = vec![0u16; (w * rows) as usize];
    let mut z = vec![u16::MAX; (w * rows) as usize];
    let mut y0 = 0;
    while y0 < h {
        let n = rows.min(h - y0);
        let len = (w * n) as usize;
        let fb = Framebuffer::<Rgb565>::new(&mut band[..len], w, n).unwrap();
        let mut strip = Band::new(fb, y0 as i32);
        strip.clear(BG).unwrap();
        let mut d = DepthBuffer::new(&mut z[..len], w, n, Compare::Less).unwrap();
        d.start_band(y0 as i32, u16::MAX);
        let mut p = pipeline::<_, Standard>(w, h, 20, -20_000, d);
        p.draw(&mut strip, &mesh.mesh(), &mut scratch).unwrap();
        let mut d = p.depth.read_only();
        d.start_band(y0 as i32, 0);
        let mut p = pipeline::<_, Standard>(w, h, -35, 22_000, d);
        p.draw(
            &mut Translucent::new(&mut strip, opacity),
            &mesh.mesh(),
            &mut scratch,
        )
        .unwrap();
        let start = (y0 * w) as usize;
        out[start..start + len].copy_from_slice(strip.framebuffer().as_slice());
        y0 += n;
    }
    out
}

#[test]
fn translucent_bands_equal_the_whole_frame() {
    let (w, h) = (96u32, 72u32);
    let mut whole = vec![0u16; (w * h) as usize];
    let mut z = vec![u16::MAX; (w * h) as usize];
    {
        let mut fb = Framebuffer::<Rgb565>::new(&mut whole, w, h).unwrap();
        fb.clear(BG).unwrap();
        two_pass::<_, Standard>(&mut fb, &mut z, w, h, 150);
    }
    for rows in [1u32, 7, 16, 72] {
        let out = two_pass_banded(w, h, rows, 150);
        let differ = whole.iter().zip(&out).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "{differ} pixels differ in bands of {rows} rows");
    }
}
