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
//! light_radius = 0.0        # radius of point and spot lights, eye-space units, >= 0 (0: points)
//! tonemap = "knee"          # "knee", "aces", "reinhard", "none" (clamp)
//! exposure = 0.0            # EV offset, -10..=10
//! accumulate = 1024         # frames accumulated while the camera stands still, 1..=65536
//! lightmaps = "keep"        # "keep" or "ignore" (baked surfaces traced as reflectors)
//! sample_emitters = true    # next-event estimation of emissive surfaces
//! temporal = true           # temporal filter with reprojection while moving
//! sky_sampling = true       # next-event estimation of the sky (its cube map's luminance)
//! sky_size = 128            # faces of the sky's environment cube map, pixels, 16..=2048
//! tracer = "auto"           # "auto" (the faster where both run, measured), "hardware" (VK_KHR_ray_tracing_pipeline), "compute"
//! bvh = "binary"            # the compute tracer's BVH nodes: "binary" or "wide" (8 children, compressed)
//! chunk_regions = 2         # both tracers merge the static world's chunks of n³ world cells, 0..=64 (0: none)
//! ```

use glam::Vec3;

use super::bvh::Layout;
use crate::config::{Key, Table, direction, integer_in, number, number_in, one_of, switch};

/// Where the knee tone curve ([`Tonemap::Knee`]) leaves the identity: linear radiance 0.8
/// (display value 0.906, 231 of 255).
pub const KNEE: f32 = 0.8;

/// How traced radiance becomes display colour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Tonemap {
    /// Display-referred (`"knee"`): the identity up to the knee [`KNEE`], so a surface shows
    /// the colour the rasterizer gives it, and above it a Reinhard shoulder, `k + (1 − k) t /
    /// (1 + t)` with `t = (x − k) / (1 − k)`, which keeps the value and slope at the knee and
    /// approaches display white: linear 1 shows as 0.9 (display 243 of 255), 2 as 0.971, 4 as
    /// 0.989. Per channel.
    #[default]
    Knee,
    /// The ACES filmic curve fitted by Narkowicz (`"aces"`): changes every colour.
    Aces,
    /// Reinhard, `c / (1 + c)` (`"reinhard"`).
    Reinhard,
    /// None: clamped to 0..=1 (`"none"`).
    Clamp,
}

/// What the tracer does with surfaces whose light is baked
/// ([`crate::frame::class::SurfaceLighting::Baked`]: a lightmap unit or pass, or baked vertex
/// colours: light the game computed, which tracing computes itself; `super::material`'s module
/// doc says why neither choice counts it twice).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Lightmaps {
    /// The surface shows its raster colour, albedo × baked light, as emitted radiance and
    /// reflects no traced light (`"keep"`).
    #[default]
    Keep,
    /// The baked light is left out: the surface reflects traced light with its albedo
    /// (`"ignore"`).
    Ignore,
}

