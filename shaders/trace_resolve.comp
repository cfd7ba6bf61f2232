#version 450
#extension GL_GOOGLE_include_directive : require
// The compute path tracer's temporal pass: each pixel's new radiance joins the running mean
// of the pixel it came from last frame (reprojected with the G-buffer's motion vector,
// rejected when depth, normal or material disagree), capped at frame.params.y frames (the setting
// `accumulate` while nothing moves, a few frames while the camera moves, 0 after a cut);
// then exposure, tone mapping and sRGB encoding for the composite. The A-SVGF denoiser of a
// later issue replaces this pass, reading the same G-buffer.

#include "trace/scene.glsl"
#include "trace/pack.glsl"
#include "trace/gbuffer.glsl"

layout(local_size_x = TRACE_GROUP, local_size_y = TRACE_GROUP) in;

// Tone mapping of linear radiance x by operator `op` (TONEMAP_*; render::trace::settings::Tonemap).
vec3 tonemap(vec3 x, uint op) {
    if (op == TONEMAP_KNEE) {
        // The identity up to the knee k (frame.params.z), then a Reinhard shoulder that keeps
        // the value and slope at k and approaches 1: k + (1 - k) t / (1 + t), t = (x - k) / (1 - k).
        float k = frame.params.z;
        vec3 t = max(x - k, 0.0) / (1.0 - k);
        return min(max(x, 0.0), vec3(k)) + (1.0 - k) * t / (1.0 + t);
    }
    if (op == TONEMAP_REINHARD) {
        return x / (1.0 + x);
    }
    if (op == TONEMAP_ACES) {
        // ACES filmic curve fitted by Narkowicz (2015).
        return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
    }
    return clamp(x, 0.0, 1.0);
}

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    uvec2 size = frame.size.xy;
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    uint index = pixel.y * size.x + pixel.x;
    GSample g = gbuffer[index];
    vec3 color = g.radiance.rgb;
    float frames = 0.0;
    vec3 mean = color;
    float cap = frame.params.y;
    uint material = g.instance != 0xffffffffu ? materials[instances[g.instance].material].key : 0u;
    if (g.instance != 0xffffffffu && cap > 0.0) {
        vec2 previous = vec2(pixel) + 0.5 - g.motion;
        if (all(greaterThanEqual(previous, vec2(0.0))) && all(lessThan(previous, vec2(size)))) {
            AccumSample h = history[uint(previous.y) * size.x + uint(previous.x)];
            // The same surface: where it was, facing as it did, showing the same material.
            bool same_surface = h.color.a > 0.0 && abs(h.view_z - g.view_z) <= 0.05 * g.view_z
                && dot(unpack_normal(h.normal), unpack_normal(g.normal)) > 0.9 && h.material == material;
            if (same_surface) {
                frames = min(h.color.a, cap);
                mean = h.color.rgb;
            }
        }
    }
    frames += 1.0;
    mean += (color - mean) / frames;
    if (g.instance == 0xffffffffu) {
        frames = 0.0;
    }
    accumulation[index] = AccumSample(vec4(mean, frames), g.view_z, g.normal, material, 0u);
    vec3 display = linear_to_srgb(tonemap(mean * frame.params.x, frame.flags.x & FRAME_TONEMAP_MASK));
    outputs[index] = OutputSample(packUnorm4x8(vec4(display, 1.0)), g.depth);
}
