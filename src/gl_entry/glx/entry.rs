//! How every hand-written GLX export runs ([`glx_export!`]): glrt's own body under
//! [`super::guard`]; when the call log is on, a line with the arguments and the result
//! (`0 glXMakeCurrent(dpy=0x55d0c1a2e2a0, drawable=0x200002, ctx=0x55d0c1b3f010) = True`);
//! in pass-through mode, the other library's function of the same name instead of the body
//! ([`crate::gl_entry::passthrough`]).
//!
//! Printing: XIDs and masks (`c_ulong`) in hex, `int`s in decimal, pointers as addresses or
//! `NULL`, attribute lists (`const int *`) also as their pairs, `glXGetProcAddress`'s name
//! also as text; `Bool` results as `True`/`False`.

use std::ffi::{c_char, c_int, c_void};
use std::fmt::Write as _;

use x11_dl::glx::arb::*;
use x11_dl::glx::*;

use super::config::read_pairs;

use crate::gl_entry::call_log::{self, Entry};
use crate::gl_entry::mode::{self, Mode};
use crate::translate::convert::ReturnDefault;

/// A GLX argument or result as the call log prints it.
pub trait GlxValue: Copy {
    /// Appends the value.
    ///
    /// # Safety
    /// A pointer points to what the GLX function it was given to reads (a NUL-terminated
    /// name for `const GLubyte *`, a None-terminated attribute list for `const int *`).
    unsafe fn print(self, out: &mut String);

    /// Appends the value of a `Bool` result (only `int`s are ever one).
    ///
    /// # Safety
    /// As [`GlxValue::print`].
    unsafe fn print_bool(self, out: &mut String) {
        // Safety: as documented.
        unsafe { self.print(out) };
    }
}

impl GlxValue for i32 {
    unsafe fn print(self, out: &mut String) {
        let _ = write!(out, "{self}");
    }

    unsafe fn print_bool(self, out: &mut String) {
        out.push_str(match self {
            0 => "False",
            1 => "True",
            // Safety: an `int` is printed as it is.
            _ => return unsafe { self.print(out) },
        });
    }
}

impl GlxValue for u32 {
    unsafe fn print(self, out: &mut String) {
        let _ = write!(out, "{self}");
    }
}

/// `c_ulong`: XIDs (windows, drawables, fonts) and event masks.
impl GlxValue for u64 {
    unsafe fn print(self, out: &mut String) {
        let _ = write!(out, "{self:#x}");
    }
}

/// Appends a pointer: `NULL` or its address.
fn print_address<T>(ptr: *const T, out: &mut String) {
    if ptr.is_null() {
        out.push_str("NULL");
    } else {
        let _ = write!(out, "{ptr:p}");
    }
}

/// Handles (`GLXContext`, `GLXFBConfig`).
impl GlxValue for *const c_void {
    unsafe fn print(self, out: &mut String) {
        print_address(self, out);
    }
}

/// Strings glrt returns (`glXQueryExtensionsString`): the address (the text is long).
impl GlxValue for *const c_char {
    unsafe fn print(self, out: &mut String) {
        print_address(self, out);
    }
}

/// `glXGetProcAddress`'s name: the address and the text, `0x55d0c1a2e2a0"glXSwapIntervalMESA"`
/// (at most [`MAX_NAME`] bytes are read).
impl GlxValue for *const u8 {
    unsafe fn print(self, out: &mut String) {
        print_address(self, out);
        if !self.is_null() {
            // Safety: the caller passes a NUL-terminated string; reading stops at its end.
            let name: Vec<u8> = (0..MAX_NAME).map(|i| unsafe { *self.add(i) }).take_while(|&b| b != 0).collect();
            let _ = write!(out, "{:?}", String::from_utf8_lossy(&name));
        }
    }
}

