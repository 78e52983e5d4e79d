//! Reading a scene file: parsing, checking every value, loading the meshes.

use super::format::{
    default_density, Camera, Color, CullMode, DitherMode, FogDef, FogMode, LightDef, MeshDef,
    NormalsMode, PixelFormat, RenderOptions, ScaleDef, SceneFile, ShadingModel, Shape,
    SpecularModel, TextureFilterDef, TextureWrapDef, VertexColorMode,
};
use super::limits;
use super::reference::Real;
use super::{MAX_LIGHTS, MAX_POLYGON};
use fixtures::obj::{LoadError, RawMesh};
use fixtures::texture_file::{TextureFileError, TextureImage, MAX_SIDE};
use fixtures::vec64::{cross, norm, sub as sub3};
use rasterizer_core::mesh::{MAGIC, NO_NEIGHBOUR};
use rasterizer_core::prelude::*;
use rasterizer_core::raster::line::MAX_LINE_WIDTH;
use rasterizer_core::shade::{FogCurve, FOG_MAX_DENSITY};
use rasterizer_core::texture::{Filter, Wrap};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A scene, checked and with its meshes loaded.
#[derive(Debug)]
pub struct Scene {
    /// The file it came from.
    pub path: PathBuf,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The display's pixel format.
    pub format: PixelFormat,
    /// Background colour.
    pub background: Rgb888,
    /// Default PNG scale.
    pub scale: u32,
    /// The camera.
    pub camera: Camera,
    /// Ambient light colour.
    pub ambient: Rgb888,
    /// The specular model.
    pub specular: Specular,
    /// The lights.
    pub lights: Vec<LightDef>,
    /// The meshes.
    pub meshes: Vec<SceneMesh>,
    /// The 2D shapes.
    pub shapes: Vec<Shape>,
}

impl Scene {
    /// The files the scene reads: the scene file, its meshes and their textures (an output must
    /// be none of them).
    pub fn inputs(&self) -> Vec<&Path> {
        std::iter::once(self.path.as_path())
            .chain(self.meshes.iter().map(|m| m.file.as_path()))
            .chain(
                self.meshes
                    .iter()
                    .filter_map(|m| m.texture.as_ref()?.file.as_deref()),
            )
            .chain(
                self.meshes
                    .iter()
                    .filter_map(|m| m.matcap.as_ref()?.file.as_deref()),
            )
            .chain(self.shapes.iter().filter_map(|s| match s {
                Shape::Sprite { file, .. } => Some(file.as_path()),
                _ => None,
            }))
            .collect()
    }
}

/// A mesh with its transform and stages.
#[derive(Debug)]
pub struct SceneMesh {
    /// The path as the scene file wrote it.
    pub name: String,
    /// The file read (relative to the scene file's directory).
    pub file: PathBuf,
    /// The vertex data.
    pub data: MeshData,
    /// Per-axis scale.
    pub scale: [f64; 3],
    /// Rotations about x, y, z in degrees.
    pub rotate: [f64; 3],
    /// Translation.
    pub translate: [f64; 3],
    /// Unlit and wireframe colour.
    pub color: Rgb888,
    /// Lit material.
    pub material: Material,
    /// Edges only.
    pub wireframe: bool,
    /// Shading model.
    pub shading: ShadingModel,
    /// Depth test.
    pub depth: bool,
    /// Culling.
    pub cull: CullMode,
    /// Perspective-correct interpolation.
    pub perspective_correct: bool,
    /// Ordered dithering.
    pub dither: DitherMode,
    /// The texture, for a mesh with texture coordinates.
    pub texture: Option<SceneTexture>,
    /// The MatCap image, for `shading = "matcap"`.
    pub matcap: Option<SceneMatCap>,
    /// Opacity: below 255, blended through `Translucent` with a read-only depth test.
    pub opacity: u8,
    /// Fog, when the mesh or `[render]` asks for it.
    pub fog: Option<SceneFog>,
    /// Anti-aliased silhouettes; the mesh then carries edge adjacency.
    pub antialias: bool,
}

/// A mesh's texture, loaded and converted to Rgb565.
#[derive(Debug, Clone)]
pub struct SceneTexture {
    /// The PNG it was read from (`None`: the packed mesh's own texture).
    pub file: Option<PathBuf>,
    /// The texels.
    pub image: TextureImage,
    /// How texels are picked.
    pub filter: Filter,
    /// How coordinates outside `0 ..= 1` address the texture.
    pub wrap: Wrap,
}

/// A mesh's MatCap image, square, converted to Rgb565.
#[derive(Debug, Clone)]
pub struct SceneMatCap {
    /// The PNG it was read from (`None`: the built-in glossy sphere).
    pub file: Option<PathBuf>,
    /// The texels.
    pub image: TextureImage,
}

/// A checked `fog` table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneFog {
    /// The fog's colour.
    pub color: Rgb888,
    /// Where it starts, in world units in front of the camera.
    pub start: f64,
    /// Where it ends.
    pub end: f64,
    /// Its curve.
    pub curve: FogCurve,
}

