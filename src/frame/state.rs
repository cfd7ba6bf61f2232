//! The raster state of a draw, as plain Rust values: everything a renderer needs to draw a
//! primitive the way OpenGL 1.5 would (per-fragment operations, rasterization, lighting, fog,
//! clip planes, viewport). `translate` converts GL enums to these types when a command is
//! called and snapshots them per draw (`Context::raster_snapshot`).
//!
//! Texture environments, coordinate generation and bindings are not here: they travel with
//! the texture snapshot of the draw ([`super::Draw::textures`]), owned by the texture module.
//! Default values are the initial values of the OpenGL 1.5 state tables (6.x).

/// The largest point size and line width glrt draws (the renderer expands points and wide
/// lines to triangles, so this is a choice, not a device limit).
pub const MAX_POINT_SIZE: f32 = 64.0;

/// A comparison of the alpha, depth and stencil tests (OpenGL 1.5 sections 4.1.4 to 4.1.6) and
/// of depth textures (`GL_TEXTURE_COMPARE_FUNC`, section 3.8.14).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CompareFunc {
    /// Never passes.
    Never,
    /// Passes if the incoming value is less.
    Less,
    /// Passes if equal.
    Equal,
    /// Passes if less or equal.
    LessEqual,
    /// Passes if greater.
    Greater,
    /// Passes if not equal.
    NotEqual,
    /// Passes if greater or equal.
    GreaterEqual,
    /// Always passes.
    #[default]
    Always,
}

/// A blend factor (section 4.1.8, table 4.2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[allow(missing_docs)] // The names are the factors of table 4.2.
pub enum BlendFactor {
    Zero,
    #[default]
    One,
    SrcColor,
    OneMinusSrcColor,
    DstColor,
    OneMinusDstColor,
    SrcAlpha,
    OneMinusSrcAlpha,
    DstAlpha,
    OneMinusDstAlpha,
    ConstantColor,
    OneMinusConstantColor,
    ConstantAlpha,
    OneMinusConstantAlpha,
    SrcAlphaSaturate,
}

/// How source and destination are combined (section 4.1.8, table 4.1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BlendEquation {
    /// `s·S + d·D`.
    #[default]
    Add,
    /// `s·S − d·D`.
    Subtract,
    /// `d·D − s·S`.
    ReverseSubtract,
    /// `min(S, D)`.
    Min,
    /// `max(S, D)`.
    Max,
}

/// Blending, when enabled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blend {
    /// Source factor of the colour channels.
    pub src_rgb: BlendFactor,
    /// Destination factor of the colour channels.
    pub dst_rgb: BlendFactor,
    /// Source factor of alpha.
    pub src_alpha: BlendFactor,
    /// Destination factor of alpha.
    pub dst_alpha: BlendFactor,
    /// Equation of the colour channels.
    pub equation_rgb: BlendEquation,
    /// Equation of alpha.
    pub equation_alpha: BlendEquation,
    /// The constant colour (`glBlendColor`).
    pub color: [f32; 4],
}

impl Default for Blend {
    fn default() -> Blend {
        Blend {
            src_rgb: BlendFactor::One,
            dst_rgb: BlendFactor::Zero,
            src_alpha: BlendFactor::One,
            dst_alpha: BlendFactor::Zero,
            equation_rgb: BlendEquation::Add,
            equation_alpha: BlendEquation::Add,
            color: [0.0; 4],
        }
    }
}

/// A stencil operation (section 4.1.5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[allow(missing_docs)] // The names are those of section 4.1.5.
pub enum StencilOp {
    #[default]
    Keep,
    Zero,
    Replace,
    Incr,
    Decr,
    Invert,
    IncrWrap,
    DecrWrap,
}

/// Stencil test and update (section 4.1.5).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Stencil {
    /// The comparison.
    pub func: CompareFunc,
    /// The reference value, clamped to the stencil range.
    pub reference: i32,
    /// Mask applied to the reference and the stored value before comparing.
    pub value_mask: u32,
    /// Operation when the stencil test fails.
    pub fail: StencilOp,
    /// Operation when the stencil test passes and the depth test fails.
    pub depth_fail: StencilOp,
    /// Operation when both pass.
    pub depth_pass: StencilOp,
    /// Bits of the stencil buffer that may be written.
    pub write_mask: u32,
}

