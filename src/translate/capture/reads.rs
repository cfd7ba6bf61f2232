//! Which client memory a GL call read: the places in `translate` that read program memory
//! report each range with [`note`]; while a collection is open on the thread ([`collect`]),
//! the ranges are kept, and merged when it closes. With no collection enabled anywhere in the
//! process a report costs one relaxed atomic load.
//!
//! Reads of glrt's own copies (display-list data, buffer object stores) are not client
//! memory: they are not reported, and [`quiet`] silences reports while a display list runs.

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};

/// Whether any thread may collect (set once capture starts; never cleared).
static ENABLED: AtomicBool = AtomicBool::new(false);

/// This thread's open collection.
#[derive(Default)]
struct Collector {
    open: bool,
    /// Nesting depth of [`quiet`] guards.
    quiet: u32,
    /// `(address, length)` as reported.
    ranges: Vec<(usize, usize)>,
}

thread_local! {
    static COLLECTOR: RefCell<Collector> = RefCell::new(Collector::default());
}

/// Allows collections in this process (the first capture or summary turns it on).
pub fn enable() {
    ENABLED.store(true, Ordering::Relaxed);
}

/// Whether reports may be kept anywhere in the process: callers that would report many
/// ranges (an array's elements, one by one) test this once instead of per [`note`].
#[inline]
pub fn enabled() -> bool {
    ENABLED.load(Ordering::Relaxed)
}

/// Reports that the current GL call read `len` bytes of client memory at `ptr`.
#[inline]
pub fn note<T>(ptr: *const T, len: usize) {
    if ENABLED.load(Ordering::Relaxed) {
        note_slow(ptr as usize, len);
    }
}

#[cold]
fn note_slow(address: usize, len: usize) {
    if len == 0 || address == 0 {
        return;
    }
    let _ = COLLECTOR.try_with(|c| {
        if let Ok(mut c) = c.try_borrow_mut()
            && c.open
            && c.quiet == 0
        {
            c.ranges.push((address, len));
        }
    });
}

/// Silences [`note`] on this thread while the guard lives (a display list runs: it reads
/// glrt's copies, not client memory).
pub fn quiet() -> Quiet {
    if ENABLED.load(Ordering::Relaxed) {
        let _ = COLLECTOR.try_with(|c| c.borrow_mut().quiet += 1);
        Quiet(true)
    } else {
        Quiet(false)
    }
}

/// Guard of [`quiet`].
pub struct Quiet(bool);

impl Drop for Quiet {
    fn drop(&mut self) {
        if self.0 {
            let _ = COLLECTOR.try_with(|c| c.borrow_mut().quiet -= 1);
        }
    }
}

/// Opens a collection on this thread; false (and nothing is collected) when one is already
/// open (a nested call). Each `true` must be followed by [`close`].
pub fn open() -> bool {
    enable();
    COLLECTOR.try_with(|c| c.try_borrow_mut().is_ok_and(|mut c| !std::mem::replace(&mut c.open, true))).unwrap_or(false)
}

/// Closes this thread's collection: the ranges reported since [`open`], sorted, with
/// overlapping and adjacent ranges joined.
pub fn close() -> Vec<(usize, usize)> {
    COLLECTOR
        .try_with(|c| {
            let mut c = c.borrow_mut();
            c.open = false;
            merge(std::mem::take(&mut c.ranges))
        })
        .unwrap_or_default()
}

/// Runs `f` collecting the client memory it reads: its result and the merged ranges (none
/// when a collection is already open on the thread). For summaries such as the call log's.
pub fn collect<R>(f: impl FnOnce() -> R) -> (R, Vec<(usize, usize)>) {
    if !open() {
        return (f(), Vec::new());
    }
    let result = f();
    (result, close())
}

/// Sorts ranges and joins those that overlap or touch.
fn merge(mut ranges: Vec<(usize, usize)>) -> Vec<(usize, usize)> {
    ranges.sort_unstable();
    let mut out: Vec<(usize, usize)> = Vec::with_capacity(ranges.len());
    for (start, len) in ranges {
        let end = start.saturating_add(len);
        match out.last_mut() {
            Some((s, l)) if start <= *s + *l => *l = (*l).max(end - *s),
            _ => out.push((start, len)),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_merge_when_they_overlap_or_touch() {
        assert_eq!(merge(vec![(100, 4), (96, 4), (200, 8), (104, 2), (202, 2)]), vec![(96, 10), (200, 8)]);
    }

    #[test]
    fn only_an_open_unsilenced_collection_keeps_reports() {
        let data = [1u8; 16];
        note(data.as_ptr(), 16);
        let ((), ranges) = collect(|| {
            note(data.as_ptr(), 4);
            note(data.as_ptr().wrapping_add(8), 4);
            let _q = quiet();
            note(data.as_ptr().wrapping_add(12), 4);
        });
        assert_eq!(ranges, vec![(data.as_ptr() as usize, 4), (data.as_ptr() as usize + 8, 4)]);
        let (nested, outer) = collect(|| collect(|| note(data.as_ptr(), 1)).1);
        assert!(nested.is_empty(), "a nested collection collects nothing");
        assert_eq!(outer, vec![(data.as_ptr() as usize, 1)], "the outer one keeps the read");
    }
}
