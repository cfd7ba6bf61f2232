//! How much client memory a command reads through a pointer whose size gl.xml does not fix,
//! for the call log's pointer summaries (bytes, xxh3 hash, first values):
//! - the vector state commands (`glLightfv`, `glMaterialiv`, `glFogfv`, `glTexEnviv`,
//!   `glTexParameterfv`, `glTexGendv`, `glLightModelfv`, `glPointParameterfv`): the count of
//!   the `pname` (OpenGL 1.5 tables 2.11, 2.12, 3.19, 3.24 and the reference pages);
//! - `glCallLists`: `n` names of `type`; `glDrawElements`/`glDrawRangeElements`: `count`
//!   indices of `type`, when no element buffer is bound (otherwise the pointer is an offset);
//! - pixel images (`glTexImage*`, `glTexSubImage*`, `glDrawPixels`): the span the current
//!   context's unpack modes give (section 3.6.4), as glrt itself reads it, when no pixel
//!   unpack buffer is bound (otherwise the pointer is an offset).
//!
//! What depends on GL state needs glrt's current context: in pass-through mode, or without a
//! context, those pointers print their address only (guessing the other library's state could
//! read past the program's memory).

use crate::gl_entry::current::with_slot;
use crate::translate::gl::{self, GLenum, GLsizei};
use crate::translate::pixels::codec;

/// How many values the vector parameter `pname` has (`None`: unknown, the address is printed).
pub fn values_of(pname: GLenum) -> Option<usize> {
    Some(match pname {
        gl::GL_AMBIENT | gl::GL_DIFFUSE | gl::GL_SPECULAR | gl::GL_POSITION | gl::GL_EMISSION => 4,
        gl::GL_AMBIENT_AND_DIFFUSE | gl::GL_FOG_COLOR | gl::GL_TEXTURE_ENV_COLOR => 4,
        gl::GL_TEXTURE_BORDER_COLOR | gl::GL_OBJECT_PLANE | gl::GL_EYE_PLANE => 4,
        gl::GL_SPOT_DIRECTION | gl::GL_COLOR_INDEXES | gl::GL_POINT_DISTANCE_ATTENUATION => 3,
        gl::GL_SPOT_EXPONENT | gl::GL_SPOT_CUTOFF | gl::GL_CONSTANT_ATTENUATION | gl::GL_LINEAR_ATTENUATION => 1,
        gl::GL_QUADRATIC_ATTENUATION | gl::GL_SHININESS => 1,
        gl::GL_LIGHT_MODEL_AMBIENT => 4,
        gl::GL_LIGHT_MODEL_LOCAL_VIEWER | gl::GL_LIGHT_MODEL_TWO_SIDE | gl::GL_LIGHT_MODEL_COLOR_CONTROL => 1,
        gl::GL_FOG_MODE | gl::GL_FOG_DENSITY | gl::GL_FOG_START | gl::GL_FOG_END | gl::GL_FOG_INDEX => 1,
        gl::GL_FOG_COORD_SRC => 1,
        gl::GL_TEXTURE_ENV_MODE | gl::GL_TEXTURE_LOD_BIAS | gl::GL_COMBINE_RGB | gl::GL_COMBINE_ALPHA => 1,
        gl::GL_SRC0_RGB | gl::GL_SRC1_RGB | gl::GL_SRC2_RGB | gl::GL_SRC0_ALPHA | gl::GL_SRC1_ALPHA => 1,
        gl::GL_SRC2_ALPHA | gl::GL_OPERAND0_RGB | gl::GL_OPERAND1_RGB | gl::GL_OPERAND2_RGB => 1,
        gl::GL_OPERAND0_ALPHA | gl::GL_OPERAND1_ALPHA | gl::GL_OPERAND2_ALPHA => 1,
        gl::GL_RGB_SCALE | gl::GL_ALPHA_SCALE => 1,
        gl::GL_TEXTURE_MIN_FILTER | gl::GL_TEXTURE_MAG_FILTER | gl::GL_TEXTURE_WRAP_S | gl::GL_TEXTURE_WRAP_T => 1,
        gl::GL_TEXTURE_WRAP_R | gl::GL_TEXTURE_PRIORITY | gl::GL_TEXTURE_MIN_LOD | gl::GL_TEXTURE_MAX_LOD => 1,
        gl::GL_TEXTURE_BASE_LEVEL | gl::GL_TEXTURE_MAX_LEVEL | gl::GL_GENERATE_MIPMAP => 1,
        gl::GL_DEPTH_TEXTURE_MODE | gl::GL_TEXTURE_COMPARE_MODE | gl::GL_TEXTURE_COMPARE_FUNC => 1,
        gl::GL_TEXTURE_GEN_MODE => 1,
        gl::GL_POINT_SIZE_MIN | gl::GL_POINT_SIZE_MAX | gl::GL_POINT_FADE_THRESHOLD_SIZE => 1,
        _ => return None,
    })
}

