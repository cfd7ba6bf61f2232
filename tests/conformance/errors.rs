//! Error rules of the OpenGL 1.5 specification (§2.5 and the "Errors" paragraphs of chapters
//! 2–6) for the commands on main, through the C exports: one table of
//! `(call, expected error, state the ignored command must leave alone)`, each row in a fresh
//! context; and every stack overflowing and underflowing (modelview, projection, texture,
//! server attribute, name stack; the client attribute stack in `*_vertex_module`).

use crate::common;

use common::*;

/// One erroneous call.
struct Row {
    /// What is called, for messages.
    what: &'static str,
    /// Sets up what the call needs (without error) and makes the call.
    call: unsafe fn(),
    /// The error the call must raise (§2.5: the first error is latched).
    want: GLenum,
    /// State the offending command must not change (§2.5: it is ignored), or 0.
    probe: GLenum,
}

/// A row.
const fn row(what: &'static str, call: unsafe fn(), want: GLenum, probe: GLenum) -> Row {
    Row { what, call, want, probe }
}

/// `GL_3D` (gl_generator drops enums whose names start with a digit).
const FEEDBACK_3D: GLenum = 0x0601;
/// A one-dimensional evaluator map's control points.
const POINTS: [f32; 6] = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
/// Client memory for the selection buffer rows.
static mut SELECT: [u32; 64] = [0; 64];
/// Client memory for the feedback buffer rows.
static mut FEEDBACK: [f32; 64] = [0.0; 64];

/// Enters selection mode (no error).
unsafe fn select_mode() {
    unsafe {
        gl::glSelectBuffer(64, (&raw mut SELECT).cast());
        gl::glRenderMode(GL_SELECT);
    }
}

