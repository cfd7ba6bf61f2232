// Ray traversal of the hardware tracer (render::trace::hardware): trace_closest() and
// trace_any(), the same queries as bvh.glsl's, through VK_KHR_ray_tracing_pipeline over the
// frame's top-level acceleration structure. Each instance's custom index is its index into
// `instances`, its geometry's primitive k is the instance's triangle first_triangle + k (the
// bottom-level structures are built from the triangle buffer in BVH order), and rays are in
// eye space as for the compute tracer, so hits mean the same to shading. The chunks of a
// region of the static world are one instance of a structure with a geometry per chunk
// (render::trace::regions): geometry g is the chunk whose record is the custom index
// + g, so the hit shaders take gl_InstanceCustomIndexEXT + gl_GeometryIndexEXT (0 elsewhere).
//
// Shaders: pathtrace.rchit records the closest hit in the payload, pathtrace.rmiss marks a
// miss, pathtrace.rahit runs the alpha test (trace_alpha_accept, surface.glsl) for the
// instances without VK_GEOMETRY_INSTANCE_FORCE_OPAQUE and the merged chunks without
// VK_GEOMETRY_OPAQUE (those with INSTANCE_ALPHA_TESTED).

#ifndef TRACE_HARDWARE_GLSL
#define TRACE_HARDWARE_GLSL

#extension GL_EXT_ray_tracing : require

#include "trace/bindings.glsl"
#include "trace/triangles.glsl"
#include "trace/hardware_payload.glsl"

layout(set = TRACE_SET, binding = BINDING_ACCELERATION) uniform accelerationStructureEXT scene_tlas;

layout(location = 0) rayPayloadEXT HitPayload payload;

// Traversal work: the hardware does not report it.
uint bvh_nodes_visited = 0u;
uint bvh_triangles_tested = 0u;

// The closest accepted hit with tmin < t < tmax; false (hit.t = tmax) when none.
bool trace_closest(vec3 origin, vec3 dir, float tmin, float tmax, out TraceHit hit) {
    payload.instance = TRACE_NONE;
    traceRayEXT(scene_tlas, gl_RayFlagsNoneEXT, 0xff, 0, 0, 0, origin, tmin, dir, tmax, 0);
    bool found = payload.instance != TRACE_NONE;
    hit.t = found ? payload.t : tmax;
    hit.instance = payload.instance;
    hit.triangle = payload.triangle;
    hit.bary = payload.bary;
    return found;
}

// Whether any accepted hit has tmin < t < tmax (shadow rays); stops at the first.
bool trace_any(vec3 origin, vec3 dir, float tmin, float tmax) {
    // The miss shader clears it; no closest-hit shader runs.
    payload.instance = 0u;
    traceRayEXT(scene_tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT, 0xff, 0, 0, 0, origin, tmin, dir, tmax, 0);
    return payload.instance != TRACE_NONE;
}

#endif
