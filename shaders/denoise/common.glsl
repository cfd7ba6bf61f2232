// What the denoiser's passes share (src/render/denoise): the bindings of its descriptor sets,
// the push constants of a pass, the packed per-pixel records, and the test of whether a
// record of last frame shows the surface a pixel shows now.
//
// Every record is packed for the filter's memory traffic: light in half floats, the surface
// (normal and eye distance) in one 8-byte guide, each kind in its own tightly packed buffer.
// A frame's history is the three records `HistoryLight`, `HistoryMoments` and `Guide`
// (36 bytes a pixel), and with the specular channel (SPECULAR_CHANNEL) `HistorySpecular`
// (16 more); the last frame's are read (`*_previous`), this frame's written.

#ifndef DENOISE_COMMON_GLSL
#define DENOISE_COMMON_GLSL

#include "generated/denoise_constants.glsl"
#include "generated/trace_constants.glsl"
#include "trace/pack.glsl"
#include "trace/samples.glsl"

layout(local_size_x = TRACE_GROUP, local_size_y = TRACE_GROUP) in;

// One pass: mirrored by render::denoise::pipelines::DenoisePass.
layout(push_constant) uniform DenoisePass {
    vec4 params;    // exposure multiplier; history cap (frames, 0: none); tone-mapping knee;
                    // frames of a moving camera's history
    uvec4 size;     // traced width, height; DENOISE_FLAG_* bits; à-trous step (pixels)
    uvec2 signal;   // records (pixels) into `signal` read and written
    uvec2 specular; // records (pixels) into `specular_signal` read and written
} pass;

// The temporal light of one pixel: the demodulated direct and indirect light (half floats:
// direct rg, direct b and indirect r, indirect gb), the history length in frames (bits 0-15)
// and the tag of the material it is of (bits 16-31, surface_tag).
struct HistoryLight {
    uvec3 light;
    uint frames_surface;
};

// The running mean and variance of each channel's luminance (half floats: mean, variance),
// and the luminance of this frame's traced sample of each (half floats: direct, indirect),
// which next frame's gradient sample of the pixel is compared with.
struct HistoryMoments {
    uint direct;
    uint indirect;
    uint traced;
};

// The surface a pixel shows: its shading normal (octahedral, trace/pack.glsl) and eye-space
// distance (0: the primary ray missed).
struct Guide {
    uint normal;
    float view_z;
};

// Light and the variance of its luminance per channel, between the spatial passes (half
// floats: rg, then b and variance).
struct Signal {
    uvec2 direct;
    uvec2 indirect;
};

// The specular channel's history of one pixel (half floats): light rg; light b and the
// luminance of this frame's traced sample (which next frame's gradient sample is compared
// with); the running mean and variance of its luminance; its own history length in frames
// (bits 0-15: a glossy lobe keeps fewer frames while the camera moves) and the primary hit's
// roughness (unorm16, bits 16-31: the à-trous filter's lobe-aware weights).
struct HistorySpecular {
    uint light_rg;
    uint light_b_traced;
    uint moments;
    uint frames_roughness;
};

// The specular light and the variance of its luminance between the spatial passes (half
// floats: rg, then b and variance), in a buffer of its own: only the first
// DENOISE_SPECULAR_ITERATIONS à-trous iterations read it.
struct SpecularSignal {
    uvec2 light;
};

// The temporal gradient of one 3x3 stratum: per channel |change| and the larger of the two
// luminances (half floats), summed apart by the temporal pass.
struct Gradient {
    uint direct;
    uint indirect;
    uint specular;
};

layout(set = 0, binding = DENOISE_BINDING_GBUFFER, std430) readonly buffer GBuffer {
    GSample gbuffer[];
};

layout(set = 0, binding = DENOISE_BINDING_OUTPUT, std430) writeonly buffer Output {
    OutputSample outputs[];
};

layout(set = 0, binding = DENOISE_BINDING_LIGHT_PREVIOUS, std430) readonly buffer LightPrevious {
    HistoryLight light_previous[];
};

layout(set = 0, binding = DENOISE_BINDING_LIGHT, std430) buffer Light {
    HistoryLight light[];
};

layout(set = 0, binding = DENOISE_BINDING_MOMENTS_PREVIOUS, std430) readonly buffer MomentsPrevious {
    HistoryMoments moments_previous[];
};

layout(set = 0, binding = DENOISE_BINDING_MOMENTS, std430) buffer Moments {
    HistoryMoments moments[];
};

layout(set = 0, binding = DENOISE_BINDING_GUIDE_PREVIOUS, std430) readonly buffer GuidePrevious {
    Guide guide_previous[];
};

layout(set = 0, binding = DENOISE_BINDING_GUIDE, std430) buffer Guides {
    Guide guide[];
};

layout(set = 0, binding = DENOISE_BINDING_SIGNAL, std430) buffer Signals {
    Signal signal[];
};

