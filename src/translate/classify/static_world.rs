//! The persistent static world: static geometry recognised below the draw level, kept when the
//! program stops drawing it, handed to the renderer as immutable chunks (DESIGN.md, "Hash
//! tracking"; issue 5, part 5).
//!
//! Old engines (Quake 3's `tess`) re-batch their world surfaces every frame from the ones that
//! are visible, so a wall arrives in a different draw, at a different offset, or not at all.
//! The caller therefore offers the **world-space triangles** of every opaque draw whose vertices
//! are in the world frame ([`StaticWorld::offer`]), and this module works triangle by triangle:
//!
//! - **Key.** Each vertex is quantised to a grid of [`QUANTUM`] world units; the three vertices
//!   are rotated so that the lexicographically smallest comes first (the same triangle issued
//!   from another first vertex matches; the winding is kept, so the two sides of a two-sided
//!   wall stay two triangles); the key is the xxh3 of the nine integers seeded with the
//!   material.
//! - **Joining.** A triangle seen in one frame is *pending*; seen again in a later frame (any
//!   batch, any order, within [`PENDING_FRAMES`]) it *joins* the world. A triangle offered twice
//!   in one frame (multi-pass drawing) counts once. An offer made mostly of triangles never
//!   seen (more than half) is a changing draw, an animated mesh whose vertices happen to come
//!   back: none of its triangles joins in that frame (a static batch seen for the first time
//!   is pending, not changing, in the next frame, so it joins then).
//! - **Float noise.** A program's own transforms can move a vertex across a grid line from one
//!   frame to the next, which changes its key. Before joining, a triangle is therefore compared
//!   with the world triangles of its material whose centroid is within [`NEAR`]; if one matches
//!   every vertex within [`NEAR`] (in any rotation), the new key becomes an *alias* of it instead
//!   of a duplicate. This costs nothing per frame: only triangles about to join are compared.
//! - **Chunks.** Joined triangles are grouped per material and per spatial cell (a grid whose
//!   cell size is fixed when the first triangles join: the power of two nearest to the extent of
//!   that first view over [`CELLS_ACROSS`]). A chunk, once built, is immutable and keeps its id.
//!   Triangles joining a cell go into a new chunk of that cell; when a cell of one material would
//!   hold more than [`MAX_CHUNKS_PER_CELL`] chunks, they are merged into one (the merge counts as
//!   new and released chunks). When nothing joins or leaves, the chunk list is the same `Arc` and
//!   the upload is zero. A chunk carries what a renderer shades its triangles with when no draw
//!   of them is in the frame: per corner the texture coordinates of units 0 and 1 and the
//!   primary colour as first offered, and the textures, material and draw state
//!   ([`ChunkShading`]) of the draw that offered its first triangle.
//! - **Anti-culling.** A triangle the program stops drawing stays: a wall behind the camera is
//!   still in the traced scene, for shadows and bounced light.
//! - **Release.** Everything goes on [`StaticWorld::clear`] (camera cut, level change) or when
//!   frame numbers go backwards (a replay restarted). Otherwise a triangle is released only when
//!   the view shows it is gone: for [`RELEASE_FRAMES`] frames since it was last offered it lay
//!   inside the view frustum (vertices inside the side planes shrunk by [`FRUSTUM_MARGIN`] and
//!   within the depth range), faced the camera, and other triangles of its cell were drawn in
//!   that frame. Engines also cull by PVS, portals, occlusion and backface plane tests, so this
//!   is conservative: the facing test skips back faces (which side is front is learnt from the
//!   triangles offered: most visible triangles face the camera), and a cell with nothing drawn
//!   says nothing (a PVS cut). A released triangle returns when seen in two frames again.
//!   Frames that give no evidence (outside the frustum, cell not drawn) leave the count as it is.
//!   Limit: a surface hidden behind another inside a drawn cell (occlusion culling, a PVS leaf
//!   next to a visible one) that stays in view that long is released, and returns when drawn.
//!
//! Cost per offered triangle: one xxh3 of 36 bytes, then a comparison with the key that follows
//! the last triangle found in its chunk (surfaces arrive whole and chunks keep them in the order
//! they joined, so this usually hits, reading memory in order); only on a miss a hash-map probe
//! (keys are hashes, so the maps use a one-multiply hasher). The frame in which each triangle
//! was last seen is kept in its chunk, next to its key. No allocation per triangle or per frame once the world is
//! built; the release test visits only the chunks whose cell was drawn and whose bounds meet the
//! frustum, and makes no hash-map probe.

use std::collections::hash_map::Entry;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};

use crate::frame::TextureRef;
use crate::frame::class::MaterialOverride;
use crate::frame::world::{CHUNK_UNITS, ChunkShading, StaticChunk};

/// Size of the grid vertices are quantised to, in world units: coarse enough that two copies of
/// a triangle through the program's transforms usually land on the same points, fine enough
/// that distinct triangles of a level (edges of centimetres in metre units, of units in Quake
/// units) never do.
pub const QUANTUM: f32 = 1.0 / 128.0;
/// Two triangles of one material whose vertices are all within this distance (per coordinate)
/// are the same triangle ([`QUANTUM`] × 2: float noise in a vertex of a transformed level).
pub const NEAR: f32 = 2.0 * QUANTUM;
/// Cell size of the near-duplicate index: a few dozen triangles per cell in a finely cut level,
/// so that the index stays small and a joining triangle is compared with few others.
const NEAR_CELL: f32 = 16.0 * NEAR;
/// A pending triangle not seen again within this many frames is forgotten (it was dynamic).
pub const PENDING_FRAMES: u64 = 8;
/// Frames of evidence that a triangle is gone before it is released.
pub const RELEASE_FRAMES: u8 = 8;
/// Fraction of the view (in normalised device coordinates) a triangle must be inside, on each
/// side, to count as visible: engines cull with bounds that are not exact.
pub const FRUSTUM_MARGIN: f32 = 0.1;
/// The first view's extent is split into about this many cells along its longest side.
pub const CELLS_ACROSS: f32 = 8.0;
/// Chunks of one material a cell may hold before they are merged into one.
pub const MAX_CHUNKS_PER_CELL: usize = 4;
/// One offered triangle in this many is projected to learn which winding faces the camera.
const FACING_SAMPLE: u32 = 16;

/// Hasher for keys that are hashes already (and small tuples of them): one multiply per word.
#[derive(Default)]
pub(super) struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }

    fn write_u64(&mut self, v: u64) {
        let x = (self.0 ^ v).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        self.0 = x ^ (x >> 32);
    }

    fn write_u32(&mut self, v: u32) {
        self.write_u64(u64::from(v));
    }
}

/// A hash map keyed by hashes (or small tuples of them), with [`KeyHasher`].
pub(super) type Map<K, V> = HashMap<K, V, BuildHasherDefault<KeyHasher>>;

