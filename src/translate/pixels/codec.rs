//! Client pixel formats and types (OpenGL 1.5 tables 3.5, 3.6 and 3.8, with the
//! `GL_DEPTH_STENCIL` format and its two packed types of EXT_packed_depth_stencil and
//! ARB_depth_buffer_float, the `GL_RG` format of ARB_texture_rg and the packed float types of
//! EXT_packed_float and EXT_texture_shared_exponent, the `*_INTEGER` formats of
//! EXT_texture_integer (with ARB_texture_rg's `GL_RG_INTEGER`)): parsing and checking `format`/`type` pairs, and decoding or encoding
//! pixel groups in client memory laid out as [`Layout`] says, with byte swapping and bit order.

use super::super::convert::{norm_i8, norm_i16, norm_i32, norm_u8, norm_u16, norm_u32};
use super::super::gl::{self, GLenum};
use super::small_float;
use super::store::{Layout, StoreModes};

/// What a format's values mean.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Colour components (normalized).
    Color,
    /// Integer colour components (EXT_texture_integer's `*_INTEGER` formats): not normalized,
    /// no pixel transfer.
    Integer,
    /// Colour indices (integers).
    Index,
    /// Stencil indices (integers).
    Stencil,
    /// Depth values (normalized).
    Depth,
    /// A depth value (normalized) and a stencil index (integer) per group
    /// (EXT_packed_depth_stencil's depth/stencil groups).
    DepthStencil,
}

/// A client pixel format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Format {
    /// The GL enum.
    pub gl: GLenum,
    /// Elements per group.
    pub components: usize,
    /// Meaning of the elements.
    pub kind: Kind,
}

/// A packed pixel type (table 3.8): the bit fields of components 0..n, most significant
/// first for the plain types, least significant first for the `_REV` types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Packed {
    /// Bytes of one packed pixel.
    pub size: usize,
    /// (shift, bits) of each component in format order.
    pub fields: &'static [(u32, u32)],
}

/// A client pixel type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Type {
    /// `GL_UNSIGNED_BYTE`.
    U8,
    /// `GL_BYTE`.
    I8,
    /// `GL_UNSIGNED_SHORT`.
    U16,
    /// `GL_SHORT`.
    I16,
    /// `GL_UNSIGNED_INT`.
    U32,
    /// `GL_INT`.
    I32,
    /// `GL_FLOAT`.
    F32,
    /// `GL_BITMAP`: one bit a pixel.
    Bitmap,
    /// A packed type.
    Packed(Packed),
    /// `GL_UNSIGNED_INT_24_8`: one `uint` a group, depth in bits 31–8 (24-bit unsigned
    /// normalized), stencil index in bits 7–0 (EXT_packed_depth_stencil table 3.11).
    Uint24_8,
    /// `GL_FLOAT_32_UNSIGNED_INT_24_8_REV`: two 32-bit words a group, the depth as a `float`
    /// in the first, the stencil index in bits 7–0 of the second (bits 31–8 unused;
    /// ARB_depth_buffer_float table 3.11).
    Float32Uint24_8Rev,
    /// `GL_UNSIGNED_INT_10F_11F_11F_REV`: one `uint` an RGB group, red an unsigned 11-bit
    /// float in bits 10–0, green one in bits 21–11, blue a 10-bit one in bits 31–22
    /// (EXT_packed_float).
    Uint10F11F11FRev,
    /// `GL_UNSIGNED_INT_5_9_9_9_REV`: one `uint` an RGB group, 9-bit mantissas of red, green
    /// and blue from bit 0 up, the shared 5-bit exponent in bits 31–27
    /// (EXT_texture_shared_exponent).
    Uint5999Rev,
}

const P332: &[(u32, u32)] = &[(5, 3), (2, 3), (0, 2)];
const P233R: &[(u32, u32)] = &[(0, 3), (3, 3), (6, 2)];
const P565: &[(u32, u32)] = &[(11, 5), (5, 6), (0, 5)];
const P565R: &[(u32, u32)] = &[(0, 5), (5, 6), (11, 5)];
const P4444: &[(u32, u32)] = &[(12, 4), (8, 4), (4, 4), (0, 4)];
const P4444R: &[(u32, u32)] = &[(0, 4), (4, 4), (8, 4), (12, 4)];
const P5551: &[(u32, u32)] = &[(11, 5), (6, 5), (1, 5), (0, 1)];
const P1555R: &[(u32, u32)] = &[(0, 5), (5, 5), (10, 5), (15, 1)];
const P8888: &[(u32, u32)] = &[(24, 8), (16, 8), (8, 8), (0, 8)];
const P8888R: &[(u32, u32)] = &[(0, 8), (8, 8), (16, 8), (24, 8)];
const P1010102: &[(u32, u32)] = &[(22, 10), (12, 10), (2, 10), (0, 2)];
const P2101010R: &[(u32, u32)] = &[(0, 10), (10, 10), (20, 10), (30, 2)];

/// The format `format`, if it is one of table 3.5.
pub fn format(format: GLenum) -> Option<Format> {
    let (components, kind) = match format {
        gl::GL_COLOR_INDEX => (1, Kind::Index),
        gl::GL_STENCIL_INDEX => (1, Kind::Stencil),
        gl::GL_DEPTH_COMPONENT => (1, Kind::Depth),
        gl::GL_DEPTH_STENCIL => (2, Kind::DepthStencil),
        gl::GL_RED | gl::GL_GREEN | gl::GL_BLUE | gl::GL_ALPHA | gl::GL_LUMINANCE => (1, Kind::Color),
        gl::GL_LUMINANCE_ALPHA | gl::GL_RG => (2, Kind::Color),
        gl::GL_RGB | gl::GL_BGR => (3, Kind::Color),
        gl::GL_RGBA | gl::GL_BGRA | gl::GL_ABGR_EXT => (4, Kind::Color),
        gl::GL_RED_INTEGER | gl::GL_GREEN_INTEGER | gl::GL_BLUE_INTEGER | gl::GL_ALPHA_INTEGER | gl::GL_LUMINANCE_INTEGER_EXT => (1, Kind::Integer),
        gl::GL_LUMINANCE_ALPHA_INTEGER_EXT | gl::GL_RG_INTEGER => (2, Kind::Integer),
        gl::GL_RGB_INTEGER | gl::GL_BGR_INTEGER => (3, Kind::Integer),
        gl::GL_RGBA_INTEGER | gl::GL_BGRA_INTEGER => (4, Kind::Integer),
        _ => return None,
    };
    Some(Format { gl: format, components, kind })
}

