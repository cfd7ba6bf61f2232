#version 450
#extension GL_GOOGLE_include_directive : require
// A-SVGF, temporal accumulation (Schied et al. 2017, section 4.1): each pixel's demodulated
// direct and indirect light join the running means of the surface it showed last frame,
// found by reprojection (the G-buffer's motion vector) as a bilinear blend of the four
// history records around that position that pass the disocclusion tests (same_surface), or,
// when none does, the mean of those of the 3x3 around it that do. The mean keeps at most
// `params.y` frames (the `accumulate` setting while nothing moves, a few frames while the
// camera moves, none after a cut); with no history the pixel starts again. The first and
// second moments of each channel's luminance are accumulated alike; their variance goes with
// the light to the spatial passes (signal, written at offsets.w) and the record to the
// history of this frame (offsets.y).

#include "denoise/common.glsl"

// The blended history at the previous position `previous` (traced pixels, centres at .5) of
// the surface of `g`; weight 0 when no record there shows it.
float reproject(vec2 previous, GSample g, out History blended) {
    blended = History(vec4(0.0), vec4(0.0), vec4(0.0), 0.0, 0u, 0u, 0u);
    vec2 p = previous - 0.5;
    ivec2 base = ivec2(floor(p));
    vec2 f = p - vec2(base);
    float total = 0.0;
    for (int k = 0; k < 4; k++) {
        ivec2 offset = ivec2(k & 1, k >> 1);
        int at = pixel_index(base + offset);
        if (at < 0) {
            continue;
        }
        History h = history[pass.offsets.x + uint(at)];
        if (!same_surface(h, g)) {
            continue;
        }
        vec2 w2 = mix(1.0 - f, f, vec2(offset));
        float w = w2.x * w2.y;
        blended.direct += w * h.direct;
        blended.indirect += w * h.indirect;
        blended.moments += w * h.moments;
        total += w;
    }
    if (total < 1e-3) {
        // An edge: the bilinear footprint straddles another surface; the matching records of
        // the 3x3 around the position, equally weighted.
        total = 0.0;
        blended = History(vec4(0.0), vec4(0.0), vec4(0.0), 0.0, 0u, 0u, 0u);
        ivec2 centre = ivec2(floor(previous));
        for (int dy = -1; dy <= 1; dy++) {
            for (int dx = -1; dx <= 1; dx++) {
                int at = pixel_index(centre + ivec2(dx, dy));
                if (at < 0) {
                    continue;
                }
                History h = history[pass.offsets.x + uint(at)];
                if (same_surface(h, g)) {
                    blended.direct += h.direct;
                    blended.indirect += h.indirect;
                    blended.moments += h.moments;
                    total += 1.0;
                }
            }
        }
    }
    if (total > 0.0) {
        blended.direct /= total;
        blended.indirect /= total;
        blended.moments /= total;
    }
    return total;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    int at = pixel_index(pixel);
    if (at < 0) {
        return;
    }
    uint index = uint(at);
    GSample g = gbuffer[index];
    vec3 direct = g.direct.rgb;
    vec3 indirect = g.indirect.rgb;
    float ld = luminance(direct);
    float li = luminance(indirect);
    vec4 moments = vec4(ld, ld * ld, li, li * li);
    float cap = pass.params.y;
    float frames = 0.0;
    History h;
    if (g.instance != MISS && cap > 0.0 && reproject(vec2(pixel) + 0.5 - g.motion, g, h) > 0.0) {
        frames = min(h.direct.a, cap);
        float alpha = 1.0 / (frames + 1.0);
        direct = mix(h.direct.rgb, direct, alpha);
        indirect = mix(h.indirect.rgb, indirect, alpha);
        moments = mix(h.moments, moments, alpha);
    }
    frames += 1.0;
    if (g.instance == MISS) {
        frames = 0.0;
    }
    history[pass.offsets.y + index] = History(vec4(direct, frames), vec4(indirect, 0.0), moments, g.view_z, g.normal, g.surface, 0u);
    vec2 variance = max(moments.yw - moments.xz * moments.xz, vec2(0.0));
    signal[pass.offsets.w + index] = Signal(vec4(direct, variance.x), vec4(indirect, variance.y));
}
