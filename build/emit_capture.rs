//! The capture side of the generated exports (`GLRT_CAPTURE`, `translate::capture`): one
//! statement per export that records the call; `capture_commands.rs`, the command table a
//! capture file describes itself with (`translate::capture::table`); and `replay_calls.rs`,
//! the replay thunks (command id → decoded arguments → the same C export a program calls,
//! `replay::calls`).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use crate::emit::HEADER;
use crate::model::{Command, Model, Route};

/// Whether the export of `c` records its calls: every generated GL export whose parameters are
/// all numbers or pointers (the few taking debug callbacks are left out: a callback cannot be
/// replayed in another process).
fn is_captured(c: &Command) -> bool {
    !matches!(c.route, Route::Hand(_)) && !c.is_glx && !c.params.iter().any(|p| p.ty.contains("DEBUGPROC"))
}

/// The capture id of each captured command: its index in the table, in name order.
pub fn ids(model: &Model) -> BTreeMap<&str, usize> {
    captured(model).into_iter().enumerate().map(|(i, c)| (c.name.as_str(), i)).collect()
}

/// The signature a capture file stores per command: one letter per parameter, `p` for a
/// pointer (translated on replay), `v` for a value.
fn signature(c: &Command) -> String {
    c.params.iter().map(|p| if p.ty.contains('*') { 'p' } else { 'v' }).collect()
}

/// The statement that starts recording a call to `c` in its export (parameters named
/// `{prefix}{name}`; the export's module is `gl_entry::exports`, whose `super::current` tells
/// whether a display list is being compiled); the returned guard finishes the record when
/// the export returns.
pub fn hook(c: &Command, ids: &BTreeMap<&str, usize>, prefix: &str) -> String {
    let Some(id) = ids.get(c.name.as_str()) else { return String::new() };
    let args: Vec<String> =
        c.params.iter().map(|p| format!("crate::translate::capture::Raw::raw({prefix}{})", p.name)).collect();
    format!("    let _capture = crate::translate::capture::begin({id}, || [{}], super::current::compiling_list);\n", args.join(", "))
}

/// The commands a capture records, in capture-id order.
fn captured(model: &Model) -> Vec<&Command> {
    model.commands.iter().filter(|c| is_captured(c)).collect()
}

/// `capture_commands.rs`: `COMMANDS`, the name and signature of each command by capture id.
pub fn commands(model: &Model) -> String {
    let mut s = String::from(HEADER);
    s.push_str("/// Every captured command by capture id: C name and signature (`p` pointer, `v` value).\n");
    s.push_str("pub static COMMANDS: &[(&str, &str)] = &[\n");
    for c in captured(model) {
        writeln!(s, "    (\"{}\", \"{}\"),", c.name, signature(c)).unwrap();
    }
    s.push_str("];\n");
    s
}

/// `replay_calls.rs`: `call`, which replays one call through the C exports.
pub fn calls(model: &Model) -> String {
    let mut s = String::from(HEADER);
    s.push_str(
        "/// Calls the export of command `id` with the raw arguments `a` (pointers mapped through\n\
         /// `ptr`); false for an unknown id or a wrong argument count.\n\
         ///\n/// # Safety\n/// Every pointer `ptr` gives is valid for what the command reads and writes.\n\
         #[allow(clippy::missing_safety_doc, unused_unsafe)]\n\
         pub unsafe fn call(id: usize, a: &[u64], ptr: &dyn Fn(u64) -> u64) -> bool {\n\
         \x20   use crate::gl_entry::exports as e;\n\
         \x20   use crate::translate::capture::Raw as R;\n\
         \x20   use crate::translate::capture::table::COMMANDS;\n\
         \x20   if COMMANDS.get(id).is_none_or(|c| c.1.len() != a.len()) { return false; }\n\
         \x20   match id {\n",
    );
    for (id, c) in captured(model).iter().enumerate() {
        let args: Vec<String> = c
            .params
            .iter()
            .enumerate()
            .map(|(i, p)| if p.ty.contains('*') { format!("R::from_raw(ptr(a[{i}]))") } else { format!("R::from_raw(a[{i}])") })
            .collect();
        let discard = if c.ret == "()" { "" } else { "let _ = " };
        writeln!(s, "        {id} => {{ {discard}unsafe {{ e::{}({}) }}; }}", c.name, args.join(", ")).unwrap();
    }
    s.push_str("        _ => return false,\n    }\n    true\n}\n");
    s
}
