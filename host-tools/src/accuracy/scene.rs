//! The scenes the sweep measures, described once in `f64` and built from that description both
//! into the `f64` reference (matrices, lit vertex colours, the reference render) and into any
//! pipeline format, so both sides start from the same parameters.

use fixtures::obj::LoadedMesh;
use fixtures::reference3d::{self as r, RefCull, RefLight, RefRender, M4, V3};
use fixtures::scenes::XorShift32;
use fixtures::scenes3d::{
    material, EYE, FAR, FOV_Y_DEGREES, LIGHT_DIRECTION, NEAR, ROTATION_Y_DEGREES,
};
use rasterizer_core::math::Scalar;
use rasterizer_core::prelude::*;
use std::path::{Path, PathBuf};

/// The camera and model placement of a scene, every angle in the pipeline's angle unit so that
/// both sides see the same angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Uniform model scale (the scene-scale sweep multiplies it, the eye and the planes by 2^k).
    pub scale: f64,
    /// Model rotation about y.
    pub yaw: Angle,
    /// Eye position.
    pub eye: V3,
    /// Point looked at.
    pub target: V3,
    /// Vertical field of view.
    pub fov: Angle,
    /// Near plane distance.
    pub near: f64,
    /// Far plane distance.
    pub far: f64,
}

impl Camera {
    /// The M1-M3 camera of WORKLOADS.md: model turned 30° about y, eye at (0, 0, 3) looking at the
    /// origin, 60° vertical field of view, near 0.1, far 100.
    pub fn workload() -> Self {
        Self {
            scale: 1.0,
            yaw: Angle::from_degrees(ROTATION_Y_DEGREES),
            eye: EYE.map(f64::from),
            target: [0.0; 3],
            fov: Angle::from_degrees(FOV_Y_DEGREES),
            near: NEAR.0 as f64 / NEAR.1 as f64,
            far: f64::from(FAR),
        }
    }

    /// The same picture with the whole scene (model, eye, target, planes) scaled by `s`.
    pub fn scaled(&self, s: f64) -> Self {
        Self {
            scale: self.scale * s,
            eye: self.eye.map(|v| v * s),
            target: self.target.map(|v| v * s),
            near: self.near * s,
            far: self.far * s,
            ..*self
        }
    }
}

/// A scene: a mesh in model space, its placement, the screen, and whether back faces are culled.
#[derive(Debug, Clone)]
pub struct SceneDef {
    /// Name in the report.
    pub name: String,
    /// Positions in model space.
    pub positions: Vec<V3>,
    /// Normals in model space, one per position.
    pub normals: Vec<V3>,
    /// Triangles.
    pub tris: Vec<[u32; 3]>,
    /// Placement.
    pub camera: Camera,
    /// Screen width in pixels.
    pub width: u32,
    /// Screen height in pixels.
    pub height: u32,
    /// Back faces culled (`CullClockwise`); otherwise every triangle is drawn.
    pub cull: bool,
}

/// The `f64` model, view and projection matrices of a camera on a `width` x `height` screen.
pub fn reference_mvp(cam: &Camera, width: u32, height: u32) -> (M4, M4) {
    let rad = |a: Angle| r::turn_units_to_radians(f64::from(a.0));
    let model = r::mul(
        &r::rotation_y(rad(cam.yaw)),
        &r::scale(cam.scale, cam.scale, cam.scale),
    );
    let view = r::look_at(cam.eye, cam.target, [0.0, 1.0, 0.0]);
    let proj = r::perspective(
        rad(cam.fov),
        f64::from(width) / f64::from(height),
        cam.near,
        cam.far,
    );
    (model, r::mul(&proj, &r::mul(&view, &model)))
}

/// `v` in format `S`: rounded to the format's grid (saturating where it is bounded).
pub fn to_s<S: Scalar>(v: f64) -> S {
    const ONE: f64 = (1u64 << 30) as f64;
    // `as` saturates: a value beyond 2^33 saturates the numerator, far outside every fixed-point
    // range; f32 sees such values only in the scene-scale sweep, which stops long before.
    S::from_ratio((v * ONE).round() as i64, 1 << 30)
}

/// A point in format `S`.
pub fn vec_s<S: Scalar>(v: V3) -> Vec3<S> {
    Vec3::new(to_s(v[0]), to_s(v[1]), to_s(v[2]))
}

