// Tone mapping and display encoding of traced radiance, shared by the temporal pass
// (trace_resolve.comp) and the denoiser's last pass (denoise/modulate.comp).

#ifndef TRACE_TONEMAP_GLSL
#define TRACE_TONEMAP_GLSL

#include "generated/trace_constants.glsl"
#include "trace/pack.glsl"

// Tone mapping of linear radiance x by operator `op` (TONEMAP_*; render::trace::settings::Tonemap),
// `knee` the knee of TONEMAP_KNEE.
vec3 tonemap(vec3 x, uint op, float knee) {
    if (op == TONEMAP_KNEE) {
        // The identity up to the knee k, then a Reinhard shoulder that keeps
        // the value and slope at k and approaches 1: k + (1 - k) t / (1 + t), t = (x - k) / (1 - k).
        float k = knee;
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

// The display-encoded colour of exposed linear radiance x.
vec3 display_color(vec3 x, uint op, float knee) {
    return linear_to_srgb(tonemap(x, op, knee));
}

#endif
