#version 450
#extension GL_GOOGLE_include_directive : require
// A-SVGF, variance estimation (Schied et al. 2017, section 4.2): where a pixel's history is
// younger than DENOISE_YOUNG_HISTORY frames its temporal variance says little, so it is
// estimated from the moments of the 7x7 pixels around it on the same surface (depth and
// normal weights as in the à-trous filter), and raised for the youngest histories so that
// the filter blurs them more. Older pixels pass through. Reads the signal at signal.x and
// this frame's history, writes the signal at signal.y; with SPECULAR_CHANNEL the
// specular channel alike (its own history length), in place at specular.x.

#include "denoise/common.glsl"

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    int at = pixel_index(pixel);
    if (at < 0) {
        return;
    }
    uint index = uint(at);
    Signal s = signal[pass.signal.x + index];
    float frames = history_frames(light[index]);
    bool young = frames < float(DENOISE_YOUNG_HISTORY) && frames > 0.0;
    // The specular channel keeps its signal in place (written by the temporal pass, read at
    // pass.specular.x) and is estimated where its own history is young.
    float frames_specular = with_specular() ? specular_frames(specular[index]) : 0.0;
    bool young_specular = frames_specular < float(DENOISE_YOUNG_HISTORY) && frames_specular > 0.0;
    if (!young) {
        signal[pass.signal.y + index] = s;
    }
    if (!young && !young_specular) {
        return;
    }
    Guide centre = guide[index];
    vec3 n = unpack_normal(centre.normal);
    vec4 sum = vec4(0.0);
    vec2 sum_specular = vec2(0.0);
    float total = 0.0;
    for (int dy = -3; dy <= 3; dy++) {
        for (int dx = -3; dx <= 3; dx++) {
            int q = pixel_index(pixel + ivec2(dx, dy));
            if (q < 0) {
                continue;
            }
            Guide gq = guide[q];
            if (gq.view_z == 0.0) {
                continue;
            }
            float wz = exp(-abs(gq.view_z - centre.view_z) / (0.02 * centre.view_z * length(vec2(dx, dy)) + 1e-6));
            float wn = pow(max(dot(n, unpack_normal(gq.normal)), 0.0), 128.0);
            float w = wz * wn;
            if (young) {
                HistoryMoments m = moments[q];
                sum += w * vec4(raw_moments(m.direct), raw_moments(m.indirect));
            }
            if (young_specular) {
                sum_specular += w * raw_moments(specular[q].moments);
            }
            total += w;
        }
    }
    total = max(total, 1e-6);
    if (young) {
        sum /= total;
        vec2 variance = max(sum.yw - sum.xz * sum.xz, vec2(0.0)) * (float(DENOISE_YOUNG_HISTORY) / frames);
        vec4 direct = unpack_half4(s.direct);
        vec4 indirect = unpack_half4(s.indirect);
        signal[pass.signal.y + index] = Signal(pack_half4(vec4(direct.rgb, variance.x)), pack_half4(vec4(indirect.rgb, variance.y)));
    }
    if (young_specular) {
        sum_specular /= total;
        float variance = max(sum_specular.y - sum_specular.x * sum_specular.x, 0.0) * (float(DENOISE_YOUNG_HISTORY) / frames_specular);
        uint at_specular = pass.specular.x + index;
        vec4 light = unpack_half4(specular_signal[at_specular].light);
        specular_signal[at_specular] = SpecularSignal(pack_half4(vec4(light.rgb, variance)));
    }
}
