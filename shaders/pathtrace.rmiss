#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require
// The hardware tracer's miss shader (trace/hardware.glsl): the ray hit nothing.

#include "trace/triangles.glsl"
#include "trace/hardware_payload.glsl"

layout(location = 0) rayPayloadInEXT HitPayload payload;

void main() {
    payload.instance = TRACE_NONE;
}
