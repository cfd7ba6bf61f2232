//! The persistent static world handed to the renderer: world-space triangles of one material
//! grouped into chunks that, once built, never change (`translate::classify::static_world`
//! builds them). A renderer uploads a chunk and builds its acceleration structure once, keyed
//! by [`StaticChunk::id`], and frees it when the chunk leaves the list.

use std::sync::Arc;

use super::class::MaterialOverride;
use super::{RasterState, TextureRef, TextureUnit};

/// How a chunk's triangles are shaded besides their texture and material: the state of the
/// draw that offered the chunk's first triangle. The static world's material key hashes the
/// parts of it that split chunks (alpha test function, culling, lighting on or off, texture
/// environments); the rest (the lit material's colours, the alpha reference) is that draw's.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ChunkShading {
    /// Raster state of the draw.
    pub state: Arc<RasterState>,
    /// Texture environment of unit 0 (`None`: unit 0 not enabled).
    pub texture_unit: Option<TextureUnit>,
    /// Texture environment of unit 1 when the draw had a texture there (a lightmap, a detail
    /// texture), which chunks do not carry: the tracer decides from it whether the draw is
    /// traced itself instead.
    pub second_unit: Option<TextureUnit>,
}

/// A piece of the persistent static world: world-space triangles of one material, stable
/// while it lives (its id is never given to other content).
#[derive(Clone, Debug, PartialEq)]
pub struct StaticChunk {
    /// Unique for the life of the world that built it.
    pub id: u64,
    /// Hash of the textures, draw state and material the triangles are drawn with.
    pub material_key: u64,
    /// Surface parameters from `glrt.toml` (those of the draws the triangles came from).
    pub material: MaterialOverride,
    /// Texture of the triangles (unit 0).
    pub texture: Option<TextureRef>,
    /// World-space positions, 3 per triangle, with the program's winding.
    pub positions: Vec<[f32; 3]>,
    /// Texture coordinates of unit 0 after its texture matrix: empty, or 3 per triangle.
    pub texcoords: Vec<[f32; 2]>,
    /// Primary colours, unorm8 RGBA: empty (every corner opaque white), or 3 per triangle.
    pub colors: Vec<[u8; 4]>,
    /// Draw state the triangles are shaded with.
    pub shading: ChunkShading,
}

impl StaticChunk {
    /// Triangle count.
    pub fn triangles(&self) -> usize {
        self.positions.len() / 3
    }

    /// Bytes a renderer uploads for this chunk: positions (12 per vertex), texture
    /// coordinates (8 per vertex) and colours (4 per vertex).
    pub fn upload_bytes(&self) -> u64 {
        (self.positions.len() * 12 + self.texcoords.len() * 8 + self.colors.len() * 4) as u64
    }
}
