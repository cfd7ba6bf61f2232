//! Uniforms (OpenGL 2.0 section 2.15.3): locations (one per array element), `glUniform*` into
//! the program's std430 block as [`UniformStorage`] lays it out, sampler units, and
//! `glGetActiveUniform` / `glGetUniform*`.

use super::info::{Active, write_active};
use super::{Linked, ProgramTable};
use crate::translate::Context;
use crate::translate::convert::{read_slice, write_slice};
use crate::translate::dispatch;
use crate::translate::gl::{self, GLboolean, GLchar, GLenum, GLfloat, GLint, GLsizei, GLuint};
use crate::translate::glsl::{ActiveUniform, UniformStorage};
use crate::translate::limits::MAX_COMBINED_TEXTURE_IMAGE_UNITS;

/// The basic type of a uniform's components.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Base {
    Float,
    Int,
    Bool,
    Sampler,
}

/// A uniform type: base type, columns (1 for scalars and vectors) and rows (components).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Shape {
    base: Base,
    columns: u32,
    rows: u32,
}

/// The shape of a GL uniform type enum.
fn shape(ty: GLenum) -> Option<Shape> {
    let s = |base, columns, rows| Some(Shape { base, columns, rows });
    match ty {
        gl::GL_FLOAT => s(Base::Float, 1, 1),
        gl::GL_FLOAT_VEC2 => s(Base::Float, 1, 2),
        gl::GL_FLOAT_VEC3 => s(Base::Float, 1, 3),
        gl::GL_FLOAT_VEC4 => s(Base::Float, 1, 4),
        gl::GL_INT => s(Base::Int, 1, 1),
        gl::GL_INT_VEC2 => s(Base::Int, 1, 2),
        gl::GL_INT_VEC3 => s(Base::Int, 1, 3),
        gl::GL_INT_VEC4 => s(Base::Int, 1, 4),
        gl::GL_BOOL => s(Base::Bool, 1, 1),
        gl::GL_BOOL_VEC2 => s(Base::Bool, 1, 2),
        gl::GL_BOOL_VEC3 => s(Base::Bool, 1, 3),
        gl::GL_BOOL_VEC4 => s(Base::Bool, 1, 4),
        gl::GL_FLOAT_MAT2 => s(Base::Float, 2, 2),
        gl::GL_FLOAT_MAT3 => s(Base::Float, 3, 3),
        gl::GL_FLOAT_MAT4 => s(Base::Float, 4, 4),
        gl::GL_FLOAT_MAT2x3 => s(Base::Float, 2, 3),
        gl::GL_FLOAT_MAT2x4 => s(Base::Float, 2, 4),
        gl::GL_FLOAT_MAT3x2 => s(Base::Float, 3, 2),
        gl::GL_FLOAT_MAT3x4 => s(Base::Float, 3, 4),
        gl::GL_FLOAT_MAT4x2 => s(Base::Float, 4, 2),
        gl::GL_FLOAT_MAT4x3 => s(Base::Float, 4, 3),
        gl::GL_SAMPLER_1D
        | gl::GL_SAMPLER_2D
        | gl::GL_SAMPLER_3D
        | gl::GL_SAMPLER_CUBE
        | gl::GL_SAMPLER_1D_SHADOW
        | gl::GL_SAMPLER_2D_SHADOW => s(Base::Sampler, 1, 1),
        _ => None,
    }
}

/// The name `glGetActiveUniform` reports: an array's with `[0]` (as OpenGL 2.1 says).
pub(crate) fn active_name(u: &ActiveUniform) -> String {
    if u.size > 1 { format!("{}[0]", u.name) } else { u.name.clone() }
}

