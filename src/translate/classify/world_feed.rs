//! The seam to the persistent static world (`static_world`): the world-space triangles of one
//! traced draw, built in reused buffers and offered to [`StaticWorld::offer`].

use glam::{Mat4, Vec4};

use super::static_world::{Offered, StaticWorld, WorldTriangles};
use crate::frame::Draw;
use crate::frame::class::MaterialOverride;

/// Buffers reused from draw to draw (no allocation once they have grown).
#[derive(Default)]
pub struct WorldFeed {
    positions: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
}

impl WorldFeed {
    /// Offers the triangles of `draw`, taken to the world by `model`, as material
    /// `material_key` with the parameters `material`.
    pub fn offer(&mut self, world: &mut StaticWorld, draw: &Draw, model: &Mat4, material_key: u64, material: MaterialOverride) -> Offered {
        self.positions.clear();
        self.texcoords.clear();
        let texcoords = draw.vertices.texcoords.first().filter(|t| !t.values.is_empty());
        let identity = *model == Mat4::IDENTITY;
        for &i in &draw.indices {
            let Some(p) = draw.vertices.position.get(i as usize) else { continue };
            let w = if identity { Vec4::from_array(*p) } else { *model * Vec4::from_array(*p) };
            let w = if w.w != 0.0 && w.w != 1.0 { w / w.w } else { w };
            self.positions.push([w.x, w.y, w.z]);
            if let Some(t) = texcoords.and_then(|t| t.get(i as usize)) {
                self.texcoords.push([t[0], t[1]]);
            }
        }
        let whole = self.positions.len() / 3 * 3;
        self.positions.truncate(whole);
        let texcoords = (self.texcoords.len() == self.positions.len()).then_some(&self.texcoords[..]);
        world.offer(WorldTriangles {
            material_key,
            material,
            texture: draw.textures.iter().flatten().next(),
            positions: &self.positions,
            texcoords,
        })
    }
}
