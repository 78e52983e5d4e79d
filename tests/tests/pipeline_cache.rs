//! The vertex cache changes the work, never the picture.

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics_core::prelude::*;
use rasterizer_core::math::{Angle, Fx16, Mat4, Vec3};
use rasterizer_core::pipeline::cull::CullClockwise;
use rasterizer_core::pipeline::shading::{FlatLit, GouraudLit, PhongLit, Shading};
use rasterizer_core::pipeline::{CachedVertex, Mesh, Pipeline, Transforms, Viewport};
use rasterizer_core::raster::interp::{Compare, DepthBuffer};
use rasterizer_core::shade::{Light, Lighting, Material, Specular};
use rasterizer_core::target::Framebuffer;

/// A closed, smooth mesh: an octahedron subdivided twice and pushed out to the unit sphere.
fn sphere() -> (Vec<Vec3<Fx16>>, Vec<[u16; 3]>) {
    let mut pts: Vec<[f64; 3]> = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let mut tris: Vec<[u16; 3]> = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    for _ in 0..2 {
        let mut next = Vec::new();
        let mut mid = std::collections::HashMap::new();
        let mut midpoint = |a: u16, b: u16, pts: &mut Vec<[f64; 3]>| -> u16 {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (pts[a as usize], pts[b as usize]);
                let m = [
                    (p[0] + q[0]) / 2.0,
                    (p[1] + q[1]) / 2.0,
                    (p[2] + q[2]) / 2.0,
                ];
                let l = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
                pts.push([m[0] / l, m[1] / l, m[2] / l]);
                (pts.len() - 1) as u16
            })
        };
        for t in &tris {
            let ab = midpoint(t[0], t[1], &mut pts);
            let bc = midpoint(t[1], t[2], &mut pts);
            let ca = midpoint(t[2], t[0], &mut pts);
            next.extend([[t[0], ab, ca], [ab, t[1], bc], [ca, bc, t[2]], [ab, bc, ca]]);
        }
        tris = next;
    }
    let fx = |v: f64| Fx16::from_bits((v * 65536.0).round() as i32);
    (
        pts.iter()
            .map(|p| Vec3::new(fx(p[0]), fx(p[1]), fx(p[2])))
            .collect(),
        tris,
    )
}

fn lighting() -> Lighting<Fx16, 2> {
    let mut l = Lighting::new(
        Material {
            ambient: Rgb888::new(30, 30, 40),
            diffuse: Rgb888::new(200, 120, 60),
            specular: Rgb888::WHITE,
            shininess: 16,
        },
        Rgb888::WHITE,
        Specular::BlinnPhong,
        Vec3::from_ints(0, 0, 3),
    );
    l.add_light(Light::Directional {
        direction: Vec3::from_ints(1, 1, 1),
        color: Rgb888::WHITE,
    })
    .unwrap();
    l
}

fn render<Sh: Shading<Fx16, Color = Rgb565> + Clone>(shading: Sh, cached: bool) -> Vec<u16> {
    let (pos, tris) = sphere();
    let mesh = Mesh {
        positions: &pos,
        normals: Some(&pos),
        colors: None,
        triangles: &tris,
    };
    let xf = Transforms {
        model: Mat4::rotation_y(Angle::from_degrees(30)),
        view: Mat4::look_at(
            Vec3::from_ints(0, 0, 3),
            Vec3::default(),
            Vec3::from_ints(0, 1, 0),
        )
        .unwrap(),
        projection: Mat4::perspective(
            Angle::from_degrees(60),
            Fx16::from_ratio(4, 3),
            Fx16::from_ratio(1, 10),
            Fx16::from_int(100),
        )
        .unwrap(),
    };
    let mut z = vec![u16::MAX; 96 * 72];
    let depth = DepthBuffer::new(&mut z, 96, 72, Compare::Less).unwrap();
    let mut p =
        Pipeline::<_, _, _, _, 4>::new(&xf, Viewport::new(96, 72), CullClockwise, depth, shading);
    let mut buf = vec![0u16; 96 * 72];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 96, 72).unwrap();
    let stats = if cached {
        // Half the cache on purpose for one of the runs below would still be right; here it is full.
        let mut cache = vec![CachedVertex::default(); pos.len()];
        p.draw_cached(&mut fb, &mesh, &mut cache).unwrap()
    } else {
        p.draw(&mut fb, &mesh).unwrap()
    };
    // From distance 3 a third of the sphere faces the camera: about 43 of 128 triangles.
    assert!(stats.drawn > 30, "{stats:?}");
    buf
}

#[test]
fn cached_and_uncached_draws_are_identical() {
    assert_eq!(
        render(GouraudLit::<_, Rgb565, 2>::new(lighting()), true),
        render(GouraudLit::<_, Rgb565, 2>::new(lighting()), false)
    );
    assert_eq!(
        render(FlatLit::<_, Rgb565, 2>::new(lighting()), true),
        render(FlatLit::<_, Rgb565, 2>::new(lighting()), false)
    );
    assert_eq!(
        render(PhongLit::<_, Rgb565, 2>::new(lighting()), true),
        render(PhongLit::<_, Rgb565, 2>::new(lighting()), false)
    );
}

