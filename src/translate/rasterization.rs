//! Rasterization parameters (OpenGL 1.5 chapter 3): points and point parameters (3.3), lines
//! and line stipple (3.4), culling, polygon mode and polygon offset (3.5), and multisample
//! coverage (3.2.1), with their queries (tables 6.12 to 6.14); point sprites (OpenGL 2.0
//! section 3.3, `GL_ARB_point_sprite`, `GL_NV_point_sprite`): `GL_POINT_SPRITE_COORD_ORIGIN`
//! and `GL_POINT_SPRITE_R_MODE_NV` here, `GL_COORD_REPLACE`
//! with the texture environments ([`super::texture::env`]). The polygon stipple pattern is
//! in [`super::stipple`].

use super::Context;
use super::dispatch;
use super::enums::{FACE, POLYGON_MODE, SPRITE_R, WINDING};
use super::get::Value;
use super::gl::{self, GLboolean, GLclampf, GLenum, GLfloat, GLint, GLushort};
use super::params::Shape;
use crate::frame::state::{Face, Point, PointSprite, PolygonMode, Winding};

/// Rasterization state of a context.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterizationState {
    /// `glCullFace`.
    pub cull_face: Face,
    /// `glFrontFace`.
    pub front_face: Winding,
    /// `glPolygonMode` of front and back faces.
    pub polygon_mode: [PolygonMode; 2],
    /// `glPolygonOffset`: factor and units.
    pub offset: (f32, f32),
    /// `glPolygonStipple`: rows bottom first, bit 31 the leftmost pixel.
    pub stipple: [u32; 32],
    /// `glLineWidth`.
    pub line_width: f32,
    /// `glLineStipple`: repeat factor in [1, 256] and pattern.
    pub line_stipple: (i32, u16),
    /// `glPointSize` and `glPointParameter` (`smooth` comes from `GL_POINT_SMOOTH`).
    pub point: Point,
    /// `GL_COORD_REPLACE` of each unit and `GL_POINT_SPRITE_COORD_ORIGIN` (point sprites
    /// apply them while `GL_POINT_SPRITE` is on).
    pub sprite: PointSprite,
    /// `glSampleCoverage`: value in [0, 1] and invert flag.
    pub sample_coverage: (f32, bool),
}

impl Default for RasterizationState {
    fn default() -> RasterizationState {
        RasterizationState {
            cull_face: Face::Back,
            front_face: Winding::Ccw,
            polygon_mode: [PolygonMode::Fill; 2],
            offset: (0.0, 0.0),
            stipple: [u32::MAX; 32],
            line_width: 1.0,
            line_stipple: (1, 0xffff),
            point: Point::default(),
            sprite: PointSprite::default(),
            sample_coverage: (1.0, false),
        }
    }
}

/// Parameters of `glPointParameter*`.
fn point_shape(pname: GLenum) -> Option<Shape> {
    Some(match pname {
        gl::GL_POINT_SIZE_MIN | gl::GL_POINT_SIZE_MAX | gl::GL_POINT_FADE_THRESHOLD_SIZE | gl::GL_POINT_SPRITE_COORD_ORIGIN
        | gl::GL_POINT_SPRITE_R_MODE_NV => {
            Shape::SCALAR
        }
        gl::GL_POINT_DISTANCE_ATTENUATION => Shape::plain(3),
        _ => return None,
    })
}

impl Context {
    /// `glCullFace`.
    pub fn glCullFace(&mut self, mode: GLenum) {
        match FACE.parse(mode) {
            Some(f) => self.fixed_mut().raster.cull_face = f,
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glCullFace"),
        }
    }

    /// `glFrontFace`.
    pub fn glFrontFace(&mut self, mode: GLenum) {
        match WINDING.parse(mode) {
            Some(w) => self.fixed_mut().raster.front_face = w,
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glFrontFace"),
        }
    }

    /// `glPolygonMode`.
    pub fn glPolygonMode(&mut self, face: GLenum, mode: GLenum) {
        let (Some(face), Some(mode)) = (FACE.parse(face), POLYGON_MODE.parse(mode)) else {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glPolygonMode");
        };
        let modes = &mut self.fixed_mut().raster.polygon_mode;
        match face {
            Face::Front => modes[0] = mode,
            Face::Back => modes[1] = mode,
            Face::FrontAndBack => *modes = [mode; 2],
        }
    }

