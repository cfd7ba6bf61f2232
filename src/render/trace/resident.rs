//! Geometry on the GPU: the bottom-level BVHs, triangles, shading attributes and pass corners
//! of every traced geometry, in four device-local buffers shared by all geometries, keyed by
//! [`super::scene::geometry_key`].
//!
//! A geometry is built on the CPU the first time its key is seen and copied into the free end
//! of the buffers (through the frame's upload ring); geometries of earlier frames stay where
//! they are, so a static scene uploads nothing after its first frame. When a buffer is full,
//! the geometries not used for [`KEEP_FRAMES`] frames are dropped and the live ones are
//! copied again, packed, into buffers of twice the live size (the GPU is idle meanwhile):
//! dynamic geometry, new every frame, costs an occasional repack, not a leak.
//!
//! Refit: a new geometry may name a resident one it replaces (the same dynamic instance last
//! frame, same triangle count: [`NewGeometry::refit_from`]). Its BVH is then refitted to the
//! new positions ([`Blas::refit`]: same tree, new boxes) instead of built, unless the refitted
//! tree's SAH cost exceeds [`REFIT_COST_LIMIT`] times that of the last build (the shape drifted
//! too far: built anew). When no other instance of this frame uses the replaced geometry, the
//! refitted one takes its place in the buffers (same sizes: written in place, after a barrier
//! so that frames still in flight finish reading the old shape first); otherwise it is placed
//! at the free end like a new one.
//!
//! Motion: a geometry that replaces another (refitted or built anew) keeps, for the frame it
//! arrives in, the triangles it replaced in its own BVH order ([`Resident::previous`]): the
//! tracer reads where a deforming mesh's hit point was last frame from them (motion vectors
//! of the denoiser).

use std::collections::HashMap;
use std::sync::Arc;

use ash::vk;
use gpu_allocator::MemoryLocation;

use super::bvh::{Aabb, Blas, GpuTriangle, Layout, sah_cost};
use super::gpu_types::{GpuLayerCorners, GpuTriangleAttributes};
use super::scene::Geometry;
use crate::render::raster::device::{Buffer, Device, Result};
use crate::render::raster::upload::Ring;

/// Frames a geometry stays after its last use.
pub const KEEP_FRAMES: u64 = 120;
/// A refitted BVH whose SAH cost exceeds this multiple of its last build's is built anew.
pub const REFIT_COST_LIMIT: f32 = 1.5;

/// A geometry not yet resident, to build (or refit) and place.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NewGeometry {
    /// Its key.
    pub key: u64,
    /// Its triangles and attributes.
    pub geometry: Geometry,
    /// A resident geometry with the same triangle count that this one replaces (a dynamic
    /// instance's last shape): its BVH is refitted rather than a new one built.
    pub refit_from: Option<u64>,
    /// A merged region of the static world's chunks ([`super::regions`]): the keys of its
    /// members, each resident or placed in the same [`Resident::insert_all`], whose input
    /// triangles `geometry` holds in turn (and no attributes: shading reads the members').
    /// Its BVH's triangles name their member and place there ([`Blas::merged`]). Empty for
    /// any other geometry.
    pub members: Vec<u64>,
}

/// A geometry's place in the shared buffers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Its root node in the BLAS node buffer.
    pub blas_root: u32,
    /// Its first triangle in the triangle and attribute buffers.
    pub first_triangle: u32,
    /// Its first record in the layer-corner buffer (`passes` records per triangle).
    pub first_layer_corners: u32,
    /// Its object-space bounds.
    pub bounds: Aabb,
}

/// A geometry built on the CPU (kept to copy it again when the buffers are repacked).
#[derive(Clone)]
struct Built {
    blas: Blas,
    attributes: Vec<GpuTriangleAttributes>,
    /// The passes' corners, `passes` records per triangle, in BVH order.
    layer_corners: Vec<GpuLayerCorners>,
    /// Passes of the surface.
    passes: usize,
    /// SAH cost of the BVH when it was last built (refits compare with it).
    built_cost: f32,
}

impl Built {
    /// Builds the BVH of `geometry` for `layout`, or with `None` only stores its triangles
    /// ([`Blas::unordered`]).
    fn new(geometry: &Geometry, layout: Option<Layout>) -> Built {
        let blas = match layout {
            Some(layout) => Blas::build(&geometry.triangles, layout),
            None => Blas::unordered(&geometry.triangles),
        };
        Built::of(blas, geometry)
    }

