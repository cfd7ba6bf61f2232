//! What the exports do besides glrt's own work: write the call log (`GLRT_TRACE`,
//! [`super::call_log`]) and forward every call to another OpenGL library (`GLRT_PASSTHROUGH`,
//! [`super::passthrough`]).
//!
//! Both are read from the environment at the first GL or GLX call and kept in one byte, so an
//! export whose program uses neither pays one relaxed atomic load ([`special`]) before its
//! usual work.

use std::cell::Cell;
use std::sync::atomic::{AtomicU8, Ordering};

/// The call log is on.
const TRACE: u8 = 1;
/// Calls are forwarded to another library.
const PASSTHROUGH: u8 = 2;
/// The environment is not read yet.
const UNREAD: u8 = 4;
/// A thread is reading the environment (and opening the log and the library).
const READING: u8 = 8;

static MODE: AtomicU8 = AtomicU8::new(UNREAD);

thread_local! {
    /// Set on the thread that reads the environment: a GL call it makes meanwhile (a library
    /// being loaded may call one) runs as plain.
    static READER: Cell<bool> = const { Cell::new(false) };
}

/// The modes on for a call: logging, forwarding, or both.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mode(u8);

impl Mode {
    /// Whether the call log is on.
    pub fn tracing(self) -> bool {
        self.0 & TRACE != 0
    }

    /// Whether calls go to another library instead of glrt.
    pub fn passthrough(self) -> bool {
        self.0 & PASSTHROUGH != 0
    }
}

/// The modes on, `None` when neither is (the exports' fast path: one relaxed load).
#[inline(always)]
pub fn special() -> Option<Mode> {
    match MODE.load(Ordering::Relaxed) {
        0 => None,
        mode => special_slow(mode),
    }
}

#[cold]
fn special_slow(mode: u8) -> Option<Mode> {
    let mode = if mode & (UNREAD | READING) != 0 { read_environment() } else { mode };
    (mode != 0).then_some(Mode(mode))
}

/// Reads `GLRT_TRACE` and `GLRT_PASSTHROUGH` once (the first caller does; others wait for it)
/// and returns the resulting modes. The reading thread's own calls meanwhile run as plain.
fn read_environment() -> u8 {
    if READER.with(Cell::get) {
        return 0;
    }
    if MODE.compare_exchange(UNREAD, READING, Ordering::Acquire, Ordering::Relaxed).is_ok() {
        READER.with(|r| r.set(true));
        let mut mode = 0;
        if super::call_log::open_from_environment() {
            mode |= TRACE;
        }
        if super::passthrough::open_from_environment() {
            mode |= PASSTHROUGH;
        }
        READER.with(|r| r.set(false));
        MODE.store(mode, Ordering::Release);
        return mode;
    }
    loop {
        match MODE.load(Ordering::Acquire) {
            READING => std::thread::yield_now(),
            mode => return mode,
        }
    }
}

/// Turns the call log off (its file could not be written); true when it was on.
pub fn stop_tracing() -> bool {
    MODE.fetch_and(!TRACE, Ordering::Relaxed) & TRACE != 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mode_bits() {
        assert!(Mode(TRACE).tracing() && !Mode(TRACE).passthrough());
        assert!(Mode(PASSTHROUGH).passthrough() && !Mode(PASSTHROUGH).tracing());
        assert!(Mode(TRACE | PASSTHROUGH).tracing() && Mode(TRACE | PASSTHROUGH).passthrough());
    }
}
