//! What the path tracer takes from a [`Frame`]: the traced draws, each turned into a geometry
//! (object-space triangles and their shading attributes, cached on the GPU by
//! [`geometry_key`]), an instance (its modelview) and a material; the camera; the environment.
//!
//! GL state is interpreted here, on the CPU, once per draw: the base colour of a corner is
//! what OpenGL would feed the texture stage (the vertex colour, or the material's diffuse
//! colour when lighting is on without colour material), normals are kept only for lit draws
//! (unlit GL geometry has no meaningful normals: the geometric normal is used).
//!
//! **Materials are stacks of layers.** A material holds one [`GpuLayer`] per traced texture
//! unit: units 0 and 1 ([`TRACED_UNITS`]), the units whose coordinates the triangle corners
//! carry; units past 1 are left out. A layer is what `shaders/texenv.glsl`'s `tex_env` needs
//! to apply the unit (its texture in the texel pool, its unit and combiner words and
//! environment colour, [`crate::render::texenv`]) and a role. `shaders/trace/surface.glsl`
//! walks the layers in order: a [`LAYER_COLOR`] layer combines its texel with the colour so
//! far, starting from the primary colour, through the same `tex_env` that `ff.frag` calls per
//! enabled unit, so every GL 1.x environment (`REPLACE`, `MODULATE`, `DECAL`, `BLEND`, `ADD`,
//! and `COMBINE` with its functions, sources including other units' texels, operands and
//! scales) gives the traced surface the raster colour as its albedo; a [`LAYER_BAKED_LIGHT`]
//! layer is a kept lightmap (below); [`LAYER_OFF`] layers are skipped.
//!
//! Multi-pass surfaces (a base pass, then lightmap, detail and glow passes over the same
//! triangles) extend the stack without a second evaluator: each later pass becomes one more
//! layer whose combiner words state its framebuffer blend with the layers below as a combine
//! of `PREVIOUS` and its texture: (`DST_COLOR`, `ZERO`) is `MODULATE`, a detail pass
//! (`DST_COLOR`, `SRC_COLOR`) is `MODULATE` with `RGB_SCALE` 2, (`SRC_ALPHA`,
//! `ONE_MINUS_SRC_ALPHA`) is `INTERPOLATE` by the texture's alpha. A lightmap pass takes the
//! role [`LAYER_BAKED_LIGHT`] as a lightmap unit does; an additive (`ONE`, `ONE`) pass takes a
//! new emission role whose result adds to the emitted radiance instead of the albedo; the
//! layer array grows, and each layer names the coordinate set of its pass.
//!
//! **Lightmaps** (unit 1 multiplying the result of unit 0, [`is_lightmap`]) hold light the
//! game baked: direct and indirect, everything that arrives at the surface. Tracing computes
//! that light itself, so counting both would count it twice. With [`Lightmaps::Ignore`] (the
//! default) unit 1 is left out ([`LAYER_OFF`]) and the surface is an ordinary reflector of
//! traced light. With
//! [`Lightmaps::Keep`] a lightmapped surface is a *baked* surface, as in RTX Remix or Quake 2
//! RTX's lightmapped mode: the lightmap is taken as its irradiance `E = π · L_map` (`L_map`
//! the texel decoded from display encoding after GL's `RGB_SCALE`, so a white lightmap texel
//! is the irradiance of a white GL light at normal incidence, lights.rs), and a Lambertian
//! surface of albedo `a` under it sends `a / π · E = a · L_map` towards every direction. The
//! tracer makes that its **emitted** radiance and lets it reflect **no traced light** (no
//! light sampling, no continuation ray: a path ends on it), for camera rays and bounces
//! alike. Each baked surface's light is then counted once, from the lightmap: the camera sees
//! what the raster game shows (linear `a · L_map`, the encoded raster product where GL does
//! not clamp), and surfaces without a lightmap (models, movers) receive the baked world's
//! light as bounce light, which their traced light does not already hold. The lightmap's
//! alpha is not used (lightmaps are RGB), and baked surfaces have no specular reflection.

