//! `glrt.toml` and its `GLRT_<KEY>` variables, read once per process by one reader and handed
//! out in typed parts: the per-texture routing lists and `[materials]` to hash tracking
//! (`translate::classify::config`), the tables of settings such as `[pathtrace]` to the
//! renderer (`render::trace::settings` and `render::hud`, through [`Table`]) and `[memory]` to the frame budget
//! (`translate::frame_memory`). The file is `GLRT_CONFIG`, or
//! `glrt.toml` next to the program's binary:
//!
//! ```toml
//! ui = ["0x8f3a2c1d00aa11bb"]      # drawn as 2D overlay
//! sky = []                          # drawn as the sky
//! ignore = []                       # not drawn
//! translucent = []                  # raster path, blended
//! emissive = []                     # traced, emits light
//! static = []                       # traced as static even if it moves
//! dynamic = []                      # traced as dynamic (rebuilt each frame)
//! lightmap = []                     # holds baked light (wherever it multiplies a surface)
//!
//! [pathtrace]                       # keys: render::trace::settings
//! spp = 4
//!
//! [denoise]                         # keys: render::denoise::settings (GLRT_DENOISE=0|1)
//! enabled = true
//!
//! [memory]                          # keys: translate::frame_memory
//! frame_budget_mb = 256
//!
//! [display]                         # keys: render::hud::Display
//! hud = true
//!
//! [radiosity]                       # keys: render::radiosity::settings (GLRT_RADIOSITY=0|1)
//! enabled = true
//! radiosity_bounces = 3
//!
//! [fog]                             # keys: render::fog::settings (GLRT_FOG=0|1)
//! enabled = true
//!
//! [ao]                              # keys: render::ao::settings (GLRT_AO=0|1)
//! enabled = true
//!
//! [materials]                       # per texture hash, every field optional
//! "0x8f3a2c1d00aa11bb" = { roughness = 0.3, metalness = 1.0, emissive = 2.0 }
//! ```
//!
//! Texture hashes (`glrt info FILE` and the `GLRT_TRACE` call log print them) are strings
//! `"0x…"` (TOML integers stop at 2^63) or integers. Each list can be replaced by `GLRT_<KEY>`
//! (upper case: `GLRT_UI="0x1f2e 0x3c4d"`, hashes separated by commas or spaces), each key of a
//! settings table by `GLRT_<KEY>` too (`GLRT_SPP=8`; the value is read as a TOML value, and
//! as a string when it is not one: `GLRT_TONEMAP=reinhard`, `GLRT_SUN_DIRECTION="[0, 1, 0]"`).
//!
//! Problems never take the program down: a file that cannot be read or parsed, or a list that
//! is not a list of hashes, is reported once with the file's name and line and the whole file
//! is ignored (as if absent); unknown keys (at the top, in a table, in a material) and bad
//! values of settings or materials are reported once (file and line, or the variable) and the
//! default is used.

use std::collections::{HashMap, HashSet};
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

/// The routing lists, the top-level keys, in the order of [`Config::lists`].
pub const LIST_KEYS: [&str; 8] = ["ui", "sky", "ignore", "translucent", "emissive", "static", "dynamic", "lightmap"];

/// The top-level tables: `[materials]` and the settings tables read through [`Table`].
pub const TABLES: [&str; 8] = ["pathtrace", "denoise", "memory", "display", "radiosity", "fog", "ao", "materials"];

/// The keys of a `[materials]` entry.
const MATERIAL_KEYS: [&str; 3] = ["roughness", "metalness", "emissive"];

/// A `[materials]` entry: what it sets (`None`: the default, chosen by the reader).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Material {
    /// 0 (mirror) ..= 1 (rough).
    pub roughness: Option<f32>,
    /// 0 (dielectric) ..= 1 (metal).
    pub metalness: Option<f32>,
    /// Radiance scale of the texture's colour, ≥ 0.
    pub emissive: Option<f32>,
}

/// A key of a settings [`Table`]: its name in the file (and, upper case, in `GLRT_<KEY>`) and
/// how a value sets it.
pub struct Key<T> {
    /// Name in the table.
    pub name: &'static str,
    /// Sets the field from a value, or says what was expected (and leaves it unchanged).
    pub set: fn(&mut T, &toml::Value) -> Result<(), String>,
}

