//! Draws one frame of the textured mesh scene M4 of `shared/bench/WORKLOADS.md` (Spot, 5,856
//! triangles, its 1024 x 1024 texture converted to Rgb565 ahead of time) for callgrind to count.
//! A program of its own, so that its frames do not change how `count3d`'s are compiled.
//!
//! `count3d_tex COMBINATION`, one of:
//!
//! | combination | shading | depth | culling |
//! |---|---|---|---|
//! | `m4` | `TexturedLit`, nearest texel, repeat (the default) | `DepthBuffer` (`Less`) | `CullClockwise` |
//! | `m4_bilinear` | `TexturedLit`, bilinear | `DepthBuffer` (`Less`) | `CullClockwise` |
//! | `m4_untextured` | `GouraudLit`, the same lighting | `DepthBuffer` (`Less`) | `CullClockwise` |
//!
//! The scene is `fixtures::scenes3d`'s M4 (the M1 camera and light, the model centred and scaled
//! to the unit sphere, smooth normals, a white diffuse colour). As in `count3d`, the mesh and
//! texture are loaded, the pipeline built and one warm frame drawn outside the counted
//! `frame_<COMBINATION>` function, with one vertex-scratch slot per vertex. Prints `COMBINATION
//! scene=M4 triangles=.. drawn=.. culled=.. clipped=.. outside=.. invalid=.. covered=..
//! checksum=..`.

use fixtures::scenes::{HEIGHT, PIXELS, WIDTH};
use fixtures::scenes3d::{transforms, Scene};
use rasterizer_core::pipeline::RenderStats;
use rasterizer_core::prelude::*;
use rasterizer_core::shade::Shading;
use std::hint::black_box;
use std::process::ExitCode;

const COMBINATIONS: [&str; 3] = ["m4", "m4_bilinear", "m4_untextured"];

type Fb<'a> = Framebuffer<'a, Rgb565>;
type Mesh3<'a> = Mesh<'a, Fx16, u32>;
type Pipe<'z, Sh> = Pipeline<Fx16, CullClockwise, DepthBuffer<'z>, Sh, 6>;
type Scratch<'a, Sh> = &'a mut [VertexSlot<<Sh as Shading<Fx16>>::Stored>];
type Textured<'t> = TexturedLit<'t, Fx16, Rgb565, 1>;
type Gouraud = GouraudLit<Fx16, Rgb565, 1>;

#[inline(always)]
fn draw<Sh: Shading<Fx16, Color = Rgb565>>(
    p: &mut Pipe<'_, Sh>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
    scratch: Scratch<'_, Sh>,
) -> RenderStats {
    p.draw(fb, mesh, scratch)
        .expect("the depth buffer covers the frame")
}

// One function per combination, each with its own name in `black_box` so that none is merged
// into another; `scripts/figures.sh` counts `*::frame_<COMBINATION>*`.
macro_rules! frame {
    ($name:ident: $shading:ty) => {
        #[inline(never)]
        fn $name(
            p: &mut Pipe<'_, $shading>,
            fb: &mut Fb<'_>,
            mesh: &Mesh3<'_>,
            scratch: Scratch<'_, $shading>,
        ) -> RenderStats {
            black_box(stringify!($name));
            draw(p, fb, mesh, scratch)
        }
    };
}

frame!(frame_m4: Textured<'_>);
frame!(frame_m4_bilinear: Textured<'_>);
frame!(frame_m4_untextured: Gouraud);

/// The warm frame, the clears and the counted frame.
fn run<Sh: Shading<Fx16, Color = Rgb565>>(
    mut p: Pipe<'_, Sh>,
    fb: &mut Fb<'_>,
    mesh: &Mesh3<'_>,
    frame: fn(&mut Pipe<'_, Sh>, &mut Fb<'_>, &Mesh3<'_>, Scratch<'_, Sh>) -> RenderStats,
) -> RenderStats {
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    let _ = draw(&mut p, fb, mesh, &mut scratch);
    let Ok(()) = fb.clear(Rgb565::BLACK);
    p.depth.clear(u16::MAX);
    frame(
        &mut p,
        black_box(fb),
        black_box(mesh),
        black_box(&mut scratch),
    )
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    // `--scene M4` is accepted for the same command line as count3d's.
    let name = match args.as_slice() {
        [s, m, name] if s == "--scene" && Scene::parse(m) == Some(Scene::M4) => name.as_str(),
        [name] => name.as_str(),
        _ => "",
    };
    if !COMBINATIONS.contains(&name) {
        eprintln!(
            "usage: count3d_tex [--scene M4] COMBINATION   one of: {}",
            COMBINATIONS.join(" ")
        );
        return ExitCode::from(2);
    }
    let scene = Scene::M4;
    let loaded = match scene.load() {
        Ok(m) => m,
        Err(e) => {
            eprintln!("count3d_tex: {}: {e}", scene.path().display());
            return ExitCode::FAILURE;
        }
    };
    let image = match scene.load_texture() {
        Ok(Some(t)) => t,
        Ok(None) => unreachable!("M4 is textured"),
        Err(e) => {
            eprintln!("count3d_tex: the texture: {e}");
            return ExitCode::FAILURE;
        }
    };
    let texture = match Texture::new(image.width_log2, image.height_log2, &image.texels) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("count3d_tex: the texture: {e}");
            return ExitCode::FAILURE;
        }
    };
    let mesh = loaded.mesh();
    let xf = transforms();
    let vp = Viewport::new(WIDTH, HEIGHT);
    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Fb::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let mut zbuf = vec![u16::MAX; PIXELS].into_boxed_slice();
    let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less).expect("depth buffer");
    let textured = TexturedLit::new(scene.lighting(), texture);
    let stats = match name {
        "m4" => run(
            Pipeline::new(&xf, vp, CullClockwise, depth, textured),
            &mut fb,
            &mesh,
            frame_m4,
        ),
        "m4_bilinear" => run(
            Pipeline::new(
                &xf,
                vp,
                CullClockwise,
                depth,
                textured.with_filter(Filter::Bilinear),
            ),
            &mut fb,
            &mesh,
            frame_m4_bilinear,
        ),
        _ => run(
            Pipeline::new(
                &xf,
                vp,
                CullClockwise,
                depth,
                Gouraud::new(scene.lighting()),
            ),
            &mut fb,
            &mesh,
            frame_m4_untextured,
        ),
    };
    let px = fb.as_slice();
    let sum = black_box(px)
        .iter()
        .fold(0u32, |s, &w| s.rotate_left(5) ^ u32::from(w));
    let covered = px.iter().filter(|&&w| w != 0).count();
    let RenderStats {
        triangles,
        invalid,
        outside,
        clipped,
        culled,
        drawn,
    } = stats;
    println!(
        "{name} scene=M4 triangles={triangles} drawn={drawn} culled={culled} clipped={clipped} \
         outside={outside} invalid={invalid} covered={covered} checksum={sum:08x}"
    );
    ExitCode::SUCCESS
}
