//! The GL error latch (OpenGL 1.5 section 2.5): the first error sticks until `glGetError`
//! reads it; later errors are dropped. Errors are logged at debug level the way Mesa does,
//! with repeats collapsed.

use super::Context;
use super::gl::{self, GLenum};

/// The error state of a context.
#[derive(Default)]
pub struct ErrorState {
    /// The latched error, `GL_NO_ERROR` when none.
    latched: GLenum,
    /// The last logged error and how many times it repeated since.
    last_logged: Option<(GLenum, &'static str)>,
    repeats: u32,
}

impl Context {
    /// The latched error, without clearing it (for the call log, `gl_entry::call_log`).
    pub(crate) fn latched_error(&self) -> GLenum {
        self.errors.latched
    }

    /// Records `error` unless one is already latched.
    pub fn set_error(&mut self, error: GLenum) {
        self.set_error_in(error, "");
    }

    /// Records `error` raised by `command`; logs it at debug level (repeats collapsed).
    pub fn set_error_in(&mut self, error: GLenum, command: &'static str) {
        let e = &mut self.errors;
        if e.latched == gl::GL_NO_ERROR {
            e.latched = error;
        }
        if e.last_logged == Some((error, command)) {
            e.repeats += 1;
            return;
        }
        if e.repeats > 0 {
            log::debug!("{} similar GL errors", e.repeats);
        }
        e.repeats = 0;
        e.last_logged = Some((error, command));
        log::debug!("{} in {}", gl::enum_name(error).unwrap_or("GL error"), command);
    }

    /// `glGetError`: returns and clears the latched error.
    pub fn glGetError(&mut self) -> GLenum {
        std::mem::replace(&mut self.errors.latched, gl::GL_NO_ERROR)
    }

    /// A null pointer where the command needs client memory: the specification defines no
    /// error, so the command does nothing and the event is logged once per command.
    pub fn null_pointer(&mut self, command: &'static str) {
        if self.errors.last_logged != Some((0, command)) {
            log::warn!("{command}: null pointer ignored");
            self.errors.last_logged = Some((0, command));
        }
    }
}
