//! The shader key: the part of a draw's state that selects code in `ff.vert`/`ff.frag`, as
//! [`WORDS`] specialisation constants. Each word holds bit fields ([`Field`]); the same
//! fields are declared in `shaders/ff_key.glsl` (`<NAME>_SHIFT`, `<NAME>_BITS`), and a test
//! reads that file back and compares it with [`GLSL_FIELDS`].
//!
//! Words: [`GENERAL`] (primitive, shading, lighting model, fog, alpha test, stipples),
//! [`CLIP`] (user clip planes), `UNIT + u` (texture unit `u`: target, base format, function,
//! coordinate generation, depth texture comparison, point sprite coordinates), `COMBINE_RGB + u` and `COMBINE_ALPHA + u` (the
//! combiner of unit `u`, section 3.8.13).

use super::MAX_UNITS;
use crate::frame::state::{ColorMaterialMode, CompareFunc, Face, FogMode, FogSource, ShadeModel};
use crate::frame::texture::{
    CombineFn, CombineOperand, CombineSource, DepthMode, EnvMode, TexGenMode, TexelFormat, TextureKind,
};
use crate::frame::{Draw, TextureUnit};

/// Number of key words (specialisation constants 0 to `WORDS - 1`).
pub const WORDS: usize = 2 + 3 * MAX_UNITS;
/// Word of the general fields.
pub const GENERAL: usize = 0;
/// Word of the clip plane mask.
pub const CLIP: usize = 1;
/// First of the [`MAX_UNITS`] texture unit words.
pub const UNIT: usize = 2;
/// First of the [`MAX_UNITS`] RGB combiner words.
pub const COMBINE_RGB: usize = UNIT + MAX_UNITS;
/// First of the [`MAX_UNITS`] alpha combiner words.
pub const COMBINE_ALPHA: usize = COMBINE_RGB + MAX_UNITS;

/// A bit field of a key word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    /// Lowest bit.
    pub shift: u32,
    /// Width in bits.
    pub bits: u32,
}

impl Field {
    const fn new(shift: u32, bits: u32) -> Field {
        Field { shift, bits }
    }

    /// `word` with this field set to `value` (which must fit).
    pub fn set(self, word: &mut u32, value: u32) {
        debug_assert!(value < 1 << self.bits, "{value} does not fit in {} bits", self.bits);
        *word |= (value & ((1 << self.bits) - 1)) << self.shift;
    }

    /// The value of this field in `word`.
    pub fn get(self, word: u32) -> u32 {
        (word >> self.shift) & ((1 << self.bits) - 1)
    }
}

