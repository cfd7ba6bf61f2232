//! Merged bottom levels of the static world (issue 21, "merged into larger BLASes per
//! region"): both tracers pay per instance in the top level (on the H200 the hardware tracer
//! lost 1.2 ms going from 28 to 268 instances; the compute tracer visits 5–15 % fewer nodes
//! per ray with regions of 2³ cells on lavapipe, bench/pathtrace.md), so each
//! traces the chunks of one region as one instance of one bottom level instead of an instance
//! per chunk. One rule for both back ends ([`region`], [`runs`], [`members_key`]):
//!
//! - **Region.** A region is a cube of `size`³ cells of the world's spatial grid (the cells the
//!   static world groups chunks by, [`crate::frame::world::StaticChunk::cell`]), `size` the
//!   `[pathtrace]` key `chunk_regions` (0: no merging, a structure per chunk as before).
//! - **Order.** The tracer sorts its items stably by region (`None`, the surfaces and chunks
//!   traced alone, first), so a region's chunks and their instance records are consecutive.
//! - **Shading is untouched.** Every chunk keeps its own instance record (material, first
//!   triangle, emitters, radiosity) and its own triangles; a hit in a merged bottom level is
//!   resolved to the chunk's record and triangle before shading.
//!
//! The hardware tracer (`hardware::accel`): a region's structure holds one geometry per chunk,
//! in the order of their instance records; its instance's custom index is the first chunk's
//! record, and the hit shaders take `gl_InstanceCustomIndexEXT + gl_GeometryIndexEXT` as the
//! instance. A chunk's geometry is opaque unless it is alpha tested (then its any-hit shader
//! runs), as the instance flags of an unmerged chunk say. A merged structure is keyed by its
//! members ([`Member`]: geometry key and opacity, in order): it is built when a run of chunks
//! appears whose members have no structure (a new chunk in the region, a released one), reused
//! while they stay, and retired in the first frame that traces merged chunks but not these
//! ([`plan`]; a frame without the static world keeps them). Other regions keep theirs.
//!
//! The compute tracer (`compute`): a run of two or more chunks is one resident geometry keyed
//! by [`members_key`] (opacity is not part of it: alpha tests are per chunk record), a BVH
//! over the members' triangles ([`crate::render::trace::bvh::Blas::merged`]) whose triangles
//! name their chunk (its place in the run) and their index in that chunk's triangles. It is
//! built once the run's chunks have stayed the same for [`SETTLE_FRAMES`] frames ([`Settling`]:
//! while the static world grows, a region would otherwise be rebuilt on the CPU at each new
//! chunk; its chunks are traced one by one meanwhile), used from then on while it is resident
//! and dropped, like any geometry, when unused. The frame's instance
//! records get one more record per run ([`merge_records`]: `INSTANCE_MERGED`, the run's first
//! record in `first_member`), which the top level holds instead of the run's chunks; the
//! traversal resolves a hit in it to the chunk's record and triangle (`bvh_resolve` of
//! `shaders/trace/bvh_common.glsl`), alpha-testing the chunks that are alpha tested.

use std::collections::{HashMap, HashSet};
use std::ops::Range;

use xxhash_rust::xxh3::Xxh3;

use super::bvh::Aabb;
use super::gpu_types::GpuInstance;
use super::shader_constants::{INSTANCE_ALPHA_TESTED, INSTANCE_MERGED, NO_PREVIOUS_TRIANGLES};

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

/// Frames a run's chunks stay the same before the compute tracer builds its merged BVH: a
/// region still growing (the static world takes in what the camera sees, a chunk at a time)
/// is traced chunk by chunk meanwhile instead of rebuilt on the CPU at every new chunk.
pub const SETTLE_FRAMES: u64 = 8;

/// How long each run of the last frames has had the same chunks ([`SETTLE_FRAMES`]).
#[derive(Debug, Default)]
pub struct Settling {
    /// A run's [`members_key`] and the first frame of the frames in a row it was traced in.
    since: HashMap<u64, u64>,
}

impl Settling {
    /// Whether each run of `keys` (this frame's, [`members_key`]) has had its chunks for
    /// [`SETTLE_FRAMES`] frames; forgets the runs not traced in `frame`.
    pub fn settled(&mut self, keys: &[u64], frame: u64) -> Vec<bool> {
        let traced: HashSet<u64> = keys.iter().copied().collect();
        self.since.retain(|k, _| traced.contains(k));
        keys.iter().map(|&k| frame.saturating_sub(*self.since.entry(k).or_insert(frame)) >= SETTLE_FRAMES).collect()
    }
}

/// A run's merged bottom level as the compute tracer placed it.
#[derive(Clone, Debug, PartialEq)]
pub struct MergedRun {
    /// The run's chunk records, consecutive.
    pub records: Range<u32>,
    /// Its root in the BLAS node buffer.
    pub blas_root: u32,
    /// Its first triangle in the triangle buffer.
    pub first_triangle: u32,
    /// Its box in eye space.
    pub bounds: Aabb,
}

