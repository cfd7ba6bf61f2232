//! The traversal of `shaders/trace/bvh.glsl` in Rust, operation for operation: the reference
//! the GPU is tested against, and the BVH builder's test oracle's counterpart.
//!
//! One loop walks the TLAS and, on reaching an instance, that instance's BLAS with the ray
//! moved into object space (direction not renormalised, so `t` stays comparable), sharing one
//! stack of `2 * BVH_MAX_DEPTH` entries: at each node both child boxes are tested, BLAS leaves
//! are intersected at once, and of the hit inner children (or TLAS instances, pushed with the
//! [`BVH_LEAF`] bit) the nearer is visited next and the farther pushed. An entry that would
//! overflow the stack is dropped (never happens for BVHs built by [`super::build`]).

use glam::{Affine3A, Vec2, Vec3, Vec4};

use super::{GpuChild, GpuNode, GpuTriangle};
use crate::render::trace::shader_constants::{BVH_LEAF, BVH_MAX_DEPTH};

/// Entries of the traversal stack (`BVH_STACK_SIZE`).
const STACK_SIZE: usize = 2 * BVH_MAX_DEPTH;
/// Smallest magnitude of a direction component before inversion (`BVH_TINY`).
const TINY: f32 = 1.0e-20;
/// Factor widening a box's exit distance to cover rounding (`BVH_BOX_SLACK`, 1 + 4 ulp).
const BOX_SLACK: f32 = 1.000_000_5;
/// No node (`BVH_NONE`).
const NONE: u32 = u32::MAX;
/// Entry distance of a missed box (`BVH_MISS`).
const MISS: f32 = f32::INFINITY;

/// The traversal's view of an instance (`Instance` in `instance.glsl`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance {
    /// Rows of the eye-to-object matrix.
    pub eye_to_object: [Vec4; 3],
    /// Its BLAS's root in the shared node array.
    pub blas_root: u32,
    /// Its BLAS's first triangle in the shared triangle array.
    pub first_triangle: u32,
    /// Whether hits ask the `accept` function (`INSTANCE_ALPHA_TESTED`).
    pub alpha_tested: bool,
}

impl Instance {
    /// An instance of the BLAS at `blas_root`/`first_triangle` placed by `object_to_eye`.
    pub fn new(object_to_eye: &Affine3A, blas_root: u32, first_triangle: u32, alpha_tested: bool) -> Instance {
        Instance { eye_to_object: affine_rows(&object_to_eye.inverse()), blas_root, first_triangle, alpha_tested }
    }
}

/// The rows of `m` as the GPU stores affine matrices (`vec4 rows[3]`: x, y, z rows with the
/// translation in `w`).
pub fn affine_rows(m: &Affine3A) -> [Vec4; 3] {
    let c = m.matrix3;
    let t = m.translation;
    [Vec4::new(c.x_axis.x, c.y_axis.x, c.z_axis.x, t.x), Vec4::new(c.x_axis.y, c.y_axis.y, c.z_axis.y, t.y), Vec4::new(c.x_axis.z, c.y_axis.z, c.z_axis.z, t.z)]
}

/// The buffers traversal reads (the bindings of `bvh.glsl` and the instance buffer).
#[derive(Clone, Copy, Debug)]
pub struct Scene<'a> {
    /// The TLAS nodes (`BINDING_TLAS_NODES`).
    pub tlas: &'a [GpuNode],
    /// Every BLAS's nodes (`BINDING_BLAS_NODES`).
    pub blas_nodes: &'a [GpuNode],
    /// Every BLAS's triangles (`BINDING_TRIANGLES`).
    pub triangles: &'a [GpuTriangle],
    /// The instances (`BINDING_INSTANCES`).
    pub instances: &'a [Instance],
}

/// A ray's closest accepted hit (`TraceHit`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the ray, in units of its direction's length.
    pub t: f32,
    /// The instance hit.
    pub instance: u32,
    /// The triangle hit, in the shared triangle array (`first_triangle` + its index in the BLAS).
    pub triangle: u32,
    /// Weights (u, v) of the triangle's second and third vertices at the hit.
    pub bary: Vec2,
}

/// The closest hit with `tmin < t < tmax` (`trace_closest`). `accept(instance, triangle,
/// bary)` decides hits on alpha-tested instances.
pub fn closest(scene: &Scene, origin: Vec3, dir: Vec3, tmin: f32, tmax: f32, accept: impl FnMut(u32, u32, Vec2) -> bool) -> Option<Hit> {
    trace(scene, origin, dir, tmin, tmax, false, accept)
}

/// Whether any accepted hit has `tmin < t < tmax` (`trace_any`).
pub fn any(scene: &Scene, origin: Vec3, dir: Vec3, tmin: f32, tmax: f32, accept: impl FnMut(u32, u32, Vec2) -> bool) -> bool {
    trace(scene, origin, dir, tmin, tmax, true, accept).is_some()
}

