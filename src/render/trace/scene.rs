//! What the path tracer takes from a [`Frame`]: the traced draws, each turned into a geometry
//! (object-space triangles and their shading attributes, cached on the GPU by
//! [`geometry_key`]), an instance (its modelview) and a material; the camera; the environment.
//!
//! GL state is interpreted here, on the CPU, once per draw: the base colour of a corner is
//! what OpenGL would feed the texture stage (the vertex colour, or the material's diffuse
//! colour when lighting is on without colour material), normals are kept only for lit draws
//! (unlit GL geometry has no meaningful normals: the geometric normal is used), texture unit
//! 0 is the albedo texture and other units (lightmaps, detail textures) are left out, so that
//! light baked into them is not counted twice.

use glam::{Mat4, Vec3, Vec4};
use xxhash_rust::xxh3::Xxh3;

use super::gpu_types::{GpuCorner, GpuMaterial, GpuTriangleAttributes, NO_TEXTURE};
use crate::frame::state::{ColorMaterialMode, CompareFunc, Lighting};
use crate::frame::texture::EnvMode;
use crate::frame::{Draw, Frame, Framebuffer, Topology};

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
/// [`geometry`] reads (positions, indices, texture coordinates after the texture matrix,
/// base colours, normals when lit).
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
    if let Some(m) = texture_matrix(draw) {
        h.update(bytemuck::cast_slice(&m.to_cols_array()));
    }
    h.digest()
}

/// Whether the lit base colour follows the vertex colour (`glColorMaterial` on diffuse).
fn tracks_diffuse(lighting: &Lighting) -> bool {
    lighting.color_material.is_some_and(|c| matches!(c.mode, ColorMaterialMode::Diffuse | ColorMaterialMode::AmbientAndDiffuse))
}

/// Unit 0's texture matrix when unit 0 is enabled and it is not the identity.
fn texture_matrix(draw: &Draw) -> Option<Mat4> {
    draw.texture_matrices.first().copied().flatten().filter(|m| *m != Mat4::IDENTITY)
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
    let uv_matrix = texture_matrix(draw);
    let textured = draw.texture_units.first().is_some_and(Option::is_some);
    let corner = |i: u32| -> ([f32; 4], GpuCorner) {
        let i = i as usize;
        let p = v.position.get(i).copied().unwrap_or([0.0, 0.0, 0.0, 1.0]);
        let color = diffuse.or_else(|| v.color.get(i)).unwrap_or([1.0; 4]);
        let uv = if textured {
            let t = v.texcoords.first().and_then(|t| t.get(i)).unwrap_or([0.0, 0.0, 0.0, 1.0]);
            let t = uv_matrix.map_or(Vec4::from_array(t), |m| m * Vec4::from_array(t));
            let q = if t.w != 0.0 { t.w } else { 1.0 };
            [t.x / q, t.y / q]
        } else {
            [0.0; 2]
        };
        let normal = match (lit, v.normal.get(i)) {
            (Some(_), Some(n)) => pack_normal(Vec3::from_array(n)),
            _ => 0,
        };
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

/// The material of a traced draw whose unit-0 texture is `texture` in the texel pool.
///
/// Lit draws take their specular reflectance from the GL material (0 for the default
/// material, so a default lit surface is Lambertian) and their roughness from its shininess
/// (Blinn-Phong exponent n to GGX alpha = sqrt(2 / (n + 2))); emission is the GL material's.
/// Roughness, metalness and emission otherwise come from the draw's `glrt.toml` material
/// ([`crate::frame::class::MaterialOverride`], defaults included).
pub fn material(draw: &Draw, texture: Option<u32>, defaults: &MaterialDefaults) -> GpuMaterial {
    let unit = draw.texture_units.first().copied().flatten();
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
        pad: 0,
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
        let m = material(&draw, None, &MaterialDefaults::default());
        assert_eq!((m.specular, m.texture, m.alpha_func), (0.0, NO_TEXTURE, 7));
        let unlit = material(&quad(DrawClass::Static), Some(3), &MaterialDefaults::default());
        assert_eq!((unlit.specular, unlit.texture), (0.04, 3));
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
