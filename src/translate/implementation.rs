//! Implementation-dependent values of glrt's visual and rasterizer (OpenGL 1.5 tables 6.29 to
//! 6.33) that no other module owns: framebuffer bit depths, the visual's buffers, point and
//! line size ranges, and the limits of the fixed-function state.

use super::Context;
use super::get::Value;
use super::gl::{self, GLenum};
use super::limits::{
    MAX_ATTRIB_STACK_DEPTH, MAX_CLIP_PLANES, MAX_COMBINED_TEXTURE_IMAGE_UNITS, MAX_DRAW_BUFFERS, MAX_ELEMENTS,
    MAX_FRAGMENT_UNIFORM_COMPONENTS, MAX_LIGHTS, MAX_TEXTURE_COORDS, MAX_TEXTURE_IMAGE_UNITS, MAX_VARYING_FLOATS,
    MAX_VERTEX_ATTRIBS, MAX_VERTEX_TEXTURE_IMAGE_UNITS, MAX_VERTEX_UNIFORM_COMPONENTS,
};
use crate::frame::state::MAX_POINT_SIZE;

/// Stencil bits of the visual.
pub const STENCIL_BITS: i32 = 8;
/// Sub-pixel precision bits (Vulkan guarantees at least 4).
const SUBPIXEL_BITS: i32 = 4;
/// Colour bits per channel (RGBA8).
const COLOR_BITS: i32 = 8;
/// Depth bits.
const DEPTH_BITS: i32 = 24;
/// Accumulation bits per channel (the accumulation buffer is emulated in 16-bit floats).
const ACCUM_BITS: i32 = 16;
/// Point sizes and line widths glrt draws: `[smallest, largest]`.
pub const POINT_SIZE_RANGE: [f32; 2] = [1.0, MAX_POINT_SIZE];
/// Size steps between supported point sizes and line widths.
const SIZE_GRANULARITY: f32 = 0.125;

