#version 450
#extension GL_GOOGLE_include_directive : require
// The fixed-function vertex stage with every varying (ff_vertex.glsl).
#include "ff_vertex.glsl"