impl Default for Stencil {
    fn default() -> Stencil {
        Stencil {
            func: CompareFunc::Always,
            reference: 0,
            value_mask: u32::MAX,
            fail: StencilOp::Keep,
            depth_fail: StencilOp::Keep,
            depth_pass: StencilOp::Keep,
            write_mask: u32::MAX,
        }
    }
}

/// The stencil state of front- and back-facing polygons (OpenGL 2.0 section 4.1.5). Points,
/// lines, bitmaps and pixel rectangles are front-facing: they use `front`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StencilFaces {
    /// Front-facing polygons and every other primitive.
    pub front: Stencil,
    /// Back-facing polygons.
    pub back: Stencil,
}

impl StencilFaces {
    /// The same state for both faces.
    pub fn both(stencil: Stencil) -> StencilFaces {
        StencilFaces { front: stencil, back: stencil }
    }
}

/// A logic operation on colour indices or RGBA values (section 4.1.10, table 4.5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[allow(missing_docs)] // The names are the operations of table 4.5.
pub enum LogicOp {
    Clear,
    And,
    AndReverse,
    #[default]
    Copy,
    AndInverted,
    Noop,
    Xor,
    Or,
    Nor,
    Equiv,
    Invert,
    OrReverse,
    CopyInverted,
    OrInverted,
    Nand,
    Set,
}

/// Which polygon faces a setting applies to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Face {
    /// Front faces.
    Front,
    /// Back faces.
    #[default]
    Back,
    /// Both.
    FrontAndBack,
}

/// The winding of front faces (`glFrontFace`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Winding {
    /// Clockwise.
    Cw,
    /// Counter-clockwise.
    #[default]
    Ccw,
}

/// How polygons are rasterized (`glPolygonMode`, section 3.5.4).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PolygonMode {
    /// Vertices as points.
    Point,
    /// Edges as lines.
    Line,
    /// Filled.
    #[default]
    Fill,
}

/// Polygon depth offset (section 3.5.5).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PolygonOffset {
    /// Slope factor.
    pub factor: f32,
    /// Constant offset, in units of the smallest resolvable depth difference.
    pub units: f32,
    /// Applies to filled polygons (`GL_POLYGON_OFFSET_FILL`).
    pub fill: bool,
    /// Applies to polygons drawn as lines.
    pub line: bool,
    /// Applies to polygons drawn as points.
    pub point: bool,
}

/// Line rasterization (section 3.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line {
    /// Width in pixels.
    pub width: f32,
    /// Stipple `(repeat factor, 16-bit pattern)` when `GL_LINE_STIPPLE` is on.
    pub stipple: Option<(i32, u16)>,
    /// `GL_LINE_SMOOTH`.
    pub smooth: bool,
}

impl Default for Line {
    fn default() -> Line {
        Line { width: 1.0, stipple: None, smooth: false }
    }
}

/// Point rasterization (section 3.3, with the point parameters of OpenGL 1.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Size in pixels.
    pub size: f32,
    /// Smallest size after attenuation.
    pub size_min: f32,
    /// Largest size after attenuation.
    pub size_max: f32,
    /// Below this size, points fade instead of shrinking.
    pub fade_threshold: f32,
    /// Constant, linear and quadratic distance attenuation coefficients.
    pub attenuation: [f32; 3],
    /// `GL_POINT_SMOOTH` (off while point sprites are on).
    pub smooth: bool,
    /// Point sprites, when `GL_POINT_SPRITE` is on.
    pub sprite: Option<PointSprite>,
}

/// Point sprites (OpenGL 2.0 section 3.3): the point is a square of the unrounded derived size
/// centred on its exact window position, and the units that replace their coordinates get
/// s from 0 to 1 left to right, t from 0 to 1 along the origin's direction, r as
/// [`PointSprite::r`] says (0 in OpenGL 2.0) and q = 1.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PointSprite {
    /// Bit `u` set when texture unit `u` replaces its coordinates (`GL_COORD_REPLACE`).
    pub coord_replace: u32,
    /// `GL_POINT_SPRITE_COORD_ORIGIN` is `GL_LOWER_LEFT`: t grows upwards (with the initial
    /// `GL_UPPER_LEFT`, downwards).
    pub lower_left: bool,
    /// The replaced r coordinate (`GL_POINT_SPRITE_R_MODE_NV`).
    pub r: SpriteR,
}

