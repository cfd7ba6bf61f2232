//! Fog (OpenGL 1.5 section 3.10): `glFog*` and the fog queries of table 6.11.

use super::Context;
use super::dispatch;
use super::enums::{FOG_MODE, FOG_SOURCE};
use super::get::Value;
use super::gl::{self, GLenum, GLfloat, GLint};
use super::params::Shape;
use crate::frame::state::Fog;

/// Fog state of a context.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FogState {
    /// Parameters used in RGBA mode.
    pub fog: Fog,
    /// `GL_FOG_INDEX` (colour-index mode).
    pub index: f32,
}

/// Parameters of `glFog*`.
fn fog_shape(pname: GLenum) -> Option<Shape> {
    Some(match pname {
        gl::GL_FOG_COLOR => Shape::COLOR,
        gl::GL_FOG_MODE | gl::GL_FOG_DENSITY | gl::GL_FOG_START | gl::GL_FOG_END | gl::GL_FOG_INDEX
        | gl::GL_FOG_COORD_SRC => Shape::SCALAR,
        _ => return None,
    })
}

impl Context {
    /// Sets one fog parameter: `GL_INVALID_ENUM` for an unknown mode or coordinate source,
    /// `GL_INVALID_VALUE` for a negative density.
    fn set_fog(&mut self, pname: GLenum, v: [f32; 4], command: &'static str) {
        let x = v[0];
        match pname {
            gl::GL_FOG_MODE => match FOG_MODE.parse(x as GLenum) {
                Some(m) => self.fixed_mut().fog.fog.mode = m,
                None => self.set_error_in(gl::GL_INVALID_ENUM, command),
            },
            gl::GL_FOG_COORD_SRC => match FOG_SOURCE.parse(x as GLenum) {
                Some(s) => self.fixed_mut().fog.fog.source = s,
                None => self.set_error_in(gl::GL_INVALID_ENUM, command),
            },
            gl::GL_FOG_DENSITY if x.is_nan() || x < 0.0 => self.set_error_in(gl::GL_INVALID_VALUE, command),
            gl::GL_FOG_DENSITY => self.fixed_mut().fog.fog.density = x,
            gl::GL_FOG_START => self.fixed_mut().fog.fog.start = x,
            gl::GL_FOG_END => self.fixed_mut().fog.fog.end = x,
            gl::GL_FOG_INDEX => self.fixed_mut().fog.index = x,
            gl::GL_FOG_COLOR => self.fixed_mut().fog.fog.color = v.map(|c| c.clamp(0.0, 1.0)),
            _ => self.set_error_in(gl::GL_INVALID_ENUM, command),
        }
    }

    /// `glFogf`: scalar parameters only.
    pub fn glFogf(&mut self, pname: GLenum, param: GLfloat) {
        self.scalar_param(fog_shape(pname), param, "glFogf", |ctx, v| ctx.set_fog(pname, v, "glFogf"));
    }

    /// `glFogi`: scalar parameters only.
    pub fn glFogi(&mut self, pname: GLenum, param: GLint) {
        self.scalar_param(fog_shape(pname), param, "glFogi", |ctx, v| ctx.set_fog(pname, v, "glFogi"));
    }

    /// `glFogfv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glFogfv(&mut self, pname: GLenum, params: *const GLfloat) {
        unsafe { self.vector_param(fog_shape(pname), params, "glFogfv", |ctx, v| ctx.set_fog(pname, v, "glFogfv")) }
    }

    /// `glFogiv`: the colour maps linearly from the integer range.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glFogiv(&mut self, pname: GLenum, params: *const GLint) {
        unsafe { self.vector_param(fog_shape(pname), params, "glFogiv", |ctx, v| ctx.set_fog(pname, v, "glFogiv")) }
    }

    /// `glFogfv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glFogfv`].
    pub unsafe fn compile_glFogfv(&mut self, pname: GLenum, params: *const GLfloat) {
        let n = fog_shape(pname).map_or(0, |s| s.count);
        unsafe { self.compile_params(params, n, "glFogfv", move |ctx, p| dispatch::exec_glFogfv(ctx, pname, p)) }
    }

    /// `glFogiv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glFogiv`].
    pub unsafe fn compile_glFogiv(&mut self, pname: GLenum, params: *const GLint) {
        let n = fog_shape(pname).map_or(0, |s| s.count);
        unsafe { self.compile_params(params, n, "glFogiv", move |ctx, p| dispatch::exec_glFogiv(ctx, pname, p)) }
    }

    /// Fog queries (table 6.11).
    pub(crate) fn query_fog(&self, pname: GLenum) -> Option<Value> {
        let f = &self.fixed.fog;
        Some(match pname {
            gl::GL_FOG_COLOR => Value::normalized(&f.fog.color),
            gl::GL_FOG_INDEX => Value::float(f.index),
            gl::GL_FOG_DENSITY => Value::float(f.fog.density),
            gl::GL_FOG_START => Value::float(f.fog.start),
            gl::GL_FOG_END => Value::float(f.fog.end),
            gl::GL_FOG_MODE => FOG_MODE.value(f.fog.mode),
            gl::GL_FOG_COORD_SRC => FOG_SOURCE.value(f.fog.source),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::gl;

    #[test]
    fn fog_parameters_errors_and_queries() {
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(ctx.query(gl::GL_FOG_MODE).unwrap().to_ints(), [gl::GL_EXP as i32]);
        ctx.glFogi(gl::GL_FOG_MODE, gl::GL_LINEAR as i32);
        ctx.glFogf(gl::GL_FOG_START, 10.0);
        ctx.glFogf(gl::GL_FOG_END, 100.0);
        ctx.glFogi(gl::GL_FOG_COORD_SRC, gl::GL_FOG_COORD as i32);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        ctx.glFogf(gl::GL_FOG_DENSITY, -0.5);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glFogi(gl::GL_FOG_MODE, gl::GL_LINE as i32);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glFogf(gl::GL_FOG_COLOR, 1.0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR, "a vector name takes (x, 0, 0, 0), as in Mesa");
        assert_eq!(ctx.query(gl::GL_FOG_COLOR).unwrap().to_doubles(), [1.0, 0.0, 0.0, 0.0]);
        unsafe { ctx.glFogiv(gl::GL_FOG_COLOR, [i32::MAX, i32::MIN, i32::MAX, i32::MAX].as_ptr()) };
        let mut color = [0.0f32; 4];
        let mut ints = [0i32; 4];
        unsafe {
            ctx.glGetFloatv(gl::GL_FOG_COLOR, color.as_mut_ptr());
            ctx.glGetIntegerv(gl::GL_FOG_COLOR, ints.as_mut_ptr());
        }
        assert_eq!(color, [1.0, 0.0, 1.0, 1.0]);
        assert_eq!(ints[0], i32::MAX);
        assert_eq!(ctx.query(gl::GL_FOG_END).unwrap().to_ints(), [100]);
        assert_eq!(ctx.query(gl::GL_FOG_MODE).unwrap().to_ints(), [gl::GL_LINEAR as i32]);
        assert_eq!(ctx.query(gl::GL_FOG_COORD_SRC).unwrap().to_ints(), [gl::GL_FOG_COORD as i32]);
        assert_eq!(ctx.fixed.fog.fog.density, 1.0);
    }
}
