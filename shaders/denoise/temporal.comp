#version 450
#extension GL_GOOGLE_include_directive : require
// A-SVGF, temporal accumulation (Schied et al. 2017, section 4.1): each pixel's demodulated
// direct and indirect light join the running means of the surface it showed last frame,
// found by reprojection (the G-buffer's motion vector) as a bilinear blend of the four
// history records around that position that pass the disocclusion tests (same_surface), or,
// when none does, the mean of those of the 3x3 around it that do. The mean keeps at most
// `params.y` frames (the `accumulate` setting while nothing moves, a few frames while the
// camera moves, none after a cut); with no history the pixel starts again. The mean and
// variance of each channel's luminance are kept alike (the running variance in its
// incremental form, which half floats hold without the cancellation of raw second moments);
// the variance goes with the light to the spatial passes (signal, written at signal.y) and
// the records to this frame's history. With DENOISE_FLAG_GRADIENTS the temporal gradients
// of the 3x3 strata around the pixel's (gradient.comp: changes and luminances summed apart,
// as Quake II RTX's asvgf_gradient_atrous filters them) give how much the lighting changed,
// lambda in 0..1, and the history kept is shortened by lambda of its length, rounded to whole
// frames: where a light was switched the new light replaces the old at once, elsewhere
// nothing changes (the history is kept in whole frames, and the few per cent by which a
// forward-projected sample differs from its source while the camera moves would otherwise,
// truncated, take a frame off every frame and hold the history at 1).
// With SPECULAR_CHANNEL the specular channel is accumulated alike, through the same
// reprojection, with a history length of its own: its strata's gradients shorten it apart
// (a view-dependent highlight changes as the eye moves where diffuse light does not), and
// while the camera moves it keeps at most the moving history times roughness / 0.5 frames
// (at least 1): a highlight slides over its surface as the eye moves, the more the glossier
// the lobe, and the surface's motion vector does not follow it.

#include "denoise/common.glsl"
#include "trace/gradient.glsl"

// Last frame's records blended: light, mean and second moment of luminance (direct xy,
// indirect zw), history length.
// With the specular channel also its light, mean and second moment, history length.
struct Past {
    vec3 direct;
    vec3 indirect;
    vec4 moments;
    float frames;
    vec3 specular;
    vec2 specular_moments;
    float specular_frames;
};

const Past NO_PAST = Past(vec3(0.0), vec3(0.0), vec4(0.0), 0.0, vec3(0.0), vec2(0.0), 0.0);

void add_record(inout Past p, uint at, float w) {
    vec3 direct, indirect;
    unpack_light(light_previous[at].light, direct, indirect);
    HistoryMoments m = moments_previous[at];
    p.direct += w * direct;
    p.indirect += w * indirect;
    p.moments += w * vec4(raw_moments(m.direct), raw_moments(m.indirect));
    p.frames += w * history_frames(light_previous[at]);
    if (with_specular()) {
        HistorySpecular s = specular_previous[at];
        p.specular += w * specular_light(s);
        p.specular_moments += w * raw_moments(s.moments);
        p.specular_frames += w * specular_frames(s);
    }
}

// The blended history at the previous position `previous` (traced pixels, centres at .5) of
// the surface of `g`; weight 0 when no record there shows it.
float reproject(vec2 previous, GSample g, out Past blended) {
    blended = NO_PAST;
    vec2 p = previous - 0.5;
    ivec2 base = ivec2(floor(p));
    vec2 f = p - vec2(base);
    float total = 0.0;
    for (int k = 0; k < 4; k++) {
        ivec2 offset = ivec2(k & 1, k >> 1);
        int at = pixel_index(base + offset);
        if (at < 0 || !same_surface(uint(at), g)) {
            continue;
        }
        vec2 w2 = mix(1.0 - f, f, vec2(offset));
        float w = w2.x * w2.y;
        add_record(blended, uint(at), w);
        total += w;
    }
    if (total < 1e-3) {
        // An edge: the bilinear footprint straddles another surface; the matching records of
        // the 3x3 around the position, equally weighted.
        total = 0.0;
        blended = NO_PAST;
        ivec2 centre = ivec2(floor(previous));
        for (int dy = -1; dy <= 1; dy++) {
            for (int dx = -1; dx <= 1; dx++) {
                int at = pixel_index(centre + ivec2(dx, dy));
                if (at >= 0 && same_surface(uint(at), g)) {
                    add_record(blended, uint(at), 1.0);
                    total += 1.0;
                }
            }
        }
    }
    if (total > 0.0) {
        blended.direct /= total;
        blended.indirect /= total;
        blended.moments /= total;
        blended.frames /= total;
        blended.specular /= total;
        blended.specular_moments /= total;
        blended.specular_frames /= total;
    }
    return total;
}

