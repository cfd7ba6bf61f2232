//! What gl.xml does not say: which extensions glrt implements, which commands the OpenGL 1.5
//! specification allows between `glBegin` and `glEnd` (section 2.6.3), which ones are executed at
//! once instead of being compiled into display lists (section 5.4), and the attribute families
//! whose many variants (`glVertex3sv`, `glColor4ub`...) reduce to one canonical command.

/// Extensions whose commands glrt exports and implements (the `GL_EXTENSIONS` string lists the
/// subset whose semantics are complete; see `translate::strings`).
pub const EXTENSIONS: &[&str] = &[
    "GL_ARB_multitexture",
    "GL_EXT_compiled_vertex_array",
    "GL_EXT_draw_range_elements",
    "GL_EXT_texture_env_add",
    "GL_EXT_texture_env_combine",
    "GL_ARB_texture_env_combine",
    "GL_ARB_texture_env_add",
    "GL_EXT_point_parameters",
    "GL_ARB_point_parameters",
    "GL_ARB_texture_compression",
    "GL_EXT_texture_compression_s3tc",
    "GL_ARB_vertex_buffer_object",
    "GL_EXT_paletted_texture",
    "GL_EXT_shared_texture_palette",
    "GL_EXT_color_subtable",
    "GL_EXT_fog_coord",
    "GL_EXT_secondary_color",
    "GL_ARB_texture_cube_map",
    "GL_EXT_blend_color",
    "GL_EXT_blend_minmax",
    "GL_EXT_blend_subtract",
    "GL_EXT_texture_object",
    "GL_EXT_vertex_array",
    "GL_EXT_polygon_offset",
    "GL_EXT_texture3D",
    "GL_EXT_multi_draw_arrays",
    "GL_ARB_window_pos",
    "GL_ARB_transpose_matrix",
    "GL_ARB_occlusion_query",
    "GL_EXT_blend_func_separate",
    "GL_EXT_framebuffer_object",
    "GL_EXT_framebuffer_blit",
    "GL_ARB_map_buffer_range",
    "GL_ATI_separate_stencil",
    "GL_EXT_stencil_two_side",
    "GL_EXT_blend_equation_separate",
    "GL_ARB_draw_buffers",
    "GL_ARB_texture_rectangle",
    "GL_NV_point_sprite",
    "GL_EXT_texture_integer",
];

/// Commands allowed between `glBegin` and `glEnd` besides the attribute families
/// (OpenGL 1.5, section 2.6.3). Every other command there raises `GL_INVALID_OPERATION`.
pub const INSIDE_BEGIN_END: &[&str] = &[
    "End", "ArrayElement", "MTexCoord2fSGIS", "EvalPoint1", "EvalPoint2", "Materialf", "Materialfv", "Materiali",
    "Materialiv", "EdgeFlag", "EdgeFlagv", "CallList", "CallLists",
];

/// Client-side commands: never compiled into display lists (section 5.4). Between `glBegin`
/// and `glEnd` they raise `GL_INVALID_OPERATION` like every command section 2.6.3 does not
/// allow there (Mesa does the same; piglit's `gl-1.0-beginend-coverage` checks it).
pub const CLIENT_SIDE: &[&str] = &[
    "VertexPointer", "NormalPointer", "ColorPointer", "IndexPointer", "TexCoordPointer",
    "EdgeFlagPointer", "FogCoordPointer", "SecondaryColorPointer", "InterleavedArrays",
    "EnableClientState", "DisableClientState", "ClientActiveTexture", "PixelStoref",
    "PixelStorei", "PushClientAttrib", "PopClientAttrib", "LockArraysEXT", "UnlockArraysEXT",
    "GetPointerv", "VertexPointerEXT", "NormalPointerEXT", "ColorPointerEXT", "IndexPointerEXT",
    "TexCoordPointerEXT", "EdgeFlagPointerEXT", "VertexAttribPointer", "EnableVertexAttribArray",
    "DisableVertexAttribArray",
];

/// Commands executed immediately even while a display list is compiled (OpenGL 1.5, section
/// 5.4), in addition to every `glGet*`, `glIs*` and the client-side commands.
pub const NOT_COMPILED: &[&str] = &[
    "NewList", "EndList", "GenLists", "DeleteLists", "FeedbackBuffer", "SelectBuffer",
    "RenderMode", "ReadPixels", "GenTextures", "DeleteTextures", "AreTexturesResident",
    "GenQueries", "DeleteQueries", "BindBuffer", "DeleteBuffers", "GenBuffers", "BufferData",
    "BufferSubData", "MapBuffer", "UnmapBuffer", "MapBufferRange", "FlushMappedBufferRange", "Flush",
    "Finish", "GetError", "GenRenderbuffersEXT", "DeleteRenderbuffersEXT", "GenFramebuffersEXT",
    "DeleteFramebuffersEXT", "CheckFramebufferStatusEXT", "CreateProgram", "CreateShader",
    "DeleteProgram", "DeleteShader", "AttachShader", "DetachShader", "BindAttribLocation",
    "CompileShader", "ShaderSource", "LinkProgram", "ValidateProgram",
];

