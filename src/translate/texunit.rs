//! The active texture unit (`glActiveTexture`) and the client active texture unit
//! (`glClientActiveTexture`), OpenGL 1.5 sections 2.7 and 3.8.

use super::Context;
use super::get::Value;
use super::gl::{self, GLenum};
use super::limits::MAX_TEXTURE_UNITS;

/// Which texture unit server- and client-side texture commands address.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TexUnitState {
    /// `GL_ACTIVE_TEXTURE` − `GL_TEXTURE0`.
    pub active: usize,
    /// `GL_CLIENT_ACTIVE_TEXTURE` − `GL_TEXTURE0`.
    pub client_active: usize,
}

/// The unit index of `GL_TEXTUREi`, if `i` is a unit glrt has.
pub fn unit_index(texture: GLenum) -> Option<usize> {
    let i = texture.checked_sub(gl::GL_TEXTURE0)? as usize;
    (i < MAX_TEXTURE_UNITS).then_some(i)
}

impl Context {
    /// The active texture unit.
    pub fn active_texture_unit(&self) -> usize {
        self.texunit.active
    }

    /// `glActiveTexture`: `GL_INVALID_ENUM` for a unit out of range.
    pub fn glActiveTexture(&mut self, texture: GLenum) {
        match unit_index(texture) {
            Some(i) => self.texunit.active = i,
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glActiveTexture"),
        }
    }

    /// `glClientActiveTexture`.
    pub fn glClientActiveTexture(&mut self, texture: GLenum) {
        match unit_index(texture) {
            Some(i) => self.texunit.client_active = i,
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glClientActiveTexture"),
        }
    }

    pub(crate) fn query_texunit(&self, pname: GLenum) -> Option<Value> {
        Some(match pname {
            gl::GL_ACTIVE_TEXTURE => Value::int(gl::GL_TEXTURE0 + self.texunit.active as u32),
            gl::GL_CLIENT_ACTIVE_TEXTURE => Value::int(gl::GL_TEXTURE0 + self.texunit.client_active as u32),
            gl::GL_MAX_TEXTURE_UNITS => Value::int(MAX_TEXTURE_UNITS as i64),
            _ => return None,
        })
    }
}
