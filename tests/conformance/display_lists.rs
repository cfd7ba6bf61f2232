//! Display lists against the OpenGL 1.5 specification, §5.4, through the C exports:
//! commands the specification executes immediately while a list is compiled take effect at
//! once in `GL_COMPILE` mode, compiled commands only when the list is called;
//! `GL_COMPILE_AND_EXECUTE` does both; lists call lists by name at execution time (nesting,
//! the nesting limit); `glCallLists` with every type and `glListBase`; the errors of
//! `glNewList`, `glEndList`, `glGenLists`, `glDeleteLists` and `glCallLists`.
//! Rows for commands of the modules still being merged are in the `*_vertex_module` and
//! `*_texture_module` tests.

use crate::common;

use std::ffi::c_void;

use common::*;

/// The list every test compiles into.
const LIST: u32 = 10;

/// `GL_FEEDBACK` buffer type `GL_3D` (gl_generator drops enums whose names start with a digit).
const FEEDBACK_3D: GLenum = 0x0601;

/// The translation part (x) of the modelview matrix.
fn modelview_x() -> f32 {
    get_f(GL_MODELVIEW_MATRIX)[12]
}

/// Compiles `body` into [`LIST`] with `mode`, returning the error left by compiling.
fn compile(mode: GLenum, body: impl FnOnce()) -> GLenum {
    unsafe { gl::glNewList(LIST, mode) };
    body();
    unsafe { gl::glEndList() };
    error()
}

/// Pushes a failure when `got` differs from `want`.
fn expect<T: PartialEq + std::fmt::Debug>(failures: &mut Vec<String>, what: &str, got: T, want: T) {
    if got != want {
        failures.push(format!("{what}: {got:?}, spec {want:?}"));
    }
}

/// Pushes a failure when `glGetError` differs from `want`.
fn expect_error(failures: &mut Vec<String>, what: &str, want: GLenum) {
    expect(failures, what, name(error()), name(want));
}

/// Immediate commands of main (§5.4: "Display list commands", feedback and selection, `glGet*`
/// and `glIs*`, `glFlush`/`glFinish`, client state) act while a list is compiled, and are not
/// part of the list.
#[test]
fn immediate_commands_act_while_compiling() {
    make_current();
    let mut failures = Vec::new();
    let mut feedback = [0.0f32; 64];
    let mut select = [0u32; 64];
    unsafe {
        gl::glNewList(99, GL_COMPILE);
        gl::glEndList();
    }
    let mut generated = 0;
    let compile_error = compile(GL_COMPILE, || unsafe {
        // Queries answer the current state, not what the list will do.
        gl::glEnable(GL_LIGHTING);
        expect(&mut failures, "glIsEnabled(LIGHTING) after a compiled glEnable", is_enabled(GL_LIGHTING), false);
        expect(&mut failures, "glGetIntegerv(LIST_INDEX)", get_i(GL_LIST_INDEX)[0], LIST as i32);
        expect(&mut failures, "glGetIntegerv(LIST_MODE)", get_i(GL_LIST_MODE)[0], GL_COMPILE as i32);
        generated = gl::glGenLists(2);
        expect(&mut failures, "glIsList(glGenLists(2))", gl::glIsList(generated), 1);
        expect(&mut failures, "glIsList(glGenLists(2) + 1)", gl::glIsList(generated + 1), 1);
        // The list being compiled is not defined yet.
        expect(&mut failures, "glIsList(the list being compiled)", gl::glIsList(LIST), 0);
        gl::glDeleteLists(99, 1);
        expect(&mut failures, "glIsList after glDeleteLists", gl::glIsList(99), 0);
        gl::glFeedbackBuffer(64, FEEDBACK_3D, feedback.as_mut_ptr());
        gl::glRenderMode(GL_FEEDBACK);
        expect(&mut failures, "RENDER_MODE after glRenderMode(FEEDBACK)", get_i(GL_RENDER_MODE)[0], GL_FEEDBACK as i32);
        gl::glRenderMode(GL_RENDER);
        gl::glSelectBuffer(64, select.as_mut_ptr());
        gl::glRenderMode(GL_SELECT);
        expect(&mut failures, "RENDER_MODE after glRenderMode(SELECT)", get_i(GL_RENDER_MODE)[0], GL_SELECT as i32);
        gl::glRenderMode(GL_RENDER);
        gl::glClientActiveTexture(GL_TEXTURE1);
        expect(
            &mut failures,
            "CLIENT_ACTIVE_TEXTURE after glClientActiveTexture",
            get_i(GL_CLIENT_ACTIVE_TEXTURE)[0],
            GL_TEXTURE1 as i32,
        );
        gl::glClientActiveTexture(GL_TEXTURE0);
        gl::glFlush();
        gl::glFinish();
        // glGetError is executed too: nothing is latched so far.
        expect(&mut failures, "glGetError while compiling", gl::glGetError(), GL_NO_ERROR);
    });
    expect(&mut failures, "error compiling", name(compile_error), name(GL_NO_ERROR));
    expect(&mut failures, "glGenLists while compiling returned", generated > 0, true);
    expect(&mut failures, "glIsList(compiled list)", unsafe { gl::glIsList(LIST) }, 1);
    expect(&mut failures, "LIST_INDEX after glEndList", get_i(GL_LIST_INDEX)[0], 0);
    expect(&mut failures, "LIST_MODE after glEndList", get_i(GL_LIST_MODE)[0], 0);

    // Calling the list runs only the compiled glEnable: not the render mode changes.
    unsafe { gl::glCallList(LIST) };
    expect(&mut failures, "LIGHTING after glCallList", is_enabled(GL_LIGHTING), true);
    expect(&mut failures, "RENDER_MODE after glCallList", get_i(GL_RENDER_MODE)[0], GL_RENDER as i32);
    expect(&mut failures, "glIsList(99) after glCallList", unsafe { gl::glIsList(99) }, 0);
    expect(&mut failures, "error after glCallList", name(error()), name(GL_NO_ERROR));
    assert_none("immediate commands in GL_COMPILE", &failures);
}

