// Fixed-function fragment stage (OpenGL 1.5 sections 3.3 to 3.5 for antialiasing coverage and
// stipples, 3.8 texturing, 3.9 colour sum, 3.10 fog (then the renderer's height fog), 3.12 coverage, 4.1.4 alpha test): see
// src/render/raster/ff/mod.rs for the interface. The texture environment is texenv.glsl's,
// shared with the path tracer.

#define FF_FRAGMENT
#include "generated/texenv_codes.glsl"
#include "generated/ff_interface.glsl"
#include "bit_field.glsl"
#include "ff_key.glsl"
#include "fog/height.glsl"
#include "ff_uniforms.glsl"
#include "ff_varyings.glsl"
#include "gl_compare.glsl"
#include "ff_fragment_ops.glsl"
#include "texenv.glsl"

layout(set = 0, binding = BINDING_SAMPLER_2D + 0u) uniform sampler2D tex2d_0;
layout(set = 0, binding = BINDING_SAMPLER_2D + 1u) uniform sampler2D tex2d_1;
layout(set = 0, binding = BINDING_SAMPLER_2D + 2u) uniform sampler2D tex2d_2;
layout(set = 0, binding = BINDING_SAMPLER_2D + 3u) uniform sampler2D tex2d_3;
layout(set = 0, binding = BINDING_SAMPLER_3D + 0u) uniform sampler3D tex3d_0;
layout(set = 0, binding = BINDING_SAMPLER_3D + 1u) uniform sampler3D tex3d_1;
layout(set = 0, binding = BINDING_SAMPLER_3D + 2u) uniform sampler3D tex3d_2;
layout(set = 0, binding = BINDING_SAMPLER_3D + 3u) uniform sampler3D tex3d_3;
layout(set = 0, binding = BINDING_SAMPLER_CUBE + 0u) uniform samplerCube texcube_0;
layout(set = 0, binding = BINDING_SAMPLER_CUBE + 1u) uniform samplerCube texcube_1;
layout(set = 0, binding = BINDING_SAMPLER_CUBE + 2u) uniform samplerCube texcube_2;
layout(set = 0, binding = BINDING_SAMPLER_CUBE + 3u) uniform samplerCube texcube_3;

layout(location = 0) out vec4 out_color;

// The texel of a unit (section 3.8): projective coordinates, the unit's LOD bias, depth
// comparison and expansion (section 3.8.14); white when the unit does not texture.
vec4 sample_unit(uint word, sampler2D s2, sampler3D s3, samplerCube sc, vec4 c, float bias) {
    uint target = field(word, TARGET_SHIFT, TARGET_BITS);
    if (target == 5u) {
        // A rectangle texture (ARB_texture_rectangle): s and t are in texels; it is sampled
        // as the 2D texture of one level it is stored as.
        c.st /= vec2(textureSize(s2, 0));
        target = 2u;
    }
    uint clamped = field(word, CLAMP_SHIFT, CLAMP_BITS);
    vec4 t = vec4(1.0);
    if (clamped != 0u && target != 4u) {
        // GL_CLAMP with a linear filter (section 3.8.7): the coordinate is clamped to [0, 1]
        // and the sampler's border fills the other half of an edge texel's footprint. The
        // level of detail comes from the unclamped coordinates (their gradients, scaled by
        // the bias).
        vec3 p = c.stp / c.q;
        vec3 q = mix(p, clamp(p, 0.0, 1.0), bvec3((clamped & 1u) != 0u, (clamped & 2u) != 0u, (clamped & 4u) != 0u));
        float scale = exp2(bias);
        if (target == 1u) {
            t = textureGrad(s2, vec2(q.x, 0.5), vec2(dFdx(p.x), 0.0) * scale, vec2(dFdy(p.x), 0.0) * scale);
        } else if (target == 2u) {
            t = textureGrad(s2, q.xy, dFdx(p.xy) * scale, dFdy(p.xy) * scale);
        } else {
            t = textureGrad(s3, q, dFdx(p) * scale, dFdy(p) * scale);
        }
    } else if (target == 1u) {
        t = texture(s2, vec2(c.s / c.q, 0.5), bias);
    } else if (target == 2u) {
        t = texture(s2, c.st / c.q, bias);
    } else if (target == 3u) {
        t = texture(s3, c.stp / c.q, bias);
    } else if (target == 4u) {
        t = texture(sc, c.stp, bias);
    }
    uint depth = field(word, DEPTH_SHIFT, DEPTH_BITS);
    if (depth != 0u) {
        float d = t.r;
        if (depth >= 2u) {
            float r = clamp(target == 4u ? c.p : c.p / c.q, 0.0, 1.0);
            d = compare(depth - 2u, r, d) ? 1.0 : 0.0;
        }
        uint format = field(word, FORMAT_SHIFT, FORMAT_BITS);
        t = format == FORMAT_ALPHA ? vec4(0.0, 0.0, 0.0, d) : format == FORMAT_INTENSITY ? vec4(d) : vec4(d, d, d, 1.0);
    }
    return t;
}

