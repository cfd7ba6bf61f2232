//! Pass-through mode: `GLRT_PASSTHROUGH=/path/to/libGL.so.1` forwards every exported `gl*`
//! and `glX*` call to the same-named function of another OpenGL library instead of running
//! glrt's own implementation, so that a program can be logged (`GLRT_TRACE`) on the user's
//! normal driver and the log compared with glrt's.
//!
//! - The library is opened with `RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND`: its symbols stay out
//!   of the global scope (the program keeps calling glrt), and its own references to `gl*` and
//!   `glX*` names resolve inside it and its dependencies before the global scope, where glrt's
//!   exports of the same names come first. glvnd's `libGL.so.1` (Debian, Ubuntu, Fedora) then
//!   loads its vendor (Mesa's `libGLX_mesa.so.0`) as usual; the vendor's own references to
//!   `gl*` names are bound inside it (Mesa links with `-Bsymbolic`).
//! - Functions are resolved at their first call: `dlsym` in the library, else its
//!   `glXGetProcAddressARB` (GLX extension functions, which glvnd's `libGL.so.1` does not
//!   export). A function the library has neither way is logged once and returns zero.
//! - `glXGetProcAddress[ARB]` returns glrt's own export for a name glrt exports (so the calls
//!   the program makes through it are logged too) and the library's address otherwise.
//! - The library's GL errors stay the program's: glrt never calls its `glGetError`, so the call
//!   log shows no ` -> GL_INVALID_...` annotation in this mode; the program's own
//!   `glGetError` calls are logged with their results.
//! - glrt's headless entry points (`glrtCreateContext`...) and the glvnd vendor entry
//!   (`__glx_Main`) are not forwarded: they have no counterpart in another library.
//!
//! A path that cannot be opened, that is glrt itself, or that the process has loaded already
//! (glrt behind glvnd as a vendor: forwarding would come back to glrt) is reported once on
//! standard error and the mode stays off.

use std::ffi::{CStr, CString, OsStr, c_char, c_int};
use std::io::Write as _;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicPtr, Ordering};

use libloading::os::unix::{Library, RTLD_LOCAL, RTLD_NOW};

use super::exports::PROCS;
use crate::translate::convert::ReturnDefault;

/// glibc's `RTLD_DEEPBIND` (`<dlfcn.h>`): the library's own symbols before the global scope.
const RTLD_DEEPBIND: c_int = 0x8;
/// glibc's `RTLD_NOLOAD`: only find a library already loaded.
const RTLD_NOLOAD: c_int = 0x4;

/// The slot value of a function the library does not have.
const MISSING: *mut () = std::ptr::without_provenance_mut(1);

/// `glXGetProcAddressARB`'s C type.
type GetProcAddress = unsafe extern "C" fn(*const c_char) -> *const ();

/// The library calls go to.
struct Real {
    lib: Library,
    /// Its `glXGetProcAddressARB`, when it has one.
    get_proc: Option<GetProcAddress>,
    /// Per export, in [`PROCS`] order: not resolved yet (null), [`MISSING`], or the address.
    table: Box<[AtomicPtr<()>]>,
}

static REAL: OnceLock<Real> = OnceLock::new();

/// Opens the library `GLRT_PASSTHROUGH` names, at most once per process ([`super::mode`] calls
/// it at the first GL call); true when calls are to be forwarded.
pub(super) fn open_from_environment() -> bool {
    if REAL.get().is_none()
        && let Some(path) = std::env::var_os("GLRT_PASSTHROUGH").filter(|p| !p.is_empty())
    {
        match open(&path) {
            Ok(real) => {
                let _ = REAL.set(real);
            }
            Err(why) => {
                let _ = writeln!(std::io::stderr(), "glrt: GLRT_PASSTHROUGH: {}: {why}; glrt runs the calls itself", path.display());
            }
        }
    }
    REAL.get().is_some()
}

/// Loads the library at `path` (see the module documentation for the flags).
fn open(path: &OsStr) -> Result<Real, String> {
    // Already in the process, the library is the program's own libGL (glrt then runs as a glvnd
    // vendor behind it), and forwarding to it would come back to glrt.
    // Safety: with RTLD_NOLOAD nothing is loaded or initialised.
    if unsafe { Library::open(Some(path), RTLD_NOW | RTLD_NOLOAD) }.is_ok() {
        return Err("already loaded in this process (the program's own libGL)".into());
    }
    // Safety: loading a library runs its initialisers; an OpenGL library's are meant to run in
    // any program that links it.
    let lib = unsafe { Library::open(Some(path), RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND) }.map_err(|e| e.to_string())?;
    if address(&lib, c"glrtCreateContext").is_some() {
        return Err("this is glrt itself".into());
    }
    // Safety: `glXGetProcAddressARB` has this C type in every libGL.
    let get_proc = address(&lib, c"glXGetProcAddressARB")
        .map(|p| unsafe { std::mem::transmute::<*const (), GetProcAddress>(p) });
    let table = PROCS.iter().map(|_| AtomicPtr::new(std::ptr::null_mut())).collect();
    Ok(Real { lib, get_proc, table })
}