/// Invalid enums (§2.5: `INVALID_ENUM` for an out-of-range enumerated argument).
const INVALID_ENUMS: &[Row] = &[
    row("glBegin(GL_POLYGON + 1)", || unsafe { gl::glBegin(GL_POLYGON + 1) }, GL_INVALID_ENUM, 0),
    row("glMatrixMode(GL_TEXTURE_2D)", || unsafe { gl::glMatrixMode(GL_TEXTURE_2D) }, GL_INVALID_ENUM, GL_MATRIX_MODE),
    row("glEnable(GL_TRIANGLES)", || unsafe { gl::glEnable(GL_TRIANGLES) }, GL_INVALID_ENUM, 0),
    row("glDisable(GL_TRIANGLES)", || unsafe { gl::glDisable(GL_TRIANGLES) }, GL_INVALID_ENUM, 0),
    row("glIsEnabled(GL_TRIANGLES)", || unsafe { gl::glIsEnabled(GL_TRIANGLES); }, GL_INVALID_ENUM, 0),
    row("glGetIntegerv(GL_TRIANGLES)", || { get_i(GL_TRIANGLES); }, GL_INVALID_ENUM, 0),
    row("glShadeModel(GL_POINTS)", || unsafe { gl::glShadeModel(GL_POINTS) }, GL_INVALID_ENUM, GL_SHADE_MODEL),
    row("glFrontFace(GL_FRONT)", || unsafe { gl::glFrontFace(GL_FRONT) }, GL_INVALID_ENUM, GL_FRONT_FACE),
    row("glCullFace(GL_CW)", || unsafe { gl::glCullFace(GL_CW) }, GL_INVALID_ENUM, GL_CULL_FACE_MODE),
    row("glPolygonMode(face GL_CW)", || unsafe { gl::glPolygonMode(GL_CW, GL_LINE) }, GL_INVALID_ENUM, GL_POLYGON_MODE),
    row("glPolygonMode(mode GL_FRONT)", || unsafe { gl::glPolygonMode(GL_FRONT, GL_FRONT) }, GL_INVALID_ENUM, GL_POLYGON_MODE),
    row("glDepthFunc(GL_ZERO)", || unsafe { gl::glDepthFunc(GL_ZERO) }, GL_INVALID_ENUM, GL_DEPTH_FUNC),
    row("glAlphaFunc(GL_ZERO)", || unsafe { gl::glAlphaFunc(GL_ZERO, 0.5) }, GL_INVALID_ENUM, GL_ALPHA_TEST_REF),
    row("glStencilFunc(GL_KEEP)", || unsafe { gl::glStencilFunc(GL_KEEP, 1, 1) }, GL_INVALID_ENUM, GL_STENCIL_REF),
    row("glStencilOp(GL_NEVER)", || unsafe { gl::glStencilOp(GL_KEEP, GL_NEVER, GL_KEEP) }, GL_INVALID_ENUM, GL_STENCIL_PASS_DEPTH_FAIL),
    row("glBlendFunc(GL_NEVER, GL_ONE)", || unsafe { gl::glBlendFunc(GL_NEVER, GL_ONE) }, GL_INVALID_ENUM, GL_BLEND_DST),
    row(
        "glBlendFunc(dst GL_SRC_ALPHA_SATURATE)",
        || unsafe { gl::glBlendFunc(GL_ONE, GL_SRC_ALPHA_SATURATE) },
        GL_INVALID_ENUM,
        GL_BLEND_DST,
    ),
    row(
        "glBlendFuncSeparate(GL_NEVER ...)",
        || unsafe { gl::glBlendFuncSeparate(GL_ONE, GL_ONE, GL_NEVER, GL_ONE) },
        GL_INVALID_ENUM,
        GL_BLEND_SRC_RGB,
    ),
    row("glBlendEquation(GL_ONE)", || unsafe { gl::glBlendEquation(GL_ONE) }, GL_INVALID_ENUM, GL_BLEND_EQUATION),
    row("glLogicOp(GL_ONE)", || unsafe { gl::glLogicOp(GL_ONE) }, GL_INVALID_ENUM, GL_LOGIC_OP_MODE),
    row("glFogi(GL_FOG_MODE, GL_NEVER)", || unsafe { gl::glFogi(GL_FOG_MODE, GL_NEVER as i32) }, GL_INVALID_ENUM, GL_FOG_MODE),
    row("glFogi(GL_FOG_COORD_SRC, GL_NEVER)", || unsafe { gl::glFogi(GL_FOG_COORD_SRC, GL_NEVER as i32) }, GL_INVALID_ENUM, GL_FOG_COORD_SRC),
    row("glFogf(GL_SHADE_MODEL)", || unsafe { gl::glFogf(GL_SHADE_MODEL, 1.0) }, GL_INVALID_ENUM, 0),
    row("glLightf(GL_LIGHT0 + 8)", || unsafe { gl::glLightf(GL_LIGHT0 + 8, GL_SPOT_EXPONENT, 1.0) }, GL_INVALID_ENUM, 0),
    // glLightf/glMaterialf with a vector name (GL_AMBIENT) are not errors in glrt: like Mesa
    // they take (x, 0, 0, 0), which piglit's gl-1.0-beginend-coverage expects.
    row(
        "glLightModeli(COLOR_CONTROL, GL_ONE)",
        || unsafe { gl::glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_ONE as i32) },
        GL_INVALID_ENUM,
        GL_LIGHT_MODEL_COLOR_CONTROL,
    ),
    row("glMaterialf(face GL_CW)", || unsafe { gl::glMaterialf(GL_CW, GL_SHININESS, 1.0) }, GL_INVALID_ENUM, 0),
    row("glColorMaterial(face GL_CW)", || unsafe { gl::glColorMaterial(GL_CW, GL_AMBIENT) }, GL_INVALID_ENUM, GL_COLOR_MATERIAL_FACE),
    row(
        "glColorMaterial(GL_SHININESS)",
        || unsafe { gl::glColorMaterial(GL_FRONT, GL_SHININESS) },
        GL_INVALID_ENUM,
        GL_COLOR_MATERIAL_PARAMETER,
    ),
    row("glHint(GL_FOG_HINT, GL_FOG)", || unsafe { gl::glHint(GL_FOG_HINT, GL_FOG) }, GL_INVALID_ENUM, GL_FOG_HINT),
    row("glHint(GL_FOG)", || unsafe { gl::glHint(GL_FOG, GL_NICEST) }, GL_INVALID_ENUM, 0),
    row("glClipPlane(GL_CLIP_PLANE0 + 6)", || unsafe { gl::glClipPlane(GL_CLIP_PLANE0 + 6, [0.0f64; 4].as_ptr()) }, GL_INVALID_ENUM, 0),
    row("glDrawBuffer(GL_TEXTURE_2D)", || unsafe { gl::glDrawBuffer(GL_TEXTURE_2D) }, GL_INVALID_ENUM, GL_DRAW_BUFFER),
    row("glReadBuffer(GL_FRONT_AND_BACK)", || unsafe { gl::glReadBuffer(GL_FRONT_AND_BACK) }, GL_INVALID_ENUM, GL_READ_BUFFER),
    row("glReadBuffer(GL_NONE)", || unsafe { gl::glReadBuffer(GL_NONE) }, GL_INVALID_ENUM, GL_READ_BUFFER),
    row("glRenderMode(GL_TRIANGLES)", || unsafe { gl::glRenderMode(GL_TRIANGLES); }, GL_INVALID_ENUM, GL_RENDER_MODE),
    row(
        "glFeedbackBuffer(type GL_FLOAT)",
        || unsafe { gl::glFeedbackBuffer(64, GL_FLOAT, (&raw mut FEEDBACK).cast()) },
        GL_INVALID_ENUM,
        0,
    ),
    row("glMap1f(GL_MAP2_VERTEX_3)", || unsafe { gl::glMap1f(GL_MAP2_VERTEX_3, 0.0, 1.0, 3, 2, POINTS.as_ptr()) }, GL_INVALID_ENUM, 0),
    row("glEvalMesh1(GL_FILL)", || unsafe { gl::glEvalMesh1(GL_FILL, 0, 1) }, GL_INVALID_ENUM, 0),
    row("glEvalMesh2(GL_POLYGON)", || unsafe { gl::glEvalMesh2(GL_POLYGON, 0, 1, 0, 1) }, GL_INVALID_ENUM, 0),
    row("glPointParameterf(GL_POINT_SIZE)", || unsafe { gl::glPointParameterf(GL_POINT_SIZE, 1.0) }, GL_INVALID_ENUM, 0),
    row("glBeginQuery(GL_TEXTURE_2D)", || unsafe { gl::glBeginQuery(GL_TEXTURE_2D, 1) }, GL_INVALID_ENUM, 0),
    row(
        "glActiveTexture(past MAX_TEXTURE_UNITS)",
        || unsafe { gl::glActiveTexture(GL_TEXTURE0 + get_i(GL_MAX_TEXTURE_UNITS)[0] as u32) },
        GL_INVALID_ENUM,
        GL_ACTIVE_TEXTURE,
    ),
    row(
        "glClientActiveTexture(past MAX_TEXTURE_UNITS)",
        || unsafe { gl::glClientActiveTexture(GL_TEXTURE0 + get_i(GL_MAX_TEXTURE_UNITS)[0] as u32) },
        GL_INVALID_ENUM,
        GL_CLIENT_ACTIVE_TEXTURE,
    ),
];

