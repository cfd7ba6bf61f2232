// The texture lookup functions of GLSL 1.10 (section 8.7) for programs translated by
// src/translate/glsl: `texture2D(s, c)` becomes `glrt_texture2D(s, c, slot)`, where `slot` is
// the sampler's slot (-1 when the sampler is a function parameter). 1D and shadow samplers are
// declared as sampler2D (1D textures are 2D textures one texel high); depth textures hold the
// depth in red, expanded and compared here with glrt_SamplerDepth (glsl_builtins.glsl). Also
// ftransform(). Included after glsl_builtins.glsl and gl_compare.glsl.

// A texel of slot `slot` as the texture's base format makes it: depth expanded by
// GL_DEPTH_TEXTURE_MODE.
vec4 glrt_expand(vec4 t, int slot) {
    if (slot < 0 || glrt_SamplerDepth[slot].z == 0u) {
        return t;
    }
    uint mode = glrt_SamplerDepth[slot].y;
    return mode == 2u ? vec4(0.0, 0.0, 0.0, t.r) : mode == 1u ? vec4(t.r) : vec4(t.rrr, 1.0);
}

// The result of a shadow lookup: depth `d` compared with reference `r` (section 3.8.14).
vec4 glrt_shadow(float d, float r, int slot) {
    uint func = slot < 0 ? 8u : glrt_SamplerDepth[slot].x;
    float v = func >= 8u ? d : (compare(func, clamp(r, 0.0, 1.0), d) ? 1.0 : 0.0);
    uint mode = slot < 0 ? 0u : glrt_SamplerDepth[slot].y;
    return mode == 2u ? vec4(0.0, 0.0, 0.0, v) : mode == 1u ? vec4(v) : vec4(v, v, v, 1.0);
}

vec4 glrt_texture1D(sampler2D s, float c, int slot) { return glrt_expand(texture(s, vec2(c, 0.5)), slot); }
vec4 glrt_texture1DProj(sampler2D s, vec2 c, int slot) { return glrt_expand(texture(s, vec2(c.x / c.y, 0.5)), slot); }
vec4 glrt_texture1DProj(sampler2D s, vec4 c, int slot) { return glrt_expand(texture(s, vec2(c.x / c.w, 0.5)), slot); }
vec4 glrt_texture1DLod(sampler2D s, float c, float lod, int slot) { return glrt_expand(textureLod(s, vec2(c, 0.5), lod), slot); }
vec4 glrt_texture1DProjLod(sampler2D s, vec2 c, float lod, int slot) { return glrt_expand(textureLod(s, vec2(c.x / c.y, 0.5), lod), slot); }
vec4 glrt_texture1DProjLod(sampler2D s, vec4 c, float lod, int slot) { return glrt_expand(textureLod(s, vec2(c.x / c.w, 0.5), lod), slot); }
vec4 glrt_texture2D(sampler2D s, vec2 c, int slot) { return glrt_expand(texture(s, c), slot); }
vec4 glrt_texture2DProj(sampler2D s, vec3 c, int slot) { return glrt_expand(textureProj(s, c), slot); }
vec4 glrt_texture2DProj(sampler2D s, vec4 c, int slot) { return glrt_expand(textureProj(s, c), slot); }
vec4 glrt_texture2DLod(sampler2D s, vec2 c, float lod, int slot) { return glrt_expand(textureLod(s, c, lod), slot); }
vec4 glrt_texture2DProjLod(sampler2D s, vec3 c, float lod, int slot) { return glrt_expand(textureProjLod(s, c, lod), slot); }
vec4 glrt_texture2DProjLod(sampler2D s, vec4 c, float lod, int slot) { return glrt_expand(textureProjLod(s, c, lod), slot); }
vec4 glrt_texture3D(sampler3D s, vec3 c, int slot) { return texture(s, c); }
vec4 glrt_texture3DProj(sampler3D s, vec4 c, int slot) { return textureProj(s, c); }
vec4 glrt_texture3DLod(sampler3D s, vec3 c, float lod, int slot) { return textureLod(s, c, lod); }
vec4 glrt_texture3DProjLod(sampler3D s, vec4 c, float lod, int slot) { return textureProjLod(s, c, lod); }
vec4 glrt_textureCube(samplerCube s, vec3 c, int slot) { return glrt_expand(texture(s, c), slot); }
vec4 glrt_textureCubeLod(samplerCube s, vec3 c, float lod, int slot) { return glrt_expand(textureLod(s, c, lod), slot); }
vec4 glrt_shadow1D(sampler2D s, vec3 c, int slot) { return glrt_shadow(texture(s, vec2(c.x, 0.5)).r, c.z, slot); }
vec4 glrt_shadow2D(sampler2D s, vec3 c, int slot) { return glrt_shadow(texture(s, c.xy).r, c.z, slot); }
vec4 glrt_shadow1DProj(sampler2D s, vec4 c, int slot) { return glrt_shadow(texture(s, vec2(c.x / c.w, 0.5)).r, c.z / c.w, slot); }
vec4 glrt_shadow2DProj(sampler2D s, vec4 c, int slot) { return glrt_shadow(texture(s, c.xy / c.w).r, c.z / c.w, slot); }
vec4 glrt_shadow1DLod(sampler2D s, vec3 c, float lod, int slot) { return glrt_shadow(textureLod(s, vec2(c.x, 0.5), lod).r, c.z, slot); }
vec4 glrt_shadow2DLod(sampler2D s, vec3 c, float lod, int slot) { return glrt_shadow(textureLod(s, c.xy, lod).r, c.z, slot); }
vec4 glrt_shadow1DProjLod(sampler2D s, vec4 c, float lod, int slot) { return glrt_shadow(textureLod(s, vec2(c.x / c.w, 0.5), lod).r, c.z / c.w, slot); }
vec4 glrt_shadow2DProjLod(sampler2D s, vec4 c, float lod, int slot) { return glrt_shadow(textureLod(s, c.xy / c.w, lod).r, c.z / c.w, slot); }

