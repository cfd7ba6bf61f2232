// The layer stack of a traced surface (render::trace::material's module doc): the base's
// texture units, then its passes, evaluated as the rasterizer draws them (texenv.glsl per unit
// and per pass, blend.glsl per pass), in one walk that yields three colours, display-encoded:
// the raster colour C, C without the emission passes, and the albedo A.
// Include after trace/scene.glsl and trace/texels.glsl.

#ifndef TRACE_STACK_GLSL
#define TRACE_STACK_GLSL

#include "gl_compare.glsl"
#include "trace/scene.glsl"
#include "trace/texels.glsl"
#include "trace/blend.glsl"
#include "texenv.glsl"

// What a surface shows at one point.
struct Stack {
    vec4 color;     // C: every unit and pass, as the rasterizer shows it
    vec4 base;      // C without the emission passes
    vec4 albedo;    // A: without baked light and emission; the material's tint for the primary RGB when the vertex colours are light
    float alpha;    // the base's own alpha (its units' result): its coverage
};

// The three corner values v0, v1, v2 interpolated at bary.
vec4 interpolate(vec4 v0, vec4 v1, vec4 v2, vec2 bary) {
    return v0 * (1.0 - bary.x - bary.y) + v1 * bary.x + v2 * bary.y;
}

vec2 interpolate2(vec2 v0, vec2 v1, vec2 v2, vec2 bary) {
    return v0 * (1.0 - bary.x - bary.y) + v1 * bary.x + v2 * bary.y;
}

// The GL colour of a triangle corner interpolated at bary, still display-encoded.
vec4 corner_color(TriangleAttributes a, vec2 bary) {
    return interpolate(unpackUnorm4x8(a.corner[0].color), unpackUnorm4x8(a.corner[1].color), unpackUnorm4x8(a.corner[2].color), bary);
}

// The coordinates of traced unit `unit` interpolated at bary.
vec2 corner_uv(TriangleAttributes a, uint unit, vec2 bary) {
    return interpolate2(a.corner[0].uv[unit], a.corner[1].uv[unit], a.corner[2].uv[unit], bary);
}

// Ray-cone level of detail of texture `tex` mapped by the corner coordinates c0, c1, c2
// (Akenine-Möller et al. 2021, "Improved Shader and Texture Level of Detail Using Ray Cones"):
// texels per eye-space unit of the triangle (of doubled eye-space area area2), times the
// cone's footprint (cone_width, seen at cosine cos_view). 0 (the base level) without a cone.
float cone_lod(uint tex, vec2 c0, vec2 c1, vec2 c2, float area2, float cone_width, float cos_view) {
    if (tex == NO_TEXTURE || cone_width <= 0.0) {
        return 0.0;
    }
    vec2 size = texel_size(tex);
    vec2 t1 = (c1 - c0) * size;
    vec2 t2 = (c2 - c0) * size;
    float texel_area = abs(t1.x * t2.y - t1.y * t2.x);
    return area2 > 0.0 && texel_area > 0.0 ? 0.5 * log2(texel_area / area2) + log2(cone_width / cos_view) : 0.0;
}

// The texels of the material's units at bary, each at its level of detail; white for units
// that are off and for the units past the traced ones (texenv.glsl's crossbar reads them all).
void unit_texels(Material m, TriangleAttributes a, vec2 bary, float area2, float cone_width, float cos_view, out vec4 texel[MAX_UNITS]) {
    for (int u = 0; u < MAX_UNITS; u++) {
        texel[u] = vec4(1.0);
    }
    for (uint u = 0u; u < TRACED_UNITS; u++) {
        Layer l = m.layer[u];
        if (l.role != LAYER_OFF) {
            float lod = cone_lod(l.texture, a.corner[0].uv[u], a.corner[1].uv[u], a.corner[2].uv[u], area2, cone_width, cos_view);
            texel[u] = texel_sample(l.texture, corner_uv(a, u, bary), lod);
        }
    }
}

