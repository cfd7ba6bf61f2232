//! The packed vertex of `ff.vert`: a draw's structure-of-arrays attributes interleaved as
//! [`VERTEX_FLOATS`] `f32`s per vertex, laid out as [`VERTEX_ATTRIBUTES`] says.

use super::shader_interface::{
    LOCATION_COLOR, LOCATION_FOG_COORD, LOCATION_INDIRECT, LOCATION_NORMAL, LOCATION_POSITION, LOCATION_RASTER, LOCATION_SECONDARY, LOCATION_TEXCOORD,
};
use crate::render::texenv::codes::MAX_UNITS;
use crate::frame::Draw;
use crate::frame::program::ShaderProgram;

/// Floats per packed vertex.
pub const VERTEX_FLOATS: usize = 40;

/// One vertex input: shader location, component count (of `f32`s) and offset in floats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VertexAttribute {
    /// `layout(location = …)` in `ff.vert`.
    pub location: u32,
    /// Number of `f32` components (1 to 4).
    pub components: u32,
    /// Offset from the start of the vertex, in floats.
    pub offset: u32,
}

/// Offset of the object-space position (4 floats).
pub const POSITION: usize = 0;
/// Offset of the primary colour (4).
pub const COLOR: usize = 4;
/// Offset of the secondary colour (4, alpha 0).
pub const SECONDARY: usize = 8;
/// Offset of the object-space normal (3).
pub const NORMAL: usize = 12;
/// Offset of the fog coordinate (1).
pub const FOG_COORD: usize = 15;
/// Offset of unit 0's texture coordinates (4 per unit).
pub const TEXCOORD: usize = 16;
/// Offset of the rasterization attribute (4): for expanded lines the window-pixel offset of
/// the corner from its endpoint (x, y), the line stipple distance and the signed distance
/// across the line (smooth lines); for expanded points the corner (±1, ±1); zero for
/// triangles. See [`super::convert`].
pub const RASTER: usize = TEXCOORD + 4 * MAX_UNITS;
/// Offset of radiosity's indirect light (4, alpha 0): zero but in draws that the radiosity
/// lights ([`set_indirect`]).
pub const INDIRECT: usize = RASTER + 4;

/// Position (4), colour (4), secondary colour (4), normal (3), fog coordinate (1), the
/// texture coordinates of each unit (4 each), the rasterization attribute (4) and the
/// indirect light (4).
pub const VERTEX_ATTRIBUTES: &[VertexAttribute] = &[
    VertexAttribute { location: LOCATION_POSITION, components: 4, offset: POSITION as u32 },
    VertexAttribute { location: LOCATION_COLOR, components: 4, offset: COLOR as u32 },
    VertexAttribute { location: LOCATION_SECONDARY, components: 4, offset: SECONDARY as u32 },
    VertexAttribute { location: LOCATION_NORMAL, components: 3, offset: NORMAL as u32 },
    VertexAttribute { location: LOCATION_FOG_COORD, components: 1, offset: FOG_COORD as u32 },
    VertexAttribute { location: LOCATION_TEXCOORD, components: 4, offset: TEXCOORD as u32 },
    VertexAttribute { location: LOCATION_TEXCOORD + 1, components: 4, offset: TEXCOORD as u32 + 4 },
    VertexAttribute { location: LOCATION_TEXCOORD + 2, components: 4, offset: TEXCOORD as u32 + 8 },
    VertexAttribute { location: LOCATION_TEXCOORD + 3, components: 4, offset: TEXCOORD as u32 + 12 },
    VertexAttribute { location: LOCATION_RASTER, components: 4, offset: RASTER as u32 },
    VertexAttribute { location: LOCATION_INDIRECT, components: 4, offset: INDIRECT as u32 },
];

// The indirect light's location follows every generic attribute's (a program's pipeline binds
// both).
const _: () = assert!(LOCATION_INDIRECT >= crate::frame::program::GENERIC_ATTRIBUTE_LOCATION + 15);

