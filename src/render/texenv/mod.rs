//! OpenGL's texture environment (OpenGL 1.5 section 3.8.13 with ARB_texture_env_combine,
//! crossbar and dot3) as the words `shaders/texenv.glsl` evaluates: one GLSL function,
//! `tex_env`, that both the fixed-function fragment shader (`ff.frag`, per enabled unit, the
//! words as specialisation constants) and the path tracer (`shaders/trace/surface.glsl`, per
//! traced unit of a material) call, so a traced surface combines its textures exactly as the
//! rasterizer does.
//!
//! A unit is described by its *unit word* (the base format and texture function fields of
//! [`codes`]), its two *combiner words* (RGB and alpha: function, three sources, three
//! operands, scale; zero unless the function is `GL_COMBINE`) and its environment colour.
//! [`unit_bits`] and [`combine_words`] encode them from a unit's GL state.

pub mod codes;

use crate::frame::TextureUnit;
use crate::frame::texture::{CombineFn, CombineOperand, CombineSource, DepthMode, EnvMode, TexelFormat, TextureContent, TextureEnv};
use codes::*;

/// The base format code (`FORMAT_*`) of `content` as the texture environment sees it
/// (table 3.22; depth textures by their `DEPTH_TEXTURE_MODE`, section 3.8.14).
pub fn format_code(content: &TextureContent) -> u32 {
    match content.format {
        TexelFormat::Alpha => FORMAT_ALPHA,
        TexelFormat::Luminance => FORMAT_LUMINANCE,
        TexelFormat::LuminanceAlpha => FORMAT_LUMINANCE_ALPHA,
        TexelFormat::Intensity => FORMAT_INTENSITY,
        TexelFormat::Rgb | TexelFormat::Red | TexelFormat::Rg => FORMAT_RGB,
        TexelFormat::Rgba => FORMAT_RGBA,
        TexelFormat::Depth => match content.sampler.depth_mode {
            DepthMode::Alpha => FORMAT_ALPHA,
            DepthMode::Luminance => FORMAT_LUMINANCE,
            DepthMode::Intensity => FORMAT_INTENSITY,
        },
    }
}

/// The texture function code (`ENV_*`) of `mode`.
pub fn env_code(mode: EnvMode) -> u32 {
    match mode {
        EnvMode::Modulate => ENV_MODULATE,
        EnvMode::Replace => ENV_REPLACE,
        EnvMode::Decal => ENV_DECAL,
        EnvMode::Blend => ENV_BLEND,
        EnvMode::Add => ENV_ADD,
        EnvMode::Combine => ENV_COMBINE,
    }
}

/// The [`FORMAT`] and [`ENV`] fields of the unit word of `unit` texturing with `content`.
pub fn unit_bits(unit: &TextureUnit, content: &TextureContent) -> u32 {
    let mut w = 0;
    FORMAT.set(&mut w, format_code(content));
    ENV.set(&mut w, env_code(unit.env.mode));
    w
}

/// The RGB and alpha combiner words of `env` (section 3.8.13, tables 3.23 to 3.26); zero
/// unless its mode is `GL_COMBINE`.
pub fn combine_words(env: &TextureEnv) -> [u32; 2] {
    if env.mode != EnvMode::Combine {
        return [0; 2];
    }
    [
        combine_word(env.combine_rgb, env.source_rgb, env.operand_rgb, env.scale[0]),
        combine_word(env.combine_alpha, env.source_alpha, env.operand_alpha, env.scale[1]),
    ]
}

