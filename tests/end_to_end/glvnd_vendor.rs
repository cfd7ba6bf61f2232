//! glrt as a glvnd GLX vendor, end to end: `libGLX_glrt.so.0` (a symlink to the built
//! `libglrt.so`) is found through `LD_LIBRARY_PATH` and chosen with
//! `__GLX_VENDOR_LIBRARY_NAME=glrt`, while the programs load the system's glvnd `libGL.so.1`.
//!
//! Two child processes on an `Xvfb` server: `glxinfo` (mesa-utils), and this test binary's
//! ignored test `glvnd_child`, which drives GLX and GL through glvnd's libraries (dispatch of
//! GL calls through libGLdispatch, and of the swap-interval extensions through glrt's
//! dispatchers).

use std::ffi::{CStr, c_int, c_uint, c_void};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::x11;

use x11_dl::glx::*;
use x11_dl::xlib::{self, Xlib};

/// Set in the environment of the child run of [`glvnd_child`].
const CHILD_VAR: &str = "GLRT_GLVND_CHILD";

/// A directory holding `libGLX_glrt.so.0` → the `libglrt.so` built with this test.
struct VendorDir(PathBuf);

impl VendorDir {
    fn new(tag: &str) -> VendorDir {
        let exe = std::env::current_exe().expect("test executable path");
        // The library cargo built with this test: target/<profile>/deps/libglrt.so, next to it
        // (cargo copies it to target/<profile>/ only for `cargo build`).
        let lib = exe.with_file_name("libglrt.so");
        assert!(
            lib.exists(),
            "{} is missing: cargo builds it with the tests",
            lib.display()
        );
        let dir = std::env::temp_dir().join(format!("glrt-glvnd-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("creating the vendor directory");
        std::os::unix::fs::symlink(&lib, dir.join("libGLX_glrt.so.0")).expect("symlinking the vendor library");
        VendorDir(dir)
    }

    /// `command` run on `server` with glrt as the GLX vendor (`with_vendor_dir`: whether the
    /// vendor library can be found at all).
    fn run(&self, server: &x11::Xvfb, mut command: Command, with_vendor_dir: bool) -> Output {
        command
            .env("DISPLAY", &server.display)
            .env("__GLX_VENDOR_LIBRARY_NAME", "glrt")
            .env("LD_DEBUG", "files");
        if with_vendor_dir {
            command.env("LD_LIBRARY_PATH", &self.0);
        } else {
            command.env_remove("LD_LIBRARY_PATH");
        }
        command.output().expect("running the child process")
    }
}

impl Drop for VendorDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Whether the dynamic loader's log (`LD_DEBUG=files`) shows glvnd's `libGLX.so.0` loading
/// `libGLX_glrt.so.0` from `vendor_dir`, and a `libGL.so.1` from elsewhere (the system's glvnd).
fn loaded_through_glvnd(stderr: &str, vendor_dir: &Path) -> bool {
    let vendor = format!("calling init: {}/libGLX_glrt.so.0", vendor_dir.display());
    let init = |l: &str| l.split_once("calling init: ").map(|(_, path)| path.to_owned());
    let by_libglx = stderr.lines().any(|l| {
        l.contains("file=libGLX_glrt.so.0") && l.contains("dynamically loaded by") && l.contains("/libGLX.so.0")
    });
    let system_libgl = stderr
        .lines()
        .filter_map(init)
        .any(|path| path.ends_with("/libGL.so.1") && !path.starts_with(&*vendor_dir.to_string_lossy()));
    by_libglx && system_libgl && stderr.lines().any(|l| l.contains(&vendor))
}

#[test]
fn glxinfo_reports_glrt_through_glvnd() {
    let glxinfo = Path::new("/usr/bin/glxinfo");
    assert!(
        glxinfo.exists(),
        "/usr/bin/glxinfo is missing: install mesa-utils (apt-get install mesa-utils)"
    );
    let server = x11::Xvfb::start(24);
    let vendor = VendorDir::new("glxinfo");

    let out = vendor.run(&server, Command::new(glxinfo), true);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "glxinfo failed: {stdout}\n{stderr}");
    assert!(
        loaded_through_glvnd(&stderr, &vendor.0),
        "glrt was not loaded by libGLX.so.0:\n{stderr}"
    );
    for expected in [
        "server glx vendor string: glrt",
        "client glx vendor string: glrt",
        "GLX version: 1.4",
        "OpenGL vendor string: glrt",
        "OpenGL version string: 2.0 glrt",
    ] {
        assert!(
            stdout.lines().any(|l| l.trim() == expected || l.starts_with(expected)),
            "no {expected:?} in:\n{stdout}"
        );
    }

    // Control: without the vendor library on the search path, glvnd cannot pick glrt.
    let out = vendor.run(&server, Command::new(glxinfo), false);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        !stdout.contains("OpenGL vendor string: glrt"),
        "glrt answered without its vendor library:\n{stdout}"
    );
}