/// A table of settings (`[pathtrace]`): every key has a default and a `GLRT_<KEY>` variable.
pub trait Table: Default + 'static {
    /// The table's name in the file.
    const NAME: &'static str;
    /// Its keys.
    const KEYS: &'static [Key<Self>];

    /// The variable that overrides key `name`: `GLRT_<NAME>` unless the table says otherwise.
    fn variable(name: &str) -> String {
        format!("GLRT_{}", name.to_uppercase())
    }
}

/// The file as read: its name for messages, its text for lines, its parsed table.
#[derive(Clone, Debug)]
struct File {
    name: String,
    text: String,
    table: toml::Table,
}

/// `glrt.toml` and the `GLRT_*` variables as read.
#[derive(Clone, Debug, Default)]
pub struct Config {
    /// One set of texture hashes per key of [`LIST_KEYS`].
    pub lists: [HashSet<u64>; LIST_KEYS.len()],
    /// `[materials]`: texture hash → entry.
    pub materials: HashMap<u64, Material>,
    /// The file (`None`: absent or ignored), for [`Config::table`].
    file: Option<File>,
    /// The `GLRT_*` variables, for [`Config::table`].
    env: HashMap<String, String>,
}

/// A texture hash: `0x…` hexadecimal or decimal.
fn parse_hash(s: &str) -> Option<u64> {
    let s = s.trim();
    match s.strip_prefix("0x").or_else(|| s.strip_prefix("0X")) {
        Some(hex) => u64::from_str_radix(hex, 16).ok(),
        None => s.parse().ok(),
    }
}

/// The line (from 1) of byte `at` of `text`.
fn line_at(text: &str, at: usize) -> usize {
    text.as_bytes()[..at.min(text.len())].iter().filter(|&&b| b == b'\n').count() + 1
}

/// The line (from 1) of the key at `path` (table names, then the key) in the TOML `text`; 0
/// when it is not there.
fn line_of(text: &str, path: &[&str]) -> usize {
    let Ok(document) = toml::de::DeTable::parse(text) else { return 0 };
    let mut table = document.get_ref();
    for (i, name) in path.iter().enumerate() {
        let Some((key, value)) = table.iter().find(|(k, _)| k.get_ref() == name) else { return 0 };
        if i + 1 == path.len() {
            return line_at(text, key.span().start);
        }
        let Some(inner) = value.get_ref().as_table() else { return 0 };
        table = inner;
    }
    0
}

/// `value` as written in TOML, for messages.
pub fn shown(value: &toml::Value) -> String {
    let list = |items: Vec<String>| items.join(", ");
    match value {
        toml::Value::String(s) => format!("{s:?}"),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(f) => format!("{f:?}"),
        toml::Value::Boolean(b) => b.to_string(),
        toml::Value::Datetime(d) => d.to_string(),
        toml::Value::Array(a) => format!("[{}]", list(a.iter().map(shown).collect())),
        toml::Value::Table(t) => format!("{{ {} }}", list(t.iter().map(|(k, v)| format!("{k} = {}", shown(v))).collect())),
    }
}

/// A number (integer or float, finite) for which `ok` holds; the error names `expected`.
pub fn number(value: &toml::Value, ok: impl Fn(f64) -> bool, expected: &str) -> Result<f64, String> {
    let x = match value {
        toml::Value::Integer(i) => *i as f64,
        toml::Value::Float(f) => *f,
        _ => f64::NAN,
    };
    if x.is_finite() && ok(x) { Ok(x) } else { Err(format!("expected {expected}, found {}", shown(value))) }
}

/// A number in `range`.
pub fn number_in(value: &toml::Value, range: RangeInclusive<f64>) -> Result<f64, String> {
    number(value, |x| range.contains(&x), &format!("a number in {}..={}", range.start(), range.end()))
}

/// An integer in `range`.
pub fn integer_in(value: &toml::Value, range: RangeInclusive<i64>) -> Result<i64, String> {
    match value {
        toml::Value::Integer(i) if range.contains(i) => Ok(*i),
        _ => Err(format!("expected an integer in {}..={}, found {}", range.start(), range.end(), shown(value))),
    }
}

/// A switch: `true`/`false`, or `1`/`0` (what `GLRT_HUD=1` reads as).
pub fn switch(value: &toml::Value) -> Result<bool, String> {
    match value {
        toml::Value::Boolean(b) => Ok(*b),
        toml::Value::Integer(i @ (0 | 1)) => Ok(*i == 1),
        _ => Err(format!("expected true, false, 1 or 0, found {}", shown(value))),
    }
}

