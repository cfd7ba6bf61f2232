// Direct light from the scene's lights (GL lights converted by src/render/trace/lights.rs):
// next-event estimation with one shadow ray per light.

#ifndef TRACE_LIGHTS_GLSL
#define TRACE_LIGHTS_GLSL

#include "trace/surface.glsl"
#include "trace/random.glsl"

// A point just off the surface, on the side of `n`, far enough that a ray leaving it does not
// hit the surface again (Wächter and Binder 2019, "A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems chapter 6).
vec3 offset_ray(vec3 p, vec3 n) {
    const float origin = 1.0 / 32.0;
    const float float_scale = 1.0 / 65536.0;
    const float int_scale = 256.0;
    ivec3 of_i = ivec3(int_scale * n);
    vec3 p_i = vec3(
        intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0 ? -of_i.x : of_i.x)),
        intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0 ? -of_i.y : of_i.y)),
        intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0 ? -of_i.z : of_i.z)));
    return vec3(
        abs(p.x) < origin ? p.x + float_scale * n.x : p_i.x,
        abs(p.y) < origin ? p.y + float_scale * n.y : p_i.y,
        abs(p.z) < origin ? p.z + float_scale * n.z : p_i.z);
}

// The reflected radiance towards v due to light i, shadow ray included; `shadow_rays` counts
// the rays traced.
vec3 direct_light(Surface s, vec3 v, uint i, inout Rng rng, inout uint shadow_rays) {
    Light light = lights[i];
    vec3 l;
    float distance;
    vec3 incident;
    if (light.position.w == 0.0) {
        l = light.params.y < 1.0 ? sample_cone(light.position.xyz, light.params.y, rng_next2(rng)) : light.position.xyz;
        distance = 1e30;
        incident = light.radiance.rgb;
    } else {
        vec3 center = light.position.xyz;
        float radius = light.radiance.a;
        if (radius > 0.0) {
            // A point on the disc of the sphere's radius facing the surface.
            vec2 u = rng_next2(rng);
            float r = radius * sqrt(u.x);
            float phi = 2.0 * PI * u.y;
            mat3 frame = basis(normalize(s.position - center));
            center += frame * vec3(r * cos(phi), r * sin(phi), 0.0);
        }
        vec3 to_light = center - s.position;
        distance = length(to_light);
        if (distance <= 0.0) {
            return vec3(0.0);
        }
        l = to_light / distance;
        incident = light.radiance.rgb / (distance * distance);
        if (light.spot.w > -1.5) {
            float c = dot(-l, light.spot.xyz);
            if (c < light.spot.w) {
                return vec3(0.0);
            }
            incident *= light.params.x > 0.0 ? pow(max(c, 0.0), light.params.x) : 1.0;
        }
    }
    vec3 f = brdf_eval_cos(s, v, l);
    if (all(equal(f, vec3(0.0))) || all(equal(incident, vec3(0.0)))) {
        return vec3(0.0);
    }
    shadow_rays += 1u;
    if (trace_any(offset_ray(s.position, s.geometric), l, 0.0, distance * 0.9999)) {
        return vec3(0.0);
    }
    return f * incident;
}

#endif