/// Compiled commands: no effect in `GL_COMPILE` until `glCallList`, then every time it is
/// called; `GL_COMPILE_AND_EXECUTE` both executes and compiles.
#[test]
fn compiled_commands_wait_for_call_list() {
    make_current();
    let mut failures = Vec::new();
    let body = || unsafe {
        gl::glEnable(GL_CULL_FACE);
        gl::glShadeModel(GL_FLAT);
        gl::glTranslatef(1.0, 0.0, 0.0);
        gl::glLightfv(GL_LIGHT0, GL_DIFFUSE, [0.5f32, 0.25, 0.125, 1.0].as_ptr());
        gl::glPushMatrix();
    };
    let light_diffuse = || {
        let mut v = [0.0f32; 4];
        unsafe { gl::glGetLightfv(GL_LIGHT0, GL_DIFFUSE, v.as_mut_ptr()) };
        v
    };
    let state = || (is_enabled(GL_CULL_FACE), get_i(GL_SHADE_MODEL)[0], modelview_x(), get_i(GL_MODELVIEW_STACK_DEPTH)[0]);
    let initial = (false, GL_SMOOTH as i32, 0.0, 1);

    expect(&mut failures, "error compiling", name(compile(GL_COMPILE, body)), name(GL_NO_ERROR));
    expect(&mut failures, "state after GL_COMPILE", state(), initial);
    expect(&mut failures, "LIGHT0 diffuse after GL_COMPILE", light_diffuse(), [1.0, 1.0, 1.0, 1.0]);
    unsafe { gl::glCallList(LIST) };
    expect(&mut failures, "state after glCallList", state(), (true, GL_FLAT as i32, 1.0, 2));
    expect(&mut failures, "LIGHT0 diffuse after glCallList", light_diffuse(), [0.5, 0.25, 0.125, 1.0]);
    unsafe { gl::glCallList(LIST) };
    expect(&mut failures, "state after a second glCallList", state(), (true, GL_FLAT as i32, 2.0, 3));

    // Back to the initial state, then GL_COMPILE_AND_EXECUTE.
    unsafe {
        gl::glPopMatrix();
        gl::glPopMatrix();
        gl::glLoadIdentity();
        gl::glDisable(GL_CULL_FACE);
        gl::glShadeModel(GL_SMOOTH);
    }
    expect(&mut failures, "error compiling and executing", name(compile(GL_COMPILE_AND_EXECUTE, body)), name(GL_NO_ERROR));
    expect(&mut failures, "state after GL_COMPILE_AND_EXECUTE", state(), (true, GL_FLAT as i32, 1.0, 2));
    unsafe { gl::glCallList(LIST) };
    expect(&mut failures, "state after calling the list", state(), (true, GL_FLAT as i32, 2.0, 3));
    assert_none("compiled commands", &failures);
}

