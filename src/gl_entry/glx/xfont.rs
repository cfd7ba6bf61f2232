//! `glXUseXFont` (GLX 1.4 section 3.5.5): one display list per glyph of an X font, each a
//! `glBitmap` of the glyph as the server draws it, that moves the raster position by the
//! glyph's advance.
//!
//! Each glyph is drawn with `XDrawString16` into a depth-1 pixmap, read back with
//! `XGetImage`, and packed into `glBitmap`'s layout (rows bottom to top, most significant bit
//! first, byte-aligned rows). The lists are compiled through the exported GL entry points on
//! the current context, as an application would, with the unpack state set to that layout and
//! restored afterwards.

use std::ffi::{c_int, c_uint, c_ulong};

use x11_dl::xlib::{self, Xlib};

use super::XDisplay;
use crate::gl_entry::exports as gl_api;
use crate::render::present::x_errors;
use crate::translate::gl;

/// Packs a `width` × `height` glyph (`lit(x, y)`, y from the top) into `glBitmap` rows.
pub fn glyph_bitmap(width: usize, height: usize, lit: impl Fn(usize, usize) -> bool) -> Vec<u8> {
    let stride = width.div_ceil(8);
    let mut bits = vec![0u8; stride * height];
    for row in 0..height {
        let y = height - 1 - row;
        for x in (0..width).filter(|&x| lit(x, y)) {
            bits[row * stride + x / 8] |= 0x80 >> (x % 8);
        }
    }
    bits
}

/// The metrics of character `code` in `font`, or `None` when the font lacks it.
///
/// # Safety
/// `font` is a valid font structure from `XQueryFont`.
unsafe fn metrics(font: &xlib::XFontStruct, code: c_uint) -> Option<xlib::XCharStruct> {
    let (byte1, byte2) = (code >> 8, code & 0xff);
    let (min2, max2) = (font.min_char_or_byte2, font.max_char_or_byte2);
    if byte1 < font.min_byte1 || byte1 > font.max_byte1 || byte2 < min2 || byte2 > max2 {
        return None;
    }
    if font.per_char.is_null() {
        return Some(font.max_bounds);
    }
    let index = (byte1 - font.min_byte1) as usize * (max2 - min2 + 1) as usize + (byte2 - min2) as usize;
    // Safety: `per_char` has an entry per character of the ranges checked above.
    let m = unsafe { *font.per_char.add(index) };
    // A character with all-zero metrics does not exist (XLFD convention).
    (m.width != 0 || m.lbearing != 0 || m.rbearing != 0 || m.ascent != 0 || m.descent != 0).then_some(m)
}

/// The unpack parameters `glBitmap` data is packed for, with the values used here.
const UNPACK: [(gl::GLenum, i32); 6] = [
    (gl::GL_UNPACK_SWAP_BYTES, 0),
    (gl::GL_UNPACK_LSB_FIRST, 0),
    (gl::GL_UNPACK_ROW_LENGTH, 0),
    (gl::GL_UNPACK_SKIP_ROWS, 0),
    (gl::GL_UNPACK_SKIP_PIXELS, 0),
    (gl::GL_UNPACK_ALIGNMENT, 1),
];

/// Sets the unpack state and returns the previous values.
fn set_unpack() -> [i32; 6] {
    let mut saved = [0, 0, 0, 0, 0, 4];
    for (slot, &(pname, value)) in saved.iter_mut().zip(&UNPACK) {
        // Safety: one GLint is written.
        unsafe {
            gl_api::glGetIntegerv(pname, slot);
            gl_api::glPixelStorei(pname, value);
        }
    }
    saved
}

