//! Where assembled primitives enter the frame: [`Context::emit_batch`] takes the state
//! snapshots of a batch and appends it to the frame, merging it into the previous draw when
//! nothing but the vertices differs. Programs that issue one `glBegin`/`glEnd` per quad thus
//! produce one draw per state change, not one per quad.

use std::sync::Arc;

use super::Context;
use super::assemble::Assembled;
use super::gl;
use super::limits::MAX_TEXTURE_UNITS;
use crate::frame::{Draw, DrawSource, Frame, Topology, Vertices};

/// A merged draw never grows past this many vertices, so its indices stay far from `u32`
/// overflow and the renderer's uploads stay bounded.
pub const MAX_MERGED_VERTICES: usize = 1 << 22;

/// Texture targets whose enable makes a unit use its texture matrix.
const TEXTURE_TARGETS: [gl::GLenum; 4] =
    [gl::GL_TEXTURE_1D, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_3D, gl::GL_TEXTURE_CUBE_MAP];

impl Context {
    /// The single entry of assembled primitives into the frame: `vertices` in object space,
    /// decomposed into `assembled` (indices into `vertices` and, for triangles, edge masks)
    /// with the given `topology`, produced by `source`. Takes the matrices and the raster and
    /// texture snapshots now. Empty batches are dropped.
    pub(crate) fn emit_batch(
        &mut self,
        topology: Topology,
        vertices: &Vertices,
        assembled: &Assembled,
        source: DrawSource,
    ) {
        if assembled.indices.is_empty() {
            return;
        }
        let header = self.draw_header(topology, source);
        push_batch(&mut self.frame, header, vertices, assembled);
    }

    /// The source of immediate-mode geometry: the display list being executed, if any.
    pub(crate) fn immediate_source(&self) -> DrawSource {
        self.lists.executing_list().map_or(DrawSource::Immediate, DrawSource::List)
    }

    /// The source of vertex-array geometry.
    pub(crate) fn arrays_source(&self) -> DrawSource {
        self.lists.executing_list().map_or(DrawSource::Arrays, DrawSource::List)
    }

    /// A draw without vertices carrying everything else a batch is drawn with.
    fn draw_header(&mut self, topology: Topology, source: DrawSource) -> Draw {
        let transform = &self.transform;
        let texture_matrices = (0..MAX_TEXTURE_UNITS)
            .map(|unit| {
                TEXTURE_TARGETS
                    .iter()
                    .any(|&t| self.enables.unit_on(unit, t))
                    .then(|| transform.texture_matrix(unit))
            })
            .collect();
        Draw {
            topology,
            modelview: transform.modelview(),
            projection: transform.projection(),
            texture_matrices,
            source,
            state: self.raster_snapshot(),
            textures: self.texture_snapshot(),
            ..Draw::default()
        }
    }
}

/// Whether a batch with `header` can be appended to `last` (`extra` more vertices).
fn mergeable(last: &Draw, header: &Draw, extra: usize) -> bool {
    last.topology == header.topology
        && last.source == header.source
        && last.modelview == header.modelview
        && last.projection == header.projection
        && last.texture_matrices == header.texture_matrices
        && (Arc::ptr_eq(&last.state, &header.state) || last.state == header.state)
        && last.textures == header.textures
        && last.vertices.len() + extra <= MAX_MERGED_VERTICES
}

