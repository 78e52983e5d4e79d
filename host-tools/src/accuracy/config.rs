//! The configurations the sweep compares: one registry entry per `Pipeline` type, each knob a
//! compile-time parameter of that type, so every entry is its own monomorphized pipeline (measured
//! for errors here, counted by callgrind through [`counted_frame`]).
//!
//! Adding a configuration is one `entry!` line in [`registry`]; the numerics knobs (divide method,
//! interpolation bits, span starts) are a `rasterizer_core::numerics` type as the last argument.

use super::metrics::{image_errors, rgb565_errors, vertex_errors, Errors};
use super::scene::{lighting, transforms, vec_s, Prepared, SceneDef};
use crate::scenefile::F64;
use fixtures::reference3d::{color_id, id_color, FaceIds};
use rasterizer_core::cull::Cull;
use rasterizer_core::math::{Fx24, Fx8, Scalar};
use rasterizer_core::numerics::{Dither, Divide, Numerics, SpanStart};
use rasterizer_core::pipeline::RenderStats;
use rasterizer_core::prelude::*;
use std::hint::black_box;

/// A geometry format with its name in the report.
pub trait Format: Scalar {
    /// Short name.
    const NAME: &'static str;
}

impl Format for Fx16 {
    const NAME: &'static str = "16.16";
}
impl Format for Fx8 {
    const NAME: &'static str = "24.8";
}
impl Format for Fx24 {
    const NAME: &'static str = "8.24";
}
impl Format for f32 {
    const NAME: &'static str = "f32";
}
impl Format for F64 {
    const NAME: &'static str = "f64";
}

/// The knobs of one configuration, as the report prints them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Knobs {
    /// Geometry format.
    pub format: &'static str,
    /// Sub-pixel bits of screen coordinates.
    pub bits: u32,
    /// Entries of the quarter-wave sine table.
    pub table: usize,
    /// Perspective-correct interpolation.
    pub perspective: bool,
    /// The reciprocal method of the perspective divide.
    pub divide: Divide,
    /// Fractional bits of interpolated colour and depth.
    pub frac: u32,
    /// How spans start their interpolated values.
    pub spans: SpanStart,
    /// How the colour is brought to the target's depth.
    pub dither: Dither,
}

impl Knobs {
    /// The divide method's name in the report.
    pub fn divide_name(&self) -> &'static str {
        match self.divide {
            Divide::Exact => "exact",
            Divide::Reciprocal => "reciprocal",
            Divide::Newton => "Newton",
        }
    }

    /// The dithering's name in the report.
    pub fn dither_name(&self) -> &'static str {
        match self.dither {
            Dither::None => "none",
            Dither::Bayer4 => "Bayer 4x4",
            Dither::Bayer8 => "Bayer 8x8",
        }
    }

    /// The span-start method's name in the report.
    pub fn spans_name(&self) -> &'static str {
        match self.spans {
            SpanStart::Exact => "exact",
            SpanStart::Gradient => "gradient",
            SpanStart::Wrapping => "wrapping",
        }
    }
}

/// What a configuration's measurement of one scene gives: its errors, or why it could not run.
pub type Measured = Result<Errors, String>;

/// One configuration.
#[derive(Debug, Clone, Copy)]
pub struct Config {
    /// Name (also the argument of the hidden `accuracy-count` command).
    pub label: &'static str,
    /// Which knob the entry moves away from the default ("default" for the default itself).
    pub varies: &'static str,
    /// The knobs.
    pub knobs: Knobs,
    /// A control, not a library configuration: shown in the tables, left out of the plot.
    pub control: bool,
    /// Measures the errors on a prepared scene (only the vertex positions when the scene has no
    /// reference render).
    pub measure: fn(&Prepared) -> Measured,
    /// Draws the counted frame of a scene (M1) and describes what was drawn.
    pub count: fn(&SceneDef) -> Result<String, String>,
}

