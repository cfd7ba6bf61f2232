//! The global declarations of a shader: its struct types, constants, uniforms, attributes and
//! varyings, and where each global statement lies in the token stream (for the rewrite).

use std::collections::HashMap;

use super::tokens::{Kind, Token};
use super::types::{self, BasicType};

/// A variable's type.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Type {
    /// A basic type.
    Basic(&'static BasicType),
    /// A struct declared by the shader (its GLSL name).
    Struct(String),
}

/// A declared variable (or struct member).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Variable {
    /// Its type.
    pub ty: Type,
    /// Its name as the program spells it.
    pub name: String,
    /// Array length, for arrays.
    pub array: Option<u32>,
}

/// What a global statement is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Statement {
    /// `uniform` declarations (indices into [`Declarations::uniforms`]).
    Uniform(Vec<usize>),
    /// `attribute` declarations.
    Attribute(Vec<usize>),
    /// `varying` declarations.
    Varying(Vec<usize>),
    /// A struct definition (hoisted before the uniform block by the rewrite).
    Struct,
    /// A `const` declaration (hoisted with the structs, which may use it).
    Const,
    /// `invariant gl_Position;` and the like: dropped (Vulkan GLSL has its own rules).
    Invariant,
    /// Anything else: functions, plain globals.
    Other,
}

/// The global declarations of a shader.
#[derive(Clone, Debug, Default)]
pub struct Declarations {
    /// Struct types by name, with their members in order.
    pub structs: HashMap<String, Vec<Variable>>,
    /// Uniforms in declaration order.
    pub uniforms: Vec<Variable>,
    /// Attributes in declaration order.
    pub attributes: Vec<Variable>,
    /// Varyings in declaration order.
    pub varyings: Vec<Variable>,
    /// Global statements: token range (end exclusive) and what it is.
    pub statements: Vec<(std::ops::Range<usize>, Statement)>,
}

/// Reads the global declarations of preprocessed `tokens`; an error names what glrt cannot
/// translate.
pub fn parse(tokens: &[Token]) -> Result<Declarations, String> {
    let mut decls = Declarations::default();
    let mut consts: HashMap<String, u32> = HashMap::new();
    let mut start = 0;
    let mut depth = 0usize;
    let mut parens = 0usize;
    for (i, token) in tokens.iter().enumerate() {
        if token.kind == Kind::Directive {
            if depth == 0 && parens == 0 && significant(&tokens[start..i]).is_empty() {
                decls.statements.push((start..i + 1, Statement::Other));
                start = i + 1;
            }
            continue;
        }
        let end = match token.text.as_str() {
            "(" => {
                parens += 1;
                None
            }
            ")" => {
                parens = parens.saturating_sub(1);
                None
            }
            "{" => {
                depth += 1;
                None
            }
            "}" => {
                depth = depth.saturating_sub(1);
                // A function body ends its statement; a struct body does not (`};` follows).
                let words = significant(&tokens[start..i]);
                (depth == 0 && !words.iter().any(|t| t.text == "struct")).then_some(i + 1)
            }
            ";" if depth == 0 => Some(i + 1),
            _ => None,
        };
        if let Some(end) = end {
            let statement = classify(&tokens[start..end], &mut decls, &mut consts)?;
            decls.statements.push((start..end, statement));
            start = end;
        }
    }
    if start < tokens.len() {
        decls.statements.push((start..tokens.len(), Statement::Other));
    }
    Ok(decls)
}

/// The tokens that are not whitespace.
fn significant(tokens: &[Token]) -> Vec<&Token> {
    tokens.iter().filter(|t| t.kind != Kind::Space).collect()
}

