//! The ambient occlusion's settings: `glrt.toml` `[ao]`, read like the other tables
//! ([`crate::config`]); the variables are `GLRT_AO` for `enabled` and `GLRT_AO_<KEY>` for the
//! others.
//!
//! ```toml
//! [ao]
//! enabled = false           # screen-space ambient occlusion in raster mode (also 1 or 0)
//! samples = 32              # hemisphere kernel size m, 32..=256
//! radius = 0.5              # sampling radius R, eye-space units, > 0
//! bias = 0.025              # depth bias delta, eye-space units, >= 0
//! blur = 4                  # N of the N x N box blur, 3..=9
//! ```

use crate::config::{Key, Table, integer_in, number, switch};

/// The `[ao]` settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AoSettings {
    /// Whether raster frames get ambient occlusion.
    pub enabled: bool,
    /// Kernel samples per pixel (m).
    pub samples: u32,
    /// Sampling radius R in eye-space units.
    pub radius: f32,
    /// Depth bias δ in eye-space units.
    pub bias: f32,
    /// N of the N × N box blur.
    pub blur: u32,
}

impl Default for AoSettings {
    fn default() -> AoSettings {
        AoSettings { enabled: false, samples: 32, radius: 0.5, bias: 0.025, blur: 4 }
    }
}

impl Table for AoSettings {
    const NAME: &'static str = "ao";
    const KEYS: &'static [Key<AoSettings>] = &[
        Key { name: "enabled", set: |s, v| switch(v).map(|b| s.enabled = b) },
        Key { name: "samples", set: |s, v| integer_in(v, 32..=256).map(|x| s.samples = x as u32) },
        Key { name: "radius", set: |s, v| number(v, |x| x > 0.0, "a number > 0").map(|x| s.radius = x as f32) },
        Key { name: "bias", set: |s, v| number(v, |x| x >= 0.0, "a number >= 0").map(|x| s.bias = x as f32) },
        Key { name: "blur", set: |s, v| integer_in(v, 3..=9).map(|x| s.blur = x as u32) },
    ];

    /// `GLRT_AO` switches the occlusion; `GLRT_AO_SAMPLES`, `GLRT_AO_RADIUS`, ...
    fn variable(name: &str) -> String {
        crate::config::switched_variable(Self::NAME, name)
    }
}

impl AoSettings {
    /// The settings of this process, read at the first call from the process's
    /// configuration ([`crate::config::process_table`]); problems are reported then.
    pub fn of_process() -> AoSettings {
        static SETTINGS: std::sync::OnceLock<AoSettings> = std::sync::OnceLock::new();
        crate::config::process_table(&SETTINGS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(body: &str, env: &[(&str, &str)]) -> (AoSettings, Vec<String>) {
        crate::config::read_table(body, env)
    }

    #[test]
    fn keys_variables_and_bad_values() {
        assert_eq!(read("", &[]), (AoSettings::default(), vec![]));
        let (s, problems) = read("enabled = 1\nsamples = 64\nradius = 2\nbias = 0\nblur = 5\n", &[("GLRT_AO_RADIUS", "1.5")]);
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!(s, AoSettings { enabled: true, samples: 64, radius: 1.5, bias: 0.0, blur: 5 });
        let (s, problems) = read("samples = 16\nblur = 2\n", &[]);
        assert_eq!(s, AoSettings::default());
        assert_eq!(problems, [
            "t.toml:3: ao.blur: expected an integer in 3..=9, found 2; the default is used",
            "t.toml:2: ao.samples: expected an integer in 32..=256, found 16; the default is used",
        ]);
    }
}
