//! The tables of BENCHMARKS.md and README.md, made from the figures of record.
//!
//! `scripts/figures.sh` prints one figure per line, `scene<TAB>renderer<TAB>metric<TAB>value`, and
//! its output is committed as `docs/figures.tsv`. This module reads that file and writes every
//! table of figures in the two documents between marker comments
//! (`<!-- figures:NAME -->` ... `<!-- /figures -->`), so that no table can be edited by hand and
//! drift from what the code measures: a test checks that the committed documents equal what is
//! made here from the committed file. Run it with
//! `cargo run -p host-tools --example figures_tables -- docs/figures.tsv`.

use std::fmt::Write as _;
use std::path::Path;

/// The lines shared/bench/WORKLOADS.md's "Figures of record" requires, and the parts of the
/// banded RAM figure.
pub const REQUIRED: &[(&str, &str, &str)] = &[
    ("L1", "ours", "instructions"),
    ("L1", "ours", "per_primitive"),
    ("T1", "ours", "instructions"),
    ("T1", "ours", "per_primitive"),
    ("T2", "ours", "instructions"),
    ("T2", "ours", "per_primitive"),
    ("G1", "ours", "instructions"),
    ("G1", "ours", "per_primitive"),
    ("P1", "ours", "instructions"),
    ("P1", "ours", "per_primitive"),
    ("L1", "eg", "instructions"),
    ("L1", "eg", "per_primitive"),
    ("T1", "eg", "instructions"),
    ("T1", "eg", "per_primitive"),
    ("T2", "eg", "instructions"),
    ("T2", "eg", "per_primitive"),
    ("LIMIT", "limit", "instructions"),
    ("LIMIT", "limit", "pixels"),
    ("T2", "ours", "pixels"),
    ("T2", "ours", "limit_share"),
    ("M1", "ours", "instructions"),
    ("M1", "ours", "per_primitive"),
    ("M2", "ours", "instructions"),
    ("M2", "ours", "per_primitive"),
    ("M3", "ours", "instructions"),
    ("M3", "ours", "per_primitive"),
    ("M4", "ours", "instructions"),
    ("M4", "ours", "per_primitive"),
    ("M4", "ours-untextured", "instructions"),
    ("M4", "ours-untextured", "per_primitive"),
    ("M1", "euc", "instructions"),
    ("M1", "euc", "per_primitive"),
    ("M2", "euc", "instructions"),
    ("M2", "euc", "per_primitive"),
    ("M3", "euc", "instructions"),
    ("M3", "euc", "per_primitive"),
    ("M1", "ours-phong", "instructions"),
    ("M1", "ours-phong", "per_primitive"),
    ("M1", "ours-matcap", "instructions"),
    ("M1", "ours-matcap", "per_primitive"),
    ("M1", "ours-aa", "instructions"),
    ("M1", "ours-aa", "per_primitive"),
    ("M1", "ours-perspective", "instructions"),
    ("M1", "ours-perspective", "per_primitive"),
    ("M1", "ours-band16", "instructions"),
    ("M1", "ours-band16", "per_primitive"),
    ("M1", "ours-band16", "ram_bytes"),
    ("M1", "ours-band16", "band_bytes"),
    ("M1", "ours-band16", "band_depth_bytes"),
    ("M1", "ours-band16", "bins_bytes"),
    ("M1", "ours-band16", "scratch_bytes"),
    ("M1", "ours-band16", "stack_bytes"),
    ("M1", "ours", "text_bytes"),
    ("M1", "ours", "div64"),
    ("M2", "ours", "div64"),
    ("M4", "ours", "div64"),
    ("G1", "ours", "div64"),
    ("M1", "ours", "mul64"),
    ("M2", "ours", "mul64"),
    ("M4", "ours", "mul64"),
    ("G1", "ours", "mul64"),
    ("S1", "ours", "instructions"),
    ("S1", "ours-band16", "instructions"),
    ("S1", "ours-band16x2", "instructions"),
    ("S1", "ours-region", "instructions"),
    ("S1", "ours-region", "pixels"),
    ("S1", "ours-band16", "ram_bytes"),
    ("S1", "ours-band16x2", "ram_bytes"),
    ("S1", "ours-band16", "text_bytes"),
    ("I1", "ours", "instructions"),
    ("I1", "ours", "per_primitive"),
    ("I1", "ours", "pixels"),
    ("I1id", "ours", "instructions"),
    ("I1id", "ours", "per_primitive"),
    ("I1id", "eg", "instructions"),
    ("I1id", "eg", "per_primitive"),
];

/// The order of renderers in the tables: the default first, then the same pipeline without its
/// vertex scratch, the other shading models, and the bands by rows.
const ORDER: &[&str] = &[
    "ours",
    "ours-m1_noscratch",
    "ours-m1_unlit",
    "ours-m1_flat",
    "ours-phong",
    "ours-matcap",
    "ours-aa",
    "ours-m1_wireframe",
    "ours-m1_band8",
    "ours-band16",
    "ours-m1_band16_noscratch",
    "ours-m1_band32",
    "ours-m1_band240",
];

/// Metrics of [`REQUIRED`] that may be zero (a configuration without a vertex scratch has none).
const MAY_BE_ZERO: &[&str] = &[
    "scratch_bytes",
    "band_depth_bytes",
    "bins_bytes",
    "div64",
    "mul64",
];

/// The documents whose tables are generated, relative to the repository root.
pub const DOCUMENTS: &[&str] = &["BENCHMARKS.md", "README.md"];

/// The command that regenerates the tables, for messages.
pub const REGENERATE: &str = "cargo run -p host-tools --example figures_tables -- docs/figures.tsv";

