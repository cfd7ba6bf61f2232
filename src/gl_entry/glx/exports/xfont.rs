//! The `glXUseXFont` export (GLX 1.4 section 3.5.5); the work is in
//! [`crate::gl_entry::glx::xfont`].

#![allow(non_snake_case)]

use std::ffi::c_int;

use crate::gl_entry::glx::context::binding;
use crate::gl_entry::glx::entry::glx_export;
use crate::gl_entry::glx::types::types;
use crate::gl_entry::glx::{connection, xfont};

/// `glXUseXFont`: display lists `list .. list + count` draw characters `first ..` of `font`
/// with `glBitmap`. Needs a current context (its display is used); without one it does
/// nothing (there is no display to report an error on).
#[unsafe(no_mangle)]
pub extern "C" fn glXUseXFont(font: types::Font, first: c_int, count: c_int, list: c_int) {
    glx_export!(glXUseXFont(font, first, count, list), {
        let Some(b) = binding() else {
            return log::info!("glXUseXFont: no current context");
        };
        let Some((x, dpy)) = (unsafe { connection(b.display.cast()) }) else { return };
        // Safety: the current context's display is live.
        unsafe { xfont::use_x_font(x, dpy, font, first, count, list) }
    })
}
