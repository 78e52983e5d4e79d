//! Textured meshes (`TexturedLit`): texel coordinates against the exact perspective-correct f64
//! ones, filters and wrap modes, bands against the whole frame, and hard input.

use fixtures::reference3d::{full_white_light, projected_corners, screen_weights};
use proptest::prelude::*;
use rasterizer_core::geom::MAX_VARYINGS;
use rasterizer_core::prelude::*;
use rasterizer_core::shade::{Shading, Specular, TexturedLit, VertexIn};
use rasterizer_core::texture::{Texture, TextureError};

const W: u32 = 96;

fn fx(x: f64) -> Fx16 {
    Fx16::from_bits((x * 65536.0).round() as i32)
}
const H: u32 = 72;

/// A 32x32 texture whose texel (x, y) is Rgb565 (x, 1, y): a drawn pixel names its texel, and
/// none is black, the colour of pixels not drawn.
fn id_texture() -> Vec<u8> {
    let mut t = Vec::with_capacity(32 * 32 * 2);
    for y in 0..32u16 {
        for x in 0..32u16 {
            t.extend_from_slice(&((x << 11) | (1 << 5) | y).to_le_bytes());
        }
    }
    t
}

/// Positions, texture coordinates and triangles.
type Floor = (Vec<Vec3<Fx16>>, Vec<[i32; 2]>, Vec<[u16; 3]>);

/// A floor quad from z = 1 to z = -9 seen from above its near end, so depth varies by a factor
/// of several across it; its uv run 0..reps.
fn floor(reps: f64) -> Floor {
    let p = |x: f64, z: f64| Vec3::new(fx(x), fx(-1.0), fx(z));
    let positions = vec![p(-2.0, 1.0), p(2.0, 1.0), p(2.0, -9.0), p(-2.0, -9.0)];
    let r = (reps * 65536.0) as i32;
    let uvs = vec![[0, r], [r, r], [r, 0], [0, 0]];
    (positions, uvs, vec![[0, 1, 2], [0, 2, 3]])
}

fn camera() -> Transforms<Fx16> {
    camera_at(0.3, 0.5, 2.5)
}

/// A camera above the floor's near end at `(x, y, z)`, looking down it.
fn camera_at(x: f64, y: f64, z: f64) -> Transforms<Fx16> {
    let p = |x: f64, y: f64, z: f64| Vec3::new(fx(x), fx(y), fx(z));
    Transforms::look_at(
        p(x, y, z),
        p(0.0, -1.0, -3.0),
        Angle::from_degrees(70),
        Viewport::new(W, H),
    )
    .unwrap()
}

fn draw(shader: TexturedLit<'_, Fx16, Rgb565, 0>, mesh: &Mesh<'_, Fx16>) -> Vec<u16> {
    draw_from(&camera(), shader, mesh)
}

fn draw_from(
    cam: &Transforms<Fx16>,
    shader: TexturedLit<'_, Fx16, Rgb565, 0>,
    mesh: &Mesh<'_, Fx16>,
) -> Vec<u16> {
    let mut buf = vec![0u16; (W * H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
    let mut p = Pipeline::new(cam, Viewport::new(W, H), NoCull, NoDepth, shader);
    let mut scratch = vec![VertexSlot::<[i32; 5]>::EMPTY; mesh.positions.len()];
    p.draw(&mut fb, mesh, &mut scratch).unwrap();
    buf
}

/// The exact texel coordinates at each pixel centre: the drawn triangles' screen vertices (the
/// pipeline's own projection) and clip-space `w`, interpolated perspective-correctly in f64
/// (or screen-linearly, without `perspective`).
fn exact_uv<'m>(
    mesh: &'m Mesh<'m, Fx16>,
    size: f64,
    perspective: bool,
) -> impl Fn(i32, i32) -> Option<(f64, f64)> + 'm {
    exact_uv_from(camera(), mesh, size, perspective)
}

