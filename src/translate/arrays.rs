//! Vertex-array state (OpenGL 1.5 section 2.8): the array pointers and their enables, the
//! buffer-object bindings they capture (section 2.9), `glInterleavedArrays`,
//! `EXT_compiled_vertex_array`, `glGetPointerv` and the array `glGet` parameters. Reading the
//! arrays is [`super::array_fetch`]; drawing from them is [`super::draw_arrays`].
//!
//! `glLockArraysEXT` records the locked range; the draws of the lock convert the vertex array
//! once ([`super::locked_arrays`]) and read the others at each draw.

use std::ffi::c_void;

use super::Context;
use super::convert::write_slice;
use super::get::Value;
use super::gl::{self, GLenum, GLint, GLsizei, GLuint};
use super::limits::{MAX_TEXTURE_UNITS, MAX_VERTEX_ATTRIBS};

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
    /// `GL_VERTEX_ATTRIB_ARRAY_NORMALIZED` (generic arrays; the others are normalized as
    /// table 2.9 says for their attribute).
    pub normalized: bool,
}

impl ArrayPointer {
    const fn new(size: GLint, type_: GLenum) -> ArrayPointer {
        ArrayPointer { enabled: false, size, type_, stride: 0, pointer: 0, buffer: 0, normalized: false }
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
    /// Generic vertex attribute array `i` (OpenGL 2.0, `glVertexAttribPointer`).
    Generic(usize),
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
    /// Generic vertex attribute arrays by index (array 0 gives positions, as the vertex
    /// array does, and wins over it).
    pub generic: [ArrayPointer; MAX_VERTEX_ATTRIBS],
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
            generic: [ArrayPointer::new(4, gl::GL_FLOAT); MAX_VERTEX_ATTRIBS],
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
            ArrayKind::Generic(i) => &self.generic[i],
        }
    }

    pub(crate) fn get_mut(&mut self, kind: ArrayKind) -> &mut ArrayPointer {
        match kind {
            ArrayKind::Vertex => &mut self.vertex,
            ArrayKind::Normal => &mut self.normal,
            ArrayKind::Color => &mut self.color,
            ArrayKind::SecondaryColor => &mut self.secondary_color,
            ArrayKind::Index => &mut self.index,
            ArrayKind::EdgeFlag => &mut self.edge_flag,
            ArrayKind::FogCoord => &mut self.fog_coord,
            ArrayKind::TexCoord(u) => &mut self.texcoord[u],
            ArrayKind::Generic(i) => &mut self.generic[i],
        }
    }

    /// Every array.
    fn all(&self) -> impl Iterator<Item = &ArrayPointer> {
        [&self.vertex, &self.normal, &self.color, &self.secondary_color, &self.index, &self.edge_flag, &self.fog_coord]
            .into_iter()
            .chain(&self.texcoord)
            .chain(&self.generic)
    }

    /// Whether an enabled array reads a buffer object.
    pub fn reads_buffers(&self) -> bool {
        self.all().any(|a| a.enabled && a.buffer != 0)
    }

    /// Forgets a deleted buffer: bindings and array buffer bindings naming it become 0.
    pub fn unbind_buffer(&mut self, name: GLuint) {
        for binding in [&mut self.array_buffer, &mut self.element_buffer] {
            if *binding == name {
                *binding = 0;
            }
        }
        for array in [
            &mut self.vertex,
            &mut self.normal,
            &mut self.color,
            &mut self.secondary_color,
            &mut self.index,
            &mut self.edge_flag,
            &mut self.fog_coord,
        ]
        .into_iter()
        .chain(&mut self.texcoord)
        .chain(&mut self.generic)
        {
            if array.buffer == name {
                array.buffer = 0;
            }
        }
    }
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
/// Component types of colour arrays, which generic attribute arrays take too
/// (`glVertexAttribPointer`).
pub(crate) const COLOR_TYPES: &[GLenum] = &[
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
    (
        ArrayKind::Vertex,
        [
            gl::GL_VERTEX_ARRAY,
            gl::GL_VERTEX_ARRAY_SIZE,
            gl::GL_VERTEX_ARRAY_TYPE,
            gl::GL_VERTEX_ARRAY_STRIDE,
            gl::GL_VERTEX_ARRAY_BUFFER_BINDING,
            gl::GL_VERTEX_ARRAY_POINTER,
        ],
    ),
    (
        ArrayKind::Normal,
        [
            gl::GL_NORMAL_ARRAY,
            0,
            gl::GL_NORMAL_ARRAY_TYPE,
            gl::GL_NORMAL_ARRAY_STRIDE,
            gl::GL_NORMAL_ARRAY_BUFFER_BINDING,
            gl::GL_NORMAL_ARRAY_POINTER,
        ],
    ),
    (
        ArrayKind::Color,
        [
            gl::GL_COLOR_ARRAY,
            gl::GL_COLOR_ARRAY_SIZE,
            gl::GL_COLOR_ARRAY_TYPE,
            gl::GL_COLOR_ARRAY_STRIDE,
            gl::GL_COLOR_ARRAY_BUFFER_BINDING,
            gl::GL_COLOR_ARRAY_POINTER,
        ],
    ),
    (
        ArrayKind::SecondaryColor,
        [
            gl::GL_SECONDARY_COLOR_ARRAY,
            gl::GL_SECONDARY_COLOR_ARRAY_SIZE,
            gl::GL_SECONDARY_COLOR_ARRAY_TYPE,
            gl::GL_SECONDARY_COLOR_ARRAY_STRIDE,
            gl::GL_SECONDARY_COLOR_ARRAY_BUFFER_BINDING,
            gl::GL_SECONDARY_COLOR_ARRAY_POINTER,
        ],
    ),
    (
        ArrayKind::Index,
        [
            gl::GL_INDEX_ARRAY,
            0,
            gl::GL_INDEX_ARRAY_TYPE,
            gl::GL_INDEX_ARRAY_STRIDE,
            gl::GL_INDEX_ARRAY_BUFFER_BINDING,
            gl::GL_INDEX_ARRAY_POINTER,
        ],
    ),
    (
        ArrayKind::EdgeFlag,
        [
            gl::GL_EDGE_FLAG_ARRAY,
            0,
            0,
            gl::GL_EDGE_FLAG_ARRAY_STRIDE,
            gl::GL_EDGE_FLAG_ARRAY_BUFFER_BINDING,
            gl::GL_EDGE_FLAG_ARRAY_POINTER,
        ],
    ),
    (
        ArrayKind::FogCoord,
        [
            gl::GL_FOG_COORD_ARRAY,
            0,
            gl::GL_FOG_COORD_ARRAY_TYPE,
            gl::GL_FOG_COORD_ARRAY_STRIDE,
            gl::GL_FOG_COORD_ARRAY_BUFFER_BINDING,
            gl::GL_FOG_COORD_ARRAY_POINTER,
        ],
    ),
    (
        ArrayKind::TexCoord(0),
        [
            gl::GL_TEXTURE_COORD_ARRAY,
            gl::GL_TEXTURE_COORD_ARRAY_SIZE,
            gl::GL_TEXTURE_COORD_ARRAY_TYPE,
            gl::GL_TEXTURE_COORD_ARRAY_STRIDE,
            gl::GL_TEXTURE_COORD_ARRAY_BUFFER_BINDING,
            gl::GL_TEXTURE_COORD_ARRAY_POINTER,
        ],
    ),
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

impl Context {
    /// Sets an array pointer after checking `rules` (section 2.8 errors).
    fn set_pointer(
        &mut self,
        kind: ArrayKind,
        rules: &PointerRules,
        size: GLint,
        type_: GLenum,
        stride: GLsizei,
        pointer: *const c_void,
    ) {
        if !rules.sizes.contains(&size) || stride < 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, rules.command);
        }
        if !rules.types.contains(&type_) {
            return self.set_error_in(gl::GL_INVALID_ENUM, rules.command);
        }
        let buffer = self.arrays.array_buffer;
        let array = self.arrays.get_mut(kind);
        *array = ArrayPointer { enabled: array.enabled, size, type_, stride, pointer: pointer as usize, buffer, normalized: false };
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

    pub(crate) fn set_client_state(&mut self, cap: GLenum, on: bool, command: &'static str) {
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
        self.fetch.locked.forget();
    }

    /// `glUnlockArraysEXT`: `GL_INVALID_OPERATION` when not locked.
    pub fn glUnlockArraysEXT(&mut self) {
        if self.arrays.lock.take().is_none() {
            self.set_error_in(gl::GL_INVALID_OPERATION, "glUnlockArraysEXT");
        }
        self.fetch.locked.forget();
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

    /// `glGetPointerv`: the array pointers, and the selection and feedback buffers
    /// (`GL_SELECTION_BUFFER_POINTER`, `GL_FEEDBACK_BUFFER_POINTER`).
    ///
    /// # Safety
    /// `params` must have room for one pointer.
    pub unsafe fn glGetPointerv(&mut self, pname: GLenum, params: *const *mut c_void) {
        match self.pointer_arrays(pname).or_else(|| self.render_mode_pointer(pname)) {
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
            _ => return self.query_client_attrib(pname),
        })
    }
}
#[cfg(test)]
mod tests {
    use std::ffi::c_void;

