//! The fixed-function state of a context (lighting, fog, per-fragment operations,
//! rasterization, clip planes, hints, clear values, buffer selection, the attribute stack)
//! and its per-draw snapshot, [`RasterState`].
//!
//! Every change goes through `Context::fixed_mut`, which bumps a version counter; with the
//! capability version (`ctx.enables.version`) and the viewport, it keys a cached snapshot, so
//! [`Context::raster_snapshot`], called for every draw, only rebuilds after a change.

use std::sync::Arc;

use super::Context;
use super::attrib::AttribStack;
use super::buffers::BufferState;
use super::clear::ClearValues;
use super::fog::FogState;
use super::fragment::FragmentState;
use super::gl::{self, GLenum};
use super::hints::Hints;
use super::lighting::LightingState;
use super::limits::{MAX_CLIP_PLANES, MAX_LIGHTS};
use super::rasterization::RasterizationState;
use super::viewport::ViewportState;
use crate::frame::state::{Line, Lighting, Multisample, Point, PolygonOffset, RasterState};

/// Fixed-function state, grouped by the module that owns each part.
#[derive(Default)]
pub struct FixedState {
    /// Lights, materials, light model, shade model.
    pub lighting: LightingState,
    /// Fog.
    pub fog: FogState,
    /// Alpha, stencil, depth, blend, logic op, write masks.
    pub fragment: FragmentState,
    /// Points, lines, polygons, multisample coverage.
    pub raster: RasterizationState,
    /// Clear values.
    pub clear: ClearValues,
    /// Draw and read buffers.
    pub buffers: BufferState,
    /// User clip planes in eye space.
    pub clip_planes: [[f64; 4]; MAX_CLIP_PLANES],
    /// `glHint`.
    pub hints: Hints,
    /// `glPushAttrib` stack.
    pub(crate) attrib: AttribStack,
    /// Bumped by every change made through [`Context::fixed_mut`].
    version: u64,
    /// The last snapshot and the versions it was built from.
    snapshot: Option<SnapshotCache>,
}

/// A snapshot and what it was built from.
struct SnapshotCache {
    fixed: u64,
    enables: u64,
    viewport: ViewportState,
    state: Arc<RasterState>,
}

impl Context {
    /// The fixed-function state, for a change: invalidates the cached raster snapshot.
    pub(crate) fn fixed_mut(&mut self) -> &mut FixedState {
        self.fixed.version += 1;
        &mut self.fixed
    }

    /// The raster state for the next draw; the same `Arc` as last time when nothing it
    /// depends on changed.
    pub fn raster_snapshot(&mut self) -> Arc<RasterState> {
        let (fixed, enables, viewport) = (self.fixed.version, self.enables.version, self.viewport);
        // A bound framebuffer object's images can change without a state change (a texture
        // level respecified): its description is taken and compared each time.
        let framebuffer = self.draw_framebuffer().unwrap_or_default();
        if let Some(c) = &self.fixed.snapshot
            && c.fixed == fixed
            && c.enables == enables
            && c.viewport == viewport
            && c.state.framebuffer == framebuffer
        {
            return c.state.clone();
        }
        let state = Arc::new(self.build_raster_state(framebuffer));
        self.fixed.snapshot = Some(SnapshotCache { fixed, enables, viewport, state: state.clone() });
        state
    }

