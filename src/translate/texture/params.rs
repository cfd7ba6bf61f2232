//! Texture object parameters (OpenGL 1.5 section 3.8.4, table 6.16): `glTexParameter*` and
//! `glGetTexParameter*`, and their conversion to the renderer's [`Sampler`].

use super::super::Context;
use super::super::convert::{norm_i32, read_slice, scalar_as_vector, write_slice};
use super::super::get::Value;
use super::super::gl::{self, GLenum, GLfloat, GLint};
use super::super::lists::ListOp;
use super::objects::Target;
use super::super::enums::COMPARE;
use crate::frame::texture::{CompareFunc, DepthMode, Filter, MinFilter, Sampler, Wrap};

/// Parameters of a texture object.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexParams {
    /// `GL_TEXTURE_MIN_FILTER`.
    pub min_filter: GLenum,
    /// `GL_TEXTURE_MAG_FILTER`.
    pub mag_filter: GLenum,
    /// `GL_TEXTURE_WRAP_S`, `_T`, `_R`.
    pub wrap: [GLenum; 3],
    /// `GL_TEXTURE_BORDER_COLOR`.
    pub border_color: [f32; 4],
    /// `GL_TEXTURE_BORDER_COLOR` as integers, when it was last set with
    /// `glTexParameterIivEXT`/`glTexParameterIuivEXT` (EXT_texture_integer: "stored with an
    /// internal data type of integer"; see [`super::params_integer`]); `None` when set as
    /// floats.
    pub border_integers: Option<[i64; 4]>,
    /// `GL_TEXTURE_PRIORITY`.
    pub priority: f32,
    /// `GL_TEXTURE_MIN_LOD`, `GL_TEXTURE_MAX_LOD`.
    pub lod: [f32; 2],
    /// `GL_TEXTURE_BASE_LEVEL`, `GL_TEXTURE_MAX_LEVEL`.
    pub levels: [i32; 2],
    /// `GL_GENERATE_MIPMAP`.
    pub generate_mipmap: bool,
    /// `GL_DEPTH_TEXTURE_MODE`.
    pub depth_mode: GLenum,
    /// `GL_TEXTURE_COMPARE_MODE`.
    pub compare_mode: GLenum,
    /// `GL_TEXTURE_COMPARE_FUNC`.
    pub compare_func: GLenum,
}

impl Default for TexParams {
    fn default() -> TexParams {
        TexParams {
            min_filter: gl::GL_NEAREST_MIPMAP_LINEAR,
            mag_filter: gl::GL_LINEAR,
            wrap: [gl::GL_REPEAT; 3],
            border_color: [0.0; 4],
            border_integers: None,
            priority: 1.0,
            lod: [-1000.0, 1000.0],
            levels: [0, 1000],
            generate_mipmap: false,
            depth_mode: gl::GL_LUMINANCE,
            compare_mode: gl::GL_NONE,
            compare_func: gl::GL_LEQUAL,
        }
    }
}

impl TexParams {
    /// The initial parameters of a texture of `target`: those of table 6.16, but a linear
    /// minification filter and `GL_CLAMP_TO_EDGE` wraps for rectangle textures.
    pub fn initial(target: Target) -> TexParams {
        match target {
            Target::Rect => TexParams { min_filter: gl::GL_LINEAR, wrap: [gl::GL_CLAMP_TO_EDGE; 3], ..TexParams::default() },
            _ => TexParams::default(),
        }
    }

    /// What rectangle textures refuse (ARB_texture_rectangle): `GL_REPEAT` and
    /// `GL_MIRRORED_REPEAT` wraps and mipmap filters (`GL_INVALID_ENUM`), a base level other
    /// than 0 (`GL_INVALID_VALUE`, as the extension's errors section says).
    fn check_rect(&self) -> Result<(), GLenum> {
        if self.wrap.iter().any(|&w| matches!(w, gl::GL_REPEAT | gl::GL_MIRRORED_REPEAT)) || uses_mipmaps(self.min_filter) {
            return Err(gl::GL_INVALID_ENUM);
        }
        if self.levels[0] != 0 {
            return Err(gl::GL_INVALID_VALUE);
        }
        Ok(())
    }
}

