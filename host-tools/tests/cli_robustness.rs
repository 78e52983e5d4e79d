//! The binary under hostile conditions, run as a user would: full disks, write failures, closed
//! and full standard output, an output that is the input, a symlink or a device node, requests
//! beyond the size limits, and scene values beyond what 16.16 can draw.
//!
//! Every failure must be exactly one `error:` line and a non-zero exit, never a panic; the user's
//! existing files stay byte-for-byte as they were and no temporary file is left behind. Cases that
//! need root (a tmpfs, a device node) print a message and skip elsewhere.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

#[path = "support/cli.rs"]
mod cli;
use cli::{
    assert_error, assert_no_panic, assert_ok, listing, run, s, scratch_in, text,
    with_closed_stdout, BIN,
};

fn models() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models")
}

/// A fresh directory for one test.
fn scratch(name: &str) -> PathBuf {
    scratch_in("robust", name)
}

fn assert_listing(dir: &Path, want: &[&str], what: &str) {
    let mut want: Vec<String> = want.iter().map(|s| s.to_string()).collect();
    want.sort();
    assert_eq!(listing(dir), want, "{what}: files in {}", dir.display());
}

/// A 2D scene whose PNG is several kilobytes (gradients compress badly), so a write limit of one
/// block is exceeded.
const SCENE_2D: &str = r#"
[output]
width = 96
height = 64
scale = 2
[[shapes]]
kind = "triangle"
vertices = [[0.0, 0.0], [95.5, 3.25], [20.0, 63.5]]
colors = [[255, 0, 0], [0, 255, 0], [0, 0, 255]]
[[shapes]]
kind = "triangle"
vertices = [[95.0, 63.0], [90.5, 0.25], [3.0, 60.5]]
colors = [[255, 255, 0], [0, 255, 255], [255, 0, 255]]
"#;

/// A small 3D scene (the unit cube), for `animate` and `compare`.
fn scene_3d(extra_mesh: &str) -> String {
    format!(
        r#"
[output]
width = 64
height = 48
scale = 2
[camera]
eye = [1.5, 1.2, 2.5]
[[lights]]
kind = "directional"
direction = [1.0, 2.0, 3.0]
[[meshes]]
path = "{}"
{extra_mesh}
"#,
        models().join("unit_cube.obj").display()
    )
}

/// Writes the test's inputs into `dir`: `2d.toml`, `3d.toml` and `cube.obj`.
fn inputs(dir: &Path) -> (PathBuf, PathBuf, PathBuf) {
    let (a, b, c) = (
        dir.join("2d.toml"),
        dir.join("3d.toml"),
        dir.join("cube.obj"),
    );
    fs::write(&a, SCENE_2D).unwrap();
    fs::write(&b, scene_3d("")).unwrap();
    fs::copy(models().join("suzanne.obj"), &c).unwrap();
    (a, b, c)
}

const OLD: &[u8] = b"the user's old file: must survive any failure";

/// Every command that writes a file, as (label, arguments), writing to `out` (a `.png`; the GIF
/// and converter outputs get their own extension next to it).
fn writers(dir: &Path, out_dir: &Path) -> Vec<(String, Vec<String>, PathBuf)> {
    let (s2, s3, obj) = inputs(dir);
    let png = out_dir.join("out.png");
    let gif = out_dir.join("out.gif");
    let rmsh = out_dir.join("out.rmsh");
    let seq0 = out_dir.join("seq_000.png");
    let v = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    vec![
        (
            "render".into(),
            v(&["render", s(&s2), "-o", s(&png)]),
            png.clone(),
        ),
        (
            "animate gif".into(),
            v(&["animate", s(&s3), "--frames", "3", "-o", s(&gif)]),
            gif,
        ),
        (
            "animate png sequence".into(),
            v(&[
                "animate",
                s(&s3),
                "--frames",
                "2",
                "--png-sequence",
                "-o",
                s(&out_dir.join("seq.png")),
            ]),
            seq0,
        ),
        (
            "compare".into(),
            v(&["compare", s(&s3), "-o", s(&png)]),
            png,
        ),
        (
            "convert".into(),
            v(&["convert", s(&obj), "-o", s(&rmsh)]),
            rmsh,
        ),
    ]
}