    /// `blas` with `geometry`'s attributes and pass corners in its order.
    fn of(blas: Blas, geometry: &Geometry) -> Built {
        let (attributes, layer_corners) = ordered(&blas, geometry);
        Built { built_cost: sah_cost(&blas.nodes), blas, attributes, layer_corners, passes: geometry.passes }
    }

    /// This BVH refitted to `geometry` (same triangle count and passes), if its SAH cost stays
    /// within [`REFIT_COST_LIMIT`] of the last build's.
    fn refitted(mut self, geometry: &Geometry) -> Option<Built> {
        if self.passes != geometry.passes || !self.blas.refit(&geometry.triangles) || sah_cost(&self.blas.nodes) > REFIT_COST_LIMIT * self.built_cost {
            return None;
        }
        (self.attributes, self.layer_corners) = ordered(&self.blas, geometry);
        Some(self)
    }
}

/// The attributes and pass corners of `geometry` in the triangle order of `blas` (none when
/// it has no attributes: a merged region's).
fn ordered(blas: &Blas, geometry: &Geometry) -> (Vec<GpuTriangleAttributes>, Vec<GpuLayerCorners>) {
    if geometry.attributes.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let attributes = blas.order.iter().map(|&i| geometry.attributes.get(i as usize).copied().unwrap_or_default()).collect();
    let n = geometry.passes;
    let corners = blas
        .order
        .iter()
        .flat_map(|&i| (0..n).map(move |k| geometry.layer_corners.get(i as usize * n + k).copied().unwrap_or_default()))
        .collect();
    (attributes, corners)
}

/// `triangles` (stored in `order`: stored triangle `k` is input triangle `order[k]`) in
/// `new_order`, another order of the same input triangles.
fn in_order_of(triangles: &[GpuTriangle], order: &[u32], new_order: &[u32]) -> Vec<GpuTriangle> {
    let mut stored_at = vec![0u32; order.len()];
    for (k, &input) in order.iter().enumerate() {
        stored_at[input as usize] = k as u32;
    }
    new_order.iter().map(|&input| triangles[stored_at[input as usize] as usize]).collect()
}

/// Where a refitted geometry goes.
enum Refit {
    /// Into the place of the geometry it replaces (entry re-keyed already).
    InPlace,
    /// At the free end (the replaced geometry is still used in this frame).
    Elsewhere(Built),
}

struct Entry {
    built: Arc<Built>,
    placement: Placement,
    last_used: u64,
}

/// One of the four shared buffers: capacity and fill in elements.
struct Shared {
    buffer: Option<Buffer>,
    capacity: u64,
    used: u64,
    stride: u64,
}

impl Shared {
    fn new(stride: u64) -> Shared {
        Shared { buffer: None, capacity: 0, used: 0, stride }
    }

    fn fits(&self, n: u64) -> bool {
        self.used + n <= self.capacity
    }
}

/// The geometry cache.
pub struct Resident {
    entries: HashMap<u64, Entry>,
    nodes: Shared,
    triangles: Shared,
    attributes: Shared,
    layer_corners: Shared,
    /// Bytes copied to the GPU by the last [`Resident::insert_all`] (statistics).
    pub uploaded: u64,
    /// Geometries whose BVH the last [`Resident::insert_all`] built.
    pub built: u32,
    /// Geometries whose BVH the last [`Resident::insert_all`] refitted.
    pub refitted: u32,
    /// For each geometry the last [`Resident::insert_all`] placed in place of another, that
    /// one's triangles in the new one's order.
    previous: HashMap<u64, Vec<GpuTriangle>>,
    /// The layout of the compute tracer's BVHs, whose nodes the node buffer holds; `None`:
    /// geometries get no BVH, their triangles stay in input order under an empty root (the
    /// hardware tracer builds its own structures).
    layout: Option<Layout>,
}

/// Copies `bytes` through the ring into `dst` at byte `offset` (recorded into `cmd`).
pub fn upload(device: &Device, cmd: vk::CommandBuffer, ring: &mut Ring, dst: vk::Buffer, offset: u64, bytes: &[u8]) -> Result<()> {
    if bytes.is_empty() {
        return Ok(());
    }
    let src = ring.push(device, bytes, 16)?;
    let region = [vk::BufferCopy { src_offset: src.offset, dst_offset: offset, size: bytes.len() as u64 }];
    // Safety: both buffers are alive for the frame; the ranges lie inside them.
    unsafe { device.raw.cmd_copy_buffer(cmd, src.buffer, dst, &region) };
    Ok(())
}

