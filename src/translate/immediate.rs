//! Immediate mode (OpenGL 1.5 sections 2.6 and 2.7): the current vertex attributes,
//! `glBegin`/`glEnd`, `glVertex` and `glRect`.
//!
//! Vertices between `glBegin` and `glEnd` are appended to a batch whose storage is reused from
//! one `glBegin` to the next; an attribute that does not change inside the batch is stored
//! once (see [`crate::frame::Attrib`]). The attribute commands set a bit in a changed-mask, so
//! `glVertex` tests one bit for each attribute that is still shared and pushes the ones already
//! stored per vertex: no allocation once the storage has grown, no lookup per vertex. `glEnd`
//! decomposes the batch ([`super::assemble`]) and hands it to `Context::emit_batch`.
//!
//! Other modules read the current values with [`ImmediateState::current`] and change them
//! with [`ImmediateState::current_mut`] (which marks them all changed), never directly.

use super::Context;
use super::assemble::{Assembled, Primitive, assemble_batch};
use super::get::Value;
use super::gl::{self, GLboolean, GLenum, GLfloat};
use super::limits::{MAX_TEXTURE_UNITS, MAX_VERTEX_ATTRIBS};
use super::texunit::unit_index;
use crate::frame::{Attrib, Vertices};

/// The current values of the vertex attributes (section 2.7, table 6.5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurrentAttribs {
    /// `GL_CURRENT_COLOR`.
    pub color: [f32; 4],
    /// `GL_CURRENT_SECONDARY_COLOR` (RGB; its alpha reads as 0).
    pub secondary_color: [f32; 3],
    /// `GL_CURRENT_NORMAL`.
    pub normal: [f32; 3],
    /// `GL_CURRENT_TEXTURE_COORDS` of each unit.
    pub texcoords: [[f32; 4]; MAX_TEXTURE_UNITS],
    /// `GL_CURRENT_FOG_COORD`.
    pub fog_coord: f32,
    /// `GL_CURRENT_INDEX`.
    pub color_index: f32,
    /// `GL_EDGE_FLAG`.
    pub edge_flag: bool,
    /// `GL_CURRENT_VERTEX_ATTRIB` of each generic attribute (index 0, the vertex, has none).
    pub generic: [[f32; 4]; MAX_VERTEX_ATTRIBS],
}

impl Default for CurrentAttribs {
    fn default() -> CurrentAttribs {
        CurrentAttribs {
            color: [1.0; 4],
            secondary_color: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
            texcoords: [[0.0, 0.0, 0.0, 1.0]; MAX_TEXTURE_UNITS],
            fog_coord: 0.0,
            color_index: 1.0,
            edge_flag: true,
            generic: [[0.0, 0.0, 0.0, 1.0]; MAX_VERTEX_ATTRIBS],
        }
    }
}

/// Bits naming the attributes of a vertex, for `ImmediateState::dirty` and
/// `Batch::per_vertex`.
pub mod bits {
    /// Normal.
    pub const NORMAL: u32 = 1;
    /// Primary colour.
    pub const COLOR: u32 = 1 << 1;
    /// Secondary colour.
    pub const SECONDARY_COLOR: u32 = 1 << 2;
    /// Fog coordinate.
    pub const FOG_COORD: u32 = 1 << 3;
    /// Colour index.
    pub const COLOR_INDEX: u32 = 1 << 4;
    /// Edge flag.
    pub const EDGE_FLAG: u32 = 1 << 5;
    /// Texture coordinates of unit 0; unit `u` is `TEXCOORD0 << u`.
    pub const TEXCOORD0: u32 = 1 << 6;
    /// Generic attribute 1; attribute `i` is `GENERIC1 << (i - 1)`.
    pub const GENERIC1: u32 = 1 << 10;
    /// Every attribute.
    pub const ALL: u32 = u32::MAX;
}

/// Vertices being assembled, with their edge flags.
#[derive(Clone, Debug, PartialEq)]
pub struct Batch {
    /// Positions and attributes.
    pub vertices: Vertices,
    /// Edge flag of each vertex (section 2.6.2).
    pub edge_flags: Attrib<bool>,
    /// Attributes already stored once per vertex ([`bits`]).
    per_vertex: u32,
}