/// Negative sizes and out-of-range values (§2.5: `INVALID_VALUE`).
const INVALID_VALUES: &[Row] = &[
    row("glViewport(width -1)", || unsafe { gl::glViewport(0, 0, -1, 1) }, GL_INVALID_VALUE, GL_VIEWPORT),
    row("glViewport(height -1)", || unsafe { gl::glViewport(0, 0, 1, -1) }, GL_INVALID_VALUE, GL_VIEWPORT),
    row("glScissor(width -1)", || unsafe { gl::glScissor(0, 0, -1, 1) }, GL_INVALID_VALUE, GL_SCISSOR_BOX),
    row("glLineWidth(0)", || unsafe { gl::glLineWidth(0.0) }, GL_INVALID_VALUE, GL_LINE_WIDTH),
    row("glLineWidth(-1)", || unsafe { gl::glLineWidth(-1.0) }, GL_INVALID_VALUE, GL_LINE_WIDTH),
    row("glPointSize(0)", || unsafe { gl::glPointSize(0.0) }, GL_INVALID_VALUE, GL_POINT_SIZE),
    row("glPointSize(-1)", || unsafe { gl::glPointSize(-1.0) }, GL_INVALID_VALUE, GL_POINT_SIZE),
    row("glPointParameterf(MIN, -1)", || unsafe { gl::glPointParameterf(GL_POINT_SIZE_MIN, -1.0) }, GL_INVALID_VALUE, GL_POINT_SIZE_MIN),
    row(
        "glPointParameterf(FADE_THRESHOLD, -1)",
        || unsafe { gl::glPointParameterf(GL_POINT_FADE_THRESHOLD_SIZE, -1.0) },
        GL_INVALID_VALUE,
        GL_POINT_FADE_THRESHOLD_SIZE,
    ),
    row("glLightf(SPOT_CUTOFF, 91)", || unsafe { gl::glLightf(GL_LIGHT0, GL_SPOT_CUTOFF, 91.0) }, GL_INVALID_VALUE, 0),
    row("glLightf(SPOT_CUTOFF, -1)", || unsafe { gl::glLightf(GL_LIGHT0, GL_SPOT_CUTOFF, -1.0) }, GL_INVALID_VALUE, 0),
    row("glLightf(SPOT_CUTOFF, 179)", || unsafe { gl::glLightf(GL_LIGHT0, GL_SPOT_CUTOFF, 179.0) }, GL_INVALID_VALUE, 0),
    row("glLightf(SPOT_EXPONENT, 129)", || unsafe { gl::glLightf(GL_LIGHT0, GL_SPOT_EXPONENT, 129.0) }, GL_INVALID_VALUE, 0),
    row("glLightf(SPOT_EXPONENT, -1)", || unsafe { gl::glLightf(GL_LIGHT0, GL_SPOT_EXPONENT, -1.0) }, GL_INVALID_VALUE, 0),
    row(
        "glLightf(CONSTANT_ATTENUATION, -1)",
        || unsafe { gl::glLightf(GL_LIGHT0, GL_CONSTANT_ATTENUATION, -1.0) },
        GL_INVALID_VALUE,
        0,
    ),
    row(
        "glLightf(QUADRATIC_ATTENUATION, -1)",
        || unsafe { gl::glLightf(GL_LIGHT0, GL_QUADRATIC_ATTENUATION, -1.0) },
        GL_INVALID_VALUE,
        0,
    ),
    row("glMaterialf(SHININESS, 129)", || unsafe { gl::glMaterialf(GL_FRONT, GL_SHININESS, 129.0) }, GL_INVALID_VALUE, 0),
    row("glMaterialf(SHININESS, -1)", || unsafe { gl::glMaterialf(GL_FRONT, GL_SHININESS, -1.0) }, GL_INVALID_VALUE, 0),
    row("glFogf(DENSITY, -1)", || unsafe { gl::glFogf(GL_FOG_DENSITY, -1.0) }, GL_INVALID_VALUE, GL_FOG_DENSITY),
    row("glFrustum(near 0)", || unsafe { gl::glFrustum(-1.0, 1.0, -1.0, 1.0, 0.0, 1.0) }, GL_INVALID_VALUE, GL_MODELVIEW_MATRIX),
    row("glFrustum(far -1)", || unsafe { gl::glFrustum(-1.0, 1.0, -1.0, 1.0, 1.0, -1.0) }, GL_INVALID_VALUE, GL_MODELVIEW_MATRIX),
    row("glFrustum(left == right)", || unsafe { gl::glFrustum(1.0, 1.0, -1.0, 1.0, 1.0, 2.0) }, GL_INVALID_VALUE, GL_MODELVIEW_MATRIX),
    row("glFrustum(near == far)", || unsafe { gl::glFrustum(-1.0, 1.0, -1.0, 1.0, 1.0, 1.0) }, GL_INVALID_VALUE, GL_MODELVIEW_MATRIX),
    row("glOrtho(bottom == top)", || unsafe { gl::glOrtho(-1.0, 1.0, 1.0, 1.0, 1.0, 2.0) }, GL_INVALID_VALUE, GL_MODELVIEW_MATRIX),
    row("glOrtho(near == far)", || unsafe { gl::glOrtho(-1.0, 1.0, -1.0, 1.0, 1.0, 1.0) }, GL_INVALID_VALUE, GL_MODELVIEW_MATRIX),
    row("glNewList(0)", || unsafe { gl::glNewList(0, GL_COMPILE) }, GL_INVALID_VALUE, GL_LIST_INDEX),
    row("glGenLists(-1)", || unsafe { gl::glGenLists(-1); }, GL_INVALID_VALUE, 0),
    row("glDeleteLists(range -1)", || unsafe { gl::glDeleteLists(1, -1) }, GL_INVALID_VALUE, 0),
    row("glCallLists(n -1)", || unsafe { gl::glCallLists(-1, GL_UNSIGNED_BYTE, [0u8].as_ptr().cast()) }, GL_INVALID_VALUE, 0),
    row("glSelectBuffer(-1)", || unsafe { gl::glSelectBuffer(-1, (&raw mut SELECT).cast()) }, GL_INVALID_VALUE, 0),
    row(
        "glFeedbackBuffer(-1)",
        || unsafe { gl::glFeedbackBuffer(-1, FEEDBACK_3D, (&raw mut FEEDBACK).cast()) },
        GL_INVALID_VALUE,
        0,
    ),
    row("glMap1f(u1 == u2)", || unsafe { gl::glMap1f(GL_MAP1_VERTEX_3, 1.0, 1.0, 3, 2, POINTS.as_ptr()) }, GL_INVALID_VALUE, 0),
    row("glMap1f(order 0)", || unsafe { gl::glMap1f(GL_MAP1_VERTEX_3, 0.0, 1.0, 3, 0, POINTS.as_ptr()) }, GL_INVALID_VALUE, 0),
    row("glMap1f(stride 2)", || unsafe { gl::glMap1f(GL_MAP1_VERTEX_3, 0.0, 1.0, 2, 2, POINTS.as_ptr()) }, GL_INVALID_VALUE, 0),
    row("glMapGrid1f(n 0)", || unsafe { gl::glMapGrid1f(0, 0.0, 1.0) }, GL_INVALID_VALUE, GL_MAP1_GRID_SEGMENTS),
    row("glMapGrid2f(vn -1)", || unsafe { gl::glMapGrid2f(2, 0.0, 1.0, -1, 0.0, 1.0) }, GL_INVALID_VALUE, GL_MAP2_GRID_SEGMENTS),
    row("glGenQueries(-1)", || unsafe { gl::glGenQueries(-1, (&raw mut SELECT).cast()) }, GL_INVALID_VALUE, 0),
];

