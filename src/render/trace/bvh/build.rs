//! Building [`Blas`]es and [`Tlas`]es: obvhs' PLOC builder on the primitives' boxes, flattened
//! into [`GpuNode`]s in depth-first order (children after parents). PLOC trees are not
//! balanced (depth ~50 for 10k triangles, ~65 for 1M): subtrees that would make a path longer
//! than [`BVH_MAX_DEPTH`] are rebuilt by median split, which is logarithmic, as deep in the tree as
//! still fits; a failed obvhs build is median-split whole.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Duration;

use bytemuck::Zeroable;

use glam::Vec3;
use obvhs::BvhBuildParams;
use obvhs::bvh2::Bvh2;

use super::wide::{self, GpuWideNode, Widened, widen};
use super::{Aabb, GpuChild, GpuNode, GpuTriangle, Layout, MAX_COORD};
use crate::render::trace::shader_constants::{BVH_LEAF, BVH_MAX_DEPTH, BVH_WIDE_COUNT, BVH_WIDE_LEAVES};

/// The bottom-level BVH of one triangle set, in object space. Node and triangle indices are
/// relative to it: node 0 is the root, triangle 0 its first (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct Blas {
    /// The nodes, root first; never empty (an empty set has one node of two empty leaves).
    /// Built in both layouts: the wide tree is collapsed from it and refitted through it.
    pub nodes: Vec<GpuNode>,
    /// `nodes` collapsed into wide nodes ([`widen`]), root first; only when built for
    /// [`Layout::Wide`].
    pub wide: Option<Widened>,
    /// The triangles in BVH order (with a wide tree, the leaves of a wide node consecutive):
    /// leaves of both layouts reference ranges of it.
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
    /// Only when built for [`Layout::Wide`]: `nodes` collapsed into wide nodes ([`widen`]),
    /// root first, as words; then, from word `20 *` [`Tlas::wide_count`] on, the instance of
    /// each wide leaf (the nodes' `leaf_base` counts in words of this buffer).
    pub wide: Option<Vec<u32>>,
    /// Wide nodes at the start of `wide` (0 without it).
    pub wide_count: usize,
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
// A wide node's leaf counts them in BVH_WIDE_COUNT; two leaves fit a wide node's hit mask.
const _: () = assert!(BLAS_LEAF_SIZE <= 1 << BVH_WIDE_COUNT.bits && 2 * BLAS_LEAF_SIZE <= BVH_WIDE_LEAVES);
/// Leaf size of the median-split fallback for BLASes.
const FALLBACK_LEAF_SIZE: usize = 4;

impl Blas {
    /// Builds the BVH of `triangles` (each `[v0, v1, v2]`, object space) for `layout`: the
    /// binary tree, and with [`Layout::Wide`] its wide collapse. Never panics: see the module
    /// doc for empty, degenerate and non-finite input.
    pub fn build(triangles: &[[Vec3; 3]], layout: Layout) -> Blas {
        let params = BvhBuildParams { max_prims_per_leaf: BLAS_LEAF_SIZE, ..BvhBuildParams::fast_build() };
        Self::build_limited(triangles, layout, params, BVH_MAX_DEPTH)
    }

    /// [`Blas::build`] with obvhs' slow preset (wider PLOC search, more SAH reinsertion;
    /// without pre-splitting, so each triangle is in one leaf): for a BVH built once and
    /// traversed by many rays (the radiosity patches').
    pub fn build_thorough(triangles: &[[Vec3; 3]], layout: Layout) -> Blas {
        let params = BvhBuildParams { max_prims_per_leaf: BLAS_LEAF_SIZE, pre_split: false, ..BvhBuildParams::slow_build() };
        Self::build_limited(triangles, layout, params, BVH_MAX_DEPTH)
    }

    /// [`Blas::build`] with obvhs' `params`, trees deeper than `max_depth` nodes rebuilt by
    /// median split.
    pub(super) fn build_limited(triangles: &[[Vec3; 3]], layout: Layout, params: BvhBuildParams, max_depth: usize) -> Blas {
        let clean: Vec<[Vec3; 3]> = triangles.iter().map(sanitize).collect();
        let boxes: Vec<Aabb> = clean.iter().map(|t| Aabb::of_points(t)).collect();
        let (mut nodes, mut order) = build_nodes(&boxes, params, FALLBACK_LEAF_SIZE, max_depth);
        let wide = (layout == Layout::Wide).then(|| {
            let wide = widen(&nodes);
            order = renumber_leaves(&mut nodes, &order, &wide.leaves);
            wide
        });
        let triangles = order.iter().map(|&i| GpuTriangle::new(&clean[i as usize])).collect();
        let bounds = boxes.iter().fold(Aabb::EMPTY, |b, t| b.union(t));
        Blas { wide, nodes, triangles, order, bounds }
    }

