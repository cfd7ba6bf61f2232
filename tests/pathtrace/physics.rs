//! Physics of the compute path tracer on lavapipe (issue 6): scenes drawn through the GL API,
//! traced with tone mapping off (the output is the sRGB encoding of the radiance), and the
//! radiance read back compared with what light transport says it must be.

use crate::classified;
use crate::lavapipe;
use crate::reference_tracer;

use std::sync::{Arc, Mutex};

use glam::DVec3;
use glrt::render::frame::Renderer;
use glrt::render::trace::settings::{Lightmaps, Settings, Tonemap};
use glrt::render::trace::stats::RayCounts;
use glrt::translate::context::ContextConfig;
use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 24;

/// A context tracing with `settings` (tone mapping off), a `SIZE`² drawable and a
/// perspective camera at the origin looking down −z with a 60° field of view.
fn context(settings: Settings) -> Context {
    classified_context(settings, |_| {})
}

/// [`context`], its frames classified by `classify` (see `classified.rs`).
fn classified_context(settings: Settings, classify: impl Fn(&mut glrt::frame::Frame) + Send + 'static) -> Context {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    renderer.enable_tracing(Settings { tonemap: Tonemap::Clamp, exposure: 0.0, ..settings }).expect("the tracer's pipelines");
    let mut ctx = lavapipe::classified_context_on(renderer, classify);
    lavapipe::perspective_60(&mut ctx, SIZE);
    ctx
}

/// [`context`] and its renderer, shared (its tracer's statistics can be read).
fn shared_context(settings: Settings) -> (Context, Arc<Mutex<Renderer>>) {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    renderer.enable_tracing(Settings { tonemap: Tonemap::Clamp, exposure: 0.0, ..settings }).expect("the tracer's pipelines");
    let renderer = Arc::new(Mutex::new(renderer));
    let mut ctx = Context::new(ContextConfig { share: None, sink: Box::new(lavapipe::Shared(renderer.clone())) });
    lavapipe::perspective_60(&mut ctx, SIZE);
    (ctx, renderer)
}

/// The linear value of an 8-bit sRGB-encoded component.
fn linear(c: u8) -> f64 {
    let c = c as f64 / 255.0;
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// The 8-bit sRGB encoding of linear value `v`.
fn encoded(v: f64) -> f64 {
    let v = v.clamp(0.0, 1.0);
    255.0 * if v <= 0.0031308 { v * 12.92 } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 }
}

/// Lighting on with light 0 off, a white Lambertian front material of diffuse `albedo`.
fn lit_material(ctx: &mut Context, albedo: f32) {
    unsafe {
        dispatch::glEnable(ctx, gl::GL_LIGHTING);
        dispatch::glDisable(ctx, gl::GL_LIGHT0);
        let diffuse = [albedo, albedo, albedo, 1.0];
        dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_DIFFUSE, diffuse.as_ptr());
        let black = [0.0f32, 0.0, 0.0, 1.0];
        dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_SPECULAR, black.as_ptr());
    }
}

/// A sphere of `radius` at `center`, as latitude bands of quads with outward normals.
fn sphere(ctx: &mut Context, center: [f32; 3], radius: f32) {
    let (bands, segments) = (24, 48);
    let point = |i: i32, j: i32| {
        let theta = std::f32::consts::PI * i as f32 / bands as f32;
        let phi = 2.0 * std::f32::consts::PI * j as f32 / segments as f32;
        [theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()]
    };
    unsafe {
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for i in 0..bands {
            for j in 0..segments {
                for (a, b) in [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)] {
                    let n = point(a, b);
                    dispatch::glNormal3f(ctx, n[0], n[1], n[2]);
                    dispatch::glVertex3f(ctx, center[0] + radius * n[0], center[1] + radius * n[1], center[2] + radius * n[2]);
                }
            }
        }
        dispatch::glEnd(ctx);
    }
}

