#version 450
#extension GL_GOOGLE_include_directive : require
// Direct light on the patches (render::radiosity::gpu::direct), once per frame: one invocation
// per patch averages, over the patch's receiver points (radiosity/patch.glsl, as the form
// factors use them), the irradiance of every light of the frame (trace/light.glsl, taken to
// the static world's frame by render::radiosity::lights) that a shadow ray through the
// patches' BVH (trace/bvh.glsl) reaches: I · falloff · cos / d² of a positional light (a
// sphere light counts as a point at its centre: its irradiance where all of it is above the
// horizon; the shadow ray ends on its surface), E · cos of a directional one (its centre
// direction). The patch's primary radiosity, which the gathering pass (radiosity/gather.comp)
// bounces, is its emission plus its albedo times that irradiance.

// No alpha-tested geometry in the patches' BVH: every hit counts (bvh.glsl needs this first).
bool trace_alpha_accept(uint instance, uint triangle, vec2 bary) {
    return true;
}

#include "trace/bvh.glsl"
#include "trace/light.glsl"
#include "radiosity/patch.glsl"

layout(local_size_x = RADIOSITY_GROUP) in;

struct PatchSurface {
    vec4 albedo;     // diffuse reflectance (rgb), linear
    vec4 emission;   // emitted radiosity (rgb), linear
};

struct PatchLight {
    vec4 irradiance; // direct irradiance (rgb), averaged over the receiver points
    vec4 primary;    // emission + albedo * irradiance (rgb)
};

layout(set = TRACE_SET, binding = RADIOSITY_BINDING_LIGHTS, std430) readonly buffer Lights {
    Light lights[];
};

layout(set = TRACE_SET, binding = RADIOSITY_BINDING_PATCH_SURFACES, std430) readonly buffer PatchSurfaces {
    PatchSurface surfaces[];
};

layout(set = TRACE_SET, binding = RADIOSITY_BINDING_DIRECT, std430) writeonly buffer PatchLights {
    PatchLight patch_lights[];
};

layout(push_constant) uniform DirectPass {
    uint patch_count;
    uint light_count;
    uint pad0;
    uint pad1;
} pass;

// The irradiance light i brings to point p of normal n, shadow ray included.
vec3 irradiance_of(uint i, vec3 p, vec3 n) {
    Light light = lights[i];
    // A light of one instance (a model's vertex light) lights no static surface.
    if (light.params.w > 0.0) {
        return vec3(0.0);
    }
    vec3 l;
    float distance;
    vec3 incident;
    if (light.position.w == 0.0) {
        l = light.position.xyz;
        distance = light.params.z > 0.0 ? light.params.z : 1e30;
        incident = light.radiance.rgb;
    } else {
        vec3 to_center = light.position.xyz - p;
        float d2 = dot(to_center, to_center);
        float r = light.radiance.a;
        // A dynamic light does not light what lies inside its sphere (trace/lights.glsl).
        if (d2 <= 0.0 || (light.params.w < 0.0 && d2 <= r * r)) {
            return vec3(0.0);
        }
        float d = sqrt(d2);
        l = to_center / d;
        distance = d2 > r * r ? d - r : d;
        incident = light.radiance.rgb * (light_falloff(light, d, l) / d2);
    }
    float c = dot(n, l);
    if (c <= 0.0 || all(equal(incident, vec3(0.0)))) {
        return vec3(0.0);
    }
    if (trace_any(p, l, 0.0, distance * 0.9999)) {
        return vec3(0.0);
    }
    return incident * c;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pass.patch_count) {
        return;
    }
    Patch receiver = patches[i];
    vec3 irradiance = vec3(0.0);
    if (receiver.normal != vec3(0.0)) {
        float total = 0.0;
        for (uint k = 0u; k < receiver_points(receiver); k++) {
            vec3 p = receiver_point(receiver, k);
            float weight = triangle_area(receiver.first + k);
            vec3 sum = vec3(0.0);
            for (uint j = 0u; j < pass.light_count; j++) {
                sum += irradiance_of(j, p, receiver.normal);
            }
            irradiance += weight * sum;
            total += weight;
        }
        irradiance = total > 0.0 ? irradiance / total : vec3(0.0);
    }
    PatchSurface s = surfaces[i];
    patch_lights[i] = PatchLight(vec4(irradiance, 0.0), vec4(s.emission.rgb + s.albedo.rgb * irradiance, 0.0));
}
