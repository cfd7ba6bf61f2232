//! Wide BVHs: a built binary BVH ([`GpuNode`]s) collapsed into nodes of up to
//! [`BVH_WIDTH`] children with quantised boxes ([`GpuWideNode`], 96 bytes; after Ylitie,
//! Karras and Laine 2017, "Efficient Incoherent Ray Traversal on GPUs Through Compressed
//! Wide BVHs"), traversed by `shaders/trace/bvh_wide.glsl`. The leaves and the triangle order
//! are the binary tree's, so both layouts trace the same triangle buffer and find the same
//! closest hits: a wide child's box holds the binary child's box it stands for (quantised
//! outwards, checked in `f32` as the GPU decodes it), so no ray that enters a binary box misses
//! its wide box.
//!
//! Collapse: a wide node starts as the binary node's two children and repeatedly replaces its
//! inner child of largest surface area by that child's two children, up to [`BVH_WIDTH`].
//!
//! Stack bound: at a node the traversal continues into the nearest hit child and pushes the
//! other hit ones that need a visit (inner children; in a TLAS also the instances). Each node is
//! built with a budget, the entries its subtree may still push along any path; the root's is
//! [`BVH_WIDE_BUDGET`]. A binary subtree's least need is what it pushes collapsed two children
//! at a time (a node with `k` pushed children pushes `k - 1`, plus the most of its inner
//! children's); it is at most the binary height ([`BVH_MAX_DEPTH`] at the root). A node that
//! would push `p` entries takes the collapse only if `p` and each of its inner children's least
//! needs fit the budget less `p`; otherwise it tries 4 children, then 2, which always fits when
//! the budget holds the node's least need.
//!
//! Quantisation per axis: the node's lowest corner `origin` and a power of two `2^e` with
//! `255 * 2^e` at least the node's extent; a child's box is `origin + q * 2^e` for bytes
//! `q_lo <= q_hi` (decoded as `origin + float(q) * scale`: the product is exact, so a fused
//! multiply-add decodes the same).

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use super::{Aabb, GpuChild, GpuNode};
use crate::render::trace::shader_constants::{BVH_EMPTY, BVH_LEAF, BVH_MAX_DEPTH, BVH_WIDE_BUDGET, BVH_WIDE_COUNT, BVH_WIDE_INDEX, BVH_WIDTH};

/// A wide BVH node (`BvhWideNode` in `bvh_wide.glsl`): the quantisation frame and, per child
/// slot, its quantised box and reference.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuWideNode {
    /// Lowest corner of the node's box: the quantisation origin.
    pub origin: [f32; 3],
    /// Biased `f32` exponents of the per-axis scales: byte `axis` is `e + 127` for `2^e`.
    pub exponents: u32,
    /// Quantised lowest corners: word `2 * axis + slot / 4`, byte `slot % 4`.
    pub lo: [u32; 6],
    /// Quantised highest corners, as `lo`.
    pub hi: [u32; 6],
    /// Per slot: [`BVH_EMPTY`]; an inner child's node (relative to the BVH's root); or
    /// [`BVH_LEAF`] with [`BVH_WIDE_COUNT`] (primitives less one) and [`BVH_WIDE_INDEX`] (the
    /// first primitive; a TLAS leaf is one instance, the instance's index).
    pub children: [u32; BVH_WIDTH],
}

include!(concat!(env!("OUT_DIR"), "/layouts/trace_bvh_wide.rs"));

impl GpuWideNode {
    /// The box of child `slot` as the GPU decodes it (`None` for an empty slot).
    pub fn child_bounds(&self, slot: usize) -> Option<Aabb> {
        if self.children[slot] == BVH_EMPTY {
            return None;
        }
        let byte = |words: &[u32; 6], axis: usize| (words[2 * axis + slot / 4] >> (8 * (slot % 4))) & 0xff;
        let corner = |words: &[u32; 6]| Vec3::from_array(std::array::from_fn(|axis| decode(self.origin[axis], self.scale(axis), byte(words, axis))));
        Some(Aabb { min: corner(&self.lo), max: corner(&self.hi) })
    }