/// The targets the issues set, shown beside the figures (not measurements).
mod target {
    /// Instructions per primitive, 2D scenes.
    pub const PER_PRIMITIVE_2D: &[(&str, f64)] = &[("L1", 1300.0), ("T1", 450.0), ("G1", 1000.0)];
    /// T2's share of LIMIT.
    pub const T2_LIMIT_SHARE: f64 = 0.30;
    /// Instructions per mesh triangle, the default configuration (`ours`).
    pub const M1_PER_TRIANGLE: f64 = 1300.0;
    /// The same for M2.
    pub const M2_PER_TRIANGLE: f64 = 650.0;
    /// The same for M3.
    pub const M3_PER_TRIANGLE: f64 = 450.0;
    /// Phong-lit M1, per triangle.
    pub const PHONG_PER_TRIANGLE: f64 = 4000.0;
    /// A 16-row banded frame against the whole frame drawn the same way.
    pub const BAND16_RATIO: f64 = 1.20;
    /// S1 in 16-row bands against the whole frame drawn directly.
    pub const S1_BAND16_RATIO: f64 = 1.25;
    /// All the RAM of S1 in 16-row bands besides mesh and font data, one band buffer and two.
    pub const S1_RAM: f64 = 36864.0;
    /// The same, double-buffered.
    pub const S1_RAM_DOUBLE: f64 = 49152.0;
    /// S1's region redraw after Suzanne turns, against the whole frame.
    pub const S1_REGION_RATIO: f64 = 0.6;
    /// All the RAM of M1 in 16-row bands, and the `.text` of the M1 link check, in bytes.
    pub const BAND16_RAM: f64 = 32768.0;
    /// The `.text` of the no_std link check built with the M1 configuration.
    pub const TEXT: f64 = 32768.0;
    /// M4 (textured) against the same scene drawn untextured, per frame.
    pub const M4_RATIO: f64 = 1.30;
    /// M1 with perspective-correct colours against the default, per frame.
    pub const PERSPECTIVE_RATIO: f64 = 1.30;
    /// M1 with MatCap shading per vertex against the default (Gouraud), per frame.
    pub const MATCAP_RATIO: f64 = 0.85;
    /// M1 with anti-aliased silhouettes against the default, per frame.
    pub const AA_RATIO: f64 = 1.25;
    /// 64-bit divisions in one M1 frame.
    pub const M1_DIV64: f64 = 700.0;
    /// 64-bit divisions in one M4 frame.
    pub const M4_DIV64: f64 = 6000.0;
}

/// One figure.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// A scene of WORKLOADS.md (`L1`, `M1`, ...) or `LIMIT`.
    pub scene: String,
    /// `ours`, `eg`, `euc`, `limit`, `ours-COMBINATION`, or `A/B` for a comparison.
    pub renderer: String,
    /// What is measured (`instructions`, `per_primitive`, ...).
    pub metric: String,
    /// The value.
    pub value: f64,
}

/// The figures of one run of `scripts/figures.sh`, in their order.
#[derive(Debug, Clone, Default)]
pub struct Figures {
    rows: Vec<Figure>,
}

impl Figures {
    /// Reads the tab-separated lines; an error names the line and what is wrong with it.
    pub fn parse(text: &str) -> Result<Self, String> {
        let mut rows: Vec<Figure> = Vec::new();
        for (i, line) in text.lines().enumerate() {
            let n = i + 1;
            let fields: Vec<&str> = line.split('\t').collect();
            let [scene, renderer, metric, value] = fields[..] else {
                return Err(format!(
                    "line {n}: expected 4 tab-separated fields, found {}: {line:?}",
                    fields.len()
                ));
            };
            if [scene, renderer, metric].iter().any(|f| f.is_empty()) {
                return Err(format!("line {n}: an empty field: {line:?}"));
            }
            let plain = !value.is_empty()
                && value.bytes().all(|b| b.is_ascii_digit() || b == b'.')
                && value.matches('.').count() <= 1
                && !value.starts_with('.')
                && !value.ends_with('.');
            let parsed = value.parse::<f64>();
            let Some(value) = parsed.ok().filter(|_| plain) else {
                return Err(format!("line {n}: not a plain number: {value:?}"));
            };
            if rows
                .iter()
                .any(|r| r.scene == scene && r.renderer == renderer && r.metric == metric)
            {
                return Err(format!("line {n}: {scene} {renderer} {metric} given twice"));
            }
            rows.push(Figure {
                scene: scene.to_string(),
                renderer: renderer.to_string(),
                metric: metric.to_string(),
                value,
            });
        }
        Ok(Self { rows })
    }

    /// The value of one figure.
    pub fn get(&self, scene: &str, renderer: &str, metric: &str) -> Option<f64> {
        self.rows
            .iter()
            .find(|r| r.scene == scene && r.renderer == renderer && r.metric == metric)
            .map(|r| r.value)
    }

    /// Every figure, in file order.
    pub fn rows(&self) -> &[Figure] {
        &self.rows
    }

    /// The renderers with figures on `scene`, comparisons (`A/B`) left out: the default, its
    /// variants and the bands first in a fixed order, then the others in file order, euc last.
    pub fn renderers(&self, scene: &str) -> Vec<&str> {
        let mut out: Vec<&str> = Vec::new();
        for r in self.rows.iter().filter(|r| r.scene == scene) {
            if !r.renderer.contains('/') && !out.contains(&r.renderer.as_str()) {
                out.push(&r.renderer);
            }
        }
        let rank = |r: &str| match ORDER.iter().position(|o| *o == r) {
            Some(i) => i,
            None if r == "euc" => ORDER.len() + 1,
            None => ORDER.len(),
        };
        // A stable sort keeps file order within a rank.
        out.sort_by_key(|r| rank(r));
        out
    }

    /// The required lines that are missing, or zero where they cannot be.
    pub fn missing_required(&self) -> Vec<String> {
        REQUIRED
            .iter()
            .filter_map(|&(s, r, m)| match self.get(s, r, m) {
                None => Some(format!("{s}\t{r}\t{m} (missing)")),
                Some(v) if v <= 0.0 && !MAY_BE_ZERO.contains(&m) => {
                    Some(format!("{s}\t{r}\t{m} (zero)"))
                }
                Some(_) => None,
            })
            .collect()
    }
}

// --- Number formats ---

/// Rounded to an integer, with thousands separators: `6,587,921`.
fn int(v: f64) -> String {
    let digits = format!("{:.0}", v.abs());
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    if v < 0.0 && digits != "0" {
        out.insert(0, '-');
    }
    out
}

/// `decimals` places.
fn dec(v: f64, decimals: usize) -> String {
    format!("{v:.decimals$}")
}

/// A fraction as a percentage with one decimal: `21.8 %`.
fn pct(v: f64) -> String {
    format!("{:.1} %", 100.0 * v)
}

/// A value, or `-` when the figure is missing.
fn or_dash(v: Option<f64>, f: impl Fn(f64) -> String) -> String {
    v.map_or_else(|| "-".to_string(), f)
}

/// `a / b` when both exist and `b` is not zero.
fn ratio(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) if b != 0.0 => Some(a / b),
        _ => None,
    }
}

/// A markdown table.
struct Table {
    text: String,
}

impl Table {
    /// `align`: one of `l` (left) or `r` (right) per column.
    fn new(header: &[&str], align: &str) -> Self {
        let mut text = format!("| {} |\n|", header.join(" | "));
        for a in align.chars() {
            text.push_str(if a == 'r' { "---:|" } else { "---|" });
        }
        text.push('\n');
        Self { text }
    }

