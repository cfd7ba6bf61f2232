#version 450
#extension GL_GOOGLE_include_directive : require
// The N x N box blur of the occlusion (seed 000): the mean over the pixels of the square
// centred on each pixel (N odd) or on its lower-left corner (N even) that lie inside the image.

#include "ao/params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) readonly buffer Params { AoParams p; };
layout(std430, set = 0, binding = 1) readonly buffer Raw { float raw[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Blurred { float blurred[]; };

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(p.sizes.xy);
    if (px.x >= size.x || px.y >= size.y) {
        return;
    }
    int n = int(p.blur.x);
    int lo = -(n / 2);
    float sum = 0.0;
    float count = 0.0;
    for (int j = lo; j < lo + n; j++) {
        for (int i = lo; i < lo + n; i++) {
            ivec2 q = px + ivec2(i, j);
            if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size))) {
                sum += raw[uint(q.y) * p.sizes.x + uint(q.x)];
                count += 1.0;
            }
        }
    }
    blurred[uint(px.y) * p.sizes.x + uint(px.x)] = sum / count;
}
