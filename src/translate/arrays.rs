//! Vertex arrays (OpenGL 1.5 section 2.8): the array pointers and their enables, buffer-object
//! bindings (section 2.9), `glInterleavedArrays`, `glArrayElement`, `glDrawArrays`,
//! `glDrawElements`, `glDrawRangeElements`, `glMultiDraw*`, `EXT_compiled_vertex_array` and
//! their display-list forms.
//!
//! A draw fetches the array elements it uses into a batch, decomposes it with
//! [`super::assemble`] and hands it to [`Context::emit_batch`]. `glDrawElements` fetches the
//! index range `min..=max` once and keeps the program's indices (shared vertices stay shared),
//! unless that range is much larger than the index count; then it fetches one vertex per index.
//! Arrays sourced from buffer objects are read under the share-group lock, bounds-checked
//! (elements past the end of the store read as zero); client arrays are read where the program
//! points, as the specification requires.
//!
//! `glLockArraysEXT` only records the locked range: glrt reads the arrays at each draw, which
//! the extension allows, so a program that locks more than it draws (Quake III) costs nothing.

use std::ffi::c_void;

use super::Context;
use super::assemble::{Primitive, assemble};
use super::buffers::BufferTable;
use super::convert::{norm_i8, norm_i16, norm_i32, norm_u8, norm_u16, norm_u32, read_slice, write_slice};
use super::dispatch::Call;
use super::get::Value;
use super::gl::{self, GLenum, GLint, GLsizei, GLuint};
use super::immediate::{Batch, CurrentAttribs};
use super::limits::{MAX_ELEMENTS, MAX_TEXTURE_UNITS};
use super::lists::ListOp;

/// One vertex array: its pointer state (table 6.8) and enable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ArrayPointer {
    /// Enabled with `glEnableClientState`.
    pub enabled: bool,
    /// Components per element.
    pub size: GLint,
    /// Component type.
    pub type_: GLenum,
    /// Stride as given (0: tightly packed).
    pub stride: GLsizei,
    /// Client address, or byte offset into `buffer` when it is not 0.
    pub pointer: usize,
    /// `GL_*_ARRAY_BUFFER_BINDING`: the `GL_ARRAY_BUFFER` binding when the pointer was set.
    pub buffer: GLuint,
}

impl ArrayPointer {
    const fn new(size: GLint, type_: GLenum) -> ArrayPointer {
        ArrayPointer { enabled: false, size, type_, stride: 0, pointer: 0, buffer: 0 }
    }
}

/// Which array.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArrayKind {
    /// `GL_VERTEX_ARRAY`.
    Vertex,
    /// `GL_NORMAL_ARRAY`.
    Normal,
    /// `GL_COLOR_ARRAY`.
    Color,
    /// `GL_SECONDARY_COLOR_ARRAY`.
    SecondaryColor,
    /// `GL_INDEX_ARRAY`.
    Index,
    /// `GL_EDGE_FLAG_ARRAY`.
    EdgeFlag,
    /// `GL_FOG_COORD_ARRAY`.
    FogCoord,
    /// `GL_TEXTURE_COORD_ARRAY` of a unit.
    TexCoord(usize),
}

/// Client vertex-array state of a context (`GL_CLIENT_VERTEX_ARRAY_BIT`, with the client
/// active texture unit kept by [`super::texunit`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ArrayState {
    /// Vertex array.
    pub vertex: ArrayPointer,
    /// Normal array.
    pub normal: ArrayPointer,
    /// Colour array.
    pub color: ArrayPointer,
    /// Secondary colour array.
    pub secondary_color: ArrayPointer,
    /// Colour-index array.
    pub index: ArrayPointer,
    /// Edge-flag array.
    pub edge_flag: ArrayPointer,
    /// Fog-coordinate array.
    pub fog_coord: ArrayPointer,
    /// Texture-coordinate array of each unit.
    pub texcoord: [ArrayPointer; MAX_TEXTURE_UNITS],
    /// `GL_ARRAY_BUFFER_BINDING`.
    pub array_buffer: GLuint,
    /// `GL_ELEMENT_ARRAY_BUFFER_BINDING`.
    pub element_buffer: GLuint,
    /// `glLockArraysEXT` range `(first, count)`.
    pub lock: Option<(GLint, GLsizei)>,
}

impl Default for ArrayState {
    /// Table 6.8 initial values.
    fn default() -> ArrayState {
        ArrayState {
            vertex: ArrayPointer::new(4, gl::GL_FLOAT),
            normal: ArrayPointer::new(3, gl::GL_FLOAT),
            color: ArrayPointer::new(4, gl::GL_FLOAT),
            secondary_color: ArrayPointer::new(3, gl::GL_FLOAT),
            index: ArrayPointer::new(1, gl::GL_FLOAT),
            edge_flag: ArrayPointer::new(1, gl::GL_UNSIGNED_BYTE),
            fog_coord: ArrayPointer::new(1, gl::GL_FLOAT),
            texcoord: [ArrayPointer::new(4, gl::GL_FLOAT); MAX_TEXTURE_UNITS],
            array_buffer: 0,
            element_buffer: 0,
            lock: None,
        }
    }
}

impl ArrayState {
    /// The array of `kind`.
    pub fn get(&self, kind: ArrayKind) -> &ArrayPointer {
        match kind {
            ArrayKind::Vertex => &self.vertex,
            ArrayKind::Normal => &self.normal,
            ArrayKind::Color => &self.color,
            ArrayKind::SecondaryColor => &self.secondary_color,
            ArrayKind::Index => &self.index,
            ArrayKind::EdgeFlag => &self.edge_flag,
            ArrayKind::FogCoord => &self.fog_coord,
            ArrayKind::TexCoord(u) => &self.texcoord[u],
        }
    }

    fn get_mut(&mut self, kind: ArrayKind) -> &mut ArrayPointer {
        match kind {
            ArrayKind::Vertex => &mut self.vertex,
            ArrayKind::Normal => &mut self.normal,
            ArrayKind::Color => &mut self.color,
            ArrayKind::SecondaryColor => &mut self.secondary_color,
            ArrayKind::Index => &mut self.index,
            ArrayKind::EdgeFlag => &mut self.edge_flag,
            ArrayKind::FogCoord => &mut self.fog_coord,
            ArrayKind::TexCoord(u) => &mut self.texcoord[u],
        }
    }

    /// Every array.
    fn all_mut(&mut self) -> impl Iterator<Item = &mut ArrayPointer> {
        [
            &mut self.vertex,
            &mut self.normal,
            &mut self.color,
            &mut self.secondary_color,
            &mut self.index,
            &mut self.edge_flag,
            &mut self.fog_coord,
        ]
        .into_iter()
        .chain(self.texcoord.iter_mut())
    }

