// The field of `bits` bits from bit `shift` of a packed word (shader key words, material
// words; the fields are render::shader_abi::Field values of the generated headers).

#ifndef BIT_FIELD_GLSL
#define BIT_FIELD_GLSL

uint field(uint word, uint shift, uint bits) {
    return (word >> shift) & ((1u << bits) - 1u);
}

#endif
