//! Writes `ACCURACY.md` and `images/accuracy.svg` from a sweep: tables, the breakdown limits, and
//! the words on the default configuration, which are a template filled with the measured numbers.

use super::breakdown::{Limit, MAX_DEPTH_MISTAKES, MAX_DIFFERING, MAX_VERTEX_PX};
use super::config::DEFAULT;
use super::metrics::{pareto_front, Errors, DEPTH_TIE};
use super::plot;
use super::{Row, Sweep};
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// How and when the report was made.
#[derive(Debug, Clone)]
pub struct Meta {
    /// UTC date, `YYYY-MM-DD`.
    pub date: String,
    /// `rustc --version`.
    pub rustc: String,
    /// `valgrind --version`, when counted.
    pub valgrind: Option<String>,
    /// A `--quick` run.
    pub quick: bool,
    /// Built without optimisations.
    pub debug_build: bool,
    /// Seconds the command took.
    pub seconds: f64,
}

/// Today's UTC date.
pub fn today() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (y, m, d) = civil(secs / 86_400);
    format!("{y:04}-{m:02}-{d:02}")
}

/// The proleptic Gregorian date of a day count since 1970-01-01 (Howard Hinnant's algorithm).
fn civil(days: u64) -> (i64, u32, u32) {
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let y = yoe + era * 400 + i64::from(m <= 2);
    (y, m, d)
}

/// `rustc --version`, or "rustc (unknown version)".
pub fn rustc_version() -> String {
    std::process::Command::new("rustc")
        .arg("--version")
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "rustc (unknown version)".into())
}

/// `1234567` as `1,234,567`.
fn thousands(v: u64) -> String {
    let s = v.to_string();
    let mut out = String::new();
    for (i, ch) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(ch);
    }
    out
}

fn pct(v: f64) -> String {
    format!("{:.3} %", 100.0 * v)
}

/// The M1 error the plot and the front use: the share of covered pixels that are wrong.
fn m1_error(row: &Row) -> Option<f64> {
    row.errors.first()?.as_ref().ok().map(Errors::wrong_share)
}

fn cost(row: &Row) -> Option<f64> {
    row.count.as_ref().map(|c| c.instructions as f64)
}

fn signed_pct(a: f64, b: f64) -> String {
    format!("{:+.1} %", 100.0 * (a / b - 1.0))
}

fn limit_cell(l: &Limit, fmt: impl Fn(f64) -> String) -> String {
    match (l.good, &l.bad) {
        (Some(g), Some((v, why))) => format!("{} (breaks at {}: {why})", fmt(g), fmt(*v)),
        (Some(g), None) => format!("{} (held at every step tried)", fmt(g)),
        (None, Some((v, why))) => format!("fails already at {}: {why}", fmt(*v)),
        (None, None) => "not tried".into(),
    }
}

fn scale_fmt(v: f64) -> String {
    let k = v.log2().round() as i32;
    format!("2^{k}")
}

fn near_fmt(v: f64) -> String {
    format!("{v:.2e}")
}

fn width_fmt(v: f64) -> String {
    let w = v as u32;
    format!("{w}x{}", w * 3 / 4)
}

/// The indices (into `rows`) of the plotted configurations and the front among them.
fn front(rows: &[Row]) -> (Vec<usize>, Vec<usize>) {
    let plotted: Vec<usize> = (0..rows.len())
        .filter(|&i| {
            !rows[i].config.control && cost(&rows[i]).is_some() && m1_error(&rows[i]).is_some()
        })
        .collect();
    let pts: Vec<(f64, f64)> = plotted
        .iter()
        .map(|&i| {
            (
                cost(&rows[i]).unwrap_or(0.0),
                m1_error(&rows[i]).unwrap_or(0.0),
            )
        })
        .collect();
    let f = pareto_front(&pts).into_iter().map(|k| plotted[k]).collect();
    (plotted, f)
}

/// Writes the report and the plot under `out`; returns the paths written.
pub fn write(
    out: &Path,
    sweep: &Sweep,
    meta: &Meta,
) -> Result<Vec<PathBuf>, Box<dyn std::error::Error>> {
    let images = out.join("images");
    std::fs::create_dir_all(&images)
        .map_err(|e| format!("cannot create {}: {e}", images.display()))?;
    let (plotted, on_front) = front(&sweep.rows);
    let mut written = Vec::new();
    let counted = !plotted.is_empty();
    if counted {
        let points: Vec<plot::Point> = plotted
            .iter()
            .map(|&i| plot::Point {
                label: sweep.rows[i].config.label.to_string(),
                cost: cost(&sweep.rows[i]).unwrap_or(0.0),
                error: 100.0 * m1_error(&sweep.rows[i]).unwrap_or(0.0),
                front: on_front.contains(&i),
            })
            .collect();
        let svg = plot::svg(
            &points,
            "M1: wrong pixels against instructions per frame",
            "instructions per M1 frame (callgrind, log scale)",
            "wrong pixels, % of covered (log scale)",
        );
        let path = images.join("accuracy.svg");
        write_text(&path, &svg)?;
        written.push(path);
    }
    let md = markdown(sweep, meta, &on_front, counted);
    let path = out.join("ACCURACY.md");
    write_text(&path, &md)?;
    written.insert(0, path);
    Ok(written)
}