#[test]
fn gl_and_glx_calls_reach_glrt_through_glvnd() {
    let server = x11::Xvfb::start(24);
    let vendor = VendorDir::new("child");
    let exe = std::env::current_exe().expect("test executable path");
    let frame_log = vendor.0.join("frames.jsonl");
    let mut command = Command::new(exe);
    // The child test's name in this binary: its module path without the crate.
    let child = module_path!().split_once("::").map_or(String::from("glvnd_child"), |(_, module)| format!("{module}::glvnd_child"));
    command.args(["--ignored", "--exact", child.as_str(), "--nocapture", "--test-threads=1"]);
    command.env(CHILD_VAR, "1").env("GLRT_FRAME_LOG", &frame_log);
    let out = vendor.run(&server, command, true);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success() && stdout.contains("1 passed"),
        "the child failed:\n{stdout}\n{stderr}"
    );
    assert!(
        loaded_through_glvnd(&stderr, &vendor.0),
        "glrt was not loaded by libGLX.so.0:\n{stderr}"
    );
    // The window's one frame, with its clear, presented by glXSwapBuffers through libGLX.
    let frames = std::fs::read_to_string(&frame_log).expect("the frame log");
    assert!(frames.starts_with("{\"frame\":0,\"draws\":0,\"vertices\":0,\"clears\":1,\"hash\":"), "{frames}");
    assert_eq!(frames.lines().count(), 1, "{frames}");
}

/// A GL or GLX function from glvnd's `glXGetProcAddress`, as type `F`.
///
/// # Safety
/// `F` is the function's C signature.
unsafe fn proc<F: Copy>(glx: &Glx, name: &CStr) -> F {
    let f = unsafe { (glx.glXGetProcAddress)(name.as_ptr().cast()) }.unwrap_or_else(|| panic!("no {name:?}"));
    assert_eq!(std::mem::size_of::<F>(), std::mem::size_of_val(&f));
    // Safety: as documented.
    unsafe { std::mem::transmute_copy(&f) }
}

