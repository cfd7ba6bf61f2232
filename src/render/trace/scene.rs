//! What the path tracer takes from a [`Frame`]: each traced surface ([`Surface`]: a traced
//! draw and its passes) turned into a geometry (object-space triangles, their shading
//! attributes and the passes' corners, cached on the GPU by [`geometry_key`]); the camera's
//! environment. Its instance is the base's modelview; its material is [`super::material`]'s.
//!
//! GL state is interpreted here, on the CPU, once per draw: the base colour of a corner is
//! what OpenGL would feed the texture stage (the vertex colour, or the material's diffuse
//! colour when lighting is on without colour material), normals are kept only for lit draws
//! (unlit GL geometry has no meaningful normals: the geometric normal is used). Corners carry
//! the coordinates of texture units 0 and 1 ([`TRACED_UNITS`]).
//!
//! A pass (a draw of class `Layer`) lies on the base's triangles: its triangle `j` covers base
//! triangle `layer.triangles[j]`, corner for corner. Each base triangle carries, per pass, a
//! [`GpuLayerCorners`] record: the pass's unit-0 coordinates and base colour at its corners
//! when the pass covers it, or `covered = 0` (a pass over some triangles only, such as a
//! dynamic-light pass, leaves the others as they are). A pass drawn twice over one triangle
//! keeps its last triangle there.

use glam::{Mat4, Vec3, Vec4};
use xxhash_rust::xxh3::Xxh3;

use super::gpu_types::{GpuCorner, GpuLayerCorners, GpuTriangleAttributes};
use super::shader_constants::TRACED_UNITS;
use super::surfaces::Surface;
use crate::frame::state::Lighting;
use crate::frame::{Draw, Frame, Framebuffer, Topology};

/// Whether `draw` is traced: a triangle draw of a traced class into the window's framebuffer,
/// run by the fixed-function pipeline (a GLSL program's output cannot be traced: those draws
/// are rasterized over the traced image like translucent ones). Traced draws are the bases of
/// the traced surfaces ([`super::surfaces`]).
pub fn is_traced(draw: &Draw) -> bool {
    draw.class.is_traced()
        && draw.topology == Topology::Triangles
        && draw.program.is_none()
        && draw.state.framebuffer == Framebuffer::default()
        && !draw.indices.is_empty()
}

/// The colour of the frame's first colour clear of the window (GL values): the environment
/// of missed rays, or where the sky draws' environment starts ([`super::sky`]).
pub fn clear_color(frame: &Frame) -> Option<[f32; 4]> {
    frame.clears.iter().filter(|c| c.framebuffer == Framebuffer::default()).find_map(|c| c.color)
}

/// The key the GPU geometry cache stores a surface's geometry under: everything [`geometry`]
/// reads (positions, indices, texture coordinates of the traced units after their texture
/// matrices, base colours, normals when lit; of each pass its indices, triangle map, unit-0
/// coordinates and base colours). The base's instance key (hash tracking) covers unit 0's
/// coordinates only, so unit 1's are hashed here.
pub fn geometry_key(surface: &Surface) -> u64 {
    let draw = surface.base;
    let mut h = Xxh3::new();
    h.update(&draw.instance.map_or(0, |i| i.geometry_key).to_le_bytes());
    if draw.instance.is_none() {
        h.update(bytemuck::cast_slice(&draw.vertices.position));
        h.update(bytemuck::cast_slice(&draw.indices));
        if let Some(t) = draw.vertices.texcoords.first() {
            h.update(bytemuck::cast_slice(&t.values));
        }
    }
    hash_shading(&mut h, draw, 0);
    for unit in 1..TRACED_UNITS {
        if enabled(draw, unit) {
            h.update(&[unit as u8]);
            hash_shading(&mut h, draw, unit);
            if let Some(t) = draw.vertices.texcoords.get(unit) {
                h.update(bytemuck::cast_slice(&t.values));
            }
        }
    }
    for pass in &surface.passes {
        h.update(b"pass");
        h.update(bytemuck::cast_slice(&pass.indices));
        if let Some(layer) = &pass.layer {
            h.update(bytemuck::cast_slice(&layer.triangles));
        }
        hash_shading(&mut h, pass, 0);
        h.update(&[u8::from(enabled(pass, 0))]);
        if let Some(t) = pass.vertices.texcoords.first().filter(|_| enabled(pass, 0)) {
            h.update(bytemuck::cast_slice(&t.values));
        }
    }
    h.digest()
}

/// Hashes what [`base_color`] and the normals read of `draw` (for `unit` 0), and unit
/// `unit`'s texture matrix.
fn hash_shading(h: &mut Xxh3, draw: &Draw, unit: usize) {
    if unit == 0 {
        h.update(bytemuck::cast_slice(&draw.vertices.color.values));
        if let Some(lighting) = &draw.state.lighting {
            h.update(bytemuck::cast_slice(&draw.vertices.normal.values));
            h.update(bytemuck::cast_slice(&lighting.front.diffuse));
            h.update(&[u8::from(lighting.tracks_diffuse())]);
        }
    }
    if let Some(m) = texture_matrix(draw, unit) {
        h.update(bytemuck::cast_slice(&m.to_cols_array()));
    }
}

