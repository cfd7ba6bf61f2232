// Random numbers of the path tracer: a PCG hash seeds one stream per pixel, frame and sample
// (Jarzynski and Olano 2020, "Hash Functions for GPU Rendering").

#ifndef TRACE_RANDOM_GLSL
#define TRACE_RANDOM_GLSL

uint pcg_hash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The state of one stream.
struct Rng {
    uint state;
};

Rng rng_seed(uvec2 pixel, uint frame_index, uint sample_index) {
    return Rng(pcg_hash(pixel.x ^ pcg_hash(pixel.y ^ pcg_hash(frame_index ^ pcg_hash(sample_index)))));
}

// A uniform number in [0, 1).
float rng_next(inout Rng rng) {
    rng.state = rng.state * 747796405u + 2891336453u;
    uint word = ((rng.state >> ((rng.state >> 28u) + 4u)) ^ rng.state) * 277803737u;
    word = (word >> 22u) ^ word;
    return float(word >> 8u) * (1.0 / 16777216.0);
}

vec2 rng_next2(inout Rng rng) {
    float a = rng_next(rng);
    return vec2(a, rng_next(rng));
}

#endif