/// Whether a minification filter uses mipmaps.
pub fn uses_mipmaps(min_filter: GLenum) -> bool {
    !matches!(min_filter, gl::GL_NEAREST | gl::GL_LINEAR)
}

fn filter(f: GLenum) -> Filter {
    if matches!(f, gl::GL_NEAREST | gl::GL_NEAREST_MIPMAP_NEAREST | gl::GL_NEAREST_MIPMAP_LINEAR) { Filter::Nearest } else { Filter::Linear }
}

impl TexParams {
    /// The renderer's view of these parameters.
    pub fn sampler(&self) -> Sampler {
        let mipmap = match self.min_filter {
            gl::GL_NEAREST_MIPMAP_NEAREST | gl::GL_LINEAR_MIPMAP_NEAREST => Some(Filter::Nearest),
            gl::GL_NEAREST_MIPMAP_LINEAR | gl::GL_LINEAR_MIPMAP_LINEAR => Some(Filter::Linear),
            _ => None,
        };
        let wrap = self.wrap.map(|w| match w {
            gl::GL_CLAMP => Wrap::Clamp,
            gl::GL_CLAMP_TO_EDGE => Wrap::ClampToEdge,
            gl::GL_CLAMP_TO_BORDER => Wrap::ClampToBorder,
            gl::GL_MIRRORED_REPEAT => Wrap::MirroredRepeat,
            _ => Wrap::Repeat,
        });
        Sampler {
            min_filter: MinFilter { texel: filter(self.min_filter), mipmap },
            mag_filter: filter(self.mag_filter),
            wrap,
            border_color: self.border_color,
            lod: self.lod,
            levels: self.levels.map(|l| l.max(0) as u32),
            compare: (self.compare_mode == gl::GL_COMPARE_R_TO_TEXTURE)
                .then(|| COMPARE.parse(self.compare_func).unwrap_or(CompareFunc::LessEqual)),
            depth_mode: match self.depth_mode {
                gl::GL_INTENSITY => DepthMode::Intensity,
                gl::GL_ALPHA => DepthMode::Alpha,
                _ => DepthMode::Luminance,
            },
        }
    }

    /// Sets `pname` from `values` (already converted to floats); the error of section 3.8.4
    /// otherwise. Returns whether anything changed.
    pub(super) fn set(&mut self, pname: GLenum, v: &[f64]) -> Result<(), GLenum> {
        let first = *v.first().ok_or(gl::GL_INVALID_ENUM)?;
        let as_enum = first as GLenum;
        let pick = |allowed: &[GLenum]| if allowed.contains(&as_enum) { Ok(as_enum) } else { Err(gl::GL_INVALID_ENUM) };
        match pname {
            gl::GL_TEXTURE_MIN_FILTER => {
                self.min_filter = pick(&[
                    gl::GL_NEAREST,
                    gl::GL_LINEAR,
                    gl::GL_NEAREST_MIPMAP_NEAREST,
                    gl::GL_LINEAR_MIPMAP_NEAREST,
                    gl::GL_NEAREST_MIPMAP_LINEAR,
                    gl::GL_LINEAR_MIPMAP_LINEAR,
                ])?
            }
            gl::GL_TEXTURE_MAG_FILTER => self.mag_filter = pick(&[gl::GL_NEAREST, gl::GL_LINEAR])?,
            gl::GL_TEXTURE_WRAP_S | gl::GL_TEXTURE_WRAP_T | gl::GL_TEXTURE_WRAP_R => {
                let i = [gl::GL_TEXTURE_WRAP_S, gl::GL_TEXTURE_WRAP_T, gl::GL_TEXTURE_WRAP_R].iter().position(|&p| p == pname).unwrap_or(0);
                self.wrap[i] = pick(&[gl::GL_CLAMP, gl::GL_REPEAT, gl::GL_CLAMP_TO_EDGE, gl::GL_CLAMP_TO_BORDER, gl::GL_MIRRORED_REPEAT])?;
            }
            gl::GL_TEXTURE_BORDER_COLOR => {
                let c: [f64; 4] = v.try_into().map_err(|_| gl::GL_INVALID_ENUM)?;
                self.border_color = c.map(|x| x.clamp(0.0, 1.0) as f32);
                self.border_integers = None;
            }
            gl::GL_TEXTURE_PRIORITY => self.priority = first.clamp(0.0, 1.0) as f32,
            gl::GL_TEXTURE_MIN_LOD => self.lod[0] = first as f32,
            gl::GL_TEXTURE_MAX_LOD => self.lod[1] = first as f32,
            gl::GL_TEXTURE_BASE_LEVEL | gl::GL_TEXTURE_MAX_LEVEL => {
                if first < 0.0 {
                    return Err(gl::GL_INVALID_VALUE);
                }
                let i = usize::from(pname == gl::GL_TEXTURE_MAX_LEVEL);
                self.levels[i] = first.round().min(f64::from(i32::MAX)) as i32;
            }
            gl::GL_GENERATE_MIPMAP => self.generate_mipmap = first != 0.0,
            gl::GL_DEPTH_TEXTURE_MODE => self.depth_mode = pick(&[gl::GL_LUMINANCE, gl::GL_INTENSITY, gl::GL_ALPHA])?,
            gl::GL_TEXTURE_COMPARE_MODE => self.compare_mode = pick(&[gl::GL_NONE, gl::GL_COMPARE_R_TO_TEXTURE])?,
            gl::GL_TEXTURE_COMPARE_FUNC => {
                self.compare_func = COMPARE.parse(as_enum).map(|_| as_enum).ok_or(gl::GL_INVALID_ENUM)?
            }
            _ => return Err(gl::GL_INVALID_ENUM),
        }
        Ok(())
    }