/// Whether texture unit `unit` of `draw` has a target enabled.
pub fn enabled(draw: &Draw, unit: usize) -> bool {
    draw.texture_units.get(unit).is_some_and(Option::is_some)
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

/// The colour of `draw`'s vertex `i` that OpenGL feeds its texture stage (see the module doc).
fn base_color(draw: &Draw, i: usize) -> [f32; 4] {
    let diffuse = draw.state.lighting.as_ref().and_then(Lighting::untracked_diffuse);
    diffuse.or_else(|| draw.vertices.color.get(i)).unwrap_or([1.0; 4])
}

/// The geometry of a traced surface in object space: one entry per triangle.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Geometry {
    /// Corner positions (divided by w).
    pub triangles: Vec<[Vec3; 3]>,
    /// Shading attributes, in the order of `triangles`.
    pub attributes: Vec<GpuTriangleAttributes>,
    /// The passes' corners: `passes` records per triangle, in the order of `triangles`.
    pub layer_corners: Vec<GpuLayerCorners>,
    /// Passes of the surface.
    pub passes: usize,
}

/// Builds the geometry of `surface` (see the module doc for what each attribute holds).
pub fn geometry(surface: &Surface) -> Geometry {
    let draw = surface.base;
    let v = &draw.vertices;
    let lit = draw.state.lighting.is_some();
    let matrices: [Option<Mat4>; TRACED_UNITS] = std::array::from_fn(|unit| texture_matrix(draw, unit));
    let corner = |i: u32| -> ([f32; 4], GpuCorner) {
        let i = i as usize;
        let p = v.position.get(i).copied().unwrap_or([0.0, 0.0, 0.0, 1.0]);
        let normal = match v.normal.get(i) {
            Some(n) if lit => pack_normal(Vec3::from_array(n)),
            _ => 0,
        };
        let uv = std::array::from_fn(|unit| texcoord(draw, unit, matrices[unit], i));
        (p, GpuCorner { uv, normal, color: pack_unorm8(base_color(draw, i)) })
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
    let n = surface.passes.len();
    geometry.passes = n;
    geometry.layer_corners = vec![GpuLayerCorners::default(); geometry.triangles.len() * n];
    for (k, pass) in surface.passes.iter().enumerate() {
        let Some(layer) = &pass.layer else { continue };
        let matrix = texture_matrix(pass, 0);
        for (tri, &base) in pass.indices.chunks_exact(3).zip(layer.triangles.iter()) {
            if let Some(record) = geometry.layer_corners.get_mut(base as usize * n + k) {
                let corners = [tri[0], tri[1], tri[2]].map(|i| i as usize);
                *record = GpuLayerCorners {
                    uv: corners.map(|i| texcoord(pass, 0, matrix, i)),
                    color: corners.map(|i| pack_unorm8(base_color(pass, i))),
                    covered: 1,
                };
            }
        }
    }
    geometry
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
    use crate::frame::class::{DrawClass, Layer, LayerRole};
    use crate::frame::{Attrib, RasterState, TextureUnit, Vertices};
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

    /// `draw` as a surface without passes.
    fn alone(draw: &Draw) -> Surface<'_> {
        Surface { base: draw, passes: Vec::new() }
    }

    #[test]
    fn traced_draws_are_opaque_classes_of_triangles() {
        assert!(is_traced(&quad(DrawClass::Static)));
        assert!(!is_traced(&quad(DrawClass::Translucent)));
        assert!(!is_traced(&quad(DrawClass::Layer)));
    }

    #[test]
    fn geometry_divides_by_w_and_keeps_unlit_colours_without_normals() {
        let draw = quad(DrawClass::Static);
        let g = geometry(&alone(&draw));
        assert_eq!(g.triangles.len(), 2);
        assert_eq!(g.triangles[1][2], Vec3::new(0.0, 1.0, 0.0));
        assert_eq!(g.attributes[0].corner[1].color, pack_unorm8([1.0, 0.5, 0.0, 1.0]));
        assert_eq!(g.attributes[0].corner[0].normal, 0, "unlit draws use the geometric normal");
        assert_eq!((g.passes, g.layer_corners.len()), (0, 0));
    }

    #[test]
    fn lit_geometry_takes_the_material_diffuse_and_normals() {
        let mut draw = quad(DrawClass::Static);
        let mut lighting = Lighting::default();
        lighting.front.diffuse = [0.25, 0.5, 0.75, 1.0];
        draw.state = Arc::new(RasterState { lighting: Some(lighting), ..RasterState::default() });
        let g = geometry(&alone(&draw));
        assert_eq!(g.attributes[0].corner[0].color, pack_unorm8([0.25, 0.5, 0.75, 1.0]));
        assert_ne!(g.attributes[0].corner[0].normal, 0);
        assert_ne!(geometry_key(&alone(&draw)), geometry_key(&alone(&quad(DrawClass::Static))));
    }

    /// `quad` with units 0 and 1 enabled; unit 1's coordinates are the positions' x, y,
    /// through a texture matrix halving s.
    fn two_units() -> Draw {
        let mut draw = quad(DrawClass::Static);
        draw.texture_units = vec![Some(TextureUnit::default()), Some(TextureUnit::default())];
        draw.texture_matrices = vec![Some(Mat4::IDENTITY), Some(Mat4::from_scale(Vec3::new(0.5, 1.0, 1.0)))];
        let second_uv = draw.vertices.position.iter().map(|p| [p[0], p[1], 0.0, p[3]]).collect();
        draw.vertices.texcoords = vec![Attrib { values: vec![[0.25, 0.75, 0.0, 1.0]] }, Attrib { values: second_uv }];
        draw
    }

    #[test]
    fn unit_1_coordinates_go_through_its_matrix_and_into_the_key() {
        let draw = two_units();
        let g = geometry(&alone(&draw));
        assert_eq!(g.attributes[0].corner.map(|c| c.uv[1]), [[0.0, 0.0], [0.5, 0.0], [0.5, 1.0]]);
        assert_eq!(g.attributes[1].corner[2].uv[1], [0.0, 1.0], "(0, 2, 0, 2) divided by q");
        assert_eq!(g.attributes[0].corner[0].uv[0], [0.25, 0.75]);
        let mut disabled = draw.clone();
        disabled.texture_units[1] = None;
        assert_eq!(geometry(&alone(&disabled)).attributes[0].corner[1].uv[1], [0.0, 0.0]);
        let mut moved = draw.clone();
        moved.vertices.texcoords[1].values[1][0] = 0.75;
        let mut scaled = draw.clone();
        scaled.texture_matrices[1] = Some(Mat4::IDENTITY);
        let keys = [&draw, &moved, &scaled, &disabled].map(|d| geometry_key(&alone(d)));
        assert!(keys.iter().enumerate().all(|(i, k)| keys[i + 1..].iter().all(|o| o != k)), "{keys:?}");
    }

    /// A pass over triangle 1 of its base (its one triangle: vertices 2, 0, 1 of its own),
    /// with unit 0's coordinates (s, t) = (10 i, 0) at vertex i and a colour per vertex.
    fn pass_over_triangle_1() -> Draw {
        let mut pass = quad(DrawClass::Layer);
        pass.indices = vec![2, 0, 1];
        pass.texture_units = vec![Some(TextureUnit::default())];
        pass.vertices.texcoords = vec![Attrib { values: (0..4).map(|i| [10.0 * i as f32, 0.0, 0.0, 1.0]).collect() }];
        pass.vertices.color = Attrib { values: vec![[1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0], [1.0; 4]] };
        pass.layer = Some(Layer { base: 0, triangles: Arc::from([1u32]), role: LayerRole::Emission });
        pass
    }

    #[test]
    fn passes_carry_their_corners_on_the_base_triangles_they_cover() {
        let base = quad(DrawClass::Static);
        let pass = pass_over_triangle_1();
        let untextured = Draw { texture_units: Vec::new(), ..pass_over_triangle_1() };
        let surface = Surface { base: &base, passes: vec![&untextured, &pass] };
        let g = geometry(&surface);
        assert_eq!((g.passes, g.layer_corners.len()), (2, 4));
        assert_eq!(g.layer_corners[0], GpuLayerCorners::default(), "triangle 0 is not covered by pass 0");
        assert_eq!(g.layer_corners[1].covered, 0, "nor by pass 1");
        let covered = g.layer_corners[3];
        assert_eq!(covered.covered, 1);
        assert_eq!(covered.uv, [[20.0, 0.0], [0.0, 0.0], [10.0, 0.0]], "the pass's vertices at the base triangle's corners");
        assert_eq!(covered.color, [pack_unorm8([0.0, 0.0, 1.0, 1.0]), pack_unorm8([1.0, 0.0, 0.0, 1.0]), pack_unorm8([0.0, 1.0, 0.0, 1.0])]);
        assert_eq!((g.layer_corners[2].covered, g.layer_corners[2].uv[0]), (1, [0.0, 0.0]), "without texturing the pass has no coordinates");

        // The key sees the passes, their order, their coordinates and where they lie.
        let mut elsewhere = pass_over_triangle_1();
        elsewhere.layer = Some(Layer { base: 0, triangles: Arc::from([0u32]), role: LayerRole::Emission });
        let mut recoloured = pass_over_triangle_1();
        recoloured.vertices.color.values[0] = [0.5; 4];
        let keys = [
            geometry_key(&alone(&base)),
            geometry_key(&surface),
            geometry_key(&Surface { base: &base, passes: vec![&pass, &untextured] }),
            geometry_key(&Surface { base: &base, passes: vec![&untextured, &elsewhere] }),
            geometry_key(&Surface { base: &base, passes: vec![&untextured, &recoloured] }),
        ];
        assert!(keys.iter().enumerate().all(|(i, k)| keys[i + 1..].iter().all(|o| o != k)), "{keys:?}");
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
