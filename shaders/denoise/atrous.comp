#version 450
#extension GL_GOOGLE_include_directive : require
// A-SVGF, one iteration of the edge-avoiding à-trous wavelet filter (Dammertz et al. 2010;
// Schied et al. 2017, section 4.3): a 5x5 B3-spline kernel whose taps are `size.w` pixels
// apart (1, 2, 4, ... over the iterations), each tap weighted by how alike its surface is
// (eye distance against the local depth slope, normals) and its light (luminance difference
// against the standard deviation of the centre's variance, prefiltered with a 3x3 Gaussian).
// The variance is filtered with the squared weights, so later iterations trust the light
// more. With DENOISE_FLAG_FEEDBACK the first iteration's light is the history's (offsets.y).
// Reads the signal at offsets.z, writes it at offsets.w.

#include "denoise/common.glsl"

// Luminance edge-stopping: a difference of this many standard deviations weighs 1/e.
const float SIGMA_LUMINANCE = 4.0;
// Normal edge-stopping exponent.
const float SIGMA_NORMAL = 128.0;

float view_z_at(ivec2 p, float fallback) {
    int at = pixel_index(p);
    return at < 0 || gbuffer[at].instance == MISS ? fallback : gbuffer[at].view_z;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    int at = pixel_index(pixel);
    if (at < 0) {
        return;
    }
    uint index = uint(at);
    Signal centre = signal[pass.offsets.z + index];
    GSample g = gbuffer[index];
    if (g.instance == MISS) {
        signal[pass.offsets.w + index] = centre;
        return;
    }
    int step = int(pass.size.w);
    // The variance of the centre, prefiltered (3x3 Gaussian) for a steadier edge-stop.
    vec2 variance = vec2(0.0);
    float vtotal = 0.0;
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            int q = pixel_index(pixel + ivec2(dx, dy));
            if (q >= 0) {
                float w = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
                Signal s = signal[pass.offsets.z + uint(q)];
                variance += w * vec2(s.direct.a, s.indirect.a);
                vtotal += w;
            }
        }
    }
    variance /= vtotal;
    // A history longer than a moving camera keeps (still frames) averages more samples: the
    // variance of its mean shrinks with its length.
    float frames = history[pass.offsets.y + index].direct.a;
    variance *= min(1.0, pass.params.w / max(frames, 1.0));
    vec2 phi = SIGMA_LUMINANCE * sqrt(max(variance, vec2(1e-10)));
    // The eye distance's change per pixel (the smaller one-sided difference per axis).
    float z = g.view_z;
    float gx = min(abs(view_z_at(pixel + ivec2(1, 0), 1e30) - z), abs(view_z_at(pixel - ivec2(1, 0), 1e30) - z));
    float gy = min(abs(view_z_at(pixel + ivec2(0, 1), 1e30) - z), abs(view_z_at(pixel - ivec2(0, 1), 1e30) - z));
    float slope = min(length(vec2(gx, gy)), 0.1 * z);
    vec3 n = unpack_normal(g.normal);
    float lcd = luminance(centre.direct.rgb);
    float lci = luminance(centre.indirect.rgb);

    const float kernel[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    vec4 direct = kernel[0] * kernel[0] * centre.direct * vec4(1.0, 1.0, 1.0, kernel[0] * kernel[0]);
    vec4 indirect = kernel[0] * kernel[0] * centre.indirect * vec4(1.0, 1.0, 1.0, kernel[0] * kernel[0]);
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
            GSample gq = gbuffer[q];
            if (gq.instance == MISS) {
                continue;
            }
            Signal s = signal[pass.offsets.z + uint(q)];
            float wz = exp(-abs(gq.view_z - z) / (slope * length(vec2(offset)) + 1e-3 * z));
            float wn = pow(max(dot(n, unpack_normal(gq.normal)), 0.0), SIGMA_NORMAL);
            float k = kernel[abs(dx)] * kernel[abs(dy)] * wz * wn;
            vec2 w = k * exp(-abs(vec2(luminance(s.direct.rgb) - lcd, luminance(s.indirect.rgb) - lci)) / phi);
            direct += vec4(w.x * s.direct.rgb, w.x * w.x * s.direct.a);
            indirect += vec4(w.y * s.indirect.rgb, w.y * w.y * s.indirect.a);
            total += w;
        }
    }
    direct /= vec4(vec3(total.x), total.x * total.x);
    indirect /= vec4(vec3(total.y), total.y * total.y);
    signal[pass.offsets.w + index] = Signal(direct, indirect);
    if ((pass.size.z & DENOISE_FLAG_FEEDBACK) != 0u && step == 1) {
        history[pass.offsets.y + index].direct.rgb = direct.rgb;
        history[pass.offsets.y + index].indirect.rgb = indirect.rgb;
    }
}
