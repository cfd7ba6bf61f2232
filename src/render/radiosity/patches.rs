//! Patches: the persistent static world's triangles fitted to radiosity elements of about one
//! patch size (seed 004 voxelises the scene; glrt fits patches to the chunks' triangles
//! instead, so a patch never straddles two surfaces and its triangles are exact geometry for
//! the form factors).
//!
//! - **Split.** A triangle whose longest edge exceeds the patch size is bisected at the
//!   midpoint of that edge, recursively ([`MAX_SPLIT_DEPTH`] levels at most), so every
//!   fragment fits a patch.
//! - **Merge.** Fragments are grouped by the surface they lie on (normal quantised to
//!   [`NORMAL_STEPS`] steps per axis, plane offset to half a patch size) and the cube of the
//!   patch-size grid holding their centroid projected onto that plane: small coplanar triangles of one cell become one
//!   patch, opposite sides of a thin wall stay apart.
//! - **Attributes.** Position: the area-weighted centroid; normal: the area-weighted mean of
//!   the fragments' normals (front side by the chunk's `glFrontFace`); albedo: the chunk's
//!   corner colour times the average colour of its [`albedo_texture`] (unit 0's; unit 1's
//!   where unit 0 holds baked light), decoded to linear, area-weighted
//!   (the texture environment is not applied, and alpha-tested texels count as opaque);
//!   emission: the chunk material's emitted radiance ([`chunks::material`]: GL material
//!   emission plus `glrt.toml` `emissive` times the surface colour), area-weighted.
//! - **Order and hash.** Chunks are read in the order of their content hashes and patches are
//!   ordered by their grid key, so the same world gives the same patches in the same order
//!   whatever the chunks' ids and order; [`world_hash`] keys the precomputed matrices.

use std::collections::{BTreeMap, HashMap};
use std::ops::Range;
use std::sync::Arc;

use glam::{DVec3, Vec3};
use xxhash_rust::xxh3::Xxh3;

use crate::frame::state::Winding;
use crate::frame::TextureRef;
use crate::frame::world::{CHUNK_UNITS, StaticChunk};
use crate::render::trace::chunks;
use crate::render::trace::material::MaterialDefaults;
use crate::render::trace::shader_constants::MATERIAL_LAYERS;
use crate::render::trace::scene::srgb_to_linear;
use crate::render::trace::texels::average_color;

/// Steps per unit of each normal component in a patch's surface key.
pub const NORMAL_STEPS: f32 = 8.0;
/// Most bisections of one input triangle (2^16 fragments).
pub const MAX_SPLIT_DEPTH: u32 = 16;
/// Triangles with less area than this are dropped (degenerate).
const MIN_AREA: f32 = 1.0e-12;

/// One radiosity element.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    /// Area-weighted centroid, world space.
    pub position: Vec3,
    /// Unit normal of the front side.
    pub normal: Vec3,
    /// Total area of its triangles.
    pub area: f32,
    /// Diffuse reflectance per channel, linear.
    pub albedo: Vec3,
    /// Emitted radiosity per channel, linear.
    pub emission: Vec3,
    /// Its triangles in [`Patches::triangles`].
    pub triangles: Range<usize>,
}

/// The patches of a static world.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Patches {
    /// The patches in their stable order.
    pub patches: Vec<Patch>,
    /// Every patch's triangles (world space, front side counter-clockwise), patch after patch.
    pub triangles: Vec<[Vec3; 3]>,
    /// [`world_hash`] of the chunks and patch size they were built from.
    pub world_hash: u64,
}

/// A fragment on its way into a patch.
struct Fragment {
    triangle: [Vec3; 3],
    albedo: Vec3,
    emission: Vec3,
}

/// A patch's grid key: quantised normal, plane offset and cell.
type Key = ([i32; 3], i64, [i32; 3]);

