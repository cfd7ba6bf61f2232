//! Queries of shader and program objects (OpenGL 2.0 section 6.1.14): `glGetShaderiv`,
//! `glGetProgramiv`, the info logs, the source, the attached shaders, `GL_CURRENT_PROGRAM`.

use super::Program;
use crate::translate::Context;
use crate::translate::convert::write_slice;
use crate::translate::get::Value;
use crate::translate::gl::{self, GLchar, GLenum, GLint, GLsizei, GLuint};
use crate::translate::glsl::Stage;

/// Length of a string as the `*_LENGTH` queries count it: with its terminating NUL, 0 when
/// empty.
fn length_with_nul(s: &str) -> GLint {
    if s.is_empty() { 0 } else { GLint::try_from(s.len() + 1).unwrap_or(GLint::MAX) }
}

/// Copies `s` into a `bufSize`-byte buffer as the `glGet*InfoLog` / `glGetShaderSource`
/// commands do: at most `bufSize - 1` bytes and a NUL; `length` (when not null) gets the bytes
/// written, NUL excluded.
///
/// # Safety
/// `out` must have room for `buf_size` bytes; `length` must be null or writable.
unsafe fn copy_string(s: &str, buf_size: usize, length: *mut GLsizei, out: *mut GLchar) {
    let n = if out.is_null() { 0 } else { s.len().min(buf_size.saturating_sub(1)) };
    if !out.is_null() && buf_size > 0 {
        let mut bytes: Vec<GLchar> = s.as_bytes()[..n].iter().map(|&b| b as GLchar).collect();
        bytes.push(0);
        unsafe { write_slice(out, &bytes) };
    }
    unsafe { write_slice(length, &[n as GLsizei]) };
}

/// `glGetProgramiv`'s value of `pname`; `None` for a name it does not know.
fn program_param(p: &Program, pname: GLenum) -> Option<GLint> {
    let linked = p.linked.as_ref().filter(|_| p.link_ok);
    let count = |n: usize| GLint::try_from(n).unwrap_or(GLint::MAX);
    Some(match pname {
        gl::GL_DELETE_STATUS => GLint::from(p.delete_pending),
        gl::GL_LINK_STATUS => GLint::from(p.link_ok),
        gl::GL_VALIDATE_STATUS => GLint::from(p.validate_ok),
        gl::GL_INFO_LOG_LENGTH => length_with_nul(&p.log),
        gl::GL_ATTACHED_SHADERS => count(p.shaders.len()),
        gl::GL_ACTIVE_UNIFORMS => count(linked.map_or(0, |l| l.uniforms.len())),
        gl::GL_ACTIVE_UNIFORM_MAX_LENGTH => {
            let names = linked.into_iter().flat_map(|l| &l.uniforms).map(|u| length_with_nul(&super::uniforms::active_name(u)));
            names.max().unwrap_or(0)
        }
        gl::GL_ACTIVE_ATTRIBUTES => count(linked.map_or(0, |l| l.attributes.len())),
        gl::GL_ACTIVE_ATTRIBUTE_MAX_LENGTH => {
            linked.into_iter().flat_map(|l| &l.attributes).map(|a| length_with_nul(&a.name)).max().unwrap_or(0)
        }
        _ => return None,
    })
}

impl Context {
    /// `glGetShaderiv`.
    ///
    /// # Safety
    /// `params` must be null or have room for one integer.
    pub unsafe fn glGetShaderiv(&mut self, shader: GLuint, pname: GLenum, params: *mut GLint) {
        let value = match self.shared.lock().programs.shader(shader) {
            Ok(s) => match pname {
                gl::GL_SHADER_TYPE => Ok(match s.stage {
                    Stage::Vertex => gl::GL_VERTEX_SHADER as GLint,
                    Stage::Fragment => gl::GL_FRAGMENT_SHADER as GLint,
                }),
                gl::GL_DELETE_STATUS => Ok(GLint::from(s.delete_pending)),
                gl::GL_COMPILE_STATUS => Ok(GLint::from(s.compiled.as_ref().is_some_and(|c| c.ok))),
                gl::GL_INFO_LOG_LENGTH => Ok(length_with_nul(s.compiled.as_ref().map_or("", |c| &c.log))),
                gl::GL_SHADER_SOURCE_LENGTH => Ok(length_with_nul(&s.source)),
                _ => Err(gl::GL_INVALID_ENUM),
            },
            Err(e) => Err(e),
        };
        match value {
            Ok(v) => unsafe { write_slice(params, &[v]) },
            Err(e) => self.set_error_in(e, "glGetShaderiv"),
        }
    }

    /// `glGetProgramiv`.
    ///
    /// # Safety
    /// `params` must be null or have room for one integer.
    pub unsafe fn glGetProgramiv(&mut self, program: GLuint, pname: GLenum, params: *mut GLint) {
        let value = self.shared.lock().programs.program(program).and_then(|p| program_param(p, pname).ok_or(gl::GL_INVALID_ENUM));
        match value {
            Ok(v) => unsafe { write_slice(params, &[v]) },
            Err(e) => self.set_error_in(e, "glGetProgramiv"),
        }
    }