/// What the batch rasterizes: [`Primitive::Triangle`] (0), expanded lines (1) or expanded
/// points (2); see [`super::convert`].
pub const PRIMITIVE: Field = Field::new(0, 2);
/// Flat shading: the fragment stage reads the provoking vertex's colours.
pub const FLAT: Field = Field::new(2, 1);
/// Which colours the fragment stage uses: 0 by `gl_FrontFacing`, 1 front, 2 back.
pub const FACING: Field = Field::new(3, 2);
/// `GL_LIGHTING`.
pub const LIGHTING: Field = Field::new(5, 1);
/// `GL_LIGHT_MODEL_TWO_SIDE`.
pub const TWO_SIDE: Field = Field::new(6, 1);
/// `GL_LIGHT_MODEL_LOCAL_VIEWER`.
pub const LOCAL_VIEWER: Field = Field::new(7, 1);
/// `GL_SEPARATE_SPECULAR_COLOR`.
pub const SEPARATE_SPECULAR: Field = Field::new(8, 1);
/// Colour material: 0 off, else 1 + [`ColorMaterialMode`] (emission, ambient, diffuse,
/// specular, ambient and diffuse).
pub const COLOR_MATERIAL: Field = Field::new(9, 3);
/// Colour material faces: bit 0 front, bit 1 back.
pub const COLOR_MATERIAL_FACES: Field = Field::new(12, 2);
/// Normal scaling: 0 none, 1 `GL_NORMALIZE`, 2 `GL_RESCALE_NORMAL`.
pub const NORMAL_SCALING: Field = Field::new(14, 2);
/// Number of enabled lights (packed first in the uniform block).
pub const LIGHT_COUNT: Field = Field::new(16, 4);
/// The colour sum is applied (section 3.9).
pub const COLOR_SUM: Field = Field::new(20, 1);
/// Fog: 0 off, 1 linear, 2 exp, 3 exp2.
pub const FOG: Field = Field::new(21, 2);
/// Fog distance from the fog coordinate instead of the eye depth.
pub const FOG_COORD: Field = Field::new(23, 1);
/// Alpha test: 0 off, else 1 + [`CompareFunc`] (never, less, equal, lequal, greater,
/// notequal, gequal, always).
pub const ALPHA_TEST: Field = Field::new(24, 4);
/// `GL_POLYGON_STIPPLE` (triangles only).
pub const POLYGON_STIPPLE: Field = Field::new(28, 1);
/// `GL_LINE_STIPPLE` (lines only).
pub const LINE_STIPPLE: Field = Field::new(29, 1);
/// Antialiasing of points (`GL_POINT_SMOOTH`) or lines (`GL_LINE_SMOOTH`): coverage to alpha.
pub const SMOOTH: Field = Field::new(30, 1);
/// Points are point sprites (`GL_POINT_SPRITE`, points only): squares of the unrounded size
/// at the exact position.
pub const SPRITE: Field = Field::new(31, 1);

/// Word [`CLIP`]: bit `i` set when the `i`-th packed clip plane is enabled.
pub const CLIP_MASK: Field = Field::new(0, 6);

/// Unit word: 0 no texturing, 1 1D, 2 2D, 3 3D, 4 cube map, 5 rectangle (coordinates in
/// texels).
pub const TARGET: Field = Field::new(0, 3);
/// Unit word: base format as the environment sees it: 0 alpha, 1 luminance, 2 luminance
/// alpha, 3 intensity, 4 RGB, 5 RGBA (depth textures by their `DEPTH_TEXTURE_MODE`).
pub const FORMAT: Field = Field::new(3, 3);
/// Unit word: texture function: 0 modulate, 1 replace, 2 decal, 3 blend, 4 add, 5 combine.
pub const ENV: Field = Field::new(6, 3);
/// Unit word: generation of coordinate `c` (s, t, r, q) at `TEXGEN.shift + 3 c`: 0 none,
/// 1 object linear, 2 eye linear, 3 sphere map, 4 normal map, 5 reflection map.
pub const TEXGEN: Field = Field::new(9, 3);
/// Unit word: 0 a colour texture, 1 a depth texture (expanded by its `DEPTH_TEXTURE_MODE`,
/// see [`FORMAT`]), 2 + [`CompareFunc`] a depth texture compared with r (section 3.8.14).
pub const DEPTH: Field = Field::new(21, 4);
/// Unit word: bit `c` set when coordinate `c` (s, t, r) is clamped to [0, 1] before sampling
/// (`GL_CLAMP` with a linear filter, [`crate::frame::texture::Sampler::clamp_blends_border`]).
pub const CLAMP: Field = Field::new(25, 3);
/// Unit word: point sprite coordinate replacement (`GL_COORD_REPLACE`, points only): 0 off,
/// 1 with t from 0 at the top (`GL_UPPER_LEFT`), 2 with t from 0 at the bottom
/// (`GL_LOWER_LEFT`).
pub const COORD_REPLACE: Field = Field::new(28, 2);
/// Unit word: the replaced r coordinate of a point sprite (`GL_POINT_SPRITE_R_MODE_NV`): 0 zero,
/// 1 the vertex's s / q, 2 its r / q.
pub const SPRITE_R: Field = Field::new(30, 2);

