//! Vector parameters of the `glXxxfv`/`glXxxiv` state commands (`glLightfv`, `glMaterialiv`,
//! `glFogiv`, `glPointParameterfv`...): how many values a parameter has, reading them as
//! floats (integer colours map linearly, OpenGL 1.5 section 2.14.1 and table 2.9), and
//! copying them into display lists.

use super::Context;
use super::convert::{norm_i32, read_slice, write_slice};
use super::get::Value;
use super::gl::{self, GLfloat, GLint};
use super::lists::ListOp;

/// How many values a parameter has and whether they are colours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Shape {
    /// Number of values, 1 to 4.
    pub count: usize,
    /// Integer values map to [-1, 1] (colours) rather than converting directly.
    pub color: bool,
}

impl Shape {
    /// One value.
    pub const SCALAR: Shape = Shape { count: 1, color: false };
    /// An RGBA colour.
    pub const COLOR: Shape = Shape { count: 4, color: true };
    /// `n` plain values.
    pub const fn plain(count: usize) -> Shape {
        Shape { count, color: false }
    }
}

/// A parameter scalar type of the `fv`/`iv` commands.
pub(crate) trait Param: Copy + Default + Send + Sync + 'static {
    /// The value as a float; colours of integer type map linearly.
    fn to_f32(self, color: bool) -> f32;
    /// A queried value in this type (section 6.1.2 conversions).
    fn from_value(v: &Value) -> Vec<Self>;
}

impl Param for GLfloat {
    fn to_f32(self, _: bool) -> f32 {
        self
    }
    fn from_value(v: &Value) -> Vec<GLfloat> {
        v.to_doubles().iter().map(|&x| x as GLfloat).collect()
    }
}

impl Param for GLint {
    fn to_f32(self, color: bool) -> f32 {
        if color { norm_i32(self) } else { self as f32 }
    }
    fn from_value(v: &Value) -> Vec<GLint> {
        v.to_ints()
    }
}

/// Reads `shape.count` values (at most 4) as floats, zero-padded; `None` for a null pointer.
///
/// # Safety
/// A non-null `ptr` must point to `shape.count` readable values.
pub(crate) unsafe fn read_params<T: Param>(ptr: *const T, shape: Shape) -> Option<[f32; 4]> {
    let values = unsafe { read_slice(ptr, shape.count.min(4)) }?;
    let mut out = [0.0; 4];
    for (o, v) in out.iter_mut().zip(values) {
        *o = v.to_f32(shape.color);
    }
    Some(out)
}

impl Context {
    /// Runs a scalar form (`glLightf`, `glMateriali`): `set` gets `[value, 0, 0, 0]`, integer
    /// colours mapped as in the vector form. A name that takes several values (`GL_AMBIENT`)
    /// reads (value, 0, 0, 0) as Mesa does (OpenGL 1.5 defines no error for it; piglit's
    /// `gl-1.0-beginend-coverage` expects it); `GL_INVALID_ENUM` for an unknown name.
    pub(crate) fn scalar_param<T: Param>(
        &mut self,
        shape: Option<Shape>,
        value: T,
        command: &'static str,
        set: impl FnOnce(&mut Context, [f32; 4]),
    ) {
        match shape {
            Some(shape) => set(self, [value.to_f32(shape.color), 0.0, 0.0, 0.0]),
            None => self.set_error_in(gl::GL_INVALID_ENUM, command),
        }
    }

    /// Runs a vector form (`glLightfv`): reads the values of `shape` and passes them to `set`;
    /// `GL_INVALID_ENUM` for an unknown parameter name.
    ///
    /// # Safety
    /// A non-null `ptr` must point to the parameter's values.
    pub(crate) unsafe fn vector_param<T: Param>(
        &mut self,
        shape: Option<Shape>,
        ptr: *const T,
        command: &'static str,
        set: impl FnOnce(&mut Context, [f32; 4]),
    ) {
        let Some(shape) = shape else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        match unsafe { read_params(ptr, shape) } {
            Some(v) => set(self, v),
            None => self.null_pointer(command),
        }
    }

    /// Writes the answer of a `glGetXxxfv/iv` query; `GL_INVALID_ENUM` when there is none.
    ///
    /// # Safety
    /// A non-null `ptr` must have room for every value of the answer.
    pub(crate) unsafe fn write_answer<T: Param>(&mut self, value: Option<Value>, ptr: *mut T, command: &'static str) {
        match value {
            Some(v) => unsafe { write_slice(ptr, &T::from_value(&v)) },
            None => self.set_error_in(gl::GL_INVALID_ENUM, command),
        }
    }

    /// Compiles a vector state command: copies `count` values (zero for a parameter name the
    /// command rejects, which then raises its error when the list runs) and records `exec`
    /// (the generated `dispatch::exec_glXxx` with the other arguments bound) on the copy.
    ///
    /// # Safety
    /// A non-null `ptr` must point to `count` readable values.
    pub(crate) unsafe fn compile_params<T: Param>(
        &mut self,
        ptr: *const T,
        count: usize,
        command: &'static str,
        exec: impl Fn(&mut Context, *const T) + Send + Sync + 'static,
    ) {
        let Some(values) = (unsafe { read_slice(ptr, count.min(4)) }) else { return self.null_pointer(command) };
        let mut copy = [T::default(); 4];
        copy[..values.len()].copy_from_slice(&values);
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| exec(ctx, copy.as_ptr()))));
    }
}
