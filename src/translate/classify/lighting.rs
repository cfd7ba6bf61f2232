//! Where a traced surface's light comes from ([`SurfaceLighting`],
//! [`crate::frame::class::Instance::light_units`], and whether a multiplying layer is baked
//! light): what the tracer needs so that it counts no light twice (issue 16).
//!
//! - **Lightmaps.** A texture multiplied over another on the same triangles (texture unit `u`
//!   modulating an earlier unit, or a pass `GL_DST_COLOR, GL_ZERO` / `GL_ZERO, GL_SRC_COLOR`
//!   over its base) is a lightmap when its texels are coarse: each covers at least
//!   [`LIGHTMAP_RATIO`] times the surface area a texel of the other texture covers (Quake 3
//!   bakes 16 world units per lightmap texel against 1–2 per texel of a surface texture; a
//!   detail texture is finer, never light). When a base pass's texture is the coarse one, it
//!   is the lightmap under a texture pass (a first unit is light only by its tag: under a
//!   finer unit it is as likely a surface under a detail texture). Densities are compared on
//!   up to [`SAMPLES`] triangles, through each unit's texture matrix; a unit with generated
//!   coordinates, or a texture that is not 2D, is never compared. A texture tagged `lightmap`
//!   in `glrt.toml` is light wherever it is.
//! - **Lighting** ([`surface_lighting`]), in this order: a GL-lit draw is `Traced` (its light
//!   is the GL lights, which the tracer has; its light units are still reported); a draw with
//!   a light unit or a `BakedLight` layer is `Baked`; an unlit draw whose vertex colours vary
//!   is `VertexLit` when it is `Movable` or `Dynamic` or its colours changed from one frame to
//!   another while its geometry stayed (a model lit from a light grid; [`ColourHistory`]),
//!   else `Baked` (a vertex-lit world surface; also a model in the first frame it is seen,
//!   before it moved); everything else is `Traced`.

use xxhash_rust::xxh3::xxh3_64;

use super::keys::bytes_of;
use super::static_world::Map;
use crate::frame::class::{DrawClass, SurfaceLighting};
use crate::frame::texture::{CombineFn, EnvMode, TextureKind};
use crate::frame::Draw;

/// A texture is a lightmap when each of its texels covers at least this many times the area a
/// texel of the texture it multiplies covers, on the same triangles.
pub const LIGHTMAP_RATIO: f64 = 4.0;

/// Triangles of a draw whose texel densities are compared, at most (spread over the draw).
pub const SAMPLES: usize = 16;

/// Frames a colour history is kept for an instance not drawn.
const KEEP_FRAMES: u64 = 120;

/// The first textured unit of `draw`.
pub fn first_unit(draw: &Draw) -> Option<usize> {
    draw.textures.iter().position(Option::is_some)
}

/// Whether unit `unit`'s texture multiplies the colour before it (`GL_MODULATE`, or a
/// `GL_COMBINE` that modulates).
fn multiplies(draw: &Draw, unit: usize) -> bool {
    draw.texture_units.get(unit).copied().flatten().is_some_and(|u| u.env.mode == EnvMode::Modulate || (u.env.mode == EnvMode::Combine && u.env.combine_rgb == CombineFn::Modulate))
}

/// Up to [`SAMPLES`] of `n` triangles, spread over them.
fn sample(n: usize) -> impl Iterator<Item = usize> {
    (0..n).step_by(n.div_ceil(SAMPLES).max(1))
}

