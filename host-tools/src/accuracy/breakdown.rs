//! Where each format breaks down: the M1 scene pushed one way at a time (the whole scene scaled by
//! powers of two, the near plane pulled in, the screen enlarged) until a configuration's error
//! passes a stated threshold or it cannot render at all.

use super::config::{Config, Measured};
use super::metrics::Errors;
use super::scene::{Prepared, SceneDef};
use std::collections::HashMap;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// A vertex farther than this from its exact place (pixels) is broken.
pub const MAX_VERTEX_PX: f64 = 1.0;
/// More than this share of covered pixels showing another triangle than the reference is broken
/// (a visibly wrong picture: the default differs on 0.6 % of M1's pixels, all along edges).
pub const MAX_DIFFERING: f64 = 0.10;
/// More than this share of covered pixels showing a farther surface is broken.
pub const MAX_DEPTH_MISTAKES: f64 = 0.01;

/// The steps each sweep tries, in order; a sweep stops at the first broken step.
#[derive(Debug, Clone)]
pub struct Plan {
    /// Powers of two the scene is scaled up by.
    pub scales_up: Vec<i32>,
    /// Powers of two the scene is scaled down by (negative).
    pub scales_down: Vec<i32>,
    /// Near plane distances.
    pub nears: Vec<f64>,
    /// Screen widths (the height is three quarters of it); vertex error only.
    pub widths: Vec<u32>,
}

impl Plan {
    /// The full plan, each sweep starting from the workload scene itself: scales 2^0..2^16 up and
    /// 2^0..2^-16 down, the near plane from 0.1 halved 24 times (down to 6e-9), screens from 320
    /// to the viewport limit of 32,767 pixels.
    pub fn full() -> Self {
        Self {
            scales_up: (0..=16).collect(),
            scales_down: (0..=16).map(|k| -k).collect(),
            nears: (0..=24).map(|k| 0.1 / 2f64.powi(k)).collect(),
            widths: vec![320, 640, 1280, 2560, 5120, 10240, 20480, 32767],
        }
    }
}

/// The last step that worked and the first that did not, with why.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Limit {
    /// The last value that worked.
    pub good: Option<f64>,
    /// The first value that broke, and the reason.
    pub bad: Option<(f64, String)>,
}

/// The limits of one configuration.
#[derive(Debug, Clone)]
pub struct Breakdown {
    /// The configuration's label.
    pub label: &'static str,
    /// Its format.
    pub format: &'static str,
    /// Largest scene scale (a power of two).
    pub scale_up: Limit,
    /// Smallest scene scale.
    pub scale_down: Limit,
    /// Nearest near plane.
    pub near: Limit,
    /// Largest screen width.
    pub screen: Limit,
}

/// Why the errors of a step count as broken, if they do.
pub fn broken(e: &Errors, raster: bool) -> Option<String> {
    if e.vertex_max > MAX_VERTEX_PX {
        return Some(format!("vertex error {:.2} px", e.vertex_max));
    }
    if raster && e.covered == 0 {
        return Some("nothing visible even in f64 (w below 2^-8 is clipped)".into());
    }
    if raster && e.differing_share() > MAX_DIFFERING {
        return Some(format!(
            "{:.1} % of pixels differ",
            100.0 * e.differing_share()
        ));
    }
    if raster && e.depth_share() > MAX_DEPTH_MISTAKES {
        return Some(format!(
            "{:.1} % depth-order mistakes",
            100.0 * e.depth_share()
        ));
    }
    None
}

/// Runs a measurement, turning a panic into an error (nothing should panic; if it does, that is
/// the step where the format broke).
fn guarded(config: &Config, scene: &Prepared) -> Measured {
    catch_unwind(AssertUnwindSafe(|| (config.measure)(scene)))
        .unwrap_or_else(|_| Err("panicked".into()))
}

/// Tries `steps` in order until one breaks.
fn sweep<T: Copy + Into<f64>>(
    steps: &[T],
    raster: bool,
    config: &Config,
    scene_at: &mut impl FnMut(T) -> std::rc::Rc<Prepared>,
) -> Limit {
    let mut limit = Limit::default();
    for &s in steps {
        let scene = scene_at(s);
        let why = match guarded(config, &scene) {
            Ok(e) => broken(&e, raster),
            Err(e) => Some(e),
        };
        match why {
            None => limit.good = Some(s.into()),
            Some(why) => {
                limit.bad = Some((s.into(), why));
                break;
            }
        }
    }
    limit
}

/// The limits of every configuration on `base` (M1), the reference renders shared between them.
pub fn run(
    base: &SceneDef,
    configs: &[Config],
    plan: &Plan,
    progress: impl Fn(&str),
) -> Vec<Breakdown> {
    use std::rc::Rc;
    let mut scaled: HashMap<i32, Rc<Prepared>> = HashMap::new();
    let mut near: HashMap<u64, Rc<Prepared>> = HashMap::new();
    let mut wide: HashMap<u32, Rc<Prepared>> = HashMap::new();
    let mut out = Vec::new();
    for c in configs {
        progress(c.label);
        let mut at_scale = |k: i32| {
            scaled
                .entry(k)
                .or_insert_with(|| {
                    let mut d = base.clone();
                    d.camera = d.camera.scaled(2f64.powi(k));
                    Rc::new(Prepared::new(d, true))
                })
                .clone()
        };
        let scale_up = sweep(&plan.scales_up, true, c, &mut at_scale);
        let scale_down = sweep(&plan.scales_down, true, c, &mut at_scale);
        let pow2 = |l: Limit| Limit {
            good: l.good.map(|k| 2f64.powf(k)),
            bad: l.bad.map(|(k, why)| (2f64.powf(k), why)),
        };
        let mut at_near = |n: f64| {
            near.entry(n.to_bits())
                .or_insert_with(|| {
                    let mut d = base.clone();
                    d.camera.near = n;
                    Rc::new(Prepared::new(d, true))
                })
                .clone()
        };
        let near_limit = sweep(&plan.nears, true, c, &mut at_near);
        let mut at_width = |w: u32| {
            wide.entry(w)
                .or_insert_with(|| {
                    let mut d = base.clone();
                    d.width = w;
                    d.height = w * 3 / 4;
                    Rc::new(Prepared::new(d, false))
                })
                .clone()
        };
        let screen = sweep(&plan.widths, false, c, &mut at_width);
        out.push(Breakdown {
            label: c.label,
            format: c.knobs.format,
            scale_up: pow2(scale_up),
            scale_down: pow2(scale_down),
            near: near_limit,
            screen,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thresholds() {
        let ok = Errors {
            vertices: 1,
            vertex_max: 0.9,
            covered: 1000,
            differing: 100,
            depth_mistakes: 10,
            ..Errors::default()
        };
        assert_eq!(broken(&ok, true), None);
        let far = Errors {
            vertex_max: 1.5,
            ..ok
        };
        assert!(broken(&far, false).unwrap().contains("vertex"));
        let differ = Errors {
            differing: 101,
            ..ok
        };
        assert!(broken(&differ, true).unwrap().contains("differ"));
        assert_eq!(broken(&differ, false), None);
        let depth = Errors {
            depth_mistakes: 11,
            ..ok
        };
        assert!(broken(&depth, true).unwrap().contains("depth"));
    }
}
