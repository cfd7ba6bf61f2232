#version 450
#extension GL_GOOGLE_include_directive : require
// The per-frame product (render::radiosity::gpu::gather): each patch's radiosity, its primary
// radiosity plus the k-bounce matrix times every patch's primary radiosity, the matrix read as
// the compressed form stands for it (render::radiosity::compress): the BC1 image sampled as
// a BC1 image (codes round(texel * 255), log-decoded as quantise::decode does) in the
// reordered rows and columns, plus the exact part's entries of the row. One workgroup per
// row: its invocations stride across the columns, then sum in shared memory.

#include "generated/radiosity_constants.glsl"

layout(local_size_x = RADIOSITY_GROUP) in;

struct SparseEntry {
    vec3 value;     // per channel
    uint column;    // the source patch
};

layout(set = 0, binding = RADIOSITY_BINDING_MATRIX) uniform sampler2D matrix;

layout(set = 0, binding = RADIOSITY_BINDING_ORDER, std430) readonly buffer Order {
    uint order[];
};

layout(set = 0, binding = RADIOSITY_BINDING_SPARSE_OFFSETS, std430) readonly buffer SparseOffsets {
    uint sparse_offsets[];
};

layout(set = 0, binding = RADIOSITY_BINDING_SPARSE_ENTRIES, std430) readonly buffer SparseEntries {
    SparseEntry sparse_entries[];
};

layout(set = 0, binding = RADIOSITY_BINDING_PRIMARY, std430) readonly buffer Primary {
    vec4 primary[];
};

layout(set = 0, binding = RADIOSITY_BINDING_RADIOSITY, std430) writeonly buffer Radiosity {
    vec4 radiosity[];
};

layout(push_constant) uniform GatherPass {
    uint patch_count;
    float max_value;  // the quantised part's largest value
    float shift;      // its log shift
    uint pad;
} pass;

shared vec3 partial[RADIOSITY_GROUP];

// quantise::decode of the code a texel channel holds.
vec3 decode(vec3 texel) {
    vec3 q = round(texel * 255.0);
    vec3 v = pass.max_value * exp((q - 1.0) * (pass.shift / 254.0) - pass.shift);
    return mix(v, vec3(0.0), lessThan(q, vec3(0.5)));
}

void main() {
    uint a = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    uint lane = gl_LocalInvocationID.x;
    uint n = pass.patch_count;
    vec3 sum = vec3(0.0);
    if (a < n) {
        for (uint b = lane; b < n; b += RADIOSITY_GROUP) {
            sum += decode(texelFetch(matrix, ivec2(b, a), 0).rgb) * primary[order[b]].rgb;
        }
        uint i = order[a];
        for (uint k = sparse_offsets[i] + lane; k < sparse_offsets[i + 1u]; k += RADIOSITY_GROUP) {
            sum += sparse_entries[k].value * primary[sparse_entries[k].column].rgb;
        }
    }
    partial[lane] = sum;
    barrier();
    for (uint s = RADIOSITY_GROUP / 2u; s > 0u; s >>= 1u) {
        if (lane < s) {
            partial[lane] += partial[lane + s];
        }
        barrier();
    }
    if (lane == 0u && a < n) {
        uint i = order[a];
        radiosity[i] = vec4(primary[i].rgb + partial[0], 0.0);
    }
}
