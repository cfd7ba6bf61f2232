//! Coordinate transformations (OpenGL 1.5 section 2.11): the matrix mode, the modelview,
//! projection and per-unit texture matrix stacks, and the commands that change them.

use glam::{DMat4, DVec3, Mat4};

use super::Context;
use super::convert::read_array;
use super::get::Value;
use super::gl::{self, GLdouble, GLenum, GLfloat};
use super::limits::{
    MAX_MODELVIEW_STACK_DEPTH, MAX_PROJECTION_STACK_DEPTH, MAX_TEXTURE_STACK_DEPTH, MAX_TEXTURE_UNITS,
};
use super::lists::ListOp;

/// Which stack matrix commands act on (`glMatrixMode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum MatrixMode {
    /// `GL_MODELVIEW`.
    #[default]
    Modelview,
    /// `GL_PROJECTION`.
    Projection,
    /// `GL_TEXTURE` (of the active texture unit).
    Texture,
}

/// A matrix stack: the top is the current matrix; never empty.
#[derive(Clone, Debug)]
pub struct MatrixStack {
    stack: Vec<DMat4>,
    max_depth: usize,
}

impl MatrixStack {
    fn new(max_depth: usize) -> MatrixStack {
        MatrixStack { stack: vec![DMat4::IDENTITY], max_depth }
    }

    /// The current matrix.
    pub fn top(&self) -> DMat4 {
        *self.stack.last().expect("matrix stack is never empty")
    }

    fn top_mut(&mut self) -> &mut DMat4 {
        self.stack.last_mut().expect("matrix stack is never empty")
    }

    /// Depth, counting the current matrix.
    pub fn depth(&self) -> usize {
        self.stack.len()
    }
}

/// Transformation state.
#[derive(Clone, Debug)]
pub struct TransformState {
    /// `GL_MATRIX_MODE`.
    pub mode: MatrixMode,
    /// `GL_MODELVIEW` stack.
    pub modelview: MatrixStack,
    /// `GL_PROJECTION` stack.
    pub projection: MatrixStack,
    /// `GL_TEXTURE` stacks, one per texture unit.
    pub texture: Vec<MatrixStack>,
    /// Bumped whenever the modelview or projection changes, so snapshots can be cached.
    pub version: u64,
}

impl Default for TransformState {
    fn default() -> TransformState {
        TransformState {
            mode: MatrixMode::Modelview,
            modelview: MatrixStack::new(MAX_MODELVIEW_STACK_DEPTH),
            projection: MatrixStack::new(MAX_PROJECTION_STACK_DEPTH),
            texture: vec![MatrixStack::new(MAX_TEXTURE_STACK_DEPTH); MAX_TEXTURE_UNITS],
            version: 0,
        }
    }
}

impl TransformState {
    /// The current modelview matrix.
    pub fn modelview(&self) -> Mat4 {
        self.modelview.top().as_mat4()
    }
    /// The current projection matrix.
    pub fn projection(&self) -> Mat4 {
        self.projection.top().as_mat4()
    }
    /// The current texture matrix of `unit`.
    pub fn texture_matrix(&self, unit: usize) -> Mat4 {
        self.texture[unit].top().as_mat4()
    }
}

impl Context {
    fn current_stack(&mut self) -> &mut MatrixStack {
        let unit = self.active_texture_unit();
        let t = &mut self.transform;
        t.version += 1;
        match t.mode {
            MatrixMode::Modelview => &mut t.modelview,
            MatrixMode::Projection => &mut t.projection,
            MatrixMode::Texture => &mut t.texture[unit],
        }
    }

    /// Replaces the current matrix with `f(current)`.
    fn change_matrix(&mut self, f: impl FnOnce(DMat4) -> DMat4) {
        let m = self.current_stack().top_mut();
        *m = f(*m);
    }

    /// `glMatrixMode`.
    pub fn glMatrixMode(&mut self, mode: GLenum) {
        self.transform.mode = match mode {
            gl::GL_MODELVIEW => MatrixMode::Modelview,
            gl::GL_PROJECTION => MatrixMode::Projection,
            gl::GL_TEXTURE => MatrixMode::Texture,
            _ => return self.set_error_in(gl::GL_INVALID_ENUM, "glMatrixMode"),
        };
    }

    /// `glLoadIdentity`.
    pub fn glLoadIdentity(&mut self) {
        self.change_matrix(|_| DMat4::IDENTITY);
    }

