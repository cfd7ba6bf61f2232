// Ray traversal of the compute tracer's compressed wide BVHs (render::trace::bvh::wide, after
// Ylitie, Karras and Laine 2017, CWBVH): the same queries, over the same instances and
// triangles, as bvh.glsl's binary traversal, with 80-byte nodes of up to BVH_WIDTH children
// whose boxes are quantised to bytes. A quantised box holds the binary box it stands for, so
// both find the same closest hit (tests/pathtrace/bvh.rs checks it on lavapipe).
//
// Rays are in eye space; the TLAS and, on reaching an instance, its BLAS (the ray in object
// space) are walked in one loop sharing one stack, as in bvh.glsl. The box test moves the ray
// into the node's quantisation grid (one fused multiply-add per plane) and takes the near and
// far planes by the direction's signs. Its result is two hit masks:
// - a node group (the node's child_base; the hit inner children at bit 24 + (slot ^ oct_inv),
//   the node's imask in bits 0-7), walked highest bit first: the builder puts in slot s the
//   child a ray with the direction signs s meets first, so this visits the children roughly
//   near to far without sorting (oct_inv: the complement of the ray's sign bits);
// - a leaf group (the node's leaf_base; bit k for its primitive leaf_base + k, k < 24): BLAS
//   triangles, tested at once, or TLAS instances, each entered in turn.
// The stack holds groups with children left to visit (node groups) and, in the TLAS, instances
// left to enter (leaf groups, bits 24-31 clear).
//
// Stack: each visited node leaves at most one group on the stack (its siblings') and entering
// an instance two (the TLAS node's children and instances left), so a TLAS path and a BLAS path
// of at most BVH_MAX_DEPTH nodes each fit BVH_WIDE_STACK. A push that would not fit is dropped
// (as bvh.glsl).
//
// Alpha testing: as bvh.glsl (trace_alpha_accept, defined by the including shader).
//
// Layout (std430, mirrored by render::trace::bvh::wide::GpuWideNode, checked by the build):
// origin (the node box's lowest corner); frame (byte a: the biased exponent of axis a's scale,
// BVH_WIDE_IMASK: the slots holding inner children); child_base (the first inner child's node,
// BLAS: relative to the instance's blas_root; the others follow in slot order); leaf_base (the
// leaves' first primitive, BLAS: triangles relative to first_triangle; TLAS: the word of the
// TLAS buffer holding the instance); meta (byte per slot: BVH_WIDE_OFFSET and BVH_WIDE_COUNT of
// a leaf, BVH_WIDE_EMPTY); bounds (bytes: lowest x, y, z, highest x, y, z, eight slots each; a
// child's bounds are origin + q * scale).

#ifndef TRACE_BVH_WIDE_GLSL
#define TRACE_BVH_WIDE_GLSL

#include "trace/bvh_common.glsl"

#define BVH_WIDE_STACK (2 * BVH_MAX_DEPTH + 2)
// The lowest bit of a node group's inner children.
#define BVH_WIDE_INNER 0x1000000u

struct BvhWideNode {
    vec3 origin;
    uint frame;
    uint child_base;
    uint leaf_base;
    uvec2 meta;
    uvec4 bounds[3];
};

layout(set = TRACE_SET, binding = BINDING_BLAS_NODES, std430) readonly buffer BlasWideNodes {
    BvhWideNode blas_wide_nodes[];
};

layout(set = TRACE_SET, binding = BINDING_TLAS_NODES, std430) readonly buffer TlasWideNodes {
    BvhWideNode tlas_wide_nodes[];
};

// The same buffer as words: the instances of the TLAS's leaves follow its nodes.
layout(set = TRACE_SET, binding = BINDING_TLAS_NODES, std430) readonly buffer TlasWideWords {
    uint tlas_wide_words[];
};

// oct_inv of a ray with inverse direction inv: bit 2 - a set where axis a is not negative.
uint bvh_wide_octant(vec3 inv) {
    return (inv.x < 0.0 ? 0u : 4u) | (inv.y < 0.0 ? 0u : 2u) | (inv.z < 0.0 ? 0u : 1u);
}

