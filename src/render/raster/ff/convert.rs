//! Primitive conversion on the CPU: what Vulkan cannot rasterize the way OpenGL 1.5 does
//! becomes triangles here.
//!
//! - **Polygon mode** (section 3.5.4): when a face's mode is not `FILL`, the facing of each
//!   triangle is computed from its clip-space vertices (the sign of `det(x, y, w)`, which is
//!   the orientation of the triangle's visible part even when it crosses the eye plane),
//!   culling is applied here (section 3.5.1), and the boundary edges ([`Draw::edge_masks`]) or
//!   the vertices that start one become lines or points with that face's colours
//!   ([`Facing::Front`]/[`Facing::Back`]); filled faces stay triangles, culled here too.
//! - **Lines** (section 3.4) are quads: aliased lines are the x- or y-major parallelograms of
//!   section 3.4.2 (the width, rounded, spread along the minor axis; the ends are then
//!   vertical or horizontal, so pixel centres between the endpoints are covered as with the
//!   diamond-exit rule), smooth lines the rectangle of section 3.4.2 widened by half a pixel
//!   each side for the coverage fringe. Each corner carries its window-pixel offset, which
//!   `ff.vert` adds in clip space (so the offset is exact after the perspective divide).
//!   Segments are first clipped to the near plane and to `w > 0`, interpolating the packed
//!   vertex.
//! - **Line stipple** (section 3.4.2): each corner carries the stipple distance, the count of
//!   major-axis pixels from the start of its run; `ff.frag` discards by the pattern. A run is
//!   a chain of segments where each starts at the vertex where the previous one ended (line
//!   strips and loops, and consecutive polygon edges); the counter restarts otherwise, as it
//!   does for independent `GL_LINES` segments. [`Draw`] keeps no primitive boundaries, so
//!   `GL_LINES` drawn with `glDrawElements` whose second segment starts at the index the first
//!   ended at counts on as if it were a strip (merged `glBegin`/`glEnd` batches get fresh
//!   indices, so they are told apart).
//! - **Points** (section 3.3) are quads of corners (±1, ±1) that `ff.vert` scales by the
//!   derived point size; a point whose centre is outside the clip volume is dropped (the
//!   whole point, as section 2.12 says); user clip planes are evaluated at the centre by
//!   every corner alike.
//! - **Flat shading** (section 2.14.7): the corners of a line or point carry the colours and
//!   normal of the primitive's provoking vertex (for polygon edges and vertices, the
//!   polygon's). Positional lights are then evaluated at the corner's own position, a small
//!   departure for edges of flat-shaded polygons lit by nearby lights.

use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

use super::indices::BatchIndices;
use super::key::{Facing, Primitive};
use super::vertex::{self, VERTEX_FLOATS};
use crate::frame::state::{Face, PolygonMode, ShadeModel, Winding, MAX_POINT_SIZE};
use crate::frame::{Draw, Topology};

/// The geometry of one batch.
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    /// What is rasterized.
    pub primitive: Primitive,
    /// Whose colours.
    pub facing: Facing,
    /// Expanded vertices, or `None` for the draw's own packed vertices.
    pub vertices: Option<Vec<f32>>,
    /// Triangle list indices (points) or as the topology says, provoking vertex first.
    pub indices: BatchIndices,
    /// The face culling the rasterizer still applies.
    pub cull: Option<Face>,
    /// Whether the polygon offset applies.
    pub polygon_offset: bool,
}

/// A line segment from vertex `a` to `b` whose colours come from `provoking` when flat.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Segment {
    /// Start.
    pub a: u32,
    /// End.
    pub b: u32,
    /// Provoking vertex.
    pub provoking: u32,
}

