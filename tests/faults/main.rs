//! Faults injected with `GLRT_FAULTS` (`glrt::faults`) and survived: a device lost mid-frame
//! (headless and on a window), a GPU allocation that fails, a swapchain out of date, a shader
//! the driver cannot compile (raster and tracer pipelines), a full disk while capturing (made
//! full on purpose, and `/dev/full`). Each degrades as DESIGN.md says: one message, a new
//! device or raster fallback or black frames, a capture closed with a valid trailer; and the
//! program goes on (no panic, later GL calls answer, `glGetError` is `GL_NO_ERROR`).
//!
//! The setting is per process, so each test runs its program in a child process: this test
//! binary again, running only that test (`--exact`) with [`CHILD`] and the fault in its
//! environment; the parent checks how the child ended, its stderr, and the files it left. The
//! programs draw through glrt's exported functions (headless contexts, or GLX on a private
//! Xvfb) on lavapipe (when its ICD file exists).

#[path = "../common/mod.rs"]
mod common;
#[path = "../programs/mod.rs"]
mod programs;
#[path = "../x11/mod.rs"]
mod x11;

use std::process::{Command, Output};
use std::time::Duration;

use common::*;
use glrt::faults::{Fault, arm};

/// Set in the environment of a child: run the program, not the parent's checks.
const CHILD: &str = "GLRT_FAULTS_TEST_CHILD";

/// Whether this process is a child running a program.
fn is_child() -> bool {
    std::env::var_os(CHILD).is_some()
}

