//! The stencil test's parameters (OpenGL 2.0 section 4.1.5): `glStencilFunc`, `glStencilOp`,
//! `glStencilMask`, their `*Separate` forms for front and back faces, `GL_ATI_separate_stencil`'s
//! `glStencilFuncSeparateATI`, and `GL_EXT_stencil_two_side` (`glActiveStencilFaceEXT`,
//! `GL_STENCIL_TEST_TWO_SIDE_EXT`), with their queries (table 6.19).
//!
//! As in Mesa, `GL_EXT_stencil_two_side` keeps its own back-face state beside OpenGL 2.0's:
//! while `GL_STENCIL_TEST_TWO_SIDE_EXT` is on, back faces use it; otherwise they use the 2.0
//! back state (which the non-separate commands keep equal to the front one). With
//! `glActiveStencilFaceEXT(GL_BACK)` the non-separate commands set and the `GL_STENCIL_*`
//! queries read the extension's back state alone; with `GL_FRONT` (initially) the commands set
//! the front and 2.0 back states and the queries read the front state.

use super::Context;
use super::enums::{COMPARE, STENCIL_OP};
use super::get::Value;
use super::gl::{self, GLenum, GLint, GLuint};
use super::implementation::STENCIL_BITS;
use crate::frame::state::{Stencil, StencilFaces};

/// Index of the front state in [`StencilState::faces`].
const FRONT: usize = 0;
/// Index of OpenGL 2.0's back state.
const BACK: usize = 1;
/// Index of `GL_EXT_stencil_two_side`'s back state.
const BACK_EXT: usize = 2;

/// The stencil state of a context.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StencilState {
    /// Front, OpenGL 2.0 back, and `GL_EXT_stencil_two_side` back state.
    faces: [Stencil; 3],
    /// `glActiveStencilFaceEXT`: [`FRONT`] or [`BACK_EXT`].
    active: usize,
}

impl StencilState {
    /// The state draws use: back faces take the extension's back state when
    /// `GL_STENCIL_TEST_TWO_SIDE_EXT` is on (`two_side`).
    pub fn for_draw(&self, two_side: bool) -> StencilFaces {
        StencilFaces { front: self.faces[FRONT], back: self.faces[if two_side { BACK_EXT } else { BACK }] }
    }

    /// The front write mask, which `glClear` uses (section 4.2.3).
    pub fn clear_mask(&self) -> u32 {
        self.faces[FRONT].write_mask
    }

    /// The faces the non-separate commands set.
    fn active_faces(&self) -> &'static [usize] {
        if self.active == BACK_EXT { &[BACK_EXT] } else { &[FRONT, BACK] }
    }
}

/// The faces `face` names in the `*Separate` commands, or `None` for an invalid enum.
fn separate_faces(face: GLenum) -> Option<&'static [usize]> {
    match face {
        gl::GL_FRONT => Some(&[FRONT]),
        gl::GL_BACK => Some(&[BACK]),
        gl::GL_FRONT_AND_BACK => Some(&[FRONT, BACK]),
        _ => None,
    }
}

/// A mask as `glGet` returns it: the bits reinterpreted as a signed integer, as Mesa does
/// (all ones reads as −1).
pub(crate) fn mask_value(mask: u32) -> Value {
    Value::int(mask as i32)
}

impl Context {
    /// Applies `set` to the stencil state of `faces`.
    fn set_stencil(&mut self, faces: &[usize], set: impl Fn(&mut Stencil)) {
        let state = &mut self.fixed_mut().fragment.stencil;
        for &f in faces {
            set(&mut state.faces[f]);
        }
    }

    /// Sets the function of `faces`; `GL_INVALID_ENUM` for an unknown function. The reference
    /// clamps to [0, 2^s − 1] for the s = 8 stencil bits.
    fn stencil_func(&mut self, faces: &[usize], func: GLenum, reference: GLint, mask: GLuint, command: &'static str) {
        let Some(func) = COMPARE.parse(func) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        let reference = reference.clamp(0, (1 << STENCIL_BITS) - 1);
        self.set_stencil(faces, |s| (s.func, s.reference, s.value_mask) = (func, reference, mask));
    }

    /// Sets the operations of `faces`; `GL_INVALID_ENUM` for an unknown operation.
    fn stencil_op(&mut self, faces: &[usize], ops: [GLenum; 3], command: &'static str) {
        let [Some(fail), Some(zfail), Some(zpass)] = ops.map(|o| STENCIL_OP.parse(o)) else {
            return self.set_error_in(gl::GL_INVALID_ENUM, command);
        };
        self.set_stencil(faces, |s| (s.fail, s.depth_fail, s.depth_pass) = (fail, zfail, zpass));
    }

