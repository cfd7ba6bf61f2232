#version 450
#extension GL_GOOGLE_include_directive : require
// A-SVGF, variance estimation (Schied et al. 2017, section 4.2): where a pixel's history is
// younger than DENOISE_YOUNG_HISTORY frames its temporal variance says little, so it is
// estimated from the moments of the 7x7 pixels around it on the same surface (depth and
// normal weights as in the à-trous filter), and raised for the youngest histories so that
// the filter blurs them more. Older pixels pass through. Reads the signal at offsets.z and
// this frame's history (offsets.y), writes the signal at offsets.w.

#include "denoise/common.glsl"

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    int at = pixel_index(pixel);
    if (at < 0) {
        return;
    }
    uint index = uint(at);
    Signal s = signal[pass.offsets.z + index];
    History centre = history[pass.offsets.y + index];
    float frames = centre.direct.a;
    if (frames >= float(DENOISE_YOUNG_HISTORY) || frames == 0.0) {
        signal[pass.offsets.w + index] = s;
        return;
    }
    vec3 n = unpack_normal(centre.normal);
    vec4 moments = vec4(0.0);
    float total = 0.0;
    for (int dy = -3; dy <= 3; dy++) {
        for (int dx = -3; dx <= 3; dx++) {
            int q = pixel_index(pixel + ivec2(dx, dy));
            if (q < 0) {
                continue;
            }
            History h = history[pass.offsets.y + uint(q)];
            if (h.direct.a == 0.0) {
                continue;
            }
            float wz = exp(-abs(h.view_z - centre.view_z) / (0.02 * centre.view_z * length(vec2(dx, dy)) + 1e-6));
            float wn = pow(max(dot(n, unpack_normal(h.normal)), 0.0), 128.0);
            float w = wz * wn;
            moments += w * h.moments;
            total += w;
        }
    }
    moments /= max(total, 1e-6);
    vec2 variance = max(moments.yw - moments.xz * moments.xz, vec2(0.0)) * (float(DENOISE_YOUNG_HISTORY) / frames);
    s.direct.a = variance.x;
    s.indirect.a = variance.y;
    signal[pass.offsets.w + index] = s;
}
