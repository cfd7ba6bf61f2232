//! Where assembled primitives enter the frame: `Context::emit_batch` takes the state
//! snapshots of a batch and appends it to the frame, merging it into the previous draw when
//! nothing but the vertices differs. Programs that issue one `glBegin`/`glEnd` per quad thus
//! produce one draw per state change, not one per quad. In selection and feedback mode the
//! batch goes to [`super::render_mode`] instead of the frame.

use std::sync::Arc;

use glam::Mat4;

use super::Context;
use super::assemble::{Assembled, Primitive};
use super::enable::EnableState;
use super::immediate::Batch;
use super::texture::Target;
use super::lighting::without_tracked_material;
use super::limits::MAX_TEXTURE_UNITS;
use crate::frame::program::ProgramDraw;
use crate::frame::storage::{DrawStorage, StoragePool};
use crate::frame::{Attrib, Draw, DrawSource, Frame, RasterState, TextureRef, TextureUnit, Topology, Vertices};

/// A merged draw never grows past this many vertices, so its indices stay far from `u32`
/// overflow and the renderer's uploads stay bounded.
pub const MAX_MERGED_VERTICES: usize = 1 << 22;

/// Everything a batch is drawn with besides its vertices; batches with equal keys merge.
/// Built without allocation (but for the snapshots), so that a `glBegin`/`glEnd` per quad
/// stays cheap.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BatchKey {
    /// Topology.
    pub topology: Topology,
    /// Source.
    pub source: DrawSource,
    /// Modelview matrix.
    pub modelview: Mat4,
    /// Projection matrix.
    pub projection: Mat4,
    /// Texture matrix of each unit with a texture target enabled.
    pub texture_matrices: [Option<Mat4>; MAX_TEXTURE_UNITS],
    /// Raster state snapshot.
    pub state: Arc<RasterState>,
    /// Texture snapshot.
    pub textures: [Option<TextureRef>; MAX_TEXTURE_UNITS],
    /// Environment and coordinate generation of each unit with a texture target enabled.
    pub texture_units: [Option<TextureUnit>; MAX_TEXTURE_UNITS],
    /// The program in use, with its values.
    pub program: Option<Arc<ProgramDraw>>,
}

/// Which texture units have a texture target enabled, for the capability state it was
/// computed from (compared by value, so restoring saved state cannot make it stale).
#[derive(Default)]
pub struct TexturingCache {
    enables: Option<EnableState>,
    units: [bool; MAX_TEXTURE_UNITS],
}

impl TexturingCache {
    /// The units with a texture target enabled under `enables`.
    pub(crate) fn units(&mut self, enables: &EnableState) -> [bool; MAX_TEXTURE_UNITS] {
        if self.enables.as_ref() != Some(enables) {
            self.units = std::array::from_fn(|u| Target::ALL.iter().any(|t| enables.unit_on(u, t.gl())));
            self.enables = Some(enables.clone());
        }
        self.units
    }
}

impl Context {
    /// The single entry of assembled primitives into the frame: the primitive `primitive` made
    /// of `batch` (object space; vertex `order[k]`, or `k`, is its `k`-th vertex), decomposed
    /// into `assembled` (indices into the batch and, for triangles, edge masks), produced by
    /// `source`. In selection and feedback mode the primitive goes to
    /// [`Context::render_mode_batch`] instead and nothing enters the frame. Takes the matrices
    /// and the raster and texture snapshots now. Empty batches are dropped.
    pub(crate) fn emit_batch(
        &mut self,
        primitive: Primitive,
        batch: &mut Batch,
        order: Option<&[u32]>,
        assembled: &Assembled,
        source: DrawSource,
    ) {
        if self.render_mode_batch(primitive.to_gl(), batch, order) || assembled.indices.is_empty() {
            return;
        }
        if self.framebuffer_incomplete("draw") {
            return;
        }
        let state = self.raster_snapshot();
        self.enter_framebuffer(&state.framebuffer);
        if self.culled_entirely(&state, primitive.topology(), batch, assembled) {
            return;
        }
        let key = self.batch_key(primitive.topology(), source, state);
        push_batch(&mut self.frame, &mut self.storage, key, &mut batch.vertices, assembled);
        self.keep_frame_in_budget();
    }

    /// Whether the renderer would cull every triangle of the batch and nothing else needs
    /// them ([`super::cull`]).
    fn culled_entirely(&self, state: &RasterState, topology: Topology, batch: &Batch, assembled: &Assembled) -> bool {
        let Some(cull) = state.cull else { return false };
        if topology != Topology::Triangles || self.programs.current != 0 || self.sink.keeps_culled_triangles() {
            return false;
        }
        let mvp = self.transform.projection() * self.transform.modelview();
        super::cull::all_culled(cull, state.front_face, &mvp, &batch.vertices.position, &assembled.indices)
    }

