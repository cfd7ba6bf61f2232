//! Several renderers in one process at once (issue 18, item 2): GL contexts on several threads,
//! each current on its own thread with its own renderer (its own Vulkan device), all drawing
//! and reading back at the same time through the exported functions, as a program with a
//! context per thread does: textures uploaded and replaced, a framebuffer object rendered to
//! and sampled, an OpenGL 2.0 program compiled and drawn with, every result read back and
//! checked, swaps; then the contexts are destroyed and made again, round after round, while
//! the other threads draw. The raster renderer on the machine's Vulkan device (the first
//! discrete GPU; lavapipe here): the renderer that hung on NVIDIA with several test threads.
//!
//! A hang fails the test instead of stopping the run: a watchdog prints where every thread
//! is when the run takes longer than its limit (and every thread's stack, with gdb when it
//! is installed and may attach), and ends the process.
//!
//! `GLRT_STRESS_THREADS` (default 4), `GLRT_STRESS_ROUNDS` (contexts made and destroyed per
//! thread, default 3), `GLRT_STRESS_FRAMES` (frames per context, default 20),
//! `GLRT_STRESS_LIMIT` (seconds per round, default 120: the run may take rounds times that).
//! On the GPU machine, 20 runs:
//!
//! ```sh
//! cargo test --release --test renderers_in_threads --no-run && \
//! for i in $(seq 20); do cargo test --release --test renderers_in_threads -q || { echo "run $i failed"; break; }; done
//! ```

#[path = "common/mod.rs"]
mod common;

use std::io::Write;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Barrier};
use std::time::{Duration, Instant};

use common::*;