    fn row<S: AsRef<str>>(&mut self, cells: &[S]) {
        let cells: Vec<&str> = cells.iter().map(AsRef::as_ref).collect();
        let _ = writeln!(self.text, "| {} |", cells.join(" | "));
    }

    fn done(self) -> String {
        self.text
    }
}

// --- What the renderers are ---

/// The mesh scenes' short names.
fn scene_name(scene: &str) -> &'static str {
    match scene {
        "M1" => "Suzanne",
        "M2" => "Stanford bunny res3",
        "M3" => "Stanford bunny",
        "M4" => "Spot, textured",
        _ => "",
    }
}

/// What a 3D renderer name draws: shading, depth, culling, call. `ours-band16` is described by
/// [`band16_label`], from its figures.
fn describe(renderer: &str) -> Option<[&'static str; 4]> {
    Some(match renderer {
        "ours" => ["Gouraud", "buffer", "clockwise", "`draw`"],
        "ours-phong" => ["Phong", "buffer", "clockwise", "`draw`"],
        "ours-m1_noscratch" => ["Gouraud", "buffer", "clockwise", "`draw`, no scratch"],
        "ours-m1_nodepth" => ["Gouraud", "none", "clockwise", "`draw`"],
        "ours-m1_nocull" => ["Gouraud", "buffer", "none", "`draw`"],
        "ours-m1_unlit" => ["unlit", "buffer", "clockwise", "`draw`"],
        "ours-m1_flat" => ["flat", "buffer", "clockwise", "`draw`"],
        "ours-m1_unlit_nodepth_nocull" => ["unlit", "none", "none", "`draw`"],
        "ours-m1_wireframe" => ["wireframe", "none", "clockwise", "`draw_wireframe`"],
        "ours-m1_depth_always" => ["Gouraud", "buffer, `Always`", "clockwise", "`draw`"],
        "ours-m1_cull_keepall" => ["Gouraud", "buffer", "run-time keep-all", "`draw`"],
        "euc" => ["Gouraud (`f32`)", "`f32` buffer", "back faces", "euc 0.5.3"],
        _ => return None,
    })
}

/// The band rows of a banded renderer name (`ours-m1_band8` is 8, `ours-band16` 16).
fn band_rows(renderer: &str) -> Option<u32> {
    if renderer == "ours-band16" {
        return Some(16);
    }
    let rest = renderer.strip_prefix("ours-m1_band")?;
    rest.split('_').next()?.parse().ok()
}

/// Whether a banded renderer has a vertex scratch: all but those named `_noscratch` (for
/// `ours-band16`, whose combination `scripts/figures.sh` chooses, its measured scratch says).
fn band_scratch(f: &Figures, renderer: &str) -> bool {
    if renderer == "ours-band16" {
        return f
            .get("M1", renderer, "scratch_bytes")
            .is_none_or(|b| b > 0.0);
    }
    !renderer.ends_with("_noscratch")
}

fn band16_label(f: &Figures) -> &'static str {
    if band_scratch(f, "ours-band16") {
        "16-row bands"
    } else {
        "16-row bands, no vertex scratch"
    }
}

/// The short label of a renderer in the 3D tables.
fn label(f: &Figures, renderer: &str) -> String {
    match renderer {
        "ours-band16" => format!("`ours-band16` ({})", band16_label(f)),
        "euc" => "**euc**".to_string(),
        r => format!("`{r}`"),
    }
}

// --- The tables ---

fn speed_2d(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "scene",
            "primitives",
            "ours instr / frame",
            "**ours instr / primitive**",
            "embedded-graphics instr / primitive",
            "ours / eg",
            "target (ours)",
            "met?",
        ],
        "lrrrrrll",
    );
    for scene in ["L1", "T1", "T2", "G1", "P1", "I1", "I1id"] {
        let ours = f.get(scene, "ours", "per_primitive");
        let target = target::PER_PRIMITIVE_2D
            .iter()
            .find(|t| t.0 == scene)
            .map(|t| t.1);
        let met = match (ours, target) {
            (Some(o), Some(t)) if o <= t => "yes".to_string(),
            (Some(o), Some(t)) => format!("no ({:.1}x over)", o / t),
            _ => "-".to_string(),
        };
        t.row(&[
            scene.to_string(),
            or_dash(f.get(scene, "ours", "primitives"), int),
            or_dash(f.get(scene, "ours", "instructions"), int),
            or_dash(ours, |v| format!("**{}**", int(v))),
            f.get(scene, "eg", "per_primitive")
                .map_or_else(|| "n/a".to_string(), int),
            or_dash(f.get(scene, "ours/eg", "ratio"), |v| dec(v, 2)),
            target.map_or_else(|| "-".to_string(), |t| format!("<= {}", int(t))),
            met,
        ]);
    }
    t.row(&[
        "LIMIT (one `slice.fill`)".to_string(),
        or_dash(f.get("LIMIT", "limit", "pixels"), |v| {
            format!("{} px", int(v))
        }),
        or_dash(f.get("LIMIT", "limit", "instructions"), int),
        String::new(),
        String::new(),
        String::new(),
        String::new(),
        String::new(),
    ]);
    t.done()
}

fn fill_rate(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "renderer",
            "T2 pixels / frame",
            "T2 instr / frame",
            "px / instr",
            "LIMIT px / instr",
            "share of LIMIT",
            "target",
        ],
        "lrrrrrl",
    );
    let limit = ratio(
        f.get("LIMIT", "limit", "pixels"),
        f.get("LIMIT", "limit", "instructions"),
    );
    for (r, name) in [("ours", "ours"), ("eg", "embedded-graphics")] {
        let share = f.get("T2", r, "limit_share");
        let target = if r == "ours" {
            match share {
                Some(s) if s >= target::T2_LIMIT_SHARE => {
                    format!(">= {} (met)", pct(target::T2_LIMIT_SHARE))
                }
                Some(_) => format!(">= {} (not met)", pct(target::T2_LIMIT_SHARE)),
                None => "-".to_string(),
            }
        } else {
            String::new()
        };
        t.row(&[
            name.to_string(),
            or_dash(f.get("T2", r, "pixels"), int),
            or_dash(f.get("T2", r, "instructions"), int),
            or_dash(
                ratio(f.get("T2", r, "pixels"), f.get("T2", r, "instructions")),
                |v| dec(v, 3),
            ),
            or_dash(limit, |v| dec(v, 3)),
            or_dash(share, |v| {
                if r == "ours" {
                    format!("**{}**", pct(v))
                } else {
                    pct(v)
                }
            }),
            target,
        ]);
    }
    t.done()
}

