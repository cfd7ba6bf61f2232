//! Writes `fuzz_calls.rs`: a caller for every served OpenGL command that draws each argument
//! from a [`FuzzArgs`] source by its C type, for the random-call robustness test
//! (`src/translate/robustness.rs`).

use std::fmt::Write as _;

use crate::model::{Command, Model, Route};

/// The argument expression for a parameter of Rust type `ty`, or `None` for a type the
/// fuzzer cannot produce.
fn argument(ty: &str) -> Option<String> {
    // gl_generator spells `void **params` (written by glGetPointerv) `*const *mut c_void`.
    if ty.starts_with("*mut") || ty.starts_with("*const *mut") {
        return Some(format!("args.out_ptr() as {ty}"));
    }
    if ty.starts_with("*const") {
        return Some(format!("args.in_ptr() as {ty}"));
    }
    let name = ty.trim_start_matches("types::");
    Some(match name {
        "GLenum" => "args.enumeration()".to_owned(),
        "GLbitfield" => "args.bits()".to_owned(),
        "GLboolean" => "args.int() as types::GLboolean".to_owned(),
        "GLfloat" | "GLclampf" => "args.float() as f32".to_owned(),
        "GLdouble" | "GLclampd" => "args.float()".to_owned(),
        "GLint" | "GLsizei" | "GLuint" | "GLshort" | "GLushort" | "GLbyte" | "GLubyte"
        | "GLintptr" | "GLsizeiptr" | "GLintptrARB" | "GLsizeiptrARB" | "GLchar" => {
            format!("args.int() as {ty}")
        }
        _ => return None,
    })
}

fn served(c: &Command) -> bool {
    c.in_surface && !matches!(c.route, Route::Missing | Route::Hand(_))
}

pub fn fuzz_calls(model: &Model) -> String {
    let mut s = String::from(crate::emit::HEADER);
    s.push_str(
        "#[allow(unused_imports)] use crate::translate::gl::{types, __gl_imports};\n\
         use crate::translate::{dispatch, Context};\n\n\
         /// Where the fuzzer's arguments come from.\n\
         pub trait FuzzArgs {\n\
             /// A small or extreme integer.\n    fn int(&mut self) -> i64;\n\
             /// A float, sometimes NaN, infinite or huge.\n    fn float(&mut self) -> f64;\n\
             /// A GL enum, sometimes invalid.\n    fn enumeration(&mut self) -> u32;\n\
             /// A bit mask, sometimes with undefined bits.\n    fn bits(&mut self) -> u32;\n\
             /// A pointer to readable client memory, or null.\n    fn in_ptr(&mut self) -> *const u8;\n\
             /// A pointer to writable client memory, or null.\n    fn out_ptr(&mut self) -> *mut u8;\n\
         }\n\n\
         /// What a fuzzed call was.\n\
         pub struct FuzzedCall {\n    /// The command's C name.\n    pub name: &'static str,\n\
             /// Whether a `GLsizei` argument was negative (the command must raise an error).\n    pub negative_size: bool,\n\
             /// Whether the command is compiled into display lists (not executed in `GL_COMPILE`).\n    pub compiled: bool,\n\
             /// Whether the command is allowed between `glBegin` and `glEnd`.\n    pub allowed_in_begin_end: bool,\n}\n\n",
    );
    let commands: Vec<(&Command, Vec<String>)> = model
        .commands
        .iter()
        .filter(|c| served(c))
        .filter_map(|c| {
            let args: Option<Vec<String>> = c.params.iter().map(|p| argument(&p.ty)).collect();
            args.map(|a| (c, a))
        })
        .collect();
    writeln!(s, "/// How many commands [`call`] can make.\npub const COMMAND_COUNT: usize = {};\n", commands.len()).unwrap();
    s.push_str(
        "/// Calls command number `index` on `ctx` through the generated dispatch.\n\
         ///\n/// # Safety\n/// `args` must hand out pointers to memory large enough for any command.\n\
         #[allow(unused_unsafe, clippy::unnecessary_cast)]\n\
         pub unsafe fn call(ctx: &mut Context, index: usize, args: &mut impl FuzzArgs) -> FuzzedCall {\n    match index {\n",
    );
    for (i, (c, args)) in commands.iter().enumerate() {
        writeln!(s, "        {i} => {{").unwrap();
        let mut negative = Vec::new();
        for (k, (p, a)) in c.params.iter().zip(args).enumerate() {
            writeln!(s, "            let a{k}: {} = {a};", p.ty).unwrap();
            if p.ty == "types::GLsizei" {
                negative.push(format!("a{k} < 0"));
            }
        }
        let call_args: Vec<String> = (0..c.params.len()).map(|k| format!("a{k}")).collect();
        writeln!(s, "            let _ = unsafe {{ dispatch::{}(ctx, {}) }};", c.name, call_args.join(", ")).unwrap();
        let neg = if negative.is_empty() { "false".to_owned() } else { negative.join(" || ") };
        writeln!(
            s,
            "            FuzzedCall {{ name: \"{}\", negative_size: {neg}, compiled: {}, allowed_in_begin_end: {} }}\n        }}",
            c.name,
            crate::emit::is_compiled(c),
            crate::emit::allowed_inside_begin_end(c),
        )
        .unwrap();
    }
    s.push_str("        _ => FuzzedCall { name: \"\", negative_size: false, compiled: false, allowed_in_begin_end: true },\n    }\n}\n");
    s
}
