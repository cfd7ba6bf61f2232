//! Compact vertex formats of a draw's own vertices (issue 17): each vertex carries the
//! position and only the attributes that vary over the draw; the attributes its vertices share
//! come from one vertex of the full layout ([`super::vertex`]) bound with stride 0 at
//! [`SHARED_BINDING`] ([`shared`]). The format is part of the pipeline key: the pipeline's
//! vertex input is [`VertexFormat::bindings`] and [`VertexFormat::attributes`], and `ff.vert`
//! is the same for every format. Expanded vertices ([`super::convert`]), a program's draws
//! and draws that carry radiosity's indirect light keep the full layout
//! ([`VertexFormat::FULL`]).
//!
//! An unlit draw's per-vertex colours travel as 4 bytes (unsigned normalized): OpenGL 1.5
//! section 2.14.9 converts each colour component, after lighting and clamping to [0, 1]
//! (2.14.6), to fixed point of at least the framebuffer's bits (8 in glrt's raster targets,
//! `target::COLOR_FORMAT`) by rounding to nearest before it is interpolated; an unlit vertex's
//! colour is only clamped, so clamping and rounding it here is that conversion. A lit draw
//! reads the colour in the lighting equation (the colour material): it keeps floats.

use super::key::{CLIP, GENERAL, ShaderKey, UNIT};
use super::shader_interface::{
    COLOR_MATERIAL, FOG_COORD, LIGHTING, LOCATION_COLOR, LOCATION_FOG_COORD, LOCATION_NORMAL, LOCATION_POSITION, LOCATION_SECONDARY, LOCATION_TEXCOORD, TEXCOORDS_UNUSED,
    TEXGEN,
};
use super::vertex::{BLACK, Column, Columns, ORIGIN, UP, VERTEX_ATTRIBUTES, VERTEX_FLOATS, WHITE};
use crate::frame::{Draw, Vertices};
use crate::render::shader_abi::Field;
use crate::render::texenv::codes::MAX_UNITS;

/// The vertex binding of the shared values (stride 0); the draw's vertices are at binding 0
/// and a program's generic attributes at 1.
pub const SHARED_BINDING: u32 = 2;

// Bits of a compact format: which attributes are stored per vertex.
/// The colour, as 4 floats.
const COLOR_FLOAT: u16 = 1;
/// The colour, as 4 unsigned normalized bytes.
const COLOR_UNORM: u16 = 2;
/// The secondary colour (4 floats, alpha 0).
const SECONDARY: u16 = 4;
/// The normal (3 floats).
const NORMAL: u16 = 8;
/// The fog coordinate (1 float).
const FOG: u16 = 16;
/// Unit 0's texture coordinates (4 floats); unit `u` at `UNIT0 << u`.
const UNIT0: u16 = 32;
/// The full layout of [`super::vertex`] at binding 0 and nothing else.
const FULL: u16 = 1 << 15;

/// How the draw's own vertices are laid out in upload memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct VertexFormat(u16);

/// How a vertex input reads its value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputFormat {
    /// `n` 32-bit floats.
    Float(u32),
    /// 4 unsigned normalized bytes (`R8G8B8A8_UNORM`).
    Unorm8x4,
}

/// One vertex input of a format: where `ff.vert`'s location `location` reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InputAttribute {
    /// `layout(location = …)` in `ff.vert`.
    pub location: u32,
    /// Vertex binding: 0 (the draw's vertices) or [`SHARED_BINDING`].
    pub binding: u32,
    /// Component type and count.
    pub format: InputFormat,
    /// Offset in bytes from the start of the binding's vertex.
    pub offset: u32,
}

/// A per-vertex attribute of a compact vertex: its bit, location and format.
struct Slot {
    bit: u16,
    location: u32,
    format: InputFormat,
}

