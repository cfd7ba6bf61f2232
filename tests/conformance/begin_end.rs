//! The Begin/End rule of the OpenGL 1.5 specification, §2.6.3, in the manner of piglit's
//! `tests/spec/gl-1.0/beginend-coverage.c` (own code):
//!
//! > The only GL commands that are allowed within any Begin/End pairs are the commands for
//! > specifying vertex coordinates, vertex color, normal coordinates, texture coordinates, and
//! > fog coordinates (Vertex, Color, SecondaryColor, Index, Normal, TexCoord and MultiTexCoord,
//! > FogCoord), the ArrayElement command, the EvalCoord and EvalPoint commands, commands for
//! > specifying lighting material parameters (Material commands), display list invocation
//! > commands (CallList and CallLists), and the EdgeFlag command. Executing any other GL
//! > command between the execution of Begin and the corresponding execution of End results in
//! > the error INVALID_OPERATION.
//!
//! Each forbidden command is called with valid arguments inside `glBegin(GL_POINTS)`/`glEnd`:
//! it must raise `INVALID_OPERATION` and leave the state it would change as it was (§2.5:
//! the offending command is ignored). The same commands compiled into a display list raise
//! nothing at compile time and the error when the list is executed inside `glBegin`/`glEnd`.
//! Allowed commands raise nothing, directly or from a list. Client-side commands (array
//! pointers, client state, pixel store) are left out: glrt, like Mesa, runs them without an
//! error (`build/overlay.rs`, `CLIENT_SIDE`). Rows of commands of the modules
//! still being merged are in the `*_vertex_module` and `*_texture_module` tests.

use crate::common;

use std::ffi::c_void;

use common::*;

/// One command of the table.
struct Row {
    /// Its name, for messages.
    name: &'static str,
    /// Calls it once with valid arguments.
    call: unsafe fn(),
    /// State it changes when it runs (read with `glGetFloatv` before and after), or 0.
    probe: GLenum,
    /// Whether it is compiled into display lists (§5.4: some commands never are).
    compiled: bool,
}

/// A row of a command that is compiled into display lists and changes `probe`.
const fn row(name: &'static str, call: unsafe fn(), probe: GLenum) -> Row {
    Row { name, call, probe, compiled: true }
}

/// A row of a command executed immediately even while a list is compiled (§5.4).
const fn immediate(name: &'static str, call: unsafe fn(), probe: GLenum) -> Row {
    Row { name, call, probe, compiled: false }
}

/// A translation matrix used by the matrix rows.
const MATRIX: [f32; 16] = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 2.0, 3.0, 1.0];
/// Four floats for vector parameters.
const VEC4: [f32; 4] = [0.5, 0.25, 0.125, 1.0];
/// Client memory the selection and feedback rows hand out (never written: the commands fail).
static mut SINK: [u32; 64] = [0; 64];
/// `GL_3D` (gl_generator drops enums whose names start with a digit).
const FEEDBACK_3D: GLenum = 0x0601;
/// The control points of a one-dimensional evaluator map.
const POINTS: [f32; 6] = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];

