//! The BVHs of the compute tracer: a bottom-level BVH ([`Blas`]) per triangle set, in object
//! space and reused across frames, and a top-level BVH ([`Tlas`]) over the instances, in eye
//! space and rebuilt every frame. Built on the CPU, uploaded as flat arrays of [`GpuNode`] and
//! [`GpuTriangle`], traversed by `shaders/trace/bvh.glsl` (or, collapsed into [`wide`] nodes,
//! by `shaders/trace/bvh_wide.glsl`); [`cpu`] is the binary traversal in Rust (tests,
//! reference).
//!
//! Build: `obvhs`' PLOC (Morton-sorted nearest-neighbour clustering), then reinsertion
//! optimisation and an SAH-driven leaf collapse (up to 8 triangles per BLAS leaf, one instance
//! per TLAS leaf). obvhs has no binned/sweep SAH builder; of its PLOC presets, "fast" is used
//! for both: on 1.5M triangles (`tests::bvh_build_speed`) it built 2.5x faster than "medium"
//! with an SAH cost 2% lower, and "slow" (without spatial splits, which would duplicate
//! triangles) was 1.5% lower than "fast" for 4x the time.
//! Subtrees that would make a path longer than [`BVH_MAX_DEPTH`](super::shader_constants::BVH_MAX_DEPTH) nodes are rebuilt by median split
//! (logarithmic depth), and a panic inside obvhs falls back to a median split of everything
//! ([`build`]), so the GPU stack never overflows.
//!
//! Layout (std430, mirrored by the GLSL structs of `bvh.glsl`; the build checks the sizes against
//! the compiled `pathtrace.comp`, see [`crate::render::shader_abi`]):
//! - a [`GpuNode`] is 64 bytes holding both children's boxes, so one fetch tests both. Each
//!   child is `(min.xyz, index)`, `(max.xyz, meta)`. `meta == 0`: an inner child, `index` is a
//!   node of the same BVH (relative to its root for a BLAS: the GPU adds the instance's
//!   `blas_root`). `meta & BVH_LEAF`: a leaf of `meta & !BVH_LEAF` primitives from `index` on
//!   (BLAS: triangles relative to the geometry's first, the GPU adds `first_triangle`; TLAS:
//!   always one instance, `index` = the instance). A leaf of 0 primitives is an empty child
//!   (a BVH whose root is one leaf, or the empty BLAS).
//! - children come after their parents (node 0 is the root): [`Blas::refit`] sweeps backwards.
//! - a [`GpuTriangle`] is `v0, e1 = v1 - v0, e2 = v2 - v0` (Möller–Trumbore), 48 bytes.
//!
//! A BVH built for [`Layout::Wide`] is also collapsed into compressed wide nodes ([`wide`]: 80
//! bytes, up to 8 children with byte-quantised boxes in slots ordered by ray octant, the same
//! leaves and triangle order: the triangles are ordered so that each wide node's leaves are
//! consecutive), which the GPU then traverses; one built for [`Layout::Binary`] has no wide
//! tree (the collapse took about 40 % of a BLAS build's CPU time, bench/pathtrace.md).
//!
//! Robustness: non-finite positions make their triangle degenerate (collapsed onto its first
//! finite vertex, or the origin): it is kept in place, so `order` stays a permutation and refit
//! keeps the topology, and it is never hit. Finite coordinates are clamped to ±[`MAX_COORD`] so
//! that box and triangle arithmetic cannot overflow. Degenerate triangles (zero area) never hit.

pub mod build;
pub mod cpu;
#[cfg(test)]
mod tests;
pub mod wide;

use bytemuck::{Pod, Zeroable};
use glam::{Affine3A, Vec3, Vec3A};

use super::shader_constants::BVH_LEAF;

pub use build::{Blas, Tlas};
pub use wide::GpuWideNode;

/// The node layout the compute tracer uploads and traverses (`[pathtrace] bvh`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Layout {
    /// [`GpuWideNode`]s, traversed by `bvh_wide.glsl` (`"wide"`): about a third of the node
    /// visits. Not the default until the GPU measures it faster (bench/pathtrace.md: the first,
    /// uncompressed wide layout was slower on the H200).
    Wide,
    /// [`GpuNode`]s, traversed by `bvh.glsl` (`"binary"`).
    #[default]
    Binary,
}

impl Layout {
    /// Bytes of one node.
    pub fn node_size(self) -> u64 {
        match self {
            Layout::Wide => size_of::<GpuWideNode>() as u64,
            Layout::Binary => size_of::<GpuNode>() as u64,
        }
    }

    /// The setting's name (`"wide"`, `"binary"`).
    pub fn name(self) -> &'static str {
        match self {
            Layout::Wide => "wide",
            Layout::Binary => "binary",
        }
    }
}

/// Largest magnitude of a coordinate in a BVH; larger finite ones are clamped to it. Its square
/// still fits an `f32`, so products in the triangle and box tests stay finite.
pub const MAX_COORD: f32 = 1.0e18;