/// The attributes a compact vertex may carry after the position, in their order.
const SLOTS: [Slot; 5 + MAX_UNITS] = [
        Slot { bit: COLOR_UNORM, location: LOCATION_COLOR, format: InputFormat::Unorm8x4 },
        float(COLOR_FLOAT, LOCATION_COLOR, 4),
        float(SECONDARY, LOCATION_SECONDARY, 4),
        float(NORMAL, LOCATION_NORMAL, 3),
        float(FOG, LOCATION_FOG_COORD, 1),
        float(UNIT0, LOCATION_TEXCOORD, 4),
        float(UNIT0 << 1, LOCATION_TEXCOORD + 1, 4),
        float(UNIT0 << 2, LOCATION_TEXCOORD + 2, 4),
        float(UNIT0 << 3, LOCATION_TEXCOORD + 3, 4),
];

/// A [`SLOTS`] entry of `n` floats.
const fn float(bit: u16, location: u32, n: u32) -> Slot {
    Slot { bit, location, format: InputFormat::Float(n) }
}

const _: () = assert!(MAX_UNITS == 4);

impl InputFormat {
    /// Bytes of one value.
    const fn bytes(self) -> u32 {
        match self {
            InputFormat::Float(n) => 4 * n,
            InputFormat::Unorm8x4 => 4,
        }
    }
}

impl VertexFormat {
    /// The full layout of [`super::vertex`] ([`VERTEX_FLOATS`] floats per vertex), nothing shared.
    pub const FULL: VertexFormat = VertexFormat(FULL);

    /// The compact format of `v` drawn with `key`: the position and each attribute that holds
    /// one value per vertex (more than one value) and that `ff.vert` reads under `key` (see
    /// [`read_by`]), the colour as bytes unless lit (see the module doc).
    pub fn of(v: &Vertices, key: &ShaderKey) -> VertexFormat {
        let read = read_by(key);
        let lit = LIGHTING.get(key.words[GENERAL]) != 0;
        let each = |values: usize, bit: u16| if values > 1 { bit & read } else { 0 };
        let mut bits = each(v.color.values.len(), if lit { COLOR_FLOAT } else { COLOR_UNORM })
            | each(v.secondary_color.values.len(), SECONDARY)
            | each(v.normal.values.len(), NORMAL)
            | each(v.fog_coord.values.len(), FOG);
        for (u, t) in v.texcoords.iter().take(MAX_UNITS).enumerate() {
            bits |= each(t.values.len(), UNIT0 << u);
        }
        VertexFormat(bits)
    }

    /// Whether this is [`VertexFormat::FULL`].
    pub fn is_full(self) -> bool {
        self.0 & FULL != 0
    }

    /// Bytes per vertex at binding 0.
    pub const fn stride(self) -> u32 {
        if self.0 & FULL != 0 {
            return 4 * VERTEX_FLOATS as u32;
        }
        let (mut bytes, mut i) = (16, 0);
        while i < SLOTS.len() {
            if self.0 & SLOTS[i].bit != 0 {
                bytes += SLOTS[i].format.bytes();
            }
            i += 1;
        }
        bytes
    }

    /// The vertex bindings as (binding, stride in bytes): binding 0 per vertex and, for a
    /// compact format, [`SHARED_BINDING`] with stride 0.
    pub fn bindings(self) -> Vec<(u32, u32)> {
        if self.is_full() { vec![(0, self.stride())] } else { vec![(0, self.stride()), (SHARED_BINDING, 0)] }
    }

    /// Where each of `ff.vert`'s inputs reads: the full layout at binding 0, or the position
    /// and per-vertex attributes at binding 0 in [`SLOTS`] order and every other input from
    /// the shared vertex at its full-layout offset.
    pub fn attributes(self) -> Vec<InputAttribute> {
        let full = |binding| {
            VERTEX_ATTRIBUTES.iter().map(move |a| InputAttribute { location: a.location, binding, format: InputFormat::Float(a.components), offset: 4 * a.offset })
        };
        if self.is_full() {
            return full(0).collect();
        }
        let mut out = vec![InputAttribute { location: LOCATION_POSITION, binding: 0, format: InputFormat::Float(4), offset: 0 }];
        let mut offset = 16;
        for s in SLOTS.iter().filter(|s| self.0 & s.bit != 0) {
            out.push(InputAttribute { location: s.location, binding: 0, format: s.format, offset });
            offset += s.format.bytes();
        }
        let shared: Vec<_> = full(SHARED_BINDING).filter(|a| !out.iter().any(|o| o.location == a.location)).collect();
        out.extend(shared);
        out
    }
}

