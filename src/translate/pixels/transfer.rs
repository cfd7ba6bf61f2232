//! Pixel transfer (OpenGL 1.5 section 3.6.3 and 3.6.5): `glPixelTransfer` scale, bias, shift,
//! offset and map switches, the pixel maps of `glPixelMap`, and their application to unpacked
//! (and packed) pixel groups.

use super::super::Context;
use super::super::gl::{self, GLenum, GLfloat, GLint, GLsizei, GLuint, GLushort};
use super::super::limits::MAX_PIXEL_MAP_TABLE;
use super::codec::{Format, Kind, to_rgba};

/// The ten pixel maps, in the order of `GL_PIXEL_MAP_I_TO_I` ... `GL_PIXEL_MAP_A_TO_A`.
const MAPS: [GLenum; 10] = [
    gl::GL_PIXEL_MAP_I_TO_I,
    gl::GL_PIXEL_MAP_S_TO_S,
    gl::GL_PIXEL_MAP_I_TO_R,
    gl::GL_PIXEL_MAP_I_TO_G,
    gl::GL_PIXEL_MAP_I_TO_B,
    gl::GL_PIXEL_MAP_I_TO_A,
    gl::GL_PIXEL_MAP_R_TO_R,
    gl::GL_PIXEL_MAP_G_TO_G,
    gl::GL_PIXEL_MAP_B_TO_B,
    gl::GL_PIXEL_MAP_A_TO_A,
];
const I_TO_I: usize = 0;
const S_TO_S: usize = 1;
const I_TO_RGBA: usize = 2;
const C_TO_C: usize = 6;

/// Index of a map enum in [`MAPS`], and whether it maps from an index (its size must be a
/// power of two).
fn map_index(map: GLenum) -> Option<(usize, bool)> {
    let i = MAPS.iter().position(|&m| m == map)?;
    Some((i, i < C_TO_C))
}

/// Index of a `*_SIZE` enum.
fn map_size_index(pname: GLenum) -> Option<usize> {
    map_index(pname.checked_sub(gl::GL_PIXEL_MAP_I_TO_I_SIZE - gl::GL_PIXEL_MAP_I_TO_I)?).map(|(i, _)| i)
}

/// Pixel transfer state (`GL_PIXEL_MODE_BIT`, with the zoom kept beside it).
#[derive(Clone, Debug, PartialEq)]
pub struct PixelTransfer {
    /// `GL_MAP_COLOR`.
    pub map_color: bool,
    /// `GL_MAP_STENCIL`.
    pub map_stencil: bool,
    /// `GL_INDEX_SHIFT`.
    pub index_shift: i32,
    /// `GL_INDEX_OFFSET`.
    pub index_offset: i32,
    /// `GL_RED_SCALE` ... `GL_ALPHA_SCALE`.
    pub scale: [f32; 4],
    /// `GL_RED_BIAS` ... `GL_ALPHA_BIAS`.
    pub bias: [f32; 4],
    /// `GL_DEPTH_SCALE`, `GL_DEPTH_BIAS`.
    pub depth: [f32; 2],
    /// The pixel maps; each has at least one entry.
    pub maps: [Vec<f32>; 10],
}

impl Default for PixelTransfer {
    fn default() -> PixelTransfer {
        PixelTransfer {
            map_color: false,
            map_stencil: false,
            index_shift: 0,
            index_offset: 0,
            scale: [1.0; 4],
            bias: [0.0; 4],
            depth: [1.0, 0.0],
            maps: std::array::from_fn(|_| vec![0.0]),
        }
    }
}

/// Pixels after unpacking and pixel transfer.
#[derive(Clone, Debug, PartialEq)]
pub enum Unpacked {
    /// RGBA colours, clamped to [0, 1] unless unpacked for an unclamped texture.
    Rgba(Vec<[f32; 4]>),
    /// Integer RGBA components (EXT_texture_integer): expanded to RGBA with 0 and 1, no pixel
    /// transfer.
    Integer(Vec<[i64; 4]>),
    /// Colour indices (kept as indices for colour-index textures and palettes).
    Index(Vec<i64>),
    /// Depth values clamped to [0, 1].
    Depth(Vec<f32>),
    /// Stencil indices.
    Stencil(Vec<i64>),
    /// Depth/stencil groups (EXT_packed_depth_stencil): depth values clamped to [0, 1] and
    /// stencil indices, one of each per pixel.
    DepthStencil(Vec<f32>, Vec<i64>),
}

