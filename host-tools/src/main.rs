//! `host-tools`: command-line tools that run `rasterizer-core` on a desktop machine.
//!
//! Run `cargo run --release -p host-tools -- --help` for the list of commands.
#![deny(missing_docs)]

mod demo;
mod demo3d;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

/// Host-side tools for the rasterizer-core crate.
#[derive(Debug, Parser)]
#[command(
    name = "host-tools",
    version,
    about = "Host-side tools for rasterizer-core, the no_std fixed-point rasterizer",
    long_about = "Host-side tools for rasterizer-core, the no_std fixed-point rasterizer.\n\n\
        Everything here runs on your desktop: the rasterizer draws into an in-memory \
        embedded-graphics simulator display instead of a real screen.\n\n\
        Start with `host-tools demo`, which renders the example pictures shown in README.md."
)]
struct Cli {
    /// What to do.
    #[command(subcommand)]
    command: Command,
}

/// The subcommands. Add new tools here as new variants.
#[derive(Debug, Subcommand)]
enum Command {
    /// Render the demo pictures (lines, triangles, polygons, clipping, 3D meshes) as PNG files.
    ///
    /// The long help, which lists every file, is made from the demo's own list in `main`.
    Demo(DemoArgs),
    /// Convert an OBJ file into the packed fixed-point mesh firmware embeds (or Rust source).
    Convert(host_tools::convert::ConvertArgs),
    /// Convert a PNG into a sprite (Rgb565 with 0, 1, 4 or 8 bits of alpha) firmware reads in place.
    Sprite(host_tools::sprite::SpriteArgs),
    /// Show a scene file in a live window, turned with the arrow keys or the mouse (feature `view`).
    ///
    /// Needs a display: X11 (DISPLAY) or Wayland (WAYLAND_DISPLAY), or a driver chosen with
    /// SDL_VIDEODRIVER; where no window can be opened it fails with an error saying why.
    #[cfg(feature = "view")]
    #[command(after_long_help = host_tools::scenefile::LIMITS_HELP)]
    View(host_tools::view::ViewArgs),
    /// Render a scene file to a PNG through embedded-graphics-simulator.
    #[command(after_long_help = host_tools::scenefile::LIMITS_HELP)]
    Render(host_tools::scenefile::RenderArgs),
    /// Render a turntable of a scene file as an animated GIF or a PNG sequence.
    #[command(after_long_help = host_tools::scenefile::LIMITS_HELP)]
    Animate(host_tools::scenefile::AnimateArgs),
    /// Render a scene in fixed point and in floating point and write the difference image.
    #[command(after_long_help = host_tools::scenefile::LIMITS_HELP)]
    Compare(host_tools::scenefile::CompareArgs),
    /// Sweep the accuracy knobs against an f64 reference and write docs/ACCURACY.md and its plot.
    #[command(
        long_about = "Sweep the accuracy knobs of the 3D pipeline and write the report.\n\n\
        Every configuration (geometry format, sub-pixel bits, sine table size, perspective-correct \
        interpolation, and combinations) is measured against an f64 reference on the workload \
        scenes M1-M3 and on random scenes, its instructions per M1 frame are counted with \
        callgrind (valgrind must be installed, or pass --no-count), and the limits of each format \
        are found. Writes OUT/ACCURACY.md and OUT/images/accuracy.svg. A progress bar is shown on \
        stderr when it is a terminal.\n\n\
        Run from the repository root, release build: \
        cargo run --release -p host-tools -- accuracy"
    )]
    Accuracy(host_tools::accuracy::AccuracyArgs),
    /// Draw one configuration's counted M1 frame (run by `accuracy` under callgrind).
    #[command(hide = true)]
    AccuracyCount(host_tools::accuracy::CountArgs),
}

/// Options of the `demo` command.
#[derive(Debug, clap::Args)]
struct DemoArgs {
    /// Directory to write the PNG files into; it is created if it does not exist.
    ///
    /// A relative path is taken from the current directory: run from the repository root to
    /// refresh the pictures README.md shows.
    #[arg(long, value_name = "DIR", default_value = "docs/images")]
    out: PathBuf,

    /// Directory holding the OBJ models of the 3D pictures (suzanne.obj).
    ///
    /// Default: assets/models, looked up in the current directory, then in the repository
    /// host-tools was built from, then in the directories above the executable (a binary cargo
    /// built lies in the repository's target/), so it is found wherever the command is run from.
    #[arg(long, value_name = "DIR")]
    models: Option<PathBuf>,
}

fn main() -> ExitCode {
    let command = Cli::command().mut_subcommand("demo", |demo| demo.long_about(demo::long_help()));
    let cli = match Cli::from_arg_matches(&command.get_matches()) {
        Ok(cli) => cli,
        Err(e) => e.exit(),
    };
    let result: Result<(), Box<dyn std::error::Error>> = match cli.command {
        Command::Demo(args) => match args.models.or_else(demo::default_models) {
            Some(models) => demo::run(&args.out, &models, |path| {
                host_tools::outln!("wrote {}", path.display())
            })
            .map_err(Into::into),
            None => Err(
                "cannot find assets/models in the current directory or above the \
                 executable; pass --models DIR"
                    .into(),
            ),
        },
        Command::Convert(args) => host_tools::convert::run(&args),
        Command::Sprite(args) => host_tools::sprite::run(&args),
        #[cfg(feature = "view")]
        Command::View(args) => host_tools::view::run(&args),
        Command::Render(args) => host_tools::scenefile::render(&args),
        Command::Animate(args) => host_tools::scenefile::animate(&args),
        Command::Compare(args) => host_tools::scenefile::compare(&args),
        Command::Accuracy(args) => host_tools::accuracy::run(&args),
        Command::AccuracyCount(args) => host_tools::accuracy::run_count(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            host_tools::errln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