fn exact_uv_from<'m>(
    cam: Transforms<Fx16>,
    mesh: &'m Mesh<'m, Fx16>,
    size: f64,
    perspective: bool,
) -> impl Fn(i32, i32) -> Option<(f64, f64)> + 'm {
    let p = Pipeline::new(
        &cam,
        Viewport::new(W, H),
        NoCull,
        NoDepth,
        Unlit {
            color: Rgb565::WHITE,
        },
    );
    let mvp = cam.model.then(&cam.view).then(&cam.projection);
    let corners = projected_corners(&p, &mvp, mesh.positions);
    move |x, y| {
        for tri in mesh.triangles {
            let c = tri.map(|i| corners[usize::from(i)]);
            let Some(b) = screen_weights(&c, x as u32, y as u32, W, H, perspective) else {
                continue;
            };
            // The pixel centre lies in the triangle (on an edge counts).
            if b.iter().any(|&w| w < -1e-9) {
                continue;
            }
            let uv = tri.map(|i| mesh.uvs.unwrap()[usize::from(i)]);
            let f =
                |a: usize| (0..3).map(|k| b[k] * f64::from(uv[k][a])).sum::<f64>() / 65536.0 * size;
            return Some((f(0), f(1)));
        }
        None
    }
}

/// How far `x` lies outside texel `i`'s interval `[i, i + 1)`, in texels.
fn outside(x: f64, i: i64) -> f64 {
    let i = i as f64;
    (i - x).max(x - (i + 1.0)).max(0.0)
}

/// Draws the floor (texture repeated `reps` times) from `cam` with the 32x32 id texture and
/// returns the pixels compared, those on a neighbouring texel, and the worst distance (texels)
/// from the exact coordinates to the texel drawn.
fn id_texture_error(cam: &Transforms<Fx16>, reps: f64) -> (usize, usize, f64) {
    let (positions, uvs, triangles) = floor(reps);
    let mesh = Mesh::new(&positions, &triangles).with_uvs(&uvs);
    let texels = id_texture();
    let texture = Texture::new(5, 5, &texels).unwrap();
    let buf = draw_from(cam, TexturedLit::new(full_white_light(), texture), &mesh);
    let exact = exact_uv_from(*cam, &mesh, 32.0, true);
    let (mut n, mut worst, mut off) = (0, 0.0f64, 0);
    for y in 0..H as i32 {
        for x in 0..W as i32 {
            let c = buf[(y as u32 * W + x as u32) as usize];
            // Pixels whose centre lies on an edge are the rasterizer's to take or leave (the
            // fill rule, tested elsewhere); those not drawn are not compared.
            let Some((u, v)) = exact(x, y).filter(|_| c != 0) else {
                continue;
            };
            n += 1;
            let (tx, ty) = (i64::from(c >> 11), i64::from(c & 31));
            // The drawn texel index is taken modulo 32: compare within the repeat.
            let (u, v) = (u.rem_euclid(32.0), v.rem_euclid(32.0));
            let e = |x: f64, i: i64| {
                outside(x, i)
                    .min(outside(x - 32.0, i))
                    .min(outside(x + 32.0, i))
            };
            let err = e(u, tx).max(e(v, ty));
            if err > 0.0 {
                off += 1;
            }
            worst = worst.max(err);
        }
    }
    (n, off, worst)
}

/// Nearest sampling, repeating, over a floor whose texture repeats twice: every pixel shows the
/// texel the exact coordinates fall in, or one within a few thousandths of a texel of them.
#[test]
fn nearest_texels_match_exact_perspective_coordinates() {
    let (n, off, worst) = id_texture_error(&camera(), 2.0);
    eprintln!("{n} pixels, {off} on a neighbouring texel, worst {worst:.5} texels");
    assert!(n > 2000, "the floor covers {n} pixels");
    // Measured: 1 pixel of 2,290 on a neighbouring texel, 0.0011 texels from it (the pixel's
    // reciprocal of 1 / w keeps 16 bits; with an exact 64-bit division per pixel it was 0 and 0).
    // The scene is fixed and the pipeline integer-only, so the result is the same on every
    // machine; the bounds are about twice the measure.
    assert!(
        off <= 2,
        "{off} pixels on a neighbouring texel, worst {worst}"
    );
    assert!(worst < 2.5e-3, "worst {worst}");
}

