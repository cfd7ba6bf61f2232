//! The one-way layering of `src/` (the list is in `src/lib.rs`): `frame` names none of the
//! other layers, `translate` and `render` name only `frame` (and the shared `config`,
//! `logging` and `faults`), `gl_entry` never names `replay`, and `config`, `logging` and
//! `faults` name no layer.
//!
//! Every file of the library is read as Rust tokens: each path that starts at `crate`
//! (`crate::render::…`, `crate::{frame, render::…}`) or climbs out of its layer with `super`
//! names the top-level module it reaches, and so does a `crate::…` written in a comment (an
//! intra-doc link is a reference too). Sources generated into `OUT_DIR` count as part of the
//! module that includes them. `#[cfg(test)]` items and the files of test modules are left
//! out: a unit test may use any layer to build its fixture.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// For each layer, the layers it must not name.
const FORBIDDEN: &[(&str, &[&str])] = &[
    ("frame", &["translate", "render", "gl_entry", "replay"]),
    ("translate", &["render", "gl_entry", "replay"]),
    ("render", &["translate", "gl_entry", "replay"]),
    ("gl_entry", &["replay"]),
    ("config", &["frame", "translate", "render", "gl_entry", "replay"]),
    ("logging", &["frame", "translate", "render", "gl_entry", "replay"]),
    ("faults", &["frame", "translate", "render", "gl_entry", "replay"]),
];

/// A Rust token, as far as paths are concerned.
#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    /// `::`.
    PathSep,
    Punct(char),
    /// A string literal's contents (escapes left as written).
    Str(String),
    Comment(String),
    /// Numbers, char literals, lifetimes.
    Other,
}