impl Default for Batch {
    fn default() -> Batch {
        Batch { vertices: Vertices::with_units(MAX_TEXTURE_UNITS), edge_flags: Attrib::default(), per_vertex: 0 }
    }
}

/// Appends `value` to an attribute: pushed when it is stored per vertex, compared with the
/// shared value when it `changed`, untouched otherwise.
#[inline(always)]
fn update<T: Copy + PartialEq>(a: &mut Attrib<T>, value: T, n: usize, bit: u32, changed: u32, per_vertex: &mut u32) {
    if *per_vertex & bit != 0 {
        a.values.push(value);
    } else if changed & bit != 0 {
        update_shared(a, value, n, bit, per_vertex);
    }
}

/// [`update`] of a shared attribute that was set: compared with the shared value, and stored
/// per vertex from now on when it differs. Kept out of line so that the per-vertex path of
/// `Batch::push` does not carry the set-up of `Attrib::push`'s fill loop.
#[inline(never)]
fn update_shared<T: Copy + PartialEq>(a: &mut Attrib<T>, value: T, n: usize, bit: u32, per_vertex: &mut u32) {
    a.push(value, n);
    if !a.is_constant() {
        *per_vertex |= bit;
    }
}

impl Batch {
    /// A batch without storage (no texture units), to stand in while the real one is lent.
    fn unallocated() -> Batch {
        Batch { vertices: Vertices::default(), edge_flags: Attrib::default(), per_vertex: 0 }
    }

    /// Removes every vertex, keeping the storage; the vertices to come store `generic`
    /// generic attributes (all of them while a program is in use, none otherwise).
    pub fn clear_for(&mut self, generic: usize) {
        self.clear();
        self.vertices.generic.resize(generic, Attrib::default());
    }

    /// Removes every vertex, keeping the storage.
    pub fn clear(&mut self) {
        self.vertices.clear();
        self.edge_flags.truncate(0);
        self.per_vertex = 0;
    }

    /// Appends a vertex with the values of `current`; `changed` names the attributes that may
    /// differ from the previous vertex ([`bits`]). Attributes that never change cost nothing
    /// per vertex: the colour, unit 0's texture coordinates and the normal are tested directly,
    /// the other attributes only when one of them is changed or stored per vertex.
    #[inline]
    pub fn push(&mut self, position: [f32; 4], c: &CurrentAttribs, changed: u32) {
        let v = &mut self.vertices;
        let n = v.position.len();
        v.position.push(position);
        if n == 0 {
            return self.start(c);
        }
        let todo = changed | self.per_vertex;
        let pv = &mut self.per_vertex;
        if todo & bits::COLOR != 0 {
            update(&mut v.color, c.color, n, bits::COLOR, changed, pv);
        }
        if todo & bits::TEXCOORD0 != 0
            && let Some(t) = v.texcoords.first_mut()
        {
            update(t, c.texcoords[0], n, bits::TEXCOORD0, changed, pv);
        }
        if todo & bits::NORMAL != 0 {
            update(&mut v.normal, c.normal, n, bits::NORMAL, changed, pv);
        }
        let rest = todo & !(bits::COLOR | bits::TEXCOORD0 | bits::NORMAL);
        if rest != 0 {
            self.push_rest(c, changed, rest, n);
        }
    }

    /// The first vertex's attributes, each stored once.
    #[cold]
    #[inline(never)]
    fn start(&mut self, c: &CurrentAttribs) {
        let v = &mut self.vertices;
        v.normal.set_constant(c.normal);
        v.color.set_constant(c.color);
        v.secondary_color.set_constant(c.secondary_color);
        v.fog_coord.set_constant(c.fog_coord);
        v.color_index.set_constant(c.color_index);
        for (t, &value) in v.texcoords.iter_mut().zip(&c.texcoords) {
            t.set_constant(value);
        }
        for (g, &value) in v.generic.iter_mut().zip(&c.generic).skip(1) {
            g.set_constant(value);
        }
        self.edge_flags.set_constant(c.edge_flag);
        self.per_vertex = 0;
    }

