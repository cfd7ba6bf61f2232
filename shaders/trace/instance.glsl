// One traced instance: a geometry (bottom-level BVH) placed in eye space. Mirrored by
// `render::trace::gpu_types::GpuInstance`. Traversal (bvh.glsl) reads the transform, the BLAS root
// and the first triangle; shading reads the rest. An instance with INSTANCE_MERGED is the
// merged BVH of a region's chunks (render::trace::regions): the traversal enters it, and a hit
// on it names the chunk's own record (first_member + the triangle's member), which shading
// reads; its own material is never read.

#ifndef TRACE_INSTANCE_GLSL
#define TRACE_INSTANCE_GLSL

#include "generated/trace_constants.glsl"
#include "trace/bindings.glsl"

struct Instance {
    vec4 object_to_eye[3];   // rows of the affine object-to-eye matrix
    vec4 eye_to_object[3];   // rows of its inverse
    vec4 previous_object_to_eye[3]; // last frame's object_to_eye (motion vectors); the same when unknown
    uint blas_root;          // index of the geometry's root in the BLAS node buffer
    uint first_triangle;     // index of the geometry's first triangle in the triangle buffers
    uint flags;              // INSTANCE_* bits
    uint material;           // index into the material buffer
    uint previous_triangles; // first of a deforming mesh's last-frame triangles (scene.glsl
                             // previous_triangles), or NO_PREVIOUS_TRIANGLES
    uint first_member;       // INSTANCE_MERGED: the record of its first chunk (trace/triangles.glsl)
    uint pad1, pad2;
};

layout(set = TRACE_SET, binding = BINDING_INSTANCES, std430) readonly buffer Instances {
    Instance instances[];
};

#endif
