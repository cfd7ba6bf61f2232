#version 450
#extension GL_GOOGLE_include_directive : require
// A-SVGF, the last pass: the filtered light of each channel (signal at signal.x, the specular
// channel's at specular.x with SPECULAR_CHANNEL) multiplied back by the factor it was
// divided by (trace/channels.glsl), plus the primary hit's own emission (the traced radiance
// less the three channels, unfiltered: baked light and emitters are not noisy); pixels whose
// ray missed keep their radiance. Then exposure, tone mapping and display encoding into the
// output the composite draws, as the temporal pass does. Other views (DENOISE_VIEW_*) show
// each pixel's history length, or one channel of this frame's traced sample remodulated, or
// all of them (unfiltered: the traced radiance again, through the channels).

#include "denoise/common.glsl"
#include "trace/channels.glsl"
#include "trace/tonemap.glsl"

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    int at = pixel_index(pixel);
    if (at < 0) {
        return;
    }
    uint index = uint(at);
    GSample g = gbuffer[index];
    uint shown = view();
    vec3 display;
    if (shown == DENOISE_VIEW_HISTORY) {
        display = vec3(min(history_frames(light[index]), 255.0) / 255.0);
    } else {
        vec3 color = g.radiance;
        if (g.instance != MISS) {
            vec3 albedo = demodulating_albedo(g.albedo);
            vec3 reflectance = demodulating_reflectance(g.albedo, g.material);
            vec3 direct = albedo * g.direct, indirect = albedo * g.indirect, specular = reflectance * g.specular;
            vec3 emission = max(g.radiance - direct - indirect - specular, vec3(0.0));
            if (shown == DENOISE_VIEW_COLOR) {
                Signal s = signal[pass.signal.x + index];
                vec3 filtered = albedo * max(unpack_half4(s.direct).rgb + unpack_half4(s.indirect).rgb, vec3(0.0));
                if (with_specular()) {
                    filtered += reflectance * max(unpack_half4(specular_signal[pass.specular.x + index].light).rgb, vec3(0.0));
                }
                color = emission + filtered;
            } else {
                color = shown == DENOISE_VIEW_DIRECT ? direct : shown == DENOISE_VIEW_INDIRECT ? indirect : shown == DENOISE_VIEW_SPECULAR ? specular : emission + direct + indirect + specular;
            }
        } else if (shown != DENOISE_VIEW_COLOR && shown != DENOISE_VIEW_UNFILTERED) {
            color = vec3(0.0);
        }
        display = display_color(color * pass.params.x, pass.size.z & DENOISE_FLAG_TONEMAP_MASK, pass.params.z);
    }
    outputs[index] = OutputSample(packUnorm4x8(vec4(display, 1.0)), g.depth);
}
