//! GLSL 1.10 and 1.20 (OpenGL 2.0 and 2.1) shaders: compiling, linking and reflecting them, and
//! turning the result into SPIR-V that fits the fixed-function pipeline of the raster renderer.
//!
//! [`compile`] validates one shader's source with glslang as the GLSL version it declares
//! (1.10 when it declares none), which gives `glCompileShader` its status and info log.
//! [`link`] checks the stages against each other, lays out the uniforms and attributes, and
//! rewrites each stage into Vulkan GLSL 4.50 (built-in `gl_*` state renamed to the `glrt_*`
//! declarations of `shaders/glsl_builtins.glsl`, `texture2D` and friends to functions of a
//! prelude, user identifiers prefixed so they cannot clash with 4.50's names or glrt's own)
//! wrapped in a `main` that does what the fixed-function stages around a shader do, and
//! compiles that to SPIR-V.
//!
//! # The shader interface (the contract with `render::raster`)
//!
//! A program pipeline is the fixed-function pipeline (`render::raster::ff`) with one or both
//! stages replaced:
//! - **Set 0** is the fixed-function set, unchanged: binding 0 the per-batch fixed-function
//!   block (`shaders/ff_uniforms.glsl`), bindings 1 to 12 the fixed-function samplers; the
//!   specialisation constants are the fixed-function key words (`shaders/ff_key.glsl`). A
//!   program stage reads from them what the fixed-function operations around a shader need
//!   (viewport, stipples, alpha test, flat shading, facing, two-sided colour selection,
//!   smooth coverage, the framebuffer height), so the renderer fills them as for any draw. For
//!   a program with a vertex shader, the key's `TWO_SIDE` bit carries
//!   `GL_VERTEX_PROGRAM_TWO_SIDE` (the generated vertex stage passes the back colours only
//!   then); with the fixed-function vertex stage it stays the lighting's bit.
//! - **Set 1** is the program's: binding [`crate::frame::program::BUILTINS_BINDING`] the
//!   built-in state block, binding [`crate::frame::program::UNIFORMS_BINDING`] the block of the
//!   program's uniforms (both read-only storage buffers, std430, visible to both stages),
//!   binding [`crate::frame::program::FIRST_SAMPLER_BINDING`] `+ i` the combined image sampler
//!   of sampler slot `i` of the kind [`crate::frame::program::ShaderProgram::samplers`] says.
//!   A depth texture in a slot holds its depth in the red channel; the shader compares and
//!   expands it with `glrt_SamplerDepth[i]` of the built-in block.
//! - **Vertex inputs** of a program's vertex stage: the fixed-function vertex layout
//!   (`render::raster::ff::VERTEX_ATTRIBUTES`, locations 0 to 9: `gl_Vertex` is location 0,
//!   `gl_Color` 1, `gl_SecondaryColor` 2, `gl_Normal` 3, `gl_FogCoord` 4,
//!   `gl_MultiTexCoord0..3` 5 to 8), and generic attribute `i` (1 to 15) at location
//!   [`crate::frame::program::GENERIC_ATTRIBUTE_LOCATION`] `+ i - 1`, as `vec4` (a matrix
//!   attribute takes one location, and one generic index, per column).
//! - **Varyings** between the stages: the fixed-function ones of `shaders/ff_varyings.glsl`
//!   at their locations (so a program stage pairs with a fixed-function stage), then the
//!   program's own varyings from location [`FIRST_USER_VARYING`], one location per `vec4`,
//!   array element or matrix column.
//! - **Primitives**: with a fixed-function vertex stage, batches arrive as the
//!   fixed-function path makes them (points and lines expanded to triangles with
//!   `v_raster`). With a program vertex stage, the CPU cannot place points and lines (it does
//!   not know the positions), so the renderer draws them with Vulkan's own point and line
//!   topologies and polygon modes; the vertex stage writes `gl_PointSize` (the shader's when
//!   [`crate::frame::program::ProgramDraw::point_size_from_shader`], else the state's size).
//! - **Output**: location 0, the fragment colour clamped to [0, 1]; `gl_FragDepth` when the
//!   shader writes it.

use std::collections::HashMap;
use std::sync::Arc;

