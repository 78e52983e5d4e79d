//! Draws one frame of the M1 scene of `shared/bench/WORKLOADS.md` (Suzanne, 968 triangles) for
//! callgrind to count, with one combination of pipeline stages (`scripts/callgrind3d.sh`).
//!
//! `count3d COMBINATION`, one of the names below. The mesh is loaded, the pipeline built and one warm
//! frame drawn outside the counted function; the colour and depth buffers are cleared outside it too.
//! Then exactly one call of `frame_<COMBINATION>` draws the counted frame. Every combination is its own
//! monomorphized `Pipeline` type and its own `#[inline(never)]` function; each function also hands its
//! own name to `black_box`, so that no two of them are identical and none can be merged into another
//! (rustc runs LLVM's function merging).
//!
//! | combination | shading | depth | culling | draw |
//! |---|---|---|---|---|
//! | `m1` | `GouraudLit` | `DepthBuffer` (`Less`) | `CullClockwise` | `draw` |
//! | `m1_nodepth` | `GouraudLit` | `NoDepth` | `CullClockwise` | `draw` |
//! | `m1_nocull` | `GouraudLit` | `DepthBuffer` (`Less`) | `NoCull` | `draw` |
//! | `m1_unlit` | `Unlit` | `DepthBuffer` (`Less`) | `CullClockwise` | `draw` |
//! | `m1_flat` | `FlatLit` | `DepthBuffer` (`Less`) | `CullClockwise` | `draw` |
//! | `m1_phong` | `PhongLit` | `DepthBuffer` (`Less`) | `CullClockwise` | `draw` |
//! | `m1_unlit_nodepth_nocull` | `Unlit` | `NoDepth` | `NoCull` | `draw` |
//! | `m1_wireframe` | - | - | `CullClockwise` | `draw_wireframe` |
//! | `m1_cached` | `GouraudLit` | `DepthBuffer` (`Less`) | `CullClockwise` | `draw_cached` |
//! | `m1_depth_always` | `GouraudLit` | `DepthBuffer` (`Always`) | `CullClockwise` | `draw` |
//! | `m1_cull_keepall` | `GouraudLit` | `DepthBuffer` (`Less`) | `KeepAll` (runtime "keep") | `draw` |
//!
//! The last two are the controls for "an effect turned off costs no more than a pipeline built
//! without it": `m1_depth_always` (depth effect present, doing nothing useful) against `m1_nodepth`,
//! and `m1_cull_keepall` (a culling stage that keeps everything, decided at run time) against
//! `m1_nocull`.
//!
//! Scene: model rotated 30° about Y; camera at (0, 0, 3) looking at the origin, up +Y; 60° vertical
//! field of view, aspect 4:3, near 0.1, far 100; 320 x 240 Rgb565; the mesh's own normals. Lighting
//! (as the reference render of M1): one directional white light from (1, 1, 1), ambient white,
//! material ambient (40, 30, 30), diffuse (220, 140, 80), specular white, shininess 16, Blinn-Phong,
//! eye at (0, 0, 3) in world space. `Unlit` draws (220, 140, 80); the wireframe is white.
//!
//! Prints `COMBINATION triangles=.. drawn=.. culled=.. clipped=.. outside=.. invalid=..
//! checksum=..` for the counted frame.

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use host_tools::obj::LoadedMesh;
use host_tools::scenes::{HEIGHT, PIXELS, WIDTH};
use rasterizer_core::math::{Angle, Fx16, Mat4, Vec3};
use rasterizer_core::pipeline::cull::{Cull, CullClockwise, NoCull};
use rasterizer_core::pipeline::shading::{FlatLit, GouraudLit, PhongLit, Shading, Unlit};
use rasterizer_core::pipeline::{
    Banding, BinEntry, CachedVertex, Mesh, Pipeline, RenderStats, Transforms, Viewport,
};
use rasterizer_core::raster::interp::{Compare, DepthBuffer, DepthTest, NoDepth};
use rasterizer_core::shade::{Light, Lighting, Material, Specular};
use rasterizer_core::target::Framebuffer;
use std::hint::black_box;
use std::path::PathBuf;
use std::process::ExitCode;

