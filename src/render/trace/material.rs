//! The material of a traced surface ([`Surface`]: a traced draw and its passes): a stack of
//! layers that `shaders/trace/stack.glsl` evaluates as the rasterizer draws the surface, and
//! the split of what it shows into albedo, baked light and emission.
//!
//! **Layers.** A material holds one [`GpuLayer`] per traced texture unit of the base (units 0
//! and 1, [`TRACED_UNITS`], whose coordinates the triangle corners carry; units past 1 are left
//! out), then one per pass ([`MAX_PASSES`]). A layer is what `shaders/texenv.glsl`'s `tex_env`
//! needs to apply a unit (its texture in the texel pool, its unit and combiner words and
//! environment colour, [`crate::render::texenv`]); a pass adds its blend function (factors,
//! equations, constant colour, as `glBlendFuncSeparate`, `glBlendEquationSeparate` and
//! `glBlendColor` set them) and its alpha test. The shader walks them in order, as the
//! rasterizer does: the base's units combine the primary colour with their texels through
//! `tex_env`, as `ff.frag` does per enabled unit; then each pass computes its own colour
//! (its unit 0's `tex_env` of its primary colour and texel, at the pass's own corners,
//! `super::scene`), drops it where its alpha test fails, and blends it over the colour so far
//! (`shaders/trace/blend.glsl`, OpenGL 1.5 section 4.1.8, clamped as a fixed-point colour
//! buffer is). Alpha tested bases cut the surface out where their own alpha test fails.
//!
//! **Light.** Each layer has a role ([`LAYER_COLOR`], [`LAYER_BAKED_LIGHT`],
//! [`LAYER_EMISSION`]): a texture unit holding baked light
//! ([`crate::frame::class::Instance::light_units`]) and a [`LayerRole::BakedLight`] pass are
//! baked light, a [`LayerRole::Emission`] pass is emission, every other unit and pass
//! ([`LayerRole::Albedo`], [`LayerRole::Decal`]) is colour. From one walk the shader takes
//! three colours (display-encoded, then decoded to linear radiance):
//! - the **raster colour** `C`: every layer, what the rasterizer shows;
//! - the **albedo** `A`: the stack without its baked-light and emission layers (left out: as a
//!   white lightmap under plain modulation would leave the colour), with white for the RGB of
//!   the primary colours when the vertex colours are light ([`MATERIAL_TINT_PRIMARY`]: a
//!   [`SurfaceLighting::Baked`] surface that has no lightmap, baked into its vertex colours),
//!   or, for a [`SurfaceLighting::VertexLit`] model, their common hue
//!   ([`super::vertex_light::tint`]: games tint models through their colours);
//! - the **emission** `E`: what the emission passes add to the display, `linear(C) −
//!   linear(C without them)`, plus the GL material's emission and the `glrt.toml` emissive
//!   scale times `linear(C without them)`.
//!
//! A vertex-lit model's colours also hold the dynamic lights near it (games add them to the
//! model's light, as Quake 3's `R_SetupEntityLighting` does): [`MATERIAL_VERTEX_LIT`] keeps
//! the dynamic lights of [`super::lights`] from lighting it a second time (its light comes
//! from its colours, [`super::vertex_light`], which also sets the material's `ambient`).
//!
//! A [`SurfaceLighting::Baked`] surface ([`MATERIAL_BAKED`]) holds light the game baked:
//! direct and indirect, everything that arrives at it. Tracing computes that light itself, so
//! counting both would count it twice. As in RTX Remix or Quake 2 RTX's lightmapped mode, the
//! tracer makes the surface **emit** its raster colour, `linear(C)` (with its emission), and
//! reflect **no traced light** (no light sampling, no continuation ray: a path ends on it),
//! for camera rays and bounces alike. The camera then sees exactly the raster colour
//! (`linear(C)` displayed through a tone curve that is the identity below its knee,
//! [`super::settings::Tonemap::Knee`]), and surfaces that are not baked (models, movers)
//! receive the baked world's light as bounce light, which their traced light does not already
//! hold. Every other surface reflects traced light with albedo `A` and emits `E`. The setting
//! [`Lightmaps::Ignore`] traces baked surfaces as reflectors too (albedo `A`, emission `E`).
//!
//! The emission of passes and emissive materials is also sampled by next-event estimation
//! ([`super::emitters`]); a baked surface's raster colour is not (it is everywhere: paths find
//! it by their continuation rays).