/// The world-space triangles of one opaque draw, offered to [`StaticWorld::offer`].
pub struct WorldTriangles<'a> {
    /// Hash of the texture ids, draw state and material (computed by the caller).
    pub material_key: u64,
    /// Surface parameters (the same for every offer of one `material_key`).
    pub material: MaterialOverride,
    /// Texture of each carried unit.
    pub textures: [Option<&'a TextureRef>; CHUNK_UNITS],
    /// World-space positions, 3 per triangle (a trailing partial triangle is ignored).
    pub positions: &'a [[f32; 3]],
    /// Texture coordinates of each carried unit, 3 per triangle (ignored unless as long as
    /// `positions`).
    pub texcoords: [Option<&'a [[f32; 2]]>; CHUNK_UNITS],
    /// Primary colours, 3 per triangle (ignored unless as long as `positions`; `None`: white).
    pub colors: Option<&'a [[u8; 4]]>,
    /// Draw state (the same for every offer of one `material_key` in what the key hashes).
    pub shading: &'a ChunkShading,
}

/// What [`StaticWorld::offer`] found in one draw.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Offered {
    /// Triangles offered.
    pub triangles: usize,
    /// Triangles in the persistent world (already, or joining in this frame).
    pub static_triangles: usize,
    /// Triangles never seen before (now pending).
    pub new_triangles: usize,
}

impl Offered {
    /// Whether every triangle offered is in the world at the end of the frame: the chunks hold
    /// the whole draw.
    pub fn all_static(&self) -> bool {
        self.triangles > 0 && self.static_triangles == self.triangles
    }
}

/// The end of a frame: the chunks the renderer must hold now, and what changed.
#[derive(Clone, Debug)]
pub struct WorldUpdate {
    /// Every live chunk, by increasing id (the same `Arc` while nothing changed).
    pub chunks: Arc<[Arc<StaticChunk>]>,
    /// Chunks built in this frame (the renderer uploads them).
    pub new_chunks: usize,
    /// Chunks kept from the previous frame.
    pub reused_chunks: usize,
    /// Chunks of the previous frame that are gone (the renderer frees them).
    pub released_chunks: usize,
    /// Bytes of the new chunks (positions and texture coordinates).
    pub upload_bytes: u64,
    /// Triangles in the world.
    pub triangles: usize,
}

/// One triangle's data.
#[derive(Clone, Copy)]
struct Tri {
    positions: [[f32; 3]; 3],
    texcoords: [Option<[[f32; 2]; 3]>; CHUNK_UNITS],
    colors: Option<[[u8; 4]; 3]>,
}

/// A triangle seen in one frame, waiting to be seen again.
struct Pending {
    tick: u64,
    material: u64,
    look: Look,
    tri: Tri,
}

/// What the renderer draws a chunk's triangles with besides their key.
#[derive(Clone)]
struct Look {
    textures: [Option<TextureRef>; CHUNK_UNITS],
    material: MaterialOverride,
    shading: ChunkShading,
}

/// Where a world triangle lives: chunk (index into `StaticWorld::chunks`, or [`JOINING`]) and
/// triangle index in it (or in `joining`).
#[derive(Clone, Copy, PartialEq, Eq)]
struct Loc {
    chunk: u32,
    index: u32,
}

/// `Loc::chunk` of a triangle that joined in the current frame.
const JOINING: u32 = u32::MAX;

/// A world triangle taken out of a chunk to be rebuilt into another.
struct Moved {
    key: u64,
    tri: Tri,
    seen: u64,
    missed: u8,
}

/// A live chunk, what the world needs to rebuild it, and when its triangles were seen.
struct LiveChunk {
    chunk: Arc<StaticChunk>,
    /// Key of each triangle.
    keys: Vec<u64>,
    /// Tick in which each triangle was last offered.
    seen: Vec<u64>,
    /// Frames of evidence that each triangle is gone, since it was last offered.
    missed: Vec<u8>,
    cell: u32,
    min: Vec3,
    max: Vec3,
}

/// Counts for the update of the current frame.
#[derive(Default)]
struct Changes {
    new_chunks: usize,
    released_chunks: usize,
    upload_bytes: u64,
}

/// The persistent static world (module documentation: how triangles join and leave).
pub struct StaticWorld {
    tick: u64,
    last_frame: Option<u64>,
    world_to_clip: Mat4,
    /// Key → place of every world triangle.
    slots: Map<u64, Loc>,
    /// Keys that float noise produced for a world triangle → that triangle's key.
    aliases: Map<u64, u64>,
    pending: Map<u64, Pending>,
    /// Triangles that joined in this frame, in order (with their key).
    joining: Vec<(u64, Pending)>,
    /// (material, centroid cell of [`NEAR_CELL`]) → keys, to find near duplicates.
    near: Map<(u64, [i32; 3]), Vec<u64>>,
    cell_size: Option<f32>,
    /// Tick in which a triangle of each spatial cell was last offered.
    cells: Vec<u64>,
    /// Grid coordinates of each cell (by index).
    cell_coords: Vec<[i32; 3]>,
    cell_index: Map<[i32; 3], u32>,
    /// (material, cell) → indices of its chunks.
    groups: Map<(u64, u32), Vec<u32>>,
    /// Live chunks by index (`None`: free, index in `free`).
    chunks: Vec<Option<LiveChunk>>,
    free: Vec<u32>,
    next_id: u64,
    list: Arc<[Arc<StaticChunk>]>,
    changes: Changes,
    /// The last triangle found: the next offered one is most often the next in its chunk
    /// (surfaces arrive whole, in the order they joined), found without a hash probe.
    cursor: Option<Loc>,
    /// Reused buffer of an offer's triangles not in the world: (index, key).
    unknown: Vec<(usize, u64)>,
    /// Facing samples of this frame: counter, counter-clockwise and clockwise in the view.
    facing_counter: u32,
    ccw: u32,
    cw: u32,
    /// Sign of the view-space area of a front face (+1: counter-clockwise).
    front_sign: f32,
}

impl Default for StaticWorld {
    fn default() -> Self {
        Self::new()
    }
}

impl StaticWorld {
    /// An empty world.
    pub fn new() -> Self {
        Self {
            tick: 0,
            last_frame: None,
            world_to_clip: Mat4::IDENTITY,
            slots: Map::default(),
            aliases: Map::default(),
            pending: Map::default(),
            joining: Vec::new(),
            near: Map::default(),
            cell_size: None,
            cells: Vec::new(),
            cell_coords: Vec::new(),
            cell_index: Map::default(),
            groups: Map::default(),
            chunks: Vec::new(),
            free: Vec::new(),
            next_id: 1,
            list: Arc::from(Vec::new()),
            changes: Changes::default(),
            cursor: None,
            unknown: Vec::new(),
            facing_counter: 0,
            ccw: 0,
            cw: 0,
            front_sign: 1.0,
        }
    }

    /// Starts a frame seen through `world_to_clip` (projection * view). A frame number lower
    /// than the previous one (a replay restarted) clears the world.
    pub fn begin_frame(&mut self, frame: u64, world_to_clip: glam::Mat4) {
        if self.last_frame.is_some_and(|last| frame < last) {
            self.clear();
        }
        self.last_frame = Some(frame);
        self.tick += 1;
        self.world_to_clip = world_to_clip;
        self.cursor = None;
        self.ccw = 0;
        self.cw = 0;
    }