// The eight bytes of `q` (two words) as floats, slot order.
#define BVH_WIDE_BYTE(q, slot) float(bitfieldExtract(q[(slot) >> 2], 8 * ((slot) & 3), 8))

// Tests the children of a node (its fields: origin, frame, meta, bounds q0, q1, q2) against
// the ray (o, inv) within [tmin, tmax]: `inner` gets the hit inner children at bit
// 24 + (slot ^ oct_inv) and the node's imask, `leaves` a bit per primitive of the hit leaves.
// Branch-free: selects only.
void bvh_wide_test(vec3 origin, uint frame, uvec2 meta, uvec4 q0, uvec4 q1, uvec4 q2, vec3 o, vec3 inv, uint oct_inv, float tmin, float tmax, out uint inner, out uint leaves) {
    vec3 scale = uintBitsToFloat(uvec3(bitfieldExtract(frame, 0, 8), bitfieldExtract(frame, 8, 8), bitfieldExtract(frame, 16, 8)) << 23u);
    // The plane at q is hit at q * a + b.
    vec3 a = scale * inv;
    vec3 b = (origin - o) * inv;
    // Lowest bounds are the near planes where the direction is positive.
    uvec2 lo_x = q0.xy, lo_y = q0.zw, lo_z = q1.xy, hi_x = q1.zw, hi_y = q2.xy, hi_z = q2.zw;
    uvec2 near_x = inv.x < 0.0 ? hi_x : lo_x, far_x = inv.x < 0.0 ? lo_x : hi_x;
    uvec2 near_y = inv.y < 0.0 ? hi_y : lo_y, far_y = inv.y < 0.0 ? lo_y : hi_y;
    uvec2 near_z = inv.z < 0.0 ? hi_z : lo_z, far_z = inv.z < 0.0 ? lo_z : hi_z;
    uint imask = bitfieldExtract(frame, int(BVH_WIDE_IMASK_SHIFT), int(BVH_WIDE_IMASK_BITS));
    inner = imask;
    leaves = 0u;
    for (int slot = 0; slot < BVH_WIDTH; slot++) {
        vec3 tn3 = vec3(BVH_WIDE_BYTE(near_x, slot), BVH_WIDE_BYTE(near_y, slot), BVH_WIDE_BYTE(near_z, slot)) * a + b;
        vec3 tf3 = vec3(BVH_WIDE_BYTE(far_x, slot), BVH_WIDE_BYTE(far_y, slot), BVH_WIDE_BYTE(far_z, slot)) * a + b;
        float tn = max(max(tn3.x, tn3.y), max(tn3.z, tmin));
        float tf = min(min(tf3.x, tf3.y), min(tf3.z, tmax)) * BVH_BOX_SLACK;
        bool hit = tn <= tf;
        bool is_inner = (imask & (1u << slot)) != 0u;
        uint m = bitfieldExtract(meta[slot >> 2], 8 * (slot & 3), 8);
        uint offset = bitfieldExtract(m, int(BVH_WIDE_OFFSET_SHIFT), int(BVH_WIDE_OFFSET_BITS));
        uint count = bitfieldExtract(m, int(BVH_WIDE_COUNT_SHIFT), int(BVH_WIDE_COUNT_BITS)) + 1u;
        // An empty slot's offset is beyond the leaves.
        uint leaf_bits = offset < BVH_WIDE_LEAVES ? ((1u << count) - 1u) << offset : 0u;
        inner |= hit && is_inner ? BVH_WIDE_INNER << (uint(slot) ^ oct_inv) : 0u;
        leaves |= hit && !is_inner ? leaf_bits : 0u;
    }
    // No inner child hit: no group (not to be read as a leaf group).
    inner = inner >= BVH_WIDE_INNER ? inner : 0u;
}

