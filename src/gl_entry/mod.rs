//! The C ABI: every exported `gl*` and `glX*` symbol and `glXGetProcAddress`. Each entry is a
//! thin shim (catch panics, find the current context, call `translate`); the GL list is
//! generated from the Khronos registry by `build/`.

pub mod current;
pub mod exports;
pub mod glvnd;
pub mod glx;
pub mod glx_config;
pub mod glx_context;
pub mod glx_drawable;
pub mod glx_query;
pub mod glx_swap;
pub mod glx_types;
pub mod glx_xfont;
pub mod headless;
pub mod mode;
pub mod passthrough;
pub mod shim;
pub mod trace;
pub mod trace_params;
pub mod trace_sizes;
