//! Clearing the framebuffer (OpenGL 1.5 section 4.2.3): the clear values, and `glClear`, which
//! records a [`Clear`] in the frame before the next draw with the values and the write masks
//! and scissor box that limit it.

use super::Context;
use super::get::Value;
use super::gl::{self, GLbitfield, GLclampd, GLclampf, GLenum, GLfloat, GLint, GLuint};
use super::implementation::STENCIL_BITS;
use crate::frame::Clear;

/// Clear values of a context.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClearValues {
    /// `glClearColor`, clamped to [0, 1].
    pub color: [f32; 4],
    /// `glClearColorIiEXT` / `glClearColorIuiEXT` (EXT_texture_integer): the clear value of
    /// integer colour buffers, stored unmodified. glrt's colour buffers are never integer
    /// (integer attachments are `GL_FRAMEBUFFER_UNSUPPORTED_EXT`), so no clear uses it; the
    /// spec leaves clearing other buffers with an integer clear colour undefined, and glrt
    /// keeps clearing them with [`ClearValues::color`].
    pub color_integer: [i64; 4],
    /// `glClearIndex`.
    pub index: f32,
    /// `glClearDepth`, clamped to [0, 1].
    pub depth: f64,
    /// `glClearStencil`.
    pub stencil: i32,
    /// `glClearAccum`, clamped to [−1, 1].
    pub accum: [f32; 4],
}

impl Default for ClearValues {
    fn default() -> ClearValues {
        ClearValues { color: [0.0; 4], color_integer: [0; 4], index: 0.0, depth: 1.0, stencil: 0, accum: [0.0; 4] }
    }
}

/// The buffers `glClear` accepts.
const CLEAR_BITS: GLbitfield =
    gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT | gl::GL_STENCIL_BUFFER_BIT | gl::GL_ACCUM_BUFFER_BIT;

impl Context {
    /// `glClearColor`.
    pub fn glClearColor(&mut self, red: GLclampf, green: GLclampf, blue: GLclampf, alpha: GLclampf) {
        self.fixed_mut().clear.color = [red, green, blue, alpha].map(|c| c.clamp(0.0, 1.0));
    }

    /// `glClearColorIiEXT` (EXT_texture_integer): the clear value of signed integer colour
    /// buffers.
    pub fn glClearColorIiEXT(&mut self, red: GLint, green: GLint, blue: GLint, alpha: GLint) {
        self.fixed_mut().clear.color_integer = [red, green, blue, alpha].map(i64::from);
    }

    /// `glClearColorIuiEXT` (EXT_texture_integer): the clear value of unsigned integer colour
    /// buffers.
    pub fn glClearColorIuiEXT(&mut self, red: GLuint, green: GLuint, blue: GLuint, alpha: GLuint) {
        self.fixed_mut().clear.color_integer = [red, green, blue, alpha].map(i64::from);
    }

    /// `glClearIndex`.
    pub fn glClearIndex(&mut self, c: GLfloat) {
        self.fixed_mut().clear.index = c;
    }

    /// `glClearDepth`.
    pub fn glClearDepth(&mut self, depth: GLclampd) {
        self.fixed_mut().clear.depth = depth.clamp(0.0, 1.0);
    }

    /// `glClearStencil`.
    pub fn glClearStencil(&mut self, s: GLint) {
        self.fixed_mut().clear.stencil = s;
    }

    /// `glClearAccum`.
    pub fn glClearAccum(&mut self, red: GLfloat, green: GLfloat, blue: GLfloat, alpha: GLfloat) {
        self.fixed_mut().clear.accum = [red, green, blue, alpha].map(|c| c.clamp(-1.0, 1.0));
    }

