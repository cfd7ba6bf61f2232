//! Contexts without any window system, for replay, tests and `glrt-demo --headless`:
//! `glrtCreateContext`, `glrtMakeCurrent`, `glrtSwapBuffers`, `glrtDestroyContext`.
//! Programs reach them with `dlsym` or `glXGetProcAddress`.

use std::ffi::c_void;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;

use parking_lot::Mutex;

use super::current::{self, SharedContext};
use super::shim::with_current;
use crate::frame::{FrameSink, Surface, Target};
use crate::render;
use crate::translate::Context;
use crate::translate::capture::{self, format::SwapKind};
use crate::translate::context::ContextConfig;
use crate::translate::context::SharedObjects;

/// What an application-visible context handle points to.
pub struct ContextHandle {
    /// The context.
    pub context: SharedContext,
    /// Its share group, kept outside the context's lock: a context current on this thread
    /// (locked by it) can still be named as the share list of a new one.
    pub shared: Arc<Mutex<SharedObjects>>,
    /// Its id in capture files (`translate::capture`).
    pub capture_id: u32,
}

impl ContextHandle {
    /// A context presenting to the default sink, sharing objects with `share`'s share group.
    pub fn new(share: Option<&ContextHandle>) -> ContextHandle {
        crate::logging::init();
        ContextHandle::with_sink(share, render::default_sink())
    }

    /// A context presenting to `sink`, sharing objects with `share`'s share group.
    pub fn with_sink(share: Option<&ContextHandle>, sink: Box<dyn FrameSink>) -> ContextHandle {
        crate::logging::init();
        let capture_id = capture::context_created(share.map_or(0, |h| h.capture_id));
        let share = share.map(|h| h.shared.clone());
        let context = Context::new(ContextConfig { share, sink });
        let shared = context.shared.clone();
        ContextHandle { context: Arc::new(Mutex::new(context)), shared, capture_id }
    }

    /// Creates a context sharing objects with `share` (a handle, or null), presenting to
    /// `sink` (`None`: the default sink), and returns its handle.
    ///
    /// # Safety
    /// A non-null `share` came from this function and was not destroyed.
    pub unsafe fn create(share: *const ContextHandle, sink: Option<Box<dyn FrameSink>>) -> *mut ContextHandle {
        // Safety: as documented.
        let share = unsafe { share.as_ref() };
        let handle = match sink {
            Some(sink) => ContextHandle::with_sink(share, sink),
            None => ContextHandle::new(share),
        };
        Box::into_raw(Box::new(handle))
    }
}

/// Creates a headless context; `share` is another glrt context handle or null.
#[unsafe(no_mangle)]
pub extern "C" fn glrtCreateContext(share: *mut c_void) -> *mut c_void {
    create_context(share, None)
}

/// Creates a headless context presenting to `sink` (`None`: the default sink); `share` is
/// another handle from [`glrtCreateContext`] or this function, not destroyed, or null.
/// Null when the context cannot be made.
pub fn create_context(share: *mut c_void, sink: Option<Box<dyn FrameSink>>) -> *mut c_void {
    // Safety: a non-null share handle came from glrtCreateContext and was not destroyed.
    catch_unwind(AssertUnwindSafe(|| unsafe { ContextHandle::create(share.cast(), sink) }.cast())).unwrap_or(std::ptr::null_mut())
}

/// Makes a headless context current on this thread with an off-screen drawable of
/// `width` × `height`; null releases the current context. Returns 1 on success.
#[unsafe(no_mangle)]
pub extern "C" fn glrtMakeCurrent(ctx: *mut c_void, width: i32, height: i32) -> u8 {
    make_current(ctx, width, height, true)
}

/// `glrtMakeCurrent` with the buffering of the drawable (a replay of a single-buffered GLX
/// context). Returns 1 on success.
pub fn make_current(ctx: *mut c_void, width: i32, height: i32, double: bool) -> u8 {
    catch_unwind(AssertUnwindSafe(|| {
        // Safety: a non-null handle came from glrtCreateContext and was not destroyed.
        let handle = unsafe { ctx.cast::<ContextHandle>().as_ref() };
        let ok = current::make_current(ctx as usize, handle.map(|h| &h.context));
        if ok && handle.is_some() {
            let size = [width.max(0) as u32, height.max(0) as u32];
            with_current("glrtMakeCurrent", |c| {
                c.set_double_buffered(double);
                c.bind_target(Target { size, surface: Surface::Offscreen, swap_interval: 0, samples: 1, alpha: true });
            });
        }
        if ok {
            capture::made_current(handle.map_or(0, |h| h.capture_id), width, height, double);
        }
        u8::from(ok)
    }))
    .unwrap_or(0)
}

/// Ends the current frame of this thread's context (the headless `glXSwapBuffers`).
#[unsafe(no_mangle)]
pub extern "C" fn glrtSwapBuffers() {
    swap(SwapKind::Headless);
}

/// Ends the current frame as `kind` did (a glX swap first takes the drawable size it read).
pub fn swap(kind: SwapKind) {
    super::call_log::frame_end(kind.name());
    with_current(kind.name(), |c| {
        if let SwapKind::Glx { width, height } = kind {
            c.bind_drawable(width, height);
        }
        c.end_frame();
    });
    capture::swapped(kind);
}

/// Destroys a headless context (it is released first if current on this thread).
#[unsafe(no_mangle)]
pub extern "C" fn glrtDestroyContext(ctx: *mut c_void) {
    if ctx.is_null() {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        if current::current_handle() == ctx as usize {
            current::make_current(0, None);
        }
        // Safety: the handle came from glrtCreateContext and is destroyed once.
        drop(unsafe { Box::from_raw(ctx.cast::<ContextHandle>()) });
    }));
}
