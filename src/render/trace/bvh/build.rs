//! Building [`Blas`]es and [`Tlas`]es: obvhs' PLOC builder on the primitives' boxes, flattened
//! into [`GpuNode`]s in depth-first order (children after parents), with a median-split
//! fallback for trees deeper than [`MAX_DEPTH`] or a failed obvhs build.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Duration;

use glam::Vec3;
use obvhs::BvhBuildParams;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::node::Bvh2Node;

use super::{Aabb, GpuChild, GpuNode, GpuTriangle, LEAF, MAX_COORD, MAX_DEPTH};

/// The bottom-level BVH of one triangle set, in object space. Node and triangle indices are
/// relative to it: node 0 is the root, triangle 0 its first (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct Blas {
    /// The nodes, root first; never empty (an empty set has one node of two empty leaves).
    pub nodes: Vec<GpuNode>,
    /// The triangles in BVH order: leaves reference ranges of it.
    pub triangles: Vec<GpuTriangle>,
    /// `order[k]`: the index in the input of stored triangle `k` (reorders per-triangle
    /// shading attributes the same way).
    pub order: Vec<u32>,
    /// The box of every triangle; [`Aabb::EMPTY`] for an empty set.
    pub bounds: Aabb,
}

/// The top-level BVH over a frame's instances, in eye space. Each leaf is one instance, by
/// its index in the instance buffer; instances with empty or non-finite bounds are left out.
#[derive(Clone, Debug, PartialEq)]
pub struct Tlas {
    /// The nodes, root first; never empty.
    pub nodes: Vec<GpuNode>,
}

/// The triangle with non-finite positions collapsed onto its first finite vertex (or the
/// origin) and coordinates clamped to ±[`MAX_COORD`] (see the module doc).
fn sanitize(t: &[Vec3; 3]) -> [Vec3; 3] {
    if t.iter().all(|v| v.is_finite()) {
        return t.map(|v| v.clamp(Vec3::splat(-MAX_COORD), Vec3::splat(MAX_COORD)));
    }
    let p = t.iter().find(|v| v.is_finite()).map_or(Vec3::ZERO, |v| v.clamp(Vec3::splat(-MAX_COORD), Vec3::splat(MAX_COORD)));
    [p; 3]
}

/// The most primitives a BLAS leaf holds.
const BLAS_LEAF_SIZE: u32 = 8;
/// Leaf size of the median-split fallback for BLASes.
const FALLBACK_LEAF_SIZE: usize = 4;

impl Blas {
    /// Builds the BVH of `triangles` (each `[v0, v1, v2]`, object space). Never panics: see the
    /// module doc for empty, degenerate and non-finite input.
    pub fn build(triangles: &[[Vec3; 3]]) -> Blas {
        let params = BvhBuildParams { max_prims_per_leaf: BLAS_LEAF_SIZE, ..BvhBuildParams::medium_build() };
        Self::build_limited(triangles, params, MAX_DEPTH)
    }

    /// [`Blas::build`] with obvhs' `params`, trees deeper than `max_depth` nodes rebuilt by
    /// median split.
    pub(super) fn build_limited(triangles: &[[Vec3; 3]], params: BvhBuildParams, max_depth: usize) -> Blas {
        let clean: Vec<[Vec3; 3]> = triangles.iter().map(sanitize).collect();
        let boxes: Vec<Aabb> = clean.iter().map(|t| Aabb::of_points(t)).collect();
        let (nodes, order) = build_nodes(&boxes, params, FALLBACK_LEAF_SIZE, max_depth);
        let triangles = order.iter().map(|&i| GpuTriangle::new(&clean[i as usize])).collect();
        let bounds = boxes.iter().fold(Aabb::EMPTY, |b, t| b.union(t));
        Blas { nodes, triangles, order, bounds }
    }

