//! The default build: every public drawing entry point, into each pixel format, through the
//! framebuffer's fast paths and the generic `DrawTarget` adapter, the 3D draws, and the frame
//! list (every kind of command, rendered in bands, as a region and double-buffered).

use core::hint::black_box;
use embedded_graphics_core::pixelcolor::{BinaryColor, Gray8, Rgb565, Rgb888};
use embedded_graphics_core::prelude::*;
use rasterizer_core::geom::SubPoint;
use rasterizer_core::raster::line::{
    draw_line, draw_line_aa, draw_line_aa_wide, draw_line_alpha, draw_line_gradient,
};
use rasterizer_core::raster::point::draw_point;
use rasterizer_core::raster::polygon::{FillRule, Polygon};
use rasterizer_core::raster::triangle::{
    draw_triangle, fill_triangle, fill_triangle_alpha, fill_triangle_gouraud,
};
use rasterizer_core::surface::{AnyTarget, Band, Framebuffer, Surface, Translucent};

static mut RGB565: [u16; 64 * 48] = [0; 64 * 48];

fn draw_all<S: Surface>(s: &mut S, a: S::Color, b: S::Color, c: S::Color) -> Result<(), S::Error>
where
    S::Color: rasterizer_core::color::Channels,
{
    let p = |x: i32, y: i32| black_box(Point::new(x, y));
    let sp = |x: i32, y: i32| black_box(SubPoint::<4>::new(x, y));
    draw_point(s, p(3, 4), a)?;
    draw_line(s, p(-5, 2), p(70, 40), a)?;
    draw_line_gradient(s, p(0, 47), p(63, 0), a, b)?;
    draw_triangle(s, [p(1, 1), p(60, 5), p(20, 40)], b)?;
    fill_triangle(s, [sp(10, 10), sp(900, 100), sp(300, 700)], a)?;
    fill_triangle_gouraud(s, [sp(10, 10), sp(900, 100), sp(300, 700)], [a, b, c])?;
    let star = [
        sp(500, 50),
        sp(700, 700),
        sp(50, 250),
        sp(950, 250),
        sp(300, 700),
    ];
    if let Ok(poly) = Polygon::<8>::new(&star) {
        poly.fill(s, FillRule::NonZero, c)?;
        poly.fill(s, FillRule::EvenOdd, a)?;
    }
    // Blending: drawn where the surface reads back, `CannotReadBack` through `AnyTarget`.
    let _ = fill_triangle_alpha(
        s,
        [sp(10, 10), sp(900, 100), sp(300, 700)],
        b,
        black_box(100),
    );
    let _ = draw_line_alpha(s, p(-5, 40), p(70, 2), c, black_box(160));
    let _ = draw_line_aa(s, p(-5, 7), p(70, 30), a);
    let _ = draw_line_aa_wide(s, p(-5, 30), p(70, 7), black_box(3), b);
    let _ = fill_triangle(
        &mut Translucent::new(s, black_box(90)),
        [sp(10, 10), sp(900, 100), sp(300, 700)],
        c,
    );
    Ok(())
}