/// One registry entry: label, the knob it varies, format, sub-pixel bits, perspective, table size
/// and (optionally; the library's defaults otherwise) the divide method, fractional bits and span
/// starts of [`Knobbed`].
macro_rules! entry {
    ($label:literal, $varies:literal, $s:ty, $bits:literal, $persp:literal, $table:literal) => {
        entry!(@ $label, $varies, $s, $bits, $persp, $table, Knobbed<0, 16, 2, $persp>, false)
    };
    ($label:literal, $varies:literal, $s:ty, $bits:literal, $persp:literal, $table:literal,
        $div:literal, $frac:literal, $spans:literal) => {
        entry!(@ $label, $varies, $s, $bits, $persp, $table, Knobbed<$div, $frac, $spans, $persp>, false)
    };
    (control $label:literal, $varies:literal, $s:ty, $bits:literal, $persp:literal, $table:literal) => {
        entry!(@ $label, $varies, $s, $bits, $persp, $table, Knobbed<0, 16, 2, $persp>, true)
    };
    (@ $label:literal, $varies:literal, $s:ty, $bits:literal, $persp:literal, $table:literal,
        $num:ty, $control:literal) => {
        Config {
            label: $label,
            varies: $varies,
            knobs: Knobs {
                format: <$s as Format>::NAME,
                bits: $bits,
                table: $table,
                perspective: $persp,
                divide: <$num as Numerics>::DIVIDE,
                frac: <$num as Numerics>::FRAC,
                spans: <$num as Numerics>::SPANS,
                dither: <$num as Numerics>::DITHER,
            },
            control: $control,
            measure: measure::<$s, $bits, $table, $num>,
            count: count::<$s, $bits, $table, $num>,
        }
    };
}

/// A configuration's numeric knobs: the divide method (0 exact, 1 reciprocal, 2 Newton), the
/// fractional bits, the span starts (0 exact, 1 gradient, 2 wrapping) and perspective correction.
pub struct Knobbed<const DIV: u8, const FRAC: u32, const SPANS: u8, const P: bool>;

impl<const DIV: u8, const FRAC: u32, const SPANS: u8, const P: bool> Numerics
    for Knobbed<DIV, FRAC, SPANS, P>
{
    const DIVIDE: Divide = [Divide::Exact, Divide::Reciprocal, Divide::Newton][DIV as usize];
    const FRAC: u32 = FRAC;
    const SPANS: SpanStart =
        [SpanStart::Exact, SpanStart::Gradient, SpanStart::Wrapping][SPANS as usize];
    const PERSPECTIVE: bool = P;
}

/// `N` dithered (0 none, 1 Bayer 4x4, 2 Bayer 8x8).
pub struct Dithered<N, const D: u8>(core::marker::PhantomData<N>);

impl<N: Numerics, const D: u8> Numerics for Dithered<N, D> {
    const DIVIDE: Divide = N::DIVIDE;
    const FRAC: u32 = N::FRAC;
    const SPANS: SpanStart = N::SPANS;
    const PERSPECTIVE: bool = N::PERSPECTIVE;
    const DITHER: Dither = [Dither::None, Dither::Bayer4, Dither::Bayer8][D as usize];
}

/// `N` with affine values.
struct Affine<N>(core::marker::PhantomData<N>);

impl<N: Numerics> Numerics for Affine<N> {
    const DIVIDE: Divide = N::DIVIDE;
    const FRAC: u32 = N::FRAC;
    const SPANS: SpanStart = N::SPANS;
}

/// The label of the library's default configuration.
pub const DEFAULT: &str = "default";

