//! The `glrt` command's conventions: `--help` of the command and of each subcommand (status 0,
//! on standard output), usage errors (status 2, a message naming the bad argument), failures
//! (status 1), and `glrt info` listing the Vulkan devices (lavapipe here) with their features
//! and the mode each would get.

use std::process::{Command, Output};

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