fn pixels_2d(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "scene",
            "renderer",
            "pixels / frame",
            "pixels / primitive",
            "spans / frame",
            "pixels / span",
        ],
        "llrrrr",
    );
    for scene in ["L1", "T1", "T2", "G1", "P1"] {
        for (r, name) in [("ours", "ours"), ("eg", "embedded-graphics")] {
            let px = f.get(scene, r, "pixels");
            if px.is_none() {
                continue;
            }
            let spans = f.get(scene, r, "spans");
            t.row(&[
                scene.to_string(),
                name.to_string(),
                or_dash(px, int),
                or_dash(ratio(px, f.get(scene, r, "primitives")), |v| {
                    if v >= 1000.0 {
                        int(v)
                    } else {
                        dec(v, 1)
                    }
                }),
                or_dash(spans, int),
                or_dash(ratio(px, spans), |v| dec(v, 1)),
            ]);
        }
    }
    t.done()
}

/// M1's whole-frame renderers (not banded, not euc).
fn m1_combinations(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "renderer",
            "shading",
            "depth",
            "cull",
            "call",
            "instructions / frame",
            "per triangle",
            "drawn",
            "culled",
            "per drawn triangle",
            "vs `ours`",
        ],
        "lllllrrrrrr",
    );
    let base = f.get("M1", "ours", "instructions");
    for r in f.renderers("M1") {
        if r == "euc" || band_rows(r).is_some() || f.get("M1", r, "instructions").is_none() {
            continue;
        }
        let d = describe(r).unwrap_or(["", "", "", ""]);
        let n = f.get("M1", r, "instructions");
        let per = f.get("M1", r, "per_primitive");
        t.row(&[
            label(f, r),
            d[0].to_string(),
            d[1].to_string(),
            d[2].to_string(),
            d[3].to_string(),
            or_dash(n, int),
            or_dash(per, |v| {
                if r == "ours" {
                    format!("**{}**", int(v))
                } else {
                    int(v)
                }
            }),
            or_dash(f.get("M1", r, "drawn"), int),
            or_dash(f.get("M1", r, "culled"), int),
            or_dash(f.get("M1", r, "per_drawn"), int),
            or_dash(ratio(n, base), |v| dec(v, 3)),
        ]);
    }
    t.done()
}

fn controls(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "stage",
            "off (zero-sized)",
            "instructions",
            "present, doing nothing",
            "instructions",
            "saved",
            "holds?",
        ],
        "llrlrrl",
    );
    for (what, off, on) in [
        ("depth", "ours-m1_nodepth", "ours-m1_depth_always"),
        ("culling", "ours-m1_nocull", "ours-m1_cull_keepall"),
    ] {
        let (a, b) = (
            f.get("M1", off, "instructions"),
            f.get("M1", on, "instructions"),
        );
        let (saved, holds) = match (a, b) {
            (Some(a), Some(b)) => (
                pct((b - a) / b),
                if a <= b { "yes" } else { "**no**" }.to_string(),
            ),
            _ => ("-".to_string(), "-".to_string()),
        };
        t.row(&[
            what.to_string(),
            format!("`{off}`"),
            or_dash(a, int),
            format!("`{on}`"),
            or_dash(b, int),
            saved,
            holds,
        ]);
    }
    t.done()
}

fn m1_bands(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "renderer",
            "band rows",
            "vertex scratch",
            "instructions / frame",
            "per triangle",
            "vs the whole frame drawn the same way",
            "band colour + depth",
        ],
        "lrlrrrr",
    );
    let whole = f.get("M1", "ours", "instructions");
    let whole_noscratch = f.get("M1", "ours-m1_noscratch", "instructions");
    for r in f.renderers("M1") {
        let Some(rows) = band_rows(r) else { continue };
        let cached = band_scratch(f, r);
        let n = f.get("M1", r, "instructions");
        let (reference, name) = if cached {
            (whole, "`ours`")
        } else {
            (whole_noscratch, "`ours-m1_noscratch`")
        };
        let vs = ratio(n, reference).map_or_else(
            || "-".to_string(),
            |v| {
                let verdict = if rows == 16 {
                    if v <= target::BAND16_RATIO {
                        " (target met)"
                    } else {
                        " (target not met)"
                    }
                } else {
                    ""
                };
                format!("{} of {name}{verdict}", dec(v, 3))
            },
        );
        // Two Rgb565 / u16 buffers of the band: a property of the type, not a measurement.
        let bytes = 2 * 2 * 320 * rows;
        t.row(&[
            label(f, r),
            rows.to_string(),
            if cached { "yes" } else { "no" }.to_string(),
            or_dash(n, int),
            or_dash(f.get("M1", r, "per_primitive"), int),
            vs,
            format!("{} B", int(f64::from(bytes))),
        ]);
    }
    for (r, what) in [
        ("ours", "whole frame"),
        ("ours-m1_noscratch", "whole frame, no vertex scratch"),
    ] {
        if let Some(n) = f.get("M1", r, "instructions") {
            t.row(&[
                format!("`{r}` ({what})"),
                "240".to_string(),
                if r == "ours" { "yes" } else { "no" }.to_string(),
                int(n),
                or_dash(f.get("M1", r, "per_primitive"), int),
                "1.000".to_string(),
                "-".to_string(),
            ]);
        }
    }
    t.done()
}

/// Bytes, or `-` for none.
fn bytes(v: Option<f64>) -> String {
    match v {
        Some(b) if b > 0.0 => int(b),
        Some(_) => "-".to_string(),
        None => "?".to_string(),
    }
}

