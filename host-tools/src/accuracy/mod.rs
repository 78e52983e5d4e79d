//! The `accuracy` command: sweeps the accuracy knobs of the 3D pipeline (geometry format,
//! sub-pixel bits, trigonometry table, perspective-correct interpolation), measures each
//! configuration against the `f64` reference on the workload scenes M1-M3 and on random scenes,
//! counts its instructions per M1 frame with callgrind, finds where each format breaks down, and
//! writes `docs/ACCURACY.md` and `docs/images/accuracy.svg`.
//!
//! Files: [`config`] (the registry of pipeline types), [`blending`] (blending and
//! anti-aliased lines), [`scene`] (the scenes on both sides),
//! [`metrics`] (the error measures and the Pareto front), [`count`] (callgrind), [`breakdown`]
//! (the limit sweeps), [`lighting`] (the shaders' directional-light plan), [`matcap`] (the
//! MatCap lookup), [`silhouette`] (anti-aliased silhouettes' coverage), [`sprite`] (the sprites'
//! texel mapping), [`plot`] and
//! [`report`] (the output).

pub mod blending;
pub mod breakdown;
pub mod config;
pub mod count;
pub mod fog;
pub mod lighting;
pub mod matcap;
pub mod metrics;
pub mod plot;
pub mod report;
pub mod scene;
pub mod silhouette;
pub mod sprite;
pub mod texture;

use crate::progress::Progress;
use config::{Config, Measured};
use count::Count;
use scene::{Prepared, SceneDef};
use std::path::PathBuf;
use std::time::Instant;

/// Options of the `accuracy` command.
#[derive(Debug, Clone, clap::Args)]
pub struct AccuracyArgs {
    /// Directory the report goes to: `DIR/ACCURACY.md` and `DIR/images/accuracy.svg`.
    #[arg(long, value_name = "DIR", default_value = "docs")]
    pub out: PathBuf,
    /// A smaller run (no M3, one small random scene, short limit sweeps), for trying changes.
    #[arg(long)]
    pub quick: bool,
    /// Do not count instructions (no valgrind needed); the report leaves the column empty and
    /// says so, and has no plot.
    #[arg(long)]
    pub no_count: bool,
    /// Directories to look for the models in, before the repository's assets and the shared
    /// assets next to the repository.
    #[arg(long, value_name = "DIR")]
    pub models: Vec<PathBuf>,
}

/// Options of the hidden `accuracy-count` command, which the `accuracy` command runs under
/// callgrind.
#[derive(Debug, Clone, clap::Args)]
pub struct CountArgs {
    /// The configuration's label.
    pub label: String,
    /// Directories to look for the models in first.
    #[arg(long, value_name = "DIR")]
    pub models: Vec<PathBuf>,
}

/// Scenes with the errors summed over them (the random scenes form one group).
#[derive(Debug, Clone)]
pub struct Group {
    /// Name in the report.
    pub name: String,
    /// The scenes.
    pub scenes: Vec<SceneDef>,
}

/// What to sweep.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The scene groups (M1 first: the plot and the counts use it).
    pub groups: Vec<Group>,
    /// The configurations.
    pub configs: Vec<Config>,
    /// The breakdown sweeps' steps.
    pub breakdown: breakdown::Plan,
}

/// One configuration's results.
#[derive(Debug, Clone)]
pub struct Row {
    /// The configuration.
    pub config: Config,
    /// Its M1 frame's count, when counted.
    pub count: Option<Count>,
    /// Its errors per group, in the plan's order.
    pub errors: Vec<Measured>,
}

/// Everything the report shows.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// Group names and triangle counts (of the first scene for single scenes, the total for
    /// several).
    pub groups: Vec<(String, usize, usize)>,
    /// One row per configuration.
    pub rows: Vec<Row>,
    /// The limits of each format.
    pub breakdown: Vec<breakdown::Breakdown>,
    /// M1's triangle count (for instructions per triangle).
    pub m1_triangles: usize,
    /// The textured pipeline's coordinates on M4 ([`texture::measure`]), when measured.
    pub texture: Option<Result<Vec<texture::TextureRow>, String>>,
    /// M4's instructions per frame from the figures of record (`docs/figures.tsv`): renderer and
    /// count, for the texture section's cost column.
    pub texture_costs: Vec<(String, u64)>,
}