/// A direction `[x, y, z]`, not zero, normalized.
pub fn direction(value: &toml::Value) -> Result<glam::Vec3, String> {
    let expected = || format!("expected a direction [x, y, z], not zero, found {}", shown(value));
    let items = value.as_array().filter(|a| a.len() == 3).ok_or_else(expected)?;
    let mut v = [0.0; 3];
    for (c, item) in v.iter_mut().zip(items) {
        *c = number(item, |_| true, "a number").map_err(|_| expected())? as f32;
    }
    glam::Vec3::from(v).try_normalize().ok_or_else(expected)
}

/// One of `names` (a string), as its index.
pub fn one_of(value: &toml::Value, names: &[&str]) -> Result<usize, String> {
    value
        .as_str()
        .and_then(|s| names.iter().position(|n| *n == s))
        .ok_or_else(|| format!("expected one of \"{}\", found {}", names.join("\", \""), shown(value)))
}

impl Config {
    /// Parses the text of a file named `file`: the configuration and the warnings (unknown
    /// keys, bad materials), or the error that makes the whole file ignored (it cannot be
    /// parsed, or a list is not a list of texture hashes), naming the file and line.
    pub fn parse(text: &str, file: &str) -> Result<(Config, Vec<String>), String> {
        let mut table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            let line = e.span().map_or(0, |s| text[..s.start.min(text.len())].lines().count().max(1));
            format!("{file}:{line}: {}", e.message())
        })?;
        let mut config = Config { file: Some(File { name: file.to_owned(), text: text.to_owned(), table: toml::Table::new() }), ..Config::default() };
        let mut warnings = Vec::new();
        for (key, value) in &table {
            let at = || format!("{file}:{}", line_of(text, &[key]));
            if let Some(k) = LIST_KEYS.iter().position(|&known| known == key) {
                let bad = |what: &str| format!("{}: {key}: {what}", at());
                let items = value.as_array().ok_or_else(|| bad("expected a list of texture hashes"))?;
                for item in items {
                    let hash = match item {
                        toml::Value::String(s) => parse_hash(s),
                        toml::Value::Integer(i) => u64::try_from(*i).ok(),
                        _ => None,
                    };
                    config.lists[k].insert(hash.ok_or_else(|| bad(&format!("{item:?} is not a texture hash (\"0x…\" or a number)")))?);
                }
            } else if !TABLES.iter().any(|t| t == key) {
                let known = [&LIST_KEYS[..], &TABLES[..]].concat().join(", ");
                warnings.push(format!("{}: unknown key '{key}' (known: {known})", at()));
            } else if !value.is_table() {
                warnings.push(format!("{}: {key}: expected a table ([{key}]), found {}; the defaults are used", at(), shown(value)));
            }
        }
        table.retain(|key, value| TABLES.contains(&key) && value.is_table());
        if let Some(toml::Value::Table(materials)) = table.get("materials") {
            config.materials = config.read_materials(materials, &mut warnings);
        }
        if let Some(f) = &mut config.file {
            f.table = table;
        }
        Ok((config, warnings))
    }

    /// The entries of `[materials]`; problems go to `warnings` (the entry or field is left out).
    fn read_materials(&self, table: &toml::Table, warnings: &mut Vec<String>) -> HashMap<u64, Material> {
        let mut materials = HashMap::new();
        for (hash, entry) in table {
            let at = |path: &[&str]| {
                let line = self.line(&[&["materials", hash.as_str()][..], path].concat());
                format!("{}:{line}: materials.\"{hash}\"", self.file_name())
            };
            let Some(h) = parse_hash(hash) else {
                warnings.push(format!("{}: not a texture hash (\"0x…\" or a number); the entry is ignored", at(&[])));
                continue;
            };
            let Some(fields) = entry.as_table() else {
                warnings.push(format!("{}: expected a table such as {{ roughness = 0.3 }}, found {}; the entry is ignored", at(&[]), shown(entry)));
                continue;
            };
            let mut m = Material::default();
            for (key, value) in fields {
                let checked = match key.as_str() {
                    "roughness" => number_in(value, 0.0..=1.0).map(|x| m.roughness = Some(x as f32)),
                    "metalness" => number_in(value, 0.0..=1.0).map(|x| m.metalness = Some(x as f32)),
                    "emissive" => number(value, |x| x >= 0.0, "a number ≥ 0").map(|x| m.emissive = Some(x as f32)),
                    _ => Err(format!("unknown key (known: {})", MATERIAL_KEYS.join(", "))),
                };
                if let Err(e) = checked {
                    warnings.push(format!("{}.{key}: {e}; the default is used", at(&[key])));
                }
            }
            materials.insert(h, m);
        }
        materials
    }

    /// Keeps the `GLRT_*` variables of `vars` (for [`Config::table`]) and replaces the lists
    /// whose `GLRT_<KEY>` is among them; the error names the first bad variable (the lists
    /// before it are replaced, it and the later ones are not).
    pub fn apply_env(&mut self, vars: impl IntoIterator<Item = (String, String)>) -> Result<(), String> {
        self.env = vars.into_iter().filter(|(name, _)| name.starts_with("GLRT_")).collect();
        for (k, key) in LIST_KEYS.iter().enumerate() {
            let name = format!("GLRT_{}", key.to_uppercase());
            let Some(value) = self.env.get(&name) else { continue };
            let hashes = value.split([',', ' ']).filter(|s| !s.trim().is_empty());
            self.lists[k] = hashes.map(|s| parse_hash(s).ok_or(format!("{name}: '{s}' is not a texture hash"))).collect::<Result<_, _>>()?;
        }
        Ok(())
    }

    /// The settings table `T`: its defaults, replaced by the file's values, then by the
    /// variables'; and the problems (unknown keys, bad values: the value is not used).
    pub fn table<T: Table>(&self) -> (T, Vec<String>) {
        let mut t = T::default();
        let mut problems = Vec::new();
        let known = || T::KEYS.iter().map(|k| k.name).collect::<Vec<_>>().join(", ");
        if let Some(toml::Value::Table(table)) = self.file.as_ref().and_then(|f| f.table.get(T::NAME)) {
            for (name, value) in table {
                let at = format!("{}:{}: {}.{name}", self.file_name(), self.line(&[T::NAME, name]), T::NAME);
                match T::KEYS.iter().find(|k| k.name == name) {
                    Some(key) => {
                        if let Err(e) = (key.set)(&mut t, value) {
                            problems.push(format!("{at}: {e}; the default is used"));
                        }
                    }
                    None => problems.push(format!("{at}: unknown key (known: {})", known())),
                }
            }
        }
        for key in T::KEYS {
            let name = T::variable(key.name);
            let Some(text) = self.env.get(&name) else { continue };
            let value = text.parse::<toml::Value>().unwrap_or_else(|_| toml::Value::String(text.clone()));
            if let Err(e) = (key.set)(&mut t, &value) {
                problems.push(format!("{name}: {e}; the variable is ignored"));
            }
        }
        (t, problems)
    }

    /// The file's name for messages.
    fn file_name(&self) -> &str {
        self.file.as_ref().map_or("", |f| &f.name)
    }

    /// The line of the key at `path` in the file (see [`line_of`]).
    fn line(&self, path: &[&str]) -> usize {
        self.file.as_ref().map_or(0, |f| line_of(&f.text, path))
    }

    /// The configuration file: `GLRT_CONFIG`, else `glrt.toml` beside the program.
    fn path() -> Option<PathBuf> {
        if let Some(p) = std::env::var_os("GLRT_CONFIG").filter(|p| !p.is_empty()) {
            return Some(p.into());
        }
        let exe = std::env::current_exe().ok()?;
        Some(exe.parent()?.join("glrt.toml")).filter(|p| p.exists())
    }

    /// The configuration of this process, read at the first call (every context and renderer
    /// shares it, so problems are reported once).
    pub fn of_process() -> &'static Config {
        static CONFIG: std::sync::OnceLock<Config> = std::sync::OnceLock::new();
        CONFIG.get_or_init(Config::load)
    }

    /// Reads the configuration (file, then environment); problems are reported on standard
    /// error and leave the affected part at its default.
    fn load() -> Config {
        let mut config = Config::default();
        if let Some(path) = Config::path() {
            match Config::read(&path) {
                Ok((c, warnings)) => {
                    config = c;
                    warn(&warnings);
                }
                Err(e) => eprintln!("glrt: {e}; the configuration file is ignored"),
            }
        }
        if let Err(e) = config.apply_env(std::env::vars()) {
            eprintln!("glrt: {e}; the variable is ignored");
        }
        config
    }

    fn read(path: &Path) -> Result<(Config, Vec<String>), String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        Config::parse(&text, &path.display().to_string())
    }
}

