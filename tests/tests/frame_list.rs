//! The frame list ([`rasterizer_core::frame`]) against a whole frame drawn directly: workload S1
//! (two meshes sharing depth, a translucent panel, anti-aliased bars, text, a Gouraud triangle)
//! rendered in bands of every kind of height, as a region after a change, and through a
//! double-buffered sender whose mock DMA fails on any write to a buffer it is reading.

use embedded_graphics::prelude::Drawable;
use fixtures::s1;
use rasterizer_core::frame::{
    changed_areas, Clear, DoubleBuffer, FrameError, FrameList, Layout, RenderError, Slot, Summary,
};
use rasterizer_core::mesh::MeshSource;
use rasterizer_core::prelude::*;
use rasterizer_core::{
    depth::SharedDepth, frame::MeshCommand, pipeline::DEFAULT_BITS, shade::Shading,
};

const W: u32 = s1::WIDTH;
const H: u32 = s1::HEIGHT;

use fixtures::s1::Meshes;

fn meshes() -> Meshes {
    s1::load().unwrap()
}

/// S1 drawn directly into one whole framebuffer, through the library's own calls, one after the
/// other: the picture every list render must give.
fn whole_frame(m: &Meshes, degrees: i32) -> Vec<u16> {
    let mut px = vec![0u16; (W * H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut px, W, H).unwrap();
    fb.clear(s1::background()).unwrap();
    let mut depth = vec![u16::MAX; (W * H) as usize];
    let buffer = DepthBuffer::new(&mut depth, W, H, Compare::Less).unwrap();
    let suzanne = m.suzanne.mesh();
    let mut p = Pipeline::new(
        &s1::transforms(s1::suzanne_model(degrees)),
        s1::viewport(),
        CullClockwise,
        buffer,
        GouraudLit::<Fx16, Rgb565, 1>::new(s1::suzanne_lighting()),
    );
    let mut scratch = vec![VertexSlot::EMPTY; suzanne.vertex_count()];
    p.draw(&mut fb, &suzanne, &mut scratch).unwrap();
    let cube = m.cube.mesh();
    let mut p = Pipeline::new(
        &s1::transforms(s1::cube_model()),
        s1::viewport(),
        CullClockwise,
        p.depth,
        FlatLit::<Fx16, Rgb565, 1>::new(s1::cube_lighting()),
    );
    let mut scratch = vec![VertexSlot::EMPTY; cube.vertex_count()];
    p.draw(&mut fb, &cube, &mut scratch).unwrap();
    let v = |s: &rasterizer_core::frame::Shape<Rgb565>| s.bounds();
    let _ = v;
    for s in s1::panel() {
        let rasterizer_core::frame::Shape::Triangle {
            vertices,
            color,
            opacity,
        } = s
        else {
            unreachable!()
        };
        fill_triangle_alpha(&mut fb, vertices, color, opacity).unwrap();
    }
    for s in s1::bars() {
        let rasterizer_core::frame::Shape::LineAa { a, b, width, color } = s else {
            unreachable!()
        };
        draw_line_aa_wide(&mut fb, a, b, width, color).unwrap();
    }
    for t in s1::labels() {
        t.draw(&mut fb).unwrap();
    }
    let rasterizer_core::frame::Shape::Gouraud {
        vertices, colors, ..
    } = s1::gouraud()
    else {
        unreachable!()
    };
    fill_triangle_gouraud(&mut fb, vertices, colors).unwrap();
    px
}

type SuzanneCommand<'m> = MeshCommand<
    'm,
    Fx16,
    CullClockwise,
    SharedDepth,
    GouraudLit<Fx16, Rgb565, 1>,
    rasterizer_core::mesh::Mesh<'m, Fx16, u32>,
>;
type CubeCommand<'m> = MeshCommand<
    'm,
    Fx16,
    CullClockwise,
    SharedDepth,
    FlatLit<Fx16, Rgb565, 1>,
    rasterizer_core::mesh::Mesh<'m, Fx16, u32>,
>;

/// The per-frame storage of S1's meshes.
struct Storage<St1, St2> {
    scratch: (Vec<VertexSlot<St1>>, Vec<VertexSlot<St2>>),
    bins: (Vec<BinEntry>, Vec<BinEntry>),
}

fn storage<Sh1: Shading<Fx16>, Sh2: Shading<Fx16>>(
    suzanne: &rasterizer_core::mesh::Mesh<'_, Fx16, u32>,
    cube: &rasterizer_core::mesh::Mesh<'_, Fx16, u32>,
) -> Storage<Sh1::Stored, Sh2::Stored> {
    Storage {
        scratch: (
            vec![VertexSlot::EMPTY; suzanne.vertex_count()],
            vec![VertexSlot::EMPTY; cube.vertex_count()],
        ),
        bins: (
            vec![BinEntry::ZERO; suzanne.triangle_count() + 4],
            vec![BinEntry::ZERO; cube.triangle_count() + 1],
        ),
    }
}

/// Builds S1's list with Suzanne turned `degrees` on `layout` and hands it to `f`.
fn with_list<R>(
    m: &Meshes,
    degrees: i32,
    layout: Layout,
    f: impl FnOnce(&mut FrameList<'_, Rgb565>) -> R,
) -> R {
    let (suzanne, cube) = (m.suzanne.mesh(), m.cube.mesh());
    let mut st = storage::<GouraudLit<Fx16, Rgb565, 1>, FlatLit<Fx16, Rgb565, 1>>(&suzanne, &cube);
    let mut monkey: SuzanneCommand = MeshCommand::new(
        Pipeline::new(
            &s1::transforms(s1::suzanne_model(degrees)),
            s1::viewport(),
            CullClockwise,
            SharedDepth,
            GouraudLit::new(s1::suzanne_lighting()),
        ),
        &suzanne,
        &mut st.scratch.0,
        &mut st.bins.0,
    );
    let mut box_: CubeCommand = MeshCommand::new(
        Pipeline::new(
            &s1::transforms(s1::cube_model()),
            s1::viewport(),
            CullClockwise,
            SharedDepth,
            FlatLit::new(s1::cube_lighting()),
        ),
        &cube,
        &mut st.scratch.1,
        &mut st.bins.1,
    );
    let labels = s1::labels();
    let mut slots = [Slot::EMPTY; 20];
    let mut list = FrameList::new(&mut slots, layout, Clear::new(s1::background()));
    list.command(&mut monkey).unwrap();
    list.command(&mut box_).unwrap();
    s1::add_2d(&mut list, &labels).unwrap();
    assert_eq!(list.len(), 19);
    f(&mut list)
}

/// Copies a band's area into a whole picture.
fn paste(out: &mut [u16], band: &rasterizer_core::surface::Band<'_, Rgb565>, area: Rectangle) {
    let data = band.framebuffer().as_slice();
    for y in area.rows() {
        let row = (y - band.y0()) as usize * W as usize;
        for x in area.columns() {
            out[y as usize * W as usize + x as usize] = data[row + x as usize];
        }
    }
}

fn render_list(m: &Meshes, degrees: i32, rows: u32) -> Vec<u16> {
    let layout = Layout::new(W, H, rows).unwrap();
    let mut out = vec![0xdead; (W * H) as usize];
    let mut band = vec![0u16; (W * rows.min(H)) as usize];
    let mut depth = vec![0u16; (W * rows.min(H)) as usize];
    let mut next = 0;
    with_list(m, degrees, layout, |list| {
        list.render(&mut band, &mut depth, |b, area| {
            assert_eq!(b.y0(), next, "bands in order, each once");
            assert_eq!(area.top_left.y, next);
            next += b.framebuffer().height() as i32;
            paste(&mut out, b, area);
        })
        .unwrap();
    });
    assert_eq!(next as u32, H);
    out
}

fn first_difference(a: &[u16], b: &[u16]) -> Option<(usize, usize)> {
    a.iter()
        .zip(b)
        .position(|(x, y)| x != y)
        .map(|i| (i % W as usize, i / W as usize))
}

#[test]
fn s1_in_bands_is_the_whole_frame() {
    let m = meshes();
    let whole = whole_frame(&m, s1::SUZANNE_DEGREES);
    // The picture has all its parts: Suzanne's colours, the cube, the panel over the bars.
    let distinct: std::collections::HashSet<_> = whole.iter().collect();
    assert!(distinct.len() > 200, "{} colours", distinct.len());
    for rows in [1, 7, 16, 100, 240, 1000] {
        let banded = render_list(&m, s1::SUZANNE_DEGREES, rows);
        assert_eq!(
            first_difference(&banded, &whole),
            None,
            "bands of {rows} rows"
        );
    }
}

#[test]
fn each_band_draws_only_what_touches_it() {
    // A band of the top rows holds only the Gouraud triangle's and Suzanne's pixels: a list
    // whose Suzanne draws into a band of rows 0..16 is the same as the whole frame's rows there,
    // and the band below the panel draws none of the panel.
    let m = meshes();
    let whole = whole_frame(&m, s1::SUZANNE_DEGREES);
    let layout = Layout::new(W, H, 16).unwrap();
    let mut band = vec![0u16; (W * 16) as usize];
    let mut depth = vec![0u16; (W * 16) as usize];
    let mut seen = 0;
    with_list(&m, s1::SUZANNE_DEGREES, layout, |list| {
        let top = Rectangle::new(Point::new(0, 0), Size::new(W, 16));
        list.render_region(&top, &mut band, &mut depth, |b, area| {
            assert_eq!(area, top);
            let row = &whole[..(W * 16) as usize];
            assert_eq!(b.framebuffer().as_slice(), row);
            seen += 1;
        })
        .unwrap();
    });
    assert_eq!(seen, 1);
}

#[test]
fn region_redraw_after_the_turn_is_the_next_frame() {
    let m = meshes();
    let before = whole_frame(&m, s1::SUZANNE_DEGREES);
    let after = whole_frame(&m, s1::SUZANNE_DEGREES_NEXT);
    let layout = Layout::new(W, H, 16).unwrap();
    let summaries = |degrees| {
        with_list(&m, degrees, layout, |list| {
            let mut out = vec![Summary::default(); 32];
            let n = list.summaries(&mut out);
            out.truncate(n);
            out
        })
    };
    let (old, new) = (
        summaries(s1::SUZANNE_DEGREES),
        summaries(s1::SUZANNE_DEGREES_NEXT),
    );
    assert_eq!(old.len(), 19);
    // Only Suzanne changed.
    let changed: Vec<usize> = (0..19).filter(|&i| old[i] != new[i]).collect();
    assert_eq!(changed, vec![0]);
    let mut areas = [Rectangle::zero(); 4];
    let n = changed_areas(&old, &new, &mut areas);
    assert_eq!(n, 1);
    let region = areas[0];
    let pixels = region.size.width * region.size.height;
    // Suzanne's old and new bounds together: far less than the screen, more than nothing.
    assert!(pixels > 10_000 && pixels < W * H / 2, "{region:?}");
    let mut screen = before.clone();
    let mut band = vec![0u16; (W * 16) as usize];
    let mut depth = vec![0u16; (W * 16) as usize];
    with_list(&m, s1::SUZANNE_DEGREES_NEXT, layout, |list| {
        list.render_region(&region, &mut band, &mut depth, |b, area| {
            assert!(area.intersection(&region) == area);
            paste(&mut screen, b, area);
        })
        .unwrap();
    });
    assert_eq!(first_difference(&screen, &after), None);
    assert_ne!(before, after);
}

#[test]
fn changed_areas_cover_every_change_and_merge_overlaps() {
    let r = |x, y, w, h| Rectangle::new(Point::new(x, y), Size::new(w, h));
    let s = |b: Rectangle, f| Summary {
        bounds: b,
        fingerprint: f,
    };
    let old = [
        s(r(0, 0, 10, 10), 1),
        s(r(50, 50, 10, 10), 2),
        s(r(100, 0, 5, 5), 3),
    ];
    // The first moves onto the second's old place; the third changes in place; a fourth is new.
    let new = [
        s(r(45, 45, 10, 10), 1),
        s(r(50, 50, 10, 10), 2),
        s(r(100, 0, 5, 5), 4),
        s(r(200, 200, 3, 3), 5),
    ];
    let mut out = [Rectangle::zero(); 8];
    let n = changed_areas(&old, &new, &mut out);
    let mut got = out[..n].to_vec();
    got.sort_by_key(|r| (r.top_left.x, r.top_left.y));
    assert_eq!(
        got,
        vec![r(0, 0, 55, 55), r(100, 0, 5, 5), r(200, 200, 3, 3)]
    );
    // One rectangle of room: everything merged into it.
    let mut one = [Rectangle::zero(); 1];
    assert_eq!(changed_areas(&old, &new, &mut one), 1);
    assert_eq!(one[0], r(0, 0, 203, 203));
    // Nothing changed: nothing to redraw.
    assert_eq!(changed_areas(&old, &old, &mut out), 0);
}

/// What the mock DMA saw, in order.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Event {
    Lend(usize),
    Start(usize, i32),
    Read(usize, usize),
    Done(usize),
}

/// A transfer: the buffer's content when it started, its rows and area, and the words read.
type Transfer = (Vec<u16>, Rectangle, Rectangle, usize);

/// Two band buffers and a DMA that reads a started buffer `chunk` words at a time, one chunk
/// each time the renderer calls it, and checks each word it reads against the buffer's content
/// when the transfer started. Lending a buffer still being read is the failure the renderer
/// must never cause: it is recorded.
struct MockDma {
    buffers: [Vec<u16>; 2],
    /// The transfer of each buffer: its snapshot, rows and area, and how far it has read.
    flight: [Option<Transfer>; 2],
    chunk: usize,
    events: Vec<Event>,
    violations: Vec<String>,
    screen: Vec<u16>,
}

impl MockDma {
    fn new(words: usize, chunk: usize) -> Self {
        Self {
            buffers: [vec![0; words], vec![0; words]],
            flight: [None, None],
            chunk,
            events: Vec::new(),
            violations: Vec::new(),
            screen: vec![0xdead; (W * H) as usize],
        }
    }

    /// The DMA moves on: each transfer in flight reads its next chunk.
    fn tick(&mut self) {
        for k in 0..2 {
            let Some((snap, rows, area, pos)) = &mut self.flight[k] else {
                continue;
            };
            let total = (rows.size.width * rows.size.height) as usize;
            let end = (*pos + self.chunk).min(total);
            for (i, &was) in snap.iter().enumerate().take(end).skip(*pos) {
                if self.buffers[k][i] != was {
                    self.violations
                        .push(format!("buffer {k} word {i} changed while being sent"));
                }
                let (x, y) = (
                    (i % W as usize) as i32,
                    rows.top_left.y + (i / W as usize) as i32,
                );
                if area.contains(Point::new(x, y)) {
                    self.screen[y as usize * W as usize + x as usize] = self.buffers[k][i];
                }
            }
            self.events.push(Event::Read(k, end));
            *pos = end;
            if end == total {
                self.events.push(Event::Done(k));
                self.flight[k] = None;
            }
        }
    }
}

impl DoubleBuffer<Rgb565> for MockDma {
    type Error = String;

    fn buffer(&mut self, k: usize) -> &mut [u16] {
        if self.flight[k].is_some() {
            self.violations
                .push(format!("buffer {k} lent for drawing while being sent"));
        }
        self.events.push(Event::Lend(k));
        &mut self.buffers[k]
    }

    fn start(&mut self, k: usize, rows: Rectangle, area: Rectangle) -> Result<(), String> {
        self.tick();
        if self.flight[k].is_some() {
            return Err(format!("buffer {k} started twice"));
        }
        self.events.push(Event::Start(k, rows.top_left.y));
        self.flight[k] = Some((self.buffers[k].clone(), rows, area, 0));
        Ok(())
    }

    fn wait(&mut self, k: usize) -> Result<(), String> {
        while self.flight[k].is_some() {
            self.tick();
        }
        Ok(())
    }
}

#[test]
fn double_buffered_render_never_writes_a_buffer_in_flight() {
    let m = meshes();
    let whole = whole_frame(&m, s1::SUZANNE_DEGREES);
    let layout = Layout::new(W, H, 16).unwrap();
    let mut depth = vec![0u16; (W * 16) as usize];
    // A DMA slower than a band (reads a band in three steps) and one faster (at once).
    for chunk in [W as usize * 6, W as usize * 16] {
        let mut dma = MockDma::new((W * 16) as usize, chunk);
        with_list(&m, s1::SUZANNE_DEGREES, layout, |list| {
            list.render_double(None, &mut depth, &mut dma).unwrap();
        });
        assert_eq!(dma.violations, Vec::<String>::new());
        assert!(
            dma.flight.iter().all(Option::is_none),
            "all sent at the end"
        );
        assert_eq!(first_difference(&dma.screen, &whole), None);
        let starts: Vec<_> = dma
            .events
            .iter()
            .filter_map(|e| match e {
                Event::Start(k, y) => Some((*k, *y)),
                _ => None,
            })
            .collect();
        // Fifteen bands, alternating buffers, top to bottom.
        let expected: Vec<_> = (0..15).map(|b| (b % 2, b as i32 * 16)).collect();
        assert_eq!(starts, expected);
        if chunk < W as usize * 16 {
            // The slow DMA overlaps: a band is drawn while the previous one is still being read.
            let at = |e: Event| dma.events.iter().position(|x| *x == e).unwrap();
            let (start, done) = (at(Event::Start(0, 0)), at(Event::Done(0)));
            let overlapped = dma.events[start..done].contains(&Event::Lend(1));
            assert!(overlapped, "{:?}", &dma.events[..12]);
        }
    }
}

#[test]
fn the_mock_dma_catches_a_write_in_flight() {
    // The check itself: drawing into a buffer still being read is reported.
    let mut dma = MockDma::new(16, 4);
    let rows = Rectangle::new(Point::zero(), Size::new(16, 1));
    dma.buffers[0].fill(7);
    dma.start(0, rows, rows).unwrap();
    let buf = dma.buffer(0);
    buf[10] = 9;
    dma.wait(0).unwrap();
    assert_eq!(dma.violations.len(), 2, "{:?}", dma.violations);
}

#[test]
fn double_buffered_region_render_sends_only_the_region() {
    let m = meshes();
    let whole = whole_frame(&m, s1::SUZANNE_DEGREES);
    let layout = Layout::new(W, H, 16).unwrap();
    let mut depth = vec![0u16; (W * 16) as usize];
    let region = Rectangle::new(Point::new(40, 30), Size::new(100, 70));
    let mut dma = MockDma::new((W * 16) as usize, W as usize * 5);
    with_list(&m, s1::SUZANNE_DEGREES, layout, |list| {
        list.render_double(Some(&region), &mut depth, &mut dma)
            .unwrap();
    });
    assert!(dma.violations.is_empty(), "{:?}", dma.violations);
    for y in 0..H as i32 {
        for x in 0..W as i32 {
            let i = (y * W as i32 + x) as usize;
            if region.contains(Point::new(x, y)) {
                assert_eq!(dma.screen[i], whole[i], "({x}, {y})");
            } else {
                assert_eq!(dma.screen[i], 0xdead, "({x}, {y}) outside the region");
            }
        }
    }
}

#[test]
fn a_sender_failure_stops_the_render() {
    struct Failing(Vec<u16>, Vec<u16>, usize);
    impl DoubleBuffer<Rgb565> for Failing {
        type Error = &'static str;
        fn buffer(&mut self, k: usize) -> &mut [u16] {
            if k == 0 {
                &mut self.0
            } else {
                &mut self.1
            }
        }
        fn start(&mut self, _: usize, _: Rectangle, _: Rectangle) -> Result<(), &'static str> {
            self.2 += 1;
            if self.2 == 3 {
                Err("bus fault")
            } else {
                Ok(())
            }
        }
        fn wait(&mut self, _: usize) -> Result<(), &'static str> {
            Ok(())
        }
    }
    let layout = Layout::new(W, H, 16).unwrap();
    let mut slots = [Slot::EMPTY; 2];
    let mut list = FrameList::new(&mut slots, layout, Clear::new(Rgb565::BLACK));
    list.shape(s1::gouraud()).unwrap();
    let mut sender = Failing(vec![0; (W * 16) as usize], vec![0; (W * 16) as usize], 0);
    assert_eq!(
        list.render_double(None, &mut [], &mut sender),
        Err(RenderError::Sink("bus fault"))
    );
    assert_eq!(sender.2, 3);
    // A buffer too short: refused before anything is sent.
    let mut short = Failing(vec![0; 10], vec![0; (W * 16) as usize], 0);
    assert_eq!(
        list.render_double(None, &mut [], &mut short),
        Err(RenderError::Frame(FrameError::BandBufferTooSmall {
            needed: (W * 16) as usize,
            actual: 10
        }))
    );
    assert_eq!(short.2, 0);
}

