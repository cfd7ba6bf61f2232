//! Drawing from vertex arrays (OpenGL 1.5 section 2.8): `glArrayElement`, `glDrawArrays`,
//! `glDrawElements`, `glDrawRangeElements`, `glMultiDrawArrays`, `glMultiDrawElements`, and
//! their display-list forms, which read the arrays when compiled (section 5.4).
//!
//! A draw fetches the array elements it uses into a batch, each array converted over them at
//! once ([`super::array_fetch`]), decomposes it with [`super::assemble`] and hands it to
//! `Context::emit_batch`. `glDrawElements` fetches the index range `min..=max` once and keeps
//! the program's indices (shared vertices stay shared), unless that range is much wider than
//! the index count; then it fetches one vertex per index. Indices, the batch and the other
//! storage a draw needs are reused from draw to draw.

use std::ffi::c_void;

use super::Context;
use super::array_convert::Span;
use super::array_fetch::{FromArrays, decode_indices, index_size};
use super::assemble::{Primitive, assemble_batch};
use super::convert::read_slice;
use super::gl::{self, GLenum, GLint, GLsizei, GLuint};
use super::immediate::{Batch, CurrentAttribs};
use super::limits::MAX_VERTEX_ATTRIBS;
use super::lists::ListOp;
use crate::frame::Attrib;

/// Which array elements a draw reads, in primitive order.
#[derive(Clone, Copy)]
enum Elements<'a> {
    /// `first..first + count`.
    Range(usize, usize),
    /// Program indices.
    Indices(&'a [u32]),
}

/// A compiled draw's vertices, fetched from the arrays: the batch, the batch vertex of each
/// element in primitive order (`None`: in order), and which attributes came from arrays.
#[derive(Clone)]
struct Fetched {
    batch: Batch,
    order: Option<Vec<u32>>,
    from_arrays: FromArrays,
}

impl Fetched {
    /// Replaces the attributes that did not come from arrays by `current` (a compiled draw
    /// uses the current values of the moment it is executed).
    fn take_current(&mut self, current: &CurrentAttribs, generic: usize) {
        let (v, f) = (&mut self.batch.vertices, &self.from_arrays);
        if !f.normal {
            v.normal.set_constant(current.normal);
        }
        if !f.color {
            v.color.set_constant(current.color);
        }
        if !f.secondary_color {
            v.secondary_color.set_constant(current.secondary_color);
        }
        if !f.index {
            v.color_index.set_constant(current.color_index);
        }
        if !f.fog_coord {
            v.fog_coord.set_constant(current.fog_coord);
        }
        if !f.edge_flag {
            self.batch.edge_flags.set_constant(current.edge_flag);
        }
        for ((t, &from), &value) in v.texcoords.iter_mut().zip(&f.texcoord).zip(&current.texcoords) {
            if !from {
                t.set_constant(value);
            }
        }
        // Generic attributes are stored while a program is in use at execution.
        let n = v.len();
        v.generic.resize(generic, Attrib { values: vec![[0.0, 0.0, 0.0, 1.0]; usize::from(n > 0)] });
        for ((g, &from), &value) in v.generic.iter_mut().zip(&f.generic).zip(&current.generic).skip(1) {
            if !from || g.values.is_empty() {
                g.set_constant(value);
            }
        }
    }
}

/// Indices ranges wider than this many times the index count are fetched per index.
const SPARSE_FACTOR: usize = 4;

impl Context {
    /// `glArrayElement`: the attribute commands of element `i` of every enabled array, then
    /// its vertex (section 2.8).
    pub fn glArrayElement(&mut self, i: GLint) {
        let Ok(i) = usize::try_from(i) else {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glArrayElement");
        };
        let fetched = self.with_sources("glArrayElement", |s, ctx| (s.element(i, ctx.immediate.current_mut()), s.color.is_some()));
        let Some((vertex, color_array)) = fetched else { return };
        if color_array {
            self.apply_color_material(self.immediate.current().color);
        }
        if let Some([x, y, z, w]) = vertex {
            self.glVertex4f(x, y, z, w);
        }
    }

    /// `glArrayElement` in a display list: the element's values are recorded as the attribute
    /// and vertex commands it stands for.
    ///
    /// # Safety
    /// The enabled client arrays must hold element `i`.
    pub unsafe fn compile_glArrayElement(&mut self, i: GLint) {
        let Ok(i) = usize::try_from(i) else {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glArrayElement");
        };
        let current = *self.immediate.current();
        if let Some(calls) = self.with_sources("glArrayElement", |s, _| s.element_calls(i, &current)) {
            for call in calls {
                self.lists.record(ListOp::Call(call));
            }
        }
    }