/// Queries with bad arguments (§6.1: the `glGet` commands of each object type).
const QUERY_ERRORS: &[Row] = &[
    row("glGetLightfv(GL_LIGHT0 + 8)", || unsafe { gl::glGetLightfv(GL_LIGHT0 + 8, GL_DIFFUSE, [0.0f32; 4].as_mut_ptr()) }, GL_INVALID_ENUM, 0),
    row("glGetLightfv(GL_SHININESS)", || unsafe { gl::glGetLightfv(GL_LIGHT0, GL_SHININESS, [0.0f32; 4].as_mut_ptr()) }, GL_INVALID_ENUM, 0),
    row(
        "glGetMaterialfv(GL_FRONT_AND_BACK)",
        || unsafe { gl::glGetMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, [0.0f32; 4].as_mut_ptr()) },
        GL_INVALID_ENUM,
        0,
    ),
    row(
        "glGetMaterialfv(GL_SPOT_CUTOFF)",
        || unsafe { gl::glGetMaterialfv(GL_FRONT, GL_SPOT_CUTOFF, [0.0f32; 4].as_mut_ptr()) },
        GL_INVALID_ENUM,
        0,
    ),
    row(
        "glGetClipPlane(GL_CLIP_PLANE0 + 6)",
        || unsafe { gl::glGetClipPlane(GL_CLIP_PLANE0 + 6, [0.0f64; 4].as_mut_ptr()) },
        GL_INVALID_ENUM,
        0,
    ),
    row("glGetMapfv(GL_TEXTURE_2D)", || unsafe { gl::glGetMapfv(GL_TEXTURE_2D, GL_ORDER, [0.0f32; 4].as_mut_ptr()) }, GL_INVALID_ENUM, 0),
    row("glGetMapfv(query GL_FOG)", || unsafe { gl::glGetMapfv(GL_MAP1_VERTEX_3, GL_FOG, [0.0f32; 4].as_mut_ptr()) }, GL_INVALID_ENUM, 0),
    row("glGetString(GL_FOG)", || unsafe { gl::glGetString(GL_FOG); }, GL_INVALID_ENUM, 0),
    row(
        "glGetQueryiv(target GL_TEXTURE_2D)",
        || unsafe { gl::glGetQueryiv(GL_TEXTURE_2D, GL_CURRENT_QUERY, [0i32; 1].as_mut_ptr()) },
        GL_INVALID_ENUM,
        0,
    ),
    row(
        "glGetQueryiv(pname GL_FOG)",
        || unsafe { gl::glGetQueryiv(GL_SAMPLES_PASSED, GL_FOG, [0i32; 1].as_mut_ptr()) },
        GL_INVALID_ENUM,
        0,
    ),
    row(
        "glGetQueryObjectiv(not a query)",
        || unsafe { gl::glGetQueryObjectiv(5, GL_QUERY_RESULT, [0i32; 1].as_mut_ptr()) },
        GL_INVALID_OPERATION,
        0,
    ),
    row(
        "glGetQueryObjectuiv(the active query)",
        || unsafe {
            gl::glBeginQuery(GL_SAMPLES_PASSED, 3);
            gl::glGetQueryObjectuiv(3, GL_QUERY_RESULT_AVAILABLE, [0u32; 1].as_mut_ptr());
        },
        GL_INVALID_OPERATION,
        0,
    ),
    row(
        "glGetQueryObjectiv(pname GL_FOG)",
        || unsafe {
            gl::glBeginQuery(GL_SAMPLES_PASSED, 3);
            gl::glEndQuery(GL_SAMPLES_PASSED);
            gl::glGetQueryObjectiv(3, GL_FOG, [0i32; 1].as_mut_ptr());
        },
        GL_INVALID_ENUM,
        0,
    ),
    row("glDeleteQueries(-1)", || unsafe { gl::glDeleteQueries(-1, [1u32].as_ptr()) }, GL_INVALID_VALUE, 0),
];

