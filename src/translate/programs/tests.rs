//! Tests of shader and program objects, uniforms and attribute bindings, with programs linked
//! by hand ([`fake_linked`]) where the GLSL compiler is not needed.

use std::ffi::CString;

use super::objects::linked_state;
use crate::frame::program::{SamplerKind, ShaderProgram};
use crate::translate::glsl::{ActiveAttribute, ActiveUniform, LinkedProgram, UniformStorage};
use crate::translate::{Context, dispatch, gl};

/// A uniform in the block.
fn block(name: &str, ty: u32, size: u32, offset: u32, array_stride: u32, matrix_stride: u32) -> ActiveUniform {
    ActiveUniform { name: name.into(), ty, size, storage: UniformStorage::Block { offset, array_stride, matrix_stride } }
}

/// A link result as the compiler would give for
/// `uniform float f; uniform vec3 v; uniform float a[4]; uniform mat3 m; struct S { int m; };
/// uniform S s; uniform bvec2 l[2].c...; uniform sampler2D tex; uniform sampler2D texs[2];
/// attribute vec4 pos; attribute vec3 extra;`.
pub(crate) fn fake_link() -> LinkedProgram {
    let uniforms = vec![
        block("f", gl::GL_FLOAT, 1, 0, 4, 0),
        block("v", gl::GL_FLOAT_VEC3, 1, 16, 16, 0),
        block("a", gl::GL_FLOAT, 4, 32, 4, 0),
        block("m", gl::GL_FLOAT_MAT3, 1, 48, 48, 16),
        block("s.m", gl::GL_INT, 1, 96, 4, 0),
        block("l[1].c", gl::GL_BOOL_VEC2, 1, 104, 8, 0),
        ActiveUniform { name: "tex".into(), ty: gl::GL_SAMPLER_2D, size: 1, storage: UniformStorage::Sampler { first_slot: 0 } },
        ActiveUniform { name: "texs".into(), ty: gl::GL_SAMPLER_3D, size: 2, storage: UniformStorage::Sampler { first_slot: 1 } },
    ];
    let executable = ShaderProgram {
        id: 0,
        vertex: Some(vec![0x0723_0203u32].into()),
        fragment: None,
        samplers: vec![SamplerKind::D2, SamplerKind::D3, SamplerKind::D3],
        attributes: vec![0, 0, 3],
    };
    LinkedProgram {
        ok: true,
        log: String::new(),
        executable: Some(executable),
        uniforms,
        uniform_block_size: 112,
        attributes: vec![ActiveAttribute { name: "extra".into(), ty: gl::GL_FLOAT_VEC3, index: 2 }],
    }
}

/// A program object that a successful link of [`fake_link`] made; in use when `use_it`.
pub(crate) fn fake_program(ctx: &mut Context, use_it: bool) -> gl::GLuint {
    let p = unsafe { dispatch::glCreateProgram(ctx) };
    let (linked, log) = linked_state(fake_link()).unwrap();
    {
        let mut shared = ctx.shared.lock();
        let program = shared.programs.program_mut(p).unwrap();
        program.link_ok = true;
        program.log = log;
        program.linked = Some(linked);
    }
    if use_it {
        unsafe { dispatch::glUseProgram(ctx, p) };
    }
    p
}

fn location(ctx: &mut Context, p: gl::GLuint, name: &str) -> gl::GLint {
    let name = CString::new(name).unwrap();
    unsafe { dispatch::glGetUniformLocation(ctx, p, name.as_ptr()) }
}

fn shader_iv(ctx: &mut Context, s: gl::GLuint, pname: gl::GLenum) -> gl::GLint {
    let mut v = -7;
    unsafe { dispatch::glGetShaderiv(ctx, s, pname, &mut v) };
    v
}

fn program_iv(ctx: &mut Context, p: gl::GLuint, pname: gl::GLenum) -> gl::GLint {
    let mut v = -7;
    unsafe { dispatch::glGetProgramiv(ctx, p, pname, &mut v) };
    v
}

