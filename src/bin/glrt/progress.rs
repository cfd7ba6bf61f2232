//! Progress of long work on stderr (indicatif): a bar of the frames done out
//! of those to do, their rate and the time left, redrawn in place; nothing at all when stderr
//! is not a terminal (a log file, a test, a pipe), so output meant for programs stays as it
//! was.

use std::io::IsTerminal;

use glrt::logging::progress;
use indicatif::ProgressBar;

/// Frames done of a known number, shown as a bar.
#[derive(Clone)]
pub struct FrameProgress {
    bar: ProgressBar,
    first: u64,
}

impl FrameProgress {
    /// A bar of frames `first..end` labelled `what`, drawn on stderr when it is a terminal
    /// (`end` is asked for only then: counting frames may read a whole capture).
    pub fn new(what: &str, first: u64, end: impl FnOnce() -> u64) -> FrameProgress {
        let bar = if std::io::stderr().is_terminal() {
            progress::bar(what, end().saturating_sub(first), "frames")
        } else {
            ProgressBar::hidden()
        };
        FrameProgress { bar, first }
    }

    /// Frame `number` is done (frames before `first` are not counted).
    pub fn frame_done(&self, number: u64) {
        if number >= self.first {
            self.bar.inc(1);
        }
    }

    /// Leaves the bar at its last state on its own line.
    pub fn finish(&self) {
        self.bar.finish();
    }
}
