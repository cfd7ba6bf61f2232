// Ray traversal of the compute tracer's wide BVHs (render::trace::bvh::wide): the same
// queries, over the same instances and triangles, as bvh.glsl's binary traversal, with nodes of
// up to BVH_WIDTH children whose boxes are quantised to bytes. A quantised box holds the
// binary box it stands for and the box test is bvh.glsl's, so both find the same closest hit
// (tests/pathtrace/bvh.rs checks it on lavapipe).
//
// Rays are in eye space; the TLAS and, on reaching an instance, its BLAS (the ray in object
// space) are walked in one loop sharing one stack, as in bvh.glsl. At each node every child
// box is tested and the hit children sorted near to far (a sorting network on registers);
// BLAS leaves are intersected at once, near first, and the inner children (or TLAS instances,
// BVH_LEAF set) that are still nearer than the closest hit are pushed far first, each with its
// entry distance; the traversal continues with the top of the stack, and a popped entry
// farther than the closest hit found since is dropped.
//
// Stack: 2 * BVH_WIDE_BUDGET + 1 entries. The builder keeps the entries one level (the TLAS, or
// one BLAS) leaves on the stack within BVH_WIDE_BUDGET along any path; the + 1 is the nearest
// child, pushed last and popped at once. A push that would not fit is dropped (as bvh.glsl).
//
// Alpha testing: as bvh.glsl (trace_alpha_accept, defined by the including shader).
//
// Layout (std430, mirrored by render::trace::bvh::wide::GpuWideNode, checked by the build):
// origin (the node box's lowest corner), exponents (byte a: the biased exponent of axis a's
// scale), lo[6] and hi[6] (byte slot % 4 of word 2 * axis + slot / 4: a child's bounds are
// origin + q * scale), children[BVH_WIDTH]: BVH_EMPTY (its quantised x bounds are then lo 255,
// hi 0), an inner child's node (BLAS: relative to the instance's blas_root), or BVH_LEAF with
// the fields BVH_WIDE_COUNT (primitives less one) and BVH_WIDE_INDEX (the first primitive:
// BLAS triangles relative to first_triangle; TLAS: the instance).

#ifndef TRACE_BVH_WIDE_GLSL
#define TRACE_BVH_WIDE_GLSL

#include "trace/bvh_common.glsl"

#define BVH_WIDE_STACK (2 * BVH_WIDE_BUDGET + 1)

struct BvhWideNode {
    vec3 origin;
    uint exponents;
    uint lo[6];
    uint hi[6];
    uint children[BVH_WIDTH];
};

layout(set = TRACE_SET, binding = BINDING_BLAS_NODES, std430) readonly buffer BlasWideNodes {
    BvhWideNode blas_wide_nodes[];
};

layout(set = TRACE_SET, binding = BINDING_TLAS_NODES, std430) readonly buffer TlasWideNodes {
    BvhWideNode tlas_wide_nodes[];
};

// Sorts the pairs (t[a], s[a]) and (t[b], s[b]) by t.
#define BVH_ORDER(a, b) { bool swap_ = t[b] < t[a]; float ta_ = t[a]; uint sa_ = s[a]; \
    t[a] = swap_ ? t[b] : t[a]; s[a] = swap_ ? s[b] : s[a]; t[b] = swap_ ? ta_ : t[b]; s[b] = swap_ ? sa_ : s[b]; }