    /// Moves the vertices of a built BVH: `triangles` is the same set in the same input order
    /// with new positions. Stores them and updates every box bottom-up, keeping the tree (its
    /// quality drops as the geometry drifts from the built shape; rebuild then). Returns false
    /// and changes nothing when the triangle count differs.
    #[must_use]
    pub fn refit(&mut self, triangles: &[[Vec3; 3]]) -> bool {
        if triangles.len() != self.order.len() {
            return false;
        }
        let clean: Vec<[Vec3; 3]> = self.order.iter().map(|&i| sanitize(&triangles[i as usize])).collect();
        for (stored, t) in self.triangles.iter_mut().zip(&clean) {
            *stored = GpuTriangle::new(t);
        }
        for n in (0..self.nodes.len()).rev() {
            let boxes = self.nodes[n].children.map(|c| {
                if c.is_leaf() {
                    let range = c.index as usize..(c.index + (c.meta & !LEAF)) as usize;
                    clean[range].iter().fold(Aabb::EMPTY, |b, t| b.union(&Aabb::of_points(t)))
                } else {
                    let [a, b] = self.nodes[c.index as usize].children;
                    a.bounds().union(&b.bounds())
                }
            });
            for (slot, b) in boxes.iter().enumerate() {
                let fitted = if b.is_empty() { boxes[1 - slot] } else { *b };
                let child = &mut self.nodes[n].children[slot];
                let fitted = if fitted.is_empty() { Aabb { min: Vec3::ZERO, max: Vec3::ZERO } } else { fitted };
                child.min = fitted.min.into();
                child.max = fitted.max.into();
            }
        }
        self.bounds = clean.iter().fold(Aabb::EMPTY, |b, t| b.union(&Aabb::of_points(t)));
        true
    }

    /// Appends this BVH to a shared node and triangle buffer; returns the `blas_root` and
    /// `first_triangle` an instance of it records.
    pub fn append_to(&self, nodes: &mut Vec<GpuNode>, triangles: &mut Vec<GpuTriangle>) -> (u32, u32) {
        let at = (nodes.len() as u32, triangles.len() as u32);
        nodes.extend_from_slice(&self.nodes);
        triangles.extend_from_slice(&self.triangles);
        at
    }
}

impl Tlas {
    /// Builds the BVH over instances whose eye-space boxes are `instance_bounds` (indexed as
    /// the instance buffer). Fast enough to run every frame for ~10k instances (PLOC, "fast").
    pub fn build(instance_bounds: &[Aabb]) -> Tlas {
        Self::build_limited(instance_bounds, MAX_DEPTH)
    }

    /// [`Tlas::build`] with trees deeper than `max_depth` nodes rebuilt by median split.
    pub(super) fn build_limited(instance_bounds: &[Aabb], max_depth: usize) -> Tlas {
        let live: Vec<u32> = (0..instance_bounds.len() as u32).filter(|&i| instance_bounds[i as usize].is_finite()).collect();
        let boxes: Vec<Aabb> = live.iter().map(|&i| instance_bounds[i as usize]).collect();
        let params = BvhBuildParams { max_prims_per_leaf: 1, ..BvhBuildParams::fast_build() };
        let (mut nodes, order) = build_nodes(&boxes, params, 1, max_depth);
        // Leaves hold one primitive: point them at the instance itself.
        for child in nodes.iter_mut().flat_map(|n| n.children.iter_mut()).filter(|c| c.is_leaf() && c.meta != LEAF) {
            child.index = live[order[child.index as usize] as usize];
        }
        Tlas { nodes }
    }
}

/// The flattened BVH over `boxes` and the primitive order its leaves index: obvhs with
/// `params`, or, when that fails or is deeper than `max_depth`, a median split with leaves of
/// at most `fallback_leaf` primitives. Empty input gives one node of two empty leaves.
fn build_nodes(boxes: &[Aabb], params: BvhBuildParams, fallback_leaf: usize, max_depth: usize) -> (Vec<GpuNode>, Vec<u32>) {
    if boxes.is_empty() {
        return empty_nodes();
    }
    let prims: Vec<obvhs::aabb::Aabb> = boxes.iter().map(|b| b.to_obvhs()).collect();
    // obvhs is third-party code run on the host program's geometry: a panic in it must not
    // reach the program, so it degrades to the fallback.
    let built = catch_unwind(AssertUnwindSafe(|| obvhs::bvh2::builder::build_bvh2(&prims, params, &mut Duration::default())));
    if let Some(flat) = built.ok().and_then(|bvh| flatten(&bvh, max_depth)) {
        return flat;
    }
    // A median split over n primitives is ceil(log2(n / leaf)) nodes deep: below MAX_DEPTH
    // for any count that fits memory (max_depth is lower only in tests that force this path).
    flatten(&median_split(&prims, fallback_leaf), usize::MAX).unwrap_or_else(empty_nodes)
}

/// The BVH over nothing: one node of two empty leaves, so that traversal reads a valid root.
fn empty_nodes() -> (Vec<GpuNode>, Vec<u32>) {
    (vec![GpuNode { children: [GpuChild::empty(Aabb::EMPTY); 2] }], Vec::new())
}

