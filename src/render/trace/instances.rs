//! The instances of one traced frame: the traced draws that the static world does not hold,
//! each placed by its modelview, then the static world's chunks, placed by the view
//! ([`super::chunks`]); for each, the key of its geometry in the GPU cache and what the
//! scene buffers take from it (geometry when new, textures, material).

use glam::Mat4;

use super::chunks;
use super::gpu_types::GpuMaterial;
use super::scene::{self, Geometry, MaterialDefaults};
use super::settings::Lightmaps;
use crate::frame::world::StaticChunk;
use crate::frame::{Draw, Frame, TextureRef};

/// Where an instance's geometry comes from.
#[derive(Clone, Copy, Debug)]
pub enum Source<'a> {
    /// A traced draw, in object space.
    Draw(&'a Draw),
    /// A chunk of the static world, in world space.
    Chunk(&'a StaticChunk),
}

/// One instance of the frame.
#[derive(Clone, Copy, Debug)]
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

/// The instances of `frame` whose traced draws are `draws`, and how many draws were left out
/// because the static world holds them. `previous_view` is the last traced frame's view
/// (`None` after a camera cut). Chunks do not carry unit 1: draws whose unit 1 is traced (a
/// colour layer, or a lightmap `lightmaps` keeps: `scene::traces_second_unit`) are traced
/// themselves, and the chunks of such draws are left out (that geometry is traced as drawn,
/// without anti-culling).
pub fn gather<'a>(frame: &'a Frame, draws: &[&'a Draw], previous_view: Option<Mat4>, lightmaps: Lightmaps) -> (Vec<Item<'a>>, u32) {
    let world = chunks::traced_world(frame);
    let mut items = Vec::with_capacity(draws.len() + world.map_or(0, |(_, c)| c.len()));
    let mut covered = 0;
    for &draw in draws {
        let second_unit = scene::traced_textures(draw, lightmaps)[1].is_some();
        if world.is_some() && chunks::is_covered(draw) && !second_unit {
            covered += 1;
            continue;
        }
        let previous = draw.instance.and_then(|i| i.previous_modelview).unwrap_or(draw.modelview);
        items.push(Item { source: Source::Draw(draw), key: scene::geometry_key(draw), object_to_eye: draw.modelview, previous_object_to_eye: previous });
    }
    if let Some((view, list)) = world {
        for chunk in list.iter().filter(|c| !c.shading.second_unit.is_some_and(|u| scene::traces_second_unit(&u, lightmaps))) {
            items.push(Item { source: Source::Chunk(chunk), key: chunks::key(chunk), object_to_eye: view, previous_object_to_eye: previous_view.unwrap_or(view) });
        }
    }
    (items, covered)
}

impl<'a> Item<'a> {
    /// The geometry to build when its key is new.
    pub fn geometry(&self) -> Geometry {
        match self.source {
            Source::Draw(d) => scene::geometry(d),
            Source::Chunk(c) => chunks::geometry(c),
        }
    }

    /// The textures it is shaded with, per traced unit (`scene::traced_textures`; chunks carry
    /// unit 0 only).
    pub fn textures(&self, lightmaps: Lightmaps) -> [Option<&'a TextureRef>; 2] {
        match self.source {
            Source::Draw(d) => scene::traced_textures(d, lightmaps),
            Source::Chunk(c) => [chunks::texture(c), None],
        }
    }

    /// Its material, with its textures (per traced unit) at `textures` in the texel pool.
    pub fn material(&self, textures: [Option<u32>; 2], defaults: &MaterialDefaults) -> GpuMaterial {
        match self.source {
            Source::Draw(d) => scene::material(d, textures, defaults),
            Source::Chunk(c) => chunks::material(c, textures[0], defaults),
        }
    }

    /// Its triangle count.
    pub fn triangles(&self) -> usize {
        match self.source {
            Source::Draw(d) => d.indices.len() / 3,
            Source::Chunk(c) => c.triangles(),
        }
    }
}
