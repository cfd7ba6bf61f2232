//! The persistent static world in the tracer (anti-culling, DESIGN.md "Hash tracking"): every
//! chunk of [`Frame::static_world`] is traced, drawn this frame or not, so a wall behind the
//! camera that the program culled still casts its shadow and bounces light.
//!
//! - **Geometry.** A chunk is a geometry of world-space triangles, its BVH built once and
//!   cached by [`key`] (its id and content; the resident cache drops it some frames after the
//!   world released it). Its instance places it in eye space by the frame's view, like a draw
//!   whose modelview is the view.
//! - **Shading.** A chunk is shaded as a draw of its triangles with the chunk's draw state
//!   ([`crate::frame::world::ChunkShading`]) would be ([`scene::geometry`],
//!   [`material::material`]): a surface without passes whose light is traced; the textures of
//!   units 0 and 1 with their environments and the units that hold baked light (a lightmap
//!   on unit 1 is a baked-light layer, as it is of the draw), the `glrt.toml` material,
//!   the alpha test, and as base colour the primary colour the chunk keeps per corner (Quake 3
//!   draws lightmapped world surfaces white, its vertex-lit ones with baked light in the
//!   colour: either way what the draw itself would be traced with), or the lit material's
//!   diffuse colour. Chunks keep no normals: lit chunks use the geometric normal (flat shading
//!   of faceted world geometry; a smooth lit mesh in the world loses its interpolated normals).
//! - **Draws.** A draw whose triangles are all in the chunks at the end of the frame
//!   ([`crate::frame::class::Instance::in_static_world`]) is not traced: the chunks hold it.
//!   A draw with triangles not in the world yet (pending: seen in one frame only) is traced
//!   whole, so nothing is missing; its triangles already in the world are then present twice,
//!   at the same place, for the frames until the rest joins (one frame for a static surface
//!   seen in consecutive frames).

use std::sync::Arc;

use glam::Mat4;
use xxhash_rust::xxh3::Xxh3;

use super::gpu_types::GpuMaterial;
use super::material::{self, MaterialDefaults};
use super::scene::{self, Geometry};
use super::settings::Lightmaps;
use super::shader_constants::{MATERIAL_LAYERS, TRACED_UNITS};
use super::surfaces::Surface;
use crate::frame::class::{DrawClass, Instance};
use crate::frame::state::{ColorMaterial, ColorMaterialMode, Lighting};
use crate::frame::world::{CHUNK_UNITS, StaticChunk};
use crate::frame::{Attrib, Draw, Frame, TextureRef};

// A chunk carries the texture units a material traces.
const _: () = assert!(CHUNK_UNITS == TRACED_UNITS);

/// The view and the chunks to trace in `frame`: the static world, when hash tracking recovered
/// a camera and the world holds chunks.
pub fn traced_world(frame: &Frame) -> Option<(Mat4, &[Arc<StaticChunk>])> {
    let view = frame.view.as_ref()?;
    (!frame.static_world.is_empty()).then_some((view.view, &frame.static_world[..]))
}

/// Whether the static world holds every triangle of `draw` (traced through the chunks).
pub fn is_covered(draw: &Draw) -> bool {
    draw.instance.is_some_and(|i| i.in_static_world)
}

/// The key the GPU geometry cache stores `chunk` under: its id, with its material key, size
/// and first triangle (ids are unique within one world; these tell two worlds apart).
pub fn key(chunk: &StaticChunk) -> u64 {
    let mut h = Xxh3::new();
    h.update(b"static chunk");
    h.update(&chunk.id.to_le_bytes());
    h.update(&chunk.material_key.to_le_bytes());
    h.update(&(chunk.positions.len() as u64).to_le_bytes());
    h.update(bytemuck::cast_slice(&chunk.positions[..chunk.positions.len().min(3)]));
    h.digest()
}

/// The texture of unit `unit` the chunk is shaded with (none when the unit was not enabled).
pub fn texture(chunk: &StaticChunk, unit: usize) -> Option<&TextureRef> {
    chunk.shading.texture_units[unit].and(chunk.textures[unit].as_ref())
}

/// The textures `chunk`'s material samples, per layer (as [`material::textures`] of its
/// draw: its units, no passes).
pub fn textures(chunk: &StaticChunk) -> [Option<&TextureRef>; MATERIAL_LAYERS] {
    std::array::from_fn(|layer| if layer < CHUNK_UNITS { texture(chunk, layer) } else { None })
}

/// The world-space geometry of `chunk`.
pub fn geometry(chunk: &StaticChunk) -> Geometry {
    scene::geometry(&Surface { base: &as_draw(chunk, true), passes: Vec::new() })
}

/// The material of `chunk`, whose [`textures`] are `textures` in the texel pool.
pub fn material(chunk: &StaticChunk, textures: [Option<u32>; MATERIAL_LAYERS], defaults: &MaterialDefaults) -> GpuMaterial {
    // The lighting of a chunk is traced: how baked surfaces are traced does not matter.
    material::material(&Surface { base: &as_draw(chunk, false), passes: Vec::new() }, textures, defaults, Lightmaps::default())
}