/// Runs test `name` as a child process with `env` (and lavapipe as its Vulkan driver when
/// installed); fails if it does not end within two minutes.
fn child(name: &str, env: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(std::env::current_exe().unwrap());
    cmd.args(["--exact", name, "--nocapture", "--test-threads=1"]).env(CHILD, "1").env_remove("GLRT_FAULTS").env_remove("GLRT_CAPTURE");
    let lavapipe = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";
    if std::path::Path::new(lavapipe).exists() {
        cmd.env("VK_DRIVER_FILES", lavapipe);
    }
    cmd.envs(env.iter().copied());
    let (out, stopped) = programs::run_for(cmd, Duration::from_secs(120));
    assert!(!stopped, "{name} did not end within 2 minutes:\n{}", stderr(&out));
    out
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Asserts that the child ended normally, having run its test, and that its stderr says
/// `message` exactly once; returns its stderr.
fn ran_and_said_once(out: &Output, message: &str) -> String {
    let err = stderr(out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "the program failed ({}):\n{err}\n{stdout}", out.status);
    assert!(stdout.contains("1 passed"), "the child ran no test:\n{stdout}");
    assert_eq!(err.matches(message).count(), 1, "'{message}' said once:\n{err}");
    err
}

/// Reads the pixel at (x, y) of the read buffer as RGBA8.
fn pixel(x: i32, y: i32) -> [u8; 4] {
    let mut out = [7u8; 4];
    // Safety: room for one RGBA8 pixel.
    unsafe { gl::glReadPixels(x, y, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out
}

/// Clears the colour buffer to `rgb`.
fn clear(rgb: [f32; 3]) {
    // Safety: plain calls on the current context.
    unsafe {
        gl::glClearColor(rgb[0], rgb[1], rgb[2], 1.0);
        gl::glClear(GL_COLOR_BUFFER_BIT);
    }
}

/// Draws the rectangle `[x0, x1] × [y0, y1]` (normalized device coordinates) in `rgb`.
fn rect(rgb: [f32; 3], corners: [f32; 4]) {
    // Safety: a plain call on the current context.
    unsafe { gl::glColor3f(rgb[0], rgb[1], rgb[2]) };
    textured_rect(corners);
}

/// What shows the host program still works after a fault: state queries answer, objects are
/// made, no error is pending.
fn gl_still_answers() {
    assert_eq!(error(), GL_NO_ERROR);
    assert_eq!(get_i(GL_VIEWPORT)[..4], [0, 0, SIZE, SIZE]);
    let mut name = 0;
    // Safety: room for one name.
    unsafe { gl::glGenTextures(1, &mut name) };
    assert_ne!(name, 0);
    // Safety: plain call; GL_INVALID_ENUM is the answer the specification names.
    unsafe { gl::glEnable(0xdead) };
    assert_eq!(error(), GL_INVALID_ENUM, "errors are still reported");
    assert_eq!(error(), GL_NO_ERROR);
}

const RED: [f32; 3] = [1.0, 0.0, 0.0];
const GREEN: [f32; 3] = [0.0, 1.0, 0.0];
const BLUE: [f32; 3] = [0.0, 0.0, 1.0];
const WHOLE: [f32; 4] = [-1.0, -1.0, 1.0, 1.0];
const LEFT: [f32; 4] = [-1.0, -1.0, 0.0, 1.0];
const RIGHT: [f32; 4] = [0.0, -1.0, 1.0, 1.0];

/// The device is lost at the fourth frame submission (each read-back submits what is recorded,
/// and so does the swap: frame 0's two read-backs and swap, then frame 1's read-back): a new
/// device replaces it (said once) and frame 1 is drawn again there, so the read-back and the
/// frames after are as drawn. A second loss stops the renderer (said once): read-backs are
/// black from then on, and the program goes on.
#[test]
fn device_lost_mid_frame() {
    if !is_child() {
        let out = child("device_lost_mid_frame", &[("GLRT_FAULTS", "device-lost@4"), ("GLRT_MODE", "raster")]);
        let err = ran_and_said_once(&out, "the Vulkan device was lost");
        assert!(err.contains("rendering goes on, rasterized, on a new device"), "{err}");
        ran_and_said_once(&out, "the Vulkan renderer stopped");
        assert_eq!(err.matches("The logical device has been lost").count(), 2, "{err}");
        return;
    }
    let ctx = make_current();
    clear(RED);
    rect(GREEN, LEFT);
    assert_eq!(pixel(48, 32), [255, 0, 0, 255]);
    assert_eq!(pixel(16, 32), [0, 255, 0, 255]);
    glrt::gl_entry::headless::glrtSwapBuffers();
    clear(BLUE);
    rect(GREEN, LEFT);
    assert_eq!(pixel(48, 32), [0, 0, 255, 255], "the frame the device was lost in, drawn again on the new one");
    assert_eq!(pixel(16, 32), [0, 255, 0, 255]);
    gl_still_answers();
    glrt::gl_entry::headless::glrtSwapBuffers();
    for _ in 0..2 {
        clear(RED);
        rect(GREEN, RIGHT);
        assert_eq!(pixel(48, 32), [0, 255, 0, 255], "later frames on the new device");
        assert_eq!(pixel(16, 32), [255, 0, 0, 255]);
        glrt::gl_entry::headless::glrtSwapBuffers();
    }
    // The new device is lost too: the renderer stops.
    arm(Fault::DeviceLost, 1);
    for _ in 0..3 {
        clear(RED);
        rect(GREEN, RIGHT);
        assert_eq!(pixel(48, 32), [0, 0, 0, 255], "black once the renderer stopped");
        glrt::gl_entry::headless::glrtSwapBuffers();
    }
    let mut depth = [0.5f32; 4];
    // Safety: room for 2 × 2 values.
    unsafe { gl::glReadPixels(0, 0, 2, 2, GL_DEPTH_COMPONENT, GL_FLOAT, depth.as_mut_ptr().cast()) };
    assert_eq!(depth, [0.0; 4], "depth reads back as zero");
    gl_still_answers();
    glrt::gl_entry::headless::glrtDestroyContext(ctx);
}

/// A GPU allocation fails: the texture a frame uploads first. That texture samples as white
/// (said once), the rest of the frame and later frames draw as asked, and a texture made later
/// is on the GPU. Then the framebuffer of a larger drawable cannot be allocated: the renderer
/// stops (said once) and reads back black.
#[test]
fn gpu_allocation_failure() {
    if !is_child() {
        let out = child("gpu_allocation_failure", &[("GLRT_MODE", "raster")]);
        let err = ran_and_said_once(&out, "cannot be used");
        assert_eq!(err.matches("vkAllocateMemory failed: A device memory allocation has failed").count(), 2, "{err}");
        ran_and_said_once(&out, "the Vulkan renderer stopped");
        return;
    }
    let ctx = make_current();
    // A first frame with a texture: everything the renderer makes once is made.
    let texture = |rgba: [u8; 4]| {
        let texels: Vec<u8> = rgba.repeat(4);
        let mut name = 0;
        // Safety: `texels` holds the 2 × 2 RGBA8 image the call reads.
        unsafe {
            gl::glGenTextures(1, &mut name);
            gl::glBindTexture(GL_TEXTURE_2D, name);
            gl::glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST as i32);
            gl::glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST as i32);
            gl::glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA as i32, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.as_ptr().cast());
            gl::glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE as i32);
            gl::glEnable(GL_TEXTURE_2D);
        }
        name
    };
    texture([0, 0, 255, 255]);
    clear(RED);
    rect(GREEN, WHOLE);
    assert_eq!(pixel(32, 32), [0, 0, 255, 255]);
    glrt::gl_entry::headless::glrtSwapBuffers();
    // The next allocation is the new texture's image.
    arm(Fault::Allocation, 1);
    texture([0, 255, 0, 255]);
    clear(RED);
    rect(GREEN, LEFT);
    assert_eq!(pixel(16, 32), [255, 255, 255, 255], "the texture that could not be made samples as white");
    assert_eq!(pixel(48, 32), [255, 0, 0, 255]);
    gl_still_answers();
    glrt::gl_entry::headless::glrtSwapBuffers();
    texture([255, 255, 0, 255]);
    clear(BLUE);
    rect(GREEN, RIGHT);
    assert_eq!(pixel(48, 32), [255, 255, 0, 255], "a later texture is on the GPU");
    assert_eq!(pixel(16, 32), [0, 0, 255, 255]);
    glrt::gl_entry::headless::glrtSwapBuffers();
    gl_still_answers();
    // A larger drawable: the framebuffer's new images cannot be allocated, the renderer stops.
    arm(Fault::Allocation, 1);
    assert_eq!(glrt::gl_entry::headless::glrtMakeCurrent(ctx, 2 * SIZE, 2 * SIZE), 1);
    for _ in 0..2 {
        clear(RED);
        assert_eq!(pixel(100, 100), [0, 0, 0, 255], "black once the renderer stopped");
        glrt::gl_entry::headless::glrtSwapBuffers();
    }
    assert_eq!(error(), GL_NO_ERROR);
    assert_eq!(get_i(GL_VIEWPORT)[..4], [0, 0, SIZE, SIZE], "the viewport is the program's");
    glrt::gl_entry::headless::glrtDestroyContext(ctx);
}

