// The per-draw block of the fixed-function shaders (std140). Mirrored by
// src/render/raster/ff/uniforms.rs (FfBlock), whose layout the build checks against the
// compiled SPIR-V; MAX_UNITS, MAX_LIGHTS and MAX_CLIP_PLANES come from the generated headers,
// HeightFog from fog/height.glsl (included before this file).
//
// It is a read-only storage buffer, not a uniform buffer: Mesa's lavapipe inlines uniform
// buffer values that feed branches or locals used five times or more (lvp_inline_uniforms.c)
// and compiles a new LLVM variant whenever those values change, so every draw with a new
// material or matrix cost a shader compile (glxgears: 4 frames/s as a uniform buffer, 900 as
// a storage buffer). Storage buffer reads are never inlined.

struct Material {
    vec4 ambient;
    vec4 diffuse;
    vec4 specular;
    vec4 emission;
    vec4 shininess;   // x
};

struct Light {
    vec4 ambient;
    vec4 diffuse;
    vec4 specular;
    vec4 position;    // eye space, homogeneous
    vec4 spot;        // normalized direction, exponent
    vec4 params;      // cos(cutoff) or -2 without spot, attenuation k0, k1, k2
};

layout(set = 0, binding = BINDING_UNIFORMS, std140) readonly buffer FF {
    mat4 modelview;
    mat4 projection;
    mat4 normal_matrix;               // inverse transpose of the modelview
    mat4 texture_matrix[MAX_UNITS];
    vec4 texgen_plane[4 * MAX_UNITS]; // unit u, coordinate c at 4u + c
    vec4 env_color[MAX_UNITS];
    vec4 lod_bias;                    // component u
    vec4 scene_ambient;
    Material material[2];             // front, back
    Light light[MAX_LIGHTS];          // the enabled ones first
    vec4 fog_color;
    vec4 fog_params;                  // start, end, density, 1 / (end - start)
    vec4 clip_plane[MAX_CLIP_PLANES]; // eye space, the enabled ones first
    vec4 point;                       // size, min, max, fade threshold
    vec4 point_attenuation;           // constant, linear, quadratic
    vec4 raster;                      // alpha reference, line width, stipple factor, rescale
    vec4 viewport;                    // x, y, width, height (window pixels, y up)
    uvec4 stipple;                    // line stipple pattern, framebuffer height
    uvec4 polygon_stipple[8];         // row r (bottom first) at [r / 4][r % 4]
    HeightFog height_fog;             // the renderer's height fog (render::fog), written per batch
} u;
