//! Evaluator tests: commands and errors through the generated dispatch, evaluation against
//! hand-computed Bernstein values, mesh walks.

use super::mesh::{MeshStep, walk_mesh1, walk_mesh2};
use super::state::MapDim;
use crate::translate::Context;
use crate::translate::dispatch;
use crate::translate::gl;

fn ctx() -> Context {
    Context::with_recording().0
}

#[test]
fn map1_errors_and_readback() {
    let mut c = ctx();
    let pts: [f32; 8] = [0.0, 0.0, 1.0, 0.0, 5.0, 5.0, 9.0, 9.0];
    unsafe {
        dispatch::glMap1f(&mut c, gl::GL_MAP1_VERTEX_3, 0.0, 0.0, 3, 2, pts.as_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_VALUE, "u1 == u2");
        dispatch::glMap1f(&mut c, gl::GL_MAP1_VERTEX_3, 0.0, 1.0, 2, 2, pts.as_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_VALUE, "stride < 3");
        dispatch::glMap1f(&mut c, gl::GL_MAP1_VERTEX_3, 0.0, 1.0, 3, 0, pts.as_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_VALUE, "order 0");
        dispatch::glMap1f(&mut c, gl::GL_MAP1_VERTEX_3, 0.0, 1.0, 3, 31, pts.as_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_VALUE, "order > MAX_EVAL_ORDER");
        dispatch::glMap1f(&mut c, gl::GL_MAP2_VERTEX_3, 0.0, 1.0, 3, 2, pts.as_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_ENUM, "2D target to glMap1");
        // Stride 4 skips one float between points of 3.
        dispatch::glMap1f(&mut c, gl::GL_MAP1_VERTEX_3, 2.0, 4.0, 4, 2, pts.as_ptr());
        assert_eq!(c.glGetError(), gl::GL_NO_ERROR);
        let mut coeff = [0.0f64; 6];
        dispatch::glGetMapdv(&mut c, gl::GL_MAP1_VERTEX_3, gl::GL_COEFF, coeff.as_mut_ptr());
        assert_eq!(coeff, [0.0, 0.0, 1.0, 5.0, 5.0, 9.0]);
        let mut order = [0i32; 1];
        dispatch::glGetMapiv(&mut c, gl::GL_MAP1_VERTEX_3, gl::GL_ORDER, order.as_mut_ptr());
        assert_eq!(order, [2]);
        let mut domain = [0.0f32; 2];
        dispatch::glGetMapfv(&mut c, gl::GL_MAP1_VERTEX_3, gl::GL_DOMAIN, domain.as_mut_ptr());
        assert_eq!(domain, [2.0, 4.0]);
        dispatch::glGetMapfv(&mut c, gl::GL_MAP1_VERTEX_3, gl::GL_TEXTURE, domain.as_mut_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_ENUM);
        // Initial colour map: one point (1, 1, 1, 1).
        let mut col = [0.0f32; 4];
        dispatch::glGetMapfv(&mut c, gl::GL_MAP2_COLOR_4, gl::GL_COEFF, col.as_mut_ptr());
        assert_eq!(col, [1.0; 4]);
        // Only texture unit 0 takes maps.
        dispatch::glActiveTexture(&mut c, gl::GL_TEXTURE1);
        dispatch::glMap1f(&mut c, gl::GL_MAP1_VERTEX_3, 0.0, 1.0, 3, 2, pts.as_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION);
    }
}

