//! The instances of one traced frame: the traced surfaces that the static world does not hold,
//! each placed by its base's modelview, then the static world's chunks, placed by the view
//! ([`super::chunks`]); for each, the key of its geometry in the GPU cache and what the
//! scene buffers take from it (geometry when new, textures, material).
//!
//! Chunks carry the base's unit 0 alone, traced as a surface whose light is traced. A surface
//! that needs more ([`own_instance`]: passes, a second unit, light that is not traced) is
//! traced as drawn even when the world holds its triangles, and the chunks of its material
//! (the same unit-0 texture, environment and draw state) are left out, together with every
//! chunk that holds a draw's second unit: that geometry is traced through its draws, without
//! anti-culling, until chunks carry passes and lighting.

use glam::Mat4;

use super::chunks;
use super::gpu_types::GpuMaterial;
use super::material::{self, MaterialDefaults};
use super::scene::{self, Geometry};
use super::settings::Lightmaps;
use super::shader_constants::{MATERIAL_LAYERS, TRACED_UNITS};
use super::surfaces::Surface;
use crate::frame::class::SurfaceLighting;
use crate::frame::state::Winding;
use crate::frame::world::StaticChunk;
use crate::frame::{Draw, Frame, RasterState, TextureRef, TextureUnit};

/// Where an instance's geometry comes from.
#[derive(Clone, Debug)]
pub enum Source<'a> {
    /// A traced surface, in its base's object space.
    Surface(Surface<'a>),
    /// A chunk of the static world, in world space.
    Chunk(&'a StaticChunk),
}

/// One instance of the frame.
#[derive(Clone, Debug)]
pub struct Item<'a> {
    /// Its geometry's origin.
    pub source: Source<'a>,
    /// Its geometry's key in the GPU cache.
    pub key: u64,
    /// Object (or world) space to eye space.
    pub object_to_eye: Mat4,
    /// The same in the previous frame (this frame's when unknown).
    pub previous_object_to_eye: Mat4,
}

/// Whether `surface` cannot be traced through the static world's chunks (see the module doc).
pub fn own_instance(surface: &Surface) -> bool {
    let base = surface.base;
    let traced_light = base.instance.is_none_or(|i| i.lighting == SurfaceLighting::Traced && i.light_units == 0);
    !surface.passes.is_empty() || !traced_light || (1..TRACED_UNITS).any(|u| scene::enabled(base, u))
}

/// What chunks split materials by, of `draw`: its unit-0 texture (when enabled), unit-0
/// environment and draw state.
fn material_of(draw: &Draw) -> (Option<u32>, Option<TextureUnit>, &RasterState) {
    let texture = draw.textures.first().and_then(Option::as_ref).filter(|_| scene::enabled(draw, 0)).map(|t| t.id);
    (texture, draw.texture_units.first().copied().flatten(), &draw.state)
}

/// Whether `chunk` holds triangles of the material of `draw`.
fn chunk_of_material(chunk: &StaticChunk, draw: &Draw) -> bool {
    (chunks::texture(chunk).map(|t| t.id), chunk.shading.texture_unit, &*chunk.shading.state) == material_of(draw)
}

/// The instances of `frame` whose traced surfaces are `surfaces`, and how many surfaces were
/// left out because the static world holds them. `previous_view` is the last traced frame's
/// view (`None` after a camera cut).
pub fn gather<'a>(frame: &'a Frame, surfaces: Vec<Surface<'a>>, previous_view: Option<Mat4>) -> (Vec<Item<'a>>, u32) {
    let world = chunks::traced_world(frame);
    let own: Vec<&Draw> = surfaces.iter().filter(|s| own_instance(s)).map(|s| s.base).collect();
    let mut items = Vec::with_capacity(surfaces.len() + world.map_or(0, |(_, c)| c.len()));
    let mut covered = 0;
    for surface in surfaces {
        let draw = surface.base;
        let own_material = own.iter().any(|o| std::ptr::eq(*o, draw) || material_of(o) == material_of(draw));
        if world.is_some() && chunks::is_covered(draw) && !own_material {
            covered += 1;
            continue;
        }
        let previous = draw.instance.and_then(|i| i.previous_modelview).unwrap_or(draw.modelview);
        let key = scene::geometry_key(&surface);
        items.push(Item { source: Source::Surface(surface), key, object_to_eye: draw.modelview, previous_object_to_eye: previous });
    }
    if let Some((view, list)) = world {
        for chunk in list.iter().filter(|c| c.shading.second_unit.is_none() && !own.iter().any(|d| chunk_of_material(c, d))) {
            items.push(Item { source: Source::Chunk(chunk), key: chunks::key(chunk), object_to_eye: view, previous_object_to_eye: previous_view.unwrap_or(view) });
        }
    }
    (items, covered)
}

