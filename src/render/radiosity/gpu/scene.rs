//! The patches as the GPU passes read them (`shaders/radiosity/patch.glsl`): each patch and
//! its triangles, and their BVH for the tracer's traversal (`trace/bvh.glsl`), so that rays
//! see the static world as the patches stand for it. The form factors
//! ([`super::form_factors`]) and the direct light ([`super::direct`]) bind the same buffers.
//!
//! The BVH is one BLAS per plane (the patches of one quantised normal and plane offset) under a
//! TLAS over the planes, all instances the identity: a plane's boxes are flat, so a ray that
//! crosses a room's empty interior enters few of them, where one BVH over all the triangles
//! has nodes mixing walls whose boxes span the room, each entered by every ray crossing it
//! (`bench/radiosity.md`: 327 nodes a shadow ray in a box of 16k patches).

use bytemuck::{Pod, Zeroable};
use std::collections::BTreeMap;

use glam::{Affine3A, Vec3};

use crate::render::radiosity::patches::{NORMAL_STEPS, Patches};
use crate::render::radiosity::shader_constants::{BINDING_PATCH_TRIANGLES, BINDING_PATCHES};
use crate::render::trace::bindings;
use crate::render::trace::bvh::cpu::affine_rows;
use crate::render::trace::bvh::{Blas, GpuNode, GpuTriangle, Layout, Tlas};
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
    /// Every plane's BLAS nodes, one after the other (each instance's `blas_root`).
    blas_nodes: Vec<GpuNode>,
    /// Every plane's BVH-ordered triangles, one after the other (`first_triangle`).
    blas_triangles: Vec<GpuTriangle>,
    tlas: Tlas,
    instances: Vec<GpuInstance>,
    patches: Vec<GpuPatch>,
    triangles: Vec<GpuPatchTriangle>,
}

impl PatchScene {
    /// The scene of `patches`.
    pub fn new(patches: &Patches) -> PatchScene {
        let rows = affine_rows(&Affine3A::IDENTITY).map(|r| r.to_array());
        let (mut blas_nodes, mut blas_triangles, mut instances, mut bounds) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut groups = planes(patches);
        if groups.is_empty() {
            // No patches: one empty BLAS, so that every buffer has content.
            groups.push(Vec::new());
        }
        for triangles in groups {
            let blas = Blas::build_thorough(&triangles, Layout::Binary);
            instances.push(GpuInstance {
                object_to_eye: rows,
                eye_to_object: rows,
                previous_object_to_eye: rows,
                blas_root: blas_nodes.len() as u32,
                first_triangle: blas_triangles.len() as u32,
                flags: 0,
                material: 0,
                previous_triangles: NO_PREVIOUS_TRIANGLES,
                first_member: 0,
                pad1: 0,
                pad2: 0,
            });
            bounds.push(blas.bounds);
            blas_nodes.extend(blas.nodes);
            blas_triangles.extend(blas.triangles);
        }
        let tlas = Tlas::build(&bounds, Layout::Binary);
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
        PatchScene { blas_nodes, blas_triangles, tlas, instances, patches: gpu_patches, triangles }
    }

    /// The read-only storage buffers of a pass over the scene: the tracer's BVH bindings and
    /// the patches'.
    pub fn storage(&self) -> Vec<(u32, &[u8])> {
        vec![
            (bindings::BLAS_NODES, bytemuck::cast_slice(&self.blas_nodes)),
            (bindings::TLAS_NODES, bytemuck::cast_slice(&self.tlas.nodes)),
            (bindings::TRIANGLES, bytemuck::cast_slice(&self.blas_triangles)),
            (bindings::INSTANCES, bytemuck::cast_slice(&self.instances)),
            (BINDING_PATCHES, bytemuck::cast_slice(&self.patches)),
            (BINDING_PATCH_TRIANGLES, bytemuck::cast_slice(&self.triangles)),
        ]
    }
}

/// The patches' triangles grouped by plane: the patches of one normal quantised as
/// [`crate::render::radiosity::patches`] does and one plane offset (to half the mean patch
/// side) together, planes in key order.
fn planes(patches: &Patches) -> Vec<Vec<[Vec3; 3]>> {
    let n = patches.patches.len().max(1) as f32;
    let side = (patches.patches.iter().map(|p| p.area).sum::<f32>() / n).sqrt();
    let step = if side > 0.0 && side.is_finite() { 0.5 * side } else { 1.0 };
    let mut planes: BTreeMap<([i32; 3], i64), Vec<[Vec3; 3]>> = BTreeMap::new();
    for p in &patches.patches {
        let normal = (p.normal * NORMAL_STEPS).round();
        let offset = (p.normal.dot(p.position) / step).round() as i64;
        planes.entry((normal.as_ivec3().to_array(), offset)).or_default().extend_from_slice(&patches.triangles[p.triangles.clone()]);
    }
    planes.into_values().collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::radiosity::test_scenes::closed_box;

    #[test]
    fn a_closed_box_is_six_planes_of_its_walls_triangles() {
        let p = closed_box(2.0, 0.5);
        let planes = planes(&p);
        assert_eq!(planes.len(), 6);
        for plane in &planes {
            // A wall's 16 patches, all its triangles: one coordinate the same everywhere.
            assert_eq!(plane.len() * 6, p.triangles.len());
            let flat = (0..3).filter(|&a| plane.iter().flatten().all(|v| v[a] == plane[0][0][a])).count();
            assert_eq!(flat, 1, "{plane:?}");
        }
        assert_eq!(planes.iter().map(Vec::len).sum::<usize>(), p.triangles.len());
    }
}
