// Packing and colour encoding shared by the tracing shaders.

#ifndef TRACE_PACK_GLSL
#define TRACE_PACK_GLSL

// sRGB transfer functions (IEC 61966-2-1): GL colours and texels are display-encoded; light is
// transported in linear units.

// The decoding curve, continued past 1 (for scaled values, c >= 0).
vec3 srgb_decode(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

vec3 srgb_to_linear(vec3 c) {
    return srgb_decode(clamp(c, 0.0, 1.0));
}

vec3 linear_to_srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

// Octahedral encoding of a unit vector into two snorm16 (Cigolle et al. 2014).
vec2 oct_wrap(vec2 v) {
    return (1.0 - abs(v.yx)) * mix(vec2(-1.0), vec2(1.0), greaterThanEqual(v, vec2(0.0)));
}

uint pack_normal(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.z >= 0.0 ? n.xy : oct_wrap(n.xy);
    return packSnorm2x16(e);
}

vec3 unpack_normal(uint packed) {
    vec2 e = unpackSnorm2x16(packed);
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) {
        n.xy = oct_wrap(n.xy);
    }
    return normalize(n);
}

#endif
