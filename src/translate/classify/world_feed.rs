//! The seam to the persistent static world (`static_world`): the world-space triangles of one
//! traced draw, built in reused buffers and offered to [`StaticWorld::offer`], with what a
//! renderer shades them with (the textures and coordinates of units 0 and 1, after their
//! texture matrices; base colours when not all white — the vertex colours, or a lit draw's
//! diffuse material colour — and the draw state with the units that hold baked light).

use glam::{Mat4, Vec4};

use super::keys;
use super::static_world::{Offered, StaticWorld, WorldTriangles};
use crate::frame::Draw;
use crate::frame::state::Lighting;
use crate::frame::class::MaterialOverride;
use crate::frame::world::{CHUNK_UNITS, ChunkShading};

/// Buffers reused from draw to draw (no allocation once they have grown).
#[derive(Default)]
pub struct WorldFeed {
    positions: Vec<[f32; 3]>,
    texcoords: [Vec<[f32; 2]>; CHUNK_UNITS],
    colors: Vec<[u8; 4]>,
}

/// `c` as unorm8 RGBA.
fn unorm8(c: [f32; 4]) -> [u8; 4] {
    c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
}

/// The material's diffuse colour that lit `draw` is traced with as its base colour (`None`:
/// unlit, or its diffuse colour tracks the vertex colour).
pub fn lit_diffuse(draw: &Draw) -> Option<[f32; 4]> {
    draw.state.lighting.as_ref().and_then(Lighting::untracked_diffuse)
}

/// Hash of what the tracer takes from a lit draw's front material (`trace::material`): the
/// diffuse colour unless it tracks the vertex colour, the specular colour's RGB and, where it
/// is not black, the shininess, and the emission's RGB (alphas are not read); 0 for an unlit
/// draw. The world keeps a triangle's material as first offered, so a `glMaterial` change
/// must make new triangles, and only a change the tracer sees (a program that resets the
/// specular colour to a transparent black keeps its walls).
pub fn lit_material_key(draw: &Draw) -> u64 {
    let Some(l) = draw.state.lighting.as_ref() else { return 0 };
    let rgb = |c: [f32; 4]| keys::combine(&[c[0], c[1], c[2]].map(|v| u64::from(v.to_bits())));
    let diffuse = l.untracked_diffuse().map_or(0, |d| keys::combine(&d.map(|v| u64::from(v.to_bits()))));
    let shininess = if l.front.specular[..3].iter().any(|&c| c > 0.0) { u64::from(l.front.shininess.to_bits()) } else { 0 };
    keys::combine(&[diffuse, rgb(l.front.specular), shininess, rgb(l.front.emission)])
}

impl WorldFeed {
    /// Offers the triangles of `draw`, taken to the world by `model`, as material
    /// `material_key` with the parameters `material`, its units `light_units` holding baked
    /// light; without `colours`, every corner white (a surface whose colours are light, not
    /// albedo: [`super::baked_world`]).
    #[allow(clippy::too_many_arguments)]
    pub fn offer(&mut self, world: &mut StaticWorld, draw: &Draw, model: &Mat4, material_key: u64, material: MaterialOverride, light_units: u8, colours: bool) -> Offered {
        self.positions.clear();
        self.colors.clear();
        let units: [_; CHUNK_UNITS] = std::array::from_fn(|u| {
            let texcoords = draw.vertices.texcoords.get(u).filter(|t| !t.values.is_empty());
            let matrix = draw.texture_matrices.get(u).copied().flatten().filter(|m| *m != Mat4::IDENTITY);
            (texcoords, matrix)
        });
        self.texcoords.iter_mut().for_each(Vec::clear);
        // The base colour the tracer shades with: the vertex colour, or the material's diffuse
        // colour of a lit draw whose diffuse does not track the colour (`trace::scene`).
        let lit_diffuse = lit_diffuse(draw);
        let colors = Some(&draw.vertices.color).filter(|c| colours && (lit_diffuse.is_some_and(|d| d != [1.0; 4]) || c.values.iter().any(|c| *c != [1.0; 4])));
        let identity = *model == Mat4::IDENTITY;
        for &i in &draw.indices {
            let Some(p) = draw.vertices.position.get(i as usize) else { continue };
            let w = if identity { Vec4::from_array(*p) } else { *model * Vec4::from_array(*p) };
            let w = if w.w != 0.0 && w.w != 1.0 { w / w.w } else { w };
            self.positions.push([w.x, w.y, w.z]);
            for ((texcoords, matrix), out) in units.iter().zip(&mut self.texcoords) {
                if let Some(t) = texcoords.and_then(|t| t.get(i as usize)) {
                    let t = matrix.map_or(Vec4::from_array(t), |m| m * Vec4::from_array(t));
                    let q = if t.w != 0.0 { t.w } else { 1.0 };
                    out.push([t.x / q, t.y / q]);
                }
            }
            if let Some(c) = colors.and_then(|c| c.get(i as usize)) {
                self.colors.push(unorm8(lit_diffuse.unwrap_or(c)));
            }
        }
        let whole = self.positions.len() / 3 * 3;
        self.positions.truncate(whole);
        let texcoords = std::array::from_fn(|u| (self.texcoords[u].len() == self.positions.len()).then_some(&self.texcoords[u][..]));
        let colors = (self.colors.len() == self.positions.len()).then_some(&self.colors[..]);
        let texture_units = std::array::from_fn(|u| draw.texture_units.get(u).copied().flatten());
        let shading = ChunkShading { state: draw.state.clone(), texture_units, light_units };
        world.offer(WorldTriangles {
            material_key,
            material,
            textures: std::array::from_fn(|u| draw.textures.get(u).and_then(Option::as_ref)),
            positions: &self.positions,
            texcoords,
            colors,
            shading: &shading,
        })
    }
}