/// Run by [`gl_and_glx_calls_reach_glrt_through_glvnd`] in a child process whose
/// `libGL.so.1` is glvnd's and whose GLX vendor is glrt.
#[test]
#[ignore = "run as a child process by gl_and_glx_calls_reach_glrt_through_glvnd"]
fn glvnd_child() {
    assert_eq!(
        std::env::var(CHILD_VAR).as_deref(),
        Ok("1"),
        "run by gl_and_glx_calls_reach_glrt_through_glvnd"
    );
    let x = Xlib::open().expect("libX11");
    let glx = Glx::open().expect("glvnd's libGL.so.1");
    unsafe {
        let dpy = (x.XOpenDisplay)(std::ptr::null());
        assert!(!dpy.is_null(), "cannot open the display");
        let screen = (x.XDefaultScreen)(dpy);
        let attrs = [GLX_DRAWABLE_TYPE, GLX_PBUFFER_BIT, GLX_RENDER_TYPE, GLX_RGBA_BIT, 0];
        let mut n = 0;
        let configs = (glx.glXChooseFBConfig)(dpy.cast(), screen, attrs.as_ptr(), &mut n);
        assert!(!configs.is_null() && n > 0, "no pbuffer configuration");
        let config = *configs;
        let pbuffer = (glx.glXCreatePbuffer)(
            dpy.cast(),
            config,
            [GLX_PBUFFER_WIDTH, 64, GLX_PBUFFER_HEIGHT, 32, 0].as_ptr(),
        );
        assert_ne!(pbuffer, 0);
        let context = (glx.glXCreateNewContext)(dpy.cast(), config, GLX_RGBA_TYPE, std::ptr::null_mut(), 1);
        assert!(!context.is_null());
        assert_eq!((glx.glXMakeContextCurrent)(dpy.cast(), pbuffer, pbuffer, context), 1);
        assert_eq!((glx.glXGetCurrentContext)(), context);

        // GL through libGLdispatch's table, built from glrt's getProcAddress.
        let get_string: unsafe extern "C" fn(c_uint) -> *const u8 = proc(&glx, c"glGetString");
        let vendor_string = CStr::from_ptr(get_string(0x1F00).cast()); // GL_VENDOR
        assert_eq!(vendor_string.to_str(), Ok("glrt"));
        let get_integerv: unsafe extern "C" fn(c_uint, *mut c_int) = proc(&glx, c"glGetIntegerv");
        let mut viewport = [-1; 4];
        get_integerv(0x0BA2, viewport.as_mut_ptr()); // GL_VIEWPORT
        assert_eq!(viewport, [0, 0, 64, 32], "the initial viewport is the pbuffer's size");
        let clear_color: unsafe extern "C" fn(f32, f32, f32, f32) = proc(&glx, c"glClearColor");
        let get_floatv: unsafe extern "C" fn(c_uint, *mut f32) = proc(&glx, c"glGetFloatv");
        clear_color(0.25, 0.5, 0.75, 1.0);
        let mut color = [0.0; 4];
        get_floatv(0x0C22, color.as_mut_ptr()); // GL_COLOR_CLEAR_VALUE
        assert_eq!(color, [0.25, 0.5, 0.75, 1.0]);

        // GLX extension functions libGLX does not know: glrt's dispatchers.
        let set_mesa: unsafe extern "C" fn(c_uint) -> c_int = proc(&glx, c"glXSwapIntervalMESA");
        let get_mesa: unsafe extern "C" fn() -> c_int = proc(&glx, c"glXGetSwapIntervalMESA");
        let set_sgi: unsafe extern "C" fn(c_int) -> c_int = proc(&glx, c"glXSwapIntervalSGI");
        let set_ext: unsafe extern "C" fn(*mut c_void, u64, c_int) = proc(&glx, c"glXSwapIntervalEXT");
        assert_eq!(set_mesa(2), 0);
        assert_eq!(get_mesa(), 2);
        assert_eq!(set_sgi(0), GLX_BAD_VALUE, "SGI_swap_control refuses 0");
        assert_eq!(set_sgi(4), 0);
        assert_eq!(get_mesa(), 4);
        set_ext(dpy.cast(), pbuffer, 3);
        assert_eq!(get_mesa(), 3);

        assert_eq!((glx.glXMakeContextCurrent)(dpy.cast(), 0, 0, std::ptr::null_mut()), 1);
        assert!((glx.glXGetCurrentContext)().is_null());
        // Without a current context the dispatchers find no vendor.
        assert_eq!(get_mesa(), 0);
        (glx.glXDestroyContext)(dpy.cast(), context);
        (glx.glXDestroyPbuffer)(dpy.cast(), pbuffer);

        // The legacy path (SDL2, GLUT): a visual, a window, glXCreateContext, one cleared frame.
        let mut attrs = [GLX_RGBA, GLX_DOUBLEBUFFER, 0];
        let visual = (glx.glXChooseVisual)(dpy.cast(), screen, attrs.as_mut_ptr());
        assert!(!visual.is_null(), "no double-buffered RGBA visual");
        let root = (x.XRootWindow)(dpy, screen);
        let mut wa: xlib::XSetWindowAttributes = std::mem::zeroed();
        wa.colormap = (x.XCreateColormap)(dpy, root, (*visual).visual.cast(), xlib::AllocNone);
        let window = (x.XCreateWindow)(
            dpy,
            root,
            0,
            0,
            80,
            60,
            0,
            (*visual).depth,
            xlib::InputOutput as c_uint,
            (*visual).visual.cast(),
            xlib::CWColormap,
            &mut wa,
        );
        let context = (glx.glXCreateContext)(dpy.cast(), visual, std::ptr::null_mut(), 1);
        assert!(!context.is_null());
        assert_eq!((glx.glXMakeCurrent)(dpy.cast(), window, context), 1);
        get_integerv(0x0BA2, viewport.as_mut_ptr()); // GL_VIEWPORT
        assert_eq!(viewport, [0, 0, 80, 60], "the initial viewport is the window's size");
        let clear: unsafe extern "C" fn(c_uint) = proc(&glx, c"glClear");
        clear(0x4000); // GL_COLOR_BUFFER_BIT
        (glx.glXSwapBuffers)(dpy.cast(), window);
        assert_eq!((glx.glXMakeCurrent)(dpy.cast(), 0, std::ptr::null_mut()), 1);
        (glx.glXDestroyContext)(dpy.cast(), context);
        (x.XDestroyWindow)(dpy, window);
        (x.XFreeColormap)(dpy, wa.colormap);
        (x.XFree)(visual.cast());
        (x.XFree)(configs.cast());
        (x.XCloseDisplay)(dpy);
    }
}
