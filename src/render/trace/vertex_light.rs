//! The light a vertex-lit model's colours hold (issue 16). Quake-3-class engines light a model
//! on the CPU, per vertex, as `ambient + max(0, n · l) · directed` (a light grid sampled at
//! the model's origin, `RB_CalcDiffuseColor`), and hash tracking marks such a draw
//! [`SurfaceLighting::VertexLit`]: it is traced with its texture as albedo, lit by the light
//! [`recover`] finds in its colours. Both parts are the level's light at the model, which no
//! traced source holds as the game shows it: the directed part is its direct light (the sun,
//! lamps: baked into the lightmaps, not drawn), the ambient part the light from everywhere
//! else (the grid's share of the world's bounced light, the sky, the level's lamps seen from
//! afar). Traced light from the baked world is a weak stand-in for the latter in a dark level,
//! and both together would count that light twice.
//!
//! So the model keeps both parts: the directed part as a directional light of that instance
//! alone ([`GpuLight`] `params.w`), sampled by next-event estimation like a GL light (it
//! lights the diffuse lobe alone: the game's lighting is Lambertian), with shadow rays as long
//! as the model is wide (its own parts shadow it; the level's occlusion is already in the
//! game's grid); the ambient part as radiance arriving from every direction
//! ([`ModelLight::ambient`], the material's `ambient`): `shaders/trace/path.glsl` gives it to
//! the model's continuation rays that meet nothing within the model's width, in place of the
//! level's traced light (rays that meet its own parts or the floor under it within that width
//! go on: occlusion and bounce light between them), and samples neither the sky nor emitters
//! from it (their light is in its colours, as the dynamic lights' is, [`super::lights`]).
//!
//! Games also tint models through the same colours (OpenArena's green player coats: the
//! colours are the light times the coat's colour). Light alone would leave that hue out of a
//! traced model, whose albedo is its texture, so the albedo keeps the colours' common hue,
//! [`tint`] (their mean colour scaled to a brightest channel of 1: a chromaticity, the light's
//! strength left out), and the light [`recover`] finds (both parts) is divided by it, so that
//! the model is lit as brightly as before and its hue comes from its colours.
//!
//! [`recover`] fits that lighting model to the draw's vertex colours and normals (the draw's
//! own, else the smoothed normals of its triangles). Draws whose colours do not follow their
//! normals (painted colours, a constant colour, lighting the fit cannot explain) get no light
//! of their own: traced light lights them.

use std::collections::HashMap;

use glam::{DMat3, DMat4, DVec3, DVec4, Mat3, Mat4, Vec3};

use super::gpu_types::GpuLight;
use super::scene::srgb_to_linear;
use crate::frame::{Draw, Topology};

/// The fit must explain at least this fraction of the variance of the vertices' brightness:
/// colours unrelated to the normals explain less than 0.06, a game's lighting seen through
/// normals smoothed from the triangles (not the model's own, which the game lit) 0.45–0.99
/// (the 24 vertex-lit draws of OpenArena's frame 400 of the benchmark demo). The lowest are
/// models under overbright light: their red and green reach 1 a little past the terminator,
/// so their colours are nearly a step from the ambient to 1, and the smoothed normals put a
/// tenth of their vertices on the wrong side of it (the player's hat: 0.46).
const MIN_EXPLAINED: f64 = 0.3;

/// Vertices a fit needs at least.
const MIN_VERTICES: usize = 8;

/// Refinements of the light's direction after the first, linear fit.
const REFINEMENTS: usize = 3;

/// The lighting `ambient + max(0, n · towards) · directed` that a model's colours hold, as
/// [`fit`] finds it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexLighting {
    /// Unit direction towards the light, eye space.
    pub towards: Vec3,
    /// Ambient colour (display-encoded, 0..1): what the vertices facing away from the light
    /// show, no brighter in any channel than the darkest vertex.
    pub ambient: Vec3,
    /// The directed light's irradiance over π (linear): what it adds to the linear radiance of
    /// a white Lambertian surface facing it. Chosen so that the linear radiance of the
    /// vertices lit as `linear(ambient) + max(0, n · towards) · irradiance` sums to that of
    /// their colours ([`directed_irradiance`]).
    pub irradiance: Vec3,
}