// Per 3x3 stratum (trace/gradient.glsl): the temporal gradients.
layout(set = 0, binding = DENOISE_BINDING_GRADIENT, std430) buffer Gradients {
    Gradient gradient[];
};

layout(set = 0, binding = DENOISE_BINDING_SPECULAR_PREVIOUS, std430) readonly buffer SpecularPrevious {
    HistorySpecular specular_previous[];
};

layout(set = 0, binding = DENOISE_BINDING_SPECULAR, std430) buffer Specular {
    HistorySpecular specular[];
};

layout(set = 0, binding = DENOISE_BINDING_SPECULAR_SIGNAL, std430) buffer SpecularSignals {
    SpecularSignal specular_signal[];
};

// Whether this pass filters the specular channel too (else it holds nothing): a
// specialisation constant (render::denoise::pipelines), so that the pipelines without it
// hold none of its loads or arithmetic, and neither its registers.
layout(constant_id = DENOISE_SPECULAR_CONSTANT) const bool SPECULAR_CHANNEL = false;

bool with_specular() {
    return SPECULAR_CHANNEL;
}

// What the output shows (DENOISE_VIEW_*).
uint view() {
    return (pass.size.z >> DENOISE_VIEW_SHIFT) & DENOISE_VIEW_MASK;
}

const uint MISS = 0xffffffffu;

// The largest finite half float: packed values are clamped to it.
const float HALF_MAX = 65504.0;

float luminance(vec3 c) {
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

uvec2 pack_half4(vec4 v) {
    v = clamp(v, -HALF_MAX, HALF_MAX);
    return uvec2(packHalf2x16(v.xy), packHalf2x16(v.zw));
}

vec4 unpack_half4(uvec2 p) {
    return vec4(unpackHalf2x16(p.x), unpackHalf2x16(p.y));
}

uvec3 pack_light(vec3 direct, vec3 indirect) {
    uvec2 a = pack_half4(vec4(direct, indirect.r));
    return uvec3(a, packHalf2x16(clamp(indirect.gb, -HALF_MAX, HALF_MAX)));
}

void unpack_light(uvec3 p, out vec3 direct, out vec3 indirect) {
    vec4 a = unpack_half4(p.xy);
    direct = a.rgb;
    indirect = vec3(a.a, unpackHalf2x16(p.z));
}

// The 16-bit tag of a material key (render::trace::material::key) that a history keeps.
uint surface_tag(uint key) {
    return (key ^ (key >> 16)) & 0xffffu;
}

uint pack_frames_surface(float frames, uint key) {
    return uint(min(frames, 65535.0)) | (surface_tag(key) << 16);
}

float history_frames(HistoryLight h) {
    return float(h.frames_surface & 0xffffu);
}

float specular_frames(HistorySpecular h) {
    return float(h.frames_roughness & 0xffffu);
}

float specular_roughness(HistorySpecular h) {
    return float(h.frames_roughness >> 16) / 65535.0;
}

vec3 specular_light(HistorySpecular h) {
    return vec3(unpackHalf2x16(h.light_rg), unpackHalf2x16(h.light_b_traced).x);
}

// `h` with its light replaced by `light` (the traced luminance kept).
HistorySpecular with_specular_light(HistorySpecular h, vec3 light) {
    light = clamp(light, -HALF_MAX, HALF_MAX);
    h.light_rg = packHalf2x16(light.rg);
    h.light_b_traced = (h.light_b_traced & 0xffff0000u) | (packHalf2x16(vec2(light.b, 0.0)) & 0xffffu);
    return h;
}

// A pixel's guide from its G-buffer sample.
Guide guide_of(GSample g) {
    return g.instance == MISS ? Guide(0u, 0.0) : Guide(g.normal, g.view_z);
}

// The mean and second moment (x, y) of a packed mean and variance.
vec2 raw_moments(uint packed) {
    vec2 m = unpackHalf2x16(packed);
    return vec2(m.x, m.y + m.x * m.x);
}

// Whether the history of last frame at record `at` shows the surface of G-buffer sample `g`:
// it has one, of the same material (tag), where it was (eye distance within 5 %) and facing
// as it did (normals within about 25 degrees). A failed test is a disocclusion: the history
// there is dropped.
bool same_surface(uint at, GSample g) {
    HistoryLight h = light_previous[at];
    Guide s = guide_previous[at];
    return history_frames(h) > 0.0 && (h.frames_surface >> 16) == surface_tag(g.surface) && abs(s.view_z - g.view_z) <= 0.05 * g.view_z
        && dot(unpack_normal(s.normal), unpack_normal(g.normal)) > 0.9;
}

// The index of `pixel`, or -1 outside the traced image.
int pixel_index(ivec2 pixel) {
    ivec2 size = ivec2(pass.size.xy);
    return all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, size)) ? pixel.y * size.x + pixel.x : -1;
}

#endif
