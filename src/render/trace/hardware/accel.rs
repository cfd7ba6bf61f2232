//! The hardware tracer's acceleration structures: one bottom-level structure per resident
//! geometry, built from its triangles in BVH order (so primitive `k` is the geometry's triangle
//! `k`, as the compute tracer numbers them), and per frame in flight one top-level structure
//! over the frame's instances, built every frame.
//!
//! A bottom-level structure lives as long as its geometry is resident
//! ([`super::super::resident`]); one whose geometry left, and the build inputs and scratch
//! memory of each build, are freed once every frame in flight that could read them has
//! finished (`slots` frames later).
//!
//! The static world's chunks of one region share one bottom-level structure, a geometry per
//! chunk, and one instance ([`super::regions`]).
//!
//! Geometry that replaces last frame's shape of a dynamic draw (same triangles, moved) is an
//! update (`ALLOW_UPDATE`, `MODE_UPDATE`) of that shape's structure into a new one when it has
//! one, else built with `PREFER_FAST_BUILD | ALLOW_UPDATE`; everything else is built with
//! `PREFER_FAST_TRACE`. Updates are out of place: frames in flight may still trace the old one.

use std::collections::HashMap;

use ash::vk;
use gpu_allocator::MemoryLocation;

use crate::render::trace::regions::{self, Member, Placed};
use crate::render::raster::device::{Buffer, Check, Device, Result};
use crate::render::trace::bvh::GpuTriangle;
use crate::render::trace::resident::Resident;

/// An acceleration structure and the buffer holding it.
struct Structure {
    raw: vk::AccelerationStructureKHR,
    buffer: Buffer,
    /// Its device address (what instances reference).
    address: u64,
    /// Triangles of a bottom level built with `ALLOW_UPDATE` (0: not updatable).
    updatable: u32,
}

/// A frame slot's top-level structure, its scratch memory and its instance records, each
/// reused while large enough.
struct TopLevel {
    structure: Structure,
    scratch: Buffer,
    instances: Buffer,
    /// Instances the three have room for.
    capacity: usize,
}

/// Something the GPU may still read, freed after the frames in flight finished.
enum Retired {
    Structure(Structure),
    Buffer(Buffer),
}

/// One traced instance as the top level holds it.
pub struct TopInstance {
    /// The resident geometry it places.
    pub key: u64,
    /// Rows of its affine object-to-eye transform.
    pub rows: [[f32; 4]; 3],
    /// Its index in the frame's instance records (the shaders' `gl_InstanceCustomIndexEXT`).
    pub index: u32,
    /// Whether it skips the any-hit shader (no alpha test).
    pub opaque: bool,
    /// The region of a static-world chunk merged with the others of its region
    /// ([`super::regions`]); `None`: traced as its own instance.
    pub region: Option<[i32; 3]>,
}

/// A bottom level being built or updated.
struct Pending {
    key: u64,
    triangles: u32,
    flags: vk::BuildAccelerationStructureFlagsKHR,
    /// The structure updated (null: built).
    source: vk::AccelerationStructureKHR,
    vertices: Buffer,
    scratch_offset: u64,
    structure: Structure,
}

/// Bottom-level structures by geometry key and the top levels of the frames in flight.
pub struct Accelerations {
    ext: ash::khr::acceleration_structure::Device,
    bottom: HashMap<u64, Structure>,
    /// Merged bottom levels of regions, by [`regions::members_key`].
    merged: HashMap<u64, Structure>,
    top: Vec<Option<TopLevel>>,
    /// What waits for the frames in flight, with the frame it was retired in.
    retired: Vec<(u64, Retired)>,
    /// Frames begun ([`Accelerations::begin_frame`]).
    frames: u64,
    scratch_alignment: u64,
}

/// Rounds `n` up to a multiple of `alignment` (a power of two).
fn align_up(n: u64, alignment: u64) -> u64 {
    n.div_ceil(alignment) * alignment
}

/// The device address of `buffer`.
fn address(device: &Device, buffer: &Buffer) -> u64 {
    // Safety: the buffer was made with SHADER_DEVICE_ADDRESS usage on a device with
    // bufferDeviceAddress.
    unsafe { device.raw.get_buffer_device_address(&vk::BufferDeviceAddressInfo::default().buffer(buffer.raw)) }
}

