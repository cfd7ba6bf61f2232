//! The per-frame product on the GPU: every patch's radiosity from every patch's primary
//! radiosity (emitted plus reflected direct light), `B = P + F^k P`, with `F^k` as the
//! compressed matrix stands for it (`shaders/radiosity/gather.comp`): its BC1 image sampled
//! as a `VK_FORMAT_BC1_RGB_UNORM_BLOCK` image (the device decodes the blocks; lavapipe
//! does too), its exact part as sparse rows. Each product is one dispatch of one workgroup
//! per row, timed with timestamps on GPUs.

use ash::vk;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use super::pass::{ComputePass, DispatchTime, ImageInput, Inputs};
use crate::render::radiosity::bc1::Bc1Matrix;
use crate::render::radiosity::compress::CompressedMatrix;
use crate::render::radiosity::sparse::SparseRows;
use crate::render::radiosity::shader_constants::{
    BINDING_MATRIX, BINDING_ORDER, BINDING_PRIMARY, BINDING_RADIOSITY, BINDING_SPARSE_ENTRIES, BINDING_SPARSE_OFFSETS,
};
use crate::render::raster::device::{Device, Error, Result};

/// Most workgroups of one dispatch dimension the gathering pass uses (Vulkan's guaranteed
/// `maxComputeWorkGroupCount`).
const MAX_GROUPS: u32 = 65_535;

/// An entry of the exact part as the shader reads it (`SparseEntry`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuSparseEntry {
    /// Value per channel.
    pub value: [f32; 3],
    /// The source patch.
    pub column: u32,
}

/// The push constants (`GatherPass`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuGatherPass {
    /// Patches.
    pub patch_count: u32,
    /// The quantised part's largest value.
    pub max_value: f32,
    /// Its log shift.
    pub shift: f32,
    /// Padding.
    pub pad: u32,
}

include!(concat!(env!("OUT_DIR"), "/layouts/radiosity_gather_types.rs"));

/// The compressed matrix on the device and the pass that multiplies with it.
pub struct Gather {
    pass: ComputePass,
    push: GpuGatherPass,
    n: usize,
}

impl Gather {
    /// Uploads `m` to `device` (which must have [`crate::render::raster::device::Features::bc_textures`]).
    pub fn new(device: &Device, m: &CompressedMatrix) -> Result<Gather> {
        if !device.features.bc_textures {
            return Err(Error::NoDevice(format!("{} cannot sample BC1 images (textureCompressionBC)", device.name())));
        }
        let n = m.order.len();
        let entries: Vec<GpuSparseEntry> = m.sparse.columns.iter().zip(&m.sparse.values).map(|(&column, &value)| GpuSparseEntry { value, column }).collect();
        let side = m.texture.side as u32;
        let inputs = Inputs {
            storage: vec![
                (BINDING_ORDER, bytemuck::cast_slice(&m.order)),
                (BINDING_SPARSE_OFFSETS, bytemuck::cast_slice(&m.sparse.offsets)),
                (BINDING_SPARSE_ENTRIES, bytemuck::cast_slice(&entries)),
            ],
            host: vec![(BINDING_PRIMARY, (n.max(1) * 16) as u64)],
            image: Some(ImageInput { binding: BINDING_MATRIX, format: vk::Format::BC1_RGB_UNORM_BLOCK, size: [side.max(4), side.max(4)], bytes: &m.texture.blocks }),
            output: (BINDING_RADIOSITY, (n.max(1) * 16) as u64),
            push_bytes: size_of::<GpuGatherPass>() as u32,
        };
        let spirv = include_bytes!(concat!(env!("OUT_DIR"), "/shaders/radiosity/gather.comp.spv"));
        let pass = ComputePass::new(device, spirv, &inputs)?;
        Ok(Gather { pass, push: GpuGatherPass { patch_count: n as u32, max_value: m.max, shift: m.shift, pad: 0 }, n })
    }

    /// Every patch's radiosity from its `primary` radiosity (one per patch), and the time it took.
    pub fn run(&mut self, device: &Device, primary: &[Vec3]) -> Result<(Vec<Vec3>, DispatchTime)> {
        assert_eq!(primary.len(), self.n, "one primary radiosity per patch");
        let words: Vec<[f32; 4]> = primary.iter().map(|p| p.extend(0.0).to_array()).collect();
        self.pass.host_input(0)[..self.n * 16].copy_from_slice(bytemuck::cast_slice(&words));
        let rows = self.n as u32;
        let groups = [rows.clamp(1, MAX_GROUPS), rows.div_ceil(MAX_GROUPS).max(1), 1];
        let time = self.pass.run_timed(device, bytemuck::bytes_of(&self.push), groups)?;
        let out: &[[f32; 4]] = bytemuck::cast_slice(&self.pass.output()[..self.n * 16]);
        let radiosity = out.iter().map(|v| Vec3::new(v[0], v[1], v[2])).collect();
        Ok((radiosity, time))
    }

    /// Frees the device's objects.
    pub fn destroy(self, device: &Device) {
        self.pass.destroy(device);
    }
}

/// A compressed matrix of `n` patches for timing the product (its cost does not depend on the
/// values): BC1 blocks of xorshift bytes from `seed`, the order reversed, and 4 % of the
/// entries exact (`n / 25` per row, value 1e-3, columns from the same generator).
pub fn synthetic(n: usize, seed: u64) -> CompressedMatrix {
    let mut state = seed | 1;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let side = n.div_ceil(4) * 4;
    let blocks: Vec<u8> = (0..(side / 4) * (side / 4) * 8).map(|_| next() as u8).collect();
    let per_row = (n / 25).max(1);
    let mut sparse = SparseRows { offsets: vec![0], ..SparseRows::default() };
    for _ in 0..n {
        for _ in 0..per_row {
            sparse.columns.push((next() % n.max(1) as u64) as u32);
            sparse.values.push([1.0e-3; 3]);
        }
        sparse.offsets.push(sparse.columns.len() as u32);
    }
    CompressedMatrix { order: (0..n as u32).rev().collect(), max: 1.0e-2, shift: 12.0, texture: Bc1Matrix { n, side, blocks }, sparse }
}
