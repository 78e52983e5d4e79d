//! One configuration at a time, for the code size of each effects combination
//! (`scripts/memory.sh`, `docs/MEMORY.md`): built with `--no-default-features` and the features
//! of one combination, `main` makes only the calls that combination needs, so the binary holds
//! only their code.
//!
//! 3D: one shading feature (`unlit`, `flat`, `gouraud`, `phong`, `matcap`), optionally `depth` (a 16-bit
//! depth buffer, `Compare::Less`), `cull` (`CullClockwise`) and the draw call (`draw` by default,
//! `banded` for `draw_banded` in 16-row bands), each with a vertex scratch of one slot per mesh
//! vertex, or with an empty one with `noscratch`, `dither` for 4 x 4 ordered dithering of the
//! interpolated colour, `fog` for linear fog (`shade::Fog`, with `flat`, `gouraud` or `phong`), and
//! `translucent` for the mesh drawn through `Translucent` at opacity 128 (with `depth`, the buffer
//! read-only). The scene is M1: the packed Suzanne, 320 x 240 Rgb565, one directional light; the
//! shading feature `textured` draws the textured cube (`TexturedLit`, the packed mesh's own
//! texture) through M1's camera instead.
//! 2D: `line2d`, `triangle2d`, `gouraud2d`, `polygon2d`, `aa2d` (an anti-aliased line 3 pixels
//! wide), each one call into a 320 x 240 Rgb565
//! framebuffer; `sprite`, a few of workload I1's sprites. A whole screen: `framelist` for workload S1 through the frame list in 16-row
//! bands (module `s1`; `double` for two band buffers); `antialias` for a cube with a static
//! adjacency table drawn with anti-aliased silhouettes, whole and in bands. No feature at all
//! gives the empty baseline (start-up and panic handler only).
//!
//! The buffers are `static`s, as firmware would place them, so `.bss` shows the frame memory of
//! the configuration.

use core::hint::black_box;

/// Screen width (M1). (Unused by the empty baseline.)
#[allow(dead_code)]
const W: u32 = 320;
/// Screen height (M1).
#[allow(dead_code)]
const H: u32 = 240;

// The feature groups `three_d` and `two_d`, and the combinations refused, are in `build.rs`.

/// A whole 320 x 240 Rgb565 frame (a static, for the 2D calls and the whole-frame 3D draws) as a
/// framebuffer.
#[cfg(any(two_d, feature = "antialias", all(three_d, not(feature = "banded"))))]
fn frame() -> Option<
    rasterizer_core::surface::Framebuffer<'static, embedded_graphics_core::pixelcolor::Rgb565>,
> {
    static mut FRAME: [u16; (W * H) as usize] = [0; (W * H) as usize];
    // SAFETY: `main` calls this once per use and drops the framebuffer before the next call; nothing
    // else refers to FRAME.
    #[allow(static_mut_refs)]
    let buf = unsafe { &mut FRAME };
    rasterizer_core::surface::Framebuffer::new(buf, W, H).ok()
}

