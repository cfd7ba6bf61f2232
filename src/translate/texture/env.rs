//! Texture environments (OpenGL 1.5 section 3.8.13, table 6.18): `glTexEnv{if}{v}` and
//! `glGetTexEnv{if}v` for each texture unit — the function (`MODULATE`, `REPLACE`, `DECAL`,
//! `BLEND`, `ADD`, `COMBINE`), the combiner's functions, sources, operands and scales, the
//! environment colour, and the unit's level-of-detail bias; and each unit's point sprite
//! coordinate replacement (`GL_COORD_REPLACE` of `GL_POINT_SPRITE`, OpenGL 2.0 section 3.3),
//! which belongs to the point state.

use super::super::Context;
use super::super::convert::{norm_i32, read_slice, write_slice};
use super::super::get::Value;
use super::super::gl::{self, GLenum, GLfloat, GLint};
use super::super::limits::MAX_TEXTURE_UNITS;
use super::super::lists::ListOp;

/// Largest `GL_TEXTURE_LOD_BIAS` magnitude (`GL_MAX_TEXTURE_LOD_BIAS`).
pub const MAX_TEXTURE_LOD_BIAS: f32 = 16.0;

/// The environment of one texture unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexEnv {
    /// `GL_TEXTURE_ENV_MODE`.
    pub mode: GLenum,
    /// `GL_TEXTURE_ENV_COLOR`.
    pub color: [f32; 4],
    /// `GL_COMBINE_RGB`.
    pub combine_rgb: GLenum,
    /// `GL_COMBINE_ALPHA`.
    pub combine_alpha: GLenum,
    /// `GL_SOURCE0_RGB` ... `GL_SOURCE2_RGB`.
    pub source_rgb: [GLenum; 3],
    /// `GL_SOURCE0_ALPHA` ... `GL_SOURCE2_ALPHA`.
    pub source_alpha: [GLenum; 3],
    /// `GL_OPERAND0_RGB` ... `GL_OPERAND2_RGB`.
    pub operand_rgb: [GLenum; 3],
    /// `GL_OPERAND0_ALPHA` ... `GL_OPERAND2_ALPHA`.
    pub operand_alpha: [GLenum; 3],
    /// `GL_RGB_SCALE`.
    pub rgb_scale: f32,
    /// `GL_ALPHA_SCALE`.
    pub alpha_scale: f32,
    /// `GL_TEXTURE_LOD_BIAS` of `GL_TEXTURE_FILTER_CONTROL`.
    pub lod_bias: f32,
}

impl Default for TexEnv {
    fn default() -> TexEnv {
        TexEnv {
            mode: gl::GL_MODULATE,
            color: [0.0; 4],
            combine_rgb: gl::GL_MODULATE,
            combine_alpha: gl::GL_MODULATE,
            source_rgb: [gl::GL_TEXTURE, gl::GL_PREVIOUS, gl::GL_CONSTANT],
            source_alpha: [gl::GL_TEXTURE, gl::GL_PREVIOUS, gl::GL_CONSTANT],
            operand_rgb: [gl::GL_SRC_COLOR, gl::GL_SRC_COLOR, gl::GL_SRC_ALPHA],
            operand_alpha: [gl::GL_SRC_ALPHA; 3],
            rgb_scale: 1.0,
            alpha_scale: 1.0,
            lod_bias: 0.0,
        }
    }
}

/// Which field an environment name addresses.
#[derive(Clone, Copy)]
enum Field {
    Mode,
    Color,
    CombineRgb,
    CombineAlpha,
    SourceRgb(usize),
    SourceAlpha(usize),
    OperandRgb(usize),
    OperandAlpha(usize),
    RgbScale,
    AlphaScale,
    LodBias,
}

