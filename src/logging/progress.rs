//! Progress bars on stderr (indicatif), one look for every long task of glrt (replays, path
//! traced frames, radiosity's precompute): the units done out of the total, the time spent and
//! left, the rate. Whether to draw one (stderr a terminal) is the caller's choice.

use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A bar of `total` `unit`s labelled `what`, drawn on stderr and redrawn every second (time
/// moves on while a step takes long).
pub fn bar(what: &str, total: u64, unit: &str) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    let template = format!("{{msg}} [{{bar:30}}] {{pos}}/{{len}} {unit}, {{elapsed}} elapsed, {{eta}} left ({{per_sec}})");
    let style = ProgressStyle::with_template(&template).expect("a valid template").progress_chars("=> ");
    bar.set_style(style);
    bar.set_message(what.to_owned());
    bar.enable_steady_tick(Duration::from_secs(1));
    bar
}
