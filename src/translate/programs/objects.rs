//! Creating, compiling, attaching, linking, using and deleting shader and program objects
//! (OpenGL 2.0 sections 2.15.1 and 2.15.2).

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use super::{Linked, Object, Program, Shader};
use crate::translate::Context;
use crate::translate::capture::{client_pointer, reads};
use crate::translate::gl::{self, GLboolean, GLchar, GLenum, GLint, GLsizei, GLuint};
use crate::translate::glsl::{self, CompiledShader, LinkedProgram, Stage, UniformStorage};

/// The id of the next successful link, unique in the process.
static NEXT_EXECUTABLE: AtomicU64 = AtomicU64::new(1);

/// The stage of a `glCreateShader` type.
fn stage_of(type_: GLenum) -> Option<Stage> {
    match type_ {
        gl::GL_VERTEX_SHADER => Some(Stage::Vertex),
        gl::GL_FRAGMENT_SHADER => Some(Stage::Fragment),
        _ => None,
    }
}

/// Reads string `i` of `glShaderSource`: `length[i]` bytes, or up to its terminating NUL when
/// `length` is null or `length[i]` is negative. Reports what it read to capture.
///
/// # Safety
/// As `glShaderSource`.
pub(crate) unsafe fn source_string(strings: *const *const GLchar, length: *const GLint, i: usize) -> String {
    let slot = unsafe { strings.add(i) };
    reads::note(slot, size_of::<*const GLchar>());
    // Captured programs' pointers are mapped into a replay's memory.
    let ptr = client_pointer(unsafe { slot.read_unaligned() }).cast::<u8>();
    let len = if length.is_null() {
        -1
    } else {
        let l = unsafe { length.add(i) };
        reads::note(l, size_of::<GLint>());
        unsafe { l.read_unaligned() }
    };
    if ptr.is_null() {
        return String::new();
    }
    let bytes = match usize::try_from(len) {
        Ok(n) => unsafe { std::slice::from_raw_parts(ptr, n) },
        Err(_) => unsafe { std::ffi::CStr::from_ptr(ptr.cast()) }.to_bytes_with_nul(),
    };
    reads::note(ptr, bytes.len());
    String::from_utf8_lossy(bytes.strip_suffix(&[0]).unwrap_or(bytes)).into_owned()
}

impl Context {
    /// `glCreateShader`: 0 and `GL_INVALID_ENUM` for an unknown type.
    pub fn glCreateShader(&mut self, type_: GLenum) -> GLuint {
        let Some(stage) = stage_of(type_) else {
            self.set_error_in(gl::GL_INVALID_ENUM, "glCreateShader");
            return 0;
        };
        let shader = Shader { stage, source: String::new(), compiled: None, delete_pending: false, attachments: 0 };
        self.shared.lock().programs.create(Object::Shader(shader))
    }

    /// `glShaderSource`: the `count` strings, concatenated, replace the shader's source.
    ///
    /// # Safety
    /// `string` must point to `count` pointers, each to a NUL-terminated string or to the
    /// number of bytes `length` gives (when `length` is not null).
    pub unsafe fn glShaderSource(&mut self, shader: GLuint, count: GLsizei, string: *const *const GLchar, length: *const GLint) {
        let Ok(count) = usize::try_from(count) else {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glShaderSource");
        };
        let found = self.shared.lock().programs.shader(shader).map(|_| ());
        if let Err(e) = found {
            return self.set_error_in(e, "glShaderSource");
        }
        if string.is_null() && count > 0 {
            return self.null_pointer("glShaderSource");
        }
        let source: String = (0..count).map(|i| unsafe { source_string(string, length, i) }).collect();
        if let Ok(s) = self.shared.lock().programs.shader_mut(shader) {
            s.source = source;
        }
    }

    /// `glCompileShader`: compiles the source with [`glsl::compile`].
    pub fn glCompileShader(&mut self, shader: GLuint) {
        let found = self.shared.lock().programs.shader(shader).map(|s| (s.stage, s.source.clone()));
        let (stage, source) = match found {
            Ok(found) => found,
            Err(e) => return self.set_error_in(e, "glCompileShader"),
        };
        let compiled = glsl::compile(stage, &source);
        if let Ok(s) = self.shared.lock().programs.shader_mut(shader) {
            s.compiled = Some(compiled);
        }
    }