// The base's units applied to `primary` as the rasterizer's texture units apply them. For
// the albedo (`albedo`), the baked-light units are left out (white to the crossbar) and the
// primary colour's RGB is the material's tint when its vertex colours are light.
vec4 units_color(Material m, vec4 primary, vec4 texel[MAX_UNITS], bool albedo) {
    vec4 p = primary;
    vec4 t[MAX_UNITS] = texel;
    if (albedo) {
        if ((m.flags & MATERIAL_TINT_PRIMARY) != 0u) {
            p.rgb = unpackUnorm4x8(m.tint).rgb;
        }
        for (uint u = 0u; u < TRACED_UNITS; u++) {
            if (m.layer[u].role == LAYER_BAKED_LIGHT) {
                t[u] = vec4(1.0);
            }
        }
    }
    vec4 color = p;
    for (uint u = 0u; u < TRACED_UNITS; u++) {
        Layer l = m.layer[u];
        if (l.role == LAYER_OFF || (albedo && l.role == LAYER_BAKED_LIGHT)) {
            continue;
        }
        color = tex_env(l.env, l.combine_rgb, l.combine_alpha, l.env_color, color, t[u], t, p);
    }
    return color;
}

// A pass's own colour: its unit 0 applied to its primary colour.
vec4 pass_color(Layer l, vec4 primary, vec4 texel) {
    vec4 t[MAX_UNITS];
    for (int u = 0; u < MAX_UNITS; u++) {
        t[u] = vec4(1.0);
    }
    t[0] = texel;
    return tex_env(l.env, l.combine_rgb, l.combine_alpha, l.env_color, primary, texel, t, primary);
}

// The stack of material `m` at bary of the triangle with attributes `a`, local index `local`
// in its instance's geometry (its passes' corners), whose units' texels are `texel`; the
// passes' texels are read at the level of detail of the ray cone (cone_width, cos_view) on the
// triangle of doubled eye-space area area2.
Stack surface_stack(Material m, uint local, TriangleAttributes a, vec2 bary, vec4 texel[MAX_UNITS], float area2, float cone_width, float cos_view) {
    vec4 primary = corner_color(a, bary);
    Stack st;
    st.color = units_color(m, primary, texel, false);
    st.base = st.color;
    st.albedo = units_color(m, primary, texel, true);
    st.alpha = st.color.a;
    uint passes = min(m.passes, uint(MAX_PASSES));
    for (uint k = 0u; k < passes; k++) {
        Layer l = m.layer[uint(TRACED_UNITS) + k];
        LayerCorners c = layer_corners[m.layer_corners + local * m.passes + k];
        if (c.covered == 0u || l.role == LAYER_OFF) {
            continue;
        }
        float lod = cone_lod(l.texture, c.uv[0], c.uv[1], c.uv[2], area2, cone_width, cos_view);
        vec4 t = texel_sample(l.texture, interpolate2(c.uv[0], c.uv[1], c.uv[2], bary), lod);
        vec4 p = interpolate(unpackUnorm4x8(c.color[0]), unpackUnorm4x8(c.color[1]), unpackUnorm4x8(c.color[2]), bary);
        vec4 src = pass_color(l, p, t);
        if (!compare(l.alpha_func, src.a, l.alpha_ref)) {
            continue;
        }
        st.color = blend_over(l.blend, l.blend_color, src, st.color);
        if (l.role != LAYER_EMISSION) {
            st.base = blend_over(l.blend, l.blend_color, src, st.base);
        }
        if (l.role == LAYER_COLOR) {
            vec4 pa = p;
            if ((m.flags & MATERIAL_TINT_PRIMARY) != 0u) {
                pa.rgb = unpackUnorm4x8(m.tint).rgb;
            }
            st.albedo = blend_over(l.blend, l.blend_color, pass_color(l, pa, t), st.albedo);
        }
    }
    return st;
}

#endif
