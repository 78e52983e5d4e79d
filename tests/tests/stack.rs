//! Peak stack of every render call, measured by painting the stack, and the RAM each configuration
//! needs besides (framebuffer, depth buffer, band buffers, bins, vertex scratch), for
//! `docs/MEMORY.md` (`scripts/memory.sh` collects the `MEMORY` lines this test prints).
//!
//! # Method
//!
//! Each configuration runs in a fresh thread with a [`THREAD_STACK`]-byte stack. There, the
//! scene is built, the render call is made once as a warm-up, the buffers are reset, and then
//! [`measure`]:
//!
//! 1. reads the stack pointer and fills the [`PAINT`] bytes below it with [`PATTERN`] (one
//!    `rep stosq`, so the painting itself writes nothing else on the stack);
//! 2. calls the render call through an `#[inline(never)]` function;
//! 3. scans the painted region from its lowest address up for the first byte that differs from
//!    the pattern: the distance from the stack pointer of step 1 to that byte is the peak stack
//!    of the call. It includes the harness's own two call frames (the `#[inline(never)]`
//!    trampoline and the closure), which [`self_check`] measures on its own (`noop`).
//!
//! The measurement is checked: a deepest byte at the very bottom of the painted region means the
//! call may have gone further, and fails the test; [`self_check`] shows that a function with a
//! 4 KB local array is measured at 4 KB plus a small tolerance, and that a region too small for it
//! is reported as overflowed rather than as a figure.
//!
//! # Bounds
//!
//! Every configuration has an upper bound ([`BOUNDS`]): the figure measured when the bound was
//! set, times 1.5, rounded up to 64 bytes. The margin absorbs compiler-version drift; a real
//! regression (a new large local, lost inlining that stacks frames, recursion) fails the test, and
//! a deliberate change updates the table. `cargo test` (debug) and `cargo test --release` use the
//! column of their own build, since an unoptimised build keeps every temporary on the stack and
//! needs several times more. `docs/MEMORY.md` gives the release figures.
//!
//! This is the stack of the host's x86-64 build (the only target installed here): a Cortex-M
//! build will differ (32-bit pointers and registers shrink frames; 64-bit arithmetic needs
//! register pairs and can spill more), so treat the figures as an estimate for firmware and
//! re-measure on the target (e.g. by painting its stack the same way).
//!
//! Run `cargo test -p tests --test stack -- --nocapture` to see the figures.
#![cfg(target_arch = "x86_64")]
// Stack painting writes below the stack pointer and reads the bytes back: only inline assembly
// and raw pointers can do that, so this one test file allows `unsafe` (the library denies it).
#![allow(unsafe_code)]

use core::hint::black_box;
use core::mem::size_of;
use rasterizer_core::cull::Cull;
use rasterizer_core::depth::DepthTest;
use rasterizer_core::pipeline::{BandError, RenderStats};
use rasterizer_core::prelude::*;
use rasterizer_core::shade::Shading;

/// The stack of each measuring thread.
const THREAD_STACK: usize = 4 << 20;
/// Bytes painted below the stack pointer: far more than any render call needs, even unoptimised.
const PAINT: usize = 1 << 20;
/// The paint: no byte of it is 0x00 or 0xff, the likeliest values for a call to write.
const PATTERN: u64 = 0xA5C3_5A3C_96E1_7BD2;

/// The M1 scene's screen.
const W: u32 = 320;
const H: u32 = 240;
/// Rows per band for `draw_banded`.
const BAND_ROWS: u32 = 16;
/// Suzanne, converted on the host: what firmware embeds (and what `nostd-check` links).
static SUZANNE: &[u8] = include_bytes!("../../assets/meshes/suzanne.rmsh");

