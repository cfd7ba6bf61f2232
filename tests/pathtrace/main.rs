//! The compute path tracer on Mesa lavapipe (the machine's Vulkan driver when its ICD file is
//! missing), one test binary: its BVH traversal ([`bvh`]) and texel pool ([`texels`]) against
//! their CPU mirrors, geometry kept across frames ([`geometry`]), light transport against
//! physics ([`physics`]) and against the independent CPU tracer of [`reference_tracer`]
//! ([`cornell`], which [`reference`] checks first), composition with the raster path
//! ([`composite`]), and surfaces of several passes, baked light and emitters ([`surfaces`],
//! on frames [`classified`] as hash tracking will classify them); the denoiser's
//! reprojection and disocclusion tests ([`denoise`]).

#[path = "../lavapipe/mod.rs"]
mod lavapipe;
mod reference_tracer;

mod bvh;
mod classified;
mod composite;
mod cornell;
mod denoise;
mod geometry;
mod physics;
mod reference;
mod surfaces;
mod texels;
