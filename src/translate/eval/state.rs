//! Evaluator state (OpenGL 1.5 section 5.1, table 6.x "Evaluators"): the nine maps of each
//! dimension, the two grids, and what `GL_EVAL_BIT` saves.

use std::sync::Arc;

use super::bernstein;
use crate::translate::enable::EnableState;
use crate::translate::gl::{self, GLenum, GLint};

/// One- or two-dimensional maps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapDim {
    /// `glMap1*`, `GL_MAP1_*`.
    One,
    /// `glMap2*`, `GL_MAP2_*`.
    Two,
}

impl MapDim {
    /// Number of parameters (u, or u and v).
    pub fn count(self) -> usize {
        match self {
            MapDim::One => 1,
            MapDim::Two => 2,
        }
    }
}

/// Components of each map target, in enum order from `GL_MAPn_COLOR_4`: COLOR_4, INDEX,
/// NORMAL, TEXTURE_COORD_1..4, VERTEX_3, VERTEX_4.
const SIZES: [usize; 9] = [4, 1, 3, 1, 2, 3, 4, 3, 4];
const COLOR: usize = 0;
const NORMAL: usize = 2;
const TEXTURE: [usize; 4] = [3, 4, 5, 6];
const VERTEX_3: usize = 7;
const VERTEX_4: usize = 8;

/// The slot of a map target of dimension `dim` and its component count.
pub fn map_slot(dim: MapDim, target: GLenum) -> Option<(usize, usize)> {
    let first = match dim {
        MapDim::One => gl::GL_MAP1_COLOR_4,
        MapDim::Two => gl::GL_MAP2_COLOR_4,
    };
    let slot = target.wrapping_sub(first) as usize;
    SIZES.get(slot).map(|&k| (slot, k))
}

fn map_enable(dim: MapDim, slot: usize) -> GLenum {
    let first = match dim {
        MapDim::One => gl::GL_MAP1_COLOR_4,
        MapDim::Two => gl::GL_MAP2_COLOR_4,
    };
    first + slot as GLenum
}

/// The capabilities `GL_EVAL_BIT` saves: the 18 map enables and `GL_AUTO_NORMAL`.
pub const EVAL_ENABLES: [GLenum; 19] = {
    let mut caps = [gl::GL_AUTO_NORMAL; 19];
    let mut i = 0;
    while i < 9 {
        caps[i] = gl::GL_MAP1_COLOR_4 + i as GLenum;
        caps[9 + i] = gl::GL_MAP2_COLOR_4 + i as GLenum;
        i += 1;
    }
    caps
};

/// One map: its domain, order and control points.
#[derive(Clone, Debug, PartialEq)]
pub struct Map {
    /// u1, u2 (and v1, v2 for two-dimensional maps).
    pub domain: [f64; 4],
    /// Order in u (and v; 1 for one-dimensional maps).
    pub order: [usize; 2],
    /// Control points, point (i, j) at `(i * order[1] + j) * k`.
    pub points: Arc<[f64]>,
}

impl Map {
    /// The initial map of a slot: order 1, domain [0, 1], one point of the initial value
    /// (table 6.x: vertex (0, 0, 0[, 1]), index 1, colour (1, 1, 1, 1), normal (0, 0, 1),
    /// texture (0, 0, 0, 1) truncated).
    fn initial(slot: usize) -> Map {
        let point: &[f64] = match slot {
            COLOR => &[1.0; 4],
            1 => &[1.0],
            NORMAL => &[0.0, 0.0, 1.0],
            3 => &[0.0],
            4 => &[0.0; 2],
            5 | VERTEX_3 => &[0.0; 3],
            _ => &[0.0, 0.0, 0.0, 1.0],
        };
        Map { domain: [0.0, 1.0, 0.0, 1.0], order: [1, 1], points: point.into() }
    }

    /// Value and derivatives at (u, v) in the map's own domain (equation 5.2: u' = (u − u1) /
    /// (u2 − u1)); `v` is ignored for one-dimensional maps.
    fn eval(&self, dim: MapDim, k: usize, u: f64, v: f64) -> bernstein::SurfacePoint {
        let t = (u - self.domain[0]) / (self.domain[1] - self.domain[0]);
        match dim {
            MapDim::One => {
                let c = bernstein::curve(&self.points, k, self.order[0], t);
                bernstein::SurfacePoint { dv: vec![0.0; k], value: c.value, du: c.derivative }
            }
            MapDim::Two => {
                let s = (v - self.domain[2]) / (self.domain[3] - self.domain[2]);
                bernstein::surface(&self.points, k, self.order[0], self.order[1], t, s)
            }
        }
    }
}

/// A grid (`glMapGrid1*`/`glMapGrid2*`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    /// n (and m): segments in u (and v).
    pub segments: [GLint; 2],
    /// u1, u2 (and v1, v2).
    pub domain: [f64; 4],
}

