//! GLX exports for drawables (GLX 1.4 section 3.3.5 and 3.3.6): GLX windows, pixmaps
//! (GLX 1.3 and 1.2 styles) and pbuffers, `glXQueryDrawable`, `glXSelectEvent`. The state is
//! in [`crate::gl_entry::glx::drawable`].

#![allow(non_snake_case)]

use std::ffi::{c_int, c_uint, c_ulong};

use x11_dl::glx::ext::*;
use x11_dl::glx::*;
use x11_dl::xlib::{self, Xlib};

use super::config::config_of_visual;
use crate::gl_entry::glx::config::{self, FbConfig, MAX_PBUFFER_SIDE, read_pairs};
use crate::gl_entry::glx::drawable::{self, Drawable, Kind};
use crate::gl_entry::glx::entry::glx_export;
use crate::gl_entry::glx::types::types;
use crate::gl_entry::glx::{BAD_ALLOC, BAD_MATCH, BAD_VALUE, GlxError, XDisplay, XError, connection, context, report};

/// Largest swap interval accepted (`GLX_MAX_SWAP_INTERVAL_EXT`).
pub const MAX_SWAP_INTERVAL: c_int = 1000;

/// Names a new GLX drawable of `config` made from the X drawable `target` (0 for pbuffers)
/// and records it; the error otherwise.
///
/// # Safety
/// `dpy` is a live display.
unsafe fn create(x: &Xlib, dpy: *mut XDisplay, config: &FbConfig, kind: Kind) -> Result<xlib::XID, XError> {
    // Section 3.3.5: the X drawable must exist (GLXBadWindow / GLXBadPixmap), match the
    // configuration (BadMatch: a window of its visual, a pixmap of its depth) and not be
    // wrapped already (BadAlloc).
    // Safety (all): `dpy` is live.
    let target = match kind {
        Kind::Window(w) => {
            let visual = unsafe { drawable::window_visual(x, dpy, w) }.ok_or(XError::Glx(GlxError::BadWindow))?;
            if visual != config.visual_id {
                return Err(BAD_MATCH);
            }
            Some(w)
        }
        Kind::Pixmap(p) => {
            let (_, _, depth) = unsafe { drawable::x_geometry(x, dpy, p) }.ok_or(XError::Glx(GlxError::BadPixmap))?;
            if depth as c_int != config.visual_depth {
                return Err(BAD_MATCH);
            }
            Some(p)
        }
        _ => None,
    };
    if target.is_some_and(|t| drawable::wraps(dpy, t)) {
        return Err(BAD_ALLOC);
    }
    // Safety: `dpy` is live and the configuration's screen is one of its screens.
    let name = unsafe { drawable::new_name(x, dpy, config.screen) }.ok_or(BAD_ALLOC)?;
    drawable::insert(dpy, name, Drawable::new(kind, config.id));
    Ok(name)
}

/// Runs a creation and reports its error; returns the new XID or `None` (0).
///
/// # Safety
/// `dpy` is null or a live display.
unsafe fn created(dpy: *mut types::Display, name: &'static str, f: impl FnOnce(&Xlib, *mut XDisplay) -> Result<xlib::XID, XError>) -> xlib::XID {
    let Some((x, xdpy)) = (unsafe { connection(dpy.cast()) }) else { return 0 };
    f(x, xdpy).unwrap_or_else(|e| {
        // Safety: `xdpy` is the application's live display.
        unsafe { report(xdpy, name, e, 0) };
        0
    })
}

/// A configuration handle, or `GLXBadFBConfig`.
fn fbconfig(config: types::GLXFBConfig) -> Result<&'static FbConfig, XError> {
    config::lookup(config).ok_or(XError::Glx(GlxError::BadFbConfig))
}

/// `glXCreateWindow`: a GLX window on X window `win`.
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXCreateWindow(
    dpy: *mut types::Display,
    config: types::GLXFBConfig,
    win: types::Window,
    _attrib_list: *const c_int,
) -> types::GLXWindow {
    glx_export!(glXCreateWindow(dpy, config, win, _attrib_list), {
        // Safety: as documented.
        let make = |x: &Xlib, d: *mut XDisplay| unsafe { create(x, d, fbconfig(config)?, Kind::Window(win)) };
        // Safety: as documented.
        unsafe { created(dpy, "glXCreateWindow", make) }
    })
}

/// `glXCreatePixmap`: a GLX pixmap on X pixmap `pixmap` (depth 24 or 32).
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXCreatePixmap(
    dpy: *mut types::Display,
    config: types::GLXFBConfig,
    pixmap: types::Pixmap,
    _attrib_list: *const c_int,
) -> types::GLXPixmap {
    glx_export!(glXCreatePixmap(dpy, config, pixmap, _attrib_list), {
        // Safety: as documented.
        let make = |x: &Xlib, d: *mut XDisplay| unsafe { create(x, d, fbconfig(config)?, Kind::Pixmap(pixmap)) };
        // Safety: as documented.
        unsafe { created(dpy, "glXCreatePixmap", make) }
    })
}

