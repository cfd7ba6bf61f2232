//! Multi-pass materials: a draw that is a later pass over triangles of an earlier traced draw
//! of the frame, its base, becomes one of the base's layers
//! ([`crate::frame::class::DrawClass::Layer`] with a [`crate::frame::class::Layer`]), traced
//! as part of the base's surface and never on its own.
//! Quake 3 draws the stages of a shader one after the other over the same locked arrays and
//! indices (a detail, a lightmap, a glow pass), and a dynamic light as one more pass over the
//! subset of the batch's triangles it reaches, with its own indices.
//!
//! - **Candidates** ([`blending`]): triangles with depth test `GL_EQUAL` or `GL_LEQUAL`, depth
//!   writes off (or `GL_EQUAL`), and a blend function of [`Blending`]; or no blending (a
//!   replace) with `GL_EQUAL`. Other blend functions stay as routed.
//! - **Bases**: the traced draws before it in the frame with the same modelview and projection
//!   (bit for bit), most recent first.
//! - **Triangles**: every triangle of the pass must be a triangle of one base: the same
//!   object-space corners (positions bit for bit) in the same order. The same positions and
//!   indices (the same arrays drawn again) give the base's triangles one for one, without
//!   hashing. Otherwise a base whose bounds hold the pass's first corner, and whose vertices
//!   hold it, is indexed (once per frame: a map from the hash of a triangle's corners to the
//!   triangle) and each triangle of the pass looked up there, its corners compared. A pass
//!   whose triangles are not all found in one base stays as routed.
//! - **At most [`MAX_LAYERS`]** per base: a pass over a base that has them all stays as routed.
//!
//! Cost: nothing for a frame without candidates; per candidate, a comparison of matrices per
//! earlier traced draw, then either two slice comparisons (stages of one batch) or a bounds test
//! and a scan of the base's positions before any hashing; each base is indexed at most once a
//! frame. The map and the lists are kept between frames and only cleared (the triangles of each
//! layer are its own `Arc`).

use std::sync::Arc;

use glam::Vec3;

use super::keys::bytes_of;
use super::static_world::Map;
use crate::frame::class::{LayerRole, MAX_LAYERS};
use crate::frame::state::{BlendEquation, BlendFactor, CompareFunc};
use crate::frame::{Draw, Topology};

/// What a candidate pass's blending does to the colour under it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Blending {
    /// No blending, or `GL_ONE, GL_ZERO`, with `GL_EQUAL`: the pass replaces the colour.
    Replace,
    /// `GL_DST_COLOR, GL_ZERO` or `GL_ZERO, GL_SRC_COLOR`: multiplies (a lightmap, or a
    /// texture over a lightmap; `super::lighting` tells which).
    Multiply,
    /// `GL_DST_COLOR, GL_SRC_COLOR` (or `GL_SRC_COLOR, GL_DST_COLOR`): 2 × source × colour, a
    /// detail texture.
    Modulate2x,
    /// `GL_ONE, GL_ONE` or `GL_SRC_ALPHA, GL_ONE`: adds.
    Add,
    /// `GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA` (or premultiplied `GL_ONE,
    /// GL_ONE_MINUS_SRC_ALPHA`): over the colour by its alpha.
    Over,
}

impl Blending {
    /// The layer role of a pass that blends so; a multiplying pass is [`LayerRole::Albedo`]
    /// here, [`LayerRole::BakedLight`] when its texture is a lightmap (`super::lighting`).
    pub fn role(self) -> LayerRole {
        match self {
            Blending::Replace | Blending::Over => LayerRole::Decal,
            Blending::Multiply | Blending::Modulate2x => LayerRole::Albedo,
            Blending::Add => LayerRole::Emission,
        }
    }
}

