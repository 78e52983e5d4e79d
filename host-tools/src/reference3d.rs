//! An independent `f64` reference for the 3D pipeline: matrices, Sutherland-Hodgman clipping in
//! homogeneous space, the perspective divide and viewport, and a renderer that rasterizes with `f64`
//! edge functions at pixel centres (top-left rule) and an `f64` depth test, producing a triangle id
//! per pixel.
//!
//! Nothing here calls into `rasterizer-core`'s geometry: the matrices are built from the same
//! parameters (angles, positions, planes) with `f64` trigonometry, so a comparison measures the
//! fixed-point pipeline against the exact computation. Then come the `f64` lighting model (the
//! formula of `rasterizer_core::shade`, unrounded) and the perspective-correct interpolation of
//! per-vertex values (the true Gouraud image). The last section holds the small pipeline-side
//! helpers the comparisons need (a shader that paints each face with its id).

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use rasterizer_core::math::{Fx16, Scalar, Vec3};
use rasterizer_core::shade::{Material, Specular};
use rasterizer_core::shade::{Shading, VertexIn};

/// A 4x4 matrix, `m[row][column]`, column vectors (`p' = M p`).
pub type M4 = [[f64; 4]; 4];
/// A homogeneous point.
pub type V4 = [f64; 4];
/// A 3D point or direction.
pub use crate::vec64::V3;
use crate::vec64::{add as add3, cross as cross3, dot as dot3, sub as sub3};

/// The identity.
pub fn identity() -> M4 {
    scale(1.0, 1.0, 1.0)
}

/// `a * b`: apply `b` first, then `a`.
pub fn mul(a: &M4, b: &M4) -> M4 {
    let mut out = [[0.0; 4]; 4];
    for (r, row) in out.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = (0..4).map(|k| a[r][k] * b[k][c]).sum();
        }
    }
    out
}

/// `m * v`.
pub fn apply(m: &M4, v: V4) -> V4 {
    let mut out = [0.0; 4];
    for (r, o) in out.iter_mut().enumerate() {
        *o = (0..4).map(|k| m[r][k] * v[k]).sum();
    }
    out
}

/// `m * (p, 1)`.
pub fn apply_point(m: &M4, p: V3) -> V4 {
    apply(m, [p[0], p[1], p[2], 1.0])
}