/// A command with a bad argument is compiled without an error; the error comes when the list
/// is executed (§5.4: the list holds the command, which runs — and fails — when called).
#[test]
fn errors_of_compiled_commands_come_at_execution() {
    make_current();
    let mut failures = Vec::new();
    let compiled = compile(GL_COMPILE, || unsafe { gl::glShadeModel(GL_POINTS) });
    expect(&mut failures, "compiling glShadeModel(GL_POINTS)", name(compiled), name(GL_NO_ERROR));
    unsafe { gl::glCallList(LIST) };
    expect(&mut failures, "calling it", name(error()), name(GL_INVALID_ENUM));
    expect(&mut failures, "SHADE_MODEL", get_i(GL_SHADE_MODEL)[0], GL_SMOOTH as i32);
    assert_none("errors in lists", &failures);
}

/// Lists call lists by name when executed: a `glCallList` compiled (not executed) in
/// `GL_COMPILE`, the callee's definition at call time, undefined names ignored, a list being
/// redefined kept until `glEndList`, and the nesting limit stopping a list that calls itself
/// (§5.4, `MAX_LIST_NESTING`).
#[test]
fn nested_lists() {
    make_current();
    let mut failures = Vec::new();
    let (outer, inner, undefined) = (20, 21, 22);
    let define = |n: u32, body: &dyn Fn()| unsafe {
        gl::glNewList(n, GL_COMPILE);
        body();
        gl::glEndList();
    };
    define(inner, &|| unsafe { gl::glTranslatef(1.0, 0.0, 0.0) });
    define(outer, &|| unsafe {
        gl::glCallList(inner);
        gl::glCallList(undefined);
        gl::glTranslatef(10.0, 0.0, 0.0);
    });
    expect(&mut failures, "x after compiling (glCallList compiled, not run)", modelview_x(), 0.0);
    unsafe { gl::glCallList(outer) };
    expect(&mut failures, "x after calling the outer list", modelview_x(), 11.0);
    // Redefining the inner list changes what the outer list does.
    define(inner, &|| unsafe { gl::glTranslatef(100.0, 0.0, 0.0) });
    unsafe { gl::glCallList(outer) };
    expect(&mut failures, "x after redefining the inner list", modelview_x(), 121.0);
    expect(&mut failures, "error", name(error()), name(GL_NO_ERROR));

    // A list being redefined keeps its old contents until glEndList (§5.4).
    unsafe { gl::glLoadIdentity() };
    let (old, caller) = (24, 25);
    define(old, &|| unsafe { gl::glTranslatef(1.0, 0.0, 0.0) });
    define(caller, &|| unsafe { gl::glCallList(old) });
    unsafe {
        gl::glNewList(old, GL_COMPILE_AND_EXECUTE);
        gl::glCallList(caller);
        expect(&mut failures, "glIsList of a list being redefined", gl::glIsList(old), 1);
        gl::glEndList();
    }
    expect(&mut failures, "x after calling a list while it is redefined", modelview_x(), 1.0);
    define(old, &|| unsafe { gl::glTranslatef(2.0, 0.0, 0.0) });
    unsafe { gl::glCallList(caller) };
    expect(&mut failures, "x after the redefinition", modelview_x(), 3.0);

    // A list that calls itself stops at the nesting limit.
    unsafe { gl::glLoadIdentity() };
    let recursive = 23;
    define(recursive, &|| unsafe {
        gl::glTranslatef(1.0, 0.0, 0.0);
        gl::glCallList(recursive);
    });
    unsafe { gl::glCallList(recursive) };
    let limit = get_i(GL_MAX_LIST_NESTING)[0];
    expect(&mut failures, "translations by a self-calling list", modelview_x(), limit as f32);
    expect(&mut failures, "error after the nesting limit", name(error()), name(GL_NO_ERROR));
    assert_none("nested lists", &failures);
}

