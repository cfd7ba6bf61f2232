//! Reading vertex arrays (OpenGL 1.5 section 2.8): each enabled array resolved to where its
//! elements are (client memory, or a buffer object's store read under the share-group lock
//! and bounds-checked: elements past its end read as zero) and converted to floats as table
//! 2.9 says ([`super::array_convert`]); a draw's elements filled into a batch, each array
//! converted over them at once; `glArrayElement`'s effect on the current values; index
//! decoding.

use super::Context;
use super::array_convert::Span;
use super::arrays::{ArrayPointer, ArrayState};
use super::buffer_objects::BufferTable;
use super::dispatch::Call;
use super::gl::{self, GLenum};
use super::immediate::{Batch, CurrentAttribs};
use super::limits::{MAX_TEXTURE_UNITS, MAX_VERTEX_ATTRIBS};
use super::locked_arrays::LockedPositions;
use crate::frame::Attrib;

/// Bytes of one component of `type_`.
fn type_size(type_: GLenum) -> usize {
    match type_ {
        gl::GL_BYTE | gl::GL_UNSIGNED_BYTE => 1,
        gl::GL_SHORT | gl::GL_UNSIGNED_SHORT => 2,
        gl::GL_DOUBLE => 8,
        _ => 4,
    }
}

/// An enabled array resolved for reading: where its elements are and how to convert them
/// ([`super::array_convert`] reads them).
#[derive(Clone, Copy, PartialEq)]
pub(crate) struct Source {
    pub(super) base: *const u8,
    /// Bytes readable from `base` (unbounded for client memory).
    available: usize,
    pub(super) stride: usize,
    pub(super) size: usize,
    pub(super) type_: GLenum,
    pub(super) normalized: bool,
}

impl Source {
    /// An array in client memory.
    #[cfg(test)]
    pub(crate) fn client(base: *const u8, stride: usize, size: usize, type_: GLenum, normalized: bool) -> Source {
        Source { base, available: usize::MAX, stride, size, type_, normalized }
    }

    /// Whether the elements are in client memory (not a buffer object's store).
    pub(crate) fn is_client(&self) -> bool {
        self.available == usize::MAX
    }

    /// Bytes of one element.
    pub(super) fn element_bytes(&self) -> usize {
        self.size * type_size(self.type_)
    }

    /// How many elements the array has: those that fit in a buffer store, unbounded for
    /// client memory.
    pub(crate) fn len(&self) -> usize {
        let elem = self.element_bytes();
        match self.available {
            usize::MAX => usize::MAX,
            n if n < elem => 0,
            n => (n - elem) / self.stride.max(1) + 1,
        }
    }
}

/// The enabled arrays of a draw, resolved.
pub(crate) struct Sources {
    pub(crate) vertex: Option<Source>,
    pub(crate) normal: Option<Source>,
    pub(crate) color: Option<Source>,
    pub(crate) secondary_color: Option<Source>,
    pub(crate) index: Option<Source>,
    pub(crate) edge_flag: Option<Source>,
    pub(crate) fog_coord: Option<Source>,
    pub(crate) texcoord: [Option<Source>; MAX_TEXTURE_UNITS],
    pub(crate) generic: [Option<Source>; MAX_VERTEX_ATTRIBS],
}

/// A resolved array uses a mapped buffer (`GL_INVALID_OPERATION`, section 2.9.3).
struct MappedBuffer;

/// Where an enabled array's elements are; `None` for a disabled one.
fn resolve(array: &ArrayPointer, normalized: bool, buffers: &BufferTable) -> Result<Option<Source>, MappedBuffer> {
    // A null client pointer would fault: the array is ignored, as if disabled.
    if !array.enabled || (array.buffer == 0 && array.pointer == 0) {
        return Ok(None);
    }
    let size = array.size.max(1) as usize;
    let elem = size * type_size(array.type_);
    let stride = if array.stride > 0 { array.stride as usize } else { elem };
    let (base, available) = if array.buffer == 0 {
        (array.pointer as *const u8, usize::MAX)
    } else {
        let Some(buffer) = buffers.get(array.buffer) else { return Ok(None) };
        if buffer.mapped {
            return Err(MappedBuffer);
        }
        let offset = array.pointer.min(buffer.data.len());
        (buffer.data[offset..].as_ptr(), buffer.data.len() - offset)
    };
    Ok(Some(Source { base, available, stride, size, type_: array.type_, normalized }))
}

