//! Running the binary as a user would and checking how it ended: what the command-line test
//! files share (a failure is exactly one `error:` line and exit 1, never a panic).

// Each test file is a crate of its own and uses only some of these.
#![allow(dead_code)]

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The binary under test.
pub const BIN: &str = env!("CARGO_BIN_EXE_host-tools");

/// A fresh directory, unique to this test, call and process; `kind` names the test file.
pub fn scratch_in(kind: &str, name: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "host-tools-{kind}-{name}-{}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// Output bytes as text.
pub fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// Runs the binary with `args`, stdout and stderr captured.
pub fn run(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

/// A path as an argument.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// No panic text anywhere in the output.
pub fn assert_no_panic(o: &Output, what: &str) {
    let all = text(&o.stdout) + &text(&o.stderr);
    assert!(
        !all.contains("panicked") && !all.contains("RUST_BACKTRACE"),
        "{what}: panic text:\n{all}"
    );
    assert_ne!(o.status.code(), Some(101), "{what}: exit 101 (a panic)");
}

/// A failure: non-zero exit (1), exactly one `error:` line, no panic; returns that line.
pub fn assert_error(o: &Output, what: &str) -> String {
    assert_no_panic(o, what);
    let stderr = text(&o.stderr);
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(
        errors.len(),
        1,
        "{what}: want one error line, stderr:\n{stderr}\nstdout:\n{}",
        text(&o.stdout)
    );
    assert_eq!(
        o.status.code(),
        Some(1),
        "{what}: exit code; stderr:\n{stderr}"
    );
    errors[0].to_string()
}

/// A success: exit 0, no `error:` line, no panic.
pub fn assert_ok(o: &Output, what: &str) {
    assert_no_panic(o, what);
    assert!(
        o.status.success(),
        "{what}: exit {:?}, stderr:\n{}",
        o.status.code(),
        text(&o.stderr)
    );
    assert!(!text(&o.stderr).contains("error:"), "{what}");
}

/// The names in `dir`, sorted: shows any temporary file left behind.
pub fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Runs `args` with stdout on a pipe whose read end is already closed.
pub fn with_closed_stdout(args: &[&str]) -> Output {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    Command::new(BIN)
        .args(args)
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap()
}
