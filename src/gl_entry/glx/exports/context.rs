//! GLX exports for rendering contexts (GLX 1.4 sections 3.3.7 and 3.5.1,
//! GLX_ARB_create_context and GLX_ARB_create_context_profile). The state is in
//! [`crate::gl_entry::glx::context`].

#![allow(non_snake_case)]

use std::ffi::{c_int, c_ulong};

use x11_dl::glx::arb::*;
use x11_dl::glx::*;
use x11_dl::xlib;

use super::config::config_of_visual;
use crate::gl_entry::current;
use crate::gl_entry::glx::config::{self, FbConfig, read_pairs};
use crate::gl_entry::glx::context;
use crate::gl_entry::glx::entry::glx_export;
use crate::gl_entry::glx::types::types;
use crate::gl_entry::glx::{BAD_ACCESS, BAD_MATCH, BAD_VALUE, GlxError, XError, connection, report};

/// Creates a context of `config` or reports why not (to the application's X error handler).
fn create(dpy: *mut types::Display, name: &'static str, config: Option<&FbConfig>, share: types::GLXContext) -> types::GLXContext {
    let created = match config {
        Some(config) => context::create(config, share as usize),
        None => Err(BAD_VALUE),
    };
    match created {
        Ok(ptr) => ptr.cast_const().cast(),
        Err(e) => {
            // Safety: the display is null or the application's live display.
            unsafe { report(dpy.cast(), name, e, 0) };
            std::ptr::null()
        }
    }
}

/// `glXCreateContext`: a context for the visual's configuration (see
/// `glx::config` on visuals). `direct` is ignored: glrt contexts are always direct.
///
/// # Safety
/// `dpy` is a live display; `vis` a valid `XVisualInfo`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXCreateContext(
    dpy: *mut types::Display,
    vis: *mut types::XVisualInfo,
    shareList: types::GLXContext,
    _direct: types::Bool,
) -> types::GLXContext {
    glx_export!(glXCreateContext(dpy, vis, shareList, _direct), {
        let Some((x, xdpy)) = (unsafe { connection(dpy.cast()) }) else { return std::ptr::null() };
        // Safety: as documented.
        let config = unsafe { config_of_visual(x, xdpy, vis) };
        create(dpy, "glXCreateContext", config, shareList)
    })
}

/// `glXCreateNewContext`: `render_type` must be `GLX_RGBA_TYPE` (glrt has no colour-index
/// configurations: `GLX_COLOR_INDEX_TYPE` is `BadMatch`, anything else `BadValue`).
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXCreateNewContext(
    dpy: *mut types::Display,
    config: types::GLXFBConfig,
    render_type: c_int,
    share_list: types::GLXContext,
    _direct: types::Bool,
) -> types::GLXContext {
    glx_export!(glXCreateNewContext(dpy, config, render_type, share_list, _direct), {
        let checked = match (config::lookup(config), render_type) {
            (None, _) => Err(XError::Glx(GlxError::BadFbConfig)),
            (Some(c), GLX_RGBA_TYPE) => Ok(c),
            (Some(_), GLX_COLOR_INDEX_TYPE) => Err(BAD_MATCH),
            _ => Err(BAD_VALUE),
        };
        match checked {
            Ok(c) => create(dpy, "glXCreateNewContext", Some(c), share_list),
            Err(e) => {
                // Safety: as documented.
                unsafe { report(dpy.cast(), "glXCreateNewContext", e, 0) };
                std::ptr::null()
            }
        }
    })
}

/// The OpenGL versions that exist (GLX_ARB_create_context: others are `BadMatch`).
fn version_exists(major: c_int, minor: c_int) -> bool {
    matches!((major, minor), (1, 0..=5) | (2, 0..=1) | (3, 0..=3) | (4, 0..=6))
}

/// Checks a `glXCreateContextAttribsARB` attribute list. glrt implements OpenGL 1.5 of the
/// compatibility kind, so a request for a later version is `BadMatch`, as the extension
/// says of unsupported versions (a 2.x request would get a context without shaders). The
/// profile mask only counts from version 3.2 on, where a bad one is `GLXBadProfileARB`.
fn check_attribs(pairs: &[(c_int, c_int)]) -> Result<(), XError> {
    let (mut major, mut minor, mut flags, mut profile) = (1, 0, 0, GLX_CONTEXT_CORE_PROFILE_BIT_ARB);
    for &(name, value) in pairs {
        match name {
            GLX_CONTEXT_MAJOR_VERSION_ARB => major = value,
            GLX_CONTEXT_MINOR_VERSION_ARB => minor = value,
            GLX_CONTEXT_FLAGS_ARB => flags = value,
            GLX_CONTEXT_PROFILE_MASK_ARB => profile = value,
            GLX_RENDER_TYPE if value == GLX_RGBA_TYPE => {}
            GLX_RENDER_TYPE => return Err(BAD_MATCH),
            _ => return Err(BAD_VALUE),
        }
    }
    let known_flags = GLX_CONTEXT_DEBUG_BIT_ARB | GLX_CONTEXT_FORWARD_COMPATIBLE_BIT_ARB;
    if flags & !known_flags != 0 {
        return Err(BAD_VALUE);
    }
    if !version_exists(major, minor) {
        return Err(BAD_MATCH);
    }
    let known_profiles = [GLX_CONTEXT_CORE_PROFILE_BIT_ARB, GLX_CONTEXT_COMPATIBILITY_PROFILE_BIT_ARB];
    if (major, minor) >= (3, 2) && !known_profiles.contains(&profile) {
        return Err(XError::Glx(GlxError::BadProfile));
    }
    if (major, minor) > (1, 5) {
        return Err(BAD_MATCH);
    }
    Ok(())
}