impl PixelTransfer {
    /// Looks `v` up in a colour map (`[0, 1]` scaled to the map size).
    fn lookup_color(&self, map: usize, v: f32) -> f32 {
        let m = &self.maps[map];
        let i = (v.clamp(0.0, 1.0) * (m.len() - 1) as f32).round() as usize;
        m.get(i).copied().unwrap_or(0.0)
    }

    /// Looks an index up in an index map (masked by the size − 1, a power of two).
    fn lookup_index(&self, map: usize, index: i64) -> f32 {
        let m = &self.maps[map];
        let i = (index & (m.len() as i64 - 1)) as usize;
        m.get(i).copied().unwrap_or(0.0)
    }

    /// Index shift and offset (section 3.6.5, "Arithmetic on Indices").
    fn shift_index(&self, index: f64) -> i64 {
        let i = index as i64;
        let shifted = if self.index_shift >= 0 {
            i.checked_shl(self.index_shift.unsigned_abs().min(63)).unwrap_or(0)
        } else {
            i >> self.index_shift.unsigned_abs().min(63)
        };
        shifted.wrapping_add(i64::from(self.index_offset))
    }

    /// RGBA scale, bias and colour maps, clamped to [0, 1] when `clamp` (sections 3.6.5 and
    /// 4.3.2; OpenGL 3.0 section 3.7.5 leaves the values of floating-point and
    /// signed-normalized textures unclamped).
    pub fn color(&self, c: [f32; 4], clamp: bool) -> [f32; 4] {
        let mut out = [0.0; 4];
        for i in 0..4 {
            let v = c[i] * self.scale[i] + self.bias[i];
            let v = if self.map_color { self.lookup_color(C_TO_C + i, v) } else { v };
            out[i] = if clamp { v.clamp(0.0, 1.0) } else { v };
        }
        out
    }

    /// Converts an index to RGBA through the `I_TO_*` maps.
    pub fn index_to_rgba(&self, index: i64) -> [f32; 4] {
        [0, 1, 2, 3].map(|i| self.lookup_index(I_TO_RGBA + i, index).clamp(0.0, 1.0))
    }

    /// Applies pixel transfer to groups decoded from `format`. Colour indices become RGBA
    /// unless `keep_index` (colour-index textures and palettes keep them); colours are clamped
    /// to [0, 1] when `clamp` (see [`PixelTransfer::color`]).
    pub fn apply(&self, format: Format, groups: &[f64], keep_index: bool, clamp: bool) -> Unpacked {
        let n = format.components;
        let narrow = |g: &[f64]| {
            let mut c = [0.0f32; 4];
            c.iter_mut().zip(g).for_each(|(c, &v)| *c = v as f32);
            c
        };
        match format.kind {
            // "None of the operations defined in this section affect integer RGBA component
            // pixel groups" (EXT_texture_integer, section 3.6.5).
            Kind::Integer => Unpacked::Integer(groups.chunks_exact(n).map(|g| to_rgba(format.gl, &g.iter().map(|&v| v as i64).collect::<Vec<_>>())).collect()),
            Kind::Color => Unpacked::Rgba(groups.chunks_exact(n).map(|g| self.color(to_rgba(format.gl, &narrow(g)[..n.min(4)]), clamp)).collect()),
            Kind::Index => {
                let shifted = groups.iter().map(|&i| self.shift_index(i));
                if keep_index {
                    Unpacked::Index(shifted.map(|i| if self.map_color { self.lookup_index(I_TO_I, i) as i64 } else { i }).collect())
                } else {
                    Unpacked::Rgba(shifted.map(|i| self.index_to_rgba(i)).collect())
                }
            }
            Kind::Depth => Unpacked::Depth(groups.iter().map(|&d| self.depth_value(d)).collect()),
            Kind::Stencil => Unpacked::Stencil(groups.iter().map(|&s| self.stencil_index(s)).collect()),
            // Depth/stencil groups: depth arithmetic on the depth, index arithmetic and the
            // S_TO_S map on the stencil index (EXT_packed_depth_stencil, section 3.6.5).
            Kind::DepthStencil => {
                let pairs = groups.chunks_exact(2);
                Unpacked::DepthStencil(pairs.clone().map(|g| self.depth_value(g[0])).collect(), pairs.map(|g| self.stencil_index(g[1])).collect())
            }
        }
    }

