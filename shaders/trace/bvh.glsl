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

#include "trace/bvh_common.glsl"

#define BVH_STACK_SIZE (2 * BVH_MAX_DEPTH)

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
bool bvh_trace(vec3 origin, vec3 dir, float tmin, float tmax, bool any_hit, out TraceHit hit) {
    BvhRay ray = bvh_start(origin, dir, tmax, hit);
    bool found = false;
    uint stack[BVH_STACK_SIZE];
    uint sp = 0u;
    uint next = 0u;
    while (true) {
        bvh_nodes_visited++;
        if ((next & BVH_LEAF) != 0u) {
            bvh_enter(ray, next & ~BVH_LEAF, origin, dir, sp);
            next = 0u;
        }
        BvhNode n = ray.instance == BVH_NONE ? tlas_nodes[next] : blas_nodes[ray.blas_root + next];
        float entry[2] = float[2](bvh_box(n.children[0].min, n.children[0].max, ray.o, ray.inv, tmin, hit.t), bvh_box(n.children[1].min, n.children[1].max, ray.o, ray.inv, tmin, hit.t));
        uvec2 order = entry[1] < entry[0] ? uvec2(1u, 0u) : uvec2(0u, 1u);
        if (ray.instance != BVH_NONE) {
            for (uint i = 0u; i < 2u; i++) {
                uint c = order[i];
                uint meta = n.children[c].meta;
                if (!(entry[c] < BVH_MISS) || (meta & BVH_LEAF) == 0u) {
                    continue;
                }
                if (bvh_leaf(ray.first_triangle + n.children[c].index, meta & ~BVH_LEAF, ray.instance, ray.alpha_tested, ray.o, ray.d, tmin, any_hit, hit)) {
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
            if (!(entry[c] < BVH_MISS && entry[c] <= hit.t && (ray.instance == BVH_NONE || !leaf) && meta != BVH_LEAF)) {
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
            if (ray.instance != BVH_NONE && sp == ray.base) {
                bvh_leave(ray, origin, dir);
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

#endif
