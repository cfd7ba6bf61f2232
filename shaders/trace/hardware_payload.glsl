// The payload of the hardware tracer's rays (hardware.glsl): the closest hit, or instance
// TRACE_NONE after a miss.

#ifndef TRACE_HARDWARE_PAYLOAD_GLSL
#define TRACE_HARDWARE_PAYLOAD_GLSL

struct HitPayload {
    float t;        // distance along the ray
    uint instance;  // the instance's custom index, TRACE_NONE when missed
    uint triangle;  // global triangle index
    vec2 bary;      // weights of v1 and v2
};

#endif
