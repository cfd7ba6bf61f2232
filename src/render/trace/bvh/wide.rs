//! Compressed wide BVHs: a built binary BVH ([`GpuNode`]s) collapsed into 80-byte nodes of up
//! to [`BVH_WIDTH`] children with byte-quantised boxes ([`GpuWideNode`]; after Ylitie, Karras
//! and Laine 2017, "Efficient Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs",
//! CWBVH), traversed by `shaders/trace/bvh_wide.glsl`. The leaves are the binary tree's; their
//! primitives are renumbered so that the leaves of one wide node are consecutive
//! ([`Widened::leaves`]: the builder reorders the triangles and the binary leaves to match), so
//! both layouts trace the same triangle buffer and find the same closest hits: a wide child's
//! box holds the binary child's box it stands for (quantised outwards, checked in `f32` as
//! decoded), so no ray that enters a binary box misses its wide box.
//!
//! Collapse: a wide node starts as the binary node's two children and repeatedly replaces its
//! inner child of largest surface area by that child's two children, while it has at most
//! [`BVH_WIDTH`] children whose leaves hold at most [`BVH_WIDE_LEAVES`] primitives (one bit
//! each in the traversal's hit mask).
//!
//! Slots by octant: child slot `s` is given to the child nearest along the direction whose
//! component `a` is negative where bit `2 - a` of `s` is set (greedy assignment by the
//! projection of the children's centres, as the paper suggests), so a ray whose direction has
//! the signs `s` visits slot `s` first and the others by `slot ^ s` ascending, without sorting.
//! The inner children are consecutive nodes from `child_base` in slot order (a child's node is
//! `child_base` plus the inner slots before it), the leaves' primitives consecutive from
//! `leaf_base` in slot order.
//!
//! Quantisation per axis: the node's lowest corner `origin` and a power of two `2^e` with
//! `255 * 2^e` at least the node's extent; a child's box is `origin + q * 2^e` for bytes
//! `q_lo <= q_hi` (the product is exact, so a fused multiply-add decodes the same).

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use super::{Aabb, GpuChild, GpuNode};
use crate::render::trace::shader_constants::{BVH_LEAF, BVH_WIDE_COUNT, BVH_WIDE_EMPTY, BVH_WIDE_IMASK, BVH_WIDE_LEAVES, BVH_WIDE_OFFSET, BVH_WIDTH};

/// A compressed wide BVH node, 80 bytes (`BvhWideNode` in `bvh_wide.glsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuWideNode {
    /// Lowest corner of the node's box: the quantisation origin.
    pub origin: [f32; 3],
    /// Byte `axis` (0 to 2): the biased `f32` exponent `e + 127` of the axis' scale `2^e`;
    /// [`BVH_WIDE_IMASK`]: bit `slot` set where the slot holds an inner child.
    pub frame: u32,
    /// The node of the first inner child (relative to the BVH's root); the others follow in
    /// slot order.
    pub child_base: u32,
    /// The first primitive of the leaves; the leaves' primitives follow in slot order (BLAS:
    /// triangles relative to the geometry's first; TLAS: the word of the TLAS buffer holding
    /// the first leaf's instance, see [`super::Tlas::wide`]).
    pub leaf_base: u32,
    /// Byte `slot` of the eight: a leaf's [`BVH_WIDE_OFFSET`] (first primitive relative to
    /// `leaf_base`) and [`BVH_WIDE_COUNT`] (primitives less one); [`BVH_WIDE_EMPTY`] for an
    /// empty slot; 0 for an inner child.
    pub meta: [u32; 2],
    /// Quantised bounds, eight bytes (one a slot) each of: lowest x, y, z, highest x, y, z.
    /// Bound `k` of slot `s` is byte `s % 4` of word `2 * k + s / 4` (words numbered through
    /// the three groups of four).
    pub bounds: [[u32; 4]; 3],
}

include!(concat!(env!("OUT_DIR"), "/layouts/trace_bvh_wide.rs"));

/// The size the GPU reads, as in the paper.
const _: () = assert!(size_of::<GpuWideNode>() == 80);

impl GpuWideNode {
    /// Byte `slot` of bound `k` (0 to 5: lowest x, y, z, highest x, y, z).
    fn bound_byte(&self, k: usize, slot: usize) -> u32 {
        let word = 2 * k + slot / 4;
        (self.bounds[word / 4][word % 4] >> (8 * (slot % 4))) & 0xff
    }