/// The parts that draw `draw`. Filled triangles keep the draw's vertices and indices (packed
/// and rotated where they are uploaded); what is expanded is packed here, with radiosity's
/// `indirect` light per vertex where there is one ([`super::prepare`]).
pub fn convert(draw: &Draw, indirect: Option<&[[f32; 3]]>) -> Vec<Part> {
    let count = draw.vertices.len() as u32;
    let valid = |p: &[u32]| p.iter().all(|&i| i < count);
    let s = &draw.state;
    match draw.topology {
        Topology::Triangles if s.polygon_mode == [PolygonMode::Fill; 2] => vec![Part {
            primitive: Primitive::Triangle,
            facing: Facing::Rasterizer,
            vertices: None,
            indices: BatchIndices::rotated(draw, 3),
            cull: s.cull,
            polygon_offset: s.polygon_offset.fill,
        }],
        Topology::Triangles => polygon_modes(draw, count, indirect),
        Topology::Lines => {
            let segments: Vec<Segment> = draw
                .indices
                .chunks_exact(2)
                .filter(|l| valid(l))
                .map(|l| Segment { a: l[0], b: l[1], provoking: l[1] })
                .collect();
            let (vertices, indices) = expand_lines(draw, &packed(draw, indirect), &segments);
            vec![expanded(Primitive::Line, Facing::Front, vertices, indices, false)]
        }
        Topology::Points => {
            let points: Vec<(u32, u32)> = draw.indices.iter().filter(|&&i| i < count).map(|&i| (i, i)).collect();
            let (vertices, indices) = expand_points(draw, &packed(draw, indirect), &points);
            vec![expanded(Primitive::Point, Facing::Front, vertices, indices, false)]
        }
    }
}

/// The draw's vertices packed, with radiosity's `indirect` light where there is one.
fn packed(draw: &Draw, indirect: Option<&[[f32; 3]]>) -> Vec<f32> {
    let mut packed = vertex::pack(draw);
    if let Some(indirect) = indirect {
        vertex::set_indirect(&mut packed, indirect);
    }
    packed
}

/// A part of expanded vertices and their list of indices.
fn expanded(primitive: Primitive, facing: Facing, vertices: Vec<f32>, indices: Vec<u32>, offset: bool) -> Part {
    Part { primitive, facing, vertices: Some(vertices), indices: BatchIndices::List(indices), cull: None, polygon_offset: offset }
}

/// Clip-space and window positions of packed vertices.
struct Window {
    mvp: Mat4,
    /// Viewport x, y, width, height.
    viewport: Vec4,
}

impl Window {
    fn new(draw: &Draw) -> Window {
        Window { mvp: draw.projection * draw.modelview, viewport: Vec4::from(draw.state.viewport.map(|v| v as f32)) }
    }

    /// The clip position of packed vertex `v`.
    fn clip(&self, v: &[f32]) -> Vec4 {
        self.mvp * Vec4::from_slice(&v[vertex::POSITION..vertex::POSITION + 4])
    }

    /// Window coordinates (pixels, y up) of a clip position with `w > 0`.
    fn window(&self, c: Vec4) -> Vec2 {
        let ndc = Vec2::new(c.x, c.y) / c.w;
        Vec2::new(self.viewport.x, self.viewport.y) + (ndc * 0.5 + 0.5) * Vec2::new(self.viewport.z, self.viewport.w)
    }
}

/// Whether the triangle with clip positions `c` faces front under `winding` (degenerate
/// triangles count as front).
pub fn is_front(c: [Vec4; 3], winding: Winding) -> bool {
    let det = Mat3::from_cols(c[0].truncate().with_z(c[0].w), c[1].truncate().with_z(c[1].w), c[2].truncate().with_z(c[2].w))
        .determinant();
    det == 0.0 || (det > 0.0) == (winding == Winding::Ccw)
}

