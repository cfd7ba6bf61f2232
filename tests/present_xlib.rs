//! The Xlib presenter against real X servers (Xvfb): an RGBA image put on a window, a resized
//! window and a pixmap, read back with `XGetImage` and compared pixel by pixel, through MIT-SHM
//! and through `XPutImage`, on a 24-bit and a 16-bit (RGB565) screen; over TCP the server
//! refuses MIT-SHM segments and the presenter falls back to `XPutImage`; a closed display is
//! not touched. The library's X error trap: nested traps, traps on several threads at once,
//! the application's handler restored and its errors passed on. The tests run in parallel:
//! the application's handler is installed once, before any trap, and counts errors per
//! display. They fail when Xvfb is not installed.

#[path = "x11/mod.rs"]
mod x11;

use glrt::frame::{Surface, XDrawable};
use glrt::render::present::xlib::XlibPresenter;
use x11_dl::xlib::{self, Xlib};

/// A test image, rows bottom to top: red rises to the right, green upwards, blue on a checker.
fn pattern(w: u32, h: u32) -> Vec<u8> {
    let mut v = Vec::with_capacity((w * h * 4) as usize);
    for y in 0..h {
        for x in 0..w {
            let checker = if (x / 4 + y / 4) % 2 == 0 { 255 } else { 30 };
            v.extend_from_slice(&[(x * 255 / (w - 1)) as u8, (y * 255 / (h - 1)) as u8, checker, 128]);
        }
    }
    v
}

/// What a component reads back as on a server storing `bits` bits of it.
fn quantized(c: u8, bits: u32) -> u8 {
    let max = (1u32 << bits) - 1;
    let v = (c as u32 * max + 127) / 255;
    ((v * 255 + max / 2) / max) as u8
}

/// Asserts that `drawable` shows `rgba` (rows bottom to top) at its top-left corner.
fn assert_shows(x: &Xlib, dpy: *mut xlib::Display, drawable: u64, [w, h]: [u32; 2], rgba: &[u8], bits: [u32; 3], what: &str) {
    let got = x11::read_rgb(x, dpy, drawable, w, h);
    for y in 0..h {
        for col in 0..w {
            let src = &rgba[(((h - 1 - y) * w + col) * 4) as usize..][..3];
            let want = [quantized(src[0], bits[0]), quantized(src[1], bits[1]), quantized(src[2], bits[2])];
            assert_eq!(got[(y * w + col) as usize], want, "{what}: pixel ({col}, {y}) from the top");
        }
    }
}

/// Window, resize, pixmap and both transports on a screen of `depth` bits whose channels
/// have `bits` bits.
fn check_server(depth: u32, bits: [u32; 3]) {
    install_app_handler();
    let server = x11::Xvfb::start(depth);
    let x = Xlib::open().expect("libX11");
    let dpy = server.open(&x);
    let win = x11::mapped_window(&x, dpy, 64, 48);
    let on = |drawable| XDrawable { display: dpy.cast(), drawable };

    // Safety: `dpy` is live.
    let mut p = unsafe { XlibPresenter::new(Surface::Window(on(win))) }.expect("presenter for the window");
    let image = pattern(64, 48);
    assert!(p.present([64, 48], &image, true));
    assert!(p.uses_shm(), "a local Xvfb accepts MIT-SHM segments");
    assert_shows(&x, dpy, win, [64, 48], &image, bits, "window through MIT-SHM");

    // Resize, then a frame of the new size.
    unsafe { (x.XResizeWindow)(dpy, win, 80, 60) };
    let image = pattern(80, 60);
    assert!(p.present([80, 60], &image, true));
    assert_shows(&x, dpy, win, [80, 60], &image, bits, "resized window");

    // The same through XPutImage.
    p.disable_shm();
    let flipped: Vec<u8> = image.chunks(4).rev().flatten().copied().collect();
    assert!(p.present([80, 60], &flipped, true));
    assert!(!p.uses_shm());
    assert_shows(&x, dpy, win, [80, 60], &flipped, bits, "window through XPutImage");
    assert!(!p.present([80, 60], &flipped[..100], true), "a short buffer is refused");
    drop(p);

    // A pixmap of the screen's depth.
    let pixmap = unsafe { (x.XCreatePixmap)(dpy, win, 32, 16, depth) };
    let mut p = unsafe { XlibPresenter::new(Surface::Pixmap(on(pixmap))) }.expect("presenter for the pixmap");
    let image = pattern(32, 16);
    assert!(p.present([32, 16], &image, true));
    unsafe { (x.XSync)(dpy, xlib::False) };
    assert_shows(&x, dpy, pixmap, [32, 16], &image, bits, "pixmap");

    // Off-screen surfaces and missing drawables have no presenter.
    assert!(unsafe { XlibPresenter::new(Surface::Offscreen) }.is_none());
    assert!(unsafe { XlibPresenter::new(Surface::Window(on(0x7ff_fff0))) }.is_none(), "no such window (error trapped)");

    // Once the display is closed (glrt learns it through the XCloseDisplay hook registered
    // by the GLX layer), the presenter issues no request.
    unsafe { glrt::gl_entry::glx::connection(dpy.cast()) }.expect("connection");
    unsafe { (x.XCloseDisplay)(dpy) };
    assert!(!p.present([32, 16], &image, true), "closed display");
    drop(p);
}

