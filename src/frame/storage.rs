//! Vertex storage recycled between frames: the vertices, indices and edge masks of the draws
//! of frames a sink is done with go back to the context that assembles frames
//! ([`crate::frame::FrameSink::spent_storage`]), which fills them again. A frame of millions of
//! vertices then writes into memory it already touched instead of faulting in fresh pages
//! (which the kernel zero-fills) every frame: allocations that large are mapped and unmapped
//! by the allocator at each frame.

use std::mem::size_of;

use glam::Mat4;

use super::{Attrib, Frame, TextureRef, TextureUnit, Vertices};

/// The storage of one draw: empty, with the capacity it had.
#[derive(Debug, Default)]
pub struct DrawStorage {
    /// Vertex attributes.
    pub vertices: Vertices,
    /// Indices.
    pub indices: Vec<u32>,
    /// Edge masks.
    pub edge_masks: Vec<u8>,
    /// The per-unit lists of a draw (a few entries each, kept so that a new draw allocates
    /// none of them).
    pub texture_matrices: Vec<Option<Mat4>>,
    /// See `texture_matrices`.
    pub textures: Vec<Option<TextureRef>>,
    /// See `texture_matrices`.
    pub texture_units: Vec<Option<TextureUnit>>,
}

impl DrawStorage {
    /// Bytes its vectors hold allocated.
    pub fn capacity_bytes(&self) -> usize {
        fn attrib<T>(a: &Attrib<T>) -> usize {
            a.values.capacity() * size_of::<T>()
        }
        let v = &self.vertices;
        let units: usize = v.texcoords.iter().chain(&v.generic).map(attrib).sum();
        v.position.capacity() * size_of::<[f32; 4]>()
            + attrib(&v.normal)
            + attrib(&v.color)
            + attrib(&v.secondary_color)
            + attrib(&v.fog_coord)
            + attrib(&v.color_index)
            + units
            + self.indices.capacity() * size_of::<u32>()
            + self.edge_masks.capacity()
    }
}

/// Spare draw storage, up to a number of bytes of capacity; what would pass that is freed.
#[derive(Debug)]
pub struct StoragePool {
    /// Spare storage, emptied, the largest last.
    spare: Vec<DrawStorage>,
    /// Capacity bytes of `spare`.
    bytes: usize,
    /// The most it keeps.
    limit: usize,
}

impl Default for StoragePool {
    /// A pool that keeps up to [`StoragePool::DEFAULT_LIMIT`] bytes of capacity.
    fn default() -> StoragePool {
        StoragePool::new(StoragePool::DEFAULT_LIMIT)
    }
}

impl StoragePool {
    /// The limit of [`StoragePool::default`]: that of [`StoragePool::for_budget`] for the
    /// default frame budget (256 MB, `translate::frame_memory`).
    pub const DEFAULT_LIMIT: usize = 2 * (256 << 20);

    /// An empty pool that keeps up to `limit` bytes of capacity.
    pub fn new(limit: usize) -> StoragePool {
        StoragePool { spare: Vec::new(), bytes: 0, limit }
    }

    /// An empty pool that keeps the storage of frames (or frame parts) of up to `budget` bytes
    /// of vertices, indices and edge masks: twice the budget of capacity, as the vectors of a
    /// draw grown batch by batch double their capacity and so hold up to twice what they store
    /// (a draw merged up to its most vertices, 4 M, holds about 1.5 times). With less, the
    /// largest draws of a frame of millions of vertices were freed at every frame and mapped
    /// and faulted in again at the next.
    pub fn for_budget(budget: usize) -> StoragePool {
        StoragePool::new(budget.saturating_mul(2))
    }

    /// Bytes of capacity it holds.
    pub fn bytes(&self) -> usize {
        self.bytes
    }

    /// Number of draws' storage it holds.
    pub fn len(&self) -> usize {
        self.spare.len()
    }

    /// Whether it holds nothing.
    pub fn is_empty(&self) -> bool {
        self.spare.is_empty()
    }

    /// Keeps the storage of `frame`'s draws; the rest of the frame is dropped now.
    pub fn keep_frame(&mut self, frame: Frame) {
        for draw in frame.draws {
            self.keep(DrawStorage {
                vertices: draw.vertices,
                indices: draw.indices,
                edge_masks: draw.edge_masks,
                texture_matrices: draw.texture_matrices,
                textures: draw.textures,
                texture_units: draw.texture_units,
            });
        }
    }

