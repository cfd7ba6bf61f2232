#version 450
#extension GL_GOOGLE_include_directive : require
// Direct light on the patches (render::radiosity::gpu::direct), once per update: each patch's
// irradiance at RADIOSITY_DIRECT_POINTS points (the centroids of the quarters of its area,
// lifted off it), the sum over the frame's lights (trace/light.glsl, taken to the static
// world's frame by render::radiosity::lights) that a shadow ray through the patches' BVH
// (trace/bvh.glsl, stopping at the first hit) reaches; the patch's irradiance is the mean over
// its points. I · falloff · cos / d² of a positional light (a sphere light counts as a point at
// its centre: its irradiance where all of it is above the horizon; the shadow ray ends on its
// surface), E · cos of a directional one (its centre direction). The patch's primary
// radiosity, which the gathering pass (radiosity/gather.comp) bounces, is its emission plus its
// albedo times that irradiance.
//
// An update traces one of pass.slices slices of the (patch, point) pairs: pair (i, k) is in
// slice (i * RADIOSITY_DIRECT_POINTS + k) % slices (all of them with 1 slice). Up to
// RADIOSITY_DIRECT_POINTS slices, every patch traces the points k with k % slices == phase;
// past it, one point of every (slices / RADIOSITY_DIRECT_POINTS)-th patch. Each point's
// irradiance is kept (point_irradiance), and so is each patch's light (patch_lights): the
// points of the other slices, and the patches of others, are the updates' that traced them.
// One invocation per (traced patch, traced point, light), one shadow ray each; neighbouring
// invocations light neighbouring patches (the patches come in spatial order) with the same
// point and light, so that their rays run through the same nodes.

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
    vec4 irradiance; // direct irradiance (rgb), averaged over the patch's points; w: BVH nodes
                     // its shadow rays of this update visited, in all
    vec4 primary;    // emission + albedo * irradiance (rgb); w: the most nodes one of them visited
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

layout(set = TRACE_SET, binding = RADIOSITY_BINDING_DIRECT_POINTS, std430) buffer PointIrradiance {
    vec4 point_irradiance[];  // patch i's point k at i * RADIOSITY_DIRECT_POINTS + k
};