/// Measures every configuration on every group and runs the breakdown sweeps on the first
/// group's first scene. `progress` hears what is being done.
pub fn sweep(plan: &Plan, progress: &dyn Fn(&str)) -> Sweep {
    let mut rows: Vec<Row> = plan
        .configs
        .iter()
        .map(|&config| Row {
            config,
            count: None,
            errors: Vec::new(),
        })
        .collect();
    let mut groups = Vec::new();
    for g in &plan.groups {
        let tris: usize = g.scenes.iter().map(|s| s.tris.len()).sum();
        groups.push((g.name.clone(), g.scenes.len(), tris));
        let mut acc: Vec<Measured> = vec![Ok(metrics::Errors::default()); rows.len()];
        for s in &g.scenes {
            progress(&format!(
                "{}: f64 reference of {} ({} triangles, {}x{})",
                g.name,
                s.name,
                s.tris.len(),
                s.width,
                s.height
            ));
            let prepared = Prepared::new(s.clone(), true);
            for (row, a) in rows.iter().zip(acc.iter_mut()) {
                let m = (row.config.measure)(&prepared);
                *a = match (&*a, m) {
                    (Ok(x), Ok(y)) => Ok(x.merge(&y)),
                    (Err(e), _) => Err(e.clone()),
                    (_, Err(e)) => Err(e),
                };
            }
        }
        for (row, a) in rows.iter_mut().zip(acc) {
            row.errors.push(a);
        }
    }
    let base = &plan.groups[0].scenes[0];
    let formats = breakdown_configs(plan);
    let breakdown = breakdown::run(base, &formats, &plan.breakdown, |label| {
        progress(&format!("limits of {label}"))
    });
    Sweep {
        groups,
        rows,
        breakdown,
        m1_triangles: base.tris.len(),
        texture: None,
        texture_costs: Vec::new(),
    }
}

/// The configurations whose limits [`sweep`] finds: the formats, the default and the control.
fn breakdown_configs(plan: &Plan) -> Vec<Config> {
    plan.configs
        .iter()
        .filter(|c| c.varies == "default" || c.varies == "format" || c.varies == "control")
        .copied()
        .collect()
}

fn model_dirs(extra: &[PathBuf]) -> Vec<PathBuf> {
    let mut dirs = extra.to_vec();
    dirs.extend(scene::default_model_dirs());
    dirs
}

fn load(dirs: &[PathBuf], name: &str, file: &str, unit: bool) -> Result<SceneDef, String> {
    let path = scene::find_model(dirs, file).ok_or_else(|| {
        let list: Vec<String> = dirs.iter().map(|d| d.display().to_string()).collect();
        format!("{file} not found in {}", list.join(", "))
    })?;
    scene::workload_scene(name, &path, unit)
}

/// The M1 scene (Suzanne).
pub fn m1(dirs: &[PathBuf]) -> Result<SceneDef, String> {
    load(dirs, "M1", "suzanne.obj", false)
}

/// The `accuracy` command.
pub fn run(args: &AccuracyArgs) -> Result<(), Box<dyn std::error::Error>> {
    let started = Instant::now();
    if cfg!(debug_assertions) {
        crate::errln!(
            "warning: this is a debug build: the instruction counts are not the release figures \
             and the sweep is slow; use `cargo run --release -p host-tools -- accuracy`"
        );
    }
    let dirs = model_dirs(&args.models);
    let mut groups = vec![Group {
        name: "M1".into(),
        scenes: vec![m1(&dirs)?],
    }];
    groups.push(Group {
        name: "M2".into(),
        scenes: vec![load(&dirs, "M2", "stanford-bunny-res3.obj", true)?],
    });
    if !args.quick {
        groups.push(Group {
            name: "M3".into(),
            scenes: vec![load(&dirs, "M3", "stanford-bunny.obj", true)?],
        });
    }
    let (n_random, per) = if args.quick { (1, 100) } else { (4, 400) };
    groups.push(Group {
        name: "random".into(),
        scenes: (0..n_random)
            .map(|k| scene::random_scene(&format!("random {k}"), per, k * 7919, 320, 240))
            .collect(),
    });
    let mut bplan = breakdown::Plan::full();
    if args.quick {
        bplan.scales_up.truncate(10);
        bplan.scales_down.truncate(6);
        bplan.nears.truncate(12);
    }
    let plan = Plan {
        groups,
        configs: config::registry(),
        breakdown: bplan,
    };

    let mut counts: Vec<Option<Count>> = vec![None; plan.configs.len()];
    let mut valgrind = None;
    // Minutes of work: a bar on a terminal, nothing in a log (the report has every figure).
    let progress = Progress::new(true);
    if !args.no_count {
        valgrind = Some(count::check_valgrind()?);
        let exe = std::env::current_exe()?;
        let scratch =
            std::env::temp_dir().join(format!("host-tools-accuracy-{}", std::process::id()));
        std::fs::create_dir_all(&scratch)?;
        let models: Vec<String> = args
            .models
            .iter()
            .map(|d| d.display().to_string())
            .collect();
        progress.stage("counting", plan.configs.len() as u64);
        for (c, slot) in plan.configs.iter().zip(counts.iter_mut()) {
            *slot = Some(count::count(&exe, c.label, &models, &scratch)?);
            progress.inc();
        }
        let _ = std::fs::remove_dir(&scratch);
    }

    // One step per scene measured, per configuration's limits and for the texture section.
    let scenes: usize = plan.groups.iter().map(|g| g.scenes.len()).sum();
    let steps = scenes + breakdown_configs(&plan).len() + 1;
    progress.stage("measuring", steps as u64);
    let mut result = sweep(&plan, &|_| progress.inc());
    for (row, c) in result.rows.iter_mut().zip(counts) {
        row.count = c;
    }
    result.texture = Some(texture::measure());
    progress.inc();
    progress.finish();
    result.texture_costs = texture::costs(&args.out.join("figures.tsv"));
    let meta = report::Meta {
        date: report::today(),
        rustc: report::rustc_version(),
        valgrind,
        quick: args.quick,
        debug_build: cfg!(debug_assertions),
        seconds: started.elapsed().as_secs_f64(),
    };
    let written = report::write(&args.out, &result, &meta)?;
    for p in written {
        crate::outln!("wrote {}", p.display())?;
    }
    Ok(())
}

