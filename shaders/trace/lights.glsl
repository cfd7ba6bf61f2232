// Direct light from the scene's lights (GL lights converted by src/render/trace/lights.rs):
// next-event estimation with one shadow ray per light; directional lights of an angular size
// and sphere lights are sampled uniformly in the cone of directions they fill. On baked
// surfaces a dynamic light brings what the game's dynamic-light pass brings (lights.rs).
// Every next-event sample (these, trace/emitters.glsl's and trace/sky_sampling.glsl's) is a
// ShadowSample: the path traces the shadow rays of a vertex at one call site
// (trace/path.glsl), since a megakernel inlines every call of the traversal.

#ifndef TRACE_LIGHTS_GLSL
#define TRACE_LIGHTS_GLSL

#include "trace/surface.glsl"
#include "trace/random.glsl"
#include "trace/channels.glsl"

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

// A next-event sample of a path vertex: the light it brings where its shadow ray, leaving the
// vertex along `dir` up to `distance`, is not occluded; `distance` 0: no ray, `light` counts
// as it is; `specular` is the share of `light` the surface's specular lobe reflects, per
// colour (pack_share of trace/channels.glsl: the denoiser's specular channel; one word, as
// the sample is held while its shadow ray is traced).
struct ShadowSample {
    vec3 light;
    uint specular;
    vec3 dir;
    float distance;
};

// A sample that brings `light` without a shadow ray (nothing, for vec3(0.0)).
ShadowSample unshadowed(vec3 light) {
    return ShadowSample(light, 0u, vec3(0.0, 0.0, 1.0), 0.0);
}

// ShadowSample.specular of light reflected by a surface's lobes, `f` both (brdf_eval_cos),
// `specular` the specular one alone (packed at once: the samples hold it, not both lobes,
// while they read the emitter's texels or the sky).
uint specular_share(vec3 f, vec3 specular) {
    return pack_share(specular / max(f, vec3(1e-30)));
}

// A direction l from p towards positional light `light` at distance d2 > 0 squared, and the
// length of the shadow ray along it: for a sphere (radiance.a > 0) a direction uniform in the
// cone it fills, of solid angle 2 pi (1 - cos_max) (all directions from inside it), the ray
// ending on the sphere (the near root from outside, the far from inside); for a point its
// centre. Returns 1 - cos_max (written without cancellation; 0 for a point).
float sample_sphere(Light light, vec3 p, float d2, vec2 u, out vec3 l, out float distance) {
    vec3 to_center = light.position.xyz - p;
    float r = light.radiance.a;
    if (r <= 0.0) {
        distance = sqrt(d2);
        l = to_center / distance;
        return 0.0;
    }
    float r2 = r * r;
    bool outside = d2 > r2;
    float cos_max = outside ? sqrt(1.0 - r2 / d2) : -1.0;
    l = sample_cone(to_center / sqrt(d2), cos_max, u);
    float b = dot(l, to_center);
    float h = sqrt(max(r2 - (d2 - b * b), 0.0));
    distance = outside ? b - h : b + h;
    return outside ? (r2 / d2) / (1.0 + cos_max) : 2.0;
}

