//! Display lists (OpenGL 1.5 section 5.4): names, compilation, execution and `glCallLists`.
//!
//! A list is a sequence of [`ListOp`]s: commands with scalar arguments are stored as generated
//! [`Call`] values; commands that read client memory copy what they read when compiled
//! (`Context::compile_glNAME` methods) and store a deferred call.

use std::collections::BTreeMap;
use std::sync::Arc;

use super::Context;
use super::dispatch::{self, Call};
use super::gl::{self, GLenum, GLsizei, GLuint, GLboolean};

/// The deepest `glCallList` nesting (`GL_MAX_LIST_NESTING`, at least 64).
pub const MAX_LIST_NESTING: u32 = 64;

/// One compiled command.
pub enum ListOp {
    /// A command whose arguments are all scalars.
    Call(Call),
    /// A command that read client memory when compiled; the closure owns a copy of it.
    Deferred(Box<dyn Fn(&mut Context) + Send + Sync>),
}

/// The display lists of a share group: name → commands (empty for reserved names).
#[derive(Default)]
pub struct ListTable {
    lists: BTreeMap<GLuint, Arc<[ListOp]>>,
    /// Version of each compiled list: unique across lists, new at each compilation, so that
    /// `translate::classify` hashes a list's geometry once per compilation.
    versions: BTreeMap<GLuint, u64>,
}

/// The next list version (unique in the process).
static NEXT_VERSION: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

impl ListTable {
    /// The version of list `name` (changes whenever it is compiled); `None` for a list never
    /// compiled.
    pub fn version(&self, name: GLuint) -> Option<u64> {
        self.versions.get(&name).copied()
    }
}

/// The list being compiled, if any.
struct Compiling {
    name: GLuint,
    execute: bool,
    ops: Vec<ListOp>,
}

/// Per-context display-list state.
#[derive(Default)]
pub struct ListState {
    compiling: Option<Compiling>,
    /// `glListBase`.
    base: GLuint,
    /// Current `glCallList` nesting depth.
    depth: u32,
    /// Name of the innermost list being executed, 0 when none.
    executing_name: GLuint,
}

impl ListState {
    /// Whether a list is being compiled (`glNewList` … `glEndList`).
    pub fn compiling(&self) -> bool {
        self.compiling.is_some()
    }

    /// Whether compiled commands are also executed (`GL_COMPILE_AND_EXECUTE`, or no list).
    pub fn executing(&self) -> bool {
        self.compiling.as_ref().is_none_or(|c| c.execute)
    }

    /// The innermost display list being executed by `glCallList`, if any.
    pub fn executing_list(&self) -> Option<GLuint> {
        (self.executing_name != 0).then_some(self.executing_name)
    }

    /// Appends a command to the list being compiled.
    pub fn record(&mut self, op: ListOp) {
        if let Some(c) = &mut self.compiling {
            c.ops.push(op);
        }
    }

    /// How many commands the list being compiled holds: a mark for [`ListState::guard_since`].
    pub fn mark(&self) -> usize {
        self.compiling.as_ref().map_or(0, |c| c.ops.len())
    }

    /// Groups the commands recorded since `mark` (by a command's `compile_` method, whose
    /// closures call the command's method directly) into one that, when the list is executed
    /// between `glBegin` and `glEnd`, raises `GL_INVALID_OPERATION` instead of running them
    /// (section 2.6.3), as recorded scalar commands do through their `exec_` function. When
    /// the method recorded nothing (a draw with no array enabled), the check alone is recorded.
    pub fn guard_since(&mut self, mark: usize) {
        let Some(c) = &mut self.compiling else { return };
        let ops: Vec<ListOp> = c.ops.drain(mark..).collect();
        c.ops.push(ListOp::Deferred(Box::new(move |ctx| {
            if ctx.inside_begin_end() {
                ctx.set_error(gl::GL_INVALID_OPERATION);
            } else {
                ctx.run_list_ops(&ops);
            }
        })));
    }
}

