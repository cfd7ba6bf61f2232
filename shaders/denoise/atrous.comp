#version 450
#extension GL_GOOGLE_include_directive : require
// A-SVGF, one iteration of the edge-avoiding à-trous wavelet filter (Dammertz et al. 2010;
// Schied et al. 2017, section 4.3): a 5x5 B3-spline kernel whose taps are `size.w` pixels
// apart (1, 2, 4, ... over the iterations), each tap weighted by how alike its surface is
// (eye distance against the local depth slope, normals) and its light (luminance difference
// against the standard deviation of the centre's variance, prefiltered with a 3x3 Gaussian).
// The variance is filtered with the squared weights, so later iterations trust the light
// more. With DENOISE_FLAG_FEEDBACK the first iteration's light is this frame's history's.
// Reads the signal at signal.x, writes it at signal.y; the surfaces come from the packed
// guides (8 bytes a tap), the light from the packed signal (8 bytes a channel and tap).

#include "denoise/common.glsl"

// Luminance edge-stopping: a difference of this many standard deviations weighs 1/e.
const float SIGMA_LUMINANCE = 4.0;
// Normal edge-stopping exponent.
const float SIGMA_NORMAL = 128.0;

float view_z_at(ivec2 p, float fallback) {
    int at = pixel_index(p);
    float z = at < 0 ? 0.0 : guide[at].view_z;
    return z == 0.0 ? fallback : z;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    int at = pixel_index(pixel);
    if (at < 0) {
        return;
    }
    uint index = uint(at);
    Signal packed = signal[pass.signal.x + index];
    Guide g = guide[index];
    if (g.view_z == 0.0) {
        signal[pass.signal.y + index] = packed;
        return;
    }
    vec4 centre_direct = unpack_half4(packed.direct);
    vec4 centre_indirect = unpack_half4(packed.indirect);
    int step = int(pass.size.w);
    // The variance of the centre, prefiltered (3x3 Gaussian) for a steadier edge-stop.
    vec2 variance = vec2(0.0);
    float vtotal = 0.0;
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            int q = pixel_index(pixel + ivec2(dx, dy));
            if (q >= 0) {
                float w = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
                Signal s = signal[pass.signal.x + uint(q)];
                variance += w * vec2(unpackHalf2x16(s.direct.y).y, unpackHalf2x16(s.indirect.y).y);
                vtotal += w;
            }
        }
    }
    variance /= vtotal;
    // A history longer than a moving camera keeps (still frames) averages more samples: the
    // variance of its mean shrinks with its length.
    float frames = history_frames(light[index]);
    variance *= min(1.0, pass.params.w / max(frames, 1.0));
    vec2 phi = SIGMA_LUMINANCE * sqrt(max(variance, vec2(1e-10)));
    // The eye distance's change per pixel (the smaller one-sided difference per axis).
    float z = g.view_z;
    float gx = min(abs(view_z_at(pixel + ivec2(1, 0), 1e30) - z), abs(view_z_at(pixel - ivec2(1, 0), 1e30) - z));
    float gy = min(abs(view_z_at(pixel + ivec2(0, 1), 1e30) - z), abs(view_z_at(pixel - ivec2(0, 1), 1e30) - z));
    float slope = min(length(vec2(gx, gy)), 0.1 * z);
    vec3 n = unpack_normal(g.normal);
    float lcd = luminance(centre_direct.rgb);
    float lci = luminance(centre_indirect.rgb);

    const float kernel[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    vec4 direct = kernel[0] * kernel[0] * centre_direct * vec4(1.0, 1.0, 1.0, kernel[0] * kernel[0]);
    vec4 indirect = kernel[0] * kernel[0] * centre_indirect * vec4(1.0, 1.0, 1.0, kernel[0] * kernel[0]);
    vec2 total = vec2(kernel[0] * kernel[0]);
    for (int dy = -2; dy <= 2; dy++) {
        for (int dx = -2; dx <= 2; dx++) {
            if (dx == 0 && dy == 0) {
                continue;
            }
            ivec2 offset = ivec2(dx, dy) * step;
            int q = pixel_index(pixel + offset);
            if (q < 0) {
                continue;
            }
            Guide gq = guide[q];
            if (gq.view_z == 0.0) {
                continue;
            }
            Signal packed_q = signal[pass.signal.x + uint(q)];
            vec4 sd = unpack_half4(packed_q.direct);
            vec4 si = unpack_half4(packed_q.indirect);
            float wz = exp(-abs(gq.view_z - z) / (slope * length(vec2(offset)) + 1e-3 * z));
            float wn = pow(max(dot(n, unpack_normal(gq.normal)), 0.0), SIGMA_NORMAL);
            float k = kernel[abs(dx)] * kernel[abs(dy)] * wz * wn;
            vec2 w = k * exp(-abs(vec2(luminance(sd.rgb) - lcd, luminance(si.rgb) - lci)) / phi);
            direct += vec4(w.x * sd.rgb, w.x * w.x * sd.a);
            indirect += vec4(w.y * si.rgb, w.y * w.y * si.a);
            total += w;
        }
    }
    direct /= vec4(vec3(total.x), total.x * total.x);
    indirect /= vec4(vec3(total.y), total.y * total.y);
    signal[pass.signal.y + index] = Signal(pack_half4(direct), pack_half4(indirect));
    if ((pass.size.z & DENOISE_FLAG_FEEDBACK) != 0u && step == 1) {
        light[index].light = pack_light(direct.rgb, indirect.rgb);
    }
}