use glam::{Mat4, Vec3, Vec4};
use xxhash_rust::xxh3::Xxh3;

use super::gpu_types::{GpuCorner, GpuLayer, GpuMaterial, GpuTriangleAttributes};
use super::settings::Lightmaps;
use super::shader_constants::{LAYER_BAKED_LIGHT, LAYER_COLOR, LAYER_OFF, NO_TEXTURE, TRACED_UNITS};
use crate::frame::state::{ColorMaterialMode, CompareFunc, Lighting};
use crate::frame::texture::{CombineFn, CombineOperand, CombineSource, EnvMode, TextureRef};
use crate::frame::{Draw, Frame, Framebuffer, Topology, TextureUnit};
use crate::render::texenv;

/// Whether `draw` is traced: a triangle draw of a traced class into the window's framebuffer,
/// run by the fixed-function pipeline (a GLSL program's output cannot be traced: those draws
/// are rasterized over the traced image like translucent ones).
pub fn is_traced(draw: &Draw) -> bool {
    draw.class.is_traced()
        && draw.topology == Topology::Triangles
        && draw.program.is_none()
        && draw.state.framebuffer == Framebuffer::default()
        && !draw.indices.is_empty()
}

/// Index of the first traced draw of `frame`: where the traced image is composited, so that
/// draws before it (sky) are behind it and draws after it (glass, HUD) over it.
pub fn first_traced(frame: &Frame) -> Option<usize> {
    frame.draws.iter().position(is_traced)
}

/// The colour of the frame's first colour clear of the window (GL values): the environment
/// of missed rays, or where the sky draws' environment starts ([`super::sky`]).
pub fn clear_color(frame: &Frame) -> Option<[f32; 4]> {
    frame.clears.iter().filter(|c| c.framebuffer == Framebuffer::default()).find_map(|c| c.color)
}

/// The key the GPU geometry cache stores a draw's geometry under: everything
/// [`geometry`] reads (positions, indices, texture coordinates of units 0 and 1 after their
/// texture matrices, base colours, normals when lit). The instance's key (hash tracking)
/// covers unit 0's coordinates only, so unit 1's are hashed here.
pub fn geometry_key(draw: &Draw) -> u64 {
    let mut h = Xxh3::new();
    h.update(&draw.instance.map_or(0, |i| i.geometry_key).to_le_bytes());
    if draw.instance.is_none() {
        h.update(bytemuck::cast_slice(&draw.vertices.position));
        h.update(bytemuck::cast_slice(&draw.indices));
        if let Some(t) = draw.vertices.texcoords.first() {
            h.update(bytemuck::cast_slice(&t.values));
        }
    }
    h.update(bytemuck::cast_slice(&draw.vertices.color.values));
    if let Some(lighting) = &draw.state.lighting {
        h.update(bytemuck::cast_slice(&draw.vertices.normal.values));
        h.update(bytemuck::cast_slice(&lighting.front.diffuse));
        h.update(&[u8::from(tracks_diffuse(lighting))]);
    }
    if let Some(m) = texture_matrix(draw, 0) {
        h.update(bytemuck::cast_slice(&m.to_cols_array()));
    }
    if enabled(draw, LIGHTMAP_UNIT) {
        h.update(&[1]);
        if let Some(t) = draw.vertices.texcoords.get(LIGHTMAP_UNIT) {
            h.update(bytemuck::cast_slice(&t.values));
        }
        if let Some(m) = texture_matrix(draw, LIGHTMAP_UNIT) {
            h.update(bytemuck::cast_slice(&m.to_cols_array()));
        }
    }
    h.digest()
}

/// The texture unit a lightmap is bound to.
const LIGHTMAP_UNIT: usize = 1;

/// Whether texture unit `unit` of `draw` has a target enabled.
fn enabled(draw: &Draw, unit: usize) -> bool {
    draw.texture_units.get(unit).is_some_and(Option::is_some)
}

