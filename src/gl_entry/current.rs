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

/// Runs `f` with this thread's current-context slot.
pub fn with_slot<R>(f: impl FnOnce(&mut Option<Current>) -> R) -> R {
    CURRENT.with(|slot| f(&mut slot.borrow_mut()))
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