/// `source` as tokens, each with its line (from 1).
fn tokenize(source: &str) -> Vec<(Tok, usize)> {
    let s: Vec<char> = source.chars().collect();
    let (mut i, mut line, mut out) = (0, 1, Vec::new());
    let ident_char = |c: char| c.is_alphanumeric() || c == '_';
    while i < s.len() {
        let (c, start_line) = (s[i], line);
        let next = s.get(i + 1).copied();
        let start = i;
        let tok = if c.is_whitespace() {
            i += 1;
            None
        } else if c == '/' && next == Some('/') {
            while i < s.len() && s[i] != '\n' {
                i += 1;
            }
            Some(Tok::Comment(s[start..i].iter().collect()))
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            loop {
                match (s.get(i), s.get(i + 1)) {
                    (Some('/'), Some('*')) => (depth, i) = (depth + 1, i + 2),
                    (Some('*'), Some('/')) => (depth, i) = (depth - 1, i + 2),
                    (Some(_), _) => i += 1,
                    (None, _) => break,
                }
                if depth == 0 {
                    break;
                }
            }
            Some(Tok::Comment(s[start..i.min(s.len())].iter().collect()))
        } else if let Some(hashes) = raw_string_start(&s[i..]) {
            // r"…", r#"…"#, br"…": ends at a quote followed by as many hashes.
            i += s[i..].iter().position(|&c| c == '"').unwrap() + 1;
            let body = i;
            while i < s.len() && !(s[i] == '"' && s[i + 1..].iter().take(hashes).filter(|&&c| c == '#').count() == hashes) {
                i += 1;
            }
            let text = s[body..i.min(s.len())].iter().collect();
            i += 1 + hashes;
            Some(Tok::Str(text))
        } else if c == '"' || (c == 'b' && next == Some('"')) {
            i += if c == 'b' { 2 } else { 1 };
            let body = i;
            while i < s.len() && s[i] != '"' {
                i += if s[i] == '\\' { 2 } else { 1 };
            }
            let text = s[body..i.min(s.len())].iter().collect();
            i += 1;
            Some(Tok::Str(text))
        } else if c == '\'' {
            // A char literal ('a', '\n', '\u{1F600}') or a lifetime ('a).
            if next == Some('\\') {
                i += 3;
                while i < s.len() && s[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if s.get(i + 2) == Some(&'\'') {
                i += 3;
            } else {
                i += 1;
                while i < s.len() && ident_char(s[i]) {
                    i += 1;
                }
            }
            Some(Tok::Other)
        } else if c.is_ascii_digit() {
            while i < s.len() && (ident_char(s[i]) || (s[i] == '.' && s.get(i + 1).is_some_and(char::is_ascii_digit))) {
                i += 1;
            }
            Some(Tok::Other)
        } else if ident_char(c) {
            while i < s.len() && ident_char(s[i]) {
                i += 1;
            }
            Some(Tok::Ident(s[start..i].iter().collect()))
        } else if c == ':' && next == Some(':') {
            i += 2;
            Some(Tok::PathSep)
        } else {
            i += 1;
            Some(Tok::Punct(c))
        };
        line += s[start..i.min(s.len())].iter().filter(|&&c| c == '\n').count();
        out.extend(tok.map(|t| (t, start_line)));
    }
    out
}

/// The number of `#`s of a raw string literal starting at `s[0]`, if one does.
fn raw_string_start(s: &[char]) -> Option<usize> {
    let rest = match s {
        ['r', rest @ ..] | ['b', 'r', rest @ ..] => rest,
        _ => return None,
    };
    let hashes = rest.iter().take_while(|&&c| c == '#').count();
    (rest.get(hashes) == Some(&'"')).then_some(hashes)
}

/// A top-level module named from a file: the layer, and the line.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Reference {
    line: usize,
    layer: String,
}

/// What reading one file found.
#[derive(Default)]
struct Scan {
    /// The top-level modules its non-test code names.
    references: Vec<Reference>,
    /// Child modules declared `#[cfg(test)] mod name;` (their files are test files).
    test_children: Vec<String>,
    /// Whether the whole file is `#![cfg(test)]`.
    test_file: bool,
}

/// Reads `source`, the file of module `module` (`["translate", "pixels", "draw"]`);
/// `generated` reads a file `include!`d from `OUT_DIR` by its name (`None`: not there).
fn scan(source: &str, module: &[String], generated: &dyn Fn(&str) -> Option<String>) -> Scan {
    let tokens = tokenize(source);
    let mut scan = Scan::default();
    Walker { tokens: &tokens, module: module.to_vec(), inline: Vec::new(), depth: 0, generated }.walk(&mut scan);
    scan
}

/// Walks the tokens of one file, knowing which module each token is in.
struct Walker<'a> {
    tokens: &'a [(Tok, usize)],
    /// The module the file is (the including file's, for generated sources).
    module: Vec<String>,
    /// Inline modules entered (`mod name {`), with the brace depth inside them.
    inline: Vec<(String, usize)>,
    depth: usize,
    generated: &'a dyn Fn(&str) -> Option<String>,
}