    /// Runs `copy` on a string of an object, for the commands that return one into a buffer
    /// of `buf_size` bytes (`GL_INVALID_VALUE` when it is negative).
    fn string_query(
        &mut self,
        buf_size: GLsizei,
        command: &'static str,
        string: impl FnOnce(&super::ProgramTable) -> Result<String, GLenum>,
        copy: impl FnOnce(&str, usize),
    ) {
        let Ok(buf_size) = usize::try_from(buf_size) else {
            return self.set_error_in(gl::GL_INVALID_VALUE, command);
        };
        let s = string(&self.shared.lock().programs);
        match s {
            Ok(s) => copy(&s, buf_size),
            Err(e) => self.set_error_in(e, command),
        }
    }

    /// `glGetShaderInfoLog`.
    ///
    /// # Safety
    /// `infoLog` must have room for `bufSize` bytes; `length` must be null or writable.
    pub unsafe fn glGetShaderInfoLog(&mut self, shader: GLuint, bufSize: GLsizei, length: *mut GLsizei, infoLog: *mut GLchar) {
        self.string_query(
            bufSize,
            "glGetShaderInfoLog",
            |t| t.shader(shader).map(|s| s.compiled.as_ref().map(|c| c.log.clone()).unwrap_or_default()),
            |s, n| unsafe { copy_string(s, n, length, infoLog) },
        );
    }

    /// `glGetProgramInfoLog`.
    ///
    /// # Safety
    /// `infoLog` must have room for `bufSize` bytes; `length` must be null or writable.
    pub unsafe fn glGetProgramInfoLog(&mut self, program: GLuint, bufSize: GLsizei, length: *mut GLsizei, infoLog: *mut GLchar) {
        self.string_query(
            bufSize,
            "glGetProgramInfoLog",
            |t| t.program(program).map(|p| p.log.clone()),
            |s, n| unsafe { copy_string(s, n, length, infoLog) },
        );
    }

    /// `glGetShaderSource`.
    ///
    /// # Safety
    /// `source` must have room for `bufSize` bytes; `length` must be null or writable.
    pub unsafe fn glGetShaderSource(&mut self, shader: GLuint, bufSize: GLsizei, length: *mut GLsizei, source: *mut GLchar) {
        self.string_query(
            bufSize,
            "glGetShaderSource",
            |t| t.shader(shader).map(|s| s.source.clone()),
            |s, n| unsafe { copy_string(s, n, length, source) },
        );
    }

    /// `glGetAttachedShaders`: at most `maxCount` names.
    ///
    /// # Safety
    /// `shaders` must have room for `maxCount` names; `count` must be null or writable.
    pub unsafe fn glGetAttachedShaders(&mut self, program: GLuint, maxCount: GLsizei, count: *mut GLsizei, shaders: *mut GLuint) {
        let Ok(max) = usize::try_from(maxCount) else {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glGetAttachedShaders");
        };
        let attached = self.shared.lock().programs.program(program).map(|p| p.shaders.clone());
        match attached {
            Ok(list) => {
                let n = list.len().min(max);
                unsafe {
                    write_slice(shaders, &list[..n]);
                    write_slice(count, &[n as GLsizei]);
                }
            }
            Err(e) => self.set_error_in(e, "glGetAttachedShaders"),
        }
    }

    /// `GL_CURRENT_PROGRAM` of `glGet`.
    pub(crate) fn query_programs(&self, pname: GLenum) -> Option<Value> {
        match pname {
            gl::GL_CURRENT_PROGRAM => Some(Value::int(self.programs.current)),
            _ => None,
        }
    }
}

/// An active uniform or attribute as `glGetActiveUniform` / `glGetActiveAttrib` report it.
pub(super) struct Active {
    /// Name.
    pub name: String,
    /// Array elements.
    pub size: GLint,
    /// GL type enum.
    pub ty: GLenum,
}

/// Writes `active` the way `glGetActiveUniform` / `glGetActiveAttrib` return it
/// (`GL_INVALID_VALUE` for a negative `buf_size`).
///
/// # Safety
/// `name` must have room for `buf_size` bytes; `length`, `size` and `type_` must be null or
/// writable.
#[allow(clippy::too_many_arguments)]
pub(super) unsafe fn write_active(
    ctx: &mut Context,
    command: &'static str,
    active: Active,
    buf_size: GLsizei,
    length: *mut GLsizei,
    size: *mut GLint,
    type_: *mut GLenum,
    name: *mut GLchar,
) {
    let Ok(buf_size) = usize::try_from(buf_size) else {
        return ctx.set_error_in(gl::GL_INVALID_VALUE, command);
    };
    unsafe {
        copy_string(&active.name, buf_size, length, name);
        write_slice(size, &[active.size]);
        write_slice(type_, &[active.ty]);
    }
}
