//! Radiosity on Mesa lavapipe (the machine's Vulkan driver when its ICD file is missing):
//! the GPU form factors ([`form_factors`]) against the CPU reference and analytic values, and
//! the per-frame product from the BC1 image ([`gather`]) against the CPU's.

#[path = "../lavapipe/mod.rs"]
mod lavapipe;

mod direct;
mod form_factors;
mod gather;
