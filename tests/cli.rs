//! The `glrt` command's conventions: `--help` of the command and of each subcommand (status 0,
//! on standard output), usage errors (status 2, a message naming the bad argument), failures
//! (status 1), and `glrt info` listing the Vulkan devices (lavapipe here) with their features
//! and the mode each would get; `glrt replay --size` and `--scale`.

#[path = "images/mod.rs"]
mod images;

use std::process::{Command, Output};

use images::Image;

fn glrt(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_glrt"));
    cmd.args(args).env_remove("GLRT_MODE").env_remove("GLRT_DEVICE");
    cmd.envs(env.iter().copied()).output().expect("run glrt")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn help_of_the_command_and_each_subcommand() {
    let out = glrt(&["--help"], &[]);
    let help = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(help.contains("Usage: glrt <COMMAND>"), "{help}");
    let listed: Vec<&str> = help
        .lines()
        .skip_while(|l| *l != "Commands:")
        .skip(1)
        .take_while(|l| !l.is_empty())
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    assert_eq!(listed, ["info", "replay", "dump", "run", "radiosity", "help"], "{help}");
    for (command, usage, option) in [
        ("info", "Usage: glrt info [FILE]", "Lists the Vulkan devices"),
        ("replay", "Usage: glrt replay [OPTIONS] <FILE>", "--frames <A..B>"),
        ("dump", "Usage: glrt dump <FILE>", "GLRT_TRACE format"),
        ("run", "Usage: glrt run [OPTIONS] <PROGRAM ARGS>...", "glrt run -- %command%"),
        ("radiosity", "Usage: glrt radiosity [OPTIONS] [FILE]", "--synthetic <N>"),
    ] {
        let out = glrt(&[command, "--help"], &[]);
        let help = text(&out.stdout);
        assert_eq!(out.status.code(), Some(0), "{command} --help");
        assert!(help.contains(usage) && help.contains(option), "{command} --help:\n{help}");
    }
    let out = glrt(&["--version"], &[]);
    assert_eq!(text(&out.stdout).trim(), format!("glrt {}", env!("CARGO_PKG_VERSION")));
}

#[test]
fn usage_errors_name_the_argument_and_exit_2() {
    let gears = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/glxgears.glrtcap");
    let cases: [(&[&str], &str); 8] = [
        (&[], "Usage: glrt <COMMAND>"),
        (&["frob"], "unrecognized subcommand 'frob'"),
        (&["replay", gears, "--frames", "5..2"], "invalid value '5..2' for '--frames <A..B>'"),
        (&["replay", gears, "--size", "640"], "invalid value '640' for '--size <WxH>': expected WxH"),
        (&["replay", gears, "--fast"], "unexpected argument '--fast'"),
        (&["dump"], "the following required arguments were not provided:\n  <FILE>"),
        (&["run", "--mode", "fast", "--", "true"], "invalid value 'fast' for '--mode <MODE>'"),
        (&["run", "--hud"], "the following required arguments were not provided:\n  <PROGRAM ARGS>..."),
    ];
    for (args, message) in cases {
        let out = glrt(args, &[]);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "glrt {args:?}: {err}");
        assert!(err.contains(message), "glrt {args:?}: expected {message:?} in\n{err}");
        assert!(out.stdout.is_empty(), "glrt {args:?}: usage errors go to stderr");
    }
}

#[test]
fn a_file_that_cannot_be_read_fails_with_status_1() {
    let out = glrt(&["info", "/nonexistent/x.glrtcap"], &[]);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.starts_with("glrt: ") && err.contains("/nonexistent/x.glrtcap"), "{err}");
}

/// The lines of `glrt info` about the device named like `name`: from its `N: name` line to the
/// next device's.
fn device_lines<'a>(info: &'a str, name: &str) -> Vec<&'a str> {
    let mut lines = info.lines().skip_while(|l| !(l.contains(": ") && l.contains(name) && !l.starts_with("    ")));
    let first = lines.next().into_iter();
    first.chain(lines.take_while(|l| l.starts_with("    "))).collect()
}