    /// Sets byte `slot` of bound `k` to `q`.
    fn set_bound_byte(&mut self, k: usize, slot: usize, q: u32) {
        let word = 2 * k + slot / 4;
        let w = &mut self.bounds[word / 4][word % 4];
        *w = (*w & !(0xff << (8 * (slot % 4)))) | (q << (8 * (slot % 4)));
    }

    /// The meta byte of `slot`.
    pub fn meta(&self, slot: usize) -> u32 {
        (self.meta[slot / 4] >> (8 * (slot % 4))) & 0xff
    }

    /// Whether `slot` holds an inner child.
    pub fn is_inner(&self, slot: usize) -> bool {
        BVH_WIDE_IMASK.get(self.frame) & (1 << slot) != 0
    }

    /// What `slot` holds.
    pub fn child(&self, slot: usize) -> WideChild {
        if self.is_inner(slot) {
            let before = BVH_WIDE_IMASK.get(self.frame) & ((1 << slot) - 1);
            return WideChild::Inner(self.child_base + before.count_ones());
        }
        let meta = self.meta(slot);
        if meta == BVH_WIDE_EMPTY {
            return WideChild::Empty;
        }
        WideChild::Leaf { first: self.leaf_base + BVH_WIDE_OFFSET.get(meta), count: BVH_WIDE_COUNT.get(meta) + 1 }
    }

    /// The box of child `slot` as the GPU decodes it (`None` for an empty slot).
    pub fn child_bounds(&self, slot: usize) -> Option<Aabb> {
        if self.child(slot) == WideChild::Empty {
            return None;
        }
        let corner = |side: usize| Vec3::from_array(std::array::from_fn(|axis| decode(self.origin[axis], self.scale(axis), self.bound_byte(3 * side + axis, slot))));
        Some(Aabb { min: corner(0), max: corner(1) })
    }

    /// The scale of `axis`: `2^e`.
    fn scale(&self, axis: usize) -> f32 {
        f32::from_bits(((self.frame >> (8 * axis)) & 0xff) << 23)
    }
}

/// What a slot of a [`GpuWideNode`] holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WideChild {
    /// Nothing.
    Empty,
    /// An inner child: its node (relative to the BVH's root).
    Inner(u32),
    /// A leaf of `count` primitives from `first` (the node's `leaf_base` added).
    Leaf { first: u32, count: u32 },
}

/// `origin + q * scale` in `f32`, as a bound decodes.
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

/// Sets the quantisation frame and bounds of `node` for the child boxes `boxes` (by slot,
/// `None` for empty slots); keeps its references.
fn quantise(node: &mut GpuWideNode, boxes: &[Option<Aabb>; BVH_WIDTH]) {
    let bounds = boxes.iter().flatten().fold(Aabb::EMPTY, |b, c| b.union(c));
    let imask = BVH_WIDE_IMASK.get(node.frame);
    node.frame = 0;
    BVH_WIDE_IMASK.set(&mut node.frame, imask);
    node.bounds = [[0; 4]; 3];
    if bounds.is_empty() {
        node.origin = [0.0; 3];
        return;
    }
    node.origin = bounds.min.into();
    let filled: Vec<(usize, Aabb)> = boxes.iter().enumerate().filter_map(|(slot, b)| b.map(|b| (slot, b))).collect();
    for axis in 0..3 {
        let extent = bounds.max[axis] - bounds.min[axis];
        let axis_bounds: Vec<(f32, f32)> = filled.iter().map(|(_, b)| (b.min[axis], b.max[axis])).collect();
        let (biased, q) = quantise_axis(bounds.min[axis], extent, &axis_bounds);
        node.frame |= biased << (8 * axis);
        for (&(slot, _), (lo, hi)) in filled.iter().zip(q) {
            node.set_bound_byte(axis, slot, lo);
            node.set_bound_byte(3 + axis, slot, hi);
        }
    }
}