/// Draws `frames` frames with `scene`, then reads the RGBA8 image (rows bottom to top).
fn render(ctx: &mut Context, frames: usize, clear: [f32; 3], mut scene: impl FnMut(&mut Context)) -> Vec<[u8; 4]> {
    for _ in 0..frames {
        unsafe {
            dispatch::glClearColor(ctx, clear[0], clear[1], clear[2], 1.0);
            dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
            dispatch::glEnable(ctx, gl::GL_DEPTH_TEST);
        }
        scene(ctx);
        ctx.end_frame();
    }
    let mut out = vec![[0u8; 4]; (SIZE * SIZE) as usize];
    unsafe { dispatch::glReadPixels(ctx, 0, 0, SIZE, SIZE, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out
}

/// White furnace: a Lambertian sphere of albedo 1 inside a uniform environment of radiance 1
/// reflects exactly the environment (bounces = 0 suffices: the sky is found by the
/// continuation ray leaving the first hit, and a convex body never sees itself),
/// so every pixel of the sphere reads 1 — the sampling weights conserve energy.
#[test]
fn white_furnace_sphere_renders_as_the_environment() {
    let mut ctx = context(Settings { spp: 4, bounces: 0, ..Settings::default() });
    let image = render(&mut ctx, 4, [1.0; 3], |ctx| {
        lit_material(ctx, 1.0);
        sphere(ctx, [0.0, 0.0, -4.0], 1.0);
    });
    let centre = image[(SIZE / 2 * SIZE + SIZE / 2) as usize];
    assert_eq!(centre[..3], [255, 255, 255], "the sphere's centre");
    let darkest = image.iter().map(|p| p[0].min(p[1]).min(p[2])).min().unwrap();
    assert!(darkest >= 253, "every pixel, sphere or environment, reads 1 (darkest {darkest})");

    // The same sphere with albedo 0.5 (GL 0.5 encoded → 0.214 linear) reflects 0.214.
    let mut ctx = context(Settings { spp: 4, bounces: 0, ..Settings::default() });
    let image = render(&mut ctx, 4, [1.0; 3], |ctx| {
        lit_material(ctx, 0.5);
        sphere(ctx, [0.0, 0.0, -4.0], 1.0);
    });
    let centre = image[(SIZE / 2 * SIZE + SIZE / 2) as usize];
    let expected = encoded(linear(128)); // GL colour 0.5 stored as 128
    assert!((centre[0] as f64 - expected).abs() <= 2.0, "{centre:?} against {expected}");
}

/// A plane of albedo a under a directional light of irradiance E, at incidence θ: radiance
/// a / π · E · cos θ, with E = π for GL's white light (src/render/trace/lights.rs).
#[test]
fn directional_light_on_a_plane_gives_albedo_over_pi_e_cos() {
    for degrees in [0.0f32, 30.0, 60.0, 75.0] {
        let theta = degrees.to_radians();
        let mut ctx = context(Settings { spp: 1, bounces: 0, sun_angle: 0.0, ..Settings::default() });
        let image = render(&mut ctx, 2, [0.0; 3], |ctx| unsafe {
            lit_material(ctx, 0.8);
            dispatch::glEnable(ctx, gl::GL_LIGHT0);
            let position = [0.0, theta.sin(), theta.cos(), 0.0f32];
            dispatch::glLightfv(ctx, gl::GL_LIGHT0, gl::GL_POSITION, position.as_ptr());
            dispatch::glBegin(ctx, gl::GL_QUADS);
            dispatch::glNormal3f(ctx, 0.0, 0.0, 1.0);
            for [x, y] in [[-10.0, -10.0], [10.0, -10.0], [10.0, 10.0], [-10.0, 10.0]] {
                dispatch::glVertex3f(ctx, x, y, -3.0);
            }
            dispatch::glEnd(ctx);
        });
        let albedo = linear(204); // GL 0.8 → 204
        let expected = encoded(albedo / std::f64::consts::PI * std::f64::consts::PI * (theta as f64).cos());
        for p in [image[0], image[(SIZE * SIZE / 2 + SIZE / 2) as usize], image[(SIZE * SIZE - 1) as usize]] {
            assert!((p[0] as f64 - expected).abs() <= 1.5, "θ = {degrees}°: {p:?} against {expected:.1}");
        }
    }
}

/// An alpha-tested quad (left texel transparent, right texel opaque) between a directional
/// light and a floor casts the shadow of its opaque half only: traversal runs the alpha test
/// on shadow rays too.
#[test]
fn alpha_tested_geometry_casts_cut_out_shadows() {
    let mut ctx = context(Settings { spp: 1, bounces: 0, sun_angle: 0.0, ..Settings::default() });
    let mut texture = 0u32;
    let texels: [u8; 8] = [255, 255, 255, 0, 255, 255, 255, 255];
    unsafe {
        dispatch::glGenTextures(&mut ctx, 1, &mut texture);
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, texture);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
    }
    let quad = |ctx: &mut Context, [x0, y0, x1, y1]: [f32; 4], z: f32| unsafe {
        dispatch::glBegin(ctx, gl::GL_QUADS);
        dispatch::glNormal3f(ctx, 0.0, 0.0, 1.0);
        for ([x, y], [s, t]) in [([x0, y0], [0.0, 0.0]), ([x1, y0], [1.0, 0.0]), ([x1, y1], [1.0, 1.0]), ([x0, y1], [0.0, 1.0])] {
            dispatch::glTexCoord2f(ctx, s, t);
            dispatch::glVertex3f(ctx, x, y, z);
        }
        dispatch::glEnd(ctx);
    };
    let image = render(&mut ctx, 2, [0.0; 3], |ctx| unsafe {
        lit_material(ctx, 1.0);
        dispatch::glEnable(ctx, gl::GL_LIGHT0);
        // Towards the light: up in z and +x, so shadows fall 2 units to −x from z = −3 to −5.
        let position = [1.0f32, 0.0, 1.0, 0.0];
        dispatch::glLightfv(ctx, gl::GL_LIGHT0, gl::GL_POSITION, position.as_ptr());
        quad(ctx, [-10.0, -10.0, 10.0, 10.0], -5.0);
        dispatch::glEnable(ctx, gl::GL_TEXTURE_2D);
        dispatch::glEnable(ctx, gl::GL_ALPHA_TEST);
        dispatch::glAlphaFunc(ctx, gl::GL_GREATER, 0.5);
        quad(ctx, [0.0, 0.0, 2.0, 2.0], -3.0);
        dispatch::glDisable(ctx, gl::GL_ALPHA_TEST);
        dispatch::glDisable(ctx, gl::GL_TEXTURE_2D);
    });
    // Window x of eye-space x on the floor (z = −5) with the 60° camera.
    let column = |x: f32| ((x / (5.0 * 30f32.to_radians().tan()) * 0.5 + 0.5) * SIZE as f32) as i32;
    let row = column(1.0);
    let at = |x: i32| image[(row * SIZE + x) as usize][0];
    let lit = encoded(std::f64::consts::FRAC_1_SQRT_2);
    assert!((at(column(-1.5)) as f64 - lit).abs() <= 1.5, "behind the transparent half the floor is lit: {} against {lit:.1}", at(column(-1.5)));
    assert_eq!(at(column(-0.5)), 0, "behind the opaque half the floor is in shadow");
    assert!((at(column(-2.5)) as f64 - lit).abs() <= 1.5, "beside the shadow the floor is lit");
}

/// A `levels.len()` × 1 texture of opaque grey texels `levels`, nearest-filtered, bound to the
/// active unit.
fn grey_texture(ctx: &mut Context, levels: &[u8]) -> u32 {
    let texels: Vec<u8> = levels.iter().flat_map(|&v| [v, v, v, 255]).collect();
    let mut texture = 0u32;
    unsafe {
        dispatch::glGenTextures(ctx, 1, &mut texture);
        dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, texture);
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        let width = levels.len() as i32;
        dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, width, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
    }
    texture
}

