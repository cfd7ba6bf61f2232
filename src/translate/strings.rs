//! `glGetString` (OpenGL 1.5 section 6.1.11): static, NUL-terminated strings.

use super::Context;
use super::gl::{self, GLenum, GLubyte};

/// `GL_VENDOR`.
const VENDOR: &str = "glrt\0";
/// `GL_RENDERER`.
const RENDERER: &str = "glrt (Vulkan path tracer)\0";
/// `GL_VERSION`: "1.5 glrt <crate version>".
const VERSION: &str = concat!("1.5 glrt ", env!("CARGO_PKG_VERSION"), "\0");

/// `GL_EXTENSIONS`: the extensions of `build/overlay.rs` `EXTENSIONS` whose commands and
/// enums are all implemented with their full semantics. Programs enable code paths from this
/// string, so an extension is listed only once it is complete; the lead adds the others
/// (multitexture, texture, vertex-array, buffer and query extensions) as their modules land.
const EXTENSIONS: &str = concat!(
    "GL_ARB_transpose_matrix ",
    "GL_ARB_point_parameters ",
    "GL_EXT_point_parameters ",
    "GL_EXT_blend_color ",
    "GL_EXT_blend_minmax ",
    "GL_EXT_blend_subtract ",
    "GL_EXT_blend_func_separate",
    "\0"
);

impl Context {
    /// `glGetString`: `GL_INVALID_ENUM` (and null) for an unknown name.
    pub fn glGetString(&mut self, name: GLenum) -> *const GLubyte {
        let s = match name {
            gl::GL_VENDOR => VENDOR,
            gl::GL_RENDERER => RENDERER,
            gl::GL_VERSION => VERSION,
            gl::GL_EXTENSIONS => EXTENSIONS,
            _ => {
                self.set_error_in(gl::GL_INVALID_ENUM, "glGetString");
                return std::ptr::null();
            }
        };
        s.as_ptr()
    }
}

#[cfg(test)]
mod tests {
    use std::ffi::CStr;

    use crate::translate::Context;
    use crate::translate::{dispatch, gl};

    fn string(ctx: &mut Context, name: gl::GLenum) -> Option<String> {
        let p = unsafe { dispatch::glGetString(ctx, name) };
        (!p.is_null()).then(|| unsafe { CStr::from_ptr(p.cast()) }.to_str().unwrap().to_owned())
    }

    #[test]
    fn strings_and_errors() {
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(string(&mut ctx, gl::GL_VENDOR).as_deref(), Some("glrt"));
        assert_eq!(string(&mut ctx, gl::GL_VERSION).unwrap(), format!("1.5 glrt {}", env!("CARGO_PKG_VERSION")));
        let ext = string(&mut ctx, gl::GL_EXTENSIONS).unwrap();
        assert!(ext.split(' ').any(|e| e == "GL_EXT_blend_minmax"), "{ext}");
        assert!(!ext.ends_with(' '));
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(string(&mut ctx, gl::GL_FOG), None);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        unsafe { dispatch::glBegin(&mut ctx, gl::GL_POINTS) };
        assert_eq!(string(&mut ctx, gl::GL_VENDOR), None);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    }
}
