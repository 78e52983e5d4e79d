//! Scene files and the `render`, `animate` and `compare` commands.

use std::path::PathBuf;

/// Options of the `render` command.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// The scene file.
    pub scene: PathBuf,
    /// The PNG to write.
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
}

/// Options of the `animate` command.
#[derive(Debug, clap::Args)]
pub struct AnimateArgs {
    /// The scene file.
    pub scene: PathBuf,
    /// The output (GIF).
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
}

/// Options of the `compare` command.
#[derive(Debug, clap::Args)]
pub struct CompareArgs {
    /// The scene file.
    pub scene: PathBuf,
    /// The difference image to write.
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
}

/// Runs `render`.
///
/// # Errors
/// Any failure, as a message for the `error:` line.
pub fn render(_args: &RenderArgs) -> Result<(), Box<dyn std::error::Error>> {
    Err("render is not implemented yet".into())
}

/// Runs `animate`.
///
/// # Errors
/// Any failure, as a message for the `error:` line.
pub fn animate(_args: &AnimateArgs) -> Result<(), Box<dyn std::error::Error>> {
    Err("animate is not implemented yet".into())
}

/// Runs `compare`.
///
/// # Errors
/// Any failure, as a message for the `error:` line.
pub fn compare(_args: &CompareArgs) -> Result<(), Box<dyn std::error::Error>> {
    Err("compare is not implemented yet".into())
}