/// Which ray-tracing back end traces ([`super::backend`] decides for `Auto`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Tracer {
    /// Where the device has the hardware back end, the faster of the two, measured in a
    /// program's first frames and remembered ([`super::auto`]); else the compute one
    /// (`"auto"`).
    #[default]
    Auto,
    /// The ray-tracing pipeline ([`super::hardware`]); the compute one, with a message, on a
    /// device without it (`"hardware"`).
    Hardware,
    /// BVH traversal in compute shaders ([`super::compute`]), on every device (`"compute"`).
    Compute,
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
    /// Radius of the spheres that point and spot lights become, in the eye-space units of
    /// the game, >= 0 (0: points, hard shadows). The intensity stays the same.
    pub light_radius: f32,
    /// The tone curve.
    pub tonemap: Tonemap,
    /// Exposure offset in EV (stops), -10..=10: radiance is multiplied by 2^exposure.
    pub exposure: f32,
    /// Frames accumulated at most while the camera stands still, 1..=65536.
    pub accumulate: u32,
    /// Whether baked surfaces show their baked light.
    pub lightmaps: Lightmaps,
    /// Next-event estimation of emissive surfaces (emission passes, emissive materials,
    /// [`super::emitters`]); off, only continuation rays find them.
    pub sample_emitters: bool,
    /// The temporal filter (with reprojection while the camera moves).
    pub temporal: bool,
    /// Next-event estimation of the sky (its cube map's luminance, [`super::sky_distribution`]);
    /// off, only continuation rays find it.
    pub sky_sampling: bool,
    /// Width and height of each face of the environment cube map the sky draws are rendered
    /// into ([`super::sky`]), 16..=2048.
    pub sky_size: u32,
    /// The ray-tracing back end.
    pub tracer: Tracer,
    /// The node layout of the compute tracer's BVHs.
    pub bvh: Layout,
    /// Cells of the static world's grid per side of a region whose chunks the tracers merge
    /// into one bottom-level structure ([`super::regions`]), 0..=64; 0: a structure and an
    /// instance per chunk.
    pub chunk_regions: u32,
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
            light_radius: 0.0,
            tonemap: Tonemap::Knee,
            exposure: 0.0,
            accumulate: 1024,
            lightmaps: Lightmaps::Keep,
            sample_emitters: true,
            temporal: true,
            sky_sampling: true,
            sky_size: 128,
            tracer: Tracer::Auto,
            bvh: Layout::Binary,
            chunk_regions: 2,
        }
    }
}

/// A boolean.
impl Table for Settings {
    const NAME: &'static str = "pathtrace";
    const KEYS: &'static [Key<Settings>] = &[
        Key { name: "spp", set: |s, v| integer_in(v, 1..=64).map(|x| s.spp = x as u32) },
        Key { name: "bounces", set: |s, v| integer_in(v, 0..=8).map(|x| s.bounces = x as u32) },
        Key { name: "resolution_scale", set: |s, v| number_in(v, 0.25..=1.0).map(|x| s.resolution_scale = x as f32) },
        Key { name: "light_scale", set: |s, v| number(v, |x| x > 0.0, "a number > 0").map(|x| s.light_scale = x as f32) },
        Key { name: "sun_direction", set: |s, v| direction(v).map(|d| s.sun_direction = Some(d)) },
        Key { name: "sun_angle", set: |s, v| number_in(v, 0.0..=10.0).map(|x| s.sun_angle = x as f32) },
        Key { name: "light_radius", set: |s, v| number(v, |x| x >= 0.0, "a number >= 0").map(|x| s.light_radius = x as f32) },
        Key {
            name: "tonemap",
            set: |s, v| one_of(v, &["knee", "aces", "reinhard", "none"]).map(|i| s.tonemap = [Tonemap::Knee, Tonemap::Aces, Tonemap::Reinhard, Tonemap::Clamp][i]),
        },
        Key { name: "exposure", set: |s, v| number_in(v, -10.0..=10.0).map(|x| s.exposure = x as f32) },
        Key { name: "accumulate", set: |s, v| integer_in(v, 1..=65536).map(|x| s.accumulate = x as u32) },
        Key { name: "lightmaps", set: |s, v| one_of(v, &["keep", "ignore"]).map(|i| s.lightmaps = [Lightmaps::Keep, Lightmaps::Ignore][i]) },
        Key { name: "sample_emitters", set: |s, v| switch(v).map(|b| s.sample_emitters = b) },
        Key { name: "temporal", set: |s, v| switch(v).map(|b| s.temporal = b) },
        Key { name: "sky_sampling", set: |s, v| switch(v).map(|b| s.sky_sampling = b) },
        Key { name: "sky_size", set: |s, v| integer_in(v, 16..=2048).map(|x| s.sky_size = x as u32) },
        Key { name: "tracer", set: |s, v| one_of(v, &["auto", "hardware", "compute"]).map(|i| s.tracer = [Tracer::Auto, Tracer::Hardware, Tracer::Compute][i]) },
        Key { name: "bvh", set: |s, v| one_of(v, &["wide", "binary"]).map(|i| s.bvh = [Layout::Wide, Layout::Binary][i]) },
        Key { name: "chunk_regions", set: |s, v| integer_in(v, 0..=64).map(|x| s.chunk_regions = x as u32) },
    ];
}

