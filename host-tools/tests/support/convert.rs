//! What the `convert` tests share: the models, a scratch directory per call, and running the
//! command.

#[path = "cli.rs"]
mod cli;
pub use cli::{scratch_in, text};

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The shared test models (CI has ../shared beside the repository).
pub fn models() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/assets/models")
}

/// Runs `host-tools convert INPUT -o OUTPUT EXTRA..`.
pub fn convert(input: &Path, output: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_host-tools"))
        .arg("convert")
        .arg(input)
        .arg("-o")
        .arg(output)
        .args(extra)
        .output()
        .unwrap()
}