#ifdef FF_FRAGMENT
// The fragment stage's lookups with a level-of-detail bias.
vec4 glrt_texture1D(sampler2D s, float c, float bias, int slot) { return glrt_expand(texture(s, vec2(c, 0.5), bias), slot); }
vec4 glrt_texture1DProj(sampler2D s, vec2 c, float bias, int slot) { return glrt_expand(texture(s, vec2(c.x / c.y, 0.5), bias), slot); }
vec4 glrt_texture1DProj(sampler2D s, vec4 c, float bias, int slot) { return glrt_expand(texture(s, vec2(c.x / c.w, 0.5), bias), slot); }
vec4 glrt_texture2D(sampler2D s, vec2 c, float bias, int slot) { return glrt_expand(texture(s, c, bias), slot); }
vec4 glrt_texture2DProj(sampler2D s, vec3 c, float bias, int slot) { return glrt_expand(textureProj(s, c, bias), slot); }
vec4 glrt_texture2DProj(sampler2D s, vec4 c, float bias, int slot) { return glrt_expand(textureProj(s, c, bias), slot); }
vec4 glrt_texture3D(sampler3D s, vec3 c, float bias, int slot) { return texture(s, c, bias); }
vec4 glrt_texture3DProj(sampler3D s, vec4 c, float bias, int slot) { return textureProj(s, c, bias); }
vec4 glrt_textureCube(samplerCube s, vec3 c, float bias, int slot) { return glrt_expand(texture(s, c, bias), slot); }
vec4 glrt_shadow1D(sampler2D s, vec3 c, float bias, int slot) { return glrt_shadow(texture(s, vec2(c.x, 0.5), bias).r, c.z, slot); }
vec4 glrt_shadow2D(sampler2D s, vec3 c, float bias, int slot) { return glrt_shadow(texture(s, c.xy, bias).r, c.z, slot); }
vec4 glrt_shadow1DProj(sampler2D s, vec4 c, float bias, int slot) { return glrt_shadow(texture(s, vec2(c.x / c.w, 0.5), bias).r, c.z / c.w, slot); }
vec4 glrt_shadow2DProj(sampler2D s, vec4 c, float bias, int slot) { return glrt_shadow(texture(s, c.xy / c.w, bias).r, c.z / c.w, slot); }
#endif