// Point sprite coordinates (OpenGL 2.0 section 3.3) for a unit that replaces them: v_raster.xy
// is the fragment centre's window offset from the point's exact position and v_misc.z the
// size, so s = 1/2 + (x_f + 1/2 - x_w) / size, and t likewise upwards or downwards; r is 0 or,
// with GL_NV_point_sprite's r mode, the vertex's s / q or r / q.
vec4 sprite_coord(uint word, vec4 tex) {
    uint replace = field(word, COORD_REPLACE_SHIFT, COORD_REPLACE_BITS);
    if (replace == 0u) {
        return tex;
    }
    vec2 st = 0.5 + v_raster.xy / max(v_misc.z, 1e-6);
    uint r_mode = field(word, SPRITE_R_SHIFT, SPRITE_R_BITS);
    float r = r_mode == 1u ? tex.s / tex.q : r_mode == 2u ? tex.p / tex.q : 0.0;
    return vec4(st.x, replace == 2u ? st.y : 1.0 - st.y, r, 1.0);
}

void main() {
    ff_varyings_in();
    if (stippled_out()) {
        discard;
    }
    uint facing = GENERAL(FACING);
    bool front = facing == FACING_RASTERIZER ? gl_FrontFacing : facing == FACING_FRONT;
    bool flat_shaded = GENERAL(FLAT) != 0u;
    vec4 primary = flat_shaded ? (front ? f_front : f_back) : (front ? v_front : v_back);
    vec4 secondary = flat_shaded ? (front ? f_front2 : f_back2) : (front ? v_front2 : v_back2);

    vec4 coord[MAX_UNITS];
    for (int i = 0; i < MAX_UNITS; i++) {
        coord[i] = sprite_coord(unit_word(i), v_tex[i]);
    }
    vec4 texel[MAX_UNITS];
    texel[0] = sample_unit(KEY_UNIT0, tex2d_0, tex3d_0, texcube_0, coord[0], u.lod_bias[0]);
    texel[1] = sample_unit(KEY_UNIT1, tex2d_1, tex3d_1, texcube_1, coord[1], u.lod_bias[1]);
    texel[2] = sample_unit(KEY_UNIT2, tex2d_2, tex3d_2, texcube_2, coord[2], u.lod_bias[2]);
    texel[3] = sample_unit(KEY_UNIT3, tex2d_3, tex3d_3, texcube_3, coord[3], u.lod_bias[3]);

    vec4 color = primary;
    for (int i = 0; i < MAX_UNITS; i++) {
        uint word = unit_word(i);
        if (field(word, TARGET_SHIFT, TARGET_BITS) != 0u) {
            uint rgb = i == 0 ? KEY_COMBINE_RGB0 : i == 1 ? KEY_COMBINE_RGB1 : i == 2 ? KEY_COMBINE_RGB2 : KEY_COMBINE_RGB3;
            uint alpha = i == 0 ? KEY_COMBINE_ALPHA0 : i == 1 ? KEY_COMBINE_ALPHA1 : i == 2 ? KEY_COMBINE_ALPHA2 : KEY_COMBINE_ALPHA3;
            color = tex_env(word, rgb, alpha, u.env_color[i], color, texel[i], texel, primary);
        }
    }

    // Colour sum (section 3.9).
    if (GENERAL(COLOR_SUM) != 0u) {
        color.rgb = min(color.rgb + secondary.rgb, 1.0);
    }

    // Fog (section 3.10).
    uint fog = GENERAL(FOG);
    if (fog != 0u) {
        float c = v_misc.x;
        vec4 p = u.fog_params;
        float f = fog == 1u ? (p.y - c) * p.w : fog == 2u ? exp(-p.z * c) : exp(-(p.z * c) * (p.z * c));
        color.rgb = mix(u.fog_color.rgb, color.rgb, clamp(f, 0.0, 1.0));
    }
    // The renderer's height fog (src/render/fog), after the program's own.
    color.rgb = height_fog_apply(u.height_fog, gl_FragCoord.xyz, color.rgb);

    color.a *= smooth_coverage();
    if (alpha_tested_out(color.a)) {
        discard;
    }
    out_color = color;
}
