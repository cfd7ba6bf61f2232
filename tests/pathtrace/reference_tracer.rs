//! An independent CPU path tracer: the reference the GPU path tracer (`GLRT_MODE=pathtrace`) is
//! compared with in the physics tests. It shares no code with `src/` or `shaders/` (std and glam
//! only), so a mistake in the shaders cannot hide in both.
//!
//! # Conventions (the GPU tracer follows the same)
//!
//! - **Space and camera.** Everything is in OpenGL eye space: the eye at the origin looking down
//!   −z, +y up. The projection is a `glFrustum` ([`Camera`]); the ray of a point of the image goes
//!   from the origin through the corresponding point of the near plane. Geometry is never clipped
//!   by the near or far plane here, so scenes keep it between them.
//! - **Pixels.** Pixel `(x, y)` has `y = 0` at the *bottom* (GL window coordinates). Its value is
//!   the mean radiance over its area (box filter): each sample takes a uniform point of the pixel.
//! - **Surfaces.** Lambertian, albedo in linear RGB (a GL colour `c` is display-encoded: the albedo
//!   is [`srgb_to_linear`]`(c)`), two-sided: both faces reflect alike. Quads are planar and
//!   convex, corners in order; a quad or triangle's *front* is the side from which its corners run
//!   counter-clockwise (GL's default front face), a sphere's front is outside.
//! - **Emitters.** A surface may emit a constant radiance `emission` from its front only. Emitters
//!   seen straight from the eye are counted on that hit; after the first hit, emitted light is
//!   counted only by next-event estimation (a uniform point of the emitter's area and a shadow
//!   ray), never when a sampled continuation ray happens to hit an emitter. Both estimate the same
//!   integral; counting one way only keeps each light path counted exactly once.
//! - **Lights** ([`Light`]) are physical quantities, whatever GL light produced them: a directional
//!   light gives irradiance `E` on a surface facing it (optionally a sun disc of angular radius
//!   `α`, sampled uniformly in its cone), a point light has intensity `I` (W/sr, irradiance
//!   `I·cosθ/d²`). Both are sampled only by shadow rays.
//! - **Environment.** A ray that leaves the scene sees the uniform radiance `environment` (the GL
//!   clear colour, linear). The eye sees it where the primary ray misses; after a hit it is found
//!   only by the cosine-sampled continuation ray (no shadow rays towards it).
//! - **Bounces.** `bounces = B` counts the indirect bounces after the primary hit. Call `x₁` the
//!   primary hit, `x₂ … ` the following hits. The image contains exactly these light paths:
//!   - zero reflections: the environment where the primary ray misses; emission of `x₁`;
//!   - `k` reflections, for every `1 ≤ k ≤ B + 1`: light from a point light, directional light or
//!     emitter (shadow ray from `x_k`), or from the environment (the continuation ray leaving `x_k`
//!     misses), reflected at `x_k, …, x₁`.
//!
//!   So `B = 0` is direct lighting only, the environment included (`x₁` lit by lights, emitters
//!   and sky), and `B = 1` adds one indirect bounce. A continuation ray leaving `x_{B+1}` that hits
//!   a surface adds nothing. With Russian roulette ([`Settings::roulette_from`]) paths may also
//!   stop earlier, unbiased.
//!
//! # Estimator
//!
//! Unidirectional path tracing, next-event estimation at every hit (one sample per emitter and
//! per light), cosine-weighted hemisphere sampling for the continuation (with a Lambertian BRDF
//! `ρ/π` the throughput simply multiplies by `ρ`). Each pixel has its own PCG32 stream (seeded
//! with the pixel index), so the image does not depend on the number of threads. Per pixel the
//! sample mean and its standard error are returned, so tests can state their error bounds.

#![allow(dead_code)]

use std::f64::consts::PI;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use glam::DVec3;

/// Offset of secondary ray origins from the surface, along its normal (scenes are metres-sized).
const RAY_OFFSET: f64 = 1e-7;

