//! The call log: `GLRT_TRACE=path` writes one line per GL call the generated exports receive,
//! one per GLX call, and one per frame boundary (`glXSwapBuffers`, `glrtSwapBuffers`).
//!
//! Line format (`N` is the frame number, counted from 0 and raised at each frame boundary, over
//! all contexts of the process):
//! - `N glBegin(mode=GL_QUADS)`, `N glVertex3f(x=1.0, y=2.0, z=0.5)`;
//! - enums by name, from the parameter's gl.xml group when it has one (`GL_POINTS`, not
//!   `GL_NONE`), else the preferred name of the value ([`gl::enum_name`]), else hex;
//! - `GLint` parameters of a gl.xml group (`glTexImage2D`'s `internalformat`) by the name of
//!   the group member of that value, else as numbers;
//! - `GLint`/`GLfloat` `param`s of a `pname` whose value is a constant
//!   (`glTexParameterf(..., pname=GL_TEXTURE_MIN_FILTER, param=GL_LINEAR)`) by name, from the
//!   table in [`params`];
//! - bitfields of a gl.xml group as an OR of its names (`GL_COLOR_BUFFER_BIT|GL_DEPTH_BUFFER_BIT`),
//!   with any bits no name covers in hex;
//! - pointers: `NULL`, or the address (in a replay, the captured program's address, so that
//!   `glrt dump` prints the same text on every run); where gl.xml gives a fixed length (`glVertex3fv`: 3,
//!   `glLoadMatrixf`: 16) also the bytes read, their xxh3 hash and the values,
//!   `0x7ffc…(12 bytes, xxh3 …)[1.0, 0.0, 0.0]`. Pointers whose size depends on other
//!   arguments or on GL state print the address only;
//! - ` = value` for a command's result (`glGetString`'s: the quoted text), ` -> GL_INVALID_ENUM` when the call raised an error
//!   (the latched error was `GL_NO_ERROR` before the call and is set after: an error raised
//!   while an earlier one is still latched is dropped by GL, and not shown), ` (no current
//!   context)` when the call had no context to run on;
//! - the GLX functions with their arguments and result, printed by `glx::entry`:
//!   `N glXMakeCurrent(dpy=0x55d0c1a2e2a0, drawable=0x200002, ctx=0x55d0c1b3f010) = True`;
//! - `N == end of frame (glXSwapBuffers)` at a frame boundary;
//! - comments `N # texture 5 hash 0x…` (the `glrt.toml` name of a texture, written when a
//!   texture's content first reaches a frame or changes: [`note`]).
//!
//! `GLRT_TRACE_FILTER=pattern` keeps the calls whose name contains `pattern` (a plain,
//! case-sensitive substring: `glVertex` keeps `glVertex3f` and `glVertexPointer`; comments
//! whose text contains it are kept too); frame boundaries are always written.
//!
//! The log is buffered, written under a lock one line at a time, flushed at each frame boundary
//! and at exit. The environment is read at the first GL call; a file that cannot be created
//! is reported once on standard error and tracing stays off. When off, an export pays one
//! relaxed atomic load ([`begin`]).

pub mod params;
pub mod sizes;

use std::fmt::Write as _;
use std::fs::File;
use std::io::{self, BufWriter, Write as _};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicU64, Ordering};

use parking_lot::Mutex;
use sizes::Typed;

use super::current::with_slot;
use super::mode::{self, Mode};
use crate::translate::classify::texture_hash;
use crate::translate::gl::{self, GLbitfield, GLchar, GLenum, GLint, GLsizei, GLubyte};

/// The gl.xml enum groups the log prints parameters by: `(name, value)` per member.
#[allow(non_upper_case_globals)]
pub mod groups {
    include!(concat!(env!("OUT_DIR"), "/call_log_groups.rs"));
}

/// The current frame number.
static FRAME: AtomicU64 = AtomicU64::new(0);

/// The open log and its filter.
struct Log {
    out: Mutex<BufWriter<File>>,
    filter: Option<String>,
}

/// The log, once `GLRT_TRACE` named a file that could be created.
static LOG: OnceLock<Log> = OnceLock::new();

/// A call being logged: its line, written by [`Entry::end`].
pub struct Entry {
    line: String,
    /// Whether an argument was printed (for the separators).
    args: usize,
}