use glam::Vec3;
use xxhash_rust::xxh3::xxh3_64;

use super::gpu_types::{GpuLayer, GpuMaterial};
use super::settings::Lightmaps;
use super::shader_constants::{
    BLEND_DST_ALPHA, BLEND_DST_RGB, BLEND_EQUATION_ALPHA, BLEND_EQUATION_RGB, BLEND_SRC_ALPHA, BLEND_SRC_RGB, EQUATION_ADD, EQUATION_MAX, EQUATION_MIN,
    EQUATION_REVERSE_SUBTRACT, EQUATION_SUBTRACT, FACTOR_CONSTANT_ALPHA, FACTOR_CONSTANT_COLOR, FACTOR_DST_ALPHA, FACTOR_DST_COLOR, FACTOR_ONE,
    FACTOR_ONE_MINUS_CONSTANT_ALPHA, FACTOR_ONE_MINUS_CONSTANT_COLOR, FACTOR_ONE_MINUS_DST_ALPHA, FACTOR_ONE_MINUS_DST_COLOR, FACTOR_ONE_MINUS_SRC_ALPHA,
    FACTOR_ONE_MINUS_SRC_COLOR, FACTOR_SRC_ALPHA, FACTOR_SRC_ALPHA_SATURATE, FACTOR_SRC_COLOR, FACTOR_ZERO, LAYER_BAKED_LIGHT, LAYER_COLOR, LAYER_EMISSION, NO_RADIOSITY,
    LAYER_OFF, MATERIAL_BAKED, MATERIAL_LAYERS, MATERIAL_TINT_PRIMARY, MATERIAL_VERTEX_LIT, MAX_PASSES, NO_EMITTER, NO_TEXTURE, TRACED_UNITS,
};
use super::surfaces::Surface;
use super::vertex_light;
use super::scene::{enabled, srgb_to_linear};
use crate::frame::class::{LayerRole, SurfaceLighting};
use crate::frame::state::{Blend, BlendEquation, BlendFactor, CompareFunc};
use crate::frame::texture::TextureRef;
use crate::frame::Draw;
use crate::render::texenv::{self, codes};

/// Material values the tracer applies where neither GL nor `glrt.toml` says otherwise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialDefaults {
    /// Dielectric reflectance at normal incidence of unlit surfaces.
    pub specular: f32,
}

impl Default for MaterialDefaults {
    fn default() -> MaterialDefaults {
        MaterialDefaults { specular: 0.04 }
    }
}

/// The textures `surface`'s material samples, per layer: the base's traced units that have a
/// target enabled, then each pass's unit 0.
pub fn textures<'a>(surface: &Surface<'a>) -> [Option<&'a TextureRef>; MATERIAL_LAYERS] {
    let texture = |draw: &'a Draw, unit: usize| draw.textures.get(unit).and_then(Option::as_ref).filter(|_| enabled(draw, unit));
    std::array::from_fn(|layer| match layer.checked_sub(TRACED_UNITS) {
        None => texture(surface.base, layer),
        Some(pass) => surface.passes.get(pass).and_then(|&p| texture(p, 0)),
    })
}

