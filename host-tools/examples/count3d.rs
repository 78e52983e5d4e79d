//! Draws one frame of a mesh scene of `shared/bench/WORKLOADS.md` (M1 Suzanne, 968 triangles; M2
//! the Stanford bunny res3, 3,851; M3 the full Stanford bunny, 69,451) for callgrind to count, with
//! one combination of pipeline stages, or with the comparison renderer euc
//! (`scripts/callgrind3d.sh`).
//!
//! `count3d [--scene M1|M2|M3] COMBINATION`, one of the names below; the scene is M1 unless given.
//! The combination names are those of the M1 benchmark (`m1` is the headline pipeline, whatever the
//! scene): a combination is a pipeline type, the scene is data. The mesh is loaded, the pipeline
//! built and one warm frame drawn outside the counted function; the colour and depth buffers are
//! cleared outside it too. Then exactly one call of `frame_<COMBINATION>` draws the counted frame.
//! Every draw has a vertex scratch of one slot per mesh vertex (the caller's RAM, allocated outside
//! the count) except the `_noscratch` ones, whose empty scratch makes every triangle process its
//! vertices again. Every combination is its own monomorphized `Pipeline` type and its own `#[inline(never)]`
//! function; each function also hands its own name to `black_box`, so that no two of them are
//! identical and none can be merged into another (rustc runs LLVM's function merging).
//!
//! | combination | shading | depth | culling | draw |
//! |---|---|---|---|---|
//! | `m1` | `GouraudLit` | `DepthBuffer` (`Less`) | `CullClockwise` | `draw` |
//! | `m1_noscratch` | `GouraudLit` | `DepthBuffer` (`Less`) | `CullClockwise` | `draw`, empty scratch |
//! | `m1_nodepth` | `GouraudLit` | `NoDepth` | `CullClockwise` | `draw` |
//! | `m1_nocull` | `GouraudLit` | `DepthBuffer` (`Less`) | `NoCull` | `draw` |
//! | `m1_unlit` | `Unlit` | `DepthBuffer` (`Less`) | `CullClockwise` | `draw` |
//! | `m1_flat` | `FlatLit` | `DepthBuffer` (`Less`) | `CullClockwise` | `draw` |
//! | `m1_phong` | `PhongLit` | `DepthBuffer` (`Less`) | `CullClockwise` | `draw` |
//! | `m1_unlit_nodepth_nocull` | `Unlit` | `NoDepth` | `NoCull` | `draw` |
//! | `m1_wireframe` | - | - | `CullClockwise` | `draw_wireframe` |
//! | `m1_depth_always` | `GouraudLit` | `DepthBuffer` (`Always`) | `CullClockwise` | `draw` |
//! | `m1_cull_keepall` | `GouraudLit` | `DepthBuffer` (`Less`) | `KeepAll` (runtime "keep") | `draw` |
//! | `m1_band8` ... `m1_band240`, `m1_band16_noscratch` | `GouraudLit` | band `DepthBuffer` | `CullClockwise` | `draw_banded` |
//! | `m1_recip`, `m1_newton` | `GouraudLit` | `DepthBuffer` (`Less`) | `CullClockwise` | `draw` with `Divide::Reciprocal` / `Divide::Newton` |
//! | `euc` | euc 0.5.3, Gouraud in `f32` | `f32` buffer | back faces | `euc::Pipeline::draw` |
//!
//! `m1_depth_always` and `m1_cull_keepall` are the controls for "an effect turned off costs no more
//! than a pipeline built without it": `m1_depth_always` (depth effect present, doing nothing
//! useful) against `m1_nodepth`, and `m1_cull_keepall` (a culling stage that keeps everything,
//! decided at run time) against `m1_nocull`. `euc` draws the same scene with euc (see
//! `benches/support/euc3d.rs`) into a `u16` Rgb565 buffer with an `f32` depth buffer.
//!
//! The scenes (camera, projection, lighting, the meshes' normalisation) are those of
//! `fixtures::scenes3d`: model rotated 30° about Y; camera at (0, 0, 3) looking at the origin, up
//! +Y; 60° vertical field of view, aspect 4:3, near 0.1, far 100; 320 x 240 Rgb565. Lighting: one
//! directional white light from (1, 1, 1), ambient white, material ambient (40, 30, 30), diffuse
//! (220, 140, 80), specular white, shininess 16, Blinn-Phong, eye at (0, 0, 3) in world space.
//! `Unlit` draws (220, 140, 80); the wireframe is white.
//!
//! Prints `COMBINATION scene=.. triangles=.. drawn=.. culled=.. clipped=.. outside=.. invalid=..
//! covered=.. checksum=..` for the counted frame (`covered`: pixels not left black). For `euc`,
//! `drawn` and `culled` come from euc's own culling test run apart from the frame.
//!
//! `count3d [--scene S] compare [DIR]` draws the scene with `m1` and with euc and prints how far
//! the two pictures are apart (and writes them as PNG files into DIR when given); nothing is
//! counted. Its last line, `compare scene=.. ours_covered=.. euc_covered=.. both=.. ours_only=..
//! euc_only=.. mean_diff=.. max_diff=.. over_16=..`, holds the same figures for scripts.

