//! The "Attribute" column of the OpenGL 1.5 state tables (§6.2, table 6.3 for the group
//! bits): `glPushAttrib(group)` … change … `glPopAttrib` restores a state variable when the
//! pushed mask holds one of its groups, and leaves it changed when the mask holds none of them
//! (§6.1.14), through the C exports. Rows of state owned by modules still being merged are in
//! `*_vertex_module` and `*_texture_module`.

use crate::common;

use common::*;

/// A state variable, a command changing it from its initial value, and its attribute groups.
struct Row {
    pname: GLenum,
    change: unsafe fn(),
    groups: GLbitfield,
}

/// A row.
const fn row(pname: GLenum, change: unsafe fn(), groups: GLbitfield) -> Row {
    Row { pname, change, groups }
}

/// Enables are in `ENABLE_BIT` and in their own group.
const fn cap(pname: GLenum, change: unsafe fn(), group: GLbitfield) -> Row {
    row(pname, change, group | GL_ENABLE_BIT)
}

/// Rows of state on main, by attribute group.
const ROWS: &[Row] = &[
    // current, transform, viewport
    row(GL_MATRIX_MODE, || unsafe { gl::glMatrixMode(GL_PROJECTION) }, GL_TRANSFORM_BIT),
    cap(GL_NORMALIZE, || unsafe { gl::glEnable(GL_NORMALIZE) }, GL_TRANSFORM_BIT),
    cap(GL_RESCALE_NORMAL, || unsafe { gl::glEnable(GL_RESCALE_NORMAL) }, GL_TRANSFORM_BIT),
    cap(GL_CLIP_PLANE2, || unsafe { gl::glEnable(GL_CLIP_PLANE2) }, GL_TRANSFORM_BIT),
    row(GL_VIEWPORT, || unsafe { gl::glViewport(1, 2, 3, 4) }, GL_VIEWPORT_BIT),
    row(GL_DEPTH_RANGE, || unsafe { gl::glDepthRange(0.25, 0.75) }, GL_VIEWPORT_BIT),
    // fog, lighting
    cap(GL_FOG, || unsafe { gl::glEnable(GL_FOG) }, GL_FOG_BIT),
    row(GL_FOG_COLOR, || unsafe { gl::glFogfv(GL_FOG_COLOR, [0.5f32, 0.5, 0.5, 0.5].as_ptr()) }, GL_FOG_BIT),
    row(GL_FOG_DENSITY, || unsafe { gl::glFogf(GL_FOG_DENSITY, 2.0) }, GL_FOG_BIT),
    row(GL_FOG_MODE, || unsafe { gl::glFogi(GL_FOG_MODE, GL_LINEAR as i32) }, GL_FOG_BIT),
    row(GL_FOG_COORD_SRC, || unsafe { gl::glFogi(GL_FOG_COORD_SRC, GL_FOG_COORD as i32) }, GL_FOG_BIT),
    cap(GL_COLOR_SUM, || unsafe { gl::glEnable(GL_COLOR_SUM) }, GL_FOG_BIT),
    row(GL_SHADE_MODEL, || unsafe { gl::glShadeModel(GL_FLAT) }, GL_LIGHTING_BIT),
    cap(GL_LIGHTING, || unsafe { gl::glEnable(GL_LIGHTING) }, GL_LIGHTING_BIT),
    cap(GL_LIGHT3, || unsafe { gl::glEnable(GL_LIGHT3) }, GL_LIGHTING_BIT),
    cap(GL_COLOR_MATERIAL, || unsafe { gl::glEnable(GL_COLOR_MATERIAL) }, GL_LIGHTING_BIT),
    row(GL_COLOR_MATERIAL_FACE, || unsafe { gl::glColorMaterial(GL_BACK, GL_SPECULAR) }, GL_LIGHTING_BIT),
    row(GL_LIGHT_MODEL_AMBIENT, || unsafe { gl::glLightModelfv(GL_LIGHT_MODEL_AMBIENT, [0.5f32; 4].as_ptr()) }, GL_LIGHTING_BIT),
    row(GL_LIGHT_MODEL_TWO_SIDE, || unsafe { gl::glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, 1) }, GL_LIGHTING_BIT),
    row(
        GL_LIGHT_MODEL_COLOR_CONTROL,
        || unsafe { gl::glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_SEPARATE_SPECULAR_COLOR as i32) },
        GL_LIGHTING_BIT,
    ),
    // rasterization
    row(GL_POINT_SIZE, || unsafe { gl::glPointSize(3.0) }, GL_POINT_BIT),
    cap(GL_POINT_SMOOTH, || unsafe { gl::glEnable(GL_POINT_SMOOTH) }, GL_POINT_BIT),
    row(GL_POINT_SIZE_MIN, || unsafe { gl::glPointParameterf(GL_POINT_SIZE_MIN, 2.0) }, GL_POINT_BIT),
    row(GL_POINT_FADE_THRESHOLD_SIZE, || unsafe { gl::glPointParameterf(GL_POINT_FADE_THRESHOLD_SIZE, 2.0) }, GL_POINT_BIT),
    row(
        GL_POINT_DISTANCE_ATTENUATION,
        || unsafe { gl::glPointParameterfv(GL_POINT_DISTANCE_ATTENUATION, [0.0f32, 1.0, 0.0].as_ptr()) },
        GL_POINT_BIT,
    ),
    row(GL_LINE_WIDTH, || unsafe { gl::glLineWidth(3.0) }, GL_LINE_BIT),
    cap(GL_LINE_SMOOTH, || unsafe { gl::glEnable(GL_LINE_SMOOTH) }, GL_LINE_BIT),
    cap(GL_LINE_STIPPLE, || unsafe { gl::glEnable(GL_LINE_STIPPLE) }, GL_LINE_BIT),
    row(GL_LINE_STIPPLE_PATTERN, || unsafe { gl::glLineStipple(3, 0x0F0F) }, GL_LINE_BIT),
    row(GL_LINE_STIPPLE_REPEAT, || unsafe { gl::glLineStipple(3, 0x0F0F) }, GL_LINE_BIT),
    cap(GL_CULL_FACE, || unsafe { gl::glEnable(GL_CULL_FACE) }, GL_POLYGON_BIT),
    row(GL_CULL_FACE_MODE, || unsafe { gl::glCullFace(GL_FRONT) }, GL_POLYGON_BIT),
    row(GL_FRONT_FACE, || unsafe { gl::glFrontFace(GL_CW) }, GL_POLYGON_BIT),
    row(GL_POLYGON_MODE, || unsafe { gl::glPolygonMode(GL_BACK, GL_POINT) }, GL_POLYGON_BIT),
    row(GL_POLYGON_OFFSET_FACTOR, || unsafe { gl::glPolygonOffset(1.0, 2.0) }, GL_POLYGON_BIT),
    row(GL_POLYGON_OFFSET_UNITS, || unsafe { gl::glPolygonOffset(1.0, 2.0) }, GL_POLYGON_BIT),
    cap(GL_POLYGON_SMOOTH, || unsafe { gl::glEnable(GL_POLYGON_SMOOTH) }, GL_POLYGON_BIT),
    cap(GL_POLYGON_OFFSET_FILL, || unsafe { gl::glEnable(GL_POLYGON_OFFSET_FILL) }, GL_POLYGON_BIT),
    cap(GL_POLYGON_OFFSET_LINE, || unsafe { gl::glEnable(GL_POLYGON_OFFSET_LINE) }, GL_POLYGON_BIT),
    cap(GL_POLYGON_STIPPLE, || unsafe { gl::glEnable(GL_POLYGON_STIPPLE) }, GL_POLYGON_BIT),
    cap(GL_MULTISAMPLE, || unsafe { gl::glDisable(GL_MULTISAMPLE) }, GL_MULTISAMPLE_BIT),
    cap(GL_SAMPLE_COVERAGE, || unsafe { gl::glEnable(GL_SAMPLE_COVERAGE) }, GL_MULTISAMPLE_BIT),
    cap(GL_SAMPLE_ALPHA_TO_ONE, || unsafe { gl::glEnable(GL_SAMPLE_ALPHA_TO_ONE) }, GL_MULTISAMPLE_BIT),
    row(GL_SAMPLE_COVERAGE_VALUE, || unsafe { gl::glSampleCoverage(0.5, 1) }, GL_MULTISAMPLE_BIT),
    row(GL_SAMPLE_COVERAGE_INVERT, || unsafe { gl::glSampleCoverage(0.5, 1) }, GL_MULTISAMPLE_BIT),
    // texture unit selection and enables
    row(GL_ACTIVE_TEXTURE, || unsafe { gl::glActiveTexture(GL_TEXTURE2) }, GL_TEXTURE_BIT),
    cap(GL_TEXTURE_2D, || unsafe { gl::glEnable(GL_TEXTURE_2D) }, GL_TEXTURE_BIT),
    cap(GL_TEXTURE_GEN_S, || unsafe { gl::glEnable(GL_TEXTURE_GEN_S) }, GL_TEXTURE_BIT),
    // pixel operations
    cap(GL_SCISSOR_TEST, || unsafe { gl::glEnable(GL_SCISSOR_TEST) }, GL_SCISSOR_BIT),
    row(GL_SCISSOR_BOX, || unsafe { gl::glScissor(1, 2, 3, 4) }, GL_SCISSOR_BIT),
    cap(GL_ALPHA_TEST, || unsafe { gl::glEnable(GL_ALPHA_TEST) }, GL_COLOR_BUFFER_BIT),
    row(GL_ALPHA_TEST_FUNC, || unsafe { gl::glAlphaFunc(GL_GEQUAL, 0.5) }, GL_COLOR_BUFFER_BIT),
    row(GL_ALPHA_TEST_REF, || unsafe { gl::glAlphaFunc(GL_GEQUAL, 0.5) }, GL_COLOR_BUFFER_BIT),
    cap(GL_STENCIL_TEST, || unsafe { gl::glEnable(GL_STENCIL_TEST) }, GL_STENCIL_BUFFER_BIT),
    row(GL_STENCIL_FUNC, || unsafe { gl::glStencilFunc(GL_EQUAL, 3, 7) }, GL_STENCIL_BUFFER_BIT),
    row(GL_STENCIL_VALUE_MASK, || unsafe { gl::glStencilFunc(GL_EQUAL, 3, 7) }, GL_STENCIL_BUFFER_BIT),
    row(GL_STENCIL_REF, || unsafe { gl::glStencilFunc(GL_EQUAL, 3, 7) }, GL_STENCIL_BUFFER_BIT),
    row(GL_STENCIL_FAIL, || unsafe { gl::glStencilOp(GL_ZERO, GL_INCR, GL_DECR) }, GL_STENCIL_BUFFER_BIT),
    row(GL_STENCIL_PASS_DEPTH_FAIL, || unsafe { gl::glStencilOp(GL_ZERO, GL_INCR, GL_DECR) }, GL_STENCIL_BUFFER_BIT),
    row(GL_STENCIL_PASS_DEPTH_PASS, || unsafe { gl::glStencilOp(GL_ZERO, GL_INCR, GL_DECR) }, GL_STENCIL_BUFFER_BIT),
    cap(GL_DEPTH_TEST, || unsafe { gl::glEnable(GL_DEPTH_TEST) }, GL_DEPTH_BUFFER_BIT),
    row(GL_DEPTH_FUNC, || unsafe { gl::glDepthFunc(GL_GEQUAL) }, GL_DEPTH_BUFFER_BIT),
    cap(GL_BLEND, || unsafe { gl::glEnable(GL_BLEND) }, GL_COLOR_BUFFER_BIT),
    row(GL_BLEND_SRC_RGB, || unsafe { gl::glBlendFuncSeparate(GL_SRC_ALPHA, GL_DST_ALPHA, GL_ZERO, GL_ONE) }, GL_COLOR_BUFFER_BIT),
    row(GL_BLEND_DST_RGB, || unsafe { gl::glBlendFuncSeparate(GL_SRC_ALPHA, GL_DST_ALPHA, GL_ZERO, GL_ONE) }, GL_COLOR_BUFFER_BIT),
    row(GL_BLEND_SRC_ALPHA, || unsafe { gl::glBlendFuncSeparate(GL_SRC_ALPHA, GL_DST_ALPHA, GL_ZERO, GL_ONE) }, GL_COLOR_BUFFER_BIT),
    row(GL_BLEND_DST_ALPHA, || unsafe { gl::glBlendFuncSeparate(GL_SRC_ALPHA, GL_DST_ALPHA, GL_ZERO, GL_ONE) }, GL_COLOR_BUFFER_BIT),
    row(GL_BLEND_EQUATION, || unsafe { gl::glBlendEquation(GL_MAX) }, GL_COLOR_BUFFER_BIT),
    row(GL_BLEND_COLOR, || unsafe { gl::glBlendColor(0.5, 0.5, 0.5, 0.5) }, GL_COLOR_BUFFER_BIT),
    cap(GL_DITHER, || unsafe { gl::glDisable(GL_DITHER) }, GL_COLOR_BUFFER_BIT),
    cap(GL_COLOR_LOGIC_OP, || unsafe { gl::glEnable(GL_COLOR_LOGIC_OP) }, GL_COLOR_BUFFER_BIT),
    cap(GL_INDEX_LOGIC_OP, || unsafe { gl::glEnable(GL_INDEX_LOGIC_OP) }, GL_COLOR_BUFFER_BIT),
    row(GL_LOGIC_OP_MODE, || unsafe { gl::glLogicOp(GL_XOR) }, GL_COLOR_BUFFER_BIT),
    // framebuffer control
    row(GL_DRAW_BUFFER, || unsafe { gl::glDrawBuffer(GL_FRONT) }, GL_COLOR_BUFFER_BIT),
    row(GL_INDEX_WRITEMASK, || unsafe { gl::glIndexMask(5) }, GL_COLOR_BUFFER_BIT),
    row(GL_COLOR_WRITEMASK, || unsafe { gl::glColorMask(1, 0, 1, 0) }, GL_COLOR_BUFFER_BIT),
    row(GL_COLOR_CLEAR_VALUE, || unsafe { gl::glClearColor(0.5, 0.5, 0.5, 0.5) }, GL_COLOR_BUFFER_BIT),
    row(GL_INDEX_CLEAR_VALUE, || unsafe { gl::glClearIndex(3.0) }, GL_COLOR_BUFFER_BIT),
    row(GL_DEPTH_WRITEMASK, || unsafe { gl::glDepthMask(0) }, GL_DEPTH_BUFFER_BIT),
    row(GL_DEPTH_CLEAR_VALUE, || unsafe { gl::glClearDepth(0.5) }, GL_DEPTH_BUFFER_BIT),
    row(GL_STENCIL_WRITEMASK, || unsafe { gl::glStencilMask(5) }, GL_STENCIL_BUFFER_BIT),
    row(GL_STENCIL_CLEAR_VALUE, || unsafe { gl::glClearStencil(5) }, GL_STENCIL_BUFFER_BIT),
    row(GL_ACCUM_CLEAR_VALUE, || unsafe { gl::glClearAccum(0.5, 0.5, 0.5, 0.5) }, GL_ACCUM_BUFFER_BIT),
    row(GL_READ_BUFFER, || unsafe { gl::glReadBuffer(GL_FRONT) }, GL_PIXEL_MODE_BIT),
    // evaluators, hints, lists
    cap(GL_MAP1_VERTEX_3, || unsafe { gl::glEnable(GL_MAP1_VERTEX_3) }, GL_EVAL_BIT),
    cap(GL_AUTO_NORMAL, || unsafe { gl::glEnable(GL_AUTO_NORMAL) }, GL_EVAL_BIT),
    row(GL_MAP1_GRID_DOMAIN, || unsafe { gl::glMapGrid1f(3, 0.5, 2.0) }, GL_EVAL_BIT),
    row(GL_MAP1_GRID_SEGMENTS, || unsafe { gl::glMapGrid1f(3, 0.5, 2.0) }, GL_EVAL_BIT),
    row(GL_MAP2_GRID_SEGMENTS, || unsafe { gl::glMapGrid2f(3, 0.5, 2.0, 4, 0.0, 1.0) }, GL_EVAL_BIT),
    row(GL_FOG_HINT, || unsafe { gl::glHint(GL_FOG_HINT, GL_NICEST) }, GL_HINT_BIT),
    row(GL_PERSPECTIVE_CORRECTION_HINT, || unsafe { gl::glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_FASTEST) }, GL_HINT_BIT),
    row(GL_GENERATE_MIPMAP_HINT, || unsafe { gl::glHint(GL_GENERATE_MIPMAP_HINT, GL_NICEST) }, GL_HINT_BIT),
    row(GL_LIST_BASE, || unsafe { gl::glListBase(7) }, GL_LIST_BIT),
];