/// Texels of unit `unit`'s texture that `triangles` of `draw` cover (their area in texture
/// coordinates after the texture matrix, times the texture's size); `None` when that cannot be
/// told (no texture, generated or missing coordinates, not 2D) or is zero.
fn texels(draw: &Draw, unit: usize, triangles: impl Iterator<Item = usize>) -> Option<f64> {
    let texture = draw.textures.get(unit)?.as_ref()?;
    let level = texture.content.faces.first()?.first()?.as_ref()?;
    let size = match texture.content.kind {
        TextureKind::D2 => f64::from(level.width - 2 * level.border) * f64::from(level.height - 2 * level.border),
        TextureKind::Rect => 1.0,
        _ => return None,
    };
    if draw.texture_units.get(unit).copied().flatten().is_some_and(|u| u.texgen.iter().any(Option::is_some)) {
        return None;
    }
    let coords = draw.vertices.texcoords.get(unit).filter(|c| !c.is_constant())?;
    let matrix = draw.texture_matrices.get(unit).copied().flatten().filter(|m| *m != glam::Mat4::IDENTITY);
    let st = |i: u32| {
        let t = glam::Vec4::from_array(coords.get(i as usize)?);
        let t = matrix.map_or(t, |m| m * t);
        let q = if t.w != 0.0 { t.w } else { 1.0 };
        Some(glam::DVec2::new(f64::from(t.x / q), f64::from(t.y / q)))
    };
    let mut area = 0.0;
    for t in triangles {
        let Some(i) = draw.indices.get(3 * t..3 * t + 3) else { continue };
        let (Some(a), Some(b), Some(c)) = (st(i[0]), st(i[1]), st(i[2])) else { continue };
        area += (b - a).perp_dot(c - a).abs() / 2.0;
    }
    let texels = area * size;
    (texels > 0.0 && texels.is_finite()).then_some(texels)
}

/// Whether a texture of which the same triangles cover `coarse` texels is a lightmap under
/// one of which they cover `fine`.
fn coarser(coarse: Option<f64>, fine: Option<f64>) -> bool {
    matches!((coarse, fine), (Some(c), Some(f)) if c * LIGHTMAP_RATIO <= f)
}

/// The texture units of a traced draw that hold baked light
/// ([`crate::frame::class::Instance::light_units`]): a unit after the first textured one that
/// multiplies and is coarser than it; `tagged(u)`: unit `u`'s texture is tagged `lightmap`.
/// The first unit is light only by its tag: a texture under a much finer one on the next unit
/// is as likely a surface under a detail texture.
pub fn light_units(draw: &Draw, tagged: impl Fn(usize) -> bool) -> u8 {
    let units = draw.textures.len().min(8);
    let textured = |u: &usize| draw.textures[*u].is_some();
    let mut bits = (0..units).filter(textured).filter(|&u| tagged(u)).fold(0u8, |bits, u| bits | 1 << u);
    let Some(first) = first_unit(draw) else { return bits };
    let n = draw.indices.len() / 3;
    let mut first_texels = None;
    for u in (first + 1..units).filter(textured).filter(|&u| multiplies(draw, u)) {
        let first_texels = *first_texels.get_or_insert_with(|| texels(draw, first, sample(n)));
        if coarser(texels(draw, u, sample(n)), first_texels) {
            bits |= 1 << u;
        }
    }
    bits
}

/// What a multiplying pass over a base holds: baked light (`pass`), or colour over a base
/// whose texture unit `base_unit` holds the light instead (a lightmap base pass).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Multiplied {
    /// The pass's texture is a lightmap: a [`crate::frame::class::LayerRole::BakedLight`] layer.
    pub pass: bool,
    /// The light units this sets on the base.
    pub base_units: u8,
}

/// What the multiplying pass `pass` over `base` holds, its triangle `t` lying on the base's
/// triangle `triangles[t]`; `tagged_pass`, `tagged_base`: the pass's texture, the base's first
/// texture, are tagged `lightmap`.
pub fn multiplied(base: &Draw, pass: &Draw, triangles: &[u32], tagged_pass: bool, tagged_base: bool) -> Multiplied {
    let (Some(pu), Some(bu)) = (first_unit(pass), first_unit(base)) else { return Multiplied { pass: tagged_pass, base_units: 0 } };
    let base_bit = 1u8 << bu.min(7);
    if tagged_pass || tagged_base {
        return Multiplied { pass: tagged_pass, base_units: if tagged_base { base_bit } else { 0 } };
    }
    let pass_texels = texels(pass, pu, sample(triangles.len()));
    let base_texels = texels(base, bu, sample(triangles.len()).map(|t| triangles[t] as usize));
    if coarser(pass_texels, base_texels) {
        Multiplied { pass: true, base_units: 0 }
    } else {
        Multiplied { pass: false, base_units: if coarser(base_texels, pass_texels) { base_bit } else { 0 } }
    }
}

