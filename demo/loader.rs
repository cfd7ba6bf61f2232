//! Function tables resolved at run time, the way Quake 3's `qgl` does it: a struct of function
//! pointers filled with `dlsym` from a library opened by name. [`fn_table!`] declares such a
//! struct together with one calling method per function, so the scene code reads like C
//! (`gl.glBegin(GL_QUADS)`).

use std::ffi::c_void;

use libloading::Library;

/// Declares a table of C functions: `fn_table!(Name { fn glFoo(a: T) -> R; ... })` gives a
/// struct `Name` with `Name::load(resolve)` and an `unsafe` method per function.
macro_rules! fn_table {
    ($(#[$doc:meta])* $table:ident { $( fn $name:ident ( $($arg:ident : $ty:ty),* ) $(-> $ret:ty)? ; )* }) => {
        $(#[$doc])*
        #[allow(non_snake_case)]
        pub struct $table {
            $( $name: unsafe extern "C" fn($($ty),*) $(-> $ret)?, )*
        }

        #[allow(non_snake_case, clippy::too_many_arguments)]
        impl $table {
            /// Resolves every function with `resolve` (which returns null for a missing name);
            /// the error names the first missing function.
            pub fn load(
                mut resolve: impl FnMut(&str) -> *mut std::ffi::c_void,
            ) -> Result<Self, String> {
                Ok(Self {
                    $( $name: {
                        let ptr = resolve(stringify!($name));
                        if ptr.is_null() {
                            return Err(format!("missing function {}", stringify!($name)));
                        }
                        // Safety: the library exports this name with this C signature.
                        unsafe { std::mem::transmute::<*mut std::ffi::c_void, unsafe extern "C" fn($($ty),*) $(-> $ret)?>(ptr) }
                    }, )*
                })
            }

            $(
                /// Calls the C function of the same name.
                ///
                /// # Safety
                /// As for the C function: a current context where GL needs one, and valid
                /// pointers for the sizes the function reads or writes.
                #[inline]
                pub unsafe fn $name(&self, $($arg: $ty),*) $(-> $ret)? {
                    unsafe { (self.$name)($($arg),*) }
                }
            )*
        }
    };
}
pub(crate) use fn_table;

/// The loaded GL library (`libGL.so.1` or `--lib PATH`).
pub struct GlLibrary {
    lib: Library,
    /// What was loaded, for messages.
    pub name: String,
}

impl GlLibrary {
    /// Opens `name` with `dlopen` (a bare soname is searched like any library, so
    /// `LD_LIBRARY_PATH` picks a replacement).
    pub fn open(name: &str) -> Result<Self, String> {
        // Safety: loading a GL library runs its initialisers, which is what a game does too.
        let lib = unsafe { Library::new(name) }.map_err(|e| format!("cannot load {name}: {e}"))?;
        Ok(Self { lib, name: name.to_owned() })
    }

    /// `dlsym(name)`, or null when the library does not export it.
    pub fn symbol(&self, name: &str) -> *mut c_void {
        // Safety: the symbol is only read as an address, never called with a guessed type.
        unsafe { self.lib.get::<*mut c_void>(name) }.map(|s| *s).unwrap_or(std::ptr::null_mut())
    }
}
