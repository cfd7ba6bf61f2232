//! Merged bottom levels of the static world (issue 21, "merged into larger BLASes per
//! region"): the driver's traversal pays per instance (on the H200 the hardware tracer lost
//! 1.2 ms going from 28 to 268 instances), so the hardware tracer traces the chunks of one
//! region as one instance of one bottom-level structure instead of an instance per chunk.
//!
//! - **Region.** A region is a cube of `size`³ cells of the world's spatial grid (the cells the
//!   static world groups chunks by, [`crate::frame::world::StaticChunk::cell`]), `size` the
//!   `[pathtrace]` key `chunk_regions` (0: no merging, a structure per chunk as before).
//! - **Order.** The tracer sorts its items stably by region (`None`, the surfaces and chunks
//!   traced alone, first), so a region's chunks and their instance records are consecutive.
//! - **Shading.** A region's structure holds one geometry per chunk, in the order of their
//!   instance records; its instance's custom index is the first chunk's record, and the hit
//!   shaders take `gl_InstanceCustomIndexEXT + gl_GeometryIndexEXT` as the instance: each
//!   chunk keeps its own record (material, first triangle, emitters, radiosity), unchanged.
//!   A chunk's geometry is opaque unless it is alpha tested (then its any-hit shader runs),
//!   as the instance flags of an unmerged chunk say.
//! - **Rebuild.** A merged structure is keyed by its members ([`Member`]: geometry key and
//!   opacity, in order): it is built when a run of chunks appears whose members have no
//!   structure (a new chunk in the region, a released one), reused while they stay, and
//!   retired in the first frame that traces merged chunks but not these ([`plan`]; a frame
//!   without the static world keeps them). Other regions keep theirs.

use std::collections::HashMap;
use std::ops::Range;

use xxhash_rust::xxh3::Xxh3;

/// The region of a chunk in `cell`, for regions of `size` cells a side; `None` when `size` is
/// 0 (chunks are not merged).
pub fn region(cell: [i32; 3], size: u32) -> Option<[i32; 3]> {
    let size = i32::try_from(size).ok().filter(|&s| s > 0)?;
    Some(cell.map(|c| c.div_euclid(size)))
}

/// One chunk of a merged structure: the geometry it places and whether it skips the any-hit
/// shader.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Member {
    /// Its resident geometry.
    pub key: u64,
    /// No alpha test.
    pub opaque: bool,
}

/// What [`runs`] reads of one top-level instance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placed {
    /// Its region (`None`: traced as its own instance).
    pub region: Option<[i32; 3]>,
    /// Its index in the frame's instance records.
    pub index: u32,
    /// Rows of its object-to-eye transform.
    pub rows: [[f32; 4]; 3],
}

/// The runs of `instances` merged into one structure each: maximal runs of instances of one
/// region with consecutive record indices and one transform (chunks are all placed by the
/// view; a region of one chunk is a run of one). Instances of no region are in none.
pub fn runs(instances: &[Placed]) -> Vec<Range<usize>> {
    let mut runs = Vec::new();
    let mut start = 0;
    while start < instances.len() {
        let first = instances[start];
        let mut end = start + 1;
        if first.region.is_some() {
            while end < instances.len() {
                let (previous, next) = (instances[end - 1], instances[end]);
                if next.region != first.region || next.index != previous.index + 1 || next.rows != first.rows {
                    break;
                }
                end += 1;
            }
            runs.push(start..end);
        }
        start = end;
    }
    runs
}

/// The key of the merged structure of `members` (in order).
pub fn members_key(members: &[Member]) -> u64 {
    let mut h = Xxh3::new();
    h.update(b"region");
    for m in members {
        h.update(&m.key.to_le_bytes());
        h.update(&[u8::from(m.opaque)]);
    }
    h.digest()
}