/// Vertices at one place whose own normals (smoothed over their own triangles) are at most
/// this far apart (cosine: 60°) share their normal: apart is a hard edge (a box's corner).
const SMOOTHING_COSINE: f32 = 0.5;

/// The per-vertex unit normals of `draw` in eye space (`object_to_eye`): its own normals when
/// it has one per vertex, else the area-weighted normals of the triangles around each
/// position, turned away from its centre. Vertices at one place share their normal unless
/// they meet at a hard edge ([`SMOOTHING_COSINE`]): models repeat the vertices of their
/// texture seams, whose normals the game keeps continuous (on OpenArena's player models,
/// normals smoothed on each side of a seam alone explain 0.43–0.75 of the colours' variance,
/// smoothed across it 0.61–0.84).
fn eye_normals(draw: &Draw, object_to_eye: &Mat4) -> Option<Vec<DVec3>> {
    let n = draw.vertices.len();
    let object: Vec<Vec3> = if draw.vertices.normal.values.len() == n && n > 1 {
        draw.vertices.normal.values.iter().map(|&v| Vec3::from(v)).collect()
    } else if draw.topology == Topology::Triangles {
        let position = |i: u32| Vec3::from_slice(&draw.vertices.position[i as usize][..3]);
        let mut own = vec![Vec3::ZERO; n];
        for t in draw.indices.chunks_exact(3) {
            if t.iter().any(|&i| i as usize >= n) {
                return None;
            }
            let face = (position(t[1]) - position(t[0])).cross(position(t[2]) - position(t[0]));
            t.iter().for_each(|&i| own[i as usize] += face);
        }
        // The vertices at each place (-0 and 0 one place).
        let place = |i: u32| position(i).to_array().map(|c| (c + 0.0).to_bits());
        let mut at: HashMap<[u32; 3], Vec<usize>> = HashMap::with_capacity(n);
        (0..n as u32).for_each(|i| at.entry(place(i)).or_default().push(i as usize));
        let mut sum: Vec<Vec3> = (0..n as u32)
            .map(|i| {
                // A vertex of degenerate triangles alone takes the normal of its place.
                let d = own[i as usize].normalize_or_zero();
                let shared = |o: &Vec3| d == Vec3::ZERO || o.normalize_or_zero().dot(d) >= SMOOTHING_COSINE;
                at[&place(i)].iter().map(|&j| own[j]).filter(shared).sum()
            })
            .collect();
        // Windings differ between programs (Quake 3's front faces are clockwise): the normals
        // point away from the model's centre.
        let centre = (0..n as u32).map(position).sum::<Vec3>() / n.max(1) as f32;
        let outwards: f32 = sum.iter().enumerate().map(|(i, s)| s.dot(position(i as u32) - centre)).sum();
        if outwards < 0.0 {
            sum.iter_mut().for_each(|s| *s = -*s);
        }
        sum
    } else {
        return None;
    };
    let to_eye = Mat3::from_mat4(*object_to_eye).inverse().transpose();
    Some(object.iter().map(|&v| (to_eye * v).as_dvec3().normalize_or_zero()).collect())
}

/// Least-squares `a + g · n` of `y` over `(n, y)`: `(a, g)`; with `ambient` given, only `g`.
fn linear_fit(samples: impl Iterator<Item = (DVec3, f64)> + Clone, ambient: Option<f64>) -> Option<(f64, DVec3)> {
    match ambient {
        None => {
            let (mut m, mut b) = (DMat4::ZERO, DVec4::ZERO);
            for (n, y) in samples {
                let x = DVec4::new(1.0, n.x, n.y, n.z);
                m += DMat4::from_cols(x * x.x, x * x.y, x * x.z, x * x.w);
                b += x * y;
            }
            (m.determinant().abs() > 1e-9).then(|| m.inverse() * b).map(|s| (s.x, DVec3::new(s.y, s.z, s.w)))
        }
        Some(a) => {
            let (mut m, mut b) = (DMat3::ZERO, DVec3::ZERO);
            for (n, y) in samples {
                m += DMat3::from_cols(n * n.x, n * n.y, n * n.z);
                b += n * (y - a);
            }
            (m.determinant().abs() > 1e-9).then(|| (a, m.inverse() * b))
        }
    }
}