/// One report file, through the shared output writer (an old report survives a failure).
fn write_text(path: &Path, text: &str) -> Result<(), crate::output::OutputError> {
    crate::output::write_output(path, &[], |w| std::io::Write::write_all(w, text.as_bytes()))
}

fn markdown(sweep: &Sweep, meta: &Meta, on_front: &[usize], counted: bool) -> String {
    let mut s = String::new();
    let rows = &sweep.rows;
    let _ = writeln!(s, "# Accuracy of the 3D pipeline\n");
    let _ = writeln!(
        s,
        "<!-- Generated by `cargo run --release -p host-tools -- accuracy`. Do not edit by hand: \
         change host-tools/src/accuracy/ and run the command again. -->\n"
    );
    let _ = writeln!(
        s,
        "Generated on {} by `cargo run --release -p host-tools -- accuracy`{} from the repository \
         root ({}{}; {:.0} s{}). Do not edit this file: it is rewritten by the command, from the \
         code in `host-tools/src/accuracy/`.\n",
        meta.date,
        if meta.quick { " --quick" } else { "" },
        meta.rustc,
        meta.valgrind
            .as_ref()
            .map_or(String::new(), |v| format!(", {v}")),
        meta.seconds,
        if meta.debug_build {
            "; a debug build, so the counts are not release figures"
        } else {
            ""
        }
    );
    if !counted {
        let _ = writeln!(
            s,
            "Instructions were **not counted** in this run (`--no-count`, or no valgrind): the \
             instruction columns are empty and there is no plot.\n"
        );
    }

    words(&mut s, sweep, on_front, counted);

    if counted {
        let _ = writeln!(s, "## Cost against error\n");
        let _ = writeln!(
            s,
            "![Wrong M1 pixels against instructions per frame](images/accuracy.svg)\n"
        );
        let _ = writeln!(
            s,
            "x: instructions per M1 frame (callgrind, log scale); y: share of the covered M1 pixels \
             that are wrong (log scale) (a different triangle than in the f64 render, or a colour more than one \
             8-bit step off). Filled red and joined by the line: the Pareto front, the \
             configurations no other one beats in both cost and error. The `f64` control is left \
             out (it is not a library format).\n"
        );
    }

    let default_cost = rows
        .iter()
        .find(|r| r.config.label == DEFAULT)
        .and_then(cost);
    let _ = writeln!(s, "## Configurations\n");
    let _ = writeln!(
        s,
        "Each is its own monomorphized `Pipeline` type (`host-tools/src/accuracy/config.rs`). \
         Counted: one M1 frame (Suzanne, {} triangles, Rgb565 320x240, Gouraud lit, depth buffer, \
         back faces culled), after a warm frame, as `count3d m1` does.\n",
        sweep.m1_triangles
    );
    let _ = writeln!(
        s,
        "| # | configuration | varies | format | sub-pixel bits | sine table | divide | \
         interpolation bits | span starts | perspective | dithering | instructions / M1 frame | \
         per triangle | vs default | Pareto front |"
    );
    let _ = writeln!(
        s,
        "|---:|---|---|---|---:|---:|---|---:|---|---|---|---:|---:|---:|---|"
    );
    for (i, r) in rows.iter().enumerate() {
        let k = &r.config.knobs;
        let (instr, per, vs) = match (&r.count, default_cost) {
            (Some(c), d) => (
                thousands(c.instructions),
                thousands(c.instructions / sweep.m1_triangles.max(1) as u64),
                d.map_or(String::new(), |d| signed_pct(c.instructions as f64, d)),
            ),
            (None, _) => ("not counted".into(), String::new(), String::new()),
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {instr} | {per} | {vs} | {} |",
            i + 1,
            r.config.label,
            r.config.varies,
            k.format,
            k.bits,
            k.table,
            k.divide_name(),
            k.frac,
            k.spans_name(),
            if k.perspective { "yes" } else { "no" },
            k.dither_name(),
            if on_front.contains(&i) {
                "**yes**"
            } else if r.config.control {
                "(control)"
            } else {
                ""
            }
        );
    }
    let _ = writeln!(s);

    let _ = writeln!(s, "## Errors per scene\n");
    let _ = writeln!(
        s,
        "Against the f64 reference (`fixtures::reference3d`): the same scene built in f64 from \
         the same parameters, clipped, projected and rasterized in f64 (pixel centres, top-left \
         rule), lit per vertex in f64 and interpolated perspective-correctly. Definitions under \
         [How it is measured](#how-it-is-measured).\n"
    );
    for (g, (name, count, tris)) in sweep.groups.iter().enumerate() {
        let what = if *count == 1 {
            format!("{tris} triangles")
        } else {
            format!("{count} scenes, {tris} triangles in all, errors summed over them")
        };
        let _ = writeln!(s, "### {name} ({what})\n");
        let _ = writeln!(
            s,
            "| configuration | vertex error max (px) | mean (px) | differing pixels | share | \
             colour error max (steps) | mean (steps) | depth-order mistakes | wrong pixels |"
        );
        let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---:|---:|---:|");
        for r in rows {
            match &r.errors[g] {
                Ok(e) => {
                    let _ = writeln!(s, "{}", error_row(r.config.label, e));
                }
                Err(why) => {
                    let _ = writeln!(s, "| {} | fails: {why} | | | | | | | |", r.config.label);
                }
            }
        }
        let _ = writeln!(s);
    }

    dithering(&mut s, sweep);
    texture_section(&mut s, sweep);
    super::blending::section(&mut s);
    super::fog::section(&mut s);
    super::lighting::section(&mut s);
    super::matcap::section(&mut s);
    super::silhouette::section(&mut s);
    super::sprite::section(&mut s);

    let _ = writeln!(s, "## Where each format breaks down\n");
    let _ = writeln!(
        s,
        "M1 pushed one way at a time, each format with the default's other knobs, until the error \
         passes a threshold: a visible vertex more than {MAX_VERTEX_PX} px from its exact place, \
         more than {} of the covered pixels showing another triangle than f64, more than {} of \
         them a farther surface, or no picture at all (a matrix the format cannot build, nothing \
         drawn). The scene scale multiplies the model, the eye and both planes by a power of two \
         (the same picture in exact arithmetic); the near plane moves in from 0.1, halved at each step \
         (far stays 100); the screen grows from 320x240 to the viewport limit of 32,767 pixels, \
         where only the vertex error is measured (an f64 raster of a billion pixels is out of \
         reach). The `f64` row is the control: what breaks there is the integer part of the \
         pipeline (the 16-bit depth buffer, the sub-pixel grid), not the format.\n"
        ,
        pct(MAX_DIFFERING),
        pct(MAX_DEPTH_MISTAKES)
    );
    let _ = writeln!(
        s,
        "| format | largest scene scale | smallest scene scale | nearest near plane | largest screen |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|");
    for b in &sweep.breakdown {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} |",
            b.format,
            limit_cell(&b.scale_up, scale_fmt),
            limit_cell(&b.scale_down, scale_fmt),
            limit_cell(&b.near, near_fmt),
            limit_cell(&b.screen, width_fmt)
        );
    }
    let _ = writeln!(s);

    let _ = writeln!(s, "## How it is measured\n");
    let _ = writeln!(
        s,
        "- **Scenes.** M1-M3 as in `shared/bench/WORKLOADS.md` (320x240, the model turned 30° \
         about y, eye at (0, 0, 3), 60° field of view, near 0.1, far 100, back faces culled; the \
         bunnies centred and scaled to the unit sphere), lit like `count3d`: one white \
         directional light from (1, 1, 1), Blinn-Phong, material ambient (40, 30, 30), diffuse \
         (220, 140, 80), specular white, shininess 16. Random scenes: xorshift32 seeded \
         0x12345678, triangles scattered through the view volume at depths 0.05 to 20 (one in \
         eight within 0.3 of the eye, crossing or before the near plane), corners up to half \
         the depth from the centre so that triangles cut through each other, random normals, \
         nothing culled. Positions are on the 16.16 grid; other formats round them to theirs \
         (their input error is part of their error).\n\
         - **Vertex position error**: for each vertex inside the f64 view volume, the distance \
         in pixels between `Pipeline::project(mvp · v)` (sub-pixel coordinates in pixels) and \
         the f64 projection.\n\
         - **Differing pixels**: pixels whose triangle (ours: a render with each face painted \
         with its id, `FaceIds`; the reference's: the nearest f64 fragment) differs, including \
         pixels only one side covers; the share is of the pixels the reference covers.\n\
         - **Colour error**: where both show the same triangle, the largest channel difference \
         between our Rgb888 Gouraud render and the true colour rounded to 8 bits, in 8-bit \
         steps; max and mean over those pixels.\n\
         - **Depth-order mistakes**: differing pixels where our triangle does cover the pixel in \
         the reference but lies more than {DEPTH_TIE} depth step (of 65,535) behind the nearest \
         surface there; closer than that is a tie (the 16-bit depth buffer cannot order it).\n\
         - **Wrong pixels**: differing pixels plus same-triangle pixels more than one step off \
         in colour: the plot's error.\n\
         - **Knobs** (`host-tools/src/accuracy/config.rs`): the geometry format (`Scalar`), \
         `Pipeline`'s `BITS`, the table size `N` of `rotation_y_with::<N>` and \
         `perspective_with::<N>`, and its `rasterizer_core::numerics::Numerics` type: the divide \
         method (exact division per coordinate; one reciprocal per vertex, then multiplications; \
         a 64-entry table and two Newton steps, no division), the fractional bits of \
         interpolated colour and depth (with exact or gradient span starts), the span starts \
         (32-bit wrapping planes in the fused loop, the default; exact; or from gradients \
         rounded once per triangle) and perspective-correct interpolation.\n\
         - **Instructions**: callgrind `--toggle-collect='*counted_frame*'` on the hidden \
         `accuracy-count CONFIGURATION` command, one M1 frame into Rgb565 after a warm frame, \
         release build, x86-64. The sine table is read only when matrices are built, so its size \
         costs flash (4 bytes per entry), not instructions per frame.\n"
    );
    s
}