    /// Offers the world-space triangles of one opaque draw whose vertices are in the world
    /// frame.
    pub fn offer(&mut self, t: WorldTriangles<'_>) -> Offered {
        let count = t.positions.len() / 3;
        let texcoords = t.texcoords.map(|uv| uv.filter(|uv| uv.len() >= count * 3));
        let colors = t.colors.filter(|c| c.len() >= count * 3);
        let mut offered = Offered { triangles: count, ..Offered::default() };
        // First pass: triangles already in the world; the others wait in `unknown`.
        let mut unknown = std::mem::take(&mut self.unknown);
        unknown.clear();
        let mut fresh = 0;
        for i in 0..count {
            let positions = [t.positions[3 * i], t.positions[3 * i + 1], t.positions[3 * i + 2]];
            self.sample_facing(&positions);
            let key = triangle_key(&positions, t.material_key);
            if self.see_next(key)
                || self.see(key)
                || self.aliases.get(&key).copied().is_some_and(|original| self.see(original))
            {
                offered.static_triangles += 1;
                continue;
            }
            fresh += usize::from(!self.pending.contains_key(&key));
            unknown.push((i, key));
        }
        // A draw mostly made of triangles never seen is changing (an animated mesh): the few
        // that happen to repeat a previous frame's do not join.
        let changing = fresh * 2 > count;
        for &(i, key) in &unknown {
            match self.pending.entry(key) {
                Entry::Occupied(entry) if entry.get().tick < self.tick && !changing => {
                    let pending = entry.remove();
                    self.join(key, pending);
                    offered.static_triangles += 1;
                }
                Entry::Occupied(_) => {} // offered twice in this frame, or in a changing draw
                Entry::Vacant(entry) => {
                    let positions = [t.positions[3 * i], t.positions[3 * i + 1], t.positions[3 * i + 2]];
                    let uv = texcoords.map(|uv| uv.map(|uv| [uv[3 * i], uv[3 * i + 1], uv[3 * i + 2]]));
                    let rgba = colors.map(|c| [c[3 * i], c[3 * i + 1], c[3 * i + 2]]);
                    entry.insert(Pending {
                        tick: self.tick,
                        material: t.material_key,
                        look: Look { textures: t.textures.map(Option::<&TextureRef>::cloned), material: t.material, shading: t.shading.clone() },
                        tri: Tri { positions, texcoords: uv, colors: rgba },
                    });
                    offered.new_triangles += 1;
                }
            }
        }
        self.unknown = unknown;
        offered
    }

    /// Ends the frame: the chunks the renderer must hold now, and what changed.
    pub fn end_frame(&mut self) -> WorldUpdate {
        if self.ccw != self.cw {
            self.front_sign = if self.ccw > self.cw { 1.0 } else { -1.0 };
        }
        self.release_gone();
        self.build_joined();
        let tick = self.tick;
        self.pending.retain(|_, p| p.tick + PENDING_FRAMES >= tick);
        self.cursor = None;
        let changes = std::mem::take(&mut self.changes);
        if changes.new_chunks + changes.released_chunks > 0 {
            let mut list: Vec<Arc<StaticChunk>> = self.live().map(|c| c.chunk.clone()).collect();
            list.sort_by_key(|c| c.id);
            self.list = list.into();
        }
        WorldUpdate {
            chunks: self.list.clone(),
            new_chunks: changes.new_chunks,
            reused_chunks: self.list.len().saturating_sub(changes.new_chunks),
            released_chunks: changes.released_chunks,
            upload_bytes: changes.upload_bytes,
            triangles: self.slots.len(),
        }
    }

    /// Camera cut or level change: forget everything (the next update reports every chunk
    /// released).
    pub fn clear(&mut self) {
        self.changes.released_chunks += self.live().count();
        self.changes.new_chunks = 0;
        self.changes.upload_bytes = 0;
        self.slots.clear();
        self.aliases.clear();
        self.pending.clear();
        self.joining.clear();
        self.near.clear();
        self.cell_size = None;
        self.cells.clear();
        self.cell_coords.clear();
        self.cell_index.clear();
        self.groups.clear();
        self.chunks.clear();
        self.free.clear();
        self.cursor = None;
        self.list = Arc::from(Vec::new());
    }

    /// The live chunks.
    fn live(&self) -> impl Iterator<Item = &LiveChunk> {
        self.chunks.iter().flatten()
    }

    /// Marks the triangle at `loc` seen in this frame (nothing for a joining one) and makes it
    /// the cursor.
    fn mark(&mut self, loc: Loc) {
        self.cursor = Some(loc);
        let Some(Some(chunk)) = self.chunks.get_mut(loc.chunk as usize) else { return };
        let i = loc.index as usize;
        if let (Some(seen), Some(missed)) = (chunk.seen.get_mut(i), chunk.missed.get_mut(i)) {
            *seen = self.tick;
            *missed = 0;
        }
        if let Some(cell) = self.cells.get_mut(chunk.cell as usize) {
            *cell = self.tick;
        }
    }

    /// Whether `key` is the triangle after the cursor in its chunk (then marked seen).
    fn see_next(&mut self, key: u64) -> bool {
        let Some(cursor) = self.cursor else { return false };
        let next = Loc { chunk: cursor.chunk, index: cursor.index + 1 };
        let hit = matches!(self.chunks.get(next.chunk as usize), Some(Some(c)) if c.keys.get(next.index as usize) == Some(&key));
        if hit {
            self.mark(next);
        }
        hit
    }

    /// Marks the world triangle `key` seen in this frame; false when it is not in the world.
    fn see(&mut self, key: u64) -> bool {
        let Some(&loc) = self.slots.get(&key) else { return false };
        self.mark(loc);
        true
    }

    /// Counts the view winding of one offered triangle in [`FACING_SAMPLE`].
    fn sample_facing(&mut self, positions: &[[f32; 3]; 3]) {
        self.facing_counter = self.facing_counter.wrapping_add(1);
        if !self.facing_counter.is_multiple_of(FACING_SAMPLE) {
            return;
        }
        let clip = positions.map(|p| self.world_to_clip * Vec3::from(p).extend(1.0));
        if clip.iter().all(|c| c.w > 0.0) {
            let area = view_area(&clip);
            if area > 0.0 {
                self.ccw += 1;
            } else if area < 0.0 {
                self.cw += 1;
            }
        }
    }

    /// A pending triangle seen again joins the world, or becomes an alias of the world triangle
    /// it is a noisy copy of.
    fn join(&mut self, key: u64, pending: Pending) {
        if let Some(original) = self.near_duplicate(pending.material, &pending.tri.positions) {
            self.aliases.insert(key, original);
            self.see(original);
            return;
        }
        let near_key = (pending.material, near_cell(&pending.tri.positions));
        self.near.entry(near_key).or_default().push(key);
        self.slots.insert(key, Loc { chunk: JOINING, index: self.joining.len() as u32 });
        self.joining.push((key, pending));
    }

