//! The fixed-function pipeline of OpenGL 1.x as one pair of "uber" shaders specialised per draw
//! (the gl4es approach: a compact key of the state selects the code, here through SPIR-V
//! specialisation constants instead of generated source).
//!
//! The contract with the Vulkan side (`render::raster` device code):
//! - vertices are interleaved `f32`s, [`VERTEX_FLOATS`] per vertex, with the attributes of
//!   [`VERTEX_ATTRIBUTES`];
//! - descriptor set 0: binding 0 is a dynamic uniform buffer holding the [`Batch::uniforms`]
//!   bytes (std140, at most [`UNIFORM_SIZE`] bytes), visible to both stages; texture unit `u`
//!   (0..[`MAX_UNITS`]) is a `sampler2D` at binding `1 + u` (1D textures are 2D textures one
//!   texel high), a `sampler3D` at `5 + u` and a `samplerCube` at `9 + u`; unused bindings hold
//!   a 1×1 white texture;
//! - specialisation constant `i` is word `i` of [`ShaderKey::words`];
//! - [`Batch::topology`] is a list topology (`*_LIST`); the provoking vertex is already placed
//!   first (Vulkan's default), so no extension is needed for flat shading.

use crate::frame::{Draw, Topology};

/// Texture units the shaders implement.
pub const MAX_UNITS: usize = 4;

/// Floats per packed vertex.
pub const VERTEX_FLOATS: usize = 32;

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

/// Position (4), colour (4), secondary colour (4), normal (3), fog coordinate (1), and the
/// texture coordinates of each unit (4 each).
pub const VERTEX_ATTRIBUTES: &[VertexAttribute] = &[
    VertexAttribute { location: 0, components: 4, offset: 0 },
    VertexAttribute { location: 1, components: 4, offset: 4 },
    VertexAttribute { location: 2, components: 4, offset: 8 },
    VertexAttribute { location: 3, components: 3, offset: 12 },
    VertexAttribute { location: 4, components: 1, offset: 15 },
    VertexAttribute { location: 5, components: 4, offset: 16 },
    VertexAttribute { location: 6, components: 4, offset: 20 },
    VertexAttribute { location: 7, components: 4, offset: 24 },
    VertexAttribute { location: 8, components: 4, offset: 28 },
];

/// Largest uniform block a batch carries, in bytes.
pub const UNIFORM_SIZE: usize = 256;

/// The SPIR-V of the vertex shader.
pub fn vertex_spirv() -> &'static [u8] {
    include_bytes!(concat!(env!("OUT_DIR"), "/shaders/ff.vert.spv"))
}

/// The SPIR-V of the fragment shader.
pub fn fragment_spirv() -> &'static [u8] {
    include_bytes!(concat!(env!("OUT_DIR"), "/shaders/ff.frag.spv"))
}

/// The part of a draw's state that selects shader code: one `u32` per specialisation constant.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ShaderKey {
    /// Specialisation constant `i` is `words[i]`.
    pub words: [u32; 1],
}

/// Bits of [`ShaderKey::words`]`[0]`.
mod key0 {
    /// Texture unit `u` samples a 2D texture: bit `u`.
    pub const TEXTURE_2D: u32 = 1;
}

/// What the Vulkan side draws for (part of) one [`Draw`].
#[derive(Clone, Debug, PartialEq)]
pub struct Batch {
    /// A list topology.
    pub topology: Topology,
    /// Packed vertices, [`VERTEX_FLOATS`] per vertex.
    pub vertices: Vec<f32>,
    /// Indices into `vertices`.
    pub indices: Vec<u32>,
    /// The shader specialisation.
    pub shader: ShaderKey,
    /// The std140 uniform block, at most [`UNIFORM_SIZE`] bytes.
    pub uniforms: Vec<u8>,
}