/// How `draw` blends when it is a candidate pass (see the module doc), `None` when it is not.
pub fn blending(draw: &Draw) -> Option<Blending> {
    use BlendFactor::{DstColor, One, OneMinusSrcAlpha, SrcAlpha, SrcColor, Zero};
    let s = &draw.state;
    let equal = s.depth_test == Some(CompareFunc::Equal);
    let later = equal || (s.depth_test == Some(CompareFunc::LessEqual) && !s.depth_write);
    if !later || draw.topology != Topology::Triangles || s.logic_op.is_some() {
        return None;
    }
    let factors = s.blend.map_or((One, Zero), |b| if b.equation_rgb == BlendEquation::Add { (b.src_rgb, b.dst_rgb) } else { (SrcAlpha, SrcAlpha) });
    match factors {
        (One, Zero) if equal => Some(Blending::Replace),
        (DstColor, Zero) | (Zero, SrcColor) => Some(Blending::Multiply),
        (DstColor, SrcColor) | (SrcColor, DstColor) => Some(Blending::Modulate2x),
        (One, One) | (SrcAlpha, One) => Some(Blending::Add),
        (SrcAlpha, OneMinusSrcAlpha) | (One, OneMinusSrcAlpha) => Some(Blending::Over),
        _ => None,
    }
}

/// A traced draw of the frame that later passes may lie on.
#[derive(Clone, Copy, Debug)]
struct Base {
    /// Index in the frame's draws.
    draw: usize,
    /// Layers found on it.
    layers: u8,
    /// Object-space bounds of its positions, once asked.
    bounds: Option<(Vec3, Vec3)>,
    /// Its triangles are in the map.
    indexed: bool,
}

/// The corners of a triangle, bit for bit.
type Corners = [[u32; 4]; 3];

/// The corners of triangle `t` of `draw` (`None` when an index is out of range).
fn corners(draw: &Draw, t: usize) -> Option<Corners> {
    let i = draw.indices.get(3 * t..3 * t + 3)?;
    let p = |k: usize| draw.vertices.position.get(i[k] as usize).map(|p| p.map(f32::to_bits));
    Some([p(0)?, p(1)?, p(2)?])
}

/// The map key of a triangle of base `slot`.
fn key(slot: usize, corners: &Corners) -> u64 {
    use std::hash::Hasher as _;
    let mut h = super::static_world::KeyHasher::default();
    h.write_u64(slot as u64);
    h.write(bytes_of(corners));
    h.finish()
}

/// Finds the bases of the passes of one frame; kept between frames.
#[derive(Default)]
pub struct LayerFinder {
    bases: Vec<Base>,
    /// Key of a triangle of an indexed base → its index in that base.
    map: Map<u64, u32>,
    /// The pass's triangles in its base, while looking it up.
    found: Vec<u32>,
}

impl LayerFinder {
    /// Starts a frame: no bases.
    pub fn begin_frame(&mut self) {
        self.bases.clear();
        self.map.clear();
    }

    /// Adds the traced draw `draw` (index in the frame's draws) as a possible base; bases are
    /// numbered from 0 in the order they are added.
    pub fn add_base(&mut self, draw: usize) {
        self.bases.push(Base { draw, layers: 0, bounds: None, indexed: false });
    }

    /// The frame's draw index of base `base`.
    pub fn draw_of(&self, base: usize) -> usize {
        self.bases[base].draw
    }

    /// Layers found on base `base`.
    pub fn layers_of(&self, base: usize) -> usize {
        usize::from(self.bases[base].layers)
    }

    /// The base of candidate pass `pass` (an index in `draws`, after every base added) and
    /// its triangles in the base, or `None` (module doc). Counts the layer on the base.
    pub fn find(&mut self, draws: &[Draw], pass: usize) -> Option<(usize, Arc<[u32]>)> {
        let p = &draws[pass];
        let triangles = p.indices.len() / 3;
        let first = corners(p, 0)?;
        for slot in (0..self.bases.len()).rev() {
            let b = &draws[self.bases[slot].draw];
            if b.modelview != p.modelview || b.projection != p.projection || b.topology != Topology::Triangles {
                continue;
            }
            let same_arrays = b.indices == p.indices && bytes_of(&b.vertices.position) == bytes_of(&p.vertices.position);
            let found = if same_arrays {
                self.found.clear();
                self.found.extend(0..triangles as u32);
                true
            } else {
                self.may_hold(slot, b, &first[0]) && self.look_up(slot, b, p)
            };
            if found {
                if self.layers_of(slot) >= MAX_LAYERS {
                    return None;
                }
                self.bases[slot].layers += 1;
                return Some((slot, Arc::from(&self.found[..])));
            }
        }
        None
    }

