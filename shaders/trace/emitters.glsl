// Next-event estimation of emissive surfaces (render::trace::emitters): one triangle of the
// frame's emitter list drawn in proportion to its estimated power (alias method), one point
// drawn uniformly on it, one shadow ray. Paths that reach an emitter by their continuation
// ray count its light too, so both strategies are weighted by the power heuristic (multiple
// importance sampling, Veach 1997): each light path is counted once, by the strategy more
// likely to find it. Only the emission the list samples (Surface.sampled_emission: emission
// passes and emissive materials) is weighted; the rest (a baked surface's raster colour) is
// found by continuation rays alone.

#ifndef TRACE_EMITTERS_GLSL
#define TRACE_EMITTERS_GLSL

#include "trace/lights.glsl"

// The power-heuristic weight of a strategy of density a against one of density b.
float mis_weight(float a, float b) {
    float a2 = a * a;
    return a2 / max(a2 + b * b, 1e-30);
}

// The density per unit solid angle, seen from the ray's origin, with which emitter sampling
// picks the point of surface s that a ray reached after travelling t at cosine `cos_hit` to
// its geometric normal.
float emitter_solid_angle_density(Surface s, float t, float cos_hit) {
    return s.emitter_density * t * t / max(cos_hit, 1e-6);
}

// The light reflected towards v at s from one emitter sample where its shadow ray is not
// occluded; `weighted`: the continuation ray leaving s also counts emitters it hits,
// so the sample takes its MIS weight (at the last vertex of a path it does not, and the
// sample counts whole). The emitter's texels are read at the width of a ray cone of
// `cone_width` at s spreading by `spread` (radians).
ShadowSample emitter_light(Surface s, vec3 v, float cone_width, float spread, bool weighted, inout Rng rng) {
    uint count = frame.flags.z;
    uint i = min(uint(rng_next(rng) * float(count)), count - 1u);
    Emitter e = emitters[i];
    if (rng_next(rng) >= e.threshold) {
        e = emitters[e.alias];
    }
    vec2 u = rng_next2(rng);
    float su = sqrt(u.x);
    vec2 bary = vec2(su * (1.0 - u.y), su * u.y);
    Instance inst = instances[e.instance];
    vec3 p0, p1, p2;
    trace_triangle_vertices(e.triangle, p0, p1, p2);
    p0 = instance_transform(inst.object_to_eye, vec4(p0, 1.0));
    p1 = instance_transform(inst.object_to_eye, vec4(p1, 1.0));
    p2 = instance_transform(inst.object_to_eye, vec4(p2, 1.0));
    vec3 n = cross(p1 - p0, p2 - p0);
    float area2 = length(n);
    vec3 to = p0 * (1.0 - bary.x - bary.y) + p1 * bary.x + p2 * bary.y - s.position;
    float d2 = dot(to, to);
    if (area2 <= 0.0 || d2 <= 0.0 || e.probability <= 0.0) {
        return unshadowed(vec3(0.0));
    }
    float d = sqrt(d2);
    vec3 l = to / d;
    float cos_light = abs(dot(n, l)) / area2;
    vec3 fs = brdf_specular_cos(s, v, l);
    vec3 f = brdf_diffuse_cos(s, v, l) + fs;
    uint share = specular_share(f, fs);
    if (cos_light <= 1e-6 || all(equal(f, vec3(0.0)))) {
        return unshadowed(vec3(0.0));
    }
    // A point the alpha test cuts out is not there (continuation rays pass through it).
    if ((inst.flags & INSTANCE_ALPHA_TESTED) != 0u && !trace_alpha_accept(e.instance, e.triangle, bary)) {
        return unshadowed(vec3(0.0));
    }
    TraceHit hit;
    hit.t = d;
    hit.instance = e.instance;
    hit.triangle = e.triangle;
    hit.bary = bary;
    vec3 emitted = surface_at(hit, s.position, l, cone_width + spread * d).sampled_emission;
    if (all(equal(emitted, vec3(0.0)))) {
        return unshadowed(vec3(0.0));
    }
    float density = e.probability * 2.0 / area2 * d2 / cos_light;
    float w = weighted ? mis_weight(density, brdf_pdf(s, v, l)) : 1.0;
    return ShadowSample(f * emitted * (w / density), share, l, d * 0.999);
}

#endif