    /// A depth component after scale and bias, clamped to [0, 1] (sections 3.6.5 and 3.8.1).
    fn depth_value(&self, d: f64) -> f32 {
        (d as f32 * self.depth[0] + self.depth[1]).clamp(0.0, 1.0)
    }

    /// A stencil index after shift, offset and, with `GL_MAP_STENCIL`, the `S_TO_S` map.
    fn stencil_index(&self, s: f64) -> i64 {
        let s = self.shift_index(s);
        if self.map_stencil { self.lookup_index(S_TO_S, s) as i64 } else { s }
    }
}

/// `(is_scale, component)` of a `GL_*_SCALE`/`GL_*_BIAS` name.
fn scale_bias_of(pname: GLenum) -> Option<(bool, usize)> {
    Some(match pname {
        gl::GL_RED_SCALE => (true, 0),
        gl::GL_GREEN_SCALE => (true, 1),
        gl::GL_BLUE_SCALE => (true, 2),
        gl::GL_ALPHA_SCALE => (true, 3),
        gl::GL_RED_BIAS => (false, 0),
        gl::GL_GREEN_BIAS => (false, 1),
        gl::GL_BLUE_BIAS => (false, 2),
        gl::GL_ALPHA_BIAS => (false, 3),
        _ => return None,
    })
}

/// The size of a `glPixelMap` call's table when it is in range (for display lists; the checks
/// and errors happen when the recorded command runs).
fn map_len(mapsize: GLsizei) -> Option<usize> {
    usize::try_from(mapsize).ok().filter(|&n| (1..=MAX_PIXEL_MAP_TABLE).contains(&n))
}

/// A value type of `glPixelMap`/`glGetPixelMap`: how it converts to and from a map entry and
/// its bytes in memory.
pub trait MapValue: Copy + Send + Sync + 'static {
    /// Entry of a map from the client value; colour maps normalize integers (table 2.9).
    fn to_entry(self, color: bool) -> f32;
    /// Client value of an entry; colour entries of integer types scale to the type's range.
    fn from_entry(entry: f32, color: bool) -> Self;
    /// The value of `size_of::<Self>()` native-endian bytes.
    fn read_ne(bytes: &[u8]) -> Self;
    /// Writes the value's native-endian bytes to `out` (`size_of::<Self>()` bytes).
    fn write_ne(self, out: &mut [u8]);
}

/// [`MapValue`]'s byte conversions for a primitive number type.
macro_rules! native_bytes {
    () => {
        fn read_ne(bytes: &[u8]) -> Self {
            Self::from_ne_bytes(bytes.try_into().unwrap_or_default())
        }
        fn write_ne(self, out: &mut [u8]) {
            out.copy_from_slice(&self.to_ne_bytes())
        }
    };
}

impl MapValue for GLfloat {
    native_bytes!();
    fn to_entry(self, _: bool) -> f32 {
        self
    }
    fn from_entry(entry: f32, _: bool) -> f32 {
        entry
    }
}
impl MapValue for GLuint {
    native_bytes!();
    fn to_entry(self, color: bool) -> f32 {
        if color { super::super::convert::norm_u32(self) } else { self as f32 }
    }
    fn from_entry(entry: f32, color: bool) -> u32 {
        if color { (f64::from(entry) * 4294967295.0).round() as u32 } else { entry as i64 as u32 }
    }
}
impl MapValue for GLushort {
    native_bytes!();
    fn to_entry(self, color: bool) -> f32 {
        if color { super::super::convert::norm_u16(self) } else { f32::from(self) }
    }
    fn from_entry(entry: f32, color: bool) -> u16 {
        if color { (entry * 65535.0).round() as u16 } else { entry as i64 as u16 }
    }
}