/// Runs every writer with an old file at its output under `wrap` (which makes writes fail) and
/// checks the failure and the old file.
fn every_writer_keeps_the_old_file(dir: &Path, out_dir: &Path, wrap: &dyn Fn(&[String]) -> Output) {
    for (label, args, target) in writers(dir, out_dir) {
        fs::write(&target, OLD).unwrap();
        let before = listing(out_dir);
        let o = wrap(&args);
        let line = assert_error(&o, &label);
        let name = target.file_name().unwrap().to_str().unwrap();
        assert!(
            line.contains(name),
            "{label}: the error names the file: {line}"
        );
        assert_eq!(fs::read(&target).unwrap(), OLD, "{label}: old file changed");
        assert_eq!(listing(out_dir), before, "{label}: files left behind");
        fs::remove_file(&target).unwrap();
    }
}

/// A tmpfs of 64 KiB mounted on a directory, unmounted when dropped.
struct Tmpfs(PathBuf);

impl Tmpfs {
    fn mount(dir: &Path) -> Option<Self> {
        fs::create_dir_all(dir).unwrap();
        let ok = Command::new("mount")
            .args(["-t", "tmpfs", "-o", "size=64k", "tmpfs"])
            .arg(dir)
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        ok.then(|| Self(dir.to_path_buf()))
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
    }
}

/// Fills the file system holding `dir` to the last byte.
fn fill(dir: &Path) {
    let mut f = fs::File::create(dir.join("filler")).unwrap();
    let block = [0x55u8; 4096];
    while f.write_all(&block).and_then(|()| f.flush()).is_ok() {}
    let _ = f.sync_all();
}

#[test]
fn full_disk_keeps_existing_outputs() {
    let dir = scratch("full-disk");
    let mnt = dir.join("mnt");
    let Some(_tmpfs) = Tmpfs::mount(&mnt) else {
        println!("skipped: mounting a tmpfs was refused (needs root)");
        return;
    };
    // The old files first, then the disk is filled.
    for (_, _, target) in writers(&dir, &mnt) {
        fs::write(&target, OLD).unwrap();
    }
    fs::write(mnt.join("lines_octants.png"), OLD).unwrap();
    fill(&mnt);
    for (label, args, target) in writers(&dir, &mnt) {
        let before = listing(&mnt);
        let o = Command::new(BIN).args(&args).output().unwrap();
        let line = assert_error(&o, &label);
        let name = target.file_name().unwrap().to_str().unwrap();
        assert!(
            line.contains(name),
            "{label}: the error names the file: {line}"
        );
        assert_eq!(fs::read(&target).unwrap(), OLD, "{label}: old file changed");
        assert_eq!(listing(&mnt), before, "{label}: files left behind");
    }
    let o = run(&["demo", "--out", s(&mnt)]);
    assert_error(&o, "demo");
    assert_eq!(fs::read(mnt.join("lines_octants.png")).unwrap(), OLD);
}