/// A setting from the environment, or `default`.
fn setting(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// What a thread is doing, for the watchdog's report: round, frame and step packed.
struct Progress(AtomicU64);

/// The steps of a frame, as the report names them.
const STEPS: [&str; 8] = ["making the context", "uploading textures", "rendering to the framebuffer object", "drawing with the program", "reading back", "swapping", "destroying the context", "done"];

impl Progress {
    fn set(&self, round: u64, frame: u64, step: usize) {
        self.0.store(round << 40 | frame << 8 | step as u64, Ordering::Relaxed);
    }

    fn describe(&self) -> String {
        let v = self.0.load(Ordering::Relaxed);
        format!("round {}, frame {}: {}", v >> 40, (v >> 8) & 0xffff_ffff, STEPS[(v & 0xff) as usize % STEPS.len()])
    }
}

const VERTEX: &str = "void main() { gl_Position = gl_Vertex; gl_TexCoord[0] = gl_MultiTexCoord0; }\0";
const FRAGMENT: &str = "uniform vec4 tint; void main() { gl_FragColor = tint; }\0";


/// The RGBA8 pixel at (x, y) of the read buffer.
fn pixel(x: i32, y: i32) -> [u8; 4] {
    let mut out = [7u8; 4];
    // Safety: room for one RGBA8 pixel.
    unsafe { gl::glReadPixels(x, y, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out
}

/// Compiles and links the program of [`VERTEX`] and [`FRAGMENT`]; returns it and the location
/// of its `tint`.
fn program() -> (u32, i32) {
    // Safety: the sources are NUL-terminated and outlive the calls.
    unsafe {
        let program = gl::glCreateProgram();
        for (kind, source) in [(GL_VERTEX_SHADER, VERTEX), (GL_FRAGMENT_SHADER, FRAGMENT)] {
            let shader = gl::glCreateShader(kind);
            let text = source.as_ptr().cast();
            gl::glShaderSource(shader, 1, &text, std::ptr::null());
            gl::glCompileShader(shader);
            let mut ok = 0;
            gl::glGetShaderiv(shader, GL_COMPILE_STATUS, &mut ok);
            assert_eq!(ok, 1, "shader compiles");
            gl::glAttachShader(program, shader);
        }
        gl::glLinkProgram(program);
        let mut ok = 0;
        gl::glGetProgramiv(program, GL_LINK_STATUS, &mut ok);
        assert_eq!(ok, 1, "program links");
        (program, gl::glGetUniformLocation(program, c"tint".as_ptr()))
    }
}

/// One thread's work: `rounds` contexts one after another, each drawing `frames` frames whose
/// colours depend on `thread`, every result checked.
fn work(thread: u64, rounds: u64, frames: u64, progress: &Progress, start: &Barrier) {
    start.wait();
    for round in 0..rounds {
        progress.set(round, 0, 0);
        let ctx = glrt::gl_entry::headless::glrtCreateContext(std::ptr::null_mut());
        assert!(!ctx.is_null(), "glrtCreateContext failed");
        // Sizes differ between threads and rounds: framebuffers of several sizes at once.
        let size = SIZE + 8 * ((thread + round) % 3) as i32;
        assert_eq!(glrt::gl_entry::headless::glrtMakeCurrent(ctx, size, size), 1);
        let (program, tint) = program();
        let mut names = [0u32; 2];
        // Safety (this block and the loop's): plain calls on the context current here; every
        // pointer outlives its call.
        unsafe {
            gl::glGenTextures(2, names.as_mut_ptr());
            gl::glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE as i32);
        }
        let [texture, target] = names;
        let mut fbo = 0;
        unsafe {
            gl::glGenFramebuffersEXT(1, &mut fbo);
            gl::glBindTexture(GL_TEXTURE_2D, target);
            gl::glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST as i32);
            gl::glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST as i32);
            gl::glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA as i32, 16, 16, 0, GL_RGBA, GL_UNSIGNED_BYTE, std::ptr::null());
            gl::glBindFramebufferEXT(GL_FRAMEBUFFER_EXT, fbo);
            gl::glFramebufferTexture2DEXT(GL_FRAMEBUFFER_EXT, GL_COLOR_ATTACHMENT0_EXT, GL_TEXTURE_2D, target, 0);
            assert_eq!(gl::glCheckFramebufferStatusEXT(GL_FRAMEBUFFER_EXT), GL_FRAMEBUFFER_COMPLETE_EXT);
            gl::glBindFramebufferEXT(GL_FRAMEBUFFER_EXT, 0);
        }
        for frame in 0..frames {
            // Colours of this thread and frame (multiples of 17: exact in 8 bits).
            let c = |k: u64| (((thread * 5 + frame * 3 + k) % 16) * 17) as u8;
            let texel = [c(0), c(1), c(2), 255];
            let fbo_color = [c(3), c(4), c(5), 255];
            let tint_color = [c(6), c(7), c(8), 255];
            let f = |v: u8| v as f32 / 255.0;
            progress.set(round, frame, 1);
            unsafe {
                // A texture replaced every frame (a new version to upload).
                gl::glBindTexture(GL_TEXTURE_2D, texture);
                gl::glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST as i32);
                gl::glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA as i32, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, texel.repeat(4).as_ptr().cast());
            }
            progress.set(round, frame, 2);
            unsafe {
                // The framebuffer object: cleared, then half drawn with the texture.
                gl::glBindFramebufferEXT(GL_FRAMEBUFFER_EXT, fbo);
                gl::glViewport(0, 0, 16, 16);
                gl::glClearColor(f(fbo_color[0]), f(fbo_color[1]), f(fbo_color[2]), 1.0);
                gl::glClear(GL_COLOR_BUFFER_BIT);
                gl::glEnable(GL_TEXTURE_2D);
                textured_rect([-1.0, -1.0, 0.0, 1.0]);
                gl::glBindFramebufferEXT(GL_FRAMEBUFFER_EXT, 0);
            }
            progress.set(round, frame, 3);
            unsafe {
                // The window: left half samples the framebuffer object's texture, the right
                // half is drawn by the program.
                gl::glViewport(0, 0, size, size);
                gl::glClearColor(0.0, 0.0, 0.0, 1.0);
                gl::glClear(GL_COLOR_BUFFER_BIT);
                gl::glBindTexture(GL_TEXTURE_2D, target);
                textured_rect([-1.0, -1.0, 0.0, 1.0]);
                gl::glDisable(GL_TEXTURE_2D);
                gl::glUseProgram(program);
                gl::glUniform4f(tint, f(tint_color[0]), f(tint_color[1]), f(tint_color[2]), 1.0);
                textured_rect([0.0, -1.0, 1.0, 1.0]);
                gl::glUseProgram(0);
            }
            progress.set(round, frame, 4);
            let q = size / 4;
            let at = |x, y| (pixel(x, y), format!("thread {thread}, round {round}, frame {frame}, pixel ({x}, {y})"));
            let (got, place) = at(q / 2, size / 2);
            assert_eq!(got, texel, "{place}: the texture drawn into the framebuffer object, sampled");
            let (got, place) = at(q + q / 2, size / 2);
            assert_eq!(got, fbo_color, "{place}: the framebuffer object's clear, sampled");
            let (got, place) = at(3 * q, size / 2);
            assert_eq!(got, tint_color, "{place}: the program's colour");
            assert_eq!(error(), GL_NO_ERROR);
            progress.set(round, frame, 5);
            glrt::gl_entry::headless::glrtSwapBuffers();
        }
        progress.set(round, frames, 6);
        glrt::gl_entry::headless::glrtDestroyContext(ctx);
    }
    progress.set(rounds, 0, 7);
}