/// The words on the default: a template filled with the numbers.
/// The textured pipeline's texture coordinates against f64 on M4, and what texturing costs.
fn texture_section(s: &mut String, sweep: &Sweep) {
    let Some(measured) = &sweep.texture else {
        return;
    };
    let _ = writeln!(s, "## Texture coordinates (M4)\n");
    let _ = writeln!(
        s,
        "`TexturedLit` on M4 (Spot, the M1 camera, nearest texel): each pixel's texel against \
         the exact perspective-correct coordinates at its centre, interpolated in f64 from the \
         triangle's vertices as the pipeline projected them (so this is the texture path's own \
         error, apart from the geometry's). A 256-texel id texture names the texel each pixel \
         drew; multiplying the model's coordinates by 4, 16 and 256 makes it address the texture \
         as one of 1024 texels a side (M4's own), 4096 and 65536 would, resolving the error \
         ever more finely. \
         Distance: how far the exact coordinates lie from the texel drawn, in texels of that \
         side, the larger of the two axes (zero when they fall in it). The affine columns are \
         the same measure had the coordinates been interpolated linearly in screen space (the \
         per-pixel division is what removes that error; M4's triangles are small, so it is \
         modest here and grows with a triangle's depth range).\n"
    );
    match measured {
        Ok(rows) => {
            let _ = writeln!(
                s,
                "| texture side | pixels | on another texel | mean distance | max distance | \
                 affine: mean | affine: max |\n|---:|---:|---:|---:|---:|---:|---:|"
            );
            for r in rows {
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {:.2e} | {:.2e} | {:.2e} | {:.2e} |",
                    r.side,
                    thousands(r.pixels as u64),
                    r.off,
                    r.mean,
                    r.max,
                    r.affine_mean,
                    r.affine_max
                );
            }
        }
        Err(why) => {
            let _ = writeln!(s, "Not measured: {why}");
        }
    }
    let _ = writeln!(s);
    let cost = |r: &str| {
        sweep
            .texture_costs
            .iter()
            .find(|(name, _)| name == r)
            .map(|(_, n)| *n)
    };
    let Some(base) = cost("ours-untextured") else {
        let _ = writeln!(
            s,
            "(No M4 counts in `docs/figures.tsv`: run `scripts/figures.sh` for the cost.)\n"
        );
        return;
    };
    let _ = writeln!(
        s,
        "Cost, instructions per M4 frame from the figures of record (`docs/figures.tsv`, \
         `scripts/figures.sh`): per pixel, two divisions (one instruction each on x86-64; a \
         core without a hardware divider pays far more). Texture coordinates are always \
         interpolated per pixel; a per-span-segment variant is not built.\n\n\
         | choice | instructions / M4 frame | against untextured |\n|---|---:|---:|"
    );
    for (label, r) in [
        ("untextured (Gouraud only)", "ours-untextured"),
        ("nearest, per pixel (the default)", "ours"),
        ("bilinear, per pixel", "ours-m4_bilinear"),
    ] {
        if let Some(n) = cost(r) {
            let _ = writeln!(
                s,
                "| {label} | {} | {:.2}x |",
                thousands(n),
                n as f64 / base as f64
            );
        }
    }
    let _ = writeln!(s);
}

