//! The patches as the GPU passes read them (`shaders/radiosity/patch.glsl`): each patch and
//! its triangles, and one BLAS of every patch triangle under a one-instance TLAS, so that rays
//! through the tracer's traversal (`trace/bvh.glsl`) see the static world as the patches
//! stand for it. The form factors ([`super::form_factors`]) and the direct light
//! ([`super::direct`]) bind the same buffers.

use bytemuck::{Pod, Zeroable};
use glam::Affine3A;

use crate::render::radiosity::patches::Patches;
use crate::render::radiosity::shader_constants::{BINDING_PATCH_TRIANGLES, BINDING_PATCHES};
use crate::render::trace::bindings;
use crate::render::trace::bvh::cpu::affine_rows;
use crate::render::trace::bvh::{Blas, Layout, Tlas};
use crate::render::trace::gpu_types::GpuInstance;
use crate::render::trace::shader_constants::NO_PREVIOUS_TRIANGLES;

/// A patch as the shaders read it (`Patch`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuPatch {
    /// Area-weighted centroid.
    pub position: [f32; 3],
    /// Area.
    pub area: f32,
    /// Unit normal of the front side.
    pub normal: [f32; 3],
    /// First triangle in the patch triangles.
    pub first: u32,
    /// Its triangles.
    pub count: u32,
    /// Padding to 16 bytes.
    pub pad0: u32,
    /// Padding.
    pub pad1: u32,
    /// Padding.
    pub pad2: u32,
}

/// A patch triangle as the shaders read it (`PatchTriangle`): corners in `xyz`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuPatchTriangle {
    /// The corners, front side counter-clockwise.
    pub v: [[f32; 4]; 3],
}

include!(concat!(env!("OUT_DIR"), "/layouts/radiosity_scene_types.rs"));

/// The patches and their BVH, ready to upload.
pub struct PatchScene {
    blas: Blas,
    tlas: Tlas,
    instance: GpuInstance,
    patches: Vec<GpuPatch>,
    triangles: Vec<GpuPatchTriangle>,
}

impl PatchScene {
    /// The scene of `patches`.
    pub fn new(patches: &Patches) -> PatchScene {
        let blas = Blas::build_thorough(&patches.triangles, Layout::Binary);
        let tlas = Tlas::build(&[blas.bounds], Layout::Binary);
        let rows = affine_rows(&Affine3A::IDENTITY).map(|r| r.to_array());
        let instance = GpuInstance { object_to_eye: rows, eye_to_object: rows, previous_object_to_eye: rows, blas_root: 0, first_triangle: 0, flags: 0, material: 0, previous_triangles: NO_PREVIOUS_TRIANGLES, pad0: 0, pad1: 0, pad2: 0 };
        let gpu_patches = patches
            .patches
            .iter()
            .map(|p| GpuPatch {
                position: p.position.to_array(),
                area: p.area,
                normal: p.normal.to_array(),
                first: p.triangles.start as u32,
                count: p.triangles.len() as u32,
                pad0: 0,
                pad1: 0,
                pad2: 0,
            })
            .collect();
        let triangles = patches.triangles.iter().map(|t| GpuPatchTriangle { v: t.map(|v| v.extend(1.0).to_array()) }).collect();
        PatchScene { blas, tlas, instance, patches: gpu_patches, triangles }
    }

    /// The read-only storage buffers of a pass over the scene: the tracer's BVH bindings and
    /// the patches'.
    pub fn storage(&self) -> Vec<(u32, &[u8])> {
        vec![
            (bindings::BLAS_NODES, bytemuck::cast_slice(&self.blas.nodes)),
            (bindings::TLAS_NODES, bytemuck::cast_slice(&self.tlas.nodes)),
            (bindings::TRIANGLES, bytemuck::cast_slice(&self.blas.triangles)),
            (bindings::INSTANCES, bytemuck::bytes_of(&self.instance)),
            (BINDING_PATCHES, bytemuck::cast_slice(&self.patches)),
            (BINDING_PATCH_TRIANGLES, bytemuck::cast_slice(&self.triangles)),
        ]
    }
}
