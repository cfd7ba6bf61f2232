//! Quake 3's shaders, written as a `.shader` script would give them (stages of texture,
//! blending, colour and texture-coordinate generation) and prepared as `tr_shader.c` prepares
//! them: the first two stages are collapsed onto two texture units when the second multiplies
//! the first (`CollapseMultitexture`: base × lightmap in one pass, `GL_MODULATE` on unit 1),
//! and each shader gets the stage iterator of `tr_shade.c` that fits it
//! (`ComputeStageIteratorFunc`). Shaders are sorted by their sort value, then by registration
//! order, which orders the frame's batches.

use crate::gl::*;

/// Blending and depth state of a stage (Q3's `GLS_*` state bits).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct StateBits {
    /// `glBlendFunc(src, dst)`, or blending off.
    pub blend: Option<(GLenum, GLenum)>,
    pub depth_write: bool,
    pub depth_test: bool,
    /// `glDepthFunc(GL_EQUAL)` instead of `GL_LEQUAL`.
    pub depth_equal: bool,
}

impl StateBits {
    /// `GLS_DEFAULT`: opaque, depth test and writes on.
    pub const DEFAULT: StateBits = StateBits { blend: None, depth_write: true, depth_test: true, depth_equal: false };
    /// `GL_State(0)`: depth test on, writes off, opaque (the sky box).
    pub const NO_DEPTH_WRITE: StateBits = StateBits { depth_write: false, ..StateBits::DEFAULT };

    /// A blended stage: `blendFunc src dst`, depth writes off (Q3's default for blending).
    pub const fn blended(src: GLenum, dst: GLenum) -> StateBits {
        StateBits { blend: Some((src, dst)), depth_write: false, depth_test: true, depth_equal: false }
    }

    /// `blendFunc filter`: the destination times the source.
    pub const FILTER: StateBits = StateBits::blended(GL_DST_COLOR, GL_ZERO);
    /// `blendFunc add`.
    pub const ADD: StateBits = StateBits::blended(GL_ONE, GL_ONE);
    /// `blendFunc blend`: alpha blending.
    pub const BLEND: StateBits = StateBits::blended(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    /// A detail texture: 2 × source × destination.
    pub const DETAIL: StateBits = StateBits::blended(GL_DST_COLOR, GL_SRC_COLOR);
    /// 2D pictures: alpha blended, no depth test.
    pub const PICTURE: StateBits = StateBits { depth_test: false, ..StateBits::BLEND };

    /// With `depthFunc equal`.
    pub const fn equal(self) -> StateBits {
        StateBits { depth_equal: true, ..self }
    }
}

/// Where a bundle's texture coordinates come from (`tcGen`).
#[derive(Clone, Copy, PartialEq, Debug)]
pub enum TcGen {
    /// The surface's texture coordinates.
    Texture,
    /// The surface's lightmap coordinates.
    Lightmap,
}

/// `tcMod`.
#[derive(Clone, Copy, PartialEq, Debug)]
pub enum TcMod {
    None,
    /// Multiplies s and t.
    Scale(f32, f32),
    /// Adds s and t per second (wrapped to 0..1).
    Scroll(f32, f32),
}

/// A texture and its coordinates (`textureBundle_t`).
#[derive(Clone, Copy, PartialEq, Debug)]
pub struct Bundle {
    pub image: GLuint,
    pub tc_gen: TcGen,
    pub tc_mod: TcMod,
}

impl Bundle {
    /// `map image` with the surface's texture coordinates.
    pub const fn map(image: GLuint) -> Bundle {
        Bundle { image, tc_gen: TcGen::Texture, tc_mod: TcMod::None }
    }

    /// `map $lightmap` (page `image`).
    pub const fn lightmap(image: GLuint) -> Bundle {
        Bundle { image, tc_gen: TcGen::Lightmap, tc_mod: TcMod::None }
    }

    /// With `tcMod`.
    pub const fn with(self, tc_mod: TcMod) -> Bundle {
        Bundle { tc_mod, ..self }
    }
}

/// `rgbGen`.
#[derive(Clone, Copy, PartialEq, Debug)]
pub enum RgbGen {
    /// White times `tr.identityLight` (1 here: no gamma-ramp overbright).
    IdentityLighting,
    /// White.
    Identity,
    /// The vertices' colours.
    Vertex,
    /// Computed from the entity's light (`lightingDiffuse`).
    LightingDiffuse,
    /// `wave sin base amplitude 0 frequency`.
    Wave { base: f32, amplitude: f32, frequency: f32 },
}

/// `alphaGen`.
#[derive(Clone, Copy, PartialEq, Debug)]
pub enum AlphaGen {
    /// 255.
    Identity,
    /// The vertices' alpha.
    Vertex,
    Const(u8),
}

/// A shader stage; `bundles[1]` is set when a lightmap stage was collapsed into it.
#[derive(Clone, Copy, PartialEq, Debug)]
pub struct Stage {
    pub bundles: [Option<Bundle>; 2],
    pub rgb_gen: RgbGen,
    pub alpha_gen: AlphaGen,
    pub state: StateBits,
}

impl Stage {
    /// A stage of one bundle.
    pub const fn new(bundle: Bundle, rgb_gen: RgbGen, alpha_gen: AlphaGen, state: StateBits) -> Stage {
        Stage { bundles: [Some(bundle), None], rgb_gen, alpha_gen, state }
    }

