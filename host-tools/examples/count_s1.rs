//! Draws one frame of workload S1 of `shared/bench/WORKLOADS.md` ("a firmware screen": Suzanne and
//! the cube sharing depth, a translucent panel, twelve anti-aliased bars, two labels, a Gouraud
//! triangle; `fixtures::s1`) for callgrind to count (`scripts/figures.sh`).
//!
//! `count_s1 MODE`, one of:
//!
//! | mode | counted frame (`frame_<MODE>`) |
//! |---|---|
//! | `s1` | the commands drawn directly into a whole 320 x 240 framebuffer and depth buffer |
//! | `s1_band16` | the frame list built and rendered in 16-row bands, one band buffer |
//! | `s1_band16x2` | the same, double-buffered (`render_double`, two band buffers) |
//! | `s1_region` | the frame after Suzanne turns 30 -> 35 degrees: the list built, its summaries compared with the previous frame's (`changed_areas`) and only the changed rectangle rendered, in 16-row bands |
//!
//! Buffers, meshes and the previous frame are set up and one warm frame drawn outside the count.
//! Each finished band is copied into a whole framebuffer row by row (where firmware would start
//! the display's transfer), as count3d's banded M1 does. Prints `MODE checksum=.. pixels=..`
//! (`pixels`: the area redrawn, for `s1_region`).

use embedded_graphics::prelude::*;
use fixtures::s1::{self, Meshes};
use rasterizer_core::depth::SharedDepth;
use rasterizer_core::frame::{
    changed_areas, Clear, DoubleBuffer, FrameList, Layout, Shape, Slot, Summary,
};
use rasterizer_core::prelude::*;
use rasterizer_core::surface::Band;
use std::hint::black_box;
use std::process::ExitCode;

const W: u32 = s1::WIDTH;
const H: u32 = s1::HEIGHT;
const ROWS: u32 = s1::BAND_ROWS;

type Mesh3<'a> = Mesh<'a, Fx16, u32>;
type Gouraud = GouraudLit<Fx16, Rgb565, 1>;
type Flat = FlatLit<Fx16, Rgb565, 1>;
type MeshCmd<'m, Sh> = MeshCommand<'m, Fx16, CullClockwise, SharedDepth, Sh, Mesh3<'m>>;
use rasterizer_core::frame::MeshCommand;

/// The caller's RAM of a list frame besides the band buffers: vertex scratch and bins.
struct Ram {
    suzanne_scratch: Vec<VertexSlot<<Gouraud as rasterizer_core::shade::Shading<Fx16>>::Stored>>,
    cube_scratch: Vec<VertexSlot<<Flat as rasterizer_core::shade::Shading<Fx16>>::Stored>>,
    suzanne_bins: Vec<BinEntry>,
    cube_bins: Vec<BinEntry>,
    depth: Vec<u16>,
}

/// Copies a band's area into the whole picture, row by row (see the module documentation).
#[inline(always)]
fn paste(out: &mut [u16], band: &Band<'_, Rgb565>, area: Rectangle) {
    let data = band.framebuffer().as_slice();
    let (x0, w) = (area.top_left.x as usize, area.size.width as usize);
    for y in area.rows() {
        let src = (y - band.y0()) as usize * W as usize + x0;
        let dst = y as usize * W as usize + x0;
        out[dst..dst + w].copy_from_slice(black_box(&data[src..src + w]));
    }
}

/// S1's commands drawn directly into a whole frame.
#[inline(always)]
fn body_s1(
    m: (&Mesh3<'_>, &Mesh3<'_>),
    fb: &mut Framebuffer<'_, Rgb565>,
    depth: &mut [u16],
    ram: &mut Ram,
) {
    let Ok(()) = fb.clear(s1::background());
    depth.fill(u16::MAX);
    let Ok(z) = DepthBuffer::new(depth, W, H, Compare::Less) else {
        return;
    };
    let mut p = Pipeline::new(
        &s1::transforms(s1::suzanne_model(s1::SUZANNE_DEGREES)),
        s1::viewport(),
        CullClockwise,
        z,
        Gouraud::new(s1::suzanne_lighting()),
    );
    let _ = p.draw(fb, m.0, &mut ram.suzanne_scratch);
    let mut p = Pipeline::new(
        &s1::transforms(s1::cube_model()),
        s1::viewport(),
        CullClockwise,
        p.depth,
        Flat::new(s1::cube_lighting()),
    );
    let _ = p.draw(fb, m.1, &mut ram.cube_scratch);
    for s in s1::panel().iter().chain(&s1::bars()) {
        let _ = s.draw(fb);
    }
    for t in &s1::labels() {
        let Ok(_) = t.draw(fb);
    }
    let _ = s1::gouraud().draw(fb);
}