/// The textured floor drawn into an embedded-graphics target (a mock that fails on any pixel
/// written twice or out of bounds) writes exactly the framebuffer's pixels, with its colours.
#[test]
fn mock_target_gets_each_pixel_once() {
    let (positions, uvs, triangles) = floor(2.0);
    let mesh = Mesh::new(&positions, &triangles).with_uvs(&uvs);
    let texels = id_texture();
    let texture = Texture::new(5, 5, &texels).unwrap();
    let shader = TexturedLit::new(full_white_light(), texture).with_filter(Filter::Bilinear);
    let whole = draw(shader.clone(), &mesh);
    let mut mock = tests::StrictMock::<Rgb565>::new(W, H);
    let mut p = Pipeline::new(&camera(), Viewport::new(W, H), NoCull, NoDepth, shader);
    let mut scratch = vec![VertexSlot::<[i32; 5]>::EMPTY; positions.len()];
    p.draw(&mut AnyTarget::new(&mut mock), &mesh, &mut scratch)
        .unwrap();
    let mut written = 0;
    for y in 0..H as i32 {
        for x in 0..W as i32 {
            let want = whole[(y as u32 * W + x as u32) as usize];
            match mock.get(x, y) {
                Some(c) => {
                    written += 1;
                    assert_eq!(
                        embedded_graphics_core::pixelcolor::raw::RawU16::from(c).into_inner(),
                        want,
                        "({x}, {y})"
                    );
                }
                None => assert_eq!(want, 0, "({x}, {y}) not written"),
            }
        }
    }
    assert!(written > 2000);
}

/// The same floor against affine (screen-linear) coordinates: the drawn texels are far from
/// them over much of the floor, so the check above tells perspective-correct from affine.
#[test]
fn affine_coordinates_would_fail_the_check() {
    let (positions, uvs, triangles) = floor(1.0);
    let mesh = Mesh::new(&positions, &triangles).with_uvs(&uvs);
    let texels = id_texture();
    let texture = Texture::new(5, 5, &texels).unwrap();
    let buf = draw(TexturedLit::new(full_white_light(), texture), &mesh);
    let exact = exact_uv(&mesh, 32.0, true);
    let affine = exact_uv(&mesh, 32.0, false);
    let (mut n, mut far) = (0, 0);
    for y in 0..H as i32 {
        for x in 0..W as i32 {
            let (Some((_, ve)), Some((_, va))) = (exact(x, y), affine(x, y)) else {
                continue;
            };
            let c = buf[(y as u32 * W + x as u32) as usize];
            if c == 0 {
                continue;
            }
            let ty = i64::from(c & 31);
            // Measured 0, as in nearest_texels_match_exact_perspective_coordinates (same camera).
            assert_eq!(outside(ve, ty), 0.0, "({x}, {y})");
            n += 1;
            if outside(va, ty) > 1.0 {
                far += 1;
            }
        }
    }
    assert!(
        far * 4 > n,
        "{far} of {n} pixels more than a texel from the affine coordinates"
    );
}

/// Colour comes from the texel times the light, rounded once: half light halves each channel.
#[test]
fn texel_times_light() {
    let grey = Rgb888::new(128, 128, 128);
    let material = Material {
        ambient: Rgb888::new(255, 255, 255),
        diffuse: Rgb888::BLACK,
        specular: Rgb888::BLACK,
        shininess: 0,
    };
    let lighting = Lighting::<Fx16, 0>::new(material, grey, Specular::None, Vec3::default());
    let texel = Rgb565::new(31, 63, 20);
    let raw = (31u16 << 11) | (63 << 5) | 20;
    let bytes: Vec<u8> = (0..4).flat_map(|_| raw.to_le_bytes()).collect();
    let texture = Texture::new(1, 1, &bytes).unwrap();
    let (positions, uvs, triangles) = floor(1.0);
    let mesh = Mesh::new(&positions, &triangles).with_uvs(&uvs);
    let buf = draw(TexturedLit::new(lighting, texture), &mesh);
    let expect = |c: u8, max: u32| ((u32::from(c) * 128 * 2 + 255) / 510).min(max) as u8;
    let want = Rgb565::new(
        expect(texel.r(), 31),
        expect(texel.g(), 63),
        expect(texel.b(), 31),
    );
    let drawn: std::collections::BTreeSet<u16> = buf.iter().copied().filter(|&c| c != 0).collect();
    assert_eq!(
        drawn.into_iter().collect::<Vec<_>>(),
        [embedded_graphics_core::pixelcolor::raw::RawU16::from(want).into_inner()]
    );
}

