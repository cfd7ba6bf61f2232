//! `shaders/trace/bvh_wide.glsl` and `shaders/trace/bvh.glsl` on lavapipe equal
//! `render::trace::bvh::cpu`: a compute shader (`tests/shaders/trace_bvh.comp`, compiled here
//! with `glslangValidator`, once per layout) traces a few thousand rays through a scene of
//! transformed instances, one of them alpha-tested (odd triangles rejected), with both queries;
//! every answer of both traversals must match the CPU traversal of the binary BVHs.

use crate::lavapipe;

use std::process::Command;

use ash::vk;
use glam::{Affine3A, Quat, Vec2, Vec3};
use gpu_allocator::MemoryLocation;

use glrt::render::raster::device::{Buffer, Device};
use glrt::render::trace::bindings;
use glrt::render::trace::bvh::cpu::{self, Instance, Scene};
use glrt::render::trace::bvh::{Aabb, Blas, GpuNode, GpuTriangle, Layout, Tlas};
use glrt::render::trace::gpu_types::GpuInstance;
use glrt::render::trace::regions::{self, MergedRun};
use glrt::render::trace::shader_constants::{INSTANCE_ALPHA_TESTED, NO_PREVIOUS_TRIANGLES};

/// Bindings of the test shader's rays and results.
const RAYS: u32 = 15;
const RESULTS: u32 = 16;

/// A deterministic xorshift generator.
struct Rng(u64);

