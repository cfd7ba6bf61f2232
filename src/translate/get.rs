//! `glGetBooleanv`, `glGetIntegerv`, `glGetFloatv`, `glGetDoublev` (OpenGL 1.5 section 6.1.2):
//! each state module answers the parameters it owns with a typed [`Value`]; this module
//! converts it to the type asked for.

use super::Context;
use super::convert::write_slice;
use super::gl::{self, GLboolean, GLdouble, GLenum, GLfloat, GLint};

/// A state value in its own type; the conversions of section 6.1.2 apply when it is read as
/// another.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// Booleans.
    Bool(Vec<bool>),
    /// Integers and enums.
    Int(Vec<i64>),
    /// Floating-point values; read as integers they are rounded to the nearest.
    Float(Vec<f64>),
    /// Colours and normals, in [-1, 1]; read as integers they map linearly to the integer range.
    Normalized(Vec<f64>),
}

impl Value {
    /// One integer.
    pub fn int(v: impl Into<i64>) -> Value {
        Value::Int(vec![v.into()])
    }
    /// One boolean.
    pub fn bool(v: bool) -> Value {
        Value::Bool(vec![v])
    }
    /// One float.
    pub fn float(v: impl Into<f64>) -> Value {
        Value::Float(vec![v.into()])
    }
    /// Floats from an `f32` slice.
    pub fn floats(v: &[f32]) -> Value {
        Value::Float(v.iter().map(|&x| f64::from(x)).collect())
    }
    /// A colour or other normalized quantity from an `f32` slice.
    pub fn normalized(v: &[f32]) -> Value {
        Value::Normalized(v.iter().map(|&x| f64::from(x)).collect())
    }

    /// As booleans: non-zero is true.
    pub fn to_bools(&self) -> Vec<GLboolean> {
        match self {
            Value::Bool(v) => v.iter().map(|&b| GLboolean::from(b)).collect(),
            Value::Int(v) => v.iter().map(|&x| GLboolean::from(x != 0)).collect(),
            Value::Float(v) | Value::Normalized(v) => v.iter().map(|&x| GLboolean::from(x != 0.0)).collect(),
        }
    }

    /// As integers: floats rounded, normalized values mapped so that 1.0 is the largest
    /// integer and -1.0 the smallest.
    pub fn to_ints(&self) -> Vec<GLint> {
        match self {
            Value::Bool(v) => v.iter().map(|&b| GLint::from(b)).collect(),
            Value::Int(v) => v.iter().map(|&x| x.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as GLint).collect(),
            Value::Float(v) => v.iter().map(|&x| x.round().clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as GLint).collect(),
            Value::Normalized(v) => v
                .iter()
                .map(|&x| {
                    let x = x.clamp(-1.0, 1.0);
                    let scale = if x >= 0.0 { f64::from(i32::MAX) } else { -f64::from(i32::MIN) };
                    (x * scale).round() as GLint
                })
                .collect(),
        }
    }

    /// As doubles.
    pub fn to_doubles(&self) -> Vec<GLdouble> {
        match self {
            Value::Bool(v) => v.iter().map(|&b| f64::from(u8::from(b))).collect(),
            Value::Int(v) => v.iter().map(|&x| x as f64).collect(),
            Value::Float(v) | Value::Normalized(v) => v.clone(),
        }
    }
}

impl Context {
    /// The value of `pname`, asking each state module in turn; `None` for an unknown name.
    pub fn query(&self, pname: GLenum) -> Option<Value> {
        None.or_else(|| self.query_enables(pname))
            .or_else(|| self.query_transform(pname))
            .or_else(|| self.query_texunit(pname))
            .or_else(|| self.query_viewport(pname))
            .or_else(|| self.query_lists(pname))
            .or_else(|| self.query_lighting(pname))
            .or_else(|| self.query_fog(pname))
            .or_else(|| self.query_fragment(pname))
            .or_else(|| self.query_stencil(pname))
            .or_else(|| self.query_rasterization(pname))
            .or_else(|| self.query_clear(pname))
            .or_else(|| self.query_framebuffers(pname))
            .or_else(|| self.query_buffers(pname))
            .or_else(|| self.query_draw_buffers(pname))
            .or_else(|| self.query_hints(pname))
            .or_else(|| self.query_attrib(pname))
            .or_else(|| self.query_implementation(pname))
            .or_else(|| self.query_eval(pname))
            .or_else(|| self.query_render_mode(pname))
            .or_else(|| self.query_texture(pname))
            .or_else(|| self.query_pixels(pname))
            .or_else(|| self.query_pixel_buffers(pname))
            .or_else(|| self.query_vertex(pname))
            .or_else(|| self.query_arrays(pname))
            .or_else(|| self.query_arrays_ext(pname))
            .or_else(|| self.query_programs(pname))
    }

    fn query_lists(&self, pname: GLenum) -> Option<Value> {
        Some(match pname {
            gl::GL_LIST_BASE => Value::int(self.list_base()),
            gl::GL_LIST_INDEX => Value::int(self.compiling_list().map_or(0, |(n, _)| n)),
            gl::GL_LIST_MODE => Value::int(self.compiling_list().map_or(0, |(_, m)| m)),
            gl::GL_MAX_LIST_NESTING => Value::int(super::lists::MAX_LIST_NESTING),
            _ => return None,
        })
    }

    fn query_or_error(&mut self, pname: GLenum, command: &'static str) -> Option<Value> {
        let value = self.query(pname);
        if value.is_none() {
            self.set_error_in(gl::GL_INVALID_ENUM, command);
        }
        value
    }

    /// `glGetBooleanv`.
    ///
    /// # Safety
    /// `params` must have room for every value of `pname`.
    pub unsafe fn glGetBooleanv(&mut self, pname: GLenum, params: *mut GLboolean) {
        if let Some(v) = self.query_or_error(pname, "glGetBooleanv") {
            unsafe { write_slice(params, &v.to_bools()) }
        }
    }

    /// `glGetIntegerv`.
    ///
    /// # Safety
    /// `params` must have room for every value of `pname`.
    pub unsafe fn glGetIntegerv(&mut self, pname: GLenum, params: *mut GLint) {
        if let Some(v) = self.query_or_error(pname, "glGetIntegerv") {
            unsafe { write_slice(params, &v.to_ints()) }
        }
    }

    /// `glGetFloatv`.
    ///
    /// # Safety
    /// `params` must have room for every value of `pname`.
    pub unsafe fn glGetFloatv(&mut self, pname: GLenum, params: *mut GLfloat) {
        if let Some(v) = self.query_or_error(pname, "glGetFloatv") {
            let floats: Vec<GLfloat> = v.to_doubles().iter().map(|&x| x as f32).collect();
            unsafe { write_slice(params, &floats) }
        }
    }

    /// `glGetDoublev`.
    ///
    /// # Safety
    /// `params` must have room for every value of `pname`.
    pub unsafe fn glGetDoublev(&mut self, pname: GLenum, params: *mut GLdouble) {
        if let Some(v) = self.query_or_error(pname, "glGetDoublev") {
            unsafe { write_slice(params, &v.to_doubles()) }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Value;

    #[test]
    fn normalized_maps_to_integer_range() {
        let v = Value::Normalized(vec![1.0, -1.0, 0.0]);
        assert_eq!(v.to_ints(), vec![i32::MAX, i32::MIN, 0]);
        assert_eq!(Value::Float(vec![2.5, -0.4]).to_ints(), vec![3, 0]);
        assert_eq!(Value::Int(vec![0, 7]).to_bools(), vec![0, 1]);
    }
}