/// The location of `name` in a linked program (section 2.15.3): a uniform's name, a struct
/// member's (`s.m`, `s[1].m`), optionally followed by an array subscript (`a[3]`); -1 when
/// no active uniform element has that name.
pub(crate) fn location(l: &Linked, name: &str) -> GLint {
    let (base, element) = match name.strip_suffix(']').and_then(|n| n.rsplit_once('[')) {
        Some((base, index)) if !index.is_empty() && index.bytes().all(|b| b.is_ascii_digit()) => {
            (base, index.parse::<u32>().unwrap_or(u32::MAX))
        }
        _ => (name, 0),
    };
    let Some(u) = l.uniforms.iter().position(|u| u.name == base) else { return -1 };
    l.locations.iter().position(|&loc| loc == (u, element)).map_or(-1, |p| p as GLint)
}

/// Values a `glUniform*` command gives.
#[derive(Clone, Copy)]
enum Given<'a> {
    Floats(&'a [f32]),
    Ints(&'a [i32]),
}

/// The component types of `glUniform*` values.
trait Component: Copy {
    /// The values as [`Given`].
    fn given(v: &[Self]) -> Given<'_>;
}

impl Component for f32 {
    fn given(v: &[f32]) -> Given<'_> {
        Given::Floats(v)
    }
}

impl Component for i32 {
    fn given(v: &[i32]) -> Given<'_> {
        Given::Ints(v)
    }
}

/// What a `glUniform*` command is: float or integer values, vectors of `rows` components, or
/// matrices of `columns` columns.
#[derive(Clone, Copy)]
struct Setter {
    ints: bool,
    columns: u32,
    rows: u32,
    transpose: bool,
}

/// Where a `glUniform*` call writes: uniform, first element, elements.
struct Target {
    uniform: usize,
    element: u32,
    elements: u32,
}

/// Checks a `glUniform*` call against the uniform at `location` (section 2.15.3):
/// `Ok(None)` for location -1, `GL_INVALID_OPERATION` for an unknown location, a type or
/// component count the uniform does not have, or several values for a non-array.
fn check(l: &Linked, location: GLint, count: usize, setter: Setter) -> Result<Option<Target>, GLenum> {
    if location == -1 {
        return Ok(None);
    }
    let &(uniform, element) =
        usize::try_from(location).ok().and_then(|i| l.locations.get(i)).ok_or(gl::GL_INVALID_OPERATION)?;
    let u = &l.uniforms[uniform];
    let shape = shape(u.ty).ok_or(gl::GL_INVALID_OPERATION)?;
    let matches = shape.columns == setter.columns
        && shape.rows == setter.rows
        && match shape.base {
            Base::Float => !setter.ints,
            Base::Int => setter.ints,
            Base::Bool => setter.columns == 1,
            Base::Sampler => setter.ints && setter.rows == 1,
        };
    if !matches || (count > 1 && u.size == 1) {
        return Err(gl::GL_INVALID_OPERATION);
    }
    Ok(Some(Target { uniform, element, elements: (count as u32).min(u.size - element) }))
}

/// Writes `given` (already checked) into the uniform storage.
fn write(l: &mut Linked, t: &Target, setter: Setter, given: Given) -> Result<(), GLenum> {
    let u = &l.uniforms[t.uniform];
    let base = shape(u.ty).map_or(Base::Float, |s| s.base);
    let per = (setter.columns * setter.rows) as usize;
    match u.storage {
        UniformStorage::Sampler { first_slot } => {
            let Given::Ints(v) = given else { return Err(gl::GL_INVALID_OPERATION) };
            let units = &v[..t.elements as usize];
            if units.iter().any(|&unit| !(0..MAX_COMBINED_TEXTURE_IMAGE_UNITS as i32).contains(&unit)) {
                return Err(gl::GL_INVALID_VALUE);
            }
            for (e, &unit) in units.iter().enumerate() {
                if let Some(slot) = l.sampler_units.get_mut(first_slot as usize + t.element as usize + e) {
                    *slot = unit as u32;
                }
            }
        }
        UniformStorage::Block { offset, array_stride, matrix_stride } => {
            for e in 0..t.elements as usize {
                let at = offset as usize + (t.element as usize + e) * array_stride as usize;
                for c in 0..setter.columns as usize {
                    for r in 0..setter.rows as usize {
                        let k = e * per + if setter.transpose { r * setter.columns as usize + c } else { c * setter.rows as usize + r };
                        let bits = match (base, given) {
                            (Base::Bool, Given::Floats(v)) => u32::from(v[k] != 0.0),
                            (Base::Bool, Given::Ints(v)) => u32::from(v[k] != 0),
                            (_, Given::Floats(v)) => v[k].to_bits(),
                            (_, Given::Ints(v)) => v[k] as u32,
                        };
                        let p = at + c * matrix_stride as usize + r * 4;
                        if let Some(bytes) = l.values.get_mut(p..p + 4) {
                            bytes.copy_from_slice(&bits.to_ne_bytes());
                        }
                    }
                }
            }
            l.shared_values = None;
        }
    }
    Ok(())
}

