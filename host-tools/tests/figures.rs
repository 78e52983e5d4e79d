//! The published tables are the figures of record: BENCHMARKS.md and README.md must hold exactly
//! the tables `host_tools::figures` makes from the committed `docs/figures.tsv` (so a hand edit of
//! a table fails), and that file must hold every line shared/bench/WORKLOADS.md requires.

use host_tools::figures::{self, Figures, REQUIRED};
use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap()
}

fn committed() -> Figures {
    let path = root().join("docs/figures.tsv");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    Figures::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn figures_tsv_has_every_required_line() {
    let f = committed();
    let missing = f.missing_required();
    assert!(
        missing.is_empty(),
        "docs/figures.tsv lacks lines WORKLOADS.md requires (run scripts/figures.sh):\n{}",
        missing.join("\n")
    );
    // The banded RAM figure is the sum of its parts.
    let part = |m| f.get("M1", "ours-band16", m).unwrap();
    let parts = [
        "band_bytes",
        "band_depth_bytes",
        "bins_bytes",
        "scratch_bytes",
        "stack_bytes",
    ];
    assert_eq!(
        part("ram_bytes"),
        parts.iter().map(|&m| part(m)).sum::<f64>()
    );
    // Every scene of WORKLOADS.md is drawn, M4 (textured) and its untextured control included.
    for r in ["ours", "ours-untextured"] {
        assert!(REQUIRED.contains(&("M4", r, "instructions")), "M4 {r}");
    }
}

#[test]
fn documents_hold_the_tables_of_figures_tsv() {
    let f = committed();
    let docs = figures::regenerate(root(), &f).unwrap_or_else(|e| panic!("{e}"));
    for (name, old, new) in docs {
        if old != new {
            let line = old
                .lines()
                .zip(new.lines())
                .position(|(a, b)| a != b)
                .map_or(old.lines().count().min(new.lines().count()), |i| i);
            panic!(
                "{name} differs from the tables docs/figures.tsv makes, from line {}:\n  \
                 on disk:   {:?}\n  generated: {:?}\nRun `{}` (tables are not edited by hand).",
                line + 1,
                old.lines().nth(line).unwrap_or(""),
                new.lines().nth(line).unwrap_or(""),
                figures::REGENERATE
            );
        }
    }
}