/// `glXCreateGLXPixmap` (GLX 1.2): a GLX pixmap for the visual's configuration.
///
/// # Safety
/// `dpy` is a live display; `visual` a valid `XVisualInfo`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXCreateGLXPixmap(
    dpy: *mut types::Display,
    visual: *mut types::XVisualInfo,
    pixmap: types::Pixmap,
) -> types::GLXPixmap {
    glx_export!(glXCreateGLXPixmap(dpy, visual, pixmap), {
        let make = |x: &Xlib, d: *mut XDisplay| {
            // Safety: as documented.
            let config = unsafe { config_of_visual(x, d, visual) }.ok_or(BAD_VALUE)?;
            unsafe { create(x, d, config, Kind::Pixmap(pixmap)) }
        };
        // Safety: as documented.
        unsafe { created(dpy, "glXCreateGLXPixmap", make) }
    })
}

/// `glXCreatePbuffer`: `GLX_PBUFFER_WIDTH`/`HEIGHT` (0 by default), `GLX_PRESERVED_CONTENTS`
/// (True), `GLX_LARGEST_PBUFFER` (False: a size above the maximum is `BadAlloc`; True: it is
/// clamped).
///
/// # Safety
/// `dpy` is a live display; `attrib_list` is null or `None`-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXCreatePbuffer(
    dpy: *mut types::Display,
    config: types::GLXFBConfig,
    attrib_list: *const c_int,
) -> types::GLXPbuffer {
    glx_export!(glXCreatePbuffer(dpy, config, attrib_list), {
        let make = |x: &Xlib, d: *mut XDisplay| {
            let config = fbconfig(config)?;
            let (mut width, mut height, mut preserved, mut largest) = (0, 0, true, false);
            // Safety: as documented.
            for (name, value) in unsafe { read_pairs(attrib_list) } {
                match name {
                    GLX_PBUFFER_WIDTH => width = value,
                    GLX_PBUFFER_HEIGHT => height = value,
                    GLX_PRESERVED_CONTENTS => preserved = value != 0,
                    GLX_LARGEST_PBUFFER => largest = value != 0,
                    _ => return Err(BAD_VALUE),
                }
            }
            if width < 0 || height < 0 {
                return Err(BAD_VALUE);
            }
            if width > MAX_PBUFFER_SIDE || height > MAX_PBUFFER_SIDE {
                if !largest {
                    return Err(BAD_ALLOC);
                }
                (width, height) = (width.min(MAX_PBUFFER_SIDE), height.min(MAX_PBUFFER_SIDE));
            }
            // Safety: as documented.
            unsafe { create(x, d, config, Kind::Pbuffer { width, height, preserved, largest }) }
        };
        // Safety: as documented.
        unsafe { created(dpy, "glXCreatePbuffer", make) }
    })
}

/// Destroys a GLX drawable of the kind `accept` recognises, or reports `error`.
///
/// # Safety
/// `dpy` is null or a live display.
unsafe fn destroy(dpy: *mut types::Display, name: &'static str, xid: xlib::XID, error: GlxError, accept: fn(&Kind) -> bool) {
    let Some((x, xdpy)) = (unsafe { connection(dpy.cast()) }) else { return };
    // Safety: the application's display is live.
    unsafe {
        if !drawable::destroy(x, xdpy, xid, accept) {
            report(xdpy, name, XError::Glx(error), xid);
        }
    }
}

/// `glXDestroyWindow`.
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXDestroyWindow(dpy: *mut types::Display, win: types::GLXWindow) {
    glx_export!(glXDestroyWindow(dpy, win), {
        unsafe { destroy(dpy, "glXDestroyWindow", win, GlxError::BadWindow, |k| matches!(k, Kind::Window(_))) }
    })
}

/// `glXDestroyPixmap`.
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXDestroyPixmap(dpy: *mut types::Display, pixmap: types::GLXPixmap) {
    glx_export!(glXDestroyPixmap(dpy, pixmap), {
        unsafe { destroy(dpy, "glXDestroyPixmap", pixmap, GlxError::BadPixmap, |k| matches!(k, Kind::Pixmap(_))) }
    })
}

/// `glXDestroyGLXPixmap` (GLX 1.2).
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXDestroyGLXPixmap(dpy: *mut types::Display, pixmap: types::GLXPixmap) {
    glx_export!(glXDestroyGLXPixmap(dpy, pixmap), {
        unsafe { destroy(dpy, "glXDestroyGLXPixmap", pixmap, GlxError::BadPixmap, |k| matches!(k, Kind::Pixmap(_))) }
    })
}