/// Rows of the `texture` branch: pixel transfer and zoom (`PIXEL_MODE_BIT`), bindings
/// (`TEXTURE_BIT`), the raster position (`CURRENT_BIT`).
const TEXTURE_ROWS: &[Row] = &[
    row(GL_ZOOM_X, || unsafe { gl::glPixelZoom(2.0, 3.0) }, GL_PIXEL_MODE_BIT),
    row(GL_RED_SCALE, || unsafe { gl::glPixelTransferf(GL_RED_SCALE, 2.0) }, GL_PIXEL_MODE_BIT),
    row(GL_INDEX_SHIFT, || unsafe { gl::glPixelTransferi(GL_INDEX_SHIFT, 2) }, GL_PIXEL_MODE_BIT),
    row(GL_MAP_COLOR, || unsafe { gl::glPixelTransferi(GL_MAP_COLOR, 1) }, GL_PIXEL_MODE_BIT),
    row(GL_TEXTURE_BINDING_2D, || unsafe { gl::glBindTexture(GL_TEXTURE_2D, 5) }, GL_TEXTURE_BIT),
    row(GL_CURRENT_RASTER_POSITION, || unsafe { gl::glWindowPos2f(5.0, 6.0) }, GL_CURRENT_BIT),
];

/// Rows of the `vertex` branch: current values (`CURRENT_BIT`).
const VERTEX_ROWS: &[Row] = &[
    row(GL_CURRENT_COLOR, || unsafe { gl::glColor4f(0.5, 0.25, 0.125, 0.0) }, GL_CURRENT_BIT),
    row(GL_CURRENT_SECONDARY_COLOR, || unsafe { gl::glSecondaryColor3f(0.5, 0.25, 0.125) }, GL_CURRENT_BIT),
    row(GL_CURRENT_INDEX, || unsafe { gl::glIndexf(3.0) }, GL_CURRENT_BIT),
    row(GL_CURRENT_NORMAL, || unsafe { gl::glNormal3f(1.0, 0.0, 0.0) }, GL_CURRENT_BIT),
    row(GL_CURRENT_TEXTURE_COORDS, || unsafe { gl::glTexCoord2f(0.5, 0.25) }, GL_CURRENT_BIT),
    row(GL_CURRENT_FOG_COORD, || unsafe { gl::glFogCoordf(2.0) }, GL_CURRENT_BIT),
    row(GL_EDGE_FLAG, || unsafe { gl::glEdgeFlag(0) }, GL_CURRENT_BIT),
];

