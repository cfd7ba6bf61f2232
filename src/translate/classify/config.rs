//! The per-texture part of `glrt.toml` that hash tracking uses: the routing lists (`ui`, `sky`,
//! `ignore`, `translucent`, `emissive`, `static`, `dynamic`) become a draw's [`Tags`], and
//! `[materials]` with the `emissive` list its [`MaterialOverride`]. The file and its
//! variables are read by [`crate::config`] (keys, syntax, messages).

use std::collections::{HashMap, HashSet};

use super::routing::Tags;
use crate::config::{LIST_KEYS, Material};
use crate::frame::class::MaterialOverride;

/// The texture hash lists and materials.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Config {
    /// One set of texture hashes per key of [`LIST_KEYS`].
    pub lists: [HashSet<u64>; LIST_KEYS.len()],
    /// `[materials]`: texture hash → entry.
    pub materials: HashMap<u64, Material>,
}

impl From<&crate::config::Config> for Config {
    fn from(c: &crate::config::Config) -> Config {
        Config { lists: c.lists.clone(), materials: c.materials.clone() }
    }
}

impl Config {
    /// The configuration of this process (read once, [`crate::config::Config::of_process`]).
    pub fn of_process() -> Config {
        Config::from(crate::config::Config::of_process())
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
        Tags { ui: has(0), sky: has(1), ignore: has(2), translucent: has(3), emissive: has(4), static_: has(5), dynamic: has(6), lightmap: has(7) }
    }

    /// Whether the texture of hash `hash` is tagged `lightmap`: it holds baked light wherever
    /// it multiplies a surface, whatever its texel density (`super::lighting`).
    pub fn is_lightmap(&self, hash: u64) -> bool {
        self.lists[7].contains(&hash)
    }

    /// The material of a draw whose unit-0 texture has the hash `unit0` and whose textures
    /// are tagged `tags`: the `[materials]` entry of `unit0`, its fields left out taken from
    /// [`MaterialOverride::default`], except `emissive`, 1.0 when tagged `emissive`.
    pub fn material(&self, unit0: Option<u64>, tags: Tags) -> MaterialOverride {
        let d = MaterialOverride { emissive: if tags.emissive { 1.0 } else { 0.0 }, ..MaterialOverride::default() };
        let Some(m) = unit0.and_then(|h| self.materials.get(&h)) else { return d };
        MaterialOverride {
            roughness: m.roughness.unwrap_or(d.roughness),
            metalness: m.metalness.unwrap_or(d.metalness),
            emissive: m.emissive.unwrap_or(d.emissive),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tags_come_from_any_texture_of_the_draw() {
        let (c, _) = crate::config::Config::parse("ui = [\"0x10\", 32]\nsky = [\"0XfF\"]\nlightmap = [\"0x40\"]\n", "g.toml").unwrap();
        let c = Config::from(&c);
        let tags = c.tags([1, 32].into_iter());
        assert!(tags.ui && !tags.sky && !tags.lightmap);
        assert!(c.tags([0x40].into_iter()).lightmap);
        assert!(c.is_lightmap(0x40) && !c.is_lightmap(32));
        assert_eq!(Config::default().tags([32].into_iter()), Tags::default());
    }

    #[test]
    fn materials_fill_in_defaults_and_the_emissive_list() {
        let text = "emissive = [\"0x10\", \"0x20\"]\n[materials]\n\"0x10\" = { roughness = 0.3 }\n\"0x20\" = { emissive = 4 }\n\"0x30\" = { metalness = 1 }\n";
        let (c, _) = crate::config::Config::parse(text, "g.toml").unwrap();
        let c = Config::from(&c);
        let tagged = Tags { emissive: true, ..Tags::default() };
        assert_eq!(c.material(Some(0x10), tagged), MaterialOverride { roughness: 0.3, metalness: 0.0, emissive: 1.0 });
        assert_eq!(c.material(Some(0x20), tagged), MaterialOverride { roughness: 0.8, metalness: 0.0, emissive: 4.0 });
        assert_eq!(c.material(Some(0x30), Tags::default()), MaterialOverride { roughness: 0.8, metalness: 1.0, emissive: 0.0 });
        assert_eq!(c.material(Some(0x40), Tags::default()), MaterialOverride::default());
        assert_eq!(c.material(None, tagged).emissive, 1.0, "a tag on another unit's texture still emits");
    }
}
