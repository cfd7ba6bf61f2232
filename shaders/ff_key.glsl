// The shader key of the fixed-function shaders: the specialisation constants (the words of
// src/render/raster/ff/key.rs). Their bit fields (`<NAME>_SHIFT`, `<NAME>_BITS`) and codes come
// from generated/texenv_codes.glsl and generated/ff_interface.glsl, read with bit_field.glsl's
// field(); the including shader includes those first.

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

#define GENERAL(NAME) field(KEY_GENERAL, NAME##_SHIFT, NAME##_BITS)

uint unit_word(int u) {
    return u == 0 ? KEY_UNIT0 : u == 1 ? KEY_UNIT1 : u == 2 ? KEY_UNIT2 : KEY_UNIT3;
}
