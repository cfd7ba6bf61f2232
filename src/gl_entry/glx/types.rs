//! GLX C types, generated from glx.xml (used by the GLX functions glrt does not implement).

#![allow(non_camel_case_types, non_snake_case, dead_code, missing_docs, clippy::all)]

/// The C types the generated type aliases refer to.
pub mod __gl_imports {
    pub use std::os::raw;
}

/// GLX C types (`GLXContext`, `XVisualInfo`...).
pub mod types {
    #![allow(non_camel_case_types, non_snake_case, dead_code, missing_docs, clippy::all)]
    include!(concat!(env!("OUT_DIR"), "/glx_types.rs"));
    /// Xlib types the template lacks.
    pub type Colormap = XID;
    /// Xlib `Status`.
    pub type Status = super::__gl_imports::raw::c_int;
}