/// `sh -c "trap '' XFSZ; ulimit -f 1; exec BIN ARGS"`: writes past one block fail with EFBIG.
fn with_file_limit(args: &[String]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg("trap '' XFSZ; ulimit -f 1; exec \"$0\" \"$@\"")
        .arg(BIN)
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn write_failure_without_root_keeps_existing_outputs() {
    let dir = scratch("ulimit");
    let out = dir.join("out");
    fs::create_dir_all(&out).unwrap();
    every_writer_keeps_the_old_file(&dir, &out, &with_file_limit);
    // demo: the first picture fails; the old one stays.
    let demo = dir.join("demo");
    fs::create_dir_all(&demo).unwrap();
    fs::write(demo.join("lines_octants.png"), OLD).unwrap();
    let o = with_file_limit(&["demo".into(), "--out".into(), s(&demo).into()]);
    assert_error(&o, "demo");
    assert_eq!(fs::read(demo.join("lines_octants.png")).unwrap(), OLD);
    assert_listing(&demo, &["lines_octants.png"], "demo");
}

#[test]
fn existing_output_is_replaced_with_its_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let dir = scratch("replace");
    let out = dir.join("out");
    fs::create_dir_all(&out).unwrap();
    for (label, args, target) in writers(&dir, &out) {
        fs::write(&target, OLD).unwrap();
        fs::set_permissions(&target, fs::Permissions::from_mode(0o640)).unwrap();
        let o = Command::new(BIN).args(&args).output().unwrap();
        assert_ok(&o, &label);
        assert_ne!(fs::read(&target).unwrap(), OLD, "{label}: not replaced");
        let mode = fs::metadata(&target).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o640, "{label}: permissions");
        assert!(
            listing(&out).iter().all(|n| !n.starts_with('.')),
            "{label}: temporary file left: {:?}",
            listing(&out)
        );
    }
}

#[test]
fn output_equal_to_input_is_refused() {
    let dir = scratch("same");
    let (s2, s3, obj) = inputs(&dir);
    let original = fs::read(&obj).unwrap();
    let scene2 = fs::read(&s2).unwrap();
    fs::hard_link(&obj, dir.join("hard.obj")).unwrap();
    std::os::unix::fs::symlink(&obj, dir.join("link.obj")).unwrap();
    let (dotted, hard, link) = (
        format!("{}/./cube.obj", s(&dir)),
        dir.join("hard.obj"),
        dir.join("link.obj"),
    );
    let cases: Vec<(&str, Vec<&str>)> = vec![
        ("convert same", vec!["convert", s(&obj), "-o", s(&obj)]),
        ("convert via ./", vec!["convert", s(&obj), "-o", &dotted]),
        (
            "convert hard link",
            vec!["convert", s(&obj), "-o", s(&hard)],
        ),
        ("convert symlink", vec!["convert", s(&obj), "-o", s(&link)]),
        ("render scene", vec!["render", s(&s2), "-o", s(&s2)]),
        ("compare scene", vec!["compare", s(&s3), "-o", s(&s3)]),
        (
            "animate scene",
            vec!["animate", s(&s3), "--frames", "2", "-o", s(&s3)],
        ),
    ];
    let before = listing(&dir);
    for (label, args) in cases {
        let o = run(&args);
        let line = assert_error(&o, label);
        assert!(line.contains("input"), "{label}: says why: {line}");
        assert_eq!(fs::read(&obj).unwrap(), original, "{label}: input changed");
        assert_eq!(fs::read(&s2).unwrap(), scene2, "{label}: scene changed");
        assert_eq!(listing(&dir), before, "{label}: files left behind");
    }
    // A mesh the scene reads is an input too.
    let mesh_scene = dir.join("mesh.toml");
    fs::write(
        &mesh_scene,
        scene_3d("").replace(&s(&models().join("unit_cube.obj")).to_string(), s(&obj)),
    )
    .unwrap();
    let o = run(&["render", s(&mesh_scene), "-o", s(&obj)]);
    assert_error(&o, "render over its mesh");
    assert_eq!(fs::read(&obj).unwrap(), original);
    assert!(std::fs::symlink_metadata(dir.join("link.obj"))
        .unwrap()
        .file_type()
        .is_symlink());
}

