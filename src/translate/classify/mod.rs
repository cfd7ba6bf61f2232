//! Hash tracking: at the end of each frame, every draw gets a class, every traced draw a
//! stable instance id and its lighting, the frame its recovered camera, the persistent static
//! world and its statistics (DESIGN.md, "Hash tracking"). One [`Classifier`] per context, kept
//! between frames.
//!
//! Per frame, in order:
//! 1. routing ([`routing`]): raster classes (`Translucent`, `Overlay`, `Sky`, `Ignored`) by
//!    state, by what came before in the frame, and by `glrt.toml` texture tags ([`config`],
//!    texture hashes from [`texture_hash`]); a draw routed `Translucent` or traced that is a
//!    dynamic-light pass is a `Light`, its light recovered into [`Frame::lights`]
//!    ([`dlights`]); one that is a later pass over triangles of an earlier traced draw is a
//!    `Layer` of it ([`layers`]),
//!    its role from its blend function and, for a multiplying pass, from texel densities
//!    ([`lighting`]); the other draws are traced;
//! 2. keys ([`keys`]) and matching ([`matching`]) of the traced draws with the previous
//!    frame's instances: exact (geometry + textures + state) or by slot; the texture units of
//!    each that hold baked light ([`lighting`]);
//! 3. the view ([`view`]) from the draws matched to static instances;
//! 4. traced classes, in this order: a texture tagged `static` → `Static`, `dynamic` →
//!    `Dynamic`; matched by slot (its vertices changed) → `Dynamic`; matched exactly an
//!    instance that was `Movable` or `Dynamic` → the same class (a door that stopped is still
//!    movable); matched exactly a `Static` instance → `Static` when its model matrix (world
//!    frame; eye space without a view) is unchanged, else `Movable`; across a camera cut the
//!    previous class is kept; new → `Static`; then how each is lit ([`lighting`]: GL lights,
//!    baked in a lightmap or its vertex colours, or vertex colours as lighting);
//! 5. the static world ([`world_feed`] → `static_world`): every traced draw not tagged
//!    `dynamic` whose vertices are in the world frame (model ≈ identity) or which is a
//!    `Static` instance (taken to the world by its model) is offered as world-space
//!    triangles, unless the chunks would lose what it is: a draw with layers, a draw whose
//!    lighting is not `Traced` (baked, or lit by its vertex colours), or whose first texture
//!    holds light (the static world's radiosity takes a chunk's first texture as its albedo).
//!    Chunks carry the textures and coordinates of units 0 and 1, which of them hold light
//!    (a traced-lit draw with a lightmap on unit 1 is offered: the tracer shades its chunks
//!    as the draw), the colours and the draw state; not the layers (other draws of the frame)
//!    nor a lighting other than `Traced`: such draws are traced as drawn (without
//!    anti-culling), and their triangles offered in earlier frames leave the world as any
//!    triangle not drawn does. The units that hold light are in the material key. A camera
//!    cut clears the world first; an instance whose triangles are all in the world is marked
//!    ([`Instance::in_static_world`]);
//! 6. statistics ([`crate::frame::class::FrameStats`]).

pub mod baked_world;
pub mod config;
pub mod dlights;
pub mod keys;
pub mod layers;
pub mod lighting;
pub mod matching;
pub mod report;
pub mod routing;
pub mod static_world;
pub mod texture_hash;
pub mod view;
pub mod world_feed;

use glam::{Mat4, Vec4};

use crate::frame::class::{DrawClass, FrameStats, Instance, Layer, LayerRole, MaterialOverride, Match, SurfaceLighting};
use crate::frame::{Draw, Frame};
use crate::translate::limits::MAX_TEXTURE_UNITS;
use layers::{Blending, LayerFinder};
use matching::{Found, Matcher, Probe, Record};
use routing::{Before, Tags};
use static_world::StaticWorld;
use view::{ViewInput, ViewTracker, same_place};

/// What the classifier keeps of a traced draw while it works on a frame.
#[derive(Clone, Copy, Debug, Default)]
struct Traced {
    draw: usize,
    tags: Tags,
    geometry: u64,
    /// Hash of the textures, draw state, material and lit diffuse colour: the static world's
    /// material key.
    material_key: u64,
    material: MaterialOverride,
    /// Its texture units that hold baked light ([`Instance::light_units`]).
    light_units: u8,
    /// It has a [`LayerRole::BakedLight`] layer.
    baked_layer: bool,
}

/// The hash of the texture of each texture unit of a draw.
type UnitHashes = [Option<u64>; MAX_TEXTURE_UNITS];

/// A pass found to be a layer of a traced draw.
struct FoundLayer {
    /// Its base's number in [`LayerFinder`] (the index in `Classifier::traced` during
    /// [`Classifier::classify`]).
    base: usize,
    layer: Layer,
    /// Light units it reveals on the base (a lightmap base pass under a texture pass).
    base_units: u8,
}

/// Hash tracking across the frames of one context.
pub struct Classifier {
    config: config::Config,
    textures: texture_hash::TextureHashes,
    lists: keys::ListKeys,
    states: keys::StateKeys,
    matcher: Matcher,
    view: ViewTracker,
    world: StaticWorld,
    feed: world_feed::WorldFeed,
    layers: LayerFinder,
    lights: dlights::DynamicLights,
    colours: lighting::ColourHistory,
    traced: Vec<Traced>,
    probes: Vec<Probe>,
    found: Vec<Found>,
    records: Vec<Record>,
}

impl Default for Classifier {
    /// A classifier with the configuration of this process (`glrt.toml`, `GLRT_<KEY>`).
    fn default() -> Classifier {
        Classifier::with_config(config::Config::of_process())
    }
}

/// Bytes of a draw's vertex data: positions, indices, texture coordinates of unit 0.
fn vertex_bytes(draw: &Draw) -> u64 {
    let texcoords = draw.vertices.texcoords.first().map_or(0, |t| t.values.len());
    (std::mem::size_of_val(&draw.vertices.position[..]) + draw.indices.len() * 4 + texcoords * 16) as u64
}

/// Triangles of a draw (0 for lines and points).
fn triangles(draw: &Draw) -> usize {
    if draw.topology == crate::frame::Topology::Triangles { draw.indices.len() / 3 } else { 0 }
}