/// How unit 1 combines its lightmap with unit 0's result.
#[derive(Clone, Copy)]
enum UnitOne {
    /// `GL_MODULATE`.
    Modulate,
    /// `GL_COMBINE`: `MODULATE` of `TEXTURE` and `PREVIOUS`, `RGB_SCALE` 2 (an overbright lightmap).
    Overbright,
    /// `GL_DECAL` (not a lightmap).
    Decal,
}

/// Unlit quads (corners in order) textured with `albedo` on unit 0 and `lightmap` on unit 1
/// combined by `unit_one`; both units' (s, t) run from (0, 0) at the first corner to (1, 1) at
/// the third.
fn lightmapped_quads(ctx: &mut Context, albedo: u32, lightmap: u32, unit_one: UnitOne, quads: &[[[f32; 3]; 4]]) {
    unsafe {
        dispatch::glActiveTexture(ctx, gl::GL_TEXTURE0);
        dispatch::glEnable(ctx, gl::GL_TEXTURE_2D);
        dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, albedo);
        dispatch::glActiveTexture(ctx, gl::GL_TEXTURE1);
        dispatch::glEnable(ctx, gl::GL_TEXTURE_2D);
        dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, lightmap);
        let env = |ctx: &mut Context, pname, value: u32| dispatch::glTexEnvi(ctx, gl::GL_TEXTURE_ENV, pname, value as i32);
        match unit_one {
            UnitOne::Modulate => env(ctx, gl::GL_TEXTURE_ENV_MODE, gl::GL_MODULATE),
            UnitOne::Decal => env(ctx, gl::GL_TEXTURE_ENV_MODE, gl::GL_DECAL),
            UnitOne::Overbright => {
                env(ctx, gl::GL_TEXTURE_ENV_MODE, gl::GL_COMBINE);
                env(ctx, gl::GL_COMBINE_RGB, gl::GL_MODULATE);
                env(ctx, gl::GL_SOURCE0_RGB, gl::GL_TEXTURE);
                env(ctx, gl::GL_SOURCE1_RGB, gl::GL_PREVIOUS);
                dispatch::glTexEnvf(ctx, gl::GL_TEXTURE_ENV, gl::GL_RGB_SCALE, 2.0);
            }
        }
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for quad in quads {
            for (corner, [s, t]) in quad.iter().zip([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]) {
                dispatch::glMultiTexCoord2f(ctx, gl::GL_TEXTURE0, s, t);
                dispatch::glMultiTexCoord2f(ctx, gl::GL_TEXTURE1, s, t);
                dispatch::glVertex3f(ctx, corner[0], corner[1], corner[2]);
            }
        }
        dispatch::glEnd(ctx);
        dispatch::glDisable(ctx, gl::GL_TEXTURE_2D);
        dispatch::glActiveTexture(ctx, gl::GL_TEXTURE0);
        dispatch::glDisable(ctx, gl::GL_TEXTURE_2D);
    }
}

/// Three lightmapped quads across the view (albedo texture grey 200, lightmap 64 left of x = 0
/// and 192 right of it), unit 1 modulating (top), modulating with `RGB_SCALE` 2 (middle) and a
/// decal (bottom), and no lights nor environment. The two lightmaps are light units of baked
/// surfaces (`classified::lightmap_units`). Ignored, they leave unlit surfaces: black. Kept, a
/// surface shows its raster colour, albedo × lightmap in display values, the scale applied by
/// the combiner and clamped as GL does (material.rs); a decal on unit 1 is not a lightmap.
#[test]
fn kept_lightmaps_show_their_baked_light_and_ignored_ones_none() {
    let band = |y0: f32, y1: f32| [[-10.0, y0, -3.0], [10.0, y0, -3.0], [10.0, y1, -3.0], [-10.0, y1, -3.0]];
    let bands = [(UnitOne::Modulate, band(0.6, 10.0), 20), (UnitOne::Overbright, band(-0.5, 0.5), 12), (UnitOne::Decal, band(-10.0, -0.6), 3)];
    let image = |lightmaps: Lightmaps| {
        let mut ctx = classified_context(Settings { spp: 1, bounces: 1, lightmaps, ..Settings::default() }, classified::lightmap_units);
        let albedo = grey_texture(&mut ctx, &[200]);
        let lightmap = grey_texture(&mut ctx, &[64, 192]);
        let image = render(&mut ctx, 2, [0.0; 3], |ctx| {
            for (unit_one, quad, _) in bands {
                lightmapped_quads(ctx, albedo, lightmap, unit_one, &[quad]);
            }
        });
        // Per band, a column each side of x = 0.
        bands.map(|(_, _, row)| [image[(row * SIZE + 4) as usize][0], image[(row * SIZE + 19) as usize][0]])
    };
    assert_eq!(image(Lightmaps::Ignore), [[0, 0]; 3], "ignored: nothing lights the quads");
    let [modulate, overbright, decal] = image(Lightmaps::Keep);
    let want = [64.0, 192.0].map(|l| 200.0 * l / 255.0);
    for (got, want) in modulate.iter().zip(want) {
        assert!((*got as f64 - want).abs() <= 1.0, "kept: {modulate:?} against {want:.1}");
    }
    let want = 2.0 * 200.0 * 64.0 / 255.0;
    assert!((overbright[0] as f64 - want).abs() <= 1.0, "RGB_SCALE 2: {overbright:?} against {want:.1}");
    assert_eq!(overbright[1], 255, "2 × 192 saturates the display, as in GL");
    assert_eq!(decal, [0, 0], "a decal on unit 1 is not baked light");
}

