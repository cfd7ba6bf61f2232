//! User clip planes (OpenGL 1.5 section 2.11.2): `glClipPlane` stores the plane in eye space,
//! multiplied by the inverse of the modelview matrix current when it is specified;
//! `glGetClipPlane` returns the eye-space equation.

use glam::DVec4;

use super::Context;
use super::convert::{read_array, write_slice};
use super::dispatch;
use super::gl::{self, GLdouble, GLenum};
use super::limits::MAX_CLIP_PLANES;
use super::lists::ListOp;

/// The index of `GL_CLIP_PLANEi`.
fn plane_index(plane: GLenum) -> Option<usize> {
    let i = plane.checked_sub(gl::GL_CLIP_PLANE0)? as usize;
    (i < MAX_CLIP_PLANES).then_some(i)
}

impl Context {
    /// `glClipPlane`: `GL_INVALID_ENUM` for a plane out of range.
    ///
    /// # Safety
    /// `equation` must point to 4 doubles.
    pub unsafe fn glClipPlane(&mut self, plane: GLenum, equation: *const GLdouble) {
        let Some(i) = plane_index(plane) else { return self.set_error_in(gl::GL_INVALID_ENUM, "glClipPlane") };
        let Some(p) = (unsafe { read_array::<GLdouble, 4>(equation) }) else {
            return self.null_pointer("glClipPlane");
        };
        // (p1 p2 p3 p4) M⁻¹ as a row vector is (M⁻¹)ᵀ p as a column vector.
        let eye = self.transform.modelview.top().inverse().transpose() * DVec4::from(p);
        self.fixed_mut().clip_planes[i] = eye.to_array();
    }

    /// `glClipPlane` in a display list.
    ///
    /// # Safety
    /// As [`Context::glClipPlane`].
    pub unsafe fn compile_glClipPlane(&mut self, plane: GLenum, equation: *const GLdouble) {
        let Some(p) = (unsafe { read_array::<GLdouble, 4>(equation) }) else {
            return self.null_pointer("glClipPlane");
        };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| unsafe {
            dispatch::exec_glClipPlane(ctx, plane, p.as_ptr())
        })));
    }

    /// `glGetClipPlane`: the eye-space equation.
    ///
    /// # Safety
    /// `equation` must have room for 4 doubles.
    pub unsafe fn glGetClipPlane(&mut self, plane: GLenum, equation: *mut GLdouble) {
        match plane_index(plane) {
            Some(i) => unsafe { write_slice(equation, &self.fixed.clip_planes[i]) },
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glGetClipPlane"),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::{dispatch, gl};

    #[test]
    fn plane_is_stored_in_eye_space() {
        let (mut ctx, _) = Context::with_recording();
        // Object-space plane x = 1 (−x + 1 ≥ 0), seen through a translation by 2 along x: the
        // eye-space plane is x = 3.
        ctx.glTranslatef(2.0, 0.0, 0.0);
        unsafe { dispatch::glClipPlane(&mut ctx, gl::GL_CLIP_PLANE2, [-1.0, 0.0, 0.0, 1.0].as_ptr()) };
        ctx.glLoadIdentity();
        let mut eq = [0.0f64; 4];
        unsafe { ctx.glGetClipPlane(gl::GL_CLIP_PLANE2, eq.as_mut_ptr()) };
        assert_eq!(eq, [-1.0, 0.0, 0.0, 3.0]);
        unsafe { ctx.glGetClipPlane(gl::GL_CLIP_PLANE0 + 6, eq.as_mut_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        unsafe { ctx.glClipPlane(gl::GL_LIGHT0, eq.as_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }

    #[test]
    fn compiled_plane_uses_the_modelview_when_the_list_runs() {
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
            dispatch::glClipPlane(&mut ctx, gl::GL_CLIP_PLANE5, [0.0, 1.0, 0.0, 0.0].as_ptr());
            dispatch::glEndList(&mut ctx);
        }
        ctx.glTranslatef(0.0, -4.0, 0.0);
        unsafe { dispatch::glCallList(&mut ctx, 1) };
        let mut eq = [0.0f64; 4];
        unsafe { ctx.glGetClipPlane(gl::GL_CLIP_PLANE5, eq.as_mut_ptr()) };
        assert_eq!(eq, [0.0, 1.0, 0.0, 4.0]);
    }
}