impl Sources {
    fn new(arrays: &ArrayState, buffers: &BufferTable) -> Result<Sources, MappedBuffer> {
        let mut texcoord = [None; MAX_TEXTURE_UNITS];
        for (slot, array) in texcoord.iter_mut().zip(&arrays.texcoord) {
            *slot = resolve(array, false, buffers)?;
        }
        let mut generic = [None; MAX_VERTEX_ATTRIBS];
        for (slot, array) in generic.iter_mut().zip(&arrays.generic) {
            *slot = resolve(array, array.normalized, buffers)?;
        }
        Ok(Sources {
            generic,
            vertex: resolve(&arrays.vertex, false, buffers)?,
            normal: resolve(&arrays.normal, true, buffers)?,
            color: resolve(&arrays.color, true, buffers)?,
            secondary_color: resolve(&arrays.secondary_color, true, buffers)?,
            index: resolve(&arrays.index, false, buffers)?,
            edge_flag: resolve(&arrays.edge_flag, false, buffers)?,
            fog_coord: resolve(&arrays.fog_coord, false, buffers)?,
            texcoord,
        })
    }

    /// Which attributes these arrays provide.
    pub(crate) fn provided(&self) -> FromArrays {
        FromArrays {
            normal: self.normal.is_some(),
            color: self.color.is_some(),
            secondary_color: self.secondary_color.is_some(),
            index: self.index.is_some(),
            edge_flag: self.edge_flag.is_some(),
            fog_coord: self.fog_coord.is_some(),
            texcoord: self.texcoord.map(|t| t.is_some()),
            generic: self.generic.map(|g| g.is_some()),
        }
    }

    /// The array that gives positions: generic array 0 when enabled, else the vertex array
    /// (OpenGL 2.0 section 2.8).
    pub(crate) fn position(&self) -> Option<&Source> {
        self.generic[0].as_ref().or(self.vertex.as_ref())
    }

    /// Stores element `i` of every enabled array but the vertex array in `current`, and returns
    /// the vertex array's element (section 2.8, `ArrayElement`).
    #[inline]
    pub(crate) fn element(&self, i: usize, current: &mut CurrentAttribs) -> Option<[f32; 4]> {
        if let Some(s) = &self.normal {
            let [x, y, z, _] = s.read(i);
            current.normal = [x, y, z];
        }
        if let Some(s) = &self.color {
            current.color = s.read(i);
        }
        if let Some(s) = &self.secondary_color {
            let [r, g, b, _] = s.read(i);
            current.secondary_color = [r, g, b];
        }
        if let Some(s) = &self.index {
            current.color_index = s.read(i)[0];
        }
        if let Some(s) = &self.edge_flag {
            current.edge_flag = s.read(i)[0] != 0.0;
        }
        if let Some(s) = &self.fog_coord {
            current.fog_coord = s.read(i)[0];
        }
        for (slot, s) in current.texcoords.iter_mut().zip(&self.texcoord) {
            if let Some(s) = s {
                *slot = s.read(i);
            }
        }
        for (slot, s) in current.generic.iter_mut().zip(&self.generic).skip(1) {
            if let Some(s) = s {
                *slot = s.read(i);
            }
        }
        self.position().map(|s| s.read(i))
    }

