//! Occlusion queries (OpenGL 1.5 section 4.1.7, `ARB_occlusion_query`): query objects,
//! `glBeginQuery`/`glEndQuery` around draws, and their results.
//!
//! Samples are counted by the renderer, not here. Each ended query is listed in the frame
//! being assembled ([`crate::frame::Frame::occlusion_queries`]: its name and the range of
//! draws it covers) and its result is asked of the renderer through
//! [`crate::frame::FrameSink::occlusion_result`] once that frame has been handed over:
//! - `GL_QUERY_RESULT_AVAILABLE` is false while the query's frame is still being assembled or
//!   the renderer has not answered;
//! - `GL_QUERY_RESULT` waits as the specification says: if the query's frame is still being
//!   assembled, the frame so far is ended (handed to the renderer, as a read-back does), then
//!   the renderer is asked;
//! - a renderer that does not count samples (`GL_QUERY_COUNTER_BITS` 0, which section 4.1.7
//!   allows) answers nothing: the result is then 0 and available once its frame was handed
//!   over, and this is logged once per context.
//!
//! A query still active when a frame ends covers, in the frame where it ends, the draws from
//! that frame's start; the draws of the earlier frame are not counted.

use std::collections::BTreeMap;

use super::Context;
use super::convert::{read_slice, write_slice};
use super::gl::{self, GLboolean, GLenum, GLint, GLsizei, GLuint};

/// One query object.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct QueryObject {
    /// Number of the frame the query ended in.
    frame: u64,
    /// The result, once known.
    result: Option<u64>,
}

/// The active query.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Active {
    id: GLuint,
    /// Frame number and draw index at `glBeginQuery`.
    frame: u64,
    first_draw: usize,
}

/// Query objects of a context: names (reserved by `glGenQueries`, `None` until first begun)
/// and the active `GL_SAMPLES_PASSED` query.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct QueryState {
    objects: BTreeMap<GLuint, Option<QueryObject>>,
    active: Option<Active>,
    warned_no_counter: bool,
}

impl QueryState {
    /// Whether a query is active (between `glBeginQuery` and `glEndQuery`).
    pub fn is_active(&self) -> bool {
        self.active.is_some()
    }
}

