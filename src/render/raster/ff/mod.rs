//! The fixed-function pipeline of OpenGL 1.x as one pair of "uber" shaders specialised per draw
//! (the gl4es approach: a compact key of the state selects the code, here through SPIR-V
//! specialisation constants instead of generated source).
//!
//! [`prepare`] turns a [`Draw`] into [`Batch`]es: the shader key ([`key`]), and the
//! primitives Vulkan cannot rasterize as OpenGL does converted to triangles ([`convert`]:
//! polygon modes, wide and stippled lines, points). The uniform block ([`uniforms::block`])
//! is the draw's, the same for all its batches: the renderer writes it once per draw. A draw whose
//! vertex stage is an OpenGL 2.0 program's is not converted: [`native`] makes its batches.
//! The draw's own vertices and indices are not copied here: the renderer packs them
//! ([`compact::pack_into`] in the draw's [`VertexFormat`], or [`vertex::pack_into`]) and
//! rotates them ([`BatchIndices::write`]) straight into upload memory.
//!
//! The contract with the Vulkan side (`render::raster` device code):
//! - vertices are laid out as their [`VertexFormat`] says (part of the pipeline key): the
//!   vertex input is [`VertexFormat::bindings`] and [`VertexFormat::attributes`]; in the full
//!   layout, interleaved `f32`s, [`VERTEX_FLOATS`] per vertex, with the attributes of
//!   [`VERTEX_ATTRIBUTES`]; in a compact one, the per-vertex attributes at binding 0 and one
//!   full-layout vertex of the shared values ([`compact::shared`]) at
//!   [`compact::SHARED_BINDING`], stride 0;
//! - descriptor set 0: binding 0 is a dynamic uniform buffer holding the draw's
//!   [`uniforms::block`] (std140, exactly [`UNIFORM_SIZE`] bytes), visible to both stages, after
//!   [`uniforms::set_framebuffer_height`] wrote the height of the render target into them;
//!   texture unit `u` (0..[`MAX_UNITS`](crate::render::texenv::codes::MAX_UNITS)) is a `sampler2D` at binding `1 + u` (1D textures are
//!   2D textures one texel high), a `sampler3D` at `5 + u` and a `samplerCube` at `9 + u`;
//!   unused bindings hold a 1×1 white texture. Depth textures hold the depth in the red
//!   channel (their RGBA8 texels already do); the shader compares and expands them, so their
//!   samplers have no compare op;
//! - specialisation constant `i` is word `i` of [`ShaderKey::words`] ([`key::WORDS`] words);
//! - the pipeline enables `shaderClipDistance` with `gl_ClipDistance[6]` written by
//!   `ff.vert` (planes not enabled get 1);
//! - [`Batch::topology`] is a list topology (`*_LIST`; points and lines arrive expanded to
//!   triangles, except from [`native`]); the provoking vertex is already placed first
//!   (Vulkan's default), so no extension is needed for flat shading;
//! - per draw, the renderer writes the render target's height with
//!   [`uniforms::set_framebuffer_height`] (the polygon stipple needs it); per batch, it culls with
//!   [`Batch::cull`] (not `RasterState::cull`: lines and points arrive as triangles of either
//!   winding) and enables depth bias by [`Batch::polygon_offset`];
//! - the viewport has a negative height (window y up as in GL, no flip in the shader), the
//!   front face is set from [`crate::frame::RasterState::front_face`] for that viewport so
//!   that `gl_FrontFacing` is OpenGL's facing, culling is [`Batch::cull`] (not the state's),
//!   depth bias (the state's polygon offset) only where [`Batch::polygon_offset`] is set; line
//!   width stays 1 and no point size or wide-line feature is needed, except for [`native`]
//!   batches (the state's line width, `gl_PointSize`, [`Batch::polygon_mode`]).

pub mod compact;
pub mod convert;
pub mod indices;
pub mod key;
pub mod native;
pub mod shader_interface;
pub mod uniforms;
pub mod vertex;

pub use compact::VertexFormat;
pub use indices::BatchIndices;
pub use key::ShaderKey;
pub use vertex::{VERTEX_ATTRIBUTES, VERTEX_FLOATS, VertexAttribute};

use crate::frame::state::{Face, PolygonMode, StencilFaces};
use crate::frame::{Draw, Topology};

/// Size of the uniform block every batch carries, in bytes.
pub const UNIFORM_SIZE: usize = size_of::<uniforms::FfBlock>();

/// The SPIR-V of the vertex shader: with every varying, or the lean one ([`ShaderKey::lean`]).
pub fn vertex_spirv(lean: bool) -> &'static [u8] {
    if lean {
        include_bytes!(concat!(env!("OUT_DIR"), "/shaders/ff_lean.vert.spv"))
    } else {
        include_bytes!(concat!(env!("OUT_DIR"), "/shaders/ff.vert.spv"))
    }
}

/// The SPIR-V of the fragment shader: with every varying, or the lean one ([`ShaderKey::lean`]).
pub fn fragment_spirv(lean: bool) -> &'static [u8] {
    if lean {
        include_bytes!(concat!(env!("OUT_DIR"), "/shaders/ff_lean.frag.spv"))
    } else {
        include_bytes!(concat!(env!("OUT_DIR"), "/shaders/ff.frag.spv"))
    }
}