/// Upper bounds on the peak stack in bytes: (configuration, debug build, release build). Each is
/// the figure measured (rustc 1.95.0) times 1.5, rounded up to 64 bytes; see the module
/// documentation. The 2D primitives were measured on 2026-11-22 with rasterizer-core of commit
/// ca08cce, the 3D configurations on 2026-11-24 with edc64e5 (the vertex scratch and the fused span
/// loop: about half the stack of the draws before it); the triangle's release figure on 2026-11-27
/// (612 bytes: a large triangle's fill and a tall one's, with its fixed-point edge walks, out of
/// line).
const BOUNDS: &[(&str, usize, usize)] = &[
    ("line", 3136, 768),
    ("triangle", 10560, 960),
    ("gouraud_triangle", 13056, 1088),
    ("polygon", 6208, 1728),
    ("flat_depth_cull_draw", 36928, 2880),
    ("flat_depth_nocull_draw", 36928, 2880),
    ("flat_nodepth_cull_draw", 26944, 2496),
    ("flat_nodepth_nocull_draw", 26944, 2496),
    ("flat_depth_cull_noscratch", 36928, 2880),
    ("flat_depth_nocull_noscratch", 36928, 2880),
    ("flat_nodepth_cull_noscratch", 26944, 2496),
    ("flat_nodepth_nocull_noscratch", 26944, 2496),
    ("flat_depth_cull_banded16", 40832, 3328),
    ("flat_depth_nocull_banded16", 40832, 3328),
    ("flat_nodepth_cull_banded16", 29952, 3008),
    ("flat_nodepth_nocull_banded16", 29952, 3008),
    ("gouraud_depth_cull_draw", 36480, 3392),
    ("gouraud_depth_nocull_draw", 36480, 3392),
    ("gouraud_nodepth_cull_draw", 27520, 3712),
    ("gouraud_nodepth_nocull_draw", 27520, 3712),
    ("gouraud_depth_cull_noscratch", 36480, 3392),
    ("gouraud_depth_nocull_noscratch", 36480, 3392),
    ("gouraud_nodepth_cull_noscratch", 27520, 3712),
    ("gouraud_nodepth_nocull_noscratch", 27520, 3712),
    ("gouraud_depth_cull_banded16", 41088, 3776),
    ("gouraud_depth_nocull_banded16", 41088, 3776),
    ("gouraud_nodepth_cull_banded16", 31104, 4032),
    ("gouraud_nodepth_nocull_banded16", 31104, 4096),
    ("gouraud_depth_cull_banded16_noscratch", 41088, 3776),
    ("unlit_depth_cull_draw", 30848, 1920),
    ("unlit_depth_nocull_draw", 30848, 1920),
    ("unlit_nodepth_cull_draw", 20864, 1536),
    ("unlit_nodepth_nocull_draw", 20864, 1536),
    ("unlit_depth_cull_noscratch", 30848, 1920),
    ("unlit_depth_nocull_noscratch", 30848, 1920),
    ("unlit_nodepth_cull_noscratch", 20864, 1536),
    ("unlit_nodepth_nocull_noscratch", 20864, 1536),
    ("unlit_depth_cull_banded16", 36416, 2432),
    ("unlit_depth_nocull_banded16", 36416, 2432),
    ("unlit_nodepth_cull_banded16", 25600, 2112),
    ("unlit_nodepth_nocull_banded16", 25600, 2112),
    ("phong_depth_cull_draw", 40000, 3648),
    ("phong_depth_nocull_draw", 40000, 3648),
    ("phong_nodepth_cull_draw", 29632, 3712),
    ("phong_nodepth_nocull_draw", 29632, 3648),
    ("phong_depth_cull_noscratch", 40000, 3648),
    ("phong_depth_nocull_noscratch", 40000, 3648),
    ("phong_nodepth_cull_noscratch", 29632, 3712),
    ("phong_nodepth_nocull_noscratch", 29632, 3648),
    ("phong_depth_cull_banded16", 44096, 4096),
    ("phong_depth_nocull_banded16", 44096, 4032),
    ("phong_nodepth_cull_banded16", 32704, 4096),
    ("phong_nodepth_nocull_banded16", 32704, 4096),
    // Workload S1 through the frame list, measured 2026-11-26 (debug 24,928 and 25,216, release
    // 6,392 and 6,424): the list's slots, both mesh commands and their pipelines are on the stack.
    ("s1_band16", 37440, 9600),
    ("s1_band16x2", 37824, 9664),
];

