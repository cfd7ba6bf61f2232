// The texel pool: every texture the path tracer samples, as RGBA8 words (red in the low byte)
// in one storage buffer, and a table of GpuTexture records into it. Mirrored by
// src/render/trace/texels.rs (GpuTexture; its TEXEL_* flags are generated from
// src/render/trace/shader_constants.rs) and texels/sample.rs (the same sampling math on the
// CPU, which the tests compare with this file).
//
//   vec4 texel_sample(uint tex, vec2 uv, float lod)
//     tex: table index, or NO_TEXTURE (opaque white);
//     uv: GL texture coordinates (s, t), t = 0 the first row (the bottom row as GL stores it);
//         in texels for rectangle textures;
//     lod: GL's lambda, log2 of base-level texels per footprint (the caller computes it from
//          its ray cone, plus the unit's LOD bias);
//     honours the wrap modes (REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT; CLAMP and CLAMP_TO_BORDER
//     come as CLAMP_TO_EDGE), the magnification and minification filters (nearest or bilinear
//     within a level; nearest level or linear between levels), the LOD range; returns RGBA in
//     [0, 1] (sRGB textures decoded to linear).
//   vec2 texel_size(uint tex)
//     base level width and height in texels ((1, 1) for NO_TEXTURE).

#ifndef TRACE_TEXELS_GLSL
#define TRACE_TEXELS_GLSL

#include "generated/trace_constants.glsl"
#include "trace/bindings.glsl"

// Texel coordinates are clamped to +-2^24 before they become integers.
#define TEXEL_COORD_LIMIT 16777216

struct GpuTexture {
    uint offset;   // word offset of level 0; level l (max(width >> l, 1) x max(height >> l, 1)) follows level l - 1
    uint width;    // base level width
    uint height;   // base level height
    uint levels;   // levels stored; 0: did not fit the pool, sample as `average`
    uint flags;    // TEXEL_* bits
    uint average;  // average colour of the base level, packed like a texel
    float lod_min; // GL_TEXTURE_MIN_LOD
    float lod_max; // GL_TEXTURE_MAX_LOD
};

layout(set = TRACE_SET, binding = BINDING_TEXELS, std430) readonly buffer TraceTexels {
    uint texels[];
};

layout(set = TRACE_SET, binding = BINDING_TEXTURES, std430) readonly buffer TraceTextures {
    GpuTexture texture_table[];
};

// A packed texel as RGBA in [0, 1], sRGB-decoded when `flags` says so.
vec4 texel_decode(uint texel, uint flags) {
    vec4 c = unpackUnorm4x8(texel);
    if ((flags & TEXEL_SRGB) == 0u) {
        return c;
    }
    vec3 lo = c.rgb / 12.92;
    vec3 hi = pow((c.rgb + 0.055) / 1.055, vec3(2.4));
    return vec4(mix(hi, lo, lessThanEqual(c.rgb, vec3(0.04045))), c.a);
}

// Integer texel index i wrapped into [0, n) by `mode` (TEXEL_WRAP_*); |i| <= 2^24 + 1.
int texel_wrap(int i, int n, uint mode) {
    if (mode == TEXEL_WRAP_CLAMP) {
        return clamp(i, 0, n - 1);
    }
    if (mode == TEXEL_WRAP_MIRROR) {
        int m = int(uint(i + 2 * n * (TEXEL_COORD_LIMIT / (2 * n) + 1)) % uint(2 * n));
        return m < n ? m : 2 * n - 1 - m;
    }
    return int(uint(i + n * (TEXEL_COORD_LIMIT / n + 1)) % uint(n));
}

// Texel (i, j), wrapped, of a w x h level starting at word `offset`.
vec4 texel_fetch(GpuTexture t, uint offset, int w, int h, int i, int j) {
    i = texel_wrap(i, w, t.flags & 3u);
    j = texel_wrap(j, h, (t.flags >> TEXEL_WRAP_T_SHIFT) & 3u);
    return texel_decode(texels[offset + uint(j * w + i)], t.flags);
}

// Level `level` of `t` at `uv`, nearest or bilinear.
vec4 texel_level(GpuTexture t, uint level, vec2 uv, bool linear) {
    uint offset = t.offset;
    int w = int(t.width);
    int h = int(t.height);
    for (uint l = 0u; l < level; l++) {
        offset += uint(w * h);
        w = max(w >> 1, 1);
        h = max(h >> 1, 1);
    }
    float limit = float(TEXEL_COORD_LIMIT);
    float x = clamp(uv.x * float(w), -limit, limit);
    float y = clamp(uv.y * float(h), -limit, limit);
    if (!linear) {
        return texel_fetch(t, offset, w, h, int(floor(x)), int(floor(y)));
    }
    x -= 0.5;
    y -= 0.5;
    float fi = floor(x);
    float fj = floor(y);
    float a = x - fi;
    float b = y - fj;
    int i = int(fi);
    int j = int(fj);
    vec4 t00 = texel_fetch(t, offset, w, h, i, j);
    vec4 t10 = texel_fetch(t, offset, w, h, i + 1, j);
    vec4 t01 = texel_fetch(t, offset, w, h, i, j + 1);
    vec4 t11 = texel_fetch(t, offset, w, h, i + 1, j + 1);
    return mix(mix(t00, t10, a), mix(t01, t11, a), b);
}

vec4 texel_sample(uint tex, vec2 uv, float lod) {
    if (tex == NO_TEXTURE) {
        return vec4(1.0);
    }
    GpuTexture t = texture_table[tex];
    if (t.levels == 0u) {
        return texel_decode(t.average, t.flags);
    }
    if ((t.flags & TEXEL_RECT) != 0u) {
        uv /= vec2(float(t.width), float(t.height));
    }
    lod = isnan(lod) ? 0.0 : min(max(lod, t.lod_min), t.lod_max);
    float switch_lod = (t.flags & TEXEL_MAG_TO_HALF) != 0u ? 0.5 : 0.0;
    if (lod <= switch_lod) {
        return texel_level(t, 0u, uv, (t.flags & TEXEL_MAG_LINEAR) != 0u);
    }
    bool linear = (t.flags & TEXEL_MIN_LINEAR) != 0u;
    if ((t.flags & TEXEL_MIPMAP) == 0u) {
        return texel_level(t, 0u, uv, linear);
    }
    float last = float(t.levels - 1u);
    if ((t.flags & TEXEL_MIP_LINEAR) == 0u) {
        float d = lod <= 0.5 ? 0.0 : min(ceil(lod + 0.5) - 1.0, last);
        return texel_level(t, uint(d), uv, linear);
    }
    float d1 = min(floor(lod), last);
    float d2 = min(d1 + 1.0, last);
    float f = d1 >= last ? 0.0 : lod - floor(lod);
    return mix(texel_level(t, uint(d1), uv, linear), texel_level(t, uint(d2), uv, linear), f);
}

vec2 texel_size(uint tex) {
    if (tex == NO_TEXTURE) {
        return vec2(1.0);
    }
    return vec2(float(texture_table[tex].width), float(texture_table[tex].height));
}

#endif