#[test]
fn symlink_output_writes_through_the_link() {
    let dir = scratch("symlink");
    let out = dir.join("out");
    fs::create_dir_all(&out).unwrap();
    let real_dir = dir.join("real");
    fs::create_dir_all(&real_dir).unwrap();
    for (label, args, target) in writers(&dir, &out) {
        let name = target.file_name().unwrap();
        let real = real_dir.join(name);
        fs::write(&real, OLD).unwrap();
        std::os::unix::fs::symlink(&real, &target).unwrap();
        let o = Command::new(BIN).args(&args).output().unwrap();
        assert_ok(&o, &label);
        assert!(
            fs::symlink_metadata(&target)
                .unwrap()
                .file_type()
                .is_symlink(),
            "{label}: the link was replaced"
        );
        assert_ne!(
            fs::read(&real).unwrap(),
            OLD,
            "{label}: the link's target was not written"
        );
        assert!(
            listing(&real_dir).iter().all(|n| !n.starts_with('.')),
            "{label}"
        );
        fs::remove_file(&target).unwrap();
        fs::remove_file(&real).unwrap();
    }
    // A relative link, and a link to a file that does not exist yet.
    let (s2, _, _) = inputs(&dir);
    std::os::unix::fs::symlink("real/new.png", dir.join("rel.png")).unwrap();
    assert_ok(
        &run(&["render", s(&s2), "-o", s(&dir.join("rel.png"))]),
        "dangling link",
    );
    assert!(fs::read(real_dir.join("new.png"))
        .unwrap()
        .starts_with(b"\x89PNG"));
    assert!(fs::symlink_metadata(dir.join("rel.png"))
        .unwrap()
        .file_type()
        .is_symlink());
}

/// A private copy of /dev/full (needs root), so a test never touches the real one.
fn dev_full(dir: &Path) -> Option<PathBuf> {
    let node = dir.join("full");
    let ok = Command::new("mknod")
        .arg(&node)
        .args(["c", "1", "7"])
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    ok.then_some(node)
}

fn is_char_device(p: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    fs::symlink_metadata(p).is_ok_and(|m| m.file_type().is_char_device())
}

#[test]
fn device_node_output_is_written_not_replaced() {
    let dir = scratch("device");
    let Some(node) = dev_full(&dir) else {
        println!("skipped: mknod was refused (needs root)");
        return;
    };
    let (s2, s3, obj) = inputs(&dir);
    let cases: Vec<(&str, Vec<&str>)> = vec![
        ("render", vec!["render", s(&s2), "-o", s(&node)]),
        (
            "animate",
            vec!["animate", s(&s3), "--frames", "2", "-o", s(&node)],
        ),
        ("compare", vec!["compare", s(&s3), "-o", s(&node)]),
        ("convert", vec!["convert", s(&obj), "-o", s(&node)]),
        (
            "convert --rust",
            vec!["convert", s(&obj), "--rust", "-o", s(&node)],
        ),
    ];
    let before = listing(&dir);
    for (label, args) in cases {
        let o = run(&args);
        let line = assert_error(&o, label);
        assert!(line.contains("full"), "{label}: names the device: {line}");
        assert!(is_char_device(&node), "{label}: the device node is gone");
        assert_eq!(listing(&dir), before, "{label}: files left behind");
    }
}

/// Runs `args` with stdout on /dev/full.
fn with_full_stdout(args: &[&str]) -> Output {
    let full = fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    Command::new(BIN)
        .args(args)
        .stdout(full)
        .stderr(Stdio::piped())
        .output()
        .unwrap()
}

