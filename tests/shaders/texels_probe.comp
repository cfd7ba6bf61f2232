// Samples the texel pool at a list of queries (tests/pathtrace/texels.rs): one invocation per
// query, result i = (texel_sample(texture, uv, lod)), and the texture's texel_size in a
// second vec4.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "trace/texels.glsl"

layout(local_size_x = 64) in;

struct Query {
    uint tex;
    float u;
    float v;
    float lod;
};

layout(set = TRACE_SET, binding = 0, std430) readonly buffer Queries {
    Query queries[];
};

layout(set = TRACE_SET, binding = 1, std430) writeonly buffer Results {
    vec4 results[];
};

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(queries.length())) {
        return;
    }
    Query q = queries[i];
    results[2u * i] = texel_sample(q.tex, vec2(q.u, q.v), q.lod);
    results[2u * i + 1u] = vec4(texel_size(q.tex), 0.0, 0.0);
}