/// Every combination, in the order the script reports them.
const COMBINATIONS: [&str; 16] = [
    "m1",
    "m1_nodepth",
    "m1_nocull",
    "m1_unlit",
    "m1_flat",
    "m1_phong",
    "m1_unlit_nodepth_nocull",
    "m1_wireframe",
    "m1_cached",
    "m1_depth_always",
    "m1_cull_keepall",
    "m1_band8",
    "m1_band16",
    "m1_band32",
    "m1_band240",
    "m1_band16_cached",
];

/// A culling stage that keeps every triangle, but only finds that out at run time: the "culling
/// present, doing nothing" control for `NoCull`.
struct KeepAll;

impl Cull for KeepAll {
    fn keep(&self, _: i64) -> bool {
        black_box(true)
    }
}

type Fb<'a> = Framebuffer<'a, Rgb565>;
type Mesh3<'a> = Mesh<'a, Fx16, u32>;
type Light1 = Lighting<Fx16, 1>;
/// A 16.16 pipeline with 28.4 screen coordinates and affine interpolation.
type Pipe<C, D, Sh> = Pipeline<Fx16, C, D, Sh, 4>;
/// A counted frame function.
type FrameFn<C, D, Sh> = fn(&mut Pipe<C, D, Sh>, &mut Fb<'_>, &Mesh3<'_>) -> RenderStats;

const DIFFUSE: Rgb888 = Rgb888::new(220, 140, 80);

fn lighting() -> Light1 {
    let material = Material {
        ambient: Rgb888::new(40, 30, 30),
        diffuse: DIFFUSE,
        specular: Rgb888::WHITE,
        shininess: 16,
    };
    let mut l = Lighting::new(
        material,
        Rgb888::WHITE,
        Specular::BlinnPhong,
        Vec3::from_ints(0, 0, 3),
    );
    l.add_light(Light::Directional {
        direction: Vec3::from_ints(1, 1, 1),
        color: Rgb888::WHITE,
    })
    .expect("one light fits");
    l
}

fn transforms() -> Transforms<Fx16> {
    Transforms {
        model: Mat4::rotation_y(Angle::from_degrees(30)),
        view: Mat4::look_at(
            Vec3::from_ints(0, 0, 3),
            Vec3::from_ints(0, 0, 0),
            Vec3::from_ints(0, 1, 0),
        )
        .expect("camera basis"),
        projection: Mat4::perspective(
            Angle::from_degrees(60),
            Fx16::from_ratio(WIDTH.into(), HEIGHT.into()),
            Fx16::from_ratio(1, 10),
            Fx16::from_int(100),
        )
        .expect("projection"),
    }
}

/// The drawing of one frame, shared by the warm frame and the counted `frame_*` functions.
#[inline(always)]
fn draw<C: Cull, D: DepthTest, Sh: Shading<Fx16, Color = Rgb565>>(
    p: &mut Pipeline<Fx16, C, D, Sh, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
) -> RenderStats {
    let Ok(stats) = p.draw(fb, mesh);
    stats
}

// The counted frames: one per combination. `black_box(NAME)` makes each function's code distinct.

#[inline(never)]
fn frame_m1(
    p: &mut Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, GouraudLit<Fx16, Rgb565, 1>, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
) -> RenderStats {
    black_box("frame_m1");
    draw(p, fb, mesh)
}

#[inline(never)]
fn frame_m1_nodepth(
    p: &mut Pipeline<Fx16, CullClockwise, NoDepth, GouraudLit<Fx16, Rgb565, 1>, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
) -> RenderStats {
    black_box("frame_m1_nodepth");
    draw(p, fb, mesh)
}

#[inline(never)]
fn frame_m1_nocull(
    p: &mut Pipeline<Fx16, NoCull, DepthBuffer<'_>, GouraudLit<Fx16, Rgb565, 1>, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
) -> RenderStats {
    black_box("frame_m1_nocull");
    draw(p, fb, mesh)
}