/// Whether a unit multiplies the previous unit's result by its texture (OpenGL 1.3 section
/// 3.8.13: unit 1 combines with unit 0's result), as a lightmap does: `MODULATE`, or a
/// `COMBINE` whose RGB function is `MODULATE` of `PREVIOUS` and `TEXTURE` colours, with any
/// `RGB_SCALE` (the usual "overbright" lightmap; the baked light is the texel times that
/// scale). Every other environment on unit 1 (`REPLACE`, `DECAL`, `BLEND`, `ADD`, other
/// combiners: decals, detail, glow and environment maps) is a colour layer.
pub fn is_lightmap(unit: &TextureUnit) -> bool {
    let env = &unit.env;
    match env.mode {
        EnvMode::Modulate => true,
        EnvMode::Combine => {
            let [a, b, _] = env.source_rgb;
            let sources = matches!((a, b), (CombineSource::Previous, CombineSource::Texture) | (CombineSource::Texture, CombineSource::Previous));
            let colours = env.operand_rgb[..2].iter().all(|&o| o == CombineOperand::SrcColor);
            env.combine_rgb == CombineFn::Modulate && sources && colours
        }
        _ => false,
    }
}

/// The textures the tracer samples for `draw`, per traced unit: the unit's texture when a
/// target is enabled there, but for a lightmap on unit 1 that `lightmaps` does not keep
/// ([`traces_second_unit`]).
pub fn traced_textures(draw: &Draw, lightmaps: Lightmaps) -> [Option<&TextureRef>; TRACED_UNITS] {
    let texture = |unit: usize| draw.textures.get(unit).and_then(Option::as_ref).filter(|_| enabled(draw, unit));
    let kept = |unit: usize| unit != LIGHTMAP_UNIT || draw.texture_units.get(unit).copied().flatten().is_some_and(|u| traces_second_unit(&u, lightmaps));
    std::array::from_fn(|unit| texture(unit).filter(|_| kept(unit)))
}

/// Whether unit 1, enabled with a texture and the environment of `unit`, is traced: as a
/// colour layer, or as a lightmap ([`is_lightmap`]) when `lightmaps` keeps them.
pub fn traces_second_unit(unit: &TextureUnit, lightmaps: Lightmaps) -> bool {
    lightmaps == Lightmaps::Keep || !is_lightmap(unit)
}

/// Whether the lit base colour follows the vertex colour (`glColorMaterial` on diffuse).
fn tracks_diffuse(lighting: &Lighting) -> bool {
    lighting.color_material.is_some_and(|c| matches!(c.mode, ColorMaterialMode::Diffuse | ColorMaterialMode::AmbientAndDiffuse))
}

/// Unit `unit`'s texture matrix when the unit is enabled and it is not the identity.
fn texture_matrix(draw: &Draw, unit: usize) -> Option<Mat4> {
    draw.texture_matrices.get(unit).copied().flatten().filter(|m| *m != Mat4::IDENTITY)
}

/// Vertex `i`'s texture coordinates of `unit` after the unit's texture `matrix`, divided by q;
/// zero when the unit is not enabled.
fn texcoord(draw: &Draw, unit: usize, matrix: Option<Mat4>, i: usize) -> [f32; 2] {
    if !enabled(draw, unit) {
        return [0.0; 2];
    }
    let t = draw.vertices.texcoords.get(unit).and_then(|t| t.get(i)).unwrap_or([0.0, 0.0, 0.0, 1.0]);
    let t = matrix.map_or(Vec4::from_array(t), |m| m * Vec4::from_array(t));
    let q = if t.w != 0.0 { t.w } else { 1.0 };
    [t.x / q, t.y / q]
}

/// The geometry of a traced draw in object space: one entry per triangle.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Geometry {
    /// Corner positions (divided by w).
    pub triangles: Vec<[Vec3; 3]>,
    /// Shading attributes, in the order of `triangles`.
    pub attributes: Vec<GpuTriangleAttributes>,
}

