//! Textures as draws use them: a reference (object name + content version) that carries the
//! resolved texel data, so the renderer uploads each content version once and reuses it while
//! the version is unchanged.
//!
//! Texels are canonical RGBA8 laid out as the base format expands them (OpenGL 1.5 table 3.15:
//! alpha → (0, 0, 0, A), luminance → (L, L, L, 1), luminance-alpha → (L, L, L, A), intensity →
//! (I, I, I, I), RGB → (R, G, B, 1), depth → (D, D, D, 1)); [`TexelFormat`] says which base
//! format it was, because texture environments treat them differently.
//!
//! Colour levels are stored at a [`Precision`]: formats of at most 8 bits a component keep
//! only the RGBA8 `texels`; sRGB formats keep sRGB-encoded RGBA8 `texels`, which a renderer
//! samples with sRGB decoding; formats with more bits, signed-normalized and floating-point
//! formats also carry [`TexImage::values`], four `f32` a texel expanded like `texels`, already
//! rounded to the internal format's precision (a renderer uploads those, for example as
//! `R32G32B32A32_SFLOAT`); their `texels` are the same values clamped to [0, 1] at 8 bits.
//!
//! Integer formats (EXT_texture_integer) keep their components exactly, as `i64` in
//! [`TexImage::integers`] ([`Precision::Integer`]).
//!
//! Depth levels also carry their values at full precision in [`TexImage::depth_values`] (one
//! `f32` per texel, already rounded to the internal format's 16 or 24 bits; 32-bit formats keep
//! the `f32`). A renderer reads depth levels from there (for example into a 32-bit float or
//! `D32_SFLOAT` texture) when it compares (`GL_TEXTURE_COMPARE_MODE`) or expands them by
//! [`DepthMode`]; the RGBA8 `texels` of a depth level are the same values at 8 bits.

use std::sync::Arc;

/// A texture as a draw uses it. Two references are equal when name and version are: the
/// version is unique across every texture of the process, so a renderer keys its uploads on it.
#[derive(Clone, Debug)]
pub struct TextureRef {
    /// Texture object name (0 for a default texture).
    pub id: u32,
    /// Content version: changes whenever images, parameters or the palette change.
    pub version: u64,
    /// What to upload for this version.
    pub content: Arc<TextureContent>,
}

impl PartialEq for TextureRef {
    fn eq(&self, other: &TextureRef) -> bool {
        self.id == other.id && self.version == other.version
    }
}
impl Eq for TextureRef {}
impl std::hash::Hash for TextureRef {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        (self.id, self.version).hash(state);
    }
}

/// The dimensionality of a texture.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TextureKind {
    /// One-dimensional.
    D1,
    /// Two-dimensional.
    #[default]
    D2,
    /// Three-dimensional.
    D3,
    /// Cube map: six faces in the order +X, −X, +Y, −Y, +Z, −Z.
    Cube,
    /// Rectangle (`GL_ARB_texture_rectangle`): two-dimensional, sampled with coordinates in
    /// texels, one level.
    Rect,
}

/// The base format the texels were specified with (table 3.15).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TexelFormat {
    /// Alpha only.
    Alpha,
    /// Luminance.
    Luminance,
    /// Luminance and alpha.
    LuminanceAlpha,
    /// Intensity.
    Intensity,
    /// RGB.
    Rgb,
    /// RGBA.
    #[default]
    Rgba,
    /// Depth, replicated as `DEPTH_TEXTURE_MODE` says at sampling time.
    Depth,
    /// Red (ARB_texture_rg): (R, 0, 0, 1); texture functions treat it as RGB.
    Red,
    /// Red and green (ARB_texture_rg): (R, G, 0, 1); texture functions treat it as RGB.
    Rg,
}

/// How the colour texels of a level are stored (see the module doc).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Precision {
    /// Linear RGBA8 `texels` only.
    #[default]
    Unorm8,
    /// sRGB-encoded RGBA8 `texels`, decoded to linear when sampled (EXT_texture_sRGB).
    Srgb8,
    /// RGBA `f32` [`TexImage::values`] beside the 8-bit `texels`.
    Float,
    /// Signed or unsigned integers in [`TexImage::integers`] (EXT_texture_integer); the 8-bit
    /// `texels` are zero. Fixed-function texturing of integer textures is undefined, so such
    /// levels never reach a frame (`translate::texture::snapshot` treats them as unbound).
    Integer,
}