    /// `glPushMatrix`: `GL_STACK_OVERFLOW` when the stack is full.
    pub fn glPushMatrix(&mut self) {
        let stack = self.current_stack();
        if stack.stack.len() >= stack.max_depth {
            return self.set_error_in(gl::GL_STACK_OVERFLOW, "glPushMatrix");
        }
        let top = stack.top();
        stack.stack.push(top);
    }

    /// `glPopMatrix`: `GL_STACK_UNDERFLOW` when only one matrix is left.
    pub fn glPopMatrix(&mut self) {
        let stack = self.current_stack();
        if stack.stack.len() <= 1 {
            return self.set_error_in(gl::GL_STACK_UNDERFLOW, "glPopMatrix");
        }
        stack.stack.pop();
    }

    /// `glLoadMatrixd`: `m` is column-major.
    ///
    /// # Safety
    /// `m` must point to 16 doubles.
    pub unsafe fn glLoadMatrixd(&mut self, m: *const GLdouble) {
        let Some(m) = (unsafe { read_array::<_, 16>(m) }) else { return self.null_pointer("glLoadMatrixd") };
        self.change_matrix(|_| DMat4::from_cols_array(&m));
    }

    /// `glLoadMatrixf`.
    ///
    /// # Safety
    /// `m` must point to 16 floats.
    pub unsafe fn glLoadMatrixf(&mut self, m: *const GLfloat) {
        let Some(m) = (unsafe { read_array::<_, 16>(m) }) else { return self.null_pointer("glLoadMatrixf") };
        self.change_matrix(|_| Mat4::from_cols_array(&m).as_dmat4());
    }

    /// `glMultMatrixd`: current = current × m.
    ///
    /// # Safety
    /// `m` must point to 16 doubles.
    pub unsafe fn glMultMatrixd(&mut self, m: *const GLdouble) {
        let Some(m) = (unsafe { read_array::<_, 16>(m) }) else { return self.null_pointer("glMultMatrixd") };
        self.change_matrix(|c| c * DMat4::from_cols_array(&m));
    }

    /// `glMultMatrixf`.
    ///
    /// # Safety
    /// `m` must point to 16 floats.
    pub unsafe fn glMultMatrixf(&mut self, m: *const GLfloat) {
        let Some(m) = (unsafe { read_array::<_, 16>(m) }) else { return self.null_pointer("glMultMatrixf") };
        self.change_matrix(|c| c * Mat4::from_cols_array(&m).as_dmat4());
    }

    /// `glLoadTransposeMatrixd`: `m` is row-major.
    ///
    /// # Safety
    /// `m` must point to 16 doubles.
    pub unsafe fn glLoadTransposeMatrixd(&mut self, m: *const GLdouble) {
        let Some(m) = (unsafe { read_array::<_, 16>(m) }) else { return self.null_pointer("glLoadTransposeMatrixd") };
        self.change_matrix(|_| DMat4::from_cols_array(&m).transpose());
    }

    /// `glLoadTransposeMatrixf`.
    ///
    /// # Safety
    /// `m` must point to 16 floats.
    pub unsafe fn glLoadTransposeMatrixf(&mut self, m: *const GLfloat) {
        let Some(m) = (unsafe { read_array::<_, 16>(m) }) else { return self.null_pointer("glLoadTransposeMatrixf") };
        self.change_matrix(|_| Mat4::from_cols_array(&m).as_dmat4().transpose());
    }

    /// `glMultTransposeMatrixd`.
    ///
    /// # Safety
    /// `m` must point to 16 doubles.
    pub unsafe fn glMultTransposeMatrixd(&mut self, m: *const GLdouble) {
        let Some(m) = (unsafe { read_array::<_, 16>(m) }) else { return self.null_pointer("glMultTransposeMatrixd") };
        self.change_matrix(|c| c * DMat4::from_cols_array(&m).transpose());
    }

    /// `glMultTransposeMatrixf`.
    ///
    /// # Safety
    /// `m` must point to 16 floats.
    pub unsafe fn glMultTransposeMatrixf(&mut self, m: *const GLfloat) {
        let Some(m) = (unsafe { read_array::<_, 16>(m) }) else { return self.null_pointer("glMultTransposeMatrixf") };
        self.change_matrix(|c| c * Mat4::from_cols_array(&m).as_dmat4().transpose());
    }

    /// `glRotated`: rotation by `angle` degrees about (x, y, z); a zero axis leaves the matrix
    /// unchanged.
    pub fn glRotated(&mut self, angle: GLdouble, x: GLdouble, y: GLdouble, z: GLdouble) {
        let axis = DVec3::new(x, y, z);
        if axis.length_squared() == 0.0 {
            return;
        }
        let r = DMat4::from_axis_angle(axis.normalize(), angle.to_radians());
        self.change_matrix(|c| c * r);
    }

