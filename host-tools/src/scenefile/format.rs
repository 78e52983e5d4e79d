//! The scene file's structure, as serde reads it. Every table rejects unknown keys.

use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;
use std::fmt;
use toml::Spanned;

/// A whole scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Size, pixel format and background.
    pub output: Output,
    /// The camera of the 3D part.
    #[serde(default)]
    pub camera: Camera,
    /// The 3D stages every mesh uses unless it says otherwise.
    #[serde(default)]
    pub render: RenderOptions,
    /// The lights (at most [`super::MAX_LIGHTS`]).
    #[serde(default)]
    pub lights: Vec<Spanned<LightDef>>,
    /// The meshes, drawn in order before the shapes.
    #[serde(default)]
    pub meshes: Vec<Spanned<MeshDef>>,
    /// The 2D shapes, drawn in order after the meshes.
    #[serde(default)]
    pub shapes: Vec<Spanned<Shape>>,
}

/// The `[output]` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Output {
    /// Width in pixels (1 ..= 4096).
    #[serde(deserialize_with = "size")]
    pub width: u32,
    /// Height in pixels (1 ..= 4096).
    #[serde(deserialize_with = "size")]
    pub height: u32,
    /// The display's pixel format.
    #[serde(default)]
    pub format: PixelFormat,
    /// The colour the display is cleared to.
    #[serde(default = "black")]
    pub background: Color,
    /// How many PNG pixels one display pixel becomes, unless `--scale` says otherwise.
    #[serde(default = "one", deserialize_with = "scale")]
    pub scale: u32,
}

/// A display pixel format.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PixelFormat {
    /// 16-bit colour, 5-6-5.
    Rgb565,
    /// 24-bit colour.
    #[default]
    Rgb888,
    /// 8-bit grey.
    Gray8,
    /// One bit: on or off.
    Binary,
}

/// The `[camera]` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    /// Where the camera is.
    #[serde(default = "default_eye")]
    pub eye: [f64; 3],
    /// The point it looks at.
    #[serde(default)]
    pub target: [f64; 3],
    /// Roughly up.
    #[serde(default = "default_up")]
    pub up: [f64; 3],
    /// Vertical field of view in degrees.
    #[serde(default = "default_fov")]
    pub fov: f64,
    /// Near clip plane distance.
    #[serde(default = "default_near")]
    pub near: f64,
    /// Far clip plane distance.
    #[serde(default = "default_far")]
    pub far: f64,
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            eye: default_eye(),
            target: [0.0; 3],
            up: default_up(),
            fov: default_fov(),
            near: default_near(),
            far: default_far(),
        }
    }
}

/// The `[render]` table: the 3D stages.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderOptions {
    /// Edges only (`Pipeline::draw_wireframe`) instead of filled triangles.
    #[serde(default)]
    pub wireframe: bool,
    /// The shading model of filled meshes.
    #[serde(default)]
    pub shading: ShadingModel,
    /// A depth buffer (filled meshes only).
    #[serde(default = "yes")]
    pub depth: bool,
    /// Which triangles to drop by their winding on screen.
    #[serde(default)]
    pub cull: CullMode,
    /// Interpolate shader values perspective-correctly.
    #[serde(default)]
    pub perspective_correct: bool,
    /// Ordered dithering of interpolated colour down to the output format.
    #[serde(default)]
    pub dither: DitherMode,
    /// The specular term of lit shading.
    #[serde(default)]
    pub specular: SpecularModel,
    /// The colour of the ambient light.
    #[serde(default = "white")]
    pub ambient: Color,
    /// Fog by depth (`shade::Fog`), for meshes that do not set their own.
    pub fog: Option<FogDef>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            wireframe: false,
            shading: ShadingModel::default(),
            depth: true,
            cull: CullMode::default(),
            perspective_correct: false,
            dither: DitherMode::default(),
            specular: SpecularModel::default(),
            ambient: white(),
            fog: None,
        }
    }
}

/// A shading model.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShadingModel {
    /// The mesh's `color`, unlit (`Unlit`).
    None,
    /// The mesh's vertex colours interpolated, unlit (`VertexColors`).
    VertexColors,
    /// Lit once per triangle (`FlatLit`).
    Flat,
    /// Lit per vertex, colours interpolated (`GouraudLit`).
    #[default]
    Gouraud,
    /// Lit per pixel (`PhongLit`).
    Phong,
    /// Coloured per vertex from a MatCap image by the view-space normal (`MatCap`).
    Matcap,
}