/// The 3D entry points: packed mesh, pipeline draws (filled, wireframe, banded; with a short
/// vertex scratch and with none) with the float-free default stages.
fn draw_3d(buf: &mut [u16]) -> u32 {
    use rasterizer_core::cull::{CullClockwise, NoCull};
    use rasterizer_core::depth::{Compare, DepthBuffer, NoDepth};
    use rasterizer_core::math::{Fx16, Vec3};
    use rasterizer_core::mesh::PackedMesh;
    use rasterizer_core::shade::{FlatLit, PhongLit, Unlit};
    use rasterizer_core::shade::{Light, Lighting, Material, Specular};
    use rasterizer_core::{
        pipeline::Banding, pipeline::BinEntry, pipeline::Pipeline, pipeline::VertexSlot,
        transform::Viewport,
    };

    let Ok(mesh) = PackedMesh::parse(black_box(crate::m1::MESH)) else {
        return 0;
    };
    let p = |x, y, z| Vec3::<Fx16>::from_ints(x, y, z);
    let xf = crate::m1::transforms();
    let mut lighting = Lighting::<Fx16, 2>::new(
        Material {
            ambient: Rgb888::new(9, 9, 9),
            diffuse: Rgb888::WHITE,
            specular: Rgb888::WHITE,
            shininess: 8,
        },
        Rgb888::WHITE,
        Specular::Phong,
        p(0, 0, 3),
    );
    let _ = lighting.add_light(Light::Point {
        position: p(2, 2, 2),
        color: Rgb888::WHITE,
    });
    let vp = Viewport::new(64, 48);
    let mut drawn = 0;
    let Ok(mut fb) = Framebuffer::<Rgb565>::new(buf, 64, 48) else {
        return 0;
    };
    let mut z = [u16::MAX; 64 * 48];
    if let Ok(depth) = DepthBuffer::new(&mut z, 64, 48, Compare::Less) {
        let mut pl = Pipeline::new(
            &xf,
            vp,
            CullClockwise,
            depth,
            PhongLit::<Fx16, Rgb565, 2>::new(lighting.clone()),
        );
        // Shorter than the mesh: the first 16 vertices are kept, the others processed per triangle.
        let mut scratch = [VertexSlot::EMPTY; 16];
        drawn += pl.draw(&mut fb, &mesh, &mut scratch).map_or(0, |s| s.drawn);
        // A translucent pass over it: the same buffer read-only.
        let mut pl = Pipeline::new(
            &xf,
            vp,
            CullClockwise,
            pl.depth.read_only(),
            FlatLit::<Fx16, Rgb565, 2>::new(lighting.clone()),
        );
        drawn += pl
            .draw(
                &mut Translucent::new(&mut fb, black_box(128)),
                &mesh,
                &mut [],
            )
            .map_or(0, |s| s.drawn);
    }
    let mut pl = Pipeline::new(&xf, vp, NoCull, NoDepth, Unlit { color: Rgb565::RED });
    drawn += pl.draw(&mut fb, &mesh, &mut []).map_or(0, |s| s.drawn);
    drawn += pl
        .draw_wireframe(&mut fb, &mesh, &mut [], Rgb565::WHITE)
        .map_or(0, |s| s.drawn);
    // MatCap per vertex with the default image, read from flash.
    let glossy = fixtures::matcap::GLOSSY_64;
    let side = black_box(fixtures::matcap::GLOSSY_64_SIDE_LOG2);
    if let Ok(matcap) = rasterizer_core::shade::MatCap::<Fx16, Rgb565>::new(side, glossy, &xf.view)
    {
        let mut pl = Pipeline::new(&xf, vp, CullClockwise, NoDepth, matcap);
        let mut scratch = [VertexSlot::EMPTY; 16];
        drawn += pl.draw(&mut fb, &mesh, &mut scratch).map_or(0, |s| s.drawn);
    }
    // Bands of 8 rows.
    let mut band_z = [u16::MAX; 64 * 8];
    if let Ok(depth) = DepthBuffer::new(&mut band_z, 64, 8, Compare::Less) {
        let mut pl = Pipeline::new(
            &xf,
            vp,
            CullClockwise,
            depth,
            FlatLit::<Fx16, Rgb565, 2>::new(lighting),
        );
        let mut band = [0u16; 64 * 8];
        let mut bins = [BinEntry::ZERO; 1024];
        let mut scratch = [VertexSlot::EMPTY; 64];
        let banding = Banding {
            width: 64,
            height: 48,
            rows: 8,
            background: Rgb565::BLACK,
            clear_depth: u16::MAX,
        };
        drawn += pl
            .draw_banded(&mesh, &banding, &mut band, &mut bins, &mut scratch, |b| {
                black_box(b.framebuffer().as_slice());
            })
            .map_or(0, |s| s.drawn);
    }
    drawn
}

/// Two band buffers and a transfer that firmware would start on the display's DMA.
struct Dma<'b> {
    bands: [&'b mut [u16]; 2],
}

impl rasterizer_core::frame::DoubleBuffer<Rgb565> for Dma<'_> {
    type Error = ();

    fn buffer(&mut self, k: usize) -> &mut [u16] {
        let [first, second] = &mut self.bands;
        if k == 0 {
            first
        } else {
            second
        }
    }

    fn start(
        &mut self,
        k: usize,
        rows: embedded_graphics_core::primitives::Rectangle,
        area: embedded_graphics_core::primitives::Rectangle,
    ) -> Result<(), ()> {
        black_box((&self.bands[k & 1][..], rows, area));
        Ok(())
    }

    fn wait(&mut self, k: usize) -> Result<(), ()> {
        black_box(k);
        Ok(())
    }
}

