//! The k-bounce matrix on the GPU: [`crate::render::radiosity::bounces::k_bounce`]'s Horner
//! sum `S_{h+1} = F^C + F^C · S_h`, each step a tiled `f32` product
//! (`shaders/radiosity/product.comp`), channel by channel, in dispatches of whole rows (at most
//! [`ENTRIES_PER_DISPATCH`] results: a GPU's watchdog never sees a long one, and each is
//! counted on the progress). Both factors of a step are uploaded to device memory (the left,
//! `F^C`'s channel, again for each step), the rows come back through one host-visible buffer
//! of a dispatch's size: the device holds two `n × n` channels and one chunk, the host the colour
//! matrix, the sum and the step's result. A factor larger than the device's storage buffers
//! can be bound (`maxStorageBufferRange`) is refused with an error that says so.

use bytemuck::{Pod, Zeroable};

use super::pass::{ComputePass, Inputs};
use crate::render::radiosity::matrix::ColourMatrix;
use crate::render::radiosity::progress::Progress;
use crate::render::radiosity::shader_constants::{BINDING_PRODUCT_LEFT, BINDING_PRODUCT_RIGHT, BINDING_PRODUCT_ROWS, PRODUCT_TILE};
use crate::render::raster::device::{Device, Error, Result};

/// Most results one dispatch computes (64 MiB of rows).
pub const ENTRIES_PER_DISPATCH: usize = 1 << 24;

/// The push constants of a dispatch (`ProductPass`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuProductPass {
    /// Rows and columns of the matrices.
    pub n: u32,
    /// The first row of the dispatch.
    pub first_row: u32,
    /// Its rows.
    pub row_count: u32,
    /// Padding.
    pub pad: u32,
}

include!(concat!(env!("OUT_DIR"), "/layouts/radiosity_product_types.rs"));

/// Whether one `n × n` channel can be bound on `device`: `Err` says why not.
pub fn fits(device: &Device, n: usize) -> Result<()> {
    let bytes = (n * n * size_of::<f32>()) as u64;
    let range = u64::from(device.properties.limits.max_storage_buffer_range);
    if bytes > range {
        return Err(Error::NoDevice(format!(
            "a channel of {n} × {n} entries is {bytes} bytes, past the {range} bytes {} binds (maxStorageBufferRange)",
            device.name()
        )));
    }
    Ok(())
}

/// The k-bounce matrix of `colour` on `device` (the CPU's [`k_bounce`] to `f32` rounding:
/// the GPU fuses multiplies and adds), its rows counted on `progress`.
///
/// [`k_bounce`]: crate::render::radiosity::bounces::k_bounce
pub fn k_bounce(device: &Device, colour: &ColourMatrix, k: u32, progress: Progress) -> Result<ColourMatrix> {
    let n = colour.n;
    if k == 0 || n == 0 {
        return Ok(ColourMatrix::zeros(n));
    }
    fits(device, n)?;
    let stage = progress.stage(&format!("k-bounce matrix (k = {k}) on {}", device.name()), u64::from(k - 1) * 3 * n as u64, "rows");
    let mut sum = ColourMatrix { n, channels: [Vec::new(), Vec::new(), Vec::new()] };
    for c in 0..3 {
        let left = &colour.channels[c];
        let mut s = left.clone();
        for _ in 1..k {
            s = step(device, left, &s, n, &|rows| stage.add(rows))?;
        }
        sum.channels[c] = s;
    }
    stage.finish();
    Ok(sum)
}

/// `left + left · right` (`n × n`, row-major), its rows counted on `rows_done`.
fn step(device: &Device, left: &[f32], right: &[f32], n: usize, rows_done: &dyn Fn(u64)) -> Result<Vec<f32>> {
    let tile = PRODUCT_TILE as usize;
    let rows_per_dispatch = ((ENTRIES_PER_DISPATCH / n) / tile * tile).clamp(tile, n.next_multiple_of(tile));
    let inputs = Inputs {
        storage: vec![(BINDING_PRODUCT_LEFT, bytemuck::cast_slice(left)), (BINDING_PRODUCT_RIGHT, bytemuck::cast_slice(right))],
        host: Vec::new(),
        image: None,
        output: (BINDING_PRODUCT_ROWS, (rows_per_dispatch.min(n) * n * size_of::<f32>()) as u64),
        push_bytes: size_of::<GpuProductPass>() as u32,
    };
    let spirv = include_bytes!(concat!(env!("OUT_DIR"), "/shaders/radiosity/product.comp.spv"));
    let mut pass = ComputePass::new(device, spirv, &inputs)?;
    let mut out = vec![0.0f32; n * n];
    let mut result = Ok(());
    for first in (0..n).step_by(rows_per_dispatch) {
        let count = rows_per_dispatch.min(n - first);
        let push = GpuProductPass { n: n as u32, first_row: first as u32, row_count: count as u32, pad: 0 };
        result = pass.run(device, bytemuck::bytes_of(&push), [n.div_ceil(tile) as u32, count.div_ceil(tile) as u32, 1]);
        if result.is_err() {
            break;
        }
        out[first * n..(first + count) * n].copy_from_slice(bytemuck::cast_slice(&pass.output()[..count * n * size_of::<f32>()]));
        rows_done(count as u64);
    }
    pass.destroy(device);
    result.map(|()| out)
}
