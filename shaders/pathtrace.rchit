#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require
// The hardware tracer's closest-hit shader (trace/hardware.glsl): records the hit as the
// compute tracer's traversal returns it.

#include "trace/instance.glsl"
#include "trace/triangles.glsl"
#include "trace/hardware_payload.glsl"

layout(location = 0) rayPayloadInEXT HitPayload payload;
hitAttributeEXT vec2 bary;

void main() {
    payload.t = gl_HitTEXT;
    // A merged region's geometry k is the chunk of record custom index + k (hardware.glsl).
    uint instance = gl_InstanceCustomIndexEXT + gl_GeometryIndexEXT;
    payload.instance = instance;
    payload.triangle = instances[instance].first_triangle + gl_PrimitiveID;
    payload.bary = bary;
}
