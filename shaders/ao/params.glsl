// The block of the ambient occlusion passes (src/render/ao; seed 000), mirrored by
// GpuAoParams (src/render/ao/gpu.rs), checked against the compiled SPIR-V. The framebuffer's
// depth arrives as a copy in a storage buffer, rows top to bottom as Vulkan stores images.

#ifndef AO_PARAMS_GLSL
#define AO_PARAMS_GLSL

#define AO_MAX_SAMPLES 256

struct AoParams {
    mat4 projection;            // the camera draw's: eye -> clip (GL)
    mat4 inverse_projection;    // GL normalized device coordinates -> eye
    vec4 viewport;              // x, y, width, height (GL window pixels, y up)
    vec4 shape;                 // glDepthRange near, far; radius R, bias delta
    uvec4 sizes;                // framebuffer width, height; samples m; depth encoding (0 f32, 1 unorm24)
    uvec4 blur;                 // N of the N x N box blur
    vec4 noise[16];             // the 4 x 4 noise tile: random tangent-plane vectors (z = 0)
    vec4 kernel[AO_MAX_SAMPLES];// hemisphere samples in tangent space (z >= 0), |k| <= 1
};

#endif