/// Commands on main that are not allowed between Begin and End, each with valid arguments.
const FORBIDDEN: &[Row] = &[
    row("glEnable", || unsafe { gl::glEnable(GL_LIGHTING) }, GL_LIGHTING),
    row("glDisable", || unsafe { gl::glDisable(GL_DITHER) }, GL_DITHER),
    row("glShadeModel", || unsafe { gl::glShadeModel(GL_FLAT) }, GL_SHADE_MODEL),
    row("glMatrixMode", || unsafe { gl::glMatrixMode(GL_PROJECTION) }, GL_MATRIX_MODE),
    row("glLoadMatrixf", || unsafe { gl::glLoadMatrixf(MATRIX.as_ptr()) }, GL_MODELVIEW_MATRIX),
    row("glMultMatrixf", || unsafe { gl::glMultMatrixf(MATRIX.as_ptr()) }, GL_MODELVIEW_MATRIX),
    row("glLoadTransposeMatrixf", || unsafe { gl::glLoadTransposeMatrixf(MATRIX.as_ptr()) }, GL_MODELVIEW_MATRIX),
    row("glMultTransposeMatrixf", || unsafe { gl::glMultTransposeMatrixf(MATRIX.as_ptr()) }, GL_MODELVIEW_MATRIX),
    row("glTranslatef", || unsafe { gl::glTranslatef(1.0, 2.0, 3.0) }, GL_MODELVIEW_MATRIX),
    row("glRotatef", || unsafe { gl::glRotatef(90.0, 0.0, 0.0, 1.0) }, GL_MODELVIEW_MATRIX),
    row("glScalef", || unsafe { gl::glScalef(2.0, 2.0, 2.0) }, GL_MODELVIEW_MATRIX),
    row("glFrustum", || unsafe { gl::glFrustum(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0) }, GL_MODELVIEW_MATRIX),
    row("glOrtho", || unsafe { gl::glOrtho(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0) }, GL_MODELVIEW_MATRIX),
    row("glPushMatrix", || unsafe { gl::glPushMatrix() }, GL_MODELVIEW_STACK_DEPTH),
    row("glLoadIdentity", || unsafe { gl::glLoadIdentity() }, GL_MODELVIEW_MATRIX),
    row("glViewport", || unsafe { gl::glViewport(1, 2, 3, 4) }, GL_VIEWPORT),
    row("glDepthRange", || unsafe { gl::glDepthRange(0.25, 0.5) }, GL_DEPTH_RANGE),
    row("glClipPlane", || unsafe { gl::glClipPlane(GL_CLIP_PLANE0, [1.0f64, 0.0, 0.0, 0.0].as_ptr()) }, 0),
    row("glFogf", || unsafe { gl::glFogf(GL_FOG_DENSITY, 2.0) }, GL_FOG_DENSITY),
    row("glFogfv", || unsafe { gl::glFogfv(GL_FOG_COLOR, VEC4.as_ptr()) }, GL_FOG_COLOR),
    row("glLightf", || unsafe { gl::glLightf(GL_LIGHT0, GL_SPOT_EXPONENT, 2.0) }, 0),
    row("glLightModelf", || unsafe { gl::glLightModelf(GL_LIGHT_MODEL_TWO_SIDE, 1.0) }, GL_LIGHT_MODEL_TWO_SIDE),
    row("glLightModelfv", || unsafe { gl::glLightModelfv(GL_LIGHT_MODEL_AMBIENT, VEC4.as_ptr()) }, GL_LIGHT_MODEL_AMBIENT),
    row("glColorMaterial", || unsafe { gl::glColorMaterial(GL_FRONT, GL_DIFFUSE) }, GL_COLOR_MATERIAL_FACE),
    row("glPointSize", || unsafe { gl::glPointSize(2.0) }, GL_POINT_SIZE),
    row("glPointParameterf", || unsafe { gl::glPointParameterf(GL_POINT_SIZE_MIN, 2.0) }, GL_POINT_SIZE_MIN),
    row("glLineWidth", || unsafe { gl::glLineWidth(2.0) }, GL_LINE_WIDTH),
    row("glLineStipple", || unsafe { gl::glLineStipple(2, 0xAAAA) }, GL_LINE_STIPPLE_PATTERN),
    row("glCullFace", || unsafe { gl::glCullFace(GL_FRONT) }, GL_CULL_FACE_MODE),
    row("glFrontFace", || unsafe { gl::glFrontFace(GL_CW) }, GL_FRONT_FACE),
    row("glPolygonMode", || unsafe { gl::glPolygonMode(GL_FRONT_AND_BACK, GL_LINE) }, GL_POLYGON_MODE),
    row("glPolygonOffset", || unsafe { gl::glPolygonOffset(1.0, 1.0) }, GL_POLYGON_OFFSET_FACTOR),
    row("glPolygonStipple", || unsafe { gl::glPolygonStipple([0x55u8; 128].as_ptr()) }, 0),
    row("glSampleCoverage", || unsafe { gl::glSampleCoverage(0.5, 1) }, GL_SAMPLE_COVERAGE_VALUE),
    row("glScissor", || unsafe { gl::glScissor(1, 2, 3, 4) }, GL_SCISSOR_BOX),
    row("glAlphaFunc", || unsafe { gl::glAlphaFunc(GL_GREATER, 0.5) }, GL_ALPHA_TEST_FUNC),
    row("glStencilFunc", || unsafe { gl::glStencilFunc(GL_NEVER, 1, 1) }, GL_STENCIL_FUNC),
    row("glStencilOp", || unsafe { gl::glStencilOp(GL_ZERO, GL_ZERO, GL_ZERO) }, GL_STENCIL_FAIL),
    row("glDepthFunc", || unsafe { gl::glDepthFunc(GL_GREATER) }, GL_DEPTH_FUNC),
    row("glBlendFunc", || unsafe { gl::glBlendFunc(GL_SRC_ALPHA, GL_ONE) }, GL_BLEND_SRC),
    row("glBlendFuncSeparate", || unsafe { gl::glBlendFuncSeparate(GL_ZERO, GL_ONE, GL_ONE, GL_ONE) }, GL_BLEND_SRC_RGB),
    row("glBlendColor", || unsafe { gl::glBlendColor(1.0, 1.0, 1.0, 1.0) }, GL_BLEND_COLOR),
    row("glBlendEquation", || unsafe { gl::glBlendEquation(GL_FUNC_SUBTRACT) }, GL_BLEND_EQUATION),
    row("glLogicOp", || unsafe { gl::glLogicOp(GL_XOR) }, GL_LOGIC_OP_MODE),
    row("glDrawBuffer", || unsafe { gl::glDrawBuffer(GL_FRONT) }, GL_DRAW_BUFFER),
    row("glReadBuffer", || unsafe { gl::glReadBuffer(GL_FRONT) }, GL_READ_BUFFER),
    row("glIndexMask", || unsafe { gl::glIndexMask(0) }, GL_INDEX_WRITEMASK),
    row("glColorMask", || unsafe { gl::glColorMask(0, 0, 0, 0) }, GL_COLOR_WRITEMASK),
    row("glDepthMask", || unsafe { gl::glDepthMask(0) }, GL_DEPTH_WRITEMASK),
    row("glStencilMask", || unsafe { gl::glStencilMask(0) }, GL_STENCIL_WRITEMASK),
    row("glClearColor", || unsafe { gl::glClearColor(1.0, 1.0, 1.0, 1.0) }, GL_COLOR_CLEAR_VALUE),
    row("glClearIndex", || unsafe { gl::glClearIndex(3.0) }, GL_INDEX_CLEAR_VALUE),
    row("glClearDepth", || unsafe { gl::glClearDepth(0.5) }, GL_DEPTH_CLEAR_VALUE),
    row("glClearStencil", || unsafe { gl::glClearStencil(1) }, GL_STENCIL_CLEAR_VALUE),
    row("glClearAccum", || unsafe { gl::glClearAccum(1.0, 1.0, 1.0, 1.0) }, GL_ACCUM_CLEAR_VALUE),
    row("glClear", || unsafe { gl::glClear(GL_COLOR_BUFFER_BIT) }, 0),
    row("glHint", || unsafe { gl::glHint(GL_FOG_HINT, GL_NICEST) }, GL_FOG_HINT),
    row("glMap1f", || unsafe { gl::glMap1f(GL_MAP1_VERTEX_3, 0.0, 1.0, 3, 2, POINTS.as_ptr()) }, 0),
    row("glMapGrid1f", || unsafe { gl::glMapGrid1f(4, 0.0, 2.0) }, GL_MAP1_GRID_SEGMENTS),
    row("glMapGrid2f", || unsafe { gl::glMapGrid2f(4, 0.0, 2.0, 5, 0.0, 2.0) }, GL_MAP2_GRID_SEGMENTS),
    row("glEvalMesh1", || unsafe { gl::glEvalMesh1(GL_POINT, 0, 1) }, 0),
    row("glPushAttrib", || unsafe { gl::glPushAttrib(GL_ALL_ATTRIB_BITS) }, GL_ATTRIB_STACK_DEPTH),
    row("glListBase", || unsafe { gl::glListBase(5) }, GL_LIST_BASE),
    row("glInitNames", || unsafe { gl::glInitNames() }, GL_NAME_STACK_DEPTH),
    row("glPassThrough", || unsafe { gl::glPassThrough(1.0) }, 0),
    row("glBeginQuery", || unsafe { gl::glBeginQuery(GL_SAMPLES_PASSED, 1) }, 0),
    row("glActiveTexture", || unsafe { gl::glActiveTexture(GL_TEXTURE1) }, GL_ACTIVE_TEXTURE),
    immediate("glNewList", || unsafe { gl::glNewList(1, GL_COMPILE) }, GL_LIST_INDEX),
    immediate("glDeleteLists", || unsafe { gl::glDeleteLists(1, 1) }, 0),
    immediate("glRenderMode", || unsafe { gl::glRenderMode(GL_SELECT); }, GL_RENDER_MODE),
    immediate("glSelectBuffer", || unsafe { gl::glSelectBuffer(64, (&raw mut SINK).cast()) }, 0),
    immediate(
        "glFeedbackBuffer",
        || unsafe { gl::glFeedbackBuffer(64, FEEDBACK_3D, (&raw mut SINK).cast()) },
        0,
    ),
    immediate("glGenQueries", || unsafe { gl::glGenQueries(1, (&raw mut SINK).cast()) }, 0),
    immediate("glFlush", || unsafe { gl::glFlush() }, 0),
    immediate("glFinish", || unsafe { gl::glFinish() }, 0),
];

