//! Direct light on the patches, per frame (`shaders/radiosity/direct.comp`): each patch's
//! irradiance from the frame's lights (in the static world's frame:
//! [`crate::render::radiosity::lights`]), averaged over [`DIRECT_POINTS`] points (the
//! centroids of the quarters of its area), with one shadow ray per point and light through the
//! tracer's BVH traversal over the patches' [`PatchScene`]; and its primary radiosity, emission
//! plus albedo times that irradiance, which [`super::gather::Gather`] bounces. One dispatch of
//! one invocation per (patch, traced point, light), summed per patch in shared memory
//! (`patches_per_group` patches a workgroup, neighbouring invocations on neighbouring patches).
//!
//! Amortised over updates: with `slices` > 1 an update traces one slice of the (patch, point)
//! pairs, slices in turn, and takes the others' irradiance from the updates that traced them,
//! kept on the device: up to [`DIRECT_POINTS`] slices, `DIRECT_POINTS / slices` points of every
//! patch; past it, one point of every `slices / DIRECT_POINTS`-th patch. The first update
//! traces them all. After the lights change, the patches' light is that of the new lights after
//! `slices` updates ([`Direct::settled`]); until then it mixes the new lights' points with the
//! older lights' (a latency of `slices - 1` updates, for `1 / slices` of the shadow rays).
//!
//! The shader takes a sphere light as a point at its centre (exact where the whole sphere is
//! above a patch's horizon, as `trace::lights` explains) and a directional light of an
//! angular size as its centre direction: one deterministic shadow ray each, no noise from frame
//! to frame. The sky's light is not gathered.
//!
//! Each update also counts its shadow rays' BVH traversal work ([`TraversalWork`]: nodes
//! visited in all and by the longest ray), which bounds the pass's time on a GPU that the rays
//! do not fill (`bench/radiosity.md`).

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use super::pass::{ComputePass, DispatchTime, Inputs};
use super::scene::PatchScene;
use crate::render::radiosity::lights::same_lights;
use crate::render::radiosity::patches::Patches;
use crate::render::radiosity::shader_constants::{BINDING_DIRECT, BINDING_DIRECT_POINTS, BINDING_LIGHTS, BINDING_PATCH_SURFACES, DIRECT_POINTS, GROUP};
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
    /// Direct irradiance (rgb); w: BVH nodes the patch's shadow rays of this update visited.
    pub irradiance: [f32; 4],
    /// Primary radiosity (rgb); w: the most nodes one of those rays visited.
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
    /// Patches one workgroup lights ([`Workgroup`]).
    pub patches_per_group: u32,
    /// Invocations per patch ([`Workgroup`]).
    pub lanes: u32,
    /// Slices of the (patch, point) pairs: pair `(i, k)` is in slice `(i * DIRECT_POINTS + k) %
    /// slices`.
    pub slices: u32,
    /// The slice traced.
    pub phase: u32,
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

/// The BVH traversal work of an update's shadow rays (the tracer's `bvh_nodes_visited`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraversalWork {
    /// (patch, point, light) pairs traced (a pair whose light is behind its point traces no
    /// ray).
    pub pairs: u64,
    /// Nodes visited in all.
    pub nodes: u64,
    /// The most nodes one ray visited.
    pub longest: u32,
}

/// The patches on the device and the pass that lights them.
pub struct Direct {
    pass: ComputePass,
    n: usize,
    /// Slices of the points, each traced by one update.
    slices: u32,
    /// The slice the next update traces; `None` before the first update, which traces all.
    next: Option<u32>,
    /// The lights of the last update.
    lights: Vec<GpuLight>,
    /// Slices last traced under other lights than the last update's.
    stale: u32,
    /// The last update's traversal work.
    work: TraversalWork,
}

impl Direct {
    /// Uploads `patches` (their BVH, albedo and emission) to `device`, for updates that
    /// trace one of `slices` (a divisor or a multiple of [`DIRECT_POINTS`]) slices of the
    /// (patch, point) pairs.
    pub fn new(device: &Device, patches: &Patches, slices: u32) -> Result<Direct> {
        assert!(slices >= 1 && (DIRECT_POINTS % slices == 0 || slices % DIRECT_POINTS == 0), "{slices} slices of {DIRECT_POINTS} points");
        let n = patches.patches.len();
        let scene = PatchScene::new(patches);
        let surfaces: Vec<GpuPatchSurface> =
            patches.patches.iter().map(|p| GpuPatchSurface { albedo: p.albedo.extend(0.0).to_array(), emission: p.emission.extend(0.0).to_array() }).collect();
        let points = vec![0u8; n.max(1) * DIRECT_POINTS as usize * 16];
        let mut storage = scene.storage();
        storage.push((BINDING_PATCH_SURFACES, bytemuck::cast_slice(&surfaces)));
        storage.push((BINDING_DIRECT_POINTS, &points));
        let inputs = Inputs {
            storage,
            host: vec![(BINDING_LIGHTS, (MAX_LIGHTS * size_of::<GpuLight>()) as u64)],
            image: None,
            output: (BINDING_DIRECT, (n.max(1) * size_of::<GpuPatchLight>()) as u64),
            push_bytes: size_of::<GpuDirectPass>() as u32,
        };
        let spirv = include_bytes!(concat!(env!("OUT_DIR"), "/shaders/radiosity/direct.comp.spv"));
        Ok(Direct { pass: ComputePass::new(device, spirv, &inputs)?, n, slices, next: None, lights: Vec::new(), stale: 0, work: TraversalWork::default() })
    }

