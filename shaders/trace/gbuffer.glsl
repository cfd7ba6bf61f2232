// Per-pixel buffers between the tracing pass (pathtrace.comp), the temporal pass
// (trace_resolve.comp) and the composite (trace_composite.frag). A denoiser (A-SVGF, a later
// issue) reads the G-buffer and the noisy radiance and writes the filtered colour in place of
// the temporal pass.

#ifndef TRACE_GBUFFER_GLSL
#define TRACE_GBUFFER_GLSL

#include "trace/bindings.glsl"

// What the primary ray of a pixel saw this frame.
struct GSample {
    vec4 radiance;      // noisy linear radiance, averaged over this frame's samples
    uint albedo;        // linear albedo, unorm8 RGB (a: coverage)
    uint normal;        // shading normal, octahedral (pack.glsl)
    float depth;        // window depth as glDepthRange maps it; >= 1 for rays that missed
    float view_z;       // eye-space distance along -z (0: missed)
    vec2 motion;        // window position now minus window position last frame, in traced pixels
    uint material;      // roughness, metalness as unorm8 in bytes 0 and 1
    uint instance;      // index of the instance hit, 0xffffffff on a miss
};

layout(set = TRACE_SET, binding = BINDING_GBUFFER, std430) buffer GBuffer {
    GSample gbuffer[];
};

// Running colour mean of a pixel and what it was computed for.
struct AccumSample {
    vec4 color;         // rgb: mean linear radiance; a: frames in the mean
    float view_z;
    uint normal;
    uint material;      // the key of the material the mean is of (Material.key)
    uint pad;
};

layout(set = TRACE_SET, binding = BINDING_ACCUMULATION, std430) buffer Accumulation {
    AccumSample accumulation[];
};

layout(set = TRACE_SET, binding = BINDING_HISTORY, std430) readonly buffer History {
    AccumSample history[];
};

// What the composite draws: tone-mapped colour and depth.
struct OutputSample {
    uint color;         // display-encoded unorm8 RGBA
    float depth;        // window depth; >= 1 where the primary ray missed (the composite keeps the framebuffer)
};

layout(set = TRACE_SET, binding = BINDING_OUTPUT, std430) buffer Output {
    OutputSample outputs[];
};

layout(set = TRACE_SET, binding = BINDING_COUNTERS, std430) buffer Counters {
    uint primary_rays;
    uint shadow_rays;
    uint diffuse_rays;
    uint specular_rays;
    uint nodes_visited;     // BVH nodes (TLAS and BLAS) visited by all rays
    uint triangles_tested;  // ray-triangle tests of all rays
} counters;

#endif
