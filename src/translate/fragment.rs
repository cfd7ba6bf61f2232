//! Per-fragment operations (OpenGL 1.5 sections 4.1 and 4.2.2): alpha test, depth,
//! blending, logic operation and the buffer write masks, with their queries (tables 6.17 to
//! 6.19). The tests are enabled with `glEnable`; this module holds their parameters (the
//! stencil test's are in [`super::stencil`]).

use super::Context;
use super::enums::{BLEND_DST, BLEND_EQUATION, COMPARE, LOGIC_OP, valid_dst_factor};
use super::get::Value;
use super::gl::{self, GLboolean, GLclampf, GLenum, GLuint};
use super::stencil::{StencilState, mask_value};
use crate::frame::state::{Blend, BlendFactor, CompareFunc, LogicOp};

/// Per-fragment operation parameters of a context.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FragmentState {
    /// `glAlphaFunc`: comparison and reference, clamped to [0, 1].
    pub alpha: (CompareFunc, f32),
    /// Blend factors, equation and constant colour.
    pub blend: Blend,
    /// `glLogicOp`.
    pub logic_op: LogicOp,
    /// `glDepthFunc`.
    pub depth_func: CompareFunc,
    /// `glDepthMask`.
    pub depth_write: bool,
    /// The stencil test's parameters ([`super::stencil`]).
    pub stencil: StencilState,
    /// `glColorMask`.
    pub color_mask: [bool; 4],
    /// `glIndexMask`.
    pub index_mask: u32,
}

impl Default for FragmentState {
    fn default() -> FragmentState {
        FragmentState {
            alpha: (CompareFunc::Always, 0.0),
            blend: Blend::default(),
            logic_op: LogicOp::Copy,
            depth_func: CompareFunc::Less,
            depth_write: true,
            stencil: StencilState::default(),
            color_mask: [true; 4],
            index_mask: u32::MAX,
        }
    }
}

impl Context {
    /// `glAlphaFunc`: the reference clamps to [0, 1].
    pub fn glAlphaFunc(&mut self, func: GLenum, reference: GLclampf) {
        match COMPARE.parse(func) {
            Some(f) => self.fixed_mut().fragment.alpha = (f, reference.clamp(0.0, 1.0)),
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glAlphaFunc"),
        }
    }

    /// `glBlendFunc`: the same factors for colour and alpha.
    pub fn glBlendFunc(&mut self, sfactor: GLenum, dfactor: GLenum) {
        self.set_blend_func([sfactor, dfactor, sfactor, dfactor], "glBlendFunc");
    }

    /// `glBlendFuncSeparate` (OpenGL 1.4, EXT_blend_func_separate).
    pub fn glBlendFuncSeparate(&mut self, src_rgb: GLenum, dst_rgb: GLenum, src_alpha: GLenum, dst_alpha: GLenum) {
        self.set_blend_func([src_rgb, dst_rgb, src_alpha, dst_alpha], "glBlendFuncSeparate");
    }

    /// Sets `[src rgb, dst rgb, src alpha, dst alpha]`; `GL_INVALID_ENUM` for an unknown
    /// factor or `GL_SRC_ALPHA_SATURATE` as a destination (table 4.2).
    fn set_blend_func(&mut self, factors: [GLenum; 4], command: &'static str) {
        let parsed = factors.map(|f| BLEND_DST.parse(f));
        let [Some(sr), Some(dr), Some(sa), Some(da)] = parsed else {
            return self.set_error_in(gl::GL_INVALID_ENUM, command);
        };
        if !valid_dst_factor(dr) || !valid_dst_factor(da) {
            return self.set_error_in(gl::GL_INVALID_ENUM, command);
        }
        let b = &mut self.fixed_mut().fragment.blend;
        (b.src_rgb, b.dst_rgb, b.src_alpha, b.dst_alpha) = (sr, dr, sa, da);
    }

    /// `glBlendColor`: each component clamps to [0, 1].
    pub fn glBlendColor(&mut self, red: GLclampf, green: GLclampf, blue: GLclampf, alpha: GLclampf) {
        self.fixed_mut().fragment.blend.color = [red, green, blue, alpha].map(|c| c.clamp(0.0, 1.0));
    }