/// A white Lambertian sphere inside a lightmapped box (white albedo, lightmap grey `v`) and no
/// lights: the box's walls emit their baked radiance linear(v) and the sphere, lit only by them
/// (one bounce), reflects exactly that — the whole image reads `v`, as a white furnace does.
/// The walls read `v` too: they reflect none of the light they send each other (which their
/// lightmaps hold already). Ignored, the lightmap lights nothing and everything is black.
#[test]
fn baked_surfaces_light_the_others_once() {
    let h = 10.0f32;
    let box_faces = [
        [[-h, -h, -h], [h, -h, -h], [h, h, -h], [-h, h, -h]],
        [[-h, -h, h], [h, -h, h], [h, h, h], [-h, h, h]],
        [[-h, -h, -h], [-h, h, -h], [-h, h, h], [-h, -h, h]],
        [[h, -h, -h], [h, h, -h], [h, h, h], [h, -h, h]],
        [[-h, -h, -h], [h, -h, -h], [h, -h, h], [-h, -h, h]],
        [[-h, h, -h], [h, h, -h], [h, h, h], [-h, h, h]],
    ];
    for (lightmaps, want) in [(Lightmaps::Keep, 150u8), (Lightmaps::Ignore, 0)] {
        let mut ctx = classified_context(Settings { spp: 4, bounces: 1, lightmaps, ..Settings::default() }, classified::lightmap_units);
        let white = grey_texture(&mut ctx, &[255]);
        let lightmap = grey_texture(&mut ctx, &[150]);
        let image = render(&mut ctx, 2, [0.0; 3], |ctx| {
            lightmapped_quads(ctx, white, lightmap, UnitOne::Modulate, &box_faces);
            lit_material(ctx, 1.0);
            sphere(ctx, [0.0, 0.0, -4.0], 1.0);
            unsafe { dispatch::glDisable(ctx, gl::GL_LIGHTING) };
        });
        let centre = image[(SIZE / 2 * SIZE + SIZE / 2) as usize][0];
        assert!(centre.abs_diff(want) <= 1, "{lightmaps:?}: the sphere's centre reads {centre}, not {want}");
        let (lo, hi) = image.iter().fold((255, 0), |(lo, hi), p| (p[0].min(lo), p[0].max(hi)));
        assert!(lo.abs_diff(want) <= 2 && hi.abs_diff(want) <= 2, "{lightmaps:?}: every pixel reads {want}: {lo}..={hi}");
    }
}

/// Eye-space point of the floor at z = `depth` seen through the centre of pixel (x, y).
fn floor_point(x: i32, y: i32, depth: f64) -> DVec3 {
    let t = 30f64.to_radians().tan();
    let ndc = |i: i32| (2.0 * (i as f64 + 0.5) / SIZE as f64 - 1.0) * t;
    DVec3::new(ndc(x), ndc(y), -1.0) * depth
}

/// The shadow scene: a floor at z = −5 (albedo 0.8), an occluder at z = −3.5 covering
/// y ∈ [1, 3] (its lower edge casts a shadow edge at y = −1 on the floor), and light 0 at
/// `LIGHT`, white, attenuation 1 / (d² / 25): intensity 25π (lights.rs fits it exactly).
fn shadow_scene(ctx: &mut Context) {
    unsafe {
        lit_material(ctx, 0.8);
        dispatch::glEnable(ctx, gl::GL_LIGHT0);
        let position = [LIGHT[0] as f32, LIGHT[1] as f32, LIGHT[2] as f32, 1.0];
        dispatch::glLightfv(ctx, gl::GL_LIGHT0, gl::GL_POSITION, position.as_ptr());
        dispatch::glLightf(ctx, gl::GL_LIGHT0, gl::GL_CONSTANT_ATTENUATION, 0.0);
        dispatch::glLightf(ctx, gl::GL_LIGHT0, gl::GL_QUADRATIC_ATTENUATION, 1.0 / 25.0);
        for ([x0, y0, x1, y1], z) in [([-10.0, -10.0, 10.0, 10.0], -5.0f32), ([-10.0, 1.0, 10.0, 3.0], -3.5)] {
            dispatch::glBegin(ctx, gl::GL_QUADS);
            dispatch::glNormal3f(ctx, 0.0, 0.0, 1.0);
            for [x, y] in [[x0, y0], [x1, y0], [x1, y1], [x0, y1]] {
                dispatch::glVertex3f(ctx, x, y, z);
            }
            dispatch::glEnd(ctx);
        }
    }
}

/// Where `shadow_scene` puts the light (eye space).
const LIGHT: [f64; 3] = [0.0, 3.0, -2.0];
/// Its intensity.
const INTENSITY: f64 = 25.0 * std::f64::consts::PI;

