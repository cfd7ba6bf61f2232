//! Ambient occlusion of raster frames (issue 23, seed 000) on Mesa lavapipe: white unlit
//! surfaces, so each pixel shows `255 · (1 − occlusion)`. An open plane is left unoccluded; in
//! a box, the pixels at the edge where the floor meets a wall and at the corner where it meets
//! two walls are occluded by the known fraction of the kernel that the walls cut off: a
//! surface point at distances `d1`, `d2` from the two other faces (whose normals are
//! orthogonal axes of its tangent plane) has a kernel sample of tangent reach `ρR` occluded
//! for the rotations θ about the normal where `ρR cos θ > d1 + δ` or `ρR sin θ > d2 + δ`
//! (at the edge line half the rotations, at the corner three quarters, as `δ → 0`), averaged
//! over the kernel, the rotations, the pixels read and the blur.
//!
//! [`reference`] compares the occlusion per pixel with ray-traced ambient occlusion of the same
//! surfaces (the box, the plane and a replayed frame of the demo).

#[path = "../images/mod.rs"]
mod images;
#[path = "../lavapipe/mod.rs"]
mod lavapipe;
mod reference;

use glam::{Mat4, Vec3, Vec4};
use glrt::render::ao::settings::AoSettings;
use glrt::render::frame::Renderer;
use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 128;
/// The floor's height, the back wall's depth and the right wall's x, in eye space before the
/// camera's pitch.
const FLOOR: f32 = -1.5;
const BACK: f32 = -5.0;
const RIGHT: f32 = 3.0;
/// The camera looks down by this many degrees.
const PITCH: f32 = 25.0;
/// The window pixels a white HUD square covers, from and to (both axes).
const HUD: (i32, i32) = (2, 10);

/// A context drawing into a `SIZE`² drawable with ambient occlusion `ao` (`None`: off).
fn context(ao: Option<AoSettings>) -> Context {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    if let Some(ao) = ao {
        renderer.enable_ambient_occlusion(ao).expect("the occlusion's pipelines");
    }
    let mut ctx = lavapipe::context_on(renderer);
    ctx.bind_drawable(SIZE, SIZE);
    ctx
}

/// One quad through `corners`.
fn quad(ctx: &mut Context, corners: [[f32; 3]; 4]) {
    unsafe {
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for [x, y, z] in corners {
            dispatch::glVertex3f(ctx, x, y, z);
        }
        dispatch::glEnd(ctx);
    }
}

/// The camera: a 90° frustum pitched down by [`PITCH`].
fn modelview() -> Mat4 {
    Mat4::from_rotation_x(PITCH.to_radians())
}

/// The scene's quads (eye space before the pitch): the floor, and with `walls` the back and
/// right walls of the box; without, the floor alone reaches far beyond the radius.
fn quads(walls: bool) -> Vec<[[f32; 3]; 4]> {
    let far = if walls { BACK } else { -60.0 };
    let right = if walls { RIGHT } else { 30.0 };
    let mut quads = vec![[[-30.0, FLOOR, 0.0], [right, FLOOR, 0.0], [right, FLOOR, far], [-30.0, FLOOR, far]]];
    if walls {
        quads.push([[-30.0, FLOOR, BACK], [RIGHT, FLOOR, BACK], [RIGHT, 20.0, BACK], [-30.0, 20.0, BACK]]);
        quads.push([[RIGHT, FLOOR, 0.0], [RIGHT, 20.0, 0.0], [RIGHT, 20.0, BACK], [RIGHT, FLOOR, BACK]]);
    }
    quads
}

/// Draws two frames of the floor, and with `walls` the back and right walls, white and unlit;
/// returns the red channel, rows bottom up.
fn render(ctx: &mut Context, walls: bool) -> Vec<u8> {
    for _ in 0..2 {
        lavapipe::begin_frame_90(ctx, SIZE);
        unsafe {
            dispatch::glLoadMatrixf(ctx, modelview().to_cols_array().as_ptr());
            dispatch::glEnable(ctx, gl::GL_DEPTH_TEST);
            dispatch::glColor3f(ctx, 1.0, 1.0, 1.0);
            for corners in quads(walls) {
                quad(ctx, corners);
            }
        }
        // A HUD square after the 3D draws, as games draw theirs: the occlusion goes before it,
        // and does not darken it.
        lavapipe::window_ortho(ctx, SIZE);
        let (lo, hi) = (HUD.0 as f32, HUD.1 as f32);
        quad(ctx, [[lo, lo, 0.0], [hi, lo, 0.0], [hi, hi, 0.0], [lo, hi, 0.0]]);
        ctx.end_frame();
    }
    lavapipe::read_rgba(ctx, SIZE).iter().map(|p| p[0]).collect()
}

/// The window pixel (x, y) of eye-space point `p` (before the pitch).
fn pixel_of(p: Vec3) -> (i32, i32) {
    let eye = modelview() * p.extend(1.0);
    let ndc = Vec4::new(eye.x / -eye.z / 1.0, eye.y / -eye.z / 1.0, 0.0, 0.0);
    let to = |v: f32| ((v * 0.5 + 0.5) * SIZE as f32).floor() as i32;
    (to(ndc.x), to(ndc.y))
}