#[test]
fn info_lists_lavapipe_with_its_features_and_mode() {
    let out = glrt(&["info"], &[]);
    let info = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(info.starts_with(&format!("glrt {}\nexports: ", env!("CARGO_PKG_VERSION"))), "{info}");
    let lavapipe = device_lines(&info, "llvmpipe");
    assert_eq!(lavapipe.len(), 4, "name, type and memory, features, mode:\n{info}");
    let memory: f64 = lavapipe[1].split(", ").nth(2).and_then(|m| m.split(' ').next()).and_then(|m| m.parse().ok()).expect(lavapipe[1]);
    assert!(lavapipe[1].trim().starts_with("CPU, Vulkan 1.3.") && memory > 0.0, "{}", lavapipe[1]);
    // Mesa 22.3's lavapipe: no ray-tracing extensions, BC textures (DESIGN.md).
    assert_eq!(lavapipe[2].trim(), "ray-tracing pipeline: no, acceleration structures: no, BC textures: yes");
    assert!(lavapipe[3].trim().starts_with("mode: raster (a CPU device;"), "unset GLRT_MODE rasterizes on a CPU: {}", lavapipe[3]);
    let only_device = info.lines().filter(|l| l.starts_with("> ")).count() == 1;
    assert!(only_device, "one device is marked as glrt's:\n{info}");

    let traced = text(&glrt(&["info"], &[("GLRT_MODE", "pathtrace")]).stdout);
    assert_eq!(device_lines(&traced, "llvmpipe")[3].trim(), "mode: pathtrace (compute tracer: the device has no VK_KHR_ray_tracing_pipeline)");
    let none = text(&glrt(&["info"], &[("GLRT_DEVICE", "no-such-device")]).stdout);
    assert!(!none.lines().any(|l| l.starts_with("> ")), "GLRT_DEVICE matching nothing marks none:\n{none}");
}

/// `glrt replay --out` on a terminal draws a bar of the frames written with the time left; with
/// stderr not a terminal (here, a pipe) it writes nothing there. `script` (util-linux) gives
/// the command a pseudo-terminal.
#[test]
fn replay_out_shows_progress_on_a_terminal_only() {
    let capture = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/demo.glrtcap");
    let dir = std::env::temp_dir().join(format!("glrt-cli-progress-{}", std::process::id()));
    let out = glrt(&["replay", capture, "--out", dir.to_str().unwrap(), "--frames", "1.."], &[("GLRT_MODE", "raster")]);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(!err.contains("frames,") && !err.contains('\r'), "no bar when stderr is a pipe:\n{err}");

    let line = format!("{} replay {capture} --out {} --frames 1..", env!("CARGO_BIN_EXE_glrt"), dir.display());
    let out = Command::new("script").args(["-qec", &line, "/dev/null"]).env("GLRT_MODE", "raster").output().expect("run script (util-linux)");
    let _ = std::fs::remove_dir_all(&dir);
    let terminal = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{terminal}");
    // The last state of the bar: frames 1 to 3 of the 4-frame capture, none left.
    let last = terminal.split(['\r', '\n']).filter(|l| l.contains("frames,")).last().unwrap_or_default();
    assert!(last.contains("replay [") && last.contains("] 3/3 frames, ") && last.contains(" 0s left"), "{terminal:?}");
    assert!(terminal.contains("wrote frames 1..4 to "), "{terminal}");
}

/// `glrt replay --size` says on stderr what it changes when the capture was made at another
/// size (the glxgears fixture: a 300x300 window), and nothing when the size is the same.
#[test]
fn replay_size_says_what_it_changes() {
    let gears = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/glxgears.glrtcap");
    let out = glrt(&["replay", gears, "--frames", "0..1", "--size", "100x80"], &[("GLRT_MODE", "raster")]);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(err.contains("glrt: --size 100x80: the capture was made at 300x300; its glViewport calls are replayed as recorded"), "{err}");
    let out = glrt(&["replay", gears, "--frames", "0..1", "--size", "300x300"], &[("GLRT_MODE", "raster")]);
    assert!(!text(&out.stderr).contains("--size"), "{}", text(&out.stderr));
}

