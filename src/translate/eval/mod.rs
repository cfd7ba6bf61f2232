//! Evaluators (OpenGL 1.5 section 5.1): one- and two-dimensional maps (`glMap1f`, `glMap2f`),
//! their grids (`glMapGrid1f`, `glMapGrid2f`), evaluation (`glEvalCoord1f`, `glEvalCoord2f`,
//! `glEvalPoint1`, `glEvalPoint2`, `glEvalMesh1`, `glEvalMesh2`), `glGetMap*v`, the
//! `GL_EVAL_BIT` attribute group and the evaluator `glGet` state (table 6.x "Evaluators").
//!
//! Control points are kept in `f64` and evaluated with de Casteljau's algorithm
//! ([`bernstein`]). Evaluated points enter the vertex pipeline through the same commands a
//! program would call ([`issue`]); the meshes are walked in [`mesh`].

pub mod bernstein;
pub mod issue;
pub mod mesh;
pub mod state;

pub use state::{EvalAttrib, EvalState, EvalVertex};

use super::Context;
use super::get::Value;
use super::gl::{self, GLdouble, GLenum, GLfloat, GLint};
use super::limits::MAX_EVAL_ORDER;
use super::lists::ListOp;
use state::{Map, MapDim, map_slot};

/// The arguments of `glMap1*`/`glMap2*` after the target: domain and, per dimension, order
/// and stride (in values of the client type).
#[derive(Clone, Copy, Debug)]
struct MapArgs {
    dim: MapDim,
    domain: [f64; 4],
    order: [GLint; 2],
    stride: [GLint; 2],
}

impl MapArgs {
    fn command(&self) -> &'static str {
        match self.dim {
            MapDim::One => "glMap1",
            MapDim::Two => "glMap2",
        }
    }

    /// The map slot and component count, or the error of section 5.1.
    fn validate(&self, target: GLenum, active_unit: usize) -> Result<(usize, usize), GLenum> {
        let (slot, k) = map_slot(self.dim, target).ok_or(gl::GL_INVALID_ENUM)?;
        let dims = self.dim.count();
        for d in 0..dims {
            if self.domain[2 * d] == self.domain[2 * d + 1] {
                return Err(gl::GL_INVALID_VALUE);
            }
            if !(1..=MAX_EVAL_ORDER as GLint).contains(&self.order[d]) || self.stride[d] < k as GLint {
                return Err(gl::GL_INVALID_VALUE);
            }
        }
        // Maps are specified for texture unit 0 only (OpenGL 1.3 appendix F.2.13, as Mesa).
        if active_unit != 0 {
            return Err(gl::GL_INVALID_OPERATION);
        }
        Ok((slot, k))
    }

    /// Reads the control points compactly (point (i, j) at `(i * vorder + j) * k`).
    ///
    /// # Safety
    /// `points` must be readable at every control point the strides and orders address.
    unsafe fn read_points<T: Copy + Into<f64>>(&self, points: *const T, k: usize) -> Option<Vec<f64>> {
        if points.is_null() {
            return None;
        }
        let [uorder, vorder] = [self.order[0] as usize, if self.dim == MapDim::Two { self.order[1] as usize } else { 1 }];
        let [ustride, vstride] = self.stride.map(|s| s as usize);
        let mut out = Vec::with_capacity(uorder * vorder * k);
        for i in 0..uorder {
            for j in 0..vorder {
                let offset = i * ustride + j * vstride;
                // Safety: the caller guarantees the addressed control points are readable.
                let p = unsafe { super::convert::read_slice(points.wrapping_add(offset), k) }?;
                out.extend(p.into_iter().map(Into::into));
            }
        }
        Some(out)
    }
}

impl Context {
    /// `glMap1*`/`glMap2*`: validates, reads the control points and stores the map.
    unsafe fn map<T: Copy + Into<f64>>(&mut self, target: GLenum, args: MapArgs, points: *const T) {
        let (slot, k) = match args.validate(target, self.active_texture_unit()) {
            Ok(v) => v,
            Err(e) => return self.set_error_in(e, args.command()),
        };
        let Some(values) = (unsafe { args.read_points(points, k) }) else { return self.null_pointer(args.command()) };
        let order = [args.order[0] as usize, if args.dim == MapDim::Two { args.order[1] as usize } else { 1 }];
        *self.eval.map_mut(args.dim, slot) = Map { domain: args.domain, order, points: values.into() };
    }