/// `glXCreateContextAttribsARB` (GLX_ARB_create_context): OpenGL 1.0 to 1.5 contexts; see
/// `check_attribs` for what is refused. Errors go to the application's X error handler.
///
/// # Safety
/// `dpy` is a live display; `attrib_list` is null or `None`-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXCreateContextAttribsARB(
    dpy: *mut types::Display,
    config: types::GLXFBConfig,
    share_context: types::GLXContext,
    _direct: types::Bool,
    attrib_list: *const c_int,
) -> types::GLXContext {
    glx_export!(glXCreateContextAttribsARB(dpy, config, share_context, _direct, attrib_list), {
        // Safety: as documented.
        let pairs = unsafe { read_pairs(attrib_list) };
        let checked = config::lookup(config).ok_or(XError::Glx(GlxError::BadFbConfig));
        match checked.and_then(|c| check_attribs(&pairs).map(|()| c)) {
            Ok(c) => create(dpy, "glXCreateContextAttribsARB", Some(c), share_context),
            Err(e) => {
                // Safety: as documented.
                unsafe { report(dpy.cast(), "glXCreateContextAttribsARB", e, 0) };
                std::ptr::null()
            }
        }
    })
}

/// `glXDestroyContext`: destroyed now, or when released if current (section 3.3.7).
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXDestroyContext(dpy: *mut types::Display, ctx: types::GLXContext) {
    glx_export!(glXDestroyContext(dpy, ctx), {
        if !context::destroy(ctx as usize) {
            // Safety: as documented.
            unsafe { report(dpy.cast(), "glXDestroyContext", XError::Glx(GlxError::BadContext), ctx as c_ulong) };
        }
    })
}

/// Makes `ctx` current with drawables `draw` and `read` (GLX 1.4 section 3.3.7), or releases
/// the current context; False after reporting the error as `name`.
///
/// # Safety
/// `dpy` is null or a live display.
unsafe fn make_current(
    name: &'static str,
    dpy: *mut types::Display,
    draw: types::GLXDrawable,
    read: types::GLXDrawable,
    ctx: types::GLXContext,
) -> types::Bool {
    if ctx.is_null() && draw == 0 && read == 0 {
        // Releasing needs no display (some programs pass none).
        context::release();
        return xlib::True;
    }
    let Some((x, xdpy)) = (unsafe { connection(dpy.cast()) }) else { return xlib::False };
    // Safety: as documented.
    match unsafe { context::make_current(x, xdpy, draw, read, ctx as usize) } {
        Ok(()) => xlib::True,
        Err(e) => {
            // Safety: as documented.
            unsafe { report(xdpy, name, e, draw) };
            xlib::False
        }
    }
}

/// `glXMakeContextCurrent` (section 3.3.7). Returns False after reporting the error.
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXMakeContextCurrent(
    dpy: *mut types::Display,
    draw: types::GLXDrawable,
    read: types::GLXDrawable,
    ctx: types::GLXContext,
) -> types::Bool {
    // Safety: as documented.
    glx_export!(glXMakeContextCurrent(dpy, draw, read, ctx) as Bool, unsafe {
        make_current("glXMakeContextCurrent", dpy, draw, read, ctx)
    })
}

/// `glXMakeCurrent`: [`glXMakeContextCurrent`] with one drawable for drawing and reading.
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXMakeCurrent(
    dpy: *mut types::Display,
    drawable: types::GLXDrawable,
    ctx: types::GLXContext,
) -> types::Bool {
    // Safety: as documented.
    glx_export!(glXMakeCurrent(dpy, drawable, ctx) as Bool, unsafe {
        make_current("glXMakeCurrent", dpy, drawable, drawable, ctx)
    })
}

/// `glXIsDirect`: True for every glrt context (rendering happens in the client).
#[unsafe(no_mangle)]
#[allow(clippy::not_unsafe_ptr_arg_deref)] // Safe to call from Rust: the display pointer is never read here, only handed to the pass-through library as the C caller gave it.
pub extern "C" fn glXIsDirect(_dpy: *mut types::Display, ctx: types::GLXContext) -> types::Bool {
    glx_export!(glXIsDirect(_dpy, ctx) as Bool, c_int::from(context::get(ctx as usize).is_some()))
}

/// `glXGetCurrentContext`: this thread's current context, or null.
#[unsafe(no_mangle)]
pub extern "C" fn glXGetCurrentContext() -> types::GLXContext {
    glx_export!(glXGetCurrentContext(), current::current_handle() as types::GLXContext)
}