#[test]
fn presents_on_a_24_bit_screen() {
    check_server(24, [8, 8, 8]);
}

#[test]
fn presents_on_a_16_bit_screen() {
    check_server(16, [5, 6, 5]);
}

#[test]
fn falls_back_to_put_image_when_the_server_refuses_shared_memory() {
    install_app_handler();
    let server = x11::Xvfb::start_with(24, true);
    let x = Xlib::open().expect("libX11");
    let dpy = server.open_tcp(&x);
    let win = x11::mapped_window(&x, dpy, 40, 30);
    let mut p = unsafe { XlibPresenter::new(Surface::Window(XDrawable { display: dpy.cast(), drawable: win })) }.unwrap();
    let image = pattern(40, 30);
    assert!(p.present([40, 30], &image, true));
    assert!(!p.uses_shm(), "a TCP client's segment is refused (BadAccess, trapped)");
    assert_shows(&x, dpy, win, [40, 30], &image, [8, 8, 8], "window over TCP");
}

/// The errors the application's handler received: display address and error code.
static APP_ERRORS: std::sync::Mutex<Vec<(usize, u8)>> = std::sync::Mutex::new(Vec::new());

unsafe extern "C" fn app_handler(dpy: *mut xlib::Display, e: *mut xlib::XErrorEvent) -> std::ffi::c_int {
    APP_ERRORS.lock().unwrap().push((dpy as usize, unsafe { (*e).error_code }));
    0
}

/// The error codes the application's handler received for `dpy`.
fn app_errors(dpy: *mut xlib::Display) -> Vec<u8> {
    APP_ERRORS.lock().unwrap().iter().filter(|e| e.0 == dpy as usize).map(|e| e.1).collect()
}

/// Whether `handler` is [`app_handler`].
fn is_app_handler(handler: Option<glrt::render::present::x_errors::Handler>) -> bool {
    handler.is_some_and(|h| std::ptr::fn_addr_eq(h, app_handler as glrt::render::present::x_errors::Handler))
}

/// Installs [`app_handler`] as the application's error handler, once, before any test of this
/// file traps an error (each calls this first): Xlib has one handler per process.
fn install_app_handler() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    let x = Xlib::open().expect("libX11");
    ONCE.call_once(|| unsafe {
        (x.XSetErrorHandler)(Some(app_handler));
    });
}

/// A window id no server has given out.
const NO_WINDOW: u64 = 0x7ff_fff0;