    /// The value of `pname` (table 6.16), `None` for an unknown name.
    pub fn get(&self, pname: GLenum) -> Option<Value> {
        Some(match pname {
            gl::GL_TEXTURE_MIN_FILTER => Value::int(self.min_filter),
            gl::GL_TEXTURE_MAG_FILTER => Value::int(self.mag_filter),
            gl::GL_TEXTURE_WRAP_S => Value::int(self.wrap[0]),
            gl::GL_TEXTURE_WRAP_T => Value::int(self.wrap[1]),
            gl::GL_TEXTURE_WRAP_R => Value::int(self.wrap[2]),
            gl::GL_TEXTURE_BORDER_COLOR => Value::normalized(&self.border_color),
            gl::GL_TEXTURE_PRIORITY => Value::normalized(&[self.priority]),
            gl::GL_TEXTURE_RESIDENT => Value::bool(true),
            gl::GL_TEXTURE_MIN_LOD => Value::float(self.lod[0]),
            gl::GL_TEXTURE_MAX_LOD => Value::float(self.lod[1]),
            gl::GL_TEXTURE_BASE_LEVEL => Value::int(self.levels[0]),
            gl::GL_TEXTURE_MAX_LEVEL => Value::int(self.levels[1]),
            gl::GL_GENERATE_MIPMAP => Value::bool(self.generate_mipmap),
            gl::GL_DEPTH_TEXTURE_MODE => Value::int(self.depth_mode),
            gl::GL_TEXTURE_COMPARE_MODE => Value::int(self.compare_mode),
            gl::GL_TEXTURE_COMPARE_FUNC => Value::int(self.compare_func),
            _ => return None,
        })
    }
}

/// Values `glTexParameter*v`/`glGetTexParameter*v` read or write for `pname`.
pub(super) fn param_count(pname: GLenum) -> usize {
    if pname == gl::GL_TEXTURE_BORDER_COLOR { 4 } else { 1 }
}

impl Context {
    /// Sets a parameter of the texture bound to `target`.
    pub(super) fn tex_parameter(&mut self, target: GLenum, pname: GLenum, values: &[f64], command: &'static str) {
        let Some(t) = Target::from_gl(target) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        if let Err(e) = self.with_bound_texture(t, |obj| {
            let mut params = obj.params;
            params.set(pname, values)?;
            if t == Target::Rect {
                params.check_rect()?;
            }
            if params != obj.params {
                obj.params = params;
                obj.touch();
            }
            Ok(())
        }) {
            self.set_error_in(e, command);
        }
    }