fn field_of(target: GLenum, pname: GLenum) -> Option<Field> {
    use Field::*;
    if target == gl::GL_TEXTURE_FILTER_CONTROL {
        return (pname == gl::GL_TEXTURE_LOD_BIAS).then_some(LodBias);
    }
    if target != gl::GL_TEXTURE_ENV {
        return None;
    }
    let idx = |first: GLenum| (pname - first) as usize;
    Some(match pname {
        gl::GL_TEXTURE_ENV_MODE => Mode,
        gl::GL_TEXTURE_ENV_COLOR => Color,
        gl::GL_COMBINE_RGB => CombineRgb,
        gl::GL_COMBINE_ALPHA => CombineAlpha,
        gl::GL_SOURCE0_RGB..=gl::GL_SOURCE2_RGB => SourceRgb(idx(gl::GL_SOURCE0_RGB)),
        gl::GL_SOURCE0_ALPHA..=gl::GL_SOURCE2_ALPHA => SourceAlpha(idx(gl::GL_SOURCE0_ALPHA)),
        gl::GL_OPERAND0_RGB..=gl::GL_OPERAND2_RGB => OperandRgb(idx(gl::GL_OPERAND0_RGB)),
        gl::GL_OPERAND0_ALPHA..=gl::GL_OPERAND2_ALPHA => OperandAlpha(idx(gl::GL_OPERAND0_ALPHA)),
        gl::GL_RGB_SCALE => RgbScale,
        gl::GL_ALPHA_SCALE => AlphaScale,
        _ => return None,
    })
}

/// Whether `src` is a combiner source: `TEXTURE`, `CONSTANT`, `PRIMARY_COLOR`, `PREVIOUS`, or
/// `TEXTUREn` of an existing unit (crossbar, OpenGL 1.4).
fn is_source(src: GLenum) -> bool {
    matches!(src, gl::GL_TEXTURE | gl::GL_CONSTANT | gl::GL_PRIMARY_COLOR | gl::GL_PREVIOUS)
        || super::super::texunit::unit_index(src).is_some_and(|u| u < MAX_TEXTURE_UNITS)
}

impl TexEnv {
    /// Sets a field: `GL_INVALID_ENUM` for a value not allowed, `GL_INVALID_VALUE` for a scale
    /// other than 1, 2, 4.
    fn set(&mut self, field: Field, v: &[f32]) -> Result<(), GLenum> {
        let first = *v.first().ok_or(gl::GL_INVALID_ENUM)?;
        let e = first as GLenum;
        let pick = |ok: bool| if ok { Ok(e) } else { Err(gl::GL_INVALID_ENUM) };
        let scale = || if [1.0, 2.0, 4.0].contains(&first) { Ok(first) } else { Err(gl::GL_INVALID_VALUE) };
        let rgb_fn = [gl::GL_REPLACE, gl::GL_MODULATE, gl::GL_ADD, gl::GL_ADD_SIGNED, gl::GL_INTERPOLATE, gl::GL_SUBTRACT];
        match field {
            Field::Mode => self.mode = pick(matches!(e, gl::GL_MODULATE | gl::GL_REPLACE | gl::GL_DECAL | gl::GL_BLEND | gl::GL_ADD | gl::GL_COMBINE))?,
            Field::Color => self.color = <[f32; 4]>::try_from(v).map_err(|_| gl::GL_INVALID_ENUM)?.map(|c| c.clamp(0.0, 1.0)),
            Field::CombineRgb => self.combine_rgb = pick(rgb_fn.contains(&e) || matches!(e, gl::GL_DOT3_RGB | gl::GL_DOT3_RGBA))?,
            Field::CombineAlpha => self.combine_alpha = pick(rgb_fn.contains(&e))?,
            Field::SourceRgb(i) => self.source_rgb[i] = pick(is_source(e))?,
            Field::SourceAlpha(i) => self.source_alpha[i] = pick(is_source(e))?,
            Field::OperandRgb(i) => {
                self.operand_rgb[i] = pick(matches!(e, gl::GL_SRC_COLOR | gl::GL_ONE_MINUS_SRC_COLOR | gl::GL_SRC_ALPHA | gl::GL_ONE_MINUS_SRC_ALPHA))?
            }
            Field::OperandAlpha(i) => self.operand_alpha[i] = pick(matches!(e, gl::GL_SRC_ALPHA | gl::GL_ONE_MINUS_SRC_ALPHA))?,
            Field::RgbScale => self.rgb_scale = scale()?,
            Field::AlphaScale => self.alpha_scale = scale()?,
            Field::LodBias => self.lod_bias = first.clamp(-MAX_TEXTURE_LOD_BIAS, MAX_TEXTURE_LOD_BIAS),
        }
        Ok(())
    }