#[test]
fn shader_sources_and_one_namespace() {
    let (mut ctx, _) = Context::with_recording();
    let s = unsafe { dispatch::glCreateShader(&mut ctx, gl::GL_FRAGMENT_SHADER) };
    let p = unsafe { dispatch::glCreateProgram(&mut ctx) };
    assert_ne!(s, p, "shaders and programs share one namespace");
    assert_eq!(unsafe { dispatch::glCreateShader(&mut ctx, gl::GL_TEXTURE_2D) }, 0);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    let parts = [c"void main() {".as_ptr(), c" gl_FragColor = vec4(1.0); }XXX".as_ptr(), c"\n".as_ptr()];
    let lengths = [-1, 28, -1];
    unsafe { dispatch::glShaderSource(&mut ctx, s, 3, parts.as_ptr(), lengths.as_ptr()) };
    let expected = "void main() { gl_FragColor = vec4(1.0); }\n";
    assert_eq!(shader_iv(&mut ctx, s, gl::GL_SHADER_SOURCE_LENGTH), expected.len() as i32 + 1);
    let mut buf = [0x55u8; 64];
    let mut len = 0;
    unsafe { dispatch::glGetShaderSource(&mut ctx, s, 10, &mut len, buf.as_mut_ptr().cast()) };
    assert_eq!((len, &buf[..10]), (9, &b"void main\0"[..]));
    unsafe { dispatch::glGetShaderSource(&mut ctx, s, 64, &mut len, buf.as_mut_ptr().cast()) };
    assert_eq!(&buf[..len as usize], expected.as_bytes());
    unsafe { dispatch::glShaderSource(&mut ctx, s, 1, parts.as_ptr(), std::ptr::null()) };
    assert_eq!(shader_iv(&mut ctx, s, gl::GL_SHADER_SOURCE_LENGTH), 14, "NUL-terminated strings without lengths");
    assert_eq!(shader_iv(&mut ctx, s, gl::GL_SHADER_TYPE), gl::GL_FRAGMENT_SHADER as i32);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    unsafe { dispatch::glShaderSource(&mut ctx, s, -1, parts.as_ptr(), std::ptr::null()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    assert_eq!(shader_iv(&mut ctx, p, gl::GL_SHADER_TYPE), -7);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "a program where a shader is expected");
    assert_eq!(program_iv(&mut ctx, s, gl::GL_LINK_STATUS), -7);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "a shader where a program is expected");
    assert_eq!(program_iv(&mut ctx, 999, gl::GL_LINK_STATUS), -7);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE, "no object of that name");
    assert_eq!(shader_iv(&mut ctx, s, gl::GL_LINK_STATUS), -7);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    unsafe { dispatch::glCompileShader(&mut ctx, s) };
    let compiled = shader_iv(&mut ctx, s, gl::GL_COMPILE_STATUS);
    let log_len = shader_iv(&mut ctx, s, gl::GL_INFO_LOG_LENGTH);
    let mut log = vec![0u8; 256];
    unsafe { dispatch::glGetShaderInfoLog(&mut ctx, s, 256, &mut len, log.as_mut_ptr().cast()) };
    assert_eq!(log_len, if len == 0 { 0 } else { len + 1 }, "INFO_LOG_LENGTH counts the NUL");
    assert!(compiled == 1 || len > 0, "a failed compile says why");
}

