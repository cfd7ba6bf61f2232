// The patches as the radiosity passes read them (render::radiosity::gpu::scene): each patch's
// centroid, area and normal and its triangles, and the points a patch receives light at, which
// the form factors (radiosity/form_factors.comp) and the direct light (radiosity/direct.comp)
// share with the CPU reference (render::radiosity::form_factors): the centroids of the
// patch's first RADIOSITY_RECEIVER_POINTS triangles, lifted off the surface, weighted by area.

#ifndef RADIOSITY_PATCH_GLSL
#define RADIOSITY_PATCH_GLSL

#include "generated/radiosity_constants.glsl"

struct Patch {
    vec3 position;   // area-weighted centroid
    float area;
    vec3 normal;     // unit normal of the front side (zero: degenerate, an empty row)
    uint first;      // first triangle in patch_triangles
    uint count;      // its triangles
    uint pad0;
    uint pad1;
    uint pad2;
};

struct PatchTriangle {
    vec4 v[3];       // corners (xyz), front side counter-clockwise
};

layout(set = TRACE_SET, binding = RADIOSITY_BINDING_PATCHES, std430) readonly buffer Patches {
    Patch patches[];
};

layout(set = TRACE_SET, binding = RADIOSITY_BINDING_PATCH_TRIANGLES, std430) readonly buffer PatchTriangles {
    PatchTriangle patch_triangles[];
};

// How far a point is moved off its surface (form_factors::offset).
float lift_of(vec3 position, float area) {
    vec3 a = abs(position);
    return 1.0e-3 * sqrt(area) + 1.0e-6 * max(a.x, max(a.y, a.z));
}

vec3 corner(uint t, uint k) {
    return patch_triangles[t].v[k].xyz;
}

float triangle_area(uint t) {
    return 0.5 * length(cross(corner(t, 1u) - corner(t, 0u), corner(t, 2u) - corner(t, 0u)));
}

// How many points the patch receives light at.
uint receiver_points(Patch receiver) {
    return min(receiver.count, RADIOSITY_RECEIVER_POINTS);
}

// The k-th receiver point of the patch (k < receiver_points): its k-th triangle's centroid,
// lifted along the normal; its weight is that triangle's area.
vec3 receiver_point(Patch receiver, uint k) {
    uint r = receiver.first + k;
    vec3 lift = receiver.normal * lift_of(receiver.position, receiver.area);
    return (corner(r, 0u) + corner(r, 1u) + corner(r, 2u)) / 3.0 + lift;
}

#endif
