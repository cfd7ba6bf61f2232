//! What the path tracer takes from a [`Frame`]: the traced draws, each turned into a geometry
//! (object-space triangles and their shading attributes, cached on the GPU by
//! [`geometry_key`]), an instance (its modelview) and a material; the camera; the environment.
//!
//! GL state is interpreted here, on the CPU, once per draw: the base colour of a corner is
//! what OpenGL would feed the texture stage (the vertex colour, or the material's diffuse
//! colour when lighting is on without colour material), normals are kept only for lit draws
//! (unlit GL geometry has no meaningful normals: the geometric normal is used), texture unit
//! 0 is the albedo texture. Units past 1 (detail textures and the like) are left out.
//!
//! **Lightmaps** (unit 1 multiplying the result of unit 0, [`lightmap_scale`]) hold light the
//! game baked: direct and indirect, everything that arrives at the surface. Tracing computes
//! that light itself, so counting both would count it twice. With [`Lightmaps::Ignore`] (the
//! default) unit 1 is left out and the surface is an ordinary reflector of traced light. With
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

use super::gpu_types::{GpuCorner, GpuMaterial, GpuTriangleAttributes};
use super::shader_constants::NO_TEXTURE;
use super::settings::Lightmaps;
use crate::frame::state::{ColorMaterialMode, CompareFunc, Lighting};
use crate::frame::texture::{CombineFn, CombineOperand, CombineSource, EnvMode, TextureRef};
use crate::frame::{Draw, Frame, Framebuffer, Topology, TextureUnit};

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

/// The scale a unit applies to its texture when it multiplies the previous unit's result by
/// it (OpenGL 1.3 section 3.8.13: unit 1 combines with unit 0's result): 1 for `MODULATE`;
/// `RGB_SCALE` for a `COMBINE` whose RGB function is `MODULATE` of `PREVIOUS` and `TEXTURE`
/// colours (the usual "overbright" lightmap). `None` for every other environment: `REPLACE`,
/// `DECAL`, `BLEND`, `ADD` or other combiners on unit 1 are not lightmaps (decals, detail,
/// glow and environment maps) and are left out like the units past 1.
pub fn lightmap_scale(unit: &TextureUnit) -> Option<f32> {
    let env = &unit.env;
    match env.mode {
        EnvMode::Modulate => Some(1.0),
        EnvMode::Combine => {
            let [a, b, _] = env.source_rgb;
            let sources = matches!((a, b), (CombineSource::Previous, CombineSource::Texture) | (CombineSource::Texture, CombineSource::Previous));
            let colours = env.operand_rgb[..2].iter().all(|&o| o == CombineOperand::SrcColor);
            (env.combine_rgb == CombineFn::Modulate && sources && colours).then_some(env.scale[0])
        }
        _ => None,
    }
}

/// The textures the tracer samples for `draw`: unit 0's when a target is enabled there
/// (the albedo), and unit 1's when it is a lightmap ([`lightmap_scale`]) kept by `lightmaps`.
pub fn traced_textures(draw: &Draw, lightmaps: Lightmaps) -> [Option<&TextureRef>; 2] {
    let texture = |unit: usize| draw.textures.get(unit).and_then(Option::as_ref).filter(|_| enabled(draw, unit));
    let lightmap = texture(LIGHTMAP_UNIT).filter(|_| lightmaps == Lightmaps::Keep && lightmap_unit(draw).is_some());
    [texture(0), lightmap]
}