    fn get(&self, field: Field) -> Value {
        match field {
            Field::Mode => Value::int(self.mode),
            Field::Color => Value::normalized(&self.color),
            Field::CombineRgb => Value::int(self.combine_rgb),
            Field::CombineAlpha => Value::int(self.combine_alpha),
            Field::SourceRgb(i) => Value::int(self.source_rgb[i]),
            Field::SourceAlpha(i) => Value::int(self.source_alpha[i]),
            Field::OperandRgb(i) => Value::int(self.operand_rgb[i]),
            Field::OperandAlpha(i) => Value::int(self.operand_alpha[i]),
            Field::RgbScale => Value::float(self.rgb_scale),
            Field::AlphaScale => Value::float(self.alpha_scale),
            Field::LodBias => Value::float(self.lod_bias),
        }
    }
}

/// Values of an environment name (4 for the colour).
fn env_count(pname: GLenum) -> usize {
    if pname == gl::GL_TEXTURE_ENV_COLOR { 4 } else { 1 }
}

impl Context {
    fn tex_env(&mut self, target: GLenum, pname: GLenum, values: &[f32], command: &'static str) {
        if target == gl::GL_POINT_SPRITE {
            return self.set_coord_replace(pname, values, command);
        }
        let Some(field) = field_of(target, pname) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        let unit = self.active_texture_unit();
        if let Err(e) = self.texture.env[unit].set(field, values) {
            self.set_error_in(e, command);
        }
    }

    /// `glTexEnvf`: `GL_INVALID_ENUM` for an unknown target or name (or the colour, which
    /// needs the vector form) and for values not allowed; `GL_INVALID_VALUE` for a scale
    /// other than 1, 2 or 4.
    pub fn glTexEnvf(&mut self, target: GLenum, pname: GLenum, param: GLfloat) {
        self.tex_env(target, pname, &[param], "glTexEnvf");
    }

    /// `glTexEnvi`.
    pub fn glTexEnvi(&mut self, target: GLenum, pname: GLenum, param: GLint) {
        self.tex_env(target, pname, &[param as GLfloat], "glTexEnvi");
    }

