#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// The compute path tracer's tracing pass: trace/path.glsl's integrator over
// trace/bvh_wide.glsl's traversal (pathtrace_binary.comp: bvh.glsl's), one invocation per
// traced pixel (one per gradient stratum in the gradient pass, trace_invocation).

#include "trace/path.glsl"

layout(local_size_x = TRACE_GROUP, local_size_y = TRACE_GROUP) in;

void main() {
    trace_invocation(gl_GlobalInvocationID.xy);
}