/// Commands of the `vertex` branch (arrays, buffer objects, rectangles) not allowed inside
/// Begin/End (§2.6.3; `glDrawArrays` and friends also by §2.8).
const FORBIDDEN_VERTEX: &[Row] = &[
    row("glRectf", || unsafe { gl::glRectf(0.0, 0.0, 1.0, 1.0) }, 0),
    row("glDrawArrays", || unsafe { gl::glDrawArrays(GL_POINTS, 0, 0) }, 0),
    row("glDrawElements", || unsafe { gl::glDrawElements(GL_POINTS, 0, GL_UNSIGNED_INT, [0u32].as_ptr().cast()) }, 0),
    immediate("glBindBuffer", || unsafe { gl::glBindBuffer(GL_ARRAY_BUFFER, 1) }, GL_ARRAY_BUFFER_BINDING),
    immediate("glGenBuffers", || unsafe { gl::glGenBuffers(1, (&raw mut SINK).cast()) }, 0),
];

/// Commands of the `texture` branch (textures, pixels, raster position) not allowed inside
/// Begin/End.
const FORBIDDEN_TEXTURE: &[Row] = &[
    row("glRasterPos3f", || unsafe { gl::glRasterPos3f(0.5, 0.5, 0.0) }, GL_CURRENT_RASTER_POSITION),
    row("glWindowPos2f", || unsafe { gl::glWindowPos2f(5.0, 6.0) }, GL_CURRENT_RASTER_POSITION),
    row("glPixelTransferf", || unsafe { gl::glPixelTransferf(GL_RED_SCALE, 2.0) }, GL_RED_SCALE),
    row("glPixelZoom", || unsafe { gl::glPixelZoom(2.0, 2.0) }, GL_ZOOM_X),
    row("glBindTexture", || unsafe { gl::glBindTexture(GL_TEXTURE_2D, 1) }, GL_TEXTURE_BINDING_2D),
    row("glTexEnvi", || unsafe { gl::glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_DECAL as i32) }, 0),
    row("glTexGeni", || unsafe { gl::glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR as i32) }, 0),
    row("glTexParameteri", || unsafe { gl::glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP as i32) }, 0),
    row("glBitmap", || unsafe { gl::glBitmap(0, 0, 0.0, 0.0, 1.0, 1.0, std::ptr::null()) }, GL_CURRENT_RASTER_POSITION),
    immediate("glGenTextures", || unsafe { gl::glGenTextures(1, (&raw mut SINK).cast()) }, 0),
];

