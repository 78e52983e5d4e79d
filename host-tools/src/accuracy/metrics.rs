//! The error measures: a render of ours (triangle ids, 8-bit colours, projected vertices) against
//! the `f64` reference, and the Pareto front of cost against error.
//!
//! Everything here is a plain function of images and numbers, so it is tested on hand-made
//! inputs.

use fixtures::reference3d::RefRender;

/// Depths within this many of the depth buffer's 65,535 steps are a tie, not a depth-order
/// mistake: the buffer stores whole steps, so no format can order surfaces closer than one step.
pub const DEPTH_TIE: f64 = 1.0;

/// The errors of one render (or, merged, of several).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Errors {
    /// Visible vertices compared.
    pub vertices: u64,
    /// Largest vertex position error in pixels.
    pub vertex_max: f64,
    /// Sum of vertex position errors in pixels (for the mean).
    pub vertex_sum: f64,
    /// Pixels the reference covers.
    pub covered: u64,
    /// Pixels whose triangle differs from the reference's (covered by another one, or covered by
    /// one side only).
    pub differing: u64,
    /// Pixels both cover with the same triangle, where colours are compared.
    pub same: u64,
    /// Largest colour error there, in 8-bit steps (worst channel, against the reference rounded
    /// to 8 bits).
    pub color_max: u32,
    /// Sum of those errors (for the mean).
    pub color_sum: u64,
    /// Pixels where our triangle is farther than the nearest surface by more than [`DEPTH_TIE`].
    pub depth_mistakes: u64,
    /// Pixels that are wrong in the picture: a differing triangle, or a colour more than one step
    /// off.
    pub wrong: u64,
    /// Pixels of the screen.
    pub pixels: u64,
}

impl Errors {
    /// Mean vertex error in pixels.
    pub fn vertex_mean(&self) -> f64 {
        ratio(self.vertex_sum, self.vertices as f64)
    }
    /// Share of covered pixels whose triangle differs.
    pub fn differing_share(&self) -> f64 {
        ratio(self.differing as f64, self.covered as f64)
    }
    /// Mean colour error in 8-bit steps.
    pub fn color_mean(&self) -> f64 {
        ratio(self.color_sum as f64, self.same as f64)
    }
    /// Share of covered pixels that are wrong in the picture.
    pub fn wrong_share(&self) -> f64 {
        ratio(self.wrong as f64, self.covered as f64)
    }
    /// Share of covered pixels with a depth-order mistake.
    pub fn depth_share(&self) -> f64 {
        ratio(self.depth_mistakes as f64, self.covered as f64)
    }

    /// The errors of two renders together.
    pub fn merge(&self, o: &Errors) -> Errors {
        Errors {
            vertices: self.vertices + o.vertices,
            vertex_max: self.vertex_max.max(o.vertex_max),
            vertex_sum: self.vertex_sum + o.vertex_sum,
            covered: self.covered + o.covered,
            differing: self.differing + o.differing,
            same: self.same + o.same,
            color_max: self.color_max.max(o.color_max),
            color_sum: self.color_sum + o.color_sum,
            depth_mistakes: self.depth_mistakes + o.depth_mistakes,
            wrong: self.wrong + o.wrong,
            pixels: self.pixels + o.pixels,
        }
    }
}

fn ratio(a: f64, b: f64) -> f64 {
    if b > 0.0 {
        a / b
    } else {
        0.0
    }
}

/// Vertex position errors: `ours[i]` against `exact[i]` (both in pixels) where the reference sees
/// the vertex (`exact[i]` is `Some`). Returns `(count, max, sum)`.
pub fn vertex_errors(exact: &[Option<[f64; 2]>], ours: &[[f64; 2]]) -> (u64, f64, f64) {
    let (mut n, mut max, mut sum) = (0, 0.0f64, 0.0);
    for (e, o) in exact.iter().zip(ours) {
        if let Some(e) = e {
            let d = (e[0] - o[0]).hypot(e[1] - o[1]);
            n += 1;
            max = max.max(d);
            sum += d;
        }
    }
    (n, max, sum)
}

/// Compares our render with the reference, pixel by pixel: `ids` our triangle per pixel,
/// `colors` our colour per pixel; `truth` the reference's true colour per pixel.
pub fn image_errors(
    reference: &RefRender,
    truth: &[Option<[f64; 3]>],
    ids: &[Option<u32>],
    colors: &[[u8; 3]],
) -> Errors {
    let mut e = Errors {
        pixels: ids.len() as u64,
        ..Errors::default()
    };
    for (i, (&want, &got)) in reference.id.iter().zip(ids).enumerate() {
        if want.is_some() {
            e.covered += 1;
        }
        if want != got {
            e.differing += 1;
            e.wrong += 1;
            // A depth-order mistake: we show a triangle that does cover this pixel in the
            // reference, but lies behind the nearest surface there.
            if let (Some(t), Some(near)) = (got, reference.nearest_depth(i)) {
                if reference
                    .depth_of(i, t)
                    .is_some_and(|d| d - near > DEPTH_TIE)
                {
                    e.depth_mistakes += 1;
                }
            }
            continue;
        }
        let (Some(_), Some(c)) = (want, truth.get(i).copied().flatten()) else {
            continue;
        };
        let err = (0..3)
            .map(|k| (i32::from(colors[i][k]) - c[k].round() as i32).unsigned_abs())
            .max()
            .unwrap_or(0);
        e.same += 1;
        e.color_max = e.color_max.max(err);
        e.color_sum += u64::from(err);
        if err > 1 {
            e.wrong += 1;
        }
    }
    e
}

