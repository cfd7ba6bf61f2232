//! Radiosity on the GPU, over the patches' [`scene`] (their BVH, walked by the tracer's
//! traversal): [`form_factors`] computes the form-factor matrix (the CPU version,
//! [`super::form_factors`], is the reference the tests compare it with and the fallback
//! without a device); per frame, [`direct`] lights the patches (shadow rays to the frame's
//! lights) and [`gather`] multiplies the compressed matrix, read as a BC1 image, with their
//! primary radiosity; [`update`] runs the two in turn; [`product`] computes the precompute's
//! k-bounce matrix (the CPU's [`super::bounces::k_bounce`] is the reference and the fallback).
//! All run as dispatches of the one-shot compute [`pass`].

pub mod direct;
pub mod form_factors;
pub mod gather;
pub mod pass;
pub mod product;
pub mod scene;
pub mod update;