    /// `glTexParameterf`: `GL_INVALID_ENUM` for an unknown target or name or a bad enum value;
    /// `GL_INVALID_VALUE` for a negative base or max level. `GL_TEXTURE_BORDER_COLOR` becomes
    /// (param, 0, 0, 0) (see [`scalar_as_vector`]).
    pub fn glTexParameterf(&mut self, target: GLenum, pname: GLenum, param: GLfloat) {
        self.tex_parameter(target, pname, &scalar_as_vector(f64::from(param), param_count(pname)), "glTexParameterf");
    }

    /// `glTexParameteri`: as `glTexParameterf`; a border colour is normalized like
    /// `glTexParameteriv`'s.
    pub fn glTexParameteri(&mut self, target: GLenum, pname: GLenum, param: GLint) {
        let value = if pname == gl::GL_TEXTURE_BORDER_COLOR { f64::from(norm_i32(param)) } else { f64::from(param) };
        self.tex_parameter(target, pname, &scalar_as_vector(value, param_count(pname)), "glTexParameteri");
    }

    /// `glTexParameterfv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname` (4 for the border colour, else 1).
    pub unsafe fn glTexParameterfv(&mut self, target: GLenum, pname: GLenum, params: *const GLfloat) {
        let Some(v) = (unsafe { read_slice(params, param_count(pname)) }) else { return self.null_pointer("glTexParameterfv") };
        let v: Vec<f64> = v.into_iter().map(f64::from).collect();
        self.tex_parameter(target, pname, &v, "glTexParameterfv");
    }

    /// `glTexParameteriv`: the border colour is normalized (table 2.9).
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glTexParameteriv(&mut self, target: GLenum, pname: GLenum, params: *const GLint) {
        let Some(v) = (unsafe { read_slice(params, param_count(pname)) }) else { return self.null_pointer("glTexParameteriv") };
        let color = pname == gl::GL_TEXTURE_BORDER_COLOR;
        let v: Vec<f64> = v.into_iter().map(|x| if color { f64::from(norm_i32(x)) } else { f64::from(x) }).collect();
        self.tex_parameter(target, pname, &v, "glTexParameteriv");
    }