/// The values of uniform element `location` as floats or integers: every component, matrices
/// column by column.
fn read_back(l: &Linked, location: GLint) -> Option<(Base, Vec<u32>)> {
    let &(uniform, element) = usize::try_from(location).ok().and_then(|i| l.locations.get(i))?;
    let u = &l.uniforms[uniform];
    let s = shape(u.ty)?;
    Some(match u.storage {
        UniformStorage::Sampler { first_slot } => (s.base, vec![*l.sampler_units.get((first_slot + element) as usize)?]),
        UniformStorage::Block { offset, array_stride, matrix_stride } => {
            let at = (offset + element * array_stride) as usize;
            let mut out = Vec::new();
            for c in 0..s.columns as usize {
                for r in 0..s.rows as usize {
                    let p = at + c * matrix_stride as usize + r * 4;
                    let bytes = l.values.get(p..p + 4)?;
                    out.push(u32::from_ne_bytes(bytes.try_into().ok()?));
                }
            }
            (s.base, out)
        }
    })
}

impl Context {
    /// The linked state of the program in use, mutably, under the share-group lock.
    fn with_current_linked<R>(&mut self, f: impl FnOnce(&mut Linked) -> R) -> Option<R> {
        let current = self.programs.current;
        let mut shared = self.shared.lock();
        let linked = shared.programs.program_mut(current).ok()?.linked.as_mut()?;
        Some(f(linked))
    }

    /// A `glUniform*` call: checks it, reads the `count` elements it gives with `read`
    /// (only those the uniform has room for), and stores them.
    fn set_uniform<T: Component>(
        &mut self,
        command: &'static str,
        location: GLint,
        count: GLsizei,
        setter: Setter,
        read: impl FnOnce(usize) -> Option<Vec<T>>,
    ) {
        let Ok(count) = usize::try_from(count) else {
            return self.set_error_in(gl::GL_INVALID_VALUE, command);
        };
        let per = (setter.columns * setter.rows) as usize;
        let result = self.with_current_linked(|l| {
            let Some(target) = check(l, location, count, setter)? else { return Ok(()) };
            let Some(values) = read(target.elements as usize * per) else { return Ok(()) };
            write(l, &target, setter, T::given(&values))
        });
        match result {
            None => self.set_error_in(gl::GL_INVALID_OPERATION, command),
            Some(Err(e)) => self.set_error_in(e, command),
            Some(Ok(())) => {}
        }
    }

    /// `glUniform{1234}f` and `glUniform{1234}i`.
    fn uniform_values<T: Component>(&mut self, command: &'static str, location: GLint, values: &[T], ints: bool) {
        let setter = Setter { ints, columns: 1, rows: values.len() as u32, transpose: false };
        self.set_uniform(command, location, 1, setter, |n| Some(values[..n].to_vec()));
    }

    /// `glUniform{1234}fv`, `glUniform{1234}iv` and `glUniformMatrix*fv`.
    ///
    /// # Safety
    /// `value` must point to `count` elements of the setter's shape.
    unsafe fn uniform_vector<T: Component>(&mut self, command: &'static str, location: GLint, count: GLsizei, value: *const T, setter: Setter) {
        let mut null = false;
        self.set_uniform(command, location, count, setter, |n| {
            let v = unsafe { read_slice(value, n) };
            null = v.is_none();
            v
        });
        if null {
            self.null_pointer(command);
        }
    }