/// Reads `pname` as floats (the values `glGetFloatv` wrote).
fn read(pname: GLenum) -> Vec<f32> {
    get_f(pname).into_iter().take_while(|v| !v.is_nan()).collect()
}

/// For each row, in fresh contexts: pushing one of its groups restores it, pushing every
/// other group does not; one line per mismatch.
fn check(rows: &[Row]) -> Vec<String> {
    let mut failures = Vec::new();
    for r in rows {
        let what = name(r.pname);
        with_fresh_context(|| {
            let initial = read(r.pname);
            unsafe {
                gl::glPushAttrib(r.groups);
                (r.change)();
            }
            let changed = read(r.pname);
            if changed == initial {
                failures.push(format!("{what}: the change left it at {initial:?}"));
            }
            unsafe { gl::glPopAttrib() };
            let popped = read(r.pname);
            if popped != initial {
                failures.push(format!("{what}: glPopAttrib of its groups gave {popped:?}, spec {initial:?}"));
            }
            let others = GL_ALL_ATTRIB_BITS & !r.groups;
            unsafe {
                gl::glPushAttrib(others);
                (r.change)();
                gl::glPopAttrib();
            }
            let kept = read(r.pname);
            if kept != changed {
                failures.push(format!("{what}: glPopAttrib of other groups gave {kept:?}, spec {changed:?}"));
            }
            let err = error();
            if err != GL_NO_ERROR {
                failures.push(format!("{what}: raised {}", name(err)));
            }
        });
    }
    failures
}

