//! The client attribute stack (OpenGL 1.5 section 6.1.14): `glPushClientAttrib` and
//! `glPopClientAttrib`.
//!
//! Each pushed entry is a list of restore actions, one per group the mask selected; each
//! action owns a copy of the state it puts back. A group is one or more
//! [`ClientAttribEntry::save`] calls in [`Context::glPushClientAttrib`]: the vertex-array group
//! (table 6.8) and the pixel-store group (table 6.17).

use super::Context;
use super::get::Value;
use super::gl::{self, GLbitfield, GLenum};
use super::limits::MAX_CLIENT_ATTRIB_STACK_DEPTH;

/// Puts back one saved piece of state (also the type of the server attribute stack's
/// restores).
pub type Restore = Box<dyn FnOnce(&mut Context) + Send>;

/// One `glPushClientAttrib`: what to restore.
#[derive(Default)]
pub struct ClientAttribEntry {
    restores: Vec<Restore>,
}

impl ClientAttribEntry {
    /// Saves a copy of the state `field` selects, to be written back by `glPopClientAttrib`.
    pub fn save<T: Clone + Send + 'static>(&mut self, ctx: &mut Context, field: fn(&mut Context) -> &mut T) {
        let saved = field(ctx).clone();
        self.restores.push(Box::new(move |ctx| *field(ctx) = saved));
    }
}

/// The client attribute stack.
#[derive(Default)]
pub struct ClientAttribStack {
    entries: Vec<ClientAttribEntry>,
}

impl Context {
    /// `glPushClientAttrib`: `GL_STACK_OVERFLOW` when the stack is full.
    pub fn glPushClientAttrib(&mut self, mask: GLbitfield) {
        if self.client_attrib.entries.len() >= MAX_CLIENT_ATTRIB_STACK_DEPTH {
            return self.set_error_in(gl::GL_STACK_OVERFLOW, "glPushClientAttrib");
        }
        let mut entry = ClientAttribEntry::default();
        if mask & gl::GL_CLIENT_VERTEX_ARRAY_BIT != 0 {
            entry.save(self, |c| &mut c.arrays);
            entry.save(self, |c| &mut c.texunit.client_active);
        }
        if mask & gl::GL_CLIENT_PIXEL_STORE_BIT != 0 {
            entry.save(self, |c| &mut c.pixels.store);
        }
        self.client_attrib.entries.push(entry);
    }

    /// `glPopClientAttrib`: `GL_STACK_UNDERFLOW` when the stack is empty.
    pub fn glPopClientAttrib(&mut self) {
        let Some(entry) = self.client_attrib.entries.pop() else {
            return self.set_error_in(gl::GL_STACK_UNDERFLOW, "glPopClientAttrib");
        };
        let lock = self.arrays.lock;
        for restore in entry.restores {
            restore(self);
        }
        // The lock of EXT_compiled_vertex_array is not pushed state.
        self.arrays.lock = lock;
    }

    /// `GL_CLIENT_ATTRIB_STACK_DEPTH` and `GL_MAX_CLIENT_ATTRIB_STACK_DEPTH`.
    pub(crate) fn query_client_attrib(&self, pname: GLenum) -> Option<Value> {
        Some(match pname {
            gl::GL_CLIENT_ATTRIB_STACK_DEPTH => Value::int(self.client_attrib.entries.len() as i64),
            gl::GL_MAX_CLIENT_ATTRIB_STACK_DEPTH => Value::int(MAX_CLIENT_ATTRIB_STACK_DEPTH as i64),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, gl};

    fn int(ctx: &mut Context, pname: gl::GLenum) -> i32 {
        let mut v = -1;
        unsafe { ctx.glGetIntegerv(pname, &mut v) };
        v
    }

    #[test]
    fn push_pop_restores_arrays_and_client_unit() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindBuffer(gl::GL_ARRAY_BUFFER, 5);
        ctx.glVertexPointer(3, gl::GL_FLOAT, 12, std::ptr::null());
        ctx.glPushClientAttrib(gl::GL_CLIENT_VERTEX_ARRAY_BIT);
        assert_eq!(int(&mut ctx, gl::GL_CLIENT_ATTRIB_STACK_DEPTH), 1);
        ctx.glEnableClientState(gl::GL_VERTEX_ARRAY);
        ctx.glBindBuffer(gl::GL_ARRAY_BUFFER, 0);
        ctx.glVertexPointer(2, gl::GL_SHORT, 0, std::ptr::null());
        ctx.glClientActiveTexture(gl::GL_TEXTURE2);
        ctx.glPopClientAttrib();
        assert_eq!(int(&mut ctx, gl::GL_VERTEX_ARRAY), 0);
        assert_eq!(int(&mut ctx, gl::GL_VERTEX_ARRAY_SIZE), 3);
        assert_eq!(int(&mut ctx, gl::GL_VERTEX_ARRAY_STRIDE), 12);
        assert_eq!(int(&mut ctx, gl::GL_VERTEX_ARRAY_BUFFER_BINDING), 5);
        assert_eq!(int(&mut ctx, gl::GL_ARRAY_BUFFER_BINDING), 5);
        assert_eq!(int(&mut ctx, gl::GL_CLIENT_ACTIVE_TEXTURE), gl::GL_TEXTURE0 as i32);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn push_pop_restores_pixel_store() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);
        ctx.glPixelStorei(gl::GL_PACK_ROW_LENGTH, 7);
        ctx.glPushClientAttrib(gl::GL_CLIENT_PIXEL_STORE_BIT);
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 8);
        ctx.glPixelStorei(gl::GL_PACK_ROW_LENGTH, 3);
        ctx.glPixelStorei(gl::GL_UNPACK_SWAP_BYTES, 1);
        ctx.glPopClientAttrib();
        assert_eq!(int(&mut ctx, gl::GL_UNPACK_ALIGNMENT), 1);
        assert_eq!(int(&mut ctx, gl::GL_PACK_ROW_LENGTH), 7);
        assert_eq!(int(&mut ctx, gl::GL_UNPACK_SWAP_BYTES), 0);
        ctx.glPushClientAttrib(gl::GL_CLIENT_VERTEX_ARRAY_BIT);
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 2);
        ctx.glPopClientAttrib();
        assert_eq!(int(&mut ctx, gl::GL_UNPACK_ALIGNMENT), 2, "the vertex-array group leaves pixel store alone");
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn overflow_and_underflow() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glPopClientAttrib();
        assert_eq!(ctx.glGetError(), gl::GL_STACK_UNDERFLOW);
        let max = int(&mut ctx, gl::GL_MAX_CLIENT_ATTRIB_STACK_DEPTH);
        assert_eq!(max, 16);
        for _ in 0..max {
            ctx.glPushClientAttrib(gl::GL_CLIENT_ALL_ATTRIB_BITS);
        }
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        ctx.glPushClientAttrib(gl::GL_CLIENT_ALL_ATTRIB_BITS);
        assert_eq!(ctx.glGetError(), gl::GL_STACK_OVERFLOW);
        assert_eq!(int(&mut ctx, gl::GL_CLIENT_ATTRIB_STACK_DEPTH), max);
    }
}
