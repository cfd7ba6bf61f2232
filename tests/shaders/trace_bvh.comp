// tests/pathtrace/bvh.rs: one ray per invocation through shaders/trace/bvh_wide.glsl (or bvh.glsl); writes the
// closest hit and the any-hit answer. The alpha test rejects odd triangles.
#version 450
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

// Defined before the include, as bvh.glsl requires.
bool trace_alpha_accept(uint instance, uint triangle, vec2 bary) {
    return (triangle & 1u) == 0u;
}

// The wide BVHs' traversal; with TRACE_BVH_BINARY defined, the binary one.
#ifdef TRACE_BVH_BINARY
#include "trace/bvh.glsl"
#else
#include "trace/bvh_wide.glsl"
#endif

struct Ray {
    vec4 origin_tmin;
    vec4 dir_tmax;
};

struct Result {
    float t;
    uint instance;
    uint triangle;
    uint flags; // 1: trace_closest hit, 2: trace_any hit
    vec2 bary;
    vec2 pad;
};

layout(set = TRACE_SET, binding = 15, std430) readonly buffer Rays {
    Ray rays[];
};

layout(set = TRACE_SET, binding = 16, std430) writeonly buffer Results {
    Result results[];
};

layout(push_constant) uniform Push {
    uint count;
};

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) {
        return;
    }
    Ray ray = rays[i];
    TraceHit hit;
    bool closest = trace_closest(ray.origin_tmin.xyz, ray.dir_tmax.xyz, ray.origin_tmin.w, ray.dir_tmax.w, hit);
    bool any = trace_any(ray.origin_tmin.xyz, ray.dir_tmax.xyz, ray.origin_tmin.w, ray.dir_tmax.w);
    results[i] = Result(hit.t, hit.instance, hit.triangle, (closest ? 1u : 0u) | (any ? 2u : 0u), hit.bary, vec2(0.0));
}
