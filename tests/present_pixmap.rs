//! A GLX pixmap receives what the program drew when it calls `glFinish` (GLX pixmaps show
//! the front buffer; glrt puts the rendered image on the X pixmap with `XPutImage`): cleared
//! colours read back from the pixmap with `XGetImage`, the right way up. Runs the raster
//! renderer in this process (lavapipe on CI); fails without Xvfb, skipped without a Vulkan device.

#[path = "x11/mod.rs"]
mod x11;

use glrt::gl_entry::exports as gl;
use glrt::gl_entry::glx::exports::config::*;
use glrt::gl_entry::glx::exports::context::*;
use glrt::gl_entry::glx::exports::drawable::*;
use glrt::translate::gl::*;
use x11_dl::glx::*;
use x11_dl::xlib::{self, Xlib};

#[test]
fn glfinish_puts_the_frame_on_a_glx_pixmap() {
    let server = x11::Xvfb::start(24);
    if let Err(e) = glrt::render::frame::Renderer::without_outputs() {
        eprintln!("skipped: no Vulkan renderer ({e})");
        return;
    }
    let x = Xlib::open().expect("libX11");
    let dpy = server.open(&x);
    // Safety (all): plain GLX and GL calls on a live display, the context current on this
    // thread.
    unsafe {
        let root = (x.XRootWindow)(dpy, 0);
        let pixmap = (x.XCreatePixmap)(dpy, root, 40, 30, 24);
        let mut attribs = [GLX_RGBA, GLX_RED_SIZE, 1, 0];
        let vis = glXChooseVisual(dpy.cast(), 0, attribs.as_mut_ptr());
        assert!(!vis.is_null());
        let glx_pixmap = glXCreateGLXPixmap(dpy.cast(), vis, pixmap);
        let ctx = glXCreateContext(dpy.cast(), vis, std::ptr::null(), 1);
        assert_eq!(glXMakeCurrent(dpy.cast(), glx_pixmap, ctx), 1);
        gl::glDrawBuffer(GL_FRONT);
        gl::glClearColor(1.0, 0.0, 0.0, 1.0);
        gl::glClear(GL_COLOR_BUFFER_BIT);
        // The bottom-left 10 × 5 corner in OpenGL's window coordinates.
        gl::glEnable(GL_SCISSOR_TEST);
        gl::glScissor(0, 0, 10, 5);
        gl::glClearColor(0.0, 0.0, 1.0, 1.0);
        gl::glClear(GL_COLOR_BUFFER_BIT);
        gl::glFinish();
        assert_eq!(gl::glGetError(), GL_NO_ERROR);
        (x.XSync)(dpy, xlib::False);
        let got = x11::read_rgb(&x, dpy, pixmap, 40, 30);
        for y in 0..30 {
            for col in 0..40 {
                let want = if col < 10 && y >= 25 { [0, 0, 255] } else { [255, 0, 0] };
                assert_eq!(got[y * 40 + col], want, "pixel ({col}, {y}) from the top");
            }
        }
        glXMakeCurrent(dpy.cast(), 0, std::ptr::null());
        glXDestroyContext(dpy.cast(), ctx);
        glXDestroyGLXPixmap(dpy.cast(), glx_pixmap);
    }
}