    /// Fetches the vertices of a draw into `batch`, with `generic` generic attributes, and
    /// the batch vertex of each element into `order`; returns whether `order` is used (else
    /// the elements are the batch's vertices in order) and which attributes came from arrays,
    /// or `None` (after raising any error) when nothing is drawn.
    fn fetch(
        &mut self,
        elements: Elements<'_>,
        command: &'static str,
        generic: usize,
        batch: &mut Batch,
        order: &mut Vec<u32>,
    ) -> Option<(bool, FromArrays)> {
        let current = *self.immediate.current();
        let lock = self.arrays.lock.map(|(first, count)| (first as usize, count as usize));
        let fetched = self.with_sources(command, |s, ctx| {
            // Elements past the end of a vertex buffer would all be zero: not fetched, so a
            // wrong count cannot allocate without bound.
            let position = s.position()?;
            let vertex_count = position.len();
            batch.clear_for(generic);
            order.clear();
            let span = match elements {
                Elements::Range(first, count) => {
                    Span::Range(first, first.saturating_add(count).min(vertex_count.max(first)) - first)
                }
                Elements::Indices(indices) => {
                    let min = indices.iter().copied().min().unwrap_or(0);
                    let max = indices.iter().copied().max().unwrap_or(0);
                    let span = (max - min) as usize + 1;
                    if span <= indices.len().saturating_mul(SPARSE_FACTOR).max(64) {
                        order.extend(indices.iter().map(|&i| i - min));
                        Span::Range(min as usize, span)
                    } else {
                        Span::Gather(indices)
                    }
                }
            };
            let storage = &mut ctx.fetch;
            s.fill(span, lock.map(|range| (&mut storage.locked, range)), &current, batch, &mut storage.scratch);
            Some((matches!(span, Span::Range(..)) && matches!(elements, Elements::Indices(_)), s.provided()))
        });
        fetched.flatten()
    }

    /// Decomposes fetched vertices (element `k` is batch vertex `order[k]`, or `k`) and emits
    /// them. With colours from an array, colour material (section 2.14.3) leaves the material
    /// with the last element's colour, as the `glColor` of each `glArrayElement` would; the
    /// renderer applies each vertex's colour to the draw.
    fn submit(&mut self, primitive: Primitive, batch: &mut Batch, order: Option<&[u32]>, color_array: bool) {
        let last = order.map_or(batch.vertices.position.len().checked_sub(1), |o| o.last().map(|&i| i as usize));
        if let Some(color) = last.filter(|_| color_array).and_then(|k| batch.vertices.color.get(k)) {
            self.apply_color_material(color);
        }
        let mut assembled = std::mem::take(&mut self.immediate.assembled);
        assembled.clear();
        assemble_batch(primitive, batch, order, &mut assembled);
        let source = self.arrays_source();
        self.emit_batch(primitive, batch, order, &assembled, source);
        self.immediate.assembled = assembled;
    }

    /// Draws `elements` now, reusing the immediate-mode batch and the fetch storage.
    fn draw_now(&mut self, primitive: Primitive, elements: Elements<'_>, command: &'static str) {
        let mut batch = self.immediate.take_batch();
        let mut order = std::mem::take(&mut self.fetch.order);
        let generic = self.generic_attributes();
        if let Some((ordered, from_arrays)) = self.fetch(elements, command, generic, &mut batch, &mut order) {
            self.submit(primitive, &mut batch, ordered.then_some(order.as_slice()), from_arrays.color);
        }
        self.fetch.order = order;
        self.immediate.batch = batch;
    }