    /// `glDeleteShader`: a shader still attached is flagged and goes with its last attachment;
    /// 0 is ignored.
    pub fn glDeleteShader(&mut self, shader: GLuint) {
        if shader == 0 {
            return;
        }
        let mut shared = self.shared.lock();
        let table = &mut shared.programs;
        match table.shader_mut(shader) {
            Ok(s) if s.attachments > 0 => s.delete_pending = true,
            Ok(_) => {
                table.objects.remove(&shader);
            }
            Err(e) => {
                drop(shared);
                self.set_error_in(e, "glDeleteShader");
            }
        }
    }

    /// `glCreateProgram`.
    pub fn glCreateProgram(&mut self) -> GLuint {
        self.shared.lock().programs.create(Object::Program(Program::default()))
    }

    /// `glAttachShader`: `GL_INVALID_OPERATION` when it is attached already.
    pub fn glAttachShader(&mut self, program: GLuint, shader: GLuint) {
        let mut shared = self.shared.lock();
        let table = &mut shared.programs;
        let result = table.program(program).and_then(|p| {
            table.shader(shader)?;
            if p.shaders.contains(&shader) { Err(gl::GL_INVALID_OPERATION) } else { Ok(()) }
        });
        if let Err(e) = result {
            drop(shared);
            return self.set_error_in(e, "glAttachShader");
        }
        if let Ok(p) = table.program_mut(program) {
            p.shaders.push(shader);
        }
        if let Ok(s) = table.shader_mut(shader) {
            s.attachments += 1;
        }
    }

    /// `glDetachShader`: `GL_INVALID_OPERATION` when it is not attached; a shader flagged for
    /// deletion goes with its last attachment.
    pub fn glDetachShader(&mut self, program: GLuint, shader: GLuint) {
        let mut shared = self.shared.lock();
        let table = &mut shared.programs;
        let result = table.program(program).and_then(|p| {
            table.shader(shader)?;
            p.shaders.iter().position(|&s| s == shader).ok_or(gl::GL_INVALID_OPERATION)
        });
        match result {
            Ok(at) => {
                if let Ok(p) = table.program_mut(program) {
                    p.shaders.remove(at);
                }
                table.release_shader(shader);
            }
            Err(e) => {
                drop(shared);
                self.set_error_in(e, "glDetachShader");
            }
        }
    }

    /// `glLinkProgram`: links the attached shaders with [`glsl::link`] and the
    /// `glBindAttribLocation` bindings. A successful link gets a new executable (with a new
    /// process-unique id) and fresh uniform values; a failed one keeps the previous
    /// executable for the contexts using the program (section 2.15.2).
    pub fn glLinkProgram(&mut self, program: GLuint) {
        let (shaders, bindings) = {
            let shared = self.shared.lock();
            let table = &shared.programs;
            match table.program(program) {
                Ok(p) => {
                    let shaders: Vec<Result<CompiledShader, GLuint>> = p
                        .shaders
                        .iter()
                        .map(|&s| match table.shader(s).ok().and_then(|s| s.compiled.clone()) {
                            Some(c) if c.ok => Ok(c),
                            _ => Err(s),
                        })
                        .collect();
                    (shaders, p.bindings.clone())
                }
                Err(e) => {
                    drop(shared);
                    return self.set_error_in(e, "glLinkProgram");
                }
            }
        };
        let result = match shaders.iter().find_map(|s| s.as_ref().err()) {
            Some(s) => Err(format!("shader {s} is not compiled\n")),
            None => {
                let compiled: Vec<&CompiledShader> = shaders.iter().flatten().collect();
                let linked = glsl::link(&compiled, &bindings);
                let log = linked.log.clone();
                linked_state(linked).ok_or(log)
            }
        };
        let mut shared = self.shared.lock();
        let Ok(p) = shared.programs.program_mut(program) else { return };
        p.validate_ok = false;
        match result {
            Ok((linked, log)) => {
                p.link_ok = true;
                p.log = log;
                p.linked = Some(linked);
            }
            Err(log) => {
                p.link_ok = false;
                p.log = log;
                if p.uses == 0 {
                    p.linked = None;
                }
            }
        }
    }

