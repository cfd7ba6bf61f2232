//! The rewrite of one stage of a GLSL 1.10/1.20 program into Vulkan GLSL 4.50 that fits the
//! shader interface of the module doc: the program's code with its identifiers renamed, between
//! glrt's declarations (`shaders/glsl_*_head.glsl`) and entry point (`shaders/glsl_*_main.glsl`).
//!
//! Renaming: the program's own identifiers get the prefix `u_` (so they can clash neither with
//! GLSL 4.50's new keywords and functions nor with glrt's names, none of which start with
//! `u_`); built-in `gl_X` becomes `glrt_X` (declared by `glsl_builtins.glsl` and the heads),
//! except the outputs Vulkan GLSL has itself (`gl_Position`, `gl_PointSize`, `gl_FragDepth`);
//! texture lookups become the prelude's functions with the sampler's slot as last argument;
//! field selections (after `.`) and struct members keep their names.

use std::collections::{HashMap, HashSet};
use std::fmt::Write;

use super::Stage;
use super::declarations::{Declarations, Statement, Type, Variable};
use super::tokens::{Kind, Token};
use crate::frame::program::GENERIC_ATTRIBUTE_LOCATION;

/// Keywords, types and built-in functions of GLSL 1.20 that keep their names.
const KEPT: &[&str] = &[
    "attribute", "const", "uniform", "varying", "centroid", "invariant", "break", "continue", "do", "for", "while",
    "if", "else", "in", "out", "inout", "true", "false", "discard", "return", "struct", "void", "float", "int", "bool",
    "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4", "bvec2", "bvec3", "bvec4", "mat2", "mat3", "mat4", "mat2x2",
    "mat2x3", "mat2x4", "mat3x2", "mat3x3", "mat3x4", "mat4x2", "mat4x3", "mat4x4", "sampler2D", "sampler3D",
    "samplerCube", "radians", "degrees", "sin", "cos", "tan", "asin", "acos", "atan", "pow", "exp", "log", "exp2",
    "log2", "sqrt", "inversesqrt", "abs", "sign", "floor", "ceil", "fract", "mod", "min", "max", "clamp", "mix", "step",
    "smoothstep", "length", "distance", "dot", "cross", "normalize", "faceforward", "reflect", "refract",
    "matrixCompMult", "outerProduct", "transpose", "lessThan", "lessThanEqual", "greaterThan", "greaterThanEqual",
    "equal", "notEqual", "any", "all", "not", "dFdx", "dFdy", "fwidth", "noise1", "noise2", "noise3", "noise4",
];

/// Built-in outputs that Vulkan GLSL has under the same name.
const VULKAN_BUILTINS: &[&str] = &["gl_Position", "gl_PointSize", "gl_FragDepth"];

/// The texture lookup functions of GLSL 1.10, which the prelude defines as `glrt_<name>`.
const LOOKUPS: &[&str] = &[
    "texture1D", "texture1DProj", "texture1DLod", "texture1DProjLod", "texture2D", "texture2DProj", "texture2DLod",
    "texture2DProjLod", "texture3D", "texture3DProj", "texture3DLod", "texture3DProjLod", "textureCube",
    "textureCubeLod", "shadow1D", "shadow2D", "shadow1DProj", "shadow2DProj", "shadow1DLod", "shadow2DLod",
    "shadow1DProjLod", "shadow2DProjLod",
];

/// Sampler types that the rewrite declares as `sampler2D`.
const AS_SAMPLER_2D: &[&str] = &["sampler1D", "sampler1DShadow", "sampler2DShadow"];

/// The renamed form of a program identifier.
pub fn renamed(name: &str) -> String {
    format!("u_{name}")
}

/// Everything the rewrite of one stage needs from the link.
pub struct StageInput<'a> {
    /// The stage.
    pub stage: Stage,
    /// The stage's preprocessed tokens.
    pub tokens: &'a [Token],
    /// Its declarations.
    pub decls: &'a Declarations,
    /// Struct definitions of both stages (the uniform block may need the other stage's).
    pub structs: &'a HashMap<String, Vec<Variable>>,
    /// The program's uniforms in block order, samplers excluded.
    pub block: &'a [Variable],
    /// Sampler slots by name.
    pub sampler_slots: &'a HashMap<String, u32>,
    /// Sampler type names by name (as declared).
    pub sampler_types: &'a HashMap<String, String>,
    /// Varying location and first component by name.
    pub varying_locations: &'a HashMap<String, (u32, u32)>,
    /// Generic attribute index of each attribute, by name (vertex stage).
    pub attribute_indices: &'a HashMap<String, u32>,
}