/// Builds S1's list with Suzanne turned `degrees` and hands it to `f`.
#[inline(always)]
fn with_list<R>(
    m: (&Mesh3<'_>, &Mesh3<'_>),
    degrees: i32,
    ram: &mut Ram,
    f: impl FnOnce(&mut FrameList<'_, Rgb565>) -> R,
) -> R {
    let mut suzanne: MeshCmd<Gouraud> = MeshCommand::new(
        Pipeline::new(
            &s1::transforms(s1::suzanne_model(degrees)),
            s1::viewport(),
            CullClockwise,
            SharedDepth,
            Gouraud::new(s1::suzanne_lighting()),
        ),
        m.0,
        &mut ram.suzanne_scratch,
        &mut ram.suzanne_bins,
    );
    let mut cube: MeshCmd<Flat> = MeshCommand::new(
        Pipeline::new(
            &s1::transforms(s1::cube_model()),
            s1::viewport(),
            CullClockwise,
            SharedDepth,
            Flat::new(s1::cube_lighting()),
        ),
        m.1,
        &mut ram.cube_scratch,
        &mut ram.cube_bins,
    );
    let labels = s1::labels();
    let mut slots = [Slot::EMPTY; 20];
    let layout = Layout::new(W, H, ROWS).unwrap_or_else(|_| unreachable!("320 x 240 in 16 rows"));
    let mut list = FrameList::new(&mut slots, layout, Clear::new(s1::background()));
    let add = |r: Result<(), _>| {
        if let Err(e) = r {
            eprintln!("count_s1: {e}");
            std::process::exit(1);
        }
    };
    add(list.command(&mut suzanne));
    add(list.command(&mut cube));
    let shapes: [Shape<Rgb565>; 14] = {
        let (p, b) = (s1::panel(), s1::bars());
        core::array::from_fn(|i| if i < 2 { p[i] } else { b[i - 2] })
    };
    for s in shapes {
        add(list.shape(s));
    }
    for t in &labels {
        add(list.item(t, 0));
    }
    add(list.shape(s1::gouraud()));
    f(&mut list)
}

#[inline(always)]
fn body_s1_band16(m: (&Mesh3<'_>, &Mesh3<'_>), out: &mut [u16], band: &mut [u16], ram: &mut Ram) {
    let mut depth = std::mem::take(&mut ram.depth);
    with_list(m, s1::SUZANNE_DEGREES, ram, |list| {
        let r = list.render(band, &mut depth, |b, area| paste(out, b, area));
        if let Err(e) = r {
            eprintln!("count_s1: {e}");
        }
    });
    ram.depth = depth;
}

/// Two band buffers and a "transfer" that copies a band into the whole picture at once.
struct Copier<'a> {
    buffers: [Vec<u16>; 2],
    out: &'a mut [u16],
}

impl DoubleBuffer<Rgb565> for Copier<'_> {
    type Error = core::convert::Infallible;

    fn buffer(&mut self, k: usize) -> &mut [u16] {
        &mut self.buffers[k & 1]
    }

    fn start(&mut self, k: usize, rows: Rectangle, area: Rectangle) -> Result<(), Self::Error> {
        let data = &self.buffers[k & 1];
        let (x0, w) = (area.top_left.x as usize, area.size.width as usize);
        for y in area.rows() {
            let src = (y - rows.top_left.y) as usize * W as usize + x0;
            let dst = y as usize * W as usize + x0;
            self.out[dst..dst + w].copy_from_slice(black_box(&data[src..src + w]));
        }
        Ok(())
    }

    fn wait(&mut self, _k: usize) -> Result<(), Self::Error> {
        Ok(())
    }
}

#[inline(always)]
fn body_s1_band16x2(m: (&Mesh3<'_>, &Mesh3<'_>), copier: &mut Copier<'_>, ram: &mut Ram) {
    let mut depth = std::mem::take(&mut ram.depth);
    with_list(m, s1::SUZANNE_DEGREES, ram, |list| {
        let Ok(()) = list.render_double(None, &mut depth, copier) else {
            eprintln!("count_s1: render_double failed");
            return;
        };
    });
    ram.depth = depth;
}

/// The region redraw: returns the pixels redrawn.
#[inline(always)]
fn body_s1_region(
    m: (&Mesh3<'_>, &Mesh3<'_>),
    previous: &[Summary],
    out: &mut [u16],
    band: &mut [u16],
    ram: &mut Ram,
) -> u64 {
    let mut depth = std::mem::take(&mut ram.depth);
    let pixels = with_list(m, s1::SUZANNE_DEGREES_NEXT, ram, |list| {
        let mut now = [Summary::default(); 20];
        let n = list.summaries(&mut now);
        let mut areas = [Rectangle::zero(); 4];
        let count = changed_areas(previous, &now[..n.min(20)], &mut areas);
        let mut pixels = 0u64;
        for area in &areas[..count] {
            pixels += u64::from(area.size.width) * u64::from(area.size.height);
            let r = list.render_region(area, band, &mut depth, |b, a| paste(out, b, a));
            if let Err(e) = r {
                eprintln!("count_s1: {e}");
            }
        }
        pixels
    });
    ram.depth = depth;
    pixels
}

