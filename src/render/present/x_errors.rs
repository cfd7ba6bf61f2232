//! The X error trap of the whole library. Xlib has one error handler per process, and its
//! default one exits the program, so glrt's own requests that may fail (a drawable the
//! application already destroyed, a shared-memory segment a remote server refuses, a font
//! that does not exist) run inside [`trapped`] or [`trapped_reply`]: their errors are kept
//! from the application and returned. The GLX layer and the presenters share this one trap
//! (it lives here, below both).
//!
//! Traps nest: one lock, reentrant, is held while any trap runs, so the traps of other
//! threads wait. The outermost trap installs glrt's handler and restores the application's
//! when it ends; a trap inside it only adds itself to the nest. An error goes to the innermost
//! trap of its display whose first request it follows (by serial); an error of an earlier
//! request or of another display (another thread of the application, or its own requests
//! flushed by a trap's `XSync`) goes on to the application's handler. A handler the
//! application installs while a trap runs (from another thread) is kept when the trap ends.

use std::ffi::c_int;

use parking_lot::{Mutex, ReentrantMutex};
use x11_dl::xlib::{self, Xlib};

/// An Xlib error handler.
pub type Handler = unsafe extern "C" fn(*mut xlib::Display, *mut xlib::XErrorEvent) -> c_int;

/// One running trap.
struct Trap {
    /// The display's address.
    display: usize,
    /// The serial of the trap's first request: errors of earlier ones are not its own.
    first_serial: u64,
    /// The first error code, 0 while none.
    code: u8,
}

/// The running traps, innermost last, and the handler the outermost one replaced.
struct Nest {
    traps: Vec<Trap>,
    application: Option<Handler>,
}

/// Held while a trap runs: one nest at a time, on one thread.
static OWNER: ReentrantMutex<()> = ReentrantMutex::new(());
/// Guards the nest itself for the moments it changes, and for the handler, which Xlib may call
/// on any thread. Held only around `XSetErrorHandler`, never across a request: a handler
/// called on another thread (which may hold that display's lock while it runs) waits for the
/// nest, never for a trap, so it cannot deadlock with a trap's `XSync`.
static NEST: Mutex<Nest> = Mutex::new(Nest { traps: Vec::new(), application: None });

/// glrt's handler while a trap runs: records the error in its trap, or forwards it.
unsafe extern "C" fn record(dpy: *mut xlib::Display, event: *mut xlib::XErrorEvent) -> c_int {
    // Safety: Xlib passes a valid event.
    let (serial, code) = unsafe { ((*event).serial, (*event).error_code) };
    let forward = {
        let mut nest = NEST.lock();
        match nest.traps.iter_mut().rev().find(|t| t.display == dpy as usize && serial >= t.first_serial) {
            Some(trap) => {
                if trap.code == 0 {
                    trap.code = code.max(1);
                }
                None
            }
            None => nest.application,
        }
    };
    match forward {
        // Safety: forwarding Xlib's own arguments to the handler the application installed.
        Some(handler) => unsafe { handler(dpy, event) },
        None => 0,
    }
}

/// Removes the innermost trap when it ends (also when `f` unwinds), restoring the
/// application's handler after the outermost one.
struct Leave<'a> {
    x: &'a Xlib,
    outermost: bool,
}

impl Drop for Leave<'_> {
    fn drop(&mut self) {
        // The handler is swapped under the nest's lock, so that Xlib, calling it from another
        // thread, sees the nest and the handler change together.
        let mut nest = NEST.lock();
        nest.traps.pop();
        if self.outermost {
            // Safety: plain Xlib calls; a handler the application set meanwhile stays.
            unsafe {
                let replaced = (self.x.XSetErrorHandler)(nest.application);
                if replaced.is_some_and(|h| !std::ptr::fn_addr_eq(h, record as Handler)) {
                    (self.x.XSetErrorHandler)(replaced);
                }
            }
        }
    }
}

/// Runs `f` as a trap on `dpy`, with `XSync` before and after when `sync`.
///
/// # Safety
/// `dpy` is a live display.
unsafe fn trap<R>(x: &Xlib, dpy: *mut xlib::Display, sync: bool, f: impl FnOnce() -> R) -> Result<R, u8> {
    let _owner = OWNER.lock();
    // Safety (all calls): `dpy` is live.
    if sync {
        // Errors of earlier requests reach whoever handles them now.
        unsafe { (x.XSync)(dpy, xlib::False) };
    }
    let first_serial = unsafe { (x.XNextRequest)(dpy) };
    let outermost = {
        let mut nest = NEST.lock();
        nest.traps.push(Trap { display: dpy as usize, first_serial, code: 0 });
        let outermost = nest.traps.len() == 1;
        if outermost {
            nest.application = unsafe { (x.XSetErrorHandler)(Some(record)) };
        }
        outermost
    };
    let leave = Leave { x, outermost };
    let result = f();
    if sync {
        unsafe { (x.XSync)(dpy, xlib::False) };
    }
    // The innermost trap is this one again: those `f` ran have ended.
    let code = NEST.lock().traps.last().map_or(0, |t| t.code);
    drop(leave);
    match code {
        0 => Ok(result),
        code => Err(code),
    }
}

/// Runs Xlib requests that may fail with their errors trapped, synchronously (`XSync` before
/// and after: errors of the application's earlier requests reach its handler first). Returns
/// the X error code of the first error of `f`'s requests, if any.
///
/// # Safety
/// `dpy` is a live display.
pub unsafe fn trapped<R>(x: &Xlib, dpy: *mut xlib::Display, f: impl FnOnce() -> R) -> Result<R, u8> {
    // Safety: forwarded.
    unsafe { trap(x, dpy, true, f) }
}

/// [`trapped`] for one request that waits for its reply (`XGetGeometry`...) in one round
/// trip instead of three: no `XSync` before or after, since the reply (or the error) ends the
/// wait; errors of earlier requests that arrive meanwhile go on to the application's handler
/// (or the enclosing trap). Used at every `glXSwapBuffers` (40 µs → 14 µs per swap on a local
/// Xvfb).
///
/// # Safety
/// `dpy` is a live display; `f` makes exactly one request that has a reply, on `dpy`.
pub unsafe fn trapped_reply<R>(x: &Xlib, dpy: *mut xlib::Display, f: impl FnOnce() -> R) -> Result<R, u8> {
    // Safety: forwarded.
    unsafe { trap(x, dpy, false, f) }
}

/// The error handler the application installed, `None` when it installed none (Xlib's
/// default, which exits, is in place). While a trap runs, the one it replaced.
pub fn application_handler(x: &Xlib) -> Option<Handler> {
    let _owner = OWNER.lock();
    let nest = NEST.lock();
    if !nest.traps.is_empty() {
        return nest.application;
    }
    drop(nest);
    // Safety: swapping handlers is how Xlib exposes the current one; it is restored at once,
    // and no trap can start meanwhile.
    let (application, default) = unsafe {
        let application = (x.XSetErrorHandler)(None);
        let default = (x.XSetErrorHandler)(application);
        (application, default)
    };
    application.filter(|h| !default.is_some_and(|d| std::ptr::fn_addr_eq(d, *h)))
}