impl Rng {
    fn f32(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    /// A point uniformly in [-s, s]³.
    fn vec(&mut self, s: f32) -> Vec3 {
        Vec3::new(self.f32() * 2.0 - 1.0, self.f32() * 2.0 - 1.0, self.f32() * 2.0 - 1.0) * s
    }
}

/// A grid of `n` × `n` quads (two triangles each) over [-1, 1]² in the z = 0 plane, bumped.
fn grid(n: usize) -> Vec<[Vec3; 3]> {
    let p = |i: usize, j: usize| {
        let (x, y) = (i as f32 / n as f32 * 2.0 - 1.0, j as f32 / n as f32 * 2.0 - 1.0);
        Vec3::new(x, y, 0.2 * (x * 3.0).sin() * (y * 2.0).cos())
    };
    (0..n * n)
        .flat_map(|k| {
            let (i, j) = (k % n, k / n);
            [[p(i, j), p(i + 1, j), p(i + 1, j + 1)], [p(i, j), p(i + 1, j + 1), p(i, j + 1)]]
        })
        .collect()
}

/// `n` random triangles about `size` large in [-1, 1]³.
fn soup(rng: &mut Rng, n: usize, size: f32) -> Vec<[Vec3; 3]> {
    (0..n)
        .map(|_| {
            let c = rng.vec(1.0);
            [c + rng.vec(size), c + rng.vec(size), c + rng.vec(size)]
        })
        .collect()
}

/// The scene on the CPU and the bytes of its GPU buffers.
struct World {
    tlas: Tlas,
    nodes: Vec<GpuNode>,
    triangles: Vec<GpuTriangle>,
    instances: Vec<Instance>,
    /// The GPU's BLAS nodes in the layout of `layout`.
    gpu_nodes: Vec<u8>,
    /// `Instance` records of `instance.glsl`, with the BLAS roots of `layout`.
    records: Vec<GpuInstance>,
    /// The GPU's top level (`tlas` unless [`World::merge`] merged instances).
    gpu_tlas: Tlas,
    /// Each instance's eye-space box, then those of merged runs.
    bounds: Vec<Aabb>,
    /// Each instance's BLAS order (its storage of its input triangles).
    orders: Vec<Vec<u32>>,
    layout: Layout,
}

impl World {
    fn new(placed: &[(Vec<[Vec3; 3]>, Affine3A, bool)], layout: Layout) -> World {
        let (mut nodes, mut gpu_nodes, mut triangles, mut instances, mut records, mut bounds, mut orders) = (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (tris, object_to_eye, alpha) in placed {
            // The CPU traverses the binary nodes, the GPU those of `layout` (of the same tree).
            let blas = Blas::build(tris, layout);
            let (binary_root, root, first) = (nodes.len() as u32, (gpu_nodes.len() as u64 / layout.node_size()) as u32, triangles.len() as u32);
            nodes.extend_from_slice(&blas.nodes);
            gpu_nodes.extend_from_slice(blas.node_bytes());
            triangles.extend_from_slice(&blas.triangles);
            bounds.push(blas.bounds.transformed(object_to_eye));
            let inst = Instance::new(object_to_eye, binary_root, first, *alpha);
            let rows = cpu::affine_rows(object_to_eye).map(|r| r.to_array());
            let record = GpuInstance {
                object_to_eye: rows,
                eye_to_object: inst.eye_to_object.map(|r| r.to_array()),
                previous_object_to_eye: rows,
                blas_root: root,
                first_triangle: first,
                flags: if *alpha { INSTANCE_ALPHA_TESTED } else { 0 },
                material: 0,
                previous_triangles: NO_PREVIOUS_TRIANGLES,
                first_member: 0,
                pad1: 0,
                pad2: 0,
            };
            records.push(record);
            instances.push(inst);
            orders.push(blas.order);
        }
        let tlas = Tlas::build(&bounds, layout);
        World { gpu_tlas: tlas.clone(), tlas, nodes, triangles, instances, gpu_nodes, records, bounds, orders, layout }
    }

    /// For the GPU only, the instances of each of `runs` (of one transform each) traced as one
    /// merged BVH over their triangles, as the compute tracer merges a region's chunks
    /// ([`Blas::merged`], [`regions::merge_records`]); `placed` as given to [`World::new`].
    /// Returns the instances in the GPU's top level.
    fn merge(&mut self, placed: &[(Vec<[Vec3; 3]>, Affine3A, bool)], runs: &[std::ops::Range<usize>]) -> u32 {
        let mut merged = Vec::new();
        for run in runs {
            let triangles: Vec<[Vec3; 3]> = placed[run.clone()].iter().flat_map(|p| p.0.iter().copied()).collect();
            let orders: Vec<&[u32]> = self.orders[run.clone()].iter().map(Vec::as_slice).collect();
            let blas = Blas::merged(&triangles, &orders, self.layout).expect("the members' triangles");
            merged.push(MergedRun {
                records: run.start as u32..run.end as u32,
                blas_root: (self.gpu_nodes.len() as u64 / self.layout.node_size()) as u32,
                first_triangle: self.triangles.len() as u32,
                bounds: blas.bounds.transformed(&placed[run.start].1),
            });
            self.gpu_nodes.extend_from_slice(blas.node_bytes());
            self.triangles.extend_from_slice(&blas.triangles);
        }
        let top = regions::merge_records(&mut self.records, &mut self.bounds, &merged);
        self.gpu_tlas = Tlas::build(&self.bounds, self.layout);
        top
    }

    fn scene(&self) -> Scene<'_> {
        Scene { tlas: &self.tlas.nodes, blas_nodes: &self.nodes, triangles: &self.triangles, instances: &self.instances }
    }
}

/// One ray: origin, tmin, direction, tmax.
#[derive(Clone, Copy)]
struct Ray {
    origin: Vec3,
    dir: Vec3,
    tmin: f32,
    tmax: f32,
}

/// What the shader wrote for one ray.
#[derive(Clone, Copy, Debug)]
struct GpuResult {
    t: f32,
    instance: u32,
    triangle: u32,
    closest: bool,
    any: bool,
    bary: Vec2,
}

/// The test shader's SPIR-V words, traversing BVHs of `layout` (each call compiles into a file
/// of its own: tests of one layout run in parallel).
fn compile_shader(layout: Layout) -> Vec<u32> {
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let out = std::env::temp_dir().join(format!("glrt-trace-bvh-{}-{}-{call}.spv", layout.name(), std::process::id()));
    let define = if layout == Layout::Binary { "-DTRACE_BVH_BINARY" } else { "-DTRACE_BVH_WIDE" };
    let status = Command::new("glslangValidator")
        .args(["-V", "--target-env", "vulkan1.1", define, "-Ishaders", concat!("-I", env!("OUT_DIR"), "/glsl"), "-o"])
        .arg(&out)
        .arg("tests/shaders/trace_bvh.comp")
        .output()
        .expect("glslangValidator (apt-get install glslang-tools)");
    assert!(status.status.success(), "{}", String::from_utf8_lossy(&status.stdout));
    let bytes = std::fs::read(&out).expect("the SPIR-V");
    let _ = std::fs::remove_file(&out);
    ash::util::read_spv(&mut std::io::Cursor::new(bytes)).expect("SPIR-V words")
}

/// A host-visible storage buffer holding `bytes`.
fn upload(device: &Device, name: &str, bytes: &[u8], location: MemoryLocation) -> Buffer {
    let mut buffer = device.create_buffer(name, bytes.len() as u64, vk::BufferUsageFlags::STORAGE_BUFFER, location).expect("buffer");
    buffer.mapped()[..bytes.len()].copy_from_slice(bytes);
    buffer
}

/// Traces `rays` through `world` with the shader on `device`.
fn trace_on_gpu(device: &Device, world: &World, rays: &[Ray]) -> Vec<GpuResult> {
    let raw = &device.raw;
    let ray_words: Vec<f32> = rays.iter().flat_map(|r| [r.origin.x, r.origin.y, r.origin.z, r.tmin, r.dir.x, r.dir.y, r.dir.z, r.tmax]).collect();
    let buffers = [
        (bindings::BLAS_NODES, upload(device, "blas", &world.gpu_nodes, MemoryLocation::CpuToGpu)),
        (bindings::TLAS_NODES, upload(device, "tlas", world.gpu_tlas.node_bytes(), MemoryLocation::CpuToGpu)),
        (bindings::TRIANGLES, upload(device, "triangles", bytemuck::cast_slice(&world.triangles), MemoryLocation::CpuToGpu)),
        (bindings::INSTANCES, upload(device, "instances", bytemuck::cast_slice(&world.records), MemoryLocation::CpuToGpu)),
        (RAYS, upload(device, "rays", bytemuck::cast_slice(&ray_words), MemoryLocation::CpuToGpu)),
        (RESULTS, upload(device, "results", &vec![0u8; rays.len() * 32], MemoryLocation::GpuToCpu)),
    ];
    let spv = compile_shader(world.layout);
    // Safety: every object is created from `raw`, used while alive, and destroyed after the
    // fence says the GPU is done.
    unsafe {
        let module = raw.create_shader_module(&vk::ShaderModuleCreateInfo::default().code(&spv), None).expect("shader module");
        let layout_bindings: Vec<_> = buffers
            .iter()
            .map(|(b, _)| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(*b)
                    .descriptor_type(vk::DescriptorType::STORAGE_BUFFER)
                    .descriptor_count(1)
                    .stage_flags(vk::ShaderStageFlags::COMPUTE)
            })
            .collect();
        let set_layout = raw.create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&layout_bindings), None).expect("set layout");
        let push = [vk::PushConstantRange::default().stage_flags(vk::ShaderStageFlags::COMPUTE).size(4)];
        let layouts = [set_layout];
        let pipeline_layout = raw
            .create_pipeline_layout(&vk::PipelineLayoutCreateInfo::default().set_layouts(&layouts).push_constant_ranges(&push), None)
            .expect("pipeline layout");
        let stage = vk::PipelineShaderStageCreateInfo::default().stage(vk::ShaderStageFlags::COMPUTE).module(module).name(c"main");
        let pipeline = raw
            .create_compute_pipelines(vk::PipelineCache::null(), &[vk::ComputePipelineCreateInfo::default().stage(stage).layout(pipeline_layout)], None)
            .expect("compute pipeline")[0];
        let sizes = [vk::DescriptorPoolSize::default().ty(vk::DescriptorType::STORAGE_BUFFER).descriptor_count(buffers.len() as u32)];
        let pool = raw.create_descriptor_pool(&vk::DescriptorPoolCreateInfo::default().max_sets(1).pool_sizes(&sizes), None).expect("pool");
        let set = raw.allocate_descriptor_sets(&vk::DescriptorSetAllocateInfo::default().descriptor_pool(pool).set_layouts(&layouts)).expect("set")[0];
        let infos: Vec<[vk::DescriptorBufferInfo; 1]> =
            buffers.iter().map(|(_, b)| [vk::DescriptorBufferInfo::default().buffer(b.raw).range(vk::WHOLE_SIZE)]).collect();
        let writes: Vec<_> = buffers
            .iter()
            .zip(&infos)
            .map(|((binding, _), info)| {
                vk::WriteDescriptorSet::default().dst_set(set).dst_binding(*binding).descriptor_type(vk::DescriptorType::STORAGE_BUFFER).buffer_info(info)
            })
            .collect();
        raw.update_descriptor_sets(&writes, &[]);
        let command_pool = raw.create_command_pool(&vk::CommandPoolCreateInfo::default().queue_family_index(device.queue_family), None).expect("command pool");
        let cmd = raw
            .allocate_command_buffers(
                &vk::CommandBufferAllocateInfo::default().command_pool(command_pool).level(vk::CommandBufferLevel::PRIMARY).command_buffer_count(1),
            )
            .expect("command buffer")[0];
        raw.begin_command_buffer(cmd, &vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT)).expect("begin");
        raw.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, pipeline);
        raw.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::COMPUTE, pipeline_layout, 0, &[set], &[]);
        raw.cmd_push_constants(cmd, pipeline_layout, vk::ShaderStageFlags::COMPUTE, 0, &(rays.len() as u32).to_ne_bytes());
        raw.cmd_dispatch(cmd, (rays.len() as u32).div_ceil(64), 1, 1);
        let barrier = [vk::MemoryBarrier::default().src_access_mask(vk::AccessFlags::SHADER_WRITE).dst_access_mask(vk::AccessFlags::HOST_READ)];
        raw.cmd_pipeline_barrier(cmd, vk::PipelineStageFlags::COMPUTE_SHADER, vk::PipelineStageFlags::HOST, vk::DependencyFlags::empty(), &barrier, &[], &[]);
        raw.end_command_buffer(cmd).expect("end");
        let fence = raw.create_fence(&vk::FenceCreateInfo::default(), None).expect("fence");
        let cmds = [cmd];
        raw.queue_submit(device.queue, &[vk::SubmitInfo::default().command_buffers(&cmds)], fence).expect("submit");
        raw.wait_for_fences(&[fence], true, u64::MAX).expect("wait");
        raw.destroy_fence(fence, None);
        raw.destroy_command_pool(command_pool, None);
        raw.destroy_descriptor_pool(pool, None);
        raw.destroy_pipeline(pipeline, None);
        raw.destroy_pipeline_layout(pipeline_layout, None);
        raw.destroy_descriptor_set_layout(set_layout, None);
        raw.destroy_shader_module(module, None);
    }
    let mut buffers = buffers.map(|(_, b)| b);
    let words: Vec<u32> = bytemuck::cast_slice(&buffers[5].mapped()[..rays.len() * 32]).to_vec();
    for b in buffers {
        device.destroy_buffer(b);
    }
    words
        .chunks(8)
        .map(|w| GpuResult {
            t: f32::from_bits(w[0]),
            instance: w[1],
            triangle: w[2],
            closest: w[3] & 1 != 0,
            any: w[3] & 2 != 0,
            bary: Vec2::new(f32::from_bits(w[4]), f32::from_bits(w[5])),
        })
        .collect()
}

