//! The words `shaders/texenv.glsl` evaluates, shared with GLSL as `generated/texenv_codes.glsl`
//! (see [`crate::render::shader_abi`]): where the base format and the texture function sit in
//! a unit's word, the fields of a combiner word, and the codes of each.
//!
//! The fixed-function shaders read these words as specialisation constants (the unit words of
//! `ff::key`, whose other fields are `ff::shader_interface`); the tracer reads them from its
//! materials (`trace::scene`).

glsl_constants! {
    /// Texture units of the fixed-function shaders and of the combiner's crossbar.
    const MAX_UNITS: usize = 4;

    /// Base format as the environment sees it (OpenGL 1.5 table 3.22; depth textures by their
    /// `DEPTH_TEXTURE_MODE`): `GL_ALPHA`.
    const FORMAT_ALPHA: u32 = 0;
    /// `GL_LUMINANCE`.
    const FORMAT_LUMINANCE: u32 = 1;
    /// `GL_LUMINANCE_ALPHA`.
    const FORMAT_LUMINANCE_ALPHA: u32 = 2;
    /// `GL_INTENSITY`.
    const FORMAT_INTENSITY: u32 = 3;
    /// `GL_RGB` (and one- and two-component colour formats).
    const FORMAT_RGB: u32 = 4;
    /// `GL_RGBA`.
    const FORMAT_RGBA: u32 = 5;

    /// Texture function (`GL_TEXTURE_ENV_MODE`): `GL_MODULATE`.
    const ENV_MODULATE: u32 = 0;
    /// `GL_REPLACE`.
    const ENV_REPLACE: u32 = 1;
    /// `GL_DECAL`.
    const ENV_DECAL: u32 = 2;
    /// `GL_BLEND`.
    const ENV_BLEND: u32 = 3;
    /// `GL_ADD`.
    const ENV_ADD: u32 = 4;
    /// `GL_COMBINE`: the unit's combiner words say what it computes.
    const ENV_COMBINE: u32 = 5;

    /// Combiner function (`GL_COMBINE_RGB`, `GL_COMBINE_ALPHA`, table 3.23): `GL_REPLACE`.
    const COMBINE_REPLACE: u32 = 0;
    /// `GL_MODULATE`.
    const COMBINE_MODULATE: u32 = 1;
    /// `GL_ADD`.
    const COMBINE_ADD: u32 = 2;
    /// `GL_ADD_SIGNED`.
    const COMBINE_ADD_SIGNED: u32 = 3;
    /// `GL_INTERPOLATE`.
    const COMBINE_INTERPOLATE: u32 = 4;
    /// `GL_SUBTRACT`.
    const COMBINE_SUBTRACT: u32 = 5;
    /// `GL_DOT3_RGB` (RGB only).
    const COMBINE_DOT3_RGB: u32 = 6;
    /// `GL_DOT3_RGBA` (RGB only; the result's red is also its alpha).
    const COMBINE_DOT3_RGBA: u32 = 7;

    /// Combiner argument source (`GL_SOURCEi_RGB`, table 3.24): `GL_TEXTURE`, the unit's own.
    const SOURCE_TEXTURE: u32 = 0;
    /// `GL_TEXTURE0` (ARB_texture_env_crossbar); unit `n` is `SOURCE_TEXTURE0 + n`.
    const SOURCE_TEXTURE0: u32 = 1;
    /// `GL_CONSTANT`: the unit's `GL_TEXTURE_ENV_COLOR`.
    const SOURCE_CONSTANT: u32 = SOURCE_TEXTURE0 + MAX_UNITS as u32;
    /// `GL_PRIMARY_COLOR`.
    const SOURCE_PRIMARY_COLOR: u32 = SOURCE_CONSTANT + 1;
    /// `GL_PREVIOUS`: the previous unit's result (the primary colour at the first unit).
    const SOURCE_PREVIOUS: u32 = SOURCE_CONSTANT + 2;

    /// Combiner operand (`GL_OPERANDi_RGB`, tables 3.25 and 3.26): `GL_SRC_COLOR`.
    const OPERAND_SRC_COLOR: u32 = 0;
    /// `GL_ONE_MINUS_SRC_COLOR`.
    const OPERAND_ONE_MINUS_SRC_COLOR: u32 = 1;
    /// `GL_SRC_ALPHA`.
    const OPERAND_SRC_ALPHA: u32 = 2;
    /// `GL_ONE_MINUS_SRC_ALPHA`.
    const OPERAND_ONE_MINUS_SRC_ALPHA: u32 = 3;
}

glsl_fields! {
    /// Unit word: base format, `FORMAT_*`.
    FORMAT = (3, 3);
    /// Unit word: texture function, `ENV_*`.
    ENV = (6, 3);
    /// Combiner word: function, `COMBINE_*`.
    COMBINE_FN = (0, 3);
    /// Combiner word: source of argument `i` (`SOURCE_*`) at `SOURCE_SHIFT + 3 i`.
    SOURCE = (3, 3);
    /// Combiner word: operand of argument `i` (`OPERAND_*`) at `OPERAND_SHIFT + 2 i`.
    OPERAND = (12, 2);
    /// Combiner word: log2 of the scale (`GL_RGB_SCALE`, `GL_ALPHA_SCALE`: 1, 2 or 4).
    SCALE = (18, 2);
}