layout(push_constant) uniform DirectPass {
    uint patch_count;
    uint light_count;
    uint patches_per_group;  // patches a workgroup lights
    uint lanes;              // invocations per patch: a multiple of the traced points
    uint slices;             // 1, 2, 4, 8 or 16: a divisor or a multiple of RADIOSITY_DIRECT_POINTS
    uint phase;              // the slice traced
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

// Patch `receiver`'s k-th point of direct light (k < RADIOSITY_DIRECT_POINTS), lifted off the surface
// as the form factors' receiver points are: the patch's area is cut in RADIOSITY_DIRECT_POINTS cells of
// equal area, in triangle order, and the point is its cell's centroid. The cell of the area
// fraction (k + 1/2) / RADIOSITY_DIRECT_POINTS is found in its triangle by halving the triangle across
// its longest edge until the half is no larger than a cell (a cell never straddles two
// triangles where they are as large or larger than a cell, as a quad's two triangles are).
vec3 direct_point(Patch receiver, uint k) {
    float total = 0.0;
    for (uint t = 0u; t < receiver.count; t++) {
        total += triangle_area(receiver.first + t);
    }
    float target = (float(k) + 0.5) / float(RADIOSITY_DIRECT_POINTS) * total;
    uint t = receiver.first;
    float area = 0.0;
    for (uint j = 0u; j < receiver.count; j++) {
        t = receiver.first + j;
        area = triangle_area(t);
        if (target < area || j + 1u == receiver.count) {
            break;
        }
        target -= area;
    }
    vec3 a = corner(t, 0u);
    vec3 b = corner(t, 1u);
    vec3 c = corner(t, 2u);
    float f = clamp(area > 0.0 ? target / area : 0.5, 0.0, 1.0);
    float cell = total / float(RADIOSITY_DIRECT_POINTS);
    // Halves across the longest edge (b, c after the rotation): (a, b, m) and (a, m, c).
    for (uint level = 0u; level < 8u && area > cell * 1.0001; level++) {
        float ab = dot(b - a, b - a);
        float bc = dot(c - b, c - b);
        float ca = dot(a - c, a - c);
        if (ab >= bc && ab >= ca) {
            vec3 x = a; a = c; c = b; b = x;      // longest edge a-b becomes b-c
        } else if (ca >= bc) {
            vec3 x = a; a = b; b = c; c = x;      // longest edge c-a becomes b-c
        }
        vec3 m = 0.5 * (b + c);
        if (f < 0.5) {
            c = m;
            f = 2.0 * f;
        } else {
            b = m;
            f = 2.0 * f - 1.0;
        }
        area *= 0.5;
    }
    vec3 lift = receiver.normal * lift_of(receiver.position, receiver.area);
    return (a + b + c) / 3.0 + lift;
}

shared vec3 partial[RADIOSITY_GROUP];
// Each invocation's BVH nodes visited: in all, and by its longest traversal.
shared uvec2 work[RADIOSITY_GROUP];

// One workgroup lights pass.patches_per_group patches (slot), each with pass.lanes invocations
// (lane), invocation lane * patches_per_group + slot. A patch's (traced point, light) pairs are
// numbered pair = light * traced + t; lane takes the pairs lane, lane + lanes, ..., all of one
// traced point t = lane % traced (lanes is a multiple of traced). The first invocation of the
// patch sums each traced point's lanes in a fixed order (the same result in every run), keeps
// those points and averages them with the kept ones of the other slices, and the traversal
// work of the patch's rays (statistics for `glrt radiosity --synthetic`).
void main() {
    uint per_group = pass.patches_per_group;
    uint lanes = pass.lanes;
    uint point_stride = min(pass.slices, RADIOSITY_DIRECT_POINTS);
    uint point_phase = pass.phase % point_stride;
    uint patch_stride = max(pass.slices / RADIOSITY_DIRECT_POINTS, 1u);
    uint traced = RADIOSITY_DIRECT_POINTS / point_stride;
    uint lid = gl_LocalInvocationID.x;
    uint slot = lid % per_group;
    uint lane = lid / per_group;
    uint i = (gl_WorkGroupID.x * per_group + slot) * patch_stride + pass.phase / point_stride;
    bool in_range = lane < lanes && i < pass.patch_count;
    vec3 sum = vec3(0.0);
    uint longest = 0u;
    if (in_range) {
        Patch receiver = patches[i];
        if (receiver.normal != vec3(0.0) && receiver.count > 0u) {
            uint t = lane % traced;
            vec3 p = direct_point(receiver, t * point_stride + point_phase);
            uint pairs = traced * pass.light_count;
            for (uint pair = lane; pair < pairs; pair += lanes) {
                uint before = bvh_nodes_visited;
                sum += irradiance_of(pair / traced, p, receiver.normal);
                longest = max(longest, bvh_nodes_visited - before);
            }
        }
    }
    partial[lid] = sum;
    work[lid] = uvec2(bvh_nodes_visited, longest);
    barrier();
    if (!in_range || lane != 0u) {
        return;
    }
    vec3 irradiance = vec3(0.0);
    for (uint k = 0u; k < RADIOSITY_DIRECT_POINTS; k++) {
        uint at = i * RADIOSITY_DIRECT_POINTS + k;
        if (k % point_stride == point_phase) {
            vec3 point = vec3(0.0);
            for (uint l = k / point_stride; l < lanes; l += traced) {
                point += partial[l * per_group + slot];
            }
            point_irradiance[at] = vec4(point, 0.0);
            irradiance += point;
        } else {
            irradiance += point_irradiance[at].rgb;
        }
    }
    irradiance /= float(RADIOSITY_DIRECT_POINTS);
    uvec2 nodes = uvec2(0u);
    for (uint l = 0u; l < lanes; l++) {
        uvec2 w = work[l * per_group + slot];
        nodes = uvec2(nodes.x + w.x, max(nodes.y, w.y));
    }
    PatchSurface s = surfaces[i];
    patch_lights[i] = PatchLight(vec4(irradiance, float(nodes.x)), vec4(s.emission.rgb + s.albedo.rgb * irradiance, float(nodes.y)));
}