/// Why a measurement is not a figure.
#[derive(Debug, PartialEq, Eq)]
enum MeasureError {
    /// The lowest painted byte was overwritten: the call may have used more than the region.
    Overflowed,
}

/// Paints `paint` bytes below the stack pointer, calls `render` through an `#[inline(never)]`
/// trampoline and returns how far below that stack pointer the deepest overwritten byte lies.
#[inline(never)]
fn measure(paint: usize, render: &mut dyn FnMut()) -> Result<usize, MeasureError> {
    assert!(paint.is_multiple_of(8) && paint >= 64);
    let sp: usize;
    // SAFETY: the `paint` bytes below the stack pointer belong to this thread's stack (the thread
    // was created with `THREAD_STACK` bytes, several times `PAINT`, and this runs near its top)
    // and hold nothing live: everything of this frame and its callers is at or above the stack
    // pointer, and this function calls others, so it keeps nothing in the red zone either.
    // `rep stosq` writes forwards (the ABI guarantees a clear direction flag) and touches no
    // other memory.
    unsafe {
        core::arch::asm!(
            "mov {sp}, rsp",
            "mov rdi, {sp}",
            "sub rdi, rcx",
            "shr rcx, 3",
            "rep stosq",
            sp = out(reg) sp,
            inout("rcx") paint => _,
            out("rdi") _,
            in("rax") PATTERN,
        );
    }
    trampoline(render);
    let low = sp - paint;
    let words = low as *const u64;
    let mut i = 0;
    // SAFETY: the same painted region, read back; it is still this thread's stack, and bytes
    // below the stack pointer may be read (they are plain memory, possibly just written).
    let word = |i: usize| unsafe { words.add(i).read_volatile() };
    while i < paint / 8 && word(i) == PATTERN {
        i += 1;
    }
    if i == 0 {
        return Err(MeasureError::Overflowed);
    }
    if i == paint / 8 {
        // Nothing written at all (cannot happen: the trampoline's call stores a return address).
        return Ok(0);
    }
    // Little-endian: the lowest-addressed byte of a word is its least significant one.
    let byte = ((word(i) ^ PATTERN).trailing_zeros() / 8) as usize;
    Ok(sp - (low + 8 * i + byte))
}

/// The call under measurement, never inlined into [`measure`].
#[inline(never)]
fn trampoline(render: &mut dyn FnMut()) {
    render();
}

/// Runs `f` in a fresh thread with a [`THREAD_STACK`]-byte stack.
fn on_fresh_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(THREAD_STACK)
        .spawn(f)
        .expect("spawn a measuring thread")
        .join()
        .expect("measuring thread")
}

/// Warm-up call, reset, then the measured call.
fn peak(render: &mut dyn FnMut(), reset: &mut dyn FnMut()) -> usize {
    render();
    reset();
    match measure(PAINT, render) {
        Ok(bytes) => bytes,
        Err(e) => panic!("stack measurement failed: {e:?} ({PAINT} bytes painted)"),
    }
}

// --- Self-check of the method ---

/// Nothing: the harness's own frames.
#[inline(never)]
fn noop() {
    black_box(());
}

/// A function with 4 KB of locals that it really writes (`black_box` makes the array escape).
#[inline(never)]
fn four_kb() {
    let mut a = [0u8; 4096];
    black_box(&mut a);
}

#[test]
fn self_check() {
    let (base, big, small_region) = on_fresh_stack(|| {
        let base = measure(PAINT, &mut || noop()).unwrap();
        let big = measure(PAINT, &mut || four_kb()).unwrap();
        let small_region = measure(1024, &mut || four_kb());
        (base, big, small_region)
    });
    println!("MEMORY selfcheck noop={base} four_kb={big}");
    // The harness costs a few call frames; an unoptimised build keeps a little more per frame.
    assert!(base > 0 && base < 512, "noop measured at {base} bytes");
    // The array and the harness, nothing missed and little added.
    assert!(
        (4096..4096 + 1024).contains(&big),
        "a 4096-byte array measured at {big} bytes"
    );
    assert_eq!(small_region, Err(MeasureError::Overflowed));
}

// --- The scene ---