    /// An opaque stage: `map image`, `rgbGen identityLighting`.
    pub const fn base(image: GLuint) -> Stage {
        Stage::new(Bundle::map(image), RgbGen::IdentityLighting, AlphaGen::Identity, StateBits::DEFAULT)
    }

    /// `map $lightmap; blendFunc filter`.
    pub const fn lightmap(page: GLuint) -> Stage {
        Stage::new(Bundle::lightmap(page), RgbGen::IdentityLighting, AlphaGen::Identity, StateBits::FILTER)
    }
}

/// Which faces are drawn (`cull`).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Cull {
    /// The front side only (Q3 culls `GL_FRONT`: its fronts are clockwise).
    FrontSided,
    TwoSided,
}

/// Shader sort values (Q3's `SS_*`).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
pub enum Sort {
    /// The sky.
    Environment = 2,
    Opaque = 3,
    /// Blended shaders, after everything opaque.
    Blend0 = 9,
}

/// How `super::shade` draws a batch of the shader.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Iterator {
    /// Any stages, one pass each (`RB_StageIteratorGeneric`).
    Generic,
    /// One collapsed base × lightmap stage (`RB_StageIteratorLightmappedMultitexture`).
    LightmappedMultitexture,
    /// One stage lit by the entity's light (`RB_StageIteratorVertexLitTexture`).
    VertexLitTexture,
    /// The sky box, then the cloud stages (`RB_StageIteratorSky`).
    Sky,
}

/// `deformVertexes wave 0 sin base amplitude 0 frequency`: vertices pushed along their
/// normals.
#[derive(Clone, Copy, PartialEq, Debug)]
pub struct Deform {
    pub base: f32,
    pub amplitude: f32,
    pub frequency: f32,
}

/// A shader as written in a script.
#[derive(Clone, Debug)]
pub struct Script {
    pub name: &'static str,
    pub sort: Sort,
    pub cull: Cull,
    pub stages: Vec<Stage>,
    pub deform: Option<Deform>,
    /// `skyParms`: the six sides of the sky box.
    pub sky: Option<[GLuint; 6]>,
    /// Batches may span entities (sprites of one kind).
    pub entity_mergable: bool,
}

impl Script {
    /// An opaque, front-sided shader of `stages`.
    pub fn opaque(name: &'static str, stages: Vec<Stage>) -> Script {
        Script { name, sort: Sort::Opaque, cull: Cull::FrontSided, stages, deform: None, sky: None, entity_mergable: false }
    }

    /// A blended shader (sort [`Sort::Blend0`]).
    pub fn blended(name: &'static str, cull: Cull, stages: Vec<Stage>) -> Script {
        Script { sort: Sort::Blend0, cull, ..Script::opaque(name, stages) }
    }

    /// A model's skin: one stage of `image` lit per vertex (`rgbGen lightingDiffuse`).
    pub fn vertex_lit(name: &'static str, image: GLuint) -> Script {
        Script::opaque(name, vec![Stage::new(Bundle::map(image), RgbGen::LightingDiffuse, AlphaGen::Identity, StateBits::DEFAULT)])
    }
}

/// A prepared shader.
#[derive(Clone, Debug)]
pub struct Shader {
    pub name: &'static str,
    pub sort: Sort,
    pub cull: Cull,
    pub stages: Vec<Stage>,
    pub deform: Option<Deform>,
    pub sky: Option<[GLuint; 6]>,
    pub entity_mergable: bool,
    /// Stage 0 holds a collapsed second bundle (`shader.multitextureEnv`).
    pub multitexture: bool,
    pub iterator: Iterator,
    /// Position among all shaders by (sort, registration): the batch order.
    pub sorted_index: usize,
}

/// Collapses stages 0 and 1 when stage 1 multiplies stage 0 (Q3's `CollapseMultitexture`,
/// its `GL_MODULATE` entries): same state but for blending and depth writes, stage 0 opaque,
/// stage 1 `blendFunc filter` (either spelling), the same colour generation.
fn collapse(stages: &mut Vec<Stage>) -> bool {
    let [a, b, ..] = stages[..] else { return false };
    let rest = |s: StateBits| StateBits { blend: None, depth_write: false, ..s };
    let filter = matches!(b.state.blend, Some((GL_DST_COLOR, GL_ZERO) | (GL_ZERO, GL_SRC_COLOR)));
    if rest(a.state) != rest(b.state) || a.state.blend.is_some() || !filter || a.rgb_gen != b.rgb_gen || a.alpha_gen != b.alpha_gen {
        return false;
    }
    stages[0].bundles[1] = b.bundles[0];
    stages.remove(1);
    true
}

