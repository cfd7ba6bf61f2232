//! One shader's translation unit: validation, declarations, and the rewrite into Vulkan GLSL.

use std::collections::HashMap;

use super::{CompiledShader, LinkedProgram, Stage};

/// What a compiled shader keeps for linking.
#[derive(Clone, Debug)]
pub struct Unit {
    /// The preprocessed source.
    pub preprocessed: String,
}

/// See [`super::compile`].
pub fn compile(stage: Stage, _source: &str) -> CompiledShader {
    CompiledShader { stage, ok: false, log: "glrt: GLSL is being built\n".into(), unit: None }
}

/// See [`super::link`].
pub fn link(_shaders: &[&CompiledShader], _attribute_bindings: &HashMap<String, u32>) -> LinkedProgram {
    LinkedProgram { ok: false, log: "glrt: GLSL is being built\n".into(), executable: None, uniforms: Vec::new(), uniform_block_size: 0, attributes: Vec::new() }
}
