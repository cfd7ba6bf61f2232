//! Running programs in integration tests: glrt's `libGL.so.1` next to the built binaries, a
//! private Xvfb server, and a child process with a time limit.

#![allow(dead_code)] // each test binary uses part of this module

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// A fresh path for file `name` of test binary `test` under Cargo's temporary directory for
/// integration tests (the directory is created, an old file removed).
pub fn scratch(test: &str, name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(test);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    path
}

/// `target/<profile>/`, holding glrt-demo and libglrt.so; makes the `libGL.so.1` symlink.
pub fn lib_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_BIN_EXE_glrt-demo")).parent().expect("target dir").to_path_buf();
    assert!(dir.join("libglrt.so").exists(), "{}/libglrt.so missing: run `cargo build`", dir.display());
    let link = dir.join("libGL.so.1");
    if std::fs::symlink_metadata(&link).is_err() {
        // Another test may create it at the same time; either link is fine.
        let _ = std::os::unix::fs::symlink("libglrt.so", &link);
    }
    dir
}

/// Runs `cmd` for at most `limit`; returns its output and whether it was stopped.
pub fn run_for(mut cmd: Command, limit: Duration) -> (Output, bool) {
    let mut child = cmd.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("spawn");
    let start = Instant::now();
    let mut stopped = false;
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > limit {
            let _ = child.kill();
            stopped = true;
            break;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    (child.wait_with_output().expect("output"), stopped)
}

/// A private Xvfb server, stopped on drop.
pub struct Xvfb {
    child: Child,
    /// `:N`, for `DISPLAY`.
    pub display: String,
}

/// Serialises display-number picking between the tests of this process.
static XVFB_START: Mutex<()> = Mutex::new(());

impl Xvfb {
    /// Starts Xvfb with a 1024×768×24 screen.
    pub fn start() -> Self {
        Xvfb::with_screen("1024x768x24")
    }

    /// Starts Xvfb with screen 0 of `geometry` (`WxHxDEPTH`) on a free display number.
    pub fn with_screen(geometry: &str) -> Self {
        let _guard = XVFB_START.lock().unwrap_or_else(|e| e.into_inner());
        for n in 90 + std::process::id() % 50..400 {
            if Path::new(&format!("/tmp/.X{n}-lock")).exists() {
                continue;
            }
            let spawned = Command::new("Xvfb")
                .args([format!(":{n}").as_str(), "-screen", "0", geometry, "-nolisten", "tcp"])
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn();
            let mut child = match spawned {
                Ok(c) => c,
                Err(e) => panic!("cannot start Xvfb ({e}): install it with `bash scripts/setup.sh`"),
            };
            let socket = PathBuf::from(format!("/tmp/.X11-unix/X{n}"));
            let start = Instant::now();
            while start.elapsed() < Duration::from_secs(10) {
                if child.try_wait().ok().flatten().is_some() {
                    break; // display taken: try the next one
                }
                if socket.exists() {
                    return Xvfb { child, display: format!(":{n}") };
                }
                std::thread::sleep(Duration::from_millis(50));
            }
            let _ = child.kill();
            let _ = child.wait();
        }
        panic!("no free X display for Xvfb");
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
