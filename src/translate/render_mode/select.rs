//! Selection (OpenGL 1.5 section 5.2): the name stack, hits and hit records.

use super::buffer::ClientBuffer;
use super::RenderMode;
use crate::translate::Context;
use crate::translate::gl::{self, GLsizei, GLuint};
use crate::translate::limits::MAX_NAME_STACK_DEPTH;

/// Selection state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SelectState {
    /// `glSelectBuffer`'s buffer.
    pub buffer: ClientBuffer,
    /// Whether `glSelectBuffer` was called at least once.
    pub specified: bool,
    /// The name stack.
    pub names: Vec<GLuint>,
    /// Minimum and maximum window z of the hits since the last record, if any.
    pub hit: Option<[f32; 2]>,
    /// Hit records written since selection mode was entered.
    pub hits: i32,
}

/// Window z in [0, 1] as the unsigned integer of a hit record: z × (2³² − 1), rounded.
pub fn depth_to_uint(z: f32) -> GLuint {
    (f64::from(z.clamp(0.0, 1.0)) * f64::from(u32::MAX)).round() as GLuint
}

impl SelectState {
    /// A primitive or raster position with window z `z` was drawn: sets the hit flag.
    pub fn record_hit(&mut self, z: f32) {
        let [lo, hi] = self.hit.get_or_insert([z, z]);
        *lo = lo.min(z);
        *hi = hi.max(z);
    }

    /// Writes the pending hit record, if any: name count, min z, max z, names bottom first.
    ///
    /// # Safety
    /// The selection buffer must still be valid (see [`ClientBuffer::push`]).
    pub unsafe fn flush_hit(&mut self) {
        let Some([lo, hi]) = self.hit.take() else { return };
        unsafe {
            self.buffer.push(self.names.len() as GLuint);
            self.buffer.push(depth_to_uint(lo));
            self.buffer.push(depth_to_uint(hi));
            for &n in &self.names {
                self.buffer.push(n);
            }
        }
        self.hits += 1;
    }

    /// Leaves selection mode: writes the pending record and returns the hit count, or −1 if
    /// the buffer overflowed; the buffer and name stack start empty again.
    ///
    /// # Safety
    /// As [`SelectState::flush_hit`].
    pub unsafe fn finish(&mut self) -> i32 {
        unsafe { self.flush_hit() };
        let result = if self.buffer.overflowed() { -1 } else { self.hits };
        self.buffer.reset();
        self.names.clear();
        self.hits = 0;
        result
    }
}

impl Context {
    /// Runs a name-stack command: ignored outside selection mode; otherwise the pending hit
    /// record is written first (section 5.2).
    fn name_stack(&mut self, change: impl FnOnce(&mut Vec<GLuint>) -> Option<gl::GLenum>, command: &'static str) {
        if self.render_mode.mode != RenderMode::Select {
            return;
        }
        let select = &mut self.render_mode.select;
        // Safety: the program keeps the selection buffer valid while in selection mode.
        unsafe { select.flush_hit() };
        if let Some(error) = change(&mut select.names) {
            self.set_error_in(error, command);
        }
    }

    /// `glSelectBuffer`: `GL_INVALID_VALUE` for a negative size, `GL_INVALID_OPERATION` in
    /// selection mode. The buffer is written during selection, until `glRenderMode` leaves it.
    ///
    /// # Safety
    /// `buffer` must stay valid for `size` values until selection mode is left.
    pub unsafe fn glSelectBuffer(&mut self, size: GLsizei, buffer: *mut GLuint) {
        if size < 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glSelectBuffer");
        }
        if self.render_mode.mode == RenderMode::Select {
            return self.set_error_in(gl::GL_INVALID_OPERATION, "glSelectBuffer");
        }
        if buffer.is_null() && size > 0 {
            self.null_pointer("glSelectBuffer");
        }
        let select = &mut self.render_mode.select;
        select.buffer = ClientBuffer::new(buffer, size as usize);
        select.specified = true;
    }

    /// `glInitNames`: empties the name stack.
    pub fn glInitNames(&mut self) {
        self.name_stack(
            |names| {
                names.clear();
                None
            },
            "glInitNames",
        );
    }

    /// `glPushName`: `GL_STACK_OVERFLOW` at `GL_MAX_NAME_STACK_DEPTH`.
    pub fn glPushName(&mut self, name: GLuint) {
        self.name_stack(
            |names| {
                if names.len() >= MAX_NAME_STACK_DEPTH {
                    return Some(gl::GL_STACK_OVERFLOW);
                }
                names.push(name);
                None
            },
            "glPushName",
        );
    }

    /// `glPopName`: `GL_STACK_UNDERFLOW` when the stack is empty.
    pub fn glPopName(&mut self) {
        self.name_stack(|names| names.pop().map_or(Some(gl::GL_STACK_UNDERFLOW), |_| None), "glPopName");
    }

    /// `glLoadName`: replaces the top name; `GL_INVALID_OPERATION` when the stack is empty.
    pub fn glLoadName(&mut self, name: GLuint) {
        self.name_stack(
            |names| match names.last_mut() {
                Some(top) => {
                    *top = name;
                    None
                }
                None => Some(gl::GL_INVALID_OPERATION),
            },
            "glLoadName",
        );
    }
}