// The counted frames: `#[inline(never)]`, each with its own name in `black_box`, around the bodies
// above, which the warm frames call directly (callgrind collects every call of a counted
// function).
#[inline(never)]
fn frame_s1(
    m: (&Mesh3<'_>, &Mesh3<'_>),
    fb: &mut Framebuffer<'_, Rgb565>,
    depth: &mut [u16],
    ram: &mut Ram,
) {
    black_box("frame_s1");
    body_s1(m, fb, depth, ram);
}

#[inline(never)]
fn frame_s1_band16(m: (&Mesh3<'_>, &Mesh3<'_>), out: &mut [u16], band: &mut [u16], ram: &mut Ram) {
    black_box("frame_s1_band16");
    body_s1_band16(m, out, band, ram);
}

#[inline(never)]
fn frame_s1_band16x2(m: (&Mesh3<'_>, &Mesh3<'_>), copier: &mut Copier<'_>, ram: &mut Ram) {
    black_box("frame_s1_band16x2");
    body_s1_band16x2(m, copier, ram);
}

#[inline(never)]
fn frame_s1_region(
    m: (&Mesh3<'_>, &Mesh3<'_>),
    previous: &[Summary],
    out: &mut [u16],
    band: &mut [u16],
    ram: &mut Ram,
) -> u64 {
    black_box("frame_s1_region");
    body_s1_region(m, previous, out, band, ram)
}

fn checksum(px: &[u16]) -> u32 {
    black_box(px)
        .iter()
        .fold(0u32, |s, &w| s.rotate_left(5) ^ u32::from(w))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let modes = ["s1", "s1_band16", "s1_band16x2", "s1_region"];
    let mode = match args.as_slice() {
        [m] if modes.contains(&m.as_str()) => m.as_str(),
        _ => {
            eprintln!("usage: count_s1 {}", modes.join("|"));
            return ExitCode::from(2);
        }
    };
    let Meshes { suzanne, cube } = match s1::load() {
        Ok(m) => m,
        Err(e) => {
            eprintln!("count_s1: {e}");
            return ExitCode::FAILURE;
        }
    };
    let (suzanne, cube) = (suzanne.mesh(), cube.mesh());
    let m = (&suzanne, &cube);
    let band_words = (W * ROWS) as usize;
    let mut ram = Ram {
        suzanne_scratch: vec![VertexSlot::EMPTY; suzanne.positions.len()],
        cube_scratch: vec![VertexSlot::EMPTY; cube.positions.len()],
        suzanne_bins: vec![BinEntry::ZERO; suzanne.triangles.len()],
        cube_bins: vec![BinEntry::ZERO; cube.triangles.len()],
        depth: vec![
            0;
            if mode == "s1" {
                (W * H) as usize
            } else {
                band_words
            }
        ],
    };
    let mut whole = vec![0u16; (W * H) as usize];
    let mut pixels = (W * H) as u64;
    match mode {
        "s1" => {
            let mut depth = std::mem::take(&mut ram.depth);
            let Ok(mut fb) = Framebuffer::<Rgb565>::new(&mut whole, W, H) else {
                return ExitCode::FAILURE;
            };
            body_s1(m, &mut fb, &mut depth, &mut ram);
            frame_s1(m, black_box(&mut fb), black_box(&mut depth), &mut ram);
        }
        "s1_band16" => {
            let mut band = vec![0u16; band_words];
            body_s1_band16(m, &mut whole, &mut band, &mut ram);
            whole.fill(0);
            frame_s1_band16(m, black_box(&mut whole), &mut band, &mut ram);
        }
        "s1_band16x2" => {
            let mut copier = Copier {
                buffers: [vec![0u16; band_words], vec![0u16; band_words]],
                out: &mut whole,
            };
            body_s1_band16x2(m, &mut copier, &mut ram);
            copier.out.fill(0);
            frame_s1_band16x2(m, black_box(&mut copier), &mut ram);
        }
        _ => {
            // The previous frame on the display, and its summaries, from outside the count.
            let mut band = vec![0u16; band_words];
            body_s1_band16(m, &mut whole, &mut band, &mut ram);
            let mut depth = std::mem::take(&mut ram.depth);
            let previous = with_list(m, s1::SUZANNE_DEGREES, &mut ram, |list| {
                let mut out = [Summary::default(); 20];
                let n = list.summaries(&mut out);
                let _ = list.render(&mut band, &mut depth, |_, _| {});
                out[..n.min(20)].to_vec()
            });
            ram.depth = depth;
            // The warm frame redraws onto a copy, the counted one onto the previous frame.
            let mut warm = whole.clone();
            body_s1_region(m, &previous, &mut warm, &mut band, &mut ram);
            pixels = frame_s1_region(m, &previous, black_box(&mut whole), &mut band, &mut ram);
        }
    }
    println!("{mode} checksum={:08x} pixels={pixels}", checksum(&whole));
    ExitCode::SUCCESS
}
