#version 450
#extension GL_GOOGLE_include_directive : require
// Form factors on the GPU (render::radiosity::gpu::form_factors): one invocation per entry
// F_ij of the rows a dispatch computes, the same point-to-patch method as the CPU reference
// (render::radiosity::form_factors, whose doc explains it), operation for operation:
// receiver points are the centroids of the receiver's first RADIOSITY_RECEIVER_POINTS
// triangles, lifted off the surface; the unoccluded part is Lambert's contour integral over
// each source triangle clipped to the receiver's hemisphere (in f32 here, f64 on the CPU); the
// visibility is the share of RADIOSITY_VISIBILITY_SAMPLES shadow rays through the tracer's
// BVH (trace/bvh.glsl) that reach the source's sample points, chosen as the CPU chooses them.

// No alpha-tested geometry in the patches' BVH: every hit counts (bvh.glsl needs this first).
bool trace_alpha_accept(uint instance, uint triangle, vec2 bary) {
    return true;
}

#include "trace/bvh.glsl"
#include "radiosity/patch.glsl"

layout(local_size_x = RADIOSITY_GROUP) in;

#define PI 3.14159265358979

layout(set = TRACE_SET, binding = RADIOSITY_BINDING_ROWS, std430) writeonly buffer Rows {
    float rows[];
};

layout(push_constant) uniform FormFactorPass {
    uint patch_count;  // n: columns of a row
    uint first_row;    // the receiver of the dispatch's first row
    uint row_count;    // rows of this dispatch
    uint pad;
} pass;

vec3 face_normal(uint t) {
    vec3 c = cross(corner(t, 1u) - corner(t, 0u), corner(t, 2u) - corner(t, 0u));
    float len = length(c);
    return len > 0.0 ? c / len : vec3(0.0);
}

// Triangle t clipped to the half-space in front of the plane through p with normal n
// (Sutherland-Hodgman against one plane): up to 4 corners.
uint clip(uint t, vec3 p, vec3 n, out vec3 poly[4]) {
    uint len = 0u;
    for (uint k = 0u; k < 3u; k++) {
        vec3 a = corner(t, k);
        vec3 b = corner(t, (k + 1u) % 3u);
        float da = dot(n, a - p);
        float db = dot(n, b - p);
        if (da >= 0.0) {
            poly[len] = a;
            len++;
        }
        if ((da >= 0.0) != (db >= 0.0)) {
            poly[len] = a + (b - a) * (da / (da - db));
            len++;
        }
    }
    return len;
}

// Lambert's contour integral: the form factor from a differential area at p with normal n
// to the polygon.
float point_to_polygon(vec3 p, vec3 n, vec3 poly[4], uint len) {
    if (len < 3u) {
        return 0.0;
    }
    float sum = 0.0;
    for (uint k = 0u; k < len; k++) {
        vec3 a = poly[k] - p;
        vec3 b = poly[(k + 1u) % len] - p;
        vec3 c = cross(a, b);
        float l = length(c);
        if (l > 0.0) {
            sum += atan(l, dot(a, b)) * dot(n, c) / l;
        }
    }
    return abs(sum) / (2.0 * PI);
}

// The part of source triangle t that receiver point p (normal n) sees unoccluded: its
// form factor (0 when t faces away or lies behind p's plane) and the clipped polygon.
float part(uint t, vec3 p, vec3 n, out vec3 poly[4], out uint len) {
    len = 0u;
    if (dot(face_normal(t), p - corner(t, 0u)) <= 0.0) {
        return 0.0;
    }
    len = clip(t, p, n, poly);
    return point_to_polygon(p, n, poly, len);
}

vec3 polygon_centroid(vec3 poly[4], uint len) {
    vec3 s = vec3(0.0);
    for (uint k = 0u; k < len; k++) {
        s += poly[k];
    }
    return s / float(len);
}

// The m-th of the source's polygons that p sees (part() > 0), clipped.
uint visible_polygon(Patch source, vec3 p, vec3 n, uint m, out vec3 poly[4]) {
    uint seen = 0u;
    for (uint t = source.first; t < source.first + source.count; t++) {
        uint len;
        if (part(t, p, n, poly, len) > 0.0) {
            if (seen == m) {
                return len;
            }
            seen++;
        }
    }
    return 0u;
}

// The share of the sample points of the source's `visible` polygons that a ray from p
// reaches, stopping `margin` short: the centroids of up to RADIOSITY_VISIBILITY_SAMPLES
// polygons evenly spaced among them, then points halfway from the first one's centroid to
// its corners.
float visible_fraction(Patch source, vec3 p, vec3 n, uint visible, float margin) {
    uint count = min(visible, RADIOSITY_VISIBILITY_SAMPLES);
    vec3 first_poly[4];
    uint first_len = visible_polygon(source, p, n, 0u, first_poly);
    vec3 first = polygon_centroid(first_poly, first_len);
    uint seen = 0u;
    uint total = 0u;
    for (uint k = 0u; k < RADIOSITY_VISIBILITY_SAMPLES; k++) {
        vec3 q;
        if (k < count) {
            vec3 poly[4];
            uint len = visible_polygon(source, p, n, k * visible / count, poly);
            q = polygon_centroid(poly, len);
        } else if (k - count < first_len) {
            q = (first_poly[k - count] + first) * 0.5;
        } else {
            break;
        }
        vec3 d = q - p;
        float tmax = 1.0 - margin / max(length(d), margin * 2.0);
        total++;
        if (!trace_any(p, d, 0.0, tmax)) {
            seen++;
        }
    }
    return float(seen) / float(total);
}

// F_ij: the form factor from receiver i to source j, averaged over i's points.
float form_factor(Patch receiver, Patch source) {
    float margin = lift_of(source.position, source.area);
    uint points = receiver_points(receiver);
    float sum = 0.0;
    float total = 0.0;
    for (uint k = 0u; k < points; k++) {
        vec3 p = receiver_point(receiver, k);
        float weight = triangle_area(receiver.first + k);
        total += weight;
        float unoccluded = 0.0;
        uint visible = 0u;
        for (uint t = source.first; t < source.first + source.count; t++) {
            vec3 poly[4];
            uint len;
            float f = part(t, p, receiver.normal, poly, len);
            if (f > 0.0) {
                unoccluded += f;
                visible++;
            }
        }
        if (unoccluded > 0.0) {
            sum += weight * unoccluded * visible_fraction(source, p, receiver.normal, visible, margin);
        }
    }
    return total > 0.0 ? sum / total : 0.0;
}

void main() {
    uint j = gl_GlobalInvocationID.x;
    uint row = gl_GlobalInvocationID.y;
    if (j >= pass.patch_count || row >= pass.row_count) {
        return;
    }
    uint i = pass.first_row + row;
    Patch receiver = patches[i];
    float value = 0.0;
    if (i != j && receiver.normal != vec3(0.0)) {
        value = form_factor(receiver, patches[j]);
    }
    rows[row * pass.patch_count + j] = value;
}
