//! The model the emitters read: every exported command with its signature and how it is served.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use gl_generator::{Api, Cmd, Fallbacks, Profile, Registry};

use crate::overlay::{self, Family};
use crate::scan;

/// A parameter: Rust name and Rust type (as `gl_generator` spells it, `types::GLenum`).
pub struct Param {
    pub name: String,
    pub ty: String,
    /// The gl.xml enum group (`group="PrimitiveType"`), which tells how the trace prints it.
    pub group: Option<String>,
}

/// How an exported command is served.
#[derive(Clone)]
pub enum Route {
    /// `translate` implements it under its own name.
    Method,
    /// A variant of an attribute family, converted to the family's canonical command.
    Family { family: &'static Family, count: usize, suffix: String, vector: bool },
    /// `glRect{sifd}[v]`, converted to `glRectf`.
    Rect { suffix: String, vector: bool },
    /// An alias (`glActiveTextureARB`) of a command that is served.
    Alias(String),
    /// Exported by hand in `gl_entry` (module path below `gl_entry`: `glx::exports::swap`).
    Hand(String),
    /// Not implemented: raises `GL_INVALID_OPERATION` (GLX: returns zero) and logs once.
    Missing,
}

/// One exported C function.
pub struct Command {
    /// C name, such as `glVertex3f`.
    pub name: String,
    pub params: Vec<Param>,
    /// Rust return type, `()` when void.
    pub ret: String,
    pub route: Route,
    /// Part of the OpenGL 1.0–1.5 + implemented-extension surface (with the OpenGL 2.0
    /// commands implemented so far).
    pub in_surface: bool,
    pub is_glx: bool,
}

/// Everything the emitters need.
pub struct Model {
    /// Every exported command, sorted by name.
    pub commands: Vec<Command>,
    /// Every `GL_*` constant: name, Rust type, value expression.
    pub enums: Vec<(String, String, String)>,
    /// Commands with a `compile_` companion method in `translate`.
    pub compile_methods: BTreeSet<String>,
    /// gl.xml enum groups by name: the names of their members.
    pub groups: BTreeMap<String, Vec<String>>,
}

impl Model {
    pub fn load() -> Model {
        let gl_xml = khronos_api::GL_XML;
        let all_gl_exts = extension_names(std::str::from_utf8(gl_xml).unwrap(), "gl");
        let all_glx_exts = extension_names(std::str::from_utf8(khronos_api::GLX_XML).unwrap(), "glx");
        let surface = Registry::new(
            Api::Gl,
            (2, 0),
            Profile::Compatibility,
            Fallbacks::None,
            overlay::EXTENSIONS,
        );
        let all = Registry::new(Api::Gl, (4, 6), Profile::Compatibility, Fallbacks::None, refs(&all_gl_exts));
        let gles1_exts = extension_names(std::str::from_utf8(gl_xml).unwrap(), "gles1");
        let gles2_exts = extension_names(std::str::from_utf8(gl_xml).unwrap(), "gles2");
        let gles1 = Registry::new(Api::Gles1, (1, 0), Profile::Core, Fallbacks::None, refs(&gles1_exts));
        let gles2 = Registry::new(Api::Gles2, (3, 2), Profile::Core, Fallbacks::None, refs(&gles2_exts));
        let glx = Registry::new(Api::Glx, (1, 4), Profile::Core, Fallbacks::None, refs(&all_glx_exts));

        let translate = Path::new("src/translate");
        let methods = scan::identifiers_after(translate, "fn gl", "gl");
        let compile_methods = scan::identifiers_after(translate, "fn compile_gl", "gl");
        let hand: BTreeMap<String, String> =
            scan::hand_exports(Path::new("src/gl_entry")).into_iter().map(|(m, n)| (n, m)).collect();

        // OpenGL 2.0 arrives command by command while `GL_VERSION` is still 1.5: a 2.0
        // command joins the surface once `translate` implements it.
        let gl_2_0 = Registry::new(Api::Gl, (2, 0), Profile::Compatibility, Fallbacks::None, [] as [&str; 0]);
        let mut surface_names: BTreeSet<String> =
            surface.cmds.iter().map(|c| format!("gl{}", c.proto.ident)).collect();
        surface_names.extend(gl_2_0.cmds.iter().map(|c| format!("gl{}", c.proto.ident)).filter(|n| methods.contains(n)));
        let glvnd: BTreeSet<String> = include_str!("../src/gl_entry/glvnd_libgl_exports.txt")
            .lines()
            .map(str::to_owned)
            .collect();

        let mut signatures: BTreeMap<String, (&Cmd, bool)> = BTreeMap::new();
        for cmd in gles1.cmds.iter().chain(&gles2.cmds).chain(&all.cmds) {
            signatures.insert(format!("gl{}", cmd.proto.ident), (cmd, false));
        }
        for cmd in &glx.cmds {
            signatures.insert(format!("glX{}", cmd.proto.ident), (cmd, true));
        }

        let mut names: BTreeSet<String> = surface_names.clone();
        names.extend(glvnd.iter().cloned());
        names.extend(hand.keys().cloned());

        let mut commands = Vec::new();
        for (name, params, ret) in overlay::EXTRA_COMMANDS {
            commands.push(Command {
                name: (*name).to_owned(),
                params: params.iter().map(|(n, t)| Param { name: (*n).to_owned(), ty: (*t).to_owned(), group: None }).collect(),
                ret: (*ret).to_owned(),
                route: if methods.contains(*name) { Route::Method } else { Route::Missing },
                in_surface: true,
                is_glx: false,
            });
        }
        for name in names {
            if let Some(module) = hand.get(&name) {
                commands.push(Command {
                    name: name.clone(),
                    params: Vec::new(),
                    ret: String::new(),
                    route: Route::Hand(module.clone()),
                    in_surface: surface_names.contains(&name),
                    is_glx: name.starts_with("glX"),
                });
                continue;
            }
            let Some(&(cmd, is_glx)) = signatures.get(&name) else {
                // Newer than the registry khronos_api ships (vendor extensions of 2020 on):
                // exported without parameters, returning zero in the integer register.
                commands.push(Command {
                    name: name.clone(),
                    params: Vec::new(),
                    ret: "usize".to_owned(),
                    route: Route::Missing,
                    in_surface: false,
                    is_glx: name.starts_with("glX"),
                });
                continue;
            };
            let in_surface = surface_names.contains(&name);
            let route = if !in_surface || is_glx {
                Route::Missing
            } else {
                route_of(&name, cmd, &methods, &surface_names)
            };
            commands.push(Command {
                params: cmd
                    .params
                    .iter()
                    .map(|p| Param { name: p.ident.clone(), ty: rust_type(&p.ty), group: p.group.clone() })
                    .collect(),
                ret: cmd.proto.ty.to_string(),
                name,
                route,
                in_surface,
                is_glx,
            });
        }
        commands.sort_by(|a, b| a.name.cmp(&b.name));
        resolve_aliases(&mut commands);

        let mut seen = BTreeSet::new();
        let mut enums = Vec::new();
        for e in surface.enums.iter().chain(all.enums.iter()) {
            if seen.insert(e.ident.clone()) {
                let ty = if e.ty == "&'static str" { e.ty.to_string() } else { format!("types::{}", e.ty) };
                let value = if e.value.starts_with('-') && ty.starts_with("types::") {
                    format!("({}i64) as {ty}", e.value)
                } else if e.cast {
                    format!("{} as {ty}", e.value)
                } else {
                    e.value.clone()
                };
                // gl_generator writes `GL_2_BYTES` as `_2_BYTES`.
                let ident = e.ident.strip_prefix('_').filter(|r| r.starts_with(|c: char| c.is_ascii_digit()));
                enums.push((format!("GL_{}", ident.unwrap_or(&e.ident)), ty, value));
            }
        }
        let groups = all.groups.values().map(|g| (g.ident.clone(), g.enums.clone())).collect();
        Model { commands, enums, compile_methods, groups }
    }
}

/// Repairs the few parameter types `gl_generator` spells in a way Rust does not accept:
/// C arrays (`[Gluint; 2]`, which decay to pointers) and a stray `const`.
fn rust_type(ty: &str) -> String {
    if let Some(inner) = ty.strip_prefix('[') {
        let elem = inner.split(';').next().unwrap_or("c_void").trim();
        let elem = if elem == "Gluint" { "types::GLuint" } else { elem };
        return format!("*const {elem}");
    }
    ty.strip_prefix("const ").unwrap_or(ty).to_owned()
}

fn refs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

/// Names of the extensions of a registry file that support `api`
/// (`<extension name="..." supported="gl|glcore">`).
fn extension_names(xml: &str, api: &str) -> Vec<String> {
    xml.split("<extension name=\"")
        .skip(1)
        .filter_map(|s| {
            let name = s.split('"').next()?;
            let tag = s.split('>').next()?;
            let supported = tag.split("supported=\"").nth(1)?.split('"').next()?;
            supported.split('|').any(|a| a == api).then(|| name.to_owned())
        })
        .collect()
}

fn route_of(name: &str, cmd: &Cmd, methods: &BTreeSet<String>, surface: &BTreeSet<String>) -> Route {
    if methods.contains(name) {
        return Route::Method;
    }
    let short = &name[2..];
    for family in overlay::FAMILIES {
        if let Some((count, suffix, vector)) = parse_variant(short, family.base, family.components)
            && format!("gl{}", family.canonical) != name {
                return Route::Family { family, count, suffix, vector };
            }
    }
    if let Some((_, suffix, vector)) = parse_variant(short, "Rect", 4)
        && name != "glRectf" {
            return Route::Rect { suffix, vector };
        }
    let extra = overlay::EXTRA_ALIASES.iter().find(|(n, _)| *n == short).map(|&(_, target)| target);
    match cmd.alias.as_deref().or(extra) {
        Some(alias) if surface.contains(&format!("gl{alias}")) => Route::Alias(format!("gl{alias}")),
        _ => Route::Missing,
    }
}

/// Parses `{base}{N}{type}[v]`; returns the component count, the type suffix and whether it
/// takes a pointer.
fn parse_variant(short: &str, base: &str, default_count: usize) -> Option<(usize, String, bool)> {
    let rest = short.strip_prefix(base)?;
    let (count, rest) = match rest.chars().next()? {
        d @ '1'..='4' => (d.to_digit(10)? as usize, &rest[1..]),
        _ => (default_count, rest),
    };
    let (rest, vector) = match rest.strip_suffix('v') {
        Some(r) => (r, true),
        None => (rest, false),
    };
    ["ub", "us", "ui", "b", "s", "i", "f", "d"]
        .contains(&rest)
        .then(|| (count, rest.to_owned(), vector))
}

/// Routes that lean on another command (family variants, `glRect` variants, then aliases)
/// whose target is not served become missing themselves.
fn resolve_aliases(commands: &mut [Command]) {
    // An alias of a family or glRect variant (`glMultiTexCoord2fARB`) is that variant itself.
    let variants: BTreeMap<String, Route> = commands
        .iter()
        .filter(|c| matches!(c.route, Route::Family { .. } | Route::Rect { .. }))
        .map(|c| (c.name.clone(), c.route.clone()))
        .collect();
    for c in commands.iter_mut() {
        if let Route::Alias(target) = &c.route
            && let Some(route) = variants.get(target) {
                c.route = route.clone();
            }
    }
    for pass_aliases in [false, true] {
        let served: BTreeSet<String> = commands
            .iter()
            .filter(|c| !matches!(c.route, Route::Missing | Route::Alias(_)))
            .map(|c| c.name.clone())
            .collect();
        for c in commands.iter_mut() {
            let target = match (&c.route, pass_aliases) {
                (Route::Alias(target), true) => target.clone(),
                (Route::Family { family, .. }, false) => format!("gl{}", family.canonical),
                (Route::Rect { .. }, false) => "glRectf".to_owned(),
                _ => continue,
            };
            if !served.contains(&target) {
                c.route = Route::Missing;
            }
        }
    }
}
