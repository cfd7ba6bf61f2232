// The declarations a translated vertex shader sees before its own code (src/translate/glsl):
// the built-in attributes at the fixed-function vertex layout's locations, and the built-in
// outputs as plain variables that glsl_vertex_main.glsl passes on. Included after
// ff_key.glsl, ff_uniforms.glsl, ff_varyings.glsl, gl_compare.glsl and glsl_builtins.glsl.

layout(location = LOCATION_POSITION) in vec4 glrt_Vertex;
layout(location = LOCATION_COLOR) in vec4 glrt_Color;
layout(location = LOCATION_SECONDARY) in vec4 glrt_SecondaryColor;
layout(location = LOCATION_NORMAL) in vec3 glrt_Normal;
layout(location = LOCATION_FOG_COORD) in float glrt_FogCoord;
layout(location = LOCATION_TEXCOORD + 0u) in vec4 glrt_MultiTexCoord0;
layout(location = LOCATION_TEXCOORD + 1u) in vec4 glrt_MultiTexCoord1;
layout(location = LOCATION_TEXCOORD + 2u) in vec4 glrt_MultiTexCoord2;
layout(location = LOCATION_TEXCOORD + 3u) in vec4 glrt_MultiTexCoord3;
// Units beyond glrt_MaxTextureCoords have no coordinates: their initial value.
const vec4 glrt_MultiTexCoord4 = vec4(0.0, 0.0, 0.0, 1.0);
const vec4 glrt_MultiTexCoord5 = vec4(0.0, 0.0, 0.0, 1.0);
const vec4 glrt_MultiTexCoord6 = vec4(0.0, 0.0, 0.0, 1.0);
const vec4 glrt_MultiTexCoord7 = vec4(0.0, 0.0, 0.0, 1.0);

vec4 glrt_FrontColor = vec4(0.0, 0.0, 0.0, 1.0);
vec4 glrt_BackColor = vec4(0.0, 0.0, 0.0, 1.0);
vec4 glrt_FrontSecondaryColor = vec4(0.0);
vec4 glrt_BackSecondaryColor = vec4(0.0);
vec4 glrt_TexCoord[glrt_MaxTextureCoords];
float glrt_FogFragCoord = 0.0;
vec4 glrt_ClipVertex;

out float gl_ClipDistance[MAX_CLIP_PLANES];

// ftransform(): the position exactly as the fixed-function vertex stage computes it.
vec4 glrt_ftransform() {
    return u.projection * (u.modelview * glrt_Vertex);
}