/// Checks a `fog` table: `start` and `end` within 16.16's comfortable range, the density within
/// what the exponential table covers and given only where it applies.
fn scene_fog(f: &FogDef) -> Result<SceneFog, String> {
    limits::within("fog.start", &[f.start], limits::MAX_COORD)?;
    limits::within("fog.end", &[f.end], limits::MAX_COORD)?;
    if f.mode == FogMode::Linear && f.density.is_some() {
        return Err(
            "fog.density applies only with mode = \"exponential\" (linear fog has no density); \
             remove it or add mode = \"exponential\""
                .into(),
        );
    }
    let density = f.density.unwrap_or_else(default_density);
    let max = f64::from(FOG_MAX_DENSITY) / 16.0;
    if !(0.0..=max).contains(&density) {
        return Err(format!(
            "fog.density = {} is out of range: 0 ..= {}",
            limits::num(density),
            limits::num(max)
        ));
    }
    Ok(SceneFog {
        color: rgb(f.color),
        start: f.start,
        end: f.end,
        curve: match f.mode {
            FogMode::Linear => FogCurve::Linear,
            // In sixteenths, as the core takes it.
            FogMode::Exponential => FogCurve::exponential((density * 16.0).round() as u16),
        },
    })
}

/// Vertex data: a packed blob drawn in place, or a mesh in memory.
#[derive(Debug)]
pub enum MeshData {
    /// A valid packed mesh (checked when loaded), drawn straight through `PackedMesh`.
    Packed(Vec<u8>),
    /// Positions, normals and colours in `f64`, converted to the scalar of each render.
    Owned(OwnedMesh),
}

impl MeshData {
    /// True when the mesh carries edge adjacency (`MeshSource::neighbours`).
    pub fn has_adjacency(&self) -> bool {
        match self {
            Self::Packed(bytes) => PackedMesh::parse(bytes).is_ok_and(|p| p.has_adjacency()),
            Self::Owned(o) => o.adjacency.is_some(),
        }
    }

    /// The same mesh with edge adjacency: a packed mesh that carries it stays packed (drawn in
    /// place, its own table read from the blob); one without it is unpacked, since the table has
    /// to live somewhere; an owned mesh gets [`OwnedMesh::with_adjacency`].
    pub fn with_adjacency(self) -> Self {
        match self {
            Self::Packed(bytes) => match PackedMesh::parse(&bytes) {
                Ok(p) if !p.has_adjacency() => Self::Owned(unpack(&p).with_adjacency()),
                // Loading checked the blob, so an error here is not expected; keep it as it was.
                _ => Self::Packed(bytes),
            },
            Self::Owned(o) => Self::Owned(o.with_adjacency()),
        }
    }
}

/// A mesh in host memory.
#[derive(Debug, Clone, Default)]
pub struct OwnedMesh {
    /// Positions.
    pub positions: Vec<[f64; 3]>,
    /// One normal per position, if any.
    pub normals: Option<Vec<[f64; 3]>>,
    /// One colour per position, if any.
    pub colors: Option<Vec<Rgb888>>,
    /// One pair of texture coordinates per position (16.16 bits), if any.
    pub uvs: Option<Vec<[i32; 2]>>,
    /// Triangles.
    pub triangles: Vec<[u32; 3]>,
    /// Edge adjacency, one entry per triangle (`MeshSource::neighbours`), if any: a packed
    /// mesh's own, or computed by [`OwnedMesh::with_adjacency`]. Whoever changes `triangles`
    /// afterwards must drop or recompute it.
    pub adjacency: Option<Vec<[u32; 3]>>,
}

impl OwnedMesh {
    /// The mesh with edge adjacency: the one it carries, else computed by
    /// `fixtures::adjacency::adjacency_by_position` over its positions rounded to 16.16 (what
    /// the fixed-point renders draw), so that vertices split at a seam of texture coordinates or
    /// normals still join their triangles, as they do for smooth normals.
    pub fn with_adjacency(mut self) -> Self {
        if self.adjacency.is_none() {
            let keys: Vec<[i64; 3]> = self.positions.iter().map(position_key).collect();
            self.adjacency = Some(fixtures::adjacency::adjacency_by_position(
                &self.triangles,
                &keys,
            ));
        }
        self
    }
}

/// A position rounded to 16.16 bits: vertices with equal keys are one point of the surface.
fn position_key(p: &[f64; 3]) -> [i64; 3] {
    p.map(|v| (v * 65536.0).round() as i64)
}