/// Operations not allowed in the current state (§2.5: `INVALID_OPERATION`).
const INVALID_OPERATIONS: &[Row] = &[
    row("glEnd without glBegin", || unsafe { gl::glEnd() }, GL_INVALID_OPERATION, 0),
    row("glEndList without glNewList", || unsafe { gl::glEndList() }, GL_INVALID_OPERATION, 0),
    row(
        "glNewList inside glNewList",
        || unsafe {
            gl::glNewList(1, GL_COMPILE);
            gl::glNewList(2, GL_COMPILE);
        },
        GL_INVALID_OPERATION,
        0,
    ),
    row("glDrawBuffer(GL_AUX0) without aux buffers", || unsafe { gl::glDrawBuffer(GL_AUX0) }, GL_INVALID_OPERATION, GL_DRAW_BUFFER),
    row("glReadBuffer(GL_AUX0) without aux buffers", || unsafe { gl::glReadBuffer(GL_AUX0) }, GL_INVALID_OPERATION, GL_READ_BUFFER),
    row("glRenderMode(GL_SELECT) without a buffer", || unsafe { gl::glRenderMode(GL_SELECT); }, GL_INVALID_OPERATION, GL_RENDER_MODE),
    row("glRenderMode(GL_FEEDBACK) without a buffer", || unsafe { gl::glRenderMode(GL_FEEDBACK); }, GL_INVALID_OPERATION, GL_RENDER_MODE),
    row(
        "glSelectBuffer in selection mode",
        || unsafe {
            select_mode();
            gl::glSelectBuffer(64, (&raw mut SELECT).cast());
        },
        GL_INVALID_OPERATION,
        0,
    ),
    row(
        "glFeedbackBuffer in feedback mode",
        || unsafe {
            gl::glFeedbackBuffer(64, FEEDBACK_3D, (&raw mut FEEDBACK).cast());
            gl::glRenderMode(GL_FEEDBACK);
            gl::glFeedbackBuffer(64, FEEDBACK_3D, (&raw mut FEEDBACK).cast());
        },
        GL_INVALID_OPERATION,
        0,
    ),
    row(
        "glLoadName on an empty name stack",
        || unsafe {
            select_mode();
            gl::glLoadName(1);
        },
        GL_INVALID_OPERATION,
        GL_NAME_STACK_DEPTH,
    ),
    row("glBeginQuery(id 0)", || unsafe { gl::glBeginQuery(GL_SAMPLES_PASSED, 0) }, GL_INVALID_OPERATION, 0),
    row("glEndQuery without glBeginQuery", || unsafe { gl::glEndQuery(GL_SAMPLES_PASSED) }, GL_INVALID_OPERATION, 0),
    row(
        "glBeginQuery while one is active",
        || unsafe {
            gl::glBeginQuery(GL_SAMPLES_PASSED, 1);
            gl::glBeginQuery(GL_SAMPLES_PASSED, 2);
        },
        GL_INVALID_OPERATION,
        0,
    ),
];