    /// `glStencilFunc`: the active faces (both, unless `glActiveStencilFaceEXT(GL_BACK)`).
    pub fn glStencilFunc(&mut self, func: GLenum, reference: GLint, mask: GLuint) {
        let faces = self.fixed.fragment.stencil.active_faces();
        self.stencil_func(faces, func, reference, mask, "glStencilFunc");
    }

    /// `glStencilOp`, with OpenGL 1.4's `GL_INCR_WRAP` and `GL_DECR_WRAP`.
    pub fn glStencilOp(&mut self, fail: GLenum, zfail: GLenum, zpass: GLenum) {
        let faces = self.fixed.fragment.stencil.active_faces();
        self.stencil_op(faces, [fail, zfail, zpass], "glStencilOp");
    }

    /// `glStencilMask`.
    pub fn glStencilMask(&mut self, mask: GLuint) {
        let faces = self.fixed.fragment.stencil.active_faces();
        self.set_stencil(faces, |s| s.write_mask = mask);
    }

    /// `glStencilFuncSeparate` (OpenGL 2.0).
    pub fn glStencilFuncSeparate(&mut self, face: GLenum, func: GLenum, reference: GLint, mask: GLuint) {
        let Some(faces) = separate_faces(face) else { return self.set_error_in(gl::GL_INVALID_ENUM, "glStencilFuncSeparate") };
        self.stencil_func(faces, func, reference, mask, "glStencilFuncSeparate");
    }

    /// `glStencilOpSeparate` (OpenGL 2.0; `glStencilOpSeparateATI` is the same command).
    pub fn glStencilOpSeparate(&mut self, face: GLenum, sfail: GLenum, dpfail: GLenum, dppass: GLenum) {
        let Some(faces) = separate_faces(face) else { return self.set_error_in(gl::GL_INVALID_ENUM, "glStencilOpSeparate") };
        self.stencil_op(faces, [sfail, dpfail, dppass], "glStencilOpSeparate");
    }

    /// `glStencilMaskSeparate` (OpenGL 2.0).
    pub fn glStencilMaskSeparate(&mut self, face: GLenum, mask: GLuint) {
        let Some(faces) = separate_faces(face) else { return self.set_error_in(gl::GL_INVALID_ENUM, "glStencilMaskSeparate") };
        self.set_stencil(faces, |s| s.write_mask = mask);
    }

    /// `glStencilFuncSeparateATI` (`GL_ATI_separate_stencil`): a function per face, one
    /// reference and mask for both.
    pub fn glStencilFuncSeparateATI(&mut self, frontfunc: GLenum, backfunc: GLenum, reference: GLint, mask: GLuint) {
        if COMPARE.parse(frontfunc).is_none() || COMPARE.parse(backfunc).is_none() {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glStencilFuncSeparateATI");
        }
        self.stencil_func(&[FRONT], frontfunc, reference, mask, "glStencilFuncSeparateATI");
        self.stencil_func(&[BACK], backfunc, reference, mask, "glStencilFuncSeparateATI");
    }

    /// `glActiveStencilFaceEXT` (`GL_EXT_stencil_two_side`): `GL_FRONT` or `GL_BACK`.
    pub fn glActiveStencilFaceEXT(&mut self, face: GLenum) {
        let active = match face {
            gl::GL_FRONT => FRONT,
            gl::GL_BACK => BACK_EXT,
            _ => return self.set_error_in(gl::GL_INVALID_ENUM, "glActiveStencilFaceEXT"),
        };
        self.fixed_mut().fragment.stencil.active = active;
    }