/// The alpha test of the shader: odd triangles are rejected.
fn even(_: u32, triangle: u32, _: Vec2) -> bool {
    triangle.is_multiple_of(2)
}

#[test]
fn wide_gpu_traversal_equals_cpu_traversal() {
    traversal_equals_cpu_traversal(Layout::Wide);
}

#[test]
fn binary_gpu_traversal_equals_cpu_traversal() {
    traversal_equals_cpu_traversal(Layout::Binary);
}

#[test]
fn wide_gpu_traversal_of_merged_regions_equals_cpu_traversal_of_their_chunks() {
    merged_regions_equal_their_chunks(Layout::Wide);
}

#[test]
fn binary_gpu_traversal_of_merged_regions_equals_cpu_traversal_of_their_chunks() {
    merged_regions_equal_their_chunks(Layout::Binary);
}

#[test]
fn wide_gpu_traversal_of_many_instances_equals_cpu_traversal() {
    many_instances_equal_cpu_traversal(Layout::Wide);
}

#[test]
fn binary_gpu_traversal_of_many_instances_equals_cpu_traversal() {
    many_instances_equal_cpu_traversal(Layout::Binary);
}

/// Traces `rays` through `world` on lavapipe and on the CPU; asserts that both queries agree
/// for every ray and returns the CPU's closest hits and the GPU's answers.
fn gpu_equals_cpu(world: &World, rays: &[Ray]) -> (Vec<Option<cpu::Hit>>, Vec<GpuResult>) {
    let scene = world.scene();
    let device = lavapipe::select(Device::new);
    let got = trace_on_gpu(&device, world, rays);
    let mut wants = Vec::with_capacity(rays.len());
    for (i, (ray, g)) in rays.iter().zip(&got).enumerate() {
        let want = cpu::closest(&scene, ray.origin, ray.dir, ray.tmin, ray.tmax, even);
        let any = cpu::any(&scene, ray.origin, ray.dir, ray.tmin, ray.tmax, even);
        assert_eq!(g.any, any, "{:?} ray {i}: trace_any", world.layout);
        match want {
            Some(w) => {
                assert!(g.closest, "{:?} ray {i}: GPU missed {w:?}", world.layout);
                assert_eq!((g.instance, g.triangle), (w.instance, w.triangle), "{:?} ray {i}: t {} vs {}", world.layout, g.t, w.t);
                // Relative, and absolute for hits just off the origin (the GPU's fused
                // multiply-adds round differently).
                assert!((g.t - w.t).abs() <= 1e-4 * w.t.abs() + 1e-7 * ray.dir.length().recip(), "ray {i}: t {} vs {}", g.t, w.t);
                assert!(g.bary.abs_diff_eq(w.bary, 1e-3), "ray {i}: bary {} vs {}", g.bary, w.bary);
            }
            None => assert!(!g.closest, "{:?} ray {i}: GPU hit {g:?}, CPU missed", world.layout),
        }
        wants.push(want);
    }
    (wants, got)
}

