// Ray traversal of the compute tracer's BVHs (render::trace::bvh; render::trace::bvh::cpu is
// the same algorithm in Rust, operation for operation, and tests/pathtrace/bvh.rs checks they
// agree on lavapipe).
//
// Rays are in eye space. The TLAS over the instances and, on reaching an instance, its BLAS
// (the ray moved into object space by the instance's eye_to_object rows, the direction not
// renormalised so that t stays comparable) are walked in one loop sharing one stack. At each
// node both child boxes are tested; BLAS leaves are intersected at once (Möller–Trumbore);
// of the hit inner children (or TLAS instances, pushed with BVH_LEAF set) the nearer is
// visited next and the farther pushed.
//
// Stack: BVH_STACK_SIZE = 2 * BVH_MAX_DEPTH entries. The builder keeps every
// root-to-leaf path of a TLAS or BLAS within MAX_DEPTH nodes and a traversal pushes at most
// one entry per level, so a TLAS path plus a BLAS path fit. A push that would not fit is
// dropped (hits behind it are lost, nothing is read or written out of bounds).
//
// Alpha testing: for instances with INSTANCE_ALPHA_TESTED, both queries call
//     bool trace_alpha_accept(uint instance, uint triangle, vec2 bary);
// before accepting a hit (triangle: global index; bary: weights of v1, v2). The including
// shader must define it before including this file.
//
// Layout (std430, mirrored by render::trace::bvh's GpuNode, GpuChild and GpuTriangle, checked
// by the build): BvhNode = 2 children, each min, index, max, meta (a vec3 and a uint fill 16
// bytes). meta == 0: inner child, index = node (BLAS: relative to the instance's blas_root).
// meta & BVH_LEAF: leaf of (meta & ~BVH_LEAF) primitives from index (BLAS: triangles relative
// to first_triangle; TLAS: one instance, index = the instance); 0 primitives = empty child.
// Triangles: trace/triangles.glsl.

#ifndef TRACE_BVH_GLSL
#define TRACE_BVH_GLSL

#include "generated/trace_constants.glsl"
#include "trace/bindings.glsl"
#include "trace/instance.glsl"
#include "trace/triangles.glsl"

#define BVH_STACK_SIZE (2 * BVH_MAX_DEPTH)
#define BVH_NONE 0xffffffffu
// Entry distance of a missed box.
#define BVH_MISS uintBitsToFloat(0x7f800000u)
// Smallest magnitude of a direction component before inversion.
#define BVH_TINY 1.0e-20
// Widens a box's exit distance to cover rounding (1 + 4 ulp).
#define BVH_BOX_SLACK 1.0000005

struct BvhChild {
    vec3 min;      // lowest corner of the child's box
    uint index;    // inner child: its node; leaf: its first primitive
    vec3 max;      // highest corner
    uint meta;     // 0 for an inner child; BVH_LEAF | primitive count for a leaf
};

struct BvhNode {
    BvhChild children[2];
};


layout(set = TRACE_SET, binding = BINDING_BLAS_NODES, std430) readonly buffer BlasNodes {
    BvhNode blas_nodes[];
};

layout(set = TRACE_SET, binding = BINDING_TLAS_NODES, std430) readonly buffer TlasNodes {
    BvhNode tlas_nodes[];
};


// 1 / d with components of magnitude below BVH_TINY replaced by ±BVH_TINY.
vec3 bvh_inverse(vec3 d) {
    vec3 tiny = mix(vec3(-BVH_TINY), vec3(BVH_TINY), greaterThanEqual(d, vec3(0.0)));
    return vec3(1.0) / mix(d, tiny, lessThan(abs(d), vec3(BVH_TINY)));
}

// Entry distance into the box of child c of n clipped to [tmin, tmax], or BVH_MISS.
float bvh_box(BvhNode n, uint c, vec3 o, vec3 inv, float tmin, float tmax) {
    vec3 t0 = (n.children[c].min - o) * inv;
    vec3 t1 = (n.children[c].max - o) * inv;
    vec3 near = min(t0, t1);
    vec3 far = max(t0, t1);
    float tn = max(max(near.x, near.y), max(near.z, tmin));
    float tf = min(min(far.x, far.y), min(far.z, tmax)) * BVH_BOX_SLACK;
    return tn <= tf ? tn : BVH_MISS;
}

// Möller–Trumbore: whether the ray hits tri with tmin < t < tmax; then t and (u, v).
bool bvh_triangle(BvhTriangle tri, vec3 o, vec3 d, float tmin, float tmax, out float t, out vec2 bary) {
    t = 0.0;
    bary = vec2(0.0);
    vec3 e1 = tri.e1;
    vec3 e2 = tri.e2;
    vec3 p = cross(d, e2);
    float det = dot(e1, p);
    if (!(abs(det) > 0.0)) {
        return false;
    }
    float inv = 1.0 / det;
    vec3 s = o - tri.v0;
    float u = dot(s, p) * inv;
    if (!(u >= 0.0 && u <= 1.0)) {
        return false;
    }
    vec3 q = cross(s, e1);
    float v = dot(d, q) * inv;
    if (!(v >= 0.0 && u + v <= 1.0)) {
        return false;
    }
    t = dot(e2, q) * inv;
    bary = vec2(u, v);
    return t > tmin && t < tmax;
}

