// Per-pixel buffers between the tracing pass (pathtrace.comp), the temporal pass
// (trace_resolve.comp) and the composite (trace_composite.frag). The denoiser
// (shaders/denoise/, src/render/denoise) reads the G-buffer and its lighting channels and
// writes the output in place of the temporal pass.

#ifndef TRACE_GBUFFER_GLSL
#define TRACE_GBUFFER_GLSL

#include "trace/bindings.glsl"
#include "trace/samples.glsl"

// What the primary ray of a pixel saw this frame, per traced pixel, then per gradient stratum
// (gradient_record of trace/gradient.glsl).
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
    uint sky_rays;          // shadow rays towards the sky (in shadow_rays too)
    uint sky_unoccluded;    // those that found the sky
} counters;

#endif
