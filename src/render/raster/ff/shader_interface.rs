//! What `ff.vert` and `ff.frag` share with Rust besides the texture environment's words
//! ([`crate::render::texenv::codes`]): the descriptor bindings of set 0, the vertex inputs'
//! locations ([`super::vertex`]), the limits of the
//! uniform block, the fields of the shader key's words ([`super::key`]) and the codes of the
//! primitive and facing fields, generated into `generated/ff_interface.glsl` (see
//! [`crate::render::shader_abi`]).

glsl_constants! {
    /// Binding of the uniform block `FF` (a storage buffer, `ff_uniforms.glsl`).
    const BINDING_UNIFORMS: u32 = 0;
    /// Binding of unit 0's `sampler2D` (1D and 2D textures); unit `u` at `+ u`.
    const BINDING_SAMPLER_2D: u32 = 1;
    /// Binding of unit 0's `sampler3D`, after the `MAX_UNITS` 2D samplers.
    const BINDING_SAMPLER_3D: u32 = 5;
    /// Binding of unit 0's `samplerCube`, after the 3D samplers.
    const BINDING_SAMPLER_CUBE: u32 = 9;
    /// Number of bindings: the cube samplers are the last.
    const BINDING_COUNT: u32 = 13;

    /// Vertex input: the object-space position.
    const LOCATION_POSITION: u32 = 0;
    /// Vertex input: the primary colour.
    const LOCATION_COLOR: u32 = 1;
    /// Vertex input: the secondary colour.
    const LOCATION_SECONDARY: u32 = 2;
    /// Vertex input: the normal.
    const LOCATION_NORMAL: u32 = 3;
    /// Vertex input: the fog coordinate.
    const LOCATION_FOG_COORD: u32 = 4;
    /// Vertex input: unit 0's texture coordinates; unit `u` at `+ u`.
    const LOCATION_TEXCOORD: u32 = 5;
    /// Vertex input: the rasterization attribute of expanded lines and points.
    const LOCATION_RASTER: u32 = 9;
    /// Vertex input: radiosity's indirect light on the vertex (read under [`RADIOSITY`]);
    /// after the locations a program's generic attributes take (10 to 24).
    const LOCATION_INDIRECT: u32 = 25;

    /// Lights the uniform block holds (`GL_MAX_LIGHTS`).
    const MAX_LIGHTS: usize = 8;
    /// Clip planes the uniform block holds (`GL_MAX_CLIP_PLANES`).
    const MAX_CLIP_PLANES: usize = 6;

    /// [`PRIMITIVE`]: filled triangles.
    const PRIM_TRIANGLE: u32 = 0;
    /// [`PRIMITIVE`]: lines expanded to quads on the CPU.
    const PRIM_LINE: u32 = 1;
    /// [`PRIMITIVE`]: points expanded to quads on the CPU.
    const PRIM_POINT: u32 = 2;
    /// [`FACING`]: the rasterizer's facing (`gl_FrontFacing`).
    const FACING_RASTERIZER: u32 = 0;
    /// [`FACING`]: the front colours.
    const FACING_FRONT: u32 = 1;
    /// [`FACING`]: the back colours.
    const FACING_BACK: u32 = 2;
}

