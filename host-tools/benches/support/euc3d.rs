//! The comparison renderer of the 3D benchmarks: euc 0.5.3, a pure-Rust `f32` software renderer,
//! drawing the scenes of `fixtures::scenes3d` (same mesh, camera, projection, size and lighting)
//! with Gouraud shading, a depth test and back-face culling.
//!
//! Shared by `benches/scenes3d.rs` and `examples/count3d.rs` (through `#[path]`), so both draw
//! the same thing.
//!
//! - Input: the loaded 16.16 mesh converted to `f32` once (exactly: every coordinate is below 256
//!   in magnitude, so its 16.16 value fits an `f32`'s 24-bit mantissa), so both renderers start
//!   from the same numbers. euc draws a flat vertex list, three per triangle; here each entry is a
//!   vertex index (euc's own suggestion for indexed meshes), so, like our `Pipeline::draw`, each
//!   triangle's three vertices are transformed and lit again (euc has no vertex cache).
//! - Vertex shader: clip position through one `f32` model-view-projection matrix, and the lit
//!   colour per vertex in `f32` (the model of `rasterizer_core::shade`: ambient + diffuse
//!   `max(0, N·L)` + Blinn-Phong specular `max(0, N·H)^16`, in world space, the normal rotated by
//!   the model matrix and normalised, a zero normal giving the ambient term only, each channel
//!   clamped to 255).
//! - Target: euc's `Buffer2d<u16>` holding Rgb565 words (euc's pixel type is free, so the colour
//!   buffer is the same 150 KB of `u16` as ours); the fragment shader rounds the interpolated
//!   channels to 8 bits and converts to Rgb565 with the same embedded-graphics conversion our
//!   shader uses.
//! - Depth: euc's depth buffer is `Buffer2d<f32>` (300 KB; ours is 16-bit), `DepthStrategy::
//!   IfLessWrite` (its default, `<=`), cleared to 1.0.
//! - Culling: euc's `BackfaceCullingEnabled` drops triangles that are clockwise in normalised
//!   device coordinates (y up), which is our `CullClockwise` on the screen.
//! - What euc does differently (its design, not a setting): no clipping (it divides by `w` and
//!   clamps the bounding box to the screen; nothing in these scenes is behind the near plane),
//!   every pixel centre of the triangle's bounding box is tested with perspective-correct
//!   barycentric weights (one division per pixel), edges are inclusive (no top-left rule, shared
//!   edges are drawn twice), and the colour is interpolated perspective-correctly (ours affinely).

use euc::buffer::Buffer2d;
use euc::rasterizer::{BackfaceCullingEnabled, Triangles};
use euc::{Pipeline, Target};
use fixtures::obj::LoadedMesh;
use fixtures::scenes::{HEIGHT, WIDTH};
use fixtures::scenes3d;
use rasterizer_core::prelude::*;

/// euc's colour buffer: one Rgb565 word per pixel.
pub type EucColor = Buffer2d<u16>;
/// euc's depth buffer.
pub type EucDepth = Buffer2d<f32>;

type V3 = [f32; 3];

fn dot(a: V3, b: V3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn scale(a: V3, s: f32) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// `a` scaled to unit length, `None` for a zero vector.
fn normalize(a: V3) -> Option<V3> {
    let len2 = dot(a, a);
    (len2 > 0.0).then(|| scale(a, 1.0 / len2.sqrt()))
}

fn mat_mul(a: &[[f32; 4]; 4], b: &[[f32; 4]; 4]) -> [[f32; 4]; 4] {
    let mut m = [[0.0; 4]; 4];
    for (r, row) in m.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = (0..4).map(|k| a[r][k] * b[k][c]).sum();
        }
    }
    m
}

fn f(x: Fx16) -> f32 {
    x.to_bits() as f32 / 65536.0
}

fn v3(v: Vec3<Fx16>) -> V3 {
    [f(v.x), f(v.y), f(v.z)]
}

fn rgb(c: Rgb888) -> V3 {
    [c.r(), c.g(), c.b()].map(f32::from)
}

/// One scene for euc: the mesh in `f32`, the matrices and the lighting. It is euc's `Pipeline`
/// (its shaders), and [`EucScene::render`] renders it.
pub struct EucScene {
    positions: Vec<V3>,
    normals: Vec<V3>,
    /// The triangles' vertex indices, three per triangle: euc's vertex list.
    corners: Vec<u32>,
    /// The model matrix (a rotation: the rows of its upper 3x3).
    model: [V3; 3],
    /// Projection x view x model.
    mvp: [[f32; 4]; 4],
    /// Towards the light, unit length.
    light: V3,
    eye: V3,
    /// Material ambient times the (white) ambient light, / 255.
    ambient: V3,
    diffuse: V3,
    specular: V3,
}

