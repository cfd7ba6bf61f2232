//! Batches of draws whose vertex stage is an OpenGL 2.0 program's (the `translate::glsl`
//! contract): the CPU does not know where the program places vertices, so nothing is expanded
//! or culled here. Points and lines keep their topology (the vertex stage writes
//! `gl_PointSize`, the renderer sets the line width); triangles are drawn with the polygon
//! mode of each face (Vulkan's `polygonMode`, one per pipeline: when the two faces differ,
//! one batch per face, the other face culled). Vulkan's polygon mode `LINE` draws every edge
//! of every triangle, diagonals of decomposed quads and polygons and edges whose edge flag is
//! false included; when neither facing nor polygon offset can matter (both faces `GL_LINE`,
//! no culling, no `GL_POLYGON_OFFSET_LINE`, no two-sided colours), the boundary edges
//! ([`Draw::edge_masks`]) are drawn as lines instead, which is exact but for flat shading (an
//! edge takes its first vertex's values, not the polygon's provoking vertex's).
//!
//! The shader key is the fixed-function one of a filled triangle (`v_raster` is only
//! meaningful for primitives the CPU expanded): [`shader_interface::PRIMITIVE`] triangle, no
//! [`shader_interface::SMOOTH`] or [`shader_interface::LINE_STIPPLE`], the polygon stipple only for filled polygons,
//! and [`shader_interface::TWO_SIDE`] from `GL_VERTEX_PROGRAM_TWO_SIDE`.

use super::key::{self, Facing, Primitive};
use super::{Batch, BatchIndices, BatchVertices, shader_interface, vertex};
use crate::render::shader_abi::Field;
use crate::frame::program::ProgramDraw;
use crate::frame::state::{Face, PolygonMode};
use crate::frame::{Draw, Topology};

/// The batches of `draw` run with `program`'s vertex stage; they draw the draw's own
/// vertices.
pub fn prepare(draw: &Draw, program: &ProgramDraw) -> Vec<Batch> {
    let per = match draw.topology {
        Topology::Triangles => 3,
        Topology::Lines => 2,
        Topology::Points => 1,
    };
    // The provoking vertex (last in a Draw) goes first, as Vulkan's default says.
    let indices = BatchIndices::rotated(draw, per);
    let generic = vertex::pack_generic(draw, &vertex::generic_indices(&program.program));
    let s = &draw.state;
    let batch = |topology: Topology, indices: BatchIndices, mode: PolygonMode, cull: Option<Face>, polygon_offset: bool| {
        let facing = if topology == Topology::Triangles { Facing::Rasterizer } else { Facing::Front };
        let mut shader = key::shader_key(draw, Primitive::Triangle, facing);
        let general = &mut shader.words[key::GENERAL];
        clear(general, shader_interface::TWO_SIDE);
        shader_interface::TWO_SIDE.set(general, program.two_side as u32);
        if topology != Topology::Triangles || mode != PolygonMode::Fill {
            clear(general, shader_interface::POLYGON_STIPPLE);
        }
        Batch {
            topology,
            polygon_mode: mode,
            vertices: BatchVertices::Draw,
            generic: generic.clone(),
            indices,
            shader,
            cull,
            facing,
            polygon_offset,
        }
    };
    if draw.topology != Topology::Triangles {
        return vec![batch(draw.topology, indices, PolygonMode::Fill, None, false)];
    }
    let hidden_edges = draw.edge_masks.iter().any(|&m| m & 7 != 7);
    if hidden_edges && s.polygon_mode == [PolygonMode::Line; 2] && s.cull.is_none() && !s.polygon_offset.line && !program.two_side {
        return vec![batch(Topology::Lines, BatchIndices::List(boundary_edges(draw)), PolygonMode::Fill, None, false)];
    }
    let triangles = |mode, cull, offset| batch(Topology::Triangles, indices.clone(), mode, cull, offset);
    let offset = |mode| match mode {
        PolygonMode::Fill => s.polygon_offset.fill,
        PolygonMode::Line => s.polygon_offset.line,
        PolygonMode::Point => s.polygon_offset.point,
    };
    let culled = |face: Face| s.cull.is_some_and(|c| c == face || c == Face::FrontAndBack);
    let [front, back] = s.polygon_mode;
    match (culled(Face::Front), culled(Face::Back)) {
        (true, true) => Vec::new(),
        (true, false) => vec![triangles(back, s.cull, offset(back))],
        (false, true) => vec![triangles(front, s.cull, offset(front))],
        (false, false) if front == back => vec![triangles(front, None, offset(front))],
        (false, false) => vec![triangles(front, Some(Face::Back), offset(front)), triangles(back, Some(Face::Front), offset(back))],
    }
}

