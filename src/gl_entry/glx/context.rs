//! GLX rendering contexts (GLX 1.4 sections 3.3.7 and 3.5): what a `GLXContext` points to,
//! which handles are live, and each thread's current display and drawables.
//!
//! A context destroyed while current stays alive until it is released (section 3.3.7: "the
//! context is destroyed when it is no longer current to any thread").

use std::cell::Cell;
use std::collections::HashSet;
use std::ffi::c_int;
use std::sync::atomic::{AtomicBool, Ordering};

use parking_lot::Mutex;
use x11_dl::xlib::{self, Xlib};

use super::config::FbConfig;
use super::{GlxError, XDisplay, XError, drawable};
use crate::gl_entry::current;
use crate::gl_entry::headless::ContextHandle;
use crate::gl_entry::shim::with_current;

/// What a `GLXContext` points to.
pub struct GlxContext {
    /// The rendering context.
    pub handle: ContextHandle,
    /// `GLX_FBCONFIG_ID` of the configuration it was created with.
    pub config_id: c_int,
    /// `GLX_SCREEN`.
    pub screen: c_int,
    /// Whether its configuration is double-buffered.
    pub double_buffer: bool,
    /// Samples per pixel of its configuration (1 when not multisampled).
    pub samples: u32,
    /// Whether its configuration has destination alpha (`GLX_ALPHA_SIZE` > 0).
    pub alpha: bool,
    /// Destroyed while current: freed when released.
    destroyed: AtomicBool,
}

/// Handles of the contexts not yet freed, so that a stale or foreign pointer is refused
/// (`GLXBadContext`) instead of read.
static LIVE: Mutex<Option<HashSet<usize>>> = Mutex::new(None);

fn with_live<R>(f: impl FnOnce(&mut HashSet<usize>) -> R) -> R {
    f(LIVE.lock().get_or_insert_with(HashSet::new))
}

/// Creates a context of `config`, sharing display lists and objects with `share` (0 or a
/// live context's handle); `GLXBadContext` for a bad share context.
pub fn create(config: &FbConfig, share: usize) -> Result<*mut GlxContext, XError> {
    let share = if share == 0 { None } else { Some(get(share).ok_or(XError::Glx(GlxError::BadContext))?) };
    let context = Box::new(GlxContext {
        handle: ContextHandle::new(share.map(|s| &s.handle)),
        config_id: config.id,
        screen: config.screen,
        double_buffer: config.double_buffer,
        samples: config.samples.max(1) as u32,
        alpha: config.rgba[3] > 0,
        destroyed: AtomicBool::new(false),
    });
    let ptr = Box::into_raw(context);
    with_live(|live| live.insert(ptr as usize));
    Ok(ptr)
}

/// The context a handle (`GLXContext` as an address) points to, when it is live and not
/// destroyed.
pub fn get(handle: usize) -> Option<&'static GlxContext> {
    if !with_live(|live| live.contains(&handle)) {
        return None;
    }
    // Safety: live handles point to contexts created by `create` and not yet freed; a context
    // is freed only by `destroy`/`release`, which GLX forbids racing with its use.
    let context = unsafe { &*(handle as *const GlxContext) };
    (!context.destroyed.load(Ordering::Acquire)).then_some(context)
}

/// `glXDestroyContext`: frees the context now, or when it is released if it is current on
/// some thread. Returns false for a handle that is not a live context.
pub fn destroy(handle: usize) -> bool {
    let Some(context) = get(handle) else { return false };
    context.destroyed.store(true, Ordering::Release);
    free_if_released(handle);
    true
}

/// Frees a destroyed context that no thread has current.
fn free_if_released(handle: usize) {
    with_live(|live| {
        if !live.contains(&handle) {
            return;
        }
        // Safety: live handle, see `get`.
        let context = unsafe { &*(handle as *const GlxContext) };
        if context.destroyed.load(Ordering::Acquire) && !context.handle.context.is_locked() {
            live.remove(&handle);
            // Safety: created by `create` with Box::into_raw; removed from LIVE, freed once.
            drop(unsafe { Box::from_raw(handle as *mut GlxContext) });
        }
    });
}

/// The display and drawables a thread's current GLX context is bound to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Binding {
    /// The display of `glXMakeCurrent`.
    pub display: *mut XDisplay,
    /// The draw drawable.
    pub draw: xlib::XID,
    /// The read drawable.
    pub read: xlib::XID,
    /// The context handle.
    pub context: usize,
}

thread_local! {
    static BINDING: Cell<Option<Binding>> = const { Cell::new(None) };
}

/// This thread's GLX binding, when a GLX context is current (not a headless one).
pub fn binding() -> Option<Binding> {
    BINDING.get().filter(|b| b.context == current::current_handle())
}

/// Releases this thread's current context (`glXMakeCurrent(dpy, None, NULL)`), freeing it
/// if it was destroyed while current.
pub fn release() {
    let previous = current::current_handle();
    current::make_current(0, None);
    crate::translate::capture::made_current(0, 0, 0, false);
    BINDING.set(None);
    free_if_released(previous);
}

/// `glXMakeContextCurrent` (GLX 1.4 section 3.3.7): binds `ctx` to `draw` and `read`, sizing
/// the context's viewport from the draw drawable on its first binding and telling its renderer
/// where frames go; a null `ctx` with no drawables releases the current context.
///
/// # Safety
/// `dpy` is a live display.
pub unsafe fn make_current(
    x: &Xlib,
    dpy: *mut XDisplay,
    draw: xlib::XID,
    read: xlib::XID,
    ctx: usize,
) -> Result<(), XError> {
    if ctx == 0 {
        if draw != 0 || read != 0 {
            return Err(super::BAD_MATCH);
        }
        release();
        return Ok(());
    }
    let previous = current::current_handle();
    let context = get(ctx).ok_or(XError::Glx(GlxError::BadContext))?;
    if draw == 0 || read == 0 {
        return Err(super::BAD_MATCH);
    }
    // Safety (both): `dpy` is live.
    let (width, height) = unsafe { drawable::size(x, dpy, draw) }.ok_or(XError::Glx(GlxError::BadDrawable))?;
    if read != draw && unsafe { drawable::size(x, dpy, read) }.is_none() {
        return Err(XError::Glx(GlxError::BadDrawable));
    }
    if !current::make_current(ctx, Some(&context.handle.context)) {
        return Err(super::BAD_ACCESS);
    }
    let double = context.double_buffer;
    // Safety: `dpy` is live.
    let target = unsafe { drawable::target(x, dpy, draw, [width, height], context.samples, context.alpha) };
    with_current("glXMakeCurrent", |c| {
        c.set_double_buffered(double);
        c.bind_target(target);
    });
    crate::translate::capture::made_current(context.handle.capture_id, width, height, double);
    BINDING.set(Some(Binding { display: dpy, draw, read, context: ctx }));
    if previous != ctx {
        free_if_released(previous);
    }
    Ok(())
}
