//! Interim, for this branch only: the vertex-pipeline commands [`super::issue`] calls are
//! written by the immediate-mode module (`immediate.rs`). Until that branch is merged they
//! behave as every unimplemented command does (`GL_INVALID_OPERATION`). Delete this file and
//! its `mod` line when merging.

use crate::translate::Context;
use crate::translate::gl::{self, GLfloat};

impl Context {
    /// `glColor4f` (owned by `immediate.rs`).
    pub fn glColor4f(&mut self, _r: GLfloat, _g: GLfloat, _b: GLfloat, _a: GLfloat) {
        self.set_error_in(gl::GL_INVALID_OPERATION, "glColor4f");
    }
    /// `glNormal3f` (owned by `immediate.rs`).
    pub fn glNormal3f(&mut self, _x: GLfloat, _y: GLfloat, _z: GLfloat) {
        self.set_error_in(gl::GL_INVALID_OPERATION, "glNormal3f");
    }
    /// `glTexCoord4f` (owned by `immediate.rs`).
    pub fn glTexCoord4f(&mut self, _s: GLfloat, _t: GLfloat, _r: GLfloat, _q: GLfloat) {
        self.set_error_in(gl::GL_INVALID_OPERATION, "glTexCoord4f");
    }
    /// `glVertex4f` (owned by `immediate.rs`).
    pub fn glVertex4f(&mut self, _x: GLfloat, _y: GLfloat, _z: GLfloat, _w: GLfloat) {
        self.set_error_in(gl::GL_INVALID_OPERATION, "glVertex4f");
    }
}