/// Writes `indirect[i]` as the indirect light of packed vertex `i` (one value per vertex).
pub fn set_indirect(packed: &mut [f32], indirect: &[[f32; 3]]) {
    for (vertex, light) in packed.chunks_exact_mut(VERTEX_FLOATS).zip(indirect) {
        vertex[INDIRECT..INDIRECT + 3].copy_from_slice(light);
    }
}

/// Interleaves the draw's attributes; missing attributes take OpenGL's initial current values.
pub fn pack(draw: &Draw) -> Vec<f32> {
    let mut out = vec![0.0; draw.vertices.len() * VERTEX_FLOATS];
    pack_into(draw, &mut out);
    out
}

/// [`pack`] into `out` (upload memory), [`VERTEX_FLOATS`] per vertex: as many vertices as
/// both hold. Every float of each vertex is written once, in order (upload memory may be
/// write-combined). Draws whose per-vertex attributes are among the colour, the normal and
/// the coordinates of units 0 and 1 (the others shared by all vertices or absent: nearly
/// every draw) take a loop specialised for that layout (`Common`); the rest look at each
/// attribute of each vertex (`Columns::vertex`).
pub fn pack_into(draw: &Draw, out: &mut [f32]) {
    let columns = Columns::of(&draw.vertices);
    let n = draw.vertices.len().min(out.len() / VERTEX_FLOATS);
    let out = &mut out[..n * VERTEX_FLOATS];
    match Common::of(&columns, n) {
        Some(common) => common.pack(out),
        None => {
            for (i, vertex) in out.chunks_exact_mut(VERTEX_FLOATS).enumerate() {
                vertex.copy_from_slice(&columns.vertex(i));
            }
        }
    }
}

/// One attribute of every vertex: one value each, or one value for all.
#[derive(Clone, Copy)]
pub(super) enum Column<'a, T> {
    Each(&'a [T]),
    One(T),
}

impl<'a, T: Copy> Column<'a, T> {
    /// The column of `a`, `initial` where it has no value (as [`crate::frame::Attrib::get`]).
    pub(super) fn of(a: &'a crate::frame::Attrib<T>, initial: T) -> Column<'a, T> {
        match a.values.len() {
            0 => Column::One(initial),
            1 => Column::One(a.values[0]),
            _ => Column::Each(&a.values),
        }
    }

    #[inline(always)]
    pub(super) fn get(&self, i: usize, initial: T) -> T {
        match self {
            Column::Each(values) => values.get(i).copied().unwrap_or(initial),
            Column::One(value) => *value,
        }
    }

    /// The value shared by every vertex (`initial` for a column of one value each).
    fn shared(&self, initial: T) -> T {
        match self {
            Column::Each(_) => initial,
            Column::One(value) => *value,
        }
    }

    /// The first `n` values of a column of one value each (`Some(&[])` for a shared value;
    /// `None` when it holds fewer than `n`).
    fn each(&self, n: usize) -> Option<&'a [T]> {
        match self {
            Column::Each(values) => values.get(..n),
            Column::One(_) => Some(&[]),
        }
    }
}

/// The attributes of a draw's vertices, each looked at once (not once per vertex).
pub(super) struct Columns<'a> {
    pub(super) position: &'a [[f32; 4]],
    pub(super) color: Column<'a, [f32; 4]>,
    pub(super) secondary: Column<'a, [f32; 3]>,
    pub(super) normal: Column<'a, [f32; 3]>,
    pub(super) fog: Column<'a, f32>,
    pub(super) texcoords: [Column<'a, [f32; 4]>; MAX_UNITS],
}

/// The initial colour.
pub(super) const WHITE: [f32; 4] = [1.0; 4];
/// The initial secondary colour.
pub(super) const BLACK: [f32; 3] = [0.0; 3];
/// The initial normal.
pub(super) const UP: [f32; 3] = [0.0, 0.0, 1.0];
/// The initial texture coordinates.
pub(super) const ORIGIN: [f32; 4] = [0.0, 0.0, 0.0, 1.0];