/// Combiner word: function (replace, modulate, add, add signed, interpolate, subtract,
/// dot3 RGB, dot3 RGBA).
pub const COMBINE_FN: Field = Field::new(0, 3);
/// Combiner word: source of argument `i` at `SOURCE.shift + 3 i`: 0 this unit's texture,
/// 1 + n texture unit n, 5 constant, 6 primary colour, 7 previous.
pub const SOURCE: Field = Field::new(3, 3);
/// Combiner word: operand of argument `i` at `OPERAND.shift + 2 i`: 0 colour, 1 one minus
/// colour, 2 alpha, 3 one minus alpha.
pub const OPERAND: Field = Field::new(12, 2);
/// Combiner word: log2 of the scale (0, 1, 2).
pub const SCALE: Field = Field::new(18, 2);

/// Every field with its name in `shaders/ff_key.glsl`.
pub const GLSL_FIELDS: &[(&str, Field)] = &[
    ("PRIMITIVE", PRIMITIVE),
    ("FLAT", FLAT),
    ("FACING", FACING),
    ("LIGHTING", LIGHTING),
    ("TWO_SIDE", TWO_SIDE),
    ("LOCAL_VIEWER", LOCAL_VIEWER),
    ("SEPARATE_SPECULAR", SEPARATE_SPECULAR),
    ("COLOR_MATERIAL", COLOR_MATERIAL),
    ("COLOR_MATERIAL_FACES", COLOR_MATERIAL_FACES),
    ("NORMAL_SCALING", NORMAL_SCALING),
    ("LIGHT_COUNT", LIGHT_COUNT),
    ("COLOR_SUM", COLOR_SUM),
    ("FOG", FOG),
    ("FOG_COORD", FOG_COORD),
    ("ALPHA_TEST", ALPHA_TEST),
    ("POLYGON_STIPPLE", POLYGON_STIPPLE),
    ("LINE_STIPPLE", LINE_STIPPLE),
    ("SMOOTH", SMOOTH),
    ("SPRITE", SPRITE),
    ("CLIP_MASK", CLIP_MASK),
    ("TARGET", TARGET),
    ("FORMAT", FORMAT),
    ("ENV", ENV),
    ("TEXGEN", TEXGEN),
    ("CLAMP", CLAMP),
    ("DEPTH", DEPTH),
    ("COORD_REPLACE", COORD_REPLACE),
    ("SPRITE_R", SPRITE_R),
    ("COMBINE_FN", COMBINE_FN),
    ("SOURCE", SOURCE),
    ("OPERAND", OPERAND),
    ("SCALE", SCALE),
];

/// What a batch rasterizes (value of [`PRIMITIVE`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Primitive {
    /// Filled triangles.
    Triangle = 0,
    /// Lines expanded to quads on the CPU.
    Line = 1,
    /// Points expanded to quads on the CPU.
    Point = 2,
}

/// Which face's colours a batch uses (value of [`FACING`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Facing {
    /// The rasterizer's facing (`gl_FrontFacing`): filled triangles.
    Rasterizer = 0,
    /// Front colours: points, lines, and front faces converted on the CPU.
    Front = 1,
    /// Back colours: back faces converted on the CPU.
    Back = 2,
}

/// The part of a draw's state that selects shader code: one `u32` per specialisation constant.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ShaderKey {
    /// Specialisation constant `i` is `words[i]`.
    pub words: [u32; WORDS],
}

/// `1 +` the index of `func` in the order of the GL enums (`GL_NEVER` + i).
fn compare_code(func: CompareFunc) -> u32 {
    1 + match func {
        CompareFunc::Never => 0,
        CompareFunc::Less => 1,
        CompareFunc::Equal => 2,
        CompareFunc::LessEqual => 3,
        CompareFunc::Greater => 4,
        CompareFunc::NotEqual => 5,
        CompareFunc::GreaterEqual => 6,
        CompareFunc::Always => 7,
    }
}

