//! Dynamic-light passes as point lights: Quake 3 lights the surfaces around a rocket or a
//! muzzle flash by drawing them once more with a radial falloff texture centred on the light
//! (`ProjectDlightTexture` in ioquake3's `tr_shade.c`), added (`GL_ONE, GL_ONE`, or
//! `GL_SRC_ALPHA, GL_ONE`) or multiplied in (`GL_DST_COLOR, GL_ONE`), with `GL_EQUAL` depth.
//! Per vertex at `p` of a light at `o` of radius `r` and colour `c`:
//!
//! - texture coordinates `s = 0.5 + (o.x - p.x) / r`, `t = 0.5 + (o.y - p.y) / r` (the texture
//!   projected along z, its square `r` wide);
//! - colour `c · m(o.z - p.z)`, `m(h) = 1` for `|h| < r/2`, `2 (r - |h|) / r` up to `|h| = r`,
//!   0 beyond.
//!
//! [`fit`] recovers `o` and `r` by least squares from the pass's vertices: `s` and `t` are
//! affine in `p.x` and `p.y` with one shared slope `-1/r`, a linear problem of three unknowns
//! (`1/r`, `o.x/r`, `o.y/r`) solved in closed form; a pass whose coordinates are not that
//! (residual over [`MAX_TEXCOORD_RESIDUAL`]) is no dynamic light. The height `o.z` and the
//! colour come from the colours: the height whose `m` explains them best (colour scale fitted
//! per height, at most 1) among a scan of heights; where several heights explain them equally (a flat
//! floor wholly within `r/2` of the light), the one nearest the viewer's height, which lies
//! on the lit side. [`falloff`] reads the falloff texture (bright at its centre, black at its
//! corners) for the strength of its inverse-square falloff and its faintest texel.
//!
//! [`DynamicLights`] collects the lights of one frame's passes in eye space, one per light: the
//! passes of a light drawn over several batches (a floor and a wall) are pooled, and its
//! height and colour fitted to all of their colours.

use glam::{Mat4, Vec3};

use crate::frame::class::DynamicLight;
use crate::frame::state::{BlendEquation, BlendFactor, CompareFunc};
use crate::frame::texture::TextureKind;
use crate::frame::{Draw, TextureRef, Topology};

/// Largest root-mean-square difference between a pass's texture coordinates and the fitted
/// projection (texture units: a thousandth of the light's square).
pub const MAX_TEXCOORD_RESIDUAL: f32 = 1e-3;

/// Largest root-mean-square difference between a pass's vertex colours and the fitted
/// colour times the height modulation (display units).
pub const MAX_COLOR_RESIDUAL: f32 = 0.02;

/// Heights scanned for the light's height.
const HEIGHT_STEPS: usize = 512;

/// One vertex of a dynamic-light pass: object-space position, texture coordinates of unit 0,
/// colour (display-encoded RGB).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PassVertex {
    pub position: Vec3,
    pub st: [f32; 2],
    pub color: Vec3,
}

/// A light recovered from one pass, in the pass's object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// The light's centre.
    pub origin: Vec3,
    /// The width of its texture's square.
    pub radius: f32,
    /// Its colour at full strength.
    pub color: Vec3,
    /// Root-mean-square residual of the texture coordinates.
    pub residual: f32,
    /// How far apart the heights are that explain the colours equally well (0: one height).
    pub height_spread: f32,
}

/// Why a pass is not a dynamic light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reject {
    /// Fewer than three vertices, or all on one vertical line.
    Degenerate,
    /// The coordinates do not shrink away from a centre (`1/r` not positive).
    NotCentred,
    /// The coordinates are not the projection of a light (residual too large).
    Texcoords,
    /// The colours are black, or do not follow the height modulation.
    Colors,
}

/// Q3's height modulation of a vertex `h` above or below a light of radius `r`.
fn modulation(h: f32, r: f32) -> f32 {
    let h = h.abs();
    if h < 0.5 * r {
        1.0
    } else if h <= r {
        2.0 * (r - h) / r
    } else {
        0.0
    }
}