/// The frame list's entry points: a mesh testing and writing the shared depth, a translucent
/// one testing it only, every 2D shape (opacities hidden from the compiler, so that both the
/// opaque and the blended paths are linked), a text label and a polygon; rendered in bands, as a region and
/// double-buffered; the summaries and the areas that changed between two frames.
fn draw_frame_list() -> u32 {
    use embedded_graphics_core::primitives::Rectangle;
    use rasterizer_core::cull::{CullClockwise, NoCull};
    use rasterizer_core::depth::{SharedDepth, SharedDepthReadOnly};
    use rasterizer_core::frame::MeshCommand;
    use rasterizer_core::frame::{
        changed_areas, Clear, FrameList, Layout, PolygonFill, Shape, Slot, Summary,
    };
    use rasterizer_core::math::Fx16;
    use rasterizer_core::mesh::PackedMesh;
    use rasterizer_core::pipeline::{BinEntry, Pipeline, VertexSlot};
    use rasterizer_core::shade::{FlatLit, GouraudLit};
    use rasterizer_core::transform::Viewport;

    let Ok(mesh) = PackedMesh::parse(black_box(crate::m1::MESH)) else {
        return 0;
    };
    let xf = crate::m1::transforms();
    let vp = Viewport::new(64, 48);
    let lighting = fixtures::scenes3d::lighting::<1>();
    let mut scratch = [VertexSlot::EMPTY; 64];
    let mut bins = [BinEntry::ZERO; 1024];
    let mut opaque = MeshCommand::new(
        Pipeline::new(
            &xf,
            vp,
            CullClockwise,
            SharedDepth,
            GouraudLit::<Fx16, Rgb565, 1>::new(lighting.clone()),
        ),
        &mesh,
        &mut scratch,
        &mut bins,
    );
    let mut glass_scratch = [VertexSlot::EMPTY; 16];
    let mut glass_bins = [BinEntry::ZERO; 1024];
    let mut glass = MeshCommand::new(
        Pipeline::new(
            &xf,
            vp,
            NoCull,
            SharedDepthReadOnly,
            FlatLit::<Fx16, Rgb565, 1>::new(lighting),
        ),
        &mesh,
        &mut glass_scratch,
        &mut glass_bins,
    )
    .with_opacity(black_box(100));
    let p = |x: i32, y: i32| black_box(Point::new(x, y));
    let sp = |x: i32, y: i32| black_box(SubPoint::<4>::new(x, y));
    let shapes = [
        Shape::Line {
            a: p(-5, 2),
            b: p(70, 40),
            color: Rgb565::RED,
        },
        Shape::LineGradient {
            a: p(0, 47),
            b: p(63, 0),
            colors: [Rgb565::RED, Rgb565::BLUE],
        },
        Shape::LineAlpha {
            a: p(-5, 40),
            b: p(70, 2),
            color: Rgb565::GREEN,
            alpha: black_box(160),
        },
        Shape::LineAa {
            a: p(-5, 30),
            b: p(70, 7),
            width: black_box(3),
            color: Rgb565::WHITE,
        },
        Shape::TriangleOutline {
            vertices: [p(1, 1), p(60, 5), p(20, 40)],
            color: Rgb565::CYAN,
        },
        Shape::Triangle {
            vertices: [sp(10, 10), sp(900, 100), sp(300, 700)],
            color: Rgb565::BLUE,
            opacity: black_box(255),
        },
        Shape::Gouraud {
            vertices: [sp(10, 10), sp(900, 100), sp(300, 700)],
            colors: [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE],
            opacity: black_box(255),
        },
    ];
    let labels = fixtures::s1::labels();
    let star = [
        sp(500, 50),
        sp(700, 700),
        sp(50, 250),
        sp(950, 250),
        sp(300, 700),
    ];
    let Ok(polygon) = Polygon::<8>::new(&star) else {
        return 0;
    };
    let star = PolygonFill {
        polygon: &polygon,
        rule: FillRule::EvenOdd,
        color: Rgb565::YELLOW,
    };
    let mut rendered = true;
    {
        let Ok(layout) = Layout::new(64, 48, 8) else {
            return 0;
        };
        let mut slots = [Slot::EMPTY; 16];
        let mut list = FrameList::new(&mut slots, layout, Clear::new(Rgb565::BLACK));
        rendered &= list.command(&mut opaque).is_ok();
        rendered &= list.command(&mut glass).is_ok();
        for shape in shapes {
            rendered &= list.shape(shape).is_ok();
        }
        rendered &= list.item(&labels[0], 0).is_ok();
        rendered &= list.item(&star, 0).is_ok();
        let (mut band, mut other) = ([0u16; 64 * 8], [0u16; 64 * 8]);
        let mut depth = [0u16; 64 * 8];
        rendered &= list
            .render(&mut band, &mut depth, |b, area| {
                black_box((b.framebuffer().as_slice(), area));
            })
            .is_ok();
        let region = black_box(Rectangle::new(Point::new(8, 5), Size::new(30, 20)));
        rendered &= list
            .render_region(&region, &mut band, &mut depth, |b, area| {
                black_box((b.framebuffer().as_slice(), area));
            })
            .is_ok();
        let mut dma = Dma {
            bands: [&mut band, &mut other],
        };
        rendered &= list.render_double(None, &mut depth, &mut dma).is_ok();
        let mut frame = [Summary::default(); 16];
        let n = list.summaries(&mut frame);
        let mut areas = [Rectangle::zero(); 4];
        black_box(changed_areas(
            black_box(&frame[..n.min(16)]),
            black_box(&[]),
            &mut areas,
        ));
        black_box(&areas);
    }
    if !rendered {
        return 0;
    }
    opaque.stats().drawn + glass.stats().drawn
}