/// `glCallLists` reads names of every type (§5.4, table 5.7) and offsets them by
/// `glListBase`; names of undefined lists are ignored.
#[test]
fn call_lists_types_and_list_base() {
    make_current();
    const BASE: u32 = 100;
    // Each list translates x by its own name, so x tells which lists ran.
    for n in [97, 98, 99, 101, 102, 105, 106, 300, 358, 359, 360, 1100] {
        unsafe {
            gl::glNewList(n, GL_COMPILE);
            gl::glTranslatef(n as f32, 0.0, 0.0);
            gl::glEndList();
        }
    }
    let f: [f32; 1] = [6.0];
    let cases: &[(GLenum, &str, Vec<u8>, i32, f32)] = &[
        (GL_BYTE, "GL_BYTE 1, 2, -1", vec![1, 2, 0xFF], 3, 101.0 + 102.0 + 99.0),
        (GL_UNSIGNED_BYTE, "GL_UNSIGNED_BYTE 200, 1", vec![200, 1], 2, 300.0 + 101.0),
        (GL_SHORT, "GL_SHORT -2", (-2i16).to_ne_bytes().to_vec(), 1, 98.0),
        (GL_UNSIGNED_SHORT, "GL_UNSIGNED_SHORT 1000", 1000u16.to_ne_bytes().to_vec(), 1, 1100.0),
        (GL_INT, "GL_INT -3", (-3i32).to_ne_bytes().to_vec(), 1, 97.0),
        (GL_UNSIGNED_INT, "GL_UNSIGNED_INT 5", 5u32.to_ne_bytes().to_vec(), 1, 105.0),
        (GL_FLOAT, "GL_FLOAT 6.0", f[0].to_ne_bytes().to_vec(), 1, 106.0),
        (GL_2_BYTES, "GL_2_BYTES 0x0102", vec![1, 2], 1, 358.0),
        (GL_3_BYTES, "GL_3_BYTES 0x000103", vec![0, 1, 3], 1, 359.0),
        (GL_4_BYTES, "GL_4_BYTES 0x00000104", vec![0, 0, 1, 4], 1, 360.0),
        (GL_UNSIGNED_INT, "GL_UNSIGNED_INT 7 (undefined list)", 7u32.to_ne_bytes().to_vec(), 1, 0.0),
    ];
    let mut failures = Vec::new();
    unsafe { gl::glListBase(BASE) };
    expect(&mut failures, "LIST_BASE", get_i(GL_LIST_BASE)[0], BASE as i32);
    for (type_, what, bytes, n, want) in cases {
        unsafe {
            gl::glLoadIdentity();
            gl::glCallLists(*n, *type_, bytes.as_ptr().cast::<c_void>());
        }
        expect(&mut failures, what, modelview_x(), *want);
        expect(&mut failures, &format!("{what}: error"), name(error()), name(GL_NO_ERROR));
    }
    // A compiled glCallLists keeps a copy of the names; the base is read when the list runs.
    let names = [1u8, 2];
    compile(GL_COMPILE, || unsafe { gl::glCallLists(2, GL_UNSIGNED_BYTE, names.as_ptr().cast()) });
    unsafe {
        gl::glLoadIdentity();
        gl::glListBase(0);
        gl::glCallList(LIST);
    }
    expect(&mut failures, "compiled glCallLists after glListBase(0)", modelview_x(), 0.0);
    unsafe {
        gl::glListBase(BASE);
        gl::glCallList(LIST);
    }
    expect(&mut failures, "compiled glCallLists after glListBase(100)", modelview_x(), 203.0);
    assert_none("glCallLists", &failures);
}

