// The declarations a translated fragment shader sees before its own code (src/translate/glsl):
// the built-in inputs and outputs as plain variables that glsl_fragment_main.glsl fills and
// reads. Included after ff_key.glsl, ff_uniforms.glsl, ff_varyings.glsl, gl_compare.glsl,
// ff_fragment_ops.glsl and glsl_builtins.glsl.

layout(location = 0) out vec4 out_color;

vec4 glrt_FragCoord;
bool glrt_FrontFacing;
vec2 glrt_PointCoord;
vec4 glrt_Color;
vec4 glrt_SecondaryColor;
vec4 glrt_TexCoord[glrt_MaxTextureCoords];
float glrt_FogFragCoord;
vec4 glrt_FragColor = vec4(0.0);
vec4 glrt_FragData[glrt_MaxDrawBuffers];