impl Resident {
    /// An empty cache; `layout`: the layout of the compute tracer's BVHs, `None` for none.
    pub fn new(layout: Option<Layout>) -> Resident {
        Resident {
            entries: HashMap::new(),
            nodes: Shared::new(layout.unwrap_or_default().node_size()),
            triangles: Shared::new(std::mem::size_of::<GpuTriangle>() as u64),
            attributes: Shared::new(std::mem::size_of::<GpuTriangleAttributes>() as u64),
            layer_corners: Shared::new(std::mem::size_of::<GpuLayerCorners>() as u64),
            uploaded: 0,
            built: 0,
            refitted: 0,
            previous: HashMap::new(),
            layout,
        }
    }

    /// The placement of geometry `key` if it is on the GPU (marking it used in `frame`).
    pub fn lookup(&mut self, key: u64, frame: u64) -> Option<Placement> {
        let entry = self.entries.get_mut(&key)?;
        entry.last_used = frame;
        Some(entry.placement)
    }

    /// Builds (or refits) the BVHs of `geometries` (new keys) and places them, recording their
    /// uploads into `cmd`. Call once per frame, before recording anything that reads the
    /// buffers: when they are full it repacks them (waiting for the GPU), which moves every
    /// placement.
    pub fn insert_all(&mut self, device: &Device, cmd: vk::CommandBuffer, ring: &mut Ring, geometries: Vec<NewGeometry>, frame: u64) -> Result<()> {
        (self.uploaded, self.built, self.refitted) = (0, 0, 0);
        self.previous.clear();
        let mut in_place = Vec::new();
        let mut to_place: Vec<(u64, Arc<Built>)> = Vec::new();
        // The triangles (and their input order) of the geometries replaced, copied before a
        // refit takes them.
        let mut replaced: Vec<(u64, Vec<GpuTriangle>, Vec<u32>)> = Vec::new();
        let (merged, geometries): (Vec<NewGeometry>, Vec<NewGeometry>) = geometries.into_iter().partition(|g| !g.members.is_empty());
        for new in geometries {
            let from = new.refit_from.and_then(|from| self.entries.get(&from));
            if let Some(old) = from.filter(|e| e.built.blas.order.len() == new.geometry.triangles.len()) {
                replaced.push((new.key, old.built.blas.triangles.clone(), old.built.blas.order.clone()));
            }
            match self.refit(&new, frame) {
                Some(Refit::InPlace) => in_place.push(new.key),
                Some(Refit::Elsewhere(built)) => to_place.push((new.key, Arc::new(built))),
                None => {
                    to_place.push((new.key, Arc::new(Built::new(&new.geometry, self.layout))));
                    self.built += 1;
                    continue;
                }
            }
            self.refitted += 1;
        }
        // Merged regions, over their members' storage order (members placed above included).
        for new in merged {
            let order = |key: &u64| match self.entries.get(key) {
                Some(entry) => Some(entry.built.blas.order.as_slice()),
                None => to_place.iter().find(|(k, _)| k == key).map(|(_, b)| b.blas.order.as_slice()),
            };
            let Some(orders) = new.members.iter().map(order).collect::<Option<Vec<&[u32]>>>() else { continue };
            let Some(blas) = Blas::merged(&new.geometry.triangles, &orders, self.layout.unwrap_or_default()) else { continue };
            to_place.push((new.key, Arc::new(Built::of(blas, &new.geometry))));
            self.built += 1;
        }
        let n: u64 = to_place.iter().map(|(_, b)| b.blas.node_count() as u64).sum();
        let t: u64 = to_place.iter().map(|(_, b)| b.blas.triangles.len() as u64).sum();
        let c: u64 = to_place.iter().map(|(_, b)| b.layer_corners.len() as u64).sum();
        if !self.nodes.fits(n) || !self.triangles.fits(t) || !self.attributes.fits(t) || !self.layer_corners.fits(c) {
            // Copies every live geometry, the ones refitted in place included.
            self.repack(device, cmd, ring, frame, [n, t, c])?;
        } else if !in_place.is_empty() {
            // Safety: `cmd` is recording outside a rendering pass (the tracer ended it).
            unsafe { super::compute::barrier(&device.raw, cmd, vk::PipelineStageFlags2::COMPUTE_SHADER, vk::PipelineStageFlags2::TRANSFER) };
            for key in in_place {
                if let Some(entry) = self.entries.get(&key) {
                    let (built, placement) = (entry.built.clone(), entry.placement);
                    self.write(device, cmd, ring, &built, &placement)?;
                }
            }
        }
        for (key, built) in to_place {
            let placement = self.place(device, cmd, ring, &built)?;
            self.entries.insert(key, Entry { built, placement, last_used: frame });
        }
        for (key, triangles, order) in replaced {
            if let Some(entry) = self.entries.get(&key) {
                self.previous.insert(key, in_order_of(&triangles, &order, &entry.built.blas.order));
            }
        }
        Ok(())
    }