/// The type `type_`, if it is one of tables 3.6 and 3.8.
pub fn pixel_type(type_: GLenum) -> Option<Type> {
    let packed = |size, fields| Some(Type::Packed(Packed { size, fields }));
    match type_ {
        gl::GL_UNSIGNED_BYTE => Some(Type::U8),
        gl::GL_BYTE => Some(Type::I8),
        gl::GL_UNSIGNED_SHORT => Some(Type::U16),
        gl::GL_SHORT => Some(Type::I16),
        gl::GL_UNSIGNED_INT => Some(Type::U32),
        gl::GL_INT => Some(Type::I32),
        gl::GL_FLOAT => Some(Type::F32),
        gl::GL_BITMAP => Some(Type::Bitmap),
        gl::GL_UNSIGNED_BYTE_3_3_2 => packed(1, P332),
        gl::GL_UNSIGNED_BYTE_2_3_3_REV => packed(1, P233R),
        gl::GL_UNSIGNED_SHORT_5_6_5 => packed(2, P565),
        gl::GL_UNSIGNED_SHORT_5_6_5_REV => packed(2, P565R),
        gl::GL_UNSIGNED_SHORT_4_4_4_4 => packed(2, P4444),
        gl::GL_UNSIGNED_SHORT_4_4_4_4_REV => packed(2, P4444R),
        gl::GL_UNSIGNED_SHORT_5_5_5_1 => packed(2, P5551),
        gl::GL_UNSIGNED_SHORT_1_5_5_5_REV => packed(2, P1555R),
        gl::GL_UNSIGNED_INT_8_8_8_8 => packed(4, P8888),
        gl::GL_UNSIGNED_INT_8_8_8_8_REV => packed(4, P8888R),
        gl::GL_UNSIGNED_INT_10_10_10_2 => packed(4, P1010102),
        gl::GL_UNSIGNED_INT_2_10_10_10_REV => packed(4, P2101010R),
        gl::GL_UNSIGNED_INT_24_8 => Some(Type::Uint24_8),
        gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV => Some(Type::Float32Uint24_8Rev),
        gl::GL_UNSIGNED_INT_10F_11F_11F_REV => Some(Type::Uint10F11F11FRev),
        gl::GL_UNSIGNED_INT_5_9_9_9_REV => Some(Type::Uint5999Rev),
        _ => None,
    }
}

/// Parses and checks a `format`/`type` pair: `GL_INVALID_ENUM` for unknown values,
/// `GL_BITMAP` with a format other than an index, or `GL_DEPTH_STENCIL` with a type other than
/// its two packed types; `GL_INVALID_OPERATION` for a packed type whose component count differs
/// from the format's (section 3.6.4), a depth/stencil type with another format
/// (EXT_packed_depth_stencil and ARB_depth_buffer_float, "Errors"), or a packed float type with
/// a format other than `GL_RGB` (EXT_packed_float, EXT_texture_shared_exponent). A packed type
/// with an unknown format meets both conditions; the specification does not order them, and
/// `GL_INVALID_OPERATION` is what Mesa records (piglit's `draw-pixels` expects it). An integer
/// format with `GL_FLOAT` is `GL_INVALID_ENUM` (EXT_texture_integer, "Errors").
pub fn parse(format_: GLenum, type_: GLenum) -> Result<(Format, Type), GLenum> {
    let t = pixel_type(type_);
    let Some(f) = format(format_) else {
        let packed = matches!(t, Some(Type::Packed(_) | Type::Uint10F11F11FRev | Type::Uint5999Rev));
        return Err(if packed { gl::GL_INVALID_OPERATION } else { gl::GL_INVALID_ENUM });
    };
    let Some(t) = t else { return Err(gl::GL_INVALID_ENUM) };
    let depth_stencil_type = matches!(t, Type::Uint24_8 | Type::Float32Uint24_8Rev);
    match t {
        _ if f.kind == Kind::DepthStencil && !depth_stencil_type => Err(gl::GL_INVALID_ENUM),
        _ if depth_stencil_type && f.kind != Kind::DepthStencil => Err(gl::GL_INVALID_OPERATION),
        Type::Bitmap if !matches!(f.kind, Kind::Index | Kind::Stencil) => Err(gl::GL_INVALID_ENUM),
        Type::F32 if f.kind == Kind::Integer => Err(gl::GL_INVALID_ENUM),
        Type::Uint10F11F11FRev | Type::Uint5999Rev if f.gl != gl::GL_RGB => Err(gl::GL_INVALID_OPERATION),
        // Table 3.8: the three-field types match `GL_RGB` only, the four-field ones `GL_RGBA`
        // and `GL_BGRA` (and EXT_abgr's `GL_ABGR_EXT`, which EXT_packed_pixels allows); OpenGL
        // 3.0's table 3.8 adds `GL_RGB_INTEGER`, `GL_RGBA_INTEGER` and `GL_BGRA_INTEGER`, whose
        // fields are unnormalized integers (piglit's `ext_texture_integer-texformats`).
        Type::Packed(p)
            if !(matches!(f.kind, Kind::Color | Kind::Integer)
                && f.components == p.fields.len()
                && !matches!(f.gl, gl::GL_BGR | gl::GL_BGR_INTEGER)
                && f.components >= 3) =>
        {
            Err(gl::GL_INVALID_OPERATION)
        }
        _ => Ok((f, t)),
    }
}

/// Largest 24-bit depth value (1.0 in `GL_UNSIGNED_INT_24_8`).
const DEPTH24_MAX: f64 = 16_777_215.0;

impl Type {
    /// Bytes of one element (0 for bitmaps; the packed size for packed types).
    pub fn element_size(self) -> usize {
        match self {
            Type::U8 | Type::I8 => 1,
            Type::U16 | Type::I16 => 2,
            Type::U32 | Type::I32 | Type::F32 => 4,
            Type::Bitmap => 0,
            Type::Packed(p) => p.size,
            Type::Uint24_8 | Type::Uint10F11F11FRev | Type::Uint5999Rev => 4,
            Type::Float32Uint24_8Rev => 8,
        }
    }