    /// `glTexEnvfv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glTexEnvfv(&mut self, target: GLenum, pname: GLenum, params: *const GLfloat) {
        let Some(v) = (unsafe { read_slice(params, env_count(pname)) }) else { return self.null_pointer("glTexEnvfv") };
        self.tex_env(target, pname, &v, "glTexEnvfv");
    }

    /// `glTexEnviv`: the colour is normalized (table 2.9).
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glTexEnviv(&mut self, target: GLenum, pname: GLenum, params: *const GLint) {
        let Some(v) = (unsafe { read_slice(params, env_count(pname)) }) else { return self.null_pointer("glTexEnviv") };
        let color = pname == gl::GL_TEXTURE_ENV_COLOR;
        let v: Vec<f32> = v.into_iter().map(|x| if color { norm_i32(x) } else { x as f32 }).collect();
        self.tex_env(target, pname, &v, "glTexEnviv");
    }

    /// `glTexEnvfv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexEnvfv`].
    pub unsafe fn compile_glTexEnvfv(&mut self, target: GLenum, pname: GLenum, params: *const GLfloat) {
        let v = unsafe { read_slice(params, env_count(pname)) };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| unsafe {
            ctx.glTexEnvfv(target, pname, v.as_ref().map_or(std::ptr::null(), |v| v.as_ptr()))
        })));
    }

    /// `glTexEnviv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexEnviv`].
    pub unsafe fn compile_glTexEnviv(&mut self, target: GLenum, pname: GLenum, params: *const GLint) {
        let v = unsafe { read_slice(params, env_count(pname)) };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| unsafe {
            ctx.glTexEnviv(target, pname, v.as_ref().map_or(std::ptr::null(), |v| v.as_ptr()))
        })));
    }

    /// `GL_COORD_REPLACE` of the active unit (`GL_ARB_point_sprite`, the one name of the
    /// `GL_POINT_SPRITE` environment, else `GL_INVALID_ENUM`): `GL_FALSE` or `GL_TRUE`, else
    /// `GL_INVALID_VALUE` (as Mesa).
    fn set_coord_replace(&mut self, pname: GLenum, values: &[f32], command: &'static str) {
        if pname != gl::GL_COORD_REPLACE {
            return self.set_error_in(gl::GL_INVALID_ENUM, command);
        }
        let bit = 1 << self.active_texture_unit();
        let sprite = &mut self.fixed_mut().raster.sprite;
        match values.first() {
            Some(0.0) => sprite.coord_replace &= !bit,
            Some(1.0) => sprite.coord_replace |= bit,
            _ => self.set_error_in(gl::GL_INVALID_VALUE, command),
        }
    }

    fn tex_env_value(&mut self, target: GLenum, pname: GLenum, command: &'static str) -> Option<Value> {
        if target == gl::GL_POINT_SPRITE && pname == gl::GL_COORD_REPLACE {
            return Some(Value::bool(self.fixed.raster.sprite.coord_replace & (1 << self.active_texture_unit()) != 0));
        }
        let Some(field) = field_of(target, pname) else {
            self.set_error_in(gl::GL_INVALID_ENUM, command);
            return None;
        };
        Some(self.texture.env[self.active_texture_unit()].get(field))
    }

    /// `glGetTexEnvfv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetTexEnvfv(&mut self, target: GLenum, pname: GLenum, params: *mut GLfloat) {
        if let Some(v) = self.tex_env_value(target, pname, "glGetTexEnvfv") {
            unsafe { write_slice(params, &v.to_doubles().iter().map(|&x| x as f32).collect::<Vec<_>>()) }
        }
    }

    /// `glGetTexEnviv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetTexEnviv(&mut self, target: GLenum, pname: GLenum, params: *mut GLint) {
        if let Some(v) = self.tex_env_value(target, pname, "glGetTexEnviv") {
            unsafe { write_slice(params, &v.to_ints()) }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn environment_round_trips_per_unit() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glActiveTexture(gl::GL_TEXTURE1);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_COMBINE as i32);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_COMBINE_RGB, gl::GL_DOT3_RGB as i32);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_SOURCE1_ALPHA, gl::GL_TEXTURE0 as i32);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_OPERAND2_RGB, gl::GL_ONE_MINUS_SRC_ALPHA as i32);
        ctx.glTexEnvf(gl::GL_TEXTURE_ENV, gl::GL_RGB_SCALE, 4.0);
        ctx.glTexEnvf(gl::GL_TEXTURE_FILTER_CONTROL, gl::GL_TEXTURE_LOD_BIAS, -1.5);
        let color = [0.25f32, 0.5, 2.0, 1.0];
        unsafe { dispatch::glTexEnvfv(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_COLOR, color.as_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        let mut i = 0;
        let mut f = [0.0f32; 4];
        unsafe {
            ctx.glGetTexEnviv(gl::GL_TEXTURE_ENV, gl::GL_COMBINE_RGB, &mut i);
            assert_eq!(i as u32, gl::GL_DOT3_RGB);
            ctx.glGetTexEnviv(gl::GL_TEXTURE_ENV, gl::GL_SOURCE1_ALPHA, &mut i);
            assert_eq!(i as u32, gl::GL_TEXTURE0);
            ctx.glGetTexEnviv(gl::GL_TEXTURE_ENV, gl::GL_OPERAND2_RGB, &mut i);
            assert_eq!(i as u32, gl::GL_ONE_MINUS_SRC_ALPHA);
            ctx.glGetTexEnvfv(gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_COLOR, f.as_mut_ptr());
            assert_eq!(f, [0.25, 0.5, 1.0, 1.0]);
            ctx.glGetTexEnvfv(gl::GL_TEXTURE_ENV, gl::GL_RGB_SCALE, f.as_mut_ptr());
            assert_eq!(f[0], 4.0);
            ctx.glGetTexEnvfv(gl::GL_TEXTURE_FILTER_CONTROL, gl::GL_TEXTURE_LOD_BIAS, f.as_mut_ptr());
            assert_eq!(f[0], -1.5);
        }
        assert_eq!(ctx.texture.env[0].mode, gl::GL_MODULATE);
        ctx.glTexEnvf(gl::GL_TEXTURE_ENV, gl::GL_ALPHA_SCALE, 3.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_COMBINE_ALPHA, gl::GL_DOT3_RGB as i32);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_LOD_BIAS, 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glTexEnvf(gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_COLOR, 1.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }
}

/// Conversion of the environment to the renderer's types.
mod convert {
    use super::super::super::gl::{self, GLenum};
    use super::TexEnv;
    use crate::frame::texture::{CombineFn, CombineOperand, CombineSource, EnvMode, TextureEnv};

    fn mode(m: GLenum) -> EnvMode {
        match m {
            gl::GL_REPLACE => EnvMode::Replace,
            gl::GL_DECAL => EnvMode::Decal,
            gl::GL_BLEND => EnvMode::Blend,
            gl::GL_ADD => EnvMode::Add,
            gl::GL_COMBINE => EnvMode::Combine,
            _ => EnvMode::Modulate,
        }
    }

    fn combine(f: GLenum) -> CombineFn {
        match f {
            gl::GL_REPLACE => CombineFn::Replace,
            gl::GL_ADD => CombineFn::Add,
            gl::GL_ADD_SIGNED => CombineFn::AddSigned,
            gl::GL_INTERPOLATE => CombineFn::Interpolate,
            gl::GL_SUBTRACT => CombineFn::Subtract,
            gl::GL_DOT3_RGB => CombineFn::Dot3Rgb,
            gl::GL_DOT3_RGBA => CombineFn::Dot3Rgba,
            _ => CombineFn::Modulate,
        }
    }

    fn source(s: GLenum) -> CombineSource {
        match s {
            gl::GL_CONSTANT => CombineSource::Constant,
            gl::GL_PRIMARY_COLOR => CombineSource::PrimaryColor,
            gl::GL_PREVIOUS => CombineSource::Previous,
            gl::GL_TEXTURE => CombineSource::Texture,
            unit => CombineSource::TextureUnit(unit.saturating_sub(gl::GL_TEXTURE0).min(u32::from(u8::MAX)) as u8),
        }
    }

    fn operand(o: GLenum) -> CombineOperand {
        match o {
            gl::GL_ONE_MINUS_SRC_COLOR => CombineOperand::OneMinusSrcColor,
            gl::GL_SRC_ALPHA => CombineOperand::SrcAlpha,
            gl::GL_ONE_MINUS_SRC_ALPHA => CombineOperand::OneMinusSrcAlpha,
            _ => CombineOperand::SrcColor,
        }
    }

    impl TexEnv {
        /// The environment as the renderer applies it.
        pub fn to_frame(&self) -> TextureEnv {
            TextureEnv {
                mode: mode(self.mode),
                color: self.color,
                combine_rgb: combine(self.combine_rgb),
                combine_alpha: combine(self.combine_alpha),
                source_rgb: self.source_rgb.map(source),
                source_alpha: self.source_alpha.map(source),
                operand_rgb: self.operand_rgb.map(operand),
                operand_alpha: self.operand_alpha.map(operand),
                scale: [self.rgb_scale, self.alpha_scale],
                lod_bias: self.lod_bias,
            }
        }
    }
}

#[cfg(test)]
mod snapshot_tests {
    use crate::frame::texture::{CombineFn, CombineOperand, CombineSource, EnvMode};
    use crate::translate::{Context, gl};

    #[test]
    fn environment_snapshot_uses_frame_types() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glActiveTexture(gl::GL_TEXTURE1);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_COMBINE as i32);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_COMBINE_ALPHA, gl::GL_INTERPOLATE as i32);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_SOURCE2_RGB, gl::GL_TEXTURE3 as i32);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_OPERAND0_ALPHA, gl::GL_ONE_MINUS_SRC_ALPHA as i32);
        ctx.glTexEnvf(gl::GL_TEXTURE_ENV, gl::GL_ALPHA_SCALE, 2.0);
        let s = ctx.texture.env.map(|e| e.to_frame());
        assert_eq!(s[0].mode, EnvMode::Modulate);
        assert_eq!((s[1].mode, s[1].combine_alpha, s[1].combine_rgb), (EnvMode::Combine, CombineFn::Interpolate, CombineFn::Modulate));
        assert_eq!(s[1].source_rgb, [CombineSource::Texture, CombineSource::Previous, CombineSource::TextureUnit(3)]);
        assert_eq!(s[1].operand_alpha[0], CombineOperand::OneMinusSrcAlpha);
        assert_eq!(s[1].scale, [1.0, 2.0]);
    }
}