/// The driver cannot compile a raster pipeline (the one of blended draws): those draws are not
/// drawn (said once, not tried again), the others are, frame after frame.
#[test]
fn raster_shader_compile_failure() {
    if !is_child() {
        let out = child("raster_shader_compile_failure", &[("GLRT_MODE", "raster")]);
        let err = ran_and_said_once(&out, "a raster pipeline cannot be created");
        assert!(err.contains("ERROR_INVALID_SHADER_NV"), "{err}");
        return;
    }
    let ctx = make_current();
    clear(RED);
    rect(GREEN, RIGHT);
    assert_eq!(pixel(48, 32), [0, 255, 0, 255]);
    glrt::gl_entry::headless::glrtSwapBuffers();
    let blended = |on: bool| unsafe {
        // Safety: plain state calls.
        if on {
            gl::glEnable(GL_BLEND);
            gl::glBlendFunc(GL_ONE, GL_ONE);
        } else {
            gl::glDisable(GL_BLEND);
        }
    };
    // The next pipeline made is the blended draw's.
    arm(Fault::ShaderCompile, 1);
    for _ in 0..3 {
        clear(RED);
        blended(true);
        rect(BLUE, LEFT);
        blended(false);
        rect(GREEN, RIGHT);
        assert_eq!(pixel(16, 32), [255, 0, 0, 255], "the blended draw is not drawn");
        assert_eq!(pixel(48, 32), [0, 255, 0, 255], "the other draw is");
        gl_still_answers();
        glrt::gl_entry::headless::glrtSwapBuffers();
    }
    // Another blend function: another pipeline, which compiles.
    clear(RED);
    blended(true);
    // Safety: plain state call.
    unsafe { gl::glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA) };
    rect(BLUE, LEFT);
    assert_eq!(pixel(16, 32), [0, 0, 255, 255]);
    glrt::gl_entry::headless::glrtDestroyContext(ctx);
}

