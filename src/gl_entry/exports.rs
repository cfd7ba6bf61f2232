//! The generated C exports: one `#[no_mangle]` shim per OpenGL function (every OpenGL 1.0–1.5
//! function, the implemented extensions, and every other name glvnd's `libGL.so.1` exports),
//! and [`PROCS`], the table behind `glXGetProcAddress`.

#![allow(non_snake_case, clippy::missing_safety_doc, clippy::too_many_arguments)]

include!(concat!(env!("OUT_DIR"), "/exports.rs"));

/// The exported function called `name`, or null (`glXGetProcAddress`).
pub fn proc_address(name: &[u8]) -> *const () {
    PROCS
        .binary_search_by(|(n, _)| n.as_bytes().cmp(name))
        .map_or(std::ptr::null(), |i| PROCS[i].1.0)
}
