#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// One à-trous iteration (denoise/atrous.glsl) with its taps unrolled: the specular channel's
// taps made compilers keep the loop, whose loads are then issued a tap at a time.
#define TAPS_UNROLLED [[unroll]]
#include "denoise/atrous.glsl"
