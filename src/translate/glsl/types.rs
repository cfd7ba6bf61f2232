//! The basic types of GLSL 1.20 (section 4.1): what each is for layouts, reflection and the
//! renderer.

use crate::frame::program::SamplerKind;

/// What a basic type holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scalar {
    /// `float`, `vec*`, `mat*`.
    Float,
    /// `int`, `ivec*`.
    Int,
    /// `bool`, `bvec*` (4-byte integers in blocks).
    Bool,
    /// A sampler.
    Sampler(SamplerKind),
}

/// A basic (non-struct) type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BasicType {
    /// Its GLSL name.
    pub name: &'static str,
    /// The GL enum `glGetActiveUniform`/`glGetActiveAttrib` report.
    pub gl: u32,
    /// Component kind.
    pub scalar: Scalar,
    /// Rows (vector components); 1 for scalars and samplers.
    pub rows: u32,
    /// Columns (1 for vectors and scalars).
    pub columns: u32,
}

const fn t(name: &'static str, gl: u32, scalar: Scalar, rows: u32, columns: u32) -> BasicType {
    BasicType { name, gl, scalar, rows, columns }
}

/// Every basic type of GLSL 1.20 but `void`.
pub const BASIC_TYPES: &[BasicType] = &[
    t("float", 0x1406, Scalar::Float, 1, 1),
    t("vec2", 0x8B50, Scalar::Float, 2, 1),
    t("vec3", 0x8B51, Scalar::Float, 3, 1),
    t("vec4", 0x8B52, Scalar::Float, 4, 1),
    t("int", 0x1404, Scalar::Int, 1, 1),
    t("ivec2", 0x8B53, Scalar::Int, 2, 1),
    t("ivec3", 0x8B54, Scalar::Int, 3, 1),
    t("ivec4", 0x8B55, Scalar::Int, 4, 1),
    t("bool", 0x8B56, Scalar::Bool, 1, 1),
    t("bvec2", 0x8B57, Scalar::Bool, 2, 1),
    t("bvec3", 0x8B58, Scalar::Bool, 3, 1),
    t("bvec4", 0x8B59, Scalar::Bool, 4, 1),
    t("mat2", 0x8B5A, Scalar::Float, 2, 2),
    t("mat3", 0x8B5B, Scalar::Float, 3, 3),
    t("mat4", 0x8B5C, Scalar::Float, 4, 4),
    t("mat2x2", 0x8B5A, Scalar::Float, 2, 2),
    t("mat3x3", 0x8B5B, Scalar::Float, 3, 3),
    t("mat4x4", 0x8B5C, Scalar::Float, 4, 4),
    t("mat2x3", 0x8B65, Scalar::Float, 3, 2),
    t("mat2x4", 0x8B66, Scalar::Float, 4, 2),
    t("mat3x2", 0x8B67, Scalar::Float, 2, 3),
    t("mat3x4", 0x8B68, Scalar::Float, 4, 3),
    t("mat4x2", 0x8B69, Scalar::Float, 2, 4),
    t("mat4x3", 0x8B6A, Scalar::Float, 3, 4),
    t("sampler1D", 0x8B5D, Scalar::Sampler(SamplerKind::D2), 1, 1),
    t("sampler2D", 0x8B5E, Scalar::Sampler(SamplerKind::D2), 1, 1),
    t("sampler3D", 0x8B5F, Scalar::Sampler(SamplerKind::D3), 1, 1),
    t("samplerCube", 0x8B60, Scalar::Sampler(SamplerKind::Cube), 1, 1),
    t("sampler1DShadow", 0x8B61, Scalar::Sampler(SamplerKind::D2Shadow), 1, 1),
    t("sampler2DShadow", 0x8B62, Scalar::Sampler(SamplerKind::D2Shadow), 1, 1),
];

/// The basic type called `name`.
pub fn basic(name: &str) -> Option<&'static BasicType> {
    BASIC_TYPES.iter().find(|t| t.name == name)
}

impl BasicType {
    /// The sampler kind, for samplers.
    pub fn sampler(&self) -> Option<SamplerKind> {
        match self.scalar {
            Scalar::Sampler(kind) => Some(kind),
            _ => None,
        }
    }

    /// The type the Vulkan rewrite declares for it: 1D samplers are 2D samplers one texel
    /// high, and shadow samplers are plain samplers the prelude compares with.
    pub fn vulkan_name(&self) -> &'static str {
        match self.sampler() {
            Some(SamplerKind::D2 | SamplerKind::D2Shadow) => "sampler2D",
            _ => self.name,
        }
    }

    /// (alignment, size) in a std430 block; matrices are arrays of column vectors.
    pub fn std430(&self) -> (u32, u32) {
        let column = match self.rows {
            1 => (4, 4),
            2 => (8, 8),
            3 => (16, 12),
            _ => (16, 16),
        };
        if self.columns == 1 {
            column
        } else {
            (column.0, column.0 * self.columns)
        }
    }

    /// Bytes between the columns of a matrix in std430 (0 for vectors and scalars).
    pub fn matrix_stride(&self) -> u32 {
        if self.columns == 1 { 0 } else { self.std430().0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn std430_sizes() {
        assert_eq!(basic("vec3").unwrap().std430(), (16, 12));
        assert_eq!(basic("mat3").unwrap().std430(), (16, 48));
        assert_eq!(basic("mat2").unwrap().std430(), (8, 16));
        assert_eq!(basic("mat4x3").unwrap().std430(), (16, 64));
        assert_eq!(basic("sampler1D").unwrap().vulkan_name(), "sampler2D");
        assert_eq!(basic("bool").unwrap().gl, 0x8B56);
    }
}
