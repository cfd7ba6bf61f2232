// Next-event estimation of the sky (render::trace::sky_distribution, whose formulas these
// are): a direction drawn in proportion to the sky cube map's luminance times solid angle over
// SKY_CELLS² cells a face (a cell by the cumulative distribution, then a point uniform in the
// cell's face coordinates), one shadow ray to infinity. Continuation rays that miss find the
// sky too, so both strategies are weighted by the power heuristic (trace/emitters.glsl).
// Only with FRAME_SKY_SAMPLED: the SKY_DISTRIBUTION binding then holds the cells. A vertex
// takes the sky sample with the frame's probability (render::trace::sky_selection), so the
// sample's density is that probability times the direction's. A gradient sample, which
// replays last frame's random numbers (trace/gradient.glsl), samples with last frame's
// probability and cells (held after this frame's) in last frame's eye space (turned by
// replay_rotation, trace/sampling.glsl), so that it makes last frame's choices: the sky's
// cube map and its distribution are in eye space and change while the camera turns.

#ifndef TRACE_SKY_SAMPLING_GLSL
#define TRACE_SKY_SAMPLING_GLSL

#include "trace/emitters.glsl"
#include "trace/environment.glsl"

// Per cell (face · SKY_CELLS² + row · SKY_CELLS + column): its probability, and the
// cumulative probability up to and including it; this frame's cells, then last frame's
// where frame.sampling.y > 0.
layout(set = TRACE_SET, binding = BINDING_SKY_DISTRIBUTION, std430) readonly buffer SkyDistribution {
    vec2 sky_cells[];
};

const uint SKY_CELL_COUNT = 6u * uint(SKY_CELLS) * uint(SKY_CELLS);

// The probability that a path vertex samples the sky this frame, or with `last_frame` last
// frame's (0: the sky is found by continuation rays alone).
float sky_selection(bool last_frame) {
    if ((frame.flags.x & FRAME_SKY_SAMPLED) == 0u) {
        return 0.0;
    }
    return last_frame ? frame.sampling.y : frame.sampling.x;
}

// The first of this frame's cells, or with `last_frame` of last frame's.
uint sky_first_cell(bool last_frame) {
    return last_frame ? SKY_CELL_COUNT : 0u;
}

// The direction (not normalised) of face coordinates (s, t) of cube face `face` (Vulkan's
// layer order, t from the top row).
vec3 sky_face_direction(uint face, float s, float t) {
    switch (face) {
    case 0u: return vec3(1.0, -t, -s);
    case 1u: return vec3(-1.0, -t, s);
    case 2u: return vec3(s, 1.0, t);
    case 3u: return vec3(s, -1.0, -t);
    case 4u: return vec3(s, -t, 1.0);
    default: return vec3(-s, -t, -1.0);
    }
}

// The density in solid angle at face coordinates (s, t) of cell `cell`.
float sky_cell_density(uint cell, float s, float t) {
    float area = (2.0 / float(SKY_CELLS)) * (2.0 / float(SKY_CELLS));
    float r2 = 1.0 + s * s + t * t;
    return sky_cells[cell].x / area * r2 * sqrt(r2);
}

// The density in solid angle with which sky_sample draws direction `towards` (Vulkan's cube
// map face selection).
float sky_density(vec3 towards, bool last_frame) {
    vec3 d = transpose(replay_rotation) * towards;
    vec3 a = abs(d);
    uint face;
    float sc, tc, ma;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x > 0.0 ? 0u : 1u;
        sc = d.x > 0.0 ? -d.z : d.z;
        tc = -d.y;
        ma = a.x;
    } else if (a.y >= a.z) {
        face = d.y > 0.0 ? 2u : 3u;
        sc = d.x;
        tc = d.y > 0.0 ? d.z : -d.z;
        ma = a.y;
    } else {
        face = d.z > 0.0 ? 4u : 5u;
        sc = d.z > 0.0 ? d.x : -d.x;
        tc = -d.y;
        ma = a.z;
    }
    float s = sc / ma, t = tc / ma;
    uvec2 index = uvec2(clamp(floor((vec2(s, t) + 1.0) * 0.5 * float(SKY_CELLS)), 0.0, float(SKY_CELLS) - 1.0));
    return sky_cell_density(sky_first_cell(last_frame) + face * uint(SKY_CELLS) * uint(SKY_CELLS) + index.y * uint(SKY_CELLS) + index.x, s, t);
}