/// Errors of the display-list commands (§5.4 and its error summary).
#[test]
fn list_command_errors() {
    make_current();
    let mut failures = Vec::new();
    unsafe { gl::glNewList(0, GL_COMPILE) };
    expect_error(&mut failures, "glNewList(0)", GL_INVALID_VALUE);
    unsafe { gl::glNewList(LIST, GL_RENDER) };
    expect_error(&mut failures, "glNewList(bad mode)", GL_INVALID_ENUM);
    expect(&mut failures, "LIST_INDEX after failed glNewList", get_i(GL_LIST_INDEX)[0], 0);
    unsafe { gl::glEndList() };
    expect_error(&mut failures, "glEndList without glNewList", GL_INVALID_OPERATION);
    unsafe {
        gl::glNewList(LIST, GL_COMPILE);
        gl::glNewList(LIST + 1, GL_COMPILE);
    }
    expect_error(&mut failures, "glNewList inside glNewList", GL_INVALID_OPERATION);
    expect(&mut failures, "LIST_INDEX after the nested glNewList", get_i(GL_LIST_INDEX)[0], LIST as i32);
    unsafe { gl::glEndList() };
    expect_error(&mut failures, "glEndList of the outer list", GL_NO_ERROR);
    expect(&mut failures, "glIsList(outer)", unsafe { gl::glIsList(LIST) }, 1);
    expect(&mut failures, "glIsList(nested)", unsafe { gl::glIsList(LIST + 1) }, 0);
    unsafe { gl::glEndList() };
    expect_error(&mut failures, "a second glEndList", GL_INVALID_OPERATION);
    let got = unsafe { gl::glGenLists(-1) };
    expect_error(&mut failures, "glGenLists(-1)", GL_INVALID_VALUE);
    expect(&mut failures, "glGenLists(-1) returned", got, 0);
    let got = unsafe { gl::glGenLists(0) };
    expect_error(&mut failures, "glGenLists(0)", GL_NO_ERROR);
    expect(&mut failures, "glGenLists(0) returned", got, 0);
    unsafe { gl::glDeleteLists(LIST, -1) };
    expect_error(&mut failures, "glDeleteLists(range -1)", GL_INVALID_VALUE);
    expect(&mut failures, "glIsList after a failed glDeleteLists", unsafe { gl::glIsList(LIST) }, 1);
    unsafe { gl::glCallLists(-1, GL_UNSIGNED_BYTE, [0u8].as_ptr().cast()) };
    expect_error(&mut failures, "glCallLists(n = -1)", GL_INVALID_VALUE);
    unsafe { gl::glCallLists(1, GL_DOUBLE, [0u8; 8].as_ptr().cast()) };
    expect_error(&mut failures, "glCallLists(type GL_DOUBLE)", GL_INVALID_ENUM);
    unsafe { gl::glCallList(12345) };
    expect_error(&mut failures, "glCallList(undefined)", GL_NO_ERROR);
    assert_none("display list errors", &failures);
}