fn m1_memory(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "renderer",
            "call",
            "depth buffer",
            "band colour + depth",
            "bins (binned triangles)",
            "vertex scratch",
            "peak stack",
            "**RAM**",
            "framebuffer (the output)",
            "`Pipeline` value",
            ".text",
            ".text (Cortex-M4F)",
            ".rodata",
        ],
        "llrrrrrrrrrrr",
    );
    for r in f.renderers("M1") {
        let g = |m: &str| f.get("M1", r, m);
        if g("ram_bytes").is_none() {
            continue;
        }
        let call = match (band_rows(r), g("scratch_bytes").is_some_and(|b| b > 0.0)) {
            (Some(rows), true) => format!("`draw_banded`, {rows} rows"),
            (Some(rows), false) => format!("`draw_banded`, {rows} rows, no scratch"),
            (None, true) => "`draw`".to_string(),
            (None, false) => "`draw`, no scratch".to_string(),
        };
        let band = match (g("band_bytes"), g("band_depth_bytes")) {
            (Some(c), Some(z)) if c > 0.0 => format!("{} + {}", int(c), int(z)),
            _ => "-".to_string(),
        };
        let bins = match (g("bins_bytes"), g("binned_triangles")) {
            (Some(b), Some(n)) if b > 0.0 => format!("{} ({})", int(b), int(n)),
            _ => "-".to_string(),
        };
        t.row(&[
            format!("`{r}`"),
            call,
            bytes(g("depth_bytes")),
            band,
            bins,
            bytes(g("scratch_bytes")),
            bytes(g("stack_bytes")),
            format!("**{}**", bytes(g("ram_bytes"))),
            bytes(g("framebuffer_bytes")),
            bytes(g("pipeline_bytes")),
            bytes(g("text_bytes")),
            bytes(g("text_bytes_thumbv7em")),
            bytes(g("rodata_bytes")),
        ]);
    }
    t.done()
}

/// The mesh scenes in the file, in order.
fn mesh_scenes(f: &Figures) -> Vec<&str> {
    let mut out: Vec<&str> = Vec::new();
    for r in &f.rows {
        if r.scene.starts_with('M') && !out.contains(&r.scene.as_str()) {
            out.push(&r.scene);
        }
    }
    out
}

fn scenes_3d(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "scene",
            "renderer",
            "shading",
            "triangles",
            "instructions / frame",
            "per triangle",
            "drawn",
            "per drawn triangle",
            "vs `ours`",
        ],
        "lllrrrrrr",
    );
    // M1's other stages are in the M1 table; here the renderers every scene has.
    let others: Vec<&str> = mesh_scenes(f).into_iter().filter(|s| *s != "M1").collect();
    for scene in mesh_scenes(f) {
        let base = f.get(scene, "ours", "instructions");
        for r in f.renderers(scene) {
            let n = f.get(scene, r, "instructions");
            if n.is_none()
                || (scene == "M1" && !others.iter().any(|s| f.get(s, r, "instructions").is_some()))
            {
                continue;
            }
            let shading = match describe(r) {
                _ if scene == "M4" => match r {
                    "ours" => "textured (nearest) x Gouraud".to_string(),
                    "ours-m4_bilinear" => "textured (bilinear) x Gouraud".to_string(),
                    "ours-untextured" => "Gouraud".to_string(),
                    _ => String::new(),
                },
                Some(d) if r == "ours-m1_noscratch" => format!("{}, no vertex scratch", d[0]),
                Some(d) => d[0].to_string(),
                None => String::new(),
            };
            let bold = |v: f64| {
                if r == "ours" || r == "euc" {
                    format!("**{}**", int(v))
                } else {
                    int(v)
                }
            };
            t.row(&[
                scene.to_string(),
                label(f, r),
                shading,
                or_dash(f.get(scene, r, "triangles"), int),
                or_dash(n, int),
                or_dash(f.get(scene, r, "per_primitive"), bold),
                or_dash(f.get(scene, r, "drawn"), int),
                or_dash(f.get(scene, r, "per_drawn"), int),
                or_dash(ratio(n, base), |v| dec(v, 3)),
            ]);
        }
    }
    t.done()
}

fn ours_vs_euc(f: &Figures, readme: bool) -> String {
    let mut t = if readme {
        Table::new(
            &[
                "scene (320x240 Rgb565, Gouraud + depth + culling)",
                "ours",
                "ours, no vertex scratch",
                "euc",
                "ours / euc",
                "no scratch / euc",
            ],
            "lrrrrr",
        )
    } else {
        Table::new(
            &[
                "scene",
                "triangles",
                "ours `draw`",
                "ours `draw`, no scratch",
                "euc",
                "ours / euc",
                "no scratch / euc",
            ],
            "lrrrrrr",
        )
    };
    for scene in mesh_scenes(f) {
        let euc = f.get(scene, "euc", "instructions");
        if euc.is_none() {
            continue;
        }
        let ours = f.get(scene, "ours", "instructions");
        let cached = f.get(scene, "ours-m1_noscratch", "instructions");
        let tris = f.get(scene, "euc", "triangles");
        let mut cells = if readme {
            vec![format!(
                "{scene}: {}, {} triangles",
                scene_name(scene),
                or_dash(tris, int)
            )]
        } else {
            vec![scene.to_string(), or_dash(tris, int)]
        };
        cells.extend([
            or_dash(ours, int),
            or_dash(cached, int),
            or_dash(euc, int),
            or_dash(f.get(scene, "ours/euc", "ratio"), |v| {
                format!("**{}**", dec(v, 2))
            }),
            or_dash(ratio(cached, euc), |v| dec(v, 2)),
        ]);
        t.row(&cells);
    }
    t.done()
}

fn same_picture(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "scene",
            "covered by ours",
            "covered by euc",
            "by both",
            "by ours only",
            "by euc only",
            "mean channel difference (8-bit steps)",
            "largest",
            "pixels more than 16 apart",
        ],
        "lrrrrrrrr",
    );
    for scene in mesh_scenes(f) {
        let g = |m: &str| f.get(scene, "ours/euc", m);
        if g("pixels_both").is_none() {
            continue;
        }
        t.row(&[
            scene.to_string(),
            or_dash(f.get(scene, "ours", "covered"), int),
            or_dash(f.get(scene, "euc", "covered"), int),
            or_dash(g("pixels_both"), int),
            or_dash(g("pixels_ours_only"), int),
            or_dash(g("pixels_euc_only"), int),
            or_dash(g("mean_channel_diff"), |v| dec(v, 2)),
            or_dash(g("max_channel_diff"), int),
            or_dash(g("pixels_over_16"), int),
        ]);
    }
    t.done()
}

/// One sentence: M1 against the per-triangle target.
fn m1_target(f: &Figures) -> String {
    let ours = f.get("M1", "ours", "per_primitive");
    let noscratch = f.get("M1", "ours-m1_noscratch", "per_primitive");
    let verdict = if ours.is_some_and(|v| v <= target::M1_PER_TRIANGLE) {
        "met"
    } else {
        "not met"
    };
    let cached = noscratch.map_or_else(String::new, |c| {
        format!(
            " (without its vertex scratch, `ours-m1_noscratch`, {})",
            int(c)
        )
    });
    format!(
        "The default configuration (`ours`) costs **{}** instructions per M1 triangle{cached}; \
         the target is {} per triangle: {verdict}.\n",
        or_dash(ours, int),
        int(target::M1_PER_TRIANGLE)
    )
}