/// The pipeline's transforms for a camera in format `S` with an `N`-entry trigonometry table;
/// `None` when the format cannot build them (a plane or the camera basis not representable).
pub fn transforms<S: Scalar, const N: usize>(
    cam: &Camera,
    width: u32,
    height: u32,
) -> Option<Transforms<S>> {
    let s: S = to_s(cam.scale);
    let mut model = Mat4::rotation_y_with::<N>(cam.yaw);
    if cam.scale != 1.0 {
        model = Mat4::scale(s, s, s).then(&model);
    }
    let view = Mat4::look_at(
        vec_s(cam.eye),
        vec_s(cam.target),
        Vec3::new(S::ZERO, S::ONE, S::ZERO),
    )?;
    let projection = Mat4::perspective_with::<N>(
        cam.fov,
        S::from_ratio(width.into(), height.into()),
        to_s(cam.near),
        to_s(cam.far),
    )?;
    Some(Transforms {
        model,
        view,
        projection,
    })
}

/// The one light: directional, white, from M1's [`LIGHT_DIRECTION`].
pub const LIGHT_FROM: V3 = [
    LIGHT_DIRECTION[0] as f64,
    LIGHT_DIRECTION[1] as f64,
    LIGHT_DIRECTION[2] as f64,
];

/// The pipeline's lighting for a camera in format `S`.
pub fn lighting<S: Scalar>(cam: &Camera) -> Lighting<S, 1> {
    let mut l = Lighting::new(
        material(),
        Rgb888::WHITE,
        Specular::BlinnPhong,
        vec_s(cam.eye),
    );
    // A unit direction never fails to normalise, and one light fits one slot.
    let _ = l.add_light(Light::Directional {
        direction: vec_s(LIGHT_FROM),
        color: Rgb888::WHITE,
    });
    l
}

/// What the `f64` side knows of a scene: matrices, the reference render, the true Gouraud image
/// and each vertex's exact screen position.
#[derive(Debug, Clone)]
pub struct Prepared {
    /// The scene.
    pub def: SceneDef,
    /// The `f64` model-view-projection matrix.
    pub mvp: M4,
    /// The reference render (triangle ids and depths per pixel); `None` for projection-only runs.
    pub render: Option<RefRender>,
    /// The true colour per pixel (unrounded, 0..255 per channel).
    pub colors: Vec<Option<V3>>,
    /// Each vertex's exact screen position in pixels, `None` when it is outside the view volume.
    pub screen: Vec<Option<[f64; 2]>>,
}

impl Prepared {
    /// Runs the reference on a scene; with `raster` false only the vertex positions.
    pub fn new(def: SceneDef, raster: bool) -> Self {
        let (model, mvp) = reference_mvp(&def.camera, def.width, def.height);
        let screen = def
            .positions
            .iter()
            .map(|&p| {
                let c = r::apply_point(&mvp, p);
                let inside = c[3] > 0.0 && (0..3).all(|k| c[k].abs() <= c[3]);
                inside.then(|| {
                    let s = r::to_screen(c, def.width, def.height);
                    [s[0], s[1]]
                })
            })
            .collect();
        let (render, colors) = if raster {
            let tris: Vec<[usize; 3]> = def.tris.iter().map(|t| t.map(|i| i as usize)).collect();
            let cull = if def.cull {
                RefCull::Clockwise
            } else {
                RefCull::None
            };
            let render = r::render(
                &mvp,
                &def.positions,
                &tris,
                None,
                def.width,
                def.height,
                cull,
            );
            let lit = vertex_colors(&def, &model);
            let colors = r::shade_image(&mvp, &def.positions, &tris, &lit, &render);
            (Some(render), colors)
        } else {
            (None, Vec::new())
        };
        Self {
            def,
            mvp,
            render,
            colors,
            screen,
        }
    }
}

/// Every vertex lit in `f64` (world position and normal through the model matrix).
fn vertex_colors(def: &SceneDef, model: &M4) -> Vec<V3> {
    let lights: [RefLight; 1] = [(false, LIGHT_FROM, Rgb888::WHITE)];
    def.positions
        .iter()
        .zip(&def.normals)
        .map(|(&p, &n)| {
            let w = r::apply_point(model, p);
            let nw = r::apply(model, [n[0], n[1], n[2], 0.0]);
            r::lit(
                &material(),
                Rgb888::WHITE,
                Specular::BlinnPhong,
                def.camera.eye,
                &lights,
                [w[0], w[1], w[2]],
                [nw[0], nw[1], nw[2]],
            )
        })
        .collect()
}