/// Recovers the light of a dynamic-light pass from its vertices (module doc); `eye_height`:
/// the viewer's height in the same object space, which picks among heights that explain the
/// colours equally.
pub fn fit(vertices: &[PassVertex], eye_height: f32) -> Result<Fit, Reject> {
    let n = vertices.len();
    if n < 3 {
        return Err(Reject::Degenerate);
    }
    // s = b - a x, t = c - a y: with means removed, a = -Σ(x̃ s̃ + ỹ t̃) / Σ(x̃² + ỹ²).
    let count = n as f64;
    let mean = |f: &dyn Fn(&PassVertex) -> f64| vertices.iter().map(f).sum::<f64>() / count;
    let (mx, my) = (mean(&|v| f64::from(v.position.x)), mean(&|v| f64::from(v.position.y)));
    let (ms, mt) = (mean(&|v| f64::from(v.st[0])), mean(&|v| f64::from(v.st[1])));
    let (mut cross, mut spread) = (0.0, 0.0);
    for v in vertices {
        let (x, y) = (f64::from(v.position.x) - mx, f64::from(v.position.y) - my);
        cross += x * (f64::from(v.st[0]) - ms) + y * (f64::from(v.st[1]) - mt);
        spread += x * x + y * y;
    }
    if spread <= 1e-12 * count {
        return Err(Reject::Degenerate);
    }
    let a = -cross / spread;
    if !(a > 0.0 && a.is_finite()) {
        return Err(Reject::NotCentred);
    }
    let (b, c) = (ms + a * mx, mt + a * my);
    let squares: f64 = vertices
        .iter()
        .map(|v| {
            let (x, y) = (f64::from(v.position.x), f64::from(v.position.y));
            (b - a * x - f64::from(v.st[0])).powi(2) + (c - a * y - f64::from(v.st[1])).powi(2)
        })
        .sum();
    let residual = (squares / (2.0 * count)).sqrt() as f32;
    if residual > MAX_TEXCOORD_RESIDUAL {
        return Err(Reject::Texcoords);
    }
    let radius = (1.0 / a) as f32;
    let (ox, oy) = (((b - 0.5) / a) as f32, ((c - 0.5) / a) as f32);
    let (oz, color, height_spread) = height_and_color(vertices, radius, eye_height)?;
    Ok(Fit { origin: Vec3::new(ox, oy, oz), radius, color, residual, height_spread })
}

/// The light's height, colour and height spread from the vertex colours (module doc).
fn height_and_color(vertices: &[PassVertex], r: f32, eye_height: f32) -> Result<(f32, Vec3, f32), Reject> {
    let brightness: Vec<f32> = vertices.iter().map(|v| v.color.max_element()).collect();
    let energy: f32 = brightness.iter().map(|b| b * b).sum();
    if energy <= 0.0 {
        return Err(Reject::Colors);
    }
    let (lo, hi) = vertices.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), v| (lo.min(v.position.z), hi.max(v.position.z)));
    let (first, step) = (lo - r, (hi - lo + 2.0 * r) / (HEIGHT_STEPS - 1) as f32);
    // The squared error Σ(b - C m)² of the best colour scale C at each height, C at most 1
    // (a display colour: a height where the colours would need a brighter light is worse).
    let cost = |z: f32| {
        let (mut bm, mut mm) = (0.0, 0.0);
        for (v, b) in vertices.iter().zip(&brightness) {
            let m = modulation(z - v.position.z, r);
            (bm, mm) = (bm + b * m, mm + m * m);
        }
        let scale = if mm > 0.0 { (bm / mm).min(1.0) } else { 0.0 };
        (energy - 2.0 * scale * bm + scale * scale * mm).max(0.0)
    };
    let costs: Vec<(f32, f32)> = (0..HEIGHT_STEPS).map(|k| first + k as f32 * step).map(|z| (z, cost(z))).collect();
    let least = costs.iter().map(|c| c.1).fold(f32::INFINITY, f32::min);
    let n = vertices.len() as f32;
    if least > n * MAX_COLOR_RESIDUAL * MAX_COLOR_RESIDUAL {
        return Err(Reject::Colors);
    }
    // Colours are 8-bit: heights within a level's rounding of the best explain them as well.
    let tolerance = least + n * (1.0 / 255.0f32).powi(2);
    let equal: Vec<f32> = costs.iter().filter(|c| c.1 <= tolerance).map(|c| c.0).collect();
    let (z_lo, z_hi) = equal.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &z| (lo.min(z), hi.max(z)));
    let z = *equal.iter().min_by(|a, b| (*a - eye_height).abs().total_cmp(&(*b - eye_height).abs())).expect("the least cost is within the tolerance");
    let (mut weighted, mut mm) = (Vec3::ZERO, 0.0);
    for v in vertices {
        let m = modulation(z - v.position.z, r);
        (weighted, mm) = (weighted + v.color * m, mm + m * m);
    }
    Ok((z, weighted / mm, z_hi - z_lo))
}

