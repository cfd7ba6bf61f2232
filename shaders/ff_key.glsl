// The shader key of the fixed-function shaders: specialisation constants and their bit
// fields. Mirrors src/render/raster/ff/key.rs (a test there reads this file back).

const uint KEY_WORDS = 14u;

layout(constant_id = 0) const uint KEY_GENERAL = 0u;
layout(constant_id = 1) const uint KEY_CLIP = 0u;
layout(constant_id = 2) const uint KEY_UNIT0 = 0u;
layout(constant_id = 3) const uint KEY_UNIT1 = 0u;
layout(constant_id = 4) const uint KEY_UNIT2 = 0u;
layout(constant_id = 5) const uint KEY_UNIT3 = 0u;
layout(constant_id = 6) const uint KEY_COMBINE_RGB0 = 0u;
layout(constant_id = 7) const uint KEY_COMBINE_RGB1 = 0u;
layout(constant_id = 8) const uint KEY_COMBINE_RGB2 = 0u;
layout(constant_id = 9) const uint KEY_COMBINE_RGB3 = 0u;
layout(constant_id = 10) const uint KEY_COMBINE_ALPHA0 = 0u;
layout(constant_id = 11) const uint KEY_COMBINE_ALPHA1 = 0u;
layout(constant_id = 12) const uint KEY_COMBINE_ALPHA2 = 0u;
layout(constant_id = 13) const uint KEY_COMBINE_ALPHA3 = 0u;

// Word KEY_GENERAL.
const uint PRIMITIVE_SHIFT = 0u;
const uint PRIMITIVE_BITS = 2u;
const uint FLAT_SHIFT = 2u;
const uint FLAT_BITS = 1u;
const uint FACING_SHIFT = 3u;
const uint FACING_BITS = 2u;
const uint LIGHTING_SHIFT = 5u;
const uint LIGHTING_BITS = 1u;
const uint TWO_SIDE_SHIFT = 6u;
const uint TWO_SIDE_BITS = 1u;
const uint LOCAL_VIEWER_SHIFT = 7u;
const uint LOCAL_VIEWER_BITS = 1u;
const uint SEPARATE_SPECULAR_SHIFT = 8u;
const uint SEPARATE_SPECULAR_BITS = 1u;
const uint COLOR_MATERIAL_SHIFT = 9u;
const uint COLOR_MATERIAL_BITS = 3u;
const uint COLOR_MATERIAL_FACES_SHIFT = 12u;
const uint COLOR_MATERIAL_FACES_BITS = 2u;
const uint NORMAL_SCALING_SHIFT = 14u;
const uint NORMAL_SCALING_BITS = 2u;
const uint LIGHT_COUNT_SHIFT = 16u;
const uint LIGHT_COUNT_BITS = 4u;
const uint COLOR_SUM_SHIFT = 20u;
const uint COLOR_SUM_BITS = 1u;
const uint FOG_SHIFT = 21u;
const uint FOG_BITS = 2u;
const uint FOG_COORD_SHIFT = 23u;
const uint FOG_COORD_BITS = 1u;
const uint ALPHA_TEST_SHIFT = 24u;
const uint ALPHA_TEST_BITS = 4u;
const uint POLYGON_STIPPLE_SHIFT = 28u;
const uint POLYGON_STIPPLE_BITS = 1u;
const uint LINE_STIPPLE_SHIFT = 29u;
const uint LINE_STIPPLE_BITS = 1u;
const uint SMOOTH_SHIFT = 30u;
const uint SMOOTH_BITS = 1u;
const uint SPRITE_SHIFT = 31u;
const uint SPRITE_BITS = 1u;

// Word KEY_CLIP.
const uint CLIP_MASK_SHIFT = 0u;
const uint CLIP_MASK_BITS = 6u;

// Words KEY_UNITn.
const uint TARGET_SHIFT = 0u;
const uint TARGET_BITS = 3u;
const uint FORMAT_SHIFT = 3u;
const uint FORMAT_BITS = 3u;
const uint ENV_SHIFT = 6u;
const uint ENV_BITS = 3u;
const uint TEXGEN_SHIFT = 9u;   // coordinate c at TEXGEN_SHIFT + 3c
const uint TEXGEN_BITS = 3u;
const uint DEPTH_SHIFT = 21u;     // 0 colour, 1 depth, 2 + func depth compared
const uint DEPTH_BITS = 4u;
const uint CLAMP_SHIFT = 25u;     // bit c: coordinate c clamped to [0, 1] (GL_CLAMP, linear)
const uint CLAMP_BITS = 3u;
const uint COORD_REPLACE_SHIFT = 28u; // point sprites: 0 off, 1 t downwards, 2 t upwards
const uint COORD_REPLACE_BITS = 2u;
const uint SPRITE_R_SHIFT = 30u;      // replaced r: 0 zero, 1 s / q, 2 r / q
const uint SPRITE_R_BITS = 2u;

// Words KEY_COMBINE_RGBn and KEY_COMBINE_ALPHAn.
const uint COMBINE_FN_SHIFT = 0u;
const uint COMBINE_FN_BITS = 3u;
const uint SOURCE_SHIFT = 3u;   // argument i at SOURCE_SHIFT + 3i
const uint SOURCE_BITS = 3u;
const uint OPERAND_SHIFT = 12u; // argument i at OPERAND_SHIFT + 2i
const uint OPERAND_BITS = 2u;
const uint SCALE_SHIFT = 18u;
const uint SCALE_BITS = 2u;

uint field(uint word, uint shift, uint bits) {
    return (word >> shift) & ((1u << bits) - 1u);
}

#define GENERAL(NAME) field(KEY_GENERAL, NAME##_SHIFT, NAME##_BITS)

// Values of PRIMITIVE and FACING.
const uint PRIM_TRIANGLE = 0u;
const uint PRIM_LINE = 1u;
const uint PRIM_POINT = 2u;
const uint FACING_RASTERIZER = 0u;
const uint FACING_FRONT = 1u;
const uint FACING_BACK = 2u;

uint unit_word(int u) {
    return u == 0 ? KEY_UNIT0 : u == 1 ? KEY_UNIT1 : u == 2 ? KEY_UNIT2 : KEY_UNIT3;
}
