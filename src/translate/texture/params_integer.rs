//! EXT_texture_integer's texture parameter commands: `glTexParameterIivEXT`,
//! `glTexParameterIuivEXT`, `glGetTexParameterIivEXT` and `glGetTexParameterIuivEXT`.
//!
//! `GL_TEXTURE_BORDER_COLOR` given with them is stored as integers, unmodified (section 3.8.4),
//! in [`super::params::TexParams::border_integers`], and read back as such. The border colour
//! is a union in the specification ("the returned values are interpreted as the same type as
//! the texture"); glrt keeps both views defined:
//! - an integer border queried with `glGetTexParameterfv`/`iv` (undefined by the
//!   specification) reads as its values clamped to [0, 1], which is also what samplers of
//!   non-integer textures see (integer textures are never sampled, see
//!   [`super::snapshot`]);
//! - a floating-point border queried with `glGetTexParameterI*` reads as its values rounded to
//!   the nearest integer.
//!
//! Every other parameter behaves as with `glTexParameteriv`/`glGetTexParameteriv` (unsigned
//! values converted as the integers they are).

use super::super::Context;
use super::super::convert::{read_slice, write_slice};
use super::super::gl::{self, GLenum, GLint, GLuint};
use super::super::lists::ListOp;
use super::objects::Target;
use super::params::param_count;

impl Context {
    /// Sets `pname` from integer `values`: the border colour as integers, anything else as
    /// `glTexParameteriv` would.
    fn tex_parameter_integers(&mut self, target: GLenum, pname: GLenum, values: &[i64], command: &'static str) {
        if pname != gl::GL_TEXTURE_BORDER_COLOR {
            let v: Vec<f64> = values.iter().map(|&x| x as f64).collect();
            return self.tex_parameter(target, pname, &v, command);
        }
        let Some(t) = Target::from_gl(target) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        let Ok(border) = <[i64; 4]>::try_from(values) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        self.with_bound_texture(t, |obj| {
            let mut params = obj.params;
            params.border_color = border.map(|x| x.clamp(0, 1) as f32);
            params.border_integers = Some(border);
            if params != obj.params {
                obj.params = params;
                obj.touch();
            }
        });
    }

    /// The integer values of `pname` for `glGetTexParameterI*` (see the module doc), raising
    /// `GL_INVALID_ENUM` for an unknown target or name.
    fn tex_parameter_integer_values(&mut self, target: GLenum, pname: GLenum, command: &'static str) -> Option<Vec<i64>> {
        let value = self.tex_parameter_value(target, pname, command)?;
        if pname != gl::GL_TEXTURE_BORDER_COLOR {
            return Some(value.to_ints().into_iter().map(i64::from).collect());
        }
        let t = Target::from_gl(target)?;
        let params = self.with_bound_texture(t, |obj| obj.params);
        Some(match params.border_integers {
            Some(b) => b.to_vec(),
            None => params.border_color.iter().map(|&c| c.round() as i64).collect(),
        })
    }

    /// `glTexParameterIivEXT`: `GL_TEXTURE_BORDER_COLOR` as signed integers, other
    /// parameters as `glTexParameteriv` (its errors).
    ///
    /// # Safety
    /// `params` must point to the values of `pname` (4 for the border colour, else 1).
    pub unsafe fn glTexParameterIivEXT(&mut self, target: GLenum, pname: GLenum, params: *const GLint) {
        let Some(v) = (unsafe { read_slice(params, param_count(pname)) }) else { return self.null_pointer("glTexParameterIivEXT") };
        self.tex_parameter_integers(target, pname, &v.into_iter().map(i64::from).collect::<Vec<_>>(), "glTexParameterIivEXT");
    }

    /// `glTexParameterIuivEXT`: `GL_TEXTURE_BORDER_COLOR` as unsigned integers, other
    /// parameters as `glTexParameteriv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname` (4 for the border colour, else 1).
    pub unsafe fn glTexParameterIuivEXT(&mut self, target: GLenum, pname: GLenum, params: *const GLuint) {
        let Some(v) = (unsafe { read_slice(params, param_count(pname)) }) else { return self.null_pointer("glTexParameterIuivEXT") };
        self.tex_parameter_integers(target, pname, &v.into_iter().map(i64::from).collect::<Vec<_>>(), "glTexParameterIuivEXT");
    }

