//! Writes the tables of BENCHMARKS.md and README.md from the figures of record
//! (`host_tools::figures`): `figures_tables [--check] [FILE]`, FILE being the output of
//! `scripts/figures.sh` (default: the repository's `docs/figures.tsv`).
//!
//! Each table sits between `<!-- figures:NAME -->` and `<!-- /figures -->` in its document and is
//! replaced whole; the text around it is kept. With `--check` nothing is written: the command
//! fails, naming the documents, when a table differs from what FILE makes. It also fails when
//! FILE lacks a line shared/bench/WORKLOADS.md requires, so a partial run cannot become the
//! published tables.

use host_tools::figures::{self, Figures};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

fn main() -> ExitCode {
    match run() {
        Ok(code) => code,
        Err(e) => {
            eprintln!("figures_tables: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<ExitCode, String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .ok_or("host-tools has no parent directory")?;
    let mut check = false;
    let mut file: Option<PathBuf> = None;
    for arg in std::env::args().skip(1) {
        match arg.as_str() {
            "--check" => check = true,
            a if a.starts_with('-') || file.is_some() => {
                eprintln!("usage: figures_tables [--check] [FILE]   (default: docs/figures.tsv)");
                return Ok(ExitCode::from(2));
            }
            a => file = Some(PathBuf::from(a)),
        }
    }
    let file = file.unwrap_or_else(|| root.join("docs/figures.tsv"));
    let text = std::fs::read_to_string(&file).map_err(|e| format!("{}: {e}", file.display()))?;
    let f = Figures::parse(&text).map_err(|e| format!("{}: {e}", file.display()))?;
    let mut stale = Vec::new();
    for (name, old, new) in figures::regenerate(root, &f)? {
        if old == new {
            continue;
        }
        if check {
            stale.push(name);
        } else {
            let path = root.join(name);
            std::fs::write(&path, new).map_err(|e| format!("{}: {e}", path.display()))?;
            eprintln!("rewrote the tables of {name}");
        }
    }
    if !stale.is_empty() {
        eprintln!(
            "figures_tables: the tables of {} differ from {}: run `{}`",
            stale.join(" and "),
            file.display(),
            figures::REGENERATE
        );
        return Ok(ExitCode::FAILURE);
    }
    Ok(ExitCode::SUCCESS)
}