    /// Every patch's direct light from `lights` (in the patches' frame) as this update's slice
    /// of the points and the kept others give it, and the time it took.
    pub fn run(&mut self, device: &Device, lights: &[GpuLight]) -> Result<(Vec<PatchLight>, DispatchTime)> {
        let lights = strongest(lights, MAX_LIGHTS);
        let bytes: &[u8] = bytemuck::cast_slice(&lights);
        self.pass.host_input(0)[..bytes.len()].copy_from_slice(bytes);
        let (slices, phase) = match self.next {
            None => (1, 0),
            Some(phase) => (self.slices, phase),
        };
        let group = Workgroup::of(DIRECT_POINTS / slices.min(DIRECT_POINTS), lights.len() as u32);
        let patches = (self.n as u32).div_ceil((slices / DIRECT_POINTS).max(1));
        let push = GpuDirectPass {
            patch_count: self.n as u32,
            light_count: lights.len() as u32,
            patches_per_group: group.patches,
            lanes: group.lanes,
            slices,
            phase,
        };
        let time = self.pass.run_timed(device, bytemuck::bytes_of(&push), [patches.div_ceil(group.patches).max(1), 1, 1])?;
        if !same_lights(&self.lights, &lights) {
            self.stale = self.slices;
        }
        self.stale = if slices == 1 { 0 } else { self.stale.saturating_sub(1) };
        self.next = Some((phase + 1) % self.slices);
        self.lights = lights;
        let (point_stride, patch_stride) = (slices.min(DIRECT_POINTS), (slices / DIRECT_POINTS).max(1));
        let out: &[GpuPatchLight] = bytemuck::cast_slice(&self.pass.output()[..self.n * size_of::<GpuPatchLight>()]);
        // The patches this update traced (the others keep an earlier update's numbers).
        let traced = || out.iter().skip((phase / point_stride) as usize).step_by(patch_stride as usize);
        self.work = TraversalWork {
            pairs: traced().count() as u64 * u64::from(DIRECT_POINTS / point_stride) * self.lights.len() as u64,
            nodes: traced().map(|p| p.irradiance[3] as u64).sum(),
            longest: traced().map(|p| p.primary[3] as u32).max().unwrap_or(0),
        };
        let light = out.iter().map(|p| PatchLight { irradiance: Vec3::from_slice(&p.irradiance[..3]), primary: Vec3::from_slice(&p.primary[..3]) }).collect();
        Ok((light, time))
    }

    /// The last update's BVH traversal work.
    pub fn work(&self) -> TraversalWork {
        self.work
    }

    /// Whether every point was traced under the last update's lights: the direct light is
    /// theirs, not partly an earlier update's.
    pub fn settled(&self) -> bool {
        self.stale == 0
    }

    /// Frees the device's objects.
    pub fn destroy(self, device: &Device) {
        self.pass.destroy(device);
    }
}

/// How a workgroup of [`GROUP`] invocations is shared between patches.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Workgroup {
    /// Patches it lights.
    patches: u32,
    /// Invocations per patch, a multiple of the traced points.
    lanes: u32,
}

impl Workgroup {
    /// For `traced` points (a divisor of [`GROUP`]) and `lights` lights: one invocation per
    /// (point, light) pair and as many patches as fit, or one patch per workgroup when it has
    /// more pairs than [`GROUP`] (its invocations looping over them).
    fn of(traced: u32, lights: u32) -> Workgroup {
        let pairs = (traced * lights).max(traced);
        if pairs >= GROUP { Workgroup { patches: 1, lanes: GROUP } } else { Workgroup { patches: GROUP / pairs, lanes: pairs } }
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_workgroup_gives_each_patch_a_multiple_of_its_traced_points_within_the_group() {
        // 4 lights: all 4 points (16 pairs, 4 patches) or one point (4 pairs, 16 patches).
        assert_eq!(Workgroup::of(4, 4), Workgroup { patches: 4, lanes: 16 });
        assert_eq!(Workgroup::of(1, 4), Workgroup { patches: 16, lanes: 4 });
        // No lights: one invocation per point still writes the patch.
        assert_eq!(Workgroup::of(2, 0), Workgroup { patches: 32, lanes: 2 });
        // More pairs than invocations: one patch, its invocations looping.
        assert_eq!(Workgroup::of(4, 100), Workgroup { patches: 1, lanes: GROUP });
        for traced in [1, 2, 4] {
            for lights in 0..40 {
                let w = Workgroup::of(traced, lights);
                assert!(w.patches * w.lanes <= GROUP && w.lanes % traced == 0, "{traced} points, {lights} lights: {w:?}");
                assert!(w.lanes >= (traced * lights).min(GROUP), "{traced} points, {lights} lights: {w:?}");
            }
        }
    }
}
