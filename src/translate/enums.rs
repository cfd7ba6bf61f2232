//! GL enums ↔ the Rust enums of [`crate::frame::state`]: one table per enum, read in both
//! directions, so a command converts its argument once and a `glGet` converts it back.

use super::gl::{self, GLenum};
use crate::frame::state::{
    BlendEquation, BlendFactor, ColorMaterialMode, CompareFunc, Face, FogMode, FogSource, LogicOp, PolygonMode,
    ShadeModel, SpriteR, StencilOp, Winding,
};

/// Pairs of a GL enum and the Rust value it stands for.
pub(crate) struct EnumTable<T: 'static>(pub &'static [(GLenum, T)]);

impl<T: Copy + PartialEq> EnumTable<T> {
    /// The value of `e`; `None` when the command does not accept it.
    pub fn parse(&self, e: GLenum) -> Option<T> {
        self.0.iter().find(|(g, _)| *g == e).map(|&(_, v)| v)
    }

    /// The GL enum of `v` (every table lists each value of its type).
    pub fn gl_enum(&self, v: T) -> GLenum {
        self.0.iter().find(|(_, x)| *x == v).map_or(gl::GL_NONE, |&(g, _)| g)
    }

    /// `glGet` value of `v`.
    pub fn value(&self, v: T) -> super::get::Value {
        super::get::Value::int(self.gl_enum(v))
    }
}

/// Comparison functions (alpha, depth, stencil tests).
pub(crate) const COMPARE: EnumTable<CompareFunc> = EnumTable(&[
    (gl::GL_NEVER, CompareFunc::Never),
    (gl::GL_LESS, CompareFunc::Less),
    (gl::GL_EQUAL, CompareFunc::Equal),
    (gl::GL_LEQUAL, CompareFunc::LessEqual),
    (gl::GL_GREATER, CompareFunc::Greater),
    (gl::GL_NOTEQUAL, CompareFunc::NotEqual),
    (gl::GL_GEQUAL, CompareFunc::GreaterEqual),
    (gl::GL_ALWAYS, CompareFunc::Always),
]);

/// Destination blend factors (OpenGL 1.5 table 4.2: every factor but `GL_SRC_ALPHA_SATURATE`).
pub(crate) const BLEND_DST: EnumTable<BlendFactor> = EnumTable(&[
    (gl::GL_ZERO, BlendFactor::Zero),
    (gl::GL_ONE, BlendFactor::One),
    (gl::GL_SRC_COLOR, BlendFactor::SrcColor),
    (gl::GL_ONE_MINUS_SRC_COLOR, BlendFactor::OneMinusSrcColor),
    (gl::GL_DST_COLOR, BlendFactor::DstColor),
    (gl::GL_ONE_MINUS_DST_COLOR, BlendFactor::OneMinusDstColor),
    (gl::GL_SRC_ALPHA, BlendFactor::SrcAlpha),
    (gl::GL_ONE_MINUS_SRC_ALPHA, BlendFactor::OneMinusSrcAlpha),
    (gl::GL_DST_ALPHA, BlendFactor::DstAlpha),
    (gl::GL_ONE_MINUS_DST_ALPHA, BlendFactor::OneMinusDstAlpha),
    (gl::GL_CONSTANT_COLOR, BlendFactor::ConstantColor),
    (gl::GL_ONE_MINUS_CONSTANT_COLOR, BlendFactor::OneMinusConstantColor),
    (gl::GL_CONSTANT_ALPHA, BlendFactor::ConstantAlpha),
    (gl::GL_ONE_MINUS_CONSTANT_ALPHA, BlendFactor::OneMinusConstantAlpha),
    (gl::GL_SRC_ALPHA_SATURATE, BlendFactor::SrcAlphaSaturate),
]);

/// Whether `f` may be a destination factor.
pub(crate) fn valid_dst_factor(f: BlendFactor) -> bool {
    f != BlendFactor::SrcAlphaSaturate
}

/// Blend equations (`glBlendEquation`, EXT_blend_minmax and EXT_blend_subtract).
pub(crate) const BLEND_EQUATION: EnumTable<BlendEquation> = EnumTable(&[
    (gl::GL_FUNC_ADD, BlendEquation::Add),
    (gl::GL_FUNC_SUBTRACT, BlendEquation::Subtract),
    (gl::GL_FUNC_REVERSE_SUBTRACT, BlendEquation::ReverseSubtract),
    (gl::GL_MIN, BlendEquation::Min),
    (gl::GL_MAX, BlendEquation::Max),
]);

/// `GL_POINT_SPRITE_R_MODE_NV` values.
pub(crate) const SPRITE_R: EnumTable<SpriteR> = EnumTable(&[(gl::GL_ZERO, SpriteR::Zero), (gl::GL_S, SpriteR::S), (gl::GL_R, SpriteR::R)]);

