//! Build script: generates glrt's OpenGL surface from the Khronos registry (gl.xml and glx.xml as
//! shipped by the `khronos_api` crate, read through `gl_generator`'s `Registry`).
//!
//! Outputs (all in `OUT_DIR`, included by the modules named):
//! - `gl_types.rs`, `gl_enums.rs`: C types and every `GL_*` constant (`translate::gl`);
//! - `dispatch.rs`: per command, the display-list and `glBegin`/`glEnd` rules and the call into
//!   `translate::Context`; the `Call` enum of commands recorded into display lists
//!   (`translate::dispatch`);
//! - `exports.rs`: the C ABI shim of every exported name and the `glXGetProcAddress` table
//!   (`gl_entry::exports`), each writing the call log when `GLRT_TRACE` is set;
//! - `call_log_groups.rs`: the gl.xml enum groups the call log prints parameters by
//!   (`gl_entry::call_log::groups`);
//! - `fuzz_calls.rs`: a random-argument caller of every served command, for the robustness
//!   test (`translate::robustness`);
//! - `capture_commands.rs`: the command table of capture files (`translate::capture::table`);
//! - `replay_calls.rs`: the replay thunks, command id to C export (`replay::calls`);
//! - `glsl/generated/*.glsl`: the constants Rust shares with the shaders, as GLSL headers
//!   (`glsl_constants.rs`);
//! - `shaders/*.spv`: the renderer's GLSL shaders compiled to SPIR-V, and `layouts/*.rs`: the
//!   assertions that hold the Rust mirrors of their structs to the compiled layouts
//!   (`shaders.rs`, `spirv_layout.rs`).
//!
//! A command is implemented when `translate` defines a method with exactly its C name
//! (`fn glVertex4f(`); the generator finds these by scanning the sources, so exporting a new
//! command is writing its method. Commands without one are exported as functions that raise
//! `GL_INVALID_OPERATION` and log their name once.

mod emit;
mod emit_call_log;
mod emit_capture;
mod emit_fuzz;
mod glsl_constants;
mod model;
mod overlay;
mod scan;
mod shaders;
mod spirv_layout;

use std::path::PathBuf;

fn main() {
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("OUT_DIR"));
    for input in ["build", "src/translate", "src/gl_entry"] {
        println!("cargo:rerun-if-changed={input}");
    }
    let model = model::Model::load();
    emit::write_all(&model, &out).expect("writing generated sources");
    let include = glsl_constants::write_all(&out);
    shaders::compile_all(&out, &include);
    // The library is a drop-in libGL.so.1.
    println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libGL.so.1");
    // Its own gl*/glX* symbols bind inside it: loaded as a glvnd vendor, libGL.so.1's and
    // libGLX.so.0's same-named entry points must not replace the addresses it hands out.
    println!("cargo:rustc-cdylib-link-arg=-Wl,-Bsymbolic");
}
