//! X11 helpers of the presentation tests: a private `Xvfb` server of a chosen depth, windows,
//! and reading pixels back with `XGetImage`. Included with `#[path]` by the tests that need it.

#![allow(dead_code)]

use std::ffi::CString;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use x11_dl::xlib::{self, Xlib};

/// A private Xvfb server, stopped on drop.
pub struct Xvfb {
    child: Child,
    /// `:N`.
    pub display: String,
}

static START: Mutex<()> = Mutex::new(());

impl Xvfb {
    /// Starts Xvfb with one `width`×`height` screen of `depth` bits; `None` (after saying so on
    /// stderr) when Xvfb is not installed, so that machines without it skip these tests.
    pub fn start(depth: u32) -> Option<Xvfb> {
        Xvfb::start_with(depth, false)
    }

    /// [`Xvfb::start`], also listening on TCP (port 6000 + N) when `tcp`: clients connected
    /// through it are remote to the server (no MIT-SHM).
    pub fn start_with(depth: u32, tcp: bool) -> Option<Xvfb> {
        let _one = START.lock().unwrap_or_else(|e| e.into_inner());
        for n in 100 + std::process::id() % 100..600 {
            if Path::new(&format!("/tmp/.X{n}-lock")).exists() {
                continue;
            }
            let screen = format!("640x480x{depth}");
            let spawned = Command::new("Xvfb")
                .args([format!(":{n}").as_str(), "-screen", "0", screen.as_str()])
                .args(if tcp { ["-listen", "tcp"] } else { ["-nolisten", "tcp"] })
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn();
            let mut child = match spawned {
                Ok(c) => c,
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                    eprintln!("skipped: Xvfb is not installed (bash scripts/setup.sh installs it)");
                    return None;
                }
                Err(e) => panic!("cannot start Xvfb: {e}"),
            };
            let socket = format!("/tmp/.X11-unix/X{n}");
            let start = Instant::now();
            while start.elapsed() < Duration::from_secs(10) {
                if child.try_wait().ok().flatten().is_some() {
                    break;
                }
                if Path::new(&socket).exists() {
                    return Some(Xvfb { child, display: format!(":{n}") });
                }
                std::thread::sleep(Duration::from_millis(20));
            }
            let _ = child.kill();
            let _ = child.wait();
        }
        panic!("no free X display for Xvfb");
    }

    /// Opens a connection to the server (retrying while it starts).
    pub fn open(&self, x: &Xlib) -> *mut xlib::Display {
        self.open_named(x, &self.display)
    }

    /// Opens a connection over TCP (`localhost:N`; the server must listen on TCP).
    pub fn open_tcp(&self, x: &Xlib) -> *mut xlib::Display {
        self.open_named(x, &format!("localhost{}", self.display))
    }

    fn open_named(&self, x: &Xlib, name: &str) -> *mut xlib::Display {
        let name = CString::new(name).unwrap();
        let deadline = Instant::now() + Duration::from_secs(10);
        loop {
            // Safety: a valid display name.
            let dpy = unsafe { (x.XOpenDisplay)(name.as_ptr()) };
            if !dpy.is_null() {
                return dpy;
            }
            assert!(Instant::now() < deadline, "cannot connect to Xvfb {}", self.display);
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        // SIGTERM, not SIGKILL: Xvfb then removes its /tmp/.X<n>-lock and socket, which
        // would otherwise pile up and use every display number.
        let _ = std::process::Command::new("kill").arg(self.child.id().to_string()).status();
        let _ = self.child.wait();
    }
}

/// Creates and maps a `width`×`height` window of the default visual at (0, 0), with a black
/// background and no window manager in between (Xvfb has none): it is viewable once this
/// returns.
pub fn mapped_window(x: &Xlib, dpy: *mut xlib::Display, width: u32, height: u32) -> xlib::Window {
    // Safety: plain Xlib calls on a live display.
    unsafe {
        let screen = (x.XDefaultScreen)(dpy);
        let root = (x.XRootWindow)(dpy, screen);
        let black = (x.XBlackPixel)(dpy, screen);
        let win = (x.XCreateSimpleWindow)(dpy, root, 0, 0, width, height, 0, black, black);
        (x.XMapWindow)(dpy, win);
        (x.XSync)(dpy, xlib::False);
        win
    }
}

/// The RGB of each pixel of `drawable` (`width`×`height` from its top-left corner), rows top to
/// bottom, decoded with the masks of the screen's default visual (`XGetImage` leaves an image's
/// masks empty for pixmaps) and scaled back to 8 bits as `round(v * 255 / max)`.
pub fn read_rgb(x: &Xlib, dpy: *mut xlib::Display, drawable: xlib::Drawable, width: u32, height: u32) -> Vec<[u8; 3]> {
    // Safety: plain Xlib calls on a live display; the image is checked and destroyed.
    unsafe {
        let image = (x.XGetImage)(dpy, drawable, 0, 0, width, height, !0, xlib::ZPixmap);
        assert!(!image.is_null(), "XGetImage failed");
        let visual = (x.XDefaultVisual)(dpy, (x.XDefaultScreen)(dpy));
        let masks = [(*visual).red_mask, (*visual).green_mask, (*visual).blue_mask];
        let mut out = Vec::with_capacity((width * height) as usize);
        for y in 0..height as i32 {
            for x_ in 0..width as i32 {
                let p = (x.XGetPixel)(image, x_, y);
                out.push(masks.map(|m| {
                    let shift = m.trailing_zeros();
                    let max = m >> shift;
                    ((((p & m) >> shift) * 255 + max / 2) / max) as u8
                }));
            }
        }
        (x.XDestroyImage)(image);
        out
    }
}