    /// `glTexParameterIivEXT` in a display list: the values are read when compiled.
    ///
    /// # Safety
    /// As [`Context::glTexParameterIivEXT`].
    pub unsafe fn compile_glTexParameterIivEXT(&mut self, target: GLenum, pname: GLenum, params: *const GLint) {
        let v = unsafe { read_slice(params, param_count(pname)) };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| unsafe {
            ctx.glTexParameterIivEXT(target, pname, v.as_ref().map_or(std::ptr::null(), |v| v.as_ptr()))
        })));
    }

    /// `glTexParameterIuivEXT` in a display list: the values are read when compiled.
    ///
    /// # Safety
    /// As [`Context::glTexParameterIuivEXT`].
    pub unsafe fn compile_glTexParameterIuivEXT(&mut self, target: GLenum, pname: GLenum, params: *const GLuint) {
        let v = unsafe { read_slice(params, param_count(pname)) };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| unsafe {
            ctx.glTexParameterIuivEXT(target, pname, v.as_ref().map_or(std::ptr::null(), |v| v.as_ptr()))
        })));
    }

    /// `glGetTexParameterIivEXT`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetTexParameterIivEXT(&mut self, target: GLenum, pname: GLenum, params: *mut GLint) {
        if let Some(v) = self.tex_parameter_integer_values(target, pname, "glGetTexParameterIivEXT") {
            let v: Vec<GLint> = v.into_iter().map(|x| x.clamp(i64::from(i32::MIN), i64::from(u32::MAX)) as u32 as i32).collect();
            unsafe { write_slice(params, &v) }
        }
    }

    /// `glGetTexParameterIuivEXT`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetTexParameterIuivEXT(&mut self, target: GLenum, pname: GLenum, params: *mut GLuint) {
        if let Some(v) = self.tex_parameter_integer_values(target, pname, "glGetTexParameterIuivEXT") {
            let v: Vec<GLuint> = v.into_iter().map(|x| x.clamp(i64::from(i32::MIN), i64::from(u32::MAX)) as u32).collect();
            unsafe { write_slice(params, &v) }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn integer_border_colours_round_trip() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 3);
        let border = [-5i32, 0, 70000, i32::MAX];
        unsafe { dispatch::glTexParameterIivEXT(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, border.as_ptr()) };
        let mut i = [0i32; 4];
        unsafe { ctx.glGetTexParameterIivEXT(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, i.as_mut_ptr()) };
        assert_eq!(i, border);
        let mut f = [9.0f32; 4];
        unsafe { ctx.glGetTexParameterfv(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, f.as_mut_ptr()) };
        assert_eq!(f, [0.0, 0.0, 1.0, 1.0]);
        let unsigned = [u32::MAX, 1, 2, 3];
        unsafe { dispatch::glTexParameterIuivEXT(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, unsigned.as_ptr()) };
        let mut u = [0u32; 4];
        unsafe { ctx.glGetTexParameterIuivEXT(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, u.as_mut_ptr()) };
        assert_eq!(u, unsigned);
        // A float border reads back rounded; setting it drops the integers.
        let floats = [0.25f32, 0.75, 1.0, 0.0];
        unsafe { dispatch::glTexParameterfv(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, floats.as_ptr()) };
        unsafe { ctx.glGetTexParameterIivEXT(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, i.as_mut_ptr()) };
        assert_eq!(i, [0, 1, 1, 0]);
        // Other parameters as glTexParameteriv.
        let nearest = [gl::GL_NEAREST as i32];
        unsafe { dispatch::glTexParameterIivEXT(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, nearest.as_ptr()) };
        unsafe { ctx.glGetTexParameterIuivEXT(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, u.as_mut_ptr()) };
        assert_eq!(u[0], gl::GL_NEAREST);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        let bad = [gl::GL_FRONT as i32];
        unsafe { dispatch::glTexParameterIivEXT(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, bad.as_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        unsafe { ctx.glGetTexParameterIivEXT(gl::GL_TEXTURE_2D, gl::GL_FOG, i.as_mut_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        unsafe { dispatch::glTexParameterIivEXT(&mut ctx, gl::GL_FOG, gl::GL_TEXTURE_BORDER_COLOR, border.as_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        // Display lists read the values when compiled.
        let mut later = vec![7i32, 8, 9, 10];
        unsafe {
            dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
            dispatch::glTexParameterIivEXT(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, later.as_ptr());
            dispatch::glEndList(&mut ctx);
        }
        later[0] = 0;
        drop(later);
        unsafe { dispatch::glCallList(&mut ctx, 1) };
        unsafe { ctx.glGetTexParameterIivEXT(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, i.as_mut_ptr()) };
        assert_eq!(i, [7, 8, 9, 10]);
    }
}