    /// The world triangle of `material` with every vertex within [`NEAR`] of `positions`.
    fn near_duplicate(&self, material: u64, positions: &[[f32; 3]; 3]) -> Option<u64> {
        let c = centroid(positions) / NEAR_CELL;
        let lo = (c - Vec3::splat(NEAR / NEAR_CELL)).floor().as_ivec3();
        let hi = (c + Vec3::splat(NEAR / NEAR_CELL)).floor().as_ivec3();
        for x in lo.x..=hi.x {
            for y in lo.y..=hi.y {
                for z in lo.z..=hi.z {
                    let Some(keys) = self.near.get(&(material, [x, y, z])) else { continue };
                    for &key in keys {
                        if self.positions_of(key).is_some_and(|other| same_triangle(positions, &other)) {
                            return Some(key);
                        }
                    }
                }
            }
        }
        None
    }

    /// The positions of world triangle `key`.
    fn positions_of(&self, key: u64) -> Option<[[f32; 3]; 3]> {
        let loc = self.slots.get(&key)?;
        let i = loc.index as usize;
        if loc.chunk == JOINING {
            return self.joining.get(i).map(|(_, p)| p.tri.positions);
        }
        let p = &self.chunks.get(loc.chunk as usize)?.as_ref()?.chunk.positions;
        Some([*p.get(3 * i)?, *p.get(3 * i + 1)?, *p.get(3 * i + 2)?])
    }

    /// Builds the chunks of the triangles that joined in this frame.
    fn build_joined(&mut self) {
        if self.joining.is_empty() {
            return;
        }
        let joining = std::mem::take(&mut self.joining);
        let cell_size = *self.cell_size.get_or_insert_with(|| first_cell_size(&joining));
        // Group by (material, cell), keeping the order of appearance.
        let mut groups: Vec<((u64, u32), Vec<Moved>, Look)> = Vec::new();
        let mut group_of: Map<(u64, u32), usize> = Map::default();
        for (key, p) in joining {
            let coords = (centroid(&p.tri.positions) / cell_size).floor().as_ivec3().to_array();
            let cell = self.cell(coords);
            let g = *group_of.entry((p.material, cell)).or_insert_with(|| {
                groups.push(((p.material, cell), Vec::new(), p.look.clone()));
                groups.len() - 1
            });
            groups[g].1.push(Moved { key, tri: p.tri, seen: self.tick, missed: 0 });
        }
        for ((material, cell), mut tris, look) in groups {
            let existing = self.groups.get(&(material, cell)).map_or(0, Vec::len);
            if existing >= MAX_CHUNKS_PER_CELL {
                let mut merged = Vec::new();
                for index in self.groups.remove(&(material, cell)).unwrap_or_default() {
                    merged.extend(self.take_chunk(index));
                }
                merged.append(&mut tris);
                tris = merged;
            }
            self.build_chunk(material, look, cell, tris);
        }
    }

    /// Index of the cell at `coords` (created if new), marked drawn in this frame.
    fn cell(&mut self, coords: [i32; 3]) -> u32 {
        let (cells, cell_coords) = (&mut self.cells, &mut self.cell_coords);
        let index = *self.cell_index.entry(coords).or_insert_with(|| {
            cells.push(0);
            cell_coords.push(coords);
            (cells.len() - 1) as u32
        });
        cells[index as usize] = self.tick;
        index
    }

    /// Removes chunk `index` (counted as released; the caller updates `groups`) and returns its
    /// triangles.
    fn take_chunk(&mut self, index: u32) -> Vec<Moved> {
        let Some(live) = self.chunks.get_mut(index as usize).and_then(Option::take) else { return Vec::new() };
        self.free.push(index);
        self.changes.released_chunks += 1;
        let c = &live.chunk;
        (0..live.keys.len())
            .map(|i| {
                let positions = [c.positions[3 * i], c.positions[3 * i + 1], c.positions[3 * i + 2]];
                let texcoords = std::array::from_fn(|u| {
                    let uv = &c.texcoords[u];
                    (!uv.is_empty()).then(|| [uv[3 * i], uv[3 * i + 1], uv[3 * i + 2]])
                });
                let colors = (!c.colors.is_empty()).then(|| [c.colors[3 * i], c.colors[3 * i + 1], c.colors[3 * i + 2]]);
                Moved { key: live.keys[i], tri: Tri { positions, texcoords, colors }, seen: live.seen[i], missed: live.missed[i] }
            })
            .collect()
    }

    /// Builds a chunk of `tris` in `cell` (nothing when empty) and points their slots at it.
    fn build_chunk(&mut self, material: u64, look: Look, cell: u32, tris: Vec<Moved>) {
        if tris.is_empty() {
            return;
        }
        let index = self.free.pop().unwrap_or_else(|| {
            self.chunks.push(None);
            (self.chunks.len() - 1) as u32
        });
        let id = self.next_id;
        self.next_id += 1;
        let with_uv: [bool; CHUNK_UNITS] = std::array::from_fn(|u| tris.iter().any(|t| t.tri.texcoords[u].is_some()));
        let with_colors = tris.iter().any(|t| t.tri.colors.is_some());
        let n = tris.len();
        let mut positions = Vec::with_capacity(n * 3);
        let mut texcoords: [Vec<[f32; 2]>; CHUNK_UNITS] = with_uv.map(|with| Vec::with_capacity(if with { n * 3 } else { 0 }));
        let mut colors = Vec::with_capacity(if with_colors { n * 3 } else { 0 });
        let (mut keys, mut seen, mut missed) = (Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n));
        let (mut min, mut max) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for (i, t) in tris.iter().enumerate() {
            for p in t.tri.positions {
                min = min.min(Vec3::from(p));
                max = max.max(Vec3::from(p));
            }
            positions.extend_from_slice(&t.tri.positions);
            for ((uv, with), out) in t.tri.texcoords.iter().zip(with_uv).zip(&mut texcoords) {
                if with {
                    out.extend_from_slice(&uv.unwrap_or_default());
                }
            }
            if with_colors {
                colors.extend_from_slice(&t.tri.colors.unwrap_or([[255; 4]; 3]));
            }
            keys.push(t.key);
            seen.push(t.seen);
            missed.push(t.missed);
            self.slots.insert(t.key, Loc { chunk: index, index: i as u32 });
        }
        let chunk = Arc::new(StaticChunk {
            id,
            material_key: material,
            material: look.material,
            textures: look.textures,
            positions,
            texcoords,
            colors,
            shading: look.shading,
            cell: self.cell_coords.get(cell as usize).copied().unwrap_or_default(),
        });
        self.changes.new_chunks += 1;
        self.changes.upload_bytes += chunk.upload_bytes();
        self.groups.entry((material, cell)).or_default().push(index);
        self.chunks[index as usize] = Some(LiveChunk { chunk, keys, seen, missed, cell, min, max });
    }

    /// Releases the triangles the view shows are gone (module documentation, "Release").
    fn release_gone(&mut self) {
        let (tick, m, front) = (self.tick, self.world_to_clip, self.front_sign);
        let mut touched = Vec::new();
        for (index, live) in self.chunks.iter_mut().enumerate() {
            let Some(live) = live else { continue };
            let drawn = self.cells.get(live.cell as usize) == Some(&tick);
            if !drawn || !box_meets_frustum(&m, live.min, live.max) {
                continue;
            }
            let mut gone = false;
            for (i, p) in live.chunk.positions.chunks_exact(3).enumerate() {
                if live.seen[i] == tick {
                    continue;
                }
                let clip = [p[0], p[1], p[2]].map(|v| m * Vec3::from(v).extend(1.0));
                if !well_inside(&clip) || view_area(&clip) * front <= 0.0 {
                    continue;
                }
                live.missed[i] = live.missed[i].saturating_add(1);
                gone |= live.missed[i] >= RELEASE_FRAMES;
            }
            if gone {
                touched.push(index as u32);
            }
        }
        for index in touched {
            let Some(Some(live)) = self.chunks.get(index as usize) else { continue };
            let (material, cell) = (live.chunk.material_key, live.cell);
            let look = Look { textures: live.chunk.textures.clone(), material: live.chunk.material, shading: live.chunk.shading.clone() };
            if let Entry::Occupied(mut group) = self.groups.entry((material, cell)) {
                group.get_mut().retain(|&other| other != index);
                if group.get().is_empty() {
                    group.remove();
                }
            }
            let (kept, gone): (Vec<Moved>, Vec<Moved>) =
                self.take_chunk(index).into_iter().partition(|t| t.missed < RELEASE_FRAMES);
            for t in gone {
                self.forget(t.key, material, &t.tri.positions);
            }
            self.build_chunk(material, look, cell, kept);
        }
    }

    /// Removes world triangle `key` from the maps. Its aliases stay: they are ignored while
    /// `key` is not in the world, and mean the same triangle if it returns.
    fn forget(&mut self, key: u64, material: u64, positions: &[[f32; 3]; 3]) {
        self.slots.remove(&key);
        if let Some(keys) = self.near.get_mut(&(material, near_cell(positions))) {
            keys.retain(|&k| k != key);
        }
    }
}