/// The Rgb565 colour of the default and the dithered configurations against the f64 colour.
fn dithering(s: &mut String, sweep: &Sweep) {
    let rows: Vec<&Row> = sweep
        .rows
        .iter()
        .filter(|r| r.config.varies == "default" || r.config.varies == "dithering")
        .collect();
    let _ = writeln!(s, "## Dithering (Rgb565)\n");
    let _ = writeln!(
        s,
        "The same Gouraud render into Rgb565, where each channel has 5 or 6 bits: rounded to the \
         nearest step (the default) or dithered with an ordered (Bayer) matrix \
         (`Numerics::DITHER`). Errors in steps of each channel against the f64 colour scaled to \
         it, the mean of the three channels, over the pixels showing the same triangle as f64: \
         per pixel (dithering trades a larger error per pixel), the signed mean (bias), and the \
         error of the mean colour of each 4x4 screen tile all of whose pixels are compared (what \
         the eye sees at a distance: dithering brings it down). Instructions: one M1 frame, as \
         in the configurations table.\n"
    );
    let _ = write!(s, "| configuration | dithering | instructions / M1 frame |");
    for (name, _, _) in &sweep.groups {
        let _ = write!(s, " {name} per pixel | {name} bias | {name} 4x4 tile |");
    }
    let _ = writeln!(s);
    let _ = write!(s, "|---|---|---:|");
    for _ in &sweep.groups {
        let _ = write!(s, "---:|---:|---:|");
    }
    let _ = writeln!(s);
    for r in rows {
        let instr = r
            .count
            .as_ref()
            .map_or("not counted".into(), |c| thousands(c.instructions));
        let _ = write!(
            s,
            "| {} | {} | {instr} |",
            r.config.label,
            r.config.knobs.dither_name()
        );
        for e in &r.errors {
            match e {
                Ok(e) => {
                    let _ = write!(
                        s,
                        " {:.4} | {:+.4} | {:.4} |",
                        e.rgb565_mean(),
                        e.rgb565_bias(),
                        e.tile_mean()
                    );
                }
                Err(_) => {
                    let _ = write!(s, " fails | | |");
                }
            }
        }
        let _ = writeln!(s);
    }
    let _ = writeln!(s);
}