impl Settings {
    /// The settings of this process, read at the first call from the process's
    /// configuration ([`crate::config::process_table`]); problems are reported then.
    pub fn of_process() -> Settings {
        static SETTINGS: std::sync::OnceLock<Settings> = std::sync::OnceLock::new();
        crate::config::process_table(&SETTINGS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The settings and problems of `[pathtrace]` holding `body`, with the variables `env`.
    fn read(body: &str, env: &[(&str, &str)]) -> (Settings, Vec<String>) {
        crate::config::read_table(body, env)
    }

    #[test]
    fn every_key_is_read() {
        let body = "spp = 8\nbounces = 0\nresolution_scale = 0.5\nlight_scale = 2\nsun_direction = [0, 2, 0]\nsun_angle = 0\nlight_radius = 0.25\n\
                    tonemap = \"reinhard\"\nexposure = -1.5\naccumulate = 65536\nlightmaps = \"ignore\"\nsample_emitters = false\ntemporal = false\nsky_sampling = false\nsky_size = 64\ntracer = \"compute\"\nbvh = \"wide\"\nchunk_regions = 0\n";
        let (s, problems) = read(body, &[]);
        assert!(problems.is_empty(), "{problems:?}");
        let expected = Settings {
            spp: 8,
            bounces: 0,
            resolution_scale: 0.5,
            light_scale: 2.0,
            sun_direction: Some(Vec3::Y),
            sun_angle: 0.0,
            light_radius: 0.25,
            tonemap: Tonemap::Reinhard,
            exposure: -1.5,
            accumulate: 65536,
            lightmaps: Lightmaps::Ignore,
            sample_emitters: false,
            temporal: false,
            sky_sampling: false,
            sky_size: 64,
            tracer: Tracer::Compute,
            bvh: Layout::Wide,
            chunk_regions: 0,
        };
        assert_eq!(s, expected);
        assert_eq!(read("tonemap = \"none\"\n", &[]).0.tonemap, Tonemap::Clamp);
        assert_eq!(read("tonemap = \"aces\"\n", &[]).0.tonemap, Tonemap::Aces);
        assert_eq!(read("tonemap = \"knee\"\nlightmaps = \"keep\"\n", &[]).0, Settings::default());
        assert_eq!(read("", &[]), (Settings::default(), vec![]));
        assert_eq!((Settings::default().tonemap, Settings::default().lightmaps), (Tonemap::Knee, Lightmaps::Keep));
        assert_eq!(read("tracer = \"hardware\"\n", &[]).0.tracer, Tracer::Hardware);
        assert_eq!(read("bvh = \"binary\"\n", &[("GLRT_BVH", "wide")]).0.bvh, Layout::Wide);
        assert_eq!(Settings::default().bvh, Layout::Binary);
        assert_eq!(read("", &[("GLRT_CHUNK_REGIONS", "8")]).0.chunk_regions, 8);
        assert_eq!(Settings::KEYS.len(), 18);
    }

    #[test]
    fn bad_values_are_reported_with_their_line_and_the_default_kept() {
        let cases = [
            ("spp = 0", "spp: expected an integer in 1..=64, found 0"),
            ("spp = 65", "spp: expected an integer in 1..=64, found 65"),
            ("spp = 2.0", "spp: expected an integer in 1..=64, found 2.0"),
            ("bounces = 9", "bounces: expected an integer in 0..=8, found 9"),
            ("resolution_scale = 0.2", "resolution_scale: expected a number in 0.25..=1, found 0.2"),
            ("light_scale = 0", "light_scale: expected a number > 0, found 0"),
            ("light_scale = inf", "light_scale: expected a number > 0, found inf"),
            ("sun_direction = [0, 0, 0]", "sun_direction: expected a direction [x, y, z], not zero, found [0, 0, 0]"),
            ("sun_direction = [1, 2]", "sun_direction: expected a direction [x, y, z], not zero, found [1, 2]"),
            ("sun_direction = \"up\"", "sun_direction: expected a direction [x, y, z], not zero, found \"up\""),
            ("sun_angle = 11", "sun_angle: expected a number in 0..=10, found 11"),
            ("light_radius = -0.5", "light_radius: expected a number >= 0, found -0.5"),
            ("tonemap = \"filmic\"", "tonemap: expected one of \"knee\", \"aces\", \"reinhard\", \"none\", found \"filmic\""),
            ("exposure = -10.5", "exposure: expected a number in -10..=10, found -10.5"),
            ("accumulate = 0", "accumulate: expected an integer in 1..=65536, found 0"),
            ("lightmaps = true", "lightmaps: expected one of \"keep\", \"ignore\", found true"),
            ("sample_emitters = \"yes\"", "sample_emitters: expected true, false, 1 or 0, found \"yes\""),
            ("temporal = 2", "temporal: expected true, false, 1 or 0, found 2"),
            ("sky_size = 8", "sky_size: expected an integer in 16..=2048, found 8"),
            ("bvh = \"quad\"", "bvh: expected one of \"wide\", \"binary\", found \"quad\""),
        ];
        for (line, message) in cases {
            let (s, problems) = read(&format!("\n{line}\n"), &[]);
            assert_eq!(s, Settings::default(), "{line}");
            assert_eq!(problems, [format!("t.toml:3: pathtrace.{message}; the default is used")], "{line}");
        }
        let (s, problems) = read("spp = 4\nsamples = 3\n", &[]);
        assert_eq!(s.spp, 4);
        assert_eq!(problems.len(), 1);
        assert!(problems[0].starts_with("t.toml:3: pathtrace.samples: unknown key (known: spp, bounces, resolution_scale,"), "{}", problems[0]);
    }

    #[test]
    fn variables_override_the_file() {
        let env = [
            ("GLRT_SPP", "16"),
            ("GLRT_TONEMAP", "none"),
            ("GLRT_SUN_DIRECTION", "[1, 0, 0]"),
            ("GLRT_TEMPORAL", "false"),
            ("GLRT_EXPOSURE", "2"),
            ("GLRT_LIGHT_RADIUS", "0.1"),
            ("GLRT_MODE", "raster"),
        ];
        let (s, problems) = read("spp = 4\ntonemap = \"reinhard\"\n", &env);
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!((s.spp, s.tonemap, s.sun_direction, s.temporal, s.exposure), (16, Tonemap::Clamp, Some(Vec3::X), false, 2.0));
        assert_eq!(s.light_radius, 0.1);
    }

    #[test]
    fn bad_variables_are_reported_and_leave_the_file_value() {
        let env = [("GLRT_SPP", "lots"), ("GLRT_BOUNCES", "-1"), ("GLRT_LIGHTMAPS", ""), ("GLRT_RESOLUTION_SCALE", "[0.5")];
        let (s, problems) = read("spp = 4\n", &env);
        assert_eq!((s.spp, s.bounces, s.lightmaps, s.resolution_scale), (4, 2, Lightmaps::Keep, 1.0));
        assert_eq!(problems, [
            "GLRT_SPP: expected an integer in 1..=64, found \"lots\"; the variable is ignored",
            "GLRT_BOUNCES: expected an integer in 0..=8, found -1; the variable is ignored",
            "GLRT_RESOLUTION_SCALE: expected a number in 0.25..=1, found \"[0.5\"; the variable is ignored",
            "GLRT_LIGHTMAPS: expected one of \"keep\", \"ignore\", found \"\"; the variable is ignored",
        ]);
    }

    #[test]
    fn the_process_settings_are_read_once() {
        assert_eq!(Settings::of_process(), Settings::of_process());
    }
}
