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
    /// While a `compile_` method of a command that is not allowed between `glBegin` and
    /// `glEnd` records, that command's name: its deferred operations then apply the rule of
    /// section 2.6.3 when the list is executed (set by the generated dispatch).
    outside_begin_end_only: Option<&'static str>,
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

    /// Runs `compile` (a command's `compile_` method) so that the deferred operations it
    /// records raise `GL_INVALID_OPERATION` instead of running when the list is executed
    /// between `glBegin` and `glEnd` (`Some(command)`), or run as they are (`None`).
    /// A command that records nothing (a draw of zero vertices) still raises the error there.
    pub fn compile_with_rule(ctx: &mut Context, rule: Option<&'static str>, compile: impl FnOnce(&mut Context)) {
        let recorded = |lists: &ListState| lists.compiling.as_ref().map_or(0, |c| c.ops.len());
        let before = recorded(&ctx.lists);
        ctx.lists.outside_begin_end_only = rule;
        compile(ctx);
        if rule.is_some() && recorded(&ctx.lists) == before {
            ctx.lists.record(ListOp::Deferred(Box::new(|_| {})));
        }
        ctx.lists.outside_begin_end_only = None;
    }

    /// Appends a command to the list being compiled.
    pub fn record(&mut self, op: ListOp) {
        let op = match (op, self.outside_begin_end_only) {
            (ListOp::Deferred(run), Some(command)) => ListOp::Deferred(Box::new(move |ctx| {
                if ctx.inside_begin_end() {
                    ctx.set_error_in(gl::GL_INVALID_OPERATION, command);
                } else {
                    run(ctx);
                }
            })),
            (op, _) => op,
        };
        if let Some(c) = &mut self.compiling {
            c.ops.push(op);
        }
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
        self.shared.lock().lists.lists.insert(done.name, done.ops.into());
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
        for op in ops.iter() {
            match op {
                ListOp::Call(call) => dispatch::execute(self, call),
                ListOp::Deferred(f) => f(self),
            }
        }
        self.lists.executing_name = outer;
        self.lists.depth -= 1;
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
