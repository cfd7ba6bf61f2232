//! Render modes (OpenGL 1.5 chapter 5.2 and 5.3): `glRenderMode`, selection and feedback,
//! computed on the CPU.
//!
//! In `GL_SELECT` and `GL_FEEDBACK` mode nothing is drawn: the vertex pipeline hands each
//! primitive ([`batch`]) to [`Context::render_mode_primitive`], which transforms, clips and rasterizes
//! it as far as selection and feedback need ([`pipeline`]), then records a hit ([`select`])
//! or writes tokens ([`feedback`]). Pixel rectangles and raster positions come through
//! [`Context::render_mode_raster_event`].
//!
//! Fed-back colours are lit and texture coordinates generated on the CPU by the fixed-function
//! vertex stage ([`Context::fixed_vertex`]), and the texture matrix of unit 0 is applied here.
//! Points, lines and front-facing polygons report the front colours; polygons whose window-space
//! facing is back report the back colours, which differ only with two-sided lighting (section
//! 2.14.1).

pub mod batch;
pub mod buffer;
pub mod feedback;
pub mod pipeline;
pub mod select;

pub use pipeline::{CpuPrimitive, CpuVertex, RasterRules, WindowVertex};

use super::Context;
use super::get::Value;
use super::gl::{self, GLenum, GLint};
use super::limits::MAX_NAME_STACK_DEPTH;
use feedback::FeedbackState;
use select::SelectState;

/// `GL_RENDER_MODE`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RenderMode {
    /// `GL_RENDER`: primitives are drawn.
    #[default]
    Render,
    /// `GL_SELECT`: primitives set the hit flag.
    Select,
    /// `GL_FEEDBACK`: primitives are written to the feedback buffer.
    Feedback,
}

/// Render-mode state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderModeState {
    /// The current mode.
    pub mode: RenderMode,
    /// Selection.
    pub select: SelectState,
    /// Feedback.
    pub feedback: FeedbackState,
}

/// A pixel event for selection and feedback.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RasterEvent {
    /// `glRasterPos*`/`glWindowPos*` set a valid raster position: a hit in selection mode.
    Position,
    /// `glBitmap`: `GL_BITMAP_TOKEN` in feedback mode.
    Bitmap,
    /// `glDrawPixels`: `GL_DRAW_PIXEL_TOKEN` in feedback mode.
    DrawPixels,
    /// `glCopyPixels`: `GL_COPY_PIXEL_TOKEN` in feedback mode.
    CopyPixels,
}

impl Context {
    /// `glRenderMode`: switches mode and returns what the mode being left produced: 0 for
    /// `GL_RENDER`, the number of hit records for `GL_SELECT`, the number of values for
    /// `GL_FEEDBACK`, −1 if the buffer overflowed. `GL_INVALID_ENUM` for an unknown mode;
    /// `GL_INVALID_OPERATION` when entering selection or feedback before its buffer was given
    /// (then nothing changes).
    pub fn glRenderMode(&mut self, mode: GLenum) -> GLint {
        let new = match mode {
            gl::GL_RENDER => RenderMode::Render,
            gl::GL_SELECT if self.render_mode.select.specified => RenderMode::Select,
            gl::GL_FEEDBACK if self.render_mode.feedback.specified => RenderMode::Feedback,
            gl::GL_SELECT | gl::GL_FEEDBACK => {
                self.set_error_in(gl::GL_INVALID_OPERATION, "glRenderMode");
                return 0;
            }
            _ => {
                self.set_error_in(gl::GL_INVALID_ENUM, "glRenderMode");
                return 0;
            }
        };
        let r = &mut self.render_mode;
        let result = match r.mode {
            RenderMode::Render => 0,
            // Safety: the program keeps the selection buffer valid while in selection mode.
            RenderMode::Select => unsafe { r.select.finish() },
            RenderMode::Feedback => r.feedback.finish(),
        };
        if new == RenderMode::Select {
            r.select.names.clear();
            r.select.hit = None;
        }
        r.mode = new;
        result
    }

    /// Whether primitives are being selected or fed back instead of drawn.
    pub fn render_mode_active(&self) -> bool {
        self.render_mode.mode != RenderMode::Render
    }