impl Walker<'_> {
    fn tok(&self, i: usize) -> Option<&Tok> {
        self.tokens.get(i).map(|t| &t.0)
    }

    fn ident(&self, i: usize) -> Option<&str> {
        match self.tok(i) {
            Some(Tok::Ident(name)) => Some(name),
            _ => None,
        }
    }

    /// The module the walker is in now.
    fn current(&self) -> Vec<String> {
        self.module.iter().cloned().chain(self.inline.iter().map(|(name, _)| name.clone())).collect()
    }

    /// The index after the group that opens at `open` (`(`, `[` or `{`).
    fn after_group(&self, open: usize) -> usize {
        let mut depth = 0;
        for (i, (t, _)) in self.tokens.iter().enumerate().skip(open) {
            match t {
                Tok::Punct('(' | '[' | '{') => depth += 1,
                Tok::Punct(')' | ']' | '}') => {
                    depth -= 1;
                    if depth == 0 {
                        return i + 1;
                    }
                }
                _ => {}
            }
        }
        self.tokens.len()
    }

    /// The index after the item starting at `i`: after its `;`, or after its first block.
    fn after_item(&self, mut i: usize) -> usize {
        while let Some(t) = self.tok(i) {
            match t {
                Tok::Punct(';') => return i + 1,
                Tok::Punct('{') => return self.after_group(i),
                Tok::Punct('(' | '[') => i = self.after_group(i),
                _ => i += 1,
            }
        }
        i
    }

    /// The names a path names right after `crate::` at `i`: one name, or the first name of
    /// each entry of a `{…}` group.
    fn first_segments(&self, i: usize) -> Vec<String> {
        match self.tok(i) {
            Some(Tok::Ident(name)) => vec![name.clone()],
            Some(Tok::Punct('{')) => {
                let end = self.after_group(i);
                let mut depth = 0;
                let mut names = Vec::new();
                for j in i..end {
                    match self.tok(j) {
                        Some(Tok::Punct('{')) => depth += 1,
                        Some(Tok::Punct('}')) => depth -= 1,
                        Some(Tok::Ident(name)) if depth == 1 && matches!(self.tok(j - 1), Some(Tok::Punct('{' | ','))) => {
                            names.push(name.clone());
                        }
                        _ => {}
                    }
                }
                names
            }
            _ => Vec::new(),
        }
    }

    fn walk(&mut self, scan: &mut Scan) {
        let mut i = 0;
        while let Some((tok, line)) = self.tokens.get(i) {
            let line = *line;
            match tok {
                Tok::Punct('#') if self.tok(i + 1) == Some(&Tok::Punct('!')) => {
                    let end = self.after_group(i + 2);
                    if is_cfg_test(&self.tokens[i + 2..end]) && self.depth == 0 && self.inline.is_empty() {
                        scan.test_file = true;
                        scan.references.clear();
                        return;
                    }
                    i = end;
                }
                Tok::Punct('#') if self.tok(i + 1) == Some(&Tok::Punct('[')) => {
                    let end = self.after_group(i + 1);
                    if !is_cfg_test(&self.tokens[i + 1..end]) {
                        i = end;
                        continue;
                    }
                    // Skip the item, after any further attributes: note `mod name;`.
                    let mut item = end;
                    while self.tok(item) == Some(&Tok::Punct('#')) {
                        item = self.after_group(item + 1);
                    }
                    let mut j = item;
                    while matches!(self.ident(j), Some("pub" | "crate")) || self.tok(j) == Some(&Tok::Punct('(')) {
                        j = if self.tok(j) == Some(&Tok::Punct('(')) { self.after_group(j) } else { j + 1 };
                    }
                    if self.ident(j) == Some("mod")
                        && let Some(name) = self.ident(j + 1)
                        && self.tok(j + 2) == Some(&Tok::Punct(';'))
                    {
                        scan.test_children.push(name.to_owned());
                    }
                    i = self.after_item(item);
                }
                Tok::Ident(word) if word == "mod" && self.tok(i + 2) == Some(&Tok::Punct('{')) => {
                    let name = self.ident(i + 1).unwrap_or_default().to_owned();
                    self.depth += 1;
                    self.inline.push((name, self.depth));
                    i += 3;
                }
                Tok::Punct('{') => {
                    self.depth += 1;
                    i += 1;
                }
                Tok::Punct('}') => {
                    if self.inline.last().is_some_and(|&(_, d)| d == self.depth) {
                        self.inline.pop();
                    }
                    self.depth = self.depth.saturating_sub(1);
                    i += 1;
                }
                Tok::Ident(word) if word == "crate" && self.tok(i + 1) == Some(&Tok::PathSep) => {
                    scan.references.extend(self.first_segments(i + 2).into_iter().map(|layer| Reference { line, layer }));
                    i += 2;
                }
                Tok::Ident(word) if (word == "super" || word == "self") && self.tok(i + 1) == Some(&Tok::PathSep) => {
                    let mut module = self.current();
                    let mut j = i;
                    while self.ident(j) == Some("super") && self.tok(j + 1) == Some(&Tok::PathSep) {
                        module.pop();
                        j += 2;
                    }
                    if self.ident(j) == Some("self") {
                        j += 2;
                    }
                    let layers = match module.first() {
                        Some(layer) => vec![layer.clone()],
                        None => self.first_segments(j),
                    };
                    scan.references.extend(layers.into_iter().map(|layer| Reference { line, layer }));
                    i = j;
                }
                Tok::Ident(word) if word == "include" && self.tok(i + 1) == Some(&Tok::Punct('!')) => {
                    let end = self.after_group(i + 2);
                    let strings: Vec<&str> = self.tokens[i..end]
                        .iter()
                        .filter_map(|(t, _)| if let Tok::Str(s) = t { Some(s.as_str()) } else { None })
                        .collect();
                    if let ["OUT_DIR", name] = strings[..] {
                        let source = (self.generated)(name.trim_start_matches('/'))
                            .unwrap_or_else(|| panic!("{name}, included from OUT_DIR, is not there"));
                        let inner = scan_generated(&source, &self.current(), self.generated);
                        scan.references.extend(inner.into_iter().map(|r| Reference { line, layer: r.layer }));
                    }
                    i = end;
                }
                Tok::Comment(text) => {
                    let mut rest = text.as_str();
                    while let Some(at) = rest.find("crate::") {
                        rest = &rest[at + "crate::".len()..];
                        let layer: String = rest.chars().take_while(|&c| c.is_alphanumeric() || c == '_').collect();
                        scan.references.push(Reference { line, layer });
                    }
                    i += 1;
                }
                _ => i += 1,
            }
        }
    }
}