/// Starts the log line of a call to `name`, or `None` when tracing is off in `mode` or
/// `name` does not match `GLRT_TRACE_FILTER`.
pub fn begin(mode: Mode, name: &'static str) -> Option<Entry> {
    if !mode.tracing() {
        return None;
    }
    let log = LOG.get()?;
    if !keeps(log.filter.as_deref(), name) {
        return None;
    }
    let mut line = String::with_capacity(96);
    let _ = write!(line, "{} {name}(", FRAME.load(Ordering::Relaxed));
    Some(Entry { line, args: 0 })
}

/// Whether `GLRT_TRACE_FILTER` (`filter`) keeps calls to `name`: a substring match.
fn keeps(filter: Option<&str>, name: &str) -> bool {
    filter.is_none_or(|f| name.contains(f))
}

/// Opens the log `GLRT_TRACE` names (with `GLRT_TRACE_FILTER`), at most once per process
/// ([`super::mode`] calls it at the first GL call), and has hash tracking announce texture
/// hashes to it ([`note`]); true when it is open.
pub(super) fn open_from_environment() -> bool {
    if LOG.get().is_none()
        && let Some(log) = open()
    {
        let _ = LOG.set(log);
        texture_hash::announce_hashes_to(|id, hash| note(format_args!("texture {id} hash {hash:#018x}")));
    }
    LOG.get().is_some()
}

/// Opens the file `GLRT_TRACE` names, if any.
fn open() -> Option<Log> {
    let path = std::env::var_os("GLRT_TRACE").filter(|p| !p.is_empty())?;
    match File::create(&path) {
        Ok(file) => {
            // Safety: `flush_at_exit` is a plain function that never unwinds.
            unsafe { atexit(flush_at_exit) };
            let filter = std::env::var("GLRT_TRACE_FILTER").ok().filter(|f| !f.is_empty());
            Some(Log { out: Mutex::new(BufWriter::with_capacity(1 << 16, file)), filter })
        }
        Err(e) => {
            let _ = writeln!(io::stderr(), "glrt: GLRT_TRACE: cannot create {}: {e}; tracing is off", path.display());
            None
        }
    }
}

unsafe extern "C" {
    /// C library: runs `f` at `exit` (or when this library is unloaded).
    fn atexit(f: extern "C" fn()) -> std::ffi::c_int;
}

extern "C" fn flush_at_exit() {
    let _ = catch_unwind(flush);
}

/// Writes buffered log lines to the file.
pub fn flush() {
    if let Some(log) = LOG.get() {
        write_or_stop(log, |out| out.flush());
    }
}

/// Runs a write on the log; on failure reports it once and turns tracing off.
fn write_or_stop(log: &Log, f: impl FnOnce(&mut BufWriter<File>) -> io::Result<()>) {
    if let Err(e) = f(&mut log.out.lock())
        && mode::stop_tracing()
    {
        let _ = writeln!(io::stderr(), "glrt: GLRT_TRACE: write failed: {e}; tracing is off");
    }
}

/// Marks the end of a frame (`name` is the swap call): writes the boundary line, flushes, and
/// counts the next frame.
pub fn frame_end(name: &'static str) {
    let Some(log) = mode::special().filter(|m| m.tracing()).and_then(|_| LOG.get()) else { return };
    let frame = FRAME.fetch_add(1, Ordering::Relaxed);
    write_or_stop(log, |out| {
        writeln!(out, "{frame} == end of frame ({name})")?;
        out.flush()
    });
}

/// Writes a comment line `N # text` (frame number `N`), such as the hash of a texture whose
/// content changed (`translate::classify`); nothing when tracing is off, or when
/// `GLRT_TRACE_FILTER` is set and `text` does not contain it.
fn note(text: std::fmt::Arguments<'_>) {
    let Some(log) = mode::special().filter(|m| m.tracing()).and_then(|_| LOG.get()) else { return };
    let text = text.to_string();
    if !keeps(log.filter.as_deref(), &text) {
        return;
    }
    let frame = FRAME.load(Ordering::Relaxed);
    write_or_stop(log, |out| writeln!(out, "{frame} # {text}"));
}

