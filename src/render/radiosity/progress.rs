//! Progress of the precompute's long stages (form factors, k-bounce products, reordering
//! passes, BC1 blocks) on stderr: a bar with the time left (indicatif) when stderr is a
//! terminal, else a line at each quarter done with the time left, so logs of a game show
//! where the precompute is; either way a last line with the stage's time. Stages are advanced
//! from worker threads ([`Stage::add`] is `Sync`).

use std::io::IsTerminal;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use indicatif::ProgressBar;

use crate::logging::progress;

/// Where a precompute's progress goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    /// Nowhere (tests, the report's repeated compressions).
    Quiet,
    /// Stderr: a bar on a terminal, else lines.
    Stderr,
}

impl Progress {
    /// A stage of `total` `unit`s named `name`.
    pub fn stage(self, name: &str, total: u64, unit: &str) -> Stage {
        let output = match self {
            Progress::Quiet => Output::Quiet,
            Progress::Stderr if std::io::stderr().is_terminal() => Output::Bar(progress::bar(&format!("glrt: radiosity: {name}"), total, unit)),
            Progress::Stderr => Output::Lines,
        };
        Stage { name: name.to_owned(), total, done: AtomicU64::new(0), start: Instant::now(), output }
    }
}

/// How a stage shows itself.
enum Output {
    Quiet,
    Bar(ProgressBar),
    Lines,
}

/// One stage in progress.
pub struct Stage {
    name: String,
    total: u64,
    done: AtomicU64,
    start: Instant,
    output: Output,
}

impl Stage {
    /// `n` more units are done.
    pub fn add(&self, n: u64) {
        let before = self.done.fetch_add(n, Ordering::Relaxed);
        match &self.output {
            Output::Quiet => {}
            Output::Bar(bar) => bar.inc(n),
            Output::Lines => {
                if let Some(line) = quarter_line(&self.name, before, before + n, self.total, self.start.elapsed()) {
                    eprintln!("{line}");
                }
            }
        }
    }

    /// Ends the stage: says how long it took (not when quiet) and returns it.
    pub fn finish(self) -> Duration {
        let t = self.start.elapsed();
        if let Output::Bar(bar) = &self.output {
            bar.finish_and_clear();
        }
        if !matches!(self.output, Output::Quiet) {
            eprintln!("glrt: radiosity: {} in {:.2} s", self.name, t.as_secs_f64());
        }
        t
    }
}

/// The line to log when `done` goes from `before` to `after` of `total` after `elapsed`:
/// one when it crosses a quarter (not the last: [`Stage::finish`] says that), with the time
/// left at the rate so far.
fn quarter_line(name: &str, before: u64, after: u64, total: u64, elapsed: Duration) -> Option<String> {
    let quarter = |d: u64| (4 * d).checked_div(total).unwrap_or(4);
    let q = quarter(after);
    if q == quarter(before) || q >= 4 {
        return None;
    }
    let left = elapsed.as_secs_f64() * (total - after) as f64 / after.max(1) as f64;
    Some(format!("glrt: radiosity: {name}: {}% after {:.1} s, about {left:.0} s left", 25 * q, elapsed.as_secs_f64()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_at_each_quarter_with_the_time_left() {
        let s = Duration::from_secs(3);
        assert_eq!(quarter_line("BC1 blocks", 0, 10, 40, s).as_deref(), Some("glrt: radiosity: BC1 blocks: 25% after 3.0 s, about 9 s left"));
        assert_eq!(quarter_line("x", 10, 11, 40, s), None);
        // A jump over two quarters says the last one crossed.
        assert_eq!(quarter_line("x", 11, 30, 40, s).as_deref(), Some("glrt: radiosity: x: 75% after 3.0 s, about 1 s left"));
        // The end is said by `finish`; nothing to count, nothing said.
        assert_eq!(quarter_line("x", 30, 40, 40, s), None);
        assert_eq!(quarter_line("x", 0, 0, 0, s), None);
        let stage = Progress::Quiet.stage("x", 8, "rows");
        stage.add(3);
        stage.add(5);
        assert_eq!(stage.done.load(Ordering::Relaxed), 8);
        stage.finish();
    }
}