#[test]
fn closed_stdout_ends_quietly() {
    let dir = scratch("pipe");
    let (s2, s3, obj) = inputs(&dir);
    let out = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let cases: Vec<(&str, Vec<String>, Option<String>)> = vec![
        (
            "render",
            vec!["render".into(), s(&s2).into(), "-o".into(), out("r.png")],
            Some(out("r.png")),
        ),
        (
            "animate",
            vec![
                "animate".into(),
                s(&s3).into(),
                "--frames".into(),
                "2".into(),
                "-o".into(),
                out("a.gif"),
            ],
            Some(out("a.gif")),
        ),
        (
            "compare",
            vec!["compare".into(), s(&s3).into(), "-o".into(), out("c.png")],
            Some(out("c.png")),
        ),
        (
            "convert",
            vec!["convert".into(), s(&obj).into(), "-o".into(), out("m.rmsh")],
            Some(out("m.rmsh")),
        ),
        (
            "demo",
            vec!["demo".into(), "--out".into(), out("demo")],
            Some(out("demo/near_plane_crossing.png")),
        ),
        ("help", vec!["--help".into()], None),
    ];
    for (label, args, written) in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = with_closed_stdout(&args);
        assert_ok(&o, label);
        assert_eq!(text(&o.stderr), "", "{label}: quiet");
        if let Some(w) = written {
            assert!(Path::new(&w).exists(), "{label}: the work was not done");
        }
    }
}

#[test]
fn full_stdout_is_one_error() {
    let dir = scratch("dev-full-stdout");
    let (s2, s3, obj) = inputs(&dir);
    let (png, rmsh, demo) = (dir.join("r.png"), dir.join("m.rmsh"), dir.join("demo"));
    let cases: Vec<(&str, Vec<&str>)> = vec![
        ("render", vec!["render", s(&s2), "-o", s(&png)]),
        ("compare", vec!["compare", s(&s3), "-o", s(&png)]),
        ("convert", vec!["convert", s(&obj), "-o", s(&rmsh)]),
        ("demo", vec!["demo", "--out", s(&demo)]),
    ];
    for (label, args) in cases {
        let o = with_full_stdout(&args);
        let line = assert_error(&o, label);
        assert!(line.contains("standard output"), "{label}: {line}");
    }
}

#[test]
fn failing_stderr_is_no_panic() {
    let dir = scratch("stderr");
    let bad = dir.join("bad.toml");
    fs::write(&bad, "[output]\nwidth = 0\nheight = 1\n").unwrap();
    let full = fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let o = Command::new(BIN)
        .args(["render", s(&bad), "-o", s(&dir.join("x.png"))])
        .stderr(full)
        .output()
        .unwrap();
    // Nothing can be read from a full stderr: the exit code tells an error from a panic.
    assert_eq!(o.status.code(), Some(1));
}

/// `render` of a scene written into `dir`; returns the error line (after checking it).
fn render_error(dir: &Path, name: &str, scene: &str, extra: &[&str]) -> String {
    let path = dir.join(format!("{name}.toml"));
    fs::write(&path, scene).unwrap();
    let png = dir.join(format!("{name}.png"));
    let mut args = vec!["render", s(&path), "-o", s(&png)];
    args.extend_from_slice(extra);
    let o = run(&args);
    let line = assert_error(&o, name);
    assert!(
        line.contains(&format!("{name}.toml")),
        "{name}: names the file: {line}"
    );
    assert!(!png.exists(), "{name}: wrote an output");
    line
}

