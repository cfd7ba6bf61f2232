//! Running programs in integration tests: glrt's `libGL.so.1` next to the built binaries, a
//! scratch path, and a child process with a time limit (the X server: `tests/x11/mod.rs`).

#![allow(dead_code)] // each test binary uses part of this module

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
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