/// Line-list indices of the boundary edges of the draw's triangles (bit `k` of a triangle's
/// edge mask: the edge from its index `k` to `k + 1`), skipping triangles with an index out
/// of range.
fn boundary_edges(draw: &Draw) -> Vec<u32> {
    let count = draw.vertices.len() as u32;
    let mut out = Vec::new();
    for (t, &mask) in draw.indices.chunks_exact(3).zip(&draw.edge_masks) {
        if t.iter().any(|&i| i >= count) {
            continue;
        }
        for k in 0..3 {
            if mask & (1 << k) != 0 {
                out.extend([t[k], t[(k + 1) % 3]]);
            }
        }
    }
    out
}

/// Clears `field` in `word`.
fn clear(word: &mut u32, field: Field) {
    *word &= !(((1 << field.bits) - 1) << field.shift);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::RasterState;
    use crate::frame::program::ShaderProgram;
    use crate::frame::state::Line;
    use std::sync::Arc;

    fn program_draw(two_side: bool) -> ProgramDraw {
        let program = ShaderProgram { id: 7, vertex: Some(Arc::from(vec![0u32])), fragment: None, samplers: Vec::new(), attributes: vec![1] };
        ProgramDraw { program: Arc::new(program), builtins: Arc::from(vec![]), uniforms: Arc::from(vec![]), textures: Vec::new(), point_size_from_shader: false, two_side }
    }

    /// The indices `b` uploads.
    fn written(b: &Batch, d: &Draw) -> Vec<u32> {
        let mut out = vec![0; b.indices.len(d)];
        b.indices.write(d, &mut out);
        out
    }

    fn draw(topology: Topology, indices: Vec<u32>, state: RasterState) -> Draw {
        let mut d = Draw { topology, indices, state: Arc::new(state), ..Draw::default() };
        d.vertices.position = vec![[0.0; 4]; 4];
        d
    }

    #[test]
    fn lines_stay_lines_with_a_triangle_key() {
        let state = RasterState { line: Line { smooth: true, stipple: Some((1, 0xf0f0)), ..Line::default() }, ..RasterState::default() };
        let d = draw(Topology::Lines, vec![0, 1, 2, 3], state);
        let p = program_draw(true);
        let batches = prepare(&d, &p);
        assert_eq!(batches.len(), 1);
        let b = &batches[0];
        assert_eq!((b.topology, b.polygon_mode, b.cull), (Topology::Lines, PolygonMode::Fill, None));
        assert_eq!(written(b, &d), vec![1, 0, 3, 2], "provoking vertex first");
        assert_eq!(b.generic.len(), 4 * 4);
        let general = b.shader.words[key::GENERAL];
        assert_eq!(shader_interface::PRIMITIVE.get(general), Primitive::Triangle as u32);
        assert_eq!((shader_interface::SMOOTH.get(general), shader_interface::LINE_STIPPLE.get(general)), (0, 0));
        assert_eq!((shader_interface::TWO_SIDE.get(general), shader_interface::FACING.get(general)), (1, Facing::Front as u32));
    }

    #[test]
    fn faces_with_different_modes_get_a_batch_each() {
        let mut state = RasterState { polygon_mode: [PolygonMode::Line, PolygonMode::Point], ..RasterState::default() };
        state.polygon_offset.point = true;
        state.polygon_stipple = Some([0; 32]);
        let d = draw(Topology::Triangles, vec![0, 1, 2], state.clone());
        let batches = prepare(&d, &program_draw(false));
        let summary: Vec<_> = batches.iter().map(|b| (b.polygon_mode, b.cull, b.polygon_offset)).collect();
        assert_eq!(summary, vec![(PolygonMode::Line, Some(Face::Back), false), (PolygonMode::Point, Some(Face::Front), true)]);
        assert_eq!(written(&batches[0], &d), vec![2, 0, 1]);
        assert!(batches.iter().all(|b| shader_interface::POLYGON_STIPPLE.get(b.shader.words[key::GENERAL]) == 0));
        let mut quad = draw(Topology::Triangles, vec![0, 1, 2, 0, 2, 3], RasterState { polygon_mode: [PolygonMode::Line; 2], ..RasterState::default() });
        quad.edge_masks = vec![0b011, 0b110];
        let edges = prepare(&quad, &program_draw(false));
        assert_eq!((edges.len(), edges[0].topology), (1, Topology::Lines));
        assert_eq!(edges[0].indices, BatchIndices::List(vec![0, 1, 1, 2, 2, 3, 3, 0]), "the quad's outline, no diagonal");
        let lined = prepare(&quad, &program_draw(true));
        assert_eq!((lined[0].topology, lined[0].polygon_mode), (Topology::Triangles, PolygonMode::Line), "two-sided colours need the facing");
        state.cull = Some(Face::Back);
        let d = draw(Topology::Triangles, vec![0, 1, 2], state.clone());
        let summary: Vec<_> = prepare(&d, &program_draw(false)).iter().map(|b| (b.polygon_mode, b.cull)).collect();
        assert_eq!(summary, vec![(PolygonMode::Line, Some(Face::Back))]);
        state.cull = Some(Face::FrontAndBack);
        let d = draw(Topology::Triangles, vec![0, 1, 2], state);
        assert!(prepare(&d, &program_draw(false)).is_empty());
    }
}