/// sRGB decoding of one display-encoded component in `[0, 1]`.
pub fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// sRGB encoding of one linear component, clamped to `[0, 1]`.
pub fn linear_to_srgb(l: f64) -> f64 {
    let l = l.clamp(0.0, 1.0);
    if l <= 0.0031308 { l * 12.92 } else { 1.055 * l.powf(1.0 / 2.4) - 0.055 }
}

/// PCG32 (O'Neill, XSH-RR 64/32): a small, well-tested, seedable generator with streams.
#[derive(Clone, Debug)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

impl Pcg32 {
    /// The generator of `stream` (any value) for `seed`, as `pcg32_srandom_r` seeds it.
    pub fn new(seed: u64, stream: u64) -> Self {
        let mut rng = Self { state: 0, inc: (stream << 1) | 1 };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(seed);
        rng.next_u32();
        rng
    }

    /// The next 32 random bits.
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(6364136223846793005).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    /// A uniform number in `[0, 1)` with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        let bits = (u64::from(self.next_u32()) << 21) | u64::from(self.next_u32() >> 11);
        bits as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// A `glFrustum(left, right, bottom, top, near, far)` projection with the eye at the origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub left: f64,
    pub right: f64,
    pub bottom: f64,
    pub top: f64,
    pub near: f64,
    pub far: f64,
}

impl Camera {
    /// `gluPerspective(fovy_degrees, aspect, near, far)`.
    pub fn perspective(fovy_degrees: f64, aspect: f64, near: f64, far: f64) -> Self {
        let top = near * (fovy_degrees.to_radians() / 2.0).tan();
        Self { left: -top * aspect, right: top * aspect, bottom: -top, top, near, far }
    }

    /// The unit direction through the point `(sx, sy)` of the image, both in `[0, 1]` with
    /// `(0, 0)` its bottom-left corner.
    pub fn direction(&self, sx: f64, sy: f64) -> DVec3 {
        let x = self.left + (self.right - self.left) * sx;
        let y = self.bottom + (self.top - self.bottom) * sy;
        DVec3::new(x, y, -self.near).normalize()
    }

    /// The direction through the centre of pixel `(x, y)` (`y = 0` the bottom row).
    pub fn pixel_center(&self, width: usize, height: usize, x: usize, y: usize) -> DVec3 {
        self.direction((x as f64 + 0.5) / width as f64, (y as f64 + 0.5) / height as f64)
    }
}

/// The geometry of a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// Front face where the corners run counter-clockwise.
    Triangle([DVec3; 3]),
    /// Planar and convex, corners in order; front face where they run counter-clockwise. Traced
    /// as the triangles (0, 1, 2) and (0, 2, 3), as `GL_QUADS` draws it.
    Quad([DVec3; 4]),
    /// Front face outside.
    Sphere { center: DVec3, radius: f64 },
}

/// A Lambertian surface, optionally emitting from its front face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// For messages and for tests to find a surface (`"floor"`).
    pub name: &'static str,
    pub shape: Shape,
    /// Linear RGB reflectance, each component in `[0, 1]`.
    pub albedo: DVec3,
    /// Emitted radiance, linear RGB (zero for no emission).
    pub emission: DVec3,
}

impl Surface {
    /// A non-emitting surface.
    pub fn new(name: &'static str, shape: Shape, albedo: DVec3) -> Self {
        Self { name, shape, albedo, emission: DVec3::ZERO }
    }

    /// The triangles of a triangle or quad (none for a sphere).
    fn triangles(&self) -> impl Iterator<Item = [DVec3; 3]> {
        let (first, second) = match self.shape {
            Shape::Triangle(t) => (Some(t), None),
            Shape::Quad([a, b, c, d]) => (Some([a, b, c]), Some([a, c, d])),
            Shape::Sphere { .. } => (None, None),
        };
        first.into_iter().chain(second)
    }

    /// Surface area.
    pub fn area(&self) -> f64 {
        match self.shape {
            Shape::Sphere { radius, .. } => 4.0 * PI * radius * radius,
            _ => self.triangles().map(|[a, b, c]| (b - a).cross(c - a).length() / 2.0).sum(),
        }
    }

