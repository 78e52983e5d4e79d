//! The standard 3D benchmark scenes of `shared/bench/WORKLOADS.md` (M1 Suzanne, M2 the Stanford
//! bunny's res3 decimation, M3 the full Stanford bunny): the meshes, the camera and the lighting.
//!
//! The instruction-counting example (`examples/count3d.rs`) and the criterion bench
//! (`benches/scenes3d.rs`) both take their scene from here, and so does the comparison renderer
//! (euc, in `benches/support/euc3d.rs`), which reads the same constants and converts the same
//! loaded mesh to `f32`.
//!
//! The scene: model rotated [`ROTATION_Y_DEGREES`] about Y; camera at [`EYE`] looking at the
//! origin, up +Y; [`FOV_Y_DEGREES`] vertical field of view, aspect 4:3 (320 x 240), near plane
//! [`NEAR`], far plane [`FAR`]. Lighting (WORKLOADS.md fixes only the light; the rest is the one of
//! the reference render of M1): one white directional light from [`LIGHT_DIRECTION`], white ambient
//! light, material ambient [`AMBIENT`], diffuse [`DIFFUSE`], specular white, shininess
//! [`SHININESS`], Blinn-Phong, the eye at [`EYE`] in world space.
//!
//! M1 is Suzanne as stored (already centred; it is not rescaled). M2 and M3 are centred on their
//! bounding box and scaled to fit the unit sphere ([`LoadedMesh::normalize_to_unit_sphere`]). M2
//! keeps the file's normals (not unit length, one of them zero: the lighting normalises them, and a
//! zero normal gets the ambient term only); M3's file has none, so it gets smooth area-weighted
//! vertex normals ([`LoadedMesh::compute_smooth_normals`]).

use crate::obj::{LoadError, LoadedMesh};
use crate::scenes::{HEIGHT, WIDTH};
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use rasterizer_core::math::{Angle, Fx16, Mat4, Vec3};
use rasterizer_core::shade::{Light, Lighting, Material, Specular};
use rasterizer_core::transform::Transforms;
use std::path::PathBuf;

/// The model's rotation about Y, in degrees.
pub const ROTATION_Y_DEGREES: i32 = 30;
/// Where the camera (and the eye of the specular term) is, in world space; it looks at the origin.
pub const EYE: [i32; 3] = [0, 0, 3];
/// The vertical field of view, in degrees.
pub const FOV_Y_DEGREES: i32 = 60;
/// The near clip plane, as a ratio (0.1).
pub const NEAR: (i64, i64) = (1, 10);
/// The far clip plane (100).
pub const FAR: i32 = 100;
/// The direction towards the one directional light (white), not normalised.
pub const LIGHT_DIRECTION: [i32; 3] = [1, 1, 1];
/// The material's ambient colour (the ambient light is white).
pub const AMBIENT: Rgb888 = Rgb888::new(40, 30, 30);
/// The material's diffuse colour, also the colour `Unlit` draws.
pub const DIFFUSE: Rgb888 = Rgb888::new(220, 140, 80);
/// The material's specular colour.
pub const SPECULAR: Rgb888 = Rgb888::WHITE;
/// The Blinn-Phong exponent.
pub const SHININESS: u16 = 16;

/// One of the three mesh scenes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scene {
    /// Suzanne, 968 triangles, the file's normals.
    M1,
    /// The Stanford bunny, res3 decimation, 3,851 triangles, the file's normals.
    M2,
    /// The full Stanford bunny, 69,451 triangles, smooth normals computed on loading.
    M3,
}

impl Scene {
    /// Every scene, in order.
    pub const ALL: [Scene; 3] = [Scene::M1, Scene::M2, Scene::M3];

    /// `"M1"`, `"M2"` or `"M3"`.
    pub fn name(self) -> &'static str {
        match self {
            Scene::M1 => "M1",
            Scene::M2 => "M2",
            Scene::M3 => "M3",
        }
    }

    /// The scene of a name, `M1`, `M2` or `M3` (either case).
    pub fn parse(name: &str) -> Option<Scene> {
        Scene::ALL
            .into_iter()
            .find(|s| s.name().eq_ignore_ascii_case(name))
    }

    /// The model's file name in `assets/models/`.
    pub fn file(self) -> &'static str {
        match self {
            Scene::M1 => "suzanne.obj",
            Scene::M2 => "stanford-bunny-res3.obj",
            Scene::M3 => "stanford-bunny.obj",
        }
    }

    /// The model's path: the repository's `assets/models/` first, then the shared collection next
    /// to the repository.
    pub fn path(self) -> PathBuf {
        let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
        let local = manifest.join("../assets/models").join(self.file());
        if local.exists() {
            local
        } else {
            manifest
                .join("../../shared/assets/models")
                .join(self.file())
        }
    }

    /// Loads the scene's mesh, normalised and with normals as described in the
    /// [module documentation](self).
    ///
    /// # Errors
    /// [`LoadError`] when the file cannot be loaded.
    pub fn load(self) -> Result<LoadedMesh, LoadError> {
        let mut mesh = LoadedMesh::load(&self.path())?;
        if self != Scene::M1 {
            mesh.normalize_to_unit_sphere();
        }
        if mesh.normals.is_none() {
            mesh.compute_smooth_normals();
        }
        Ok(mesh)
    }
}

/// The material of every scene.
pub fn material() -> Material {
    Material {
        ambient: AMBIENT,
        diffuse: DIFFUSE,
        specular: SPECULAR,
        shininess: SHININESS,
    }
}

/// The lighting of every scene: [`material`], white ambient light, Blinn-Phong seen from [`EYE`],
/// one white directional light from [`LIGHT_DIRECTION`].
pub fn lighting() -> Lighting<Fx16, 1> {
    let [ex, ey, ez] = EYE;
    let mut l = Lighting::new(
        material(),
        Rgb888::WHITE,
        Specular::BlinnPhong,
        Vec3::from_ints(ex, ey, ez),
    );
    let [lx, ly, lz] = LIGHT_DIRECTION;
    l.add_light(Light::Directional {
        direction: Vec3::from_ints(lx, ly, lz),
        color: Rgb888::WHITE,
    })
    .expect("one light fits");
    l
}

/// The model, view and projection matrices of every scene, in 16.16.
pub fn transforms() -> Transforms<Fx16> {
    camera(
        Mat4::rotation_y(Angle::from_degrees(ROTATION_Y_DEGREES)),
        WIDTH,
        HEIGHT,
    )
}

/// The scenes' camera (eye, field of view, near and far planes) for a `width` x `height` frame,
/// with `model` as the model matrix.
pub fn camera(model: Mat4<Fx16>, width: u32, height: u32) -> Transforms<Fx16> {
    let [ex, ey, ez] = EYE;
    Transforms {
        model,
        view: Mat4::look_at(
            Vec3::from_ints(ex, ey, ez),
            Vec3::from_ints(0, 0, 0),
            Vec3::from_ints(0, 1, 0),
        )
        .expect("camera basis"),
        projection: Mat4::perspective(
            Angle::from_degrees(FOV_Y_DEGREES),
            Fx16::from_ratio(width.into(), height.into()),
            Fx16::from_ratio(NEAR.0, NEAR.1),
            Fx16::from_int(FAR),
        )
        .expect("projection"),
    }
}