/// What the Vulkan side draws for (part of) one [`Draw`], in order: the batches of a draw
/// may overlap (filled faces, then edges) and are drawn in the order [`prepare`] returns.
#[derive(Clone, Debug, PartialEq)]
pub struct Batch {
    /// A list topology: [`Topology::Triangles`] (lines and points arrive expanded) but for
    /// [`native`] batches.
    pub topology: Topology,
    /// How triangles are rasterized: [`PolygonMode::Fill`] but for [`native`] batches.
    pub polygon_mode: PolygonMode,
    /// Its vertices.
    pub vertices: BatchVertices,
    /// The generic attributes of a program's vertex stage ([`vertex::pack_generic`]; empty
    /// without one).
    pub generic: Vec<f32>,
    /// Indices into `vertices`, the provoking vertex first in each primitive.
    pub indices: BatchIndices,
    /// The shader specialisation.
    pub shader: ShaderKey,
    /// Faces the rasterizer culls: the draw's culling for triangles it still faces itself,
    /// `None` for geometry the CPU already culled or expanded.
    pub cull: Option<Face>,
    /// Whose colours and stencil state: the rasterizer's facing for filled triangles, or the
    /// one face of expanded lines, points and polygon edges and vertices.
    pub facing: key::Facing,
    /// Whether the draw's polygon offset (`RasterState::polygon_offset` factor and units)
    /// applies as depth bias: filled triangles with `GL_POLYGON_OFFSET_FILL`, polygon edges
    /// with `..._LINE`, polygon vertices with `..._POINT`; never for `GL_LINES`/`GL_POINTS`.
    pub polygon_offset: bool,
}

/// Where the vertices of a [`Batch`] come from.
#[derive(Clone, Debug, PartialEq)]
pub enum BatchVertices {
    /// The draw's own vertices, packed where they are uploaded ([`compact::pack_into`] in the
    /// draw's [`VertexFormat`], or [`vertex::pack_into`]), once for all the batches of the
    /// draw that use them.
    Draw,
    /// Vertices made for the batch ([`convert`]), packed, [`VERTEX_FLOATS`] per vertex.
    Expanded(Vec<f32>),
}

/// The batches that draw `draw`, in drawing order; `indirect`, one value per vertex, is
/// radiosity's indirect light on a lit draw's vertices, which replaces its ambient term
/// ([`shader_interface::RADIOSITY`]; not for a program's vertex stage). The renderer writes it
/// into the draw's own vertices where it packs them ([`vertex::set_indirect`]); expanded
/// vertices carry it from [`convert`].
pub fn prepare(draw: &Draw, indirect: Option<&[[f32; 3]]>) -> Vec<Batch> {
    if draw.indices.is_empty() || draw.vertices.is_empty() {
        return Vec::new();
    }
    if let Some(program) = draw.program.as_ref().filter(|p| p.program.vertex.is_some()) {
        return native::prepare(draw, program);
    }
    convert::convert(draw, indirect)
        .into_iter()
        .filter(|part| part.indices.len(draw) > 0)
        .map(|part| Batch {
            topology: Topology::Triangles,
            polygon_mode: PolygonMode::Fill,
            vertices: part.vertices.map_or(BatchVertices::Draw, BatchVertices::Expanded),
            generic: Vec::new(),
            indices: part.indices,
            shader: key::shader_key(draw, part.primitive, part.facing).with_radiosity(indirect.is_some()),
            cull: part.cull,
            facing: part.facing,
            polygon_offset: part.polygon_offset,
        })
        .collect()
}

impl Batch {
    /// The stencil state of the rasterizer's front and back faces for this batch: OpenGL's
    /// faces where the rasterizer faces the triangles itself; for expanded primitives, whose
    /// triangles come in either winding, the state of their one face on both (lines and
    /// points are front-facing, OpenGL 2.0 section 4.1.5).
    pub fn stencil(&self, stencil: Option<StencilFaces>) -> Option<StencilFaces> {
        stencil.map(|s| match self.facing {
            key::Facing::Rasterizer => s,
            key::Facing::Front => StencilFaces::both(s.front),
            key::Facing::Back => StencilFaces::both(s.back),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use key::Primitive;

    #[test]
    fn lines_become_triangles() {
        let mut draw = Draw::default();
        draw.vertices.position = vec![[0.0, 0.0, 0.0, 1.0], [0.5, 0.0, 0.0, 1.0]];
        draw.indices = vec![0, 1];
        draw.topology = Topology::Lines;
        let state = crate::frame::RasterState { viewport: [0, 0, 64, 64], ..Default::default() };
        draw.state = std::sync::Arc::new(state);
        let batches = prepare(&draw, None);
        assert_eq!(batches.len(), 1);
        let b = &batches[0];
        let BatchVertices::Expanded(vertices) = &b.vertices else { panic!("lines are expanded") };
        assert_eq!((b.topology, b.indices.len(&draw), vertices.len()), (Topology::Triangles, 6, 4 * VERTEX_FLOATS));
        assert_eq!(shader_interface::PRIMITIVE.get(b.shader.words[key::GENERAL]), Primitive::Line as u32);
    }

    #[test]
    fn filled_triangles_keep_their_vertices() {
        let mut draw = Draw::default();
        draw.vertices.position = vec![[0.0; 4], [1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]];
        draw.indices = vec![0, 1, 2];
        let b = &prepare(&draw, None)[0];
        assert_eq!((&b.vertices, &b.indices), (&BatchVertices::Draw, &BatchIndices::Draw { per: 3 }));
        let mut indices = [0; 3];
        b.indices.write(&draw, &mut indices);
        assert_eq!(indices, [2, 0, 1]);
        assert!(prepare(&Draw::default(), None).is_empty());
        // With radiosity's indirect light: in the key (the renderer writes the vertices).
        let lit = &prepare(&draw, Some(&[[0.5; 3], [0.25; 3], [0.0; 3]]))[0];
        assert_eq!(shader_interface::RADIOSITY.get(lit.shader.words[key::CLIP]), 1);
        assert_eq!(shader_interface::RADIOSITY.get(b.shader.words[key::CLIP]), 0);
        draw.indices.truncate(2);
        assert!(prepare(&draw, None).is_empty(), "no whole triangle");
    }
}
