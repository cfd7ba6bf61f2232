// The surface model of traced GL geometry: Lambertian diffuse plus a GGX specular lobe
// (metalness workflow). Shared by every back end: evaluation, sampling and its density.

#ifndef TRACE_BRDF_GLSL
#define TRACE_BRDF_GLSL

#include "trace/sampling.glsl"

struct Surface {
    vec3 position;      // eye space
    vec3 normal;        // shading normal, on the side the ray came from
    vec3 geometric;     // geometric normal, on the side the ray came from
    vec3 albedo;        // linear
    vec3 emission;      // linear radiance it emits
    vec3 sampled_emission; // the part of `emission` that next-event estimation samples (emitters.glsl)
    float emitter_density; // the probability density per unit area (eye space) that emitter sampling picks this point; 0 when not listed
    float roughness;
    float metalness;
    float specular;     // dielectric F0
    float alpha;        // coverage (texture and colour alpha)
    bool baked;         // its light is baked: emission is all it sends, it reflects nothing
};

// Reflectance at normal incidence.
vec3 brdf_f0(Surface s) {
    return mix(vec3(s.specular), s.albedo, s.metalness);
}

// Probability of sampling the specular lobe (0 for a pure Lambertian surface).
float brdf_specular_probability(Surface s) {
    vec3 f0 = brdf_f0(s);
    return clamp(max(max(f0.r, f0.g), f0.b) + s.metalness, 0.0, 1.0);
}

vec3 fresnel_schlick(vec3 f0, float c) {
    float m = 1.0 - c;
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

float ggx_alpha(Surface s) {
    return max(s.roughness * s.roughness, 1e-3);
}

// The reflectance of the Lambertian lobe: the share of an irradiance it reflects.
vec3 brdf_diffuse_albedo(Surface s) {
    return s.albedo * (1.0 - s.metalness) * (1.0 - s.specular);
}

// The Lambertian lobe of brdf_eval_cos alone.
vec3 brdf_diffuse_cos(Surface s, vec3 v, vec3 l) {
    float nl = dot(s.normal, l);
    if (nl <= 0.0 || dot(s.normal, v) <= 0.0 || dot(s.geometric, l) <= 0.0) {
        return vec3(0.0);
    }
    return brdf_diffuse_albedo(s) / PI * nl;
}

// The GGX specular lobe of brdf_eval_cos alone (the denoiser's specular channel,
// trace/channels.glsl).
vec3 brdf_specular_cos(Surface s, vec3 v, vec3 l) {
    float nl = dot(s.normal, l);
    float nv = dot(s.normal, v);
    if (nl <= 0.0 || nv <= 0.0 || dot(s.geometric, l) <= 0.0 || brdf_specular_probability(s) <= 0.0) {
        return vec3(0.0);
    }
    vec3 h = normalize(v + l);
    float alpha = ggx_alpha(s);
    float d = ggx_d(max(dot(s.normal, h), 0.0), alpha);
    float g = ggx_g1(nv, alpha) * ggx_g1(nl, alpha);
    return fresnel_schlick(brdf_f0(s), max(dot(v, h), 0.0)) * (d * g / (4.0 * nv));
}

// f(v, l) * cos(n, l): the reflected radiance per unit incident radiance from l.
vec3 brdf_eval_cos(Surface s, vec3 v, vec3 l) {
    return brdf_diffuse_cos(s, v, l) + brdf_specular_cos(s, v, l);
}

// The density of brdf_sample() choosing l (solid angle).
float brdf_pdf(Surface s, vec3 v, vec3 l) {
    float nl = dot(s.normal, l);
    if (nl <= 0.0) {
        return 0.0;
    }
    float ps = brdf_specular_probability(s);
    float pdf = (1.0 - ps) * nl / PI;
    if (ps > 0.0) {
        vec3 h = normalize(v + l);
        float alpha = ggx_alpha(s);
        float nv = max(dot(s.normal, v), 1e-6);
        pdf += ps * ggx_g1(nv, alpha) * ggx_d(max(dot(s.normal, h), 0.0), alpha) / (4.0 * nv);
    }
    return pdf;
}

// Samples an incident direction; `specular` says which lobe was chosen. Returns false when
// the sample is below the surface.
bool brdf_sample(Surface s, vec3 v, vec3 u, out vec3 l, out bool specular) {
    float ps = brdf_specular_probability(s);
    specular = u.z < ps;
    if (specular) {
        mat3 frame = basis(s.normal);
        vec3 local_v = transpose(frame) * v;
        vec3 h = frame * sample_ggx_vndf(local_v, ggx_alpha(s), u.xy);
        l = reflect(-v, h);
    } else {
        l = sample_cosine(s.normal, u.xy);
    }
    return dot(s.normal, l) > 0.0 && dot(s.geometric, l) > 0.0;
}

#endif