impl Accelerations {
    /// Empty, for `slots` frames in flight.
    pub fn new(device: &Device, slots: usize) -> Accelerations {
        let mut properties = vk::PhysicalDeviceAccelerationStructurePropertiesKHR::default();
        let mut all = vk::PhysicalDeviceProperties2::default().push_next(&mut properties);
        // Safety: the device has VK_KHR_acceleration_structure (`Device::ray_tracing`).
        unsafe { device.instance.get_physical_device_properties2(device.physical, &mut all) };
        Accelerations {
            ext: ash::khr::acceleration_structure::Device::new(&device.instance, &device.raw),
            bottom: HashMap::new(),
            merged: HashMap::new(),
            top: (0..slots).map(|_| None).collect(),
            retired: Vec::new(),
            frames: 0,
            scratch_alignment: u64::from(properties.min_acceleration_structure_scratch_offset_alignment).max(1),
        }
    }

    /// Starts a frame: frees what the finished frames no longer read.
    pub fn begin_frame(&mut self, device: &Device) {
        self.frames += 1;
        let slots = self.top.len() as u64;
        let frames = self.frames;
        let (done, waiting): (Vec<_>, Vec<_>) = std::mem::take(&mut self.retired).into_iter().partition(|(f, _)| frames >= f + slots + 1);
        self.retired = waiting;
        for (_, r) in done {
            self.free(device, r);
        }
    }

    fn free(&self, device: &Device, retired: Retired) {
        match retired {
            Retired::Structure(s) => self.destroy_structure(device, s),
            Retired::Buffer(b) => device.destroy_buffer(b),
        }
    }

    fn destroy_structure(&self, device: &Device, s: Structure) {
        // Safety: no frame in flight reads it any more (retired, or the GPU is idle).
        unsafe { self.ext.destroy_acceleration_structure(s.raw, None) };
        device.destroy_buffer(s.buffer);
    }

    /// A structure of `ty` with room for `size` bytes.
    fn create_structure(&self, device: &Device, ty: vk::AccelerationStructureTypeKHR, size: u64) -> Result<Structure> {
        let usage = vk::BufferUsageFlags::ACCELERATION_STRUCTURE_STORAGE_KHR | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS;
        let buffer = device.create_buffer("glrt acceleration structure", size, usage, MemoryLocation::GpuOnly)?;
        let info = vk::AccelerationStructureCreateInfoKHR::default().buffer(buffer.raw).size(size).ty(ty);
        // Safety: valid create info; the buffer outlives the structure.
        let raw = match unsafe { self.ext.create_acceleration_structure(&info, None) }.check("vkCreateAccelerationStructureKHR") {
            Ok(raw) => raw,
            Err(e) => {
                device.destroy_buffer(buffer);
                return Err(e);
            }
        };
        // Safety: `raw` is a structure of this device.
        let address = unsafe { self.ext.get_acceleration_structure_device_address(&vk::AccelerationStructureDeviceAddressInfoKHR::default().acceleration_structure(raw)) };
        Ok(Structure { raw, buffer, address, updatable: 0 })
    }

    /// A build-input or scratch buffer of `size` bytes.
    fn input_buffer(device: &Device, name: &str, size: u64, location: MemoryLocation) -> Result<Buffer> {
        let usage = vk::BufferUsageFlags::ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_KHR
            | vk::BufferUsageFlags::STORAGE_BUFFER
            | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS;
        device.create_buffer(name, size, usage, location)
    }

    /// Whether geometry `key` has its bottom level.
    pub fn has(&self, key: u64) -> bool {
        self.bottom.contains_key(&key)
    }

    /// Records the builds of the bottom levels of the resident geometries `keys` that have none
    /// yet (`replaces`: the geometry a key replaces, the same dynamic draw's last shape, whose
    /// structure it updates), then a barrier before the top level's build reads them; then
    /// retires the bottom levels of geometry no longer resident.
    pub fn build_bottom(&mut self, device: &Device, cmd: vk::CommandBuffer, resident: &Resident, keys: &[u64], replaces: &dyn Fn(u64) -> Option<u64>) -> Result<()> {
        let pending = self.record_bottom(device, cmd, resident, keys, replaces);
        let gone: Vec<u64> = self.bottom.keys().copied().filter(|&k| resident.contents(k).is_none()).collect();
        for key in gone {
            if let Some(s) = self.bottom.remove(&key) {
                self.retired.push((self.frames, Retired::Structure(s)));
            }
        }
        pending
    }

