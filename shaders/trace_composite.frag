#version 450
// Draws the traced image into the raster framebuffer with its depth (thesis 4.3.6): pixels
// whose primary ray hit get the tone-mapped colour and the hit's window depth (depth test
// LEQUAL, so raster draws made earlier and nearer stay); pixels whose ray missed keep what the
// framebuffer holds (the clear colour, the sky). Translucent and overlay draws that follow are
// depth-tested against the traced depth. The height fog (fog/height.glsl) fogs each hit on the
// segment from the eye to it, with the camera draw's mapping from window to world.
#extension GL_GOOGLE_include_directive : require

#include "fog/height.glsl"

layout(std430, set = 0, binding = 0) readonly buffer Output {
    uvec2 outputs[];    // trace/gbuffer.glsl OutputSample: colour, depth bits
};

layout(std430, set = 0, binding = 1) readonly buffer Fog {
    HeightFog fog;      // zero: no fog
};

layout(push_constant) uniform Sizes {
    uvec2 traced;       // traced image size
    uvec2 window;       // framebuffer size
} sizes;

layout(location = 0) out vec4 color;

void main() {
    // Framebuffer row 0 is the top of the window; traced row 0 is the bottom (GL).
    vec2 window = vec2(gl_FragCoord.x, float(sizes.window.y) - gl_FragCoord.y);
    uvec2 pixel = min(uvec2(window * vec2(sizes.traced) / vec2(sizes.window)), sizes.traced - 1u);
    uvec2 o = outputs[pixel.y * sizes.traced.x + pixel.x];
    float depth = uintBitsToFloat(o.y);
    if (depth >= 1.0) {
        discard;
    }
    color = unpackUnorm4x8(o.x);
    color.rgb = height_fog_apply(fog, vec3(gl_FragCoord.xy, depth), color.rgb);
    gl_FragDepth = depth;
}