/// `glXDestroyPbuffer`.
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXDestroyPbuffer(dpy: *mut types::Display, pbuf: types::GLXPbuffer) {
    glx_export!(glXDestroyPbuffer(dpy, pbuf), {
        unsafe { destroy(dpy, "glXDestroyPbuffer", pbuf, GlxError::BadPbuffer, |k| matches!(k, Kind::Pbuffer { .. })) }
    })
}

/// The value of a `glXQueryDrawable` attribute, `None` for an unknown attribute.
///
/// # Safety
/// `dpy` is a live display.
unsafe fn query(x: &Xlib, dpy: *mut XDisplay, xid: xlib::XID, attribute: c_int) -> Result<Option<c_uint>, XError> {
    // Safety: as documented.
    let (width, height) = unsafe { drawable::size(x, dpy, xid) }.ok_or(XError::Glx(GlxError::BadDrawable))?;
    let state = drawable::get(dpy, xid).unwrap_or(Drawable::new(Kind::X, 0));
    let current_config = || context::binding().filter(|b| b.display == dpy && b.draw == xid);
    let config_id = match state.config_id {
        0 => current_config().and_then(|b| context::get(b.context)).map_or(0, |c| c.config_id),
        id => id,
    };
    let (preserved, largest) = match state.kind {
        Kind::Pbuffer { preserved, largest, .. } => (preserved, largest),
        _ => (true, false),
    };
    Ok(Some(match attribute {
        GLX_WIDTH => width,
        GLX_HEIGHT => height,
        GLX_PRESERVED_CONTENTS => c_int::from(preserved),
        GLX_LARGEST_PBUFFER => c_int::from(largest),
        GLX_FBCONFIG_ID => config_id,
        GLX_SWAP_INTERVAL_EXT => state.swap_interval,
        GLX_MAX_SWAP_INTERVAL_EXT => MAX_SWAP_INTERVAL,
        _ => return Ok(None),
    } as c_uint))
}

/// `glXQueryDrawable` (section 3.3.6, plus `GLX_SWAP_INTERVAL_EXT` and
/// `GLX_MAX_SWAP_INTERVAL_EXT`): `GLXBadDrawable` for an unknown drawable, `BadValue` for an
/// unknown attribute.
///
/// # Safety
/// `dpy` is a live display; `value` is writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXQueryDrawable(
    dpy: *mut types::Display,
    draw: types::GLXDrawable,
    attribute: c_int,
    value: *mut c_uint,
) {
    glx_export!(glXQueryDrawable(dpy, draw, attribute, value), {
        let Some((x, xdpy)) = (unsafe { connection(dpy.cast()) }) else { return };
        // Safety: as documented.
        match unsafe { query(x, xdpy, draw, attribute) } {
            Ok(Some(v)) if !value.is_null() => unsafe { *value = v },
            Ok(_) => unsafe { report(xdpy, "glXQueryDrawable", BAD_VALUE, draw) },
            Err(e) => unsafe { report(xdpy, "glXQueryDrawable", e, draw) },
        }
    })
}

/// `glXSelectEvent`: records the mask of GLX events (only `GLX_PBUFFER_CLOBBER_MASK` exists,
/// and glrt's pbuffers are never clobbered) for a GLX window or pbuffer.
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXSelectEvent(dpy: *mut types::Display, draw: types::GLXDrawable, event_mask: c_ulong) {
    glx_export!(glXSelectEvent(dpy, draw, event_mask), {
        let xdpy = dpy.cast::<XDisplay>();
        match drawable::get(xdpy, draw) {
            Some(Drawable { kind: Kind::Window(_) | Kind::Pbuffer { .. }, .. }) => {
                drawable::update(xdpy, draw, |d| d.event_mask = event_mask)
            }
            // Safety: as documented.
            _ => unsafe { report(xdpy, "glXSelectEvent", XError::Glx(GlxError::BadDrawable), draw) },
        }
    })
}

/// `glXGetSelectedEvent`: the mask given to `glXSelectEvent`.
///
/// # Safety
/// `dpy` is a live display; `event_mask` is writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetSelectedEvent(dpy: *mut types::Display, draw: types::GLXDrawable, event_mask: *mut c_ulong) {
    glx_export!(glXGetSelectedEvent(dpy, draw, event_mask), {
        let xdpy = dpy.cast::<XDisplay>();
        match drawable::get(xdpy, draw) {
            Some(d) if !event_mask.is_null() => unsafe { *event_mask = d.event_mask },
            // Safety: as documented.
            _ => unsafe { report(xdpy, "glXGetSelectedEvent", XError::Glx(GlxError::BadDrawable), draw) },
        }
    })
}