/// The key of a triangle: its quantised vertices, first the smallest, seeded with `material`.
fn triangle_key(positions: &[[f32; 3]; 3], material: u64) -> u64 {
    // Rounded half away from zero with a truncating conversion: no libm call.
    let q = positions.map(|p| {
        p.map(|c| {
            let x = c * (1.0 / QUANTUM);
            (x + 0.5f32.copysign(x)) as i32
        })
    });
    let first = if q[1] < q[0] { if q[2] < q[1] { 2 } else { 1 } } else if q[2] < q[0] { 2 } else { 0 };
    let mut bytes = [0u8; 36];
    for v in 0..3 {
        for (c, value) in q[(first + v) % 3].iter().enumerate() {
            let at = (v * 3 + c) * 4;
            bytes[at..at + 4].copy_from_slice(&value.to_le_bytes());
        }
    }
    xxhash_rust::xxh3::xxh3_64_with_seed(&bytes, material)
}

fn centroid(positions: &[[f32; 3]; 3]) -> Vec3 {
    (Vec3::from(positions[0]) + Vec3::from(positions[1]) + Vec3::from(positions[2])) / 3.0
}

/// The cell of the near-duplicate index holding a triangle.
fn near_cell(positions: &[[f32; 3]; 3]) -> [i32; 3] {
    (centroid(positions) / NEAR_CELL).floor().as_ivec3().to_array()
}

/// Whether `a` and `b` are the same triangle within [`NEAR`], whatever their first vertex.
fn same_triangle(a: &[[f32; 3]; 3], b: &[[f32; 3]; 3]) -> bool {
    (0..3).any(|r| {
        (0..3).all(|v| {
            let (p, q) = (Vec3::from(a[v]), Vec3::from(b[(v + r) % 3]));
            (p - q).abs().max_element() <= NEAR
        })
    })
}

/// The cell size of a new world: the power of two nearest to the extent of the first
/// triangles over [`CELLS_ACROSS`] (at least 256 quanta).
fn first_cell_size(joining: &[(u64, Pending)]) -> f32 {
    let (mut min, mut max) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for (_, p) in joining {
        for v in p.tri.positions {
            min = min.min(Vec3::from(v));
            max = max.max(Vec3::from(v));
        }
    }
    let extent = (max - min).max_element();
    let size = if extent.is_finite() { extent / CELLS_ACROSS } else { 0.0 };
    size.max(256.0 * QUANTUM).log2().round().exp2()
}

/// Twice the signed area of a triangle in normalised device coordinates (positive:
/// counter-clockwise); every `w` must be positive.
fn view_area(clip: &[Vec4; 3]) -> f32 {
    let n = clip.map(|c| glam::Vec2::new(c.x / c.w, c.y / c.w));
    (n[1] - n[0]).perp_dot(n[2] - n[0])
}

/// Every vertex in front of the camera, inside the side planes shrunk by [`FRUSTUM_MARGIN`]
/// and inside the depth range.
fn well_inside(clip: &[Vec4; 3]) -> bool {
    let k = 1.0 - FRUSTUM_MARGIN;
    clip.iter().all(|c| c.w > 0.0 && c.x.abs() <= k * c.w && c.y.abs() <= k * c.w && c.z.abs() <= c.w)
}

/// Whether the box `min`..`max` may meet the frustum of `world_to_clip` (false only when all
/// its corners are outside one clip plane).
fn box_meets_frustum(world_to_clip: &Mat4, min: Vec3, max: Vec3) -> bool {
    let corners: [Vec4; 8] = std::array::from_fn(|i| {
        let p = Vec3::new(
            if i & 1 == 0 { min.x } else { max.x },
            if i & 2 == 0 { min.y } else { max.y },
            if i & 4 == 0 { min.z } else { max.z },
        );
        *world_to_clip * p.extend(1.0)
    });
    let planes: [fn(&Vec4) -> f32; 6] =
        [|c| c.w + c.x, |c| c.w - c.x, |c| c.w + c.y, |c| c.w - c.y, |c| c.w + c.z, |c| c.w - c.z];
    planes.iter().all(|plane| corners.iter().any(|c| plane(c) >= 0.0))
}

#[cfg(test)]
mod tests {
    use std::collections::HashSet;

    use super::*;

    /// A few triangles of one material with their bounds, as an engine stores a surface.
    struct Surface {
        material: u64,
        positions: Vec<[f32; 3]>,
        texcoords: Vec<[f32; 2]>,
        min: Vec3,
        max: Vec3,
    }

    /// The rectangle `origin + a·u + b·v` cut into surfaces of `size` × `size` units, each of
    /// 2 × 2 quads, counter-clockwise seen from the side `u × v` points to.
    fn face(material: u64, origin: Vec3, u: Vec3, v: Vec3, size: f32) -> Vec<Surface> {
        let (nu, nv) = ((u.length() / size).round() as usize, (v.length() / size).round() as usize);
        let mut surfaces = Vec::new();
        for j in 0..nv {
            for i in 0..nu {
                let at = |a: f32, b: f32| origin + u * ((i as f32 + a) / nu as f32) + v * ((j as f32 + b) / nv as f32);
                let mut s = Surface {
                    material,
                    positions: Vec::new(),
                    texcoords: Vec::new(),
                    min: Vec3::INFINITY,
                    max: Vec3::NEG_INFINITY,
                };
                for (a, b) in [(0.0, 0.0), (0.5, 0.0), (0.0, 0.5), (0.5, 0.5)] {
                    let q = [at(a, b), at(a + 0.5, b), at(a + 0.5, b + 0.5), at(a, b + 0.5)];
                    for k in [0, 1, 2, 0, 2, 3] {
                        s.positions.push(q[k].to_array());
                        s.texcoords.push([q[k].x + q[k].z, q[k].y]);
                        s.min = s.min.min(q[k]);
                        s.max = s.max.max(q[k]);
                    }
                }
                surfaces.push(s);
            }
        }
        surfaces
    }

