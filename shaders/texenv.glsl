// OpenGL's texture environment (OpenGL 1.5 section 3.8.13, tables 3.22 to 3.26; GL 1.3's
// GL_COMBINE with ARB_texture_env_combine, _crossbar and _dot3): what one texture unit makes
// of the colour so far. Shared by the fixed-function fragment shader (ff.frag, once per
// enabled unit) and the path tracer (trace/surface.glsl, once per colour layer of a material),
// so a traced surface combines its textures as the rasterizer does. src/render/texenv/mod.rs
// describes the words; their fields and codes come from generated/texenv_codes.glsl.
//
//   vec4 tex_env(uint unit_word, uint rgb_word, uint alpha_word, vec4 cc, vec4 cf, vec4 ct,
//                vec4 texel[MAX_UNITS], vec4 primary)
//     unit_word: the unit's FORMAT and ENV fields; rgb_word, alpha_word: its combiner words
//     (read for ENV_COMBINE); cc: its GL_TEXTURE_ENV_COLOR; cf: the colour so far (the
//     previous unit's result, the primary colour at the first unit); ct: the unit's texel;
//     texel: every unit's texel (the crossbar's sources; white for a unit without texture);
//     primary: the primary colour. Returns the unit's result, clamped to [0, 1].

#ifndef TEXENV_GLSL
#define TEXENV_GLSL

#include "generated/texenv_codes.glsl"
#include "bit_field.glsl"

// Argument `i` of a combiner word (table 3.24).
vec4 combine_source(uint word, uint i, vec4 ct, vec4 texel[MAX_UNITS], vec4 cc, vec4 primary, vec4 previous) {
    uint source = field(word, SOURCE_SHIFT + SOURCE_BITS * i, SOURCE_BITS);
    switch (source) {
    case SOURCE_TEXTURE: return ct;
    case SOURCE_TEXTURE0: return texel[0];
    case SOURCE_TEXTURE0 + 1u: return texel[1];
    case SOURCE_TEXTURE0 + 2u: return texel[2];
    case SOURCE_TEXTURE0 + 3u: return texel[3];
    case SOURCE_CONSTANT: return cc;
    case SOURCE_PRIMARY_COLOR: return primary;
    default: return previous;
    }
}

// The RGB combiner's argument i after its operand (table 3.25).
vec3 rgb_arg(uint word, uint i, vec4 ct, vec4 texel[MAX_UNITS], vec4 cc, vec4 primary, vec4 previous) {
    vec4 v = combine_source(word, i, ct, texel, cc, primary, previous);
    uint op = field(word, OPERAND_SHIFT + OPERAND_BITS * i, OPERAND_BITS);
    return op == OPERAND_SRC_COLOR ? v.rgb
        : op == OPERAND_ONE_MINUS_SRC_COLOR ? 1.0 - v.rgb
        : op == OPERAND_SRC_ALPHA ? vec3(v.a)
        : vec3(1.0 - v.a);
}

// The alpha combiner's argument i after its operand (table 3.26: SRC_ALPHA or
// ONE_MINUS_SRC_ALPHA; the colour operands read alpha too).
float alpha_arg(uint word, uint i, vec4 ct, vec4 texel[MAX_UNITS], vec4 cc, vec4 primary, vec4 previous) {
    vec4 v = combine_source(word, i, ct, texel, cc, primary, previous);
    uint op = field(word, OPERAND_SHIFT + OPERAND_BITS * i, OPERAND_BITS);
    return (op & 1u) == 0u ? v.a : 1.0 - v.a;
}

// The combiner functions of table 3.23 (DOT3 only for RGB).
vec3 combine3(uint f, vec3 a0, vec3 a1, vec3 a2) {
    switch (f) {
    case COMBINE_REPLACE: return a0;
    case COMBINE_MODULATE: return a0 * a1;
    case COMBINE_ADD: return a0 + a1;
    case COMBINE_ADD_SIGNED: return a0 + a1 - 0.5;
    case COMBINE_INTERPOLATE: return a0 * a2 + a1 * (1.0 - a2);
    case COMBINE_SUBTRACT: return a0 - a1;
    default: return vec3(4.0 * dot(a0 - 0.5, a1 - 0.5));
    }
}

float combine1(uint f, float a0, float a1, float a2) {
    return combine3(f, vec3(a0), vec3(a1), vec3(a2)).x;
}

// The texture function of one unit (table 3.22 with the base-format rules; GL_COMBINE).
vec4 tex_env(uint unit_word, uint rgb_word, uint alpha_word, vec4 cc, vec4 cf, vec4 ct, vec4 texel[MAX_UNITS], vec4 primary) {
    uint env = field(unit_word, ENV_SHIFT, ENV_BITS);
    uint format = field(unit_word, FORMAT_SHIFT, FORMAT_BITS);
    bool has_color = format != FORMAT_ALPHA;
    bool has_alpha = format == FORMAT_ALPHA || format == FORMAT_LUMINANCE_ALPHA || format == FORMAT_INTENSITY || format == FORMAT_RGBA;
    bool intensity = format == FORMAT_INTENSITY;
    vec3 c = cf.rgb;
    float a = cf.a;
    if (env == ENV_MODULATE) {
        c = has_color ? cf.rgb * ct.rgb : cf.rgb;
        a = has_alpha ? cf.a * ct.a : cf.a;
    } else if (env == ENV_REPLACE) {
        c = has_color ? ct.rgb : cf.rgb;
        a = has_alpha ? ct.a : cf.a;
    } else if (env == ENV_DECAL) {
        c = mix(cf.rgb, ct.rgb, ct.a);
    } else if (env == ENV_BLEND) {
        c = has_color ? mix(cf.rgb, cc.rgb, ct.rgb) : cf.rgb;
        a = intensity ? mix(cf.a, cc.a, ct.a) : has_alpha ? cf.a * ct.a : cf.a;
    } else if (env == ENV_ADD) {
        c = has_color ? cf.rgb + ct.rgb : cf.rgb;
        a = intensity ? cf.a + ct.a : has_alpha ? cf.a * ct.a : cf.a;
    } else {
        uint frgb = field(rgb_word, COMBINE_FN_SHIFT, COMBINE_FN_BITS);
        c = combine3(frgb,
            rgb_arg(rgb_word, 0u, ct, texel, cc, primary, cf),
            rgb_arg(rgb_word, 1u, ct, texel, cc, primary, cf),
            rgb_arg(rgb_word, 2u, ct, texel, cc, primary, cf));
        c *= float(1u << field(rgb_word, SCALE_SHIFT, SCALE_BITS));
        if (frgb == COMBINE_DOT3_RGBA) {
            a = c.r;
        } else {
            a = combine1(field(alpha_word, COMBINE_FN_SHIFT, COMBINE_FN_BITS),
                alpha_arg(alpha_word, 0u, ct, texel, cc, primary, cf),
                alpha_arg(alpha_word, 1u, ct, texel, cc, primary, cf),
                alpha_arg(alpha_word, 2u, ct, texel, cc, primary, cf));
            a *= float(1u << field(alpha_word, SCALE_SHIFT, SCALE_BITS));
        }
    }
    return clamp(vec4(c, a), 0.0, 1.0);
}

#endif