    /// `glClear`: `GL_INVALID_VALUE` for bits other than the four buffers. Records the clear
    /// before the next draw of the frame; colour is not cleared while the draw buffer is
    /// `GL_NONE`.
    pub fn glClear(&mut self, mask: GLbitfield) {
        if mask & !CLEAR_BITS != 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glClear");
        }
        if self.render_mode_active() {
            // Selection and feedback modes write no pixels (sections 5.2, 5.3).
            return;
        }
        let Ok(framebuffer) = self.draw_framebuffer() else {
            return self.set_error_in(gl::GL_INVALID_FRAMEBUFFER_OPERATION_EXT, "glClear");
        };
        let draw_buffer = self.object_draw_buffer().unwrap_or(self.fixed.buffers.draw);
        let fbo = framebuffer.object().cloned();
        let f = &self.fixed;
        let has = |bit| mask & bit != 0;
        let clear = Clear {
            before_draw: self.frame.draws.len(),
            color: (has(gl::GL_COLOR_BUFFER_BIT) && draw_buffer != gl::GL_NONE && fbo.as_ref().is_none_or(|o| o.color.is_some()))
                .then_some(f.clear.color),
            draw_buffers: self.draw_buffers(),
            depth: (has(gl::GL_DEPTH_BUFFER_BIT) && fbo.as_ref().is_none_or(|o| o.depth.is_some())).then_some(f.clear.depth),
            stencil: (has(gl::GL_STENCIL_BUFFER_BIT) && fbo.as_ref().is_none_or(|o| o.stencil.is_some()))
                .then_some(f.clear.stencil & ((1 << STENCIL_BITS) - 1)),
            accum: (has(gl::GL_ACCUM_BUFFER_BIT) && fbo.is_none()).then_some(f.clear.accum),
            scissor: self.enables.is_on(gl::GL_SCISSOR_TEST).then_some(self.viewport.scissor),
            color_mask: f.fragment.color_mask,
            depth_mask: f.fragment.depth_write,
            stencil_mask: f.fragment.stencil.clear_mask(),
            framebuffer,
        };
        if clear.color.is_some() || clear.depth.is_some() || clear.stencil.is_some() || clear.accum.is_some() {
            self.enter_framebuffer(&clear.framebuffer);
            let clear = Clear { before_draw: self.frame.draws.len(), ..clear };
            self.frame.clears.push(clear);
            self.keep_frame_in_budget();
        }
    }

    /// Clear-value queries (tables 6.18 and 6.19).
    pub(crate) fn query_clear(&self, pname: GLenum) -> Option<Value> {
        let c = &self.fixed.clear;
        Some(match pname {
            gl::GL_COLOR_CLEAR_VALUE => Value::normalized(&c.color),
            gl::GL_INDEX_CLEAR_VALUE => Value::float(c.index),
            gl::GL_DEPTH_CLEAR_VALUE => Value::Normalized(vec![c.depth]),
            gl::GL_STENCIL_CLEAR_VALUE => Value::int(c.stencil),
            gl::GL_ACCUM_CLEAR_VALUE => Value::normalized(&c.accum),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::frame::Clear;
    use crate::translate::Context;
    use crate::translate::gl;

    #[test]
    fn clear_writes_nothing_in_selection_mode() {
        let (mut ctx, _) = Context::with_recording();
        let mut names = [0u32; 8];
        unsafe { ctx.glSelectBuffer(8, names.as_mut_ptr()) };
        ctx.glRenderMode(gl::GL_SELECT);
        ctx.glClear(gl::GL_COLOR_BUFFER_BIT);
        assert!(ctx.frame.clears.is_empty());
        ctx.glRenderMode(gl::GL_RENDER);
        ctx.glClear(gl::GL_COLOR_BUFFER_BIT);
        assert_eq!(ctx.frame.clears.len(), 1);
    }

    #[test]
    fn clear_records_values_masks_and_scissor() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glClearColor(0.25, 0.5, 2.0, 1.0);
        ctx.glClearDepth(0.5);
        ctx.glClearStencil(0x1ff);
        ctx.glClearAccum(-2.0, 0.0, 0.0, 0.5);
        ctx.glClear(gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT | gl::GL_STENCIL_BUFFER_BIT);
        ctx.glEnable(gl::GL_SCISSOR_TEST);
        ctx.glScissor(1, 2, 3, 4);
        ctx.glColorMask(1, 1, 1, 0);
        ctx.glClear(gl::GL_ACCUM_BUFFER_BIT | gl::GL_COLOR_BUFFER_BIT);
        ctx.glClear(0x10);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glClear(0);
        assert_eq!(ctx.frame.clears.len(), 2);
        assert_eq!(
            ctx.frame.clears[0],
            Clear {
                before_draw: 0,
                color: Some([0.25, 0.5, 1.0, 1.0]),
                depth: Some(0.5),
                stencil: Some(0xff),
                accum: None,
                scissor: None,
                color_mask: [true; 4],
                depth_mask: true,
                stencil_mask: u32::MAX,
                draw_buffers: crate::frame::DrawBuffers::default(),
                framebuffer: crate::frame::Framebuffer::Window,
            }
        );
        let second = &ctx.frame.clears[1];
        assert_eq!(second.accum, Some([-1.0, 0.0, 0.0, 0.5]));
        assert_eq!(second.depth, None);
        assert_eq!(second.scissor, Some([1, 2, 3, 4]));
        assert_eq!(second.color_mask, [true, true, true, false]);
        let mut depth = 0.0f64;
        unsafe { ctx.glGetDoublev(gl::GL_DEPTH_CLEAR_VALUE, &mut depth) };
        assert_eq!(depth, 0.5);
        assert_eq!(ctx.query(gl::GL_STENCIL_CLEAR_VALUE).unwrap().to_ints(), [0x1ff]);
        let mut color = [0i32; 4];
        unsafe { ctx.glGetIntegerv(gl::GL_COLOR_CLEAR_VALUE, color.as_mut_ptr()) };
        assert_eq!([color[2], color[3]], [i32::MAX, i32::MAX]);
        assert!((color[0] - i32::MAX / 4).abs() <= 1, "{color:?}");
        let mut accum = [0.0f32; 4];
        unsafe { ctx.glGetFloatv(gl::GL_ACCUM_CLEAR_VALUE, accum.as_mut_ptr()) };
        assert_eq!(accum, [-1.0, 0.0, 0.0, 0.5]);
        ctx.glDrawBuffer(gl::GL_NONE);
        ctx.glClear(gl::GL_COLOR_BUFFER_BIT);
        assert_eq!(ctx.frame.clears.len(), 2, "nothing to clear with no draw buffer");
    }
}
