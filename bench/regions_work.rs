//! Nodes and triangle tests per ray of the compute tracer's binary BVHs (`Blas::build`,
//! `Tlas::build`) over a capture's static world (its chunks after frame 1), traced on the CPU:
//! a BLAS per chunk (today), per region of n³ world cells (what `chunk_regions` merges for the
//! hardware tracer) and one BLAS. Rays: 20,000 from random points of random triangles, on a
//! random side, in directions around its normal (diffuse-like), closest hit; every variant must
//! find the same hits (a line per ray that does not). bench/pathtrace.md, "Merged chunk regions".
//! A bench tool built as an example:
//!   cargo run --release --example regions_work -- tests/fixtures/demo.glrtcap
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use glam::Vec3;
use glrt::frame::world::StaticChunk;
use glrt::frame::{FrameSink, NullSink};
use glrt::render::trace::bvh::{Aabb, Blas, GpuNode, GpuTriangle, Layout, Tlas};
use glrt::replay::{self, reader::Capture};
use glrt::translate::classify::report::FrameTap;

const LEAF: u32 = 0x8000_0000;
struct Scene { tlas: Vec<GpuNode>, blas: Vec<Blas> }

fn enter(min: [f32; 3], max: [f32; 3], o: Vec3, inv: Vec3, tmax: f32) -> f32 {
    let t0 = (Vec3::from(min) - o) * inv;
    let t1 = (Vec3::from(max) - o) * inv;
    let near = t0.min(t1);
    let far = t0.max(t1);
    let tn = near.x.max(near.y).max(near.z.max(1e-4));
    let tf = far.x.min(far.y).min(far.z.min(tmax)) * 1.000_000_5;
    if tn <= tf { tn } else { f32::INFINITY }
}
fn hit(tri: &GpuTriangle, o: Vec3, d: Vec3, tmax: f32) -> Option<f32> {
    let (e1, e2) = (Vec3::from(tri.e1), Vec3::from(tri.e2));
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 { return None; }
    let inv = 1.0 / det;
    let s = o - Vec3::from(tri.v0);
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) { return None; }
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    if !(v >= 0.0 && u + v <= 1.0) { return None; }
    let t = e2.dot(q) * inv;
    (t > 1e-4 && t < tmax).then_some(t)
}
// Closest hit; returns (t, nodes, tests).
fn trace(s: &Scene, o: Vec3, d: Vec3) -> (f32, u64, u64) {
    let inv = Vec3::ONE / d;
    let (mut nodes, mut tests, mut tmax) = (0u64, 0u64, f32::INFINITY);
    // stack of (instance or None, node)
    let mut stack: Vec<(Option<usize>, u32)> = vec![(None, 0)];
    while let Some((inst, n)) = stack.pop() {
        nodes += 1;
        let node = match inst { None => s.tlas[n as usize], Some(i) => s.blas[i].nodes[n as usize] };
        let entry = node.children.map(|c| enter(c.min, c.max, o, inv, tmax));
        let order = if entry[1] < entry[0] { [1, 0] } else { [0, 1] };
        let mut push = Vec::new();
        for slot in order {
            let c = node.children[slot];
            if entry[slot] == f32::INFINITY || entry[slot] > tmax || c.meta == LEAF { continue; }
            match (inst, c.meta & LEAF != 0) {
                (Some(i), true) => {
                    for k in c.index..c.index + (c.meta & !LEAF) {
                        tests += 1;
                        if let Some(t) = hit(&s.blas[i].triangles[k as usize], o, d, tmax) { tmax = t; }
                    }
                }
                (None, true) => push.push((Some(c.index as usize), 0)),
                (_, false) => push.push((inst, c.index)),
            }
        }
        // nearer visited first: push farther first
        for p in push.into_iter().rev() { stack.push(p); }
    }
    (tmax, nodes, tests)
}
fn scene(groups: &[Vec<[Vec3; 3]>]) -> Scene {
    let blas: Vec<Blas> = groups.iter().map(|g| Blas::build(g, Layout::Binary)).collect();
    let bounds: Vec<Aabb> = blas.iter().map(|b| b.bounds).collect();
    Scene { tlas: Tlas::build(&bounds, Layout::Binary).nodes, blas }
}
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let capture = Capture::open(std::path::Path::new(&path)).unwrap();
    let world: Arc<Mutex<Vec<Arc<StaticChunk>>>> = Arc::default();
    let w2 = world.clone();
    let mut options = replay::Options::default();
    options.end_frame = Some(2);
    options.sink = Some(replay::SinkWrapper(Arc::new(move |_i: Option<Box<dyn FrameSink>>| {
        let w = w2.clone();
        Box::new(FrameTap::new(Box::new(NullSink::default()), move |f: &glrt::frame::Frame| { *w.lock().unwrap() = f.static_world.to_vec(); })) as Box<dyn FrameSink>
    })));
    replay::run(&capture, &options).unwrap();
    let chunks = world.lock().unwrap().clone();
    let tris = |c: &StaticChunk| -> Vec<[Vec3; 3]> { c.positions.chunks_exact(3).map(|t| [Vec3::from(t[0]), Vec3::from(t[1]), Vec3::from(t[2])]).collect() };
    let all: Vec<[Vec3; 3]> = chunks.iter().flat_map(|c| tris(c)).collect();
    println!("{} chunks, {} triangles", chunks.len(), all.len());
    // rays: from random points on random triangles, cosine-ish random directions on either side
    let mut seed = 12345u64;
    let mut rnd = move || { seed ^= seed << 13; seed ^= seed >> 7; seed ^= seed << 17; (seed >> 40) as f32 / (1u64 << 24) as f32 };
    let mut rays = Vec::new();
    for _ in 0..20000 {
        let t = all[(rnd() * all.len() as f32) as usize % all.len()];
        let (mut u, mut v) = (rnd(), rnd());
        if u + v > 1.0 { u = 1.0 - u; v = 1.0 - v; }
        let p = t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v;
        let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
        let side = if rnd() < 0.5 { 1.0 } else { -1.0 };
        let d = (Vec3::new(rnd() * 2.0 - 1.0, rnd() * 2.0 - 1.0, rnd() * 2.0 - 1.0).normalize_or_zero() + n * side).normalize_or_zero();
        if d == Vec3::ZERO { continue; }
        rays.push((p + n * side * 1e-3, d));
    }
    let mut variants: Vec<(String, Vec<Vec<[Vec3; 3]>>)> = vec![("a BLAS per chunk".into(), chunks.iter().map(|c| tris(c)).collect())];
    for size in [1, 2, 4, 8] {
        let mut by: HashMap<[i32; 3], Vec<[Vec3; 3]>> = HashMap::new();
        for c in &chunks { by.entry(c.cell.map(|x| x.div_euclid(size))).or_default().extend(tris(c)); }
        variants.push((format!("regions of {size}^3 cells"), by.into_values().collect()));
    }
    variants.push(("one BLAS".into(), vec![all.clone()]));
    let mut reference = Vec::new();
    for (k, (name, groups)) in variants.iter().enumerate() {
        let s = scene(groups);
        let (mut n, mut t) = (0, 0);
        for (i, (o, d)) in rays.iter().enumerate() {
            let (th, nodes, tests) = trace(&s, *o, *d);
            n += nodes; t += tests;
            if k == 0 { reference.push(th); } else if (reference[i] - th).abs() > 1e-3 * reference[i].abs().max(1.0) && reference[i].is_finite() { eprintln!("ray {i}: {} vs {}", reference[i], th); }
        }
        println!("{name}: {} instances, {:.1} nodes and {:.2} triangle tests per ray", groups.len(), n as f64 / rays.len() as f64, t as f64 / rays.len() as f64);
    }
}