#[test]
fn map2_strides_and_display_list_copy() {
    let mut c = ctx();
    // 2 × 3 points of one component, stored v-major in the client array (vstride 1, ustride 3
    // would be the packed layout; use ustride 1, vstride 2 to transpose).
    let mut pts: [f64; 6] = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
    unsafe {
        dispatch::glNewList(&mut c, 1, gl::GL_COMPILE);
        dispatch::glMap2d(&mut c, gl::GL_MAP2_TEXTURE_COORD_1, 0.0, 1.0, 1, 2, 0.0, 2.0, 2, 3, pts.as_ptr());
        dispatch::glEndList(&mut c);
        let mut coeff = [0.0f64; 6];
        dispatch::glGetMapdv(&mut c, gl::GL_MAP2_TEXTURE_COORD_1, gl::GL_COEFF, coeff.as_mut_ptr());
        assert_eq!(coeff[0], 0.0, "compiled, not executed");
        pts[0] = 100.0; // the list keeps its own copy
        dispatch::glCallList(&mut c, 1);
        assert_eq!(c.glGetError(), gl::GL_NO_ERROR);
        dispatch::glGetMapdv(&mut c, gl::GL_MAP2_TEXTURE_COORD_1, gl::GL_COEFF, coeff.as_mut_ptr());
        // Point (i, j) = pts[i + 2j] as compiled: row i=0 is 1, 3, 5; row i=1 is 2, 4, 6.
        assert_eq!(coeff, [1.0, 3.0, 5.0, 2.0, 4.0, 6.0]);
        let mut order = [0i32; 2];
        dispatch::glGetMapiv(&mut c, gl::GL_MAP2_TEXTURE_COORD_1, gl::GL_ORDER, order.as_mut_ptr());
        assert_eq!(order, [2, 3]);
        let mut domain = [0.0f64; 4];
        dispatch::glGetMapdv(&mut c, gl::GL_MAP2_TEXTURE_COORD_1, gl::GL_DOMAIN, domain.as_mut_ptr());
        assert_eq!(domain, [0.0, 1.0, 0.0, 2.0]);
        // An invalid map in a list raises its error when executed.
        dispatch::glNewList(&mut c, 2, gl::GL_COMPILE);
        dispatch::glMap2d(&mut c, gl::GL_MAP2_VERTEX_3, 0.0, 1.0, 1, 2, 0.0, 1.0, 3, 2, pts.as_ptr());
        dispatch::glEndList(&mut c);
        assert_eq!(c.glGetError(), gl::GL_NO_ERROR);
        dispatch::glCallList(&mut c, 2);
        assert_eq!(c.glGetError(), gl::GL_INVALID_VALUE);
    }
}

#[test]
fn evaluates_cubic_colour_texture_and_vertex() {
    let mut c = ctx();
    // Cubic in x with control x = 0, 1, 3, 2 on domain [10, 20]; u = 12.5 → t = 0.25.
    let pts: [f32; 12] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 3.0, 0.0, 0.0, 2.0, 0.0, 0.0];
    let tex: [f32; 2] = [0.0, 1.0];
    unsafe {
        dispatch::glMap1f(&mut c, gl::GL_MAP1_VERTEX_3, 10.0, 20.0, 3, 4, pts.as_ptr());
        dispatch::glMap1f(&mut c, gl::GL_MAP1_TEXTURE_COORD_1, 10.0, 20.0, 1, 2, tex.as_ptr());
    }
    assert!(c.eval.evaluate(MapDim::One, &c.enables, 12.5, 0.0).is_none(), "no vertex map enabled");
    c.glEnable(gl::GL_MAP1_VERTEX_3);
    c.glEnable(gl::GL_MAP1_TEXTURE_COORD_1);
    let v = c.eval.evaluate(MapDim::One, &c.enables, 12.5, 0.0).expect("vertex map on");
    let x = 0.421875 + 3.0 * 0.140625 + 2.0 * 0.015625;
    assert!((v.position[0] - x as f32).abs() < 1e-6, "{:?}", v.position);
    assert_eq!(v.position[3], 1.0);
    assert_eq!(v.texcoord, Some([0.25, 0.0, 0.0, 1.0]));
    assert_eq!(v.color, None);
    assert_eq!(v.normal, None);
}