/// Triangles of a draw with a non-`FILL` polygon mode, by face.
fn polygon_modes(draw: &Draw, count: u32, indirect: Option<&[[f32; 3]]>) -> Vec<Part> {
    let s = &draw.state;
    let window = Window::new(draw);
    let mut fill = Vec::new();
    let mut edges: [Vec<Segment>; 2] = Default::default();
    let mut points: [Vec<(u32, u32)>; 2] = Default::default();
    for (t, tri) in draw.indices.chunks_exact(3).enumerate() {
        if tri.iter().any(|&i| i >= count) {
            continue;
        }
        let clip = [0, 1, 2].map(|k| window.mvp * Vec4::from(draw.vertices.position[tri[k] as usize]));
        let face = if is_front(clip, s.front_face) { 0 } else { 1 };
        let culled = match s.cull {
            None => false,
            Some(Face::Front) => face == 0,
            Some(Face::Back) => face == 1,
            Some(Face::FrontAndBack) => true,
        };
        if culled {
            continue;
        }
        let mask = draw.edge_masks.get(t).copied().unwrap_or(0b111);
        let provoking = tri[2];
        match s.polygon_mode[face] {
            PolygonMode::Fill => fill.extend_from_slice(&[tri[2], tri[0], tri[1]]),
            PolygonMode::Line => {
                for k in (0..3).filter(|k| mask & (1 << k) != 0) {
                    edges[face].push(Segment { a: tri[k], b: tri[(k + 1) % 3], provoking });
                }
            }
            PolygonMode::Point => {
                points[face].extend((0..3).filter(|k| mask & (1 << k) != 0).map(|k| (tri[k], provoking)));
            }
        }
    }
    let mut parts = Vec::new();
    if !fill.is_empty() {
        parts.push(Part {
            primitive: Primitive::Triangle,
            facing: Facing::Rasterizer,
            vertices: None,
            indices: BatchIndices::List(fill),
            cull: None,
            polygon_offset: s.polygon_offset.fill,
        });
    }
    // Edges and points are copies of packed vertices.
    let expanded_any = edges.iter().any(|e| !e.is_empty()) || points.iter().any(|p| !p.is_empty());
    let packed = if expanded_any { packed(draw, indirect) } else { Vec::new() };
    for (face, facing) in [Facing::Front, Facing::Back].into_iter().enumerate() {
        if !edges[face].is_empty() {
            let (v, i) = expand_lines(draw, &packed, &edges[face]);
            parts.push(expanded(Primitive::Line, facing, v, i, s.polygon_offset.line));
        }
        if !points[face].is_empty() {
            let (v, i) = expand_points(draw, &packed, &points[face]);
            parts.push(expanded(Primitive::Point, facing, v, i, s.polygon_offset.point));
        }
    }
    parts
}

/// Builds expanded vertices: copies of packed vertices with their rasterization attribute.
struct Corners<'a> {
    packed: &'a [f32],
    flat: bool,
    vertices: Vec<f32>,
    indices: Vec<u32>,
}

impl Corners<'_> {
    /// Appends a copy of `v` (with `provoking`'s colours and normal when flat) and returns
    /// its index.
    fn push(&mut self, v: &[f32], provoking: u32, raster: [f32; 4]) -> u32 {
        let index = (self.vertices.len() / VERTEX_FLOATS) as u32;
        let start = self.vertices.len();
        self.vertices.extend_from_slice(v);
        if self.flat {
            let shaded = vertex::COLOR..vertex::NORMAL + 3;
            self.vertices[start + shaded.start..start + shaded.end]
                .copy_from_slice(&vertex::get(self.packed, provoking)[shaded]);
        }
        self.vertices[start + vertex::RASTER..start + vertex::RASTER + 4].copy_from_slice(&raster);
        index
    }

    /// Two triangles over corners `c` (in order around the quad), `c[0]` first in both.
    fn quad(&mut self, c: [u32; 4]) {
        self.indices.extend_from_slice(&[c[0], c[1], c[2], c[0], c[2], c[3]]);
    }
}

/// The part of the segment from clip position `a` to `b` with `z ≥ −w` and `w > 0`, as
/// parameters `t0 < t1` along it, or `None` when nothing is left.
fn clip_near(a: Vec4, b: Vec4) -> Option<(f32, f32)> {
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for (da, db) in [(a.z + a.w, b.z + b.w), (a.w - 1e-6, b.w - 1e-6)] {
        if da < 0.0 && db < 0.0 {
            return None;
        }
        if da < 0.0 {
            t0 = t0.max(da / (da - db));
        } else if db < 0.0 {
            t1 = t1.min(da / (da - db));
        }
    }
    (t0 < t1).then_some((t0, t1))
}

/// `a + t (b − a)` for packed vertices.
fn lerp(a: &[f32], b: &[f32], t: f32) -> [f32; VERTEX_FLOATS] {
    std::array::from_fn(|i| a[i] + t * (b[i] - a[i]))
}

