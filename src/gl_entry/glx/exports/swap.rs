//! GLX exports for buffer swaps and synchronisation (GLX 1.4 sections 3.3.10 and 3.3.11;
//! GLX_EXT_swap_control, GLX_MESA_swap_control, GLX_SGI_swap_control): `glXSwapBuffers`
//! ends the current frame; swap intervals are kept per drawable for the presenter.

#![allow(non_snake_case)]

use std::ffi::{c_int, c_uint};

use x11_dl::glx::*;
use x11_dl::xlib;

use super::drawable::MAX_SWAP_INTERVAL;
use crate::gl_entry::glx::context;
use crate::gl_entry::glx::drawable::{self, Kind};
use crate::gl_entry::glx::entry::glx_export;
use crate::gl_entry::glx::types::types;
use crate::gl_entry::glx::{BAD_VALUE, GlxError, XError, connection, report};
use crate::gl_entry::shim::with_current;

/// `glXSwapBuffers`: when `drawable` is the draw drawable of this thread's current context
/// and that context is double-buffered, ends its frame (`Context::end_frame`), after
/// refreshing the drawable size the frame is presented at (`Context::refresh_target`: the
/// renderer follows window resizes and swap intervals, the viewport does not). Swapping a single-buffered
/// context, a GLX pixmap, or a drawable current elsewhere has no effect (section 3.3.10);
/// an unknown drawable is `GLXBadDrawable`.
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXSwapBuffers(dpy: *mut types::Display, drawable: types::GLXDrawable) {
    glx_export!(glXSwapBuffers(dpy, drawable), {
        let Some((x, xdpy)) = (unsafe { connection(dpy.cast()) }) else { return };
        // Safety: as documented.
        let Some((width, height)) = (unsafe { drawable::size(x, xdpy, drawable) }) else {
            return unsafe { report(xdpy, "glXSwapBuffers", XError::Glx(GlxError::BadDrawable), drawable) };
        };
        let Some(binding) = context::binding().filter(|b| b.display == xdpy && b.draw == drawable) else { return };
        let double = context::get(binding.context).is_some_and(|c| c.double_buffer);
        let pixmap = matches!(drawable::get(xdpy, drawable).map(|d| d.kind), Some(Kind::Pixmap(_)));
        let interval = drawable::get(xdpy, drawable).map_or(1, |d| d.swap_interval.max(0) as u32);
        if double && !pixmap {
            with_current("glXSwapBuffers", |c| {
                c.refresh_target(width, height, interval);
                c.end_frame();
            });
            crate::translate::capture::swapped(crate::translate::capture::format::SwapKind::Glx { width, height });
        }
    });
    crate::gl_entry::call_log::frame_end("glXSwapBuffers");
}

/// `glXWaitGL`: OpenGL rendering issued before it completes before later X rendering. glrt
/// renders a frame only when it ends (at a swap), so nothing is in flight here.
#[unsafe(no_mangle)]
pub extern "C" fn glXWaitGL() {
    glx_export!(glXWaitGL(), ())
}

/// `glXWaitX`: X rendering issued before it completes before later OpenGL rendering
/// (`XSync` on the current context's display).
#[unsafe(no_mangle)]
pub extern "C" fn glXWaitX() {
    glx_export!(glXWaitX(), {
        if let Some((x, dpy)) = context::binding().and_then(|b| unsafe { connection(b.display.cast()) }) {
            // Safety: the display of the current context is live.
            unsafe { (x.XSync)(dpy, xlib::False) };
        }
    })
}

/// `glXSwapIntervalEXT` (GLX_EXT_swap_control): sets `drawable`'s swap interval; negative is
/// `BadValue`, values above `GLX_MAX_SWAP_INTERVAL_EXT` are clamped to it.
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXSwapIntervalEXT(dpy: *mut types::Display, drawable: types::GLXDrawable, interval: c_int) {
    glx_export!(glXSwapIntervalEXT(dpy, drawable, interval), {
        let Some((x, xdpy)) = (unsafe { connection(dpy.cast()) }) else { return };
        // Safety (all): as documented.
        if interval < 0 {
            return unsafe { report(xdpy, "glXSwapIntervalEXT", BAD_VALUE, drawable) };
        }
        if unsafe { drawable::size(x, xdpy, drawable) }.is_none() {
            return unsafe { report(xdpy, "glXSwapIntervalEXT", XError::Glx(GlxError::BadDrawable), drawable) };
        }
        drawable::update(xdpy, drawable, |d| d.swap_interval = interval.min(MAX_SWAP_INTERVAL));
    })
}

/// Sets the swap interval of the current draw drawable: 0, or `GLX_BAD_CONTEXT` without a
/// current context.
fn set_current_interval(interval: c_int) -> c_int {
    match context::binding() {
        Some(b) => {
            drawable::update(b.display, b.draw, |d| d.swap_interval = interval.min(MAX_SWAP_INTERVAL));
            0
        }
        None => GLX_BAD_CONTEXT,
    }
}

/// `glXSwapIntervalMESA` (GLX_MESA_swap_control): 0 (vsync off) allowed.
#[unsafe(no_mangle)]
pub extern "C" fn glXSwapIntervalMESA(interval: c_uint) -> c_int {
    glx_export!(glXSwapIntervalMESA(interval), match c_int::try_from(interval) {
        Ok(i) => set_current_interval(i),
        Err(_) => GLX_BAD_VALUE,
    })
}

/// `glXGetSwapIntervalMESA`: the current draw drawable's interval, 0 without a context.
#[unsafe(no_mangle)]
pub extern "C" fn glXGetSwapIntervalMESA() -> c_int {
    glx_export!(glXGetSwapIntervalMESA(), {
        let Some(b) = context::binding() else { return 0 };
        // A drawable without recorded state has the default interval, 1.
        drawable::get(b.display, b.draw).map_or(1, |d| d.swap_interval)
    })
}

/// `glXSwapIntervalSGI` (GLX_SGI_swap_control): intervals of at least 1 only.
#[unsafe(no_mangle)]
pub extern "C" fn glXSwapIntervalSGI(interval: c_int) -> c_int {
    glx_export!(glXSwapIntervalSGI(interval), if interval <= 0 { GLX_BAD_VALUE } else { set_current_interval(interval) })
}