/// Vulkan GLSL 4.50 source of one stage.
pub fn rewrite(input: &StageInput) -> String {
    let mut out = String::from("#version 450\n");
    let fragment = input.stage == Stage::Fragment;
    if fragment {
        out.push_str("#define FF_FRAGMENT\n");
    }
    for part in [
        include_str!(concat!(env!("OUT_DIR"), "/glsl/generated/texenv_codes.glsl")),
        include_str!(concat!(env!("OUT_DIR"), "/glsl/generated/ff_interface.glsl")),
        include_str!("../../../shaders/bit_field.glsl"),
        include_str!("../../../shaders/ff_key.glsl"),
        include_str!("../../../shaders/fog/height.glsl"),
        include_str!("../../../shaders/ff_uniforms.glsl"),
        include_str!("../../../shaders/ff_varyings.glsl"),
        include_str!("../../../shaders/gl_compare.glsl"),
    ] {
        out.push_str(part);
    }
    if fragment {
        out.push_str(include_str!("../../../shaders/ff_fragment_ops.glsl"));
    }
    out.push_str(include_str!("../../../shaders/glsl_builtins.glsl"));
    out.push_str(if fragment {
        include_str!("../../../shaders/glsl_fragment_head.glsl")
    } else {
        include_str!("../../../shaders/glsl_vertex_head.glsl")
    });
    out.push_str(include_str!("../../../shaders/glsl_prelude.glsl"));
    declare_structs(&mut out, input.structs);
    declare_interface(&mut out, input);
    out.push_str("#line 1\n");
    out.push_str(&rewrite_code(input));
    out.push('\n');
    if fragment {
        let output = if uses(input.tokens, "gl_FragData") { "glrt_FragData[0]" } else { "glrt_FragColor" };
        let _ = writeln!(out, "#define GLRT_FRAGMENT_OUTPUT {output}");
        out.push_str(include_str!("../../../shaders/glsl_fragment_main.glsl"));
    } else {
        let mut before = String::new();
        for a in &input.decls.attributes {
            if input.attribute_indices.get(&a.name) == Some(&0) {
                let _ = write!(before, "{} = {}(glrt_Vertex); ", renamed(&a.name), type_name(&a.ty));
            }
        }
        let _ = writeln!(out, "#define GLRT_BEFORE_MAIN {before}");
        out.push_str(include_str!("../../../shaders/glsl_vertex_main.glsl"));
    }
    out
}

/// Whether identifier `name` occurs in `tokens`.
pub fn uses(tokens: &[Token], name: &str) -> bool {
    tokens.iter().any(|t| t.kind == Kind::Ident && t.text == name)
}

/// The Vulkan GLSL name of a type.
fn type_name(ty: &Type) -> String {
    match ty {
        Type::Basic(b) => b.vulkan_name().to_string(),
        Type::Struct(s) => renamed(s),
    }
}

/// `type name[N]` of a variable.
fn declarator(v: &Variable) -> String {
    match v.array {
        Some(n) => format!("{} {}[{n}]", type_name(&v.ty), renamed(&v.name)),
        None => format!("{} {}", type_name(&v.ty), renamed(&v.name)),
    }
}

/// The struct definitions of both stages, each after the structs it contains.
fn declare_structs(out: &mut String, structs: &HashMap<String, Vec<Variable>>) {
    let mut done = HashSet::new();
    let mut names: Vec<_> = structs.keys().collect();
    names.sort();
    fn emit(name: &str, structs: &HashMap<String, Vec<Variable>>, done: &mut HashSet<String>, out: &mut String) {
        if !done.insert(name.to_string()) {
            return;
        }
        for m in &structs[name] {
            if let Type::Struct(inner) = &m.ty {
                emit(inner, structs, done, out);
            }
        }
        let _ = write!(out, "struct {} {{", renamed(name));
        for m in &structs[name] {
            let member = match m.array {
                Some(n) => format!(" {} {}[{n}];", type_name(&m.ty), m.name),
                None => format!(" {} {};", type_name(&m.ty), m.name),
            };
            out.push_str(&member);
        }
        out.push_str(" };\n");
    }
    for name in names {
        emit(name, structs, &mut done, out);
    }
}

/// The uniform block, samplers, attributes and varyings of the stage.
fn declare_interface(out: &mut String, input: &StageInput) {
    if !input.block.is_empty() {
        out.push_str("layout(set = 1, binding = 1, std430) readonly buffer GlrtUniforms {\n");
        for v in input.block {
            let _ = writeln!(out, "    {};", declarator(v));
        }
        out.push_str("};\n");
    }
    let mut samplers: Vec<_> = input.sampler_slots.iter().collect();
    samplers.sort_by_key(|(_, slot)| **slot);
    for (name, slot) in samplers {
        let ty = &input.sampler_types[name];
        let ty = if AS_SAMPLER_2D.contains(&ty.as_str()) { "sampler2D" } else { ty.as_str() };
        let _ = writeln!(out, "layout(set = 1, binding = {}) uniform {ty} {};", 2 + slot, renamed(name));
    }
    let direction = if input.stage == Stage::Fragment { "in" } else { "out" };
    for v in &input.decls.varyings {
        if let Some((location, component)) = input.varying_locations.get(&v.name) {
            // Vulkan GLSL allows `component` on scalars and vectors only.
            let packable = matches!(&v.ty, Type::Basic(b) if b.columns == 1);
            let at = if packable { format!("location = {location}, component = {component}") } else { format!("location = {location}") };
            let _ = writeln!(out, "layout({at}) {direction} {};", declarator(v));
        }
    }
    for a in &input.decls.attributes {
        match input.attribute_indices.get(&a.name) {
            Some(0) | None => {
                let _ = writeln!(out, "{};", declarator(a));
            }
            Some(&index) => {
                let location = GENERIC_ATTRIBUTE_LOCATION + index - 1;
                let _ = writeln!(out, "layout(location = {location}) in {};", declarator(a));
            }
        }
    }
}