/// Fits `ambient + max(0, n · l) · directed` to `colours` (display-encoded RGB) at unit
/// `normals`: a linear fit of the brightness gives a first direction, then, a few times, the
/// colours are regressed on `max(0, n · l)` (ambient and directed per channel) and the
/// direction refitted on the lit vertices. `None` when the fit explains less than
/// [`MIN_EXPLAINED`] of the brightness's variance or finds no directed light.
///
/// The ambient is then capped at the darkest colour of each channel: the game's lighting
/// makes no vertex darker than its ambient, but the fit's constant part overestimates it
/// where the normals it sees put lit vertices on the shadowed side (OpenArena frame 400: up to
/// 0.48 where every model's darkest vertex is 0.31). The directed light's strength follows
/// from the colours and that ambient ([`directed_irradiance`]).
pub fn fit(normals: &[DVec3], colours: &[DVec3]) -> Option<VertexLighting> {
    let brightness = |c: &DVec3| c.x + c.y + c.z;
    let samples = normals.iter().zip(colours).filter(|(n, _)| n.length_squared() > 0.5).map(|(&n, c)| (n, c));
    let count = samples.clone().count() as f64;
    if count < MIN_VERTICES as f64 {
        return None;
    }
    let mean = samples.clone().map(|(_, c)| brightness(c)).sum::<f64>() / count;
    let total: f64 = samples.clone().map(|(_, c)| (brightness(c) - mean).powi(2)).sum();
    if total <= 1e-6 * count {
        return None;
    }
    let (_, g) = linear_fit(samples.clone().map(|(n, c)| (n, brightness(c))), None)?;
    let mut towards = g.try_normalize()?;
    let mut lighting = None;
    for _ in 0..=REFINEMENTS {
        let x = |n: DVec3| n.dot(towards).max(0.0);
        let mean_x = samples.clone().map(|(n, _)| x(n)).sum::<f64>() / count;
        let mean_c = samples.clone().map(|(_, &c)| c).sum::<DVec3>() / count;
        let var_x: f64 = samples.clone().map(|(n, _)| (x(n) - mean_x).powi(2)).sum();
        if var_x <= 1e-9 {
            return None;
        }
        let cov: DVec3 = samples.clone().map(|(n, &c)| (c - mean_c) * (x(n) - mean_x)).sum();
        let directed = cov / var_x;
        let ambient = mean_c - directed * mean_x;
        lighting = Some((ambient, directed));
        // The direction again, from the vertices the light reaches.
        let lit = samples.clone().filter(|(n, _)| x(*n) > 0.05).map(|(n, c)| (n, brightness(c)));
        match linear_fit(lit, Some(brightness(&ambient))).and_then(|(_, g)| g.try_normalize()) {
            Some(t) => towards = t,
            None => break,
        }
    }
    let (ambient, directed) = lighting?;
    let predicted = |n: DVec3| brightness(&(ambient + directed * n.dot(towards).max(0.0)));
    let residual: f64 = samples.clone().map(|(n, c)| (brightness(c) - predicted(n)).powi(2)).sum();
    if 1.0 - residual / total < MIN_EXPLAINED || brightness(&directed.max(DVec3::ZERO)) <= 1e-3 {
        return None;
    }
    let darkest = samples.clone().fold(DVec3::ONE, |d, (_, c)| d.min(*c)).max(DVec3::ZERO);
    let ambient = ambient.clamp(DVec3::ZERO, darkest).as_vec3();
    let towards = towards.as_vec3();
    let irradiance = directed_irradiance(samples.map(|(n, c)| (n.as_vec3(), c.as_vec3())), towards, ambient)?;
    Some(VertexLighting { towards, ambient, irradiance })
}

