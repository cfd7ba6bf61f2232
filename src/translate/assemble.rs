//! Primitive decomposition (OpenGL 1.5 section 2.6.1): the ten `glBegin` modes become indexed
//! triangles, lines or points.
//!
//! Conventions of the output (see [`crate::frame::Draw`]):
//! - each primitive keeps the winding of the program's vertices;
//! - the provoking vertex of each output primitive (section 2.14.7, table 2.11: the last vertex
//!   of each primitive, the first for `GL_POLYGON`) is its **last** index, so a renderer using
//!   the last-vertex convention flat-shades exactly as OpenGL does;
//! - triangles carry an edge mask (bit `k`: edge from index `k` to index `k + 1`) that keeps
//!   only the boundary edges of the program's polygons whose edge flag was true (section 2.6.2);
//!   strips and fans ignore edge flags, like the specification says.
//!
//! Incomplete primitives are dropped: a trailing vertex that does not complete a line,
//! triangle or quad, and strips, loops, fans and polygons with too few vertices.

use super::gl::{self, GLenum};
use super::immediate::Batch;
use crate::frame::Topology;

/// A `glBegin` mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Primitive {
    /// `GL_POINTS`.
    Points,
    /// `GL_LINES`.
    Lines,
    /// `GL_LINE_LOOP`.
    LineLoop,
    /// `GL_LINE_STRIP`.
    LineStrip,
    /// `GL_TRIANGLES`.
    Triangles,
    /// `GL_TRIANGLE_STRIP`.
    TriangleStrip,
    /// `GL_TRIANGLE_FAN`.
    TriangleFan,
    /// `GL_QUADS`.
    Quads,
    /// `GL_QUAD_STRIP`.
    QuadStrip,
    /// `GL_POLYGON`.
    Polygon,
}

impl Primitive {
    /// The mode of a `glBegin` / `glDrawArrays` enum; `None` for an invalid one.
    pub fn from_gl(mode: GLenum) -> Option<Primitive> {
        Some(match mode {
            gl::GL_POINTS => Primitive::Points,
            gl::GL_LINES => Primitive::Lines,
            gl::GL_LINE_LOOP => Primitive::LineLoop,
            gl::GL_LINE_STRIP => Primitive::LineStrip,
            gl::GL_TRIANGLES => Primitive::Triangles,
            gl::GL_TRIANGLE_STRIP => Primitive::TriangleStrip,
            gl::GL_TRIANGLE_FAN => Primitive::TriangleFan,
            gl::GL_QUADS => Primitive::Quads,
            gl::GL_QUAD_STRIP => Primitive::QuadStrip,
            gl::GL_POLYGON => Primitive::Polygon,
            _ => return None,
        })
    }

    /// The GL enum of the mode.
    pub fn to_gl(self) -> GLenum {
        match self {
            Primitive::Points => gl::GL_POINTS,
            Primitive::Lines => gl::GL_LINES,
            Primitive::LineLoop => gl::GL_LINE_LOOP,
            Primitive::LineStrip => gl::GL_LINE_STRIP,
            Primitive::Triangles => gl::GL_TRIANGLES,
            Primitive::TriangleStrip => gl::GL_TRIANGLE_STRIP,
            Primitive::TriangleFan => gl::GL_TRIANGLE_FAN,
            Primitive::Quads => gl::GL_QUADS,
            Primitive::QuadStrip => gl::GL_QUAD_STRIP,
            Primitive::Polygon => gl::GL_POLYGON,
        }
    }

    /// What the mode decomposes into.
    pub fn topology(self) -> Topology {
        match self {
            Primitive::Points => Topology::Points,
            Primitive::Lines | Primitive::LineLoop | Primitive::LineStrip => Topology::Lines,
            _ => Topology::Triangles,
        }
    }
}

/// Decomposed primitives: indices and, for triangles, edge masks. Reused between batches.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Assembled {
    /// Indices into the batch's vertices.
    pub indices: Vec<u32>,
    /// One edge mask per triangle (empty for lines and points).
    pub edge_masks: Vec<u8>,
}