/// A binary BVH collapsed into wide nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct Widened {
    /// The wide nodes, root first, children after parents.
    pub nodes: Vec<GpuWideNode>,
    /// Per wide node and slot, the binary child it stands for (`2 * node + child`), or
    /// `u32::MAX` for an empty slot: [`refit`] updates the boxes from them.
    pub sources: Vec<[u32; BVH_WIDTH]>,
    /// The binary leaves as `(first, count)` in the order the wide nodes number their
    /// primitives: leaf `k`'s primitives are numbered from the sum of the counts before it.
    pub leaves: Vec<(u32, u32)>,
}

/// No binary child: an empty slot's source.
const NO_SOURCE: u32 = u32::MAX;

/// Collapses the binary BVH `nodes` (root first, children after parents) into wide nodes.
pub fn widen(nodes: &[GpuNode]) -> Widened {
    let mut w = Widened { nodes: vec![GpuWideNode::zeroed()], sources: vec![[NO_SOURCE; BVH_WIDTH]], leaves: Vec::new() };
    let mut primitives = 0;
    w.node(nodes, 0, 0, &mut primitives);
    w
}

/// The updated boxes of `wide` after its binary tree `nodes` was refitted (same topology).
pub fn refit(nodes: &[GpuNode], wide: &mut Widened) {
    for (node, sources) in wide.nodes.iter_mut().zip(&wide.sources) {
        quantise(node, &sources.map(|s| (s != NO_SOURCE).then(|| binary_child(nodes, s).bounds())));
    }
}

/// The binary child `2 * node + child`.
fn binary_child(nodes: &[GpuNode], source: u32) -> GpuChild {
    nodes[(source / 2) as usize].children[(source % 2) as usize]
}

/// Primitives under a slot that is a leaf (0 for an inner child).
fn leaf_primitives(c: &GpuChild) -> u32 {
    if c.is_leaf() { c.meta & !BVH_LEAF } else { 0 }
}

impl Widened {
    /// Binary node `n`'s subtree collapsed into at most [`BVH_WIDTH`] children whose leaves
    /// hold at most [`BVH_WIDE_LEAVES`] primitives, each with its source.
    fn collapse(nodes: &[GpuNode], n: u32) -> Vec<(GpuChild, u32)> {
        let children = |n: u32| (0..2).map(move |c| (nodes[n as usize].children[c as usize], 2 * n + c)).filter(|(c, _)| c.meta != BVH_LEAF);
        let mut slots: Vec<(GpuChild, u32)> = children(n).collect();
        let mut leaves: u32 = slots.iter().map(|(c, _)| leaf_primitives(c)).sum();
        // Inner children that were tried and could not be opened.
        let mut kept = Vec::new();
        loop {
            let widest = slots
                .iter()
                .enumerate()
                .filter(|(_, (c, s))| !c.is_leaf() && !kept.contains(s))
                .max_by(|(_, (a, _)), (_, (b, _))| a.bounds().half_area().total_cmp(&b.bounds().half_area()))
                .map(|(i, _)| i);
            let Some(i) = widest else { return slots };
            let grand: Vec<(GpuChild, u32)> = children(slots[i].0.index).collect();
            if slots.len() - 1 + grand.len() > BVH_WIDTH {
                return slots;
            }
            let more: u32 = grand.iter().map(|(c, _)| leaf_primitives(c)).sum();
            if leaves + more > BVH_WIDE_LEAVES {
                kept.push(slots[i].1);
                continue;
            }
            leaves += more;
            slots.splice(i..=i, grand);
        }
    }

