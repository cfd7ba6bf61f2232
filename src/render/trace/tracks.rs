//! Dynamic instances across frames: the geometry each `Dynamic` draw had when last traced, so
//! that its next shape refits that BVH ([`super::resident::NewGeometry::refit_from`]) instead
//! of building a new one.
//!
//! Hash tracking gives a dynamic draw the same instance id from frame to frame when it matches
//! by slot (same textures, state, vertex and index counts, order of appearance: an animated
//! mesh whose vertices moved). A refit keeps the tree, so it is offered only when the index
//! list is the same as well (hashed here): then the triangles are the same ones, moved, and
//! the tree stays a good one until the shape drifts far (the resident cache checks its SAH
//! cost).

use std::collections::HashMap;

use xxhash_rust::xxh3::xxh3_64;

use crate::frame::Draw;
use crate::frame::class::DrawClass;

/// Frames a track stays without its instance being traced.
const KEEP_FRAMES: u64 = super::resident::KEEP_FRAMES;

/// The last traced geometry of one dynamic instance.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Track {
    /// Its geometry key in the resident cache.
    key: u64,
    /// Hash of its index list and vertex count.
    topology: u64,
    /// Frame it was traced in.
    frame: u64,
}

/// The tracks of the dynamic instances, by instance id.
#[derive(Debug, Default)]
pub struct Tracks {
    tracks: HashMap<u64, Track>,
}

/// Hash of what a refit keeps: the index list and the vertex count.
fn topology(draw: &Draw) -> u64 {
    xxh3_64(bytemuck::cast_slice(&draw.indices)) ^ (draw.vertices.len() as u64).rotate_left(32)
}

/// The instance id of a dynamic draw.
fn dynamic_id(draw: &Draw) -> Option<u64> {
    draw.instance.filter(|_| draw.class == DrawClass::Dynamic).map(|i| i.id)
}

impl Tracks {
    /// The geometry that `draw`'s new geometry can refit: its instance's last one, when the
    /// draw is dynamic and its index list is unchanged.
    pub fn refit_source(&self, draw: &Draw) -> Option<u64> {
        let track = self.tracks.get(&dynamic_id(draw)?)?;
        (track.topology == topology(draw)).then_some(track.key)
    }

    /// Records that `draw` (if dynamic) was traced in `frame` with geometry `key`.
    pub fn record(&mut self, draw: &Draw, key: u64, frame: u64) {
        if let Some(id) = dynamic_id(draw) {
            self.tracks.insert(id, Track { key, topology: topology(draw), frame });
        }
    }

    /// Forgets the instances not traced for [`KEEP_FRAMES`] frames before `frame`.
    pub fn prune(&mut self, frame: u64) {
        self.tracks.retain(|_, t| frame.saturating_sub(t.frame) < KEEP_FRAMES);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::class::Instance;

    fn dynamic(id: u64, indices: Vec<u32>) -> Draw {
        let mut draw = Draw { indices, class: DrawClass::Dynamic, instance: Some(Instance { id, ..Instance::default() }), ..Draw::default() };
        draw.vertices.position = vec![[0.0, 0.0, 0.0, 1.0]; 4];
        draw
    }

    #[test]
    fn a_dynamic_instance_refits_its_last_geometry_while_its_indices_stay() {
        let mut tracks = Tracks::default();
        let draw = dynamic(7, vec![0, 1, 2, 0, 2, 3]);
        assert_eq!(tracks.refit_source(&draw), None);
        tracks.record(&draw, 100, 1);
        assert_eq!(tracks.refit_source(&draw), Some(100));
        assert_eq!(tracks.refit_source(&dynamic(8, vec![0, 1, 2, 0, 2, 3])), None, "another instance");
        assert_eq!(tracks.refit_source(&dynamic(7, vec![0, 1, 2, 1, 2, 3])), None, "other triangles");
        let mut moved = dynamic(7, vec![0, 1, 2, 0, 2, 3]);
        moved.class = DrawClass::Movable;
        assert_eq!(tracks.refit_source(&moved), None, "only dynamic draws refit");
        tracks.record(&moved, 200, 2);
        assert_eq!(tracks.refit_source(&draw), Some(100), "a movable draw leaves no track");
        tracks.prune(KEEP_FRAMES);
        assert_eq!(tracks.refit_source(&draw), Some(100), "kept {KEEP_FRAMES} frames");
        tracks.prune(1 + KEEP_FRAMES);
        assert_eq!(tracks.refit_source(&draw), None);
    }
}