    /// `glPolygonOffset`.
    pub fn glPolygonOffset(&mut self, factor: GLfloat, units: GLfloat) {
        self.fixed_mut().raster.offset = (factor, units);
    }

    /// `glLineWidth`: `GL_INVALID_VALUE` unless positive.
    pub fn glLineWidth(&mut self, width: GLfloat) {
        if width.is_nan() || width <= 0.0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glLineWidth");
        }
        self.fixed_mut().raster.line_width = width;
    }

    /// `glLineStipple`: the factor clamps to [1, 256].
    pub fn glLineStipple(&mut self, factor: GLint, pattern: GLushort) {
        self.fixed_mut().raster.line_stipple = (factor.clamp(1, 256), pattern);
    }

    /// `glPointSize`: `GL_INVALID_VALUE` unless positive.
    pub fn glPointSize(&mut self, size: GLfloat) {
        if size.is_nan() || size <= 0.0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glPointSize");
        }
        self.fixed_mut().raster.point.size = size;
    }

    /// Sets a point parameter (section 3.3): `GL_INVALID_VALUE` for a negative size or
    /// threshold; `GL_INVALID_ENUM` for a sprite origin other than `GL_LOWER_LEFT` and
    /// `GL_UPPER_LEFT` (OpenGL 2.0 section 2.5: an enum not allowed) and for an r mode other
    /// than `GL_ZERO`, `GL_S` and `GL_R` (`GL_NV_point_sprite`).
    fn set_point_parameter(&mut self, pname: GLenum, v: [f32; 4], command: &'static str) {
        if pname == gl::GL_POINT_SPRITE_COORD_ORIGIN {
            return match v[0] as GLenum {
                gl::GL_LOWER_LEFT => self.fixed_mut().raster.sprite.lower_left = true,
                gl::GL_UPPER_LEFT => self.fixed_mut().raster.sprite.lower_left = false,
                _ => self.set_error_in(gl::GL_INVALID_ENUM, command),
            };
        }
        if pname == gl::GL_POINT_SPRITE_R_MODE_NV {
            return match SPRITE_R.parse(v[0] as GLenum) {
                Some(r) => self.fixed_mut().raster.sprite.r = r,
                None => self.set_error_in(gl::GL_INVALID_ENUM, command),
            };
        }
        if pname != gl::GL_POINT_DISTANCE_ATTENUATION && (v[0].is_nan() || v[0] < 0.0) {
            return self.set_error_in(gl::GL_INVALID_VALUE, command);
        }
        let p = &mut self.fixed_mut().raster.point;
        match pname {
            gl::GL_POINT_SIZE_MIN => p.size_min = v[0],
            gl::GL_POINT_SIZE_MAX => p.size_max = v[0],
            gl::GL_POINT_FADE_THRESHOLD_SIZE => p.fade_threshold = v[0],
            _ => p.attenuation = [v[0], v[1], v[2]],
        }
    }

    /// `glPointParameterf` (OpenGL 1.4, ARB/EXT_point_parameters).
    pub fn glPointParameterf(&mut self, pname: GLenum, param: GLfloat) {
        self.scalar_param(point_shape(pname), param, "glPointParameterf", |ctx, v| {
            ctx.set_point_parameter(pname, v, "glPointParameterf")
        });
    }

    /// `glPointParameteri` (OpenGL 1.4).
    pub fn glPointParameteri(&mut self, pname: GLenum, param: GLint) {
        self.scalar_param(point_shape(pname), param, "glPointParameteri", |ctx, v| {
            ctx.set_point_parameter(pname, v, "glPointParameteri")
        });
    }

    /// `glPointParameterfv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glPointParameterfv(&mut self, pname: GLenum, params: *const GLfloat) {
        unsafe {
            self.vector_param(point_shape(pname), params, "glPointParameterfv", |ctx, v| {
                ctx.set_point_parameter(pname, v, "glPointParameterfv")
            })
        }
    }

    /// `glPointParameteriv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glPointParameteriv(&mut self, pname: GLenum, params: *const GLint) {
        unsafe {
            self.vector_param(point_shape(pname), params, "glPointParameteriv", |ctx, v| {
                ctx.set_point_parameter(pname, v, "glPointParameteriv")
            })
        }
    }

    /// `glPointParameterfv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glPointParameterfv`].
    pub unsafe fn compile_glPointParameterfv(&mut self, pname: GLenum, params: *const GLfloat) {
        let n = point_shape(pname).map_or(0, |s| s.count);
        unsafe {
            self.compile_params(params, n, "glPointParameterfv", move |ctx, p| {
                dispatch::exec_glPointParameterfv(ctx, pname, p)
            })
        }
    }

    /// `glPointParameteriv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glPointParameteriv`].
    pub unsafe fn compile_glPointParameteriv(&mut self, pname: GLenum, params: *const GLint) {
        let n = point_shape(pname).map_or(0, |s| s.count);
        unsafe {
            self.compile_params(params, n, "glPointParameteriv", move |ctx, p| {
                dispatch::exec_glPointParameteriv(ctx, pname, p)
            })
        }
    }

    /// `glSampleCoverage`: the value clamps to [0, 1].
    pub fn glSampleCoverage(&mut self, value: GLclampf, invert: GLboolean) {
        self.fixed_mut().raster.sample_coverage = (value.clamp(0.0, 1.0), invert != 0);
    }

    /// Rasterization queries (tables 6.12 to 6.14 and 6.17's multisample values).
    pub(crate) fn query_rasterization(&self, pname: GLenum) -> Option<Value> {
        let r = &self.fixed.raster;
        Some(match pname {
            gl::GL_CULL_FACE_MODE => FACE.value(r.cull_face),
            gl::GL_FRONT_FACE => WINDING.value(r.front_face),
            gl::GL_POLYGON_MODE => Value::Int(r.polygon_mode.iter().map(|&m| i64::from(POLYGON_MODE.gl_enum(m))).collect()),
            gl::GL_POLYGON_OFFSET_FACTOR => Value::float(r.offset.0),
            gl::GL_POLYGON_OFFSET_UNITS => Value::float(r.offset.1),
            gl::GL_LINE_WIDTH => Value::float(r.line_width),
            gl::GL_LINE_STIPPLE_REPEAT => Value::int(r.line_stipple.0),
            gl::GL_LINE_STIPPLE_PATTERN => Value::int(r.line_stipple.1),
            gl::GL_POINT_SIZE => Value::float(r.point.size),
            gl::GL_POINT_SIZE_MIN => Value::float(r.point.size_min),
            gl::GL_POINT_SIZE_MAX => Value::float(r.point.size_max),
            gl::GL_POINT_FADE_THRESHOLD_SIZE => Value::float(r.point.fade_threshold),
            gl::GL_POINT_DISTANCE_ATTENUATION => Value::floats(&r.point.attenuation),
            gl::GL_POINT_SPRITE_R_MODE_NV => SPRITE_R.value(r.sprite.r),
            gl::GL_POINT_SPRITE_COORD_ORIGIN => Value::int(if r.sprite.lower_left { gl::GL_LOWER_LEFT } else { gl::GL_UPPER_LEFT }),
            gl::GL_SAMPLE_COVERAGE_VALUE => Value::float(r.sample_coverage.0),
            gl::GL_SAMPLE_COVERAGE_INVERT => Value::bool(r.sample_coverage.1),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::{dispatch, gl};

    fn ints(ctx: &Context, pname: gl::GLenum) -> Vec<i32> {
        ctx.query(pname).unwrap().to_ints()
    }

    #[test]
    fn faces_modes_and_offset() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glCullFace(gl::GL_FRONT_AND_BACK);
        ctx.glFrontFace(gl::GL_CW);
        ctx.glPolygonMode(gl::GL_FRONT_AND_BACK, gl::GL_POINT);
        ctx.glPolygonMode(gl::GL_BACK, gl::GL_LINE);
        ctx.glPolygonOffset(1.5, -2.0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(ints(&ctx, gl::GL_CULL_FACE_MODE), [gl::GL_FRONT_AND_BACK as i32]);
        assert_eq!(ints(&ctx, gl::GL_FRONT_FACE), [gl::GL_CW as i32]);
        assert_eq!(ints(&ctx, gl::GL_POLYGON_MODE), [gl::GL_POINT as i32, gl::GL_LINE as i32]);
        assert_eq!(ctx.query(gl::GL_POLYGON_OFFSET_FACTOR).unwrap().to_doubles(), [1.5]);
        assert_eq!(ctx.query(gl::GL_POLYGON_OFFSET_UNITS).unwrap().to_doubles(), [-2.0]);
        ctx.glCullFace(gl::GL_LEFT);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glFrontFace(gl::GL_FRONT);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glPolygonMode(gl::GL_FRONT, gl::GL_FRONT);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }

    #[test]
    fn lines_points_and_point_parameters() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glLineWidth(0.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glLineWidth(2.5);
        ctx.glLineStipple(300, 0xf0f0);
        assert_eq!(ctx.query(gl::GL_LINE_WIDTH).unwrap().to_doubles(), [2.5]);
        assert_eq!(ints(&ctx, gl::GL_LINE_STIPPLE_REPEAT), [256]);
        assert_eq!(ints(&ctx, gl::GL_LINE_STIPPLE_PATTERN), [0xf0f0]);
        ctx.glPointSize(-1.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glPointSize(4.0);
        ctx.glPointParameterf(gl::GL_POINT_SIZE_MIN, 2.0);
        ctx.glPointParameteri(gl::GL_POINT_SIZE_MAX, 10);
        unsafe { ctx.glPointParameterfv(gl::GL_POINT_DISTANCE_ATTENUATION, [0.0f32, 0.5, 0.25].as_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        ctx.glPointParameterf(gl::GL_POINT_FADE_THRESHOLD_SIZE, -1.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        assert_eq!(ctx.query(gl::GL_POINT_SIZE).unwrap().to_doubles(), [4.0]);
        assert_eq!(ctx.query(gl::GL_POINT_SIZE_MIN).unwrap().to_doubles(), [2.0]);
        assert_eq!(ctx.query(gl::GL_POINT_SIZE_MAX).unwrap().to_doubles(), [10.0]);
        assert_eq!(ctx.query(gl::GL_POINT_DISTANCE_ATTENUATION).unwrap().to_doubles(), [0.0, 0.5, 0.25]);
        assert_eq!(ctx.query(gl::GL_POINT_FADE_THRESHOLD_SIZE).unwrap().to_doubles(), [1.0]);
        ctx.glPointParameterf(gl::GL_POINT_DISTANCE_ATTENUATION, 2.0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR, "a vector name takes (x, 0, 0), as in Mesa");
        assert_eq!(ctx.query(gl::GL_POINT_DISTANCE_ATTENUATION).unwrap().to_doubles(), [2.0, 0.0, 0.0]);

        // The vector form compiled into a list.
        unsafe {
            dispatch::glNewList(&mut ctx, 3, gl::GL_COMPILE);
            dispatch::glPointParameterfv(&mut ctx, gl::GL_POINT_SIZE_MIN, [3.0f32].as_ptr());
            dispatch::glEndList(&mut ctx);
            dispatch::glCallList(&mut ctx, 3);
        }
        assert_eq!(ctx.query(gl::GL_POINT_SIZE_MIN).unwrap().to_doubles(), [3.0]);
        ctx.glSampleCoverage(2.0, 1);
        assert_eq!(ctx.query(gl::GL_SAMPLE_COVERAGE_VALUE).unwrap().to_doubles(), [1.0]);
        assert_eq!(ints(&ctx, gl::GL_SAMPLE_COVERAGE_INVERT), [1]);
    }

    #[test]
    fn multisample_state_reaches_the_draw_state() {
        use crate::frame::state::Multisample;
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(ctx.raster_snapshot().multisample, Multisample::default());
        ctx.glSampleCoverage(0.25, gl::GL_TRUE);
        assert_eq!(ctx.raster_snapshot().multisample.coverage, None, "GL_SAMPLE_COVERAGE is off");
        ctx.glEnable(gl::GL_SAMPLE_COVERAGE);
        ctx.glEnable(gl::GL_SAMPLE_ALPHA_TO_COVERAGE);
        ctx.glDisable(gl::GL_MULTISAMPLE);
        let expected = Multisample { enabled: false, alpha_to_coverage: true, alpha_to_one: false, coverage: Some((0.25, true)) };
        assert_eq!(ctx.raster_snapshot().multisample, expected);
    }

    #[test]
    fn point_sprite_state_errors_queries_and_attrib() {
        use crate::frame::state::PointSprite;
        let (mut ctx, _) = Context::with_recording();
        let int = |ctx: &Context, pname| ctx.query(pname).unwrap().to_ints()[0];
        let coord_replace = |ctx: &mut Context| {
            let mut v = -1;
            unsafe { ctx.glGetTexEnviv(gl::GL_POINT_SPRITE, gl::GL_COORD_REPLACE, &mut v) };
            v
        };
        assert_eq!(int(&ctx, gl::GL_POINT_SPRITE_COORD_ORIGIN), gl::GL_UPPER_LEFT as i32);
        assert_eq!((coord_replace(&mut ctx), ctx.glIsEnabled(gl::GL_POINT_SPRITE)), (0, 0));
        ctx.glActiveTexture(gl::GL_TEXTURE2);
        ctx.glTexEnvi(gl::GL_POINT_SPRITE, gl::GL_COORD_REPLACE, 1);
        assert_eq!(coord_replace(&mut ctx), 1);
        ctx.glActiveTexture(gl::GL_TEXTURE0);
        assert_eq!(coord_replace(&mut ctx), 0, "per unit");
        ctx.glTexEnvi(gl::GL_POINT_SPRITE, gl::GL_COORD_REPLACE, 2);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glTexEnvi(gl::GL_POINT_SPRITE, gl::GL_TEXTURE_ENV_MODE, 1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glPointParameteri(gl::GL_POINT_SPRITE_COORD_ORIGIN, gl::GL_LOWER_LEFT as i32);
        assert_eq!(int(&ctx, gl::GL_POINT_SPRITE_COORD_ORIGIN), gl::GL_LOWER_LEFT as i32);
        ctx.glPointParameterf(gl::GL_POINT_SPRITE_COORD_ORIGIN, gl::GL_LEFT as f32);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        assert_eq!(int(&ctx, gl::GL_POINT_SPRITE_COORD_ORIGIN), gl::GL_LOWER_LEFT as i32);

        assert_eq!(int(&ctx, gl::GL_POINT_SPRITE_R_MODE_NV), gl::GL_ZERO as i32);
        ctx.glPointParameteri(gl::GL_POINT_SPRITE_R_MODE_NV, gl::GL_T as i32);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glPointParameteri(gl::GL_POINT_SPRITE_R_MODE_NV, gl::GL_R as i32);
        assert_eq!(int(&ctx, gl::GL_POINT_SPRITE_R_MODE_NV), gl::GL_R as i32);
        ctx.glPointParameteri(gl::GL_POINT_SPRITE_R_MODE_NV, gl::GL_ZERO as i32);

        ctx.glEnable(gl::GL_POINT_SMOOTH);
        assert_eq!(ctx.raster_snapshot().point.sprite, None);
        assert!(ctx.raster_snapshot().point.smooth);
        ctx.glEnable(gl::GL_POINT_SPRITE);
        let point = ctx.raster_snapshot().point;
        assert_eq!(point.sprite, Some(PointSprite { coord_replace: 0b100, lower_left: true, ..PointSprite::default() }));
        assert!(!point.smooth, "sprites ignore GL_POINT_SMOOTH");

        // The point attribute group holds the enable, the origin and each unit's replacement.
        ctx.glPushAttrib(gl::GL_POINT_BIT);
        ctx.glDisable(gl::GL_POINT_SPRITE);
        ctx.glPointParameteri(gl::GL_POINT_SPRITE_COORD_ORIGIN, gl::GL_UPPER_LEFT as i32);
        ctx.glActiveTexture(gl::GL_TEXTURE2);
        ctx.glTexEnvi(gl::GL_POINT_SPRITE, gl::GL_COORD_REPLACE, 0);
        ctx.glPopAttrib();
        assert_eq!(ctx.raster_snapshot().point.sprite, Some(PointSprite { coord_replace: 0b100, lower_left: true, ..PointSprite::default() }));
    }
}
