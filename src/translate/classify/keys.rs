//! Geometry, texture and state keys (xxh3). A geometry key hashes the object-space positions,
//! the indices, the texture coordinates of unit 0 and the topology as raw bytes, never a
//! matrix: the same mesh drawn elsewhere has the same key. Draws of display lists take their
//! key from a cache filled the first time each list version is drawn, so a list is hashed once
//! per compilation, not every frame.

use std::collections::HashMap;
use std::fmt;

use xxhash_rust::xxh3::Xxh3;

use crate::frame::{Draw, DrawSource};

/// The bytes of a slice of plain numbers (`f32`, `u32`, arrays of them).
pub fn bytes_of<T: Copy>(values: &[T]) -> &[u8] {
    // Safety: only used with arrays of f32/u32 (no padding, every byte initialised); the
    // length is the slice's size in bytes and the alignment of u8 is 1.
    unsafe { std::slice::from_raw_parts(values.as_ptr().cast::<u8>(), std::mem::size_of_val(values)) }
}

/// A hasher that takes formatted text without allocating (for state snapshots with floats,
/// which have no `Hash`).
pub struct HashWriter(pub Xxh3);

impl fmt::Write for HashWriter {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.0.update(s.as_bytes());
        Ok(())
    }
}

/// Hashes the object-space geometry of `draw` (see the module doc).
pub fn geometry_key(draw: &Draw) -> u64 {
    let mut h = Xxh3::new();
    h.update(&[draw.topology as u8]);
    h.update(&(draw.vertices.len() as u64).to_le_bytes());
    h.update(bytes_of(&draw.vertices.position));
    h.update(bytes_of(&draw.indices));
    if let Some(t) = draw.vertices.texcoords.first() {
        h.update(bytes_of(&t.values));
    }
    h.digest()
}

/// Hashes the texture names (not their content versions: a lightmap upload keeps the key).
pub fn texture_key(draw: &Draw) -> u64 {
    let mut h = Xxh3::new();
    for t in &draw.textures {
        h.update(&t.as_ref().map_or(u64::MAX, |t| u64::from(t.id)).to_le_bytes());
    }
    h.digest()
}

/// Hashes the state that makes two draws of the same geometry different surfaces: alpha
/// test, culling, polygon mode, lighting on or off, texture environments. Colours, material
/// values and fog, which change without changing the surface, are left out.
pub fn state_key(draw: &Draw) -> u64 {
    use fmt::Write as _;
    let s = &draw.state;
    let mut w = HashWriter(Xxh3::new());
    let _ = write!(
        w,
        "{:?}{:?}{:?}{:?}{}{:?}",
        s.alpha_test.map(|a| a.0),
        s.cull,
        s.front_face,
        s.polygon_mode,
        s.lighting.is_some(),
        draw.texture_units
    );
    w.0.digest()
}

/// [`state_key`] remembered for the last state seen: consecutive draws mostly share their
/// state, and formatting it is the costly part.
#[derive(Default)]
pub struct StateKeys {
    last: Option<(std::sync::Arc<crate::frame::RasterState>, Vec<Option<crate::frame::TextureUnit>>, u64)>,
}

impl StateKeys {
    /// The state key of `draw`.
    pub fn key(&mut self, draw: &Draw) -> u64 {
        if let Some((state, units, key)) = &self.last
            && (std::sync::Arc::ptr_eq(state, &draw.state) || **state == *draw.state)
            && *units == draw.texture_units
        {
            return *key;
        }
        let key = state_key(draw);
        self.last = Some((draw.state.clone(), draw.texture_units.clone(), key));
        key
    }
}

/// Combines keys into one.
pub fn combine(keys: &[u64]) -> u64 {
    xxhash_rust::xxh3::xxh3_64(bytes_of(keys))
}

/// What identifies a display-list draw's geometry in the cache: its list version and its
/// place among the draws of that list in the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct ListSlot {
    name: u32,
    version: u64,
    ordinal: u32,
}

/// A cached key with what must still hold for it to apply (the list's draw can have merged
/// with another call of the same list, or taken attributes set outside the list).
#[derive(Clone, Copy, Debug)]
struct Cached {
    vertices: usize,
    indices: usize,
    first: [f32; 4],
    key: u64,
    used: u64,
}

/// Geometry keys of display-list draws, per list version.
#[derive(Default)]
pub struct ListKeys {
    cache: HashMap<ListSlot, Cached>,
    ordinals: HashMap<u32, u32>,
    frame: u64,
    /// Keys computed (cache misses) since the start.
    pub computed: u64,
}

/// The version of each display list `frame` draws from, read from the share group's `lists`
/// up front so that its lock is not held while the frame is classified.
pub fn list_versions(frame: &crate::frame::Frame, lists: &crate::translate::lists::ListTable) -> Vec<(u32, Option<u64>)> {
    let mut versions: Vec<(u32, Option<u64>)> = Vec::new();
    for draw in &frame.draws {
        if let DrawSource::List(name) = draw.source
            && !versions.iter().any(|v| v.0 == name)
        {
            versions.push((name, lists.version(name)));
        }
    }
    versions
}