/// The layer of texture unit `unit` of `draw`, whose texture is `texture` in the texel pool,
/// with role `role` (when the unit textures).
fn unit_layer(draw: &Draw, unit: usize, texture: Option<u32>, role: u32) -> GpuLayer {
    let env = draw.texture_units.get(unit).copied().flatten();
    let content = draw.textures.get(unit).and_then(Option::as_ref).map(|t| &t.content);
    let (Some(texture), Some(env), Some(content)) = (texture, env, content) else {
        return GpuLayer { texture: NO_TEXTURE, role: LAYER_OFF, ..replacing() };
    };
    let [combine_rgb, combine_alpha] = texenv::combine_words(&env.env);
    GpuLayer { env_color: env.env.color, texture, env: texenv::unit_bits(&env, content), combine_rgb, combine_alpha, role, ..replacing() }
}

/// A layer that blends by replacing, without alpha test (what the units are).
fn replacing() -> GpuLayer {
    GpuLayer { blend: blend_word(None), alpha_func: CompareFunc::Always as u32, ..GpuLayer::default() }
}

/// The layer of pass `pass` (a draw of class `Layer`), whose unit-0 texture is `texture` in
/// the texel pool: its texture environment (an untextured pass is its primary colour: a
/// modulation by white), role, blend function and alpha test.
fn pass_layer(pass: &Draw, texture: Option<u32>) -> GpuLayer {
    let role = match pass.layer.as_ref().map(|l| l.role) {
        Some(LayerRole::BakedLight) => LAYER_BAKED_LIGHT,
        Some(LayerRole::Emission) => LAYER_EMISSION,
        _ => LAYER_COLOR,
    };
    let mut layer = unit_layer(pass, 0, texture, role);
    if layer.role == LAYER_OFF {
        let mut env = 0;
        codes::FORMAT.set(&mut env, codes::FORMAT_RGBA);
        codes::ENV.set(&mut env, codes::ENV_MODULATE);
        layer = GpuLayer { env, role, ..layer };
    }
    let (alpha_func, alpha_ref) = pass.state.alpha_test.map_or((CompareFunc::Always as u32, 0.0), |(f, r)| (f as u32, r));
    GpuLayer {
        blend: blend_word(pass.state.blend.as_ref()),
        blend_color: pass.state.blend.map_or([0.0; 4], |b| b.color),
        alpha_func,
        alpha_ref,
        ..layer
    }
}

/// The `FACTOR_*` code of `f`.
fn factor_code(f: BlendFactor) -> u32 {
    match f {
        BlendFactor::Zero => FACTOR_ZERO,
        BlendFactor::One => FACTOR_ONE,
        BlendFactor::SrcColor => FACTOR_SRC_COLOR,
        BlendFactor::OneMinusSrcColor => FACTOR_ONE_MINUS_SRC_COLOR,
        BlendFactor::DstColor => FACTOR_DST_COLOR,
        BlendFactor::OneMinusDstColor => FACTOR_ONE_MINUS_DST_COLOR,
        BlendFactor::SrcAlpha => FACTOR_SRC_ALPHA,
        BlendFactor::OneMinusSrcAlpha => FACTOR_ONE_MINUS_SRC_ALPHA,
        BlendFactor::DstAlpha => FACTOR_DST_ALPHA,
        BlendFactor::OneMinusDstAlpha => FACTOR_ONE_MINUS_DST_ALPHA,
        BlendFactor::ConstantColor => FACTOR_CONSTANT_COLOR,
        BlendFactor::OneMinusConstantColor => FACTOR_ONE_MINUS_CONSTANT_COLOR,
        BlendFactor::ConstantAlpha => FACTOR_CONSTANT_ALPHA,
        BlendFactor::OneMinusConstantAlpha => FACTOR_ONE_MINUS_CONSTANT_ALPHA,
        BlendFactor::SrcAlphaSaturate => FACTOR_SRC_ALPHA_SATURATE,
    }
}

/// The `EQUATION_*` code of `e`.
fn equation_code(e: BlendEquation) -> u32 {
    match e {
        BlendEquation::Add => EQUATION_ADD,
        BlendEquation::Subtract => EQUATION_SUBTRACT,
        BlendEquation::ReverseSubtract => EQUATION_REVERSE_SUBTRACT,
        BlendEquation::Min => EQUATION_MIN,
        BlendEquation::Max => EQUATION_MAX,
    }
}