    /// `glBlendEquation`: add, subtract, reverse subtract, min, max, for every channel.
    pub fn glBlendEquation(&mut self, mode: GLenum) {
        self.set_blend_equation([mode, mode], "glBlendEquation");
    }

    /// `glBlendEquationSeparate` (OpenGL 2.0, `GL_EXT_blend_equation_separate`): one equation
    /// for the colour channels, one for alpha.
    pub fn glBlendEquationSeparate(&mut self, mode_rgb: GLenum, mode_alpha: GLenum) {
        self.set_blend_equation([mode_rgb, mode_alpha], "glBlendEquationSeparate");
    }

    /// Sets the `[rgb, alpha]` equations; `GL_INVALID_ENUM` if either is unknown.
    fn set_blend_equation(&mut self, modes: [GLenum; 2], command: &'static str) {
        let [Some(rgb), Some(alpha)] = modes.map(|m| BLEND_EQUATION.parse(m)) else {
            return self.set_error_in(gl::GL_INVALID_ENUM, command);
        };
        let b = &mut self.fixed_mut().fragment.blend;
        (b.equation_rgb, b.equation_alpha) = (rgb, alpha);
    }

    /// `glLogicOp`.
    pub fn glLogicOp(&mut self, opcode: GLenum) {
        match LOGIC_OP.parse(opcode) {
            Some(op) => self.fixed_mut().fragment.logic_op = op,
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glLogicOp"),
        }
    }

    /// `glDepthFunc`.
    pub fn glDepthFunc(&mut self, func: GLenum) {
        match COMPARE.parse(func) {
            Some(f) => self.fixed_mut().fragment.depth_func = f,
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glDepthFunc"),
        }
    }

    /// `glDepthMask`.
    pub fn glDepthMask(&mut self, flag: GLboolean) {
        self.fixed_mut().fragment.depth_write = flag != 0;
    }

    /// `glColorMask`.
    pub fn glColorMask(&mut self, red: GLboolean, green: GLboolean, blue: GLboolean, alpha: GLboolean) {
        self.fixed_mut().fragment.color_mask = [red, green, blue, alpha].map(|c| c != 0);
    }

    /// `glIndexMask`.
    pub fn glIndexMask(&mut self, mask: GLuint) {
        self.fixed_mut().fragment.index_mask = mask;
    }

