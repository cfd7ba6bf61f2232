//! Texturing (OpenGL 1.5 sections 3.8, 6.1.3–6.1.4) with ARB_texture_compression,
//! EXT_texture_compression_s3tc and EXT_paletted_texture: texture objects, their images and
//! parameters, texture environments and coordinate generation per unit, and the snapshot of
//! what each unit samples for a draw.
//!
//! Images are stored in a canonical form: RGBA8 texels expanded from the base format (see
//! [`crate::frame::texture`]), shared through `Arc`s so that frames hold them without copies.
//! Paletted images keep their indices too, compressed images their blocks. Every change gives
//! the object a fresh content version, unique in the process, so the renderer uploads each
//! version once (DESIGN.md, "Hash tracking").
//!
//! Pixels copied from the framebuffer (`glCopyTexImage*`, `glCopyTexSubImage*`) are not known
//! here: the level is (re)allocated and zero-filled, and a
//! [`crate::frame::pixels::PixelKind::TextureCopy`] is recorded in the frame, in order with the
//! draws, for the renderer to perform on its copy of that content version.

pub mod attrib;
pub mod compressed;
pub mod env;
pub mod formats;
pub mod image;
pub mod mipmap;
pub mod objects;
pub mod palette;
pub mod params;
pub mod s3tc;
pub mod snapshot;
pub mod texgen;

use super::Context;
use super::get::Value;
use super::gl::{self, GLenum};
use super::limits::{MAX_3D_TEXTURE_SIZE, MAX_CUBE_MAP_TEXTURE_SIZE, MAX_TEXTURE_SIZE, MAX_TEXTURE_UNITS};
pub use objects::{Target, TextureObject, TextureTable};

/// Per-context texture state.
#[derive(Clone, Debug)]
pub struct TextureState {
    /// `bindings[unit][target]`: the bound texture names.
    pub bindings: [[u32; 4]; MAX_TEXTURE_UNITS],
    /// The default textures (name 0), one per target.
    pub defaults: [TextureObject; 4],
    /// Proxy textures, one per target (levels hold sizes only).
    pub proxies: [TextureObject; 4],
    /// Texture environment of each unit.
    pub env: [env::TexEnv; MAX_TEXTURE_UNITS],
    /// Texture coordinate generation of each unit.
    pub texgen: [texgen::TexGen; MAX_TEXTURE_UNITS],
    /// The shared palette (EXT_shared_texture_palette).
    pub shared_palette: palette::Palette,
    /// A fresh content version after every change of the shared palette.
    pub shared_palette_version: u64,
}

impl Default for TextureState {
    fn default() -> TextureState {
        let object = |t: Target| TextureObject { target: Some(t), ..TextureObject::new() };
        TextureState {
            bindings: [[0; 4]; MAX_TEXTURE_UNITS],
            defaults: Target::ALL.map(object),
            proxies: Target::ALL.map(object),
            env: Default::default(),
            texgen: Default::default(),
            shared_palette: palette::Palette::default(),
            shared_palette_version: objects::next_version(),
        }
    }
}

impl Context {
    /// `glGet` values of texturing: bindings of the active unit, limits, compressed formats.
    pub(crate) fn query_texture(&self, pname: GLenum) -> Option<Value> {
        let unit = self.active_texture_unit();
        if let Some(t) = Target::ALL.into_iter().find(|t| t.binding_gl() == pname) {
            return Some(Value::int(self.texture.bindings[unit][t.index()]));
        }
        Some(match pname {
            gl::GL_MAX_TEXTURE_SIZE => Value::int(MAX_TEXTURE_SIZE as i64),
            gl::GL_MAX_3D_TEXTURE_SIZE => Value::int(MAX_3D_TEXTURE_SIZE as i64),
            gl::GL_MAX_CUBE_MAP_TEXTURE_SIZE => Value::int(MAX_CUBE_MAP_TEXTURE_SIZE as i64),
            gl::GL_MAX_TEXTURE_LOD_BIAS => Value::float(env::MAX_TEXTURE_LOD_BIAS),
            gl::GL_NUM_COMPRESSED_TEXTURE_FORMATS => Value::int(formats::COMPRESSED_FORMATS.len() as i64),
            gl::GL_COMPRESSED_TEXTURE_FORMATS => Value::Int(formats::COMPRESSED_FORMATS.iter().map(|&f| i64::from(f)).collect()),
            _ => return None,
        })
    }
}
