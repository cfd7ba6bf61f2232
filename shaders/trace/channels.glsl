// Demodulation of the lighting channels (Schied et al. 2017, section 4.1): the denoiser
// filters light, and texture detail comes back when the filtered light is multiplied by the
// same factor. The diffuse channels (direct, indirect) are divided by the primary hit's albedo,
// the specular channel by the directional albedo of its specular lobe (the share of light from
// all directions the GGX lobe reflects towards the eye: Karis' analytic fit of the split-sum
// integral, "Physically based shading on mobile", 2014, as NRD and Quake II RTX demodulate
// specular by a pre-integrated reflectance), computed from the G-buffer's packed albedo and
// material (pack_material), so that tracer and denoiser use exactly the same factor. Both are
// floored so that light reflected by black texels is kept: the division and the
// multiplication use the same factor, so remodulation gives back exactly what was traced.

#ifndef TRACE_CHANNELS_GLSL
#define TRACE_CHANNELS_GLSL

// The factor diffuse light is divided by at a primary hit of packed (unorm8) albedo `albedo`.
vec3 demodulating_albedo(uint albedo) {
    return max(unpackUnorm4x8(albedo).rgb, vec3(0.04));
}

// The G-buffer's material word of a primary hit: roughness, metalness, dielectric F0 and the
// cosine between shading normal and view direction, unorm8 each.
uint pack_material(float roughness, float metalness, float specular, float nv) {
    return packUnorm4x8(vec4(roughness, metalness, specular, nv));
}

// The factor specular light is divided by at a primary hit of packed albedo `albedo` and
// material `material` (pack_material): F0 * A + B of the split-sum fit, floored at 0.01.
vec3 demodulating_reflectance(uint albedo, uint material) {
    vec4 m = unpackUnorm4x8(material);
    vec3 f0 = mix(vec3(m.z), unpackUnorm4x8(albedo).rgb, m.y);
    vec4 r = m.x * vec4(-1.0, -0.0275, -0.572, 0.022) + vec4(1.0, 0.0425, 1.04, -0.04);
    float a004 = min(r.x * r.x, exp2(-9.28 * m.w)) * r.x + r.y;
    vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
    return max(f0 * ab.x + ab.y, vec3(0.01));
}

// A share per colour (0..1) packed in one word, 10 bits each: what a path carries of its
// primary hit through its bounces (trace/path.glsl), the light of its continuation ray split
// by it (exactly: the diffuse part is the rest).
uint pack_share(vec3 share) {
    uvec3 q = uvec3(round(clamp(share, 0.0, 1.0) * 1023.0));
    return q.r | (q.g << 10) | (q.b << 20);
}

vec3 unpack_share(uint packed) {
    return vec3(uvec3(packed, packed >> 10, packed >> 20) & 1023u) / 1023.0;
}

#endif
