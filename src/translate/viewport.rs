//! The viewport and depth range (OpenGL 1.5 section 2.11.1) and the scissor box (4.1.2): the
//! window-coordinate rectangles of the drawable. Both start as the drawable's size the first
//! time a context is made current on one (GLX 1.4 section 3.3.7).

use super::Context;
use super::get::Value;
use super::gl::{self, GLclampd, GLenum, GLint, GLsizei};
use super::limits::MAX_VIEWPORT_DIMS;

/// Viewport, depth range and scissor box.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ViewportState {
    /// `GL_VIEWPORT`: x, y, width, height.
    pub viewport: [i32; 4],
    /// `GL_DEPTH_RANGE`: near, far, clamped to [0, 1].
    pub depth_range: [f64; 2],
    /// `GL_SCISSOR_BOX`: x, y, width, height.
    pub scissor: [i32; 4],
    /// Whether a drawable has set the initial viewport yet.
    pub initialized: bool,
}

impl ViewportState {
    /// The initial state before any drawable: an empty viewport, depth range [0, 1].
    pub fn new() -> ViewportState {
        ViewportState { depth_range: [0.0, 1.0], ..ViewportState::default() }
    }

    /// Maps normalized device coordinates to window coordinates (equation 2.13).
    pub fn to_window(&self, ndc: [f32; 3]) -> [f32; 3] {
        let [x, y, w, h] = self.viewport.map(|v| v as f32);
        let [n, f] = self.depth_range.map(|v| v as f32);
        [
            (ndc[0] + 1.0) * w / 2.0 + x,
            (ndc[1] + 1.0) * h / 2.0 + y,
            ndc[2] * (f - n) / 2.0 + (n + f) / 2.0,
        ]
    }
}

impl Context {
    /// Sets the viewport and scissor box to the drawable's size the first time a drawable is
    /// bound.
    pub(crate) fn init_viewport(&mut self, width: i32, height: i32) {
        let v = &mut self.viewport;
        if !v.initialized {
            v.viewport = [0, 0, width, height];
            v.scissor = [0, 0, width, height];
            v.initialized = true;
        }
    }

    /// `glViewport`: `GL_INVALID_VALUE` for a negative size; sizes clamp to
    /// `GL_MAX_VIEWPORT_DIMS`.
    pub fn glViewport(&mut self, x: GLint, y: GLint, width: GLsizei, height: GLsizei) {
        if width < 0 || height < 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glViewport");
        }
        self.viewport.viewport = [x, y, width.min(MAX_VIEWPORT_DIMS), height.min(MAX_VIEWPORT_DIMS)];
    }

    /// `glDepthRange`: both values clamp to [0, 1].
    pub fn glDepthRange(&mut self, near: GLclampd, far: GLclampd) {
        self.viewport.depth_range = [near.clamp(0.0, 1.0), far.clamp(0.0, 1.0)];
    }

    /// `glScissor`: `GL_INVALID_VALUE` for a negative size.
    pub fn glScissor(&mut self, x: GLint, y: GLint, width: GLsizei, height: GLsizei) {
        if width < 0 || height < 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glScissor");
        }
        self.viewport.scissor = [x, y, width, height];
    }

    pub(crate) fn query_viewport(&self, pname: GLenum) -> Option<Value> {
        let v = &self.viewport;
        Some(match pname {
            gl::GL_VIEWPORT => Value::Int(v.viewport.iter().map(|&x| i64::from(x)).collect()),
            gl::GL_DEPTH_RANGE => Value::Normalized(v.depth_range.to_vec()),
            gl::GL_SCISSOR_BOX => Value::Int(v.scissor.iter().map(|&x| i64::from(x)).collect()),
            gl::GL_MAX_VIEWPORT_DIMS => Value::Int(vec![MAX_VIEWPORT_DIMS.into(); 2]),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::gl;

    #[test]
    fn drawable_sets_initial_viewport_once() {
        let (mut ctx, _) = Context::with_recording();
        ctx.bind_drawable(640, 480);
        assert_eq!(ctx.viewport.viewport, [0, 0, 640, 480]);
        ctx.glViewport(10, 20, 30, 40);
        ctx.bind_drawable(800, 600);
        assert_eq!(ctx.viewport.viewport, [10, 20, 30, 40]);
        ctx.glViewport(0, 0, -1, 5);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glDepthRange(-1.0, 2.0);
        assert_eq!(ctx.viewport.depth_range, [0.0, 1.0]);
        assert_eq!(ctx.viewport.to_window([1.0, -1.0, 0.0]), [40.0, 20.0, 0.5]);
    }
}