/// A client array of `count` elements of the GL data type `type_` (`glCallLists` names,
/// `glDrawElements` indices).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Typed {
    /// The GL type (`GL_UNSIGNED_SHORT`, `GL_2_BYTES`...).
    pub type_: GLenum,
    /// Number of elements.
    pub count: usize,
}

impl Typed {
    /// `count` elements of `type_`; `None` for a negative count or a type without a size.
    pub fn new(type_: GLenum, count: GLsizei) -> Option<Typed> {
        let count = usize::try_from(count).ok()?;
        element_size(type_).map(|_| Typed { type_, count })
    }

    /// The bytes the elements take.
    pub fn bytes(self) -> usize {
        element_size(self.type_).unwrap_or(0).saturating_mul(self.count)
    }
}

/// Bytes per element of a GL data type.
pub fn element_size(type_: GLenum) -> Option<usize> {
    Some(match type_ {
        gl::GL_BYTE | gl::GL_UNSIGNED_BYTE => 1,
        gl::GL_SHORT | gl::GL_UNSIGNED_SHORT | gl::GL_2_BYTES => 2,
        gl::GL_3_BYTES => 3,
        gl::GL_INT | gl::GL_UNSIGNED_INT | gl::GL_FLOAT | gl::GL_4_BYTES => 4,
        _ => return None,
    })
}

/// `glCallLists`' names.
pub fn call_lists(n: GLsizei, type_: GLenum) -> Option<Typed> {
    Typed::new(type_, n)
}

/// `glDrawElements`' indices, when they are in client memory: a glrt context is current and
/// has no element buffer bound.
pub fn indices(count: GLsizei, type_: GLenum) -> Option<Typed> {
    let client = with_slot(|slot| slot.as_ref().is_some_and(|c| !c.broken && c.context.arrays.element_buffer == 0));
    if !client || !matches!(type_, gl::GL_UNSIGNED_BYTE | gl::GL_UNSIGNED_SHORT | gl::GL_UNSIGNED_INT) {
        return None;
    }
    Typed::new(type_, count)
}

/// The bytes a `width` × `height` × `depth` image of `format`/`type_` takes in client memory
/// under the current context's unpack modes; `None` without a glrt context, with a pixel
/// unpack buffer bound, or for arguments the command refuses.
pub fn image(format: GLenum, type_: GLenum, width: GLsizei, height: GLsizei, depth: GLsizei) -> Option<usize> {
    let (f, t) = codec::parse(format, type_).ok()?;
    let [w, h, d] = [width, height, depth].map(|v| usize::try_from(v).ok());
    let (w, h, d) = (w?, h?, d?);
    with_slot(|slot| {
        let c = slot.as_ref().filter(|c| !c.broken && c.context.pixels.store.unpack_buffer == 0)?;
        t.layout(f, &c.context.pixels.store.unpack, w, h, d).map(|layout| layout.span)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vector_parameter_counts() {
        assert_eq!(values_of(gl::GL_POSITION), Some(4));
        assert_eq!(values_of(gl::GL_SPOT_DIRECTION), Some(3));
        assert_eq!(values_of(gl::GL_SHININESS), Some(1));
        assert_eq!(values_of(gl::GL_FOG_COLOR), Some(4));
        assert_eq!(values_of(0x1234), None);
    }

    #[test]
    fn typed_arrays() {
        assert_eq!(call_lists(5, gl::GL_UNSIGNED_SHORT).map(Typed::bytes), Some(10));
        assert_eq!(call_lists(2, gl::GL_3_BYTES).map(Typed::bytes), Some(6));
        assert_eq!(call_lists(-1, gl::GL_UNSIGNED_BYTE), None);
        assert_eq!(call_lists(1, gl::GL_DOUBLE), None);
    }

    #[test]
    fn state_dependent_sizes_need_a_context() {
        std::thread::spawn(|| {
            assert_eq!(indices(6, gl::GL_UNSIGNED_SHORT), None);
            assert_eq!(image(gl::GL_RGB, gl::GL_UNSIGNED_BYTE, 3, 2, 1), None);
        })
        .join()
        .expect("no panic");
    }
}