#[test]
fn bad_input_gets_typed_errors() {
    assert!(matches!(
        Layout::new(0, 10, 1),
        Err(FrameError::BadLayout { .. })
    ));
    assert!(matches!(
        Layout::new(10, 10, 0),
        Err(FrameError::BadLayout { .. })
    ));
    assert!(matches!(
        Layout::new(40_000, 10, 1),
        Err(FrameError::BadLayout { .. })
    ));
    assert_eq!(Layout::new(10, 10, 99).unwrap().rows(), 10);
    let m = meshes();
    let layout = Layout::new(W, H, 16).unwrap();
    // Full.
    let mut slots = [Slot::EMPTY; 1];
    let mut list = FrameList::new(&mut slots, layout, Clear::new(Rgb565::BLACK));
    list.shape(s1::gouraud()).unwrap();
    assert_eq!(
        list.shape(s1::gouraud()),
        Err(FrameError::Full { capacity: 1 })
    );
    // Too few bins: the mesh is refused and the list unchanged.
    let suzanne = m.suzanne.mesh();
    let mut scratch = vec![VertexSlot::EMPTY; 600];
    let mut bins = vec![BinEntry::ZERO; 10];
    let mut monkey: SuzanneCommand = MeshCommand::new(
        Pipeline::new(
            &s1::transforms(s1::suzanne_model(30)),
            s1::viewport(),
            CullClockwise,
            SharedDepth,
            GouraudLit::new(s1::suzanne_lighting()),
        ),
        &suzanne,
        &mut scratch,
        &mut bins,
    );
    let mut slots = [Slot::EMPTY; 4];
    let mut list = FrameList::new(&mut slots, layout, Clear::new(Rgb565::BLACK));
    assert!(matches!(
        list.command(&mut monkey),
        Err(FrameError::TooFewBins { actual: 10, .. })
    ));
    assert!(list.is_empty());
    // A depth buffer too small for a band while a mesh tests depth.
    let mut bins = vec![BinEntry::ZERO; 1000];
    let mut monkey: SuzanneCommand = MeshCommand::new(
        Pipeline::new(
            &s1::transforms(s1::suzanne_model(30)),
            s1::viewport(),
            CullClockwise,
            SharedDepth,
            GouraudLit::new(s1::suzanne_lighting()),
        ),
        &suzanne,
        &mut scratch,
        &mut bins,
    );
    let mut slots = [Slot::EMPTY; 4];
    let mut list = FrameList::new(&mut slots, layout, Clear::new(Rgb565::BLACK));
    list.command(&mut monkey).unwrap();
    let mut band = vec![0u16; (W * 16) as usize];
    let mut depth = vec![0u16; 100];
    let mut called = false;
    assert_eq!(
        list.render(&mut band, &mut depth, |_, _| called = true),
        Err(FrameError::DepthTooSmall {
            needed: (W * 16) as usize,
            actual: 100
        })
    );
    assert!(!called);
    assert!(matches!(
        list.render(&mut band[..5], &mut [], |_, _| called = true),
        Err(FrameError::BandBufferTooSmall { actual: 5, .. })
    ));
    assert!(!called);
}

