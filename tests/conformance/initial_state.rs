//! Initial values of the OpenGL 1.5 state tables (specification §6.2, tables 6.5–6.31 and the
//! miscellaneous table), read back through the C exports as a freshly created and current
//! context answers them: `glGetIntegerv`/`glGetFloatv`/`glGetBooleanv` and `glIsEnabled`.
//!
//! One table of `(pname, expected)` per specification table; each is checked in a loop that
//! reports every mismatch at once. Implementation-dependent values are checked against the
//! minimums of tables 6.30–6.31. Rows whose state belongs to modules still being merged
//! (current attributes, vertex arrays and buffer objects; textures, pixel store, pixel transfer
//! and the raster position) are in the `*_vertex_module` and `*_texture_module` tests.

use crate::common;

use common::*;

/// What a state variable must read back as.
#[derive(Clone, Copy)]
enum Want {
    /// `glGetIntegerv` returns exactly these values (enums, counts, integer state).
    Int(&'static [i32]),
    /// `glGetFloatv` returns exactly these values.
    Float(&'static [f32]),
    /// `glGetBooleanv` returns these values.
    Bool(&'static [bool]),
    /// A capability: `glIsEnabled` and `glGetBooleanv` both answer this.
    Enabled(bool),
    /// The 4×4 identity matrix (`glGetFloatv`).
    Identity,
    /// A mask with every bit set ("1's" in the tables), read with `glGetIntegerv`.
    AllOnes,
    /// An implementation-dependent value of at least this (`glGetIntegerv`), one per element.
    AtLeast(&'static [i32]),
    /// An implementation-dependent range `[lo, hi]` that contains this value (`glGetFloatv`).
    RangeHolds(f32),
    /// A value a check over the context's other state decides (`glGetFloatv`), with what it
    /// demands for the failure message.
    Custom(fn(&[f32]) -> bool, &'static str),
}

use Want::*;

/// Checks every row, returning one line per mismatch or per error raised by a query.
fn check(rows: &[(GLenum, Want)]) -> Vec<String> {
    let mut failures = Vec::new();
    for &(pname, want) in rows {
        let problem = match want {
            Int(v) => {
                let got = &get_i(pname)[..v.len()];
                (got != v).then(|| format!("glGetIntegerv = {got:?}, spec {v:?}"))
            }
            Float(v) => {
                let got = &get_f(pname)[..v.len()];
                let same = got.iter().zip(v).all(|(g, w)| (g - w).abs() <= 1e-6);
                (!same).then(|| format!("glGetFloatv = {got:?}, spec {v:?}"))
            }
            Bool(v) => {
                let got = &get_b(pname)[..v.len()];
                let want: Vec<_> = v.iter().map(|&b| Some(b)).collect();
                (got != want).then(|| format!("glGetBooleanv = {got:?}, spec {v:?}"))
            }
            Enabled(on) => {
                let is = is_enabled(pname);
                let b = get_b(pname)[0];
                (is != on || b != Some(on)).then(|| format!("glIsEnabled = {is}, glGetBooleanv = {b:?}, spec {on}"))
            }
            Identity => {
                let got = &get_f(pname)[..16];
                let id: Vec<f32> = (0..16).map(|i| if i % 5 == 0 { 1.0 } else { 0.0 }).collect();
                (got != id).then(|| format!("glGetFloatv = {got:?}, spec identity"))
            }
            AllOnes => {
                let got = get_i(pname)[0];
                let u = u64::from(got as u32);
                (u == 0 || !(u + 1).is_power_of_two()).then(|| format!("glGetIntegerv = {got:#x}, spec all 1's"))
            }
            AtLeast(min) => {
                let got = &get_i(pname)[..min.len()];
                (got.iter().zip(min).any(|(g, m)| g < m)).then(|| format!("glGetIntegerv = {got:?}, spec minimum {min:?}"))
            }
            RangeHolds(x) => {
                let got = &get_f(pname)[..2];
                (!(got[0] <= x && x <= got[1] && got[0] > 0.0))
                    .then(|| format!("glGetFloatv = {got:?}, spec a positive range holding {x}"))
            }
            Custom(ok, what) => {
                let got = get_f(pname);
                (!ok(&got)).then(|| format!("glGetFloatv = {:?}, spec {what}", &got[..4]))
            }
        };
        let err = error();
        if let Some(p) = problem {
            failures.push(format!("{}: {p}", name(pname)));
        }
        if err != GL_NO_ERROR {
            failures.push(format!("{}: query raised {}", name(pname), name(err)));
        }
        failures.extend(every_getter_answers(pname));
    }
    failures
}

/// A `glGet*` command's name and a call of it that drops the answer.
type Getter = (&'static str, fn(GLenum));

/// §6.1.1–6.1.2: every state variable can be read with each of `glGetBooleanv`,
/// `glGetIntegerv`, `glGetFloatv` and `glGetDoublev`, converted; a line per getter that fails.
fn every_getter_answers(pname: GLenum) -> Vec<String> {
    let getters: [Getter; 4] = [
        ("glGetBooleanv", |p| drop(get_b(p))),
        ("glGetIntegerv", |p| drop(get_i(p))),
        ("glGetFloatv", |p| drop(get_f(p))),
        ("glGetDoublev", |p| drop(get_d(p))),
    ];
    getters
        .iter()
        .filter_map(|(getter, get)| {
            get(pname);
            let err = error();
            (err != GL_NO_ERROR).then(|| format!("{}: {getter} raised {}", name(pname), name(err)))
        })
        .collect()
}

/// Makes a context current and checks `rows`.
fn run(table: &str, rows: &[(GLenum, Want)]) {
    make_current();
    assert_none(table, &check(rows));
}

/// Viewport and scissor box start as the whole window.
const WINDOW: &[i32] = &[0, 0, SIZE, SIZE];
const ZERO4: &[f32] = &[0.0, 0.0, 0.0, 0.0];

/// Table 6.5 (current values), 6.6–6.7 (vertex arrays, buffer bindings) and the client
/// attribute stack — `vertex` branch.
const CURRENT_AND_ARRAYS: &[(GLenum, Want)] = &[
    (GL_CURRENT_COLOR, Float(&[1.0, 1.0, 1.0, 1.0])),
    (GL_CURRENT_SECONDARY_COLOR, Float(&[0.0, 0.0, 0.0, 1.0])),
    (GL_CURRENT_INDEX, Int(&[1])),
    (GL_CURRENT_TEXTURE_COORDS, Float(&[0.0, 0.0, 0.0, 1.0])),
    (GL_CURRENT_NORMAL, Float(&[0.0, 0.0, 1.0])),
    (GL_CURRENT_FOG_COORD, Float(&[0.0])),
    (GL_EDGE_FLAG, Bool(&[true])),
    (GL_VERTEX_ARRAY, Enabled(false)),
    (GL_VERTEX_ARRAY_SIZE, Int(&[4])),
    (GL_VERTEX_ARRAY_TYPE, Int(&[GL_FLOAT as i32])),
    (GL_VERTEX_ARRAY_STRIDE, Int(&[0])),
    (GL_NORMAL_ARRAY, Enabled(false)),
    (GL_NORMAL_ARRAY_TYPE, Int(&[GL_FLOAT as i32])),
    (GL_NORMAL_ARRAY_STRIDE, Int(&[0])),
    (GL_FOG_COORD_ARRAY, Enabled(false)),
    (GL_FOG_COORD_ARRAY_TYPE, Int(&[GL_FLOAT as i32])),
    (GL_FOG_COORD_ARRAY_STRIDE, Int(&[0])),
    (GL_COLOR_ARRAY, Enabled(false)),
    (GL_COLOR_ARRAY_SIZE, Int(&[4])),
    (GL_COLOR_ARRAY_TYPE, Int(&[GL_FLOAT as i32])),
    (GL_COLOR_ARRAY_STRIDE, Int(&[0])),
    (GL_SECONDARY_COLOR_ARRAY, Enabled(false)),
    (GL_SECONDARY_COLOR_ARRAY_SIZE, Int(&[3])),
    (GL_SECONDARY_COLOR_ARRAY_TYPE, Int(&[GL_FLOAT as i32])),
    (GL_SECONDARY_COLOR_ARRAY_STRIDE, Int(&[0])),
    (GL_INDEX_ARRAY, Enabled(false)),
    (GL_INDEX_ARRAY_TYPE, Int(&[GL_FLOAT as i32])),
    (GL_INDEX_ARRAY_STRIDE, Int(&[0])),
    (GL_TEXTURE_COORD_ARRAY, Enabled(false)),
    (GL_TEXTURE_COORD_ARRAY_SIZE, Int(&[4])),
    (GL_TEXTURE_COORD_ARRAY_TYPE, Int(&[GL_FLOAT as i32])),
    (GL_TEXTURE_COORD_ARRAY_STRIDE, Int(&[0])),
    (GL_EDGE_FLAG_ARRAY, Enabled(false)),
    (GL_EDGE_FLAG_ARRAY_STRIDE, Int(&[0])),
    (GL_ARRAY_BUFFER_BINDING, Int(&[0])),
    (GL_VERTEX_ARRAY_BUFFER_BINDING, Int(&[0])),
    (GL_NORMAL_ARRAY_BUFFER_BINDING, Int(&[0])),
    (GL_COLOR_ARRAY_BUFFER_BINDING, Int(&[0])),
    (GL_INDEX_ARRAY_BUFFER_BINDING, Int(&[0])),
    (GL_TEXTURE_COORD_ARRAY_BUFFER_BINDING, Int(&[0])),
    (GL_EDGE_FLAG_ARRAY_BUFFER_BINDING, Int(&[0])),
    (GL_SECONDARY_COLOR_ARRAY_BUFFER_BINDING, Int(&[0])),
    (GL_FOG_COORD_ARRAY_BUFFER_BINDING, Int(&[0])),
    (GL_ELEMENT_ARRAY_BUFFER_BINDING, Int(&[0])),
    // The client attribute stack (tables 6.30 and 6.32) comes with the client state.
    (GL_MAX_CLIENT_ATTRIB_STACK_DEPTH, AtLeast(&[16])),
    (GL_CLIENT_ATTRIB_STACK_DEPTH, Int(&[0])),
];

/// Table 6.6: the client active texture unit (texture unit selection is on main).
const CLIENT_UNIT: &[(GLenum, Want)] = &[(GL_CLIENT_ACTIVE_TEXTURE, Int(&[GL_TEXTURE0 as i32]))];

/// Table 6.9: transformation state.
const TRANSFORMATION: &[(GLenum, Want)] = &[
    (GL_MODELVIEW_MATRIX, Identity),
    (GL_PROJECTION_MATRIX, Identity),
    (GL_TEXTURE_MATRIX, Identity),
    (GL_TRANSPOSE_MODELVIEW_MATRIX, Identity),
    (GL_TRANSPOSE_PROJECTION_MATRIX, Identity),
    (GL_TRANSPOSE_TEXTURE_MATRIX, Identity),
    (GL_VIEWPORT, Int(WINDOW)),
    (GL_DEPTH_RANGE, Float(&[0.0, 1.0])),
    (GL_MODELVIEW_STACK_DEPTH, Int(&[1])),
    (GL_PROJECTION_STACK_DEPTH, Int(&[1])),
    (GL_TEXTURE_STACK_DEPTH, Int(&[1])),
    (GL_MATRIX_MODE, Int(&[GL_MODELVIEW as i32])),
    (GL_NORMALIZE, Enabled(false)),
    (GL_RESCALE_NORMAL, Enabled(false)),
    (GL_CLIP_PLANE0, Enabled(false)),
    (GL_CLIP_PLANE1, Enabled(false)),
    (GL_CLIP_PLANE2, Enabled(false)),
    (GL_CLIP_PLANE3, Enabled(false)),
    (GL_CLIP_PLANE4, Enabled(false)),
    (GL_CLIP_PLANE5, Enabled(false)),
];

/// Table 6.10: coloring (fog, colour sum, shading).
const COLORING: &[(GLenum, Want)] = &[
    (GL_FOG_COLOR, Float(ZERO4)),
    (GL_FOG_INDEX, Float(&[0.0])),
    (GL_FOG_DENSITY, Float(&[1.0])),
    (GL_FOG_START, Float(&[0.0])),
    (GL_FOG_END, Float(&[1.0])),
    (GL_FOG_MODE, Int(&[GL_EXP as i32])),
    (GL_FOG, Enabled(false)),
    (GL_FOG_COORD_SRC, Int(&[GL_FRAGMENT_DEPTH as i32])),
    (GL_COLOR_SUM, Enabled(false)),
    (GL_SHADE_MODEL, Int(&[GL_SMOOTH as i32])),
];

/// Tables 6.11–6.12: lighting (the per-light and material values are read with
/// `glGetLight`/`glGetMaterial`, not here; their enables are).
const LIGHTING: &[(GLenum, Want)] = &[
    (GL_LIGHTING, Enabled(false)),
    (GL_COLOR_MATERIAL, Enabled(false)),
    (GL_COLOR_MATERIAL_PARAMETER, Int(&[GL_AMBIENT_AND_DIFFUSE as i32])),
    (GL_COLOR_MATERIAL_FACE, Int(&[GL_FRONT_AND_BACK as i32])),
    (GL_LIGHT_MODEL_AMBIENT, Float(&[0.2, 0.2, 0.2, 1.0])),
    (GL_LIGHT_MODEL_LOCAL_VIEWER, Bool(&[false])),
    (GL_LIGHT_MODEL_TWO_SIDE, Bool(&[false])),
    (GL_LIGHT_MODEL_COLOR_CONTROL, Int(&[GL_SINGLE_COLOR as i32])),
    (GL_LIGHT0, Enabled(false)),
    (GL_LIGHT1, Enabled(false)),
    (GL_LIGHT2, Enabled(false)),
    (GL_LIGHT3, Enabled(false)),
    (GL_LIGHT4, Enabled(false)),
    (GL_LIGHT5, Enabled(false)),
    (GL_LIGHT6, Enabled(false)),
    (GL_LIGHT7, Enabled(false)),
];

/// `POINT_SIZE_MAX` starts at the larger of the aliased and smooth maximum point sizes (§3.3).
fn point_size_max_ok(v: &[f32]) -> bool {
    let largest = get_f(GL_ALIASED_POINT_SIZE_RANGE)[1].max(get_f(GL_SMOOTH_POINT_SIZE_RANGE)[1]);
    v[0] == largest
}

/// Table 6.13: rasterization.
const RASTERIZATION: &[(GLenum, Want)] = &[
    (GL_POINT_SIZE, Float(&[1.0])),
    (GL_POINT_SMOOTH, Enabled(false)),
    (GL_POINT_SIZE_MIN, Float(&[0.0])),
    (GL_POINT_SIZE_MAX, Custom(point_size_max_ok, "the largest of the aliased and smooth maximum sizes")),
    (GL_POINT_FADE_THRESHOLD_SIZE, Float(&[1.0])),
    (GL_POINT_DISTANCE_ATTENUATION, Float(&[1.0, 0.0, 0.0])),
    (GL_LINE_WIDTH, Float(&[1.0])),
    (GL_LINE_SMOOTH, Enabled(false)),
    (GL_LINE_STIPPLE_PATTERN, Int(&[0xFFFF])),
    (GL_LINE_STIPPLE_REPEAT, Int(&[1])),
    (GL_LINE_STIPPLE, Enabled(false)),
    (GL_CULL_FACE, Enabled(false)),
    (GL_CULL_FACE_MODE, Int(&[GL_BACK as i32])),
    (GL_FRONT_FACE, Int(&[GL_CCW as i32])),
    (GL_POLYGON_SMOOTH, Enabled(false)),
    (GL_POLYGON_MODE, Int(&[GL_FILL as i32, GL_FILL as i32])),
    (GL_POLYGON_OFFSET_FACTOR, Float(&[0.0])),
    (GL_POLYGON_OFFSET_UNITS, Float(&[0.0])),
    (GL_POLYGON_OFFSET_POINT, Enabled(false)),
    (GL_POLYGON_OFFSET_LINE, Enabled(false)),
    (GL_POLYGON_OFFSET_FILL, Enabled(false)),
    (GL_POLYGON_STIPPLE, Enabled(false)),
];

/// Table 6.14: multisampling.
const MULTISAMPLING: &[(GLenum, Want)] = &[
    (GL_MULTISAMPLE, Enabled(true)),
    (GL_SAMPLE_ALPHA_TO_COVERAGE, Enabled(false)),
    (GL_SAMPLE_ALPHA_TO_ONE, Enabled(false)),
    (GL_SAMPLE_COVERAGE, Enabled(false)),
    (GL_SAMPLE_COVERAGE_VALUE, Float(&[1.0])),
    (GL_SAMPLE_COVERAGE_INVERT, Bool(&[false])),
];

/// Tables 6.15 and 6.19: texture enables and texture-coordinate generation enables, the
/// active unit (all on main).
const TEXTURE_ENABLES: &[(GLenum, Want)] = &[
    (GL_TEXTURE_1D, Enabled(false)),
    (GL_TEXTURE_2D, Enabled(false)),
    (GL_TEXTURE_3D, Enabled(false)),
    (GL_TEXTURE_CUBE_MAP, Enabled(false)),
    (GL_TEXTURE_GEN_S, Enabled(false)),
    (GL_TEXTURE_GEN_T, Enabled(false)),
    (GL_TEXTURE_GEN_R, Enabled(false)),
    (GL_TEXTURE_GEN_Q, Enabled(false)),
    (GL_ACTIVE_TEXTURE, Int(&[GL_TEXTURE0 as i32])),
];

/// Table 6.15 texture bindings, tables 6.22 and 6.27 (pixel store, transfer, zoom, maps) and
/// table 6.5's raster position — `texture` branch.
const TEXTURE_PIXELS_RASTER: &[(GLenum, Want)] = &[
    (GL_TEXTURE_BINDING_1D, Int(&[0])),
    (GL_TEXTURE_BINDING_2D, Int(&[0])),
    (GL_TEXTURE_BINDING_3D, Int(&[0])),
    (GL_TEXTURE_BINDING_CUBE_MAP, Int(&[0])),
    (GL_CURRENT_RASTER_POSITION, Float(&[0.0, 0.0, 0.0, 1.0])),
    (GL_CURRENT_RASTER_DISTANCE, Float(&[0.0])),
    (GL_CURRENT_RASTER_COLOR, Float(&[1.0, 1.0, 1.0, 1.0])),
    (GL_CURRENT_RASTER_INDEX, Int(&[1])),
    (GL_CURRENT_RASTER_TEXTURE_COORDS, Float(&[0.0, 0.0, 0.0, 1.0])),
    (GL_CURRENT_RASTER_POSITION_VALID, Bool(&[true])),
    (GL_UNPACK_SWAP_BYTES, Bool(&[false])),
    (GL_UNPACK_LSB_FIRST, Bool(&[false])),
    (GL_UNPACK_IMAGE_HEIGHT, Int(&[0])),
    (GL_UNPACK_SKIP_IMAGES, Int(&[0])),
    (GL_UNPACK_ROW_LENGTH, Int(&[0])),
    (GL_UNPACK_SKIP_ROWS, Int(&[0])),
    (GL_UNPACK_SKIP_PIXELS, Int(&[0])),
    (GL_UNPACK_ALIGNMENT, Int(&[4])),
    (GL_PACK_SWAP_BYTES, Bool(&[false])),
    (GL_PACK_LSB_FIRST, Bool(&[false])),
    (GL_PACK_IMAGE_HEIGHT, Int(&[0])),
    (GL_PACK_SKIP_IMAGES, Int(&[0])),
    (GL_PACK_ROW_LENGTH, Int(&[0])),
    (GL_PACK_SKIP_ROWS, Int(&[0])),
    (GL_PACK_SKIP_PIXELS, Int(&[0])),
    (GL_PACK_ALIGNMENT, Int(&[4])),
    (GL_PIXEL_PACK_BUFFER_BINDING, Int(&[0])),
    (GL_PIXEL_UNPACK_BUFFER_BINDING, Int(&[0])),
    (GL_MAP_COLOR, Bool(&[false])),
    (GL_MAP_STENCIL, Bool(&[false])),
    (GL_INDEX_SHIFT, Int(&[0])),
    (GL_INDEX_OFFSET, Int(&[0])),
    (GL_RED_SCALE, Float(&[1.0])),
    (GL_GREEN_SCALE, Float(&[1.0])),
    (GL_BLUE_SCALE, Float(&[1.0])),
    (GL_ALPHA_SCALE, Float(&[1.0])),
    (GL_DEPTH_SCALE, Float(&[1.0])),
    (GL_RED_BIAS, Float(&[0.0])),
    (GL_GREEN_BIAS, Float(&[0.0])),
    (GL_BLUE_BIAS, Float(&[0.0])),
    (GL_ALPHA_BIAS, Float(&[0.0])),
    (GL_DEPTH_BIAS, Float(&[0.0])),
    (GL_ZOOM_X, Float(&[1.0])),
    (GL_ZOOM_Y, Float(&[1.0])),
    (GL_PIXEL_MAP_I_TO_I_SIZE, Int(&[1])),
    (GL_PIXEL_MAP_S_TO_S_SIZE, Int(&[1])),
    (GL_PIXEL_MAP_I_TO_R_SIZE, Int(&[1])),
    (GL_PIXEL_MAP_I_TO_G_SIZE, Int(&[1])),
    (GL_PIXEL_MAP_I_TO_B_SIZE, Int(&[1])),
    (GL_PIXEL_MAP_I_TO_A_SIZE, Int(&[1])),
    (GL_PIXEL_MAP_R_TO_R_SIZE, Int(&[1])),
    (GL_PIXEL_MAP_G_TO_G_SIZE, Int(&[1])),
    (GL_PIXEL_MAP_B_TO_B_SIZE, Int(&[1])),
    (GL_PIXEL_MAP_A_TO_A_SIZE, Int(&[1])),
    (GL_MAX_TEXTURE_SIZE, AtLeast(&[64])),
    (GL_MAX_3D_TEXTURE_SIZE, AtLeast(&[16])),
    (GL_MAX_CUBE_MAP_TEXTURE_SIZE, AtLeast(&[16])),
    (GL_MAX_TEXTURE_LOD_BIAS, AtLeast(&[2])),
    (GL_MAX_PIXEL_MAP_TABLE, AtLeast(&[32])),
    (GL_NUM_COMPRESSED_TEXTURE_FORMATS, AtLeast(&[0])),
];

/// Table 6.20: pixel operations (scissor, alpha, stencil, depth, blending, dither, logic op).
const PIXEL_OPERATIONS: &[(GLenum, Want)] = &[
    (GL_SCISSOR_TEST, Enabled(false)),
    (GL_SCISSOR_BOX, Int(WINDOW)),
    (GL_ALPHA_TEST, Enabled(false)),
    (GL_ALPHA_TEST_FUNC, Int(&[GL_ALWAYS as i32])),
    (GL_ALPHA_TEST_REF, Float(&[0.0])),
    (GL_STENCIL_TEST, Enabled(false)),
    (GL_STENCIL_FUNC, Int(&[GL_ALWAYS as i32])),
    (GL_STENCIL_VALUE_MASK, AllOnes),
    (GL_STENCIL_REF, Int(&[0])),
    (GL_STENCIL_FAIL, Int(&[GL_KEEP as i32])),
    (GL_STENCIL_PASS_DEPTH_FAIL, Int(&[GL_KEEP as i32])),
    (GL_STENCIL_PASS_DEPTH_PASS, Int(&[GL_KEEP as i32])),
    (GL_DEPTH_TEST, Enabled(false)),
    (GL_DEPTH_FUNC, Int(&[GL_LESS as i32])),
    (GL_BLEND, Enabled(false)),
    (GL_BLEND_SRC_RGB, Int(&[GL_ONE as i32])),
    (GL_BLEND_SRC_ALPHA, Int(&[GL_ONE as i32])),
    (GL_BLEND_DST_RGB, Int(&[GL_ZERO as i32])),
    (GL_BLEND_DST_ALPHA, Int(&[GL_ZERO as i32])),
    (GL_BLEND_SRC, Int(&[GL_ONE as i32])),
    (GL_BLEND_DST, Int(&[GL_ZERO as i32])),
    (GL_BLEND_EQUATION, Int(&[GL_FUNC_ADD as i32])),
    (GL_BLEND_COLOR, Float(ZERO4)),
    (GL_DITHER, Enabled(true)),
    (GL_INDEX_LOGIC_OP, Enabled(false)),
    (GL_COLOR_LOGIC_OP, Enabled(false)),
    (GL_LOGIC_OP_MODE, Int(&[GL_COPY as i32])),
];

/// `DRAW_BUFFER` and `READ_BUFFER` start as `BACK` in a double-buffered context, else `FRONT`
/// (tables 6.21 and 6.27).
fn front_or_back_ok(v: &[f32]) -> bool {
    let back = get_b(GL_DOUBLEBUFFER)[0] == Some(true);
    v[0] == if back { GL_BACK } else { GL_FRONT } as f32
}

/// Table 6.21: framebuffer control (and `READ_BUFFER` of table 6.27).
const FRAMEBUFFER_CONTROL: &[(GLenum, Want)] = &[
    (GL_DRAW_BUFFER, Custom(front_or_back_ok, "BACK when double-buffered, else FRONT")),
    (GL_READ_BUFFER, Custom(front_or_back_ok, "BACK when double-buffered, else FRONT")),
    (GL_INDEX_WRITEMASK, AllOnes),
    (GL_COLOR_WRITEMASK, Bool(&[true, true, true, true])),
    (GL_DEPTH_WRITEMASK, Bool(&[true])),
    (GL_STENCIL_WRITEMASK, AllOnes),
    (GL_COLOR_CLEAR_VALUE, Float(ZERO4)),
    (GL_INDEX_CLEAR_VALUE, Float(&[0.0])),
    (GL_DEPTH_CLEAR_VALUE, Float(&[1.0])),
    (GL_STENCIL_CLEAR_VALUE, Int(&[0])),
    (GL_ACCUM_CLEAR_VALUE, Float(ZERO4)),
];

/// Table 6.28: evaluators (the maps' control points are read with `glGetMap`).
const EVALUATORS: &[(GLenum, Want)] = &[
    (GL_MAP1_VERTEX_3, Enabled(false)),
    (GL_MAP1_VERTEX_4, Enabled(false)),
    (GL_MAP1_INDEX, Enabled(false)),
    (GL_MAP1_COLOR_4, Enabled(false)),
    (GL_MAP1_NORMAL, Enabled(false)),
    (GL_MAP1_TEXTURE_COORD_1, Enabled(false)),
    (GL_MAP1_TEXTURE_COORD_2, Enabled(false)),
    (GL_MAP1_TEXTURE_COORD_3, Enabled(false)),
    (GL_MAP1_TEXTURE_COORD_4, Enabled(false)),
    (GL_MAP2_VERTEX_3, Enabled(false)),
    (GL_MAP2_VERTEX_4, Enabled(false)),
    (GL_MAP2_INDEX, Enabled(false)),
    (GL_MAP2_COLOR_4, Enabled(false)),
    (GL_MAP2_NORMAL, Enabled(false)),
    (GL_MAP2_TEXTURE_COORD_1, Enabled(false)),
    (GL_MAP2_TEXTURE_COORD_2, Enabled(false)),
    (GL_MAP2_TEXTURE_COORD_3, Enabled(false)),
    (GL_MAP2_TEXTURE_COORD_4, Enabled(false)),
    (GL_MAP1_GRID_DOMAIN, Float(&[0.0, 1.0])),
    (GL_MAP2_GRID_DOMAIN, Float(&[0.0, 1.0, 0.0, 1.0])),
    (GL_MAP1_GRID_SEGMENTS, Int(&[1])),
    (GL_MAP2_GRID_SEGMENTS, Int(&[1, 1])),
    (GL_AUTO_NORMAL, Enabled(false)),
];

/// Table 6.29: hints.
const HINTS: &[(GLenum, Want)] = &[
    (GL_PERSPECTIVE_CORRECTION_HINT, Int(&[GL_DONT_CARE as i32])),
    (GL_POINT_SMOOTH_HINT, Int(&[GL_DONT_CARE as i32])),
    (GL_LINE_SMOOTH_HINT, Int(&[GL_DONT_CARE as i32])),
    (GL_POLYGON_SMOOTH_HINT, Int(&[GL_DONT_CARE as i32])),
    (GL_FOG_HINT, Int(&[GL_DONT_CARE as i32])),
    (GL_GENERATE_MIPMAP_HINT, Int(&[GL_DONT_CARE as i32])),
    (GL_TEXTURE_COMPRESSION_HINT, Int(&[GL_DONT_CARE as i32])),
];

/// Tables 6.30–6.31: implementation-dependent values, against the specification's minimums.
const IMPLEMENTATION: &[(GLenum, Want)] = &[
    (GL_MAX_LIGHTS, AtLeast(&[8])),
    (GL_MAX_CLIP_PLANES, AtLeast(&[6])),
    (GL_MAX_MODELVIEW_STACK_DEPTH, AtLeast(&[32])),
    (GL_MAX_PROJECTION_STACK_DEPTH, AtLeast(&[2])),
    (GL_MAX_TEXTURE_STACK_DEPTH, AtLeast(&[2])),
    (GL_SUBPIXEL_BITS, AtLeast(&[4])),
    (GL_MAX_NAME_STACK_DEPTH, AtLeast(&[64])),
    (GL_MAX_LIST_NESTING, AtLeast(&[64])),
    (GL_MAX_EVAL_ORDER, AtLeast(&[8])),
    (GL_MAX_VIEWPORT_DIMS, AtLeast(&[SIZE, SIZE])),
    (GL_MAX_ATTRIB_STACK_DEPTH, AtLeast(&[16])),
    (GL_AUX_BUFFERS, AtLeast(&[0])),
    (GL_RGBA_MODE, Bool(&[true])),
    (GL_INDEX_MODE, Bool(&[false])),
    (GL_STEREO, Bool(&[false])),
    (GL_ALIASED_POINT_SIZE_RANGE, RangeHolds(1.0)),
    (GL_SMOOTH_POINT_SIZE_RANGE, RangeHolds(1.0)),
    (GL_ALIASED_LINE_WIDTH_RANGE, RangeHolds(1.0)),
    (GL_SMOOTH_LINE_WIDTH_RANGE, RangeHolds(1.0)),
    (GL_MAX_ELEMENTS_INDICES, AtLeast(&[1])),
    (GL_MAX_ELEMENTS_VERTICES, AtLeast(&[1])),
    (GL_MAX_TEXTURE_UNITS, AtLeast(&[2])),
    (GL_SAMPLE_BUFFERS, AtLeast(&[0])),
    (GL_SAMPLES, AtLeast(&[0])),
    (GL_RED_BITS, AtLeast(&[1])),
    (GL_GREEN_BITS, AtLeast(&[1])),
    (GL_BLUE_BITS, AtLeast(&[1])),
    (GL_ALPHA_BITS, AtLeast(&[0])),
    (GL_INDEX_BITS, AtLeast(&[0])),
    (GL_DEPTH_BITS, AtLeast(&[1])),
    (GL_STENCIL_BITS, AtLeast(&[0])),
    (GL_ACCUM_RED_BITS, AtLeast(&[0])),
    (GL_ACCUM_GREEN_BITS, AtLeast(&[0])),
    (GL_ACCUM_BLUE_BITS, AtLeast(&[0])),
    (GL_ACCUM_ALPHA_BITS, AtLeast(&[0])),
];

/// Table 6.32 (miscellaneous): display lists, attribute and name stacks, render mode.
const MISCELLANEOUS: &[(GLenum, Want)] = &[
    (GL_LIST_BASE, Int(&[0])),
    (GL_LIST_INDEX, Int(&[0])),
    (GL_LIST_MODE, Int(&[0])),
    (GL_ATTRIB_STACK_DEPTH, Int(&[0])),
    (GL_NAME_STACK_DEPTH, Int(&[0])),
    (GL_RENDER_MODE, Int(&[GL_RENDER as i32])),
];

#[test]
fn current_values_and_vertex_arrays_vertex_module() {
    run("tables 6.5-6.7 (current values, vertex arrays)", CURRENT_AND_ARRAYS);
}

#[test]
fn client_active_texture() {
    run("table 6.6 (client active texture)", CLIENT_UNIT);
}

#[test]
fn transformation() {
    run("table 6.9 (transformation)", TRANSFORMATION);
}

#[test]
fn coloring() {
    run("table 6.10 (coloring)", COLORING);
}

#[test]
fn lighting() {
    run("tables 6.11-6.12 (lighting)", LIGHTING);
}

#[test]
fn rasterization() {
    run("table 6.13 (rasterization)", RASTERIZATION);
}

#[test]
fn multisampling() {
    run("table 6.14 (multisampling)", MULTISAMPLING);
}

#[test]
fn texture_enables_and_units() {
    run("tables 6.15, 6.19 (texture enables, active unit)", TEXTURE_ENABLES);
}

#[test]
fn textures_pixels_raster_position_texture_module() {
    run("tables 6.5, 6.15, 6.22, 6.27, 6.30 (textures, pixels, raster position)", TEXTURE_PIXELS_RASTER);
}

#[test]
fn pixel_operations() {
    run("table 6.20 (pixel operations)", PIXEL_OPERATIONS);
}

#[test]
fn framebuffer_control() {
    run("table 6.21 (framebuffer control)", FRAMEBUFFER_CONTROL);
}

#[test]
fn evaluators() {
    run("table 6.28 (evaluators)", EVALUATORS);
}

#[test]
fn hints() {
    run("table 6.29 (hints)", HINTS);
}

#[test]
fn implementation_dependent_minimums() {
    run("tables 6.30-6.31 (implementation-dependent values)", IMPLEMENTATION);
}

#[test]
fn miscellaneous() {
    run("table 6.32 (miscellaneous)", MISCELLANEOUS);
}

/// The queries themselves: an unknown pname is `INVALID_ENUM` and leaves the output untouched
/// (§6.1.1), so the tables above cannot pass by a query that writes nothing.
#[test]
fn unknown_pname_is_invalid_enum() {
    make_current();
    let got = get_i(GL_TRIANGLES);
    assert_eq!(error(), GL_INVALID_ENUM);
    assert_eq!(got[0], i32::MIN, "glGetIntegerv wrote an answer for an invalid pname");
}

/// §6.1.2 data conversions: booleans read as integers and floats are 0 or 1; non-zero
/// values read as booleans are TRUE; floats read as integers are rounded, except colour
/// components, depth range and depth clear values, which are mapped so that 1.0 becomes the
/// largest integer and 0.0 becomes 0; enums read as floats are their values.
#[test]
fn query_conversions() {
    make_current();
    unsafe {
        gl::glEnable(GL_LIGHTING);
        gl::glLineWidth(2.6);
        gl::glPolygonOffset(1.5, -2.5);
        gl::glClearColor(1.0, 0.0, 1.0, 0.0);
        gl::glDepthRange(0.0, 1.0);
        gl::glFogf(GL_FOG_DENSITY, 0.5);
        gl::glShadeModel(GL_FLAT);
    }
    let mut failures = Vec::new();
    let mut expect = |what: &str, ok: bool, got: String| {
        if !ok {
            failures.push(format!("{what}: got {got}"));
        }
    };
    let i = get_i(GL_LIGHTING)[0];
    expect("glGetIntegerv(LIGHTING) after glEnable = 1", i == 1, format!("{i}"));
    let f = get_f(GL_LIGHTING)[0];
    expect("glGetFloatv(LIGHTING) = 1.0", f == 1.0, format!("{f}"));
    let i = get_i(GL_LINE_WIDTH)[0];
    expect("glGetIntegerv(LINE_WIDTH 2.6) rounds to 3", i == 3, format!("{i}"));
    let i = &get_i(GL_POLYGON_OFFSET_FACTOR)[..1];
    expect("glGetIntegerv(POLYGON_OFFSET_FACTOR 1.5) rounds to 2", i == [2], format!("{i:?}"));
    let b = get_b(GL_FOG_DENSITY)[0];
    expect("glGetBooleanv(FOG_DENSITY 0.5) = TRUE", b == Some(true), format!("{b:?}"));
    let b = get_b(GL_POLYGON_OFFSET_UNITS)[0];
    expect("glGetBooleanv(POLYGON_OFFSET_UNITS -2.5) = TRUE", b == Some(true), format!("{b:?}"));
    let b = &get_b(GL_COLOR_CLEAR_VALUE)[..4];
    let want = [Some(true), Some(false), Some(true), Some(false)];
    expect("glGetBooleanv(COLOR_CLEAR_VALUE 1,0,1,0)", b == want, format!("{b:?}"));
    let i = &get_i(GL_COLOR_CLEAR_VALUE)[..4];
    expect("glGetIntegerv(COLOR_CLEAR_VALUE 1,0,1,0) maps 1.0 to 2^31-1", i == [i32::MAX, 0, i32::MAX, 0], format!("{i:?}"));
    let i = &get_i(GL_DEPTH_RANGE)[..2];
    expect("glGetIntegerv(DEPTH_RANGE 0,1) maps 1.0 to 2^31-1", i == [0, i32::MAX], format!("{i:?}"));
    let i = get_i(GL_DEPTH_CLEAR_VALUE)[0];
    expect("glGetIntegerv(DEPTH_CLEAR_VALUE 1) maps 1.0 to 2^31-1", i == i32::MAX, format!("{i}"));
    let i = &get_i(GL_LIGHT_MODEL_AMBIENT)[..4];
    let fifth = (f64::from(0.2f32) * f64::from(u32::MAX) - 1.0) / 2.0;
    let near = |v: i32, w: f64| (f64::from(v) - w).abs() <= 256.0;
    let ok = near(i[0], fifth) && near(i[1], fifth) && near(i[2], fifth) && i[3] == i32::MAX;
    expect("glGetIntegerv(LIGHT_MODEL_AMBIENT 0.2,0.2,0.2,1) is mapped", ok, format!("{i:?}"));
    let f = get_f(GL_SHADE_MODEL)[0];
    expect("glGetFloatv(SHADE_MODEL) = GL_FLAT", f == GL_FLAT as f32, format!("{f}"));
    let d = &get_d(GL_VIEWPORT)[..4];
    expect("glGetDoublev(VIEWPORT)", d == [0.0, 0.0, f64::from(SIZE), f64::from(SIZE)], format!("{d:?}"));
    let err = error();
    expect("no error", err == GL_NO_ERROR, name(err));
    assert_none("§6.1.2 conversions", &failures);
}