/// Prints every thread's stack with gdb, when it is installed and may attach to this process
/// (where the driver or glrt waits, for the report of a hang). At most five minutes: reading
/// the symbols of a debug build takes gdb minutes on a busy machine (a release build, seconds).
fn print_stacks() {
    let pid = std::process::id().to_string();
    let gdb = std::process::Command::new("timeout")
        .args(["-k", "5", "300", "gdb", "-batch", "-p", &pid, "-ex", "thread apply all bt"])
        .output();
    match gdb {
        Ok(out) => {
            let _ = std::io::stderr().write_all(&out.stdout);
            let _ = std::io::stderr().write_all(&out.stderr);
        }
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "(no stacks: gdb: {e})");
        }
    }
}

#[test]
fn contexts_on_several_threads_render_at_once() {
    // Safety: set before any thread starts and before glrt reads it (this binary's only test).
    unsafe { std::env::set_var("GLRT_MODE", "raster") };
    let threads = setting("GLRT_STRESS_THREADS", 4);
    let rounds = setting("GLRT_STRESS_ROUNDS", 3);
    let frames = setting("GLRT_STRESS_FRAMES", 20);
    let limit = Duration::from_secs(setting("GLRT_STRESS_LIMIT", 120) * rounds.max(1));
    let progress: Arc<Vec<Progress>> = Arc::new((0..threads).map(|_| Progress(AtomicU64::new(0))).collect());
    let start = Arc::new(Barrier::new(threads as usize));
    let workers: Vec<_> = (0..threads)
        .map(|t| {
            let (progress, start) = (progress.clone(), start.clone());
            std::thread::Builder::new()
                .name(format!("gl-{t}"))
                .spawn(move || work(t, rounds, frames, &progress[t as usize], &start))
                .unwrap()
        })
        .collect();
    let began = Instant::now();
    while !workers.iter().all(|w| w.is_finished()) {
        if began.elapsed() > limit {
            let report: Vec<String> = progress.iter().enumerate().map(|(t, p)| format!("  thread {t}: {}", p.describe())).collect();
            // Straight to stderr: the test harness would keep `eprintln!` output, and the
            // process ends here.
            let _ = writeln!(std::io::stderr(), "renderers_in_threads: no end after {limit:?} (a hang):\n{}", report.join("\n"));
            print_stacks();
            std::process::exit(2);
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let failed: Vec<String> = workers
        .into_iter()
        .enumerate()
        .filter_map(|(t, w)| w.join().err().map(|e| format!("thread {t}: {}", e.downcast_ref::<String>().cloned().unwrap_or_default())))
        .collect();
    assert!(failed.is_empty(), "{}", failed.join("\n"));
    let device = glrt::render::raster::device::probe_properties().map(|p| p.device_name_as_c_str().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default());
    eprintln!("{threads} threads × {rounds} contexts × {frames} frames on {device:?} in {:.1} s", began.elapsed().as_secs_f64());
}
