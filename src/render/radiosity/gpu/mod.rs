//! Radiosity on the GPU: [`form_factors`] computes the form-factor matrix with the tracer's
//! BVH traversal (the CPU version, [`super::form_factors`], is the reference the tests compare
//! it with and the fallback without a device); [`gather`] is the per-frame product of the
//! compressed matrix, read as a BC1 image, with the patches' primary radiosity. Both run as
//! dispatches of the one-shot compute [`pass`].

pub mod form_factors;
pub mod gather;
pub mod pass;
