#version 450
#extension GL_GOOGLE_include_directive : require
// The compute path tracer's temporal pass: each pixel's new radiance joins the running mean
// of the pixel it came from last frame (reprojected with the G-buffer's motion vector,
// rejected when depth, normal or material disagree), capped at frame.params.y frames (the setting
// `accumulate` while nothing moves, a few frames while the camera moves, 0 after a cut);
// then exposure, tone mapping and sRGB encoding for the composite. The A-SVGF denoiser
// (shaders/denoise/, `[denoise] enabled`) replaces this pass, reading the same G-buffer.

#include "trace/scene.glsl"
#include "trace/pack.glsl"
#include "trace/gbuffer.glsl"
#include "trace/tonemap.glsl"

layout(local_size_x = TRACE_GROUP, local_size_y = TRACE_GROUP) in;

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
    vec3 display = display_color(mean * frame.params.x, frame.flags.x & FRAME_TONEMAP_MASK, frame.params.z);
    outputs[index] = OutputSample(packUnorm4x8(vec4(display, 1.0)), g.depth);
}