/// Display-encoded RGB to linear.
fn linear(v: Vec3) -> Vec3 {
    Vec3::new(srgb_to_linear(v.x), srgb_to_linear(v.y), srgb_to_linear(v.z))
}

/// The irradiance over π of a directed light from `towards` that, with `ambient`, makes the
/// vertices' linear radiance (`linear(ambient) + max(0, n · towards) · irradiance` on a white
/// Lambertian surface) sum to their colours' in each channel. The game adds its directed
/// colour in display units and clamps it at 1: a linear light that matched it where it falls
/// straight on the surface would leave the rest of the lit side darker than the game shows it
/// (display values grow faster than linear ones), the more so where the colours saturate, as
/// under overbright light. `None` when no vertex faces the light.
fn directed_irradiance(samples: impl Iterator<Item = (Vec3, Vec3)>, towards: Vec3, ambient: Vec3) -> Option<Vec3> {
    let base = linear(ambient);
    let (cosines, added) = samples.fold((0.0f32, Vec3::ZERO), |(x, sum), (n, c)| (x + n.dot(towards).max(0.0), sum + linear(c) - base));
    (cosines > 1e-6).then(|| (added / cosines).max(Vec3::ZERO))
}

/// The common hue of `draw`'s vertex colours (display-encoded): their mean RGB over its
/// brightest channel, white when they are black or the draw has no colour per vertex. The
/// albedo of a vertex-lit model takes it for the colours' RGB
/// ([`super::material::material`]).
pub fn tint(draw: &Draw) -> Vec3 {
    let colours = &draw.vertices.color.values;
    if colours.len() != draw.vertices.len() || colours.is_empty() {
        return Vec3::ONE;
    }
    let mean = colours.iter().map(|c| Vec3::new(c[0], c[1], c[2])).sum::<Vec3>() / colours.len() as f32;
    let brightest = mean.max_element();
    if brightest < 1.0 / 255.0 { Vec3::ONE } else { (mean / brightest).clamp(Vec3::ZERO, Vec3::ONE) }
}

/// The smallest linear tint a light is divided by (a channel the colours hardly have).
const MIN_TINT: f32 = 1.0 / 256.0;

/// The light of a vertex-lit model's colours ([`recover`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelLight {
    /// The directed part: a directional light of the model's instance alone.
    pub directed: GpuLight,
    /// The ambient part: linear radiance arriving from every direction (rgb), divided by the
    /// linear [`tint`] as the directed part is; a: the model's width, in eye space (how far
    /// its continuation rays look for its own parts before they take this radiance).
    pub ambient: [f32; 4],
}