#[test]
fn attaching_detaching_and_deleting() {
    let (mut ctx, _) = Context::with_recording();
    let p = unsafe { dispatch::glCreateProgram(&mut ctx) };
    let vs = unsafe { dispatch::glCreateShader(&mut ctx, gl::GL_VERTEX_SHADER) };
    let fs = unsafe { dispatch::glCreateShader(&mut ctx, gl::GL_FRAGMENT_SHADER) };
    unsafe {
        dispatch::glAttachShader(&mut ctx, p, vs);
        dispatch::glAttachShader(&mut ctx, p, fs);
    }
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    unsafe { dispatch::glAttachShader(&mut ctx, p, vs) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "the same shader twice");
    unsafe { dispatch::glAttachShader(&mut ctx, vs, fs) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "a shader is no program");
    assert_eq!(program_iv(&mut ctx, p, gl::GL_ATTACHED_SHADERS), 2);
    let (mut names, mut n) = ([0u32; 4], 0);
    unsafe { dispatch::glGetAttachedShaders(&mut ctx, p, 1, &mut n, names.as_mut_ptr()) };
    assert_eq!((n, names[0], names[1]), (1, vs, 0));
    unsafe { dispatch::glDeleteShader(&mut ctx, vs) };
    assert_eq!(unsafe { dispatch::glIsShader(&mut ctx, vs) }, 1, "an attached shader is only flagged");
    assert_eq!(shader_iv(&mut ctx, vs, gl::GL_DELETE_STATUS), 1);
    unsafe { dispatch::glLinkProgram(&mut ctx, p) };
    assert_eq!(program_iv(&mut ctx, p, gl::GL_LINK_STATUS), 0, "uncompiled shaders do not link");
    assert!(program_iv(&mut ctx, p, gl::GL_INFO_LOG_LENGTH) > 1);
    unsafe { dispatch::glUseProgram(&mut ctx, p) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "an unlinked program cannot be used");
    unsafe { dispatch::glDetachShader(&mut ctx, p, vs) };
    assert_eq!(unsafe { dispatch::glIsShader(&mut ctx, vs) }, 0, "gone with its last attachment");
    unsafe { dispatch::glDetachShader(&mut ctx, p, vs) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    unsafe { dispatch::glDetachShader(&mut ctx, p, fs + 100) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    let other = unsafe { dispatch::glCreateShader(&mut ctx, gl::GL_VERTEX_SHADER) };
    unsafe { dispatch::glDetachShader(&mut ctx, p, other) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "not attached");
    unsafe { dispatch::glDeleteProgram(&mut ctx, p) };
    assert_eq!(unsafe { dispatch::glIsProgram(&mut ctx, p) }, 0);
    assert_eq!(unsafe { dispatch::glIsShader(&mut ctx, fs) }, 1, "deleting a program detaches, not deletes");
    unsafe { dispatch::glDeleteShader(&mut ctx, fs) };
    assert_eq!(unsafe { dispatch::glIsShader(&mut ctx, fs) }, 0);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
}

#[test]
fn a_program_in_use_outlives_deletion_and_failed_relinks() {
    let (mut ctx, _) = Context::with_recording();
    let p = fake_program(&mut ctx, true);
    let mut current = 0;
    unsafe { dispatch::glGetIntegerv(&mut ctx, gl::GL_CURRENT_PROGRAM, &mut current) };
    assert_eq!(current as u32, p);
    let id = ctx.shared.lock().programs.program(p).unwrap().linked.as_ref().unwrap().executable.id;
    assert_ne!(id, 0, "each executable is numbered");
    let q = fake_program(&mut ctx, false);
    let id_q = ctx.shared.lock().programs.program(q).unwrap().linked.as_ref().unwrap().executable.id;
    assert_ne!(id, id_q);
    let vs = unsafe { dispatch::glCreateShader(&mut ctx, gl::GL_VERTEX_SHADER) };
    unsafe {
        dispatch::glAttachShader(&mut ctx, p, vs);
        dispatch::glLinkProgram(&mut ctx, p);
    }
    assert_eq!(program_iv(&mut ctx, p, gl::GL_LINK_STATUS), 0);
    assert_eq!(program_iv(&mut ctx, p, gl::GL_ACTIVE_UNIFORMS), 0, "a failed link has no active uniforms");
    assert!(ctx.shared.lock().programs.program(p).unwrap().linked.is_some(), "the executable in use stays");
    unsafe { dispatch::glDeleteProgram(&mut ctx, p) };
    assert_eq!(unsafe { dispatch::glIsProgram(&mut ctx, p) }, 1, "a program in use is only flagged");
    assert_eq!(program_iv(&mut ctx, p, gl::GL_DELETE_STATUS), 1);
    unsafe { dispatch::glUseProgram(&mut ctx, q) };
    assert_eq!(unsafe { dispatch::glIsProgram(&mut ctx, p) }, 0, "gone once out of use");
    assert_eq!(unsafe { dispatch::glIsShader(&mut ctx, vs) }, 1);
    unsafe { dispatch::glUseProgram(&mut ctx, vs) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    unsafe { dispatch::glUseProgram(&mut ctx, 0) };
    unsafe { dispatch::glGetIntegerv(&mut ctx, gl::GL_CURRENT_PROGRAM, &mut current) };
    assert_eq!((current, ctx.glGetError()), (0, gl::GL_NO_ERROR));
}

#[test]
fn program_queries_and_validation() {
    let (mut ctx, _) = Context::with_recording();
    let p = fake_program(&mut ctx, false);
    assert_eq!(program_iv(&mut ctx, p, gl::GL_ACTIVE_UNIFORMS), 8);
    assert_eq!(program_iv(&mut ctx, p, gl::GL_ACTIVE_UNIFORM_MAX_LENGTH), "texs[0]".len() as i32 + 1);
    assert_eq!(program_iv(&mut ctx, p, gl::GL_ACTIVE_ATTRIBUTES), 1);
    assert_eq!(program_iv(&mut ctx, p, gl::GL_ACTIVE_ATTRIBUTE_MAX_LENGTH), 6);
    assert_eq!(program_iv(&mut ctx, p, gl::GL_VALIDATE_STATUS), 0);
    let (mut buf, mut len, mut size, mut ty) = ([0u8; 32], 0, 0, 0);
    unsafe { dispatch::glGetActiveUniform(&mut ctx, p, 2, 32, &mut len, &mut size, &mut ty, buf.as_mut_ptr().cast()) };
    assert_eq!((&buf[..len as usize], size, ty), (&b"a[0]"[..], 4, gl::GL_FLOAT));
    unsafe { dispatch::glGetActiveUniform(&mut ctx, p, 8, 32, &mut len, &mut size, &mut ty, buf.as_mut_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    unsafe { dispatch::glGetActiveAttrib(&mut ctx, p, 0, 3, &mut len, &mut size, &mut ty, buf.as_mut_ptr().cast()) };
    assert_eq!((&buf[..3], len, size, ty), (&b"ex\0"[..], 2, 1, gl::GL_FLOAT_VEC3));
    assert_eq!(unsafe { dispatch::glGetAttribLocation(&mut ctx, p, c"extra".as_ptr()) }, 2);
    assert_eq!(unsafe { dispatch::glGetAttribLocation(&mut ctx, p, c"gl_Vertex".as_ptr()) }, -1);
    // `tex` (2D) and `texs` (3D) on the same unit cannot run; all start on unit 0.
    unsafe { dispatch::glValidateProgram(&mut ctx, p) };
    assert_eq!(program_iv(&mut ctx, p, gl::GL_VALIDATE_STATUS), 0);
    unsafe { dispatch::glUseProgram(&mut ctx, p) };
    let texs = location(&mut ctx, p, "texs[1]");
    unsafe {
        dispatch::glUniform1iv(&mut ctx, texs - 1, 2, [1, 2].as_ptr());
        dispatch::glValidateProgram(&mut ctx, p);
    }
    assert_eq!(program_iv(&mut ctx, p, gl::GL_VALIDATE_STATUS), 1);
    unsafe {
        dispatch::glUniform1i(&mut ctx, texs, 0);
        dispatch::glValidateProgram(&mut ctx, p);
    }
    assert_eq!(program_iv(&mut ctx, p, gl::GL_VALIDATE_STATUS), 0);
    assert!(program_iv(&mut ctx, p, gl::GL_INFO_LOG_LENGTH) > 1);
    unsafe { dispatch::glBindAttribLocation(&mut ctx, p, 16, c"extra".as_ptr()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    unsafe { dispatch::glBindAttribLocation(&mut ctx, p, 0, c"gl_Color".as_ptr()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    unsafe { dispatch::glBindAttribLocation(&mut ctx, p, 0, c"extra".as_ptr()) };
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR, "index 0 can be bound");
    assert_eq!(ctx.shared.lock().programs.program(p).unwrap().bindings.get("extra"), Some(&0));
}

#[test]
fn uniform_locations() {
    let (mut ctx, _) = Context::with_recording();
    let p = fake_program(&mut ctx, false);
    let names = ["f", "v", "a", "a[0]", "a[3]", "m", "s.m", "l[1].c", "tex", "texs", "texs[1]"];
    let locs: Vec<i32> = names.iter().map(|n| location(&mut ctx, p, n)).collect();
    assert_eq!(locs, vec![0, 1, 2, 2, 5, 6, 7, 8, 9, 10, 11], "every array element has its location");
    for missing in ["a[4]", "b", "s", "l[1]", "a[", "a[x]", "gl_ModelViewMatrix"] {
        assert_eq!(location(&mut ctx, p, missing), -1, "{missing}");
    }
    let unlinked = unsafe { dispatch::glCreateProgram(&mut ctx) };
    assert_eq!(location(&mut ctx, unlinked, "f"), -1);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
}

/// The program's uniform bytes.
fn values(ctx: &Context, p: gl::GLuint) -> Vec<u8> {
    ctx.shared.lock().programs.program(p).unwrap().linked.as_ref().unwrap().values.clone()
}

fn f32_at(bytes: &[u8], at: usize) -> f32 {
    f32::from_ne_bytes(bytes[at..at + 4].try_into().unwrap())
}

fn i32_at(bytes: &[u8], at: usize) -> i32 {
    i32::from_ne_bytes(bytes[at..at + 4].try_into().unwrap())
}

#[test]
fn uniform_values_land_in_the_block() {
    let (mut ctx, _) = Context::with_recording();
    let p = fake_program(&mut ctx, true);
    let [f, v, a, a2, m, sm, lc] = ["f", "v", "a", "a[2]", "m", "s.m", "l[1].c"].map(|n| location(&mut ctx, p, n));
    let mat: [f32; 18] = std::array::from_fn(|i| i as f32);
    unsafe {
        dispatch::glUniform1f(&mut ctx, f, 2.5);
        dispatch::glUniform3f(&mut ctx, v, 1.0, 2.0, 3.0);
        dispatch::glUniform1fv(&mut ctx, a2, 5, [7.0, 8.0, 9.0].as_ptr());
        dispatch::glUniformMatrix3fv(&mut ctx, m, 1, gl::GL_TRUE, mat.as_ptr());
        dispatch::glUniform1i(&mut ctx, sm, -4);
        dispatch::glUniform2f(&mut ctx, lc, 0.0, 0.5);
    }
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    let b = values(&ctx, p);
    assert_eq!(f32_at(&b, 0), 2.5);
    assert_eq!([f32_at(&b, 16), f32_at(&b, 20), f32_at(&b, 24)], [1.0, 2.0, 3.0]);
    assert_eq!([40, 44].map(|o| f32_at(&b, o)), [7.0, 8.0], "values past the array's end are ignored");
    // Transposed: column c of the stored matrix is row c of the given one.
    assert_eq!([48, 52, 56, 64, 68, 72].map(|o| f32_at(&b, o)), [0.0, 3.0, 6.0, 1.0, 4.0, 7.0]);
    assert_eq!(i32_at(&b, 96), -4);
    assert_eq!([i32_at(&b, 104), i32_at(&b, 108)], [0, 1], "booleans are 0 or 1");
    let mut out = [0.0f32; 9];
    unsafe { dispatch::glGetUniformfv(&mut ctx, p, m, out.as_mut_ptr()) };
    assert_eq!(out, [0.0, 3.0, 6.0, 1.0, 4.0, 7.0, 2.0, 5.0, 8.0]);
    let mut ints = [0i32; 2];
    unsafe { dispatch::glGetUniformiv(&mut ctx, p, lc, ints.as_mut_ptr()) };
    assert_eq!(ints, [0, 1]);
    unsafe { dispatch::glGetUniformfv(&mut ctx, p, a + 1, out.as_mut_ptr()) };
    assert_eq!(out[0], 0.0);
    unsafe { dispatch::glGetUniformfv(&mut ctx, p, a + 2, out.as_mut_ptr()) };
    assert_eq!(out[0], 7.0);
}

#[test]
fn uniform_errors() {
    let (mut ctx, _) = Context::with_recording();
    let p = fake_program(&mut ctx, false);
    let [f, v, a, m, tex, texs] = ["f", "v", "a", "m", "tex", "texs"].map(|n| location(&mut ctx, p, n));
    unsafe { dispatch::glUniform1f(&mut ctx, f, 1.0) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "no current program");
    unsafe { dispatch::glUseProgram(&mut ctx, p) };
    type Case = (&'static str, Box<dyn Fn(&mut Context)>, u32);
    let cases: [Case; 10] = [
        ("location -1 is ignored", Box::new(|c| unsafe { dispatch::glUniform1f(c, -1, 1.0) }), gl::GL_NO_ERROR),
        ("unknown location", Box::new(|c| unsafe { dispatch::glUniform1f(c, 99, 1.0) }), gl::GL_INVALID_OPERATION),
        ("integer into float", Box::new(move |c| unsafe { dispatch::glUniform1i(c, f, 1) }), gl::GL_INVALID_OPERATION),
        ("wrong size", Box::new(move |c| unsafe { dispatch::glUniform2f(c, v, 1.0, 1.0) }), gl::GL_INVALID_OPERATION),
        ("count > 1 for a non-array", Box::new(move |c| unsafe { dispatch::glUniform1fv(c, f, 2, [0.0; 2].as_ptr()) }), gl::GL_INVALID_OPERATION),
        ("negative count", Box::new(move |c| unsafe { dispatch::glUniform1fv(c, a, -1, [0.0; 2].as_ptr()) }), gl::GL_INVALID_VALUE),
        ("vector into matrix", Box::new(move |c| unsafe { dispatch::glUniform4fv(c, m, 1, [0.0; 4].as_ptr()) }), gl::GL_INVALID_OPERATION),
        ("sampler by float", Box::new(move |c| unsafe { dispatch::glUniform1f(c, tex, 1.0) }), gl::GL_INVALID_OPERATION),
        ("sampler unit out of range", Box::new(move |c| unsafe { dispatch::glUniform1iv(c, texs, 2, [1, 4].as_ptr()) }), gl::GL_INVALID_VALUE),
        ("sampler units", Box::new(move |c| unsafe { dispatch::glUniform1iv(c, texs, 2, [1, 3].as_ptr()) }), gl::GL_NO_ERROR),
    ];
    for (what, call, error) in cases {
        call(&mut ctx);
        assert_eq!(ctx.glGetError(), error, "{what}");
    }
    let units = ctx.shared.lock().programs.program(p).unwrap().linked.as_ref().unwrap().sampler_units.clone();
    assert_eq!(units, vec![0, 1, 3]);
    let mut unit = -1;
    unsafe { dispatch::glGetUniformiv(&mut ctx, p, texs + 1, &mut unit) };
    assert_eq!(unit, 3);
    unsafe { dispatch::glGetUniformiv(&mut ctx, p, -1, &mut unit) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
}

#[test]
fn uniforms_in_display_lists_take_their_values_at_compile_time() {
    let (mut ctx, _) = Context::with_recording();
    let p = fake_program(&mut ctx, true);
    let v = location(&mut ctx, p, "v");
    let given = std::cell::Cell::new([1.0f32, 2.0, 3.0]);
    unsafe {
        dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
        dispatch::glUniform3fv(&mut ctx, v, 1, given.as_ptr().cast());
        dispatch::glEndList(&mut ctx);
    }
    given.set([9.0; 3]);
    assert_eq!(f32_at(&values(&ctx, p), 16), 0.0, "GL_COMPILE does not execute");
    unsafe { dispatch::glCallList(&mut ctx, 1) };
    assert_eq!(f32_at(&values(&ctx, p), 16), 1.0);
}

#[test]
fn draws_carry_the_program_and_split_on_uniform_changes() {
    let (mut ctx, _) = Context::with_recording();
    let p = fake_program(&mut ctx, true);
    let f = location(&mut ctx, p, "f");
    let tri = |ctx: &mut Context| unsafe {
        dispatch::glBegin(ctx, gl::GL_TRIANGLES);
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)] {
            dispatch::glVertex2f(ctx, x, y);
        }
        dispatch::glEnd(ctx);
    };
    unsafe { dispatch::glEnable(&mut ctx, gl::GL_VERTEX_PROGRAM_POINT_SIZE) };
    assert_eq!(unsafe { dispatch::glIsEnabled(&mut ctx, gl::GL_VERTEX_PROGRAM_POINT_SIZE) }, 1);
    tri(&mut ctx);
    tri(&mut ctx);
    assert_eq!(ctx.frame.draws.len(), 1, "equal programs and values merge");
    unsafe { dispatch::glUniform1f(&mut ctx, f, 3.0) };
    tri(&mut ctx);
    unsafe { dispatch::glUseProgram(&mut ctx, 0) };
    tri(&mut ctx);
    let draws = &ctx.frame.draws;
    assert_eq!(draws.len(), 3, "new uniform values and the fixed-function pipeline split draws");
    let first = draws[0].program.as_ref().expect("a program draw");
    assert!(first.point_size_from_shader && !first.two_side);
    assert_eq!(first.uniforms.len(), 112);
    assert_eq!(f32::from_ne_bytes(draws[1].program.as_ref().unwrap().uniforms[..4].try_into().unwrap()), 3.0);
    assert_eq!(first.textures.len(), 3, "one texture per sampler slot");
    assert!(first.textures.iter().all(Option::is_none), "no complete texture bound");
    assert!(draws[2].program.is_none());
}

#[test]
fn real_compile_and_link() {
    let (mut ctx, _) = Context::with_recording();
    let shader = |ctx: &mut Context, ty, src: &std::ffi::CStr| unsafe {
        let s = dispatch::glCreateShader(ctx, ty);
        dispatch::glShaderSource(ctx, s, 1, [src.as_ptr()].as_ptr(), std::ptr::null());
        dispatch::glCompileShader(ctx, s);
        s
    };
    let vs = shader(&mut ctx, gl::GL_VERTEX_SHADER, c"attribute vec3 extra; varying vec3 c; void main() { c = extra; gl_Position = ftransform(); }");
    let fs = shader(&mut ctx, gl::GL_FRAGMENT_SHADER, c"uniform vec4 tint[2]; varying vec3 c; void main() { gl_FragColor = vec4(c, 1.0) * tint[1]; }");
    assert_eq!((shader_iv(&mut ctx, vs, gl::GL_COMPILE_STATUS), shader_iv(&mut ctx, fs, gl::GL_COMPILE_STATUS)), (1, 1));
    let p = unsafe { dispatch::glCreateProgram(&mut ctx) };
    unsafe {
        dispatch::glAttachShader(&mut ctx, p, vs);
        dispatch::glAttachShader(&mut ctx, p, fs);
        dispatch::glBindAttribLocation(&mut ctx, p, 5, c"extra".as_ptr());
        dispatch::glLinkProgram(&mut ctx, p);
    }
    assert_eq!(program_iv(&mut ctx, p, gl::GL_LINK_STATUS), 1);
    assert_eq!(unsafe { dispatch::glGetAttribLocation(&mut ctx, p, c"extra".as_ptr()) }, 5, "the binding applies at link");
    let tint1 = location(&mut ctx, p, "tint[1]");
    assert_eq!(tint1, location(&mut ctx, p, "tint") + 1);
    unsafe {
        dispatch::glUseProgram(&mut ctx, p);
        dispatch::glUniform4f(&mut ctx, tint1, 1.0, 0.5, 0.25, 1.0);
        dispatch::glBegin(&mut ctx, gl::GL_TRIANGLES);
        dispatch::glVertexAttrib3f(&mut ctx, 5, 0.1, 0.2, 0.3);
        for _ in 0..3 {
            dispatch::glVertex2f(&mut ctx, 0.0, 0.0);
        }
        dispatch::glEnd(&mut ctx);
    }
    let mut out = [0.0f32; 4];
    unsafe { dispatch::glGetUniformfv(&mut ctx, p, tint1, out.as_mut_ptr()) };
    assert_eq!(out, [1.0, 0.5, 0.25, 1.0]);
    let draw = &ctx.frame.draws[0];
    assert!(draw.program.as_ref().is_some_and(|d| d.program.vertex.is_some() && d.program.fragment.is_some()));
    assert_eq!(draw.vertices.generic[5].get(0), Some([0.1, 0.2, 0.3, 1.0]));
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
}

#[test]
fn a_deleted_program_goes_with_the_last_context_using_it() {
    let (mut a, _) = Context::with_recording();
    let (mut b, _) = Context::with_recording();
    b.shared = a.shared.clone();
    let p = fake_program(&mut a, true);
    unsafe {
        dispatch::glUseProgram(&mut b, p);
        dispatch::glDeleteProgram(&mut a, p);
        dispatch::glUseProgram(&mut a, 0);
    }
    assert_eq!(unsafe { dispatch::glIsProgram(&mut a, p) }, 1, "still in use by the other context");
    drop(b);
    assert_eq!(unsafe { dispatch::glIsProgram(&mut a, p) }, 0);
}

#[test]
fn sampler_slots_take_the_texture_bound_to_their_unit_enabled_or_not() {
    let (mut ctx, _) = Context::with_recording();
    let p = fake_program(&mut ctx, true);
    let [tex, texs] = ["tex", "texs"].map(|n| location(&mut ctx, p, n));
    let texel = [255u8, 0, 0, 255];
    unsafe {
        dispatch::glActiveTexture(&mut ctx, gl::GL_TEXTURE2);
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, 5);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 1, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texel.as_ptr().cast());
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_3D, 6);
        dispatch::glUniform1i(&mut ctx, tex, 2);
        dispatch::glUniform1iv(&mut ctx, texs, 2, [2, 3].as_ptr());
        dispatch::glBegin(&mut ctx, gl::GL_POINTS);
        dispatch::glVertex2f(&mut ctx, 0.0, 0.0);
        dispatch::glEnd(&mut ctx);
    }
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    let draw = ctx.frame.draws[0].program.clone().unwrap();
    let ids: Vec<Option<u32>> = draw.textures.iter().map(|t| t.as_ref().map(|t| t.id)).collect();
    assert_eq!(ids, vec![Some(5), None, None], "the 2D texture of unit 2, not enabled; no complete 3D texture");
}