use crate::frame::program::ShaderProgram;

/// Vulkan location of the first varying a program declares itself.
pub const FIRST_USER_VARYING: u32 = 14;

/// A shader stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stage {
    /// `GL_VERTEX_SHADER`.
    Vertex,
    /// `GL_FRAGMENT_SHADER`.
    Fragment,
}

/// What `glCompileShader` made of a shader's source.
#[derive(Clone, Debug)]
pub struct CompiledShader {
    /// The stage.
    pub stage: Stage,
    /// `GL_COMPILE_STATUS`.
    pub ok: bool,
    /// The info log (empty when there is nothing to say).
    pub log: String,
    /// What [`link`] needs of it (present when `ok`).
    pub unit: Option<Arc<unit::Unit>>,
}

/// An active uniform as `glGetActiveUniform` reports it: one entry per variable of a basic
/// type, arrays as one entry, struct members as separate entries (`light.color`,
/// `lights[1].color`).
#[derive(Clone, Debug, PartialEq)]
pub struct ActiveUniform {
    /// The name as the program spells it (an array without `[0]`).
    pub name: String,
    /// The GL type enum (`GL_FLOAT_VEC3`, `GL_SAMPLER_2D`, ...).
    pub ty: u32,
    /// Array elements (1 for a non-array).
    pub size: u32,
    /// Where it lives: bytes in the uniform block, or a sampler slot.
    pub storage: UniformStorage,
}

/// Where an active uniform's value lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UniformStorage {
    /// In the program's uniform block (std430): element `i` at `offset + i * array_stride`;
    /// a matrix's column `c` at `matrix_stride * c` from its element; a bool is a 4-byte
    /// integer (0 or 1); an int is a 4-byte integer; a float is an `f32`.
    Block {
        /// Offset of element 0.
        offset: u32,
        /// Bytes between array elements.
        array_stride: u32,
        /// Bytes between matrix columns (0 for vectors and scalars).
        matrix_stride: u32,
    },
    /// A sampler: element `i` is slot `first_slot + i` of [`ShaderProgram::samplers`], and its
    /// value (`glUniform1i`) is the texture unit it samples.
    Sampler {
        /// Slot of element 0.
        first_slot: u32,
    },
}

/// An active vertex attribute as `glGetActiveAttrib` reports it.
#[derive(Clone, Debug, PartialEq)]
pub struct ActiveAttribute {
    /// The name.
    pub name: String,
    /// The GL type enum (`GL_FLOAT`, `GL_FLOAT_VEC4`, `GL_FLOAT_MAT3`, ...).
    pub ty: u32,
    /// Its generic attribute index (0 for `gl_Vertex`-like built-ins is never reported: only
    /// the program's own attributes are listed); a matrix takes this index and the next ones.
    pub index: u32,
}

/// What `glLinkProgram` made of a program's attached shaders.
#[derive(Clone, Debug)]
pub struct LinkedProgram {
    /// `GL_LINK_STATUS`.
    pub ok: bool,
    /// The info log.
    pub log: String,
    /// The executable, present when `ok` (its id is 0: the caller numbers it).
    pub executable: Option<ShaderProgram>,
    /// Active uniforms, in the order `glGetActiveUniform` enumerates them.
    pub uniforms: Vec<ActiveUniform>,
    /// Size of the program's uniform block in bytes.
    pub uniform_block_size: u32,
    /// Active attributes (the program's own, not the built-in `gl_*` ones).
    pub attributes: Vec<ActiveAttribute>,
}

/// Compiles one shader: validates `source` as the GLSL it declares.
pub fn compile(stage: Stage, source: &str) -> CompiledShader {
    unit::compile(stage, source)
}

/// Links compiled shaders (at most one per stage is glrt's limit; the log says so otherwise)
/// with the `glBindAttribLocation` bindings in force.
pub fn link(shaders: &[&CompiledShader], attribute_bindings: &HashMap<String, u32>) -> LinkedProgram {
    unit::link(shaders, attribute_bindings)
}

pub mod builtins;
pub mod unit;
pub mod compiler;
pub mod declarations;
pub mod layout;
pub mod tokens;
pub mod types;
pub mod rewrite;
#[cfg(test)]
mod tests;
