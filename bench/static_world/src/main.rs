//! Per-frame cost of [`StaticWorld`] on a Quake-3-like turn: the room of `glrt-demo --rebatch`
//! (floor, ceiling, walls cut into 1 m surfaces of (2·detail)² quads), the surfaces whose
//! bounds meet the frustum offered every frame in per-material batches (nearest first, each
//! triangle from another first vertex each frame), the camera turning in 120 frames.
//! Compiles glrt's module files as they are, with the one type it needs from `glrt::frame`.
//!
//! Usage: `static-world-bench [DETAIL] [FRAMES]` (default 6 and 360). Prints one line per
//! phase: frames, triangles offered per frame, ms per frame (mean, median, max), GB/s of
//! positions offered.

/// Stand-in for glrt's texture reference (the bench has no textures).
#[derive(Clone, Debug, PartialEq)]
pub struct TextureRef;

/// Stand-in for glrt's draw state (the bench shades nothing).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RasterState;

/// Stand-in for glrt's texture unit state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TextureUnit;

#[path = "../../../src/frame/class.rs"]
pub mod class;

#[path = "../../../src/frame/world.rs"]
pub mod world;

#[path = "../../../src/translate/classify/static_world.rs"]
pub mod static_world;

/// The paths the module files use inside glrt.
mod frame {
    pub use crate::{TextureRef, class, world};
}

use std::time::Instant;

use glam::{Mat4, Vec3, Vec4};
use static_world::{StaticWorld, WorldTriangles};
use world::ChunkShading;

const TURN: u64 = 120;
const EYE: Vec3 = Vec3::new(0.0, 1.6, 0.0);

struct Surface {
    material: u64,
    positions: Vec<[f32; 3]>,
    min: Vec3,
    max: Vec3,
}

fn room(detail: usize) -> Vec<Surface> {
    let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
    let faces = [
        (Vec3::new(-8.0, 0.0, 10.0), x * 16.0, -z * 20.0),
        (Vec3::new(-8.0, 5.0, -10.0), x * 16.0, z * 20.0),
        (Vec3::new(-8.0, 0.0, -10.0), x * 16.0, y * 5.0),
        (Vec3::new(8.0, 0.0, 10.0), -x * 16.0, y * 5.0),
        (Vec3::new(-8.0, 0.0, 10.0), -z * 20.0, y * 5.0),
        (Vec3::new(8.0, 0.0, -10.0), z * 20.0, y * 5.0),
    ];
    let quads = 2 * detail;
    let mut out = Vec::new();
    for (m, (o, u, v)) in faces.into_iter().enumerate() {
        let (nu, nv) = (u.length().round() as usize, v.length().round() as usize);
        for cj in 0..nv {
            for ci in 0..nu {
                let at = |i: usize, j: usize| {
                    o + u * ((ci as f32 + i as f32 / quads as f32) / nu as f32)
                        + v * ((cj as f32 + j as f32 / quads as f32) / nv as f32)
                };
                let mut s = Surface { material: m as u64 + 1, positions: Vec::new(), min: Vec3::INFINITY, max: Vec3::NEG_INFINITY };
                for j in 0..quads {
                    for i in 0..quads {
                        let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                        for k in [0, 1, 2, 0, 2, 3] {
                            s.positions.push(q[k].to_array());
                            s.min = s.min.min(q[k]);
                            s.max = s.max.max(q[k]);
                        }
                    }
                }
                out.push(s);
            }
        }
    }
    out
}

fn camera(frame: u64) -> Mat4 {
    let yaw = std::f32::consts::TAU * (frame % TURN) as f32 / TURN as f32;
    let pitch = 55f32.to_radians() * (2.0 * yaw).sin();
    let f = Vec3::new(yaw.sin() * pitch.cos(), pitch.sin(), -yaw.cos() * pitch.cos());
    let s = f.cross(Vec3::Y).normalize();
    let u = s.cross(f);
    let view = Mat4::from_cols(
        Vec4::new(s.x, u.x, -f.x, 0.0),
        Vec4::new(s.y, u.y, -f.y, 0.0),
        Vec4::new(s.z, u.z, -f.z, 0.0),
        Vec4::new(-s.dot(EYE), -u.dot(EYE), f.dot(EYE), 1.0),
    );
    let (near, far, top) = (0.1f32, 100.0f32, 0.1 * 35f32.to_radians().tan());
    let right = top * 4.0 / 3.0;
    let projection = Mat4::from_cols(
        Vec4::new(near / right, 0.0, 0.0, 0.0),
        Vec4::new(0.0, near / top, 0.0, 0.0),
        Vec4::new(0.0, 0.0, -(far + near) / (far - near), -1.0),
        Vec4::new(0.0, 0.0, -2.0 * far * near / (far - near), 0.0),
    );
    projection * view
}