/// Commands allowed between Begin and End that are on main.
const ALLOWED: &[(&str, unsafe fn())] = &[
    ("glMaterialf", || unsafe { gl::glMaterialf(GL_FRONT, GL_SHININESS, 10.0) }),
    ("glMaterialfv", || unsafe { gl::glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, VEC4.as_ptr()) }),
    ("glEvalCoord1f", || unsafe { gl::glEvalCoord1f(0.5) }),
    ("glEvalCoord2f", || unsafe { gl::glEvalCoord2f(0.5, 0.5) }),
    ("glEvalPoint1", || unsafe { gl::glEvalPoint1(0) }),
    ("glEvalPoint2", || unsafe { gl::glEvalPoint2(0, 0) }),
    ("glCallList", || unsafe { gl::glCallList(EMPTY_LIST) }),
    ("glCallLists", || unsafe { gl::glCallLists(1, GL_UNSIGNED_INT, [EMPTY_LIST].as_ptr().cast::<c_void>()) }),
];

/// Allowed commands of the `vertex` branch (main has placeholders for the first four).
const ALLOWED_VERTEX: &[(&str, unsafe fn())] = &[
    ("glVertex3f", || unsafe { gl::glVertex3f(0.0, 0.0, 0.0) }),
    ("glColor4f", || unsafe { gl::glColor4f(1.0, 0.0, 0.0, 1.0) }),
    ("glNormal3f", || unsafe { gl::glNormal3f(0.0, 1.0, 0.0) }),
    ("glTexCoord2f", || unsafe { gl::glTexCoord2f(0.5, 0.5) }),
    ("glMultiTexCoord2f", || unsafe { gl::glMultiTexCoord2f(GL_TEXTURE1, 0.5, 0.5) }),
    ("glEdgeFlag", || unsafe { gl::glEdgeFlag(0) }),
    ("glArrayElement", || unsafe { gl::glArrayElement(0) }),
    ("glFogCoordf", || unsafe { gl::glFogCoordf(1.0) }),
    ("glSecondaryColor3f", || unsafe { gl::glSecondaryColor3f(0.0, 1.0, 0.0) }),
    ("glIndexf", || unsafe { gl::glIndexf(2.0) }),
];

