#version 450
#extension GL_GOOGLE_include_directive : require
// A-SVGF, the last pass: the filtered light of each channel (signal at signal.x) multiplied
// back by the albedo it was divided by (trace/channels.glsl), plus the primary hit's own
// emission (the traced radiance less both channels, unfiltered: baked light and emitters are
// not noisy); pixels whose ray missed keep their radiance. Then exposure, tone mapping and
// display encoding into the output the composite draws, as the temporal pass does. With
// DENOISE_FLAG_VIEW_HISTORY the output is each pixel's history length instead.

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
    vec3 display;
    if ((pass.size.z & DENOISE_FLAG_VIEW_HISTORY) != 0u) {
        display = vec3(min(history_frames(light[index]), 255.0) / 255.0);
    } else {
        vec3 color = g.radiance.rgb;
        if (g.instance != MISS) {
            Signal s = signal[pass.signal.x + index];
            vec3 albedo = demodulating_albedo(g.albedo);
            vec3 emission = max(g.radiance.rgb - albedo * (g.direct.rgb + g.indirect.rgb), vec3(0.0));
            color = emission + albedo * max(unpack_half4(s.direct).rgb + unpack_half4(s.indirect).rgb, vec3(0.0));
        }
        display = display_color(color * pass.params.x, pass.size.z & DENOISE_FLAG_TONEMAP_MASK, pass.params.z);
    }
    outputs[index] = OutputSample(packUnorm4x8(vec4(display, 1.0)), g.depth);
}