/// Lines as quads, with stipple distances (see the module doc). Returns vertices and
/// triangle-list indices.
pub fn expand_lines(draw: &Draw, packed: &[f32], segments: &[Segment]) -> (Vec<f32>, Vec<u32>) {
    let line = &draw.state.line;
    let window = Window::new(draw);
    let width = line.width.clamp(0.0, MAX_POINT_SIZE);
    let mut out = Corners {
        packed,
        flat: draw.state.shade_model == ShadeModel::Flat,
        vertices: Vec::with_capacity(segments.len() * 4 * VERTEX_FLOATS),
        indices: Vec::with_capacity(segments.len() * 6),
    };
    let mut run_end = None;
    let mut distance = 0.0f32;
    for s in segments {
        if run_end != Some(s.a) {
            distance = 0.0;
        }
        run_end = Some(s.b);
        let (va, vb) = (vertex::get(packed, s.a), vertex::get(packed, s.b));
        let (ca, cb) = (window.clip(va), window.clip(vb));
        let Some((t0, t1)) = clip_near(ca, cb) else { continue };
        let (pa, pb) = (lerp(va, vb, t0), lerp(va, vb, t1));
        let (wa, wb) = (window.window(ca.lerp(cb, t0)), window.window(ca.lerp(cb, t1)));
        let d = wb - wa;
        let length = d.x.abs().max(d.y.abs());
        if length.is_nan() || length <= 0.0 {
            continue;
        }
        let x_major = d.x.abs() >= d.y.abs();
        let (offset, across, shift) = if line.smooth {
            let half = width * 0.5 + 0.5;
            (Vec2::new(-d.y, d.x).normalize() * half, half, 0.0)
        } else {
            // Section 3.4.2: the width rounded, at least one pixel, along the minor axis.
            let half = width.round().max(1.0) * 0.5;
            (if x_major { Vec2::new(0.0, half) } else { Vec2::new(half, 0.0) }, 0.0, ALIASED_SHIFT)
        };
        // Aliased lines (diamond exit, section 3.4.1) cover the pixel centres c with
        // a − ½ < c ≤ b − ½ along the major axis: the quad moves back by ½ (less a sliver, so
        // that a centre on its start edge stays out and one on its end edge in), and no centre
        // lies on an edge whether the vertices sit on pixel centres or on pixel corners.
        let major = if x_major { Vec2::new(d.x.signum(), 0.0) } else { Vec2::new(0.0, d.y.signum()) };
        let along = major * shift;
        let (da, db, fragments) = stipple_span(wa, wb, distance);
        distance += fragments;
        let corner = |o: Vec2, dist: f32, side: f32| [o.x * side + along.x, o.y * side + along.y, dist + shift, across * side];
        let c = [
            out.push(&pb, s.provoking, corner(offset, db, -1.0)),
            out.push(&pb, s.provoking, corner(offset, db, 1.0)),
            out.push(&pa, s.provoking, corner(offset, da, 1.0)),
            out.push(&pa, s.provoking, corner(offset, da, -1.0)),
        ];
        out.quad(c);
    }
    (out.vertices, out.indices)
}

/// How far aliased line quads move along their direction, in pixels: back by one half, less
/// 1/256 (see [`expand_lines`]).
const ALIASED_SHIFT: f32 = -0.5 + 1.0 / 256.0;

/// The stipple distances at the start and end of a segment from window position `a` to `b`
/// whose run has produced `count` fragments, and the fragments the segment adds. Along the
/// major axis, with diamond exit (section 3.4.1), the segment's fragments are the pixel centres
/// c with a < c + ½ ≤ b (mirrored when it runs backwards): the first is at ⌊a⌋ + ½, and there
/// are ⌊b⌋ − ⌊a⌋ of them. The distance is aligned so that fragment k of the run sits at k + ½,
/// the middle of its count, where interpolation error cannot move it to the next one.
fn stipple_span(a: Vec2, b: Vec2, count: f32) -> (f32, f32, f32) {
    let d = b - a;
    let (p0, p1) = if d.x.abs() >= d.y.abs() { (a.x, b.x) } else { (a.y, b.y) };
    let sign = if p1 >= p0 { 1.0 } else { -1.0 };
    let (m0, m1) = (p0 * sign, p1 * sign);
    let first_centre = m0.floor() + 0.5;
    let start = count + 0.5 - (first_centre - m0);
    (start, start + (m1 - m0), m1.floor() - m0.floor())
}

