//! Colour buffer selection (OpenGL 1.5 sections 4.2.1 and 4.3.2) for glrt's visual, which is
//! double-buffered RGBA without stereo or auxiliary buffers, and `glFlush`/`glFinish` (5.5).

use super::Context;
use crate::frame::pixels::PixelBuffer;
use crate::frame::{ColorBuffer, DrawBuffers, FrameEnd};
use super::get::Value;
use super::gl::{self, GLenum};

/// `glDrawBuffer` and `glReadBuffer` state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BufferState {
    /// `GL_DRAW_BUFFER`.
    pub draw: GLenum,
    /// `GL_READ_BUFFER`.
    pub read: GLenum,
}

impl Default for BufferState {
    /// `GL_BACK` for both in a double-buffered visual.
    fn default() -> BufferState {
        BufferState { draw: gl::GL_BACK, read: gl::GL_BACK }
    }
}

/// Buffers of the visual (left front and back) that a name selects.
const EXISTING: &[GLenum] =
    &[gl::GL_FRONT_LEFT, gl::GL_BACK_LEFT, gl::GL_FRONT, gl::GL_BACK, gl::GL_LEFT, gl::GL_FRONT_AND_BACK, gl::GL_NONE];

/// Names that are valid enums but select buffers the visual lacks (right buffers without
/// stereo, auxiliary buffers).
const MISSING: &[GLenum] =
    &[gl::GL_FRONT_RIGHT, gl::GL_BACK_RIGHT, gl::GL_RIGHT, gl::GL_AUX0, gl::GL_AUX1, gl::GL_AUX2, gl::GL_AUX3];

/// `Ok` if `buf` selects buffers of the visual, else the error: `GL_INVALID_OPERATION` for a
/// valid name of a missing buffer, `GL_INVALID_ENUM` otherwise.
fn check_buffer(buf: GLenum) -> Result<(), GLenum> {
    if EXISTING.contains(&buf) {
        Ok(())
    } else if MISSING.contains(&buf) {
        Err(gl::GL_INVALID_OPERATION)
    } else {
        Err(gl::GL_INVALID_ENUM)
    }
}

/// Whether `buf` (a valid draw or read buffer name) selects the front buffer.
fn names_front(buf: GLenum) -> bool {
    matches!(buf, gl::GL_FRONT | gl::GL_FRONT_LEFT | gl::GL_LEFT | gl::GL_FRONT_AND_BACK)
}

/// Whether `buf` selects the back buffer.
fn names_back(buf: GLenum) -> bool {
    matches!(buf, gl::GL_BACK | gl::GL_BACK_LEFT | gl::GL_LEFT | gl::GL_FRONT_AND_BACK)
}

impl Context {
    /// The colour buffers the draw buffer selects, for the frame: a single-buffered drawable
    /// has no back buffer.
    pub(crate) fn draw_buffers(&self) -> DrawBuffers {
        if let Some(draw) = self.object_draw_buffer() {
            // A framebuffer object's one colour image stands where the back buffer would.
            return DrawBuffers { front: false, back: draw != gl::GL_NONE };
        }
        let draw = self.fixed.buffers.draw;
        DrawBuffers { front: names_front(draw), back: names_back(draw) && !self.single_buffered }
    }

    /// The colour buffer the read buffer selects: always the front buffer of a
    /// single-buffered drawable.
    pub(crate) fn read_color_buffer(&self) -> ColorBuffer {
        if self.framebuffers.read_bound != 0 {
            return ColorBuffer::Back;
        }
        if self.single_buffered || names_front(self.fixed.buffers.read) { ColorBuffer::Front } else { ColorBuffer::Back }
    }

    /// Reads `rect` of `buffer` (the read buffer, for colour) of the frame so far through the
    /// renderer ([`crate::frame::FrameSink::read_pixels`]).
    pub(crate) fn read_framebuffer(&mut self, buffer: PixelBuffer, rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        let Ok(framebuffer) = self.read_framebuffer_object() else {
            self.set_error_in(gl::GL_INVALID_FRAMEBUFFER_OPERATION_EXT, "read");
            return None;
        };
        self.frame.read_buffer = self.read_color_buffer();
        self.frame.read_framebuffer = framebuffer;
        if self.reads_classes() {
            self.classify.route_partial(&mut self.frame);
        }
        let pixels = self.sink.read_pixels(&self.frame, buffer, rect);
        self.part_after_read_back();
        pixels
    }

    /// How a `glXSwapBuffers` ends the frame: a swap for double-buffered drawables, nothing
    /// more than a flush for single-buffered ones (GLX 1.4 section 3.3.10).
    pub(crate) fn swap_end(&self) -> FrameEnd {
        if self.single_buffered { FrameEnd::Flush } else { FrameEnd::Swap }
    }

    /// `glDrawBuffer`.
    pub fn glDrawBuffer(&mut self, buf: GLenum) {
        if self.set_object_buffer(buf, false, "glDrawBuffer") {
            return;
        }
        match check_buffer(buf) {
            Ok(()) => self.fixed_mut().buffers.draw = buf,
            Err(e) => self.set_error_in(e, "glDrawBuffer"),
        }
    }