/// What a radial falloff texture brings as a function of the distance from its centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Falloff {
    /// The strength of its inverse-square falloff, as a multiple of the light's radius
    /// squared (`falloff / r²` of [`DynamicLight`]).
    pub strength: f32,
    /// Its faintest texel that is not black ([`DynamicLight::floor`]).
    pub floor: f32,
}

/// The falloff of a radial falloff texture: its strength is the median over the texels
/// between black and full of brightness times squared distance from the centre (distances
/// in widths of the texture, which spans `r`). `None` when the texture is not a radial
/// falloff: not 2D RGBA8 of at least 4 × 4 texels, brightest elsewhere than around its
/// centre, or not black at its corners.
pub fn falloff(texture: &TextureRef) -> Option<Falloff> {
    let content = &texture.content;
    let image = content.faces.first()?.first()?.as_ref()?;
    let (w, h) = (image.width as usize, image.height as usize);
    if content.kind != TextureKind::D2 || w < 4 || h < 4 || image.border != 0 || image.texels.len() < w * h * 4 {
        return None;
    }
    let brightness = |x: usize, y: usize| {
        let t = &image.texels[(y * w + x) * 4..][..3];
        f32::from(t[0].max(t[1]).max(t[2])) / 255.0
    };
    let brightest = (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).map(|(x, y)| brightness(x, y)).fold(0.0, f32::max);
    let centre = [(w - 1) / 2, w / 2].iter().flat_map(|&x| [(h - 1) / 2, h / 2].map(|y| brightness(x, y))).fold(0.0, f32::max);
    let corners = [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)].map(|(x, y)| brightness(x, y));
    if brightest <= 0.0 || centre < brightest || corners.iter().any(|&c| c > 0.0) {
        return None;
    }
    let mut strengths: Vec<f32> = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let b = brightness(x, y);
            if b > 0.0 && b < 1.0 {
                let (u, v) = ((x as f32 + 0.5) / w as f32 - 0.5, (y as f32 + 0.5) / h as f32 - 0.5);
                strengths.push(b * (u * u + v * v));
            }
        }
    }
    if strengths.is_empty() {
        return None;
    }
    strengths.sort_by(f32::total_cmp);
    let floor = (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).map(|(x, y)| brightness(x, y)).filter(|&b| b > 0.0).fold(1.0, f32::min);
    Some(Falloff { strength: strengths[strengths.len() / 2], floor })
}