/// A point light of intensity I and a sphere light of the same intensity and radius 0.5 light
/// the floor alike where it sees all of the sphere: radiance a/π · I cos θ / d² (the sphere's
/// irradiance is the point's, lights.rs). Where the occluder hides part of the sphere, the
/// sphere light's shadow has a penumbra that the point light's has not, and its values are the
/// CPU reference tracer's (the light as a spherical emitter of radiance I / (π r²), sampled by
/// area, sharing nothing with the shaders), within the noise of the frames accumulated.
#[test]
fn sphere_lights_keep_the_irradiance_and_soften_shadows() {
    const FRAMES: usize = 32;
    const SPP: u32 = 4;
    let albedo = linear(204);
    let unshadowed = |x: i32, y: i32| {
        let p = floor_point(x, y, 5.0);
        let d = DVec3::from_array(LIGHT) - p;
        albedo / std::f64::consts::PI * INTENSITY * (d.z / d.length()) / d.length_squared()
    };
    let column = 12;
    let mut rows = Vec::new();
    for radius in [0.0f32, 0.5] {
        let mut ctx = context(Settings { spp: SPP, bounces: 0, light_radius: radius, ..Settings::default() });
        let image = render(&mut ctx, FRAMES, [0.0; 3], shadow_scene);
        // Rows 0–2 see the floor and all of the sphere: the inverse-square law holds for both.
        for y in 0..3 {
            for x in 0..SIZE {
                let (got, want) = (image[(y * SIZE + x) as usize][0] as f64, encoded(unshadowed(x, y)));
                assert!((got - want).abs() <= 2.0, "radius {radius}: pixel ({x}, {y}) reads {got}, the inverse-square law {want:.1}");
            }
        }
        rows.push((0..SIZE).map(|y| linear(image[(y * SIZE + column) as usize][0])).collect::<Vec<f64>>());
    }
    let fraction = |row: &[f64], y: i32| row[y as usize] / unshadowed(column, y);
    let penumbra = |row: &[f64]| (4..12).filter(|&y| (0.1..0.9).contains(&fraction(row, y))).count();
    // (The pixel the point light's shadow edge crosses is partly lit: samples 1–3 of a pixel
    // are spread over it.)
    assert!(penumbra(&rows[0]) <= 1, "a point light's shadow is hard: {:?}", (4..12).map(|y| fraction(&rows[0], y)).collect::<Vec<_>>());
    assert!(penumbra(&rows[1]) >= 3, "a sphere light's shadow has a penumbra: {:?}", (4..12).map(|y| fraction(&rows[1], y)).collect::<Vec<_>>());
    assert!(rows[1][14] == 0.0, "and an umbra");

    // The penumbra against the reference tracer, per pixel centre.
    use reference_tracer::{Camera, Pcg32, Scene, Shape, Surface};
    let a = DVec3::splat(albedo);
    let radius = 0.5;
    let floor = Shape::Quad([DVec3::new(-10.0, -10.0, -5.0), DVec3::new(10.0, -10.0, -5.0), DVec3::new(10.0, 10.0, -5.0), DVec3::new(-10.0, 10.0, -5.0)]);
    let occluder = Shape::Quad([DVec3::new(-10.0, 1.0, -3.5), DVec3::new(10.0, 1.0, -3.5), DVec3::new(10.0, 3.0, -3.5), DVec3::new(-10.0, 3.0, -3.5)]);
    let light = Surface { emission: DVec3::splat(INTENSITY / (std::f64::consts::PI * radius * radius)), ..Surface::new("light", Shape::Sphere { center: DVec3::from_array(LIGHT), radius }, DVec3::ZERO) };
    let scene = Scene {
        surfaces: vec![Surface::new("floor", floor, a), Surface::new("occluder", occluder, a), light],
        lights: vec![],
        environment: DVec3::ZERO,
        camera: Camera::perspective(60.0, 1.0, 0.1, 100.0),
    };
    let settings = reference_tracer::Settings::new(SIZE as usize, SIZE as usize, 2, 0);
    let samples = f64::from(SPP) * FRAMES as f64;
    for y in 4..12 {
        let dir = scene.camera.pixel_center(SIZE as usize, SIZE as usize, column as usize, y as usize);
        let mut rng = Pcg32::new(7, y as u64);
        let n = 20000;
        let reference = (0..n).map(|_| scene.radiance(DVec3::ZERO, dir, &settings, &mut rng).x).sum::<f64>() / n as f64;
        // The GPU's visibility is a Bernoulli mean over `samples` shadow rays: 4 standard errors,
        // plus the 8-bit encoding's step.
        let lit = unshadowed(column, y);
        let p = (reference / lit).clamp(0.0, 1.0);
        let bound = 4.0 * lit * (p * (1.0 - p) / samples).sqrt() + 0.01 * lit + 0.002;
        let got = rows[1][y as usize];
        assert!((got - reference).abs() <= bound, "row {y}: {got:.4} against the reference {reference:.4} (± {bound:.4}; visible fraction {p:.2})");
    }
}

/// A sky box around the eye, drawn unlit with depth writes off before the scene (so it is a
/// `Sky` draw): the cube [-10, 10]³, each face split into 2×2 quads coloured `above` where
/// the quad's centre lies on the positive side of `axis` (0: x, 1: y, 2: z) and `below`
/// elsewhere, so the sky is `above` in every direction d with d[axis] > 0. The quads face
/// inwards and back faces are culled, as games draw their sky boxes.
fn sky_box(ctx: &mut Context, axis: usize, above: [f32; 3], below: [f32; 3]) {
    unsafe {
        dispatch::glDisable(ctx, gl::GL_LIGHTING);
        dispatch::glEnable(ctx, gl::GL_CULL_FACE);
        dispatch::glDepthMask(ctx, gl::GL_FALSE);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for face in 0..3 {
            let (u, v) = ((face + 1) % 3, (face + 2) % 3);
            for sign in [-10.0f32, 10.0] {
                for [u0, v0] in [[-10.0f32, -10.0], [0.0, -10.0], [-10.0, 0.0], [0.0, 0.0]] {
                    let mut centre = [0.0f32; 3];
                    (centre[face], centre[u], centre[v]) = (sign, u0 + 5.0, v0 + 5.0);
                    let [r, g, b] = if centre[axis] > 0.0 { above } else { below };
                    dispatch::glColor3f(ctx, r, g, b);
                    // Counter-clockwise seen from the positive side of the face's axis.
                    let mut corners = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
                    if sign > 0.0 {
                        corners.reverse();
                    }
                    for [du, dv] in corners {
                        let mut p = [0.0f32; 3];
                        (p[face], p[u], p[v]) = (sign, u0 + du, v0 + dv);
                        dispatch::glVertex3f(ctx, p[0], p[1], p[2]);
                    }
                }
            }
        }
        dispatch::glEnd(ctx);
        dispatch::glDepthMask(ctx, gl::GL_TRUE);
        dispatch::glDisable(ctx, gl::GL_CULL_FACE);
        dispatch::glColor3f(ctx, 1.0, 1.0, 1.0);
    }
}