/// The latched GL error of this thread's current context, `None` without one.
fn latched() -> Option<GLenum> {
    catch_unwind(AssertUnwindSafe(|| {
        with_slot(|slot| slot.as_ref().filter(|c| !c.broken).map(|c| c.context.latched_error()))
    }))
    .ok()
    .flatten()
}

/// A value the log prints as it is.
pub trait Arg: Copy {
    /// Appends the value to `out`.
    fn print(self, out: &mut String);
}

macro_rules! display_arg {
    ($($t:ty),*) => { $(impl Arg for $t { fn print(self, out: &mut String) { let _ = write!(out, "{self}"); } })* };
}
display_arg!(u8, i8, u16, i16, u32, i32, u64, i64, usize, isize);

macro_rules! float_arg {
    ($($t:ty),*) => { $(impl Arg for $t { fn print(self, out: &mut String) { let _ = write!(out, "{self:?}"); } })* };
}
float_arg!(f32, f64);

/// Pointers print as the captured program's address during a replay (the shadow's addresses
/// mapped back, `translate::capture::captured_address`), so that `glrt dump` prints the same
/// text on every run; elsewhere as they are.
impl<T> Arg for *const T {
    fn print(self, out: &mut String) {
        if self.is_null() {
            out.push_str("NULL");
        } else {
            let _ = write!(out, "{:#x}", crate::translate::capture::captured_address(self as u64));
        }
    }
}

impl<T> Arg for *mut T {
    fn print(self, out: &mut String) {
        self.cast_const().print(out);
    }
}

/// How many elements or bytes of a variable-size pointer the log prints.
pub const FIRST_VALUES: usize = 16;

/// Appends the first [`FIRST_VALUES`] elements of `typed` in `bytes`: `[1, 2, 3]`, with `...`
/// when there are more. `GL_2_BYTES`..`GL_4_BYTES` names are big-endian (section 5.4).
fn print_elements(out: &mut String, bytes: &[u8], typed: Typed) {
    let size = sizes::element_size(typed.type_).unwrap_or(1);
    out.push('[');
    for (i, e) in bytes.chunks_exact(size).take(FIRST_VALUES).enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        // `e` has exactly the type's size (1, 2 or 4 bytes for these types).
        let _ = match typed.type_ {
            gl::GL_BYTE => write!(out, "{}", e[0] as i8),
            gl::GL_SHORT => write!(out, "{}", i16::from_ne_bytes([e[0], e[1]])),
            gl::GL_UNSIGNED_SHORT => write!(out, "{}", u16::from_ne_bytes([e[0], e[1]])),
            gl::GL_INT => write!(out, "{}", i32::from_ne_bytes([e[0], e[1], e[2], e[3]])),
            gl::GL_UNSIGNED_INT => write!(out, "{}", u32::from_ne_bytes([e[0], e[1], e[2], e[3]])),
            gl::GL_FLOAT => write!(out, "{:?}", f32::from_ne_bytes([e[0], e[1], e[2], e[3]])),
            // GL_UNSIGNED_BYTE and the big-endian GL_n_BYTES.
            _ => write!(out, "{}", e.iter().fold(0u32, |v, &b| v << 8 | u32::from(b))),
        };
    }
    out.push_str(if typed.count > FIRST_VALUES { ", ...]" } else { "]" });
}

