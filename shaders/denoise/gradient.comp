#version 450
#extension GL_GOOGLE_include_directive : require
// A-SVGF, temporal gradients (Schied et al. 2018, section 4; Quake II RTX's
// asvgf_gradient_img): one invocation per 3x3 stratum of traced pixels. Its gradient sample
// (trace/gradient.glsl, the stratum's G-buffer record after the pixels'), traced this frame
// by the tracer's gradient pass with last frame's random numbers of its source pixel over the
// surface point the source saw (trace/forward_projection.glsl), is compared with the sample
// last frame traced at the source (the history's `traced` luminance there): the change of each
// channel's luminance and the larger of the two, summed apart over strata by the temporal
// pass, whose ratio is how much the lighting changed (0: not at all, 1: entirely); with
// SPECULAR_CHANNEL the specular channel's too (zeros without). Strata without a valid
// sample write zeros.

#include "denoise/common.glsl"
#include "trace/gradient.glsl"

void main() {
    uvec2 stratum = gl_GlobalInvocationID.xy;
    uvec2 strata = gradient_strata(pass.size.xy);
    if (any(greaterThanEqual(stratum, strata))) {
        return;
    }
    Gradient change = Gradient(0u, 0u, 0u);
    GSample g = gbuffer[gradient_record(stratum, pass.size.xy)];
    uint source = g.gradient - 1u;
    if (g.gradient != 0u && g.instance != MISS && same_surface(source, g)) {
        // Rounded as the history's is, so that an unchanged sample differs by nothing.
        vec3 now = vec3(luminance(g.direct), luminance(g.indirect), luminance(g.specular));
        now = vec3(unpackHalf2x16(packHalf2x16(min(now.xy, HALF_MAX))), unpackHalf2x16(packHalf2x16(vec2(min(now.z, HALF_MAX), 0.0))).x);
        vec3 before = vec3(unpackHalf2x16(moments_previous[source].traced), 0.0);
        if (with_specular()) {
            before.z = unpackHalf2x16(specular_previous[source].light_b_traced).y;
        }
        vec3 difference = abs(now - before);
        vec3 larger = max(now, before);
        change = Gradient(packHalf2x16(vec2(difference.x, larger.x)), packHalf2x16(vec2(difference.y, larger.y)), packHalf2x16(vec2(difference.z, larger.z)));
    }
    gradient[stratum.y * strata.x + stratum.x] = change;
}
