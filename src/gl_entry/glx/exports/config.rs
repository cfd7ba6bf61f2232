//! GLX exports for visuals and framebuffer configurations (GLX 1.4 sections 3.3.3 and 3.4):
//! `glXChooseVisual`, `glXGetConfig`, `glXChooseFBConfig`, `glXGetFBConfigs`,
//! `glXGetFBConfigAttrib`, `glXGetVisualFromFBConfig`. The state is in
//! [`crate::gl_entry::glx::config`].

#![allow(non_snake_case)]

use std::ffi::{c_int, c_ulong};

use x11_dl::glx::*;
use x11_dl::xlib::{self, Xlib};

use crate::gl_entry::glx::config::{self, FbConfig, Request};
use crate::gl_entry::glx::entry::glx_export;
use crate::gl_entry::glx::types::types;
use crate::gl_entry::glx::{XDisplay, connection, malloc_array};

/// The `XVisualInfo` of visual `id` on `screen`, allocated by Xlib (the application frees it
/// with `XFree`); null when the server has no such visual.
///
/// # Safety
/// `dpy` is a live display.
unsafe fn visual_info(x: &Xlib, dpy: *mut XDisplay, screen: c_int, id: c_ulong) -> *mut types::XVisualInfo {
    // Safety: a zeroed template is valid; Xlib allocates the result.
    unsafe {
        let mut template: xlib::XVisualInfo = std::mem::zeroed();
        template.screen = screen;
        template.visualid = id;
        let mut count = 0;
        (x.XGetVisualInfo)(dpy, xlib::VisualIDMask | xlib::VisualScreenMask, &mut template, &mut count).cast()
    }
}

/// `glXChooseVisual`: the visual of the best configuration matching `attribList` (the
/// visual rules of section 3.4), or null.
///
/// # Safety
/// `dpy` is a live display; `attribList` is null or `None`-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXChooseVisual(
    dpy: *mut types::Display,
    screen: c_int,
    attribList: *mut c_int,
) -> *mut types::XVisualInfo {
    glx_export!(glXChooseVisual(dpy, screen, attribList), {
        let Some((x, dpy)) = (unsafe { connection(dpy.cast()) }) else { return std::ptr::null_mut() };
        // Safety: as documented.
        let Some(table) = (unsafe { config::screen_configs(x, dpy, screen) }) else { return std::ptr::null_mut() };
        let Some(request) = (unsafe { Request::visual(attribList) }) else { return std::ptr::null_mut() };
        let Some(best) = request.choose(&table.configs).first().copied() else { return std::ptr::null_mut() };
        table.remember_choice(best);
        // Safety: as documented.
        unsafe { visual_info(x, dpy, screen, best.visual_id) }
    })
}

/// The configuration an `XVisualInfo` stands for.
///
/// # Safety
/// `dpy` is a live display; `vis` is null or a valid `XVisualInfo`.
pub(crate) unsafe fn config_of_visual(
    x: &Xlib,
    dpy: *mut XDisplay,
    vis: *const types::XVisualInfo,
) -> Option<&'static FbConfig> {
    // Safety: as documented.
    let vis = unsafe { vis.as_ref() }?;
    let table = unsafe { config::screen_configs(x, dpy, vis.screen) }?;
    table.of_visual(vis.visualid)
}

/// `glXGetConfig` (section 3.4): an attribute of the visual's configuration, plus
/// `GLX_USE_GL` and `GLX_RGBA`. Returns 0, `GLX_BAD_VISUAL` (visual without OpenGL: only
/// `GLX_USE_GL` answers, with False), `GLX_BAD_ATTRIBUTE` or `GLX_NO_EXTENSION`.
///
/// # Safety
/// `dpy` is a live display; `visual` is a valid `XVisualInfo`; `value` is writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetConfig(
    dpy: *mut types::Display,
    visual: *mut types::XVisualInfo,
    attrib: c_int,
    value: *mut c_int,
) -> c_int {
    glx_export!(glXGetConfig(dpy, visual, attrib, value), {
        let Some((x, dpy)) = (unsafe { connection(dpy.cast()) }) else { return GLX_NO_EXTENSION };
        if value.is_null() || visual.is_null() {
            return GLX_BAD_VALUE;
        }
        // Safety: as documented.
        let answer = match unsafe { config_of_visual(x, dpy, visual) } {
            None if attrib == GLX_USE_GL => Ok(xlib::False),
            None => Err(GLX_BAD_VISUAL),
            Some(_) if attrib == GLX_USE_GL || attrib == GLX_RGBA => Ok(xlib::True),
            Some(c) => c.attrib(attrib).ok_or(GLX_BAD_ATTRIBUTE),
        };
        match answer {
            Ok(v) => {
                // Safety: `value` is writable.
                unsafe { *value = v };
                0
            }
            Err(e) => e,
        }
    })
}

