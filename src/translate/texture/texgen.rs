//! Texture coordinate generation (OpenGL 1.5 section 2.10.4, table 6.14): `glTexGen{ifd}{v}`
//! and `glGetTexGen{ifd}v` for the s, t, r, q coordinates of each unit. Eye planes are
//! stored transformed by the inverse of the modelview matrix current when they are given.

use glam::DVec4;

use super::super::Context;
use super::super::convert::{read_slice, scalar_as_vector, write_slice};
use super::super::gl::{self, GLdouble, GLenum, GLfloat, GLint};
use super::super::lists::ListOp;

/// Generation state of one coordinate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoordGen {
    /// `GL_TEXTURE_GEN_MODE`.
    pub mode: GLenum,
    /// `GL_OBJECT_PLANE`.
    pub object_plane: [f64; 4],
    /// `GL_EYE_PLANE` (already multiplied by the inverse modelview).
    pub eye_plane: [f64; 4],
}

/// Generation state of s, t, r, q of one unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexGen {
    /// s, t, r, q.
    pub coords: [CoordGen; 4],
}

impl Default for TexGen {
    fn default() -> TexGen {
        let plane = |i: usize| {
            let mut p = [0.0; 4];
            if i < 2 {
                p[i] = 1.0;
            }
            p
        };
        TexGen { coords: std::array::from_fn(|i| CoordGen { mode: gl::GL_EYE_LINEAR, object_plane: plane(i), eye_plane: plane(i) }) }
    }
}

fn coord_index(coord: GLenum) -> Option<usize> {
    [gl::GL_S, gl::GL_T, gl::GL_R, gl::GL_Q].iter().position(|&c| c == coord)
}

/// Values of a texgen name (4 for the planes).
fn gen_count(pname: GLenum) -> usize {
    if pname == gl::GL_TEXTURE_GEN_MODE { 1 } else { 4 }
}

impl Context {
    /// Sets generation state: `GL_INVALID_ENUM` for an unknown coordinate or name, or a mode that coordinate cannot use (`SPHERE_MAP` for r and
    /// q, `NORMAL_MAP` and `REFLECTION_MAP` for q).
    fn tex_gen(&mut self, coord: GLenum, pname: GLenum, v: &[f64], command: &'static str) {
        let result = (|| {
            let c = coord_index(coord).ok_or(gl::GL_INVALID_ENUM)?;
            let unit = self.active_texture_unit();
            match pname {
                gl::GL_TEXTURE_GEN_MODE => {
                    let mode = *v.first().ok_or(gl::GL_INVALID_ENUM)? as GLenum;
                    let ok = match mode {
                        gl::GL_OBJECT_LINEAR | gl::GL_EYE_LINEAR => true,
                        gl::GL_SPHERE_MAP => c < 2,
                        gl::GL_NORMAL_MAP | gl::GL_REFLECTION_MAP => c < 3,
                        _ => false,
                    };
                    if !ok {
                        return Err(gl::GL_INVALID_ENUM);
                    }
                    self.texture.texgen[unit].coords[c].mode = mode;
                }
                gl::GL_OBJECT_PLANE => self.texture.texgen[unit].coords[c].object_plane = v.try_into().map_err(|_| gl::GL_INVALID_ENUM)?,
                gl::GL_EYE_PLANE => {
                    let p: [f64; 4] = v.try_into().map_err(|_| gl::GL_INVALID_ENUM)?;
                    // (p1 p2 p3 p4) M⁻¹: a row vector times the inverse modelview.
                    let inv = self.transform.modelview.top().inverse();
                    let row = DVec4::from_array(p);
                    let eye = [0, 1, 2, 3].map(|i| row.dot(inv.col(i)));
                    self.texture.texgen[unit].coords[c].eye_plane = eye;
                }
                _ => return Err(gl::GL_INVALID_ENUM),
            }
            Ok(())
        })();
        if let Err(e) = result {
            self.set_error_in(e, command);
        }
    }

    /// `glTexGeni`: a plane becomes (param, 0, 0, 0) (see [`scalar_as_vector`]).
    pub fn glTexGeni(&mut self, coord: GLenum, pname: GLenum, param: GLint) {
        self.tex_gen(coord, pname, &scalar_as_vector(f64::from(param), gen_count(pname)), "glTexGeni");
    }
    /// `glTexGenf`: as `glTexGeni`.
    pub fn glTexGenf(&mut self, coord: GLenum, pname: GLenum, param: GLfloat) {
        self.tex_gen(coord, pname, &scalar_as_vector(f64::from(param), gen_count(pname)), "glTexGenf");
    }
    /// `glTexGend`: as `glTexGeni`.
    pub fn glTexGend(&mut self, coord: GLenum, pname: GLenum, param: GLdouble) {
        self.tex_gen(coord, pname, &scalar_as_vector(param, gen_count(pname)), "glTexGend");
    }