/// The references of a generated source included in module `module`.
fn scan_generated(source: &str, module: &[String], generated: &dyn Fn(&str) -> Option<String>) -> Vec<Reference> {
    scan(source, module, generated).references
}

/// Whether the attribute tokens (from its `[`) are `cfg(…)` with `test` in them, not negated.
fn is_cfg_test(attribute: &[(Tok, usize)]) -> bool {
    let idents: Vec<&str> = attribute.iter().filter_map(|(t, _)| if let Tok::Ident(s) = t { Some(s.as_str()) } else { None }).collect();
    idents.first() == Some(&"cfg") && idents.contains(&"test") && !idents.contains(&"not")
}

/// The layering violations of one file of layer `module[0]`: `line: names layer`.
fn violations(references: &[Reference], module: &[String]) -> Vec<String> {
    let Some(layer) = module.first() else { return Vec::new() };
    let forbidden = FORBIDDEN.iter().find(|(l, _)| l == layer).map_or(&[][..], |(_, f)| f);
    let found: BTreeSet<&Reference> = references.iter().filter(|r| forbidden.contains(&r.layer.as_str())).collect();
    found.into_iter().map(|r| format!("line {}: {layer} names {}", r.line, r.layer)).collect()
}

/// The module path of a file under `src/` (`translate/pixels/mod.rs` → `translate::pixels`).
fn module_of(relative: &Path) -> Vec<String> {
    let mut parts: Vec<String> = relative.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    let file = parts.pop().unwrap_or_default();
    let stem = file.trim_end_matches(".rs");
    if stem != "mod" && stem != "lib" {
        parts.push(stem.to_owned());
    }
    parts
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).expect("readable source folder") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            out.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out.sort();
    out
}