/// A trap inside a trap keeps its own errors, the outer one its first, and the application's
/// handler is back afterwards.
#[test]
fn nested_traps_keep_their_own_errors_and_restore_the_application_handler() {
    use glrt::render::present::x_errors::{application_handler, trapped, trapped_reply};
    install_app_handler();
    let server = x11::Xvfb::start(24);
    let x = Xlib::open().expect("libX11");
    let dpy = server.open(&x);
    let outer = unsafe {
        trapped(&x, dpy, || {
            (x.XMapWindow)(dpy, NO_WINDOW);
            let inner = trapped(&x, dpy, || (x.XFreePixmap)(dpy, NO_WINDOW));
            assert_eq!(inner.err(), Some(xlib::BadPixmap), "the inner trap's own error");
            let (mut root, mut at, mut size, mut depth) = (0, [0; 2], [0u32; 2], [0u32; 2]);
            let reply = trapped_reply(&x, dpy, || {
                (x.XGetGeometry)(dpy, NO_WINDOW, &mut root, &mut at[0], &mut at[1], &mut size[0], &mut size[1], &mut depth[0], &mut depth[1])
            });
            assert_eq!(reply.err(), Some(xlib::BadDrawable), "the one-request trap's own error");
            assert!(is_app_handler(application_handler(&x)), "seen through the traps");
            let fine = trapped(&x, dpy, || (x.XNoOp)(dpy));
            assert!(fine.is_ok(), "a trap without errors");
        })
    };
    assert_eq!(outer.err(), Some(xlib::BadWindow), "the outer trap's first error");
    assert_eq!(app_errors(dpy), [], "no trapped error reached the application");
    unsafe {
        (x.XMapWindow)(dpy, NO_WINDOW);
        (x.XSync)(dpy, xlib::False);
    }
    assert_eq!(app_errors(dpy), [xlib::BadWindow], "the application's handler is back");
    assert!(is_app_handler(application_handler(&x)));
}

/// Four threads trap errors on their own connections at once while the application makes
/// bad requests on another: every trap gets exactly its own errors, the application all of its.
#[test]
fn traps_on_several_threads_at_once() {
    use glrt::render::present::x_errors::trapped;
    install_app_handler();
    let server = x11::Xvfb::start(24);
    let x = Xlib::open().expect("libX11");
    let app = server.open(&x);
    let displays: Vec<usize> = (0..4).map(|_| server.open(&x) as usize).collect();
    let threads: Vec<_> = displays
        .iter()
        .map(|&dpy| {
            std::thread::spawn(move || {
                let x = Xlib::open().expect("libX11");
                let dpy = dpy as *mut xlib::Display;
                let win = x11::mapped_window(&x, dpy, 8, 8);
                for i in 0..200 {
                    let bad = unsafe { trapped(&x, dpy, || (x.XMapWindow)(dpy, NO_WINDOW)) };
                    assert_eq!(bad.err(), Some(xlib::BadWindow), "iteration {i}");
                    let good = unsafe { trapped(&x, dpy, || (x.XMapWindow)(dpy, win)) };
                    assert!(good.is_ok(), "iteration {i}: {good:?}");
                }
            })
        })
        .collect();
    for _ in 0..50 {
        unsafe {
            (x.XMapWindow)(app, NO_WINDOW);
            (x.XSync)(app, xlib::False);
        }
    }
    for t in threads {
        t.join().expect("trapping thread");
    }
    assert_eq!(app_errors(app), vec![xlib::BadWindow; 50], "each of the application's errors reached its handler once");
    for &dpy in &displays {
        assert_eq!(app_errors(dpy as *mut xlib::Display), [], "no trapped error reached the application");
    }
}

/// The drawable size check run at every swap (one round trip): its own error is kept from the
/// application, an earlier error of the application's still reaches the application's handler.
#[test]
fn swap_size_check_traps_only_its_own_error() {
    install_app_handler();
    let server = x11::Xvfb::start(24);
    let x = Xlib::open().expect("libX11");
    let dpy = server.open(&x);
    let win = x11::mapped_window(&x, dpy, 40, 30);
    let (gx, gdpy) = unsafe { glrt::gl_entry::glx::connection(dpy.cast()) }.expect("connection");
    // The application's bad request, not yet synced.
    unsafe { (x.XMapWindow)(dpy, 0x7ff_fff0) };
    let size = unsafe { glrt::gl_entry::glx::drawable::x_geometry(gx, gdpy, win) };
    assert_eq!(size, Some((40, 30, 24)));
    assert_eq!(app_errors(dpy), [xlib::BadWindow], "the application's error reached its handler");
    assert_eq!(unsafe { glrt::gl_entry::glx::drawable::x_geometry(gx, gdpy, 0x7ff_fff0) }, None);
    unsafe { (x.XSync)(dpy, xlib::False) };
    assert_eq!(app_errors(dpy).len(), 1, "glrt's own error was trapped");
    let start = std::time::Instant::now();
    for _ in 0..500 {
        unsafe { glrt::gl_entry::glx::drawable::x_geometry(gx, gdpy, win) };
    }
    eprintln!("size check: {:?} per swap", start.elapsed() / 500);
}
