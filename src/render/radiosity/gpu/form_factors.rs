//! The form-factor matrix on the GPU: `shaders/radiosity/form_factors.comp`, the CPU
//! reference's method ([`crate::render::radiosity::form_factors`]) with its visibility rays
//! through the tracer's BVH traversal (`trace/bvh.glsl`) over one BLAS of every patch
//! triangle, in chunks of rows.
//!
//! Each dispatch computes [`PAIRS_PER_DISPATCH`] entries or fewer (whole rows): a GPU's
//! watchdog never sees a long one, lavapipe's work is split the same way, and the caller's
//! `progress` hears of every chunk. The rows come back through one host-visible buffer of a
//! chunk's size, so the device holds the scene and one chunk, never the matrix.

use bytemuck::{Pod, Zeroable};
use glam::Affine3A;

use super::pass::{ComputePass, Inputs};
use crate::render::radiosity::form_factors::FormFactors;
use crate::render::radiosity::patches::Patches;
use crate::render::radiosity::shader_constants::{BINDING_PATCH_TRIANGLES, BINDING_PATCHES, BINDING_ROWS, GROUP};
use crate::render::raster::device::{Device, Result};
use crate::render::trace::bindings;
use crate::render::trace::bvh::cpu::affine_rows;
use crate::render::trace::bvh::{Blas, Tlas};
use crate::render::trace::gpu_types::GpuInstance;

/// Most matrix entries one dispatch computes.
pub const PAIRS_PER_DISPATCH: usize = 1 << 17;

/// A patch as the shader reads it (`Patch`).
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

/// A patch triangle as the shader reads it (`PatchTriangle`): corners in `xyz`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuPatchTriangle {
    /// The corners, front side counter-clockwise.
    pub v: [[f32; 4]; 3],
}

/// The push constants of a dispatch (`FormFactorPass`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuPass {
    /// Columns of a row.
    pub patch_count: u32,
    /// The receiver of the first row.
    pub first_row: u32,
    /// Rows of the dispatch.
    pub row_count: u32,
    /// Padding.
    pub pad: u32,
}

include!(concat!(env!("OUT_DIR"), "/layouts/radiosity_gpu_types.rs"));

/// The form factors between all `patches`, computed on `device`; `progress(rows done, rows)`
/// after each chunk.
pub fn compute(device: &Device, patches: &Patches, progress: &mut dyn FnMut(usize, usize)) -> Result<FormFactors> {
    let n = patches.patches.len();
    let mut values = vec![0.0f32; n * n];
    if n == 0 {
        return Ok(FormFactors { n, values });
    }
    let blas = Blas::build(&patches.triangles);
    let tlas = Tlas::build(&[blas.bounds]);
    let rows = affine_rows(&Affine3A::IDENTITY).map(|r| r.to_array());
    let instance = GpuInstance { object_to_eye: rows, eye_to_object: rows, previous_object_to_eye: rows, blas_root: 0, first_triangle: 0, flags: 0, material: 0 };
    let gpu_patches: Vec<GpuPatch> = patches
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
    let triangles: Vec<GpuPatchTriangle> = patches.triangles.iter().map(|t| GpuPatchTriangle { v: t.map(|v| v.extend(1.0).to_array()) }).collect();
    let rows_per_dispatch = (PAIRS_PER_DISPATCH / n).clamp(1, n);
    let inputs = Inputs {
        storage: vec![
            (bindings::BLAS_NODES, bytemuck::cast_slice(&blas.nodes)),
            (bindings::TLAS_NODES, bytemuck::cast_slice(&tlas.nodes)),
            (bindings::TRIANGLES, bytemuck::cast_slice(&blas.triangles)),
            (bindings::INSTANCES, bytemuck::bytes_of(&instance)),
            (BINDING_PATCHES, bytemuck::cast_slice(&gpu_patches)),
            (BINDING_PATCH_TRIANGLES, bytemuck::cast_slice(&triangles)),
        ],
        host: Vec::new(),
        image: None,
        output: (BINDING_ROWS, (rows_per_dispatch * n * size_of::<f32>()) as u64),
        push_bytes: size_of::<GpuPass>() as u32,
    };
    let spirv = include_bytes!(concat!(env!("OUT_DIR"), "/shaders/radiosity/form_factors.comp.spv"));
    let mut pass = ComputePass::new(device, spirv, &inputs)?;
    let mut result = Ok(());
    for first in (0..n).step_by(rows_per_dispatch) {
        let count = rows_per_dispatch.min(n - first);
        let push = GpuPass { patch_count: n as u32, first_row: first as u32, row_count: count as u32, pad: 0 };
        result = pass.run(device, bytemuck::bytes_of(&push), [(n as u32).div_ceil(GROUP), count as u32, 1]);
        if result.is_err() {
            break;
        }
        let out: &[f32] = bytemuck::cast_slice(&pass.output()[..count * n * size_of::<f32>()]);
        values[first * n..(first + count) * n].copy_from_slice(out);
        progress(first + count, n);
    }
    pass.destroy(device);
    result.map(|()| FormFactors { n, values })
}