/// An axis-aligned box. Empty when `min > max` on some axis ([`Aabb::EMPTY`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lowest corner.
    pub min: Vec3,
    /// Highest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The box containing nothing; the identity of [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb { min: Vec3::INFINITY, max: Vec3::NEG_INFINITY };

    /// The box of `points`.
    pub fn of_points(points: &[Vec3]) -> Aabb {
        points.iter().fold(Aabb::EMPTY, |b, &p| Aabb { min: b.min.min(p), max: b.max.max(p) })
    }

    /// Whether the box contains no point (also when a bound is NaN).
    pub fn is_empty(&self) -> bool {
        !(self.min.cmple(self.max).all())
    }

    /// Whether the box is non-empty with finite bounds.
    pub fn is_finite(&self) -> bool {
        !self.is_empty() && self.min.is_finite() && self.max.is_finite()
    }

    /// The smallest box containing both.
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb { min: self.min.min(other.min), max: self.max.max(other.max) }
    }

    /// Half the surface area (the SAH's measure); 0 for an empty box.
    pub fn half_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let d = self.max - self.min;
        d.x * d.y + d.y * d.z + d.z * d.x
    }

    /// The box of this box's corners transformed by `m` (Arvo's method: per output axis, the
    /// smaller and larger products of each input axis). An empty box stays empty.
    pub fn transformed(&self, m: &Affine3A) -> Aabb {
        if self.is_empty() {
            return Aabb::EMPTY;
        }
        let mut min = m.translation;
        let mut max = m.translation;
        for (axis, column) in [m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis].into_iter().enumerate() {
            let a = column * self.min[axis];
            let b = column * self.max[axis];
            min += a.min(b);
            max += a.max(b);
        }
        Aabb { min: min.into(), max: max.into() }
    }

    /// obvhs' box type.
    fn to_obvhs(self) -> obvhs::aabb::Aabb {
        obvhs::aabb::Aabb::new(Vec3A::from(self.min), Vec3A::from(self.max))
    }

    /// From obvhs' box type.
    fn from_obvhs(b: &obvhs::aabb::Aabb) -> Aabb {
        Aabb { min: b.min.into(), max: b.max.into() }
    }
}

/// The SAH cost of the BVH `nodes` (root first) relative to its root's box: 1 per node
/// visited and 1 per primitive tested, each weighted by the chance that a ray through the
/// root's box enters the node's (area ratio). Compares trees of one geometry (a refitted tree
/// with its build); 0 when the root's box has no area.
pub fn sah_cost(nodes: &[GpuNode]) -> f32 {
    let Some(root) = nodes.first() else { return 0.0 };
    let area = root.children[0].bounds().union(&root.children[1].bounds()).half_area();
    if !(area > 0.0 && area.is_finite()) {
        return 0.0;
    }
    let mut cost = 0.0;
    for n in nodes {
        cost += n.children[0].bounds().union(&n.children[1].bounds()).half_area();
        for c in n.children.iter().filter(|c| c.is_leaf()) {
            cost += c.bounds().half_area() * (c.meta & !BVH_LEAF) as f32;
        }
    }
    cost / area
}

/// One child slot of a [`GpuNode`]: its box and the child it refers to (`BvhChild` in
/// `bvh.glsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuChild {
    /// Lowest corner of the child's box.
    pub min: [f32; 3],
    /// Inner child: its node index. Leaf: its first primitive.
    pub index: u32,
    /// Highest corner of the child's box.
    pub max: [f32; 3],
    /// 0 for an inner child; [`BVH_LEAF`] | primitive count for a leaf.
    pub meta: u32,
}

impl GpuChild {
    /// An empty leaf (no primitives) with the box `bounds` (the sibling's, so it costs no extra
    /// box hits).
    fn empty(bounds: Aabb) -> GpuChild {
        let mut child = GpuChild { min: [0.0; 3], index: 0, max: [0.0; 3], meta: BVH_LEAF };
        child.set_bounds(bounds);
        child
    }

    /// Sets the child's box; an empty one is stored as the point at the origin (the GPU box
    /// test swaps inverted bounds, so an inverted box would not miss).
    fn set_bounds(&mut self, bounds: Aabb) {
        let b = if bounds.is_empty() { Aabb { min: Vec3::ZERO, max: Vec3::ZERO } } else { bounds };
        self.min = b.min.into();
        self.max = b.max.into();
    }

    /// The child's box.
    pub fn bounds(&self) -> Aabb {
        Aabb { min: self.min.into(), max: self.max.into() }
    }

    /// Whether the child is a leaf.
    pub fn is_leaf(&self) -> bool {
        self.meta & BVH_LEAF != 0
    }
}

/// A BVH node: the boxes and references of its two children (`BvhNode` in `bvh.glsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuNode {
    /// The two children, in no particular order (traversal visits the nearer first).
    pub children: [GpuChild; 2],
}

/// A triangle as the traversal tests it (`BvhTriangle` in `triangles.glsl`): a vertex and the
/// two edges from it, each padded to a `vec4`; in a merged BVH, the padding names the member
/// triangle it copies.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuTriangle {
    /// The first vertex.
    pub v0: [f32; 3],
    /// In a merged BVH ([`Blas::merged`]): the member whose triangle this is (0 elsewhere).
    pub member: u32,
    /// `v1 - v0`.
    pub e1: [f32; 3],
    /// In a merged BVH: the triangle's index in its member's storage (0 elsewhere).
    pub member_triangle: u32,
    /// `v2 - v0`.
    pub e2: [f32; 3],
    /// Padding (`e2.w`).
    pub pad2: u32,
}

include!(concat!(env!("OUT_DIR"), "/layouts/trace_bvh.rs"));

impl GpuTriangle {
    /// The stored form of `[v0, v1, v2]` (already sanitised).
    fn new(t: &[Vec3; 3]) -> GpuTriangle {
        GpuTriangle { v0: t[0].into(), member: 0, e1: (t[1] - t[0]).into(), member_triangle: 0, e2: (t[2] - t[0]).into(), pad2: 0 }
    }
}