/// Scale along the axes.
pub fn scale(x: f64, y: f64, z: f64) -> M4 {
    [
        [x, 0.0, 0.0, 0.0],
        [0.0, y, 0.0, 0.0],
        [0.0, 0.0, z, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// Translation by `t`.
pub fn translation(t: V3) -> M4 {
    let mut m = identity();
    for (k, v) in t.iter().enumerate() {
        m[k][3] = *v;
    }
    m
}

/// An angle in 1/65536 turns (the unit of `rasterizer_core::math::Angle`) in radians.
pub fn turn_units_to_radians(units: f64) -> f64 {
    units / 65536.0 * std::f64::consts::TAU
}

/// Rotation about x (counter-clockwise looking from +x towards the origin).
pub fn rotation_x(rad: f64) -> M4 {
    let (s, c) = rad.sin_cos();
    [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, c, -s, 0.0],
        [0.0, s, c, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// Rotation about y.
pub fn rotation_y(rad: f64) -> M4 {
    let (s, c) = rad.sin_cos();
    [
        [c, 0.0, s, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [-s, 0.0, c, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// Rotation about z.
pub fn rotation_z(rad: f64) -> M4 {
    let (s, c) = rad.sin_cos();
    [
        [c, -s, 0.0, 0.0],
        [s, c, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

fn unit3(a: V3) -> V3 {
    let l = dot3(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// The view matrix of a camera at `eye` looking at `target`, `up` roughly up (right-handed, the
/// camera looking down -z).
pub fn look_at(eye: V3, target: V3, up: V3) -> M4 {
    let f = unit3(sub3(target, eye));
    let s = unit3(cross3(f, up));
    let u = cross3(s, f);
    [
        [s[0], s[1], s[2], -dot3(s, eye)],
        [u[0], u[1], u[2], -dot3(u, eye)],
        [-f[0], -f[1], -f[2], dot3(f, eye)],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// The OpenGL perspective projection (vertical field of view in radians).
pub fn perspective(fov_y: f64, aspect: f64, near: f64, far: f64) -> M4 {
    let f = 1.0 / (fov_y / 2.0).tan();
    [
        [f / aspect, 0.0, 0.0, 0.0],
        [0.0, f, 0.0, 0.0],
        [
            0.0,
            0.0,
            (far + near) / (near - far),
            2.0 * far * near / (near - far),
        ],
        [0.0, 0.0, -1.0, 0.0],
    ]
}

/// The inverse by Gauss-Jordan elimination with partial pivoting; `None` when singular.
pub fn inverse(m: &M4) -> Option<M4> {
    let mut a = *m;
    let mut inv = identity();
    for col in 0..4 {
        let pivot = (col..4).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, pivot);
        inv.swap(col, pivot);
        let p = a[col][col];
        for k in 0..4 {
            a[col][k] /= p;
            inv[col][k] /= p;
        }
        for r in 0..4 {
            if r != col {
                let f = a[r][col];
                for k in 0..4 {
                    a[r][k] -= f * a[col][k];
                    inv[r][k] -= f * inv[col][k];
                }
            }
        }
    }
    Some(inv)
}

/// A clip-space point on a `width` x `height` viewport at the origin: `(x, y)` in pixels (y down,
/// `x/w = -1` at the left edge, `y/w = +1` at the top) and the depth `(z/w + 1) / 2 * 65535`.
///
/// `x` and `y` are snapped to multiples of 2^-24 pixels: far below any error that matters, but it
/// turns the last-bit noise of `f64` (184.00000000000003) into the exact value when a vertex lies
/// exactly on a pixel grid line, so that pixel centres exactly on an edge follow the top-left rule
/// instead of that noise.
pub fn to_screen(p: V4, width: u32, height: u32) -> V3 {
    let (x, y, z) = (p[0] / p[3], p[1] / p[3], p[2] / p[3]);
    let snap = |v: f64| (v * 16_777_216.0).round() / 16_777_216.0;
    [
        snap((x + 1.0) * f64::from(width) / 2.0),
        snap((1.0 - y) * f64::from(height) / 2.0),
        (z + 1.0) / 2.0 * 65535.0,
    ]
}

/// The smallest `w` the reference keeps, as the pipeline documents (`2^-8`): only matters for
/// projections without a near plane.
pub const W_MIN: f64 = 1.0 / 256.0;

/// Sutherland-Hodgman against `w >= W_MIN`, the near plane `z >= -w` and the far plane `z <= w`.
/// (No x/y planes: the rasterizer below clips to the screen exactly.)
pub fn clip_polygon(poly: &[V4]) -> Vec<V4> {
    let planes: [fn(&V4) -> f64; 3] = [|p| p[3] - W_MIN, |p| p[2] + p[3], |p| p[3] - p[2]];
    let mut cur: Vec<V4> = poly.to_vec();
    for d in planes {
        if cur.len() < 3 {
            return Vec::new();
        }
        let mut out = Vec::with_capacity(cur.len() + 1);
        for i in 0..cur.len() {
            let (a, b) = (cur[i], cur[(i + 1) % cur.len()]);
            let (da, db) = (d(&a), d(&b));
            if da >= 0.0 {
                out.push(a);
            }
            // A vertex on the plane is kept as it is and makes no crossing point (which would
            // only duplicate it).
            if (da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0) {
                let t = da / (da - db);
                out.push([0, 1, 2, 3].map(|k| a[k] + (b[k] - a[k]) * t));
            }
        }
        cur = out;
    }
    if cur.len() < 3 {
        Vec::new()
    } else {
        cur
    }
}

/// Which triangles the reference drops, by their signed area on screen (y down), as the pipeline's
/// culling stages document.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RefCull {
    /// Keep all.
    None,
    /// Drop those that appear clockwise with y up (positive area with y down).
    Clockwise,
    /// Drop those that appear counter-clockwise with y up (negative area with y down).
    CounterClockwise,
}

/// A reference render.
#[derive(Debug, Clone)]
pub struct RefRender {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The nearest triangle's id per pixel (the first drawn wins an exact tie, as with `Less`).
    pub id: Vec<Option<u32>>,
    /// Every triangle covering each pixel centre, with its depth there (0..65535, unrounded).
    pub frags: Vec<Vec<(u32, f64)>>,
    /// Per pixel, the distance in pixels from its centre to the nearest edge of any drawn polygon
    /// (clipped, projected, not culled), capped at [`EDGE_SEARCH`].
    pub edge_dist: Vec<f64>,
    /// Polygons drawn (not culled, not clipped away).
    pub drawn: u32,
    /// Polygons culled or of zero area.
    pub culled: u32,
}

/// How far from a polygon [`RefRender::edge_dist`] looks, in pixels.
pub const EDGE_SEARCH: f64 = 3.0;

impl RefRender {
    /// The reference depth of triangle `id` at pixel `i`, if it covers that centre.
    pub fn depth_of(&self, i: usize, id: u32) -> Option<f64> {
        self.frags[i]
            .iter()
            .find(|(t, _)| *t == id)
            .map(|(_, d)| *d)
    }

    /// The depth of the nearest fragment at pixel `i`.
    pub fn nearest_depth(&self, i: usize) -> Option<f64> {
        self.frags[i].iter().map(|(_, d)| *d).min_by(f64::total_cmp)
    }
}

/// The distance from `p` to the segment `a`-`b`.
fn seg_dist(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (qx, qy) = (a.0 + dx * t - p.0, a.1 + dy * t - p.1);
    (qx * qx + qy * qy).sqrt()
}

/// Renders triangles (`positions` in model space, `mvp` the full transform) in draw order; the id
/// of a triangle is its index in `tris` unless `ids` gives one.
pub fn render(
    mvp: &M4,
    positions: &[V3],
    tris: &[[usize; 3]],
    ids: Option<&[u32]>,
    width: u32,
    height: u32,
    cull: RefCull,
) -> RefRender {
    let n = (width * height) as usize;
    let mut out = RefRender {
        width,
        height,
        id: vec![None; n],
        frags: vec![Vec::new(); n],
        edge_dist: vec![EDGE_SEARCH; n],
        drawn: 0,
        culled: 0,
    };
    let mut best = vec![f64::INFINITY; n];
    for (t, tri) in tris.iter().enumerate() {
        let id = ids.map_or(t as u32, |ids| ids[t]);
        let clip: Vec<V4> = tri
            .iter()
            .map(|&i| apply_point(mvp, positions[i]))
            .collect();
        let poly = clip_polygon(&clip);
        if poly.is_empty() {
            continue;
        }
        let scr: Vec<V3> = poly.iter().map(|p| to_screen(*p, width, height)).collect();
        // Signed doubled area (y down) of the convex polygon.
        let mut area = 0.0;
        for k in 1..scr.len() - 1 {
            let (a, b, c) = (scr[0], scr[k], scr[k + 1]);
            area += (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        }
        let keep = match cull {
            RefCull::None => true,
            RefCull::Clockwise => area < 0.0,
            RefCull::CounterClockwise => area > 0.0,
        };
        if area == 0.0 || !keep {
            out.culled += 1;
            continue;
        }
        out.drawn += 1;
        draw_polygon(&mut out, &mut best, &scr, area, id);
    }
    out
}

/// Rasterizes one convex screen polygon (`area` its signed doubled area) into `out`.
fn draw_polygon(out: &mut RefRender, best: &mut [f64], scr: &[V3], area: f64, id: u32) {
    let (w, h) = (out.width as i64, out.height as i64);
    // Wound so that the inside has all edge functions positive (as `reference_triangle`).
    let v: Vec<V3> = if area > 0.0 {
        scr.to_vec()
    } else {
        scr.iter().rev().copied().collect()
    };
    // Depth as an affine function of the screen position, from the fan triangle of largest area.
    let mut pick = (1, 0.0);
    for k in 1..v.len() - 1 {
        let (a, b, c) = (v[0], v[k], v[k + 1]);
        let ar = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        if ar.abs() > pick.1 {
            pick = (k, ar.abs());
        }
    }
    let (a, b, c) = (v[0], v[pick.0], v[pick.0 + 1]);
    let den = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    let depth_at = |x: f64, y: f64| {
        let l1 = ((x - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (y - a[1])) / den;
        let l2 = ((b[0] - a[0]) * (y - a[1]) - (x - a[0]) * (b[1] - a[1])) / den;
        a[2] + l1 * (b[2] - a[2]) + l2 * (c[2] - a[2])
    };
    let xs = v.iter().map(|p| p[0]);
    let ys = v.iter().map(|p| p[1]);
    let lo_x = xs.clone().fold(f64::INFINITY, f64::min) - EDGE_SEARCH;
    let hi_x = xs.fold(f64::NEG_INFINITY, f64::max) + EDGE_SEARCH;
    let lo_y = ys.clone().fold(f64::INFINITY, f64::min) - EDGE_SEARCH;
    let hi_y = ys.fold(f64::NEG_INFINITY, f64::max) + EDGE_SEARCH;
    let px0 = (lo_x.floor().max(0.0) as i64).min(w);
    let px1 = (hi_x.ceil().max(0.0) as i64).min(w);
    let py0 = (lo_y.floor().max(0.0) as i64).min(h);
    let py1 = (hi_y.ceil().max(0.0) as i64).min(h);
    // Edges of (numerically) zero length carry no direction: drop their repeated vertices.
    let mut v2: Vec<V3> = Vec::with_capacity(v.len());
    for p in &v {
        let dup = |q: &V3| (p[0] - q[0]).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9;
        if !v2.last().is_some_and(dup) {
            v2.push(*p);
        }
    }
    while v2.len() > 1 && {
        let (a, b) = (v2[0], v2[v2.len() - 1]);
        (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9
    } {
        v2.pop();
    }
    let v = v2;
    if v.len() < 3 {
        return;
    }
    let m = v.len();
    for py in py0..py1 {
        for px in px0..px1 {
            let (cx, cy) = (px as f64 + 0.5, py as f64 + 0.5);
            let i = (py * w + px) as usize;
            let mut inside = true;
            let mut near_edge = f64::INFINITY;
            for k in 0..m {
                let (p, q) = (v[k], v[(k + 1) % m]);
                let (ex, ey) = (q[0] - p[0], q[1] - p[1]);
                let e = ex * (cy - p[1]) - ey * (cx - p[0]);
                let ok = if e != 0.0 {
                    e > 0.0
                } else {
                    (ey == 0.0 && ex > 0.0) || ey < 0.0
                };
                inside &= ok;
                near_edge = near_edge.min(seg_dist((cx, cy), (p[0], p[1]), (q[0], q[1])));
            }
            out.edge_dist[i] = out.edge_dist[i].min(near_edge);
            if inside {
                let d = depth_at(cx, cy);
                out.frags[i].push((id, d));
                if d < best[i] {
                    best[i] = d;
                    out.id[i] = Some(id);
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Lighting and the true Gouraud image.

/// The channels of a colour as `f64`.
fn channels(c: Rgb888) -> [f64; 3] {
    [c.r(), c.g(), c.b()].map(f64::from)
}

/// A light of [`lit`]: `(is_point, position or direction, colour)`.
pub type RefLight = (bool, V3, Rgb888);

/// The lit colour per channel, unrounded, clamped to 255: ambient plus, per light facing the
/// surface, diffuse and a Phong or Blinn-Phong highlight, the formula `rasterizer_core::shade`
/// documents. A zero normal gives the ambient term only, as there.
pub fn lit(
    material: &Material,
    ambient: Rgb888,
    model: Specular,
    eye: V3,
    lights: &[RefLight],
    position: V3,
    normal: V3,
) -> [f64; 3] {
    let (ma, md, ms) = (
        channels(material.ambient),
        channels(material.diffuse),
        channels(material.specular),
    );
    let la = channels(ambient);
    let mut out = [0, 1, 2].map(|c| ma[c] * la[c] / 255.0);
    if dot3(normal, normal) == 0.0 {
        return out.map(|x| x.min(255.0));
    }
    let n = unit3(normal);
    let v = unit3(sub3(eye, position));
    for &(point, p, color) in lights {
        let l = if point {
            unit3(sub3(p, position))
        } else {
            unit3(p)
        };
        let nl = dot3(n, l);
        if nl <= 0.0 {
            continue;
        }
        let e = i32::from(material.shininess);
        let spec = match model {
            Specular::None => 0.0,
            Specular::Phong => {
                let r = sub3([2.0 * nl * n[0], 2.0 * nl * n[1], 2.0 * nl * n[2]], l);
                dot3(r, v).max(0.0).powi(e)
            }
            Specular::BlinnPhong => dot3(n, unit3(add3(l, v))).max(0.0).powi(e),
        };
        let lc = channels(color);
        for c in 0..3 {
            out[c] += md[c] * lc[c] / 255.0 * nl + ms[c] * lc[c] / 255.0 * spec;
        }
    }
    out.map(|x| x.min(255.0))
}

/// The perspective-correct barycentric weights, at the pixel centre `(px + 0.5, py + 0.5)` of a
/// `width` x `height` viewport, of the triangle with clip-space corners `clip` (unclipped: the
/// weights of a clipped polygon's pixel are those of its source triangle). `None` when the
/// triangle is seen edge-on.
///
/// The pixel is the ray `(x_ndc, y_ndc, 1)` in the triangle's homogeneous 2D coordinates
/// `(x, y, w)`; solving `sum b_k (x_k, y_k, w_k) = t (x_ndc, y_ndc, 1)` and scaling the `b_k` to sum
/// to one gives the weights with which values vary linearly across the triangle in 3D.
pub fn perspective_weights(
    clip: &[V4; 3],
    px: u32,
    py: u32,
    width: u32,
    height: u32,
) -> Option<V3> {
    let xn = (f64::from(px) + 0.5) / f64::from(width) * 2.0 - 1.0;
    let yn = 1.0 - (f64::from(py) + 0.5) / f64::from(height) * 2.0;
    let col = |k: usize| [clip[k][0], clip[k][1], clip[k][3]];
    let (a, b, c) = (col(0), col(1), col(2));
    let det = dot3(a, cross3(b, c));
    if det.abs() < 1e-300 {
        return None;
    }
    let p = [xn, yn, 1.0];
    // Cramer's rule.
    let w = [
        dot3(p, cross3(b, c)) / det,
        dot3(a, cross3(p, c)) / det,
        dot3(a, cross3(b, p)) / det,
    ];
    let sum = w[0] + w[1] + w[2];
    (sum.abs() > 1e-300).then(|| w.map(|x| x / sum))
}

/// The true image of per-vertex values (e.g. lit colours): each pixel of `render` gets the values
/// of its triangle interpolated perspective-correctly. `values[i]` belongs to position `i`; the
/// triangle ids of `render` must be indices into `tris`.
pub fn shade_image(
    mvp: &M4,
    positions: &[V3],
    tris: &[[usize; 3]],
    values: &[V3],
    render: &RefRender,
) -> Vec<Option<V3>> {
    let (w, h) = (render.width, render.height);
    let mut out = vec![None; render.id.len()];
    for (i, id) in render.id.iter().enumerate() {
        let Some(t) = *id else { continue };
        let tri = tris[t as usize];
        let clip = tri.map(|k| apply_point(mvp, positions[k]));
        let (px, py) = (i as u32 % w, i as u32 / w);
        if let Some(b) = perspective_weights(&clip, px, py, w, h) {
            let v = tri.map(|k| values[k]);
            out[i] = Some([0, 1, 2].map(|c| b[0] * v[0][c] + b[1] * v[1][c] + b[2] * v[2][c]));
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Pipeline-side helpers.

/// A 16.16 value as `f64`, exactly.
pub fn f(v: Fx16) -> f64 {
    f64::from(v.to_bits()) / 65536.0
}

/// The 16.16 value nearest `v`.
pub fn fx(v: f64) -> Fx16 {
    Fx16::from_bits((v * 65536.0).round() as i32)
}

/// A 16.16 point as `f64`, exactly.
pub fn f3(v: Vec3<Fx16>) -> V3 {
    [f(v.x), f(v.y), f(v.z)]
}

/// The colour that stands for triangle `id` (24 bits).
pub fn id_color(id: u32) -> Rgb888 {
    Rgb888::new((id >> 16) as u8, (id >> 8) as u8, id as u8)
}

/// The triangle id a colour stands for.
pub fn color_id(c: Rgb888) -> u32 {
    (u32::from(c.r()) << 16) | (u32::from(c.g()) << 8) | u32::from(c.b())
}

/// Paints every pixel of a face with its id: with [`FaceMesh`] each vertex carries its triangle's
/// id as its colour, handed on as one varying. A varying equal at the three corners is a constant
/// plane, which the rasterizer and the clipper reproduce exactly, so this needs no per-face hook.
#[derive(Debug, Clone, Copy, Default)]
pub struct FaceIds;

impl<S: Scalar> Shading<S> for FaceIds {
    type Color = Rgb888;
    type Varyings = [i32; 1];
    type Stored = [i32; 1];
    const NEEDS_WORLD: bool = false;
    // A 24-bit id has no room for fractional bits; its plane is constant, so it needs none.
    const FUSED_FRAC: u32 = 0;
    fn vertex(&mut self, v: &VertexIn<S>) -> [i32; 1] {
        [color_id(v.color) as i32]
    }
    fn pixel(&self, v: &[i32; 1]) -> Rgb888 {
        id_color(v[0] as u32)
    }
}

/// A mesh with its vertices unshared (three per triangle), coloured with each triangle's id, in a
/// chosen order.
#[derive(Debug, Clone)]
pub struct FaceMesh {
    /// Three positions per triangle.
    pub positions: Vec<Vec3<Fx16>>,
    /// The id colour of each vertex's triangle.
    pub colors: Vec<Rgb888>,
    /// `[3k, 3k + 1, 3k + 2]`.
    pub triangles: Vec<[u32; 3]>,
    /// The id of each triangle, in draw order.
    pub ids: Vec<u32>,
}

impl FaceMesh {
    /// Triangles `order` (indices into `tris`) of a mesh; each keeps its index in `tris` as its id.
    pub fn new(positions: &[Vec3<Fx16>], tris: &[[u32; 3]], order: &[usize]) -> Self {
        let mut m = FaceMesh {
            positions: Vec::new(),
            colors: Vec::new(),
            triangles: Vec::new(),
            ids: Vec::new(),
        };
        for &t in order {
            let base = m.positions.len() as u32;
            for &i in &tris[t] {
                m.positions.push(positions[i as usize]);
                m.colors.push(id_color(t as u32));
            }
            m.triangles.push([base, base + 1, base + 2]);
            m.ids.push(t as u32);
        }
        m
    }

    /// The whole mesh in its own order.
    pub fn all(positions: &[Vec3<Fx16>], tris: &[[u32; 3]]) -> Self {
        let order: Vec<usize> = (0..tris.len()).collect();
        Self::new(positions, tris, &order)
    }

    /// As a pipeline mesh.
    pub fn mesh(&self) -> rasterizer_core::mesh::Mesh<'_, Fx16, u32> {
        rasterizer_core::mesh::Mesh {
            positions: &self.positions,
            normals: None,
            colors: Some(&self.colors),
            triangles: &self.triangles,
        }
    }
}