// Applies the rows of an affine matrix to (v, w).
vec3 bvh_transform(vec4 rows[3], vec3 v, float w) {
    vec4 h = vec4(v, w);
    return vec3(dot(rows[0], h), dot(rows[1], h), dot(rows[2], h));
}

// Both queries: with any_hit, returns at the first accepted hit.
// Work of this invocation's traversals so far (statistics: nodes visited, triangles tested).
uint bvh_nodes_visited = 0u;
uint bvh_triangles_tested = 0u;

bool bvh_trace(vec3 origin, vec3 dir, float tmin, float tmax, bool any_hit, out TraceHit hit) {
    hit.t = tmax;
    hit.instance = BVH_NONE;
    hit.triangle = BVH_NONE;
    hit.bary = vec2(0.0);
    bool found = false;
    vec3 o = origin;
    vec3 d = dir;
    vec3 inv = bvh_inverse(dir);
    uint instance = BVH_NONE;  // BVH_NONE: in the TLAS
    uint blas_root = 0u;
    uint first_triangle = 0u;
    bool alpha_tested = false;
    uint base = 0u;            // stack entries below this belong to the TLAS
    uint stack[BVH_STACK_SIZE];
    uint sp = 0u;
    uint next = 0u;
    while (true) {
        bvh_nodes_visited++;
        if ((next & BVH_LEAF) != 0u) {
            instance = next & ~BVH_LEAF;
            o = bvh_transform(instances[instance].eye_to_object, origin, 1.0);
            d = bvh_transform(instances[instance].eye_to_object, dir, 0.0);
            inv = bvh_inverse(d);
            blas_root = instances[instance].blas_root;
            first_triangle = instances[instance].first_triangle;
            alpha_tested = (instances[instance].flags & INSTANCE_ALPHA_TESTED) != 0u;
            base = sp;
            next = 0u;
        }
        BvhNode n = instance == BVH_NONE ? tlas_nodes[next] : blas_nodes[blas_root + next];
        float entry[2] = float[2](bvh_box(n, 0u, o, inv, tmin, hit.t), bvh_box(n, 1u, o, inv, tmin, hit.t));
        uvec2 order = entry[1] < entry[0] ? uvec2(1u, 0u) : uvec2(0u, 1u);
        if (instance != BVH_NONE) {
            for (uint i = 0u; i < 2u; i++) {
                uint c = order[i];
                uint meta = n.children[c].meta;
                if (!(entry[c] < BVH_MISS) || (meta & BVH_LEAF) == 0u) {
                    continue;
                }
                uint first = n.children[c].index;
                uint end = first + (meta & ~BVH_LEAF);
                for (uint k = first; k < end; k++) {
                    bvh_triangles_tested++;
                    uint triangle = first_triangle + k;
                    float t;
                    vec2 bary;
                    if (!bvh_triangle(triangles[triangle], o, d, tmin, hit.t, t, bary)) {
                        continue;
                    }
                    if (alpha_tested && !trace_alpha_accept(instance, triangle, bary)) {
                        continue;
                    }
                    hit.t = t;
                    hit.instance = instance;
                    hit.triangle = triangle;
                    hit.bary = bary;
                    found = true;
                    if (any_hit) {
                        return true;
                    }
                }
            }
        }
        next = BVH_NONE;
        for (uint i = 0u; i < 2u; i++) {
            uint c = order[i];
            uint meta = n.children[c].meta;
            bool leaf = (meta & BVH_LEAF) != 0u;
            // Hit, still in range after this node's leaves, an inner node or (TLAS) an instance.
            if (!(entry[c] < BVH_MISS && entry[c] <= hit.t && (instance == BVH_NONE || !leaf) && meta != BVH_LEAF)) {
                continue;
            }
            uint index = n.children[c].index;
            uint target = leaf ? (index | BVH_LEAF) : index;
            if (next == BVH_NONE) {
                next = target;
            } else if (sp < BVH_STACK_SIZE) {
                stack[sp] = target;
                sp++;
            }
        }
        if (next == BVH_NONE) {
            if (instance != BVH_NONE && sp == base) {
                instance = BVH_NONE;
                o = origin;
                d = dir;
                inv = bvh_inverse(dir);
            }
            if (sp == 0u) {
                return found;
            }
            sp--;
            next = stack[sp];
        }
    }
    return found;
}

// The closest accepted hit with tmin < t < tmax; false (hit.t = tmax) when none.
bool trace_closest(vec3 origin, vec3 dir, float tmin, float tmax, out TraceHit hit) {
    return bvh_trace(origin, dir, tmin, tmax, false, hit);
}

// Whether any accepted hit has tmin < t < tmax (shadow rays); stops at the first.
bool trace_any(vec3 origin, vec3 dir, float tmin, float tmax) {
    TraceHit hit;
    return bvh_trace(origin, dir, tmin, tmax, true, hit);
}

#endif