/// The attributes (format bits) `ff.vert` reads under `key`: the colour unless lit without
/// the colour material, the secondary colour unlit, the normal lit or where a unit whose
/// coordinates are read generates them, the fog coordinate under [`FOG_COORD`], the
/// coordinates of units not in [`TEXCOORDS_UNUSED`].
fn read_by(key: &ShaderKey) -> u16 {
    let general = key.words[GENERAL];
    let lit = LIGHTING.get(general) != 0;
    let unused = TEXCOORDS_UNUSED.get(key.words[CLIP]);
    let units = (0..MAX_UNITS).filter(|&u| unused & 1 << u == 0);
    let texgen = units.clone().any(|u| Field::new(TEXGEN.shift, 12).get(key.words[UNIT + u]) != 0);
    let mut read = if !lit || COLOR_MATERIAL.get(general) != 0 { COLOR_FLOAT | COLOR_UNORM } else { 0 };
    read |= if lit { 0 } else { SECONDARY };
    read |= if lit || texgen { NORMAL } else { 0 };
    read |= if FOG_COORD.get(general) != 0 { FOG } else { 0 };
    units.fold(read, |read, u| read | UNIT0 << u)
}

/// The shared vertex of a compact format: the full-layout vertex of the values every vertex
/// of `draw` shares (OpenGL's initial values for absent attributes; per-vertex attributes, the
/// rasterization attribute and the indirect light hold what binding 0 or nothing overrides).
pub fn shared(draw: &Draw) -> [f32; VERTEX_FLOATS] {
    if draw.vertices.is_empty() {
        return [0.0; VERTEX_FLOATS];
    }
    let mut v = Columns::of(&draw.vertices).vertex(0);
    v[..4].fill(0.0);
    v
}

/// Writes the draw's vertices in `format` (not [`VertexFormat::FULL`]: that is
/// [`super::vertex::pack_into`]) into `out`, `stride / 4` words per vertex, as many vertices as
/// both hold; every word of each vertex once, in order (upload memory may be write-combined).
/// Formats of the colour, the normal and units 0 and 1 take a loop made for them; the others
/// one that tests the format's bits per vertex.
pub fn pack_into(draw: &Draw, format: VertexFormat, out: &mut [u32]) {
    let c = Columns::of(&draw.vertices);
    macro_rules! by_format {
        ($($bits:expr),*) => {
            match format.0 {
                $(b if b == $bits => rows::<{ $bits }>(&c, out),)*
                b => rows_of(b, &c, out),
            }
        };
    }
    const C: u16 = COLOR_UNORM;
    const F: u16 = COLOR_FLOAT;
    const N: u16 = NORMAL;
    const T0: u16 = UNIT0;
    const T1: u16 = UNIT0 << 1;
    by_format!(0, C, F, N, C | N, F | N, T0, C | T0, F | T0, N | T0, C | N | T0, F | N | T0, T0 | T1, C | T0 | T1, F | T0 | T1, N | T0 | T1, F | N | T0 | T1);
}

/// The loop of format `B`, its tests and vertex size made at compile time.
fn rows<const B: u16>(c: &Columns<'_>, out: &mut [u32]) {
    rows_with(B, const { VertexFormat(B).stride() as usize / 4 }, c, out)
}

/// The loop of any compact format `bits`.
#[inline(never)]
fn rows_of(bits: u16, c: &Columns<'_>, out: &mut [u32]) {
    rows_with(bits, VertexFormat(bits).stride() as usize / 4, c, out)
}