/// Stencil operations.
pub(crate) const STENCIL_OP: EnumTable<StencilOp> = EnumTable(&[
    (gl::GL_KEEP, StencilOp::Keep),
    (gl::GL_ZERO, StencilOp::Zero),
    (gl::GL_REPLACE, StencilOp::Replace),
    (gl::GL_INCR, StencilOp::Incr),
    (gl::GL_DECR, StencilOp::Decr),
    (gl::GL_INVERT, StencilOp::Invert),
    (gl::GL_INCR_WRAP, StencilOp::IncrWrap),
    (gl::GL_DECR_WRAP, StencilOp::DecrWrap),
]);

/// Logic operations (table 4.5).
pub(crate) const LOGIC_OP: EnumTable<LogicOp> = EnumTable(&[
    (gl::GL_CLEAR, LogicOp::Clear),
    (gl::GL_AND, LogicOp::And),
    (gl::GL_AND_REVERSE, LogicOp::AndReverse),
    (gl::GL_COPY, LogicOp::Copy),
    (gl::GL_AND_INVERTED, LogicOp::AndInverted),
    (gl::GL_NOOP, LogicOp::Noop),
    (gl::GL_XOR, LogicOp::Xor),
    (gl::GL_OR, LogicOp::Or),
    (gl::GL_NOR, LogicOp::Nor),
    (gl::GL_EQUIV, LogicOp::Equiv),
    (gl::GL_INVERT, LogicOp::Invert),
    (gl::GL_OR_REVERSE, LogicOp::OrReverse),
    (gl::GL_COPY_INVERTED, LogicOp::CopyInverted),
    (gl::GL_OR_INVERTED, LogicOp::OrInverted),
    (gl::GL_NAND, LogicOp::Nand),
    (gl::GL_SET, LogicOp::Set),
]);

/// Polygon faces.
pub(crate) const FACE: EnumTable<Face> =
    EnumTable(&[(gl::GL_FRONT, Face::Front), (gl::GL_BACK, Face::Back), (gl::GL_FRONT_AND_BACK, Face::FrontAndBack)]);

/// Front-face windings.
pub(crate) const WINDING: EnumTable<Winding> = EnumTable(&[(gl::GL_CW, Winding::Cw), (gl::GL_CCW, Winding::Ccw)]);

/// Polygon modes.
pub(crate) const POLYGON_MODE: EnumTable<PolygonMode> =
    EnumTable(&[(gl::GL_POINT, PolygonMode::Point), (gl::GL_LINE, PolygonMode::Line), (gl::GL_FILL, PolygonMode::Fill)]);

/// Shade models.
pub(crate) const SHADE_MODEL: EnumTable<ShadeModel> =
    EnumTable(&[(gl::GL_FLAT, ShadeModel::Flat), (gl::GL_SMOOTH, ShadeModel::Smooth)]);

/// Colour-material modes.
pub(crate) const COLOR_MATERIAL_MODE: EnumTable<ColorMaterialMode> = EnumTable(&[
    (gl::GL_EMISSION, ColorMaterialMode::Emission),
    (gl::GL_AMBIENT, ColorMaterialMode::Ambient),
    (gl::GL_DIFFUSE, ColorMaterialMode::Diffuse),
    (gl::GL_SPECULAR, ColorMaterialMode::Specular),
    (gl::GL_AMBIENT_AND_DIFFUSE, ColorMaterialMode::AmbientAndDiffuse),
]);

/// Fog modes.
pub(crate) const FOG_MODE: EnumTable<FogMode> =
    EnumTable(&[(gl::GL_LINEAR, FogMode::Linear), (gl::GL_EXP, FogMode::Exp), (gl::GL_EXP2, FogMode::Exp2)]);

/// Fog distance sources.
pub(crate) const FOG_SOURCE: EnumTable<FogSource> =
    EnumTable(&[(gl::GL_FRAGMENT_DEPTH, FogSource::FragmentDepth), (gl::GL_FOG_COORD, FogSource::FogCoord)]);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_round_trip() {
        assert_eq!(COMPARE.parse(gl::GL_LEQUAL), Some(CompareFunc::LessEqual));
        assert_eq!(COMPARE.gl_enum(CompareFunc::GreaterEqual), gl::GL_GEQUAL);
        assert_eq!(COMPARE.parse(gl::GL_FRONT), None);
        for &(g, v) in LOGIC_OP.0 {
            assert_eq!(LOGIC_OP.gl_enum(v), g);
        }
        assert!(!valid_dst_factor(BLEND_DST.parse(gl::GL_SRC_ALPHA_SATURATE).unwrap()));
    }
}
