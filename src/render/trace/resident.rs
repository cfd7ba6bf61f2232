//! Geometry on the GPU: the bottom-level BVHs, triangles and shading attributes of every
//! traced geometry, in three device-local buffers shared by all geometries, keyed by
//! [`super::scene::geometry_key`].
//!
//! A geometry is built on the CPU the first time its key is seen and copied into the free end
//! of the buffers (through the frame's upload ring); geometries of earlier frames stay where
//! they are, so a static scene uploads nothing after its first frame. When a buffer is full,
//! the geometries not used for [`KEEP_FRAMES`] frames are dropped and the live ones are
//! copied again, packed, into buffers of twice the live size (the GPU is idle meanwhile):
//! dynamic geometry, new every frame, costs an occasional repack, not a leak.

use std::collections::HashMap;
use std::sync::Arc;

use ash::vk;
use gpu_allocator::MemoryLocation;

use super::bvh::{Aabb, Blas, GpuNode, GpuTriangle};
use super::gpu_types::GpuTriangleAttributes;
use super::scene::Geometry;
use crate::render::raster::device::{Buffer, Device, Result};
use crate::render::raster::upload::Ring;

/// Frames a geometry stays after its last use.
pub const KEEP_FRAMES: u64 = 120;

/// A geometry's place in the shared buffers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Its root node in the BLAS node buffer.
    pub blas_root: u32,
    /// Its first triangle in the triangle and attribute buffers.
    pub first_triangle: u32,
    /// Its object-space bounds.
    pub bounds: Aabb,
}

/// A geometry built on the CPU (kept to copy it again when the buffers are repacked).
struct Built {
    blas: Blas,
    attributes: Vec<GpuTriangleAttributes>,
}

struct Entry {
    built: Arc<Built>,
    placement: Placement,
    last_used: u64,
}

/// One of the three shared buffers: capacity and fill in elements.
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
    /// Bytes copied to the GPU in the current frame (statistics).
    pub uploaded: u64,
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

impl Default for Resident {
    fn default() -> Resident {
        Resident {
            entries: HashMap::new(),
            nodes: Shared::new(std::mem::size_of::<GpuNode>() as u64),
            triangles: Shared::new(std::mem::size_of::<GpuTriangle>() as u64),
            attributes: Shared::new(std::mem::size_of::<GpuTriangleAttributes>() as u64),
            uploaded: 0,
        }
    }
}

impl Resident {
    /// The placement of geometry `key` if it is on the GPU (marking it used in `frame`).
    pub fn lookup(&mut self, key: u64, frame: u64) -> Option<Placement> {
        let entry = self.entries.get_mut(&key)?;
        entry.last_used = frame;
        Some(entry.placement)
    }

    /// Builds the BVHs of `geometries` (new keys) and places them, recording their uploads
    /// into `cmd`. Call once per frame, before recording anything that reads the buffers: when
    /// they are full it repacks them (waiting for the GPU), which moves every placement.
    pub fn insert_all(&mut self, device: &Device, cmd: vk::CommandBuffer, ring: &mut Ring, geometries: Vec<(u64, Geometry)>, frame: u64) -> Result<()> {
        let built: Vec<(u64, Arc<Built>)> = geometries
            .into_iter()
            .map(|(key, geometry)| {
                let blas = Blas::build(&geometry.triangles);
                let attributes = blas.order.iter().map(|&i| geometry.attributes.get(i as usize).copied().unwrap_or_default()).collect();
                (key, Arc::new(Built { blas, attributes }))
            })
            .collect();
        let n: u64 = built.iter().map(|(_, b)| b.blas.nodes.len() as u64).sum();
        let t: u64 = built.iter().map(|(_, b)| b.blas.triangles.len() as u64).sum();
        if !self.nodes.fits(n) || !self.triangles.fits(t) || !self.attributes.fits(t) {
            self.repack(device, cmd, ring, frame, n, t)?;
        }
        for (key, built) in built {
            let placement = self.place(device, cmd, ring, &built)?;
            self.entries.insert(key, Entry { built, placement, last_used: frame });
        }
        Ok(())
    }

    /// Copies `built` to the free end of the buffers.
    fn place(&mut self, device: &Device, cmd: vk::CommandBuffer, ring: &mut Ring, built: &Built) -> Result<Placement> {
        let placement = Placement { blas_root: self.nodes.used as u32, first_triangle: self.triangles.used as u32, bounds: built.blas.bounds };
        for (shared, bytes) in [
            (&mut self.nodes, bytemuck::cast_slice::<_, u8>(&built.blas.nodes)),
            (&mut self.triangles, bytemuck::cast_slice(&built.blas.triangles)),
            (&mut self.attributes, bytemuck::cast_slice(&built.attributes)),
        ] {
            if let Some(buffer) = &shared.buffer {
                upload(device, cmd, ring, buffer.raw, shared.used * shared.stride, bytes)?;
            }
            shared.used += bytes.len() as u64 / shared.stride;
            self.uploaded += bytes.len() as u64;
        }
        Ok(placement)
    }

    /// Drops geometries unused for [`KEEP_FRAMES`], makes buffers of twice the live size plus
    /// `nodes`/`triangles` more, and copies the live geometries into them.
    fn repack(&mut self, device: &Device, cmd: vk::CommandBuffer, ring: &mut Ring, frame: u64, nodes: u64, triangles: u64) -> Result<()> {
        device.wait_idle()?;
        self.entries.retain(|_, e| frame.saturating_sub(e.last_used) < KEEP_FRAMES);
        let live_nodes: u64 = self.entries.values().map(|e| e.built.blas.nodes.len() as u64).sum::<u64>() + nodes;
        let live_triangles: u64 = self.entries.values().map(|e| e.built.blas.triangles.len() as u64).sum::<u64>() + triangles;
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST;
        for (shared, live, name) in [
            (&mut self.nodes, live_nodes, "glrt BLAS nodes"),
            (&mut self.triangles, live_triangles, "glrt triangles"),
            (&mut self.attributes, live_triangles, "glrt triangle attributes"),
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

    /// The three buffers (nodes, triangles, attributes) and their used bytes, once any
    /// geometry was placed.
    pub fn buffers(&self) -> Option<[(vk::Buffer, u64); 3]> {
        let get = |s: &Shared| s.buffer.as_ref().map(|b| (b.raw, (s.used * s.stride).max(s.stride)));
        Some([get(&self.nodes)?, get(&self.triangles)?, get(&self.attributes)?])
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
        for shared in [&mut self.nodes, &mut self.triangles, &mut self.attributes] {
            if let Some(b) = shared.buffer.take() {
                device.destroy_buffer(b);
            }
        }
        self.entries.clear();
    }
}