    use crate::translate::{Context, gl};

    fn int(ctx: &mut Context, pname: gl::GLenum) -> i32 {
        let mut v = -1;
        unsafe { ctx.glGetIntegerv(pname, &mut v) };
        v
    }

    /// A row of table 2.5: format, texture size, colour size and type, normal, vertex size,
    /// stride, colour, normal and vertex offsets.
    type Row = (gl::GLenum, i32, i32, gl::GLenum, bool, i32, i32, usize, usize, usize);

    /// A command and the error it must raise.
    type ErrorCase = (fn(&mut Context), gl::GLenum);

    #[test]
    fn interleaved_formats_set_the_arrays() {
        let (mut ctx, _) = Context::with_recording();
        let table: [Row; 14] = [
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
        let data = [
            V { t: [0.5, 0.25], c: [255, 0, 0, 255], v: [1.0, 2.0, 3.0] },
            V { t: [1.0, 1.0], c: [0, 255, 0, 255], v: [4.0, 5.0, 6.0] },
        ];
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
        let cases: [ErrorCase; 12] = [
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
        unsafe { ctx.glGetPointerv(gl::GL_TEXTURE_COORD_ARRAY_POINTER, &raw mut got) };
        assert_eq!(got as usize, 0x40);
        ctx.glClientActiveTexture(gl::GL_TEXTURE0);
        assert_eq!(ctx.glIsEnabled(gl::GL_TEXTURE_COORD_ARRAY), 0);
        assert_eq!(int(&mut ctx, gl::GL_TEXTURE_COORD_ARRAY_SIZE), 4);
        unsafe { ctx.glGetPointerv(gl::GL_LIGHTING, &raw mut got) };
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
