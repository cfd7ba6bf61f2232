//! Conformance of the C exports against the OpenGL 1.5 specification, one test binary: the
//! built library's exported symbols ([`exports`]), the initial state tables
//! ([`initial_state`]), errors ([`errors`]), the Begin/End rule ([`begin_end`]), display lists
//! ([`display_lists`]) and attribute groups ([`attrib`]). Each test makes its own headless
//! context current on its own thread, so the tests share the process.

#[path = "../common/mod.rs"]
mod common;

mod attrib;
mod begin_end;
mod display_lists;
mod errors;
mod exports;
mod initial_state;