/// Everything a renderer needs to build a texture and its sampler.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TextureContent {
    /// Dimensionality.
    pub kind: TextureKind,
    /// Base format of the base level.
    pub format: TexelFormat,
    /// `faces[face][level]`: one face except for cube maps.
    pub faces: Vec<Vec<Option<Arc<TexImage>>>>,
    /// Sampling parameters.
    pub sampler: Sampler,
}

/// One mipmap level: canonical RGBA8 texels, border included, rows bottom to top, slices
/// front to back.
#[derive(Clone, Default, PartialEq)]
pub struct TexImage {
    /// Width including the border.
    pub width: u32,
    /// Height including the border (1 for 1D).
    pub height: u32,
    /// Depth including the border (1 for 1D and 2D).
    pub depth: u32,
    /// Border width, 0 or 1.
    pub border: u32,
    /// `width * height * depth * 4` bytes.
    pub texels: Vec<u8>,
    /// How the texels are stored.
    pub precision: Precision,
    /// [`Precision::Float`]: `width * height * depth * 4` values in the order of `texels`;
    /// empty otherwise.
    pub values: Vec<f32>,
    /// [`Precision::Integer`]: `width * height * depth * 4` integer components in the order of
    /// `texels` (expanded as they are, with 0 and 1 for missing components), already clamped
    /// to the internal format's range; empty otherwise.
    pub integers: Vec<i64>,
    /// Depth formats: `width * height * depth` depth values in [0, 1], in the order of
    /// `texels`; empty for colour formats (see the module doc).
    pub depth_values: Vec<f32>,
}

impl std::fmt::Debug for TexImage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "TexImage({}x{}x{}, border {})", self.width, self.height, self.depth, self.border)
    }
}

/// Magnification filter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Filter {
    /// Nearest texel.
    Nearest,
    /// Bilinear.
    #[default]
    Linear,
}

/// Minification filter: texel filter and mipmap filter (`None` = base level only).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct MinFilter {
    /// Filter within a level.
    pub texel: Filter,
    /// Filter between levels; `None` when mipmapping is off.
    pub mipmap: Option<Filter>,
}

/// Wrap mode of one coordinate.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Wrap {
    /// `GL_REPEAT`.
    #[default]
    Repeat,
    /// `GL_CLAMP` (legacy: blends with the border colour at the edge).
    Clamp,
    /// `GL_CLAMP_TO_EDGE`.
    ClampToEdge,
    /// `GL_CLAMP_TO_BORDER`.
    ClampToBorder,
    /// `GL_MIRRORED_REPEAT`.
    MirroredRepeat,
}

/// Depth comparison function (`GL_TEXTURE_COMPARE_FUNC`): any of the eight (EXT_shadow_funcs,
/// core in OpenGL 1.5).
pub use super::state::CompareFunc;

/// How a depth texel becomes a colour (`GL_DEPTH_TEXTURE_MODE`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DepthMode {
    /// (D, D, D, 1).
    #[default]
    Luminance,
    /// (D, D, D, D).
    Intensity,
    /// (0, 0, 0, D).
    Alpha,
}

/// Sampler state of a texture object (OpenGL 1.5 table 6.16).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampler {
    /// Minification.
    pub min_filter: MinFilter,
    /// Magnification.
    pub mag_filter: Filter,
    /// Wrap of s, t, r.
    pub wrap: [Wrap; 3],
    /// Border colour, expanded as the texels of the base format are (so luminance and
    /// intensity replicate red, RGB has alpha 1).
    pub border_color: [f32; 4],
    /// Level-of-detail clamp, min and max.
    pub lod: [f32; 2],
    /// Base and max level.
    pub levels: [u32; 2],
    /// Depth comparison, when `GL_TEXTURE_COMPARE_MODE` is `GL_COMPARE_R_TO_TEXTURE`.
    pub compare: Option<CompareFunc>,
    /// Depth texel expansion.
    pub depth_mode: DepthMode,
}

