#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// The compute path tracer's tracing pass over binary BVHs (`[pathtrace] bvh = "binary"`):
// pathtrace.comp with trace/bvh.glsl's traversal instead of trace/bvh_wide.glsl's.

#define TRACE_BVH_BINARY
#include "trace/path.glsl"

layout(local_size_x = TRACE_GROUP, local_size_y = TRACE_GROUP) in;

void main() {
    trace_invocation(gl_GlobalInvocationID.xy);
}