    /// [`Accelerations::build_bottom`]'s builds.
    fn record_bottom(&mut self, device: &Device, cmd: vk::CommandBuffer, resident: &Resident, keys: &[u64], replaces: &dyn Fn(u64) -> Option<u64>) -> Result<()> {
        let mut pending: Vec<Pending> = Vec::new();
        let mut scratch_size = 0u64;
        for &key in keys {
            if self.bottom.contains_key(&key) || pending.iter().any(|p| p.key == key) {
                continue;
            }
            let Some((triangles, _, _)) = resident.contents(key) else { continue };
            if triangles.is_empty() {
                continue;
            }
            let positions = corners(triangles);
            let bytes: &[u8] = bytemuck::cast_slice(&positions);
            let mut vertices = Self::input_buffer(device, "glrt BLAS vertices", bytes.len() as u64, MemoryLocation::CpuToGpu)?;
            vertices.mapped()[..bytes.len()].copy_from_slice(bytes);
            let count = triangles.len() as u32;
            let replaced = replaces(key);
            let flags = if replaced.is_some() {
                vk::BuildAccelerationStructureFlagsKHR::PREFER_FAST_BUILD | vk::BuildAccelerationStructureFlagsKHR::ALLOW_UPDATE
            } else {
                vk::BuildAccelerationStructureFlagsKHR::PREFER_FAST_TRACE
            };
            let source = replaced.and_then(|r| self.bottom.get(&r)).filter(|s| s.updatable == count).map_or(vk::AccelerationStructureKHR::null(), |s| s.raw);
            let geometry = [triangle_geometry(address(device, &vertices), count)];
            let info = vk::AccelerationStructureBuildGeometryInfoKHR::default()
                .ty(vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL)
                .flags(flags)
                .mode(vk::BuildAccelerationStructureModeKHR::BUILD)
                .geometries(&geometry);
            let mut sizes = vk::AccelerationStructureBuildSizesInfoKHR::default();
            // Safety: valid build info.
            unsafe { self.ext.get_acceleration_structure_build_sizes(vk::AccelerationStructureBuildTypeKHR::DEVICE, &info, &[count], &mut sizes) };
            let structure = match self.create_structure(device, vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL, sizes.acceleration_structure_size) {
                Ok(s) if replaced.is_some() => Structure { updatable: count, ..s },
                Ok(s) => s,
                Err(e) => {
                    device.destroy_buffer(vertices);
                    return Err(e);
                }
            };
            let scratch_offset = align_up(scratch_size, self.scratch_alignment);
            scratch_size = scratch_offset + if source == vk::AccelerationStructureKHR::null() { sizes.build_scratch_size } else { sizes.update_scratch_size };
            pending.push(Pending { key, triangles: count, flags, source, vertices, scratch_offset, structure });
        }
        if pending.is_empty() {
            return Ok(());
        }
        let scratch = Self::input_buffer(device, "glrt BLAS scratch", scratch_size + self.scratch_alignment, MemoryLocation::GpuOnly)?;
        let scratch_base = align_up(address(device, &scratch), self.scratch_alignment);
        let geometries: Vec<[vk::AccelerationStructureGeometryKHR; 1]> =
            pending.iter().map(|p| [triangle_geometry(address(device, &p.vertices), p.triangles)]).collect();
        let infos: Vec<vk::AccelerationStructureBuildGeometryInfoKHR> = pending
            .iter()
            .zip(&geometries)
            .map(|(p, g)| {
                let mode = if p.source == vk::AccelerationStructureKHR::null() { vk::BuildAccelerationStructureModeKHR::BUILD } else { vk::BuildAccelerationStructureModeKHR::UPDATE };
                vk::AccelerationStructureBuildGeometryInfoKHR::default()
                    .ty(vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL)
                    .flags(p.flags)
                    .mode(mode)
                    .src_acceleration_structure(p.source)
                    .dst_acceleration_structure(p.structure.raw)
                    .geometries(g)
                    .scratch_data(vk::DeviceOrHostAddressKHR { device_address: scratch_base + p.scratch_offset })
            })
            .collect();
        let ranges: Vec<[vk::AccelerationStructureBuildRangeInfoKHR; 1]> =
            pending.iter().map(|p| [vk::AccelerationStructureBuildRangeInfoKHR::default().primitive_count(p.triangles)]).collect();
        let range_refs: Vec<&[vk::AccelerationStructureBuildRangeInfoKHR]> = ranges.iter().map(|r| &r[..]).collect();
        // Safety: `cmd` is recording outside a rendering pass; every buffer named lives until
        // the frame finishes (retired below); scratch regions do not overlap.
        unsafe {
            self.ext.cmd_build_acceleration_structures(cmd, &infos, &range_refs);
            build_barrier(&device.raw, cmd);
        }
        let frames = self.frames;
        self.retired.push((frames, Retired::Buffer(scratch)));
        for p in pending {
            self.retired.push((frames, Retired::Buffer(p.vertices)));
            self.bottom.insert(p.key, p.structure);
        }
        Ok(())
    }