#[path = "../benches/support/euc3d.rs"]
mod euc3d;

use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use euc3d::{EucColor, EucDepth, EucScene};
use fixtures::obj::LoadedMesh;
use fixtures::scenes::{HEIGHT, PIXELS, WIDTH};
use fixtures::scenes3d::{lighting, transforms, Scene, DIFFUSE};
use rasterizer_core::cull::Cull;
use rasterizer_core::depth::DepthTest;
use rasterizer_core::numerics::{Divide, Numerics, Standard};
use rasterizer_core::pipeline::RenderStats;
use rasterizer_core::prelude::*;
use rasterizer_core::shade::Shading;
use std::hint::black_box;
use std::path::Path;
use std::process::ExitCode;

/// Every combination, in the order the script reports them.
const COMBINATIONS: [&str; 19] = [
    "m1",
    "m1_noscratch",
    "m1_nodepth",
    "m1_nocull",
    "m1_unlit",
    "m1_flat",
    "m1_phong",
    "m1_unlit_nodepth_nocull",
    "m1_wireframe",
    "m1_depth_always",
    "m1_cull_keepall",
    "m1_band8",
    "m1_band16",
    "m1_band32",
    "m1_band240",
    "m1_band16_noscratch",
    "m1_recip",
    "m1_newton",
    "euc",
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
/// A 16.16 pipeline with 26.6 screen coordinates and affine interpolation.
type Pipe<C, D, Sh> = Pipeline<Fx16, C, D, Sh, 6>;
/// The vertex scratch of a shading model.
type Scratch<'a, Sh> = &'a mut [VertexSlot<<Sh as Shading<Fx16>>::Stored>];
/// A counted frame function.
type FrameFn<C, D, Sh, N = Standard> = for<'a> fn(
    &mut Pipeline<Fx16, C, D, Sh, 6, N>,
    &mut Fb<'_>,
    &Mesh3<'_>,
    Scratch<'a, Sh>,
) -> RenderStats;

/// The drawing of one frame, shared by the warm frame and the counted `frame_*` functions.
#[inline(always)]
fn draw<C: Cull, D: DepthTest, Sh: Shading<Fx16, Color = Rgb565>, N: Numerics>(
    p: &mut Pipeline<Fx16, C, D, Sh, 6, N>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
    scratch: Scratch<'_, Sh>,
) -> RenderStats {
    p.draw(fb, mesh, scratch)
        .expect("the depth buffer covers the frame")
}

// The counted frames: one per combination, each `#[inline(never)]` with its own name in
// `black_box`, so that no two are identical and none can be merged into another. The name is
// what `scripts/figures.sh` tells callgrind to count (`*::frame_<COMBINATION>*`).
macro_rules! frame {
    ($name:ident: $cull:ty, $depth:ty, $shading:ty) => {
        frame!($name: $cull, $depth, $shading, |p, fb, mesh, scratch| draw(p, fb, mesh, scratch));
    };
    ($name:ident: $cull:ty, $depth:ty, $shading:ty,
     |$p:ident, $fb:ident, $mesh:ident, $scratch:ident| $body:expr) => {
        #[inline(never)]
        fn $name(
            $p: &mut Pipe<$cull, $depth, $shading>,
            $fb: &mut Fb<'_>,
            $mesh: &Mesh3<'_>,
            $scratch: Scratch<'_, $shading>,
        ) -> RenderStats {
            black_box(stringify!($name));
            $body
        }
    };
}