/// The scale of unit 1 when it is enabled and multiplies unit 0's result ([`lightmap_scale`]).
fn lightmap_unit(draw: &Draw) -> Option<f32> {
    draw.texture_units.get(LIGHTMAP_UNIT).copied().flatten().and_then(|u| lightmap_scale(&u))
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
    let matrices = [texture_matrix(draw, 0), texture_matrix(draw, LIGHTMAP_UNIT)];
    let corner = |i: u32| -> ([f32; 4], GpuCorner) {
        let i = i as usize;
        let p = v.position.get(i).copied().unwrap_or([0.0, 0.0, 0.0, 1.0]);
        let color = diffuse.or_else(|| v.color.get(i)).unwrap_or([1.0; 4]);
        let normal = match (lit, v.normal.get(i)) {
            (Some(_), Some(n)) => pack_normal(Vec3::from_array(n)),
            _ => 0,
        };
        let uv = texcoord(draw, 0, matrices[0], i);
        let lightmap_uv = texcoord(draw, LIGHTMAP_UNIT, matrices[1], i);
        (p, GpuCorner { uv, normal, color: pack_unorm8(color), lightmap_uv })
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

/// The material of a traced draw whose [`traced_textures`] are `textures` in the texel pool
/// (unit 0's, and a kept lightmap).
///
/// Lit draws take their specular reflectance from the GL material (0 for the default
/// material, so a default lit surface is Lambertian) and their roughness from its shininess
/// (Blinn-Phong exponent n to GGX alpha = sqrt(2 / (n + 2))); emission is the GL material's.
/// Roughness, metalness and emission otherwise come from the draw's `glrt.toml` material
/// ([`crate::frame::class::MaterialOverride`], defaults included).
pub fn material(draw: &Draw, textures: [Option<u32>; 2], defaults: &MaterialDefaults) -> GpuMaterial {
    let [texture, lightmap] = textures;
    let unit = draw.texture_units.first().copied().flatten();
    let lightmap = lightmap.zip(lightmap_unit(draw));
    let texenv = match unit.map(|u| u.env.mode) {
        Some(EnvMode::Replace) => 1,
        Some(EnvMode::Decal) => 2,
        Some(EnvMode::Blend) => 3,
        Some(EnvMode::Add) => 4,
        _ => 0,
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
        Some((func, reference)) if texture.is_some() => (func as u32, reference),
        _ => (CompareFunc::Always as u32, 0.0),
    };
    GpuMaterial {
        emission,
        env_color: unit.map_or([0.0; 4], |u| u.env.color),
        texture: texture.unwrap_or(NO_TEXTURE),
        texenv,
        roughness,
        metalness: over.metalness.clamp(0.0, 1.0),
        specular,
        alpha_func,
        alpha_ref,
        lightmap: lightmap.map_or(NO_TEXTURE, |(index, _)| index),
        lightmap_scale: lightmap.map_or(0.0, |(_, scale)| scale),
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
        assert_eq!((m.specular, m.texture, m.alpha_func, m.lightmap), (0.0, NO_TEXTURE, 7, NO_TEXTURE));
        let unlit = material(&quad(DrawClass::Static), [Some(3), None], &MaterialDefaults::default());
        assert_eq!((unlit.specular, unlit.texture), (0.04, 3));
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
    fn modulating_units_are_lightmaps_with_their_scale() {
        let modulate = TextureEnv::default();
        assert_eq!(lightmap_scale(&TextureUnit { env: modulate, ..TextureUnit::default() }), Some(1.0));
        let overbright = TextureEnv {
            mode: EnvMode::Combine,
            combine_rgb: CombineFn::Modulate,
            source_rgb: [CombineSource::Texture, CombineSource::Previous, CombineSource::Constant],
            scale: [2.0, 1.0],
            ..TextureEnv::default()
        };
        assert_eq!(lightmap_scale(&TextureUnit { env: overbright, ..TextureUnit::default() }), Some(2.0));
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
            assert_eq!(lightmap_scale(&TextureUnit { env, ..TextureUnit::default() }), None, "{env:?}");
        }
    }

    #[test]
    fn kept_lightmaps_are_sampled_with_unit_1_coordinates() {
        let draw = lightmapped(TextureEnv::default());
        let ids = |t: [Option<&TextureRef>; 2]| t.map(|t| t.map(|t| t.id));
        assert_eq!(ids(traced_textures(&draw, Lightmaps::Ignore)), [Some(1), None]);
        assert_eq!(ids(traced_textures(&draw, Lightmaps::Keep)), [Some(1), Some(2)]);
        let decal = lightmapped(TextureEnv { mode: EnvMode::Decal, ..TextureEnv::default() });
        assert_eq!(ids(traced_textures(&decal, Lightmaps::Keep)), [Some(1), None], "a decal on unit 1 is not a lightmap");
        let mut disabled = draw.clone();
        disabled.texture_units[1] = None;
        assert_eq!(ids(traced_textures(&disabled, Lightmaps::Keep)), [Some(1), None]);

        // Unit 1's coordinates after its texture matrix (s halved), divided by q; unit 0's too.
        let g = geometry(&draw);
        assert_eq!(g.attributes[0].corner.map(|c| c.lightmap_uv), [[0.0, 0.0], [0.5, 0.0], [0.5, 1.0]]);
        assert_eq!(g.attributes[1].corner[2].lightmap_uv, [0.0, 1.0], "(0, 2, 0, 2) divided by q");
        assert_eq!(g.attributes[0].corner[0].uv, [0.25, 0.75]);
        assert_eq!(geometry(&disabled).attributes[0].corner[1].lightmap_uv, [0.0, 0.0]);
        // The key sees unit 1's coordinates and matrix, and whether the unit is on.
        let mut moved = draw.clone();
        moved.vertices.texcoords[1].values[1][0] = 0.75;
        let mut scaled = draw.clone();
        scaled.texture_matrices[1] = Some(Mat4::IDENTITY);
        let keys = [&draw, &moved, &scaled, &disabled].map(geometry_key);
        assert!(keys.iter().enumerate().all(|(i, k)| keys[i + 1..].iter().all(|o| o != k)), "{keys:?}");

        let m = material(&draw, [Some(4), Some(5)], &MaterialDefaults::default());
        assert_eq!((m.texture, m.lightmap, m.lightmap_scale), (4, 5, 1.0));
        let m = material(&decal, [Some(4), Some(5)], &MaterialDefaults::default());
        assert_eq!((m.lightmap, m.lightmap_scale), (NO_TEXTURE, 0.0));
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