// Reads the fields of node `at` of `nodes` (tlas_wide_nodes or blas_wide_nodes) one by one
// (no struct copy) into the variables of the same names in bvh_trace.
#define BVH_WIDE_READ(nodes, at) \
    node_origin = nodes[at].origin; \
    frame = nodes[at].frame; \
    child_base = nodes[at].child_base; \
    leaf_base = nodes[at].leaf_base; \
    meta = nodes[at].meta; \
    q0 = nodes[at].bounds[0]; \
    q1 = nodes[at].bounds[1]; \
    q2 = nodes[at].bounds[2]

bool bvh_trace(vec3 origin, vec3 dir, float tmin, float tmax, bool any_hit, out TraceHit hit) {
    BvhRay ray = bvh_start(origin, dir, tmax, hit);
    uint oct_inv = bvh_wide_octant(ray.inv);
    bool found = false;
    uvec2 stack[BVH_WIDE_STACK];
    uint sp = 0u;
    // The root: the one inner child (slot 0) of a node group at node 0.
    uvec2 group = uvec2(0u, (BVH_WIDE_INNER << oct_inv) | 1u);
    uvec2 leaves = uvec2(0u);
    // One loop, one step per pass: a leaf primitive, or a node, or a pop.
    while (true) {
        if (leaves.y != 0u) {
            uint bit = uint(findLSB(leaves.y));
            leaves.y &= leaves.y - 1u;
            if (ray.instance != BVH_NONE) {
                if (bvh_leaf_triangle(ray.first_triangle + leaves.x + bit, ray.instance, ray.alpha_tested, ray.o, ray.d, tmin, hit)) {
                    found = true;
                    if (any_hit) {
                        return true;
                    }
                }
                continue;
            }
            // Enter the instance; the TLAS node's children wait on the stack (pushed when the
            // node was visited), its instances left too.
            if (leaves.y != 0u && sp < BVH_WIDE_STACK) {
                stack[sp] = leaves;
                sp++;
            }
            bvh_enter(ray, tlas_wide_words[leaves.x + bit], origin, dir, sp);
            oct_inv = bvh_wide_octant(ray.inv);
            group = uvec2(0u, (BVH_WIDE_INNER << oct_inv) | 1u);
            leaves.y = 0u;
            continue;
        }
        if (group.y >= BVH_WIDE_INNER) {
            // The next child of the node group: its node is child_base plus the inner slots
            // before it.
            uint bit = uint(findMSB(group.y));
            group.y &= ~(1u << bit);
            uint slot = (bit - 24u) ^ oct_inv;
            uint at = group.x + bitCount(group.y & ((1u << slot) - 1u));
            if (group.y >= BVH_WIDE_INNER && sp < BVH_WIDE_STACK) {
                stack[sp] = group;
                sp++;
            }
            bvh_nodes_visited++;
            vec3 node_origin;
            uint frame;
            uint child_base;
            uint leaf_base;
            uvec2 meta;
            uvec4 q0;
            uvec4 q1;
            uvec4 q2;
            if (ray.instance == BVH_NONE) {
                BVH_WIDE_READ(tlas_wide_nodes, at);
            } else {
                BVH_WIDE_READ(blas_wide_nodes, ray.blas_root + at);
            }
            uint inner;
            uint hits;
            bvh_wide_test(node_origin, frame, meta, q0, q1, q2, ray.o, ray.inv, oct_inv, tmin, hit.t, inner, hits);
            group = uvec2(child_base, inner);
            leaves = uvec2(leaf_base, hits);
            // TLAS: the children wait while the instances are entered.
            if (ray.instance == BVH_NONE && hits != 0u && group.y >= BVH_WIDE_INNER && sp < BVH_WIDE_STACK) {
                stack[sp] = group;
                sp++;
                group = uvec2(0u);
            }
            continue;
        }
        if (group.y != 0u && ray.instance == BVH_NONE) {
            // A popped leaf group: TLAS instances left to enter.
            leaves = group;
            group = uvec2(0u);
            continue;
        }
        if (ray.instance != BVH_NONE && sp == ray.base) {
            bvh_leave(ray, origin, dir);
            oct_inv = bvh_wide_octant(ray.inv);
        }
        if (sp == 0u) {
            return found;
        }
        sp--;
        group = stack[sp];
    }
    return found;
}

#endif