/// Ordered dithering (`Numerics::DITHER`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DitherMode {
    /// Each pixel rounded to the nearest step.
    #[default]
    None,
    /// The 4 x 4 Bayer matrix.
    Bayer4,
    /// The 8 x 8 Bayer matrix.
    Bayer8,
}

/// A `fog` table: the colour, where it starts and ends (depths in front of the camera) and how
/// it thickens in between.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FogDef {
    /// The fog's colour.
    pub color: Color,
    /// The depth where fog begins.
    pub start: f64,
    /// The depth where only fog is seen.
    pub end: f64,
    /// The curve between them.
    #[serde(default)]
    pub mode: FogMode,
    /// The exponential curve's density `k` (0 ..= 8; default 3); only with `mode =
    /// "exponential"`.
    pub density: Option<f64>,
}

/// How fog thickens between `start` and `end`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FogMode {
    /// In proportion to depth (`FogCurve::Linear`).
    #[default]
    Linear,
    /// `(1 - e^(-k t)) / (1 - e^(-k))` (`FogCurve::exponential`).
    Exponential,
}

/// Back-face culling.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CullMode {
    /// Keep every triangle (`NoCull`).
    None,
    /// Drop triangles that appear clockwise: the back faces of a counter-clockwise mesh
    /// (`CullClockwise`).
    #[default]
    Cw,
    /// Drop triangles that appear counter-clockwise (`CullCounterClockwise`).
    Ccw,
}

/// The specular term of lit shading.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SpecularModel {
    /// No highlight.
    None,
    /// Phong's reflected vector.
    Phong,
    /// Blinn-Phong's half vector.
    #[default]
    BlinnPhong,
}

/// One `[[lights]]` entry.
#[derive(Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum LightDef {
    /// Infinitely far away.
    Directional {
        /// From the surface towards the light.
        direction: [f64; 3],
        /// Its colour.
        #[serde(default = "white")]
        color: Color,
    },
    /// At a point, not attenuated.
    Point {
        /// Where it is, in world space.
        position: [f64; 3],
        /// Its colour.
        #[serde(default = "white")]
        color: Color,
    },
}

/// One `[[meshes]]` entry.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshDef {
    /// An OBJ file or a packed `.rmsh` blob, relative to the scene file.
    pub path: String,
    /// Centre the bounding box on the origin and scale the mesh into the unit sphere.
    #[serde(default)]
    pub fit_unit_sphere: bool,
    /// Where the vertex normals come from.
    #[serde(default)]
    pub normals: NormalsMode,
    /// Vertex colours to generate for `shading = "vertex_colors"`.
    #[serde(default)]
    pub vertex_colors: VertexColorMode,
    /// Scale factor: one number, or `[x, y, z]`.
    #[serde(default)]
    pub scale: ScaleDef,
    /// Rotations about x, then y, then z, in degrees.
    #[serde(default)]
    pub rotate: [f64; 3],
    /// Translation, applied last.
    #[serde(default)]
    pub translate: [f64; 3],
    /// Base colour: the unlit and wireframe colour, and the lit material's default colour.
    #[serde(default = "clay")]
    pub color: Color,
    /// The lit material; missing entries derive from `color`.
    #[serde(default)]
    pub material: Option<MaterialDef>,
    /// Overrides `render.wireframe`.
    pub wireframe: Option<bool>,
    /// Overrides `render.shading`.
    pub shading: Option<ShadingModel>,
    /// Overrides `render.depth`.
    pub depth: Option<bool>,
    /// Overrides `render.cull`.
    pub cull: Option<CullMode>,
    /// Overrides `render.perspective_correct`.
    pub perspective_correct: Option<bool>,
    /// Overrides `render.dither`.
    pub dither: Option<DitherMode>,
    /// A PNG texture (power-of-two sides, at most 1024), relative to the scene file; the mesh
    /// needs texture coordinates.
    pub texture: Option<String>,
    /// How texels are picked (needs `texture`).
    pub texture_filter: Option<TextureFilterDef>,
    /// How coordinates outside the texture address it (needs `texture`).
    pub texture_wrap: Option<TextureWrapDef>,
    /// A PNG MatCap image (square, a power-of-two side of at most 256), relative to the scene
    /// file, for `shading = "matcap"`; without it the built-in glossy sphere.
    pub matcap: Option<String>,
    /// Opacity 0 ..= 255 (default 255, opaque): below 255 the mesh is blended over what is
    /// drawn before it and tests depth without writing it.
    #[serde(default, deserialize_with = "opacity")]
    pub opacity: Option<u8>,
    /// Replaces `render.fog`.
    pub fog: Option<FogDef>,
    /// Anti-aliased silhouettes (`Pipeline::draw_antialiased`): the loader computes the mesh's
    /// edge adjacency for it.
    #[serde(default)]
    pub antialias: bool,
}

