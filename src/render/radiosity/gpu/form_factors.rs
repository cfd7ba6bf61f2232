//! The form-factor matrix on the GPU: `shaders/radiosity/form_factors.comp`, the CPU
//! reference's method ([`crate::render::radiosity::form_factors`]) with its visibility rays
//! through the tracer's BVH traversal (`trace/bvh.glsl`) over the patches' [`PatchScene`], in
//! chunks of rows.
//!
//! Each dispatch computes [`PAIRS_PER_DISPATCH`] entries or fewer (whole rows): a GPU's
//! watchdog never sees a long one, lavapipe's work is split the same way, and the caller's
//! `progress` hears of every chunk. The rows come back through one host-visible buffer of a
//! chunk's size, so the device holds the scene and one chunk, never the matrix.

use bytemuck::{Pod, Zeroable};

use super::pass::{ComputePass, Inputs};
use super::scene::PatchScene;
use crate::render::radiosity::form_factors::FormFactors;
use crate::render::radiosity::patches::Patches;
use crate::render::radiosity::shader_constants::{BINDING_ROWS, GROUP};
use crate::render::raster::device::{Device, Result};

/// Most matrix entries one dispatch computes.
pub const PAIRS_PER_DISPATCH: usize = 1 << 17;

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
    let scene = PatchScene::new(patches);
    let rows_per_dispatch = (PAIRS_PER_DISPATCH / n).clamp(1, n);
    let inputs = Inputs {
        storage: scene.storage(),
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