impl Assembled {
    /// Empties both lists, keeping their storage.
    pub fn clear(&mut self) {
        self.indices.clear();
        self.edge_masks.clear();
    }

    fn tri(&mut self, a: u32, b: u32, c: u32, mask: u8) {
        self.indices.extend_from_slice(&[a, b, c]);
        self.edge_masks.push(mask);
    }
}

/// Every edge of a triangle.
const ALL_EDGES: u8 = 0b111;

/// Appends to `out` the primitives of `mode` over `n` vertices: the `k`-th vertex given
/// between `glBegin` and `glEnd` is batch vertex `vertex(k)`, with edge flag `edge(k)`.
pub fn assemble(
    mode: Primitive,
    n: usize,
    vertex: impl Fn(usize) -> u32,
    edge: impl Fn(usize) -> bool,
    out: &mut Assembled,
) {
    let v = &vertex;
    let bit = |k: usize, shift: u8| u8::from(edge(k)) << shift;
    match mode {
        Primitive::Points => out.indices.extend((0..n).map(v)),
        Primitive::Lines => out.indices.extend((0..n / 2 * 2).map(v)),
        Primitive::LineStrip | Primitive::LineLoop if n >= 2 => {
            for k in 0..n - 1 {
                out.indices.extend_from_slice(&[v(k), v(k + 1)]);
            }
            if mode == Primitive::LineLoop {
                // Closing segment: its provoking vertex is the first vertex (table 2.11).
                out.indices.extend_from_slice(&[v(n - 1), v(0)]);
            }
        }
        Primitive::Triangles => {
            for k in (0..n / 3 * 3).step_by(3) {
                out.tri(v(k), v(k + 1), v(k + 2), bit(k, 0) | bit(k + 1, 1) | bit(k + 2, 2));
            }
        }
        Primitive::TriangleStrip if n >= 3 => {
            for k in 0..n - 2 {
                // Odd triangles swap their first two vertices to keep the winding.
                let (a, b) = if k % 2 == 0 { (k, k + 1) } else { (k + 1, k) };
                out.tri(v(a), v(b), v(k + 2), ALL_EDGES);
            }
        }
        Primitive::TriangleFan if n >= 3 => {
            for k in 1..n - 1 {
                out.tri(v(0), v(k), v(k + 1), ALL_EDGES);
            }
        }
        Primitive::Quads => {
            for k in (0..n / 4 * 4).step_by(4) {
                // Quad a b c d, provoking d: split along b–d.
                let (a, b, c, d) = (k, k + 1, k + 2, k + 3);
                out.tri(v(a), v(b), v(d), bit(a, 0) | bit(d, 2));
                out.tri(v(b), v(c), v(d), bit(b, 0) | bit(c, 1));
            }
        }
        Primitive::QuadStrip if n >= 4 => {
            for q in 0..(n - 2) / 2 {
                // Quad q is a = 2q, b = 2q+1, c = 2q+3, d = 2q+2 in boundary order; provoking c.
                let (a, b, c, d) = (2 * q, 2 * q + 1, 2 * q + 3, 2 * q + 2);
                out.tri(v(a), v(b), v(c), 0b011);
                out.tri(v(d), v(a), v(c), 0b101);
            }
        }
        Primitive::Polygon if n >= 3 => {
            for k in 1..n - 1 {
                // Rotated fan (k, k+1, 0): provoking vertex 0 comes last.
                let first = if k == 1 { bit(0, 2) } else { 0 };
                let last = if k + 1 == n - 1 { bit(n - 1, 1) } else { 0 };
                out.tri(v(k), v(k + 1), v(0), bit(k, 0) | last | first);
            }
        }
        _ => {}
    }
}

