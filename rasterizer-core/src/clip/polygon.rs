//! Sutherland-Hodgman clipping of triangles in homogeneous clip space.
//!
//! A triangle is clipped against `w >= W_MIN` and the near plane always (so nothing with `w <= 0`
//! reaches the perspective divide), and against the far plane and the guard-band planes
//! `|x|, |y| <= GUARD w` only when a vertex lies outside them; everything else is left to the
//! rasterizer's exact 2D clipping. Each crossing point is computed from the inside vertex towards the
//! outside one, so two triangles sharing an edge get bit-identical new vertices and stay watertight.

use crate::geom::Varyings;
use crate::math::{Scalar, Vec4};
use heapless::Vec;

/// The most vertices a clipped triangle can have: three plus one per plane.
pub const MAX_CLIPPED: usize = 3 + PLANES;

const PLANES: usize = 7;

/// Half-width of the guard band in clip space, in units of `w`: vertices with `|x| <= GUARD w` and
/// `|y| <= GUARD w` are not clipped in x and y. Four keeps projected coordinates within a few screen
/// widths, far inside the rasterizer's own guard band and the 16.16 range.
pub const GUARD: i32 = 4;

/// The smallest `w` a vertex may keep, as a fraction of one: `2^-8`. Clipping against it before the
/// near plane keeps the divide bounded for any matrix, also for projections without a near plane.
pub const W_MIN_SHIFT: u32 = 8;

/// A vertex in clip space with the values a shader interpolates (colours, normals, ...), carried
/// through clipping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipVertex<S, V> {
    /// Clip-space position.
    pub pos: Vec4<S>,
    /// Values interpolated linearly in clip space when an edge is cut.
    pub var: V,
}

/// Which planes a triangle was outside of, as returned by [`outcode`].
pub type Outcode = u8;

const W_MIN: u8 = 1;
const NEAR: u8 = 2;
const FAR: u8 = 4;
const LEFT: u8 = 8;
const RIGHT: u8 = 16;
const BOTTOM: u8 = 32;
const TOP: u8 = 64;
/// Outside the visible frustum in x or y (not a clipping plane: used for trivial rejection only).
const VIEW_X_NEG: u8 = 128;

/// Signed distance of `p` to plane `bit`: inside when `>= 0`.
#[inline]
fn distance<S: Scalar>(p: &Vec4<S>, bit: u8) -> S {
    let g = S::from_int(GUARD);
    match bit {
        // 2^-8 as 16.16 bits: exact in every fixed-point format and in f32, and no division.
        W_MIN => p.w - S::from_fx16_bits(1 << (16 - W_MIN_SHIFT)),
        NEAR => p.z + p.w,
        FAR => p.w - p.z,
        LEFT => p.x + g * p.w,
        RIGHT => g * p.w - p.x,
        BOTTOM => p.y + g * p.w,
        _ => g * p.w - p.y,
    }
}

/// [`distance`] out of line for the clipper, which tests one plane at a time: one copy instead
/// of the seven arms inlined at each of its calls.
#[inline(never)]
fn distance_to<S: Scalar>(p: &Vec4<S>, bit: u8) -> S {
    distance(p, bit)
}

/// The planes a point lies outside of.
#[inline]
pub fn outcode<S: Scalar>(p: &Vec4<S>) -> Outcode {
    let mut code = 0;
    for bit in [W_MIN, NEAR, FAR, LEFT, RIGHT, BOTTOM, TOP] {
        if distance(p, bit) < S::ZERO {
            code |= bit;
        }
    }
    code
}

/// True when the three points lie outside one of the visible frustum's planes together, so the
/// triangle cannot show (the screen planes `|x|, |y| <= w` are stricter than the guard band).
/// `codes` are the points' [`outcode`]s.
#[inline]
pub fn trivially_outside<S: Scalar>(p: &[Vec4<S>; 3], codes: [Outcode; 3]) -> bool {
    let view = |v: &Vec4<S>, code: Outcode| -> u8 {
        let mut c = 0;
        if v.x < -v.w {
            c |= VIEW_X_NEG;
        }
        if v.x > v.w {
            c |= RIGHT;
        }
        if v.y < -v.w {
            c |= BOTTOM;
        }
        if v.y > v.w {
            c |= TOP;
        }
        c | code & (W_MIN | NEAR | FAR)
    };
    view(&p[0], codes[0]) & view(&p[1], codes[1]) & view(&p[2], codes[2]) != 0
}

/// `a + (b - a) t` for a varying, `t` in 2.30.
#[inline]
fn lerp_i32(a: i32, b: i32, t30: i64) -> i32 {
    let d = i64::from(b) - i64::from(a);
    (i64::from(a) + ((d * t30 + (1 << 29)) >> 30)) as i32
}