    /// `glRotatef`.
    pub fn glRotatef(&mut self, angle: GLfloat, x: GLfloat, y: GLfloat, z: GLfloat) {
        self.glRotated(angle.into(), x.into(), y.into(), z.into());
    }

    /// `glTranslated`.
    pub fn glTranslated(&mut self, x: GLdouble, y: GLdouble, z: GLdouble) {
        self.change_matrix(|c| c * DMat4::from_translation(DVec3::new(x, y, z)));
    }

    /// `glTranslatef`.
    pub fn glTranslatef(&mut self, x: GLfloat, y: GLfloat, z: GLfloat) {
        self.glTranslated(x.into(), y.into(), z.into());
    }

    /// `glScaled`.
    pub fn glScaled(&mut self, x: GLdouble, y: GLdouble, z: GLdouble) {
        self.change_matrix(|c| c * DMat4::from_scale(DVec3::new(x, y, z)));
    }

    /// `glScalef`.
    pub fn glScalef(&mut self, x: GLfloat, y: GLfloat, z: GLfloat) {
        self.glScaled(x.into(), y.into(), z.into());
    }

    /// `glFrustum` (equation 2.7); `GL_INVALID_VALUE` for non-positive near or far, or an
    /// empty volume.
    pub fn glFrustum(&mut self, l: GLdouble, r: GLdouble, b: GLdouble, t: GLdouble, n: GLdouble, f: GLdouble) {
        if n <= 0.0 || f <= 0.0 || l == r || b == t || n == f {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glFrustum");
        }
        let m = DMat4::from_cols_array(&[
            2.0 * n / (r - l), 0.0, 0.0, 0.0,
            0.0, 2.0 * n / (t - b), 0.0, 0.0,
            (r + l) / (r - l), (t + b) / (t - b), -(f + n) / (f - n), -1.0,
            0.0, 0.0, -2.0 * f * n / (f - n), 0.0,
        ]);
        self.change_matrix(|c| c * m);
    }

    /// `glOrtho` (equation 2.8); `GL_INVALID_VALUE` for an empty volume.
    pub fn glOrtho(&mut self, l: GLdouble, r: GLdouble, b: GLdouble, t: GLdouble, n: GLdouble, f: GLdouble) {
        if l == r || b == t || n == f {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glOrtho");
        }
        let m = DMat4::from_cols_array(&[
            2.0 / (r - l), 0.0, 0.0, 0.0,
            0.0, 2.0 / (t - b), 0.0, 0.0,
            0.0, 0.0, -2.0 / (f - n), 0.0,
            -(r + l) / (r - l), -(t + b) / (t - b), -(f + n) / (f - n), 1.0,
        ]);
        self.change_matrix(|c| c * m);
    }