/// Whether `draw`'s state is that of a dynamic-light pass: triangles of the fixed-function
/// pipeline, added or multiplied in over what is drawn (`GL_EQUAL` depth, or `GL_LEQUAL`
/// without depth writes), unit 0 alone textured with coordinates as issued. `Some(true)`
/// when it multiplies the colour under it (`GL_DST_COLOR, GL_ONE`), `Some(false)` when it adds.
fn is_candidate(draw: &Draw) -> Option<bool> {
    use BlendFactor::{DstColor, One, SrcAlpha};
    let s = &draw.state;
    let later = s.depth_test == Some(CompareFunc::Equal) || (s.depth_test == Some(CompareFunc::LessEqual) && !s.depth_write);
    let adds = s.blend.is_some_and(|b| b.equation_rgb == BlendEquation::Add && matches!((b.src_rgb, b.dst_rgb), (One, One) | (SrcAlpha, One) | (DstColor, One)));
    let unit0 = draw.texture_units.first().copied().flatten().is_some_and(|u| u.texgen.iter().all(Option::is_none));
    let candidate = later && adds && unit0 && draw.topology == Topology::Triangles && draw.program.is_none() && s.logic_op.is_none() && draw.texture_units.iter().skip(1).all(Option::is_none);
    candidate.then(|| s.blend.is_some_and(|b| b.src_rgb == DstColor))
}

/// The vertices of `draw` that its triangles use, as a pass's vertices (`None` when one lacks
/// a texture coordinate or colour, or has `w = 0`).
fn pass_vertices(draw: &Draw) -> Option<Vec<PassVertex>> {
    let mut used = vec![false; draw.vertices.len()];
    for &i in &draw.indices {
        *used.get_mut(i as usize)? = true;
    }
    let texcoords = draw.vertices.texcoords.first()?;
    let matrix = draw.texture_matrices.first().copied().flatten().unwrap_or(Mat4::IDENTITY);
    let mut out = Vec::new();
    for (i, _) in used.iter().enumerate().filter(|(_, u)| **u) {
        let p = draw.vertices.position[i];
        if p[3] == 0.0 {
            return None;
        }
        let st = matrix * glam::Vec4::from_array(texcoords.get(i)?);
        let c = draw.vertices.color.get(i)?;
        out.push(PassVertex { position: Vec3::new(p[0], p[1], p[2]) / p[3], st: [st.x / st.w, st.y / st.w], color: Vec3::new(c[0], c[1], c[2]) });
    }
    Some(out)
}

/// The passes of one light in one object space: the same modelview, centre and radius.
#[derive(Debug)]
struct Group {
    modelview: Mat4,
    /// The light as the best single pass placed it (colours checked pass by pass).
    fit: Fit,
    /// Falloff of its texture.
    falloff: Falloff,
    /// Whether its passes multiply the colour under them ([`DynamicLight::modulates`]).
    modulates: bool,
    /// The viewer's height in the object space.
    eye_height: f32,
    /// Every pass's vertices.
    vertices: Vec<PassVertex>,
}

impl Group {
    /// The light in eye space and the height spread it is placed with: the height and colour
    /// fitted to every pass's colours together (one pass over a floor 30 units lower than
    /// another's pins the height that neither does alone), else the best single pass's.
    fn light(&self) -> (DynamicLight, f32) {
        let f = &self.fit;
        let (z, color, spread) = height_and_color(&self.vertices, f.radius, self.eye_height).unwrap_or((f.origin.z, f.color, f.height_spread));
        let scale = self.modelview.x_axis.truncate().length();
        let position = self.modelview.transform_point3(f.origin.with_z(z));
        let radius = f.radius * scale;
        let axis = self.modelview.z_axis.truncate().normalize_or_zero().to_array();
        let falloff = self.falloff.strength * radius * radius;
        (DynamicLight { position: position.to_array(), color: color.to_array(), radius, falloff, axis, floor: self.falloff.floor, modulates: self.modulates }, spread * scale)
    }
}

/// The dynamic lights of one frame, in eye space (module doc); kept between frames and
/// cleared.
#[derive(Debug, Default)]
pub struct DynamicLights {
    groups: Vec<Group>,
}

impl DynamicLights {
    /// Starts a frame: no lights.
    pub fn begin_frame(&mut self) {
        self.groups.clear();
    }