/// Clamped coordinates continue the edge texels; repeated ones tile.
#[test]
fn clamp_and_repeat_differ_beyond_the_texture() {
    let (positions, uvs, triangles) = floor(3.0);
    let mesh = Mesh::new(&positions, &triangles).with_uvs(&uvs);
    let texels = id_texture();
    let texture = Texture::new(5, 5, &texels).unwrap();
    let repeat = draw(TexturedLit::new(full_white_light(), texture), &mesh);
    let clamp = draw(
        TexturedLit::new(full_white_light(), texture).with_wrap(Wrap::Clamp),
        &mesh,
    );
    let exact = exact_uv(&mesh, 32.0, true);
    let mut checked = 0;
    for y in 0..H as i32 {
        for x in 0..W as i32 {
            let Some((u, v)) = exact(x, y) else { continue };
            let i = (y as u32 * W + x as u32) as usize;
            // Well past the texture in both axes: clamped shows the last texel.
            if u > 33.0 && v > 33.0 {
                assert_eq!(clamp[i], (31 << 11) | (1 << 5) | 31, "({x}, {y})");
                checked += 1;
            }
        }
    }
    assert!(checked > 50, "{checked} pixels beyond the texture");
    assert_ne!(repeat, clamp);
}

/// Bilinear filtering of a texture of two colours gives the colours between them, and equals
/// nearest where all four texels agree.
#[test]
fn bilinear_blends_neighbouring_texels() {
    let (positions, uvs, triangles) = floor(1.0);
    let mesh = Mesh::new(&positions, &triangles).with_uvs(&uvs);
    // Left half black, right half red (31).
    let mut bytes = Vec::new();
    for _y in 0..4 {
        for x in 0..4u16 {
            bytes.extend_from_slice(&(if x < 2 { 0u16 } else { 31 << 11 }).to_le_bytes());
        }
    }
    let texture = Texture::new(2, 2, &bytes).unwrap();
    let nearest = draw(TexturedLit::new(full_white_light(), texture), &mesh);
    let bilinear = draw(
        TexturedLit::new(full_white_light(), texture).with_filter(Filter::Bilinear),
        &mesh,
    );
    let reds = |b: &[u16]| {
        b.iter()
            .map(|c| c >> 11)
            .collect::<std::collections::BTreeSet<_>>()
    };
    assert_eq!(reds(&nearest), [0, 31].into_iter().collect());
    let between = reds(&bilinear)
        .into_iter()
        .filter(|&r| r > 0 && r < 31)
        .count();
    assert!(
        between >= 10,
        "bilinear shows {between} levels between the two colours"
    );
}

/// The same frame drawn in bands of every height equals the whole frame.
#[test]
fn bands_equal_the_whole_frame() {
    let (positions, uvs, triangles) = floor(2.0);
    let mesh = Mesh::new(&positions, &triangles).with_uvs(&uvs);
    let texels = id_texture();
    let texture = Texture::new(5, 5, &texels).unwrap();
    for filter in [Filter::Nearest, Filter::Bilinear] {
        let shader = TexturedLit::new(full_white_light(), texture).with_filter(filter);
        let whole = draw(shader.clone(), &mesh);
        for rows in [1u32, 7, 16, 72] {
            let mut p = Pipeline::new(
                &camera(),
                Viewport::new(W, H),
                NoCull,
                NoDepth,
                shader.clone(),
            );
            let (frame, _) = tests::draw_banded_rgb565(&mut p, &mesh, W, H, rows);
            assert_eq!(frame, whole, "{filter:?}, bands of {rows}");
        }
    }
}

