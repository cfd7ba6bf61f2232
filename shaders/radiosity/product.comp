#version 450
#extension GL_GOOGLE_include_directive : require
// One step of the k-bounce matrix's Horner sum on the GPU (render::radiosity::gpu::product):
// rows first_row .. first_row + row_count of left + left · right, for one colour channel, the
// n × n matrices row-major f32 (render::radiosity::matrix::ColourMatrix's channels). Each
// workgroup computes a RADIOSITY_PRODUCT_TILE square of results, each of its 16 × 16
// invocations a 4 × 4 block of it, the factors staged through shared memory DEPTH inner
// indices at a time. Every result sums left[i][k] · right[k][j] over k in order, then adds
// left[i][j] (the CPU's order: ColourMatrix::multiply, then add).

#include "generated/radiosity_constants.glsl"

#define TILE RADIOSITY_PRODUCT_TILE
#define DEPTH 16u

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 0, binding = RADIOSITY_BINDING_PRODUCT_LEFT, std430) readonly buffer Left {
    float left[];
};

layout(set = 0, binding = RADIOSITY_BINDING_PRODUCT_RIGHT, std430) readonly buffer Right {
    float right[];
};

layout(set = 0, binding = RADIOSITY_BINDING_PRODUCT_ROWS, std430) writeonly buffer Rows {
    float rows[];   // row first_row + r at r * n
};

layout(push_constant) uniform ProductPass {
    uint n;
    uint first_row;
    uint row_count;
    uint pad;
} pass;

// The staged factors, 4 rows (columns) a vec4, so that an invocation reads its 4 with one load.
shared vec4 left_tile[DEPTH][TILE / 4u];   // [k][row / 4][row % 4]
shared vec4 right_tile[DEPTH][TILE / 4u];  // [k][column / 4][column % 4]

void main() {
    uint n = pass.n;
    uint end = pass.first_row + pass.row_count;
    uint row0 = pass.first_row + gl_WorkGroupID.y * TILE;
    uint column0 = gl_WorkGroupID.x * TILE;
    uint tx = gl_LocalInvocationID.x;
    uint ty = gl_LocalInvocationID.y;
    uint id = ty * 16u + tx;
    float sum[4][4];
    for (uint a = 0u; a < 4u; a++) {
        for (uint b = 0u; b < 4u; b++) {
            sum[a][b] = 0.0;
        }
    }
    for (uint k0 = 0u; k0 < n; k0 += DEPTH) {
        // Each invocation stages 4 of the TILE × DEPTH left entries and 4 of the
        // DEPTH × TILE right entries (outside the matrix: 0).
        for (uint q = 0u; q < 4u; q++) {
            uint e = id + q * 256u;
            uint r = e / DEPTH;
            uint kl = e % DEPTH;
            uint i = row0 + r;
            left_tile[kl][r / 4u][r % 4u] = (i < end && k0 + kl < n) ? left[i * n + k0 + kl] : 0.0;
            uint kr = e / TILE;
            uint c = e % TILE;
            right_tile[kr][c / 4u][c % 4u] = (k0 + kr < n && column0 + c < n) ? right[(k0 + kr) * n + column0 + c] : 0.0;
        }
        barrier();
        for (uint k = 0u; k < DEPTH; k++) {
            vec4 l = left_tile[k][ty];
            vec4 r = right_tile[k][tx];
            for (uint a = 0u; a < 4u; a++) {
                for (uint b = 0u; b < 4u; b++) {
                    sum[a][b] += l[a] * r[b];
                }
            }
        }
        barrier();
    }
    for (uint a = 0u; a < 4u; a++) {
        uint i = row0 + ty * 4u + a;
        for (uint b = 0u; b < 4u; b++) {
            uint j = column0 + tx * 4u + b;
            if (i < end && j < n) {
                rows[(i - pass.first_row) * n + j] = sum[a][b] + left[i * n + j];
            }
        }
    }
}
