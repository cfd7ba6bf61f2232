#version 450
#extension GL_GOOGLE_include_directive : require
// Screen-space ambient occlusion (seed 000): per framebuffer pixel, the eye-space position from
// the depth buffer and the normal from its neighbours, a hemisphere kernel of m samples of
// radius R around the normal, rotated per pixel by the 4 x 4 noise tile (Gram-Schmidt), each
// sample occluded where the depth buffer's surface lies in front of it by more than the bias
// delta (weighted by a range check that ignores surfaces far outside R). Writes the
// unoccluded fraction 1 - occlusion / m; 1 where nothing was drawn.
//
// The depth a sample is compared with is the sampled pixel's, carried from that pixel's centre
// to the sample's own window point along the centre pixel's depth gradient (window depth is
// affine across the window on a plane). Read at the pixel centre alone, a surface seen at a
// grazing angle far away spans more depth within one pixel than the bias, and samples just
// above it met a nearer depth: an open plane darkened by up to 0.18 near the horizon.

#include "ao/params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) readonly buffer Params { AoParams p; };
layout(std430, set = 0, binding = 1) readonly buffer Depth { uint depth_bits[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Occlusion { float ao[]; };

// Window depth of the pixel at image column x, row r (top first).
float window_depth(ivec2 px) {
    uint bits = depth_bits[uint(px.y) * p.sizes.x + uint(px.x)];
    return p.sizes.w == 1u ? float(bits & 0xffffffu) / 16777215.0 : uintBitsToFloat(bits);
}

// Eye-space position of window point (x, y GL with y up, depth d).
vec3 eye_position(vec2 window, float d) {
    vec2 ndc_xy = (window - p.viewport.xy) / p.viewport.zw * 2.0 - 1.0;
    float range = p.shape.y - p.shape.x;
    float ndc_z = (d - p.shape.x) / (range != 0.0 ? range : 1.0) * 2.0 - 1.0;
    vec4 e = p.inverse_projection * vec4(ndc_xy, ndc_z, 1.0);
    return e.xyz / e.w;
}

// Eye-space position seen through the centre of image pixel px.
vec3 position_at(ivec2 px) {
    vec2 window = vec2(float(px.x) + 0.5, float(p.sizes.y) - float(px.y) - 0.5);
    return eye_position(window, window_depth(px));
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(p.sizes.xy);
    if (px.x >= size.x || px.y >= size.y) {
        return;
    }
    uint index = uint(px.y) * p.sizes.x + uint(px.x);
    if (window_depth(px) >= 1.0) {
        ao[index] = 1.0;
        return;
    }
    vec3 pos = position_at(px);
    // The normal and the window depth gradient from the nearer neighbour on each axis (the
    // other may lie across an edge), the one inside the image at its border.
    float depth = window_depth(px);
    ivec2 l = max(px - ivec2(1, 0), ivec2(0)), r = min(px + ivec2(1, 0), size - 1);
    ivec2 u = max(px - ivec2(0, 1), ivec2(0)), d = min(px + ivec2(0, 1), size - 1);
    float dl = window_depth(l) - depth, dr = window_depth(r) - depth;
    float du = window_depth(u) - depth, dd = window_depth(d) - depth;
    bool left = px.x == size.x - 1 || (px.x > 0 && abs(dl) < abs(dr));
    bool up = px.y == size.y - 1 || (px.y > 0 && abs(du) < abs(dd));
    vec3 dx = left ? pos - position_at(l) : position_at(r) - pos;
    vec3 dy = up ? position_at(u) - pos : pos - position_at(d);
    // Per window pixel, x right and y up (image rows run down).
    vec2 gradient = vec2(left ? -dl : dr, up ? du : -dd);
    vec3 n = normalize(cross(dx, dy));
    if (dot(n, -pos) < 0.0) {
        n = -n;
    }
    // Tangent frame: the pixel's noise vector made orthogonal to the normal (Gram-Schmidt).
    vec3 noise = p.noise[(px.x & 3) + 4 * (px.y & 3)].xyz;
    vec3 t = noise - n * dot(noise, n);
    t = dot(t, t) > 1e-8 ? normalize(t) : normalize(abs(n.x) < 0.9 ? cross(n, vec3(1.0, 0.0, 0.0)) : cross(n, vec3(0.0, 1.0, 0.0)));
    mat3 tbn = mat3(t, cross(n, t), n);

    float radius = p.shape.z, bias = p.shape.w;
    float occlusion = 0.0;
    uint m = min(p.sizes.z, uint(AO_MAX_SAMPLES));
    for (uint i = 0u; i < m; i++) {
        vec3 s = pos + tbn * p.kernel[i].xyz * radius;
        vec4 clip = p.projection * vec4(s, 1.0);
        if (clip.w <= 0.0) {
            continue;
        }
        vec2 window = p.viewport.xy + (clip.xy / clip.w * 0.5 + 0.5) * p.viewport.zw;
        // Samples beyond the image read its edge, as a texture clamped to its edge would.
        ivec2 at = clamp(ivec2(int(floor(window.x)), size.y - 1 - int(floor(window.y))), ivec2(0), size - 1);
        float scene_depth = window_depth(at);
        if (scene_depth >= 1.0) {
            continue;
        }
        // From the pixel's centre to the sample's point within it (the edge pixel's own
        // depth beyond the image).
        vec2 centre = vec2(float(at.x) + 0.5, float(size.y - at.y) - 0.5);
        vec2 offset = clamp(window - centre, vec2(-0.5), vec2(0.5));
        float scene_z = eye_position(centre + offset, scene_depth + dot(gradient, offset)).z;
        float range = smoothstep(0.0, 1.0, radius / max(abs(pos.z - scene_z), 1e-6));
        occlusion += (scene_z >= s.z + bias ? 1.0 : 0.0) * range;
    }
    ao[index] = 1.0 - occlusion / float(max(m, 1u));
}
