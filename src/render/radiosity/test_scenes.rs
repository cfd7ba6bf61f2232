//! Scenes for the radiosity tests (the crate's and `tests/radiosity`'s): quads as static-world
//! chunks and the patches of a closed box.

use std::sync::{Arc, OnceLock};

use glam::Vec3;

use super::form_factors::{self, FormFactors};
use super::patches::{self, Patches};
use crate::frame::class::MaterialOverride;
use crate::frame::world::{ChunkShading, StaticChunk};

/// A white quad chunk `origin + s·u + t·v` (s, t in 0..1), front side `u × v`.
pub fn quad(id: u64, origin: Vec3, u: Vec3, v: Vec3) -> Arc<StaticChunk> {
    let c = [origin, origin + u, origin + u + v, origin + v];
    let positions = [c[0], c[1], c[2], c[0], c[2], c[3]].map(|p| p.to_array()).to_vec();
    Arc::new(StaticChunk {
        id,
        material_key: 1,
        material: MaterialOverride::default(),
        texture: None,
        positions,
        texcoords: Vec::new(),
        colors: Vec::new(),
        shading: ChunkShading::default(),
    })
}

/// The patches of the inside of the box `[0, side]³` (six white faces facing in).
pub fn closed_box(side: f32, patch_size: f32) -> Patches {
    let (x, y, z) = (Vec3::X * side, Vec3::Y * side, Vec3::Z * side);
    let faces = [
        quad(1, Vec3::ZERO, x, y),
        quad(2, z, y, x),
        quad(3, Vec3::ZERO, y, z),
        quad(4, x, z, y),
        quad(5, Vec3::ZERO, z, x),
        quad(6, y, x, z),
    ];
    patches::build(&faces, patch_size)
}

/// The patches of the unit box at patch size 0.25 (96 patches) and their form factors,
/// computed once for the tests that share them.
pub fn unit_box() -> &'static (Patches, FormFactors) {
    static UNIT_BOX: OnceLock<(Patches, FormFactors)> = OnceLock::new();
    UNIT_BOX.get_or_init(|| {
        let p = closed_box(1.0, 0.25);
        let f = form_factors::compute(&p);
        (p, f)
    })
}
