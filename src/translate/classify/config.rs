//! `glrt.toml`: per-texture overrides of the routing rules. The file is `GLRT_CONFIG`, or
//! `glrt.toml` next to the program's binary; each key can be replaced by the environment
//! variable `GLRT_<KEY>` (upper case: `GLRT_UI="0x1f2e 0x3c4d"`, hashes separated by commas or
//! spaces). Every key is a list of texture hashes (`glrt info FILE` and the `GLRT_TRACE` call
//! log print them), written as strings `"0x…"` (TOML integers stop at 2^63) or integers:
//!
//! ```toml
//! ui = ["0x8f3a2c1d00aa11bb"]      # drawn as 2D overlay
//! sky = []                          # drawn as the sky
//! ignore = []                       # not drawn
//! translucent = []                  # raster path, blended
//! emissive = []                     # traced, emits light
//! static = []                       # traced as static even if it moves
//! dynamic = []                      # traced as dynamic (rebuilt each frame)
//! ```
//!
//! Unknown keys are reported once (a warning naming the file and line); a file that cannot be
//! read or parsed is reported once with its name and line and the configuration stays empty:
//! a bad file never takes the program down.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use super::routing::Tags;

/// The keys, in the order of [`Config::lists`].
pub const KEYS: [&str; 7] = ["ui", "sky", "ignore", "translucent", "emissive", "static", "dynamic"];

/// The texture hash lists.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Config {
    /// One set of texture hashes per key of [`KEYS`].
    pub lists: [HashSet<u64>; 7],
}

/// The line (from 1) of `key = ...` in `text`, for messages.
fn line_of(text: &str, key: &str) -> usize {
    text.lines()
        .position(|l| l.trim_start().strip_prefix(key).is_some_and(|r| r.trim_start().starts_with('=')))
        .map_or(0, |i| i + 1)
}

/// A texture hash: `0x…` hexadecimal or decimal.
fn parse_hash(s: &str) -> Option<u64> {
    let s = s.trim();
    match s.strip_prefix("0x").or_else(|| s.strip_prefix("0X")) {
        Some(hex) => u64::from_str_radix(hex, 16).ok(),
        None => s.parse().ok(),
    }
}

impl Config {
    /// Parses the text of a file named `file`: the configuration and the warnings (unknown
    /// keys), or the error, naming the file and line.
    pub fn parse(text: &str, file: &str) -> Result<(Config, Vec<String>), String> {
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            let line = e.span().map_or(0, |s| text[..s.start.min(text.len())].lines().count().max(1));
            format!("{file}:{line}: {}", e.message())
        })?;
        let mut config = Config::default();
        let mut warnings = Vec::new();
        for (key, value) in &table {
            let Some(k) = KEYS.iter().position(|&known| known == key) else {
                warnings.push(format!("{file}:{}: unknown key '{key}' (known: {})", line_of(text, key), KEYS.join(", ")));
                continue;
            };
            let bad = |what: &str| format!("{file}:{}: {key}: {what}", line_of(text, key));
            let items = value.as_array().ok_or_else(|| bad("expected a list of texture hashes"))?;
            for item in items {
                let hash = match item {
                    toml::Value::String(s) => parse_hash(s),
                    toml::Value::Integer(i) => u64::try_from(*i).ok(),
                    _ => None,
                };
                config.lists[k].insert(hash.ok_or_else(|| bad(&format!("{item:?} is not a texture hash (\"0x…\" or a number)")))?);
            }
        }
        Ok((config, warnings))
    }

    /// Replaces the lists whose `GLRT_<KEY>` variable `var` returns.
    pub fn apply_env(&mut self, var: impl Fn(&str) -> Option<String>) -> Result<(), String> {
        for (k, key) in KEYS.iter().enumerate() {
            let name = format!("GLRT_{}", key.to_uppercase());
            let Some(value) = var(&name) else { continue };
            let hashes = value.split([',', ' ']).filter(|s| !s.trim().is_empty());
            self.lists[k] = hashes.map(|s| parse_hash(s).ok_or(format!("{name}: '{s}' is not a texture hash"))).collect::<Result<_, _>>()?;
        }
        Ok(())
    }

    /// The configuration file: `GLRT_CONFIG`, else `glrt.toml` beside the program.
    fn path() -> Option<PathBuf> {
        if let Some(p) = std::env::var_os("GLRT_CONFIG").filter(|p| !p.is_empty()) {
            return Some(p.into());
        }
        let exe = std::env::current_exe().ok()?;
        Some(exe.parent()?.join("glrt.toml")).filter(|p| p.exists())
    }

    /// The configuration of this process, read at the first call (every context shares it,
    /// so problems are reported once).
    pub fn of_process() -> Config {
        static CONFIG: std::sync::OnceLock<Config> = std::sync::OnceLock::new();
        CONFIG.get_or_init(Config::load).clone()
    }

    /// Reads the configuration (file, then environment); problems are reported on standard
    /// error and leave the affected part empty.
    fn load() -> Config {
        let mut config = Config::default();
        if let Some(path) = Config::path() {
            match Config::read(&path) {
                Ok((c, warnings)) => {
                    config = c;
                    warnings.iter().for_each(|w| eprintln!("glrt: warning: {w}"));
                }
                Err(e) => eprintln!("glrt: {e}; the configuration file is ignored"),
            }
        }
        if let Err(e) = config.apply_env(|name| std::env::var(name).ok()) {
            eprintln!("glrt: {e}; the variable is ignored");
        }
        config
    }

    fn read(path: &Path) -> Result<(Config, Vec<String>), String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        Config::parse(&text, &path.display().to_string())
    }

    /// Whether any texture is tagged (texture hashes are only needed then, or for the log).
    pub fn is_empty(&self) -> bool {
        self.lists.iter().all(HashSet::is_empty)
    }

    /// The tags of a draw whose textures have the hashes `hashes`.
    pub fn tags(&self, hashes: impl Iterator<Item = u64> + Clone) -> Tags {
        if self.is_empty() {
            return Tags::default();
        }
        let has = |k: usize| hashes.clone().any(|h| self.lists[k].contains(&h));
        Tags { ui: has(0), sky: has(1), ignore: has(2), translucent: has(3), emissive: has(4), static_: has(5), dynamic: has(6) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_lists_and_reports_unknown_keys() {
        let text = "ui = [\"0x10\", 32]\n\nsky = [\"0XfF\"]\nshadows = true\n";
        let (c, warnings) = Config::parse(text, "g.toml").unwrap();
        assert_eq!(c.lists[0], HashSet::from([16, 32]));
        assert_eq!(c.lists[1], HashSet::from([255]));
        assert_eq!(warnings.len(), 1);
        assert!(warnings[0].starts_with("g.toml:4: unknown key 'shadows'"), "{}", warnings[0]);
        let tags = c.tags([1, 32].into_iter());
        assert!(tags.ui && !tags.sky);
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
    }

    #[test]
    fn environment_replaces_a_key() {
        let (mut c, _) = Config::parse("ui = [\"0x10\"]\nsky=[1]", "g.toml").unwrap();
        c.apply_env(|name| (name == "GLRT_UI").then(|| "0x20, 0x30".to_owned())).unwrap();
        assert_eq!(c.lists[0], HashSet::from([0x20, 0x30]));
        assert_eq!(c.lists[1], HashSet::from([1]));
        assert!(c.apply_env(|name| (name == "GLRT_SKY").then(|| "nope".to_owned())).unwrap_err().starts_with("GLRT_SKY: 'nope'"));
    }
}
