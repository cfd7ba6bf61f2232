//! What every generated export does: catch panics so none crosses the C ABI, find the current
//! context, call into `translate`; and the behaviour of functions glrt does not implement.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};

use super::current::with_current_slot;
use crate::translate::Context;
use crate::translate::convert::ReturnDefault;
use crate::translate::gl;

/// An exported function's address, for the `glXGetProcAddress` table.
#[derive(Clone, Copy)]
pub struct Proc(pub *const ());

// Safety: the pointers are addresses of functions, immutable for the life of the program.
unsafe impl Sync for Proc {}

/// Calls `f` on the current context. Without a current context the call does nothing (GLX
/// 1.4, 3.3.7) and returns zero; a panic is caught, logged once, and marks the context broken.
/// A GL call made while another runs on the same thread (re-entry) does nothing either.
#[inline(always)]
pub fn with_current<R: ReturnDefault>(name: &'static str, f: impl FnOnce(&mut Context) -> R) -> R {
    with_current_slot(|cur| match catch_unwind(AssertUnwindSafe(|| f(&mut cur.context))) {
        Ok(value) => Some(value),
        Err(_) => {
            log::error!("internal error in {name}; this context ignores further GL calls");
            cur.broken = true;
            None
        }
    })
    .unwrap_or_else(R::return_default)
}

static MISSING_LOGGED: [AtomicBool; super::exports::MISSING_COUNT] =
    [const { AtomicBool::new(false) }; super::exports::MISSING_COUNT];

/// A function glrt exports but does not implement: logs its name once, raises
/// `GL_INVALID_OPERATION` on the current context, returns zero.
pub fn missing<R: ReturnDefault>(index: usize, name: &'static str) -> R {
    if !MISSING_LOGGED[index].swap(true, Ordering::Relaxed) {
        log::warn!("{name} is not implemented");
    }
    if !name.starts_with("glX") {
        with_current(name, |ctx| ctx.set_error_in(gl::GL_INVALID_OPERATION, name));
    }
    R::return_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gl_entry::current::{SharedContext, current_handle, make_current};
    use parking_lot::Mutex;
    use std::sync::Arc;

    /// Runs `test` on a fresh thread (its own current-context slot), with a context current
    /// under handle 9.
    fn on_thread_with_context(test: impl FnOnce() + Send + 'static) {
        std::thread::spawn(move || {
            let ctx: SharedContext = Arc::new(Mutex::new(Context::with_recording().0));
            assert!(make_current(9, Some(&ctx)));
            test();
        })
        .join()
        .expect("the test thread did not panic");
    }

    #[test]
    fn without_a_current_context_nothing_runs_and_zero_comes_back() {
        std::thread::spawn(|| {
            let mut ran = false;
            assert_eq!(with_current("glGetError", |_| { ran = true; 7u32 }), 0);
            assert!(!ran);
        })
        .join()
        .expect("no panic");
    }

    #[test]
    fn calls_reach_the_current_context() {
        on_thread_with_context(|| {
            with_current("glMatrixMode", |ctx| ctx.set_error_in(gl::GL_INVALID_ENUM, "test"));
            assert_eq!(with_current("glGetError", |ctx| ctx.glGetError()), gl::GL_INVALID_ENUM);
            assert_eq!(with_current("glGetError", |ctx| ctx.glGetError()), gl::GL_NO_ERROR);
        });
    }

    #[test]
    fn a_panic_breaks_the_context_and_later_calls_do_nothing() {
        on_thread_with_context(|| {
            let value: u32 = with_current("glFlush", |_| panic!("internal error for the test"));
            assert_eq!(value, 0);
            let mut ran = false;
            assert_eq!(with_current("glGetError", |_| { ran = true; 7u32 }), 0);
            assert!(!ran, "a broken context takes no more calls");
            assert_eq!(current_handle(), 9, "it stays current until released");
            assert!(make_current(0, None));
            assert_eq!(current_handle(), 0);
        });
    }

    #[test]
    fn a_call_made_during_a_call_does_nothing() {
        on_thread_with_context(|| {
            let mut inner_ran = false;
            let outer = with_current("glFlush", |_| {
                assert_eq!(with_current("glGetError", |_| { inner_ran = true; 7u32 }), 0);
                5u32
            });
            assert_eq!(outer, 5);
            assert!(!inner_ran);
            assert_eq!(with_current("glGetError", |_| 6u32), 6, "the context still works");
        });
    }
}