    /// `glUniform1f`.
    pub fn glUniform1f(&mut self, location: GLint, v0: GLfloat) {
        self.uniform_values("glUniform1f", location, &[v0], false);
    }
    /// `glUniform2f`.
    pub fn glUniform2f(&mut self, location: GLint, v0: GLfloat, v1: GLfloat) {
        self.uniform_values("glUniform2f", location, &[v0, v1], false);
    }
    /// `glUniform3f`.
    pub fn glUniform3f(&mut self, location: GLint, v0: GLfloat, v1: GLfloat, v2: GLfloat) {
        self.uniform_values("glUniform3f", location, &[v0, v1, v2], false);
    }
    /// `glUniform4f`.
    pub fn glUniform4f(&mut self, location: GLint, v0: GLfloat, v1: GLfloat, v2: GLfloat, v3: GLfloat) {
        self.uniform_values("glUniform4f", location, &[v0, v1, v2, v3], false);
    }
    /// `glUniform1i` (also sets samplers: the texture unit they sample).
    pub fn glUniform1i(&mut self, location: GLint, v0: GLint) {
        self.uniform_values("glUniform1i", location, &[v0], true);
    }
    /// `glUniform2i`.
    pub fn glUniform2i(&mut self, location: GLint, v0: GLint, v1: GLint) {
        self.uniform_values("glUniform2i", location, &[v0, v1], true);
    }
    /// `glUniform3i`.
    pub fn glUniform3i(&mut self, location: GLint, v0: GLint, v1: GLint, v2: GLint) {
        self.uniform_values("glUniform3i", location, &[v0, v1, v2], true);
    }
    /// `glUniform4i`.
    pub fn glUniform4i(&mut self, location: GLint, v0: GLint, v1: GLint, v2: GLint, v3: GLint) {
        self.uniform_values("glUniform4i", location, &[v0, v1, v2, v3], true);
    }

    /// `glGetUniformLocation`: -1 for a name that is no active uniform element.
    ///
    /// # Safety
    /// `name` must be null or a NUL-terminated string.
    pub unsafe fn glGetUniformLocation(&mut self, program: GLuint, name: *const GLchar) -> GLint {
        let Some(name) = (unsafe { super::attributes::name_arg(name) }) else {
            self.null_pointer("glGetUniformLocation");
            return -1;
        };
        let result = linked_program(&self.shared.lock().programs, program).map(|l| location(l, &name));
        result.unwrap_or_else(|e| {
            self.set_error_in(e, "glGetUniformLocation");
            -1
        })
    }

    /// `glGetActiveUniform`.
    ///
    /// # Safety
    /// `name` must have room for `bufSize` bytes; `length`, `size` and `type_` must be null or
    /// writable.
    #[allow(clippy::too_many_arguments)]
    pub unsafe fn glGetActiveUniform(
        &mut self,
        program: GLuint,
        index: GLuint,
        bufSize: GLsizei,
        length: *mut GLsizei,
        size: *mut GLint,
        type_: *mut GLenum,
        name: *mut GLchar,
    ) {
        let found = self.shared.lock().programs.program(program).and_then(|p| {
            let l = p.linked.as_ref().filter(|_| p.link_ok).ok_or(gl::GL_INVALID_VALUE)?;
            let u = l.uniforms.get(index as usize).ok_or(gl::GL_INVALID_VALUE)?;
            Ok(Active { name: active_name(u), size: u.size as GLint, ty: u.ty })
        });
        match found {
            Err(e) => self.set_error_in(e, "glGetActiveUniform"),
            Ok(a) => unsafe { write_active(self, "glGetActiveUniform", a, bufSize, length, size, type_, name) },
        }
    }