    /// The scale of `axis`: `2^e`.
    fn scale(&self, axis: usize) -> f32 {
        f32::from_bits(((self.exponents >> (8 * axis)) & 0xff) << 23)
    }
}

/// `origin + q * scale` in `f32`, as `bvh_wide.glsl` decodes a quantised bound.
fn decode(origin: f32, scale: f32, q: u32) -> f32 {
    origin + q as f32 * scale
}

/// The quantisation of one axis of a node: biased exponent and, per box, the bytes of its
/// bounds. Widens the scale until every bound fits outwards (a box's decoded `lo` at most its
/// `lo`, decoded `hi` at least its `hi`).
fn quantise_axis(origin: f32, extent: f32, bounds: &[(f32, f32)]) -> (u32, Vec<(u32, u32)>) {
    // The smallest normal power of two with 255 * 2^e >= extent, then larger ones if rounding
    // of `origin + q * 2^e` leaves a bound outside.
    let mut biased = 1u32;
    while biased < 254 && 255.0 * f32::from_bits(biased << 23) < extent {
        biased += 1;
    }
    loop {
        let scale = f32::from_bits(biased << 23);
        let fit = |&(lo, hi): &(f32, f32)| -> Option<(u32, u32)> {
            let mut qlo = ((lo - origin) / scale).floor().clamp(0.0, 255.0) as u32;
            while qlo > 0 && decode(origin, scale, qlo) > lo {
                qlo -= 1;
            }
            let mut qhi = ((hi - origin) / scale).ceil().clamp(0.0, 255.0) as u32;
            while qhi < 255 && decode(origin, scale, qhi) < hi {
                qhi += 1;
            }
            (decode(origin, scale, qlo) <= lo && decode(origin, scale, qhi) >= hi).then_some((qlo, qhi))
        };
        let quantised: Option<Vec<(u32, u32)>> = bounds.iter().map(fit).collect();
        match quantised {
            Some(q) => return (biased, q),
            // Coordinates are clamped to MAX_COORD (2^60): 2^127 always fits.
            None if biased < 254 => biased += 1,
            None => return (biased, bounds.iter().map(|_| (0, 255)).collect()),
        }
    }
}

/// Collapses the binary BVH `nodes` (root first, as built by [`super::build`]) into wide
/// nodes, root first. `leaves_pushed`: whether the traversal pushes leaves (a TLAS: each leaf
/// is an instance to enter) or tests them at once (a BLAS: triangles).
pub fn widen(nodes: &[GpuNode], leaves_pushed: bool) -> Vec<GpuWideNode> {
    let mut w = Widener { nodes, needs: least_needs(nodes, leaves_pushed), leaves_pushed, out: Vec::new() };
    let root = GpuChild { min: [0.0; 3], index: 0, max: [0.0; 3], meta: 0 };
    w.node(root, BVH_WIDE_BUDGET);
    w.out
}

// The root's budget must hold a binary tree's height (see the module doc).
const _: () = assert!(BVH_WIDE_BUDGET >= BVH_MAX_DEPTH);

/// The least need of every node of `nodes` (module doc; children come after their parents,
/// so one backward sweep).
fn least_needs(nodes: &[GpuNode], leaves_pushed: bool) -> Vec<usize> {
    let mut need = vec![0; nodes.len()];
    for n in (0..nodes.len()).rev() {
        let children = nodes[n].children.iter().filter(|c| c.meta != BVH_LEAF);
        let pushed = children.clone().filter(|c| leaves_pushed || !c.is_leaf()).count();
        let below = children.filter(|c| !c.is_leaf()).map(|c| need[c.index as usize]).max().unwrap_or(0);
        need[n] = pushed.saturating_sub(1) + below;
    }
    need
}

/// The collapse in progress.
struct Widener<'a> {
    nodes: &'a [GpuNode],
    needs: Vec<usize>,
    leaves_pushed: bool,
    out: Vec<GpuWideNode>,
}