#[inline(never)]
fn frame_m1_unlit(
    p: &mut Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, Unlit<Rgb565>, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
) -> RenderStats {
    black_box("frame_m1_unlit");
    draw(p, fb, mesh)
}

#[inline(never)]
fn frame_m1_flat(
    p: &mut Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, FlatLit<Fx16, Rgb565, 1>, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
) -> RenderStats {
    black_box("frame_m1_flat");
    draw(p, fb, mesh)
}

#[inline(never)]
fn frame_m1_phong(
    p: &mut Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, PhongLit<Fx16, Rgb565, 1>, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
) -> RenderStats {
    black_box("frame_m1_phong");
    draw(p, fb, mesh)
}

#[inline(never)]
fn frame_m1_unlit_nodepth_nocull(
    p: &mut Pipeline<Fx16, NoCull, NoDepth, Unlit<Rgb565>, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
) -> RenderStats {
    black_box("frame_m1_unlit_nodepth_nocull");
    draw(p, fb, mesh)
}

#[inline(never)]
fn frame_m1_wireframe(
    p: &mut Pipeline<Fx16, CullClockwise, NoDepth, Unlit<Rgb565>, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
) -> RenderStats {
    black_box("frame_m1_wireframe");
    let Ok(stats) = p.draw_wireframe(fb, mesh, Rgb565::WHITE);
    stats
}

#[inline(never)]
fn frame_m1_cached(
    p: &mut Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, GouraudLit<Fx16, Rgb565, 1>, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
    cache: &mut [CachedVertex<Fx16, [i32; 3], 4>],
) -> RenderStats {
    black_box("frame_m1_cached");
    let Ok(stats) = p.draw_cached(fb, mesh, cache);
    stats
}

type BandPipeline<'a> =
    Pipeline<Fx16, CullClockwise, DepthBuffer<'a>, GouraudLit<Fx16, Rgb565, 1>, 4>;

/// One banded M1 frame: each finished band is copied into `fb` (where firmware would start the
/// display's DMA); the copy is a few thousand instructions of the count.
#[inline(always)]
fn banded(
    p: &mut BandPipeline<'_>,
    rows: u32,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
    band: &mut [u16],
    bins: &mut [BinEntry],
    cache: &mut [CachedVertex<Fx16, [i32; 3], 4>],
) -> RenderStats {
    let banding = Banding {
        width: WIDTH,
        height: HEIGHT,
        rows,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    let out = fb.as_mut_slice();
    let result = p.draw_banded(mesh, &banding, band, bins, cache, |b| {
        let y0 = b.y0() as usize * WIDTH as usize;
        let data = b.framebuffer().as_slice();
        out[y0..y0 + data.len()].copy_from_slice(data);
    });
    result.unwrap_or_default()
}

macro_rules! band_frame {
    ($name:ident, $rows:expr) => {
        #[inline(never)]
        fn $name(
            p: &mut BandPipeline<'_>,
            fb: &mut Fb<'_>,
            mesh: &Mesh3<'_>,
            band: &mut [u16],
            bins: &mut [BinEntry],
            cache: &mut [CachedVertex<Fx16, [i32; 3], 4>],
        ) -> RenderStats {
            black_box(stringify!($name));
            banded(p, $rows, fb, mesh, band, bins, cache)
        }
    };
}

band_frame!(frame_m1_band8, 8);
band_frame!(frame_m1_band16, 16);
band_frame!(frame_m1_band32, 32);
band_frame!(frame_m1_band240, 240);
band_frame!(frame_m1_band16_cached, 16);

#[inline(never)]
fn frame_m1_depth_always(
    p: &mut Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, GouraudLit<Fx16, Rgb565, 1>, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
) -> RenderStats {
    black_box("frame_m1_depth_always");
    draw(p, fb, mesh)
}

#[inline(never)]
fn frame_m1_cull_keepall(
    p: &mut Pipeline<Fx16, KeepAll, DepthBuffer<'_>, GouraudLit<Fx16, Rgb565, 1>, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
) -> RenderStats {
    black_box("frame_m1_cull_keepall");
    draw(p, fb, mesh)
}

/// Builds a pipeline, draws the warm frame (not counted), clears both buffers (not counted) and
/// calls `frame` once for the counted frame.
fn run<C, D, Sh>(
    mut p: Pipeline<Fx16, C, D, Sh, 4>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
    clear_depth: fn(&mut D),
    frame: FrameFn<C, D, Sh>,
) -> RenderStats
where
    C: Cull,
    D: DepthTest,
    Sh: Shading<Fx16, Color = Rgb565>,
{
    let _ = draw(&mut p, fb, mesh);
    let Ok(()) = fb.clear(Rgb565::BLACK);
    clear_depth(&mut p.depth);
    frame(&mut p, black_box(fb), black_box(mesh))
}

fn zb(z: &mut [u16], compare: Compare) -> DepthBuffer<'_> {
    DepthBuffer::new(z, WIDTH, HEIGHT, compare).expect("320 x 240 depth buffer")
}