// What dynamic light i's pass brings to a baked surface s that shows display colour `shown`,
// in display units (render::trace::lights's module doc): colour (radiance over pi falloff,
// display-encoded) x the height fade x min(1, falloff / d^2), 0 below the texture's floor,
// times `shown` for a pass that modulates; 0 where s faces away from the light or a shadow
// ray to its sphere is occluded (none from inside the sphere).
ShadowSample dynamic_pass_light(Surface s, vec3 shown, uint i, inout Rng rng) {
    Light light = lights[i];
    vec3 to_center = light.position.xyz - s.position;
    float d2 = dot(to_center, to_center);
    float h = abs(dot(to_center, light.spot.xyz));
    float across2 = max(d2 - h * h, 0.0);
    float reach = light.params.z;
    float fade = h < 0.5 * reach ? 1.0 : max(2.0 * (reach - h) / reach, 0.0);
    float falloff = light.params.y;
    if (fade == 0.0 || falloff <= 0.0 || falloff < light.params.x * across2 || d2 <= 0.0) {
        return unshadowed(vec3(0.0));
    }
    vec3 color = linear_to_srgb(light.radiance.rgb / (3.14159265 * falloff));
    vec3 brought = color * (fade * min(1.0, falloff / max(across2, 1e-30)));
    if (light.params.w < -1.5) {
        brought *= shown;
    }
    float r = light.radiance.a;
    if (d2 <= r * r || all(equal(brought, vec3(0.0)))) {
        return unshadowed(brought);
    }
    vec3 l;
    float distance;
    sample_sphere(light, s.position, d2, rng_next2(rng), l, distance);
    if (dot(l, s.geometric) <= 0.0) {
        return unshadowed(vec3(0.0));
    }
    return ShadowSample(brought, 0u, l, distance * 0.9999);
}

// The reflected radiance towards v at a point of instance `instance` due to light i where its
// shadow ray is not occluded. A light of one instance (params.w > 0,
// render::trace::vertex_light) lights no other; a dynamic light (params.w < 0) lights no
// vertex-lit model (MATERIAL_VERTEX_LIT: its colours hold it already).
ShadowSample direct_light(Surface s, vec3 v, uint instance, uint i, inout Rng rng) {
    Light light = lights[i];
    if (light.params.w > 0.0 && uint(light.params.w) != instance + 1u) {
        return unshadowed(vec3(0.0));
    }
    if (light.params.w < 0.0 && (materials[instances[instance].material].flags & MATERIAL_VERTEX_LIT) != 0u) {
        return unshadowed(vec3(0.0));
    }
    vec3 l;
    float distance;
    vec3 incident;
    if (light.position.w == 0.0) {
        l = light.params.y < 1.0 ? sample_cone(light.position.xyz, light.params.y, rng_next2(rng)) : light.position.xyz;
        distance = light.params.z > 0.0 ? light.params.z : 1e30;
        incident = light.radiance.rgb;
    } else {
        vec3 to_center = light.position.xyz - s.position;
        float d2 = dot(to_center, to_center);
        if (d2 <= 0.0) {
            return unshadowed(vec3(0.0));
        }
        float d = sqrt(d2);
        vec3 axis = to_center / d;
        float r = light.radiance.a;
        // A dynamic light (params.w < 0) does not light what lies inside its sphere: the model
        // that carries it, whose own colours hold its light already.
        if (light.params.w < 0.0 && d2 <= r * r) {
            return unshadowed(vec3(0.0));
        }
        // A sphere of radiance I / (pi r^2) (lights.rs): incident = radiance * solid angle.
        float one_minus_cos = sample_sphere(light, s.position, d2, rng_next2(rng), l, distance);
        incident = r > 0.0 ? light.radiance.rgb * (2.0 * one_minus_cos / (r * r)) : light.radiance.rgb / d2;
        float falloff = light_falloff(light, d, axis);
        if (falloff == 0.0) {
            return unshadowed(vec3(0.0));
        }
        incident *= falloff;
    }
    // The light of a model's vertex colours is the game's Lambertian lighting (divided by
    // the hue the model's albedo keeps, render::trace::vertex_light): it lights the diffuse
    // lobe alone.
    vec3 fs = light.params.w > 0.0 ? vec3(0.0) : brdf_specular_cos(s, v, l);
    vec3 f = brdf_diffuse_cos(s, v, l) + fs;
    if (all(equal(f, vec3(0.0))) || all(equal(incident, vec3(0.0)))) {
        return unshadowed(vec3(0.0));
    }
    return ShadowSample(f * incident, specular_share(f, fs), l, distance * 0.9999);
}

#endif
