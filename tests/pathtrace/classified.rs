//! What hash tracking concludes about multi-pass and lightmapped draws (issue 16:
//! `DrawClass::Layer`, `Instance::lighting`, `Instance::light_units`), stated by the tests
//! that trace such draws: edits of the frames a context makes, for
//! `lavapipe::Classified`, so the tracer is tested on frames classified as it expects.

use std::sync::Arc;

use glrt::frame::class::{DrawClass, Layer, LayerRole, SurfaceLighting};
use glrt::frame::state::{Blend, BlendFactor};
use glrt::frame::texture::EnvMode;
use glrt::frame::{Draw, Frame};

/// The role of a pass blending with `blend`, as Quake 3's shader stages use them.
pub fn role(blend: &Blend) -> Option<LayerRole> {
    use BlendFactor::{DstColor, One, OneMinusSrcAlpha, SrcAlpha, SrcColor, Zero};
    match (blend.src_rgb, blend.dst_rgb) {
        (DstColor, Zero) | (Zero, SrcColor) => Some(LayerRole::BakedLight),
        (DstColor, SrcColor) => Some(LayerRole::Albedo),
        (One, One) | (SrcAlpha, One) => Some(LayerRole::Emission),
        (SrcAlpha, OneMinusSrcAlpha) => Some(LayerRole::Decal),
        _ => None,
    }
}

/// Whether `draw` is traced by hash tracking (a traced class, an instance).
fn traced(draw: &Draw) -> bool {
    draw.class.is_traced() && draw.instance.is_some()
}

/// Every blended draw over the same vertices and indices as an earlier traced draw becomes a
/// pass of it (class `Layer`, the role of its blend function, triangle for triangle); a base
/// with a lightmap pass is `Baked`.
pub fn passes(frame: &mut Frame) {
    for i in 0..frame.draws.len() {
        let draw = &frame.draws[i];
        let Some(role) = draw.state.blend.as_ref().and_then(role).filter(|_| !traced(draw)) else { continue };
        let same = |base: &Draw| traced(base) && base.vertices.position == draw.vertices.position && base.indices == draw.indices;
        let Some(base) = frame.draws[..i].iter().rposition(same) else { continue };
        let triangles: Arc<[u32]> = (0..draw.indices.len() as u32 / 3).collect();
        let draw = &mut frame.draws[i];
        draw.class = DrawClass::Layer;
        draw.layer = Some(Layer { base, triangles, role });
        if role == LayerRole::BakedLight
            && let Some(instance) = &mut frame.draws[base].instance
        {
            instance.lighting = SurfaceLighting::Baked;
        }
    }
}

/// Every traced draw whose unit 1 multiplies the result of unit 0 by its texture
/// (`GL_MODULATE`, or `GL_COMBINE` modulating) holds its light in unit 1: `Baked`.
pub fn lightmap_units(frame: &mut Frame) {
    for draw in frame.draws.iter_mut().filter(|d| traced(d)) {
        let modulates = draw.texture_units.get(1).copied().flatten().is_some_and(|u| matches!(u.env.mode, EnvMode::Modulate | EnvMode::Combine));
        if modulates && let Some(instance) = &mut draw.instance {
            instance.lighting = SurfaceLighting::Baked;
            instance.light_units = 0b10;
        }
    }
}

/// Every traced draw that `which` picks is lit as `lighting` says.
pub fn lit(frame: &mut Frame, which: impl Fn(&Draw) -> bool, lighting: SurfaceLighting) {
    for draw in frame.draws.iter_mut().filter(|d| traced(d) && which(d)) {
        if let Some(instance) = &mut draw.instance {
            instance.lighting = lighting;
        }
    }
}

/// Leaves the static world out: no chunk, no draw covered by one (for tests of what is drawn
/// in the frame alone).
pub fn without_world(frame: &mut Frame) {
    frame.static_world = Default::default();
    for instance in frame.draws.iter_mut().filter_map(|d| d.instance.as_mut()) {
        instance.in_static_world = false;
    }
}