    /// Bytes of the GL data type (table 3.5) that a pixel buffer offset must be a multiple of:
    /// the element size, 1 (`ubyte`) for bitmaps.
    pub fn datum_size(self) -> usize {
        self.element_size().max(1)
    }

    /// Elements per group of `format` (1 for the types that pack a whole group).
    pub fn elements(self, format: Format) -> usize {
        if matches!(self, Type::Packed(_) | Type::Uint24_8 | Type::Float32Uint24_8Rev | Type::Uint10F11F11FRev | Type::Uint5999Rev) { 1 } else { format.components }
    }

    /// The layout of a `w` × `h` × `d` image of `format` with `modes`.
    pub fn layout(self, format: Format, modes: &StoreModes, w: usize, h: usize, d: usize) -> Option<Layout> {
        modes.layout(self.element_size(), self.elements(format), w, h, d)
    }
}

/// Reads one element of `size` bytes at `at`, swapping bytes when asked.
fn read_uint(bytes: &[u8], at: usize, size: usize, swap: bool) -> u32 {
    let mut b = [0u8; 4];
    for (i, slot) in b.iter_mut().take(size).enumerate() {
        *slot = bytes.get(at + i).copied().unwrap_or(0);
    }
    if swap {
        b[..size].reverse();
    }
    match size {
        1 => u32::from(b[0]),
        2 => u32::from(u16::from_ne_bytes([b[0], b[1]])),
        _ => u32::from_ne_bytes(b),
    }
}

fn write_uint(bytes: &mut [u8], at: usize, size: usize, swap: bool, v: u32) {
    let mut b = match size {
        1 => vec![v as u8],
        2 => (v as u16).to_ne_bytes().to_vec(),
        _ => v.to_ne_bytes().to_vec(),
    };
    if swap {
        b.reverse();
    }
    for (i, x) in b.into_iter().enumerate() {
        if let Some(slot) = bytes.get_mut(at + i) {
            *slot = x;
        }
    }
}

/// Decodes element `raw` (as read) of type `t` to a value: normalized (table 2.9) for colour
/// and depth, the integer itself for indices, the float itself for `GL_FLOAT`. The value is an
/// `f64` so that 32-bit indices keep every bit (an `f32` holds 24).
fn decode_element(t: Type, raw: u32, normalized: bool) -> f64 {
    let norm = match (t, normalized) {
        (Type::F32, _) => f32::from_bits(raw),
        (Type::U8, true) => norm_u8(raw as u8),
        (Type::I8, true) => norm_i8(raw as u8 as i8),
        (Type::U16, true) => norm_u16(raw as u16),
        (Type::I16, true) => norm_i16(raw as u16 as i16),
        (Type::U32, true) => norm_u32(raw),
        (Type::I32, true) => norm_i32(raw as i32),
        (Type::I8, false) => return f64::from(raw as u8 as i8),
        (Type::I16, false) => return f64::from(raw as u16 as i16),
        (Type::I32, false) => return f64::from(raw as i32),
        _ => return f64::from(raw),
    };
    f64::from(norm)
}

/// Encodes `v` as element of type `t` (equation 4.1's inverse of table 2.9 for normalized
/// values; integer values are wrapped to the type).
fn encode_element(t: Type, v: f32, normalized: bool) -> u32 {
    let unsigned = |max: f64| (f64::from(v).clamp(0.0, 1.0) * max).round() as u32;
    let signed = |max: f64| ((f64::from(v).clamp(-1.0, 1.0) * max - 1.0) / 2.0).round() as i64 as u32;
    match (t, normalized) {
        (Type::F32, _) => v.to_bits(),
        (Type::U8, true) => unsigned(255.0),
        (Type::U16, true) => unsigned(65535.0),
        (Type::U32, true) => unsigned(4294967295.0),
        (Type::I8, true) => signed(255.0) & 0xff,
        (Type::I16, true) => signed(65535.0) & 0xffff,
        (Type::I32, true) => signed(4294967295.0),
        _ => v as i64 as u32,
    }
}

/// The low 8 bits of a stencil index: what the depth/stencil types keep (EXT_packed_depth_stencil
/// table 4.6, index mask 2^8 − 1).
fn stencil_byte(index: f32) -> u32 {
    (index as i64 & 0xff) as u32
}

/// A group of elements and how to find them in client memory.
pub struct Codec<'a> {
    /// Format of the groups.
    pub format: Format,
    /// Type of the elements.
    pub ty: Type,
    /// Where pixels lie.
    pub layout: Layout,
    /// Storage modes (swap bytes, LSB first).
    pub modes: &'a StoreModes,
}

