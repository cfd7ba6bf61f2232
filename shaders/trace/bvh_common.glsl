// What both compute traversals (bvh.glsl: binary nodes; bvh_wide.glsl: wide nodes with
// quantised boxes) share: the ray-box and ray-triangle tests, the instance transform, the
// traversal's ray and instance state (BvhRay: start, entering and leaving an instance), the
// statistics, the hits in merged regions of chunks (bvh_resolve) and the two queries over the
// including file's bvh_trace(). Include from those
// files only.

#ifndef TRACE_BVH_COMMON_GLSL
#define TRACE_BVH_COMMON_GLSL

#include "generated/trace_constants.glsl"
#include "trace/bindings.glsl"
#include "trace/instance.glsl"
#include "trace/triangles.glsl"

#define BVH_NONE 0xffffffffu
// Entry distance of a missed box.
#define BVH_MISS uintBitsToFloat(0x7f800000u)
// Smallest magnitude of a direction component before inversion.
#define BVH_TINY 1.0e-20
// Widens a box's exit distance to cover rounding (1 + 4 ulp).
#define BVH_BOX_SLACK 1.0000005

// 1 / d with components of magnitude below BVH_TINY replaced by ±BVH_TINY.
vec3 bvh_inverse(vec3 d) {
    vec3 tiny = mix(vec3(-BVH_TINY), vec3(BVH_TINY), greaterThanEqual(d, vec3(0.0)));
    return vec3(1.0) / mix(d, tiny, lessThan(abs(d), vec3(BVH_TINY)));
}

// Entry distance into the box (lo, hi) clipped to [tmin, tmax], or BVH_MISS.
float bvh_box(vec3 lo, vec3 hi, vec3 o, vec3 inv, float tmin, float tmax) {
    vec3 t0 = (lo - o) * inv;
    vec3 t1 = (hi - o) * inv;
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

// Where a traversal is: the ray in the space of the tree being walked (eye space in the TLAS;
// in a BLAS, the instance's object space through its eye_to_object rows, the direction not
// renormalised so that t stays comparable) and the instance being walked.
struct BvhRay {
    vec3 o;
    vec3 d;
    vec3 inv;              // bvh_inverse(d)
    uint instance;         // BVH_NONE: in the TLAS
    uint blas_root;
    uint first_triangle;
    bool alpha_tested;
    uint base;             // stack entries below this belong to the TLAS
};

// The start of a traversal of the ray (origin, dir) up to tmax: in the TLAS, no hit yet.
BvhRay bvh_start(vec3 origin, vec3 dir, float tmax, out TraceHit hit) {
    hit.t = tmax;
    hit.instance = BVH_NONE;
    hit.triangle = BVH_NONE;
    hit.bary = vec2(0.0);
    return BvhRay(origin, dir, bvh_inverse(dir), BVH_NONE, 0u, 0u, false, 0u);
}

// Enters the BLAS of `instance`, its entries on the stack from `sp` on.
void bvh_enter(inout BvhRay ray, uint instance, vec3 origin, vec3 dir, uint sp) {
    ray.instance = instance;
    ray.o = bvh_transform(instances[instance].eye_to_object, origin, 1.0);
    ray.d = bvh_transform(instances[instance].eye_to_object, dir, 0.0);
    ray.inv = bvh_inverse(ray.d);
    ray.blas_root = instances[instance].blas_root;
    ray.first_triangle = instances[instance].first_triangle;
    ray.alpha_tested = (instances[instance].flags & INSTANCE_ALPHA_TESTED) != 0u;
    ray.base = sp;
}

// Back in the TLAS, the ray (origin, dir) in eye space.
void bvh_leave(inout BvhRay ray, vec3 origin, vec3 dir) {
    ray.instance = BVH_NONE;
    ray.o = origin;
    ray.d = dir;
    ray.inv = bvh_inverse(dir);
}

// Work of this invocation's traversals so far (statistics: nodes visited, triangles tested).
uint bvh_nodes_visited = 0u;
uint bvh_triangles_tested = 0u;

// The chunk record and global triangle a hit on global triangle `triangle` of `instance`
// names: the same, or in the merged BVH of a region's chunks (INSTANCE_MERGED), the chunk's
// own record and triangle, which the merged triangle copies (trace/triangles.glsl), so that
// shading reads what it reads for an unmerged chunk.
void bvh_resolve(inout uint instance, inout uint triangle) {
    if ((instances[instance].flags & INSTANCE_MERGED) != 0u) {
        uint member = instances[instance].first_member + triangles[triangle].member;
        triangle = instances[member].first_triangle + triangles[triangle].member_triangle;
        instance = member;
    }
}

// The alpha test of a hit in an alpha-tested instance (trace_alpha_accept); in a merged one,
// of the chunk hit, when that chunk is alpha tested.
bool bvh_alpha_accept(uint instance, uint triangle, vec2 bary) {
    bvh_resolve(instance, triangle);
    return (instances[instance].flags & INSTANCE_ALPHA_TESTED) == 0u || trace_alpha_accept(instance, triangle, bary);
}

// Tests global triangle `triangle` of `instance` against the ray (o, d) in the instance's
// space: whether it is hit with tmin < t < hit.t and accepted (alpha-tested instances ask
// trace_alpha_accept); then `hit` holds it.
bool bvh_leaf_triangle(uint triangle, uint instance, bool alpha_tested, vec3 o, vec3 d, float tmin, inout TraceHit hit) {
    bvh_triangles_tested++;
    float t;
    vec2 bary;
    if (!bvh_triangle(triangles[triangle], o, d, tmin, hit.t, t, bary)) {
        return false;
    }
    if (alpha_tested && !bvh_alpha_accept(instance, triangle, bary)) {
        return false;
    }
    hit.t = t;
    hit.instance = instance;
    hit.triangle = triangle;
    hit.bary = bary;
    return true;
}

// Tests the count triangles from global triangle `first` (bvh_leaf_triangle), keeping in `hit`
// the closest accepted one; with any_hit, stops at the first accepted. Returns whether it
// accepted one.
bool bvh_leaf(uint first, uint count, uint instance, bool alpha_tested, vec3 o, vec3 d, float tmin, bool any_hit, inout TraceHit hit) {
    bool found = false;
    for (uint triangle = first; triangle < first + count; triangle++) {
        if (bvh_leaf_triangle(triangle, instance, alpha_tested, o, d, tmin, hit)) {
            found = true;
            if (any_hit) {
                return true;
            }
        }
    }
    return found;
}

// The traversal of both queries, defined by the including file: with any_hit, returns at the
// first accepted hit.
bool bvh_trace(vec3 origin, vec3 dir, float tmin, float tmax, bool any_hit, out TraceHit hit);

// The closest accepted hit with tmin < t < tmax; false (hit.t = tmax) when none. A hit in a
// merged region names the chunk's record and triangle (bvh_resolve).
bool trace_closest(vec3 origin, vec3 dir, float tmin, float tmax, out TraceHit hit) {
    bool found = bvh_trace(origin, dir, tmin, tmax, false, hit);
    if (found) {
        bvh_resolve(hit.instance, hit.triangle);
    }
    return found;
}

// Whether any accepted hit has tmin < t < tmax (shadow rays); stops at the first.
bool trace_any(vec3 origin, vec3 dir, float tmin, float tmax) {
    TraceHit hit;
    return bvh_trace(origin, dir, tmin, tmax, true, hit);
}

#endif