/// The path tracer's first pipeline does not compile: the renderer rasterizes every draw,
/// said once.
#[test]
fn tracer_shader_compile_failure_rasterizes() {
    if !is_child() {
        let out = child("tracer_shader_compile_failure_rasterizes", &[("GLRT_FAULTS", "shader@1"), ("GLRT_MODE", "pathtrace")]);
        let err = ran_and_said_once(&out, "path tracing is not available");
        assert!(err.contains("vkCreateComputePipelines failed: ERROR_INVALID_SHADER_NV"), "{err}");
        return;
    }
    let ctx = make_current();
    for _ in 0..2 {
        clear(RED);
        rect(GREEN, LEFT);
        assert_eq!(pixel(16, 32), [0, 255, 0, 255]);
        assert_eq!(pixel(48, 32), [255, 0, 0, 255]);
        glrt::gl_entry::headless::glrtSwapBuffers();
    }
    gl_still_answers();
    glrt::gl_entry::headless::glrtDestroyContext(ctx);
}

/// A pipeline of the path tracer does not compile in the first traced frame (made then): the
/// renderer rasterizes from then on (said once); the traced quad shows in its raster colour.
#[test]
fn tracer_failing_mid_frame_rasterizes() {
    if !is_child() {
        let out = child("tracer_failing_mid_frame_rasterizes", &[("GLRT_MODE", "pathtrace")]);
        let err = ran_and_said_once(&out, "path tracing stopped");
        assert!(err.contains("ERROR_INVALID_SHADER_NV"), "{err}");
        return;
    }
    let ctx = make_current();
    // The next pipeline made: one of the tracer's, made in its first frame.
    arm(Fault::ShaderCompile, 1);
    // Safety: plain state calls on the current context.
    unsafe {
        gl::glMatrixMode(GL_PROJECTION);
        gl::glFrustum(-0.1, 0.1, -0.1, 0.1, 0.1, 100.0);
        gl::glMatrixMode(GL_MODELVIEW);
        gl::glEnable(GL_DEPTH_TEST);
    }
    let quad = || unsafe {
        // Safety: plain calls on the current context.
        gl::glClear(GL_DEPTH_BUFFER_BIT);
        gl::glColor3f(0.0, 1.0, 0.0);
        gl::glBegin(GL_QUADS);
        gl::glVertex3f(-1.0, -1.0, -2.0);
        gl::glVertex3f(1.0, -1.0, -2.0);
        gl::glVertex3f(1.0, 1.0, -2.0);
        gl::glVertex3f(-1.0, 1.0, -2.0);
        gl::glEnd();
    };
    clear(RED);
    quad();
    glrt::gl_entry::headless::glrtSwapBuffers();
    for _ in 0..2 {
        clear(RED);
        quad();
        assert_eq!(pixel(32, 32), [0, 255, 0, 255], "the quad, rasterized");
        assert_eq!(pixel(1, 1), [255, 0, 0, 255]);
        glrt::gl_entry::headless::glrtSwapBuffers();
    }
    assert_eq!(error(), GL_NO_ERROR);
    glrt::gl_entry::headless::glrtDestroyContext(ctx);
}

