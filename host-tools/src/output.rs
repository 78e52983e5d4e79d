//! Writing output files so that a failure never costs the user a file.
//!
//! Every command that writes a file goes through [`OutputFile`]. A regular file (new or existing)
//! is written to a temporary file in the same directory and renamed over the target only once it
//! is complete and synced, so a full disk or a write limit leaves the old file as it was and no
//! temporary file behind. A symbolic link is followed and its target replaced (the link stays);
//! a device node, FIFO or socket is written in place and never removed. An output that is one of
//! the command's inputs (same device and inode, however it is spelt) is refused before anything
//! is written. `-` is standard output, written in place; a reader that goes away (a closed pipe)
//! ends it quietly, as [`crate::console`] does for messages.
//!
//! Whether a path is a device is asked of the path itself (the kernel follows its links):
//! `/dev/stdout` links to `/proc/self/fd/1`, which links to `pipe:[N]`, a name that exists
//! nowhere, so following the links by hand would take a pipe for a new file in `/proc`.

use std::fmt;
use std::fs::{self, File, OpenOptions, Permissions};
use std::io::{self, BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

/// Why an output could not be written: `cannot write PATH: CAUSE`.
#[derive(Debug)]
pub struct OutputError {
    /// The output as the user named it.
    pub path: PathBuf,
    /// What went wrong.
    pub message: String,
}

impl fmt::Display for OutputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot write {}: {}", self.path.display(), self.message)
    }
}

impl std::error::Error for OutputError {}

/// Where the bytes go.
enum Sink {
    /// A temporary file beside `target`, renamed over it when finished.
    Replace {
        target: PathBuf,
        tmp: PathBuf,
        file: BufWriter<File>,
        /// The permissions of the file being replaced, given to its successor.
        mode: Option<Permissions>,
    },
    /// A device, FIFO, socket or standard output: written in place.
    Direct(BufWriter<Box<dyn Write>>),
}

/// True for the output `-`: standard output.
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// True when `path` is standard output however it is named (`-`, `/dev/stdout`, or the file
/// stdout is redirected to): messages must then go to stderr, or they would corrupt the data.
pub fn goes_to_stdout(path: &Path) -> bool {
    is_stdout(path) || same_file(path, Path::new("/dev/stdout"))
}

/// Checks an output before the work: it must not be one of `inputs`, and its extension must
/// name the format the command writes. `accepted` are the extensions of that format (lower
/// case, without the dot); `format` names it for the message, `hint` says what else the user
/// can do. A path without an extension (`-`, a device, a FIFO) is taken as it is: the
/// command's format is the only one it could mean.
///
/// # Errors
/// An [`OutputError`] naming the path and the input, or the format and the extensions accepted.
pub fn check_output(
    path: &Path,
    inputs: &[&Path],
    accepted: &[&str],
    format: &str,
    hint: &str,
) -> Result<(), OutputError> {
    // First, as the graver mistake: a scene named as its own output has a wrong extension too.
    refuse_input(path, inputs)?;
    let Some(ext) = path.extension() else {
        return Ok(());
    };
    let ext = ext.to_string_lossy();
    if accepted.iter().any(|a| ext.eq_ignore_ascii_case(a)) {
        return Ok(());
    }
    let list: Vec<String> = accepted.iter().map(|a| format!(".{a}")).collect();
    Err(OutputError {
        path: path.to_path_buf(),
        message: format!(
            "this writes {format}, but the extension is .{ext}; accepted: {}{hint}",
            list.join(", ")
        ),
    })
}

/// An output being written. Implements [`Write`]; nothing is visible at the output path until
/// [`OutputFile::commit`] (or [`OutputFile::finish`] and [`Pending::commit`]). Dropping it
/// unfinished removes the temporary file.
pub struct OutputFile {
    shown: PathBuf,
    sink: Option<Sink>,
    /// The first write error, kept because encoders often replace it with a vaguer one.
    first_error: Option<io::Error>,
}

/// A finished output waiting to be renamed into place (its file is closed). Dropping it
/// uncommitted removes the temporary file, so a set of outputs can be committed all or none.
pub struct Pending {
    shown: PathBuf,
    rename: Option<(PathBuf, PathBuf)>,
}