/// Packs the vertices of format `bits`, `words` (its stride in words) each, every stored
/// attribute read from a slice of one value per vertex (no test of the column per vertex).
#[inline(always)]
fn rows_with(bits: u16, words: usize, c: &Columns<'_>, out: &mut [u32]) {
    let n = (out.len() / words).min(c.position.len());
    let (out, position) = (&mut out[..n * words], &c.position[..n]);
    let mut padded = Padded::default();
    let color = stored_values(bits & (COLOR_UNORM | COLOR_FLOAT) != 0, &c.color, n, WHITE, &mut padded.color);
    let secondary = stored_values(bits & SECONDARY != 0, &c.secondary, n, BLACK, &mut padded.secondary);
    let normal = stored_values(bits & NORMAL != 0, &c.normal, n, UP, &mut padded.normal);
    let fog = stored_values(bits & FOG != 0, &c.fog, n, 0.0, &mut padded.fog);
    let [p0, p1, p2, p3] = &mut padded.texcoords;
    let texcoords = [
        stored_values(bits & UNIT0 != 0, &c.texcoords[0], n, ORIGIN, p0),
        stored_values(bits & (UNIT0 << 1) != 0, &c.texcoords[1], n, ORIGIN, p1),
        stored_values(bits & (UNIT0 << 2) != 0, &c.texcoords[2], n, ORIGIN, p2),
        stored_values(bits & (UNIT0 << 3) != 0, &c.texcoords[3], n, ORIGIN, p3),
    ];
    for (i, (row, position)) in out.chunks_exact_mut(words).zip(position).enumerate() {
        let mut k = 0;
        put(row, &mut k, position);
        if bits & COLOR_UNORM != 0 {
            row[k] = unorm8x4(color[i]);
            k += 1;
        }
        if bits & COLOR_FLOAT != 0 {
            put(row, &mut k, &color[i]);
        }
        if bits & SECONDARY != 0 {
            let [r, g, b] = secondary[i];
            put(row, &mut k, &[r, g, b, 0.0]);
        }
        if bits & NORMAL != 0 {
            put(row, &mut k, &normal[i]);
        }
        if bits & FOG != 0 {
            put(row, &mut k, &[fog[i]]);
        }
        for (u, t) in texcoords.iter().enumerate() {
            if bits & (UNIT0 << u) != 0 {
                put(row, &mut k, &t[i]);
            }
        }
    }
}

/// Copies of stored columns that hold fewer values than the vertices (translate makes none),
/// padded with the attribute's initial value.
#[derive(Default)]
struct Padded {
    color: Vec<[f32; 4]>,
    secondary: Vec<[f32; 3]>,
    normal: Vec<[f32; 3]>,
    fog: Vec<f32>,
    texcoords: [Vec<[f32; 4]>; MAX_UNITS],
}

/// The first `n` values of `column` when it is `stored` (none when not): the column's own, or
/// a copy in `padded` of those it has followed by `initial`.
#[inline(always)]
fn stored_values<'a, T: Copy>(stored: bool, column: &Column<'a, T>, n: usize, initial: T, padded: &'a mut Vec<T>) -> &'a [T] {
    match column {
        _ if !stored => &[],
        Column::Each(values) if values.len() >= n => &values[..n],
        _ => {
            padded.extend((0..n).map(|i| column.get(i, initial)));
            padded
        }
    }
}

/// Writes `values` as words at `vertex[*k..]` and moves `k` past them.
#[inline(always)]
fn put<const N: usize>(vertex: &mut [u32], k: &mut usize, values: &[f32; N]) {
    // One copy of the value's `N` words (a vector move), not a loop over them.
    vertex[*k..*k + N].copy_from_slice(&values.map(f32::to_bits));
    *k += N;
}

/// A colour clamped to [0, 1] and rounded to 8 bits per component, as `R8G8B8A8_UNORM` lays
/// it out in memory.
#[inline(always)]
fn unorm8x4(color: [f32; 4]) -> u32 {
    // `max` then `min` also take NaN to 0; the rounded value is then in [0.5, 255.5], which
    // truncates to a byte without the saturating conversion's tests.
    u32::from_ne_bytes(color.map(|c| {
        let scaled = c.max(0.0).min(1.0) * 255.0 + 0.5;
        // Safety: finite and in [0.5, 255.5], so it fits in an i32.
        (unsafe { scaled.to_int_unchecked::<i32>() }) as u8
    }))
}

#[cfg(test)]
mod tests {
    use super::super::vertex;
    use super::super::vertex::tests::{attrib, attribute_cases};
    use super::*;

    fn vertices(n: usize) -> Vertices {
        let mut v = Vertices::with_units(MAX_UNITS);
        v.position = vec![[0.0, 0.0, 0.0, 1.0]; n];
        v
    }

