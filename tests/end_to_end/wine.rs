//! A Windows OpenGL 1.1 program under Wine, through `glrt run`, on an Xvfb server:
//! `tests/programs/wgl_triangle.c` (a WGL window and context, a texture, a display list, an
//! immediate-mode triangle, `glReadPixels`) built with mingw-w64 and run as
//! `glrt run -- wine wgl_triangle.exe` in a fresh Wine prefix. Wine's `opengl32` must reach glrt:
//! the renderer string is glrt's, glrt's frame log has the frames, the pixels read back are the
//! triangle's and the clear colour, and the command set the prefix's `UseEGL` value (which keeps
//! Wine 10.17 and later on GLX) saying so. Skipped, with a message, where Wine (`wine`) or the
//! mingw-w64 compiler (`x86_64-w64-mingw32-gcc`) is not installed: neither is part of
//! `scripts/setup.sh` (Debian: `apt-get install wine wine64 gcc-mingw-w64-x86-64`).

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use crate::demo::read_frame_log;
use crate::programs::run_for;
use crate::x11;

const WINE: &str = "/usr/bin/wine";
const MINGW_GCC: &str = "/usr/bin/x86_64-w64-mingw32-gcc";

/// The `R G B` numbers after `label` in the program's output.
fn pixel(stdout: &str, label: &str) -> [i32; 3] {
    let line = stdout.lines().find_map(|l| l.strip_prefix(label)).unwrap_or_else(|| panic!("no {label:?} line:\n{stdout}"));
    let v: Vec<i32> = line.split_whitespace().map(|n| n.parse().unwrap()).collect();
    [v[0], v[1], v[2]]
}

#[test]
fn a_windows_opengl_program_runs_on_glrt_under_wine() {
    let missing: Vec<&str> = [WINE, MINGW_GCC].into_iter().filter(|p| !Path::new(p).exists()).collect();
    if !missing.is_empty() {
        eprintln!("skipped: {missing:?} not installed (apt-get install wine wine64 gcc-mingw-w64-x86-64)");
        return;
    }
    let base = Path::new(env!("CARGO_TARGET_TMPDIR")).join("wine");
    let _ = std::fs::remove_dir_all(&base);
    std::fs::create_dir_all(&base).unwrap();
    let (exe, prefix, frame_log) = (base.join("wgl_triangle.exe"), base.join("prefix"), base.join("frames.jsonl"));
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/programs/wgl_triangle.c");
    let built = Command::new(MINGW_GCC).arg("-O2").arg("-o").arg(&exe).arg(&source).args(["-lopengl32", "-lgdi32"]).output().unwrap();
    assert!(built.status.success(), "mingw-w64 build:\n{}", String::from_utf8_lossy(&built.stderr));

    let server = x11::Xvfb::start(24);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_glrt"));
    cmd.args(["run", "--mode", "raster", "--", WINE])
        .arg(&exe)
        .arg("3")
        .env("DISPLAY", &server.display)
        .env("WINEPREFIX", &prefix)
        .env("WINEDEBUG", "-all")
        // No Mono or Gecko installer dialogs in the new prefix.
        .env("WINEDLLOVERRIDES", "mscoree,mshtml=")
        .env("XDG_CACHE_HOME", base.join("cache"))
        .env("GLRT_FRAME_LOG", &frame_log)
        .env_remove("LD_LIBRARY_PATH")
        .env_remove("__GLX_VENDOR_LIBRARY_NAME")
        .env_remove("GLRT_DEVICE");
    let (out, stopped) = run_for(cmd, Duration::from_secs(180));
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    // The prefix's registry is written when its wineserver ends.
    let _ = Command::new("/usr/bin/wineserver").arg("-w").env("WINEPREFIX", &prefix).status();
    assert!(!stopped && out.status.success(), "{:?}\n{stdout}\n{stderr}", out.status);

    assert!(stdout.contains("renderer glrt (Vulkan raster)"), "Wine's opengl32 must load glrt:\n{stdout}\n{stderr}");
    let said = stderr.lines().filter(|l| l.starts_with(r"glrt: Wine: setting HKCU\Software\Wine\X11 Driver UseEGL=N in ")).count();
    assert_eq!(said, 1, "{stderr}");
    let user_reg = std::fs::read_to_string(prefix.join("user.reg")).unwrap();
    let key = user_reg.split("\n[").find(|k| k.starts_with(r"Software\\Wine\\X11 Driver]")).unwrap_or_default();
    assert!(key.contains("\"UseEGL\"=\"N\""), "the prefix's X11 driver key:\n{key}");
    // A second run finds the value and says nothing about it.
    let mut again = Command::new(env!("CARGO_BIN_EXE_glrt"));
    again.args(["run", "--mode", "raster", "--", WINE]).arg(&exe).arg("1");
    for (name, value) in [("DISPLAY", server.display.as_str()), ("WINEDEBUG", "-all"), ("WINEDLLOVERRIDES", "mscoree,mshtml=")] {
        again.env(name, value);
    }
    again.env("WINEPREFIX", &prefix).env("XDG_CACHE_HOME", base.join("cache")).env_remove("LD_LIBRARY_PATH");
    let (second, stopped) = run_for(again, Duration::from_secs(120));
    let second_err = String::from_utf8_lossy(&second.stderr);
    assert!(!stopped && second.status.success(), "{second_err}");
    assert!(!second_err.contains("UseEGL"), "{second_err}");
    let _ = Command::new("/usr/bin/wineserver").arg("-k").env("WINEPREFIX", &prefix).status();

    // glrt drew the program's 3 frames: one draw of 3 vertices each.
    let frames = read_frame_log(&frame_log);
    assert_eq!(frames.len(), 3, "{frames:?}");
    assert!(frames.iter().all(|f| f.draws == 1 && f.vertices == 3 && f.clears == 1), "{frames:?}");
    // The orange triangle (1, 0.5, 0) over the blue clear colour, read back with glReadPixels.
    let [r, g, b] = pixel(&stdout, "center ");
    assert!(r == 255 && (127..=128).contains(&g) && b == 0, "centre {r} {g} {b}");
    assert_eq!(pixel(&stdout, "corner "), [0, 0, 255], "corner");
}