#[test]
fn attribute_groups() {
    assert_none("attribute groups (§6.1.14)", &check(ROWS));
}

#[test]
fn attribute_groups_vertex_module() {
    assert_none("attribute groups (§6.1.14)", &check(VERTEX_ROWS));
}

/// `glPushClientAttrib(CLIENT_VERTEX_ARRAY_BIT)` restores the array state and not the pixel
/// store; `CLIENT_PIXEL_STORE_BIT` the reverse (§6.1.14, tables 6.6 and 6.22). Needs the
/// pixel store of the `texture` branch too.
#[test]
fn client_attribute_groups_vertex_module() {
    make_current();
    let mut failures = Vec::new();
    let state = || (is_enabled(GL_VERTEX_ARRAY), get_i(GL_UNPACK_ALIGNMENT)[0]);
    let change = || unsafe {
        gl::glEnableClientState(GL_VERTEX_ARRAY);
        gl::glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
    };
    unsafe { gl::glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT) };
    change();
    unsafe { gl::glPopClientAttrib() };
    if state() != (false, 8) {
        failures.push(format!("after popping CLIENT_VERTEX_ARRAY_BIT: {:?}, spec (false, 8)", state()));
    }
    unsafe {
        gl::glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl::glPushClientAttrib(GL_CLIENT_PIXEL_STORE_BIT);
    }
    change();
    unsafe { gl::glPopClientAttrib() };
    if state() != (true, 4) {
        failures.push(format!("after popping CLIENT_PIXEL_STORE_BIT: {:?}, spec (true, 4)", state()));
    }
    expect_no_error(&mut failures);
    assert_none("client attribute groups", &failures);
}