/// The sky's colour (GL values) on the positive side of its split.
const ABOVE: [f32; 3] = [0.9, 0.5, 0.25];
/// The sky's colour on the negative side.
const BELOW: [f32; 3] = [0.0, 0.25, 1.0];
/// The clear colour (what missed rays would see without the sky).
const CLEAR: [f32; 3] = [0.2; 3];

/// A quad: its normal and corners.
type Quad = ([f32; 3], [[f32; 3]; 4]);

/// A floor at y = −1 facing up, under the camera.
const FLOOR: Quad = ([0.0, 1.0, 0.0], [[-50.0, -1.0, 50.0], [50.0, -1.0, 50.0], [50.0, -1.0, -50.0], [-50.0, -1.0, -50.0]]);

/// The image of `frames` frames of [`sky_box`] split along `axis` over a white Lambertian
/// quad, the sky sampled as `sky_sampling` says.
fn plane_under_sky(axis: usize, (normal, corners): Quad, frames: usize, sky_sampling: bool) -> Vec<[u8; 4]> {
    let mut ctx = context(Settings { spp: 4, bounces: 1, sky_sampling, ..Settings::default() });
    render(&mut ctx, frames, CLEAR, |ctx| unsafe {
        sky_box(ctx, axis, ABOVE, BELOW);
        lit_material(ctx, 1.0);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        dispatch::glNormal3f(ctx, normal[0], normal[1], normal[2]);
        for [x, y, z] in corners {
            dispatch::glVertex3f(ctx, x, y, z);
        }
        dispatch::glEnd(ctx);
    })
}

/// The sky draws are the environment: a white Lambertian plane under a sky that is one
/// colour on the side its normal faces and another behind it sees only the first (the cube
/// map is sampled by direction; a plane never sees itself), so its radiance is that colour —
/// albedo × the cosine-weighted mean of the sky over the hemisphere — not the clear colour.
/// One plane per axis (a floor facing +y, a wall facing +x, a wall facing +z): a cube face
/// mirrored or swapped shows the other colour. Where the primary ray misses, the window shows
/// the rasterized sky, as in raster mode. Continuation rays alone (cosine-weighted, the sky
/// not sampled) see a sky of one colour over the hemisphere without noise, so one pixel is
/// checked tightly.
#[test]
fn the_sky_draws_light_the_scene_as_its_environment() {
    // GL colours stored as 8 bits (0.9 → 230, 0.5 → 128, 0.25 → 64).
    let stored = ABOVE.map(|c| (c * 255.0).round() as u8);
    let half = SIZE / 4;
    // (axis, the plane's normal and corners, a pixel on it, a pixel of sky above it).
    let cases = [
        (1, FLOOR, [SIZE / 2, half], Some([SIZE / 2, SIZE - half])),
        (0, ([1.0, 0.0, 0.0], [[-1.0, -50.0, 50.0], [-1.0, -50.0, -50.0], [-1.0, 50.0, -50.0], [-1.0, 50.0, 50.0]]), [half, SIZE / 2], Some([SIZE - half, SIZE / 2])),
        (2, ([0.0, 0.0, 1.0], [[-50.0, -50.0, -3.0], [50.0, -50.0, -3.0], [50.0, 50.0, -3.0], [-50.0, 50.0, -3.0]]), [SIZE / 2, SIZE / 2], None),
    ];
    for (axis, quad, lit_pixel, sky_pixel) in cases {
        let image = plane_under_sky(axis, quad, 3, false);
        let at = |[x, y]: [i32; 2]| image[(y * SIZE + x) as usize];
        let lit = at(lit_pixel);
        for c in 0..3 {
            let expected = encoded(linear(stored[c]));
            assert!((lit[c] as f64 - expected).abs() <= 3.0, "axis {axis}: the plane reads {lit:?}, the sky above it is {stored:?}");
        }
        if let Some(p) = sky_pixel {
            let sky = at(p);
            assert!(sky[..3].iter().zip(stored).all(|(&a, b)| a.abs_diff(b) <= 1), "axis {axis}: the visible sky is the rasterized one: {sky:?} against {stored:?}");
        }
    }
}

/// A floor under a sky split along x sees half of each colour, cosine-weighted: its radiance
/// is the mean of both (linear), measured as the mean over floor pixels symmetric about the
/// centre column (accumulated over still frames, the sky sampled once its distribution is read back).
#[test]
fn a_floor_under_a_sky_of_two_halves_reads_their_mean() {
    let image = plane_under_sky(0, FLOOR, 8, true);
    let pixels: Vec<[u8; 4]> = (0..SIZE / 2 - 1).flat_map(|y| (4..SIZE - 4).map(move |x| (x, y))).map(|(x, y)| image[(y * SIZE + x) as usize]).collect();
    for c in 0..3 {
        let mean = pixels.iter().map(|p| linear(p[c])).sum::<f64>() / pixels.len() as f64;
        let [a, b] = [ABOVE[c], BELOW[c]].map(|v| linear((v * 255.0).round() as u8));
        let expected = 0.5 * (a + b);
        assert!((mean - expected).abs() <= 0.02, "channel {c}: mean radiance {mean:.4} over {} pixels against {expected:.4}", pixels.len());
    }
}

