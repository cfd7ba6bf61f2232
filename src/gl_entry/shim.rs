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