    /// `glTexParameterfv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexParameterfv`].
    pub unsafe fn compile_glTexParameterfv(&mut self, target: GLenum, pname: GLenum, params: *const GLfloat) {
        let v = unsafe { read_slice(params, param_count(pname)) };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| unsafe {
            ctx.glTexParameterfv(target, pname, v.as_ref().map_or(std::ptr::null(), |v| v.as_ptr()))
        })));
    }

    /// `glTexParameteriv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexParameteriv`].
    pub unsafe fn compile_glTexParameteriv(&mut self, target: GLenum, pname: GLenum, params: *const GLint) {
        let v = unsafe { read_slice(params, param_count(pname)) };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| unsafe {
            ctx.glTexParameteriv(target, pname, v.as_ref().map_or(std::ptr::null(), |v| v.as_ptr()))
        })));
    }

    /// The value of a parameter of the texture bound to `target`, raising `GL_INVALID_ENUM`
    /// for an unknown target or name.
    pub(super) fn tex_parameter_value(&mut self, target: GLenum, pname: GLenum, command: &'static str) -> Option<Value> {
        let value = Target::from_gl(target).and_then(|t| self.with_bound_texture(t, |obj| obj.params.get(pname)));
        if value.is_none() {
            self.set_error_in(gl::GL_INVALID_ENUM, command);
        }
        value
    }

    /// `glGetTexParameterfv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetTexParameterfv(&mut self, target: GLenum, pname: GLenum, params: *mut GLfloat) {
        if let Some(v) = self.tex_parameter_value(target, pname, "glGetTexParameterfv") {
            let f: Vec<f32> = v.to_doubles().into_iter().map(|x| x as f32).collect();
            unsafe { write_slice(params, &f) }
        }
    }

    /// `glGetTexParameteriv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetTexParameteriv(&mut self, target: GLenum, pname: GLenum, params: *mut GLint) {
        if let Some(v) = self.tex_parameter_value(target, pname, "glGetTexParameteriv") {
            unsafe { write_slice(params, &v.to_ints()) }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn parameters_round_trip_and_check() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 5);
        let version = ctx.with_bound_texture(super::Target::D2, |o| o.version);
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_WRAP_T, gl::GL_MIRRORED_REPEAT as i32);
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_LINEAR as i32);
        ctx.glTexParameterf(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAX_LOD, 3.5);
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_GENERATE_MIPMAP, 1);
        let border = [0.5f32, 2.0, -1.0, 1.0];
        unsafe { dispatch::glTexParameterfv(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, border.as_ptr()) };
        assert!(ctx.with_bound_texture(super::Target::D2, |o| o.version) > version);
        let mut i = [0i32; 4];
        unsafe { ctx.glGetTexParameteriv(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_WRAP_T, i.as_mut_ptr()) };
        assert_eq!(i[0], gl::GL_MIRRORED_REPEAT as i32);
        let mut f = [0.0f32; 4];
        unsafe { ctx.glGetTexParameterfv(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, f.as_mut_ptr()) };
        assert_eq!(f, [0.5, 1.0, 0.0, 1.0]);
        unsafe { ctx.glGetTexParameterfv(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAX_LOD, f.as_mut_ptr()) };
        assert_eq!(f[0], 3.5);
        unsafe { ctx.glGetTexParameteriv(gl::GL_TEXTURE_2D, gl::GL_GENERATE_MIPMAP, i.as_mut_ptr()) };
        assert_eq!(i[0], 1);
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_LINEAR_MIPMAP_LINEAR as i32);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BASE_LEVEL, -1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glTexParameterf(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, 0.5);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        let mut border = [9.0f32; 4];
        unsafe { ctx.glGetTexParameterfv(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, border.as_mut_ptr()) };
        assert_eq!(border, [0.5, 0.0, 0.0, 0.0]);
        ctx.glTexParameteri(gl::GL_TEXTURE_CUBE_MAP_POSITIVE_X, gl::GL_TEXTURE_MIN_FILTER, gl::GL_LINEAR as i32);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        let s = ctx.with_bound_texture(super::Target::D2, |o| o.params.sampler());
        assert_eq!(s.wrap[1], crate::frame::texture::Wrap::MirroredRepeat);
        assert_eq!(s.min_filter.mipmap, None);
    }

    #[test]
    fn every_compare_function_is_accepted() {
        use crate::frame::texture::CompareFunc;
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_COMPARE_MODE, gl::GL_COMPARE_R_TO_TEXTURE as i32);
        for (func, expected) in [(gl::GL_NOTEQUAL, CompareFunc::NotEqual), (gl::GL_NEVER, CompareFunc::Never)] {
            ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_COMPARE_FUNC, func as i32);
            let mut read = 0;
            unsafe { ctx.glGetTexParameteriv(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_COMPARE_FUNC, &mut read) };
            assert_eq!(read, func as i32);
            let sampler = ctx.with_bound_texture(super::Target::D2, |o| o.params.sampler());
            assert_eq!(sampler.compare, Some(expected));
        }
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_COMPARE_FUNC, gl::GL_FRONT as i32);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }
}

#[cfg(test)]
mod rectangle_tests {
    use crate::frame::texture::TextureKind;
    use crate::translate::{Context, dispatch, gl};

    fn int(ctx: &mut Context, pname: gl::GLenum) -> i32 {
        let mut v = 0;
        unsafe { ctx.glGetTexParameteriv(gl::GL_TEXTURE_RECTANGLE_ARB, pname, &mut v) };
        v
    }

