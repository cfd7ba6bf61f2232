// Fixed-function vertex stage (OpenGL 1.5 sections 2.10 to 2.14, 3.3 and 3.4 for the expanded
// points and lines): see src/render/raster/ff/mod.rs for the interface (vertex layout,
// descriptor bindings, specialisation constants) and convert.rs for the expanded primitives.

#include "generated/texenv_codes.glsl"
#include "generated/ff_interface.glsl"
#include "bit_field.glsl"
#include "ff_key.glsl"
#include "fog/height.glsl"
#include "ff_uniforms.glsl"
#include "ff_varyings.glsl"

layout(location = LOCATION_POSITION) in vec4 in_position;
layout(location = LOCATION_COLOR) in vec4 in_color;
layout(location = LOCATION_SECONDARY) in vec4 in_secondary;
layout(location = LOCATION_NORMAL) in vec3 in_normal;
layout(location = LOCATION_FOG_COORD) in float in_fog_coord;
layout(location = LOCATION_TEXCOORD) in vec4 in_texcoord[MAX_UNITS];
layout(location = LOCATION_RASTER) in vec4 in_raster;
layout(location = LOCATION_INDIRECT) in vec4 in_indirect;

out float gl_ClipDistance[MAX_CLIP_PLANES];

vec3 normalize_or_zero(vec3 v) {
    float l = length(v);
    return l > 0.0 ? v / l : vec3(0.0);
}

// x^e with 0^0 = 1 (the specular and spot exponents may be 0).
float pow_gl(float x, float e) {
    return e == 0.0 ? 1.0 : pow(max(x, 0.0), e);
}

// The unit vector from p1 to p2 with the rules of section 2.14.1 for points at infinity.
vec3 unit_between(vec4 p1, vec4 p2) {
    vec3 v;
    if (p1.w != 0.0 && p2.w != 0.0) {
        v = p2.xyz / p2.w - p1.xyz / p1.w;
    } else if (p1.w != 0.0) {
        v = p2.xyz;
    } else if (p2.w != 0.0) {
        v = -p1.xyz;
    } else {
        v = p2.xyz - p1.xyz;
    }
    return normalize_or_zero(v);
}

// The material of face `face` (0 front, 1 back) with the colour material (section 2.14.3).
Material material_of(int face) {
    Material m = u.material[face];
    uint mode = GENERAL(COLOR_MATERIAL);
    if (mode != 0u && (GENERAL(COLOR_MATERIAL_FACES) & (1u << uint(face))) != 0u) {
        vec4 c = in_color;
        if (mode == 1u) {
            m.emission = c;
        } else if (mode == 2u) {
            m.ambient = c;
        } else if (mode == 3u) {
            m.diffuse = c;
        } else if (mode == 4u) {
            m.specular = c;
        } else {
            m.ambient = c;
            m.diffuse = c;
        }
    }
    return m;
}