    /// A uniform point of the surface and the front normal there.
    fn sample_point(&self, rng: &mut Pcg32) -> (DVec3, DVec3) {
        if let Shape::Sphere { center, radius } = self.shape {
            let n = uniform_sphere(rng.next_f64(), rng.next_f64());
            return (center + n * radius, n);
        }
        // Pick a triangle in proportion to its area (twice the area on both sides of `<`).
        let mut pick = rng.next_f64() * 2.0 * self.area();
        let mut chosen = [DVec3::ZERO; 3];
        for t in self.triangles() {
            chosen = t;
            let double_area = (t[1] - t[0]).cross(t[2] - t[0]).length();
            if pick < double_area {
                break;
            }
            pick -= double_area;
        }
        let [a, b, c] = chosen;
        let su = rng.next_f64().sqrt();
        let (u, v) = (1.0 - su, rng.next_f64() * su);
        (a * u + b * v + c * (1.0 - u - v), (b - a).cross(c - a).normalize())
    }

    /// The nearest hit in `(0, t_max)`: distance and front normal.
    fn intersect(&self, origin: DVec3, dir: DVec3, t_max: f64) -> Option<(f64, DVec3)> {
        if let Shape::Sphere { center, radius } = self.shape {
            let oc = origin - center;
            let b = oc.dot(dir);
            let disc = b * b - (oc.length_squared() - radius * radius);
            if disc < 0.0 {
                return None;
            }
            let root = disc.sqrt();
            let t = [-b - root, -b + root].into_iter().find(|&t| t > 0.0 && t < t_max)?;
            return Some((t, (origin + dir * t - center) / radius));
        }
        let mut best: Option<(f64, DVec3)> = None;
        for [a, b, c] in self.triangles() {
            let limit = best.map_or(t_max, |(t, _)| t);
            if let Some(t) = intersect_triangle(origin, dir, a, b, c, limit) {
                best = Some((t, (b - a).cross(c - a).normalize()));
            }
        }
        best
    }
}

/// Möller–Trumbore: the distance to triangle `abc` along the ray, if in `(0, t_max)`.
fn intersect_triangle(origin: DVec3, dir: DVec3, a: DVec3, b: DVec3, c: DVec3, t_max: f64) -> Option<f64> {
    let (e1, e2) = (b - a, c - a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-14 {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > 0.0 && t < t_max).then_some(t)
}

/// A light sampled by shadow rays only (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// Light from direction `towards` (unit, pointing at the light): irradiance `irradiance` on a
    /// surface facing it. With `angular_radius > 0` a disc of uniform radiance
    /// `E / (π sin²α)` seen under that half-angle, sampled uniformly in its cone.
    Directional { towards: DVec3, irradiance: DVec3, angular_radius: f64 },
    /// An isotropic point light of `intensity` (W/sr per channel): irradiance `I·cosθ / d²`.
    Point { position: DVec3, intensity: DVec3 },
}

/// A scene in eye space, with the camera that views it.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub surfaces: Vec<Surface>,
    pub lights: Vec<Light>,
    /// Radiance of every ray that leaves the scene, linear RGB.
    pub environment: DVec3,
    pub camera: Camera,
}

/// A surface hit: where, which surface, and its front normal.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub surface: usize,
    pub point: DVec3,
    pub normal: DVec3,
    pub distance: f64,
}

/// How to render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub width: usize,
    pub height: usize,
    /// Samples per pixel, at least 2 (for the standard error).
    pub samples: u32,
    /// Indirect bounces after the primary hit (0: direct light only), see the module doc.
    pub bounces: u32,
    /// From this bounce on, a path continues with probability `min(max(throughput), 0.95)`
    /// and is reweighted; `None`: every path runs to `bounces`.
    pub roulette_from: Option<u32>,
    pub seed: u64,
}

impl Settings {
    /// `bounces` bounces, no roulette, seed 1.
    pub fn new(width: usize, height: usize, samples: u32, bounces: u32) -> Self {
        Self { width, height, samples, bounces, roulette_from: None, seed: 1 }
    }
}

