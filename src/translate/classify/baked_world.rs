//! The static draws whose light is baked, as a static world of their own: for measurements
//! that need a game's geometry and albedos only (`glrt radiosity --baked`, issue 19's table on
//! a Quake-3 map), never for drawing.
//!
//! The classifier leaves a draw whose lighting is not `Traced` out of
//! [`Frame::static_world`] (rule 5 of [`super`]): a lightmapped wall's bounced light is its
//! lightmap's, so radiosity must not light it again, and a game whose world is all lightmaps
//! (Quake 3) starts no precompute when radiosity is on. Its geometry is still exactly what
//! radiosity is for. [`BakedWorld`] takes the classified frames after the classifier and
//! offers their `Static` draws lit `Baked` (and not already in the static world) to a
//! [`StaticWorld`] of its own, which joins, chunks and releases their triangles as the
//! classifier's does. A chunk's colours are dropped (a baked surface's vertex colours are
//! light, or white), so radiosity's patches take its albedo from its texture alone (the first
//! carried unit that does not hold light; a surface with only a lightmap is white).

use std::sync::Arc;

use glam::Mat4;

use super::keys;
use super::static_world::StaticWorld;
use super::world_feed::WorldFeed;
use crate::frame::Frame;
use crate::frame::class::{DrawClass, SurfaceLighting};
use crate::frame::state::Winding;
use crate::frame::world::StaticChunk;

/// The baked static draws of the frames seen so far, as chunks (see the module doc).
#[derive(Default)]
pub struct BakedWorld {
    world: StaticWorld,
    feed: WorldFeed,
    chunks: Option<Arc<[Arc<StaticChunk>]>>,
}

impl BakedWorld {
    /// Offers the baked static draws of classified `frame`.
    pub fn add(&mut self, frame: &Frame) {
        let clip = frame.view.map_or(Mat4::IDENTITY, |v| v.projection * v.view);
        self.world.begin_frame(frame.number, clip);
        if frame.stats.camera_cut {
            self.world.clear();
        }
        for draw in &frame.draws {
            let Some(instance) = draw.instance.filter(|i| draw.class == DrawClass::Static && i.lighting == SurfaceLighting::Baked && !i.in_static_world) else { continue };
            let Some(model) = instance.model else { continue };
            // A chunk is shaded as its first draw: the textures, the units that hold light,
            // the material and the winding (which side is the front) split chunks.
            let [m0, m1] = instance.material.key();
            let winding = u64::from(draw.state.front_face == Winding::Cw);
            let key = keys::combine(&[keys::texture_key(draw), u64::from(instance.light_units), m0, m1, winding]);
            self.feed.offer(&mut self.world, draw, &model, key, instance.material, instance.light_units, false);
        }
        self.chunks = Some(self.world.end_frame().chunks);
    }

    /// The chunks after the last frame added.
    pub fn chunks(&self) -> &[Arc<StaticChunk>] {
        self.chunks.as_deref().unwrap_or(&[])
    }
}