/// Traces the rays of the test with the GPU traversal of `layout` and the CPU's.
fn traversal_equals_cpu_traversal(layout: Layout) {
    let mut rng = Rng(0x5eed_f00d);
    let t = |s: f32, r: Quat, at: Vec3| Affine3A::from_scale_rotation_translation(Vec3::splat(s), r, at);
    let placed = vec![
        (grid(40), t(0.8, Quat::from_rotation_x(-1.2), Vec3::new(0.0, -0.6, -0.8)), false),
        (soup(&mut rng, 600, 0.25), t(0.5, Quat::from_rotation_y(0.7), Vec3::new(0.5, 0.3, 0.0)), true),
        (soup(&mut rng, 400, 0.1), t(0.6, Quat::from_rotation_z(2.0), Vec3::new(-0.5, 0.1, 0.2)), false),
        (vec![[Vec3::ZERO, Vec3::X, Vec3::Y]], t(1.5, Quat::from_rotation_y(-0.4), Vec3::new(-1.0, 0.6, -1.0)), false),
        (Vec::new(), Affine3A::IDENTITY, false),
        (grid(8), Affine3A::from_mat3_translation(glam::Mat3::from_diagonal(Vec3::new(0.3, 1.0, 0.5)), Vec3::new(0.6, -0.4, 0.5)), false),
    ];
    let world = World::new(&placed, layout);

    let mut rays: Vec<Ray> = (0..4000)
        .map(|_| {
            let origin = rng.vec(1.6);
            let dir = (rng.vec(0.8) - origin) * (0.5 + rng.f32());
            let tmax = if rng.f32() < 0.5 { f32::INFINITY } else { rng.f32() * 3.0 };
            Ray { origin, dir, tmin: if rng.f32() < 0.2 { 0.05 } else { 0.0 }, tmax }
        })
        .collect();
    // Rays at the odd (rejected) triangles of the alpha-tested instance, ending just past them.
    let alpha = &world.instances[1];
    let first = alpha.first_triangle;
    let count = placed[1].0.len() as u32;
    let targeted = rays.len();
    for k in (1..count).step_by(2) {
        let tri = &world.triangles[(first + k) as usize];
        let object = Vec3::from(tri.v0) + Vec3::from(tri.e1) * 0.3 + Vec3::from(tri.e2) * 0.3;
        let origin = Vec3::new(0.1, 0.2, 3.0);
        let dir = placed[1].1.transform_point3(object) - origin;
        rays.push(Ray { origin, dir, tmin: 0.0, tmax: 1.001 });
    }

    let (wants, got) = gpu_equals_cpu(&world, &rays);
    let mut hits = [0usize; 6];
    let mut passed_through = 0;
    for (i, (want, g)) in wants.iter().zip(&got).enumerate() {
        if let Some(w) = want {
            hits[w.instance as usize] += 1;
        }
        if i >= targeted {
            let aimed = first + 1 + 2 * (i - targeted) as u32;
            assert!(!(g.closest && g.triangle == aimed), "ray {i}: rejected triangle {aimed} hit");
            passed_through += usize::from(!g.any);
        }
    }
    println!("hits per instance: {hits:?}; rays through rejected triangles with no other hit: {passed_through}");
    assert!(hits.iter().sum::<usize>() > 1500, "{hits:?}");
    assert!(hits[0] > 100 && hits[1] > 100 && hits[2] > 50 && hits[3] > 10 && hits[5] > 10, "{hits:?}");
    assert_eq!(hits[4], 0);
    assert!(passed_through > 50, "{passed_through}");
}