// How much the lighting around `pixel` changed since last frame, 0..1: of the diffuse light
// (the larger of the direct and indirect channels') and of the specular, from the gradients
// of the 3x3 strata around its own.
vec2 lighting_change(ivec2 pixel) {
    ivec2 strata = ivec2(gradient_strata(pass.size.xy));
    ivec2 centre = pixel / int(GRADIENT_STRATUM);
    vec2 direct = vec2(0.0), indirect = vec2(0.0), specular = vec2(0.0);
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            ivec2 s = centre + ivec2(dx, dy);
            if (all(greaterThanEqual(s, ivec2(0))) && all(lessThan(s, strata))) {
                Gradient g = gradient[s.y * strata.x + s.x];
                direct += unpackHalf2x16(g.direct);
                indirect += unpackHalf2x16(g.indirect);
                specular += unpackHalf2x16(g.specular);
            }
        }
    }
    vec3 lambda = vec3(direct.y > 0.0 ? direct.x / direct.y : 0.0, indirect.y > 0.0 ? indirect.x / indirect.y : 0.0, specular.y > 0.0 ? specular.x / specular.y : 0.0);
    return clamp(vec2(max(lambda.x, lambda.y), lambda.z), 0.0, 1.0);
}

// Blends the sample `x` (light, luminance `l`) into a history of `frames` frames: its light
// `light`, luminance mean and variance `moments` (running mean and variance:
// m' = m + a (x - m), v' = (1 - a)(v + a (x - m)^2), the same as running means of the first
// two moments).
void accumulate(float frames, vec3 past, vec2 past_moments, inout vec3 x, inout float l, out float variance) {
    float alpha = 1.0 / (frames + 1.0);
    x = mix(past, x, alpha);
    float past_variance = max(past_moments.y - past_moments.x * past_moments.x, 0.0);
    float delta = l - past_moments.x;
    l = past_moments.x + alpha * delta;
    variance = (1.0 - alpha) * (past_variance + alpha * delta * delta);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    int at = pixel_index(pixel);
    if (at < 0) {
        return;
    }
    uint index = uint(at);
    GSample g = gbuffer[index];
    bool specular_on = with_specular();
    vec3 direct = g.direct;
    vec3 indirect = g.indirect;
    vec3 specular_now = g.specular;
    vec2 mean = vec2(luminance(direct), luminance(indirect));
    float specular_mean = luminance(specular_now);
    uint traced = packHalf2x16(min(mean, HALF_MAX));
    float traced_specular = min(specular_mean, HALF_MAX);
    vec2 variance = vec2(0.0);
    float specular_variance = 0.0;
    float roughness = unpackUnorm4x8(g.material).x;
    float cap = pass.params.y;
    float frames = 0.0;
    float specular_kept = 0.0;
    Past h;
    if (g.instance != MISS && cap > 0.0 && reproject(vec2(pixel) + 0.5 - g.motion, g, h) > 0.0) {
        frames = min(h.frames, cap);
        vec2 lambda = (pass.size.z & DENOISE_FLAG_GRADIENTS) != 0u ? lighting_change(pixel) : vec2(0.0);
        frames -= round(frames * lambda.x);
        accumulate(frames, h.direct, h.moments.xy, direct, mean.x, variance.x);
        accumulate(frames, h.indirect, h.moments.zw, indirect, mean.y, variance.y);
        if (specular_on) {
            bool moving = (pass.size.z & DENOISE_FLAG_FEEDBACK) != 0u;
            float specular_cap = moving ? max(1.0, round(cap * min(roughness / 0.5, 1.0))) : cap;
            specular_kept = min(h.specular_frames, specular_cap);
            specular_kept -= round(specular_kept * lambda.y);
            accumulate(specular_kept, h.specular, h.specular_moments, specular_now, specular_mean, specular_variance);
        }
    }
    frames += 1.0;
    specular_kept += 1.0;
    if (g.instance == MISS) {
        frames = 0.0;
        specular_kept = 0.0;
    }
    light[index] = HistoryLight(pack_light(direct, indirect), pack_frames_surface(frames, g.surface));
    moments[index] = HistoryMoments(packHalf2x16(min(vec2(mean.x, variance.x), HALF_MAX)), packHalf2x16(min(vec2(mean.y, variance.y), HALF_MAX)), traced);
    guide[index] = guide_of(g);
    signal[pass.signal.y + index] = Signal(pack_half4(vec4(direct, variance.x)), pack_half4(vec4(indirect, variance.y)));
    if (specular_on) {
        vec3 s = clamp(specular_now, -HALF_MAX, HALF_MAX);
        specular[index] = HistorySpecular(packHalf2x16(s.rg), packHalf2x16(vec2(s.b, traced_specular)),
            packHalf2x16(min(vec2(specular_mean, specular_variance), HALF_MAX)), uint(min(specular_kept, 65535.0)) | (uint(roughness * 65535.0 + 0.5) << 16));
        specular_signal[pass.specular.y + index] = SpecularSignal(pack_half4(vec4(specular_now, specular_variance)));
    }
}
