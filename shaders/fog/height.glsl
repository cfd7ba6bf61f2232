// Analytic height fog (seed 002; src/render/fog/mod.rs explains where it applies). One source
// for both modes: ff.frag fogs every rasterized 3D fragment with it, trace_composite.frag the
// traced primary hits it composites. The block is mirrored by GpuHeightFog
// (src/render/fog/mod.rs), checked against the compiled SPIR-V.

#ifndef FOG_HEIGHT_GLSL
#define FOG_HEIGHT_GLSL

struct HeightFog {
    mat4 window_to_world;   // (gl_FragCoord.xyz, 1) -> world position, homogeneous
    vec4 eye;               // the eye O in the world; w: 1 where the fog applies, 0 elsewhere
    vec4 up;                // unit world up; w: the height of the origin of the density
    vec4 density;           // rho0, falloff b, unused, unused
    vec4 color;             // what the fragment fades to (rgb, framebuffer values): the fog colour,
                            // or the neutral colour of a pass that adds to or multiplies the framebuffer
};

// (1 - e^-x) / x for x >= 0, without the cancellation of 1 - e^-x near 0: its Taylor series
// below x = 1/16 (truncation below 2e-9), the closed form above (relative error below 2e-6).
float fog_ratio(float x) {
    if (x < 0.0625) {
        return 1.0 - x * (0.5 - x * (1.0 / 6.0 - x * (1.0 / 24.0 - x * (1.0 / 120.0))));
    }
    return (1.0 - exp(-x)) / x;
}

// The fog amount F on a segment of length s between heights h0 and h1 (above the density's
// origin) of the density rho(z) = rho0 e^(-b z): the integral of rho along the segment,
//   F = rho0 e^(-b h0) (1 - e^(-b Dz s)) / (b Dz),   Dz s = h1 - h0,
// as seed 002 writes it for O at h0. The integral does not depend on the direction the segment
// is walked, so it is taken from its lower end: rho0 e^(-b min) s (1 - e^-x) / x with
// x = b |h1 - h0| >= 0, which never overflows in the ratio and has the limit rho0 e^(-b h0) s
// for Dz -> 0 (and for b = 0) in fog_ratio's series.
float height_fog_amount(float rho0, float b, float h0, float h1, float s) {
    if (!(s > 0.0) || !(rho0 > 0.0)) {
        return 0.0;
    }
    float low = min(h0, h1);
    return rho0 * exp(-b * low) * s * fog_ratio(b * abs(h1 - h0));
}

// `color` of the fragment at window position `frag` (gl_FragCoord.xyz) after the fog on the
// segment from the eye to it: mix(color, fog.color, clamp(F, 0, 1)).
vec3 height_fog_apply(HeightFog fog, vec3 frag, vec3 color) {
    if (fog.eye.w == 0.0) {
        return color;
    }
    vec4 w = fog.window_to_world * vec4(frag, 1.0);
    vec3 p = w.xyz / w.w;
    float h0 = dot(fog.eye.xyz, fog.up.xyz) - fog.up.w;
    float h1 = dot(p, fog.up.xyz) - fog.up.w;
    float f = height_fog_amount(fog.density.x, fog.density.y, h0, h1, length(p - fog.eye.xyz));
    return mix(color, fog.color.rgb, clamp(f, 0.0, 1.0));
}

#endif
