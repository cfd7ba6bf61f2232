//! Shared helpers of the conformance tests: a headless context current on the calling thread,
//! typed `glGet` wrappers and GL enum names for failure messages. Everything goes through the
//! C exports (`glrt::gl_entry::exports`), exactly as a program calls them.

#![allow(dead_code)]

pub use glrt::gl_entry::exports as gl;
pub use glrt::translate::gl::*;

/// Width and height of the drawable every test context is made current with.
pub const SIZE: i32 = 64;

/// Creates a headless context and makes it current on this thread (each `#[test]` runs on its
/// own thread, so each test has its own context); returns its handle.
pub fn make_current() -> *mut std::ffi::c_void {
    let ctx = glrt::gl_entry::headless::glrtCreateContext(std::ptr::null_mut());
    assert!(!ctx.is_null(), "glrtCreateContext failed");
    assert_eq!(glrt::gl_entry::headless::glrtMakeCurrent(ctx, SIZE, SIZE), 1, "glrtMakeCurrent failed");
    assert_eq!(error(), GL_NO_ERROR, "error after making the context current");
    ctx
}

/// Runs `f` in a new context current on this thread, destroyed afterwards.
pub fn with_fresh_context<T>(f: impl FnOnce() -> T) -> T {
    let ctx = make_current();
    let result = f();
    glrt::gl_entry::headless::glrtDestroyContext(ctx);
    result
}

/// The name of a GL enum for messages (`GL_FOG_MODE`), or its hexadecimal value.
pub fn name(value: GLenum) -> String {
    enum_name(value).map_or_else(|| format!("{value:#06x}"), str::to_owned)
}

/// `glGetError`.
pub fn error() -> GLenum {
    // Safety: plain call on this thread's current context.
    unsafe { gl::glGetError() }
}

/// Room for the largest `glGet` answer read here (a matrix), plus a sentinel tail.
const ROOM: usize = 32;

/// `glGetIntegerv`: the first values written.
pub fn get_i(pname: GLenum) -> Vec<GLint> {
    let mut v = [i32::MIN; ROOM];
    // Safety: `v` has room for any state variable.
    unsafe { gl::glGetIntegerv(pname, v.as_mut_ptr()) };
    v.to_vec()
}

/// `glGetFloatv`: the first values written.
pub fn get_f(pname: GLenum) -> Vec<GLfloat> {
    let mut v = [f32::NAN; ROOM];
    // Safety: `v` has room for any state variable.
    unsafe { gl::glGetFloatv(pname, v.as_mut_ptr()) };
    v.to_vec()
}

/// `glGetBooleanv`: the first values written, as `bool`s (`None` where nothing was written).
pub fn get_b(pname: GLenum) -> Vec<Option<bool>> {
    let mut v = [0xAAu8; ROOM];
    // Safety: `v` has room for any state variable.
    unsafe { gl::glGetBooleanv(pname, v.as_mut_ptr()) };
    v.iter().map(|&b| match b {
        0 => Some(false),
        1 => Some(true),
        _ => None,
    })
    .collect()
}

/// `glGetDoublev`: the first values written.
pub fn get_d(pname: GLenum) -> Vec<GLdouble> {
    let mut v = [f64::NAN; ROOM];
    // Safety: `v` has room for any state variable.
    unsafe { gl::glGetDoublev(pname, v.as_mut_ptr()) };
    v.to_vec()
}

/// `glIsEnabled`.
pub fn is_enabled(cap: GLenum) -> bool {
    // Safety: plain call on this thread's current context.
    unsafe { gl::glIsEnabled(cap) != 0 }
}

/// Asserts that `failures` is empty, listing every entry otherwise.
pub fn assert_none(what: &str, failures: &[String]) {
    assert!(failures.is_empty(), "{what}: {} mismatch(es):\n  {}", failures.len(), failures.join("\n  "));
}

/// Draws the rectangle `[x0, x1] × [y0, y1]` (normalized device coordinates) as one quad with
/// texture coordinates from 0 to 1, in the current colour.
pub fn textured_rect([x0, y0, x1, y1]: [f32; 4]) {
    // Safety: plain calls on the current context.
    unsafe {
        gl::glBegin(GL_QUADS);
        gl::glTexCoord2f(0.0, 0.0);
        gl::glVertex2f(x0, y0);
        gl::glTexCoord2f(1.0, 0.0);
        gl::glVertex2f(x1, y0);
        gl::glTexCoord2f(1.0, 1.0);
        gl::glVertex2f(x1, y1);
        gl::glTexCoord2f(0.0, 1.0);
        gl::glVertex2f(x0, y1);
        gl::glEnd();
    }
}
