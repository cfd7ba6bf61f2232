//! The hand-written `glX*` C exports, each a few lines run through
//! [`super::entry::glx_export!`] (panic guard, call log, pass-through): one file per part of
//! GLX 1.4, named as the file of the state it works on in [`super`]. `build/scan.rs` finds
//! the functions here for the `glXGetProcAddress` table.

pub mod config;
pub mod context;
pub mod drawable;
pub mod query;
pub mod swap;
pub mod xfont;