    /// The triangles that geometry `key` replaced this frame (the same dynamic instance's last
    /// shape), in `key`'s BVH order; `None` for a geometry that replaced none.
    pub fn previous(&self, key: u64) -> Option<&[GpuTriangle]> {
        self.previous.get(&key).map(Vec::as_slice)
    }

    /// Refits the BVH of `new.refit_from` to `new` (see the module doc). In place, the entry
    /// is re-keyed to `new.key` (its upload is left to the caller). `None` when there is
    /// nothing to refit or the refitted tree is too poor (the replaced geometry is then
    /// dropped if this frame does not use it).
    fn refit(&mut self, new: &NewGeometry, frame: u64) -> Option<Refit> {
        let from = new.refit_from?;
        let entry = self.entries.get(&from)?;
        if entry.built.blas.order.len() != new.geometry.triangles.len() {
            return None;
        }
        if entry.last_used == frame {
            return entry.built.as_ref().clone().refitted(&new.geometry).map(Refit::Elsewhere);
        }
        let entry = self.entries.remove(&from)?;
        let built = Arc::try_unwrap(entry.built).unwrap_or_else(|shared| shared.as_ref().clone()).refitted(&new.geometry)?;
        let placement = Placement { bounds: built.blas.bounds, ..entry.placement };
        self.entries.insert(new.key, Entry { built: Arc::new(built), placement, last_used: frame });
        Some(Refit::InPlace)
    }

    /// Copies `built` to the free end of the buffers.
    fn place(&mut self, device: &Device, cmd: vk::CommandBuffer, ring: &mut Ring, built: &Built) -> Result<Placement> {
        let placement = Placement {
            blas_root: self.nodes.used as u32,
            first_triangle: self.triangles.used as u32,
            first_layer_corners: self.layer_corners.used as u32,
            bounds: built.blas.bounds,
        };
        self.write(device, cmd, ring, built, &placement)?;
        self.nodes.used += built.blas.node_count() as u64;
        self.triangles.used += built.blas.triangles.len() as u64;
        // Attributes share the triangles' indices (a merged region's range stays unwritten).
        self.attributes.used = self.triangles.used;
        self.layer_corners.used += built.layer_corners.len() as u64;
        Ok(placement)
    }

    /// Copies `built` into the buffers at `placement`.
    fn write(&mut self, device: &Device, cmd: vk::CommandBuffer, ring: &mut Ring, built: &Built, placement: &Placement) -> Result<()> {
        let (root, first, corners) = (u64::from(placement.blas_root), u64::from(placement.first_triangle), u64::from(placement.first_layer_corners));
        for (shared, at, bytes) in [
            (&self.nodes, root, built.blas.node_bytes()),
            (&self.triangles, first, bytemuck::cast_slice(&built.blas.triangles)),
            (&self.attributes, first, bytemuck::cast_slice(&built.attributes)),
            (&self.layer_corners, corners, bytemuck::cast_slice(&built.layer_corners)),
        ] {
            if let Some(buffer) = &shared.buffer {
                upload(device, cmd, ring, buffer.raw, at * shared.stride, bytes)?;
            }
            self.uploaded += bytes.len() as u64;
        }
        Ok(())
    }