/// Follows symbolic links (relative ones from their own directory) to the path that is really
/// written. The result need not exist.
fn resolve_links(path: &Path) -> io::Result<PathBuf> {
    let mut p = path.to_path_buf();
    // The kernel's own limit on links followed in one lookup.
    for _ in 0..40 {
        match fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let link = fs::read_link(&p)?;
                p = match p.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
            }
            _ => return Ok(p),
        }
    }
    Err(io::Error::other("too many levels of symbolic links"))
}

/// True when `a` and `b` are the same existing file.
fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        match (fs::metadata(a), fs::metadata(b)) {
            (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        match (fs::canonicalize(a), fs::canonicalize(b)) {
            (Ok(x), Ok(y)) => x == y,
            _ => false,
        }
    }
}

/// A temporary file in `dir` named after `name`, created exclusively so nothing is clobbered.
fn create_temp(dir: &Path, name: &str) -> io::Result<(PathBuf, File)> {
    static COUNTER: AtomicU32 = AtomicU32::new(0);
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let tmp = dir.join(format!(".{name}.{}.{n}.tmp", std::process::id()));
        match OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(f) => return Ok((tmp, f)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && n < 1000 => continue,
            Err(e) => return Err(e),
        }
    }
}

/// An output that is one of the inputs (same device and inode) is refused.
fn refuse_input(path: &Path, inputs: &[&Path]) -> Result<(), OutputError> {
    match inputs.iter().find(|i| same_file(path, i)) {
        Some(input) => Err(OutputError {
            path: path.to_path_buf(),
            message: format!("it is the input {}; choose another output", input.display()),
        }),
        None => Ok(()),
    }
}

impl OutputFile {
    /// Prepares to write `path`. `inputs` are the files the command reads; an output that is one
    /// of them is refused.
    ///
    /// # Errors
    /// An [`OutputError`] naming `path`: it is an input or a directory, or no temporary file can
    /// be created beside it (or, for a device, it cannot be opened).
    pub fn create(path: &Path, inputs: &[&Path]) -> Result<Self, OutputError> {
        let fail = |message: String| OutputError {
            path: path.to_path_buf(),
            message,
        };
        if is_stdout(path) {
            // A picture on a terminal is only noise, and likely a forgotten redirection.
            if io::stdout().is_terminal() {
                return Err(fail(
                    "standard output is a terminal; redirect it to a file or a pipe".into(),
                ));
            }
            return Ok(Self {
                shown: path.to_path_buf(),
                sink: Some(Sink::Direct(BufWriter::new(Box::new(
                    crate::console::Stdout,
                )))),
                first_error: None,
            });
        }
        refuse_input(path, inputs)?;
        // The kernel follows the links here (see the module's comment on /dev/stdout).
        match fs::metadata(path) {
            Ok(m) if m.is_dir() => return Err(fail("it is a directory".into())),
            Ok(m) if !m.is_file() => {
                let file = OpenOptions::new()
                    .write(true)
                    .open(path)
                    .map_err(|e| fail(e.to_string()))?;
                return Ok(Self {
                    shown: path.to_path_buf(),
                    sink: Some(Sink::Direct(BufWriter::new(Box::new(file)))),
                    first_error: None,
                });
            }
            _ => {}
        }
        let target = resolve_links(path).map_err(|e| fail(e.to_string()))?;
        let sink = match fs::metadata(&target) {
            Ok(m) if m.is_dir() => return Err(fail("it is a directory".into())),
            existing => {
                let name = target
                    .file_name()
                    .ok_or_else(|| fail("the path names no file".into()))?
                    .to_string_lossy()
                    .into_owned();
                let dir = match target.parent() {
                    Some(d) if !d.as_os_str().is_empty() => d,
                    _ => Path::new("."),
                };
                let (tmp, file) = create_temp(dir, &name).map_err(|e| {
                    fail(format!(
                        "cannot create a temporary file in {}: {e}",
                        dir.display()
                    ))
                })?;
                Sink::Replace {
                    target,
                    tmp,
                    file: BufWriter::new(file),
                    mode: existing.ok().map(|m| m.permissions()),
                }
            }
        };
        Ok(Self {
            shown: path.to_path_buf(),
            sink: Some(sink),
            first_error: None,
        })
    }

