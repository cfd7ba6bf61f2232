// What a ray hit: the shading inputs of a traced triangle (position, normals; albedo, emission
// and whether it is baked from the material's layer stack, stack.glsl; material), and the
// alpha test that traversal asks for. render::trace::material's module doc describes the
// layers and what the surface makes of them.
// Include after bvh.glsl's prerequisites: defines trace_alpha_accept(), then includes the
// traversal (below).

#ifndef TRACE_SURFACE_GLSL
#define TRACE_SURFACE_GLSL

#include "trace/scene.glsl"
#include "trace/pack.glsl"
#include "trace/texels.glsl"
#include "trace/brdf.glsl"
#include "trace/stack.glsl"

// Traversal's question for alpha-tested instances: does the alpha test pass at this point?
// (The base's own colour, its units' result, sampled at the base level: traversal knows no
// ray cone.)
bool trace_alpha_accept(uint instance, uint triangle, vec2 bary) {
    Material m = materials[instances[instance].material];
    TriangleAttributes a = attributes[triangle];
    vec4 texel[MAX_UNITS];
    unit_texels(m, a, bary, 0.0, 0.0, 1.0, texel);
    float alpha = units_color(m, corner_color(a, bary), texel, false).a;
    return compare(m.alpha_func, alpha, m.alpha_ref);
}

// The traversal: the compute tracer's wide BVHs (with TRACE_BVH_BINARY its binary ones), or
// with TRACE_HARDWARE the ray-tracing pipeline; none in the hardware tracer's any-hit shader
// (TRACE_HARDWARE_ANY_HIT), which only shades.
#if defined(TRACE_HARDWARE_ANY_HIT)
#include "trace/triangles.glsl"
#elif defined(TRACE_HARDWARE)
#include "trace/hardware.glsl"
#elif defined(TRACE_BVH_BINARY)
#include "trace/bvh.glsl"
#else
#include "trace/bvh_wide.glsl"
#endif

// The object-space corners of global triangle `triangle`.
void trace_triangle_vertices(uint triangle, out vec3 v0, out vec3 v1, out vec3 v2) {
    BvhTriangle t = triangles[triangle];
    v0 = t.v0;
    v1 = v0 + t.e1;
    v2 = v0 + t.e2;
}

// An object-space vector or point through the instance's rows.
vec3 instance_transform(vec4 rows[3], vec4 v) {
    return vec3(dot(rows[0], v), dot(rows[1], v), dot(rows[2], v));
}

// The shading inputs at `hit` of a ray (origin, unit dir); cone_width is the ray cone's width
// at the hit (texture level of detail).
Surface surface_at(TraceHit hit, vec3 origin, vec3 dir, float cone_width) {
    Instance inst = instances[hit.instance];
    TriangleAttributes a = attributes[hit.triangle];
    Material m = materials[inst.material];
    vec3 p0, p1, p2;
    trace_triangle_vertices(hit.triangle, p0, p1, p2);
    vec3 e1 = instance_transform(inst.object_to_eye, vec4(p1 - p0, 0.0));
    vec3 e2 = instance_transform(inst.object_to_eye, vec4(p2 - p0, 0.0));
    vec3 ng = cross(e1, e2);
    float area2 = length(ng);
    ng = area2 > 0.0 ? ng / area2 : -dir;
    bool back = dot(ng, dir) > 0.0;
    if (back) {
        ng = -ng;
    }

    Surface s;
    s.position = origin + dir * hit.t;
    s.geometric = ng;
    s.normal = ng;
    if (a.corner[0].normal != 0u || a.corner[1].normal != 0u || a.corner[2].normal != 0u) {
        float w0 = 1.0 - hit.bary.x - hit.bary.y;
        vec3 n = unpack_normal(a.corner[0].normal) * w0 + unpack_normal(a.corner[1].normal) * hit.bary.x
            + unpack_normal(a.corner[2].normal) * hit.bary.y;
        // Normals go through the inverse transpose: the columns of eye_to_object's rows.
        n = inst.eye_to_object[0].xyz * n.x + inst.eye_to_object[1].xyz * n.y + inst.eye_to_object[2].xyz * n.z;
        float len = length(n);
        if (len > 0.0) {
            n /= len;
            s.normal = dot(n, ng) < 0.0 ? -n : n;
        }
    }

    float cos_view = max(abs(dot(ng, dir)), 1e-3);
    vec4 texel[MAX_UNITS];
    unit_texels(m, a, hit.bary, area2, cone_width, cos_view, texel);
    uint local = hit.triangle - inst.first_triangle;
    Stack st = surface_stack(m, local, a, hit.bary, texel, area2, cone_width, cos_view);
    s.albedo = srgb_to_linear(st.albedo.rgb);
    s.alpha = st.alpha;
    // render::trace::material's module doc: emission E is what the emission passes add to the
    // display, the GL material's emission and the glrt.toml emissive scale; a baked surface
    // emits its raster colour (E included) and reflects no traced light.
    vec3 base = srgb_to_linear(st.base.rgb);
    vec3 light = max(srgb_to_linear(st.color.rgb) - base, vec3(0.0)) + m.emission.rgb + base * m.emission.a;
    s.baked = (m.flags & MATERIAL_BAKED) != 0u;
    s.emission = s.baked ? base + light : light;
    bool listed = m.emitters != NO_EMITTER && area2 > 0.0;
    s.sampled_emission = listed ? light : vec3(0.0);
    s.emitter_density = listed ? emitters[m.emitters + local].probability * 2.0 / area2 : 0.0;
    s.roughness = m.roughness;
    s.metalness = m.metalness;
    s.specular = m.specular;
    return s;
}

#endif