/// A configuration's row of an error table (one scene group).
pub(crate) fn error_row(label: &str, e: &Errors) -> String {
    format!(
        "| {} | {:.4} | {:.4} | {} | {} | {} | {:.3} | {} | {} |",
        label,
        e.vertex_max,
        e.vertex_mean(),
        thousands(e.differing),
        pct(e.differing_share()),
        e.color_max,
        e.color_mean(),
        thousands(e.depth_mistakes),
        pct(e.wrong_share())
    )
}

/// The report's headline: the default configuration and its M1 errors `de`.
pub(crate) fn default_headline(de: &Errors) -> String {
    format!(
        "The library's default is **16.16 geometry, 6 sub-pixel bits (26.6 screen coordinates), \
         the 256-entry sine table, exact division in the perspective divide, 32-bit wrapping span \
         planes (exact at an anchor pixel, 16 fractional bits for colour and depth), affine \
         interpolation** (`rasterizer_core::numerics::Standard`). On M1 its vertices land within {:.3} px of \
         their exact place (mean {:.4} px), {} of the covered pixels show another triangle than \
         the f64 render, colours are off by at most {} steps (mean {:.3}), and {} of the pixels \
         are wrong in all.",
        de.vertex_max,
        de.vertex_mean(),
        pct(de.differing_share()),
        de.color_max,
        de.color_mean(),
        pct(de.wrong_share())
    )
}