/// The address of the symbol `name` of `lib`, when it has one.
fn address(lib: &Library, name: &CStr) -> Option<*const ()> {
    // Safety: the symbol's address is only read, not called, here.
    let symbol = unsafe { lib.get::<*const ()>(name) }.ok()?;
    Some(*symbol).filter(|p| !p.is_null())
}

impl Real {
    /// The library's function `name`: its symbol, else what its `glXGetProcAddressARB` gives.
    fn lookup(&self, name: &CStr) -> Option<*const ()> {
        address(&self.lib, name).or_else(|| {
            // Safety: `name` is NUL-terminated; the function only reads it.
            self.get_proc.map(|f| unsafe { f(name.as_ptr()) }).filter(|p| !p.is_null())
        })
    }

    /// Resolves export `index` and remembers the answer.
    #[cold]
    fn resolve(&self, index: usize) -> Option<*const ()> {
        let (name, _) = PROCS[index];
        let found = CString::new(name).ok().and_then(|c| self.lookup(&c));
        self.table[index].store(found.map_or(MISSING, |p| p.cast_mut()), Ordering::Relaxed);
        if found.is_none() {
            log::warn!("GLRT_PASSTHROUGH: the library has no {name}; calls to it do nothing");
        }
        found
    }
}

/// The library's function for export `index` (its position in [`PROCS`]), `None` when
/// pass-through mode is off or the library has no such function.
#[inline]
pub fn real(index: usize) -> Option<*const ()> {
    let real = REAL.get()?;
    let slot = real.table.get(index)?;
    match slot.load(Ordering::Relaxed) {
        p if p.is_null() => real.resolve(index),
        MISSING => None,
        p => Some(p.cast_const()),
    }
}

/// The library's function called `name`, typed like glrt's own export `own` of that name.
///
/// # Safety
/// `F` is the `extern "C"` function-pointer type of the C function `name`.
pub unsafe fn real_like<F: Copy>(_own: F, name: &str) -> Option<F> {
    const { assert!(size_of::<F>() == size_of::<*const ()>()) };
    let index = PROCS.binary_search_by(|(n, _)| n.cmp(&name)).ok()?;
    // Safety: as documented, the address is a function of type `F`.
    real(index).map(|p| unsafe { std::mem::transmute_copy::<*const (), F>(&p) })
}

/// What a forwarded call to `name` returns when it cannot be made: zero, logged once per
/// function by [`real`] (or here, for a function whose C prototype glrt does not know).
pub fn not_forwarded<R: ReturnDefault>(name: &'static str, known_signature: bool) -> R {
    if !known_signature {
        static LOGGED: std::sync::Once = std::sync::Once::new();
        LOGGED.call_once(|| log::warn!("GLRT_PASSTHROUGH: {name} and other functions newer than glrt's registry are not forwarded"));
    }
    R::return_default()
}

/// `glXGetProcAddress` in pass-through mode: glrt's own export of `name` when there is one
/// (its calls are then logged and forwarded), else the library's function; `None` when the
/// mode is off.
pub fn proc_address(name: &CStr) -> Option<*const ()> {
    let real = REAL.get()?;
    let own = super::exports::proc_address(name.to_bytes());
    Some(if own.is_null() { real.lookup(name).unwrap_or(std::ptr::null()) } else { own })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_library_of_gl_functions_is_read_by_name() {
        let lib = unsafe { Library::open(Some("libc.so.6"), RTLD_NOW | RTLD_LOCAL) }.expect("libc");
        assert!(address(&lib, c"strlen").is_some());
        assert!(address(&lib, c"glrtCreateContext").is_none());
        let real = Real { lib, get_proc: None, table: PROCS.iter().map(|_| AtomicPtr::new(std::ptr::null_mut())).collect() };
        let index = PROCS.binary_search_by(|(n, _)| n.cmp(&"glBegin")).expect("glBegin is exported");
        assert_eq!(real.resolve(index), None, "libc has no glBegin");
        assert_eq!(real.table[index].load(Ordering::Relaxed), MISSING);
    }
}
