//! The height fog (issue 23, seed 002) on Mesa lavapipe, one test binary: the closed form of
//! `shaders/fog/height.glsl` against numerical integration of the density ([`formula`]), and
//! whole frames in both modes: fogged walls against the formula, glass in front of a fogged
//! wall, raster against path traced ([`frames`]).

#[path = "../lavapipe/mod.rs"]
mod lavapipe;

mod formula;
mod frames;
