//! What the fogged M1 counting programs (`count3d_fog`, `count3d_fog_phong`) share: the scene,
//! the fog, the pipeline, the warm frame and the printed line. Each program keeps its counted
//! frame function of its own, so callgrind's `--toggle-collect` finds it by name.

use embedded_graphics::pixelcolor::Rgb565;
use fixtures::scenes::{HEIGHT, PIXELS, WIDTH};
use fixtures::scenes3d::{lighting, transforms, Scene};
use rasterizer_core::math::Mat4;
use rasterizer_core::pipeline::RenderStats;
use rasterizer_core::prelude::*;
use rasterizer_core::shade::{Fog, FogCurve, FogSettings, Foggable, Shading};
use std::hint::black_box;
use std::process::ExitCode;

/// The pipeline of a fogged M1 frame around the lit model `Sh`.
pub type Pipe<'z, Sh> = Pipeline<Fx16, CullClockwise, DepthBuffer<'z>, Fog<Fx16, Sh>, 6>;

/// The vertex scratch of that pipeline.
pub type Slots<Sh> = [VertexSlot<<Fog<Fx16, Sh> as Shading<Fx16>>::Stored>];

/// Loads M1, builds the `m1` pipeline with `make(lighting)` wrapped in linear fog from depth 2
/// to 4 towards grey-blue, draws a warm frame, then the counted one through `frame`, and prints
/// `LABEL scene=M1 triangles=.. drawn=.. culled=.. covered=.. checksum=..`. `program` names the
/// program in an error line.
pub fn run<Sh>(
    program: &str,
    label: &str,
    make: impl FnOnce(Lighting<Fx16, 1>) -> Sh,
    frame: impl FnOnce(
        &mut Pipe<'_, Sh>,
        &mut Framebuffer<'_, Rgb565>,
        &Mesh<'_, Fx16, u32>,
        &mut Slots<Sh>,
    ) -> RenderStats,
) -> ExitCode
where
    Sh: Foggable<Fx16, Color = Rgb565>,
{
    let loaded = match Scene::M1.load() {
        Ok(m) => m,
        Err(e) => {
            eprintln!("{program}: {}: {e}", Scene::M1.path().display());
            return ExitCode::FAILURE;
        }
    };
    let mesh = loaded.mesh();
    let xf = transforms();
    let mut buf = vec![0u16; PIXELS].into_boxed_slice();
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, WIDTH, HEIGHT).expect("320 x 240 buffer");
    let mut zbuf = vec![u16::MAX; PIXELS].into_boxed_slice();
    let settings = FogSettings {
        color: Rgb888::new(128, 144, 160),
        start: Fx16::from_int(2),
        end: Fx16::from_int(4),
        curve: FogCurve::Linear,
    };
    let view: &Mat4<Fx16> = &xf.view;
    let shading = Fog::new(make(lighting()), settings, view);
    let depth = DepthBuffer::new(&mut zbuf, WIDTH, HEIGHT, Compare::Less).expect("depth buffer");
    let mut p = Pipeline::new(
        &xf,
        Viewport::new(WIDTH, HEIGHT),
        CullClockwise,
        depth,
        shading,
    );
    let mut scratch = vec![VertexSlot::EMPTY; mesh.positions.len()];
    // The warm frame, outside the counted function.
    let _ = p.draw(&mut fb, &mesh, &mut scratch);
    let Ok(()) = fb.clear(Rgb565::BLACK);
    p.depth.clear(u16::MAX);
    let stats = frame(
        &mut p,
        black_box(&mut fb),
        black_box(&mesh),
        black_box(&mut scratch),
    );
    let px = fb.as_slice();
    let covered = px.iter().filter(|&&w| w != 0).count();
    let checksum = px
        .iter()
        .fold(0u32, |s, &w| s.rotate_left(5) ^ u32::from(w));
    println!(
        "{label} scene=M1 triangles={} drawn={} culled={} covered={covered} checksum={checksum:08x}",
        stats.triangles, stats.drawn, stats.culled
    );
    ExitCode::SUCCESS
}
