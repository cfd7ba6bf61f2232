//! Radiosity's settings: `glrt.toml` `[radiosity]`, each key overridable by `GLRT_<KEY>` (read
//! by [`crate::config`], which reports unknown keys and bad values once and keeps the
//! default); `enabled` is `GLRT_RADIOSITY`. Keys carry a `radiosity_` prefix where the bare name would make an unclear
//! variable (`GLRT_RADIOSITY_BOUNCES`, not `GLRT_BOUNCES`, which would read as the tracer's).
//!
//! ```toml
//! [radiosity]
//! enabled = false             # radiosity's indirect light on the static world: raster frames'
//!                             # static draws, traced frames' first diffuse bounce on it
//! patch_size = 0.0            # side of a patch, world units; 0: chosen to fit the budget
//! radiosity_bounces = 3       # k of the k-bounce matrix, 1..=16
//! top_share = 0.04            # share of the matrix kept exactly, 0..=1
//! radiosity_budget_mb = 256   # memory of the precompute's dense matrices, MiB, 1..=65536
//! radiosity_wait = false      # frames wait for a new static world's precompute instead of
//!                             # being drawn without radiosity until it is ready
//! radiosity_direct_slices = 4 # 1, 2, 4, 8 or 16: an update traces the shadow rays of one
//!                             # slice of the patches' direct-light points, the others kept
//!                             # from earlier updates (new lights are whole after this many)
//! radiosity_reorder = "sketch" # how the matrix's reordering passes find the nearest line:
//!                             # "sketch" (by sketches of the lines, O(n²)) or "exact" (the
//!                             # seed's search over whole lines, O(n³))
//! ```

use super::reorder::Search;
use crate::config::{Key, Table, integer_in, number, number_in, one_of, switch};

/// Bytes per entry of the precompute's dense matrices: the colour matrix and the k-bounce sum,
/// three `f32` channels each.
pub const DENSE_BYTES_PER_ENTRY: usize = 2 * 3 * 4;

/// The `[radiosity]` table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Whether radiosity lights the static world (`enabled`, [`super::stage`]): raster
    /// frames' static draws ([`super::transfer`]) and, path traced, the first diffuse bounce
    /// on it ([`crate::render::trace::radiosity`]).
    pub enabled: bool,
    /// Side of a patch in world units; 0: the smallest that fits the budget (`patch_size`).
    pub patch_size: f32,
    /// Bounces of the k-bounce matrix (`radiosity_bounces`).
    pub bounces: u32,
    /// Share of the matrix's entries kept exactly (`top_share`).
    pub top_share: f32,
    /// MiB the precompute's dense matrices may take (`radiosity_budget_mb`).
    pub budget_mb: u32,
    /// Whether the frame that meets a new static world waits for its precompute
    /// (`radiosity_wait`); else frames are drawn without radiosity until it is ready
    /// ([`super::stage`]).
    pub wait: bool,
    /// Slices of the patches' direct-light points, one traced per update
    /// (`radiosity_direct_slices`: 1, 2, 4, 8 or 16; [`super::gpu::direct`]).
    pub direct_slices: u32,
    /// How the reordering passes find the nearest line (`radiosity_reorder`: `"sketch"`,
    /// [`Search::SKETCH`], or `"exact"`, [`Search::Exact`]).
    pub reorder: Search,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings { enabled: false, patch_size: 0.0, bounces: 3, top_share: 0.04, budget_mb: 256, wait: false, direct_slices: 4, reorder: Search::SKETCH }
    }
}

