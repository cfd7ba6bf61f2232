// The traced triangles and what a traversal returns, shared by both tracers' traversals
// (bvh.glsl, hardware.glsl) and shading. Layout (std430, mirrored by render::trace::bvh's
// GpuTriangle): BvhTriangle = v0, e1 = v1 - v0, e2 = v2 - v0, each padded to 16 bytes, in
// BVH order (an instance's triangle k is global triangle first_triangle + k). In the BVH of a
// merged region of the static world's chunks (render::trace::regions, INSTANCE_MERGED) the
// first two pads name the chunk triangle each copies: member (the chunk's record, counted
// from the instance's first_member) and member_triangle (its index from that chunk's
// first_triangle).

#ifndef TRACE_TRIANGLES_GLSL
#define TRACE_TRIANGLES_GLSL

#include "trace/bindings.glsl"

struct BvhTriangle {
    vec3 v0;
    uint member;           // merged BVHs: the chunk record, from the instance's first_member
    vec3 e1;
    uint member_triangle;  // merged BVHs: the triangle, from that chunk's first_triangle
    vec3 e2;
    uint pad2;
};

layout(set = TRACE_SET, binding = BINDING_TRIANGLES, std430) readonly buffer Triangles {
    BvhTriangle triangles[];
};

// A deforming mesh's triangles as they were last frame, in the order of its triangles now
// (Instance.previous_triangles: the motion vectors of its hit points).
layout(set = TRACE_SET, binding = BINDING_PREVIOUS_TRIANGLES, std430) readonly buffer PreviousTriangles {
    BvhTriangle previous_triangles[];
};

// A ray's closest accepted hit.
struct TraceHit {
    float t;        // distance along the ray, in units of its direction's length
    uint instance;  // the instance hit
    uint triangle;  // global triangle index: the instance's first_triangle + index in its BLAS
    vec2 bary;      // (u, v): weights of the triangle's v1 and v2 at the hit
};

// No hit, no instance.
#define TRACE_NONE 0xffffffffu

#endif