/// The batches that draw `draw`.
pub fn prepare(draw: &Draw) -> Vec<Batch> {
    if draw.indices.is_empty() {
        return Vec::new();
    }
    let mut shader = ShaderKey::default();
    for (unit, texture) in draw.textures.iter().enumerate().take(MAX_UNITS) {
        if texture.is_some() {
            shader.words[0] |= key0::TEXTURE_2D << unit;
        }
    }
    vec![Batch {
        topology: draw.topology,
        vertices: pack_vertices(draw),
        indices: provoking_first(draw.topology, &draw.indices),
        shader,
        uniforms: uniforms(draw),
    }]
}

/// Interleaves the draw's attributes as [`VERTEX_ATTRIBUTES`] lays them out.
fn pack_vertices(draw: &Draw) -> Vec<f32> {
    let v = &draw.vertices;
    let mut out = Vec::with_capacity(v.len() * VERTEX_FLOATS);
    for (i, position) in v.position.iter().enumerate() {
        out.extend_from_slice(position);
        out.extend_from_slice(&v.color.get(i).unwrap_or([1.0; 4]));
        let [r, g, b] = v.secondary_color.get(i).unwrap_or([0.0; 3]);
        out.extend_from_slice(&[r, g, b, 0.0]);
        out.extend_from_slice(&v.normal.get(i).unwrap_or([0.0, 0.0, 1.0]));
        out.push(v.fog_coord.get(i).unwrap_or(0.0));
        for unit in 0..MAX_UNITS {
            let coord = v.texcoords.get(unit).and_then(|t| t.get(i));
            out.extend_from_slice(&coord.unwrap_or([0.0, 0.0, 0.0, 1.0]));
        }
    }
    out
}

/// The draw's indices with each primitive's provoking vertex (last in a [`Draw`]) moved first,
/// keeping the winding: `(a, b, c)` becomes `(c, a, b)`, `(a, b)` becomes `(b, a)`.
fn provoking_first(topology: Topology, indices: &[u32]) -> Vec<u32> {
    match topology {
        Topology::Triangles => indices.chunks_exact(3).flat_map(|t| [t[2], t[0], t[1]]).collect(),
        Topology::Lines => indices.chunks_exact(2).flat_map(|l| [l[1], l[0]]).collect(),
        Topology::Points => indices.to_vec(),
    }
}

/// The std140 uniform block of `ff.vert`/`ff.frag`: the projection × modelview matrix.
fn uniforms(draw: &Draw) -> Vec<u8> {
    let mvp = draw.projection * draw.modelview;
    mvp.to_cols_array().iter().flat_map(|f| f.to_le_bytes()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packs_each_vertex_at_the_declared_offsets() {
        let mut draw = Draw::default();
        draw.vertices.position = vec![[1.0, 2.0, 3.0, 1.0], [4.0, 5.0, 6.0, 1.0]];
        draw.vertices.color.values = vec![[0.5, 0.25, 0.125, 1.0]];
        draw.vertices.texcoords = vec![crate::frame::Attrib { values: vec![[0.0; 4], [7.0, 8.0, 0.0, 1.0]] }];
        draw.indices = vec![0, 1];
        draw.topology = Topology::Lines;
        let batch = &prepare(&draw)[0];
        assert_eq!(batch.vertices.len(), 2 * VERTEX_FLOATS);
        let second = &batch.vertices[VERTEX_FLOATS..];
        assert_eq!(&second[0..4], &[4.0, 5.0, 6.0, 1.0]);
        assert_eq!(&second[4..8], &[0.5, 0.25, 0.125, 1.0]);
        assert_eq!(&second[16..20], &[7.0, 8.0, 0.0, 1.0]);
        assert_eq!(batch.indices, vec![1, 0]);
    }

    #[test]
    fn triangles_keep_winding_with_the_provoking_vertex_first() {
        assert_eq!(provoking_first(Topology::Triangles, &[0, 1, 2, 3, 4, 5]), vec![2, 0, 1, 5, 3, 4]);
    }

    #[test]
    fn uniform_block_fits() {
        assert!(uniforms(&Draw::default()).len() <= UNIFORM_SIZE);
    }
}
