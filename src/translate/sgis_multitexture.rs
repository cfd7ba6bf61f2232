//! `GL_SGIS_multitexture`, the multitexture extension GLQuake and Quake 2 look for before
//! `GL_ARB_multitexture` (withdrawn before the Khronos registry, so its commands come from
//! `build/overlay.rs`). Both games name the units `TEXTURE0_SGIS = 0x835E` and
//! `TEXTURE1_SGIS = 0x835F`; glrt maps `0x835E + i` to unit `i`.

use super::Context;
use super::gl::{self, GLenum, GLfloat};
use super::limits::MAX_TEXTURE_UNITS;

/// `GL_TEXTURE0_SGIS` as GL 1.x games define it.
pub const GL_TEXTURE0_SGIS: GLenum = 0x835E;

/// The ARB unit enum for an SGIS unit enum, if the unit exists.
fn arb_unit(target: GLenum) -> Option<GLenum> {
    let i = target.checked_sub(GL_TEXTURE0_SGIS)?;
    ((i as usize) < MAX_TEXTURE_UNITS).then(|| gl::GL_TEXTURE0 + i)
}

impl Context {
    /// `glSelectTextureSGIS`: selects the unit for texture state and texture-coordinate
    /// arrays alike (the extension has one selector for both).
    pub fn glSelectTextureSGIS(&mut self, target: GLenum) {
        match arb_unit(target) {
            Some(unit) => {
                self.glActiveTexture(unit);
                self.glClientActiveTexture(unit);
            }
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glSelectTextureSGIS"),
        }
    }

    /// `glMTexCoord2fSGIS`: the texture coordinates of unit `target`.
    pub fn glMTexCoord2fSGIS(&mut self, target: GLenum, s: GLfloat, t: GLfloat) {
        match arb_unit(target) {
            Some(unit) => self.glMultiTexCoord4f(unit, s, t, 0.0, 1.0),
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glMTexCoord2fSGIS"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::GL_TEXTURE0_SGIS;
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn sgis_units_map_to_arb_units() {
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            dispatch::glSelectTextureSGIS(&mut ctx, GL_TEXTURE0_SGIS + 1);
            assert_eq!(ctx.query(gl::GL_ACTIVE_TEXTURE).unwrap().to_ints(), [gl::GL_TEXTURE1 as i32]);
            assert_eq!(ctx.query(gl::GL_CLIENT_ACTIVE_TEXTURE).unwrap().to_ints(), [gl::GL_TEXTURE1 as i32]);
            dispatch::glBegin(&mut ctx, gl::GL_POINTS);
            dispatch::glMTexCoord2fSGIS(&mut ctx, GL_TEXTURE0_SGIS + 1, 0.25, 0.5);
            dispatch::glEnd(&mut ctx);
            assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
            assert_eq!(ctx.query(gl::GL_CURRENT_TEXTURE_COORDS).unwrap().to_doubles(), [0.25, 0.5, 0.0, 1.0]);
            dispatch::glSelectTextureSGIS(&mut ctx, gl::GL_TEXTURE1);
            assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        }
    }
}
