//! The denoiser's settings: `glrt.toml` `[denoise]`, read like the tracer's
//! ([`crate::config`]); the variables are `GLRT_DENOISE` for `enabled` and
//! `GLRT_DENOISE_<KEY>` for the others.
//!
//! ```toml
//! [denoise]
//! enabled = true            # A-SVGF in place of the tracer's temporal filter (also 1 or 0)
//! iterations = 5            # à-trous iterations, 1..=8
//! gradients = true          # temporal gradients shorten the history where lighting changed
//! specular = true           # specular light is a channel of its own (else it rides the diffuse ones)
//! view = "color"            # "color", "history" (history lengths as grey), "direct", "indirect",
//!                           # "specular" (one traced channel) or "unfiltered" (all of them)
//! ```
//!
//! With `enabled = false` the tracer's own temporal filter runs (`[pathtrace] temporal`), and
//! with `temporal = false` too the raw traced samples are shown, for comparison.

use crate::config::{Key, Table, integer_in, one_of, switch};

/// What the denoiser's output shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum View {
    /// The denoised colour (`"color"`).
    #[default]
    Color,
    /// Each pixel's history length in frames, as the grey level 0..=255 (`"history"`): where
    /// reprojection kept the history and where a disocclusion dropped it.
    History,
    /// This frame's traced direct diffuse light, remodulated, unfiltered (`"direct"`).
    Direct,
    /// This frame's traced indirect diffuse light, remodulated, unfiltered (`"indirect"`).
    Indirect,
    /// This frame's traced specular light, remodulated, unfiltered (`"specular"`; black with
    /// `specular = false`).
    Specular,
    /// The primary hit's emission and the three channels remodulated, unfiltered
    /// (`"unfiltered"`): the traced radiance again, through the channels.
    Unfiltered,
}

impl View {
    /// The views in the order of their names.
    const ALL: [View; 6] = [View::Color, View::History, View::Direct, View::Indirect, View::Specular, View::Unfiltered];

    /// The view's `VIEW_*` code of [`super::shader_constants`].
    pub fn code(self) -> u32 {
        use super::shader_constants::{VIEW_COLOR, VIEW_DIRECT, VIEW_HISTORY, VIEW_INDIRECT, VIEW_SPECULAR, VIEW_UNFILTERED};
        match self {
            View::Color => VIEW_COLOR,
            View::History => VIEW_HISTORY,
            View::Direct => VIEW_DIRECT,
            View::Indirect => VIEW_INDIRECT,
            View::Specular => VIEW_SPECULAR,
            View::Unfiltered => VIEW_UNFILTERED,
        }
    }
}

/// The `[denoise]` settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DenoiseSettings {
    /// Whether traced frames are denoised (else the tracer's temporal filter resolves them).
    pub enabled: bool,
    /// Iterations of the à-trous filter, 1..=8 (the kernel reaches 2^(iterations + 1) pixels).
    pub iterations: u32,
    /// Whether temporal gradients (A-SVGF) shorten the history where the lighting changed;
    /// without them a change reaches the image only as fast as the history cap allows.
    pub gradients: bool,
    /// Whether the tracer splits the specular lobe's light into a channel of its own, filtered
    /// apart (fewer à-trous iterations, lobe-aware weights); without it specular light rides
    /// the direct and indirect channels, demodulated by the albedo.
    pub specular: bool,
    /// What the output shows.
    pub view: View,
}

impl Default for DenoiseSettings {
    fn default() -> DenoiseSettings {
        DenoiseSettings { enabled: true, iterations: 5, gradients: true, specular: true, view: View::Color }
    }
}

impl Table for DenoiseSettings {
    const NAME: &'static str = "denoise";
    const KEYS: &'static [Key<DenoiseSettings>] = &[
        Key { name: "enabled", set: |s, v| switch(v).map(|b| s.enabled = b) },
        Key { name: "iterations", set: |s, v| integer_in(v, 1..=8).map(|x| s.iterations = x as u32) },
        Key { name: "gradients", set: |s, v| switch(v).map(|b| s.gradients = b) },
        Key { name: "specular", set: |s, v| switch(v).map(|b| s.specular = b) },
        Key { name: "view", set: |s, v| one_of(v, &["color", "history", "direct", "indirect", "specular", "unfiltered"]).map(|i| s.view = View::ALL[i]) },
    ];

    /// `GLRT_DENOISE` switches the denoiser; `GLRT_DENOISE_ITERATIONS`, `GLRT_DENOISE_GRADIENTS`,
    /// `GLRT_DENOISE_SPECULAR`, `GLRT_DENOISE_VIEW`.
    fn variable(name: &str) -> String {
        crate::config::switched_variable(Self::NAME, name)
    }
}

impl DenoiseSettings {
    /// The settings of this process, read at the first call from the process's
    /// configuration ([`crate::config::process_table`]); problems are reported then.
    pub fn of_process() -> DenoiseSettings {
        static SETTINGS: std::sync::OnceLock<DenoiseSettings> = std::sync::OnceLock::new();
        crate::config::process_table(&SETTINGS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The settings and problems of `[denoise]` holding `body`, with the variables `env`.
    fn read(body: &str, env: &[(&str, &str)]) -> (DenoiseSettings, Vec<String>) {
        crate::config::read_table(body, env)
    }

    #[test]
    fn keys_and_variables_are_read() {
        assert_eq!(read("", &[]), (DenoiseSettings::default(), vec![]));
        let (s, problems) = read("enabled = false\niterations = 3\ngradients = false\nspecular = false\nview = \"history\"\n", &[]);
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!(s, DenoiseSettings { enabled: false, iterations: 3, gradients: false, specular: false, view: View::History });
        assert!(!read("", &[("GLRT_DENOISE_GRADIENTS", "0")]).0.gradients);
        assert!(!read("", &[("GLRT_DENOISE_SPECULAR", "0")]).0.specular);
        assert_eq!(read("view = \"unfiltered\"", &[("GLRT_DENOISE_VIEW", "specular")]).0.view, View::Specular);
        let (s, problems) = read("enabled = false\niterations = 3\n", &[("GLRT_DENOISE", "1"), ("GLRT_DENOISE_ITERATIONS", "7"), ("GLRT_ENABLED", "0")]);
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!((s.enabled, s.iterations), (true, 7));
        assert!(!read("", &[("GLRT_DENOISE", "0")]).0.enabled);
        assert!(!read("enabled = 0", &[]).0.enabled);
    }

    #[test]
    fn bad_values_are_reported_and_the_default_kept() {
        let (s, problems) = read("enabled = 2\niterations = 9\n", &[("GLRT_DENOISE_VIEW", "depth")]);
        assert_eq!(s, DenoiseSettings::default());
        assert_eq!(problems, [
            "t.toml:2: denoise.enabled: expected true, false, 1 or 0, found 2; the default is used",
            "t.toml:3: denoise.iterations: expected an integer in 1..=8, found 9; the default is used",
            "GLRT_DENOISE_VIEW: expected one of \"color\", \"history\", \"direct\", \"indirect\", \"specular\", \"unfiltered\", found \"depth\"; the variable is ignored",
        ]);
    }
}
