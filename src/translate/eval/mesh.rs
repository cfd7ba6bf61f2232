//! Evaluation commands (OpenGL 1.5 section 5.1): `glEvalCoord1f`/`glEvalCoord2f` (the other
//! variants are generated), `glEvalPoint1`/`glEvalPoint2` and `glEvalMesh1`/`glEvalMesh2`,
//! whose grid walks are the pure [`walk_mesh1`] and [`walk_mesh2`].

use super::state::MapDim;
use crate::translate::Context;
use crate::translate::gl::{self, GLenum, GLfloat, GLint};

/// One step of a mesh walk: the commands `glEvalMesh` is equivalent to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshStep {
    /// `glBegin(mode)`.
    Begin(GLenum),
    /// `glEvalPoint2(i, j)` (`j` is 0 for one-dimensional meshes).
    Point(GLint, GLint),
    /// `glEnd`.
    End,
}

/// `glEvalMesh1`'s walk: `GL_POINT` → one `GL_POINTS`, `GL_LINE` → one `GL_LINE_STRIP`, over
/// i1..=i2. `None` for another mode (`GL_INVALID_ENUM`).
pub fn walk_mesh1(mode: GLenum, i1: GLint, i2: GLint, step: &mut dyn FnMut(MeshStep)) -> Option<()> {
    let prim = match mode {
        gl::GL_POINT => gl::GL_POINTS,
        gl::GL_LINE => gl::GL_LINE_STRIP,
        _ => return None,
    };
    step(MeshStep::Begin(prim));
    for i in i1..=i2 {
        step(MeshStep::Point(i, 0));
    }
    step(MeshStep::End);
    Some(())
}

/// `glEvalMesh2`'s walk (section 5.1): `GL_POINT` → one `GL_POINTS` over the grid;
/// `GL_LINE` → a `GL_LINE_STRIP` along u for each j, then along v for each i; `GL_FILL` → a
/// `GL_QUAD_STRIP` for each j in j1..j2. `None` for another mode (`GL_INVALID_ENUM`).
pub fn walk_mesh2(mode: GLenum, [i1, i2, j1, j2]: [GLint; 4], step: &mut dyn FnMut(MeshStep)) -> Option<()> {
    match mode {
        gl::GL_POINT => {
            step(MeshStep::Begin(gl::GL_POINTS));
            for j in j1..=j2 {
                for i in i1..=i2 {
                    step(MeshStep::Point(i, j));
                }
            }
            step(MeshStep::End);
        }
        gl::GL_LINE => {
            for j in j1..=j2 {
                step(MeshStep::Begin(gl::GL_LINE_STRIP));
                (i1..=i2).for_each(|i| step(MeshStep::Point(i, j)));
                step(MeshStep::End);
            }
            for i in i1..=i2 {
                step(MeshStep::Begin(gl::GL_LINE_STRIP));
                (j1..=j2).for_each(|j| step(MeshStep::Point(i, j)));
                step(MeshStep::End);
            }
        }
        gl::GL_FILL => {
            for j in j1..j2 {
                step(MeshStep::Begin(gl::GL_QUAD_STRIP));
                for i in i1..=i2 {
                    step(MeshStep::Point(i, j));
                    step(MeshStep::Point(i, j + 1));
                }
                step(MeshStep::End);
            }
        }
        _ => return None,
    }
    Some(())
}

impl Context {
    /// Evaluates the enabled maps of `dim` at (u, v) and issues the result.
    fn eval_coord(&mut self, dim: MapDim, u: f64, v: f64) {
        if let Some(vertex) = self.eval.evaluate(dim, &self.enables, u, v) {
            self.issue_evaluated(&vertex);
        }
    }

    /// `glEvalCoord1f`: evaluates every enabled one-dimensional map at `u`.
    pub fn glEvalCoord1f(&mut self, u: GLfloat) {
        self.eval_coord(MapDim::One, u.into(), 0.0);
    }

    /// `glEvalCoord2f`: evaluates every enabled two-dimensional map at (`u`, `v`).
    pub fn glEvalCoord2f(&mut self, u: GLfloat, v: GLfloat) {
        self.eval_coord(MapDim::Two, u.into(), v.into());
    }

    /// `glEvalPoint1`: `glEvalCoord1` at grid step `i`.
    pub fn glEvalPoint1(&mut self, i: GLint) {
        let u = self.eval.grid1.coord(0, i);
        self.eval_coord(MapDim::One, u, 0.0);
    }

    /// `glEvalPoint2`: `glEvalCoord2` at grid step (`i`, `j`).
    pub fn glEvalPoint2(&mut self, i: GLint, j: GLint) {
        let (u, v) = (self.eval.grid2.coord(0, i), self.eval.grid2.coord(1, j));
        self.eval_coord(MapDim::Two, u, v);
    }

    /// Runs a mesh walk, issuing its `glBegin`/points/`glEnd`.
    fn run_mesh(&mut self, dim: MapDim, walk: impl FnOnce(&mut dyn FnMut(MeshStep)) -> Option<()>, command: &'static str) {
        let (state, enables) = (self.eval.clone(), self.enables.clone());
        let grid = match dim {
            MapDim::One => state.grid1,
            MapDim::Two => state.grid2,
        };
        let has_vertex_map = state.vertex_map(dim, &enables).is_some();
        let mut step = |s: MeshStep| {
            if !has_vertex_map {
                return;
            }
            match s {
                MeshStep::Begin(prim) => self.issue_begin(prim),
                MeshStep::Point(i, j) => {
                    if let Some(v) = state.evaluate(dim, &enables, grid.coord(0, i), grid.coord(1, j)) {
                        self.issue_evaluated(&v);
                    }
                }
                MeshStep::End => self.issue_end(),
            }
        };
        if walk(&mut step).is_none() {
            self.set_error_in(gl::GL_INVALID_ENUM, command);
        }
    }

    /// `glEvalMesh1`: `GL_INVALID_ENUM` unless `mode` is `GL_POINT` or `GL_LINE`; without an
    /// enabled vertex map nothing is drawn.
    pub fn glEvalMesh1(&mut self, mode: GLenum, i1: GLint, i2: GLint) {
        self.run_mesh(MapDim::One, |step| walk_mesh1(mode, i1, i2, step), "glEvalMesh1");
    }

    /// `glEvalMesh2`: `GL_INVALID_ENUM` unless `mode` is `GL_POINT`, `GL_LINE` or `GL_FILL`.
    pub fn glEvalMesh2(&mut self, mode: GLenum, i1: GLint, i2: GLint, j1: GLint, j2: GLint) {
        self.run_mesh(MapDim::Two, |step| walk_mesh2(mode, [i1, i2, j1, j2], step), "glEvalMesh2");
    }
}