/// A rendered image: per pixel the mean radiance and its standard error, row `y = 0` first
/// (the bottom row).
#[derive(Clone, Debug)]
pub struct Image {
    pub width: usize,
    pub height: usize,
    pub mean: Vec<DVec3>,
    pub std_error: Vec<DVec3>,
}

impl Image {
    /// Mean radiance of pixel `(x, y)`.
    pub fn at(&self, x: usize, y: usize) -> DVec3 {
        self.mean[y * self.width + x]
    }

    /// Standard error of pixel `(x, y)`'s mean.
    pub fn error_at(&self, x: usize, y: usize) -> DVec3 {
        self.std_error[y * self.width + x]
    }

    /// The mean over several pixels and its standard error (pixels are independent).
    pub fn region_mean(&self, pixels: &[(usize, usize)]) -> (DVec3, DVec3) {
        assert!(!pixels.is_empty(), "empty region");
        let n = pixels.len() as f64;
        let sum: DVec3 = pixels.iter().map(|&(x, y)| self.at(x, y)).sum();
        let var: DVec3 = pixels.iter().map(|&(x, y)| self.error_at(x, y).powf(2.0)).sum();
        (sum / n, var.powf(0.5) / n)
    }

    /// Writes the image as an 8-bit sRGB PNG (values clamped to `[0, 1]`, no tone mapping), top
    /// row first as PNG wants.
    pub fn save_png(&self, path: &Path) -> std::io::Result<()> {
        let file = std::io::BufWriter::new(std::fs::File::create(path)?);
        let mut encoder = png::Encoder::new(file, self.width as u32, self.height as u32);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        let mut data = Vec::with_capacity(self.width * self.height * 3);
        for y in (0..self.height).rev() {
            for x in 0..self.width {
                let c = self.at(x, y);
                data.extend([c.x, c.y, c.z].map(|l| (linear_to_srgb(l) * 255.0).round() as u8));
            }
        }
        let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
        writer.write_image_data(&data).map_err(std::io::Error::other)
    }
}

/// A point of the unit sphere from two uniform numbers.
fn uniform_sphere(u1: f64, u2: f64) -> DVec3 {
    let z = 1.0 - 2.0 * u1;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u2;
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Maps a local direction (z along `n`) to world space (Duff et al. 2017, orthonormal basis).
fn to_world(n: DVec3, local: DVec3) -> DVec3 {
    let s = 1f64.copysign(n.z);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    let t = DVec3::new(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    let bt = DVec3::new(b, s + n.y * n.y * a, -n.y);
    t * local.x + bt * local.y + n * local.z
}

/// A cosine-distributed direction around `n` (pdf `cosθ/π`).
fn cosine_hemisphere(n: DVec3, rng: &mut Pcg32) -> DVec3 {
    let (u1, u2) = (rng.next_f64(), rng.next_f64());
    let r = u1.sqrt();
    let phi = 2.0 * PI * u2;
    to_world(n, DVec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u1).max(0.0).sqrt()))
}

/// A uniform direction in the cone of half-angle `acos(cos_max)` around `axis`.
fn uniform_cone(axis: DVec3, cos_max: f64, rng: &mut Pcg32) -> DVec3 {
    let cos = 1.0 - rng.next_f64() * (1.0 - cos_max);
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let phi = 2.0 * PI * rng.next_f64();
    to_world(axis, DVec3::new(sin * phi.cos(), sin * phi.sin(), cos))
}