    /// Forgets a deleted buffer: bindings and array buffer bindings naming it become 0.
    pub fn unbind_buffer(&mut self, name: GLuint) {
        for binding in [&mut self.array_buffer, &mut self.element_buffer] {
            if *binding == name {
                *binding = 0;
            }
        }
        for array in self.all_mut() {
            if array.buffer == name {
                array.buffer = 0;
            }
        }
    }
}

/// Bytes of one component of `type_`.
fn type_size(type_: GLenum) -> usize {
    match type_ {
        gl::GL_BYTE | gl::GL_UNSIGNED_BYTE => 1,
        gl::GL_SHORT | gl::GL_UNSIGNED_SHORT => 2,
        gl::GL_DOUBLE => 8,
        _ => 4,
    }
}

/// Reads one component; integer types map to [-1, 1] / [0, 1] when `normalized` (table 2.9).
///
/// # Safety
/// `p` must point to a readable component of `type_`.
#[inline]
unsafe fn component(p: *const u8, type_: GLenum, normalized: bool) -> f32 {
    macro_rules! int {
        ($t:ty, $norm:ident) => {{
            let c = unsafe { p.cast::<$t>().read_unaligned() };
            if normalized { $norm(c) } else { c as f32 }
        }};
    }
    match type_ {
        gl::GL_BYTE => int!(i8, norm_i8),
        gl::GL_UNSIGNED_BYTE => int!(u8, norm_u8),
        gl::GL_SHORT => int!(i16, norm_i16),
        gl::GL_UNSIGNED_SHORT => int!(u16, norm_u16),
        gl::GL_INT => int!(i32, norm_i32),
        gl::GL_UNSIGNED_INT => int!(u32, norm_u32),
        gl::GL_DOUBLE => unsafe { p.cast::<f64>().read_unaligned() as f32 },
        _ => unsafe { p.cast::<f32>().read_unaligned() },
    }
}

/// An enabled array resolved for reading: where its elements are and how to convert them.
#[derive(Clone, Copy)]
struct Source {
    base: *const u8,
    /// Bytes readable from `base` (unbounded for client memory).
    available: usize,
    stride: usize,
    size: usize,
    type_: GLenum,
    normalized: bool,
}

impl Source {
    /// Element `i`, missing components from `(0, 0, 0, 1)`; zero past the end of a buffer.
    #[inline]
    fn read(&self, i: usize) -> [f32; 4] {
        let mut out = [0.0, 0.0, 0.0, 1.0];
        let width = type_size(self.type_);
        let start = i.checked_mul(self.stride);
        let in_range = start.and_then(|s| s.checked_add(self.size * width)).is_some_and(|end| end <= self.available);
        if !in_range {
            return [0.0; 4];
        }
        let start = start.unwrap_or(0);
        for (k, slot) in out.iter_mut().enumerate().take(self.size) {
            // Safety: in range of a buffer store, or client memory the program vouches for.
            *slot = unsafe { component(self.base.wrapping_add(start + k * width), self.type_, self.normalized) };
        }
        out
    }
}

/// The enabled arrays of a draw, resolved.
struct Sources {
    vertex: Option<Source>,
    normal: Option<Source>,
    color: Option<Source>,
    secondary_color: Option<Source>,
    index: Option<Source>,
    edge_flag: Option<Source>,
    fog_coord: Option<Source>,
    texcoord: [Option<Source>; MAX_TEXTURE_UNITS],
}

/// A resolved array uses a mapped buffer (`GL_INVALID_OPERATION`, section 2.9.3).
struct MappedBuffer;

