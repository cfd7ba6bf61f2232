//! `glGetString` (OpenGL 1.5 section 6.1.11): static, NUL-terminated strings.

use super::Context;
use super::gl::{self, GLenum, GLubyte};

/// `GL_VENDOR`.
const VENDOR: &str = "glrt\0";
/// `GL_RENDERER`.
const RENDERER: &str = "glrt (Vulkan raster)\0";
/// `GL_VERSION`: "2.0 glrt <crate version>". Everything OpenGL 2.0 adds to 1.5 is there
/// (GLSL programs through `translate::glsl`, multiple draw buffers with one colour buffer,
/// non-power-of-two textures, point sprites, separate stencil and blend equations).
const VERSION: &str = concat!("2.0 glrt ", env!("CARGO_PKG_VERSION"), "\0");

/// `GL_SHADING_LANGUAGE_VERSION`: GLSL 1.10, OpenGL 2.0's. Shaders that declare
/// `#version 120` compile too (as 1.20), but OpenGL 2.1's commands for their non-square matrix
/// uniforms are not there, so 1.20 is not announced.
const SHADING_LANGUAGE_VERSION: &str = "1.10\0";

/// `GL_EXTENSIONS`: the extensions whose commands and enums are all implemented with their full
/// semantics (programs enable code paths from this string), in alphabetical order, each
/// followed by a space as in Mesa's string (piglit's `glinfo` prints it with spaces turned into
/// newlines and needs the last one to end its line). Left out although partly there:
/// `GL_EXT_texture_env_dot3` (its own `DOT3_*_EXT` enums are not accepted),
/// `GL_EXT_color_subtable` (exported for `GL_EXT_paletted_texture`, whose palettes it edits,
/// but not announced on its own). `GL_ARB_multisample` is announced with or without a
/// multisampled drawable, as Mesa does: its state and queries work on any context.
/// `GL_EXT_packed_depth_stencil` and `GL_ARB_depth_buffer_float` are announced for their pixel
/// formats and texture internal formats (as Mesa's compatibility profile does); their
/// renderbuffer formats work with `GL_EXT_framebuffer_object`.
/// `GL_ARB_pixel_buffer_object` and `GL_EXT_pixel_buffer_object` cover every pixel command glrt
/// has; the imaging-subset commands they also name (convolution, histogram, minmax) are not
/// part of OpenGL 1.5 without `GL_ARB_imaging`, which glrt does not announce.
/// The texture format extensions (`GL_ARB_texture_float`, `GL_ARB_texture_rg`,
/// `GL_EXT_packed_float`, `GL_EXT_texture_sRGB`, `GL_EXT_texture_shared_exponent`,
/// `GL_EXT_texture_snorm`) are complete for textures (`translate::texture::storage`); their
/// formats are `GL_FRAMEBUFFER_UNSUPPORTED_EXT` as framebuffer attachments where they keep more
/// than 8 bits, which the specifications allow. `GL_EXT_texture_integer` stores its formats
/// exactly and has its whole pixel path; integer attachments are `GL_FRAMEBUFFER_UNSUPPORTED_EXT`
/// (allowed), so no colour buffer is integer, and fixed-function sampling of integer textures
/// (undefined by the specification) leaves the unit untextured (`translate::texture::snapshot`).
const EXTENSIONS: &str = concat!(
    "GL_ARB_depth_buffer_float ",
    "GL_ARB_depth_texture ",
    "GL_ARB_draw_buffers ",
    "GL_ARB_map_buffer_range ",
    "GL_ARB_multisample ",
    "GL_ARB_multitexture ",
    "GL_ARB_occlusion_query ",
    "GL_ARB_pixel_buffer_object ",
    "GL_ARB_point_parameters ",
    "GL_ARB_point_sprite ",
    "GL_ARB_shadow ",
    "GL_ARB_texture_border_clamp ",
    "GL_ARB_texture_compression ",
    "GL_ARB_texture_cube_map ",
    "GL_ARB_texture_env_add ",
    "GL_ARB_texture_env_combine ",
    "GL_ARB_texture_env_crossbar ",
    "GL_ARB_texture_env_dot3 ",
    "GL_ARB_texture_float ",
    "GL_ARB_texture_mirrored_repeat ",
    "GL_ARB_texture_non_power_of_two ",
    "GL_ARB_texture_rectangle ",
    "GL_ARB_texture_rg ",
    "GL_ARB_transpose_matrix ",
    "GL_ARB_vertex_buffer_object ",
    "GL_ARB_window_pos ",
    "GL_ATI_separate_stencil ",
    "GL_EXT_abgr ",
    "GL_EXT_bgra ",
    "GL_EXT_blend_color ",
    "GL_EXT_blend_equation_separate ",
    "GL_EXT_blend_func_separate ",
    "GL_EXT_blend_minmax ",
    "GL_EXT_blend_subtract ",
    "GL_EXT_compiled_vertex_array ",
    "GL_EXT_draw_range_elements ",
    "GL_EXT_fog_coord ",
    "GL_EXT_framebuffer_blit ",
    "GL_EXT_framebuffer_object ",
    "GL_EXT_multi_draw_arrays ",
    "GL_EXT_packed_float ",
    "GL_EXT_packed_depth_stencil ",
    "GL_EXT_packed_pixels ",
    "GL_EXT_paletted_texture ",
    "GL_EXT_pixel_buffer_object ",
    "GL_EXT_point_parameters ",
    "GL_EXT_polygon_offset ",
    "GL_EXT_rescale_normal ",
    "GL_EXT_secondary_color ",
    "GL_EXT_separate_specular_color ",
    "GL_EXT_shadow_funcs ",
    "GL_EXT_shared_texture_palette ",
    "GL_EXT_stencil_two_side ",
    "GL_EXT_stencil_wrap ",
    "GL_EXT_texture3D ",
    "GL_EXT_texture_compression_s3tc ",
    "GL_EXT_texture_edge_clamp ",
    "GL_EXT_texture_env_add ",
    "GL_EXT_texture_env_combine ",
    "GL_EXT_texture_integer ",
    "GL_EXT_texture_lod_bias ",
    "GL_EXT_texture_object ",
    "GL_EXT_texture_sRGB ",
    "GL_EXT_texture_shared_exponent ",
    "GL_EXT_texture_snorm ",
    "GL_EXT_vertex_array ",
    "GL_IBM_texture_mirrored_repeat ",
    "GL_NV_blend_square ",
    "GL_NV_point_sprite ",
    "GL_SGIS_generate_mipmap ",
    "GL_SGIS_multitexture ",
    "GL_SGIS_texture_edge_clamp ",
    "GL_SGIS_texture_lod ",
    "\0"
);