impl Classifier {
    /// A classifier with `config`.
    pub fn with_config(config: config::Config) -> Classifier {
        Classifier {
            config,
            textures: Default::default(),
            lists: Default::default(),
            states: Default::default(),
            matcher: Default::default(),
            view: Default::default(),
            world: StaticWorld::new(),
            feed: Default::default(),
            layers: Default::default(),
            lights: Default::default(),
            colours: Default::default(),
            traced: Vec::new(),
            probes: Vec::new(),
            found: Vec::new(),
            records: Vec::new(),
        }
    }

    /// Classifies `frame` in place (classes, instances, view, static world, statistics);
    /// `list_version` gives the version of a display list (`ListTable::version`).
    pub fn classify(&mut self, frame: &mut Frame, list_version: impl Fn(u32) -> Option<u64>) {
        let start = std::time::Instant::now();
        self.route(frame, &list_version);
        self.matcher.match_frame(&self.probes, &mut self.found);
        let recovered = {
            let inputs: Vec<ViewInput> = self.traced.iter().zip(&self.found).map(|(t, f)| view_input(&frame.draws[t.draw], f)).collect();
            self.view.recover(&inputs)
        };
        let mut stats = FrameStats { camera_cut: recovered.cut, matches_lost: self.matcher.lost(), ..FrameStats::default() };
        let view = recovered.view.map(|v| v.view);
        let inverse = view.map(|v| v.inverse());
        let clip = recovered.view.map_or(Mat4::IDENTITY, |v| v.projection * v.view);
        self.world.begin_frame(frame.number, clip);
        if recovered.cut {
            self.world.clear();
        }
        self.records.clear();
        let mut instance_upload = 0;
        for (k, (t, f)) in self.traced.iter().zip(&self.found).enumerate() {
            let draw = &mut frame.draws[t.draw];
            let class = traced_class(t.tags, f, view.as_ref(), &draw.modelview, recovered.cut);
            let colours = &mut self.colours;
            let lighting = lighting::surface_lighting(draw, class, t.light_units, t.baked_layer, || colours.changed(f.id, &draw.vertices.color.values, frame.number));
            // Chunks carry units 0 and 1 and the colours, not layers nor a lighting other than
            // traced (rule 5).
            let unit_light = lighting::first_unit(draw).is_some_and(|u| t.light_units >> u & 1 != 0);
            let chunks_hold_it = self.layers.layers_of(k) == 0 && lighting == SurfaceLighting::Traced && !unit_light;
            let model = model_of(inverse.as_ref(), draw, f, class == DrawClass::Static && !t.tags.static_ && !recovered.cut);
            let in_world = chunks_hold_it && !t.tags.dynamic && (class == DrawClass::Static || model.as_ref().is_some_and(view::is_identity));
            let offered = match model {
                Some(m) if in_world => Some(self.feed.offer(&mut self.world, draw, &m, t.material_key, t.material, t.light_units, true)),
                _ => None,
            };
            if class == DrawClass::Static && f.matched == Match::New && offered.is_none() {
                instance_upload += vertex_bytes(draw);
            }
            if f.matched != Match::New {
                stats.matches_found += 1;
            }
            // Motion vectors only from the frame just before (not from an instance seen again).
            let previous_modelview = f.previous.filter(|p| p.age == 0 && !recovered.cut).map(|p| p.modelview);
            draw.class = class;
            let in_static_world = offered.is_some_and(|o| o.all_static());
            let (geometry_key, material, light_units) = (t.geometry, t.material, t.light_units);
            draw.instance = Some(Instance { id: f.id, matched: f.matched, previous_modelview, model, geometry_key, material, in_static_world, lighting, light_units });
            let probe = self.probes[self.records.len()];
            self.records.push(Record { id: f.id, probe, ordinal: f.ordinal, modelview: draw.modelview, model, class, age: 0 });
        }
        self.colours.end_frame(frame.number);
        self.matcher.finish(self.records.iter().copied(), recovered.cut);
        let update = self.world.end_frame();
        stats.static_upload_bytes = instance_upload + update.upload_bytes;
        (stats.static_chunks_new, stats.static_chunks_reused, stats.static_chunks_released) =
            (update.new_chunks, update.reused_chunks, update.released_chunks);
        stats.static_world_triangles = update.triangles;
        self.count(frame, &mut stats);
        stats.classify_ns = start.elapsed().as_nanos() as u64;
        frame.view = recovered.view;
        frame.lights = self.lights.lights();
        frame.static_world = update.chunks;
        frame.stats = stats;
    }

    /// Draws, triangles and vertex bytes per class of a classified frame.
    fn count(&self, frame: &Frame, stats: &mut FrameStats) {
        for draw in &frame.draws {
            stats.classes.add(draw.class, 1);
            stats.triangles.add(draw.class, triangles(draw) as u64);
        }
        stats.vertex_bytes = self.traced.iter().map(|t| vertex_bytes(&frame.draws[t.draw])).sum();
    }

    /// Steps 1 and 2: raster classes, layers, and the keys and probes of the traced draws.
    fn route(&mut self, frame: &mut Frame, list_version: &impl Fn(u32) -> Option<u64>) {
        self.lists.begin_frame(frame.number);
        self.layers.begin_frame();
        self.lights.begin_frame();
        self.traced.clear();
        self.probes.clear();
        let mut before = Before::default();
        for i in 0..frame.draws.len() {
            before.clears_before(&frame.clears, i);
            let (tags, hashes) = self.tags_of(&frame.draws[i]);
            let raster = routing::raster_class(&frame.draws[i], &before, tags);
            let blended = matches!(raster, None | Some(DrawClass::Translucent));
            if blended && self.lights.take(&frame.draws[i]) {
                let draw = &mut frame.draws[i];
                (draw.class, draw.instance, draw.layer) = (DrawClass::Light, None, None);
                continue;
            }
            let found = if blended { self.layer_of(&frame.draws, i, &hashes) } else { None };
            let draw = &mut frame.draws[i];
            (draw.instance, draw.layer) = (None, None);
            if let Some(found) = found {
                let base = &mut self.traced[found.base];
                base.light_units |= found.base_units;
                base.baked_layer |= found.layer.role == LayerRole::BakedLight;
                (draw.class, draw.layer) = (DrawClass::Layer, Some(found.layer));
                continue;
            }
            if let Some(class) = raster {
                draw.class = class;
                continue;
            }
            before.traced(draw);
            self.layers.add_base(i);
            let geometry = self.lists.key(draw, list_version);
            let (texture, state) = (keys::texture_key(draw), self.states.key(draw));
            let first = draw.vertices.position.first().map_or(Vec4::W, |p| Vec4::from_array(*p));
            self.probes.push(Probe {
                exact: keys::combine(&[geometry, texture, state]),
                slot: keys::combine(&[texture, state, draw.vertices.len() as u64, draw.indices.len() as u64]),
                anchor: (draw.modelview * first).truncate(),
            });
            let material = self.config.material(hashes[0], tags);
            let [m0, m1] = material.key();
            let light_units = lighting::light_units(draw, |u| hashes[u].is_some_and(|h| self.config.is_lightmap(h)));
            // The world keeps a triangle's colours and material as first offered: a lit draw's
            // GL material is in the key, so that a `glMaterial` change makes new triangles; so
            // are the units holding light, which chunks carry (a draw with layers, whose passes
            // may add light units below, is not offered).
            let lit = world_feed::lit_material_key(draw);
            let material_key = keys::combine(&[texture, state, m0, m1, lit, u64::from(light_units)]);
            self.traced.push(Traced { draw: i, tags, geometry, material_key, material, light_units, baked_layer: false });
        }
    }