/// The 2D calls of the chosen features.
#[cfg(two_d)]
fn draw_2d() {
    use embedded_graphics_core::pixelcolor::Rgb565;
    use embedded_graphics_core::prelude::*;
    use rasterizer_core::geom::SubPoint;

    let Some(mut fb) = frame() else {
        return;
    };
    #[allow(unused_variables)]
    let sp = |x: i32, y: i32| black_box(SubPoint::<4>::new(x * 16 + 5, y * 16 + 11));
    #[cfg(feature = "line2d")]
    {
        let p = |x: i32, y: i32| black_box(Point::new(x, y));
        let _ = rasterizer_core::raster::line::draw_line(
            &mut fb,
            p(-40, 7),
            p(371, 233),
            Rgb565::WHITE,
        );
    }
    #[cfg(feature = "triangle2d")]
    {
        let v = [sp(20, 10), sp(300, 120), sp(90, 230)];
        let _ = rasterizer_core::raster::triangle::fill_triangle(&mut fb, v, Rgb565::GREEN);
    }
    #[cfg(feature = "gouraud2d")]
    {
        let v = [sp(20, 10), sp(300, 120), sp(90, 230)];
        let c = [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE];
        let _ = rasterizer_core::raster::triangle::fill_triangle_gouraud(&mut fb, v, c);
    }
    #[cfg(feature = "aa2d")]
    {
        let p = |x: i32, y: i32| black_box(Point::new(x, y));
        let _ = rasterizer_core::raster::line::draw_line_aa_wide(
            &mut fb,
            p(-40, 7),
            p(371, 233),
            black_box(3),
            Rgb565::WHITE,
        );
    }
    #[cfg(feature = "sprite")]
    {
        use rasterizer_core::raster::sprite::{draw_sprite, Affine, Sprite};
        use rasterizer_core::texture::Filter;
        // I1's image from flash, a few of its placements (opaque, so the compiler cannot fold
        // the transforms away), over a cleared frame.
        let _ = fb.clear(Rgb565::BLACK);
        if let Ok(sprite) = Sprite::from_bytes(fixtures::sprite::I1_IMAGE) {
            for (i, deg) in [0, 37, 90, 211].into_iter().enumerate() {
                let p = black_box(fixtures::sprite::Placement {
                    cx: 40 + 80 * i as i32,
                    cy: 120,
                    degrees: deg,
                    scale_128: 64 + 48 * i as i32,
                });
                let _ = draw_sprite(&mut fb, &sprite, &p.transform(), Filter::Nearest);
                let _ = draw_sprite(&mut fb, &sprite, &p.transform(), Filter::Bilinear);
                let opaque: Affine = p.identity_transform();
                let _ = draw_sprite(&mut fb, &sprite.without_alpha(), &opaque, Filter::Nearest);
            }
        }
    }
    #[cfg(feature = "polygon2d")]
    {
        use rasterizer_core::raster::polygon::{FillRule, Polygon};
        let star = [
            sp(160, 5),
            sp(250, 230),
            sp(10, 80),
            sp(310, 80),
            sp(70, 230),
        ];
        if let Ok(poly) = Polygon::<8>::new(&star) {
            let _ = poly.fill(&mut fb, FillRule::NonZero, Rgb565::CYAN);
        }
    }
    black_box(fb.as_slice());
}

/// The 3D configuration of the chosen features.
#[cfg(three_d)]
mod three_d {
    use super::{H, W};
    use core::hint::black_box;
    use embedded_graphics_core::pixelcolor::Rgb565;
    use rasterizer_core::math::Fx16;
    use rasterizer_core::mesh::PackedMesh;
    use rasterizer_core::{pipeline::Pipeline, transform::Viewport};

    /// The mesh: Suzanne, or with `textured` the textured cube (its 64 x 64 texture inside).
    #[cfg(not(feature = "textured"))]
    use crate::m1::MESH;
    #[cfg(feature = "textured")]
    const MESH: &[u8] = include_bytes!("../../assets/meshes/cube_textured.rmsh");
    /// The mesh's vertices: the length of the vertex scratch.
    #[cfg(all(not(feature = "noscratch"), not(feature = "textured")))]
    const VERTICES: usize = 507;
    #[cfg(all(not(feature = "noscratch"), feature = "textured"))]
    const VERTICES: usize = 24;
    /// The mesh's triangles: bins for the worst case, every triangle visible.
    #[cfg(all(feature = "banded", not(feature = "textured")))]
    const TRIANGLES: usize = 968;
    #[cfg(all(feature = "banded", feature = "textured"))]
    const TRIANGLES: usize = 12;
    /// Rows per band.
    #[cfg(feature = "banded")]
    const ROWS: u32 = 16;
    /// Rows of the depth buffer: a band's or the whole frame's.
    #[cfg(all(feature = "depth", feature = "banded"))]
    const DEPTH_ROWS: u32 = ROWS;
    #[cfg(all(feature = "depth", not(feature = "banded")))]
    const DEPTH_ROWS: u32 = H;

    #[cfg(feature = "unlit")]
    type Sh = rasterizer_core::shade::Unlit<Rgb565>;
    #[cfg(feature = "flat")]
    type Sh = rasterizer_core::shade::FlatLit<Fx16, Rgb565, 1>;
    #[cfg(feature = "gouraud")]
    type Sh = rasterizer_core::shade::GouraudLit<Fx16, Rgb565, 1>;
    #[cfg(feature = "phong")]
    type Sh = rasterizer_core::shade::PhongLit<Fx16, Rgb565, 1>;
    #[cfg(feature = "textured")]
    type Sh = rasterizer_core::shade::TexturedLit<'static, Fx16, Rgb565, 1>;
    #[cfg(feature = "matcap")]
    type Sh = rasterizer_core::shade::MatCap<'static, Fx16, Rgb565>;

    /// The shading stage: the chosen model, fogged with `fog`.
    #[cfg(feature = "fog")]
    type Stage = rasterizer_core::shade::Fog<Fx16, Sh>;
    #[cfg(not(feature = "fog"))]
    type Stage = Sh;