    /// `triangles` in their input order under a root of two empty leaves: no tree, for the
    /// hardware tracer, whose driver builds its own structure over the same triangles (the
    /// stored triangles, order and bounds are those a built BVH would have, in input order).
    pub fn unordered(triangles: &[[Vec3; 3]]) -> Blas {
        let clean: Vec<[Vec3; 3]> = triangles.iter().map(sanitize).collect();
        let bounds = clean.iter().fold(Aabb::EMPTY, |b, t| b.union(&Aabb::of_points(t)));
        let triangles = clean.iter().map(GpuTriangle::new).collect();
        let Blas { nodes, wide, .. } = Blas::build(&[], Layout::Binary);
        Blas { nodes, wide, triangles, order: (0..clean.len() as u32).collect(), bounds }
    }

    /// One BVH over the triangles of several geometries, its members (the static world's
    /// chunks of a region, [`crate::render::trace::regions`]): `triangles` holds each member's
    /// input triangles in turn, `members[m]` is member `m`'s stored order ([`Blas::order`]
    /// of its own storage). Each stored triangle names where its copy lies in the members'
    /// storage: [`GpuTriangle::member`] `m` and [`GpuTriangle::member_triangle`], its index
    /// there. `None` when the counts of `members` do not add up to `triangles`. Never
    /// refitted (a refit would clear the names).
    pub fn merged(triangles: &[[Vec3; 3]], members: &[&[u32]], layout: Layout) -> Option<Blas> {
        if members.iter().map(|order| order.len()).sum::<usize>() != triangles.len() {
            return None;
        }
        // Input triangle j: its member and its index in that member's storage.
        let mut names: Vec<(u32, u32)> = vec![(0, 0); triangles.len()];
        let mut first = 0;
        for (m, order) in members.iter().enumerate() {
            for (stored, &input) in order.iter().enumerate() {
                let name = names.get_mut(first + input as usize)?;
                *name = (m as u32, stored as u32);
            }
            first += order.len();
        }
        let mut blas = Blas::build(triangles, layout);
        for (t, &input) in blas.triangles.iter_mut().zip(&blas.order) {
            (t.member, t.member_triangle) = names[input as usize];
        }
        Some(blas)
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
                    let range = c.index as usize..(c.index + (c.meta & !BVH_LEAF)) as usize;
                    clean[range].iter().fold(Aabb::EMPTY, |b, t| b.union(&Aabb::of_points(t)))
                } else {
                    let [a, b] = self.nodes[c.index as usize].children;
                    a.bounds().union(&b.bounds())
                }
            });
            for (slot, b) in boxes.iter().enumerate() {
                // An empty leaf takes its sibling's box, as when built.
                self.nodes[n].children[slot].set_bounds(if b.is_empty() { boxes[1 - slot] } else { *b });
            }
        }
        self.bounds = clean.iter().fold(Aabb::EMPTY, |b, t| b.union(&Aabb::of_points(t)));
        if let Some(wide) = &mut self.wide {
            wide::refit(&self.nodes, wide);
        }
        true
    }

    /// The nodes of the layout it was built for (wide when it has a wide tree), as the GPU
    /// reads them.
    pub fn node_bytes(&self) -> &[u8] {
        match &self.wide {
            Some(wide) => bytemuck::cast_slice(&wide.nodes),
            None => bytemuck::cast_slice(&self.nodes),
        }
    }

    /// Nodes of the layout it was built for.
    pub fn node_count(&self) -> usize {
        self.wide.as_ref().map_or(self.nodes.len(), |wide| wide.nodes.len())
    }
}

impl Tlas {
    /// Builds the BVH over instances whose eye-space boxes are `instance_bounds` (indexed as
    /// the instance buffer) for `layout` (the binary tree, and with [`Layout::Wide`] its wide
    /// collapse). Fast enough to run every frame for ~10k instances (PLOC, "fast").
    pub fn build(instance_bounds: &[Aabb], layout: Layout) -> Tlas {
        Self::build_limited(instance_bounds, layout, BVH_MAX_DEPTH)
    }