    /// The output as the user named it.
    pub fn path(&self) -> &Path {
        &self.shown
    }

    /// An error for this output: the first write error if there was one (an encoder's own
    /// message often hides it), else `cause`.
    pub fn error(&mut self, cause: impl fmt::Display) -> OutputError {
        OutputError {
            path: self.shown.clone(),
            message: match self.first_error.take() {
                Some(e) => e.to_string(),
                None => cause.to_string(),
            },
        }
    }

    /// Flushes and closes the file (syncing a temporary file, so a full disk shows now and not
    /// after the rename); the result still has to be committed.
    ///
    /// # Errors
    /// An [`OutputError`]; the temporary file is removed then.
    pub fn finish(mut self) -> Result<Pending, OutputError> {
        // A write that failed is fatal even when the writer carried on: some encoders ignore
        // errors on their last writes (a GIF's trailer is written on drop).
        if let Some(e) = self.first_error.take() {
            return Err(OutputError {
                path: self.shown.clone(),
                message: e.to_string(),
            });
        }
        let sink = self.sink.take();
        let result = match sink {
            None => Ok(None),
            Some(Sink::Direct(mut w)) => w.flush().map(|()| None),
            Some(Sink::Replace {
                target,
                tmp,
                file,
                mode,
            }) => {
                let done = file
                    .into_inner()
                    .map_err(io::IntoInnerError::into_error)
                    .and_then(|f| {
                        f.sync_all()?;
                        if let Some(mode) = mode {
                            f.set_permissions(mode)?;
                        }
                        Ok(())
                    });
                match done {
                    Ok(()) => Ok(Some((tmp, target))),
                    Err(e) => {
                        let _ = fs::remove_file(&tmp);
                        Err(e)
                    }
                }
            }
        };
        match result {
            Ok(rename) => Ok(Pending {
                shown: self.shown.clone(),
                rename,
            }),
            Err(e) => {
                let e = self.first_error.take().unwrap_or(e);
                Err(OutputError {
                    path: self.shown.clone(),
                    message: e.to_string(),
                })
            }
        }
    }

    /// [`OutputFile::finish`], then [`Pending::commit`].
    ///
    /// # Errors
    /// An [`OutputError`]; the old file (if any) is untouched and no temporary file is left.
    pub fn commit(self) -> Result<(), OutputError> {
        self.finish()?.commit()
    }

    fn writer(&mut self) -> io::Result<&mut dyn Write> {
        match &mut self.sink {
            Some(Sink::Replace { file, .. }) => Ok(file),
            Some(Sink::Direct(file)) => Ok(file),
            None => Err(io::Error::other("the output is already finished")),
        }
    }

    fn note<T>(&mut self, r: io::Result<T>) -> io::Result<T> {
        if let Err(e) = &r {
            if self.first_error.is_none() && e.kind() != io::ErrorKind::Interrupted {
                self.first_error = Some(io::Error::new(e.kind(), e.to_string()));
            }
        }
        r
    }
}

impl Write for OutputFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let r = self.writer().and_then(|w| w.write(buf));
        self.note(r)
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        let r = self.writer().and_then(|w| w.write_all(buf));
        self.note(r)
    }

    fn flush(&mut self) -> io::Result<()> {
        let r = self.writer().and_then(|w| w.flush());
        self.note(r)
    }
}

impl Drop for OutputFile {
    fn drop(&mut self) {
        if let Some(Sink::Replace { tmp, .. }) = &self.sink {
            let _ = fs::remove_file(tmp);
        }
    }
}

impl Pending {
    /// Renames the finished file over its target.
    ///
    /// # Errors
    /// An [`OutputError`]; the temporary file is removed then.
    pub fn commit(mut self) -> Result<(), OutputError> {
        if let Some((tmp, target)) = self.rename.take() {
            if let Err(e) = fs::rename(&tmp, &target) {
                let _ = fs::remove_file(&tmp);
                return Err(OutputError {
                    path: self.shown.clone(),
                    message: e.to_string(),
                });
            }
        }
        Ok(())
    }
}

impl Drop for Pending {
    fn drop(&mut self) {
        if let Some((tmp, _)) = &self.rename {
            let _ = fs::remove_file(tmp);
        }
    }
}

