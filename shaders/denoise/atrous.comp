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
// With SPECULAR_CHANNEL (the first DENOISE_SPECULAR_ITERATIONS iterations: a specular
// lobe's light varies over shorter distances than diffuse light) the specular channel too,
// from specular.x to specular.y, with weights that follow its lobe: the normal weight's
// exponent grows as the roughness (of the centre's surface, kept in its specular history)
// falls, since the reflected direction turns twice as fast as the normal and a narrow lobe
// sees a different part of the scene after a small turn (Quake II RTX filters specular
// with narrower normal weights and fewer iterations alike).
// The taps' loop is left to the driver's compiler: unrolled with [[unroll]] the whole
// denoiser took 2.05 ms at 1920x1080 on an H200 against 1.95 ms (bench/denoise.md).

#include "denoise/common.glsl"

// Luminance edge-stopping: a difference of this many standard deviations weighs 1/e.
const float SIGMA_LUMINANCE = 4.0;
// Normal edge-stopping exponent.
const float SIGMA_NORMAL = 128.0;

// The specular channel's normal edge-stopping exponent at GGX alpha `alpha` (roughness²):
// SIGMA_NORMAL for the roughest lobes, ten times that at alpha 0.1 and below.
float specular_sigma_normal(float alpha) {
    return SIGMA_NORMAL / max(alpha, 0.1);
}

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
    bool specular_on = with_specular();
    if (g.view_z == 0.0) {
        signal[pass.signal.y + index] = packed;
        if (specular_on) {
            specular_signal[pass.specular.y + index] = specular_signal[pass.specular.x + index];
        }
        return;
    }
    vec4 centre_direct = unpack_half4(packed.direct);
    vec4 centre_indirect = unpack_half4(packed.indirect);
    int step = int(pass.size.w);
    // The variance of the centre, prefiltered (3x3 Gaussian) for a steadier edge-stop.
    // (direct, indirect, specular)
    vec3 variance = vec3(0.0);
    float vtotal = 0.0;
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            int q = pixel_index(pixel + ivec2(dx, dy));
            if (q >= 0) {
                float w = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
                Signal s = signal[pass.signal.x + uint(q)];
                float vs = specular_on ? unpackHalf2x16(specular_signal[pass.specular.x + uint(q)].light.y).y : 0.0;
                variance += w * vec3(unpackHalf2x16(s.direct.y).y, unpackHalf2x16(s.indirect.y).y, vs);
                vtotal += w;
            }
        }
    }
    variance /= vtotal;
    // A history longer than a moving camera keeps (still frames) averages more samples: the
    // variance of its mean shrinks with its length.
    float frames = history_frames(light[index]);
    HistorySpecular history_specular = specular_on ? specular[index] : HistorySpecular(0u, 0u, 0u, 0u);
    vec3 frames_each = vec3(frames, frames, specular_frames(history_specular));
    variance *= min(vec3(1.0), pass.params.w / max(frames_each, vec3(1.0)));
    vec3 phi = SIGMA_LUMINANCE * sqrt(max(variance, vec3(1e-10)));
    float roughness = specular_roughness(history_specular);
    float sigma_specular = specular_sigma_normal(roughness * roughness);
    // The eye distance's change per pixel (the smaller one-sided difference per axis).
    float z = g.view_z;
    float gx = min(abs(view_z_at(pixel + ivec2(1, 0), 1e30) - z), abs(view_z_at(pixel - ivec2(1, 0), 1e30) - z));
    float gy = min(abs(view_z_at(pixel + ivec2(0, 1), 1e30) - z), abs(view_z_at(pixel - ivec2(0, 1), 1e30) - z));
    float slope = min(length(vec2(gx, gy)), 0.1 * z);
    vec3 n = unpack_normal(g.normal);
    float lcd = luminance(centre_direct.rgb);
    float lci = luminance(centre_indirect.rgb);
    vec4 centre_specular = specular_on ? unpack_half4(specular_signal[pass.specular.x + index].light) : vec4(0.0);
    float lcs = luminance(centre_specular.rgb);

    const float kernel[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    vec4 direct = kernel[0] * kernel[0] * centre_direct * vec4(1.0, 1.0, 1.0, kernel[0] * kernel[0]);
    vec4 indirect = kernel[0] * kernel[0] * centre_indirect * vec4(1.0, 1.0, 1.0, kernel[0] * kernel[0]);
    vec4 specular_sum = kernel[0] * kernel[0] * centre_specular * vec4(1.0, 1.0, 1.0, kernel[0] * kernel[0]);
    vec3 total = vec3(kernel[0] * kernel[0]);
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
            float cosine = max(dot(n, unpack_normal(gq.normal)), 0.0);
            float kz = kernel[abs(dx)] * kernel[abs(dy)] * wz;
            float k = kz * pow(cosine, SIGMA_NORMAL);
            vec2 w = k * exp(-abs(vec2(luminance(sd.rgb) - lcd, luminance(si.rgb) - lci)) / phi.xy);
            direct += vec4(w.x * sd.rgb, w.x * w.x * sd.a);
            indirect += vec4(w.y * si.rgb, w.y * w.y * si.a);
            total.xy += w;
            if (specular_on) {
                vec4 ss = unpack_half4(specular_signal[pass.specular.x + uint(q)].light);
                float ws = kz * pow(cosine, sigma_specular) * exp(-abs(luminance(ss.rgb) - lcs) / phi.z);
                specular_sum += vec4(ws * ss.rgb, ws * ws * ss.a);
                total.z += ws;
            }
        }
    }
    direct /= vec4(vec3(total.x), total.x * total.x);
    indirect /= vec4(vec3(total.y), total.y * total.y);
    signal[pass.signal.y + index] = Signal(pack_half4(direct), pack_half4(indirect));
    bool feedback = (pass.size.z & DENOISE_FLAG_FEEDBACK) != 0u && step == 1;
    if (feedback) {
        light[index].light = pack_light(direct.rgb, indirect.rgb);
    }
    if (specular_on) {
        specular_sum /= vec4(vec3(total.z), total.z * total.z);
        specular_signal[pass.specular.y + index] = SpecularSignal(pack_half4(specular_sum));
        if (feedback) {
            specular[index] = with_specular_light(history_specular, specular_sum.rgb);
        }
    }
}