// The M1 scene's matrices and lighting, shared with the benchmarks.
use fixtures::scenes3d::{lighting, transforms, DIFFUSE};

/// How the frame is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// `draw` into a whole 320 x 240 framebuffer, with one scratch slot per mesh vertex.
    Draw,
    /// `draw` with an empty scratch (every vertex processed by each triangle that uses it).
    NoScratch,
    /// `draw_banded` in 16-row bands, with one scratch slot per mesh vertex.
    Banded,
    /// `draw_banded` in 16-row bands, with an empty scratch.
    BandedNoScratch,
}

impl Mode {
    fn name(self) -> &'static str {
        match self {
            Mode::Draw => "draw",
            Mode::NoScratch => "noscratch",
            Mode::Banded => "banded16",
            Mode::BandedNoScratch => "banded16_noscratch",
        }
    }

    /// Whether the draw gets a scratch slot per mesh vertex.
    fn scratch(self) -> bool {
        matches!(self, Mode::Draw | Mode::Banded)
    }
}

type Pipe<C, D, Sh> = Pipeline<Fx16, C, D, Sh>;
type Slot<Sh> = VertexSlot<<Sh as Shading<Fx16>>::Stored>;

#[inline(never)]
fn render_draw<C: Cull, D: DepthTest, Sh: Shading<Fx16, Color = Rgb565>>(
    p: &mut Pipe<C, D, Sh>,
    fb: &mut Framebuffer<'_, Rgb565>,
    mesh: &PackedMesh<'_>,
    scratch: &mut [Slot<Sh>],
) -> RenderStats {
    p.draw(fb, mesh, scratch)
        .expect("the depth buffer covers the frame")
}

/// A banded frame; each finished band is handed to `black_box`, where firmware would start the
/// display's DMA.
#[inline(never)]
fn render_banded<C: Cull, D: DepthTest, Sh: Shading<Fx16, Color = Rgb565>>(
    p: &mut Pipe<C, D, Sh>,
    mesh: &PackedMesh<'_>,
    band: &mut [u16],
    bins: &mut [BinEntry],
    scratch: &mut [Slot<Sh>],
) -> Result<RenderStats, BandError> {
    let banding = Banding {
        width: W,
        height: H,
        rows: BAND_ROWS,
        background: Rgb565::BLACK,
        clear_depth: u16::MAX,
    };
    p.draw_banded(mesh, &banding, band, bins, scratch, |b| {
        black_box(b.framebuffer().as_slice());
    })
}

/// One configuration's figures, in bytes.
#[derive(Debug, Default)]
struct Figures {
    name: String,
    stack: usize,
    framebuffer: usize,
    depth: usize,
    band: usize,
    band_depth: usize,
    bins: usize,
    visible: usize,
    scratch: usize,
    slot: usize,
    pipeline: usize,
    drawn: u32,
}

impl Figures {
    /// The line `scripts/memory.sh` reads.
    fn line(&self) -> String {
        format!(
            "MEMORY {} stack={} framebuffer={} depth={} band={} band_depth={} bins={} \
             visible={} scratch={} slot={} pipeline={} drawn={}",
            self.name,
            self.stack,
            self.framebuffer,
            self.depth,
            self.band,
            self.band_depth,
            self.bins,
            self.visible,
            self.scratch,
            self.slot,
            self.pipeline,
            self.drawn,
        )
    }
}

/// Words of an Rgb565 framebuffer of `rows` rows, and its bytes.
fn rgb565_bytes(rows: u32) -> (usize, usize) {
    let words = Framebuffer::<Rgb565>::required_len(W, rows).unwrap();
    (words, words * size_of::<u16>())
}