    fn image(ctx: &mut Context, target: gl::GLenum, level: i32, w: i32, h: i32, border: i32) -> gl::GLenum {
        unsafe { dispatch::glTexImage2D(ctx, target, level, gl::GL_RGBA as i32, w, h, border, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        ctx.glGetError()
    }

    /// `GL_ARB_texture_rectangle`: binding, initial parameters, the parameters and images it
    /// refuses, the proxy, the limit, and the enable's priority over 2D.
    #[test]
    fn rectangle_textures_state_errors_and_queries() {
        let (mut ctx, _) = Context::with_recording();
        let rect = gl::GL_TEXTURE_RECTANGLE_ARB;
        ctx.glBindTexture(rect, 3);
        assert_eq!(ctx.query(gl::GL_TEXTURE_BINDING_RECTANGLE_ARB).unwrap().to_ints(), [3]);
        assert_eq!(ctx.query(gl::GL_MAX_RECTANGLE_TEXTURE_SIZE_ARB).unwrap().to_ints(), [8192]);
        assert_eq!(int(&mut ctx, gl::GL_TEXTURE_MIN_FILTER), gl::GL_LINEAR as i32);
        assert_eq!(int(&mut ctx, gl::GL_TEXTURE_WRAP_S), gl::GL_CLAMP_TO_EDGE as i32);
        for (pname, value, error) in [
            (gl::GL_TEXTURE_WRAP_S, gl::GL_REPEAT, gl::GL_INVALID_ENUM),
            (gl::GL_TEXTURE_WRAP_T, gl::GL_MIRRORED_REPEAT, gl::GL_INVALID_ENUM),
            (gl::GL_TEXTURE_MIN_FILTER, gl::GL_LINEAR_MIPMAP_LINEAR, gl::GL_INVALID_ENUM),
            (gl::GL_TEXTURE_BASE_LEVEL, 1, gl::GL_INVALID_VALUE),
            (gl::GL_TEXTURE_WRAP_S, gl::GL_CLAMP, gl::GL_NO_ERROR),
            (gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST, gl::GL_NO_ERROR),
        ] {
            ctx.glTexParameteri(rect, pname, value as i32);
            assert_eq!(ctx.glGetError(), error, "{pname:#x} = {value:#x}");
        }
        assert_eq!(int(&mut ctx, gl::GL_TEXTURE_WRAP_S), gl::GL_CLAMP as i32);
        assert_eq!(int(&mut ctx, gl::GL_TEXTURE_BASE_LEVEL), 0, "refused values are not kept");
        assert_eq!(image(&mut ctx, rect, 1, 4, 4, 0), gl::GL_INVALID_VALUE, "one level");
        assert_eq!(image(&mut ctx, rect, 0, 6, 6, 1), gl::GL_INVALID_VALUE, "no border");
        assert_eq!(image(&mut ctx, gl::GL_PROXY_TEXTURE_RECTANGLE_ARB, 0, 8192, 1, 0), gl::GL_NO_ERROR);
        let mut w = 0;
        unsafe { ctx.glGetTexLevelParameteriv(gl::GL_PROXY_TEXTURE_RECTANGLE_ARB, 0, gl::GL_TEXTURE_WIDTH, &mut w) };
        assert_eq!(w, 8192);
        unsafe { dispatch::glCompressedTexImage2D(&mut ctx, rect, 0, gl::GL_COMPRESSED_RGBA_S3TC_DXT1_EXT, 4, 4, 0, 8, [0u8; 8].as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glGenerateMipmapEXT(rect);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);

        assert_eq!(image(&mut ctx, rect, 0, 5, 3, 0), gl::GL_NO_ERROR);
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 4);
        assert_eq!(image(&mut ctx, gl::GL_TEXTURE_2D, 0, 2, 2, 0), gl::GL_NO_ERROR);
        ctx.glEnable(gl::GL_TEXTURE_2D);
        ctx.glEnable(rect);
        assert_eq!(ctx.glIsEnabled(rect), 1);
        let snapshot = ctx.texture_snapshot()[0].clone().expect("a complete rectangle texture");
        assert_eq!((snapshot.content.kind, snapshot.id), (TextureKind::Rect, 3), "rectangle before 2D");
        ctx.glBindTexture(rect, 4);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "a 2D texture's name");

        // A framebuffer object takes level 0 of a rectangle texture.
        let mut fbo = 0;
        unsafe { dispatch::glGenFramebuffersEXT(&mut ctx, 1, &mut fbo) };
        ctx.glBindFramebufferEXT(gl::GL_FRAMEBUFFER_EXT, fbo);
        ctx.glFramebufferTexture2DEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, rect, 3, 1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glFramebufferTexture2DEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, rect, 3, 0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(ctx.glCheckFramebufferStatusEXT(gl::GL_FRAMEBUFFER_EXT), gl::GL_FRAMEBUFFER_COMPLETE_EXT);
    }
}