    /// The source of immediate-mode geometry: the display list being executed, if any.
    pub(crate) fn immediate_source(&self) -> DrawSource {
        self.lists.executing_list().map_or(DrawSource::Immediate, DrawSource::List)
    }

    /// The source of vertex-array geometry.
    pub(crate) fn arrays_source(&self) -> DrawSource {
        self.lists.executing_list().map_or(DrawSource::Arrays, DrawSource::List)
    }

    /// The key of a batch emitted now with raster state `state`.
    fn batch_key(&mut self, topology: Topology, source: DrawSource, state: Arc<RasterState>) -> BatchKey {
        let units = self.immediate.texturing.units(&self.enables);
        let transform = &self.transform;
        BatchKey {
            topology,
            source,
            modelview: transform.modelview(),
            projection: transform.projection(),
            texture_matrices: std::array::from_fn(|u| units[u].then(|| transform.texture_matrix(u))),
            state,
            textures: self.texture_snapshot_of(units),
            texture_units: self.texture_units_snapshot(units),
            program: self.program_draw(),
        }
    }

    /// The environment and coordinate generation of the units in `units` (those with a
    /// texture target enabled; the others do not texture).
    /// Only those units' state is converted.
    pub(crate) fn texture_units_snapshot(&self, units: [bool; MAX_TEXTURE_UNITS]) -> [Option<TextureUnit>; MAX_TEXTURE_UNITS] {
        std::array::from_fn(|u| units[u].then(|| TextureUnit { env: self.texture.env[u].to_frame(), texgen: self.texgen_of(u) }))
    }
}

/// Whether two raster states draw alike: equal, or different only in the material properties
/// colour material takes from the vertex colours (each `glColor` with `GL_COLOR_MATERIAL` on
/// changes the material, which must not split the draws of a `glBegin`/`glEnd` per quad).
fn same_state(a: &Arc<RasterState>, b: &Arc<RasterState>) -> bool {
    if Arc::ptr_eq(a, b) || a == b {
        return true;
    }
    let (Some(la), Some(lb)) = (&a.lighting, &b.lighting) else { return false };
    la.color_material.is_some()
        && without_tracked_material(la) == without_tracked_material(lb)
        && RasterState { lighting: None, ..(**a).clone() } == RasterState { lighting: None, ..(**b).clone() }
}

/// Whether two draws run the same program with the same values.
fn same_program(a: &Option<Arc<ProgramDraw>>, b: &Option<Arc<ProgramDraw>>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => Arc::ptr_eq(a, b) || a == b,
        _ => false,
    }
}

/// Whether a batch with `key` can be appended to `last` (`extra` more vertices).
fn mergeable(last: &Draw, key: &BatchKey, extra: usize) -> bool {
    last.topology == key.topology
        && last.source == key.source
        && last.modelview == key.modelview
        && last.projection == key.projection
        && last.texture_matrices == key.texture_matrices
        && same_state(&last.state, &key.state)
        && last.textures[..] == key.textures[..]
        && last.texture_units == key.texture_units
        && same_program(&last.program, &key.program)
        && last.vertices.len() + extra <= MAX_MERGED_VERTICES
}