    /// Records the builds of the merged bottom levels of `runs` (their members, in order) that
    /// have none ([`regions::plan`]), retires those no run names (unless there is no run: a
    /// frame without the static world, such as a menu, keeps them for its return), then a
    /// barrier when anything was built; returns each run's [`regions::members_key`].
    fn build_merged(&mut self, device: &Device, cmd: vk::CommandBuffer, resident: &Resident, runs: &[Vec<Member>]) -> Result<Vec<u64>> {
        if runs.is_empty() {
            return Ok(Vec::new());
        }
        let keys: Vec<u64> = runs.iter().map(|m| regions::members_key(m)).collect();
        let (build, retire) = regions::plan(&self.merged, &keys);
        let frames = self.frames;
        for key in retire {
            if let Some(s) = self.merged.remove(&key) {
                self.retired.push((frames, Retired::Structure(s)));
            }
        }
        /// A merged bottom level being built: a geometry per member.
        struct Merge {
            key: u64,
            geometries: Vec<vk::AccelerationStructureGeometryKHR<'static>>,
            counts: Vec<u32>,
            scratch_offset: u64,
            structure: Structure,
        }
        let mut pending: Vec<Merge> = Vec::new();
        let mut scratch_size = 0u64;
        for key in build {
            let Some(members) = keys.iter().position(|&k| k == key).map(|i| &runs[i]) else { continue };
            let contents: Vec<&[GpuTriangle]> = members.iter().map(|m| resident.contents(m.key).map_or(&[][..], |c| c.0)).collect();
            let positions: Vec<[f32; 3]> = contents.iter().flat_map(|t| corners(t)).collect();
            if positions.is_empty() {
                continue;
            }
            let bytes: &[u8] = bytemuck::cast_slice(&positions);
            let mut vertices = Self::input_buffer(device, "glrt merged BLAS vertices", bytes.len() as u64, MemoryLocation::CpuToGpu)?;
            vertices.mapped()[..bytes.len()].copy_from_slice(bytes);
            let base = address(device, &vertices);
            self.retired.push((frames, Retired::Buffer(vertices)));
            let counts: Vec<u32> = contents.iter().map(|t| t.len() as u32).collect();
            let mut first = 0u64;
            let geometries: Vec<vk::AccelerationStructureGeometryKHR<'static>> = members
                .iter()
                .zip(&counts)
                .map(|(m, &count)| {
                    let geometry = triangle_geometry(base + first * 36, count);
                    first += u64::from(count);
                    if m.opaque { geometry.flags(vk::GeometryFlagsKHR::OPAQUE) } else { geometry }
                })
                .collect();
            let info = vk::AccelerationStructureBuildGeometryInfoKHR::default()
                .ty(vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL)
                .flags(vk::BuildAccelerationStructureFlagsKHR::PREFER_FAST_TRACE)
                .mode(vk::BuildAccelerationStructureModeKHR::BUILD)
                .geometries(&geometries);
            let mut sizes = vk::AccelerationStructureBuildSizesInfoKHR::default();
            // Safety: valid build info, a count per geometry.
            unsafe { self.ext.get_acceleration_structure_build_sizes(vk::AccelerationStructureBuildTypeKHR::DEVICE, &info, &counts, &mut sizes) };
            let structure = match self.create_structure(device, vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL, sizes.acceleration_structure_size) {
                Ok(s) => s,
                Err(e) => {
                    for p in pending {
                        self.retired.push((frames, Retired::Structure(p.structure)));
                    }
                    return Err(e);
                }
            };
            let scratch_offset = align_up(scratch_size, self.scratch_alignment);
            scratch_size = scratch_offset + sizes.build_scratch_size;
            pending.push(Merge { key, geometries, counts, scratch_offset, structure });
        }
        if pending.is_empty() {
            return Ok(keys);
        }
        let scratch = match Self::input_buffer(device, "glrt merged BLAS scratch", scratch_size + self.scratch_alignment, MemoryLocation::GpuOnly) {
            Ok(b) => b,
            Err(e) => {
                for p in pending {
                    self.retired.push((frames, Retired::Structure(p.structure)));
                }
                return Err(e);
            }
        };
        let scratch_base = align_up(address(device, &scratch), self.scratch_alignment);
        let infos: Vec<vk::AccelerationStructureBuildGeometryInfoKHR> = pending
            .iter()
            .map(|p| {
                vk::AccelerationStructureBuildGeometryInfoKHR::default()
                    .ty(vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL)
                    .flags(vk::BuildAccelerationStructureFlagsKHR::PREFER_FAST_TRACE)
                    .mode(vk::BuildAccelerationStructureModeKHR::BUILD)
                    .dst_acceleration_structure(p.structure.raw)
                    .geometries(&p.geometries)
                    .scratch_data(vk::DeviceOrHostAddressKHR { device_address: scratch_base + p.scratch_offset })
            })
            .collect();
        let ranges: Vec<Vec<vk::AccelerationStructureBuildRangeInfoKHR>> =
            pending.iter().map(|p| p.counts.iter().map(|&c| vk::AccelerationStructureBuildRangeInfoKHR::default().primitive_count(c)).collect()).collect();
        let range_refs: Vec<&[vk::AccelerationStructureBuildRangeInfoKHR]> = ranges.iter().map(Vec::as_slice).collect();
        // Safety: `cmd` is recording outside a rendering pass; the vertex and scratch buffers
        // live until the frame finishes (retired); scratch regions do not overlap.
        unsafe {
            self.ext.cmd_build_acceleration_structures(cmd, &infos, &range_refs);
            build_barrier(&device.raw, cmd);
        }
        self.retired.push((frames, Retired::Buffer(scratch)));
        for p in pending {
            self.merged.insert(p.key, p.structure);
        }
        Ok(keys)
    }