#[test]
fn bilinear_patch_with_auto_normal() {
    let mut c = ctx();
    // Plane z = 1: (0,0,1) (0,2,1) / (4,0,1) (4,2,1); u along x, v along y; colours per corner.
    let pts: [f32; 12] = [0.0, 0.0, 1.0, 0.0, 2.0, 1.0, 4.0, 0.0, 1.0, 4.0, 2.0, 1.0];
    let cols: [f32; 16] = [0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 1.0];
    unsafe {
        dispatch::glMap2f(&mut c, gl::GL_MAP2_VERTEX_3, 0.0, 1.0, 6, 2, 0.0, 1.0, 3, 2, pts.as_ptr());
        dispatch::glMap2f(&mut c, gl::GL_MAP2_COLOR_4, 0.0, 1.0, 8, 2, 0.0, 1.0, 4, 2, cols.as_ptr());
    }
    c.glEnable(gl::GL_MAP2_VERTEX_3);
    c.glEnable(gl::GL_MAP2_COLOR_4);
    c.glEnable(gl::GL_AUTO_NORMAL);
    let v = c.eval.evaluate(MapDim::Two, &c.enables, 0.25, 0.5).unwrap();
    assert_eq!(v.position, [1.0, 1.0, 1.0, 1.0]);
    assert_eq!(v.color, Some([0.25, 0.5, 0.0, 1.0]));
    assert_eq!(v.normal, Some([0.0, 0.0, 1.0]));
    c.glDisable(gl::GL_AUTO_NORMAL);
    assert_eq!(c.eval.evaluate(MapDim::Two, &c.enables, 0.25, 0.5).unwrap().normal, None);
}

#[test]
fn grids_queries_and_eval_attrib() {
    let mut c = ctx();
    let mut seg = [0i32; 2];
    unsafe {
        dispatch::glMapGrid2f(&mut c, 0, 0.0, 1.0, 4, 0.0, 1.0);
        assert_eq!(c.glGetError(), gl::GL_INVALID_VALUE);
        dispatch::glMapGrid1d(&mut c, 5, -1.0, 1.0);
        dispatch::glMapGrid2f(&mut c, 3, 0.0, 3.0, 6, 1.0, 2.0);
        dispatch::glGetIntegerv(&mut c, gl::GL_MAP2_GRID_SEGMENTS, seg.as_mut_ptr());
        assert_eq!(seg, [3, 6]);
        let mut dom = [0.0f32; 4];
        dispatch::glGetFloatv(&mut c, gl::GL_MAP2_GRID_DOMAIN, dom.as_mut_ptr());
        assert_eq!(dom, [0.0, 3.0, 1.0, 2.0]);
        dispatch::glGetFloatv(&mut c, gl::GL_MAP1_GRID_DOMAIN, dom.as_mut_ptr());
        assert_eq!(&dom[..2], &[-1.0, 1.0]);
        dispatch::glGetIntegerv(&mut c, gl::GL_MAX_EVAL_ORDER, seg.as_mut_ptr());
        assert_eq!(seg[0], 30);
    }
    assert_eq!(c.eval.grid1.coord(0, 5), 1.0);
    assert_eq!(c.eval.grid1.coord(0, 1), -0.6);
    let saved = c.capture_eval_attrib();
    c.glEnable(gl::GL_MAP2_VERTEX_4);
    c.glEnable(gl::GL_AUTO_NORMAL);
    c.glMapGrid1d(2, 0.0, 1.0);
    c.restore_eval_attrib(&saved);
    assert_eq!(c.glIsEnabled(gl::GL_MAP2_VERTEX_4), 0);
    assert_eq!(c.glIsEnabled(gl::GL_AUTO_NORMAL), 0);
    assert_eq!(c.eval.grid1.segments[0], 5);
}

fn count(walk: impl FnOnce(&mut dyn FnMut(MeshStep)) -> Option<()>) -> Option<(usize, usize)> {
    let (mut prims, mut points) = (0, 0);
    walk(&mut |s| match s {
        MeshStep::Begin(_) => prims += 1,
        MeshStep::Point(..) => points += 1,
        MeshStep::End => {}
    })?;
    Some((prims, points))
}

