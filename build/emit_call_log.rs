//! The call-log side of the generated exports (`GLRT_TRACE`, `gl_entry::call_log`): how each
//! parameter of a command is printed, chosen from its C type, its gl.xml enum group and, for
//! client pointers, the fixed length gl.xml gives (`len="3"`); and the tables of the enum groups
//! the printing uses (`call_log_groups.rs`, included as `gl_entry::call_log::groups`).

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

use crate::emit::HEADER;
use crate::model::{Command, Model, Param};

/// Scalar C types the call log prints by value (every other non-pointer type prints as `?`).
const SCALARS: &[&str] = &[
    "GLenum", "GLboolean", "GLbitfield", "GLbyte", "GLubyte", "GLshort", "GLushort", "GLint", "GLuint",
    "GLsizei", "GLfloat", "GLclampf", "GLdouble", "GLclampd", "GLchar", "GLcharARB", "GLhalf",
    "GLhalfARB", "GLhalfNV", "GLfixed", "GLclampx", "GLintptr", "GLsizeiptr", "GLintptrARB",
    "GLsizeiptrARB", "GLint64", "GLuint64", "GLint64EXT", "GLuint64EXT", "GLhandleARB",
];

/// Whether `ty` (`types::GLfloat`) is a scalar the call log prints by value.
fn is_scalar(ty: &str) -> bool {
    ty.strip_prefix("types::").is_some_and(|t| SCALARS.contains(&t))
}

/// `(command, parameter) -> N` for every `const` pointer parameter gl.xml gives a numeric
/// length (`<param len="16">const <ptype>GLfloat</ptype> *<name>m</name></param>`): the
/// values the call log can print without knowing what the command does with them.
pub fn fixed_lengths() -> BTreeMap<(String, String), usize> {
    let xml = std::str::from_utf8(khronos_api::GL_XML).expect("gl.xml is UTF-8");
    let mut lens = BTreeMap::new();
    for command in xml.split("<command").skip(1) {
        let Some(name) = between(command, "<name>", "</name>") else { continue };
        for param in command.split("<param").skip(1) {
            let Some(param) = param.split("</param>").next() else { continue };
            let tag = param.split('>').next().unwrap_or("");
            let len = between(tag, "len=\"", "\"").and_then(|l| l.parse::<usize>().ok());
            let body = param.split_once('>').map_or("", |(_, b)| b);
            if let (Some(len), Some(pname)) = (len, between(body, "<name>", "</name>"))
                && body.trim_start().starts_with("const")
                && body.contains('*')
            {
                lens.insert((name.to_owned(), pname.to_owned()), len);
            }
        }
    }
    lens
}

fn between<'a>(s: &'a str, start: &str, end: &str) -> Option<&'a str> {
    let rest = &s[s.find(start)? + start.len()..];
    Some(&rest[..rest.find(end)?])
}

/// The Rust path of a group's table in `call_log_groups.rs`.
fn group_path(group: &str) -> String {
    format!("crate::gl_entry::call_log::groups::{group}")
}

/// Whether `model` has a table for `p`'s group (gl.xml names some groups it never defines).
fn group_of<'a>(model: &Model, p: &'a Param) -> Option<&'a str> {
    p.group.as_deref().filter(|g| model.groups.contains_key(*g))
}

/// The vector state commands (`glLightfv`, `glTexParameteriv`...), whose `params` count
/// depends on `pname` (`gl_entry::call_log::sizes::values_of`).
const PNAME_VECTORS: &[&str] =
    &["glLight", "glLightModel", "glMaterial", "glFog", "glTexEnv", "glTexParameter", "glTexGen", "glPointParameter"];