/// The dim sky around [`sunny_floor`]'s sun (GL value of each channel).
const DIM: [f32; 3] = [0.05; 3];

/// Frames drawn before those measured, with the floor a unit lower (accumulation restarts when
/// it moves up): the sky's distribution is read back from the cube a frame slot after it is drawn
/// (the cube is drawn again at the second frame), and the measured frames all sample it.
const WARM_UP: usize = 3;

/// A [`sky_box`] of colour `dim` with a small bright quad overhead (white, 6×6 at height 9:
/// about 0.34 sr), drawn as sky draws are (no depth writes).
fn sunny_sky(ctx: &mut Context, dim: [f32; 3]) {
    sky_box(ctx, 1, dim, dim);
    // Safety: plain drawing calls on a current context.
    unsafe {
        dispatch::glDepthMask(ctx, gl::GL_FALSE);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for [x, z] in [[-3.0f32, -3.0], [3.0, -3.0], [3.0, 3.0], [-3.0, 3.0]] {
            dispatch::glVertex3f(ctx, x, 9.0, z);
        }
        dispatch::glEnd(ctx);
        dispatch::glDepthMask(ctx, gl::GL_TRUE);
    }
}

/// The floor pixels' linear radiance (red) after `frames` frames of [`FLOOR`] under a dim
/// [`sky_box`] with a small bright quad overhead (white, 6×6 at height 9: about 0.34 sr, as
/// sky draws), traced with `spp` samples a frame, direct light only, after [`WARM_UP`] frames.
/// `redrawn`: the dim sky's colour alternates between two values of the same 8-bit colour, so
/// its draws differ and the cube is drawn again every frame (as when the camera turns).
fn sunny_floor(sky_sampling: bool, spp: u32, frames: usize, redrawn: bool) -> Vec<f64> {
    let mut ctx = context(Settings { spp, bounces: 0, sky_sampling, temporal: false, ..Settings::default() });
    let mut frame = 0;
    let image = render(&mut ctx, WARM_UP + frames, CLEAR, |ctx| unsafe {
        let dim = if redrawn && frame % 2 == 1 { DIM.map(|c| c + 1e-4) } else { DIM };
        sunny_sky(ctx, dim);
        lit_material(ctx, 1.0);
        dispatch::glPushMatrix(ctx);
        if frame < WARM_UP {
            dispatch::glTranslatef(ctx, 0.0, -1.0, 0.0);
        }
        frame += 1;
        let (normal, corners) = FLOOR;
        dispatch::glBegin(ctx, gl::GL_QUADS);
        dispatch::glNormal3f(ctx, normal[0], normal[1], normal[2]);
        for [x, y, z] in corners {
            dispatch::glVertex3f(ctx, x, y, z);
        }
        dispatch::glEnd(ctx);
        dispatch::glPopMatrix(ctx);
    });
    (0..SIZE / 2 - 1).flat_map(|y| (0..SIZE).map(move |x| (x, y))).map(|(x, y)| linear(image[(y * SIZE + x) as usize][0])).collect()
}

/// The radiance of a white Lambertian floor under [`sunny_floor`]'s sky: the sun's form
/// factor (a square of half-width a = 3/9 its height, centred overhead: four corner rectangles,
/// each (1 / 2π) (a / √(1 + a²)) atan(a / √(1 + a²)) · 2) times its radiance 1, and the dim
/// sky's radiance over the rest of the hemisphere.
fn sunny_floor_radiance() -> f64 {
    let a = 3.0f64 / 9.0;
    let r = (1.0 + a * a).sqrt();
    let sun = 4.0 * (a / r * (a / r).atan()) / std::f64::consts::PI;
    sun + linear((DIM[0] * 255.0).round() as u8) * (1.0 - sun)
}