/// Client state and vertex-array commands (`vertex` branch) act while compiling (§5.4).
#[test]
fn immediate_client_commands_vertex_module() {
    make_current();
    let mut failures = Vec::new();
    let coords = [0.0f32; 12];
    let compiled = compile(GL_COMPILE, || unsafe {
        gl::glEnableClientState(GL_VERTEX_ARRAY);
        gl::glVertexPointer(2, GL_FLOAT, 8, coords.as_ptr().cast());
        gl::glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT);
        let mut buffer = 0u32;
        gl::glGenBuffers(1, &mut buffer);
        gl::glBindBuffer(GL_ARRAY_BUFFER, buffer);
        expect(&mut failures, "ARRAY_BUFFER_BINDING", get_i(GL_ARRAY_BUFFER_BINDING)[0], buffer as i32);
        gl::glBindBuffer(GL_ARRAY_BUFFER, 0);
        // Buffer mapping (ARB_map_buffer_range) is not compiled either.
        gl::glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
        gl::glBufferData(GL_PIXEL_PACK_BUFFER, 8, std::ptr::null(), GL_STREAM_READ);
        let mapped = gl::glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, 8, GL_MAP_WRITE_BIT | GL_MAP_FLUSH_EXPLICIT_BIT);
        expect(&mut failures, "glMapBufferRange while compiling", mapped.is_null(), false);
        gl::glFlushMappedBufferRange(GL_PIXEL_PACK_BUFFER, 0, 8);
        expect(&mut failures, "glUnmapBuffer while compiling", gl::glUnmapBuffer(GL_PIXEL_PACK_BUFFER), 1);
        gl::glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    });
    expect(&mut failures, "error compiling", name(compiled), name(GL_NO_ERROR));
    expect(&mut failures, "VERTEX_ARRAY", is_enabled(GL_VERTEX_ARRAY), true);
    expect(&mut failures, "VERTEX_ARRAY_SIZE", get_i(GL_VERTEX_ARRAY_SIZE)[0], 2);
    expect(&mut failures, "VERTEX_ARRAY_STRIDE", get_i(GL_VERTEX_ARRAY_STRIDE)[0], 8);
    expect(&mut failures, "CLIENT_ATTRIB_STACK_DEPTH", get_i(GL_CLIENT_ATTRIB_STACK_DEPTH)[0], 1);
    unsafe { gl::glCallList(LIST) };
    expect(&mut failures, "CLIENT_ATTRIB_STACK_DEPTH after glCallList", get_i(GL_CLIENT_ATTRIB_STACK_DEPTH)[0], 1);
    expect(&mut failures, "error after glCallList", name(error()), name(GL_NO_ERROR));
    assert_none("client commands in GL_COMPILE", &failures);
}

/// Pixel store and texture names act while compiling (§5.4).
#[test]
fn immediate_pixel_and_texture_commands_texture_module() {
    make_current();
    let mut failures = Vec::new();
    let mut names = [0u32; 2];
    let compiled = compile(GL_COMPILE, || unsafe {
        gl::glPixelStorei(GL_PACK_ALIGNMENT, 1);
        expect(&mut failures, "PACK_ALIGNMENT", get_i(GL_PACK_ALIGNMENT)[0], 1);
        gl::glGenTextures(2, names.as_mut_ptr());
        gl::glBindTexture(GL_TEXTURE_2D, names[0]);
        gl::glDeleteTextures(1, &names[1]);
    });
    expect(&mut failures, "error compiling", name(compiled), name(GL_NO_ERROR));
    expect(&mut failures, "glGenTextures names", names[0] != 0 && names[1] != 0 && names[0] != names[1], true);
    expect(&mut failures, "TEXTURE_BINDING_2D (glBindTexture is compiled)", get_i(GL_TEXTURE_BINDING_2D)[0], 0);
    unsafe { gl::glCallList(LIST) };
    expect(&mut failures, "TEXTURE_BINDING_2D after glCallList", get_i(GL_TEXTURE_BINDING_2D)[0], names[0] as i32);
    expect(&mut failures, "error after glCallList", name(error()), name(GL_NO_ERROR));
    assert_none("pixel and texture commands in GL_COMPILE", &failures);
}

/// `glReadPixels` reads at once while compiling, and sees the clears of the list only once it
/// is called (§5.4).
#[test]
#[ignore = "glReadPixels needs the Vulkan renderer (issue: Vulkan back end); no pixels exist before it"]
fn read_pixels_acts_while_compiling() {
    make_current();
    let mut failures = Vec::new();
    let mut pixels = [0xAAu8; 4];
    unsafe { gl::glClear(GL_COLOR_BUFFER_BIT) };
    let compiled = compile(GL_COMPILE, || unsafe {
        gl::glClearColor(1.0, 1.0, 1.0, 1.0);
        gl::glClear(GL_COLOR_BUFFER_BIT);
        gl::glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixels.as_mut_ptr().cast());
    });
    expect(&mut failures, "error compiling", name(compiled), name(GL_NO_ERROR));
    expect(&mut failures, "glReadPixels wrote the cleared black pixel", pixels, [0, 0, 0, 0]);
    unsafe { gl::glCallList(LIST) };
    unsafe { gl::glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixels.as_mut_ptr().cast()) };
    expect(&mut failures, "glReadPixels after the list cleared to white", pixels, [255, 255, 255, 255]);
    assert_none("glReadPixels in GL_COMPILE", &failures);
}