/// A display list made empty by `prepare` (calling it inside Begin/End is allowed).
const EMPTY_LIST: u32 = 900;
/// The list each row's command is compiled into.
const ROW_LIST: u32 = 901;

/// Makes a context current and defines the lists and evaluator map the rows rely on.
fn prepare() {
    make_current();
    unsafe {
        gl::glNewList(EMPTY_LIST, GL_COMPILE);
        gl::glEndList();
        gl::glMap1f(GL_MAP1_VERTEX_3, 0.0, 1.0, 3, 2, POINTS.as_ptr());
        gl::glMap2f(GL_MAP2_VERTEX_3, 0.0, 1.0, 3, 2, 0.0, 1.0, 6, 1, POINTS.as_ptr());
    }
    assert_eq!(error(), GL_NO_ERROR, "setting up");
}

/// The probe's value (the values `glGetFloatv` wrote), or `None` where it is 0 (no probe).
fn probe(pname: GLenum) -> Option<Vec<f32>> {
    (pname != 0).then(|| get_f(pname).into_iter().take_while(|v| !v.is_nan()).collect())
}

/// Runs `execute` (a command or a list call) between `glBegin(GL_POINTS)` and `glEnd` and
/// checks the error it leaves (`INVALID_OPERATION` when `forbidden`, else none) and that the
/// probe did not change; appends one line per problem to `failures`.
fn check_inside(what: &str, probe_pname: GLenum, forbidden: bool, execute: &dyn Fn(), failures: &mut Vec<String>) {
    let before = probe(probe_pname);
    let probe_error = error();
    if probe_error != GL_NO_ERROR {
        failures.push(format!("{what}: probe {} raised {}", name(probe_pname), name(probe_error)));
    }
    unsafe { gl::glBegin(GL_POINTS) };
    execute();
    unsafe { gl::glEnd() };
    let got = error();
    let want = if forbidden { GL_INVALID_OPERATION } else { GL_NO_ERROR };
    if got != want {
        failures.push(format!("{what}: raised {}, spec {}", name(got), name(want)));
    }
    let after = probe(probe_pname);
    if before != after {
        failures.push(format!("{what}: {} changed from {before:?} to {after:?}", name(probe_pname)));
    }
    error();
}