#[test]
fn attribute_groups_texture_module() {
    assert_none("attribute groups (§6.1.14)", &check(TEXTURE_ROWS));
}

/// `ENABLE_BIT` and `TEXTURE_BIT` restore the texture enables of every unit, not only of the
/// active one (§6.1.14).
#[test]
fn texture_enables_of_every_unit_are_restored() {
    make_current();
    let mut failures = Vec::new();
    for group in [GL_ENABLE_BIT, GL_TEXTURE_BIT] {
        unsafe {
            gl::glPushAttrib(group);
            gl::glActiveTexture(GL_TEXTURE1);
            gl::glEnable(GL_TEXTURE_2D);
            gl::glActiveTexture(GL_TEXTURE0);
            gl::glPopAttrib();
            gl::glActiveTexture(GL_TEXTURE1);
        }
        if is_enabled(GL_TEXTURE_2D) {
            failures.push(format!("unit 1 TEXTURE_2D still enabled after popping {group:#x}"));
        }
        unsafe {
            gl::glDisable(GL_TEXTURE_2D);
            gl::glActiveTexture(GL_TEXTURE0);
        }
    }
    expect_no_error(&mut failures);
    assert_none("texture enables of every unit", &failures);
}

/// Pushes a failure if an error is latched.
fn expect_no_error(failures: &mut Vec<String>) {
    let err = error();
    if err != GL_NO_ERROR {
        failures.push(format!("raised {}", name(err)));
    }
}