/// The point where the edge from `inside` to `outside` crosses plane `bit`.
fn crossing<S: Scalar, V: Varyings>(
    inside: &ClipVertex<S, V>,
    outside: &ClipVertex<S, V>,
    bit: u8,
) -> ClipVertex<S, V> {
    let (di, do_) = (
        distance_to(&inside.pos, bit),
        distance_to(&outside.pos, bit),
    );
    // di >= 0 > do_, so the denominator is positive and t = di / (di - do_) lies in [0, 1]; each
    // coordinate is interpolated with the exact ratio, rounded once.
    let den = di - do_;
    let (a, b) = (&inside.pos, &outside.pos);
    let pos = Vec4::new(
        S::lerp_ratio(a.x, b.x, di, den),
        S::lerp_ratio(a.y, b.y, di, den),
        S::lerp_ratio(a.z, b.z, di, den),
        S::lerp_ratio(a.w, b.w, di, den),
    );
    let t30 = S::scaled_ratio(di, den, 1 << 30, 1).clamp(0, 1 << 30);
    let mut var = inside.var;
    for (v, o) in var.as_mut_slice().iter_mut().zip(outside.var.as_slice()) {
        *v = lerp_i32(*v, *o, t30);
    }
    ClipVertex { pos, var }
}

/// Clips a triangle; the result is a convex polygon of 0 or 3 to [`MAX_CLIPPED`] vertices in the
/// same winding. `codes` are the three vertices' [`outcode`]s; only planes some vertex is outside of
/// are clipped against.
// Out of line: the rare path of every draw call, one copy each.
#[inline(never)]
pub fn clip_triangle<S: Scalar, V: Varyings>(
    tri: &[ClipVertex<S, V>; 3],
    codes: [Outcode; 3],
) -> Vec<ClipVertex<S, V>, MAX_CLIPPED> {
    let mut poly: Vec<ClipVertex<S, V>, MAX_CLIPPED> = Vec::new();
    for v in tri {
        let _ = poly.push(*v);
    }
    let any = codes[0] | codes[1] | codes[2];
    for bit in [W_MIN, NEAR, FAR, LEFT, RIGHT, BOTTOM, TOP] {
        if any & bit == 0 {
            continue;
        }
        let mut out: Vec<ClipVertex<S, V>, MAX_CLIPPED> = Vec::new();
        let n = poly.len();
        for i in 0..n {
            let (a, b) = (&poly[i], &poly[(i + 1) % n]);
            let a_in = distance_to(&a.pos, bit) >= S::ZERO;
            let b_in = distance_to(&b.pos, bit) >= S::ZERO;
            // Each plane adds at most one vertex to a convex polygon, so MAX_CLIPPED is never
            // exceeded; a failed push would only drop a vertex, never write out of bounds.
            if a_in {
                let _ = out.push(*a);
                if !b_in {
                    let _ = out.push(crossing(a, b, bit));
                }
            } else if b_in {
                let _ = out.push(crossing(b, a, bit));
            }
        }
        poly = out;
        if poly.len() < 3 {
            poly.clear();
            break;
        }
    }
    poly
}

/// Clips the segment `a`-`b` against the same planes as [`clip_triangle`] (only those an end lies
/// outside of), returning the visible part with the ends in the order given, or `None`. The
/// crossing points are computed from a canonical order of the ends, so a mesh edge shared by two
/// triangles clips to the same points either way round.
pub fn clip_segment<S: Scalar>(a: Vec4<S>, b: Vec4<S>) -> Option<(Vec4<S>, Vec4<S>)> {
    let (ca, cb) = (outcode(&a), outcode(&b));
    if ca & cb != 0 {
        return None;
    }
    if ca | cb == 0 {
        return Some((a, b));
    }
    let key = |p: &Vec4<S>| [p.x, p.y, p.z, p.w];
    let swap = key(&b).partial_cmp(&key(&a)) == Some(core::cmp::Ordering::Less);
    let (p, q) = if swap { (b, a) } else { (a, b) };
    let (mut t0, mut t1) = (S::ZERO, S::ONE);
    for bit in [W_MIN, NEAR, FAR, LEFT, RIGHT, BOTTOM, TOP] {
        if (ca | cb) & bit == 0 {
            continue;
        }
        let (dp, dq) = (distance_to(&p, bit), distance_to(&q, bit));
        if dp < S::ZERO && dq < S::ZERO {
            return None;
        }
        if dp < S::ZERO {
            t0 = max(t0, dp / (dp - dq));
        } else if dq < S::ZERO {
            t1 = min(t1, dp / (dp - dq));
        }
    }
    if t0 > t1 {
        return None;
    }
    let (p0, p1) = (p.lerp(q, t0), p.lerp(q, t1));
    Some(if swap { (p1, p0) } else { (p0, p1) })
}

fn max<S: Scalar>(a: S, b: S) -> S {
    if a > b {
        a
    } else {
        b
    }
}

fn min<S: Scalar>(a: S, b: S) -> S {
    if a < b {
        a
    } else {
        b
    }
}