/// Every configuration: the default, one knob at a time away from it, then combinations and the
/// `f64` control (the same pipeline with `f64` geometry: what is left is the integer stages').
pub fn registry() -> Vec<Config> {
    vec![
        entry!("default", "default", Fx16, 6, false, 256),
        entry!("24.8", "format", Fx8, 6, false, 256),
        entry!("8.24", "format", Fx24, 6, false, 256),
        entry!("f32", "format", f32, 6, false, 256),
        entry!("bits0", "sub-pixel bits", Fx16, 0, false, 256),
        entry!("bits2", "sub-pixel bits", Fx16, 2, false, 256),
        entry!("bits4", "sub-pixel bits", Fx16, 4, false, 256),
        entry!("bits8", "sub-pixel bits", Fx16, 8, false, 256),
        entry!("table4", "trig table", Fx16, 6, false, 4),
        entry!("table16", "trig table", Fx16, 6, false, 16),
        entry!("table64", "trig table", Fx16, 6, false, 64),
        entry!("table1024", "trig table", Fx16, 6, false, 1024),
        entry!("perspective", "perspective", Fx16, 6, true, 256),
        entry!("reciprocal", "divide", Fx16, 6, false, 256, 1, 16, 2),
        entry!("newton", "divide", Fx16, 6, false, 256, 2, 16, 2),
        entry!(
            "frac12",
            "interpolation bits",
            Fx16,
            6,
            false,
            256,
            0,
            12,
            0
        ),
        entry!("frac8", "interpolation bits", Fx16, 6, false, 256, 0, 8, 0),
        entry!("frac4", "interpolation bits", Fx16, 6, false, 256, 0, 4, 0),
        entry!("gradient", "span starts", Fx16, 6, false, 256, 0, 16, 1),
        entry!("exact-spans", "span starts", Fx16, 6, false, 256, 0, 16, 0),
        entry!(@ "bayer4", "dithering", Fx16, 6, false, 256,
            Dithered<Knobbed<0, 16, 2, false>, 1>, false),
        entry!(@ "bayer8", "dithering", Fx16, 6, false, 256,
            Dithered<Knobbed<0, 16, 2, false>, 2>, false),
        entry!("cheap", "combination", Fx16, 0, false, 16, 2, 4, 1),
        entry!("cheap-24.8", "combination", Fx8, 0, false, 16, 2, 4, 1),
        entry!("fine", "combination", Fx16, 8, true, 1024),
        entry!("fine-8.24", "combination", Fx24, 8, true, 1024),
        entry!("f32-perspective", "combination", f32, 6, true, 256),
        entry!(control "f64", "control", F64, 6, false, 256),
    ]
}

/// The default configuration of each format (the breakdown sweep's subjects), with the `f64`
/// control.
pub fn per_format() -> Vec<Config> {
    registry()
        .into_iter()
        .filter(|c| c.varies == "default" || c.varies == "format" || c.varies == "control")
        .collect()
}

/// Culling chosen at run time: back faces (as `CullClockwise`) or none. The error measurement
/// needs both (workload meshes cull, random soups do not); the counted frame uses the
/// compile-time `CullClockwise` as firmware would.
#[derive(Debug, Clone, Copy)]
struct SceneCull(bool);

impl Cull for SceneCull {
    fn keep(&self, area: i64) -> bool {
        !self.0 || CullClockwise.keep(area)
    }
}

/// The screen position in pixels of a sub-pixel coordinate.
fn px(v: i32, bits: u32) -> f64 {
    f64::from(v) / f64::from(1u32 << bits)
}

/// "No triangle" in the id image: more triangles than any scene has.
const NO_ID: u32 = 0xFF_FFFF;

