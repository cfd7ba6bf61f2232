//! The C ABI: every exported `gl*` and `glX*` symbol and `glXGetProcAddress`. Each entry is a
//! thin shim (catch panics, find the current context, call `translate`); the GL list is
//! generated from the Khronos registry by `build/`.
//!
//! - [`exports`]: the generated `gl*` exports and the `glXGetProcAddress` table; [`shim`],
//!   what each of them does; [`current`], each thread's current context;
//! - [`glx`]: GLX 1.4, its state and, in [`glx::exports`], its hand-written `glX*` exports;
//! - [`headless`]: contexts without a window system (`glrtCreateContext`, used by replay);
//! - [`call_log`]: the `GLRT_TRACE` call log; [`mode`] and [`passthrough`], the modes that
//!   log or forward calls; [`glvnd`], loading as a libglvnd vendor.

pub mod call_log;
pub mod current;
pub mod exports;
pub mod glvnd;
pub mod glx;
pub mod headless;
pub mod mode;
pub mod passthrough;
pub mod shim;