    /// The inside of the room -8..8 × 0..5 × -10..10 (one material per face), 1-unit surfaces.
    fn room() -> Vec<Surface> {
        let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
        [
            (Vec3::new(-8.0, 0.0, 10.0), x * 16.0, -z * 20.0),
            (Vec3::new(-8.0, 5.0, -10.0), x * 16.0, z * 20.0),
            (Vec3::new(-8.0, 0.0, -10.0), x * 16.0, y * 5.0),
            (Vec3::new(8.0, 0.0, 10.0), -x * 16.0, y * 5.0),
            (Vec3::new(-8.0, 0.0, 10.0), -z * 20.0, y * 5.0),
            (Vec3::new(8.0, 0.0, -10.0), z * 20.0, y * 5.0),
        ]
        .into_iter()
        .enumerate()
        .flat_map(|(m, (o, u, v))| face(m as u64 + 1, o, u, v, 1.0))
        .collect()
    }

    const EYE: Vec3 = Vec3::new(0.0, 1.6, 0.0);

    /// `gluPerspective`: vertical field of view in degrees.
    fn perspective(fovy: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
        let f = 1.0 / (fovy.to_radians() / 2.0).tan();
        let d = near - far;
        Mat4::from_cols(
            Vec4::new(f / aspect, 0.0, 0.0, 0.0),
            Vec4::new(0.0, f, 0.0, 0.0),
            Vec4::new(0.0, 0.0, (far + near) / d, -1.0),
            Vec4::new(0.0, 0.0, 2.0 * far * near / d, 0.0),
        )
    }

    /// The view of a camera at `eye` looking along `dir` (y up), as `gluLookAt` builds it.
    fn look_to(eye: Vec3, dir: Vec3) -> Mat4 {
        let f = dir.normalize();
        let s = f.cross(Vec3::Y).normalize();
        let u = s.cross(f);
        Mat4::from_cols(
            Vec4::new(s.x, u.x, -f.x, 0.0),
            Vec4::new(s.y, u.y, -f.y, 0.0),
            Vec4::new(s.z, u.z, -f.z, 0.0),
            Vec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
        )
    }

    /// Projection × view of a camera at `EYE` looking along yaw and pitch (degrees).
    fn camera(yaw: f32, pitch: f32) -> Mat4 {
        let (yaw, pitch) = (yaw.to_radians(), pitch.to_radians());
        let dir = Vec3::new(yaw.sin() * pitch.cos(), pitch.sin(), -yaw.cos() * pitch.cos());
        perspective(73.74, 4.0 / 3.0, 0.1, 100.0) * look_to(EYE, dir)
    }

    /// The camera of frame `f` of a turn of `frames` frames, looking up and down twice per turn.
    fn turning(f: u64, frames: u64) -> Mat4 {
        let yaw = 360.0 * (f % frames) as f32 / frames as f32;
        camera(yaw, 55.0 * (2.0 * yaw.to_radians()).sin())
    }

    /// One frame the way Quake 3 draws it: the surfaces whose bounds meet the frustum, nearest
    /// first, re-batched per material into batches of at most 1000 vertices, each triangle
    /// starting from another vertex every frame. Returns the update and the triangles drawn.
    fn q3_frame(world: &mut StaticWorld, surfaces: &[Surface], frame: u64, m: Mat4) -> (WorldUpdate, usize) {
        world.begin_frame(frame, m);
        let mut visible: Vec<&Surface> = surfaces.iter().filter(|s| box_meets_frustum(&m, s.min, s.max)).collect();
        visible.sort_by(|a, b| {
            let d = |s: &Surface| ((s.min + s.max) * 0.5 - EYE).length();
            d(a).total_cmp(&d(b))
        });
        let mut drawn = 0;
        for material in 1..=6 {
            let (mut pos, mut uv) = (Vec::new(), Vec::new());
            for s in visible.iter().filter(|s| s.material == material) {
                if pos.len() + s.positions.len() > 1000 {
                    drawn += offer(world, material, &pos, &uv);
                    pos.clear();
                    uv.clear();
                }
                for t in 0..s.positions.len() / 3 {
                    for v in 0..3 {
                        let k = 3 * t + (v + frame as usize) % 3;
                        pos.push(s.positions[k]);
                        uv.push(s.texcoords[k]);
                    }
                }
            }
            drawn += offer(world, material, &pos, &uv);
        }
        (world.end_frame(), drawn)
    }

    fn offer(world: &mut StaticWorld, material: u64, positions: &[[f32; 3]], texcoords: &[[f32; 2]]) -> usize {
        let o = offer_plain(world, material, positions, Some(texcoords));
        o.static_triangles + o.new_triangles
    }

    /// Offers `positions` (and `texcoords`) of `material` with default shading.
    fn offer_plain(world: &mut StaticWorld, material: u64, positions: &[[f32; 3]], texcoords: Option<&[[f32; 2]]>) -> Offered {
        let shading = ChunkShading::default();
        world.offer(WorldTriangles { material_key: material, material: MaterialOverride::default(), textures: [None; CHUNK_UNITS], positions, texcoords: [texcoords, None], colors: None, shading: &shading })
    }

    /// Every chunk triangle's key: the world holds each once.
    fn keys(update: &WorldUpdate) -> HashSet<u64> {
        let mut keys = HashSet::new();
        for c in update.chunks.iter() {
            for t in c.positions.chunks(3) {
                assert!(keys.insert(triangle_key(&[t[0], t[1], t[2]], c.material_key)), "duplicate triangle {t:?}");
            }
        }
        keys
    }

    /// A wall of `n` quads at z = -5 in front of a camera at the origin looking down -z,
    /// counter-clockwise towards the camera.
    fn wall(n: usize) -> Vec<[f32; 3]> {
        let mut p = Vec::new();
        for i in 0..n {
            let x = -2.0 + 4.0 * i as f32 / n as f32;
            let (x1, y0, y1) = (x + 4.0 / n as f32, -1.0, 1.0);
            p.extend_from_slice(&[[x, y0, -5.0], [x1, y0, -5.0], [x1, y1, -5.0], [x, y0, -5.0], [x1, y1, -5.0], [x, y1, -5.0]]);
        }
        p
    }

    fn front_view() -> Mat4 {
        perspective(90.0, 1.0, 0.1, 100.0)
    }