    /// Records a draw whose arrays were read now (section 5.4): at execution, attributes not
    /// taken from arrays use the then-current values.
    fn draw_compiled(&mut self, primitive: Primitive, elements: Elements<'_>, command: &'static str) {
        let mut batch = Batch::default();
        let mut order = Vec::new();
        // Generic arrays are kept whether or not a program is in use now: one may be when the
        // list runs.
        let generic_arrays = self.arrays.generic[1..].iter().any(|a| a.enabled);
        let generic = if generic_arrays { MAX_VERTEX_ATTRIBS } else { self.generic_attributes() };
        let Some((ordered, from_arrays)) = self.fetch(elements, command, generic, &mut batch, &mut order) else { return };
        let order = ordered.then_some(order);
        let fetched = Fetched { batch, order, from_arrays };
        // The generated dispatch applies the glBegin/glEnd rule to this deferred draw.
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| {
            let mut f = fetched.clone();
            f.take_current(ctx.immediate.current(), ctx.generic_attributes());
            ctx.submit(primitive, &mut f.batch, f.order.as_deref(), f.from_arrays.color);
        })));
    }

    /// Checks `glDrawArrays` arguments: the mode and the element range.
    fn draw_arrays_args(
        &mut self,
        mode: GLenum,
        first: GLint,
        count: GLsizei,
    ) -> Option<(Primitive, Elements<'static>)> {
        let Some(primitive) = Primitive::from_gl(mode) else {
            self.set_error_in(gl::GL_INVALID_ENUM, "glDrawArrays");
            return None;
        };
        let (Ok(first), Ok(count)) = (usize::try_from(first), usize::try_from(count)) else {
            self.set_error_in(gl::GL_INVALID_VALUE, "glDrawArrays");
            return None;
        };
        Some((primitive, Elements::Range(first, count)))
    }

    /// `glDrawArrays`.
    pub fn glDrawArrays(&mut self, mode: GLenum, first: GLint, count: GLsizei) {
        if let Some((p, e)) = self.draw_arrays_args(mode, first, count) {
            self.draw_now(p, e, "glDrawArrays");
        }
    }

    /// `glDrawArrays` in a display list.
    ///
    /// # Safety
    /// The enabled client arrays must hold the drawn elements.
    pub unsafe fn compile_glDrawArrays(&mut self, mode: GLenum, first: GLint, count: GLsizei) {
        if let Some((p, e)) = self.draw_arrays_args(mode, first, count) {
            self.draw_compiled(p, e, "glDrawArrays");
        }
    }

    /// Checks `glDrawElements` arguments, decodes the indices (from the client or the
    /// element array buffer) into the fetch storage and runs `draw` on them.
    unsafe fn read_elements(
        &mut self,
        mode: GLenum,
        count: GLsizei,
        type_: GLenum,
        indices: *const c_void,
        command: &'static str,
        draw: fn(&mut Context, Primitive, Elements<'_>, &'static str),
    ) {
        let mut decoded = std::mem::take(&mut self.fetch.indices);
        decoded.clear();
        if let Some(primitive) = unsafe { self.decode_elements(mode, count, type_, indices, command, &mut decoded) } {
            draw(self, primitive, Elements::Indices(&decoded), command);
        }
        self.fetch.indices = decoded;
    }

    /// The checks and decoding of [`Context::read_elements`]: the primitive, with the indices
    /// appended to `out`.
    unsafe fn decode_elements(
        &mut self,
        mode: GLenum,
        count: GLsizei,
        type_: GLenum,
        indices: *const c_void,
        command: &'static str,
        out: &mut Vec<u32>,
    ) -> Option<Primitive> {
        let Some(primitive) = Primitive::from_gl(mode) else {
            self.set_error_in(gl::GL_INVALID_ENUM, command);
            return None;
        };
        let Ok(count) = usize::try_from(count) else {
            self.set_error_in(gl::GL_INVALID_VALUE, command);
            return None;
        };
        let Some(width) = index_size(type_) else {
            self.set_error_in(gl::GL_INVALID_ENUM, command);
            return None;
        };
        let bytes_len = count.checked_mul(width)?;
        if self.arrays.element_buffer == 0 {
            if indices.is_null() {
                self.null_pointer(command);
                return None;
            }
            super::capture::reads::note(indices, bytes_len);
            // Safety: the caller guarantees `count` readable indices at `indices`.
            let bytes = unsafe { std::slice::from_raw_parts(indices.cast::<u8>(), bytes_len) };
            decode_indices(bytes, width, out);
            return Some(primitive);
        }
        let shared = self.shared.clone();
        let guard = shared.lock();
        let buffer = guard.buffers.get(self.arrays.element_buffer)?;
        if buffer.mapped {
            drop(guard);
            self.set_error_in(gl::GL_INVALID_OPERATION, command);
            return None;
        }
        let start = indices as usize;
        let bytes = buffer.data.get(start..start.checked_add(bytes_len)?)?;
        decode_indices(bytes, width, out);
        Some(primitive)
    }

    /// `glDrawElements`.
    ///
    /// # Safety
    /// Without an element array buffer, `indices` must point to `count` indices of `type_`;
    /// the enabled client arrays must hold the elements they name.
    pub unsafe fn glDrawElements(&mut self, mode: GLenum, count: GLsizei, type_: GLenum, indices: *const c_void) {
        unsafe { self.read_elements(mode, count, type_, indices, "glDrawElements", Context::draw_now) }
    }

    /// `glDrawElements` in a display list.
    ///
    /// # Safety
    /// As [`Context::glDrawElements`].
    pub unsafe fn compile_glDrawElements(
        &mut self,
        mode: GLenum,
        count: GLsizei,
        type_: GLenum,
        indices: *const c_void,
    ) {
        unsafe { self.read_elements(mode, count, type_, indices, "glDrawElements", Context::draw_compiled) }
    }

    /// `glDrawRangeElements`: `GL_INVALID_VALUE` when `end < start`.
    ///
    /// # Safety
    /// As [`Context::glDrawElements`].
    pub unsafe fn glDrawRangeElements(
        &mut self,
        mode: GLenum,
        start: GLuint,
        end: GLuint,
        count: GLsizei,
        type_: GLenum,
        indices: *const c_void,
    ) {
        unsafe { self.draw_range_elements(start, end, mode, count, type_, indices, Context::draw_now) }
    }

    /// `glDrawRangeElements` in a display list.
    ///
    /// # Safety
    /// As [`Context::glDrawElements`].
    pub unsafe fn compile_glDrawRangeElements(
        &mut self,
        mode: GLenum,
        start: GLuint,
        end: GLuint,
        count: GLsizei,
        type_: GLenum,
        indices: *const c_void,
    ) {
        unsafe { self.draw_range_elements(start, end, mode, count, type_, indices, Context::draw_compiled) }
    }

    /// `glDrawRangeElements` checks, then `draw` (now, or into the list being compiled).
    #[allow(clippy::too_many_arguments)] // the command's arguments and the draw to run
    unsafe fn draw_range_elements(
        &mut self,
        start: GLuint,
        end: GLuint,
        mode: GLenum,
        count: GLsizei,
        type_: GLenum,
        indices: *const c_void,
        draw: fn(&mut Context, Primitive, Elements<'_>, &'static str),
    ) {
        if end < start {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glDrawRangeElements");
        }
        unsafe { self.read_elements(mode, count, type_, indices, "glDrawRangeElements", draw) }
    }

    /// The `(first, count)` pairs of `glMultiDrawArrays`; `GL_INVALID_VALUE` for a negative
    /// `drawcount` or any negative count, and then nothing is drawn (the command is one
    /// command: a bad range makes the whole call fail, as in Mesa).
    unsafe fn multi_ranges(
        &mut self,
        first: *const GLint,
        count: *const GLsizei,
        drawcount: GLsizei,
    ) -> Option<Vec<(GLint, GLsizei)>> {
        let Ok(n) = usize::try_from(drawcount) else {
            self.set_error_in(gl::GL_INVALID_VALUE, "glMultiDrawArrays");
            return None;
        };
        let (Some(firsts), Some(counts)) = (unsafe { read_slice(first, n) }, unsafe { read_slice(count, n) }) else {
            self.null_pointer("glMultiDrawArrays");
            return None;
        };
        if counts.iter().any(|&c| c < 0) {
            self.set_error_in(gl::GL_INVALID_VALUE, "glMultiDrawArrays");
            return None;
        }
        Some(firsts.into_iter().zip(counts).collect())
    }

    /// `glMultiDrawArrays`: `glDrawArrays` for each range.
    ///
    /// # Safety
    /// `first` and `count` must point to `drawcount` values; the arrays must hold the elements.
    pub unsafe fn glMultiDrawArrays(
        &mut self,
        mode: GLenum,
        first: *const GLint,
        count: *const GLsizei,
        drawcount: GLsizei,
    ) {
        for (f, c) in unsafe { self.multi_ranges(first, count, drawcount) }.unwrap_or_default() {
            self.glDrawArrays(mode, f, c);
        }
    }

    /// `glMultiDrawArrays` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMultiDrawArrays`].
    pub unsafe fn compile_glMultiDrawArrays(
        &mut self,
        mode: GLenum,
        first: *const GLint,
        count: *const GLsizei,
        drawcount: GLsizei,
    ) {
        for (f, c) in unsafe { self.multi_ranges(first, count, drawcount) }.unwrap_or_default() {
            unsafe { self.compile_glDrawArrays(mode, f, c) };
        }
    }

    /// The `(count, indices)` pairs of `glMultiDrawElements`.
    unsafe fn multi_elements(
        &mut self,
        count: *const GLsizei,
        indices: *const *const c_void,
        drawcount: GLsizei,
    ) -> Option<Vec<(GLsizei, *const c_void)>> {
        let Ok(n) = usize::try_from(drawcount) else {
            self.set_error_in(gl::GL_INVALID_VALUE, "glMultiDrawElements");
            return None;
        };
        let (Some(counts), Some(pointers)) = (unsafe { read_slice(count, n) }, unsafe { read_slice(indices, n) })
        else {
            self.null_pointer("glMultiDrawElements");
            return None;
        };
        if counts.iter().any(|&c| c < 0) {
            self.set_error_in(gl::GL_INVALID_VALUE, "glMultiDrawElements");
            return None;
        }
        // Index-list addresses read from client memory are captured addresses in a replay.
        Some(counts.into_iter().zip(pointers.into_iter().map(super::capture::client_pointer)).collect())
    }

    /// `glMultiDrawElements`: `glDrawElements` for each index list.
    ///
    /// # Safety
    /// `count` and `indices` must point to `drawcount` values, each index list as
    /// [`Context::glDrawElements`] requires.
    pub unsafe fn glMultiDrawElements(
        &mut self,
        mode: GLenum,
        count: *const GLsizei,
        type_: GLenum,
        indices: *const *const c_void,
        drawcount: GLsizei,
    ) {
        for (c, p) in unsafe { self.multi_elements(count, indices, drawcount) }.unwrap_or_default() {
            unsafe { self.glDrawElements(mode, c, type_, p) };
        }
    }

    /// `glMultiDrawElements` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMultiDrawElements`].
    pub unsafe fn compile_glMultiDrawElements(
        &mut self,
        mode: GLenum,
        count: *const GLsizei,
        type_: GLenum,
        indices: *const *const c_void,
        drawcount: GLsizei,
    ) {
        for (c, p) in unsafe { self.multi_elements(count, indices, drawcount) }.unwrap_or_default() {
            unsafe { self.compile_glDrawElements(mode, c, type_, p) };
        }
    }
}