/// Appends a batch to `frame`: into its last draw when `mergeable` and no clear or pixel
/// operation came after that draw, else as a new draw, in storage taken from `storage`.
/// `vertices` are copied into a draw they are merged into. A new draw whose spare storage is
/// no larger than theirs takes them whole instead, and `vertices` is left empty in that
/// storage (the same texture units): the larger storage goes to the draw either way, where
/// batches merged after this one grow it.
pub fn push_batch(frame: &mut Frame, storage: &mut StoragePool, key: BatchKey, vertices: &mut Vertices, assembled: &Assembled) {
    // A clear or pixel operation after the last draw must stay between it and this batch.
    let cleared_since = frame.clears.last().is_some_and(|c| c.before_draw >= frame.draws.len());
    let pixels_since = frame.pixels.last().is_some_and(|p| p.before_draw >= frame.draws.len());
    let merge = !cleared_since && !pixels_since && frame.draws.last().is_some_and(|last| mergeable(last, &key, vertices.len()));
    if !merge {
        let mut spare: DrawStorage = storage.take();
        spare.texture_matrices.extend_from_slice(&key.texture_matrices);
        spare.textures.extend(key.textures);
        spare.texture_units.extend_from_slice(&key.texture_units);
        frame.draws.push(Draw {
            vertices: spare.vertices,
            indices: spare.indices,
            edge_masks: spare.edge_masks,
            topology: key.topology,
            source: key.source,
            modelview: key.modelview,
            projection: key.projection,
            texture_matrices: spare.texture_matrices,
            state: key.state,
            textures: spare.textures,
            texture_units: spare.texture_units,
            program: key.program,
            // Not `..Draw::default()`, which would allocate a default raster state per draw.
            vertex_count: 0,
            class: Default::default(),
            instance: None,
            layer: None,
        });
    }
    let draw = frame.draws.last_mut().expect("a draw was just pushed or merged into");
    let base = draw.vertices.len() as u32;
    if base == 0 && vertices.position.capacity() >= draw.vertices.position.capacity() {
        // Appending to no vertex gives `vertices` (Vertices::append): taken without a copy.
        let units = vertices.texcoords.len();
        std::mem::swap(&mut draw.vertices, vertices);
        vertices.clear();
        vertices.texcoords.resize(units, Attrib::default());
    } else {
        draw.vertices.append(vertices);
    }
    draw.vertex_count = draw.vertices.len();
    draw.indices.extend(assembled.indices.iter().map(|&i| i + base));
    draw.edge_masks.extend_from_slice(&assembled.edge_masks);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Clear;
    use crate::translate::{dispatch, gl};
    use crate::translate::immediate::{Batch, CurrentAttribs, bits};

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
        assert_eq!(draw[0].vertex_count, 4000);
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
        assert_eq!(draws[0].vertex_count, 8);
        assert_eq!(draws[1].modelview.w_axis.x, 1.0);
        assert_eq!(draws[2].topology, Topology::Lines);
        assert_eq!(draws[3].topology, Topology::Lines);
        ctx.glEnable(gl::GL_TEXTURE_2D);
        quad(&mut ctx, 0.0);
        assert_eq!(ctx.frame.draws.len(), 5, "enabling a texture target adds its matrix");
        assert!(ctx.frame.draws[4].texture_matrices[0].is_some());
    }

    #[test]
    fn texture_environment_splits_draws_and_reaches_the_frame() {
        use crate::frame::texture::{EnvMode, TexGenMode};
        let (mut ctx, _) = Context::with_recording();
        ctx.glEnable(gl::GL_TEXTURE_2D);
        quad(&mut ctx, 0.0);
        quad(&mut ctx, 1.0);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_REPLACE as i32);
        quad(&mut ctx, 2.0);
        ctx.glTexGeni(gl::GL_S, gl::GL_TEXTURE_GEN_MODE, gl::GL_SPHERE_MAP as i32);
        ctx.glEnable(gl::GL_TEXTURE_GEN_S);
        quad(&mut ctx, 3.0);
        ctx.glDisable(gl::GL_TEXTURE_2D);
        quad(&mut ctx, 4.0);
        ctx.glTexEnvi(gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_DECAL as i32);
        quad(&mut ctx, 5.0);
        let draws = &ctx.frame.draws;
        assert_eq!(draws.len(), 4, "an environment of a unit that does not texture does not split");
        assert_eq!(draws[0].vertex_count, 8);
        let unit0 = |d: &Draw| d.texture_units[0];
        assert_eq!(unit0(&draws[0]).map(|u| (u.env.mode, u.texgen[0])), Some((EnvMode::Modulate, None)));
        assert_eq!(unit0(&draws[1]).map(|u| u.env.mode), Some(EnvMode::Replace));
        assert_eq!(unit0(&draws[2]).map(|u| u.texgen[0]), Some(Some(TexGenMode::SphereMap)));
        assert_eq!(draws[2].texture_units[1], None);
        assert_eq!(draws[3].texture_units, vec![None; MAX_TEXTURE_UNITS]);
    }

    #[test]
    fn colour_material_changes_merge_other_material_changes_split() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glEnable(gl::GL_LIGHTING);
        ctx.glEnable(gl::GL_COLOR_MATERIAL);
        for i in 0..3 {
            unsafe { dispatch::glColor3f(&mut ctx, i as f32 / 2.0, 0.0, 0.0) };
            quad(&mut ctx, i as f32);
        }
        assert_eq!(ctx.frame.draws.len(), 1, "the tracked material comes from the vertex colours");
        unsafe { dispatch::glMaterialfv(&mut ctx, gl::GL_FRONT, gl::GL_SPECULAR, [1.0; 4].as_ptr()) };
        quad(&mut ctx, 3.0);
        assert_eq!(ctx.frame.draws.len(), 2, "an untracked property splits");
        let lighting = ctx.frame.draws[1].state.lighting.as_ref().map(|l| l.front.specular);
        assert_eq!(lighting, Some([1.0; 4]));
        ctx.glDisable(gl::GL_COLOR_MATERIAL);
        quad(&mut ctx, 4.0);
        unsafe { dispatch::glMaterialfv(&mut ctx, gl::GL_FRONT, gl::GL_DIFFUSE, [0.5; 4].as_ptr()) };
        quad(&mut ctx, 5.0);
        assert_eq!(ctx.frame.draws.len(), 4, "without colour material the diffuse colour splits");
    }

    #[test]
    fn push_batch_offsets_indices_and_keeps_masks() {
        let mut frame = Frame::default();
        let mut batch = Batch::default();
        let current = CurrentAttribs::default();
        for i in 0..3 {
            batch.push([i as f32, 0.0, 0.0, 1.0], &current, 0);
        }
        let a = Assembled { indices: vec![0, 1, 2], edge_masks: vec![0b101] };
        let mut storage = StoragePool::default();
        push_batch(&mut frame, &mut storage, BatchKey::default(), &mut batch.vertices.clone(), &a);
        push_batch(&mut frame, &mut storage, BatchKey::default(), &mut batch.vertices.clone(), &a);
        assert_eq!(frame.draws.len(), 1);
        assert_eq!(frame.draws[0].indices, vec![0, 1, 2, 3, 4, 5]);
        assert_eq!(frame.draws[0].edge_masks, vec![0b101, 0b101]);
        assert_eq!(frame.draws[0].vertices.position.iter().map(|p| p[0]).collect::<Vec<_>>(), [0.0, 1.0, 2.0, 0.0, 1.0, 2.0]);
        let other = BatchKey { source: DrawSource::List(3), ..BatchKey::default() };
        push_batch(&mut frame, &mut storage, other, &mut batch.vertices.clone(), &a);
        assert_eq!(frame.draws.len(), 2, "another source starts another draw");
    }

    #[test]
    fn a_new_draw_takes_the_batch_s_vertices_unless_its_spare_storage_is_larger() {
        let mut batch = Batch::default();
        let current = CurrentAttribs { color: [0.5, 0.25, 1.0, 1.0], ..CurrentAttribs::default() };
        for i in 0..3 {
            batch.push([i as f32, 0.0, 0.0, 1.0], &CurrentAttribs { texcoords: [[i as f32, 1.0, 0.0, 1.0]; MAX_TEXTURE_UNITS], ..current }, bits::ALL);
        }
        let a = Assembled { indices: vec![0, 1, 2], edge_masks: vec![0b111] };
        let (mut frame, mut storage) = (Frame::default(), StoragePool::default());
        let mut vertices = batch.vertices.clone();
        let (held, units) = (vertices.position.as_ptr(), vertices.texcoords.len());
        push_batch(&mut frame, &mut storage, BatchKey::default(), &mut vertices, &a);
        let draw = &frame.draws[0];
        assert_eq!(draw.vertices, batch.vertices, "the draw holds what appending would give");
        assert_eq!(draw.vertices.position.as_ptr(), held, "not copied");
        assert!(vertices.is_empty() && vertices.texcoords.len() == units, "the batch is left empty with its units");
        // A larger spare storage goes to the draw, and the batch is copied into it.
        let mut spare = StoragePool::default();
        spare.keep_frame(Frame { draws: vec![Draw { vertices: Vertices { position: Vec::with_capacity(1000), ..Vertices::default() }, ..Draw::default() }], ..Frame::default() });
        let mut frame = Frame::default();
        let mut vertices = batch.vertices.clone();
        push_batch(&mut frame, &mut spare, BatchKey::default(), &mut vertices, &a);
        assert_eq!(frame.draws[0].vertices, batch.vertices);
        assert!(frame.draws[0].vertices.position.capacity() >= 1000);
        assert_eq!(vertices, batch.vertices, "copied, not taken");
    }

    #[test]
    fn new_draws_fill_the_storage_the_sink_gave_back() {
        use crate::frame::NullSink;
        use crate::translate::context::ContextConfig;
        let mut ctx = Context::new(ContextConfig { share: None, sink: Box::new(NullSink::default()) });
        for i in 0..1000 {
            quad(&mut ctx, i as f32);
        }
        ctx.end_frame();
        assert_eq!(ctx.storage.len(), 1, "the one draw's storage came back");
        assert!(ctx.storage.bytes() >= 4000 * (16 + 16) + 6000 * 4 + 2000, "{} bytes", ctx.storage.bytes());
        quad(&mut ctx, 0.0);
        assert!(ctx.storage.is_empty());
        let draw = &ctx.frame.draws[0];
        assert!(draw.vertices.position.capacity() >= 4000 && draw.indices.capacity() >= 6000);
        assert_eq!((draw.vertex_count, draw.indices.len(), draw.edge_masks.len()), (4, 6, 2));
        assert_eq!(draw.vertices.texcoords[0].get(2), Some([1.0, 1.0, 0.0, 1.0]));
    }
}
