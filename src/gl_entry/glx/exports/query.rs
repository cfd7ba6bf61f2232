//! GLX exports for versions, strings and function addresses (GLX 1.4 sections 3.3.1 and
//! 3.3.12): `glXQueryVersion`, `glXQueryExtension`, `glXQueryExtensionsString`,
//! `glXGetClientString`, `glXQueryServerString`, `glXGetProcAddress[ARB]`.
//!
//! glrt implements GLX in the client, so the "server" strings are glrt's own.

#![allow(non_snake_case)]

use std::ffi::{CStr, c_char, c_int};

use x11_dl::glx::*;
use x11_dl::xlib;

use crate::gl_entry::exports::proc_address;
use crate::gl_entry::glx::entry::glx_export;
use crate::gl_entry::glx::types::types;
use crate::gl_entry::glx::{connection, glx_extension};
use crate::gl_entry::passthrough;

/// The GLX extensions glrt implements.
pub const EXTENSIONS: &CStr = c"GLX_ARB_create_context GLX_ARB_create_context_profile \
GLX_ARB_get_proc_address GLX_ARB_multisample GLX_EXT_swap_control GLX_EXT_visual_info GLX_EXT_visual_rating \
GLX_MESA_swap_control GLX_SGI_swap_control";

/// The answer to a `GLX_VENDOR`, `GLX_VERSION` or `GLX_EXTENSIONS` query, null otherwise.
fn string(name: c_int) -> *const c_char {
    match name {
        GLX_VENDOR => c"glrt".as_ptr(),
        GLX_VERSION => c"1.4".as_ptr(),
        GLX_EXTENSIONS => EXTENSIONS.as_ptr(),
        _ => std::ptr::null(),
    }
}

/// `glXQueryVersion`: GLX 1.4.
///
/// # Safety
/// `maj` and `min` are null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXQueryVersion(dpy: *mut types::Display, maj: *mut c_int, min: *mut c_int) -> types::Bool {
    glx_export!(glXQueryVersion(dpy, maj, min) as Bool, {
        if unsafe { connection(dpy.cast()) }.is_none() {
            return xlib::False;
        }
        // Safety: as documented.
        unsafe {
            if let Some(m) = maj.as_mut() {
                *m = 1;
            }
            if let Some(m) = min.as_mut() {
                *m = 4;
            }
        }
        xlib::True
    })
}

/// `glXQueryExtension`: True (glrt needs no server support). The error and event bases are
/// the server's GLX extension's when it has one (X errors glrt reports use them), else 0.
///
/// # Safety
/// `dpy` is a live display; `errorb` and `event` are null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXQueryExtension(dpy: *mut types::Display, errorb: *mut c_int, event: *mut c_int) -> types::Bool {
    glx_export!(glXQueryExtension(dpy, errorb, event) as Bool, {
        let Some((x, xdpy)) = (unsafe { connection(dpy.cast()) }) else { return xlib::False };
        // Safety: as documented.
        let (_, event_base, error_base) = unsafe { glx_extension(x, xdpy) }.unwrap_or((0, 0, 0));
        unsafe {
            if let Some(e) = errorb.as_mut() {
                *e = error_base;
            }
            if let Some(e) = event.as_mut() {
                *e = event_base;
            }
        }
        xlib::True
    })
}

/// `glXQueryExtensionsString`: the extensions of every screen.
#[unsafe(no_mangle)]
#[allow(clippy::not_unsafe_ptr_arg_deref)] // Safe to call from Rust: the display pointer is never read here, only handed to the pass-through library as the C caller gave it.
pub extern "C" fn glXQueryExtensionsString(_dpy: *mut types::Display, _screen: c_int) -> *const c_char {
    glx_export!(glXQueryExtensionsString(_dpy, _screen), EXTENSIONS.as_ptr())
}

/// `glXGetClientString`: `GLX_VENDOR`, `GLX_VERSION`, `GLX_EXTENSIONS`; null otherwise.
#[unsafe(no_mangle)]
#[allow(clippy::not_unsafe_ptr_arg_deref)] // Safe to call from Rust: the display pointer is never read here, only handed to the pass-through library as the C caller gave it.
pub extern "C" fn glXGetClientString(_dpy: *mut types::Display, name: c_int) -> *const c_char {
    glx_export!(glXGetClientString(_dpy, name), string(name))
}

/// `glXQueryServerString`: as [`glXGetClientString`] (the GLX "server" is glrt).
#[unsafe(no_mangle)]
#[allow(clippy::not_unsafe_ptr_arg_deref)] // Safe to call from Rust: the display pointer is never read here, only handed to the pass-through library as the C caller gave it.
pub extern "C" fn glXQueryServerString(_dpy: *mut types::Display, _screen: c_int, name: c_int) -> *const c_char {
    glx_export!(glXQueryServerString(_dpy, _screen, name), string(name))
}

/// The exported function called `procName`, or null. In pass-through mode, see
/// [`passthrough::proc_address`].
///
/// # Safety
/// `procName` is null or a NUL-terminated string.
unsafe fn proc_address_of(procName: *const types::GLubyte, passthrough: bool) -> types::__GLXextFuncPtr {
    if procName.is_null() {
        return std::ptr::null_mut();
    }
    // Safety: as documented.
    let name = unsafe { CStr::from_ptr(procName.cast()) };
    let address = if passthrough { passthrough::proc_address(name) } else { None };
    address.unwrap_or_else(|| proc_address(name.to_bytes())).cast_mut().cast()
}

/// `glXGetProcAddress`: every exported GL and GLX function by name (core ones too), null for
/// unknown names.
///
/// # Safety
/// `procName` is null or a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetProcAddress(procName: *const types::GLubyte) -> types::__GLXextFuncPtr {
    // Safety (both): as documented.
    glx_export!(glXGetProcAddress(procName) forward { Some(unsafe { proc_address_of(procName, true) }) }, unsafe {
        proc_address_of(procName, false)
    })
}

/// `glXGetProcAddressARB`: [`glXGetProcAddress`].
///
/// # Safety
/// As [`glXGetProcAddress`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetProcAddressARB(procName: *const types::GLubyte) -> types::__GLXextFuncPtr {
    // Safety (both): as documented.
    glx_export!(glXGetProcAddressARB(procName) forward { Some(unsafe { proc_address_of(procName, true) }) }, unsafe {
        proc_address_of(procName, false)
    })
}
