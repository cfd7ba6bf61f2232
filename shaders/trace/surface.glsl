// What a ray hit: the shading inputs of a traced triangle (position, normals, albedo from the
// GL colour through the texture environment of the material's colour layers, texenv.glsl,
// baked light from a kept lightmap layer, material), and the alpha test that traversal asks
// for. render::trace::scene's module doc describes the layers.
// Include after bvh.glsl's prerequisites: defines trace_alpha_accept(), then includes bvh.glsl.

#ifndef TRACE_SURFACE_GLSL
#define TRACE_SURFACE_GLSL

#include "gl_compare.glsl"
#include "trace/scene.glsl"
#include "trace/pack.glsl"
#include "trace/texels.glsl"
#include "trace/brdf.glsl"
#include "texenv.glsl"

// The GL colour of a triangle corner interpolated at bary, still display-encoded.
vec4 corner_color(TriangleAttributes a, vec2 bary) {
    return unpackUnorm4x8(a.corner[0].color) * (1.0 - bary.x - bary.y) + unpackUnorm4x8(a.corner[1].color) * bary.x
        + unpackUnorm4x8(a.corner[2].color) * bary.y;
}

// The coordinates of traced unit `unit` interpolated at bary.
vec2 corner_uv(TriangleAttributes a, uint unit, vec2 bary) {
    return a.corner[0].uv[unit] * (1.0 - bary.x - bary.y) + a.corner[1].uv[unit] * bary.x + a.corner[2].uv[unit] * bary.y;
}

// Ray-cone level of detail of texture `tex` mapped by the corner coordinates c0, c1, c2
// (Akenine-Möller et al. 2021, "Improved Shader and Texture Level of Detail Using Ray Cones"):
// texels per eye-space unit of the triangle (of doubled eye-space area area2), times the
// cone's footprint (cone_width, seen at cosine cos_view).
float cone_lod(uint tex, vec2 c0, vec2 c1, vec2 c2, float area2, float cone_width, float cos_view) {
    vec2 size = texel_size(tex);
    vec2 t1 = (c1 - c0) * size;
    vec2 t2 = (c2 - c0) * size;
    float texel_area = abs(t1.x * t2.y - t1.y * t2.x);
    return area2 > 0.0 && texel_area > 0.0 ? 0.5 * log2(texel_area / area2) + log2(max(cone_width, 1e-12) / cos_view) : 0.0;
}

// The texels of the material's layers at bary, each at its level of detail; white for units
// that are off and for the units past the traced ones (texenv.glsl's crossbar reads them all).
void layer_texels(Material m, TriangleAttributes a, vec2 bary, float lod[TRACED_UNITS], out vec4 texel[MAX_UNITS]) {
    for (int u = 0; u < MAX_UNITS; u++) {
        texel[u] = vec4(1.0);
    }
    for (uint u = 0u; u < TRACED_UNITS; u++) {
        if (m.layer[u].role != LAYER_OFF) {
            texel[u] = texel_sample(m.layer[u].texture, corner_uv(a, u, bary), lod[u]);
        }
    }
}

// The colour (display-encoded RGBA) of a triangle at bary: the primary colour through the
// texture environment of each colour layer, as the rasterizer's texture units apply it.
vec4 surface_color(Material m, TriangleAttributes a, vec2 bary, vec4 texel[MAX_UNITS]) {
    vec4 primary = corner_color(a, bary);
    vec4 color = primary;
    for (uint u = 0u; u < TRACED_UNITS; u++) {
        Layer l = m.layer[u];
        if (l.role == LAYER_COLOR) {
            color = tex_env(l.env, l.combine_rgb, l.combine_alpha, l.env_color, color, texel[u], texel, primary);
        }
    }
    return color;
}

// The factor of a baked-light layer's texels: its RGB scale under GL_COMBINE, else 1.
float layer_scale(Layer l) {
    return field(l.env, ENV_SHIFT, ENV_BITS) == ENV_COMBINE ? float(1u << field(l.combine_rgb, SCALE_SHIFT, SCALE_BITS)) : 1.0;
}