/// A top level of 512 instances (8 x 8 x 8, every fourth alpha-tested, rotated and scaled,
/// some overlapping) of a few shared shapes, so that the wide top level has inner nodes, leaf
/// groups of several instances and a deep stack, traced with the GPU traversal of `layout`
/// and the CPU's: 3,000 rays from inside and outside the crowd.
fn many_instances_equal_cpu_traversal(layout: Layout) {
    let mut rng = Rng(0xc0ff_ee11);
    let shapes = [grid(6), soup(&mut rng, 120, 0.3), soup(&mut rng, 40, 0.6)];
    let placed: Vec<(Vec<[Vec3; 3]>, Affine3A, bool)> = (0..512)
        .map(|i| {
            let at = Vec3::new((i % 8) as f32, (i / 8 % 8) as f32, (i / 64) as f32) * 0.5 - 1.75 + rng.vec(0.1);
            let object_to_eye = Affine3A::from_scale_rotation_translation(Vec3::splat(0.1 + 0.2 * rng.f32()), Quat::from_rotation_y(rng.f32() * 6.0) * Quat::from_rotation_x(rng.f32() * 6.0), at);
            (shapes[i % 3].clone(), object_to_eye, i % 4 == 1)
        })
        .collect();
    let world = World::new(&placed, layout);
    let rays: Vec<Ray> = (0..3000)
        .map(|k| {
            let origin = if k % 2 == 0 { rng.vec(2.0) } else { rng.vec(6.0) };
            let dir = rng.vec(1.0);
            Ray { origin, dir, tmin: 0.0, tmax: if k % 3 == 0 { 2.0 } else { f32::INFINITY } }
        })
        .collect();
    let (wants, _) = gpu_equals_cpu(&world, &rays);
    let instances_hit: std::collections::HashSet<u32> = wants.iter().flatten().map(|w| w.instance).collect();
    let hit = wants.iter().flatten().count();
    println!("{hit} of {} rays hit, {} instances hit", rays.len(), instances_hit.len());
    assert!(hit > 1000 && instances_hit.len() > 200, "{hit} rays hit {} instances", instances_hit.len());
}