/// One combiner word.
fn combine_word(f: CombineFn, sources: [CombineSource; 3], operands: [CombineOperand; 3], scale: f32) -> u32 {
    let mut w = 0;
    COMBINE_FN.set(
        &mut w,
        match f {
            CombineFn::Replace => COMBINE_REPLACE,
            CombineFn::Modulate => COMBINE_MODULATE,
            CombineFn::Add => COMBINE_ADD,
            CombineFn::AddSigned => COMBINE_ADD_SIGNED,
            CombineFn::Interpolate => COMBINE_INTERPOLATE,
            CombineFn::Subtract => COMBINE_SUBTRACT,
            CombineFn::Dot3Rgb => COMBINE_DOT3_RGB,
            CombineFn::Dot3Rgba => COMBINE_DOT3_RGBA,
        },
    );
    for (i, (source, operand)) in sources.into_iter().zip(operands).enumerate() {
        let source = match source {
            CombineSource::Texture => SOURCE_TEXTURE,
            CombineSource::TextureUnit(n) if (n as usize) < MAX_UNITS => SOURCE_TEXTURE0 + n as u32,
            // A unit the shaders do not have: its texture is undefined; use this unit's.
            CombineSource::TextureUnit(_) => SOURCE_TEXTURE,
            CombineSource::Constant => SOURCE_CONSTANT,
            CombineSource::PrimaryColor => SOURCE_PRIMARY_COLOR,
            CombineSource::Previous => SOURCE_PREVIOUS,
        };
        SOURCE.nth(i as u32).set(&mut w, source);
        let operand = match operand {
            CombineOperand::SrcColor => OPERAND_SRC_COLOR,
            CombineOperand::OneMinusSrcColor => OPERAND_ONE_MINUS_SRC_COLOR,
            CombineOperand::SrcAlpha => OPERAND_SRC_ALPHA,
            CombineOperand::OneMinusSrcAlpha => OPERAND_ONE_MINUS_SRC_ALPHA,
        };
        OPERAND.nth(i as u32).set(&mut w, operand);
    }
    SCALE.set(&mut w, if scale >= 4.0 { 2 } else if scale >= 2.0 { 1 } else { 0 });
    w
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::texture::TextureKind;

    #[test]
    fn fields_do_not_overlap_within_a_word() {
        let unit = [FORMAT, ENV];
        let combine = [COMBINE_FN, SOURCE.nth(0), SOURCE.nth(1), SOURCE.nth(2), OPERAND.nth(0), OPERAND.nth(1), OPERAND.nth(2), SCALE];
        for word in [&unit[..], &combine] {
            let mut used = 0u64;
            for f in word {
                let mask = ((1u64 << f.bits) - 1) << f.shift;
                assert_eq!(used & mask, 0, "{f:?} overlaps");
                assert!(f.shift + f.bits <= 32, "{f:?} past bit 31");
                used |= mask;
            }
        }
        assert!(SOURCE_PREVIOUS < 1 << SOURCE.bits);
    }

    #[test]
    fn combiner_word_sources_operands_scale() {
        let env = TextureEnv {
            mode: EnvMode::Combine,
            combine_rgb: CombineFn::Dot3Rgba,
            source_rgb: [CombineSource::TextureUnit(3), CombineSource::Constant, CombineSource::Previous],
            operand_rgb: [CombineOperand::OneMinusSrcAlpha, CombineOperand::SrcColor, CombineOperand::SrcAlpha],
            scale: [4.0, 2.0],
            ..TextureEnv::default()
        };
        let [w, alpha] = combine_words(&env);
        assert_eq!(COMBINE_FN.get(w), 7);
        assert_eq!([0, 1, 2].map(|i| SOURCE.nth(i).get(w)), [4, 5, 7]);
        assert_eq!([0, 1, 2].map(|i| OPERAND.nth(i).get(w)), [3, 0, 2]);
        assert_eq!((SCALE.get(w), SCALE.get(alpha)), (2, 1), "log2 of 4 and 2");
        assert_eq!(combine_words(&TextureEnv::default()), [0, 0], "combiner words only for COMBINE");
    }

    #[test]
    fn unit_bits_carry_format_and_function() {
        let content = TextureContent { kind: TextureKind::D2, format: TexelFormat::Intensity, ..TextureContent::default() };
        let unit = TextureUnit { env: TextureEnv { mode: EnvMode::Blend, ..TextureEnv::default() }, texgen: [None; 4] };
        let w = unit_bits(&unit, &content);
        assert_eq!((FORMAT.get(w), ENV.get(w)), (FORMAT_INTENSITY, ENV_BLEND));
    }
}