type Gouraud = GouraudLit<Fx16, Rgb565, 1>;

frame!(frame_m1: CullClockwise, DepthBuffer<'_>, Gouraud);
frame!(frame_m1_noscratch: CullClockwise, DepthBuffer<'_>, Gouraud, |p, fb, mesh, _scratch| {
    draw(p, fb, mesh, &mut [])
});
frame!(frame_m1_nodepth: CullClockwise, NoDepth, Gouraud);
frame!(frame_m1_nocull: NoCull, DepthBuffer<'_>, Gouraud);
frame!(frame_m1_unlit: CullClockwise, DepthBuffer<'_>, Unlit<Rgb565>);
frame!(frame_m1_flat: CullClockwise, DepthBuffer<'_>, FlatLit<Fx16, Rgb565, 1>);
frame!(frame_m1_phong: CullClockwise, DepthBuffer<'_>, PhongLit<Fx16, Rgb565, 1>);
frame!(frame_m1_unlit_nodepth_nocull: NoCull, NoDepth, Unlit<Rgb565>);
frame!(frame_m1_wireframe: CullClockwise, NoDepth, Unlit<Rgb565>, |p, fb, mesh, scratch| {
    let Ok(stats) = p.draw_wireframe(fb, mesh, scratch, Rgb565::WHITE);
    stats
});
frame!(frame_m1_depth_always: CullClockwise, DepthBuffer<'_>, Gouraud);
frame!(frame_m1_cull_keepall: KeepAll, DepthBuffer<'_>, Gouraud);

/// `m1` with the divider-free divide methods.
struct RecipDivide;
impl Numerics for RecipDivide {
    const DIVIDE: Divide = Divide::Reciprocal;
}
struct NewtonDivide;
impl Numerics for NewtonDivide {
    const DIVIDE: Divide = Divide::Newton;
}

macro_rules! divide_frame {
    ($name:ident, $numerics:ty) => {
        #[inline(never)]
        fn $name(
            p: &mut Pipeline<Fx16, CullClockwise, DepthBuffer<'_>, Gouraud, 6, $numerics>,
            fb: &mut Fb<'_>,
            mesh: &Mesh3<'_>,
            scratch: Scratch<'_, Gouraud>,
        ) -> RenderStats {
            black_box(stringify!($name));
            draw(p, fb, mesh, scratch)
        }
    };
}
divide_frame!(frame_m1_recip, RecipDivide);
divide_frame!(frame_m1_newton, NewtonDivide);

type BandPipeline<'a> = Pipe<CullClockwise, DepthBuffer<'a>, Gouraud>;

/// One banded M1 frame: each finished band is copied into `fb` (where firmware would start the
/// display's DMA). The copy goes row by row: glibc copies a larger block with `rep movsb`,
/// which callgrind counts once per byte, far beyond what the copy costs any core.
#[inline(always)]
fn banded(
    p: &mut BandPipeline<'_>,
    rows: u32,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
    band: &mut [u16],
    bins: &mut [BinEntry],
    scratch: Scratch<'_, Gouraud>,
) -> RenderStats {
    let banding = Banding {
        width: WIDTH,
        height: HEIGHT,
        rows,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    let out = fb.as_mut_slice();
    let result = p.draw_banded(mesh, &banding, band, bins, scratch, |b| {
        let y0 = b.y0() as usize * WIDTH as usize;
        let data = b.framebuffer().as_slice();
        let w = WIDTH as usize;
        for (dst, src) in out[y0..y0 + data.len()]
            .chunks_exact_mut(w)
            .zip(data.chunks_exact(w))
        {
            // Opaque, so that the rows are not merged back into one block copy.
            dst.copy_from_slice(std::hint::black_box(src));
        }
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
            scratch: Scratch<'_, Gouraud>,
        ) -> RenderStats {
            black_box(stringify!($name));
            banded(p, $rows, fb, mesh, band, bins, scratch)
        }
    };
}

band_frame!(frame_m1_band8, 8);
band_frame!(frame_m1_band16, 16);
band_frame!(frame_m1_band32, 32);
band_frame!(frame_m1_band240, 240);
band_frame!(frame_m1_band16_noscratch, 16);

/// Builds a pipeline, draws the warm frame (not counted), clears both buffers (not counted) and
/// calls `frame` once for the counted frame.
fn run<C, D, Sh, N>(
    mut p: Pipeline<Fx16, C, D, Sh, 6, N>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
    frame: FrameFn<C, D, Sh, N>,
) -> RenderStats
where
    C: Cull,
    D: DepthTest + Clear,
    Sh: Shading<Fx16, Color = Rgb565>,
    N: Numerics,
{
    // One slot per mesh vertex, allocated outside the counted frame (the caller's RAM).
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let _ = draw(&mut p, fb, mesh, &mut scratch);
    let Ok(()) = fb.clear(Rgb565::BLACK);
    p.depth.clear_all();
    frame(
        &mut p,
        black_box(fb),
        black_box(mesh),
        black_box(&mut scratch),
    )
}

fn zb(z: &mut [u16], compare: Compare) -> DepthBuffer<'_> {
    DepthBuffer::new(z, WIDTH, HEIGHT, compare).expect("320 x 240 depth buffer")
}

/// Clearing a depth stage to the far plane between the warm and the counted frame.
trait Clear {
    fn clear_all(&mut self);
}

impl Clear for DepthBuffer<'_> {
    fn clear_all(&mut self) {
        self.clear(u16::MAX);
    }
}

impl Clear for NoDepth {
    fn clear_all(&mut self) {}
}

#[inline(never)]
fn frame_euc(scene: &EucScene, color: &mut EucColor, depth: &mut EucDepth) {
    black_box("frame_euc");
    scene.render(color, depth);
}

/// A checksum of a picture, so that the frame cannot be optimised away and runs can be compared.
fn checksum(px: &[u16]) -> u32 {
    black_box(px)
        .iter()
        .fold(0u32, |s, &w| s.rotate_left(5) ^ u32::from(w))
}

/// Pixels not left black (every lit colour of the scenes is at least the ambient term).
fn covered(px: &[u16]) -> usize {
    px.iter().filter(|&&w| w != 0).count()
}

fn rgb888(w: u16) -> [u8; 3] {
    let c = Rgb888::from(Rgb565::from(RawU16::new(w)));
    [c.r(), c.g(), c.b()]
}

/// Draws the scene with `m1` and with euc, prints how far apart the two pictures are and writes
/// them into `dir` as PNG files when given.
fn compare(scene: Scene, loaded: &LoadedMesh, dir: Option<&Path>) -> ExitCode {
    let mesh = loaded.mesh();
    let xf = transforms();
    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Fb::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let mut zbuf = vec![u16::MAX; PIXELS].into_boxed_slice();
    let mut p = Pipeline::new(
        &xf,
        Viewport::new(WIDTH, HEIGHT),
        CullClockwise,
        zb(&mut zbuf, Compare::Less),
        GouraudLit::<Fx16, Rgb565, 1>::new(lighting()),
    );
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let ours = draw(&mut p, &mut fb, &mesh, &mut scratch);
    let euc = EucScene::new(loaded);
    let (mut color, mut depth) = EucScene::buffers();
    euc.render(&mut color, &mut depth);
    let (euc_drawn, euc_culled) = euc.stats();
    let (a, b) = (fb.as_slice(), color.as_ref());
    let (mut only_ours, mut only_euc, mut both, mut sum, mut max, mut off2) = (0, 0, 0, 0u64, 0, 0);
    for (&x, &y) in a.iter().zip(b) {
        match (x != 0, y != 0) {
            (true, false) => only_ours += 1,
            (false, true) => only_euc += 1,
            (true, true) => {
                both += 1;
                let d = (0..3)
                    .map(|k| rgb888(x)[k].abs_diff(rgb888(y)[k]))
                    .max()
                    .unwrap_or(0);
                sum += u64::from(d);
                max = max.max(d);
                off2 += usize::from(d > 16);
            }
            (false, false) => {}
        }
    }
    println!(
        "{} ours: drawn={} culled={} covered={}; euc: drawn={euc_drawn} culled={euc_culled} \
         covered={}",
        scene.name(),
        ours.drawn,
        ours.culled,
        covered(a),
        covered(b)
    );
    println!(
        "pixels covered by both {both}, by ours only {only_ours}, by euc only {only_euc}; \
         largest channel difference where both: mean {:.2}, max {max} (8-bit steps), \
         {off2} pixels more than 16 apart",
        sum as f64 / both.max(1) as f64
    );
    // The same figures in one line of key=value pairs, for scripts/figures.sh.
    println!(
        "compare scene={} ours_covered={} euc_covered={} both={both} ours_only={only_ours} \
         euc_only={only_euc} mean_diff={:.2} max_diff={max} over_16={off2}",
        scene.name(),
        covered(a),
        covered(b),
        sum as f64 / both.max(1) as f64
    );
    if let Some(dir) = dir {
        for (who, px) in [("ours", a), ("euc", b)] {
            let img = image::RgbImage::from_fn(WIDTH, HEIGHT, |x, y| {
                image::Rgb(rgb888(px[(y * WIDTH + x) as usize]))
            });
            let path = dir.join(format!("{}-{who}.png", scene.name()));
            if let Err(e) = img.save(&path) {
                eprintln!("count3d: {}: {e}", path.display());
                return ExitCode::FAILURE;
            }
        }
    }
    ExitCode::SUCCESS
}

fn usage() -> ExitCode {
    eprintln!(
        "usage: count3d [--scene M1|M2|M3] COMBINATION   one of: {}\n       \
         count3d [--scene M1|M2|M3] compare [DIR]",
        COMBINATIONS.join(" ")
    );
    ExitCode::from(2)
}

fn main() -> ExitCode {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut scene = Scene::M1;
    if args.first().map(String::as_str) == Some("--scene") {
        let Some(s) = args.get(1).and_then(|s| Scene::parse(s)) else {
            return usage();
        };
        scene = s;
        args.drain(..2);
    }
    let (name, dir) = match args.as_slice() {
        [c] if c == "compare" => ("compare", None),
        [c, dir] if c == "compare" => ("compare", Some(Path::new(dir))),
        [name] if COMBINATIONS.contains(&name.as_str()) => (name.as_str(), None),
        _ => return usage(),
    };
    let loaded = match scene.load() {
        Ok(m) => m,
        Err(e) => {
            eprintln!("count3d: {}: {e}", scene.path().display());
            return ExitCode::FAILURE;
        }
    };
    if name == "compare" {
        return compare(scene, &loaded, dir);
    }
    let scene_name = scene.name();
    if name == "euc" {
        // The scene in f32 and both buffers are set up, and one warm frame drawn, outside the count.
        let euc = EucScene::new(&loaded);
        let (mut color, mut depth) = EucScene::buffers();
        euc.render(&mut color, &mut depth);
        EucScene::clear(&mut color, &mut depth);
        frame_euc(
            black_box(&euc),
            black_box(&mut color),
            black_box(&mut depth),
        );
        let (drawn, culled) = euc.stats();
        let px = color.as_ref();
        println!(
            "euc scene={scene_name} triangles={} drawn={drawn} culled={culled} covered={} \
             checksum={:08x}",
            euc.triangles(),
            covered(px),
            checksum(px)
        );
        return ExitCode::SUCCESS;
    }
    let mesh = loaded.mesh();

    let xf = transforms();
    let vp = Viewport::new(WIDTH, HEIGHT);
    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Fb::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let mut zbuf = vec![u16::MAX; PIXELS].into_boxed_slice();
    let gouraud = || Gouraud::new(lighting());
    let flat = || FlatLit::<Fx16, Rgb565, 1>::new(lighting());
    let phong = || PhongLit::<Fx16, Rgb565, 1>::new(lighting());
    let unlit = Unlit {
        color: Rgb565::from(DIFFUSE),
    };

    // A pipeline of the given stages, counted through `run`.
    macro_rules! count {
        ($cull:expr, $depth:expr, $shading:expr, $frame:expr) => {
            run(
                Pipeline::new(&xf, vp, $cull, $depth, $shading),
                &mut fb,
                &mesh,
                $frame,
            )
        };
    }
    let less = |z| zb(z, Compare::Less);
    let stats = match name {
        "m1" => count!(CullClockwise, less(&mut zbuf), gouraud(), frame_m1),
        "m1_noscratch" => count!(
            CullClockwise,
            less(&mut zbuf),
            gouraud(),
            frame_m1_noscratch
        ),
        "m1_nodepth" => count!(CullClockwise, NoDepth, gouraud(), frame_m1_nodepth),
        "m1_nocull" => count!(NoCull, less(&mut zbuf), gouraud(), frame_m1_nocull),
        "m1_unlit" => count!(CullClockwise, less(&mut zbuf), unlit, frame_m1_unlit),
        "m1_flat" => count!(CullClockwise, less(&mut zbuf), flat(), frame_m1_flat),
        "m1_phong" => count!(CullClockwise, less(&mut zbuf), phong(), frame_m1_phong),
        "m1_unlit_nodepth_nocull" => count!(NoCull, NoDepth, unlit, frame_m1_unlit_nodepth_nocull),
        "m1_wireframe" => {
            let mut p = Pipeline::new(&xf, vp, CullClockwise, NoDepth, unlit);
            let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
            let Ok(_) = p.draw_wireframe(&mut fb, &mesh, &mut scratch, Rgb565::WHITE);
            let Ok(()) = fb.clear(Rgb565::BLACK);
            frame_m1_wireframe(
                &mut p,
                black_box(&mut fb),
                black_box(&mesh),
                black_box(&mut scratch),
            )
        }
        "m1_depth_always" => {
            let z = zb(&mut zbuf, Compare::Always);
            count!(CullClockwise, z, gouraud(), frame_m1_depth_always)
        }
        "m1_cull_keepall" => count!(KeepAll, less(&mut zbuf), gouraud(), frame_m1_cull_keepall),
        "m1_recip" => run(
            Pipeline::new(&xf, vp, CullClockwise, less(&mut zbuf), gouraud())
                .with_numerics::<RecipDivide>(),
            &mut fb,
            &mesh,
            frame_m1_recip,
        ),
        "m1_newton" => run(
            Pipeline::new(&xf, vp, CullClockwise, less(&mut zbuf), gouraud())
                .with_numerics::<NewtonDivide>(),
            &mut fb,
            &mesh,
            frame_m1_newton,
        ),
        band if band.starts_with("m1_band") => {
            let noscratch = band.ends_with("_noscratch");
            let rows: u32 = band
                .trim_start_matches("m1_band")
                .trim_end_matches("_noscratch")
                .parse()
                .unwrap_or(16);
            // The band's colour and depth rows, the bins and the vertex scratch (none for
            // _noscratch) are the caller's RAM, allocated outside the counted frame.
            let mut band_buf = vec![0u16; (WIDTH * rows) as usize];
            let mut band_z = vec![u16::MAX; (WIDTH * rows) as usize];
            let mut bins = vec![BinEntry::default(); mesh.triangles.len()];
            let slots = if noscratch { 0 } else { mesh.positions.len() };
            let mut cache = vec![VertexSlot::EMPTY; slots];
            let mut p = Pipeline::new(
                &xf,
                vp,
                CullClockwise,
                DepthBuffer::new(&mut band_z, WIDTH, rows, Compare::Less).expect("band depth"),
                gouraud(),
            );
            let frame = match (rows, noscratch) {
                (8, _) => frame_m1_band8,
                (32, _) => frame_m1_band32,
                (240, _) => frame_m1_band240,
                (_, true) => frame_m1_band16_noscratch,
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
    let px = fb.as_slice();
    let (sum, covered) = (checksum(px), covered(px));
    let RenderStats {
        triangles,
        invalid,
        outside,
        clipped,
        culled,
        drawn,
    } = stats;
    println!(
        "{name} scene={scene_name} triangles={triangles} drawn={drawn} culled={culled} \
         clipped={clipped} outside={outside} invalid={invalid} covered={covered} checksum={sum:08x}"
    );
    ExitCode::SUCCESS
}
