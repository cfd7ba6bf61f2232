//! The persistent static world as the renderer receives it: stable chunks of world-space
//! triangles that change rarely.
//!
//! PLACEHOLDER (branch `classify`): a minimal private copy of the contract agreed with the
//! `world` branch, which owns this file; the lead replaces it by theirs on merge.

/// A chunk of static world-space triangles of one material.
#[derive(Clone, Debug, PartialEq)]
pub struct StaticChunk {
    /// Stable id.
    pub id: u64,
    /// Material key (texture id and state).
    pub material: u64,
    /// Texture of the material.
    pub texture: Option<crate::frame::TextureRef>,
    /// World-space positions, 3 per triangle.
    pub positions: Vec<[f32; 3]>,
    /// Empty, or 3 texture coordinates per triangle.
    pub texcoords: Vec<[f32; 2]>,
}
