//! Finds what the hand-written sources implement: `translate` methods named after GL commands,
//! their `compile_` companions, and C functions exported by hand in `gl_entry`.

use std::collections::BTreeSet;
use std::fs;
use std::path::Path;

/// Identifiers following `marker` (for example `fn gl`) in every `.rs` file under `dir`,
/// with `prefix` put back in front.
pub fn identifiers_after(dir: &Path, marker: &str, prefix: &str) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    visit(dir, &mut |text| found.extend(identifiers_in(text, marker, prefix, true)));
    found
}

/// C functions exported by hand: `(module path below dir, name)` for each `extern "C" fn gl...`
/// in the `.rs` files under `dir` (`("headless", "glrtSwapBuffers")`,
/// `("glx::exports::swap", "glXSwapBuffers")`).
pub fn hand_exports(dir: &Path) -> Vec<(String, String)> {
    let mut found = Vec::new();
    hand_exports_under(dir, &[], &mut found);
    found
}

/// [`hand_exports`] of the folder `dir`, the module `module`.
fn hand_exports_under(dir: &Path, module: &[String], found: &mut Vec<(String, String)>) {
    let mut entries: Vec<_> = fs::read_dir(dir).expect("gl_entry dir").flatten().collect();
    entries.sort_by_key(|e| e.path());
    for entry in entries {
        let path = entry.path();
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            hand_exports_under(&path, &[module, &[stem]].concat(), found);
            continue;
        }
        if path.extension().is_none_or(|e| e != "rs") {
            continue;
        }
        let inner = if stem == "mod" { module.to_vec() } else { [module, &[stem]].concat() };
        let text = fs::read_to_string(&path).expect("reading source");
        for name in identifiers_in(&text, "extern \"C\" fn ", "", false) {
            if name.starts_with("gl") {
                found.push((inner.join("::"), name));
            }
        }
    }
}

/// Identifiers following `marker` in `text`, with `prefix` put back in front; with
/// `upper_first`, only those starting with an upper-case letter.
fn identifiers_in(text: &str, marker: &str, prefix: &str, upper_first: bool) -> Vec<String> {
    let mut found = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find(marker) {
        rest = &rest[at + marker.len()..];
        let ident: String =
            rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
        if !ident.is_empty() && (!upper_first || ident.starts_with(|c: char| c.is_ascii_uppercase())) {
            found.push(format!("{prefix}{ident}"));
        }
    }
    found
}

fn visit(dir: &Path, f: &mut dyn FnMut(&str)) {
    let Ok(entries) = fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            visit(&path, f);
        } else if path.extension().is_some_and(|e| e == "rs") {
            f(&fs::read_to_string(&path).expect("reading source"));
        }
    }
}
