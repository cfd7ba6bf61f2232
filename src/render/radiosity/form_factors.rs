//! Form factors on the CPU, the reference the GPU version ([`super::gpu::form_factors`], the
//! same method in `shaders/radiosity/form_factors.comp`) is checked against: point-to-patch
//! with visibility by ray casting against the tracer's BVH.
//!
//! `F_ij` is the form factor from receiver `i` to source `j` as the gathering equation
//! `B_i = E_i + ρ_i Σ_j F_ij B_j` uses it (the cosine-weighted share of `i`'s hemisphere that
//! `j` covers), averaged over points `p` of the receiver: the centroids of its first
//! [`RECEIVER_POINTS`] triangles (its fragments, about a quarter of a patch each on flat
//! ground), weighted by area, moved off the surface by [`offset`]. For each point:
//!
//! - **Unoccluded part, exact.** For each of `j`'s triangles that faces `p`, clipped to the
//!   hemisphere above `i`, the point-to-polygon form factor of Lambert's contour integral
//!   (Baum, Rushmeier and Winget 1989, eq. 3): `F = 1/2π Σ_k γ_k n·(R_k × R_k+1)/|R_k × R_k+1|`,
//!   `R_k` the vertices relative to `p`, `γ_k` the angle between consecutive ones. It is exact
//!   for every size and distance (no disc approximation), so in a closed room the row sums are
//!   1 up to rounding and visibility: the white furnace holds by construction of the geometry,
//!   and what the test checks is the code.
//! - **Visibility, sampled.** The fraction of [`VISIBILITY_SAMPLES`] points of the source
//!   patch's clipped triangles (see [`visible_fraction`]) that a shadow ray
//!   from `p` reaches ([`cpu::any`] on one BLAS of every patch triangle, the traversal the GPU
//!   runs). Partly hidden sources get a coarse fraction; finer patches refine it.
//!
//! Hemisphere sampling would trade the exact integral for noise (`1/√rays` per entry) and needs
//! many rays per patch to resolve small far patches; the contour integral costs one evaluation
//! per triangle pair plus a few rays, and is the better reference. Its approximation is the
//! point receiver: `F_ij` is exact for the receiver's points, not averaged over its whole area, so
//! reciprocity `A_i F_ij = A_j F_ji` holds only as the patches get small against their
//! distance (the tests state how well); several points per patch make it a finer midpoint rule.

use glam::{Affine3A, DVec3, Vec3};

use super::patches::{Patches, area, face_normal};
use super::shader_constants;
use crate::render::trace::bvh::cpu::{self, Instance, Scene};
use crate::render::trace::bvh::{Blas, Layout, Tlas};

/// Visibility rays per source patch and receiver point.
const VISIBILITY_SAMPLES: usize = shader_constants::VISIBILITY_SAMPLES as usize;
/// Most receiver points of a patch: the centroids of its first triangles.
const RECEIVER_POINTS: usize = shader_constants::RECEIVER_POINTS as usize;

/// A dense form-factor matrix: `values[i * n + j]` = `F_ij`, receiver `i`, source `j`.
#[derive(Clone, Debug, PartialEq)]
pub struct FormFactors {
    /// Patch count.
    pub n: usize,
    /// Row-major values.
    pub values: Vec<f32>,
}

impl FormFactors {
    /// Row `i`: the form factors from receiver `i` to every source.
    pub fn row(&self, i: usize) -> &[f32] {
        &self.values[i * self.n..(i + 1) * self.n]
    }

    /// Bytes of the dense matrix.
    pub fn bytes(&self) -> usize {
        self.values.len() * size_of::<f32>()
    }
}

/// The form factors between all `patches` (rows computed on every available core).
pub fn compute(patches: &Patches) -> FormFactors {
    let n = patches.patches.len();
    let blas = Blas::build(&patches.triangles, Layout::Binary);
    let tlas = Tlas::build(&[blas.bounds], Layout::Binary);
    let instances = [Instance::new(&Affine3A::IDENTITY, 0, 0, false)];
    let scene = Scene { tlas: &tlas.nodes, blas_nodes: &blas.nodes, triangles: &blas.triangles, instances: &instances };
    let mut values = vec![0.0f32; n * n];
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get());
    let rows_per_thread = n.div_ceil(threads).max(1);
    std::thread::scope(|s| {
        for (t, rows) in values.chunks_mut(rows_per_thread * n.max(1)).enumerate() {
            let scene = &scene;
            s.spawn(move || {
                for (k, row) in rows.chunks_mut(n).enumerate() {
                    fill_row(patches, scene, t * rows_per_thread + k, row);
                }
            });
        }
    });
    FormFactors { n, values }
}