/// Adds a record per merged run to `records` (the frame's instance records) and `bounds`
/// (their eye-space boxes, which the top level is built over): the run's first record with
/// the merged bottom level's root and triangles, `INSTANCE_MERGED` (and
/// `INSTANCE_ALPHA_TESTED` when a chunk of it is), `first_member` its first record; the
/// run's chunks leave the top level (their boxes become empty), their records stay for
/// shading. Returns the instances in the top level. A run whose records are not all there is
/// left as it is.
pub fn merge_records(records: &mut Vec<GpuInstance>, bounds: &mut Vec<Aabb>, runs: &[MergedRun]) -> u32 {
    for run in runs {
        let range = run.records.start as usize..run.records.end as usize;
        let Some(chunks) = records.get(range.clone()).filter(|c| !c.is_empty()) else { continue };
        let Some(boxes) = bounds.get_mut(range) else { continue };
        let alpha = chunks.iter().fold(0, |a, c| a | (c.flags & INSTANCE_ALPHA_TESTED));
        let merged = GpuInstance {
            blas_root: run.blas_root,
            first_triangle: run.first_triangle,
            flags: INSTANCE_MERGED | alpha,
            previous_triangles: NO_PREVIOUS_TRIANGLES,
            first_member: run.records.start,
            ..chunks[0]
        };
        boxes.fill(Aabb::EMPTY);
        records.push(merged);
        bounds.push(run.bounds);
    }
    bounds.iter().filter(|b| b.is_finite()).count() as u32
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

    /// The compute tracer's top level: a merged run's chunks leave it (their records stay, for
    /// shading), its merged record joins it, naming the first chunk's record and alpha-tested
    /// when a chunk is; a run whose records are missing changes nothing.
    #[test]
    fn merged_records_replace_their_chunks_in_the_top_level() {
        let record = |i: u32, flags: u32| GpuInstance { blas_root: 100 + i, first_triangle: 1000 + i, flags, material: i, ..GpuInstance::default() };
        let mut records = vec![record(0, 0), record(1, 0), record(2, INSTANCE_ALPHA_TESTED), record(3, 0), record(4, 0), record(5, 0)];
        let unit = |x: f32| Aabb { min: glam::Vec3::splat(x), max: glam::Vec3::splat(x + 1.0) };
        let mut bounds: Vec<Aabb> = (0..6).map(|i| unit(i as f32)).collect();
        bounds[5] = Aabb::EMPTY;
        let run = |records: Range<u32>, at: u32| MergedRun { records, blas_root: at, first_triangle: 10 * at, bounds: unit(at as f32) };
        let runs = [run(1..3, 50), run(3..5, 60), run(4..9, 70)];
        assert_eq!(merge_records(&mut records, &mut bounds, &runs), 3, "instance 0 and two merged runs (5 has no box)");
        assert_eq!(records.len(), 8, "the run beyond the records is left");
        assert_eq!((records[6].blas_root, records[6].first_triangle, records[6].first_member), (50, 500, 1));
        assert_eq!(records[6].flags, INSTANCE_MERGED | INSTANCE_ALPHA_TESTED, "a chunk of it is alpha tested");
        assert_eq!((records[7].flags, records[7].first_member, records[7].previous_triangles), (INSTANCE_MERGED, 3, NO_PREVIOUS_TRIANGLES));
        assert_eq!(records[..6].iter().map(|r| (r.blas_root, r.flags)).collect::<Vec<_>>(), [(100, 0), (101, 0), (102, 1), (103, 0), (104, 0), (105, 0)], "chunk records are kept");
        assert_eq!(bounds.iter().map(Aabb::is_finite).collect::<Vec<_>>(), [true, false, false, false, false, false, true, true]);
        assert_eq!(bounds[6], unit(50.0));
    }

    /// A run is settled after SETTLE_FRAMES frames in a row with the same chunks; a frame
    /// without it starts it again.
    #[test]
    fn a_run_settles_after_frames_with_the_same_chunks() {
        let mut settling = Settling::default();
        let (a, b) = (members_key(&[Member { key: 1, opaque: true }]), members_key(&[Member { key: 2, opaque: true }]));
        assert_eq!(settling.settled(&[a], 10), [false]);
        assert_eq!(settling.settled(&[a, b], 10 + SETTLE_FRAMES - 1), [false, false]);
        assert_eq!(settling.settled(&[a, b], 10 + SETTLE_FRAMES), [true, false]);
        assert_eq!(settling.settled(&[b], 11 + SETTLE_FRAMES), [false], "a left");
        assert_eq!(settling.settled(&[a, b], 12 + SETTLE_FRAMES), [false, false], "a starts again");
        assert_eq!(settling.settled(&[a, b], 10 + 2 * SETTLE_FRAMES), [false, true]);
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
