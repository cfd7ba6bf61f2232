//! Pass-through mode (`GLRT_PASSTHROUGH`, `gl_entry::passthrough`): glxgears runs through glrt's
//! `libGL.so.1` under Xvfb with every call forwarded to the system's (Mesa's) libGL and logged
//! (`GLRT_TRACE`); the log holds its GLX and GL calls, and the screen shows the gears Mesa drew
//! (glrt itself has no window renderer yet, so coloured pixels can only come from Mesa).
//! Needs Xvfb, `xwd` and `glxgears` (`bash scripts/setup.sh` installs them); fails, saying
//! so, without them.

use crate::x11;

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::programs::lib_dir;

/// The system libGL the calls are forwarded to (Debian's glvnd `libGL.so.1`, Mesa behind it).
const SYSTEM_LIBGL: &str = "/usr/lib/x86_64-linux-gnu/libGL.so.1";

/// Fails, naming it, when a program the glxgears test needs is missing (Xvfb: when started).
fn assert_tools_present() {
    for tool in ["/usr/bin/xwd", "/usr/bin/glxgears", SYSTEM_LIBGL] {
        assert!(Path::new(tool).exists(), "{tool} is missing: `bash scripts/setup.sh` installs it");
    }
}

fn temp_path(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("glrt-passthrough-{}-{name}", std::process::id()))
}

/// An `xwd` screenshot (TrueColor, 24 or 32 bits per pixel): width, height and RGB per pixel.
fn read_xwd(data: &[u8]) -> (usize, usize, Vec<[u8; 3]>) {
    let field = |i: usize| u32::from_be_bytes(data[i * 4..i * 4 + 4].try_into().expect("4 bytes")) as usize;
    let (header, width, height) = (field(0), field(4), field(5));
    let (little, bpp, stride, ncolors) = (field(7) == 0, field(11), field(12), field(19));
    let masks = [field(14), field(15), field(16)];
    assert!(bpp == 24 || bpp == 32, "{bpp} bits per pixel");
    let step = bpp / 8;
    let pixels = &data[header + 12 * ncolors..];
    let mut rgb = Vec::with_capacity(width * height);
    for y in 0..height {
        for x in 0..width {
            let bytes = &pixels[y * stride + x * step..][..step];
            let fold = |v: usize, &b: &u8| v << 8 | usize::from(b);
            let v = if little { bytes.iter().rev().fold(0, fold) } else { bytes.iter().fold(0, fold) };
            rgb.push(masks.map(|m| ((v & m) >> m.trailing_zeros()) as u8));
        }
    }
    (width, height, rgb)
}

