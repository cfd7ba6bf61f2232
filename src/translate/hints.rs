//! `glHint` (OpenGL 1.5 section 5.6) and the hint queries of table 6.28. glrt records the
//! hints for `glGet` and `glPushAttrib`; they do not change how it renders.

use super::Context;
use super::get::Value;
use super::gl::{self, GLenum};

/// Every hint target.
const TARGETS: [GLenum; 7] = [
    gl::GL_PERSPECTIVE_CORRECTION_HINT,
    gl::GL_POINT_SMOOTH_HINT,
    gl::GL_LINE_SMOOTH_HINT,
    gl::GL_POLYGON_SMOOTH_HINT,
    gl::GL_FOG_HINT,
    gl::GL_GENERATE_MIPMAP_HINT,
    gl::GL_TEXTURE_COMPRESSION_HINT,
];

/// The mode of each target, in the order of `TARGETS`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Hints([GLenum; TARGETS.len()]);

impl Default for Hints {
    /// `GL_DONT_CARE` everywhere.
    fn default() -> Hints {
        Hints([gl::GL_DONT_CARE; TARGETS.len()])
    }
}

fn target_index(target: GLenum) -> Option<usize> {
    TARGETS.iter().position(|&t| t == target)
}

impl Context {
    /// `glHint`: `GL_INVALID_ENUM` for an unknown target or mode.
    pub fn glHint(&mut self, target: GLenum, mode: GLenum) {
        let valid_mode = matches!(mode, gl::GL_DONT_CARE | gl::GL_FASTEST | gl::GL_NICEST);
        match target_index(target) {
            Some(i) if valid_mode => self.fixed_mut().hints.0[i] = mode,
            _ => self.set_error_in(gl::GL_INVALID_ENUM, "glHint"),
        }
    }

    /// Hint queries.
    pub(crate) fn query_hints(&self, pname: GLenum) -> Option<Value> {
        target_index(pname).map(|i| Value::int(self.fixed.hints.0[i]))
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::gl;

    #[test]
    fn hints_set_and_read_back() {
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(ctx.query(gl::GL_FOG_HINT).unwrap().to_ints(), [gl::GL_DONT_CARE as i32]);
        ctx.glHint(gl::GL_PERSPECTIVE_CORRECTION_HINT, gl::GL_NICEST);
        ctx.glHint(gl::GL_GENERATE_MIPMAP_HINT, gl::GL_FASTEST);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(ctx.query(gl::GL_PERSPECTIVE_CORRECTION_HINT).unwrap().to_ints(), [gl::GL_NICEST as i32]);
        assert_eq!(ctx.query(gl::GL_GENERATE_MIPMAP_HINT).unwrap().to_ints(), [gl::GL_FASTEST as i32]);
        ctx.glHint(gl::GL_FOG_HINT, gl::GL_FOG);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glHint(gl::GL_FOG, gl::GL_NICEST);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }
}