/// The `texture_filter` key.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TextureFilterDef {
    /// The texel the point falls in.
    #[default]
    Nearest,
    /// The four nearest texels, weighted.
    Bilinear,
}

/// The `texture_wrap` key.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TextureWrapDef {
    /// The texture tiles.
    #[default]
    Repeat,
    /// The edge texels continue outwards.
    Clamp,
}

/// Where a mesh's normals come from.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NormalsMode {
    /// The file's normals when it has usable ones (all non-zero), else `smooth`.
    #[default]
    Auto,
    /// The file's normals; an error when it has none.
    File,
    /// Area-weighted averages of the adjacent faces, vertices at the same position welded.
    Smooth,
    /// None: lit shading uses each triangle's face normal.
    Face,
}

/// Generated vertex colours.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VertexColorMode {
    /// The file's colours (packed meshes), else white.
    #[default]
    File,
    /// The position in the bounding box as red, green, blue.
    Position,
    /// The normal's direction as red, green, blue.
    Normal,
}

/// A uniform or per-axis scale.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum ScaleDef {
    /// The same on every axis.
    Uniform(f64),
    /// Per axis.
    Axes([f64; 3]),
}

impl Default for ScaleDef {
    fn default() -> Self {
        Self::Uniform(1.0)
    }
}

/// A mesh's `material` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDef {
    /// Reflected ambient light; default a fifth of `color`.
    pub ambient: Option<Color>,
    /// Reflected diffuse light; default `color`.
    pub diffuse: Option<Color>,
    /// Reflected highlight; default white.
    pub specular: Option<Color>,
    /// Specular exponent 0 ..= 65535; default 16.
    #[serde(default, deserialize_with = "shininess")]
    pub shininess: Option<u16>,
}

