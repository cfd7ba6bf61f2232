//! Progress of long work on stderr (indicatif): a bar of the frames (or other units) done out
//! of those to do, their rate and the time left, redrawn in place; nothing at all when stderr
//! is not a terminal (a log file, a test, a pipe), so output meant for programs stays as it
//! was.

use std::io::IsTerminal;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

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
        FrameProgress { bar: counted(what, "frames", || end().saturating_sub(first)), first }
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

/// A bar of `len()` `unit` labelled `what` on stderr when it is a terminal, else hidden.
pub fn counted(what: &str, unit: &str, len: impl FnOnce() -> u64) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(len()), ProgressDrawTarget::stderr());
    let template = format!("{{msg}} [{{bar:30}}] {{pos}}/{{len}} {unit}, {{elapsed}} elapsed, {{eta}} left ({{per_sec}})");
    let style = ProgressStyle::with_template(&template).expect("a valid template").progress_chars("=> ");
    bar.set_style(style);
    bar.set_message(what.to_owned());
    // Redrawn every second while a step takes long (path tracing on a CPU): time moves on.
    bar.enable_steady_tick(Duration::from_secs(1));
    bar
}