/// The blend word (`BLEND_*` fields) of `blend`; `None` (blending off) replaces: `GL_ONE`,
/// `GL_ZERO`, `GL_FUNC_ADD`.
pub fn blend_word(blend: Option<&Blend>) -> u32 {
    let b = blend.copied().unwrap_or_default();
    let mut w = 0;
    BLEND_SRC_RGB.set(&mut w, factor_code(b.src_rgb));
    BLEND_DST_RGB.set(&mut w, factor_code(b.dst_rgb));
    BLEND_SRC_ALPHA.set(&mut w, factor_code(b.src_alpha));
    BLEND_DST_ALPHA.set(&mut w, factor_code(b.dst_alpha));
    BLEND_EQUATION_RGB.set(&mut w, equation_code(b.equation_rgb));
    BLEND_EQUATION_ALPHA.set(&mut w, equation_code(b.equation_alpha));
    w
}

/// The material of `surface`, whose [`textures`] are `textures` in the texel pool; baked
/// surfaces are traced as `lightmaps` says. Its `layer_corners` (where its geometry's pass
/// corners are), `emitters` (its entries in the emitter list, [`NO_EMITTER`] here) and `key`
/// ([`key`], once the rest is set) are the caller's to set.
///
/// Lit draws take their specular reflectance from the GL material (0 for the default
/// material, so a default lit surface is Lambertian) and their roughness from its shininess
/// (Blinn-Phong exponent n to GGX alpha = sqrt(2 / (n + 2))); emission is the GL material's.
/// Roughness, metalness and emission otherwise come from the base's `glrt.toml` material
/// ([`crate::frame::class::MaterialOverride`], defaults included).
pub fn material(surface: &Surface, textures: [Option<u32>; MATERIAL_LAYERS], defaults: &MaterialDefaults, lightmaps: Lightmaps) -> GpuMaterial {
    let draw = surface.base;
    let instance = draw.instance.unwrap_or_default();
    let layer = |i: usize| match i.checked_sub(TRACED_UNITS) {
        None => unit_layer(draw, i, textures[i], if instance.light_units & (1 << i) != 0 { LAYER_BAKED_LIGHT } else { LAYER_COLOR }),
        Some(k) => surface.passes.get(k).map_or(GpuLayer { texture: NO_TEXTURE, role: LAYER_OFF, ..replacing() }, |p| pass_layer(p, textures[i])),
    };
    let layers: [GpuLayer; MATERIAL_LAYERS] = std::array::from_fn(layer);
    let has_lightmap = layers.iter().any(|l| l.role == LAYER_BAKED_LIGHT);
    let mut flags = 0;
    if instance.lighting == SurfaceLighting::Baked && lightmaps == Lightmaps::Keep {
        flags |= MATERIAL_BAKED;
    }
    let mut tint = Vec3::ONE;
    if instance.lighting == SurfaceLighting::VertexLit || (instance.lighting == SurfaceLighting::Baked && !has_lightmap) {
        flags |= MATERIAL_TINT_PRIMARY;
    }
    if instance.lighting == SurfaceLighting::VertexLit {
        flags |= MATERIAL_VERTEX_LIT;
        tint = vertex_light::tint(draw);
    }
    let over = instance.material;
    let (mut roughness, mut specular, mut emission) = (over.roughness, defaults.specular, [0.0; 4]);
    if let Some(l) = &draw.state.lighting {
        let s = l.front.specular;
        specular = 0.04 * s[0].max(s[1]).max(s[2]).clamp(0.0, 1.0);
        if specular > 0.0 {
            roughness = (2.0 / (l.front.shininess + 2.0)).sqrt().sqrt();
        }
        let e = l.front.emission;
        emission = [srgb_to_linear(e[0]), srgb_to_linear(e[1]), srgb_to_linear(e[2]), 0.0];
    }
    emission[3] = over.emissive.max(0.0);
    let (alpha_func, alpha_ref) = match draw.state.alpha_test {
        Some((func, reference)) if textures[..TRACED_UNITS].iter().any(Option::is_some) => (func as u32, reference),
        _ => (CompareFunc::Always as u32, 0.0),
    };
    GpuMaterial {
        emission,
        ambient: [0.0; 4],
        layer: layers,
        roughness,
        metalness: over.metalness.clamp(0.0, 1.0),
        specular,
        alpha_func,
        alpha_ref,
        flags,
        layer_corners: 0,
        passes: surface.passes.len().min(MAX_PASSES) as u32,
        emitters: NO_EMITTER,
        key: 0,
        tint: pack_unorm(tint),
        radiosity: NO_RADIOSITY,
    }
}