impl Grid {
    /// The grid coordinate of step `i` along dimension `d` (0 for u, 1 for v): u1 + i·Δu,
    /// exactly u2 at i = n (section 5.1, `glEvalMesh`).
    pub fn coord(&self, d: usize, i: GLint) -> f64 {
        let (a, b, n) = (self.domain[2 * d], self.domain[2 * d + 1], self.segments[d]);
        if i == n { b } else { a + f64::from(i) * (b - a) / f64::from(n) }
    }
}

/// The evaluator state of a context.
#[derive(Clone, Debug, PartialEq)]
pub struct EvalState {
    map1: [Map; 9],
    map2: [Map; 9],
    /// `GL_MAP1_GRID_DOMAIN`, `GL_MAP1_GRID_SEGMENTS`.
    pub grid1: Grid,
    /// `GL_MAP2_GRID_DOMAIN`, `GL_MAP2_GRID_SEGMENTS`.
    pub grid2: Grid,
}

impl Default for EvalState {
    fn default() -> EvalState {
        let grid = Grid { segments: [1, 1], domain: [0.0, 1.0, 0.0, 1.0] };
        EvalState {
            map1: std::array::from_fn(Map::initial),
            map2: std::array::from_fn(Map::initial),
            grid1: grid,
            grid2: grid,
        }
    }
}

/// What `glPushAttrib(GL_EVAL_BIT)` saves.
#[derive(Clone, Debug, PartialEq)]
pub struct EvalAttrib {
    /// The states of [`EVAL_ENABLES`], in order.
    pub enables: [bool; 19],
    /// The one-dimensional grid.
    pub grid1: Grid,
    /// The two-dimensional grid.
    pub grid2: Grid,
}

/// The attributes an evaluation produced, issued as the commands of section 5.1 would be.
#[derive(Clone, Debug, PartialEq)]
pub struct EvalVertex {
    /// From `GL_MAPn_COLOR_4`, for `glColor4f`.
    pub color: Option<[f32; 4]>,
    /// From `GL_MAPn_NORMAL` or `GL_AUTO_NORMAL`, for `glNormal3f`.
    pub normal: Option<[f32; 3]>,
    /// From the highest enabled `GL_MAPn_TEXTURE_COORD_k`, completed to (s, t, 0, 1), for
    /// `glTexCoord4f`.
    pub texcoord: Option<[f32; 4]>,
    /// From `GL_MAPn_VERTEX_4` or `GL_MAPn_VERTEX_3` (w = 1), for `glVertex4f`.
    pub position: [f32; 4],
}

impl EvalState {
    /// The map of `dim` in `slot`.
    pub fn map(&self, dim: MapDim, slot: usize) -> &Map {
        match dim {
            MapDim::One => &self.map1[slot],
            MapDim::Two => &self.map2[slot],
        }
    }

    /// The map of `dim` in `slot`, to replace.
    pub fn map_mut(&mut self, dim: MapDim, slot: usize) -> &mut Map {
        match dim {
            MapDim::One => &mut self.map1[slot],
            MapDim::Two => &mut self.map2[slot],
        }
    }

    /// The enabled vertex map of `dim` (`VERTEX_4` wins over `VERTEX_3`), if any.
    pub fn vertex_map(&self, dim: MapDim, enables: &EnableState) -> Option<usize> {
        [VERTEX_4, VERTEX_3].into_iter().find(|&s| enables.is_on(map_enable(dim, s)))
    }

    /// Evaluates the enabled maps of `dim` at (u, v) (section 5.1). `None` when no vertex
    /// map is enabled: then no vertex is generated. The index map is not evaluated: glrt's
    /// contexts are RGBA, where the colour index is unused.
    pub fn evaluate(&self, dim: MapDim, enables: &EnableState, u: f64, v: f64) -> Option<EvalVertex> {
        let on = |slot: usize| enables.is_on(map_enable(dim, slot));
        let eval = |slot: usize| self.map(dim, slot).eval(dim, SIZES[slot], u, v);
        let f32s = |x: &[f64]| -> [f32; 4] { std::array::from_fn(|i| x.get(i).map_or(if i == 3 { 1.0 } else { 0.0 }, |&c| c as f32)) };
        let vertex_slot = self.vertex_map(dim, enables)?;
        let p = eval(vertex_slot);
        let position = f32s(&p.value);
        let normal = if dim == MapDim::Two && enables.is_on(gl::GL_AUTO_NORMAL) {
            Some(bernstein::auto_normal(&p).map(|c| c as f32))
        } else if on(NORMAL) {
            let n = eval(NORMAL).value;
            Some([n[0] as f32, n[1] as f32, n[2] as f32])
        } else {
            None
        };
        let texcoord = TEXTURE.into_iter().rev().find(|&s| on(s)).map(|s| f32s(&eval(s).value));
        let color = on(COLOR).then(|| f32s(&eval(COLOR).value));
        Some(EvalVertex { color, normal, texcoord, position })
    }
}
