//! Logging to standard error, enabled by `GLRT_LOG=error|warn|info|debug|trace` (off when
//! unset). Installed once, when the first context is created.

pub mod progress;

use std::sync::Once;

use log::{Level, LevelFilter, Log, Metadata, Record};

struct Stderr;

impl Log for Stderr {
    fn enabled(&self, metadata: &Metadata) -> bool {
        metadata.level() <= log::max_level()
    }

    fn log(&self, record: &Record) {
        if self.enabled(record.metadata()) {
            eprintln!("glrt {}: {}", record.level(), record.args());
        }
    }

    fn flush(&self) {}
}

/// The level `GLRT_LOG` names (`None` when unset or unknown).
fn level_from(value: &str) -> Option<LevelFilter> {
    value.parse::<Level>().ok().map(|l| l.to_level_filter())
}

/// Installs the logger when `GLRT_LOG` names a level and no other logger is installed.
pub fn init() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let Some(level) = std::env::var("GLRT_LOG").ok().as_deref().and_then(level_from) else { return };
        if log::set_logger(&Stderr).is_ok() {
            log::set_max_level(level);
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_parse_case_insensitively() {
        assert_eq!(level_from("warn"), Some(LevelFilter::Warn));
        assert_eq!(level_from("DEBUG"), Some(LevelFilter::Debug));
        assert_eq!(level_from("loud"), None);
    }
}
