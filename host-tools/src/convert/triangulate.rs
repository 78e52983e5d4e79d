//! Polygon triangulation by ear clipping in the polygon's best-fit plane.
//!
//! tobj's own triangulation is a fan from the first vertex, which is wrong for concave polygons
//! (it makes back-facing triangles and covers the notches). Ear clipping handles any simple
//! polygon. The plane is the one of the Newell normal, which is robust to slightly non-planar
//! faces; the polygon is projected onto it so that its winding is counter-clockwise in 2D. Input
//! that is not a simple polygon (self-intersecting, collinear, repeated points) still gets `n - 2`
//! triangles without a panic: when no ear is found the most convex corner is clipped anyway, and a
//! polygon with no area at all is fanned; triangles of no area are dropped later.

use fixtures::vec64::{cross, dot, sub, V3 as P3};

/// `v` scaled to unit length, or `None` for a zero or non-finite vector.
pub(super) fn normalize(v: P3) -> Option<P3> {
    let len = dot(v, v).sqrt();
    (len > 0.0 && len.is_finite()).then(|| [v[0] / len, v[1] / len, v[2] / len])
}

/// The Newell normal of a polygon: twice its vector area, pointing the way its winding turns.
pub fn newell_normal(points: &[P3]) -> P3 {
    let mut n = [0.0; 3];
    for (i, &a) in points.iter().enumerate() {
        let b = points[(i + 1) % points.len()];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

/// Twice the signed area of 2D triangle `a b c` (positive when counter-clockwise).
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Triangulates the polygon `points` (in order; either winding), returning `points.len() - 2`
/// triangles as indices into `points`, each wound like the polygon. Fewer than three points give
/// no triangles.
pub fn triangulate_polygon(points: &[P3]) -> Vec<[usize; 3]> {
    let n = points.len();
    if n < 3 {
        return Vec::new();
    }
    if n == 3 {
        return vec![[0, 1, 2]];
    }
    let fan = || (1..n - 1).map(|i| [0, i, i + 1]).collect();
    let Some(normal) = normalize(newell_normal(points)) else {
        return fan();
    };
    // An orthonormal basis (u, v) of the plane with u x v = normal, so a polygon wound
    // counter-clockwise about the normal is counter-clockwise in (u, v).
    let axis = {
        let a = normal.map(f64::abs);
        let k = if a[0] <= a[1] && a[0] <= a[2] {
            0
        } else if a[1] <= a[2] {
            1
        } else {
            2
        };
        let mut e = [0.0; 3];
        e[k] = 1.0;
        e
    };
    let Some(u) = normalize(cross(normal, axis)) else {
        return fan();
    };
    let v = cross(normal, u);
    let origin = points[0];
    let flat: Vec<[f64; 2]> = points
        .iter()
        .map(|&p| {
            let d = sub(p, origin);
            [dot(d, u), dot(d, v)]
        })
        .collect();
    if flat.iter().flatten().any(|c| !c.is_finite()) {
        return fan();
    }
    // Tolerance for "strictly convex" and "inside": relative to the polygon's size, so noise
    // from the projection of a nearly planar polygon does not make sliver ears.
    let size = flat
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, c| m.max(c.abs()));
    let eps = size * size * 1e-12;

    let mut ring: Vec<usize> = (0..n).collect();
    let mut out = Vec::with_capacity(n - 2);
    let mut start = 0;
    while ring.len() > 3 {
        let m = ring.len();
        let corner = |i: usize| (ring[(i + m - 1) % m], ring[i], ring[(i + 1) % m]);
        let is_ear = |i: usize| {
            let (a, b, c) = corner(i);
            let (pa, pb, pc) = (flat[a], flat[b], flat[c]);
            if orient(pa, pb, pc) <= eps {
                return false;
            }
            ring.iter().all(|&j| {
                if j == a || j == b || j == c {
                    return true;
                }
                let p = flat[j];
                // Points at an ear corner's position (touching polygons, repeated points) do not
                // block it.
                if p == pa || p == pb || p == pc {
                    return true;
                }
                !(orient(pa, pb, p) >= -eps
                    && orient(pb, pc, p) >= -eps
                    && orient(pc, pa, p) >= -eps)
            })
        };
        let ear = (0..m).map(|s| (start + s) % m).find(|&i| is_ear(i));
        let i = ear.unwrap_or_else(|| {
            // Not a simple polygon: clip the most convex corner.
            (0..m)
                .max_by(|&x, &y| {
                    let o = |i: usize| {
                        let (a, b, c) = corner(i);
                        orient(flat[a], flat[b], flat[c])
                    };
                    o(x).total_cmp(&o(y))
                })
                .unwrap_or(0)
        });
        let (a, b, c) = corner(i);
        out.push([a, b, c]);
        ring.remove(i);
        start = if i == 0 { 0 } else { i - 1 };
    }
    out.push([ring[0], ring[1], ring[2]]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area2d(points: &[[f64; 3]], t: [usize; 3]) -> f64 {
        let [a, b, c] = t.map(|i| [points[i][0], points[i][1]]);
        orient(a, b, c) / 2.0
    }

    fn check_ccw(points: &[[f64; 3]], area: f64) {
        let tris = triangulate_polygon(points);
        assert_eq!(tris.len(), points.len() - 2);
        let mut total = 0.0;
        for &t in &tris {
            let a = area2d(points, t);
            assert!(a > 0.0, "triangle {t:?} is not counter-clockwise: {a}");
            total += a;
        }
        assert!(
            (total - area).abs() < 1e-12,
            "area {total}, expected {area}"
        );
    }

    #[test]
    fn concave_l_shape() {
        let l = [
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, 0.0],
        ];
        check_ccw(&l, 3.0);
    }

    #[test]
    fn concave_dart_uses_the_inner_diagonal() {
        let d = [
            [0.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.7, 1.0, 0.0],
        ];
        check_ccw(&d, 1.3);
        for t in triangulate_polygon(&d) {
            assert!(
                t.contains(&1) && t.contains(&3),
                "{t:?} does not use the 2-4 diagonal"
            );
        }
    }

    #[test]
    fn clockwise_and_tilted_polygons_keep_their_winding() {
        // The L shape wound clockwise, then rotated out of the z = 0 plane.
        let mut l = [
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, 0.0],
        ];
        l.reverse();
        let tilted: Vec<P3> = l.iter().map(|p| [p[0], p[1] * 0.6, p[1] * 0.8]).collect();
        let want = normalize(newell_normal(&tilted)).unwrap();
        let tris = triangulate_polygon(&tilted);
        let mut total = 0.0;
        for t in tris {
            let [a, b, c] = t.map(|i| tilted[i]);
            let n = cross(sub(b, a), sub(c, a));
            assert!(dot(n, want) > 0.0, "{t:?} flips the winding");
            total += dot(n, n).sqrt() / 2.0;
        }
        assert!((total - 3.0).abs() < 1e-9);
    }

    #[test]
    fn bad_polygons_do_not_panic() {
        let bowtie = [
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        assert_eq!(triangulate_polygon(&bowtie).len(), 2);
        let line = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
        ];
        assert_eq!(triangulate_polygon(&line).len(), 2);
        let same = [[1.0; 3]; 5];
        assert_eq!(triangulate_polygon(&same).len(), 3);
        let nan = [
            [f64::NAN; 3],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        assert_eq!(triangulate_polygon(&nan).len(), 2);
        let repeated = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let tris = triangulate_polygon(&repeated);
        let total: f64 = tris.iter().map(|&t| area2d(&repeated, t)).sum();
        assert!((total - 1.0).abs() < 1e-12);
    }
}