/// `v` (0..1) as `packUnorm4x8` packs it, alpha 1.
fn pack_unorm(v: Vec3) -> u32 {
    let byte = |x: f32| (x.clamp(0.0, 1.0) * 255.0).round() as u32;
    byte(v.x) | byte(v.y) << 8 | byte(v.z) << 16 | 255 << 24
}

/// A hash of what `m` shows: every field but those that say where its passes' corners,
/// emitter entries and radiosity records are (they move when the buffers are repacked or the
/// lists change), the
/// tint (a summary of the vertex colours, which change as a model moves and are not in the
/// key either) and the ambient light (light, not what the surface is).
pub fn key(m: &GpuMaterial) -> u32 {
    let shown = GpuMaterial { layer_corners: 0, emitters: 0, key: 0, tint: 0, radiosity: 0, ambient: [0.0; 4], ..*m };
    xxh3_64(bytemuck::bytes_of(&shown)) as u32
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::frame::class::{DrawClass, Instance, Layer};
    use crate::frame::state::Lighting;
    use crate::frame::texture::{CombineFn, CombineSource, EnvMode, TextureContent, TextureEnv};
    use crate::frame::{RasterState, TextureUnit};
    use crate::render::texenv::codes::{ENV, ENV_COMBINE, ENV_DECAL, FORMAT, FORMAT_LUMINANCE, SCALE};

    fn texture(id: u32) -> Option<TextureRef> {
        Some(TextureRef { id, version: 1, content: Arc::new(TextureContent::default()) })
    }

    /// A draw of class `class` textured with texture `id` on unit 0, environment `env`.
    fn textured(class: DrawClass, id: u32, env: TextureEnv) -> Draw {
        Draw {
            indices: vec![0, 1, 2],
            class,
            state: Arc::new(RasterState::default()),
            textures: vec![texture(id)],
            texture_units: vec![Some(TextureUnit { env, ..TextureUnit::default() })],
            ..Draw::default()
        }
    }

    /// A base textured on units 0 (texture 1) and 1 (texture 2, environment `env`), with
    /// `lighting` and `light_units`.
    fn base(env: TextureEnv, lighting: SurfaceLighting, light_units: u8) -> Draw {
        let mut draw = textured(DrawClass::Static, 1, TextureEnv::default());
        draw.textures.push(texture(2));
        draw.texture_units.push(Some(TextureUnit { env, ..TextureUnit::default() }));
        draw.instance = Some(Instance { lighting, light_units, ..Instance::default() });
        draw
    }

    /// A pass of `role` blending with `blend`.
    fn pass(role: LayerRole, blend: Option<Blend>) -> Draw {
        let mut draw = textured(DrawClass::Layer, 9, TextureEnv::default());
        draw.state = Arc::new(RasterState { blend, alpha_test: Some((CompareFunc::Greater, 0.25)), ..RasterState::default() });
        draw.layer = Some(Layer { base: 0, triangles: Arc::from([0u32]), role });
        draw
    }

    fn blend(src: BlendFactor, dst: BlendFactor) -> Blend {
        Blend { src_rgb: src, dst_rgb: dst, src_alpha: src, dst_alpha: dst, ..Blend::default() }
    }

    const ALL: [Option<u32>; MATERIAL_LAYERS] = [Some(4), Some(5), Some(6), Some(7), Some(8), Some(9)];

    #[test]
    fn units_holding_light_are_baked_light_layers() {
        let modulate = TextureEnv::default();
        let traced = base(modulate, SurfaceLighting::Traced, 0);
        let m = material(&Surface { base: &traced, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        assert_eq!(m.layer.map(|l| (l.texture, l.role)), [(4, LAYER_COLOR), (5, LAYER_COLOR), (NO_TEXTURE, LAYER_OFF), (NO_TEXTURE, LAYER_OFF), (NO_TEXTURE, LAYER_OFF), (NO_TEXTURE, LAYER_OFF)]);
        assert_eq!((m.flags, m.passes, m.emitters, m.specular), (0, 0, NO_EMITTER, 0.04));
        let lightmapped = base(modulate, SurfaceLighting::Baked, 0b10);
        let m = material(&Surface { base: &lightmapped, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        assert_eq!((m.layer[0].role, m.layer[1].role, m.flags), (LAYER_COLOR, LAYER_BAKED_LIGHT, MATERIAL_BAKED));
        let m = material(&Surface { base: &lightmapped, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Ignore);
        assert_eq!((m.layer[1].role, m.flags), (LAYER_BAKED_LIGHT, 0), "ignored: a reflector whose albedo leaves the lightmap out");
        let decal = base(TextureEnv { mode: EnvMode::Decal, ..modulate }, SurfaceLighting::Traced, 0);
        let m = material(&Surface { base: &decal, passes: Vec::new() }, [Some(4), None, None, None, None, None], &MaterialDefaults::default(), Lightmaps::Keep);
        assert_eq!((m.layer[1].texture, m.layer[1].role), (NO_TEXTURE, LAYER_OFF), "a unit without its texture in the pool is off");
        let m = material(&Surface { base: &decal, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        assert_eq!((m.layer[1].role, ENV.get(m.layer[1].env)), (LAYER_COLOR, ENV_DECAL));
        assert_eq!((m.layer[0].blend, m.layer[0].alpha_func), (blend_word(None), 7), "units replace, untested");
    }

    #[test]
    fn vertex_colours_that_are_light_leave_the_albedo() {
        let white = |lighting, light_units| {
            let draw = base(TextureEnv::default(), lighting, light_units);
            let m = material(&Surface { base: &draw, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
            assert_eq!(m.tint, u32::MAX, "no colours: white");
            m.flags & MATERIAL_TINT_PRIMARY != 0
        };
        assert!(white(SurfaceLighting::VertexLit, 0));
        assert!(white(SurfaceLighting::Baked, 0), "baked without a lightmap: into its vertex colours");
        assert!(!white(SurfaceLighting::Baked, 0b10));
        assert!(!white(SurfaceLighting::Traced, 0));
        // A lightmap pass makes a baked surface lightmapped too.
        let draw = base(TextureEnv::default(), SurfaceLighting::Baked, 0);
        let lightmap = pass(LayerRole::BakedLight, Some(blend(BlendFactor::DstColor, BlendFactor::Zero)));
        let m = material(&Surface { base: &draw, passes: vec![&lightmap] }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        assert_eq!(m.flags, MATERIAL_BAKED);
        // A vertex-lit model keeps its colours' hue; a surface baked into them does not.
        let mut model = base(TextureEnv::default(), SurfaceLighting::VertexLit, 0);
        model.vertices.position = vec![[0.0; 4]; 2];
        model.vertices.color.values = vec![[0.1, 0.4, 0.2, 1.0], [0.1, 0.6, 0.0, 1.0]];
        let m = material(&Surface { base: &model, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        assert_eq!((m.flags, m.tint), (MATERIAL_TINT_PRIMARY | MATERIAL_VERTEX_LIT, 0xff_33_ff_33), "(0.2, 1, 0.2)");
        model.instance = Some(Instance { lighting: SurfaceLighting::Baked, ..Instance::default() });
        let m = material(&Surface { base: &model, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        assert_eq!(m.tint, u32::MAX);
        assert_eq!(key(&m), key(&GpuMaterial { tint: 0xff_33_ff_33, ..m }), "the tint is not in the key");
        assert_eq!(key(&m), key(&GpuMaterial { ambient: [0.1, 0.2, 0.3, 2.0], ..m }), "nor the ambient light");
    }

    /// Each pass is a layer after the units: its unit 0, role, blend function and alpha test.
    #[test]
    fn passes_follow_the_units_with_their_blend_functions() {
        let draw = base(TextureEnv::default(), SurfaceLighting::Baked, 0);
        let lightmap = pass(LayerRole::BakedLight, Some(blend(BlendFactor::DstColor, BlendFactor::Zero)));
        let detail = pass(LayerRole::Albedo, Some(blend(BlendFactor::DstColor, BlendFactor::SrcColor)));
        let mut glow = pass(LayerRole::Emission, Some(Blend { color: [0.5, 0.25, 0.125, 1.0], equation_alpha: BlendEquation::Max, ..blend(BlendFactor::SrcAlpha, BlendFactor::One) }));
        glow.texture_units.clear();
        let decal = pass(LayerRole::Decal, None);
        let surface = Surface { base: &draw, passes: vec![&lightmap, &detail, &glow, &decal] };
        let m = material(&surface, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        assert_eq!(m.passes, 4);
        let passes = &m.layer[TRACED_UNITS..];
        assert_eq!(passes.iter().map(|l| (l.texture, l.role)).collect::<Vec<_>>(), [(6, LAYER_BAKED_LIGHT), (7, LAYER_COLOR), (NO_TEXTURE, LAYER_EMISSION), (9, LAYER_COLOR)]);
        let fields = |w: u32| [BLEND_SRC_RGB, BLEND_DST_RGB, BLEND_SRC_ALPHA, BLEND_DST_ALPHA, BLEND_EQUATION_RGB, BLEND_EQUATION_ALPHA].map(|f| f.get(w));
        assert_eq!(fields(passes[0].blend), [FACTOR_DST_COLOR, FACTOR_ZERO, FACTOR_DST_COLOR, FACTOR_ZERO, EQUATION_ADD, EQUATION_ADD]);
        assert_eq!(fields(passes[1].blend)[..2], [FACTOR_DST_COLOR, FACTOR_SRC_COLOR]);
        assert_eq!(fields(passes[2].blend), [FACTOR_SRC_ALPHA, FACTOR_ONE, FACTOR_SRC_ALPHA, FACTOR_ONE, EQUATION_ADD, EQUATION_MAX]);
        assert_eq!(passes[2].blend_color, [0.5, 0.25, 0.125, 1.0]);
        assert_eq!(fields(passes[3].blend), [FACTOR_ONE, FACTOR_ZERO, FACTOR_ONE, FACTOR_ZERO, EQUATION_ADD, EQUATION_ADD], "no blending: the pass replaces");
        assert_eq!((ENV.get(passes[2].env), FORMAT.get(passes[2].env)), (codes::ENV_MODULATE, codes::FORMAT_RGBA), "untextured: its primary colour");
        assert!(passes.iter().all(|l| (l.alpha_func, l.alpha_ref) == (CompareFunc::Greater as u32, 0.25)));
        // Textures: the units', then the passes' unit 0.
        let ids = textures(&surface).map(|t| t.map(|t| t.id));
        assert_eq!(ids, [Some(1), Some(2), Some(9), Some(9), None, Some(9)]);
    }

    /// A `GL_COMBINE` unit becomes a colour layer with the words `ff.frag` gets for it, its
    /// environment colour and its texture's base format; an overbright lightmap keeps its scale
    /// in its combiner word.
    #[test]
    fn combine_units_carry_the_raster_words() {
        let interpolate = TextureEnv {
            mode: EnvMode::Combine,
            combine_rgb: CombineFn::Interpolate,
            source_rgb: [CombineSource::Texture, CombineSource::Constant, CombineSource::PrimaryColor],
            color: [0.25, 0.5, 0.75, 1.0],
            scale: [1.0, 4.0],
            ..TextureEnv::default()
        };
        let mut draw = base(interpolate, SurfaceLighting::Traced, 0);
        let luminance = TextureContent { format: crate::frame::texture::TexelFormat::Luminance, ..TextureContent::default() };
        draw.textures[1] = Some(TextureRef { id: 2, version: 1, content: Arc::new(luminance) });
        let m = material(&Surface { base: &draw, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        let l = m.layer[1];
        let unit = draw.texture_units[1].expect("unit 1");
        assert_eq!([l.combine_rgb, l.combine_alpha], texenv::combine_words(&interpolate));
        assert_eq!((l.role, l.env_color, ENV.get(l.env), FORMAT.get(l.env)), (LAYER_COLOR, interpolate.color, ENV_COMBINE, FORMAT_LUMINANCE));
        assert_eq!(l.env, texenv::unit_bits(&unit, &draw.textures[1].as_ref().expect("texture").content));
        let overbright = TextureEnv {
            mode: EnvMode::Combine,
            combine_rgb: CombineFn::Modulate,
            source_rgb: [CombineSource::Previous, CombineSource::Texture, CombineSource::Constant],
            scale: [2.0, 1.0],
            ..TextureEnv::default()
        };
        let draw = base(overbright, SurfaceLighting::Baked, 0b10);
        let m = material(&Surface { base: &draw, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        assert_eq!((m.layer[1].role, SCALE.get(m.layer[1].combine_rgb)), (LAYER_BAKED_LIGHT, 1), "RGB_SCALE 2");
    }

    #[test]
    fn the_key_follows_what_the_material_shows() {
        let draw = base(TextureEnv::default(), SurfaceLighting::Traced, 0);
        let m = material(&Surface { base: &draw, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        let placed = GpuMaterial { layer_corners: 40, emitters: 3, radiosity: 7, ..m };
        assert_eq!(key(&m), key(&placed), "where its records are is not what it shows");
        let replaced = base(TextureEnv { mode: EnvMode::Replace, ..TextureEnv::default() }, SurfaceLighting::Traced, 0);
        let other = material(&Surface { base: &replaced, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        assert_ne!(key(&m), key(&other), "another texture environment");
        let retextured = material(&Surface { base: &draw, passes: Vec::new() }, [Some(4), Some(6), None, None, None, None], &MaterialDefaults::default(), Lightmaps::Keep);
        assert_ne!(key(&m), key(&retextured), "another texture");
    }

    #[test]
    fn default_lit_material_is_lambertian() {
        let mut draw = base(TextureEnv::default(), SurfaceLighting::Traced, 0);
        draw.state = Arc::new(RasterState { lighting: Some(Lighting::default()), alpha_test: Some((CompareFunc::Greater, 0.5)), ..RasterState::default() });
        let m = material(&Surface { base: &draw, passes: Vec::new() }, [None; MATERIAL_LAYERS], &MaterialDefaults::default(), Lightmaps::Keep);
        assert_eq!((m.specular, m.alpha_func), (0.0, 7), "untextured: no alpha test");
        let m = material(&Surface { base: &draw, passes: Vec::new() }, ALL, &MaterialDefaults::default(), Lightmaps::Keep);
        assert_eq!((m.alpha_func, m.alpha_ref), (CompareFunc::Greater as u32, 0.5));
    }
}