// Child `slot`'s quantised bound on each axis from the words `q` (lo or hi) of a node.
vec3 bvh_wide_bound(uint q[6], uint slot, vec3 origin, vec3 scale) {
    uint word = slot >> 2u;
    int shift = int(8u * (slot & 3u));
    uvec3 b = uvec3(bitfieldExtract(q[word], shift, 8), bitfieldExtract(q[2u + word], shift, 8), bitfieldExtract(q[4u + word], shift, 8));
    return origin + vec3(b) * scale;
}

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
    uint stack[BVH_WIDE_STACK];
    float stack_t[BVH_WIDE_STACK];
    uint sp = 0u;
    uint next = 0u;
    while (true) {
        bvh_nodes_visited++;
        if ((next & BVH_LEAF) != 0u) {
            instance = bitfieldExtract(next, int(BVH_WIDE_INDEX_SHIFT), int(BVH_WIDE_INDEX_BITS));
            o = bvh_transform(instances[instance].eye_to_object, origin, 1.0);
            d = bvh_transform(instances[instance].eye_to_object, dir, 0.0);
            inv = bvh_inverse(d);
            blas_root = instances[instance].blas_root;
            first_triangle = instances[instance].first_triangle;
            alpha_tested = (instances[instance].flags & INSTANCE_ALPHA_TESTED) != 0u;
            base = sp;
            next = 0u;
        }
        uint at = instance == BVH_NONE ? next : blas_root + next;
        vec3 node_origin;
        uint exponents;
        uint lo[6];
        uint hi[6];
        if (instance == BVH_NONE) {
            node_origin = tlas_wide_nodes[at].origin;
            exponents = tlas_wide_nodes[at].exponents;
            lo = tlas_wide_nodes[at].lo;
            hi = tlas_wide_nodes[at].hi;
        } else {
            node_origin = blas_wide_nodes[at].origin;
            exponents = blas_wide_nodes[at].exponents;
            lo = blas_wide_nodes[at].lo;
            hi = blas_wide_nodes[at].hi;
        }
        vec3 scale = uintBitsToFloat(uvec3(bitfieldExtract(exponents, 0, 8), bitfieldExtract(exponents, 8, 8), bitfieldExtract(exponents, 16, 8)) << 23u);
        // Entry distances of the children, sorted near to far with their slots (misses last).
        float t[BVH_WIDTH];
        uint s[BVH_WIDTH];
        for (uint slot = 0u; slot < BVH_WIDTH; slot++) {
            vec3 box_lo = bvh_wide_bound(lo, slot, node_origin, scale);
            vec3 box_hi = bvh_wide_bound(hi, slot, node_origin, scale);
            int shift = int(8u * (slot & 3u));
            bool filled = bitfieldExtract(lo[slot >> 2u], shift, 8) <= bitfieldExtract(hi[slot >> 2u], shift, 8);
            t[slot] = filled ? bvh_box(box_lo, box_hi, o, inv, tmin, hit.t) : BVH_MISS;
            s[slot] = slot;
        }
        BVH_ORDER(0, 2) BVH_ORDER(1, 3) BVH_ORDER(4, 6) BVH_ORDER(5, 7)
        BVH_ORDER(0, 4) BVH_ORDER(1, 5) BVH_ORDER(2, 6) BVH_ORDER(3, 7)
        BVH_ORDER(0, 1) BVH_ORDER(2, 3) BVH_ORDER(4, 5) BVH_ORDER(6, 7)
        BVH_ORDER(2, 4) BVH_ORDER(3, 5)
        BVH_ORDER(1, 4) BVH_ORDER(3, 6)
        BVH_ORDER(1, 2) BVH_ORDER(3, 4) BVH_ORDER(5, 6)
        if (instance != BVH_NONE) {
            for (uint i = 0u; i < BVH_WIDTH; i++) {
                if (!(t[i] < BVH_MISS)) {
                    continue;
                }
                uint child = blas_wide_nodes[at].children[s[i]];
                if ((child & BVH_LEAF) == 0u) {
                    continue;
                }
                uint first = bitfieldExtract(child, int(BVH_WIDE_INDEX_SHIFT), int(BVH_WIDE_INDEX_BITS));
                uint count = bitfieldExtract(child, int(BVH_WIDE_COUNT_SHIFT), int(BVH_WIDE_COUNT_BITS)) + 1u;
                if (bvh_leaf(first_triangle + first, count, instance, alpha_tested, o, d, tmin, any_hit, hit)) {
                    found = true;
                    if (any_hit) {
                        return true;
                    }
                }
            }
        }
        // Far first, so that the nearest is on top; only what is still nearer than the hit.
        for (int i = BVH_WIDTH - 1; i >= 0; i--) {
            if (!(t[i] < BVH_MISS && t[i] <= hit.t)) {
                continue;
            }
            uint child = instance == BVH_NONE ? tlas_wide_nodes[at].children[s[i]] : blas_wide_nodes[at].children[s[i]];
            if (instance != BVH_NONE && (child & BVH_LEAF) != 0u) {
                continue;
            }
            if (sp < BVH_WIDE_STACK) {
                stack[sp] = child;
                stack_t[sp] = t[i];
                sp++;
            }
        }
        next = BVH_NONE;
        while (next == BVH_NONE) {
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
            if (stack_t[sp] <= hit.t) {
                next = stack[sp];
            }
        }
    }
    return found;
}

#endif