/// Writes one output: `fill` writes the bytes, then the file is committed.
///
/// # Errors
/// An [`OutputError`] naming `path` with the first cause (the operating system's, when a write
/// failed); the old file is untouched and no temporary file is left.
pub fn write_output<E: fmt::Display>(
    path: &Path,
    inputs: &[&Path],
    fill: impl FnOnce(&mut OutputFile) -> Result<(), E>,
) -> Result<(), OutputError> {
    let mut out = OutputFile::create(path, inputs)?;
    if let Err(e) = fill(&mut out) {
        return Err(out.error(e));
    }
    out.commit()
}

/// Writes 8-bit RGB pixels (`width * height * 3` bytes, rows top down) as a PNG, streamed from
/// the buffer through the encoder into the file.
///
/// # Errors
/// As [`write_output`].
pub fn write_png(
    path: &Path,
    inputs: &[&Path],
    width: u32,
    height: u32,
    rgb: &[u8],
) -> Result<(), OutputError> {
    write_output(path, inputs, |w| encode_png(w, width, height, rgb))
}

/// Encodes 8-bit RGB pixels as a PNG into `w`, with the settings of the simulator's own
/// `save_png` (best compression), so the pictures are byte for byte what it wrote.
///
/// # Errors
/// The encoder's error (a write failure, or a buffer of the wrong size).
pub fn encode_png(
    w: impl Write,
    width: u32,
    height: u32,
    rgb: &[u8],
) -> Result<(), image::ImageError> {
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    use image::ImageEncoder;
    PngEncoder::new_with_quality(w, CompressionType::Best, FilterType::default()).write_image(
        rgb,
        width,
        height,
        image::ExtendedColorType::Rgb8,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("host-tools-output-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn failed_fill_keeps_the_old_file_and_no_temporary() {
        let dir = scratch("fail");
        let path = dir.join("a.png");
        fs::write(&path, b"old").unwrap();
        let r = write_output(&path, &[], |w| {
            w.write_all(b"half")?;
            Err::<(), io::Error>(io::Error::other("encoder broke"))
        });
        assert!(r.unwrap_err().to_string().contains("encoder broke"));
        assert_eq!(fs::read(&path).unwrap(), b"old");
        assert_eq!(names(&dir), ["a.png"]);
    }

    #[test]
    fn an_ignored_write_error_still_fails_the_output() {
        let dir = scratch("ignored");
        let path = dir.join("c");
        fs::write(&path, b"old").unwrap();
        let mut out = OutputFile::create(&path, &[]).unwrap();
        let e = io::Error::new(io::ErrorKind::StorageFull, "disk full");
        let _ = out.note::<()>(Err(e));
        assert!(out.commit().unwrap_err().to_string().contains("disk full"));
        assert_eq!(fs::read(&path).unwrap(), b"old");
        assert_eq!(names(&dir), ["c"]);
    }

    #[test]
    fn an_output_that_is_an_input_is_refused() {
        let dir = scratch("input");
        let input = dir.join("in.obj");
        fs::write(&input, b"v 0 0 0").unwrap();
        let spelt = dir.join(".").join("in.obj");
        let e = OutputFile::create(&spelt, &[&input]).err().unwrap();
        assert!(e.to_string().contains("it is the input"), "{e}");
    }

    #[test]
    fn uncommitted_pending_files_are_removed() {
        let dir = scratch("pending");
        let mut out = OutputFile::create(&dir.join("b"), &[]).unwrap();
        out.write_all(b"data").unwrap();
        drop(out.finish().unwrap());
        assert!(names(&dir).is_empty());
    }

    #[test]
    fn relative_links_resolve_from_their_directory() {
        let dir = scratch("links");
        fs::create_dir_all(dir.join("sub")).unwrap();
        std::os::unix::fs::symlink("sub/t", dir.join("l1")).unwrap();
        std::os::unix::fs::symlink("l1", dir.join("l2")).unwrap();
        assert_eq!(resolve_links(&dir.join("l2")).unwrap(), dir.join("sub/t"));
        std::os::unix::fs::symlink("loop", dir.join("loop")).unwrap();
        assert!(resolve_links(&dir.join("loop")).is_err());
    }
}
