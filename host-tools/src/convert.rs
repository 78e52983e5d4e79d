//! The `convert` command: OBJ -> packed mesh (or Rust source).

use std::path::PathBuf;

/// Options of the `convert` command.
#[derive(Debug, clap::Args)]
pub struct ConvertArgs {
    /// The OBJ file to convert.
    pub input: PathBuf,
    /// The output file.
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
}

/// Runs the command.
///
/// # Errors
/// Any failure, as a message for the `error:` line.
pub fn run(_args: &ConvertArgs) -> Result<(), Box<dyn std::error::Error>> {
    Err("convert is not implemented yet".into())
}