    fn frame(world: &mut StaticWorld, f: u64, m: Mat4, batches: &[(u64, &[[f32; 3]])]) -> (WorldUpdate, Offered) {
        world.begin_frame(f, m);
        let mut total = Offered::default();
        for &(material, positions) in batches {
            let o = offer_plain(world, material, positions, None);
            total.static_triangles += o.static_triangles;
            total.new_triangles += o.new_triangles;
        }
        (world.end_frame(), total)
    }

    #[test]
    fn chunks_carry_colours_coordinates_of_both_units_and_the_draw_state() {
        let mut world = StaticWorld::new();
        let positions = wall(2);
        let texcoords: Vec<[f32; 2]> = positions.iter().map(|p| [p[0], p[1]]).collect();
        let lightmap_texcoords: Vec<[f32; 2]> = positions.iter().map(|p| [p[0] / 16.0, 0.5 - p[1] / 16.0]).collect();
        let colors: Vec<[u8; 4]> = (0..positions.len()).map(|i| [i as u8, 0, 255, 255]).collect();
        let state = crate::frame::RasterState { depth_write: true, ..Default::default() };
        let unit = Some(crate::frame::TextureUnit::default());
        let shading = ChunkShading { state: Arc::new(state), texture_units: [unit, unit], light_units: 0b10 };
        let texture = |id| TextureRef { id, version: 1, content: Arc::default() };
        let (surface, lightmap) = (texture(3), texture(4));
        let mut last = None;
        for f in 0..2 {
            world.begin_frame(f, front_view());
            let o = world.offer(WorldTriangles {
                material_key: 1,
                material: MaterialOverride::default(),
                textures: [Some(&surface), Some(&lightmap)],
                positions: &positions,
                texcoords: [Some(&texcoords), Some(&lightmap_texcoords)],
                colors: Some(&colors),
                shading: &shading,
            });
            assert_eq!((o.triangles, o.all_static()), (4, f == 1), "frame {f}: {o:?}");
            last = Some(world.end_frame());
        }
        let update = last.unwrap();
        assert_eq!(update.triangles, 4);
        for c in update.chunks.iter() {
            assert_eq!((c.shading.clone(), c.colors.len()), (shading.clone(), c.positions.len()));
            assert_eq!(c.textures.clone().map(|t| t.map(|t| t.id)), [Some(3), Some(4)]);
            for (k, p) in c.positions.iter().enumerate() {
                let i = positions.iter().position(|q| q == p).unwrap();
                assert_eq!((c.colors[k][2], c.texcoords[0][k], c.texcoords[1][k]), (255, texcoords[i], lightmap_texcoords[i]));
            }
            assert_eq!(c.upload_bytes(), c.positions.len() as u64 * 32, "12 + 8 + 8 + 4 bytes a corner");
            let size = world.cell_size.expect("fixed when the first triangles joined");
            for tri in c.positions.chunks_exact(3) {
                let tri: [[f32; 3]; 3] = [tri[0], tri[1], tri[2]];
                assert_eq!(c.cell, (centroid(&tri) / size).floor().as_ivec3().to_array(), "the grid cell its triangles were grouped in");
            }
        }
    }

    #[test]
    fn the_key_ignores_the_first_vertex_and_keeps_winding_and_material() {
        let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let key = triangle_key(&t, 7);
        assert_eq!(triangle_key(&[t[1], t[2], t[0]], 7), key);
        assert_eq!(triangle_key(&[t[2], t[0], t[1]], 7), key);
        assert_ne!(triangle_key(&[t[0], t[2], t[1]], 7), key, "the other side is another triangle");
        assert_ne!(triangle_key(&t, 8), key, "another material");
        let noisy = t.map(|p| p.map(|c| c + 1e-4));
        assert_eq!(triangle_key(&noisy, 7), key, "noise well below the quantum");
    }

    #[test]
    fn the_same_triangles_in_other_batches_and_orders_join_once() {
        let wall = wall(10);
        let mut world = StaticWorld::new();
        let (u, o) = frame(&mut world, 0, front_view(), &[(1, &wall)]);
        assert_eq!((o.new_triangles, o.static_triangles, u.triangles, u.chunks.len()), (20, 0, 0, 0));
        // Frame 1: three batches in reverse order, each triangle from its second vertex.
        let mut turned: Vec<[f32; 3]> = Vec::new();
        for t in wall.chunks(3).rev() {
            turned.extend_from_slice(&[t[1], t[2], t[0]]);
        }
        let (a, b) = turned.split_at(21);
        let (b, c) = b.split_at(30);
        let (u, o) = frame(&mut world, 1, front_view(), &[(1, c), (1, a), (1, b)]);
        assert_eq!((o.new_triangles, o.static_triangles), (0, 20));
        assert_eq!((u.triangles, u.new_chunks, u.released_chunks), (20, u.chunks.len(), 0));
        assert_eq!(u.upload_bytes, 20 * 3 * 12, "positions only: no texture coordinates were offered");
        assert_eq!(keys(&u).len(), 20);
        let (again, o) = frame(&mut world, 2, front_view(), &[(1, &wall)]);
        assert_eq!((o.new_triangles, o.static_triangles), (0, 20));
        assert_eq!((again.upload_bytes, again.new_chunks, again.released_chunks), (0, 0, 0));
        assert_eq!(again.reused_chunks, u.chunks.len());
        assert!(Arc::ptr_eq(&again.chunks, &u.chunks), "nothing changed: the same list");
    }

    #[test]
    fn a_triangle_offered_twice_in_one_frame_stays_pending() {
        let wall = wall(1);
        let mut world = StaticWorld::new();
        let (u, o) = frame(&mut world, 0, front_view(), &[(1, &wall), (1, &wall)]);
        assert_eq!((o.new_triangles, u.triangles), (2, 0));
    }

    #[test]
    fn a_pending_triangle_not_seen_again_soon_is_forgotten() {
        let wall = wall(1);
        let mut world = StaticWorld::new();
        frame(&mut world, 0, front_view(), &[(1, &wall)]);
        for f in 1..=PENDING_FRAMES + 1 {
            frame(&mut world, f, front_view(), &[]);
        }
        let (u, o) = frame(&mut world, PENDING_FRAMES + 2, front_view(), &[(1, &wall)]);
        assert_eq!((o.new_triangles, u.triangles), (2, 0), "seen again too late: pending anew");
        let (u, _) = frame(&mut world, PENDING_FRAMES + 3, front_view(), &[(1, &wall)]);
        assert_eq!(u.triangles, 2);
    }

    #[test]
    fn an_animated_mesh_whose_triangles_come_back_by_chance_does_not_join() {
        let still = wall(1);
        let mut world = StaticWorld::new();
        for f in 0..20u64 {
            // 18 triangles move every frame, 2 stand still.
            let mut mesh: Vec<[f32; 3]> = wall(9).iter().map(|p| [p[0], p[1] + 0.01 * f as f32, p[2]]).collect();
            mesh.extend_from_slice(&still);
            let (u, _) = frame(&mut world, f, front_view(), &[(1, &mesh)]);
            assert_eq!(u.triangles, 0, "frame {f}");
        }
        // The same two triangles in a draw of their own are static.
        frame(&mut world, 20, front_view(), &[(1, &still)]);
        assert_eq!(frame(&mut world, 21, front_view(), &[(1, &still)]).0.triangles, 2);
    }

