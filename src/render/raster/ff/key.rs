//! The shader key: the part of a draw's state that selects code in `ff.vert`/`ff.frag`, as
//! [`WORDS`] specialisation constants. Each word holds bit fields
//! ([`Field`](crate::render::shader_abi::Field)s), declared once
//! in [`super::shader_interface`] and, for the texture environment's, in
//! [`crate::render::texenv::codes`]; the shaders read the same fields from the headers
//! generated from those modules.
//!
//! Words: [`GENERAL`] (primitive, shading, lighting model, fog, alpha test, stipples),
//! [`CLIP`] (user clip planes, radiosity's ambient term), `UNIT + u` (texture unit `u`: target, base format, function,
//! coordinate generation, depth texture comparison, point sprite coordinates), `COMBINE_RGB + u` and `COMBINE_ALPHA + u` (the
//! combiner of unit `u`, section 3.8.13).

use super::shader_interface::*;
use crate::frame::state::{ColorMaterialMode, CompareFunc, Face, FogMode, FogSource, ShadeModel};
use crate::frame::texture::{TexGenMode, TexelFormat, TextureKind};
use crate::frame::{Draw, TextureUnit};
use crate::render::texenv::{self, codes::MAX_UNITS};

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

/// What a batch rasterizes (value of [`PRIMITIVE`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u32)]
pub enum Primitive {
    /// Filled triangles.
    Triangle = PRIM_TRIANGLE,
    /// Lines expanded to quads on the CPU.
    Line = PRIM_LINE,
    /// Points expanded to quads on the CPU.
    Point = PRIM_POINT,
}

/// Which face's colours a batch uses (value of [`FACING`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u32)]
pub enum Facing {
    /// The rasterizer's facing (`gl_FrontFacing`): filled triangles.
    Rasterizer = FACING_RASTERIZER,
    /// Front colours: points, lines, and front faces converted on the CPU.
    Front = FACING_FRONT,
    /// Back colours: back faces converted on the CPU.
    Back = FACING_BACK,
}

/// The part of a draw's state that selects shader code: one `u32` per specialisation constant.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ShaderKey {
    /// Specialisation constant `i` is `words[i]`.
    pub words: [u32; WORDS],
}

impl ShaderKey {
    /// The key with [`RADIOSITY`] set to `on`.
    pub fn with_radiosity(mut self, on: bool) -> ShaderKey {
        RADIOSITY.set(&mut self.words[CLIP], on as u32);
        self
    }