#[cfg(test)]
mod tests {
    use std::ffi::c_void;

    use crate::frame::{DrawSource, Topology};
    use crate::translate::{Context, dispatch, gl};

    fn int(ctx: &mut Context, pname: gl::GLenum) -> i32 {
        let mut v = -1;
        unsafe { ctx.glGetIntegerv(pname, &mut v) };
        v
    }

    /// A unit square as a triangle fan of 4 vertices `(x, y)`.
    const SQUARE: [f32; 8] = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    #[test]
    fn draw_arrays_reads_client_memory() {
        let (mut ctx, _) = Context::with_recording();
        let colors: [u8; 16] = [255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255];
        ctx.glVertexPointer(2, gl::GL_FLOAT, 0, SQUARE.as_ptr().cast());
        ctx.glColorPointer(4, gl::GL_UNSIGNED_BYTE, 0, colors.as_ptr().cast());
        ctx.glEnableClientState(gl::GL_VERTEX_ARRAY);
        ctx.glEnableClientState(gl::GL_COLOR_ARRAY);
        ctx.glDrawArrays(gl::GL_TRIANGLE_FAN, 0, 4);
        let d = &ctx.frame.draws[0];
        assert_eq!(d.source, DrawSource::Arrays);
        assert_eq!(d.indices, vec![0, 1, 2, 0, 2, 3]);
        assert_eq!(d.vertices.position[2], [1.0, 1.0, 0.0, 1.0]);
        assert_eq!(d.vertices.color.get(1), Some([0.0, 1.0, 0.0, 1.0]));
        assert!(d.vertices.normal.is_constant(), "a disabled array gives the current value");
        ctx.glDrawArrays(gl::GL_POINTS, 1, 2);
        assert_eq!(ctx.frame.draws[1].vertices.position[0], [1.0, 0.0, 0.0, 1.0]);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        ctx.glDisableClientState(gl::GL_VERTEX_ARRAY);
        ctx.glDrawArrays(gl::GL_POINTS, 0, 4);
        assert_eq!(ctx.frame.draws.len(), 2, "nothing is drawn without the vertex array");
        ctx.glVertexPointer(2, gl::GL_FLOAT, 0, std::ptr::null());
        ctx.glEnableClientState(gl::GL_VERTEX_ARRAY);
        ctx.glDrawArrays(gl::GL_POINTS, 0, 4);
        assert_eq!(ctx.frame.draws.len(), 2, "a null client pointer is ignored, not read");
    }