/// Attribute lists (every `const int *` parameter of a GLX export is one): the address and
/// the pairs, names by [`attribute_name`], `0x7ffd…[GLX_RENDER_TYPE=1, GLX_DOUBLEBUFFER=1]`.
impl GlxValue for *const c_int {
    unsafe fn print(self, out: &mut String) {
        print_address(self, out);
        if self.is_null() {
            return;
        }
        out.push('[');
        // Safety: the caller passes a None-terminated list of pairs.
        for (i, (name, value)) in unsafe { read_pairs(self) }.into_iter().enumerate() {
            let sep = if i > 0 { ", " } else { "" };
            let _ = match attribute_name(name) {
                Some(n) => write!(out, "{sep}{n}={value}"),
                None => write!(out, "{sep}{name:#x}={value}"),
            };
        }
        out.push(']');
    }
}

/// Other pointers (displays, visuals, out-parameters): the address.
impl<T> GlxValue for *mut T {
    unsafe fn print(self, out: &mut String) {
        print_address(self.cast_const(), out);
    }
}

/// Longest `glXGetProcAddress` name the log reads.
const MAX_NAME: usize = 256;

/// The name of a GLX attribute of the lists the log prints (GLX 1.4 tables 3.1 and 3.5,
/// GLX_ARB_create_context, GLX_ARB_multisample).
fn attribute_name(attribute: c_int) -> Option<&'static str> {
    macro_rules! names {
        ($($c:ident),* $(,)?) => { match attribute { $($c => Some(stringify!($c)),)* _ => None } };
    }
    names![
        GLX_BUFFER_SIZE, GLX_LEVEL, GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, GLX_AUX_BUFFERS,
        GLX_RED_SIZE, GLX_GREEN_SIZE, GLX_BLUE_SIZE, GLX_ALPHA_SIZE, GLX_DEPTH_SIZE, GLX_STENCIL_SIZE,
        GLX_ACCUM_RED_SIZE, GLX_ACCUM_GREEN_SIZE, GLX_ACCUM_BLUE_SIZE, GLX_ACCUM_ALPHA_SIZE,
        GLX_CONFIG_CAVEAT, GLX_X_VISUAL_TYPE, GLX_TRANSPARENT_TYPE, GLX_DRAWABLE_TYPE, GLX_RENDER_TYPE,
        GLX_X_RENDERABLE, GLX_FBCONFIG_ID, GLX_SAMPLE_BUFFERS, GLX_SAMPLES, GLX_PBUFFER_WIDTH,
        GLX_PBUFFER_HEIGHT, GLX_PRESERVED_CONTENTS, GLX_LARGEST_PBUFFER, GLX_CONTEXT_MAJOR_VERSION_ARB,
        GLX_CONTEXT_MINOR_VERSION_ARB, GLX_CONTEXT_FLAGS_ARB, GLX_CONTEXT_PROFILE_MASK_ARB,
    ]
}

impl GlxValue for () {
    unsafe fn print(self, _: &mut String) {}
}

/// Appends argument `name` to a call line.
///
/// # Safety
/// As [`GlxValue::print`].
pub unsafe fn arg<T: GlxValue>(t: &mut Entry, name: &str, value: T) {
    // Safety: as documented.
    unsafe { value.print(t.next(name.trim_start_matches('_'))) };
}

/// Runs a GLX export: `own` (glrt's body) under [`super::guard`], or when the call log or
/// pass-through mode is on, [`special`]. The plain path is one relaxed load.
#[inline(always)]
pub fn run<R: GlxValue + ReturnDefault>(
    name: &'static str,
    bool_result: bool,
    own: impl FnOnce() -> R,
    args: impl FnOnce(&mut Entry),
    forward: impl FnOnce() -> Option<R>,
) -> R {
    match mode::special() {
        None => super::guard(name, own),
        Some(mode) => special(mode, name, bool_result, own, args, forward),
    }
}

