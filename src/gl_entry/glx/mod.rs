//! GLX 1.4 on the application's own Xlib `Display`. The `glX*` C functions are in
//! [`exports`], one file per part of the API beside the file of the state it works on:
//! `exports/config.rs` and [`config`] (framebuffer configurations), `exports/context.rs` and
//! [`context`], `exports/drawable.rs` and [`drawable`], `exports/xfont.rs` and [`xfont`]; and
//! `exports/query.rs` and `exports/swap.rs`, whose state is elsewhere (the exports table, the
//! current context). Here: what every export shares, Xlib loaded once, panic guards
//! ([`entry`]), reporting GLX errors to the application's error handler (the X errors of glrt's
//! own requests are trapped by [`crate::render::present::x_errors`]); and the GLX C types
//! ([`types`]).
//!
//! glrt does not use the server's GLX extension: it renders into its own buffers, so GLX
//! objects are client-side state keyed by the application's `Display` pointer.

pub mod config;
pub mod context;
pub mod drawable;
pub mod entry;
pub mod exports;
pub mod types;
pub mod xfont;

use std::collections::HashSet;
use std::ffi::{c_int, c_uchar, c_ulong, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::OnceLock;

use parking_lot::Mutex;
use x11_dl::xlib::{self, Xlib};

use crate::render::present::x_errors;
use crate::translate::convert::ReturnDefault;

/// The Xlib `Display` of the application.
pub type XDisplay = xlib::Display;

/// Xlib's functions, loaded on first use from the `libX11.so.6` the application already uses;
/// `None` (logged once) when it cannot be loaded.
pub fn xlib() -> Option<&'static Xlib> {
    static XLIB: OnceLock<Option<Xlib>> = OnceLock::new();
    XLIB.get_or_init(|| Xlib::open().map_err(|e| log::error!("cannot load Xlib: {e}")).ok()).as_ref()
}

/// Runs the body of the export `name`: a panic is caught and logged, and the export returns
/// zero (GLX functions never let a panic reach the application). The exports call it through
/// [`entry::glx_export!`], which also writes the call log and forwards in pass-through mode.
pub fn guard<R: ReturnDefault>(name: &'static str, f: impl FnOnce() -> R) -> R {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|_| {
        log::error!("internal error in {name}");
        R::return_default()
    })
}

/// Xlib and the display, when the display is not null and Xlib is available. The first time
/// a display is seen, glrt asks to be told when it closes (see [`forget_display`]).
///
/// # Safety
/// `dpy` is null or a live display.
pub unsafe fn connection(dpy: *mut c_void) -> Option<(&'static Xlib, *mut XDisplay)> {
    let x = xlib().filter(|_| !dpy.is_null())?;
    let dpy = dpy.cast::<XDisplay>();
    let mut watched = WATCHED.lock();
    let watched = watched.get_or_insert_with(HashSet::new);
    if watched.insert(dpy as usize) {
        // Safety: `dpy` is the application's live display; Xlib calls the hook from
        // XCloseDisplay, before the display is freed.
        unsafe {
            let codes = (x.XAddExtension)(dpy);
            if !codes.is_null() {
                (x.XESetCloseDisplay)(dpy, (*codes).extension, Some(display_closed));
            }
        }
    }
    Some((x, dpy))
}

/// Displays whose closing glrt watches.
static WATCHED: Mutex<Option<HashSet<usize>>> = Mutex::new(None);

unsafe extern "C" fn display_closed(dpy: *mut XDisplay, _codes: *mut xlib::XExtCodes) -> c_int {
    guard("XCloseDisplay", || forget_display(dpy as usize));
    0
}

/// Forgets the state of a closed display, so that a display opened later at the same
/// address (or a new server reusing its XIDs) starts afresh. Configuration handles of the
/// closed display stay readable.
pub fn forget_display(dpy: usize) {
    if let Some(watched) = WATCHED.lock().as_mut() {
        watched.remove(&dpy);
    }
    config::forget_display(dpy);
    drawable::forget_display(dpy);
    crate::render::present::display_closed(dpy);
}