impl Scene {
    /// The nearest surface along the ray within `(0, t_max)`.
    pub fn intersect(&self, origin: DVec3, dir: DVec3, t_max: f64) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        for (i, s) in self.surfaces.iter().enumerate() {
            let limit = best.map_or(t_max, |h| h.distance);
            if let Some((t, normal)) = s.intersect(origin, dir, limit) {
                best = Some(Hit { surface: i, point: origin + dir * t, normal, distance: t });
            }
        }
        best
    }

    /// Whether anything lies on the ray within `(0, t_max)`.
    fn occluded(&self, origin: DVec3, dir: DVec3, t_max: f64) -> bool {
        self.surfaces.iter().any(|s| s.intersect(origin, dir, t_max).is_some())
    }

    /// Whether the segment from `origin` to `target` is free, `target`'s own surface excluded:
    /// the shadow ray aims at `target` itself (not along a direction measured from elsewhere),
    /// so that the surface it lies on is met at the segment's end even at grazing angles.
    fn visible(&self, origin: DVec3, target: DVec3) -> bool {
        let d = target - origin;
        let length = d.length();
        !self.occluded(origin, d / length, length - RAY_OFFSET)
    }

    /// Light arriving at `p` (normal `n`, facing the side being shaded) from every light and
    /// emitter, weighted by the cosine at `p`: one shadow-ray sample each. The BRDF is applied by
    /// the caller.
    fn direct_irradiance(&self, p: DVec3, n: DVec3, rng: &mut Pcg32) -> DVec3 {
        let origin = p + n * RAY_OFFSET;
        let mut e = DVec3::ZERO;
        for light in &self.lights {
            match *light {
                Light::Directional { towards, irradiance, angular_radius } => {
                    let (wi, scale) = if angular_radius > 0.0 {
                        let cos_max = angular_radius.cos();
                        (uniform_cone(towards.normalize(), cos_max, rng), 2.0 / (1.0 + cos_max))
                    } else {
                        (towards.normalize(), 1.0)
                    };
                    let cos = n.dot(wi);
                    if cos > 0.0 && !self.occluded(origin, wi, f64::INFINITY) {
                        e += irradiance * scale * cos;
                    }
                }
                Light::Point { position, intensity } => {
                    let d = position - p;
                    let dist = d.length();
                    let wi = d / dist;
                    let cos = n.dot(wi);
                    if cos > 0.0 && self.visible(origin, position) {
                        e += intensity * cos / (dist * dist);
                    }
                }
            }
        }
        for emitter in self.surfaces.iter().filter(|s| s.emission != DVec3::ZERO) {
            let (q, nq) = emitter.sample_point(rng);
            let d = q - p;
            let dist = d.length();
            let wi = d / dist;
            let (cos, cos_q) = (n.dot(wi), -nq.dot(wi));
            if cos > 0.0 && cos_q > 0.0 && self.visible(origin, q) {
                e += emitter.emission * (cos * cos_q * emitter.area() / (dist * dist));
            }
        }
        e
    }

    /// One path-traced estimate of the radiance arriving at `origin` from direction `-dir`
    /// (`dir` unit), following the module's conventions.
    pub fn radiance(&self, origin: DVec3, dir: DVec3, settings: &Settings, rng: &mut Pcg32) -> DVec3 {
        let Some(mut hit) = self.intersect(origin, dir, f64::INFINITY) else {
            return self.environment;
        };
        let mut surface = &self.surfaces[hit.surface];
        let mut radiance = if hit.normal.dot(dir) < 0.0 { surface.emission } else { DVec3::ZERO };
        let mut throughput = DVec3::ONE;
        let mut incoming = dir;
        for bounce in 0..=settings.bounces {
            // Two-sided: shade the side the ray came from.
            let n = if hit.normal.dot(incoming) < 0.0 { hit.normal } else { -hit.normal };
            throughput *= surface.albedo;
            radiance += throughput / PI * self.direct_irradiance(hit.point, n, rng);
            let last = bounce == settings.bounces;
            if last && self.environment == DVec3::ZERO {
                break;
            }
            // Lambertian BRDF ρ/π with cosine sampling: the weight is ρ, already in `throughput`.
            incoming = cosine_hemisphere(n, rng);
            let Some(next) = self.intersect(hit.point + n * RAY_OFFSET, incoming, f64::INFINITY) else {
                radiance += throughput * self.environment;
                break;
            };
            if last {
                break;
            }
            if settings.roulette_from.is_some_and(|from| bounce >= from) {
                let survive = throughput.max_element().min(0.95);
                if rng.next_f64() >= survive {
                    break;
                }
                throughput /= survive;
            }
            hit = next;
            surface = &self.surfaces[hit.surface];
        }
        radiance
    }

    /// Renders the image on every available core, rows handed out in turn. Deterministic for a
    /// seed: pixel `i = y·width + x` uses PCG32 stream `i`.
    pub fn render(&self, settings: &Settings) -> Image {
        assert!(settings.samples >= 2, "the standard error needs at least 2 samples");
        let (w, h) = (settings.width, settings.height);
        let threads = std::thread::available_parallelism().map_or(1, usize::from).min(h);
        let next_row = AtomicUsize::new(0);
        let rows: Vec<(usize, Vec<(DVec3, DVec3)>)> = std::thread::scope(|scope| {
            let workers: Vec<_> = (0..threads)
                .map(|_| {
                    scope.spawn(|| {
                        let mut done = Vec::new();
                        loop {
                            let y = next_row.fetch_add(1, Ordering::Relaxed);
                            if y >= h {
                                break done;
                            }
                            done.push((y, (0..w).map(|x| self.render_pixel(settings, x, y)).collect()));
                        }
                    })
                })
                .collect();
            workers.into_iter().flat_map(|t| t.join().expect("render thread panicked")).collect()
        });
        let mut image =
            Image { width: w, height: h, mean: vec![DVec3::ZERO; w * h], std_error: vec![DVec3::ZERO; w * h] };
        for (y, row) in rows {
            for (x, (mean, error)) in row.into_iter().enumerate() {
                image.mean[y * w + x] = mean;
                image.std_error[y * w + x] = error;
            }
        }
        image
    }

    /// Mean and standard error of one pixel.
    fn render_pixel(&self, settings: &Settings, x: usize, y: usize) -> (DVec3, DVec3) {
        let mut rng = Pcg32::new(settings.seed, (y * settings.width + x) as u64);
        let (mut sum, mut sum_sq) = (DVec3::ZERO, DVec3::ZERO);
        for _ in 0..settings.samples {
            let sx = (x as f64 + rng.next_f64()) / settings.width as f64;
            let sy = (y as f64 + rng.next_f64()) / settings.height as f64;
            let l = self.radiance(DVec3::ZERO, self.camera.direction(sx, sy), settings, &mut rng);
            sum += l;
            sum_sq += l * l;
        }
        let n = f64::from(settings.samples);
        let mean = sum / n;
        let variance = ((sum_sq - sum * mean) / (n - 1.0)).max(DVec3::ZERO);
        (mean, (variance / n).powf(0.5))
    }
}