/// The key of `draw` rasterized as `primitive` with the colours of `facing`.
pub fn shader_key(draw: &Draw, primitive: Primitive, facing: Facing) -> ShaderKey {
    let mut words = [0; WORDS];
    words[GENERAL] = general_word(draw, primitive, facing);
    CLIP_MASK.set(&mut words[CLIP], (1 << draw.state.clip_planes.len().min(6)) - 1);
    for u in 0..MAX_UNITS {
        let unit = draw.texture_units.get(u).copied().flatten();
        let texture = draw.textures.get(u).and_then(|t| t.as_ref());
        if let (Some(unit), Some(texture)) = (unit, texture) {
            words[UNIT + u] = unit_word(&unit, &texture.content);
            if let Some(sprite) = draw.state.point.sprite.filter(|s| primitive == Primitive::Point && s.coord_replace & (1 << u) != 0) {
                COORD_REPLACE.set(&mut words[UNIT + u], 1 + sprite.lower_left as u32);
                SPRITE_R.set(&mut words[UNIT + u], sprite.r as u32);
            }
            if unit.env.mode == EnvMode::Combine {
                let env = &unit.env;
                words[COMBINE_RGB + u] = combine_word(env.combine_rgb, env.source_rgb, env.operand_rgb, env.scale[0]);
                words[COMBINE_ALPHA + u] =
                    combine_word(env.combine_alpha, env.source_alpha, env.operand_alpha, env.scale[1]);
            }
        } else if let Some(unit) = unit {
            // Enabled without a complete texture: no texturing (section 3.8.10), but the
            // coordinates are still generated (they are unused).
            words[UNIT + u] = texgen_bits(&unit);
        }
    }
    ShaderKey { words }
}

/// Word [`GENERAL`].
fn general_word(draw: &Draw, primitive: Primitive, facing: Facing) -> u32 {
    let s = &draw.state;
    let mut w = 0;
    PRIMITIVE.set(&mut w, primitive as u32);
    FLAT.set(&mut w, (s.shade_model == ShadeModel::Flat) as u32);
    FACING.set(&mut w, facing as u32);
    if let Some(l) = &s.lighting {
        LIGHTING.set(&mut w, 1);
        TWO_SIDE.set(&mut w, l.model.two_side as u32);
        LOCAL_VIEWER.set(&mut w, l.model.local_viewer as u32);
        SEPARATE_SPECULAR.set(&mut w, l.model.separate_specular as u32);
        if let Some(cm) = l.color_material {
            let mode = match cm.mode {
                ColorMaterialMode::Emission => 1,
                ColorMaterialMode::Ambient => 2,
                ColorMaterialMode::Diffuse => 3,
                ColorMaterialMode::Specular => 4,
                ColorMaterialMode::AmbientAndDiffuse => 5,
            };
            COLOR_MATERIAL.set(&mut w, mode);
            let faces = match cm.face {
                Face::Front => 1,
                Face::Back => 2,
                Face::FrontAndBack => 3,
            };
            COLOR_MATERIAL_FACES.set(&mut w, faces);
        }
        LIGHT_COUNT.set(&mut w, l.lights.len().min(super::uniforms::MAX_LIGHTS) as u32);
    }
    NORMAL_SCALING.set(&mut w, if s.normalize { 1 } else if s.rescale_normal { 2 } else { 0 });
    // Section 3.9: with lighting on, the colour sum applies whatever COLOR_SUM says.
    COLOR_SUM.set(&mut w, (s.color_sum || s.lighting.is_some()) as u32);
    if let Some(fog) = &s.fog {
        FOG.set(
            &mut w,
            match fog.mode {
                FogMode::Linear => 1,
                FogMode::Exp => 2,
                FogMode::Exp2 => 3,
            },
        );
        FOG_COORD.set(&mut w, (fog.source == FogSource::FogCoord) as u32);
    }
    if let Some((func, _)) = s.alpha_test {
        ALPHA_TEST.set(&mut w, compare_code(func));
    }
    match primitive {
        Primitive::Triangle => POLYGON_STIPPLE.set(&mut w, s.polygon_stipple.is_some() as u32),
        Primitive::Line => {
            LINE_STIPPLE.set(&mut w, s.line.stipple.is_some() as u32);
            SMOOTH.set(&mut w, s.line.smooth as u32);
        }
        Primitive::Point => {
            SMOOTH.set(&mut w, s.point.smooth as u32);
            SPRITE.set(&mut w, s.point.sprite.is_some() as u32);
        }
    }
    w
}