/// The hidden `accuracy-count` command: draws configuration `label`'s counted M1 frame and prints
/// what it drew.
pub fn run_count(args: &CountArgs) -> Result<(), Box<dyn std::error::Error>> {
    let c = config::registry()
        .into_iter()
        .find(|c| c.label == args.label)
        .ok_or_else(|| format!("no configuration {}", args.label))?;
    let scene = m1(&model_dirs(&args.models))?;
    crate::outln!("{}", (c.count)(&scene)?)?;
    Ok(())
}

/// Panics unless docs/ACCURACY.md holds `section` as the report's code writes it now (for the
/// sections computed without scenes, which their tests check against the committed report).
#[cfg(test)]
pub(crate) fn assert_report_holds(section: &str) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/ACCURACY.md");
    let doc = std::fs::read_to_string(path).unwrap();
    assert!(
        doc.contains(section),
        "regenerate docs/ACCURACY.md; the section is now:\n{section}"
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The whole sweep on a tiny scene, every configuration, no valgrind: runs in debug in
    /// seconds.
    #[test]
    fn smoke_sweep_writes_the_report() {
        let tiny = |k: u32| scene::random_scene(&format!("tiny {k}"), 12, k, 64, 48);
        let plan = Plan {
            groups: vec![
                Group {
                    name: "tiny".into(),
                    scenes: vec![tiny(0)],
                },
                Group {
                    name: "random".into(),
                    scenes: vec![tiny(1), tiny(2)],
                },
            ],
            configs: config::registry(),
            breakdown: breakdown::Plan {
                scales_up: vec![1, 12],
                scales_down: vec![-1],
                nears: vec![0.01],
                widths: vec![640, 32767],
            },
        };
        let result = sweep(&plan, &|_| {});
        assert_eq!(result.rows.len(), plan.configs.len());
        assert_eq!(result.breakdown.len(), 5);
        let default = &result.rows[0];
        assert_eq!(default.config.label, config::DEFAULT);
        let e = default.errors[0].as_ref().expect("the default renders");
        assert!(e.covered > 0 && e.vertices > 0);
        assert!(e.vertex_max < 0.5, "16.16 vertices within half a pixel");
        // The f64 control agrees with the reference to well under a pixel.
        let f64_row = result.rows.iter().find(|r| r.config.control).unwrap();
        assert!(f64_row.errors[0].as_ref().unwrap().vertex_max < 0.1);
        let dir = std::env::temp_dir().join(format!("accuracy-smoke-{}", std::process::id()));
        let meta = report::Meta {
            date: "2026-01-01".into(),
            rustc: "rustc".into(),
            valgrind: None,
            quick: true,
            debug_build: true,
            seconds: 0.0,
        };
        let written = report::write(&dir, &result, &meta).unwrap();
        let md = std::fs::read_to_string(&written[0]).unwrap();
        assert!(md.contains("not counted"));
        assert!(md.contains("| default |"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
