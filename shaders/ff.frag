#version 450
#extension GL_GOOGLE_include_directive : require
// The fixed-function fragment stage with every varying (ff_fragment.glsl).
#include "ff_fragment.glsl"