    /// Records the build of frame slot `slot`'s top level over `instances` (those whose
    /// geometry has a bottom level; the chunks of a region as one instance of their merged
    /// bottom level, built first when new), then a barrier before tracing reads it; returns it
    /// and its instance count.
    pub fn build_top(&mut self, device: &Device, cmd: vk::CommandBuffer, slot: usize, instances: &[TopInstance], resident: &Resident) -> Result<(vk::AccelerationStructureKHR, u32)> {
        let placed: Vec<Placed> = instances.iter().map(|i| Placed { region: i.region, index: i.index, rows: i.rows }).collect();
        let runs = regions::runs(&placed);
        let members: Vec<Vec<Member>> = runs.iter().map(|r| instances[r.clone()].iter().map(|i| Member { key: i.key, opaque: i.opaque }).collect()).collect();
        let keys = self.build_merged(device, cmd, resident, &members)?;
        let record = |i: &TopInstance, flags: vk::GeometryInstanceFlagsKHR, blas: &Structure| {
            let r = &i.rows;
            vk::AccelerationStructureInstanceKHR {
                transform: vk::TransformMatrixKHR { matrix: [r[0][0], r[0][1], r[0][2], r[0][3], r[1][0], r[1][1], r[1][2], r[1][3], r[2][0], r[2][1], r[2][2], r[2][3]] },
                instance_custom_index_and_mask: vk::Packed24_8::new(i.index, 0xff),
                instance_shader_binding_table_record_offset_and_flags: vk::Packed24_8::new(0, flags.as_raw() as u8),
                acceleration_structure_reference: vk::AccelerationStructureReferenceKHR { device_handle: blas.address },
            }
        };
        let alone = instances.iter().filter(|i| i.region.is_none()).filter_map(|i| {
            let opacity = if i.opaque { vk::GeometryInstanceFlagsKHR::FORCE_OPAQUE } else { vk::GeometryInstanceFlagsKHR::FORCE_NO_OPAQUE };
            Some(record(i, vk::GeometryInstanceFlagsKHR::TRIANGLE_FACING_CULL_DISABLE | opacity, self.bottom.get(&i.key)?))
        });
        // A run's geometries carry their opacity; its first chunk's record is the custom index.
        let merged = runs.iter().zip(&keys).filter_map(|(r, key)| Some(record(&instances[r.start], vk::GeometryInstanceFlagsKHR::TRIANGLE_FACING_CULL_DISABLE, self.merged.get(key)?)));
        let records: Vec<vk::AccelerationStructureInstanceKHR> = alone.chain(merged).collect();
        let count = records.len() as u32;
        let capacity = records.len().max(1).next_power_of_two();
        if self.top[slot].as_ref().is_none_or(|t| t.capacity < records.len()) {
            if let Some(old) = self.top[slot].take() {
                let frames = self.frames;
                self.retired.push((frames, Retired::Structure(old.structure)));
                self.retired.push((frames, Retired::Buffer(old.scratch)));
                self.retired.push((frames, Retired::Buffer(old.instances)));
            }
            let record_bytes = std::mem::size_of::<vk::AccelerationStructureInstanceKHR>() as u64;
            let instances_buffer = Self::input_buffer(device, "glrt TLAS instances", capacity as u64 * record_bytes, MemoryLocation::CpuToGpu)?;
            let geometry = [instance_geometry(address(device, &instances_buffer))];
            let info = top_info(&geometry);
            let mut sizes = vk::AccelerationStructureBuildSizesInfoKHR::default();
            // Safety: valid build info.
            unsafe { self.ext.get_acceleration_structure_build_sizes(vk::AccelerationStructureBuildTypeKHR::DEVICE, &info, &[capacity as u32], &mut sizes) };
            let structure = self.create_structure(device, vk::AccelerationStructureTypeKHR::TOP_LEVEL, sizes.acceleration_structure_size)?;
            let scratch = Self::input_buffer(device, "glrt TLAS scratch", sizes.build_scratch_size + self.scratch_alignment, MemoryLocation::GpuOnly)?;
            self.top[slot] = Some(TopLevel { structure, scratch, instances: instances_buffer, capacity });
        }
        let Some(top) = self.top[slot].as_mut() else { unreachable!("made above") };
        top.instances.mapped()[..std::mem::size_of_val(records.as_slice())].copy_from_slice(instance_bytes(&records));
        let geometry = [instance_geometry(address(device, &top.instances))];
        let scratch = align_up(address(device, &top.scratch), self.scratch_alignment);
        let info = top_info(&geometry).dst_acceleration_structure(top.structure.raw).scratch_data(vk::DeviceOrHostAddressKHR { device_address: scratch });
        let range = [vk::AccelerationStructureBuildRangeInfoKHR::default().primitive_count(count)];
        // Safety: `cmd` is recording outside a rendering pass; this slot's previous frame,
        // the last reader of its top level, has finished.
        unsafe {
            self.ext.cmd_build_acceleration_structures(cmd, &[info], &[&range]);
            build_barrier(&device.raw, cmd);
        }
        Ok((top.structure.raw, count))
    }

