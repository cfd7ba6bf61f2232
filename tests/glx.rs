//! GLX 1.4 against a real X server: starts `Xvfb` on a free display, then drives glrt's
//! exported `glX*` and `gl*` functions (called as Rust functions) on an Xlib connection:
//! visuals and configurations against the server's visuals, contexts, make-current and the
//! initial viewport, drawables and pbuffers, swaps and the frame log, share lists, X errors,
//! `glXGetProcAddress`, `glXUseXFont`.
//!
//! One test function: the frame log is chosen by an environment variable read when a context
//! is created, and the X server is shared by every step.

#[path = "x11/mod.rs"]
mod x11;

use std::collections::HashMap;
use std::ffi::{c_int, c_uint, c_ulong};
use std::sync::atomic::{AtomicU8, Ordering};

use glrt::gl_entry::exports as gl;
use glrt::gl_entry::glx::exports::config::*;
use glrt::gl_entry::glx::exports::context::*;
use glrt::gl_entry::glx::exports::drawable::*;
use glrt::gl_entry::glx::exports::query::*;
use glrt::gl_entry::glx::exports::swap::*;
use glrt::gl_entry::glx::exports::xfont::glXUseXFont;
use glrt::gl_entry::glx::types::types;
use glrt::translate::gl::{
    GL_ALPHA_BITS, GL_COLOR_BUFFER_BIT, GL_COMPILE, GL_RGBA, GL_SAMPLE_BUFFERS, GL_SAMPLES, GL_UNSIGNED_BYTE, GL_VIEWPORT,
};
use x11_dl::glx::arb::*;
use x11_dl::glx::ext::*;
use x11_dl::glx::*;
use x11_dl::xlib::{self, Xlib};

static LAST_ERROR: AtomicU8 = AtomicU8::new(0);

unsafe extern "C" fn record_error(_: *mut xlib::Display, e: *mut xlib::XErrorEvent) -> c_int {
    LAST_ERROR.store(unsafe { (*e).error_code }, Ordering::SeqCst);
    0
}

fn take_error() -> u8 {
    LAST_ERROR.swap(0, Ordering::SeqCst)
}

fn viewport() -> [i32; 4] {
    let mut v = [0; 4];
    unsafe { gl::glGetIntegerv(GL_VIEWPORT, v.as_mut_ptr()) };
    v
}

fn fb_attrib(dpy: *mut types::Display, config: types::GLXFBConfig, attribute: c_int) -> c_int {
    let mut v = -1;
    assert_eq!(unsafe { glXGetFBConfigAttrib(dpy, config, attribute, &mut v) }, 0, "attribute {attribute:#x}");
    v
}

/// The server's visuals usable for RGBA rendering (TrueColor/DirectColor, depth 24 or 32),
/// with their depths and classes.
fn server_visuals(x: &Xlib, dpy: *mut xlib::Display) -> HashMap<c_ulong, (c_int, c_int)> {
    unsafe {
        let mut template: xlib::XVisualInfo = std::mem::zeroed();
        let mut n = 0;
        let list = (x.XGetVisualInfo)(dpy, xlib::VisualNoMask, &mut template, &mut n);
        let all = std::slice::from_raw_parts(list, n as usize);
        let set = all
            .iter()
            .filter(|v| matches!(v.class, xlib::TrueColor | xlib::DirectColor) && matches!(v.depth, 24 | 32))
            .map(|v| (v.visualid, (v.depth, v.class)))
            .collect();
        (x.XFree)(list.cast());
        set
    }
}

fn create_window(x: &Xlib, dpy: *mut xlib::Display, vis: &xlib::XVisualInfo, w: c_uint, h: c_uint) -> xlib::Window {
    unsafe {
        let root = (x.XRootWindow)(dpy, vis.screen);
        let mut attrs: xlib::XSetWindowAttributes = std::mem::zeroed();
        attrs.colormap = (x.XCreateColormap)(dpy, root, vis.visual, xlib::AllocNone);
        let mask = xlib::CWColormap | xlib::CWBorderPixel;
        (x.XCreateWindow)(dpy, root, 0, 0, w, h, 0, vis.depth, xlib::InputOutput as c_uint, vis.visual, mask, &mut attrs)
    }
}