fn fx_f64(v: Fx16) -> f64 {
    f64::from(v.to_bits()) / 65536.0
}

/// Where the models are: the repository's assets, then the shared ones next to the repository
/// (the full Stanford bunny of M3 is only there).
pub fn find_model(dirs: &[PathBuf], name: &str) -> Option<PathBuf> {
    dirs.iter().map(|d| d.join(name)).find(|p| p.exists())
}

/// The default model directories.
pub fn default_model_dirs() -> Vec<PathBuf> {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    vec![
        manifest.join("../assets/models"),
        manifest.join("../../shared/assets/models"),
    ]
}

/// A workload mesh scene: `file` loaded in 16.16 as the benchmarks do (the bunnies centred and
/// scaled to the unit sphere, smooth normals where the file has none), placed with the workload
/// camera on a 320 x 240 screen with back faces culled.
pub fn workload_scene(name: &str, path: &Path, unit_sphere: bool) -> Result<SceneDef, String> {
    let mut m = LoadedMesh::load(path).map_err(|e| format!("{}: {e}", path.display()))?;
    if unit_sphere {
        m.normalize_to_unit_sphere();
    }
    if m.normals.is_none() {
        m.compute_smooth_normals();
    }
    let normals = m.normals.clone().unwrap_or_default();
    let v3 = |v: &Vec3<Fx16>| [fx_f64(v.x), fx_f64(v.y), fx_f64(v.z)];
    Ok(SceneDef {
        name: name.to_string(),
        positions: m.positions.iter().map(v3).collect(),
        normals: normals.iter().map(v3).collect(),
        tris: m.triangles,
        camera: Camera::workload(),
        width: 320,
        height: 240,
        cull: true,
    })
}

/// A uniform value in `[lo, hi)` from the generator.
fn uniform(rng: &mut XorShift32, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * f64::from(rng.next_u32()) / 4_294_967_296.0
}

/// A random scene (WORKLOADS.md's xorshift32): `count` triangles scattered through the view volume
/// of a camera at the origin looking down -z (60° field of view, near 0.1, far 100), nothing
/// culled. Centres lie at depths from 0.05 to 20 (one in eight within 0.3 of the eye, so that
/// some cross the near plane or lie wholly before it), each corner up to half the depth away from
/// its centre in x, y and z, so that neighbours cut through each other. Normals are random and
/// turned towards the eye. `skip` draws that many values first, for several different scenes.
pub fn random_scene(name: &str, count: usize, skip: u32, width: u32, height: u32) -> SceneDef {
    let mut rng = XorShift32::new();
    for _ in 0..skip {
        rng.next_u32();
    }
    let aspect = f64::from(width) / f64::from(height);
    let half = (30f64).to_radians().tan();
    let (mut positions, mut normals, mut tris) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..count {
        let near = rng.next_u32().is_multiple_of(8);
        let d = if near {
            uniform(&mut rng, 0.05, 0.3)
        } else {
            uniform(&mut rng, 0.3, 20.0)
        };
        let cx = uniform(&mut rng, -1.0, 1.0) * d * half * aspect;
        let cy = uniform(&mut rng, -1.0, 1.0) * d * half;
        let size = d * uniform(&mut rng, 0.05, 0.5);
        let base = positions.len() as u32;
        for _ in 0..3 {
            positions.push([
                cx + uniform(&mut rng, -size, size),
                cy + uniform(&mut rng, -size, size),
                -d + uniform(&mut rng, -size, size),
            ]);
            let n = [
                uniform(&mut rng, -1.0, 1.0),
                uniform(&mut rng, -1.0, 1.0),
                uniform(&mut rng, 0.2, 1.0),
            ];
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            normals.push(n.map(|v| v / l));
        }
        tris.push([base, base + 1, base + 2]);
    }
    // Quantise to the 16.16 grid, like the workload meshes: the scenes are then exact in 16.16
    // and the reference renders what 16.16 firmware would be given.
    let q = |v: V3| v.map(|x| (x * 65536.0).round() / 65536.0);
    SceneDef {
        name: name.to_string(),
        positions: positions.into_iter().map(q).collect(),
        normals: normals.into_iter().map(q).collect(),
        tris,
        camera: Camera {
            scale: 1.0,
            yaw: Angle(0),
            eye: [0.0; 3],
            target: [0.0, 0.0, -1.0],
            fov: Angle::from_degrees(60),
            near: 0.1,
            far: 100.0,
        },
        width,
        height,
        cull: false,
    }
}
