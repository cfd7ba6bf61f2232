// A light as the tracer and the radiosity pass read it (mirrored by render::trace::gpu_types's
// GpuLight; render::trace::lights converts GL and dynamic lights to it), and the share of a
// positional light's intensity that its reach and spot cone let through.

#ifndef TRACE_LIGHT_GLSL
#define TRACE_LIGHT_GLSL

struct Light {
    vec4 position;  // eye space; w = 0: directional, xyz = unit direction towards the light
    vec4 radiance;  // directional: irradiance at normal incidence; point: intensity (rgb); a: sphere radius (0: a point)
    vec4 spot;      // unit direction the spot points at; w: cos(cutoff), or -2 without a spot
    vec4 params;    // x: spot exponent; y: cos of a directional light's angular radius;
                    // z: directional: shadow ray length (0: to the light); point: reach, beyond which
                    // it fades to nothing (0: unlimited); w: 0, or 1 + the only instance lit,
                    // or -1: a dynamic light, which baked surfaces reflect too
};

// The factor on a positional light's inverse-square incident light at distance d from its
// centre, `axis` the unit direction from the lit point to the centre: 0 outside the spot cone;
// the spot exponent's pow(cos) inside it; a light of limited reach (params.z > 0: a dynamic
// light's radius) fading smoothly to nothing there, (1 - (d / reach)^4)^2 (Karis 2013, "Real
// Shading in Unreal Engine 4").
float light_falloff(Light light, float d, vec3 axis) {
    float k = 1.0;
    if (light.params.z > 0.0) {
        float x = d / light.params.z;
        float fade = clamp(1.0 - x * x * x * x, 0.0, 1.0);
        k = fade * fade;
    }
    if (light.spot.w > -1.5) {
        float c = dot(-axis, light.spot.xyz);
        if (c < light.spot.w) {
            return 0.0;
        }
        k *= light.params.x > 0.0 ? pow(max(c, 0.0), light.params.x) : 1.0;
    }
    return k;
}

#endif
