// The radiance of rays that leave the scene: with FRAME_SKY, the sky cube map (the frame's Sky
// draws rendered around the eye, src/render/trace/sky.rs; sRGB texels decoded by the
// sampler, filtered linearly, sampled with the eye-space direction); otherwise the linear
// clear colour frame.environment.

#ifndef TRACE_ENVIRONMENT_GLSL
#define TRACE_ENVIRONMENT_GLSL

#include "trace/scene.glsl"

layout(set = TRACE_SET, binding = BINDING_SKY) uniform samplerCube sky;

// Radiance arriving from eye-space direction `dir` (towards the sky).
vec3 environment(vec3 dir) {
    if ((frame.flags.x & FRAME_SKY) != 0u) {
        return textureLod(sky, dir, 0.0).rgb;
    }
    return frame.environment.rgb;
}

#endif