/// A configuration list the application frees with `XFree`; its length goes to `nelements`.
fn config_list(configs: &[&FbConfig], nelements: *mut c_int) -> *mut types::GLXFBConfig {
    if !nelements.is_null() {
        // Safety: checked non-null; the caller passes a writable int.
        unsafe { *nelements = configs.len() as c_int };
    }
    if configs.is_empty() {
        return std::ptr::null_mut();
    }
    let handles: Vec<types::GLXFBConfig> = configs.iter().map(|c| (*c as *const FbConfig).cast()).collect();
    malloc_array(&handles)
}

/// `glXChooseFBConfig` (section 3.3.3): the matching configurations, best first.
///
/// # Safety
/// `dpy` is a live display; `attrib_list` is null or `None`-terminated; `nelements` is
/// writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXChooseFBConfig(
    dpy: *mut types::Display,
    screen: c_int,
    attrib_list: *const c_int,
    nelements: *mut c_int,
) -> *mut types::GLXFBConfig {
    glx_export!(glXChooseFBConfig(dpy, screen, attrib_list, nelements), {
        let chosen = unsafe { connection(dpy.cast()) }.and_then(|(x, dpy)| {
            // Safety: as documented.
            let table = unsafe { config::screen_configs(x, dpy, screen) }?;
            Some(unsafe { Request::fbconfig(attrib_list) }.choose(&table.configs))
        });
        config_list(&chosen.unwrap_or_default(), nelements)
    })
}

/// `glXGetFBConfigs`: every configuration of `screen`.
///
/// # Safety
/// `dpy` is a live display; `nelements` is writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetFBConfigs(
    dpy: *mut types::Display,
    screen: c_int,
    nelements: *mut c_int,
) -> *mut types::GLXFBConfig {
    glx_export!(glXGetFBConfigs(dpy, screen, nelements), {
        let all = unsafe { connection(dpy.cast()) }.and_then(|(x, dpy)| {
            // Safety: as documented.
            let table = unsafe { config::screen_configs(x, dpy, screen) }?;
            Some(table.configs.iter().collect::<Vec<_>>())
        });
        config_list(&all.unwrap_or_default(), nelements)
    })
}

/// `glXGetFBConfigAttrib`: 0, `GLX_BAD_ATTRIBUTE`, or `GLX_NO_EXTENSION` for a handle that is
/// not a configuration.
///
/// # Safety
/// `value` is writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetFBConfigAttrib(
    _dpy: *mut types::Display,
    config: types::GLXFBConfig,
    attribute: c_int,
    value: *mut c_int,
) -> c_int {
    glx_export!(glXGetFBConfigAttrib(_dpy, config, attribute, value), {
        let Some(config) = config::lookup(config) else { return GLX_NO_EXTENSION };
        match config.attrib(attribute) {
            Some(v) if !value.is_null() => {
                // Safety: checked non-null.
                unsafe { *value = v };
                0
            }
            _ => GLX_BAD_ATTRIBUTE,
        }
    })
}

/// `glXGetVisualFromFBConfig`: the configuration's visual (Xlib-allocated), or null.
///
/// # Safety
/// `dpy` is a live display.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetVisualFromFBConfig(
    dpy: *mut types::Display,
    config: types::GLXFBConfig,
) -> *mut types::XVisualInfo {
    glx_export!(glXGetVisualFromFBConfig(dpy, config), {
        let (Some((x, dpy)), Some(config)) = (unsafe { connection(dpy.cast()) }, config::lookup(config)) else {
            return std::ptr::null_mut();
        };
        // Safety: as documented.
        unsafe { visual_info(x, dpy, config.screen, config.visual_id) }
    })
}