/// One `[[shapes]]` entry: a 2D primitive in pixel coordinates (x right, y down; pixel `(x, y)`
/// covers `[x, x + 1) x [y, y + 1)`).
#[derive(Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Shape {
    /// One pixel: the one containing `at`.
    Point {
        /// The position.
        at: [f64; 2],
        /// Its colour.
        color: Color,
        /// Opacity 0 ..= 255 (default opaque).
        #[serde(default, deserialize_with = "opacity")]
        opacity: Option<u8>,
        /// Optional clip rectangle `[x, y, width, height]`.
        #[serde(default, deserialize_with = "clip")]
        clip: Option<[i32; 4]>,
    },
    /// A line between the pixels containing `from` and `to`, in one colour or (`colors`) a
    /// gradient.
    Line {
        /// Start.
        from: [f64; 2],
        /// End.
        to: [f64; 2],
        /// One colour (give this or `colors`).
        color: Option<Color>,
        /// Start and end colours (give this or `color`).
        colors: Option<[Color; 2]>,
        /// Opacity 0 ..= 255 (default opaque).
        #[serde(default, deserialize_with = "opacity")]
        opacity: Option<u8>,
        /// Anti-aliased (`draw_line_aa_wide`), one colour only.
        #[serde(default)]
        antialias: bool,
        /// Width in pixels across the line (anti-aliased lines only; default 1).
        #[serde(default, deserialize_with = "line_width")]
        width: Option<u32>,
        /// Optional clip rectangle.
        #[serde(default, deserialize_with = "clip")]
        clip: Option<[i32; 4]>,
    },
    /// A filled triangle with sub-pixel vertices (rounded to 1/16 pixel), flat (`color`) or
    /// Gouraud (`colors`).
    Triangle {
        /// The corners.
        vertices: [[f64; 2]; 3],
        /// One colour (give this or `colors`).
        color: Option<Color>,
        /// One colour per corner (give this or `color`).
        colors: Option<[Color; 3]>,
        /// Opacity 0 ..= 255 (default opaque).
        #[serde(default, deserialize_with = "opacity")]
        opacity: Option<u8>,
        /// Optional clip rectangle.
        #[serde(default, deserialize_with = "clip")]
        clip: Option<[i32; 4]>,
    },
    /// A triangle's outline: three lines between the pixels containing the corners.
    Outline {
        /// The corners.
        vertices: [[f64; 2]; 3],
        /// Its colour.
        color: Color,
        /// Opacity 0 ..= 255 (default opaque).
        #[serde(default, deserialize_with = "opacity")]
        opacity: Option<u8>,
        /// Optional clip rectangle.
        #[serde(default, deserialize_with = "clip")]
        clip: Option<[i32; 4]>,
    },
    /// A filled polygon, concave or self-intersecting, sub-pixel vertices.
    Polygon {
        /// The corners, in order (at most [`super::MAX_POLYGON`]).
        vertices: Vec<[f64; 2]>,
        /// How overlapping parts are filled.
        #[serde(default)]
        fill_rule: FillRuleDef,
        /// Its colour.
        color: Color,
        /// Opacity 0 ..= 255 (default opaque).
        #[serde(default, deserialize_with = "opacity")]
        opacity: Option<u8>,
        /// Optional clip rectangle.
        #[serde(default, deserialize_with = "clip")]
        clip: Option<[i32; 4]>,
    },
    /// An image turned, scaled and sheared about its centre, which lands on `at`
    /// (`raster::sprite::draw_sprite`).
    Sprite {
        /// The image: a PNG (converted as `host-tools sprite` does, alpha kept exactly) or a
        /// sprite file (`.bin`), relative to the scene file.
        image: String,
        /// Where the image's centre lands, in pixels.
        at: [f64; 2],
        /// Clockwise turn in degrees (default 0).
        #[serde(default)]
        angle: f64,
        /// Scale, uniform or `[x, y]` along the image's own axes (default 1).
        #[serde(default)]
        scale: SpriteScaleDef,
        /// Horizontal shear of the image before it turns: x += shear * y (default 0).
        #[serde(default)]
        shear: f64,
        /// `nearest` (default) or `bilinear`.
        #[serde(default)]
        filter: TextureFilterDef,
        /// Opacity 0 ..= 255 (default opaque), times the image's own alpha.
        #[serde(default, deserialize_with = "opacity")]
        opacity: Option<u8>,
        /// Optional clip rectangle.
        #[serde(default, deserialize_with = "clip")]
        clip: Option<[i32; 4]>,
        /// The image file read (set by the loader).
        #[serde(skip)]
        file: std::path::PathBuf,
        /// The sprite bytes (set by the loader).
        #[serde(skip)]
        data: Vec<u8>,
    },
}

/// A sprite's uniform or per-axis scale.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum SpriteScaleDef {
    /// The same along both axes.
    Uniform(f64),
    /// Along the image's x and y.
    Axes([f64; 2]),
}

impl Default for SpriteScaleDef {
    fn default() -> Self {
        Self::Uniform(1.0)
    }
}

/// A polygon fill rule.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FillRuleDef {
    /// Filled where the crossing count is odd.
    #[default]
    EvenOdd,
    /// Filled where the winding number is not zero.
    NonZero,
}

/// A colour: `[r, g, b]` (0 ..= 255 each) or `"#rrggbb"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Color(pub [u8; 3]);

impl<'de> Deserialize<'de> for Color {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Color;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a colour: [r, g, b] with 0 ..= 255 each, or \"#rrggbb\"")
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<Color, E> {
                let hex = s
                    .strip_prefix('#')
                    .filter(|h| h.len() == 6 && h.bytes().all(|b| b.is_ascii_hexdigit()))
                    .ok_or_else(|| E::invalid_value(de::Unexpected::Str(s), &self))?;
                let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).unwrap_or(0);
                Ok(Color([byte(0), byte(2), byte(4)]))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Color, A::Error> {
                let mut c = [0u8; 3];
                for (i, slot) in c.iter_mut().enumerate() {
                    let v: i64 = seq
                        .next_element()?
                        .ok_or_else(|| de::Error::invalid_length(i, &self))?;
                    *slot = u8::try_from(v).map_err(|_| {
                        de::Error::invalid_value(de::Unexpected::Signed(v), &"0 ..= 255")
                    })?;
                }
                if seq.next_element::<de::IgnoredAny>()?.is_some() {
                    return Err(de::Error::invalid_length(4, &self));
                }
                Ok(Color(c))
            }
        }
        d.deserialize_any(V)
    }
}

