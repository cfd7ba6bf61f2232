// OpenGL's blending (OpenGL 1.5 section 4.1.8, tables 4.1 and 4.2, with
// EXT_blend_func_separate, EXT_blend_equation_separate, EXT_blend_color and EXT_blend_minmax):
// what a pass of a traced surface makes of the colour below it, as the rasterizer's colour
// buffer does. Colours are display-encoded, as in a fixed-point colour buffer: the source and
// destination in [0, 1], the result clamped to [0, 1].
//
//   vec4 blend_over(uint word, vec4 constant, vec4 src, vec4 dst)
//     word: the pass's BLEND_* fields (generated/trace_constants.glsl, render::trace::material);
//     constant: its glBlendColor; src: the pass's fragment colour; dst: the colour below it.

#ifndef TRACE_BLEND_GLSL
#define TRACE_BLEND_GLSL

#include "generated/trace_constants.glsl"
#include "bit_field.glsl"

// Blend factor `f` (FACTOR_*) for source src and destination dst (table 4.2).
vec4 blend_factor(uint f, vec4 constant, vec4 src, vec4 dst) {
    switch (f) {
    case FACTOR_ZERO: return vec4(0.0);
    case FACTOR_ONE: return vec4(1.0);
    case FACTOR_SRC_COLOR: return src;
    case FACTOR_ONE_MINUS_SRC_COLOR: return 1.0 - src;
    case FACTOR_DST_COLOR: return dst;
    case FACTOR_ONE_MINUS_DST_COLOR: return 1.0 - dst;
    case FACTOR_SRC_ALPHA: return vec4(src.a);
    case FACTOR_ONE_MINUS_SRC_ALPHA: return vec4(1.0 - src.a);
    case FACTOR_DST_ALPHA: return vec4(dst.a);
    case FACTOR_ONE_MINUS_DST_ALPHA: return vec4(1.0 - dst.a);
    case FACTOR_CONSTANT_COLOR: return constant;
    case FACTOR_ONE_MINUS_CONSTANT_COLOR: return 1.0 - constant;
    case FACTOR_CONSTANT_ALPHA: return vec4(constant.a);
    case FACTOR_ONE_MINUS_CONSTANT_ALPHA: return vec4(1.0 - constant.a);
    default: {
        float f = min(src.a, 1.0 - dst.a);
        return vec4(f, f, f, 1.0);
    }
    }
}

// Equation `e` (EQUATION_*) of the weighted source s and destination d, or of the unweighted
// src and dst for MIN and MAX (table 4.1).
vec4 blend_equation(uint e, vec4 s, vec4 d, vec4 src, vec4 dst) {
    switch (e) {
    case EQUATION_SUBTRACT: return s - d;
    case EQUATION_REVERSE_SUBTRACT: return d - s;
    case EQUATION_MIN: return min(src, dst);
    case EQUATION_MAX: return max(src, dst);
    default: return s + d;
    }
}

vec4 blend_over(uint word, vec4 constant, vec4 src, vec4 dst) {
    src = clamp(src, 0.0, 1.0);
    dst = clamp(dst, 0.0, 1.0);
    constant = clamp(constant, 0.0, 1.0);
    vec4 s = blend_factor(field(word, BLEND_SRC_RGB_SHIFT, BLEND_SRC_RGB_BITS), constant, src, dst);
    vec4 d = blend_factor(field(word, BLEND_DST_RGB_SHIFT, BLEND_DST_RGB_BITS), constant, src, dst);
    s.a = blend_factor(field(word, BLEND_SRC_ALPHA_SHIFT, BLEND_SRC_ALPHA_BITS), constant, src, dst).a;
    d.a = blend_factor(field(word, BLEND_DST_ALPHA_SHIFT, BLEND_DST_ALPHA_BITS), constant, src, dst).a;
    vec4 rgb = blend_equation(field(word, BLEND_EQUATION_RGB_SHIFT, BLEND_EQUATION_RGB_BITS), s * src, d * dst, src, dst);
    vec4 alpha = blend_equation(field(word, BLEND_EQUATION_ALPHA_SHIFT, BLEND_EQUATION_ALPHA_BITS), s * src, d * dst, src, dst);
    return clamp(vec4(rgb.rgb, alpha.a), 0.0, 1.0);
}

#endif