    /// Hands a primitive to selection or feedback. Returns `false` in `GL_RENDER` mode (the
    /// caller draws it as usual) and `true` when selection or feedback consumed it (nothing
    /// may reach the frame). `rules` is the culling and polygon-mode state; `clip_planes` the
    /// enabled user clip planes in eye coordinates.
    pub fn render_mode_primitive(&mut self, prim: &CpuPrimitive, rules: &RasterRules, clip_planes: &[[f32; 4]]) -> bool {
        if self.render_mode.mode == RenderMode::Render {
            return false;
        }
        let transforms = pipeline::Transforms {
            modelview: self.transform.modelview(),
            projection: self.transform.projection(),
            texture: self.transform.texture_matrix(0),
            viewport: &self.viewport,
            clip_planes,
        };
        let shapes = transforms.shapes(prim, rules);
        let r = &mut self.render_mode;
        for shape in &shapes {
            match r.mode {
                RenderMode::Select => shape_depths(shape).for_each(|z| r.select.record_hit(z)),
                _ => r.feedback.shape(shape),
            }
        }
        true
    }

    /// A raster position or pixel rectangle in selection or feedback mode (sections 5.2,
    /// 5.3). `raster` is the current raster position (window coordinates and clip w, raster
    /// colour, raster texture coordinates of unit 0) or `None` when it is invalid, in which
    /// case nothing is recorded. Returns `true` when the pixels must not be drawn (selection
    /// or feedback mode); a raster position is set as usual in every mode.
    pub fn render_mode_raster_event(&mut self, event: RasterEvent, raster: Option<&WindowVertex>) -> bool {
        let r = &mut self.render_mode;
        match (r.mode, event, raster) {
            (RenderMode::Select, RasterEvent::Position, Some(v)) => r.select.record_hit(v.window[2]),
            (RenderMode::Feedback, RasterEvent::Bitmap, Some(v)) => r.feedback.raster(gl::GL_BITMAP_TOKEN, v),
            (RenderMode::Feedback, RasterEvent::DrawPixels, Some(v)) => r.feedback.raster(gl::GL_DRAW_PIXEL_TOKEN, v),
            (RenderMode::Feedback, RasterEvent::CopyPixels, Some(v)) => r.feedback.raster(gl::GL_COPY_PIXEL_TOKEN, v),
            _ => {}
        }
        r.mode != RenderMode::Render
    }

    /// `GL_SELECTION_BUFFER_POINTER` and `GL_FEEDBACK_BUFFER_POINTER` for `glGetPointerv`.
    pub fn render_mode_pointer(&self, pname: GLenum) -> Option<*mut std::ffi::c_void> {
        match pname {
            gl::GL_SELECTION_BUFFER_POINTER => Some(self.render_mode.select.buffer.pointer()),
            gl::GL_FEEDBACK_BUFFER_POINTER => Some(self.render_mode.feedback.buffer.pointer()),
            _ => None,
        }
    }

    /// Render-mode state queries (tables 6.x "Selection", "Feedback").
    pub(crate) fn query_render_mode(&self, pname: GLenum) -> Option<Value> {
        let r = &self.render_mode;
        Some(match pname {
            gl::GL_RENDER_MODE => Value::int(match r.mode {
                RenderMode::Render => gl::GL_RENDER,
                RenderMode::Select => gl::GL_SELECT,
                RenderMode::Feedback => gl::GL_FEEDBACK,
            }),
            gl::GL_NAME_STACK_DEPTH => Value::int(r.select.names.len() as i64),
            gl::GL_MAX_NAME_STACK_DEPTH => Value::int(MAX_NAME_STACK_DEPTH as i64),
            gl::GL_SELECTION_BUFFER_SIZE => Value::int(r.select.buffer.size() as i64),
            gl::GL_FEEDBACK_BUFFER_SIZE => Value::int(r.feedback.buffer.size() as i64),
            gl::GL_FEEDBACK_BUFFER_TYPE => Value::int(r.feedback.kind.to_gl()),
            _ => return None,
        })
    }
}

/// The window z of every vertex of a shape.
fn shape_depths(shape: &pipeline::Shape) -> Box<dyn Iterator<Item = f32> + '_> {
    match shape {
        pipeline::Shape::Point(v) => Box::new(std::iter::once(v.window[2])),
        pipeline::Shape::Line { ends, .. } => Box::new(ends.iter().map(|v| v.window[2])),
        pipeline::Shape::Polygon(vs) => Box::new(vs.iter().map(|v| v.window[2])),
    }
}

#[cfg(test)]
mod tests;