/// Builds the M1 pipeline with the given stages and measures one render call in `mode`.
fn run<C, D, Sh>(cull: C, depth: D, shading: Sh, mode: Mode, depth_rows: u32) -> Figures
where
    C: Cull,
    D: DepthTest,
    Sh: Shading<Fx16, Color = Rgb565>,
{
    let mesh = PackedMesh::parse(SUZANNE).expect("packed Suzanne");
    let xf = transforms();
    let mut p = Pipe::new(&xf, Viewport::new(W, H), cull, depth, shading);
    let uses_depth = D::ENABLED;
    let mut fig = Figures {
        pipeline: size_of::<Pipe<C, D, Sh>>(),
        slot: size_of::<Slot<Sh>>(),
        depth: if uses_depth {
            depth_rows as usize * W as usize * size_of::<u16>()
        } else {
            0
        },
        ..Figures::default()
    };
    let vertices = mesh.vertices();
    let mut scratch = vec![Slot::<Sh>::EMPTY; if mode.scratch() { vertices } else { 0 }];
    fig.scratch = scratch.len() * size_of::<Slot<Sh>>();
    let mut drawn = 0;
    match mode {
        Mode::Draw | Mode::NoScratch => {
            let (words, bytes) = rgb565_bytes(H);
            fig.framebuffer = bytes;
            let mut buf = vec![0u16; words];
            let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
            let cell = core::cell::RefCell::new((&mut p, &mut fb, &mut scratch));
            fig.stack = peak(
                &mut || {
                    let mut g = cell.borrow_mut();
                    let (p, fb, scratch) = &mut *g;
                    let stats = render_draw(p, fb, &mesh, scratch);
                    drawn = black_box(stats).drawn;
                },
                &mut || {
                    let mut g = cell.borrow_mut();
                    g.1.clear(Rgb565::BLACK).unwrap();
                    g.0.depth.start_band(0, u16::MAX);
                },
            );
        }
        Mode::Banded | Mode::BandedNoScratch => {
            let (words, bytes) = rgb565_bytes(BAND_ROWS);
            fig.band = bytes;
            fig.band_depth = fig.depth;
            fig.depth = 0;
            let mut band = vec![0u16; words];
            // Exactly as many bins as the frame has visible triangles: a draw without bins says.
            let visible = match render_banded(&mut p, &mesh, &mut band, &mut [], &mut scratch) {
                Err(BandError::TooFewBins { needed, .. }) => needed,
                other => panic!("expected TooFewBins, got {other:?}"),
            };
            fig.visible = visible;
            fig.bins = visible * size_of::<BinEntry>();
            let mut bins = vec![BinEntry::default(); visible];
            fig.stack = peak(
                &mut || {
                    let stats = render_banded(&mut p, &mesh, &mut band, &mut bins, &mut scratch);
                    drawn = black_box(stats.unwrap()).drawn;
                },
                // Each band starts from the background and a cleared depth buffer.
                &mut || {},
            );
        }
    }
    fig.drawn = drawn;
    fig
}

/// Measures one configuration in its own thread.
fn config<C, Sh>(
    name: &str,
    cull: impl FnOnce() -> C + Send + 'static,
    shading: impl FnOnce() -> Sh + Send + 'static,
    depth: bool,
    mode: Mode,
) -> Figures
where
    C: Cull,
    Sh: Shading<Fx16, Color = Rgb565>,
{
    let mut fig = on_fresh_stack(move || {
        let rows = match mode {
            Mode::Draw | Mode::NoScratch => H,
            Mode::Banded | Mode::BandedNoScratch => BAND_ROWS,
        };
        let mut z = vec![u16::MAX; (W * rows) as usize];
        if depth {
            let d = DepthBuffer::new(&mut z, W, rows, Compare::Less).unwrap();
            run(cull(), d, shading(), mode, rows)
        } else {
            run(cull(), NoDepth, shading(), mode, rows)
        }
    });
    fig.name = name.to_string();
    fig
}

/// The bound of a configuration for this build.
fn bound(name: &str) -> Option<usize> {
    BOUNDS
        .iter()
        .find(|b| b.0 == name)
        .map(|b| if cfg!(debug_assertions) { b.1 } else { b.2 })
}

/// Prints the figures and checks each against its bound (all printed before any failure).
fn report(figures: &[Figures]) {
    let mut failures = Vec::new();
    let mut out = String::new();
    for f in figures {
        out.push_str(&f.line());
        out.push('\n');
        match bound(&f.name) {
            Some(b) if f.stack <= b => {}
            Some(b) => failures.push(format!("{}: {} bytes > bound {b}", f.name, f.stack)),
            None => failures.push(format!("{}: no bound ({} bytes measured)", f.name, f.stack)),
        }
    }
    print!("{out}");
    assert!(failures.is_empty(), "peak stack: {failures:#?}");
}