#[test]
fn size_limits_are_refused_up_front() {
    let dir = scratch("limits");
    let big = "[output]\nwidth = 4096\nheight = 4096\nscale = 16\n";
    let started = std::time::Instant::now();
    let line = render_error(&dir, "huge", big, &[]);
    assert!(
        line.contains("16777216") && line.contains("4294967296"),
        "{line}"
    );
    let line = render_error(
        &dir,
        "huge_flag",
        "[output]\nwidth = 2048\nheight = 2048\n",
        &["--scale", "3"],
    );
    assert!(
        line.contains("16777216") && line.contains("37748736"),
        "{line}"
    );
    let line = render_error(
        &dir,
        "too_wide",
        "[output]\nwidth = 5000\nheight = 10\n",
        &[],
    );
    assert!(line.contains("4096") && line.contains("5000"), "{line}");
    assert!(started.elapsed().as_secs() < 5, "refused up front");

    let scene = dir.join("anim.toml");
    fs::write(&scene, "[output]\nwidth = 4096\nheight = 2\n").unwrap();
    // GIF frames are at most 65535 pixels wide.
    let o = run(&[
        "animate",
        s(&scene),
        "--scale",
        "16",
        "--frames",
        "2",
        "-o",
        s(&dir.join("a.gif")),
    ]);
    let line = assert_error(&o, "gif too wide");
    assert!(line.contains("65535") && line.contains("65536"), "{line}");
    let o = run(&[
        "animate",
        s(&scene),
        "--frames",
        "721",
        "-o",
        s(&dir.join("a.gif")),
    ]);
    assert_no_panic(&o, "frames");
    assert_eq!(o.status.code(), Some(2), "a usage error");
    assert!(text(&o.stderr).contains("721") && text(&o.stderr).contains("720"));
    assert_listing(
        &dir,
        &["anim.toml", "huge.toml", "huge_flag.toml", "too_wide.toml"],
        "limits",
    );
}

#[test]
fn help_documents_the_limits() {
    for cmd in ["render", "animate"] {
        let o = run(&[cmd, "--help"]);
        let help = text(&o.stdout);
        assert!(
            help.contains("16777216") || help.contains("16,777,216"),
            "{cmd}: {help}"
        );
        assert!(help.to_lowercase().contains("memory"), "{cmd}: {help}");
    }
}

#[test]
fn scene_values_beyond_16_16_are_errors() {
    let dir = scratch("range");
    let cases: &[(&str, &str, &[&str])] = &[
        ("mesh_scale", "scale = 1e30", &["scale", "1e30"]),
        ("mesh_neg_scale", "scale = -1e30", &["scale", "-1e30"]),
        ("mesh_tiny_scale", "scale = 1e-30", &["scale", "1e-30"]),
        (
            "mesh_translate",
            "translate = [1e30, 0.0, 0.0]",
            &["translate", "1e30"],
        ),
    ];
    for (name, line, needles) in cases {
        let e = render_error(&dir, name, &scene_3d(line), &[]);
        for n in *needles {
            assert!(e.contains(n), "{name}: {n} missing in {e}");
        }
    }
    let eye = scene_3d("").replace("eye = [1.5, 1.2, 2.5]", "eye = [0.0, 0.0, 1e6]");
    let e = render_error(&dir, "camera_eye", &eye, &[]);
    assert!(e.contains("eye") && e.contains("1e6"), "{e}");

    let shape = |v: &str| {
        format!("[output]\nwidth = 32\nheight = 32\n[[shapes]]\n{v}\ncolor = [255, 255, 255]\n")
    };
    let e = render_error(
        &dir,
        "triangle_far",
        &shape("kind = \"triangle\"\nvertices = [[0.0, 0.0], [3e6, 5.0], [5.0, 9.0]]"),
        &[],
    );
    assert!(e.contains("3e6") && e.contains("2097152"), "{e}");
    let e = render_error(
        &dir,
        "polygon_far",
        &shape("kind = \"polygon\"\nvertices = [[0.0, 0.0], [10.0, 0.0], [5.0, -1e9]]"),
        &[],
    );
    assert!(e.contains("-1e9") && e.contains("2097152"), "{e}");
    // Lines take whole pixels: any i32 is drawn exactly, beyond that is an error.
    let e = render_error(
        &dir,
        "line_far",
        &shape("kind = \"line\"\nfrom = [1e30, 0.0]\nto = [5.0, 5.0]"),
        &[],
    );
    assert!(e.contains("1e30") && e.contains("2147483647"), "{e}");
}

