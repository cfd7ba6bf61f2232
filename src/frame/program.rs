//! OpenGL 2.0 shader programs as draws use them: the linked program's SPIR-V (a stage it lacks
//! is the fixed-function one) and, per draw, the bytes of its uniform blocks and the textures
//! of its samplers.
//!
//! The shader interface (descriptor sets, vertex inputs, varyings, specialisation constants)
//! is the contract written in `translate::glsl` (its module doc): the programs' SPIR-V is
//! generated to fit the fixed-function pipeline's set 0 and adds set 1.

use std::sync::Arc;

use super::TextureRef;

/// What a sampler uniform samples (its GLSL type); 1D samplers are 2D samplers one texel high,
/// as in the fixed-function shaders.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SamplerKind {
    /// `sampler1D`, `sampler2D`.
    D2,
    /// `sampler3D`.
    D3,
    /// `samplerCube`.
    Cube,
    /// `sampler1DShadow`, `sampler2DShadow`: a depth texture the shader compares.
    D2Shadow,
}

/// A linked program object's executable: what `glLinkProgram` produced. A relink makes a new
/// one, with a new [`ShaderProgram::id`].
#[derive(Clone, Debug, PartialEq)]
pub struct ShaderProgram {
    /// Unique across the process for every successful link: renderers key pipelines on it.
    pub id: u64,
    /// SPIR-V of the vertex stage; `None` when the program has no vertex shader (the
    /// fixed-function vertex stage runs).
    pub vertex: Option<Arc<[u32]>>,
    /// SPIR-V of the fragment stage; `None` when the program has no fragment shader (the
    /// fixed-function fragment stage runs).
    pub fragment: Option<Arc<[u32]>>,
    /// The sampler slots of set 1 (slot `i` at binding [`FIRST_SAMPLER_BINDING`] `+ i`).
    pub samplers: Vec<SamplerKind>,
    /// Generic vertex attribute indices the vertex stage reads, ascending (1 to 15, one per
    /// `vec4` location; index 0 is the position, which every draw has).
    pub attributes: Vec<u32>,
}

/// Vulkan location of generic vertex attribute 1 in a program's vertex stage (attribute 0 is
/// `gl_Vertex`, location 0; generic attribute `i` is at this `+ i - 1`).
pub const GENERIC_ATTRIBUTE_LOCATION: u32 = 10;
/// Binding in set 1 of the built-in state block (`shaders/glsl_builtins.glsl`).
pub const BUILTINS_BINDING: u32 = 0;
/// Binding in set 1 of the block of the program's own uniforms.
pub const UNIFORMS_BINDING: u32 = 1;
/// Binding in set 1 of sampler slot 0.
pub const FIRST_SAMPLER_BINDING: u32 = 2;
/// Sampler slots a program may have.
pub const MAX_SAMPLERS: usize = 8;

/// The program a draw runs, with the values it runs with.
#[derive(Clone, Debug, PartialEq)]
pub struct ProgramDraw {
    /// The executable.
    pub program: Arc<ShaderProgram>,
    /// The built-in state block (`shaders/glsl_builtins.glsl`, std430), packed from the
    /// context state of the draw.
    pub builtins: Arc<[u8]>,
    /// The program's own uniforms (std430, laid out by the link).
    pub uniforms: Arc<[u8]>,
    /// Per sampler slot: the texture bound, for the slot's kind, to the texture unit the
    /// sampler uniform names (`None`: no complete texture, which samples as (0, 0, 0, 1)).
    pub textures: Vec<Option<TextureRef>>,
    /// `GL_VERTEX_PROGRAM_POINT_SIZE`: points take the size the vertex shader wrote.
    pub point_size_from_shader: bool,
    /// `GL_VERTEX_PROGRAM_TWO_SIDE`: back faces take the back colours the vertex shader wrote.
    pub two_side: bool,
}