/// Whether `draw`'s vertex colours differ from vertex to vertex.
pub fn colours_vary(draw: &Draw) -> bool {
    let c = &draw.vertices.color.values;
    c.len() > 1 && c.iter().any(|v| *v != c[0])
}

/// How a traced draw of class `class` is lit (module doc): `light_units` of its units,
/// `baked_layer`: it has a `BakedLight` layer; `changed()`: its vertex colours changed since an
/// earlier frame (asked only of a static unlit draw whose colours vary).
pub fn surface_lighting(draw: &Draw, class: DrawClass, light_units: u8, baked_layer: bool, changed: impl FnOnce() -> bool) -> SurfaceLighting {
    if draw.state.lighting.is_some() {
        SurfaceLighting::Traced
    } else if light_units != 0 || baked_layer {
        SurfaceLighting::Baked
    } else if !colours_vary(draw) {
        SurfaceLighting::Traced
    } else if class != DrawClass::Static || changed() {
        SurfaceLighting::VertexLit
    } else {
        SurfaceLighting::Baked
    }
}

/// The vertex colours each traced instance had when last drawn; kept between frames.
#[derive(Default)]
pub struct ColourHistory {
    seen: Map<u64, Seen>,
}

/// An instance's colours.
#[derive(Clone, Copy, Debug)]
struct Seen {
    hash: u64,
    changed: bool,
    frame: u64,
}

impl ColourHistory {
    /// Whether instance `id`, drawn in frame `frame` with `colours`, has had other colours in
    /// an earlier frame (once true, true for as long as the instance is remembered).
    pub fn changed(&mut self, id: u64, colours: &[[f32; 4]], frame: u64) -> bool {
        let hash = xxh3_64(bytes_of(colours));
        let seen = self.seen.entry(id).or_insert(Seen { hash, changed: false, frame });
        seen.changed |= seen.hash != hash;
        (seen.hash, seen.frame) = (hash, frame);
        seen.changed
    }

    /// Forgets instances not drawn for a while (checked every 120 frames: `KEEP_FRAMES`).
    pub fn end_frame(&mut self, frame: u64) {
        if frame.is_multiple_of(KEEP_FRAMES) {
            self.seen.retain(|_, s| frame - s.frame.min(frame) < KEEP_FRAMES);
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    use std::sync::Arc;

    use glam::Mat4;

    use super::*;
    use crate::frame::texture::{TexImage, TextureContent, TextureEnv};
    use crate::frame::{Attrib, TextureRef, TextureUnit};

    /// A `width` × `height` texture `id`.
    pub(in crate::translate::classify) fn sized(id: u32, width: u32, height: u32) -> TextureRef {
        let image = TexImage { width, height, depth: 1, texels: vec![id as u8; (width * height * 4) as usize], ..TexImage::default() };
        let content = TextureContent { faces: vec![vec![Some(Arc::new(image))]], ..TextureContent::default() };
        TextureRef { id, version: u64::from(id), content: Arc::new(content) }
    }

    /// A unit environment `mode`.
    pub(in crate::translate::classify) fn unit(mode: EnvMode) -> Option<TextureUnit> {
        Some(TextureUnit { env: TextureEnv { mode, ..TextureEnv::default() }, ..TextureUnit::default() })
    }

    /// Texture coordinates of a quad's 6 corners (two triangles of 1 × 1 world units) that
    /// repeat `repeat` times across it.
    pub(in crate::translate::classify) fn coords(repeat: f32) -> Attrib<[f32; 4]> {
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        Attrib { values: corners.iter().map(|[s, t]| [s * repeat, t * repeat, 0.0, 1.0]).collect() }
    }

    /// A quad textured with `textures` on the units in order, each unit's coordinates
    /// repeating as `repeats` says, unit 0 modulating the colour, the others `mode`.
    pub(in crate::translate::classify) fn quad(textures: &[TextureRef], repeats: &[f32], mode: EnvMode) -> Draw {
        let mut d = Draw::default();
        d.vertices.position = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0], [1.0, 1.0], [0.0, 1.0]].iter().map(|[x, y]| [*x, *y, 0.0, 1.0]).collect();
        d.indices = (0..6).collect();
        d.vertex_count = 6;
        d.textures = textures.iter().cloned().map(Some).collect();
        d.texture_units = (0..textures.len()).map(|u| unit(if u == 0 { EnvMode::Modulate } else { mode })).collect();
        d.vertices.texcoords = repeats.iter().map(|&r| coords(r)).collect();
        d
    }