/// The program's code without the declarations glrt made, its identifiers renamed.
fn rewrite_code(input: &StageInput) -> String {
    let tokens = input.tokens;
    let closing = matching_parens(tokens);
    let mut insert_before: HashMap<usize, String> = HashMap::new();
    let mut out = String::new();
    for (range, statement) in &input.decls.statements {
        let dropped = !matches!(statement, Statement::Other | Statement::Const);
        let mut in_struct_depth: Option<usize> = None;
        let mut depth = 0usize;
        let mut prev: Option<&Token> = None;
        for i in range.clone() {
            let token = &tokens[i];
            if let Some(text) = insert_before.remove(&i) {
                out.push_str(&text);
            }
            if dropped || token.kind == Kind::Directive {
                // Keep the line structure, so log lines still match the program's.
                out.extend(token.text.chars().filter(|&c| c == '\n'));
                continue;
            }
            match token.text.as_str() {
                "{" => depth += 1,
                "}" => {
                    depth = depth.saturating_sub(1);
                    if in_struct_depth.is_some_and(|d| depth < d) {
                        in_struct_depth = None;
                    }
                }
                _ => {}
            }
            if token.kind == Kind::Ident {
                if token.text == "struct" {
                    in_struct_depth = Some(depth + 1);
                }
                let member_name = in_struct_depth == Some(depth)
                    && prev.is_some_and(|p| p.text == "," || (p.kind == Kind::Ident && p.text != "struct"));
                let field = prev.is_some_and(|p| p.text == ".");
                if field || member_name {
                    out.push_str(&token.text);
                } else if LOOKUPS.contains(&token.text.as_str()) {
                    let _ = write!(out, "glrt_{}", token.text);
                    let slot = lookup_slot(tokens, i, input.sampler_slots);
                    if let Some(&close) = next_significant(tokens, i).and_then(|open| closing.get(&open)) {
                        insert_before.insert(close, format!(", {slot}"));
                    }
                } else {
                    out.push_str(&identifier(&token.text));
                }
            } else {
                out.push_str(&token.text);
            }
            if token.kind != Kind::Space {
                prev = Some(token);
            }
        }
    }
    out
}

/// The new name of an identifier outside field selections and struct members.
fn identifier(name: &str) -> String {
    if AS_SAMPLER_2D.contains(&name) {
        "sampler2D".into()
    } else if name == "ftransform" {
        "glrt_ftransform".into()
    } else if VULKAN_BUILTINS.contains(&name) || KEPT.contains(&name) {
        name.into()
    } else if let Some(builtin) = name.strip_prefix("gl_") {
        format!("glrt_{builtin}")
    } else {
        renamed(name)
    }
}

/// The slot of the sampler a lookup at token `at` reads: its first argument when that is a
/// sampler uniform, else -1.
fn lookup_slot(tokens: &[Token], at: usize, slots: &HashMap<String, u32>) -> i64 {
    let args: Vec<&Token> = tokens[at + 1..].iter().filter(|t| t.kind != Kind::Space).take(3).collect();
    match args.as_slice() {
        [open, name, comma] if open.text == "(" && comma.text == "," => slots.get(&name.text).map_or(-1, |&s| s as i64),
        _ => -1,
    }
}

/// The index of the next non-space token after `at`, when it is `(`.
fn next_significant(tokens: &[Token], at: usize) -> Option<usize> {
    let (i, t) = tokens.iter().enumerate().skip(at + 1).find(|(_, t)| t.kind != Kind::Space)?;
    (t.text == "(").then_some(i)
}

/// Index of the `)` matching each `(`.
fn matching_parens(tokens: &[Token]) -> HashMap<usize, usize> {
    let mut open = Vec::new();
    let mut pairs = HashMap::new();
    for (i, t) in tokens.iter().enumerate() {
        if t.kind == Kind::Punct && t.text == "(" {
            open.push(i);
        } else if t.kind == Kind::Punct && t.text == ")"
            && let Some(o) = open.pop() {
                pairs.insert(o, i);
            }
    }
    pairs
}
