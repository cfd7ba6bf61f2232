//! Physics of the compute path tracer on lavapipe (issue 6): scenes drawn through the GL API,
//! traced with tone mapping off (the output is the sRGB encoding of the radiance), and the
//! radiance read back compared with what light transport says it must be.

mod lavapipe;

use glrt::render::raster::renderer::Renderer;
use glrt::render::trace::settings::{Settings, Tonemap};
use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 24;

/// A context tracing with `settings` (tone mapping off), a `SIZE`² drawable and a
/// perspective camera at the origin looking down −z with a 60° field of view.
fn context(settings: Settings) -> Context {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    renderer.enable_tracing(Settings { tonemap: Tonemap::Clamp, exposure: 0.0, ..settings }).expect("the tracer's pipelines");
    let mut ctx = lavapipe::context_on(renderer);
    ctx.bind_drawable(SIZE, SIZE);
    unsafe {
        dispatch::glViewport(&mut ctx, 0, 0, SIZE, SIZE);
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        let n = 0.1f64;
        let h = n * (30f64).to_radians().tan();
        dispatch::glFrustum(&mut ctx, -h, h, -h, h, n, 100.0);
        dispatch::glMatrixMode(&mut ctx, gl::GL_MODELVIEW);
        dispatch::glLoadIdentity(&mut ctx);
    }
    ctx
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
/// quad.
fn plane_under_sky(axis: usize, (normal, corners): Quad, frames: usize) -> Vec<[u8; 4]> {
    let mut ctx = context(Settings { spp: 4, bounces: 1, ..Settings::default() });
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
/// the rasterized sky, as in raster mode.
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
        let image = plane_under_sky(axis, quad, 3);
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
/// centre column (accumulated over still frames).
#[test]
fn a_floor_under_a_sky_of_two_halves_reads_their_mean() {
    let image = plane_under_sky(0, FLOOR, 8);
    let pixels: Vec<[u8; 4]> = (0..SIZE / 2 - 1).flat_map(|y| (4..SIZE - 4).map(move |x| (x, y))).map(|(x, y)| image[(y * SIZE + x) as usize]).collect();
    for c in 0..3 {
        let mean = pixels.iter().map(|p| linear(p[c])).sum::<f64>() / pixels.len() as f64;
        let [a, b] = [ABOVE[c], BELOW[c]].map(|v| linear((v * 255.0).round() as u8));
        let expected = 0.5 * (a + b);
        assert!((mean - expected).abs() <= 0.02, "channel {c}: mean radiance {mean:.4} over {} pixels against {expected:.4}", pixels.len());
    }
}