    /// Fills the cleared `batch` with the elements of `span`: positions and the attributes
    /// of enabled arrays converted at once (an attribute whose elements are all equal is
    /// stored once, as `glArrayElement` per vertex would leave it), the others given the one
    /// value of `current`. While arrays are locked (`locked`: the conversion and the locked
    /// range), positions come from the locked vertex array's conversion. `scratch` holds
    /// conversions of attributes narrower than 4 components.
    pub(crate) fn fill(
        &self,
        span: Span<'_>,
        locked: Option<(&mut LockedPositions, (usize, usize))>,
        current: &CurrentAttribs,
        batch: &mut Batch,
        scratch: &mut Vec<[f32; 4]>,
    ) {
        let n = span.len();
        if n == 0 {
            return;
        }
        let v = &mut batch.vertices;
        let from_lock = match (locked, self.position()) {
            (Some((l, range)), Some(s)) => l.positions(s, range, span, &mut v.position),
            _ => false,
        };
        if !from_lock {
            match self.position() {
                Some(s) => s.convert_into(span, &mut v.position),
                None => v.position.resize(n, [0.0, 0.0, 0.0, 1.0]),
            }
        }
        /// An attribute from its array (narrowed by `f`), else from its current value.
        fn narrow<T: Copy + PartialEq>(
            a: &mut Attrib<T>,
            s: &Option<Source>,
            span: Span<'_>,
            scratch: &mut Vec<[f32; 4]>,
            current: T,
            f: impl Fn([f32; 4]) -> T,
        ) {
            match s {
                Some(s) => {
                    scratch.clear();
                    s.convert_into(span, scratch);
                    a.values.extend(scratch.iter().map(|&e| f(e)));
                    share_if_uniform(a);
                }
                None => a.set_constant(current),
            }
        }
        /// A four-component attribute: converted straight into its storage.
        fn wide(a: &mut Attrib<[f32; 4]>, s: &Option<Source>, span: Span<'_>, current: [f32; 4]) {
            match s {
                Some(s) => {
                    s.convert_into(span, &mut a.values);
                    share_if_uniform(a);
                }
                None => a.set_constant(current),
            }
        }
        narrow(&mut v.normal, &self.normal, span, scratch, current.normal, |[x, y, z, _]| [x, y, z]);
        wide(&mut v.color, &self.color, span, current.color);
        narrow(&mut v.secondary_color, &self.secondary_color, span, scratch, current.secondary_color, |[r, g, b, _]| [r, g, b]);
        narrow(&mut v.fog_coord, &self.fog_coord, span, scratch, current.fog_coord, |e| e[0]);
        narrow(&mut v.color_index, &self.index, span, scratch, current.color_index, |e| e[0]);
        narrow(&mut batch.edge_flags, &self.edge_flag, span, scratch, current.edge_flag, |e| e[0] != 0.0);
        for ((t, s), &value) in v.texcoords.iter_mut().zip(&self.texcoord).zip(&current.texcoords) {
            wide(t, s, span, value);
        }
        for ((g, s), &value) in v.generic.iter_mut().zip(&self.generic).zip(&current.generic).skip(1) {
            wide(g, s, span, value);
        }
    }

    /// The display-list commands `glArrayElement(i)` stands for, in the order of section 2.8.
    pub(crate) fn element_calls(&self, i: usize, current: &CurrentAttribs) -> Vec<Call> {
        let mut c = *current;
        let vertex = self.element(i, &mut c);
        let mut calls = Vec::new();
        if self.edge_flag.is_some() {
            calls.push(Call::EdgeFlag(u8::from(c.edge_flag)));
        }
        for (unit, s) in self.texcoord.iter().enumerate() {
            if s.is_some() {
                let [s, t, r, q] = c.texcoords[unit];
                calls.push(Call::MultiTexCoord4f(gl::GL_TEXTURE0 + unit as u32, s, t, r, q));
            }
        }
        if self.color.is_some() {
            let [r, g, b, a] = c.color;
            calls.push(Call::Color4f(r, g, b, a));
        }
        if self.secondary_color.is_some() {
            let [r, g, b] = c.secondary_color;
            calls.push(Call::SecondaryColor3f(r, g, b));
        }
        if self.fog_coord.is_some() {
            calls.push(Call::FogCoordf(c.fog_coord));
        }
        if self.index.is_some() {
            calls.push(Call::Indexf(c.color_index));
        }
        if self.normal.is_some() {
            let [x, y, z] = c.normal;
            calls.push(Call::Normal3f(x, y, z));
        }
        for (index, s) in self.generic.iter().enumerate().skip(1) {
            if s.is_some() {
                let [x, y, z, w] = c.generic[index];
                calls.push(Call::VertexAttrib4f(index as u32, x, y, z, w));
            }
        }
        if let Some([x, y, z, w]) = vertex {
            calls.push(Call::Vertex4f(x, y, z, w));
        }
        calls
    }
}