impl Widener<'_> {
    /// Least need of a child slot (0 for a leaf).
    fn need(&self, c: &GpuChild) -> usize {
        if c.is_leaf() { 0 } else { self.needs[c.index as usize] }
    }

    /// The children of binary node `n`, empty leaves left out.
    fn children(&self, n: u32) -> impl Iterator<Item = GpuChild> + '_ {
        self.nodes[n as usize].children.into_iter().filter(|c| c.meta != BVH_LEAF)
    }

    /// Binary node `n`'s subtree collapsed to at most `width` child slots.
    fn collapse(&self, n: u32, width: usize) -> Vec<GpuChild> {
        let mut slots: Vec<GpuChild> = self.children(n).collect();
        loop {
            let widest = slots
                .iter()
                .enumerate()
                .filter(|(_, c)| !c.is_leaf())
                .max_by(|(_, a), (_, b)| a.bounds().half_area().total_cmp(&b.bounds().half_area()))
                .map(|(i, _)| i);
            let Some(i) = widest else { return slots };
            let grand: Vec<GpuChild> = self.children(slots[i].index).collect();
            if slots.len() - 1 + grand.len() > width {
                return slots;
            }
            slots.splice(i..=i, grand);
        }
    }

    /// Entries a visit pushes at worst with these slots (all hit: one is visited next).
    fn pushes(&self, slots: &[GpuChild]) -> usize {
        slots.iter().filter(|c| self.leaves_pushed || !c.is_leaf()).count().saturating_sub(1)
    }

    /// Writes the wide node standing for binary child `inner` (an inner child) with stack
    /// `budget`; returns its index.
    fn node(&mut self, inner: GpuChild, budget: usize) -> u32 {
        let mut slots = Vec::new();
        for width in [BVH_WIDTH, 4, 2] {
            slots = self.collapse(inner.index, width);
            let pushes = self.pushes(&slots);
            if pushes <= budget && slots.iter().all(|c| self.need(c) <= budget - pushes) {
                break;
            }
        }
        let left = budget.saturating_sub(self.pushes(&slots));
        let at = self.out.len();
        self.out.push(GpuWideNode::zeroed());
        let mut refs = [BVH_EMPTY; BVH_WIDTH];
        for (slot, c) in slots.iter().enumerate() {
            refs[slot] = if c.is_leaf() {
                let mut word = BVH_LEAF;
                BVH_WIDE_COUNT.set(&mut word, (c.meta & !BVH_LEAF) - 1);
                BVH_WIDE_INDEX.set(&mut word, c.index);
                word
            } else {
                self.node(*c, left)
            };
        }
        self.out[at] = encode(&slots.iter().map(GpuChild::bounds).collect::<Vec<_>>(), refs);
        at as u32
    }
}

