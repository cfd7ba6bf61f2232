// Demodulation of the lighting channels by the primary hit's albedo (Schied et al. 2017,
// section 4.1): the denoiser filters light, and texture detail comes back when the filtered
// light is multiplied by the same albedo. The albedo is floored so that light reflected by
// black texels (specular) is kept: the division and the multiplication use the same factor,
// so remodulation gives back exactly what was traced.

#ifndef TRACE_CHANNELS_GLSL
#define TRACE_CHANNELS_GLSL

// The factor light is divided by at a primary hit of packed (unorm8) albedo `albedo`.
vec3 demodulating_albedo(uint albedo) {
    return max(unpackUnorm4x8(albedo).rgb, vec3(0.04));
}

#endif