/// Compiles the lists `list_base .. list_base + count` from characters `first ..` of `font`
/// on the current context (whose display is `dpy`).
///
/// # Safety
/// `dpy` is a live display.
pub unsafe fn use_x_font(x: &Xlib, dpy: *mut XDisplay, font: xlib::Font, first: c_int, count: c_int, list_base: c_int) {
    // Safety (block): `dpy` is live, every X resource is created and freed here; a bad font
    // is an error that is trapped.
    unsafe {
        let info = x_errors::trapped(x, dpy, || (x.XQueryFont)(dpy, font)).ok().filter(|f| !f.is_null());
        let Some(info) = info else {
            return super::report(dpy, "glXUseXFont", super::XError::Core(7), font); // BadFont
        };
        let fs = &*info;
        let width = (fs.max_bounds.rbearing as c_int - fs.min_bounds.lbearing as c_int).max(1) as c_uint;
        let height = (fs.max_bounds.ascent as c_int + fs.max_bounds.descent as c_int).max(1) as c_uint;
        let root = (x.XDefaultRootWindow)(dpy);
        let pixmap = (x.XCreatePixmap)(dpy, root, width, height, 1);
        let gc = (x.XCreateGC)(dpy, pixmap, 0, std::ptr::null_mut());
        (x.XSetFont)(dpy, gc, font);
        let saved = set_unpack();
        for i in 0..count.max(0) {
            let code = first.wrapping_add(i) as c_uint;
            let list = list_base.wrapping_add(i) as gl::GLuint;
            gl_api::glNewList(list, gl::GL_COMPILE);
            match metrics(fs, code) {
                Some(m) => {
                    let bits = draw_glyph(x, dpy, pixmap, gc, code, &m);
                    let (w, h) = glyph_size(&m);
                    let ptr = if bits.is_empty() { std::ptr::null() } else { bits.as_ptr() };
                    let (xorig, yorig) = (-(m.lbearing as f32), m.descent as f32);
                    gl_api::glBitmap(w as i32, h as i32, xorig, yorig, m.width as f32, 0.0, ptr);
                }
                None => gl_api::glBitmap(0, 0, 0.0, 0.0, 0.0, 0.0, std::ptr::null()),
            }
            gl_api::glEndList();
        }
        for (&(pname, _), value) in UNPACK.iter().zip(saved) {
            gl_api::glPixelStorei(pname, value);
        }
        (x.XFreeGC)(dpy, gc);
        (x.XFreePixmap)(dpy, pixmap);
        (x.XFreeFontInfo)(std::ptr::null_mut(), info, 0);
    }
}

/// Pixel size of a glyph's ink.
fn glyph_size(m: &xlib::XCharStruct) -> (usize, usize) {
    let w = (m.rbearing as i32 - m.lbearing as i32).max(0) as usize;
    let h = (m.ascent as i32 + m.descent as i32).max(0) as usize;
    (w, h)
}

/// Draws one glyph into `pixmap` and packs it (empty for a glyph without ink).
///
/// # Safety
/// `dpy`, `pixmap` (depth 1, large enough for every glyph of the font) and `gc` (with the
/// font set) are live.
unsafe fn draw_glyph(
    x: &Xlib,
    dpy: *mut XDisplay,
    pixmap: xlib::Pixmap,
    gc: xlib::GC,
    code: c_uint,
    m: &xlib::XCharStruct,
) -> Vec<u8> {
    let (w, h) = glyph_size(m);
    if w == 0 || h == 0 {
        return Vec::new();
    }
    // Safety: as documented.
    unsafe {
        (x.XSetForeground)(dpy, gc, 0);
        (x.XFillRectangle)(dpy, pixmap, gc, 0, 0, w as c_uint, h as c_uint);
        (x.XSetForeground)(dpy, gc, 1);
        let ch = xlib::XChar2b { byte1: (code >> 8) as u8, byte2: (code & 0xff) as u8 };
        (x.XDrawString16)(dpy, pixmap, gc, -(m.lbearing as c_int), m.ascent as c_int, &ch, 1);
        let image = (x.XGetImage)(dpy, pixmap, 0, 0, w as c_uint, h as c_uint, 1 as c_ulong, xlib::ZPixmap);
        if image.is_null() {
            return Vec::new();
        }
        let get_pixel = (*image).funcs.get_pixel;
        let bits = glyph_bitmap(w, h, |px, py| get_pixel.is_some_and(|f| f(image, px as c_int, py as c_int) != 0));
        if let Some(destroy) = (*image).funcs.destroy_image {
            destroy(image);
        }
        bits
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glyph_rows_go_bottom_up_msb_first_byte_aligned() {
        // A 10×2 glyph: top row has pixels 0 and 9, bottom row pixel 1.
        let lit = |x: usize, y: usize| (y == 0 && (x == 0 || x == 9)) || (y == 1 && x == 1);
        let bits = glyph_bitmap(10, 2, lit);
        assert_eq!(bits, vec![0b0100_0000, 0, 0b1000_0000, 0b0100_0000]);
    }

    #[test]
    fn missing_and_present_characters() {
        let mut per_char = [xlib::XCharStruct { lbearing: 0, rbearing: 5, width: 6, ascent: 7, descent: 2, attributes: 0 }; 3];
        per_char[1] = xlib::XCharStruct { lbearing: 0, rbearing: 0, width: 0, ascent: 0, descent: 0, attributes: 0 };
        let mut font: xlib::XFontStruct = unsafe { std::mem::zeroed() };
        font.min_char_or_byte2 = 65;
        font.max_char_or_byte2 = 67;
        font.per_char = per_char.as_mut_ptr();
        unsafe {
            assert_eq!(metrics(&font, 65).map(|m| m.width), Some(6));
            assert!(metrics(&font, 66).is_none());
            assert!(metrics(&font, 64).is_none());
            assert!(metrics(&font, 0x141).is_none());
        }
        assert_eq!(glyph_size(&per_char[0]), (5, 9));
    }
}