/// `image` shrunk `n` times in each direction, each pixel the mean of the `n × n` it covers.
fn box_downscaled(image: &Image, n: usize) -> Image {
    let (width, height) = (image.width / n, image.height / n);
    let mut rgb = Vec::with_capacity(width * height * 3);
    for y in 0..height {
        for x in 0..width {
            for c in 0..3 {
                let sum: usize = (0..n * n).map(|k| usize::from(image.pixel(x * n + k % n, y * n + k / n)[c])).sum();
                rgb.push(((sum + n * n / 2) / (n * n)) as u8);
            }
        }
    }
    Image { width, height, rgb }
}

/// `glrt replay --scale 2` renders the glxgears fixture (a 300x300 window, one glViewport) and
/// the q3 fixture (viewports and scissors for its 3D HUD icons) at
/// twice the size; each frame, shrunk back by averaging 2x2 pixels, must match the frame
/// replayed at 1x: mean absolute difference per channel below 1.5 (glxgears, measured 0.40) and
/// 4 (q3, measured 1.73) of 255, and fewer than 1 % of the channels more than 64 apart
/// (measured 0.15 % and 0.07 %: polygon edges). A capture drawing in window pixels (the demo's
/// glBitmap text) is refused with status 1, naming the call and frame; `--size` and `--scale`
/// together are a usage error.
#[test]
fn replay_scale_renders_a_capture_larger() {
    let dir = std::env::temp_dir().join(format!("glrt-cli-scale-{}", std::process::id()));
    for (fixture, size, mean_limit) in [("glxgears", (300, 300), 1.5), ("q3", (320, 240), 4.0)] {
        let capture = format!("{}/tests/fixtures/{fixture}.glrtcap", env!("CARGO_MANIFEST_DIR"));
        let frame = |scale: &str| {
            let out_dir = dir.join(format!("{fixture}-{scale}"));
            let mut args = vec!["replay", &capture, "--frames", "3..4", "--out", out_dir.to_str().unwrap()];
            if scale != "1" {
                args.extend(["--scale", scale]);
            }
            let out = glrt(&args, &[("GLRT_MODE", "raster")]);
            assert_eq!(out.status.code(), Some(0), "{fixture} --scale {scale}: {}", text(&out.stderr));
            Image::load_png(&out_dir.join("frame-00003.png"))
        };
        let (once, twice) = (frame("1"), frame("2"));
        assert_eq!((once.width, once.height), size, "{fixture}");
        assert_eq!((twice.width, twice.height), (size.0 * 2, size.1 * 2), "{fixture}");
        let shrunk = box_downscaled(&twice, 2);
        let differences: Vec<u8> = once.rgb.iter().zip(&shrunk.rgb).map(|(a, b)| a.abs_diff(*b)).collect();
        let mean = differences.iter().map(|&d| f64::from(d)).sum::<f64>() / differences.len() as f64;
        let far = differences.iter().filter(|&&d| d > 64).count() as f64 / differences.len() as f64;
        assert!(mean < mean_limit && far < 0.01, "{fixture}: mean |difference| {mean:.3}, {:.3} % of channels off by more than 64", far * 100.0);
    }
    let _ = std::fs::remove_dir_all(&dir);

    let demo = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/demo.glrtcap");
    let out = glrt(&["replay", demo, "--scale", "2"], &[("GLRT_MODE", "raster")]);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("--scale 2: the capture cannot be scaled exactly: in frame 0 it calls glBitmap, which draws a bitmap in window pixels"), "{err}");
    let gears = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/glxgears.glrtcap");
    let out = glrt(&["replay", gears, "--scale", "2", "--size", "600x600"], &[]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("the argument '--scale <N>' cannot be used with '--size <WxH>'"), "{}", text(&out.stderr));
    let out = glrt(&["replay", gears, "--scale", "17"], &[]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("invalid value '17' for '--scale <N>'"), "{}", text(&out.stderr));
}