#[test]
fn texture_sizes_are_checked() {
    let bytes = [0u8; 8];
    assert_eq!(
        Texture::new(1, 2, &bytes[..6]),
        Err(TextureError::WrongLength {
            expected: 16,
            actual: 6
        })
    );
    assert!(matches!(
        Texture::new(11, 0, &bytes),
        Err(TextureError::TooLarge { .. })
    ));
    assert!(Texture::new(1, 1, &bytes).is_ok());
    assert!(!TextureError::TooLarge {
        width_log2: 200,
        height_log2: 0
    }
    .to_string()
    .is_empty());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// From random eye positions and texture repeats, every pixel's texel is within 12/1,000 texel
    /// of the exact f64 perspective-correct coordinates.
    #[test]
    fn texels_match_f64_from_any_eye(
        x in -1.5f64..1.5,
        y in -0.6f64..3.0,
        z in 1.5f64..5.0,
        reps in 0.25f64..8.0,
    ) {
        let (n, _, worst) = id_texture_error(&camera_at(x, y, z), reps);
        prop_assume!(n > 100);
        // Measured: 5.8e-3 texels at worst over 2,000 random eyes (PROPTEST_CASES=2000); the
        // bound is about twice that. A pixel's reciprocal of 1 / w keeps 16 bits, so the
        // coordinates are within about 2^-14 of the triangle's extent in texels (up to 256 here);
        // with an exact 64-bit division per pixel this was 7.9e-5.
        prop_assert!(worst < 1.2e-2, "worst {worst} over {n} pixels");
    }

    /// Any texture coordinates (i32 extremes included), any camera turn, a mesh without uvs, a
    /// near-plane crossing: no panic (debug builds check overflow), and with a 1x1 texture every
    /// drawn pixel is its colour.
    #[test]
    fn any_coordinates_draw_without_panic(
        uvs in proptest::collection::vec(
            prop_oneof![any::<i32>(), -200_000..200_000i32, Just(i32::MIN), Just(i32::MAX)], 8),
        eye_z in -3.0f64..6.0,
        has_uvs in any::<bool>(),
    ) {
        let (positions, _, triangles) = floor(1.0);
        let uv: Vec<[i32; 2]> = uvs.chunks(2).map(|c| [c[0], c[1]]).collect();
        let mut mesh = Mesh::new(&positions, &triangles);
        if has_uvs {
            mesh = mesh.with_uvs(&uv);
        }
        let bytes = 0xf81fu16.to_le_bytes();
        let texture = Texture::new(0, 0, &bytes).unwrap();
        let p = |x: f64, y: f64, z: f64| Vec3::new(fx(x), fx(y), fx(z));
        let cam = Transforms::look_at(p(0.0, 0.5, eye_z), p(0.0, -1.0, eye_z - 3.0),
            Angle::from_degrees(70), Viewport::new(W, H)).unwrap();
        let mut buf = vec![0u16; (W * H) as usize];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
        let mut pl = Pipeline::new(&cam, Viewport::new(W, H), NoCull, NoDepth,
            TexturedLit::new(full_white_light(), texture).with_filter(Filter::Bilinear));
        let mut scratch = vec![VertexSlot::<[i32; 5]>::EMPTY; 4];
        pl.draw(&mut fb, &mesh, &mut scratch).unwrap();
        prop_assert!(buf.iter().all(|&c| c == 0 || c == 0xf81f));
    }
}

/// `TexturedLit` with every item forwarded but `FUSED_PAIRED` (the default, false): the fused
/// loop steps its values one by one.
#[derive(Debug, Clone)]
struct Unpaired<'t>(TexturedLit<'t, Fx16, Rgb565, 0>);