/// `1 / d` with components of magnitude below [`TINY`] replaced by ±`TINY` (`bvh_inverse`).
fn inverse(d: Vec3) -> Vec3 {
    let safe = |x: f32| {
        if x.abs() < TINY { if x >= 0.0 { TINY } else { -TINY } } else { x }
    };
    Vec3::ONE / Vec3::new(safe(d.x), safe(d.y), safe(d.z))
}

/// Entry distance of the ray into `c`'s box clipped to `[tmin, tmax]`, or [`MISS`]
/// (`bvh_box`).
fn enter(c: &GpuChild, o: Vec3, inv: Vec3, tmin: f32, tmax: f32) -> f32 {
    let t0 = (Vec3::from(c.min) - o) * inv;
    let t1 = (Vec3::from(c.max) - o) * inv;
    let near = t0.min(t1);
    let far = t0.max(t1);
    let tn = near.x.max(near.y).max(near.z.max(tmin));
    let tf = far.x.min(far.y).min(far.z.min(tmax)) * BOX_SLACK;
    if tn <= tf { tn } else { MISS }
}

/// Möller–Trumbore: `(t, (u, v))` when the ray hits `tri` with `tmin < t < tmax`
/// (`bvh_triangle`).
pub(super) fn intersect(tri: &GpuTriangle, o: Vec3, d: Vec3, tmin: f32, tmax: f32) -> Option<(f32, Vec2)> {
    let e1 = Vec3::from(tri.e1);
    let e2 = Vec3::from(tri.e2);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || det.is_nan() {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - Vec3::from(tri.v0);
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    if !(v >= 0.0 && u + v <= 1.0) {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > tmin && t < tmax).then_some((t, Vec2::new(u, v)))
}

/// Applies the rows of an affine matrix to `(v, w)`.
pub(super) fn transform(rows: &[Vec4; 3], v: Vec3, w: f32) -> Vec3 {
    let h = v.extend(w);
    Vec3::new(rows[0].dot(h), rows[1].dot(h), rows[2].dot(h))
}

/// The traversal of both queries (`bvh_trace`): with `any_hit`, returns at the first accepted
/// hit.
fn trace(scene: &Scene, origin: Vec3, dir: Vec3, tmin: f32, tmax: f32, any_hit: bool, mut accept: impl FnMut(u32, u32, Vec2) -> bool) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    let mut t_max = tmax;
    let (mut o, mut d, mut inv) = (origin, dir, inverse(dir));
    let mut instance: Option<(u32, &Instance)> = None;
    let mut base = 0;
    let mut stack = [0u32; STACK_SIZE];
    let mut sp = 0;
    let mut next = 0u32;
    loop {
        if next & BVH_LEAF != 0 {
            let id = next & !BVH_LEAF;
            let inst = &scene.instances[id as usize];
            o = transform(&inst.eye_to_object, origin, 1.0);
            d = transform(&inst.eye_to_object, dir, 0.0);
            inv = inverse(d);
            instance = Some((id, inst));
            base = sp;
            next = 0;
        }
        let node = match instance {
            None => scene.tlas[next as usize],
            Some((_, inst)) => scene.blas_nodes[(inst.blas_root + next) as usize],
        };
        let entry = node.children.map(|c| enter(&c, o, inv, tmin, t_max));
        let order = if entry[1] < entry[0] { [1, 0] } else { [0, 1] };
        if let Some((id, inst)) = instance {
            for slot in order {
                let c = &node.children[slot];
                if entry[slot] == MISS || !c.is_leaf() {
                    continue;
                }
                for k in c.index..c.index + (c.meta & !BVH_LEAF) {
                    let triangle = inst.first_triangle + k;
                    let Some((t, bary)) = intersect(&scene.triangles[triangle as usize], o, d, tmin, t_max) else {
                        continue;
                    };
                    if inst.alpha_tested && !accept(id, triangle, bary) {
                        continue;
                    }
                    best = Some(Hit { t, instance: id, triangle, bary });
                    if any_hit {
                        return best;
                    }
                    t_max = t;
                }
            }
        }
        next = NONE;
        for slot in order {
            let c = &node.children[slot];
            // Hit, still in range after this node's leaves, an inner node or (TLAS) an instance.
            let visit = entry[slot] < MISS && entry[slot] <= t_max && (instance.is_none() || !c.is_leaf()) && c.meta != BVH_LEAF;
            if !visit {
                continue;
            }
            let target = if c.is_leaf() { c.index | BVH_LEAF } else { c.index };
            if next == NONE {
                next = target;
            } else if sp < STACK_SIZE {
                stack[sp] = target;
                sp += 1;
            }
        }
        if next == NONE {
            if instance.is_some() && sp == base {
                instance = None;
                (o, d, inv) = (origin, dir, inverse(dir));
            }
            if sp == 0 {
                return best;
            }
            sp -= 1;
            next = stack[sp];
        }
    }
}
