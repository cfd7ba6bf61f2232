#version 450
// Multiplies the framebuffer's colour by the blurred unoccluded fraction (the pipeline blends
// with factors ZERO, SRC_COLOR and writes rgb only); a full-screen triangle from
// trace_composite.vert.

layout(std430, set = 0, binding = 0) readonly buffer Blurred {
    float blurred[];
};

layout(push_constant) uniform Size {
    uvec2 size;         // framebuffer width, height
} framebuffer;

layout(location = 0) out vec4 color;

void main() {
    uvec2 px = min(uvec2(gl_FragCoord.xy), framebuffer.size - 1u);
    float a = blurred[px.y * framebuffer.size.x + px.x];
    color = vec4(a, a, a, 1.0);
}