#[test]
fn glx_on_xvfb() {
    let x = Xlib::open().expect("libX11");
    let server = x11::Xvfb::start(24);
    let xdpy = server.open(&x);
    let dpy = xdpy.cast::<types::Display>();
    unsafe { (x.XSetErrorHandler)(Some(record_error)) };
    let usable = server_visuals(&x, xdpy);
    assert!(!usable.is_empty());

    // Version, strings, extension.
    let (mut major, mut minor) = (0, 0);
    assert_eq!(unsafe { glXQueryVersion(dpy, &mut major, &mut minor) }, 1);
    assert_eq!((major, minor), (1, 4));
    let (mut error_base, mut event_base) = (-1, -1);
    assert_eq!(unsafe { glXQueryExtension(dpy, &mut error_base, &mut event_base) }, 1);
    assert!(error_base >= 0 && event_base >= 0);
    let ext = unsafe { std::ffi::CStr::from_ptr(glXQueryExtensionsString(dpy, 0)) }.to_str().unwrap();
    assert!(ext.split(' ').any(|e| e == "GLX_ARB_create_context"));
    assert!(ext.split(' ').any(|e| e == "GLX_ARB_multisample"));
    let vendor = unsafe { std::ffi::CStr::from_ptr(glXGetClientString(dpy, GLX_VENDOR)) };
    assert_eq!(vendor.to_bytes(), b"glrt");
    assert!(glXQueryServerString(dpy, 0, 99).is_null());

    // Configurations: per group of usable server visuals of one depth and class, four RGBA kinds
    // per sample count (single-sampled, then each count the Vulkan device renders
    // multisampled) and four RGB ones more at depth 24, dealt out over the group's visuals:
    // as many configurations as the larger of the two counts.
    let counts = glrt::render::multisample_counts();
    let mut n = 0;
    let configs = unsafe { glXGetFBConfigs(dpy, 0, &mut n) };
    let mut groups: HashMap<(c_int, c_int), usize> = HashMap::new();
    for &group in usable.values() {
        *groups.entry(group).or_default() += 1;
    }
    let kinds = |depth| if depth == 24 { 8 } else { 4 } * (1 + counts.len());
    let expected: usize = groups.iter().map(|(&(depth, _), &visuals)| visuals.max(kinds(depth))).sum();
    assert_eq!(n as usize, expected);
    let all = unsafe { std::slice::from_raw_parts(configs, n as usize) }.to_vec();
    unsafe { (x.XFree)(configs.cast()) };
    for &c in &all {
        let (depth, _) = usable[&(fb_attrib(dpy, c, GLX_VISUAL_ID) as c_ulong)];
        let alpha = fb_attrib(dpy, c, GLX_ALPHA_SIZE);
        assert!(alpha == 8 || (alpha == 0 && depth == 24), "alpha {alpha} on a visual of depth {depth}");
        assert_eq!(fb_attrib(dpy, c, GLX_BUFFER_SIZE), 24 + alpha);
        assert_eq!(fb_attrib(dpy, c, GLX_RENDER_TYPE), GLX_RGBA_BIT);
        assert_eq!(fb_attrib(dpy, c, GLX_X_RENDERABLE), 1);
        let samples = fb_attrib(dpy, c, GLX_SAMPLES);
        assert!(samples == 0 || counts.contains(&(samples as u32)), "GLX_SAMPLES {samples} is rendered");
        assert_eq!(fb_attrib(dpy, c, GLX_SAMPLE_BUFFERS), c_int::from(samples > 0));
    }
    assert_eq!(fb_attrib(dpy, all[0], GLX_SAMPLES), 0, "single-sampled configurations first");
    // Xvfb's GLX extension gives it a visual for every kind: no two configurations share one.
    assert!(groups.iter().all(|(&(depth, _), &visuals)| visuals >= kinds(depth)), "Xvfb has few visuals: {groups:?}");
    let mut named: Vec<c_int> = all.iter().map(|&c| fb_attrib(dpy, c, GLX_VISUAL_ID)).collect();
    named.sort_unstable();
    named.dedup();
    assert_eq!(named.len(), all.len(), "a visual names one configuration");
    assert!(unsafe { glXGetFBConfigs(dpy, 7, &mut n) }.is_null());
    assert_eq!(n, 0);

    let wanted = [GLX_DOUBLEBUFFER, 1, GLX_DEPTH_SIZE, 24, GLX_STENCIL_SIZE, 8, GLX_DRAWABLE_TYPE, GLX_PBUFFER_BIT, 0];
    let chosen = unsafe { glXChooseFBConfig(dpy, 0, wanted.as_ptr(), &mut n) };
    assert!(n > 0 && (n as usize) < all.len());
    let fbconfig = unsafe { *chosen };
    unsafe { (x.XFree)(chosen.cast()) };
    assert_eq!(fb_attrib(dpy, fbconfig, GLX_DOUBLEBUFFER), 1);
    assert_eq!(fb_attrib(dpy, fbconfig, GLX_STENCIL_SIZE), 8);
    let fb_vis = unsafe { glXGetVisualFromFBConfig(dpy, fbconfig) };
    assert_eq!(unsafe { (*fb_vis).visualid } as c_int, fb_attrib(dpy, fbconfig, GLX_VISUAL_ID));
    unsafe { (x.XFree)(fb_vis.cast()) };

    // glXChooseVisual and glXGetConfig.
    let mut attribs = [GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, GLX_DEPTH_SIZE, 16, 0];
    let vis = unsafe { glXChooseVisual(dpy, 0, attribs.as_mut_ptr()) };
    assert!(!vis.is_null());
    let xvis = unsafe { &*vis.cast::<xlib::XVisualInfo>() };
    assert!(usable.contains_key(&xvis.visualid));
    let config_value = |attribute| {
        let mut v = -1;
        assert_eq!(unsafe { glXGetConfig(dpy, vis, attribute, &mut v) }, 0);
        v
    };
    assert_eq!(config_value(GLX_USE_GL), 1);
    assert_eq!(config_value(GLX_DOUBLEBUFFER), 1);
    assert!(config_value(GLX_DEPTH_SIZE) >= 16);
    assert_eq!(config_value(GLX_ALPHA_SIZE), 0, "no alpha asked for: an RGB visual (smaller buffer)");
    let mut v = 0;
    assert_eq!(unsafe { glXGetConfig(dpy, vis, 0x7777, &mut v) }, GLX_BAD_ATTRIBUTE);
    let mut color_index = [GLX_DOUBLEBUFFER, 0];
    assert!(unsafe { glXChooseVisual(dpy, 0, color_index.as_mut_ptr()) }.is_null());

    // A window, a context with the frame log, make-current and the initial viewport.
    let win = create_window(&x, xdpy, xvis, 320, 200);
    let log_path = std::env::temp_dir().join(format!("glrt-glx-test-{}.jsonl", std::process::id()));
    let _ = std::fs::remove_file(&log_path);
    unsafe { std::env::set_var("GLRT_FRAME_LOG", &log_path) };
    let ctx = unsafe { glXCreateContext(dpy, vis, std::ptr::null(), 1) };
    unsafe { std::env::remove_var("GLRT_FRAME_LOG") };
    assert!(!ctx.is_null());
    assert_eq!(glXIsDirect(dpy, ctx), 1);
    assert_eq!(unsafe { glXMakeCurrent(dpy, win, ctx) }, 1);
    assert_eq!(glXGetCurrentContext(), ctx);
    assert_eq!(glXGetCurrentDrawable(), win);
    assert_eq!(glXGetCurrentReadDrawable(), win);
    assert_eq!(glXGetCurrentDisplay(), dpy);
    assert_eq!(viewport(), [0, 0, 320, 200]);
    let query = |d, attribute| {
        let mut v = u32::MAX;
        unsafe { glXQueryDrawable(dpy, d, attribute, &mut v) };
        v
    };
    assert_eq!((query(win, GLX_WIDTH), query(win, GLX_HEIGHT)), (320, 200));
    let mut id = 0;
    assert_eq!(unsafe { glXQueryContext(dpy, ctx, GLX_FBCONFIG_ID, &mut id) }, 0);
    assert_eq!(query(win, GLX_FBCONFIG_ID), id as u32);

    // Three swaps: three frames in the log.
    for _ in 0..3 {
        unsafe { glXSwapBuffers(dpy, win) };
    }
    let log = std::fs::read_to_string(&log_path).expect("frame log written");
    let _ = std::fs::remove_file(&log_path);
    let frames: Vec<&str> = log.lines().collect();
    assert_eq!(frames.len(), 3, "{log}");
    assert!(frames[2].starts_with("{\"frame\":2,\"draws\":"), "{log}");

    // Swap intervals.
    assert_eq!(query(win, GLX_SWAP_INTERVAL_EXT), 1);
    unsafe { glXSwapIntervalEXT(dpy, win, 0) };
    assert_eq!(query(win, GLX_SWAP_INTERVAL_EXT), 0);
    assert_eq!(glXSwapIntervalMESA(2), 0);
    assert_eq!(glXGetSwapIntervalMESA(), 2);
    assert_eq!(glXSwapIntervalSGI(0), GLX_BAD_VALUE);

    // Share lists: a list made in one context is a list in the other, not in a third.
    let list = unsafe { gl::glGenLists(1) };
    unsafe {
        gl::glNewList(list, GL_COMPILE);
        gl::glEndList();
    }
    let shared = unsafe { glXCreateContext(dpy, vis, ctx, 1) };
    let alone = unsafe { glXCreateNewContext(dpy, fbconfig, GLX_RGBA_TYPE, std::ptr::null(), 1) };
    assert!(!shared.is_null() && !alone.is_null());
    assert_eq!(unsafe { glXMakeCurrent(dpy, win, shared) }, 1);
    assert_eq!(unsafe { gl::glIsList(list) }, 1);
    assert_eq!(unsafe { glXMakeContextCurrent(dpy, win, win, alone) }, 1);
    assert_eq!(unsafe { gl::glIsList(list) }, 0);

    // glXGetProcAddress.
    let proc = |name: &[u8]| unsafe { glXGetProcAddressARB(name.as_ptr()) };
    assert_eq!(proc(b"glXCreateContext\0") as usize, glXCreateContext as *const () as usize);
    assert_eq!(proc(b"glIsList\0") as usize, gl::glIsList as *const () as usize);
    assert!(proc(b"glNoSuchFunction\0").is_null());
    assert!(unsafe { glXGetProcAddress(std::ptr::null()) }.is_null());

    // A pbuffer: size, attributes, make-current, destroy; then the X error of a stale one.
    let pb_attribs = [GLX_PBUFFER_WIDTH, 64, GLX_PBUFFER_HEIGHT, 32, 0];
    let pbuffer = unsafe { glXCreatePbuffer(dpy, fbconfig, pb_attribs.as_ptr()) };
    assert_ne!(pbuffer, 0);
    assert_eq!((query(pbuffer, GLX_WIDTH), query(pbuffer, GLX_HEIGHT)), (64, 32));
    assert_eq!(query(pbuffer, GLX_LARGEST_PBUFFER), 0);
    assert_eq!(query(pbuffer, GLX_PRESERVED_CONTENTS), 1);
    assert_eq!(query(pbuffer, GLX_FBCONFIG_ID) as c_int, fb_attrib(dpy, fbconfig, GLX_FBCONFIG_ID));
    let pb_ctx = unsafe { glXCreateNewContext(dpy, fbconfig, GLX_RGBA_TYPE, std::ptr::null(), 1) };
    assert_eq!(unsafe { glXMakeContextCurrent(dpy, pbuffer, pbuffer, pb_ctx) }, 1);
    assert_eq!(viewport(), [0, 0, 64, 32]);
    unsafe { glXSelectEvent(dpy, pbuffer, GLX_PBUFFER_CLOBBER_MASK) };
    let mut mask = 0;
    unsafe { glXGetSelectedEvent(dpy, pbuffer, &mut mask) };
    assert_eq!(mask, GLX_PBUFFER_CLOBBER_MASK);
    unsafe { glXDestroyPbuffer(dpy, pbuffer) };
    take_error();
    unsafe { glXDestroyPbuffer(dpy, pbuffer) };
    assert_eq!(take_error() as c_int, error_base + 10, "GLXBadPbuffer");
    let too_big = [GLX_PBUFFER_WIDTH, 1 << 20, GLX_PBUFFER_HEIGHT, 1, 0];
    assert_eq!(unsafe { glXCreatePbuffer(dpy, fbconfig, too_big.as_ptr()) }, 0);
    assert_eq!(take_error(), 11, "BadAlloc");

    // A GLX window on a window of the configuration's visual: its own XID, the X window's
    // size; BadMatch for a configuration of another visual, BadAlloc for a second one.
    let fb_vis = unsafe { glXGetVisualFromFBConfig(dpy, fbconfig) };
    let fb_win = create_window(&x, xdpy, unsafe { &*fb_vis.cast() }, 100, 50);
    let visual_id = unsafe { (*fb_vis).visualid };
    unsafe { (x.XFree)(fb_vis.cast()) };
    let other = all.iter().find(|&&c| fb_attrib(dpy, c, GLX_VISUAL_ID) as c_ulong != visual_id).unwrap();
    assert_eq!(unsafe { glXCreateWindow(dpy, *other, fb_win, std::ptr::null()) }, 0);
    assert_eq!(take_error(), 8, "BadMatch");
    let glx_win = unsafe { glXCreateWindow(dpy, fbconfig, fb_win, std::ptr::null()) };
    assert!(glx_win != 0 && glx_win != fb_win);
    assert_eq!((query(glx_win, GLX_WIDTH), query(glx_win, GLX_HEIGHT)), (100, 50));
    assert_eq!(unsafe { glXCreateWindow(dpy, fbconfig, fb_win, std::ptr::null()) }, 0);
    assert_eq!(take_error(), 11, "BadAlloc");
    assert_eq!(unsafe { glXMakeContextCurrent(dpy, glx_win, glx_win, pb_ctx) }, 1);
    assert_eq!(glXGetCurrentDrawable(), glx_win);
    unsafe { glXDestroyWindow(dpy, glx_win) };
    assert_eq!(take_error(), 0);
    unsafe { glXDestroyWindow(dpy, glx_win) };
    assert_eq!(take_error() as c_int, error_base + 12, "GLXBadWindow");

    // GLX pixmaps (1.2 and 1.3 styles) take the X pixmap's size; a depth-1 pixmap is BadMatch.
    let root = unsafe { (x.XRootWindow)(xdpy, 0) };
    let pixmap = unsafe { (x.XCreatePixmap)(xdpy, root, 40, 30, 24) };
    let glx_pixmap = unsafe { glXCreateGLXPixmap(dpy, vis, pixmap) };
    assert_ne!(glx_pixmap, 0);
    assert_eq!((query(glx_pixmap, GLX_WIDTH), query(glx_pixmap, GLX_HEIGHT)), (40, 30));
    let pixmap_ctx = unsafe { glXCreateContext(dpy, vis, std::ptr::null(), 1) };
    assert_eq!(unsafe { glXMakeCurrent(dpy, glx_pixmap, pixmap_ctx) }, 1);
    assert_eq!(viewport(), [0, 0, 40, 30]);
    unsafe { glXDestroyGLXPixmap(dpy, glx_pixmap) };
    let bitmap = unsafe { (x.XCreatePixmap)(xdpy, root, 8, 8, 1) };
    assert_eq!(unsafe { glXCreatePixmap(dpy, fbconfig, bitmap, std::ptr::null()) }, 0);
    assert_eq!(take_error(), 8, "BadMatch");
    let glx_pixmap = unsafe { glXCreatePixmap(dpy, fbconfig, pixmap, std::ptr::null()) };
    assert_ne!(glx_pixmap, 0);
    unsafe { glXDestroyPixmap(dpy, glx_pixmap) };
    assert_eq!(take_error(), 0);
    unsafe { glXDestroyContext(dpy, pixmap_ctx) };

    // Errors of bad arguments go to the application's handler and do not kill it.
    assert_eq!(unsafe { glXMakeCurrent(dpy, 0x7fff_fff0, ctx) }, 0);
    assert_eq!(take_error() as c_int, error_base + 2, "GLXBadDrawable");
    let core = [GLX_CONTEXT_MAJOR_VERSION_ARB, 3, GLX_CONTEXT_MINOR_VERSION_ARB, 3, 0];
    assert!(unsafe { glXCreateContextAttribsARB(dpy, fbconfig, std::ptr::null(), 1, core.as_ptr()) }.is_null());
    assert_eq!(take_error(), 8, "BadMatch");
    let legacy = [GLX_CONTEXT_MAJOR_VERSION_ARB, 1, GLX_CONTEXT_MINOR_VERSION_ARB, 4, 0];
    let attribs_ctx = unsafe { glXCreateContextAttribsARB(dpy, fbconfig, std::ptr::null(), 1, legacy.as_ptr()) };
    assert!(!attribs_ctx.is_null());

    // Releasing needs no display.
    assert_eq!(unsafe { glXMakeCurrent(std::ptr::null_mut(), 0, std::ptr::null()) }, 1);
    assert!(glXGetCurrentContext().is_null() && glXGetCurrentDisplay().is_null());

    // glXUseXFont: one list per character.
    assert_eq!(unsafe { glXMakeCurrent(dpy, win, ctx) }, 1);
    let font = unsafe { (x.XLoadQueryFont)(xdpy, c"fixed".as_ptr()) };
    assert!(!font.is_null(), "the server's built-in font");
    let base = unsafe { gl::glGenLists(96) };
    glXUseXFont(unsafe { (*font).fid }, 32, 96, base as c_int);
    for l in base..base + 96 {
        assert_eq!(unsafe { gl::glIsList(l) }, 1, "list {l}");
    }
    assert_eq!(unsafe { gl::glIsList(base + 96) }, 0);

    // A context destroyed while current lives until released.
    unsafe { glXDestroyContext(dpy, ctx) };
    assert_eq!(glXGetCurrentContext(), ctx);
    assert_eq!(viewport(), [0, 0, 320, 200]);
    assert_eq!(unsafe { glXMakeCurrent(dpy, 0, std::ptr::null()) }, 1);
    assert!(glXGetCurrentContext().is_null());
    assert_eq!(glXIsDirect(dpy, ctx), 0, "freed once released");
    assert_eq!(unsafe { glXMakeCurrent(dpy, win, ctx) }, 0);
    assert_eq!(take_error() as c_int, error_base, "GLXBadContext");

    // A multisampled configuration (when the device renders one): GL_SAMPLES answers it.
    if let Some(&samples) = counts.first() {
        let wanted = [GLX_SAMPLE_BUFFERS, 1, GLX_SAMPLES, samples as c_int, GLX_DRAWABLE_TYPE, GLX_PBUFFER_BIT, 0];
        let chosen = unsafe { glXChooseFBConfig(dpy, 0, wanted.as_ptr(), &mut n) };
        assert!(n > 0);
        let multi = unsafe { *chosen };
        unsafe { (x.XFree)(chosen.cast()) };
        assert_eq!(fb_attrib(dpy, multi, GLX_SAMPLES), samples as c_int);
        let pbuffer = unsafe { glXCreatePbuffer(dpy, multi, pb_attribs.as_ptr()) };
        let multi_ctx = unsafe { glXCreateNewContext(dpy, multi, GLX_RGBA_TYPE, std::ptr::null(), 1) };
        assert_eq!(unsafe { glXMakeContextCurrent(dpy, pbuffer, pbuffer, multi_ctx) }, 1);
        let mut v = [0; 2];
        unsafe {
            gl::glGetIntegerv(GL_SAMPLE_BUFFERS, &mut v[0]);
            gl::glGetIntegerv(GL_SAMPLES, &mut v[1]);
        }
        assert_eq!(v, [1, samples as i32]);
        unsafe {
            glXMakeContextCurrent(dpy, 0, 0, std::ptr::null());
            glXDestroyContext(dpy, multi_ctx);
            glXDestroyPbuffer(dpy, pbuffer);
        }
    }
    // RGB and RGBA configurations: GL_ALPHA_BITS answers the configuration, and alpha drawn
    // into an RGB drawable reads back as 1.
    for (wanted_alpha, bits, read) in [(0, 0, 255), (1, 8, 102)] {
        let wanted = [GLX_ALPHA_SIZE, wanted_alpha, GLX_DRAWABLE_TYPE, GLX_PBUFFER_BIT, 0];
        let chosen = unsafe { glXChooseFBConfig(dpy, 0, wanted.as_ptr(), &mut n) };
        assert!(n > 0);
        let config = unsafe { *chosen };
        unsafe { (x.XFree)(chosen.cast()) };
        assert_eq!(fb_attrib(dpy, config, GLX_ALPHA_SIZE), bits);
        let pbuffer = unsafe { glXCreatePbuffer(dpy, config, pb_attribs.as_ptr()) };
        let context = unsafe { glXCreateNewContext(dpy, config, GLX_RGBA_TYPE, std::ptr::null(), 1) };
        assert_eq!(unsafe { glXMakeContextCurrent(dpy, pbuffer, pbuffer, context) }, 1);
        let (mut alpha_bits, mut pixel) = (-1, [0u8; 4]);
        unsafe {
            gl::glGetIntegerv(GL_ALPHA_BITS, &mut alpha_bits);
            gl::glClearColor(0.0, 0.0, 1.0, 0.0);
            gl::glClear(GL_COLOR_BUFFER_BIT);
            gl::glColor4f(1.0, 0.0, 0.0, 0.4);
            gl::glRectf(-1.0, -1.0, 1.0, 1.0);
            gl::glReadPixels(1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel.as_mut_ptr().cast());
        }
        assert_eq!((alpha_bits, pixel), (bits, [255, 0, 0, read]), "GLX_ALPHA_SIZE {bits}");
        unsafe {
            glXMakeContextCurrent(dpy, 0, 0, std::ptr::null());
            glXDestroyContext(dpy, context);
            glXDestroyPbuffer(dpy, pbuffer);
        }
    }
    for c in [shared, alone, pb_ctx, attribs_ctx] {
        unsafe { glXDestroyContext(dpy, c) };
    }
    assert_eq!(take_error(), 0);
    // Closing the display forgets its drawables: a new connection (perhaps at the same
    // address) does not see the old pbuffer.
    let pbuffer = unsafe { glXCreatePbuffer(dpy, fbconfig, pb_attribs.as_ptr()) };
    assert_eq!(query(pbuffer, GLX_WIDTH), 64);
    unsafe {
        (x.XFree)(vis.cast());
        (x.XCloseDisplay)(xdpy);
    }
    let dpy = server.open(&x).cast::<types::Display>();
    let mut width = u32::MAX;
    unsafe { glXQueryDrawable(dpy, pbuffer, GLX_WIDTH, &mut width) };
    assert_eq!(width, u32::MAX);
    assert_eq!(take_error() as c_int, error_base + 2, "GLXBadDrawable");
    let again = unsafe { glXGetFBConfigs(dpy, 0, &mut n) };
    assert!(!again.is_null());
    assert_eq!(n as usize, all.len());
    unsafe { (x.XFree)(again.cast()) };

    // With Xlib's default handler (which exits) errors are only logged: the program lives.
    unsafe { (x.XSetErrorHandler)(None) };
    unsafe { glXDestroyPbuffer(dpy, pbuffer) };
    let ctx = unsafe { glXCreateNewContext(dpy, all[0], GLX_RGBA_TYPE, std::ptr::null(), 1) };
    assert_eq!(unsafe { glXMakeCurrent(dpy, 0x7fff_fff0, ctx) }, 0);
    unsafe { (x.XSync)(dpy.cast(), 0) };
    unsafe { glXDestroyContext(dpy, ctx) };
    unsafe { (x.XCloseDisplay)(dpy.cast()) };
}