/// The printing of a `const` pointer parameter whose size depends on other arguments or on
/// GL state (`gl_entry::call_log::sizes`), `None` for other parameters.
fn variable_size(c: &Command, p: &Param, prefix: &str) -> Option<String> {
    let (label, name) = (p.name.trim_matches('_'), format!("{prefix}{}", p.name));
    let has = |n: &str| c.params.iter().any(|q| q.name == n);
    let arg = |n: &str| if has(n) { format!("{prefix}{n}") } else { "1".to_owned() };
    let sizes = "crate::gl_entry::call_log::sizes";
    let base = c.name.trim_end_matches("ARB").trim_end_matches("EXT").strip_suffix('v').and_then(|n| n.strip_suffix(['f', 'i', 'd']));
    if p.name == "params" && has("pname") && base.is_some_and(|b| PNAME_VECTORS.contains(&b)) {
        return Some(format!("__t.values_if(\"{label}\", {name}, {sizes}::values_of({prefix}pname))"));
    }
    let typed = match (c.name.as_str(), p.name.as_str()) {
        ("glShaderSource", "string") => {
            return Some(format!("__t.strings(\"{label}\", {name}, {prefix}count, {prefix}length)"));
        }
        ("glCallLists", "lists") => format!("{sizes}::call_lists({prefix}n, {prefix}type_)"),
        ("glDrawElements" | "glDrawRangeElements" | "glDrawRangeElementsEXT", "indices") => {
            format!("{sizes}::indices({prefix}count, {prefix}type_)")
        }
        (_, "pixels") if c.name.starts_with("glTexImage") || c.name.starts_with("glTexSubImage") || c.name == "glDrawPixels" => {
            let (w, h, d) = (arg("width"), arg("height"), arg("depth"));
            let size = format!("{sizes}::image({prefix}format, {prefix}type_, {w}, {h}, {d})");
            return Some(format!("__t.bytes(\"{label}\", {name}, {size})"));
        }
        _ => return None,
    };
    Some(format!("__t.typed(\"{label}\", {name}, {typed})"))
}

/// The statement that prints parameter `p` of command `c` into the call-log entry `t`.
fn print_param(model: &Model, lens: &BTreeMap<(String, String), usize>, c: &Command, p: &Param, prefix: &str) -> String {
    let (label, ty) = (p.name.trim_matches('_'), p.ty.as_str());
    let name = format!("{prefix}{}", p.name);
    let group = group_of(model, p).map_or("&[]".to_owned(), group_path);
    let has_pname = c.params.iter().any(|q| q.name == "pname" && q.ty == "types::GLenum");
    if has_pname && p.name == "param" && ["types::GLint", "types::GLfloat", "types::GLdouble"].contains(&ty) {
        format!("__t.param_of(\"{label}\", {prefix}pname, {name});")
    } else if ty == "types::GLenum" {
        format!("__t.enumerant(\"{label}\", {name}, {group});")
    } else if ty == "types::GLbitfield" && group_of(model, p).is_some() {
        format!("__t.bits(\"{label}\", {name}, {group});")
    } else if ty == "types::GLint" && group_of(model, p).is_some() {
        format!("__t.int_or_enum(\"{label}\", {name}, {group});")
    } else if ty.strip_prefix("*const ").is_some_and(is_scalar)
        && let Some(n) = lens.get(&(c.name.clone(), p.name.clone()))
    {
        format!("unsafe {{ __t.values(\"{label}\", {name}, {n}) }};")
    } else if let Some(size) = ty.starts_with("*const ").then(|| variable_size(c, p, prefix)).flatten() {
        format!("unsafe {{ {size} }};")
    } else if is_scalar(ty) || ty.contains('*') {
        format!("__t.arg(\"{label}\", {name});")
    } else {
        format!("let _ = &{name}; __t.opaque(\"{label}\");")
    }
}

/// The expression that forwards a call to `c` to the library of pass-through mode (its
/// function of the same name, zero when it has none). Commands exported without a known
/// prototype (newer than the registry) are not forwarded.
fn forward(model: &Model, c: &Command, prefix: &str) -> String {
    let known = !(c.params.is_empty() && c.ret == "usize");
    let fallback = format!("crate::gl_entry::passthrough::not_forwarded(\"{}\", {known})", c.name);
    if !known {
        return fallback;
    }
    let index = model.commands.iter().position(|x| x.name == c.name).expect("a command of the model");
    let tys: Vec<&str> = c.params.iter().map(|p| p.ty.as_str()).collect();
    let args: Vec<String> = c.params.iter().map(|p| format!("{prefix}{}", p.name)).collect();
    let ret = if c.ret == "()" { String::new() } else { format!(" -> {}", c.ret) };
    format!(
        "match crate::gl_entry::passthrough::real({index}) {{\n\
         \x20                   Some(__f) => unsafe {{ std::mem::transmute::<*const (), unsafe extern \"C\" fn({}){ret}>(__f)({}) }},\n\
         \x20                   None => {fallback},\n\
         \x20               }}",
        tys.join(", "),
        args.join(", "),
    )
}