impl EucScene {
    /// The scene of `fixtures::scenes3d` with `mesh` (which must have normals).
    pub fn new(mesh: &LoadedMesh) -> Self {
        let normals = mesh.normals.as_ref().expect("the scenes have normals");
        let (s, c) = (scenes3d::ROTATION_Y_DEGREES as f32).to_radians().sin_cos();
        let model = [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]];
        let eye = scenes3d::EYE.map(|v| v as f32);
        // look_at(eye, origin, +Y), as OpenGL's gluLookAt.
        let fwd = normalize(sub([0.0; 3], eye)).expect("eye away from the origin");
        let side = normalize(cross(fwd, [0.0, 1.0, 0.0])).expect("camera basis");
        let up = cross(side, fwd);
        let view = [
            [side[0], side[1], side[2], -dot(side, eye)],
            [up[0], up[1], up[2], -dot(up, eye)],
            [-fwd[0], -fwd[1], -fwd[2], dot(fwd, eye)],
            [0.0, 0.0, 0.0, 1.0],
        ];
        // OpenGL's perspective projection.
        let cot = 1.0 / (scenes3d::FOV_Y_DEGREES as f32 / 2.0).to_radians().tan();
        let aspect = WIDTH as f32 / HEIGHT as f32;
        let (near, far) = (
            scenes3d::NEAR.0 as f32 / scenes3d::NEAR.1 as f32,
            scenes3d::FAR as f32,
        );
        let proj = [
            [cot / aspect, 0.0, 0.0, 0.0],
            [0.0, cot, 0.0, 0.0],
            [
                0.0,
                0.0,
                (far + near) / (near - far),
                2.0 * far * near / (near - far),
            ],
            [0.0, 0.0, -1.0, 0.0],
        ];
        let model4 = [
            [model[0][0], model[0][1], model[0][2], 0.0],
            [model[1][0], model[1][1], model[1][2], 0.0],
            [model[2][0], model[2][1], model[2][2], 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let mvp = mat_mul(&proj, &mat_mul(&view, &model4));
        let light = normalize(scenes3d::LIGHT_DIRECTION.map(|v| v as f32)).expect("a light");
        Self {
            positions: mesh.positions.iter().map(|&p| v3(p)).collect(),
            normals: normals.iter().map(|&n| v3(n)).collect(),
            corners: mesh.triangles.iter().flatten().copied().collect(),
            model,
            mvp,
            light,
            eye,
            // The ambient light is white (255): Ma La / 255 = Ma.
            ambient: rgb(scenes3d::AMBIENT),
            diffuse: rgb(scenes3d::DIFFUSE),
            specular: rgb(scenes3d::SPECULAR),
        }
    }

    /// Triangles in the mesh.
    pub fn triangles(&self) -> usize {
        self.corners.len() / 3
    }

    /// A colour buffer and a depth buffer of the scene's size, cleared.
    pub fn buffers() -> (EucColor, EucDepth) {
        let size = [WIDTH as usize, HEIGHT as usize];
        (Buffer2d::new(size, 0), Buffer2d::new(size, 1.0))
    }

    /// Clears the colour buffer to black and the depth buffer to the far plane.
    pub fn clear(color: &mut EucColor, depth: &mut EucDepth) {
        color.clear(0);
        depth.clear(1.0);
    }

    /// Draws the mesh: Gouraud, depth test, back faces culled.
    #[inline(always)]
    pub fn render(&self, color: &mut EucColor, depth: &mut EucDepth) {
        Pipeline::draw::<Triangles<'_, EucDepth, BackfaceCullingEnabled>, _>(
            self,
            &self.corners,
            color,
            Some(depth),
        );
    }

    /// The triangles euc draws and the ones it culls, by euc's own test (the sign of the
    /// triangle's area in normalised device coordinates), computed apart from the drawing.
    pub fn stats(&self) -> (u32, u32) {
        let (mut drawn, mut culled) = (0, 0);
        for t in self.corners.chunks_exact(3) {
            let ndc = |i: u32| {
                let c = self.clip(self.positions[i as usize]);
                [c[0] / c[3], c[1] / c[3], c[2] / c[3]]
            };
            let (a, b, c) = (ndc(t[0]), ndc(t[1]), ndc(t[2]));
            if cross(sub(b, a), sub(c, a))[2] < 0.0 {
                culled += 1;
            } else {
                drawn += 1;
            }
        }
        (drawn, culled)
    }

    #[inline(always)]
    fn clip(&self, p: V3) -> [f32; 4] {
        let m = &self.mvp;
        let row = |r: usize| m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3];
        [row(0), row(1), row(2), row(3)]
    }

    /// The lit colour of a world-space point, per channel in `0.0..=255.0`.
    #[inline(always)]
    fn shade(&self, position: V3, normal: V3) -> V3 {
        let mut out = self.ambient;
        if let Some(n) = normalize(normal) {
            let nl = dot(n, self.light);
            if nl > 0.0 {
                let spec = normalize(sub(self.eye, position))
                    .and_then(|v| normalize([0, 1, 2].map(|k| self.light[k] + v[k])))
                    .map_or(0.0, |h| {
                        dot(n, h).max(0.0).powi(i32::from(scenes3d::SHININESS))
                    });
                for (k, o) in out.iter_mut().enumerate() {
                    *o += self.diffuse[k] * nl + self.specular[k] * spec;
                }
            }
        }
        out.map(|c| c.min(255.0))
    }
}

impl Pipeline for EucScene {
    type Vertex = u32;
    type VsOut = (f32, f32, f32);
    type Pixel = u16;

    #[inline(always)]
    fn vert(&self, &i: &u32) -> ([f32; 4], (f32, f32, f32)) {
        let p = self.positions[i as usize];
        let n = self.normals[i as usize];
        let m = &self.model;
        let world = [dot(m[0], p), dot(m[1], p), dot(m[2], p)];
        let normal = [dot(m[0], n), dot(m[1], n), dot(m[2], n)];
        let [r, g, b] = self.shade(world, normal);
        (self.clip(p), (r, g, b))
    }

    #[inline(always)]
    fn frag(&self, &(r, g, b): &(f32, f32, f32)) -> u16 {
        let ch = |x: f32| (x + 0.5).clamp(0.0, 255.0) as u8;
        Rgb565::from(Rgb888::new(ch(r), ch(g), ch(b))).into_storage()
    }
}