/// Memory the application releases with `XFree` (which is `free`).
pub fn malloc_array<T: Copy>(items: &[T]) -> *mut T {
    unsafe extern "C" {
        fn malloc(size: usize) -> *mut c_void;
    }
    let bytes = std::mem::size_of_val(items).max(1);
    // Safety: malloc returns memory suitably aligned for any type, or null.
    let ptr = unsafe { malloc(bytes) }.cast::<T>();
    if !ptr.is_null() {
        // Safety: `ptr` has room for `items.len()` elements.
        unsafe { std::ptr::copy_nonoverlapping(items.as_ptr(), ptr, items.len()) };
    }
    ptr
}

/// GLX protocol errors (GLX 1.4 section 3.2.1; `GLXBadProfileARB` from
/// GLX_ARB_create_context_profile), numbered from the extension's first error.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GlxError {
    /// `GLXBadContext`.
    BadContext = 0,
    /// `GLXBadDrawable`.
    BadDrawable = 2,
    /// `GLXBadPixmap`.
    BadPixmap = 3,
    /// `GLXBadFBConfig`.
    BadFbConfig = 9,
    /// `GLXBadPbuffer`.
    BadPbuffer = 10,
    /// `GLXBadWindow`.
    BadWindow = 12,
    /// `GLXBadProfileARB`.
    BadProfile = 13,
}

/// An X error: a GLX error (offset from the GLX error base) or a core one (`BadMatch` = 8,
/// `BadValue` = 2, `BadAlloc` = 11, `BadAccess` = 10).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum XError {
    /// A GLX extension error.
    Glx(GlxError),
    /// A core X protocol error code.
    Core(u8),
}

/// `BadValue`.
pub const BAD_VALUE: XError = XError::Core(2);
/// `BadMatch`.
pub const BAD_MATCH: XError = XError::Core(8);
/// `BadAccess`.
pub const BAD_ACCESS: XError = XError::Core(10);
/// `BadAlloc`.
pub const BAD_ALLOC: XError = XError::Core(11);

/// Reports an X error for a failed GLX call to the application's error handler, as a server
/// would (GLFW, for example, checks for `GLXBadProfileARB` to fall back). The request code is
/// the server's GLX opcode when it has the extension; without it, GLX errors have no number
/// and are only logged. When the application installed no handler, the error is only logged:
/// Xlib's default handler would exit the program.
///
/// # Safety
/// `dpy` is null or a live display.
pub unsafe fn report(dpy: *mut XDisplay, name: &'static str, error: XError, resource: c_ulong) {
    log::info!("{name}: {error:?}");
    let Some(x) = xlib().filter(|_| !dpy.is_null()) else { return };
    // Safety: `dpy` is live.
    let (opcode, _, error_base) = unsafe { glx_extension(x, dpy) }.unwrap_or((0, 0, 0));
    let code = match error {
        XError::Core(code) => code,
        XError::Glx(_) if opcode == 0 => return,
        XError::Glx(glx) => (error_base + glx as c_int) as c_uchar,
    };
    let Some(handler) = x_errors::application_handler(x) else { return };
    let mut event = xlib::XErrorEvent {
        type_: 0,
        display: dpy,
        resourceid: resource,
        // Safety: `dpy` is live.
        serial: unsafe { (x.XNextRequest)(dpy) }.saturating_sub(1),
        error_code: code,
        request_code: opcode as c_uchar,
        minor_code: 0,
    };
    // Safety: the handler was installed by the application for this display.
    unsafe { handler(dpy, &mut event) };
}

/// The server's GLX major opcode, first event and first error, when it has the extension.
///
/// # Safety
/// `dpy` is a live display.
pub unsafe fn glx_extension(x: &Xlib, dpy: *mut XDisplay) -> Option<(c_int, c_int, c_int)> {
    let (mut opcode, mut event, mut error) = (0, 0, 0);
    // Safety: `dpy` is live; the out-pointers are valid.
    let present = unsafe { (x.XQueryExtension)(dpy, c"GLX".as_ptr(), &mut opcode, &mut event, &mut error) };
    (present != 0).then_some((opcode, event, error))
}