    /// The key of an unlit (`lit` false) or lit draw with the colour material in which
    /// `ff.vert` reads every attribute: the fog coordinate, every unit textured.
    fn reading_all(lit: bool) -> ShaderKey {
        let mut key = ShaderKey::default();
        FOG_COORD.set(&mut key.words[GENERAL], 1);
        if lit {
            LIGHTING.set(&mut key.words[GENERAL], 1);
            COLOR_MATERIAL.set(&mut key.words[GENERAL], 5);
        }
        key
    }

    #[test]
    fn the_format_holds_what_varies_over_the_draw_and_is_read() {
        let mut v = vertices(3);
        let (unlit, lit) = (reading_all(false), reading_all(true));
        assert_eq!((VertexFormat::of(&v, &unlit), VertexFormat::of(&v, &unlit).stride()), (VertexFormat(0), 16), "positions only");
        // The benchmark's glColor3f + glTexCoord2f + glVertex3f, every value changing.
        v.color.values = vec![[0.5; 4], [0.25; 4], [1.0; 4]];
        v.texcoords[0].values = vec![[0.0; 4]; 3];
        let f = VertexFormat::of(&v, &unlit);
        assert_eq!((f, f.stride()), (VertexFormat(COLOR_UNORM | UNIT0), 16 + 4 + 16));
        let f = VertexFormat::of(&v, &lit);
        assert_eq!((f, f.stride()), (VertexFormat(COLOR_FLOAT | UNIT0), 16 + 16 + 16));
        // Untextured (unit 0's coordinates unused): the colour only.
        let mut untextured = unlit;
        TEXCOORDS_UNUSED.set(&mut untextured.words[CLIP], 0b1111);
        assert_eq!(VertexFormat::of(&v, &untextured), VertexFormat(COLOR_UNORM));
        // Lit without the colour material: no colour; with normals per vertex: the normal.
        let mut plain = ShaderKey::default();
        LIGHTING.set(&mut plain.words[GENERAL], 1);
        v.normal.values = vec![[0.0, 1.0, 0.0]; 3];
        assert_eq!(VertexFormat::of(&v, &plain), VertexFormat(NORMAL | UNIT0));
        // Unlit, the normal only for a unit that generates coordinates (sphere map on unit 0).
        assert_eq!(VertexFormat::of(&v, &unlit), VertexFormat(COLOR_UNORM | UNIT0));
        let mut sphere = unlit;
        TEXGEN.set(&mut sphere.words[UNIT], 3);
        assert_eq!(VertexFormat::of(&v, &sphere), VertexFormat(COLOR_UNORM | NORMAL | UNIT0));
        // A shared colour and fog coordinate stay out; unit 2 varies.
        v.normal.values.truncate(1);
        v.color.values.truncate(1);
        v.fog_coord.values = vec![2.0];
        v.texcoords[2].values = vec![[1.0; 4]; 3];
        let f = VertexFormat::of(&v, &unlit);
        assert_eq!((f, f.stride()), (VertexFormat(UNIT0 | UNIT0 << 2), 16 + 32));
        let on_zero: Vec<_> = f.attributes().iter().filter(|a| a.binding == 0).map(|a| (a.location, a.offset)).collect();
        assert_eq!(on_zero, vec![(LOCATION_POSITION, 0), (LOCATION_TEXCOORD, 16), (LOCATION_TEXCOORD + 2, 32)]);
        assert_eq!(f.bindings(), vec![(0, 48), (SHARED_BINDING, 0)]);
        assert!(!f.is_full() && VertexFormat::FULL.is_full());
        assert_eq!(VertexFormat::FULL.bindings(), vec![(0, 160)]);
    }

    #[test]
    fn every_input_has_one_source() {
        for bits in 0..(UNIT0 << MAX_UNITS) {
            if bits & COLOR_FLOAT != 0 && bits & COLOR_UNORM != 0 {
                continue;
            }
            let attributes = VertexFormat(bits).attributes();
            let mut locations: Vec<u32> = attributes.iter().map(|a| a.location).collect();
            locations.sort();
            let mut full: Vec<u32> = VERTEX_ATTRIBUTES.iter().map(|a| a.location).collect();
            full.sort();
            assert_eq!(locations, full, "format {bits:#x}");
            let end = attributes.iter().filter(|a| a.binding == 0).map(|a| a.offset + a.format.bytes()).max();
            assert_eq!(end, Some(VertexFormat(bits).stride()), "format {bits:#x}: binding 0 is tiled");
        }
    }