/// The mean occlusion `1 − value / 255` over the `n` × `n` pixels around (x, y).
fn occlusion(image: &[u8], (x, y): (i32, i32), n: i32) -> f64 {
    let mut sum = 0.0;
    for j in y - n / 2..y - n / 2 + n {
        for i in x - n / 2..x - n / 2 + n {
            sum += 1.0 - image[(j * SIZE + i) as usize] as f64 / 255.0;
        }
    }
    sum / (n * n) as f64
}

fn settings() -> AoSettings {
    AoSettings { enabled: true, samples: 64, radius: 3.0, bias: 0.05, blur: 3 }
}

#[test]
fn an_open_plane_is_not_occluded() {
    let plain = render(&mut context(None), false);
    assert!(plain.iter().filter(|&&v| v == 255).count() > (SIZE * SIZE / 3) as usize, "the floor is white without occlusion");
    let image = render(&mut context(Some(settings())), false);
    // The floor within 8 units of the eye (the lower half of the image).
    let floor: Vec<usize> = (0..plain.len() / 2).filter(|&i| plain[i] == 255).collect();
    let mean = floor.iter().map(|&i| 1.0 - image[i] as f64 / 255.0).sum::<f64>() / floor.len() as f64;
    let worst = floor.iter().map(|&i| 1.0 - image[i] as f64 / 255.0).fold(0.0, f64::max);
    eprintln!("open plane: mean occlusion {mean:.4}, largest {worst:.4} over {} pixels", floor.len());
    assert!(mean < 0.01 && worst < 0.05, "mean {mean}, largest {worst}");
}

#[test]
fn a_box_edge_is_half_and_its_corner_three_quarters_occluded() {
    let image = render(&mut context(Some(settings())), true);
    let open = occlusion(&image, pixel_of(Vec3::new(-0.5, FLOOR, -1.6)), 5);
    let edge_pixel = pixel_of(Vec3::new(-4.0, FLOOR, BACK));
    let corner_pixel = pixel_of(Vec3::new(RIGHT, FLOOR, BACK));
    let (edge, corner) = (occlusion(&image, edge_pixel, 3), occlusion(&image, corner_pixel, 3));
    let (want_edge, want_corner) = (expected(edge_pixel, 3), expected(corner_pixel, 3));
    eprintln!("box: occlusion open floor {open:.3}, floor-wall edge {edge:.3} (expected {want_edge:.3}), corner {corner:.3} (expected {want_corner:.3})");
    let hud = (HUD.0..HUD.1).flat_map(|y| (HUD.0..HUD.1).map(move |x| (y * SIZE + x) as usize));
    assert!(hud.clone().all(|i| image[i] == 255), "the HUD square drawn after the 3D draws is not occluded");
    assert!(open < 0.05, "open floor {open}");
    assert!((edge - want_edge).abs() < 0.08, "edge {edge} against {want_edge}");
    assert!((corner - want_corner).abs() < 0.08, "corner {corner} against {want_corner}");
}

/// The distances from the box surface seen through the centre of pixel (x, y) to the two
/// other faces of the box (floor, back wall, right wall).
fn distances(x: i32, y: i32) -> [f32; 2] {
    let ndc = |i: i32| (i as f32 + 0.5) / SIZE as f32 * 2.0 - 1.0;
    let d = modelview().inverse().transform_vector3(Vec3::new(ndc(x), ndc(y), -1.0));
    let hits = [(FLOOR / d.y, 1usize), (BACK / d.z, 2), (RIGHT / d.x, 0)];
    let (t, face) = hits.iter().copied().filter(|(t, _)| *t > 0.0).fold((f32::MAX, 3), |a, b| if b.0 < a.0 { b } else { a });
    let p = d * t;
    let to = [RIGHT - p.x, p.y - FLOOR, p.z - BACK];
    match face {
        0 => [to[1], to[2]],
        1 => [to[0], to[2]],
        _ => [to[0], to[1]],
    }
}

/// The expected occlusion of a pixel at distances `d` from the two other faces: the share of
/// kernel samples and rotations (1° steps) whose reach towards a face passes its distance and
/// the bias.
fn expected_at(d: [f32; 2]) -> f64 {
    let s = settings();
    let kernel = glrt::render::ao::kernel(s.samples as usize);
    let mut hidden = 0usize;
    for k in &kernel {
        let reach = (k[0]).hypot(k[1]) * s.radius;
        for step in 0..360 {
            let (sin, cos) = (step as f32).to_radians().sin_cos();
            if reach * cos > d[0] + s.bias || reach * sin > d[1] + s.bias {
                hidden += 1;
            }
        }
    }
    hidden as f64 / (kernel.len() * 360) as f64
}

/// [`expected_at`] averaged as [`occlusion`] reads the `n` × `n` pixels around (x, y), each
/// the mean of the blur's square around it.
fn expected((x, y): (i32, i32), n: i32) -> f64 {
    let blur = settings().blur as i32;
    let mut sum = 0.0;
    for j in y - n / 2..y - n / 2 + n {
        for i in x - n / 2..x - n / 2 + n {
            for bj in -(blur / 2)..-(blur / 2) + blur {
                for bi in -(blur / 2)..-(blur / 2) + blur {
                    sum += expected_at(distances(i + bi, j + bj));
                }
            }
        }
    }
    sum / (n * n * blur * blur) as f64
}