/// Twelve chunk-like instances of one transform (grids and soups side by side, every third
/// alpha-tested, one empty) and two others of their own, traced by the GPU traversal of
/// `layout` with the chunks merged in three runs (the compute tracer's merged regions,
/// `regions::merge_records`) and by the CPU's over the unmerged chunks: the GPU's answers,
/// resolved to the chunk's record and triangle, are the same for every ray, alpha tests
/// included.
fn merged_regions_equal_their_chunks(layout: Layout) {
    let mut rng = Rng(0x4e6e_d5ee);
    let view = Affine3A::from_scale_rotation_translation(Vec3::splat(0.7), Quat::from_rotation_y(0.5) * Quat::from_rotation_x(-0.3), Vec3::new(0.1, -0.2, -0.5));
    let mut placed: Vec<(Vec<[Vec3; 3]>, Affine3A, bool)> = vec![
        (grid(10), Affine3A::from_rotation_translation(Quat::from_rotation_x(1.0), Vec3::new(0.0, 0.0, 1.5)), false),
        (soup(&mut rng, 200, 0.2), Affine3A::from_translation(Vec3::new(-1.0, 0.5, 0.0)), true),
    ];
    for k in 0..12 {
        let at = Vec3::new((k % 4) as f32 * 0.6 - 0.9, (k / 4) as f32 * 0.6 - 0.6, 0.0);
        let shape: Vec<[Vec3; 3]> = match k {
            7 => Vec::new(),
            // Apart (0.6 between centres): overlapping chunks would make ties, which the two
            // traversals may break differently.
            k if k % 2 == 0 => grid(4).iter().map(|t| t.map(|v| v * 0.28 + at)).collect(),
            _ => soup(&mut rng, 60, 0.15).iter().map(|t| t.map(|v| v * 0.25 + at)).collect(),
        };
        placed.push((shape, view, k % 3 == 1));
    }
    let mut world = World::new(&placed, layout);
    assert_eq!(world.merge(&placed, &[2..6, 6..11, 11..14]), 5, "two instances and three merged runs in the top level");
    let rays: Vec<Ray> = (0..3000)
        .map(|k| {
            let origin = rng.vec(2.0);
            let dir = rng.vec(0.6) - origin;
            Ray { origin, dir, tmin: 0.0, tmax: if k % 4 == 0 { 0.8 } else { f32::INFINITY } }
        })
        .collect();
    let (wants, _) = gpu_equals_cpu(&world, &rays);
    let chunks_hit: std::collections::HashSet<u32> = wants.iter().flatten().map(|w| w.instance).filter(|&i| i >= 2).collect();
    let alpha_chunk_hits = wants.iter().flatten().filter(|w| w.instance >= 2 && placed[w.instance as usize].2).count();
    println!("{} of {} rays hit, chunks hit: {chunks_hit:?}, {alpha_chunk_hits} in alpha-tested chunks", wants.iter().flatten().count(), rays.len());
    assert_eq!(chunks_hit.len(), 11, "every chunk but the empty one is hit through its merged BVH");
    assert!(alpha_chunk_hits > 50, "{alpha_chunk_hits}");
}