/// Every depth, cull and draw-mode combination of one shading stage.
fn shading_configs<Sh>(label: &str, make: fn() -> Sh) -> Vec<Figures>
where
    Sh: Shading<Fx16, Color = Rgb565> + 'static,
{
    let mut figures = Vec::new();
    for mode in [Mode::Draw, Mode::NoScratch, Mode::Banded] {
        for depth in [true, false] {
            for cull in [true, false] {
                let name = format!(
                    "{label}_{}_{}_{}",
                    if depth { "depth" } else { "nodepth" },
                    if cull { "cull" } else { "nocull" },
                    mode.name()
                );
                figures.push(if cull {
                    config(&name, || CullClockwise, make, depth, mode)
                } else {
                    config(&name, || NoCull, make, depth, mode)
                });
            }
        }
    }
    figures
}

#[test]
fn stack_unlit() {
    // The diffuse colour of the lit material, as count3d's unlit M1.
    report(&shading_configs("unlit", || Unlit {
        color: Rgb565::from(DIFFUSE),
    }));
}

#[test]
fn stack_flat() {
    report(&shading_configs("flat", || {
        FlatLit::<Fx16, Rgb565, 1>::new(lighting())
    }));
}

#[test]
fn stack_gouraud() {
    let mut figures = shading_configs("gouraud", || GouraudLit::<Fx16, Rgb565, 1>::new(lighting()));
    // M1 in bands without the vertex scratch too.
    figures.push(config(
        "gouraud_depth_cull_banded16_noscratch",
        || CullClockwise,
        || GouraudLit::<Fx16, Rgb565, 1>::new(lighting()),
        true,
        Mode::BandedNoScratch,
    ));
    report(&figures);
}

#[test]
fn stack_phong() {
    report(&shading_configs("phong", || {
        PhongLit::<Fx16, Rgb565, 1>::new(lighting())
    }));
}

// --- 2D primitives ---

