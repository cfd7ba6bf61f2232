//! Feedback (OpenGL 1.5 section 5.3): the feedback buffer, its vertex layouts and the token
//! stream of points, lines, polygons, pixel rectangles and pass-through markers.

use super::buffer::ClientBuffer;
use super::RenderMode;
use super::pipeline::{Shape, WindowVertex};
use crate::translate::Context;
use crate::translate::gl::{self, GL_2D, GL_3D, GL_3D_COLOR, GL_3D_COLOR_TEXTURE, GL_4D_COLOR_TEXTURE, GLenum, GLfloat, GLsizei};

/// What each fed-back vertex holds (table 5.2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FeedbackType {
    /// `GL_2D`: x, y.
    #[default]
    TwoD,
    /// `GL_3D`: x, y, z.
    ThreeD,
    /// `GL_3D_COLOR`: x, y, z, r, g, b, a.
    ThreeDColor,
    /// `GL_3D_COLOR_TEXTURE`: x, y, z, colour, s, t, r, q.
    ThreeDColorTexture,
    /// `GL_4D_COLOR_TEXTURE`: x, y, z, w, colour, s, t, r, q.
    FourDColorTexture,
}

impl FeedbackType {
    fn from_gl(ty: GLenum) -> Option<FeedbackType> {
        Some(match ty {
            GL_2D => FeedbackType::TwoD,
            GL_3D => FeedbackType::ThreeD,
            GL_3D_COLOR => FeedbackType::ThreeDColor,
            GL_3D_COLOR_TEXTURE => FeedbackType::ThreeDColorTexture,
            GL_4D_COLOR_TEXTURE => FeedbackType::FourDColorTexture,
            _ => return None,
        })
    }

    /// The GL enum, for `GL_FEEDBACK_BUFFER_TYPE`.
    pub fn to_gl(self) -> GLenum {
        match self {
            FeedbackType::TwoD => GL_2D,
            FeedbackType::ThreeD => GL_3D,
            FeedbackType::ThreeDColor => GL_3D_COLOR,
            FeedbackType::ThreeDColorTexture => GL_3D_COLOR_TEXTURE,
            FeedbackType::FourDColorTexture => GL_4D_COLOR_TEXTURE,
        }
    }

    /// The values of one vertex.
    pub fn vertex_values(self, v: &WindowVertex) -> Vec<f32> {
        let coords = match self {
            FeedbackType::TwoD => 2,
            FeedbackType::FourDColorTexture => 4,
            _ => 3,
        };
        let mut out = v.window[..coords].to_vec();
        if !matches!(self, FeedbackType::TwoD | FeedbackType::ThreeD) {
            out.extend(v.color);
        }
        if matches!(self, FeedbackType::ThreeDColorTexture | FeedbackType::FourDColorTexture) {
            out.extend(v.texcoord);
        }
        out
    }
}

/// Feedback state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FeedbackState {
    /// `glFeedbackBuffer`'s buffer.
    pub buffer: ClientBuffer,
    /// `GL_FEEDBACK_BUFFER_TYPE`.
    pub kind: FeedbackType,
    /// Whether `glFeedbackBuffer` was called at least once.
    pub specified: bool,
}

/// Tokens are written as floats (section 5.3).
fn token(t: GLenum) -> f32 {
    t as f32
}

impl FeedbackState {
    fn value(&mut self, v: f32) {
        // Safety: the program keeps the feedback buffer valid while in feedback mode.
        unsafe { self.buffer.push::<GLfloat>(v) }
    }

    fn vertex(&mut self, v: &WindowVertex) {
        for x in self.kind.vertex_values(v) {
            self.value(x);
        }
    }

    /// Writes the tokens of one shape.
    pub fn shape(&mut self, shape: &Shape) {
        match shape {
            Shape::Point(v) => {
                self.value(token(gl::GL_POINT_TOKEN));
                self.vertex(v);
            }
            Shape::Line { ends, reset } => {
                self.value(token(if *reset { gl::GL_LINE_RESET_TOKEN } else { gl::GL_LINE_TOKEN }));
                ends.iter().for_each(|v| self.vertex(v));
            }
            Shape::Polygon(vs) => {
                self.value(token(gl::GL_POLYGON_TOKEN));
                self.value(vs.len() as f32);
                vs.iter().for_each(|v| self.vertex(v));
            }
        }
    }

    /// Writes a pixel-rectangle token (`GL_BITMAP_TOKEN`, `GL_DRAW_PIXEL_TOKEN`,
    /// `GL_COPY_PIXEL_TOKEN`) followed by the raster position.
    pub fn raster(&mut self, tok: GLenum, raster: &WindowVertex) {
        self.value(token(tok));
        self.vertex(raster);
    }

    /// Leaves feedback mode: the number of values written, or −1 if the buffer overflowed.
    pub fn finish(&mut self) -> i32 {
        let result = if self.buffer.overflowed() { -1 } else { self.buffer.count() as i32 };
        self.buffer.reset();
        result
    }
}

impl Context {
    /// `glFeedbackBuffer`: `GL_INVALID_VALUE` for a negative size, `GL_INVALID_ENUM` for an
    /// unknown type, `GL_INVALID_OPERATION` in feedback mode.
    ///
    /// # Safety
    /// `buffer` must stay valid for `size` floats until feedback mode is left.
    pub unsafe fn glFeedbackBuffer(&mut self, size: GLsizei, type_: GLenum, buffer: *mut GLfloat) {
        if self.render_mode.mode == RenderMode::Feedback {
            return self.set_error_in(gl::GL_INVALID_OPERATION, "glFeedbackBuffer");
        }
        if size < 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glFeedbackBuffer");
        }
        let Some(kind) = FeedbackType::from_gl(type_) else {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glFeedbackBuffer");
        };
        if buffer.is_null() && size > 0 {
            self.null_pointer("glFeedbackBuffer");
        }
        self.render_mode.feedback = FeedbackState { buffer: ClientBuffer::new(buffer, size as usize), kind, specified: true };
    }

    /// `glPassThrough`: in feedback mode, writes `GL_PASS_THROUGH_TOKEN` and `token`;
    /// ignored otherwise.
    pub fn glPassThrough(&mut self, token_value: GLfloat) {
        if self.render_mode.mode == RenderMode::Feedback {
            let f = &mut self.render_mode.feedback;
            f.value(token(gl::GL_PASS_THROUGH_TOKEN));
            f.value(token_value);
        }
    }
}