/// Frames a cached key survives without being used.
const KEEP_FRAMES: u64 = 600;

impl ListKeys {
    /// Starts frame `frame`.
    pub fn begin_frame(&mut self, frame: u64) {
        self.frame = frame;
        self.ordinals.clear();
        if frame.is_multiple_of(KEEP_FRAMES) {
            self.cache.retain(|_, c| frame.saturating_sub(c.used) < KEEP_FRAMES);
        }
    }

    /// The geometry key of `draw`: from the cache for a display-list draw (`version` is the
    /// list's version, see `ListTable::version`), hashed otherwise.
    pub fn key(&mut self, draw: &Draw, version: impl FnOnce(u32) -> Option<u64>) -> u64 {
        let DrawSource::List(name) = draw.source else { return geometry_key(draw) };
        let Some(version) = version(name) else { return geometry_key(draw) };
        let ordinal = self.ordinals.entry(name).or_insert(0);
        let slot = ListSlot { name, version, ordinal: *ordinal };
        *ordinal += 1;
        let first = draw.vertices.position.first().copied().unwrap_or_default();
        let (vertices, indices, frame) = (draw.vertices.len(), draw.indices.len(), self.frame);
        if let Some(c) = self.cache.get_mut(&slot)
            && (c.vertices, c.indices, c.first) == (vertices, indices, first)
        {
            c.used = frame;
            return c.key;
        }
        self.computed += 1;
        let key = geometry_key(draw);
        self.cache.insert(slot, Cached { vertices, indices, first, key, used: frame });
        key
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn triangle(offset: f32) -> Draw {
        let mut d = Draw::default();
        d.vertices.position = vec![[offset, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]];
        d.vertex_count = 3;
        d.indices = vec![0, 1, 2];
        d
    }

    #[test]
    fn geometry_key_ignores_matrices_and_sees_vertices() {
        let (a, mut b) = (triangle(0.0), triangle(0.0));
        b.modelview = glam::Mat4::from_translation(glam::Vec3::X);
        assert_eq!(geometry_key(&a), geometry_key(&b), "matrices are not hashed");
        assert_ne!(geometry_key(&a), geometry_key(&triangle(0.5)));
        let mut c = triangle(0.0);
        c.indices = vec![0, 2, 1];
        assert_ne!(geometry_key(&a), geometry_key(&c), "indices are hashed");
        let mut t = triangle(0.0);
        t.vertices.texcoords = vec![crate::frame::Attrib { values: vec![[0.5, 0.0, 0.0, 1.0]] }];
        assert_ne!(geometry_key(&a), geometry_key(&t), "texture coordinates are hashed");
        let mut l = triangle(0.0);
        l.topology = crate::frame::Topology::Points;
        assert_ne!(geometry_key(&a), geometry_key(&l), "topology is hashed");
    }

    #[test]
    fn state_keys_follow_the_state() {
        let mut keys = StateKeys::default();
        let a = triangle(0.0);
        let mut b = triangle(0.0);
        b.state = std::sync::Arc::new(crate::frame::RasterState { cull: Some(crate::frame::state::Face::Back), ..Default::default() });
        let mut c = triangle(0.0);
        c.texture_units = vec![Some(crate::frame::TextureUnit::default())];
        let (ka, kb, kc) = (keys.key(&a), keys.key(&b), keys.key(&c));
        assert_eq!((ka, kb, kc), (state_key(&a), state_key(&b), state_key(&c)));
        assert!(ka != kb && kb != kc && ka != kc);
        assert_eq!(keys.key(&triangle(5.0)), ka, "equal states, other vertices");
    }

    #[test]
    fn list_draws_are_hashed_once_per_version() {
        let mut keys = ListKeys::default();
        let mut d = triangle(0.0);
        d.source = DrawSource::List(3);
        keys.begin_frame(1);
        let k = keys.key(&d, |_| Some(7));
        keys.begin_frame(2);
        assert_eq!(keys.key(&d, |_| Some(7)), k);
        assert_eq!(keys.computed, 1, "the second frame used the cache");
        let moved = triangle(2.0);
        let mut recompiled = moved.clone();
        recompiled.source = DrawSource::List(3);
        keys.begin_frame(3);
        assert_eq!(keys.key(&recompiled, |_| Some(8)), geometry_key(&moved), "a new version is hashed again");
        keys.begin_frame(4);
        assert_eq!(keys.key(&recompiled, |_| Some(8)), geometry_key(&moved));
        assert_eq!(keys.key(&recompiled, |_| Some(8)), geometry_key(&moved), "second draw of the list in a frame");
        assert_eq!(keys.computed, 3);
    }
}