fn words(s: &mut String, sweep: &Sweep, on_front: &[usize], counted: bool) {
    let rows = &sweep.rows;
    let Some((di, d)) = rows
        .iter()
        .enumerate()
        .find(|(_, r)| r.config.label == DEFAULT)
    else {
        return;
    };
    let find = |label: &str| rows.iter().find(|r| r.config.label == label);
    let Ok(de) = d.errors.first().cloned().unwrap_or(Err(String::new())) else {
        return;
    };
    let _ = writeln!(s, "## The default and why\n");
    let _ = write!(s, "{}", default_headline(&de));
    if let (true, Some(dc)) = (counted, cost(d)) {
        let _ = write!(
            s,
            " A frame costs {} instructions ({} per triangle).",
            thousands(dc as u64),
            thousands(dc as u64 / sweep.m1_triangles.max(1) as u64)
        );
        let de_err = de.wrong_share();
        if on_front.contains(&di) {
            let _ = write!(
                s,
                " It is **on the Pareto front**: no configuration is both cheaper and more \
                 accurate."
            );
        } else {
            let better: Vec<&str> = rows
                .iter()
                .filter(|r| !r.config.control)
                .filter(|r| {
                    matches!((cost(r), m1_error(r)),
                        (Some(c), Some(e)) if c <= dc && e <= de_err && (c < dc || e < de_err))
                })
                .map(|r| r.config.label)
                .collect();
            // The cheapest front point at least as accurate, and the most accurate one no dearer.
            let as_good = on_front
                .iter()
                .filter(|&&i| m1_error(&rows[i]).is_some_and(|e| e <= de_err))
                .filter_map(|&i| cost(&rows[i]).map(|c| (c, i)))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let _ = write!(
                s,
                " It is **not on the Pareto front**: {} at least as accurate for no more \
                 instructions and better in one of the two",
                if better.len() == 1 {
                    format!("`{}` is", better[0])
                } else {
                    format!(
                        "{} are",
                        better
                            .iter()
                            .map(|b| format!("`{b}`"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                }
            );
            if let Some((c, i)) = as_good {
                let _ = write!(
                    s,
                    "; the front reaches its accuracy with `{}` at {} of its cost",
                    rows[i].config.label,
                    pct(c / dc)
                );
            }
            let _ = write!(s, ".");
            if better.iter().any(|b| b.starts_with("f32")) {
                let _ = write!(
                    s,
                    " f32 is cheap here because x86-64 has a hardware FPU; the microcontrollers \
                     the library is for mostly have none (every f32 operation a library call), \
                     and its default build has no float code at all."
                );
            }
            // The same question among the integer-only configurations.
            let ints: Vec<usize> = (0..rows.len())
                .filter(|&i| !rows[i].config.control && rows[i].config.knobs.format != "f32")
                .filter(|&i| cost(&rows[i]).is_some() && m1_error(&rows[i]).is_some())
                .collect();
            let pts: Vec<(f64, f64)> = ints
                .iter()
                .map(|&i| {
                    (
                        cost(&rows[i]).unwrap_or(0.0),
                        m1_error(&rows[i]).unwrap_or(0.0),
                    )
                })
                .collect();
            let int_front: Vec<usize> = pareto_front(&pts).into_iter().map(|k| ints[k]).collect();
            if int_front.contains(&di) {
                let _ = write!(
                    s,
                    " Among the integer-only configurations it is on the front."
                );
            } else {
                let beat: Vec<String> = ints
                    .iter()
                    .filter(|&&i| i != di)
                    .filter(|&&i| {
                        matches!((cost(&rows[i]), m1_error(&rows[i])),
                            (Some(c), Some(e)) if c <= dc && e <= de_err && (c < dc || e < de_err))
                    })
                    .map(|&i| {
                        format!(
                            "`{}` ({}, {} wrong)",
                            rows[i].config.label,
                            signed_pct(cost(&rows[i]).unwrap_or(0.0), dc),
                            pct(m1_error(&rows[i]).unwrap_or(0.0))
                        )
                    })
                    .collect();
                let _ = write!(
                    s,
                    " Among the integer-only configurations, {} beat it by these numbers.",
                    beat.join(", ")
                );
            }
        }
    }
    let _ = writeln!(s, "\n");
    let _ = writeln!(s, "Why these knobs, from the tables below:\n");
    // Formats.
    for label in ["24.8", "8.24", "f32"] {
        let Some(r) = find(label) else { continue };
        let b = sweep.breakdown.iter().find(|b| b.label == label);
        let mut line = format!("- **{}**", r.config.knobs.format);
        if let (Some(c), Some(dc)) = (cost(r), cost(d)) {
            let _ = write!(
                line,
                " costs {} instructions per frame ({} against 16.16)",
                thousands(c as u64),
                signed_pct(c, dc)
            );
            if label == "24.8" {
                line.push_str(
                    " (its 8 fractional bits carry the model matrix too coarsely to light in \
                     model space, so it lights in world space)",
                );
            }
        }
        match r.errors.first() {
            Some(Ok(e)) => {
                let _ = write!(
                    line,
                    "; on M1 its vertices are up to {:.3} px off and {} of the pixels are wrong",
                    e.vertex_max,
                    pct(e.wrong_share())
                );
            }
            Some(Err(why)) => {
                let _ = write!(line, "; it cannot render M1: {why}");
            }
            None => {}
        }
        if let Some(b) = b {
            let _ = write!(
                line,
                "; it holds scenes scaled from {} to {} and screens up to {}",
                b.scale_down.good.map_or("-".into(), scale_fmt),
                b.scale_up.good.map_or("-".into(), scale_fmt),
                b.screen.good.map_or("-".into(), width_fmt)
            );
        }
        let _ = writeln!(s, "{line}.");
    }
    if let Some(b) = sweep.breakdown.iter().find(|b| b.label == DEFAULT) {
        let _ = writeln!(
            s,
            "- **16.16** holds scenes scaled from {} to {}, a near plane down to {} and screens up \
             to {}: the range and resolution a microcontroller scene needs, in plain `i32` \
             arithmetic.",
            b.scale_down.good.map_or("-".into(), scale_fmt),
            b.scale_up.good.map_or("-".into(), scale_fmt),
            b.near.good.map_or("-".into(), near_fmt),
            b.screen.good.map_or("-".into(), width_fmt)
        );
    }
    let knob_against = |s: &mut String, what: &str, labels: &[&str], reference: &str| {
        let Some(base) = find(reference) else { return };
        let Some(Ok(de)) = base.errors.first().cloned() else {
            return;
        };
        let parts: Vec<String> = labels
            .iter()
            .filter_map(|l| find(l))
            .filter_map(|r| {
                let e = r.errors.first()?.as_ref().ok()?;
                let c = match (cost(r), cost(base)) {
                    (Some(c), Some(dc)) => format!("{}, ", signed_pct(c, dc)),
                    _ => String::new(),
                };
                Some(format!(
                    "`{}` {c}{} wrong, vertices {:.3} px, colour mean {:.3}",
                    r.config.label,
                    pct(e.wrong_share()),
                    e.vertex_max,
                    e.color_mean()
                ))
            })
            .collect();
        if !parts.is_empty() {
            let _ = writeln!(
                s,
                "- **{what}** (`{reference}`: {} wrong, vertices {:.3} px, colour mean {:.3}): {}.",
                pct(de.wrong_share()),
                de.vertex_max,
                de.color_mean(),
                parts.join("; ")
            );
        }
    };
    let knob_line =
        |s: &mut String, what: &str, labels: &[&str]| knob_against(s, what, labels, DEFAULT);
    knob_line(s, "Sub-pixel bits", &["bits0", "bits2", "bits4", "bits8"]);
    knob_line(
        s,
        "Sine table (with 16 entries or fewer the model matrix is too far from a rotation for \
         lighting in model space, so the vertices are lit in world space)",
        &["table4", "table16", "table64", "table1024"],
    );
    knob_line(
        s,
        "Perspective-correct interpolation (through the fused wrapping loop: for a colour \
         shader's triangle its values over w and 1/w as planes, one 32-bit division per pixel \
         that passes the depth test; otherwise 1/w and two barycentrics over w, two divisions)",
        &["perspective"],
    );
    knob_line(
        s,
        "Divide method (x86-64 divides in hardware, so a division-free method cannot be cheaper \
         here; Newton is for cores without a divide instruction, such as the Cortex-M0+)",
        &["reciprocal", "newton"],
    );
    knob_line(
        s,
        "Span starts (the general span engine, as against the default's fused wrapping loop)",
        &["exact-spans", "gradient"],
    );
    knob_against(
        s,
        "Interpolation bits (a knob of the general engine's exact span starts; the wrapping \
         planes always carry 16 bits)",
        &["frac12", "frac8", "frac4"],
        "exact-spans",
    );
    let _ = writeln!(s);
    conclusion(s, sweep);
}

/// The closing argument, each clause only when its numbers are there.
fn conclusion(s: &mut String, sweep: &Sweep) {
    let rows = &sweep.rows;
    let find = |label: &str| rows.iter().find(|r| r.config.label == label);
    let m1 = |label: &str| find(label).and_then(|r| r.errors.first()?.as_ref().ok().copied());
    let c = |label: &str| find(label).and_then(cost);
    let Some(d) = m1(DEFAULT) else { return };
    let mut parts = Vec::new();
    if let (Some(f), Some(e8)) = (m1("f32"), m1("24.8")) {
        let mut p = format!(
            "16.16 puts M1's vertices within {:.3} px, as f32 does ({:.3} px), where 24.8 is off by \
             up to {:.3} px",
            d.vertex_max, f.vertex_max, e8.vertex_max
        );
        if let (Some(dc), Some(fc)) = (c(DEFAULT), c("f32")) {
            let _ = write!(
                p,
                ", in integer arithmetic only ({} of f32's instructions on x86-64, which has an \
                 FPU)",
                pct(dc / fc)
            );
        }
        if let Some(b) = sweep.breakdown.iter().find(|b| b.label == "8.24") {
            if let Some((v, _)) = &b.scale_up.bad {
                let _ = write!(
                    p,
                    "; 8.24 is as accurate but its range (±128) gives out at a scene scale of {}",
                    scale_fmt(*v)
                );
            }
        }
        parts.push(p);
    }
    if let (Some(b2), Some(b4), Some(b8)) = (m1("bits2"), m1("bits4"), m1("bits8")) {
        let mut p = format!(
            "sub-pixel bits decide how many edge pixels differ: {} of M1's pixels with 2 bits, {} \
             with 4, {} with 6 (the default), {} with 8",
            pct(b2.differing_share()),
            pct(b4.differing_share()),
            pct(d.differing_share()),
            pct(b8.differing_share())
        );
        if let (Some(dc), Some(c4), Some(c8)) = (c(DEFAULT), c("bits4"), c("bits8")) {
            let _ = write!(
                p,
                " (4 bits: {} instructions, 8 bits: {}): 6 bits are the default because they \
                 take most of what 8 bits give for no measurable cost over 4, and leave \
                 coordinates two bits more headroom than 8 (26.6 holds the ±2^21-pixel guard band \
                 in 27 bits, edge products in 56)",
                signed_pct(c4, dc),
                signed_pct(c8, dc)
            );
        }
        parts.push(p);
    }
    if let (Some(t64), Some(t1024)) = (m1("table64"), m1("table1024")) {
        parts.push(format!(
            "the sine table costs flash, not work per frame, as long as the rotation it builds \
             is close enough to one for lighting in model space: 256 entries (1 KiB) give the vertices of 1,024 entries \
             ({:.4} against {:.4} px), 64 entries (256 bytes) {:.4} px, 16 entries {}",
            d.vertex_max,
            t1024.vertex_max,
            t64.vertex_max,
            m1("table16").map_or("-".into(), |e| format!("{:.4} px", e.vertex_max))
        ));
    }
    if let Some(p) = m1("perspective") {
        let mut t = format!(
            "perspective-correct interpolation lowers M1's mean colour error from {:.3} to {:.3} \
             steps",
            d.color_mean(),
            p.color_mean()
        );
        if let (Some(dc), Some(pc)) = (c(DEFAULT), c("perspective")) {
            let _ = write!(t, " for {} instructions", signed_pct(pc, dc));
        }
        t.push_str(
            ", so it stays a choice for scenes with large triangles near the eye (the \
                    random scenes) rather than the default",
        );
        parts.push(t);
    }
    if !parts.is_empty() {
        let _ = writeln!(s, "In short: {}.\n", parts.join("; "));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_and_numbers() {
        assert_eq!(civil(0), (1970, 1, 1));
        assert_eq!(civil(20_775), (2026, 11, 18));
        assert_eq!(thousands(6_942_538), "6,942,538");
        assert_eq!(thousands(968), "968");
        assert_eq!(scale_fmt(256.0), "2^8");
        assert_eq!(scale_fmt(0.25), "2^-2");
    }

    /// The rows of `group`'s error table in the committed report.
    fn section<'d>(doc: &'d str, group: &str) -> &'d str {
        let start = doc
            .find(&format!("### {group} ("))
            .unwrap_or_else(|| panic!("docs/ACCURACY.md has no {group} table"));
        let rest = &doc[start..];
        let end = rest[4..].find("\n#").map_or(rest.len(), |e| e + 4);
        &rest[..end]
    }

    /// The committed report's headline and its M1 and M2 rows of the default and the
    /// perspective-correct configurations, recomputed from the code now (the errors only: the
    /// instruction counts need callgrind and a release build, and M3, the random scenes and the
    /// limit sweeps are minutes of work in a debug build). A change that moves these figures
    /// fails here until the report is regenerated, so the report cannot drift from the code.
    #[test]
    fn report_headline_matches_the_code() {
        use crate::accuracy::{config, load, m1, scene};
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/ACCURACY.md");
        let doc = std::fs::read_to_string(path).unwrap();
        let dirs = scene::default_model_dirs();
        let m2 = load(&dirs, "M2", "stanford-bunny-res3.obj", true).unwrap();
        let registry = config::registry();
        for (group, def) in [("M1", m1(&dirs).unwrap()), ("M2", m2)] {
            let prepared = scene::Prepared::new(def, true);
            let table = section(&doc, group);
            for label in [DEFAULT, "perspective"] {
                let c = registry.iter().find(|c| c.label == label).unwrap();
                let e = (c.measure)(&prepared).unwrap();
                let row = error_row(label, &e);
                assert!(
                    table.lines().any(|l| l == row),
                    "docs/ACCURACY.md's {group} row of {label} is not what the code measures \
                     now ({row}); regenerate the report"
                );
                if group == "M1" && label == DEFAULT {
                    let headline = default_headline(&e);
                    assert!(
                        doc.contains(&headline),
                        "docs/ACCURACY.md's headline is not what the code measures now:\n\
                         {headline}\nregenerate the report"
                    );
                }
            }
        }
    }
}