/// Every forbidden row, called directly inside Begin/End.
fn forbidden_direct(rows: &[Row]) -> Vec<String> {
    let mut failures = Vec::new();
    for r in rows {
        check_inside(r.name, r.probe, true, &|| unsafe { (r.call)() }, &mut failures);
    }
    failures
}

/// Every compiled forbidden row, compiled into a list (no error) and the list called inside
/// Begin/End (the error, state unchanged).
fn forbidden_from_list(rows: &[Row]) -> Vec<String> {
    let mut failures = Vec::new();
    for r in rows.iter().filter(|r| r.compiled) {
        let before = probe(r.probe);
        error();
        unsafe {
            gl::glNewList(ROW_LIST, GL_COMPILE);
            (r.call)();
            gl::glEndList();
        }
        let compile = error();
        if compile != GL_NO_ERROR {
            failures.push(format!("{}: compiling raised {}", r.name, name(compile)));
        }
        if probe(r.probe) != before {
            failures.push(format!("{}: compiling changed {}", r.name, name(r.probe)));
        }
        let what = format!("{} from a list", r.name);
        check_inside(&what, r.probe, true, &|| unsafe { gl::glCallList(ROW_LIST) }, &mut failures);
    }
    failures
}

/// Every allowed command, directly and compiled into a list, inside Begin/End.
fn allowed(rows: &[(&str, unsafe fn())]) -> Vec<String> {
    let mut failures = Vec::new();
    for &(what, call) in rows {
        check_inside(what, 0, false, &|| unsafe { call() }, &mut failures);
        unsafe {
            gl::glNewList(ROW_LIST, GL_COMPILE);
            call();
            gl::glEndList();
        }
        let compile = error();
        if compile != GL_NO_ERROR {
            failures.push(format!("{what}: compiling raised {}", name(compile)));
        }
        let from_list = format!("{what} from a list");
        check_inside(&from_list, 0, false, &|| unsafe { gl::glCallList(ROW_LIST) }, &mut failures);
    }
    failures
}

#[test]
fn forbidden_commands_raise_invalid_operation() {
    prepare();
    assert_none("forbidden inside Begin/End", &forbidden_direct(FORBIDDEN));
}

#[test]
fn forbidden_commands_from_a_list() {
    prepare();
    assert_none("forbidden inside Begin/End, from a display list", &forbidden_from_list(FORBIDDEN));
}

#[test]
fn allowed_commands_raise_nothing() {
    prepare();
    assert_none("allowed inside Begin/End", &allowed(ALLOWED));
}

#[test]
fn forbidden_and_allowed_vertex_module() {
    prepare();
    let mut failures = forbidden_direct(FORBIDDEN_VERTEX);
    failures.extend(forbidden_from_list(FORBIDDEN_VERTEX));
    failures.extend(allowed(ALLOWED_VERTEX));
    assert_none("vertex branch commands inside Begin/End", &failures);
}

#[test]
fn forbidden_texture_module() {
    prepare();
    let mut failures = forbidden_direct(FORBIDDEN_TEXTURE);
    failures.extend(forbidden_from_list(FORBIDDEN_TEXTURE));
    assert_none("texture branch commands inside Begin/End", &failures);
}