    /// Step 1's layers: draw `pass` of `draws` as a layer of an earlier base (`layers`), with
    /// its role (`lighting` for a multiplying pass); `hashes`: its texture hashes.
    fn layer_of(&mut self, draws: &[Draw], pass: usize, hashes: &UnitHashes) -> Option<FoundLayer> {
        let blending = layers::blending(&draws[pass])?;
        let (base, triangles) = self.layers.find(draws, pass)?;
        let base_draw = &draws[self.layers.draw_of(base)];
        let (role, base_units) = if blending == Blending::Multiply {
            let tagged_pass = lighting::first_unit(&draws[pass]).and_then(|u| hashes[u]).is_some_and(|h| self.config.is_lightmap(h));
            let base_texture = lighting::first_unit(base_draw).and_then(|u| base_draw.textures[u].as_ref());
            let tagged_base = base_texture.is_some_and(|t| self.config.is_lightmap(self.textures.hash(t)));
            let m = lighting::multiplied(base_draw, &draws[pass], &triangles, tagged_pass, tagged_base);
            (if m.pass { LayerRole::BakedLight } else { LayerRole::Albedo }, m.base_units)
        } else {
            (blending.role(), 0)
        };
        Some(FoundLayer { base, layer: Layer { base: self.layers.draw_of(base), triangles, role }, base_units })
    }
}

impl Classifier {
    /// The `glrt.toml` tags of `draw`'s textures, and the hash of each unit's texture.
    fn tags_of(&mut self, draw: &Draw) -> (Tags, UnitHashes) {
        let mut hashes: UnitHashes = [None; MAX_TEXTURE_UNITS];
        for (h, t) in hashes.iter_mut().zip(&draw.textures) {
            *h = t.as_ref().map(|t| self.textures.hash(t));
        }
        (self.config.tags(hashes.iter().flatten().copied()), hashes)
    }

    /// Routes the draws of a frame read back before it ends (`glReadPixels` before the swap),
    /// so that the renderer traces what it will trace when the frame ends: a raster class by
    /// the rules of [`routing`], a `Light` by those of [`dlights`] (the frame's lights so far
    /// listed), a `Layer` by those of [`layers`], or `Dynamic` for a traced
    /// draw (its exact class needs the whole frame's matching; [`Classifier::classify`]
    /// replaces every class and instance when the frame ends), with an instance of a new id
    /// that says how it is lit ([`Classifier::partial_instance`]).
    /// Draws routed by an earlier read-back keep their class and instance.
    pub fn route_partial(&mut self, frame: &mut Frame) {
        self.layers.begin_frame();
        self.lights.begin_frame();
        let mut before = Before::default();
        for i in 0..frame.draws.len() {
            before.clears_before(&frame.clears, i);
            if frame.draws[i].class == DrawClass::Light {
                self.lights.take(&frame.draws[i]);
            }
            if frame.draws[i].class == DrawClass::Unclassified {
                let (tags, hashes) = self.tags_of(&frame.draws[i]);
                let raster = routing::raster_class(&frame.draws[i], &before, tags);
                let blended = matches!(raster, None | Some(DrawClass::Translucent));
                if blended && self.lights.take(&frame.draws[i]) {
                    frame.draws[i].class = DrawClass::Light;
                    continue;
                }
                let found = if blended { self.layer_of(&frame.draws, i, &hashes) } else { None };
                match found {
                    Some(found) => {
                        let base = &mut frame.draws[found.layer.base];
                        if let Some(mut instance) = base.instance {
                            // The light the layer reveals on its base, as `route` adds it.
                            instance.light_units |= found.base_units;
                            let baked_layer = found.layer.role == LayerRole::BakedLight;
                            if baked_layer || found.base_units != 0 {
                                instance.lighting = lighting::surface_lighting(base, base.class, instance.light_units, baked_layer, || false);
                            }
                            base.instance = Some(instance);
                        }
                        (frame.draws[i].class, frame.draws[i].layer) = (DrawClass::Layer, Some(found.layer));
                    }
                    None => {
                        let class = raster.unwrap_or(DrawClass::Dynamic);
                        let instance = class.is_traced().then(|| self.partial_instance(&frame.draws[i], tags, &hashes));
                        let draw = &mut frame.draws[i];
                        (draw.class, draw.layer, draw.instance) = (class, None, instance);
                    }
                }
            }
            if frame.draws[i].class.is_traced() {
                before.traced(&frame.draws[i]);
                self.layers.add_base(i);
            }
        }
        frame.lights = self.lights.lights();
    }

    /// The instance of a draw that a read-back before the frame's end routes `Dynamic`: a new
    /// id, its geometry key, `glrt.toml` material, light units, and its lighting as
    /// [`lighting::surface_lighting`] decides for a dynamic draw (the light its later layers
    /// reveal is added as they are found).
    fn partial_instance(&mut self, draw: &Draw, tags: Tags, hashes: &UnitHashes) -> Instance {
        let light_units = lighting::light_units(draw, |u| hashes[u].is_some_and(|h| self.config.is_lightmap(h)));
        Instance {
            id: self.matcher.new_id(),
            geometry_key: keys::geometry_key(draw),
            material: self.config.material(hashes[0], tags),
            lighting: lighting::surface_lighting(draw, DrawClass::Dynamic, light_units, false, || false),
            light_units,
            ..Instance::default()
        }
    }
}