impl Context {
    /// `glPixelTransferf`: `GL_INVALID_ENUM` for an unknown name.
    pub fn glPixelTransferf(&mut self, pname: GLenum, param: GLfloat) {
        let t = &mut self.pixels.transfer;
        match pname {
            gl::GL_MAP_COLOR => t.map_color = param != 0.0,
            gl::GL_MAP_STENCIL => t.map_stencil = param != 0.0,
            gl::GL_INDEX_SHIFT => t.index_shift = param.round() as i32,
            gl::GL_INDEX_OFFSET => t.index_offset = param.round() as i32,
            gl::GL_DEPTH_SCALE => t.depth[0] = param,
            gl::GL_DEPTH_BIAS => t.depth[1] = param,
            _ => match scale_bias_of(pname) {
                Some((true, i)) => t.scale[i] = param,
                Some((false, i)) => t.bias[i] = param,
                None => self.set_error_in(gl::GL_INVALID_ENUM, "glPixelTransfer"),
            },
        }
    }

    /// `glPixelTransferi`.
    pub fn glPixelTransferi(&mut self, pname: GLenum, param: GLint) {
        self.glPixelTransferf(pname, param as GLfloat);
    }

    /// `glPixelMap*v` after the checks of section 3.6.3: `GL_INVALID_ENUM` for an unknown
    /// map, `GL_INVALID_VALUE` for a size out of [1, `GL_MAX_PIXEL_MAP_TABLE`] or, for maps
    /// from indices, not a power of two. The values come from client memory or the unpack
    /// buffer ([`Context::unpack_bytes`]). Colour entries are clamped to [0, 1].
    unsafe fn pixel_map<T: MapValue>(&mut self, map: GLenum, mapsize: GLsizei, values: *const T, command: &'static str) {
        let Some((i, from_index)) = map_index(map) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        let Some(n) = map_len(mapsize) else { return self.set_error_in(gl::GL_INVALID_VALUE, command) };
        if from_index && !n.is_power_of_two() {
            return self.set_error_in(gl::GL_INVALID_VALUE, command);
        }
        let size = size_of::<T>();
        let Ok(bytes) = (unsafe { self.unpack_bytes(values.cast(), n * size, size, command) }) else { return };
        let Some(bytes) = bytes else { return self.null_pointer(command) };
        let color = i >= I_TO_RGBA;
        self.pixels.transfer.maps[i] = bytes.chunks_exact(size).map(|b| {
            let e = T::read_ne(b).to_entry(color);
            if color { e.clamp(0.0, 1.0) } else { e }
        }).collect();
    }

    /// Records a `glPixelMap*v` with a copy of its values ([`Context::compile_unpack`]).
    unsafe fn compile_pixel_map<T: MapValue>(&mut self, map: GLenum, mapsize: GLsizei, values: *const T, command: &'static str, run: unsafe fn(&mut Context, GLenum, GLsizei, *const T)) {
        let size = map_len(mapsize).map(|n| (n * size_of::<T>(), size_of::<T>()));
        unsafe { self.compile_unpack(values.cast(), size, command, move |ctx, p| run(ctx, map, mapsize, p.cast())) }
    }

    /// `glPixelMapfv`.
    ///
    /// # Safety
    /// `values` must point to `mapsize` values.
    pub unsafe fn glPixelMapfv(&mut self, map: GLenum, mapsize: GLsizei, values: *const GLfloat) {
        unsafe { self.pixel_map(map, mapsize, values, "glPixelMapfv") }
    }
    /// `glPixelMapuiv`: colour values are normalized (table 2.9).
    ///
    /// # Safety
    /// `values` must point to `mapsize` values.
    pub unsafe fn glPixelMapuiv(&mut self, map: GLenum, mapsize: GLsizei, values: *const GLuint) {
        unsafe { self.pixel_map(map, mapsize, values, "glPixelMapuiv") }
    }
    /// `glPixelMapusv`: colour values are normalized (table 2.9).
    ///
    /// # Safety
    /// `values` must point to `mapsize` values.
    pub unsafe fn glPixelMapusv(&mut self, map: GLenum, mapsize: GLsizei, values: *const GLushort) {
        unsafe { self.pixel_map(map, mapsize, values, "glPixelMapusv") }
    }
    /// `glPixelMapfv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glPixelMapfv`].
    pub unsafe fn compile_glPixelMapfv(&mut self, map: GLenum, mapsize: GLsizei, values: *const GLfloat) {
        unsafe { self.compile_pixel_map(map, mapsize, values, "glPixelMapfv", super::super::dispatch::exec_glPixelMapfv) }
    }
    /// `glPixelMapuiv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glPixelMapuiv`].
    pub unsafe fn compile_glPixelMapuiv(&mut self, map: GLenum, mapsize: GLsizei, values: *const GLuint) {
        unsafe { self.compile_pixel_map(map, mapsize, values, "glPixelMapuiv", super::super::dispatch::exec_glPixelMapuiv) }
    }
    /// `glPixelMapusv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glPixelMapusv`].
    pub unsafe fn compile_glPixelMapusv(&mut self, map: GLenum, mapsize: GLsizei, values: *const GLushort) {
        unsafe { self.compile_pixel_map(map, mapsize, values, "glPixelMapusv", super::super::dispatch::exec_glPixelMapusv) }
    }