    /// Drops geometries unused for [`KEEP_FRAMES`], makes buffers of twice the live size plus
    /// `more` (nodes, triangles, layer corners), and copies the live geometries into them.
    fn repack(&mut self, device: &Device, cmd: vk::CommandBuffer, ring: &mut Ring, frame: u64, more: [u64; 3]) -> Result<()> {
        device.wait_idle()?;
        self.entries.retain(|_, e| frame.saturating_sub(e.last_used) < KEEP_FRAMES);
        let live = |size: fn(&Built) -> usize| self.entries.values().map(|e| size(&e.built) as u64).sum::<u64>();
        let live_nodes = self.entries.values().map(|e| e.built.blas.node_count() as u64).sum::<u64>() + more[0];
        let live_triangles = live(|b| b.blas.triangles.len()) + more[1];
        let live_corners = live(|b| b.layer_corners.len()) + more[2];
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST;
        for (shared, live, name) in [
            (&mut self.nodes, live_nodes, "glrt BLAS nodes"),
            (&mut self.triangles, live_triangles, "glrt triangles"),
            (&mut self.attributes, live_triangles, "glrt triangle attributes"),
            (&mut self.layer_corners, live_corners, "glrt layer corners"),
        ] {
            if let Some(old) = shared.buffer.take() {
                device.destroy_buffer(old);
            }
            shared.capacity = (live * 2).max(1024);
            shared.used = 0;
            shared.buffer = Some(device.create_buffer(name, shared.capacity * shared.stride, usage, MemoryLocation::GpuOnly)?);
        }
        let mut entries: Vec<(u64, Arc<Built>)> = self.entries.iter().map(|(&k, e)| (k, e.built.clone())).collect();
        entries.sort_by_key(|(k, _)| *k);
        for (key, built) in entries {
            let placement = self.place(device, cmd, ring, &built)?;
            if let Some(e) = self.entries.get_mut(&key) {
                e.placement = placement;
            }
        }
        Ok(())
    }

    /// The four buffers (nodes, triangles, attributes, layer corners) and their used bytes,
    /// once any geometry was placed.
    pub fn buffers(&self) -> Option<[(vk::Buffer, u64); 4]> {
        let get = |s: &Shared| s.buffer.as_ref().map(|b| (b.raw, (s.used * s.stride).max(s.stride)));
        Some([get(&self.nodes)?, get(&self.triangles)?, get(&self.attributes)?, get(&self.layer_corners)?])
    }

    /// The triangles (object space), attributes and pass corners of resident geometry `key`,
    /// in BVH order (the emitter list reads them).
    pub fn contents(&self, key: u64) -> Option<(&[GpuTriangle], &[GpuTriangleAttributes], &[GpuLayerCorners])> {
        let b = &self.entries.get(&key)?.built;
        Some((&b.blas.triangles, &b.attributes, &b.layer_corners))
    }