/// The hash of one chunk's content (positions, texture coordinates, colours, material and
/// texture version), independent of its id.
pub fn chunk_hash(chunk: &StaticChunk) -> u64 {
    let mut h = Xxh3::new();
    h.update(bytemuck::cast_slice(&chunk.positions));
    h.update(bytemuck::cast_slice(&chunk.texcoords[0]));
    h.update(bytemuck::cast_slice(&chunk.colors));
    h.update(&chunk.material_key.to_le_bytes());
    let m = &chunk.material;
    for x in [m.roughness, m.metalness, m.emissive] {
        h.update(&x.to_le_bytes());
    }
    if let Some(t) = albedo_texture(chunk) {
        h.update(&t.id.to_le_bytes());
        h.update(&t.version.to_le_bytes());
    }
    h.digest()
}

/// The texture whose average colour is `chunk`'s albedo: that of its first carried unit that
/// does not hold baked light (unit 0 for the static world's chunks, which never have light
/// there; the baked draws of `translate::classify::baked_world` may), `None` when that unit
/// has none or every unit holds light.
pub fn albedo_texture(chunk: &StaticChunk) -> Option<&TextureRef> {
    (0..CHUNK_UNITS).find(|&u| chunk.shading.light_units >> u & 1 == 0).and_then(|u| chunks::texture(chunk, u))
}

/// The hash of a static world as patches of `patch_size` see it: its chunks' content hashes
/// in sorted order (the chunks' order and ids do not matter).
pub fn world_hash(chunks: &[Arc<StaticChunk>], patch_size: f32) -> u64 {
    let mut hashes: Vec<u64> = chunks.iter().map(|c| chunk_hash(c)).collect();
    hashes.sort_unstable();
    let mut h = Xxh3::new();
    h.update(b"radiosity world");
    h.update(&patch_size.to_le_bytes());
    for x in hashes {
        h.update(&x.to_le_bytes());
    }
    h.digest()
}

