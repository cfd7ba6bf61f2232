//! The persistent static world: world-space triangles seen unchanged in two frames.
//!
//! PLACEHOLDER (branch `classify`): a minimal private copy of the contract agreed with the
//! `world` branch, which owns this file and implements it below the draw level (triangles,
//! anti-culling, release); the lead replaces it by theirs on merge. This copy works per
//! offered draw: a draw's triangles become a chunk when they were offered, unchanged, in the
//! previous frame too, and chunks are kept until [`StaticWorld::clear`].

use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use crate::frame::TextureRef;
use crate::frame::world::StaticChunk;

/// World-space triangles of one opaque draw whose vertices are in the world frame.
pub struct WorldTriangles<'a> {
    /// Material key.
    pub material: u64,
    /// Texture of the material.
    pub texture: Option<&'a TextureRef>,
    /// World-space positions, 3 per triangle.
    pub positions: &'a [[f32; 3]],
    /// 3 texture coordinates per triangle.
    pub texcoords: Option<&'a [[f32; 2]]>,
}

/// What the static world made of an offer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Offered {
    /// Triangles the static world holds.
    pub static_triangles: usize,
    /// Triangles it did not hold before.
    pub new_triangles: usize,
}

/// The static world after a frame.
#[derive(Clone, Debug, Default)]
pub struct WorldUpdate {
    /// Every chunk.
    pub chunks: Arc<[Arc<StaticChunk>]>,
    /// Chunks made this frame.
    pub new_chunks: usize,
    /// Chunks kept.
    pub reused_chunks: usize,
    /// Chunks released.
    pub released_chunks: usize,
    /// Bytes of the new chunks.
    pub upload_bytes: u64,
    /// Triangles in all chunks.
    pub triangles: usize,
}

/// The persistent static world.
#[derive(Default)]
pub struct StaticWorld {
    chunks: HashMap<u64, Arc<StaticChunk>>,
    offered_before: HashSet<u64>,
    offered_now: HashSet<u64>,
    new_chunks: usize,
    upload_bytes: u64,
    released: usize,
}

impl StaticWorld {
    /// An empty world.
    pub fn new() -> Self {
        Self::default()
    }

    /// Starts a frame seen through `world_to_clip`.
    pub fn begin_frame(&mut self, _frame: u64, _world_to_clip: glam::Mat4) {
        self.offered_before = std::mem::take(&mut self.offered_now);
        (self.new_chunks, self.upload_bytes, self.released) = (0, 0, 0);
    }

    /// Offers the triangles of one draw.
    pub fn offer(&mut self, t: WorldTriangles<'_>) -> Offered {
        let mut h = xxhash_rust::xxh3::Xxh3::new();
        h.update(&t.material.to_le_bytes());
        h.update(crate::translate::classify::keys::bytes_of(t.positions));
        let key = h.digest();
        let triangles = t.positions.len() / 3;
        self.offered_now.insert(key);
        if self.chunks.contains_key(&key) {
            return Offered { static_triangles: triangles, new_triangles: 0 };
        }
        if !self.offered_before.contains(&key) {
            return Offered::default();
        }
        let chunk = StaticChunk {
            id: key,
            material: t.material,
            texture: t.texture.cloned(),
            positions: t.positions.to_vec(),
            texcoords: t.texcoords.map(<[_]>::to_vec).unwrap_or_default(),
        };
        self.upload_bytes += (chunk.positions.len() * 12 + chunk.texcoords.len() * 8) as u64;
        self.new_chunks += 1;
        self.chunks.insert(key, Arc::new(chunk));
        Offered { static_triangles: triangles, new_triangles: triangles }
    }

    /// Ends the frame: the chunks to render.
    pub fn end_frame(&mut self) -> WorldUpdate {
        let mut chunks: Vec<Arc<StaticChunk>> = self.chunks.values().cloned().collect();
        chunks.sort_by_key(|c| c.id);
        WorldUpdate {
            triangles: chunks.iter().map(|c| c.positions.len() / 3).sum(),
            chunks: chunks.into(),
            new_chunks: self.new_chunks,
            reused_chunks: self.chunks.len() - self.new_chunks,
            released_chunks: self.released,
            upload_bytes: self.upload_bytes,
        }
    }

    /// Forgets everything (camera cut, level change).
    pub fn clear(&mut self) {
        self.released += self.chunks.len();
        self.chunks.clear();
        self.offered_before.clear();
        self.offered_now.clear();
    }
}