/// Measures a 2D call drawing into a 320 x 240 Rgb565 framebuffer.
fn primitive(name: &str, draw: fn(&mut Framebuffer<'_, Rgb565>)) -> Figures {
    let mut fig = on_fresh_stack(move || {
        let (words, bytes) = rgb565_bytes(H);
        let mut buf = vec![0u16; words];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
        let cell = core::cell::RefCell::new(&mut fb);
        let stack = peak(&mut || draw(&mut cell.borrow_mut()), &mut || {
            cell.borrow_mut().clear(Rgb565::BLACK).unwrap()
        });
        Figures {
            stack,
            framebuffer: bytes,
            ..Figures::default()
        }
    });
    fig.name = name.to_string();
    fig
}

fn sp(x: i32, y: i32) -> SubPoint<4> {
    black_box(SubPoint::new(x * 16 + 5, y * 16 + 11))
}

/// A line with both ends off screen: the clipped path.
#[inline(never)]
fn line(fb: &mut Framebuffer<'_, Rgb565>) {
    let p = |x, y| black_box(Point::new(x, y));
    draw_line(fb, p(-40, 7), p(371, 233), Rgb565::WHITE).unwrap();
}

/// A triangle over about a third of the screen, with sub-pixel vertices.
#[inline(never)]
fn triangle(fb: &mut Framebuffer<'_, Rgb565>) {
    fill_triangle(fb, [sp(20, 10), sp(300, 120), sp(90, 230)], Rgb565::GREEN).unwrap();
}

/// The same triangle with a colour per vertex.
#[inline(never)]
fn gouraud_triangle(fb: &mut Framebuffer<'_, Rgb565>) {
    let colors = [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE];
    fill_triangle_gouraud(fb, [sp(20, 10), sp(300, 120), sp(90, 230)], colors).unwrap();
}

/// The polygon, built by the caller (its edge table is the caller's RAM).
fn star() -> Polygon<8> {
    Polygon::new(&[
        sp(160, 5),
        sp(250, 230),
        sp(10, 80),
        sp(310, 80),
        sp(70, 230),
    ])
    .unwrap()
}

/// A self-intersecting five-pointed star, non-zero rule.
#[inline(never)]
fn polygon(fb: &mut Framebuffer<'_, Rgb565>) {
    black_box(star())
        .fill(fb, FillRule::NonZero, Rgb565::CYAN)
        .unwrap();
}

#[test]
fn stack_2d() {
    let mut figures = vec![
        primitive("line", line),
        primitive("triangle", triangle),
        primitive("gouraud_triangle", gouraud_triangle),
        primitive("polygon", polygon),
    ];
    figures[3].pipeline = size_of::<Polygon<8>>();
    report(&figures);
}

/// Sizes of the types the RAM figures are made of.
#[test]
fn type_sizes() {
    let mesh = PackedMesh::parse(SUZANNE).expect("packed Suzanne");
    println!(
        "MEMORY types bin_entry={} slot_unlit={} slot_flat={} slot_gouraud={} \
         slot_phong={} polygon8={} mesh_vertices={} mesh_triangles={}",
        size_of::<BinEntry>(),
        size_of::<Slot<Unlit<Rgb565>>>(),
        size_of::<Slot<FlatLit<Fx16, Rgb565, 1>>>(),
        size_of::<Slot<GouraudLit<Fx16, Rgb565, 1>>>(),
        size_of::<Slot<PhongLit<Fx16, Rgb565, 1>>>(),
        size_of::<Polygon<8>>(),
        mesh.vertices(),
        mesh.triangles(),
    );
}

// --- Workload S1 through the frame list ---

type Gouraud = GouraudLit<Fx16, Rgb565, 1>;
type Flat = FlatLit<Fx16, Rgb565, 1>;

/// S1's caller-owned RAM besides the band buffers: vertex scratch and bins of both meshes.
struct S1Ram {
    suzanne_scratch: Vec<Slot<Gouraud>>,
    cube_scratch: Vec<Slot<Flat>>,
    suzanne_bins: Vec<BinEntry>,
    cube_bins: Vec<BinEntry>,
}

/// Two band buffers whose transfer is a `black_box` (blocking), for `render_double`.
struct Blocking([Vec<u16>; 2]);

impl rasterizer_core::frame::DoubleBuffer<Rgb565> for Blocking {
    type Error = core::convert::Infallible;
    fn buffer(&mut self, k: usize) -> &mut [u16] {
        &mut self.0[k & 1]
    }
    fn start(&mut self, k: usize, _: Rectangle, _: Rectangle) -> Result<(), Self::Error> {
        black_box(self.0[k & 1].as_slice());
        Ok(())
    }
    fn wait(&mut self, _: usize) -> Result<(), Self::Error> {
        Ok(())
    }
}

/// One S1 frame: the list built (its slots, the mesh commands and their pipelines are locals,
/// on the stack) and rendered in 16-row bands, into `band` or through `double`. Returns the
/// triangles the meshes draw.
#[inline(never)]
fn render_s1(
    suzanne: &PackedMesh<'_>,
    cube: &Mesh<'_, Fx16, u8>,
    ram: &mut S1Ram,
    band: &mut [u16],
    depth: &mut [u16],
    double: Option<&mut Blocking>,
) -> Result<u32, rasterizer_core::frame::FrameError> {
    use fixtures::s1;
    use rasterizer_core::depth::SharedDepth;
    use rasterizer_core::frame::MeshCommand;
    use rasterizer_core::frame::{Clear, FrameList, Layout, Slot as ListSlot};
    let mut monkey = MeshCommand::new(
        Pipeline::new(
            &s1::transforms(s1::suzanne_model(s1::SUZANNE_DEGREES)),
            s1::viewport(),
            CullClockwise,
            SharedDepth,
            Gouraud::new(s1::suzanne_lighting()),
        ),
        suzanne,
        &mut ram.suzanne_scratch,
        &mut ram.suzanne_bins,
    );
    let mut box_ = MeshCommand::new(
        Pipeline::new(
            &s1::transforms(s1::cube_model()),
            s1::viewport(),
            CullClockwise,
            SharedDepth,
            Flat::new(s1::cube_lighting()),
        ),
        cube,
        &mut ram.cube_scratch,
        &mut ram.cube_bins,
    );
    let labels = s1::labels();
    let mut slots = [ListSlot::EMPTY; 19];
    let mut list = FrameList::new(
        &mut slots,
        Layout::new(W, H, BAND_ROWS)?,
        Clear::new(s1::background()),
    );
    list.command(&mut monkey)?;
    list.command(&mut box_)?;
    for s in s1::panel().into_iter().chain(s1::bars()) {
        list.shape(s)?;
    }
    for t in &labels {
        list.item(t, 0)?;
    }
    list.shape(s1::gouraud())?;
    match double {
        None => list.render(band, depth, |b, _| {
            black_box(b.framebuffer().as_slice());
        })?,
        Some(d) => list.render_double(None, depth, d).map_err(|e| match e {
            rasterizer_core::frame::RenderError::Frame(e) => e,
            rasterizer_core::frame::RenderError::Sink(never) => match never {},
        })?,
    }
    Ok(monkey.stats().drawn + box_.stats().drawn)
}

/// S1 in 16-row bands, single- or double-buffered.
fn s1_config(name: &str, double: bool) -> Figures {
    let mut fig = on_fresh_stack(move || {
        let suzanne = PackedMesh::parse(SUZANNE).expect("packed Suzanne");
        let cube = fixtures::s1::cube_mesh();
        let (words, bytes) = rgb565_bytes(BAND_ROWS);
        let mut ram = S1Ram {
            suzanne_scratch: vec![Slot::<Gouraud>::EMPTY; suzanne.vertices()],
            cube_scratch: vec![Slot::<Flat>::EMPTY; 8],
            // A bin per triangle for the warm-up; then exactly as many as are drawn.
            suzanne_bins: vec![BinEntry::ZERO; suzanne.triangles()],
            cube_bins: vec![BinEntry::ZERO; 12],
        };
        let mut band = vec![0u16; words];
        let mut depth = vec![0u16; (W * BAND_ROWS) as usize];
        let mut pair = Blocking([vec![0u16; words], vec![0u16; words]]);
        let drawn =
            render_s1(&suzanne, &cube, &mut ram, &mut band, &mut depth, None).expect("S1 renders");
        // Exactly as many bins as the frame has visible triangles: a list without them says.
        ram.suzanne_bins.clear();
        let visible = match render_s1(&suzanne, &cube, &mut ram, &mut band, &mut depth, None) {
            Err(rasterizer_core::frame::FrameError::TooFewBins { needed, .. }) => needed,
            other => panic!("expected TooFewBins, got {other:?}"),
        };
        ram.suzanne_bins = vec![BinEntry::ZERO; visible];
        let cell = core::cell::RefCell::new((&mut ram, &mut band, &mut depth, &mut pair));
        let mut got = 0;
        let stack = peak(
            &mut || {
                let mut g = cell.borrow_mut();
                let (ram, band, depth, pair) = &mut *g;
                let d = if double { Some(&mut **pair) } else { None };
                got = black_box(render_s1(&suzanne, &cube, ram, band, depth, d).unwrap());
            },
            &mut || {},
        );
        assert_eq!(got, drawn);
        if double {
            band = Vec::new();
        }
        let _ = &band;
        let bins = (ram.suzanne_bins.len() + ram.cube_bins.len()) * size_of::<BinEntry>();
        Figures {
            stack,
            band: if double { 2 * bytes } else { bytes },
            band_depth: (W * BAND_ROWS) as usize * size_of::<u16>(),
            bins,
            visible: drawn as usize,
            scratch: ram.suzanne_scratch.len() * size_of::<Slot<Gouraud>>()
                + ram.cube_scratch.len() * size_of::<Slot<Flat>>(),
            slot: size_of::<Slot<Gouraud>>(),
            drawn,
            ..Figures::default()
        }
    });
    fig.name = name.to_string();
    fig
}

#[test]
fn stack_s1() {
    report(&[
        s1_config("s1_band16", false),
        s1_config("s1_band16x2", true),
    ]);
}
