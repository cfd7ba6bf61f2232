#version 450
#extension GL_GOOGLE_include_directive : require
// The fixed-function fragment stage of lean keys (ShaderKey::lean in src/render/raster/ff/key.rs):
// only the varyings such keys read are interpolated (ff_varyings.glsl).
#define FF_LEAN
#include "ff_fragment.glsl"