/// A quad from a corner and two edges: corners `o, o+u, o+u+v, o+v`, front normal along `u×v`.
fn rect(o: DVec3, u: DVec3, v: DVec3) -> Shape {
    Shape::Quad([o, o + u, o + u + v, o + v])
}

/// The quads of a box standing on `y = floor_y` (no bottom face), fronts outside: centre
/// `(x, z)`, half-sizes along its own axes, height, turned by `angle_degrees` about +y.
fn block(name: &'static str, centre: (f64, f64), half: (f64, f64), height: f64, angle_degrees: f64, floor_y: f64,
         albedo: DVec3) -> Vec<Surface> {
    let (sin, cos) = angle_degrees.to_radians().sin_cos();
    let corner = |sx: f64, sz: f64| {
        let (lx, lz) = (sx * half.0, sz * half.1);
        DVec3::new(centre.0 + cos * lx + sin * lz, floor_y, centre.1 - sin * lx + cos * lz)
    };
    // Counter-clockwise seen from above (+y).
    let base = [corner(-1.0, 1.0), corner(1.0, 1.0), corner(1.0, -1.0), corner(-1.0, -1.0)];
    let up = DVec3::Y * height;
    let mut quads = vec![Surface::new(name, Shape::Quad(base.map(|c| c + up)), albedo)];
    for i in 0..4 {
        let (a, b) = (base[i], base[(i + 1) % 4]);
        quads.push(Surface::new(name, rect(a, b - a, up), albedo));
    }
    quads
}