    #[test]
    fn a_noisy_copy_is_an_alias_not_a_duplicate() {
        // x on a grid line's edge: the copy rounds to the next grid point.
        let x = 100.5 * QUANTUM;
        let t = [[x - 1e-6, 0.0, -5.0], [x + 1.0, 0.0, -5.0], [x, 1.0, -5.0]];
        let noisy = [[x + 1e-6, 0.0, -5.0], t[1], t[2]];
        assert_ne!(triangle_key(&t, 1), triangle_key(&noisy, 1));
        let mut world = StaticWorld::new();
        frame(&mut world, 0, front_view(), &[(1, &t)]);
        let (u, _) = frame(&mut world, 1, front_view(), &[(1, &t)]);
        assert_eq!(u.triangles, 1);
        frame(&mut world, 2, front_view(), &[(1, &noisy)]);
        let (u, o) = frame(&mut world, 3, front_view(), &[(1, &noisy)]);
        assert_eq!((u.triangles, u.upload_bytes, u.new_chunks, o.static_triangles), (1, 0, 0, 1));
        let (_, o) = frame(&mut world, 4, front_view(), &[(1, &noisy)]);
        assert_eq!((o.static_triangles, o.new_triangles), (1, 0), "the alias finds the original");
    }

    #[test]
    fn a_triangle_no_longer_offered_outside_the_view_stays() {
        let wall = wall(4);
        let mut world = StaticWorld::new();
        frame(&mut world, 0, front_view(), &[(1, &wall)]);
        frame(&mut world, 1, front_view(), &[(1, &wall)]);
        // The camera turns round: the wall is behind it and no longer drawn.
        let behind = front_view() * Mat4::from_rotation_y(std::f32::consts::PI);
        for f in 2..100 {
            let (u, _) = frame(&mut world, f, behind, &[]);
            assert_eq!((u.triangles, u.released_chunks, u.upload_bytes), (8, 0, 0), "frame {f}");
        }
    }

    #[test]
    fn a_triangle_missing_inside_the_view_while_its_neighbours_are_drawn_is_released_and_returns() {
        let wall = wall(10);
        let (gone, rest) = wall.split_at(3);
        let mut world = StaticWorld::new();
        frame(&mut world, 0, front_view(), &[(1, &wall)]);
        frame(&mut world, 1, front_view(), &[(1, &wall)]);
        let mut before = Vec::new();
        for f in 2..2 + u64::from(RELEASE_FRAMES) - 1 {
            let (u, _) = frame(&mut world, f, front_view(), &[(1, rest)]);
            assert_eq!((u.triangles, u.released_chunks), (20, 0), "frame {f}: not yet");
            before = u.chunks.iter().map(|c| c.id).collect();
        }
        let (u, _) = frame(&mut world, 1 + u64::from(RELEASE_FRAMES), front_view(), &[(1, rest)]);
        assert_eq!(u.triangles, 19);
        assert_eq!((u.released_chunks, u.new_chunks), (1, 1), "its chunk is rebuilt without it");
        let rebuilt: Vec<&Arc<StaticChunk>> = u.chunks.iter().filter(|c| !before.contains(&c.id)).collect();
        assert_eq!(rebuilt.len(), 1);
        assert_eq!(u.upload_bytes, rebuilt[0].upload_bytes());
        assert!(u.upload_bytes < 19 * 3 * 12, "only its chunk is uploaded again");
        assert!(!keys(&u).contains(&triangle_key(&[gone[0], gone[1], gone[2]], 1)));
        // It returns when seen in two frames again.
        let f = 2 + u64::from(RELEASE_FRAMES);
        assert_eq!(frame(&mut world, f, front_view(), &[(1, &wall)]).0.triangles, 19);
        assert_eq!(frame(&mut world, f + 1, front_view(), &[(1, &wall)]).0.triangles, 20);
    }

    #[test]
    fn a_missing_triangle_stays_when_nothing_near_it_is_drawn_or_it_faces_away() {
        let wall = wall(10);
        // Reversed: the camera sees its back.
        let back: Vec<[f32; 3]> = wall[..3].iter().rev().copied().collect();
        let mut world = StaticWorld::new();
        frame(&mut world, 0, front_view(), &[(1, &wall[3..]), (1, &back)]);
        frame(&mut world, 1, front_view(), &[(1, &wall[3..]), (1, &back)]);
        for f in 2..40 {
            // The back face is missing while its neighbours are drawn.
            let (u, _) = frame(&mut world, f, front_view(), &[(1, &wall[3..])]);
            assert_eq!(u.triangles, 20, "frame {f}");
        }
        for f in 40..80 {
            // Nothing of the wall's cell is drawn (a PVS cut): no evidence.
            let (u, _) = frame(&mut world, f, front_view(), &[]);
            assert_eq!(u.triangles, 20, "frame {f}");
        }
    }

    #[test]
    fn clear_forgets_everything() {
        let wall = wall(10);
        let mut world = StaticWorld::new();
        frame(&mut world, 0, front_view(), &[(1, &wall)]);
        let (u, _) = frame(&mut world, 1, front_view(), &[(1, &wall)]);
        assert!(u.triangles == 20 && !u.chunks.is_empty());
        world.clear();
        let (after, o) = frame(&mut world, 2, front_view(), &[(1, &wall)]);
        assert_eq!((after.triangles, after.chunks.len(), o.new_triangles), (0, 0, 20));
        assert_eq!(after.released_chunks, u.chunks.len());
        // A replay that starts again (frame numbers go back) clears too.
        frame(&mut world, 3, front_view(), &[(1, &wall)]);
        let (u, _) = frame(&mut world, 0, front_view(), &[(1, &wall)]);
        assert_eq!(u.triangles, 0);
    }

    #[test]
    fn a_quake_3_turn_builds_the_whole_world_once_then_uploads_nothing() {
        const TURN: u64 = 120;
        let surfaces = room();
        let total: usize = surfaces.iter().map(|s| s.positions.len() / 3).sum();
        let mut world = StaticWorld::new();
        let mut uploaded = 0;
        for f in 0..=TURN {
            let (u, drawn) = q3_frame(&mut world, &surfaces, f, turning(f, TURN));
            assert!(drawn < total);
            uploaded += u.upload_bytes;
        }
        for f in TURN + 1..=2 * TURN {
            let (u, drawn) = q3_frame(&mut world, &surfaces, f, turning(f, TURN));
            assert_eq!(u.triangles, total, "frame {f}: every surface, drawn or not");
            assert_eq!((u.upload_bytes, u.new_chunks, u.released_chunks), (0, 0, 0), "frame {f}");
            assert!(drawn < total / 2, "frame {f}: {drawn} of {total} drawn");
            assert_eq!(keys(&u).len(), total, "each triangle once");
        }
        // Merges re-upload some triangles; the whole world went up less than twice.
        let bytes = (total * 3 * 20) as u64;
        assert!(uploaded >= bytes && uploaded < 2 * bytes, "{uploaded} bytes for {bytes}");
    }
}