/// Which attributes a fetched batch took from arrays (the others take current values).
#[derive(Clone, Copy)]
pub(crate) struct FromArrays {
    pub(crate) normal: bool,
    pub(crate) color: bool,
    pub(crate) secondary_color: bool,
    pub(crate) index: bool,
    pub(crate) edge_flag: bool,
    pub(crate) fog_coord: bool,
    pub(crate) texcoord: [bool; MAX_TEXTURE_UNITS],
    pub(crate) generic: [bool; MAX_VERTEX_ATTRIBS],
}

/// Index types of `glDrawElements`.
pub(crate) fn index_size(type_: GLenum) -> Option<usize> {
    match type_ {
        gl::GL_UNSIGNED_BYTE => Some(1),
        gl::GL_UNSIGNED_SHORT => Some(2),
        gl::GL_UNSIGNED_INT => Some(4),
        _ => None,
    }
}

/// Appends the indices in `bytes` (each `width` bytes, native order) to `out`.
pub(crate) fn decode_indices(bytes: &[u8], width: usize, out: &mut Vec<u32>) {
    match width {
        1 => out.extend(bytes.iter().map(|&b| u32::from(b))),
        2 => out.extend(bytes.chunks_exact(2).map(|b| u32::from(u16::from_ne_bytes([b[0], b[1]])))),
        _ => out.extend(bytes.chunks_exact(4).map(|b| u32::from_ne_bytes([b[0], b[1], b[2], b[3]]))),
    }
}

/// Stores an attribute once when all its per-vertex values are equal.
fn share_if_uniform<T: Copy + PartialEq>(a: &mut Attrib<T>) {
    if let Some((&first, rest)) = a.values.split_first()
        && rest.iter().all(|&x| x == first)
    {
        a.values.truncate(1);
    }
}

/// Storage the draws from arrays reuse, so that a draw allocates nothing once it has grown:
/// the decoded indices, the batch vertex of each drawn element, converted narrow attributes
/// and the locked vertex array.
#[derive(Default)]
pub(crate) struct FetchStorage {
    /// Indices of the draw, decoded.
    pub(crate) indices: Vec<u32>,
    /// The batch vertex of each element, when the draw has indices.
    pub(crate) order: Vec<u32>,
    /// Conversions of attributes of fewer than 4 components.
    pub(crate) scratch: Vec<[f32; 4]>,
    /// The vertex array converted over the `glLockArraysEXT` range.
    pub(crate) locked: LockedPositions,
}

impl Context {
    /// Resolves the enabled arrays and runs `f` on them under the share-group lock;
    /// `GL_INVALID_OPERATION` when one reads a mapped buffer. Client arrays alone are resolved
    /// without taking the lock (`glArrayElement` runs once per vertex).
    pub(crate) fn with_sources<R>(
        &mut self,
        command: &'static str,
        f: impl FnOnce(&Sources, &mut Self) -> R,
    ) -> Option<R> {
        if !self.arrays.reads_buffers() {
            let sources = Sources::new(&self.arrays, &BufferTable::default()).ok()?;
            return Some(f(&sources, self));
        }
        let shared = self.shared.clone();
        let guard = shared.lock();
        match Sources::new(&self.arrays, &guard.buffers) {
            Ok(sources) => Some(f(&sources, self)),
            Err(MappedBuffer) => {
                drop(guard);
                self.set_error_in(gl::GL_INVALID_OPERATION, command);
                None
            }
        }
    }
}
