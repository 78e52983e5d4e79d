//! Where `render`, `animate` and `compare` can write: `-o -` (standard output), a device
//! (`/dev/stdout`) or a FIFO, written in place; and the format must agree with the extension.

use std::fs;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

#[path = "support/cli.rs"]
mod cli;
use cli::{assert_error, assert_no_panic, assert_ok, listing, run, s, scratch_in, text, BIN};

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/scenes")
        .join(name)
}

const PNG: &[u8] = b"\x89PNG";
const GIF: &[u8] = b"GIF89a";

/// The three writers with their output set to `out`, and the magic of what they write.
fn writers(out: &str) -> Vec<(&'static str, Vec<String>, &'static [u8])> {
    let two_d = scene("polygons.toml");
    let three_d = scene("suzanne_gouraud.toml");
    let v = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    vec![
        ("render", v(&["render", s(&two_d), "-o", out]), PNG),
        (
            "animate",
            v(&["animate", s(&three_d), "--frames", "2", "-o", out]),
            GIF,
        ),
        ("compare", v(&["compare", s(&three_d), "-o", out]), PNG),
    ]
}

#[test]
fn dash_writes_the_image_to_stdout_and_messages_to_stderr() {
    let dir = scratch_in("outputs", "dash");
    for (label, args, magic) in writers("-") {
        let o = Command::new(BIN)
            .args(&args)
            .current_dir(&dir)
            .output()
            .unwrap();
        assert_ok(&o, label);
        assert!(
            o.stdout.starts_with(magic),
            "{label}: stdout is not the image"
        );
        assert!(
            text(&o.stderr).contains("wrote"),
            "{label}: {}",
            text(&o.stderr)
        );
        assert!(listing(&dir).is_empty(), "{label}: wrote a file named -");
    }
}

#[test]
fn dash_output_whose_reader_leaves_is_no_panic() {
    for (label, args, _) in writers("-") {
        let mut child = Command::new(BIN)
            .args(&args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // `| head -c1`: one byte read, then the pipe is closed.
        let mut stdout = child.stdout.take().unwrap();
        let mut byte = [0u8; 1];
        stdout.read_exact(&mut byte).unwrap();
        drop(stdout);
        let o = child.wait_with_output().unwrap();
        assert_no_panic(&o, label);
        assert!(o.status.success(), "{label}: {}", text(&o.stderr));
    }
}

#[test]
fn dev_stdout_is_written_in_place() {
    for (label, args, magic) in writers("/dev/stdout") {
        let o = run(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert_ok(&o, label);
        assert!(o.stdout.starts_with(magic), "{label}: {}", text(&o.stderr));
    }
}

#[test]
fn a_fifo_is_written_in_place() {
    let dir = scratch_in("outputs", "fifo");
    let fifo = dir.join("pipe");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        println!("skipped: mkfifo is not available");
        return;
    }
    for (label, args, magic) in writers(s(&fifo)) {
        let path = fifo.clone();
        let reader = std::thread::spawn(move || fs::read(path).unwrap());
        let o = run(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert_ok(&o, label);
        assert!(reader.join().unwrap().starts_with(magic), "{label}");
        assert_eq!(listing(&dir), ["pipe"], "{label}: files left behind");
    }
}

#[test]
fn an_extension_of_another_format_is_refused() {
    let dir = scratch_in("outputs", "ext");
    let three_d = scene("suzanne_gouraud.toml");
    let old = b"the user's file";
    let cases: Vec<(&str, Vec<&str>, &str, &str)> = vec![
        ("render gif", vec!["render", s(&three_d)], "x.gif", ".png"),
        ("compare jpg", vec!["compare", s(&three_d)], "x.jpg", ".png"),
        ("animate png", vec!["animate", s(&three_d)], "x.png", ".gif"),
        (
            "animate sequence gif",
            vec!["animate", s(&three_d), "--png-sequence"],
            "x.gif",
            ".png",
        ),
    ];
    for (label, mut args, name, accepted) in cases {
        let path = dir.join(name);
        fs::write(&path, old).unwrap();
        args.extend(["-o", s(&path)]);
        let line = assert_error(&run(&args), label);
        assert!(
            line.contains(name) && line.contains("accepted") && line.contains(accepted),
            "{label}: {line}"
        );
        assert_eq!(fs::read(&path).unwrap(), old, "{label}: the file changed");
    }
    let line = assert_error(
        &run(&["animate", s(&three_d), "--png-sequence", "-o", "-"]),
        "sequence to stdout",
    );
    assert!(line.contains("standard output"), "{line}");
    // The case of the extension does not matter.
    let upper = dir.join("UPPER.PNG");
    assert_ok(
        &run(&["render", s(&scene("polygons.toml")), "-o", s(&upper)]),
        "upper case",
    );
    assert!(fs::read(&upper).unwrap().starts_with(PNG));
}