/// The r coordinate of a replaced point sprite coordinate set (`GL_NV_point_sprite`'s
/// `GL_POINT_SPRITE_R_MODE_NV`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SpriteR {
    /// 0 (`GL_ZERO`, and always in OpenGL 2.0).
    #[default]
    Zero,
    /// The vertex's s / q (`GL_S`).
    S,
    /// The vertex's r / q (`GL_R`).
    R,
}

impl Default for Point {
    fn default() -> Point {
        Point {
            size: 1.0,
            size_min: 0.0,
            size_max: MAX_POINT_SIZE,
            fade_threshold: 1.0,
            attenuation: [1.0, 0.0, 0.0],
            smooth: false,
            sprite: None,
        }
    }
}

/// `glShadeModel`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ShadeModel {
    /// The provoking vertex's colour for the whole primitive.
    Flat,
    /// Colours interpolated.
    #[default]
    Smooth,
}

/// One light source (section 2.14.1), position and direction in eye space as they were when
/// specified.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Ambient intensity.
    pub ambient: [f32; 4],
    /// Diffuse intensity.
    pub diffuse: [f32; 4],
    /// Specular intensity.
    pub specular: [f32; 4],
    /// Homogeneous eye-space position; `w = 0` is a directional light.
    pub position: [f32; 4],
    /// Eye-space spot direction.
    pub spot_direction: [f32; 3],
    /// Spot exponent, in [0, 128].
    pub spot_exponent: f32,
    /// Spot cutoff angle in degrees, in [0, 90], or 180 for no spot.
    pub spot_cutoff: f32,
    /// Constant, linear and quadratic attenuation.
    pub attenuation: [f32; 3],
}

impl Light {
    /// The initial state of light `index`: light 0 is white, the others black (table 6.x).
    pub fn initial(index: usize) -> Light {
        let white = if index == 0 { [1.0; 4] } else { [0.0, 0.0, 0.0, 1.0] };
        Light {
            ambient: [0.0, 0.0, 0.0, 1.0],
            diffuse: white,
            specular: white,
            position: [0.0, 0.0, 1.0, 0.0],
            spot_direction: [0.0, 0.0, -1.0],
            spot_exponent: 0.0,
            spot_cutoff: 180.0,
            attenuation: [1.0, 0.0, 0.0],
        }
    }
}

/// Material properties of one face (section 2.14.1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Ambient reflectance.
    pub ambient: [f32; 4],
    /// Diffuse reflectance.
    pub diffuse: [f32; 4],
    /// Specular reflectance.
    pub specular: [f32; 4],
    /// Emitted light.
    pub emission: [f32; 4],
    /// Specular exponent, in [0, 128].
    pub shininess: f32,
}

impl Default for Material {
    fn default() -> Material {
        Material {
            ambient: [0.2, 0.2, 0.2, 1.0],
            diffuse: [0.8, 0.8, 0.8, 1.0],
            specular: [0.0, 0.0, 0.0, 1.0],
            emission: [0.0, 0.0, 0.0, 1.0],
            shininess: 0.0,
        }
    }
}

/// Which material property follows the current colour (`glColorMaterial`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[allow(missing_docs)] // The names are the material properties.
pub enum ColorMaterialMode {
    Emission,
    Ambient,
    Diffuse,
    Specular,
    #[default]
    AmbientAndDiffuse,
}

/// Colour material (section 2.14.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ColorMaterial {
    /// Faces whose material tracks the colour.
    pub face: Face,
    /// Which property tracks it.
    pub mode: ColorMaterialMode,
}

impl Default for ColorMaterial {
    fn default() -> ColorMaterial {
        ColorMaterial { face: Face::FrontAndBack, mode: ColorMaterialMode::AmbientAndDiffuse }
    }
}

/// The light model (section 2.14.1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightModel {
    /// Scene ambient light.
    pub ambient: [f32; 4],
    /// Specular highlights computed from the eye position rather than along −z.
    pub local_viewer: bool,
    /// Back faces lit with the back material and reversed normals.
    pub two_side: bool,
    /// `GL_SEPARATE_SPECULAR_COLOR`: specular goes to the secondary colour.
    pub separate_specular: bool,
}

impl Default for LightModel {
    fn default() -> LightModel {
        LightModel { ambient: [0.2, 0.2, 0.2, 1.0], local_viewer: false, two_side: false, separate_specular: false }
    }
}