/// The texture coordinate generation bits of a unit word.
fn texgen_bits(unit: &TextureUnit) -> u32 {
    let mut w = 0;
    for (c, mode) in unit.texgen.iter().enumerate() {
        let code = match mode {
            None => 0,
            Some(TexGenMode::ObjectLinear(_)) => 1,
            Some(TexGenMode::EyeLinear(_)) => 2,
            Some(TexGenMode::SphereMap) => 3,
            Some(TexGenMode::NormalMap) => 4,
            Some(TexGenMode::ReflectionMap) => 5,
        };
        Field::new(TEXGEN.shift + 3 * c as u32, 3).set(&mut w, code);
    }
    w
}

/// Word `UNIT + u` of a unit that textures with `content`.
fn unit_word(unit: &TextureUnit, content: &crate::frame::texture::TextureContent) -> u32 {
    let mut w = texgen_bits(unit);
    TARGET.set(
        &mut w,
        match content.kind {
            TextureKind::D1 => 1,
            TextureKind::D2 => 2,
            TextureKind::D3 => 3,
            TextureKind::Cube => 4,
            TextureKind::Rect => 5,
        },
    );
    let format = match content.format {
        TexelFormat::Alpha => 0,
        TexelFormat::Luminance => 1,
        TexelFormat::LuminanceAlpha => 2,
        TexelFormat::Intensity => 3,
        TexelFormat::Rgb | TexelFormat::Red | TexelFormat::Rg => 4,
        TexelFormat::Rgba => 5,
        TexelFormat::Depth => match content.sampler.depth_mode {
            DepthMode::Alpha => 0,
            DepthMode::Luminance => 1,
            DepthMode::Intensity => 3,
        },
    };
    FORMAT.set(&mut w, format);
    ENV.set(
        &mut w,
        match unit.env.mode {
            EnvMode::Modulate => 0,
            EnvMode::Replace => 1,
            EnvMode::Decal => 2,
            EnvMode::Blend => 3,
            EnvMode::Add => 4,
            EnvMode::Combine => 5,
        },
    );
    if content.format == TexelFormat::Depth {
        DEPTH.set(&mut w, content.sampler.compare.map_or(1, |f| 1 + compare_code(f)));
    }
    if content.kind != TextureKind::Cube {
        let axes = content.sampler.clamp_blends_border();
        CLAMP.set(&mut w, (0..3).filter(|&c| axes[c]).map(|c| 1 << c).sum());
    }
    w
}