impl Table for Settings {
    const NAME: &'static str = "radiosity";
    const KEYS: &'static [Key<Settings>] = &[
        Key { name: "enabled", set: |s, v| switch(v).map(|b| s.enabled = b) },
        Key { name: "patch_size", set: |s, v| number(v, |x| x >= 0.0 && x.is_finite(), "a number >= 0").map(|x| s.patch_size = x as f32) },
        Key { name: "radiosity_bounces", set: |s, v| integer_in(v, 1..=16).map(|x| s.bounces = x as u32) },
        Key { name: "top_share", set: |s, v| number_in(v, 0.0..=1.0).map(|x| s.top_share = x as f32) },
        Key { name: "radiosity_budget_mb", set: |s, v| integer_in(v, 1..=65536).map(|x| s.budget_mb = x as u32) },
        Key { name: "radiosity_wait", set: |s, v| switch(v).map(|b| s.wait = b) },
        Key { name: "radiosity_direct_slices", set: |s, v| number(v, |x| [1.0, 2.0, 4.0, 8.0, 16.0].contains(&x), "1, 2, 4, 8 or 16").map(|x| s.direct_slices = x as u32) },
        Key { name: "radiosity_reorder", set: |s, v| one_of(v, &["sketch", "exact"]).map(|i| s.reorder = [Search::SKETCH, Search::Exact][i]) },
    ];

    fn variable(name: &str) -> String {
        match name {
            "enabled" => "GLRT_RADIOSITY".to_owned(),
            other => format!("GLRT_{}", other.to_uppercase()),
        }
    }
}

impl Settings {
    /// The settings of this process, read at the first call from the process's
    /// configuration ([`crate::config::process_table`]); problems are reported then.
    pub fn of_process() -> Settings {
        static SETTINGS: std::sync::OnceLock<Settings> = std::sync::OnceLock::new();
        crate::config::process_table(&SETTINGS)
    }

    /// The most patches whose dense matrices fit the budget.
    pub fn max_patches(&self) -> usize {
        ((self.budget_mb as f64 * (1 << 20) as f64 / DENSE_BYTES_PER_ENTRY as f64).sqrt()) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The settings and problems of `[radiosity]` holding `body`, with the variables `env`.
    fn read(body: &str, env: &[(&str, &str)]) -> (Settings, Vec<String>) {
        crate::config::read_table(body, env)
    }

    #[test]
    fn every_key_is_read_from_the_file_and_the_environment() {
        let body = "enabled = true\npatch_size = 0.5\nradiosity_bounces = 5\ntop_share = 0.1\nradiosity_budget_mb = 64\nradiosity_wait = true\nradiosity_direct_slices = 2\nradiosity_reorder = \"exact\"\n";
        let (s, problems) = read(body, &[]);
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!(s, Settings { enabled: true, patch_size: 0.5, bounces: 5, top_share: 0.1, budget_mb: 64, wait: true, direct_slices: 2, reorder: Search::Exact });
        let env = [
            ("GLRT_RADIOSITY", "0"),
            ("GLRT_PATCH_SIZE", "2"),
            ("GLRT_RADIOSITY_BOUNCES", "1"),
            ("GLRT_TOP_SHARE", "0"),
            ("GLRT_RADIOSITY_BUDGET_MB", "1"),
            ("GLRT_RADIOSITY_WAIT", "0"),
            ("GLRT_RADIOSITY_DIRECT_SLICES", "1"),
            ("GLRT_RADIOSITY_REORDER", "sketch"),
        ];
        let (s, problems) = read(body, &env);
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!(s, Settings { enabled: false, patch_size: 2.0, bounces: 1, top_share: 0.0, budget_mb: 1, wait: false, direct_slices: 1, reorder: Search::SKETCH });
        assert_eq!(read("", &[]), (Settings::default(), vec![]));
        // 1 MiB of two dense colour matrices: 209 patches (209² · 24 bytes < 2^20).
        assert_eq!(s.max_patches(), 209);
    }

    #[test]
    fn bad_values_are_reported_and_the_default_kept() {
        for (line, message) in [
            ("radiosity_bounces = 0", "radiosity_bounces: expected an integer in 1..=16, found 0"),
            ("top_share = 1.5", "top_share: expected a number in 0..=1, found 1.5"),
            ("patch_size = -1", "patch_size: expected a number >= 0, found -1"),
            ("radiosity_budget_mb = 0", "radiosity_budget_mb: expected an integer in 1..=65536, found 0"),
            ("radiosity_direct_slices = 3", "radiosity_direct_slices: expected 1, 2, 4, 8 or 16, found 3"),
            ("radiosity_reorder = \"fast\"", "radiosity_reorder: expected one of \"sketch\", \"exact\", found \"fast\""),
        ] {
            let (s, problems) = read(line, &[]);
            assert_eq!(s, Settings::default(), "{line}");
            assert_eq!(problems, [format!("t.toml:2: radiosity.{message}; the default is used")], "{line}");
        }
    }
}