impl Context {
    /// `glNewList`.
    pub fn glNewList(&mut self, list: GLuint, mode: GLenum) {
        if list == 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glNewList");
        }
        if mode != gl::GL_COMPILE && mode != gl::GL_COMPILE_AND_EXECUTE {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glNewList");
        }
        if self.lists.compiling() {
            return self.set_error_in(gl::GL_INVALID_OPERATION, "glNewList");
        }
        self.lists.compiling =
            Some(Compiling { name: list, execute: mode == gl::GL_COMPILE_AND_EXECUTE, ops: Vec::new() });
    }

    /// `glEndList`: the compiled list replaces any list of that name.
    pub fn glEndList(&mut self) {
        let Some(done) = self.lists.compiling.take() else {
            return self.set_error_in(gl::GL_INVALID_OPERATION, "glEndList");
        };
        let version = NEXT_VERSION.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let mut shared = self.shared.lock();
        shared.lists.versions.insert(done.name, version);
        shared.lists.lists.insert(done.name, done.ops.into());
    }

    /// `glGenLists`: `range` contiguous unused names, reserved as empty lists; 0 on failure.
    pub fn glGenLists(&mut self, range: GLsizei) -> GLuint {
        if range < 0 {
            self.set_error_in(gl::GL_INVALID_VALUE, "glGenLists");
            return 0;
        }
        if range == 0 {
            return 0;
        }
        let mut shared = self.shared.lock();
        let table = &mut shared.lists.lists;
        let range = range as u32;
        let mut first = 1u32;
        for &used in table.keys() {
            if used >= first && used - first >= range {
                break;
            }
            first = first.max(used + 1);
        }
        if first.checked_add(range).is_none() {
            return 0;
        }
        for name in first..first + range {
            table.insert(name, Arc::from(Vec::new()));
        }
        first
    }

    /// `glDeleteLists`.
    pub fn glDeleteLists(&mut self, list: GLuint, range: GLsizei) {
        if range < 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glDeleteLists");
        }
        let end = list.saturating_add(range as u32);
        let mut shared = self.shared.lock();
        let doomed: Vec<GLuint> = shared.lists.lists.range(list..end).map(|(k, _)| *k).collect();
        for name in doomed {
            shared.lists.lists.remove(&name);
            shared.lists.versions.remove(&name);
        }
    }

    /// `glIsList`.
    pub fn glIsList(&mut self, list: GLuint) -> GLboolean {
        GLboolean::from(self.shared.lock().lists.lists.contains_key(&list))
    }

    /// `glListBase`.
    pub fn glListBase(&mut self, base: GLuint) {
        self.lists.base = base;
    }

    /// `glCallList`: executes the list's commands; lists nest up to [`MAX_LIST_NESTING`].
    pub fn glCallList(&mut self, list: GLuint) {
        if self.lists.depth >= MAX_LIST_NESTING {
            return;
        }
        let Some(ops) = self.shared.lock().lists.lists.get(&list).cloned() else { return };
        self.lists.depth += 1;
        let outer = std::mem::replace(&mut self.lists.executing_name, list);
        self.run_list_ops(&ops);
        self.lists.executing_name = outer;
        self.lists.depth -= 1;
    }

    /// Executes recorded commands in order.
    fn run_list_ops(&mut self, ops: &[ListOp]) {
        let _copies_not_client_memory = super::capture::reads::quiet();
        for op in ops {
            match op {
                ListOp::Call(call) => dispatch::execute(self, call),
                ListOp::Deferred(f) => f(self),
            }
        }
    }

    /// `glCallLists`: calls `base + offset` for each of `n` offsets of type `type_`.
    ///
    /// # Safety
    /// `lists` must point to `n` offsets of `type_`.
    pub unsafe fn glCallLists(&mut self, n: GLsizei, type_: GLenum, lists: *const std::ffi::c_void) {
        let Some(offsets) = (unsafe { self.list_offsets(n, type_, lists) }) else { return };
        for offset in offsets {
            self.glCallList(self.lists.base.wrapping_add(offset));
        }
    }

    /// `glCallLists` in a display list: the offsets are copied now, the base applies when the
    /// list is executed.
    ///
    /// # Safety
    /// As [`Context::glCallLists`].
    pub unsafe fn compile_glCallLists(&mut self, n: GLsizei, type_: GLenum, lists: *const std::ffi::c_void) {
        let Some(offsets) = (unsafe { self.list_offsets(n, type_, lists) }) else { return };
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| {
            for &offset in &offsets {
                ctx.glCallList(ctx.lists.base.wrapping_add(offset));
            }
        })));
    }

    /// Decodes `glCallLists` offsets; raises the errors of section 5.4.
    unsafe fn list_offsets(&mut self, n: GLsizei, type_: GLenum, lists: *const std::ffi::c_void) -> Option<Vec<u32>> {
        if n < 0 {
            self.set_error_in(gl::GL_INVALID_VALUE, "glCallLists");
            return None;
        }
        let width = match type_ {
            gl::GL_BYTE | gl::GL_UNSIGNED_BYTE | gl::GL_2_BYTES | gl::GL_3_BYTES | gl::GL_4_BYTES => 1,
            gl::GL_SHORT | gl::GL_UNSIGNED_SHORT => 2,
            gl::GL_INT | gl::GL_UNSIGNED_INT | gl::GL_FLOAT => 4,
            _ => {
                self.set_error_in(gl::GL_INVALID_ENUM, "glCallLists");
                return None;
            }
        };
        let per_name = match type_ {
            gl::GL_2_BYTES => 2,
            gl::GL_3_BYTES => 3,
            gl::GL_4_BYTES => 4,
            _ => 1,
        };
        let n = n as usize;
        if n == 0 {
            return Some(Vec::new());
        }
        let bytes = unsafe { super::convert::read_slice(lists.cast::<u8>(), n * width * per_name) };
        let Some(bytes) = bytes else {
            self.null_pointer("glCallLists");
            return None;
        };
        Some(
            (0..n)
                .map(|i| {
                    let b = &bytes[i * width * per_name..(i + 1) * width * per_name];
                    match type_ {
                        gl::GL_BYTE => b[0] as i8 as i32 as u32,
                        gl::GL_UNSIGNED_BYTE => u32::from(b[0]),
                        gl::GL_SHORT => i16::from_ne_bytes([b[0], b[1]]) as i32 as u32,
                        gl::GL_UNSIGNED_SHORT => u32::from(u16::from_ne_bytes([b[0], b[1]])),
                        gl::GL_INT => i32::from_ne_bytes([b[0], b[1], b[2], b[3]]) as u32,
                        gl::GL_UNSIGNED_INT => u32::from_ne_bytes([b[0], b[1], b[2], b[3]]),
                        gl::GL_FLOAT => f32::from_ne_bytes([b[0], b[1], b[2], b[3]]) as u32,
                        // GL_n_BYTES: big-endian byte sequences (section 5.4, table 5.7).
                        _ => b.iter().fold(0u32, |acc, &x| (acc << 8) | u32::from(x)),
                    }
                })
                .collect(),
        )
    }

    /// The list being compiled and its mode, for `GL_LIST_INDEX` / `GL_LIST_MODE`.
    pub fn compiling_list(&self) -> Option<(GLuint, GLenum)> {
        self.lists.compiling.as_ref().map(|c| {
            (c.name, if c.execute { gl::GL_COMPILE_AND_EXECUTE } else { gl::GL_COMPILE })
        })
    }

    /// `glListBase` value.
    pub fn list_base(&self) -> GLuint {
        self.lists.base
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, dispatch, gl};

    /// Compiles `Begin(POINTS)`, `command`, `End` into list 1 with `mode`; returns the error
    /// left by compiling and the one left by calling the list.
    fn compile_and_call(ctx: &mut Context, mode: gl::GLenum, command: impl Fn(&mut Context)) -> [gl::GLenum; 2] {
        unsafe {
            dispatch::glNewList(ctx, 1, mode);
            dispatch::glBegin(ctx, gl::GL_POINTS);
            command(ctx);
            dispatch::glEnd(ctx);
            dispatch::glEndList(ctx);
        }
        let compiled = ctx.glGetError();
        unsafe { dispatch::glCallList(ctx, 1) };
        [compiled, ctx.glGetError()]
    }

    #[test]
    fn pointer_commands_in_a_list_obey_the_begin_end_rule() {
        let (mut ctx, _) = Context::with_recording();
        let one = 1.0f32;
        let tex_env = |c: &mut Context| unsafe {
            dispatch::glTexEnvfv(c, gl::GL_TEXTURE_ENV, gl::GL_ALPHA_SCALE, &one);
        };
        let invalid = gl::GL_INVALID_OPERATION;
        assert_eq!(compile_and_call(&mut ctx, gl::GL_COMPILE, tex_env), [gl::GL_NO_ERROR, invalid]);
        assert_eq!(compile_and_call(&mut ctx, gl::GL_COMPILE_AND_EXECUTE, tex_env), [invalid, invalid]);
        let raster = |c: &mut Context| unsafe { dispatch::glRasterPos2fv(c, [1.0f32, 2.0].as_ptr()) };
        assert_eq!(compile_and_call(&mut ctx, gl::GL_COMPILE_AND_EXECUTE, raster), [invalid, invalid]);
        // A draw with no array enabled records nothing to draw, but still the rule.
        let draw = |c: &mut Context| unsafe { dispatch::glDrawArrays(c, gl::GL_POINTS, 0, 1) };
        assert_eq!(compile_and_call(&mut ctx, gl::GL_COMPILE, draw), [gl::GL_NO_ERROR, invalid]);
        // Outside Begin/End the guarded command runs when the list is called.
        let two = 2.0f32;
        unsafe {
            dispatch::glNewList(&mut ctx, 2, gl::GL_COMPILE);
            dispatch::glTexEnvfv(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_ALPHA_SCALE, &two);
            dispatch::glEndList(&mut ctx);
            dispatch::glCallList(&mut ctx, 2);
        }
        let mut scale = 0.0f32;
        unsafe { ctx.glGetTexEnvfv(gl::GL_TEXTURE_ENV, gl::GL_ALPHA_SCALE, &mut scale) };
        assert_eq!((scale, ctx.glGetError()), (2.0, gl::GL_NO_ERROR));
    }

    #[test]
    fn client_side_commands_are_refused_inside_begin_end() {
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            dispatch::glBegin(&mut ctx, gl::GL_POINTS);
            dispatch::glEnableClientState(&mut ctx, gl::GL_VERTEX_ARRAY);
            dispatch::glEnd(&mut ctx);
        }
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        assert_eq!(ctx.glIsEnabled(gl::GL_VERTEX_ARRAY), gl::GL_FALSE);
    }
}
