//! Scenes for the radiosity tests (the crate's and `tests/radiosity`'s) and benchmarks (`glrt
//! radiosity --precompute`): quads as static-world chunks, the patches of a closed box, and
//! quick approximate form factors for timing the precompute at sizes whose exact form factors
//! take too long.

use std::sync::{Arc, OnceLock};

use glam::Vec3;
use rayon::prelude::*;

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
        textures: [None, None],
        positions,
        texcoords: [Vec::new(), Vec::new()],
        colors: Vec::new(),
        shading: ChunkShading::default(),
        cell: [0; 3],
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

/// Form factors of `p` by Wallace's disc approximation, `cos_i cos_j A_j / (π r² + A_j)`
/// between the patches' centres, without visibility: close to the exact ones inside a convex
/// box, O(n²) and on every core; for timing the later stages on many patches.
pub fn disc_form_factors(p: &Patches) -> FormFactors {
    let n = p.patches.len();
    let mut values = vec![0.0f32; n * n];
    values.par_chunks_mut(n.max(1)).zip(&p.patches).for_each(|(row, r)| {
        for (x, s) in row.iter_mut().zip(&p.patches) {
            let d = s.position - r.position;
            let (cos_r, cos_s) = (r.normal.dot(d), -s.normal.dot(d));
            if cos_r > 0.0 && cos_s > 0.0 {
                let r2 = d.length_squared();
                *x = cos_r * cos_s / r2 * s.area / (std::f32::consts::PI * r2 + s.area);
            }
        }
    });
    FormFactors { n, values }
}

/// A permutation of `0..n` drawn from `seed` (Fisher–Yates over xorshift64): an order of
/// patches without spatial coherence, for the reordering's tests and benchmarks.
pub fn shuffled_order(n: usize, seed: u64) -> Vec<u32> {
    let mut state = seed | 1;
    let mut order: Vec<u32> = (0..n as u32).collect();
    for k in (1..n).rev() {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        order.swap(k, (state % (k as u64 + 1)) as usize);
    }
    order
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
