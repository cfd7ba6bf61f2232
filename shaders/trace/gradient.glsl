// Temporal gradient samples (A-SVGF, Schied et al. 2018, section 4; Quake II RTX's
// asvgf_fwd_project and asvgf_gradient_*): in every GRADIENT_STRATUM² stratum of traced
// pixels one pixel a frame repeats a sample of last frame (its random numbers, its surface
// point), so that the difference of the two samples is the change of the lighting alone,
// without noise. The tracer (trace/path.glsl, with FRAME_GRADIENTS) traces them in a pass of
// its own after the main pass, which traces every pixel with this frame's numbers: one
// invocation per stratum, which picks the pixel and where its surface moved traces it through
// the point last frame's sample saw, with that sample's random numbers
// (trace/forward_projection.glsl), into the stratum's G-buffer record after the pixels'; the
// denoiser (shaders/denoise/gradient.comp) compares.

#ifndef TRACE_GRADIENT_GLSL
#define TRACE_GRADIENT_GLSL

#include "generated/trace_constants.glsl"
#include "trace/random.glsl"

// The pixel of `stratum` that is frame `frame_index`'s gradient sample: a per-stratum start
// stepped by 4 of the 9 each frame, so that the samples visit every pixel of a stratum and
// never the pixel of last frame.
uvec2 gradient_pixel(uvec2 stratum, uint frame_index) {
    uint k = (pcg_hash(stratum.x ^ pcg_hash(stratum.y)) % 9u + 4u * (frame_index % 9u)) % 9u;
    return stratum * GRADIENT_STRATUM + uvec2(k % GRADIENT_STRATUM, k / GRADIENT_STRATUM);
}

// Strata per side of a traced image of `size` (those at the far edges may be partial).
uvec2 gradient_strata(uvec2 size) {
    return (size + GRADIENT_STRATUM - 1u) / GRADIENT_STRATUM;
}

// The G-buffer record of `stratum`'s gradient sample: after the records of the image's pixels.
uint gradient_record(uvec2 stratum, uvec2 size) {
    return size.x * size.y + stratum.y * gradient_strata(size).x + stratum.x;
}

#endif
