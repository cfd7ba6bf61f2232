//! `glDrawBuffers` (OpenGL 2.0 section 4.2.1, `GL_ARB_draw_buffers`, with the rules
//! `GL_EXT_framebuffer_object` adds for framebuffer objects) and its queries.
//!
//! `GL_MAX_DRAW_BUFFERS` is 1: the fixed-function pipeline writes one fragment colour, and a
//! framebuffer object has one colour attachment. So `glDrawBuffers` names at most one buffer,
//! which is the state `glDrawBuffer` sets (`GL_DRAW_BUFFER0` is `GL_DRAW_BUFFER`); unlike
//! `glDrawBuffer`, it takes only single buffers (`GL_FRONT_LEFT`, `GL_BACK_LEFT`,
//! `GL_COLOR_ATTACHMENT0_EXT`...), never names of several (`GL_FRONT`, `GL_FRONT_AND_BACK`).

use super::Context;
use super::convert::read_slice;
use super::get::Value;
use super::gl::{self, GLenum, GLsizei};
use super::lists::ListOp;

/// `GL_MAX_DRAW_BUFFERS`.
pub const MAX_DRAW_BUFFERS: GLsizei = 1;

/// Names of several buffers, which `glDrawBuffers` refuses with `GL_INVALID_OPERATION`
/// (EXT_framebuffer_object's text of section 4.2.1).
const MULTIPLE: &[GLenum] = &[gl::GL_FRONT, gl::GL_BACK, gl::GL_LEFT, gl::GL_RIGHT, gl::GL_FRONT_AND_BACK];

/// Single buffers of the window-system framebuffer (table 4.4) and the error for those the
/// drawable lacks.
const WINDOW: &[GLenum] =
    &[gl::GL_FRONT_LEFT, gl::GL_FRONT_RIGHT, gl::GL_BACK_LEFT, gl::GL_BACK_RIGHT, gl::GL_AUX0, gl::GL_AUX1, gl::GL_AUX2, gl::GL_AUX3];

/// Whether `buf` is `GL_COLOR_ATTACHMENTi_EXT`.
fn is_attachment(buf: GLenum) -> bool {
    (gl::GL_COLOR_ATTACHMENT0_EXT..=gl::GL_COLOR_ATTACHMENT15_EXT).contains(&buf)
}

impl Context {
    /// The error `glDrawBuffers` raises for `buf`, if any: `GL_INVALID_ENUM` for a name that
    /// is no buffer at all, `GL_INVALID_OPERATION` for one that names several buffers, one
    /// the framebuffer lacks, or one of the other kind of framebuffer.
    fn draw_buffers_error(&self, buf: GLenum) -> Option<GLenum> {
        let known = buf == gl::GL_NONE || MULTIPLE.contains(&buf) || WINDOW.contains(&buf) || is_attachment(buf);
        let available = if self.framebuffers.bound != 0 {
            buf == gl::GL_COLOR_ATTACHMENT0_EXT
        } else {
            buf == gl::GL_FRONT_LEFT || (buf == gl::GL_BACK_LEFT && !self.single_buffered)
        };
        match () {
            _ if !known => Some(gl::GL_INVALID_ENUM),
            _ if buf != gl::GL_NONE && !available => Some(gl::GL_INVALID_OPERATION),
            _ => None,
        }
    }

    /// `glDrawBuffers`: `GL_INVALID_VALUE` for `n` outside [0, `GL_MAX_DRAW_BUFFERS`]; with
    /// `n` = 0 no colour is written (`GL_NONE`).
    ///
    /// # Safety
    /// `bufs` must point to `n` enums.
    pub unsafe fn glDrawBuffers(&mut self, n: GLsizei, bufs: *const GLenum) {
        const COMMAND: &str = "glDrawBuffers";
        if !(0..=MAX_DRAW_BUFFERS).contains(&n) {
            return self.set_error_in(gl::GL_INVALID_VALUE, COMMAND);
        }
        let buf = if n == 0 {
            gl::GL_NONE
        } else {
            // Safety: as this function's.
            match unsafe { read_slice(bufs, 1) } {
                Some(b) => b[0],
                None => return self.null_pointer(COMMAND),
            }
        };
        if let Some(error) = self.draw_buffers_error(buf) {
            return self.set_error_in(error, COMMAND);
        }
        if !self.set_object_buffer(buf, false, COMMAND) {
            self.fixed_mut().buffers.draw = buf;
        }
    }