    /// `glGetPixelMap*v`: `GL_INVALID_ENUM` for an unknown map; the values go to client
    /// memory or the pack buffer ([`Context::pack_bytes`]).
    unsafe fn get_pixel_map<T: MapValue>(&mut self, map: GLenum, values: *mut T, command: &'static str) {
        let Some((i, _)) = map_index(map) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        let color = i >= I_TO_RGBA;
        let out: Vec<T> = self.pixels.transfer.maps[i].iter().map(|&e| T::from_entry(e, color)).collect();
        let size = size_of::<T>();
        let write = |bytes: &mut [u8]| out.iter().zip(bytes.chunks_exact_mut(size)).for_each(|(v, b)| v.write_ne(b));
        unsafe { self.pack_bytes(values.cast(), out.len() * size, size, command, write) }
    }

    /// `glGetPixelMapfv`.
    ///
    /// # Safety
    /// `values` must have room for the map's size.
    pub unsafe fn glGetPixelMapfv(&mut self, map: GLenum, values: *mut GLfloat) {
        unsafe { self.get_pixel_map(map, values, "glGetPixelMapfv") }
    }
    /// `glGetPixelMapuiv`.
    ///
    /// # Safety
    /// `values` must have room for the map's size.
    pub unsafe fn glGetPixelMapuiv(&mut self, map: GLenum, values: *mut GLuint) {
        unsafe { self.get_pixel_map(map, values, "glGetPixelMapuiv") }
    }
    /// `glGetPixelMapusv`.
    ///
    /// # Safety
    /// `values` must have room for the map's size.
    pub unsafe fn glGetPixelMapusv(&mut self, map: GLenum, values: *mut GLushort) {
        unsafe { self.get_pixel_map(map, values, "glGetPixelMapusv") }
    }

