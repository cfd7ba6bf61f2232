//! Presentation end to end: Mesa's `glxgears` and `glrt-demo` run with glrt's `libGL.so.1`
//! in Xvfb windows, and the windows are read back with `XGetImage` from another connection
//! (what `xwd` sees): the window must show, pixel for pixel, one of the frames the renderer
//! drew (all dumped with `GLRT_DUMP`), the scene must be there (lit pixels, colours), and after
//! the window is resized the picture must have the new size and fill it. Each runs twice: the path the device chooses (Vulkan
//! swapchain on lavapipe) and `GLRT_PRESENT=xlib` (the read-back fallback); the path taken is
//! read from glrt's log and printed. Fails, saying so, when Xvfb or glxgears is missing.

use crate::programs::lib_dir;
use crate::x11;

use std::ffi::CStr;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use x11_dl::xlib::{self, Xlib};

/// A program running through glrt on `server`, killed on drop; its stderr goes to a file.
struct Program {
    child: Child,
    stderr: PathBuf,
    frames: PathBuf,
    /// `GLRT_DUMP` directory: every frame the renderer drew.
    dump: PathBuf,
}

impl Program {
    fn start(server: &x11::Xvfb, program: &str, args: &[&str], present: Option<&str>, tag: &str) -> Program {
        let base = std::env::temp_dir().join(format!("glrt-present-{tag}-{}", std::process::id()));
        let (stderr, frames) = (base.with_extension("log"), base.with_extension("jsonl"));
        let _ = std::fs::remove_file(&frames);
        let dump = base.with_extension("dump");
        let _ = std::fs::remove_dir_all(&dump);
        let mut cmd = Command::new(program);
        cmd.args(args)
            .env("DISPLAY", &server.display)
            .env("LD_LIBRARY_PATH", lib_dir())
            .env("GLRT_LOG", "info")
            .env("GLRT_FRAME_LOG", &frames)
            .env("GLRT_DUMP", &dump)
            .stdout(Stdio::null())
            .stderr(std::fs::File::create(&stderr).expect("log file"));
        match present {
            Some(p) => cmd.env("GLRT_PRESENT", p),
            None => cmd.env_remove("GLRT_PRESENT"),
        };
        Program { child: cmd.spawn().expect("spawn"), stderr, frames, dump }
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
        let _ = std::fs::remove_dir_all(&self.dump);
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

/// Whether a pixel is not the black background.
fn lit(p: [i32; 3]) -> bool {
    p.iter().sum::<i32>() > 60
}

/// The frames the renderer dumped (`GLRT_DUMP`) of size `size`, newest first, as RGB rows top
/// to bottom.
fn dumped_frames(dir: &Path, size: [u32; 2]) -> Vec<(String, Vec<[u8; 3]>)> {
    let mut names: Vec<String> = std::fs::read_dir(dir).map_or_else(|_| Vec::new(), |d| d.flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect());
    names.sort_unstable_by(|a, b| b.cmp(a));
    names
        .into_iter()
        .filter_map(|name| {
            let file = std::fs::File::open(dir.join(&name)).ok()?;
            let mut reader = png::Decoder::new(std::io::BufReader::new(file)).read_info().ok()?;
            let mut buf = vec![0; reader.output_buffer_size()?];
            let info = reader.next_frame(&mut buf).ok()?;
            if [info.width, info.height] != size || info.color_type != png::ColorType::Rgb {
                return None;
            }
            Some((name, buf[..info.buffer_size()].chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect()))
        })
        .collect()
}

/// Reads the window (`size`) and checks that it shows, pixel for pixel, one of the frames the
/// renderer drew (dumped with `GLRT_DUMP`: presentation adds nothing and loses nothing);
/// returns the screenshot.
fn shows_a_rendered_frame(x: &Xlib, dpy: *mut xlib::Display, win: xlib::Window, program: &mut Program, size: [u32; 2]) -> Vec<[u8; 3]> {
    let shot = x11::read_rgb(x, dpy, win, size[0], size[1]);
    // The frame on screen ended before the frames counted now; frames are dumped once their
    // slot completes, in order by one writer: when frame `ended` exists, all before it are
    // written.
    let ended = program.frames();
    let deadline = Instant::now() + Duration::from_secs(120);
    while !program.dump.join(format!("frame-{ended:05}.png")).exists() {
        assert!(Instant::now() < deadline, "frame {ended} was not dumped:\n{}", program.log());
        std::thread::sleep(Duration::from_millis(20));
    }
    let frames = dumped_frames(&program.dump, size);
    let found = frames.iter().find(|(_, f)| *f == shot).map(|(n, _)| n.clone());
    eprintln!("{}x{}: screenshot is {found:?} of {} dumped frames of that size", size[0], size[1], frames.len());
    if found.is_none() {
        for (n, f) in &frames {
            let diff = f.iter().zip(&shot).filter(|(a, b)| a != b).count();
            let first = f.iter().zip(&shot).position(|(a, b)| a != b).unwrap_or(0);
            eprintln!("{n}: {diff} differ, first at ({}, {}): dump {:?} window {:?}", first as u32 % size[0], first as u32 / size[0], f[first], shot[first]);
        }
    }
    assert!(found.is_some(), "the window shows none of the {} rendered {size:?} frames", frames.len());
    shot
}

/// glxgears (300 × 300 window, black background), then resized to 500 × 400: glxgears'
/// reshape widens the view, so gears reach past the old 300 × 300 corner.
fn check_glxgears(present: Option<&str>) {
    assert!(Path::new("/usr/bin/glxgears").exists(), "glxgears is missing: `bash scripts/setup.sh` installs it (mesa-utils)");
    let server = x11::Xvfb::start(24);
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
    assert_eq!([w, h], [300, 300]);
    let shot = shows_a_rendered_frame(&x, dpy, win, &mut gears, [w, h]);
    let gear_pixels = count(&shot, w, [0, 0, w, h], lit);
    assert!(gear_pixels > (w * h / 10) as usize, "gears on screen: {gear_pixels} lit pixels");
    assert_eq!(shot[0], [0, 0, 0], "black background in the corner");

    // Resize, let glxgears see the ConfigureNotify and draw some frames.
    unsafe { (x.XResizeWindow)(dpy, win, 500, 400) };
    unsafe { (x.XSync)(dpy, xlib::False) };
    let before = gears.frames();
    gears.wait_frames(before, 10);
    let shot = shows_a_rendered_frame(&x, dpy, win, &mut gears, [500, 400]);
    let beyond = count(&shot, 500, [300, 0, 500, 400], lit) + count(&shot, 500, [0, 300, 300, 400], lit);
    eprintln!("500x400: {beyond} lit pixels outside the old 300x300");
    assert!(beyond > 2000, "after the resize the picture fills the window: {beyond} lit pixels outside 300x300");
}

#[test]
fn glxgears_on_screen_through_the_device_path() {
    check_glxgears(None);
}

#[test]
fn glxgears_on_screen_through_xlib() {
    check_glxgears(Some("xlib"));
}

/// glrt-demo in a 320 × 240 window: a rendered frame, many colours.
fn check_demo(present: Option<&str>) {
    let server = x11::Xvfb::start(24);
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
    let shot = shows_a_rendered_frame(&x, dpy, win, &mut run, [w, h]);
    let colours: std::collections::HashSet<[u8; 3]> = shot.iter().copied().collect();
    eprintln!("demo: {} colours", colours.len());
    assert!(colours.len() > 20, "the scene is on screen: {} colours", colours.len());
}

#[test]
fn demo_on_screen_through_the_device_path() {
    check_demo(None);
}

#[test]
fn demo_on_screen_through_xlib() {
    check_demo(Some("xlib"));
}