    /// Writes wide node `at` (allocated) standing for binary node `n`, then its subtree;
    /// `primitives` counts the primitives numbered so far.
    fn node(&mut self, nodes: &[GpuNode], n: u32, at: usize, primitives: &mut u32) {
        let slots = Self::collapse(nodes, n);
        let by_slot = octant_slots(&slots.iter().map(|(c, _)| c.bounds()).collect::<Vec<_>>());
        let child_base = self.nodes.len();
        let mut node = GpuWideNode { child_base: child_base as u32, leaf_base: *primitives, ..GpuWideNode::zeroed() };
        let mut imask = 0;
        let mut inner = Vec::new();
        let mut boxes = [None; BVH_WIDTH];
        for (slot, taken) in by_slot.iter().enumerate() {
            let byte = match taken {
                None => BVH_WIDE_EMPTY,
                Some(k) => {
                    let (c, source) = slots[*k];
                    self.sources[at][slot] = source;
                    boxes[slot] = Some(c.bounds());
                    if c.is_leaf() {
                        let count = c.meta & !BVH_LEAF;
                        let mut byte = 0;
                        BVH_WIDE_OFFSET.set(&mut byte, *primitives - node.leaf_base);
                        BVH_WIDE_COUNT.set(&mut byte, count - 1);
                        self.leaves.push((c.index, count));
                        *primitives += count;
                        byte
                    } else {
                        imask |= 1 << slot;
                        inner.push(c.index);
                        0
                    }
                }
            };
            node.meta[slot / 4] |= byte << (8 * (slot % 4));
        }
        BVH_WIDE_IMASK.set(&mut node.frame, imask);
        quantise(&mut node, &boxes);
        self.nodes[at] = node;
        self.nodes.resize(child_base + inner.len(), GpuWideNode::zeroed());
        self.sources.resize(child_base + inner.len(), [NO_SOURCE; BVH_WIDTH]);
        for (k, child) in inner.into_iter().enumerate() {
            self.node(nodes, child, child_base + k, primitives);
        }
    }
}

