#version 450
#extension GL_GOOGLE_include_directive : require
// One à-trous iteration (denoise/atrous.glsl) with the taps' loop left to the driver's
// compiler, as before the specular channel: the other side of atrous.comp's unrolling, for
// one comparison on the GPU (GLRT_DENOISE_UNROLL=0, render::denoise::pipelines).
#define TAPS_UNROLLED
#include "denoise/atrous.glsl"