/// What view recovery needs of a traced draw matched as `f`.
fn view_input<'a>(draw: &'a Draw, f: &Found) -> ViewInput<'a> {
    let previous_model = f.previous.filter(|p| f.matched == Match::Exact && p.class == DrawClass::Static).and_then(|p| p.model);
    ViewInput {
        id: f.id,
        modelview: draw.modelview,
        projection: draw.projection,
        triangles: triangles(draw),
        previous_model,
        positions: &draw.vertices.position,
    }
}

/// The model matrix (object to world) of a traced draw matched as `f`, given the inverse of
/// the view: exactly the identity when it is close to it, and the previous frame's when the
/// instance keeps its place (`keep`: static), so that world-space triangles stay bit-identical
/// from frame to frame.
fn model_of(inverse_view: Option<&Mat4>, draw: &Draw, f: &Found, keep: bool) -> Option<Mat4> {
    let model = inverse_view.map(|i| *i * draw.modelview).map(|m| if view::is_identity(&m) { Mat4::IDENTITY } else { m });
    match f.previous.and_then(|p| p.model) {
        Some(previous) if keep && model.is_some() => Some(previous),
        _ => model,
    }
}

/// The class of a traced draw (rule 4 of the module doc).
fn traced_class(tags: Tags, f: &Found, view: Option<&Mat4>, modelview: &Mat4, cut: bool) -> DrawClass {
    if tags.static_ {
        return DrawClass::Static;
    }
    if tags.dynamic || f.matched == Match::Slot {
        return DrawClass::Dynamic;
    }
    let Some(previous) = f.previous else { return DrawClass::Static };
    if previous.class != DrawClass::Static || cut {
        return previous.class;
    }
    let unchanged = match (view, previous.model) {
        (Some(view), Some(model)) => same_place(&(*view * model), modelview),
        _ => same_place(&previous.modelview, modelview),
    };
    if unchanged { DrawClass::Static } else { DrawClass::Movable }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::Vec3;

    use super::*;
    use crate::frame::class::{LayerRole, SurfaceLighting};
    use crate::frame::state::{Blend, BlendFactor, CompareFunc, RasterState};
    use crate::frame::texture::EnvMode;
    use crate::frame::{Attrib, Clear, TextureRef};
    use lighting::tests::{sized, unit};

    /// A draw of `n` triangles side by side starting at `x`, seen through `modelview`.
    fn draw(n: usize, x: f32, modelview: Mat4) -> Draw {
        let mut d = Draw::default();
        for i in 0..n {
            let x = x + i as f32;
            d.vertices.position.extend([[x, 0.0, 0.0, 1.0], [x + 1.0, 0.0, 0.0, 1.0], [x, 1.0, 0.0, 1.0]]);
            d.indices.extend([3 * i as u32, 3 * i as u32 + 1, 3 * i as u32 + 2]);
        }
        d.vertex_count = d.vertices.len();
        let mut s = RasterState { depth_test: Some(CompareFunc::Less), depth_write: true, color_mask: [true; 4], ..RasterState::default() };
        s.depth_range = [0.0, 1.0];
        d.state = Arc::new(s);
        d.modelview = modelview;
        d.projection = view::perspective(1.0, 1.0, 0.1, 1000.0);
        d
    }

    /// [`draw`] textured with `units` (texture, and how many times its coordinates repeat
    /// over each triangle's legs), every unit modulating.
    fn textured(n: usize, x: f32, modelview: Mat4, units: &[(&TextureRef, f32)]) -> Draw {
        let mut d = draw(n, x, modelview);
        d.textures = units.iter().map(|(t, _)| Some((*t).clone())).collect();
        d.texture_units = units.iter().map(|_| unit(EnvMode::Modulate)).collect();
        let corners = |r: f32| (0..n).flat_map(move |_| [[0.0, 0.0, 0.0, 1.0], [r, 0.0, 0.0, 1.0], [0.0, r, 0.0, 1.0]]).collect();
        d.vertices.texcoords = units.iter().map(|(_, r)| Attrib { values: corners(*r) }).collect();
        d
    }

    /// `base`'s triangles `triangles` drawn again (vertices copied out) as a pass textured with
    /// `units`, blending `factors` with depth test `depth` and depth writes off.
    fn pass(base: &Draw, triangles: std::ops::Range<usize>, units: &[(&TextureRef, f32)], factors: (BlendFactor, BlendFactor), depth: CompareFunc) -> Draw {
        let mut d = textured(triangles.len(), 0.0, base.modelview, units);
        d.vertices.position = base.vertices.position[3 * triangles.start..3 * triangles.end].to_vec();
        let blend = Blend { src_rgb: factors.0, dst_rgb: factors.1, ..Blend::default() };
        d.state = Arc::new(RasterState { blend: Some(blend), depth_test: Some(depth), depth_write: false, ..(*base.state).clone() });
        d
    }

    /// The layer of `draw` as (base, role, triangles).
    fn layer(draw: &Draw) -> Option<(usize, LayerRole, Vec<u32>)> {
        draw.layer.as_ref().map(|l| (l.base, l.role, l.triangles.to_vec()))
    }

    /// How traced `draw` is lit, and its light units.
    fn lit(draw: &Draw) -> (SurfaceLighting, u8) {
        draw.instance.map(|i| (i.lighting, i.light_units)).expect("traced")
    }

    /// `colours` as the per-vertex colours of `draw`.
    fn coloured(mut draw: Draw, colour: impl Fn(usize) -> [f32; 4]) -> Draw {
        draw.vertices.color = Attrib { values: (0..draw.vertices.len()).map(colour).collect() };
        draw
    }

    fn classify(c: &mut Classifier, number: u64, draws: Vec<Draw>) -> Frame {
        let mut frame = Frame { number, draws, ..Frame::default() };
        c.classify(&mut frame, |_| None);
        frame
    }

    #[test]
    fn frames_get_classes_ids_view_and_cuts() {
        let mut c = Classifier::with_config(config::Config::default());
        let placed = Mat4::from_translation(Vec3::new(0.0, 0.0, -3.0));
        let camera = |yaw: f32| Mat4::from_rotation_y(yaw) * Mat4::from_translation(Vec3::new(0.0, -1.0, -20.0));
        // Frame 0: the world (8 triangles, modelview = view) and a placed object (2).
        let f0 = classify(&mut c, 0, vec![draw(8, 0.0, camera(0.0)), draw(2, 50.0, camera(0.0) * placed)]);
        assert!(f0.draws.iter().all(|d| d.class == DrawClass::Static));
        let ids: Vec<u64> = f0.draws.iter().map(|d| d.instance.unwrap().id).collect();
        assert_eq!(f0.view.unwrap().view, camera(0.0));
        // Frame 1: the camera turns, the object moves, an animated mesh appears.
        let moved = Mat4::from_translation(Vec3::new(0.5, 0.0, -3.0));
        let f1 = classify(&mut c, 1, vec![draw(8, 0.0, camera(0.1)), draw(2, 50.0, camera(0.1) * moved), draw(3, 9.0, camera(0.1))]);
        let classes: Vec<DrawClass> = f1.draws.iter().map(|d| d.class).collect();
        assert_eq!(classes, [DrawClass::Static, DrawClass::Movable, DrawClass::Static]);
        assert_eq!(f1.draws[1].instance.unwrap().previous_modelview, Some(camera(0.0) * placed));
        assert_eq!((f1.stats.matches_found, f1.stats.matches_lost, f1.stats.camera_cut), (2, 0, false));
        // Frame 2: the mesh's vertices change (same slot): dynamic, same id.
        let f2 = classify(&mut c, 2, vec![draw(8, 0.0, camera(0.2)), draw(3, 9.5, camera(0.2))]);
        assert_eq!((f2.draws[1].class, f2.draws[1].instance.unwrap().id), (DrawClass::Dynamic, f1.draws[2].instance.unwrap().id));
        assert_eq!(f2.draws[0].instance.unwrap().id, ids[0]);
        assert_eq!(f2.stats.matches_lost, 1, "the movable object was not drawn");
        assert!(f2.stats.static_world_triangles >= 8, "the world was offered twice: {:?}", f2.stats);
        // Frame 3: the world is culled; a second static object drawn since frame 1 would chain
        // the view; here only the world's twin (new geometry) is drawn far away: a cut.
        let f3 = classify(&mut c, 3, vec![draw(4, 100.0, camera(0.3) * Mat4::from_translation(Vec3::splat(900.0)))]);
        assert!(f3.stats.camera_cut && f3.stats.static_chunks_released > 0, "{:?}", f3.stats);
        assert_eq!(f3.stats.static_world_triangles, 0);
        assert!(f3.draws[0].instance.unwrap().previous_modelview.is_none());
    }

    #[test]
    fn a_frame_read_back_before_it_ends_is_routed_as_its_end_will_be() {
        let mut c = Classifier::with_config(config::Config::default());
        let camera = Mat4::from_translation(Vec3::new(0.0, -1.0, -20.0));
        let mut hud = draw(2, 0.0, Mat4::IDENTITY);
        hud.projection = Mat4::from_scale(Vec3::new(1.0 / 32.0, 1.0 / 32.0, -1.0)); // glOrtho: last row (0, 0, 0, 1)
        let mut frame = Frame { number: 0, draws: vec![draw(8, 0.0, camera), hud], ..Frame::default() };
        c.route_partial(&mut frame);
        assert_eq!([frame.draws[0].class, frame.draws[1].class], [DrawClass::Dynamic, DrawClass::Overlay]);
        // The end of the frame gives the traced draw its class from matching.
        c.classify(&mut frame, |_| None);
        assert_eq!([frame.draws[0].class, frame.draws[1].class], [DrawClass::Static, DrawClass::Overlay]);
    }

    #[test]
    fn materials_reach_instances_and_the_static_world() {
        let texture = texture_hash::tests::texture(5, 1, 200);
        let hash = texture_hash::content_hash(&texture.content);
        let text = format!("emissive = [\"{hash:#x}\"]\n[materials]\n\"{hash:#x}\" = {{ roughness = 0.1, metalness = 1 }}\n");
        let (config, warnings) = crate::config::Config::parse(&text, "g.toml").unwrap();
        assert!(warnings.is_empty(), "{warnings:?}");
        let mut c = Classifier::with_config(config::Config::from(&config));
        let camera = Mat4::from_translation(Vec3::new(0.0, 0.0, -10.0));
        let textured = || Draw { textures: vec![Some(texture.clone())], ..draw(4, 0.0, camera) };
        classify(&mut c, 0, vec![textured(), draw(4, 10.0, camera)]);
        let f = classify(&mut c, 1, vec![textured(), draw(4, 10.0, camera)]);
        let listed = MaterialOverride { roughness: 0.1, metalness: 1.0, emissive: 1.0 };
        assert_eq!(f.draws[0].instance.unwrap().material, listed, "[materials], emissive from the list");
        assert_eq!(f.draws[1].instance.unwrap().material, MaterialOverride::default());
        let chunks: Vec<(Option<u32>, MaterialOverride)> = f.static_world.iter().map(|c| (c.textures[0].as_ref().map(|t| t.id), c.material)).collect();
        assert!(chunks.contains(&(Some(5), listed)) && chunks.contains(&(None, MaterialOverride::default())), "{chunks:?}");
        assert!(chunks.iter().all(|&(id, m)| (id == Some(5)) == (m == listed)), "{chunks:?}");
    }

    #[test]
    fn draws_whose_triangles_all_joined_the_world_are_marked() {
        let mut c = Classifier::with_config(config::Config::default());
        let camera = Mat4::from_translation(Vec3::new(0.0, -1.0, -20.0));
        let marked = |f: &Frame| f.draws.iter().map(|d| d.instance.unwrap().in_static_world).collect::<Vec<_>>();
        // Seen once: pending; seen again: in the world.
        assert_eq!(marked(&classify(&mut c, 0, vec![draw(8, 0.0, camera)])), [false]);
        assert_eq!(marked(&classify(&mut c, 1, vec![draw(8, 0.0, camera)])), [true]);
        // The batch grows by two triangles never seen: partly in the world, not marked, until
        // they joined too.
        assert_eq!(marked(&classify(&mut c, 2, vec![draw(10, 0.0, camera)])), [false]);
        let f = classify(&mut c, 3, vec![draw(10, 0.0, camera)]);
        assert_eq!((marked(&f), f.stats.static_world_triangles), (vec![true], 10));
        // A draw tagged nothing but moving every frame (dynamic by slot) is never marked.
        for k in 4..8 {
            let f = classify(&mut c, k, vec![draw(10, 0.0, camera), draw(3, 30.0 + k as f32 * 0.37, camera)]);
            assert!(!marked(&f)[1], "frame {k}");
        }
    }

    /// A lit wall whose `glMaterial` diffuse colour changes (red, then blue) is traced blue:
    /// drawn blue twice, it is in the world again (its draw marked, so the tracer shades it
    /// by the chunks), and the chunks hold it blue; the red triangles, no longer drawn where
    /// the view shows their cell drawn, are released. Before, the chunks kept it red.
    #[test]
    fn a_lit_wall_whose_diffuse_colour_changes_is_held_in_its_new_colour() {
        let mut c = Classifier::with_config(config::Config::default());
        let camera = Mat4::from_translation(Vec3::new(-4.0, -0.5, -20.0));
        let wall = |diffuse: [f32; 4]| {
            let mut d = draw(8, 0.0, camera);
            let mut lighting = crate::frame::state::Lighting::default();
            lighting.front.diffuse = diffuse;
            d.state = Arc::new(RasterState { lighting: Some(lighting), ..(*d.state).clone() });
            d.vertices.color = Attrib { values: vec![[1.0; 4]] };
            d
        };
        let (red, blue) = ([1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]);
        let colours = |f: &Frame| {
            let mut seen: Vec<[u8; 4]> = f.static_world.iter().flat_map(|c| c.colors.iter().copied()).collect();
            seen.dedup();
            seen
        };
        for n in 0..2 {
            classify(&mut c, n, vec![wall(red)]);
        }
        let held = classify(&mut c, 2, vec![wall(red)]);
        assert_eq!(colours(&held), [[255, 0, 0, 255]]);
        classify(&mut c, 3, vec![wall(blue)]);
        let f = classify(&mut c, 4, vec![wall(blue)]);
        assert!(f.draws[0].instance.unwrap().in_static_world);
        assert!(colours(&f).contains(&[0, 0, 255, 255]), "the chunks hold the wall blue: {:?}", colours(&f));
        let f = (5..5 + u64::from(static_world::RELEASE_FRAMES) + 1).map(|n| classify(&mut c, n, vec![wall(blue)])).last().expect("frames");
        assert_eq!(colours(&f), [[0, 0, 255, 255]], "the red triangles released");
    }

    /// A lit wall whose `glMaterial` specular colour and shininess are set after it joined
    /// the world is held with its new material: the tracer shades chunks by their state as
    /// first offered, so the change must make new triangles (before, the wall stayed matte).
    #[test]
    fn a_lit_wall_whose_specular_material_changes_is_held_with_it() {
        let mut c = Classifier::with_config(config::Config::default());
        let camera = Mat4::from_translation(Vec3::new(-4.0, -0.5, -20.0));
        let wall = |specular: [f32; 4], shininess: f32| {
            let mut d = draw(8, 0.0, camera);
            let mut lighting = crate::frame::state::Lighting::default();
            (lighting.front.specular, lighting.front.shininess) = (specular, shininess);
            d.state = Arc::new(RasterState { lighting: Some(lighting), ..(*d.state).clone() });
            d
        };
        let held = |f: &Frame| {
            let mut seen: Vec<([f32; 4], f32)> = f.static_world.iter().filter_map(|c| c.shading.state.lighting.as_ref()).map(|l| (l.front.specular, l.front.shininess)).collect();
            seen.dedup();
            seen
        };
        let (matte, glossy) = (([0.0, 0.0, 0.0, 1.0], 0.0), ([1.0; 4], 32.0));
        let f = (0..3).map(|n| classify(&mut c, n, vec![wall(matte.0, matte.1)])).last().expect("frames");
        assert_eq!(held(&f), [matte]);
        let f = (3..5).map(|n| classify(&mut c, n, vec![wall(glossy.0, glossy.1)])).last().expect("frames");
        assert!(f.draws[0].instance.unwrap().in_static_world);
        assert!(held(&f).contains(&glossy), "the chunks hold the wall glossy: {:?}", held(&f));
        let f = (5..5 + u64::from(static_world::RELEASE_FRAMES) + 1).map(|n| classify(&mut c, n, vec![wall(glossy.0, glossy.1)])).last().expect("frames");
        assert_eq!(held(&f), [glossy], "the matte triangles released");
    }

    #[test]
    fn the_view_chains_through_other_static_draws() {
        let mut c = Classifier::with_config(config::Config::default());
        let placed = Mat4::from_translation(Vec3::new(4.0, 0.0, 0.0));
        let camera = |z: f32| Mat4::from_translation(Vec3::new(0.0, 0.0, -z));
        classify(&mut c, 0, vec![draw(8, 0.0, camera(10.0)), draw(2, 0.0, camera(10.0) * placed)]);
        classify(&mut c, 1, vec![draw(8, 0.0, camera(10.5)), draw(2, 0.0, camera(10.5) * placed)]);
        // The reference (8 triangles) leaves the screen; the placed object keeps the world frame.
        let f = classify(&mut c, 2, vec![draw(2, 0.0, camera(11.0) * placed)]);
        let view = f.view.unwrap();
        assert!(view::same_place(&view.view, &camera(11.0)) && !f.stats.camera_cut, "{view:?}");
        assert_eq!(f.draws[0].class, DrawClass::Static);
        assert!(view::same_place(&f.draws[0].instance.unwrap().model.unwrap(), &placed));
    }

    #[test]
    fn a_rebatched_world_keeps_its_world_frame() {
        // Every frame the world comes in other batches (nothing matches exactly), drawn with
        // modelview = view while the camera turns and walks: no cut, the view follows.
        let mut c = Classifier::with_config(config::Config::default());
        for k in 0..20u64 {
            let camera = Mat4::from_rotation_y(0.05 * k as f32) * Mat4::from_translation(Vec3::new(0.1 * k as f32, -1.0, -5.0));
            let batches = vec![draw(6 + (k % 4) as usize, k as f32, camera), draw(2, 40.0 + k as f32, camera)];
            let f = classify(&mut c, k, batches);
            assert!(!f.stats.camera_cut, "frame {k}");
            assert!(view::same_place(&f.view.unwrap().view, &camera), "frame {k}");
            assert!(f.draws.iter().all(|d| d.instance.unwrap().model == Some(Mat4::IDENTITY)), "frame {k}: in the world frame");
        }
    }

    #[test]
    fn multi_pass_materials_become_layers_of_their_base() {
        use BlendFactor::{DstColor, One, OneMinusSrcAlpha, SrcAlpha, SrcColor, Zero};
        use CompareFunc::{Equal, LessEqual};
        use LayerRole::{Albedo, BakedLight, Decal, Emission};
        // A 64² surface texture once over each triangle's legs, a 128² lightmap page of which a
        // triangle covers a 16th across (64 times fewer texels), a 32² detail texture 8 times.
        let (texture, page, detail) = (sized(1, 64, 64), sized(2, 128, 128), sized(3, 32, 32));
        let camera = Mat4::from_translation(Vec3::new(0.0, -1.0, -20.0));
        let frame = |c: &mut Classifier, number| {
            // Quake 3's multitexture (base × lightmap on unit 1), its detail pass, a dynamic
            // light pass over its triangles 2 and 3, a decal over triangle 0.
            let floor = textured(4, 0.0, camera, &[(&texture, 1.0), (&page, 1.0 / 16.0)]);
            let detail_pass = pass(&floor, 0..4, &[(&detail, 8.0)], (DstColor, SrcColor), LessEqual);
            let dlight = pass(&floor, 2..4, &[(&texture, 1.0)], (One, One), Equal);
            let decal = pass(&floor, 0..1, &[(&texture, 1.0)], (SrcAlpha, OneMinusSrcAlpha), LessEqual);
            // A texture, then its lightmap as a pass; a lightmap base pass, then the texture
            // multiplied over it (`GL_ZERO, GL_SRC_COLOR`).
            let metal = textured(2, 10.0, camera, &[(&texture, 1.0)]);
            let lightmap_pass = pass(&metal, 0..2, &[(&page, 1.0 / 16.0)], (DstColor, Zero), Equal);
            let lightmap_base = textured(2, 20.0, camera, &[(&page, 1.0 / 16.0)]);
            let texture_pass = pass(&lightmap_base, 0..2, &[(&texture, 1.0)], (Zero, SrcColor), LessEqual);
            // Water over nothing traced; a pass over the floor's triangles seen elsewhere.
            let water = pass(&draw(2, 30.0, camera), 0..2, &[(&texture, 1.0)], (SrcAlpha, OneMinusSrcAlpha), LessEqual);
            let elsewhere = Draw { modelview: Mat4::IDENTITY, ..pass(&floor, 0..1, &[(&texture, 1.0)], (One, One), Equal) };
            // A plain wall; a GL-lit wall with a lightmap on unit 1.
            let wall = draw(2, 40.0, camera);
            let mut lit_wall = textured(2, 50.0, camera, &[(&texture, 1.0), (&page, 1.0 / 16.0)]);
            lit_wall.state = Arc::new(RasterState { lighting: Some(Default::default()), ..(*lit_wall.state).clone() });
            let draws = vec![floor, detail_pass, dlight, decal, metal, lightmap_pass, lightmap_base, texture_pass, water, elsewhere, wall, lit_wall];
            classify(c, number, draws)
        };
        let mut c = Classifier::with_config(config::Config::default());
        for number in 0..3 {
            let f = frame(&mut c, number);
            let classes: Vec<DrawClass> = f.draws.iter().map(|d| d.class).collect();
            use DrawClass::{Layer, Static, Translucent};
            assert_eq!(classes, [Static, Layer, Layer, Layer, Static, Layer, Static, Layer, Translucent, Translucent, Static, Static], "frame {number}");
            let layers: Vec<_> = f.draws.iter().filter_map(layer).collect();
            assert_eq!(
                layers,
                [(0, Albedo, vec![0, 1, 2, 3]), (0, Emission, vec![2, 3]), (0, Decal, vec![0]), (4, BakedLight, vec![0, 1]), (6, Albedo, vec![0, 1])],
                "frame {number}"
            );
            let bases = [0, 4, 6, 10, 11].map(|i| lit(&f.draws[i]));
            use SurfaceLighting::{Baked, Traced};
            assert_eq!(bases, [(Baked, 0b10), (Baked, 0), (Baked, 0b01), (Traced, 0), (Traced, 0b10)], "frame {number}");
            assert_eq!((f.stats.classes.get(Layer), f.stats.triangles.get(Layer)), (5, 11));
            // The static world holds the plain wall and the GL-lit one (its chunks are its
            // albedo), none of the surfaces it would take layers or baked light from.
            let in_world: Vec<bool> = f.draws.iter().filter_map(|d| d.instance).map(|i| i.in_static_world).collect();
            assert_eq!(in_world, [false, false, false, number > 0, number > 0], "frame {number}");
            assert_eq!(f.stats.static_world_triangles, if number > 0 { 4 } else { 0 }, "frame {number}");
        }
        // Read back before it ends, the frame is routed as its end will be.
        let mut partial = frame(&mut Classifier::with_config(config::Config::default()), 0);
        partial.draws.iter_mut().for_each(|d| (d.class, d.layer) = (DrawClass::Unclassified, None));
        c.route_partial(&mut partial);
        assert_eq!(partial.draws.iter().filter_map(layer).map(|l| (l.0, l.1)).collect::<Vec<_>>(), [(0, Albedo), (0, Emission), (0, Decal), (4, BakedLight), (6, Albedo)]);
        assert_eq!([0, 4, 8].map(|i| partial.draws[i].class), [DrawClass::Dynamic, DrawClass::Dynamic, DrawClass::Translucent]);
        // And lit as its end will light it: the lightmap unit, the lightmap pass and the
        // lightmap base pass under a texture pass make baked surfaces.
        let bases = [0, 4, 6, 10, 11].map(|i| lit(&partial.draws[i]));
        use SurfaceLighting::{Baked, Traced};
        assert_eq!(bases, [(Baked, 0b10), (Baked, 0), (Baked, 0b01), (Traced, 0), (Traced, 0b10)], "read back");
    }

    #[test]
    fn the_baked_world_holds_the_static_draws_whose_light_is_baked() {
        let (texture, page) = (sized(1, 64, 64), sized(2, 128, 128));
        let camera = Mat4::from_translation(Vec3::new(0.0, -1.0, -20.0));
        let mut c = Classifier::with_config(config::Config::default());
        let mut baked = baked_world::BakedWorld::default();
        for number in 0..3 {
            // Quake 3's multitexture (a lightmap on unit 1) with constant vertex colours, a
            // lightmap base with the texture multiplied over it, and a plain wall (traced: the
            // static world's, not the baked world's).
            let floor = coloured(textured(4, 0.0, camera, &[(&texture, 1.0), (&page, 1.0 / 16.0)]), |_| [0.5, 0.4, 0.3, 1.0]);
            let lightmap_base = textured(2, 20.0, camera, &[(&page, 1.0 / 16.0)]);
            let texture_pass = pass(&lightmap_base, 0..2, &[(&texture, 1.0)], (BlendFactor::Zero, BlendFactor::SrcColor), CompareFunc::LessEqual);
            let f = classify(&mut c, number, vec![floor, lightmap_base, texture_pass, draw(2, 40.0, camera)]);
            baked.add(&f);
            // Triangles join in the second frame that offers them.
            let triangles: usize = baked.chunks().iter().map(|c| c.triangles()).sum();
            assert_eq!((triangles, f.stats.static_world_triangles), if number > 0 { (6, 2) } else { (0, 0) }, "frame {number}");
        }
        // A chunk per material, with the units that hold light and without the colours.
        let mut units: Vec<(u8, Option<u32>)> = baked.chunks().iter().map(|c| (c.shading.light_units, c.textures[0].as_ref().map(|t| t.id))).collect();
        units.sort_unstable();
        units.dedup();
        assert_eq!(units, [(0b01, Some(2)), (0b10, Some(1))]);
        assert!(baked.chunks().iter().all(|c| c.colors.is_empty()));
    }

    #[test]
    fn a_lightmap_tag_makes_a_texture_light_whatever_its_density() {
        // The "lightmap" here is as fine as the texture.
        let (texture, lightmap) = (sized(1, 64, 64), sized(2, 64, 64));
        let hash = texture_hash::content_hash(&lightmap.content);
        let (config, _) = crate::config::Config::parse(&format!("lightmap = [\"{hash:#x}\"]\n"), "g.toml").unwrap();
        let camera = Mat4::from_translation(Vec3::new(0.0, 0.0, -10.0));
        let base = textured(2, 0.0, camera, &[(&texture, 1.0)]);
        let over = pass(&base, 0..2, &[(&lightmap, 1.0)], (BlendFactor::DstColor, BlendFactor::Zero), CompareFunc::Equal);
        let two_units = textured(2, 10.0, camera, &[(&texture, 1.0), (&lightmap, 1.0)]);
        let roles = |config: config::Config| {
            let f = classify(&mut Classifier::with_config(config), 0, vec![base.clone(), over.clone(), two_units.clone()]);
            (layer(&f.draws[1]).map(|l| l.1), lit(&f.draws[0]), lit(&f.draws[2]))
        };
        let untagged = roles(config::Config::default());
        assert_eq!(untagged, (Some(LayerRole::Albedo), (SurfaceLighting::Traced, 0), (SurfaceLighting::Traced, 0)));
        let tagged = roles(config::Config::from(&config));
        assert_eq!(tagged, (Some(LayerRole::BakedLight), (SurfaceLighting::Baked, 0), (SurfaceLighting::Baked, 0b10)));
    }

    #[test]
    fn vertex_colours_are_baked_light_or_lighting() {
        let camera = Mat4::from_translation(Vec3::new(0.0, -1.0, -20.0));
        let grey = |k: f32| move |i: usize| [0.2 + 0.1 * (i % 3) as f32 + k, 0.5, 0.5, 1.0];
        let mut c = Classifier::with_config(config::Config::default());
        for number in 0..3u64 {
            let k = number as f32 * 0.01;
            let place = Mat4::from_translation(Vec3::new(k, 0.0, 0.0));
            let mut gl_lit = coloured(draw(2, 40.0, camera), grey(0.0));
            gl_lit.state = Arc::new(RasterState { lighting: Some(Default::default()), ..(*gl_lit.state).clone() });
            let draws = vec![
                draw(8, 0.0, camera),                          // white: its colour is its albedo
                coloured(draw(2, 10.0, camera), grey(0.0)),    // vertex-lit world: baked
                coloured(draw(2, 20.0, camera), grey(k)),      // a model standing, light changing
                coloured(draw(2, 30.0, camera * place), grey(0.0)), // a model moving
                gl_lit,
            ];
            let f = classify(&mut c, number, draws);
            let lighting: Vec<SurfaceLighting> = f.draws.iter().map(|d| lit(d).0).collect();
            use SurfaceLighting::{Baked, Traced, VertexLit};
            let expected = if number == 0 { [Traced, Baked, Baked, Baked, Traced] } else { [Traced, Baked, VertexLit, VertexLit, Traced] };
            assert_eq!(lighting, expected, "frame {number}");
            assert_eq!(f.draws[2].class, DrawClass::Static, "same geometry, same place");
            // Chunks do not say how a surface is lit: only the traced-lit ones are offered.
            let in_world: Vec<bool> = f.draws.iter().map(|d| d.instance.unwrap().in_static_world).collect();
            assert_eq!(in_world, [number > 0, false, false, false, number > 0], "frame {number}");
        }
    }

    #[test]
    fn the_view_weapon_and_hud_icons_are_drawn_over_the_scene() {
        let camera = Mat4::from_translation(Vec3::new(0.0, -1.0, -20.0));
        let with = |d: Draw, f: &dyn Fn(&mut RasterState)| {
            let mut s = (*d.state).clone();
            f(&mut s);
            Draw { state: Arc::new(s), ..d }
        };
        let draws = vec![
            draw(8, 0.0, camera),
            with(draw(2, 0.0, Mat4::IDENTITY), &|s| s.depth_range = [0.0, 0.3]), // weapon
            draw(3, 20.0, camera),                                               // after the clear
            with(draw(4, 0.0, Mat4::IDENTITY), &|s| s.viewport = [10, 0, 24, 24]), // icon
        ];
        let clear = Clear { before_draw: 2, depth: Some(1.0), depth_mask: true, scissor: Some([10, 0, 24, 24]), ..Clear::default() };
        let mut frame = Frame { number: 0, draws, clears: vec![clear], ..Frame::default() };
        Classifier::with_config(config::Config::default()).classify(&mut frame, |_| None);
        let classes: Vec<DrawClass> = frame.draws.iter().map(|d| d.class).collect();
        assert_eq!(classes, [DrawClass::Static, DrawClass::Overlay, DrawClass::Overlay, DrawClass::Overlay]);
        assert!(frame.draws[1..].iter().all(|d| d.instance.is_none()));
    }
}