/// The wide operations a frame executes (`div64`, `mul64`): what a Cortex-M pays library calls
/// or multiply sequences for and an x86 count shows as one instruction each.
fn wide_ops(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "scene",
            "64-bit divisions",
            "64 x 64 -> 128-bit products",
            "primitives",
        ],
        "lrrr",
    );
    for scene in ["M1", "M2", "M4", "G1"] {
        let prims = f
            .get(scene, "ours", "triangles")
            .or_else(|| f.get(scene, "ours", "primitives"));
        t.row(&[
            scene.to_string(),
            or_dash(f.get(scene, "ours", "div64"), int),
            or_dash(f.get(scene, "ours", "mul64"), int),
            or_dash(prims, int),
        ]);
    }
    t.done()
}

/// The speed and size targets of the 3D pipeline against the figures.
fn targets(f: &Figures) -> String {
    let mut t = Table::new(&["figure", "now", "target", "met?"], "lrrl");
    let verdict = |v: Option<f64>, target: f64| match v {
        Some(v) if v <= target => "yes",
        Some(_) => "no",
        None => "-",
    };
    let per = |scene: &str, r: &str| f.get(scene, r, "per_primitive");
    let rows: [(&str, Option<f64>, f64, bool); 18] = [
        (
            "M1 whole frame, per triangle",
            per("M1", "ours"),
            target::M1_PER_TRIANGLE,
            false,
        ),
        (
            "M2 whole frame, per triangle",
            per("M2", "ours"),
            target::M2_PER_TRIANGLE,
            false,
        ),
        (
            "M3 whole frame, per triangle",
            per("M3", "ours"),
            target::M3_PER_TRIANGLE,
            false,
        ),
        (
            "M1 Phong, per triangle",
            per("M1", "ours-phong"),
            target::PHONG_PER_TRIANGLE,
            false,
        ),
        (
            "M4 textured, against the same scene untextured (per frame)",
            f.get("M4", "ours/ours-untextured", "ratio"),
            target::M4_RATIO,
            true,
        ),
        (
            "M1 perspective-correct, against the default (per frame)",
            f.get("M1", "ours-perspective/ours", "ratio"),
            target::PERSPECTIVE_RATIO,
            true,
        ),
        (
            "M1 MatCap per vertex, against the default (Gouraud, per frame)",
            f.get("M1", "ours-matcap/ours", "ratio"),
            target::MATCAP_RATIO,
            true,
        ),
        (
            "M1 with anti-aliased silhouettes, against the default (per frame)",
            f.get("M1", "ours-aa/ours", "ratio"),
            target::AA_RATIO,
            true,
        ),
        (
            "M1 in 16-row bands, against the whole frame",
            ratio(
                f.get("M1", "ours-band16", "instructions"),
                f.get("M1", "ours", "instructions"),
            ),
            target::BAND16_RATIO,
            true,
        ),
        (
            "M1 in 16-row bands, all RAM (bytes)",
            f.get("M1", "ours-band16", "ram_bytes"),
            target::BAND16_RAM,
            false,
        ),
        (
            "`.text` of the no_std check, M1 configuration (bytes)",
            f.get("M1", "ours", "text_bytes"),
            target::TEXT,
            false,
        ),
        (
            "the same built for a Cortex-M4F (`thumbv7em-none-eabihf`): the flash it needs (bytes)",
            f.get("M1", "ours", "text_bytes_thumbv7em"),
            target::TEXT,
            false,
        ),
        (
            "64-bit divisions in an M1 frame (all of the vertex, set-up, span and pixel work; not `Fx`'s square root and quotient, used off the lighting plan and when clipping)",
            f.get("M1", "ours", "div64"),
            target::M1_DIV64,
            false,
        ),
        (
            "64-bit divisions in an M4 frame (the same)",
            f.get("M4", "ours", "div64"),
            target::M4_DIV64,
            false,
        ),
        (
            "S1 (a firmware screen) in 16-row bands, against the whole frame drawn directly",
            f.get("S1", "ours-band16/ours", "ratio"),
            target::S1_BAND16_RATIO,
            true,
        ),
        (
            "S1 in 16-row bands, all RAM besides mesh and font data (bytes)",
            f.get("S1", "ours-band16", "ram_bytes"),
            target::S1_RAM,
            false,
        ),
        (
            "S1 in 16-row bands, double-buffered, the same (bytes)",
            f.get("S1", "ours-band16x2", "ram_bytes"),
            target::S1_RAM_DOUBLE,
            false,
        ),
        (
            "S1 region redraw after Suzanne turns 5 degrees, against the whole frame",
            f.get("S1", "ours-region/ours", "ratio"),
            target::S1_REGION_RATIO,
            true,
        ),
    ];
    for (what, now, target, fraction) in rows {
        let show = |v: f64| if fraction { dec(v, 3) } else { int(v) };
        t.row(&[
            what.to_string(),
            or_dash(now, show),
            show(target),
            verdict(now, target).to_string(),
        ]);
    }
    t.done()
}

/// Workload S1 (a firmware screen through the frame list): each way of drawing it.
fn s1(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "S1 drawn",
            "instructions",
            "against the whole frame",
            "RAM (bytes)",
            "of it: bands, band depth, bins, vertex scratch, stack",
        ],
        "lrrrl",
    );
    let whole = f.get("S1", "ours", "instructions");
    let rows = [
        ("whole frame, each command drawn directly", "ours"),
        ("frame list, 16-row bands, one band buffer", "ours-band16"),
        ("frame list, 16-row bands, double-buffered", "ours-band16x2"),
        (
            "frame list, region redraw after Suzanne turns 30 -> 35 degrees",
            "ours-region",
        ),
    ];
    for (what, r) in rows {
        let n = f.get("S1", r, "instructions");
        let parts = [
            "band_bytes",
            "band_depth_bytes",
            "bins_bytes",
            "scratch_bytes",
            "stack_bytes",
        ]
        .map(|m| f.get("S1", r, m));
        let parts = if parts.iter().all(Option::is_some) {
            parts.map(|p| int(p.unwrap_or(0.0))).join(" + ")
        } else {
            "-".to_string()
        };
        let what = if r == "ours-region" {
            format!("{what} ({} pixels)", or_dash(f.get("S1", r, "pixels"), int))
        } else {
            what.to_string()
        };
        t.row(&[
            what,
            or_dash(n, int),
            or_dash(ratio(n, whole), |v| dec(v, 3)),
            or_dash(f.get("S1", r, "ram_bytes"), int),
            parts,
        ]);
    }
    let mut out = t.done();
    out.push_str(&format!(
        "\n`.text` of the no_std build of S1 through the frame list (nostd-check `framelist`, opt-level s): {} bytes for x86-64, {} bytes for a Cortex-M4F (`thumbv7em-none-eabihf`).\n",
        or_dash(f.get("S1", "ours-band16", "text_bytes"), int),
        or_dash(f.get("S1", "ours-band16", "text_bytes_thumbv7em"), int)
    ));
    out
}

