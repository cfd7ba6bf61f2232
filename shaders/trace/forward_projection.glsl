// Forward projection of a temporal gradient sample whose surface moved (A-SVGF, Schied et al.
// 2018, section 4.1; Quake II RTX's asvgf_fwd_project): the gradient pixel's primary hit is
// followed back to the pixel that saw its surface last frame (the source), and the source's
// own primary ray of last frame (through its centre, or its jitter of that sample) is carried
// onto the hit triangle and forward to this frame with its instance's transforms. The gradient
// sample is then traced from this frame's camera through that surface point with the
// source's random numbers of last frame (the caller seeds them), so that its difference with
// the source's sample of last frame is the change of the lighting alone; its directions are
// drawn in last frame's eye space (replay_rotation, trace/sampling.glsl), where the source
// drew them. A deforming mesh's point is followed through its triangle's last shape
// (Instance.previous_triangles: the same barycentric point), as its motion vector is.
// Included by trace/path.glsl, which defines camera_ray and window_xy.

#ifndef TRACE_FORWARD_PROJECTION_GLSL
#define TRACE_FORWARD_PROJECTION_GLSL

#include "trace/gradient.glsl"
#include "trace/instance.glsl"
#include "trace/surface.glsl"

// The affine matrix of an instance's rows (instance_transform as a mat4).
mat4 instance_matrix(vec4 rows[3]) {
    return transpose(mat4(rows[0], rows[1], rows[2], vec4(0.0, 0.0, 0.0, 1.0)));
}

// Where the point of `hit` at eye-space `position` was last frame, in last frame's eye space:
// the same object-space point through last frame's transform, or on a deforming mesh the same
// barycentric point of its triangle's last shape.
vec3 previous_position(TraceHit hit, vec3 position) {
    Instance inst = instances[hit.instance];
    vec3 object = instance_transform(inst.eye_to_object, vec4(position, 1.0));
    if (inst.previous_triangles != NO_PREVIOUS_TRIANGLES) {
        BvhTriangle was = previous_triangles[inst.previous_triangles + hit.triangle - inst.first_triangle];
        object = was.v0 + hit.bary.x * was.e1 + hit.bary.y * was.e2;
    }
    return instance_transform(inst.previous_object_to_eye, vec4(object, 1.0));
}

// The traced pixel that saw the point of `hit` at eye-space `position` last frame, or false
// when it lies outside the traced image.
bool gradient_source(vec3 position, TraceHit hit, vec2 scale, out uvec2 source) {
    vec3 previous = previous_position(hit, position);
    vec4 clip = frame.previous_projection * vec4(previous, 1.0);
    if (clip.w <= 0.0 && (frame.flags.x & FRAME_PERSPECTIVE) != 0u) {
        return false;
    }
    ivec2 at = ivec2(floor(window_xy(frame.previous_projection, previous) / scale));
    source = uvec2(at);
    return all(greaterThanEqual(at, ivec2(0))) && all(lessThan(at, ivec2(frame.size.xy)));
}

// The rotation of instance `inst`'s transform to eye space since last frame (the camera's
// turn for the static world), made orthonormal.
mat3 eye_rotation_since_last_frame(Instance inst) {
    mat3 m = mat3(instance_matrix(inst.object_to_eye)) * inverse(mat3(instance_matrix(inst.previous_object_to_eye)));
    vec3 x = normalize(m[0]);
    vec3 y = normalize(m[1] - dot(m[1], x) * x);
    return mat3(x, y, cross(x, y));
}