    /// Whether `draw` is a dynamic-light pass; if so its light is added, or joins the passes
    /// of the same light (the same modelview, centre and radius within a thousandth of it).
    pub fn take(&mut self, draw: &Draw) -> bool {
        let Some(modulates) = is_candidate(draw) else { return false };
        let Some(falloff) = draw.textures.first().and_then(Option::as_ref).and_then(falloff) else { return false };
        let Some(vertices) = pass_vertices(draw) else { return false };
        let eye = draw.modelview.inverse().w_axis;
        let eye_height = eye.z / eye.w;
        let Ok(fit) = fit(&vertices, eye_height) else { return false };
        let same = |g: &Group| {
            let r = fit.radius;
            g.modelview == draw.modelview && g.modulates == modulates && g.fit.origin.truncate().distance(fit.origin.truncate()) < 1e-3 * r && (g.fit.radius - r).abs() < 1e-3 * r
        };
        match self.groups.iter_mut().find(|g| same(g)) {
            Some(g) => {
                if fit.height_spread < g.fit.height_spread {
                    g.fit = fit;
                }
                g.vertices.extend(vertices);
            }
            None => self.groups.push(Group { modelview: draw.modelview, fit, falloff, modulates, eye_height, vertices }),
        }
        true
    }

    /// The frame's lights: one per group, and one for groups of different object spaces
    /// whose lights meet (the same radius and hue, within half the radius), placed as the
    /// best-placed of them and as bright as the brightest.
    pub fn lights(&self) -> Vec<DynamicLight> {
        let mut out: Vec<(DynamicLight, f32)> = Vec::new();
        for (light, spread) in self.groups.iter().map(Group::light) {
            let hue = |c: [f32; 3]| Vec3::from_array(c).normalize_or_zero();
            let same = |l: &DynamicLight| {
                let close = Vec3::from_array(l.position).distance(Vec3::from_array(light.position)) < 0.5 * light.radius;
                close && hue(l.color).abs_diff_eq(hue(light.color), 0.05) && (l.radius - light.radius).abs() <= 0.01 * light.radius
            };
            match out.iter_mut().find(|(l, _)| same(l)) {
                Some((kept, kept_spread)) => {
                    let color = Vec3::from_array(kept.color).max(Vec3::from_array(light.color)).to_array();
                    if spread < *kept_spread {
                        (*kept, *kept_spread) = (light, spread);
                    }
                    kept.color = color;
                }
                None => out.push((light, spread)),
            }
        }
        out.into_iter().map(|(l, _)| l).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pass's vertices at `points`, made the ioquake3 way (`ProjectDlightTexture`) for a light
    /// at `origin` of radius `r` and colour `color`, colours rounded to 8 bits.
    fn ioquake3(points: &[Vec3], origin: Vec3, r: f32, color: Vec3) -> Vec<PassVertex> {
        let scale = 1.0 / r;
        points
            .iter()
            .map(|&p| {
                let dist = origin - p;
                let st = [0.5 + dist.x * scale, 0.5 + dist.y * scale];
                let c = (color * 255.0 * modulation(dist.z, r)).floor() / 255.0;
                PassVertex { position: p, st, color: c }
            })
            .collect()
    }

    /// A grid of `n × n` points over the square `[x0, x0 + size]²` at height `z`.
    fn floor(x0: f32, size: f32, z: f32, n: usize) -> Vec<Vec3> {
        (0..n * n).map(|k| Vec3::new(x0 + size * (k % n) as f32 / (n - 1) as f32, x0 + size * (k / n) as f32 / (n - 1) as f32, z)).collect()
    }

    /// A wall (the plane y = `y`) from z = 0 to 256.
    fn wall(y: f32, n: usize) -> Vec<Vec3> {
        (0..n * n).map(|k| Vec3::new(400.0 + 200.0 * (k % n) as f32 / (n - 1) as f32, y, 256.0 * (k / n) as f32 / (n - 1) as f32)).collect()
    }

    #[test]
    fn a_light_over_a_wall_and_a_floor_is_recovered() {
        let origin = Vec3::new(512.3, 171.7, 61.0);
        let (r, color) = (200.0, Vec3::new(1.0, 0.75, 0.0));
        let mut points = wall(120.0, 9);
        points.extend(floor(380.0, 260.0, 0.0, 9));
        let f = fit(&ioquake3(&points, origin, r, color), 40.0).expect("a fit");
        eprintln!("wall and floor: origin error {:.4}, radius error {:.5}, residual {:.2e}", f.origin.distance(origin), (f.radius - r).abs(), f.residual);
        assert!(f.origin.truncate().distance(origin.truncate()) < 0.01 && (f.radius - r).abs() < 0.01, "{f:?}");
        // The heights: the wall's vertices 100 to 200 below and above the light fix it to the
        // scan's step (1.4 units) and the colours' 8 bits.
        assert!((f.origin.z - origin.z).abs() < 3.0 && f.height_spread < 6.0, "{f:?}");
        assert!(f.color.abs_diff_eq(color, 0.01), "{f:?}");
        assert!(f.residual < 1e-5);
    }

    #[test]
    fn over_a_floor_alone_the_height_is_the_one_nearest_the_viewer_within_half_the_radius() {
        let origin = Vec3::new(100.0, -50.0, 40.0);
        let points = floor(-100.0, 300.0, 0.0, 6);
        let f = fit(&ioquake3(&points, origin, 300.0, Vec3::ONE), 56.0).expect("a fit");
        assert!(f.origin.truncate().distance(origin.truncate()) < 0.01 && (f.radius - 300.0).abs() < 0.01, "{f:?}");
        // Every height within 150 of the floor explains full colours: the viewer's.
        assert!((f.origin.z - 56.0).abs() < 1.5 && (f.height_spread - 300.0).abs() < 3.0, "{f:?}");
        let high = fit(&ioquake3(&points, origin, 300.0, Vec3::ONE), 900.0).expect("a fit");
        assert!((high.origin.z - 150.0).abs() < 1.5, "clamped to half the radius above: {high:?}");
    }

    #[test]
    fn coordinates_that_are_not_a_dynamic_light_are_rejected() {
        let origin = Vec3::new(10.0, 20.0, 30.0);
        let points = floor(0.0, 100.0, 0.0, 5);
        let good = ioquake3(&points, origin, 200.0, Vec3::ONE);
        assert!(fit(&good, 0.0).is_ok());
        // A texture mapped by the surface's own coordinates (growing with x: not centred).
        let planar: Vec<PassVertex> = good.iter().map(|v| PassVertex { st: [v.position.x / 64.0, v.position.y / 64.0], ..*v }).collect();
        assert_eq!(fit(&planar, 0.0), Err(Reject::NotCentred));
        // Different scales along s and t.
        let stretched: Vec<PassVertex> = good.iter().map(|v| PassVertex { st: [v.st[0], 0.5 + (v.st[1] - 0.5) * 2.0], ..*v }).collect();
        assert_eq!(fit(&stretched, 0.0), Err(Reject::Texcoords));
        // Noise of a hundredth of the square on the coordinates.
        let noisy: Vec<PassVertex> = good.iter().enumerate().map(|(i, v)| PassVertex { st: [v.st[0] + if i % 2 == 0 { 0.01 } else { -0.01 }, v.st[1]], ..*v }).collect();
        assert_eq!(fit(&noisy, 0.0), Err(Reject::Texcoords));
        // Black, and colours that no height explains (bright far below, dark near).
        let black: Vec<PassVertex> = good.iter().map(|v| PassVertex { color: Vec3::ZERO, ..*v }).collect();
        assert_eq!(fit(&black, 0.0), Err(Reject::Colors));
        let wall = ioquake3(&wall(0.0, 5), Vec3::new(500.0, 100.0, 128.0), 200.0, Vec3::ONE);
        let inverted: Vec<PassVertex> = wall.iter().map(|v| PassVertex { color: Vec3::ONE - v.color, ..*v }).collect();
        assert_eq!(fit(&inverted, 128.0), Err(Reject::Colors));
        assert_eq!(fit(&good[..2], 0.0), Err(Reject::Degenerate));
        let line: Vec<PassVertex> = good.iter().map(|v| PassVertex { position: Vec3::new(5.0, 5.0, v.position.z), ..*v }).collect();
        assert_eq!(fit(&line, 0.0), Err(Reject::Degenerate));
    }

    #[test]
    fn passes_over_floors_at_two_heights_pin_the_height_together() {
        // 78.5 above one floor and 110.5 above the other: neither floor alone fixes the height
        // (every height within 100 of the first gives it full colour), both do.
        let origin = Vec3::new(832.7, 212.7, 78.5);
        let (r, color) = (200.0, Vec3::new(1.0, 0.75, 0.0));
        let high = ioquake3(&floor(700.0, 200.0, 0.0, 5), origin, r, color);
        let low = ioquake3(&floor(760.0, 150.0, -32.0, 5), origin, r, color);
        let alone = fit(&high, 60.0).expect("a fit");
        assert!(alone.height_spread > 150.0, "{alone:?}");
        let fit = fit(&low, 60.0).expect("a fit");
        let falloff = Falloff { strength: 0.06, floor: 0.3 };
        let group = Group { modelview: Mat4::IDENTITY, fit, falloff, modulates: false, eye_height: 60.0, vertices: [high, low].concat() };
        let (light, spread) = group.light();
        eprintln!("two floors: height {:.2} (spread {spread:.2}), colour {:?}", light.position[2], light.color);
        assert!((light.position[2] - 78.5).abs() < 1.5 && spread < 3.0, "{light:?}");
        assert!(Vec3::from_array(light.color).abs_diff_eq(color, 0.01) && (light.falloff - 0.06 * r * r).abs() < 1.0, "{light:?}");
        assert_eq!((light.axis, light.floor, light.modulates), ([0.0, 0.0, 1.0], 0.3, false), "projected along the object's z");
    }

    /// Quake 3's dynamic light image (`R_CreateDlightImage`): 16 × 16, 4000 / d² of the
    /// squared texel distance from the centre, clamped to 255, 0 below 75.
    fn q3_image() -> Vec<u8> {
        (0..256)
            .flat_map(|k| {
                let (x, y) = ((k % 16) as f32, (k / 16) as f32);
                let d = (8.0 - x - 0.5).powi(2) + (8.0 - y - 0.5).powi(2);
                let b = (4000.0 / d).min(255.0);
                let b = if b < 75.0 { 0 } else { b as u8 };
                [b, b, b, 255]
            })
            .collect()
    }

    fn texture(size: u32, texels: Vec<u8>) -> TextureRef {
        use crate::frame::texture::{TexImage, TextureContent};
        let image = TexImage { width: size, height: size, depth: 1, texels, ..TexImage::default() };
        let content = TextureContent { kind: TextureKind::D2, faces: vec![vec![Some(std::sync::Arc::new(image))]], ..TextureContent::default() };
        TextureRef { id: 1, version: 1, content: std::sync::Arc::new(content) }
    }

    #[test]
    fn quake_3s_falloff_texture_is_a_radial_falloff_of_its_strength() {
        // 4000 / d² over 255, with d in texels (16 per r): 4000 / (255 · 256) of r².
        let k = falloff(&texture(16, q3_image())).expect("a falloff");
        assert!((k.strength - 4000.0 / (255.0 * 256.0)).abs() < 0.002, "{k:?}");
        // The faintest texel: 4000 / (4.5² + 5.5²) = 79.2 (the next, 6.5² + 3.5², gives 73: black).
        assert_eq!(k.floor, 79.0 / 255.0, "{k:?}");
        assert_eq!(falloff(&texture(16, vec![255; 16 * 16 * 4])), None, "white: not black at the corners");
        let mut off_centre = q3_image();
        off_centre[..4].copy_from_slice(&[255; 4]);
        assert_eq!(falloff(&texture(16, off_centre)), None, "a bright corner");
    }
}