impl Codec<'_> {
    fn normalized(&self) -> bool {
        matches!(self.format.kind, Kind::Color | Kind::Depth)
    }

    fn bit_position(&self, bit: usize) -> (usize, u32) {
        let shift = if self.modes.lsb_first { bit % 8 } else { 7 - bit % 8 };
        (bit / 8, shift as u32)
    }

    /// Decodes the `w` × `h` × `d` image in `bytes` (the client memory from the pointer on,
    /// [`Layout::span`] bytes): `format.components` values a pixel, in format order (`f64`:
    /// integer indices are exact).
    pub fn decode(&self, bytes: &[u8], w: usize, h: usize, d: usize) -> Vec<f64> {
        let n = self.format.components;
        let mut out = Vec::with_capacity(w * h * d * n);
        let size = self.ty.element_size();
        let swap = self.modes.swap_bytes && size > 1;
        for z in 0..d {
            for y in 0..h {
                for x in 0..w {
                    let at = self.layout.offset(x, y, z);
                    match self.ty {
                        Type::Bitmap => {
                            let (byte, shift) = self.bit_position(at);
                            out.push(f64::from((bytes.get(byte).copied().unwrap_or(0) >> shift) & 1));
                        }
                        Type::Packed(p) => {
                            let raw = read_uint(bytes, at, size, swap);
                            for &(shift, bits) in p.fields {
                                let max = (1u32 << bits) - 1;
                                let field = (raw >> shift) & max;
                                out.push(if self.normalized() { f64::from(field as f32 / max as f32) } else { f64::from(field) });
                            }
                        }
                        Type::Uint24_8 => {
                            let raw = read_uint(bytes, at, 4, swap);
                            out.extend([f64::from(raw >> 8) / DEPTH24_MAX, f64::from(raw & 0xff)]);
                        }
                        Type::Float32Uint24_8Rev => {
                            let depth = f32::from_bits(read_uint(bytes, at, 4, swap));
                            out.extend([f64::from(depth), f64::from(read_uint(bytes, at + 4, 4, swap) & 0xff)]);
                        }
                        Type::Uint10F11F11FRev => {
                            let raw = read_uint(bytes, at, 4, swap);
                            let (r, g, b) = (raw & 0x7ff, (raw >> 11) & 0x7ff, raw >> 22);
                            let rgb = [small_float::from_unsigned_float(r, 6), small_float::from_unsigned_float(g, 6), small_float::from_unsigned_float(b, 5)];
                            out.extend(rgb.map(f64::from));
                        }
                        Type::Uint5999Rev => {
                            let raw = read_uint(bytes, at, 4, swap);
                            let rgb = small_float::from_rgb9e5([raw & 0x1ff, (raw >> 9) & 0x1ff, (raw >> 18) & 0x1ff], raw >> 27);
                            out.extend(rgb.map(f64::from));
                        }
                        t => {
                            for c in 0..n {
                                out.push(decode_element(t, read_uint(bytes, at + c * size, size, swap), self.normalized()));
                            }
                        }
                    }
                }
            }
        }
        out
    }

    /// Encodes `values` (`format.components` a pixel, in format order) into `bytes`, leaving
    /// padding and skipped pixels as they were.
    pub fn encode(&self, bytes: &mut [u8], values: &[f32], w: usize, h: usize, d: usize) {
        let n = self.format.components;
        let size = self.ty.element_size();
        let swap = self.modes.swap_bytes && size > 1;
        let mut groups = values.chunks_exact(n);
        for z in 0..d {
            for y in 0..h {
                for x in 0..w {
                    let Some(g) = groups.next() else { return };
                    let at = self.layout.offset(x, y, z);
                    match self.ty {
                        Type::Bitmap => {
                            let (byte, shift) = self.bit_position(at);
                            if let Some(b) = bytes.get_mut(byte) {
                                let bit = (g[0] as i64 & 1) as u8;
                                *b = (*b & !(1 << shift)) | (bit << shift);
                            }
                        }
                        Type::Packed(p) => {
                            let mut raw = 0u32;
                            for (&(shift, bits), &v) in p.fields.iter().zip(g) {
                                let max = (1u32 << bits) - 1;
                                raw |= ((f64::from(v).clamp(0.0, 1.0) * f64::from(max)).round() as u32) << shift;
                            }
                            write_uint(bytes, at, size, swap, raw);
                        }
                        Type::Uint24_8 => {
                            let depth = (f64::from(g[0]).clamp(0.0, 1.0) * DEPTH24_MAX).round() as u32;
                            write_uint(bytes, at, 4, swap, depth << 8 | stencil_byte(g[1]));
                        }
                        Type::Float32Uint24_8Rev => {
                            write_uint(bytes, at, 4, swap, g[0].to_bits());
                            write_uint(bytes, at + 4, 4, swap, stencil_byte(g[1]));
                        }
                        Type::Uint10F11F11FRev => {
                            let [r, gr, b] = [(g[0], 6), (g[1], 6), (g[2], 5)].map(|(v, man)| small_float::to_unsigned_float(v, man));
                            write_uint(bytes, at, 4, swap, r | gr << 11 | b << 22);
                        }
                        Type::Uint5999Rev => {
                            let ([r, gr, b], e) = small_float::to_rgb9e5([g[0], g[1], g[2]]);
                            write_uint(bytes, at, 4, swap, r | gr << 9 | b << 18 | e << 27);
                        }
                        t => {
                            for (c, &v) in g.iter().enumerate() {
                                write_uint(bytes, at + c * size, size, swap, encode_element(t, v, self.normalized()));
                            }
                        }
                    }
                }
            }
        }
    }
}

impl Codec<'_> {
    /// Encodes integer components `values` (`format.components` a pixel, in format order) into
    /// `bytes`, each clamped to the representable range of the type, or of its bit field for
    /// packed types (EXT_texture_integer, "Final Conversion" of section 4.3.2), leaving
    /// padding and skipped pixels as they were. Only the plain integer and packed types pair
    /// with integer formats ([`parse`]).
    pub fn encode_integers(&self, bytes: &mut [u8], values: &[i64], w: usize, h: usize, d: usize) {
        let n = self.format.components;
        let size = self.ty.element_size();
        let swap = self.modes.swap_bytes && size > 1;
        let (min, max) = match self.ty {
            Type::U8 => (0, i64::from(u8::MAX)),
            Type::I8 => (i64::from(i8::MIN), i64::from(i8::MAX)),
            Type::U16 => (0, i64::from(u16::MAX)),
            Type::I16 => (i64::from(i16::MIN), i64::from(i16::MAX)),
            Type::I32 => (i64::from(i32::MIN), i64::from(i32::MAX)),
            _ => (0, i64::from(u32::MAX)),
        };
        let mut groups = values.chunks_exact(n);
        for z in 0..d {
            for y in 0..h {
                for x in 0..w {
                    let Some(g) = groups.next() else { return };
                    let at = self.layout.offset(x, y, z);
                    if let Type::Packed(p) = self.ty {
                        let raw = p.fields.iter().zip(g).fold(0u32, |raw, (&(shift, bits), &v)| raw | (v.clamp(0, (1i64 << bits) - 1) as u32) << shift);
                        write_uint(bytes, at, size, swap, raw);
                        continue;
                    }
                    for (c, &v) in g.iter().enumerate() {
                        write_uint(bytes, at + c * size, size, swap, v.clamp(min, max) as u32);
                    }
                }
            }
        }
    }
}