/// Runs each row in a fresh context; one line per mismatch.
fn check(rows: &[Row]) -> Vec<String> {
    let mut failures = Vec::new();
    for r in rows {
        with_fresh_context(|| {
            let before = (r.probe != 0).then(|| get_f(r.probe));
            unsafe { (r.call)() };
            let got = error();
            if got != r.want {
                failures.push(format!("{}: {}, spec {}", r.what, name(got), name(r.want)));
            }
            let after = (r.probe != 0).then(|| get_f(r.probe));
            let same = match (&before, &after) {
                (Some(b), Some(a)) => b.iter().zip(a).all(|(x, y)| x.to_bits() == y.to_bits()),
                _ => true,
            };
            if !same {
                failures.push(format!("{}: the ignored command changed {}", r.what, name(r.probe)));
            }
        });
    }
    failures
}

#[test]
fn invalid_enums() {
    assert_none("INVALID_ENUM rows", &check(INVALID_ENUMS));
}

#[test]
fn invalid_values() {
    assert_none("INVALID_VALUE rows", &check(INVALID_VALUES));
}

#[test]
fn query_errors() {
    assert_none("query rows", &check(QUERY_ERRORS));
}

/// A clamping row: what is called, the call, the state it sets, the clamped value.
type Clamped = (&'static str, unsafe fn(), GLenum, &'static [f32]);

