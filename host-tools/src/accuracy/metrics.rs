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
    /// The same pixels drawn into Rgb565 (where dithering acts): each one's error against the
    /// true colour in steps of the channel (5 or 6 bits), the mean of its three channels' absolute
    /// errors, summed.
    pub rgb565_sum: f64,
    /// Their signed errors summed (the mean is the bias of the rounding).
    pub rgb565_signed: f64,
    /// 4 x 4 tiles (aligned to the screen) whose 16 pixels are all compared.
    pub tiles: u64,
    /// Each such tile's error of the mean colour (mean of the three channels' absolute errors of
    /// the tile's mean), in steps, summed: what the eye sees from a distance.
    pub tile_sum: f64,
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

    /// Mean error of an Rgb565 pixel, in steps of its channels.
    pub fn rgb565_mean(&self) -> f64 {
        ratio(self.rgb565_sum, self.same as f64)
    }
    /// Mean signed error of an Rgb565 pixel (the bias), in steps.
    pub fn rgb565_bias(&self) -> f64 {
        ratio(self.rgb565_signed, 3.0 * self.same as f64)
    }
    /// Mean error of a 4 x 4 tile's mean Rgb565 colour, in steps.
    pub fn tile_mean(&self) -> f64 {
        ratio(self.tile_sum, self.tiles as f64)
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
            rgb565_sum: self.rgb565_sum + o.rgb565_sum,
            rgb565_signed: self.rgb565_signed + o.rgb565_signed,
            tiles: self.tiles + o.tiles,
            tile_sum: self.tile_sum + o.tile_sum,
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

/// The largest value of each Rgb565 channel.
const RGB565_MAX: [f64; 3] = [31.0, 63.0, 31.0];

/// Adds the Rgb565 measures to `e` (whose `same` counts the compared pixels): `ours` our Rgb565
/// channels per pixel, compared where `ids` matches the reference's triangle, against the true
/// colour scaled to each channel's steps; `width` the screen's.
pub fn rgb565_errors(
    e: &mut Errors,
    reference: &RefRender,
    truth: &[Option<[f64; 3]>],
    ids: &[Option<u32>],
    ours: &[[u8; 3]],
    width: usize,
) {
    // The signed error per channel of each compared pixel.
    let err: Vec<Option<[f64; 3]>> = (0..ids.len())
        .map(|i| {
            let c = truth.get(i).copied().flatten()?;
            (reference.id[i].is_some() && reference.id[i] == ids[i])
                .then(|| [0, 1, 2].map(|k| f64::from(ours[i][k]) - c[k] * RGB565_MAX[k] / 255.0))
        })
        .collect();
    for d in err.iter().flatten() {
        e.rgb565_sum += d.iter().map(|v| v.abs()).sum::<f64>() / 3.0;
        e.rgb565_signed += d.iter().sum::<f64>();
    }
    let height = ids.len() / width.max(1);
    for ty in (0..height.saturating_sub(3)).step_by(4) {
        for tx in (0..width.saturating_sub(3)).step_by(4) {
            let tile: Option<Vec<[f64; 3]>> = (0..16)
                .map(|j| err[(ty + j / 4) * width + tx + j % 4])
                .collect();
            if let Some(tile) = tile {
                let mean = [0, 1, 2].map(|k| tile.iter().map(|d| d[k]).sum::<f64>() / 16.0);
                e.tiles += 1;
                e.tile_sum += mean.iter().map(|v| v.abs()).sum::<f64>() / 3.0;
            }
        }
    }
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

    /// A flat grey a quarter of the way between two red steps: rounding is off by a quarter
    /// everywhere, a dithered tile (four of sixteen pixels a step up) not at all on average.
    #[test]
    fn rgb565_tiles_average_dithered_pixels() {
        let truth = vec![Some([9.25 * 255.0 / 31.0, 0.0, 0.0]); 16];
        let ids = vec![Some(0); 16];
        let r = reference(ids.clone(), vec![vec![(0, 1.0)]; 16]);
        let rounded = [[9u8, 0, 0]; 16];
        let mut e = Errors {
            same: 16,
            ..Errors::default()
        };
        rgb565_errors(&mut e, &r, &truth, &ids, &rounded, 4);
        assert!((e.rgb565_mean() - 0.25 / 3.0).abs() < 1e-9);
        assert!((e.tile_mean() - 0.25 / 3.0).abs() < 1e-9);
        let mut dithered = rounded;
        for i in [4, 6, 12, 14] {
            dithered[i][0] = 10;
        }
        let mut e = Errors {
            same: 16,
            ..Errors::default()
        };
        rgb565_errors(&mut e, &r, &truth, &ids, &dithered, 4);
        assert_eq!(e.tiles, 1);
        assert!(e.tile_mean() < 1e-9);
        assert!(e.rgb565_bias().abs() < 1e-9);
        assert!(e.rgb565_mean() > 0.25 / 3.0);
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
