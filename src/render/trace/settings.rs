//! The path tracer's settings: `glrt.toml` `[pathtrace]`, each key overridable by
//! `GLRT_<KEY>` (read by [`crate::config`], which reports unknown keys and bad values once
//! and keeps the default). `GLRT_MODE` (pathtrace, raster, none) is not one of them: it
//! chooses the renderer before any is built.
//!
//! ```toml
//! [pathtrace]
//! spp = 1                   # samples per pixel per frame, 1..=64
//! bounces = 2               # indirect bounces after the primary hit, 0..=8
//! resolution_scale = 1.0    # traced image / window, per direction, 0.25..=1
//! light_scale = 1.0         # multiplies every light converted from glLight, > 0
//! sun_direction = [0.3, 1.0, 0.2]  # towards the sun, world frame; absent: GL's own
//! sun_angle = 0.53          # angular diameter of directional lights, degrees, 0..=10
//! tonemap = "aces"          # "aces", "reinhard", "none" (clamp)
//! exposure = 0.0            # EV offset, -10..=10
//! accumulate = 1024         # frames accumulated while the camera stands still, 1..=65536
//! lightmaps = "ignore"      # "ignore" or "keep" (a second unit modulated over the first)
//! temporal = true           # temporal filter with reprojection while moving
//! ```

use glam::Vec3;


/// How traced radiance becomes display colour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Tonemap {
    /// The ACES filmic curve (`"aces"`).
    #[default]
    Aces,
    /// Reinhard, `c / (1 + c)` (`"reinhard"`).
    Reinhard,
    /// None: clamped to 0..=1 (`"none"`).
    Clamp,
}

/// What the tracer does with a second texture unit modulated over the first (a lightmap: the
/// light baked by the game, which tracing computes itself).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Lightmaps {
    /// Left out of the albedo (`"ignore"`).
    #[default]
    Ignore,
    /// Multiplied into the albedo (`"keep"`).
    Keep,
}

/// The `[pathtrace]` settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Samples per pixel per frame, 1..=64.
    pub spp: u32,
    /// Indirect bounces after the primary hit, 0..=8.
    pub bounces: u32,
    /// The traced image is this fraction of the window in each direction, 0.25..=1.
    pub resolution_scale: f32,
    /// Multiplies every light converted from `glLight`, > 0.
    pub light_scale: f32,
    /// Unit direction towards the sun in the world frame of the recovered view
    /// ([`crate::frame::class::View`]); when set, the directional GL light of largest
    /// intensity takes it. `None`: the lights keep their GL directions.
    pub sun_direction: Option<Vec3>,
    /// Angular diameter of directional lights in degrees, 0..=10 (0: hard shadows; the sun
    /// is 0.53).
    pub sun_angle: f32,
    /// The tone curve.
    pub tonemap: Tonemap,
    /// Exposure offset in EV (stops), -10..=10: radiance is multiplied by 2^exposure.
    pub exposure: f32,
    /// Frames accumulated at most while the camera stands still, 1..=65536.
    pub accumulate: u32,
    /// Whether a second texture unit modulated over the first is part of the albedo.
    pub lightmaps: Lightmaps,
    /// The temporal filter (with reprojection while the camera moves).
    pub temporal: bool,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings {
            spp: 1,
            bounces: 2,
            resolution_scale: 1.0,
            light_scale: 1.0,
            sun_direction: None,
            sun_angle: 0.53,
            tonemap: Tonemap::Aces,
            exposure: 0.0,
            accumulate: 1024,
            lightmaps: Lightmaps::Ignore,
            temporal: true,
        }
    }
}

impl Settings {
    /// The settings of this process (provisional: the defaults until glrt.toml is read).
    pub fn of_process() -> Settings {
        Settings::default()
    }
}