    /// [`Tlas::build`] with trees deeper than `max_depth` nodes rebuilt by median split.
    pub(super) fn build_limited(instance_bounds: &[Aabb], layout: Layout, max_depth: usize) -> Tlas {
        let live: Vec<u32> = (0..instance_bounds.len() as u32).filter(|&i| instance_bounds[i as usize].is_finite()).collect();
        let boxes: Vec<Aabb> = live.iter().map(|&i| instance_bounds[i as usize]).collect();
        let params = BvhBuildParams { max_prims_per_leaf: 1, ..BvhBuildParams::fast_build() };
        let (mut nodes, order) = build_nodes(&boxes, params, 1, max_depth);
        // Leaves hold one primitive: point them at the instance itself.
        for child in nodes.iter_mut().flat_map(|n| n.children.iter_mut()).filter(|c| c.is_leaf() && c.meta != BVH_LEAF) {
            child.index = live[order[child.index as usize] as usize];
        }
        if layout == Layout::Binary {
            return Tlas { nodes, wide: None, wide_count: 0 };
        }
        let Widened { nodes: mut wide_nodes, leaves, .. } = widen(&nodes);
        let wide_count = wide_nodes.len();
        let first_instance = (wide_count * size_of::<GpuWideNode>() / 4) as u32;
        for n in &mut wide_nodes {
            n.leaf_base += first_instance;
        }
        let mut wide: Vec<u32> = bytemuck::cast_slice(&wide_nodes).to_vec();
        wide.extend(leaves.iter().map(|&(instance, _)| instance));
        Tlas { wide: Some(wide), wide_count, nodes }
    }

    /// The wide nodes at the start of [`Tlas::wide`] (none without it).
    pub fn wide_nodes(&self) -> &[GpuWideNode] {
        self.wide.as_ref().map_or(&[], |wide| bytemuck::cast_slice(&wide[..self.wide_count * size_of::<GpuWideNode>() / 4]))
    }

    /// The nodes the GPU reads: the wide buffer (nodes, then instances) when it has one, else
    /// the binary nodes.
    pub fn node_bytes(&self) -> &[u8] {
        match &self.wide {
            Some(wide) => bytemuck::cast_slice(wide),
            None => bytemuck::cast_slice(&self.nodes),
        }
    }
}

/// The primitive order with the wide tree's leaves (`leaves`, binary `(first, count)` in the
/// wide numbering's order) consecutive, from the binary build's `order`; points the binary
/// leaves of `nodes` at their new places.
fn renumber_leaves(nodes: &mut [GpuNode], order: &[u32], leaves: &[(u32, u32)]) -> Vec<u32> {
    let mut renumbered = Vec::with_capacity(order.len());
    // The new first primitive of the binary leaf starting at each old one.
    let mut moved = vec![0u32; order.len()];
    for &(first, count) in leaves {
        moved[first as usize] = renumbered.len() as u32;
        renumbered.extend_from_slice(&order[first as usize..(first + count) as usize]);
    }
    for child in nodes.iter_mut().flat_map(|n| n.children.iter_mut()).filter(|c| c.is_leaf() && c.meta != BVH_LEAF) {
        child.index = moved[child.index as usize];
    }
    renumbered
}

/// The flattened BVH over `boxes` and the primitive order its leaves index: obvhs with
/// `params`, its subtrees that would make a path longer than `max_depth` nodes replaced by
/// median splits with leaves of at most `fallback_leaf` primitives (all of it when obvhs
/// fails). Empty input gives one node of two empty leaves.
fn build_nodes(boxes: &[Aabb], params: BvhBuildParams, fallback_leaf: usize, max_depth: usize) -> (Vec<GpuNode>, Vec<u32>) {
    if boxes.is_empty() {
        return (vec![GpuNode { children: [GpuChild::empty(Aabb::EMPTY); 2] }], Vec::new());
    }
    let prims: Vec<obvhs::aabb::Aabb> = boxes.iter().map(|b| b.to_obvhs()).collect();
    // obvhs is third-party code run on the host program's geometry: a panic in it must not
    // reach the program, so it degrades to a median split of everything.
    let built = catch_unwind(AssertUnwindSafe(|| obvhs::bvh2::builder::build_bvh2(&prims, params, &mut Duration::default())));
    let bvh = built.ok().filter(|bvh| !bvh.nodes.is_empty());
    let mut flat = Flattener { prims: &prims, leaf: fallback_leaf.max(1), max_depth, nodes: Vec::new(), order: Vec::new(), shape: Vec::new() };
    let root = match &bvh {
        Some(bvh) => {
            flat.shape = shapes(bvh);
            flat.child(bvh, 0, 1)
        }
        None => flat.median(&mut (0..prims.len() as u32).collect::<Vec<_>>()),
    };
    if root.is_leaf() {
        flat.nodes.push(GpuNode { children: [root, GpuChild::empty(root.bounds())] });
    }
    (flat.nodes, flat.order)
}

/// Height (nodes on the longest downward path, 0 for a leaf) and primitive count of every
/// node of `bvh`, computed without recursion (an obvhs tree may be deep).
fn shapes(bvh: &Bvh2) -> Vec<(usize, usize)> {
    let mut shape = vec![(0, 0); bvh.nodes.len()];
    let mut stack = vec![(0usize, false)];
    while let Some((id, done)) = stack.pop() {
        let node = &bvh.nodes[id];
        if node.is_leaf() {
            shape[id] = (0, node.prim_count as usize);
        } else if done {
            let (a, b) = (shape[node.first_index as usize], shape[node.first_index as usize + 1]);
            shape[id] = (1 + a.0.max(b.0), a.1 + b.1);
        } else {
            stack.extend([(id, true), (node.first_index as usize, false), (node.first_index as usize + 1, false)]);
        }
    }
    shape
}