    /// Keeps `storage`, emptied, unless the pool would pass its limit (it is freed then).
    pub fn keep(&mut self, mut storage: DrawStorage) {
        let bytes = storage.capacity_bytes();
        if bytes == 0 || self.bytes + bytes > self.limit {
            return;
        }
        storage.vertices.clear();
        storage.indices.clear();
        storage.edge_masks.clear();
        storage.texture_matrices.clear();
        storage.textures.clear();
        storage.texture_units.clear();
        self.bytes += bytes;
        self.spare.push(storage);
    }

    /// Moves what `other` holds into this pool (up to its limit), the largest storage to be
    /// taken first.
    pub fn refill(&mut self, other: &mut StoragePool) {
        other.bytes = 0;
        for storage in other.spare.drain(..) {
            self.keep(storage);
        }
        // Each storage's size summed once, not at every comparison (a frame gives back
        // hundreds of draws' storage).
        self.spare.sort_by_cached_key(DrawStorage::capacity_bytes);
    }

    /// Empty storage for a new draw: the largest kept, or new.
    pub fn take(&mut self) -> DrawStorage {
        match self.spare.pop() {
            Some(storage) => {
                self.bytes -= storage.capacity_bytes();
                storage
            }
            None => DrawStorage::default(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Draw;

    fn draw(vertices: usize) -> Draw {
        let mut draw = Draw::default();
        draw.vertices.position = vec![[1.0; 4]; vertices];
        draw.vertices.texcoords = vec![Attrib { values: vec![[0.5; 4]; vertices] }];
        draw.indices = (0..vertices as u32).collect();
        draw.vertex_count = vertices;
        draw
    }

    #[test]
    fn storage_comes_back_empty_with_its_capacity_largest_first() {
        let mut spent = StoragePool::default();
        spent.keep_frame(Frame { draws: vec![draw(1000), draw(10), draw(100)], ..Frame::default() });
        assert_eq!(spent.len(), 3);
        let mut pool = StoragePool::default();
        pool.refill(&mut spent);
        assert_eq!((spent.len(), spent.bytes()), (0, 0));
        assert_eq!(pool.bytes(), (1000 + 10 + 100) * (16 + 16 + 4));
        let first = pool.take();
        assert!(first.vertices.is_empty() && first.indices.is_empty());
        assert_eq!(first.vertices.texcoords.len(), 1, "the attributes keep their storage");
        assert!(first.vertices.position.capacity() >= 1000 && first.indices.capacity() >= 1000);
        assert_eq!(pool.take().indices.capacity(), 100);
        assert_eq!(pool.take().indices.capacity(), 10);
        assert_eq!(pool.bytes(), 0);
        assert!(pool.take().indices.capacity() == 0, "then new storage");
    }

    #[test]
    fn a_pool_keeps_a_budget_of_draws_grown_batch_by_batch() {
        // A frame part as a frame of immediate-mode batches of 3000 vertices leaves it: its draws
        // grew by appending until they held up to the budget (vertices, indices, edge masks).
        let budget = 4 << 20;
        let mut batch = Vertices::with_units(1);
        batch.position = vec![[1.0; 4]; 3000];
        batch.color.values = (0..3000).map(|i| [i as f32; 4]).collect();
        batch.texcoords[0].values = (0..3000).map(|i| [i as f32; 4]).collect();
        let mut frame = Frame::default();
        let mut stored = 0;
        while stored < budget {
            let mut draw = Draw::default();
            while draw.vertices.len() < 20_000 && stored < budget {
                draw.vertices.append(&batch);
                draw.indices.extend(0..3000);
                stored += 3000 * (3 * 16 + 4);
            }
            frame.draws.push(draw);
        }
        let draws = frame.draws.len();
        let mut pool = StoragePool::for_budget(budget);
        pool.keep_frame(frame);
        assert_eq!(pool.len(), draws, "every draw's storage kept ({} bytes of capacity)", pool.bytes());
        assert!(pool.bytes() > budget, "capacity beyond what the draws stored: a pool of one budget frees some");
    }

    #[test]
    fn a_pool_frees_what_would_pass_its_limit() {
        let mut pool = StoragePool::new(150 * 36);
        pool.keep_frame(Frame { draws: vec![draw(100), draw(100), draw(10), draw(0)], ..Frame::default() });
        assert_eq!((pool.len(), pool.bytes()), (2, 110 * 36), "the second 100 would pass; no storage at all is not kept");
    }
}