#[test]
fn no_layer_names_one_it_must_not() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let out_dir = PathBuf::from(env!("OUT_DIR"));
    let generated = |name: &str| std::fs::read_to_string(out_dir.join(name)).ok();
    // The library's files (the `glrt` command in `src/bin` is a client of every layer).
    let files: Vec<PathBuf> = rust_files(&src).into_iter().filter(|f| !f.starts_with(src.join("bin"))).collect();
    let scans: Vec<(Vec<String>, Scan)> = files
        .iter()
        .map(|f| {
            let module = module_of(f.strip_prefix(&src).unwrap());
            let scan = scan(&std::fs::read_to_string(f).expect("readable source"), &module, &generated);
            (module, scan)
        })
        .collect();
    let test_modules: Vec<Vec<String>> = scans
        .iter()
        .flat_map(|(module, scan)| scan.test_children.iter().map(move |child| [module.clone(), vec![child.clone()]].concat()))
        .collect();
    let mut problems = Vec::new();
    let mut checked = BTreeSet::new();
    for ((module, scan), file) in scans.iter().zip(&files) {
        if scan.test_file || test_modules.iter().any(|t| module.starts_with(t)) {
            continue;
        }
        checked.insert(module.first().cloned().unwrap_or_default());
        problems.extend(violations(&scan.references, module).into_iter().map(|v| format!("{}: {v}", file.display())));
    }
    for (layer, _) in FORBIDDEN {
        assert!(checked.contains(*layer), "no file of layer {layer} was checked");
    }
    assert!(problems.is_empty(), "layering violations:\n{}", problems.join("\n"));
}

/// The violations of `source` as the file of module `module` (`"translate::pixels"`).
fn check(source: &str, module: &str) -> Vec<String> {
    let module: Vec<String> = module.split("::").map(str::to_owned).collect();
    let generated = |name: &str| (name == "table.rs").then(|| "fn f() { crate::gl_entry::exports::glFlush() }".to_owned());
    violations(&scan(source, &module, &generated).references, &module)
}

#[test]
fn the_checker_finds_each_way_of_naming_a_layer() {
    assert_eq!(check("use crate::render::FrameSink;", "translate::context"), ["line 1: translate names render"]);
    assert_eq!(check("use crate::{frame::Frame,\n gl_entry::current};", "translate"), ["line 1: translate names gl_entry"]);
    assert_eq!(check("fn f() { super::super::super::render::x(); }", "translate::pixels::draw"), ["line 1: translate names render"]);
    assert_eq!(check("use super::{frame, replay};", "translate"), ["line 1: translate names replay"]);
    assert_eq!(check("mod inner { use super::super::translate::Context; }", "frame"), ["line 1: frame names translate"]);
    assert_eq!(check("/// Through [`crate::render::FrameSink`].\nfn f() {}", "frame::sink"), ["line 1: frame names render"]);
    assert_eq!(check("pub mod table { include!(concat!(env!(\"OUT_DIR\"), \"/table.rs\")); }", "translate::capture"), [
        "line 1: translate names gl_entry"
    ]);
    assert_eq!(check("\n\nlet x = crate::replay::run;", "gl_entry::headless"), ["line 3: gl_entry names replay"]);
}

#[test]
fn the_checker_allows_what_the_layers_may_name() {
    let allowed = "use crate::frame::Frame;\nuse super::gl;\nuse crate::config::Config;\nuse self::inner::X;";
    assert!(check(allowed, "translate::context").is_empty());
    assert!(check("use crate::{render, translate::Context};", "gl_entry::headless").is_empty());
    assert!(check("use crate::gl_entry::headless;", "replay").is_empty());
    // Strings, char literals and lifetimes are not paths.
    assert!(check("const S: &str = \"crate::render\"; fn f<'a>(c: char) -> bool { c == '{' || c == '\\'' }", "translate").is_empty());
    assert!(check("const S: &str = r#\"crate::render \"quoted\"\"#;", "translate").is_empty());
}

#[test]
fn the_checker_leaves_out_test_code() {
    let source = "#[cfg(test)]\nmod tests {\n    use crate::render::NullSink;\n}\n#[cfg(test)]\nuse crate::gl_entry::x;\n\
                  #[cfg(test)]\nmod more;\nuse crate::render::Late;";
    assert_eq!(check(source, "translate::queries"), ["line 9: translate names render"], "only the line after the test items");
    let module = ["translate".to_owned()];
    let scanned = scan(source, &module, &|_| None);
    assert_eq!(scanned.test_children, ["more"]);
    assert!(scan("#![cfg(test)]\nuse crate::render::X;", &module, &|_| None).test_file);
    assert_eq!(check("#[cfg(not(test))]\nuse crate::render::X;", "translate"), ["line 2: translate names render"]);
}