/// The wide node of child boxes `boxes` (slots in order) and references `refs`.
fn encode(boxes: &[Aabb], refs: [u32; BVH_WIDTH]) -> GpuWideNode {
    let bounds = boxes.iter().fold(Aabb::EMPTY, |b, c| b.union(c));
    let mut node = GpuWideNode { children: refs, ..GpuWideNode::zeroed() };
    // Empty slots: x bounds lo 255 > hi 0, which the traversal reads as "no child".
    for slot in boxes.len()..BVH_WIDTH {
        node.lo[slot / 4] |= 0xff << (8 * (slot % 4));
    }
    if bounds.is_empty() {
        return node;
    }
    node.origin = bounds.min.into();
    for axis in 0..3 {
        let extent = bounds.max[axis] - bounds.min[axis];
        let axis_bounds: Vec<(f32, f32)> = boxes.iter().map(|b| (b.min[axis], b.max[axis])).collect();
        let (biased, q) = quantise_axis(bounds.min[axis], extent, &axis_bounds);
        node.exponents |= biased << (8 * axis);
        for (slot, (lo, hi)) in q.into_iter().enumerate() {
            node.lo[2 * axis + slot / 4] |= lo << (8 * (slot % 4));
            node.hi[2 * axis + slot / 4] |= hi << (8 * (slot % 4));
        }
    }
    node
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::render::trace::bvh::{Blas, Tlas};

    /// A deterministic xorshift generator's next value in [0, 1).
    fn next(state: &mut u64) -> f32 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        (*state >> 40) as f32 / (1u64 << 24) as f32
    }

    /// `n` random triangles of about `size` in a box of `extent`, shifted by `at`.
    fn soup(n: usize, size: f32, extent: f32, at: Vec3) -> Vec<[Vec3; 3]> {
        let mut s = 0x1234_5678_9abc_def1u64;
        let mut v = |scale: f32| Vec3::new(next(&mut s), next(&mut s), next(&mut s)) * scale;
        (0..n)
            .map(|_| {
                let c = at + v(extent);
                [c + v(size), c + v(size), c + v(size)]
            })
            .collect()
    }

    /// Walks the wide tree `wide` from `node`: checks that each child's decoded box holds the
    /// binary box it stands for (of a leaf: `leaf_box(first primitive)`; of an inner child: the
    /// union of its leaves') and that children come after parents; collects the leaves'
    /// primitive ranges; returns the box of the node's leaves and the most stack entries the
    /// traversal leaves below it along any path (`leaves_pushed` as in [`widen`]).
    fn walk(wide: &[GpuWideNode], node: usize, leaves_pushed: bool, leaf_box: &dyn Fn(u32) -> Aabb, ranges: &mut Vec<(u32, u32)>) -> (Aabb, usize) {
        let n = &wide[node];
        let (mut bounds, mut deepest, mut pushable) = (Aabb::EMPTY, 0, 0);
        for slot in 0..BVH_WIDTH {
            let Some(decoded) = n.child_bounds(slot) else {
                assert!(n.lo[slot / 4] >> (8 * (slot % 4)) & 0xff > n.hi[slot / 4] >> (8 * (slot % 4)) & 0xff, "an empty slot reads as empty");
                continue;
            };
            let child = n.children[slot];
            let exact = if child & BVH_LEAF != 0 {
                let (first, count) = (BVH_WIDE_INDEX.get(child), BVH_WIDE_COUNT.get(child) + 1);
                ranges.push((first, count));
                pushable += usize::from(leaves_pushed);
                leaf_box(first)
            } else {
                assert!(child as usize > node, "children after parents");
                pushable += 1;
                let (b, need) = walk(wide, child as usize, leaves_pushed, leaf_box, ranges);
                deepest = deepest.max(need);
                b
            };
            assert!(decoded.min.cmple(exact.min).all() && decoded.max.cmpge(exact.max).all(), "node {node} slot {slot}: {decoded:?} does not hold {exact:?}");
            bounds = bounds.union(&exact);
        }
        (bounds, deepest + pushable.saturating_sub(1))
    }

    #[test]
    fn wide_boxes_hold_every_leaf_once_and_the_stack_stays_in_budget() {
        for (name, triangles) in [
            ("soup", soup(20_000, 0.02, 1.0, Vec3::ZERO)),
            ("far, flat", soup(3000, 1.0, 1.0e4, Vec3::new(1.0e6, -3.0e5, 7.0)).into_iter().map(|t| t.map(|v| Vec3::new(v.x, v.y, 2.5))).collect()),
            ("one", vec![[Vec3::ZERO, Vec3::X, Vec3::Y]]),
            ("none", Vec::new()),
        ] {
            let blas = Blas::build(&triangles);
            let leaves: Vec<GpuChild> = blas.nodes.iter().flat_map(|n| n.children).filter(|c| c.is_leaf() && c.meta != BVH_LEAF).collect();
            let leaf_box = |first: u32| leaves.iter().find(|c| c.index == first).expect("a binary leaf").bounds();
            let mut ranges = Vec::new();
            let (_, need) = walk(&blas.wide, 0, false, &leaf_box, &mut ranges);
            ranges.sort_unstable();
            let mut next_first = 0;
            for (first, count) in &ranges {
                assert_eq!(*first, next_first, "{name}: the leaves cover the triangles once");
                next_first += count;
            }
            assert_eq!(next_first as usize, triangles.len(), "{name}");
            assert!(need <= BVH_WIDE_BUDGET, "{name}: {need}");
            if triangles.len() > 1000 {
                let filled = blas.wide.iter().map(|n| n.children.iter().filter(|&&c| c != BVH_EMPTY).count()).sum::<usize>();
                let per_node = filled as f32 / blas.wide.len() as f32;
                // Top-down collapse leaves subtrees of few leaves in small nodes: 3.7 children
                // per node on the soup (2,353 wide nodes for 6,366 binary).
                assert!(per_node > 3.5 && blas.wide.len() * 5 < blas.nodes.len() * 2, "{name}: {per_node} children per node, {} wide nodes for {} binary", blas.wide.len(), blas.nodes.len());
            }
        }
    }

    #[test]
    fn a_deep_top_level_keeps_its_pushes_in_budget() {
        // Boxes of sizes growing geometrically along a line: a PLOC tree of them is deep (a
        // caterpillar), and every leaf of a TLAS is pushed.
        let boxes: Vec<Aabb> = (0..3000)
            .map(|i| {
                let x = 1.05f32.powi(i % 400) + i as f32 * 1e-3;
                Aabb { min: Vec3::new(x, 0.0, (i / 400) as f32), max: Vec3::new(x * 1.01, 1.0, (i / 400) as f32 + 0.5) }
            })
            .collect();
        let tlas = Tlas::build(&boxes);
        let mut ranges = Vec::new();
        let (_, need) = walk(&tlas.wide, 0, true, &|i| boxes[i as usize], &mut ranges);
        let mut instances: Vec<u32> = ranges.iter().map(|&(first, count)| {
            assert_eq!(count, 1);
            first
        }).collect();
        instances.sort_unstable();
        assert_eq!(instances, (0..3000).collect::<Vec<u32>>());
        assert!(need <= BVH_WIDE_BUDGET, "{need}");
    }

    #[test]
    fn nodes_narrow_where_the_budget_runs_out() {
        // A complete binary tree of height 6 (64 leaves of one primitive, node i's children
        // 2i + 1 and 2i + 2), every leaf pushed, with a budget of 6: eight children would push
        // 7, four 3 with children needing 4 > 3: the root keeps two.
        let height = 6;
        let inner = (1usize << height) - 1;
        let slot = |i: usize| {
            if i < inner {
                GpuChild { min: [0.0; 3], index: i as u32, max: [64.0, 1.0, 1.0], meta: 0 }
            } else {
                let p = (i - inner) as f32;
                GpuChild { min: [p, 0.0, 0.0], index: (i - inner) as u32, max: [p + 1.0, 1.0, 1.0], meta: BVH_LEAF | 1 }
            }
        };
        let nodes: Vec<GpuNode> = (0..inner).map(|i| GpuNode { children: [slot(2 * i + 1), slot(2 * i + 2)] }).collect();
        let mut w = Widener { nodes: &nodes, needs: least_needs(&nodes, true), leaves_pushed: true, out: Vec::new() };
        assert_eq!(w.needs[0], height, "two children pushed at every level");
        w.node(GpuChild { min: [0.0; 3], index: 0, max: [0.0; 3], meta: 0 }, height);
        let mut ranges = Vec::new();
        let prim = |i: u32| Aabb { min: Vec3::new(i as f32, 0.0, 0.0), max: Vec3::new(i as f32 + 1.0, 1.0, 1.0) };
        let (_, need) = walk(&w.out, 0, true, &prim, &mut ranges);
        assert_eq!(ranges.len(), 64);
        assert!(need <= height, "{need}");
        let width = |n: &GpuWideNode| n.children.iter().filter(|&&c| c != BVH_EMPTY).count();
        assert_eq!(width(&w.out[0]), 2);

        // With the full budget the root takes eight.
        let wide = widen(&nodes, true);
        assert_eq!(width(&wide[0]), BVH_WIDTH);
    }
}
