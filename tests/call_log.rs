//! The call log (`GLRT_TRACE`, `gl_entry::call_log`): `glrt-demo --headless` through glrt's
//! `libGL.so.1` (`target/<profile>/libGL.so.1`, a symlink to `libglrt.so` made here when
//! missing) writes the lines the module documents; and calls made in this process through the
//! exports show the errors they raise.

#[path = "programs/mod.rs"]
mod programs;

use std::path::PathBuf;
use std::process::{Command, Output};

use programs::lib_dir;

use glrt::gl_entry::glx::exports::query::glXGetProcAddress;
use glrt::gl_entry::{exports as gl, headless};
use glrt::translate::gl::*;

fn temp_path(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("glrt-trace-{}-{name}", std::process::id()))
}

/// Runs `glrt-demo --headless --frames 3` with `GLRT_TRACE` at a fresh file (and the extra
/// environment); returns the run and the log's lines.
fn demo_trace(name: &str, env: &[(&str, &str)]) -> (Output, Vec<String>) {
    let log = temp_path(name);
    let _ = std::fs::remove_file(&log);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_glrt-demo"));
    cmd.args(["--headless", "--frames", "3"]).env("LD_LIBRARY_PATH", lib_dir()).env("GLRT_TRACE", &log);
    cmd.env_remove("GLRT_TRACE_FILTER");
    for (k, v) in env {
        cmd.env(k, v);
    }
    let out = cmd.output().expect("glrt-demo runs");
    assert!(out.status.success(), "glrt-demo failed: {}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&log).unwrap_or_default();
    let _ = std::fs::remove_file(&log);
    (out, text.lines().map(str::to_owned).collect())
}

/// The frame-boundary lines.
fn boundaries(lines: &[String]) -> Vec<&String> {
    lines.iter().filter(|l| l.contains(" == end of frame (")).collect()
}

/// The values of `name=` arguments of a call line, parsed as floats.
fn float_args(line: &str) -> Vec<f32> {
    let args = line.split_once('(').and_then(|(_, r)| r.rsplit_once(')')).map_or("", |(a, _)| a);
    args.split(", ").filter_map(|a| a.split_once('=')?.1.parse().ok()).collect()
}

#[test]
fn demo_log_has_frames_enum_names_and_values() {
    let (_, lines) = demo_trace("demo", &[]);
    let frames = boundaries(&lines);
    assert_eq!(
        frames.iter().map(|l| l.as_str()).collect::<Vec<_>>(),
        ["0 == end of frame (glrtSwapBuffers)", "1 == end of frame (glrtSwapBuffers)", "2 == end of frame (glrtSwapBuffers)"]
    );
    // Every call line starts with its frame number, in order.
    let mut last = 0;
    for line in &lines {
        let frame: u64 = line.split(' ').next().and_then(|n| n.parse().ok()).unwrap_or_else(|| panic!("no frame: {line}"));
        assert!(frame >= last && frame <= 3, "{line}");
        last = frame;
    }
    for frame in 0..3 {
        let begin = format!("{frame} glBegin(mode=GL_QUADS)");
        assert!(lines.contains(&begin), "no {begin}");
        let clear = format!("{frame} glClear(mask=GL_COLOR_BUFFER_BIT|GL_DEPTH_BUFFER_BIT)");
        assert!(lines.contains(&clear), "no {clear}");
    }
    let vertex = lines.iter().find(|l| l.starts_with("0 glVertex3f(x=")).expect("a glVertex3f line");
    assert_eq!(float_args(vertex).len(), 3, "{vertex}");
    assert!(vertex.contains(", y=") && vertex.contains(", z="), "{vertex}");
    // The demo's calls raise no error and all have a context.
    assert!(lines.iter().all(|l| !l.contains(" -> ") && !l.contains("no current context")));
}

#[test]
fn filter_keeps_only_matching_calls() {
    let (_, all) = demo_trace("all", &[]);
    let (_, lines) = demo_trace("filtered", &[("GLRT_TRACE_FILTER", "glVertex")]);
    assert_eq!(boundaries(&lines).len(), 3);
    let calls: Vec<&String> = lines.iter().filter(|l| !l.contains(" == end of frame (")).collect();
    assert!(calls.iter().all(|l| l.split(' ').nth(1).is_some_and(|c| c.starts_with("glVertex"))), "{calls:?}");
    // Exactly the glVertex* lines of the unfiltered log.
    let expected = all.iter().filter(|l| l.split(' ').nth(1).is_some_and(|c| c.contains("glVertex"))).count();
    assert!(expected > 0);
    assert_eq!(calls.len(), expected);
}

#[test]
fn unwritable_trace_file_disables_tracing() {
    let dir = temp_path("no-such-dir");
    let bad = dir.join("trace.log");
    let out = Command::new(env!("CARGO_BIN_EXE_glrt-demo"))
        .args(["--headless", "--frames", "3"])
        .env("LD_LIBRARY_PATH", lib_dir())
        .env("GLRT_TRACE", &bad)
        .output()
        .expect("glrt-demo runs");
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.matches("GLRT_TRACE: cannot create").count(), 1, "{stderr}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("frames: 3"));
    assert!(!bad.exists());
}

fn hash_of(bytes: &[u8]) -> u64 {
    xxhash_rust::xxh3::xxh3_64(bytes)
}

/// The only test that calls glrt in this process: the log is opened at the first call.
#[test]
fn errors_results_and_pointers_in_process() {
    let log = temp_path("in-process");
    // Safety: no other test of this binary reads or writes the environment of this process.
    unsafe {
        std::env::set_var("GLRT_TRACE", &log);
        std::env::remove_var("GLRT_TRACE_FILTER");
    }
    let v = [1.0f32, 2.5, -3.0];
    let light = [0.0f32, 1.0, 0.0, 0.0];
    let names = [7u16, 8, 9];
    let indices = [2u8, 1, 0];
    let image: Vec<u8> = (0..14).collect();
    let proc_name = c"glBegin";
    let parts = [c"void main()".as_ptr(), c" {}XX".as_ptr()];
    let lengths = [-1, 3];
    unsafe {
        gl::glEnable(GL_TEXTURE_2D); // no context yet
        let ctx = headless::glrtCreateContext(std::ptr::null_mut());
        assert_eq!(headless::glrtMakeCurrent(ctx, 64, 64), 1);
        gl::glBegin(0x1234); // not a primitive
        gl::glBegin(GL_QUADS);
        gl::glVertex3fv(v.as_ptr());
        gl::glVertex3fv(std::ptr::null());
        gl::glEnd();
        assert_eq!(gl::glGetError(), GL_INVALID_ENUM);
        assert_eq!(gl::glGetError(), 0);
        gl::glMatrixMode(0x1234);
        gl::glEnable(GL_TEXTURE_2D);
        gl::glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR as i32);
        gl::glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP as f32);
        gl::glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE as i32);
        gl::glFogi(GL_FOG_MODE, GL_EXP as i32);
        gl::glFogf(GL_FOG_DENSITY, 2048.0); // numeric: GL_EXP's value, not its name
        gl::glLightfv(GL_LIGHT0, GL_POSITION, light.as_ptr());
        gl::glCallLists(3, GL_UNSIGNED_SHORT, names.as_ptr().cast());
        gl::glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_BYTE, indices.as_ptr().cast());
        // 2 x 2 RGB bytes, rows aligned to 4: 8 + 6 bytes.
        gl::glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB as i32, 2, 2, 0, GL_RGB, GL_UNSIGNED_BYTE, image.as_ptr().cast());
        // With a pixel unpack buffer bound the pointer is an offset: its address only.
        gl::glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 1);
        gl::glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB as i32, 2, 2, 0, GL_RGB, GL_UNSIGNED_BYTE, std::ptr::without_provenance(8));
        let shader = gl::glCreateShader(GL_FRAGMENT_SHADER);
        gl::glShaderSource(shader, 2, parts.as_ptr(), lengths.as_ptr());
        glXGetProcAddress(proc_name.as_ptr().cast());
        headless::glrtSwapBuffers();
        headless::glrtMakeCurrent(std::ptr::null_mut(), 0, 0);
        headless::glrtDestroyContext(ctx);
    }
    let text = std::fs::read_to_string(&log).expect("the log was flushed at the swap");
    let _ = std::fs::remove_file(&log);
    let lines: Vec<&str> = text.lines().collect();
    let addr = format!("{:p}", v.as_ptr());
    let hash = hash_of(&v.map(f32::to_ne_bytes).concat());
    assert_eq!(
        lines,
        [
            "0 glEnable(cap=GL_TEXTURE_2D) (no current context)".to_owned(),
            "0 glBegin(mode=0x1234) -> GL_INVALID_ENUM".to_owned(),
            "0 glBegin(mode=GL_QUADS)".to_owned(),
            format!("0 glVertex3fv(v={addr}(12 bytes, xxh3 {hash:016x})[1.0, 2.5, -3.0])"),
            "0 glVertex3fv(v=NULL)".to_owned(),
            "0 glEnd()".to_owned(),
            "0 glGetError() = GL_INVALID_ENUM".to_owned(),
            "0 glGetError() = GL_NO_ERROR".to_owned(),
            "0 glMatrixMode(mode=0x1234) -> GL_INVALID_ENUM".to_owned(),
            "0 glEnable(cap=GL_TEXTURE_2D)".to_owned(),
            "0 glTexParameteri(target=GL_TEXTURE_2D, pname=GL_TEXTURE_MIN_FILTER, param=GL_LINEAR)".to_owned(),
            "0 glTexParameterf(target=GL_TEXTURE_2D, pname=GL_TEXTURE_WRAP_S, param=GL_CLAMP)".to_owned(),
            "0 glTexEnvi(target=GL_TEXTURE_ENV, pname=GL_TEXTURE_ENV_MODE, param=GL_MODULATE)".to_owned(),
            "0 glFogi(pname=GL_FOG_MODE, param=GL_EXP)".to_owned(),
            "0 glFogf(pname=GL_FOG_DENSITY, param=2048.0)".to_owned(),
            format!("0 glLightfv(light=GL_LIGHT0, pname=GL_POSITION, params={:p}(16 bytes, xxh3 {:016x})[0.0, 1.0, 0.0, 0.0])", light.as_ptr(), hash_of(&light.map(f32::to_ne_bytes).concat())),
            format!("0 glCallLists(n=3, type=GL_UNSIGNED_SHORT, lists={:p}(6 bytes, xxh3 {:016x})[7, 8, 9])", names.as_ptr(), hash_of(&names.map(u16::to_ne_bytes).concat())),
            format!("0 glDrawElements(mode=GL_TRIANGLES, count=3, type=GL_UNSIGNED_BYTE, indices={:p}(3 bytes, xxh3 {:016x})[2, 1, 0])", indices.as_ptr(), hash_of(&indices)),
            format!(
                "0 glTexImage2D(target=GL_TEXTURE_2D, level=0, internalformat=GL_RGB, width=2, height=2, border=0, format=GL_RGB, type=GL_UNSIGNED_BYTE, pixels={:p}(14 bytes, xxh3 {:016x})[00 01 02 03 04 05 06 07 08 09 0a 0b 0c 0d])",
                image.as_ptr(),
                hash_of(&image)
            ),
            "0 glBindBuffer(target=GL_PIXEL_UNPACK_BUFFER, buffer=1)".to_owned(),
            "0 glTexImage2D(target=GL_TEXTURE_2D, level=0, internalformat=GL_RGB, width=2, height=2, border=0, format=GL_RGB, type=GL_UNSIGNED_BYTE, pixels=0x8)".to_owned(),
            "0 glCreateShader(type=GL_FRAGMENT_SHADER) = 1".to_owned(),
            format!("0 glShaderSource(shader=1, count=2, string={:p}[\"void main()\", \" {{}}\"], length={:p})", parts.as_ptr(), lengths.as_ptr()),
            format!("0 glXGetProcAddress(procName={:p}\"glBegin\") = {:p}", proc_name.as_ptr(), gl::glBegin as *const ()),
            "0 == end of frame (glrtSwapBuffers)".to_owned(),
        ]
    );
}