/// `chunk` as the draw of its triangles in the world frame: its state, textures, light units,
/// material and, with `vertices`, its positions, texture coordinates and colours (one vertex
/// per corner).
fn as_draw(chunk: &StaticChunk, vertices: bool) -> Draw {
    // A chunk holds triangles of draws with different material colours: its colours carry
    // each triangle's base colour (white when absent), so a lit state tracks them.
    let state = match &chunk.shading.state.lighting {
        Some(lighting) => {
            let mut state = (*chunk.shading.state).clone();
            let color_material = ColorMaterial { mode: ColorMaterialMode::AmbientAndDiffuse, ..ColorMaterial::default() };
            state.lighting = Some(Lighting { color_material: Some(color_material), ..lighting.clone() });
            Arc::new(state)
        }
        None => chunk.shading.state.clone(),
    };
    let mut draw = Draw {
        state,
        textures: chunk.textures.to_vec(),
        texture_units: chunk.shading.texture_units.to_vec(),
        class: DrawClass::Static,
        instance: Some(Instance {
            model: Some(Mat4::IDENTITY),
            material: chunk.material,
            in_static_world: true,
            light_units: chunk.shading.light_units,
            ..Instance::default()
        }),
        ..Draw::default()
    };
    if vertices {
        let v = &mut draw.vertices;
        v.position = chunk.positions.iter().map(|p| [p[0], p[1], p[2], 1.0]).collect();
        v.texcoords = chunk.texcoords.iter().map(|uv| Attrib { values: uv.iter().map(|t| [t[0], t[1], 0.0, 1.0]).collect() }).collect();
        v.color = Attrib { values: chunk.colors.iter().map(|c| c.map(|x| f32::from(x) / 255.0)).collect() };
        draw.vertex_count = v.position.len();
        draw.indices = (0..draw.vertex_count as u32).collect();
    }
    draw
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::RasterState;
    use crate::frame::TextureUnit;
    use crate::frame::class::{MaterialOverride, View};
    use crate::frame::state::CompareFunc;
    use crate::frame::world::ChunkShading;
    use crate::frame::texture::{EnvMode, TextureEnv};
    use crate::render::trace::shader_constants::{LAYER_BAKED_LIGHT, LAYER_OFF, NO_TEXTURE};

    fn chunk(colors: Vec<[u8; 4]>, state: RasterState) -> StaticChunk {
        StaticChunk {
            id: 3,
            material_key: 9,
            material: MaterialOverride { roughness: 0.3, metalness: 1.0, emissive: 0.0 },
            textures: [None, None],
            positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [5.0, 0.0, 0.0], [6.0, 0.0, 0.0], [5.0, 1.0, 0.0]],
            texcoords: [vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.5], [0.5, 0.5], [0.5, 0.5]], Vec::new()],
            colors,
            shading: ChunkShading { state: Arc::new(state), texture_units: [Some(TextureUnit::default()), None], light_units: 0 },
            cell: [0; 3],
        }
    }

    fn texture_ref(id: u32) -> TextureRef {
        TextureRef { id, version: 1, content: Arc::new(crate::frame::texture::TextureContent::default()) }
    }

    /// Texel pool slots: unit 0's texture at 4, unit 1's at 5.
    const POOLED: [Option<u32>; MATERIAL_LAYERS] = [Some(4), Some(5), None, None, None, None];

    #[test]
    fn a_chunk_is_shaded_as_its_draw_would_be() {
        let colors = vec![[255, 0, 0, 255], [255, 0, 0, 255], [255, 0, 0, 255], [0, 0, 255, 255], [0, 0, 255, 255], [0, 0, 255, 255]];
        let mut c = chunk(colors, RasterState { alpha_test: Some((CompareFunc::Greater, 0.5)), ..RasterState::default() });
        c.textures[0] = Some(texture_ref(7));
        let g = geometry(&c);
        assert_eq!(g.triangles.len(), 2);
        assert_eq!(g.triangles[1][1], glam::Vec3::new(6.0, 0.0, 0.0));
        let corner = g.attributes[1].corner[0];
        assert_eq!((corner.uv[0], corner.color, corner.normal), ([0.5, 0.5], scene::pack_unorm8([0.0, 0.0, 1.0, 1.0]), 0));
        let m = material(&c, POOLED, &MaterialDefaults::default());
        assert_eq!((m.layer[0].texture, m.roughness, m.metalness, m.alpha_func, m.alpha_ref), (4, 0.3, 1.0, CompareFunc::Greater as u32, 0.5));
        assert_eq!((m.layer[1].texture, m.layer[1].role), (NO_TEXTURE, LAYER_OFF), "no unit 1");

        // Without colours the base colour is white, lit or not: the world feed puts a lit
        // draw's diffuse colour in the chunk's colours (chunks mix draws of other materials,
        // so the state's diffuse colour, the first draw's, is not used).
        let white = geometry(&chunk(Vec::new(), RasterState::default()));
        assert_eq!(white.attributes[0].corner[2].color, scene::pack_unorm8([1.0; 4]));
        let mut lighting = Lighting::default();
        lighting.front.diffuse = [0.5, 0.25, 1.0, 1.0];
        let lit_state = RasterState { lighting: Some(lighting), ..RasterState::default() };
        let lit = geometry(&chunk(Vec::new(), lit_state.clone()));
        assert_eq!((lit.attributes[0].corner[1].color, lit.attributes[0].corner[1].normal), (scene::pack_unorm8([1.0; 4]), 0));
        let red = geometry(&chunk(vec![[255, 0, 0, 255]; 6], lit_state));
        assert_eq!(red.attributes[1].corner[0].color, scene::pack_unorm8([1.0, 0.0, 0.0, 1.0]));
        assert_eq!(material(&c, [None; MATERIAL_LAYERS], &MaterialDefaults::default()).layer[0].texture, NO_TEXTURE);
    }

    /// A chunk of a draw with a lightmap on unit 1 is shaded as that draw: the same textures,
    /// material layers (unit 1 a baked-light layer) and corners (unit 1's coordinates).
    #[test]
    fn a_lightmapped_chunk_has_the_layers_of_its_draw() {
        let mut c = chunk(Vec::new(), RasterState::default());
        let lightmap = TextureUnit { env: TextureEnv { mode: EnvMode::Modulate, ..TextureEnv::default() }, ..TextureUnit::default() };
        c.textures = [Some(texture_ref(7)), Some(texture_ref(8))];
        c.texcoords[1] = (0..6).map(|i| [i as f32 / 8.0, 1.0 - i as f32 / 16.0]).collect();
        c.shading.texture_units[1] = Some(lightmap);
        c.shading.light_units = 0b10;
        // The draw it came from, in the world frame.
        let mut draw = Draw {
            indices: (0..6).collect(),
            vertex_count: 6,
            state: c.shading.state.clone(),
            textures: vec![Some(texture_ref(7)), Some(texture_ref(8))],
            texture_units: vec![Some(TextureUnit::default()), Some(lightmap)],
            class: DrawClass::Static,
            instance: Some(Instance { material: c.material, light_units: 0b10, ..Instance::default() }),
            ..Draw::default()
        };
        draw.vertices.position = c.positions.iter().map(|p| [p[0], p[1], p[2], 1.0]).collect();
        draw.vertices.texcoords = c.texcoords.iter().map(|uv| Attrib { values: uv.iter().map(|t| [t[0], t[1], 0.0, 1.0]).collect() }).collect();
        let surface = Surface { base: &draw, passes: Vec::new() };
        let ids = |t: [Option<&TextureRef>; MATERIAL_LAYERS]| t.map(|t| t.map(|t| t.id));
        assert_eq!(ids(textures(&c)), [Some(7), Some(8), None, None, None, None]);
        assert_eq!(ids(textures(&c)), ids(material::textures(&surface)));
        let m = material(&c, POOLED, &MaterialDefaults::default());
        assert_eq!((m.layer[1].texture, m.layer[1].role), (5, LAYER_BAKED_LIGHT));
        let drawn = material::material(&surface, POOLED, &MaterialDefaults::default(), Lightmaps::default());
        assert_eq!(bytemuck::bytes_of(&m), bytemuck::bytes_of(&drawn));
        let g = geometry(&c);
        assert_eq!(g.attributes[1].corner[2].uv, [[0.5, 0.5], [5.0 / 8.0, 1.0 - 5.0 / 16.0]]);
        assert_eq!(g, scene::geometry(&surface));
        c.shading.texture_units[1] = None;
        assert_eq!(ids(textures(&c))[1], None, "a unit not enabled has no texture");
    }

    #[test]
    fn the_world_is_traced_with_a_view_and_chunks() {
        let c = Arc::new(chunk(Vec::new(), RasterState::default()));
        let view = View { view: Mat4::from_translation(glam::Vec3::new(0.0, 0.0, -4.0)), ..View::default() };
        let frame = Frame { view: Some(view), static_world: vec![c.clone()].into(), ..Frame::default() };
        let (m, chunks) = traced_world(&frame).expect("a view and chunks");
        assert_eq!((m, chunks.len()), (view.view, 1));
        assert!(traced_world(&Frame { view: None, ..frame.clone() }).is_none());
        assert!(traced_world(&Frame { static_world: Vec::new().into(), ..frame }).is_none());
        let other = StaticChunk { id: 4, ..(*c).clone() };
        assert_ne!(key(&c), key(&other));
        assert_eq!(key(&c), key(&c.as_ref().clone()));
        assert!(texture(&c, 0).is_none());
    }
}
