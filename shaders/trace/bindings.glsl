// Descriptor bindings of the compute path tracer (set 0 of every tracing pipeline):
// BINDING_<NAME>, generated from src/render/trace/bindings.rs. Every buffer is a std430
// storage buffer: lavapipe inlines uniform-buffer values and recompiles per value (see
// ff_uniforms.glsl), and has no descriptor indexing, so scene data lives in a fixed set of
// large buffers. The one image is the sky's cube map, after the buffers.

#ifndef TRACE_BINDINGS_GLSL
#define TRACE_BINDINGS_GLSL

#include "generated/trace_bindings.glsl"

// The tracer's only descriptor set.
#define TRACE_SET 0

#endif