/// The iterator for a prepared shader (Q3's `ComputeStageIteratorFunc`).
fn iterator(script: &Script, multitexture: bool) -> Iterator {
    if script.sky.is_some() {
        return Iterator::Sky;
    }
    let [stage] = script.stages[..] else { return Iterator::Generic };
    let plain = |b: Option<Bundle>| b.is_some_and(|b| b.tc_mod == TcMod::None);
    if script.deform.is_none() && stage.rgb_gen == RgbGen::LightingDiffuse && stage.bundles[1].is_none() && plain(stage.bundles[0]) {
        Iterator::VertexLitTexture
    } else if multitexture && stage.rgb_gen == RgbGen::IdentityLighting && stage.alpha_gen == AlphaGen::Identity && plain(stage.bundles[0]) && plain(stage.bundles[1]) {
        Iterator::LightmappedMultitexture
    } else {
        Iterator::Generic
    }
}

/// The index of a registered shader.
pub type ShaderId = usize;

/// Every registered shader.
#[derive(Default)]
pub struct Shaders {
    list: Vec<Shader>,
}

impl Shaders {
    /// Prepares and registers `script`.
    pub fn register(&mut self, mut script: Script) -> ShaderId {
        let multitexture = script.sky.is_none() && collapse(&mut script.stages);
        let iterator = iterator(&script, multitexture);
        let Script { name, sort, cull, stages, deform, sky, entity_mergable } = script;
        self.list.push(Shader { name, sort, cull, stages, deform, sky, entity_mergable, multitexture, iterator, sorted_index: 0 });
        let mut order: Vec<usize> = (0..self.list.len()).collect();
        order.sort_by_key(|&i| (self.list[i].sort, i));
        for (position, &i) in order.iter().enumerate() {
            self.list[i].sorted_index = position;
        }
        self.list.len() - 1
    }

    /// The shader `id`.
    pub fn get(&self, id: ShaderId) -> &Shader {
        &self.list[id]
    }

    /// Every shader in registration order.
    pub fn iter(&self) -> impl std::iter::Iterator<Item = &Shader> {
        self.list.iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn detail_wall() -> Script {
        let detail = Stage::new(Bundle::map(7).with(TcMod::Scale(4.0, 4.0)), RgbGen::Identity, AlphaGen::Identity, StateBits::DETAIL);
        Script::opaque("wall", vec![Stage::base(1), Stage::lightmap(2), detail])
    }

    #[test]
    fn base_and_lightmap_collapse_onto_two_units() {
        let mut shaders = Shaders::default();
        let floor = shaders.register(Script::opaque("floor", vec![Stage::base(1), Stage::lightmap(2)]));
        let f = shaders.get(floor);
        assert!(f.multitexture && f.stages.len() == 1 && f.iterator == Iterator::LightmappedMultitexture);
        assert_eq!(f.stages[0].bundles[1], Some(Bundle::lightmap(2)));
        // With a detail stage the collapsed pair stays, drawn by the generic iterator.
        let wall = shaders.register(detail_wall());
        let w = shaders.get(wall);
        assert!(w.multitexture && w.stages.len() == 2 && w.iterator == Iterator::Generic);
        assert_eq!(w.stages[1].state, StateBits::DETAIL);
    }

    #[test]
    fn a_lightmap_with_depth_func_equal_stays_a_second_pass() {
        let mut shaders = Shaders::default();
        let metal = shaders.register(Script::opaque("metal", vec![Stage::base(1), Stage { state: StateBits::FILTER.equal(), ..Stage::lightmap(2) }]));
        let m = shaders.get(metal);
        assert!(!m.multitexture && m.stages.len() == 2 && m.iterator == Iterator::Generic);
        let skin = shaders.register(Script::vertex_lit("skin", 3));
        assert_eq!(shaders.get(skin).iterator, Iterator::VertexLitTexture);
    }

    #[test]
    fn shaders_sort_by_sort_then_registration() {
        let mut shaders = Shaders::default();
        let water = shaders.register(Script::blended("water", Cull::TwoSided, vec![Stage::new(Bundle::map(1), RgbGen::Identity, AlphaGen::Const(128), StateBits::BLEND)]));
        let wall = shaders.register(detail_wall());
        let sky = shaders.register(Script { sort: Sort::Environment, sky: Some([1; 6]), ..Script::opaque("sky", vec![]) });
        let floor = shaders.register(Script::opaque("floor", vec![Stage::base(1), Stage::lightmap(2)]));
        let order = |id| shaders.get(id).sorted_index;
        assert_eq!([order(sky), order(wall), order(floor), order(water)], [0, 1, 2, 3]);
        assert_eq!(shaders.get(sky).iterator, Iterator::Sky);
    }
}