    /// Records a matrix command that reads 16 client values.
    unsafe fn compile_matrix<T: Copy + Send + Sync + 'static>(
        &mut self,
        m: *const T,
        name: &'static str,
        run: unsafe fn(&mut Context, *const T),
    ) {
        let Some(m) = (unsafe { read_array::<T, 16>(m) }) else { return self.null_pointer(name) };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| unsafe { run(ctx, m.as_ptr()) })));
    }

    /// `glLoadMatrixd` in a display list.
    ///
    /// # Safety
    /// As [`Context::glLoadMatrixd`].
    pub unsafe fn compile_glLoadMatrixd(&mut self, m: *const GLdouble) {
        unsafe { self.compile_matrix(m, "glLoadMatrixd", super::dispatch::exec_glLoadMatrixd) }
    }
    /// `glLoadMatrixf` in a display list.
    ///
    /// # Safety
    /// As [`Context::glLoadMatrixf`].
    pub unsafe fn compile_glLoadMatrixf(&mut self, m: *const GLfloat) {
        unsafe { self.compile_matrix(m, "glLoadMatrixf", super::dispatch::exec_glLoadMatrixf) }
    }
    /// `glMultMatrixd` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMultMatrixd`].
    pub unsafe fn compile_glMultMatrixd(&mut self, m: *const GLdouble) {
        unsafe { self.compile_matrix(m, "glMultMatrixd", super::dispatch::exec_glMultMatrixd) }
    }
    /// `glMultMatrixf` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMultMatrixf`].
    pub unsafe fn compile_glMultMatrixf(&mut self, m: *const GLfloat) {
        unsafe { self.compile_matrix(m, "glMultMatrixf", super::dispatch::exec_glMultMatrixf) }
    }
    /// `glLoadTransposeMatrixd` in a display list.
    ///
    /// # Safety
    /// As [`Context::glLoadTransposeMatrixd`].
    pub unsafe fn compile_glLoadTransposeMatrixd(&mut self, m: *const GLdouble) {
        unsafe { self.compile_matrix(m, "glLoadTransposeMatrixd", super::dispatch::exec_glLoadTransposeMatrixd) }
    }
    /// `glLoadTransposeMatrixf` in a display list.
    ///
    /// # Safety
    /// As [`Context::glLoadTransposeMatrixf`].
    pub unsafe fn compile_glLoadTransposeMatrixf(&mut self, m: *const GLfloat) {
        unsafe { self.compile_matrix(m, "glLoadTransposeMatrixf", super::dispatch::exec_glLoadTransposeMatrixf) }
    }
    /// `glMultTransposeMatrixd` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMultTransposeMatrixd`].
    pub unsafe fn compile_glMultTransposeMatrixd(&mut self, m: *const GLdouble) {
        unsafe { self.compile_matrix(m, "glMultTransposeMatrixd", super::dispatch::exec_glMultTransposeMatrixd) }
    }
    /// `glMultTransposeMatrixf` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMultTransposeMatrixf`].
    pub unsafe fn compile_glMultTransposeMatrixf(&mut self, m: *const GLfloat) {
        unsafe { self.compile_matrix(m, "glMultTransposeMatrixf", super::dispatch::exec_glMultTransposeMatrixf) }
    }

    /// Transformation state queries (table 6.5).
    pub(crate) fn query_transform(&self, pname: GLenum) -> Option<Value> {
        let t = &self.transform;
        let unit = self.active_texture_unit();
        let matrix = |m: DMat4| Value::Float(m.to_cols_array().to_vec());
        Some(match pname {
            gl::GL_MATRIX_MODE => Value::int(match t.mode {
                MatrixMode::Modelview => gl::GL_MODELVIEW,
                MatrixMode::Projection => gl::GL_PROJECTION,
                MatrixMode::Texture => gl::GL_TEXTURE,
            }),
            gl::GL_MODELVIEW_MATRIX => matrix(t.modelview.top()),
            gl::GL_PROJECTION_MATRIX => matrix(t.projection.top()),
            gl::GL_TEXTURE_MATRIX => matrix(t.texture[unit].top()),
            gl::GL_TRANSPOSE_MODELVIEW_MATRIX => matrix(t.modelview.top().transpose()),
            gl::GL_TRANSPOSE_PROJECTION_MATRIX => matrix(t.projection.top().transpose()),
            gl::GL_TRANSPOSE_TEXTURE_MATRIX => matrix(t.texture[unit].top().transpose()),
            gl::GL_MODELVIEW_STACK_DEPTH => Value::int(t.modelview.depth() as i64),
            gl::GL_PROJECTION_STACK_DEPTH => Value::int(t.projection.depth() as i64),
            gl::GL_TEXTURE_STACK_DEPTH => Value::int(t.texture[unit].depth() as i64),
            gl::GL_MAX_MODELVIEW_STACK_DEPTH => Value::int(MAX_MODELVIEW_STACK_DEPTH as i64),
            gl::GL_MAX_PROJECTION_STACK_DEPTH => Value::int(MAX_PROJECTION_STACK_DEPTH as i64),
            gl::GL_MAX_TEXTURE_STACK_DEPTH => Value::int(MAX_TEXTURE_STACK_DEPTH as i64),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::gl;

    #[test]
    fn stack_errors_and_depth() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glPopMatrix();
        assert_eq!(ctx.glGetError(), gl::GL_STACK_UNDERFLOW);
        for _ in 0..31 {
            ctx.glPushMatrix();
        }
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        ctx.glPushMatrix();
        assert_eq!(ctx.glGetError(), gl::GL_STACK_OVERFLOW);
    }

    #[test]
    fn translate_then_rotate_composes_on_the_right() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glTranslatef(1.0, 2.0, 3.0);
        ctx.glRotatef(90.0, 0.0, 0.0, 1.0);
        let m = ctx.transform.modelview();
        let p = m.transform_point3(glam::Vec3::X);
        assert!((p - glam::Vec3::new(1.0, 3.0, 3.0)).length() < 1e-5, "{p}");
        ctx.glFrustum(-1.0, 1.0, -1.0, 1.0, 0.0, 10.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    }
}
