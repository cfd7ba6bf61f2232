//! Shader and program objects (OpenGL 2.0 sections 2.15.1 to 2.15.3 and 6.1.14): the objects
//! of a share group in one namespace ([`ProgramTable`]), the program each context uses
//! ([`ProgramState`]), and, in the submodules, their commands: [`objects`] (creation,
//! sources, compiling, attaching, linking, use, deletion), [`info`] (object queries),
//! [`uniforms`] (locations, values), [`attributes`] (vertex attribute bindings) and [`draw`]
//! (what a draw takes of the program in use).

pub mod attributes;
pub mod draw;
pub mod info;
pub mod objects;
pub mod uniforms;

use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;

use super::gl::{self, GLenum, GLuint};
use super::glsl::{ActiveAttribute, ActiveUniform, CompiledShader, Stage};
use crate::frame::program::ShaderProgram;

/// A shader object.
#[derive(Clone, Debug)]
pub struct Shader {
    /// `GL_SHADER_TYPE`.
    pub stage: Stage,
    /// The source `glShaderSource` gave (`GL_SHADER_SOURCE_LENGTH`, `glGetShaderSource`).
    pub source: String,
    /// The last `glCompileShader`'s result (`None` before the first).
    pub compiled: Option<CompiledShader>,
    /// `GL_DELETE_STATUS`: deleted while attached; it goes when the last program lets go.
    pub delete_pending: bool,
    /// Programs it is attached to.
    pub attachments: u32,
}

/// The result of a successful link that a program keeps until its next successful link: the
/// executable and the values of its uniforms (program object state, section 2.15.3).
#[derive(Clone, Debug)]
pub struct Linked {
    /// The executable.
    pub executable: Arc<ShaderProgram>,
    /// Active uniforms, as `glGetActiveUniform` enumerates them.
    pub uniforms: Vec<ActiveUniform>,
    /// Active attributes, as `glGetActiveAttrib` enumerates them.
    pub attributes: Vec<ActiveAttribute>,
    /// Uniform locations: location `l` is element `.1` of uniform `.0`.
    pub locations: Vec<(usize, u32)>,
    /// The uniform block's bytes (std430, laid out by the link).
    pub values: Vec<u8>,
    /// The texture unit of each sampler slot.
    pub sampler_units: Vec<u32>,
    /// The texture target of each sampler slot.
    pub sampler_targets: Vec<crate::translate::texture::objects::Target>,
    /// [`Linked::values`] as draws share them, made again after a change.
    pub shared_values: Option<Arc<[u8]>>,
}

/// A program object.
#[derive(Clone, Debug, Default)]
pub struct Program {
    /// Attached shaders, in attachment order.
    pub shaders: Vec<GLuint>,
    /// `glBindAttribLocation` bindings, applied at the next link.
    pub bindings: HashMap<String, u32>,
    /// `GL_LINK_STATUS`.
    pub link_ok: bool,
    /// `GL_VALIDATE_STATUS`.
    pub validate_ok: bool,
    /// The info log of the last link or validation.
    pub log: String,
    /// `GL_DELETE_STATUS`: deleted while in use; it goes when no context uses it.
    pub delete_pending: bool,
    /// Contexts using it.
    pub uses: u32,
    /// The last successful link: kept by a program in use whose relink failed (section
    /// 2.15.2), present while [`Program::link_ok`].
    pub linked: Option<Linked>,
}

/// A shader or program object.
#[derive(Clone, Debug)]
pub enum Object {
    /// A shader object.
    Shader(Shader),
    /// A program object.
    Program(Program),
}

/// The shader and program objects of a share group, in one namespace.
#[derive(Default)]
pub struct ProgramTable {
    objects: BTreeMap<GLuint, Object>,
}

impl ProgramTable {
    /// A new object under an unused name.
    fn create(&mut self, object: Object) -> GLuint {
        let name = self.objects.last_key_value().map_or(1, |(&n, _)| n + 1);
        self.objects.insert(name, object);
        name
    }

    /// Shader `name`: `GL_INVALID_VALUE` when there is no such object, `GL_INVALID_OPERATION`
    /// when it is a program.
    pub fn shader(&self, name: GLuint) -> Result<&Shader, GLenum> {
        match self.objects.get(&name) {
            Some(Object::Shader(s)) => Ok(s),
            Some(Object::Program(_)) => Err(gl::GL_INVALID_OPERATION),
            None => Err(gl::GL_INVALID_VALUE),
        }
    }

    /// Shader `name`, mutably (errors as [`ProgramTable::shader`]).
    pub fn shader_mut(&mut self, name: GLuint) -> Result<&mut Shader, GLenum> {
        match self.objects.get_mut(&name) {
            Some(Object::Shader(s)) => Ok(s),
            Some(Object::Program(_)) => Err(gl::GL_INVALID_OPERATION),
            None => Err(gl::GL_INVALID_VALUE),
        }
    }

    /// Program `name`: `GL_INVALID_VALUE` when there is no such object, `GL_INVALID_OPERATION`
    /// when it is a shader.
    pub fn program(&self, name: GLuint) -> Result<&Program, GLenum> {
        match self.objects.get(&name) {
            Some(Object::Program(p)) => Ok(p),
            Some(Object::Shader(_)) => Err(gl::GL_INVALID_OPERATION),
            None => Err(gl::GL_INVALID_VALUE),
        }
    }

    /// Program `name`, mutably (errors as [`ProgramTable::program`]).
    pub fn program_mut(&mut self, name: GLuint) -> Result<&mut Program, GLenum> {
        match self.objects.get_mut(&name) {
            Some(Object::Program(p)) => Ok(p),
            Some(Object::Shader(_)) => Err(gl::GL_INVALID_OPERATION),
            None => Err(gl::GL_INVALID_VALUE),
        }
    }

    /// Detaches `shader` from a program; a shader flagged for deletion goes with its last
    /// attachment.
    fn release_shader(&mut self, shader: GLuint) {
        if let Ok(s) = self.shader_mut(shader) {
            s.attachments = s.attachments.saturating_sub(1);
            if s.delete_pending && s.attachments == 0 {
                self.objects.remove(&shader);
            }
        }
    }

    /// One context stops using program `name`: a program flagged for deletion goes with its
    /// last use, and a failed relink's executable stays only while the program is in use.
    fn stop_using(&mut self, name: GLuint) {
        if let Ok(p) = self.program_mut(name) {
            p.uses = p.uses.saturating_sub(1);
            if p.uses == 0 {
                if p.delete_pending {
                    self.remove_program(name);
                } else if !p.link_ok {
                    p.linked = None;
                }
            }
        }
    }

    /// Deletes program `name` now: its shaders are detached.
    fn remove_program(&mut self, name: GLuint) {
        if let Some(Object::Program(p)) = self.objects.remove(&name) {
            for s in p.shaders {
                self.release_shader(s);
            }
        }
    }
}

/// The program a context uses (`glUseProgram`, `GL_CURRENT_PROGRAM`; 0 for none).
#[derive(Clone, Copy, Debug, Default)]
pub struct ProgramState {
    /// The program object in use.
    pub current: GLuint,
}

impl Drop for super::Context {
    /// A destroyed context stops using its program (which goes if it was deleted meanwhile:
    /// the share group may outlive the context).
    fn drop(&mut self) {
        let current = self.programs.current;
        self.shared.lock().programs.stop_using(current);
    }
}

#[cfg(test)]
pub(crate) mod tests;