/// [`assemble`] of `batch`'s vertices, the `k`-th being batch vertex `order[k]` (or `k`), with
/// their edge flags. Separate triangles whose vertices share one edge flag (no edge flag
/// array, no `glEdgeFlag` change inside the batch) are copied whole, the indices as given and
/// one mask for all, instead of vertex by vertex.
pub fn assemble_batch(mode: Primitive, batch: &Batch, order: Option<&[u32]>, out: &mut Assembled) {
    let n = order.map_or(batch.vertices.len(), <[u32]>::len);
    let shared_edge = match batch.edge_flags.values.as_slice() {
        [] => Some(true),
        [flag] => Some(*flag),
        _ => None,
    };
    match (mode, shared_edge, order) {
        (Primitive::Triangles, Some(edge), order) => {
            let whole = n / 3 * 3;
            match order {
                Some(order) => out.indices.extend_from_slice(&order[..whole]),
                None => out.indices.extend(0..whole as u32),
            }
            out.edge_masks.resize(out.edge_masks.len() + whole / 3, if edge { ALL_EDGES } else { 0 });
        }
        (_, _, None) => assemble(mode, n, |k| k as u32, |k| batch.edge_flag(k as u32), out),
        (_, _, Some(order)) => assemble(mode, n, |k| order[k], |k| batch.edge_flag(order[k]), out),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(mode: Primitive, n: usize) -> Assembled {
        let mut out = Assembled::default();
        assemble(mode, n, |k| k as u32, |_| true, &mut out);
        out
    }

    /// Signed area of triangle (a, b, c) for vertices on a convex polygon placed
    /// counter-clockwise on a circle in input order: positive means the winding is kept.
    fn ccw_on_circle(n: usize, t: &[u32]) -> bool {
        let p = |i: u32| {
            let a = i as f64 / n as f64 * std::f64::consts::TAU;
            (a.cos(), a.sin())
        };
        let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
        (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0) > 0.0
    }

    #[test]
    fn points_and_lines() {
        assert_eq!(run(Primitive::Points, 3).indices, vec![0, 1, 2]);
        assert_eq!(run(Primitive::Lines, 5).indices, vec![0, 1, 2, 3], "odd vertex dropped");
        assert_eq!(run(Primitive::LineStrip, 3).indices, vec![0, 1, 1, 2]);
        assert_eq!(run(Primitive::LineLoop, 3).indices, vec![0, 1, 1, 2, 2, 0]);
        assert!(run(Primitive::LineStrip, 1).indices.is_empty());
        assert!(run(Primitive::LineLoop, 1).indices.is_empty());
        assert!(run(Primitive::Lines, 4).edge_masks.is_empty());
    }

    #[test]
    fn triangles_keep_last_vertex_provoking() {
        let t = run(Primitive::Triangles, 7);
        assert_eq!(t.indices, vec![0, 1, 2, 3, 4, 5]);
        assert_eq!(t.edge_masks, vec![ALL_EDGES, ALL_EDGES]);
        assert!(run(Primitive::Triangles, 2).indices.is_empty());
    }

    #[test]
    fn triangle_strip_alternates_and_provokes_last() {
        let t = run(Primitive::TriangleStrip, 5);
        assert_eq!(t.indices, vec![0, 1, 2, 2, 1, 3, 2, 3, 4]);
        for (i, tri) in t.indices.chunks(3).enumerate() {
            assert_eq!(tri[2] as usize, i + 2, "provoking vertex of strip triangle {i}");
        }
        assert!(run(Primitive::TriangleStrip, 2).indices.is_empty());
    }

    #[test]
    fn triangle_fan() {
        let t = run(Primitive::TriangleFan, 5);
        assert_eq!(t.indices, vec![0, 1, 2, 0, 2, 3, 0, 3, 4]);
        for tri in t.indices.chunks(3) {
            assert!(ccw_on_circle(5, tri));
        }
    }

    #[test]
    fn quads_split_keep_winding_provoking_and_boundary_edges() {
        let t = run(Primitive::Quads, 9);
        assert_eq!(t.indices.len(), 12, "two quads, trailing vertex dropped");
        for (i, tri) in t.indices.chunks(3).enumerate() {
            let quad = (i / 2) as u32;
            assert_eq!(tri[2], quad * 4 + 3, "provoking vertex is the quad's fourth");
            let local: Vec<u32> = tri.iter().map(|x| x - quad * 4).collect();
            assert!(ccw_on_circle(4, &local));
        }
        // The b–d diagonal is never a boundary edge.
        assert_eq!(t.edge_masks, vec![0b101, 0b011, 0b101, 0b011]);
        let mut out = Assembled::default();
        assemble(Primitive::Quads, 4, |k| k as u32, |k| k != 0, &mut out);
        assert_eq!(out.edge_masks, vec![0b100, 0b011], "edge flag of vertex 0 hides edge 0→1");
    }

    #[test]
    fn quad_strip() {
        let t = run(Primitive::QuadStrip, 7);
        assert_eq!(t.indices, vec![0, 1, 3, 2, 0, 3, 2, 3, 5, 4, 2, 5], "odd vertex dropped");
        assert_eq!(t.edge_masks, vec![0b011, 0b101, 0b011, 0b101]);
        assert!(run(Primitive::QuadStrip, 3).indices.is_empty());
        // Quad 0 in boundary order is 0 1 3 2: both triangles wind like it.
        let boundary = [0u32, 1, 3, 2];
        for tri in t.indices[..6].chunks(3) {
            let pos: Vec<u32> = tri.iter().map(|x| boundary.iter().position(|b| b == x).unwrap() as u32).collect();
            assert!(ccw_on_circle(4, &pos));
        }
    }

    #[test]
    fn polygon_provokes_first_vertex_and_hides_diagonals() {
        let t = run(Primitive::Polygon, 5);
        assert_eq!(t.indices, vec![1, 2, 0, 2, 3, 0, 3, 4, 0]);
        for tri in t.indices.chunks(3) {
            assert_eq!(tri[2], 0, "flat shading of a polygon uses its first vertex");
            assert!(ccw_on_circle(5, tri));
        }
        assert_eq!(t.edge_masks, vec![0b101, 0b001, 0b011]);
        assert!(run(Primitive::Polygon, 2).indices.is_empty());
        let tri = run(Primitive::Polygon, 3);
        assert_eq!(tri.edge_masks, vec![ALL_EDGES]);
    }

    #[test]
    fn enum_round_trip() {
        for mode in gl::GL_POINTS..=gl::GL_POLYGON {
            assert_eq!(Primitive::from_gl(mode).map(Primitive::to_gl), Some(mode));
        }
        assert_eq!(Primitive::from_gl(gl::GL_POLYGON + 1), None);
    }

    #[test]
    fn a_batch_assembles_as_its_vertices_one_by_one() {
        use crate::translate::immediate::CurrentAttribs;
        let order: Vec<u32> = vec![4, 0, 3, 1, 1, 2, 0, 4];
        for flags in [vec![], vec![true], vec![false], vec![true, false, true, true, false]] {
            let mut batch = Batch::default();
            for i in 0..5 {
                batch.push([i as f32, 0.0, 0.0, 1.0], &CurrentAttribs::default(), 0);
            }
            batch.edge_flags.values = flags.clone();
            for mode in [Primitive::Points, Primitive::Lines, Primitive::Triangles, Primitive::Quads, Primitive::Polygon] {
                for order in [None, Some(&order[..]), Some(&order[..6])] {
                    let n = order.map_or(5, <[u32]>::len);
                    let vertex = |k: usize| order.map_or(k as u32, |o| o[k]);
                    let mut one_by_one = Assembled { indices: vec![9], edge_masks: vec![1] };
                    assemble(mode, n, vertex, |k| batch.edge_flag(vertex(k)), &mut one_by_one);
                    let mut whole = Assembled { indices: vec![9], edge_masks: vec![1] };
                    assemble_batch(mode, &batch, order, &mut whole);
                    assert_eq!(whole, one_by_one, "{mode:?}, flags {flags:?}, order {order:?}");
                }
            }
        }
    }
}