/// The swapchain is out of date when frame 1's image is acquired (the second acquisition): it
/// is recreated and frame 1 still reaches the window, and so do the frames after.
#[test]
fn swapchain_out_of_date() {
    if !is_child() {
        let out = window_child("swapchain_out_of_date", "out-of-date@2");
        if !stderr(&out).contains("through vulkan") {
            eprintln!("skipped: the device does not present to Xvfb windows here, no swapchain to make out of date:\n{}", stderr(&out));
            return;
        }
        ran_and_said_once(&out, "the swapchain is out of date");
        return;
    }
    frames_reach_the_window();
}

/// The device is lost when frame 1 is submitted: on the new device, the window's presentation
/// is made again and frame 1 and the frames after reach the window.
#[test]
fn device_lost_on_a_window() {
    if !is_child() {
        let out = window_child("device_lost_on_a_window", "device-lost@2");
        ran_and_said_once(&out, "the Vulkan device was lost");
        return;
    }
    frames_reach_the_window();
}

/// Runs window test `name` in a child on a private Xvfb with `faults`, raster mode and info logs;
/// asserts it ended normally.
fn window_child(name: &str, faults: &str) -> Output {
    let server = x11::Xvfb::start(24);
    let out = child(name, &[("DISPLAY", &server.display), ("GLRT_FAULTS", faults), ("GLRT_MODE", "raster"), ("GLRT_LOG", "info")]);
    assert!(out.status.success(), "the program failed ({}):\n{}", out.status, stderr(&out));
    out
}

/// A GLX program: a window cleared red, green and blue in three frames; each frame must reach
/// the window (read back with `XGetImage`).
fn frames_reach_the_window() {
    use glrt::gl_entry::glx::exports::{config::glXChooseVisual, context::*, swap::glXSwapBuffers};
    use glrt::gl_entry::glx::types::types;
    use x11_dl::xlib::Xlib;
    let x = Xlib::open().expect("libX11");
    // Safety: plain Xlib and GLX calls on the display opened here, which outlives them.
    unsafe {
        let dpy = (x.XOpenDisplay)(std::ptr::null());
        assert!(!dpy.is_null(), "cannot open the display");
        let win = x11::mapped_window(&x, dpy, SIZE as u32, SIZE as u32);
        let mut attribs = [x11_dl::glx::GLX_RGBA, x11_dl::glx::GLX_DOUBLEBUFFER, 0];
        let gdpy = dpy.cast::<types::Display>();
        let vis = glXChooseVisual(gdpy, 0, attribs.as_mut_ptr());
        assert!(!vis.is_null());
        let ctx = glXCreateContext(gdpy, vis, std::ptr::null_mut(), 1);
        assert!(!ctx.is_null());
        assert_eq!(glXMakeCurrent(gdpy, win, ctx), 1);
        for (frame, rgb) in [RED, GREEN, BLUE].into_iter().enumerate() {
            clear(rgb);
            glXSwapBuffers(gdpy, win);
            let want = rgb.map(|c| (c * 255.0) as u8);
            let deadline = std::time::Instant::now() + Duration::from_secs(20);
            loop {
                let shown = x11::read_rgb(&x, dpy, win, SIZE as u32, SIZE as u32);
                if shown.iter().all(|&p| p == want) {
                    break;
                }
                assert!(std::time::Instant::now() < deadline, "frame {frame} never reached the window: {:?}", shown[0]);
                std::thread::sleep(Duration::from_millis(20));
            }
        }
        gl_still_answers_on_window();
        glXMakeCurrent(gdpy, 0, std::ptr::null_mut());
        glXDestroyContext(gdpy, ctx);
        (x.XFree)(vis.cast());
        (x.XCloseDisplay)(dpy);
    }
}

/// [`gl_still_answers`] without the viewport check's size (the window's).
fn gl_still_answers_on_window() {
    assert_eq!(error(), GL_NO_ERROR);
    assert_eq!(get_i(GL_VIEWPORT)[2..4], [SIZE, SIZE]);
}

