//! Radiosity on Mesa lavapipe (the machine's Vulkan driver when its ICD file is missing):
//! the GPU form factors ([`form_factors`]) against the CPU reference and analytic values.

#[path = "../lavapipe/mod.rs"]
mod lavapipe;

mod form_factors;
