//! What Quake 3's back end remembers of GL state (`glState` in `tr_backend.c`) so that it only
//! calls GL when something changes: the texture unit selected (`GL_SelectTexture`: server and
//! client unit together), the texture bound on each unit (`GL_Bind`), each unit's texture
//! environment (`GL_TexEnv`), face culling (`GL_Cull`) and the blend and depth state
//! (`GL_State`). [`GlState::set_default`] is `GL_SetDefaultState`, run once at start-up.

use super::shaders::{Cull, StateBits};
use crate::gl::*;

/// The remembered state.
pub struct GlState {
    current_tmu: usize,
    textures: [GLuint; 2],
    tex_env: [GLenum; 2],
    bits: StateBits,
    culling: Option<Cull>,
}

/// The GL entry points the back end calls.
#[derive(Clone, Copy)]
pub struct Api<'a> {
    pub gl: &'a Gl,
    pub mt: &'a Multitexture,
    pub lock: &'a LockArrays,
}

impl GlState {
    /// Puts GL in Q3's default state and remembers it (`GL_SetDefaultState`): unit 1
    /// modulating but disabled, unit 0 texturing, smooth shading, `GL_LEQUAL`, the vertex
    /// array on, depth writes on, depth test, culling and blending off, the scissor test on.
    pub fn set_default(api: Api) -> GlState {
        let gl = api.gl;
        let mut state = GlState {
            current_tmu: 0,
            textures: [0; 2],
            tex_env: [0; 2],
            bits: StateBits { blend: None, depth_write: true, depth_test: false, depth_equal: false },
            culling: None,
        };
        // Safety: a context is current.
        unsafe {
            gl.glCullFace(GL_FRONT);
            gl.glColor4f(1.0, 1.0, 1.0, 1.0);
            state.select_texture(api, 1);
            state.tex_env(api, GL_MODULATE);
            gl.glDisable(GL_TEXTURE_2D);
            state.select_texture(api, 0);
            gl.glEnable(GL_TEXTURE_2D);
            state.tex_env(api, GL_MODULATE);
            gl.glShadeModel(GL_SMOOTH);
            gl.glDepthFunc(GL_LEQUAL);
            gl.glEnableClientState(GL_VERTEX_ARRAY);
            gl.glDepthMask(GL_TRUE);
            gl.glDisable(GL_DEPTH_TEST);
            gl.glEnable(GL_SCISSOR_TEST);
            gl.glDisable(GL_CULL_FACE);
            gl.glDisable(GL_BLEND);
        }
        state
    }

    /// Selects texture unit `unit` for both texture and client state
    /// (`glActiveTextureARB` + `glClientActiveTextureARB`).
    pub fn select_texture(&mut self, api: Api, unit: usize) {
        if self.current_tmu == unit {
            return;
        }
        let texture = GL_TEXTURE0_ARB + unit as GLenum;
        // Safety: a context is current; unit is 0 or 1.
        unsafe {
            api.mt.glActiveTextureARB(texture);
            api.mt.glClientActiveTextureARB(texture);
        }
        self.current_tmu = unit;
    }

    /// Binds `image` on the selected unit.
    pub fn bind(&mut self, api: Api, image: GLuint) {
        if self.textures[self.current_tmu] != image {
            self.textures[self.current_tmu] = image;
            // Safety: a context is current.
            unsafe { api.gl.glBindTexture(GL_TEXTURE_2D, image) };
        }
    }

    /// Sets the texture environment mode of the selected unit.
    pub fn tex_env(&mut self, api: Api, env: GLenum) {
        if self.tex_env[self.current_tmu] != env {
            self.tex_env[self.current_tmu] = env;
            // Safety: a context is current.
            unsafe { api.gl.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, env as GLint) };
        }
    }

    /// Face culling for `cull`: `GL_FRONT` culled for front-sided shaders.
    pub fn cull(&mut self, api: Api, cull: Cull) {
        if self.culling == Some(cull) {
            return;
        }
        self.culling = Some(cull);
        // Safety: a context is current.
        unsafe {
            match cull {
                Cull::TwoSided => api.gl.glDisable(GL_CULL_FACE),
                Cull::FrontSided => {
                    api.gl.glEnable(GL_CULL_FACE);
                    api.gl.glCullFace(GL_FRONT);
                }
            }
        }
    }

    /// Forgets the culling state, so the next [`GlState::cull`] sets it (each view does this).
    pub fn forget_culling(&mut self) {
        self.culling = None;
    }

    /// Sets blending and depth state (`GL_State`), calling GL only for what changed.
    pub fn state(&mut self, api: Api, bits: StateBits) {
        let (gl, old) = (api.gl, self.bits);
        // Safety: a context is current.
        unsafe {
            if bits.depth_equal != old.depth_equal {
                gl.glDepthFunc(if bits.depth_equal { GL_EQUAL } else { GL_LEQUAL });
            }
            if bits.blend != old.blend {
                match bits.blend {
                    Some((src, dst)) => {
                        gl.glEnable(GL_BLEND);
                        gl.glBlendFunc(src, dst);
                    }
                    None => gl.glDisable(GL_BLEND),
                }
            }
            if bits.depth_write != old.depth_write {
                gl.glDepthMask(if bits.depth_write { GL_TRUE } else { GL_FALSE });
            }
            if bits.depth_test != old.depth_test {
                if bits.depth_test { gl.glEnable(GL_DEPTH_TEST) } else { gl.glDisable(GL_DEPTH_TEST) }
            }
        }
        self.bits = bits;
    }
}