impl Sampler {
    /// The axes (s, t, r) whose `GL_CLAMP` wrap blends edge texels with the border colour:
    /// `GL_CLAMP` clamps the coordinate to [0, 1] (section 3.8.7), so a linear filter at the
    /// edge reads half border; with nearest filters only, it picks edge texels, as
    /// clamp-to-edge does.
    pub fn clamp_blends_border(&self) -> [bool; 3] {
        let linear = self.mag_filter == Filter::Linear || self.min_filter.texel == Filter::Linear;
        self.wrap.map(|w| linear && w == Wrap::Clamp)
    }
}

impl Default for Sampler {
    fn default() -> Sampler {
        Sampler {
            min_filter: MinFilter { texel: Filter::Nearest, mipmap: Some(Filter::Linear) },
            mag_filter: Filter::Linear,
            wrap: [Wrap::Repeat; 3],
            border_color: [0.0; 4],
            lod: [-1000.0, 1000.0],
            levels: [0, 1000],
            compare: None,
            depth_mode: DepthMode::Luminance,
        }
    }
}

/// Texture function of a unit (`GL_TEXTURE_ENV_MODE`, OpenGL 1.5 section 3.8.13).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum EnvMode {
    /// Colour × texture.
    #[default]
    Modulate,
    /// Texture replaces.
    Replace,
    /// Texture blended over by its alpha.
    Decal,
    /// Blend with the environment colour.
    Blend,
    /// Colour + texture.
    Add,
    /// The combiner ([`TextureEnv::combine_rgb`] ...).
    Combine,
}

/// Combiner function (`GL_COMBINE_RGB`, `GL_COMBINE_ALPHA`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CombineFn {
    /// Arg0.
    Replace,
    /// Arg0 × Arg1.
    #[default]
    Modulate,
    /// Arg0 + Arg1.
    Add,
    /// Arg0 + Arg1 − 0.5.
    AddSigned,
    /// Arg0 × Arg2 + Arg1 × (1 − Arg2).
    Interpolate,
    /// Arg0 − Arg1.
    Subtract,
    /// 4 × dot(Arg0 − 0.5, Arg1 − 0.5) into RGB.
    Dot3Rgb,
    /// The same into RGBA.
    Dot3Rgba,
}

/// Combiner source (`GL_SOURCEn_RGB`, `GL_SOURCEn_ALPHA`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CombineSource {
    /// This unit's texture.
    #[default]
    Texture,
    /// The texture of another unit (crossbar).
    TextureUnit(u8),
    /// The environment colour.
    Constant,
    /// The fragment's primary colour.
    PrimaryColor,
    /// The previous unit's result.
    Previous,
}

/// Combiner operand (`GL_OPERANDn_RGB`, `GL_OPERANDn_ALPHA`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CombineOperand {
    /// The colour.
    #[default]
    SrcColor,
    /// One minus the colour.
    OneMinusSrcColor,
    /// The alpha.
    SrcAlpha,
    /// One minus the alpha.
    OneMinusSrcAlpha,
}

/// The texture environment of a unit, as the renderer applies it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TextureEnv {
    /// Texture function.
    pub mode: EnvMode,
    /// Environment colour.
    pub color: [f32; 4],
    /// RGB combiner function.
    pub combine_rgb: CombineFn,
    /// Alpha combiner function.
    pub combine_alpha: CombineFn,
    /// RGB sources 0–2.
    pub source_rgb: [CombineSource; 3],
    /// Alpha sources 0–2.
    pub source_alpha: [CombineSource; 3],
    /// RGB operands 0–2.
    pub operand_rgb: [CombineOperand; 3],
    /// Alpha operands 0–2.
    pub operand_alpha: [CombineOperand; 3],
    /// Scales of the combiner results (1, 2 or 4).
    pub scale: [f32; 2],
    /// Level-of-detail bias of the unit.
    pub lod_bias: f32,
}

/// How one texture coordinate is generated (section 2.10.4); planes in the space they apply
/// in (object plane on object coordinates, eye plane on eye coordinates).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TexGenMode {
    /// dot(plane, object position).
    ObjectLinear([f32; 4]),
    /// dot(plane, eye position).
    EyeLinear([f32; 4]),
    /// Sphere map from the eye-space reflection vector.
    SphereMap,
    /// The eye-space normal.
    NormalMap,
    /// The eye-space reflection vector.
    ReflectionMap,
}