/// A sphere as `slices × stacks` planar faces (triangles at the poles, trapezoids between),
/// fronts outside, with `+y` as its axis: the same faces can be drawn through GL and traced here.
pub fn tessellate_sphere(center: DVec3, radius: f64, slices: usize, stacks: usize) -> Vec<Shape> {
    let point = |stack: usize, slice: usize| {
        let theta = PI * stack as f64 / stacks as f64;
        let phi = 2.0 * PI * slice as f64 / slices as f64;
        center + DVec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin()) * radius
    };
    let mut faces = Vec::new();
    for i in 0..stacks {
        for j in 0..slices {
            // Counter-clockwise seen from outside: down the meridian, then along the parallel.
            let (a, b, c, d) = (point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1));
            faces.push(if i == 0 {
                Shape::Triangle([a, b, c])
            } else if i == stacks - 1 {
                Shape::Triangle([a, b, d])
            } else {
                Shape::Quad([a, b, c, d])
            });
        }
    }
    faces
}

/// Lambertian albedos of the classic Cornell box (linear RGB).
pub const CORNELL_WHITE: DVec3 = DVec3::new(0.73, 0.73, 0.73);
pub const CORNELL_RED: DVec3 = DVec3::new(0.63, 0.065, 0.05);
pub const CORNELL_GREEN: DVec3 = DVec3::new(0.14, 0.45, 0.091);

/// How a Cornell box is lit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CornellLight {
    /// A 0.5 × 0.5 square emitter (surface `"light"`, radiance 12, albedo 0.78) facing down
    /// 0.005 below the ceiling's centre.
    Area,
    /// A point light of intensity 2 W/sr at `(0, 0.6, -3.6)`, 0.4 below the ceiling's centre:
    /// what a GL 1.x program (which has no area lights) can express. (Closer to the ceiling, the
    /// hot spot above it makes indirect light converge much more slowly.)
    Point,
}

/// A Cornell-box-like room in eye space: `x, y ∈ [-1, 1]`, `z ∈ [-4.6, -2.6]`, open towards the
/// eye (front at `z = -2.6`); white floor, ceiling and back wall, red left wall (`x = -1`), green
/// right wall (`x = 1`), a short block front right and a tall one back left; every quad's front
/// faces into the room. Seen with `gluPerspective(40°, 1, 1, 10)`, the room fills the view; the
/// environment is black. Surfaces are named `"floor"`, `"ceiling"`, `"back"`, `"left"`,
/// `"right"`, `"short block"`, `"tall block"` and, lit by [`CornellLight::Area`], `"light"`.
pub fn cornell_box(light: CornellLight) -> Scene {
    let (front, depth) = (-2.6, -2.0);
    let mut surfaces = vec![
        Surface::new("floor", rect(DVec3::new(-1.0, -1.0, front), DVec3::X * 2.0, DVec3::Z * depth), CORNELL_WHITE),
        Surface::new("ceiling", rect(DVec3::new(-1.0, 1.0, front), DVec3::Z * depth, DVec3::X * 2.0), CORNELL_WHITE),
        Surface::new("back", rect(DVec3::new(-1.0, -1.0, front + depth), DVec3::X * 2.0, DVec3::Y * 2.0), CORNELL_WHITE),
        Surface::new("left", rect(DVec3::new(-1.0, -1.0, front), DVec3::Z * depth, DVec3::Y * 2.0), CORNELL_RED),
        Surface::new("right", rect(DVec3::new(1.0, -1.0, front), DVec3::Y * 2.0, DVec3::Z * depth), CORNELL_GREEN),
    ];
    surfaces.extend(block("short block", (0.33, -3.25), (0.3, 0.3), 0.6, -17.0, -1.0, CORNELL_WHITE));
    surfaces.extend(block("tall block", (-0.33, -3.95), (0.3, 0.3), 1.2, 17.0, -1.0, CORNELL_WHITE));
    let lights = match light {
        CornellLight::Area => {
            let corner = DVec3::new(-0.25, 0.995, -3.35);
            surfaces.push(Surface {
                name: "light",
                shape: rect(corner, DVec3::Z * -0.5, DVec3::X * 0.5),
                albedo: DVec3::splat(0.78),
                emission: DVec3::splat(12.0),
            });
            Vec::new()
        }
        CornellLight::Point => {
            vec![Light::Point { position: DVec3::new(0.0, 0.6, -3.6), intensity: DVec3::splat(2.0) }]
        }
    };
    Scene { surfaces, lights, environment: DVec3::ZERO, camera: Camera::perspective(40.0, 1.0, 1.0, 10.0) }
}