/// Builds the geometry of `draw` (see the module doc for what each attribute holds).
pub fn geometry(draw: &Draw) -> Geometry {
    let v = &draw.vertices;
    let lit = draw.state.lighting.as_ref();
    let diffuse = lit.filter(|l| !tracks_diffuse(l)).map(|l| l.front.diffuse);
    let matrices: [Option<Mat4>; TRACED_UNITS] = std::array::from_fn(|unit| texture_matrix(draw, unit));
    let corner = |i: u32| -> ([f32; 4], GpuCorner) {
        let i = i as usize;
        let p = v.position.get(i).copied().unwrap_or([0.0, 0.0, 0.0, 1.0]);
        let color = diffuse.or_else(|| v.color.get(i)).unwrap_or([1.0; 4]);
        let normal = match (lit, v.normal.get(i)) {
            (Some(_), Some(n)) => pack_normal(Vec3::from_array(n)),
            _ => 0,
        };
        let uv = std::array::from_fn(|unit| texcoord(draw, unit, matrices[unit], i));
        (p, GpuCorner { uv, normal, color: pack_unorm8(color) })
    };
    let mut geometry = Geometry::default();
    for tri in draw.indices.chunks_exact(3) {
        let [(p0, c0), (p1, c1), (p2, c2)] = [corner(tri[0]), corner(tri[1]), corner(tri[2])];
        geometry.triangles.push([p0, p1, p2].map(|p| {
            let w = if p[3] != 0.0 { p[3] } else { 1.0 };
            Vec3::new(p[0] / w, p[1] / w, p[2] / w)
        }));
        geometry.attributes.push(GpuTriangleAttributes { corner: [c0, c1, c2] });
    }
    geometry
}

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

/// The material of a traced draw whose [`traced_textures`] are `textures` in the texel pool.
///
/// Each traced unit with a texture is a layer (see the module doc): [`LAYER_BAKED_LIGHT`] for a
/// kept lightmap, [`LAYER_COLOR`] otherwise. Lit draws take their specular reflectance from
/// the GL material (0 for the default material, so a default lit surface is Lambertian) and
/// their roughness from its shininess (Blinn-Phong exponent n to GGX alpha = sqrt(2 / (n +
/// 2))); emission is the GL material's. Roughness, metalness and emission otherwise come from
/// the draw's `glrt.toml` material ([`crate::frame::class::MaterialOverride`], defaults
/// included).
pub fn material(draw: &Draw, textures: [Option<u32>; TRACED_UNITS], defaults: &MaterialDefaults) -> GpuMaterial {
    let layer = |unit: usize| {
        let env = draw.texture_units.get(unit).copied().flatten();
        let content = draw.textures.get(unit).and_then(Option::as_ref).map(|t| &t.content);
        let (Some(texture), Some(env), Some(content)) = (textures[unit], env, content) else {
            return GpuLayer { texture: NO_TEXTURE, role: LAYER_OFF, ..GpuLayer::default() };
        };
        let [combine_rgb, combine_alpha] = texenv::combine_words(&env.env);
        let baked = unit == LIGHTMAP_UNIT && is_lightmap(&env);
        GpuLayer {
            env_color: env.env.color,
            texture,
            env: texenv::unit_bits(&env, content),
            combine_rgb,
            combine_alpha,
            role: if baked { LAYER_BAKED_LIGHT } else { LAYER_COLOR },
            pad: [0; 3],
        }
    };
    let over = draw.instance.map(|i| i.material).unwrap_or_default();
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
        Some((func, reference)) if textures.iter().any(Option::is_some) => (func as u32, reference),
        _ => (CompareFunc::Always as u32, 0.0),
    };
    GpuMaterial {
        emission,
        layer: std::array::from_fn(layer),
        roughness,
        metalness: over.metalness.clamp(0.0, 1.0),
        specular,
        alpha_func,
        alpha_ref,
        pad: [0; 3],
    }
}