/// Values the specification clamps instead of rejecting, read back as stored.
const CLAMPED: &[Clamped] = &[
    ("glDepthRange(-1, 2) (§2.11.1)", || unsafe { gl::glDepthRange(-1.0, 2.0) }, GL_DEPTH_RANGE, &[0.0, 1.0]),
    ("glClearColor(-1, 2, .5, 0) (§4.2.3)", || unsafe { gl::glClearColor(-1.0, 2.0, 0.5, 0.0) }, GL_COLOR_CLEAR_VALUE, &[0.0, 1.0, 0.5, 0.0]),
    ("glClearDepth(2) (§4.2.3)", || unsafe { gl::glClearDepth(2.0) }, GL_DEPTH_CLEAR_VALUE, &[1.0]),
    ("glClearAccum(-2, 2, .5, 0) (§4.2.3)", || unsafe { gl::glClearAccum(-2.0, 2.0, 0.5, 0.0) }, GL_ACCUM_CLEAR_VALUE, &[-1.0, 1.0, 0.5, 0.0]),
    ("glAlphaFunc(GL_LESS, 2) (§4.1.4)", || unsafe { gl::glAlphaFunc(GL_LESS, 2.0) }, GL_ALPHA_TEST_REF, &[1.0]),
    ("glBlendColor(2, -1, .5, 0) (§4.1.8)", || unsafe { gl::glBlendColor(2.0, -1.0, 0.5, 0.0) }, GL_BLEND_COLOR, &[1.0, 0.0, 0.5, 0.0]),
    ("glSampleCoverage(2) (§4.1.3)", || unsafe { gl::glSampleCoverage(2.0, 0) }, GL_SAMPLE_COVERAGE_VALUE, &[1.0]),
    ("glFogfv(GL_FOG_COLOR, 2, -1, .5, 0) (§3.10)", || unsafe { gl::glFogfv(GL_FOG_COLOR, [2.0f32, -1.0, 0.5, 0.0].as_ptr()) }, GL_FOG_COLOR, &[1.0, 0.0, 0.5, 0.0]),
    ("glLineStipple(0, p) (§3.4.2)", || unsafe { gl::glLineStipple(0, 0x0F0F) }, GL_LINE_STIPPLE_REPEAT, &[1.0]),
    ("glLineStipple(300, p) (§3.4.2)", || unsafe { gl::glLineStipple(300, 0x0F0F) }, GL_LINE_STIPPLE_REPEAT, &[256.0]),
];

/// Out-of-range values the specification clamps: no error, the clamped value stored.
#[test]
fn out_of_range_values_are_clamped() {
    let mut failures = Vec::new();
    for &(what, call, pname, want) in CLAMPED {
        with_fresh_context(|| {
            unsafe { call() };
            let got = &get_f(pname)[..want.len()];
            if got != want {
                failures.push(format!("{what}: {} = {got:?}, spec {want:?}", name(pname)));
            }
            let err = error();
            if err != GL_NO_ERROR {
                failures.push(format!("{what}: raised {}", name(err)));
            }
        });
    }
    assert_none("clamped values", &failures);
}

#[test]
fn invalid_operations() {
    assert_none("INVALID_OPERATION rows", &check(INVALID_OPERATIONS));
}

/// A stack: how to push and pop, its depth, its limit, and its depth when empty.
struct Stack {
    what: &'static str,
    /// Makes the stack the one `push`/`pop` act on (no error).
    select: unsafe fn(),
    push: unsafe fn(),
    pop: unsafe fn(),
    depth: GLenum,
    max: GLenum,
    /// Depth of the initial stack: 1 for matrix stacks (§2.11.2), 0 for the others.
    initial: i32,
}