    /// `glReadBuffer`: `GL_NONE` and `GL_FRONT_AND_BACK` are not sources (`GL_INVALID_ENUM`).
    pub fn glReadBuffer(&mut self, src: GLenum) {
        if self.set_object_buffer(src, true, "glReadBuffer") {
            return;
        }
        let result = match src {
            gl::GL_NONE | gl::GL_FRONT_AND_BACK => Err(gl::GL_INVALID_ENUM),
            _ => check_buffer(src),
        };
        match result {
            Ok(()) => self.fixed_mut().buffers.read = src,
            Err(e) => self.set_error_in(e, "glReadBuffer"),
        }
    }

    /// `glFlush`: a program drawing to the front buffer shows its picture now, so the frame so
    /// far goes to the renderer; otherwise frames end at `glXSwapBuffers` or a read-back.
    pub fn glFlush(&mut self) {
        self.flush_front();
    }

    /// `glFinish`: like `glFlush`; once a renderer draws frames asynchronously it also waits
    /// here until every earlier command's pixels exist.
    pub fn glFinish(&mut self) {
        self.flush_front();
    }

    /// Buffer selection queries (tables 6.19 and 6.20).
    pub(crate) fn query_buffers(&self, pname: GLenum) -> Option<Value> {
        Some(match pname {
            gl::GL_DRAW_BUFFER => Value::int(self.fixed.buffers.draw),
            gl::GL_READ_BUFFER => Value::int(self.fixed.buffers.read),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::gl;

    #[test]
    fn draw_and_read_buffer_errors() {
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(ctx.query(gl::GL_DRAW_BUFFER).unwrap().to_ints(), [gl::GL_BACK as i32]);
        ctx.glDrawBuffer(gl::GL_FRONT_AND_BACK);
        ctx.glReadBuffer(gl::GL_FRONT);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(ctx.query(gl::GL_DRAW_BUFFER).unwrap().to_ints(), [gl::GL_FRONT_AND_BACK as i32]);
        assert_eq!(ctx.query(gl::GL_READ_BUFFER).unwrap().to_ints(), [gl::GL_FRONT as i32]);
        ctx.glDrawBuffer(gl::GL_AUX0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        ctx.glDrawBuffer(gl::GL_BACK_RIGHT);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        ctx.glDrawBuffer(gl::GL_TEXTURE_2D);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glReadBuffer(gl::GL_NONE);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glReadBuffer(gl::GL_AUX1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        assert_eq!(ctx.query(gl::GL_READ_BUFFER).unwrap().to_ints(), [gl::GL_FRONT as i32]);
    }

    #[test]
    fn buffer_names_select_frame_buffers() {
        use crate::frame::{ColorBuffer, DrawBuffers, FrameEnd};
        let (mut ctx, sink) = Context::with_recording();
        let both = DrawBuffers { front: true, back: true };
        let front = DrawBuffers { front: true, back: false };
        let none = DrawBuffers { front: false, back: false };
        for (name, want) in [(gl::GL_BACK, DrawBuffers::default()), (gl::GL_FRONT_LEFT, front), (gl::GL_FRONT_AND_BACK, both), (gl::GL_LEFT, both), (gl::GL_NONE, none)] {
            ctx.glDrawBuffer(name);
            assert_eq!(ctx.draw_buffers(), want, "{name:#x}");
        }
        ctx.glClear(gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        assert_eq!(ctx.frame.clears[0].draw_buffers, none);
        assert_eq!(ctx.frame.clears[0].color, None);
        assert_eq!(ctx.read_color_buffer(), ColorBuffer::Back);
        ctx.glReadBuffer(gl::GL_FRONT);
        assert_eq!(ctx.read_color_buffer(), ColorBuffer::Front);
        ctx.glDrawBuffer(gl::GL_FRONT);
        ctx.glFlush();
        ctx.end_frame();
        ctx.set_double_buffered(false);
        ctx.glDrawBuffer(gl::GL_FRONT_AND_BACK);
        assert_eq!(ctx.draw_buffers(), front, "a single-buffered drawable has no back buffer");
        ctx.glReadBuffer(gl::GL_BACK);
        assert_eq!(ctx.read_color_buffer(), ColorBuffer::Front);
        ctx.glClear(gl::GL_COLOR_BUFFER_BIT);
        ctx.end_frame();
        let ends: Vec<FrameEnd> = sink.frames.lock().iter().map(|f| f.end).collect();
        assert_eq!(ends, [FrameEnd::Flush, FrameEnd::Swap, FrameEnd::Flush]);
    }

    #[test]
    fn single_buffered_contexts_end_frames_at_flush() {
        let (mut ctx, sink) = Context::with_recording();
        ctx.set_double_buffered(false);
        assert_eq!(ctx.query(gl::GL_DRAW_BUFFER).unwrap().to_ints(), vec![gl::GL_FRONT as i32]);
        ctx.glFlush();
        assert_eq!(sink.frames.lock().len(), 0, "nothing drawn, no frame");
        ctx.glClear(gl::GL_COLOR_BUFFER_BIT);
        ctx.glFlush();
        assert_eq!(sink.frames.lock().len(), 1);
        ctx.set_double_buffered(true);
        ctx.glClear(gl::GL_COLOR_BUFFER_BIT);
        ctx.glFinish();
        assert_eq!(sink.frames.lock().len(), 1, "double-buffered: frames end at swaps");
    }
}