/// How far a receiver's point is moved off its surface along the normal: a thousandth of
/// the patch's side plus a margin for the coordinates' rounding.
pub fn offset(position: Vec3, area: f32) -> f32 {
    1.0e-3 * area.sqrt() + 1.0e-6 * position.abs().max_element()
}

/// Row `i` of the matrix.
fn fill_row(patches: &Patches, scene: &Scene, i: usize, row: &mut [f32]) {
    let receiver = &patches.patches[i];
    if receiver.normal == Vec3::ZERO {
        return;
    }
    let lift = receiver.normal * offset(receiver.position, receiver.area);
    let points: Vec<(Vec3, f32)> = patches.triangles[receiver.triangles.clone()]
        .iter()
        .take(RECEIVER_POINTS)
        .map(|t| ((t[0] + t[1] + t[2]) / 3.0 + lift, area(t)))
        .collect();
    let total: f32 = points.iter().map(|(_, a)| a).sum();
    if !(total > 0.0) {
        return;
    }
    for (j, source) in patches.patches.iter().enumerate() {
        if j == i {
            continue;
        }
        let margin = offset(source.position, source.area);
        let mut sum = 0.0;
        for &(p, weight) in &points {
            let mut unoccluded = 0.0;
            let mut visible: Vec<Vec<Vec3>> = Vec::new();
            for t in &patches.triangles[source.triangles.clone()] {
                // Only the front of the source emits: p must be in front of its plane.
                if face_normal(t).dot(p - t[0]) <= 0.0 {
                    continue;
                }
                let polygon = clip(t, p, receiver.normal);
                let f = point_to_polygon(p, receiver.normal, &polygon);
                if f > 0.0 {
                    unoccluded += f;
                    visible.push(polygon);
                }
            }
            if unoccluded > 0.0 {
                sum += weight * unoccluded * visible_fraction(scene, p, &visible, margin);
            }
        }
        row[j] = sum / total;
    }
}

/// `t` clipped to the half-space in front of the plane through `p` with normal `n`
/// (Sutherland–Hodgman against one plane: at most 4 vertices).
fn clip(t: &[Vec3; 3], p: Vec3, n: Vec3) -> Vec<Vec3> {
    let side = |v: Vec3| n.dot(v - p);
    let mut out = Vec::with_capacity(4);
    for k in 0..3 {
        let (a, b) = (t[k], t[(k + 1) % 3]);
        let (da, db) = (side(a), side(b));
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            out.push(a + (b - a) * (da / (da - db)));
        }
    }
    out
}

/// The form factor from a differential area at `p` with normal `n` to the polygon (in front
/// of it): Lambert's contour integral, in f64.
pub fn point_to_polygon(p: Vec3, n: Vec3, polygon: &[Vec3]) -> f32 {
    if polygon.len() < 3 {
        return 0.0;
    }
    let n = n.as_dvec3();
    let r: Vec<DVec3> = polygon.iter().map(|v| (*v - p).as_dvec3()).collect();
    let mut sum = 0.0;
    for k in 0..r.len() {
        let (a, b) = (r[k], r[(k + 1) % r.len()]);
        let c = a.cross(b);
        let len = c.length();
        if len > 0.0 {
            sum += len.atan2(a.dot(b)) * n.dot(c) / len;
        }
    }
    (sum.abs() / (2.0 * std::f64::consts::PI)) as f32
}

/// The share of sample points of the `polygons` (the parts of a source patch in front of the
/// receiver) that a ray from `p` reaches unoccluded, stopping `margin` short of the point:
/// [`VISIBILITY_SAMPLES`] points, the polygons' centroids (evenly spaced among them when there
/// are more), then points halfway from the first polygon's centroid to its vertices.
fn visible_fraction(scene: &Scene, p: Vec3, polygons: &[Vec<Vec3>], margin: f32) -> f32 {
    let centroid = |poly: &[Vec3]| poly.iter().copied().sum::<Vec3>() / poly.len() as f32;
    let count = polygons.len().min(VISIBILITY_SAMPLES);
    let mut samples: Vec<Vec3> = (0..count).map(|k| centroid(&polygons[k * polygons.len() / count])).collect();
    let first = centroid(&polygons[0]);
    samples.extend(polygons[0].iter().map(|v| (*v + first) * 0.5).take(VISIBILITY_SAMPLES - count));
    let (mut seen, mut total) = (0u32, 0u32);
    for q in samples {
        let d = q - p;
        let tmax = 1.0 - margin / d.length().max(margin * 2.0);
        total += 1;
        if !cpu::any(scene, p, d, 0.0, tmax, |_, _, _| true) {
            seen += 1;
        }
    }
    seen as f32 / total as f32
}