/// The colour format an integer format (EXT_texture_integer's table 3.6) has the components
/// of (`GL_RGBA_INTEGER` → `GL_RGBA`...); any other format itself.
pub fn color_counterpart(format: GLenum) -> GLenum {
    match format {
        gl::GL_RED_INTEGER => gl::GL_RED,
        gl::GL_GREEN_INTEGER => gl::GL_GREEN,
        gl::GL_BLUE_INTEGER => gl::GL_BLUE,
        gl::GL_ALPHA_INTEGER => gl::GL_ALPHA,
        gl::GL_RG_INTEGER => gl::GL_RG,
        gl::GL_RGB_INTEGER => gl::GL_RGB,
        gl::GL_RGBA_INTEGER => gl::GL_RGBA,
        gl::GL_BGR_INTEGER => gl::GL_BGR,
        gl::GL_BGRA_INTEGER => gl::GL_BGRA,
        gl::GL_LUMINANCE_INTEGER_EXT => gl::GL_LUMINANCE,
        gl::GL_LUMINANCE_ALPHA_INTEGER_EXT => gl::GL_LUMINANCE_ALPHA,
        f => f,
    }
}

/// Expands a colour group of `format` to RGBA (section 3.6.4, "Conversion to RGB" and "Final
/// Expansion to RGBA"): luminance is copied to R, G and B, missing components are 0, alpha 1.
/// Generic over the component type: `f32` colours, and the `i64` components of integer
/// formats, expanded with 0 and 1 alike (EXT_texture_integer).
pub fn to_rgba<T: Copy + From<u8>>(format: GLenum, g: &[T]) -> [T; 4] {
    let (zero, one) = (T::from(0), T::from(1));
    let c = |i: usize| g.get(i).copied().unwrap_or(zero);
    match color_counterpart(format) {
        gl::GL_RED => [c(0), zero, zero, one],
        gl::GL_GREEN => [zero, c(0), zero, one],
        gl::GL_BLUE => [zero, zero, c(0), one],
        gl::GL_ALPHA => [zero, zero, zero, c(0)],
        gl::GL_LUMINANCE => [c(0), c(0), c(0), one],
        gl::GL_LUMINANCE_ALPHA => [c(0), c(0), c(0), c(1)],
        gl::GL_RG => [c(0), c(1), zero, one],
        gl::GL_RGB => [c(0), c(1), c(2), one],
        gl::GL_BGR => [c(2), c(1), c(0), one],
        gl::GL_BGRA => [c(2), c(1), c(0), c(3)],
        gl::GL_ABGR_EXT => [c(3), c(2), c(1), c(0)],
        _ => [c(0), c(1), c(2), c(3)],
    }
}

/// How packing forms `GL_LUMINANCE` from a colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Luminance {
    /// R + G + B clamped to [0, 1]: `glReadPixels` (section 4.3.2, "Conversion to L").
    Sum,
    /// R alone: `glGetTexImage` and `glGetColorTable`, whose table 6.1 puts a luminance
    /// texel in R (Mesa does the same; piglit's `getteximage-luminance` checks it).
    Red,
}

/// Selects the components of `format` from an RGBA colour, luminance formed as `luminance`
/// says.
pub fn from_rgba(format: GLenum, c: [f32; 4], luminance: Luminance, out: &mut Vec<f32>) {
    let l = match luminance {
        Luminance::Sum => (c[0] + c[1] + c[2]).clamp(0.0, 1.0),
        Luminance::Red => c[0],
    };
    select(format, c, l, out);
}

/// Selects the components of integer format `format` from an integer RGBA colour; luminance
/// is R (EXT_texture_integer, "Conversion to L").
pub fn from_integer_rgba(format: GLenum, c: [i64; 4], out: &mut Vec<i64>) {
    select(color_counterpart(format), c, c[0], out);
}