/// Reports `warnings` on standard error.
pub fn warn(warnings: &[String]) {
    warnings.iter().for_each(|w| eprintln!("glrt: warning: {w}"));
}

/// The variable of key `name` of a table that one variable switches on and off: `GLRT_<TABLE>`
/// for `enabled`, `GLRT_<TABLE>_<NAME>` for the others (`[fog]`: `GLRT_FOG`,
/// `GLRT_FOG_DENSITY`).
pub fn switched_variable(table: &str, name: &str) -> String {
    match name {
        "enabled" => format!("GLRT_{}", table.to_uppercase()),
        other => format!("GLRT_{}_{}", table.to_uppercase(), other.to_uppercase()),
    }
}

/// Table `T` of this process's configuration ([`Config::of_process`]), read into `cell` (the
/// caller's, one per table) at the first call; problems are reported then ([`warn`]).
pub fn process_table<T: Table + Copy + Sync + Send>(cell: &'static std::sync::OnceLock<T>) -> T {
    *cell.get_or_init(|| {
        let (table, problems) = Config::of_process().table::<T>();
        warn(&problems);
        table
    })
}

/// The user's cache directory: `$XDG_CACHE_HOME`, else `~/.cache`, else the temporary
/// directory (glrt keeps its files under `glrt/` there).
pub fn cache_dir() -> PathBuf {
    std::env::var_os("XDG_CACHE_HOME")
        .filter(|d| !d.is_empty())
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").filter(|d| !d.is_empty()).map(|home| Path::new(&home).join(".cache")))
        .unwrap_or_else(std::env::temp_dir)
}

