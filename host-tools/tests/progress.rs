//! Progress of the long commands (`animate`, `accuracy`, `demo`): a bar on a terminal's stderr, and
//! nothing progress-like when stderr is a pipe or a log, where the command works as before.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

#[path = "support/cli.rs"]
mod cli;
use cli::{assert_ok, run, s, scratch_in, text, BIN};

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/scenes")
        .join(name)
}

/// Nothing a bar draws or a progress line says: carriage returns, escapes, percentages.
fn assert_no_progress(stderr: &str, what: &str) {
    assert!(
        !stderr.contains('\r') && !stderr.contains('\x1b') && !stderr.contains('%'),
        "{what}: progress on a non-terminal stderr:\n{stderr}"
    );
}

#[test]
fn animate_is_quiet_on_a_non_terminal_stderr() {
    let dir = scratch_in("progress", "animate");
    let gif = dir.join("a.gif");
    let o = run(&[
        "animate",
        s(&scene("suzanne_gouraud.toml")),
        "--frames",
        "3",
        "-o",
        s(&gif),
    ]);
    assert_ok(&o, "animate");
    assert_eq!(text(&o.stderr), "", "animate: stderr");
    assert!(fs::read(&gif).unwrap().starts_with(b"GIF89a"));
}

#[test]
fn accuracy_is_quiet_on_a_non_terminal_stderr() {
    let dir = scratch_in("progress", "accuracy");
    let o = run(&["accuracy", "--quick", "--no-count", "--out", s(&dir)]);
    assert_ok(&o, "accuracy");
    let stderr = text(&o.stderr);
    assert_no_progress(&stderr, "accuracy");
    // Only warnings (a debug build says it is one), no lines about what is being measured.
    assert!(
        stderr.lines().all(|l| l.starts_with("warning: ")),
        "accuracy: stderr:\n{stderr}"
    );
    assert!(dir.join("ACCURACY.md").is_file());
}

/// Runs `command` (a shell command line) on a pseudo-terminal through util-linux's `script`
/// (installed with Debian's essential bsdutils); None where it is missing or cannot make a
/// terminal.
fn on_a_terminal(command: &str) -> Option<String> {
    let o = Command::new("script")
        .args(["-qec", command, "/dev/null"])
        .stdin(std::process::Stdio::null())
        .output()
        .ok()?;
    let shown = text(&o.stdout) + &text(&o.stderr);
    if !o.status.success() && shown.starts_with("script:") {
        return None;
    }
    assert!(
        o.status.success(),
        "{command} failed on a terminal:\n{shown}"
    );
    Some(shown)
}

#[test]
fn animate_draws_a_bar_on_a_terminal() {
    let dir = scratch_in("progress", "terminal");
    let gif = dir.join("a.gif");
    let command = format!(
        "'{BIN}' animate '{}' --frames 6 -o '{}'",
        s(&scene("suzanne_gouraud.toml")),
        s(&gif)
    );
    let Some(shown) = on_a_terminal(&command) else {
        println!("skipped: `script` (util-linux) is not installed or cannot open a terminal");
        return;
    };
    assert!(
        shown.contains("frames [") && shown.contains('%'),
        "no bar on the terminal:\n{shown}"
    );
    assert!(fs::read(&gif).unwrap().starts_with(b"GIF89a"));
}

#[test]
fn demo_draws_a_bar_on_a_terminal() {
    let dir = scratch_in("progress", "demo");
    let command = format!("'{BIN}' demo --out '{}'", s(&dir.join("images")));
    let Some(shown) = on_a_terminal(&command) else {
        println!("skipped: `script` (util-linux) is not installed or cannot open a terminal");
        return;
    };
    assert!(
        shown.contains("demo [") && shown.contains('%'),
        "no bar on the terminal:\n{shown}"
    );
    assert!(fs::read(dir.join("images/polygons.png"))
        .unwrap()
        .starts_with(b"\x89PNG"));
}