/// Next-event estimation of the sky (issue 16, item 4): a floor lit by a small bright patch of
/// an otherwise dim sky is much less noisy with the sky sampled than with continuation rays
/// alone, at equal samples per pixel, and both agree with its radiance. Every floor point sees
/// the same sky (the environment is a function of direction; nothing occludes it), so the
/// reference radiance of every pixel is the mean of a many-sample image, itself checked against
/// the radiance the sun's form factor gives.
#[test]
fn sampling_the_sky_lowers_the_noise_of_a_small_bright_sky() {
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let exact = sunny_floor_radiance();
    let reference = mean(&sunny_floor(true, 8, 6, false));
    let rmse = |v: &[f64]| (v.iter().map(|x| (x - reference).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
    let frames = 4;
    let sampled = sunny_floor(true, 2, frames, false);
    let unsampled = sunny_floor(false, 2, frames, false);
    let (sampled_rmse, unsampled_rmse) = (rmse(&sampled), rmse(&unsampled));
    let (sampled_mean, unsampled_mean) = (mean(&sampled), mean(&unsampled));
    eprintln!(
        "exact {exact:.4}, reference {reference:.4}; sampled: mean {sampled_mean:.4}, RMSE {sampled_rmse:.4}; unsampled: mean {unsampled_mean:.4}, RMSE {unsampled_rmse:.4} ({} pixels, 2 spp x {frames} frames)",
        sampled.len()
    );
    assert!((reference / exact - 1.0).abs() < 0.03, "reference radiance {reference:.4} against {exact:.4}");
    assert!(sampled_rmse < 0.5 * unsampled_rmse, "RMSE sampled {sampled_rmse:.4} against unsampled {unsampled_rmse:.4}");
    assert!((sampled_mean / exact - 1.0).abs() < 0.03, "sampled mean {sampled_mean:.4} against {exact:.4}");
    assert!((unsampled_mean / exact - 1.0).abs() < 0.1, "unsampled mean {unsampled_mean:.4} against {exact:.4}");
}

/// A sky drawn again every frame (an eye-space cube while the camera turns) is still sampled:
/// its distribution is that of a content read back a frame slot earlier, and sampling by it
/// stays unbiased and much less noisy than continuation rays alone. The cube's content is the
/// same in every frame here, so the frames' mean is the sun's radiance.
#[test]
fn a_sky_redrawn_every_frame_is_still_sampled() {
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let exact = sunny_floor_radiance();
    let rmse = |v: &[f64]| (v.iter().map(|x| (x - exact).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
    let sampled = sunny_floor(true, 2, 3, true);
    let unsampled = sunny_floor(false, 2, 3, true);
    let (sampled_rmse, unsampled_rmse) = (rmse(&sampled), rmse(&unsampled));
    eprintln!("exact {exact:.4}; sampled: mean {:.4}, RMSE {sampled_rmse:.4}; unsampled: mean {:.4}, RMSE {unsampled_rmse:.4}", mean(&sampled), mean(&unsampled));
    assert!(sampled_rmse < 0.5 * unsampled_rmse, "RMSE sampled {sampled_rmse:.4} against unsampled {unsampled_rmse:.4}");
    assert!((mean(&sampled) / exact - 1.0).abs() < 0.05, "sampled mean {:.4} against {exact:.4}", mean(&sampled));
}

/// The rays of each frame and the floor's linear radiance (red, mean over the frames after
/// the first two) of [`sunny_floor`]'s sky over a floor roofed at y = 1 but for a 1 × 1 hole
/// straight ahead, direct light only, `frames` frames of `spp` samples.
fn roofed_floor(sky_sampling: bool, spp: u32, frames: usize) -> (Vec<RayCounts>, f64) {
    let (mut ctx, renderer) = shared_context(Settings { spp, bounces: 0, sky_sampling, temporal: false, ..Settings::default() });
    let mut rays = Vec::new();
    let mut sum = 0.0;
    for frame in 0..frames {
        let image = render(&mut ctx, 1, CLEAR, |ctx| unsafe {
            sunny_sky(ctx, DIM);
            lit_material(ctx, 1.0);
            // The floor, and the roof facing down: four quads around the hole x, z in [-0.5, 0.5] x [-4.5, -3.5].
            dispatch::glBegin(ctx, gl::GL_QUADS);
            let (normal, corners) = FLOOR;
            dispatch::glNormal3f(ctx, normal[0], normal[1], normal[2]);
            for [x, y, z] in corners {
                dispatch::glVertex3f(ctx, x, y, z);
            }
            dispatch::glNormal3f(ctx, 0.0, -1.0, 0.0);
            for [x0, x1, z0, z1] in [[-50.0f32, 50.0, -3.5, 50.0], [-50.0, 50.0, -50.0, -4.5], [-50.0, -0.5, -4.5, -3.5], [0.5, 50.0, -4.5, -3.5]] {
                for [x, z] in [[x0, z0], [x0, z1], [x1, z1], [x1, z0]] {
                    dispatch::glVertex3f(ctx, x, 1.0, z);
                }
            }
            dispatch::glEnd(ctx);
        });
        rays.push(renderer.lock().unwrap().tracer().expect("tracing").statistics().rays);
        if frame >= 2 {
            let floor: Vec<f64> = (0..SIZE / 2 - 1).flat_map(|y| (0..SIZE).map(move |x| (x, y))).map(|(x, y)| linear(image[(y * SIZE + x) as usize][0])).collect();
            sum += floor.iter().sum::<f64>() / floor.len() as f64;
        }
    }
    (rays, sum / (frames - 2) as f64)
}

/// Where nearly every sky sample is occluded (a roofed floor lit through one hole), the
/// vertices sample the sky ever less often (render::trace::sky_selection: the counted rays
/// fall to at most a quarter of the first frames'), and the floor's radiance keeps its mean:
/// the same as with the sky found by continuation rays alone (within 25 %: the choice is made
/// for 8 × 4 tiles of pixels together, so this 24 × 11-pixel floor has few independent
/// choices; a sample not divided by its probability would be 4–16 times off).
#[test]
fn a_roofed_floor_samples_the_sky_less_and_keeps_its_mean() {
    let frames = 12;
    let (rays, selected) = roofed_floor(true, 4, frames);
    let (unsampled_rays, unsampled) = roofed_floor(false, 4, frames);
    let sky: Vec<u64> = rays.iter().map(|r| r.sky).collect();
    let open: Vec<u64> = rays.iter().map(|r| r.sky_unoccluded).collect();
    eprintln!("sky rays per frame {sky:?}, unoccluded {open:?}; floor mean: sampled {selected:.5}, unsampled {unsampled:.5}");
    assert!(unsampled_rays.iter().all(|r| r.sky == 0), "no sky rays without sky sampling");
    let first = sky.iter().copied().find(|&n| n > 0).expect("sky rays in some frame");
    assert!(sky[frames - 1] * 4 <= first, "sky rays per frame {sky:?}");
    assert!(selected > 0.0 && (selected / unsampled - 1.0).abs() < 0.25, "floor mean {selected:.5} against {unsampled:.5}");
}