// A direction (unit) drawn by the uniform numbers u; returns its density in solid angle.
float sky_sample(vec3 u, bool last_frame, out vec3 dir) {
    // The first cell whose cumulative probability exceeds u.x.
    uint first = sky_first_cell(last_frame);
    uint low = first, high = first + SKY_CELL_COUNT - 1u;
    while (low < high) {
        uint mid = (low + high) / 2u;
        if (sky_cells[mid].y <= u.x) {
            low = mid + 1u;
        } else {
            high = mid;
        }
    }
    uint cells = uint(SKY_CELLS);
    uint cell = low - first;
    uint face = cell / (cells * cells), row = cell / cells % cells, column = cell % cells;
    float s = 2.0 * (float(column) + u.y) / float(SKY_CELLS) - 1.0;
    float t = 2.0 * (float(row) + u.z) / float(SKY_CELLS) - 1.0;
    dir = replay_rotation * normalize(sky_face_direction(face, s, t));
    return sky_cell_density(low, s, t);
}

// The pixels of a tile make the choice of a sky sample together: a subgroup of 32 invocations
// is 8 × 4 pixels of the tracing pass's 8 × 8 groups, and a shadow ray taken by one of its
// lanes holds the others back, so a choice per lane at probability 1/16 still cost more than
// half of a sky sample at every vertex (the demo on the H200: tracing 19.2 ms against 13.4 ms
// without sky samples and 22.4 ms with one at every vertex).
const uvec2 SKY_CHOICE_TILE = uvec2(8u, 4u);

// Whether vertex `depth` of a path drawing the numbers of `pixel` samples the sky, with
// probability `chance`: one choice for every pixel of its tile, drawn from numbers of the
// tile, frame, sample and depth alone (independent of each path's own numbers, so every pixel
// still samples with probability `chance`, and a gradient sample replaying last frame's
// numbers of its source, with last frame's probability, makes the source's choice).
bool sky_chosen(uvec2 pixel, uint frame_index, uint sample_index, uint depth, float chance) {
    if (chance >= 1.0) {
        return true;
    }
    Rng tile = rng_seed(pixel / SKY_CHOICE_TILE, frame_index ^ 0x68e31da4u, pcg_hash(sample_index) + depth);
    return rng_next(tile) < chance;
}

// Rays of the sky samples of a path, in one word (a path carries it through its bounces, and
// it has at most 9 of each: [pathtrace] bounces is at most 8): traced (bits 0-15), and those
// that found the sky (bits 16-31; render::trace::sky_selection reads them).
const uint SKY_RAY_TRACED = 1u;
const uint SKY_RAY_UNOCCLUDED = 0x10000u;

// The sky's light reflected towards v at s from one sky sample taken with probability
// `selection`, from this frame's cells or with `last_frame` last frame's, where its shadow ray
// to infinity is not occluded; `weighted`: a continuation ray leaves s and finds the sky where
// it misses, so the sample takes its MIS weight (where the path ends at s, at radiosity's
// vertex, it counts whole). Its ray is traced whenever the sample has a direction (the counts
// of sky rays then follow the sky's visibility alone).
ShadowSample sky_light(Surface s, vec3 v, float selection, bool last_frame, bool weighted, inout Rng rng) {
    vec3 l;
    float density = selection * sky_sample(vec3(rng_next2(rng), rng_next(rng)), last_frame, l);
    vec3 fs = brdf_specular_cos(s, v, l);
    vec3 f = brdf_diffuse_cos(s, v, l) + fs;
    if (density <= 0.0 || all(equal(f, vec3(0.0)))) {
        return unshadowed(vec3(0.0));
    }
    uint share = specular_share(f, fs);
    return ShadowSample(f * environment(l) * ((weighted ? mis_weight(density, brdf_pdf(s, v, l)) : 1.0) / density), share, l, 1e30);
}

#endif