impl Context {
    /// Implementation-dependent values.
    pub(crate) fn query_implementation(&self, pname: GLenum) -> Option<Value> {
        let range = || Value::floats(&POINT_SIZE_RANGE);
        Some(match pname {
            gl::GL_MAX_LIGHTS => Value::int(MAX_LIGHTS as i64),
            gl::GL_MAX_CLIP_PLANES => Value::int(MAX_CLIP_PLANES as i64),
            gl::GL_MAX_VERTEX_ATTRIBS => Value::int(MAX_VERTEX_ATTRIBS as i64),
            gl::GL_MAX_TEXTURE_IMAGE_UNITS => Value::int(MAX_TEXTURE_IMAGE_UNITS as i64),
            gl::GL_MAX_TEXTURE_COORDS => Value::int(MAX_TEXTURE_COORDS as i64),
            gl::GL_MAX_VERTEX_UNIFORM_COMPONENTS => Value::int(MAX_VERTEX_UNIFORM_COMPONENTS as i64),
            gl::GL_MAX_FRAGMENT_UNIFORM_COMPONENTS => Value::int(MAX_FRAGMENT_UNIFORM_COMPONENTS as i64),
            gl::GL_MAX_VARYING_FLOATS => Value::int(MAX_VARYING_FLOATS as i64),
            gl::GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS => Value::int(MAX_VERTEX_TEXTURE_IMAGE_UNITS as i64),
            gl::GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS => Value::int(MAX_COMBINED_TEXTURE_IMAGE_UNITS as i64),
            gl::GL_MAX_DRAW_BUFFERS => Value::int(MAX_DRAW_BUFFERS as i64),
            gl::GL_MAX_ATTRIB_STACK_DEPTH => Value::int(MAX_ATTRIB_STACK_DEPTH as i64),
            gl::GL_MAX_ELEMENTS_VERTICES | gl::GL_MAX_ELEMENTS_INDICES => Value::int(MAX_ELEMENTS),
            gl::GL_SUBPIXEL_BITS => Value::int(SUBPIXEL_BITS),
            gl::GL_RED_BITS | gl::GL_GREEN_BITS | gl::GL_BLUE_BITS => Value::int(COLOR_BITS),
            // The drawable's configuration: an RGB one has no destination alpha.
            gl::GL_ALPHA_BITS => Value::int(if self.target.is_none_or(|t| t.alpha) { COLOR_BITS } else { 0 }),
            gl::GL_DEPTH_BITS => Value::int(DEPTH_BITS),
            gl::GL_STENCIL_BITS => Value::int(STENCIL_BITS),
            gl::GL_ACCUM_RED_BITS | gl::GL_ACCUM_GREEN_BITS | gl::GL_ACCUM_BLUE_BITS | gl::GL_ACCUM_ALPHA_BITS => {
                Value::int(ACCUM_BITS)
            }
            // EXT_packed_float: whether R, G, B, A of the colour buffer are signed; glrt's colour
            // buffers (drawables and framebuffer objects) are all unsigned normalized.
            gl::GL_RGBA_SIGNED_COMPONENTS_EXT => Value::Int(vec![0; 4]),
            // An RGBA visual has no colour-index bits.
            gl::GL_INDEX_BITS => Value::int(0),
            gl::GL_AUX_BUFFERS => Value::int(0),
            gl::GL_RGBA_MODE => Value::bool(true),
            // EXT_texture_integer: whether the colour buffers hold integers; glrt's never do
            // (integer attachments are GL_FRAMEBUFFER_UNSUPPORTED_EXT).
            gl::GL_RGBA_INTEGER_MODE_EXT => Value::bool(false),
            gl::GL_INDEX_MODE => Value::bool(false),
            gl::GL_DOUBLEBUFFER => Value::bool(true),
            gl::GL_STEREO => Value::bool(false),
            // The drawable's configuration (GLX_SAMPLE_BUFFERS, GLX_SAMPLES).
            gl::GL_SAMPLE_BUFFERS => Value::int(i64::from(self.target.is_some_and(|t| t.samples > 1))),
            gl::GL_SAMPLES => Value::int(self.target.filter(|t| t.samples > 1).map_or(0, |t| i64::from(t.samples))),
            gl::GL_POINT_SIZE_RANGE | gl::GL_ALIASED_POINT_SIZE_RANGE => range(),
            gl::GL_LINE_WIDTH_RANGE | gl::GL_ALIASED_LINE_WIDTH_RANGE => range(),
            gl::GL_POINT_SIZE_GRANULARITY | gl::GL_LINE_WIDTH_GRANULARITY => Value::float(SIZE_GRANULARITY),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::gl;

    #[test]
    fn visual_and_limits() {
        let (mut ctx, _) = Context::with_recording();
        let mut v = [0i32; 2];
        for (pname, expected) in [
            (gl::GL_MAX_LIGHTS, 8),
            (gl::GL_MAX_CLIP_PLANES, 6),
            (gl::GL_MAX_ATTRIB_STACK_DEPTH, 16),
            (gl::GL_ALPHA_BITS, 8),
            (gl::GL_DEPTH_BITS, 24),
            (gl::GL_STENCIL_BITS, 8),
            (gl::GL_ACCUM_RED_BITS, 16),
            (gl::GL_AUX_BUFFERS, 0),
            (gl::GL_DOUBLEBUFFER, 1),
            (gl::GL_STEREO, 0),
            (gl::GL_RGBA_MODE, 1),
            (gl::GL_RGBA_INTEGER_MODE_EXT, 0),
            (gl::GL_SAMPLES, 0),
        ] {
            unsafe { ctx.glGetIntegerv(pname, v.as_mut_ptr()) };
            assert_eq!(v[0], expected, "pname {pname:#x}");
        }
        let mut range = [0.0f32; 2];
        unsafe { ctx.glGetFloatv(gl::GL_POINT_SIZE_RANGE, range.as_mut_ptr()) };
        assert_eq!(range, [1.0, 64.0]);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn sample_queries_answer_the_drawable() {
        use crate::frame::{Surface, Target};
        let (mut ctx, _) = Context::with_recording();
        let samples = |ctx: &Context| [gl::GL_SAMPLE_BUFFERS, gl::GL_SAMPLES].map(|p| ctx.query(p).unwrap().to_ints()[0]);
        ctx.bind_target(Target { size: [8, 8], surface: Surface::Offscreen, swap_interval: 0, samples: 4, alpha: true });
        assert_eq!(samples(&ctx), [1, 4]);
        ctx.bind_target(Target { size: [8, 8], surface: Surface::Offscreen, swap_interval: 0, samples: 1, alpha: true });
        assert_eq!(samples(&ctx), [0, 0]);
    }

    #[test]
    fn alpha_bits_answer_the_drawable() {
        use crate::frame::{Surface, Target};
        let (mut ctx, _) = Context::with_recording();
        let alpha_bits = |ctx: &Context| ctx.query(gl::GL_ALPHA_BITS).unwrap().to_ints()[0];
        let rgb = Target { size: [8, 8], surface: Surface::Offscreen, swap_interval: 0, samples: 1, alpha: false };
        ctx.bind_target(rgb);
        assert_eq!(alpha_bits(&ctx), 0);
        assert_eq!(ctx.query(gl::GL_RED_BITS).unwrap().to_ints()[0], 8);
        assert_eq!(ctx.query(gl::GL_RGBA_SIGNED_COMPONENTS_EXT).unwrap().to_ints(), [0; 4]);
        ctx.bind_target(Target { alpha: true, ..rgb });
        assert_eq!(alpha_bits(&ctx), 8);
    }
}