    /// [`Batch::push`] of the attributes in `rest` (changed or per vertex, but for the three
    /// tested directly) of vertex `n`: only their set bits are visited, lowest first.
    #[inline(never)]
    fn push_rest(&mut self, c: &CurrentAttribs, changed: u32, mut rest: u32, n: usize) {
        let v = &mut self.vertices;
        while rest != 0 {
            let bit = rest & rest.wrapping_neg();
            rest &= rest - 1;
            let pv = &mut self.per_vertex;
            match bit {
                bits::SECONDARY_COLOR => update(&mut v.secondary_color, c.secondary_color, n, bit, changed, pv),
                bits::FOG_COORD => update(&mut v.fog_coord, c.fog_coord, n, bit, changed, pv),
                bits::COLOR_INDEX => update(&mut v.color_index, c.color_index, n, bit, changed, pv),
                bits::EDGE_FLAG => update(&mut self.edge_flags, c.edge_flag, n, bit, changed, pv),
                _ if bit >= bits::GENERIC1 => {
                    // A generic attribute's bit; those the batch does not store name nothing.
                    let index = 1 + (bit / bits::GENERIC1).trailing_zeros() as usize;
                    if let (Some(g), Some(&value)) = (v.generic.get_mut(index), c.generic.get(index)) {
                        update(g, value, n, bit, changed, pv);
                    }
                }
                _ => {
                    // A texture unit's bit (unit 0's is never in `rest`); bits past the last
                    // unit name nothing.
                    let unit = (bit / bits::TEXCOORD0).trailing_zeros() as usize;
                    if let (Some(t), Some(&value)) = (v.texcoords.get_mut(unit), c.texcoords.get(unit)) {
                        update(t, value, n, bit, changed, pv);
                    }
                }
            }
        }
    }

    /// Gives every vertex so far the colour `color`, stored once.
    pub fn set_color(&mut self, color: [f32; 4]) {
        if !self.vertices.is_empty() {
            self.vertices.color.set_constant(color);
        }
        self.per_vertex &= !bits::COLOR;
    }

    /// The edge flag of vertex `i` (true when unknown).
    pub fn edge_flag(&self, i: u32) -> bool {
        self.edge_flags.get(i as usize).unwrap_or(true)
    }
}

/// Immediate-mode assembly state.
#[derive(Default)]
pub struct ImmediateState {
    /// The primitive of the open `glBegin`, if any.
    pub primitive: Option<Primitive>,
    /// Current vertex attributes (read with [`ImmediateState::current`]).
    current: CurrentAttribs,
    /// Attributes changed since the last vertex ([`bits`]).
    dirty: u32,
    /// Vertices since `glBegin`.
    pub batch: Batch,
    /// Decomposition of the batch, reused.
    pub assembled: Assembled,
    /// Which units texture, for the batch keys of [`super::frame_builder`].
    pub texturing: super::frame_builder::TexturingCache,
    /// `glMaterial` calls since `glBegin` ([`super::begin_material`]).
    pub material: super::begin_material::BeginMaterial,
}

impl ImmediateState {
    /// Lends the batch storage (put it back when done); no allocation.
    pub fn take_batch(&mut self) -> Batch {
        std::mem::replace(&mut self.batch, Batch::unallocated())
    }

    /// The current vertex attributes.
    pub fn current(&self) -> &CurrentAttribs {
        &self.current
    }

    /// The current vertex attributes, to change them: every attribute counts as changed for
    /// the next vertex.
    pub fn current_mut(&mut self) -> &mut CurrentAttribs {
        self.dirty = bits::ALL;
        &mut self.current
    }

    /// Changes one attribute (`bit` of [`bits`]).
    #[inline]
    pub(crate) fn set(&mut self, bit: u32, f: impl FnOnce(&mut CurrentAttribs)) {
        self.dirty |= bit;
        f(&mut self.current);
    }
}

impl Context {
    /// `glBegin`.
    pub fn glBegin(&mut self, mode: GLenum) {
        let Some(primitive) = Primitive::from_gl(mode) else {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glBegin");
        };
        let generic = self.generic_attributes();
        self.immediate.batch.clear_for(generic);
        self.immediate.primitive = Some(primitive);
    }

