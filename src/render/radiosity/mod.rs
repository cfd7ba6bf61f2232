//! Radiosity over the persistent static world (seed 004, DESIGN.md "Radiosity"; issue 19).
//! The precompute, in the order it runs:
//!
//! 1. [`patches`]: the static world's chunks fitted to patches of a target size, in a stable
//!    order, with the world's hash.
//! 2. [`form_factors`]: the form-factor matrix (CPU reference: point-to-patch contour integral
//!    with visibility rays through the tracer's BVH); [`gpu::form_factors`] computes the same
//!    on the GPU, with the numbers they share in [`shader_constants`].
//! 3. [`bounces`]: the colour matrix and the k-bounce matrix, and the Neumann series they are
//!    checked against, over the dense [`matrix`] type.
//! 4. [`compress`]: the seed's compression: [`sparse`] top share, [`quantise`]d rest,
//!    [`reorder`]ed, [`bc1`] blocks, and the round trip's errors.
//!
//! [`precompute`] runs these steps within the memory budget of the [`settings`] and reports
//! times, sizes and errors (`glrt radiosity`), or builds the matrix the renderer uses, kept
//! on disk by [`cache`] (`glrt radiosity --matrix`).
//!
//! Per frame, [`gpu::direct`] lights the patches (shadow rays to the frame's [`lights`], in
//! the world frame) and adds their emission, and [`gpu::gather`] multiplies the compressed
//! matrix (its BC1 image sampled by the device) with that primary radiosity, the two run in
//! turn by [`gpu::update`]; [`transfer`] turns the result into the indirect light on the
//! raster draws of the static world, and [`stage`] runs it all for the renderer's frames; the
//! path tracer reads the same indirect light at its first diffuse bounce on the static world
//! ([`crate::render::trace::radiosity`]).

pub mod bc1;
pub mod bounces;
pub mod cache;
pub mod compress;
pub mod form_factors;
pub mod gpu;
pub mod lights;
pub mod matrix;
pub mod patches;
pub mod precompute;
pub mod progress;
pub mod quantise;
pub mod reorder;
pub mod settings;
pub mod shader_constants;
pub mod sparse;
pub mod stage;
pub mod test_scenes;
pub mod transfer;
#[cfg(test)]
mod tests;