/// The name of `value` in `group`, else its preferred name among all constants.
fn name_in(value: u64, group: &[(&'static str, u64)]) -> Option<&'static str> {
    member(value, group).or_else(|| u32::try_from(value).ok().and_then(gl::enum_name))
}

/// The preferred name of `value` among the members of `group`.
fn member(value: u64, group: &[(&'static str, u64)]) -> Option<&'static str> {
    gl::best_name(group.iter().filter(|(_, v)| *v == value).map(|(n, _)| *n))
}

/// Appends `value` by name (`GL_QUADS`), or in hex when no constant has that value.
fn print_enum(out: &mut String, value: GLenum, group: &[(&'static str, u64)]) {
    match name_in(u64::from(value), group) {
        Some(name) => out.push_str(name),
        None => {
            let _ = write!(out, "{value:#x}");
        }
    }
}

/// Appends `bits` as the OR of the names of `group` it contains, then any bits left in hex;
/// `0` when empty.
fn print_bits(out: &mut String, bits: GLbitfield, group: &[(&'static str, u64)]) {
    if bits == 0 {
        out.push('0');
        return;
    }
    let mut left = u64::from(bits);
    let mut first = true;
    let mut sep = |out: &mut String| {
        if !std::mem::take(&mut first) {
            out.push('|');
        }
    };
    for &(name, value) in group {
        if value != 0 && value.count_ones() == 1 && left & value != 0 {
            sep(out);
            out.push_str(name);
            left &= !value;
        }
    }
    if left != 0 {
        sep(out);
        let _ = write!(out, "{left:#x}");
    }
}

impl Entry {
    /// Starts the next argument, `name=`; the caller appends the value.
    pub(crate) fn next(&mut self, name: &str) -> &mut String {
        if self.args > 0 {
            self.line.push_str(", ");
        }
        self.args += 1;
        self.line.push_str(name);
        self.line.push('=');
        &mut self.line
    }

    /// A scalar or pointer argument, printed as it is.
    pub fn arg<T: Arg>(&mut self, name: &str, value: T) {
        value.print(self.next(name));
    }

    /// A `GLenum` argument of enum group `group` (empty when it has none).
    pub fn enumerant(&mut self, name: &str, value: GLenum, group: &[(&'static str, u64)]) {
        print_enum(self.next(name), value, group);
    }

    /// A `GLbitfield` argument of enum group `group`.
    pub fn bits(&mut self, name: &str, value: GLbitfield, group: &[(&'static str, u64)]) {
        print_bits(self.next(name), value, group);
    }

    /// A `GLint` argument of enum group `group` (`glTexImage2D`'s `internalformat`): the
    /// member's name when `value` is one, else the number (`internalformat=3`).
    pub fn int_or_enum(&mut self, name: &str, value: GLint, group: &[(&'static str, u64)]) {
        let out = self.next(name);
        match u64::try_from(value).ok().and_then(|v| member(v, group)) {
            Some(member) => out.push_str(member),
            None => value.print(out),
        }
    }

    /// The scalar `param` of a command that takes a `pname` (`glTexParameterf`, `glFogi`): by
    /// name when `pname` takes constants ([`params`]) and `value` is one of
    /// them, else as the number.
    pub fn param_of<T: Arg + Into<f64>>(&mut self, name: &str, pname: GLenum, value: T) {
        let out = self.next(name);
        match params::name_of(pname, value.into()) {
            Some(constant) => out.push_str(constant),
            None => value.print(out),
        }
    }

    /// An argument of a type the log does not print (`?`).
    pub fn opaque(&mut self, name: &str) {
        self.next(name).push('?');
    }

    /// A pointer to `len` values: `NULL`, or the address, the bytes read and their hash, and
    /// the values: `0x7ffd5c0e1a3c(12 bytes, xxh3 a1f7c2750768aadb)[1.0, 2.5, -3.0]`.
    ///
    /// # Safety
    /// A non-null `ptr` points to `len` readable values (what the command itself reads).
    pub unsafe fn values<T: Arg>(&mut self, name: &str, ptr: *const T, len: usize) {
        // Safety: as documented.
        let Some(out) = (unsafe { self.summary(name, ptr.cast(), len * size_of::<T>()) }) else { return };
        out.push('[');
        for i in 0..len {
            if i > 0 {
                out.push_str(", ");
            }
            // Safety: as documented.
            unsafe { ptr.add(i).read_unaligned() }.print(out);
        }
        out.push(']');
    }

    /// [`Entry::values`] when the length is known (`Some`), else the address only.
    ///
    /// # Safety
    /// As [`Entry::values`].
    pub unsafe fn values_if<T: Arg>(&mut self, name: &str, ptr: *const T, len: Option<usize>) {
        match len {
            // Safety: as documented.
            Some(len) => unsafe { self.values(name, ptr, len) },
            None => self.arg(name, ptr),
        }
    }

    /// A client array of GL-typed elements (`glCallLists` names, `glDrawElements` indices):
    /// the summary and the first [`FIRST_VALUES`] elements; the address only when the size is
    /// not known (`None`).
    ///
    /// # Safety
    /// A non-null `ptr` points to the elements `typed` describes.
    pub unsafe fn typed(&mut self, name: &str, ptr: *const std::ffi::c_void, typed: Option<Typed>) {
        let Some(typed) = typed else { return self.arg(name, ptr) };
        // Safety: as documented.
        let Some(out) = (unsafe { self.summary(name, ptr, typed.bytes()) }) else { return };
        // Safety: as documented.
        let bytes = unsafe { std::slice::from_raw_parts(ptr.cast::<u8>(), typed.bytes()) };
        print_elements(out, bytes, typed);
    }

    /// Client bytes of a known size (a pixel image): the summary and the first
    /// [`FIRST_VALUES`] bytes in hex; the address only when the size is not known (`None`).
    ///
    /// # Safety
    /// A non-null `ptr` points to `len` readable bytes.
    pub unsafe fn bytes(&mut self, name: &str, ptr: *const std::ffi::c_void, len: Option<usize>) {
        let Some(len) = len else { return self.arg(name, ptr) };
        // Safety: as documented.
        let Some(out) = (unsafe { self.summary(name, ptr, len) }) else { return };
        // Safety: as documented.
        let bytes = unsafe { std::slice::from_raw_parts(ptr.cast::<u8>(), len) };
        out.push('[');
        for (i, b) in bytes.iter().take(FIRST_VALUES).enumerate() {
            let _ = write!(out, "{}{b:02x}", if i > 0 { " " } else { "" });
        }
        out.push_str(if len > FIRST_VALUES { " ...]" } else { "]" });
    }

    /// `glShaderSource`'s `count` strings (lengths from `length`, or NUL-terminated): the
    /// address, then each string quoted: `0x55d0c8e2a010["void main() {}"]`.
    ///
    /// # Safety
    /// As `glShaderSource`'s arguments.
    pub unsafe fn strings(&mut self, name: &str, ptr: *const *const GLchar, count: GLsizei, length: *const GLint) {
        let out = self.next(name);
        ptr.print(out);
        if ptr.is_null() {
            return;
        }
        out.push('[');
        for i in 0..usize::try_from(count).unwrap_or(0) {
            // Safety: as documented.
            let s = unsafe { crate::translate::programs::objects::source_string(ptr, length, i) };
            let _ = write!(out, "{}{s:?}", if i > 0 { ", " } else { "" });
        }
        out.push(']');
    }

    /// Starts pointer argument `name`: `NULL` (then `None`), or the address, the size and the
    /// xxh3 hash of its `len` bytes, `0x7ffd5c0e1a3c(12 bytes, xxh3 a1f7c2750768aadb)`.
    ///
    /// # Safety
    /// A non-null `ptr` points to `len` readable bytes.
    unsafe fn summary(&mut self, name: &str, ptr: *const std::ffi::c_void, len: usize) -> Option<&mut String> {
        let out = self.next(name);
        ptr.print(out);
        if ptr.is_null() {
            return None;
        }
        // Safety: as documented; any bytes are valid `u8`s.
        let bytes = unsafe { std::slice::from_raw_parts(ptr.cast::<u8>(), len) };
        let _ = write!(out, "({len} bytes, xxh3 {:016x})", xxhash_rust::xxh3::xxh3_64(bytes));
        Some(out)
    }

    /// Runs the call, noting the error it raised (or that there was no current context).
    /// In pass-through mode the call runs in another library, whose error glrt does not read
    /// (calling its `glGetError` would clear the error before the program sees it): the line
    /// shows the call only.
    pub fn observe<R>(&mut self, mode: Mode, call: impl FnOnce() -> R) -> R {
        self.line.push(')');
        if mode.passthrough() {
            return call();
        }
        let before = latched();
        let result = call();
        match (before, latched()) {
            (Some(gl::GL_NO_ERROR), Some(error)) if error != gl::GL_NO_ERROR => {
                self.line.push_str(" -> ");
                print_enum(&mut self.line, error, groups::ErrorCode);
            }
            (None, _) | (_, None) => self.line.push_str(" (no current context)"),
            _ => {}
        }
        result
    }

    /// Ends the argument list (for calls not run through [`Entry::observe`]).
    pub fn close_args(&mut self) {
        self.line.push(')');
    }

    /// Appends the call's result as `print` writes it.
    pub fn returned_with(&mut self, print: impl FnOnce(&mut String)) {
        print(&mut self.line);
    }

    /// The call's result.
    pub fn returned<T: Arg>(&mut self, value: T) {
        self.line.push_str(" = ");
        value.print(&mut self.line);
    }

    /// The call's string result (`glGetString`): the text, quoted (`NULL` for none), not the
    /// address, which is the library's own and changes from run to run.
    pub fn returned_string(&mut self, value: *const GLubyte) {
        self.line.push_str(" = ");
        if value.is_null() {
            self.line.push_str("NULL");
        } else {
            // Safety: glGetString returns a NUL-terminated string that lives as long as glrt.
            let text = unsafe { std::ffi::CStr::from_ptr(value.cast()) }.to_string_lossy();
            let _ = write!(self.line, "{text:?}");
        }
    }

    /// The call's `GLenum` result (`glGetError`), by name; 0 is `GL_NO_ERROR`.
    pub fn returned_enum(&mut self, value: GLenum) {
        self.line.push_str(" = ");
        if value == gl::GL_NO_ERROR {
            self.line.push_str("GL_NO_ERROR");
        } else {
            print_enum(&mut self.line, value, groups::ErrorCode);
        }
    }

    /// Writes the line.
    pub fn end(mut self) {
        self.line.push('\n');
        if let Some(log) = LOG.get() {
            write_or_stop(log, |out| out.write_all(self.line.as_bytes()));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bits(value: GLbitfield) -> String {
        let mut s = String::new();
        print_bits(&mut s, value, groups::ClearBufferMask);
        s
    }

    #[test]
    fn bitfields_print_as_or_of_group_names() {
        assert_eq!(bits(gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT), "GL_COLOR_BUFFER_BIT|GL_DEPTH_BUFFER_BIT");
        assert_eq!(bits(0), "0");
        assert_eq!(bits(gl::GL_STENCIL_BUFFER_BIT | 0x2), "GL_STENCIL_BUFFER_BIT|0x2");
    }

    #[test]
    fn enums_prefer_the_parameter_group() {
        let mut s = String::new();
        print_enum(&mut s, gl::GL_POINTS, groups::PrimitiveType);
        assert_eq!(s, "GL_POINTS");
        s.clear();
        print_enum(&mut s, gl::GL_TEXTURE_2D, &[]);
        assert_eq!(s, "GL_TEXTURE_2D");
        s.clear();
        print_enum(&mut s, 0xdead_beef, &[]);
        assert_eq!(s, "0xdeadbeef");
    }

    #[test]
    fn arguments_and_fixed_length_pointers() {
        let mut t = Entry { line: "0 glFoo(".into(), args: 0 };
        let v = [1.0f32, 2.5, -3.0];
        t.arg("x", 0.5f32);
        unsafe { t.values("v", v.as_ptr(), 3) };
        unsafe { t.values("w", std::ptr::null::<f32>(), 3) };
        t.opaque("cb");
        let line = t.line;
        assert!(line.starts_with("0 glFoo(x=0.5, v=0x"), "{line}");
        let hash = xxhash_rust::xxh3::xxh3_64(&v.iter().flat_map(|f| f.to_ne_bytes()).collect::<Vec<u8>>());
        assert!(line.ends_with(&format!("(12 bytes, xxh3 {hash:016x})[1.0, 2.5, -3.0], w=NULL, cb=?")), "{line}");
    }

    #[test]
    fn integers_of_a_group_print_members_by_name() {
        let mut t = Entry { line: String::new(), args: 0 };
        t.int_or_enum("internalformat", gl::GL_RGB as GLint, groups::InternalFormat);
        t.int_or_enum("internalformat", 3, groups::InternalFormat);
        assert_eq!(t.line, "internalformat=GL_RGB, internalformat=3");
    }

    #[test]
    fn the_filter_is_a_substring() {
        assert!(keeps(None, "glBegin"));
        assert!(keeps(Some("glVertex"), "glVertex3f"));
        assert!(keeps(Some("Vertex"), "glVertexPointer"));
        assert!(!keeps(Some("glVertex"), "glBegin"));
        assert!(!keeps(Some("glvertex"), "glVertex3f"));
    }
}