/// The patches of `chunks` at `patch_size` (world units, > 0).
pub fn build(chunks: &[Arc<StaticChunk>], patch_size: f32) -> Patches {
    let mut ordered: Vec<(u64, &StaticChunk)> = chunks.iter().map(|c| (chunk_hash(c), c.as_ref())).collect();
    ordered.sort_by_key(|(h, _)| *h);
    let mut averages: HashMap<(u32, u64), Vec3> = HashMap::new();
    let mut cells: BTreeMap<Key, Vec<Fragment>> = BTreeMap::new();
    for (_, chunk) in ordered {
        let texture = albedo_texture(chunk).map_or(Vec3::ONE, |t| {
            *averages.entry((t.id, t.version)).or_insert_with(|| average_color(&t.content).map_or(Vec3::ONE, |w| linear(unpack(w))))
        });
        let material = chunks::material(chunk, [None; MATERIAL_LAYERS], &MaterialDefaults::default());
        let own_emission = Vec3::new(material.emission[0], material.emission[1], material.emission[2]);
        let clockwise = chunk.shading.state.front_face == Winding::Cw;
        for (t, corners) in chunk.positions.chunks_exact(3).enumerate() {
            let mut tri = [0, 1, 2].map(|k| Vec3::from(corners[k]));
            if clockwise {
                tri.swap(1, 2);
            }
            if !tri.iter().all(|v| v.is_finite()) || area(&tri) < MIN_AREA {
                continue;
            }
            let color = chunk.colors.get(3 * t..3 * t + 3).map_or(Vec3::ONE, |c| {
                let mean = |i: usize| (c[0][i] as f32 + c[1][i] as f32 + c[2][i] as f32) / (3.0 * 255.0);
                linear([mean(0), mean(1), mean(2)])
            });
            let albedo = (color * texture).clamp(Vec3::ZERO, Vec3::ONE);
            let emission = own_emission + material.emission[3] * albedo;
            split(tri, patch_size, MAX_SPLIT_DEPTH, &mut |fragment| {
                // Far from the origin a sliver's halves can round onto one line: such a
                // fragment has no area to give a patch (a cell of only those would be 0 / 0).
                if area(&fragment) > 0.0 {
                    cells.entry(key(&fragment, patch_size)).or_default().push(Fragment { triangle: fragment, albedo, emission });
                }
            });
        }
    }
    let mut out = Patches { world_hash: world_hash(chunks, patch_size), ..Patches::default() };
    for fragments in cells.into_values() {
        let first = out.triangles.len();
        let (mut sum_area, mut centroid, mut normal, mut albedo, mut emission) = (0.0f64, DVec3::ZERO, DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        for f in &fragments {
            let a = f64::from(area(&f.triangle));
            sum_area += a;
            centroid += a * (f.triangle[0] + f.triangle[1] + f.triangle[2]).as_dvec3() / 3.0;
            normal += a * face_normal(&f.triangle).as_dvec3();
            albedo += a * f.albedo.as_dvec3();
            emission += a * f.emission.as_dvec3();
            out.triangles.push(f.triangle);
        }
        out.patches.push(Patch {
            position: (centroid / sum_area).as_vec3(),
            normal: normal.normalize_or_zero().as_vec3(),
            area: sum_area as f32,
            albedo: (albedo / sum_area).as_vec3(),
            emission: (emission / sum_area).as_vec3(),
            triangles: first..out.triangles.len(),
        });
    }
    out
}

/// Calls `emit` with `t`, or with the halves of `t` split at its longest edge's midpoint until
/// every edge is at most `size` (or `depth` splits were made).
fn split(t: [Vec3; 3], size: f32, depth: u32, emit: &mut impl FnMut([Vec3; 3])) {
    let edge = |k: usize| (t[(k + 1) % 3] - t[k]).length();
    let longest = (0..3).max_by(|&a, &b| edge(a).total_cmp(&edge(b))).unwrap_or(0);
    if depth == 0 || edge(longest) <= size {
        emit(t);
        return;
    }
    let (a, b, c) = (t[longest], t[(longest + 1) % 3], t[(longest + 2) % 3]);
    let m = (a + b) * 0.5;
    split([a, m, c], size, depth - 1, emit);
    split([m, b, c], size, depth - 1, emit);
}

/// The grid key of a fragment.
fn key(t: &[Vec3; 3], size: f32) -> Key {
    let n = face_normal(t);
    let centroid = (t[0] + t[1] + t[2]) / 3.0;
    let quantised = (n * NORMAL_STEPS).round();
    let axis = quantised.normalize_or_zero();
    let distance = axis.dot(centroid);
    let offset = (f64::from(distance) / f64::from(size * 0.5)).round() as i64;
    // The cell of the centroid projected onto the plane: no rounding noise across it.
    let cell = ((centroid - axis * distance) / size).floor();
    (quantised.as_ivec3().to_array(), offset, cell.as_ivec3().to_array())
}

/// Area of a triangle.
pub fn area(t: &[Vec3; 3]) -> f32 {
    0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length()
}

/// Unit normal of a counter-clockwise triangle (zero when degenerate).
pub fn face_normal(t: &[Vec3; 3]) -> Vec3 {
    (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero()
}

/// A unorm8 RGBA word's colour channels.
fn unpack(word: u32) -> [f32; 3] {
    std::array::from_fn(|i| ((word >> (8 * i)) & 0xff) as f32 / 255.0)
}

/// Display-encoded colour to linear.
fn linear(c: [f32; 3]) -> Vec3 {
    Vec3::new(srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::class::MaterialOverride;
    use crate::frame::world::ChunkShading;

    /// A chunk of the unit square in the plane z = 0 (two triangles, facing +z), coloured.
    fn square(id: u64, color: [u8; 4], emissive: f32) -> Arc<StaticChunk> {
        let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        Arc::new(StaticChunk {
            id,
            material_key: 1,
            material: MaterialOverride { emissive, ..MaterialOverride::default() },
            textures: [None, None],
            positions: p.to_vec(),
            texcoords: [Vec::new(), Vec::new()],
            colors: vec![color; 6],
            shading: ChunkShading::default(),
            cell: [0; 3],
        })
    }

    #[test]
    fn a_square_becomes_patches_of_the_patch_size() {
        let world = [square(1, [255, 128, 0, 255], 0.0)];
        let p = build(&world, 0.25);
        // Split to edges <= 0.25, merged per 0.25 cell: 16 patches of 1/16 area each.
        assert_eq!(p.patches.len(), 16);
        let total: f32 = p.patches.iter().map(|x| x.area).sum();
        assert!((total - 1.0).abs() < 1e-5, "{total}");
        for x in &p.patches {
            assert!((x.area - 1.0 / 16.0).abs() < 1e-5, "{}", x.area);
            assert!((x.normal - Vec3::Z).length() < 1e-6);
            let cell = (x.position / 0.25).floor();
            assert!((x.position - (cell + 0.5) * 0.25).truncate().length() < 1e-5, "{:?}", x.position);
            assert!((x.albedo - Vec3::new(1.0, srgb_to_linear(128.0 / 255.0), 0.0)).length() < 1e-5);
            assert_eq!(x.emission, Vec3::ZERO);
        }
        // Coarser than the square: one patch.
        assert_eq!(build(&world, 2.0).patches.len(), 1);
    }

    #[test]
    fn a_sliver_far_from_the_origin_makes_no_patch_without_area() {
        // A sliver two f32 steps high at x, y = 4096: its halves' corners round onto one line,
        // so some fragments have no area; a cell of only those made a patch of zero area whose
        // position and albedo were 0 / 0 (NaN: OpenArena's map at 14,916 patches).
        let (x, y) = (4096.0, 4096.0);
        let p = [[x, y, 0.0], [x + 100.0, y, 0.0], [x + 100.0, y + 1.0e-3, 0.0]];
        let mut chunk = Arc::unwrap_or_clone(square(1, [200; 4], 0.0));
        chunk.positions = p.to_vec();
        chunk.colors = vec![[200; 4]; 3];
        let patches = build(&[Arc::new(chunk)], 1.0);
        assert!(!patches.patches.is_empty());
        for x in &patches.patches {
            assert!(x.area > 0.0 && x.position.is_finite() && x.albedo.is_finite() && x.emission.is_finite(), "{x:?}");
        }
        for t in &patches.triangles {
            assert!(area(t) > 0.0, "{t:?}");
        }
    }

    #[test]
    fn order_and_hash_do_not_depend_on_chunk_ids_or_order() {
        let a = square(1, [255; 4], 0.0);
        let mut moved = (*square(2, [255; 4], 2.0)).clone();
        for p in &mut moved.positions {
            p[2] = 1.0;
            p.swap(0, 1);
        }
        let b = Arc::new(moved);
        let one = build(&[a.clone(), b.clone()], 0.5);
        let renamed = Arc::new(StaticChunk { id: 9, ..(*a).clone() });
        let two = build(&[b.clone(), renamed], 0.5);
        assert_eq!(one, two);
        assert_eq!(one.patches.len(), 8);
        // The second square emits 2 x its (white) colour and faces -z.
        let lit: Vec<_> = one.patches.iter().filter(|p| p.emission == Vec3::splat(2.0)).collect();
        assert_eq!(lit.len(), 4);
        assert!(lit.iter().all(|p| (p.normal + Vec3::Z).length() < 1e-6 && p.position.z == 1.0));
        assert_ne!(one.world_hash, build(&[a.clone()], 0.5).world_hash);
        assert_ne!(one.world_hash, build(&[a, b], 0.25).world_hash);
    }

    #[test]
    fn clockwise_front_faces_flip_the_normal() {
        let mut c = (*square(1, [255; 4], 0.0)).clone();
        let mut state = (*c.shading.state).clone();
        state.front_face = Winding::Cw;
        c.shading.state = Arc::new(state);
        let p = build(&[Arc::new(c)], 4.0);
        assert!((p.patches[0].normal + Vec3::Z).length() < 1e-6);
    }
}