/// Nodes on the longest path of a median split over `count` primitives with `leaf` per leaf.
fn median_height(mut count: usize, leaf: usize) -> usize {
    let mut height = 0;
    while count > leaf {
        count -= count / 2;
        height += 1;
    }
    height
}

/// Writes [`GpuNode`]s in depth-first order (children after parents).
struct Flattener<'a> {
    /// The primitives' boxes.
    prims: &'a [obvhs::aabb::Aabb],
    /// Leaf size of median splits.
    leaf: usize,
    /// The most nodes on a path.
    max_depth: usize,
    /// The output nodes.
    nodes: Vec<GpuNode>,
    /// The output primitive order.
    order: Vec<u32>,
    /// [`shapes`] of the obvhs tree.
    shape: Vec<(usize, usize)>,
}

impl Flattener<'_> {
    /// The child slot for obvhs node `id`, whose node (if inner) lands at `depth` (the root is
    /// 1). Invariant: a median split of its primitives fits there. It keeps obvhs' split while
    /// the whole subtree fits or both children could still be median-split one level lower,
    /// and median-splits it otherwise.
    fn child(&mut self, bvh: &Bvh2, id: usize, depth: usize) -> GpuChild {
        let node = &bvh.nodes[id];
        if node.is_leaf() {
            let first = node.first_index as usize;
            return self.leaf_child(&bvh.primitive_indices[first..first + node.prim_count as usize]);
        }
        let (a, b) = (node.first_index as usize, node.first_index as usize + 1);
        let fits = depth - 1 + self.shape[id].0 <= self.max_depth;
        let split_fits = [a, b].iter().all(|&c| depth + median_height(self.shape[c].1, self.leaf) <= self.max_depth);
        if !fits && !split_fits {
            let mut indices = Vec::with_capacity(self.shape[id].1);
            collect(bvh, id, &mut indices);
            return self.median(&mut indices);
        }
        let at = self.push_node();
        let children = [self.child(bvh, a, depth + 1), self.child(bvh, b, depth + 1)];
        self.nodes[at].children = children;
        self.inner_child(at)
    }

    /// The child slot of a median split over `indices` (reordered).
    fn median(&mut self, indices: &mut [u32]) -> GpuChild {
        if indices.len() <= self.leaf {
            return self.leaf_child(indices);
        }
        let prims = self.prims;
        let centroids = indices.iter().fold(obvhs::aabb::Aabb::empty(), |mut b, &i| *b.extend(prims[i as usize].center()));
        let axis = centroids.largest_axis();
        let mid = indices.len() / 2;
        indices.select_nth_unstable_by(mid, |&a, &b| prims[a as usize].center_axis(axis).total_cmp(&prims[b as usize].center_axis(axis)));
        let at = self.push_node();
        let (low, high) = indices.split_at_mut(mid);
        let children = [self.median(low), self.median(high)];
        self.nodes[at].children = children;
        self.inner_child(at)
    }

    /// Appends a node to fill in later; returns its index.
    fn push_node(&mut self) -> usize {
        self.nodes.push(GpuNode::zeroed());
        self.nodes.len() - 1
    }

    /// The child slot of the filled node `at`: its box is the union of its children's.
    fn inner_child(&self, at: usize) -> GpuChild {
        let [a, b] = self.nodes[at].children;
        let bounds = a.bounds().union(&b.bounds());
        GpuChild { min: bounds.min.into(), index: at as u32, max: bounds.max.into(), meta: 0 }
    }

    /// The child slot of a leaf of `prims`; appends them to the order.
    fn leaf_child(&mut self, prims: &[u32]) -> GpuChild {
        let bounds = prims.iter().fold(Aabb::EMPTY, |b, &i| b.union(&Aabb::from_obvhs(&self.prims[i as usize])));
        let index = self.order.len() as u32;
        self.order.extend_from_slice(prims);
        GpuChild { min: bounds.min.into(), index, max: bounds.max.into(), meta: BVH_LEAF | prims.len() as u32 }
    }
}

/// Appends the primitives under obvhs node `id` to `out`.
fn collect(bvh: &Bvh2, id: usize, out: &mut Vec<u32>) {
    let mut stack = vec![id];
    while let Some(id) = stack.pop() {
        let node = &bvh.nodes[id];
        if node.is_leaf() {
            let first = node.first_index as usize;
            out.extend_from_slice(&bvh.primitive_indices[first..first + node.prim_count as usize]);
        } else {
            stack.extend([node.first_index as usize, node.first_index as usize + 1]);
        }
    }
}