    /// Converts the current state to a [`RasterState`] drawing into `framebuffer`.
    fn build_raster_state(&self, framebuffer: crate::frame::Framebuffer) -> RasterState {
        let on = |cap: GLenum| self.enables.is_on(cap);
        let f = &self.fixed;
        let (fr, r, l) = (&f.fragment, &f.raster, &f.lighting);
        let draw_buffer = self.object_draw_buffer().unwrap_or(f.buffers.draw);
        let color_mask = if draw_buffer == gl::GL_NONE { [false; 4] } else { fr.color_mask };
        let mut state = RasterState {
            alpha_test: on(gl::GL_ALPHA_TEST).then_some(fr.alpha),
            blend: on(gl::GL_BLEND).then_some(fr.blend),
            logic_op: on(gl::GL_COLOR_LOGIC_OP).then_some(fr.logic_op),
            depth_test: on(gl::GL_DEPTH_TEST).then_some(fr.depth_func),
            depth_write: fr.depth_write,
            stencil: on(gl::GL_STENCIL_TEST).then(|| fr.stencil.for_draw(on(gl::GL_STENCIL_TEST_TWO_SIDE_EXT))),
            color_mask,
            draw_buffers: self.draw_buffers(),
            read_buffer: self.read_color_buffer(),
            cull: on(gl::GL_CULL_FACE).then_some(r.cull_face),
            front_face: r.front_face,
            polygon_mode: r.polygon_mode,
            polygon_offset: PolygonOffset {
                factor: r.offset.0,
                units: r.offset.1,
                fill: on(gl::GL_POLYGON_OFFSET_FILL),
                line: on(gl::GL_POLYGON_OFFSET_LINE),
                point: on(gl::GL_POLYGON_OFFSET_POINT),
            },
            polygon_stipple: on(gl::GL_POLYGON_STIPPLE).then_some(r.stipple),
            line: Line {
                width: r.line_width,
                stipple: on(gl::GL_LINE_STIPPLE).then_some(r.line_stipple),
                smooth: on(gl::GL_LINE_SMOOTH),
            },
            point: Point {
                // Sprites ignore GL_POINT_SMOOTH (OpenGL 2.0 section 3.3).
                smooth: on(gl::GL_POINT_SMOOTH) && !on(gl::GL_POINT_SPRITE),
                sprite: on(gl::GL_POINT_SPRITE).then_some(r.sprite),
                ..r.point
            },
            shade_model: l.shade_model,
            lighting: on(gl::GL_LIGHTING).then(|| Lighting {
                lights: (0..MAX_LIGHTS)
                    .filter(|&i| on(gl::GL_LIGHT0 + i as GLenum))
                    .map(|i| (i, l.lights[i]))
                    .collect(),
                model: l.model,
                front: l.materials[0],
                back: l.materials[1],
                color_material: on(gl::GL_COLOR_MATERIAL).then_some(l.color_material),
            }),
            color_sum: on(gl::GL_COLOR_SUM),
            fog: on(gl::GL_FOG).then_some(f.fog.fog),
            clip_planes: (0..MAX_CLIP_PLANES)
                .filter(|&i| on(gl::GL_CLIP_PLANE0 + i as GLenum))
                .map(|i| (i, f.clip_planes[i]))
                .collect(),
            scissor: on(gl::GL_SCISSOR_TEST).then_some(self.viewport.scissor),
            viewport: self.viewport.viewport,
            depth_range: self.viewport.depth_range,
            normalize: on(gl::GL_NORMALIZE),
            rescale_normal: on(gl::GL_RESCALE_NORMAL),
            dither: on(gl::GL_DITHER),
            multisample: Multisample {
                enabled: on(gl::GL_MULTISAMPLE),
                alpha_to_coverage: on(gl::GL_SAMPLE_ALPHA_TO_COVERAGE),
                alpha_to_one: on(gl::GL_SAMPLE_ALPHA_TO_ONE),
                coverage: on(gl::GL_SAMPLE_COVERAGE).then_some(r.sample_coverage),
            },
            framebuffer,
        };
        super::framebuffers::restrict_state(&mut state);
        state
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use crate::frame::state::{BlendFactor, CompareFunc, FogMode};
    use crate::translate::Context;
    use crate::translate::gl;

    #[test]
    fn snapshot_is_reused_until_something_changes() {
        let (mut ctx, _) = Context::with_recording();
        let a = ctx.raster_snapshot();
        let b = ctx.raster_snapshot();
        assert!(Arc::ptr_eq(&a, &b));
        assert_eq!(a.depth_test, None);

        ctx.glDepthFunc(gl::GL_LEQUAL);
        let c = ctx.raster_snapshot();
        assert!(!Arc::ptr_eq(&b, &c), "state change rebuilds");
        assert_eq!(c.depth_test, None, "depth test still off");
        ctx.glEnable(gl::GL_DEPTH_TEST);
        let d = ctx.raster_snapshot();
        assert_eq!(d.depth_test, Some(CompareFunc::LessEqual));
        ctx.glViewport(1, 2, 3, 4);
        let e = ctx.raster_snapshot();
        assert!(!Arc::ptr_eq(&d, &e), "viewport change rebuilds");
        assert_eq!(e.viewport, [1, 2, 3, 4]);
        // Queries do not invalidate.
        let _ = ctx.query(gl::GL_DEPTH_FUNC);
        assert!(Arc::ptr_eq(&e, &ctx.raster_snapshot()));
    }

    #[test]
    fn snapshot_converts_enabled_state() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glEnable(gl::GL_BLEND);
        ctx.glBlendFunc(gl::GL_SRC_ALPHA, gl::GL_ONE_MINUS_SRC_ALPHA);
        ctx.glEnable(gl::GL_LIGHTING);
        ctx.glEnable(gl::GL_LIGHT3);
        ctx.glTranslatef(0.0, 0.0, -5.0);
        unsafe { ctx.glLightfv(gl::GL_LIGHT3, gl::GL_POSITION, [0.0f32, 0.0, 0.0, 1.0].as_ptr()) };
        ctx.glEnable(gl::GL_FOG);
        ctx.glFogi(gl::GL_FOG_MODE, gl::GL_EXP2 as i32);
        ctx.glEnable(gl::GL_CLIP_PLANE1);
        ctx.glEnable(gl::GL_SCISSOR_TEST);
        ctx.glScissor(5, 6, 7, 8);
        let s = ctx.raster_snapshot();
        let blend = s.blend.unwrap();
        assert_eq!((blend.src_rgb, blend.dst_alpha), (BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha));
        let lighting = s.lighting.as_ref().unwrap();
        assert_eq!(lighting.lights.len(), 1);
        assert_eq!(lighting.lights[0].0, 3);
        assert_eq!(lighting.lights[0].1.position, [0.0, 0.0, -5.0, 1.0]);
        assert_eq!(s.fog.unwrap().mode, FogMode::Exp2);
        assert_eq!(s.clip_planes, vec![(1, [0.0; 4])]);
        assert_eq!(s.scissor, Some([5, 6, 7, 8]));
        assert!(s.dither);
    }
}