    /// Geometries on the GPU.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether no geometry is on the GPU.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Frees the buffers (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        for shared in [&mut self.nodes, &mut self.triangles, &mut self.attributes, &mut self.layer_corners] {
            if let Some(b) = shared.buffer.take() {
                device.destroy_buffer(b);
            }
        }
        self.entries.clear();
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::render::trace::gpu_types::GpuCorner;

    /// A `side` × `side` grid of small triangles in the xy plane, offset by `shift`, each
    /// triangle's texture coordinate its index; `place(i)` picks the cell of triangle `i`.
    fn grid(side: usize, shift: Vec3, place: impl Fn(usize) -> usize) -> Geometry {
        let mut g = Geometry::default();
        for i in 0..side * side {
            let cell = place(i);
            let p = Vec3::new((cell % side) as f32, (cell / side) as f32, 0.0) + shift;
            g.triangles.push([p, p + Vec3::X * 0.9, p + Vec3::Y * 0.9]);
            g.attributes.push(GpuTriangleAttributes { corner: [GpuCorner { uv: [[i as f32, 0.0], [0.0; 2]], ..GpuCorner::default() }; 3] });
            // Two passes, the second covering every triangle.
            g.layer_corners.push(GpuLayerCorners::default());
            g.layer_corners.push(GpuLayerCorners { uv: [[i as f32, 0.0]; 3], covered: 1, ..GpuLayerCorners::default() });
        }
        g.passes = 2;
        g
    }

    #[test]
    fn a_refit_keeps_the_layout_until_the_tree_degrades() {
        let built = Built::new(&grid(32, Vec3::ZERO, |i| i), Some(Layout::Binary));
        let moved = grid(32, Vec3::new(3.0, -2.0, 1.0), |i| i);
        let refitted = built.clone().refitted(&moved).expect("a rigid move keeps the tree as good");
        assert_eq!((refitted.blas.nodes.len(), refitted.blas.order.clone()), (built.blas.nodes.len(), built.blas.order.clone()));
        assert_eq!(refitted.blas.bounds.min, Vec3::new(3.0, -2.0, 1.0));
        for (k, &i) in refitted.blas.order.iter().enumerate() {
            assert_eq!(refitted.attributes[k].corner[0].uv[0][0], i as f32, "attributes follow the BVH order");
            assert_eq!(refitted.layer_corners[2 * k + 1].uv[0][0], i as f32, "and so do the passes' corners");
            assert_eq!(refitted.layer_corners[2 * k].covered, 0);
        }
        assert_eq!(refitted.built_cost, built.built_cost);

        // Every triangle moved to a far cell: the leaves' boxes span the grid, the tree is poor.
        let scrambled = grid(32, Vec3::ZERO, |i| i * 397 % 1024);
        assert!(built.clone().refitted(&scrambled).is_none());
        let mut fewer = moved.clone();
        fewer.triangles.pop();
        assert!(built.clone().refitted(&fewer).is_none(), "another triangle count");
        let mut one_pass = moved.clone();
        one_pass.passes = 1;
        assert!(built.refitted(&one_pass).is_none(), "another number of passes");
    }

    #[test]
    fn a_replaced_shape_is_given_in_the_order_of_its_successor() {
        let old = Built::new(&grid(32, Vec3::ZERO, |i| i), Some(Layout::Binary));
        // Built anew (not refitted): another BVH order of the same input triangles.
        let new = Built::new(&grid(32, Vec3::new(5.0, 0.0, 0.0), |i| i * 397 % 1024), Some(Layout::Binary));
        assert_ne!(old.blas.order, new.blas.order);
        let previous = in_order_of(&old.blas.triangles, &old.blas.order, &new.blas.order);
        for (k, &input) in new.blas.order.iter().enumerate() {
            let was = old.blas.order.iter().position(|&i| i == input).unwrap();
            assert_eq!(previous[k], old.blas.triangles[was], "stored triangle {k} is input triangle {input}");
        }
    }

    #[test]
    fn a_geometry_gets_the_nodes_of_the_buffer_layout_only() {
        let g = grid(32, Vec3::ZERO, |i| i);
        let binary = Built::new(&g, Some(Layout::Binary));
        assert!(binary.blas.wide.is_none());
        assert_eq!(binary.blas.node_bytes().len() as u64, binary.blas.nodes.len() as u64 * Layout::Binary.node_size());
        let wide = Built::new(&g, Some(Layout::Wide));
        let collapsed = wide.blas.wide.as_ref().expect("a wide tree for the wide layout").nodes.len();
        assert_eq!(wide.blas.node_count(), collapsed);
        assert_eq!(wide.blas.node_bytes().len() as u64, collapsed as u64 * Layout::Wide.node_size());
        let none = Built::new(&g, None);
        assert_eq!((none.blas.wide.is_none(), none.blas.node_count()), (true, 1));
        // A refit keeps the layout.
        let refitted = wide.refitted(&grid(32, Vec3::new(3.0, -2.0, 1.0), |i| i)).expect("a rigid move");
        assert_eq!(refitted.blas.node_count(), collapsed);
        assert_eq!(refitted.blas.wide.as_ref().map(|w| w.nodes[0].origin), Some([3.0, -2.0, 1.0]));
    }

    #[test]
    fn without_bvhs_triangles_keep_their_order_and_refit_in_place() {
        let built = Built::new(&grid(32, Vec3::ZERO, |i| i), None);
        assert_eq!(built.blas.order, (0..1024).collect::<Vec<u32>>());
        assert_eq!(built.blas.nodes.len(), 1, "one root of two empty leaves");
        assert_eq!(built.attributes[7].corner[0].uv[0][0], 7.0);
        assert_eq!(built.blas.bounds.max, Vec3::new(31.9, 31.9, 0.0));
        let moved = grid(32, Vec3::new(3.0, -2.0, 1.0), |i| i * 397 % 1024);
        let refitted = built.refitted(&moved).expect("no tree to degrade");
        assert_eq!(refitted.blas.triangles[5].v0, [3.0 + (5 * 397 % 1024 % 32) as f32, -2.0 + (5 * 397 % 1024 / 32) as f32, 1.0]);
    }
}