    /// A vertex scratch slot of the chosen shading.
    type Slot = rasterizer_core::pipeline::VertexSlot<
        <Stage as rasterizer_core::shade::Shading<Fx16>>::Stored,
    >;

    #[cfg(feature = "depth")]
    static mut DEPTH: [u16; (W * DEPTH_ROWS) as usize] = [0; (W * DEPTH_ROWS) as usize];
    #[cfg(feature = "banded")]
    static mut BAND: [u16; (W * ROWS) as usize] = [0; (W * ROWS) as usize];
    #[cfg(feature = "banded")]
    static mut BINS: [rasterizer_core::pipeline::BinEntry; TRIANGLES] =
        [rasterizer_core::pipeline::BinEntry::ZERO; TRIANGLES];
    // Uninitialised, so that it lies in .bss (an initialised static's image would cost flash); the
    // draw call needs no particular contents anyway, but the slots are written once below so that
    // the array is initialised.
    #[cfg(not(feature = "noscratch"))]
    static mut SCRATCH: core::mem::MaybeUninit<[Slot; VERTICES]> = core::mem::MaybeUninit::uninit();

    #[cfg(feature = "unlit")]
    fn shading(_: &PackedMesh<'static>) -> Option<Sh> {
        Some(rasterizer_core::shade::Unlit {
            color: black_box(Rgb565::new(27, 35, 10)),
        })
    }

    #[cfg(not(any(feature = "unlit", feature = "textured", feature = "matcap")))]
    fn shading(_: &PackedMesh<'static>) -> Option<Sh> {
        use fixtures::scenes3d::{light_direction, lighting_with};
        // The light's direction is opaque, so that its normalisation is not folded away.
        Some(Sh::new(lighting_with::<1>(black_box(light_direction()))))
    }

    /// The default image, in flash; the view matrix opaque, so that the per-frame transform is
    /// not folded away.
    #[cfg(feature = "matcap")]
    fn shading(_: &PackedMesh<'static>) -> Option<Sh> {
        use fixtures::matcap::{GLOSSY_64, GLOSSY_64_SIDE_LOG2};
        let view = black_box(crate::m1::transforms()).view;
        Sh::new(GLOSSY_64_SIDE_LOG2, GLOSSY_64, &view).ok()
    }

    /// The texture is the packed mesh's own.
    #[cfg(feature = "textured")]
    fn shading(mesh: &PackedMesh<'static>) -> Option<Sh> {
        use fixtures::scenes3d::{light_direction, lighting_with};
        Some(Sh::new(
            lighting_with::<1>(black_box(light_direction())),
            mesh.texture()?,
        ))
    }