/// An integer key's value, range-checked here rather than by serde's `u8`, `u32`, ... so that
/// an error names the range the key allows (`expected an integer 0 ..= 255`), not a Rust type.
/// With `LATER`, any `u32` passes: `load` checks the range then, in a one-line message with the
/// key and the value.
struct Int<const MIN: i64, const MAX: i64, const LATER: bool = false>(i64);

impl<'de, const MIN: i64, const MAX: i64, const LATER: bool> Deserialize<'de>
    for Int<MIN, MAX, LATER>
{
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V<const MIN: i64, const MAX: i64, const LATER: bool>;
        impl<const MIN: i64, const MAX: i64, const LATER: bool> Visitor<'_> for V<MIN, MAX, LATER> {
            type Value = Int<MIN, MAX, LATER>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "an integer {MIN} ..= {MAX}")
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
                if (MIN..=MAX).contains(&v) || (LATER && u32::try_from(v).is_ok()) {
                    Ok(Int(v))
                } else {
                    Err(E::invalid_value(de::Unexpected::Signed(v), &self))
                }
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
                match i64::try_from(v) {
                    Ok(v) => self.visit_i64(v),
                    Err(_) => Err(E::invalid_value(de::Unexpected::Unsigned(v), &self)),
                }
            }
        }
        d.deserialize_i64(V::<MIN, MAX, LATER>)
    }
}

// The integer keys, one function per range (the ranges are also in docs/SCENES.md). The casts
// cannot truncate: each range fits the field's type.

/// Puts the key's name before an error: inside `[[shapes]]` (an internally tagged enum) the
/// parser can point only at the table, not at the key.
fn named<T, E: de::Error>(key: &str, r: Result<T, E>) -> Result<T, E> {
    r.map_err(|e| E::custom(format_args!("`{key}`: {e}")))
}

fn size<'de, D: Deserializer<'de>>(d: D) -> Result<u32, D::Error> {
    Int::<1, { super::MAX_SIZE as i64 }, true>::deserialize(d).map(|i| i.0 as u32)
}

fn scale<'de, D: Deserializer<'de>>(d: D) -> Result<u32, D::Error> {
    Int::<1, 16, true>::deserialize(d).map(|i| i.0 as u32)
}

fn opacity<'de, D: Deserializer<'de>>(d: D) -> Result<Option<u8>, D::Error> {
    let r = Option::<Int<0, 255>>::deserialize(d);
    named("opacity", r).map(|o| o.map(|i| i.0 as u8))
}

fn shininess<'de, D: Deserializer<'de>>(d: D) -> Result<Option<u16>, D::Error> {
    Option::<Int<0, 65535>>::deserialize(d).map(|o| o.map(|i| i.0 as u16))
}

fn line_width<'de, D: Deserializer<'de>>(d: D) -> Result<Option<u32>, D::Error> {
    const MAX: i64 = rasterizer_core::raster::line::MAX_LINE_WIDTH as i64;
    let r = Option::<Int<1, MAX>>::deserialize(d);
    named("width", r).map(|o| o.map(|i| i.0 as u32))
}

fn clip<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[i32; 4]>, D::Error> {
    const MIN: i64 = i32::MIN as i64;
    const MAX: i64 = i32::MAX as i64;
    let r = Option::<[Int<MIN, MAX>; 4]>::deserialize(d);
    named("clip", r).map(|o| o.map(|c| c.map(|i| i.0 as i32)))
}

fn black() -> Color {
    Color([0, 0, 0])
}
fn white() -> Color {
    Color([255, 255, 255])
}
fn clay() -> Color {
    Color([220, 140, 80])
}
fn one() -> u32 {
    1
}
fn yes() -> bool {
    true
}
fn default_eye() -> [f64; 3] {
    [0.0, 0.0, 3.0]
}
fn default_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}
fn default_fov() -> f64 {
    60.0
}
fn default_near() -> f64 {
    0.1
}
fn default_far() -> f64 {
    100.0
}
/// The exponential curve's density when `fog.density` is not given.
pub fn default_density() -> f64 {
    3.0
}