/// Commands that read client arrays: in a display list they are compiled with the array data
/// dereferenced at compile time, by `Context::compile_glNAME` (section 5.4).
pub const COMPILED_DEREFERENCED: &[&str] = &[
    "ArrayElement", "DrawArrays", "DrawElements", "DrawRangeElements", "MultiDrawArrays",
    "MultiDrawElements",
];

/// An attribute family: `gl{base}{N}{type}[v]` variants all become one canonical command.
pub struct Family {
    /// Name stem, such as `Vertex`.
    pub base: &'static str,
    /// The command every variant becomes, such as `Vertex4f`.
    pub canonical: &'static str,
    /// Components of the canonical command.
    pub components: usize,
    /// Values of components a variant does not give.
    pub defaults: [&'static str; 4],
    /// Integer components map to [-1, 1] or [0, 1] (table 2.9) instead of being converted.
    pub normalized: bool,
    /// A leading non-component parameter (`target` of `glMultiTexCoord`).
    pub leading: bool,
    /// Allowed between `glBegin` and `glEnd` (all but `glRasterPos` and `glWindowPos`).
    pub inside_begin_end: bool,
}

const fn family(
    base: &'static str,
    canonical: &'static str,
    components: usize,
    defaults: [&'static str; 4],
    normalized: bool,
) -> Family {
    Family { base, canonical, components, defaults, normalized, leading: false, inside_begin_end: true }
}

/// Every attribute family of OpenGL 1.5 and the implemented extensions.
pub const FAMILIES: &[Family] = &[
    family("Vertex", "Vertex4f", 4, ["0.0", "0.0", "0.0", "1.0"], false),
    family("TexCoord", "TexCoord4f", 4, ["0.0", "0.0", "0.0", "1.0"], false),
    Family {
        base: "MultiTexCoord",
        canonical: "MultiTexCoord4f",
        components: 4,
        defaults: ["0.0", "0.0", "0.0", "1.0"],
        normalized: false,
        leading: true,
        inside_begin_end: true,
    },
    family("Color", "Color4f", 4, ["0.0", "0.0", "0.0", "1.0"], true),
    family("SecondaryColor", "SecondaryColor3f", 3, ["0.0", "0.0", "0.0", "0.0"], true),
    family("Normal", "Normal3f", 3, ["0.0", "0.0", "0.0", "0.0"], true),
    family("FogCoord", "FogCoordf", 1, ["0.0", "0.0", "0.0", "0.0"], false),
    family("Index", "Indexf", 1, ["0.0", "0.0", "0.0", "0.0"], false),
    Family {
        inside_begin_end: false,
        ..family("RasterPos", "RasterPos4f", 4, ["0.0", "0.0", "0.0", "1.0"], false)
    },
    Family {
        inside_begin_end: false,
        ..family("WindowPos", "WindowPos3f", 3, ["0.0", "0.0", "0.0", "0.0"], false)
    },
    Family {
        leading: true,
        ..family("VertexAttrib", "VertexAttrib4f", 4, ["0.0", "0.0", "0.0", "1.0"], false)
    },
    Family {
        leading: true,
        ..family("VertexAttrib4N", "VertexAttrib4f", 4, ["0.0", "0.0", "0.0", "1.0"], true)
    },
    family("EvalCoord1", "EvalCoord1f", 1, ["0.0", "0.0", "0.0", "0.0"], false),
    family("EvalCoord2", "EvalCoord2f", 2, ["0.0", "0.0", "0.0", "0.0"], false),
];

/// Commands of extensions withdrawn before the registry was written, which GL 1.x games still
/// use: `(C name, parameters as (name, Rust type), Rust return type)`. GLQuake and Quake 2 use
/// `GL_SGIS_multitexture`.
/// Aliases the registry does not record: EXT_texture_object's commands, whose
/// texture names the extension shares like OpenGL 1.1's (Mesa serves both by one function).
pub const EXTRA_ALIASES: &[(&str, &str)] = &[
    ("GenTexturesEXT", "GenTextures"),
    ("DeleteTexturesEXT", "DeleteTextures"),
    ("IsTextureEXT", "IsTexture"),
    ("AreTexturesResidentEXT", "AreTexturesResident"),
];

/// A command the registry lacks: name, parameters (name, Rust type), return type.
pub type ExtraCommand = (&'static str, &'static [(&'static str, &'static str)], &'static str);

pub const EXTRA_COMMANDS: &[ExtraCommand] = &[
    ("glSelectTextureSGIS", &[("target", "types::GLenum")], "()"),
    ("glMTexCoord2fSGIS", &[("target", "types::GLenum"), ("s", "types::GLfloat"), ("t", "types::GLfloat")], "()"),
];