    /// `glGetUniformfv`.
    ///
    /// # Safety
    /// `params` must have room for every component of the uniform.
    pub unsafe fn glGetUniformfv(&mut self, program: GLuint, location: GLint, params: *mut GLfloat) {
        if let Some((base, bits)) = self.uniform_value(program, location, "glGetUniformfv") {
            let v: Vec<f32> = bits
                .iter()
                .map(|&b| match base {
                    Base::Float => f32::from_bits(b),
                    _ => b as i32 as f32,
                })
                .collect();
            unsafe { write_slice(params, &v) }
        }
    }

    /// `glGetUniformiv`.
    ///
    /// # Safety
    /// `params` must have room for every component of the uniform.
    pub unsafe fn glGetUniformiv(&mut self, program: GLuint, location: GLint, params: *mut GLint) {
        if let Some((base, bits)) = self.uniform_value(program, location, "glGetUniformiv") {
            let v: Vec<i32> = bits
                .iter()
                .map(|&b| match base {
                    Base::Float => f32::from_bits(b).round() as i32,
                    _ => b as i32,
                })
                .collect();
            unsafe { write_slice(params, &v) }
        }
    }

    /// The value at `location` of a linked program, for `glGetUniform*`:
    /// `GL_INVALID_OPERATION` for a location it does not have.
    fn uniform_value(&mut self, program: GLuint, location: GLint, command: &'static str) -> Option<(Base, Vec<u32>)> {
        let result = linked_program(&self.shared.lock().programs, program)
            .and_then(|l| read_back(l, location).ok_or(gl::GL_INVALID_OPERATION));
        result.map_err(|e| self.set_error_in(e, command)).ok()
    }
}

/// The linked state of `program`: errors of [`ProgramTable::program`], and
/// `GL_INVALID_OPERATION` when it is not linked.
pub(crate) fn linked_program(t: &ProgramTable, program: GLuint) -> Result<&Linked, GLenum> {
    let p = t.program(program)?;
    p.linked.as_ref().filter(|_| p.link_ok).ok_or(gl::GL_INVALID_OPERATION)
}

/// Records a `glUniform*v` call in a display list with its `count * per` values copied now.
///
/// # Safety
/// `value` must point to `count * per` values.
unsafe fn compile_vector<T: Copy + Send + Sync + 'static>(
    ctx: &mut Context,
    command: &'static str,
    count: GLsizei,
    per: usize,
    value: *const T,
    exec: impl Fn(&mut Context, *const T) + Send + Sync + 'static,
) {
    let n = usize::try_from(count).unwrap_or(0).saturating_mul(per);
    let Some(copy) = (unsafe { read_slice(value, n) }) else { return ctx.null_pointer(command) };
    ctx.lists.record(crate::translate::lists::ListOp::Deferred(Box::new(move |ctx| exec(ctx, copy.as_ptr()))));
}

impl Context {
    /// `glUniform1fv`.
    ///
    /// # Safety
    /// `value` must point to `count` elements of 1 values.
    pub unsafe fn glUniform1fv(&mut self, location: GLint, count: GLsizei, value: *const GLfloat) {
        let setter = Setter { ints: false, columns: 1, rows: 1, transpose: false };
        unsafe { self.uniform_vector("glUniform1fv", location, count, value, setter) }
    }

    /// `glUniform1fv` in a display list.
    ///
    /// # Safety
    /// As the command.
    pub unsafe fn compile_glUniform1fv(&mut self, location: GLint, count: GLsizei, value: *const GLfloat) {
        unsafe { compile_vector(self, "glUniform1fv", count, 1, value, move |ctx, v| dispatch::exec_glUniform1fv(ctx, location, count, v)) }
    }

    /// `glUniform2fv`.
    ///
    /// # Safety
    /// `value` must point to `count` elements of 2 values.
    pub unsafe fn glUniform2fv(&mut self, location: GLint, count: GLsizei, value: *const GLfloat) {
        let setter = Setter { ints: false, columns: 1, rows: 2, transpose: false };
        unsafe { self.uniform_vector("glUniform2fv", location, count, value, setter) }
    }