/// Lighting, when `GL_LIGHTING` is on.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Lighting {
    /// The enabled lights with their index (`GL_LIGHTi`).
    pub lights: Vec<(usize, Light)>,
    /// The light model.
    pub model: LightModel,
    /// Front material.
    pub front: Material,
    /// Back material.
    pub back: Material,
    /// Colour material, when `GL_COLOR_MATERIAL` is on.
    pub color_material: Option<ColorMaterial>,
}

impl Lighting {
    /// Whether the front material's diffuse colour follows the vertex colour
    /// (`glColorMaterial` on `GL_DIFFUSE` or `GL_AMBIENT_AND_DIFFUSE`).
    pub fn tracks_diffuse(&self) -> bool {
        self.color_material.is_some_and(|c| matches!(c.mode, ColorMaterialMode::Diffuse | ColorMaterialMode::AmbientAndDiffuse))
    }

    /// The front material's diffuse colour, unless it follows the vertex colour: the base
    /// colour a lit draw is traced with in place of its vertex colours.
    pub fn untracked_diffuse(&self) -> Option<[f32; 4]> {
        (!self.tracks_diffuse()).then_some(self.front.diffuse)
    }
}

/// The fog equation (section 3.10).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FogMode {
    /// `(end − c) / (end − start)`.
    Linear,
    /// `exp(−density·c)`.
    #[default]
    Exp,
    /// `exp(−(density·c)²)`.
    Exp2,
}

/// Where the fog distance `c` comes from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FogSource {
    /// The eye-space distance to the fragment.
    #[default]
    FragmentDepth,
    /// The fog coordinate of the vertices.
    FogCoord,
}

/// Fog (section 3.10).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fog {
    /// Equation.
    pub mode: FogMode,
    /// Density of the exponential modes.
    pub density: f32,
    /// Start of linear fog.
    pub start: f32,
    /// End of linear fog.
    pub end: f32,
    /// Fog colour.
    pub color: [f32; 4],
    /// Distance source.
    pub source: FogSource,
}

impl Default for Fog {
    fn default() -> Fog {
        Fog { mode: FogMode::Exp, density: 1.0, start: 0.0, end: 1.0, color: [0.0; 4], source: FogSource::FragmentDepth }
    }
}

/// Snapshot of the state a draw is rasterized or traced with. `None` means disabled.
#[derive(Clone, Debug, PartialEq)]
pub struct RasterState {
    /// Alpha test: comparison and reference value.
    pub alpha_test: Option<(CompareFunc, f32)>,
    /// Blending.
    pub blend: Option<Blend>,
    /// RGBA logic operation (replaces blending when on).
    pub logic_op: Option<LogicOp>,
    /// Depth test.
    pub depth_test: Option<CompareFunc>,
    /// Depth writes (`glDepthMask`).
    pub depth_write: bool,
    /// Stencil test, per face.
    pub stencil: Option<StencilFaces>,
    /// Colour channels written (`glColorMask`).
    pub color_mask: [bool; 4],
    /// Faces culled.
    pub cull: Option<Face>,
    /// Winding of front faces.
    pub front_face: Winding,
    /// Polygon mode of front and back faces.
    pub polygon_mode: [PolygonMode; 2],
    /// Polygon offset.
    pub polygon_offset: PolygonOffset,
    /// Polygon stipple rows, bottom row first, bit 31 is the leftmost pixel.
    pub polygon_stipple: Option<[u32; 32]>,
    /// Lines.
    pub line: Line,
    /// Points.
    pub point: Point,
    /// Shading.
    pub shade_model: ShadeModel,
    /// Lighting.
    pub lighting: Option<Lighting>,
    /// `GL_COLOR_SUM`: the secondary colour is added after texturing.
    pub color_sum: bool,
    /// Fog.
    pub fog: Option<Fog>,
    /// Enabled user clip planes in eye space, with their index.
    pub clip_planes: Vec<(usize, [f64; 4])>,
    /// Scissor box (x, y, width, height) when the scissor test is on.
    pub scissor: Option<[i32; 4]>,
    /// Viewport (x, y, width, height).
    pub viewport: [i32; 4],
    /// Depth range (near, far).
    pub depth_range: [f64; 2],
    /// `GL_NORMALIZE`.
    pub normalize: bool,
    /// `GL_RESCALE_NORMAL`.
    pub rescale_normal: bool,
    /// `GL_DITHER`.
    pub dither: bool,
    /// Multisample rasterization and fragment operations.
    pub multisample: Multisample,
    /// Colour buffers that draws and pixel writes go to (`glDrawBuffer`).
    pub draw_buffers: DrawBuffers,
    /// Colour buffer that `glCopyPixels` and `glAccum` read (`glReadBuffer`).
    pub read_buffer: ColorBuffer,
    /// The framebuffer draws and pixel operations go to (and `glCopyPixels` reads).
    pub framebuffer: super::Framebuffer,
}