fn clear_z(d: &mut DepthBuffer<'_>) {
    d.clear(u16::MAX);
}

fn no_z(_: &mut NoDepth) {}

fn model_path() -> PathBuf {
    // CARGO_MANIFEST_DIR is host-tools/: the repository's own assets first, then the shared ones
    // next to the repository.
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let local = manifest.join("../assets/models/suzanne.obj");
    if local.exists() {
        local
    } else {
        manifest.join("../../shared/assets/models/suzanne.obj")
    }
}

fn usage() -> ExitCode {
    eprintln!(
        "usage: count3d COMBINATION   one of: {}",
        COMBINATIONS.join(" ")
    );
    ExitCode::from(2)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [name] = args.as_slice() else {
        return usage();
    };
    let name = name.as_str();
    if !COMBINATIONS.contains(&name) {
        return usage();
    }
    let path = model_path();
    let loaded = match LoadedMesh::load(&path) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("count3d: {}: {e}", path.display());
            return ExitCode::FAILURE;
        }
    };
    if loaded.normals.is_none() {
        eprintln!("count3d: {} has no normals", path.display());
        return ExitCode::FAILURE;
    }
    let mesh = loaded.mesh();

    let xf = transforms();
    let vp = Viewport::new(WIDTH, HEIGHT);
    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Fb::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let mut zbuf = vec![u16::MAX; PIXELS].into_boxed_slice();
    let gouraud = || GouraudLit::<Fx16, Rgb565, 1>::new(lighting());
    let unlit = Unlit {
        color: Rgb565::from(DIFFUSE),
    };

    let stats = match name {
        "m1" => run(
            Pipeline::new(
                &xf,
                vp,
                CullClockwise,
                zb(&mut zbuf, Compare::Less),
                gouraud(),
            ),
            &mut fb,
            &mesh,
            clear_z,
            frame_m1,
        ),
        "m1_nodepth" => run(
            Pipeline::new(&xf, vp, CullClockwise, NoDepth, gouraud()),
            &mut fb,
            &mesh,
            no_z,
            frame_m1_nodepth,
        ),
        "m1_nocull" => run(
            Pipeline::new(&xf, vp, NoCull, zb(&mut zbuf, Compare::Less), gouraud()),
            &mut fb,
            &mesh,
            clear_z,
            frame_m1_nocull,
        ),
        "m1_unlit" => run(
            Pipeline::new(&xf, vp, CullClockwise, zb(&mut zbuf, Compare::Less), unlit),
            &mut fb,
            &mesh,
            clear_z,
            frame_m1_unlit,
        ),
        "m1_flat" => run(
            Pipeline::new(
                &xf,
                vp,
                CullClockwise,
                zb(&mut zbuf, Compare::Less),
                FlatLit::<Fx16, Rgb565, 1>::new(lighting()),
            ),
            &mut fb,
            &mesh,
            clear_z,
            frame_m1_flat,
        ),
        "m1_phong" => run(
            Pipeline::new(
                &xf,
                vp,
                CullClockwise,
                zb(&mut zbuf, Compare::Less),
                PhongLit::<Fx16, Rgb565, 1>::new(lighting()),
            ),
            &mut fb,
            &mesh,
            clear_z,
            frame_m1_phong,
        ),
        "m1_unlit_nodepth_nocull" => run(
            Pipeline::new(&xf, vp, NoCull, NoDepth, unlit),
            &mut fb,
            &mesh,
            no_z,
            frame_m1_unlit_nodepth_nocull,
        ),
        "m1_wireframe" => {
            let mut p = Pipeline::new(&xf, vp, CullClockwise, NoDepth, unlit);
            let Ok(_) = p.draw_wireframe(&mut fb, &mesh, Rgb565::WHITE);
            let Ok(()) = fb.clear(Rgb565::BLACK);
            frame_m1_wireframe(&mut p, black_box(&mut fb), black_box(&mesh))
        }
        "m1_cached" => {
            // One entry per mesh vertex, allocated outside the counted frame (the caller's RAM).
            let mut cache = vec![CachedVertex::default(); mesh.positions.len()];
            let mut p = Pipeline::new(
                &xf,
                vp,
                CullClockwise,
                zb(&mut zbuf, Compare::Less),
                gouraud(),
            );
            let Ok(_) = p.draw_cached(&mut fb, &mesh, &mut cache);
            let Ok(()) = fb.clear(Rgb565::BLACK);
            p.depth.clear(u16::MAX);
            frame_m1_cached(
                &mut p,
                black_box(&mut fb),
                black_box(&mesh),
                black_box(&mut cache),
            )
        }
        "m1_depth_always" => run(
            Pipeline::new(
                &xf,
                vp,
                CullClockwise,
                zb(&mut zbuf, Compare::Always),
                gouraud(),
            ),
            &mut fb,
            &mesh,
            clear_z,
            frame_m1_depth_always,
        ),
        "m1_cull_keepall" => run(
            Pipeline::new(&xf, vp, KeepAll, zb(&mut zbuf, Compare::Less), gouraud()),
            &mut fb,
            &mesh,
            clear_z,
            frame_m1_cull_keepall,
        ),
        band if band.starts_with("m1_band") => {
            let cached = band.ends_with("_cached");
            let rows: u32 = band
                .trim_start_matches("m1_band")
                .trim_end_matches("_cached")
                .parse()
                .unwrap_or(16);
            // The band's colour and depth rows, the bins and (for _cached) the vertex cache are
            // the caller's RAM, allocated outside the counted frame.
            let mut band_buf = vec![0u16; (WIDTH * rows) as usize];
            let mut band_z = vec![u16::MAX; (WIDTH * rows) as usize];
            let mut bins = vec![BinEntry::default(); mesh.triangles.len()];
            let mut cache =
                vec![CachedVertex::default(); if cached { mesh.positions.len() } else { 0 }];
            let mut p = Pipeline::new(
                &xf,
                vp,
                CullClockwise,
                DepthBuffer::new(&mut band_z, WIDTH, rows, Compare::Less).expect("band depth"),
                gouraud(),
            );
            let frame = match (rows, cached) {
                (8, _) => frame_m1_band8,
                (32, _) => frame_m1_band32,
                (240, _) => frame_m1_band240,
                (_, true) => frame_m1_band16_cached,
                _ => frame_m1_band16,
            };
            let _ = banded(
                &mut p,
                rows,
                &mut fb,
                &mesh,
                &mut band_buf,
                &mut bins,
                &mut cache,
            );
            let Ok(()) = fb.clear(Rgb565::BLACK);
            frame(
                &mut p,
                black_box(&mut fb),
                black_box(&mesh),
                &mut band_buf,
                &mut bins,
                &mut cache,
            )
        }
        _ => return usage(),
    };

    // Keep the frame alive and print a checksum, so that nothing can be optimised away.
    let sum = black_box(fb.as_slice())
        .iter()
        .fold(0u32, |s, &w| s.rotate_left(5) ^ u32::from(w));
    let RenderStats {
        triangles,
        invalid,
        outside,
        clipped,
        culled,
        drawn,
    } = stats;
    println!(
        "{name} triangles={triangles} drawn={drawn} culled={culled} clipped={clipped} \
         outside={outside} invalid={invalid} checksum={sum:08x}"
    );
    ExitCode::SUCCESS
}
