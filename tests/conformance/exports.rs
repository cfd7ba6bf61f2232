//! Export conformance of the built `libGL.so.1` (`target/<profile>/libglrt.so`): every
//! OpenGL 1.0–1.5 function of the Khronos registry is a dynamic symbol (the Linux OpenGL ABI
//! requires static exports of the core API) and is returned by the `glXGetProcAddress`
//! table; every name glvnd's `libGL.so.1` exports is exported too; the SONAME is
//! `libGL.so.1`; and an exported but unimplemented command raises `GL_INVALID_OPERATION`.

use std::ffi::c_void;
use std::path::PathBuf;
use std::process::Command;

use gl_generator::{Api, Fallbacks, Profile, Registry};
use glrt::gl_entry::{exports, headless};

/// `target/<profile>/libglrt.so`, next to this test's executable's directory
/// (`target/<profile>/deps/`). Cargo builds the cdylib before the integration tests.
fn library_path() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    let profile_dir = exe.parent().and_then(|deps| deps.parent()).expect("target/<profile>");
    let lib = profile_dir.join("libglrt.so");
    assert!(lib.exists(), "{} missing: run `cargo build` first", lib.display());
    lib
}

/// Every command of OpenGL 1.0 through 1.5 (compatibility profile), with its `gl` prefix.
fn gl_1_5_commands() -> Vec<String> {
    let registry =
        Registry::new(Api::Gl, (1, 5), Profile::Compatibility, Fallbacks::None, [] as [&str; 0]);
    registry.cmds.iter().map(|c| format!("gl{}", c.proto.ident)).collect()
}

fn open_library() -> libloading::Library {
    // Safety: loading glrt runs no initialisers with side effects on this process' GL state.
    unsafe { libloading::Library::new(library_path()) }.expect("dlopen libglrt.so")
}

fn is_exported(lib: &libloading::Library, name: &str) -> bool {
    // Safety: the symbol is only compared with null, never called.
    unsafe { lib.get::<*mut c_void>(name) }.is_ok_and(|s| !s.is_null())
}

#[test]
fn registry_lists_the_gl_1_5_surface() {
    let names = gl_1_5_commands();
    // GL 1.0: 306 commands, 1.1: +30, 1.2: +4, 1.3: +46, 1.4: +47, 1.5: +19 = 452 (gl.xml).
    assert!(names.len() > 440, "only {} GL 1.0-1.5 commands in the registry", names.len());
    for expected in
        ["glBegin", "glDrawRangeElements", "glActiveTexture", "glWindowPos3f", "glBufferData"]
    {
        assert!(names.iter().any(|n| n == expected), "{expected} missing from the registry list");
    }
}

#[test]
fn every_gl_1_5_function_is_a_dynamic_symbol() {
    let lib = open_library();
    let missing: Vec<_> = gl_1_5_commands().into_iter().filter(|n| !is_exported(&lib, n)).collect();
    assert!(missing.is_empty(), "not exported: {missing:?}");
}

#[test]
fn get_proc_address_table_has_every_gl_1_5_function_and_nothing_unknown() {
    let missing: Vec<_> = gl_1_5_commands()
        .into_iter()
        .filter(|n| exports::proc_address(n.as_bytes()).is_null())
        .collect();
    assert!(missing.is_empty(), "glXGetProcAddress returns null for: {missing:?}");
    assert!(exports::proc_address(b"glNotAFunction").is_null());
    assert!(exports::proc_address(b"").is_null());
    assert!(exports::proc_address(b"glBegin\0").is_null(), "names are compared exactly");
}