    /// `glDrawBuffers` in a display list: the enums are copied now.
    ///
    /// # Safety
    /// As [`Context::glDrawBuffers`].
    pub unsafe fn compile_glDrawBuffers(&mut self, n: GLsizei, bufs: *const GLenum) {
        // An `n` out of range reads nothing: the list raises its error when it runs.
        let count = if (0..=MAX_DRAW_BUFFERS).contains(&n) { n as usize } else { 0 };
        // Safety: as this function's.
        let Some(copy) = (if count == 0 { Some(Vec::new()) } else { unsafe { read_slice(bufs, count) } }) else {
            return self.null_pointer("glDrawBuffers");
        };
        // Safety: `copy` holds the `n` enums an in-range `n` reads.
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| unsafe { super::dispatch::exec_glDrawBuffers(ctx, n, copy.as_ptr()) })));
    }

    /// `GL_DRAW_BUFFER0` and `GL_MAX_DRAW_BUFFERS`.
    pub(crate) fn query_draw_buffers(&self, pname: GLenum) -> Option<Value> {
        Some(match pname {
            gl::GL_DRAW_BUFFER0 => Value::int(self.object_draw_buffer().unwrap_or(self.fixed.buffers.draw)),
            gl::GL_MAX_DRAW_BUFFERS => Value::int(MAX_DRAW_BUFFERS),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, dispatch, gl};

    fn draw_buffers(ctx: &mut Context, bufs: &[gl::GLenum]) -> gl::GLenum {
        unsafe { dispatch::glDrawBuffers(ctx, bufs.len() as i32, bufs.as_ptr()) };
        ctx.glGetError()
    }

    fn int(ctx: &Context, pname: gl::GLenum) -> i32 {
        ctx.query(pname).unwrap().to_ints()[0]
    }

    #[test]
    fn one_window_buffer_with_the_errors_of_section_4_2_1() {
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(int(&ctx, gl::GL_MAX_DRAW_BUFFERS), 1);
        assert_eq!(int(&ctx, gl::GL_DRAW_BUFFER0), gl::GL_BACK as i32);
        assert_eq!(draw_buffers(&mut ctx, &[gl::GL_FRONT_LEFT]), gl::GL_NO_ERROR);
        assert_eq!(int(&ctx, gl::GL_DRAW_BUFFER0), gl::GL_FRONT_LEFT as i32);
        assert_eq!(int(&ctx, gl::GL_DRAW_BUFFER), gl::GL_FRONT_LEFT as i32);
        assert!(ctx.draw_buffers().front && !ctx.draw_buffers().back);
        assert_eq!(draw_buffers(&mut ctx, &[gl::GL_BACK_LEFT]), gl::GL_NO_ERROR);
        assert!(ctx.draw_buffers().back && !ctx.draw_buffers().front);
        let expected = [
            (gl::GL_FRONT, gl::GL_INVALID_OPERATION),
            (gl::GL_FRONT_AND_BACK, gl::GL_INVALID_OPERATION),
            (gl::GL_BACK_RIGHT, gl::GL_INVALID_OPERATION),
            (gl::GL_AUX0, gl::GL_INVALID_OPERATION),
            (gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_INVALID_OPERATION),
            (gl::GL_TEXTURE_2D, gl::GL_INVALID_ENUM),
        ];
        for (buf, error) in expected {
            assert_eq!(draw_buffers(&mut ctx, &[buf]), error, "{buf:#x}");
        }
        assert_eq!(draw_buffers(&mut ctx, &[gl::GL_FRONT_LEFT, gl::GL_BACK_LEFT]), gl::GL_INVALID_VALUE, "n > max");
        unsafe { dispatch::glDrawBuffers(&mut ctx, -1, [0].as_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        assert_eq!(int(&ctx, gl::GL_DRAW_BUFFER0), gl::GL_BACK_LEFT as i32, "errors change nothing");
        assert_eq!(draw_buffers(&mut ctx, &[]), gl::GL_NO_ERROR);
        assert_eq!(int(&ctx, gl::GL_DRAW_BUFFER0), gl::GL_NONE as i32);
        assert_eq!(draw_buffers(&mut ctx, &[gl::GL_NONE]), gl::GL_NO_ERROR);
    }

    #[test]
    fn framebuffer_objects_take_their_colour_attachment() {
        let (mut ctx, _) = Context::with_recording();
        let mut fbo = 0;
        unsafe {
            dispatch::glGenFramebuffersEXT(&mut ctx, 1, &mut fbo);
            dispatch::glBindFramebufferEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT, fbo);
        }
        assert_eq!(int(&ctx, gl::GL_DRAW_BUFFER0), gl::GL_COLOR_ATTACHMENT0_EXT as i32);
        assert_eq!(draw_buffers(&mut ctx, &[gl::GL_NONE]), gl::GL_NO_ERROR);
        assert_eq!(int(&ctx, gl::GL_DRAW_BUFFER0), gl::GL_NONE as i32);
        assert_eq!(draw_buffers(&mut ctx, &[gl::GL_BACK_LEFT]), gl::GL_INVALID_OPERATION);
        assert_eq!(draw_buffers(&mut ctx, &[gl::GL_COLOR_ATTACHMENT1_EXT]), gl::GL_INVALID_OPERATION, "m >= max attachments");
        assert_eq!(draw_buffers(&mut ctx, &[gl::GL_COLOR_ATTACHMENT0_EXT]), gl::GL_NO_ERROR);
        assert_eq!(int(&ctx, gl::GL_DRAW_BUFFER), gl::GL_COLOR_ATTACHMENT0_EXT as i32);
        unsafe { dispatch::glBindFramebufferEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT, 0) };
        assert_eq!(int(&ctx, gl::GL_DRAW_BUFFER0), gl::GL_BACK as i32, "the window's state is apart");
    }

    #[test]
    fn draw_buffers_in_display_lists() {
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
            dispatch::glDrawBuffers(&mut ctx, 1, [gl::GL_FRONT_LEFT].as_ptr());
            dispatch::glDrawBuffers(&mut ctx, 2, std::ptr::null());
            dispatch::glEndList(&mut ctx);
        }
        assert_eq!((int(&ctx, gl::GL_DRAW_BUFFER0), ctx.glGetError()), (gl::GL_BACK as i32, gl::GL_NO_ERROR));
        unsafe { dispatch::glCallList(&mut ctx, 1) };
        assert_eq!(int(&ctx, gl::GL_DRAW_BUFFER0), gl::GL_FRONT_LEFT as i32);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE, "the bad n is raised when the list runs");
    }
}
