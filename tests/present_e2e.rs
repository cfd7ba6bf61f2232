//! Presentation end to end: Mesa's `glxgears` and `glrt-demo` run with glrt's `libGL.so.1`
//! in Xvfb windows, and the windows are read back with `XGetImage` from another connection
//! (what `xwd` sees): the scene's colours must be on screen, and after the window is resized
//! the picture must fill the new size. Each runs twice: the path the device chooses (Vulkan
//! swapchain on lavapipe) and `GLRT_PRESENT=xlib` (the read-back fallback); the path taken is
//! read from glrt's log and printed. Skipped when Xvfb or glxgears is missing.

#[path = "x11/mod.rs"]
mod x11;

use std::ffi::CStr;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use x11_dl::xlib::{self, Xlib};

/// `target/<profile>/` with the `libGL.so.1` symlink to `libglrt.so` (as tests/demo.rs).
fn lib_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_BIN_EXE_glrt-demo")).parent().expect("target dir").to_path_buf();
    assert!(dir.join("libglrt.so").exists(), "{}/libglrt.so missing: run `cargo build`", dir.display());
    let link = dir.join("libGL.so.1");
    if std::fs::symlink_metadata(&link).is_err() {
        let _ = std::os::unix::fs::symlink("libglrt.so", &link);
    }
    dir
}

/// A program running through glrt on `server`, killed on drop; its stderr goes to a file.
struct Program {
    child: Child,
    stderr: PathBuf,
    frames: PathBuf,
}

impl Program {
    fn start(server: &x11::Xvfb, program: &str, args: &[&str], present: Option<&str>, tag: &str) -> Program {
        let base = std::env::temp_dir().join(format!("glrt-present-{tag}-{}", std::process::id()));
        let (stderr, frames) = (base.with_extension("log"), base.with_extension("jsonl"));
        let _ = std::fs::remove_file(&frames);
        let mut cmd = Command::new(program);
        cmd.args(args)
            .env("DISPLAY", &server.display)
            .env("LD_LIBRARY_PATH", lib_dir())
            .env("GLRT_LOG", "info")
            .env("GLRT_FRAME_LOG", &frames)
            .stdout(Stdio::null())
            .stderr(std::fs::File::create(&stderr).expect("log file"));
        match present {
            Some(p) => cmd.env("GLRT_PRESENT", p),
            None => cmd.env_remove("GLRT_PRESENT"),
        };
        Program { child: cmd.spawn().expect("spawn"), stderr, frames }
    }

    /// Frames presented so far (lines of the frame log).
    fn frames(&self) -> usize {
        std::fs::read_to_string(&self.frames).map_or(0, |t| t.lines().count())
    }