    /// Per-fragment queries (tables 6.17 and 6.18).
    pub(crate) fn query_fragment(&self, pname: GLenum) -> Option<Value> {
        let f = &self.fixed.fragment;
        let factor = |x: BlendFactor| BLEND_DST.value(x);
        Some(match pname {
            gl::GL_ALPHA_TEST_FUNC => COMPARE.value(f.alpha.0),
            gl::GL_ALPHA_TEST_REF => Value::Normalized(vec![f64::from(f.alpha.1)]),
            gl::GL_BLEND_SRC | gl::GL_BLEND_SRC_RGB => factor(f.blend.src_rgb),
            gl::GL_BLEND_DST | gl::GL_BLEND_DST_RGB => factor(f.blend.dst_rgb),
            gl::GL_BLEND_SRC_ALPHA => factor(f.blend.src_alpha),
            gl::GL_BLEND_DST_ALPHA => factor(f.blend.dst_alpha),
            gl::GL_BLEND_EQUATION_RGB => BLEND_EQUATION.value(f.blend.equation_rgb),
            gl::GL_BLEND_EQUATION_ALPHA => BLEND_EQUATION.value(f.blend.equation_alpha),
            gl::GL_BLEND_COLOR => Value::normalized(&f.blend.color),
            gl::GL_LOGIC_OP_MODE => LOGIC_OP.value(f.logic_op),
            gl::GL_DEPTH_FUNC => COMPARE.value(f.depth_func),
            gl::GL_DEPTH_WRITEMASK => Value::bool(f.depth_write),
            gl::GL_COLOR_WRITEMASK => Value::Bool(f.color_mask.to_vec()),
            gl::GL_INDEX_WRITEMASK => mask_value(f.index_mask),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::gl;

    fn int(ctx: &Context, pname: gl::GLenum) -> i32 {
        ctx.query(pname).unwrap().to_ints()[0]
    }

    #[test]
    fn blend_state_errors_and_queries() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBlendFunc(gl::GL_SRC_ALPHA, gl::GL_ONE_MINUS_SRC_ALPHA);
        assert_eq!(int(&ctx, gl::GL_BLEND_SRC), gl::GL_SRC_ALPHA as i32);
        assert_eq!(int(&ctx, gl::GL_BLEND_DST_ALPHA), gl::GL_ONE_MINUS_SRC_ALPHA as i32);
        ctx.glBlendFunc(gl::GL_ONE, gl::GL_SRC_ALPHA_SATURATE);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glBlendFuncSeparate(gl::GL_ONE, gl::GL_ZERO, gl::GL_SRC_ALPHA_SATURATE, gl::GL_DST_COLOR);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(int(&ctx, gl::GL_BLEND_SRC_ALPHA), gl::GL_SRC_ALPHA_SATURATE as i32);
        assert_eq!(int(&ctx, gl::GL_BLEND_DST), gl::GL_ZERO as i32);
        ctx.glBlendFuncSeparate(gl::GL_ONE, gl::GL_ZERO, gl::GL_LESS, gl::GL_ZERO);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glBlendEquation(gl::GL_MAX);
        assert_eq!(int(&ctx, gl::GL_BLEND_EQUATION), gl::GL_MAX as i32);
        assert_eq!(int(&ctx, gl::GL_BLEND_EQUATION_ALPHA), gl::GL_MAX as i32);
        ctx.glBlendEquation(gl::GL_ONE);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glBlendEquationSeparate(gl::GL_FUNC_SUBTRACT, gl::GL_MIN);
        assert_eq!(int(&ctx, gl::GL_BLEND_EQUATION_RGB), gl::GL_FUNC_SUBTRACT as i32);
        assert_eq!(int(&ctx, gl::GL_BLEND_EQUATION), gl::GL_FUNC_SUBTRACT as i32, "the same name as _RGB");
        assert_eq!(int(&ctx, gl::GL_BLEND_EQUATION_ALPHA), gl::GL_MIN as i32);
        ctx.glBlendEquationSeparate(gl::GL_FUNC_ADD, gl::GL_ZERO);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        assert_eq!(int(&ctx, gl::GL_BLEND_EQUATION_RGB), gl::GL_FUNC_SUBTRACT as i32, "unchanged after an error");
        ctx.glBlendColor(2.0, 0.5, -1.0, 1.0);
        let mut c = [0i32; 4];
        unsafe { ctx.glGetIntegerv(gl::GL_BLEND_COLOR, c.as_mut_ptr()) };
        assert_eq!([c[0], c[2], c[3]], [i32::MAX, 0, i32::MAX]);
        assert!((c[1] - i32::MAX / 2).abs() <= 1, "{c:?}");
        ctx.glLogicOp(gl::GL_XOR);
        assert_eq!(int(&ctx, gl::GL_LOGIC_OP_MODE), gl::GL_XOR as i32);
        ctx.glLogicOp(gl::GL_ZERO);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }

    #[test]
    fn depth_alpha_and_masks() {
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(int(&ctx, gl::GL_DEPTH_FUNC), gl::GL_LESS as i32);
        ctx.glDepthFunc(gl::GL_LEQUAL);
        ctx.glDepthMask(0);
        assert_eq!(int(&ctx, gl::GL_DEPTH_FUNC), gl::GL_LEQUAL as i32);
        assert_eq!(int(&ctx, gl::GL_DEPTH_WRITEMASK), 0);
        ctx.glDepthFunc(gl::GL_KEEP);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glAlphaFunc(gl::GL_GREATER, 1.5);
        assert_eq!(int(&ctx, gl::GL_ALPHA_TEST_FUNC), gl::GL_GREATER as i32);
        assert_eq!(ctx.query(gl::GL_ALPHA_TEST_REF).unwrap().to_doubles(), [1.0]);
        ctx.glAlphaFunc(gl::GL_ZERO, 0.5);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glColorMask(1, 0, 1, 0);
        assert_eq!(ctx.query(gl::GL_COLOR_WRITEMASK).unwrap().to_bools(), [1, 0, 1, 0]);
        ctx.glIndexMask(7);
        assert_eq!(int(&ctx, gl::GL_INDEX_WRITEMASK), 7);
    }
}