/// The white furnace: a sphere of albedo 1 (radius 1, centre `(0, 0, -3)`) inside a uniform
/// environment of radiance 1, no lights. Every pixel converges to 1, sphere or not: a convex
/// surface of albedo 1 under a uniform sky neither gains nor loses energy.
pub fn white_furnace() -> Scene {
    let sphere = Shape::Sphere { center: DVec3::new(0.0, 0.0, -3.0), radius: 1.0 };
    Scene {
        surfaces: vec![Surface::new("sphere", sphere, DVec3::ONE)],
        lights: Vec::new(),
        environment: DVec3::ONE,
        camera: Camera::perspective(40.0, 1.0, 1.0, 10.0),
    }
}

/// A square plane facing the eye (normal +z, `z = -2`, 4 × 4, filling the view of
/// `gluPerspective(40°, 1, 1, 10)`) of `albedo`, under a directional light of `irradiance`
/// arriving at `incidence` radians from the normal (tilted towards +x); black environment.
/// Its radiance is `albedo/π · irradiance · cos(incidence)` everywhere.
pub fn lit_plane(incidence: f64, albedo: DVec3, irradiance: DVec3) -> Scene {
    let plane = rect(DVec3::new(-2.0, -2.0, -2.0), DVec3::X * 4.0, DVec3::Y * 4.0);
    let towards = DVec3::new(incidence.sin(), 0.0, incidence.cos());
    Scene {
        surfaces: vec![Surface::new("plane", plane, albedo)],
        lights: vec![Light::Directional { towards, irradiance, angular_radius: 0.0 }],
        environment: DVec3::ZERO,
        camera: Camera::perspective(40.0, 1.0, 1.0, 10.0),
    }
}

/// A closed box around the eye (`x, y ∈ [-1, 1]`, `z ∈ [-2, 1]`) whose six walls all have
/// `albedo` and emit `emission` inwards. Radiance is then the same everywhere and, with `B`
/// bounces, exactly `emission · (1 + ρ + … + ρ^(B+1))`, converging to `emission / (1 − ρ)`:
/// each reflection of the uniform field `L` gives `ρL` (the irradiance of a uniform enclosure is
/// `πL`), whatever the box's shape.
pub fn glowing_box(albedo: f64, emission: f64) -> Scene {
    let (lo, hi) = (DVec3::new(-1.0, -1.0, -2.0), DVec3::new(1.0, 1.0, 1.0));
    let size = hi - lo;
    let (x, y, z) = (DVec3::X * size.x, DVec3::Y * size.y, DVec3::Z * size.z);
    let walls = [
        rect(lo, z, x),     // floor, facing +y
        rect(lo + y, x, z), // ceiling, facing −y
        rect(lo, x, y),     // far wall (z = −2), facing +z
        rect(lo + z, y, x), // near wall (z = 1), facing −z
        rect(lo, y, z),     // left, facing +x
        rect(lo + x, z, y), // right, facing −x
    ];
    Scene {
        surfaces: walls
            .into_iter()
            .map(|shape| Surface { name: "wall", shape, albedo: DVec3::splat(albedo), emission: DVec3::splat(emission) })
            .collect(),
        lights: Vec::new(),
        environment: DVec3::ZERO,
        camera: Camera::perspective(40.0, 1.0, 0.1, 10.0),
    }
}