    /// Waits until `n` more frames than `after` were presented.
    fn wait_frames(&mut self, after: usize, n: usize) {
        let deadline = Instant::now() + Duration::from_secs(120);
        while self.frames() < after + n {
            assert!(self.child.try_wait().unwrap().is_none(), "the program exited:\n{}", self.log());
            assert!(Instant::now() < deadline, "only {} frames:\n{}", self.frames(), self.log());
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    fn log(&self) -> String {
        std::fs::read_to_string(&self.stderr).unwrap_or_default()
    }

    /// The presentation path glrt logged (`vulkan` or `xlib`).
    fn path(&self) -> String {
        let log = self.log();
        let line = log.lines().find(|l| l.contains("present: Window")).unwrap_or_else(|| panic!("no presenter logged:\n{log}"));
        line.rsplit(' ').next().unwrap_or_default().to_owned()
    }
}

impl Drop for Program {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_file(&self.stderr);
        let _ = std::fs::remove_file(&self.frames);
    }
}

/// The top-level window called `name` on `dpy`, once it is mapped.
fn find_window(x: &Xlib, dpy: *mut xlib::Display, name: &str) -> xlib::Window {
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        // Safety: plain Xlib calls; returned memory is freed with XFree.
        let found = unsafe {
            let (mut root, mut parent, mut children, mut count) = (0, 0, std::ptr::null_mut(), 0u32);
            (x.XQueryTree)(dpy, (x.XDefaultRootWindow)(dpy), &mut root, &mut parent, &mut children, &mut count);
            let windows = if children.is_null() { &[][..] } else { std::slice::from_raw_parts(children, count as usize) };
            let found = windows.iter().copied().find(|&w| {
                let mut title = std::ptr::null_mut();
                let named = (x.XFetchName)(dpy, w, &mut title) != 0 && !title.is_null();
                let same = named && CStr::from_ptr(title).to_bytes() == name.as_bytes();
                if named {
                    (x.XFree)(title.cast());
                }
                same
            });
            if !children.is_null() {
                (x.XFree)(children.cast());
            }
            found
        };
        if let Some(w) = found {
            return w;
        }
        assert!(Instant::now() < deadline, "no window called {name}");
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// The size of a window.
fn window_size(x: &Xlib, dpy: *mut xlib::Display, win: xlib::Window) -> [u32; 2] {
    // Safety: plain Xlib call with valid out-pointers.
    unsafe {
        let mut attrs: xlib::XWindowAttributes = std::mem::zeroed();
        (x.XGetWindowAttributes)(dpy, win, &mut attrs);
        [attrs.width as u32, attrs.height as u32]
    }
}

/// Pixels of `shot` (`w` wide) in the rectangle `[x0, y0, x1, y1)` that `f` accepts.
fn count(shot: &[[u8; 3]], w: u32, [x0, y0, x1, y1]: [u32; 4], f: impl Fn([i32; 3]) -> bool) -> usize {
    (y0..y1).flat_map(|y| (x0..x1).map(move |x| (y * w + x) as usize)).filter(|&i| f(shot[i].map(i32::from))).count()
}

fn red(p: [i32; 3]) -> bool {
    p[0] > p[1] + 40 && p[0] > p[2] + 40
}
fn green(p: [i32; 3]) -> bool {
    p[1] > p[0] + 40 && p[1] > p[2] + 20
}
fn blue(p: [i32; 3]) -> bool {
    p[2] > p[0] + 40 && p[2] > p[1] + 40
}

/// glxgears (300 × 300 window, black background, red, green and blue gears), then resized to
/// 500 × 400: glxgears' reshape widens the view, so gears reach past the old 300 × 300 corner.
fn check_glxgears(present: Option<&str>) {
    if !Path::new("/usr/bin/glxgears").exists() {
        eprintln!("skipped: glxgears is not installed (mesa-utils)");
        return;
    }
    let Some(server) = x11::Xvfb::start(24) else { return };
    let tag = format!("gears-{}", present.unwrap_or("auto"));
    let mut gears = Program::start(&server, "/usr/bin/glxgears", &[], present, &tag);
    let x = Xlib::open().expect("libX11");
    let dpy = server.open(&x);
    let win = find_window(&x, dpy, "glxgears");
    gears.wait_frames(0, 5);
    let path = gears.path();
    eprintln!("glxgears, GLRT_PRESENT={present:?}: presented through {path}");
    if present == Some("xlib") {
        assert_eq!(path, "xlib");
    }
    let [w, h] = window_size(&x, dpy, win);
    let shot = x11::read_rgb(&x, dpy, win, w, h);
    let all = [0, 0, w, h];
    let (r, g, b) = (count(&shot, w, all, red), count(&shot, w, all, green), count(&shot, w, all, blue));
    eprintln!("{w}x{h}: {r} red, {g} green, {b} blue pixels");
    assert!(r > 2000 && g > 500 && b > 500, "gears on screen: {r} red, {g} green, {b} blue pixels");
    assert_eq!(shot[0], [0, 0, 0], "black background in the corner");

    // Resize, let glxgears see the ConfigureNotify and draw some frames.
    unsafe { (x.XResizeWindow)(dpy, win, 500, 400) };
    unsafe { (x.XSync)(dpy, xlib::False) };
    let before = gears.frames();
    gears.wait_frames(before, 10);
    let shot = x11::read_rgb(&x, dpy, win, 500, 400);
    let outside = |f: fn([i32; 3]) -> bool| count(&shot, 500, [300, 0, 500, 400], f) + count(&shot, 500, [0, 300, 300, 400], f);
    let beyond = outside(red) + outside(green) + outside(blue);
    eprintln!("500x400: {beyond} gear pixels outside the old 300x300");
    assert!(beyond > 2000, "after the resize the picture fills the window: {beyond} gear pixels outside 300x300");
    let all = [0, 0, 500, 400];
    assert!(count(&shot, 500, all, red) > r, "the gears grew with the window");
}

#[test]
fn glxgears_on_screen_through_the_device_path() {
    check_glxgears(None);
}

#[test]
fn glxgears_on_screen_through_xlib() {
    check_glxgears(Some("xlib"));
}

/// glrt-demo in a 320 × 240 window: brick walls (red) and sky (light blue) on screen.
fn check_demo(present: Option<&str>) {
    let Some(server) = x11::Xvfb::start(24) else { return };
    let tag = format!("demo-{}", present.unwrap_or("auto"));
    let demo = env!("CARGO_BIN_EXE_glrt-demo");
    let mut run = Program::start(&server, demo, &["--frames", "100000", "--size", "320x240"], present, &tag);
    let x = Xlib::open().expect("libX11");
    let dpy = server.open(&x);
    let win = find_window(&x, dpy, "glrt-demo");
    run.wait_frames(0, 5);
    eprintln!("glrt-demo, GLRT_PRESENT={present:?}: presented through {}", run.path());
    let [w, h] = window_size(&x, dpy, win);
    assert_eq!([w, h], [320, 240]);
    let shot = x11::read_rgb(&x, dpy, win, w, h);
    let brick = count(&shot, w, [0, 52, w, h], red);
    let sky = count(&shot, w, [0, 52, w, h], |[r, g, b]| b > 170 && b > r + 15 && g > 120);
    eprintln!("demo: {brick} brick, {sky} sky pixels");
    assert!(brick > (w * h / 20) as usize, "brick walls: {brick} red pixels");
    assert!(sky > 100, "sky: {sky} light blue pixels");
}

#[test]
fn demo_on_screen_through_the_device_path() {
    check_demo(None);
}

#[test]
fn demo_on_screen_through_xlib() {
    check_demo(Some("xlib"));
}