    /// Records `glMap1*`/`glMap2*` into a display list: the control points are copied now,
    /// compactly, and the command is replayed (with its errors) when the list is executed.
    unsafe fn compile_map<T: Copy + Into<f64>>(&mut self, target: GLenum, args: MapArgs, points: *const T) {
        let copy = match args.validate(target, 0) {
            Ok((_, k)) => unsafe { args.read_points(points, k) }.map(|p| (p, k)),
            Err(_) => None,
        };
        let (copied, stride) = match copy {
            Some((p, k)) => {
                let vorder = if args.dim == MapDim::Two { args.order[1] } else { 1 };
                (Some(p), [k as GLint * vorder, k as GLint])
            }
            None => (None, args.stride),
        };
        let replay = MapArgs { stride, ..args };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| {
            let ptr = copied.as_ref().map_or(std::ptr::null(), |p| p.as_ptr());
            unsafe { ctx.map::<f64>(target, replay, ptr) }
        })));
    }

    /// `glMap1f`.
    ///
    /// # Safety
    /// `points` must hold `order` control points `stride` floats apart.
    pub unsafe fn glMap1f(&mut self, target: GLenum, u1: GLfloat, u2: GLfloat, stride: GLint, order: GLint, points: *const GLfloat) {
        unsafe { self.map(target, map1_args(u1.into(), u2.into(), stride, order), points) }
    }

    /// `glMap1d`.
    ///
    /// # Safety
    /// `points` must hold `order` control points `stride` doubles apart.
    pub unsafe fn glMap1d(&mut self, target: GLenum, u1: GLdouble, u2: GLdouble, stride: GLint, order: GLint, points: *const GLdouble) {
        unsafe { self.map(target, map1_args(u1, u2, stride, order), points) }
    }

    /// `glMap2f`.
    ///
    /// # Safety
    /// `points` must hold `uorder` × `vorder` control points at the given strides.
    #[allow(clippy::too_many_arguments)] // the C signature of the GL command
    pub unsafe fn glMap2f(
        &mut self, target: GLenum, u1: GLfloat, u2: GLfloat, ustride: GLint, uorder: GLint,
        v1: GLfloat, v2: GLfloat, vstride: GLint, vorder: GLint, points: *const GLfloat,
    ) {
        let args = map2_args([u1, u2, v1, v2].map(f64::from), [uorder, vorder], [ustride, vstride]);
        unsafe { self.map(target, args, points) }
    }

    /// `glMap2d`.
    ///
    /// # Safety
    /// `points` must hold `uorder` × `vorder` control points at the given strides.
    #[allow(clippy::too_many_arguments)] // the C signature of the GL command
    pub unsafe fn glMap2d(
        &mut self, target: GLenum, u1: GLdouble, u2: GLdouble, ustride: GLint, uorder: GLint,
        v1: GLdouble, v2: GLdouble, vstride: GLint, vorder: GLint, points: *const GLdouble,
    ) {
        unsafe { self.map(target, map2_args([u1, u2, v1, v2], [uorder, vorder], [ustride, vstride]), points) }
    }

    /// `glMap1f` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMap1f`].
    pub unsafe fn compile_glMap1f(&mut self, target: GLenum, u1: GLfloat, u2: GLfloat, stride: GLint, order: GLint, points: *const GLfloat) {
        unsafe { self.compile_map(target, map1_args(u1.into(), u2.into(), stride, order), points) }
    }

    /// `glMap1d` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMap1d`].
    pub unsafe fn compile_glMap1d(&mut self, target: GLenum, u1: GLdouble, u2: GLdouble, stride: GLint, order: GLint, points: *const GLdouble) {
        unsafe { self.compile_map(target, map1_args(u1, u2, stride, order), points) }
    }

    /// `glMap2f` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMap2f`].
    #[allow(clippy::too_many_arguments)] // the C signature of the GL command
    pub unsafe fn compile_glMap2f(
        &mut self, target: GLenum, u1: GLfloat, u2: GLfloat, ustride: GLint, uorder: GLint,
        v1: GLfloat, v2: GLfloat, vstride: GLint, vorder: GLint, points: *const GLfloat,
    ) {
        let args = map2_args([u1, u2, v1, v2].map(f64::from), [uorder, vorder], [ustride, vstride]);
        unsafe { self.compile_map(target, args, points) }
    }

    /// `glMap2d` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMap2d`].
    #[allow(clippy::too_many_arguments)] // the C signature of the GL command
    pub unsafe fn compile_glMap2d(
        &mut self, target: GLenum, u1: GLdouble, u2: GLdouble, ustride: GLint, uorder: GLint,
        v1: GLdouble, v2: GLdouble, vstride: GLint, vorder: GLint, points: *const GLdouble,
    ) {
        unsafe { self.compile_map(target, map2_args([u1, u2, v1, v2], [uorder, vorder], [ustride, vstride]), points) }
    }

    /// `glMapGrid1f`: `GL_INVALID_VALUE` when `un` is not positive.
    pub fn glMapGrid1f(&mut self, un: GLint, u1: GLfloat, u2: GLfloat) {
        self.glMapGrid1d(un, u1.into(), u2.into());
    }

    /// `glMapGrid1d`.
    pub fn glMapGrid1d(&mut self, un: GLint, u1: GLdouble, u2: GLdouble) {
        if un <= 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glMapGrid1");
        }
        self.eval.grid1 = state::Grid { segments: [un, 1], domain: [u1, u2, 0.0, 1.0] };
    }

    /// `glMapGrid2f`: `GL_INVALID_VALUE` when `un` or `vn` is not positive.
    pub fn glMapGrid2f(&mut self, un: GLint, u1: GLfloat, u2: GLfloat, vn: GLint, v1: GLfloat, v2: GLfloat) {
        self.glMapGrid2d(un, u1.into(), u2.into(), vn, v1.into(), v2.into());
    }

    /// `glMapGrid2d`.
    pub fn glMapGrid2d(&mut self, un: GLint, u1: GLdouble, u2: GLdouble, vn: GLint, v1: GLdouble, v2: GLdouble) {
        if un <= 0 || vn <= 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glMapGrid2");
        }
        self.eval.grid2 = state::Grid { segments: [un, vn], domain: [u1, u2, v1, v2] };
    }

    /// `glGetMapdv`.
    ///
    /// # Safety
    /// `v` must have room for every value of `query` (`GL_COEFF`: all control points).
    pub unsafe fn glGetMapdv(&mut self, target: GLenum, query: GLenum, v: *mut GLdouble) {
        if let Some(values) = self.map_values(target, query) {
            unsafe { super::convert::write_slice(v, &values) }
        }
    }

    /// `glGetMapfv`.
    ///
    /// # Safety
    /// As [`Context::glGetMapdv`].
    pub unsafe fn glGetMapfv(&mut self, target: GLenum, query: GLenum, v: *mut GLfloat) {
        if let Some(values) = self.map_values(target, query) {
            let floats: Vec<GLfloat> = values.iter().map(|&x| x as f32).collect();
            unsafe { super::convert::write_slice(v, &floats) }
        }
    }

    /// `glGetMapiv`: control points and domains are rounded to the nearest integer.
    ///
    /// # Safety
    /// As [`Context::glGetMapdv`].
    pub unsafe fn glGetMapiv(&mut self, target: GLenum, query: GLenum, v: *mut GLint) {
        if let Some(values) = self.map_values(target, query) {
            unsafe { super::convert::write_slice(v, &Value::Float(values).to_ints()) }
        }
    }

    /// The values `glGetMap*v` returns (section 6.1.8), or the `GL_INVALID_ENUM` it raises.
    fn map_values(&mut self, target: GLenum, query: GLenum) -> Option<Vec<f64>> {
        let found = [MapDim::One, MapDim::Two]
            .into_iter()
            .find_map(|dim| map_slot(dim, target).map(|(slot, _)| (dim, slot)));
        let Some((dim, slot)) = found else {
            self.set_error_in(gl::GL_INVALID_ENUM, "glGetMap");
            return None;
        };
        let map = self.eval.map(dim, slot);
        let n = dim.count();
        Some(match query {
            gl::GL_COEFF => map.points.to_vec(),
            gl::GL_ORDER => map.order[..n].iter().map(|&o| o as f64).collect(),
            gl::GL_DOMAIN => map.domain[..2 * n].to_vec(),
            _ => {
                self.set_error_in(gl::GL_INVALID_ENUM, "glGetMap");
                return None;
            }
        })
    }

    /// Evaluator state queries: grids and `GL_MAX_EVAL_ORDER` (the map and `GL_AUTO_NORMAL`
    /// enables are answered by [`super::enable`]).
    pub(crate) fn query_eval(&self, pname: GLenum) -> Option<Value> {
        let e = &self.eval;
        Some(match pname {
            gl::GL_MAP1_GRID_DOMAIN => Value::Float(e.grid1.domain[..2].to_vec()),
            gl::GL_MAP1_GRID_SEGMENTS => Value::int(e.grid1.segments[0]),
            gl::GL_MAP2_GRID_DOMAIN => Value::Float(e.grid2.domain.to_vec()),
            gl::GL_MAP2_GRID_SEGMENTS => Value::Int(e.grid2.segments.iter().map(|&s| i64::from(s)).collect()),
            gl::GL_MAX_EVAL_ORDER => Value::int(MAX_EVAL_ORDER as i64),
            _ => return None,
        })
    }

    /// Saves the `GL_EVAL_BIT` group for `glPushAttrib`: the map enables, `GL_AUTO_NORMAL`
    /// and both grids (table 6.x; control points are not part of it).
    pub fn capture_eval_attrib(&self) -> EvalAttrib {
        EvalAttrib {
            enables: state::EVAL_ENABLES.map(|cap| self.enables.is_on(cap)),
            grid1: self.eval.grid1,
            grid2: self.eval.grid2,
        }
    }

    /// Restores what [`Context::capture_eval_attrib`] saved (`glPopAttrib`).
    pub fn restore_eval_attrib(&mut self, saved: &EvalAttrib) {
        for (cap, on) in state::EVAL_ENABLES.into_iter().zip(saved.enables) {
            self.enables.set(cap, 0, on);
        }
        self.eval.grid1 = saved.grid1;
        self.eval.grid2 = saved.grid2;
    }
}

fn map1_args(u1: f64, u2: f64, stride: GLint, order: GLint) -> MapArgs {
    MapArgs { dim: MapDim::One, domain: [u1, u2, 0.0, 1.0], order: [order, 1], stride: [stride, 0] }
}

fn map2_args(domain: [f64; 4], order: [GLint; 2], stride: [GLint; 2]) -> MapArgs {
    MapArgs { dim: MapDim::Two, domain, order, stride }
}

#[cfg(test)]
mod tests;
