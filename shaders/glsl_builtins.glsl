// The built-in uniform state of GLSL 1.10 (OpenGL 2.0 section 7.5 of the GLSL 1.10
// specification), as programs translated by src/translate/glsl read it: a gl_Name of the
// specification is glrt_Name here. Set 1, binding 0 (frame::program::BUILTINS_BINDING), std430.
// Packed per draw by src/translate/glsl/builtins.rs, whose test compares its offsets with this
// block's compiled SPIR-V. Not compiled on its own.

struct glrt_DepthRangeParameters {
    float near;
    float far;
    float diff;               // far - near
};

struct glrt_PointParameters {
    float size;
    float sizeMin;
    float sizeMax;
    float fadeThresholdSize;
    float distanceConstantAttenuation;
    float distanceLinearAttenuation;
    float distanceQuadraticAttenuation;
};

struct glrt_MaterialParameters {
    vec4 emission;
    vec4 ambient;
    vec4 diffuse;
    vec4 specular;
    float shininess;
};

struct glrt_LightSourceParameters {
    vec4 ambient;
    vec4 diffuse;
    vec4 specular;
    vec4 position;            // eye space
    vec4 halfVector;          // eye space: normalize(position + (0, 0, 1)) for directional lights
    vec3 spotDirection;       // eye space
    float spotExponent;
    float spotCutoff;         // degrees, 180 when off
    float spotCosCutoff;
    float constantAttenuation;
    float linearAttenuation;
    float quadraticAttenuation;
};

struct glrt_LightModelParameters {
    vec4 ambient;
};

struct glrt_LightModelProducts {
    vec4 sceneColor;          // emission + ambient * light model ambient
};

struct glrt_LightProducts {
    vec4 ambient;
    vec4 diffuse;
    vec4 specular;
};

struct glrt_FogParameters {
    vec4 color;
    float density;
    float start;
    float end;
    float scale;              // 1 / (end - start)
};

const int glrt_MaxLights = 8;
const int glrt_MaxClipPlanes = 6;
const int glrt_MaxTextureUnits = 4;
const int glrt_MaxTextureCoords = 4;
const int glrt_MaxVertexAttribs = 16;
const int glrt_MaxVertexUniformComponents = 1024;
const int glrt_MaxVaryingFloats = 64;
const int glrt_MaxVertexTextureImageUnits = 4;
const int glrt_MaxCombinedTextureImageUnits = 4;
const int glrt_MaxTextureImageUnits = 4;
const int glrt_MaxFragmentUniformComponents = 1024;
const int glrt_MaxDrawBuffers = 1;

layout(set = 1, binding = 0, std430) readonly buffer GlrtBuiltins {
    mat4 glrt_ModelViewMatrix;
    mat4 glrt_ProjectionMatrix;
    mat4 glrt_ModelViewProjectionMatrix;
    mat4 glrt_ModelViewMatrixInverse;
    mat4 glrt_ProjectionMatrixInverse;
    mat4 glrt_ModelViewProjectionMatrixInverse;
    mat4 glrt_ModelViewMatrixTranspose;
    mat4 glrt_ProjectionMatrixTranspose;
    mat4 glrt_ModelViewProjectionMatrixTranspose;
    mat4 glrt_ModelViewMatrixInverseTranspose;
    mat4 glrt_ProjectionMatrixInverseTranspose;
    mat4 glrt_ModelViewProjectionMatrixInverseTranspose;
    mat4 glrt_TextureMatrix[glrt_MaxTextureCoords];
    mat4 glrt_TextureMatrixInverse[glrt_MaxTextureCoords];
    mat4 glrt_TextureMatrixTranspose[glrt_MaxTextureCoords];
    mat4 glrt_TextureMatrixInverseTranspose[glrt_MaxTextureCoords];
    mat3 glrt_NormalMatrix;   // upper 3x3 of the modelview's inverse transpose
    float glrt_NormalScale;
    glrt_DepthRangeParameters glrt_DepthRange;
    vec4 glrt_ClipPlane[glrt_MaxClipPlanes];  // eye space, by plane index (disabled ones too)
    glrt_PointParameters glrt_Point;
    glrt_MaterialParameters glrt_FrontMaterial;
    glrt_MaterialParameters glrt_BackMaterial;
    glrt_LightSourceParameters glrt_LightSource[glrt_MaxLights];  // by light index
    glrt_LightModelParameters glrt_LightModel;
    glrt_LightModelProducts glrt_FrontLightModelProduct;
    glrt_LightModelProducts glrt_BackLightModelProduct;
    glrt_LightProducts glrt_FrontLightProduct[glrt_MaxLights];
    glrt_LightProducts glrt_BackLightProduct[glrt_MaxLights];
    vec4 glrt_TextureEnvColor[glrt_MaxTextureUnits];
    vec4 glrt_EyePlaneS[glrt_MaxTextureCoords];
    vec4 glrt_EyePlaneT[glrt_MaxTextureCoords];
    vec4 glrt_EyePlaneR[glrt_MaxTextureCoords];
    vec4 glrt_EyePlaneQ[glrt_MaxTextureCoords];
    vec4 glrt_ObjectPlaneS[glrt_MaxTextureCoords];
    vec4 glrt_ObjectPlaneT[glrt_MaxTextureCoords];
    vec4 glrt_ObjectPlaneR[glrt_MaxTextureCoords];
    vec4 glrt_ObjectPlaneQ[glrt_MaxTextureCoords];
    glrt_FogParameters glrt_Fog;
    // Not GLSL state: per sampler slot (frame::program::MAX_SAMPLERS), how a shadow sampler
    // compares and what a depth texture expands to. x: comparison, in the order NEVER, LESS,
    // EQUAL, LEQUAL, GREATER, NOTEQUAL, GEQUAL, ALWAYS (8: GL_TEXTURE_COMPARE_MODE is NONE);
    // y: GL_DEPTH_TEXTURE_MODE, 0 LUMINANCE, 1 INTENSITY, 2 ALPHA; z: 1 for a depth texture.
    uvec4 glrt_SamplerDepth[8];
    // Not GLSL state: x is 1 when GL_VERTEX_PROGRAM_POINT_SIZE is on (points take the size the
    // vertex shader wrote, else the state's).
    uvec4 glrt_Flags;
};
