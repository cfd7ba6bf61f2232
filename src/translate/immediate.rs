//! Immediate mode (OpenGL 1.5 section 2.6): `glBegin`/`glEnd` and the vertices between them.

use super::Context;
use super::gl::{self, GLenum};

/// Immediate-mode assembly state.
#[derive(Default)]
pub struct ImmediateState {
    /// The primitive of the open `glBegin`, if any.
    pub primitive: Option<GLenum>,
}

impl Context {
    /// `glBegin`.
    pub fn glBegin(&mut self, mode: GLenum) {
        if mode > gl::GL_POLYGON {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glBegin");
        }
        self.immediate.primitive = Some(mode);
    }

    /// `glEnd`.
    pub fn glEnd(&mut self) {
        if self.immediate.primitive.take().is_none() {
            self.set_error_in(gl::GL_INVALID_OPERATION, "glEnd");
        }
    }
}