/// The indices of the points on the Pareto front of `(cost, error)` (lower is better in both),
/// ordered by cost: those no other point matches or beats in both with a strict gain in one.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut front: Vec<usize> = (0..points.len())
        .filter(|&i| {
            let (c, e) = points[i];
            !points
                .iter()
                .enumerate()
                .any(|(j, &(cj, ej))| j != i && cj <= c && ej <= e && (cj < c || ej < e))
        })
        .collect();
    front.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reference(ids: Vec<Option<u32>>, frags: Vec<Vec<(u32, f64)>>) -> RefRender {
        let n = ids.len();
        RefRender {
            width: n as u32,
            height: 1,
            id: ids,
            frags,
            edge_dist: vec![0.0; n],
            drawn: 0,
            culled: 0,
        }
    }

    #[test]
    fn identical_renders_have_no_error() {
        let r = reference(
            vec![Some(0), None, Some(1)],
            vec![vec![(0, 10.0)], vec![], vec![(1, 5.0)]],
        );
        let truth = vec![Some([10.4, 20.0, 30.6]), None, Some([0.0, 255.0, 1.2])];
        let colors = [[10, 20, 31], [0, 0, 0], [0, 255, 1]];
        let e = image_errors(&r, &truth, &r.id.clone(), &colors);
        assert_eq!(e.differing, 0);
        assert_eq!(e.color_max, 0);
        assert_eq!(e.depth_mistakes, 0);
        assert_eq!(e.wrong, 0);
        assert_eq!((e.covered, e.same, e.pixels), (2, 2, 3));
        let (n, max, sum) = vertex_errors(&[Some([1.0, 2.0]), None], &[[1.0, 2.0], [9.0, 9.0]]);
        assert_eq!((n, max, sum), (1, 0.0, 0.0));
    }

    #[test]
    fn shifted_vertex_gives_its_distance() {
        let exact = [Some([10.0, 10.0]), Some([20.0, 5.0]), None];
        let ours = [[10.0, 10.0], [23.0, 9.0], [0.0, 0.0]];
        let (n, max, sum) = vertex_errors(&exact, &ours);
        assert_eq!(n, 2);
        assert_eq!(max, 5.0);
        assert_eq!(sum, 5.0);
    }

    #[test]
    fn swapped_depth_order_is_a_mistake_and_a_tie_is_not() {
        // Pixel 0: triangle 0 is nearer by 100 steps but we show 1. Pixel 1: the two are within
        // the tie tolerance. Pixel 2: we show a triangle that does not cover the pixel at all.
        let r = reference(
            vec![Some(0), Some(0), Some(0)],
            vec![
                vec![(0, 100.0), (1, 200.0)],
                vec![(0, 100.0), (1, 100.5)],
                vec![(0, 100.0)],
            ],
        );
        let truth = vec![Some([0.0; 3]); 3];
        let e = image_errors(&r, &truth, &[Some(1), Some(1), Some(7)], &[[0; 3]; 3]);
        assert_eq!(e.differing, 3);
        assert_eq!(e.depth_mistakes, 1);
    }

    #[test]
    fn colour_error_in_steps_and_wrong_pixels() {
        let r = reference(vec![Some(0), Some(0)], vec![vec![(0, 1.0)], vec![(0, 1.0)]]);
        let truth = vec![Some([100.0, 100.0, 100.0]), Some([50.2, 60.0, 70.0])];
        let e = image_errors(&r, &truth, &r.id.clone(), &[[101, 100, 100], [50, 63, 70]]);
        assert_eq!(e.color_max, 3);
        assert_eq!(e.color_sum, 4);
        assert_eq!(e.wrong, 1);
        assert_eq!(e.color_mean(), 2.0);
    }

    #[test]
    fn pareto_front_of_a_hand_made_set() {
        // 0 and 3 are dominated (by 1 and by 2); 4 ties 1 exactly, so neither beats the other.
        let pts = [
            (10.0, 5.0),
            (5.0, 5.0),
            (20.0, 1.0),
            (30.0, 1.0),
            (5.0, 5.0),
            (1.0, 9.0),
        ];
        assert_eq!(pareto_front(&pts), vec![5, 1, 4, 2]);
    }
}