    /// What `ff.vert` reads at vertex `i` through `format`'s inputs, in the full layout's
    /// floats: from `packed` (binding 0) or `shared`.
    fn fetch(format: VertexFormat, packed: &[u32], shared: &[f32; VERTEX_FLOATS], i: usize) -> [f32; VERTEX_FLOATS] {
        let mut out = [0.0; VERTEX_FLOATS];
        let stride = format.stride() as usize / 4;
        let full_offset = |location| VERTEX_ATTRIBUTES.iter().find(|a| a.location == location).unwrap().offset as usize;
        for a in format.attributes() {
            let to = full_offset(a.location);
            let from = a.offset as usize / 4;
            match (a.binding, a.format) {
                (0, InputFormat::Float(n)) => {
                    for c in 0..n as usize {
                        out[to + c] = f32::from_bits(packed[i * stride + from + c]);
                    }
                }
                (0, InputFormat::Unorm8x4) => {
                    for (c, byte) in packed[i * stride + from].to_ne_bytes().into_iter().enumerate() {
                        out[to + c] = byte as f32 / 255.0;
                    }
                }
                (_, InputFormat::Float(n)) => out[to..to + n as usize].copy_from_slice(&shared[from..from + n as usize]),
                (_, InputFormat::Unorm8x4) => unreachable!("shared values are floats"),
            }
        }
        out
    }

    #[test]
    fn every_format_reads_as_the_full_layout() {
        let n = 4;
        let quad = |x: f32| [x.fract(), 1.0 - x.fract(), x, x + 0.125];
        let triple = |x: f32| [x, x + 0.125, x + 0.25];
        for how in attribute_cases() {
            let mut draw = Draw::default();
            let v = &mut draw.vertices;
            v.position = (0..n).map(|i| [i as f32, 2.0, 3.0, 1.0]).collect();
            // Colours beyond [0, 1] too: the byte colour is clamped.
            v.color = attrib(how[0], n, -0.4, quad);
            v.secondary_color = attrib(how[1], n, 20.0, triple);
            v.normal = attrib(how[2], n, 30.0, triple);
            v.fog_coord = attrib(how[3], n, 40.0, |x| x);
            v.texcoords = (0..MAX_UNITS).map(|u| attrib(how[4 + u], n, 50.0 + 10.0 * u as f32, quad)).collect();
            let full = vertex::pack(&draw);
            let shared = shared(&draw);
            for lit in [false, true] {
                let format = VertexFormat::of(&draw.vertices, &reading_all(lit));
                let words = format.stride() as usize / 4;
                // One word more than the vertices need: left as it was.
                let mut packed = vec![7; n * words + 1];
                pack_into(&draw, format, &mut packed);
                assert_eq!(packed[n * words], 7, "layout {how:?}: past the vertices");
                for i in 0..n {
                    let mut expected: Vec<f32> = vertex::get(&full, i as u32).to_vec();
                    if format.0 & COLOR_UNORM != 0 {
                        for c in &mut expected[vertex::COLOR..vertex::COLOR + 4] {
                            *c = (c.clamp(0.0, 1.0) * 255.0).round() / 255.0;
                        }
                    }
                    let mut got = fetch(format, &packed, &shared, i);
                    // What ff.vert does not read comes from the shared vertex (any value).
                    let read = read_by(&reading_all(lit));
                    for (bit, at, n) in [(SECONDARY, vertex::SECONDARY, 4), (NORMAL, vertex::NORMAL, 3)] {
                        if read & bit == 0 {
                            got[at..at + n].copy_from_slice(&expected[at..at + n]);
                        }
                    }
                    assert_eq!(got.map(f32::to_bits).to_vec(), expected.iter().map(|f| f.to_bits()).collect::<Vec<_>>(), "layout {how:?}, lit {lit}, vertex {i}");
                }
            }
        }
    }
}