/// Workload I1's sprite from flash, turned and scaled into a framebuffer and a band, every
/// filter, blended and opaque, and a 1-bit and a 4-bit sprite of the same texels.
fn draw_sprites() -> usize {
    use rasterizer_core::raster::sprite::{draw_sprite, AlphaBits, Sprite};
    use rasterizer_core::texture::Filter;
    let Ok(sprite) = Sprite::from_bytes(fixtures::sprite::I1_IMAGE) else {
        return 0;
    };
    let colors = sprite.color_bytes();
    let keyed = Sprite::from_parts(32, 32, AlphaBits::One, colors, &[0xA5; 4 * 32]);
    let soft = Sprite::from_parts(32, 32, AlphaBits::Four, colors, &[0x9C; 16 * 32]);
    let mut drawn = 0;
    let mut buf = [0u16; 64 * 48];
    let mut strip = [0u16; 64 * 8];
    let p = black_box(fixtures::sprite::Placement {
        cx: 30,
        cy: 20,
        degrees: 33,
        scale_128: 150,
    });
    for s in [Ok(sprite), keyed, soft, Ok(sprite.without_alpha())]
        .into_iter()
        .flatten()
    {
        for filter in [Filter::Nearest, Filter::Bilinear] {
            if let Ok(mut fb) = Framebuffer::<Rgb565>::new(&mut buf, 64, 48) {
                drawn += usize::from(draw_sprite(&mut fb, &s, &p.transform(), filter).is_ok());
            }
            if let Ok(fb) = Framebuffer::<Rgb565>::new(&mut strip, 64, 8) {
                let mut band = Band::new(fb, 16);
                drawn += usize::from(draw_sprite(&mut band, &s, &p.transform(), filter).is_ok());
            }
        }
    }
    black_box((&buf, &strip));
    drawn
}

#[unsafe(no_mangle)]
pub extern "C" fn main() -> i32 {
    // Rgb565 through the framebuffer's own fast paths, in a static buffer as firmware would.
    #[allow(static_mut_refs)]
    let buf = unsafe { &mut RGB565 };
    if let Ok(mut fb) = Framebuffer::<Rgb565>::new(buf, 64, 48) {
        let _ = draw_all(&mut fb, Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE);
        // And through the generic DrawTarget adapter.
        let _ = draw_all(
            &mut AnyTarget::new(&mut fb),
            Rgb565::WHITE,
            Rgb565::CYAN,
            Rgb565::BLACK,
        );
        black_box(fb.as_slice());
    }
    let mut rgb = [0u8; 16 * 16 * 3];
    if let Ok(mut fb) = Framebuffer::<Rgb888>::new(&mut rgb, 16, 16) {
        let _ = draw_all(&mut fb, Rgb888::RED, Rgb888::GREEN, Rgb888::BLUE);
    }
    let mut gray = [0u8; 16 * 16];
    if let Ok(mut fb) = Framebuffer::<Gray8>::new(&mut gray, 16, 16) {
        let _ = draw_all(&mut fb, Gray8::WHITE, Gray8::new(80), Gray8::BLACK);
    }
    let mut mono = [0u8; 2 * 16];
    if let Ok(mut fb) = Framebuffer::<BinaryColor>::new(&mut mono, 16, 16) {
        let _ = fb.clear(BinaryColor::Off);
        let _ = draw_all(&mut fb, BinaryColor::On, BinaryColor::Off, BinaryColor::On);
    }
    black_box((&rgb, &gray, &mono));
    // A band blends in screen coordinates.
    let mut strip = [0u16; 64 * 8];
    if let Ok(fb) = Framebuffer::<Rgb565>::new(&mut strip, 64, 8) {
        let _ = draw_all(
            &mut Band::new(fb, 16),
            Rgb565::RED,
            Rgb565::GREEN,
            Rgb565::BLUE,
        );
    }
    black_box(&strip);
    black_box(draw_sprites());
    let mut small = [0u16; 64 * 48];
    black_box(draw_3d(&mut small));
    // Nothing drawn through the list means it refused something: fail the run.
    if black_box(draw_frame_list()) == 0 {
        return 1;
    }
    0
}
