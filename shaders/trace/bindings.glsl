// Descriptor bindings of the compute path tracer (set 0 of every tracing pipeline). Mirrors
// src/render/trace/bindings.rs. Every buffer is a std430 storage buffer: lavapipe inlines
// uniform-buffer values and recompiles per value (see ff_uniforms.glsl), and has no descriptor
// indexing, so scene data lives in a fixed set of large buffers. The one image is the sky's
// cube map, after the buffers.

#ifndef TRACE_BINDINGS_GLSL
#define TRACE_BINDINGS_GLSL

#define TRACE_SET 0
#define BINDING_FRAME 0        // TraceFrame: camera, settings, counts (scene.glsl)
#define BINDING_BLAS_NODES 1   // bottom-level BVH nodes of every geometry (bvh.glsl)
#define BINDING_TLAS_NODES 2   // top-level BVH over the instances, rebuilt per frame (bvh.glsl)
#define BINDING_TRIANGLES 3    // triangle positions in BVH order (bvh.glsl)
#define BINDING_INSTANCES 4    // Instance records (scene.glsl)
#define BINDING_ATTRIBUTES 5   // per-triangle shading attributes, in BVH order (scene.glsl)
#define BINDING_MATERIALS 6    // Material records (scene.glsl)
#define BINDING_LIGHTS 7       // Light records (scene.glsl)
#define BINDING_TEXELS 8       // the texel pool (texels.glsl)
#define BINDING_TEXTURES 9     // the texture table into the pool (texels.glsl)
#define BINDING_ACCUMULATION 10 // running radiance sums per pixel
#define BINDING_GBUFFER 11     // primary-hit G-buffer per pixel
#define BINDING_OUTPUT 12      // tone-mapped colour and depth per pixel, read by the composite
#define BINDING_COUNTERS 13    // ray counters (statistics)
#define BINDING_HISTORY 14     // previous frame's G-buffer and colour (temporal filter)
#define BINDING_SKY 15         // the sky draws' environment cube map, a samplerCube (environment.glsl)

#endif