/// The slot of each of `boxes` (at most [`BVH_WIDTH`]): `result[slot]` is the box in that slot.
/// Greedy: of all (box, free slot) pairs, the box whose centre lies farthest against the slot's
/// direction (the one a ray of that octant meets first) takes it, until every box has one.
fn octant_slots(boxes: &[Aabb]) -> [Option<usize>; BVH_WIDTH] {
    let centre = boxes.iter().fold(Aabb::EMPTY, |b, c| b.union(c));
    let centre = (centre.min + centre.max) * 0.5;
    let direction = |slot: usize| Vec3::new(if slot & 4 != 0 { -1.0 } else { 1.0 }, if slot & 2 != 0 { -1.0 } else { 1.0 }, if slot & 1 != 0 { -1.0 } else { 1.0 });
    let mut by_slot = [None; BVH_WIDTH];
    let mut placed = vec![false; boxes.len()];
    for _ in 0..boxes.len() {
        let mut best: Option<(f32, usize, usize)> = None;
        for (k, b) in boxes.iter().enumerate().filter(|&(k, _)| !placed[k]) {
            let offset = (b.min + b.max) * 0.5 - centre;
            for slot in (0..BVH_WIDTH).filter(|&s| by_slot[s].is_none()) {
                let cost = direction(slot).dot(offset);
                if best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, k, slot));
                }
            }
        }
        let (_, k, slot) = best.expect("a free slot per box");
        by_slot[slot] = Some(k);
        placed[k] = true;
    }
    by_slot
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::render::trace::bvh::{Blas, Layout, Tlas};
    use crate::render::trace::shader_constants::BVH_MAX_DEPTH;

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

    /// Walks the wide tree `wide` from `node` at depth `depth` (the root 1): checks that each
    /// child's decoded box holds the exact box of what it stands for (of a leaf:
    /// `leaf_box(first, count)`; of an inner child: the union of its leaves'), that inner
    /// children come after their parent and leaves are consecutive from `leaf_base` and fit
    /// the hit mask; collects the leaves' ranges; returns the box of the node's leaves and the
    /// deepest depth below.
    fn walk(wide: &[GpuWideNode], node: usize, depth: usize, leaf_box: &dyn Fn(u32, u32) -> Aabb, ranges: &mut Vec<(u32, u32)>) -> (Aabb, usize) {
        let n = &wide[node];
        let (mut bounds, mut deepest, mut next_leaf) = (Aabb::EMPTY, depth, n.leaf_base);
        for slot in 0..BVH_WIDTH {
            let Some(decoded) = n.child_bounds(slot) else { continue };
            let exact = match n.child(slot) {
                WideChild::Leaf { first, count } => {
                    assert_eq!(first, next_leaf, "node {node}: leaves consecutive in slot order");
                    next_leaf += count;
                    assert!(next_leaf - n.leaf_base <= BVH_WIDE_LEAVES);
                    ranges.push((first, count));
                    leaf_box(first, count)
                }
                WideChild::Inner(child) => {
                    assert!(child as usize > node, "children after parents");
                    let (b, d) = walk(wide, child as usize, depth + 1, leaf_box, ranges);
                    deepest = deepest.max(d);
                    b
                }
                WideChild::Empty => unreachable!(),
            };
            assert!(decoded.min.cmple(exact.min).all() && decoded.max.cmpge(exact.max).all(), "node {node} slot {slot}: {decoded:?} does not hold {exact:?}");
            bounds = bounds.union(&exact);
        }
        (bounds, deepest)
    }

    /// The wide tree of `blas`, built for [`Layout::Wide`].
    fn wide_of(blas: &Blas) -> &Widened {
        blas.wide.as_ref().expect("a BLAS built for the wide layout")
    }

    /// Checks `blas`'s wide tree against its binary tree: each wide leaf is a binary leaf
    /// (same triangles) whose box it holds, the leaves cover every triangle once; returns the
    /// wide tree's depth.
    fn check_blas(name: &str, blas: &Blas, count: usize) -> usize {
        let binary: std::collections::HashMap<(u32, u32), Aabb> =
            blas.nodes.iter().flat_map(|n| n.children).filter(|c| c.is_leaf() && c.meta != BVH_LEAF).map(|c| ((c.index, c.meta & !BVH_LEAF), c.bounds())).collect();
        let leaf_box = |first: u32, count: u32| *binary.get(&(first, count)).expect("a binary leaf of the same triangles");
        let mut ranges = Vec::new();
        let (_, depth) = walk(&wide_of(blas).nodes, 0, 1, &leaf_box, &mut ranges);
        ranges.sort_unstable();
        let mut next_first = 0;
        for (first, count) in &ranges {
            assert_eq!(*first, next_first, "{name}: the leaves cover the triangles once");
            next_first += count;
        }
        assert_eq!(next_first as usize, count, "{name}");
        depth
    }

    #[test]
    fn wide_boxes_hold_every_leaf_once() {
        for (name, triangles) in [
            ("soup", soup(20_000, 0.02, 1.0, Vec3::ZERO)),
            ("far, flat", soup(3000, 1.0, 1.0e4, Vec3::new(1.0e6, -3.0e5, 7.0)).into_iter().map(|t| t.map(|v| Vec3::new(v.x, v.y, 2.5))).collect()),
            ("tiny, far", soup(2000, 1e-4, 1e-2, Vec3::new(-3.0e3, 1.0e5, 0.1))),
            ("one", vec![[Vec3::ZERO, Vec3::X, Vec3::Y]]),
            ("none", Vec::new()),
        ] {
            let blas = Blas::build(&triangles, Layout::Wide);
            let wide = wide_of(&blas);
            let depth = check_blas(name, &blas, triangles.len());
            assert!(depth <= BVH_MAX_DEPTH, "{name}: {depth}");
            if triangles.len() > 1000 {
                let filled = wide.nodes.iter().map(|n| (0..BVH_WIDTH).filter(|&s| n.child(s) != WideChild::Empty).count()).sum::<usize>();
                let per_node = filled as f32 / wide.nodes.len() as f32;
                assert!(per_node > 3.5 && wide.nodes.len() * 5 < blas.nodes.len() * 2, "{name}: {per_node} children per node, {} wide nodes for {} binary", wide.nodes.len(), blas.nodes.len());
            }
        }
    }

    #[test]
    fn quantised_bounds_round_outwards() {
        // Bounds just above and below representable steps, far from the origin: each decoded
        // box holds its exact box, and a box on the grid is kept exactly.
        for &(origin, extent) in &[(0.0f32, 1.0f32), (1.0e6, 3.0), (-7.5e4, 1.0e-2), (123.456, 1.0e5)] {
            let mut state = 0x9e37_79b9_7f4a_7c15u64;
            let boxes: Vec<(f32, f32)> = (0..64)
                .map(|_| {
                    let a = origin + next(&mut state) * extent;
                    let b = origin + next(&mut state) * extent;
                    (a.min(b), a.max(b))
                })
                .chain([(origin, origin + extent), (origin, origin), (origin + extent, origin + extent)])
                .collect();
            let (biased, q) = quantise_axis(origin, extent, &boxes);
            let scale = f32::from_bits(biased << 23);
            assert!(255.0 * scale >= extent, "{origin} {extent}: scale {scale}");
            let mut slack = 0.0;
            for (&(lo, hi), &(qlo, qhi)) in boxes.iter().zip(&q) {
                assert!(qlo <= qhi && qhi <= 255);
                let (dlo, dhi) = (decode(origin, scale, qlo), decode(origin, scale, qhi));
                assert!(dlo <= lo && dhi >= hi, "{origin} {extent}: [{lo}, {hi}] as [{qlo}, {qhi}] = [{dlo}, {dhi}]");
                slack += (lo - dlo) + (dhi - hi);
            }
            // About one step of rounding per box, not a blown-up grid.
            assert!(slack / boxes.len() as f32 <= 2.0 * scale, "{origin} {extent}: {slack}");
        }
        // A bound on the grid decodes to itself.
        let (biased, q) = quantise_axis(0.0, 255.0, &[(3.0, 17.0)]);
        assert_eq!((biased, q), (127, vec![(3, 17)]));
    }

    #[test]
    fn slots_follow_the_octants() {
        // Eight unit boxes at the corners of a cube: slot s holds the box nearest the corner a
        // ray with the signs of s (bit 2: x negative, 1: y, 0: z) enters first, the lowest
        // corner on the axes where the direction is positive.
        let corner = |k: usize| Vec3::new((k & 4) as f32, (k & 2) as f32, (k & 1) as f32 * 2.0);
        let boxes: Vec<Aabb> = (0..8).rev().map(|k| Aabb { min: corner(k), max: corner(k) + 1.0 }).collect();
        let by_slot = octant_slots(&boxes);
        for slot in 0..8 {
            let b = boxes[by_slot[slot].expect("every slot filled")];
            assert_eq!(b.min, corner(slot), "slot {slot}");
        }
        // Fewer boxes than slots: each gets its own.
        let two = octant_slots(&boxes[..2]);
        assert_eq!(two.iter().flatten().count(), 2);
    }

    #[test]
    fn a_refit_keeps_the_tree_and_holds_the_moved_boxes() {
        let triangles = soup(5000, 0.05, 1.0, Vec3::ZERO);
        let mut blas = Blas::build(&triangles, Layout::Wide);
        let moved: Vec<[Vec3; 3]> = triangles.iter().map(|t| t.map(|v| v * Vec3::new(2.0, 0.5, 1.0) + Vec3::new(v.y * v.y, 0.0, -3.0))).collect();
        let before = blas.clone();
        assert!(blas.refit(&moved));
        assert_eq!(blas.order, before.order);
        assert_eq!(wide_of(&blas).sources, wide_of(&before).sources);
        for (a, b) in wide_of(&blas).nodes.iter().zip(&wide_of(&before).nodes) {
            assert_eq!((a.child_base, a.leaf_base, a.meta, BVH_WIDE_IMASK.get(a.frame)), (b.child_base, b.leaf_base, b.meta, BVH_WIDE_IMASK.get(b.frame)));
        }
        check_blas("refitted", &blas, triangles.len());
        // The same boxes as a fresh collapse of the refitted binary tree would quantise.
        assert_eq!(wide_of(&blas).nodes[0].origin, <[f32; 3]>::from(blas.bounds.min));
    }

    #[test]
    fn the_top_level_lists_every_instance_once() {
        let boxes: Vec<Aabb> = (0..3000)
            .map(|i| {
                let x = 1.05f32.powi(i % 400) + i as f32 * 1e-3;
                Aabb { min: Vec3::new(x, 0.0, (i / 400) as f32), max: Vec3::new(x * 1.01, 1.0, (i / 400) as f32 + 0.5) }
            })
            .chain([Aabb::EMPTY])
            .collect();
        let tlas = Tlas::build(&boxes, Layout::Wide);
        let nodes = tlas.wide_nodes();
        let instance = |word: u32| tlas.wide.as_ref().expect("a wide TLAS")[word as usize];
        let mut ranges = Vec::new();
        let (_, depth) = walk(nodes, 0, 1, &|first, count| {
            assert_eq!(count, 1);
            boxes[instance(first) as usize]
        }, &mut ranges);
        assert!(depth <= BVH_MAX_DEPTH);
        let mut instances: Vec<u32> = ranges.iter().map(|&(first, _)| instance(first)).collect();
        instances.sort_unstable();
        assert_eq!(instances, (0..3000).collect::<Vec<u32>>(), "the empty instance is left out");
    }
}
