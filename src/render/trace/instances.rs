//! The instances of one traced frame: the traced surfaces that the static world does not hold,
//! each placed by its base's modelview, then the static world's chunks, placed by the view
//! ([`super::chunks`]); for each, the key of its geometry in the GPU cache and what the
//! scene buffers take from it (geometry when new, textures, material).
//!
//! Chunks carry the base's texture units 0 and 1 (textures, coordinates, environments and
//! which of them hold baked light: a lightmapped world is traced as chunks), traced as a
//! surface whose light is traced. A surface that needs more ([`own_instance`]: passes, or a
//! lighting other than traced: baked, or lit by its vertex colours) is traced as drawn even
//! when the world holds its triangles, and the chunks of its material (the same textures,
//! environments and draw state) are left out: that geometry is traced through its draws,
//! without anti-culling, until chunks carry passes and lighting.

use glam::Mat4;

use super::chunks;
use super::gpu_types::GpuMaterial;
use super::material::{self, MaterialDefaults};
use super::scene::{self, Geometry};
use super::settings::Lightmaps;
use super::shader_constants::MATERIAL_LAYERS;
use super::surfaces::Surface;
use crate::frame::class::SurfaceLighting;
use crate::frame::state::Winding;
use crate::frame::world::{CHUNK_UNITS, StaticChunk};
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

/// Whether `surface` cannot be traced through the static world's chunks: it has passes, or
/// its light is not traced (see the module doc).
pub fn own_instance(surface: &Surface) -> bool {
    let traced_light = surface.base.instance.is_none_or(|i| i.lighting == SurfaceLighting::Traced);
    !surface.passes.is_empty() || !traced_light
}

/// What chunks split materials by, of `draw`: the textures (when enabled) and environments of
/// its carried units, and its draw state.
fn material_of(draw: &Draw) -> ([Option<u32>; CHUNK_UNITS], [Option<TextureUnit>; CHUNK_UNITS], &RasterState) {
    let textures = std::array::from_fn(|u| draw.textures.get(u).and_then(Option::as_ref).filter(|_| scene::enabled(draw, u)).map(|t| t.id));
    (textures, std::array::from_fn(|u| draw.texture_units.get(u).copied().flatten()), &draw.state)
}

/// Whether `chunk` holds triangles of the material of `draw`.
fn chunk_of_material(chunk: &StaticChunk, draw: &Draw) -> bool {
    let textures = std::array::from_fn(|u| chunks::texture(chunk, u).map(|t| t.id));
    (textures, chunk.shading.texture_units, &*chunk.shading.state) == material_of(draw)
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
        for chunk in list.iter().filter(|c| !own.iter().any(|d| chunk_of_material(c, d))) {
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

    /// The textures it is shaded with, per layer ([`material::textures`], [`chunks::textures`]).
    pub fn textures(&self) -> [Option<&'a TextureRef>; MATERIAL_LAYERS] {
        match &self.source {
            Source::Surface(s) => material::textures(s),
            Source::Chunk(c) => chunks::textures(c),
        }
    }

    /// Its material, with its textures (per layer) at `textures` in the texel pool.
    pub fn material(&self, textures: [Option<u32>; MATERIAL_LAYERS], defaults: &MaterialDefaults, lightmaps: Lightmaps) -> GpuMaterial {
        match &self.source {
            Source::Surface(s) => material::material(s, textures, defaults, lightmaps),
            Source::Chunk(c) => chunks::material(c, textures, defaults),
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

    /// `draw` with texture `id` on unit 1 too, which holds baked light.
    fn lightmapped(mut draw: Draw, id: u32) -> Draw {
        draw.textures.push(Some(crate::frame::TextureRef { id, version: 1, content: Arc::default() }));
        draw.texture_units.push(Some(TextureUnit::default()));
        draw.instance = draw.instance.map(|i| Instance { light_units: 0b10, ..i });
        draw
    }

    /// A chunk of the material of `draw`.
    fn chunk_of(draw: &Draw, id: u64) -> Arc<StaticChunk> {
        let unit = |u: usize| draw.texture_units.get(u).copied().flatten();
        Arc::new(StaticChunk {
            id,
            material_key: id,
            material: Default::default(),
            textures: std::array::from_fn(|u| draw.textures.get(u).cloned().flatten()),
            positions: vec![[0.0; 3]; 3],
            texcoords: [Vec::new(), Vec::new()],
            colors: Vec::new(),
            shading: ChunkShading { state: draw.state.clone(), texture_units: [unit(0), unit(1)], light_units: draw.instance.map_or(0, |i| i.light_units) },
            cell: [0; 3],
        })
    }

    #[test]
    fn surfaces_chunks_cannot_shade_are_traced_as_drawn_and_their_chunks_left_out() {
        let traced = world_draw(1, SurfaceLighting::Traced);
        let baked = world_draw(2, SurfaceLighting::Baked);
        let baked_too = world_draw(2, SurfaceLighting::Baked);
        let lit_lightmapped = lightmapped(world_draw(3, SurfaceLighting::Traced), 4);
        let other_lightmap = lightmapped(world_draw(2, SurfaceLighting::Traced), 5);
        let chunks = [chunk_of(&traced, 10), chunk_of(&baked, 11), chunk_of(&lit_lightmapped, 12), chunk_of(&other_lightmap, 13)];
        let frame = Frame { view: Some(View::default()), static_world: chunks.to_vec().into(), ..Frame::default() };
        let surfaces = [&traced, &baked, &baked_too, &lit_lightmapped].map(|base| Surface { base, passes: Vec::new() }).to_vec();
        assert_eq!(surfaces.iter().map(own_instance).collect::<Vec<_>>(), [false, true, true, false], "light not traced: own instances; a second unit: chunks");
        let (items, covered) = gather(&frame, surfaces, None);
        let what: Vec<String> = items
            .iter()
            .map(|i| match &i.source {
                Source::Surface(s) => format!("draw {}", s.base.textures[0].as_ref().unwrap().id),
                Source::Chunk(c) => format!("chunk {}", c.id),
            })
            .collect();
        assert_eq!(what, ["draw 2", "draw 2", "chunk 10", "chunk 12", "chunk 13"], "the baked draws are traced, their chunk is not; a chunk with another unit 1 is another material");
        assert_eq!(covered, 2, "the traced draws are the world's");
        let lightmap_layers = items[3].textures().map(|t| t.map(|t| t.id));
        assert_eq!(lightmap_layers[..2], [Some(3), Some(4)], "the chunk's textures are its draw's");
    }
}
