// What the denoiser's passes share (src/render/denoise): the bindings of its one descriptor
// set, the push constants of a pass, the per-pixel records, and the tests of whether two
// samples show the same surface.

#ifndef DENOISE_COMMON_GLSL
#define DENOISE_COMMON_GLSL

#include "generated/denoise_constants.glsl"
#include "generated/trace_constants.glsl"
#include "trace/pack.glsl"
#include "trace/samples.glsl"

layout(local_size_x = TRACE_GROUP, local_size_y = TRACE_GROUP) in;

// One pass: mirrored by render::denoise::pipelines::DenoisePass.
layout(push_constant) uniform DenoisePass {
    uvec4 size;     // traced width, height; DENOISE_FLAG_* bits; à-trous step (pixels)
    uvec4 offsets;  // records (pixels) into `history` read and written, into `signal` read and written
    vec4 params;    // exposure multiplier; history cap (frames, 0: none); tone-mapping knee;
                    // frames of a moving camera's history
} pass;

// The temporal history of one pixel.
struct History {
    vec4 direct;    // rgb: demodulated direct light; a: history length (frames)
    vec4 indirect;  // rgb: demodulated indirect light; a unused
    vec4 moments;   // first and second moments of luminance: direct (xy), indirect (zw)
    float view_z;   // what the history is of: eye-space distance, normal, material key
    uint normal;
    uint surface;
    uint pad;
};

// Light and the variance of its luminance per channel, between the spatial passes.
struct Signal {
    vec4 direct;    // rgb: light; a: variance
    vec4 indirect;
};

layout(set = 0, binding = DENOISE_BINDING_GBUFFER, std430) readonly buffer GBuffer {
    GSample gbuffer[];
};

layout(set = 0, binding = DENOISE_BINDING_OUTPUT, std430) writeonly buffer Output {
    OutputSample outputs[];
};

layout(set = 0, binding = DENOISE_BINDING_HISTORY, std430) buffer Histories {
    History history[];
};

layout(set = 0, binding = DENOISE_BINDING_SIGNAL, std430) buffer Signals {
    Signal signal[];
};

const uint MISS = 0xffffffffu;

float luminance(vec3 c) {
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// Whether history `h` (of the last frame) shows the surface of G-buffer sample `g`: the same
// material, where it was (eye distance within 5 %) and facing as it did (normals within
// about 25 degrees). A failed test is a disocclusion: the history there is dropped.
bool same_surface(History h, GSample g) {
    return h.direct.a > 0.0 && h.surface == g.surface && abs(h.view_z - g.view_z) <= 0.05 * g.view_z
        && dot(unpack_normal(h.normal), unpack_normal(g.normal)) > 0.9;
}

// The index of `pixel`, or -1 outside the traced image.
int pixel_index(ivec2 pixel) {
    ivec2 size = ivec2(pass.size.xy);
    return all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, size)) ? pixel.y * size.x + pixel.x : -1;
}

#endif