/// `bvh` as [`GpuNode`]s in depth-first order with the primitive order of its leaves, or
/// `None` when some path has more than `max_depth` nodes.
fn flatten(bvh: &Bvh2, max_depth: usize) -> Option<(Vec<GpuNode>, Vec<u32>)> {
    let root = bvh.nodes.first()?;
    let mut nodes = Vec::with_capacity(bvh.nodes.len() / 2 + 1);
    let mut order = Vec::with_capacity(bvh.primitive_indices.len());
    if root.is_leaf() {
        let leaf = leaf_child(bvh, root, &mut order);
        nodes.push(GpuNode { children: [leaf, GpuChild::empty(leaf.bounds())] });
    } else {
        flatten_inner(bvh, 0, 1, max_depth, &mut nodes, &mut order)?;
    }
    Some((nodes, order))
}

/// Emits the inner obvhs node `id`, at `depth` (the root is 1), and its subtree.
fn flatten_inner(bvh: &Bvh2, id: usize, depth: usize, max_depth: usize, nodes: &mut Vec<GpuNode>, order: &mut Vec<u32>) -> Option<()> {
    if depth > max_depth {
        return None;
    }
    let at = nodes.len();
    nodes.push(bytemuck::Zeroable::zeroed());
    let first = bvh.nodes[id].first_index as usize;
    for slot in 0..2 {
        let node = &bvh.nodes[first + slot];
        let child = if node.is_leaf() {
            leaf_child(bvh, node, order)
        } else {
            let b = Aabb::from_obvhs(node.aabb());
            let child = GpuChild { min: b.min.into(), index: nodes.len() as u32, max: b.max.into(), meta: 0 };
            flatten_inner(bvh, first + slot, depth + 1, max_depth, nodes, order)?;
            child
        };
        nodes[at].children[slot] = child;
    }
    Some(())
}

/// The child slot of the obvhs leaf `node`; appends its primitives to `order`.
fn leaf_child(bvh: &Bvh2, node: &Bvh2Node, order: &mut Vec<u32>) -> GpuChild {
    let b = Aabb::from_obvhs(node.aabb());
    let first = node.first_index as usize;
    let index = order.len() as u32;
    order.extend_from_slice(&bvh.primitive_indices[first..first + node.prim_count as usize]);
    GpuChild { min: b.min.into(), index, max: b.max.into(), meta: LEAF | node.prim_count }
}

/// A balanced BVH: split at the median centroid along the widest centroid axis, down to
/// `leaf` primitives.
fn median_split(prims: &[obvhs::aabb::Aabb], leaf: usize) -> Bvh2 {
    let mut indices: Vec<u32> = (0..prims.len() as u32).collect();
    let mut nodes = vec![Bvh2Node::default()];
    split(prims, &mut indices, 0, 0, leaf.max(1), &mut nodes);
    Bvh2 { nodes, primitive_indices: indices, ..Bvh2::default() }
}

/// Fills `nodes[slot]` with the subtree over `indices`, which start at `offset` in the
/// primitive order.
fn split(prims: &[obvhs::aabb::Aabb], indices: &mut [u32], offset: u32, slot: usize, leaf: usize, nodes: &mut Vec<Bvh2Node>) {
    let bounds = indices.iter().fold(obvhs::aabb::Aabb::empty(), |b, &i| b.union(&prims[i as usize]));
    if indices.len() <= leaf {
        nodes[slot] = Bvh2Node::new(bounds, indices.len() as u32, offset);
        return;
    }
    let centroids = indices.iter().fold(obvhs::aabb::Aabb::empty(), |mut b, &i| *b.extend(prims[i as usize].center()));
    let axis = centroids.largest_axis();
    let mid = indices.len() / 2;
    indices.select_nth_unstable_by(mid, |&a, &b| prims[a as usize].center_axis(axis).total_cmp(&prims[b as usize].center_axis(axis)));
    let first = nodes.len();
    nodes.extend([Bvh2Node::default(); 2]);
    nodes[slot] = Bvh2Node::new(bounds, 0, first as u32);
    let (low, high) = indices.split_at_mut(mid);
    split(prims, low, offset, first, leaf, nodes);
    split(prims, high, offset + mid as u32, first + 1, leaf, nodes);
}
#[cfg(test)]
pub(super) fn flatten_for_tests(bvh: &Bvh2) -> Vec<GpuNode> { flatten(bvh, usize::MAX).unwrap().0 }
