//! The progress bar of the commands that can take more than a moment (`convert` of a large
//! model, `animate`, `accuracy`): one look for all of them, on stderr, drawn only when stderr is
//! a terminal, so logs and pipes never see it.

use indicatif::{ProgressBar, ProgressStyle};
use std::borrow::Cow;
use std::io::IsTerminal;

/// A progress bar on stderr, or nothing (all methods do nothing then).
pub struct Progress(Option<ProgressBar>);

impl Progress {
    /// A bar when `wanted` and stderr is a terminal.
    pub fn new(wanted: bool) -> Self {
        Self((wanted && std::io::stderr().is_terminal()).then(|| {
            let bar = ProgressBar::new(0);
            bar.set_style(
                ProgressStyle::with_template("{msg:>14} [{bar:40}] {percent:>3}%")
                    .unwrap_or_else(|_| ProgressStyle::default_bar())
                    .progress_chars("=> "),
            );
            bar
        }))
    }

    /// A new stage of `len` steps begins.
    pub fn stage(&self, message: impl Into<Cow<'static, str>>, len: u64) {
        if let Some(bar) = &self.0 {
            // Length first: a message drawn with the old length would flash a wrong percentage.
            bar.set_length(len.max(1));
            bar.set_position(0);
            bar.set_message(message);
        }
    }

    /// The position within the stage.
    pub fn set(&self, pos: u64) {
        if let Some(bar) = &self.0 {
            bar.set_position(pos);
        }
    }

    /// One more step done.
    pub fn inc(&self) {
        if let Some(bar) = &self.0 {
            bar.inc(1);
        }
    }

    /// Removes the bar (done or failed: an error line follows on a clean line).
    pub fn finish(&self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}

impl Drop for Progress {
    /// An early return (`?`) leaves no bar behind the error line.
    fn drop(&mut self) {
        self.finish();
    }
}

impl fixtures::obj::Progress for Progress {
    fn stage(&self, message: &'static str, len: u64) {
        Progress::stage(self, message, len);
    }

    fn set(&self, pos: u64) {
        Progress::set(self, pos);
    }
}