    /// Frees everything (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        for (_, r) in std::mem::take(&mut self.retired) {
            self.free(device, r);
        }
        for (_, s) in std::mem::take(&mut self.bottom).into_iter().chain(std::mem::take(&mut self.merged)) {
            self.destroy_structure(device, s);
        }
        for top in std::mem::take(&mut self.top).into_iter().flatten() {
            self.destroy_structure(device, top.structure);
            device.destroy_buffer(top.scratch);
            device.destroy_buffer(top.instances);
        }
    }
}

/// The corner positions of `triangles`, three per triangle (the build input).
fn corners(triangles: &[GpuTriangle]) -> Vec<[f32; 3]> {
    triangles
        .iter()
        .flat_map(|t| {
            let v0 = t.v0;
            let corner = |e: [f32; 3]| [v0[0] + e[0], v0[1] + e[1], v0[2] + e[2]];
            [v0, corner(t.e1), corner(t.e2)]
        })
        .collect()
}

/// The bytes of instance records (`VkAccelerationStructureInstanceKHR` is 64 plain bytes).
fn instance_bytes(records: &[vk::AccelerationStructureInstanceKHR]) -> &[u8] {
    // Safety: the records are plain data without padding (12 floats, two packed u32 and a u64).
    unsafe { std::slice::from_raw_parts(records.as_ptr().cast::<u8>(), std::mem::size_of_val(records)) }
}