impl Context {
    /// `glGetString`: `GL_INVALID_ENUM` (and null) for an unknown name.
    pub fn glGetString(&mut self, name: GLenum) -> *const GLubyte {
        let s = match name {
            gl::GL_VENDOR => VENDOR,
            gl::GL_RENDERER => RENDERER,
            gl::GL_VERSION => VERSION,
            gl::GL_EXTENSIONS => EXTENSIONS,
            gl::GL_SHADING_LANGUAGE_VERSION => SHADING_LANGUAGE_VERSION,
            _ => {
                self.set_error_in(gl::GL_INVALID_ENUM, "glGetString");
                return std::ptr::null();
            }
        };
        s.as_ptr()
    }
}

#[cfg(test)]
mod tests {
    use std::ffi::CStr;

    use crate::translate::Context;
    use crate::translate::{dispatch, gl};

    fn string(ctx: &mut Context, name: gl::GLenum) -> Option<String> {
        let p = unsafe { dispatch::glGetString(ctx, name) };
        (!p.is_null()).then(|| unsafe { CStr::from_ptr(p.cast()) }.to_str().unwrap().to_owned())
    }

    #[test]
    fn strings_and_errors() {
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(string(&mut ctx, gl::GL_VENDOR).as_deref(), Some("glrt"));
        assert_eq!(string(&mut ctx, gl::GL_VERSION).unwrap(), format!("2.0 glrt {}", env!("CARGO_PKG_VERSION")));
        assert_eq!(string(&mut ctx, gl::GL_SHADING_LANGUAGE_VERSION).unwrap(), "1.10");
        let ext = string(&mut ctx, gl::GL_EXTENSIONS).unwrap();
        assert!(ext.split(' ').any(|e| e == "GL_EXT_blend_minmax"), "{ext}");
        assert!(ext.split(' ').any(|e| e == "GL_ARB_window_pos"), "{ext}");
        assert!(ext.ends_with(' ') && !ext.contains("  "), "{ext:?}");
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(string(&mut ctx, gl::GL_FOG), None);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        unsafe { dispatch::glBegin(&mut ctx, gl::GL_POINTS) };
        assert_eq!(string(&mut ctx, gl::GL_VENDOR), None);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    }
}