/// The components of colour format `format` from an RGBA colour with luminance `l`.
fn select<T: Copy>(format: GLenum, c: [T; 4], l: T, out: &mut Vec<T>) {
    match format {
        gl::GL_RED => out.push(c[0]),
        gl::GL_GREEN => out.push(c[1]),
        gl::GL_BLUE => out.push(c[2]),
        gl::GL_ALPHA => out.push(c[3]),
        gl::GL_LUMINANCE => out.push(l),
        gl::GL_LUMINANCE_ALPHA => out.extend([l, c[3]]),
        gl::GL_RG => out.extend([c[0], c[1]]),
        gl::GL_RGB => out.extend([c[0], c[1], c[2]]),
        gl::GL_BGR => out.extend([c[2], c[1], c[0]]),
        gl::GL_BGRA => out.extend([c[2], c[1], c[0], c[3]]),
        gl::GL_ABGR_EXT => out.extend([c[3], c[2], c[1], c[0]]),
        _ => out.extend(c),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn codec(format_: GLenum, type_: GLenum, modes: &StoreModes, w: usize, h: usize) -> Codec<'_> {
        let (format, ty) = parse(format_, type_).unwrap();
        let layout = ty.layout(format, modes, w, h, 1).unwrap();
        Codec { format, ty, layout, modes }
    }

    #[test]
    fn plain_types_decode_with_swap_bytes() {
        let swap = StoreModes { swap_bytes: true, alignment: 1, ..StoreModes::default() };
        let c = codec(gl::GL_LUMINANCE, gl::GL_UNSIGNED_SHORT, &swap, 2, 1);
        let bytes = [0xff, 0xff, 0x00, 0x80];
        let v = c.decode(&bytes, 2, 1, 1);
        assert_eq!(v[0], 1.0);
        // Swapped 0x00 0x80 is 0x0080 = 128.
        assert_eq!(v[1], f64::from(128.0f32 / 65535.0));
        let plain = StoreModes { alignment: 1, ..StoreModes::default() };
        let c = codec(gl::GL_LUMINANCE, gl::GL_UNSIGNED_SHORT, &plain, 2, 1);
        assert_eq!(c.decode(&bytes, 2, 1, 1)[1], f64::from(f32::from(u16::from_ne_bytes([0x00, 0x80])) / 65535.0));
        let c = codec(gl::GL_RGBA, gl::GL_BYTE, &plain, 1, 1);
        assert_eq!(c.decode(&[127, 0x80, 0, 1], 1, 1, 1)[..2], [1.0, -1.0]);
        let c = codec(gl::GL_COLOR_INDEX, gl::GL_INT, &plain, 1, 1);
        assert_eq!(c.decode(&(-5i32).to_ne_bytes(), 1, 1, 1), [-5.0]);
        let c = codec(gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, &swap, 1, 1);
        let mut be = 0.25f32.to_ne_bytes();
        be.reverse();
        assert_eq!(c.decode(&be, 1, 1, 1), [0.25]);
    }

    #[test]
    fn every_plain_type_swaps_bytes() {
        let swap = StoreModes { swap_bytes: true, alignment: 1, ..StoreModes::default() };
        let plain = StoreModes { alignment: 1, ..StoreModes::default() };
        // Each value written in the opposite byte order decodes with swapping, and as the
        // byte-reversed value without.
        let cases: [(GLenum, Vec<u8>, f32); 7] = [
            (gl::GL_UNSIGNED_BYTE, vec![7], 7.0),
            (gl::GL_BYTE, vec![0xf9], -7.0),
            (gl::GL_UNSIGNED_SHORT, 0x0102u16.to_ne_bytes().into_iter().rev().collect(), 258.0),
            (gl::GL_SHORT, (-300i16).to_ne_bytes().into_iter().rev().collect(), -300.0),
            (gl::GL_UNSIGNED_INT, 0x01020304u32.to_ne_bytes().into_iter().rev().collect(), 16909060.0),
            (gl::GL_INT, (-70000i32).to_ne_bytes().into_iter().rev().collect(), -70000.0),
            (gl::GL_FLOAT, 1.5f32.to_ne_bytes().into_iter().rev().collect(), 1.5),
        ];
        for (ty, bytes, value) in cases {
            let c = codec(gl::GL_COLOR_INDEX, ty, &swap, 1, 1);
            assert_eq!(c.decode(&bytes, 1, 1, 1), [f64::from(value)], "{ty:#x}");
            let mut back = vec![0u8; bytes.len()];
            c.encode(&mut back, &[value], 1, 1, 1);
            assert_eq!(back, bytes, "{ty:#x}");
            if bytes.len() > 1 {
                let unswapped = codec(gl::GL_COLOR_INDEX, ty, &plain, 1, 1).decode(&bytes, 1, 1, 1);
                assert_ne!(unswapped, [f64::from(value)], "{ty:#x}");
            }
        }
    }

    #[test]
    fn alignment_and_skips_select_bytes() {
        let m = StoreModes { alignment: 4, skip_pixels: 1, skip_rows: 1, row_length: 3, ..StoreModes::default() };
        let c = codec(gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, &m, 2, 2);
        // Rows of 3 bytes padded to 4; start at row 1, pixel 1.
        let bytes: Vec<u8> = (0..12).map(|i| i * 10).collect();
        let v: Vec<u8> = c.decode(&bytes, 2, 2, 1).iter().map(|x| (x * 255.0).round() as u8).collect();
        assert_eq!(v, [50, 60, 90, 100]);
    }

    #[test]
    fn packed_types_round_trip_every_field() {
        let m = StoreModes::default();
        for (fmt, ty, raw) in [
            (gl::GL_RGB, gl::GL_UNSIGNED_BYTE_3_3_2, 0b1010_1001u32),
            (gl::GL_RGB, gl::GL_UNSIGNED_BYTE_2_3_3_REV, 0b0101_0101),
            (gl::GL_RGB, gl::GL_UNSIGNED_SHORT_5_6_5, 0xf81f),
            (gl::GL_RGB, gl::GL_UNSIGNED_SHORT_5_6_5_REV, 0x07e0),
            (gl::GL_RGBA, gl::GL_UNSIGNED_SHORT_4_4_4_4, 0x1234),
            (gl::GL_BGRA, gl::GL_UNSIGNED_SHORT_4_4_4_4_REV, 0x1234),
            (gl::GL_RGBA, gl::GL_UNSIGNED_SHORT_5_5_5_1, 0x8421),
            (gl::GL_BGRA, gl::GL_UNSIGNED_SHORT_1_5_5_5_REV, 0x8421),
            (gl::GL_RGBA, gl::GL_UNSIGNED_INT_8_8_8_8, 0x11223344),
            (gl::GL_BGRA, gl::GL_UNSIGNED_INT_8_8_8_8_REV, 0x11223344),
            (gl::GL_RGBA, gl::GL_UNSIGNED_INT_10_10_10_2, 0xdeadbeef),
            (gl::GL_RGBA, gl::GL_UNSIGNED_INT_2_10_10_10_REV, 0xdeadbeef),
        ] {
            let c = codec(fmt, ty, &m, 1, 1);
            let size = c.ty.element_size();
            let mut bytes = vec![0u8; 4];
            write_uint(&mut bytes, 0, size, false, raw);
            let v: Vec<f32> = c.decode(&bytes, 1, 1, 1).iter().map(|&x| x as f32).collect();
            let mut back = vec![0u8; 4];
            c.encode(&mut back, &v, 1, 1, 1);
            assert_eq!(back, bytes, "{ty:#x}");
        }
        // 5_6_5: red in the top five bits.
        let c = codec(gl::GL_RGB, gl::GL_UNSIGNED_SHORT_5_6_5, &m, 1, 1);
        assert_eq!(c.decode(&0xf800u16.to_ne_bytes(), 1, 1, 1), [1.0, 0.0, 0.0]);
        // 8_8_8_8_REV: first component in the low byte.
        let c = codec(gl::GL_RGBA, gl::GL_UNSIGNED_INT_8_8_8_8_REV, &m, 1, 1);
        assert_eq!(c.decode(&0x000000ffu32.to_ne_bytes(), 1, 1, 1), [1.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn bitmaps_follow_lsb_first() {
        let msb = StoreModes { alignment: 1, ..StoreModes::default() };
        let c = codec(gl::GL_COLOR_INDEX, gl::GL_BITMAP, &msb, 3, 1);
        assert_eq!(c.decode(&[0b1010_0000], 3, 1, 1), [1.0, 0.0, 1.0]);
        let lsb = StoreModes { lsb_first: true, alignment: 1, ..StoreModes::default() };
        let c = codec(gl::GL_COLOR_INDEX, gl::GL_BITMAP, &lsb, 3, 1);
        assert_eq!(c.decode(&[0b0000_0110], 3, 1, 1), [0.0, 1.0, 1.0]);
        let mut out = [0xffu8];
        c.encode(&mut out, &[0.0, 1.0, 0.0], 3, 1, 1);
        assert_eq!(out, [0b1111_1010]);
    }

    #[test]
    fn format_type_errors() {
        assert_eq!(parse(gl::GL_RGBA, gl::GL_UNSIGNED_SHORT_5_6_5), Err(gl::GL_INVALID_OPERATION));
        assert_eq!(parse(gl::GL_RGB, gl::GL_BITMAP), Err(gl::GL_INVALID_ENUM));
        assert_eq!(parse(gl::GL_TEXTURE_2D, gl::GL_FLOAT), Err(gl::GL_INVALID_ENUM));
        assert_eq!(parse(gl::GL_RG_INTEGER, gl::GL_FLOAT), Err(gl::GL_INVALID_ENUM));
        assert!(parse(gl::GL_RG, gl::GL_UNSIGNED_BYTE).is_ok());
        assert_eq!(parse(gl::GL_RGBA, gl::GL_UNSIGNED_INT_10F_11F_11F_REV), Err(gl::GL_INVALID_OPERATION));
        assert_eq!(parse(gl::GL_BGR, gl::GL_UNSIGNED_INT_5_9_9_9_REV), Err(gl::GL_INVALID_OPERATION));
        assert!(parse(gl::GL_RGB, gl::GL_UNSIGNED_INT_5_9_9_9_REV).is_ok());
        assert_eq!(parse(gl::GL_BGR, gl::GL_UNSIGNED_SHORT_5_6_5), Err(gl::GL_INVALID_OPERATION));
        assert!(parse(gl::GL_RGB, gl::GL_UNSIGNED_BYTE_3_3_2).is_ok());
        assert_eq!(parse(gl::GL_RG, gl::GL_UNSIGNED_SHORT_4_4_4_4), Err(gl::GL_INVALID_OPERATION));
        assert_eq!(parse(gl::GL_RGB, 0x1234), Err(gl::GL_INVALID_ENUM));
        assert!(parse(gl::GL_BGRA, gl::GL_UNSIGNED_INT_8_8_8_8_REV).is_ok());
    }

    #[test]
    fn depth_stencil_types_round_trip_every_bit() {
        let plain = StoreModes::default();
        // 24_8: depth in the top 24 bits, stencil in the low 8.
        let c = codec(gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, &plain, 4, 1);
        let raws = [0x0000_0000u32, 0xffff_ffbb, 0x4000_00bb, 0x1234_5678];
        let bytes: Vec<u8> = raws.iter().flat_map(|r| r.to_ne_bytes()).collect();
        let v = c.decode(&bytes, 4, 1, 1);
        assert_eq!(v[2..4], [1.0, 187.0]);
        assert_eq!(v[6..8], [f64::from(0x12_3456) / DEPTH24_MAX, 120.0]);
        // Every 24-bit depth survives the trip through the f32 that pixel transfer carries.
        let narrowed: Vec<f32> = v.iter().map(|&x| x as f32).collect();
        let mut back = vec![0u8; 16];
        c.encode(&mut back, &narrowed, 4, 1, 1);
        assert_eq!(back, bytes);
        for depth in [1u32, 2, 0x7f_ffff, 0x80_0000, 0xff_fffe, 0xab_cdef] {
            let d = (f64::from(depth) / DEPTH24_MAX) as f32;
            let mut out = [0u8; 4];
            c.encode(&mut out, &[d, 3.0], 1, 1, 1);
            assert_eq!(u32::from_ne_bytes(out), depth << 8 | 3, "{depth:#x}");
        }
        // FLOAT_32_UNSIGNED_INT_24_8_REV: the float, then a word with the stencil in bits 7-0;
        // the unused bits 31-8 are ignored when unpacking and written as 0.
        let c = codec(gl::GL_DEPTH_STENCIL, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV, &plain, 2, 1);
        let words = [0.3f32.to_bits(), 0xabcd_ef42, 1.0f32.to_bits(), 0x0000_00ff];
        let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_ne_bytes()).collect();
        let v = c.decode(&bytes, 2, 1, 1);
        assert_eq!(v, [f64::from(0.3f32), 66.0, 1.0, 255.0]);
        let mut back = vec![0u8; 16];
        c.encode(&mut back, &v.iter().map(|&x| x as f32).collect::<Vec<_>>(), 2, 1, 1);
        let expect: Vec<u8> = [0.3f32.to_bits(), 0x42, 1.0f32.to_bits(), 0xff].iter().flat_map(|w| w.to_ne_bytes()).collect();
        assert_eq!(back, expect);
        // Swapping reverses each 32-bit word.
        let swap = StoreModes { swap_bytes: true, ..StoreModes::default() };
        let c = codec(gl::GL_DEPTH_STENCIL, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV, &swap, 1, 1);
        let swapped: Vec<u8> = [0.5f32.to_bits(), 7].iter().flat_map(|w| w.swap_bytes().to_ne_bytes()).collect();
        assert_eq!(c.decode(&swapped, 1, 1, 1), [0.5, 7.0]);
        let c = codec(gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, &swap, 1, 1);
        assert_eq!(c.decode(&0xffff_ff09u32.swap_bytes().to_ne_bytes(), 1, 1, 1), [1.0, 9.0]);
        // Rows: 8-byte groups, 4-byte alignment pads nothing.
        assert_eq!(c.layout.span, 4);
        let c = codec(gl::GL_DEPTH_STENCIL, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV, &plain, 3, 2);
        assert_eq!((c.layout.row_stride, c.layout.span), (24, 48));
    }

    #[test]
    fn integer_formats_parse_and_pack_clamped() {
        for f in [gl::GL_RGBA_INTEGER_EXT, gl::GL_LUMINANCE_ALPHA_INTEGER_EXT, gl::GL_BGR_INTEGER_EXT, gl::GL_ALPHA_INTEGER_EXT] {
            assert_eq!(parse(f, gl::GL_FLOAT), Err(gl::GL_INVALID_ENUM), "{f:#x}");
            assert_eq!(parse(f, gl::GL_BITMAP), Err(gl::GL_INVALID_ENUM), "{f:#x}");
            assert_eq!(parse(f, gl::GL_UNSIGNED_INT).map(|(f, _)| f.kind), Ok(Kind::Integer), "{f:#x}");
        }
        assert_eq!(parse(gl::GL_BGR_INTEGER_EXT, gl::GL_UNSIGNED_SHORT_5_6_5), Err(gl::GL_INVALID_OPERATION));
        assert_eq!(parse(gl::GL_RGB_INTEGER_EXT, gl::GL_UNSIGNED_INT_8_8_8_8), Err(gl::GL_INVALID_OPERATION));
        // Packed integer fields are unnormalized; packing clamps to each field.
        let plain = StoreModes::default();
        let c = codec(gl::GL_BGRA_INTEGER_EXT, gl::GL_UNSIGNED_SHORT_1_5_5_5_REV, &plain, 1, 1);
        let raw = 0b1_00111_00010_00001u16;
        assert_eq!(c.decode(&raw.to_ne_bytes(), 1, 1, 1), [1.0, 2.0, 7.0, 1.0]);
        let mut out = [0u8; 2];
        c.encode_integers(&mut out, &[1, 2, 7, 1], 1, 1, 1);
        assert_eq!(u16::from_ne_bytes(out), raw);
        c.encode_integers(&mut out, &[-3, 99, 0, 5], 1, 1, 1);
        assert_eq!(u16::from_ne_bytes(out), 0b1_00000_11111_00000);
        assert_eq!(parse(gl::GL_RGB_INTEGER_EXT, gl::GL_UNSIGNED_INT_10F_11F_11F_REV), Err(gl::GL_INVALID_OPERATION));
        assert_eq!(parse(gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_INT_24_8), Err(gl::GL_INVALID_OPERATION));
        // Integers decode unnormalized, every bit of 32-bit ones kept.
        let m = StoreModes::default();
        let c = codec(gl::GL_RGBA_INTEGER_EXT, gl::GL_INT, &m, 1, 1);
        let bytes: Vec<u8> = [i32::MIN, -1, 0, i32::MAX].iter().flat_map(|v| v.to_ne_bytes()).collect();
        assert_eq!(c.decode(&bytes, 1, 1, 1), [f64::from(i32::MIN), -1.0, 0.0, f64::from(i32::MAX)]);
        let c = codec(gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_INT, &m, 1, 1);
        assert_eq!(c.decode(&u32::MAX.to_ne_bytes().repeat(4), 1, 1, 1)[0], f64::from(u32::MAX));
        // Packing clamps to the type.
        let c = codec(gl::GL_RGBA_INTEGER_EXT, gl::GL_BYTE, &m, 1, 1);
        let mut out = [0u8; 4];
        c.encode_integers(&mut out, &[-1000, 1000, -5, 5], 1, 1, 1);
        assert_eq!(out.map(|b| b as i8), [-128, 127, -5, 5]);
        let c = codec(gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_SHORT, &m, 1, 1);
        let mut out = [0u8; 8];
        c.encode_integers(&mut out, &[-1, 70000, 3, 65535], 1, 1, 1);
        assert_eq!([0, 2, 4, 6].map(|i| u16::from_ne_bytes([out[i], out[i + 1]])), [0, 65535, 3, 65535]);
        assert_eq!(to_rgba(gl::GL_BGR_INTEGER_EXT, &[3i64, 2, 1]), [1, 2, 3, 1]);
        assert_eq!(to_rgba(gl::GL_LUMINANCE_ALPHA_INTEGER_EXT, &[-4i64, 9]), [-4, -4, -4, 9]);
        let mut v = Vec::new();
        from_integer_rgba(gl::GL_LUMINANCE_ALPHA_INTEGER_EXT, [5, 6, 7, 8], &mut v);
        from_integer_rgba(gl::GL_BGRA_INTEGER_EXT, [5, 6, 7, 8], &mut v);
        assert_eq!(v, [5, 8, 7, 6, 5, 8]);
    }

    #[test]
    fn depth_stencil_format_type_errors() {
        assert_eq!(parse(gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT), Err(gl::GL_INVALID_ENUM));
        assert_eq!(parse(gl::GL_DEPTH_STENCIL, gl::GL_FLOAT), Err(gl::GL_INVALID_ENUM));
        assert_eq!(parse(gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_SHORT_5_6_5), Err(gl::GL_INVALID_ENUM));
        assert_eq!(parse(gl::GL_DEPTH_STENCIL, gl::GL_BITMAP), Err(gl::GL_INVALID_ENUM));
        assert_eq!(parse(gl::GL_DEPTH_COMPONENT, gl::GL_UNSIGNED_INT_24_8), Err(gl::GL_INVALID_OPERATION));
        assert_eq!(parse(gl::GL_RGBA, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV), Err(gl::GL_INVALID_OPERATION));
        assert_eq!(parse(gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8).map(|(f, _)| f.kind), Ok(Kind::DepthStencil));
        assert_eq!(parse(gl::GL_DEPTH_STENCIL, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV).map(|(_, t)| t), Ok(Type::Float32Uint24_8Rev));
    }

    #[test]
    fn signed_encoding_inverts_table_2_9() {
        let m = StoreModes::default();
        let c = codec(gl::GL_RGBA, gl::GL_BYTE, &m, 1, 1);
        let mut out = [0u8; 4];
        c.encode(&mut out, &[1.0, -1.0, 0.5, -0.5], 1, 1, 1);
        assert_eq!(out.map(|b| b as i8), [127, -128, 63, -64]);
        let mut v = Vec::new();
        from_rgba(gl::GL_BGR, [0.1, 0.2, 0.3, 1.0], Luminance::Sum, &mut v);
        assert_eq!(to_rgba(gl::GL_ABGR_EXT, &[0.25, 0.5, 0.75, 1.0]), [1.0, 0.75, 0.5, 0.25]);
        from_rgba(gl::GL_LUMINANCE, [0.5, 0.25, 0.5, 1.0], Luminance::Sum, &mut v);
        from_rgba(gl::GL_LUMINANCE_ALPHA, [0.5, 0.25, 0.125, 0.75], Luminance::Red, &mut v);
        assert_eq!(v, [0.3, 0.2, 0.1, 1.0, 0.5, 0.75]);
        assert_eq!(to_rgba(gl::GL_LUMINANCE_ALPHA, &[0.5, 0.25]), [0.5, 0.5, 0.5, 0.25]);
    }
}