impl<'a> Columns<'a> {
    /// The columns of `v`'s attributes.
    pub(super) fn of(v: &'a crate::frame::Vertices) -> Columns<'a> {
        Columns {
            position: &v.position,
            color: Column::of(&v.color, WHITE),
            secondary: Column::of(&v.secondary_color, BLACK),
            normal: Column::of(&v.normal, UP),
            fog: Column::of(&v.fog_coord, 0.0),
            texcoords: std::array::from_fn(|u| v.texcoords.get(u).map_or(Column::One(ORIGIN), |t| Column::of(t, ORIGIN))),
        }
    }

    /// Packed vertex `i`.
    #[inline(always)]
    pub(super) fn vertex(&self, i: usize) -> [f32; VERTEX_FLOATS] {
        let mut out = [0.0; VERTEX_FLOATS];
        out[POSITION..POSITION + 4].copy_from_slice(&self.position[i]);
        out[COLOR..COLOR + 4].copy_from_slice(&self.color.get(i, WHITE));
        out[SECONDARY..SECONDARY + 3].copy_from_slice(&self.secondary.get(i, BLACK));
        out[NORMAL..NORMAL + 3].copy_from_slice(&self.normal.get(i, UP));
        out[FOG_COORD] = self.fog.get(i, 0.0);
        for (unit, column) in self.texcoords.iter().enumerate() {
            let at = TEXCOORD + 4 * unit;
            out[at..at + 4].copy_from_slice(&column.get(i, ORIGIN));
        }
        out
    }
}

/// A packed vertex as its ten vec4s.
type Quads = [[f32; 4]; VERTEX_FLOATS / 4];

// The vec4s `Common` writes: position, colour, secondary colour (alpha 0), normal with the
// fog coordinate, units 0 to 3, then the rasterization attribute and the indirect light.
const _: () = assert!(
    POSITION == 0 && COLOR == 4 && SECONDARY == 8 && NORMAL == 12 && FOG_COORD == 15 && TEXCOORD == 16 && RASTER == 32 && INDIRECT == 36 && VERTEX_FLOATS == 40
);

// Bits of a [`Common`] layout: which attributes have one value per vertex.
/// The colour.
const EACH_COLOR: u8 = 1;
/// The normal.
const EACH_NORMAL: u8 = 2;
/// Unit 0's texture coordinates.
const EACH_UNIT0: u8 = 4;
/// Unit 1's texture coordinates.
const EACH_UNIT1: u8 = 8;

/// A draw whose per-vertex attributes are the position and any of the colour, the normal and
/// the coordinates of units 0 and 1, each holding a value for every packed vertex: the
/// vertex's vec4s that all vertices share are made once ([`Common::shared`]).
struct Common<'a> {
    /// The packed vertex of the shared values (position and per-vertex attributes zero).
    shared: Quads,
    position: &'a [[f32; 4]],
    /// Per-vertex values, empty where shared.
    color: &'a [[f32; 4]],
    normal: &'a [[f32; 3]],
    unit0: &'a [[f32; 4]],
    unit1: &'a [[f32; 4]],
    /// `EACH_*` bits of the attributes stored per vertex.
    layout: u8,
}