    #[test]
    fn draw_elements_each_index_type() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glVertexPointer(2, gl::GL_FLOAT, 0, SQUARE.as_ptr().cast());
        ctx.glEnableClientState(gl::GL_VERTEX_ARRAY);
        let ub: [u8; 6] = [0, 1, 2, 2, 3, 0];
        let us: [u16; 6] = [0, 1, 2, 2, 3, 0];
        let ui: [u32; 6] = [0, 1, 2, 2, 3, 0];
        let lists: [(gl::GLenum, *const c_void); 3] = [
            (gl::GL_UNSIGNED_BYTE, ub.as_ptr().cast()),
            (gl::GL_UNSIGNED_SHORT, us.as_ptr().cast()),
            (gl::GL_UNSIGNED_INT, ui.as_ptr().cast()),
        ];
        for (i, (ty, ptr)) in lists.into_iter().enumerate() {
            ctx.glLoadIdentity();
            ctx.glTranslatef(i as f32, 0.0, 0.0);
            unsafe { ctx.glDrawElements(gl::GL_TRIANGLES, 6, ty, ptr) };
            let d = ctx.frame.draws.last().unwrap();
            assert_eq!(d.vertex_count, 4, "shared vertices are fetched once");
            assert_eq!(d.indices, vec![0, 1, 2, 2, 3, 0]);
            assert_eq!(d.vertices.position[3], [0.0, 1.0, 0.0, 1.0]);
        }
        assert_eq!(ctx.frame.draws.len(), 3);
        unsafe { ctx.glDrawElements(gl::GL_TRIANGLES, 6, gl::GL_FLOAT, ui.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        unsafe { ctx.glDrawElements(gl::GL_TRIANGLES, -1, gl::GL_UNSIGNED_INT, ui.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        unsafe { ctx.glDrawRangeElements(gl::GL_TRIANGLES, 3, 0, 6, gl::GL_UNSIGNED_INT, ui.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE, "end < start");
        unsafe { ctx.glDrawRangeElements(gl::GL_LINES, 0, 3, 2, gl::GL_UNSIGNED_INT, ui[1..].as_ptr().cast()) };
        let d = ctx.frame.draws.last().unwrap();
        assert_eq!((d.topology, d.vertex_count, d.indices.clone()), (Topology::Lines, 2, vec![0, 1]));
        ctx.glDrawArrays(gl::GL_POLYGON + 1, 0, 3);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glDrawArrays(gl::GL_TRIANGLES, 0, -3);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    }

    #[test]
    fn sparse_indices_fetch_per_index() {
        let (mut ctx, _) = Context::with_recording();
        let far: Vec<f32> = (0..2000).map(|i| i as f32).collect();
        ctx.glVertexPointer(2, gl::GL_FLOAT, 0, far.as_ptr().cast());
        ctx.glEnableClientState(gl::GL_VERTEX_ARRAY);
        let idx: [u16; 2] = [0, 999];
        unsafe { ctx.glDrawElements(gl::GL_LINES, 2, gl::GL_UNSIGNED_SHORT, idx.as_ptr().cast()) };
        let d = &ctx.frame.draws[0];
        assert_eq!(d.vertex_count, 2);
        assert_eq!(d.vertices.position[1], [1998.0, 1999.0, 0.0, 1.0]);
    }

    #[test]
    fn buffer_object_draws() {
        let (mut ctx, _) = Context::with_recording();
        // Two floats of padding, then the square.
        let mut data = vec![9.0f32, 9.0];
        data.extend_from_slice(&SQUARE);
        ctx.glBindBuffer(gl::GL_ARRAY_BUFFER, 1);
        unsafe { ctx.glBufferData(gl::GL_ARRAY_BUFFER, 40, data.as_ptr().cast(), gl::GL_STATIC_DRAW) };
        ctx.glVertexPointer(2, gl::GL_FLOAT, 8, 8 as *const c_void);
        ctx.glBindBuffer(gl::GL_ARRAY_BUFFER, 0);
        assert_eq!(int(&mut ctx, gl::GL_VERTEX_ARRAY_BUFFER_BINDING), 1);
        ctx.glEnableClientState(gl::GL_VERTEX_ARRAY);
        let idx: [u16; 4] = [0, 1, 2, 3];
        ctx.glBindBuffer(gl::GL_ELEMENT_ARRAY_BUFFER, 2);
        unsafe { ctx.glBufferData(gl::GL_ELEMENT_ARRAY_BUFFER, 8, idx.as_ptr().cast(), gl::GL_STATIC_DRAW) };
        unsafe { ctx.glDrawElements(gl::GL_QUADS, 4, gl::GL_UNSIGNED_SHORT, std::ptr::null()) };
        let d = &ctx.frame.draws[0];
        assert_eq!(
            d.vertices.position,
            vec![[0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0], [1.0, 1.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]]
        );
        assert_eq!(d.indices, vec![0, 1, 3, 1, 2, 3]);
        // Past the end of the store: elements are not fetched, whatever the count.
        ctx.glDrawArrays(gl::GL_POINTS, 3, i32::MAX);
        assert_eq!(ctx.frame.draws.last().unwrap().vertex_count, 1);
        let count = ctx.frame.draws.len();
        ctx.glDrawArrays(gl::GL_POINTS, 30, 3);
        assert_eq!(ctx.frame.draws.len(), count, "nothing drawn from past the end");
        // Indices past the end of the vertex buffer read as zero.
        ctx.glBindBuffer(gl::GL_ELEMENT_ARRAY_BUFFER, 0);
        let far: [u32; 2] = [1, 100];
        unsafe { ctx.glDrawElements(gl::GL_LINES, 2, gl::GL_UNSIGNED_INT, far.as_ptr().cast()) };
        let d = ctx.frame.draws.last().unwrap();
        assert_eq!(d.vertices.position, vec![[1.0, 0.0, 0.0, 1.0], [0.0; 4]]);
        ctx.glBindBuffer(gl::GL_ELEMENT_ARRAY_BUFFER, 2);
        // Indices past the end of the element buffer: nothing drawn.
        let before = ctx.frame.draws.len();
        unsafe { ctx.glDrawElements(gl::GL_POINTS, 8, gl::GL_UNSIGNED_SHORT, std::ptr::null()) };
        assert_eq!(ctx.frame.draws.len(), before);
        // A mapped buffer cannot be drawn from.
        ctx.glBindBuffer(gl::GL_ARRAY_BUFFER, 1);
        ctx.glMapBuffer(gl::GL_ARRAY_BUFFER, gl::GL_READ_ONLY);
        ctx.glDrawArrays(gl::GL_POINTS, 0, 1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        assert_eq!(ctx.frame.draws.len(), before);
    }

    #[test]
    fn arrays_shorter_than_the_draw_read_zero_past_their_buffer() {
        let (mut ctx, _) = Context::with_recording();
        // Two colours in a buffer; four vertices in client memory.
        let colors: [u8; 8] = [255, 0, 0, 255, 0, 255, 0, 255];
        ctx.glBindBuffer(gl::GL_ARRAY_BUFFER, 1);
        unsafe { ctx.glBufferData(gl::GL_ARRAY_BUFFER, 8, colors.as_ptr().cast(), gl::GL_STATIC_DRAW) };
        ctx.glColorPointer(4, gl::GL_UNSIGNED_BYTE, 0, std::ptr::null());
        ctx.glBindBuffer(gl::GL_ARRAY_BUFFER, 0);
        ctx.glVertexPointer(2, gl::GL_FLOAT, 0, SQUARE.as_ptr().cast());
        ctx.glEnableClientState(gl::GL_VERTEX_ARRAY);
        ctx.glEnableClientState(gl::GL_COLOR_ARRAY);
        for draw in 0..2 {
            if draw == 0 {
                ctx.glDrawArrays(gl::GL_POINTS, 0, 4);
            } else {
                ctx.glTranslatef(1.0, 0.0, 0.0);
                let idx: [u16; 4] = [0, 1, 2, 3];
                unsafe { ctx.glDrawElements(gl::GL_POINTS, 4, gl::GL_UNSIGNED_SHORT, idx.as_ptr().cast()) };
            }
            let d = ctx.frame.draws.last().unwrap();
            assert_eq!(d.vertices.position[3], [0.0, 1.0, 0.0, 1.0]);
            let colors: Vec<_> = (0..4).map(|k| d.vertices.color.get(k)).collect();
            assert_eq!(colors, [Some([1.0, 0.0, 0.0, 1.0]), Some([0.0, 1.0, 0.0, 1.0]), Some([0.0; 4]), Some([0.0; 4])]);
        }
        assert_eq!(ctx.frame.draws.len(), 2);
    }

    #[test]
    fn locked_positions_are_converted_once_per_lock() {
        let (mut ctx, _) = Context::with_recording();
        let mut xyz = SQUARE;
        let mut colors: [u8; 16] = [255; 16];
        let (xyz_ptr, colors_ptr) = (xyz.as_mut_ptr(), colors.as_mut_ptr());
        ctx.glVertexPointer(2, gl::GL_FLOAT, 0, xyz_ptr.cast_const().cast());
        ctx.glColorPointer(4, gl::GL_UNSIGNED_BYTE, 0, colors_ptr.cast_const().cast());
        ctx.glEnableClientState(gl::GL_VERTEX_ARRAY);
        ctx.glEnableClientState(gl::GL_COLOR_ARRAY);
        let idx: [u8; 6] = [0, 1, 2, 2, 3, 0];
        ctx.glLockArraysEXT(0, 4);
        unsafe { ctx.glDrawElements(gl::GL_TRIANGLES, 6, gl::GL_UNSIGNED_BYTE, idx.as_ptr().cast()) };
        // Within the lock, positions are what the first draw converted; colours are read again.
        unsafe {
            xyz_ptr.write(-7.0);
            colors_ptr.write(0);
        }
        ctx.glTranslatef(1.0, 0.0, 0.0);
        unsafe { ctx.glDrawElements(gl::GL_TRIANGLES, 6, gl::GL_UNSIGNED_BYTE, idx.as_ptr().cast()) };
        ctx.glUnlockArraysEXT();
        let d = &ctx.frame.draws[1];
        assert_eq!(d.vertices.position[0], [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(d.vertices.color.get(0), Some([0.0, 1.0, 1.0, 1.0]));
        assert!(d.vertices.color.get(1) == Some([1.0; 4]) && !d.vertices.color.is_constant());
        assert!(ctx.frame.draws[0].vertices.color.is_constant(), "equal colours from an array are stored once");
        ctx.glTranslatef(1.0, 0.0, 0.0);
        unsafe { ctx.glDrawElements(gl::GL_TRIANGLES, 6, gl::GL_UNSIGNED_BYTE, idx.as_ptr().cast()) };
        assert_eq!(ctx.frame.draws[2].vertices.position[0], [-7.0, 0.0, 0.0, 1.0], "unlocked: read again");
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn compiled_draws_keep_the_data_of_compile_time() {
        let (mut ctx, _) = Context::with_recording();
        let mut verts = SQUARE;
        let idx: [u8; 3] = [0, 1, 2];
        ctx.glVertexPointer(2, gl::GL_FLOAT, 0, verts.as_ptr().cast());
        ctx.glEnableClientState(gl::GL_VERTEX_ARRAY);
        unsafe {
            dispatch::glNewList(&mut ctx, 7, gl::GL_COMPILE);
            dispatch::glDrawArrays(&mut ctx, gl::GL_TRIANGLES, 0, 3);
            dispatch::glDrawElements(&mut ctx, gl::GL_LINES, 2, gl::GL_UNSIGNED_BYTE, idx[1..].as_ptr().cast());
            dispatch::glBegin(&mut ctx, gl::GL_POINTS);
            dispatch::glArrayElement(&mut ctx, 3);
            dispatch::glEnd(&mut ctx);
            dispatch::glEndList(&mut ctx);
        }
        assert!(ctx.frame.draws.is_empty(), "GL_COMPILE draws nothing");
        verts.fill(-5.0);
        std::hint::black_box(&verts);
        unsafe {
            dispatch::glColor3f(&mut ctx, 0.0, 0.0, 1.0);
            dispatch::glCallList(&mut ctx, 7);
        }
        let draws = &ctx.frame.draws;
        assert_eq!(draws.len(), 3);
        assert_eq!(draws[0].source, DrawSource::List(7));
        assert_eq!(draws[0].vertices.position[1], [1.0, 0.0, 0.0, 1.0]);
        assert_eq!(draws[0].vertices.color.get(0), Some([0.0, 0.0, 1.0, 1.0]), "current colour at execution");
        assert_eq!(draws[1].vertices.position, vec![[1.0, 0.0, 0.0, 1.0], [1.0, 1.0, 0.0, 1.0]]);
        assert_eq!(draws[2].vertices.position, vec![[0.0, 1.0, 0.0, 1.0]]);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn multi_draw() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glVertexPointer(2, gl::GL_FLOAT, 0, SQUARE.as_ptr().cast());
        ctx.glEnableClientState(gl::GL_VERTEX_ARRAY);
        let (first, count) = ([0, 2], [2, 2]);
        unsafe { ctx.glMultiDrawArrays(gl::GL_LINES, first.as_ptr(), count.as_ptr(), 2) };
        let d = &ctx.frame.draws[0];
        assert_eq!((d.vertex_count, d.indices.len()), (4, 4), "the two draws merge");
        let a: [u32; 1] = [3];
        let b: [u32; 2] = [0, 1];
        let ptrs: [*const c_void; 2] = [a.as_ptr().cast(), b.as_ptr().cast()];
        unsafe { ctx.glMultiDrawElements(gl::GL_POINTS, [1, 2].as_ptr(), gl::GL_UNSIGNED_INT, ptrs.as_ptr(), 2) };
        let d = &ctx.frame.draws[1];
        assert_eq!(d.vertices.position[0], [0.0, 1.0, 0.0, 1.0]);
        assert_eq!(d.vertex_count, 3);
        unsafe { ctx.glMultiDrawArrays(gl::GL_LINES, first.as_ptr(), count.as_ptr(), -1) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        // One negative count: an error and no draw at all, not even of the valid range.
        unsafe { ctx.glMultiDrawArrays(gl::GL_LINES, first.as_ptr(), [2, -1].as_ptr(), 2) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        unsafe { ctx.glMultiDrawElements(gl::GL_POINTS, [-1, 2].as_ptr(), gl::GL_UNSIGNED_INT, ptrs.as_ptr(), 2) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        let counts: Vec<u32> = ctx.frame.draws.iter().map(|d| d.vertex_count as u32).collect();
        assert_eq!(counts, [4, 3], "nothing drawn or merged");
    }

    #[test]
    fn array_element_sets_current_values() {
        let (mut ctx, _) = Context::with_recording();
        let normals: [i8; 6] = [0, 127, 0, 0, 0, -128];
        ctx.glNormalPointer(gl::GL_BYTE, 0, normals.as_ptr().cast());
        ctx.glEnableClientState(gl::GL_NORMAL_ARRAY);
        ctx.glArrayElement(1);
        let mut n = [0.0f32; 3];
        unsafe { ctx.glGetFloatv(gl::GL_CURRENT_NORMAL, n.as_mut_ptr()) };
        assert_eq!(n, [0.0f32.max(1.0 / 255.0), 1.0 / 255.0, -1.0]);
        ctx.glArrayElement(-1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    }

    #[test]
    fn edge_flag_array_masks_edges() {
        let (mut ctx, _) = Context::with_recording();
        let flags: [u8; 4] = [0, 1, 1, 1];
        ctx.glVertexPointer(2, gl::GL_FLOAT, 0, SQUARE.as_ptr().cast());
        ctx.glEdgeFlagPointer(0, flags.as_ptr().cast());
        ctx.glEnableClientState(gl::GL_VERTEX_ARRAY);
        ctx.glEnableClientState(gl::GL_EDGE_FLAG_ARRAY);
        ctx.glDrawArrays(gl::GL_QUADS, 0, 4);
        assert_eq!(ctx.frame.draws[0].edge_masks, vec![0b100, 0b011]);
    }
}
