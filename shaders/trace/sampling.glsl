// Direction sampling of the path tracer: orthonormal bases, cosine-weighted hemispheres,
// cones, and GGX visible normals.

#ifndef TRACE_SAMPLING_GLSL
#define TRACE_SAMPLING_GLSL

const float PI = 3.14159265358979;

// The rotation from last frame's eye space to this frame's while a gradient sample replays a
// sample of last frame on a surface that moved in eye space (trace/forward_projection.glsl
// sets it; the identity otherwise): bases are then built around directions turned back into
// last frame's eye space and turned forward again, so that the same random numbers give the
// directions last frame's sample drew, carried along with the surface.
mat3 replay_rotation = mat3(1.0);

// An orthonormal basis around unit n (Duff et al. 2017, in the eye space of replay_rotation):
// columns t, b, n.
mat3 basis(vec3 n) {
    vec3 m = transpose(replay_rotation) * n;
    float s = m.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + m.z);
    float b = m.x * m.y * a;
    return replay_rotation * mat3(vec3(1.0 + s * m.x * m.x * a, s * b, -s * m.x), vec3(b, s + m.y * m.y * a, -m.y), m);
}

// Cosine-weighted direction around unit n; pdf = cos / pi.
vec3 sample_cosine(vec3 n, vec2 u) {
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    vec3 local = vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
    return basis(n) * local;
}

// Uniform direction in the cone of half-angle acos(cos_max) around unit axis.
vec3 sample_cone(vec3 axis, float cos_max, vec2 u) {
    float c = mix(1.0, cos_max, u.x);
    float s = sqrt(max(0.0, 1.0 - c * c));
    float phi = 2.0 * PI * u.y;
    return basis(axis) * vec3(s * cos(phi), s * sin(phi), c);
}

// GGX normal distribution for alpha = roughness^2, m·n = cos_h.
float ggx_d(float cos_h, float alpha) {
    float a2 = alpha * alpha;
    float d = cos_h * cos_h * (a2 - 1.0) + 1.0;
    return a2 / max(PI * d * d, 1e-12);
}

// Smith masking G1 of GGX for a direction at cosine c to the normal.
float ggx_g1(float c, float alpha) {
    float a2 = alpha * alpha;
    return 2.0 * c / max(c + sqrt(a2 + (1.0 - a2) * c * c), 1e-12);
}

// A GGX visible normal for view direction v in the local frame (z = normal) (Heitz 2018,
// "Sampling the GGX Distribution of Visible Normals").
vec3 sample_ggx_vndf(vec3 v, float alpha, vec2 u) {
    vec3 vh = normalize(vec3(alpha * v.x, alpha * v.y, v.z));
    float len2 = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = len2 > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(len2) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    float p1 = r * cos(phi);
    float p2 = r * sin(phi);
    float s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0, nh.z)));
}

#endif