/// Fills `stack` to its limit without error, checks one more push is `STACK_OVERFLOW` and
/// leaves the depth, empties it, and checks one more pop is `STACK_UNDERFLOW` (§2.5, §2.11.2,
/// §5.2, §6.1.14).
fn check_stack(s: &Stack, failures: &mut Vec<String>) {
    unsafe { (s.select)() };
    let max = get_i(s.max)[0];
    let mut depth = get_i(s.depth)[0];
    if depth != s.initial {
        failures.push(format!("{}: initial depth {depth}, spec {}", s.what, s.initial));
    }
    while depth < max {
        unsafe { (s.push)() };
        let d = get_i(s.depth)[0];
        if d != depth + 1 {
            failures.push(format!("{}: push at depth {depth} gave depth {d}", s.what));
            return;
        }
        depth = d;
    }
    let filling = error();
    if filling != GL_NO_ERROR {
        failures.push(format!("{}: filling to {max} raised {}", s.what, name(filling)));
    }
    unsafe { (s.push)() };
    let overflow = error();
    if overflow != GL_STACK_OVERFLOW {
        failures.push(format!("{}: push past {max}: {}, spec GL_STACK_OVERFLOW", s.what, name(overflow)));
    }
    if get_i(s.depth)[0] != max {
        failures.push(format!("{}: the overflowing push changed the depth", s.what));
    }
    for _ in s.initial..max {
        unsafe { (s.pop)() };
    }
    let emptying = error();
    if emptying != GL_NO_ERROR || get_i(s.depth)[0] != s.initial {
        failures.push(format!("{}: emptying raised {}, depth {}", s.what, name(emptying), get_i(s.depth)[0]));
    }
    unsafe { (s.pop)() };
    let underflow = error();
    if underflow != GL_STACK_UNDERFLOW {
        failures.push(format!("{}: pop at depth {}: {}, spec GL_STACK_UNDERFLOW", s.what, s.initial, name(underflow)));
    }
    if get_i(s.depth)[0] != s.initial {
        failures.push(format!("{}: the underflowing pop changed the depth", s.what));
    }
}

/// The matrix stacks push and pop with the same commands.
unsafe fn push_matrix() {
    unsafe { gl::glPushMatrix() }
}
unsafe fn pop_matrix() {
    unsafe { gl::glPopMatrix() }
}

#[test]
fn stacks_overflow_and_underflow() {
    let stacks = [
        Stack {
            what: "modelview",
            select: || unsafe { gl::glMatrixMode(GL_MODELVIEW) },
            push: push_matrix,
            pop: pop_matrix,
            depth: GL_MODELVIEW_STACK_DEPTH,
            max: GL_MAX_MODELVIEW_STACK_DEPTH,
            initial: 1,
        },
        Stack {
            what: "projection",
            select: || unsafe { gl::glMatrixMode(GL_PROJECTION) },
            push: push_matrix,
            pop: pop_matrix,
            depth: GL_PROJECTION_STACK_DEPTH,
            max: GL_MAX_PROJECTION_STACK_DEPTH,
            initial: 1,
        },
        Stack {
            what: "texture (unit 0)",
            select: || unsafe { gl::glMatrixMode(GL_TEXTURE) },
            push: push_matrix,
            pop: pop_matrix,
            depth: GL_TEXTURE_STACK_DEPTH,
            max: GL_MAX_TEXTURE_STACK_DEPTH,
            initial: 1,
        },
        Stack {
            what: "texture (unit 1)",
            select: || unsafe {
                gl::glMatrixMode(GL_TEXTURE);
                gl::glActiveTexture(GL_TEXTURE1);
            },
            push: push_matrix,
            pop: pop_matrix,
            depth: GL_TEXTURE_STACK_DEPTH,
            max: GL_MAX_TEXTURE_STACK_DEPTH,
            initial: 1,
        },
        Stack {
            what: "server attributes",
            select: || {},
            push: || unsafe { gl::glPushAttrib(GL_ALL_ATTRIB_BITS) },
            pop: || unsafe { gl::glPopAttrib() },
            depth: GL_ATTRIB_STACK_DEPTH,
            max: GL_MAX_ATTRIB_STACK_DEPTH,
            initial: 0,
        },
        Stack {
            what: "name stack (selection mode)",
            select: || unsafe { select_mode() },
            push: || unsafe { gl::glPushName(7) },
            pop: || unsafe { gl::glPopName() },
            depth: GL_NAME_STACK_DEPTH,
            max: GL_MAX_NAME_STACK_DEPTH,
            initial: 0,
        },
    ];
    let mut failures = Vec::new();
    for s in &stacks {
        with_fresh_context(|| check_stack(s, &mut failures));
    }
    assert_none("stacks", &failures);
}

#[test]
fn client_attrib_stack_vertex_module() {
    let stack = Stack {
        what: "client attributes",
        select: || {},
        push: || unsafe { gl::glPushClientAttrib(GL_CLIENT_ALL_ATTRIB_BITS) },
        pop: || unsafe { gl::glPopClientAttrib() },
        depth: GL_CLIENT_ATTRIB_STACK_DEPTH,
        max: GL_MAX_CLIENT_ATTRIB_STACK_DEPTH,
        initial: 0,
    };
    let mut failures = Vec::new();
    with_fresh_context(|| check_stack(&stack, &mut failures));
    assert_none("client attribute stack", &failures);
}