/// Tests of settings tables: table `T` of a file holding `[T::NAME]` with `body`, with the
/// variables `env`, and the problems reported (the file itself must parse without warnings).
#[cfg(test)]
pub(crate) fn read_table<T: Table>(body: &str, env: &[(&str, &str)]) -> (T, Vec<String>) {
    let (mut c, warnings) = Config::parse(&format!("[{}]\n{body}", T::NAME), "t.toml").unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    c.apply_env(env.iter().map(|(k, v)| (k.to_string(), v.to_string()))).unwrap();
    c.table::<T>()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
        pairs.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect()
    }

    #[test]
    fn parses_lists_and_reports_unknown_keys() {
        let text = "ui = [\"0x10\", 32]\n\nsky = [\"0XfF\"]\nshadows = true\n";
        let (c, warnings) = Config::parse(text, "g.toml").unwrap();
        assert_eq!(c.lists[0], HashSet::from([16, 32]));
        assert_eq!(c.lists[1], HashSet::from([255]));
        assert_eq!(warnings.len(), 1);
        assert!(warnings[0].starts_with("g.toml:4: unknown key 'shadows' (known: ui, sky, ignore, translucent, emissive, static, dynamic, lightmap, pathtrace, denoise, memory, display, radiosity, fog, ao, materials)"), "{}", warnings[0]);
    }

    #[test]
    fn bad_files_name_file_and_line() {
        let e = Config::parse("ui = [\"0x10\"]\nsky = [\"0xZZ\"]\n", "a/glrt.toml").unwrap_err();
        assert!(e.starts_with("a/glrt.toml:2: sky: "), "{e}");
        let e = Config::parse("ui = [\"0x10\"]\n\ndynamic = 3\n", "x.toml").unwrap_err();
        assert!(e.starts_with("x.toml:3: dynamic: expected a list"), "{e}");
        let e = Config::parse("ui = [\n\nsky = ]\n", "y.toml").unwrap_err();
        assert!(e.starts_with("y.toml:3: "), "{e}");
        assert!(Config::parse("emissive = [-5]", "z.toml").is_err(), "negative hashes are refused");
        let (_, w) = Config::parse("pathtrace = 3\n", "t.toml").unwrap();
        assert_eq!(w, ["t.toml:1: pathtrace: expected a table ([pathtrace]), found 3; the defaults are used"]);
    }

    #[test]
    fn environment_replaces_a_key() {
        let (mut c, _) = Config::parse("ui = [\"0x10\"]\nsky=[1]", "g.toml").unwrap();
        c.apply_env(env(&[("GLRT_UI", "0x20, 0x30"), ("HOME", "/")])).unwrap();
        assert_eq!(c.lists[0], HashSet::from([0x20, 0x30]));
        assert_eq!(c.lists[1], HashSet::from([1]));
        assert!(!c.env.contains_key("HOME"), "only GLRT_* variables are kept");
        assert!(c.apply_env(env(&[("GLRT_SKY", "nope")])).unwrap_err().starts_with("GLRT_SKY: 'nope'"));
    }

    #[test]
    fn materials_are_read_with_lines_and_defaults_left_open() {
        let text = "ui = []\n[materials]\n\"0x10\" = { roughness = 0.25, metalness = 1, emissive = 2.5 }\n\"0x20\" = { emissive = -1, shine = 3 }\n\"0x30\" = { roughness = 1.5 }\n\"zz\" = { roughness = 0.1 }\n\"0x40\" = 7\n";
        let (c, w) = Config::parse(text, "m.toml").unwrap();
        assert_eq!(c.materials.len(), 3);
        assert_eq!(c.materials[&0x10], Material { roughness: Some(0.25), metalness: Some(1.0), emissive: Some(2.5) });
        assert_eq!(c.materials[&0x20], Material::default(), "bad and unknown fields are left to the defaults");
        assert_eq!(c.materials[&0x30], Material::default());
        assert_eq!(w.len(), 5, "{w:#?}");
        assert!(w.contains(&"m.toml:4: materials.\"0x20\".emissive: expected a number ≥ 0, found -1; the default is used".to_owned()), "{w:#?}");
        assert!(w.contains(&"m.toml:4: materials.\"0x20\".shine: unknown key (known: roughness, metalness, emissive); the default is used".to_owned()), "{w:#?}");
        assert!(w.contains(&"m.toml:5: materials.\"0x30\".roughness: expected a number in 0..=1, found 1.5; the default is used".to_owned()), "{w:#?}");
        assert!(w.iter().any(|w| w.starts_with("m.toml:6: materials.\"zz\": not a texture hash")), "{w:#?}");
        assert!(w.iter().any(|w| w.starts_with("m.toml:7: materials.\"0x40\": expected a table")), "{w:#?}");
    }

    /// A settings table for the tests of [`Config::table`].
    #[derive(Debug, Default, PartialEq)]
    struct Knobs {
        count: i64,
        mode: usize,
    }

    impl Table for Knobs {
        const NAME: &'static str = "pathtrace";
        const KEYS: &'static [Key<Knobs>] = &[
            Key { name: "count", set: |k, v| integer_in(v, 1..=8).map(|x| k.count = x) },
            Key { name: "mode", set: |k, v| one_of(v, &["a", "b"]).map(|i| k.mode = i) },
        ];
    }

    #[test]
    fn tables_take_file_then_variables_and_keep_defaults_on_problems() {
        let text = "[pathtrace]\ncount = 4\nmode = \"c\"\nspeed = 2\n";
        let (mut c, w) = Config::parse(text, "k.toml").unwrap();
        assert!(w.is_empty(), "{w:?}");
        let (k, problems) = c.table::<Knobs>();
        assert_eq!(k, Knobs { count: 4, mode: 0 });
        assert_eq!(problems, [
            "k.toml:3: pathtrace.mode: expected one of \"a\", \"b\", found \"c\"; the default is used",
            "k.toml:4: pathtrace.speed: unknown key (known: count, mode)",
        ]);
        c.apply_env(env(&[("GLRT_MODE", "b"), ("GLRT_COUNT", "9")])).unwrap();
        let (k, problems) = c.table::<Knobs>();
        assert_eq!(k, Knobs { count: 4, mode: 1 }, "a bad variable leaves the file's value");
        assert_eq!(problems[2], "GLRT_COUNT: expected an integer in 1..=8, found 9; the variable is ignored");
        c.apply_env(env(&[("GLRT_COUNT", "2")])).unwrap();
        assert_eq!(c.table::<Knobs>().0, Knobs { count: 2, mode: 0 });
        assert_eq!(Config::default().table::<Knobs>(), (Knobs::default(), vec![]), "no file, no variables: defaults");
    }
}