/// The light that `draw`'s vertex colours hold, for instance `instance` (its index in the
/// frame's instances), seen through `object_to_eye` (see the module doc), both parts divided
/// by the linear [`tint`] the model's albedo holds: the directed part's irradiance is π times
/// [`VertexLighting::irradiance`] (a white Lambertian model lit by it and the ambient is as
/// bright, in linear light summed over its vertices, as its colours); the ambient radiance
/// `linear(ambient)` is what a white Lambertian surface reflects under it, as the game shows
/// the ambient colour.
pub fn recover(draw: &Draw, object_to_eye: &Mat4, instance: u32) -> Option<ModelLight> {
    let colours = &draw.vertices.color.values;
    if colours.len() != draw.vertices.len() {
        return None;
    }
    let normals = eye_normals(draw, object_to_eye)?;
    let colours: Vec<DVec3> = colours.iter().map(|c| DVec3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2]))).collect();
    let lighting = fit(&normals, &colours)?;
    let tint = linear(tint(draw)).max(Vec3::splat(MIN_TINT));
    let irradiance = lighting.irradiance * std::f32::consts::PI / tint;
    let ambient = linear(lighting.ambient) / tint;
    // Shadow rays as long as the model is wide, in eye space.
    let points: Vec<Vec3> = draw.vertices.position.iter().map(|p| object_to_eye.project_point3(Vec3::from_slice(&p[..3]))).collect();
    let centre = points.iter().copied().sum::<Vec3>() / points.len().max(1) as f32;
    let width = 2.0 * points.iter().map(|p| p.distance(centre)).fold(0.0, f32::max);
    Some(ModelLight {
        directed: GpuLight {
            position: [lighting.towards.x, lighting.towards.y, lighting.towards.z, 0.0],
            radiance: [irradiance.x, irradiance.y, irradiance.z, 0.0],
            spot: [0.0, 0.0, 0.0, -2.0],
            params: [0.0, 1.0, width, (instance + 1) as f32],
        },
        ambient: [ambient.x, ambient.y, ambient.z, width],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unit normals spread over the sphere (a Fibonacci lattice).
    fn sphere(n: usize) -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
                let phi = i as f64 * 2.399963;
                let r = (1.0 - z * z).sqrt();
                DVec3::new(r * phi.cos(), r * phi.sin(), z)
            })
            .collect()
    }

    #[test]
    fn the_game_s_lighting_is_recovered_from_colours_and_normals() {
        let normals = sphere(200);
        let towards = DVec3::new(0.3, 0.8, -0.5).normalize();
        let (ambient, directed) = (DVec3::new(0.2, 0.18, 0.15), DVec3::new(0.5, 0.45, 0.3));
        let colours: Vec<DVec3> = normals.iter().map(|n| ambient + directed * n.dot(towards).max(0.0)).collect();
        let l = fit(&normals, &colours).expect("a light");
        assert!(l.towards.as_dvec3().dot(towards) > 0.999, "{l:?}");
        assert!((l.ambient.as_dvec3() - ambient).abs().max_element() < 0.01, "{l:?}");
        // The light makes the vertices as bright in linear light as their colours, summed.
        let lit = |c: DVec3| linear(c.as_vec3()).as_dvec3();
        let sum = |f: &dyn Fn(DVec3, DVec3) -> DVec3| normals.iter().zip(&colours).map(|(&n, &c)| f(n, c)).sum::<DVec3>();
        let shown = sum(&|n, _| lit(ambient) + l.irradiance.as_dvec3() * n.dot(l.towards.as_dvec3()).max(0.0));
        let held = sum(&|_, c| lit(c));
        assert!((shown - held).abs().max_element() < 1e-3 * held.min_element(), "{shown} against {held}");
        // Less than matched where the light falls straight (a display value grows faster than
        // its linear value: (0.322, 0.255, 0.122) against (0.415, 0.327, 0.151)).
        let straight = lit(ambient + directed) - lit(ambient);
        assert!((l.irradiance.as_dvec3() / straight).cmpge(DVec3::splat(0.7)).all() && l.irradiance.as_dvec3().cmplt(straight).all(), "{l:?} against {straight}");
    }

    #[test]
    fn a_box_whose_faces_have_their_own_vertices_keeps_its_hard_edges() {
        // A cube, each face its own four corners (as the q3 demo's players are built).
        let mut draw = Draw::default();
        for axis in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z] {
            let t1 = if axis.x.abs() > 0.5 { Vec3::Y } else { Vec3::X };
            let t2 = axis.cross(t1);
            let base = draw.vertices.len() as u32;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                let p = axis + t1 * a + t2 * b;
                draw.vertices.position.push([p.x, p.y, p.z, 1.0]);
            }
            draw.indices.extend([0, 1, 2, 0, 2, 3].map(|k| base + k));
        }
        let normals = eye_normals(&draw, &Mat4::IDENTITY).expect("normals");
        for (face, axis) in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z].into_iter().enumerate() {
            for n in &normals[face * 4..face * 4 + 4] {
                assert!(n.dot(axis.as_dvec3()) > 1.0 - 1e-9, "face {face}: {n}");
            }
        }
    }

    /// The colours the game gives vertices of `normals` under `ambient` and `directed` light
    /// from `towards`, lit through its own normals: each of ours turned by a pseudo-random
    /// offset of up to `turn` per axis.
    fn game_colours(normals: &[DVec3], turn: f64, towards: DVec3, ambient: DVec3, directed: DVec3) -> Vec<DVec3> {
        (0u64..)
            .zip(normals)
            .map(|(i, &n)| {
                let offset = DVec3::from_array(std::array::from_fn(|k| ((i * 2654435761 + k as u64 * 40503) % 1000) as f64 / 500.0 - 1.0));
                let game = (n + turn * offset).normalize();
                (ambient + directed * game.dot(towards).max(0.0)).min(DVec3::ONE)
            })
            .collect()
    }

    #[test]
    fn lighting_through_normals_other_than_the_game_s_is_still_recovered() {
        // The game lit its own normals (here each turned by up to ~30°, as a model's stored
        // normals differ from those smoothed from its triangles); the fit sees the others.
        let normals = sphere(300);
        let towards = DVec3::new(0.3, 0.8, -0.5).normalize();
        let (ambient, directed) = (DVec3::new(0.3, 0.28, 0.22), DVec3::new(0.9, 0.85, 0.5));
        let colours = game_colours(&normals, 0.6, towards, ambient, directed);
        let l = fit(&normals, &colours).expect("a light");
        assert!(l.towards.as_dvec3().dot(towards) > 0.99, "{l:?}");
        // The ambient is the game's (the fit's constant part, 0.36, is capped at the darkest
        // colour), and the directed light within a quarter of the game's where it falls
        // straight (1.12, 1.01 and 0.83 of it).
        assert!((l.ambient.as_dvec3() - ambient).abs().max_element() < 1e-6, "{l:?}");
        let straight = linear((ambient + directed).min(DVec3::ONE).as_vec3()) - linear(ambient.as_vec3());
        let ratio = l.irradiance / straight;
        assert!(ratio.cmpgt(Vec3::splat(0.75)).all() && ratio.cmplt(Vec3::splat(1.25)).all(), "{l:?} against {straight}");
    }

    #[test]
    fn overbright_lighting_through_normals_other_than_the_game_s_is_recovered_with_its_ambient() {
        // As OpenArena lights its player's hat in frame 400 of the benchmark demo: red and green
        // reach 1 a little past the terminator (the game's directed colour is three times the
        // range), and the normals the fit sees put many vertices on the wrong side of it (each
        // of the game's turned by up to ~60°). The colours explain 0.46 of the brightness's
        // variance, and the darkest vertex shows the game's ambient.
        let normals = sphere(300);
        let towards = DVec3::new(0.3, 0.8, -0.5).normalize();
        let (ambient, directed) = (DVec3::new(0.314, 0.282, 0.22), DVec3::new(3.2, 3.3, 0.6));
        let colours = game_colours(&normals, 1.0, towards, ambient, directed);
        let l = fit(&normals, &colours).expect("a light");
        assert!(l.towards.as_dvec3().dot(towards) > 0.9, "{l:?}");
        assert!((l.ambient.as_dvec3() - ambient).abs().max_element() < 1e-6, "the game's ambient: {l:?}");
        // Matched in the sum, the lit side is brighter than 1 where the light falls straight
        // (the game shows 1 over most of it): about 1.8 in red and green.
        assert!(l.irradiance.x > 1.5 && l.irradiance.y > 1.5, "{l:?}");
    }

    #[test]
    fn colours_that_do_not_follow_the_normals_hold_no_light() {
        let normals = sphere(200);
        let constant = vec![DVec3::splat(0.6); 200];
        assert_eq!(fit(&normals, &constant), None, "one colour");
        // Painted: a colour per vertex from a hash, unrelated to the normal.
        let painted: Vec<DVec3> = (0..200u64).map(|i| DVec3::splat(((i * 2654435761) % 1000) as f64 / 1000.0)).collect();
        assert_eq!(fit(&normals, &painted), None, "painted colours");
    }

    #[test]
    fn a_lit_octahedron_gives_a_light_of_its_instance_with_the_linear_difference_as_irradiance() {
        // An octahedron, its vertices' normals smoothed from its faces: the six axes.
        let mut draw = Draw::default();
        let corners = [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
        // Four copies of each corner, slightly apart, so that there are enough vertices.
        for k in 0..4 {
            for c in corners {
                draw.vertices.position.push([c[0] * (1.0 + 0.01 * k as f32), c[1], c[2], 1.0]);
            }
        }
        for k in 0..4u32 {
            let o = 6 * k;
            for (a, b, c) in [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)] {
                draw.indices.extend([o + a, o + b, o + c]);
            }
        }
        draw.vertex_count = draw.vertices.len();
        // Lit from +x: the +x corners get ambient + directed, the others ambient.
        let colour = |p: [f32; 4]| if p[0] > 0.5 { [0.25 + 0.5, 0.25 + 0.5, 0.25 + 0.5, 1.0] } else { [0.25, 0.25, 0.25, 1.0] };
        draw.vertices.color.values = draw.vertices.position.iter().map(|&p| colour(p)).collect();
        let recovered = recover(&draw, &Mat4::from_translation(Vec3::new(0.0, 0.0, -5.0)), 7).expect("a light");
        let light = recovered.directed;
        assert!(light.position[0] > 0.95 && light.position[3] == 0.0, "{light:?}");
        // Wound the other way, the same light.
        let mut clockwise = draw.clone();
        clockwise.indices.chunks_exact_mut(3).for_each(|t| t.swap(0, 1));
        assert_eq!(recover(&clockwise, &Mat4::from_translation(Vec3::new(0.0, 0.0, -5.0)), 7), Some(recovered));
        assert_eq!(light.params[3], 8.0, "instance 7 alone");
        assert!((light.params[2] - 2.0).abs() < 0.1, "shadow rays as long as the model is wide: {light:?}");
        let expected = std::f32::consts::PI * (srgb_to_linear(0.75) - srgb_to_linear(0.25));
        assert!((light.radiance[0] - expected).abs() < 0.02 * expected, "{light:?}, expected {expected}");
        assert_eq!(tint(&draw), Vec3::ONE, "grey colours: no hue");
        // The ambient part: linear(0.25) from every direction, what the game shows on the
        // corners the directed light does not reach, in rays as long as the model is wide.
        let ambient = srgb_to_linear(0.25);
        assert!(recovered.ambient[..3].iter().all(|a| (a - ambient).abs() < 0.02 * ambient), "{recovered:?}, expected {ambient}");
        assert_eq!(recovered.ambient[3], light.params[2], "ambient rays as long as the shadow rays");

        // The same light through a green coat: the colours times (0.35, 1, 0.35).
        let green = Vec3::new(0.35, 1.0, 0.35);
        let mut coated = draw.clone();
        coated.vertices.color.values.iter_mut().for_each(|c| *c = [c[0] * green.x, c[1], c[2] * green.z, c[3]]);
        assert!(tint(&coated).abs_diff_eq(green, 1e-5), "{}", tint(&coated));
        let coat = recover(&coated, &Mat4::from_translation(Vec3::new(0.0, 0.0, -5.0)), 7).expect("a light");
        let through = coat.directed;
        assert!((through.radiance[1] - expected).abs() < 0.02 * expected, "green as before: {through:?}");
        // Red: what the coat's colours add, once the albedo multiplies the tint back.
        let red = std::f32::consts::PI * (srgb_to_linear(0.75 * green.x) - srgb_to_linear(0.25 * green.x));
        assert!((through.radiance[0] * srgb_to_linear(green.x) - red).abs() < 0.02 * red, "{through:?}, expected {red} / tint");
        // The ambient part likewise: green as before, red once the albedo multiplies the tint.
        assert!((coat.ambient[1] - ambient).abs() < 0.02 * ambient, "{coat:?}");
        let red = srgb_to_linear(0.25 * green.x);
        assert!((coat.ambient[0] * srgb_to_linear(green.x) - red).abs() < 0.02 * red, "{coat:?}, expected {red} / tint");
    }

    /// A sphere of `rows` × `columns` quads lit as Quake 3 lights a model (ambient + max(0,
    /// n · l) × directed, clamped to 1, with the smooth normals of the sphere): its vertices
    /// shared between the triangles, or (`split`) three of its own for every triangle, as a
    /// model that repeats the vertices of its texture seams, here everywhere.
    fn lit_sphere(rows: usize, columns: usize, split: bool) -> Draw {
        let towards = Vec3::new(0.6, 0.7, 0.4).normalize();
        // The poles exactly at the poles (their triangles of zero area).
        let point = |r: usize, c: usize| match r {
            0 => Vec3::Y,
            r if r == rows => -Vec3::Y,
            r => {
                let (theta, phi) = (std::f32::consts::PI * r as f32 / rows as f32, std::f32::consts::TAU * c as f32 / columns as f32);
                Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin())
            }
        };
        let mut corners = Vec::new();
        for r in 0..rows {
            for c in 0..columns {
                let [a, b, d, e] = [(r, c), (r + 1, c), (r + 1, c + 1), (r, c + 1)];
                corners.extend([a, b, d, a, d, e]);
            }
        }
        let mut draw = Draw::default();
        let mut index = std::collections::HashMap::new();
        for (r, c) in corners {
            let p = point(r, c % columns);
            let key = if split { draw.indices.len() } else { r * columns + c % columns };
            let i = *index.entry(key).or_insert_with(|| {
                let light = (0.3 + 0.9 * p.dot(towards).max(0.0)).min(1.0);
                draw.vertices.position.push([p.x, p.y, p.z, 1.0]);
                draw.vertices.color.values.push([light, light * 0.95, light * 0.7, 1.0]);
                draw.vertices.position.len() as u32 - 1
            });
            draw.indices.push(i);
        }
        draw.vertex_count = draw.vertices.len();
        draw
    }

    #[test]
    fn a_model_whose_vertices_repeat_at_its_seams_has_the_normals_and_light_of_one_without() {
        let eye = Mat4::from_translation(Vec3::new(0.0, 0.0, -5.0));
        let (shared, split) = (lit_sphere(8, 12, false), lit_sphere(8, 12, true));
        assert_eq!(split.vertices.len(), split.indices.len());
        // Each split vertex has the normal of the shared vertex at its place.
        let (smooth, normals) = (eye_normals(&shared, &eye).expect("normals"), eye_normals(&split, &eye).expect("normals"));
        let at = |draw: &Draw, i: usize| Vec3::from_slice(&draw.vertices.position[i][..3]);
        for (i, n) in normals.iter().enumerate() {
            let j = (0..shared.vertices.len()).find(|&j| at(&shared, j) == at(&split, i)).expect("the same place");
            assert!(n.dot(smooth[j]) > 1.0 - 1e-9, "vertex {i}: {n} against {}", smooth[j]);
        }
        // And the light of the game's lighting.
        let towards = Vec3::new(0.6, 0.7, 0.4).normalize();
        for draw in [&shared, &split] {
            let light = recover(draw, &eye, 3).expect("a light");
            assert!(Vec3::from_slice(&light.directed.position[..3]).dot(towards) > 0.995, "{light:?}");
            // The ambient (0.3, 0.285, 0.21) over the tint (1, 0.95, 0.7): linear(0.3) in
            // each channel, from every direction (the colours clamped to 1 where the light is
            // strongest raise the fitted ambient by up to 0.02 in display terms: 17 % linear).
            let ambient = srgb_to_linear(0.3);
            assert!(light.ambient[..3].iter().all(|a| (a - ambient).abs() < 0.2 * ambient), "{light:?}, expected {ambient}");
        }
    }
}
