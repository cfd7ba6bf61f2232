//! Where the demo draws: an X11 window with a GLX context (`glXChooseVisual`,
//! `glXCreateContext`, `glXMakeCurrent`, `glXSwapBuffers`, as GLQuake and Quake 3 do), or
//! glrt's headless context (`glrtCreateContext` and friends, looked up with `dlsym`).

use std::ffi::{c_int, c_ulong, c_void};
use std::ptr::null_mut;

use x11_dl::xlib::{self, Display, XVisualInfo, Xlib};

use crate::loader::{GlLibrary, fn_table};

fn_table!(
    /// The GLX 1.0 functions a window needs.
    Glx {
        fn glXChooseVisual(dpy: *mut Display, screen: c_int, attribs: *mut c_int) -> *mut XVisualInfo;
        fn glXCreateContext(dpy: *mut Display, vis: *mut XVisualInfo, share: *mut c_void, direct: c_int) -> *mut c_void;
        fn glXMakeCurrent(dpy: *mut Display, drawable: c_ulong, ctx: *mut c_void) -> c_int;
        fn glXSwapBuffers(dpy: *mut Display, drawable: c_ulong);
        fn glXDestroyContext(dpy: *mut Display, ctx: *mut c_void);
    }
);

fn_table!(
    /// glrt's headless context API.
    Headless {
        fn glrtCreateContext(share: *mut c_void) -> *mut c_void;
        fn glrtMakeCurrent(ctx: *mut c_void, width: i32, height: i32) -> u8;
        fn glrtSwapBuffers();
        fn glrtDestroyContext(ctx: *mut c_void);
    }
);

// GLX attribute tokens (glx.h).
const GLX_RGBA: c_int = 4;
const GLX_DOUBLEBUFFER: c_int = 5;
const GLX_RED_SIZE: c_int = 8;
const GLX_GREEN_SIZE: c_int = 9;
const GLX_BLUE_SIZE: c_int = 10;
const GLX_DEPTH_SIZE: c_int = 12;

/// A drawable with a current GL context.
pub enum Surface {
    /// An X11 window.
    X11(Box<X11Window>),
    /// glrt's off-screen drawable.
    Headless(HeadlessContext),
}

impl Surface {
    /// Presents the frame (`glXSwapBuffers` or `glrtSwapBuffers`) and, for a window, drains
    /// pending X events.
    pub fn swap(&self) {
        match self {
            Surface::X11(w) => w.swap(),
            Surface::Headless(h) => h.swap(),
        }
    }
}

/// An X11 window with a GLX context current on it.
pub struct X11Window {
    xlib: Xlib,
    glx: Glx,
    display: *mut Display,
    window: c_ulong,
    context: *mut c_void,
}

impl X11Window {
    /// Opens `$DISPLAY`, picks a double-buffered RGB visual with depth, creates and maps a
    /// `width` × `height` window and makes a new GLX context current on it.
    pub fn open(lib: &GlLibrary, width: i32, height: i32, title: &str) -> Result<Self, String> {
        let glx = Glx::load(|name| lib.symbol(name))?;
        let xlib = Xlib::open().map_err(|e| format!("cannot load Xlib: {e}"))?;
        // Safety: plain Xlib/GLX calls on the display opened here; every pointer is checked.
        unsafe {
            let display = (xlib.XOpenDisplay)(std::ptr::null());
            if display.is_null() {
                return Err("cannot open the X display (is DISPLAY set? try --headless)".into());
            }
            let screen = (xlib.XDefaultScreen)(display);
            let mut attribs = [
                GLX_RGBA,
                GLX_DOUBLEBUFFER,
                GLX_RED_SIZE,
                5,
                GLX_GREEN_SIZE,
                5,
                GLX_BLUE_SIZE,
                5,
                GLX_DEPTH_SIZE,
                16,
                0,
            ];
            let visual = glx.glXChooseVisual(display, screen, attribs.as_mut_ptr());
            if visual.is_null() {
                (xlib.XCloseDisplay)(display);
                return Err("glXChooseVisual found no double-buffered RGB visual with depth".into());
            }
            let root = (xlib.XRootWindow)(display, (*visual).screen);
            let mut swa: xlib::XSetWindowAttributes = std::mem::zeroed();
            swa.colormap = (xlib.XCreateColormap)(display, root, (*visual).visual, xlib::AllocNone);
            swa.event_mask = xlib::ExposureMask | xlib::StructureNotifyMask | xlib::KeyPressMask;
            let window = (xlib.XCreateWindow)(
                display,
                root,
                0,
                0,
                width as u32,
                height as u32,
                0,
                (*visual).depth,
                xlib::InputOutput as u32,
                (*visual).visual,
                xlib::CWColormap | xlib::CWEventMask,
                &mut swa,
            );
            let ctitle = std::ffi::CString::new(title).unwrap_or_default();
            (xlib.XStoreName)(display, window, ctitle.as_ptr());
            (xlib.XMapWindow)(display, window);
            let context = glx.glXCreateContext(display, visual, null_mut(), 1);
            (xlib.XFree)(visual.cast());
            if context.is_null() {
                (xlib.XDestroyWindow)(display, window);
                (xlib.XCloseDisplay)(display);
                return Err("glXCreateContext failed".into());
            }
            let this = Self { xlib, glx, display, window, context };
            if this.glx.glXMakeCurrent(display, window, context) == 0 {
                return Err("glXMakeCurrent failed".into());
            }
            Ok(this)
        }
    }

    fn swap(&self) {
        // Safety: display, window and context are alive (owned by self).
        unsafe {
            self.glx.glXSwapBuffers(self.display, self.window);
            let mut event: xlib::XEvent = std::mem::zeroed();
            while (self.xlib.XPending)(self.display) > 0 {
                (self.xlib.XNextEvent)(self.display, &mut event);
            }
        }
    }
}

impl Drop for X11Window {
    fn drop(&mut self) {
        // Safety: releases what open() created, once.
        unsafe {
            self.glx.glXMakeCurrent(self.display, 0, null_mut());
            self.glx.glXDestroyContext(self.display, self.context);
            (self.xlib.XDestroyWindow)(self.display, self.window);
            (self.xlib.XCloseDisplay)(self.display);
        }
    }
}

/// A glrt headless context current on this thread.
pub struct HeadlessContext {
    api: Headless,
    context: *mut c_void,
}

impl HeadlessContext {
    /// Creates a headless context with a `width` × `height` drawable and makes it current.
    /// Fails when the library is not glrt (no `glrt*` functions).
    pub fn open(lib: &GlLibrary, width: i32, height: i32) -> Result<Self, String> {
        let api = Headless::load(|name| lib.symbol(name))?;
        // Safety: glrt's headless API; the handle is checked before use.
        unsafe {
            let context = api.glrtCreateContext(null_mut());
            if context.is_null() {
                return Err("glrtCreateContext failed".into());
            }
            if api.glrtMakeCurrent(context, width, height) == 0 {
                api.glrtDestroyContext(context);
                return Err("glrtMakeCurrent failed".into());
            }
            Ok(Self { api, context })
        }
    }

    fn swap(&self) {
        // Safety: the context is current on this thread.
        unsafe { self.api.glrtSwapBuffers() }
    }
}

impl Drop for HeadlessContext {
    fn drop(&mut self) {
        // Safety: the handle came from glrtCreateContext and is destroyed once.
        unsafe {
            self.api.glrtMakeCurrent(null_mut(), 0, 0);
            self.api.glrtDestroyContext(self.context);
        }
    }
}