/// The branch of an export (parameters named `{prefix}{name}`, glrt's own work the expression
/// `call`) taken when the call log or pass-through mode is on ([`gl_entry::mode`]): the call
/// goes to glrt or to the other library, and is logged with its arguments, result and error.
/// The branch is a function of its own, never inlined, with its own copy of `call`: the
/// export's plain path then has its one call of glrt's work, inlined as without the branch,
/// and one relaxed load more.
pub fn special_branch(model: &Model, lens: &BTreeMap<(String, String), usize>, c: &Command, prefix: &str, call: &str) -> String {
    let ret = if c.ret == "()" { String::new() } else { format!(" -> {}", c.ret) };
    let params: String = c.params.iter().map(|p| format!(", {prefix}{}: {}", p.name, p.ty)).collect();
    let args: String = c.params.iter().map(|p| format!(", {prefix}{}", p.name)).collect();
    let mut s = String::new();
    s.push_str("    if let Some(__mode) = crate::gl_entry::mode::special() {\n");
    s.push_str("        #[cold]\n        #[inline(never)]\n");
    writeln!(
        s,
        "        unsafe fn __special(__mode: crate::gl_entry::mode::Mode{params}){ret} {{"
    )
    .unwrap();
    writeln!(s, "            let __call = || if __mode.passthrough() {{\n                {}\n            }} else {{\n                {call}\n            }};", forward(model, c, prefix)).unwrap();
    writeln!(s, "            if let Some(mut __t) = crate::gl_entry::call_log::begin(__mode, \"{}\") {{", c.name).unwrap();
    for p in &c.params {
        writeln!(s, "                {}", print_param(model, lens, c, p, prefix)).unwrap();
    }
    if c.ret == "()" {
        s.push_str("                __t.observe(__mode, __call);\n                __t.end();\n                return;\n            }\n");
    } else {
        s.push_str("                let __r = __t.observe(__mode, __call);\n");
        if c.ret == "types::GLenum" {
            s.push_str("                __t.returned_enum(__r);\n");
        } else if c.ret == "*const types::GLubyte" {
            s.push_str("                __t.returned_string(__r);\n");
        } else if is_scalar(&c.ret) || c.ret.contains('*') {
            s.push_str("                __t.returned(__r);\n");
        }
        s.push_str("                __t.end();\n                return __r;\n            }\n");
    }
    s.push_str("            __call()\n        }\n");
    writeln!(s, "        return unsafe {{ __special(__mode{args}) }};\n    }}").unwrap();
    s
}

/// `call_log_groups.rs`: one table of `(name, value)` per enum group a logged parameter names.
pub fn groups(model: &Model, logged: &[&Command]) -> String {
    let integer: BTreeSet<&str> = model
        .enums
        .iter()
        .filter(|(_, ty, _)| crate::emit::is_integer_enum(ty))
        .map(|(n, _, _)| n.as_str())
        .collect();
    // ErrorCode: results of glGetError and the errors calls raise.
    let used: BTreeSet<&str> = std::iter::once("ErrorCode")
        .chain(logged.iter()
        .flat_map(|c| &c.params)
        .filter(|p| ["types::GLenum", "types::GLbitfield", "types::GLint"].contains(&p.ty.as_str()))
        .filter_map(|p| group_of(model, p)))
        .collect();
    let mut s = String::from(HEADER);
    s.push_str("use crate::translate::gl;\n\n");
    for group in used {
        writeln!(s, "/// gl.xml enum group `{group}`.\npub static {group}: &[(&str, u64)] = &[").unwrap();
        let members: BTreeSet<String> = model.groups[group].iter().map(|e| format!("GL_{e}")).collect();
        for m in members.iter().filter(|m| integer.contains(m.as_str())) {
            writeln!(s, "    (\"{m}\", gl::{m} as u64),").unwrap();
        }
        s.push_str("];\n");
    }
    s
}