    #[test]
    fn a_coarse_unit_modulating_another_is_a_lightmap() {
        // Quake 3's multitexture: a 256² texture repeating 4 times over the quad, a lightmap
        // page of 128² of which the quad covers a 16th (4 × 4 texels).
        let (texture, page) = (sized(1, 256, 256), sized(2, 128, 128));
        assert_eq!(light_units(&quad(&[texture.clone(), page.clone()], &[4.0, 0.25], EnvMode::Modulate), |_| false), 0b10);
        // The lightmap on unit 0 and the texture modulating it on unit 1: light only by its
        // tag (the same densities as a texture under a detail texture).
        assert_eq!(light_units(&quad(&[page.clone(), texture.clone()], &[0.25, 4.0], EnvMode::Modulate), |_| false), 0);
        assert_eq!(light_units(&quad(&[page.clone(), texture.clone()], &[0.25, 4.0], EnvMode::Modulate), |u| u == 0), 0b01);
        // A detail texture on unit 1: finer than the texture, never light; nor is a lightmap
        // applied as a decal.
        assert_eq!(light_units(&quad(&[texture.clone(), sized(3, 64, 64)], &[4.0, 32.0], EnvMode::Modulate), |_| false), 0);
        assert_eq!(light_units(&quad(&[texture.clone(), page.clone()], &[4.0, 0.25], EnvMode::Decal), |_| false), 0);
        // Equal densities (the page repeating 8 times: 64 × its 128² texels against 16 × 256²):
        // neither.
        assert_eq!(light_units(&quad(&[texture.clone(), page.clone()], &[4.0, 8.0], EnvMode::Modulate), |_| false), 0);
        // The texture matrix counts: unit 1's coordinates scaled by 1/16 make it coarse.
        let mut scaled = quad(&[texture.clone(), page.clone()], &[4.0, 4.0], EnvMode::Modulate);
        scaled.texture_matrices = vec![None, Some(Mat4::from_scale(glam::Vec3::new(1.0 / 16.0, 1.0 / 16.0, 1.0)))];
        assert_eq!(light_units(&scaled, |_| false), 0b10);
        // A tag makes a texture light whatever its density.
        assert_eq!(light_units(&quad(&[texture.clone(), page], &[4.0, 8.0], EnvMode::Modulate), |u| u == 1), 0b10);
        assert_eq!(light_units(&quad(&[texture], &[4.0], EnvMode::Modulate), |_| false), 0, "one unit");
    }