impl Shading<Fx16> for Unpaired<'_> {
    type Color = Rgb565;
    type Varyings = <TexturedLit<'static, Fx16, Rgb565, 0> as Shading<Fx16>>::Varyings;
    type Stored = [i32; 5];
    const NEEDS_WORLD: bool = true;
    const NEEDS_UV: bool = true;
    const NEEDS_W: bool = true;
    const NEEDS_TRIANGLE: bool = true;
    const FUSED_FRAC: u32 = 0;
    const FUSED_OFFSET: u32 = 0;
    fn begin_frame(&mut self, model: Option<&Mat4<Fx16>>) -> bool {
        self.0.begin_frame(model)
    }
    fn vertex(&mut self, v: &VertexIn<Fx16>) -> Self::Varyings {
        self.0.vertex(v)
    }
    fn vertex_stored(&mut self, v: &VertexIn<Fx16>) -> Self::Stored {
        self.0.vertex_stored(v)
    }
    fn project(&self, v: &mut Self::Varyings, w: Fx16) {
        self.0.project(v, w)
    }
    fn triangle(&mut self, v: &mut [Self::Varyings; 3]) {
        self.0.triangle(v)
    }
    fn face(&mut self, vertices: &[VertexIn<Fx16>; 3]) {
        self.0.face(vertices)
    }
    fn pixel(&self, v: &Self::Varyings) -> Rgb565 {
        self.0.pixel(v)
    }
    fn pixel_fused(&self, acc: &[u32; MAX_VARYINGS]) -> Rgb565 {
        self.0.pixel_fused(acc)
    }
}

/// A frame with a depth buffer (the fused loop's path), `Less`.
fn draw_depth<Sh: Shading<Fx16, Color = Rgb565, Stored = [i32; 5]>>(
    cam: &Transforms<Fx16>,
    shader: Sh,
    mesh: &Mesh<'_, Fx16>,
) -> Vec<u16> {
    let mut buf = vec![0u16; (W * H) as usize];
    let mut z = vec![u16::MAX; (W * H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
    let depth = DepthBuffer::new(&mut z, W, H, Compare::Less).unwrap();
    let mut p = Pipeline::new(cam, Viewport::new(W, H), NoCull, depth, shader);
    let mut scratch = vec![VertexSlot::<[i32; 5]>::EMPTY; mesh.positions.len()];
    p.draw(&mut fb, mesh, &mut scratch).unwrap();
    buf
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// `TexturedLit` claims `FUSED_PAIRED`: its values stepped in pairs give the pixels they
    /// give stepped one by one, from any eye (the floor's far end ten times the near one's
    /// depth: 1 / w far apart), any texture repeat and offset, either filter.
    #[test]
    fn paired_texture_values_draw_the_unpaired_pixels(
        x in -1.5f64..1.5,
        y in -0.6f64..3.0,
        z in 1.2f64..6.0,
        reps in 0.05f64..40.0,
        offset in -5_000_000i32..5_000_000,
        bilinear in any::<bool>(),
    ) {
        // The floor in 12 x 12 quads: triangles small enough for the fused loop's lean path.
        const N: u16 = 12;
        let p = |i: u16, j: u16| {
            let (s, t) = (f64::from(i) / f64::from(N), f64::from(j) / f64::from(N));
            Vec3::new(fx(-2.0 + 4.0 * s), fx(-1.0), fx(1.0 - 10.0 * t))
        };
        let uv = |i: u16, j: u16| {
            let r = reps * 65536.0 / f64::from(N);
            [(f64::from(i) * r) as i32 + offset, (f64::from(N - j) * r) as i32 - offset]
        };
        let (mut positions, mut uvs, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
        for j in 0..=N {
            for i in 0..=N {
                positions.push(p(i, j));
                uvs.push(uv(i, j));
            }
        }
        let at = |i: u16, j: u16| j * (N + 1) + i;
        for j in 0..N {
            for i in 0..N {
                triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        let mesh = Mesh::new(&positions, &triangles).with_uvs(&uvs);
        let texels = id_texture();
        let texture = Texture::new(5, 5, &texels).unwrap();
        let filter = if bilinear { Filter::Bilinear } else { Filter::Nearest };
        let shader = TexturedLit::new(full_white_light(), texture).with_filter(filter);
        let cam = camera_at(x, y, z);
        let paired = draw_depth(&cam, shader.clone(), &mesh);
        prop_assume!(paired.iter().any(|&p| p != 0));
        prop_assert_eq!(paired, draw_depth(&cam, Unpaired(shader), &mesh));
    }
}