/// What one global statement is; records its declarations.
fn classify(tokens: &[Token], decls: &mut Declarations, consts: &mut HashMap<String, u32>) -> Result<Statement, String> {
    let words = significant(tokens);
    let Some(first) = words.first() else { return Ok(Statement::Other) };
    let mut qualifiers = Vec::new();
    let mut rest = &words[..];
    while let Some(w) = rest.first().filter(|w| matches!(w.text.as_str(), "uniform" | "attribute" | "varying" | "const" | "centroid" | "invariant")) {
        qualifiers.push(w.text.as_str());
        rest = &rest[1..];
    }
    if first.text == "struct" {
        if words.last().is_some_and(|w| w.text == ";") && words.len() >= 2 && words[words.len() - 2].text != "}" {
            return Err("glrt: a variable declared with its struct definition (declare the struct first)".into());
        }
        let name = words.get(1).filter(|w| w.kind == Kind::Ident).ok_or("glrt: anonymous structs are not supported")?;
        let open = words.iter().position(|w| w.text == "{").ok_or("glrt: malformed struct")?;
        let close = words.iter().rposition(|w| w.text == "}").ok_or("glrt: malformed struct")?;
        let mut members = Vec::new();
        for member in words[open + 1..close].split(|w| w.text == ";").filter(|m| !m.is_empty()) {
            members.extend(declarators(member, decls, consts)?);
        }
        decls.structs.insert(name.text.clone(), members);
        return Ok(Statement::Struct);
    }
    if qualifiers.first() == Some(&"invariant") && rest.len() == 2 {
        return Ok(Statement::Invariant);
    }
    let body = &rest[..rest.len().saturating_sub(1)];
    let kind = if qualifiers.contains(&"uniform") {
        if body.iter().any(|w| w.text == "=") {
            return Err("glrt: uniform initializers (GLSL 1.20) are not supported".into());
        }
        Some(Statement::Uniform as fn(Vec<usize>) -> Statement)
    } else if qualifiers.contains(&"attribute") {
        Some(Statement::Attribute as fn(Vec<usize>) -> Statement)
    } else if qualifiers.contains(&"varying") {
        Some(Statement::Varying as fn(Vec<usize>) -> Statement)
    } else {
        None
    };
    if qualifiers.contains(&"const") && kind.is_none() {
        // `const int N = 4;`: remembered for array sizes.
        if let [ty, name, eq, value, ..] = body
            && ty.text == "int" && eq.text == "="
                && let Ok(v) = value.text.parse() {
                    consts.insert(name.text.clone(), v);
                }
        return Ok(Statement::Const);
    }
    let Some(make) = kind else { return Ok(Statement::Other) };
    // Built-in redeclarations (`varying vec4 gl_TexCoord[2];`) declare nothing of the program's.
    if body.iter().any(|w| w.text.starts_with("gl_")) {
        return Ok(Statement::Invariant);
    }
    let vars = declarators(body, decls, consts)?;
    let list = match make(Vec::new()) {
        Statement::Uniform(_) => &mut decls.uniforms,
        Statement::Attribute(_) => &mut decls.attributes,
        _ => &mut decls.varyings,
    };
    let first_index = list.len();
    list.extend(vars);
    Ok(make((first_index..list.len()).collect()))
}

/// The variables of `type name [N], name, ...` (a declaration without its qualifiers and `;`).
fn declarators(words: &[&Token], decls: &Declarations, consts: &HashMap<String, u32>) -> Result<Vec<Variable>, String> {
    let Some(ty_word) = words.first() else { return Ok(Vec::new()) };
    let ty = match types::basic(&ty_word.text) {
        Some(b) => Type::Basic(b),
        None if decls.structs.contains_key(&ty_word.text) => Type::Struct(ty_word.text.clone()),
        None => return Err(format!("glrt: unknown type '{}' in a declaration", ty_word.text)),
    };
    let mut vars = Vec::new();
    for part in words[1..].split(|w| w.text == ",") {
        let Some(name) = part.first().filter(|w| w.kind == Kind::Ident) else {
            return Err(format!("glrt: cannot read the declaration of a '{}'", ty_word.text));
        };
        let array = match part.get(1).map(|w| w.text.as_str()) {
            Some("[") => {
                let size = part.get(2).ok_or("glrt: unsized array")?;
                let n = size.text.parse().ok().or_else(|| consts.get(&size.text).copied());
                Some(n.ok_or_else(|| format!("glrt: array size '{}' is not a literal or an int constant", size.text))?)
            }
            _ => None,
        };
        vars.push(Variable { ty: ty.clone(), name: name.text.clone(), array });
    }
    Ok(vars)
}

#[cfg(test)]
mod tests {
    use super::super::tokens::tokenize;
    use super::*;

    #[test]
    fn reads_globals() {
        let src = "#version 110\nconst int N = 3;\nstruct L { vec4 c; float k[N]; };\nuniform L lights[2];\nuniform sampler2D tex;\nuniform vec3 a, b[4];\nattribute vec3 tangent;\nvarying vec2 uv;\nvarying vec4 gl_TexCoord[2];\nfloat helper(float x) { return x * 2.0; }\nvoid main() { gl_FragColor = vec4(helper(a.x)); }\n";
        let tokens = tokenize(src);
        let d = parse(&tokens).unwrap();
        let names: Vec<_> = d.uniforms.iter().map(|u| (u.name.as_str(), u.array)).collect();
        assert_eq!(names, vec![("lights", Some(2)), ("tex", None), ("a", None), ("b", Some(4))]);
        assert_eq!(d.structs["L"][1].array, Some(3));
        assert_eq!(d.attributes[0].name, "tangent");
        assert_eq!(d.varyings.len(), 1);
        let kinds: Vec<_> = d.statements.iter().map(|(_, s)| s.clone()).collect();
        assert_eq!(kinds.iter().filter(|s| **s == Statement::Other).count(), 4, "{kinds:?}"); // the directive, two functions, the last newline
        assert!(kinds.contains(&Statement::Invariant));
        // Every token belongs to exactly one statement, in order.
        let mut next = 0;
        for (range, _) in &d.statements {
            assert_eq!(range.start, next);
            next = range.end;
        }
        assert_eq!(next, tokens.len());
    }
}