    /// `glUniform2fv` in a display list.
    ///
    /// # Safety
    /// As the command.
    pub unsafe fn compile_glUniform2fv(&mut self, location: GLint, count: GLsizei, value: *const GLfloat) {
        unsafe { compile_vector(self, "glUniform2fv", count, 2, value, move |ctx, v| dispatch::exec_glUniform2fv(ctx, location, count, v)) }
    }

    /// `glUniform3fv`.
    ///
    /// # Safety
    /// `value` must point to `count` elements of 3 values.
    pub unsafe fn glUniform3fv(&mut self, location: GLint, count: GLsizei, value: *const GLfloat) {
        let setter = Setter { ints: false, columns: 1, rows: 3, transpose: false };
        unsafe { self.uniform_vector("glUniform3fv", location, count, value, setter) }
    }

    /// `glUniform3fv` in a display list.
    ///
    /// # Safety
    /// As the command.
    pub unsafe fn compile_glUniform3fv(&mut self, location: GLint, count: GLsizei, value: *const GLfloat) {
        unsafe { compile_vector(self, "glUniform3fv", count, 3, value, move |ctx, v| dispatch::exec_glUniform3fv(ctx, location, count, v)) }
    }

    /// `glUniform4fv`.
    ///
    /// # Safety
    /// `value` must point to `count` elements of 4 values.
    pub unsafe fn glUniform4fv(&mut self, location: GLint, count: GLsizei, value: *const GLfloat) {
        let setter = Setter { ints: false, columns: 1, rows: 4, transpose: false };
        unsafe { self.uniform_vector("glUniform4fv", location, count, value, setter) }
    }

    /// `glUniform4fv` in a display list.
    ///
    /// # Safety
    /// As the command.
    pub unsafe fn compile_glUniform4fv(&mut self, location: GLint, count: GLsizei, value: *const GLfloat) {
        unsafe { compile_vector(self, "glUniform4fv", count, 4, value, move |ctx, v| dispatch::exec_glUniform4fv(ctx, location, count, v)) }
    }

    /// `glUniform1iv`.
    ///
    /// # Safety
    /// `value` must point to `count` elements of 1 values.
    pub unsafe fn glUniform1iv(&mut self, location: GLint, count: GLsizei, value: *const GLint) {
        let setter = Setter { ints: true, columns: 1, rows: 1, transpose: false };
        unsafe { self.uniform_vector("glUniform1iv", location, count, value, setter) }
    }

    /// `glUniform1iv` in a display list.
    ///
    /// # Safety
    /// As the command.
    pub unsafe fn compile_glUniform1iv(&mut self, location: GLint, count: GLsizei, value: *const GLint) {
        unsafe { compile_vector(self, "glUniform1iv", count, 1, value, move |ctx, v| dispatch::exec_glUniform1iv(ctx, location, count, v)) }
    }

    /// `glUniform2iv`.
    ///
    /// # Safety
    /// `value` must point to `count` elements of 2 values.
    pub unsafe fn glUniform2iv(&mut self, location: GLint, count: GLsizei, value: *const GLint) {
        let setter = Setter { ints: true, columns: 1, rows: 2, transpose: false };
        unsafe { self.uniform_vector("glUniform2iv", location, count, value, setter) }
    }

    /// `glUniform2iv` in a display list.
    ///
    /// # Safety
    /// As the command.
    pub unsafe fn compile_glUniform2iv(&mut self, location: GLint, count: GLsizei, value: *const GLint) {
        unsafe { compile_vector(self, "glUniform2iv", count, 2, value, move |ctx, v| dispatch::exec_glUniform2iv(ctx, location, count, v)) }
    }

    /// `glUniform3iv`.
    ///
    /// # Safety
    /// `value` must point to `count` elements of 3 values.
    pub unsafe fn glUniform3iv(&mut self, location: GLint, count: GLsizei, value: *const GLint) {
        let setter = Setter { ints: true, columns: 1, rows: 3, transpose: false };
        unsafe { self.uniform_vector("glUniform3iv", location, count, value, setter) }
    }