// Traversal's question for alpha-tested instances: does the alpha test pass at this point?
// (Sampled at the base level: traversal knows no ray cone.)
bool trace_alpha_accept(uint instance, uint triangle, vec2 bary) {
    Material m = materials[instances[instance].material];
    TriangleAttributes a = attributes[triangle];
    float lod[TRACED_UNITS];
    for (uint u = 0u; u < TRACED_UNITS; u++) {
        lod[u] = 0.0;
    }
    vec4 texel[MAX_UNITS];
    layer_texels(m, a, bary, lod, texel);
    float alpha = surface_color(m, a, bary, texel).a;
    return compare(m.alpha_func, alpha, m.alpha_ref);
}

#include "trace/bvh.glsl"

// The object-space corners of global triangle `triangle`.
void trace_triangle_vertices(uint triangle, out vec3 v0, out vec3 v1, out vec3 v2) {
    BvhTriangle t = triangles[triangle];
    v0 = t.v0;
    v1 = v0 + t.e1;
    v2 = v0 + t.e2;
}

// An object-space vector or point through the instance's rows.
vec3 instance_transform(vec4 rows[3], vec4 v) {
    return vec3(dot(rows[0], v), dot(rows[1], v), dot(rows[2], v));
}

// The shading inputs at `hit` of a ray (origin, unit dir); cone_width is the ray cone's width
// at the hit (texture level of detail).
Surface surface_at(TraceHit hit, vec3 origin, vec3 dir, float cone_width) {
    Instance inst = instances[hit.instance];
    TriangleAttributes a = attributes[hit.triangle];
    Material m = materials[inst.material];
    vec3 p0, p1, p2;
    trace_triangle_vertices(hit.triangle, p0, p1, p2);
    vec3 e1 = instance_transform(inst.object_to_eye, vec4(p1 - p0, 0.0));
    vec3 e2 = instance_transform(inst.object_to_eye, vec4(p2 - p0, 0.0));
    vec3 ng = cross(e1, e2);
    float area2 = length(ng);
    ng = area2 > 0.0 ? ng / area2 : -dir;
    bool back = dot(ng, dir) > 0.0;
    if (back) {
        ng = -ng;
    }

    Surface s;
    s.position = origin + dir * hit.t;
    s.geometric = ng;
    s.normal = ng;
    if (a.corner[0].normal != 0u || a.corner[1].normal != 0u || a.corner[2].normal != 0u) {
        float w0 = 1.0 - hit.bary.x - hit.bary.y;
        vec3 n = unpack_normal(a.corner[0].normal) * w0 + unpack_normal(a.corner[1].normal) * hit.bary.x
            + unpack_normal(a.corner[2].normal) * hit.bary.y;
        // Normals go through the inverse transpose: the columns of eye_to_object's rows.
        n = inst.eye_to_object[0].xyz * n.x + inst.eye_to_object[1].xyz * n.y + inst.eye_to_object[2].xyz * n.z;
        float len = length(n);
        if (len > 0.0) {
            n /= len;
            s.normal = dot(n, ng) < 0.0 ? -n : n;
        }
    }

    float cos_view = max(abs(dot(ng, dir)), 1e-3);
    float lod[TRACED_UNITS];
    for (uint u = 0u; u < TRACED_UNITS; u++) {
        uint tex = m.layer[u].role == LAYER_OFF ? NO_TEXTURE : m.layer[u].texture;
        lod[u] = tex == NO_TEXTURE ? 0.0 : cone_lod(tex, a.corner[0].uv[u], a.corner[1].uv[u], a.corner[2].uv[u], area2, cone_width, cos_view);
    }
    vec4 texel[MAX_UNITS];
    layer_texels(m, a, hit.bary, lod, texel);
    vec4 color = surface_color(m, a, hit.bary, texel);
    s.albedo = srgb_to_linear(color.rgb);
    s.alpha = color.a;
    s.emission = m.emission.rgb + s.albedo * m.emission.a;
    // A kept lightmap (render::trace::scene's module doc): the surface sends its baked light,
    // albedo x decoded (scale x lightmap), and reflects no traced light.
    s.baked = false;
    for (uint u = 0u; u < TRACED_UNITS; u++) {
        if (m.layer[u].role == LAYER_BAKED_LIGHT) {
            s.baked = true;
            s.emission += s.albedo * srgb_decode(max(texel[u].rgb * layer_scale(m.layer[u]), 0.0));
        }
    }
    s.roughness = m.roughness;
    s.metalness = m.metalness;
    s.specular = m.specular;
    return s;
}

#endif
