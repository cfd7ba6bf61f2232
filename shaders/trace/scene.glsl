// The traced scene as the compute shaders read it: per-frame constants, per-triangle shading
// attributes, materials and lights. Mirrored by src/render/trace/gpu_types.rs, whose layouts
// the build checks against this file's compiled SPIR-V; the flags are generated from
// src/render/trace/shader_constants.rs. Everything is in the eye space of the current frame.

#ifndef TRACE_SCENE_GLSL
#define TRACE_SCENE_GLSL

#include "generated/trace_constants.glsl"
#include "trace/bindings.glsl"
#include "trace/instance.glsl"

layout(set = TRACE_SET, binding = BINDING_FRAME, std430) readonly buffer TraceFrameBlock {
    mat4 projection;            // eye to clip, this frame
    mat4 inverse_projection;
    mat4 previous_projection;   // eye to clip, last frame (motion vectors)
    vec4 environment;           // linear radiance of missed rays (rgb) without FRAME_SKY
    vec4 viewport;              // the GL viewport traced: x, y, width, height in window pixels
    vec4 depth_range;           // near, far of glDepthRange; z, w unused
    vec4 params;                // x: exposure multiplier; y: history cap (frames); z: unused;
                                // w: ray-cone spread angle of one traced pixel (radians)
    uvec4 size;                 // traced width, height; window width, height
    uvec4 counts;               // frame index (random seed), samples per pixel, bounces, lights
    uvec4 flags;                // x: FRAME_* bits; y: instance count; z, w unused
} frame;

// The shading attributes of one triangle corner.
struct Corner {
    vec2 uv[TRACED_UNITS]; // texture coordinates of each traced unit (after its texture matrix), or 0
    uint normal;    // object-space normal, octahedral snorm16x2 (0: use the geometric normal)
    uint color;     // base colour, sRGB-encoded unorm8 RGBA (GL's colour or material diffuse)
};

struct TriangleAttributes {
    Corner corner[3];
};

layout(set = TRACE_SET, binding = BINDING_ATTRIBUTES, std430) readonly buffer Attributes {
    TriangleAttributes attributes[];
};

// One traced texture unit of a material: what texenv.glsl's tex_env needs to apply it, and
// what the surface makes of it (render::trace::scene's module doc).
struct Layer {
    vec4 env_color;     // GL_TEXTURE_ENV_COLOR
    uint texture;       // texel pool index, or NO_TEXTURE
    uint env;           // the unit word's FORMAT and ENV fields (generated/texenv_codes.glsl)
    uint combine_rgb;   // the combiner words (ENV_COMBINE)
    uint combine_alpha;
    uint role;          // LAYER_*
    uint pad[3];
};

struct Material {
    vec4 emission;      // linear emitted radiance (rgb); a: emissive scale applied to the albedo
    Layer layer[TRACED_UNITS]; // layer u: texture unit u, with corner coordinates uv[u]
    float roughness;    // GGX alpha = roughness^2
    float metalness;
    float specular;     // dielectric reflectance at normal incidence (F0)
    uint alpha_func;    // the alpha test's compare function (gl_compare.glsl order; 7: always)
    float alpha_ref;
    uint pad[3];
};

layout(set = TRACE_SET, binding = BINDING_MATERIALS, std430) readonly buffer Materials {
    Material materials[];
};

struct Light {
    vec4 position;  // eye space; w = 0: directional, xyz = unit direction towards the light
    vec4 radiance;  // directional: irradiance at normal incidence; point: intensity (rgb); a: sphere radius (0: a point)
    vec4 spot;      // unit direction the spot points at; w: cos(cutoff), or -2 without a spot
    vec4 params;    // x: spot exponent; y: cos of a directional light's angular radius
};

layout(set = TRACE_SET, binding = BINDING_LIGHTS, std430) readonly buffer Lights {
    Light lights[];
};

#endif