glsl_fields! {
    /// What the batch rasterizes: `PRIM_*` (see `super::convert`).
    PRIMITIVE = (0, 2);
    /// Flat shading: the fragment stage reads the provoking vertex's colours.
    FLAT = (2, 1);
    /// Which colours the fragment stage uses: `FACING_*`.
    FACING = (3, 2);
    /// `GL_LIGHTING`.
    LIGHTING = (5, 1);
    /// `GL_LIGHT_MODEL_TWO_SIDE`.
    TWO_SIDE = (6, 1);
    /// `GL_LIGHT_MODEL_LOCAL_VIEWER`.
    LOCAL_VIEWER = (7, 1);
    /// `GL_SEPARATE_SPECULAR_COLOR`.
    SEPARATE_SPECULAR = (8, 1);
    /// Colour material: 0 off, else 1 + the mode (emission, ambient, diffuse, specular,
    /// ambient and diffuse).
    COLOR_MATERIAL = (9, 3);
    /// Colour material faces: bit 0 front, bit 1 back.
    COLOR_MATERIAL_FACES = (12, 2);
    /// Normal scaling: 0 none, 1 `GL_NORMALIZE`, 2 `GL_RESCALE_NORMAL`.
    NORMAL_SCALING = (14, 2);
    /// Number of enabled lights (packed first in the uniform block).
    LIGHT_COUNT = (16, 4);
    /// The colour sum is applied (section 3.9).
    COLOR_SUM = (20, 1);
    /// Fog: 0 off, 1 linear, 2 exp, 3 exp2.
    FOG = (21, 2);
    /// Fog distance from the fog coordinate instead of the eye depth.
    FOG_COORD = (23, 1);
    /// Alpha test: 0 off, else 1 + the compare function (never, less, equal, lequal, greater,
    /// notequal, gequal, always).
    ALPHA_TEST = (24, 4);
    /// `GL_POLYGON_STIPPLE` (triangles only).
    POLYGON_STIPPLE = (28, 1);
    /// `GL_LINE_STIPPLE` (lines only).
    LINE_STIPPLE = (29, 1);
    /// Antialiasing of points (`GL_POINT_SMOOTH`) or lines (`GL_LINE_SMOOTH`): coverage to
    /// alpha.
    SMOOTH = (30, 1);
    /// Points are point sprites (`GL_POINT_SPRITE`, points only): squares of the unrounded
    /// size at the exact position.
    SPRITE = (31, 1);

    /// Clip word: bit `i` set when the `i`-th packed clip plane is enabled.
    CLIP_MASK = (0, 6);
    /// Clip word: radiosity's indirect light replaces the lighting's scene ambient term: the
    /// vertex input at `LOCATION_INDIRECT` (irradiance / π, linear) times the material's
    /// diffuse colour, added to the rest of the light in linear units
    /// (`crate::render::radiosity::transfer`).
    RADIOSITY = (6, 1);
    /// Clip word: bit `u` set when nothing reads texture unit `u`'s coordinates (the unit does
    /// not texture and no program runs): `ff.vert` leaves them zero, and the compact vertex
    /// formats (`super::compact`) do not carry them.
    TEXCOORDS_UNUSED = (7, 4);

    /// Unit word: 0 no texturing, 1 1D, 2 2D, 3 3D, 4 cube map, 5 rectangle (coordinates in
    /// texels). The base format and texture function sit beside it (`texenv::codes`).
    TARGET = (0, 3);
    /// Unit word: generation of coordinate `c` (s, t, r, q) at `TEXGEN_SHIFT + 3 c`: 0 none,
    /// 1 object linear, 2 eye linear, 3 sphere map, 4 normal map, 5 reflection map.
    TEXGEN = (9, 3);
    /// Unit word: 0 a colour texture, 1 a depth texture (expanded by its
    /// `DEPTH_TEXTURE_MODE`), 2 + the compare function: a depth texture compared with r
    /// (section 3.8.14).
    DEPTH = (21, 4);
    /// Unit word: bit `c` set when coordinate `c` (s, t, r) is clamped to [0, 1] before
    /// sampling (`GL_CLAMP` with a linear filter).
    CLAMP = (25, 3);
    /// Unit word: point sprite coordinate replacement (`GL_COORD_REPLACE`, points only): 0
    /// off, 1 with t from 0 at the top (`GL_UPPER_LEFT`), 2 with t from 0 at the bottom
    /// (`GL_LOWER_LEFT`).
    COORD_REPLACE = (28, 2);
    /// Unit word: the replaced r coordinate of a point sprite (`GL_POINT_SPRITE_R_MODE_NV`):
    /// 0 zero, 1 the vertex's s / q, 2 its r / q.
    SPRITE_R = (30, 2);
}