#[test]
fn collapsed_model_is_a_convert_error() {
    let dir = scratch("collapse");
    // Below one 16.16 step: every vertex decodes to the same point. And far below it.
    for (name, e) in [("tiny", "1e-6"), ("tinier", "1e-30")] {
        let obj = dir.join(format!("{name}.obj"));
        fs::write(
            &obj,
            format!("v 0 0 0\nv {e} 0 0\nv 0 {e} 0\nv 0 0 {e}\nf 1 2 3\nf 1 3 4\n"),
        )
        .unwrap();
        let out = dir.join(format!("{name}.rmsh"));
        let o = run(&["convert", s(&obj), "-o", s(&out)]);
        let line = assert_error(&o, name);
        assert!(
            line.contains(&format!("{name}.obj")) && line.contains("--center-unit-sphere"),
            "{line}"
        );
        assert!(!out.exists(), "{name}: written");
        // Rescaled, it converts.
        let o = run(&["convert", s(&obj), "--center-unit-sphere", "-o", s(&out)]);
        assert_ok(&o, name);
    }
}

#[test]
fn scene_messages_name_their_cause() {
    let dir = scratch("messages");
    // A degenerate camera names the file and the keys.
    let same = scene_3d("").replace("eye = [1.5, 1.2, 2.5]", "eye = [0.0, 0.0, 0.0]");
    let e = render_error(&dir, "eye_is_target", &same, &[]);
    assert!(
        e.contains("[camera]") && e.contains("eye") && e.contains("target"),
        "{e}"
    );
    let parallel = scene_3d("").replace("eye = [1.5, 1.2, 2.5]", "eye = [0.0, 3.0, 0.0]");
    let e = render_error(&dir, "up_parallel", &parallel, &[]);
    assert!(e.contains("[camera]") && e.contains("up"), "{e}");
    // The eye so close to the target that 16.16 cannot tell them apart.
    let close = scene_3d("").replace("eye = [1.5, 1.2, 2.5]", "eye = [0.0, 0.0, 1e-7]");
    let e = render_error(&dir, "eye_too_close", &close, &[]);
    assert!(e.contains("[camera]") && e.contains("eye"), "{e}");

    // fit_unit_sphere happens before the range check.
    let huge = dir.join("huge.obj");
    fs::write(&huge, "v 0 0 0\nv 1e6 0 0\nv 0 1e6 0\nf 1 2 3\n").unwrap();
    let fit = scene_3d("fit_unit_sphere = true\ncull = \"none\"")
        .replace(s(&models().join("unit_cube.obj")), s(&huge));
    let path = dir.join("fit.toml");
    fs::write(&path, &fit).unwrap();
    let o = run(&["render", s(&path), "-o", s(&dir.join("fit.png"))]);
    assert_ok(&o, "fit_unit_sphere on a huge model");
    let e = render_error(
        &dir,
        "no_fit",
        &fit.replace("fit_unit_sphere = true", ""),
        &[],
    );
    assert!(
        e.contains("huge.obj") && e.contains("fit_unit_sphere"),
        "{e}"
    );
}

#[test]
fn model_messages_name_their_cause() {
    let dir = scratch("model-messages");
    // A garbage OBJ gives the converter's reason, with the file name.
    let garbage = dir.join("garbage.obj");
    fs::write(&garbage, b"v 0 0 0\nv 1 0 0\xff\xfe\nv 0 1 0\nf 1 2 3\n").unwrap();
    let e = render_error(
        &dir,
        "garbage",
        &scene_3d("").replace(s(&models().join("unit_cube.obj")), s(&garbage)),
        &[],
    );
    assert!(
        e.contains("garbage.obj") && e.contains("not UTF-8 text"),
        "{e}"
    );

    // A missing demo model: the path and the operating system's reason.
    let o = run(&[
        "demo",
        "--out",
        s(&dir.join("demo")),
        "--models",
        s(&dir.join("nowhere")),
    ]);
    let e = assert_error(&o, "demo model");
    assert!(e.contains("nowhere") && e.contains("suzanne.obj"), "{e}");
    assert!(e.contains("No such file or directory"), "{e}");
}