impl<'a> Common<'a> {
    /// The common layout of the first `n` vertices of `c`, `None` when it has another.
    fn of(c: &Columns<'a>, n: usize) -> Option<Common<'a>> {
        if matches!(c.secondary, Column::Each(_)) || matches!(c.fog, Column::Each(_)) || c.texcoords[2..].iter().any(|t| matches!(t, Column::Each(_))) {
            return None;
        }
        let (color, normal, unit0, unit1) = (c.color.each(n)?, c.normal.each(n)?, c.texcoords[0].each(n)?, c.texcoords[1].each(n)?);
        let [r, g, b] = c.secondary.shared(BLACK);
        let [x, y, z] = c.normal.shared(UP);
        let bit = |values: usize, bit: u8| if values > 0 { bit } else { 0 };
        Some(Common {
            shared: [
                [0.0; 4],
                c.color.shared(WHITE),
                [r, g, b, 0.0],
                [x, y, z, c.fog.shared(0.0)],
                c.texcoords[0].shared(ORIGIN),
                c.texcoords[1].shared(ORIGIN),
                c.texcoords[2].shared(ORIGIN),
                c.texcoords[3].shared(ORIGIN),
                [0.0; 4],
                [0.0; 4],
            ],
            position: c.position.get(..n)?,
            color,
            normal,
            unit0,
            unit1,
            layout: bit(color.len(), EACH_COLOR) | bit(normal.len(), EACH_NORMAL) | bit(unit0.len(), EACH_UNIT0) | bit(unit1.len(), EACH_UNIT1),
        })
    }

    /// Packs every vertex into `out` (exactly their [`VERTEX_FLOATS`] each), by the loop made
    /// for this layout.
    fn pack(&self, out: &mut [f32]) {
        macro_rules! by_layout {
            ($($layout:literal)*) => {
                match self.layout {
                    $($layout => self.rows::<$layout>(out),)*
                    _ => self.rows::<15>(out),
                }
            };
        }
        by_layout!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14);
    }

    /// Packs the vertices of layout `L` (`EACH_*` bits): the vec4s of per-vertex attributes
    /// from their columns, the others from [`Common::shared`].
    #[inline(always)]
    fn rows<const L: u8>(&self, out: &mut [f32]) {
        let s = &self.shared;
        let (color, normal, unit0, unit1) = (self.color, self.normal, self.unit0, self.unit1);
        for (i, (vertex, position)) in out.chunks_exact_mut(VERTEX_FLOATS).zip(self.position).enumerate() {
            let normal = if L & EACH_NORMAL != 0 {
                let [x, y, z] = normal[i];
                [x, y, z, s[3][3]]
            } else {
                s[3]
            };
            let quads: Quads = [
                *position,
                if L & EACH_COLOR != 0 { color[i] } else { s[1] },
                s[2],
                normal,
                if L & EACH_UNIT0 != 0 { unit0[i] } else { s[4] },
                if L & EACH_UNIT1 != 0 { unit1[i] } else { s[5] },
                s[6],
                s[7],
                s[8],
                s[9],
            ];
            vertex.copy_from_slice(quads.as_flattened());
        }
    }
}

/// The generic attribute indices (1 to 15) a program's vertex stage reads, in the order of
/// [`ShaderProgram::attributes`], each once: the order of [`pack_generic`]'s vec4s.
pub fn generic_indices(program: &ShaderProgram) -> Vec<u32> {
    let mut out: Vec<u32> = Vec::new();
    for &i in &program.attributes {
        if (1..16).contains(&i) && !out.contains(&i) {
            out.push(i);
        }
    }
    out
}

/// Interleaves the generic attributes `indices` of the draw's vertices, 4 floats each per
/// vertex; an attribute the draw lacks is (0, 0, 0, 1).
pub fn pack_generic(draw: &Draw, indices: &[u32]) -> Vec<f32> {
    let v = &draw.vertices;
    let mut out = Vec::with_capacity(v.len() * 4 * indices.len());
    for i in 0..v.position.len() {
        for &index in indices {
            let value = v.generic.get(index as usize).and_then(|a| a.get(i));
            out.extend_from_slice(&value.unwrap_or([0.0, 0.0, 0.0, 1.0]));
        }
    }
    out
}