    /// The M1 frame; returns the number of triangles drawn.
    pub fn draw() -> u32 {
        let Ok(mesh) = PackedMesh::parse(black_box(MESH)) else {
            return 0;
        };
        let Some(shading) = shading(&mesh) else {
            return 0;
        };
        let xf = crate::m1::transforms();
        #[cfg(feature = "cull")]
        let cull = rasterizer_core::cull::CullClockwise;
        #[cfg(not(feature = "cull"))]
        let cull = rasterizer_core::cull::NoCull;
        #[cfg(feature = "depth")]
        let depth = {
            use rasterizer_core::depth::{Compare, DepthBuffer};
            // SAFETY: the only reference to DEPTH, made once.
            #[allow(static_mut_refs)]
            let z = unsafe { &mut DEPTH };
            z.fill(u16::MAX);
            let Ok(depth) = DepthBuffer::new(z, W, DEPTH_ROWS, Compare::Less) else {
                return 0;
            };
            #[cfg(feature = "translucent")]
            let depth = depth.read_only();
            depth
        };
        #[cfg(not(feature = "depth"))]
        let depth = rasterizer_core::depth::NoDepth;
        #[cfg(not(feature = "noscratch"))]
        let scratch: &mut [Slot] = {
            // SAFETY: the only reference to SCRATCH, made once; every slot is written before the
            // array is treated as initialised.
            #[allow(static_mut_refs)]
            let scratch = unsafe { &mut SCRATCH };
            let first = scratch.as_mut_ptr().cast::<Slot>();
            for i in 0..VERTICES {
                // SAFETY: `i` is within the array.
                unsafe { first.add(i).write(Slot::EMPTY) };
            }
            // SAFETY: all VERTICES slots were written above.
            unsafe { scratch.assume_init_mut() }
        };
        #[cfg(feature = "noscratch")]
        let scratch: &mut [Slot] = &mut [];
        #[cfg(feature = "fog")]
        let stage = {
            use rasterizer_core::shade::{Fog, FogCurve, FogSettings};
            // Opaque settings, so that the fog's arithmetic is not folded away.
            let settings = FogSettings {
                color: black_box(embedded_graphics_core::pixelcolor::Rgb888::new(
                    128, 144, 160,
                )),
                start: black_box(Fx16::from_int(2)),
                end: black_box(Fx16::from_int(4)),
                curve: FogCurve::Linear,
            };
            Fog::new(shading, settings, &xf.view)
        };
        #[cfg(not(feature = "fog"))]
        let stage = shading;
        let pl = Pipeline::new(&xf, Viewport::new(W, H), cull, depth, stage);
        #[cfg(feature = "dither")]
        let mut pl = {
            struct Bayer4;
            impl rasterizer_core::numerics::Numerics for Bayer4 {
                const DITHER: rasterizer_core::numerics::Dither =
                    rasterizer_core::numerics::Dither::Bayer4;
            }
            pl.with_numerics::<Bayer4>()
        };
        #[cfg(not(feature = "dither"))]
        let mut pl = pl;

        #[cfg(not(feature = "banded"))]
        {
            let Some(mut fb) = super::frame() else {
                return 0;
            };
            #[cfg(feature = "translucent")]
            let stats = pl
                .draw(
                    &mut rasterizer_core::surface::Translucent::new(&mut fb, black_box(128)),
                    &mesh,
                    scratch,
                )
                .ok();
            #[cfg(not(feature = "translucent"))]
            let stats = pl.draw(&mut fb, &mesh, scratch).ok();
            black_box(fb.as_slice());
            stats.map_or(0, |s| s.drawn)
        }
        #[cfg(feature = "banded")]
        {
            use rasterizer_core::pipeline::Banding;
            // SAFETY: the only references to BAND and BINS, made once.
            #[allow(static_mut_refs)]
            let (band, bins) = unsafe { (&mut BAND, &mut BINS) };
            let banding = Banding {
                width: W,
                height: H,
                rows: ROWS,
                background: Rgb565::new(0, 0, 0),
                clear_depth: u16::MAX,
            };
            pl.draw_banded(&mesh, &banding, band, bins, scratch, |b| {
                // Where firmware would start the display's DMA.
                black_box(b.framebuffer().as_slice());
            })
            .map_or(0, |s| s.drawn)
        }
    }
}

/// `antialias`: a cube with its adjacency table in flash, drawn with anti-aliased silhouettes
/// through M1's camera, whole (`Pipeline::draw_antialiased`) and in 16-row bands
/// (`Pipeline::draw_banded_antialiased`), flat-lit with a depth buffer. The table is what
/// `fixtures::adjacency::adjacency` gives for these triangles, written out as firmware would embed
/// it (a packed mesh from `convert --adjacency` carries its own).
#[cfg(feature = "antialias")]
mod antialias {
    use super::{H, W};
    use core::hint::black_box;
    use embedded_graphics_core::pixelcolor::Rgb565;
    use rasterizer_core::depth::{Compare, DepthBuffer};
    use rasterizer_core::math::{Fx16, Vec3};
    use rasterizer_core::mesh::{Mesh, MeshSource};
    use rasterizer_core::pipeline::{Banding, BinEntry, Pipeline, VertexSlot};
    use rasterizer_core::shade::{FlatLit, Shading};
    use rasterizer_core::transform::Viewport;

    /// Coordinate `bit` of corner `i`: half the cube's side (16.16), + when the bit is set.
    const fn at(i: usize, bit: usize) -> Fx16 {
        Fx16::from_bits(if i >> bit & 1 == 1 {
            1 << 15
        } else {
            -(1 << 15)
        })
    }
    /// The corners: bit 0 of the index is x, bit 1 y, bit 2 z.
    static CORNERS: [Vec3<Fx16>; 8] = {
        let mut c = [Vec3::new(at(0, 0), at(0, 1), at(0, 2)); 8];
        let mut i = 1;
        while i < 8 {
            c[i] = Vec3::new(at(i, 0), at(i, 1), at(i, 2));
            i += 1;
        }
        c
    };
    /// Two triangles a face, counter-clockwise seen from outside.
    static TRIANGLES: [[u32; 3]; 12] = [
        [0, 2, 3],
        [0, 3, 1],
        [4, 5, 7],
        [4, 7, 6],
        [0, 1, 5],
        [0, 5, 4],
        [2, 6, 7],
        [2, 7, 3],
        [0, 4, 6],
        [0, 6, 2],
        [1, 3, 7],
        [1, 7, 5],
    ];
    /// Entry `e` of triangle `t`: the triangle across its edge from corner `e` to `e + 1`.
    static ADJACENCY: [[u32; 3]; 12] = [
        [9, 7, 1],
        [0, 10, 4],
        [5, 11, 3],
        [2, 6, 8],
        [1, 11, 5],
        [4, 2, 8],
        [9, 3, 7],
        [6, 10, 0],
        [5, 3, 9],
        [8, 6, 0],
        [1, 7, 11],
        [10, 2, 4],
    ];
    /// Rows per band.
    const ROWS: u32 = 16;