/// Appends a batch to `frame`: into its last draw when [`mergeable`] and no clear came after
/// that draw, else as a new draw made from `header`.
pub fn push_batch(frame: &mut Frame, header: Draw, vertices: &Vertices, assembled: &Assembled) {
    let cleared_since = frame.clears.last().is_some_and(|c| c.before_draw >= frame.draws.len());
    let merge = !cleared_since && frame.draws.last().is_some_and(|last| mergeable(last, &header, vertices.len()));
    if !merge {
        frame.draws.push(header);
    }
    let draw = frame.draws.last_mut().expect("a draw was just pushed or merged into");
    let base = draw.vertices.len() as u32;
    draw.vertices.append(vertices);
    draw.indices.extend(assembled.indices.iter().map(|&i| i + base));
    draw.edge_masks.extend_from_slice(&assembled.edge_masks);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Clear;
    use crate::translate::dispatch;

    fn quad(ctx: &mut Context, x: f32) {
        unsafe {
            dispatch::glBegin(ctx, gl::GL_QUADS);
            dispatch::glTexCoord2f(ctx, 0.0, 0.0);
            dispatch::glVertex2f(ctx, x, 0.0);
            dispatch::glTexCoord2f(ctx, 1.0, 0.0);
            dispatch::glVertex2f(ctx, x + 1.0, 0.0);
            dispatch::glTexCoord2f(ctx, 1.0, 1.0);
            dispatch::glVertex2f(ctx, x + 1.0, 1.0);
            dispatch::glTexCoord2f(ctx, 0.0, 1.0);
            dispatch::glVertex2f(ctx, x, 1.0);
            dispatch::glEnd(ctx);
        }
    }

    #[test]
    fn thousand_quads_merge_into_one_draw() {
        let (mut ctx, sink) = Context::with_recording();
        for i in 0..1000 {
            quad(&mut ctx, i as f32);
        }
        ctx.end_frame();
        let frames = sink.frames.lock();
        let draw = &frames[0].draws;
        assert_eq!(draw.len(), 1);
        assert_eq!(draw[0].vertex_count(), 4000);
        assert_eq!(draw[0].indices.len(), 6000);
        assert_eq!(draw[0].edge_masks.len(), 2000);
        assert_eq!(draw[0].indices[6 * 999..6 * 999 + 3], [3996, 3997, 3999]);
        assert_eq!(draw[0].vertices.position[3999], [999.0, 1.0, 0.0, 1.0]);
        assert_eq!(draw[0].vertices.texcoords[0].get(3998), Some([1.0, 1.0, 0.0, 1.0]));
    }

    #[test]
    fn state_topology_matrix_and_clear_split_draws() {
        let (mut ctx, _) = Context::with_recording();
        quad(&mut ctx, 0.0);
        quad(&mut ctx, 1.0);
        ctx.glTranslatef(1.0, 0.0, 0.0);
        quad(&mut ctx, 2.0);
        unsafe {
            dispatch::glBegin(&mut ctx, gl::GL_LINES);
            dispatch::glVertex2f(&mut ctx, 0.0, 0.0);
            dispatch::glVertex2f(&mut ctx, 1.0, 0.0);
            dispatch::glEnd(&mut ctx);
        }
        let before = ctx.frame.draws.len();
        ctx.frame.clears.push(Clear { before_draw: before, ..Clear::default() });
        unsafe {
            dispatch::glBegin(&mut ctx, gl::GL_LINES);
            dispatch::glVertex2f(&mut ctx, 0.0, 0.0);
            dispatch::glVertex2f(&mut ctx, 1.0, 0.0);
            dispatch::glEnd(&mut ctx);
        }
        let draws = &ctx.frame.draws;
        assert_eq!(draws.len(), 4);
        assert_eq!(draws[0].vertex_count(), 8);
        assert_eq!(draws[1].modelview.w_axis.x, 1.0);
        assert_eq!(draws[2].topology, Topology::Lines);
        assert_eq!(draws[3].topology, Topology::Lines);
        ctx.glEnable(gl::GL_TEXTURE_2D);
        quad(&mut ctx, 0.0);
        assert_eq!(ctx.frame.draws.len(), 5, "enabling a texture target adds its matrix");
        assert!(ctx.frame.draws[4].texture_matrices[0].is_some());
    }

    #[test]
    fn push_batch_offsets_indices_and_keeps_masks() {
        let mut frame = Frame::default();
        let mut v = Vertices::with_units(1);
        let values = crate::translate::immediate::CurrentAttribs::default();
        for i in 0..3 {
            v.push([i as f32, 0.0, 0.0, 1.0], &values.values());
        }
        let a = Assembled { indices: vec![0, 1, 2], edge_masks: vec![0b101] };
        push_batch(&mut frame, Draw::default(), &v, &a);
        push_batch(&mut frame, Draw::default(), &v, &a);
        assert_eq!(frame.draws.len(), 1);
        assert_eq!(frame.draws[0].indices, vec![0, 1, 2, 3, 4, 5]);
        assert_eq!(frame.draws[0].edge_masks, vec![0b101, 0b101]);
        let other = Draw { source: DrawSource::List(3), ..Draw::default() };
        push_batch(&mut frame, other, &v, &a);
        assert_eq!(frame.draws.len(), 2, "another source starts another draw");
    }
}