/// The 1-based line of a byte offset.
fn line_of(src: &str, offset: usize) -> usize {
    src.as_bytes()[..offset.min(src.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

fn rgb(c: Color) -> Rgb888 {
    Rgb888::new(c.0[0], c.0[1], c.0[2])
}

fn finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// Reads and checks a scene file and loads its meshes; the OBJ reader's warnings are dropped
/// (see [`load_with_warnings`]).
///
/// # Errors
/// A message starting with the file's path: TOML errors carry the parser's line and column,
/// other problems the line of the table they are in.
pub fn load(path: &Path) -> Result<Scene, String> {
    load_with_warnings(path, &mut Vec::new())
}

/// [`load`], pushing the OBJ reader's warnings (`file:line: message`, odd but usable input such
/// as CR line endings or a missing `.mtl`) onto `warnings`, also when the scene is then refused.
///
/// # Errors
/// As [`load`].
pub fn load_with_warnings(path: &Path, warnings: &mut Vec<String>) -> Result<Scene, String> {
    let shown = path.display();
    let src =
        std::fs::read_to_string(path).map_err(|e| format!("{shown}: cannot read scene: {e}"))?;
    let file: SceneFile =
        toml::from_str(&src).map_err(|e| format!("{shown}: {}", e.to_string().trim_end()))?;
    let at = |span: std::ops::Range<usize>| format!("{shown}: line {}", line_of(&src, span.start));

    let out = &file.output;
    if !(1..=4096).contains(&out.width) || !(1..=4096).contains(&out.height) {
        return Err(format!(
            "{shown}: [output] width and height must be 1 ..= 4096, got {} x {}",
            out.width, out.height
        ));
    }
    if !(1..=16).contains(&out.scale) {
        return Err(format!(
            "{shown}: [output] scale must be 1 ..= 16, got {}",
            out.scale
        ));
    }
    limits::check_camera(&file.camera)
        .and_then(|()| camera_in_fixed_point(&file.camera, out.width, out.height))
        .map_err(|e| format!("{shown}: [camera] {e}"))?;

    if file.lights.len() > MAX_LIGHTS {
        return Err(format!(
            "{shown}: {} lights, at most {MAX_LIGHTS} are supported",
            file.lights.len()
        ));
    }
    let mut lights = Vec::new();
    for l in file.lights {
        let span = l.span();
        let light = l.into_inner();
        let checked = match &light {
            LightDef::Directional { direction, .. } => {
                limits::within("direction", direction, limits::MAX_COORD).and_then(|()| {
                    if norm(*direction) >= limits::MIN_LENGTH {
                        Ok(())
                    } else {
                        Err(format!(
                            "direction = {} is too short: its length must be at least {}",
                            limits::vector(direction),
                            limits::num(limits::MIN_LENGTH)
                        ))
                    }
                })
            }
            LightDef::Point { position, .. } => {
                limits::within("position", position, limits::MAX_COORD)
            }
        };
        checked.map_err(|e| format!("{}: [[lights]] {e}", at(span)))?;
        lights.push(light);
    }

    // Checked once here, so that its errors name [render] rather than the first mesh taking it.
    if let Some(fog) = &file.render.fog {
        scene_fog(fog).map_err(|e| format!("{shown}: [render] {e}"))?;
    }
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut meshes = Vec::new();
    for m in file.meshes {
        let span = m.span();
        let def = m.into_inner();
        let name = def.path.clone();
        let mesh = load_mesh(dir, def, &file.render, warnings)
            .and_then(|m| {
                let positions = match &m.data {
                    MeshData::Owned(o) => o.positions.clone(),
                    MeshData::Packed(bytes) => PackedMesh::parse(bytes)
                        .map(|p| unpack(&p).positions)
                        .unwrap_or_default(),
                };
                limits::check_mesh(
                    &positions,
                    m.scale,
                    m.translate,
                    &file.camera,
                    out.width,
                    out.height,
                )
                .map_err(|e| format!("mesh {name}: {e}"))?;
                Ok(m)
            })
            .map_err(|e| format!("{}: [[meshes]] {e}", at(span)))?;
        meshes.push(mesh);
    }

    let mut shapes = Vec::new();
    for s in file.shapes {
        let span = s.span();
        let mut shape = s.into_inner();
        super::sprite::load(dir, &mut shape)
            .and_then(|()| check_shape(&shape))
            .map_err(|e| format!("{}: [[shapes]] {e}", at(span)))?;
        shapes.push(shape);
    }

    Ok(Scene {
        path: path.to_path_buf(),
        width: out.width,
        height: out.height,
        format: out.format,
        background: rgb(out.background),
        scale: out.scale,
        camera: file.camera,
        ambient: rgb(file.render.ambient),
        specular: match file.render.specular {
            SpecularModel::None => Specular::None,
            SpecularModel::Phong => Specular::Phong,
            SpecularModel::BlinnPhong => Specular::BlinnPhong,
        },
        lights,
        meshes,
        shapes,
    })
}

/// The camera's matrices built in 16.16, as the renderer will: `Mat4::look_at` and
/// `Mat4::perspective` refuse what that format cannot represent.
fn camera_in_fixed_point(c: &Camera, width: u32, height: u32) -> Result<(), String> {
    use rasterizer_core::math::{Angle, Mat4, Vec3};
    let v = |a: [f64; 3]| {
        Vec3::new(
            Fx16::from_f64(a[0]),
            Fx16::from_f64(a[1]),
            Fx16::from_f64(a[2]),
        )
    };
    Mat4::look_at(v(c.eye), v(c.target), v(c.up)).ok_or_else(|| {
        format!(
            "eye = {}, target = {}, up = {}: 16.16 cannot form a view direction and a right angle \
             from them",
            limits::vector(&c.eye),
            limits::vector(&c.target),
            limits::vector(&c.up)
        )
    })?;
    Mat4::perspective(
        Angle::from_degrees_ratio((c.fov * 3600.0).round() as i64, 3600),
        Fx16::from_ratio(i64::from(width), i64::from(height)),
        Fx16::from_f64(c.near),
        Fx16::from_f64(c.far),
    )
    .ok_or_else(|| {
        format!(
            "fov = {}, near = {}, far = {}: 16.16 cannot form the projection from them",
            limits::num(c.fov),
            limits::num(c.near),
            limits::num(c.far)
        )
    })?;
    Ok(())
}

fn check_shape(shape: &Shape) -> Result<(), String> {
    let (pts, clip): (Vec<[f64; 2]>, _) = match shape {
        Shape::Point { at, clip, .. } => (vec![*at], clip),
        Shape::Line {
            from,
            to,
            color,
            colors,
            antialias,
            width,
            clip,
            ..
        } => {
            if color.is_some() == colors.is_some() {
                return Err("a line needs exactly one of `color` and `colors`".into());
            }
            if *antialias && colors.is_some() {
                return Err("an anti-aliased line takes one `color`, not `colors`".into());
            }
            if !*antialias && width.is_some_and(|w| w != 1) {
                return Err("`width` above 1 needs `antialias = true`".into());
            }
            if width.is_some_and(|w| w == 0 || w > MAX_LINE_WIDTH) {
                return Err(format!("a line's `width` is 1 ..= {MAX_LINE_WIDTH}"));
            }
            (vec![*from, *to], clip)
        }
        Shape::Triangle {
            vertices,
            color,
            colors,
            clip,
            ..
        } => {
            if color.is_some() == colors.is_some() {
                return Err("a triangle needs exactly one of `color` and `colors`".into());
            }
            (vertices.to_vec(), clip)
        }
        Shape::Outline { vertices, clip, .. } => (vertices.to_vec(), clip),
        Shape::Sprite { at, clip, .. } => {
            super::sprite::transform(shape).map_err(|e| format!("sprite: {e}"))?;
            (vec![*at], clip)
        }
        Shape::Polygon { vertices, clip, .. } => {
            if vertices.len() < 3 || vertices.len() > MAX_POLYGON {
                return Err(format!(
                    "a polygon needs 3 ..= {MAX_POLYGON} vertices, got {}",
                    vertices.len()
                ));
            }
            (vertices.clone(), clip)
        }
    };
    let kind = match shape {
        Shape::Point { .. } => "point",
        Shape::Line { .. } => "line",
        Shape::Triangle { .. } => "triangle",
        Shape::Outline { .. } => "outline",
        Shape::Polygon { .. } => "polygon",
        Shape::Sprite { .. } => "sprite",
    };
    let filled = matches!(shape, Shape::Triangle { .. } | Shape::Polygon { .. });
    limits::check_pixels(&pts, filled).map_err(|e| format!("{kind}: {e}"))?;
    if let Some([_, _, w, h]) = clip {
        if *w < 0 || *h < 0 {
            return Err("clip = [x, y, width, height] needs width, height >= 0".into());
        }
    }
    Ok(())
}

fn load_mesh(
    dir: &Path,
    def: MeshDef,
    render: &super::format::RenderOptions,
    warnings: &mut Vec<String>,
) -> Result<SceneMesh, String> {
    let file = dir.join(&def.path);
    let name = def.path.clone();
    let bytes = std::fs::read(&file)
        .map_err(|e| format!("cannot read mesh file {}: {e}", file.display()))?;
    let scale = match def.scale {
        ScaleDef::Uniform(s) => [s; 3],
        ScaleDef::Axes(a) => a,
    };
    if !finite(&def.rotate) {
        return Err(format!(
            "mesh {name}: rotate = {} must be finite",
            limits::vector(&def.rotate)
        ));
    }
    let needs_edit = def.fit_unit_sphere
        || matches!(def.normals, NormalsMode::Smooth | NormalsMode::Face)
        || def.vertex_colors != VertexColorMode::File;
    // A packed mesh's own texture, kept whether the mesh is drawn in place or edited.
    let own_texture = PackedMesh::parse(&bytes)
        .ok()
        .and_then(|p| p.texture())
        .map(|t| TextureImage {
            width_log2: t.width_log2(),
            height_log2: t.height_log2(),
            texels: t.bytes().to_vec(),
        });
    let data = if bytes.starts_with(&MAGIC) {
        let packed =
            PackedMesh::parse(&bytes).map_err(|e| format!("mesh {}: {e}", file.display()))?;
        let has_normals = MeshSourceExt::has_normals(&packed);
        if def.normals == NormalsMode::File && !has_normals {
            return Err(format!(
                "mesh {}: normals = \"file\" but it has none",
                file.display()
            ));
        }
        if needs_edit || (def.normals == NormalsMode::Auto && !has_normals) {
            MeshData::Owned(edit(unpack(&packed), &def))
        } else {
            MeshData::Packed(bytes)
        }
    } else {
        let shown = file.display().to_string();
        let mut found = Vec::new();
        let raw = RawMesh::from_bytes(&shown, &bytes, file.parent(), &mut found);
        warnings.extend(found.iter().map(|w| w.display(&shown)));
        let raw = raw.map_err(|e| format!("mesh {shown}: {}", LoadError::Obj(e)))?;
        if def.normals == NormalsMode::File && raw.normals.is_none() {
            return Err(format!(
                "mesh {}: normals = \"file\" but it has none",
                file.display()
            ));
        }
        MeshData::Owned(edit(from_raw(raw), &def))
    };
    // The silhouettes are found through the adjacency: computed here, once, by position (so a
    // seam of texture coordinates or normals is not taken for an edge of the surface).
    let data = if def.antialias {
        data.with_adjacency()
    } else {
        data
    };
    let texture = load_texture(dir, &def, own_texture, &data)?;
    let shading = def.shading.unwrap_or(render.shading);
    if texture.is_some() && shading != ShadingModel::Gouraud {
        return Err(format!(
            "mesh {name}: a texture is drawn with shading = \"gouraud\" (the texel times the \
             light of the vertices), not \"{}\"",
            shading_name(shading)
        ));
    }
    check_stages_apply(&def, render, texture.is_some())?;
    let matcap = load_matcap(dir, &def, shading)?;
    if texture.is_some() && def.opacity.is_some_and(|o| o < u8::MAX) {
        return Err(format!(
            "mesh {name}: opacity below 255 does not apply to a textured mesh; remove it or the \
             texture"
        ));
    }
    // A mesh's table replaces [render]'s as a whole.
    let fog = def
        .fog
        .or(render.fog)
        .map(|f| scene_fog(&f))
        .transpose()
        .map_err(|e| format!("mesh {name}: {e}"))?;
    let c = def.color.0;
    let m = def.material.as_ref();
    let material = Material {
        ambient: m
            .and_then(|m| m.ambient)
            .map_or(Rgb888::new(c[0] / 5, c[1] / 5, c[2] / 5), rgb),
        diffuse: m.and_then(|m| m.diffuse).map_or(rgb(def.color), rgb),
        specular: m
            .and_then(|m| m.specular)
            .map_or(Rgb888::new(255, 255, 255), rgb),
        shininess: m.and_then(|m| m.shininess).unwrap_or(16),
    };
    Ok(SceneMesh {
        name,
        file,
        data,
        scale,
        rotate: def.rotate,
        translate: def.translate,
        color: rgb(def.color),
        material,
        wireframe: def.wireframe.unwrap_or(render.wireframe),
        shading: def.shading.unwrap_or(render.shading),
        depth: def.depth.unwrap_or(render.depth),
        cull: def.cull.unwrap_or(render.cull),
        perspective_correct: def
            .perspective_correct
            .unwrap_or(render.perspective_correct),
        dither: def.dither.unwrap_or(render.dither),
        texture,
        matcap,
        opacity: def.opacity.unwrap_or(u8::MAX),
        fog,
        antialias: def.antialias,
    })
}

/// Refuses a key the mesh's drawing would ignore: fog and dithering where the pipeline it gets
/// has no colour to mix or dither, a material or generated vertex colours its shading does not
/// read, a depth buffer for edges. A key inherited from `[render]` is named as such, since the
/// fix is there.
fn check_stages_apply(def: &MeshDef, render: &RenderOptions, textured: bool) -> Result<(), String> {
    let name = &def.path;
    let wireframe = def.wireframe.unwrap_or(render.wireframe);
    let shading = def.shading.unwrap_or(render.shading);
    let translucent = def.opacity.is_some_and(|o| o < u8::MAX);
    let from = |own: bool| if own { "" } else { " (from [render])" };
    // What a colour-mixing stage cannot work on, or None.
    let no_colour = if wireframe {
        Some("a wireframe mesh (its edges are one unlit colour)".to_string())
    } else if textured {
        Some("a textured mesh".to_string())
    } else if translucent {
        Some("a translucent mesh (opacity below 255)".to_string())
    } else if shading == ShadingModel::None {
        Some("shading = \"none\" (one unlit colour)".to_string())
    } else {
        None
    };
    // `key`, set on the mesh (`own`) or inherited from [render], does not apply to `what`.
    let refuse = |key: &str, own: bool, what: &str, takes: &str| {
        Err(format!(
            "mesh {name}: {key}{} does not apply to {what}; remove it{}",
            from(own),
            if own {
                String::new()
            } else {
                format!(" from [render] and give each mesh that takes {takes} its own `{key}`")
            }
        ))
    };
    if def.fog.is_some() || render.fog.is_some() {
        if let Some(what) = &no_colour {
            return refuse("fog", def.fog.is_some(), what, "fog");
        }
    }
    let dither = def.dither.unwrap_or(render.dither);
    if dither != DitherMode::None {
        let perspective = def
            .perspective_correct
            .unwrap_or(render.perspective_correct);
        let what = no_colour.or_else(|| match shading {
            ShadingModel::Flat | ShadingModel::Phong | ShadingModel::Matcap => Some(format!(
                "shading = \"{}\" (it dithers the colour Gouraud and vertex-colour shading \
                 interpolate)",
                shading_name(shading)
            )),
            _ if perspective => Some("a perspective-correct mesh".into()),
            _ => None,
        });
        if let Some(what) = what {
            return refuse("dither", def.dither.is_some(), &what, "dithering");
        }
    }
    let unlit = wireframe
        || matches!(
            shading,
            ShadingModel::None | ShadingModel::VertexColors | ShadingModel::Matcap
        );
    if def.material.is_some() && unlit {
        return Err(format!(
            "mesh {name}: material applies only to lit shading (flat, gouraud, phong), not to {}",
            if wireframe {
                "a wireframe mesh".to_string()
            } else {
                format!("shading = \"{}\"", shading_name(shading))
            }
        ));
    }
    if def.vertex_colors != VertexColorMode::File
        && (wireframe || shading != ShadingModel::VertexColors)
    {
        return Err(format!(
            "mesh {name}: vertex_colors applies only to shading = \"vertex_colors\" (filled)"
        ));
    }
    if wireframe && def.antialias {
        return Err(format!(
            "mesh {name}: antialias = true does not apply to a wireframe mesh{} (its edges are \
             lines, not the silhouettes of filled triangles); remove it or draw the mesh filled",
            if def.wireframe.is_some() {
                ""
            } else {
                " (wireframe = true from [render])"
            }
        ));
    }
    if wireframe && def.depth == Some(true) {
        return Err(format!(
            "mesh {name}: depth = true does not apply to a wireframe mesh (edges are drawn \
             without a depth buffer); remove it"
        ));
    }
    Ok(())
}

/// A shading model as the scene file spells it.
fn shading_name(s: ShadingModel) -> &'static str {
    match s {
        ShadingModel::None => "none",
        ShadingModel::VertexColors => "vertex_colors",
        ShadingModel::Flat => "flat",
        ShadingModel::Gouraud => "gouraud",
        ShadingModel::Phong => "phong",
        ShadingModel::Matcap => "matcap",
    }
}

/// The MatCap image of a mesh with `shading = "matcap"`: the `matcap` key's PNG, else the
/// built-in glossy sphere (`fixtures::matcap::GLOSSY_64`); `None` for other shading, where the
/// key is an error.
fn load_matcap(
    dir: &Path,
    def: &MeshDef,
    shading: ShadingModel,
) -> Result<Option<SceneMatCap>, String> {
    let name = &def.path;
    if shading != ShadingModel::Matcap {
        return match &def.matcap {
            Some(_) => Err(format!(
                "mesh {name}: matcap applies only to shading = \"matcap\", not \"{}\"; remove \
                 it or set the shading",
                shading_name(shading)
            )),
            None => Ok(None),
        };
    }
    let Some(m) = &def.matcap else {
        return Ok(Some(SceneMatCap {
            file: None,
            image: TextureImage {
                width_log2: fixtures::matcap::GLOSSY_64_SIDE_LOG2,
                height_log2: fixtures::matcap::GLOSSY_64_SIDE_LOG2,
                texels: fixtures::matcap::GLOSSY_64.to_vec(),
            },
        }));
    };
    let file = dir.join(m);
    let image = TextureImage::load_png(&file, None)
        .map_err(|e| format!("mesh {name}: matcap {}: {e}", file.display()))?;
    // The shader's own check, so that the message is the core's.
    rasterizer_core::shade::MatCap::<rasterizer_core::math::Fx16, Rgb888>::from_texture(
        image.texture(),
        &rasterizer_core::math::Mat4::identity(),
    )
    .map_err(|e| format!("mesh {name}: matcap {}: {e}", file.display()))?;
    Ok(Some(SceneMatCap {
        file: Some(file),
        image,
    }))
}

/// The mesh's texture: the `texture` key's PNG, else a packed mesh's own texture (`own`);
/// checked against the mesh's texture coordinates.
fn load_texture(
    dir: &Path,
    def: &MeshDef,
    own: Option<TextureImage>,
    data: &MeshData,
) -> Result<Option<SceneTexture>, String> {
    let name = &def.path;
    let filter = match def.texture_filter {
        None | Some(TextureFilterDef::Nearest) => Filter::Nearest,
        Some(TextureFilterDef::Bilinear) => Filter::Bilinear,
    };
    let wrap = match def.texture_wrap {
        None | Some(TextureWrapDef::Repeat) => Wrap::Repeat,
        Some(TextureWrapDef::Clamp) => Wrap::Clamp,
    };
    let has_uvs = match data {
        MeshData::Owned(o) => o.uvs.is_some(),
        MeshData::Packed(bytes) => PackedMesh::parse(bytes).is_ok_and(|p| p.has_uvs()),
    };
    let (file, image) = match &def.texture {
        Some(t) => {
            let file = dir.join(t);
            let image = TextureImage::load_png(&file, None).map_err(|e| {
                let fix = match e {
                    TextureFileError::NotPowerOfTwo { .. } | TextureFileError::TooLarge { .. } => {
                        format!(
                            "; resample it to a power of two up to {MAX_SIDE} (`host-tools \
                             convert --texture-size N` does, into a packed mesh)"
                        )
                    }
                    _ => String::new(),
                };
                format!("mesh {name}: texture {}: {e}{fix}", file.display())
            })?;
            (Some(file), image)
        }
        None => match own {
            Some(image) => (None, image),
            None if def.texture_filter.is_some() || def.texture_wrap.is_some() => {
                return Err(format!(
                    "mesh {name}: texture_filter and texture_wrap need a `texture`"
                ))
            }
            None => return Ok(None),
        },
    };
    if !has_uvs {
        return Err(format!(
            "mesh {name}: texture = \"{}\" but the mesh has no texture coordinates (every face \
             corner needs a `vt`)",
            def.texture.as_deref().unwrap_or_default()
        ));
    }
    Ok(Some(SceneTexture {
        file,
        image,
        filter,
        wrap,
    }))
}

/// `MeshSource::has_normals` without naming a scalar at the call site.
trait MeshSourceExt {
    fn has_normals(&self) -> bool;
}

impl MeshSourceExt for PackedMesh<'_> {
    fn has_normals(&self) -> bool {
        rasterizer_core::mesh::MeshSource::<rasterizer_core::math::Fx16>::has_normals(self)
    }
}

fn fx_to_f64(bits: i32) -> f64 {
    f64::from(bits) / 65536.0
}

/// A packed mesh in memory (positions and normals are exact: 16.16 values).
fn unpack(p: &PackedMesh<'_>) -> OwnedMesh {
    let n = p.vertices();
    let positions = (0..n)
        .map(|i| p.position_bits(i).unwrap_or_default().map(fx_to_f64))
        .collect();
    let normals = (0..n)
        .map(|i| p.normal_bits(i).map(|b| b.map(fx_to_f64)))
        .collect::<Option<Vec<_>>>();
    let colors = (0..n).map(|i| p.color_of(i)).collect::<Option<Vec<_>>>();
    let uvs = (0..n).map(|i| p.uv_bits(i)).collect::<Option<Vec<_>>>();
    let triangles = (0..p.triangles())
        .filter_map(|t| p.triangle_indices(t))
        .collect();
    // Kept as it is: editing the mesh (normals, colours, fitting) never changes its triangles.
    let adjacency = p.has_adjacency().then(|| {
        (0..p.triangles())
            .map(|t| p.neighbour_indices(t).unwrap_or([NO_NEIGHBOUR; 3]))
            .collect()
    });
    OwnedMesh {
        positions,
        normals,
        colors,
        uvs,
        triangles,
        adjacency,
    }
}

/// An OBJ mesh in memory.
fn from_raw(m: RawMesh) -> OwnedMesh {
    // In range: the reader refuses texture coordinates beyond 16.16.
    let bits = |c: f64| (c * 65536.0).round() as i32;
    OwnedMesh {
        positions: m.positions,
        normals: m.normals,
        colors: None,
        uvs: m.uvs.map(|u| u.iter().map(|uv| uv.map(bits)).collect()),
        triangles: m.triangles,
        adjacency: None,
    }
}

/// Applies the mesh options that change its data.
fn edit(mut m: OwnedMesh, def: &MeshDef) -> OwnedMesh {
    if def.fit_unit_sphere {
        fit_unit_sphere(&mut m);
    }
    match def.normals {
        NormalsMode::File => {}
        NormalsMode::Auto => {
            let usable = m
                .normals
                .as_ref()
                .is_some_and(|n| n.iter().all(|v| finite(v) && norm(*v) > 1e-6));
            if !usable {
                m.normals = Some(smooth_normals(&m));
            }
        }
        NormalsMode::Smooth => m.normals = Some(smooth_normals(&m)),
        NormalsMode::Face => m.normals = None,
    }
    match def.vertex_colors {
        VertexColorMode::File => {}
        VertexColorMode::Position => {
            let (lo, hi) = bounds(&m.positions);
            let colors = m
                .positions
                .iter()
                .map(|p| {
                    let c = |k: usize| {
                        let span = (hi[k] - lo[k]).max(1e-12);
                        (40.0 + 215.0 * (p[k] - lo[k]) / span).round() as u8
                    };
                    Rgb888::new(c(0), c(1), c(2))
                })
                .collect();
            m.colors = Some(colors);
        }
        VertexColorMode::Normal => {
            let normals = m.normals.clone().unwrap_or_else(|| smooth_normals(&m));
            let colors = normals
                .iter()
                .map(|n| {
                    let len = norm(*n).max(1e-12);
                    let c = |k: usize| (127.5 + 127.5 * n[k] / len).round().clamp(0.0, 255.0) as u8;
                    Rgb888::new(c(0), c(1), c(2))
                })
                .collect();
            m.colors = Some(colors);
        }
    }
    m
}

fn bounds(p: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::MAX; 3];
    let mut hi = [f64::MIN; 3];
    for v in p {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    (lo, hi)
}

/// Moves the bounding box's centre to the origin and scales the farthest vertex to distance 1.
fn fit_unit_sphere(m: &mut OwnedMesh) {
    let (lo, hi) = bounds(&m.positions);
    let c = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
    let r = m
        .positions
        .iter()
        .map(|p| norm(sub3(*p, c)))
        .fold(0.0, f64::max)
        .max(1e-12);
    for p in &mut m.positions {
        *p = [0, 1, 2].map(|k| (p[k] - c[k]) / r);
    }
}

/// Area-weighted vertex normals, vertices at the same position sharing one (so unwelded seams,
/// as in the teapot, and texture seams, as in Spot, do not show).
fn smooth_normals(m: &OwnedMesh) -> Vec<[f64; 3]> {
    let key = position_key;
    let mut slot = HashMap::new();
    let ids: Vec<usize> = m
        .positions
        .iter()
        .map(|p| {
            let n = slot.len();
            *slot.entry(key(p)).or_insert(n)
        })
        .collect();
    let mut acc = vec![[0.0f64; 3]; slot.len()];
    for t in &m.triangles {
        let Some(p) = t
            .iter()
            .map(|&i| m.positions.get(i as usize).copied())
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let n = cross(sub3(p[1], p[0]), sub3(p[2], p[0]));
        for &i in t {
            let a = &mut acc[ids[i as usize]];
            for k in 0..3 {
                a[k] += n[k];
            }
        }
    }
    ids.iter()
        .map(|&s| {
            let n = acc[s];
            let len = norm(n);
            if len > 0.0 {
                n.map(|v| v / len)
            } else {
                [0.0; 3]
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::convert::{convert_obj, Options};

    const N: u32 = NO_NEIGHBOUR;

    /// A closed cube, one quad a face, outward winding.
    const CUBE: &str = "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\n\
                        v -1 1 1\nv 1 1 1\nf 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\n\
                        f 1 5 7 3\nf 2 4 8 6\n";

    /// The cube packed by the converter, with adjacency or without.
    fn packed_cube(adjacency: bool) -> Vec<u8> {
        let opts = Options {
            adjacency,
            ..Options::default()
        };
        convert_obj("cube.obj", CUBE.as_bytes(), None, &opts, &mut Vec::new())
            .unwrap()
            .blob
    }

    fn assert_closed(a: &[[u32; 3]], triangles: usize) {
        assert_eq!(a.len(), triangles);
        for (t, row) in a.iter().enumerate() {
            for &u in row {
                assert!((u as usize) < triangles, "{t}: {row:?}");
                assert!(a[u as usize].contains(&(t as u32)), "{t} <-> {u}");
            }
        }
    }

    #[test]
    fn unpacking_keeps_a_packed_mesh_s_adjacency() {
        let blob = packed_cube(true);
        let p = PackedMesh::parse(&blob).unwrap();
        let owned = unpack(&p);
        let a = owned.adjacency.as_deref().unwrap();
        for (t, row) in a.iter().enumerate() {
            assert_eq!(p.neighbour_indices(t), Some(*row));
        }
        assert_closed(a, 12);
        assert!(unpack(&PackedMesh::parse(&packed_cube(false)).unwrap())
            .adjacency
            .is_none());
    }

    #[test]
    fn owned_meshes_compute_adjacency_across_seams() {
        // A quad whose diagonal's vertices are split, as a texture seam splits them.
        let quad = OwnedMesh {
            positions: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
            ],
            triangles: vec![[0, 1, 2], [4, 5, 3]],
            ..OwnedMesh::default()
        };
        let m = quad.with_adjacency();
        assert_eq!(m.adjacency, Some(vec![[N, N, 1], [0, N, N]]));
        // A table it carries is kept.
        let kept = OwnedMesh {
            adjacency: Some(vec![[N; 3]; 2]),
            ..m
        }
        .with_adjacency();
        assert_eq!(kept.adjacency, Some(vec![[N; 3]; 2]));
    }

    #[test]
    fn mesh_data_with_adjacency() {
        let with = MeshData::Packed(packed_cube(true));
        assert!(with.has_adjacency());
        assert!(matches!(with.with_adjacency(), MeshData::Packed(_)));
        let without = MeshData::Packed(packed_cube(false));
        assert!(!without.has_adjacency());
        let MeshData::Owned(o) = without.with_adjacency() else {
            panic!("a packed mesh without adjacency is unpacked to get one");
        };
        assert_closed(o.adjacency.as_deref().unwrap(), 12);
        let mut warnings = Vec::new();
        let raw = RawMesh::from_bytes("cube.obj", CUBE.as_bytes(), None, &mut warnings).unwrap();
        let obj = MeshData::Owned(from_raw(raw));
        assert!(!obj.has_adjacency());
        assert!(obj.with_adjacency().has_adjacency());
    }

    /// `antialias = true` gives the mesh adjacency: computed for an OBJ and for a packed mesh
    /// without its own (unpacked then), the packed table kept (drawn in place); without the key
    /// an OBJ gets none.
    #[test]
    fn antialias_key_gives_the_mesh_adjacency() {
        let dir = std::env::temp_dir().join(format!("scene-antialias-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("with.rmsh"), packed_cube(true)).unwrap();
        std::fs::write(dir.join("without.rmsh"), packed_cube(false)).unwrap();
        std::fs::write(dir.join("cube.obj"), CUBE).unwrap();
        for (file, antialias, adjacency, packed) in [
            ("with.rmsh", true, true, true),
            ("without.rmsh", true, true, false),
            ("cube.obj", true, true, false),
            ("cube.obj", false, false, false),
        ] {
            let path = dir.join("scene.toml");
            std::fs::write(
                &path,
                format!(
                    "[output]\nwidth = 32\nheight = 32\n[camera]\neye = [0.0, 0.0, 5.0]\n\
                     [[meshes]]\npath = \"{file}\"\nantialias = {antialias}\n"
                ),
            )
            .unwrap();
            let s = load(&path).unwrap();
            let m = &s.meshes[0];
            assert_eq!(m.antialias, antialias, "{file}");
            assert_eq!(m.data.has_adjacency(), adjacency, "{file} {antialias}");
            assert_eq!(matches!(m.data, MeshData::Packed(_)), packed, "{file}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn scenes_keep_a_packed_mesh_s_adjacency_drawn_in_place_or_edited() {
        let dir = std::env::temp_dir().join(format!("scene-adjacency-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("cube.rmsh"), packed_cube(true)).unwrap();
        let scene = |normals: &str| {
            format!(
                "[output]\nwidth = 32\nheight = 32\n[camera]\neye = [0.0, 0.0, 5.0]\n\
                 [[meshes]]\npath = \"cube.rmsh\"\nnormals = \"{normals}\"\n"
            )
        };
        for (normals, packed) in [("auto", true), ("smooth", false)] {
            let path = dir.join(format!("{normals}.toml"));
            std::fs::write(&path, scene(normals)).unwrap();
            let s = load(&path).unwrap();
            let data = &s.meshes[0].data;
            assert_eq!(matches!(data, MeshData::Packed(_)), packed, "{normals}");
            assert!(data.has_adjacency(), "{normals}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