    /// `glUseProgram`: 0 returns to the fixed-function pipeline; a program must be linked.
    /// A program flagged for deletion goes when it stops being used.
    pub fn glUseProgram(&mut self, program: GLuint) {
        let mut shared = self.shared.lock();
        let table = &mut shared.programs;
        if program != 0 {
            let check = table.program(program).and_then(|p| if p.link_ok { Ok(()) } else { Err(gl::GL_INVALID_OPERATION) });
            if let Err(e) = check {
                drop(shared);
                return self.set_error_in(e, "glUseProgram");
            }
        }
        let previous = std::mem::replace(&mut self.programs.current, program);
        if let Ok(p) = table.program_mut(program) {
            p.uses += 1;
        }
        table.stop_using(previous);
    }

    /// `glDeleteProgram`: a program in use is flagged and goes when it stops being used;
    /// 0 is ignored.
    pub fn glDeleteProgram(&mut self, program: GLuint) {
        if program == 0 {
            return;
        }
        let mut shared = self.shared.lock();
        let table = &mut shared.programs;
        match table.program_mut(program) {
            Ok(p) if p.uses > 0 => p.delete_pending = true,
            Ok(_) => table.remove_program(program),
            Err(e) => {
                drop(shared);
                self.set_error_in(e, "glDeleteProgram");
            }
        }
    }

    /// `glValidateProgram`: whether the program could run in the current state (section
    /// 2.15.4): it is linked, and no two samplers of different kinds name the same unit.
    pub fn glValidateProgram(&mut self, program: GLuint) {
        let mut shared = self.shared.lock();
        let p = match shared.programs.program_mut(program) {
            Ok(p) => p,
            Err(e) => {
                drop(shared);
                return self.set_error_in(e, "glValidateProgram");
            }
        };
        let problem = match &p.linked {
            Some(l) if p.link_ok => sampler_conflict(l),
            _ => Some("the program is not linked\n".to_owned()),
        };
        p.validate_ok = problem.is_none();
        p.log = problem.unwrap_or_default();
    }

    /// `glIsShader`.
    pub fn glIsShader(&mut self, shader: GLuint) -> GLboolean {
        GLboolean::from(self.shared.lock().programs.shader(shader).is_ok())
    }

    /// `glIsProgram`.
    pub fn glIsProgram(&mut self, program: GLuint) -> GLboolean {
        GLboolean::from(self.shared.lock().programs.program(program).is_ok())
    }
}

/// Two sampler slots of different kinds on the same texture unit, described for the log.
fn sampler_conflict(l: &Linked) -> Option<String> {
    let kinds = &l.executable.samplers;
    for (i, (&unit, kind)) in l.sampler_units.iter().zip(kinds).enumerate() {
        for (&other_unit, other) in l.sampler_units[..i].iter().zip(kinds) {
            if unit == other_unit && kind != other {
                return Some(format!("samplers of different types use texture unit {unit}\n"));
            }
        }
    }
    None
}

/// What a program keeps of a successful link (and the link's log); `None` for a failed one.
pub(crate) fn linked_state(linked: LinkedProgram) -> Option<(Linked, String)> {
    let LinkedProgram { ok, log, executable, uniforms, uniform_block_size, attributes } = linked;
    let mut executable = executable.filter(|_| ok)?;
    executable.id = NEXT_EXECUTABLE.fetch_add(1, Ordering::Relaxed);
    let locations = uniforms.iter().enumerate().flat_map(|(u, au)| (0..au.size).map(move |e| (u, e))).collect();
    let slots = uniforms
        .iter()
        .filter_map(|u| match u.storage {
            UniformStorage::Sampler { first_slot } => Some(first_slot + u.size),
            UniformStorage::Block { .. } => None,
        })
        .max()
        .unwrap_or(0)
        .max(executable.samplers.len() as u32);
    let sampler_targets = super::draw::slot_targets(&uniforms, slots as usize);
    let state = Linked {
        sampler_targets,
        executable: Arc::new(executable),
        uniforms,
        attributes,
        locations,
        values: vec![0; uniform_block_size as usize],
        sampler_units: vec![0; slots as usize],
        shared_values: None,
    };
    Some((state, log))
}