    /// `glEnd`: decomposes the primitive and emits it.
    pub fn glEnd(&mut self) {
        let Some(primitive) = self.immediate.primitive.take() else {
            return self.set_error_in(gl::GL_INVALID_OPERATION, "glEnd");
        };
        let mut assembled = std::mem::take(&mut self.immediate.assembled);
        let mut batch = self.immediate.take_batch();
        assembled.clear();
        assemble_batch(primitive, &batch, None, &mut assembled);
        let source = self.immediate_source();
        self.emit_with_begin_material(|ctx| ctx.emit_batch(primitive, &mut batch, None, &assembled, source));
        self.immediate.assembled = assembled;
        self.immediate.batch = batch;
    }

    /// `glVertex4f`: between `glBegin` and `glEnd`, a vertex with the current attributes;
    /// outside, nothing (the specification leaves it undefined).
    #[inline]
    pub fn glVertex4f(&mut self, x: GLfloat, y: GLfloat, z: GLfloat, w: GLfloat) {
        if self.immediate.primitive.is_some() {
            let material = self.begin_material_color();
            let im = &mut self.immediate;
            match material {
                None => im.batch.push([x, y, z, w], &im.current, im.dirty),
                Some(color) => im.batch.push([x, y, z, w], &CurrentAttribs { color, ..im.current }, im.dirty | bits::COLOR),
            }
            im.dirty = 0;
        }
    }

    /// `glColor4f`; with `GL_COLOR_MATERIAL` on, the material follows (section 2.14.3).
    pub fn glColor4f(&mut self, red: GLfloat, green: GLfloat, blue: GLfloat, alpha: GLfloat) {
        let color = [red, green, blue, alpha];
        self.immediate.set(bits::COLOR, |c| c.color = color);
        self.apply_color_material(color);
    }

    /// `glSecondaryColor3f`.
    pub fn glSecondaryColor3f(&mut self, red: GLfloat, green: GLfloat, blue: GLfloat) {
        self.immediate.set(bits::SECONDARY_COLOR, |c| c.secondary_color = [red, green, blue]);
    }

    /// `glNormal3f`.
    pub fn glNormal3f(&mut self, nx: GLfloat, ny: GLfloat, nz: GLfloat) {
        self.immediate.set(bits::NORMAL, |c| c.normal = [nx, ny, nz]);
    }

    /// `glTexCoord4f`: texture coordinates of unit 0 (section 2.7).
    pub fn glTexCoord4f(&mut self, s: GLfloat, t: GLfloat, r: GLfloat, q: GLfloat) {
        self.immediate.set(bits::TEXCOORD0, |c| c.texcoords[0] = [s, t, r, q]);
    }

    /// `glMultiTexCoord4f`: `GL_INVALID_ENUM` for a unit glrt does not have.
    pub fn glMultiTexCoord4f(&mut self, target: GLenum, s: GLfloat, t: GLfloat, r: GLfloat, q: GLfloat) {
        match unit_index(target) {
            Some(unit) => self.immediate.set(bits::TEXCOORD0 << unit, |c| c.texcoords[unit] = [s, t, r, q]),
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glMultiTexCoord"),
        }
    }

    /// `glFogCoordf`.
    pub fn glFogCoordf(&mut self, coord: GLfloat) {
        self.immediate.set(bits::FOG_COORD, |c| c.fog_coord = coord);
    }

    /// `glIndexf`.
    pub fn glIndexf(&mut self, c: GLfloat) {
        self.immediate.set(bits::COLOR_INDEX, |cur| cur.color_index = c);
    }

    /// `glEdgeFlag`.
    pub fn glEdgeFlag(&mut self, flag: GLboolean) {
        self.immediate.set(bits::EDGE_FLAG, |c| c.edge_flag = flag != 0);
    }

    /// `glEdgeFlagv`.
    ///
    /// # Safety
    /// `flag` must be null or point to one `GLboolean`.
    pub unsafe fn glEdgeFlagv(&mut self, flag: *const GLboolean) {
        match unsafe { super::convert::read_array::<_, 1>(flag) } {
            Some([f]) => self.glEdgeFlag(f),
            None => self.null_pointer("glEdgeFlagv"),
        }
    }