    /// Reads the values of a vector texgen command.
    unsafe fn tex_gen_v<T: Copy + Into<f64>>(&mut self, coord: GLenum, pname: GLenum, params: *const T, command: &'static str) {
        let Some(v) = (unsafe { read_slice(params, gen_count(pname)) }) else { return self.null_pointer(command) };
        let v: Vec<f64> = v.into_iter().map(Into::into).collect();
        self.tex_gen(coord, pname, &v, command);
    }

    /// `glTexGeniv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glTexGeniv(&mut self, coord: GLenum, pname: GLenum, params: *const GLint) {
        unsafe { self.tex_gen_v(coord, pname, params, "glTexGeniv") }
    }
    /// `glTexGenfv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glTexGenfv(&mut self, coord: GLenum, pname: GLenum, params: *const GLfloat) {
        unsafe { self.tex_gen_v(coord, pname, params, "glTexGenfv") }
    }
    /// `glTexGendv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glTexGendv(&mut self, coord: GLenum, pname: GLenum, params: *const GLdouble) {
        unsafe { self.tex_gen_v(coord, pname, params, "glTexGendv") }
    }

    /// Records a vector texgen command with a copy of its values.
    unsafe fn compile_tex_gen<T: Copy + Send + Sync + 'static>(&mut self, coord: GLenum, pname: GLenum, params: *const T, run: unsafe fn(&mut Context, GLenum, GLenum, *const T)) {
        let v = unsafe { read_slice(params, gen_count(pname)) };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| unsafe { run(ctx, coord, pname, v.as_ref().map_or(std::ptr::null(), |v| v.as_ptr())) })));
    }

    /// `glTexGeniv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexGeniv`].
    pub unsafe fn compile_glTexGeniv(&mut self, coord: GLenum, pname: GLenum, params: *const GLint) {
        unsafe { self.compile_tex_gen(coord, pname, params, super::super::dispatch::exec_glTexGeniv) }
    }
    /// `glTexGenfv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexGenfv`].
    pub unsafe fn compile_glTexGenfv(&mut self, coord: GLenum, pname: GLenum, params: *const GLfloat) {
        unsafe { self.compile_tex_gen(coord, pname, params, super::super::dispatch::exec_glTexGenfv) }
    }
    /// `glTexGendv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexGendv`].
    pub unsafe fn compile_glTexGendv(&mut self, coord: GLenum, pname: GLenum, params: *const GLdouble) {
        unsafe { self.compile_tex_gen(coord, pname, params, super::super::dispatch::exec_glTexGendv) }
    }

    /// The values of a texgen name, raising `GL_INVALID_ENUM` for an unknown one.
    fn tex_gen_value(&mut self, coord: GLenum, pname: GLenum, command: &'static str) -> Option<Vec<f64>> {
        let unit = self.active_texture_unit();
        let c = coord_index(coord).map(|c| self.texture.texgen[unit].coords[c]);
        let v = match (c, pname) {
            (Some(c), gl::GL_TEXTURE_GEN_MODE) => Some(vec![f64::from(c.mode)]),
            (Some(c), gl::GL_OBJECT_PLANE) => Some(c.object_plane.to_vec()),
            (Some(c), gl::GL_EYE_PLANE) => Some(c.eye_plane.to_vec()),
            _ => None,
        };
        if v.is_none() {
            self.set_error_in(gl::GL_INVALID_ENUM, command);
        }
        v
    }

    /// `glGetTexGeniv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetTexGeniv(&mut self, coord: GLenum, pname: GLenum, params: *mut GLint) {
        if let Some(v) = self.tex_gen_value(coord, pname, "glGetTexGeniv") {
            unsafe { write_slice(params, &v.iter().map(|&x| x.round() as GLint).collect::<Vec<_>>()) }
        }
    }
    /// `glGetTexGenfv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetTexGenfv(&mut self, coord: GLenum, pname: GLenum, params: *mut GLfloat) {
        if let Some(v) = self.tex_gen_value(coord, pname, "glGetTexGenfv") {
            unsafe { write_slice(params, &v.iter().map(|&x| x as GLfloat).collect::<Vec<_>>()) }
        }
    }
    /// `glGetTexGendv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetTexGendv(&mut self, coord: GLenum, pname: GLenum, params: *mut GLdouble) {
        if let Some(v) = self.tex_gen_value(coord, pname, "glGetTexGendv") {
            unsafe { write_slice(params, &v) }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn texgen_modes_and_planes() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glTexGeni(gl::GL_S, gl::GL_TEXTURE_GEN_MODE, gl::GL_SPHERE_MAP as i32);
        ctx.glTexGeni(gl::GL_R, gl::GL_TEXTURE_GEN_MODE, gl::GL_SPHERE_MAP as i32);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glTexGeni(gl::GL_Q, gl::GL_TEXTURE_GEN_MODE, gl::GL_REFLECTION_MAP as i32);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glTexGeni(gl::GL_R, gl::GL_TEXTURE_GEN_MODE, gl::GL_NORMAL_MAP as i32);
        let mut mode = 0;
        unsafe { ctx.glGetTexGeniv(gl::GL_S, gl::GL_TEXTURE_GEN_MODE, &mut mode) };
        assert_eq!(mode as u32, gl::GL_SPHERE_MAP);
        let mut plane = [0.0f64; 4];
        unsafe { ctx.glGetTexGendv(gl::GL_T, gl::GL_OBJECT_PLANE, plane.as_mut_ptr()) };
        assert_eq!(plane, [0.0, 1.0, 0.0, 0.0]);
        // Eye plane given under a translation by (0, 0, -5): p M⁻¹ with M⁻¹ translating by +5.
        ctx.glTranslatef(0.0, 0.0, -5.0);
        let p = [0.0f32, 0.0, 1.0, 0.0];
        unsafe { dispatch::glTexGenfv(&mut ctx, gl::GL_Q, gl::GL_EYE_PLANE, p.as_ptr()) };
        let mut f = [0.0f32; 4];
        unsafe { ctx.glGetTexGenfv(gl::GL_Q, gl::GL_EYE_PLANE, f.as_mut_ptr()) };
        assert_eq!(f, [0.0, 0.0, 1.0, 5.0]);
        ctx.glTexGenf(gl::GL_S, gl::GL_OBJECT_PLANE, 2.0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        unsafe { ctx.glGetTexGenfv(gl::GL_S, gl::GL_OBJECT_PLANE, f.as_mut_ptr()) };
        assert_eq!(f, [2.0, 0.0, 0.0, 0.0]);
    }
}