fn measure<S: Format, const BITS: u32, const N: usize, Nu: Numerics>(scene: &Prepared) -> Measured {
    let def = &scene.def;
    let (w, h) = (def.width, def.height);
    let xf = transforms::<S, N>(&def.camera, w, h)
        .ok_or("the camera or the projection is not representable")?;
    let vp = Viewport::new(w, h);
    let positions: Vec<Vec3<S>> = def.positions.iter().map(|&p| vec_s(p)).collect();
    let normals: Vec<Vec3<S>> = def.normals.iter().map(|&n| vec_s(n)).collect();
    let cull = SceneCull(def.cull);
    let pixels = w as usize * h as usize;

    // Vertex positions: the configuration's own projection (no buffers needed).
    let probe = Pipeline::new(
        &xf,
        vp,
        cull,
        NoDepth,
        Unlit {
            color: Rgb888::BLACK,
        },
    )
    .with_bits::<BITS>()
    .with_numerics::<Nu>();
    let ours: Vec<[f64; 2]> = positions
        .iter()
        .map(|&v| {
            let (sp, _) = probe.project(&probe.mvp().transform_point(v));
            [px(sp.x, BITS), px(sp.y, BITS)]
        })
        .collect();
    let (vertices, vertex_max, vertex_sum) = vertex_errors(&scene.screen, &ours);
    let vertex = Errors {
        vertices,
        vertex_max,
        vertex_sum,
        ..Errors::default()
    };
    let Some(reference) = &scene.render else {
        return Ok(vertex);
    };

    // Colours: Gouraud into Rgb888, the configuration exactly.
    let mut rgb = vec![0u8; pixels * 3];
    draw_gouraud::<S, Rgb888, BITS, Nu>(&xf, cull, def, &positions, &normals, &mut rgb)?;

    // Triangle ids: each face painted with its id (three unshared corners per triangle). Ids and
    // coverage do not depend on perspective-correct interpolation (depth is affine in screen space
    // either way), and a constant is reproduced exactly only by affine interpolation, so this
    // render is always affine.
    let mut face_pos = Vec::with_capacity(def.tris.len() * 3);
    let mut face_col = Vec::with_capacity(def.tris.len() * 3);
    let mut face_tri = Vec::with_capacity(def.tris.len());
    for (t, tri) in def.tris.iter().enumerate() {
        let base = face_pos.len() as u32;
        for &i in tri {
            face_pos.push(positions[i as usize]);
            face_col.push(id_color(t as u32));
        }
        face_tri.push([base, base + 1, base + 2]);
    }
    let mut ids_rgb = vec![0u8; pixels * 3];
    {
        let mut fb =
            Framebuffer::<Rgb888>::new(&mut ids_rgb, w, h).map_err(|e| format!("{e:?}"))?;
        let Ok(()) = fb.clear(id_color(NO_ID));
        let mut zbuf = vec![u16::MAX; pixels];
        let depth =
            DepthBuffer::new(&mut zbuf, w, h, Compare::Less).map_err(|e| format!("{e:?}"))?;
        let mut p = Pipeline::new(&xf, vp, cull, depth, FaceIds)
            .with_bits::<BITS>()
            .with_numerics::<Affine<Nu>>();
        let mesh = Mesh {
            positions: &face_pos,
            normals: None,
            colors: Some(&face_col),
            uvs: None,
            triangles: &face_tri,
            adjacency: None,
        };
        let mut scratch = vec![VertexSlot::EMPTY; face_pos.len()];
        p.draw(&mut fb, &mesh, &mut scratch)
            .map_err(|e| e.to_string())?;
    }
    let ids: Vec<Option<u32>> = ids_rgb
        .chunks_exact(3)
        .map(|c| {
            let id = color_id(Rgb888::new(c[0], c[1], c[2]));
            (id != NO_ID).then_some(id)
        })
        .collect();
    let colors: Vec<[u8; 3]> = rgb.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let mut errors = vertex.merge(&image_errors(reference, &scene.colors, &ids, &colors));

    // The same colours into Rgb565, where rounding (or dithering) to 5 and 6 bits shows.
    let mut c565 = vec![0u16; pixels];
    draw_gouraud::<S, Rgb565, BITS, Nu>(&xf, cull, def, &positions, &normals, &mut c565)?;
    let ours565: Vec<[u8; 3]> = c565
        .iter()
        .map(|&v| {
            let c = Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(v));
            [c.r(), c.g(), c.b()]
        })
        .collect();
    rgb565_errors(
        &mut errors,
        reference,
        &scene.colors,
        &ids,
        &ours565,
        w as usize,
    );
    Ok(errors)
}