    /// Whether base `slot` (draw `b`) has the vertex `corner`: inside its bounds, then among
    /// its positions.
    fn may_hold(&mut self, slot: usize, b: &Draw, corner: &[u32; 4]) -> bool {
        let bounds = *self.bases[slot].bounds.get_or_insert_with(|| {
            let points = b.vertices.position.iter().map(|p| Vec3::new(p[0], p[1], p[2]));
            points.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)))
        });
        let c = Vec3::new(f32::from_bits(corner[0]), f32::from_bits(corner[1]), f32::from_bits(corner[2]));
        c.cmpge(bounds.0).all() && c.cmple(bounds.1).all() && b.vertices.position.iter().any(|p| p.map(f32::to_bits) == *corner)
    }

    /// Indexes base `slot` (draw `b`) when it is not yet, then looks up every triangle of pass
    /// `p` there; true when all are found (in `self.found`).
    fn look_up(&mut self, slot: usize, b: &Draw, p: &Draw) -> bool {
        if !self.bases[slot].indexed {
            self.bases[slot].indexed = true;
            for t in 0..b.indices.len() / 3 {
                if let Some(c) = corners(b, t) {
                    self.map.entry(key(slot, &c)).or_insert(t as u32);
                }
            }
        }
        self.found.clear();
        for t in 0..p.indices.len() / 3 {
            let Some(c) = corners(p, t) else { return false };
            match self.map.get(&key(slot, &c)) {
                Some(&in_base) if corners(b, in_base as usize) == Some(c) => self.found.push(in_base),
                _ => return false,
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::Mat4;

    use super::*;
    use crate::frame::state::{Blend, RasterState};

    /// A base: `n` triangles side by side (vertices not shared), depth test `GL_LEQUAL`.
    fn base(n: usize) -> Draw {
        let mut d = Draw::default();
        for i in 0..n {
            let x = i as f32;
            d.vertices.position.extend([[x, 0.0, 0.0, 1.0], [x + 1.0, 0.0, 0.0, 1.0], [x, 1.0, 0.0, 1.0]]);
            d.indices.extend([3 * i as u32, 3 * i as u32 + 1, 3 * i as u32 + 2]);
        }
        d.vertex_count = d.vertices.len();
        d.state = Arc::new(RasterState { depth_test: Some(CompareFunc::LessEqual), depth_write: true, color_mask: [true; 4], ..RasterState::default() });
        d.modelview = Mat4::from_translation(glam::Vec3::new(0.0, 0.0, -5.0));
        d
    }

    /// `draw` drawn again as a pass blending `factors`, with `depth` and depth writes off.
    fn pass(draw: &Draw, factors: (BlendFactor, BlendFactor), depth: CompareFunc) -> Draw {
        let blend = Blend { src_rgb: factors.0, dst_rgb: factors.1, ..Blend::default() };
        Draw { state: Arc::new(RasterState { blend: Some(blend), depth_test: Some(depth), depth_write: false, ..(*draw.state).clone() }), ..draw.clone() }
    }

    fn finder(bases: &[usize]) -> LayerFinder {
        let mut f = LayerFinder::default();
        f.begin_frame();
        bases.iter().for_each(|&b| f.add_base(b));
        f
    }

    #[test]
    fn blend_functions_give_blendings() {
        use BlendFactor::*;
        let b = base(1);
        let of = |factors, depth| blending(&pass(&b, factors, depth));
        assert_eq!(of((DstColor, Zero), CompareFunc::Equal), Some(Blending::Multiply));
        assert_eq!(of((Zero, SrcColor), CompareFunc::LessEqual), Some(Blending::Multiply));
        assert_eq!(of((DstColor, SrcColor), CompareFunc::LessEqual), Some(Blending::Modulate2x));
        assert_eq!(of((One, One), CompareFunc::Equal), Some(Blending::Add));
        assert_eq!(of((SrcAlpha, One), CompareFunc::LessEqual), Some(Blending::Add));
        assert_eq!(of((SrcAlpha, OneMinusSrcAlpha), CompareFunc::LessEqual), Some(Blending::Over));
        assert_eq!(of((One, Zero), CompareFunc::Equal), Some(Blending::Replace), "an opaque GL_EQUAL pass");
        assert_eq!(of((One, Zero), CompareFunc::LessEqual), None, "an opaque GL_LEQUAL draw is a surface of its own");
        assert_eq!(of((One, One), CompareFunc::Less), None, "GL_LESS never passes over the same depth");
        assert_eq!(of((OneMinusDstColor, Zero), CompareFunc::Equal), None);
        let writes = Draw { state: Arc::new(RasterState { depth_write: true, ..(*pass(&b, (One, One), CompareFunc::LessEqual).state).clone() }), ..b.clone() };
        assert_eq!(blending(&writes), None, "GL_LEQUAL with depth writes: a surface of its own");
        assert_eq!(Blending::Add.role(), LayerRole::Emission);
        assert_eq!([Blending::Over.role(), Blending::Replace.role(), Blending::Modulate2x.role()], [LayerRole::Decal, LayerRole::Decal, LayerRole::Albedo]);
    }

    #[test]
    fn a_pass_over_the_same_arrays_covers_every_triangle() {
        let draws = [base(4), pass(&base(4), (BlendFactor::DstColor, BlendFactor::SrcColor), CompareFunc::LessEqual)];
        let mut f = finder(&[0]);
        let (slot, triangles) = f.find(&draws, 1).unwrap();
        assert_eq!((slot, &triangles[..], f.layers_of(0)), (0, &[0, 1, 2, 3][..], 1));
    }

    #[test]
    fn a_dynamic_light_pass_covers_a_subset_with_its_own_indices() {
        // The base's triangles 3 and 1, from vertices copied out in another order.
        let b = base(4);
        let mut p = pass(&b, (BlendFactor::One, BlendFactor::One), CompareFunc::Equal);
        let corners = &b.vertices.position;
        p.vertices.position = [3, 1].iter().flat_map(|&t| (0..3).map(move |k| corners[3 * t + k])).collect();
        p.indices = vec![0, 1, 2, 3, 4, 5];
        let other = {
            let mut o = base(2);
            o.vertices.position.iter_mut().for_each(|v| v[1] += 10.0);
            o
        };
        let draws = [b, other, p];
        let mut f = finder(&[0, 1]);
        let (slot, triangles) = f.find(&draws, 2).unwrap();
        assert_eq!((slot, &triangles[..]), (0, &[3, 1][..]), "found in the older base, not the one after it");
        // Corners in another order are another triangle.
        let mut turned = draws[2].clone();
        turned.indices = vec![1, 2, 0, 3, 4, 5];
        let draws = [draws[0].clone(), draws[1].clone(), turned];
        assert!(finder(&[0, 1]).find(&draws, 2).is_none());
    }

    #[test]
    fn a_pass_not_wholly_on_one_base_or_elsewhere_stays() {
        let (a, mut b) = (base(2), base(2));
        b.vertices.position.iter_mut().for_each(|v| v[0] += 2.0);
        // Triangle 0 of `a` and triangle 1 of `b`.
        let mut straddling = pass(&a, (BlendFactor::One, BlendFactor::One), CompareFunc::Equal);
        straddling.vertices.position = [&a.vertices.position[0..3], &b.vertices.position[3..6]].concat();
        let draws = [a.clone(), b, straddling];
        assert!(finder(&[0, 1]).find(&draws, 2).is_none());
        // The same triangles seen through another modelview: another place.
        let mut moved = pass(&a, (BlendFactor::One, BlendFactor::One), CompareFunc::Equal);
        moved.modelview = Mat4::IDENTITY;
        assert!(finder(&[0]).find(&[a.clone(), moved], 1).is_none());
        // A pass over a draw that is not a base (not traced).
        assert!(finder(&[]).find(&[a.clone(), pass(&a, (BlendFactor::One, BlendFactor::One), CompareFunc::Equal)], 1).is_none());
    }

    #[test]
    fn a_base_keeps_at_most_max_layers() {
        let b = base(3);
        let mut draws = vec![b.clone()];
        draws.extend((0..MAX_LAYERS + 1).map(|_| pass(&b, (BlendFactor::One, BlendFactor::One), CompareFunc::Equal)));
        let mut f = finder(&[0]);
        let found: Vec<bool> = (1..draws.len()).map(|i| f.find(&draws, i).is_some()).collect();
        assert_eq!(found, [vec![true; MAX_LAYERS], vec![false]].concat());
        assert_eq!(f.layers_of(0), MAX_LAYERS);
    }
}
