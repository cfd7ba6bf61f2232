//! Radiosity on Mesa lavapipe (the machine's Vulkan driver when its ICD file is missing):
//! the GPU form factors ([`form_factors`]) against the CPU reference and analytic values, the
//! patches' direct light ([`direct`]) against analytic irradiance, the per-frame product from
//! the BC1 image ([`gather`]) against the CPU's, the two in turn ([`update`]), and the
//! renderer's stage, its precompute on a thread of its own while frames go on ([`stage`]).

#[path = "../lavapipe/mod.rs"]
mod lavapipe;

mod direct;
mod form_factors;
mod gather;
mod product;
mod stage;
mod update;