/// The exported `glXGetProcAddressARB` (implemented by the GLX layer; until that is merged
/// the generated placeholder returns null and this test fails).
#[test]
fn exported_get_proc_address_returns_the_exported_functions() {
    let lib = open_library();
    // Safety: glXGetProcAddressARB has this C signature.
    let gpa = unsafe {
        lib.get::<unsafe extern "C" fn(*const u8) -> *const c_void>("glXGetProcAddressARB")
    }
    .expect("glXGetProcAddressARB exported");
    let lookup = |name: &str| {
        let cname = std::ffi::CString::new(name).expect("no NUL in GL names");
        // Safety: cname is NUL-terminated.
        unsafe { gpa(cname.as_ptr().cast()) }
    };
    let mut wrong = Vec::new();
    for name in gl_1_5_commands() {
        // Safety: the symbol is only compared.
        let symbol = unsafe { lib.get::<*const c_void>(name.as_str()) }.map(|s| *s).ok();
        if symbol != Some(lookup(&name)) || symbol.is_none_or(|s| s.is_null()) {
            wrong.push(name);
        }
    }
    assert!(
        wrong.is_empty(),
        "glXGetProcAddressARB disagrees with dlsym for {} names, e.g. {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(10)]
    );
    assert!(lookup("glNotAFunction").is_null());
}

#[test]
fn every_glvnd_libgl_name_is_exported() {
    let list = include_str!("../../src/gl_entry/glvnd_libgl_exports.txt");
    let names: Vec<&str> =
        list.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#')).collect();
    assert!(names.len() >= 3400, "glvnd list has only {} names", names.len());
    let lib = open_library();
    let missing: Vec<_> = names.iter().filter(|n| !is_exported(&lib, n)).collect();
    assert!(
        missing.is_empty(),
        "{} glvnd names not exported, e.g. {:?}",
        missing.len(),
        &missing[..missing.len().min(10)]
    );
}

/// The dynamic symbol table holds the GL surface and nothing else: glvnd's names, the
/// `glXGetProcAddress` table's names, glrt's headless API (`glrt*`) and the glvnd vendor entry.
#[test]
fn exports_nothing_but_the_gl_surface() {
    let out = Command::new("nm")
        .args(["-D", "--defined-only"])
        .arg(library_path())
        .output()
        .expect("run nm (binutils)");
    assert!(out.status.success(), "nm failed: {}", String::from_utf8_lossy(&out.stderr));
    let glvnd: std::collections::HashSet<&str> =
        include_str!("../../src/gl_entry/glvnd_libgl_exports.txt").lines().map(str::trim).collect();
    let text = String::from_utf8_lossy(&out.stdout);
    let names: Vec<&str> = text.lines().filter_map(|l| l.split_whitespace().nth(2)).collect();
    let stray: Vec<_> = names
        .iter()
        .filter(|n| {
            !glvnd.contains(*n)
                && exports::proc_address(n.as_bytes()).is_null()
                && !n.starts_with("glrt")
                && **n != "__glx_Main"
        })
        .collect();
    assert!(stray.is_empty(), "unexpected exports: {stray:?}");
    for name in ["glrtCreateContext", "glrtMakeCurrent", "glrtSwapBuffers", "glrtDestroyContext"] {
        assert!(names.contains(&name), "{name} not exported");
    }
}

#[test]
fn soname_is_libgl_so_1() {
    let out = Command::new("readelf")
        .arg("-d")
        .arg(library_path())
        .output()
        .expect("run readelf (binutils)");
    assert!(out.status.success(), "readelf failed: {}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    let soname = text
        .lines()
        .find(|l| l.contains("(SONAME)"))
        .and_then(|l| l.split('[').nth(1))
        .and_then(|l| l.split(']').next());
    assert_eq!(soname, Some("libGL.so.1"), "readelf -d:\n{text}");
}

#[test]
fn unimplemented_command_raises_invalid_operation() {
    const GL_NO_ERROR: u32 = 0;
    const GL_INVALID_OPERATION: u32 = 0x0502;
    let ctx = headless::glrtCreateContext(std::ptr::null_mut());
    assert!(!ctx.is_null());
    assert_eq!(headless::glrtMakeCurrent(ctx, 64, 64), 1);
    // Safety: a context is current; the commands take scalars only.
    unsafe {
        assert_eq!(exports::glGetError(), GL_NO_ERROR);
        // glUniform1ui belongs to GL 3.0, which glrt does not implement.
        exports::glUniform1ui(0, 1);
        assert_eq!(exports::glGetError(), GL_INVALID_OPERATION);
        assert_eq!(exports::glGetError(), GL_NO_ERROR, "glGetError clears the flag");
    }
    assert_eq!(headless::glrtMakeCurrent(std::ptr::null_mut(), 0, 0), 1);
    headless::glrtDestroyContext(ctx);
}