fn meets(clip: &Mat4, min: Vec3, max: Vec3) -> bool {
    let corners: [Vec4; 8] = std::array::from_fn(|i| {
        let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
        *clip * Vec4::new(pick(1, min.x, max.x), pick(2, min.y, max.y), pick(4, min.z, max.z), 1.0)
    });
    (0..3).all(|a| [1.0f32, -1.0].iter().all(|&s| corners.iter().any(|c| c.w + s * c[a] >= 0.0)))
}

fn main() {
    let args: Vec<u64> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let detail = args.first().copied().unwrap_or(6).clamp(1, 64) as usize;
    let frames = args.get(1).copied().unwrap_or(3 * TURN).max(2 * TURN);
    let surfaces = room(detail);
    let total: usize = surfaces.iter().map(|s| s.positions.len() / 3).sum();
    println!("static world bench: detail {detail}, {} surfaces, {total} triangles, {frames} frames", surfaces.len());
    let mut world = StaticWorld::new();
    let mut batch: Vec<[f32; 3]> = Vec::new();
    let mut first_turn = Vec::new();
    let mut later = Vec::new();
    for frame in 0..frames {
        let clip = camera(frame);
        let mut visible: Vec<&Surface> = surfaces.iter().filter(|s| meets(&clip, s.min, s.max)).collect();
        let d = |s: &Surface| ((s.min + s.max) * 0.5 - EYE).length();
        visible.sort_by(|a, b| d(a).total_cmp(&d(b)));
        // Batches prepared before the clock starts: only the world's work is timed.
        let mut batches: Vec<(u64, Vec<[f32; 3]>)> = Vec::new();
        for material in 1..=6 {
            batch.clear();
            for s in visible.iter().filter(|s| s.material == material) {
                for t in s.positions.chunks(3) {
                    let r = frame as usize % 3;
                    batch.extend_from_slice(&[t[r], t[(r + 1) % 3], t[(r + 2) % 3]]);
                }
            }
            batches.push((material, batch.clone()));
        }
        let offered: usize = batches.iter().map(|(_, b)| b.len() / 3).sum();
        let start = Instant::now();
        world.begin_frame(frame, clip);
        let shading = ChunkShading::default();
        for (material, positions) in &batches {
            world.offer(WorldTriangles { material_key: *material, material: Default::default(), texture: None, positions, texcoords: None, colors: None, shading: &shading });
        }
        let update = world.end_frame();
        let ms = start.elapsed().as_secs_f64() * 1000.0;
        if frame >= TURN {
            assert_eq!(update.triangles, total, "frame {frame}: the whole world once");
            assert_eq!(update.upload_bytes, 0, "frame {frame}: nothing to upload");
            later.push((ms, offered));
        } else {
            first_turn.push((ms, offered));
        }
    }
    report("first turn (building)", &first_turn);
    report("later turns (steady)", &later);
}

fn report(phase: &str, samples: &[(f64, usize)]) {
    let mut ms: Vec<f64> = samples.iter().map(|s| s.0).collect();
    ms.sort_by(f64::total_cmp);
    let mean = ms.iter().sum::<f64>() / ms.len() as f64;
    let triangles = samples.iter().map(|s| s.1).sum::<usize>() as f64 / samples.len() as f64;
    let bytes = triangles * 36.0;
    println!(
        "{phase}: {} frames, {:.0} triangles offered per frame, ms per frame mean {mean:.3} median {:.3} max {:.3}, {:.2} GB/s of positions",
        samples.len(),
        triangles,
        ms[ms.len() / 2],
        ms[ms.len() - 1],
        bytes / (mean / 1000.0) / 1e9
    );
}
