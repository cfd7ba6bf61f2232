//! `glrt run -- PROGRAM ARGS...` on an Xvfb server: Mesa's `glxgears` (linked with glvnd's
//! `libGL.so.1`) and `glrt-demo` (which `dlopen`s `libGL.so.1`) are run through the command
//! with no `LD_LIBRARY_PATH` of their own, and must be drawn by glrt: its frame log has their
//! frames (draw and vertex counts of their scenes), its dumped frames show their pixels, and the
//! command says once which device and mode it chose; `--hud` turns the HUD on. Fails, saying so, when Xvfb or glxgears is
//! missing.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::demo::{DEMO_DRAWS, GEARS_DRAWS, read_frame_log};
use crate::images::Image;
use crate::programs::run_for;
use crate::x11;

/// Scratch files of one run: stderr, the frame log, the dump directory, the cache directory
/// `glrt run` keeps its links in.
struct Files {
    stderr: PathBuf,
    frame_log: PathBuf,
    dump: PathBuf,
    cache: PathBuf,
}

impl Files {
    fn new(tag: &str) -> Files {
        let base = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("glrt-run-{tag}"));
        let _ = std::fs::remove_dir_all(&base);
        std::fs::create_dir_all(&base).unwrap();
        Files { stderr: base.join("stderr.txt"), frame_log: base.join("frames.jsonl"), dump: base.join("dump"), cache: base.join("cache") }
    }

    /// `glrt run ARGS` on `server`, with a clean environment for the libraries: no
    /// `LD_LIBRARY_PATH`, no glvnd vendor, no mode of the test's own.
    fn command(&self, server: &x11::Xvfb, args: &[&str]) -> Command {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_glrt"));
        cmd.arg("run")
            .args(args)
            .env("DISPLAY", &server.display)
            .env("XDG_CACHE_HOME", &self.cache)
            .env("GLRT_FRAME_LOG", &self.frame_log)
            .env("GLRT_DUMP", &self.dump)
            .env_remove("LD_LIBRARY_PATH")
            .env_remove("__GLX_VENDOR_LIBRARY_NAME")
            .env_remove("GLRT_MODE")
            .env_remove("GLRT_DEVICE");
        cmd
    }

    /// The dumped frame `n`.
    fn frame(&self, n: u64) -> Image {
        Image::load_png(&self.dump.join(format!("frame-{n:05}.png")))
    }
}

/// Pixels of `image` whose channel `c` stands out (above 100 and twice each other channel).
fn pixels_of_channel(image: &Image, c: usize) -> usize {
    image.rgb.chunks(3).filter(|p| p[c] > 100 && (0..3).all(|o| o == c || u16::from(p[c]) > 2 * u16::from(p[o]))).count()
}

#[test]
fn glxgears_runs_on_glrt_through_glrt_run() {
    assert!(Path::new("/usr/bin/glxgears").exists(), "glxgears is missing: `bash scripts/setup.sh` installs it (mesa-utils)");
    let server = x11::Xvfb::start(24);
    let files = Files::new("glxgears");
    let mut cmd = files.command(&server, &["--mode", "raster", "--", "/usr/bin/glxgears"]);
    let stderr = std::fs::File::create(&files.stderr).unwrap();
    let mut child = cmd.stdout(Stdio::null()).stderr(stderr).spawn().expect("run glrt");
    let deadline = Instant::now() + Duration::from_secs(120);
    // The writer thread writes the dumped frames in order: frame 3 is whole once 4 exists.
    while !files.dump.join("frame-00004.png").exists() {
        let exited = child.try_wait().unwrap();
        let log = std::fs::read_to_string(&files.stderr).unwrap_or_default();
        assert!(exited.is_none(), "glxgears exited ({exited:?}) before 5 frames were dumped:\n{log}");
        assert!(Instant::now() < deadline, "5 frames not dumped in time:\n{log}");
        std::thread::sleep(Duration::from_millis(100));
    }
    // `glrt run` became glxgears: stopping it stops the program.
    child.kill().unwrap();
    child.wait().unwrap();
    let log = std::fs::read_to_string(&files.stderr).unwrap();
    let said: Vec<&str> = log.lines().filter(|l| l.starts_with("glrt: /usr/bin/glxgears ")).collect();
    assert_eq!(said.len(), 1, "said once:\n{log}");
    assert!(said[0].contains(" on llvmpipe") && said[0].ends_with(" (CPU), mode raster"), "device and mode:\n{log}");
    let frames = read_frame_log(&files.frame_log);
    assert!(frames.iter().all(|f| (GEARS_DRAWS.0..=GEARS_DRAWS.1).contains(&f.draws) && f.vertices == 1064), "{frames:?}");
    // Frame 3 as glrt drew it: glxgears' red, green and blue gears on black.
    let image = files.frame(3);
    assert_eq!((image.width, image.height), (300, 300));
    let [red, green, blue] = [0, 1, 2].map(|c| pixels_of_channel(&image, c));
    assert!(red > 5000 && green > 1500 && blue > 1500, "gear pixels: red {red}, green {green}, blue {blue}");
    assert_eq!(image.pixel(2, 2), [0, 0, 0], "black background");
}

#[test]
fn the_demo_runs_on_glrt_through_glrt_run() {
    let server = x11::Xvfb::start(24);
    let files = Files::new("demo");
    let demo = env!("CARGO_BIN_EXE_glrt-demo");
    let cmd = files.command(&server, &["--hud", "--", demo, "--frames", "4", "--size", "320x240"]);
    let (out, stopped) = run_for(cmd, Duration::from_secs(300));
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(!stopped && out.status.success(), "{:?}\n{stdout}\n{stderr}", out.status);
    assert!(stdout.contains("frames: 4 "), "the demo's summary:\n{stdout}");
    let said: Vec<&str> = stderr.lines().filter(|l| l.starts_with(&format!("glrt: {demo} on llvmpipe"))).collect();
    assert_eq!(said.len(), 1, "said once:\n{stderr}");
    assert!(said[0].contains(" (CPU), mode raster (a CPU device;"), "unset GLRT_MODE on lavapipe rasterizes:\n{stderr}");
    let frames = read_frame_log(&files.frame_log);
    assert_eq!(frames.len(), 4, "{frames:?}");
    assert!(frames.iter().all(|f| (DEMO_DRAWS.0..=DEMO_DRAWS.1).contains(&f.draws)), "{frames:?}");
    // The room, not a cleared frame: many colours over the picture.
    let image = files.frame(3);
    assert_eq!((image.width, image.height), (320, 240));
    let colours: std::collections::HashSet<[u8; 3]> = (0..image.height).flat_map(|y| (0..image.width).map(move |x| (x, y))).map(|(x, y)| image.pixel(x, y)).collect();
    assert!(colours.len() > 500, "{} colours in the demo's frame", colours.len());
    // --hud: the panel's background in the top-left corner (tests/hud.rs reads its text).
    let [r, g, b, _] = glrt::render::hud::BACKGROUND;
    assert_eq!(image.pixel(0, 0), [r, g, b], "the HUD panel");
}

#[test]
fn a_program_that_cannot_be_run_fails_with_a_message() {
    let server = x11::Xvfb::start(24);
    let files = Files::new("missing");
    let out = files.command(&server, &["--", "/nonexistent/game"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("glrt: cannot run /nonexistent/game: No such file or directory"), "{stderr}");
    let out = files.command(&server, &["--config", "/nonexistent/glrt.toml", "--", "/usr/bin/true"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("--config /nonexistent/glrt.toml: No such file"), "{stderr}");
}