// Where last frame's primary ray of traced pixel `source` (through window position
// `previous_window`) met the plane of triangle `hit.triangle` of instance `hit.instance`, in
// this frame's eye space: false when the ray runs along the plane or meets it behind the camera.
// On a deforming mesh the plane is the triangle's last shape's, and the point found there is
// carried to the same barycentric point of its shape now.
bool forward_project(TraceHit hit, vec2 previous_window, out vec3 target) {
    Instance inst = instances[hit.instance];
    vec3 v0, e1, e2;
    bool deforming = inst.previous_triangles != NO_PREVIOUS_TRIANGLES;
    if (deforming) {
        BvhTriangle was = previous_triangles[inst.previous_triangles + hit.triangle - inst.first_triangle];
        v0 = was.v0;
        e1 = was.e1;
        e2 = was.e2;
    } else {
        vec3 v1, v2;
        trace_triangle_vertices(hit.triangle, v0, v1, v2);
        e1 = v1 - v0;
        e2 = v2 - v0;
    }
    vec3 n = cross(e1, e2);
    // Last frame's ray in last frame's eye space (camera_ray with last frame's projection).
    vec2 ndc = 2.0 * (previous_window - frame.viewport.xy) / frame.viewport.zw - 1.0;
    mat4 unproject = inverse(frame.previous_projection);
    vec4 near = unproject * vec4(ndc, -1.0, 1.0);
    vec4 far = unproject * vec4(ndc, 1.0, 1.0);
    // ... and in object space, through the inverse of last frame's object-to-eye transform.
    mat4 previous_eye_to_object = inverse(instance_matrix(inst.previous_object_to_eye));
    vec3 origin = (previous_eye_to_object * vec4(near.xyz / near.w, 1.0)).xyz;
    vec3 dir = (previous_eye_to_object * vec4(far.xyz / far.w, 1.0)).xyz - origin;
    float facing = dot(dir, n);
    if (abs(facing) <= 1e-6 * length(dir) * length(n)) {
        return false;
    }
    float t = dot(v0 - origin, n) / facing;
    vec3 point = origin + t * dir;
    if (deforming) {
        // Its barycentrics in the last shape (n is not 0: the ray met the plane), then the
        // same point of the triangle now.
        vec3 p = point - v0;
        float d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2), d20 = dot(p, e1), d21 = dot(p, e2);
        vec2 bary = vec2(d11 * d20 - d01 * d21, d00 * d21 - d01 * d20) / dot(n, n);
        vec3 c0, c1, c2;
        trace_triangle_vertices(hit.triangle, c0, c1, c2);
        point = c0 + bary.x * (c1 - c0) + bary.y * (c2 - c0);
    }
    target = instance_transform(inst.object_to_eye, vec4(point, 1.0));
    return t > 0.0;
}

// Gradient pixel `pixel` (its primary ray origin, dir hit `hit`) repeats the sample its source
// (written to `source`) traced last frame: where the surface stayed in place the source is
// the pixel itself, whose random numbers the caller drew (rng); where it moved, the primary
// ray is traced again through the forward-projected point (`rays` counts it), rng re-seeded
// with the source's numbers of last frame and replay_rotation set to the surface's turn.
// False where no sample can be repeated (the source outside the image; the projected point
// off the pixel or hidden): there is no gradient sample then. Every pixel's sample of last
// frame was drawn with that frame's numbers (the main pass traces them all; gradient samples
// have their own records), so every source can be repeated.
bool repeat_source(uvec2 pixel, vec2 scale, uint sample_index, inout vec3 origin, inout vec3 dir, inout TraceHit hit, inout Rng rng,
                   inout uint rays, out uvec2 source) {
    vec3 position = origin + hit.t * dir;
    if (!gradient_source(position, hit, scale, source)) {
        return false;
    }
    Instance inst = instances[hit.instance];
    vec3 previous = previous_position(hit, position);
    vec2 motion = window_xy(frame.projection, position) - window_xy(frame.previous_projection, previous);
    if (all(lessThan(abs(motion), vec2(1e-4 * max(scale.x, scale.y))))) {
        return true;
    }
    Rng source_rng = rng_seed(source, frame.counts.x - 1u, sample_index);
    vec2 jitter = sample_index == 0u ? vec2(0.5) : rng_next2(source_rng);
    vec3 target;
    if (!forward_project(hit, (vec2(source) + jitter) * scale, target)) {
        return false;
    }
    vec2 window = window_xy(frame.projection, target);
    if (any(greaterThan(abs(window / scale - (vec2(pixel) + 0.5)), vec2(1.5)))) {
        return false;
    }
    vec3 o, d;
    camera_ray(window, o, d);
    rays += 1u;
    TraceHit h;
    if (!trace_closest(o, d, 0.0, 1e30, h) || h.instance != hit.instance || distance(o + h.t * d, target) > 1e-3 * length(target)) {
        return false;
    }
    origin = o;
    dir = d;
    hit = h;
    rng = source_rng;
    replay_rotation = eye_rotation_since_last_frame(inst);
    return true;
}

#endif