/// The configuration's Gouraud render of a scene's mesh into a framebuffer of colour `C` over
/// `buf`, with a depth buffer and the scene's culling.
fn draw_gouraud<S: Format, C, const BITS: u32, Nu: Numerics>(
    xf: &Transforms<S>,
    cull: SceneCull,
    def: &SceneDef,
    positions: &[Vec3<S>],
    normals: &[Vec3<S>],
    buf: &mut [C::Word],
) -> Result<(), String>
where
    C: rasterizer_core::color::ShadeColor + rasterizer_core::surface::Storage,
{
    let (w, h) = (def.width, def.height);
    let mut fb = Framebuffer::<C>::new(buf, w, h).map_err(|e| format!("{e:?}"))?;
    let mut zbuf = vec![u16::MAX; w as usize * h as usize];
    let depth = DepthBuffer::new(&mut zbuf, w, h, Compare::Less).map_err(|e| format!("{e:?}"))?;
    let shading = GouraudLit::<S, C, 1>::new(lighting::<S>(&def.camera));
    let mut p = Pipeline::new(xf, Viewport::new(w, h), cull, depth, shading)
        .with_bits::<BITS>()
        .with_numerics::<Nu>();
    let mesh = Mesh::new(positions, &def.tris).with_normals(normals);
    let mut scratch = vec![VertexSlot::EMPTY; positions.len()];
    p.draw(&mut fb, &mesh, &mut scratch)
        .map_err(|e| e.to_string())?;
    Ok(())
}

/// The M1 frame callgrind counts: the whole draw call of one frame, nothing else. Generic, so each
/// configuration has its own copy; `--toggle-collect='*counted_frame*'` matches all of them, and
/// each counting process runs exactly one.
#[inline(never)]
pub fn counted_frame<S: Scalar, const BITS: u32, Nu: Numerics>(
    p: &mut Pipeline<S, CullClockwise, DepthBuffer<'_>, GouraudLit<S, Rgb565, 1>, BITS, Nu>,
    fb: &mut Framebuffer<'_, Rgb565>,
    mesh: &Mesh<'_, S, u32>,
    scratch: &mut [VertexSlot],
) -> RenderStats {
    p.draw(fb, mesh, scratch).unwrap_or_default()
}

fn count<S: Format, const BITS: u32, const N: usize, Nu: Numerics>(
    def: &SceneDef,
) -> Result<String, String> {
    let (w, h) = (def.width, def.height);
    let xf = transforms::<S, N>(&def.camera, w, h)
        .ok_or("the camera or the projection is not representable")?;
    let positions: Vec<Vec3<S>> = def.positions.iter().map(|&p| vec_s(p)).collect();
    let normals: Vec<Vec3<S>> = def.normals.iter().map(|&n| vec_s(n)).collect();
    let mesh = Mesh {
        positions: &positions,
        normals: Some(&normals),
        colors: None,
        uvs: None,
        triangles: &def.tris,
        adjacency: None,
    };
    let pixels = w as usize * h as usize;
    let mut buf = vec![0u16; pixels];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, w, h).map_err(|e| format!("{e:?}"))?;
    let mut zbuf = vec![u16::MAX; pixels];
    let depth = DepthBuffer::new(&mut zbuf, w, h, Compare::Less).map_err(|e| format!("{e:?}"))?;
    let mut p = Pipeline::new(
        &xf,
        Viewport::new(w, h),
        CullClockwise,
        depth,
        GouraudLit::<S, Rgb565, 1>::new(lighting::<S>(&def.camera)),
    )
    .with_bits::<BITS>()
    .with_numerics::<Nu>();
    // The warm frame, then clear: neither is counted. The scratch is the caller's RAM.
    let mut scratch = vec![VertexSlot::EMPTY; positions.len()];
    p.draw(&mut fb, &mesh, &mut scratch)
        .map_err(|e| e.to_string())?;
    let Ok(()) = fb.clear(Rgb565::BLACK);
    p.depth.clear(u16::MAX);
    let stats = counted_frame(
        &mut p,
        black_box(&mut fb),
        black_box(&mesh),
        black_box(&mut scratch),
    );
    let checksum = fb
        .as_slice()
        .iter()
        .fold(0u32, |a, &v| a.rotate_left(5) ^ u32::from(v));
    Ok(format!(
        "drawn={} culled={} clipped={} checksum={checksum:08x}",
        stats.drawn, stats.culled, stats.clipped
    ))
}