impl Context {
    /// `glGenQueries`: `GL_INVALID_VALUE` for a negative count.
    ///
    /// # Safety
    /// `ids` must have room for `n` names.
    pub unsafe fn glGenQueries(&mut self, n: GLsizei, ids: *mut GLuint) {
        if n < 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glGenQueries");
        }
        if ids.is_null() {
            return self.null_pointer("glGenQueries");
        }
        let mut name: GLuint = 1;
        for i in 0..n as usize {
            while self.queries.objects.contains_key(&name) {
                name = name.wrapping_add(1).max(1);
            }
            self.queries.objects.insert(name, None);
            // Safety: the caller guarantees room for n names.
            unsafe { write_slice(ids.add(i), &[name]) };
        }
    }

    /// `glDeleteQueries`: `GL_INVALID_VALUE` for a negative count; an active query is ended
    /// first; unused names and 0 are ignored.
    ///
    /// # Safety
    /// `ids` must point to `n` names.
    pub unsafe fn glDeleteQueries(&mut self, n: GLsizei, ids: *const GLuint) {
        if n < 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glDeleteQueries");
        }
        for i in 0..n as usize {
            // Safety: the caller guarantees n readable names.
            let Some(id) = (unsafe { read_slice(ids.wrapping_add(i), 1) }) else { return self.null_pointer("glDeleteQueries") };
            if self.queries.active.is_some_and(|a| a.id == id[0]) {
                self.end_active_query();
            }
            self.queries.objects.remove(&id[0]);
        }
    }

    /// `glIsQuery`: whether `id` names a query object (one that was begun at least once).
    pub fn glIsQuery(&mut self, id: GLuint) -> GLboolean {
        GLboolean::from(matches!(self.queries.objects.get(&id), Some(Some(_))))
    }

    /// `glBeginQuery`: `GL_INVALID_ENUM` unless `target` is `GL_SAMPLES_PASSED`;
    /// `GL_INVALID_OPERATION` for id 0 or while a query is active.
    pub fn glBeginQuery(&mut self, target: GLenum, id: GLuint) {
        if target != gl::GL_SAMPLES_PASSED {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glBeginQuery");
        }
        if id == 0 || self.queries.active.is_some() {
            return self.set_error_in(gl::GL_INVALID_OPERATION, "glBeginQuery");
        }
        let frame = self.frame.number;
        self.queries.objects.insert(id, Some(QueryObject { frame, result: None }));
        self.queries.active = Some(Active { id, frame, first_draw: self.frame.draws.len() });
    }

    /// `glEndQuery`: `GL_INVALID_ENUM` for another target, `GL_INVALID_OPERATION` when no
    /// query is active.
    pub fn glEndQuery(&mut self, target: GLenum) {
        if target != gl::GL_SAMPLES_PASSED {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glEndQuery");
        }
        if self.queries.active.is_none() {
            return self.set_error_in(gl::GL_INVALID_OPERATION, "glEndQuery");
        }
        self.end_active_query();
    }

    /// Ends the active query: lists it in the frame with the draws it covers.
    fn end_active_query(&mut self) {
        let Some(active) = self.queries.active.take() else { return };
        let frame = self.frame.number;
        let first = if active.frame == frame { active.first_draw } else { 0 };
        self.frame.occlusion_queries.push((active.id, first..self.frame.draws.len()));
        self.queries.objects.insert(active.id, Some(QueryObject { frame, result: None }));
    }

    /// `glGetQueryiv`: `GL_CURRENT_QUERY` (the active query or 0) and
    /// `GL_QUERY_COUNTER_BITS` (the renderer's).
    ///
    /// # Safety
    /// `params` must have room for one value.
    pub unsafe fn glGetQueryiv(&mut self, target: GLenum, pname: GLenum, params: *mut GLint) {
        if target != gl::GL_SAMPLES_PASSED {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glGetQueryiv");
        }
        let value = match pname {
            gl::GL_CURRENT_QUERY => self.queries.active.map_or(0, |a| a.id as GLint),
            gl::GL_QUERY_COUNTER_BITS => self.sink.occlusion_counter_bits() as GLint,
            _ => return self.set_error_in(gl::GL_INVALID_ENUM, "glGetQueryiv"),
        };
        unsafe { write_slice(params, &[value]) }
    }

    /// `glGetQueryObjectiv`: results above `GLint`'s range are clamped.
    ///
    /// # Safety
    /// `params` must have room for one value.
    pub unsafe fn glGetQueryObjectiv(&mut self, id: GLuint, pname: GLenum, params: *mut GLint) {
        if let Some(v) = self.query_object_value(id, pname, "glGetQueryObjectiv") {
            unsafe { write_slice(params, &[v.min(GLint::MAX as u64) as GLint]) }
        }
    }

    /// `glGetQueryObjectuiv`: results above `GLuint`'s range are clamped.
    ///
    /// # Safety
    /// `params` must have room for one value.
    pub unsafe fn glGetQueryObjectuiv(&mut self, id: GLuint, pname: GLenum, params: *mut GLuint) {
        if let Some(v) = self.query_object_value(id, pname, "glGetQueryObjectuiv") {
            unsafe { write_slice(params, &[v.min(u64::from(GLuint::MAX)) as GLuint]) }
        }
    }

    /// `GL_QUERY_RESULT` or `GL_QUERY_RESULT_AVAILABLE` of query `id`; `GL_INVALID_OPERATION`
    /// if `id` is not a query object or is active, `GL_INVALID_ENUM` for another `pname`.
    fn query_object_value(&mut self, id: GLuint, pname: GLenum, command: &'static str) -> Option<u64> {
        let known = matches!(self.queries.objects.get(&id), Some(Some(_)));
        if !known || self.queries.active.is_some_and(|a| a.id == id) {
            self.set_error_in(gl::GL_INVALID_OPERATION, command);
            return None;
        }
        match pname {
            gl::GL_QUERY_RESULT => self.query_result(id, true),
            gl::GL_QUERY_RESULT_AVAILABLE => Some(u64::from(self.query_result(id, false).is_some())),
            _ => {
                self.set_error_in(gl::GL_INVALID_ENUM, command);
                None
            }
        }
    }

    /// The result of query `id`, asking the renderer; with `wait`, the frame being assembled
    /// is ended first if the query is in it, and an unanswered query resolves to 0.
    fn query_result(&mut self, id: GLuint, wait: bool) -> Option<u64> {
        let Some(Some(object)) = self.queries.objects.get(&id).copied() else { return None };
        if object.result.is_some() {
            return object.result;
        }
        if object.frame == self.frame.number {
            if !wait {
                return None;
            }
            self.end_frame();
        }
        let answer = self.sink.occlusion_result(object.frame, id);
        let result = match answer {
            Some(n) => n,
            None if wait || self.sink.occlusion_counter_bits() == 0 => {
                if !std::mem::replace(&mut self.queries.warned_no_counter, true) {
                    log::warn!("occlusion query {id}: the renderer reports no sample count; returning 0");
                }
                0
            }
            None => return None,
        };
        self.queries.objects.insert(id, Some(QueryObject { result: Some(result), ..object }));
        Some(result)
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;
    use std::sync::Arc;

    use parking_lot::Mutex;

    use crate::frame::Frame;
    use crate::frame::FrameSink;
    use crate::translate::context::ContextConfig;
    use crate::translate::gl::{self, GLuint};
    use crate::translate::{Context, dispatch};

    /// A renderer that counts samples: answers from a table once a frame was presented.
    #[derive(Clone, Default)]
    struct Counter {
        frames: Arc<Mutex<Vec<Frame>>>,
        samples: Arc<Mutex<HashMap<(u64, u32), u64>>>,
    }

    impl FrameSink for Counter {
        fn present(&mut self, frame: Frame) {
            self.frames.lock().push(frame);
        }
        fn occlusion_result(&mut self, frame: u64, query: u32) -> Option<u64> {
            let presented = self.frames.lock().iter().any(|f| f.number == frame);
            if presented { self.samples.lock().get(&(frame, query)).copied() } else { None }
        }
        fn occlusion_counter_bits(&self) -> u32 {
            64
        }
    }

    fn get(c: &mut Context, id: GLuint, pname: u32) -> i32 {
        let mut v = -7;
        unsafe { dispatch::glGetQueryObjectiv(c, id, pname, &mut v) };
        v
    }

    #[test]
    fn query_object_errors() {
        let (mut c, _) = Context::with_recording();
        let mut ids = [0u32; 2];
        unsafe {
            dispatch::glGenQueries(&mut c, -1, ids.as_mut_ptr());
            assert_eq!(c.glGetError(), gl::GL_INVALID_VALUE);
            dispatch::glGenQueries(&mut c, 2, ids.as_mut_ptr());
            assert_eq!(ids, [1, 2]);
            assert_eq!(dispatch::glIsQuery(&mut c, 1), 0, "not a query object until begun");
            dispatch::glBeginQuery(&mut c, gl::GL_SAMPLES_PASSED, 0);
            assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION, "id 0");
            dispatch::glBeginQuery(&mut c, gl::GL_TEXTURE_2D, 1);
            assert_eq!(c.glGetError(), gl::GL_INVALID_ENUM);
            dispatch::glEndQuery(&mut c, gl::GL_SAMPLES_PASSED);
            assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION, "no active query");
            dispatch::glBeginQuery(&mut c, gl::GL_SAMPLES_PASSED, 1);
            assert_eq!(dispatch::glIsQuery(&mut c, 1), 1);
            dispatch::glBeginQuery(&mut c, gl::GL_SAMPLES_PASSED, 2);
            assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION, "already active");
            let mut cur = 0;
            dispatch::glGetQueryiv(&mut c, gl::GL_SAMPLES_PASSED, gl::GL_CURRENT_QUERY, &mut cur);
            assert_eq!(cur, 1);
            assert_eq!(get(&mut c, 1, gl::GL_QUERY_RESULT), -7);
            assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION, "result of the active query");
            assert_eq!(get(&mut c, 2, gl::GL_QUERY_RESULT), -7);
            assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION, "never begun");
            dispatch::glEndQuery(&mut c, gl::GL_SAMPLES_PASSED);
            assert_eq!(get(&mut c, 1, gl::GL_QUERY_COUNTER_BITS), -7);
            assert_eq!(c.glGetError(), gl::GL_INVALID_ENUM);
            dispatch::glGetQueryiv(&mut c, gl::GL_SAMPLES_PASSED, gl::GL_CURRENT_QUERY, &mut cur);
            assert_eq!(cur, 0);
            dispatch::glGetQueryiv(&mut c, gl::GL_SAMPLES_PASSED, gl::GL_QUERY_COUNTER_BITS, &mut cur);
            assert_eq!(cur, 0, "no renderer counts samples");
            dispatch::glDeleteQueries(&mut c, 2, ids.as_ptr());
            assert_eq!(dispatch::glIsQuery(&mut c, 1), 0);
            assert_eq!(c.glGetError(), gl::GL_NO_ERROR);
        }
    }

    #[test]
    fn results_without_a_counting_renderer() {
        let (mut c, sink) = Context::with_recording();
        unsafe {
            dispatch::glBeginQuery(&mut c, gl::GL_SAMPLES_PASSED, 5);
            dispatch::glEndQuery(&mut c, gl::GL_SAMPLES_PASSED);
        }
        assert_eq!(get(&mut c, 5, gl::GL_QUERY_RESULT_AVAILABLE), 0, "frame not handed over");
        assert_eq!(sink.frames.lock().len(), 0);
        assert_eq!(get(&mut c, 5, gl::GL_QUERY_RESULT), 0);
        assert_eq!(sink.frames.lock().len(), 1, "reading the result ended the frame");
        assert_eq!(sink.frames.lock()[0].occlusion_queries, vec![(5, 0..0)]);
        assert_eq!(get(&mut c, 5, gl::GL_QUERY_RESULT_AVAILABLE), 1);
    }

    #[test]
    fn results_from_a_counting_renderer() {
        let counter = Counter::default();
        let mut c = Context::new(ContextConfig { share: None, sink: Box::new(counter.clone()) });
        counter.samples.lock().insert((0, 3), 1234);
        unsafe {
            dispatch::glBeginQuery(&mut c, gl::GL_SAMPLES_PASSED, 3);
            dispatch::glEndQuery(&mut c, gl::GL_SAMPLES_PASSED);
            let mut bits = 0;
            dispatch::glGetQueryiv(&mut c, gl::GL_SAMPLES_PASSED, gl::GL_QUERY_COUNTER_BITS, &mut bits);
            assert_eq!(bits, 64);
        }
        assert_eq!(get(&mut c, 3, gl::GL_QUERY_RESULT_AVAILABLE), 0);
        c.end_frame();
        assert_eq!(get(&mut c, 3, gl::GL_QUERY_RESULT_AVAILABLE), 1);
        let mut v = 0u32;
        unsafe { dispatch::glGetQueryObjectuiv(&mut c, 3, gl::GL_QUERY_RESULT, &mut v) };
        assert_eq!(v, 1234);
        // A query of frame 1 the renderer has not answered yet stays unavailable.
        unsafe {
            dispatch::glBeginQuery(&mut c, gl::GL_SAMPLES_PASSED, 4);
            dispatch::glEndQuery(&mut c, gl::GL_SAMPLES_PASSED);
        }
        c.end_frame();
        assert_eq!(get(&mut c, 4, gl::GL_QUERY_RESULT_AVAILABLE), 0);
        counter.samples.lock().insert((1, 4), 9);
        assert_eq!(get(&mut c, 4, gl::GL_QUERY_RESULT_AVAILABLE), 1);
        assert_eq!(get(&mut c, 4, gl::GL_QUERY_RESULT), 9);
    }
}