    /// Stencil queries (table 6.19 of OpenGL 2.0, and `GL_ACTIVE_STENCIL_FACE_EXT`).
    pub(crate) fn query_stencil(&self, pname: GLenum) -> Option<Value> {
        let state = &self.fixed.fragment.stencil;
        let (s, back) = (&state.faces[state.active], &state.faces[BACK]);
        Some(match pname {
            gl::GL_STENCIL_FUNC => COMPARE.value(s.func),
            gl::GL_STENCIL_REF => Value::int(s.reference),
            gl::GL_STENCIL_VALUE_MASK => mask_value(s.value_mask),
            gl::GL_STENCIL_FAIL => STENCIL_OP.value(s.fail),
            gl::GL_STENCIL_PASS_DEPTH_FAIL => STENCIL_OP.value(s.depth_fail),
            gl::GL_STENCIL_PASS_DEPTH_PASS => STENCIL_OP.value(s.depth_pass),
            gl::GL_STENCIL_WRITEMASK => mask_value(s.write_mask),
            gl::GL_STENCIL_BACK_FUNC => COMPARE.value(back.func),
            gl::GL_STENCIL_BACK_REF => Value::int(back.reference),
            gl::GL_STENCIL_BACK_VALUE_MASK => mask_value(back.value_mask),
            gl::GL_STENCIL_BACK_FAIL => STENCIL_OP.value(back.fail),
            gl::GL_STENCIL_BACK_PASS_DEPTH_FAIL => STENCIL_OP.value(back.depth_fail),
            gl::GL_STENCIL_BACK_PASS_DEPTH_PASS => STENCIL_OP.value(back.depth_pass),
            gl::GL_STENCIL_BACK_WRITEMASK => mask_value(back.write_mask),
            gl::GL_ACTIVE_STENCIL_FACE_EXT => Value::int(if state.active == FRONT { gl::GL_FRONT } else { gl::GL_BACK } as i32),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::frame::state::{CompareFunc, StencilOp};
    use crate::translate::Context;
    use crate::translate::gl;

    fn int(ctx: &Context, pname: gl::GLenum) -> i32 {
        ctx.query(pname).unwrap().to_ints()[0]
    }

    #[test]
    fn one_face_commands_set_both_faces() {
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(int(&ctx, gl::GL_STENCIL_VALUE_MASK), -1);
        ctx.glStencilFunc(gl::GL_EQUAL, 300, 0x0f);
        ctx.glStencilOp(gl::GL_INCR_WRAP, gl::GL_DECR_WRAP, gl::GL_INVERT);
        ctx.glStencilMask(0xf0);
        for (front, back) in [
            (gl::GL_STENCIL_FUNC, gl::GL_STENCIL_BACK_FUNC),
            (gl::GL_STENCIL_REF, gl::GL_STENCIL_BACK_REF),
            (gl::GL_STENCIL_VALUE_MASK, gl::GL_STENCIL_BACK_VALUE_MASK),
            (gl::GL_STENCIL_FAIL, gl::GL_STENCIL_BACK_FAIL),
            (gl::GL_STENCIL_PASS_DEPTH_FAIL, gl::GL_STENCIL_BACK_PASS_DEPTH_FAIL),
            (gl::GL_STENCIL_PASS_DEPTH_PASS, gl::GL_STENCIL_BACK_PASS_DEPTH_PASS),
            (gl::GL_STENCIL_WRITEMASK, gl::GL_STENCIL_BACK_WRITEMASK),
        ] {
            assert_eq!(int(&ctx, front), int(&ctx, back), "{front:#x}");
        }
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_REF), 255);
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_FUNC), gl::GL_EQUAL as i32);
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_PASS_DEPTH_PASS), gl::GL_INVERT as i32);
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_WRITEMASK), 0xf0);
        ctx.glStencilOp(gl::GL_KEEP, gl::GL_LESS, gl::GL_KEEP);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }

    #[test]
    fn separate_commands_set_the_named_faces() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glStencilFuncSeparate(gl::GL_BACK, gl::GL_GREATER, -4, 0x3);
        ctx.glStencilOpSeparate(gl::GL_FRONT, gl::GL_ZERO, gl::GL_INCR, gl::GL_DECR);
        ctx.glStencilMaskSeparate(gl::GL_FRONT_AND_BACK, 0x7);
        assert_eq!(int(&ctx, gl::GL_STENCIL_FUNC), gl::GL_ALWAYS as i32);
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_FUNC), gl::GL_GREATER as i32);
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_REF), 0);
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_VALUE_MASK), 3);
        assert_eq!(int(&ctx, gl::GL_STENCIL_FAIL), gl::GL_ZERO as i32);
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_FAIL), gl::GL_KEEP as i32);
        assert_eq!([int(&ctx, gl::GL_STENCIL_WRITEMASK), int(&ctx, gl::GL_STENCIL_BACK_WRITEMASK)], [7, 7]);
        for bad in [gl::GL_LEFT, gl::GL_NONE] {
            ctx.glStencilFuncSeparate(bad, gl::GL_LESS, 0, 0);
            assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
            ctx.glStencilOpSeparate(bad, gl::GL_KEEP, gl::GL_KEEP, gl::GL_KEEP);
            assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
            ctx.glStencilMaskSeparate(bad, 0);
            assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        }
        ctx.glStencilFuncSeparate(gl::GL_FRONT, gl::GL_KEEP, 0, 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glStencilFuncSeparateATI(gl::GL_NEVER, gl::GL_LEQUAL, 9, 0xff);
        assert_eq!(int(&ctx, gl::GL_STENCIL_FUNC), gl::GL_NEVER as i32);
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_FUNC), gl::GL_LEQUAL as i32);
        assert_eq!([int(&ctx, gl::GL_STENCIL_REF), int(&ctx, gl::GL_STENCIL_BACK_REF)], [9, 9]);
        ctx.glStencilFuncSeparateATI(gl::GL_NEVER, gl::GL_INCR, 1, 1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        assert_eq!(int(&ctx, gl::GL_STENCIL_REF), 9, "nothing changed");
    }

    #[test]
    fn two_side_ext_has_its_own_back_state() {
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(int(&ctx, gl::GL_ACTIVE_STENCIL_FACE_EXT), gl::GL_FRONT as i32);
        ctx.glActiveStencilFaceEXT(gl::GL_BACK);
        ctx.glStencilFunc(gl::GL_NOTEQUAL, 5, 0xf);
        ctx.glStencilOp(gl::GL_KEEP, gl::GL_KEEP, gl::GL_DECR_WRAP);
        assert_eq!(int(&ctx, gl::GL_ACTIVE_STENCIL_FACE_EXT), gl::GL_BACK as i32);
        assert_eq!(int(&ctx, gl::GL_STENCIL_FUNC), gl::GL_NOTEQUAL as i32, "queries read the active face");
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_FUNC), gl::GL_ALWAYS as i32, "OpenGL 2.0's back state is apart");
        ctx.glActiveStencilFaceEXT(gl::GL_FRONT);
        ctx.glStencilOp(gl::GL_KEEP, gl::GL_KEEP, gl::GL_INCR_WRAP);
        assert_eq!(int(&ctx, gl::GL_STENCIL_FUNC), gl::GL_ALWAYS as i32);
        ctx.glActiveStencilFaceEXT(gl::GL_FRONT_AND_BACK);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);

        let stencil = ctx.fixed.fragment.stencil;
        let off = stencil.for_draw(false);
        assert_eq!((off.front.depth_pass, off.back.depth_pass), (StencilOp::IncrWrap, StencilOp::IncrWrap));
        let on = stencil.for_draw(true);
        assert_eq!((on.front.depth_pass, on.back.depth_pass), (StencilOp::IncrWrap, StencilOp::DecrWrap));
        assert_eq!((on.back.func, on.back.reference, on.back.value_mask), (CompareFunc::NotEqual, 5, 0xf));

        // The enable reaches the draw's state; glPushAttrib(GL_STENCIL_BUFFER_BIT) keeps it
        // and the active face.
        ctx.glEnable(gl::GL_STENCIL_TEST);
        ctx.glEnable(gl::GL_STENCIL_TEST_TWO_SIDE_EXT);
        assert_eq!(ctx.glIsEnabled(gl::GL_STENCIL_TEST_TWO_SIDE_EXT), 1);
        ctx.glPushAttrib(gl::GL_STENCIL_BUFFER_BIT);
        ctx.glActiveStencilFaceEXT(gl::GL_BACK);
        ctx.glDisable(gl::GL_STENCIL_TEST_TWO_SIDE_EXT);
        ctx.glStencilFuncSeparate(gl::GL_FRONT, gl::GL_NEVER, 0, 0);
        ctx.glPopAttrib();
        assert_eq!(ctx.glIsEnabled(gl::GL_STENCIL_TEST_TWO_SIDE_EXT), 1);
        assert_eq!(int(&ctx, gl::GL_ACTIVE_STENCIL_FACE_EXT), gl::GL_FRONT as i32);
        assert_eq!(int(&ctx, gl::GL_STENCIL_FUNC), gl::GL_ALWAYS as i32);
        let state = ctx.raster_snapshot();
        assert_eq!(state.stencil.map(|s| s.back.depth_pass), Some(StencilOp::DecrWrap));
    }

    #[test]
    fn separate_stencil_in_display_lists() {
        use crate::translate::dispatch;
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
            dispatch::glStencilFuncSeparate(&mut ctx, gl::GL_BACK, gl::GL_LESS, 3, 1);
            dispatch::glStencilMaskSeparate(&mut ctx, gl::GL_BACK, 0x11);
            dispatch::glActiveStencilFaceEXT(&mut ctx, gl::GL_BACK);
            dispatch::glEndList(&mut ctx);
        }
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_FUNC), gl::GL_ALWAYS as i32, "compiled, not executed");
        unsafe { dispatch::glCallList(&mut ctx, 1) };
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_FUNC), gl::GL_LESS as i32);
        assert_eq!(int(&ctx, gl::GL_STENCIL_BACK_WRITEMASK), 0x11);
        assert_eq!(int(&ctx, gl::GL_ACTIVE_STENCIL_FACE_EXT), gl::GL_BACK as i32);
    }
}