/// The packed vertex `i` of `packed`.
pub fn get(packed: &[f32], i: u32) -> &[f32] {
    let start = i as usize * VERTEX_FLOATS;
    &packed[start..start + VERTEX_FLOATS]
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::frame::Attrib;

    #[test]
    fn packs_each_vertex_at_the_declared_offsets() {
        let mut draw = Draw::default();
        draw.vertices.position = vec![[1.0, 2.0, 3.0, 1.0], [4.0, 5.0, 6.0, 1.0]];
        draw.vertices.color.values = vec![[0.5, 0.25, 0.125, 1.0]];
        draw.vertices.fog_coord.values = vec![3.0, 9.0];
        draw.vertices.texcoords = vec![Attrib::default(), Attrib { values: vec![[0.0; 4], [7.0, 8.0, 0.0, 1.0]] }];
        let packed = pack(&draw);
        assert_eq!(packed.len(), 2 * VERTEX_FLOATS);
        let second = get(&packed, 1);
        assert_eq!(&second[POSITION..POSITION + 4], &[4.0, 5.0, 6.0, 1.0]);
        assert_eq!(&second[COLOR..COLOR + 4], &[0.5, 0.25, 0.125, 1.0], "a shared colour");
        assert_eq!(&second[NORMAL..NORMAL + 3], &[0.0, 0.0, 1.0], "the initial normal");
        assert_eq!(second[FOG_COORD], 9.0);
        assert_eq!(&second[TEXCOORD..TEXCOORD + 4], &[0.0, 0.0, 0.0, 1.0], "unit 0 had none");
        assert_eq!(&second[TEXCOORD + 4..TEXCOORD + 8], &[7.0, 8.0, 0.0, 1.0]);
        assert_eq!(&second[INDIRECT..INDIRECT + 4], &[0.0; 4], "no indirect light");
        let mut lit = packed.clone();
        set_indirect(&mut lit, &[[0.1, 0.2, 0.3], [0.4, 0.5, 0.6]]);
        assert_eq!(&get(&lit, 1)[INDIRECT..INDIRECT + 4], &[0.4, 0.5, 0.6, 0.0]);
        assert_eq!(&get(&lit, 1)[..INDIRECT], &second[..INDIRECT], "the rest untouched");
    }

    /// Packed vertex `i` of `v` by definition: each attribute's value ([`Attrib::get`]) or
    /// its initial value, at its offset; zero elsewhere.
    fn by_definition(v: &crate::frame::Vertices, i: usize) -> [f32; VERTEX_FLOATS] {
        let mut out = [0.0; VERTEX_FLOATS];
        out[POSITION..POSITION + 4].copy_from_slice(&v.position[i]);
        out[COLOR..COLOR + 4].copy_from_slice(&v.color.get(i).unwrap_or([1.0; 4]));
        out[SECONDARY..SECONDARY + 3].copy_from_slice(&v.secondary_color.get(i).unwrap_or([0.0; 3]));
        out[NORMAL..NORMAL + 3].copy_from_slice(&v.normal.get(i).unwrap_or([0.0, 0.0, 1.0]));
        out[FOG_COORD] = v.fog_coord.get(i).unwrap_or(0.0);
        for unit in 0..MAX_UNITS {
            let t = v.texcoords.get(unit).and_then(|t| t.get(i)).unwrap_or([0.0, 0.0, 0.0, 1.0]);
            out[TEXCOORD + 4 * unit..TEXCOORD + 4 * unit + 4].copy_from_slice(&t);
        }
        out
    }

    /// How each of colour, secondary colour, normal, fog coordinate and units 0 to 3 is given
    /// (for [`attrib`]): absent, shared, per vertex or short, every combination with at most
    /// one short attribute (3^8 without a short one, plus each short one).
    pub(crate) fn attribute_cases() -> impl Iterator<Item = [usize; 8]> {
        (0..4usize.pow(8)).map(|code| std::array::from_fn(|a| code / 4usize.pow(a as u32) % 4)).filter(|how: &[usize; 8]| how.iter().filter(|&&h| h == 3).count() <= 1)
    }

    /// An attribute of `n` vertices with no value (`how` 0), one shared value (1), one value
    /// each (2) or fewer values than vertices (3); values made from `seed` by `value` (also
    /// the compact format's tests).
    pub(crate) fn attrib<T: Copy>(how: usize, n: usize, seed: f32, value: impl Fn(f32) -> T) -> Attrib<T> {
        let count = [0, 1, n, n - 1][how];
        Attrib { values: (0..count).map(|i| value(seed + i as f32 * 0.5)).collect() }
    }

    #[test]
    fn every_layout_packs_as_defined() {
        let n = 5;
        let quad = |x: f32| [x, x + 0.125, x + 0.25, x + 0.375];
        let triple = |x: f32| [x, x + 0.125, x + 0.25];
        let (mut specialised, mut general) = (0, 0);
        for how in attribute_cases() {
            let mut draw = Draw::default();
            let v = &mut draw.vertices;
            v.position = (0..n).map(|i| quad(i as f32)).collect();
            v.color = attrib(how[0], n, 10.0, quad);
            v.secondary_color = attrib(how[1], n, 20.0, triple);
            v.normal = attrib(how[2], n, 30.0, triple);
            v.fog_coord = attrib(how[3], n, 40.0, |x| x);
            v.texcoords = (0..MAX_UNITS).map(|u| attrib(how[4 + u], n, 50.0 + 10.0 * u as f32, quad)).collect();
            let columns = Columns::of(&draw.vertices);
            match Common::of(&columns, n) {
                Some(_) => specialised += 1,
                None => general += 1,
            }
            // One float more than the vertices need: left as it was.
            let mut out = vec![-7.0; n * VERTEX_FLOATS + 1];
            pack_into(&draw, &mut out);
            for i in 0..n {
                let packed: Vec<u32> = get(&out, i as u32).iter().map(|f| f.to_bits()).collect();
                let defined: Vec<u32> = by_definition(&draw.vertices, i).iter().map(|f| f.to_bits()).collect();
                assert_eq!(packed, defined, "layout {how:?}, vertex {i}");
            }
            assert_eq!(out[n * VERTEX_FLOATS], -7.0, "layout {how:?}: past the vertices");
        }
        // Colour, normal, units 0 and 1 in any of 3 forms, the others in 2 forms: 3^4 * 2^4.
        assert_eq!(specialised, 81 * 16);
        assert!(general > 0);
    }

    #[test]
    fn packs_as_many_vertices_as_fit() {
        let mut draw = Draw::default();
        draw.vertices.position = vec![[1.0; 4], [2.0; 4], [3.0; 4]];
        draw.vertices.color.values = vec![[0.5; 4], [0.25; 4], [0.125; 4]];
        let mut out = vec![0.0; 2 * VERTEX_FLOATS + 3];
        pack_into(&draw, &mut out);
        assert_eq!(&get(&out, 1)[COLOR..COLOR + 4], &[0.25; 4]);
        assert_eq!(&out[2 * VERTEX_FLOATS..], &[0.0; 3], "no part of a third vertex");
    }

    #[test]
    fn generic_attributes_interleave_with_defaults() {
        let mut draw = Draw::default();
        draw.vertices.position = vec![[0.0; 4], [1.0; 4]];
        draw.vertices.generic = vec![Attrib::default(), Attrib::default(), Attrib { values: vec![[2.0; 4], [3.0; 4]] }];
        let program = ShaderProgram { id: 1, vertex: None, fragment: None, samplers: Vec::new(), attributes: vec![4, 2, 0, 2, 16] };
        let indices = generic_indices(&program);
        assert_eq!(indices, vec![4, 2]);
        let packed = pack_generic(&draw, &indices);
        assert_eq!(packed, vec![0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 2.0, 0.0, 0.0, 0.0, 1.0, 3.0, 3.0, 3.0, 3.0]);
    }

    #[test]
    fn attributes_tile_the_vertex() {
        let mut covered = [false; VERTEX_FLOATS];
        for a in VERTEX_ATTRIBUTES {
            for f in a.offset..a.offset + a.components {
                assert!(!covered[f as usize], "float {f} twice");
                covered[f as usize] = true;
            }
        }
        assert!(covered.iter().all(|&c| c));
    }
}