// A display-encoded colour (sRGB) in linear units, negative values as 0.
vec3 linear_of(vec3 c) {
    c = max(c, vec3(0.0));
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

// A linear colour display-encoded (sRGB).
vec3 display_encoded(vec3 c) {
    c = max(c, vec3(0.0));
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

// The lighting equation of section 2.14.1 for one face: primary and secondary colour; with
// the key's RADIOSITY, radiosity's indirect light in place of the scene's ambient light.
void shade(Material m, vec3 n, vec4 pos, out vec4 primary, out vec4 secondary) {
    vec3 eye_dir = GENERAL(LOCAL_VIEWER) != 0u ? unit_between(pos, vec4(0.0, 0.0, 0.0, 1.0)) : vec3(0.0, 0.0, 1.0);
    // Radiosity's indirect light replaces the scene's ambient light (added below).
    bool radiosity = field(KEY_CLIP, RADIOSITY_SHIFT, RADIOSITY_BITS) != 0u;
    vec3 sum = m.emission.rgb + (radiosity ? vec3(0.0) : m.ambient.rgb * u.scene_ambient.rgb);
    vec3 spec = vec3(0.0);
    for (int i = 0; i < int(GENERAL(LIGHT_COUNT)); i++) {
        Light l = u.light[i];
        vec3 to_light = unit_between(pos, l.position);
        float att = 1.0;
        if (l.position.w != 0.0) {
            vec3 k = l.params.yzw;
            if (pos.w == 0.0) {
                att = (k.y == 0.0 && k.z == 0.0) ? 1.0 / k.x : 0.0;
            } else {
                float d = length(l.position.xyz / l.position.w - pos.xyz / pos.w);
                att = 1.0 / (k.x + k.y * d + k.z * d * d);
            }
        }
        float spot = 1.0;
        if (l.params.x >= -1.0) {
            float d = max(dot(-to_light, l.spot.xyz), 0.0);
            spot = d >= l.params.x ? pow_gl(d, l.spot.w) : 0.0;
        }
        float factor = att * spot;
        float diffuse = max(dot(n, to_light), 0.0);
        sum += factor * (m.ambient.rgb * l.ambient.rgb + diffuse * m.diffuse.rgb * l.diffuse.rgb);
        if (diffuse != 0.0) {
            vec3 h = normalize_or_zero(to_light + eye_dir);
            spec += factor * pow_gl(max(dot(n, h), 0.0), m.shininess.x) * m.specular.rgb * l.specular.rgb;
        }
    }
    if (radiosity) {
        // The indirect irradiance / pi (linear, as the tracer's light) reflected by the diffuse
        // colour, added to GL's light in linear units (GL's colours are display-encoded).
        sum = display_encoded(linear_of(sum) + linear_of(m.diffuse.rgb) * in_indirect.rgb);
    }
    if (GENERAL(SEPARATE_SPECULAR) != 0u) {
        primary = clamp(vec4(sum, m.diffuse.a), 0.0, 1.0);
        secondary = vec4(clamp(spec, 0.0, 1.0), 0.0);
    } else {
        primary = clamp(vec4(sum + spec, m.diffuse.a), 0.0, 1.0);
        secondary = vec4(0.0);
    }
}

// Texture coordinates of unit i: generation (section 2.10.4), then the texture matrix.
vec4 texcoord(int i, vec4 eye, vec3 n) {
    uint word = unit_word(i);
    vec4 t = in_texcoord[i];
    if (field(word, TEXGEN_SHIFT, 12u) != 0u) {
        vec3 e = normalize_or_zero(eye.xyz);
        vec3 r = e - 2.0 * n * dot(n, e);
        float m = 2.0 * sqrt(r.x * r.x + r.y * r.y + (r.z + 1.0) * (r.z + 1.0));
        for (int c = 0; c < 4; c++) {
            uint mode = field(word, TEXGEN_SHIFT + 3u * uint(c), TEXGEN_BITS);
            if (mode == 1u) {
                t[c] = dot(u.texgen_plane[4 * i + c], in_position);
            } else if (mode == 2u) {
                t[c] = dot(u.texgen_plane[4 * i + c], eye);
            } else if (mode == 3u && c < 2) {
                t[c] = (m > 0.0 ? r[c] / m : 0.0) + 0.5;
            } else if (mode == 4u && c < 3) {
                t[c] = n[c];
            } else if (mode == 5u && c < 3) {
                t[c] = r[c];
            }
        }
    }
    return u.texture_matrix[i] * t;
}

// Section 3.3 with the point parameters: the derived size (no fade: the fade threshold only
// applies to multisample rasterization, which glrt does not do).
float point_size(vec4 eye) {
    vec3 p = eye.w != 0.0 ? eye.xyz / eye.w : eye.xyz;
    float d = length(p);
    vec3 a = u.point_attenuation.xyz;
    float size = u.point.x * sqrt(1.0 / (a.x + a.y * d + a.z * d * d));
    size = clamp(size, u.point.y, u.point.z);
    // Smooth points and point sprites take the size as it is; aliased points round it.
    return GENERAL(SMOOTH) != 0u || GENERAL(SPRITE) != 0u ? size : max(round(size), 1.0);
}

void main() {
    vec4 eye = u.modelview * in_position;
    gl_Position = u.projection * eye;
    vec3 n = mat3(u.normal_matrix) * in_normal;
    uint scaling = GENERAL(NORMAL_SCALING);
    if (scaling == 1u) {
        n = normalize_or_zero(n);
    } else if (scaling == 2u) {
        n *= u.raster.w;
    }

    vec4 front, front2, back, back2;
    if (GENERAL(LIGHTING) != 0u) {
        shade(material_of(0), n, eye, front, front2);
        if (GENERAL(TWO_SIDE) != 0u) {
            shade(material_of(1), -n, eye, back, back2);
        } else {
            back = front;
            back2 = front2;
        }
    } else {
        front = clamp(in_color, 0.0, 1.0);
        front2 = clamp(in_secondary, 0.0, 1.0);
        back = front;
        back2 = front2;
    }
    ff_colors_out(front, front2, back, back2);

    // Units whose coordinates nothing reads (no texturing, no program) leave them zero.
    uint unused = field(KEY_CLIP, TEXCOORDS_UNUSED_SHIFT, TEXCOORDS_UNUSED_BITS);
    for (int i = 0; i < MAX_UNITS; i++) {
        v_tex[i] = (unused & (1u << uint(i))) != 0u ? vec4(0.0) : texcoord(i, eye, n);
    }

    // Fog distance (section 3.10): the fog coordinate, or the eye-space depth |z_e|.
    float fog = GENERAL(FOG_COORD) != 0u ? in_fog_coord : abs(eye.w != 0.0 ? eye.z / eye.w : eye.z);

    // User clip planes (section 2.12), in eye space.
    for (int i = 0; i < MAX_CLIP_PLANES; i++) {
        bool on = (field(KEY_CLIP, CLIP_MASK_SHIFT, CLIP_MASK_BITS) & (1u << uint(i))) != 0u;
        gl_ClipDistance[i] = on ? dot(u.clip_plane[i], eye) : 1.0;
    }

    vec2 viewport = max(u.viewport.zw, vec2(1.0));
    float size = 0.0;
    v_raster = in_raster;
    if (GENERAL(PRIMITIVE) == PRIM_POINT && gl_Position.w > 0.0) {
        // A square of the derived size centred on the point (section 3.3): aliased points
        // are centred on a pixel centre (odd sizes) or corner (even sizes); point sprites
        // on the exact position (OpenGL 2.0 section 3.3).
        size = point_size(eye);
        float half_size = size * 0.5 + (GENERAL(SMOOTH) != 0u ? 0.5 : 0.0);
        vec2 window = u.viewport.xy + (gl_Position.xy / gl_Position.w * 0.5 + 0.5) * viewport;
        if (GENERAL(SMOOTH) == 0u && GENERAL(SPRITE) == 0u) {
            window = mod(size, 2.0) == 1.0 ? floor(window) + 0.5 : floor(window + 0.5);
        }
        vec2 corner = in_raster.xy * half_size;
        vec2 ndc = (window + corner - u.viewport.xy) / viewport * 2.0 - 1.0;
        gl_Position.xy = ndc * gl_Position.w;
        v_raster.xy = corner;
    } else if (GENERAL(PRIMITIVE) == PRIM_LINE) {
        // The corner's window-pixel offset from its endpoint (convert.rs), in clip space.
        gl_Position.xy += in_raster.xy * 2.0 / viewport * gl_Position.w;
    }
    v_misc = vec4(fog, 0.0, size, 0.0);

    // OpenGL's clip-space depth is [-w, w], Vulkan's [0, w]. Window y: the renderer's
    // viewport has a negative height, so y needs no flip here.
    gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5;
    ff_varyings_out();
}