#[test]
fn shared_depth_alone_draws_nothing_and_says_so() {
    // A pipeline built for a list, drawn on its own, reports the missing buffer instead of
    // drawing without depth.
    let m = meshes();
    let suzanne = m.suzanne.mesh();
    let mut p = Pipeline::new(
        &s1::transforms(s1::suzanne_model(30)),
        s1::viewport(),
        CullClockwise,
        SharedDepth,
        GouraudLit::<Fx16, Rgb565, 1>::new(s1::suzanne_lighting()),
    );
    let mut px = vec![0u16; (W * H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut px, W, H).unwrap();
    let mut scratch = vec![VertexSlot::EMPTY; 600];
    assert!(p.draw(&mut fb, &suzanne, &mut scratch).is_err());
    assert!(px.iter().all(|&p| p == 0));
    let _ = DEFAULT_BITS;
}

/// Every kind of command the list takes, in an order where each one overlaps others: every
/// `Shape` variant, a polygon item, text, an opaque mesh with shared depth, a translucent mesh
/// testing that depth read-only, and a mesh without depth.
mod every_command {
    use super::*;
    use rasterizer_core::depth::{NoDepth, SharedDepthReadOnly};
    use rasterizer_core::frame::{PolygonFill, Shape};

    const W: u32 = 96;
    const H: u32 = 72;

    fn sp(x: i32, y: i32) -> SubPoint {
        SubPoint::new(x, y)
    }

    /// The 2D shapes, sub-pixel corners in 1/16 pixel.
    fn shapes() -> Vec<Shape<Rgb565>> {
        let c = |r, g, b| Rgb565::new(r, g, b);
        vec![
            Shape::Line {
                a: Point::new(-5, 3),
                b: Point::new(100, 60),
                color: c(31, 0, 0),
            },
            Shape::LineGradient {
                a: Point::new(2, 70),
                b: Point::new(90, 1),
                colors: [c(0, 63, 0), c(0, 0, 31)],
            },
            Shape::LineAlpha {
                a: Point::new(10, 0),
                b: Point::new(12, 71),
                color: c(31, 63, 0),
                alpha: 100,
            },
            Shape::LineAa {
                a: Point::new(5, 40),
                b: Point::new(91, 20),
                width: 5,
                color: c(0, 63, 31),
            },
            Shape::TriangleOutline {
                vertices: [Point::new(3, 3), Point::new(80, 30), Point::new(30, 68)],
                color: c(31, 31, 31),
            },
            Shape::Triangle {
                vertices: [sp(100, 50), sp(1400, 300), sp(600, 1100)],
                color: c(20, 10, 5),
                opacity: 255,
            },
            Shape::Triangle {
                vertices: [sp(300, 200), sp(1500, 900), sp(100, 1100)],
                color: c(5, 40, 25),
                opacity: 90,
            },
            Shape::Gouraud {
                vertices: [sp(700, 10), sp(1530, 700), sp(400, 800)],
                colors: [c(31, 0, 0), c(0, 63, 0), c(0, 0, 31)],
                opacity: 255,
            },
            Shape::Gouraud {
                vertices: [sp(0, 600), sp(1000, 500), sp(500, 1150)],
                colors: [c(31, 63, 0), c(0, 63, 31), c(31, 0, 31)],
                opacity: 170,
            },
        ]
    }

    fn star() -> Polygon<8> {
        Polygon::new(&[
            sp(760, 40),
            sp(1200, 1100),
            sp(40, 380),
            sp(1500, 380),
            sp(330, 1100),
        ])
        .unwrap()
    }

    fn camera(yaw: i32) -> Transforms<Fx16> {
        fixtures::scenes3d::camera(Mat4::rotation_y(Angle::from_degrees(yaw)), W, H)
    }

    fn lit() -> GouraudLit<Fx16, Rgb565, 1> {
        GouraudLit::new(fixtures::scenes3d::lighting())
    }

    /// The same commands drawn directly into one framebuffer.
    fn direct(m: &Meshes) -> Vec<u16> {
        let mut px = vec![0u16; (W * H) as usize];
        let mut fb = Framebuffer::<Rgb565>::new(&mut px, W, H).unwrap();
        fb.clear(Rgb565::new(3, 6, 9)).unwrap();
        let shapes = shapes();
        for s in &shapes[..5] {
            s.draw(&mut fb).unwrap();
        }
        let mut depth = vec![u16::MAX; (W * H) as usize];
        let suzanne = m.suzanne.mesh();
        let mut scratch = vec![VertexSlot::EMPTY; suzanne.vertex_count()];
        let zb = DepthBuffer::new(&mut depth, W, H, Compare::Less).unwrap();
        let mut p = Pipeline::new(&camera(20), Viewport::new(W, H), CullClockwise, zb, lit());
        p.draw(&mut fb, &suzanne, &mut scratch).unwrap();
        star()
            .fill(&mut fb, FillRule::NonZero, Rgb565::new(10, 50, 10))
            .unwrap();
        for s in &shapes[5..] {
            s.draw(&mut fb).unwrap();
        }
        let cube = m.cube.mesh();
        let mut cs = vec![VertexSlot::EMPTY; cube.vertex_count()];
        let mut q = Pipeline::new(
            &camera(-35),
            Viewport::new(W, H),
            CullClockwise,
            p.depth.read_only(),
            lit(),
        );
        q.draw(
            &mut rasterizer_core::surface::Translucent::new(&mut fb, 128),
            &cube,
            &mut cs,
        )
        .unwrap();
        let mut r = Pipeline::new(&camera(60), Viewport::new(W, H), NoCull, NoDepth, lit());
        r.draw(&mut fb, &cube, &mut cs).unwrap();
        for t in s1::labels() {
            // The labels moved into this small screen.
            Text::with_baseline(t.text, Point::new(4, 50), t.character_style, Baseline::Top)
                .draw(&mut fb)
                .unwrap();
        }
        px
    }

    use embedded_graphics::text::{Baseline, Text};

    /// The list of the same commands, rendered with `rows`-row bands within `region`, pasted
    /// over a copy of `base`.
    fn listed(m: &Meshes, rows: u32, region: Rectangle, base: &[u16]) -> Vec<u16> {
        let (suzanne, cube) = (m.suzanne.mesh(), m.cube.mesh());
        let mut ss = vec![VertexSlot::EMPTY; suzanne.vertex_count()];
        let mut sb = vec![BinEntry::ZERO; suzanne.triangle_count() + 4];
        let mut cs1 = vec![VertexSlot::EMPTY; cube.vertex_count()];
        let mut cb1 = vec![BinEntry::ZERO; 16];
        let mut cs2 = vec![VertexSlot::EMPTY; cube.vertex_count()];
        let mut cb2 = vec![BinEntry::ZERO; 16];
        let vp = Viewport::new(W, H);
        let mut monkey = MeshCommand::new(
            Pipeline::new(&camera(20), vp, CullClockwise, SharedDepth, lit()),
            &suzanne,
            &mut ss,
            &mut sb,
        );
        let mut glass = MeshCommand::new(
            Pipeline::new(&camera(-35), vp, CullClockwise, SharedDepthReadOnly, lit()),
            &cube,
            &mut cs1,
            &mut cb1,
        )
        .with_opacity(128);
        let mut plain = MeshCommand::new(
            Pipeline::new(&camera(60), vp, NoCull, NoDepth, lit()),
            &cube,
            &mut cs2,
            &mut cb2,
        );
        let star = star();
        let fill = PolygonFill {
            polygon: &star,
            rule: FillRule::NonZero,
            color: Rgb565::new(10, 50, 10),
        };
        let labels: Vec<_> = s1::labels()
            .iter()
            .map(|t| {
                Text::with_baseline(t.text, Point::new(4, 50), t.character_style, Baseline::Top)
            })
            .collect();
        let shapes = shapes();
        let mut slots: Vec<Slot<'_, Rgb565>> = (0..20).map(|_| Slot::EMPTY).collect();
        let layout = Layout::new(W, H, rows).unwrap();
        let mut list = FrameList::new(&mut slots, layout, Clear::new(Rgb565::new(3, 6, 9)));
        for s in &shapes[..5] {
            list.shape(*s).unwrap();
        }
        list.command(&mut monkey).unwrap();
        list.item(&fill, 0).unwrap();
        for s in &shapes[5..] {
            list.shape(*s).unwrap();
        }
        list.command(&mut glass).unwrap();
        list.command(&mut plain).unwrap();
        for t in &labels {
            list.item(t, 0).unwrap();
        }
        let mut out = base.to_vec();
        let mut band = vec![0u16; (W * rows.min(H)) as usize];
        let mut depth = vec![0u16; (W * rows.min(H)) as usize];
        list.render_region(&region, &mut band, &mut depth, |b, area| {
            let data = b.framebuffer().as_slice();
            for y in area.rows() {
                for x in area.columns() {
                    let src = (y - b.y0()) as usize * W as usize + x as usize;
                    out[y as usize * W as usize + x as usize] = data[src];
                }
            }
        })
        .unwrap();
        out
    }

    #[test]
    fn every_command_in_bands_is_the_direct_drawing() {
        let m = meshes();
        let whole = direct(&m);
        let distinct: std::collections::HashSet<_> = whole.iter().collect();
        assert!(distinct.len() > 100, "{} colours", distinct.len());
        let screen = Rectangle::new(Point::zero(), Size::new(W, H));
        let blank = vec![0u16; (W * H) as usize];
        for rows in [1, 5, 16, 72] {
            let got = listed(&m, rows, screen, &blank);
            let diff = got.iter().zip(&whole).position(|(a, b)| a != b);
            assert_eq!(
                diff.map(|i| (i % W as usize, i / W as usize)),
                None,
                "{rows} rows"
            );
        }
    }

    #[test]
    fn any_region_is_the_direct_drawing_within_it() {
        let m = meshes();
        let whole = direct(&m);
        let blank = vec![0xbeef_u16; (W * H) as usize];
        let regions = [
            Rectangle::new(Point::new(13, 7), Size::new(40, 33)),
            Rectangle::new(Point::new(0, 0), Size::new(1, 1)),
            Rectangle::new(Point::new(95, 71), Size::new(5, 5)),
            Rectangle::new(Point::new(-10, 30), Size::new(200, 3)),
            Rectangle::new(Point::new(50, -4), Size::new(9, 200)),
        ];
        for region in regions {
            for rows in [3, 16] {
                let got = listed(&m, rows, region, &blank);
                for y in 0..H as i32 {
                    for x in 0..W as i32 {
                        let i = (y * W as i32 + x) as usize;
                        let want = if region.contains(Point::new(x, y)) {
                            whole[i]
                        } else {
                            0xbeef
                        };
                        assert_eq!(got[i], want, "({x}, {y}) of {region:?}, {rows} rows");
                    }
                }
            }
        }
    }
}

#[test]
fn summaries_change_with_what_a_command_draws() {
    // The same frame twice gives the same summaries; a change of light, material, opacity,
    // revision, shape colour or item revision changes exactly that command's.
    let m = meshes();
    let suzanne = m.suzanne.mesh();
    let layout = Layout::new(W, H, 16).unwrap();
    let summarize =
        |light: [i32; 3], diffuse: Rgb888, opacity: u8, revision: u32, red: u8, text: u32| {
            let mut scratch = vec![VertexSlot::EMPTY; suzanne.vertex_count()];
            let mut bins = vec![BinEntry::ZERO; suzanne.triangle_count()];
            let mut lighting = Lighting::new(
                Material {
                    diffuse,
                    ..fixtures::scenes3d::material()
                },
                Rgb888::WHITE,
                rasterizer_core::shade::Specular::BlinnPhong,
                Vec3::from_ints(0, 0, 3),
            );
            lighting
                .add_light(Light::Directional {
                    direction: Vec3::from_ints(light[0], light[1], light[2]),
                    color: Rgb888::WHITE,
                })
                .unwrap();
            let mut monkey: SuzanneCommand = MeshCommand::new(
                Pipeline::new(
                    &s1::transforms(s1::suzanne_model(30)),
                    s1::viewport(),
                    CullClockwise,
                    SharedDepth,
                    GouraudLit::new(lighting),
                ),
                &suzanne,
                &mut scratch,
                &mut bins,
            )
            .with_opacity(opacity);
            monkey.set_revision(revision);
            let labels = s1::labels();
            let mut slots = [Slot::EMPTY; 4];
            let mut list = FrameList::new(&mut slots, layout, Clear::new(Rgb565::BLACK));
            list.command(&mut monkey).unwrap();
            let mut g = s1::gouraud();
            if let rasterizer_core::frame::Shape::Gouraud { colors, .. } = &mut g {
                colors[0] = Rgb565::new(red, 0, 0);
            }
            list.shape(g).unwrap();
            list.item(&labels[0], text).unwrap();
            let mut out = [Summary::default(); 3];
            assert_eq!(list.summaries(&mut out), 3);
            out
        };
    let base = summarize([1, 1, 1], Rgb888::new(220, 140, 80), 255, 0, 31, 0);
    assert_eq!(
        base,
        summarize([1, 1, 1], Rgb888::new(220, 140, 80), 255, 0, 31, 0)
    );
    let variants = [
        (
            summarize([1, 2, 1], Rgb888::new(220, 140, 80), 255, 0, 31, 0),
            0,
        ),
        (
            summarize([1, 1, 1], Rgb888::new(220, 141, 80), 255, 0, 31, 0),
            0,
        ),
        (
            summarize([1, 1, 1], Rgb888::new(220, 140, 80), 254, 0, 31, 0),
            0,
        ),
        (
            summarize([1, 1, 1], Rgb888::new(220, 140, 80), 255, 1, 31, 0),
            0,
        ),
        (
            summarize([1, 1, 1], Rgb888::new(220, 140, 80), 255, 0, 30, 0),
            1,
        ),
        (
            summarize([1, 1, 1], Rgb888::new(220, 140, 80), 255, 0, 31, 7),
            2,
        ),
    ];
    for (k, (v, changed)) in variants.iter().enumerate() {
        for i in 0..3 {
            assert_eq!(v[i] != base[i], i == *changed, "variant {k}, command {i}");
        }
        // Same bounds: only the fingerprint tells the change.
        assert_eq!(v[*changed].bounds, base[*changed].bounds, "variant {k}");
    }
}