    /// `glUniform3iv` in a display list.
    ///
    /// # Safety
    /// As the command.
    pub unsafe fn compile_glUniform3iv(&mut self, location: GLint, count: GLsizei, value: *const GLint) {
        unsafe { compile_vector(self, "glUniform3iv", count, 3, value, move |ctx, v| dispatch::exec_glUniform3iv(ctx, location, count, v)) }
    }

    /// `glUniform4iv`.
    ///
    /// # Safety
    /// `value` must point to `count` elements of 4 values.
    pub unsafe fn glUniform4iv(&mut self, location: GLint, count: GLsizei, value: *const GLint) {
        let setter = Setter { ints: true, columns: 1, rows: 4, transpose: false };
        unsafe { self.uniform_vector("glUniform4iv", location, count, value, setter) }
    }

    /// `glUniform4iv` in a display list.
    ///
    /// # Safety
    /// As the command.
    pub unsafe fn compile_glUniform4iv(&mut self, location: GLint, count: GLsizei, value: *const GLint) {
        unsafe { compile_vector(self, "glUniform4iv", count, 4, value, move |ctx, v| dispatch::exec_glUniform4iv(ctx, location, count, v)) }
    }

    /// `glUniformMatrix2fv`: column-major values, row-major with `transpose`.
    ///
    /// # Safety
    /// `value` must point to `count` matrices.
    pub unsafe fn glUniformMatrix2fv(&mut self, location: GLint, count: GLsizei, transpose: GLboolean, value: *const GLfloat) {
        let setter = Setter { ints: false, columns: 2, rows: 2, transpose: transpose != 0 };
        unsafe { self.uniform_vector("glUniformMatrix2fv", location, count, value, setter) }
    }

    /// `glUniformMatrix2fv` in a display list.
    ///
    /// # Safety
    /// As the command.
    pub unsafe fn compile_glUniformMatrix2fv(&mut self, location: GLint, count: GLsizei, transpose: GLboolean, value: *const GLfloat) {
        unsafe { compile_vector(self, "glUniformMatrix2fv", count, 4, value, move |ctx, v| dispatch::exec_glUniformMatrix2fv(ctx, location, count, transpose, v)) }
    }

    /// `glUniformMatrix3fv`: column-major values, row-major with `transpose`.
    ///
    /// # Safety
    /// `value` must point to `count` matrices.
    pub unsafe fn glUniformMatrix3fv(&mut self, location: GLint, count: GLsizei, transpose: GLboolean, value: *const GLfloat) {
        let setter = Setter { ints: false, columns: 3, rows: 3, transpose: transpose != 0 };
        unsafe { self.uniform_vector("glUniformMatrix3fv", location, count, value, setter) }
    }

    /// `glUniformMatrix3fv` in a display list.
    ///
    /// # Safety
    /// As the command.
    pub unsafe fn compile_glUniformMatrix3fv(&mut self, location: GLint, count: GLsizei, transpose: GLboolean, value: *const GLfloat) {
        unsafe { compile_vector(self, "glUniformMatrix3fv", count, 9, value, move |ctx, v| dispatch::exec_glUniformMatrix3fv(ctx, location, count, transpose, v)) }
    }

    /// `glUniformMatrix4fv`: column-major values, row-major with `transpose`.
    ///
    /// # Safety
    /// `value` must point to `count` matrices.
    pub unsafe fn glUniformMatrix4fv(&mut self, location: GLint, count: GLsizei, transpose: GLboolean, value: *const GLfloat) {
        let setter = Setter { ints: false, columns: 4, rows: 4, transpose: transpose != 0 };
        unsafe { self.uniform_vector("glUniformMatrix4fv", location, count, value, setter) }
    }

    /// `glUniformMatrix4fv` in a display list.
    ///
    /// # Safety
    /// As the command.
    pub unsafe fn compile_glUniformMatrix4fv(&mut self, location: GLint, count: GLsizei, transpose: GLboolean, value: *const GLfloat) {
        unsafe { compile_vector(self, "glUniformMatrix4fv", count, 16, value, move |ctx, v| dispatch::exec_glUniformMatrix4fv(ctx, location, count, transpose, v)) }
    }

}