impl<'a> Item<'a> {
    /// The geometry to build when its key is new.
    pub fn geometry(&self) -> Geometry {
        match &self.source {
            Source::Surface(s) => scene::geometry(s),
            Source::Chunk(c) => chunks::geometry(c),
        }
    }

    /// The textures it is shaded with, per layer ([`material::textures`]; chunks carry unit 0
    /// only).
    pub fn textures(&self) -> [Option<&'a TextureRef>; MATERIAL_LAYERS] {
        match &self.source {
            Source::Surface(s) => material::textures(s),
            Source::Chunk(c) => std::array::from_fn(|i| if i == 0 { chunks::texture(c) } else { None }),
        }
    }

    /// Its material, with its textures (per layer) at `textures` in the texel pool.
    pub fn material(&self, textures: [Option<u32>; MATERIAL_LAYERS], defaults: &MaterialDefaults, lightmaps: Lightmaps) -> GpuMaterial {
        match &self.source {
            Source::Surface(s) => material::material(s, textures, defaults, lightmaps),
            Source::Chunk(c) => chunks::material(c, textures[0], defaults),
        }
    }

    /// The front side of its triangles when they are the static world's (a chunk, or a
    /// surface whose draw the chunks hold whole): radiosity lights those
    /// ([`super::radiosity`]).
    pub fn static_world_front(&self) -> Option<Winding> {
        match &self.source {
            Source::Surface(s) => chunks::is_covered(s.base).then_some(s.base.state.front_face),
            Source::Chunk(c) => Some(c.shading.state.front_face),
        }
    }

    /// Its triangle count.
    pub fn triangles(&self) -> usize {
        match &self.source {
            Source::Surface(s) => s.base.indices.len() / 3,
            Source::Chunk(c) => c.triangles(),
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::frame::class::{DrawClass, Instance, View};
    use crate::frame::world::ChunkShading;

    /// A static draw of one triangle, in the static world, textured with texture `id` on
    /// unit 0, lit as `lighting` says.
    fn world_draw(id: u32, lighting: SurfaceLighting) -> Draw {
        let texture = crate::frame::TextureRef { id, version: 1, content: Arc::default() };
        Draw {
            indices: vec![0, 1, 2],
            vertex_count: 3,
            class: DrawClass::Static,
            state: Arc::new(RasterState::default()),
            textures: vec![Some(texture)],
            texture_units: vec![Some(TextureUnit::default())],
            instance: Some(Instance { in_static_world: true, lighting, ..Instance::default() }),
            ..Draw::default()
        }
    }

    /// A chunk of the material of `draw`.
    fn chunk_of(draw: &Draw, id: u64) -> Arc<StaticChunk> {
        Arc::new(StaticChunk {
            id,
            material_key: id,
            material: Default::default(),
            texture: draw.textures[0].clone(),
            positions: vec![[0.0; 3]; 3],
            texcoords: Vec::new(),
            colors: Vec::new(),
            shading: ChunkShading { state: draw.state.clone(), texture_unit: draw.texture_units[0], second_unit: None },
        })
    }

    #[test]
    fn surfaces_chunks_cannot_shade_are_traced_as_drawn_and_their_chunks_left_out() {
        let traced = world_draw(1, SurfaceLighting::Traced);
        let baked = world_draw(2, SurfaceLighting::Baked);
        let baked_too = world_draw(2, SurfaceLighting::Baked);
        let chunks = [chunk_of(&traced, 10), chunk_of(&baked, 11)];
        let mut with_second_unit = (*chunk_of(&traced, 12)).clone();
        with_second_unit.shading.second_unit = Some(TextureUnit::default());
        let frame = Frame { view: Some(View::default()), static_world: vec![chunks[0].clone(), chunks[1].clone(), Arc::new(with_second_unit)].into(), ..Frame::default() };
        let surfaces = [&traced, &baked, &baked_too].map(|base| Surface { base, passes: Vec::new() }).to_vec();
        assert!(!own_instance(&surfaces[0]) && own_instance(&surfaces[1]));
        let (items, covered) = gather(&frame, surfaces, None);
        let what: Vec<String> = items
            .iter()
            .map(|i| match &i.source {
                Source::Surface(s) => format!("draw {}", s.base.textures[0].as_ref().unwrap().id),
                Source::Chunk(c) => format!("chunk {}", c.id),
            })
            .collect();
        assert_eq!(what, ["draw 2", "draw 2", "chunk 10"], "the baked draws are traced, their chunk and the two-unit chunk are not");
        assert_eq!(covered, 1, "the traced draw is the world's");
    }
}
