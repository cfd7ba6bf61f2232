//! The height fog's settings: `glrt.toml` `[fog]`, read like the other tables
//! ([`crate::config`]); the variables are `GLRT_FOG` for `enabled` and `GLRT_FOG_<KEY>` for
//! the others.
//!
//! ```toml
//! [fog]
//! enabled = false           # height fog in both modes (also 1 or 0)
//! density = 0.02            # rho0: density at the origin height, per world unit, >= 0
//! falloff = 0.1             # b: rho(z) = rho0 exp(-b z), per world unit, >= 0 (0: uniform fog)
//! height = 0.0              # the world height z = 0 of the density
//! up = [0, 1, 0]            # the world's up direction (Quake-engine worlds: [0, 0, 1])
//! color = [0.6, 0.65, 0.7]  # framebuffer values 0..=1, or "gl": the frame's GL fog colour
//! ```
//!
//! The world is the recovered view's ([`crate::frame::class::View`]); frames without one use
//! the eye space of their draws.

use glam::Vec3;

use crate::config::{Key, Table, direction, number, shown, switch};

/// Where the fog colour comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FogColor {
    /// A fixed colour (framebuffer values, 0..=1).
    Fixed([f32; 3]),
    /// `"gl"`: the colour of the frame's first draw with GL fog enabled (the fixed colour
    /// [`DEFAULT_COLOR`] when none has).
    FromGl,
}

/// The fog colour when none is given.
pub const DEFAULT_COLOR: [f32; 3] = [0.6, 0.65, 0.7];

/// The `[fog]` settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FogSettings {
    /// Whether frames are fogged.
    pub enabled: bool,
    /// rho0, the density at height 0, per world unit.
    pub density: f32,
    /// b, the exponential falloff of the density with height, per world unit.
    pub falloff: f32,
    /// The world height of the density's origin (z = 0).
    pub height: f32,
    /// The world's unit up direction.
    pub up: Vec3,
    /// The fog colour.
    pub color: FogColor,
}

impl Default for FogSettings {
    fn default() -> FogSettings {
        FogSettings { enabled: false, density: 0.02, falloff: 0.1, height: 0.0, up: Vec3::Y, color: FogColor::Fixed(DEFAULT_COLOR) }
    }
}

/// A colour `[r, g, b]` in 0..=1, or `"gl"`.
fn color(value: &toml::Value) -> Result<FogColor, String> {
    if value.as_str() == Some("gl") {
        return Ok(FogColor::FromGl);
    }
    let expected = || format!("expected \"gl\" or a colour [r, g, b] in 0..=1, found {}", shown(value));
    let items = value.as_array().filter(|a| a.len() == 3).ok_or_else(expected)?;
    let mut c = [0.0; 3];
    for (c, item) in c.iter_mut().zip(items) {
        *c = number(item, |x| (0.0..=1.0).contains(&x), "a number").map_err(|_| expected())? as f32;
    }
    Ok(FogColor::Fixed(c))
}

/// A number >= 0.
fn non_negative(value: &toml::Value) -> Result<f32, String> {
    number(value, |x| x >= 0.0, "a number >= 0").map(|x| x as f32)
}

impl Table for FogSettings {
    const NAME: &'static str = "fog";
    const KEYS: &'static [Key<FogSettings>] = &[
        Key { name: "enabled", set: |s, v| switch(v).map(|b| s.enabled = b) },
        Key { name: "density", set: |s, v| non_negative(v).map(|x| s.density = x) },
        Key { name: "falloff", set: |s, v| non_negative(v).map(|x| s.falloff = x) },
        Key { name: "height", set: |s, v| number(v, |_| true, "a number").map(|x| s.height = x as f32) },
        Key { name: "up", set: |s, v| direction(v).map(|d| s.up = d) },
        Key { name: "color", set: |s, v| color(v).map(|c| s.color = c) },
    ];

    /// `GLRT_FOG` switches the fog; `GLRT_FOG_DENSITY`, `GLRT_FOG_FALLOFF`, ...
    fn variable(name: &str) -> String {
        crate::config::switched_variable(Self::NAME, name)
    }
}

impl FogSettings {
    /// The settings of this process, read at the first call from the process's
    /// configuration ([`crate::config::process_table`]); problems are reported then.
    pub fn of_process() -> FogSettings {
        static SETTINGS: std::sync::OnceLock<FogSettings> = std::sync::OnceLock::new();
        crate::config::process_table(&SETTINGS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(body: &str, env: &[(&str, &str)]) -> (FogSettings, Vec<String>) {
        crate::config::read_table(body, env)
    }

    #[test]
    fn keys_and_variables_are_read() {
        assert_eq!(read("", &[]), (FogSettings::default(), vec![]));
        let (s, problems) = read("enabled = true\ndensity = 0.5\nfalloff = 0\nheight = -3\nup = [0, 0, 2]\ncolor = \"gl\"\n", &[]);
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!(s, FogSettings { enabled: true, density: 0.5, falloff: 0.0, height: -3.0, up: Vec3::Z, color: FogColor::FromGl });
        let (s, problems) = read("color = [1, 0.5, 0]", &[("GLRT_FOG", "1"), ("GLRT_FOG_DENSITY", "0.25"), ("GLRT_FOG_COLOR", "[0, 0, 1]")]);
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!((s.enabled, s.density, s.color), (true, 0.25, FogColor::Fixed([0.0, 0.0, 1.0])));
    }

    #[test]
    fn bad_values_are_reported_and_the_default_kept() {
        let (s, problems) = read("density = -1\ncolor = [2, 0, 0]\nup = [0, 0, 0]\n", &[]);
        assert_eq!(s, FogSettings::default());
        assert_eq!(problems, [
            "t.toml:3: fog.color: expected \"gl\" or a colour [r, g, b] in 0..=1, found [2, 0, 0]; the default is used",
            "t.toml:2: fog.density: expected a number >= 0, found -1; the default is used",
            "t.toml:4: fog.up: expected a direction [x, y, z], not zero, found [0, 0, 0]; the default is used",
        ]);
    }
}
