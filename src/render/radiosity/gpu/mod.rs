//! Radiosity on the GPU: [`form_factors`] computes the form-factor matrix with the tracer's
//! BVH traversal (the CPU version, [`super::form_factors`], is the reference the tests compare
//! it with and the fallback without a device), in dispatches of the one-shot compute
//! [`pass`].

pub mod form_factors;
pub mod pass;