/// What to do with the merged structures: `built` holds them by [`members_key`], `wanted` is
/// this frame's runs' keys. Returns the keys to build (wanted, not built, each once) and those
/// to retire (built, not wanted).
pub fn plan<T>(built: &HashMap<u64, T>, wanted: &[u64]) -> (Vec<u64>, Vec<u64>) {
    let mut build: Vec<u64> = Vec::new();
    for &key in wanted {
        if !built.contains_key(&key) && !build.contains(&key) {
            build.push(key);
        }
    }
    let retire = built.keys().copied().filter(|k| !wanted.contains(k)).collect();
    (build, retire)
}

#[cfg(test)]
mod tests {
    use super::*;

    const VIEW: [[f32; 4]; 3] = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, -4.0]];

    #[test]
    fn cells_fall_in_regions_of_size_cells_a_side() {
        assert_eq!(region([0, 1, -1], 2), Some([0, 0, -1]));
        assert_eq!(region([3, -2, -3], 2), Some([1, -1, -2]), "floor division below zero");
        assert_eq!(region([5, 5, 5], 1), Some([5, 5, 5]));
        assert_eq!(region([5, 5, 5], 0), None, "0: no merging");
    }

    #[test]
    fn runs_are_consecutive_records_of_one_region_and_transform() {
        let at = |region: Option<[i32; 3]>, index: u32| Placed { region, index, rows: VIEW };
        let (a, b) = (Some([0, 0, 0]), Some([1, 0, 0]));
        let mut moved = at(b, 7);
        moved.rows[0][3] = 1.0;
        let instances = [at(None, 0), at(None, 1), at(a, 2), at(a, 3), at(a, 4), at(b, 5), at(b, 6), moved, at(b, 9), at(b, 10), at(a, 11)];
        assert_eq!(runs(&instances), [2..5, 5..7, 7..8, 8..10, 10..11], "another region, transform or a gap in the records ends a run");
        assert_eq!(runs(&[at(None, 0), at(a, 1)]), [1..2], "a region of one chunk is a run of one");
    }

    /// The rule of rebuilding: a region's structure is built when its chunks change, and only
    /// then; a region that is gone is retired.
    #[test]
    fn a_region_is_rebuilt_when_its_chunks_change_and_not_otherwise() {
        let m = |key: u64| Member { key, opaque: true };
        let region_a = [m(1), m(2), m(3)];
        let region_b = [m(10), m(11)];
        let mut built: HashMap<u64, ()> = HashMap::new();
        let frame = |built: &mut HashMap<u64, ()>, regions: &[&[Member]]| {
            let wanted: Vec<u64> = regions.iter().map(|r| members_key(r)).collect();
            let (build, retire) = plan(built, &wanted);
            for k in &retire {
                built.remove(k);
            }
            for &k in &build {
                built.insert(k, ());
            }
            (build.len(), retire.len())
        };
        assert_eq!(frame(&mut built, &[&region_a, &region_b]), (2, 0), "first frame: both built");
        assert_eq!(frame(&mut built, &[&region_a, &region_b]), (0, 0), "unchanged: nothing built");
        let grown = [m(1), m(2), m(3), m(4)];
        assert_eq!(frame(&mut built, &[&grown, &region_b]), (1, 1), "a new chunk in A: A rebuilt, its old structure retired, B kept");
        let released = [m(1), m(3), m(4)];
        assert_eq!(frame(&mut built, &[&released, &region_b]), (1, 1), "a released chunk: rebuilt");
        let alpha = [m(1), Member { key: 3, opaque: false }, m(4)];
        assert_eq!(frame(&mut built, &[&alpha, &region_b]), (1, 1), "another opacity is another structure");
        assert_eq!(frame(&mut built, &[&region_b]), (0, 1), "A gone: retired");
        assert_eq!(built.len(), 1);
        assert_eq!(frame(&mut built, &[&region_b, &region_b]), (0, 0), "two runs of the same members share one structure");
        assert_ne!(members_key(&[m(1), m(2)]), members_key(&[m(2), m(1)]), "the order is the geometry index");
    }
}
