//! The persistent static world handed to the renderer: world-space triangles of one material
//! grouped into chunks that, once built, never change (`translate::classify::static_world`
//! builds them). A renderer uploads a chunk and builds its acceleration structure once, keyed
//! by [`StaticChunk::id`], and frees it when the chunk leaves the list.

use std::sync::Arc;

use super::class::MaterialOverride;
use super::{RasterState, TextureRef, TextureUnit};

/// Texture units a chunk carries (units 0 and 1: a surface texture and a lightmap or detail
/// texture over it, as the tracer's materials take them).
pub const CHUNK_UNITS: usize = 2;

/// How a chunk's triangles are shaded besides their textures and material: the state of the
/// draw that offered the chunk's first triangle. The static world's material key hashes the
/// parts of it that split chunks (alpha test function, culling, lighting on or off, texture
/// environments, light units); the rest (the lit material's colours, the alpha reference) is
/// that draw's.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ChunkShading {
    /// Raster state of the draw.
    pub state: Arc<RasterState>,
    /// Texture environment of each carried unit (`None`: the unit not enabled).
    pub texture_units: [Option<TextureUnit>; CHUNK_UNITS],
    /// The units whose texture holds baked light (bit `u`: unit `u`), as
    /// [`super::class::Instance::light_units`] of the draw.
    pub light_units: u8,
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
    /// Texture of each carried unit.
    pub textures: [Option<TextureRef>; CHUNK_UNITS],
    /// World-space positions, 3 per triangle, with the program's winding.
    pub positions: Vec<[f32; 3]>,
    /// Texture coordinates of each carried unit after its texture matrix: empty, or 3 per
    /// triangle.
    pub texcoords: [Vec<[f32; 2]>; CHUNK_UNITS],
    /// Primary colours, unorm8 RGBA: empty (every corner opaque white), or 3 per triangle.
    pub colors: Vec<[u8; 4]>,
    /// Draw state the triangles are shaded with.
    pub shading: ChunkShading,
    /// The cell of the world's spatial grid its triangles were grouped in (chunks of one
    /// cell lie close together: a renderer may merge them, as the tracers' regions do).
    pub cell: [i32; 3],
}

impl StaticChunk {
    /// Triangle count.
    pub fn triangles(&self) -> usize {
        self.positions.len() / 3
    }

    /// Bytes a renderer uploads for this chunk: positions (12 per vertex), texture
    /// coordinates (8 per vertex and unit) and colours (4 per vertex).
    pub fn upload_bytes(&self) -> u64 {
        let texcoords: usize = self.texcoords.iter().map(Vec::len).sum();
        (self.positions.len() * 12 + texcoords * 8 + self.colors.len() * 4) as u64
    }
}