    /// `glEdgeFlagv` in a display list: recorded as `glEdgeFlag`.
    ///
    /// # Safety
    /// As [`Context::glEdgeFlagv`].
    pub unsafe fn compile_glEdgeFlagv(&mut self, flag: *const GLboolean) {
        match unsafe { super::convert::read_array::<_, 1>(flag) } {
            Some([f]) => self.lists.record(super::lists::ListOp::Call(super::dispatch::Call::EdgeFlag(f))),
            None => self.null_pointer("glEdgeFlagv"),
        }
    }

    /// `glRectf`: `glBegin(GL_POLYGON)`, the four corners counter-clockwise from
    /// `(x1, y1)`, `glEnd` (section 2.10).
    pub fn glRectf(&mut self, x1: GLfloat, y1: GLfloat, x2: GLfloat, y2: GLfloat) {
        self.glBegin(gl::GL_POLYGON);
        for (x, y) in [(x1, y1), (x2, y1), (x2, y2), (x1, y2)] {
            self.glVertex4f(x, y, 0.0, 1.0);
        }
        self.glEnd();
    }

    /// Saves the current values of `GL_CURRENT_BIT` this module owns (colours, normal, texture
    /// coordinates, fog coordinate, index, edge flag; not the raster position) for
    /// `glPopAttrib`: pushes one closure that puts them back.
    pub fn save_current_attrib(&self, out: &mut Vec<super::client_attrib::Restore>) {
        let saved = self.immediate.current;
        out.push(Box::new(move |ctx| *ctx.immediate.current_mut() = saved));
    }

