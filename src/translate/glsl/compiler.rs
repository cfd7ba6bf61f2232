//! glslang, Khronos' reference GLSL front end, used twice: to validate and preprocess the
//! program's source as the GLSL version it declares, and to compile glrt's Vulkan GLSL rewrite
//! of it to SPIR-V.

use glslang::{
    Compiler, CompilerOptions, GlslProfile, Shader, ShaderInput, ShaderMessage, ShaderSource, ShaderStage, SourceLanguage,
    SpirvVersion, Target, VulkanVersion,
};

use super::Stage;

/// glslang's stage.
fn stage_of(stage: Stage) -> ShaderStage {
    match stage {
        Stage::Vertex => ShaderStage::Vertex,
        Stage::Fragment => ShaderStage::Fragment,
    }
}

/// The compiler instance (glslang's process-wide initialisation).
fn compiler() -> Result<&'static Compiler, String> {
    Compiler::acquire().ok_or_else(|| "glrt: the GLSL compiler (glslang) could not be initialised\n".to_string())
}

/// glslang's log without the "parse error: " prefix of the Rust binding, ending in a newline.
fn log_text(e: glslang::error::GlslangError) -> String {
    let text = match e {
        glslang::error::GlslangError::ParseError(s) | glslang::error::GlslangError::PreprocessError(s) => s,
        other => other.to_string(),
    };
    let mut text = text.trim_end().to_string();
    text.push('\n');
    text
}

/// Validates `source` as OpenGL GLSL of the version it declares (1.10 when it declares none,
/// as section 3.3 of the GLSL 1.10 specification says) and returns it preprocessed, or the
/// info log of its errors.
pub fn validate(stage: Stage, source: &str) -> Result<String, String> {
    let compiler = compiler()?;
    let text = ShaderSource::from(source.to_string());
    let version = match text.parse_profile() {
        Some(profile) => profile,
        None => (110, GlslProfile::None),
    };
    if version.0 > 120 {
        return Err(format!("ERROR: 0:1: '#version' : GLSL {} is not supported by glrt (1.10 and 1.20 are)\n", version.0));
    }
    let options = CompilerOptions {
        source_language: SourceLanguage::GLSL,
        target: Target::None(None),
        version_profile: Some(version),
        messages: ShaderMessage::DEFAULT,
    };
    let input = ShaderInput::new(&text, stage_of(stage), &options, None::<&[(&str, Option<&str>)]>, None).map_err(log_text)?;
    let shader = Shader::new(compiler, input).map_err(log_text)?;
    Ok(shader.get_preprocessed_code())
}

/// Compiles Vulkan GLSL 4.50 `source` (glrt's rewrite) to SPIR-V.
pub fn spirv(stage: Stage, source: &str) -> Result<Vec<u32>, String> {
    let compiler = compiler()?;
    let text = ShaderSource::from(source.to_string());
    let options = CompilerOptions {
        source_language: SourceLanguage::GLSL,
        target: Target::Vulkan { version: VulkanVersion::Vulkan1_0, spirv_version: SpirvVersion::SPIRV1_0 },
        version_profile: None,
        messages: ShaderMessage::DEFAULT,
    };
    let input = ShaderInput::new(&text, stage_of(stage), &options, None::<&[(&str, Option<&str>)]>, None).map_err(log_text)?;
    let shader = Shader::new(compiler, input).map_err(log_text)?;
    shader.compile().map_err(log_text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validates_glsl_110_by_its_rules() {
        let ok = validate(Stage::Fragment, "uniform sampler2D t;\nvoid main() { gl_FragColor = texture2D(t, gl_TexCoord[0].xy); }\n");
        assert!(ok.is_ok(), "{ok:?}");
        // GLSL 1.10 has no implicit int-to-float conversion; 1.20 has.
        let int_to_float = "void main() { float x = 1; gl_FragColor = vec4(x); }\n";
        let err = validate(Stage::Fragment, int_to_float).unwrap_err();
        assert!(err.contains("ERROR: 0:1:"), "{err}");
        assert!(validate(Stage::Fragment, &format!("#version 120\n{int_to_float}")).is_ok());
        assert!(validate(Stage::Vertex, "#version 130\nvoid main() {}\n").unwrap_err().contains("not supported"));
    }

    #[test]
    fn compiles_vulkan_glsl() {
        let words = spirv(Stage::Fragment, "#version 450\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec4(1.0); }\n").unwrap();
        assert_eq!(words[0], 0x0723_0203);
        assert!(spirv(Stage::Fragment, "#version 450\nvoid main() { c = 1; }\n").is_err());
    }
}