/// The export `name` with the call log or pass-through mode on: `forward` (the other
/// library's function, zero when it has none) or `own`, and the log line.
#[cold]
#[inline(never)]
pub fn special<R: GlxValue + ReturnDefault>(
    mode: Mode,
    name: &'static str,
    bool_result: bool,
    own: impl FnOnce() -> R,
    args: impl FnOnce(&mut Entry),
    forward: impl FnOnce() -> Option<R>,
) -> R {
    let call = || if mode.passthrough() { forward().unwrap_or_else(R::return_default) } else { super::guard(name, own) };
    let Some(mut t) = call_log::begin(mode, name) else { return call() };
    args(&mut t);
    t.close_args();
    let result = call();
    t.returned_with(|out| {
        if std::mem::size_of::<R>() > 0 {
            out.push_str(" = ");
            // Safety: results are numbers, handles and pointers printed by address.
            unsafe { if bool_result { result.print_bool(out) } else { result.print(out) } }
        }
    });
    t.end();
    result
}

/// Runs the body of a hand-written GLX export through [`run`]:
/// `glx_export!(glXMakeCurrent(dpy, drawable, ctx) as Bool, { body })`, where the name is the
/// export's own (its C prototype types the forwarded call) and the arguments are its
/// parameters, logged in this order; `as Bool` prints the result as `True`/`False`.
/// `glx_export!(name(args) forward { expr }, { body })` gives the pass-through call instead
/// (an `Option` of the result).
macro_rules! glx_export {
    ($name:ident($($arg:ident),*) $(as $kind:ident)?, $body:expr) => {
        glx_export!($name($($arg),*) $(as $kind)? forward {
            let own: unsafe extern "C" fn($(glx_export!(@any $arg)),*) -> _ = $name;
            // Safety: `own` has the C prototype of `$name`, and the arguments are the caller's.
            unsafe { $crate::gl_entry::passthrough::real_like(own, stringify!($name)).map(|real| real($($arg),*)) }
        }, $body)
    };
    ($name:ident($($arg:ident),*) $(as $kind:ident)? forward $forward:block, $body:expr) => {
        $crate::gl_entry::glx::entry::run(
            stringify!($name),
            glx_export!(@bool $($kind)?),
            || $body,
            |t| {
                let _ = &t;
                // Safety: the arguments are the C caller's, valid as the GLX function requires.
                $(unsafe { $crate::gl_entry::glx::entry::arg(t, stringify!($arg), $arg) };)*
            },
            || $forward,
        )
    };
    (@any $arg:ident) => { _ };
    (@bool Bool) => { true };
    (@bool) => { false };
}
pub(crate) use glx_export;

#[cfg(test)]
mod tests {
    use super::*;

    fn printed<T: GlxValue>(value: T, as_bool: bool) -> String {
        let mut s = String::new();
        // Safety: the tests pass valid names and lists.
        unsafe { if as_bool { value.print_bool(&mut s) } else { value.print(&mut s) } }
        s
    }

    #[test]
    fn values_print_by_type() {
        assert_eq!(printed(0x200002u64, false), "0x200002");
        assert_eq!(printed(-3i32, false), "-3");
        assert_eq!(printed(1i32, true), "True");
        assert_eq!(printed(0i32, true), "False");
        assert_eq!(printed(2i32, true), "2");
        assert_eq!(printed(std::ptr::null::<u8>(), false), "NULL");
        assert_eq!(printed(0x1000 as *mut u8, false), "0x1000");
        let name = c"glXSwapIntervalMESA";
        let ptr = name.as_ptr().cast::<u8>();
        assert_eq!(printed(ptr, false), format!("{ptr:p}\"glXSwapIntervalMESA\""));
        let list = [GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DOUBLEBUFFER, 1, 0x7777, 2, 0];
        assert_eq!(
            printed(list.as_ptr(), false),
            format!("{:p}[GLX_RENDER_TYPE=1, GLX_DOUBLEBUFFER=1, 0x7777=2]", list.as_ptr())
        );
        assert_eq!(printed((), false), "");
    }
}