    /// The current-attribute parameters of `glGet` (table 6.5).
    pub(crate) fn query_vertex(&self, pname: GLenum) -> Option<Value> {
        let c = &self.immediate.current;
        Some(match pname {
            gl::GL_CURRENT_COLOR => Value::normalized(&c.color),
            gl::GL_CURRENT_SECONDARY_COLOR => {
                // Table 6.5: the current secondary colour has alpha 1 (as Mesa reports).
                let [r, g, b] = c.secondary_color;
                Value::normalized(&[r, g, b, 1.0])
            }
            gl::GL_CURRENT_NORMAL => Value::normalized(&c.normal),
            gl::GL_CURRENT_TEXTURE_COORDS => Value::floats(&c.texcoords[self.active_texture_unit()]),
            gl::GL_CURRENT_FOG_COORD => Value::float(c.fog_coord),
            gl::GL_CURRENT_INDEX => Value::float(c.color_index),
            gl::GL_EDGE_FLAG => Value::bool(c.edge_flag),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::frame::Topology;
    use crate::translate::dispatch;
    use crate::translate::{Context, gl};

    fn floats(ctx: &mut Context, pname: gl::GLenum) -> Vec<f32> {
        let mut v = [f32::NAN; 4];
        unsafe { ctx.glGetFloatv(pname, v.as_mut_ptr()) };
        v.to_vec()
    }

    #[test]
    fn current_attributes_read_back() {
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(floats(&mut ctx, gl::GL_CURRENT_COLOR), vec![1.0; 4]);
        assert_eq!(floats(&mut ctx, gl::GL_CURRENT_NORMAL)[..3], [0.0, 0.0, 1.0]);
        unsafe {
            dispatch::glColor3ub(&mut ctx, 255, 0, 51);
            dispatch::glSecondaryColor3f(&mut ctx, 0.5, 0.25, 0.0);
            dispatch::glNormal3f(&mut ctx, 0.0, 1.0, 0.0);
            dispatch::glMultiTexCoord2f(&mut ctx, gl::GL_TEXTURE1, 3.0, 4.0);
            dispatch::glFogCoordf(&mut ctx, 2.5);
            dispatch::glIndexi(&mut ctx, 7);
            dispatch::glEdgeFlag(&mut ctx, 0);
        }
        assert_eq!(floats(&mut ctx, gl::GL_CURRENT_COLOR), vec![1.0, 0.0, 0.2, 1.0]);
        assert_eq!(floats(&mut ctx, gl::GL_CURRENT_SECONDARY_COLOR), vec![0.5, 0.25, 0.0, 1.0]);
        assert_eq!(floats(&mut ctx, gl::GL_CURRENT_NORMAL)[..3], [0.0, 1.0, 0.0]);
        assert_eq!(floats(&mut ctx, gl::GL_CURRENT_TEXTURE_COORDS), vec![0.0, 0.0, 0.0, 1.0]);
        ctx.glActiveTexture(gl::GL_TEXTURE1);
        assert_eq!(floats(&mut ctx, gl::GL_CURRENT_TEXTURE_COORDS), vec![3.0, 4.0, 0.0, 1.0]);
        assert_eq!(floats(&mut ctx, gl::GL_CURRENT_FOG_COORD)[0], 2.5);
        assert_eq!(floats(&mut ctx, gl::GL_CURRENT_INDEX)[0], 7.0);
        assert_eq!(floats(&mut ctx, gl::GL_EDGE_FLAG)[0], 0.0);
        let mut i = [0i32; 4];
        unsafe { ctx.glGetIntegerv(gl::GL_CURRENT_COLOR, i.as_mut_ptr()) };
        assert_eq!(i[0], i32::MAX, "colours read as integers map 1.0 to the largest integer");
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn saved_current_values_come_back() {
        let (mut ctx, _) = Context::with_recording();
        let mut saved = Vec::new();
        unsafe { dispatch::glColor4f(&mut ctx, 0.25, 0.5, 0.75, 1.0) };
        ctx.save_current_attrib(&mut saved);
        unsafe {
            dispatch::glColor4f(&mut ctx, 0.0, 0.0, 0.0, 0.0);
            dispatch::glEdgeFlag(&mut ctx, 0);
        }
        for restore in saved {
            restore(&mut ctx);
        }
        assert_eq!(floats(&mut ctx, gl::GL_CURRENT_COLOR), vec![0.25, 0.5, 0.75, 1.0]);
        assert_eq!(floats(&mut ctx, gl::GL_EDGE_FLAG)[0], 1.0);
    }

    #[test]
    fn errors() {
        let (mut ctx, _) = Context::with_recording();
        unsafe { dispatch::glMultiTexCoord4f(&mut ctx, gl::GL_TEXTURE0 + 4, 0.0, 0.0, 0.0, 1.0) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        unsafe { dispatch::glBegin(&mut ctx, gl::GL_POLYGON + 1) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        unsafe { dispatch::glEnd(&mut ctx) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        unsafe {
            dispatch::glBegin(&mut ctx, gl::GL_POINTS);
            dispatch::glBegin(&mut ctx, gl::GL_POINTS);
        }
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "glBegin inside glBegin");
        unsafe { dispatch::glRectf(&mut ctx, 0.0, 0.0, 1.0, 1.0) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "glRect inside glBegin");
        unsafe { dispatch::glEnd(&mut ctx) };
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn begin_end_emits_vertices_with_attributes() {
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            dispatch::glColor3f(&mut ctx, 1.0, 0.0, 0.0);
            dispatch::glBegin(&mut ctx, gl::GL_TRIANGLES);
            dispatch::glVertex2f(&mut ctx, 0.0, 0.0);
            dispatch::glVertex2f(&mut ctx, 1.0, 0.0);
            dispatch::glColor3f(&mut ctx, 0.0, 1.0, 0.0);
            dispatch::glVertex3f(&mut ctx, 1.0, 1.0, 2.0);
            dispatch::glVertex2f(&mut ctx, 9.0, 9.0);
            dispatch::glEnd(&mut ctx);
        }
        let draw = &ctx.frame.draws[0];
        assert_eq!(draw.topology, Topology::Triangles);
        assert_eq!(draw.indices, vec![0, 1, 2]);
        assert_eq!(draw.vertices.position[2], [1.0, 1.0, 2.0, 1.0]);
        assert_eq!(draw.vertices.color.get(1), Some([1.0, 0.0, 0.0, 1.0]));
        assert_eq!(draw.vertices.color.get(2), Some([0.0, 1.0, 0.0, 1.0]));
        assert!(draw.vertices.normal.is_constant(), "an unchanged normal is stored once");
    }

    #[test]
    fn only_changing_attributes_are_stored_per_vertex() {
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            dispatch::glBegin(&mut ctx, gl::GL_POINTS);
            dispatch::glColor3f(&mut ctx, 0.5, 0.5, 0.5);
            dispatch::glVertex2f(&mut ctx, 0.0, 0.0);
            dispatch::glColor3f(&mut ctx, 0.5, 0.5, 0.5);
            dispatch::glVertex2f(&mut ctx, 1.0, 0.0);
            dispatch::glMultiTexCoord1f(&mut ctx, gl::GL_TEXTURE3, 7.0);
            dispatch::glEdgeFlag(&mut ctx, 0);
            dispatch::glVertex2f(&mut ctx, 2.0, 0.0);
            dispatch::glVertex2f(&mut ctx, 3.0, 0.0);
            dispatch::glEnd(&mut ctx);
        }
        let v = &ctx.frame.draws[0].vertices;
        assert_eq!(v.color.values, vec![[0.5, 0.5, 0.5, 1.0]], "setting an equal colour keeps it shared");
        assert_eq!(v.texcoords[3].values.len(), 4);
        assert_eq!(v.texcoords[3].get(1), Some([0.0, 0.0, 0.0, 1.0]));
        assert_eq!(v.texcoords[3].get(3), Some([7.0, 0.0, 0.0, 1.0]));
        assert!(v.texcoords[0].is_constant());
        assert_eq!(ctx.immediate.batch.edge_flags.values, vec![true, true, false, false]);
    }

    #[test]
    fn a_vertex_with_every_bit_changed_stores_only_what_differs() {
        use super::{Batch, CurrentAttribs, bits};
        let mut batch = Batch::default();
        let mut c = CurrentAttribs::default();
        batch.push([0.0, 0.0, 0.0, 1.0], &c, bits::ALL);
        c.texcoords[3] = [5.0, 0.0, 0.0, 1.0];
        c.fog_coord = 2.0;
        // `bits::ALL` also has bits past the last texture unit: they name nothing.
        batch.push([1.0, 0.0, 0.0, 1.0], &c, bits::ALL);
        batch.push([2.0, 0.0, 0.0, 1.0], &c, 0);
        let v = &batch.vertices;
        assert_eq!(v.texcoords[3].values, vec![[0.0, 0.0, 0.0, 1.0], [5.0, 0.0, 0.0, 1.0], [5.0, 0.0, 0.0, 1.0]]);
        assert_eq!(v.fog_coord.values, vec![0.0, 2.0, 2.0]);
        assert!(v.color.is_constant() && v.normal.is_constant() && v.texcoords[0].is_constant());
    }

    #[test]
    fn incomplete_primitives_draw_nothing_and_lists_are_the_source() {
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            dispatch::glBegin(&mut ctx, gl::GL_TRIANGLES);
            dispatch::glVertex2f(&mut ctx, 0.0, 0.0);
            dispatch::glVertex2f(&mut ctx, 1.0, 0.0);
            dispatch::glEnd(&mut ctx);
        }
        assert!(ctx.frame.draws.is_empty());
        unsafe {
            dispatch::glNewList(&mut ctx, 4, gl::GL_COMPILE_AND_EXECUTE);
            dispatch::glRectf(&mut ctx, 0.0, 0.0, 1.0, 1.0);
            dispatch::glEndList(&mut ctx);
            dispatch::glCallList(&mut ctx, 4);
        }
        let sources: Vec<_> = ctx.frame.draws.iter().map(|d| d.source).collect();
        assert_eq!(sources, vec![crate::frame::DrawSource::Immediate, crate::frame::DrawSource::List(4)]);
    }

    #[test]
    fn rect_is_a_polygon() {
        let (mut ctx, _) = Context::with_recording();
        unsafe { dispatch::glRecti(&mut ctx, 1, 2, 3, 4) };
        let draw = &ctx.frame.draws[0];
        assert_eq!(
            draw.vertices.position,
            vec![[1.0, 2.0, 0.0, 1.0], [3.0, 2.0, 0.0, 1.0], [3.0, 4.0, 0.0, 1.0], [1.0, 4.0, 0.0, 1.0]]
        );
        assert_eq!(draw.indices, vec![1, 2, 0, 2, 3, 0]);
        assert_eq!(draw.edge_masks, vec![0b101, 0b011]);
    }
}