/// Runs glxgears through glrt in pass-through mode under Xvfb until it has logged
/// `frames` frames, screenshots the screen with `xwd -root`, stops it; returns the log and
/// the screenshot and glxgears' standard output.
fn glxgears_passthrough(frames: usize) -> (String, Vec<u8>, String) {
    let (log, shot) = (temp_path("gears.log"), temp_path("gears.xwd"));
    let _ = std::fs::remove_file(&log);
    // The log is flushed at every frame boundary, so the script can wait for frame `frames`.
    let script = format!(
        "glxgears -info & pid=$!
         for i in $(seq 600); do grep -q '^{frames} == end of frame' \"$GLRT_TRACE\" 2>/dev/null && break; sleep 0.1; done
         xwd -root -silent > '{}'; kill $pid; wait $pid; true",
        shot.display()
    );
    let server = x11::Xvfb::start(24);
    let out = Command::new("sh")
        .args(["-c", &script])
        .env("DISPLAY", &server.display)
        .env("LD_LIBRARY_PATH", lib_dir())
        .env("GLRT_PASSTHROUGH", SYSTEM_LIBGL)
        .env("GLRT_TRACE", &log)
        .env_remove("GLRT_TRACE_FILTER")
        .output()
        .expect("sh runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "glxgears script: {:?}\n{stderr}", out.status);
    assert!(!stderr.contains("GLRT_PASSTHROUGH:"), "the library was not forwarded to: {stderr}");
    let text = std::fs::read_to_string(&log).expect("the call log");
    let xwd = std::fs::read(&shot).expect("the screenshot");
    let _ = (std::fs::remove_file(&log), std::fs::remove_file(&shot));
    (text, xwd, String::from_utf8_lossy(&out.stdout).into_owned())
}

#[test]
fn glxgears_on_mesa_through_glrt_is_logged_and_drawn() {
    assert_tools_present();
    let (log, xwd, stdout) = glxgears_passthrough(20);
    let lines: Vec<&str> = log.lines().collect();

    // Window-system calls with their arguments and results, then frame boundaries in order.
    let make_current = lines.iter().find(|l| l.starts_with("0 glXMakeCurrent(")).expect("a glXMakeCurrent line");
    assert!(make_current.contains("drawable=0x") && make_current.ends_with(") = True"), "{make_current}");
    assert!(lines.iter().any(|l| l.starts_with("0 glXCreateContext(dpy=0x") && !l.ends_with("= NULL")));
    for frame in 0..20 {
        let swap = format!("{frame} glXSwapBuffers(dpy=0x");
        assert!(lines.iter().any(|l| l.starts_with(&swap)), "no {swap}");
        let boundary = format!("{frame} == end of frame (glXSwapBuffers)");
        assert!(lines.contains(&boundary.as_str()), "no {boundary}");
    }
    // The gears are compiled into display lists (glBegin/glVertex3f) and drawn with glCallList.
    assert!(lines.contains(&"0 glBegin(mode=GL_QUAD_STRIP)"));
    assert!(lines.iter().any(|l| l.starts_with("0 glVertex3f(x=")));
    for list in 1..=3 {
        let call = format!("5 glCallList(list={list})");
        assert!(lines.contains(&call.as_str()), "no {call}");
    }
    // Mesa answers the queries (`-info` prints them), not glrt.
    let version = stdout.lines().find(|l| l.starts_with("GL_VERSION")).unwrap_or_default();
    assert!(version.contains("Mesa") && !stdout.contains("glrt"), "{stdout}");
    let logged = lines.iter().find(|l| l.starts_with("0 glGetString(name=GL_VERSION) = \"")).expect("glGetString(GL_VERSION) logged with its text");
    assert!(logged.contains("Mesa"), "{logged}");
    // Errors are not read behind the program's back, and no call lacked a context.
    assert!(lines.iter().all(|l| !l.contains(" -> ") && !l.contains("no current context")));

    // glxgears' window (300x300 at the origin): the red, green and blue gears, lit.
    let (width, height, rgb) = read_xwd(&xwd);
    assert!(width >= 300 && height >= 300, "{width}x{height}");
    let count = |f: &dyn Fn([i32; 3]) -> bool| {
        (0..300).flat_map(|y| (0..300).map(move |x| y * width + x)).filter(|&i| f(rgb[i].map(i32::from))).count()
    };
    let red = count(&|[r, g, b]| r > 80 && r > 2 * g && r > 2 * b);
    let green = count(&|[r, g, b]| g > 80 && g > 2 * r && g > b + 30);
    let blue = count(&|[r, g, b]| b > 80 && b > r + 40 && b > g + 40);
    assert!(red > 2000 && green > 1000 && blue > 1000, "gear pixels: red {red}, green {green}, blue {blue}");
    // Outside the window the root stays black.
    let outside = (0..height).flat_map(|y| (300..width).map(move |x| y * width + x)).filter(|&i| rgb[i] != [0; 3]).count();
    assert_eq!(outside, 0, "pixels drawn outside glxgears' window");
}

/// Runs `glrt-demo --headless --frames 2` through glrt with `GLRT_PASSTHROUGH=target`; returns
/// its standard error after checking that the demo ran.
fn demo_passthrough_to(target: &Path) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_glrt-demo"))
        .args(["--headless", "--frames", "2"])
        .env("LD_LIBRARY_PATH", lib_dir())
        .env("GLRT_PASSTHROUGH", target)
        .env_remove("GLRT_TRACE")
        .output()
        .expect("glrt-demo runs");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{stderr}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("frames: 2"), "glrt ran the demo itself");
    assert_eq!(stderr.matches("GLRT_PASSTHROUGH: ").count(), 1, "reported once: {stderr}");
    stderr
}

/// `GLRT_PASSTHROUGH` naming a library the process has loaded already (here glrt's own file,
/// as when glrt is a glvnd vendor behind the program's libGL) or another copy of glrt, either of
/// which would call glrt forever, is refused once on standard error, and glrt runs the program.
#[test]
fn passthrough_back_to_glrt_is_refused() {
    let own = lib_dir().join("libglrt.so");
    let stderr = demo_passthrough_to(&own);
    assert!(stderr.contains("already loaded in this process (the program's own libGL); glrt runs the calls itself"), "{stderr}");

    let copy = temp_path("libglrt-copy.so");
    std::fs::copy(&own, &copy).expect("copy of libglrt.so");
    let stderr = demo_passthrough_to(&copy);
    let _ = std::fs::remove_file(&copy);
    assert!(stderr.contains("this is glrt itself; glrt runs the calls itself"), "{stderr}");
}