/// The queries are commands too: inside Begin/End they raise `INVALID_OPERATION` and return
/// nothing (§2.6.3, §2.5: the command is ignored).
#[test]
fn queries_inside_begin_end() {
    prepare();
    let mut failures = Vec::new();
    unsafe { gl::glEnable(GL_FOG) };
    unsafe { gl::glBegin(GL_POINTS) };
    let v = get_i(GL_FOG_MODE);
    let f = get_f(GL_FOG_DENSITY);
    let b = get_b(GL_FOG);
    let enabled = is_enabled(GL_FOG);
    // Safety: plain calls.
    let is_list = unsafe { gl::glIsList(EMPTY_LIST) };
    let new_lists = unsafe { gl::glGenLists(1) };
    unsafe { gl::glEnd() };
    if v[0] != i32::MIN || !f[0].is_nan() || b[0].is_some() {
        failures.push(format!("glGet* wrote {}, {}, {:?}", v[0], f[0], b[0]));
    }
    if enabled || is_list != 0 || new_lists != 0 {
        failures.push(format!("glIsEnabled = {enabled}, glIsList = {is_list}, glGenLists = {new_lists}: spec 0"));
    }
    let err = error();
    if err != GL_INVALID_OPERATION {
        failures.push(format!("error after the queries: {}, spec GL_INVALID_OPERATION", name(err)));
    }
    assert_none("queries inside Begin/End", &failures);
}

/// `glGetError` inside Begin/End is itself an error (§2.6.3 allows only the listed commands;
/// §2.5: a command that raises an error is ignored): it returns 0 and latches
/// `INVALID_OPERATION`, which the next `glGetError` after `glEnd` returns. An error latched
/// before `glBegin` stays latched (the ignored `glGetError` does not clear it).
#[test]
fn get_error_inside_begin_end() {
    prepare();
    unsafe { gl::glBegin(GL_POINTS) };
    let inside = error();
    unsafe { gl::glEnd() };
    assert_eq!(name(inside), name(GL_NO_ERROR), "glGetError inside Begin/End returned an error code");
    assert_eq!(name(error()), name(GL_INVALID_OPERATION), "glGetError inside Begin/End latched no error");
    assert_eq!(error(), GL_NO_ERROR, "the latch was not cleared");

    unsafe { gl::glShadeModel(GL_POINTS) };
    unsafe { gl::glBegin(GL_POINTS) };
    let inside = error();
    unsafe { gl::glEnd() };
    assert_eq!(inside, GL_NO_ERROR, "glGetError inside Begin/End returned the latched error");
    assert_eq!(name(error()), name(GL_INVALID_ENUM), "the error latched before glBegin was lost");
}

/// `glEnd` without `glBegin` and `glBegin` inside `glBegin` raise `INVALID_OPERATION`
/// (§2.6.3); an invalid primitive mode raises `INVALID_ENUM` (§2.6.1).
#[test]
fn unbalanced_begin_end() {
    prepare();
    let mut failures = Vec::new();
    let mut expect = |what: &str, want: GLenum| {
        let got = error();
        if got != want {
            failures.push(format!("{what}: {}, spec {}", name(got), name(want)));
        }
    };
    unsafe { gl::glEnd() };
    expect("glEnd without glBegin", GL_INVALID_OPERATION);
    unsafe { gl::glBegin(GL_TRIANGLES) };
    unsafe { gl::glBegin(GL_POINTS) };
    unsafe { gl::glEnd() };
    expect("glBegin inside glBegin", GL_INVALID_OPERATION);
    unsafe { gl::glEnd() };
    expect("the glEnd after the ignored nested glBegin", GL_INVALID_OPERATION);
    unsafe { gl::glBegin(GL_POLYGON + 1) };
    expect("glBegin(GL_POLYGON + 1)", GL_INVALID_ENUM);
    unsafe { gl::glEnd() };
    expect("glEnd after the rejected glBegin", GL_INVALID_OPERATION);
    assert_none("Begin/End pairing", &failures);
}