    /// Whether the key reads only the primary colour and unit 0's coordinates of
    /// `ff_varyings.glsl`, so that the lean stages (`ff_lean.vert`, `ff_lean.frag`) can draw
    /// it: filled triangles, smooth shading, no GL fog, the back colours equal
    /// to the front ones (no two-sided lighting), a secondary colour that is zero or not
    /// summed (lighting without `GL_SEPARATE_SPECULAR_COLOR` makes it zero, section 2.14.1),
    /// units 1 to 3 unused. Each interpolated varying costs a CPU rasterizer per triangle
    /// (lavapipe's setup computes and stores its plane equations), which draws of this key,
    /// most of old games', skip.
    pub fn lean(&self) -> bool {
        let general = self.words[GENERAL];
        let lit = LIGHTING.get(general) != 0;
        let secondary_zero = lit && SEPARATE_SPECULAR.get(general) == 0;
        PRIMITIVE.get(general) == PRIM_TRIANGLE
            && FLAT.get(general) == 0
            && FOG.get(general) == 0
            && !(lit && TWO_SIDE.get(general) != 0)
            && (COLOR_SUM.get(general) == 0 || secondary_zero)
            && TEXCOORDS_UNUSED.get(self.words[CLIP]) & 0b1110 == 0b1110
    }
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
            [words[COMBINE_RGB + u], words[COMBINE_ALPHA + u]] = texenv::combine_words(&unit.env);
        } else if let Some(unit) = unit {
            // Enabled without a complete texture: no texturing (section 3.8.10), but the
            // coordinates are still generated (they are unused).
            words[UNIT + u] = texgen_bits(&unit);
        }
        if draw.program.is_none() && TARGET.get(words[UNIT + u]) == 0 {
            let unused = TEXCOORDS_UNUSED.get(words[CLIP]) | 1 << u;
            TEXCOORDS_UNUSED.set(&mut words[CLIP], unused);
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
        LIGHT_COUNT.set(&mut w, l.lights.len().min(MAX_LIGHTS) as u32);
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
        TEXGEN.nth(c as u32).set(&mut w, code);
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
    w |= texenv::unit_bits(unit, content);
    if content.format == TexelFormat::Depth {
        DEPTH.set(&mut w, content.sampler.compare.map_or(1, |f| 1 + compare_code(f)));
    }
    if content.kind != TextureKind::Cube {
        let axes = content.sampler.clamp_blends_border();
        CLAMP.set(&mut w, (0..3).filter(|&c| axes[c]).map(|c| 1 << c).sum());
    }
    w
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::frame::state::{Fog, Lighting, RasterState};
    use crate::frame::texture::{DepthMode, EnvMode, Sampler, TextureContent, TextureEnv};
    use crate::render::shader_abi::Field;
    use crate::frame::{TextureRef, TextureUnit};
    use crate::render::texenv::codes::{ENV, FORMAT};

    fn textured(format: TexelFormat, kind: TextureKind, env: TextureEnv) -> Draw {
        let content = TextureContent { kind, format, ..TextureContent::default() };
        Draw {
            textures: vec![None, Some(TextureRef { id: 1, version: 1, content: Arc::new(content) })],
            texture_units: vec![None, Some(TextureUnit { env, texgen: [None; 4] })],
            ..Draw::default()
        }
    }

    #[test]
    fn lean_keys_read_the_primary_colour_and_unit_0_of_smooth_triangles() {
        let key = |draw: &Draw, primitive| shader_key(draw, primitive, Facing::Rasterizer);
        let plain = Draw::default();
        assert!(key(&plain, Primitive::Triangle).lean(), "unlit, untextured triangles");
        assert!(!key(&plain, Primitive::Line).lean(), "expanded lines read v_raster");
        assert!(!key(&plain, Primitive::Point).lean());
        let flat = Draw { state: Arc::new(RasterState { shade_model: ShadeModel::Flat, ..RasterState::default() }), ..Draw::default() };
        assert!(!key(&flat, Primitive::Triangle).lean(), "flat shading reads the provoking colours");
        let summed = Draw { state: Arc::new(RasterState { color_sum: true, ..RasterState::default() }), ..Draw::default() };
        assert!(!key(&summed, Primitive::Triangle).lean(), "an unlit colour sum adds the secondary colour");
        let fogged = Draw { state: Arc::new(RasterState { fog: Some(Fog::default()), ..RasterState::default() }), ..Draw::default() };
        assert!(!key(&fogged, Primitive::Triangle).lean(), "GL fog reads the fog distance");
        let mut lighting = Lighting::default();
        let lit = |l: &Lighting| Draw { state: Arc::new(RasterState { lighting: Some(l.clone()), ..RasterState::default() }), ..Draw::default() };
        assert!(key(&lit(&lighting), Primitive::Triangle).lean(), "lit: the secondary colour is zero");
        lighting.model.separate_specular = true;
        assert!(!key(&lit(&lighting), Primitive::Triangle).lean(), "the specular colour is summed");
        lighting.model.separate_specular = false;
        lighting.model.two_side = true;
        assert!(!key(&lit(&lighting), Primitive::Triangle).lean(), "back faces have their own colours");
        let env = TextureEnv::default();
        assert!(!key(&textured(TexelFormat::Rgba, TextureKind::D2, env), Primitive::Triangle).lean(), "unit 1 textures");
    }

    #[test]
    fn fields_do_not_overlap_within_a_word() {
        let general = [
            PRIMITIVE, FLAT, FACING, LIGHTING, TWO_SIDE, LOCAL_VIEWER, SEPARATE_SPECULAR, COLOR_MATERIAL,
            COLOR_MATERIAL_FACES, NORMAL_SCALING, LIGHT_COUNT, COLOR_SUM, FOG, FOG_COORD, ALPHA_TEST,
            POLYGON_STIPPLE, LINE_STIPPLE, SMOOTH, SPRITE,
        ];
        let texgen_all = Field::new(TEXGEN.shift, 12);
        for word in [&general[..], &[TARGET, FORMAT, ENV, texgen_all, DEPTH, CLAMP, COORD_REPLACE, SPRITE_R]] {
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
        assert_eq!(TEXCOORDS_UNUSED.get(key.words[CLIP]), 0b1101, "only unit 1 reads its coordinates");
        // A program may read every unit's coordinates.
        let mut draw = textured(TexelFormat::Intensity, TextureKind::D3, env);
        let program = crate::frame::program::ShaderProgram { id: 1, vertex: None, fragment: None, samplers: Vec::new(), attributes: Vec::new() };
        draw.program = Some(Arc::new(crate::frame::program::ProgramDraw {
            program: Arc::new(program),
            builtins: Arc::from(Vec::new()),
            uniforms: Arc::from(Vec::new()),
            textures: Vec::new(),
            point_size_from_shader: false,
            two_side: false,
        }));
        assert_eq!(TEXCOORDS_UNUSED.get(shader_key(&draw, Primitive::Triangle, Facing::Front).words[CLIP]), 0);
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
    fn combiner_words_follow_the_unit_words() {
        let env = TextureEnv { mode: EnvMode::Combine, scale: [4.0, 2.0], ..TextureEnv::default() };
        let key = shader_key(&textured(TexelFormat::Rgba, TextureKind::D2, env), Primitive::Triangle, Facing::Front);
        assert_eq!([key.words[COMBINE_RGB + 1], key.words[COMBINE_ALPHA + 1]], texenv::combine_words(&env));
        assert_ne!(key.words[COMBINE_RGB + 1], 0);
        assert_eq!(key.words[COMBINE_RGB], 0, "unit 0 has no texture");
    }

    #[test]
    fn texgen_modes_per_coordinate() {
        let unit = TextureUnit {
            texgen: [Some(TexGenMode::SphereMap), None, Some(TexGenMode::EyeLinear([0.0; 4])), Some(TexGenMode::ReflectionMap)],
            ..TextureUnit::default()
        };
        let w = texgen_bits(&unit);
        let mode = |c: u32| TEXGEN.nth(c).get(w);
        assert_eq!([mode(0), mode(1), mode(2), mode(3)], [3, 0, 2, 5]);
    }
}