/// Frames of the capture program: a clear of its own colour each (frame `n` clears to
/// `(n, 255 - n, 128)`), and a swap.
fn capture_frames(count: u8) {
    let ctx = make_current();
    for n in 0..count {
        clear([n as f32 / 255.0, (255 - n) as f32 / 255.0, 128.0 / 255.0]);
        rect(GREEN, [0.5, 0.5, 1.0, 1.0]);
        glrt::gl_entry::headless::glrtSwapBuffers();
    }
    gl_still_answers();
    glrt::gl_entry::headless::glrtDestroyContext(ctx);
}

/// Frames the capture program draws.
const CAPTURED_FRAMES: u8 = 60;

/// `glrt ARGS`: whether it succeeded, its stdout and stderr.
fn glrt(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_glrt")).args(args).env("GLRT_MODE", "raster").output().expect("run glrt");
    (out.status.success(), String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// The disk of a capture is full part way through: the program goes on, one message says the
/// capture stopped, and the file is a finished capture of the frames written before, which
/// `glrt dump` reads and `glrt replay` renders, the last one as drawn.
#[test]
fn full_disk_while_capturing() {
    if is_child() {
        return capture_frames(CAPTURED_FRAMES);
    }
    let whole = programs::scratch("faults", "whole.glrtcap");
    let out = child("full_disk_while_capturing", &[("GLRT_CAPTURE", whole.to_str().unwrap()), ("GLRT_MODE", "none")]);
    assert!(out.status.success(), "{}", stderr(&out));
    let size = std::fs::metadata(&whole).unwrap().len();
    let (ok, dump, err) = glrt(&["dump", whole.to_str().unwrap()]);
    assert!(ok, "{err}");
    assert_eq!(dump.matches("== end of frame").count(), CAPTURED_FRAMES as usize, "the whole capture");

    // A disk with room for all but the last 1,000 bytes: the last frames are not written.
    let cut = programs::scratch("faults", "cut.glrtcap");
    let room = (size - 1000).to_string();
    let faults = format!("disk-full@{room}");
    let out = child("full_disk_while_capturing", &[("GLRT_CAPTURE", cut.to_str().unwrap()), ("GLRT_MODE", "none"), ("GLRT_FAULTS", &faults)]);
    let err = ran_and_said_once(&out, "the capture stops here and the file holds the frames written before");
    assert!(err.contains("No space left on device"), "{err}");
    assert!(std::fs::metadata(&cut).unwrap().len() <= size - 1000);
    let (ok, dump, err) = glrt(&["dump", cut.to_str().unwrap()]);
    assert!(ok, "glrt dump reads the capture left behind: {err}");
    let frames = dump.matches("== end of frame").count();
    assert!((1..CAPTURED_FRAMES as usize).contains(&frames), "{frames} frames of {CAPTURED_FRAMES} kept");
    let dir = programs::scratch("faults", "cut-frames");
    let _ = std::fs::remove_dir_all(&dir);
    let (ok, _, err) = glrt(&["replay", cut.to_str().unwrap(), "--out", dir.to_str().unwrap()]);
    assert!(ok, "glrt replay renders the capture left behind: {err}");
    let last = frames - 1;
    let png = dir.join(format!("frame-{last:05}.png"));
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&png).unwrap_or_else(|e| panic!("{}: {e}", png.display()))));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (SIZE as u32, SIZE as u32));
    let channels = info.line_size / info.width as usize;
    let at = |x: usize, y: usize| buf[y * info.line_size + x * channels..][..3].to_vec();
    assert_eq!(at(0, SIZE as usize - 1), [last as u8, 255 - last as u8, 128], "frame {last}'s clear colour");
    assert!(!dir.join(format!("frame-{frames:05}.png")).exists(), "no frame after the last one written");
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_file(&whole).unwrap();
    std::fs::remove_file(&cut).unwrap();
}

/// A capture to `/dev/full`: nothing can be written; one message, and the program goes on.
#[test]
fn capture_to_dev_full() {
    if is_child() {
        return capture_frames(3);
    }
    let out = child("capture_to_dev_full", &[("GLRT_CAPTURE", "/dev/full"), ("GLRT_MODE", "none")]);
    let err = ran_and_said_once(&out, "GLRT_CAPTURE");
    assert!(err.contains("cannot create /dev/full: No space left on device"), "{err}");
}
