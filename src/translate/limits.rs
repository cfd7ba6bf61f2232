//! Implementation limits glrt advertises (`glGet` of the `GL_MAX_*` values). Chosen to cover
//! what OpenGL 1.x programs use while staying inside Mesa lavapipe's Vulkan limits.

/// Texture units (`GL_MAX_TEXTURE_UNITS`); the specification asks for at least 2.
pub const MAX_TEXTURE_UNITS: usize = 4;
/// Generic vertex attributes (`GL_MAX_VERTEX_ATTRIBS`).
pub const MAX_VERTEX_ATTRIBS: usize = 16;
/// Texture image units a fragment shader samples (`GL_MAX_TEXTURE_IMAGE_UNITS`).
pub const MAX_TEXTURE_IMAGE_UNITS: usize = 4;
/// Texture coordinate sets of vertex shaders (`GL_MAX_TEXTURE_COORDS`).
pub const MAX_TEXTURE_COORDS: usize = 4;
/// Uniform components of a vertex shader (`GL_MAX_VERTEX_UNIFORM_COMPONENTS`).
pub const MAX_VERTEX_UNIFORM_COMPONENTS: usize = 1024;
/// Uniform components of a fragment shader (`GL_MAX_FRAGMENT_UNIFORM_COMPONENTS`).
pub const MAX_FRAGMENT_UNIFORM_COMPONENTS: usize = 1024;
/// Varying floats between the shaders (`GL_MAX_VARYING_FLOATS`).
pub const MAX_VARYING_FLOATS: usize = 64;
/// Texture image units a vertex shader samples (`GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS`).
pub const MAX_VERTEX_TEXTURE_IMAGE_UNITS: usize = 4;
/// Texture image units of both shaders together (`GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS`): the
/// fixed-function units, which both stages share (`glActiveTexture` takes units below the
/// larger of this and `GL_MAX_TEXTURE_COORDS`, OpenGL 2.0 section 3.8.13).
pub const MAX_COMBINED_TEXTURE_IMAGE_UNITS: usize = MAX_TEXTURE_UNITS;
/// Colour buffers a fragment shader writes (`GL_MAX_DRAW_BUFFERS`).
pub const MAX_DRAW_BUFFERS: usize = 1;
/// Lights (`GL_MAX_LIGHTS`).
pub const MAX_LIGHTS: usize = 8;
/// User clip planes (`GL_MAX_CLIP_PLANES`).
pub const MAX_CLIP_PLANES: usize = 6;
/// Modelview stack depth (`GL_MAX_MODELVIEW_STACK_DEPTH`).
pub const MAX_MODELVIEW_STACK_DEPTH: usize = 32;
/// Projection stack depth (`GL_MAX_PROJECTION_STACK_DEPTH`).
pub const MAX_PROJECTION_STACK_DEPTH: usize = 32;
/// Texture matrix stack depth per unit (`GL_MAX_TEXTURE_STACK_DEPTH`).
pub const MAX_TEXTURE_STACK_DEPTH: usize = 10;
/// Server attribute stack depth (`GL_MAX_ATTRIB_STACK_DEPTH`).
pub const MAX_ATTRIB_STACK_DEPTH: usize = 16;
/// Client attribute stack depth (`GL_MAX_CLIENT_ATTRIB_STACK_DEPTH`).
pub const MAX_CLIENT_ATTRIB_STACK_DEPTH: usize = 16;
/// Name stack depth for selection (`GL_MAX_NAME_STACK_DEPTH`).
pub const MAX_NAME_STACK_DEPTH: usize = 64;
/// Largest 1D/2D texture (`GL_MAX_TEXTURE_SIZE`).
pub const MAX_TEXTURE_SIZE: usize = 8192;
/// Largest 3D texture (`GL_MAX_3D_TEXTURE_SIZE`).
pub const MAX_3D_TEXTURE_SIZE: usize = 2048;
/// Largest cube-map face (`GL_MAX_CUBE_MAP_TEXTURE_SIZE`).
pub const MAX_CUBE_MAP_TEXTURE_SIZE: usize = 8192;
/// Highest evaluator order (`GL_MAX_EVAL_ORDER`).
pub const MAX_EVAL_ORDER: usize = 30;
/// Largest pixel map (`GL_MAX_PIXEL_MAP_TABLE`).
pub const MAX_PIXEL_MAP_TABLE: usize = 256;
/// Largest viewport (`GL_MAX_VIEWPORT_DIMS`).
pub const MAX_VIEWPORT_DIMS: i32 = 16384;
/// Largest `glDrawRangeElements` vertex range and index count hints.
pub const MAX_ELEMENTS: i32 = 1 << 20;