#[test]
fn mesh_vertex_counts() {
    assert_eq!(count(|s| walk_mesh1(gl::GL_LINE, 0, 4, s)), Some((1, 5)));
    assert_eq!(count(|s| walk_mesh1(gl::GL_FILL, 0, 4, s)), None);
    assert_eq!(count(|s| walk_mesh2(gl::GL_POINT, [0, 3, 0, 2], s)), Some((1, 12)));
    assert_eq!(count(|s| walk_mesh2(gl::GL_LINE, [0, 3, 0, 2], s)), Some((3 + 4, 24)));
    assert_eq!(count(|s| walk_mesh2(gl::GL_FILL, [0, 3, 0, 2], s)), Some((2, 16)));
    assert_eq!(count(|s| walk_mesh2(gl::GL_TRIANGLES, [0, 3, 0, 2], s)), None);
    let mut first = Vec::new();
    walk_mesh2(gl::GL_FILL, [1, 2, 0, 1], &mut |s| first.push(s));
    assert_eq!(
        first,
        [
            MeshStep::Begin(gl::GL_QUAD_STRIP),
            MeshStep::Point(1, 0),
            MeshStep::Point(1, 1),
            MeshStep::Point(2, 0),
            MeshStep::Point(2, 1),
            MeshStep::End
        ]
    );
}

#[test]
fn eval_mesh_mode_errors() {
    let mut c = ctx();
    unsafe {
        dispatch::glEvalMesh2(&mut c, gl::GL_POLYGON, 0, 1, 0, 1);
        assert_eq!(c.glGetError(), gl::GL_INVALID_ENUM);
        dispatch::glEvalMesh1(&mut c, gl::GL_FILL, 0, 1);
        assert_eq!(c.glGetError(), gl::GL_INVALID_ENUM);
        // No vertex map enabled: nothing is issued, no error.
        dispatch::glEvalMesh2(&mut c, gl::GL_FILL, 0, 1, 0, 1);
        assert_eq!(c.glGetError(), gl::GL_NO_ERROR);
        assert!(!c.inside_begin_end());
        // Not allowed inside glBegin/glEnd, while glEvalPoint is.
        dispatch::glBegin(&mut c, gl::GL_POINTS);
        dispatch::glEvalPoint2(&mut c, 0, 0);
        assert_eq!(c.glGetError(), gl::GL_NO_ERROR);
        dispatch::glEvalMesh1(&mut c, gl::GL_POINT, 0, 1);
        assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION);
        dispatch::glEnd(&mut c);
    }
}

#[test]
fn compiled_maps_inside_begin_end_are_invalid_operation() {
    let mut c = ctx();
    let pts: [f32; 8] = [0.0, 0.0, 1.0, 0.0, 5.0, 5.0, 9.0, 9.0];
    let mut coeff = [0.0f32; 6];
    unsafe {
        dispatch::glNewList(&mut c, 3, gl::GL_COMPILE);
        dispatch::glMap1f(&mut c, gl::GL_MAP1_VERTEX_3, 0.0, 1.0, 3, 2, pts.as_ptr());
        dispatch::glMap2f(&mut c, gl::GL_MAP2_VERTEX_3, 0.0, 1.0, 3, 2, 0.0, 1.0, 6, 1, pts.as_ptr());
        dispatch::glEndList(&mut c);
        dispatch::glBegin(&mut c, gl::GL_POINTS);
        dispatch::glCallList(&mut c, 3);
        dispatch::glEnd(&mut c);
        assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION);
        dispatch::glGetMapfv(&mut c, gl::GL_MAP1_VERTEX_3, gl::GL_COEFF, coeff.as_mut_ptr());
        assert_eq!(coeff[..3], [0.0, 0.0, 0.0], "glMap1f replayed inside Begin/End");
        dispatch::glGetMapfv(&mut c, gl::GL_MAP2_VERTEX_3, gl::GL_COEFF, coeff.as_mut_ptr());
        assert_eq!(coeff[..3], [0.0, 0.0, 0.0], "glMap2f replayed inside Begin/End");
        dispatch::glCallList(&mut c, 3);
        assert_eq!(c.glGetError(), gl::GL_NO_ERROR);
        dispatch::glGetMapfv(&mut c, gl::GL_MAP1_VERTEX_3, gl::GL_COEFF, coeff.as_mut_ptr());
        assert_eq!(coeff, [0.0, 0.0, 1.0, 0.0, 5.0, 5.0]);
    }
}