fn resolve(array: &ArrayPointer, normalized: bool, buffers: &BufferTable) -> Result<Option<Source>, MappedBuffer> {
    if !array.enabled {
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
        Ok(Sources {
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

    /// Stores element `i` of every enabled array but the vertex array in `current`, and returns
    /// the vertex array's element (section 2.8, `ArrayElement`).
    #[inline]
    fn element(&self, i: usize, current: &mut CurrentAttribs) -> Option<[f32; 4]> {
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
        self.vertex.as_ref().map(|s| s.read(i))
    }

    /// The display-list commands `glArrayElement(i)` stands for, in the order of section 2.8.
    fn element_calls(&self, i: usize, current: &CurrentAttribs) -> Vec<Call> {
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
        if let Some([x, y, z, w]) = vertex {
            calls.push(Call::Vertex4f(x, y, z, w));
        }
        calls
    }
}

/// Which array elements a draw reads, in primitive order.
#[derive(Clone, Copy)]
enum Elements<'a> {
    /// `first..first + count`.
    Range(usize, usize),
    /// Program indices.
    Indices(&'a [u32]),
}

/// A draw's vertices fetched from the arrays: the batch, the batch vertex of each element in
/// primitive order (`None`: in order), and which attributes came from arrays.
#[derive(Clone)]
struct Fetched {
    primitive: Primitive,
    batch: Batch,
    order: Option<Vec<u32>>,
    from_arrays: FromArrays,
}

/// Which attributes a fetched batch took from arrays (the others take current values).
#[derive(Clone, Copy, Default)]
struct FromArrays {
    normal: bool,
    color: bool,
    secondary_color: bool,
    index: bool,
    edge_flag: bool,
    fog_coord: bool,
    texcoord: [bool; MAX_TEXTURE_UNITS],
}

impl Fetched {
    /// Replaces the attributes that did not come from arrays by `current` (a compiled draw
    /// uses the current values of the moment it is executed).
    fn take_current(&mut self, current: &CurrentAttribs) {
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
    }
}

/// Index types of `glDrawElements`.
fn index_size(type_: GLenum) -> Option<usize> {
    match type_ {
        gl::GL_UNSIGNED_BYTE => Some(1),
        gl::GL_UNSIGNED_SHORT => Some(2),
        gl::GL_UNSIGNED_INT => Some(4),
        _ => None,
    }
}

fn decode_indices(bytes: &[u8], width: usize) -> Vec<u32> {
    bytes
        .chunks_exact(width)
        .map(|b| match *b {
            [x] => u32::from(x),
            [x, y] => u32::from(u16::from_ne_bytes([x, y])),
            [x, y, z, w] => u32::from_ne_bytes([x, y, z, w]),
            _ => 0,
        })
        .collect()
}

/// Type and size rules of a `gl*Pointer` command (section 2.8).
struct PointerRules {
    command: &'static str,
    sizes: &'static [GLint],
    types: &'static [GLenum],
}

const VERTEX_RULES: PointerRules = PointerRules {
    command: "glVertexPointer",
    sizes: &[2, 3, 4],
    types: &[gl::GL_SHORT, gl::GL_INT, gl::GL_FLOAT, gl::GL_DOUBLE],
};
const NORMAL_RULES: PointerRules = PointerRules {
    command: "glNormalPointer",
    sizes: &[3],
    types: &[gl::GL_BYTE, gl::GL_SHORT, gl::GL_INT, gl::GL_FLOAT, gl::GL_DOUBLE],
};
const COLOR_TYPES: &[GLenum] = &[
    gl::GL_BYTE,
    gl::GL_UNSIGNED_BYTE,
    gl::GL_SHORT,
    gl::GL_UNSIGNED_SHORT,
    gl::GL_INT,
    gl::GL_UNSIGNED_INT,
    gl::GL_FLOAT,
    gl::GL_DOUBLE,
];
const COLOR_RULES: PointerRules = PointerRules { command: "glColorPointer", sizes: &[3, 4], types: COLOR_TYPES };
const SECONDARY_COLOR_RULES: PointerRules =
    PointerRules { command: "glSecondaryColorPointer", sizes: &[3], types: COLOR_TYPES };
const INDEX_RULES: PointerRules = PointerRules {
    command: "glIndexPointer",
    sizes: &[1],
    types: &[gl::GL_UNSIGNED_BYTE, gl::GL_SHORT, gl::GL_INT, gl::GL_FLOAT, gl::GL_DOUBLE],
};
const TEXCOORD_RULES: PointerRules = PointerRules {
    command: "glTexCoordPointer",
    sizes: &[1, 2, 3, 4],
    types: &[gl::GL_SHORT, gl::GL_INT, gl::GL_FLOAT, gl::GL_DOUBLE],
};
const EDGE_FLAG_RULES: PointerRules =
    PointerRules { command: "glEdgeFlagPointer", sizes: &[1], types: &[gl::GL_UNSIGNED_BYTE] };
const FOG_COORD_RULES: PointerRules =
    PointerRules { command: "glFogCoordPointer", sizes: &[1], types: &[gl::GL_FLOAT, gl::GL_DOUBLE] };

/// `glGet` names of an array: enable, size, type, stride, buffer binding, pointer (0: none).
const ARRAY_PNAMES: [(ArrayKind, [GLenum; 6]); 8] = [
    (ArrayKind::Vertex, [
        gl::GL_VERTEX_ARRAY,
        gl::GL_VERTEX_ARRAY_SIZE,
        gl::GL_VERTEX_ARRAY_TYPE,
        gl::GL_VERTEX_ARRAY_STRIDE,
        gl::GL_VERTEX_ARRAY_BUFFER_BINDING,
        gl::GL_VERTEX_ARRAY_POINTER,
    ]),
    (ArrayKind::Normal, [
        gl::GL_NORMAL_ARRAY,
        0,
        gl::GL_NORMAL_ARRAY_TYPE,
        gl::GL_NORMAL_ARRAY_STRIDE,
        gl::GL_NORMAL_ARRAY_BUFFER_BINDING,
        gl::GL_NORMAL_ARRAY_POINTER,
    ]),
    (ArrayKind::Color, [
        gl::GL_COLOR_ARRAY,
        gl::GL_COLOR_ARRAY_SIZE,
        gl::GL_COLOR_ARRAY_TYPE,
        gl::GL_COLOR_ARRAY_STRIDE,
        gl::GL_COLOR_ARRAY_BUFFER_BINDING,
        gl::GL_COLOR_ARRAY_POINTER,
    ]),
    (ArrayKind::SecondaryColor, [
        gl::GL_SECONDARY_COLOR_ARRAY,
        gl::GL_SECONDARY_COLOR_ARRAY_SIZE,
        gl::GL_SECONDARY_COLOR_ARRAY_TYPE,
        gl::GL_SECONDARY_COLOR_ARRAY_STRIDE,
        gl::GL_SECONDARY_COLOR_ARRAY_BUFFER_BINDING,
        gl::GL_SECONDARY_COLOR_ARRAY_POINTER,
    ]),
    (ArrayKind::Index, [
        gl::GL_INDEX_ARRAY,
        0,
        gl::GL_INDEX_ARRAY_TYPE,
        gl::GL_INDEX_ARRAY_STRIDE,
        gl::GL_INDEX_ARRAY_BUFFER_BINDING,
        gl::GL_INDEX_ARRAY_POINTER,
    ]),
    (ArrayKind::EdgeFlag, [
        gl::GL_EDGE_FLAG_ARRAY,
        0,
        0,
        gl::GL_EDGE_FLAG_ARRAY_STRIDE,
        gl::GL_EDGE_FLAG_ARRAY_BUFFER_BINDING,
        gl::GL_EDGE_FLAG_ARRAY_POINTER,
    ]),
    (ArrayKind::FogCoord, [
        gl::GL_FOG_COORD_ARRAY,
        0,
        gl::GL_FOG_COORD_ARRAY_TYPE,
        gl::GL_FOG_COORD_ARRAY_STRIDE,
        gl::GL_FOG_COORD_ARRAY_BUFFER_BINDING,
        gl::GL_FOG_COORD_ARRAY_POINTER,
    ]),
    (ArrayKind::TexCoord(0), [
        gl::GL_TEXTURE_COORD_ARRAY,
        gl::GL_TEXTURE_COORD_ARRAY_SIZE,
        gl::GL_TEXTURE_COORD_ARRAY_TYPE,
        gl::GL_TEXTURE_COORD_ARRAY_STRIDE,
        gl::GL_TEXTURE_COORD_ARRAY_BUFFER_BINDING,
        gl::GL_TEXTURE_COORD_ARRAY_POINTER,
    ]),
];

/// One row of table 2.5 (`glInterleavedArrays`): texture coordinate, colour, normal and
/// vertex components, colour type, and byte offsets of colour, normal and vertex.
struct Interleaved {
    format: GLenum,
    tex: GLint,
    color: GLint,
    color_type: GLenum,
    normal: bool,
    vertex: GLint,
    pc: usize,
    pn: usize,
    pv: usize,
    stride: usize,
}

const F: usize = 4;
/// `c`: four unsigned bytes, rounded up to a multiple of a float.
const C: usize = 4;

const fn row(
    format: GLenum,
    (tex, color, color_type, normal, vertex): (GLint, GLint, GLenum, bool, GLint),
    (pc, pn, pv, stride): (usize, usize, usize, usize),
) -> Interleaved {
    Interleaved { format, tex, color, color_type, normal, vertex, pc, pn, pv, stride }
}

const UB: GLenum = gl::GL_UNSIGNED_BYTE;
const FL: GLenum = gl::GL_FLOAT;

/// Table 2.5.
const INTERLEAVED: [Interleaved; 14] = [
    row(gl::GL_V2F, (0, 0, 0, false, 2), (0, 0, 0, 2 * F)),
    row(gl::GL_V3F, (0, 0, 0, false, 3), (0, 0, 0, 3 * F)),
    row(gl::GL_C4UB_V2F, (0, 4, UB, false, 2), (0, 0, C, C + 2 * F)),
    row(gl::GL_C4UB_V3F, (0, 4, UB, false, 3), (0, 0, C, C + 3 * F)),
    row(gl::GL_C3F_V3F, (0, 3, FL, false, 3), (0, 0, 3 * F, 6 * F)),
    row(gl::GL_N3F_V3F, (0, 0, 0, true, 3), (0, 0, 3 * F, 6 * F)),
    row(gl::GL_C4F_N3F_V3F, (0, 4, FL, true, 3), (0, 4 * F, 7 * F, 10 * F)),
    row(gl::GL_T2F_V3F, (2, 0, 0, false, 3), (0, 0, 2 * F, 5 * F)),
    row(gl::GL_T4F_V4F, (4, 0, 0, false, 4), (0, 0, 4 * F, 8 * F)),
    row(gl::GL_T2F_C4UB_V3F, (2, 4, UB, false, 3), (2 * F, 0, C + 2 * F, C + 5 * F)),
    row(gl::GL_T2F_C3F_V3F, (2, 3, FL, false, 3), (2 * F, 0, 5 * F, 8 * F)),
    row(gl::GL_T2F_N3F_V3F, (2, 0, 0, true, 3), (0, 2 * F, 5 * F, 8 * F)),
    row(gl::GL_T2F_C4F_N3F_V3F, (2, 4, FL, true, 3), (2 * F, 6 * F, 9 * F, 12 * F)),
    row(gl::GL_T4F_C4F_N3F_V4F, (4, 4, FL, true, 4), (4 * F, 8 * F, 11 * F, 15 * F)),
];

/// Indices ranges wider than this many times the index count are fetched per index.
const SPARSE_FACTOR: usize = 4;

impl Context {
    /// Sets an array pointer after checking `rules` (section 2.8 errors).
    fn set_pointer(&mut self, kind: ArrayKind, rules: &PointerRules, size: GLint, type_: GLenum, stride: GLsizei, pointer: *const c_void) {
        if !rules.sizes.contains(&size) || stride < 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, rules.command);
        }
        if !rules.types.contains(&type_) {
            return self.set_error_in(gl::GL_INVALID_ENUM, rules.command);
        }
        let buffer = self.arrays.array_buffer;
        let array = self.arrays.get_mut(kind);
        *array = ArrayPointer { enabled: array.enabled, size, type_, stride, pointer: pointer as usize, buffer };
    }

    /// `glVertexPointer`.
    pub fn glVertexPointer(&mut self, size: GLint, type_: GLenum, stride: GLsizei, pointer: *const c_void) {
        self.set_pointer(ArrayKind::Vertex, &VERTEX_RULES, size, type_, stride, pointer);
    }

    /// `glNormalPointer`.
    pub fn glNormalPointer(&mut self, type_: GLenum, stride: GLsizei, pointer: *const c_void) {
        self.set_pointer(ArrayKind::Normal, &NORMAL_RULES, 3, type_, stride, pointer);
    }

    /// `glColorPointer`.
    pub fn glColorPointer(&mut self, size: GLint, type_: GLenum, stride: GLsizei, pointer: *const c_void) {
        self.set_pointer(ArrayKind::Color, &COLOR_RULES, size, type_, stride, pointer);
    }

    /// `glSecondaryColorPointer`.
    pub fn glSecondaryColorPointer(&mut self, size: GLint, type_: GLenum, stride: GLsizei, pointer: *const c_void) {
        self.set_pointer(ArrayKind::SecondaryColor, &SECONDARY_COLOR_RULES, size, type_, stride, pointer);
    }

    /// `glIndexPointer`.
    pub fn glIndexPointer(&mut self, type_: GLenum, stride: GLsizei, pointer: *const c_void) {
        self.set_pointer(ArrayKind::Index, &INDEX_RULES, 1, type_, stride, pointer);
    }

    /// `glTexCoordPointer`: the array of the client active texture unit.
    pub fn glTexCoordPointer(&mut self, size: GLint, type_: GLenum, stride: GLsizei, pointer: *const c_void) {
        let unit = self.texunit.client_active;
        self.set_pointer(ArrayKind::TexCoord(unit), &TEXCOORD_RULES, size, type_, stride, pointer);
    }

    /// `glEdgeFlagPointer`.
    pub fn glEdgeFlagPointer(&mut self, stride: GLsizei, pointer: *const c_void) {
        self.set_pointer(ArrayKind::EdgeFlag, &EDGE_FLAG_RULES, 1, gl::GL_UNSIGNED_BYTE, stride, pointer);
    }

    /// `glFogCoordPointer`.
    pub fn glFogCoordPointer(&mut self, type_: GLenum, stride: GLsizei, pointer: *const c_void) {
        self.set_pointer(ArrayKind::FogCoord, &FOG_COORD_RULES, 1, type_, stride, pointer);
    }

    /// The array an enable names (`GL_TEXTURE_COORD_ARRAY`: of the client active unit).
    fn array_of_cap(&self, cap: GLenum) -> Option<ArrayKind> {
        ARRAY_PNAMES.iter().find(|(_, p)| p[0] == cap).map(|&(kind, _)| match kind {
            ArrayKind::TexCoord(_) => ArrayKind::TexCoord(self.texunit.client_active),
            k => k,
        })
    }

    fn set_client_state(&mut self, cap: GLenum, on: bool, command: &'static str) {
        match self.array_of_cap(cap) {
            Some(kind) => self.arrays.get_mut(kind).enabled = on,
            None => self.set_error_in(gl::GL_INVALID_ENUM, command),
        }
    }

    /// `glEnableClientState`.
    pub fn glEnableClientState(&mut self, array: GLenum) {
        self.set_client_state(array, true, "glEnableClientState");
    }

    /// `glDisableClientState`.
    pub fn glDisableClientState(&mut self, array: GLenum) {
        self.set_client_state(array, false, "glDisableClientState");
    }

    /// `glInterleavedArrays` (section 2.8, table 2.5).
    pub fn glInterleavedArrays(&mut self, format: GLenum, stride: GLsizei, pointer: *const c_void) {
        let Some(f) = INTERLEAVED.iter().find(|r| r.format == format) else {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glInterleavedArrays");
        };
        if stride < 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glInterleavedArrays");
        }
        let s = if stride == 0 { f.stride as GLsizei } else { stride };
        let at = |offset: usize| (pointer as usize).wrapping_add(offset) as *const c_void;
        for cap in [gl::GL_EDGE_FLAG_ARRAY, gl::GL_INDEX_ARRAY, gl::GL_SECONDARY_COLOR_ARRAY, gl::GL_FOG_COORD_ARRAY] {
            self.set_client_state(cap, false, "glInterleavedArrays");
        }
        self.set_client_state(gl::GL_TEXTURE_COORD_ARRAY, f.tex != 0, "glInterleavedArrays");
        if f.tex != 0 {
            self.glTexCoordPointer(f.tex, gl::GL_FLOAT, s, pointer);
        }
        self.set_client_state(gl::GL_COLOR_ARRAY, f.color != 0, "glInterleavedArrays");
        if f.color != 0 {
            self.glColorPointer(f.color, f.color_type, s, at(f.pc));
        }
        self.set_client_state(gl::GL_NORMAL_ARRAY, f.normal, "glInterleavedArrays");
        if f.normal {
            self.glNormalPointer(gl::GL_FLOAT, s, at(f.pn));
        }
        self.set_client_state(gl::GL_VERTEX_ARRAY, true, "glInterleavedArrays");
        self.glVertexPointer(f.vertex, gl::GL_FLOAT, s, at(f.pv));
    }

    /// `glLockArraysEXT`: `GL_INVALID_VALUE` for a bad range, `GL_INVALID_OPERATION` when
    /// already locked.
    pub fn glLockArraysEXT(&mut self, first: GLint, count: GLsizei) {
        if first < 0 || count <= 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glLockArraysEXT");
        }
        if self.arrays.lock.is_some() {
            return self.set_error_in(gl::GL_INVALID_OPERATION, "glLockArraysEXT");
        }
        self.arrays.lock = Some((first, count));
    }

    /// `glUnlockArraysEXT`: `GL_INVALID_OPERATION` when not locked.
    pub fn glUnlockArraysEXT(&mut self) {
        if self.arrays.lock.take().is_none() {
            self.set_error_in(gl::GL_INVALID_OPERATION, "glUnlockArraysEXT");
        }
    }

    /// Resolves the enabled arrays and runs `f` on them under the share-group lock;
    /// `GL_INVALID_OPERATION` when one reads a mapped buffer.
    fn with_sources<R>(&mut self, command: &'static str, f: impl FnOnce(&Sources, &mut Self) -> R) -> Option<R> {
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

    /// `glArrayElement`: the attribute commands of element `i` of every enabled array, then
    /// its vertex (section 2.8).
    pub fn glArrayElement(&mut self, i: GLint) {
        let Ok(i) = usize::try_from(i) else {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glArrayElement");
        };
        let vertex = self.with_sources("glArrayElement", |s, ctx| s.element(i, &mut ctx.immediate.current));
        if let Some(Some([x, y, z, w])) = vertex {
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
        let current = self.immediate.current;
        if let Some(calls) = self.with_sources("glArrayElement", |s, _| s.element_calls(i, &current)) {
            for call in calls {
                self.lists.record(ListOp::Call(call));
            }
        }
    }

    /// Fetches the vertices of a draw; `None` (after raising any error) when nothing is drawn.
    fn fetch(&mut self, primitive: Primitive, elements: Elements<'_>, command: &'static str, mut batch: Batch) -> Option<Fetched> {
        let current = self.immediate.current;
        let fetched = self.with_sources(command, |s, _| {
            s.vertex?;
            let from_arrays = FromArrays {
                normal: s.normal.is_some(),
                color: s.color.is_some(),
                secondary_color: s.secondary_color.is_some(),
                index: s.index.is_some(),
                edge_flag: s.edge_flag.is_some(),
                fog_coord: s.fog_coord.is_some(),
                texcoord: s.texcoord.map(|t| t.is_some()),
            };
            batch.clear();
            let mut cur = current;
            let mut push = |i: usize| {
                let position = s.element(i, &mut cur).unwrap_or([0.0, 0.0, 0.0, 1.0]);
                batch.push(position, &cur);
            };
            let order = match elements {
                Elements::Range(first, count) => {
                    (first..first.saturating_add(count)).for_each(&mut push);
                    None
                }
                Elements::Indices(indices) => {
                    let min = indices.iter().copied().min().unwrap_or(0);
                    let max = indices.iter().copied().max().unwrap_or(0);
                    let span = (max - min) as usize + 1;
                    if span <= indices.len().saturating_mul(SPARSE_FACTOR).max(64) {
                        (min as usize..=max as usize).for_each(&mut push);
                        Some(indices.iter().map(|&i| i - min).collect())
                    } else {
                        indices.iter().for_each(|&i| push(i as usize));
                        None
                    }
                }
            };
            Some(Fetched { primitive, batch, order, from_arrays })
        });
        fetched.flatten()
    }

    /// Decomposes fetched vertices and emits them.
    fn submit(&mut self, fetched: &Fetched) {
        let mut assembled = std::mem::take(&mut self.immediate.assembled);
        assembled.clear();
        let batch = &fetched.batch;
        match &fetched.order {
            None => assemble(fetched.primitive, batch.vertices.len(), |k| k as u32, |k| batch.edge_flag(k as u32), &mut assembled),
            Some(order) => assemble(fetched.primitive, order.len(), |k| order[k], |k| batch.edge_flag(order[k]), &mut assembled),
        }
        let source = self.arrays_source();
        self.emit_batch(fetched.primitive.topology(), &batch.vertices, &assembled, source);
        self.immediate.assembled = assembled;
    }

    /// Draws `elements` now, reusing the immediate-mode batch storage.
    fn draw_now(&mut self, primitive: Primitive, elements: Elements<'_>, command: &'static str) {
        let storage = std::mem::take(&mut self.immediate.batch);
        match self.fetch(primitive, elements, command, storage) {
            Some(fetched) => {
                self.submit(&fetched);
                self.immediate.batch = fetched.batch;
            }
            None => self.immediate.batch = Batch::default(),
        }
    }

    /// Records a draw whose arrays were read now (section 5.4): at execution, attributes not
    /// taken from arrays use the then-current values.
    fn draw_compiled(&mut self, primitive: Primitive, elements: Elements<'_>, command: &'static str) {
        let Some(fetched) = self.fetch(primitive, elements, command, Batch::default()) else { return };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| {
            if ctx.inside_begin_end() {
                return ctx.set_error_in(gl::GL_INVALID_OPERATION, command);
            }
            let mut f = fetched.clone();
            f.take_current(&ctx.immediate.current);
            ctx.submit(&f);
        })));
    }

    /// Checks `glDrawArrays` arguments: the mode and the element range.
    fn draw_arrays_args(&mut self, mode: GLenum, first: GLint, count: GLsizei) -> Option<(Primitive, Elements<'static>)> {
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

    /// Checks `glDrawElements` arguments and reads the indices (from the client or the
    /// element array buffer).
    unsafe fn read_elements(&mut self, mode: GLenum, count: GLsizei, type_: GLenum, indices: *const c_void, command: &'static str) -> Option<(Primitive, Vec<u32>)> {
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
            let Some(bytes) = (unsafe { read_slice(indices.cast::<u8>(), bytes_len) }) else {
                self.null_pointer(command);
                return None;
            };
            return Some((primitive, decode_indices(&bytes, width)));
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
        Some((primitive, decode_indices(bytes, width)))
    }

    /// `glDrawElements`.
    ///
    /// # Safety
    /// Without an element array buffer, `indices` must point to `count` indices of `type_`;
    /// the enabled client arrays must hold the elements they name.
    pub unsafe fn glDrawElements(&mut self, mode: GLenum, count: GLsizei, type_: GLenum, indices: *const c_void) {
        if let Some((p, idx)) = unsafe { self.read_elements(mode, count, type_, indices, "glDrawElements") } {
            self.draw_now(p, Elements::Indices(&idx), "glDrawElements");
        }
    }

    /// `glDrawElements` in a display list.
    ///
    /// # Safety
    /// As [`Context::glDrawElements`].
    pub unsafe fn compile_glDrawElements(&mut self, mode: GLenum, count: GLsizei, type_: GLenum, indices: *const c_void) {
        if let Some((p, idx)) = unsafe { self.read_elements(mode, count, type_, indices, "glDrawElements") } {
            self.draw_compiled(p, Elements::Indices(&idx), "glDrawElements");
        }
    }

    /// `glDrawRangeElements`: `GL_INVALID_VALUE` when `end < start`.
    ///
    /// # Safety
    /// As [`Context::glDrawElements`].
    pub unsafe fn glDrawRangeElements(&mut self, mode: GLenum, start: GLuint, end: GLuint, count: GLsizei, type_: GLenum, indices: *const c_void) {
        if end < start {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glDrawRangeElements");
        }
        if let Some((p, idx)) = unsafe { self.read_elements(mode, count, type_, indices, "glDrawRangeElements") } {
            self.draw_now(p, Elements::Indices(&idx), "glDrawRangeElements");
        }
    }

    /// `glDrawRangeElements` in a display list.
    ///
    /// # Safety
    /// As [`Context::glDrawElements`].
    pub unsafe fn compile_glDrawRangeElements(&mut self, mode: GLenum, start: GLuint, end: GLuint, count: GLsizei, type_: GLenum, indices: *const c_void) {
        if end < start {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glDrawRangeElements");
        }
        if let Some((p, idx)) = unsafe { self.read_elements(mode, count, type_, indices, "glDrawRangeElements") } {
            self.draw_compiled(p, Elements::Indices(&idx), "glDrawRangeElements");
        }
    }

    /// The `(first, count)` pairs of `glMultiDrawArrays`; `GL_INVALID_VALUE` for a negative
    /// `drawcount`.
    unsafe fn multi_ranges(&mut self, first: *const GLint, count: *const GLsizei, drawcount: GLsizei) -> Option<Vec<(GLint, GLsizei)>> {
        let Ok(n) = usize::try_from(drawcount) else {
            self.set_error_in(gl::GL_INVALID_VALUE, "glMultiDrawArrays");
            return None;
        };
        let (Some(firsts), Some(counts)) = (unsafe { read_slice(first, n) }, unsafe { read_slice(count, n) }) else {
            self.null_pointer("glMultiDrawArrays");
            return None;
        };
        Some(firsts.into_iter().zip(counts).collect())
    }

    /// `glMultiDrawArrays`: `glDrawArrays` for each range.
    ///
    /// # Safety
    /// `first` and `count` must point to `drawcount` values; the arrays must hold the elements.
    pub unsafe fn glMultiDrawArrays(&mut self, mode: GLenum, first: *const GLint, count: *const GLsizei, drawcount: GLsizei) {
        for (f, c) in unsafe { self.multi_ranges(first, count, drawcount) }.unwrap_or_default() {
            self.glDrawArrays(mode, f, c);
        }
    }

    /// `glMultiDrawArrays` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMultiDrawArrays`].
    pub unsafe fn compile_glMultiDrawArrays(&mut self, mode: GLenum, first: *const GLint, count: *const GLsizei, drawcount: GLsizei) {
        for (f, c) in unsafe { self.multi_ranges(first, count, drawcount) }.unwrap_or_default() {
            unsafe { self.compile_glDrawArrays(mode, f, c) };
        }
    }

    /// The `(count, indices)` pairs of `glMultiDrawElements`.
    unsafe fn multi_elements(&mut self, count: *const GLsizei, indices: *const *const c_void, drawcount: GLsizei) -> Option<Vec<(GLsizei, *const c_void)>> {
        let Ok(n) = usize::try_from(drawcount) else {
            self.set_error_in(gl::GL_INVALID_VALUE, "glMultiDrawElements");
            return None;
        };
        let (Some(counts), Some(pointers)) = (unsafe { read_slice(count, n) }, unsafe { read_slice(indices, n) }) else {
            self.null_pointer("glMultiDrawElements");
            return None;
        };
        Some(counts.into_iter().zip(pointers).collect())
    }

    /// `glMultiDrawElements`: `glDrawElements` for each index list.
    ///
    /// # Safety
    /// `count` and `indices` must point to `drawcount` values, each index list as
    /// [`Context::glDrawElements`] requires.
    pub unsafe fn glMultiDrawElements(&mut self, mode: GLenum, count: *const GLsizei, type_: GLenum, indices: *const *const c_void, drawcount: GLsizei) {
        for (c, p) in unsafe { self.multi_elements(count, indices, drawcount) }.unwrap_or_default() {
            unsafe { self.glDrawElements(mode, c, type_, p) };
        }
    }

    /// `glMultiDrawElements` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMultiDrawElements`].
    pub unsafe fn compile_glMultiDrawElements(&mut self, mode: GLenum, count: *const GLsizei, type_: GLenum, indices: *const *const c_void, drawcount: GLsizei) {
        for (c, p) in unsafe { self.multi_elements(count, indices, drawcount) }.unwrap_or_default() {
            unsafe { self.compile_glDrawElements(mode, c, type_, p) };
        }
    }

    /// The array a `glGet` name is about, and which of its six names it is.
    fn array_pname(&self, pname: GLenum) -> Option<(&ArrayPointer, usize)> {
        ARRAY_PNAMES.iter().find_map(|(kind, names)| {
            let which = names.iter().position(|&n| n == pname && n != 0)?;
            let kind = match *kind {
                ArrayKind::TexCoord(_) => ArrayKind::TexCoord(self.texunit.client_active),
                k => k,
            };
            Some((self.arrays.get(kind), which))
        })
    }

    /// `glGetPointerv` parameters of the arrays: the address, or the offset into the buffer.
    pub(crate) fn pointer_arrays(&self, pname: GLenum) -> Option<*mut c_void> {
        match self.array_pname(pname)? {
            (array, 5) => Some(array.pointer as *mut c_void),
            _ => None,
        }
    }

    /// `glGetPointerv`. Other modules' pointers (feedback and selection buffers) join the
    /// chain with `.or_else(|| self.pointer_xxx(pname))`.
    ///
    /// # Safety
    /// `params` must have room for one pointer.
    pub unsafe fn glGetPointerv(&mut self, pname: GLenum, params: *const *mut c_void) {
        match None.or_else(|| self.pointer_arrays(pname)) {
            Some(p) => unsafe { write_slice(params.cast_mut(), &[p]) },
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glGetPointerv"),
        }
    }

    /// The vertex-array parameters of `glGet` (table 6.8), with the client attribute stack's.
    pub(crate) fn query_arrays(&self, pname: GLenum) -> Option<Value> {
        if let Some((array, which)) = self.array_pname(pname) {
            return match which {
                0 => Some(Value::bool(array.enabled)),
                1 => Some(Value::int(array.size)),
                2 => Some(Value::int(array.type_)),
                3 => Some(Value::int(array.stride)),
                4 => Some(Value::int(array.buffer)),
                _ => None,
            };
        }
        let a = &self.arrays;
        Some(match pname {
            gl::GL_ARRAY_BUFFER_BINDING => Value::int(a.array_buffer),
            gl::GL_ELEMENT_ARRAY_BUFFER_BINDING => Value::int(a.element_buffer),
            gl::GL_ARRAY_ELEMENT_LOCK_FIRST_EXT => Value::int(a.lock.map_or(0, |l| l.0)),
            gl::GL_ARRAY_ELEMENT_LOCK_COUNT_EXT => Value::int(a.lock.map_or(0, |l| l.1)),
            gl::GL_MAX_ELEMENTS_VERTICES | gl::GL_MAX_ELEMENTS_INDICES => Value::int(MAX_ELEMENTS),
            _ => return self.query_client_attrib(pname),
        })
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
            assert_eq!(d.vertex_count(), 4, "shared vertices are fetched once");
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
        assert_eq!((d.topology, d.vertex_count(), d.indices.clone()), (Topology::Lines, 2, vec![0, 1]));
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
        assert_eq!(d.vertex_count(), 2);
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
        unsafe { ctx.glDrawElements(gl::GL_QUADS, 4, gl::GL_UNSIGNED_SHORT, 0 as *const c_void) };
        let d = &ctx.frame.draws[0];
        assert_eq!(d.vertices.position, vec![
            [0.0, 0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0, 1.0],
            [1.0, 1.0, 0.0, 1.0],
            [0.0, 1.0, 0.0, 1.0]
        ]);
        assert_eq!(d.indices, vec![0, 1, 3, 1, 2, 3]);
        // Past the end of the store: elements read as zero, no crash.
        ctx.glDrawArrays(gl::GL_POINTS, 3, 3);
        assert_eq!(ctx.frame.draws.last().unwrap().vertices.position[2], [0.0; 4]);
        // Indices past the end of the element buffer: nothing drawn.
        let before = ctx.frame.draws.len();
        unsafe { ctx.glDrawElements(gl::GL_POINTS, 8, gl::GL_UNSIGNED_SHORT, 0 as *const c_void) };
        assert_eq!(ctx.frame.draws.len(), before);
        // A mapped buffer cannot be drawn from.
        ctx.glBindBuffer(gl::GL_ARRAY_BUFFER, 1);
        ctx.glMapBuffer(gl::GL_ARRAY_BUFFER, gl::GL_READ_ONLY);
        ctx.glDrawArrays(gl::GL_POINTS, 0, 1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        assert_eq!(ctx.frame.draws.len(), before);
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
        assert_eq!((d.vertex_count(), d.indices.len()), (4, 4), "the two draws merge");
        let a: [u32; 1] = [3];
        let b: [u32; 2] = [0, 1];
        let ptrs: [*const c_void; 2] = [a.as_ptr().cast(), b.as_ptr().cast()];
        unsafe { ctx.glMultiDrawElements(gl::GL_POINTS, [1, 2].as_ptr(), gl::GL_UNSIGNED_INT, ptrs.as_ptr(), 2) };
        let d = &ctx.frame.draws[1];
        assert_eq!(d.vertices.position[0], [0.0, 1.0, 0.0, 1.0]);
        assert_eq!(d.vertex_count(), 3);
        unsafe { ctx.glMultiDrawArrays(gl::GL_LINES, first.as_ptr(), count.as_ptr(), -1) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
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

    #[test]
    fn interleaved_formats_set_the_arrays() {
        let (mut ctx, _) = Context::with_recording();
        // (format, tex size, colour size, colour type, normal, vertex size, stride, pc, pn, pv)
        let table: [(gl::GLenum, i32, i32, gl::GLenum, bool, i32, i32, usize, usize, usize); 14] = [
            (gl::GL_V2F, 0, 0, 0, false, 2, 8, 0, 0, 0),
            (gl::GL_V3F, 0, 0, 0, false, 3, 12, 0, 0, 0),
            (gl::GL_C4UB_V2F, 0, 4, gl::GL_UNSIGNED_BYTE, false, 2, 12, 0, 0, 4),
            (gl::GL_C4UB_V3F, 0, 4, gl::GL_UNSIGNED_BYTE, false, 3, 16, 0, 0, 4),
            (gl::GL_C3F_V3F, 0, 3, gl::GL_FLOAT, false, 3, 24, 0, 0, 12),
            (gl::GL_N3F_V3F, 0, 0, 0, true, 3, 24, 0, 0, 12),
            (gl::GL_C4F_N3F_V3F, 0, 4, gl::GL_FLOAT, true, 3, 40, 0, 16, 28),
            (gl::GL_T2F_V3F, 2, 0, 0, false, 3, 20, 0, 0, 8),
            (gl::GL_T4F_V4F, 4, 0, 0, false, 4, 32, 0, 0, 16),
            (gl::GL_T2F_C4UB_V3F, 2, 4, gl::GL_UNSIGNED_BYTE, false, 3, 24, 8, 0, 12),
            (gl::GL_T2F_C3F_V3F, 2, 3, gl::GL_FLOAT, false, 3, 32, 8, 0, 20),
            (gl::GL_T2F_N3F_V3F, 2, 0, 0, true, 3, 32, 0, 8, 20),
            (gl::GL_T2F_C4F_N3F_V3F, 2, 4, gl::GL_FLOAT, true, 3, 48, 8, 24, 36),
            (gl::GL_T4F_C4F_N3F_V4F, 4, 4, gl::GL_FLOAT, true, 4, 60, 16, 32, 44),
        ];
        let base = 0x1000usize;
        for (format, tex, color, color_type, normal, vertex, stride, pc, pn, pv) in table {
            ctx.glEnableClientState(gl::GL_EDGE_FLAG_ARRAY);
            ctx.glInterleavedArrays(format, 0, base as *const c_void);
            let name = gl::enum_name(format).unwrap();
            assert_eq!(int(&mut ctx, gl::GL_EDGE_FLAG_ARRAY), 0, "{name}");
            assert_eq!(int(&mut ctx, gl::GL_VERTEX_ARRAY), 1, "{name}");
            assert_eq!(int(&mut ctx, gl::GL_VERTEX_ARRAY_SIZE), vertex, "{name}");
            assert_eq!(int(&mut ctx, gl::GL_VERTEX_ARRAY_STRIDE), stride, "{name}");
            assert_eq!(ctx.arrays.vertex.pointer, base + pv, "{name}");
            assert_eq!(int(&mut ctx, gl::GL_TEXTURE_COORD_ARRAY), i32::from(tex != 0), "{name}");
            assert_eq!(int(&mut ctx, gl::GL_COLOR_ARRAY), i32::from(color != 0), "{name}");
            assert_eq!(int(&mut ctx, gl::GL_NORMAL_ARRAY), i32::from(normal), "{name}");
            if tex != 0 {
                assert_eq!(int(&mut ctx, gl::GL_TEXTURE_COORD_ARRAY_SIZE), tex, "{name}");
                assert_eq!(ctx.arrays.texcoord[0].pointer, base, "{name}");
            }
            if color != 0 {
                assert_eq!(int(&mut ctx, gl::GL_COLOR_ARRAY_SIZE), color, "{name}");
                assert_eq!(int(&mut ctx, gl::GL_COLOR_ARRAY_TYPE), color_type as i32, "{name}");
                assert_eq!(ctx.arrays.color.pointer, base + pc, "{name}");
            }
            if normal {
                assert_eq!(ctx.arrays.normal.pointer, base + pn, "{name}");
            }
        }
        // A real draw through T2F_C4UB_V3F.
        #[repr(C)]
        struct V {
            t: [f32; 2],
            c: [u8; 4],
            v: [f32; 3],
        }
        let data = [V { t: [0.5, 0.25], c: [255, 0, 0, 255], v: [1.0, 2.0, 3.0] }, V {
            t: [1.0, 1.0],
            c: [0, 255, 0, 255],
            v: [4.0, 5.0, 6.0],
        }];
        ctx.glInterleavedArrays(gl::GL_T2F_C4UB_V3F, 0, data.as_ptr().cast());
        ctx.glDrawArrays(gl::GL_LINES, 0, 2);
        let d = &ctx.frame.draws[0];
        assert_eq!(d.vertices.position[1], [4.0, 5.0, 6.0, 1.0]);
        assert_eq!(d.vertices.texcoords[0].get(0), Some([0.5, 0.25, 0.0, 1.0]));
        assert_eq!(d.vertices.color.get(1), Some([0.0, 1.0, 0.0, 1.0]));
        ctx.glInterleavedArrays(gl::GL_RGBA, 0, std::ptr::null());
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glInterleavedArrays(gl::GL_V2F, -4, std::ptr::null());
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    }

    #[test]
    fn pointer_errors_queries_and_lock() {
        let (mut ctx, _) = Context::with_recording();
        let p = 0x40 as *const c_void;
        let cases: [(fn(&mut Context), gl::GLenum); 12] = [
            (|c| c.glVertexPointer(1, gl::GL_FLOAT, 0, std::ptr::null()), gl::GL_INVALID_VALUE),
            (|c| c.glVertexPointer(3, gl::GL_UNSIGNED_BYTE, 0, std::ptr::null()), gl::GL_INVALID_ENUM),
            (|c| c.glVertexPointer(3, gl::GL_FLOAT, -1, std::ptr::null()), gl::GL_INVALID_VALUE),
            (|c| c.glNormalPointer(gl::GL_UNSIGNED_BYTE, 0, std::ptr::null()), gl::GL_INVALID_ENUM),
            (|c| c.glColorPointer(2, gl::GL_FLOAT, 0, std::ptr::null()), gl::GL_INVALID_VALUE),
            (|c| c.glSecondaryColorPointer(4, gl::GL_FLOAT, 0, std::ptr::null()), gl::GL_INVALID_VALUE),
            (|c| c.glIndexPointer(gl::GL_BYTE, 0, std::ptr::null()), gl::GL_INVALID_ENUM),
            (|c| c.glTexCoordPointer(5, gl::GL_FLOAT, 0, std::ptr::null()), gl::GL_INVALID_VALUE),
            (|c| c.glFogCoordPointer(gl::GL_INT, 0, std::ptr::null()), gl::GL_INVALID_ENUM),
            (|c| c.glEdgeFlagPointer(-1, std::ptr::null()), gl::GL_INVALID_VALUE),
            (|c| c.glEnableClientState(gl::GL_LIGHTING), gl::GL_INVALID_ENUM),
            (|c| c.glUnlockArraysEXT(), gl::GL_INVALID_OPERATION),
        ];
        for (i, (f, error)) in cases.into_iter().enumerate() {
            f(&mut ctx);
            assert_eq!(ctx.glGetError(), error, "case {i}");
        }
        ctx.glClientActiveTexture(gl::GL_TEXTURE1);
        ctx.glTexCoordPointer(2, gl::GL_SHORT, 4, p);
        ctx.glEnableClientState(gl::GL_TEXTURE_COORD_ARRAY);
        assert_eq!(ctx.glIsEnabled(gl::GL_TEXTURE_COORD_ARRAY), 1);
        assert_eq!(int(&mut ctx, gl::GL_TEXTURE_COORD_ARRAY_TYPE), gl::GL_SHORT as i32);
        let mut got = std::ptr::null_mut();
        unsafe { ctx.glGetPointerv(gl::GL_TEXTURE_COORD_ARRAY_POINTER, &mut got) };
        assert_eq!(got as usize, 0x40);
        ctx.glClientActiveTexture(gl::GL_TEXTURE0);
        assert_eq!(ctx.glIsEnabled(gl::GL_TEXTURE_COORD_ARRAY), 0);
        assert_eq!(int(&mut ctx, gl::GL_TEXTURE_COORD_ARRAY_SIZE), 4);
        unsafe { ctx.glGetPointerv(gl::GL_LIGHTING, &mut got) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glLockArraysEXT(2, 100);
        assert_eq!(int(&mut ctx, gl::GL_ARRAY_ELEMENT_LOCK_COUNT_EXT), 100);
        ctx.glLockArraysEXT(0, 1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        ctx.glUnlockArraysEXT();
        ctx.glLockArraysEXT(0, 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        assert_eq!(int(&mut ctx, gl::GL_ARRAY_ELEMENT_LOCK_COUNT_EXT), 0);
    }
}
