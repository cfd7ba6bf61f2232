//! X11 helpers of the tests: the one way they start a private `Xvfb` server (of a chosen
//! screen; a test fails, saying how to install it, when Xvfb is missing), windows, and reading
//! pixels back with `XGetImage`. Included with `#[path]` by the tests that need it.

#![allow(dead_code)]

use std::ffi::CString;
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use x11_dl::xlib::{self, Xlib};

/// A private Xvfb server, stopped on drop.
pub struct Xvfb {
    child: Child,
    /// `:N`, for `DISPLAY`.
    pub display: String,
}

impl Xvfb {
    /// Starts Xvfb with one 640×480 screen of `depth` bits.
    pub fn start(depth: u32) -> Xvfb {
        Xvfb::launch(&format!("640x480x{depth}"), false)
    }

    /// [`Xvfb::start`], also listening on TCP (port 6000 + N) when `tcp`: clients connected
    /// through it are remote to the server (no MIT-SHM).
    pub fn start_with(depth: u32, tcp: bool) -> Xvfb {
        Xvfb::launch(&format!("640x480x{depth}"), tcp)
    }

    /// Starts Xvfb with screen 0 of `geometry` (`WxHxDEPTH`).
    pub fn with_screen(geometry: &str) -> Xvfb {
        Xvfb::launch(geometry, false)
    }

    /// Starts `Xvfb -displayfd`: the server picks a free display number itself and writes it
    /// to our pipe once it accepts connections, so parallel tests (of this process or others)
    /// never meet on one number. Panics, saying how to install it, when Xvfb is missing: a test
    /// that needs a server must not pass without one.
    fn launch(geometry: &str, tcp: bool) -> Xvfb {
        let spawned = Command::new("Xvfb")
            .args(["-displayfd", "1", "-screen", "0", geometry])
            .args(if tcp { ["-listen", "tcp"] } else { ["-nolisten", "tcp"] })
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn();
        let mut child = match spawned {
            Ok(child) => child,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                panic!("this test needs Xvfb, which is not installed: `bash scripts/setup.sh` (or `apt-get install xvfb`) installs it")
            }
            Err(e) => panic!("cannot start Xvfb: {e}"),
        };
        let mut line = String::new();
        let read = BufReader::new(child.stdout.take().expect("piped stdout")).read_line(&mut line);
        let number = line.trim().to_owned();
        let server = Xvfb { child, display: format!(":{number}") };
        assert!(read.is_ok() && !number.is_empty() && number.bytes().all(|b| b.is_ascii_digit()), "Xvfb did not report a display number");
        server
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