fn readme_speed(f: &Figures) -> String {
    let mut t = Table::new(
        &["scene (320x240 Rgb565)", "ours", "embedded-graphics"],
        "lrr",
    );
    let prims = |s: &str| or_dash(f.get(s, "ours", "primitives"), int);
    for (scene, what, unit) in [
        ("L1", "random lines", "line"),
        ("T1", "small triangles", "triangle"),
        ("G1", "small Gouraud triangles", "triangle"),
    ] {
        t.row(&[
            format!("{scene}: {} {what}, instructions per {unit}", prims(scene)),
            or_dash(f.get(scene, "ours", "per_primitive"), int),
            or_dash(f.get(scene, "eg", "per_primitive"), int),
        ]);
    }
    t.row(&[
        "T2: large triangles, fill rate as a share of LIMIT (`slice.fill`)".to_string(),
        or_dash(f.get("T2", "ours", "limit_share"), pct),
        or_dash(f.get("T2", "eg", "limit_share"), pct),
    ]);
    let with_cache = |main: Option<f64>, other: Option<f64>| {
        let extra = other.map_or_else(String::new, |c| {
            format!(" ({} without the vertex scratch)", int(c))
        });
        format!("{}{extra}", or_dash(main, int))
    };
    t.row(&[
        "M1: Suzanne, Gouraud + depth + culling, instructions per mesh triangle".to_string(),
        with_cache(
            f.get("M1", "ours", "per_primitive"),
            f.get("M1", "ours-m1_noscratch", "per_primitive"),
        ),
        "-".to_string(),
    ]);
    let band_ram = match (
        f.get("M1", "ours-band16", "band_bytes"),
        f.get("M1", "ours-band16", "band_depth_bytes"),
    ) {
        (Some(c), Some(z)) => format!(" ({} B of colour and depth)", int(c + z)),
        _ => String::new(),
    };
    let cached = band_scratch(f, "ours-band16");
    t.row(&[
        format!("M1 in 16-row bands{band_ram}, per mesh triangle"),
        if cached {
            with_cache(
                f.get("M1", "ours-band16", "per_primitive"),
                f.get("M1", "ours-m1_band16_noscratch", "per_primitive"),
            )
        } else {
            or_dash(f.get("M1", "ours-band16", "per_primitive"), int)
        },
        "-".to_string(),
    ]);
    if let Some(per) = f.get("M4", "ours", "per_primitive") {
        let against = f
            .get("M4", "ours/ours-untextured", "ratio")
            .map_or_else(String::new, |r| {
                format!(" ({}x the same scene untextured)", dec(r, 2))
            });
        t.row(&[
            "M4: Spot textured (nearest texel x Gouraud), instructions per mesh triangle"
                .to_string(),
            format!("{}{against}", int(per)),
            "-".to_string(),
        ]);
    }
    t.done()
}

fn readme_memory(f: &Figures) -> String {
    let mut t = Table::new(
        &[
            "M1",
            "RAM besides mesh and framebuffer",
            "of it peak stack",
            "code (`.text`, x86-64)",
            "code (`.text`, Cortex-M4F)",
        ],
        "lrrrr",
    );
    for (r, what) in [
        (
            "ours",
            "`draw`: whole frame, 16-bit depth buffer".to_string(),
        ),
        ("ours-band16", format!("`draw_banded`: {}", band16_label(f))),
    ] {
        let g = |m: &str| f.get("M1", r, m);
        if g("ram_bytes").is_none() {
            continue;
        }
        t.row(&[
            what,
            or_dash(g("ram_bytes"), |v| format!("{} B", int(v))),
            or_dash(g("stack_bytes"), |v| format!("{} B", int(v))),
            or_dash(g("text_bytes"), |v| format!("{} B", int(v))),
            or_dash(g("text_bytes_thumbv7em"), |v| format!("{} B", int(v))),
        ]);
    }
    t.done()
}

/// One generated block: the text between `<!-- figures:NAME -->` and `<!-- /figures -->` in
/// `file`.
#[derive(Debug, Clone)]
pub struct Block {
    /// The document, relative to the repository root.
    pub file: &'static str,
    /// The block's name in its opening marker.
    pub name: &'static str,
    /// The generated markdown.
    pub text: String,
}

/// Every generated block of [`DOCUMENTS`].
pub fn blocks(f: &Figures) -> Vec<Block> {
    let b = |file, name, text| Block { file, name, text };
    vec![
        b("BENCHMARKS.md", "speed-2d", speed_2d(f)),
        b("BENCHMARKS.md", "fill-rate", fill_rate(f)),
        b("BENCHMARKS.md", "pixels-2d", pixels_2d(f)),
        b("BENCHMARKS.md", "m1-combinations", m1_combinations(f)),
        b("BENCHMARKS.md", "m1-controls", controls(f)),
        b("BENCHMARKS.md", "m1-bands", m1_bands(f)),
        b("BENCHMARKS.md", "m1-memory", m1_memory(f)),
        b("BENCHMARKS.md", "m1-target", m1_target(f)),
        b("BENCHMARKS.md", "targets", targets(f)),
        b("BENCHMARKS.md", "wide-ops", wide_ops(f)),
        b("BENCHMARKS.md", "s1", s1(f)),
        b("BENCHMARKS.md", "scenes-3d", scenes_3d(f)),
        b("BENCHMARKS.md", "ours-vs-euc", ours_vs_euc(f, false)),
        b("BENCHMARKS.md", "same-picture", same_picture(f)),
        b("README.md", "speed", readme_speed(f)),
        b("README.md", "speed-euc", ours_vs_euc(f, true)),
        b("README.md", "memory", readme_memory(f)),
    ]
}

const OPEN: &str = "<!-- figures:";
const CLOSE: &str = "<!-- /figures -->";

