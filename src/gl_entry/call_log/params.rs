//! Which scalar `param` values the call log prints by name: those of the `pname`s whose value
//! is a symbolic constant (`glTexParameteri(..., pname=GL_TEXTURE_MIN_FILTER,
//! param=GL_LINEAR)`, `glFogf(pname=GL_FOG_MODE, param=GL_EXP)`). gl.xml types these
//! parameters as plain `GLint`/`GLfloat` for every `pname`, so the table is written here, from
//! the OpenGL 1.5 specification (tables 3.19 and 3.24, sections 2.11.4, 2.14.1, 3.10) and the
//! `glTexEnv`, `glTexParameter`, `glFog`, `glLightModel`, `glTexGen` and `glPointParameter`
//! reference pages. The commands are found by the build script: any whose parameters include
//! a `GLenum pname` followed by a scalar `param` ([`super::Entry::param_of`]).

use crate::translate::gl::{self, GLenum};

/// `(name, value)` pairs of the listed constants.
macro_rules! named {
    ($($c:ident),* $(,)?) => { &[$((stringify!($c), gl::$c)),*] };
}

type Names = &'static [(&'static str, GLenum)];

const COMPARE_FUNCS: Names = named![GL_NEVER, GL_LESS, GL_EQUAL, GL_LEQUAL, GL_GREATER, GL_NOTEQUAL, GL_GEQUAL, GL_ALWAYS];
const WRAP_MODES: Names = named![GL_CLAMP, GL_REPEAT, GL_CLAMP_TO_EDGE, GL_CLAMP_TO_BORDER, GL_MIRRORED_REPEAT];
/// `GLboolean` constants (typed `GLboolean`, not `GLenum`).
const BOOLEANS: Names = &[("GL_FALSE", 0), ("GL_TRUE", 1)];
const COMBINE_ALPHA: Names = named![GL_REPLACE, GL_MODULATE, GL_ADD, GL_ADD_SIGNED, GL_INTERPOLATE, GL_SUBTRACT];
const COMBINE_RGB: Names =
    named![GL_REPLACE, GL_MODULATE, GL_ADD, GL_ADD_SIGNED, GL_INTERPOLATE, GL_SUBTRACT, GL_DOT3_RGB, GL_DOT3_RGBA];
/// `GL_SRCn_RGB`/`GL_SRCn_ALPHA`, with ARB_texture_env_crossbar's texture units.
const COMBINE_SOURCES: Names = named![
    GL_TEXTURE, GL_CONSTANT, GL_PRIMARY_COLOR, GL_PREVIOUS, GL_TEXTURE0, GL_TEXTURE1, GL_TEXTURE2, GL_TEXTURE3
];
const OPERANDS_RGB: Names = named![GL_SRC_COLOR, GL_ONE_MINUS_SRC_COLOR, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA];
const OPERANDS_ALPHA: Names = named![GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA];

/// The constants `pname`'s value is one of, `None` for a numeric `pname`.
pub fn symbolic_values(pname: GLenum) -> Option<Names> {
    Some(match pname {
        gl::GL_TEXTURE_MIN_FILTER => named![
            GL_NEAREST, GL_LINEAR, GL_NEAREST_MIPMAP_NEAREST, GL_LINEAR_MIPMAP_NEAREST,
            GL_NEAREST_MIPMAP_LINEAR, GL_LINEAR_MIPMAP_LINEAR
        ],
        gl::GL_TEXTURE_MAG_FILTER => named![GL_NEAREST, GL_LINEAR],
        gl::GL_TEXTURE_WRAP_S | gl::GL_TEXTURE_WRAP_T | gl::GL_TEXTURE_WRAP_R => WRAP_MODES,
        gl::GL_GENERATE_MIPMAP => BOOLEANS,
        gl::GL_DEPTH_TEXTURE_MODE => named![GL_LUMINANCE, GL_INTENSITY, GL_ALPHA],
        gl::GL_TEXTURE_COMPARE_MODE => named![GL_NONE, GL_COMPARE_R_TO_TEXTURE],
        gl::GL_TEXTURE_COMPARE_FUNC => COMPARE_FUNCS,
        gl::GL_TEXTURE_ENV_MODE => named![GL_MODULATE, GL_DECAL, GL_BLEND, GL_REPLACE, GL_ADD, GL_COMBINE],
        gl::GL_COMBINE_RGB => COMBINE_RGB,
        gl::GL_COMBINE_ALPHA => COMBINE_ALPHA,
        gl::GL_SRC0_RGB | gl::GL_SRC1_RGB | gl::GL_SRC2_RGB => COMBINE_SOURCES,
        gl::GL_SRC0_ALPHA | gl::GL_SRC1_ALPHA | gl::GL_SRC2_ALPHA => COMBINE_SOURCES,
        gl::GL_OPERAND0_RGB | gl::GL_OPERAND1_RGB | gl::GL_OPERAND2_RGB => OPERANDS_RGB,
        gl::GL_OPERAND0_ALPHA | gl::GL_OPERAND1_ALPHA | gl::GL_OPERAND2_ALPHA => OPERANDS_ALPHA,
        gl::GL_FOG_MODE => named![GL_LINEAR, GL_EXP, GL_EXP2],
        gl::GL_FOG_COORD_SRC => named![GL_FOG_COORD, GL_FRAGMENT_DEPTH],
        gl::GL_LIGHT_MODEL_COLOR_CONTROL => named![GL_SINGLE_COLOR, GL_SEPARATE_SPECULAR_COLOR],
        gl::GL_TEXTURE_GEN_MODE => named![GL_OBJECT_LINEAR, GL_EYE_LINEAR, GL_SPHERE_MAP, GL_NORMAL_MAP, GL_REFLECTION_MAP],
        gl::GL_POINT_SPRITE_COORD_ORIGIN => named![GL_LOWER_LEFT, GL_UPPER_LEFT],
        _ => return None,
    })
}

/// The name of `value` (as the command received it, maybe as a float) when `pname` takes
/// constants and `value` is one of them.
pub fn name_of(pname: GLenum, value: f64) -> Option<&'static str> {
    let names = symbolic_values(pname)?;
    let value = (value.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&value)).then_some(value as GLenum)?;
    names.iter().find(|(_, v)| *v == value).map(|(n, _)| *n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symbolic_values_by_pname() {
        assert_eq!(name_of(gl::GL_TEXTURE_MIN_FILTER, f64::from(gl::GL_LINEAR_MIPMAP_LINEAR)), Some("GL_LINEAR_MIPMAP_LINEAR"));
        assert_eq!(name_of(gl::GL_TEXTURE_ENV_MODE, f64::from(gl::GL_MODULATE)), Some("GL_MODULATE"));
        assert_eq!(name_of(gl::GL_FOG_MODE, 2048.0), Some("GL_EXP"));
        assert_eq!(name_of(gl::GL_SRC1_RGB, f64::from(gl::GL_PREVIOUS)), Some("GL_PREVIOUS"));
        assert_eq!(name_of(gl::GL_GENERATE_MIPMAP, 1.0), Some("GL_TRUE"));
        // A value the pname does not take, a fraction, a numeric pname.
        assert_eq!(name_of(gl::GL_TEXTURE_MAG_FILTER, f64::from(gl::GL_NEAREST_MIPMAP_NEAREST)), None);
        assert_eq!(name_of(gl::GL_FOG_MODE, 2048.5), None);
        assert_eq!(name_of(gl::GL_FOG_DENSITY, 2048.0), None);
        assert_eq!(name_of(gl::GL_TEXTURE_WRAP_S, -1.0), None);
    }
}