/// A non-indexed triangle list of `triangles` at device address `vertices` (3 floats a vertex).
fn triangle_geometry<'a>(vertices: u64, triangles: u32) -> vk::AccelerationStructureGeometryKHR<'a> {
    let data = vk::AccelerationStructureGeometryTrianglesDataKHR::default()
        .vertex_format(vk::Format::R32G32B32_SFLOAT)
        .vertex_data(vk::DeviceOrHostAddressConstKHR { device_address: vertices })
        .vertex_stride(12)
        .max_vertex((triangles * 3).saturating_sub(1))
        .index_type(vk::IndexType::NONE_KHR);
    vk::AccelerationStructureGeometryKHR::default()
        .geometry_type(vk::GeometryTypeKHR::TRIANGLES)
        .geometry(vk::AccelerationStructureGeometryDataKHR { triangles: data })
}

/// Instance records at device address `records`.
fn instance_geometry<'a>(records: u64) -> vk::AccelerationStructureGeometryKHR<'a> {
    let data = vk::AccelerationStructureGeometryInstancesDataKHR::default().data(vk::DeviceOrHostAddressConstKHR { device_address: records });
    vk::AccelerationStructureGeometryKHR::default()
        .geometry_type(vk::GeometryTypeKHR::INSTANCES)
        .geometry(vk::AccelerationStructureGeometryDataKHR { instances: data })
}

/// The top level's build info over `geometry` (one instance geometry).
fn top_info<'a>(geometry: &'a [vk::AccelerationStructureGeometryKHR<'a>; 1]) -> vk::AccelerationStructureBuildGeometryInfoKHR<'a> {
    vk::AccelerationStructureBuildGeometryInfoKHR::default()
        .ty(vk::AccelerationStructureTypeKHR::TOP_LEVEL)
        .flags(vk::BuildAccelerationStructureFlagsKHR::PREFER_FAST_TRACE)
        .mode(vk::BuildAccelerationStructureModeKHR::BUILD)
        .geometries(geometry)
}

/// Acceleration-structure builds finish before later builds and ray tracing read them.
///
/// # Safety
/// `cmd` is recording outside a rendering pass.
unsafe fn build_barrier(d: &ash::Device, cmd: vk::CommandBuffer) {
    let barrier = [vk::MemoryBarrier2::default()
        .src_stage_mask(vk::PipelineStageFlags2::ACCELERATION_STRUCTURE_BUILD_KHR)
        .src_access_mask(vk::AccessFlags2::ACCELERATION_STRUCTURE_WRITE_KHR)
        .dst_stage_mask(vk::PipelineStageFlags2::ACCELERATION_STRUCTURE_BUILD_KHR | vk::PipelineStageFlags2::RAY_TRACING_SHADER_KHR)
        .dst_access_mask(vk::AccessFlags2::ACCELERATION_STRUCTURE_READ_KHR)];
    // Safety: per the function's contract.
    unsafe { d.cmd_pipeline_barrier2(cmd, &vk::DependencyInfo::default().memory_barriers(&barrier)) };
}