impl Context {
    /// How each of s, t, r, q of `unit` is generated for the next draw (`None` where
    /// generation is off, `GL_TEXTURE_GEN_*` of the enable module).
    pub fn texgen_of(&self, unit: usize) -> [Option<crate::frame::texture::TexGenMode>; 4] {
        use crate::frame::texture::TexGenMode;
        let caps = [gl::GL_TEXTURE_GEN_S, gl::GL_TEXTURE_GEN_T, gl::GL_TEXTURE_GEN_R, gl::GL_TEXTURE_GEN_Q];
        std::array::from_fn(|c| {
            let g = self.texture.texgen[unit].coords[c];
            let f = |p: [f64; 4]| p.map(|v| v as f32);
            self.enables.unit_on(unit, caps[c]).then(|| match g.mode {
                gl::GL_OBJECT_LINEAR => TexGenMode::ObjectLinear(f(g.object_plane)),
                gl::GL_SPHERE_MAP => TexGenMode::SphereMap,
                gl::GL_NORMAL_MAP => TexGenMode::NormalMap,
                gl::GL_REFLECTION_MAP => TexGenMode::ReflectionMap,
                _ => TexGenMode::EyeLinear(f(g.eye_plane)),
            })
        })
    }
}

#[cfg(test)]
mod snapshot_tests {
    use crate::frame::texture::TexGenMode;
    use crate::translate::{Context, gl};

    #[test]
    fn texgen_snapshot_follows_enables() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glTexGeni(gl::GL_T, gl::GL_TEXTURE_GEN_MODE, gl::GL_OBJECT_LINEAR as i32);
        ctx.glEnable(gl::GL_TEXTURE_GEN_T);
        ctx.glEnable(gl::GL_TEXTURE_GEN_S);
        let s = [ctx.texgen_of(0), ctx.texgen_of(1)];
        assert_eq!(s[0][0], Some(TexGenMode::EyeLinear([1.0, 0.0, 0.0, 0.0])));
        assert_eq!(s[0][1], Some(TexGenMode::ObjectLinear([0.0, 1.0, 0.0, 0.0])));
        assert_eq!((s[0][2], s[1][0]), (None, None));
    }
}
