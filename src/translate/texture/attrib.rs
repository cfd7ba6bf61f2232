//! Save and restore of `GL_TEXTURE_BIT` for `glPushAttrib`/`glPopAttrib` (OpenGL 1.5 tables
//! 6.14–6.18): each unit's bindings, environment and coordinate generation, and the parameters
//! of the textures bound at push time. The per-unit enables and the active unit belong to the
//! attribute-stack module, which saves them with this group.

use super::super::Context;
use super::super::limits::MAX_TEXTURE_UNITS;
use super::env::TexEnv;
use super::objects::Target;
use super::params::TexParams;
use super::texgen::TexGen;

/// Saved `GL_TEXTURE_BIT` state.
#[derive(Clone, Debug)]
pub struct TextureAttrib {
    bindings: [[u32; Target::ALL.len()]; MAX_TEXTURE_UNITS],
    env: [TexEnv; MAX_TEXTURE_UNITS],
    texgen: [TexGen; MAX_TEXTURE_UNITS],
    /// (name, target, parameters) of every bound texture.
    params: Vec<(u32, Target, TexParams)>,
}

impl Context {
    /// Captures `GL_TEXTURE_BIT`.
    pub fn save_texture_attrib(&self) -> TextureAttrib {
        let bindings = self.texture.bindings;
        let shared = self.shared.lock();
        let mut params = Vec::new();
        for unit in &bindings {
            for t in Target::ALL {
                let name = unit[t.index()];
                if !params.iter().any(|&(n, tt, _)| n == name && tt == t) {
                    let object = shared.textures.get(name).filter(|_| name != 0).unwrap_or(&self.texture.defaults[t.index()]);
                    params.push((name, t, object.params));
                }
            }
        }
        TextureAttrib { bindings, env: self.texture.env, texgen: self.texture.texgen, params }
    }

    /// Restores `GL_TEXTURE_BIT`: textures deleted since are bound as the default texture;
    /// parameters are restored on the textures that still exist.
    pub fn restore_texture_attrib(&mut self, saved: TextureAttrib) {
        for (name, target, params) in saved.params {
            let exists = name == 0 || self.shared.lock().textures.get(name).is_some();
            if exists {
                self.with_object(target, name, |o| {
                    if o.params != params {
                        o.params = params;
                        o.touch();
                    }
                });
            }
        }
        let shared = self.shared.clone();
        let shared = shared.lock();
        self.texture.bindings = saved.bindings.map(|unit| unit.map(|n| if n == 0 || shared.textures.get(n).is_some() { n } else { 0 }));
        drop(shared);
        self.texture.env = saved.env;
        self.texture.texgen = saved.texgen;
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, gl};

    #[test]
    fn texture_bit_round_trip() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 3);
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        let saved = ctx.save_texture_attrib();
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_LINEAR as i32);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_REPLACE as i32);
        ctx.glActiveTexture(gl::GL_TEXTURE2);
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 4);
        ctx.glActiveTexture(gl::GL_TEXTURE0);
        ctx.restore_texture_attrib(saved);
        assert_eq!(ctx.texture.bindings[2][1], 0);
        assert_eq!(ctx.texture.bindings[0][1], 3);
        assert_eq!(ctx.texture.env[0].mode, gl::GL_MODULATE);
        let mut mag = 0;
        unsafe { ctx.glGetTexParameteriv(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, &mut mag) };
        assert_eq!(mag as u32, gl::GL_NEAREST);
    }
}