/// `glXGetCurrentDrawable`: the current draw drawable, or `None`.
#[unsafe(no_mangle)]
pub extern "C" fn glXGetCurrentDrawable() -> types::GLXDrawable {
    glx_export!(glXGetCurrentDrawable(), context::binding().map_or(0, |b| b.draw))
}

/// `glXGetCurrentReadDrawable`: the current read drawable, or `None`.
#[unsafe(no_mangle)]
pub extern "C" fn glXGetCurrentReadDrawable() -> types::GLXDrawable {
    glx_export!(glXGetCurrentReadDrawable(), context::binding().map_or(0, |b| b.read))
}

/// `glXGetCurrentDisplay`: the display of the current context, or null.
#[unsafe(no_mangle)]
pub extern "C" fn glXGetCurrentDisplay() -> *mut types::Display {
    glx_export!(glXGetCurrentDisplay(), context::binding().map_or(std::ptr::null_mut(), |b| b.display.cast()))
}

/// `glXQueryContext` (section 3.3.7): `GLX_FBCONFIG_ID`, `GLX_RENDER_TYPE`, `GLX_SCREEN`.
/// Returns 0, `GLX_BAD_ATTRIBUTE`, or `GLX_BAD_CONTEXT`.
///
/// # Safety
/// `value` is writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXQueryContext(
    _dpy: *mut types::Display,
    ctx: types::GLXContext,
    attribute: c_int,
    value: *mut c_int,
) -> c_int {
    glx_export!(glXQueryContext(_dpy, ctx, attribute, value), {
        let Some(c) = context::get(ctx as usize) else { return GLX_BAD_CONTEXT };
        let v = match attribute {
            GLX_FBCONFIG_ID => c.config_id,
            GLX_RENDER_TYPE => GLX_RGBA_TYPE,
            GLX_SCREEN => c.screen,
            _ => return GLX_BAD_ATTRIBUTE,
        };
        if value.is_null() {
            return GLX_BAD_VALUE;
        }
        // Safety: checked non-null.
        unsafe { *value = v };
        0
    })
}

/// `glXCopyContext` (section 3.3.7): copies the attribute groups of `mask` (the
/// `glPushAttrib` bits) from `src` to `dst`. `BadAccess` when `dst` is current to some thread
/// or `src` is current to another thread; `GLXBadContext` for a handle that is not a context.
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXCopyContext(
    dpy: *mut types::Display,
    src: types::GLXContext,
    dst: types::GLXContext,
    mask: c_ulong,
) {
    glx_export!(glXCopyContext(dpy, src, dst, mask), {
        let fail = |error, resource: types::GLXContext| {
            // Safety: as documented.
            unsafe { report(dpy.cast(), "glXCopyContext", error, resource as c_ulong) }
        };
        let (Some(from), Some(to)) = (context::get(src as usize), context::get(dst as usize)) else {
            return fail(XError::Glx(GlxError::BadContext), if context::get(src as usize).is_none() { src } else { dst });
        };
        let Some(mut target) = to.handle.context.try_lock() else { return fail(BAD_ACCESS, dst) };
        let mask = mask as u32;
        if current::current_handle() == src as usize {
            crate::gl_entry::shim::with_current("glXCopyContext", |ctx| ctx.copy_attributes_to(&mut target, mask));
        } else {
            let Some(source) = from.handle.context.try_lock() else { return fail(BAD_ACCESS, src) };
            source.copy_attributes_to(&mut target, mask);
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn create_context_attribs_accepts_legacy_versions_only() {
        assert_eq!(check_attribs(&[]), Ok(()));
        assert_eq!(check_attribs(&[(GLX_CONTEXT_MAJOR_VERSION_ARB, 1), (GLX_CONTEXT_MINOR_VERSION_ARB, 5)]), Ok(()));
        assert_eq!(check_attribs(&[(GLX_CONTEXT_MINOR_VERSION_ARB, 6)]), Err(BAD_MATCH));
        assert_eq!(check_attribs(&[(GLX_CONTEXT_MAJOR_VERSION_ARB, 2)]), Err(BAD_MATCH));
        let core = [(GLX_CONTEXT_MAJOR_VERSION_ARB, 3), (GLX_CONTEXT_MINOR_VERSION_ARB, 3)];
        assert_eq!(check_attribs(&core), Err(BAD_MATCH));
        let bad_profile = [(GLX_CONTEXT_MAJOR_VERSION_ARB, 3), (GLX_CONTEXT_MINOR_VERSION_ARB, 2), (GLX_CONTEXT_PROFILE_MASK_ARB, 0)];
        assert_eq!(check_attribs(&bad_profile), Err(XError::Glx(GlxError::BadProfile)));
        // Below 3.2 the profile mask is ignored.
        assert_eq!(check_attribs(&[(GLX_CONTEXT_PROFILE_MASK_ARB, 0)]), Ok(()));
        assert_eq!(check_attribs(&[(GLX_CONTEXT_FLAGS_ARB, 0x80)]), Err(BAD_VALUE));
        assert_eq!(check_attribs(&[(0x7777, 1)]), Err(BAD_VALUE));
    }
}