    type Sh = FlatLit<Fx16, Rgb565, 1>;
    type Slot = VertexSlot<<Sh as Shading<Fx16>>::Stored>;

    static mut DEPTH: [u16; (W * H) as usize] = [0; (W * H) as usize];
    static mut BAND: [u16; (W * ROWS) as usize] = [0; (W * ROWS) as usize];
    /// One a triangle: the cube's visible ones are far fewer than 255 apart.
    static mut BINS: [BinEntry; 12] = [BinEntry::ZERO; 12];
    static mut SCRATCH: [Slot; 8] = [Slot::EMPTY; 8];

    fn shading() -> Sh {
        use fixtures::scenes3d::{light_direction, lighting_with};
        // The light's direction is opaque, so that its normalisation is not folded away.
        Sh::new(lighting_with::<1>(black_box(light_direction())))
    }

    /// Draws the cube whole, then in bands; returns the triangles drawn by both, or 0 when a
    /// draw was refused or the table does not pair its triangles up.
    pub fn draw() -> u32 {
        let mesh = Mesh::new(black_box(&CORNERS[..]), &TRIANGLES[..]).with_adjacency(&ADJACENCY);
        // A neighbour names its neighbour back: a table out of step with the triangles would
        // give wrong silhouettes, not a failure, so the run checks it.
        for t in 0..mesh.triangle_count() {
            for n in mesh.neighbours(t) {
                if !mesh.neighbours(n as usize).contains(&(t as u32)) {
                    return 0;
                }
            }
        }
        let xf = crate::m1::transforms();
        let cull = rasterizer_core::cull::CullClockwise;
        // SAFETY: the only references to these statics, made once.
        #[allow(static_mut_refs)]
        let (z, band, bins, scratch) = unsafe { (&mut DEPTH, &mut BAND, &mut BINS, &mut SCRATCH) };
        z.fill(u16::MAX);
        let Ok(depth) = DepthBuffer::new(z, W, H, Compare::Less) else {
            return 0;
        };
        let Some(mut fb) = super::frame() else {
            return 0;
        };
        let mut pl = Pipeline::new(&xf, Viewport::new(W, H), cull, depth, shading());
        let whole = pl
            .draw_antialiased(&mut fb, &mesh, scratch)
            .map_or(0, |s| s.drawn);
        black_box(fb.as_slice());
        let Ok(depth) = DepthBuffer::new(&mut z[..(W * ROWS) as usize], W, ROWS, Compare::Less)
        else {
            return 0;
        };
        let mut pl = Pipeline::new(&xf, Viewport::new(W, H), cull, depth, shading());
        let banding = Banding {
            width: W,
            height: H,
            rows: ROWS,
            background: Rgb565::new(0, 0, 0),
            clear_depth: u16::MAX,
        };
        let banded = pl
            .draw_banded_antialiased(&mesh, &banding, band, bins, scratch, |b| {
                // Where firmware would start the display's DMA.
                black_box(b.framebuffer().as_slice());
            })
            .map_or(0, |s| s.drawn);
        if whole == 0 || banded == 0 {
            return 0;
        }
        whole + banded
    }
}

/// The calls of the chosen combination; exits with 1 if a 3D configuration drew nothing.
#[unsafe(no_mangle)]
pub extern "C" fn main() -> i32 {
    #[cfg(two_d)]
    draw_2d();
    #[allow(unused_mut)]
    let mut drawn = 0u32;
    #[cfg(three_d)]
    {
        drawn += three_d::draw();
        // Nothing drawn means a broken configuration: fail the run.
        if black_box(drawn) == 0 {
            return 1;
        }
    }
    #[cfg(feature = "antialias")]
    {
        // Likewise for the anti-aliased cube (0 also when a draw was refused).
        if black_box(antialias::draw()) == 0 {
            return 1;
        }
    }
    #[cfg(feature = "framelist")]
    {
        // Likewise for S1's meshes (0 also when the list could not render).
        if black_box(crate::s1::draw()) == 0 {
            return 1;
        }
    }
    black_box(drawn);
    0
}