/// Points as quads of corners (±1, ±1); `points` pairs each vertex with its provoking vertex.
/// Points whose centre is outside the clip volume are dropped.
pub fn expand_points(draw: &Draw, packed: &[f32], points: &[(u32, u32)]) -> (Vec<f32>, Vec<u32>) {
    let window = Window::new(draw);
    let mut out = Corners {
        packed,
        flat: draw.state.shade_model == ShadeModel::Flat,
        vertices: Vec::with_capacity(points.len() * 4 * VERTEX_FLOATS),
        indices: Vec::with_capacity(points.len() * 6),
    };
    for &(i, provoking) in points {
        let v = vertex::get(packed, i);
        let c = window.clip(v);
        let inside = c.w > 0.0 && Vec3::new(c.x, c.y, c.z).abs().cmple(Vec3::splat(c.w)).all();
        if !inside {
            continue;
        }
        let corners = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]
            .map(|[x, y]| out.push(v, provoking, [x, y, 0.0, 0.0]));
        out.quad(corners);
    }
    (out.vertices, out.indices)
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::frame::state::{Line, RasterState};

    /// A draw with an identity transform and a 100×100 viewport, so object x, y in [−1, 1]
    /// map to window pixels `50 (x + 1)`.
    fn draw(topology: Topology, positions: &[[f32; 2]], indices: &[u32], state: RasterState) -> Draw {
        let mut d = Draw {
            topology,
            indices: indices.to_vec(),
            state: Arc::new(RasterState { viewport: [0, 0, 100, 100], ..state }),
            ..Draw::default()
        };
        d.vertices.position = positions.iter().map(|p| [p[0], p[1], 0.0, 1.0]).collect();
        d.vertices.color.values = (0..positions.len()).map(|i| [i as f32, 0.0, 0.0, 1.0]).collect();
        d
    }

    fn raster(part: &Part, corner: usize) -> [f32; 4] {
        let v = part.vertices.as_ref().expect("expanded");
        v[corner * VERTEX_FLOATS + vertex::RASTER..][..4].try_into().unwrap()
    }

    fn color(part: &Part, corner: usize) -> f32 {
        part.vertices.as_ref().expect("expanded")[corner * VERTEX_FLOATS + vertex::COLOR]
    }

    /// The indices of a part that lists them.
    fn list(part: &Part) -> &[u32] {
        match &part.indices {
            BatchIndices::List(list) => list,
            BatchIndices::Draw { .. } => panic!("the draw's own indices"),
        }
    }

    const CCW: [[f32; 2]; 3] = [[-0.5, -0.5], [0.5, -0.5], [0.0, 0.5]];

    #[test]
    fn fill_keeps_the_vertices_and_puts_the_provoking_vertex_first() {
        let d = draw(Topology::Triangles, &CCW, &[0, 1, 2, 0, 1, 9], RasterState { cull: Some(Face::Back), ..Default::default() });
        let parts = convert(&d, None);
        assert_eq!(parts.len(), 1);
        assert_eq!(parts[0].vertices, None);
        assert_eq!(parts[0].indices, BatchIndices::List(vec![2, 0, 1]), "the triangle with an out-of-range index is dropped");
        assert_eq!(parts[0].cull, Some(Face::Back), "the rasterizer culls");
        let d = Draw { indices: vec![0, 1, 2, 0, 2, 1], ..d };
        assert_eq!(convert(&d, None)[0].indices, BatchIndices::Draw { per: 3 }, "in range: rotated where they are uploaded");
    }

    #[test]
    fn facing_from_clip_space_winding() {
        let c = |p: [f32; 2], w: f32| Vec4::new(p[0] * w, p[1] * w, 0.0, w);
        assert!(is_front([c(CCW[0], 1.0), c(CCW[1], 1.0), c(CCW[2], 1.0)], Winding::Ccw));
        assert!(!is_front([c(CCW[0], 1.0), c(CCW[2], 1.0), c(CCW[1], 1.0)], Winding::Ccw));
        assert!(!is_front([c(CCW[0], 1.0), c(CCW[1], 1.0), c(CCW[2], 1.0)], Winding::Cw));
        // Homogeneous scale by w > 0 keeps the facing.
        assert!(is_front([c(CCW[0], 3.0), c(CCW[1], 0.5), c(CCW[2], 2.0)], Winding::Ccw));
    }

    #[test]
    fn line_mode_draws_only_boundary_edges_by_face() {
        // A quad as two triangles (0 1 2) and (0 2 3), diagonal 0–2 hidden; front faces in
        // line mode, back faces filled.
        let quad = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]];
        let state = RasterState { polygon_mode: [PolygonMode::Line, PolygonMode::Fill], ..Default::default() };
        let mut d = draw(Topology::Triangles, &quad, &[0, 1, 2, 0, 2, 3], state);
        d.edge_masks = vec![0b011, 0b110];
        let parts = convert(&d, None);
        assert_eq!(parts.len(), 1);
        let lines = &parts[0];
        assert_eq!((lines.primitive, lines.facing, lines.cull), (Primitive::Line, Facing::Front, None));
        assert_eq!(list(lines).len(), 4 * 6, "four edges, two triangles each");
        // The edges run 0→1→2→3→0 without a break: stipple distances keep counting, each
        // edge 50 pixels long (the quads start half a pixel back, less a sliver).
        let starts: Vec<f32> = (0..4).map(|e| raster(lines, 4 * e + 2)[2]).collect();
        assert_eq!(starts, [0.0, 50.0, 100.0, 150.0].map(|d| d + ALIASED_SHIFT));
        // Reversed winding: the same triangles are back faces and fill.
        let mut back = d.clone();
        back.indices = vec![0, 2, 1, 0, 3, 2];
        let parts = convert(&back, None);
        assert_eq!(parts.len(), 1);
        assert_eq!((parts[0].primitive, parts[0].facing, parts[0].vertices.is_none()), (Primitive::Triangle, Facing::Rasterizer, true));
    }

    #[test]
    fn culling_happens_before_the_mode_conversion() {
        let state = RasterState {
            polygon_mode: [PolygonMode::Point; 2],
            cull: Some(Face::Front),
            polygon_offset: crate::frame::state::PolygonOffset { point: true, ..Default::default() },
            ..Default::default()
        };
        let d = draw(Topology::Triangles, &CCW, &[0, 1, 2, 0, 2, 1], state);
        let parts = convert(&d, None);
        assert_eq!(parts.len(), 1);
        assert_eq!((parts[0].primitive, parts[0].facing, parts[0].polygon_offset), (Primitive::Point, Facing::Back, true));
        assert_eq!(list(&parts[0]).len(), 3 * 6, "three vertices as points");
    }

    #[test]
    fn aliased_lines_widen_along_the_minor_axis() {
        let state = RasterState { line: Line { width: 2.6, ..Line::default() }, ..Default::default() };
        // x-major: from (25, 50) to (75, 60) in window pixels.
        let d = draw(Topology::Lines, &[[-0.5, 0.0], [0.5, 0.2]], &[0, 1], state);
        let part = &convert(&d, None)[0];
        assert_eq!(list(part), [0, 1, 2, 0, 2, 3]);
        let r: Vec<[f32; 4]> = (0..4).map(|c| raster(part, c)).collect();
        // Width 3 across; moved back along x by half a pixel less a sliver (diamond exit).
        assert_eq!(r[0][..2], [ALIASED_SHIFT, -1.5], "width 3, vertical offset");
        assert_eq!(r[1][..2], [ALIASED_SHIFT, 1.5]);
        // End corners first (provoking vertex = the end), with the stipple distance 50.
        assert_eq!((r[0][2], r[2][2]), (50.0 + ALIASED_SHIFT, ALIASED_SHIFT));
        assert_eq!((color(part, 0), color(part, 2)), (1.0, 0.0), "copies of end and start");
    }

    #[test]
    fn smooth_lines_widen_perpendicular_with_a_fringe() {
        let state = RasterState { line: Line { width: 1.0, smooth: true, ..Line::default() }, ..Default::default() };
        // A 45° line.
        let d = draw(Topology::Lines, &[[0.0, 0.0], [0.5, 0.5]], &[0, 1], state);
        let part = &convert(&d, None)[0];
        let r = raster(part, 1);
        let h = 1.0 / 2f32.sqrt();
        assert!((r[0] + h).abs() < 1e-5 && (r[1] - h).abs() < 1e-5, "{r:?}");
        assert_eq!(r[3], 1.0, "distance across the line at the edge: half width + 0.5");
    }

    #[test]
    fn stipple_restarts_between_unconnected_segments() {
        let state = RasterState { line: Line { stipple: Some((1, 0xff)), ..Line::default() }, ..Default::default() };
        let p = [[-1.0, 0.0], [-0.5, 0.0], [0.0, 0.0], [0.5, 0.5]];
        // A strip 0→1→2 then a separate segment 2→3... which starts where the strip ended,
        // so it continues; then 0→1 again restarts.
        let d = draw(Topology::Lines, &p, &[0, 1, 1, 2, 2, 3, 0, 1], state);
        let part = &convert(&d, None)[0];
        let start = |s: usize| raster(part, 4 * s + 2)[2];
        assert_eq!([start(0), start(1), start(2), start(3)], [0.0, 25.0, 50.0, 0.0].map(|d| d + ALIASED_SHIFT));
        // Major-axis distance of the 45° segment: 25 pixels.
        assert_eq!(raster(part, 4 * 2)[2], 75.0 + ALIASED_SHIFT);
    }

    #[test]
    fn flat_lines_take_the_provoking_colour() {
        let state = RasterState { shade_model: ShadeModel::Flat, ..Default::default() };
        let d = draw(Topology::Lines, &[[0.0, 0.0], [0.5, 0.0]], &[0, 1], state);
        let part = &convert(&d, None)[0];
        assert!((0..4).all(|c| color(part, c) == 1.0));
    }

    #[test]
    fn lines_are_clipped_at_the_near_plane() {
        let mut d = draw(Topology::Lines, &[[0.0, 0.0], [0.5, 0.0]], &[0, 1], RasterState::default());
        // z = −3 is behind the near plane z = −w = −1; z = 1 is in front: the part from
        // z = −1 (t = 0.5) on remains, so its start is halfway.
        d.vertices.position[0][2] = -3.0;
        d.vertices.position[1][2] = 1.0;
        let part = &convert(&d, None)[0];
        let v = part.vertices.as_ref().unwrap();
        let start_x = v[2 * VERTEX_FLOATS + vertex::POSITION];
        assert!((start_x - 0.25).abs() < 1e-6, "{start_x}");
        d.vertices.position[1][2] = -2.0;
        assert!(list(&convert(&d, None)[0]).is_empty(), "wholly behind");
    }

    #[test]
    fn points_outside_the_clip_volume_are_dropped() {
        let d = draw(Topology::Points, &[[0.0, 0.0], [1.5, 0.0], [-0.99, 0.99]], &[0, 1, 2], RasterState::default());
        let part = &convert(&d, None)[0];
        assert_eq!(list(part).len(), 2 * 6);
        assert_eq!(raster(part, 2), [1.0, 1.0, 0.0, 0.0]);
        assert_eq!((part.primitive, part.facing), (Primitive::Point, Facing::Front));
    }

    #[test]
    fn stipple_spans_put_fragment_centres_mid_count() {
        // From pixel centre 0.5 to 24.5: fragments 0..24, the first centre at distance 0.5.
        let (a, b, n) = stipple_span(Vec2::new(0.5, 6.5), Vec2::new(24.5, 6.5), 0.0);
        assert_eq!((a, b, n), (0.5, 24.5, 24.0));
        // From the pixel edge 0.0: the first centre (0.5) is fragment 0 too.
        assert_eq!(stipple_span(Vec2::new(0.0, 16.5), Vec2::new(32.0, 16.5), 0.0), (0.0, 32.0, 32.0));
        // Continuing a run of 24 fragments upwards from (24.5, 6.5).
        let (a, _, n) = stipple_span(Vec2::new(24.5, 6.5), Vec2::new(24.5, 30.5), 24.0);
        assert_eq!((a, n), (24.5, 24.0));
        // Backwards: from 24.5 down to 0.5, 24 fragments, the first at 24.5.
        assert_eq!(stipple_span(Vec2::new(24.5, 2.5), Vec2::new(0.5, 2.5), 0.0), (0.5, 24.5, 24.0));
    }
}