#[test]
fn short_cache_is_slower_not_wrong() {
    let (pos, tris) = sphere();
    let mesh = Mesh {
        positions: &pos,
        normals: Some(&pos),
        colors: None,
        triangles: &tris,
    };
    let xf = Transforms {
        model: Mat4::identity(),
        view: Mat4::look_at(
            Vec3::from_ints(0, 0, 3),
            Vec3::default(),
            Vec3::from_ints(0, 1, 0),
        )
        .unwrap(),
        projection: Mat4::perspective(
            Angle::from_degrees(60),
            Fx16::ONE,
            Fx16::from_ratio(1, 10),
            Fx16::from_int(100),
        )
        .unwrap(),
    };
    let draw = |cache_len: usize| {
        let mut buf = vec![0u16; 64 * 64];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 64, 64).unwrap();
        let mut z = vec![u16::MAX; 64 * 64];
        let depth = DepthBuffer::new(&mut z, 64, 64, Compare::Less).unwrap();
        let mut p = Pipeline::<_, _, _, _, 4>::new(
            &xf,
            Viewport::new(64, 64),
            CullClockwise,
            depth,
            GouraudLit::<_, Rgb565, 2>::new(lighting()),
        );
        let mut cache = vec![CachedVertex::default(); cache_len];
        p.draw_cached(&mut fb, &mesh, &mut cache).unwrap();
        buf
    };
    assert_eq!(draw(pos.len() / 3), draw(pos.len()));
    assert_eq!(draw(0), draw(pos.len()));
}

#[test]
fn cached_vertex_size_is_as_documented() {
    assert_eq!(core::mem::size_of::<CachedVertex<Fx16, [i32; 3], 4>>(), 40);
}

#[test]
fn lit_shading_without_normals_uses_face_normals() {
    // The sphere with no normals: Gouraud lighting falls back to each face's normal, so every
    // triangle is evenly lit (no specular term here) and the picture equals flat shading's.
    let (pos, tris) = sphere();
    let mesh = Mesh::new(&pos, &tris);
    let mut plain = lighting();
    plain.set_material(Material {
        ambient: Rgb888::new(30, 30, 40),
        diffuse: Rgb888::new(200, 120, 60),
        specular: Rgb888::BLACK,
        shininess: 0,
    });
    let draw = |gouraud: bool| {
        let xf = Transforms {
            model: Mat4::identity(),
            view: Mat4::look_at(
                Vec3::from_ints(0, 0, 3),
                Vec3::default(),
                Vec3::from_ints(0, 1, 0),
            )
            .unwrap(),
            projection: Mat4::perspective(
                Angle::from_degrees(60),
                Fx16::ONE,
                Fx16::from_ratio(1, 10),
                Fx16::from_int(100),
            )
            .unwrap(),
        };
        let mut buf = vec![0u16; 64 * 64];
        let mut fb = Framebuffer::<Rgb565>::new(&mut buf, 64, 64).unwrap();
        let mut z = vec![u16::MAX; 64 * 64];
        let depth = DepthBuffer::new(&mut z, 64, 64, Compare::Less).unwrap();
        if gouraud {
            let mut p = Pipeline::<_, _, _, _, 4>::new(
                &xf,
                Viewport::new(64, 64),
                CullClockwise,
                depth,
                GouraudLit::<_, Rgb565, 2>::new(plain.clone()),
            );
            p.draw(&mut fb, &mesh).unwrap();
        } else {
            let mut p = Pipeline::<_, _, _, _, 4>::new(
                &xf,
                Viewport::new(64, 64),
                CullClockwise,
                depth,
                FlatLit::<_, Rgb565, 2>::new(plain.clone()),
            );
            p.draw(&mut fb, &mesh).unwrap();
        }
        buf
    };
    let (g, f) = (draw(true), draw(false));
    let distinct: std::collections::BTreeSet<u16> = g.iter().copied().filter(|&c| c != 0).collect();
    assert!(
        distinct.len() > 10,
        "faces should be lit differently: {} colours",
        distinct.len()
    );
    // Flat shading lights the centroid and Gouraud each corner with the same normal; with no
    // specular term and a directional light the colour does not depend on the position, so they
    // agree up to the 8.8 rounding of the interpolated colour: at most one step of a channel.
    let close = g.iter().zip(&f).all(|(&a, &b)| {
        let (ca, cb) = (
            Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(a)),
            Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(b)),
        );
        (i16::from(ca.r()) - i16::from(cb.r())).abs() <= 1
            && (i16::from(ca.g()) - i16::from(cb.g())).abs() <= 1
            && (i16::from(ca.b()) - i16::from(cb.b())).abs() <= 1
    });
    assert!(close);
}