/// `doc` with the text of every block of `file` put between its markers. Fails when a block has
/// no markers in `doc`, when `doc` has a marker no block fills, or when the markers do not pair.
pub fn fill(doc: &str, file: &str, blocks: &[Block]) -> Result<String, String> {
    let mut out = String::with_capacity(doc.len());
    let mut seen: Vec<&str> = Vec::new();
    let mut lines = doc.split_inclusive('\n').enumerate();
    while let Some((i, line)) = lines.next() {
        if line.trim() == CLOSE {
            return Err(format!(
                "{file}:{}: {CLOSE} without an opening marker",
                i + 1
            ));
        }
        let Some(name) = line
            .trim()
            .strip_prefix(OPEN)
            .and_then(|r| r.strip_suffix("-->"))
            .map(str::trim)
        else {
            out.push_str(line);
            continue;
        };
        let Some(block) = blocks.iter().find(|b| b.file == file && b.name == name) else {
            return Err(format!(
                "{file}:{}: no generated block is named {name:?}",
                i + 1
            ));
        };
        if seen.contains(&block.name) {
            return Err(format!("{file}:{}: block {name:?} appears twice", i + 1));
        }
        seen.push(block.name);
        out.push_str(line);
        if !line.ends_with('\n') {
            out.push('\n');
        }
        // Blank lines around the text, so that every markdown renderer ends a table before the
        // closing marker.
        out.push('\n');
        out.push_str(&block.text);
        out.push('\n');
        loop {
            match lines.next() {
                Some((_, l)) if l.trim() == CLOSE => {
                    out.push_str(l);
                    break;
                }
                Some((j, l)) if l.trim().starts_with(OPEN) => {
                    return Err(format!(
                        "{file}:{}: block {name:?} (line {}) is not closed before the next one",
                        j + 1,
                        i + 1
                    ));
                }
                Some(_) => {}
                None => return Err(format!("{file}:{}: block {name:?} is not closed", i + 1)),
            }
        }
    }
    let missing: Vec<&str> = blocks
        .iter()
        .filter(|b| b.file == file && !seen.contains(&b.name))
        .map(|b| b.name)
        .collect();
    if !missing.is_empty() {
        return Err(format!(
            "{file}: no markers for the block(s) {}",
            missing.join(", ")
        ));
    }
    Ok(out)
}

/// The documents as they should be: (file, what is on disk, what it should be), for every
/// document of [`DOCUMENTS`] under `root`. Fails when the figures lack a required line.
pub fn regenerate(root: &Path, f: &Figures) -> Result<Vec<(&'static str, String, String)>, String> {
    let missing = f.missing_required();
    if !missing.is_empty() {
        return Err(format!(
            "the figures lack lines WORKLOADS.md requires:\n  {}",
            missing.join("\n  ")
        ));
    }
    let all = blocks(f);
    DOCUMENTS
        .iter()
        .map(|&file| {
            let path = root.join(file);
            let old =
                std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            let new = fill(&old, file, &all)?;
            Ok((file, old, new))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn block(name: &'static str, text: &str) -> Block {
        Block {
            file: "X.md",
            name,
            text: text.to_string(),
        }
    }

    #[test]
    fn parse_reads_lines_and_rejects_bad_ones() {
        let f =
            Figures::parse("L1\tours\tinstructions\t20803203\nL1\tours\tper_primitive\t2080.3\n")
                .unwrap();
        assert_eq!(f.get("L1", "ours", "per_primitive"), Some(2080.3));
        assert_eq!(f.get("L1", "eg", "per_primitive"), None);
        for bad in [
            "L1\tours\tinstructions",
            "L1\tours\tinstructions\t1,000",
            "L1\tours\tinstructions\t-3",
            "L1\tours\tinstructions\t1e6",
            "L1\tours\tinstructions\t.5",
            "L1\tours\tinstructions\t",
            "L1\t\tinstructions\t5",
            "L1\tours\tinstructions\t5\nL1\tours\tinstructions\t6",
        ] {
            assert!(Figures::parse(bad).is_err(), "{bad:?} was accepted");
        }
    }

    #[test]
    fn numbers_are_formatted_for_reading() {
        assert_eq!(int(6_587_921.0), "6,587,921");
        assert_eq!(int(999.4), "999");
        assert_eq!(int(999.6), "1,000");
        assert_eq!(int(0.0), "0");
        assert_eq!(pct(0.2182), "21.8 %");
    }

    #[test]
    fn fill_replaces_between_markers_and_keeps_the_rest() {
        let doc = "a\n<!-- figures:t -->\nold\nold\n<!-- /figures -->\nb\n";
        let out = fill(doc, "X.md", &[block("t", "new\n")]).unwrap();
        assert_eq!(
            out,
            "a\n<!-- figures:t -->\n\nnew\n\n<!-- /figures -->\nb\n"
        );
        assert_eq!(fill(&out, "X.md", &[block("t", "new\n")]).unwrap(), out);
    }

    #[test]
    fn fill_rejects_unknown_missing_and_unpaired_markers() {
        let t = [block("t", "x\n")];
        assert!(fill("<!-- figures:u -->\n<!-- /figures -->\n", "X.md", &t).is_err());
        assert!(fill("no markers\n", "X.md", &t).is_err());
        assert!(fill("<!-- figures:t -->\nx\n", "X.md", &t).is_err());
        assert!(fill("<!-- /figures -->\n", "X.md", &[]).is_err());
        let twice =
            "<!-- figures:t -->\n<!-- /figures -->\n<!-- figures:t -->\n<!-- /figures -->\n";
        assert!(fill(twice, "X.md", &t).is_err());
        let nested = "<!-- figures:t -->\n<!-- figures:t -->\n<!-- /figures -->\n";
        assert!(fill(nested, "X.md", &t).is_err());
    }

    #[test]
    fn band_names_give_rows_and_scratch() {
        assert_eq!(band_rows("ours-m1_band8"), Some(8));
        assert_eq!(band_rows("ours-m1_band16_noscratch"), Some(16));
        assert_eq!(band_rows("ours-band16"), Some(16));
        assert_eq!(band_rows("ours-m1_noscratch"), None);
        assert!(band_scratch(&Figures::default(), "ours-m1_band8"));
        assert!(!band_scratch(
            &Figures::default(),
            "ours-m1_band16_noscratch"
        ));
        let f = Figures::parse("M1\tours-band16\tscratch_bytes\t8112\n").unwrap();
        assert!(band_scratch(&f, "ours-band16"));
        let f = Figures::parse("M1\tours-band16\tscratch_bytes\t0\n").unwrap();
        assert!(!band_scratch(&f, "ours-band16"));
    }
}
