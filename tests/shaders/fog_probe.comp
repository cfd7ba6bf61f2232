// Evaluates height_fog_amount of shaders/fog/height.glsl at a list of segments
// (tests/fog/formula.rs): result i = F(rho0, b, h0, h1, s) of query i.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "fog/height.glsl"

layout(local_size_x = 64) in;

struct Query {
    float rho0;
    float b;
    float h0;
    float h1;
    float s;
    float unused0;
    float unused1;
    float unused2;
};

layout(set = 0, binding = 0, std430) readonly buffer Queries {
    Query queries[];
};

layout(set = 0, binding = 1, std430) writeonly buffer Results {
    float results[];
};

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(queries.length())) {
        return;
    }
    Query q = queries[i];
    results[i] = height_fog_amount(q.rho0, q.b, q.h0, q.h1, q.s);
}