/// The linear value of a display-encoded (sRGB) component.
pub fn srgb_to_linear(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// `packUnorm4x8`.
pub fn pack_unorm8(c: [f32; 4]) -> u32 {
    c.iter().enumerate().fold(0, |acc, (i, v)| acc | (((v.clamp(0.0, 1.0) * 255.0).round() as u32) << (8 * i)))
}

/// `pack_normal` of `shaders/trace/pack.glsl`: octahedral snorm16x2; 0 for a zero vector
/// (which the shaders read as "no normal").
pub fn pack_normal(n: Vec3) -> u32 {
    let sum = n.x.abs() + n.y.abs() + n.z.abs();
    if sum.is_nan() || sum <= 0.0 || sum.is_infinite() {
        return 0;
    }
    let n = n / sum;
    let (x, y) = if n.z >= 0.0 {
        (n.x, n.y)
    } else {
        let sign = |v: f32| if v >= 0.0 { 1.0 } else { -1.0 };
        ((1.0 - n.y.abs()) * sign(n.x), (1.0 - n.x.abs()) * sign(n.y))
    };
    let snorm = |v: f32| ((v.clamp(-1.0, 1.0) * 32767.0).round() as i16) as u16 as u32;
    let packed = snorm(x) | (snorm(y) << 16);
    // A normal that packs to 0 ((0, 0, +1) does) is nudged so that 0 keeps meaning "none".
    if packed == 0 { 1 } else { packed }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::class::DrawClass;
    use crate::frame::texture::{TextureContent, TextureEnv};
    use crate::render::texenv::codes::{ENV, ENV_COMBINE, ENV_DECAL, FORMAT, FORMAT_LUMINANCE, SCALE};
    use crate::frame::{Attrib, RasterState, Vertices};
    use std::sync::Arc;

    fn quad(class: DrawClass) -> Draw {
        Draw {
            vertex_count: 4,
            vertices: Vertices {
                position: vec![[0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0], [1.0, 1.0, 0.0, 1.0], [0.0, 2.0, 0.0, 2.0]],
                color: Attrib { values: vec![[1.0, 0.5, 0.0, 1.0]] },
                normal: Attrib { values: vec![[0.0, 0.0, 1.0]] },
                ..Vertices::default()
            },
            indices: vec![0, 1, 2, 0, 2, 3],
            class,
            state: Arc::new(RasterState::default()),
            ..Draw::default()
        }
    }

    #[test]
    fn traced_draws_are_opaque_classes_of_triangles() {
        assert!(is_traced(&quad(DrawClass::Static)));
        assert!(!is_traced(&quad(DrawClass::Translucent)));
        let frame = Frame { draws: vec![quad(DrawClass::Sky), quad(DrawClass::Movable), quad(DrawClass::Overlay)], ..Frame::default() };
        assert_eq!(first_traced(&frame), Some(1));
    }

    #[test]
    fn geometry_divides_by_w_and_keeps_unlit_colours_without_normals() {
        let g = geometry(&quad(DrawClass::Static));
        assert_eq!(g.triangles.len(), 2);
        assert_eq!(g.triangles[1][2], Vec3::new(0.0, 1.0, 0.0));
        assert_eq!(g.attributes[0].corner[1].color, pack_unorm8([1.0, 0.5, 0.0, 1.0]));
        assert_eq!(g.attributes[0].corner[0].normal, 0, "unlit draws use the geometric normal");
    }

    #[test]
    fn lit_geometry_takes_the_material_diffuse_and_normals() {
        let mut draw = quad(DrawClass::Static);
        let mut lighting = Lighting::default();
        lighting.front.diffuse = [0.25, 0.5, 0.75, 1.0];
        draw.state = Arc::new(RasterState { lighting: Some(lighting), ..RasterState::default() });
        let g = geometry(&draw);
        assert_eq!(g.attributes[0].corner[0].color, pack_unorm8([0.25, 0.5, 0.75, 1.0]));
        assert_ne!(g.attributes[0].corner[0].normal, 0);
        assert_ne!(geometry_key(&draw), geometry_key(&quad(DrawClass::Static)));
    }

    #[test]
    fn default_lit_material_is_lambertian() {
        let mut draw = quad(DrawClass::Static);
        draw.state = Arc::new(RasterState { lighting: Some(Lighting::default()), ..RasterState::default() });
        let m = material(&draw, [None; 2], &MaterialDefaults::default());
        assert_eq!((m.specular, m.alpha_func), (0.0, 7));
        assert!(m.layer.iter().all(|l| (l.texture, l.role) == (NO_TEXTURE, LAYER_OFF)), "{:?}", m.layer);
        let unlit = material(&lightmapped(TextureEnv::default()), [Some(3), None], &MaterialDefaults::default());
        assert_eq!((unlit.specular, unlit.layer[0].texture, unlit.layer[0].role), (0.04, 3, LAYER_COLOR));
        assert_eq!(unlit.layer[1].role, LAYER_OFF, "unit 1's texture is not traced");
    }

    /// `quad` textured on unit 0 and with texture 2 on unit 1 of environment `env`; unit 1's
    /// coordinates are the positions' x, y, through a texture matrix halving s.
    fn lightmapped(env: TextureEnv) -> Draw {
        let mut draw = quad(DrawClass::Static);
        let texture = |id| Some(TextureRef { id, version: 1, content: Arc::new(TextureContent::default()) });
        draw.textures = vec![texture(1), texture(2)];
        draw.texture_units = vec![Some(TextureUnit::default()), Some(TextureUnit { env, ..TextureUnit::default() })];
        draw.texture_matrices = vec![Some(Mat4::IDENTITY), Some(Mat4::from_scale(Vec3::new(0.5, 1.0, 1.0)))];
        let lightmap_uv = draw.vertices.position.iter().map(|p| [p[0], p[1], 0.0, p[3]]).collect();
        draw.vertices.texcoords = vec![Attrib { values: vec![[0.25, 0.75, 0.0, 1.0]] }, Attrib { values: lightmap_uv }];
        draw
    }

    #[test]
    fn modulating_units_are_lightmaps() {
        let modulate = TextureEnv::default();
        assert!(is_lightmap(&TextureUnit { env: modulate, ..TextureUnit::default() }));
        let overbright = TextureEnv {
            mode: EnvMode::Combine,
            combine_rgb: CombineFn::Modulate,
            source_rgb: [CombineSource::Texture, CombineSource::Previous, CombineSource::Constant],
            scale: [2.0, 1.0],
            ..TextureEnv::default()
        };
        assert!(is_lightmap(&TextureUnit { env: overbright, ..TextureUnit::default() }));
        let not_lightmaps = [
            TextureEnv { mode: EnvMode::Decal, ..modulate },
            TextureEnv { mode: EnvMode::Add, ..modulate },
            TextureEnv { mode: EnvMode::Replace, ..modulate },
            TextureEnv { mode: EnvMode::Blend, ..modulate },
            TextureEnv { combine_rgb: CombineFn::Add, ..overbright },
            TextureEnv { source_rgb: [CombineSource::Texture, CombineSource::PrimaryColor, CombineSource::Constant], ..overbright },
            TextureEnv { operand_rgb: [CombineOperand::SrcColor, CombineOperand::OneMinusSrcColor, CombineOperand::SrcColor], ..overbright },
        ];
        for env in not_lightmaps {
            assert!(!is_lightmap(&TextureUnit { env, ..TextureUnit::default() }), "{env:?}");
        }
    }

    #[test]
    fn kept_lightmaps_are_sampled_with_unit_1_coordinates() {
        let draw = lightmapped(TextureEnv::default());
        let ids = |t: [Option<&TextureRef>; 2]| t.map(|t| t.map(|t| t.id));
        assert_eq!(ids(traced_textures(&draw, Lightmaps::Ignore)), [Some(1), None]);
        assert_eq!(ids(traced_textures(&draw, Lightmaps::Keep)), [Some(1), Some(2)]);
        let decal = lightmapped(TextureEnv { mode: EnvMode::Decal, ..TextureEnv::default() });
        for lightmaps in [Lightmaps::Ignore, Lightmaps::Keep] {
            assert_eq!(ids(traced_textures(&decal, lightmaps)), [Some(1), Some(2)], "a decal on unit 1 is a colour layer");
        }
        let mut disabled = draw.clone();
        disabled.texture_units[1] = None;
        assert_eq!(ids(traced_textures(&disabled, Lightmaps::Keep)), [Some(1), None]);

        // Unit 1's coordinates after its texture matrix (s halved), divided by q; unit 0's too.
        let g = geometry(&draw);
        assert_eq!(g.attributes[0].corner.map(|c| c.uv[1]), [[0.0, 0.0], [0.5, 0.0], [0.5, 1.0]]);
        assert_eq!(g.attributes[1].corner[2].uv[1], [0.0, 1.0], "(0, 2, 0, 2) divided by q");
        assert_eq!(g.attributes[0].corner[0].uv[0], [0.25, 0.75]);
        assert_eq!(geometry(&disabled).attributes[0].corner[1].uv[1], [0.0, 0.0]);
        // The key sees unit 1's coordinates and matrix, and whether the unit is on.
        let mut moved = draw.clone();
        moved.vertices.texcoords[1].values[1][0] = 0.75;
        let mut scaled = draw.clone();
        scaled.texture_matrices[1] = Some(Mat4::IDENTITY);
        let keys = [&draw, &moved, &scaled, &disabled].map(geometry_key);
        assert!(keys.iter().enumerate().all(|(i, k)| keys[i + 1..].iter().all(|o| o != k)), "{keys:?}");

        let m = material(&draw, [Some(4), Some(5)], &MaterialDefaults::default());
        assert_eq!(m.layer.map(|l| (l.texture, l.role)), [(4, LAYER_COLOR), (5, LAYER_BAKED_LIGHT)]);
        let m = material(&decal, [Some(4), Some(5)], &MaterialDefaults::default());
        assert_eq!(m.layer.map(|l| (l.texture, l.role)), [(4, LAYER_COLOR), (5, LAYER_COLOR)]);
        assert_eq!(ENV.get(m.layer[1].env), ENV_DECAL);
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
        let mut draw = lightmapped(interpolate);
        let luminance = TextureContent { format: crate::frame::texture::TexelFormat::Luminance, ..TextureContent::default() };
        draw.textures[1] = Some(TextureRef { id: 2, version: 1, content: Arc::new(luminance) });
        let m = material(&draw, [Some(4), Some(5)], &MaterialDefaults::default());
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
        let m = material(&lightmapped(overbright), [Some(4), Some(5)], &MaterialDefaults::default());
        assert_eq!((m.layer[1].role, SCALE.get(m.layer[1].combine_rgb)), (LAYER_BAKED_LIGHT, 1), "RGB_SCALE 2");
    }

    #[test]
    fn normals_pack_as_the_shader_unpacks_them() {
        for n in [Vec3::X, -Vec3::Y, Vec3::new(0.3, -0.5, -0.8).normalize()] {
            let p = pack_normal(n);
            let e = [(p & 0xffff) as u16 as i16, (p >> 16) as u16 as i16].map(|v| (v as f32 / 32767.0).max(-1.0));
            let mut d = Vec3::new(e[0], e[1], 1.0 - e[0].abs() - e[1].abs());
            if d.z < 0.0 {
                let sign = |v: f32| if v >= 0.0 { 1.0 } else { -1.0 };
                d = Vec3::new((1.0 - d.y.abs()) * sign(d.x), (1.0 - d.x.abs()) * sign(d.y), d.z);
            }
            assert!(d.normalize().dot(n) > 0.9999, "{n} -> {d}");
        }
        assert_eq!(pack_normal(Vec3::ZERO), 0);
    }
}
