// Temporal gradient samples (A-SVGF, Schied et al. 2018, section 4; Quake II RTX's
// asvgf_fwd_project and asvgf_gradient_*): in every GRADIENT_STRATUM² stratum of traced
// pixels one pixel a frame repeats a sample of last frame (its random numbers, its surface
// point), so that the difference of the two samples is the change of the lighting alone,
// without noise. The tracer (trace/path.glsl, with FRAME_GRADIENTS)
// picks the pixel and its seed, and where its surface moved traces it through the point last
// frame's sample saw, with that sample's random numbers (trace/forward_projection.glsl); the
// denoiser (shaders/denoise/gradient.comp) compares.

#ifndef TRACE_GRADIENT_GLSL
#define TRACE_GRADIENT_GLSL

#include "trace/random.glsl"

// Traced pixels per stratum side.
const uint GRADIENT_STRATUM = 3u;

// The pixel of `stratum` that is frame `frame_index`'s gradient sample: a per-stratum start
// stepped by 4 of the 9 each frame, so that it is never last frame's (whose own sample then
// was drawn with last frame's seed).
uvec2 gradient_pixel(uvec2 stratum, uint frame_index) {
    uint k = (pcg_hash(stratum.x ^ pcg_hash(stratum.y)) % 9u + 4u * (frame_index % 9u)) % 9u;
    return stratum * GRADIENT_STRATUM + uvec2(k % GRADIENT_STRATUM, k / GRADIENT_STRATUM);
}

#endif
