// The traced scene as the compute shaders read it: per-frame constants, per-triangle shading
// attributes and pass corners, materials, lights and emitters. Mirrored by src/render/trace/gpu_types.rs, whose layouts
// the build checks against this file's compiled SPIR-V; the flags are generated from
// src/render/trace/shader_constants.rs. Everything is in the eye space of the current frame.

#ifndef TRACE_SCENE_GLSL
#define TRACE_SCENE_GLSL

#include "generated/trace_constants.glsl"
#include "trace/bindings.glsl"
#include "trace/instance.glsl"
#include "trace/light.glsl"

layout(set = TRACE_SET, binding = BINDING_FRAME, std430) readonly buffer TraceFrameBlock {
    mat4 projection;            // eye to clip, this frame
    mat4 inverse_projection;
    mat4 previous_projection;   // eye to clip, last frame (motion vectors)
    vec4 environment;           // linear radiance of missed rays (rgb) without FRAME_SKY
    vec4 viewport;              // the GL viewport traced: x, y, width, height in window pixels
    vec4 depth_range;           // near, far of glDepthRange; z, w unused
    vec4 params;                // x: exposure multiplier; y: history cap (frames); z: knee of
                                // TONEMAP_KNEE; w: ray-cone spread angle of one traced pixel (radians)
    uvec4 size;                 // traced width, height; window width, height
    uvec4 counts;               // frame index (random seed), samples per pixel, bounces, lights
    uvec4 flags;                // x: FRAME_* bits; y: instance count; z: emitter count; w unused
    vec4 sampling;              // x: probability that a path vertex samples the sky
                                // (trace/sky_sampling.glsl); y: last frame's (0 where its
                                // cells are not held); z, w unused
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

// One traced texture unit or pass of a material: what texenv.glsl's tex_env needs to apply it,
// how a pass blends, and what the surface makes of it (render::trace::material's module doc).
struct Layer {
    vec4 env_color;     // GL_TEXTURE_ENV_COLOR
    vec4 blend_color;   // a pass's glBlendColor
    uint texture;       // texel pool index, or NO_TEXTURE
    uint env;           // the unit word's FORMAT and ENV fields (generated/texenv_codes.glsl)
    uint combine_rgb;   // the combiner words (ENV_COMBINE)
    uint combine_alpha;
    uint role;          // LAYER_*
    uint blend;         // a pass's blend function (BLEND_* fields; units: GL_ONE, GL_ZERO)
    uint alpha_func;    // a pass's alpha test (gl_compare.glsl order; 7: always)
    float alpha_ref;
};

// What one triangle's corners carry for one pass of its surface.
struct LayerCorners {
    vec2 uv[3];         // the pass's unit-0 coordinates at each corner
    uint color[3];      // the pass's primary colour at each corner, sRGB-encoded unorm8 RGBA
    uint covered;       // 1: the pass covers the triangle; 0: it leaves it as it is
};

layout(set = TRACE_SET, binding = BINDING_LAYER_CORNERS, std430) readonly buffer LayerCornerBlock {
    LayerCorners layer_corners[];
};

struct Material {
    vec4 emission;      // linear emitted radiance (rgb); a: emissive scale applied to the raster colour
    vec4 ambient;       // a vertex-lit model's light from every direction (rgb, linear radiance), taken by its
                        // continuation rays that meet nothing within a (the model's width); a = 0: none
    Layer layer[MATERIAL_LAYERS]; // layer u < TRACED_UNITS: texture unit u (corner coordinates uv[u]); then the passes
    float roughness;    // GGX alpha = roughness^2
    float metalness;
    float specular;     // dielectric reflectance at normal incidence (F0)
    uint alpha_func;    // the alpha test's compare function (gl_compare.glsl order; 7: always)
    float alpha_ref;
    uint flags;         // MATERIAL_*
    uint layer_corners; // the instance's first LayerCorners record (passes per triangle, BVH order)
    uint passes;        // passes of the surface
    uint emitters;      // the instance's first Emitter (one per triangle, BVH order), or NO_EMITTER
    uint key;           // a hash of what the material shows (the temporal pass's history follows it)
    uint tint;          // with MATERIAL_TINT_PRIMARY: the primary colours' RGB in the albedo (packUnorm4x8, display-encoded)
    uint radiosity;     // the instance's first RadiosityTriangle (one per triangle, BVH order), or NO_RADIOSITY
};

layout(set = TRACE_SET, binding = BINDING_MATERIALS, std430) readonly buffer Materials {
    Material materials[];
};

// One emissive triangle of the frame: an entry of the alias table next-event estimation draws
// triangles from in proportion to their power (render::trace::emitters).
struct Emitter {
    uint instance;      // its instance
    uint triangle;      // its triangle (global index)
    uint alias;         // the entry taken when the draw exceeds `threshold`
    float threshold;
    float probability;  // probability that a sample picks this triangle
};

layout(set = TRACE_SET, binding = BINDING_EMITTERS, std430) readonly buffer Emitters {
    Emitter emitters[];
};

// Radiosity's indirect light at the corners of a static-world triangle (render::trace::radiosity):
// irradiance / pi, linear RGB per corner, read by trace/radiosity.glsl.
struct RadiosityTriangle {
    float corner[9];    // corner k's red, green, blue at 3k .. 3k + 2
};

layout(set = TRACE_SET, binding = BINDING_RADIOSITY, std430) readonly buffer Radiosity {
    RadiosityTriangle radiosity_triangles[];
};

layout(set = TRACE_SET, binding = BINDING_LIGHTS, std430) readonly buffer Lights {
    Light lights[];
};

#endif