/// Multisample state (OpenGL 1.5 sections 3.2.1 and 4.1.3); it matters only on a
/// multisampled drawable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Multisample {
    /// `GL_MULTISAMPLE`: rasterize with the drawable's samples; off, every sample of a pixel
    /// takes the pixel centre's coverage and values.
    pub enabled: bool,
    /// `GL_SAMPLE_ALPHA_TO_COVERAGE`.
    pub alpha_to_coverage: bool,
    /// `GL_SAMPLE_ALPHA_TO_ONE`.
    pub alpha_to_one: bool,
    /// `GL_SAMPLE_COVERAGE` on: `glSampleCoverage`'s value and invert flag.
    pub coverage: Option<(f32, bool)>,
}

impl Default for Multisample {
    /// `GL_MULTISAMPLE` on, the coverage operations off.
    fn default() -> Multisample {
        Multisample { enabled: true, alpha_to_coverage: false, alpha_to_one: false, coverage: None }
    }
}

/// A colour buffer of the drawable (OpenGL 1.5 section 4.2.1). A double-buffered drawable
/// has both; a single-buffered one only the front buffer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ColorBuffer {
    /// The front buffer: what the window shows.
    Front,
    /// The back buffer: shown after `glXSwapBuffers`.
    #[default]
    Back,
}

/// The colour buffers that draws, clears and pixel writes go to (`glDrawBuffer`, section
/// 4.2.1): `GL_FRONT_AND_BACK` sets both, `GL_NONE` neither.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct DrawBuffers {
    /// The front buffer is written.
    pub front: bool,
    /// The back buffer is written.
    pub back: bool,
}

impl Default for DrawBuffers {
    /// The back buffer (the initial `GL_BACK` of a double-buffered drawable).
    fn default() -> DrawBuffers {
        DrawBuffers { front: false, back: true }
    }
}

impl DrawBuffers {
    /// The buffers written, front first.
    pub fn buffers(self) -> impl Iterator<Item = ColorBuffer> {
        [(self.front, ColorBuffer::Front), (self.back, ColorBuffer::Back)].into_iter().filter_map(|(on, b)| on.then_some(b))
    }
}

impl Default for RasterState {
    /// The initial OpenGL state, with a zero viewport.
    fn default() -> RasterState {
        RasterState {
            alpha_test: None,
            blend: None,
            logic_op: None,
            depth_test: None,
            depth_write: true,
            stencil: None,
            color_mask: [true; 4],
            cull: None,
            front_face: Winding::Ccw,
            polygon_mode: [PolygonMode::Fill; 2],
            polygon_offset: PolygonOffset::default(),
            polygon_stipple: None,
            line: Line::default(),
            point: Point::default(),
            shade_model: ShadeModel::Smooth,
            lighting: None,
            color_sum: false,
            fog: None,
            clip_planes: Vec::new(),
            scissor: None,
            viewport: [0; 4],
            depth_range: [0.0, 1.0],
            normalize: false,
            rescale_normal: false,
            dither: true,
            multisample: Multisample::default(),
            draw_buffers: DrawBuffers::default(),
            read_buffer: ColorBuffer::Back,
            framebuffer: super::Framebuffer::Window,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_diffuse_colour_is_untracked_unless_colour_material_sets_it() {
        let mut lighting = Lighting::default();
        lighting.front.diffuse = [0.25, 0.5, 0.75, 1.0];
        assert_eq!(lighting.untracked_diffuse(), Some([0.25, 0.5, 0.75, 1.0]), "no colour material");
        for (mode, tracked) in [
            (ColorMaterialMode::Emission, false),
            (ColorMaterialMode::Ambient, false),
            (ColorMaterialMode::Specular, false),
            (ColorMaterialMode::Diffuse, true),
            (ColorMaterialMode::AmbientAndDiffuse, true),
        ] {
            lighting.color_material = Some(ColorMaterial { face: Face::Front, mode });
            assert_eq!(lighting.tracks_diffuse(), tracked, "{mode:?}");
            assert_eq!(lighting.untracked_diffuse(), (!tracked).then_some(lighting.front.diffuse), "{mode:?}");
        }
    }
}
