//! Direct light on the patches, per frame (`shaders/radiosity/direct.comp`): each patch's
//! irradiance from the frame's lights (in the static world's frame:
//! [`crate::render::radiosity::lights`]), averaged over [`DIRECT_POINTS`] points (the
//! centroids of the quarters of its area), with one shadow ray per point and light through the
//! tracer's BVH traversal over the patches' [`PatchScene`]; and its primary radiosity, emission
//! plus albedo times that irradiance, which [`super::gather::Gather`] bounces. One dispatch of
//! one invocation per (patch, point, light), summed per patch in shared memory
//! (`patches_per_group` patches a workgroup).
//!
//! The shader takes a sphere light as a point at its centre (exact where the whole sphere is
//! above a patch's horizon, as `trace::lights` explains) and a directional light of an
//! angular size as its centre direction: one deterministic shadow ray each, no noise from frame
//! to frame. The sky's light is not gathered.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use super::pass::{ComputePass, DispatchTime, Inputs};
use super::scene::PatchScene;
use crate::render::radiosity::patches::Patches;
use crate::render::radiosity::shader_constants::{BINDING_DIRECT, BINDING_LIGHTS, BINDING_PATCH_SURFACES, DIRECT_POINTS, GROUP};
use crate::render::raster::device::{Device, Result};
use crate::render::trace::gpu_types::GpuLight;

/// Most lights one pass takes; past it, the weakest are left out.
pub const MAX_LIGHTS: usize = 256;

/// A patch's surface as the shader reads it (`PatchSurface`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuPatchSurface {
    /// Diffuse reflectance (rgb), linear.
    pub albedo: [f32; 4],
    /// Emitted radiosity (rgb), linear.
    pub emission: [f32; 4],
}

/// What the shader writes per patch (`PatchLight`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuPatchLight {
    /// Direct irradiance (rgb).
    pub irradiance: [f32; 4],
    /// Primary radiosity (rgb).
    pub primary: [f32; 4],
}

/// The push constants (`DirectPass`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuDirectPass {
    /// Patches.
    pub patch_count: u32,
    /// Lights.
    pub light_count: u32,
    /// Patches one workgroup lights ([`patches_per_group`]).
    pub patches_per_group: u32,
    /// Padding.
    pub pad0: u32,
}

include!(concat!(env!("OUT_DIR"), "/layouts/radiosity_direct_types.rs"));

/// A patch's direct light.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PatchLight {
    /// Irradiance from the lights, shadows included.
    pub irradiance: Vec3,
    /// Emission plus albedo times the irradiance.
    pub primary: Vec3,
}

/// The patches on the device and the pass that lights them.
pub struct Direct {
    pass: ComputePass,
    n: usize,
}

impl Direct {
    /// Uploads `patches` (their BVH, albedo and emission) to `device`.
    pub fn new(device: &Device, patches: &Patches) -> Result<Direct> {
        let n = patches.patches.len();
        let scene = PatchScene::new(patches);
        let surfaces: Vec<GpuPatchSurface> =
            patches.patches.iter().map(|p| GpuPatchSurface { albedo: p.albedo.extend(0.0).to_array(), emission: p.emission.extend(0.0).to_array() }).collect();
        let mut storage = scene.storage();
        storage.push((BINDING_PATCH_SURFACES, bytemuck::cast_slice(&surfaces)));
        let inputs = Inputs {
            storage,
            host: vec![(BINDING_LIGHTS, (MAX_LIGHTS * size_of::<GpuLight>()) as u64)],
            image: None,
            output: (BINDING_DIRECT, (n.max(1) * size_of::<GpuPatchLight>()) as u64),
            push_bytes: size_of::<GpuDirectPass>() as u32,
        };
        let spirv = include_bytes!(concat!(env!("OUT_DIR"), "/shaders/radiosity/direct.comp.spv"));
        Ok(Direct { pass: ComputePass::new(device, spirv, &inputs)?, n })
    }

    /// Every patch's direct light from `lights` (in the patches' frame), and the time it took.
    pub fn run(&mut self, device: &Device, lights: &[GpuLight]) -> Result<(Vec<PatchLight>, DispatchTime)> {
        let lights = strongest(lights, MAX_LIGHTS);
        let bytes: &[u8] = bytemuck::cast_slice(&lights);
        self.pass.host_input(0)[..bytes.len()].copy_from_slice(bytes);
        let per_group = patches_per_group(lights.len());
        let push = GpuDirectPass { patch_count: self.n as u32, light_count: lights.len() as u32, patches_per_group: per_group, pad0: 0 };
        let time = self.pass.run_timed(device, bytemuck::bytes_of(&push), [(self.n as u32).div_ceil(per_group).max(1), 1, 1])?;
        let out: &[GpuPatchLight] = bytemuck::cast_slice(&self.pass.output()[..self.n * size_of::<GpuPatchLight>()]);
        let light = out.iter().map(|p| PatchLight { irradiance: Vec3::from_slice(&p.irradiance[..3]), primary: Vec3::from_slice(&p.primary[..3]) }).collect();
        Ok((light, time))
    }

    /// Frees the device's objects.
    pub fn destroy(self, device: &Device) {
        self.pass.destroy(device);
    }
}

/// How many patches one workgroup of [`GROUP`] invocations lights when there are `lights`
/// lights: as many as leave each patch at least one invocation per (point, light) pair, and one
/// patch per workgroup (its invocations looping over the pairs) when it has more pairs than that.
fn patches_per_group(lights: usize) -> u32 {
    (GROUP / (DIRECT_POINTS * lights as u32).max(1)).max(1)
}

/// `lights`, or the `most` of them with the largest intensity (or irradiance) when there are
/// more.
fn strongest(lights: &[GpuLight], most: usize) -> Vec<GpuLight> {
    let mut out = lights.to_vec();
    if out.len() > most {
        let strength = |l: &GpuLight| l.radiance[0] + l.radiance[1] + l.radiance[2];
        out.sort_by(|a, b| strength(b).total_cmp(&strength(a)));
        out.truncate(most);
    }
    out
}