    #[test]
    fn a_multiplying_pass_is_light_or_colour_over_light() {
        let (texture, page) = (sized(1, 256, 256), sized(2, 128, 128));
        let (base, lightmap_pass) = (quad(std::slice::from_ref(&texture), &[4.0], EnvMode::Modulate), quad(std::slice::from_ref(&page), &[0.25], EnvMode::Modulate));
        assert_eq!(multiplied(&base, &lightmap_pass, &[0, 1], false, false), Multiplied { pass: true, base_units: 0 });
        // A lightmap base pass, then the texture multiplied over it.
        assert_eq!(multiplied(&lightmap_pass, &base, &[0, 1], false, false), Multiplied { pass: false, base_units: 0b1 });
        // The pass's triangle 0 is the base's triangle 1 (the other half: same area here, but
        // the base's coordinates of triangle 1 are what is measured).
        let mut half = base.clone();
        half.vertices.texcoords[0].values[3..].iter_mut().for_each(|c| *c = [0.0; 4]);
        assert!(!multiplied(&half, &lightmap_pass, &[1], false, false).pass, "triangle 1 of the base has no texels");
        assert!(multiplied(&half, &lightmap_pass, &[0], false, false).pass);
        // Tags win.
        assert_eq!(multiplied(&base, &base, &[0, 1], true, false), Multiplied { pass: true, base_units: 0 });
        assert_eq!(multiplied(&base, &base, &[0, 1], false, true), Multiplied { pass: false, base_units: 0b1 });
        assert_eq!(multiplied(&base, &base, &[0, 1], false, false), Multiplied::default());
    }

    #[test]
    fn vertex_colours_light_unlit_surfaces() {
        let mut d = quad(&[sized(1, 4, 4)], &[1.0], EnvMode::Modulate);
        let varied = Attrib { values: (0..6).map(|i| [0.1 * i as f32, 0.5, 0.5, 1.0]).collect() };
        let never = || panic!("not asked");
        assert_eq!(surface_lighting(&d, DrawClass::Static, 0, false, never), SurfaceLighting::Traced, "white");
        d.vertices.color = varied.clone();
        assert_eq!(surface_lighting(&d, DrawClass::Static, 0, false, || false), SurfaceLighting::Baked, "Quake 3's vertex-lit world");
        assert_eq!(surface_lighting(&d, DrawClass::Static, 0, false, || true), SurfaceLighting::VertexLit, "colours changed");
        assert_eq!(surface_lighting(&d, DrawClass::Movable, 0, false, never), SurfaceLighting::VertexLit);
        assert_eq!(surface_lighting(&d, DrawClass::Dynamic, 0, false, never), SurfaceLighting::VertexLit);
        assert_eq!(surface_lighting(&d, DrawClass::Dynamic, 0b10, false, never), SurfaceLighting::Baked, "a lightmap");
        assert_eq!(surface_lighting(&d, DrawClass::Movable, 0, true, never), SurfaceLighting::Baked, "a lightmap pass");
        d.vertices.color = Attrib { values: vec![[0.5; 4]; 6] };
        assert_eq!(surface_lighting(&d, DrawClass::Dynamic, 0, false, never), SurfaceLighting::Traced, "one colour");
        d.vertices.color = varied;
        d.state = Arc::new(crate::frame::RasterState { lighting: Some(Default::default()), ..Default::default() });
        assert_eq!(surface_lighting(&d, DrawClass::Dynamic, 0b10, true, never), SurfaceLighting::Traced, "GL lighting");
    }

    #[test]
    fn colour_history_remembers_a_change() {
        let mut h = ColourHistory::default();
        let (a, b) = ([[0.5f32; 4]; 3], [[0.25f32; 4]; 3]);
        assert!(!h.changed(7, &a, 0));
        assert!(!h.changed(7, &a, 1));
        assert!(!h.changed(8, &b, 1), "another instance");
        assert!(h.changed(7, &b, 2));
        assert!(h.changed(7, &b, 3), "once changed, vertex-lit");
        h.end_frame(KEEP_FRAMES * 2);
        assert!(!h.changed(7, &b, KEEP_FRAMES * 2 + 1), "forgotten when not drawn for a while");
    }
}
