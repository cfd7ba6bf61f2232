//! The current context of each thread. A context is current on at most one thread; while it
//! is, that thread holds its lock, so a GL call costs a thread-local lookup, not a lock.

use std::cell::RefCell;
use std::sync::Arc;

use parking_lot::{Mutex, RawMutex, lock_api::ArcMutexGuard};

use crate::translate::Context;

/// A context as the window-system layer owns it.
pub type SharedContext = Arc<Mutex<Context>>;

/// The current context of this thread: its handle (as given to the application) and the lock.
pub struct Current {
    /// The application-visible handle (`GLXContext`).
    pub handle: usize,
    /// The context, locked for this thread.
    pub context: ArcMutexGuard<RawMutex, Context>,
    /// Set after a panic inside a GL call: the context's state may be inconsistent, so later
    /// calls do nothing.
    pub broken: bool,
}

thread_local! {
    static CURRENT: RefCell<Option<Current>> = const { RefCell::new(None) };
}

/// Runs `f` with this thread's current-context slot. Once the thread's storage is destroyed
/// (at `exit`, glibc runs thread-local destructors before `atexit` handlers, and handlers such
/// as waffle's teardown still call `glXMakeCurrent`), the slot reads as empty: the context it
/// held was released when the slot was dropped.
pub(crate) fn with_slot<R>(f: impl FnOnce(&mut Option<Current>) -> R) -> R {
    let mut f = Some(f);
    let ran = CURRENT.try_with(|slot| f.take().map(|f| f(&mut slot.borrow_mut())));
    match (ran, f) {
        (Ok(Some(result)), _) => result,
        (_, Some(f)) => f(&mut None),
        (_, None) => unreachable!("the closure ran but returned nothing"),
    }
}

/// Whether this thread's current context is compiling a display list (what a capture's
/// frame range asks of each drawing command: `translate::capture::begin`).
pub fn compiling_list() -> bool {
    with_slot(|slot| slot.as_ref().is_some_and(|c| c.context.lists.compiling()))
}

/// Runs `f` with this thread's current context when there is one that is not broken and no
/// other call is using it (re-entry); otherwise returns `None`. The GL calls' path: one
/// thread-local access, no allocation.
#[inline(always)]
pub fn with_current_slot<R>(f: impl FnOnce(&mut Current) -> Option<R>) -> Option<R> {
    CURRENT
        .try_with(|slot| {
            let mut slot = slot.try_borrow_mut().ok()?;
            slot.as_mut().filter(|cur| !cur.broken).and_then(f)
        })
        .ok()
        .flatten()
}

/// Makes `context` (with application handle `handle`) current on this thread, releasing the
/// previous one; `None` releases only. Returns false when `context` is current on another
/// thread (GLX `BadAccess`).
pub fn make_current(handle: usize, context: Option<&SharedContext>) -> bool {
    with_slot(|slot| {
        if let (Some(cur), Some(ctx)) = (slot.as_ref(), context)
            && Arc::ptr_eq(ArcMutexGuard::mutex(&cur.context), ctx) {
                slot.as_mut().unwrap().handle = handle;
                return true;
            }
        let Some(ctx) = context else {
            *slot = None;
            return true;
        };
        let Some(guard) = ctx.try_lock_arc() else { return false };
        *slot = Some(Current { handle, context: guard, broken: false });
        true
    })
}

/// The handle of this thread's current context, 0 when none.
pub fn current_handle() -> usize {
    with_slot(|slot| slot.as_ref().map_or(0, |c| c.handle))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// What `current_handle` returned from a destructor run after the slot was destroyed.
    static SEEN_AT_EXIT: AtomicUsize = AtomicUsize::new(usize::MAX);

    struct AtExit;
    impl Drop for AtExit {
        fn drop(&mut self) {
            SEEN_AT_EXIT.store(current_handle(), Ordering::SeqCst);
        }
    }

    thread_local! {
        static PROBE: AtExit = const { AtExit };
    }

    #[test]
    fn slot_reads_empty_after_thread_storage_is_destroyed() {
        std::thread::spawn(|| {
            // Registered before the slot, so destroyed after it (reverse order).
            PROBE.with(|_| {});
            let ctx: SharedContext = Arc::new(Mutex::new(Context::with_recording().0));
            assert!(make_current(7, Some(&ctx)));
            assert_eq!(current_handle(), 7);
        })
        .join()
        .expect("no panic at thread exit");
        assert_eq!(SEEN_AT_EXIT.load(Ordering::SeqCst), 0);
    }
}