    /// The pixel transfer values and map sizes for `glGet`.
    pub(crate) fn query_transfer(&self, pname: GLenum) -> Option<super::super::get::Value> {
        use super::super::get::Value;
        let t = &self.pixels.transfer;
        if let Some(i) = map_size_index(pname) {
            return Some(Value::int(t.maps[i].len() as i64));
        }
        if let Some((scale, i)) = scale_bias_of(pname) {
            return Some(Value::float(if scale { t.scale[i] } else { t.bias[i] }));
        }
        Some(match pname {
            gl::GL_MAP_COLOR => Value::bool(t.map_color),
            gl::GL_MAP_STENCIL => Value::bool(t.map_stencil),
            gl::GL_INDEX_SHIFT => Value::int(t.index_shift),
            gl::GL_INDEX_OFFSET => Value::int(t.index_offset),
            gl::GL_DEPTH_SCALE => Value::float(t.depth[0]),
            gl::GL_DEPTH_BIAS => Value::float(t.depth[1]),
            gl::GL_MAX_PIXEL_MAP_TABLE => Value::int(MAX_PIXEL_MAP_TABLE as i64),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::translate::pixels::codec;

    #[test]
    fn maps_check_sizes_and_round_trip() {
        let (mut ctx, _) = Context::with_recording();
        let three = [0.0f32, 0.5, 1.0];
        unsafe { ctx.glPixelMapfv(gl::GL_PIXEL_MAP_I_TO_R, 3, three.as_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        unsafe { ctx.glPixelMapfv(gl::GL_PIXEL_MAP_R_TO_R, 3, three.as_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        unsafe { ctx.glPixelMapfv(gl::GL_TEXTURE_2D, 1, three.as_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        let mut back = [0u16; 3];
        unsafe { ctx.glGetPixelMapusv(gl::GL_PIXEL_MAP_R_TO_R, back.as_mut_ptr()) };
        assert_eq!(back, [0, 32768, 65535]);
        assert_eq!(ctx.query_transfer(gl::GL_PIXEL_MAP_R_TO_R_SIZE), Some(super::super::super::get::Value::int(3)));
        let idx = [7u32, 9];
        unsafe { ctx.glPixelMapuiv(gl::GL_PIXEL_MAP_I_TO_I, 2, idx.as_ptr()) };
        let mut f = [0.0f32; 2];
        unsafe { ctx.glGetPixelMapfv(gl::GL_PIXEL_MAP_I_TO_I, f.as_mut_ptr()) };
        assert_eq!(f, [7.0, 9.0]);
    }

    #[test]
    fn transfer_scales_biases_and_maps() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glPixelTransferf(gl::GL_RED_SCALE, 0.5);
        ctx.glPixelTransferf(gl::GL_BLUE_BIAS, 0.25);
        ctx.glPixelTransferi(gl::GL_INDEX_SHIFT, 1);
        ctx.glPixelTransferi(gl::GL_INDEX_OFFSET, 1);
        let rgba = codec::format(gl::GL_RGBA).unwrap();
        assert_eq!(ctx.pixels.transfer.apply(rgba, &[1.0, 1.0, 0.5, 1.0], false, true), Unpacked::Rgba(vec![[0.5, 1.0, 0.75, 1.0]]));
        let index = codec::format(gl::GL_COLOR_INDEX).unwrap();
        assert_eq!(ctx.pixels.transfer.apply(index, &[3.0], true, true), Unpacked::Index(vec![7]));
        let ramp = [0.0f32, 0.25, 0.5, 1.0, 0.0, 0.0, 0.0, 1.0];
        unsafe { ctx.glPixelMapfv(gl::GL_PIXEL_MAP_I_TO_R, 8, ramp.as_ptr()) };
        assert_eq!(ctx.pixels.transfer.apply(index, &[1.0], false, true), Unpacked::Rgba(vec![[1.0, 0.0, 0.0, 0.0]]));
        ctx.glPixelTransferf(gl::GL_MAP_COLOR, 1.0);
        let two = [1.0f32, 0.0];
        unsafe { ctx.glPixelMapfv(gl::GL_PIXEL_MAP_G_TO_G, 2, two.as_ptr()) };
        // Green 1.0 maps to the last entry (0.0).
        assert_eq!(ctx.pixels.transfer.color([0.0, 1.0, 0.0, 0.0], true)[1], 0.0);
        ctx.glPixelTransferf(gl::GL_TEXTURE_2D, 1.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }

    #[test]
    fn depth_stencil_groups_take_depth_and_index_transfer() {
        let (mut ctx, _) = Context::with_recording();
        let ds = codec::format(gl::GL_DEPTH_STENCIL).unwrap();
        assert_eq!(ctx.pixels.transfer.apply(ds, &[0.25, 3.0, 1.0, 255.0], false, true), Unpacked::DepthStencil(vec![0.25, 1.0], vec![3, 255]));
        ctx.glPixelTransferf(gl::GL_DEPTH_SCALE, 2.0);
        ctx.glPixelTransferf(gl::GL_DEPTH_BIAS, 0.125);
        ctx.glPixelTransferi(gl::GL_INDEX_SHIFT, 2);
        ctx.glPixelTransferi(gl::GL_INDEX_OFFSET, 1);
        // 0.25 × 2 + 0.125 and 1.0 × 2 + 0.125 (clamped); 3 << 2 + 1 and 255 << 2 + 1.
        assert_eq!(ctx.pixels.transfer.apply(ds, &[0.25, 3.0, 1.0, 255.0], false, true), Unpacked::DepthStencil(vec![0.625, 1.0], vec![13, 1021]));
        let map = [5.0f32, 6.0, 7.0, 8.0];
        unsafe { ctx.glPixelMapfv(gl::GL_PIXEL_MAP_S_TO_S, 4, map.as_ptr()) };
        ctx.glPixelTransferi(gl::GL_MAP_STENCIL, 1);
        // 13 & 3 = 1 → 6; 1021 & 3 = 1 → 6.
        assert_eq!(ctx.pixels.transfer.apply(ds, &[0.25, 3.0, 1.0, 255.0], false, true), Unpacked::DepthStencil(vec![0.625, 1.0], vec![6, 6]));
    }
}