/// A combiner word (section 3.8.13, tables 3.24 to 3.26).
fn combine_word(f: CombineFn, sources: [CombineSource; 3], operands: [CombineOperand; 3], scale: f32) -> u32 {
    let mut w = 0;
    COMBINE_FN.set(
        &mut w,
        match f {
            CombineFn::Replace => 0,
            CombineFn::Modulate => 1,
            CombineFn::Add => 2,
            CombineFn::AddSigned => 3,
            CombineFn::Interpolate => 4,
            CombineFn::Subtract => 5,
            CombineFn::Dot3Rgb => 6,
            CombineFn::Dot3Rgba => 7,
        },
    );
    for i in 0..3 {
        let source = match sources[i] {
            CombineSource::Texture => 0,
            CombineSource::TextureUnit(n) if (n as usize) < MAX_UNITS => 1 + n as u32,
            // A unit the shaders do not have: its texture is undefined; use this unit's.
            CombineSource::TextureUnit(_) => 0,
            CombineSource::Constant => 5,
            CombineSource::PrimaryColor => 6,
            CombineSource::Previous => 7,
        };
        Field::new(SOURCE.shift + 3 * i as u32, 3).set(&mut w, source);
        let operand = match operands[i] {
            CombineOperand::SrcColor => 0,
            CombineOperand::OneMinusSrcColor => 1,
            CombineOperand::SrcAlpha => 2,
            CombineOperand::OneMinusSrcAlpha => 3,
        };
        Field::new(OPERAND.shift + 2 * i as u32, 2).set(&mut w, operand);
    }
    SCALE.set(&mut w, if scale >= 4.0 { 2 } else if scale >= 2.0 { 1 } else { 0 });
    w
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::frame::state::{Fog, Lighting, RasterState};
    use crate::frame::texture::{Sampler, TextureContent, TextureEnv};
    use crate::frame::{TextureRef, TextureUnit};

    fn textured(format: TexelFormat, kind: TextureKind, env: TextureEnv) -> Draw {
        let content = TextureContent { kind, format, ..TextureContent::default() };
        Draw {
            textures: vec![None, Some(TextureRef { id: 1, version: 1, content: Arc::new(content) })],
            texture_units: vec![None, Some(TextureUnit { env, texgen: [None; 4] })],
            ..Draw::default()
        }
    }

    #[test]
    fn fields_do_not_overlap_within_a_word() {
        let general = [
            PRIMITIVE, FLAT, FACING, LIGHTING, TWO_SIDE, LOCAL_VIEWER, SEPARATE_SPECULAR, COLOR_MATERIAL,
            COLOR_MATERIAL_FACES, NORMAL_SCALING, LIGHT_COUNT, COLOR_SUM, FOG, FOG_COORD, ALPHA_TEST,
            POLYGON_STIPPLE, LINE_STIPPLE, SMOOTH,
        ];
        let texgen_all = Field::new(TEXGEN.shift, 12);
        let combine = [COMBINE_FN, Field::new(SOURCE.shift, 9), Field::new(OPERAND.shift, 6), SCALE];
        for word in [&general[..], &[TARGET, FORMAT, ENV, texgen_all, DEPTH], &combine] {
            let mut used = 0u64;
            for f in word {
                let mask = ((1u64 << f.bits) - 1) << f.shift;
                assert_eq!(used & mask, 0, "{f:?} overlaps");
                assert!(f.shift + f.bits <= 32, "{f:?} past bit 31");
                used |= mask;
            }
        }
    }

    #[test]
    fn general_word_of_a_lit_fogged_alpha_tested_draw() {
        let state = RasterState {
            lighting: Some(Lighting {
                lights: vec![(0, crate::frame::state::Light::initial(0)), (3, crate::frame::state::Light::initial(3))],
                color_material: Some(crate::frame::state::ColorMaterial::default()),
                ..Lighting::default()
            }),
            fog: Some(Fog { mode: FogMode::Exp2, source: FogSource::FogCoord, ..Fog::default() }),
            alpha_test: Some((CompareFunc::Greater, 0.5)),
            shade_model: ShadeModel::Flat,
            rescale_normal: true,
            polygon_stipple: Some([0; 32]),
            ..RasterState::default()
        };
        let draw = Draw { state: Arc::new(state), ..Draw::default() };
        let w = shader_key(&draw, Primitive::Triangle, Facing::Rasterizer).words[GENERAL];
        assert_eq!(LIGHTING.get(w), 1);
        assert_eq!(LIGHT_COUNT.get(w), 2);
        assert_eq!(COLOR_MATERIAL.get(w), 5, "ambient and diffuse");
        assert_eq!(COLOR_MATERIAL_FACES.get(w), 3);
        assert_eq!(COLOR_SUM.get(w), 1, "lighting forces the colour sum");
        assert_eq!(FOG.get(w), 3);
        assert_eq!(FOG_COORD.get(w), 1);
        assert_eq!(ALPHA_TEST.get(w), 5, "GL_GREATER is GL_NEVER + 4");
        assert_eq!(FLAT.get(w), 1);
        assert_eq!(NORMAL_SCALING.get(w), 2);
        assert_eq!(POLYGON_STIPPLE.get(w), 1);
        // The polygon stipple does not apply to lines.
        let w = shader_key(&draw, Primitive::Line, Facing::Back).words[GENERAL];
        assert_eq!((POLYGON_STIPPLE.get(w), PRIMITIVE.get(w), FACING.get(w)), (0, 1, 2));
    }

    #[test]
    fn unit_word_carries_target_format_and_function() {
        let env = TextureEnv { mode: EnvMode::Blend, ..TextureEnv::default() };
        let key = shader_key(&textured(TexelFormat::Intensity, TextureKind::D3, env), Primitive::Triangle, Facing::Front);
        assert_eq!(key.words[UNIT], 0, "unit 0 has no texture");
        let w = key.words[UNIT + 1];
        assert_eq!((TARGET.get(w), FORMAT.get(w), ENV.get(w)), (3, 3, 3));
        assert_eq!(key.words[COMBINE_RGB + 1], 0, "combiner words only for COMBINE");
    }

    #[test]
    fn depth_textures_take_their_depth_mode_and_comparison() {
        let mut draw = textured(TexelFormat::Depth, TextureKind::D2, TextureEnv::default());
        let content = TextureContent {
            kind: TextureKind::D2,
            format: TexelFormat::Depth,
            sampler: Sampler { compare: Some(CompareFunc::LessEqual), depth_mode: DepthMode::Intensity, ..Sampler::default() },
            ..TextureContent::default()
        };
        draw.textures[1] = Some(TextureRef { id: 2, version: 2, content: Arc::new(content) });
        let w = shader_key(&draw, Primitive::Triangle, Facing::Front).words[UNIT + 1];
        assert_eq!((FORMAT.get(w), DEPTH.get(w)), (3, 5), "GL_LEQUAL is GL_NEVER + 3");
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
        let key = shader_key(&textured(TexelFormat::Rgba, TextureKind::D2, env), Primitive::Triangle, Facing::Front);
        let w = key.words[COMBINE_RGB + 1];
        assert_eq!(COMBINE_FN.get(w), 7);
        let source = |i: u32| Field::new(SOURCE.shift + 3 * i, 3).get(w);
        let operand = |i: u32| Field::new(OPERAND.shift + 2 * i, 2).get(w);
        assert_eq!([source(0), source(1), source(2)], [4, 5, 7]);
        assert_eq!([operand(0), operand(1), operand(2)], [3, 0, 2]);
        assert_eq!(SCALE.get(w), 2);
        assert_eq!(SCALE.get(key.words[COMBINE_ALPHA + 1]), 1);
    }

    #[test]
    fn texgen_modes_per_coordinate() {
        let unit = TextureUnit {
            texgen: [Some(TexGenMode::SphereMap), None, Some(TexGenMode::EyeLinear([0.0; 4])), Some(TexGenMode::ReflectionMap)],
            ..TextureUnit::default()
        };
        let w = texgen_bits(&unit);
        let mode = |c: u32| Field::new(TEXGEN.shift + 3 * c, 3).get(w);
        assert_eq!([mode(0), mode(1), mode(2), mode(3)], [3, 0, 2, 5]);
    }

    #[test]
    fn glsl_declares_the_same_fields() {
        let glsl = include_str!("../../../../shaders/ff_key.glsl");
        let constant = |name: &str| -> u32 {
            let decl = format!("const uint {name} = ");
            let start = glsl.find(&decl).unwrap_or_else(|| panic!("{name} missing in ff_key.glsl")) + decl.len();
            let end = start + glsl[start..].find('u').expect("uint literal");
            glsl[start..end].trim().parse().expect("a number")
        };
        for (name, field) in GLSL_FIELDS {
            assert_eq!(constant(&format!("{name}_SHIFT")), field.shift, "{name}_SHIFT");
            assert_eq!(constant(&format!("{name}_BITS")), field.bits, "{name}_BITS");
        }
        assert_eq!(constant("KEY_WORDS"), WORDS as u32);
    }
}
